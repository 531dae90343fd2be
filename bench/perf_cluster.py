#!/usr/bin/python3
"""Cluster scale (issue 27, item 3): Example 2 from a small gmsh file refined in parallel after distribution
(-dm_refine N), on NP ranks; peak resident memory of each rank (/usr/bin/time -v) and the times of three runs:
  setup    the mesh read, distributed and refined, the problem set up and K assembled (no contact; one CG step with
           Jacobi, so that the run stops right after the set-up)
  linear   the yardstick: the same body without contact, CG + BoomerAMG l1-GS (scripts/bench.py's YARDSTICK_3D
           candidate of the default contact configuration) at rtol 1e-8
  contact  the default iterative configuration (-cont_direct_max_unknowns 0) with -output_file and -checkpoint_file
Prints a row per run (unknowns, peak MB of each rank, the run's wall time, mesh set-up, assembly, linear setup + solve,
contact solve, output, file sizes) for bench/nested.md. Measurements, not part of `make bench`; one run each.

usage: perf_cluster.py [--mesh ex2_coarse] [--refine 3] [--np 2] [--out DIR] [--runs setup,linear,contact]
"""
import argparse
import json
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
import sgrun  # noqa: E402

ROOT = sgrun.ROOT
ENV = dict(sgrun.mpi_env(), OMP_NUM_THREADS="1")
ELASTIC = "-dm_plex_gmsh_use_regions -E 1e6 -nu 0.45 -dirichlet_label top -dirichlet_values 0,0,-0.2"
L1GS = "-pc_hypre_boomeramg_relax_type_down l1-Gauss-Seidel -pc_hypre_boomeramg_relax_type_up backward-l1-Gauss-Seidel"


def event_time(logview, name):
    """The time of a -log_view event (max over ranks), 0 if absent."""
    for line in open(logview):
        f = line.split()
        if f and f[0] == name and len(f) > 3:
            return float(f[3])
    return 0.0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--mesh", default="ex2_coarse")
    ap.add_argument("--refine", type=int, default=3)
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--out", default="/tmp/perf_cluster")
    ap.add_argument("--runs", default="setup,linear,contact")
    opt = ap.parse_args()
    os.makedirs(opt.out, exist_ok=True)
    mesh = "-dm_plex_filename %s -dm_refine %d" % (os.path.join(ROOT, "meshes", opt.mesh + ".msh"), opt.refine)
    tag = "%s_r%d_np%d" % (opt.mesh, opt.refine, opt.np)
    runs = {"setup": "%s %s -ksp_type cg -pc_type jacobi -ksp_max_it 1" % (mesh, ELASTIC),
            "linear": "%s %s -options_file %s %s -ksp_rtol 1e-8" % (mesh, ELASTIC, os.path.join(ROOT, "options/solver/hypre.opts"), L1GS),
            "contact": "-options_file %s %s -cont_direct_max_unknowns 0 -output_file {out}/%s_out.h5 -checkpoint_file {out}/%s_ck.h5"
                       % (os.path.join(ROOT, "options/ex2_problem.opts"), mesh, tag, tag)}
    print("| run | unknowns | peak MB per rank | wall [s] | mesh set-up [s] | assembly [s] | linear setup + solve [s] | contact solve [s] | output [s] | fields file MB | checkpoint MB |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for name in opt.runs.split(","):
        base = os.path.join(opt.out, "%s_%s" % (tag, name))
        timef = base + ".time."
        args = runs[name].format(out=opt.out).split() + ["-summary_file", base + ".json", "-log_view", ":" + base + ".logview"]
        cmd = ["mpiexec", "-n", str(opt.np), "sh", "-c", 'exec /usr/bin/time -v -o %s$OMPI_COMM_WORLD_RANK "$0" "$@"' % timef,
               os.path.join(ROOT, "bin", "signorini")] + args
        with open(base + ".log", "w") as log:
            subprocess.run(cmd, env=ENV, stdout=log, stderr=subprocess.STDOUT, cwd=ROOT)
        rss = []
        for r in range(opt.np):
            m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", open(timef + str(r)).read()) if os.path.exists(timef + str(r)) else None
            rss.append("%.0f" % (int(m.group(1)) / 1024.0) if m else "-")
        try:
            s = json.load(open(base + ".json"))
        except (OSError, ValueError):
            print("| %s | failed (see %s.log) |" % (name, base))
            continue
        lv = base + ".logview"
        size = (lambda p: "%.1f" % (os.path.getsize(p) / 1e6) if os.path.exists(p) else "-")
        print("| %s | %d | %s | %.1f | %.1f | %.1f | %.1f | %s | %s | %s | %s |" % (
            name, s["dofs"], " / ".join(rss), s["wall_time"], event_time(lv, "SgMeshSetUp"), s["assembly_time"],
            s["linear_solve_time"], ("%.1f" % s["solve_time"]) if name == "contact" else "-",
            ("%.1f" % event_time(lv, "SgOutput")) if name == "contact" else "-",
            size(os.path.join(opt.out, tag + "_out.h5")) if name == "contact" else "-",
            size(os.path.join(opt.out, tag + "_ck.h5")) if name == "contact" else "-"), flush=True)
    print("%d ranks, OMP_NUM_THREADS=1; options: bench/perf_cluster.py" % opt.np)


if __name__ == "__main__":
    main()
