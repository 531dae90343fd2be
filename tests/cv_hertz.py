#!/usr/bin/python3
"""Hertz with a curved elastic body (tests/verification/curved.ini): results of the quarter hemisphere (meshes/cv_hemisphere.geo,
3D) or the half of the half disc (meshes/cv_halfdisc.geo, 2D plane strain) of radius R pressed by d onto the rigid plane
through the origin normal to the last axis, against the Hertz formulas of an elastic sphere / cylinder on a rigid
plane (E* = E / (1 - nu^2)):
    3D   F = (4/3) E* R^1/2 d^3/2,  a = (R d)^1/2         (F the whole sphere's force, 4 times the quarter's)
         and at the run's own force P: a = (3 P R / (4 E*))^1/3, p0 = 3 P / (2 pi a^2)
    2D   at the run's own force P per unit length (twice the half's): a = (4 P R / (pi E*))^1/2, p0 = 2 P / (pi a)
         (a cylinder's approach is not a function of P alone, so d is not compared in 2D)
Everything from the output fields: P = sum of the nodal contact pressures times the lumped weights of the contact
boundary (the facets on the circle/sphere of radius R about (0,..,R), not on the symmetry planes nor the top), a from
the active vertices' weights (3D: a quarter of pi a^2; 2D: the half's contact length a) and bracketed by
[a_lo, a_hi], the distances from the axis of the outermost active and the innermost inactive contact vertex (the
discrete contact edge lies between them), p0 the pressure at the
vertex at the origin. Writes a JSON summary {"rows": [per mesh: h_min, P, F_hertz, a, a_hertz, a_hertz_P, p0,
p0_hertz, err_F, err_a, err_a_P, err_p0, a_lo, a_hi, penetration]} (penetration: the largest depth of x + u below the plane,
from the fields).

Two elastic bodies (tests/verification/twobody.ini): the slave body is the one of radius R above; --Estar and --Rhertz
give the pair's E* and curvature radius for the formulas (the field of the master side is not read).

usage: cv_hertz.py --out OUT.json -E E -nu NU -R R -d D [--Estar E* --Rhertz R*] RESULT.h5 ...
"""
import argparse
import json
import math
import os

import h5py
import numpy as np


def dataset(group, name):
    for k in group:  # PETSc names a field <vector>_<section field>
        if k == name or k.startswith(name + "_"):
            return group[k][()]
    raise KeyError("no field %s in %s" % (name, group.name))


def boundary_facets(cells):
    """facets of exactly one cell (sorted vertex tuples)"""
    count = {}
    k = cells.shape[1]
    for c in cells:
        for j in range(k):
            f = tuple(sorted(np.delete(c, j)))
            count[f] = count.get(f, 0) + 1
    return [f for f, n in count.items() if n == 1]


def measure(path, E, nu, R, d, Estar=None, Rhertz=None):
    with h5py.File(path, "r") as f:
        x = f["geometry/vertices"][()]
        cells = f["viz/topology/cells"][()].astype(int)
        p = dataset(f["vertex_fields"], "contact_pressure")
        act = dataset(f["vertex_fields"], "active") > 0.5
        u = dataset(f["vertex_fields"], "displacement")
    dim = x.shape[1]
    centre = np.zeros(dim)
    centre[-1] = R
    tol = 1e-9 * R
    on_arc = np.abs(np.linalg.norm(x - centre, axis=1) - R) < tol
    w = np.zeros(len(x))
    for fc in boundary_facets(cells):
        fc = list(fc)
        if not on_arc[fc].all():
            continue
        y = x[fc]
        if np.all(np.abs(y[:, -1] - R) < tol) or any(np.all(np.abs(y[:, k]) < tol) for k in range(dim - 1)):
            continue  # a facet of the top or of a symmetry plane whose vertices all lie on the rim
        if dim == 3:
            size = 0.5 * np.linalg.norm(np.cross(y[1] - y[0], y[2] - y[0]))
        else:
            size = np.linalg.norm(y[1] - y[0])
        w[fc] += size / dim
    Es = Estar if Estar else E / (1 - nu * nu)
    origin = int(np.argmin(np.linalg.norm(x, axis=1)))
    p0 = float(p[origin])
    h = float(min(np.linalg.norm(x[c[i]] - x[c[j]]) for c in cells if on_arc[c].sum() == dim
                  for i in range(dim + 1) for j in range(i)))
    pen = float(max(0.0, -(x[:, -1] + u[:, -1]).min()))
    r = np.linalg.norm(x[:, :-1], axis=1)  # the distance from the axis along the plane
    cand = w > 0
    a_lo = float(r[cand & act].max())  # the contact radius lies between the last active vertex
    a_hi = float(r[cand & ~act].min()) if (cand & ~act).any() else float("inf")  # and the first inactive one
    R = Rhertz if Rhertz else R  # two bodies: the curvature radius of the pair, 1/R = 1/R1 + 1/R2
    if dim == 3:
        P = 4 * float(np.dot(w, p))
        a = math.sqrt(4 * float(w[act].sum()) / math.pi)
        F_h = 4.0 / 3.0 * Es * math.sqrt(R) * d ** 1.5
        a_h = math.sqrt(R * d)
        a_hP = (3 * P * R / (4 * Es)) ** (1 / 3)
        p0_h = 3 * P / (2 * math.pi * a_hP ** 2)
    else:
        P = 2 * float(np.dot(w, p))
        a = float(w[act].sum())
        F_h = a_h = float("nan")
        a_hP = math.sqrt(4 * P * R / (math.pi * Es))
        p0_h = 2 * P / (math.pi * a_hP)
    row = {"file": os.path.basename(path), "dim": dim, "h_min": h, "P": P, "a": a, "p0": p0, "a_hertz_P": a_hP,
           "p0_hertz": p0_h, "err_a_P": abs(a - a_hP) / a_hP, "err_p0": abs(p0 - p0_h) / p0_h, "active": int(act.sum()),
           "a_lo": a_lo, "a_hi": a_hi, "penetration": pen}
    if dim == 3:
        row.update({"F_hertz": F_h, "a_hertz": a_h, "err_F": abs(P - F_h) / F_h, "err_a": abs(a - a_h) / a_h})
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True)
    ap.add_argument("-E", type=float, required=True)
    ap.add_argument("-nu", type=float, required=True)
    ap.add_argument("-R", type=float, required=True)
    ap.add_argument("-d", type=float, required=True)
    ap.add_argument("--Estar", type=float, help="two bodies: 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (default E / (1 - nu^2))")
    ap.add_argument("--Rhertz", type=float, help="two bodies: 1/R = 1/R1 + 1/R2 in the formulas (-R stays the slave arc's radius)")
    ap.add_argument("results", nargs="+")
    a = ap.parse_args()
    rows = [measure(r, a.E, a.nu, a.R, a.d, a.Estar, a.Rhertz) for r in a.results]
    for r in rows:
        print(" ".join("%s %.6g" % (k, v) if isinstance(v, float) else "%s %s" % (k, v) for k, v in r.items()))
    tmp = a.out + ".tmp"
    with open(tmp, "w") as f:
        json.dump({"rows": rows}, f, indent=1)
    os.replace(tmp, a.out)


if __name__ == "__main__":
    main()
