#!/usr/bin/python3
"""Map of the contact pressure on the contact face of a 3D result (HDF5 from bin/signorini), seen from below.

usage: plot_pressure.py RESULT.h5 OUT.png [TITLE]
"""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_mesh import boundary_faces, load  # noqa: E402


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    d = load(sys.argv[1])
    if d["x"].shape[1] != 3 or "pressure" not in d:
        sys.exit("plot_pressure.py: %s is not a 3D contact result" % sys.argv[1])
    faces, _ = boundary_faces(d["cells"])
    on = np.linalg.norm(d["obstacle"], axis=1) > 0          # contact vertices carry the obstacle offset
    faces = faces[on[faces].all(axis=1)]
    x, p = d["x"], d["pressure"]
    fig, ax = plt.subplots(figsize=(5, 8))
    t = ax.tripcolor(x[:, 0], x[:, 1], faces, p, shading="gouraud", cmap="inferno")
    ax.tricontour(x[:, 0], x[:, 1], faces, d["active"], levels=[0.5], colors="c", linewidths=0.8)
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_title((sys.argv[3] if len(sys.argv) > 3 else "contact pressure on the bottom face") + "\n(cyan: edge of the active set)")
    fig.colorbar(t, ax=ax, label="contact pressure", shrink=0.7)
    tmp = sys.argv[2] + ".part.png"
    fig.savefig(tmp, dpi=150, bbox_inches="tight")
    os.replace(tmp, sys.argv[2])


if __name__ == "__main__":
    main()
