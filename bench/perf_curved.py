#!/usr/bin/python3
"""The curved family of issue 30 (curved and tilted bodies): the default contact solve (the problem's options alone:
the default controller and linear solver choose themselves) on
  hemi   the quarter elastic hemisphere on a rigid plane (options/cv_hemisphere.opts, meshes/cv_hemisphere.geo) at
         about 1e4, 1.2e5 and 1e6 unknowns (mesh scales --hemi-scales, default 4,8.5,18; measured 14,730 unknowns at 4
         and 100,761 at 8: the graded mesh grows about 7x per doubling of the scale, so 18 is an estimate: check the
         unknowns printed); with --hemi-refine N each mesh is also refined N times by -dm_refine N (the contact solve and
         its yardstick alike; the default then solves the coarser levels first, nested iteration, and its SSN steps
         use the geometric multigrid of the levels; the refined curved face is the coarse mesh's facets, not the
         sphere): about 8x the unknowns per refinement, case hemi_sS_rN. Two yardsticks (see below): the problem's own
         Dirichlet data without contact, a rigid translation of the body (zero strain), and the body "tied" to the
         plane, the contact face clamped (u = 0 on -contact_ids 1, listed last: it wins on the rim it shares with the
         top), the top pushed down as in the problem: a real deformation, like Example 2's yardstick;
  ex2    Example 2 turned rigidly by 30 degrees about (1,1,1) (options/cv_ex2_r30.opts, meshes/cv_ex2_sS_r30.msh made by
         tests/rotate_msh.py from meshes/ex2_sS.msh) against the unturned mesh, at scales --ex2-scales (default 2,4.2:
         124,128 and 1,074,513 unknowns);
  cyl    the 2D half disc on a plane (plane strain, options/cv_halfdisc.opts, meshes/cv_halfdisc.geo) on 2 ranks at
         mesh scale --cyl-scale (default 60, an estimate of 5e5 unknowns from 2,338 at scale 4 and about 3.6x per doubling:
         check the unknowns printed); with --cyl-refine N the mesh is also refined N times by -dm_refine N (about 4x the
         unknowns per refinement; the default then starts by nested iteration from the gmsh mesh), case cyl_sS_rN_np2;
         its yardsticks on the same 2 ranks (YARDSTICK_2D below: the iterative ones and MUMPS), the rigid translation
         and the clamped contact face as the hemisphere's;
  ex2c   the flat Example 2 as its default is measured (bench/nested.md): meshes/ex2_coarse.msh (2,733 unknowns) refined
         by -dm_refine N for each N of --ex2c-refine (e.g. 2,3: 144,666 and 1,115,460 unknowns), with its yardstick,
         run in the same rounds as the curved cases so that their cost ratios are measured side by side (not merged into
         cost_ratio_3d_curved), case ex2c_rN;
  ex2t   Example 2 turned by 30 degrees about (1,1,1) as the flat one is measured now: meshes/ex2_coarse.msh turned
         (meshes/cv_ex2_coarse_r30.msh, made by make: tests/rotate_msh.py) refined by -dm_refine N for each N of
         --ex2t-refine (2: 144,666 unknowns, 3: 1,115,460), options/cv_ex2_r30.opts, with its yardstick, against its
         flat partner (meshes/ex2_coarse.msh, the same N) run in the same rounds; both with -contact_kkt_scale vertex
         (the scales the same turned; the default's component maxima are not), so the flat partner is not ex2c's run:
         cases ex2t_rN_r30 and ex2t_rN_flat; into turned_vs_flat and (the turned) cost_ratio_3d_curved. With
         --ex2t-extra OPTS a third case ex2t_rN_r30x, the turned run with OPTS added (e.g. "-ssn_frame_global false"),
         in the table and in curved.runs only.
Each contact solve is set against the yardstick of scripts/bench.py: the fastest configured linear solve of the same
mesh (the same body and Dirichlet data without contact, each of bench.py's YARDSTICK_3D configurations at its
YARD_RTOL; 2D: YARDSTICK_2D), on the case's ranks, minimum over --repeat runs made in rounds (so that every case sees
the same load of a shared machine). Cases with a second yardstick (hemi, cyl: the clamped contact face) print both
ratios; cost_ratio_3d_curved keeps the first (the rigid translation, as measured before). Writes into --json (default bench/results.json; its other keys are kept, and the entries below are merged by unknowns
and case, so that a run of some sizes keeps the numbers of the others):
  cost_ratio_3d_curved  {unknowns: the default contact solve's time / the yardstick's time}  (hemi and the turned ex2;
                        the 2D cyl's ratios are in curved.runs: cost_ratio, cost_ratio_clamped)
  turned_vs_flat        {unknowns: the turned Example 2's contact solve time / the unturned one's}
  curved                the runs (unknowns, SSN, KSP, times, converged) and the yardsticks
and prints a markdown section for bench/results.md. Goals of issue 30: the default converges everywhere; its cost
against the yardstick at most 2.5 from 1e5 unknowns on; the turned Example 2 within 20 % of the unturned; at most 8
SSN steps. A benchmark, not a test: never run by make test.

With --geo-yard (bench/perf_nested.py's geometric yardstick, bench/nested.md): beside the yardstick above, a strained
linear problem on the same mesh, the case's Dirichlet data plus a body force (GEO below: hemisphere (0,0,-0.01), half
disc (0,-0.01), Example 2 (0,0,-1e5), the turned one turned), solved (a) by the case's default itself with the
obstacle moved out of reach (nothing touches: on a hierarchy every SSN step is a linear solve by nested iteration +
the geometric multigrid, coarse levels included; a run in which a vertex touches is not counted) and (b) by the same
AMG yardstick configurations from zero, --yard-repeat rounds each; cost_ratio_geometric = contact solve / the fastest
of (a) and (b). Cases hemi, cyl, ex2c and ex2t (the turned); printed as a second table with the hemisphere's ratios
against the flat Example 2's of the same -dm_refine, and in curved.runs.

usage: perf_curved.py [--only hemi,ex2,cyl,ex2c,ex2t] [--hemi-scales 4,8.5,18] [--hemi-refine N] [--ex2-scales 2,4.2] [--cyl-scale 60]
                      [--cyl-refine N] [--ex2c-refine 2,3] [--ex2t-refine 2,3] [--ex2t-extra OPTS] [--repeat N]
                      [--yard-repeat N] [--yard-configs NAME,...] [--geo-yard]
                      [--json FILE|none] [--out DIR]
The meshes are made with make (e.g. make meshes/cv_hemisphere_s8.msh meshes/cv_ex2_s2_r30.msh).
"""
import argparse
import json
import os
import resource
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import sgrun  # noqa: E402
from bench import YARDSTICK_3D, YARD_RTOL  # noqa: E402
from perf_nested import GEO_FAR, GEO_FORCE, timed  # noqa: E402

