#!/usr/bin/python3
"""Stick, slip and free states on the contact boundary of a frictional result (HDF5 from bin/signorini).

2D: along the contact boundary (x), the normal pressure lam_N, the tangential traction lam_T (its x component) inside
the admissible band |lam_T| <= g (g = F lam_N for Coulomb, the bound s for Tresca), the vertices' states as coloured
bands; a strip above shows the states along the whole boundary, the main panel the part in contact.
3D: the contact face in the (x, y) plane (as results/fig8_pressure.png), vertices coloured by state, arrows of the
tangential traction (x, y components) at stick and slip vertices.

usage: plot_friction.py RESULT.h5 OUT.png (--coefficient F | --bound s) [--title TEXT]
"""
import argparse
import os
import sys

import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_mesh import boundary_faces, dataset  # noqa: E402

STATES = [("free", "0.8"), ("stick", "tab:blue"), ("slip", "tab:red")]  # friction_state 0, 1, 2


def load(path):
    with h5py.File(path, "r") as f:
        g = f["vertex_fields"]
        try:
            d = {"x": f["geometry/vertices"][()], "cells": f["viz/topology/cells"][()].astype(int),
                 "state": dataset(g, "friction_state").ravel().round().astype(int), "lt": dataset(g, "tangential_traction"),
                 "p": dataset(g, "contact_pressure").ravel(), "obstacle": dataset(g, "obstacle_offset")}
        except KeyError as e:
            sys.exit("plot_friction.py: %s is not a frictional contact result (%s)" % (path, e))
    d["on"] = np.linalg.norm(d["obstacle"], axis=1) > 0  # contact vertices carry the obstacle offset
    return d


def counts(d):
    return ", ".join("%d %s" % ((d["state"][d["on"]] == k).sum(), name) for k, (name, _) in enumerate(STATES))


def bands(ax, x, state, y0, y1):
    """Each vertex's state as a band from halfway to its left neighbour to halfway to its right one."""
    mid = np.concatenate([[x[0]], 0.5 * (x[1:] + x[:-1]), [x[-1]]])
    for k, (_, colour) in enumerate(STATES):
        for i in np.where(state == k)[0]:
            ax.axvspan(mid[i], mid[i + 1], ymin=y0, ymax=y1, color=colour, lw=0)


def plot2d(d, opt):
    i = np.where(d["on"])[0]
    i = i[np.argsort(d["x"][i, 0])]
    x, p, lt, st = d["x"][i, 0], d["p"][i], d["lt"][i, 0], d["state"][i]
    g = opt.coefficient * p if opt.coefficient is not None else np.full_like(p, opt.bound)
    fig, (top, ax) = plt.subplots(2, 1, figsize=(10, 6), gridspec_kw={"height_ratios": [1, 6]})
    bands(top, x, st, 0, 1)
    top.set_xlim(x[0], x[-1])
    top.set_yticks([])
    top.set_title(opt.title or "friction states along the contact boundary")
    top.set_xlabel("x (whole contact boundary)", fontsize=8, labelpad=1)
    # the main panel: where a vertex sticks or slips (Tresca: everywhere), with a margin of a fifth of that width
    act = np.where(st > 0)[0]
    lo, hi = (x[act[0]], x[act[-1]]) if len(act) else (x[0], x[-1])
    w = max(hi - lo, 1e-12)
    zoom = (x >= lo - 0.2 * w) & (x <= hi + 0.2 * w)
    ax.fill_between(x[zoom], -g[zoom], g[zoom], color="0.9", label="admissible |lam_T| <= %s" % ("F lam_N" if opt.coefficient is not None else "s"))
    ax.plot(x[zoom], p[zoom], "k-", lw=1.5, label="normal pressure lam_N")
    ax.plot(x[zoom], g[zoom], "k--", lw=1, label="bound F lam_N (F = %g)" % opt.coefficient if opt.coefficient is not None else "bound s = %g" % opt.bound)
    ax.plot(x[zoom], -g[zoom], "k--", lw=1)
    ax.plot(x[zoom], lt[zoom], "-", color="0.4", lw=0.8, zorder=2)
    for k, (name, colour) in enumerate(STATES):
        m = zoom & (st == k)
        ax.plot(x[m], lt[m], "o", ms=3.5, color=colour, label="lam_T (x component), %s" % name, zorder=3)
    ylo, yhi = ax.get_ylim()
    bands(ax, x[zoom], st[zoom], 0, 0.03)
    ax.set_ylim(ylo, yhi)
    ax.set_xlim(x[zoom][0], x[zoom][-1])
    ax.axhline(0, color="0.6", lw=0.5)
    ax.set_xlabel("x (contact zone; bands at the bottom and above: grey free, blue stick, red slip)")
    ax.set_ylabel("traction")
    ax.legend(fontsize=8, loc="upper left")
    ax.text(0.99, 0.97, counts(d), transform=ax.transAxes, ha="right", va="top", fontsize=8)
    return fig


