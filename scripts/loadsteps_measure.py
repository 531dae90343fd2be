#!/usr/bin/python3
"""Load steps against independent solves: total SSN (PDAS) iterations of one run with -load_steps N (each step
warm-started from the last) and of N runs solving each load level from the unconstrained start (the load options
scaled by t_k = k/N), for ipf and pdas on Example 1 and on coarse Example 2. Prints a Markdown table.

usage: loadsteps_measure.py [--steps 4] [--out DIR]
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sgrun  # noqa: E402

# each example: its options and the load options as a function of the factor t
EXAMPLES = {
    "ex1": ("-options_file options/ex1.opts -options_file options/solver/mumps.opts",
            lambda t: "-neumann_traction 0,%.17g" % (-2 * t)),
    "ex2_coarse": ("-options_file options/ex2_problem.opts -dm_plex_filename meshes/ex2_coarse.msh -options_file options/solver/mumps.opts",
                   lambda t: "-dirichlet_values 0,0,%.17g" % (-0.2 * t)),
}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--steps", type=int, default=4)
    ap.add_argument("--out", default=os.path.join(sgrun.ROOT, "results", "runs", "loadsteps"))
    opt = ap.parse_args()
    n = opt.steps
    print("| example | controller | N | SSN per load step (warm) | total | independent solves (SSN each) | total | final force rel. diff |")
    print("|---|---|---|---|---|---|---|---|")
    for ex, (base, load) in EXAMPLES.items():
        for cont in ("ipf", "pdas"):
            args = "%s -options_file options/cont/%s.opts" % (base, cont)
            s, _ = sgrun.run("%s -load_steps %d" % (args, n), "%s_%s_steps%d" % (ex, cont, n), opt.out)
            cold = []
            for k in range(1, n + 1):
                c, _ = sgrun.run("%s %s" % (args, load(k / n)), "%s_%s_cold%d_%d" % (ex, cont, k, n), opt.out)
                cold.append(c)
            warm = s["load_step_ssn_iterations"]
            its = [c["ssn_iterations"] for c in cold]
            rel = abs(s["contact_force"] - cold[-1]["contact_force"]) / abs(cold[-1]["contact_force"])
            print("| %s | %s | %d | %s | %d | %s | %d | %.1e |" % (ex, cont, n, ", ".join(map(str, warm)), sum(warm),
                                                               ", ".join(map(str, its)), sum(its), rel))


if __name__ == "__main__":
    main()
