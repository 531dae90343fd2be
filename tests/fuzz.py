#!/usr/bin/python3
"""Randomized robustness test (issue 10): random option combinations and random mutations of a valid options file,
a gmsh mesh and a checkpoint, run through bin/signorini. For every run it asserts

  (a) no signal, abort or crash, and no hang (a run over --run-timeout seconds is killed and counted as a hang);
  (b) exit 0 only when the JSON summary says converged and the residual of the problem solved meets its tolerance
      (keys problem/residual/residual_tol; for problem "P" also residual == kkt_residual; without those keys:
      kkt_residual <= the -cont_kkt_tol the run was given); no NaN or negative count in a successful summary, and
      where y = 0 is admissible the energy of a solution is <= 0 and >= the unconstrained energy;
  (c) a nonzero exit names an option ("-something") or a file given to the run in its error message;
  (d) no .part file after any run, no result file (-output_file .h5/.xmf) after a failure, a file that was at a result
      path before is either untouched or replaced by a complete result, no other file written.

The generators of issue 25 add their own judgements of a run's physics, which do not trust the program's measures:
  unload    load paths back to zero (-load_dirichlet_values): back at zero y = 0 and no contact force, lifted off a
            rigid translation, frictionless the answer of a fresh solve at the path's end, the forces balance
            (reaction = contact + friction - load) and friction stays within its bound; a step at zero must be solved
            where y = 0 solves it (frictionless, Coulomb: item 9);
  nu        nu from 0.49 to 0.4999999999999999 with every controller: V <= 0 where y = 0 is admissible, the force
            balance, no contact force without an active set, and a second controller that converges agrees (item 1);
  restart   -restart_file with the problem changed (a sign, a direction of the same norm, E and nu with the same
            shear modulus, the obstacle mirrored, the friction law): refused, naming -restart_file; unchanged (also
            spelled otherwise, reordered, on 2 ranks): accepted with the fresh solve's answer (item 2);
  misuse    bin/misuse_tests -case GROUP (tests/misuse.c: wrong calls of the library), where that program is built:
            no signal, exit 0 with every wrong call caught; skipped (one line in the report) where it is not (item 12).
`--only unload,nu` runs only those generators' cases (numbered as in the full run), --verbose a line per case.

Cases are drawn from --seed and the case number alone, so a case is the same on every machine and in every order;
--time-limit stops starting new cases (the summary then counts fewer than --count). Every run writes only into its own
temporary directory ($T in the commands printed); `fuzz.py --seed S --case I --keep` recreates case I there.

The code: tests/fuzzing/generators.py draws the cases (the controller and friction law names from the program's
registries, read by fuzzing/registry.py from bin/signorini -help), fuzzing/checks.py judges the runs ((a)-(d) and the
physics), fuzzing/selftest.py checks the checks (--self-test), fuzzing/common.py holds what they share; this file runs
the cases and reports.

usage: fuzz.py [--count N] [--seed S] [--time-limit T] [--jobs J] [--case I] [--only GEN,..] [--verbose] [--keep]
               [-summary_file F]
Output: one line per violation with the command, a count per generator, and "N passed, N failed" (cases).
"""
import argparse
import ctypes
import json
import os
import random
import resource
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from concurrent.futures import ThreadPoolExecutor

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fuzzing.common import ENV, MEM_LIMIT, ROOT, SENTINEL, output_args, sgrun, snapshot
from fuzzing.checks import check_misuse, check_run
from fuzzing.generators import LAWS_NOT_DRAWN, draw_case, generator_of, make_checkpoints
from fuzzing.selftest import self_test


LIBC = ctypes.CDLL(None, use_errno=True)
ACTIVE, TMPDIRS = set(), set()  # running runs and case directories, for a clean stop on SIGINT/SIGTERM


def _limits():
    resource.setrlimit(resource.RLIMIT_AS, (MEM_LIMIT, MEM_LIMIT))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    LIBC.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG: a run does not outlive the fuzzer (a killed harness leaves no hang)


def _stop(signum, frame):
    for p in list(ACTIVE):
        try:
            os.killpg(p.pid, signal.SIGKILL)  # each run is its own process group (start_new_session)
        except ProcessLookupError:
            pass
    for d in list(TMPDIRS):
        shutil.rmtree(d, ignore_errors=True)
    os._exit(128 + signum)


# ---------------------------------------------------------------- running and checking

