#!/usr/bin/python3
"""Contact patch test on an inclined rigid plane (tests/verification/curved.ini, options/cv_tilt2d.opts, options/cv_tilt3d.opts),
checked from the output fields alone: a block resting with its bottom face on the plane through X0 with unit normal n,
a uniform pressure p on its top face, frictionless contact, pins holding the rigid motions at their exact
displacements. The exact solution is uniaxial stress -p n n^T: the contact pressure is p at every contact vertex and
    u(x) = eps_t (I - n n^T)(x - X0) + eps_n ((x - X0).n) n,
    3D: eps_t = nu p / E, eps_n = -p / E;  2D plane strain: eps_t = nu (1 + nu) p / E, eps_n = -(1 - nu^2) p / E.
Reports (JSON): the vertices on the plane (reference positions within 1e-9 of it), how many of them are active and
how many are not (the pins), the largest relative deviation of the active vertices' pressure from p, the largest
displacement error relative to the largest exact displacement, and the largest depth of a deformed vertex x + u below
the plane.

usage: cv_patch.py --out OUT.json --point X0 --normal N -p P -E E -nu NU RESULT.h5
"""
import argparse
import json
import os

import h5py
import numpy as np


def dataset(group, name):
    for k in group:
        if k == name or k.startswith(name + "_"):
            return group[k][()]
    raise KeyError("no field %s in %s" % (name, group.name))


def contact_fields(path):
    """The vertex coordinates, displacement, contact pressure and active flags of a result file."""
    with h5py.File(path, "r") as f:
        x = f["geometry/vertices"][()]
        u = dataset(f["vertex_fields"], "displacement")
        pr = dataset(f["vertex_fields"], "contact_pressure")
        act = dataset(f["vertex_fields"], "active") > 0.5
    return x, u, pr, act


def report(res, out):
    """Print the results on one line and write them to OUT (JSON; replaced whole, never half-written)."""
    print(" ".join("%s %.6g" % (k, v) for k, v in res.items()))
    tmp = out + ".tmp"
    with open(tmp, "w") as f:
        json.dump(res, f, indent=1)
    os.replace(tmp, out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True)
    ap.add_argument("--point", required=True)
    ap.add_argument("--normal", required=True)
    ap.add_argument("-p", type=float, required=True)
    ap.add_argument("-E", type=float, required=True)
    ap.add_argument("-nu", type=float, required=True)
    ap.add_argument("result")
    a = ap.parse_args()
    x, u, pr, act = contact_fields(a.result)
    dim = x.shape[1]
    x0 = np.array([float(v) for v in a.point.split(",")])
    n = np.array([float(v) for v in a.normal.split(",")])
    n /= np.linalg.norm(n)
    if len(x0) != dim or len(n) != dim:
        raise SystemExit("cv_patch.py: --point and --normal need %d numbers" % dim)
    if dim == 3:
        et, en = a.nu * a.p / a.E, -a.p / a.E
    else:
        et, en = a.nu * (1 + a.nu) * a.p / a.E, -(1 - a.nu ** 2) * a.p / a.E
    r = x - x0
    rn = r @ n
    uex = et * (r - np.outer(rn, n)) + en * np.outer(rn, n)
    on = np.abs(rn) < 1e-9 * np.ptp(x)
    res = {"on_plane": int(on.sum()), "active": int((on & act).sum()), "inactive_on_plane": int((on & ~act).sum()),
           "active_off_plane": int((~on & act).sum()),
           "pressure_dev": float(np.abs(pr[on & act] - a.p).max() / a.p) if (on & act).any() else float("inf"),
           "pressure_mean": float(pr[on & act].mean()) if (on & act).any() else 0.0,
           "u_err": float(np.abs(u - uex).max() / np.abs(uex).max()),
           "penetration": float(max(0.0, -((r + u) @ n).min()))}
    report(res, a.out)


if __name__ == "__main__":
    main()
