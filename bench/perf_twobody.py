#!/usr/bin/python3
"""Two elastic bodies (issue 28, "Benchmarks"): the sphere on an elastic block in 3D (options/twobody_sphere.opts,
meshes/tb_sphere.geo: the quarter of a hemisphere of radius 1 on the quarter of a block, dual mortar between them) at
the mesh scales --scales (default 7: about 1e5 unknowns; measured 990, 4,431, 25,440 unknowns at scales 1, 2, 4, about
5.7 times per doubling: check the unknowns printed), one rank:
  default   the problem's options alone (the default controller and linear solver choose themselves);
  mumps     the same with options/solver/mumps.opts (the direct solve, for reference).
Each contact solve is set against a yardstick: the fastest configured linear solve of the same two-body mesh with
the same Dirichlet data and no contact (scripts/bench.py's YARDSTICK_3D at its YARD_RTOL, minimum over --repeat
runs). Each body is held by its own Dirichlet data here (the sphere's top, the block's bottom), so that solve is the
two bodies apart: the issue asks for the bodies tied (the Jacobian with every pair row active), a system of the same
size with the interface coupled, which the driver cannot solve alone today; the untied solve is at most as costly,
so the ratio here is an upper bound of the asked one. A contact run that takes longer than --timeout seconds is
stopped and recorded as not converged. Writes into --json (default bench/results.json; its other keys are kept):
  cost_ratio_twobody  {unknowns: the default contact solve's time / the yardstick's time}  (converged runs only)
  twobody             the runs (unknowns, controller, linear solver, SSN, KSP, times, converged) and the yardsticks
and prints a markdown section for bench/results.md. Goals of issue 28: cost at most 3 (2.5), at most 8 SSN steps.
A benchmark, not a test: never run by make test.

--refine MESH:N (branch pair4) measures instead one coarse mesh refined N times after distribution (-dm_refine N:
nested iteration's default), --problem sphere or cylinders (options/twobody_hertz.opts, the 2D pair; its yardstick
MUMPS and CG + BoomerAMG as in scripts/bench.py's YARDSTICK_3D, the bodies apart), --np 1,2 on those ranks, --exe
another binary (e.g. main's) run alongside: every run in rounds, each round every case once, and for each run the
CPU time (user + sys of the run and its ranks, from the children's rusage) and the load average at its start; a base
run (the yardstick's mesh and assembly, -ksp_type preonly -pc_type jacobi) gives the CPU-based cost ratio
(run - base) / (yardstick - base). Writes cost_ratio_twobody {unknowns: median of the rounds' ratios} and, with
--np 1,2, speedup_np2_twobody {unknowns: median of the rounds' contact-solve time on 1 rank / on 2}.

usage: perf_twobody.py [--scales 7] [--repeat N] [--timeout S] [--json FILE|none] [--out DIR]
       perf_twobody.py --refine meshes/tb_sphere_s1.msh:3 [--problem sphere|cylinders] [--np 1,2] [--exe BIN] [--yard fast|all] ...
"""
import argparse
import json
import os
import shlex
import signal
import resource
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import sgrun  # noqa: E402
from bench import YARDSTICK_3D, YARD_RTOL  # noqa: E402

sgrun.ENV["OMP_NUM_THREADS"] = "1"  # hypre links libgomp: no spinning second thread

SPHERE = "-options_file options/twobody_sphere.opts"
# options/twobody_sphere.opts without its contact part: the two bodies apart, each on its own Dirichlet data
APART = "-E 1 -nu 0.3 -dirichlet_ids 2,6,3,1,7,4 -dirichlet_components xyz,x,y,xyz,x,y -dirichlet_values 0,0,-0.01,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0"
MUMPS = "-options_file options/solver/mumps.opts"
CYLINDERS = "-options_file options/twobody_hertz.opts"
APART_2D = "-E 1 -nu 0.3 -dirichlet_ids 2,6,1,7 -dirichlet_components xy,x,xy,x -dirichlet_values 0,-0.01,0,0,0,0,0,0"
# the yardstick candidates that were fastest on these meshes (branch pair3: BoomerAMG nodal 4 + l1-GS and GAMG
# without near null space in 3D); 2D: MUMPS against BoomerAMG l1-GS
YARD_FAST = {"sphere": [n for n in YARDSTICK_3D if n[0] in ("BoomerAMG, nodal coarsening 4 + l1-Gauss-Seidel", "GAMG, no near null space")],
             "cylinders": [("MUMPS", MUMPS), ("BoomerAMG, l1-Gauss-Seidel", dict(YARDSTICK_3D)["BoomerAMG, l1-Gauss-Seidel"])]}