def plot3d(d, opt):
    faces, _ = boundary_faces(d["cells"])
    faces = faces[d["on"][faces].all(axis=1)]
    x, st, lt = d["x"], d["state"], d["lt"]
    v = np.unique(faces)
    c = v[st[v] > 0]
    fig, axes = plt.subplots(1, 2, figsize=(11, 8), gridspec_kw={"width_ratios": [1, 1.6]})
    for ax in axes:
        ax.triplot(x[:, 0], x[:, 1], faces, color="0.85", lw=0.4)
        for k, (name, colour) in enumerate(STATES):
            m = v[st[v] == k]
            ax.plot(x[m, 0], x[m, 1], "o", ms=2 if k == 0 else 3.5, color=colour, label="%s (%d)" % (name, len(m)), zorder=3)
        ax.set_aspect("equal")
        ax.set_xlabel("x")
        ax.set_ylabel("y")
    axes[0].legend(fontsize=8, loc="lower left")
    axes[0].set_title("the whole contact face", fontsize=9)
    if len(c):
        # the right panel: the stick and slip vertices with a margin of a tenth of the face's size, within the face
        flo, fhi = x[v, :2].min(axis=0), x[v, :2].max(axis=0)
        pad = 0.1 * (fhi - flo).max()
        lo, hi = np.maximum(x[c, :2].min(axis=0) - pad, flo), np.minimum(x[c, :2].max(axis=0) + pad, fhi)
        axes[1].set_xlim(lo[0], hi[0])
        axes[1].set_ylim(lo[1], hi[1])
        axes[0].add_patch(plt.Rectangle(lo, *(hi - lo), fill=False, ls="--", lw=0.8))
        q = axes[1].quiver(x[c, 0], x[c, 1], lt[c, 0], lt[c, 1], color="k", width=0.003, zorder=4, angles="xy")
        ref = float("%.1g" % np.linalg.norm(lt[c, :2], axis=1).max())
        axes[1].quiverkey(q, 0.62, 0.04, ref, "|lam_T| = %g" % ref, labelpos="E", coordinates="axes", fontproperties={"size": 8})
    axes[1].set_title("where it sticks or slips; arrows: tangential traction lam_T (x, y)", fontsize=9)
    fig.suptitle("%s: %s" % (opt.title or "friction states on the contact face", counts(d)), fontsize=10, y=0.93)
    return fig


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("h5")
    ap.add_argument("png")
    law = ap.add_mutually_exclusive_group(required=True)
    law.add_argument("--coefficient", type=float, help="Coulomb: the friction coefficient F of the run")
    law.add_argument("--bound", type=float, help="Tresca: the friction bound s of the run")
    ap.add_argument("--title", default=None)
    opt = ap.parse_args()
    if not os.path.exists(opt.h5):
        sys.exit("plot_friction.py: no result file %s" % opt.h5)
    d = load(opt.h5)
    fig = plot2d(d, opt) if d["x"].shape[1] == 2 else plot3d(d, opt)
    tmp = opt.png + ".part.png"
    fig.savefig(tmp, dpi=150, bbox_inches="tight")
    plt.close(fig)
    os.replace(tmp, opt.png)


if __name__ == "__main__":
    main()
