#!/usr/bin/env python3
"""Check the XDMF files bin/signorini writes for awkward file names, and render them with ParaView when it is there.

For each name (spaces, several dots, a subdirectory, XML's special characters & " < >, a name without .h5) a small problem is solved with
-output_file NAME (once with load steps: a temporal collection), then the .xmf beside it is checked:
  - it is well-formed XML with the XDMF structure (Xdmf/Domain/Grid, Topology, Geometry, Attributes);
  - every HDF DataItem names the HDF5 file beside it by its base name, unambiguously ("FILE:/dataset", no ':' in
    FILE), the file exists, holds the dataset, and its shape is the DataItem's Dimensions;
  - the number of cells and vertices agrees with the run's summary.
(A ':' in the name is not among them: ParaView's XDMF reader cuts FILE:/dataset at the first ':', see doc/paraview.md.)
Then, if pvpython is installed, scripts/render.py draws three of them (a plain result, load steps, friction) (xvfb-run -a pvpython ...) and the PNG must exist
and not be blank; otherwise a line "skip: pvpython not installed ..." says so and the rest still counts.

usage: check_xdmf.py OUTDIR [--out FILE.json]
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py

import pvrender

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BOX = ["-box_faces", "8,3", "-box_upper", "3,1", "-dirichlet_ids", "3", "-dirichlet_values", "0,-0.01",
       "-contact_ids", "1", "-obstacle_type", "parabola", "-quiet"]
NAMES = [("spaces", "with spaces/my result.h5", []),
         ("dots", "a.b.c/res.v1.2.h5", []),
         ("amp", "x&y/r&s.h5", []),
         ("xmlchars", 'q"<d/a"b<c>#%.h5', []),
         ("noext", "plain/result", []),
         ("steps", "load steps/ex 1.steps.h5", ["-load_steps", "3"]),
         ("friction", "fr/fr.h5", ["-friction_type", "coulomb", "-friction_coefficient", "0.3"])]


RENDER = ("spaces", "steps", "friction")  # rendered when pvpython is there (a few seconds each)


def env():
    return dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")


def check_xmf(xmf, h5, summary):
    """The problems of one .xmf file (empty: valid)."""
    bad = []
    try:
        tree = ET.parse(xmf)
    except ET.ParseError as e:
        return ["%s: not well-formed XML: %s" % (xmf, e)]
    root = tree.getroot()
    if root.tag != "Xdmf" or root.find("Domain") is None:
        return ["%s: no Xdmf/Domain" % xmf]
    grids = [g for g in root.iter("Grid") if g.get("GridType") == "Uniform"]
    if not grids:
        bad.append("%s: no uniform grid" % xmf)
    base = os.path.basename(h5)
    with h5py.File(h5, "r") as f:
        for g in grids:
            for tag in ("Topology", "Geometry"):
                if g.find(tag) is None:
                    bad.append("%s: grid %s has no %s" % (xmf, g.get("Name"), tag))
            if not g.findall("Attribute"):
                bad.append("%s: grid %s has no fields" % (xmf, g.get("Name")))
            ncell = int(g.find("Topology").get("NumberOfElements"))
            if summary and ncell != summary.get("cells", ncell):
                bad.append("%s: %d cells, the summary says %s" % (xmf, ncell, summary.get("cells")))
        for item in root.iter("DataItem"):
            if item.get("Format") != "HDF":
                continue
            text = (item.text or "").strip()
            fname, sep, dset = text.partition(":")
            if not sep or not dset.startswith("/"):
                bad.append("%s: DataItem '%s' is not FILE:/dataset" % (xmf, text))
                continue
            if fname != base:
                bad.append("%s: DataItem names the file '%s', the HDF5 file beside it is '%s'" % (xmf, fname, base))
            if dset not in f:
                bad.append("%s: dataset %s is not in %s" % (xmf, dset, h5))
                continue
            dims = tuple(int(x) for x in item.get("Dimensions").split())
            shape = f[dset].shape
            if tuple(shape) != dims and not (len(shape) == 1 and dims == (shape[0], 1)):
                bad.append("%s: %s has shape %s, the DataItem says %s" % (xmf, dset, shape, dims))
    return bad


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("outdir")
    ap.add_argument("--out")
    opt = ap.parse_args()
    shutil.rmtree(opt.outdir, ignore_errors=True)
    os.makedirs(opt.outdir)
    pvpython, xvfb = pvrender.available()
    problems, checked, rendered, glfail = [], 0, 0, 0
    if not (pvpython and xvfb):
        print("skip: pvpython not installed (apt-get install paraview python3-paraview xvfb): the .xmf files are "
              "checked, not rendered" if not pvpython else "skip: xvfb-run not installed: the .xmf files are checked, not rendered")
    for key, name, extra in NAMES:
        h5 = os.path.join(opt.outdir, name)
        os.makedirs(os.path.dirname(h5), exist_ok=True)
        sumf = os.path.join(opt.outdir, key + ".json")
        p = subprocess.run([os.path.join(ROOT, "bin", "signorini")] + BOX + extra + ["-output_file", h5, "-summary_file", sumf],
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env(), timeout=120)
        if p.returncode != 0:
            problems.append("%s: bin/signorini exited %d: %s" % (name, p.returncode, p.stdout.decode()[-400:]))
            continue
        xmf = (h5[:-3] if h5.endswith(".h5") else h5) + ".xmf"
        if not os.path.isfile(xmf):
            problems.append("%s: no .xmf file %s" % (name, xmf))
            continue
        with open(sumf) as f:
            summary = json.load(f)
        bad = check_xmf(xmf, h5, summary)
        problems += bad
        checked += 1
        print("%s %s" % ("ok" if not bad else "not ok", xmf))
        if pvpython and xvfb and not bad and key in RENDER:
            png = os.path.join(opt.outdir, key + ".png")
            field = "friction_state" if key == "friction" else "contact_pressure" if key == "steps" else "von_mises"
            verdict, out = pvrender.render([xmf, png, "--field", field], png)
            print(out.strip().splitlines()[-1] if out.strip() else "(no output)")
            if verdict == "gl":
                print("skip: %s not rendered: the X server's GL failed three times (an environment problem, not the "
                      "script's)" % xmf)
                glfail += 1
            elif verdict == "failed":
                problems.append("%s: render.py failed: %s" % (xmf, out[-600:]))
            else:
                rendered += 1
    for q in problems:
        print("not ok " + q)
    res = {"checked": checked, "rendered": rendered, "names": len(NAMES), "pvpython": bool(pvpython and xvfb),
           "problems": len(problems), "gl_failed": glfail}
    print("%d of %d .xmf files valid, %d rendered%s, %d problems" % (checked - sum(1 for q in problems if ".xmf" in q), len(NAMES), rendered,
                                                                   "" if pvpython and xvfb else " (pvpython not installed: skipped)", len(problems)))
    if opt.out:
        with open(opt.out, "w") as f:
            json.dump(res, f)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
