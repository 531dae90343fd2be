#!/usr/bin/python3
"""The load-displacement curve of a run with load steps: total contact force against the load factor (and against
the obstacle's displacement when -obstacle_translation moved it), from the CSV of -load_curve_file, as a PNG.

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
    t = [0.0] + [r["load_factor"] for r in rows]
    F = [0.0] + [r["contact_force"] for r in rows]
    u = [0.0] + [r["obstacle_displacement"] for r in rows]
    moved = any(x > 0 for x in u)
    fig, axes = plt.subplots(1, 2 if moved else 1, figsize=(10 if moved else 5.5, 4), squeeze=False)
    ax = axes[0][0]
    ax.plot(t, F, "o-")
    ax.set_xlabel("load factor t")
    ax.set_ylabel("total contact force")
    ax.grid(True, alpha=0.3)
    if moved:
        ax = axes[0][1]
        ax.plot(u, F, "o-")
        ax.set_xlabel("obstacle displacement (indentation)")
        ax.set_ylabel("total contact force")
        ax.grid(True, alpha=0.3)
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
