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

Cases are drawn from --seed and the case number alone, so a case is the same on every machine and in every order;
--time-limit stops starting new cases (the summary then counts fewer than --count). Every run writes only into its own
temporary directory ($T in the commands printed); `fuzz.py --seed S --case I --keep` recreates case I there.

usage: fuzz.py [--count N] [--seed S] [--time-limit T] [--jobs J] [--case I] [--keep] [-summary_file F]
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
CONTROLLERS = ["none", "alm", "pf", "ipf", "pdas", "vi"]
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

    def __init__(self, args, np_=1, kkt_tol=None, y0_admissible=False, inputs=(), tail=(), checkpoint=None):
        self.args, self.np, self.tail = list(args), np_, list(tail)
        self.kkt_tol = kkt_tol
        self.y0_admissible = y0_admissible  # y = 0 is admissible: a solution's energy is <= 0
        self.inputs = list(inputs)  # files of the case directory the run reads
        self.checkpoint = checkpoint  # a -checkpoint_file in the case directory
        self.result = None
        self.must_converge = False  # a well-posed problem: anything but exit 0 is a failure
        self.contact = False  # contact was asked for: an exit 0 without contact has dropped it silently
        self.exact = not any(a in ("-ksp_rtol", "-ksp_type", "-pc_type") or "hypre" in a or "mumps_reuse" in a for a in self.args)


class Case:
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
    ct = rng.choice(sorted(base))
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


GENERATORS = [("options", gen_options, 0.35), ("wellposed", gen_wellposed, 0.1), ("optfile", gen_optfile, 0.2), ("mesh", gen_mesh, 0.2), ("checkpoint", gen_checkpoint, 0.15)]


def draw_case(seed, index, T, base):
    rng = random.Random("fuzz:%d:%d" % (seed, index))
    r, acc = rng.random(), 0.0
    for name, fn, w in GENERATORS:
        acc += w
        if r < acc:
            break
    desc, runs, twin = fn(rng, T, base)
    return Case(name, index, desc, runs, twin)


# ---------------------------------------------------------------- running and checking

def shown(run, T):
    """The command as a user would type it in the repository, the case directory written $T."""
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
        last = [l for l in error_message(out).splitlines() if l.strip()]
        v.append(("b: a well-posed problem not solved", "exit %d: %s" % (rc, " / ".join(last[:2])[:150])))
    # (c) a failure names an option or a file
    if rc != 0 and not v:  # a crash or a hang is reported as such
        files = run.inputs + [a for a in run.args if "/" in a or a.endswith((".h5", ".opts", ".msh"))]
        if not names_option_or_file(error_message(out), files):
            last = [l for l in error_message(out).splitlines() if l.strip()]
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
        v, s = check_run(case, run, T, before)
        summaries.append(s)
        case.violations += [(c, d, run) for c, d in v]
    if case.twin and all(r.result["rc"] in (0, 3) for r in case.runs):
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
    print("%d passed, %d failed" % (len(cases) - bad, bad))
    return bad


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
        return case

    with ThreadPoolExecutor(max_workers=opt.jobs) as pool:
        list(pool.map(work, indices))
    shutil.rmtree(master, ignore_errors=True)
    cases.sort(key=lambda c: c.index)
    stray = sorted(repo_listing() - listing)

    by_class, by_gen = {}, {}
    nviol = 0
    for c in cases:
        g = by_gen.setdefault(c.gen, {"cases": 0, "failed": 0, "violations": 0})
        g["cases"] += 1
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
