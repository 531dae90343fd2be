#!/usr/bin/python3
"""Mirror symmetry of a two-body run (tests/verification/twobody_mirror.ini): two equal bodies, meshed as mirror
images of each other about the plane x_last = 0, pressed together by mirrored Dirichlet data. The answer of the
continuous problem is its own mirror image: u(S x) = S u(x), S the reflection x_last -> -x_last. Dual mortar is not
symmetric in its two sides (the slave side carries the multiplier and the normals), so the discrete answer is
symmetric up to the discretization error; this script measures how far, from the .h5 alone.

Reported in a JSON summary:
  - mesh_mirrored: every vertex has a mirror vertex (to 1e-12) and every cell a mirror cell (the premise of the test);
  - asym_u: max over the vertices of |u(S x) - S u(x)| / max |u|;
  - asym_p: max over the slave's vertices of |contact_pressure(x) - master_pressure(S x)| / max contact_pressure:
    the slave's multiplier against its mortar projection onto the master side, vertex by vertex;
  - umax, pmax, n_active.

usage: tb_mirror.py --out OUT.json RESULT.h5
"""
import argparse

import h5py
import numpy as np

from cv_patch import dataset, report


def mirror_map(x):
    """For each vertex the index of its mirror image (or -1), matched on coordinates rounded to 1e-12."""
    key = {tuple(np.round(p, 12)): i for i, p in enumerate(x)}
    xs = x.copy()
    xs[:, -1] = -xs[:, -1]
    return np.array([key.get(tuple(np.round(p, 12)), -1) for p in xs])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True)
    ap.add_argument("h5")
    a = ap.parse_args()
    with h5py.File(a.h5, "r") as f:
        x = f["geometry/vertices"][()]
        cells = f["viz/topology/cells"][()]
        u = dataset(f["vertex_fields"], "displacement")
        p = dataset(f["vertex_fields"], "contact_pressure")
        pm = dataset(f["vertex_fields"], "master_pressure")
    m = mirror_map(x)
    ok = bool((m >= 0).all())
    if ok:
        have = {tuple(sorted(c)) for c in cells.tolist()}
        ok = all(tuple(sorted(m[c])) in have for c in cells)
    res = {"mesh_mirrored": ok, "n_vertices": int(len(x))}
    if ok:
        su = u.copy()
        su[:, -1] = -su[:, -1]
        umax = float(np.abs(u).max())
        res["umax"] = umax
        res["asym_u"] = float(np.abs(u[m] - su).max() / umax)
        slave = p > 0
        pmax = float(p.max())
        res["pmax"] = pmax
        res["n_active"] = int(slave.sum())
        res["asym_p"] = float(np.abs(p[slave] - pm[m[slave]]).max() / pmax) if pmax > 0 else float("nan")
    report(res, a.out)


if __name__ == "__main__":
    main()
