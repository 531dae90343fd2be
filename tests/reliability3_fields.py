#!/usr/bin/env python3
"""Checks of result files for tests/*/outputs.ini (issue 25, items 6 and 7).

  reliability3_fields.py integrals RESULT.h5 SUMMARY.json AXIS VALUE RTOL [STEP]
      The contact fields integrated over Gamma_c against the summary. Gamma_c is taken as the boundary facets (facets
      of one cell only) whose vertices all have coordinate AXIS (0, 1, 2) equal to VALUE, a face of a box; the lumped
      weights w_i = sum of |facet| / (vertices of a facet) are computed here from the mesh in the file. Checked:
      sum w_i p_i = contact_force, sum w_i p_i n = contact_force_vector (n the outward normal of that face), the
      active field's count = active_set_size, and with friction sum w_i lam_T,i = friction_force_vector, the states'
      counts = stick_size and slip_size, and (Coulomb) every active vertex stick or slip, every other one free.
      STEP k (load steps): the fields of step k (datasets *_step<k>_*) against the summary's load_step_* entries of
      that step (contact force, active set size, stick and slip sizes, friction force).
  reliability3_fields.py xmf FILE.xmf [NSTEPS]
      The .xmf parses as XML (xml.etree), and every HDF dataset it names (file:/path, the file relative to the .xmf)
      exists in that file; NSTEPS: a temporal collection of that many grids.
"""
import json
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np


STEP = ""


def field(g, name):
    for k in g:
        if k.startswith(name + STEP + "_") and (STEP or "_step" not in k):
            return g[k][()]
    raise KeyError(name)


def boundary_facets(cells, dim):
    """facets (vertex tuples) of exactly one cell"""
    count = {}
    for c in cells:
        for skip in range(dim + 1):
            f = tuple(sorted(np.delete(c, skip)))
            count[f] = count.get(f, 0) + 1
    return [f for f, n in count.items() if n == 1]


def measure(x):
    if len(x) == 2:
        return np.linalg.norm(x[1] - x[0])
    return 0.5 * np.linalg.norm(np.cross(x[1] - x[0], x[2] - x[0]))


def integrals(h5, js, axis, value, rtol, step=None):
    s = json.load(open(js))
    if step is not None:  # that load step's numbers in the names of the last step's
        global STEP
        STEP = "_step%d" % step
        j = step - 1
        s["contact_force"] = s["load_step_contact_force"][j]
        s["active_set_size"] = s["load_step_active_set_size"][j]
        s["contact_force_vector"] = None
        if "stick_size" in s:
            s["stick_size"], s["slip_size"] = s["load_step_stick_size"][j], s["load_step_slip_size"][j]
            s["friction_force"], s["friction_force_vector"] = s["load_step_friction_force"][j], None
    f = h5py.File(h5, "r")
    x = f["geometry/vertices"][()]
    cells = f["viz/topology/cells"][()].astype(int)
    dim = x.shape[1]
    g = f["vertex_fields"]
    p = field(g, "contact_pressure").ravel()
    act = field(g, "active").ravel().round().astype(int)
    tol = 1e-12 * np.abs(x).max()
    w = np.zeros(len(x))
    for fc in boundary_facets(cells, dim):
        if all(abs(x[v, axis] - value) <= tol for v in fc):
            a = measure(x[list(fc)])
            for v in fc:
                w[v] += a / len(fc)
    onface = w > 0
    n = np.zeros(dim)
    n[axis] = -1.0 if value <= x[:, axis].min() + tol else 1.0
    bad = []
    scale = max(abs(s["contact_force"]), 1e-300)

    def cmp(what, a, b, sc):
        d = np.max(np.abs(np.asarray(a, float) - np.asarray(b, float)))
        print("%s: fields %s, summary %s, difference %.3g (relative %.3g)" % (what, np.round(a, 12), np.round(b, 12), d, d / sc))
        if not d <= rtol * sc:
            bad.append(what)

    if (np.abs(p[~onface]) > 0).any() or (act[~onface] != 0).any():
        bad.append("pressure or active flag off the face AXIS = VALUE (a wrong face?)")
    cmp("contact_force", np.sum(w * p), s["contact_force"], scale)
    if s["contact_force_vector"] is not None:
        cmp("contact_force_vector", np.sum(w * p) * n, s["contact_force_vector"], scale)
        cmp("|contact_force_vector| vs contact_force", np.linalg.norm(s["contact_force_vector"]), s["contact_force"], scale)
    if act.sum() != s["active_set_size"]:
        bad.append("active field counts %d, summary active_set_size %d" % (act.sum(), s["active_set_size"]))
    if "stick_size" in s:
        st = field(g, "friction_state").ravel().round().astype(int)
        lt = field(g, "tangential_traction")
        F = np.sum(w[:, None] * lt, axis=0)
        if s["friction_force_vector"] is not None:
            cmp("friction_force_vector", F, s["friction_force_vector"][:dim], scale)
        cmp("friction_force", np.linalg.norm(F), s["friction_force"], scale)
        nst, nsl = int((st == 1).sum()), int((st == 2).sum())
        print("states: stick %d slip %d active %d; summary stick %d slip %d active %d" % (nst, nsl, act.sum(), s["stick_size"], s["slip_size"], s["active_set_size"]))
        if nst != s["stick_size"] or nsl != s["slip_size"]:
            bad.append("friction states against the summary")
        if s["friction_type"] == "coulomb":
            if ((st > 0) != (act > 0)).any():
                bad.append("Coulomb: %d vertices active but free, or stick/slip but not active" % ((st > 0) != (act > 0)).sum())
            if s["stick_size"] + s["slip_size"] != s["active_set_size"]:
                bad.append("Coulomb: stick + slip != active in the summary")
    print("\n".join(bad))
    return 1 if bad else 0


def xmf(path, nsteps=None):
    root = ET.parse(path).getroot()
    base = os.path.dirname(os.path.abspath(path))
    names = set()
    bad = []
    for d in root.iter("DataItem"):
        if d.get("Format") != "HDF":
            continue
        fname, dset = d.text.strip().rsplit(":", 1)
        names.add(fname)
        h5 = os.path.join(base, fname)
        if not os.path.isfile(h5):
            bad.append("%s: no such file (named %r in the .xmf)" % (h5, fname))
            continue
        with h5py.File(h5, "r") as f:
            if dset not in f:
                bad.append("%s: no dataset %s" % (fname, dset))
    grids = [gr for gr in root.iter("Grid") if gr.get("GridType") == "Uniform"]
    print("files %s, %d grids, %d attributes" % (sorted(names), len(grids), len(list(root.iter("Attribute")))))
    if len(names) != 1:
        bad.append("the .xmf names %d files" % len(names))
    if nsteps is not None:
        coll = [gr for gr in root.iter("Grid") if gr.get("CollectionType") == "Temporal"]
        if len(coll) != 1 or len(grids) != nsteps or len(list(root.iter("Time"))) != nsteps:
            bad.append("not a temporal collection of %d grids" % nsteps)
    print("\n".join(bad))
    return 1 if bad else 0


if __name__ == "__main__":
    a = sys.argv[1:]
    if a and a[0] == "integrals" and len(a) in (6, 7):
        sys.exit(integrals(a[1], a[2], int(a[3]), float(a[4]), float(a[5]), int(a[6]) if len(a) == 7 else None))
    if a and a[0] == "xmf" and len(a) in (2, 3):
        sys.exit(xmf(a[1], int(a[2]) if len(a) == 3 else None))
    sys.exit(__doc__)
