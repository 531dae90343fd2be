#!/usr/bin/python3
"""The default controller and linear solver (issues 12 and 13): contact solves of Examples 1 and 2 with ipf or fast
and a direct or an iterative linear solver, run in rounds (every case once per round, so all see the same load of a
shared machine); the minimum solve_time of each case is kept. Measurements for bench/perf_notes.md, not part of
`make bench`.

usage: perf_default.py CASE... [--repeat N] [--out DIR]
CASE: PROBLEM:CONTROLLER:SOLVER[:nu], PROBLEM one of ex1@NX,NY (Example 1, -box_faces NX,NY) or ex2@MESH (Example 2
on meshes/MESH.msh), CONTROLLER ipf or fast, SOLVER a file of options/solver/ without .opts; nu e.g. 0.4999.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
import sgrun  # noqa: E402

# hypre links libgomp: without this a second, spinning thread takes the other core (issue 12, point (c))
sgrun.ENV["OMP_NUM_THREADS"] = "1"


def options(case):
    parts = case.split(":")
    prob, cont, solver = parts[:3]
    kind, arg = prob.split("@")
    if kind == "ex1":
        args = "-options_file options/ex1.opts -box_faces %s" % arg
        ipf = "-options_file options/cont/ipf.opts"
    else:
        args = "-options_file options/ex2_problem.opts -dm_plex_filename meshes/%s.msh" % arg
        ipf = "-options_file options/cont/ipf.opts -ipf_tau 1e8"  # as options/ex2.opts
    args += " -options_file options/solver/%s.opts" % solver
    args += " " + (ipf if cont == "ipf" else "-options_file options/cont/fast.opts")
    if len(parts) > 3:
        args += " -nu %s" % parts[3]
    return args


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cases", nargs="+")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--out", default="/tmp/perf_default")
    opt = ap.parse_args()
    best, runs = {}, {}
    for r in range(opt.repeat):
        for case in opt.cases:
            name = case.replace(":", "_").replace("@", "_").replace(",", "x")
            s, _ = sgrun.run(options(case), "%s_%d" % (name, r), opt.out, check=False)
            runs.setdefault(case, []).append(s.get("solve_time"))
            if not s.get("converged"):
                best.setdefault(case, (None, s))
                continue
            if best.get(case, (None,))[0] is None or s["solve_time"] < best[case][0]:
                best[case] = (s["solve_time"], s)
            sys.stderr.write("%s round %d: %.3g s\n" % (case, r, s["solve_time"]))
    print("| case | unknowns | solve_time [s] (min) | all rounds [s] | converged | KKT / tol | outer | SSN | KSP its |")
    print("|---|---|---|---|---|---|---|---|---|")
    for case in opt.cases:
        t, s = best[case]
        allr = " ".join("%.3g" % x if x is not None else "-" for x in runs[case])
        if t is None:
            print("| %s | %s | failed: %s | %s | no | | | | |" % (case, s.get("dofs", ""), str(s.get("reason", "no summary (see the log)"))[:80], allr))
            continue
        print("| %s | %d | %.3g | %s | %s | %.1e / %.0e | %d | %d | %d |" % (case, s["dofs"], t, allr, "yes" if s["converged"] else "no", s["kkt_residual"], s["residual_tol"],
              s["outer_iterations"], s["ssn_iterations"], s["ksp_iterations"]))
    print("minimum of %d runs per case, made in rounds, one rank, OMP_NUM_THREADS=1; options: bench/perf_default.py" % opt.repeat)


if __name__ == "__main__":
    main()
