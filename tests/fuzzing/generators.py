"""The generators of the fuzz test: each draws one case (its runs and, for some, the generator's own judgement of
a run or of the case's runs together) from a random.Random seeded by the seed and the case number alone. The
controller names and the friction laws come from the program's registries (registry.py)."""
import math
import os
import random
import re
import shutil
import subprocess
import sys
import threading
from concurrent.futures import ThreadPoolExecutor

import h5py
import numpy as np

from .common import Case, DEFAULT_KKT_TOL, ENV, ROOT, Run, log_uniform, num, options_in, pick_weird_number, sgrun
from . import registry
from .checks import agree, error_message, finite, force_checks, norm, of_exit0

# The program's registries (bin/signorini -help): every controller type; of the friction laws those whose parameter
# the generators know how to set (a law registered without an entry here is not drawn: the runner says so).
CONTROLLERS = registry.controllers()
LAW_PARAMETER = {"none": None, "tresca": "-friction_bound", "coulomb": "-friction_coefficient"}
FRICTION_LAWS = [f for f in registry.friction_laws() if f in LAW_PARAMETER]
LAWS_NOT_DRAWN = [f for f in registry.friction_laws() if f not in LAW_PARAMETER]


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


def cont_args(ct):
    """A controller's options file; alm with a growing gamma (with gamma fixed it needs no bound of steps)."""
    return ["-options_file", "options/cont/%s.opts" % ct] + (["-alm_gamma_factor", "10"] if ct == "alm" else [])




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
    fr = rng.choice(["none", "none"] + sorted(f for f in FRICTION_LAWS if f != "none"))  # frictionless half the time
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
    other = rng.choice([f for f in FRICTION_LAWS if f != fr])
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
