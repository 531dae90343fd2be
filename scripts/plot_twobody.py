#!/usr/bin/python3
"""Picture of a two-body run in 2D (a contact pair, -contact_master_ids) from its HDF5 result.

Left: the deformed bodies near the contact (displacement magnified) coloured by the von Mises stress, the cell field
`body` as each body's outline. Right: the pressure along the interface against x, the slave's
`contact_pressure` and the master's `master_pressure` (its mortar projection), and with --estar/--rhertz/--force the
Hertz profile p0 (1 - (x/a)^2)^1/2 of two cylinders at that force per unit length (a = (4 P R / (pi E*))^1/2,
p0 = 2 P / (pi a)). The PNG is written atomically.

usage: plot_twobody.py RESULT.h5 OUT.png [--estar E* --rhertz R --force P] [--window W] [--title TEXT]
"""
import argparse
import math
import os

import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from plot_mesh import dataset  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("result")
    ap.add_argument("out")
    ap.add_argument("--estar", type=float)
    ap.add_argument("--rhertz", type=float)
    ap.add_argument("--force", type=float, help="the force per unit length of the whole pair (Hertz's P)")
    ap.add_argument("--window", type=float, default=0.25, help="half width of the picture around the origin")
    ap.add_argument("--magnify", type=float, default=1.0)
    ap.add_argument("--title", default="")
    a = ap.parse_args()
    with h5py.File(a.result, "r") as f:
        x = f["geometry/vertices"][()]
        cells = f["viz/topology/cells"][()].astype(int)
        u = dataset(f["vertex_fields"], "displacement")
        vm = dataset(f["cell_fields"], "von_mises").ravel()
        body = dataset(f["cell_fields"], "body").ravel()
        p = dataset(f["vertex_fields"], "contact_pressure").ravel()
        mp = dataset(f["vertex_fields"], "master_pressure").ravel()
    assert x.shape[1] == 2, "plot_twobody.py draws 2D results"
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.8), gridspec_kw={"width_ratios": [1.1, 1]})
    xd = x + a.magnify * u
    W = a.window
    near = np.all(np.abs(x[cells]).max(axis=1) < 2.5 * W, axis=1)
    tpc = ax.tripcolor(xd[:, 0], xd[:, 1], cells[near], facecolors=vm[near], cmap="viridis", edgecolors="k", linewidth=0.08)
    for b, col in zip(sorted(set(body)), ("tab:red", "tab:orange", "tab:pink", "tab:cyan")):
        count = {}  # the outline of body b: the edges of one of its cells
        for c in cells[body == b]:
            for e in ((c[0], c[1]), (c[1], c[2]), (c[2], c[0])):
                k = tuple(sorted(e))
                count[k] = count.get(k, 0) + 1
        for k, n in count.items():
            if n == 1:
                ax.plot(xd[list(k), 0], xd[list(k), 1], color=col, lw=1.5)
        ax.plot([], [], color=col, lw=1.5, label="body %d" % b)
    ax.set_xlim(-0.05 * W, W)
    ax.set_ylim(-0.6 * W, 0.4 * W)
    ax.set_aspect("equal")
    ax.legend(loc="lower right", fontsize=8)
    ax.set_title("deformed (x%g), von Mises" % a.magnify, fontsize=10)
    fig.colorbar(tpc, ax=ax, shrink=0.8)
    s, m = p != 0, mp != 0
    os_, om = np.argsort(x[s, 0]), np.argsort(x[m, 0])
    bx.plot(x[s, 0][os_], p[s][os_], "o-", ms=3, lw=1, label="slave: contact_pressure")
    bx.plot(x[m, 0][om], mp[m][om], "s--", ms=3, lw=1, label="master: master_pressure (projection)")
    if a.estar and a.rhertz and a.force:
        ah = math.sqrt(4 * a.force * a.rhertz / (math.pi * a.estar))
        p0 = 2 * a.force / (math.pi * ah)
        xs = np.linspace(0, ah, 200)
        bx.plot(xs, p0 * np.sqrt(1 - (xs / ah) ** 2), "k-", lw=0.8, label="Hertz at the run's force (a = %.4g)" % ah)
    bx.set_xlim(0, W)
    bx.set_xlabel("x1 (reference position)")
    bx.set_ylabel("pressure")
    bx.legend(fontsize=8)
    bx.set_title("pressure on both sides of the interface", fontsize=10)
    if a.title:
        fig.suptitle(a.title)
    fig.savefig(a.out + ".part.png", dpi=150, bbox_inches="tight")
    os.replace(a.out + ".part.png", a.out)
    plt.close(fig)


if __name__ == "__main__":
    main()
