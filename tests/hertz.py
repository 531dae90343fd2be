#!/usr/bin/python3
"""Hertz indentation check (tests/*/rollers.ini): contact radius a and peak pressure p0 of quarter-model results of a
rigid ball pressed into an elastic block, against the Hertz formulas for a rigid sphere on an elastic half-space,
    a = (3 P R (1 - nu^2) / (4 E))^(1/3),   p0 = 3 P / (2 pi a^2),
with P the total force, 4 times the quarter's (the sum of the nodal pressures times the lumped weights of the
contact face z = 0). Measured: a from the active area (lumped weights of the active vertices, a quarter of pi a^2),
p0 the nodal pressure on the axis (the vertex at the origin). The largest nodal pressure is reported too but not
used: P1 nodal pressures scatter by a few per cent about the Hertz profile on unstructured meshes, and the largest
picks the scatter (measured 3.2, 2.4, 2.3 % above p0 on hertz_s1/s2/s4: it does not converge). Writes a JSON summary (per mesh: P, a, p0, their Hertz values and relative errors).

usage: hertz.py --out OUT.json -E E -nu NU -R R RESULT.h5 ...
"""
import argparse
import json
import math
import os
import sys

import h5py
import numpy as np


def dataset(group, name):
    for k in group:  # PETSc names a field <vector>_<section field>
        if k == name or k.startswith(name + "_"):
            return group[k][()]
    raise KeyError("no field %s in %s" % (name, group.name))


def contact_weights(x, cells, tol):
    """Lumped weights int phi_i over the faces of the boundary z = 0 (a third of each triangle's area per vertex)."""
    w = np.zeros(len(x))
    on = np.abs(x[:, 2]) < tol
    for c in cells:
        f = [v for v in c if on[v]]
        if len(f) == 3:  # a tetrahedron touches the plane z = 0 with at most one face
            area = 0.5 * np.linalg.norm(np.cross(x[f[1]] - x[f[0]], x[f[2]] - x[f[0]]))
            w[f] += area / 3
    return w


def measure(path, E, nu, R):
    with h5py.File(path, "r") as f:
        x = f["geometry/vertices"][()]
        cells = f["viz/topology/cells"][()].astype(int)
        p = dataset(f["vertex_fields"], "contact_pressure")
        act = dataset(f["vertex_fields"], "active") > 0.5
        u = dataset(f["vertex_fields"], "displacement")
    w = contact_weights(x, cells, 1e-12 * np.ptp(x))
    P = 4 * float(np.dot(w, p))
    a = math.sqrt(4 * float(w[act].sum()) / math.pi)
    p0 = float(p[np.argmin(np.linalg.norm(x, axis=1))])
    aH = (3 * P * R * (1 - nu * nu) / (4 * E)) ** (1 / 3)
    p0H = 3 * P / (2 * math.pi * aH * aH)
    h = float(min(np.linalg.norm(x[c[i]] - x[c[j]]) for c in cells if (np.abs(x[c, 2]) < 1e-12).sum() == 3
                  for i in range(4) for j in range(i)))  # the smallest edge of a tetrahedron on the contact face
    # the rollers' data in the output: u_x on x = 0 and u_y on y = 0 (exactly 0)
    sym = float(max(np.abs(u[np.abs(x[:, 0]) < 1e-14, 0]).max(), np.abs(u[np.abs(x[:, 1]) < 1e-14, 1]).max()))
    return {"file": os.path.basename(path), "sym": sym, "P": P, "a": a, "p0": p0, "a_hertz": aH, "p0_hertz": p0H,
            "err_a": abs(a - aH) / aH, "err_p0": abs(p0 - p0H) / p0H, "p_max": float(p.max()), "active": int(act.sum()), "h_min": h}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", required=True)
    ap.add_argument("-E", type=float, required=True)
    ap.add_argument("-nu", type=float, required=True)
    ap.add_argument("-R", type=float, required=True)
    ap.add_argument("results", nargs="+")
    a = ap.parse_args()
    rows = [measure(r, a.E, a.nu, a.R) for r in a.results]
    for r in rows:
        print("%-16s P %.6e  a %.5f (Hertz %.5f, error %.4f)  p0 %.6e (Hertz %.6e, error %.4f)  active %d  h_min %.4f"
              % (r["file"], r["P"], r["a"], r["a_hertz"], r["err_a"], r["p0"], r["p0_hertz"], r["err_p0"], r["active"], r["h_min"]))
    s = {"meshes": rows, "err_a": [r["err_a"] for r in rows], "err_p0": [r["err_p0"] for r in rows], "P": [r["P"] for r in rows]}
    with open(a.out + ".part", "w") as f:
        json.dump(s, f, indent=1)
    os.replace(a.out + ".part", a.out)


if __name__ == "__main__":
    sys.exit(main())