BASE = "-ksp_type preonly -pc_type jacobi"
FIELDS = ("dofs", "cont_type", "linear_solver", "outer_iterations", "ssn_iterations", "ksp_iterations", "linear_setup_time",
          "linear_solve_time", "solve_time", "peak_rss_mb", "converged", "reason", "energy", "contact_force")


def mesh(path):
    """make the mesh if it is missing (the Makefile's rule meshes/tb_sphere_s%.msh)"""
    if not os.path.exists(os.path.join(ROOT, path)):
        subprocess.run(["make", "--no-print-directory", path], cwd=ROOT, check=True)
    return path


def run_capped(args, name, out, timeout):
    """sgrun.run with a wall-time cap: a run stopped by it is recorded as {"converged": False, "reason": "timeout"}"""
    os.makedirs(out, exist_ok=True)
    base = os.path.join(out, name)
    cmd = sgrun.command(shlex.split(args), 1, summary=base + ".json", history=base + ".csv")
    # a session of its own, so that a run over the cap is stopped with mpiexec's ranks (a killed mpiexec alone would
    # leave them running)
    p = subprocess.Popen(cmd, cwd=ROOT, env=sgrun.ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True)
    try:
        log, _ = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGTERM)
        log, _ = p.communicate()
        with open(base + ".log", "w") as f:
            f.write(" ".join(shlex.quote(c) for c in cmd) + "\n" + (log or "") + "\n(stopped after %g s)\n" % timeout)
        return {"converged": False, "reason": "timeout after %g s" % timeout}
    with open(base + ".log", "w") as f:
        f.write(" ".join(shlex.quote(c) for c in cmd) + "\n" + log)
    return sgrun.summary(base + ".json")


def best_of(runs):
    ok = [s for s in runs if s.get("converged") and s.get("solve_time")]
    return min(ok, key=lambda s: s["solve_time"]) if ok else (runs[-1] if runs else {})


def yardstick(args, tag, repeat, out):
    """the fastest configured linear solve of the mesh without contact (minimum of repeat runs, in rounds)"""
    best = {}
    for r in range(repeat):
        for name, opts in YARDSTICK_3D:
            s, _ = sgrun.run("%s %s %s" % (args, opts, YARD_RTOL), "Y_%s_%s_%d" % (tag, "".join(c for c in name if c.isalnum())[:40], r), out, check=False)
            if s.get("converged") and s.get("linear_solve_time") and (name not in best or s["linear_solve_time"] < best[name]["linear_solve_time"]):
                best[name] = s
    if not best:
        return {"name": None, "time": None, "dofs": None}
    name = min(best, key=lambda n: best[n]["linear_solve_time"])
    return {"name": name, "time": best[name]["linear_solve_time"], "dofs": best[name]["dofs"], "ksp_iterations": best[name]["ksp_iterations"],
            "candidates": {n: {"time": v["linear_solve_time"], "ksp_iterations": v["ksp_iterations"]} for n, v in best.items()}}


def fmt(x, f="%.3g"):
    return "-" if x is None else f % x


def run_timed(args, name, out, timeout, np=1, exe=None):
    """run_capped with the run's CPU time (user + sys of the finished children: mpiexec's ranks included) and the
    load average at its start"""
    load = os.getloadavg()[0]
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    os.makedirs(out, exist_ok=True)
    base = os.path.join(out, name)
    cmd = sgrun.command(shlex.split(args), np, exe=exe or sgrun.SIGNORINI, summary=base + ".json", history=base + ".csv")
    p = subprocess.Popen(cmd, cwd=ROOT, env=sgrun.ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True)
    try:
        log, _ = p.communicate(timeout=timeout)
        s = None
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGTERM)
        log, _ = p.communicate()
        s = {"converged": False, "reason": "timeout after %g s" % timeout}
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    with open(base + ".log", "w") as f:
        f.write(" ".join(shlex.quote(c) for c in cmd) + "\n" + (log or ""))
    s = s or sgrun.summary(base + ".json")
    s["cpu_time"] = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    s["load"] = load
    return s


def median(xs):
    xs = [x for x in xs if x is not None]
    return statistics.median(xs) if xs else None


