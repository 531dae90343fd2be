#!/usr/bin/python3
"""2D (plane strain) Cattaneo-Mindlin partial slip check (tests/*/friction.ini, scripts/figures.py --only cattaneo):
a rigid cylinder (the parabola d = x^2 / (2 R), Hertz's own profile) on the top face y = 0 of an elastic block
standing for the half plane, pressed by P (per unit thickness), then loaded tangentially by Q < F P with Coulomb
friction F. K. L. Johnson, Contact Mechanics (1985), eqs. (4.45), (4.43) and section 7.1: for a rigid cylinder on
an elastic half plane (E* = E / (1 - nu^2))
    a^2 = 4 P R (1 - nu^2) / (pi E),   p(x) = p0 sqrt(1 - x^2/a^2),   p0 = 2 P / (pi a),
    c / a = sqrt(1 - Q / (F P)),
    q(x) = F p0 sqrt(1 - x^2/a^2)                                  c <= |x| <= a   (slip)
    q(x) = F p0 [sqrt(1 - x^2/a^2) - (c/a) sqrt(1 - x^2/c^2)]      |x| < c         (stick).
Cattaneo's solution assumes that the normal and tangential problems decouple (Dundurs' beta = 0); for a rigid
indenter on an elastic body beta = (1 - 2 nu) / (2 (1 - nu)), hence nu close to 1/2 in options/cattaneo.opts.

Measured from the result's vertex fields (per load step with --step; every step of a load-step file by default):
P = sum_i w_i p_i and Q = sum_i w_i lam_T,i.e_x (w_i the lumped weights of the top face, the contact boundary);
a = half the summed weights of the active vertices (the contact zone between the midpoints to the first vertices
out of contact; within h/2 of the zone's edges for a vertex spacing h), its centre e_a; c = half the summed weights
of the stick vertices, its centre e_c (the stick zone's offset); and, less dependent on the vertex spacing, a_fit
and c_fit from least-squares fits of p^2 and of (F p - |q|)^2 over the active and the stick vertices, both
quadratics in x whose roots are the zone's edges (p^2 = p0^2 (1 - x^2/a^2); in the stick zone
F p - q = F p0 (c/a) sqrt(1 - x^2/c^2)). The profile error is q_i - q(x_i) over the contact vertices, in units of
F p0, q(x) evaluated with a and c from the measured P and Q (Hertz's a, c = a sqrt(1 - Q/(F P))): rms and max,
nodal and filtered by (1/4, 1/2, 1/4) over neighbouring vertices (near nu = 1/2, P1 contact tractions oscillate from
vertex to vertex about the profile: the locking's checkerboard mode; the filter removes it).

usage: cattaneo.py --out OUT.json -E E -nu NU -R R [-F F] RESULT.h5 ...
"""
import argparse
import json
import math
import os
import re
import sys

import h5py
import numpy as np


def field(group, name, step):
    """The vertex field name (of load step `step`, None: of a file without steps) as an array."""
    pat = re.compile(r"^%s%s_[a-z]+$" % (re.escape(name), "" if step is None else "_step%d" % step))
    for k in group:
        if pat.match(k):
            return group[k][()]
    return None


def steps(path):
    """The load steps stored in a result file ([None] for a file without load steps)."""
    with h5py.File(path, "r") as f:
        ks = sorted({int(m.group(1)) for k in f["vertex_fields"] for m in [re.search(r"_step(\d+)_", k)] if m})
    return ks or [None]


def top_weights(x, cells):
    """Lumped weights int phi_i over the top face y = 0 (half of each edge's length per vertex) and its vertices."""
    on = np.abs(x[:, 1]) < 1e-12 * np.ptp(x)
    w = np.zeros(len(x))
    for c in cells:
        e = [v for v in c if on[v]]
        if len(e) == 2:  # a triangle has at most one edge on the line y = 0
            w[e] += abs(x[e[1], 0] - x[e[0], 0]) / 2
    return w, on


def zone(x, w, sel):
    """Half width (half the summed weights) and centre (of the outermost vertices) of the vertices sel."""
    if not sel.any():
        return 0.0, 0.0
    return float(w[sel].sum()) / 2, float(x[sel].min() + x[sel].max()) / 2


def roots_fit(x, y2):
    """Half distance between the roots and their midpoint of the least-squares quadratic through (x, y2)."""
    if len(x) < 3:
        return float("nan"), float("nan")
    c2, c1, c0 = np.polyfit(x, y2, 2)
    disc = c1 * c1 - 4 * c2 * c0
    if c2 >= 0 or disc <= 0:
        return float("nan"), float("nan")
    return float(math.sqrt(disc) / (2 * abs(c2))), float(-c1 / (2 * c2))


def theory_q(x, a, c):
    """Cattaneo-Mindlin shear traction q(x) / (F p0)."""
    x = np.asarray(x, dtype=float)
    q = np.sqrt(np.clip(1 - (x / a) ** 2, 0, None))
    stick = np.abs(x) < c
    q[stick] -= (c / a) * np.sqrt(1 - (x[stick] / c) ** 2)
    return q


