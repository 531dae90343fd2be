#!/usr/bin/python3
"""Truncated multigrid (-ssn_pc_truncated_mg, src/solver/tmg.c) against a new BoomerAMG setup per active set, in the
contact solve of -cont_type fast on Example 2. Runs are made in rounds (every configuration once per round) and the
minimum time of each is kept (a shared machine). Besides the summary's times: the preconditioner set-ups from
-log_view (BoomerAMG: the PCSetUp event; truncated multigrid: SgTMGBuild, the AMG set up once on K and its
interpolations taken, and SgTMGUpdate, the truncation and the coarse operators of each new Jacobian), the CG
iterations of each SSN step from the history, and the CPU time (user + system) of each whole run (mesh and assembly
included: the configuration `overhead` measures them without a solve; less disturbed by the load than the wall
times). Measurements for the performance issue (bench/perf_notes.md, part D); not part of `make bench`.
OMP_NUM_THREADS=1 for every run (libHYPRE's OpenMP thread otherwise spins beside the solver).

usage: perf_tmg.py MESH [--repeat N] [--only NAME,...] [--exe BINARY] [--timeout SECONDS]
"""
import argparse
import os
import re
import resource
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
import sgrun  # noqa: E402

ELASTIC = "-dm_plex_gmsh_use_regions -E 1e6 -nu 0.45 -dirichlet_label top -dirichlet_values 0,0,-0.2"
CONTACT = "-options_file options/ex2_problem.opts"
L1GS = "-options_file options/solver/hypre_l1gs.opts"
FAST = "-options_file options/cont/fast.opts"
# PETSc's PCHMG: the same multigrid as -ssn_pc_truncated_mg on K (BoomerAMG's interpolations of hypre.opts, Galerkin
# operators, SOR smoothers), as a yardstick candidate
HMG_INNER = " ".join("-hmg_inner_pc_hypre_boomeramg_" + o for o in ("strong_threshold 0.5", "coarsen_type HMIS", "interp_type ext+i", "P_max 4", "agg_nl 1"))
CONFIGS = [
    # (name, kind, options); kind "linear": the block without contact (the yardstick), "contact": Example 2
    ("overhead", "overhead", "-ksp_type preonly -pc_type none"),  # reading, assembly, output: in every run's CPU time
    ("lin_hypre_l1gs", "linear", L1GS + " -ksp_rtol 1e-8"),
    ("lin_hmg", "linear", "-ksp_type cg -ksp_rtol 1e-8 -pc_type hmg -hmg_inner_pc_type hypre " + HMG_INNER + " -mg_levels_ksp_type richardson -mg_levels_ksp_max_it 1 -mg_levels_pc_type sor"),
    ("lin_gamg", "linear", "-ksp_type cg -ksp_rtol 1e-8 -pc_type gamg"),
    ("lin_gamg_nonns", "linear", "-ksp_type cg -ksp_rtol 1e-8 -pc_type gamg -elasticity_near_null_space false"),
    ("fast_l1gs", "contact", L1GS + " " + FAST),
    ("fast_gamg_tmg", "contact", "-ksp_type cg -pc_type gamg " + FAST + " -ssn_pc_truncated_mg"),
    ("fast_gamg_nonns_tmg", "contact", "-ksp_type cg -pc_type gamg -elasticity_near_null_space false " + FAST + " -ssn_pc_truncated_mg"),
    ("fast_l1gs_tmg", "contact", L1GS + " " + FAST + " -ssn_pc_truncated_mg"),
    ("ipf_l1gs", "contact", L1GS + " -options_file options/cont/ipf.opts -ipf_tau 1e8"),
    ("ipf_l1gs_tmg", "contact", L1GS + " -options_file options/cont/ipf.opts -ipf_tau 1e8 -ssn_pc_truncated_mg"),
]
EVENTS = ("PCSetUp", "PCApply", "KSPSolve", "SgTMGBuild", "SgTMGUpdate", "MatPtAPNumeric", "MatPtAPSymbolic")