# 2D (the half disc on 2 ranks): the iterative configurations of YARDSTICK_3D that work in 2D, and MUMPS (the fastest
# linear solve of a 2D mesh of 5e5 unknowns may be the direct one)
YARDSTICK_2D = [(n, o) for n, o in YARDSTICK_3D if n.startswith(("BoomerAMG", "GAMG"))] + [
    ("MUMPS Cholesky (options/solver/mumps.opts)", "-options_file options/solver/mumps.opts")]

sgrun.ENV["OMP_NUM_THREADS"] = "1"  # hypre links libgomp: no spinning second thread

HEMI = "-options_file options/cv_hemisphere.opts"
HEMI_ELASTIC = "-E 1 -nu 0.3 -dirichlet_ids 2,6,3 -dirichlet_components xyz,x,y -dirichlet_values 0,0,-0.01,0,0,0,0,0,0"
# the second yardstick: the contact face (id 1) clamped, listed last so that it wins on the rim shared with the top
HEMI_CLAMPED = "-E 1 -nu 0.3 -dirichlet_ids 2,6,3,1 -dirichlet_components xyz,x,y,xyz -dirichlet_values 0,0,-0.01,0,0,0,0,0,0,0,0,0"
EX2P = "-options_file options/ex2_problem.opts -contact_kkt_scale vertex"  # the flat and the turned alike: the scales the same turned (the paper's file keeps component)
EX2_ELASTIC = "-dm_plex_gmsh_use_regions -E 1e6 -nu 0.45 -dirichlet_label top"
EX2_VALUES = "-dirichlet_values 0,0,-0.2"
EX2_VALUES_R30 = "-dirichlet_values -0.06666666666666667,0.04880338717125848,-0.18213672050459184"  # options/cv_ex2_r30.opts
CYL = "-options_file options/cv_halfdisc.opts"
CYL_ELASTIC = "-E 1 -nu 0.3 -dirichlet_ids 2,6 -dirichlet_components xy,x -dirichlet_values 0,-0.01,0,0"  # options/cv_halfdisc.opts
CYL_CLAMPED = "-E 1 -nu 0.3 -dirichlet_ids 2,6,1 -dirichlet_components xy,x,xy -dirichlet_values 0,-0.01,0,0,0,0"
# --geo-yard: (the body force, the obstacle out of reach) per problem; Example 2's are perf_nested.py's, the turned
# one's R (0,0,-1e5) and R c - 99 R e_z (options/cv_ex2_r30.opts' centre moved 99 along its up direction, as -0.3,0,-100)
GEO = {"hemi": ("-body_force 0,0,-0.01", "-obstacle_plane_point 0,0,-100"), "cyl": ("-body_force 0,-0.01", "-obstacle_plane_point 0,-100"),
       "ex2c": (GEO_FORCE, GEO_FAR),
       "ex2t": ("-body_force -33333.33333333333,24401.69358562924,-91068.36025229591",
                "-obstacle_ball_center -33.606538414090224,24.30169358562924,-90.99515517153903")}
