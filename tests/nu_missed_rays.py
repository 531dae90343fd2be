#!/usr/bin/python3
"""Checks the contact fields of a result whose obstacle some contact vertices' normals miss (a CAD or meshed
obstacle of finite extent, or a plane parallel to the normal): at a vertex whose ray misses, `gap` and
`obstacle_offset` are NaN (no obstacle along the normal), never a huge number; everywhere else they are finite and
the offset's length is the gap's reference value d. The vertices expected to miss are computed from the geometry:
the contact vertices whose last coordinate is above LEVEL (the box's vertical sides, whose normals are horizontal,
above a floor whose top is below LEVEL). Exits 1 on any violation.

usage: nu_missed_rays.py RESULT.h5 LEVEL [RESULT.h5 LEVEL ...]
"""
import sys

import h5py
import numpy as np


def check(path, level):
    with h5py.File(path, "r") as f:
        v = f["vertex_fields"]
        x, gap, off = f["geometry/vertices"][()], v["gap_vertex"][()].ravel(), v["obstacle_offset_vector"][()]
        pen, act = v["penetration_vertex"][()].ravel(), v["active_vertex"][()].ravel()
    miss = np.isnan(off).any(axis=1)
    contact = miss | (np.linalg.norm(np.where(miss[:, None], 0, off), axis=1) > 0)
    expect = contact & (x[:, -1] > level)
    bad = []
    if not expect.any():
        bad.append("no contact vertex above %g: the test does not test anything" % level)
    if (miss != expect).any():
        bad.append("NaN offsets at %d vertices, expected at %d" % (miss.sum(), expect.sum()))
    if (np.isnan(gap) != miss).any():
        bad.append("the gap is NaN at %d vertices, the offset at %d" % (np.isnan(gap).sum(), miss.sum()))
    if np.isnan(off[~miss]).any() or np.abs(gap[~np.isnan(gap)]).max() > 1e3 or np.abs(off[~miss]).max() > 1e3:
        bad.append("finite fields hold huge values (largest gap %g)" % np.nanmax(np.abs(gap)))
    if not np.isfinite(pen).all() or (pen[miss] != 0).any() or (act[miss] != 0).any():
        bad.append("a missing ray's vertex has a penetration or is active")
    print("%s: %d contact vertices, %d rays miss (%d expected), largest finite gap %.6g" % (path, contact.sum(), miss.sum(), expect.sum(), np.nanmax(gap)))
    for b in bad:
        print("  FAIL: " + b)
    return not bad


def main():
    if len(sys.argv) < 3 or len(sys.argv) % 2 != 1:
        sys.exit(__doc__)
    ok = [check(sys.argv[i], float(sys.argv[i + 1])) for i in range(1, len(sys.argv), 2)]
    sys.exit(0 if all(ok) else 1)


if __name__ == "__main__":
    main()
