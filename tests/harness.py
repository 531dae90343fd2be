#!/usr/bin/env python3
"""Test harness in PETSc's test vocabulary.

Each section of a tests/GROUP/*.ini file is one test: a run of bin/signorini (or of a command given by `cmd`) with
`nsize` MPI ranks and `args`, followed by `checks` on the quantities the run computed (its JSON summary and
CSV history). A check is a Python expression; it may use
    s            this test's summary (dict),        h   its history rows (list of dicts)
    t[name]      the summary of another test,       H[name] its history
`depends_on = NAME ...` names tests that must have run first: their results are read by the checks (t, H) or their
files by the run (a restart reads a checkpoint). -k runs them too, -x leaves out the tests that depend on a left-out
one. A dependency may sit in another file or group: when it is not among the files given, the harness finds it in
the tree (tests/**/*.ini) and runs it too. (Not PETSc's `requires`, which names configure features.)
    close(a, b, rtol, atol=0), between(x, lo, hi), order(e_coarse, e_fine, ratio), rel(a, b), ssn(rows)
Tests with `expect_error = REGEX` must fail: nonzero exit, REGEX found in the output, and no result file left.
Every run uses -options_left: an option the program did not use fails the test.

Groups (a directory each; a topic may have a file in several groups, named alike, e.g. tests/*/friction.ini):
    unit          kernels and house rules, each computing what it is checked on (bin/unit_tests, tests/check_layers.py)
    verification  against known answers: manufactured solutions, analytic obstacles, Hertz, Cattaneo, 1/gamma rates,
                  the solvers against each other, the KKT measures at the edges of valid input
    regression    the paper's reproductions: Table 1, Table 2, Examples 1 and 2 with every controller
    features      one feature each (friction, load steps, rollers, restarts, outputs, the verdicts of the solvers, ...)
    input         bad input and refusals: options, meshes, files, wrong library calls, the random robustness test
    parallel      the same runs on several ranks against one
A FILE argument may be an .ini file, a group's directory or tests/ (every .ini below it).

`memcheck = yes` in a section puts the test into `make check-memory` (harness.py --valgrind runs only those): a test
is NOT run under valgrind unless it says so (each run costs 10-30 s or more under memcheck, and the suite has a time
budget). Tag one test per code path that handles memory: a 2D run, not its 3D, parallel or long variants, not a second
run of a path another tagged test covers, not the scripted cases (cmd = python ...: they do not run our executables
under valgrind), not energies compared with long double (valgrind computes it in double precision). The tests a tagged
test depends on must be tagged too (checked at start). `--list` prints the selected tests without running them;
`--check` checks the whole tree (names unique, tags yes or no and closed under depends_on, dependencies found, every
file in a group) and runs nothing.

usage: harness.py [-j JOBS] [-k PATTERN] [-x PATTERN] [--valgrind] [--list] [--check] FILE.ini|DIR|GROUP ...
"""
import argparse
import configparser
import glob
import math
import os
import re
import shlex
import subprocess
import sys
import threading
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
import sgrun  # noqa: E402

ROOT = sgrun.ROOT
OUT = os.path.join(ROOT, "tests", "output")
ENV = sgrun.mpi_env(single_copy=False)


def close(a, b, rtol=1e-10, atol=0.0):
    return a is not None and b is not None and abs(a - b) <= atol + rtol * max(abs(a), abs(b))


def rel(a, b):
    return abs(a - b) / max(abs(a), abs(b), 1e-300)


def between(x, lo, hi):
    return x is not None and lo <= x <= hi


def order(e_coarse, e_fine, ratio=2.0):
    return math.log(e_coarse / e_fine) / math.log(ratio)


def ssn(rows):
    return [r for r in rows if r["kind"] == "ssn"]


TESTS = os.path.join(ROOT, "tests")
GROUPS = ("unit", "verification", "regression", "features", "input", "parallel")


def ini_files(args):
    """The .ini files named, and every .ini file below a directory named (sorted)."""
    files = []
    for a in args:
        if not os.path.exists(a) and os.path.basename(a) == "*.ini" and os.path.isdir(os.path.dirname(a) or "."):
            a = os.path.dirname(a) or "."  # an unexpanded tests/*.ini (the tests moved into groups): the whole tree
        if os.path.isdir(a):
            files += sorted(f for f in glob.glob(os.path.join(a, "**", "*.ini"), recursive=True)
                            if not os.path.abspath(f).startswith(OUT + os.sep))  # not what the runs wrote
        elif os.path.exists(a):
            files.append(a)
        elif not os.path.isdir(os.path.join(TESTS, a)):
            sys.exit("harness.py: no file or group %s (the tests are grouped by concern in tests/GROUP/TOPIC.ini: "
                     "`harness.py -k NAME tests` finds a test in any of them)" % a)
        else:  # a group's name alone
            files += sorted(glob.glob(os.path.join(TESTS, a, "*.ini")))
    seen = set()  # a file named twice (tests and tests/unit) is read once
    return [f for f in files if not (os.path.realpath(f) in seen or seen.add(os.path.realpath(f)))]


