#!/usr/bin/env python3
"""Checks the friction fields of a result file (tests/*/friction.ini): the states against the summary's stick_size and
slip_size, and the friction law vertex by vertex: on the slip set |lam_T| = F p and the slip along lam_T (the body
feels -lam_T, opposing its slip), on the stick set |lam_T| <= F p.  usage: friction_fields.py RESULT.h5 SUMMARY.json F TOL"""
import json
import sys

import h5py
import numpy as np

h5, js, F, tol = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
s = json.load(open(js))
g = h5py.File(h5, "r")["vertex_fields"]
st = g["friction_state_vertex"][()].ravel().round().astype(int)
lt = g["tangential_traction_vector"][()]
u = g["slip_vector"][()]
p = g["contact_pressure_vertex"][()].ravel()
nl, nu = np.linalg.norm(lt, axis=1), np.linalg.norm(u, axis=1)
slip, stick = st == 2, st == 1
bad = []
if slip.sum() != s["slip_size"] or stick.sum() != s["stick_size"]:
    bad.append("states %d stick %d slip, summary %d %d" % (stick.sum(), slip.sum(), s["stick_size"], s["slip_size"]))
r = nl[slip] / (F * p[slip])
if slip.any() and abs(r - 1).max() > tol:
    bad.append("slip: |lam_T| / (F p) in [%g, %g]" % (r.min(), r.max()))
cosang = np.sum(lt[slip] * u[slip], axis=1) / np.maximum(nl[slip] * nu[slip], 1e-300)
if slip.any() and cosang.min() < 1 - tol:
    bad.append("slip: cos(lam_T, slip) down to %g" % cosang.min())
if stick.any() and (nl[stick] > F * p[stick] * (1 + tol)).any():
    bad.append("stick: |lam_T| above F p")
print("stick %d slip %d, |lam_T|/(F p) on slip in [%g, %g], cos >= %g" % (stick.sum(), slip.sum(), r.min() if slip.any() else 0, r.max() if slip.any() else 0, cosang.min() if slip.any() else 1))
print("\n".join(bad))
sys.exit(1 if bad else 0)
