#!/usr/bin/python3
"""The largest difference of the obstacle offsets d n (the gap along the normal, output field obstacle_offset) of
two results on the same mesh, vertices matched by their coordinates; exits 1 if it is above TOL.

usage: cad_gap.py A.h5 B.h5 TOL
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
from plot_mesh import load  # noqa: E402


def offsets(path):
    d = load(path)
    order = np.lexsort(d["x"].T[::-1])
    return d["x"][order], d["obstacle"][order]


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    xa, oa = offsets(sys.argv[1])
    xb, ob = offsets(sys.argv[2])
    if xa.shape != xb.shape or np.abs(xa - xb).max() > 1e-12:
        sys.exit("cad_gap.py: the two results are not on the same mesh")
    # a vertex whose ray misses the obstacle has NaN offsets: both results must miss at the same vertices
    ma, mb = np.isnan(oa).any(axis=1), np.isnan(ob).any(axis=1)
    on = np.linalg.norm(np.where(ma[:, None], 0, oa), axis=1) > 0
    diff = np.inf if (ma != mb).any() else (np.abs(oa[~ma] - ob[~ma]).max() if (~ma).any() else 0.0)
    print("contact vertices %d (%d), %d missed, largest |d n| %.6g, largest difference %.3g" % (on.sum(), (np.linalg.norm(np.where(mb[:, None], 0, ob), axis=1) > 0).sum(), ma.sum(), np.abs(oa[~ma]).max() if (~ma).any() else 0.0, diff))
    sys.exit(0 if on.sum() > 0 and diff <= float(sys.argv[3]) else 1)


if __name__ == "__main__":
    main()
