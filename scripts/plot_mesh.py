#!/usr/bin/python3
"""Picture of the deformed mesh from a result file of bin/signorini (HDF5).

2D: the deformed triangles coloured by a cell field, and the obstacle (gap magnified like the displacement).
3D: the deformed boundary surface coloured by a cell field, seen from below (plot_pressure.py maps the contact pressure).
The magnification defaults to the one stored by -output_magnification. The PNG is written atomically.

usage: plot_mesh.py RESULT.h5 OUT.png [--field shear_energy_density|von_mises] [--magnify M] [--title TEXT]
"""
import argparse
import os
import sys

import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def dataset(group, name):
    """PETSc names a field <vector>_<section field>; find it by the vector's name."""
    for k in group:
        if k == name or k.startswith(name + "_"):
            return group[k][()]
    raise KeyError("no field %s in %s" % (name, group.name))


def load(path):
    with h5py.File(path, "r") as f:
        d = {"x": f["geometry/vertices"][()], "cells": f["viz/topology/cells"][()].astype(int),
             "u": dataset(f["vertex_fields"], "displacement"), "mag": float(f.attrs.get("magnification", 1.0))}
        for name in ("shear_energy_density", "von_mises"):
            d[name] = dataset(f["cell_fields"], name)
        try:
            d["obstacle"] = dataset(f["vertex_fields"], "obstacle_offset")
            d["active"] = dataset(f["vertex_fields"], "active")
            d["pressure"] = dataset(f["vertex_fields"], "contact_pressure")
        except KeyError:
            pass
    return d


def boundary_faces(cells):
    faces = np.concatenate([cells[:, [0, 1, 2]], cells[:, [0, 1, 3]], cells[:, [0, 2, 3]], cells[:, [1, 2, 3]]])
    owner = np.tile(np.arange(len(cells)), 4)
    key = np.sort(faces, axis=1)
    _, idx, cnt = np.unique(key, axis=0, return_index=True, return_counts=True)
    keep = idx[cnt == 1]
    return faces[keep], owner[keep]


def plot2d(d, field, mag, ax):
    xd = d["x"] + mag * d["u"]
    tpc = ax.tripcolor(xd[:, 0], xd[:, 1], d["cells"], facecolors=d[field], cmap="viridis", edgecolors="k", linewidth=0.05)
    if "obstacle" in d:
        on = np.linalg.norm(d["obstacle"], axis=1) > 0
        xo = d["x"][on] + mag * d["obstacle"][on]
        order = np.argsort(xo[:, 0])
        ax.plot(xo[order, 0], xo[order, 1], "r-", lw=1.2, label="obstacle (gap x%g)" % mag)
        ax.legend(loc="lower left", fontsize=8)
    ax.set_aspect("equal")
    ax.set_xlabel("x1")
    ax.set_ylabel("x2")
    return tpc


def plot3d(d, field, mag, fig):
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    ax = fig.add_subplot(111, projection="3d")
    xd = d["x"] + mag * d["u"]
    faces, owner = boundary_faces(d["cells"])
    vals = d[field][owner]
    norm = plt.Normalize(vals.min(), vals.max())
    cmap = plt.get_cmap("viridis")
    pc = Poly3DCollection(xd[faces], facecolors=cmap(norm(vals)), edgecolors=(0, 0, 0, 0.15), linewidths=0.1)
    ax.add_collection3d(pc)
    lo, hi = xd.min(axis=0), xd.max(axis=0)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(hi - lo)
    ax.view_init(elev=-25, azim=-60)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
    sm = plt.cm.ScalarMappable(norm=norm, cmap=cmap)
    sm.set_array([])
    return sm, ax


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("h5")
    ap.add_argument("png")
    ap.add_argument("--field", default="shear_energy_density", choices=["shear_energy_density", "von_mises"])
    ap.add_argument("--magnify", type=float, default=None)
    ap.add_argument("--title", default=None)
    opt = ap.parse_args()
    if not os.path.exists(opt.h5):
        sys.exit("plot_mesh.py: no result file %s" % opt.h5)
    d = load(opt.h5)
    mag = d["mag"] if opt.magnify is None else opt.magnify
    dim = d["x"].shape[1]
    label = {"shear_energy_density": "elastic shear energy density", "von_mises": "von Mises stress"}[opt.field]
    if dim == 2:
        fig, ax = plt.subplots(figsize=(10, 4.2))
        m = plot2d(d, opt.field, mag, ax)
        fig.colorbar(m, ax=ax, label=label, shrink=0.8)
    else:
        fig = plt.figure(figsize=(9, 7))
        m, ax = plot3d(d, opt.field, mag, fig)
        fig.colorbar(m, ax=ax, label=label, shrink=0.6)
    ax.set_title(opt.title or "deformed mesh, displacement x%g, coloured by %s" % (mag, label))
    tmp = opt.png + ".part.png"
    fig.savefig(tmp, dpi=150, bbox_inches="tight")
    os.replace(tmp, opt.png)


if __name__ == "__main__":
    main()
