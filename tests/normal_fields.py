#!/usr/bin/python3
"""How far the deformed body of a result file lies inside a rigid obstacle, from the output fields alone (coordinates
x and displacement u of every vertex, not the solver's own measures), for -contact_normal (tests/normal.ini).

The obstacle's signed distance at y = x + u, computed here from its parameters:
    plane:P:N      the half-space below the plane through P with normal N (pointing towards the body)
    ball:C:R[:U]   the half-ball of radius R centred at C standing on the plane through C normal to U (default e_dim),
                   the half-space below that plane included (as -obstacle_type ball)
    parabola:A:OFF:C  below the surface z_d = C_d - OFF - A |z_t - C_t|^2 (d the last axis, t the others; as
                   -obstacle_type parabola under a flat face at the height C_d): the depth below it along e_d (not a
                   distance, but zero exactly where y is outside)
Prints the largest penetration max(0, -sd(y)) over all vertices and the vertex (with load steps: of the last step); exits 1 if it is above PEN (an
absolute length). With REF.h5 (a result on the same mesh) also the largest difference of the displacements relative
to the largest displacement of REF; exits 1 if it is above UTOL.

usage: normal_fields.py RESULT.h5 OBSTACLE PEN [REF.h5 UTOL]
"""
import os
import re
import sys

import h5py
import numpy as np


def load(path):
    """coordinates and displacement of every vertex; with load steps the last step's displacement"""
    with h5py.File(path, "r") as f:
        g = f["vertex_fields"]
        names = [k for k in g if k.startswith("displacement")]
        step = lambda k: int(re.search(r"_step(\d+)", k).group(1)) if "_step" in k else 0  # noqa: E731
        return {"x": f["geometry/vertices"][()], "u": g[max(names, key=step)][()]}


def vec(text, dim):
    v = np.array([float(a) for a in text.split(",")])
    if len(v) != dim:
        sys.exit("normal_fields.py: %s has %d numbers, the mesh is %dD" % (text, len(v), dim))
    return v


def signed_distance(spec, y):
    dim = y.shape[1]
    part = spec.split(":")
    if part[0] == "plane" and len(part) == 3:
        p, n = vec(part[1], dim), vec(part[2], dim)
        n = n / np.linalg.norm(n)
        return (y - p) @ n
    if part[0] == "ball" and len(part) in (3, 4):
        c, R = vec(part[1], dim), float(part[2])
        up = vec(part[3], dim) if len(part) == 4 else np.eye(dim)[dim - 1]
        up = up / np.linalg.norm(up)
        return np.minimum(np.linalg.norm(y - c, axis=1) - R, (y - c) @ up)
    if part[0] == "parabola" and len(part) == 4:
        a, off, c = float(part[1]), float(part[2]), vec(part[3], dim)
        rt = y[:, :-1] - c[:-1]
        return y[:, -1] - (c[-1] - off - a * np.sum(rt * rt, axis=1))
    sys.exit("normal_fields.py: unknown obstacle %s" % spec)


def main():
    if len(sys.argv) not in (4, 6):
        sys.exit(__doc__)
    d = load(sys.argv[1])
    x, u = d["x"], d["u"]
    sd = signed_distance(sys.argv[2], x + u)
    i = int(np.argmin(sd))
    pen = max(0.0, -sd[i])
    bad = pen > float(sys.argv[3])
    print("vertices %d, largest |u| %.6g, largest penetration %.3e at x = %s" % (len(x), np.abs(u).max(), pen, np.array2string(x[i], precision=6)))
    if len(sys.argv) == 6:
        r = load(sys.argv[4])
        oa, ob = np.lexsort(x.T[::-1]), np.lexsort(r["x"].T[::-1])
        if x.shape != r["x"].shape or np.abs(x[oa] - r["x"][ob]).max() > 1e-12:
            sys.exit("normal_fields.py: the two results are not on the same mesh")
        du = np.abs(u[oa] - r["u"][ob]).max() / np.abs(r["u"]).max()
        print("largest displacement difference to %s: %.3g of its largest displacement" % (os.path.basename(sys.argv[4]), du))
        bad = bad or not du <= float(sys.argv[5])
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
