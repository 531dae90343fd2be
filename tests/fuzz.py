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

usage: fuzz.py [--count N] [--seed S] [--time-limit T] [--jobs J] [--case I] [--only GEN,..] [--verbose] [--keep]
               [-summary_file F]
Output: one line per violation with the command, a count per generator, and "N passed, N failed" (cases).
"""
import argparse
import ctypes
import json
import math
import os
import random
import re
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

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
import sgrun  # noqa: E402

ROOT = sgrun.ROOT
ENV = sgrun.mpi_env(single_copy=False)


def controller_names():
    """The controllers -cont_type accepts: the SGCONT* names of the public header (the library's registry of types)."""
    try:
        with open(os.path.join(ROOT, "include", "signorini.h")) as f:
            names = re.findall(r'^#define\s+SGCONT\w+\s+"(\w+)"', f.read(), re.M)
    except OSError:
        names = []
    return names or ["none", "alm", "pf", "ipf", "fast", "pdas", "vi"]


CONTROLLERS = controller_names()
DEFAULT_KKT_TOL = 1e-10
MEM_LIMIT = 2 << 30  # address space per process: an absurd mesh size fails fast instead of swapping the machine
SENTINEL = b"a file that was here before the run\n"
CRASH = re.compile(r"Caught signal|Segmentation|Signal received|signal number|exited on signal|buffer overflow detected|"
                   r"stack smashing|double free|corrupted|free\(\): invalid|malloc\(\): |Aborted \(core dumped\)")


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


# ---------------------------------------------------------------- value pools

def num(x):
    return x if isinstance(x, str) else "%.6g" % x


def pick_weird_number(rng, orig=None):
    """A number or a non-number for a field that held `orig`."""
    pool = ["0", "-1", "1e308", "-1e308", "1e-320", "nan", "inf", "-inf", "2147483648", "9223372036854775808",
            "abc", "", "1,2,3", "0x10", "1e999", "--", ",", "1,,2", "%d" % rng.randint(-1000, 100000)]
    if orig is not None:
        try:
            v = float(orig)
            pool += [num(v * 10 ** rng.randint(-8, 8)), num(-v), num(v * 1.0001), str(int(v) + rng.choice([-1, 1]))]
        except ValueError:
            pass
    return rng.choice(pool)


def log_uniform(rng, lo, hi):
    return 10 ** rng.uniform(math.log10(lo), math.log10(hi))


# ---------------------------------------------------------------- runs and cases

class Run:
    """One invocation of bin/signorini. args are relative to the repository, except files in the case directory."""

    def __init__(self, args, np_=1, kkt_tol=None, y0_admissible=False, inputs=(), tail=(), checkpoint=None, exe=None):
        self.args, self.np, self.tail = list(args), np_, list(tail)
        self.exe = exe  # another program than bin/signorini (bin/misuse_tests): judged by check_misuse
        self.judge = None  # judge(run, summary) -> [(class, detail)]: the generator's own checks of a run
        self.kkt_tol = kkt_tol
        self.y0_admissible = y0_admissible  # y = 0 is admissible: a solution's energy is <= 0
        self.inputs = list(inputs)  # files of the case directory the run reads
        self.checkpoint = checkpoint  # a -checkpoint_file in the case directory
        self.result = None
        self.must_converge = False  # a well-posed problem: anything but exit 0 is a failure
        self.contact = False  # contact was asked for: an exit 0 without contact has dropped it silently
        self.exact = not any(a in ("-ksp_rtol", "-ksp_type", "-pc_type") or "hypre" in a or "mumps_reuse" in a for a in self.args)


class Case:
    """twin: True for the units twin of gen_options (the same verdict), or a function (case, summaries) ->
    [(class, detail, run)] that compares the runs of the case (a fresh solve against a restart, two controllers)."""

    def __init__(self, gen, index, desc, runs, twin=False):
        self.gen, self.index, self.desc, self.runs, self.twin = gen, index, desc, runs, twin
        self.violations = []  # (class, detail, run)
        self.skipped = False
        self.seconds = 0.0


def output_args(T):
    return ["-output_file", os.path.join(T, "r.h5"), "-summary_file", os.path.join(T, "r.json"),
            "-history_file", os.path.join(T, "r.csv")]


def options_in(args, name, default=None):
    """The last value of option `name` in args, reading -options_file files as PETSc does (later wins)."""
    val = default

    def walk(tokens, depth):
        nonlocal val
        i = 0
        while i < len(tokens):
            t = tokens[i]
            nxt = tokens[i + 1] if i + 1 < len(tokens) else None
            if t == "-options_file" and nxt is not None and depth < 4:
                p = nxt if os.path.isabs(nxt) else os.path.join(ROOT, nxt)
                try:
                    with open(p, errors="replace") as f:
                        for line in f:
                            line = line.split("#", 1)[0].split()
                            if line:
                                walk([line[0], " ".join(line[1:])] if len(line) > 1 else line, depth + 1)
                except OSError:
                    pass
                i += 2
                continue
            if t == name:
                val = nxt if nxt is not None and not (nxt.startswith("-") and nxt[1:2].isalpha()) else ""
            i += 1
    walk(list(args), 0)
    return val


# ---------------------------------------------------------------- generator 1: random option combinations

def gen_options(rng, T, base):
    if rng.random() < 0.06:  # no contact: the elasticity problem alone
        args = ["-options_file", "tests/opts/beam.opts", "-box_faces", "%d,%d" % (rng.randint(4, 24), rng.randint(2, 8))]
        if rng.random() < 0.5:
            args += ["-options_file", "options/solver/hypre.opts", "-ksp_rtol", "%.3g" % log_uniform(rng, 1e-12, 1e-1)]
        if rng.random() < 0.5:
            args += ["-neumann_traction", "%s,%s" % (num(rng.uniform(-10, 10)), num(rng.uniform(-10, 10)))]
        if rng.random() < 0.3:
            args += ["-nu", num(rng.choice([0, 0.25, 0.49999, 0.5, -0.5]))]
        return "options elasticity", [Run(args, 2 if rng.random() < 0.1 else 1, None, True)], False
    args = ["-options_file", "tests/opts/ex1_coarse.opts"]
    faces = "%d,%d" % (rng.randint(4, 24), rng.randint(2, 8))
    if rng.random() < 0.06:
        faces = rng.choice(["0,4", "-3,4", "12", "12,4,7", "abc", "12,4.5", "65536,65536", "100000,100000",
                            "2147483647,2", "1e9,1", "", "3000000000,1"])
    args += ["-box_faces", faces]
    if rng.random() < 0.05:
        args += ["-box_diagonal", rng.choice(["left", "right", "up"])]
    if rng.random() < 0.04:
        args += ["-box_dim", rng.choice(["1", "3", "0", "4", "abc"])]
    ct = rng.choice(CONTROLLERS)
    args += ["-options_file", "options/cont/%s.opts" % ct]
    s = rng.random()
    if s < 0.30:
        args += ["-options_file", "options/solver/hypre.opts", "-ksp_rtol", "%.3g" % log_uniform(rng, 1e-12, 1e-1)]
    elif s < 0.38:
        args += ["-options_file", "options/solver/mumps_reuse.opts"]
    elif s < 0.44:
        args += ["-options_file", "options/solver/mumps_condensed.opts"]
    # loads; E and the loads scaled together by 10^k leave the displacement unchanged
    k = rng.randint(-6, 6) if rng.random() < 0.25 else 0
    y0 = True
    trac = [0.0, -2.0]
    body = None
    r = rng.random()
    if r < 0.35:
        kind = rng.choice(["scale", "zero", "tiny", "huge", "flip", "random"])
        if kind == "scale":
            trac = [0.0, -2.0 * 10 ** rng.uniform(-6, 6)]
        elif kind == "zero":
            trac = [0.0, 0.0]
        elif kind == "tiny":
            trac = [0.0, -rng.choice([1e-300, 1e-30, 1e-12, 1e-6])]
        elif kind == "huge":
            trac = [0.0, -rng.choice([1e12, 1e30, 1e200, 1e300])]
        elif kind == "flip":
            trac = rng.choice([[0.0, 2.0], [2.0, 0.0], [-2.0, 0.0], [2.0, -2.0]])
        else:
            trac = [rng.uniform(-10, 10), rng.uniform(-10, 10)]
    if rng.random() < 0.1:
        body = [rng.uniform(-5, 5), rng.uniform(-5, 5)]
    E = 5000.0
    if k:
        E *= 10 ** k
        trac = [t * 10 ** k for t in trac]
        body = [b * 10 ** k for b in body] if body else None
    weird = []
    if k or trac != [0.0, -2.0]:
        args += ["-E", num(E), "-neumann_traction", ",".join(num(t) for t in trac)]
    if body:
        args += ["-body_force", ",".join(num(b) for b in body)]
    if rng.random() < 0.03:
        weird += ["-body_force", rng.choice(["1,2,3", "1", "nan,0", "abc"])]
    if rng.random() < 0.05:
        weird += ["-E", rng.choice(["0", "-1", "nan", "1e300", "1e-300", "inf"])]
    if rng.random() < 0.25:
        nu = rng.choice([0, rng.uniform(0, 0.5), 0.49, 0.4999, 0.499999, -0.1, 0.5, 0.7, "nan", "inf", "abc", 1e-12])
        args += ["-nu", num(nu)]
    # gamma and controller parameters, extremes included
    gscale = 10 ** k
    extreme = [1e-12, 1e-3, 1, 1e12, 1e16, 1e20, 1e300, 0, -1, "inf", "nan"]
    gammaopt = {"none": "-contact_gamma", "alm": "-alm_gamma", "pf": "-pf_gamma1", "ipf": "-ipf_gamma1"}.get(ct)
    if gammaopt and rng.random() < 0.3:
        g = rng.choice(extreme + [log_uniform(rng, 1, 1e8)] * 4)
        args += [gammaopt, num(g)]
        gscale = 1
    if ct == "none" and rng.random() < 0.15:
        args += ["-contact_lamhat", num(rng.choice([0, 1, 1e-3, 1e6, -1, "nan"]))]
    if ct == "alm" and rng.random() < 0.2:
        args += ["-alm_gamma_factor", num(rng.choice([0.5, 1, 2, 10, 1e6, 0, "nan"]))]
    if ct == "pf" and rng.random() < 0.15:
        args += ["-pf_tau0", num(rng.choice([0, 0.01, 0.5, 0.99, 1, 2, -0.1]))]
    if ct == "ipf" and rng.random() < 0.2:
        opt = rng.choice(["-ipf_tau", "-ipf_tau1", "-ipf_q", "-ipf_tau3"])
        args += [opt, num(rng.choice([0, 1, 1.5, 10, 1e12, -1, "nan", rng.uniform(0.1, 10)]))]
    if ct == "pdas" and rng.random() < 0.15:
        args += [rng.choice(["-pdas_c", "-pdas_max_it"]), num(rng.choice([0, 1, 3, 1e-8, 1e8, -1]))]
    if rng.random() < 0.1:
        args += ["-cont_gamma_max", num(rng.choice([1, 1e3, 1e8, 1e30, 0, -1]))]
    if rng.random() < 0.2:
        args += ["-cont_max_it", str(rng.choice([0, 1, 2, 3, 4, -1]))]
    if rng.random() < 0.05:
        args += ["-cont_stall_it", str(rng.choice([0, 1, 2, -1]))]
    if rng.random() < 0.15:
        args += ["-cont_kkt_tol", num(rng.choice([log_uniform(rng, 1e-14, 1e-4), 1e-16, 1e-2, 0, -1]))]
    if rng.random() < 0.1:
        args += ["-snes_max_it", str(rng.randint(1, 5))]
    # obstacles
    if rng.random() < 0.4:
        o = rng.choice(["plane", "parabola", "ball"])
        args += ["-obstacle_type", o]
        if o == "plane":
            depth = rng.choice([0, 1e-4, 1e-3, 1e-2, 1, 1e3, -1e-3])
            normal = rng.choice([(0, 1), (0, 1), (0.05, 1), (1, 0), (0, -1), (0, 0), (1e-300, 1)])
            args += ["-obstacle_plane_point", "0,%s" % num(-depth), "-obstacle_plane_normal", "%s,%s" % tuple(num(n) for n in normal)]
            y0 = depth >= 0 and normal in [(0, 1), (1e-300, 1)]
        elif o == "parabola":
            a = rng.choice([0, 0.003, rng.uniform(0, 0.1), 10, -0.001])
            off = rng.choice([0, 1e-4, 0.001, 0.01, 1, 1e3, -0.001])
            c = rng.uniform(-1, 4)
            args += ["-obstacle_parabola_a", num(a), "-obstacle_parabola_offset", num(off), "-obstacle_parabola_center", "%s,0" % num(c)]
            y0 = a >= 0 and off >= 0
        else:
            rad = rng.choice([0.5, 2, 1e-3, 0, 100])
            gap = rng.choice([0, 1e-3, 0.1, -1e-3])
            args += ["-obstacle_ball_radius", num(rad), "-obstacle_ball_center", "1.5,%s" % num(-rad - gap), "-obstacle_ball_up", "0,1"]
            y0 = gap >= 0
    tail = []
    if rng.random() < 0.12:
        args += ["-contact_ids", rng.choice(["", "1,2", "2", "3", "4", "7", "1,1", "-1", "abc", "1,3", "1,2,3,4"])]
    elif rng.random() < 0.02:
        tail = ["-contact_ids"]  # a bare option at the end of the command line
    if ct in ("alm", "pf", "ipf") and rng.random() < 0.1:
        args += ["-checkpoint_file", os.path.join(T, "ck.h5")]
    np_ = 2 if rng.random() < 0.08 else 1
    args += weird
    tol = options_in(args, "-cont_kkt_tol", str(DEFAULT_KKT_TOL))
    runs = [Run(args, np_, tol, y0, tail=tail, checkpoint=os.path.join(T, "ck.h5") if "-checkpoint_file" in args else None)]
    runs[0].contact = True
    desc = "options %s" % ct
    twin = False
    dimensional = ("-contact_gamma", "-alm_gamma", "-pf_gamma1", "-ipf_gamma1", "-contact_lamhat", "-pdas_c", "-cont_gamma_max")
    if k and not weird and not tail and not any(a in dimensional for a in args) and rng.random() < 0.5:
        # the same problem in other units: E, loads and the gamma parameters x 10^k; the verdict must not change
        twin = True
        scaled = list(args)
        if gammaopt:
            defaults = {"none": 1e10, "alm": 1e3, "pf": 1e2, "ipf": 1e2}
            scaled += [gammaopt, num(defaults[ct] * gscale)]
        unscaled = [a for a in args]
        # the twin at k = 0: undo the scaling of E and the loads
        def undo(lst, opt, f):
            for i in range(len(lst) - 1):
                if lst[i] == opt:
                    lst[i + 1] = ",".join(num(float(v) / f) for v in lst[i + 1].split(","))
        undo(unscaled, "-E", 10 ** k)
        undo(unscaled, "-neumann_traction", 10 ** k)
        undo(unscaled, "-body_force", 10 ** k)
        runs = [Run(scaled, np_, tol, y0, checkpoint=runs[0].checkpoint), Run(unscaled, np_, tol, y0, checkpoint=runs[0].checkpoint)]
        for r in runs:
            r.contact = True
        desc += " scaled 10^%d" % k
    return desc, runs, twin


# ---------------------------------------------------------------- generator 1b: well-posed problems that must converge

def gen_wellposed(rng, T, base):
    """Example 1 with a random load level, material scale, nu in [0, 0.5) and an obstacle that is touched, barely
    touched or never touched, exact solves: a normal contact problem every controller must solve (issue 10, item 1)."""
    k = rng.randint(-6, 6)
    load = rng.choice([2.0, 0.01, 1e-3, 1e-5, log_uniform(rng, 1e-5, 5)])
    off = rng.choice([0, 1e-4, 0.001, 0.01, 0.1, 1, 1e3])
    a = rng.choice([0.003, 0, rng.uniform(0, 0.02)])
    ct = rng.choice(CONTROLLERS)
    args = ["-options_file", "tests/opts/ex1_coarse.opts", "-box_faces", "%d,%d" % (rng.randint(6, 24), rng.randint(2, 8)),
            "-options_file", "options/cont/%s.opts" % ct]
    if rng.random() < 0.25:
        args += ["-options_file", "options/solver/mumps_reuse.opts"]
    args += ["-E", num(5000 * 10 ** k), "-nu", num(rng.choice([0.4, 0.3, 0.0, rng.uniform(0, 0.49)])),
             "-neumann_traction", "0,%s" % num(-load * 10 ** k), "-obstacle_parabola_a", num(a), "-obstacle_parabola_offset", num(off)]
    if ct == "alm":
        # gamma is dimensional (a pressure per length): it scales with E. With gamma fixed, ALM contracts the multiplier
        # error by 1/(1 + gamma mu) per step (mu ~ h/E), so no step count bounds it: the growing variant is the one
        # that must converge
        args += ["-alm_gamma", num(1e3 * 10 ** k), "-alm_gamma_factor", "10"]
    elif ct == "none":  # one (P_gamma) at none.opts' gamma in units of E: relative to E it is the same problem
        args += ["-contact_gamma", num(1e10 * 10 ** k)]
    run = Run(args, 2 if rng.random() < 0.08 else 1, str(DEFAULT_KKT_TOL), True)
    run.must_converge = run.contact = True
    return "wellposed %s load %.3g offset %g" % (ct, load, off), [run], False


# ---------------------------------------------------------------- generator 2: mutations of a valid options file

OPTION_POOL = [("-contact_ids", ["", "1", "2,1", "abc"]), ("-cont_type", CONTROLLERS + ["", "sqp"]), ("-box_faces", ["12", "0,0", "12,4,7", "-1,4"]),
               ("-nu", ["0", "0.5", "-0.2"]), ("-E", ["0", "1e-300"]), ("-cont_max_it", ["0", "1", "-5"]),
               ("-obstacle_type", ["plane", "ball", "wall", ""]), ("-dirichlet_ids", ["", "7", "1", "2"]),
               ("-neumann_traction", ["0", "0,0,0", "nan,1"]), ("-contact_gamma", ["0", "1e300"]), ("-box_upper", ["0,0", "3", "-3,1"]),
               ("-ssn_condense", ["", "true", "maybe"]), ("-dirichlet_values", ["1,1", "0"]), ("-cont_kkt_tol", ["1e-3", "0"]),
               ("-ksp_type", ["cg", "gmres", "nonsense"]), ("-pc_type", ["none", "jacobi", "lu", "nonsense"])]


def base_options_file(ct):
    lines = []
    for f in ["options/ex1.opts", "options/solver/mumps.opts", "options/cont/%s.opts" % ct]:
        with open(os.path.join(ROOT, f)) as fp:
            for line in fp:
                lines.append("-box_faces 12,4\n" if line.startswith("-box_faces") else line)
    return lines


def mutate_lines(rng, lines, path):
    """1-3 random edits of an options file's lines; returns the new text (bytes) and what was done."""
    done = []
    data = None
    for _ in range(rng.randint(1, 3)):
        what = rng.choice(["drop", "dup", "swap", "number", "number", "value", "truncate", "garbage", "name", "insert",
                           "insert", "comment", "crlf", "self"])
        if what == "self" and rng.random() < 0.6:
            what = "insert"  # including itself is a known crash of PETSc's parser (issue 10, item 8): draw it rarely
        opt_lines = [i for i, l in enumerate(lines) if l.startswith("-")] or [0]
        i = rng.choice(opt_lines) if lines else 0
        if what == "drop" and lines:
            del lines[i]
        elif what == "dup" and lines:
            lines.insert(rng.randrange(len(lines) + 1), lines[i])
        elif what == "swap" and len(lines) > 1:
            j = rng.randrange(len(lines))
            lines[i], lines[j] = lines[j], lines[i]
        elif what == "number" and lines:
            toks = re.split(r"([-+]?\d+\.?\d*(?:[eE][-+]?\d+)?)", lines[i])
            nums = [j for j in range(1, len(toks), 2)]
            if nums:
                j = rng.choice(nums)
                toks[j] = pick_weird_number(rng, toks[j])
                lines[i] = "".join(toks)
        elif what == "value" and lines:
            parts = lines[i].split(None, 1)
            lines[i] = "%s %s\n" % (parts[0], pick_weird_number(rng))
        elif what == "garbage":
            g = rng.choice(["printable", "binary", "long", "value_only"])
            if g == "printable":
                s = "".join(chr(rng.randint(32, 126)) for _ in range(rng.randint(1, 80))) + "\n"
            elif g == "binary":
                s = "".join(chr(rng.randint(0, 255)) for _ in range(rng.randint(1, 80))) + "\n"
            elif g == "long":
                s = "-box_faces " + "1" * rng.randint(300, 20000) + "\n"
            else:
                s = "%s\n" % pick_weird_number(rng)
            lines.insert(rng.randrange(len(lines) + 1), s)
        elif what == "name" and lines:
            l = lines[i]
            j = rng.randrange(1, max(2, l.find(" ") if " " in l else len(l)))
            lines[i] = rng.choice([l[:j] + l[j + 1:], l[:j] + "x" + l[j:], l.lstrip("-"), "--" + l.lstrip("-")])
        elif what == "insert":
            opt, vals = rng.choice(OPTION_POOL)
            lines.insert(rng.randrange(len(lines) + 1), ("%s %s\n" % (opt, rng.choice(vals))).replace(" \n", "\n"))
        elif what == "comment" and lines:
            lines[i] = "# " + lines[i]
        elif what == "crlf":
            lines = [l.replace("\n", "\r\n") for l in lines]
        elif what == "self":
            lines.insert(rng.randrange(len(lines) + 1), "-options_file %s\n" % path)
        elif what == "truncate":
            data = "".join(lines).encode("latin-1")
            data = data[:rng.randrange(len(data) + 1)]
        done.append(what)
    if data is None:
        data = "".join(lines).encode("latin-1", errors="replace")
    return data, done


def gen_optfile(rng, T, base):
    ct = rng.choice(CONTROLLERS)
    path = os.path.join(T, "case.opts")
    data, done = mutate_lines(rng, base_options_file(ct), path)
    with open(path, "wb") as f:
        f.write(data)
    args = ["-options_file", path]
    tol = options_in(args, "-cont_kkt_tol", str(DEFAULT_KKT_TOL))
    run = Run(args, 1, tol, None, inputs=[path])
    run.contact = re.search(rb"^-contact_(ids|label)\b", data, re.M) is not None
    return "optfile %s: %s" % (ct, ",".join(done)), [run], False


# ---------------------------------------------------------------- generator 3: mutations of a gmsh mesh

def mutate_mesh(rng, lines):
    done = []
    data = None
    sec = {}
    for i, l in enumerate(lines):
        if l.startswith("$") and not l.startswith("$End"):
            sec[l.strip()] = i
    nodes = range(sec.get("$Nodes", 0) + 1, len(lines))
    elems = range(sec.get("$Elements", 0) + 1, len(lines))
    for _ in range(rng.randint(1, 3)):
        what = rng.choice(["number", "number", "number", "drop", "dup", "swap", "truncate", "tilt", "format", "names",
                           "node_ref", "garbage"])
        if what == "number":
            i = rng.choice([rng.randrange(len(lines)), rng.choice(nodes), rng.choice(elems)])
            toks = lines[i].split(" ")
            j = rng.randrange(len(toks))
            toks[j] = pick_weird_number(rng, toks[j].strip()) + ("\n" if toks[j].endswith("\n") else "")
            lines[i] = " ".join(toks)
        elif what == "drop":
            del lines[rng.randrange(len(lines))]
        elif what == "dup":
            i = rng.randrange(len(lines))
            lines.insert(i, lines[i])
        elif what == "swap":
            i, j = rng.randrange(len(lines)), rng.randrange(len(lines))
            lines[i], lines[j] = lines[j], lines[i]
        elif what == "truncate":
            data = "".join(lines).encode()
            data = data[:rng.randrange(len(data) + 1)]
        elif what == "tilt":  # the same plane mesh with 3D coordinates z = s x (coordinate lines are "x y z")
            s = rng.choice([0.3, 1.0, 1e-12])
            end = next((i for i, l in enumerate(lines) if l.startswith("$EndNodes")), 0)
            for i in range(sec.get("$Nodes", 0) + 2, end):
                t = lines[i].split()
                if len(t) == 3:
                    try:
                        x = [float(v) for v in t]
                    except ValueError:
                        continue
                    lines[i] = "%.17g %.17g %.17g\n" % (x[0], x[1], s * x[0])
        elif what == "format":
            for i, l in enumerate(lines):
                if l.startswith("$MeshFormat"):
                    lines[i + 1] = rng.choice(["2.2 0 8\n", "4.1 1 8\n", "5 0 8\n", "4.1 0 4\n", "abc\n", "4.1 0 8 extra\n"])
                    break
        elif what == "names":
            for i, l in enumerate(lines):
                if '"clamped"' in l or '"contact"' in l or '"loaded"' in l:
                    if rng.random() < 0.5:
                        lines[i] = rng.choice([l.replace('"clamped"', '"contact"'), l.replace('"', ""), l.replace("1 ", "7 ", 1), ""])
                        break
        elif what == "node_ref":
            i = rng.choice(elems)
            toks = lines[i].split()
            if len(toks) == 4:
                toks[rng.randrange(1, 4)] = rng.choice(["0", "99999", "-1", "404", "1"])
                lines[i] = " ".join(toks) + "\n"
        elif what == "garbage":
            lines.insert(rng.randrange(len(lines)), "".join(chr(rng.randint(0, 255)) for _ in range(rng.randint(1, 60))) + "\n")
        done.append(what)
    if data is None:
        data = "".join(lines).encode("latin-1", errors="replace")
    return data, done


def gen_mesh(rng, T, base):
    path = os.path.join(T, "m.msh")
    with open(os.path.join(ROOT, "meshes", "beam.msh")) as f:
        lines = f.readlines()
    if rng.random() < 0.1:
        data, done = "".join(lines).encode(), ["none"]
    else:
        data, done = mutate_mesh(rng, lines)
    with open(path, "wb") as f:
        f.write(data)
    ct = rng.choice(["ipf", "pdas", "none", "alm", "pf", "elasticity"])
    args = ["-dm_plex_filename", path]
    if ct == "elasticity":  # no contact
        args += ["-dm_plex_gmsh_use_regions", "-neumann_label", "loaded"]
        if rng.random() < 0.8:
            args += ["-dirichlet_label", "clamped"]
        else:
            done.append("no_dirichlet")
    elif rng.random() < 0.2:
        args += ["-dirichlet_ids", "4", "-neumann_ids", "2", "-contact_ids", "1"]
    else:
        args += ["-dm_plex_gmsh_use_regions", "-neumann_label", "loaded", "-contact_label", "contact"]
        if rng.random() < 0.85:
            args += ["-dirichlet_label", "clamped"]
        else:
            done.append("no_dirichlet")  # no Dirichlet part: rigid motions free
    args += ["-neumann_traction", "0,-2", "-E", "5000", "-nu", "0.4", "-options_file", "options/solver/mumps.opts"]
    if ct != "elasticity":
        args += ["-obstacle_type", "parabola", "-options_file", "options/cont/%s.opts" % ct]
    y0 = set(done) <= {"none", "no_dirichlet", "format", "names", "garbage"}  # no vertex moved: y = 0 stays admissible
    run = Run(args, 1, str(DEFAULT_KKT_TOL), y0, inputs=[path])
    run.contact = ct != "elasticity"
    return "mesh %s: %s" % (ct, ",".join(done)), [run], False


# ---------------------------------------------------------------- generator 4: mutations of a checkpoint

CK_RUNS = {"ipf": ["-options_file", "options/cont/ipf.opts"],
           "pf": ["-options_file", "options/cont/pf.opts"],
           "alm": ["-options_file", "options/cont/alm.opts", "-alm_gamma_factor", "10"]}
CK_STEPS = {"ipf": 3, "pf": 2, "alm": 2}
CK_BASE = ["-options_file", "tests/opts/ex1_coarse.opts", "-box_faces", "12,4"]


def make_checkpoints(master):
    """Checkpoints of short alm, pf and ipf runs (stopped by -cont_max_it): the valid files the mutations start from."""
    out = {}
    for ct, extra in CK_RUNS.items():
        ck = os.path.join(master, "ck_%s.h5" % ct)
        cmd = sgrun.command(CK_BASE + extra + ["-cont_max_it", str(CK_STEPS[ct]), "-checkpoint_file", ck], None)
        p = sgrun.execute(cmd, ENV, 120)
        if not os.path.exists(ck):
            sys.exit("fuzz.py: could not make the base checkpoint (%s): exit %d\n%s" % (" ".join(cmd), p.returncode, p.stdout[-2000:]))
        out[ct] = ck
    out["restart"] = make_restart_bases(master)
    return out


def mutate_checkpoint(rng, path):
    what = rng.choice(["truncate", "flip", "flip", "zero_block", "append", "attr", "attr", "attr", "attr_type", "attr_del",
                       "value", "value", "value", "reals", "reals", "resize", "resize", "dtype", "del_dataset", "coords", "group"])
    size = os.path.getsize(path)
    if what in ("truncate", "flip", "zero_block", "append"):
        with open(path, "r+b") as f:
            if what == "truncate":
                f.truncate(rng.randrange(size))
            elif what == "flip":
                for _ in range(rng.randint(1, 20)):
                    o = rng.randrange(size)
                    f.seek(o)
                    b = f.read(1)
                    f.seek(o)
                    f.write(bytes([b[0] ^ (1 << rng.randrange(8))]))
            elif what == "zero_block":
                o = rng.randrange(size)
                f.seek(o)
                f.write(b"\0" * min(4096, size - o))
            else:
                f.seek(0, 2)
                f.write(bytes(rng.randrange(256) for _ in range(rng.randint(1, 5000))))
        return what
    with h5py.File(path, "r+") as f:
        g = f["checkpoint"]
        if what == "attr":
            a = rng.choice(["outer", "ssn_iterations", "ksp_iterations", "best_step", "dim", "vertices", "cont_type"])
            if a == "cont_type":
                v = rng.choice(["", "pdas", "none", "vi", "ipf ", "x" * 500, "alm", "pf", "ipf"])
                g.attrs[a] = np.bytes_(v)
            else:
                o = int(g.attrs[a])
                g.attrs[a] = np.int64(rng.choice([-4, -1, 0, 1, 2 ** 31 - 1, 10 ** 12, -2 ** 40, o + 1, o - 1, o + 100]))
            what += ":%s=%r" % (a, g.attrs[a])
        elif what == "attr_type":
            a = rng.choice(["outer", "dim", "vertices", "cont_type"])
            v = rng.choice([np.float64(2.5), np.bytes_("3"), np.array([1, 2], dtype=np.int64), np.float64("nan")])
            g.attrs[a] = v
            what += ":%s=%r" % (a, v)
        elif what == "attr_del":
            a = rng.choice(list(g.attrs.keys()))
            del g.attrs[a]
            what += ":" + a
        elif what in ("value", "reals", "coords"):
            name = "reals" if what == "reals" else "coordinates" if what == "coords" else rng.choice(
                ["coordinates", "displacement", "lamhat", "gammas", "history", "reals"])
            d = g[name]
            arr = d[...]
            if arr.size == 0:
                return what + ":%s empty" % name
            v = rng.choice([np.nan, np.inf, -np.inf, -1.0, 0.0, 1e300, -1e300, 1e-300])
            if what == "coords":
                if rng.random() < 0.5:
                    arr = arr + 1e-9
                else:
                    i, j = rng.randrange(arr.size), rng.randrange(arr.size)
                    arr[i], arr[j] = arr[j], arr[i]
            elif rng.random() < 0.2:
                arr[:] = v
            else:
                i = 0 if name == "reals" and rng.random() < 0.5 else rng.randrange(arr.size)  # reals[0] is gamma
                arr[i] = v
            d[...] = arr
            what += ":%s" % name
        elif what in ("resize", "dtype", "del_dataset", "group"):
            name = rng.choice(["coordinates", "displacement", "lamhat", "gammas", "history", "reals"])
            arr = g[name][...]
            del g[name]
            if what == "resize":
                n = rng.choice([0, 1, max(arr.size - 1, 0), arr.size + 1, 2 * arr.size])
                g.create_dataset(name, data=np.resize(arr, n) if n else np.zeros(0))
            elif what == "dtype":
                g.create_dataset(name, data=rng.choice([arr.astype(np.int32), arr.astype(np.float32), arr.reshape(-1, 1), np.bytes_("abc")]))
            elif what == "group":
                g.create_group(name)
            what += ":%s" % name
    return what


def gen_checkpoint(rng, T, base):
    ct = rng.choice(sorted(k for k in base if k in CK_RUNS))
    path = os.path.join(T, "ck.h5")
    shutil.copyfile(base[ct], path)
    done = mutate_checkpoint(rng, path) if rng.random() >= 0.1 else "none"
    run_ct = ct if rng.random() < 0.9 else rng.choice(CONTROLLERS)
    extra = CK_RUNS[run_ct] if run_ct in CK_RUNS else ["-options_file", "options/cont/%s.opts" % run_ct]
    args = CK_BASE + extra + ["-restart_file", path]
    if rng.random() < 0.15:
        args += ["-nu", num(rng.choice([0.3, 0.25, 0.45]))]
    if rng.random() < 0.2:
        args += ["-cont_max_it", str(rng.randint(1, 6))]
    if rng.random() < 0.08:
        args[3] = rng.choice(["24,8", "12,5"])  # another mesh
    ck = None
    if rng.random() < 0.1:
        ck = path if rng.random() < 0.5 else os.path.join(T, "ck2.h5")
        args += ["-checkpoint_file", ck]
    np_ = 2 if rng.random() < 0.1 else 1
    run = Run(args, np_, str(DEFAULT_KKT_TOL), True, inputs=[path], checkpoint=ck)
    run.contact = True
    return "checkpoint %s->%s: %s" % (ct, run_ct, done), [run], False


# ---------------------------------------------------------------- physics of a result (issue 25)

EPS = 2.220446049250313e-16


def vec_of(s, key, dim):
    v = s.get(key)
    if isinstance(v, list) and len(v) == dim and all(finite(x) for x in v):
        return [float(x) for x in v]
    return None


def norm(v):
    return math.sqrt(sum(x * x for x in v))


def stiffness(E, nu):
    """lambda + 2 mu of (E, nu), the largest modulus of the material (inf at nu = 0.5)."""
    return E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) if nu < 0.5 else float("inf")