def main_refine(opt):
    """--refine MESH:N: one coarse mesh refined N times, the contact runs (--np, --exe) and the yardsticks in rounds"""
    path, n = opt.refine.rsplit(":", 1)
    mesh(path)
    m = "-dm_plex_filename %s -dm_refine %s" % (path, n)
    prob, apart = (SPHERE, APART) if opt.problem == "sphere" else (CYLINDERS, APART_2D)
    yards = YARD_FAST[opt.problem] if opt.yard == "fast" else (YARDSTICK_3D if opt.problem == "sphere" else YARD_FAST["cylinders"] + list(YARDSTICK_3D))
    nps = [int(x) for x in opt.np.split(",")]
    exes = [("this", None)] + ([("other", opt.exe)] if opt.exe else [])
    cases = [("%s_np%d" % (tag, k), "%s %s" % (prob, m), k, exe) for tag, exe in exes for k in nps]
    cases += [("Y_%s%s" % ("".join(c for c in yn if c.isalnum())[:40], "" if k == 1 else "_np%d" % k), "%s %s %s %s" % (m, apart, yo, YARD_RTOL), k, None) for k in nps for yn, yo in yards]
    cases += [("base", "%s %s %s" % (m, apart, BASE), 1, None)]
    tag = "%s_%s_r%s" % (opt.problem, os.path.splitext(os.path.basename(path))[0], n)
    runs = {c[0]: [] for c in cases}
    for r in range(opt.repeat):
        for key, args, k, exe in cases:
            s = run_timed(args, "%s_%s_%d" % (tag, key, r), opt.out, opt.timeout, np=k, exe=exe)
            runs[key].append(s)
            sys.stderr.write("%s %s round %d: solve %s s, linear %s s, CPU %.1f s, load %.1f, %s\n" % (tag, key, r, s.get("solve_time"), s.get("linear_solve_time"), s["cpu_time"], s["load"],
                                                                                                   "converged" if s.get("converged") else s.get("reason", "no summary")))
    ykeys = [c[0] for c in cases if c[0].startswith("Y_") and c[2] == 1]
    rows, cost, speed = [], {}, {}
    for key, _, k, exe in cases:
        if key.startswith("Y_") or key == "base":
            continue
        ratios, cratios = [], []
        for r in range(opt.repeat):
            s = runs[key][r]
            ys = [runs[y][r] for y in ykeys if runs[y][r].get("converged") and runs[y][r].get("linear_solve_time")]
            if not s.get("converged") or not ys:
                continue
            y = min(ys, key=lambda v: v["linear_solve_time"])
            ratios.append(s["solve_time"] / y["linear_solve_time"])
            b = runs["base"][r].get("cpu_time")
            if b is not None and y["cpu_time"] > b:
                cratios.append((s["cpu_time"] - b) / (y["cpu_time"] - b))
        s0 = runs[key][0]
        rows.append((key, s0.get("dofs"), s0.get("cont_type"), s0.get("ssn_iterations"), s0.get("nested_coarse_ssn_its"), s0.get("ksp_iterations"),
                     [v.get("solve_time") for v in runs[key]], [v["cpu_time"] for v in runs[key]], median(ratios), median(cratios),
                     all(v.get("converged") for v in runs[key]), s0.get("energy"), s0.get("contact_force"), [v["load"] for v in runs[key]]))
        if key == "this_np1" and ratios:
            cost[str(s0["dofs"])] = round(median(ratios), 3)
    if "this_np1" in runs and "this_np2" in runs:
        sp = [a["solve_time"] / b["solve_time"] for a, b in zip(runs["this_np1"], runs["this_np2"]) if a.get("converged") and b.get("converged")]
        if sp:
            speed[str(runs["this_np1"][0]["dofs"])] = round(median(sp), 3)
    for y in ykeys:  # the yardstick's own speedup, for reference
        y2 = [c[0] for c in cases if c[0].startswith(y + "_np2")]
        if y2:
            sp = [a["linear_solve_time"] / b["linear_solve_time"] for a, b in zip(runs[y], runs[y2[0]]) if a.get("linear_solve_time") and b.get("linear_solve_time")]
            sys.stderr.write("yardstick %s: np 2 speedup (median of rounds) %s\n" % (y, fmt(median(sp), "%.2f")))
    lines = ["| run | unknowns | controller | SSN finest (coarse) | KSP | solve per round [s] | CPU per round [s] | cost ratio (median) | CPU-based | converged | energy | force | load |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for row in rows:
        lines.append("| %s | %s | %s | %s (%s) | %s | %s | %s | %s | %s | %s | %.13g | %.12g | %s |" % (row[0], row[1], row[2], row[3], row[4], row[5], ", ".join(fmt(x) for x in row[6]), ", ".join(fmt(x) for x in row[7]),
                                                                                     fmt(row[8], "%.2f"), fmt(row[9], "%.2f"), "yes" if row[10] else "NO", row[11] or 0, row[12] or 0, ", ".join("%.1f" % x for x in row[13])))
    for y in [c[0] for c in cases if c[0].startswith("Y_")] + ["base"]:
        lines.append("| %s | %s | | | %s | linear %s | %s | | | %s | | | %s |" % (y, runs[y][0].get("dofs"), runs[y][0].get("ksp_iterations"), ", ".join(fmt(v.get("linear_solve_time")) for v in runs[y]),
                                                                       ", ".join(fmt(v["cpu_time"]) for v in runs[y]), "yes" if all(v.get("converged") for v in runs[y]) else "NO", ", ".join("%.1f" % v["load"] for v in runs[y])))
    print("\n".join(lines))
    if opt.json != "none" and (cost or speed):
        js = {}
        if os.path.exists(opt.json):
            with open(opt.json) as f:
                js = json.load(f)
        js.setdefault("cost_ratio_twobody", {}).update(cost)
        if speed:
            js.setdefault("speedup_np2_twobody", {}).update(speed)
        sgrun.write_atomic(opt.json, json.dumps(js, indent=1, sort_keys=False) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--refine", default=None, help="MESH:N: a coarse mesh refined N times (-dm_refine N)")
    ap.add_argument("--problem", default="sphere", choices=("sphere", "cylinders"))
    ap.add_argument("--np", default="1")
    ap.add_argument("--exe", default=None, help="another binary run alongside (with --refine)")
    ap.add_argument("--yard", default="fast", choices=("fast", "all"))
    ap.add_argument("--scales", default="7")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--timeout", type=float, default=1800)
    ap.add_argument("--json", default=os.path.join(HERE, "results.json"))
    ap.add_argument("--out", default=os.path.join(HERE, "runs", "twobody"))
    opt = ap.parse_args()
    if opt.refine:
        return main_refine(opt)
    cases = []  # (key, contact args, scale)
    for sc in opt.scales.split(","):
        m = mesh("meshes/tb_sphere_s%s.msh" % sc)
        cases.append(("sphere_s%s_default" % sc, "%s -dm_plex_filename %s" % (SPHERE, m), sc))
        cases.append(("sphere_s%s_mumps" % sc, "%s -dm_plex_filename %s %s" % (SPHERE, m, MUMPS), sc))
    runs = {k: [] for k, _, _ in cases}
    for r in range(opt.repeat):  # rounds: every case once per round
        for key, args, _ in cases:
            s = run_capped(args, "%s_%d" % (key, r), opt.out, opt.timeout)
            runs[key].append(s)
            sys.stderr.write("%s round %d: %s s, %s\n" % (key, r, s.get("solve_time"), "converged" if s.get("converged") else s.get("reason", "no summary")))
    res = {k: {f: best_of(v).get(f) for f in FIELDS} for k, v in runs.items()}
    yards, cost = {}, {}
    for sc in opt.scales.split(","):
        m = "meshes/tb_sphere_s%s.msh" % sc
        yards["sphere_s%s" % sc] = yardstick("-dm_plex_filename %s %s" % (m, APART), "sphere_s%s" % sc, opt.repeat, opt.out)
    for key, _, sc in cases:
        s, y = res[key], yards["sphere_s%s" % sc]
        if key.endswith("_default") and y["time"] and s.get("converged") and s.get("dofs"):
            cost[str(s["dofs"])] = s["solve_time"] / y["time"]
    lines = ["## Two elastic bodies (issue 28, bench/perf_twobody.py)", "",
             "The sphere on an elastic block (options/twobody_sphere.opts), the default configuration and MUMPS; the yardstick "
             "is the fastest configured linear solve of the same mesh without contact, the two bodies apart (scripts/bench.py's "
             "YARDSTICK_3D at %s; the tied system the issue names is not available to the driver). Minimum of %d runs made in "
             "rounds; times in seconds." % (YARD_RTOL, opt.repeat), "",
             "| case | unknowns | controller | linear solver | outer | SSN | KSP | contact solve | yardstick | cost ratio | converged |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for key, _, sc in cases:
        s, y = res[key], yards["sphere_s%s" % sc]
        ratio = s["solve_time"] / y["time"] if y.get("time") and s.get("converged") else None
        lines.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            key, s.get("dofs") or y.get("dofs"), s.get("cont_type"), s.get("linear_solver"), s.get("outer_iterations"), s.get("ssn_iterations"),
            s.get("ksp_iterations"), fmt(s.get("solve_time")), fmt(y.get("time")) + (" (%s)" % y["name"] if y.get("name") else ""),
            fmt(ratio, "%.2f"), "yes" if s.get("converged") else "NO: %s" % str(s.get("reason"))[:60]))
    print("\n".join(lines))
    if opt.json != "none":
        js = {}
        if os.path.exists(opt.json):
            with open(opt.json) as f:
                js = json.load(f)
        js.setdefault("cost_ratio_twobody", {}).update(cost)
        tb = js.setdefault("twobody", {})
        tb.setdefault("runs", {}).update(res)
        tb.setdefault("yardsticks", {}).update(yards)
        tb["repeat"] = opt.repeat
        sgrun.write_atomic(opt.json, json.dumps(js, indent=1, sort_keys=False) + "\n")


if __name__ == "__main__":
    main()
