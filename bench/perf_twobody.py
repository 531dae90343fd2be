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

usage: perf_twobody.py [--scales 7] [--repeat N] [--timeout S] [--json FILE|none] [--out DIR]
"""
import argparse
import json
import os
import shlex
import signal
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


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scales", default="7")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--timeout", type=float, default=1800)
    ap.add_argument("--json", default=os.path.join(HERE, "results.json"))
    ap.add_argument("--out", default=os.path.join(HERE, "runs", "twobody"))
    opt = ap.parse_args()
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
