#!/usr/bin/python3
"""The two-body patch test (tests/features/twobody.ini, tests/opts/tb_stack2d.opts, tb_stack3d.opts), checked from the
output fields alone: two blocks stacked along the last axis, the lower one on [0, H1], the upper one on
[H1 + g0, H1 + g0 + H2], meshed independently; the bottom held on rollers along that axis, the top pressed by delta,
frictionless contact between them (dual mortar), symmetry rollers at the coordinate planes x = 0 (y = 0). The exact
solution is uniaxial: the axial strain eps = -(delta - g0) / (H1 + H2) in both bodies, the stress -p along the axis,
    3D: p = -E eps, lateral strain nu p / E;  2D plane strain: p = -E eps / (1 - nu^2), lateral nu (1 + nu) p / E,
u = lateral strain * (the lateral coordinates) and, along the axis, eps * z below and -delta + eps * (z - top) above.
Reports (JSON): the slave vertices (active, with their pressure), the largest relative deviation of their pressure from
p, the largest displacement error relative to the largest exact displacement, and the deepest penetration of a
deformed slave vertex into the lower block (its top at H1 + u).

usage: tb_patch.py --out OUT.json -E E -nu NU --h1 H1 --h2 H2 --gap G0 --delta D RESULT.h5
"""
import argparse
import numpy as np

from cv_patch import contact_fields, report


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True)
    for o in ("-E", "-nu", "--h1", "--h2", "--gap", "--delta"):
        ap.add_argument(o, type=float, required=True)
    ap.add_argument("result")
    a = ap.parse_args()
    x, u, pr, act = contact_fields(a.result)
    dim = x.shape[1]
    z = x[:, dim - 1]
    eps = -(a.delta - a.gap) / (a.h1 + a.h2)
    if dim == 3:
        p, lat = -a.E * eps, a.nu * (-a.E * eps) / a.E
    else:
        p = -a.E * eps / (1 - a.nu ** 2)
        lat = a.nu * (1 + a.nu) * p / a.E
    top = a.h1 + a.gap + a.h2
    upper = z > a.h1 + 0.5 * a.gap
    uex = np.zeros_like(u)
    uex[:, :dim - 1] = lat * x[:, :dim - 1]
    uex[:, dim - 1] = np.where(upper, -a.delta + eps * (z - top), eps * z)
    slave = upper & (np.abs(z - (a.h1 + a.gap)) < 1e-9)
    lower_top = a.h1 + eps * a.h1
    res = {"slave": int(slave.sum()), "active": int((slave & act).sum()), "active_elsewhere": int((~slave & act).sum()),
           "pressure": p,
           "pressure_dev": float(np.abs(pr[slave & act] - p).max() / p) if (slave & act).any() else float("inf"),
           "u_err": float(np.abs(u - uex).max() / np.abs(uex).max()),
           "penetration": float(max(0.0, -(z[slave] + u[slave, dim - 1] - lower_top).min())) if slave.any() else 0.0}
    report(res, a.out)


if __name__ == "__main__":
    main()
