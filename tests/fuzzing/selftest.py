"""The fuzz test's self-test: every check of checks.py and every judgement of the generators, on synthetic runs
that each carry one known fault (it must be found) and on right results (they must pass)."""
import json
import os
import random
import shutil
import tempfile

import h5py

from .common import Run, SENTINEL, snapshot
from .checks import check_misuse, check_run, force_checks
from .generators import MISUSE, RS_PROBLEM, RS_VARIANTS, gen_nu, gen_restart, gen_unload


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