def force_checks(s, applied, dim, E, nu, friction="none", fparam=0.0, fscale=0.0, rtol=1e-5):
    """Physics of a result, not the program's own measures: the Dirichlet reactions balance the contact and friction
    forces and the applied load (reaction_force = contact_force_vector + friction_force_vector - load); the contact
    force vector is no longer than the summed contact force, which is >= 0 and 0 without an active set; the friction
    force within its bound. The balance allows the round-off of the reactions, (lambda + 2 mu) |y|_max eps per cell.
    fscale: a force of the problem (the load, E x displacement): the floor of the force scale, where every force of
    the answer is 0. Keys the summary does not have are not checked."""
    v = []
    R, C = vec_of(s, "reaction_force", dim), vec_of(s, "contact_force_vector", dim)
    Ff = vec_of(s, "friction_force_vector", dim) or [0.0] * dim
    cf = s.get("contact_force")
    cf = float(cf) if finite(cf) else None
    scale = max([fscale, norm(applied), norm(Ff)] + ([norm(R)] if R else []) + ([norm(C)] if C else []) + ([abs(cf)] if cf is not None else []))
    if scale == 0:
        return v
    umax = s.get("displacement_max") if finite(s.get("displacement_max")) else 0.0
    roundoff = 100 * EPS * stiffness(E, nu) * umax * math.sqrt(max(1, s.get("cells") or 1))
    if R and C:
        off = norm([R[d] - (C[d] + Ff[d] - applied[d]) for d in range(dim)])
        if not off <= rtol * scale + roundoff:
            v.append(("b: exit 0 but the forces do not balance",
                      "reaction %s vs contact %s + friction %s - load %s: off by %.3g (%.2g of the force scale %.4g)"
                      % tuple(["[%s]" % ",".join("%.5g" % x for x in w) for w in (R, C, Ff, applied)] + [off, off / scale, scale])))
    if cf is not None:
        if cf < -rtol * scale:
            v.append(("b: exit 0 with a negative contact force", "contact_force %.6g" % cf))
        if C and norm(C) > abs(cf) * (1 + 1e-6) + 1e-6 * scale:
            v.append(("b: contact force vector longer than the contact force", "|contact_force_vector| %.8g > |contact_force| %.8g" % (norm(C), abs(cf))))
        if s.get("active_set_size") == 0 and abs(cf) > rtol * scale:
            v.append(("b: contact force without an active set", "active_set_size 0, contact_force %.6g" % cf))
        bound = fparam * cf if friction == "coulomb" else fparam * (s.get("contact_area") or 0) if friction == "tresca" else None
        if bound is not None and norm(Ff) > bound * (1 + 1e-6) + 1e-6 * scale:
            v.append(("b: friction force beyond its bound", "|friction_force_vector| %.8g > %s bound %.8g" % (norm(Ff), friction, bound)))
    return v


