#!/usr/bin/env python3
"""Checks of the HDF5 files a run writes on several ranks (tests/cluster27.ini): each rank writes its own rows, in
an order that depends on the partition, so the files of runs on different rank counts are compared vertex by vertex
(rows sorted by the vertex coordinates). Writes a JSON summary for the harness's checks.

usage: cl_h5check.py ck A.h5 B.h5 OUT.json       two checkpoints: the vertex datasets of A against B's
       cl_h5check.py out A.h5 A.xmf B.h5 OUT.json  a fields file: its shapes, the .xmf's datasets, its fields against B's
"""
import json
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np


def sorted_rows(x, dim):
    """The permutation that sorts the vertices (rows of x, dim columns) by their coordinates."""
    x = np.asarray(x).reshape(-1, dim)
    return np.lexsort(tuple(x[:, d] for d in reversed(range(dim))))


def rel_diff(a, b):
    return float(np.abs(a - b).max() / max(np.abs(a).max(), np.abs(b).max(), 1e-300)) if a.size else 0.0


def ck(fa, fb):
    out = {}
    with h5py.File(fa, "r") as A, h5py.File(fb, "r") as B:
        ga, gb = A["checkpoint"], B["checkpoint"]
        dim, nv = int(ga.attrs["dim"]), int(ga.attrs["vertices"])
        out.update(dim=dim, vertices=nv, vertices_b=int(gb.attrs["vertices"]))
        pa, pb = sorted_rows(ga["coordinates"][()], dim), sorted_rows(gb["coordinates"][()], dim)
        diffs, names = {}, []
        for name in sorted(ga):
            n = ga[name].shape[0]
            if name in ("history", "problem_moments", "materials") or n == 0 or n % nv or n // nv > dim or name not in gb:
                continue
            bs = n // nv
            a, b = ga[name][()].reshape(nv, bs)[pa], gb[name][()].reshape(nv, bs)[pb]
            diffs[name] = rel_diff(a, b)
            names.append(name)
        out["vertex_datasets"] = names
        out["diffs"] = diffs
        out["max_diff"] = max(diffs.values()) if diffs else None
        out["same_names"] = sorted(ga) == sorted(gb)
        # the partition-independent numbers must be equal
        out["history_diff"] = rel_diff(ga["history"][()], gb["history"][()]) if ga["history"].shape == gb["history"].shape else None
    return out


def out(fh, fx, fref):
    res = {}
    with h5py.File(fh, "r") as F, h5py.File(fref, "r") as R:
        x, c = F["geometry/vertices"], F["viz/topology/cells"]
        res.update(vertices=x.shape[0], dim=x.shape[1], cells=c.shape[0], cell_size=c.shape[1])
        shapes = {}
        F.visititems(lambda n, o: shapes.__setitem__("/" + n, list(o.shape)) if isinstance(o, h5py.Dataset) else None)
        res["vertex_fields_rows"] = sorted({shapes[k][0] for k in shapes if k.startswith("/vertex_fields/")})
        res["cell_fields_rows"] = sorted({shapes[k][0] for k in shapes if k.startswith("/cell_fields/")})
        # every HDF DataItem of the .xmf: a dataset of this file with the shape it states
        bad, n = [], 0
        for it in ET.parse(fx).iter("DataItem"):
            if it.get("Format") != "HDF":
                continue
            n += 1
            fname, path = it.text.strip().split(":", 1)
            dims = [int(v) for v in it.get("Dimensions").split()]
            if fname != os.path.basename(fh) or path not in shapes or (shapes[path] + [1])[:len(dims)] != dims:
                bad.append("%s %s %s" % (it.text.strip(), dims, shapes.get(path)))
        res.update(xmf_items=n, xmf_bad=bad)
        # the fields against the reference file's, vertex by vertex and cell by cell (cells by their centroids)
        dim = res["dim"]
        pa, pb = sorted_rows(x[()], dim), sorted_rows(R["geometry/vertices"][()], dim)
        res["geometry_diff"] = rel_diff(x[()][pa], R["geometry/vertices"][()][pb])
        diffs = {}
        for k in F["vertex_fields"]:
            a, b = F["vertex_fields"][k][()], R["vertex_fields"][k][()]
            diffs[k] = rel_diff(a[pa], b[pb])

        def centroids(G):
            return G["geometry/vertices"][()][G["viz/topology/cells"][()]].mean(axis=1)
        ca, cb = sorted_rows(centroids(F), dim), sorted_rows(centroids(R), dim)
        for k in F["cell_fields"]:
            a, b = F["cell_fields"][k][()], R["cell_fields"][k][()]
            diffs[k] = rel_diff(a[ca], b[cb])
        res["diffs"] = diffs
        res["max_diff"] = max(diffs.values()) if diffs else None
    return res


def main():
    mode = sys.argv[1]
    res = ck(sys.argv[2], sys.argv[3]) if mode == "ck" else out(sys.argv[2], sys.argv[3], sys.argv[4])
    with open(sys.argv[-1], "w") as f:
        json.dump(res, f, indent=1)
    print(json.dumps(res))


if __name__ == "__main__":
    main()
