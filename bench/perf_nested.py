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

usage: perf_nested.py --default MESH:N [--np 1,2] [--rounds R] [--yard-rounds R] [--geo-yard] [--json FILE] [--out DIR]
The measurement of the idle-machine sections of bench/nested.md in one command: Example 2's default configuration
alone (-options_file options/ex2_problem.opts -dm_plex_filename meshes/MESH.msh -dm_refine N: nested iteration and
the geometric truncated multigrid) on each rank count of --np, the rank counts alternating, --rounds rounds; then
its yardsticks on each rank count, --yard-rounds rounds: the same refined mesh without contact at scripts/bench.py's
YARD_RTOL, CG + GAMG without near null space and CG + BoomerAMG nodal 4 + l1-GS (of bench.py's YARDSTICK_3D, the two
fastest on this mesh family). Prints a row per run (counts, times, CPU time of all ranks, peak memory summed over the
ranks and of the largest rank, the load average before it) and per rank count the median contact solve time, the
fastest yardstick, the cost ratio (median / fastest yardstick, the coarse levels included), the np speedup against
the first rank count and the peak memory against the yardsticks'; --json writes it all (default: none; never
bench/results.json). E.g. ex2_coarse2:3 (4.1e6 unknowns from meshes/ex2_coarse2.msh, made by make if missing),
ex2_coarse:3 (1,115,460).
With --geo-yard, also a geometric-multigrid linear yardstick in each yardstick round: the yardsticks' problem is a
rigid translation of the block (zero strain), which the coarsest mesh represents exactly, so nested iteration would
start the finest level at the answer; with a body force (0,0,-1e5) it has strain. That strained linear problem is
solved (a) by the default itself with the obstacle out of reach (-obstacle_ball_center -0.3,0,-100: nothing
touches, every SSN step a linear solve by nested iteration + the geometric multigrid, the coarse levels included)
and (b) by the AMG yardsticks from zero; the summary adds the cost ratio against the fastest of (a) and (b).
"""
import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
import sgrun  # noqa: E402
from bench import EX2_ELASTIC, YARD_RTOL, YARDSTICK_3D  # noqa: E402

sgrun.ENV["OMP_NUM_THREADS"] = "1"


def options(case):
    prob, n, lv = case.split(":")
    kind, arg = prob.split("@")
    if kind == "ex1":
        args = "-options_file options/ex1.opts -box_faces %s" % arg
    else:
        args = "-options_file options/ex2_problem.opts -dm_plex_filename meshes/%s.msh -cont_direct_max_unknowns 0" % arg
    return args + " -dm_refine %s -cont_nested %s" % (n, lv)


# the yardsticks of --default: the two fastest of YARDSTICK_3D on Example 2's refined meshes (bench/nested.md)
DEFAULT_YARDS = ("GAMG, no near null space", "BoomerAMG, nodal coarsening 4 + l1-Gauss-Seidel")
# --geo-yard: the strained linear problem (a body force) and the obstacle out of reach (bench/nested.md, stop 42)
GEO_FORCE = "-body_force 0,0,-1e5"
GEO_FAR = "-obstacle_ball_center -0.3,0,-100"


def timed(args, name, out, np):
    """one run: its summary with the wall time, the CPU time of all its processes and the load average before it"""
    load, ru, t0 = os.getloadavg()[0], resource.getrusage(resource.RUSAGE_CHILDREN), time.time()
    s, _ = sgrun.run(args, name, out, np=np, check=False)
    ru2 = resource.getrusage(resource.RUSAGE_CHILDREN)
    s["wall_time"] = time.time() - t0
    s["cpu_time"] = (ru2.ru_utime + ru2.ru_stime) - (ru.ru_utime + ru.ru_stime)
    s["load_before"] = load
    return s


def default_scale(opt):
    """--default MESH:N: the default on each rank count, alternating, and its yardsticks (see the usage)"""
    mesh, n = opt.default.split(":")
    path = "meshes/%s.msh" % mesh
    if not os.path.exists(os.path.join(sgrun.ROOT, path)):  # the Makefile's rule (e.g. meshes/ex2_coarse2.msh)
        if subprocess.run(["make", "--no-print-directory", path], cwd=sgrun.ROOT).returncode != 0:
            sys.exit("perf_nested.py: --default %s: no mesh %s and no rule to make it" % (opt.default, path))
    nps = [int(x) for x in opt.np.split(",")]
    cargs = "-options_file options/ex2_problem.opts -dm_plex_filename %s -dm_refine %s" % (path, n)
    yards = [(name, o) for name, o in YARDSTICK_3D if name in DEFAULT_YARDS]
    print("| run | ranks | unknowns | SSN / CG finest | SSN / CG coarse levels | contact or linear solve [s] | of it coarse levels [s] "
          "| whole run wall [s] | CPU all ranks [s] | peak MB summed (largest rank) | load before | energy |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    res = {"command": cargs, "default": {np: [] for np in nps}, "yardsticks": {np: {y: [] for y, _ in yards} for np in nps},
           "geo_yardsticks": {np: {} for np in nps}}

    def row(label, np, s, contact):
        if "dofs" not in s:
            print("| %s | %d | failed (see %s) |" % (label, np, opt.out), flush=True)
            return
        t = s["solve_time"] if contact else s.get("linear_solve_time")
        print("| %s | %d | %d | %s / %d | %s / %s | %.2f | %s | %.1f | %.1f | %.0f (%.0f) | %.1f | %s |" % (
            label, np, s["dofs"], s.get("ssn_iterations", "-") if contact else "-", s["ksp_iterations"],
            s.get("nested_coarse_ssn_its", "-"), s.get("nested_coarse_ksp_its", "-"), t,
            ("%.2f" % s["nested_coarse_time"]) if "nested_coarse_time" in s else "-", s["wall_time"], s["cpu_time"],
            s.get("peak_rss_mb", 0), s.get("peak_rss_mb_max_rank", 0), s["load_before"],
            ("%.12e" % s["energy"]) if contact else "-"), flush=True)

    for r in range(opt.rounds):
        for np in nps:
            s = timed(cargs, "default_%s_r%s_np%d_%d" % (mesh, n, np, r), opt.out, np)
            res["default"][np].append(s)
            row("default" + ("" if s.get("converged") else " (NOT CONVERGED)"), np, s, True)
    for r in range(opt.yard_rounds):
        for np in nps:
            for name, o in yards:
                s = timed("-dm_plex_filename %s -dm_refine %s %s %s %s" % (path, n, EX2_ELASTIC, o, YARD_RTOL),
                          "yard_%s_r%s_np%d_%s_%d" % (mesh, n, np, "".join(c for c in name if c.isalnum())[:24], r), opt.out, np)
                res["yardsticks"][np][name].append(s)
                row("yardstick " + name, np, s, False)
            if not opt.geo_yard:
                continue
            s = timed("%s %s %s" % (cargs, GEO_FAR, GEO_FORCE), "geo_%s_r%s_np%d_default_%d" % (mesh, n, np, r), opt.out, np)
            if s.get("active_set_size", 0) != 0:
                print("perf_nested.py: --geo-yard: %s vertices touch the obstacle moved out of reach" % s.get("active_set_size"))
                s["converged"] = False
            s["linear_solve_time"] = s.get("solve_time")  # the default's whole solve, coarse levels included
            res["geo_yardsticks"][np].setdefault("default, nothing touching", []).append(s)
            row("strained, the default, nothing touching", np, s, True)
            for name, o in yards:
                s = timed("-dm_plex_filename %s -dm_refine %s %s %s %s %s" % (path, n, EX2_ELASTIC, GEO_FORCE, o, YARD_RTOL),
                          "geo_%s_r%s_np%d_%s_%d" % (mesh, n, np, "".join(c for c in name if c.isalnum())[:24], r), opt.out, np)
                res["geo_yardsticks"][np].setdefault(name, []).append(s)
                row("strained, " + name, np, s, False)
    print()
    summ = {}
    for np in nps:
        ok = [s for s in res["default"][np] if s.get("converged")]
        ys = {name: min((s["linear_solve_time"] for s in v if s.get("converged") and s.get("linear_solve_time")), default=None)
              for name, v in res["yardsticks"][np].items()}
        ys = {k: v for k, v in ys.items() if v}
        if not ok or not ys:
            print("%d rank(s): no converged default or yardstick" % np)
            continue
        med = statistics.median(s["solve_time"] for s in ok)
        fast = min(ys, key=ys.get)
        peak = max(s.get("peak_rss_mb", 0) for s in ok)
        ypeak = {name: max(s.get("peak_rss_mb", 0) for s in v) for name, v in res["yardsticks"][np].items() if v}
        summ[np] = {"unknowns": ok[0]["dofs"], "ssn_finest": sorted({s["ssn_iterations"] for s in ok}),
                    "solve_median": med, "solve_times": [s["solve_time"] for s in ok], "yardstick": fast,
                    "yardstick_time": ys[fast], "cost_ratio": med / ys[fast], "peak_mb": peak,
                    "peak_ratio": {name: peak / v for name, v in ypeak.items() if v}}
        print("%d rank(s), %d unknowns: SSN finest %s; contact solve median %.2f s (%s); fastest yardstick %s %.2f s; cost "
              "ratio %.2f; peak %.0f MB, %s the yardsticks'" % (
                  np, ok[0]["dofs"], "/".join(map(str, summ[np]["ssn_finest"])), med, ", ".join("%.2f" % s["solve_time"] for s in ok),
                  fast, ys[fast], med / ys[fast], peak, ", ".join("%.2fx %s" % (v, k.split(",")[0]) for k, v in summ[np]["peak_ratio"].items())))
        gs = {name: min((s["linear_solve_time"] for s in v if s.get("converged") and s.get("linear_solve_time")), default=None)
              for name, v in res["geo_yardsticks"][np].items()}
        gs = {k: v for k, v in gs.items() if v}
        if gs:
            gfast = min(gs, key=gs.get)
            summ[np].update({"geo_yardstick": gfast, "geo_yardstick_time": gs[gfast], "cost_ratio_geometric": med / gs[gfast]})
            print("%d rank(s): the strained linear problem's fastest solve %s %.2f s; cost ratio against it %.2f" % (np, gfast, gs[gfast], med / gs[gfast]))
    if len(summ) > 1 and nps[0] in summ:
        for np in nps[1:]:
            if np in summ:
                summ[np]["speedup"] = summ[nps[0]]["solve_median"] / summ[np]["solve_median"]
                print("np %d speedup of the contact solve (medians): %.2f" % (np, summ[np]["speedup"]))
    print("OMP_NUM_THREADS=1; options: bench/perf_nested.py --default %s" % opt.default)
    if opt.json != "none":
        res["summary"] = summ
        sgrun.write_atomic(opt.json, json.dumps(res, indent=1, default=str) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cases", nargs="*")
    ap.add_argument("--out", default="/tmp/perf_nested")
    ap.add_argument("--default", default=None, help="MESH:N: the default and its yardsticks on meshes/MESH.msh -dm_refine N")
    ap.add_argument("--np", default="1,2", help="with --default: the rank counts, alternating")
    ap.add_argument("--rounds", type=int, default=3, help="with --default: runs of the default per rank count")
    ap.add_argument("--yard-rounds", type=int, default=1, help="with --default: runs of each yardstick per rank count")
    ap.add_argument("--geo-yard", action="store_true", help="with --default: also the strained linear problem by the default (nothing touching) and by the AMG yardsticks")
    ap.add_argument("--json", default="none", help="with --default: write the runs and the ratios here")
    opt = ap.parse_args()
    if opt.default:
        default_scale(opt)
        return
    if not opt.cases:
        ap.error("give CASEs or --default MESH:N")
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