def load(files, skip=()):
    """The tests of the files by name; a name twice is an error (`skip`: names already loaded elsewhere)."""
    tests = {}
    for fn in files:
        cp = configparser.ConfigParser(interpolation=None)
        cp.optionxform = str
        with open(fn) as f:
            cp.read_file(f)
        for name in cp.sections():
            if name in tests:
                sys.exit("duplicate test name %s in %s" % (name, fn))
            if name not in skip:
                tests[name] = Test(name, cp[name])
    return tests


VALGRIND = []  # --valgrind: the memcheck command put in front of our executables


class Test:
    def __init__(self, name, sec):
        self.name = name
        self.nsize = int(sec.get("nsize", "1"))
        self.args = " ".join(sec.get("args", "").split())
        self.cmd = sec.get("cmd", "bin/signorini")
        self.checks = [c.strip() for c in sec.get("checks", "").splitlines() if c.strip()]
        self.expect_error = sec.get("expect_error")
        if "requires" in sec:  # the old name, refused so that a dependency is never dropped silently
            sys.exit("test %s: the key `requires` is now `depends_on`" % name)
        self.depends_on = sec.get("depends_on", "").split()
        self.timeout = float(sec.get("timeout", "600")) * (20 if VALGRIND else 1)
        self.outputs = sec.get("outputs", "").split()  # files the run must not leave behind when it fails
        self.memcheck = sec.get("memcheck", "no")
        if self.memcheck not in ("yes", "no"):
            sys.exit("test %s: memcheck = %s, must be yes or no" % (name, self.memcheck))
        self.memcheck = self.memcheck == "yes"
        self.returncode = None
        self.output = ""
        self.summary = {}
        self.history = []
        self.seconds = 0.0
        self.failures = []

    def files(self):
        base = os.path.join(OUT, self.name)
        return {"summary": base + ".json", "history": base + ".csv", "output": base + ".h5"}

    def run(self):
        f = self.files()
        for p in glob.glob(os.path.join(OUT, self.name + ".*")):
            os.remove(p)
        args = self.args.replace("@OUT@", OUT).replace("@NAME@", self.name)
        if self.cmd == "bin/signorini" or self.cmd.startswith("bin/"):
            vg = VALGRIND
            if vg and self.expect_error is not None:  # PETSc's error handler aborts: memory is not freed then, but errors still count
                vg = [a for a in vg if not a.startswith("--errors-for-leak-kinds")] + ["--errors-for-leak-kinds=none"]
            main = self.cmd == "bin/signorini"  # other executables write no history and take no -options_left
            # one rank: an MPI singleton, without mpiexec (whose start and clean-up cost more than most of our runs)
            cmd = sgrun.command(shlex.split(args), None if self.nsize == 1 else self.nsize, os.path.join(ROOT, self.cmd), vg, f["summary"],
                                f["history"] if main else None) + (["-options_left"] if main else [])
            if not VALGRIND:
                # PETSc lists what was not freed: a leak fails the test. -malloc_dump alone turns on PETSc's tracing
                # malloc (it lists leaks and checks each block's guards when it is freed); -malloc_debug adds a walk
                # over the whole heap at every PetscMalloc and PetscFree, which made a 2-rank run of 306 unknowns take
                # 16 s instead of 2.7 s: SG_MALLOC_DEBUG=1 in the environment asks for it (the memcheck tests run
                # under valgrind, which sees every byte).
                cmd += (["-malloc_debug"] if os.environ.get("SG_MALLOC_DEBUG") == "1" else []) + ["-malloc_dump"]
        else:
            cmd = shlex.split(self.cmd.replace("@OUT@", OUT).replace("@NAME@", self.name)) + shlex.split(args)
        t0 = time.time()
        try:
            p = sgrun.execute(cmd, ENV, self.timeout)
            self.returncode, self.output = p.returncode, p.stdout
        except subprocess.TimeoutExpired as e:
            self.returncode, self.output = -1, (e.stdout or "") if isinstance(e.stdout, str) else ""
            self.failures.append("timed out after %g s" % self.timeout)
        self.seconds = time.time() - t0
        try:
            self.summary = sgrun.summary(f["summary"])
        except ValueError as e:
            self.failures.append("summary is not valid JSON: %s" % e)
        self.history = sgrun.history(f["history"])

    def evaluate(self, tests):
        if VALGRIND and self.returncode == 201:
            self.failures.append("valgrind memcheck found errors or definite leaks")
        if self.failures:
            return
        if self.expect_error is not None:
            if self.returncode == 0:
                self.failures.append("expected a failure, but the run exited 0")
            if not re.search(self.expect_error, self.output, re.S):
                self.failures.append("output does not match /%s/" % self.expect_error)
            if re.search(r"Segmentation Violation|signal number 11|Caught signal", self.output):
                self.failures.append("the run crashed instead of stopping with an error")
            left = [p for p in self.outputs + [self.files()["output"]] if os.path.exists(os.path.join(ROOT, p.replace("@OUT@", OUT).replace("@NAME@", self.name)))]
            left += glob.glob(os.path.join(OUT, self.name + "*.part"))
            if left:
                self.failures.append("result files left behind: %s" % " ".join(left))
        elif self.returncode != 0:
            self.failures.append("exit status %d" % self.returncode)
        if self.expect_error is None and re.search(r"^\[\s*\d+\]\s*\d+ bytes ", self.output, re.M):
            self.failures.append("memory not freed (-malloc_dump): " + "; ".join(l.strip() for l in self.output.splitlines() if re.search(r"\d+ bytes", l))[:400])
        if self.cmd == "bin/signorini" and self.expect_error is None and "Option left:" in self.output:
            self.failures.append("unused options: " + "; ".join(l.strip() for l in self.output.splitlines() if "Option left" in l))
        ns = {"s": self.summary, "h": self.history, "t": {k: v.summary for k, v in tests.items()},
              "H": {k: v.history for k, v in tests.items()}, "close": close, "rel": rel, "between": between,
              "order": order, "ssn": ssn, "math": math, "out": self.output, "re": re}
        for c in self.checks:
            try:
                ok = eval(c, ns)
            except Exception as e:  # a missing key or test is a failed check
                ok, c = False, "%s  [%s: %s]" % (c, type(e).__name__, e)
            if not ok:
                self.failures.append("check failed: %s" % c)


