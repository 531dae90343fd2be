#!/usr/bin/python3
"""How far the curved boundary of a result file's mesh lies from the true circle or sphere (-dm_refine_geometry,
tests/features/snap30.ini), from the output's vertices and cells alone (geometry/vertices, viz/topology/cells).

The boundary facets (those of one cell) are sorted: a facet whose vertices all lie on one of the PLANES (to 1e-12 of
the mesh's size) is planar; every other facet is on the curved face, and each of its vertices is measured against
the circle / sphere |x - C| = R. A vertex of the rim (on a curved and a planar facet) that left its plane makes its
planar facet count as curved, with vertices far from the sphere: so the rim is checked too.
Prints the largest | |x - C| - R | over the curved facets' vertices and their number. Exits 1 if it is above TOL, or,
with --expect-off, if it is not (the refinement without the option: the check can fail).

usage: snap30_fields.py RESULT.h5 C R PLANES TOL [--expect-off]
    C       the centre, comma separated (2 or 3 numbers)
    PLANES  ';'-separated planes axis=value, e.g. "0=0;1=0;2=1" (x = 0, y = 0, z = 1)
"""
import sys
from collections import Counter

import h5py
import numpy as np


def main():
    if len(sys.argv) not in (6, 7) or (len(sys.argv) == 7 and sys.argv[6] != "--expect-off"):
        sys.exit(__doc__)
    path, ctext, rtext, ptext, ttext = sys.argv[1:6]
    expect_off = len(sys.argv) == 7
    with h5py.File(path, "r") as f:
        x = f["geometry/vertices"][()]
        cells = f["viz/topology/cells"][()].astype(int)
    dim = x.shape[1]
    c = np.array([float(a) for a in ctext.split(",")])
    if len(c) != dim or cells.shape[1] != dim + 1:
        sys.exit("snap30_fields.py: the centre has %d numbers, the mesh is %dD with %d vertices per cell" % (len(c), dim, cells.shape[1]))
    R, tol = float(rtext), float(ttext)
    planes = [(int(a.split("=")[0]), float(a.split("=")[1])) for a in ptext.split(";") if a]
    size = np.max(np.abs(x))
    facets = Counter()
    for cell in cells:
        for k in range(dim + 1):
            facets[tuple(sorted(np.delete(cell, k)))] += 1
    bnd = [fc for fc, n in facets.items() if n == 1]
    curved = set()
    for fc in bnd:
        if any(all(abs(x[v, ax] - val) <= 1e-12 * size for v in fc) for ax, val in planes):
            continue
        curved.update(fc)
    if not curved:
        sys.exit("snap30_fields.py: %s has no curved boundary facets" % path)
    idx = np.array(sorted(curved))
    dev = np.abs(np.linalg.norm(x[idx] - c, axis=1) - R)
    worst = idx[np.argmax(dev)]
    print("curved boundary: %d vertices, largest | |x - C| - R | = %.3e at %s" % (len(idx), dev.max(), x[worst]))
    if expect_off:
        sys.exit(0 if dev.max() > tol else 1)
    sys.exit(1 if not dev.max() <= tol else 0)


if __name__ == "__main__":
    main()
