#!/usr/bin/python3
"""Two materials in series (tests/*/materials.ini): the displacement of a result against the exact piecewise-linear
field of a bar or layered block loaded along one axis, with rollers on the lateral faces (uniaxial strain: the
stress s is the same in both layers and the strain in layer i is s / M_i, M_i = E_i (1 - nu_i) / ((1 + nu_i)
(1 - 2 nu_i)) the constrained modulus; with -free, lateral faces free and nu = 0: M_i = E_i). The layers are
x_a < xi (material E[0], nu[0]) and x_a > xi (E[1], nu[1]) along the axis a, from x0 = min x_a to x1 = max x_a. The
stress is -stress S, or, with -closing U0 U1, the one that takes the end x0 to U0 and x1 to U1 (a bar pushed by U0
against a rigid plane that stops its end at U1). Writes a JSON summary: err (largest |u - u_exact| over the vertices,
relative to the largest |u_exact|), stress, the force it makes on the end face (stress times the face's area, from
the mesh's extent) and the exact end displacements; with a von Mises cell field, vm_err: its largest error relative
to |s| against the exact 2 mu_i |s| / M_i of each layer (uniaxial strain; |s| with -free), by the cell centroid.

usage: materials.py --out OUT.json -axis A -xi XI -E E0,E1 -nu NU0,NU1 (-stress S | -closing U0 U1) [-free] RESULT.h5
"""
import argparse
import json
import os

import h5py
import numpy as np


def dataset(group, name):
    for k in group:  # PETSc names a field <vector>_<section field>
        if k == name or k.startswith(name + "_"):
            return group[k][()]
    raise KeyError("no field %s in %s" % (name, group.name))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", required=True)
    ap.add_argument("-axis", type=int, required=True)
    ap.add_argument("-xi", type=float, required=True)
    ap.add_argument("-E", required=True)
    ap.add_argument("-nu", required=True)
    ap.add_argument("-stress", type=float)
    ap.add_argument("-closing", type=float, nargs=2)
    ap.add_argument("-free", action="store_true")
    ap.add_argument("result")
    a = ap.parse_args()
    E = [float(v) for v in a.E.split(",")]
    nu = [float(v) for v in a.nu.split(",")]
    M = [e if a.free else e * (1 - n) / ((1 + n) * (1 - 2 * n)) for e, n in zip(E, nu)]
    with h5py.File(a.result, "r") as f:
        x = f["geometry/vertices"][()]
        u = dataset(f["vertex_fields"], "displacement")
        cells = f["viz/topology/cells"][()].astype(int)
        vm = dataset(f["cell_fields"], "von_mises") if "cell_fields" in f else None
    ax = a.axis
    x0, x1 = float(x[:, ax].min()), float(x[:, ax].max())
    flex = (a.xi - x0) / M[0] + (x1 - a.xi) / M[1]  # end displacement per unit stress
    if a.closing:
        u0 = a.closing[0]
        s = (a.closing[1] - a.closing[0]) / flex
    else:
        u0 = 0.0
        s = a.stress
    xa = x[:, ax]
    ue = np.zeros_like(u)
    ue[:, ax] = u0 + s * np.where(xa < a.xi, (xa - x0) / M[0], (a.xi - x0) / M[0] + (xa - a.xi) / M[1])
    area = float(np.prod([np.ptp(x[:, d]) for d in range(x.shape[1]) if d != ax]))
    err = float(np.abs(u - ue).max() / np.abs(ue).max())
    vm_err = None
    if vm is not None:
        mu = [e / (2 * (1 + n)) for e, n in zip(E, nu)]
        side = x[cells].mean(axis=1)[:, ax] > a.xi
        vme = np.where(side, 1.0 if a.free else 2 * mu[1] / M[1], 1.0 if a.free else 2 * mu[0] / M[0]) * abs(s)
        vm_err = float(np.abs(vm.ravel() - vme).max() / abs(s))
    out = {"err": err, "vm_err": vm_err, "stress": s, "force": abs(s) * area, "u_end": u0 + s * flex, "u_start": u0, "vertices": len(x)}
    print("%s: max |u - u_exact| / max |u_exact| = %.3e, von Mises error %s, stress %.12g, end force %.12g" % (os.path.basename(a.result), err, vm_err, s, out["force"]))
    with open(a.out + ".part", "w") as f:
        json.dump(out, f, indent=1)
    os.replace(a.out + ".part", a.out)


if __name__ == "__main__":
    main()