def measure(path, E, nu, R, F=None, step=None):
    with h5py.File(path, "r") as f:
        x2 = f["geometry/vertices"][()]
        cells = f["viz/topology/cells"][()].astype(int)
        g = f["vertex_fields"]
        p = field(g, "contact_pressure", step).ravel()
        act = field(g, "active", step).ravel() > 0.5
        lt = field(g, "tangential_traction", step)
        st = field(g, "friction_state", step)
    w, on = top_weights(x2, cells)
    x = x2[:, 0]
    P = float(np.dot(w, p))
    a, e_a = zone(x, w, act & on)
    aH = math.sqrt(4 * P * R * (1 - nu * nu) / (math.pi * E))
    p0 = 2 * P / (math.pi * aH)
    sel = act & on & (p > 0)
    a_fit, e_fit = roots_fit(x[sel], p[sel] ** 2)
    xs = np.sort(x[on & (np.abs(x) <= 1.2 * aH)])
    h = float(np.diff(xs).max()) if len(xs) > 1 else float("nan")  # the vertex spacing at the contact
    r = {"file": os.path.basename(path), "step": step, "P": P, "a": a, "e_a": e_a, "a_hertz": aH, "p0_hertz": p0,
         "err_a": abs(a - aH) / aH, "a_fit": a_fit, "e_a_fit": e_fit, "err_a_fit": abs(a_fit - aH) / aH,
         "active": int((act & on).sum()), "h": h, "h_over_a": h / aH}
    if lt is None or F is None:
        return r
    st = st.ravel().round().astype(int)
    Qv = float(np.dot(w, lt[:, 0]))
    sgn = 1.0 if Qv >= 0 else -1.0
    q = sgn * lt[:, 0]
    ratio = abs(Qv) / (F * P)
    stick, slip = (st == 1) & on, (st == 2) & on
    c, e_c = zone(x, w, stick)
    cth = aH * math.sqrt(max(0.0, 1 - ratio))
    d2 = np.clip(F * p[stick] - np.abs(q[stick]), 0, None) ** 2
    c_fit, e_cfit = roots_fit(x[stick], d2)
    cv = act & on
    err = q[cv] / (F * p0) - theory_q(x[cv], aH, cth)
    # the same error with the filter (1/4, 1/2, 1/4) over neighbouring vertices of the top face (equally spaced at the
    # contact): P1 tractions near nu = 1/2 oscillate from vertex to vertex (the locking's checkerboard mode), which
    # the filter removes; the theory is filtered alike (its kinks at +-c stay comparable)
    band = on & (np.abs(x) <= aH + 2 * h)
    o = np.argsort(x[band])
    eb = (q[band] / (F * p0) - theory_q(x[band], aH, cth))[o]
    eb = np.where(act[band][o], eb, 0.0) - np.where(act[band][o], 0.0, theory_q(x[band][o], aH, cth))
    es = 0.25 * eb[:-2] + 0.5 * eb[1:-1] + 0.25 * eb[2:]
    r.update({"F": F, "Q": abs(Qv), "Q_over_FP": ratio, "stick": int(stick.sum()), "slip": int(slip.sum()),
              "c": c, "e_c": e_c, "c_theory": cth, "c_over_a": c / a if a > 0 else float("nan"),
              "c_over_a_theory": math.sqrt(max(0.0, 1 - ratio)), "e_c_over_a": e_c / aH,
              "c_fit": c_fit, "e_c_fit": e_cfit, "e_c_fit_over_a": e_cfit / aH, "c_fit_over_a_fit": c_fit / a_fit,
              "q_err_rms": float(np.sqrt(np.mean(err ** 2))), "q_err_max": float(np.abs(err).max()),
              "q_err_smooth_rms": float(np.sqrt(np.mean(es ** 2))), "q_err_smooth_max": float(np.abs(es).max()),
              "q_max_over_Fp": float(np.max(np.abs(q[cv]) / np.maximum(F * p[cv], 1e-300)))})
    return r


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", required=True)
    ap.add_argument("-E", type=float, required=True)
    ap.add_argument("-nu", type=float, required=True)
    ap.add_argument("-R", type=float, required=True)
    ap.add_argument("-F", type=float)
    ap.add_argument("--step", type=int, action="append", help="only these load steps (default: all)")
    ap.add_argument("results", nargs="+")
    o = ap.parse_args()
    rows = []
    for path in o.results:
        for k in o.step or steps(path):
            r = measure(path, o.E, o.nu, o.R, o.F, k)
            rows.append(r)
            line = "%-18s step %-4s P %.6e  a %.5f (Hertz %.5f, error %.4f; fit %.5f)  active %d  h/a %.4f" % (
                r["file"], k, r["P"], r["a"], r["a_hertz"], r["err_a"], r["a_fit"], r["active"], r["h_over_a"])
            if "Q" in r:
                line += ("\n%18s Q/(FP) %.4f  c/a %.4f (theory %.4f; fit %.4f)  e_c/a %+.4f  stick %d slip %d  "
                         "q error rms %.4f max %.4f, filtered rms %.4f max %.4f (F p0)" % (
                             "", r["Q_over_FP"], r["c_over_a"], r["c_over_a_theory"], r["c_fit_over_a_fit"], r["e_c_over_a"],
                             r["stick"], r["slip"], r["q_err_rms"], r["q_err_max"], r["q_err_smooth_rms"], r["q_err_smooth_max"]))
            print(line)
    with open(o.out + ".part", "w") as f:
        json.dump({"rows": rows}, f, indent=1)
    os.replace(o.out + ".part", o.out)


if __name__ == "__main__":
    sys.exit(main())