def shown(run, T):
    """The command as a user would type it in the repository, the case directory written $T."""
    if run.exe:
        cmd = sgrun.command(run.args, run.np if run.np > 1 else None, os.path.relpath(run.exe, ROOT))
    else:
        cmd = sgrun.command(run.args + output_args(T) + run.tail, run.np if run.np > 1 else None, "bin/signorini")
    return " ".join(shlex.quote(a).replace(T, "$T") if T in a else shlex.quote(a) for a in cmd)



def execute(run, T, timeout):
    if run.exe:
        cmd = sgrun.command(run.args, run.np if run.np > 1 else None, run.exe)
    else:
        cmd = sgrun.command(run.args + output_args(T) + run.tail, run.np if run.np > 1 else None)
    t0 = time.time()
    p = subprocess.Popen(cmd, cwd=ROOT, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True,
                         preexec_fn=_limits)
    ACTIVE.add(p)
    timed_out = False
    try:
        out, _ = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        timed_out = True
        try:
            os.killpg(p.pid, signal.SIGKILL)  # the run's own process group (start_new_session)
        except ProcessLookupError:
            pass
        out, _ = p.communicate()
    ACTIVE.discard(p)
    return {"rc": p.returncode, "out": out.decode("utf-8", errors="replace"), "timeout": timed_out, "limit": timeout,
            "seconds": time.time() - t0}


def run_case(case, T, opt, rng):
    t0 = time.time()
    summaries = []
    for run in case.runs:
        for n in ("r.h5", "r.xmf", "r.json", "r.csv"):
            p = os.path.join(T, n)
            if os.path.exists(p):
                os.remove(p)
        for p in [os.path.join(T, f) for f in os.listdir(T) if f.endswith(".part")]:
            os.remove(p)
        if rng.random() < 0.3:  # results of an earlier run at the result paths: never replaced by a broken file
            for n in ("r.h5", "r.xmf", "r.json", "r.csv"):
                with open(os.path.join(T, n), "wb") as f:
                    f.write(SENTINEL)
        before = snapshot(T)
        run.result = execute(run, T, opt.run_timeout)
        run.shown = shown(run, T)
        if run.exe:
            v, s = check_misuse(run, T, before)
        else:
            v, s = check_run(case, run, T, before)
            crashed = any(c.startswith("a:") for c, d in v)
            if run.judge and not crashed:
                v += run.judge(run, s)  # the generator's own judgement
        summaries.append(s)
        case.violations += [(c, d, run) for c, d in v]
    if callable(case.twin):
        case.violations += case.twin(case, summaries)
    elif case.twin and all(r.result["rc"] in (0, 3) for r in case.runs):
        a, b = case.runs[0].result["rc"], case.runs[1].result["rc"]
        if a != b:
            case.violations.append(("b: verdict changes with the units (E, loads, gamma x 10^k)",
                                    "exit %d scaled, %d unscaled; outer %s vs %s" % (a, b, *(str((s or {}).get("outer_iterations")) for s in summaries)), case.runs[0]))
    case.seconds = time.time() - t0


