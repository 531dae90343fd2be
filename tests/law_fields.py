#!/usr/bin/env python3
"""Checks the law's output fields of a result file (tests/house5.ini): the fields a law names (SgContactLawGetFields:
tangential_traction, slip, friction_state for a law with a bound) against another result file's, value for value
(--same B.h5), their absence (--none: the frictionless law has none), or vertex by vertex against a Tresca bound
s0 + s1 x_1 (--bound s0,s1: on the slip set |lam_T| = s(x) and the slip along lam_T; on the stick set |lam_T| <= s(x)),
and the states against the summary's stick_size and slip_size (--summary S.json).
usage: law_fields.py A.h5 [--same B.h5] [--none] [--bound s0,s1] [--summary S.json] [--tol TOL]"""
import argparse
import json
import sys

import h5py
import numpy as np

LAW = ("tangential_traction_vector", "slip_vector", "friction_state_vertex")
ap = argparse.ArgumentParser()
ap.add_argument("h5")
ap.add_argument("--same")
ap.add_argument("--none", action="store_true")
ap.add_argument("--bound")
ap.add_argument("--summary")
ap.add_argument("--tol", type=float, default=1e-8)
a = ap.parse_args()
g = h5py.File(a.h5, "r")["vertex_fields"]
bad = []
if a.none:
    bad += ["a field of a law without one: %s" % k for k in g if k in LAW]
else:
    bad += ["no %s" % k for k in LAW if k not in g]
if a.same and not bad:
    o = h5py.File(a.same, "r")["vertex_fields"]
    if sorted(g) != sorted(o):
        bad.append("fields %s, the other file %s" % (sorted(g), sorted(o)))
    for k in g:
        if k in o and not np.array_equal(g[k][()], o[k][()], equal_nan=True):
            bad.append("%s differs (largest difference %g)" % (k, np.nanmax(np.abs(g[k][()] - o[k][()]))))
if (a.bound or a.summary) and not bad:
    st = g["friction_state_vertex"][()].ravel().round().astype(int)
    slip, stick = st == 2, st == 1
    if a.summary:
        s = json.load(open(a.summary))
        if slip.sum() != s["slip_size"] or stick.sum() != s["stick_size"]:
            bad.append("states %d stick %d slip, summary %d %d" % (stick.sum(), slip.sum(), s["stick_size"], s["slip_size"]))
    if a.bound:
        s0, s1 = (float(v) for v in a.bound.split(","))
        x = h5py.File(a.h5, "r")["geometry/vertices"][()]
        lt, u = g["tangential_traction_vector"][()], g["slip_vector"][()]
        nl, nu = np.linalg.norm(lt, axis=1), np.linalg.norm(u, axis=1)
        sb = s0 + s1 * x[:, 0]
        if not slip.any():
            bad.append("no slip vertex")
        r = nl[slip] / sb[slip]
        if slip.any() and abs(r - 1).max() > a.tol:
            bad.append("slip: |lam_T| / s(x) in [%g, %g]" % (r.min(), r.max()))
        c = np.sum(lt[slip] * u[slip], axis=1) / np.maximum(nl[slip] * nu[slip], 1e-300)
        if slip.any() and c.min() < 1 - a.tol:
            bad.append("slip: cos(lam_T, slip) down to %g" % c.min())
        if stick.any() and (nl[stick] > sb[stick] * (1 + a.tol)).any():
            bad.append("stick: |lam_T| above s(x)")
print("\n".join(bad) if bad else "ok")
sys.exit(1 if bad else 0)