def of_exit0(judge):
    """A judgement of a result: applied to runs that exit 0 with a summary (the rest check_run judges)."""
    return lambda run, s: judge(run, s) if run.result["rc"] == 0 and not run.result["timeout"] and s else []


def cont_args(ct):
    """A controller's options file; alm with a growing gamma (with gamma fixed it needs no bound of steps)."""
    return ["-options_file", "options/cont/%s.opts" % ct] + (["-alm_gamma_factor", "10"] if ct == "alm" else [])


def agree(a, b, what, rtol, floor):
    """Two values of the same problem's answer agree to rtol (relative to the larger) plus an absolute floor."""
    if not (finite(a) and finite(b)) or abs(a - b) <= rtol * max(abs(a), abs(b)) + floor:
        return []
    return ["%s %.10g vs %.10g" % (what, a, b)]


# ---------------------------------------------------------------- generator 5: load paths back to zero (issue 25, item 9)

def gen_unload(rng, T, base):
    """The sliding block (Dirichlet-driven, no loads) along a -load_dirichlet_values path that returns to zero, unloads
    partly, lifts off or starts at zero, frictionless, Coulomb or Tresca, 2D or 3D, every controller. Judged by the
    physics of the last step: back at zero a converged run has y = 0 and no contact force (frictionless; with friction
    when nothing presses); lifted off, a rigid translation (no force, no energy); frictionless, the answer of a fresh
    solve at the last values (path independence, a twin run); always the force balance and the friction bound.
    Sometimes -load_factors that go back (the program accepts only increasing ones: an error that names it)."""
    dim = 3 if rng.random() < 0.2 else 2
    ct = rng.choice(CONTROLLERS)
    fr = rng.choice(["none", "none", "coulomb", "tresca"])
    nu = rng.choice([0.0, 0.3, 0.45, rng.uniform(0, 0.49)])
    E = 1000.0
    if dim == 2:
        args = ["-options_file", "options/sliding_block.opts", "-box_faces", "%d,%d" % (rng.randint(6, 20), rng.randint(3, 10))]
    else:
        args = ["-options_file", "options/sliding_block.opts", "-box_dim", "3", "-box_faces", "%d,%d,%d" % (rng.randint(3, 5), rng.randint(2, 3), rng.randint(2, 3)),
                "-box_lower", "0,0,0", "-box_upper", "1,0.5,0.5", "-dirichlet_ids", "2", "-contact_ids", "1"]
    g = rng.choice([0.5, 2.0, 10.0])
    F = rng.choice([0.1, 0.3, 1.0])
    args += ["-nu", num(nu), "-friction_type", fr] + (["-friction_bound", num(g)] if fr == "tresca" else ["-friction_coefficient", num(F)] if fr == "coulomb" else [])
    args += cont_args(ct)
    p = rng.choice([0.01, 0.001, 1e-5])  # the compression of the top
    tx = rng.choice([0.0, 0.0, 0.2, 1.0, 5.0]) * p  # and its tangential drag (beyond the friction limit from about 0.3 p)

    def value(x, y):  # the top's displacement: x along the first axis, y normal (towards the plane: negative)
        return [x, y] if dim == 2 else [x, 0.0, y]
    kind = rng.choice(["zero", "zero", "zero", "partial", "partial", "lift", "tangential_back", "zero_first", "factors_back"])
    if kind == "zero":
        path = rng.choice([[value(tx, -p), value(0, 0)], [value(tx / 2, -p / 2), value(tx, -p), value(tx / 2, -p / 2), value(0, 0)],
                           [value(tx, -p), value(tx, -2 * p), value(0, 0)]])
    elif kind == "partial":
        f = rng.choice([0.5, 0.1, 0.9, rng.uniform(0, 1)])
        path = [value(tx, -p), value(f * tx, -f * p)]
    elif kind == "lift":
        path = [value(tx, -p), value(rng.choice([0, tx]), rng.choice([0.5, 1, 2]) * p)]
    elif kind == "tangential_back":
        path = [value(tx or p, -p), value(0, -p)]
    elif kind == "zero_first":
        path = rng.choice([[value(0, 0), value(tx, -p)], [value(0, 0), value(tx, -p), value(0, 0)]])
    else:
        path = None
    tol = options_in(args, "-cont_kkt_tol", str(DEFAULT_KKT_TOL))
    if path is None:  # -load_factors that do not increase: refused (an error naming the option) or solved right
        lf = rng.choice(["0.5,1,0", "1,0.5,1", "0.5,0,1", "0,1", "1,0"])
        args += ["-dirichlet_values", ",".join(num(x) for x in value(tx, -p)), "-load_steps", str(lf.count(",") + 1), "-load_factors", lf]
        path = [value(tx * float(t), -p * float(t)) for t in lf.split(",")]
    else:
        args += ["-load_steps", str(len(path)), "-load_dirichlet_values", ",".join(num(x) for v in path for x in v)]
        if dim == 3:  # -dirichlet_values (sliding_block.opts': 2 numbers) is still read
            args[-4:-4] = ["-dirichlet_values", ",".join(num(x) for x in value(tx, -p))]
    last = path[-1]
    peak = max(norm(v) for v in path) or p
    run = Run(args, 2 if rng.random() < 0.06 else 1, tol, False)
    run.contact = True

    def judge_failure(run, s):
        """A step at zero (frictionless or Coulomb: y = 0 solves it) that failed (issue 25, item 9: the displacement
        scale 0, exit 3 on the right answer, DIVERGED_NAN with Coulomb); other failures may be honest."""
        conv = s.get("load_step_converged") if s else None
        if run.result["rc"] == 0 or fr == "tresca" or not isinstance(conv, list) or 0 not in conv or len(conv) > len(path):
            return []
        k = conv.index(0)
        if norm(path[k]) > 0:
            return []
        return [("b: a load step back at zero not solved", "step %d of %d (Dirichlet values 0, friction %s): %s"
                 % (k + 1, len(path), fr, str(s.get("reason"))[:120]))]

    def judge(run, s):
        v = force_checks(s, [0.0] * dim, dim, E, nu, fr, g if fr == "tresca" else F, E * peak)
        fsteps = [x for x in (s.get("load_step_contact_force") or []) if finite(x)]
        fscale = max([abs(x) for x in fsteps] + [E * peak])  # E |u| / height x width: the block's force at peak
        cf, dmax, e = s.get("contact_force"), s.get("displacement_max"), s.get("energy")
        nothing_presses = finite(cf) and abs(cf) <= 1e-6 * fscale
        if norm(last) == 0 and (fr == "none" or nothing_presses):
            if finite(dmax) and dmax > 1e-6 * peak:
                v.append(("b: back at zero but the displacement is not", "displacement_max %.4g after a path to %.4g and back (friction %s)" % (dmax, peak, fr)))
            if finite(cf) and abs(cf) > 1e-6 * fscale:
                v.append(("b: back at zero with a contact force", "contact_force %.4g (force scale %.4g)" % (cf, fscale)))
        if last[-1] > 0 and fr != "tresca":  # the top lifted: the block hangs from it, a rigid translation
            if finite(cf) and abs(cf) > 1e-6 * fscale:
                v.append(("b: lifted off with a contact force", "contact_force %.4g (force scale %.4g)" % (cf, fscale)))
            if finite(e) and abs(e) > 1e-8 * fscale * peak:
                v.append(("b: lifted off with strain energy", "energy %.4g (scale %.4g)" % (e, fscale * peak)))
        return v
    run.judge = lambda run, s: of_exit0(judge)(run, s) + judge_failure(run, s)
    desc = "unload %s %dD friction %s %s: %s" % (ct, dim, fr, kind, " -> ".join("(%s)" % ",".join("%.3g" % x for x in v) for v in path))
    twin = False
    if fr == "none" and norm(last) > 0 and kind != "factors_back" and rng.random() < 0.5:
        # frictionless contact has no history: the path's last step is the fresh solve of its values
        ct2 = rng.choice(["pdas", "ipf", "pf"])
        fresh = [a for a in args]
        i = fresh.index("-load_dirichlet_values")
        fresh[i - 2:i + 2] = ["-dirichlet_values", ",".join(num(x) for x in last)]
        fresh += cont_args(ct2)
        run2 = Run(fresh, 1, tol, False)
        run2.contact = True
        desc += " vs fresh %s" % ct2

        def twin(case, summaries):
            a, b = case.runs
            sa, sb = summaries
            if a.result["rc"] or b.result["rc"] or not sa or not sb:
                return []
            d = agree(sa.get("energy"), sb.get("energy"), "energy", 1e-5, 1e-8 * E * peak * peak)
            d += agree(sa.get("contact_force"), sb.get("contact_force"), "contact_force", 1e-5, 1e-6 * E * peak)
            d += agree(sa.get("displacement_norm"), sb.get("displacement_norm"), "displacement_norm", 1e-5, 1e-6 * peak)
            return [("b: frictionless path's end differs from a fresh solve", "; ".join(d), a)] if d else []
        return desc, [run, run2], twin
    return desc, [run], twin


