#!/usr/bin/python3
"""One linear elasticity solve on an Example 2 mesh (the block without contact, the K of every SSN step) with
several solver configurations: setup, setup + solve, CG iterations, backward error. Minimum over --repeat runs.
Measurements for the performance issue (bench/perf_notes.md); not part of `make bench`.

usage: perf_linear.py MESH [--repeat N] [--only NAME,...] [--extra "OPTIONS"]
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
import sgrun  # noqa: E402

PROBLEM = "-dm_plex_gmsh_use_regions -E 1e6 -nu 0.45 -dirichlet_label top -dirichlet_values 0,0,-0.2"
HYPRE = "-options_file options/solver/hypre.opts"
NODAL_L1GS = "-pc_hypre_boomeramg_nodal_coarsen 4 -pc_hypre_boomeramg_relax_type_down l1-Gauss-Seidel -pc_hypre_boomeramg_relax_type_up backward-l1-Gauss-Seidel"
L1GS = "-pc_hypre_boomeramg_relax_type_down l1-Gauss-Seidel -pc_hypre_boomeramg_relax_type_up backward-l1-Gauss-Seidel"
GM = "-pc_hypre_boomeramg_nodal_coarsen 4 -pc_hypre_boomeramg_vec_interp_variant 2 -pc_hypre_boomeramg_vec_interp_qmax 4 -pc_hypre_boomeramg_vec_interp_smooth"
GAMG = "-ksp_type cg -ksp_rtol 1e-8 -pc_type gamg"
VARIANTS = [
    ("hypre", HYPRE),
    ("hypre_nodal4_l1gs", HYPRE + " " + NODAL_L1GS),
    ("hypre_l1gs", HYPRE + " " + L1GS),
    ("hypre_nodal4", HYPRE + " -pc_hypre_boomeramg_nodal_coarsen 4"),
    ("hypre_gm2", HYPRE + " " + GM),
    ("hypre_gm2_l1gs", HYPRE + " " + GM + " " + L1GS),
    ("hypre_nodal4_l1gs_th07", HYPRE + " " + NODAL_L1GS + " -pc_hypre_boomeramg_strong_threshold 0.7"),
    ("hypre_nodal4_l1gs_th03", HYPRE + " " + NODAL_L1GS + " -pc_hypre_boomeramg_strong_threshold 0.3"),
    ("hypre_nodal4_l1gs_pmax2", HYPRE + " " + NODAL_L1GS + " -pc_hypre_boomeramg_P_max 2"),
    ("hypre_nodal4_l1gs_agg2", HYPRE + " " + NODAL_L1GS + " -pc_hypre_boomeramg_agg_nl 2"),
    ("hypre_nodal1_l1gs", HYPRE + " -pc_hypre_boomeramg_nodal_coarsen 1 " + L1GS),
    ("hypre_nodal6_l1gs", HYPRE + " -pc_hypre_boomeramg_nodal_coarsen 6 " + L1GS),
    ("gamg", GAMG),
    ("gamg_th001", GAMG + " -pc_gamg_threshold 0.01"),
    ("gamg_th005", GAMG + " -pc_gamg_threshold 0.05"),
    ("gamg_th001_noagg", GAMG + " -pc_gamg_threshold 0.01 -pc_gamg_aggressive_coarsening 0"),
    ("gamg_th001_sor", GAMG + " -pc_gamg_threshold 0.01 -mg_levels_pc_type sor -mg_levels_ksp_type richardson"),
    ("gamg_th001_cheb_sor", GAMG + " -pc_gamg_threshold 0.01 -mg_levels_pc_type sor -mg_levels_ksp_type chebyshev"),
    ("gamg_nonull", GAMG + " -elasticity_near_null_space 0"),
    ("ml", "-ksp_type cg -ksp_rtol 1e-8 -pc_type ml -pc_ml_nullspace user"),
]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mesh")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--only", default="")
    ap.add_argument("--extra", default="")
    ap.add_argument("--out", default="/tmp/perf_linear")
    opt = ap.parse_args()
    only = [o for o in opt.only.split(",") if o]
    todo = [(n, a) for n, a in VARIANTS if not only or n in only]
    best, failed = {}, {}
    # round robin: every variant once per round, so that all see the same load of a shared machine
    for r in range(opt.repeat):
        for name, args in todo:
            if name in failed:
                continue
            s, _ = sgrun.run("-dm_plex_filename %s %s %s %s" % (opt.mesh, PROBLEM, args, opt.extra), "%s_%d" % (name, r), opt.out, check=False)
            if not s.get("converged"):
                failed[name] = s.get("reason", "no summary (see the log)")
            elif name not in best or s["linear_solve_time"] < best[name]["linear_solve_time"]:
                best[name] = s
    print("| variant | unknowns | CG its | setup [s] | setup + solve [s] | backward error |")
    print("|---|---|---|---|---|---|")
    for name, _ in todo:
        if name in failed:
            print("| %s | - | failed: %s | | | |" % (name, failed[name][:80]))
        else:
            s = best[name]
            print("| %s | %d | %d | %.3g | %.3g | %.1e |" % (name, s["dofs"], s["ksp_iterations"], s["linear_setup_time"], s["linear_solve_time"], s["residual"]))
    print("minimum of %d runs per variant, run in rounds; options: see VARIANTS in bench/perf_linear.py" % opt.repeat)

if __name__ == "__main__":
    main()