FIELDS = ("dofs", "cont_type", "linear_solver", "outer_iterations", "ssn_iterations", "ksp_iterations", "linear_setup_time",
          "linear_solve_time", "solve_time", "peak_rss_mb", "converged", "reason", "energy", "contact_force", "nested_levels",
          "nested_coarse_ssn_its", "nested_coarse_ksp_its", "nested_coarse_time")


def mesh(path):
    """make the mesh if it is missing (the Makefile's rules)"""
    if not os.path.exists(os.path.join(ROOT, path)):
        subprocess.run(["make", "--no-print-directory", path], cwd=ROOT, check=True)
    return path


def best_of(runs):
    ok = [s for s in runs if s.get("converged") and s.get("solve_time")]
    return min(ok, key=lambda s: s["solve_time"]) if ok else (runs[-1] if runs else {})


def yardstick(args, tag, repeat, out, only=None, np=1, configs=YARDSTICK_3D):
    """the fastest configured linear solve of the body without contact on np ranks (minimum of repeat runs, in
    rounds); only: the configurations whose names contain one of these strings (None: all of configs)"""
    best = {}
    for r in range(repeat):
        for name, opts in configs:
            if only and not any(o in name for o in only):
                continue
            s, _ = sgrun.run("%s %s %s" % (args, opts, YARD_RTOL), "Y_%s_%s_%d" % (tag, "".join(c for c in name if c.isalnum())[:40], r), out, np=np, check=False)
            if s.get("converged") and s.get("linear_solve_time") and (name not in best or s["linear_solve_time"] < best[name]["linear_solve_time"]):
                best[name] = s
    if not best:
        return {"name": None, "time": None, "dofs": None}
    name = min(best, key=lambda n: best[n]["linear_solve_time"])
    return {"name": name, "time": best[name]["linear_solve_time"], "dofs": best[name]["dofs"], "ksp_iterations": best[name]["ksp_iterations"],
            "peak_rss_mb": best[name].get("peak_rss_mb"), "energy": best[name].get("energy"),
            "candidates": {n: {"time": v["linear_solve_time"], "ksp_iterations": v["ksp_iterations"]} for n, v in best.items()}}