def repo_listing():
    out = set()
    for d in ("", "tests", "tests/opts", "tests/data", "options", "options/cont", "options/solver", "meshes", "bin"):
        try:
            out |= {os.path.join(d, f) for f in os.listdir(os.path.join(ROOT, d))}
        except OSError:
            pass
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--count", type=int, default=200)
    ap.add_argument("--seed", type=int, default=int(os.environ.get("FUZZ_SEED", "1")))
    ap.add_argument("--time-limit", type=float, default=600, help="start no case after this many seconds")
    ap.add_argument("--run-timeout", type=float, default=30, help="a run longer than this is a hang")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--case", type=int, action="append", help="run only this case (repeatable)")
    ap.add_argument("--keep", action="store_true", help="keep the case directories and print them")
    ap.add_argument("--verbose", action="store_true", help="print a line per case: its description and exit codes")
    ap.add_argument("--only", default="", help="run only the cases of these generators (comma-separated names), "
                    "numbered as in the full run")
    ap.add_argument("-summary_file", "--summary-file", dest="summary_file", default="")
    ap.add_argument("--self-test", action="store_true", help="check the checks on synthetic runs, then stop")
    opt = ap.parse_args()
    if opt.self_test:
        bad = self_test()
        if opt.summary_file:
            with open(opt.summary_file, "w") as f:
                json.dump({"self_test_failures": bad}, f)
        sys.exit(1 if bad else 0)
    if not os.access(sgrun.SIGNORINI, os.X_OK):
        sys.exit("fuzz.py: bin/signorini is missing: run make all")
    t0 = time.time()
    listing = repo_listing()
    signal.signal(signal.SIGINT, _stop)
    signal.signal(signal.SIGTERM, _stop)
    master = tempfile.mkdtemp(prefix="fuzz-base-")
    TMPDIRS.add(master)
    base = make_checkpoints(master)
    indices = opt.case if opt.case else list(range(opt.count))
    if opt.only:
        indices = [i for i in indices if generator_of(opt.seed, i) in opt.only.split(",")]
    cases, lock = [], threading.Lock()
    start = time.time()

    def work(i):
        if time.time() - start > opt.time_limit:
            return None
        T = tempfile.mkdtemp(prefix="fuzz-%d-" % i)
        TMPDIRS.add(T)
        try:
            case = draw_case(opt.seed, i, T, base)
            run_case(case, T, opt, random.Random("files:%d:%d" % (opt.seed, i)))
        finally:
            if opt.keep:
                print("case %d: kept in %s" % (i, T), flush=True)
            else:
                shutil.rmtree(T, ignore_errors=True)
            TMPDIRS.discard(T)
        with lock:
            cases.append(case)
            if opt.verbose:
                print("case %d %s [%s]: exit %s, %.1f s%s" % (i, case.gen, case.desc, ",".join(str(r.result["rc"]) for r in case.runs) or "-",
                                                             case.seconds, "" if not case.violations else ", FAIL"), flush=True)
        return case

    with ThreadPoolExecutor(max_workers=opt.jobs) as pool:
        list(pool.map(work, indices))
    shutil.rmtree(master, ignore_errors=True)
    cases.sort(key=lambda c: c.index)
    stray = sorted(repo_listing() - listing)

    by_class, by_gen = {}, {}
    nviol = 0
    for c in cases:
        g = by_gen.setdefault(c.gen, {"cases": 0, "failed": 0, "violations": 0, "skipped": 0})
        g["cases"] += 1
        g["skipped"] += c.skipped
        g["failed"] += bool(c.violations)
        g["violations"] += len(c.violations)
        for cls, detail, run in c.violations:
            nviol += 1
            by_class[cls] = by_class.get(cls, 0) + 1
            print("FAIL %s #%d [%s] %s: %s\n    $ %s" % (c.gen, c.index, c.desc, cls, detail, run.shown))
    if stray:
        nviol += 1
        by_class["d: file written into the repository"] = 1
        print("FAIL files written into the repository: %s" % " ".join(stray[:10]))
    print("# $T is the case's own temporary directory; `tests/fuzz.py --seed %d --case I --keep` recreates case I" % opt.seed)
    print("# violations by class:")
    for cls in sorted(by_class):
        print("#   %4d  %s" % (by_class[cls], cls))
    print("# by generator (cases, failing cases, violations):")
    for g in sorted(by_gen):
        print("#   %-10s %5d %5d %5d" % (g, by_gen[g]["cases"], by_gen[g]["failed"], by_gen[g]["violations"]))
    for g in sorted(by_gen):
        if by_gen[g]["skipped"]:
            why = sorted({c.desc for c in cases if c.gen == g and c.skipped})
            print("# %s: %d cases skipped: %s" % (g, by_gen[g]["skipped"], "; ".join(why)[:200]))
    if LAWS_NOT_DRAWN:
        print("# friction laws registered but not drawn (fuzzing/generators.py knows no parameter of theirs): %s" % " ".join(LAWS_NOT_DRAWN))
    secs = time.time() - t0
    failed = sum(1 for c in cases if c.violations) + bool(stray)
    print("# seed %d, %d cases in %.1f s (%d runs)" % (opt.seed, len(cases), secs, sum(len(c.runs) for c in cases)))
    if len(cases) < len(indices):
        print("# time limit: %d of %d cases not run" % (len(indices) - len(cases), len(indices)))
    if opt.summary_file:
        with open(opt.summary_file, "w") as f:
            json.dump({"cases": len(cases), "violations": nviol, "failed_cases": failed, "seed": opt.seed, "seconds": secs,
                       "by_class": by_class, "by_generator": by_gen}, f, indent=1)
    print("%d passed, %d failed" % (len(cases) - failed + bool(stray), failed))
    sys.exit(1 if nviol or len(cases) < len(indices) else 0)


if __name__ == "__main__":
    main()
