#!/usr/bin/python3
"""Geometric multigrid on the mesh hierarchy (-ssn_pc_truncated_mg_interp geometric, issue 27 item 2) against the
default truncated multigrid on BoomerAMG's interpolations (-ssn_pc_truncated_mg_interp amg), both CG, iterative.
Each case and configuration is run REPEAT times (the machine may be shared: medians of the times); the iteration
counts and flops do not vary. Prints a row per case and configuration: unknowns, SSN steps, CG iterations (all,
unconstrained start included) and per SSN step, the contact solve's time, the unconstrained start's set-up and solve,
the multigrid's build (SgTMGBuild: AMG set-up or interpolations, Galerkin operators of K) and its updates per active set
(SgTMGUpdate: the truncated Galerkin operators, the coarse factorization), KSPSolve's time and flops, and the total
flops of the run (-log_view). Measurements for bench/nested.md, not part of `make bench`.

usage: perf_gmg.py CASE... [--repeat 3] [--np 1] [--out DIR] [--extra OPTIONS]
CASE: PROBLEM:N[:CONTROLLER], PROBLEM ex1@NX,NY (Example 1, -box_faces NX,NY) or ex2@MESH (Example 2 on
meshes/MESH.msh); N the -dm_refine count; CONTROLLER the -cont_type (default: the default, fast).
"""
import argparse
import os
import re
import statistics
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
import sgrun  # noqa: E402

sgrun.ENV["OMP_NUM_THREADS"] = "1"
CONFIGS = ("amg", "geometric")


def options(case, interp):
    parts = case.split(":")
    prob, n = parts[0], parts[1]
    kind, arg = prob.split("@")
    if kind == "ex1":
        args = "-options_file options/ex1.opts -box_faces %s" % arg
    else:
        args = "-options_file options/ex2_problem.opts -dm_plex_filename meshes/%s.msh" % arg
    args += " -cont_direct_max_unknowns 0 -dm_refine %s -ssn_pc_truncated_mg_interp %s" % (n, interp)
    if len(parts) > 2:
        args += " -cont_type %s" % parts[2]
    return args


def log_event(text, name):
    """(count, time, flops) of an event in -log_view's table, zeros if absent"""
    m = re.search(r"^%s\s+(\d+)\s+\S+\s+(\S+)\s+\S+\s+(\S+)" % re.escape(name), text, re.M)
    return (int(m.group(1)), float(m.group(2)), float(m.group(3))) if m else (0, 0.0, 0.0)


def total_flops(text):
    m = re.search(r"^Flops?:\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)", text, re.M)
    return float(m.group(4)) if m else 0.0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cases", nargs="+")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--out", default="/tmp/perf_gmg")
    ap.add_argument("--extra", default="")
    opt = ap.parse_args()
    print("| case | interp | unknowns | SSN | CG its | CG / SSN | solve [s] | start setup + solve [s] | TMG build [s] | TMG updates [s] (n) | KSPSolve [s] | KSPSolve Gflop | total Gflop | energy | contact force |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for case in opt.cases:
        for interp in CONFIGS:
            name = (case + "_" + interp).replace(":", "_").replace("@", "_").replace(",", "x")
            rows = []
            for r in range(opt.repeat):
                lv = os.path.join(opt.out, name + ".log_view")
                # without nested iteration (now the default with -dm_refine) unless --extra asks for it
                nest = "" if "-cont_nested" in opt.extra else " -cont_nested 0"
                s, _ = sgrun.run(options(case, interp) + nest + " " + opt.extra + " -log_view :" + lv, name, opt.out, np=opt.np if opt.np > 1 else None, check=False)
                if "dofs" not in s:
                    break
                text = open(lv).read()
                rows.append((s, log_event(text, "SgTMGBuild"), log_event(text, "SgTMGUpdate"), log_event(text, "KSPSolve"), total_flops(text)))
            if not rows:
                print("| %s | %s | failed (see %s/%s.log) |" % (case, interp, opt.out, name))
                continue
            s = rows[0][0]
            med = lambda f: statistics.median(f(r) for r in rows)  # noqa: E731
            print("| %s | %s | %d | %d | %d | %.1f | %.3g | %.3g | %.3g | %.3g (%d) | %.3g | %.3g | %.3g | %.12e | %.8e |%s" % (
                case, interp, s["dofs"], s["ssn_iterations"], s["ksp_iterations"], s["ksp_iterations"] / max(1, s["ssn_iterations"]),
                med(lambda r: r[0]["solve_time"]), med(lambda r: r[0]["linear_setup_time"] + r[0]["linear_solve_time"]),
                med(lambda r: r[1][1]), med(lambda r: r[2][1]), rows[0][2][0], med(lambda r: r[3][1]), rows[0][3][2] / 1e9,
                rows[0][4] / 1e9, s["energy"], s["contact_force"], "" if s["converged"] else " NOT CONVERGED"), flush=True)
    print("%d rank(s), OMP_NUM_THREADS=1, medians of %d runs; options: bench/perf_gmg.py" % (opt.np, opt.repeat))


if __name__ == "__main__":
    main()