def geo_yardstick(key, args, yargs, repeat, out, only, np, configs):
    """--geo-yard: the strained linear problem by the default, nothing touching, and by the AMG yardsticks; the fastest"""
    force, far = GEO[key.split("_")[0]]
    y = yardstick("%s %s" % (yargs, force), key + "_geo", repeat, out, only, np, configs)
    cand = dict(y.get("candidates") or {})
    own = []
    for r in range(repeat):
        s = timed("%s %s %s" % (args, far, force), "G_%s_default_%d" % (key, r), out, np)
        touching = s.get("active_set_size", 0) != 0
        sys.stderr.write("%s strained, the default (load %.1f): %s s, %s\n" % (key, s["load_before"], s.get("solve_time"),
                         "%s vertices touch: not counted" % s.get("active_set_size") if touching else s.get("reason")))
        if s.get("converged") and s.get("solve_time") and not touching:
            own.append(s)
    if own:
        b = min(own, key=lambda s: s["solve_time"])
        cand["default, nothing touching"] = {"time": b["solve_time"], "ksp_iterations": b["ksp_iterations"], "times": [s["solve_time"] for s in own],
                                             "coarse_ksp_iterations": b.get("nested_coarse_ksp_its"), "load_before": [s["load_before"] for s in own],
                                             "linear_solver": b.get("linear_solver"), "cpu_time": [s["cpu_time"] for s in own]}
    if not cand:
        return {"name": None, "time": None, "candidates": {}}
    name = min(cand, key=lambda n: cand[n]["time"])
    return {"name": name, "time": cand[name]["time"], "ksp_iterations": cand[name]["ksp_iterations"], "candidates": cand}


def geo_table(cases, res, geo, yards):
    """--geo-yard's markdown: both ratios, and the hemisphere's against the flat Example 2 of the same -dm_refine"""
    lines = ["", "The strained linear problem (--geo-yard: body force, obstacle out of reach), its fastest solve and both cost ratios; "
             "load: the 1-minute load average before each contact round.", "",
             "| case | unknowns | contact solve (rounds) | load | AMG yardstick (rigid data) | strained: default, nothing touching (CG finest / coarse) "
             "| strained: fastest configured yardstick (CG) | cost ratio (AMG) | cost_ratio_geometric |", "|---|---|---|---|---|---|---|---|---|"]
    for key, _, _, _ in cases:
        if key not in geo:
            continue
        s, c = res[key], geo[key]["candidates"]
        d = c.get("default, nothing touching", {})
        amg = {n: v for n, v in c.items() if n != "default, nothing touching"}
        fa = min(amg, key=lambda n: amg[n]["time"]) if amg else None
        lines.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            key, s.get("dofs"), ", ".join(fmt(t) for t in s["round_solve_times"]), ", ".join(fmt(x, "%.1f") for x in s["round_loads"]),
            "%s (%s, %s)" % (fmt(yards[key]["time"]), yards[key]["name"], yards[key].get("ksp_iterations")) if yards[key].get("time") else "-",
            "%s (%s / %s)" % (fmt(d.get("time")), d.get("ksp_iterations"), d.get("coarse_ksp_iterations")) if d else "-",
            "%s (%s, %s)" % (fmt(amg[fa]["time"]), fa, amg[fa]["ksp_iterations"]) if fa else "-",
            fmt(s.get("cost_ratio"), "%.2f"), fmt(s.get("cost_ratio_geometric"), "%.2f")))
    for key in geo:
        if key.startswith("hemi") and "_r" in key:
            flat = res.get("ex2c_r" + key.rsplit("_r", 1)[1], {})
            for f in ("cost_ratio", "cost_ratio_geometric"):
                if res[key].get(f) and flat.get(f):
                    q = res[key][f] / flat[f]
                    lines.append("%s: %s %.2f against ex2c's %.2f: %.2fx (%s 20 %%)" % (key, f, res[key][f], flat[f], q,
                                                                                      "within" if abs(q - 1) <= 0.2 else "NOT within"))
    return lines