# ---------------------------------------------------------------- generator 6: nu near 0.5 (issue 25, item 1)

NU_NEAR_HALF = ["0.49", "0.499", "0.4999", "0.49999", "0.4999999", "0.499999999", "0.49999999999", "0.4999999999999",
                "0.499999999999999", "0.4999999999999999"]


def gen_nu(rng, T, base):
    """Near-incompressible material with every controller. Judged by physics, not by the program's verdict: a
    converged run has V <= 0 where y = 0 is admissible (Example 1: no Dirichlet displacement, the obstacle below the
    body), its forces balance (force_checks), and a second controller that also converges finds the same energy and
    contact force; otherwise an error that says why."""
    nu = rng.choice(NU_NEAR_HALF)
    ct = rng.choice(CONTROLLERS)
    kind = rng.choice(["ex1", "ex1", "ex1", "ex1", "ex1_coulomb", "block"])
    if kind.startswith("ex1"):
        nx = rng.choice([12, 24, 30, 45, 60])
        load = rng.choice([2.0, 2.0, 0.5, 20.0])
        E = 5000.0
        args = ["-options_file", "tests/opts/ex1_coarse.opts", "-box_faces", "%d,%d" % (nx, max(2, nx // 3)), "-nu", nu,
                "-neumann_traction", "0,%s" % num(-load)]
        applied = [0.0, -load]  # the traction on the right face (height 1)
        fr, F = ("coulomb", 0.3) if kind == "ex1_coulomb" else ("none", 0.0)
        if fr == "coulomb":
            args += ["-friction_type", "coulomb", "-friction_coefficient", "0.3", "-pc_type", "lu"]
        y0 = True
    else:  # the sliding block, its top moved: y = 0 is not admissible
        nx = rng.choice([10, 16, 20])
        E = 1000.0
        fr, F = rng.choice([("none", 0.0), ("coulomb", 0.3)])
        args = ["-options_file", "options/sliding_block.opts", "-box_faces", "%d,%d" % (nx, nx // 2), "-nu", nu,
                "-friction_type", fr, "-dirichlet_values", rng.choice(["0.002,-0.01", "0,-0.01", "0.05,-0.01"])]
        applied = [0.0, 0.0]
        y0 = False
    args += cont_args(ct)
    tol = options_in(args, "-cont_kkt_tol", str(DEFAULT_KKT_TOL))
    run = Run(args, 1, tol, y0)
    run.contact = True
    fscale = norm(applied) or E * 0.01  # the load, or the block's force at its top's displacement
    run.judge = of_exit0(lambda run, s: force_checks(s, applied, 2, E, float(nu), fr, F, fscale))
    desc = "nu %s %s %s" % (nu, ct, kind)
    if rng.random() < 0.3:
        ct2 = rng.choice([c for c in ("pdas", "ipf", "pf") if c != ct])
        run2 = Run(args + cont_args(ct2), 1, tol, y0)
        run2.contact = True
        run2.judge = run.judge
        desc += " vs %s" % ct2

        def twin(case, summaries):
            a, b = case.runs
            sa, sb = summaries
            if a.result["rc"] or b.result["rc"] or not sa or not sb:
                return []
            fs = max(abs(x) for x in applied + [sa.get("contact_force") or 0, sb.get("contact_force") or 0] if finite(x))
            d = agree(sa.get("energy"), sb.get("energy"), "energy", 1e-5, 0)
            d += agree(sa.get("contact_force"), sb.get("contact_force"), "contact_force", 0, 1e-4 * fs)
            return [("b: two controllers converged to different answers", "%s vs %s: %s" % (sa.get("cont_type"), sb.get("cont_type"), "; ".join(d)), a)] if d else []
        return desc, [run, run2], twin
    return desc, [run], False


# ---------------------------------------------------------------- generator 7: restarts of another problem (issue 25, item 2)

# The problem of the restart checkpoints: every datum nonzero and asymmetric (a traction with both components, a
# Dirichlet displacement, the obstacle's apex off the middle), so that a sign, a direction or a mirror changes it.
RS_PROBLEM = [("-options_file", "tests/opts/ex1_coarse.opts"), ("-box_faces", "12,4"), ("-E", "5000"), ("-nu", "0.4"),
              ("-neumann_traction", "1,-2"), ("-dirichlet_values", "0.0005,0"), ("-obstacle_parabola_a", "0.003"),
              ("-obstacle_parabola_offset", "0.001"), ("-obstacle_parabola_center", "1.25,0")]
RS_VARIANTS = {  # controller and friction, and how the checkpoint run stops: in a step (-cont_max_it) or between steps
    "ipf": ([("-options_file", "options/cont/ipf.opts")], ["-cont_max_it", "3"]),
    "ipf_coulomb": ([("-friction_type", "coulomb"), ("-friction_coefficient", "0.3"), ("-pc_type", "lu"), ("-options_file", "options/cont/ipf.opts")], ["-cont_max_it", "3"]),
    "pf_tresca_steps": ([("-friction_type", "tresca"), ("-friction_bound", "0.5"), ("-pc_type", "lu"), ("-options_file", "options/cont/pf.opts"),
                         ("-load_steps", "2")], ["-load_step_stop", "1"]),
}


def flat(pairs):
    return [x for p in pairs for x in p]


def make_restart_bases(master):
    """For each variant a checkpoint (the run stopped in a step or between load steps) and the summary of the same
    problem solved fresh, to which an unchanged restart must come."""
    def make(name):
        extra, stop = RS_VARIANTS[name]
        args = flat(RS_PROBLEM + extra)
        ck, ref = os.path.join(master, "rs_%s.h5" % name), os.path.join(master, "rs_%s.json" % name)
        cmd = sgrun.command(args + stop + ["-checkpoint_file", ck], None)
        p = sgrun.execute(cmd, ENV, 120)
        if not os.path.exists(ck):
            return "fuzz.py: could not make the restart checkpoint (%s): exit %d\n%s" % (" ".join(cmd), p.returncode, p.stdout[-2000:])
        p = sgrun.execute(sgrun.command(args + ["-summary_file", ref], None), ENV, 120)
        return {"ck": ck, "pairs": RS_PROBLEM + extra, "ref": sgrun.summary(ref) if p.returncode == 0 else None}
    with ThreadPoolExecutor(max_workers=2) as pool:
        out = dict(zip(RS_VARIANTS, pool.map(make, RS_VARIANTS)))
    for v in out.values():
        if isinstance(v, str):
            sys.exit(v)
    return out


def set_opt(pairs, opt, value):
    """pairs with opt's value replaced (added if absent; value None: removed)."""
    out, done = [], False
    for o, v in pairs:
        if o == opt:
            if value is not None and not done:
                out.append((o, value))
            done = True
        else:
            out.append((o, v))
    if not done and value is not None:
        out.append((opt, value))
    return out


def restart_change(rng, name, pairs):
    """One change of the problem's data (a new problem: the restart must be refused), or None."""
    fr = dict(pairs).get("-friction_type", "none")
    kinds = ["traction_sign", "traction_rotated", "traction_turned", "traction_flipped", "dirichlet_sign", "dirichlet_turned",
             "E", "nu", "E_nu_same_mu", "obstacle_mirrored", "obstacle_shifted", "obstacle_same_gap_sum", "obstacle_offset",
             "body_force", "geometry"] + (["friction_coefficient", "friction_type"] if fr == "coulomb" else ["friction_bound", "friction_type"] if fr == "tresca" else ["friction_type"])
    k = rng.choice(kinds)
    if k == "traction_sign":  # (1,-2) -> (-1,-2): the same norm and largest entry
        return k, set_opt(pairs, "-neumann_traction", "-1,-2")
    if k == "traction_rotated":  # by 90 degrees
        return k, set_opt(pairs, "-neumann_traction", rng.choice(["2,1", "-2,-1"]))
    if k == "traction_turned":  # by another angle, the same norm
        a = math.atan2(-2, 1) + rng.choice([-1, 1]) * rng.uniform(0.05, 0.5)
        return k, set_opt(pairs, "-neumann_traction", "%.17g,%.17g" % (math.sqrt(5) * math.cos(a), math.sqrt(5) * math.sin(a)))
    if k == "traction_flipped":
        return k, set_opt(pairs, "-neumann_traction", "-1,2")
    if k == "dirichlet_sign":
        return k, set_opt(pairs, "-dirichlet_values", "-0.0005,0")
    if k == "dirichlet_turned":
        return k, set_opt(pairs, "-dirichlet_values", rng.choice(["0,0.0005", "0,-0.0005"]))
    if k == "E":
        return k, set_opt(pairs, "-E", num(5000 * rng.choice([1.1, 0.5, 1.001])))
    if k == "nu":
        return k, set_opt(pairs, "-nu", rng.choice(["0.3", "0.41", "0.45"]))
    if k == "E_nu_same_mu":  # the shear modulus E / (2 (1 + nu)) kept
        nu2 = rng.choice([0.3, 0.2, 0.45])
        return k, set_opt(set_opt(pairs, "-nu", num(nu2)), "-E", "%.17g" % (5000 / 1.4 * (1 + nu2)))
    if k == "obstacle_mirrored":  # apex at 1.75 instead of 1.25: the mirror image, the same gaps in another order
        return k, set_opt(pairs, "-obstacle_parabola_center", "1.75,0")
    if k == "obstacle_shifted":
        return k, set_opt(pairs, "-obstacle_parabola_center", rng.choice(["1.3,0", "1.5,0", "1.25,0.001"]))
    if k == "obstacle_same_gap_sum":  # a steeper parabola lowered by as much: the gaps at the 13 vertices sum the same
        a2 = rng.choice([0.004, 0.0035])
        m = sum((0.25 * i - 1.25) ** 2 for i in range(13)) / 13
        return k, set_opt(set_opt(pairs, "-obstacle_parabola_a", num(a2)), "-obstacle_parabola_offset", "%.17g" % (0.001 - (a2 - 0.003) * m))
    if k == "obstacle_offset":
        return k, set_opt(pairs, "-obstacle_parabola_offset", rng.choice(["0.002", "0.0005"]))
    if k == "body_force":
        return k, set_opt(pairs, "-body_force", rng.choice(["0,-0.5", "0.1,0"]))
    if k == "geometry":  # the same mesh numbering, other coordinates
        return k, set_opt(pairs, "-box_upper", rng.choice(["3.1,1", "3,0.9"]))
    if k == "friction_coefficient":
        return k, set_opt(pairs, "-friction_coefficient", rng.choice(["0.35", "0.2"]))
    if k == "friction_bound":
        return k, set_opt(pairs, "-friction_bound", rng.choice(["0.6", "0.25"]))
    # another friction law (or none)
    other = rng.choice([f for f in ("none", "tresca", "coulomb") if f != fr])
    pairs = set_opt(pairs, "-friction_type", other)
    if other == "tresca":
        pairs = set_opt(pairs, "-friction_bound", "0.5")
    if other == "coulomb":
        pairs = set_opt(set_opt(pairs, "-friction_coefficient", "0.3"), "-pc_type", "lu")
    return k + ":" + other, pairs


def gen_restart(rng, T, base):
    """A restart (-restart_file) of a checkpoint with the problem's data changed: a sign, a direction of the same
    norm, E and nu with the same shear modulus, the obstacle mirrored or lowered with the same gap sum, the friction
    law: a new problem, which must be refused (a nonzero exit whose message names -restart_file, no result file).
    Or unchanged (the same, spelled otherwise, options in another order, on 2 ranks): accepted, and its answer that of
    the problem solved fresh."""
    name = rng.choice(sorted(base["restart"]))
    b = base["restart"][name]
    path = os.path.join(T, "ck.h5")
    shutil.copyfile(b["ck"], path)
    pairs = list(b["pairs"])
    np_ = 1
    if rng.random() < 0.3:
        k = rng.choice(["same", "same_spelled", "same_reordered", "same_np2"])
        if k == "same_spelled":
            pairs = set_opt(set_opt(set_opt(pairs, "-E", "5e3"), "-neumann_traction", "1.0,-2.00"), "-dirichlet_values", "5e-4,0.0")
        elif k == "same_reordered":
            head = [p for p in pairs if p[0] == "-options_file" and "cont/" not in p[1]]
            rest = [p for p in pairs if p not in head]
            rng.shuffle(rest)  # options_file of the controller stays after the problem's: none of them sets problem data
            pairs = head + rest
        elif k == "same_np2":
            np_ = 2
        changed = False
    else:
        k, pairs = restart_change(rng, name, pairs)
        changed = True
    args = flat(pairs) + ["-restart_file", path]
    tol = options_in(args, "-cont_kkt_tol", str(DEFAULT_KKT_TOL))
    run = Run(args, np_, tol, False, inputs=[path])
    run.contact = True
    ref = b["ref"]
    if not changed and ref:
        run.must_converge = True

    def judge(run, s):
        rc, out = run.result["rc"], run.result["out"]
        if changed:
            if rc == 0:
                return [("b: restart of another problem accepted", "%s: exit 0, energy %r, contact_force %r (the checkpoint's problem, fresh: %r, %r)"
                         % (k, s.get("energy") if s else None, s.get("contact_force") if s else None, (ref or {}).get("energy"), (ref or {}).get("contact_force")))]
            if 0 < rc < 128 and not re.search(r"-restart_file|restart", error_message(out), re.I):
                last = [l for l in error_message(out).splitlines() if l.strip()]
                return [("c: a refused restart does not name -restart_file", "%s: exit %d: %s" % (k, rc, " / ".join(last[:2])[:150]))]
            return []
        if rc == 0 and s and ref:
            d = agree(s.get("energy"), ref.get("energy"), "energy", 1e-6, 0)
            d += agree(s.get("contact_force"), ref.get("contact_force"), "contact_force", 1e-5, 0)
            if d:
                return [("b: an unchanged restart differs from the fresh solve", "%s: %s" % (k, "; ".join(d)))]
        return []
    run.judge = judge
    return "restart %s %s %s" % (name, "changed" if changed else "unchanged", k), [run], False


# ---------------------------------------------------------------- generator 8: library misuse (issue 25, item 12)

MISUSE = os.path.join(ROOT, "bin", "misuse_tests")
MISUSE_GROUPS = []
MISUSE_LOCK = threading.Lock()


def misuse_groups():
    """The groups of wrong calls bin/misuse_tests knows (-case NAME): the list its error message for an unknown name
    gives, '(problem, cont, ...)'. Empty if the program is not built (it is not in every tree)."""
    with MISUSE_LOCK:
        if MISUSE_GROUPS or not os.access(MISUSE, os.X_OK):
            return list(MISUSE_GROUPS)
        try:
            p = sgrun.execute([MISUSE, "-case", "no_such_group_of_the_fuzz_test"], ENV, 60)
            m = re.search(r"no such group \(([^)]*)\)", p.stdout)
            MISUSE_GROUPS.extend(g.strip() for g in (m.group(1).split(",") if m else []) if re.match(r"^\w+$", g.strip()))
        except (OSError, subprocess.SubprocessError):
            pass
        return list(MISUSE_GROUPS)


def gen_misuse(rng, T, base):
    """bin/misuse_tests -case GROUP (tests/misuse.c): the library's public functions called wrongly (NULL handles and
    pointers, a DMDA for a DMPlex, calls out of order, a problem destroyed before its controller). The program catches
    each error itself and exits 0 when every wrong call returned an error and every right call around them worked.
    Judged by check_misuse: no signal, no hang, exit 0, no 'not ok' line. Skipped where the program is not built."""
    if not os.access(MISUSE, os.X_OK):
        return "misuse: skipped (bin/misuse_tests is not built)", [], False
    g = rng.choice(misuse_groups() + [""])  # "": all groups in one process (also where the names cannot be read)
    args = (["-case", g] if g else []) + (["-malloc_debug"] if rng.random() < 0.5 else [])
    run = Run(args, 1, exe=MISUSE)
    return "misuse %s" % (g or "all"), [run], False


def check_misuse(run, T, before):
    res = run.result
    rc, out = res["rc"], res["out"]
    v = []
    if res["timeout"]:
        v.append(("a: hang", "no exit after %g s (killed)" % res["limit"]))
    elif rc < 0 or rc >= 128 or CRASH.search(out):
        m = CRASH.search(out)
        v.append(("a: crash", "exit %d%s" % (rc, ", '%s'" % m.group(0) if m else "")))
    else:
        bad = [l for l in out.splitlines() if l.startswith("not ok")]
        if rc != 0 or bad:
            msg = bad or [l for l in error_message(out).splitlines() if l.strip()]
            v.append(("e: a wrong call of the library misbehaved", "exit %d: %s" % (rc, " / ".join(msg[:2])[:200] or "(no message)")))
        elif not re.search(r"^[1-9]\d* cases, 0 misbehaved", out, re.M):
            v.append(("e: misuse run without its tally", "exit 0 but no 'N cases, 0 misbehaved' line"))
    now = {os.path.join(dp, f) for dp, dn, fn in os.walk(T) for f in fn}
    extra = sorted(now - set(before))
    if extra:
        v.append(("d: unexpected file written", " ".join(os.path.relpath(p, T) for p in extra)[:160]))
    return v, None


# weights: the issue-25 kinds (unload, nu, restart, misuse) about 12, 14, 12 and 6 of the 200 cases of make test
GENERATORS = [("options", gen_options, 0.28), ("wellposed", gen_wellposed, 0.08), ("optfile", gen_optfile, 0.16), ("mesh", gen_mesh, 0.16),
              ("checkpoint", gen_checkpoint, 0.10), ("unload", gen_unload, 0.06), ("nu", gen_nu, 0.07), ("restart", gen_restart, 0.06),
              ("misuse", gen_misuse, 0.03)]


def pick_generator(rng):
    r, acc = rng.random(), 0.0
    for name, fn, w in GENERATORS:
        acc += w
        if r < acc:
            break
    return name, fn


def generator_of(seed, index):
    """The generator of case `index` (without drawing the case: for --only)."""
    return pick_generator(random.Random("fuzz:%d:%d" % (seed, index)))[0]


def draw_case(seed, index, T, base):
    rng = random.Random("fuzz:%d:%d" % (seed, index))
    name, fn = pick_generator(rng)
    desc, runs, twin = fn(rng, T, base)
    case = Case(name, index, desc, runs, twin)
    case.skipped = not runs  # a kind this tree cannot run (bin/misuse_tests not built)
    return case


# ---------------------------------------------------------------- running and checking

def shown(run, T):
    """The command as a user would type it in the repository, the case directory written $T."""
    if run.exe:
        cmd = sgrun.command(run.args, run.np if run.np > 1 else None, os.path.relpath(run.exe, ROOT))
    else:
        cmd = sgrun.command(run.args + output_args(T) + run.tail, run.np if run.np > 1 else None, "bin/signorini")
    return " ".join(shlex.quote(a).replace(T, "$T") if T in a else shlex.quote(a) for a in cmd)


def valid_result(path):
    """None if path is a readable result file of its kind, else the reason (a read error's text cut at 80 characters)."""
    return sgrun.result_problem(path, width=80)


def error_message(out):
    """What the run said about the failure: PETSc's error message lines (without the unused-option list, the option
    table and the traceback) and the program's own lines; HDF5's and MPI's diagnostics left out."""
    msg, state = [], {}  # per rank: the ranks' lines interleave
    for l in out.splitlines():
        m = re.match(r"\[(\d+)\]PETSC ERROR: ?(.*)", l)
        if m:
            rank, body = m.group(1), m.group(2)
            if "---- Error Message ----" in body:
                state[rank] = "msg"
            elif "for trouble shooting" in body or body.startswith("PETSc Option Table") or "End of Error Message" in body:
                state[rank] = "tail"
            elif state.get(rank) == "msg" and not body.startswith("Option left:") and not body.startswith("WARNING! There are option"):
                msg.append(body)
            continue
        if re.match(r"^HDF5-DIAG|^\s+#\d+:|^\s+(major|minor):|^-{20,}|^MPI_ABORT|^with errorcode|^NOTE: invoking|^You may or may not|^exactly when|^\s*$", l):
            continue
        msg.append(l)
    return "\n".join(msg)


# not options of the run: numbers, and the debugging hints PETSc adds to some messages
NOT_OPTIONS = {"nan", "inf", "infinity", "malloc_dump", "malloc_view", "malloc_debug", "malloc_test", "start_in_debugger",
               "on_error_attach_debugger", "no_signal_handler", "log_view", "info", "help", "options_left", "fp_trap"}


def verdict_first(msg):
    """The lines of a message, the verdict (FAILED, DIVERGED, an error) first: for the report of a failure."""
    lines = [l for l in msg.splitlines() if l.strip()]
    return [l for l in lines if re.search(r"FAILED|DIVERGED|rror", l)] + [l for l in lines if not re.search(r"FAILED|DIVERGED|rror", l)]


def names_option_or_file(msg, files):
    for m in re.finditer(r"(?<![\w.\-/])-([A-Za-z][A-Za-z0-9_]*)", msg):
        if m.group(1).lower() not in NOT_OPTIONS:
            return True
    return any(f and f in msg for f in files)


def finite(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


def check_run(case, run, T, before):
    res = run.result
    v = []
    rc, out = res["rc"], res["out"]
    # (a) crash or hang
    if res["timeout"]:
        v.append(("a: hang", "no exit after %g s (killed)" % res["limit"]))
    elif rc < 0 or rc in (134, 139, 59) or CRASH.search(out):
        m = CRASH.search(out)
        v.append(("a: crash", "exit %d%s" % (rc, ", '%s'" % m.group(0) if m else "")))
    s = None
    sp = os.path.join(T, "r.json")
    if os.path.exists(sp) and open(sp, "rb").read() != SENTINEL:
        try:
            with open(sp) as f:
                s = json.load(f)
        except ValueError as e:
            v.append(("d: broken summary", "-summary_file is not valid JSON: %s" % e))
    # (b) exit 0 only for a converged solve that meets its tolerance
    if rc == 0 and not res["timeout"]:
        if s is None:
            v.append(("b: exit 0 without summary", "no JSON summary written"))
        else:
            if s.get("converged") is not True:
                v.append(("b: exit 0 but not converged", "summary converged = %r" % s.get("converged")))
            if "problem" in s:
                prob, r, tol = s.get("problem"), s.get("residual"), s.get("residual_tol")
                if prob not in ("P", "P_gamma", "elasticity"):
                    v.append(("b: unknown problem", "summary problem = %r" % prob))
                elif prob != "elasticity" and not (finite(r) and finite(tol) and r <= tol):
                    v.append(("b: exit 0 with residual above its tolerance", "problem %s: residual %r > residual_tol %r" % (prob, r, tol)))
                if prob == "P" and r != s.get("kkt_residual"):
                    v.append(("b: residual of P is not the KKT residual", "residual %r, kkt_residual %r" % (r, s.get("kkt_residual"))))
            elif "kkt_residual" in s:
                try:
                    tol = float(run.kkt_tol)
                except (TypeError, ValueError):
                    tol = DEFAULT_KKT_TOL
                r = s["kkt_residual"]
                if not (finite(r) and r <= tol):
                    v.append(("b: exit 0 with KKT residual above -cont_kkt_tol", "%s: kkt_residual %r > -cont_kkt_tol %g (%s)" % (s.get("cont_type"), r, tol, str(s.get("reason"))[:60])))
            if run.contact and "kkt_residual" not in s and s.get("problem") in (None, "elasticity"):
                v.append(("b: exit 0 with contact silently dropped", "the run asked for contact, the summary has none (%s)" % s.get("reason")))
            bad = [k for k in ("energy", "kkt_residual", "displacement_norm", "residual") if k in s and not finite(s[k])]
            bad += [k for k in ("outer_iterations", "ssn_iterations", "ksp_iterations") if k in s and not (finite(s[k]) and s[k] >= 0)]
            if s.get("cont_type") in ("none", "alm", "pf", "ipf"):  # pdas and vi have no gamma (null)
                bad += ["gammas"] if any(not (finite(g) and g > 0) for g in s.get("gammas", [])) else []
            if bad:
                v.append(("b: exit 0 with nonsense in the summary", ", ".join("%s = %r" % (k, s.get(k)) for k in bad)[:160]))
            e, eu = s.get("energy"), s.get("energy_unconstrained")
            if run.y0_admissible and finite(e):
                scale = abs(eu) if finite(eu) else abs(e)
                if e > 1e-8 * scale + 1e-300:
                    v.append(("b: exit 0 with positive energy (y = 0 is admissible)", "energy %.4g, unconstrained %r" % (e, eu)))
                elif finite(eu) and run.exact and e < eu - 1e-8 * abs(eu) - 1e-300:  # an inexact unconstrained solve is no bound
                    v.append(("b: exit 0 with energy below the unconstrained minimum", "energy %.10g < %.10g" % (e, eu)))
    if run.must_converge and rc != 0 and not v:
        last = verdict_first(error_message(out))
        v.append(("b: a well-posed problem not solved", "exit %d: %s" % (rc, " / ".join(last[:2])[:150])))
    # (c) a failure names an option or a file
    if rc != 0 and not v:  # a crash or a hang is reported as such
        files = run.inputs + [a for a in run.args if "/" in a or a.endswith((".h5", ".opts", ".msh"))]
        if not names_option_or_file(error_message(out), files):
            last = verdict_first(error_message(out))
            v.append(("c: failure names no option or file", "exit %d: %s" % (rc, (" / ".join(last[:2]) if last else "(no message)")[:150])))
    # (d) files
    now = set()
    for dp, dn, fn in os.walk(T):
        for f in fn:
            now.add(os.path.join(dp, f))
    parts = sorted(p for p in now if p.endswith(".part"))
    if parts:
        v.append(("d: .part file left", " ".join(os.path.basename(p) for p in parts)))
    for name in ("r.h5", "r.xmf"):
        p = os.path.join(T, name)
        if rc != 0 or res["timeout"]:
            if before.get(p) is None and os.path.exists(p):
                v.append(("d: result file left after a failure", name))
            elif before.get(p) is not None and (not os.path.exists(p) or open(p, "rb").read() != before[p]):
                why = valid_result(p) if os.path.exists(p) else "removed"
                if why:
                    v.append(("d: earlier file replaced by a broken one", "%s: %s" % (name, why)))
        else:
            why = valid_result(p) if os.path.exists(p) else "missing"
            if why:
                v.append(("d: exit 0 with a broken result file", "%s: %s" % (name, why)))
    for p in [os.path.join(T, "r.csv"), run.checkpoint]:
        if p and os.path.exists(p) and open(p, "rb").read() != before.get(p):
            why = valid_result(p)
            if why:
                v.append(("d: broken file at a result path", "%s: %s" % (os.path.basename(p), why)))
    expected = set(before) | {os.path.join(T, n) for n in ("r.h5", "r.xmf", "r.json", "r.csv")} | ({run.checkpoint} if run.checkpoint else set())
    # MPI-IO's lock probe beside an HDF5 file, left when a rank is aborted inside the open: the MPI library's file
    extra = sorted(p for p in now - expected if not p.endswith(".part") and ".locktest." not in p)
    if extra:
        v.append(("d: unexpected file written", " ".join(os.path.relpath(p, T) for p in extra)[:160]))
    return v, s


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


def snapshot(T):
    snap = {}
    for dp, dn, fn in os.walk(T):
        for f in fn:
            p = os.path.join(dp, f)
            with open(p, "rb") as fp:
                snap[p] = fp.read()
    return snap


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


PETSC_ERR = "[0]PETSC ERROR: --------------------- Error Message ----------\n[0]PETSC ERROR: Missing or incorrect user input\n[0]PETSC ERROR: %s\n" \
            "[0]PETSC ERROR: Option left: name:-box_faces value: 12,4\n[0]PETSC ERROR: See https://petsc.org/release/faq/\n" \
            "[0]PETSC ERROR: PETSc Option Table entries:\n[0]PETSC ERROR: -nu 0.7\n"
GOOD = {"cont_type": "ipf", "converged": True, "kkt_residual": 1e-11, "energy": -1.0, "energy_unconstrained": -2.0,
        "outer_iterations": 3, "ssn_iterations": 4, "gammas": [1e2, 1e4, 1e6]}


def self_test():
    """Each check must be able to fail: synthetic runs, each with one known fault, and clean ones that must pass."""
    cases = [  # (expected class prefix or None, rc, output, summary, files written {name: bytes}, before {name: bytes}, timeout)
        (None, 0, "ipf: CONVERGED.", GOOD, {"r.h5": "h5", "r.xmf": "xmf"}, {}, False),
        (None, 95, PETSC_ERR % "-nu: Poisson's ratio must lie in [0, 0.5), got 0.7", None, {}, {}, False),
        (None, 66, PETSC_ERR % "cannot read mesh file '$T/m.msh'", None, {}, {}, False),
        (None, 3, "ipf: FAILED. MAX_IT: 2 outer steps (-cont_max_it)", dict(GOOD, converged=False), {}, {"r.h5": SENTINEL}, False),
        (None, 0, "ipf: CONVERGED.", dict(GOOD, problem="P_gamma", residual=1e-3, residual_tol=1e-2, kkt_residual=0.5), {"r.h5": "h5", "r.xmf": "xmf"}, {}, False),
        ("a: crash", -11, "", None, {}, {}, False),
        ("a: crash", 59, PETSC_ERR % "Caught signal number 11 SEGV", None, {}, {}, False),
        ("a: hang", -9, "", None, {}, {}, True),
        ("b: exit 0 but not converged", 0, "", dict(GOOD, converged=False), {"r.h5": "h5", "r.xmf": "xmf"}, {}, False),
        ("b: exit 0 without summary", 0, "", None, {"r.h5": "h5", "r.xmf": "xmf"}, {}, False),
        ("b: exit 0 with KKT residual above", 0, "", dict(GOOD, kkt_residual=0.68), {"r.h5": "h5", "r.xmf": "xmf"}, {}, False),
        ("b: exit 0 with residual above its tolerance", 0, "", dict(GOOD, problem="P_gamma", residual=2.6e-4, residual_tol=1e-12), {"r.h5": "h5", "r.xmf": "xmf"}, {}, False),
        ("b: residual of P is not the KKT residual", 0, "", dict(GOOD, problem="P", residual=1e-12, residual_tol=1e-10), {"r.h5": "h5", "r.xmf": "xmf"}, {}, False),
        ("b: exit 0 with nonsense", 0, "", dict(GOOD, outer_iterations=-4), {"r.h5": "h5", "r.xmf": "xmf"}, {}, False),
        ("b: exit 0 with positive energy", 0, "", dict(GOOD, energy=3.9e15, energy_unconstrained=3.9e15), {"r.h5": "h5", "r.xmf": "xmf"}, {}, False),
        ("b: exit 0 with contact silently dropped", 0, "", {"converged": True, "energy": -1.0, "reason": "LINEAR_SOLVE"}, {"r.h5": "h5", "r.xmf": "xmf"}, {}, False),
        ("c: failure names no option", 63, PETSC_ERR % "Input string abc has no numeric value", None, {}, {}, False),
        ("c: failure names no option", 3, "ipf: FAILED. STALLED: no progress for 10 outer steps", dict(GOOD, converged=False), {}, {}, False),
        ("d: .part file left", 3, "-cont_max_it", dict(GOOD, converged=False), {"r.h5.part": b"x"}, {}, False),
        ("d: result file left after a failure", 3, "-cont_max_it", dict(GOOD, converged=False), {"r.h5": "h5"}, {}, False),
        ("d: earlier file replaced by a broken one", 3, "-cont_max_it", dict(GOOD, converged=False), {"r.h5": b"half"}, {"r.h5": SENTINEL}, False),
        ("d: exit 0 with a broken result file", 0, "", GOOD, {"r.h5": b"half", "r.xmf": "xmf"}, {}, False),
        ("d: unexpected file written", 0, "", GOOD, {"r.h5": "h5", "r.xmf": "xmf", "stray.txt": b"x"}, {}, False),
    ]
    bad = 0
    for want, rc, out, summ, written, pre, timeout in cases:
        T = tempfile.mkdtemp(prefix="fuzz-self-")
        try:
            for n, data in pre.items():
                with open(os.path.join(T, n), "wb") as f:
                    f.write(data)
            before = snapshot(T)
            for n, data in written.items():
                p = os.path.join(T, n)
                if data == "h5":
                    with h5py.File(p, "w") as f:
                        f.create_group("vertex_fields")
                        f.create_group("cell_fields")
                elif data == "xmf":
                    with open(p, "w") as f:
                        f.write("<Xdmf/>\n")
                else:
                    with open(p, "wb") as f:
                        f.write(data)
            if summ is not None:
                with open(os.path.join(T, "r.json"), "w") as f:
                    json.dump(summ, f)
            run = Run(["-dm_plex_filename", os.path.join(T, "m.msh")], kkt_tol="1e-10", y0_admissible=True, inputs=[os.path.join(T, "m.msh")])
            run.contact = True
            run.result = {"rc": rc, "out": out.replace("$T", T), "timeout": timeout, "limit": 30, "seconds": 0}
            got = [c for c, d in check_run(None, run, T, before)[0]]
        finally:
            shutil.rmtree(T, ignore_errors=True)
        ok = (not got) if want is None else any(c.startswith(want) for c in got)
        bad += not ok
        print("%s self-test %s: found %s" % ("ok" if ok else "not ok", want or "clean run", got or "nothing"))
    jbad, jn = judge_self_test()
    bad += jbad
    print("%d passed, %d failed" % (len(cases) + jn - bad, bad))
    return bad


def judge_self_test():
    """The judgements of the issue-25 generators on synthetic results: each fault found, each right result passed."""
    T = tempfile.mkdtemp(prefix="fuzz-self-")
    base = {"restart": {}}
    for name, (extra, stop) in RS_VARIANTS.items():
        ck = os.path.join(T, "rs_%s.h5" % name)
        open(ck, "wb").close()
        base["restart"][name] = {"ck": ck, "pairs": RS_PROBLEM + extra, "ref": {"energy": -0.013, "contact_force": 2.66}}

    def find(gen, pred):  # a case of the generator whose description matches
        for i in range(5000):
            desc, runs, twin = gen(random.Random("selftest:%d" % i), T, base)
            if pred(desc, runs):
                return runs, twin
        raise RuntimeError("self-test: no case of %s found" % gen.__name__)

    def judged(run, rc, s, out=""):
        run.result = {"rc": rc, "out": out, "timeout": False, "limit": 30, "seconds": 0}
        return [c for c, d in run.judge(run, s)]

    def fc(*a):  # the classes force_checks finds
        return [c for c, d in force_checks(*a)]

    refused = PETSC_ERR % "-restart_file: 'ck.h5' was written for another problem: E differs"
    # Example 1's answers (nu 0.4): balanced; fast at nu = 0.4999999 (issue 25, item 1); nu = 1 - 1e-16
    good = {"reaction_force": [2.3e-12, -0.6483], "contact_force_vector": [0, -2.6483], "contact_force": 2.6483, "active_set_size": 14,
            "displacement_max": 0.007, "cells": 2400}
    fast = {"reaction_force": [-2.5e-7, 0.9803], "contact_force_vector": [0, -3.438], "contact_force": 1.0197, "active_set_size": 12,
            "displacement_max": 0.007, "cells": 2400}
    nocontact = {"reaction_force": [-0.383, 0.4068], "contact_force_vector": [0, 0], "contact_force": 0.8874, "active_set_size": 0,
                 "displacement_max": 0.007, "cells": 2400}
    block = {"reaction_force": [7.152, -23.84], "contact_force_vector": [0, -23.84], "friction_force_vector": [7.152, 0],
             "contact_force": 23.84, "contact_area": 1.0, "active_set_size": 10, "displacement_max": 0.05, "cells": 100}
    tests = [("force balance: Example 1", fc(good, [0, -2], 2, 5000, 0.4), None),
             ("force balance: fast at nu 0.4999999", fc(fast, [0, -2], 2, 5000, 0.4999999), "b: exit 0 but the forces do not balance"),
             ("force vector vs force: fast", fc(fast, [0, -2], 2, 5000, 0.4999999), "b: contact force vector longer"),
             ("force without active set", fc(nocontact, [0, -2], 2, 5000, 0.4), "b: contact force without an active set"),
             ("negative contact force", fc(dict(good, contact_force=-0.3), [0, -2], 2, 5000, 0.4), "b: exit 0 with a negative contact force"),
             ("Coulomb block at its bound", fc(block, [0, 0], 2, 1000, 0.3, "coulomb", 0.3), None),
             ("Coulomb beyond its bound", fc(block, [0, 0], 2, 1000, 0.3, "coulomb", 0.2), "b: friction force beyond its bound"),
             ("Tresca beyond its bound", fc(block, [0, 0], 2, 1000, 0.3, "tresca", 5.0), "b: friction force beyond its bound"),
             ("round-off of the reactions allowed at nu = 1 - 1e-10",
              fc(dict(good, reaction_force=[0, -0.6493]), [0, -2], 2, 5000, 0.49999999995), None),
             ("the same imbalance at nu = 0.4", fc(dict(good, reaction_force=[0, -0.6493]), [0, -2], 2, 5000, 0.4), "b: exit 0 but the forces do not balance")]
    runs, twin = find(gen_unload, lambda d, r: " friction none zero:" in d and " 2D " in d)
    zero = {"converged": True, "displacement_max": 0.0, "contact_force": 0.0, "energy": 0.0, "reaction_force": [0, 0],
            "contact_force_vector": [0, 0], "active_set_size": 0, "cells": 100, "load_step_contact_force": [23.8, 0]}
    tests += [("unload to zero: y = 0", judged(runs[0], 0, zero), None),
              ("unload to zero: y left over", judged(runs[0], 0, dict(zero, displacement_max=1e-3)), "b: back at zero but the displacement"),
              ("unload to zero: a force left over", judged(runs[0], 0, dict(zero, contact_force=1.0, active_set_size=3, contact_force_vector=[0, -1.0], reaction_force=[0, -1.0])), "b: back at zero with a contact force"),
              ("unload to zero: failure judged by check_run only", judged(runs[0], 3, dict(zero, displacement_max=1.0)), None)]
    n = int(runs[0].args[runs[0].args.index("-load_steps") + 1])
    tests += [("unload: the step at zero failed", judged(runs[0], 3, {"load_step_converged": [1] * (n - 1) + [0], "reason": "GAMMA_OVERFLOW"}),
               "b: a load step back at zero not solved"),
              ("unload: the first (loaded) step failed", judged(runs[0], 3, {"load_step_converged": [0], "reason": "GAMMA_OVERFLOW"}), None)]
    runs, twin = find(gen_unload, lambda d, r: " friction none lift:" in d)
    tests += [("lift off: rigid translation", judged(runs[0], 0, dict(zero, displacement_max=0.01)), None),
              ("lift off with strain energy", judged(runs[0], 0, dict(zero, energy=0.05)), "b: lifted off with strain energy")]
    runs, twin = find(gen_unload, lambda d, r: " friction none partial:" in d and len(r) == 2)
    for r in runs:
        r.result = {"rc": 0}
    a = {"energy": 0.03, "contact_force": 11.6, "displacement_norm": 0.05}
    tests += [("path end = fresh solve", [c for c, d, r in twin(type("C", (), {"runs": runs}), [a, dict(a)])], None),
              ("path end != fresh solve", [c for c, d, r in twin(type("C", (), {"runs": runs}), [a, dict(a, energy=0.0302)])], "b: frictionless path's end differs")]
    runs, twin = find(gen_nu, lambda d, r: len(r) == 2)
    for r in runs:
        r.result = {"rc": 0}
    a = {"energy": -0.00354368, "contact_force": 1.1423, "cont_type": "pdas"}
    tests += [("two controllers agree", [c for c, d, r in twin(type("C", (), {"runs": runs}), [a, dict(a)])], None),
              ("fast 8 % off pdas", [c for c, d, r in twin(type("C", (), {"runs": runs}), [a, dict(a, energy=-0.00325188, contact_force=1.0197)])], "b: two controllers converged to different")]
    runs, twin = find(gen_restart, lambda d, r: " changed " in d)
    tests += [("changed restart refused", judged(runs[0], 95, None, refused), None),
              ("changed restart accepted", judged(runs[0], 0, {"energy": -0.012, "contact_force": 2.6}), "b: restart of another problem accepted"),
              ("changed restart refused without naming it", judged(runs[0], 95, None, PETSC_ERR % "E differs"), "c: a refused restart does not name")]
    runs, twin = find(gen_restart, lambda d, r: " unchanged same" in d)
    tests += [("unchanged restart = fresh", judged(runs[0], 0, {"energy": -0.013, "contact_force": 2.66}), None),
              ("unchanged restart != fresh", judged(runs[0], 0, {"energy": -0.0121, "contact_force": 2.66}), "b: an unchanged restart differs")]
    mrun = Run(["-case", "problem"], exe=MISUSE)
    for label, rc, out, want in [("misuse caught", 0, "ok SgProblemCreate(comm, NULL): error 85\n7 cases, 0 misbehaved\n", None),
                                 ("misuse: a wrong call accepted", 1, "not ok SgContSolve(NULL): error 0\n7 cases, 1 misbehaved\n", "e: a wrong call"),
                                 ("misuse: segfault", -11, "", "a: crash"),
                                 ("misuse: PETSc's signal handler", 59, PETSC_ERR % "Caught signal number 11 SEGV", "a: crash"),
                                 ("misuse: no tally", 0, "", "e: misuse run without its tally")]:
        mrun.result = {"rc": rc, "out": out, "timeout": False, "limit": 30, "seconds": 0}
        tests.append((label, [c for c, d in check_misuse(mrun, T, snapshot(T))[0]], want))
    shutil.rmtree(T, ignore_errors=True)
    bad = 0
    for label, got, want in tests:
        ok = (not got) if want is None else any(c.startswith(want) for c in got)
        bad += not ok
        print("%s self-test %s (%s): found %s" % ("ok" if ok else "not ok", want or "clean", label, got or "nothing"))
    return bad, len(tests)


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
