#!/usr/bin/python3
"""Contact solve of Example 2 against one linear solve (the yardstick) on the same mesh, for several controller and
solver configurations. Runs are made in rounds (every configuration once per round) and the minimum time of each is
kept, so that all see the same load of a shared machine. Measurements for the performance issue (bench/perf_notes.md);
not part of `make bench`.

usage: perf_contact.py MESH [--repeat N] [--only NAME,...] [--yard NAME]
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
import sgrun  # noqa: E402

ELASTIC = "-dm_plex_gmsh_use_regions -E 1e6 -nu 0.45 -dirichlet_label top -dirichlet_values 0,0,-0.2"
CONTACT = "-options_file options/ex2_problem.opts"
HYPRE = "-options_file options/solver/hypre.opts"
NODAL_L1GS = "-pc_hypre_boomeramg_nodal_coarsen 4 -pc_hypre_boomeramg_relax_type_down l1-Gauss-Seidel -pc_hypre_boomeramg_relax_type_up backward-l1-Gauss-Seidel"
L1GS = "-pc_hypre_boomeramg_relax_type_down l1-Gauss-Seidel -pc_hypre_boomeramg_relax_type_up backward-l1-Gauss-Seidel"
IPF = "-options_file options/cont/ipf.opts -ipf_tau 1e8"
RTOL = "-ksp_rtol 1e-8"  # the yardstick's own tolerance, appended last
CONFIGS = [
    # (name, kind, options); kind "linear": the block without contact (a yardstick), "contact": Example 2
    ("lin_hypre", "linear", HYPRE + " " + RTOL),
    ("lin_hypre_nodal4_l1gs", "linear", HYPRE + " " + NODAL_L1GS + " " + RTOL),
    ("lin_hypre_l1gs", "linear", HYPRE + " " + L1GS + " " + RTOL),
    ("ipf", "contact", HYPRE + " " + IPF),
    ("ipf_nodal4_l1gs", "contact", HYPRE + " " + NODAL_L1GS + " " + IPF),
    ("ipf_rtol1e-2", "contact", HYPRE + " " + IPF + " -ksp_rtol 1e-2"),
    ("fast", "contact", HYPRE + " -cont_type fast"),
    ("fast_nodal4_l1gs", "contact", HYPRE + " " + NODAL_L1GS + " -cont_type fast"),
    ("fast_noearly", "contact", HYPRE + " -cont_type fast -fast_early 0"),
    ("fast_loose1e-1", "contact", HYPRE + " -cont_type fast -fast_ksp_loose 1e-1"),
    ("fast_start1e-1", "contact", HYPRE + " -cont_type fast -fast_start_rtol 1e-1"),
    ("fast_rtol1e-2", "contact", HYPRE + " -cont_type fast -ksp_rtol 1e-2"),
    ("fast_nodal4_l1gs_rtol1e-1", "contact", HYPRE + " " + NODAL_L1GS + " -cont_type fast -ksp_rtol 1e-1"),
    ("fast_l1gs", "contact", HYPRE + " " + L1GS + " -cont_type fast"),
    ("fast_l1gs_start1e-1", "contact", HYPRE + " " + L1GS + " -cont_type fast -fast_start_rtol 1e-1"),
    ("fast_nodal4_l1gs_start1e-1", "contact", HYPRE + " " + NODAL_L1GS + " -cont_type fast -fast_start_rtol 1e-1"),
]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mesh")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--only", default="")
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--out", default="/tmp/perf_contact")
    opt = ap.parse_args()
    only = [o for o in opt.only.split(",") if o]
    todo = [c for c in CONFIGS if not only or c[0] in only]
    best, failed = {}, {}
    for r in range(opt.repeat):
        for name, kind, args in todo:
            if name in failed:
                continue
            base = ELASTIC if kind == "linear" else CONTACT
            s, _ = sgrun.run("%s -dm_plex_filename %s %s" % (base, opt.mesh, args), "%s_np%d_%d" % (name, opt.np, r), opt.out, np=opt.np, check=False)
            if not s.get("converged"):
                failed[name] = s.get("reason", "no summary (see the log)")
                continue
            t = s["linear_solve_time"] if kind == "linear" else s["solve_time"]
            if name not in best or t < best[name][0]:
                best[name] = (t, s)
    lin = [(v[0], n) for n, v in best.items() if n.startswith("lin_")]
    yard = min(lin) if lin else (None, None)
    print("yardstick: %s, %.3g s (the fastest linear solve above, at %s)" % (yard[1], yard[0] or float("nan"), RTOL))
    print("| configuration | unknowns | time [s] | / yardstick | outer | SSN | CG its | CG stopped early / full | KKT | gamma |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, kind, _ in todo:
        if name in failed:
            print("| %s | | failed: %s | | | | | | | |" % (name, failed[name][:90]))
            continue
        t, s = best[name]
        if kind == "linear":
            print("| %s | %d | %.3g | %.2f | | | %d | | | |" % (name, s["dofs"], t, t / yard[0], s["ksp_iterations"]))
        else:
            g = s.get("gammas") or []
            print("| %s | %d | %.3g | %.2f | %d | %d | %d | %s / %s | %.1e | %s |" % (name, s["dofs"], t, t / yard[0], s["outer_iterations"], s["ssn_iterations"], s["ksp_iterations"],
                  s.get("fast_linear_solves_stopped_early", "-"), s.get("fast_linear_solves_full", "-"), s["kkt_residual"], "%.2g" % g[-1] if g else "-"))
    print("minimum of %d runs per configuration, made in rounds, %d rank(s); options: CONFIGS in bench/perf_contact.py" % (opt.repeat, opt.np))


if __name__ == "__main__":
    main()
