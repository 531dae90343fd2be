#!/usr/bin/python3
"""The fields of a two-body run (tests/*/twobody_fields.ini): its .h5 and the .xmf beside it, read back as ParaView would.

Checks, reported in a JSON summary:
  - the .xmf is valid and names its datasets right (check_xdmf.check_xmf), with the attributes "body" (a cell field)
    and "master_pressure" (a vertex field) among them;
  - body: the mesh's connected parts (cells joined through shared vertices, found here on their own) each take one
    value, different parts different values, the values exactly 1..n (n_parts, body_values, body_split_ok);
    with --split Z: the cells whose centroid lies below Z along the last axis are body 1, those above body 2;
  - with --pressure P (a flat patch test under the uniform pressure P, the master side the top of the
    lower body): the largest
    relative deviation from P of the slave's contact_pressure at its active vertices (slave_dev) and of
    master_pressure at the master's vertices on that plane (master_dev, master_on_plane: their number, master_set:
    how many of them have a value); the projected force sum_k W_k p_k over the master's facets on the plane
    (master_force, W_k the lumped facet weights);
  - max_slave, max_master: the largest pressures on either side; p0_slave, p0_master: each side's pressure at the
    vertex nearest the origin where it is not 0 (a Hertz run touching there: the peak pressure seen from both sides);
  - with --step K (a run with load steps): the fields of load step K (datasets <name>_stepK_...);
  - has_body, has_master_pressure: whether the fields are there at all (a run without a pair has neither: the rest
    is then left out).

usage: tb_fields.py --out OUT.json [--split Z] [--pressure P] [--step K] RESULT.h5
"""
import argparse
import json
import os

import h5py
import numpy as np

from check_xdmf import check_xmf
from cv_patch import dataset


def components(cells, nvert):
    par = np.arange(nvert)

    def root(v):
        while par[v] != v:
            par[v] = par[par[v]]
            v = par[v]
        return v

    for c in cells:
        r0 = root(c[0])
        for v in c[1:]:
            r = root(v)
            if r != r0:
                par[r] = r0
    return np.array([root(c[0]) for c in cells])


def boundary_facets(cells):
    count = {}
    k = cells.shape[1]
    for c in cells:
        for j in range(k):
            f = tuple(sorted(np.delete(c, j)))
            count[f] = count.get(f, 0) + 1
    return [f for f, n in count.items() if n == 1]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True)
    ap.add_argument("--split", type=float)
    ap.add_argument("--pressure", type=float)
    ap.add_argument("--step", type=int)
    ap.add_argument("result")
    a = ap.parse_args()
    xmf = os.path.splitext(a.result)[0] + ".xmf"
    res = {"xmf_problems": check_xmf(xmf, a.result, None)}
    import xml.etree.ElementTree as ET
    attrs = {(at.get("Name"), at.get("Center")) for at in ET.parse(xmf).getroot().iter("Attribute")}
    res["xmf_body"] = ("body", "Cell") in attrs
    res["xmf_master_pressure"] = ("master_pressure", "Node") in attrs
    sfx = "_step%d" % a.step if a.step is not None else ""
    with h5py.File(a.result, "r") as f:
        res["has_body"] = any(k.startswith("body" + sfx + "_") for k in f["cell_fields"])
        res["has_master_pressure"] = any(k.startswith("master_pressure" + sfx + "_") for k in f["vertex_fields"])
        if not (res["has_body"] and res["has_master_pressure"]):
            with open(a.out, "w") as g:
                json.dump(res, g, indent=1)
            return
        x = f["geometry/vertices"][()]
        cells = f["viz/topology/cells"][()].astype(int)
        body = dataset(f["cell_fields"], "body" + sfx).ravel()
        p = dataset(f["vertex_fields"], "contact_pressure" + sfx).ravel()
        mp = dataset(f["vertex_fields"], "master_pressure" + sfx).ravel()
        act = dataset(f["vertex_fields"], "active" + sfx).ravel() > 0.5
    dim = x.shape[1]
    comp = components(cells, len(x))
    parts = np.unique(comp)
    vals = [np.unique(body[comp == r]) for r in parts]
    res["n_parts"] = int(len(parts))
    res["one_value_per_part"] = all(len(v) == 1 for v in vals)
    res["body_values"] = sorted(float(v[0]) for v in vals)
    res["body_values_ok"] = res["one_value_per_part"] and res["body_values"] == [float(k + 1) for k in range(len(parts))]
    if a.split is not None:
        zc = x[cells][:, :, dim - 1].mean(axis=1)
        res["body_split_ok"] = bool(np.all(body[zc < a.split] == 1) and np.all(body[zc > a.split] == 2))
    res["max_slave"] = float(p.max())
    res["max_master"] = float(mp.max())
    res["master_nonzero"] = int(np.count_nonzero(mp))
    near = np.argsort(np.linalg.norm(x, axis=1))
    res["p0_slave"] = float(next((p[i] for i in near if p[i] != 0), 0.0))
    res["p0_master"] = float(next((mp[i] for i in near if mp[i] != 0), 0.0))
    if a.pressure is not None:
        assert a.split is not None, "--pressure needs --split"
        P = a.pressure
        res["slave_active"] = int(act.sum())
        res["slave_dev"] = float(np.max(np.abs(p[act] - P)) / P)
        # the master's vertices: the top plane of body 1 (the lower block)
        zc = x[cells][:, :, dim - 1].mean(axis=1)
        lowerv = np.zeros(len(x), bool)
        lowerv[cells[zc < a.split].ravel()] = True
        ztop = x[lowerv, dim - 1].max()
        plane = lowerv & (np.abs(x[:, dim - 1] - ztop) < 1e-9)
        res["master_on_plane"] = int(plane.sum())
        res["master_set"] = int(np.count_nonzero(mp[plane]))
        res["master_dev"] = float(np.max(np.abs(mp[plane] - P)) / P)
        res["master_off_plane_max"] = float(np.max(np.abs(mp[~plane]))) if (~plane).any() else 0.0
        W = np.zeros(len(x))
        for fc in boundary_facets(cells):
            fc = list(fc)
            if not plane[fc].all():
                continue
            y = x[fc]
            size = 0.5 * np.linalg.norm(np.cross(y[1] - y[0], y[2] - y[0])) if dim == 3 else np.linalg.norm(y[1] - y[0])
            W[fc] += size / dim
        res["master_force"] = float(np.sum(W * mp))
    with open(a.out, "w") as f:
        json.dump(res, f, indent=1)


if __name__ == "__main__":
    main()