def check_tree():
    """--check: the whole tree's test files (load() stops at a duplicate name or a bad memcheck value); 0 if sound."""
    files = ini_files([TESTS])
    tests = load(files)
    bad = ["test %s depends on unknown test %s" % (t.name, r) for t in tests.values() for r in t.depends_on if r not in tests]
    bad += ["test %s has memcheck = yes but depends on %s, which has not" % (t.name, r) for t in tests.values() if t.memcheck
            for r in t.depends_on if r in tests and not tests[r].memcheck]
    bad += ["%s is in no group (tests/GROUP/: %s)" % (os.path.relpath(f, ROOT), ", ".join(GROUPS)) for f in files
            if os.path.relpath(f, TESTS).split(os.sep)[0] not in GROUPS]
    for b in bad:
        print("not ok " + b)
    print("%d test files, %d tests, %d of them under valgrind (memcheck = yes); %d problems"
          % (len(files), len(tests), sum(t.memcheck for t in tests.values()), len(bad)))
    return 1 if bad else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="+")
    ap.add_argument("-j", "--jobs", type=int, default=2, help="MPI ranks to keep busy at once")
    ap.add_argument("-k", "--match", default="", help="run only tests whose name matches this regex (and the tests they depend on)")
    ap.add_argument("-x", "--exclude", default="", help="leave out tests whose name matches this regex")
    ap.add_argument("--valgrind", action="store_true", help="run the tests tagged memcheck = yes, our executables under valgrind memcheck (tests/valgrind.supp)")
    ap.add_argument("--list", action="store_true", help="print the names of the tests selected, run nothing")
    ap.add_argument("--check", action="store_true", help="check the tree's test files, run nothing: unique names, "
                    "memcheck tags yes or no and closed under depends_on, every dependency found, every file in a group")
    opt = ap.parse_args()
    os.makedirs(OUT, exist_ok=True)
    if opt.valgrind:
        VALGRIND.extend(["valgrind", "-q", "--leak-check=full", "--errors-for-leak-kinds=definite", "--show-leak-kinds=definite",
                         "--error-exitcode=201", "--suppressions=/usr/share/openmpi/openmpi-valgrind.supp",  # not one of PETSc's error codes (66 is PETSC_ERR_FILE_READ)
                         "--suppressions=" + os.path.join(ROOT, "tests", "valgrind.supp")])
    if opt.check:
        sys.exit(check_tree())
    tests = load(ini_files(opt.files))
    known = None
    while any(r not in tests for t in tests.values() for r in t.depends_on):  # a dependency in a file not given
        if known is None:
            known = load(ini_files([TESTS]), set(tests))
        need = {r for t in tests.values() for r in t.depends_on if r not in tests}
        if not need <= set(known):
            break  # reported below
        tests.update({r: known[r] for r in need})
    if opt.valgrind:  # the tests tagged memcheck = yes, which depend on tagged tests only
        for t in tests.values():
            if t.memcheck:
                for r in t.depends_on:
                    if r in tests and not tests[r].memcheck:
                        sys.exit("test %s has memcheck = yes but depends on %s, which has not" % (t.name, r))
        tests = {n: t for n, t in tests.items() if t.memcheck}
    if opt.match:
        want = {n for n in tests if re.search(opt.match, n)}
        grow = True
        while grow:
            need = {r for n in want for r in tests[n].depends_on} - want
            grow = bool(need)
            want |= need
        tests = {n: t for n, t in tests.items() if n in want}
    if opt.exclude:  # and what depends on a left-out test
        tests = {n: t for n, t in tests.items() if not re.search(opt.exclude, n)}
        while any(r not in tests for t in tests.values() for r in t.depends_on):
            tests = {n: t for n, t in tests.items() if all(r in tests for r in t.depends_on)}
    for t in tests.values():
        for r in t.depends_on:
            if r not in tests:
                sys.exit("test %s depends on unknown test %s" % (t.name, r))
    if opt.list:
        for n in tests:
            print(n)
        return

    # run: larger jobs first, never more ranks than --jobs at once; a test runs after the tests it depends on (so a
    # restart can read a checkpoint), which come earlier in this order and are thus already taken by a worker
    pending = sorted(tests.values(), key=lambda t: -t.nsize)
    order_, placed = [], set()
    while pending:
        for t in pending:
            if all(r in placed for r in t.depends_on):
                order_.append(t)
                placed.add(t.name)
                pending.remove(t)
                break
        else:
            sys.exit("circular depends_on among: " + " ".join(t.name for t in pending))
    # a scheduler with a ready list: a test starts as soon as the tests it depends on have finished and the ranks it
    # needs are free, the first such in the order above (a worker never sits waiting for a dependency while a rank is
    # idle, which a pool of workers taking the tests in order did: half the suite's wall time went to such waits)
    t0 = time.time()
    free = [opt.jobs]
    finished = set()
    cv = threading.Condition()
    waiting = list(order_)

    def run(t, need):
        try:
            t.run()
        finally:
            with cv:
                free[0] += need
                finished.add(t.name)
                cv.notify_all()

    def startable():
        for t in waiting:
            if free[0] >= min(t.nsize, opt.jobs) and all(r in finished for r in t.depends_on):
                return t
        return None
    before = set(os.listdir(ROOT))
    threads = []
    with cv:
        while waiting:
            t = startable()
            if t is None:
                cv.wait()
                continue
            need = min(t.nsize, opt.jobs)
            free[0] -= need
            waiting.remove(t)
            th = threading.Thread(target=run, args=(t, need))
            th.start()
            threads.append(th)
    for th in threads:
        th.join()
    passed = failed = 0
    stray = sorted(repr(f) for f in set(os.listdir(ROOT)) - before)
    if stray:  # every test writes under tests/output; anything new at the top of the tree is a bug
        failed += 1
        print("not ok no_stray_files\n    # new files at the top of the tree: " + ", ".join(stray[:10]))
    for name in tests:
        t = tests[name]
        t.evaluate(tests)
        if t.failures:
            failed += 1
            print("not ok %s (np %d, %.1fs)" % (name, t.nsize, t.seconds))
            for f in t.failures:
                print("    # " + f)
            tail = "\n".join(t.output.strip().splitlines()[-15:])
            print("    # output (last lines):\n" + "\n".join("    #   " + l for l in tail.splitlines()))
        else:
            passed += 1
            print("ok %s (np %d, %.1fs)" % (name, t.nsize, t.seconds))
    print("# total %.1f s" % (time.time() - t0))
    print("%d passed, %d failed" % (passed, failed))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