def fmt(x, f="%.3g"):
    return "-" if x is None else f % x


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--only", default="hemi,ex2,cyl")
    ap.add_argument("--hemi-scales", default="4,8.5,18")
    ap.add_argument("--hemi-refine", type=int, default=0, help="-dm_refine N on each hemisphere mesh (0: none)")
    ap.add_argument("--ex2-scales", default="2,4.2")
    ap.add_argument("--cyl-scale", default="60")
    ap.add_argument("--cyl-refine", type=int, default=0, help="-dm_refine N on the half disc's mesh (0: none)")
    ap.add_argument("--ex2c-refine", default="2,3", help="the -dm_refine levels of the flat Example 2 from meshes/ex2_coarse.msh (case ex2c)")
    ap.add_argument("--ex2t-refine", default="2,3", help="the -dm_refine levels of the turned Example 2 from meshes/cv_ex2_coarse_r30.msh (case ex2t)")
    ap.add_argument("--ex2t-extra", default=None, help="case ex2t: also the turned run with these options added (case ex2t_rN_r30x)")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--yard-repeat", type=int, default=None, help="rounds of the yardsticks (default: --repeat)")
    ap.add_argument("--yard-configs", default=None, help="comma-separated parts of the names of the yardstick configurations "
                    "to run (default: all of scripts/bench.py's YARDSTICK_3D), e.g. PCHMG,l1-Gauss-Seidel where an earlier run "
                    "showed the others slower on the same mesh")
    ap.add_argument("--geo-yard", action="store_true", help="also the strained linear problem (a body force, the obstacle out of reach) "
                    "by the default and by the AMG yardsticks, and cost_ratio_geometric (see the usage)")
    ap.add_argument("--json", default=os.path.join(HERE, "results.json"))
    ap.add_argument("--out", default=os.path.join(HERE, "runs", "curved"))
    opt = ap.parse_args()
    only = set(opt.only.split(","))
    cases = []  # (key, contact args, yardstick args or None, ranks)
    clamped = {}  # key: the second yardstick's args (the contact face clamped)
    if "hemi" in only:
        for sc in opt.hemi_scales.split(","):
            m = mesh("meshes/cv_hemisphere_s%s.msh" % sc)
            ref, tag = (" -dm_refine %d" % opt.hemi_refine, "_r%d" % opt.hemi_refine) if opt.hemi_refine else ("", "")
            cases.append(("hemi_s%s%s" % (sc, tag), "%s -dm_plex_filename %s%s" % (HEMI, m, ref), "-dm_plex_filename %s %s%s" % (m, HEMI_ELASTIC, ref), 1))
            clamped["hemi_s%s%s" % (sc, tag)] = "-dm_plex_filename %s %s%s" % (m, HEMI_CLAMPED, ref)
    if "ex2" in only:
        for sc in opt.ex2_scales.split(","):
            flat = mesh("meshes/ex2_s%s.msh" % sc)  # scale 1: the mesh of meshes/ex2.msh
            turned = mesh("meshes/cv_ex2_s%s_r30.msh" % sc)
            cases.append(("ex2_s%s_flat" % sc, "%s -dm_plex_filename %s" % (EX2P, flat), None, 1))
            cases.append(("ex2_s%s_r30" % sc, "%s -dm_plex_filename %s -options_file options/cv_ex2_r30.opts" % (EX2P, turned),
                          "-dm_plex_filename %s %s %s" % (turned, EX2_ELASTIC, EX2_VALUES_R30), 1))
    if "cyl" in only:
        m = mesh("meshes/cv_halfdisc_s%s.msh" % opt.cyl_scale)
        ref, tag = (" -dm_refine %d" % opt.cyl_refine, "_r%d" % opt.cyl_refine) if opt.cyl_refine else ("", "")
        cases.append(("cyl_s%s%s_np2" % (opt.cyl_scale, tag), "%s -dm_plex_filename %s%s" % (CYL, m, ref), "-dm_plex_filename %s %s%s" % (m, CYL_ELASTIC, ref), 2))
        clamped["cyl_s%s%s_np2" % (opt.cyl_scale, tag)] = "-dm_plex_filename %s %s%s" % (m, CYL_CLAMPED, ref)
    if "ex2c" in only:
        for n in opt.ex2c_refine.split(","):
            m = "meshes/ex2_coarse.msh -dm_refine %s" % n
            cases.append(("ex2c_r%s" % n, "-options_file options/ex2_problem.opts -dm_plex_filename %s" % m,  # as scripts/bench.py's nested_default
                          "-dm_plex_filename %s %s %s" % (m, EX2_ELASTIC, EX2_VALUES), 1))
    if "ex2t" in only:
        flat, turned = mesh("meshes/ex2_coarse.msh"), mesh("meshes/cv_ex2_coarse_r30.msh")
        for n in opt.ex2t_refine.split(","):
            cases.append(("ex2t_r%s_flat" % n, "%s -dm_plex_filename %s -dm_refine %s" % (EX2P, flat, n), None, 1))
            cases.append(("ex2t_r%s_r30" % n, "%s -dm_plex_filename %s -dm_refine %s -options_file options/cv_ex2_r30.opts" % (EX2P, turned, n),
                          "-dm_plex_filename %s -dm_refine %s %s %s" % (turned, n, EX2_ELASTIC, EX2_VALUES_R30), 1))
            if opt.ex2t_extra:
                cases.append(("ex2t_r%s_r30x" % n, "%s -dm_plex_filename %s -dm_refine %s -options_file options/cv_ex2_r30.opts %s"
                              % (EX2P, turned, n, opt.ex2t_extra), None, 1))
    runs = {k: [] for k, _, _, _ in cases}
    for r in range(opt.repeat):  # rounds: every case once per round
        for key, args, _, np in cases:
            load, ru = os.getloadavg()[0], resource.getrusage(resource.RUSAGE_CHILDREN)
            s, _ = sgrun.run(args, "%s_%d" % (key, r), opt.out, np=np, check=False)
            ru2 = resource.getrusage(resource.RUSAGE_CHILDREN)
            s["load_before"] = load  # the 1-minute load average of the shared machine when the run started
            # the CPU time of the whole run (all ranks, set-up and output included): less sensitive than the wall time to
            # the other jobs of a shared machine, though not immune (caches, memory bandwidth)
            s["cpu_time"] = (ru2.ru_utime + ru2.ru_stime) - (ru.ru_utime + ru.ru_stime)
            runs[key].append(s)
            sys.stderr.write("%s round %d (load %.1f): %s s, %s\n" % (key, r, load, s.get("solve_time"), "converged" if s.get("converged") else s.get("reason", "no summary")))
    res = {k: {f: best_of(v).get(f) for f in FIELDS} for k, v in runs.items()}
    for k, v in runs.items():  # every round's time and load, for the medians and the side-by-side ratios
        res[k]["round_solve_times"] = [s.get("solve_time") if s.get("converged") else None for s in v]
        res[k]["round_loads"] = [s.get("load_before") for s in v]
        res[k]["round_cpu_times"] = [s.get("cpu_time") for s in v]
    yards, yards2, cost, turned = {}, {}, {}, {}
    geo = {}
    for key, args, yargs, np in cases:
        if yargs is None:
            continue
        yrep = opt.repeat if opt.yard_repeat is None else opt.yard_repeat
        only_y = opt.yard_configs.split(",") if opt.yard_configs else None
        configs = YARDSTICK_2D if key.startswith("cyl") else YARDSTICK_3D
        y = yardstick(yargs, key, yrep, opt.out, only_y, np, configs)
        yards[key] = y
        s = res[key]
        if y["time"] and s.get("converged"):
            s["cost_ratio"] = s["solve_time"] / y["time"]
        if key in clamped:  # beside the rigid translation, never instead of it
            y2 = yardstick(clamped[key], key + "_clamped", yrep, opt.out, only_y, np, configs)
            yards2[key] = y2
            if y2["time"] and s.get("converged"):
                s["cost_ratio_clamped"] = s["solve_time"] / y2["time"]
        if opt.geo_yard and key.split("_")[0] in GEO:
            geo[key] = geo_yardstick(key, args, yargs, yrep, opt.out, only_y, np, configs)
            if geo[key]["time"] and s.get("converged"):
                s["cost_ratio_geometric"] = s["solve_time"] / geo[key]["time"]
        # ex2c: the flat reference; cyl: 2D (its ratios stay in curved.runs)
        if y["time"] and s.get("converged") and s.get("dofs") and not key.startswith(("ex2c", "cyl")):
            cost[str(s["dofs"])] = s["solve_time"] / y["time"]
    for key in res:
        if key.endswith("_r30"):
            flat, tr = res[key[:-len("_r30")] + "_flat"], res[key]
            if flat.get("converged") and tr.get("converged") and tr.get("dofs"):
                turned[str(tr["dofs"])] = tr["solve_time"] / flat["solve_time"]
    # the markdown section
    lines = ["## Curved and tilted bodies (issue 30, bench/perf_curved.py)", "",
             "The default configuration (the problem's options alone) on the curved family; the yardstick is the fastest "
             "configured linear solve of the same mesh without contact (scripts/bench.py's YARDSTICK_3D, 2D: YARDSTICK_2D, at %s), on the case's ranks. Minimum of %d "
             "runs made in rounds; times in seconds." % (YARD_RTOL, opt.repeat), "",
             "| case | ranks | unknowns | controller | SSN / KSP finest | SSN / KSP coarse levels | contact solve | yardstick (CG) | cost ratio "
             "| clamped-face yardstick (CG) | cost ratio, clamped | peak MB (yardsticks') | converged |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]

    def ystr(y):
        return "-" if not y.get("time") else "%s (%s, %s)" % (fmt(y["time"]), y["name"], y.get("ksp_iterations"))

    for key, _, _, np in cases:
        s, y, y2 = res[key], yards.get(key, {}), yards2.get(key, {})
        lines.append("| %s | %d | %s | %s | %s / %s | %s / %s | %s | %s | %s | %s | %s | %s (%s) | %s |" % (
            key, np, s.get("dofs"), s.get("cont_type"), s.get("ssn_iterations"), s.get("ksp_iterations"), s.get("nested_coarse_ssn_its", "-"),
            s.get("nested_coarse_ksp_its", "-"), fmt(s.get("solve_time")), ystr(y), fmt(s.get("cost_ratio"), "%.2f"),
            ystr(y2) if key in clamped else "-", fmt(s.get("cost_ratio_clamped"), "%.2f"), fmt(s.get("peak_rss_mb"), "%.0f"),
            "/".join(fmt(v.get("peak_rss_mb"), "%.0f") for v in (y, y2) if v.get("time")) or "-",
            "yes" if s.get("converged") else "NO: %s" % str(s.get("reason"))[:60]))
    if geo:
        lines += geo_table(cases, res, geo, yards)
    lines += ["", "Turned Example 2 against the unturned, contact solve time ratio: %s (goal: within 20 %%)." %
              (", ".join("%s unknowns %.2f" % (d, v) for d, v in turned.items()) or "-"), ""]
    print("\n".join(lines))
    if opt.json != "none":
        js = {}
        if os.path.exists(opt.json):
            with open(opt.json) as f:
                js = json.load(f)
        # merged by unknowns and case: a run of some sizes only (e.g. the 1e6 ones) keeps the others' numbers
        js.setdefault("cost_ratio_3d_curved", {}).update(cost)
        js.setdefault("turned_vs_flat", {}).update(turned)
        cv = js.setdefault("curved", {})
        cv.setdefault("runs", {}).update(res)
        cv.setdefault("yardsticks", {}).update(yards)
        cv.setdefault("yardsticks_clamped", {}).update(yards2)
        cv.setdefault("yardsticks_geometric", {}).update(geo)
        cv["repeat"] = opt.repeat
        sgrun.write_atomic(opt.json, json.dumps(js, indent=1, sort_keys=False) + "\n")


if __name__ == "__main__":
    main()
