#!/usr/bin/python3
"""The load-displacement curve of a run with load steps: total contact force against the load factor and against the
approach of body and obstacle, from the CSV of -load_curve_file, as a PNG.

usage: load_curve.py CURVE.csv OUT.png [--title TEXT]
"""
import argparse
import csv
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def plot(rows, out, title=""):
    """Force against the load factor, and against the approach of body and obstacle: the obstacle's displacement plus
    the largest normal displacement of the contact boundary towards it (the indentation of a punch or ball test)."""
    t = [0.0] + [r["load_factor"] for r in rows]
    F = [0.0] + [r["contact_force"] for r in rows]
    a = [0.0] + [r["obstacle_displacement"] + r["normal_displacement_max"] for r in rows]
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, x, label in ((axes[0], t, "load factor t"), (axes[1], a, "approach: obstacle displacement + largest normal displacement")):
        ax.plot(x, F, "o-")
        ax.set_xlabel(label)
        ax.set_ylabel("total contact force")
        ax.grid(True, alpha=0.3)
        ax.ticklabel_format(axis="both", style="sci", scilimits=(-3, 4))
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out + ".part.png", dpi=150, bbox_inches="tight")
    os.replace(out + ".part.png", out)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv")
    ap.add_argument("png")
    ap.add_argument("--title", default="")
    opt = ap.parse_args()
    plot(read(opt.csv), opt.png, opt.title)
    print("wrote %s" % opt.png)


if __name__ == "__main__":
    main()
