#!/usr/bin/python3
"""Friction between two elastic bodies (tests/*/twobody_friction.ini), checked from the output fields of the slave side.

patch: the blocks of meshes/tbf_stack2d.geo / tbf_stack3d.geo (the slave side the plane of the last coordinate = --zs)
under a uniform stress with normal pressure -p and shear q (along x) across the contact: every slave vertex is
active, with pressure p and tangential traction (q, 0[, 0]) up to its sign (the field holds the traction on the master
side), and (stick) no slip. Reports the counts of slave, active, stick and slip vertices, max |p_i / p - 1|,
max ||lam_T,i| / q - 1|, the largest component of lam_T off x relative to q, and the largest slip |u_T,i| and, with
--slip S, max |u_T,i.e_x / S - 1| (a uniform slip S along x expected).

cattaneo: a half disc of radius R (the arc x^2 + (y - R)^2 = R^2 below y = R: the slave side) on a block (master),
pressed by P per unit thickness, then loaded tangentially by Q < F P; elastically similar bodies, so that the normal
and tangential problems decouple (Dundurs' beta = 0) and Cattaneo-Mindlin holds: c / a = (1 - Q / (F P))^(1/2).
P = sum_i w_i p_i and Q = |sum_i w_i lam_T,i.e_x| with w_i the lumped weights of the arc; a = half the summed weights
of the active vertices, c = half the summed weights of the stick vertices (within h/2 of the zones' edges for a vertex
spacing h); Hertz's a^2 = 4 P R* / (pi E*), 1/E* = 2 (1 - nu^2) / E, R* = R (a flat block). Every load step of each
file, a row each.

usage: tbf_fields.py patch --out OUT.json -p P -q Q --zs Z [--slip S] RESULT.h5
       tbf_fields.py cattaneo --out OUT.json -E E -nu NU -R R -F F RESULT.h5 ...
"""
import argparse
import math
import os
import re

import h5py
import numpy as np

from cv_patch import report


def field(group, name, step):
    """The vertex field name (of load step `step`, None: without steps) as an array, or None."""
    pat = re.compile(r"^%s%s_[a-z]+$" % (re.escape(name), "" if step is None else "_step%d" % step))
    for k in group:
        if pat.match(k):
            return group[k][()]
    return None


def steps(f):
    ks = sorted({int(m.group(1)) for k in f["vertex_fields"] for m in [re.search(r"_step(\d+)_", k)] if m})
    return ks or [None]


def patch(a):
    with h5py.File(a.result, "r") as f:
        x = f["geometry/vertices"][()]
        g = f["vertex_fields"]
        st = steps(f)[-1]
        p, act = field(g, "contact_pressure", st).ravel(), field(g, "active", st).ravel() > 0.5
        lt, sl, fs = field(g, "tangential_traction", st), field(g, "slip", st), field(g, "friction_state", st).ravel().round()
    dim = x.shape[1]
    on = np.abs(x[:, dim - 1] - a.zs) < 1e-9
    lt, sl = lt.reshape(-1, dim)[on], sl.reshape(-1, dim)[on]
    res = {"slave": int(on.sum()), "active": int((act & on).sum()), "stick": int((fs[on] == 1).sum()),
           "slip": int((fs[on] == 2).sum()), "active_elsewhere": int((act & ~on).sum()),
           "pressure_dev": float(np.abs(p[on] / a.p - 1).max()),
           "traction_dev": float(np.abs(np.linalg.norm(lt, axis=1) / a.q - 1).max()),
           "traction_off_x": float(np.abs(lt[:, 1:]).max() / a.q),
           "traction_x_sign": float(np.sign(lt[:, 0]).min() * np.sign(lt[:, 0]).max()),
           "slip_max": float(np.linalg.norm(sl, axis=1).max())}
    if a.slip is not None:
        res["slip_dev"] = float(np.abs(sl[:, 0] / a.slip - 1).max())
    report(res, a.out)


def arc_weights(x, cells, R):
    """The arc's vertices and lumped weights (half of each arc edge's length per vertex)."""
    on = (np.abs(np.hypot(x[:, 0], x[:, 1] - R) - R) < 1e-9 * R) & (x[:, 1] < R * (1 - 1e-9))
    w = np.zeros(len(x))
    for c in cells:
        e = [v for v in c if on[v]]
        if len(e) == 2:
            w[e] += np.linalg.norm(x[e[1]] - x[e[0]]) / 2
    return w, on


def cattaneo(a):
    rows = []
    for path in a.result:
        rows += cattaneo_file(a, path)
    import json
    import os
    print("\n".join(" ".join("%s %.6g" % (k, v) for k, v in r.items() if isinstance(v, (int, float))) for r in rows))
    tmp = a.out + ".tmp"
    with open(tmp, "w") as fo:
        json.dump({"rows": rows}, fo, indent=1)
    os.replace(tmp, a.out)


def cattaneo_file(a, path):
    rows = []
    with h5py.File(path, "r") as f:
        x = f["geometry/vertices"][()]
        cells = f["viz/topology/cells"][()].astype(int)
        w, on = arc_weights(x, cells, a.R)
        Es = a.E / (2 * (1 - a.nu ** 2))
        for st in steps(f):
            g = f["vertex_fields"]
            p, act = field(g, "contact_pressure", st).ravel(), field(g, "active", st).ravel() > 0.5
            lt, fs = field(g, "tangential_traction", st).reshape(-1, 2), field(g, "friction_state", st).ravel().round()
            P, Q = float(np.dot(w, p)), abs(float(np.dot(w, lt[:, 0])))
            aa = float(w[act & on].sum()) / 2
            c = float(w[(fs == 1) & on].sum()) / 2
            aH = math.sqrt(4 * P * a.R / (math.pi * Es))
            xs = np.sort(x[on & (np.abs(x[:, 0]) <= 1.2 * aH), 0])
            h = float(np.diff(xs).max())
            ratio = Q / (a.F * P) if P > 0 else float("nan")
            th = math.sqrt(max(0.0, 1 - ratio))
            rows.append({"file": os.path.basename(path), "step": st, "P": P, "Q": Q, "Q_over_FP": ratio, "a": aa, "a_hertz": aH, "h": h, "h_over_a": h / aH,
                         "c": c, "c_over_a": c / aa if aa > 0 else float("nan"), "c_over_a_theory": th,
                         "c_over_a_err": abs(c / aa - th) if aa > 0 else float("nan"),
                         "stick": int(((fs == 1) & on).sum()), "slip": int(((fs == 2) & on).sum()), "active": int((act & on).sum())})
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mode", choices=("patch", "cattaneo"))
    ap.add_argument("--out", required=True)
    ap.add_argument("-p", type=float)
    ap.add_argument("-q", type=float)
    ap.add_argument("--zs", type=float)
    ap.add_argument("--slip", type=float)
    ap.add_argument("-E", type=float)
    ap.add_argument("-nu", type=float)
    ap.add_argument("-R", type=float)
    ap.add_argument("-F", type=float)
    ap.add_argument("result", nargs="+")
    a = ap.parse_args()
    if a.mode == "patch":
        a.result = a.result[0]
    (patch if a.mode == "patch" else cattaneo)(a)


if __name__ == "__main__":
    main()