def log_events(path):
    """{event: (count, time)} of the -log_view table in a run's log."""
    ev = {}
    with open(path) as f:
        for line in f:
            m = re.match(r"^(\w+)\s+(\d+) [\d.]+ ([\d.e+-]+) ", line)
            if m and m.group(1) in EVENTS:
                ev[m.group(1)] = (int(m.group(2)), float(m.group(3)))
    return ev


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mesh")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--only", default="")
    ap.add_argument("--out", default="/tmp/perf_tmg")
    ap.add_argument("--timeout", type=int, default=600)
    ap.add_argument("--exe", default=sgrun.SIGNORINI, help="the solver binary (a copy, to keep measuring while rebuilding)")
    opt = ap.parse_args()
    only = [o for o in opt.only.split(",") if o]
    todo = [c for c in CONFIGS if not only or c[0] in only]
    env = dict(sgrun.ENV, OMP_NUM_THREADS="1")
    best, failed, bestcpu = {}, {}, {}
    for r in range(opt.repeat):
        for name, kind, args in todo:
            if name in failed:
                continue
            base = CONTACT if kind == "contact" else ELASTIC
            tag = "%s_%d" % (name, r)
            stem = os.path.join(opt.out, tag)
            os.makedirs(opt.out, exist_ok=True)
            cmd = sgrun.command(("%s -dm_plex_filename %s %s -log_view" % (base, opt.mesh, args)).split(), 1, exe=opt.exe, summary=stem + ".json", history=stem + ".csv")
            ru0 = resource.getrusage(resource.RUSAGE_CHILDREN)
            try:
                p = sgrun.execute(cmd, env=env, timeout=opt.timeout)
            except subprocess.TimeoutExpired:
                failed[name] = "no end after %d s" % opt.timeout
                continue
            ru1 = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu = (ru1.ru_utime + ru1.ru_stime) - (ru0.ru_utime + ru0.ru_stime)
            with open(stem + ".log", "w") as f:
                f.write(" ".join(cmd) + "\n" + p.stdout)
            s = sgrun.summary(stem + ".json")
            if kind == "overhead":
                bestcpu[name] = min(cpu, bestcpu.get(name, cpu))
                continue
            if not s.get("converged"):
                failed[name] = s.get("reason", "no summary (see %s.log)" % stem)
                continue
            t = s["linear_solve_time"] if kind == "linear" else s["solve_time"]
            print("round %d %s: %.3g s (CPU of the whole run %.3g s)" % (r, name, t, cpu), flush=True)
            bestcpu[name] = min(cpu, bestcpu.get(name, cpu))
            if name not in best or t < best[name][0]:
                best[name] = (t, s, log_events(stem + ".log"), sgrun.history(stem + ".csv"))
    lin = [(v[0], n) for n, v in best.items() if n.startswith("lin_")]
    yard = min(lin) if lin else (None, None)
    print("yardstick: %s, %.3g s" % (yard[1], yard[0] or float("nan")))
    # CPU of the solve: the run's CPU less that of a run without a solve (when measured); its ratio to the yardstick's
    base = bestcpu.get("overhead")
    solvecpu = {n: c - base for n, c in bestcpu.items() if base is not None and n != "overhead"}
    lincpu = min([c for n, c in solvecpu.items() if n.startswith("lin_")] or [float("nan")])

    def cpucol(name):
        if name not in solvecpu:
            return "%.3g" % bestcpu[name]
        return "%.3g (%.3g; %.2f)" % (bestcpu[name], solvecpu[name], solvecpu[name] / lincpu)
    print("| configuration | unknowns | time [s] | / yardstick | CPU of the run (less a run without a solve; / yardstick's) [s] | outer | SSN | CG its | PC set-ups | set-up time [s] (per set-up) | AMG once [s] | KKT | CG its per SSN step |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name, kind, _ in todo:
        if kind == "overhead":
            print("| %s (CPU of a run without a solve) | | | | %.3g | | | | | | | | |" % (name, bestcpu.get(name, float("nan"))))
            continue
        if name in failed:
            print("| %s | | failed: %s | | | | | | | | | | |" % (name, failed[name][:90]))
            continue
        t, s, ev, hist = best[name]
        ratio = t / yard[0] if yard[0] else float("nan")
        if "SgTMGUpdate" in ev:
            n, tu = ev["SgTMGUpdate"]
            once = "%.3g" % ev["SgTMGBuild"][1]
        else:
            n, tu = ev.get("PCSetUp", (0, float("nan")))
            once = ""
        if kind == "linear":
            print("| %s | %d | %.3g | %.2f | %s | | | %d | %d | %.3g | | | |" % (name, s["dofs"], t, ratio, cpucol(name), s["ksp_iterations"], n, tu))
            continue
        steps = [int(h["ksp_its"]) for h in hist if h["kind"] == "ssn"]
        print("| %s | %d | %.3g | %.2f | %s | %d | %d | %d | %d | %.3g (%.3g) | %s | %.1e | %s |" % (name, s["dofs"], t, ratio, cpucol(name), s["outer_iterations"], s["ssn_iterations"], s["ksp_iterations"], n, tu, tu / max(n, 1), once, s["kkt_residual"], " ".join(map(str, steps))))
    print("minimum of %d runs per configuration, made in rounds, one rank; options: CONFIGS in bench/perf_tmg.py" % opt.repeat)


if __name__ == "__main__":
    main()
