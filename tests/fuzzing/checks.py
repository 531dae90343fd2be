"""The checks of the fuzz test: check_run judges every run of bin/signorini by (a)-(d) of tests/fuzz.py's
docstring, check_misuse a run of bin/misuse_tests, force_checks the physics of a result (the generators' judges use
it); none trusts the program's own measures beyond the summary's keys."""
import json
import math
import os
import re

from .common import CRASH, DEFAULT_KKT_TOL, SENTINEL, sgrun


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



def agree(a, b, what, rtol, floor):
    """Two values of the same problem's answer agree to rtol (relative to the larger) plus an absolute floor."""
    if not (finite(a) and finite(b)) or abs(a - b) <= rtol * max(abs(a), abs(b)) + floor:
        return []
    return ["%s %.10g vs %.10g" % (what, a, b)]



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
