#!/usr/bin/python3
"""Nested iteration (-cont_nested, issue 27): each case run plain and nested on the same finest mesh (the problem's
mesh refined -dm_refine N times after distribution; nested: the solve starts on the mesh refined N - L times fewer).
Prints a row per run: unknowns, SSN steps and CG/KSP iterations on the finest level, those of the coarse levels, the
solve time (coarse levels included), the coarse levels' part, the energy and the contact force. Measurements for
bench/nested.md, not part of `make bench`.

usage: perf_nested.py CASE... [--out DIR]
CASE: PROBLEM:N:L, PROBLEM one of ex1@NX,NY (Example 1, -box_faces NX,NY, its default configuration) or ex2@MESH
(Example 2 on meshes/MESH.msh, the default iterative configuration: -cont_direct_max_unknowns 0); N the -dm_refine
count, L the -cont_nested levels (0: plain).
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
import sgrun  # noqa: E402

sgrun.ENV["OMP_NUM_THREADS"] = "1"


def options(case):
    prob, n, lv = case.split(":")
    kind, arg = prob.split("@")
    if kind == "ex1":
        args = "-options_file options/ex1.opts -box_faces %s" % arg
    else:
        args = "-options_file options/ex2_problem.opts -dm_plex_filename meshes/%s.msh -cont_direct_max_unknowns 0" % arg
    return args + " -dm_refine %s -cont_nested %s" % (n, lv)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cases", nargs="+")
    ap.add_argument("--out", default="/tmp/perf_nested")
    opt = ap.parse_args()
    print("| case | unknowns | controller | SSN (finest) | KSP its (finest) | SSN (coarse) | KSP its (coarse) | solve [s] | of it coarse levels [s] | energy | contact force | converged |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for case in opt.cases:
        name = case.replace(":", "_").replace("@", "_").replace(",", "x")
        s, _ = sgrun.run(options(case), name, opt.out, check=False)
        if "dofs" not in s:
            print("| %s | failed (see %s/%s.log) |" % (case, opt.out, name))
            continue
        print("| %s | %d | %s | %d | %d | %s | %s | %.3g | %s | %.12e | %.8e | %s |" % (
            case, s["dofs"], s["cont_type"], s["ssn_iterations"], s["ksp_iterations"], s.get("nested_coarse_ssn_its", "-"),
            s.get("nested_coarse_ksp_its", "-"), s["solve_time"], ("%.3g" % s["nested_coarse_time"]) if "nested_coarse_time" in s else "-",
            s["energy"], s["contact_force"], "yes" if s["converged"] else "no"), flush=True)
    print("one rank, OMP_NUM_THREADS=1; options: bench/perf_nested.py")


if __name__ == "__main__":
    main()
