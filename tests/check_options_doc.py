#!/usr/bin/env python3
"""Check doc/options.md against `bin/signorini -help`: every option of ours that -help lists is documented, and every
option documented is listed.

Our options are the lines of -help that end with "(None)" or "((null))" (PetscOptions* calls without a manual page)
but for the prefixes of PETSc's objects (a few of PETSc's own options, MUMPS's and hypre's, have no manual page
either), and the viewers under our prefixes (-cont_view). An option is listed only
when the object reading it is created, so -help is run on several small problems: -help alone (which must exit 0),
then a 2D and a 3D box with each obstacle type that `-obstacle_type` lists, each friction law, an iterative linear
solver; the union of their options is compared with the documented ones.

Defaults: where a row's default is a plain number, a list of numbers or true/false, it must be the default -help prints
("formerly"); defaults in words or formulas are not compared.

A documented option is an `-option` in backquotes in the first cell of a table row of doc/options.md (the tables
have four columns: option, default, meaning, bad values; a row with another count fails). Options named elsewhere
(prose, bullet lists: PETSc's options, the old names) are not counted.

usage: check_options_doc.py [--bin bin/signorini] [--doc doc/options.md] [--out FILE.json]
Exit 0 when both lists agree; otherwise each option to add or remove is printed on a line of its own.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUR_VIEWER = re.compile(r"^Viewer \(-((?:cont|ssn|sg|contact|obstacle|friction|load)_[A-Za-z0-9_]*)\) options:")
OPTION_LINE = re.compile(r"^\s+-([A-Za-z][A-Za-z0-9_]*)\b")
# PETSc's objects (also under our prefix vi_ of the SNESVI baseline) print some options without a manual page too
# ours under a PETSc object's prefix, named as the PETSc options they extend (-dm_refine_geometry: fem/geometry.c)
OURS_UNDER_PETSC_PREFIX = {"dm_refine_geometry"}
PETSC_PREFIX = re.compile(r"^(?:vi_)?(?:mat|pc|ksp|snes|dm|vec|is|sf|petscpartitioner|petscsection|tao|ts|viewer|draw|log|options|malloc)_")

# meshed obstacle for the cad type's second run: a square in 2D, written at run time (no file in the tree needed)
SQUARE_MSH = """$MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
4
1 -1 -2 0
2 2 -2 0
3 2 -0.01 0
4 -1 -0.01 0
$EndNodes
$Elements
4
1 1 2 0 1 1 2
2 1 2 0 1 2 3
3 1 2 0 1 3 4
4 1 2 0 1 4 1
$EndElements
"""


def configurations(tmp, obstacle_types):
    """(name, arguments) of the -help runs: small problems that create every object whose options we document."""
    box2 = ["-box_faces", "6,3", "-box_upper", "2,1", "-dirichlet_ids", "3", "-dirichlet_values", "0,-0.01", "-contact_ids", "1"]
    box3 = ["-box_dim", "3", "-box_faces", "3,3,2", "-dirichlet_ids", "2", "-dirichlet_values", "0,0,-0.01", "-contact_ids", "1"]
    runs = [("help alone", [])]
    per_type = {"cad": ["-obstacle_cad_file", os.path.join(ROOT, "tests", "data", "cad_line.geo")],
                "ball": ["-obstacle_ball_center", "1,0", "-obstacle_ball_radius", "0.5"]}
    for t in obstacle_types:
        runs.append(("2D, -obstacle_type %s" % t, box2 + ["-obstacle_type", t] + per_type.get(t, [])))
    msh = os.path.join(tmp, "square.msh")
    with open(msh, "w") as f:
        f.write(SQUARE_MSH)
    runs.append(("2D, meshed obstacle", box2 + ["-obstacle_type", "cad", "-obstacle_cad_file", msh]))
    runs.append(("2D, Tresca", box2 + ["-friction_type", "tresca", "-friction_bound", "0.01"]))
    runs.append(("2D, Coulomb, pdas", box2 + ["-friction_type", "coulomb", "-friction_coefficient", "0.3", "-cont_type", "pdas"]))
    runs.append(("2D, Coulomb", box2 + ["-friction_type", "coulomb", "-friction_coefficient", "0.3"]))
    runs.append(("3D, CG + BoomerAMG, fast", box3 + ["-ksp_type", "cg", "-pc_type", "hypre", "-cont_type", "fast"]))
    runs.append(("3D, vi", box3 + ["-cont_type", "vi"]))
    runs.append(("2D, load steps, -cont_view", box2 + ["-load_steps", "2", "-cont_view"]))
    return runs


def run_help(exe, args):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
    p = subprocess.run([exe, "-help", "-quiet"] + args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env,
                       cwd=ROOT, timeout=120)
    return p.returncode, p.stdout.decode("utf-8", "replace")


def our_options(text):
    """The option names of ours in one -help output."""
    names = set()
    for line in text.splitlines():
        m = OUR_VIEWER.match(line)
        if m:
            names.add(m.group(1))
            continue
        m = OPTION_LINE.match(line)
        if m and (line.rstrip().endswith("(None)") or line.rstrip().endswith("((null))")) and (not PETSC_PREFIX.match(m.group(1)) or m.group(1) in OURS_UNDER_PETSC_PREFIX):
            names.add(m.group(1))
    return names


def defaults(text):
    """{option: its default} as -help prints it ("<now X : formerly D>": D, the value before the command line)."""
    d = {}
    for line in text.splitlines():
        m = re.match(r"^\s+-([A-Za-z][A-Za-z0-9_]*) <now .*? : formerly (.*?)>", line)
        if m:
            d.setdefault(m.group(1), m.group(2).strip())
    return d


NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)(e[-+]?\d+)?$", re.I)


def comparable(doc):
    doc = doc.strip()
    return doc in ("true", "false") or all(NUMBER.match(x) for x in doc.split(","))


def default_differs(doc, helpval):
    """True when the documented default (a plain number, a comma list of numbers, true or false) is not -help's; other
    documented defaults (words, formulas, "none") are not compared, nor an empty one of -help."""
    doc = doc.strip()
    if not helpval or not comparable(doc):
        return False
    if doc in ("true", "false"):
        return doc != helpval
    h = [x for x in helpval.split(",") if x]
    if not all(NUMBER.match(x) for x in h):
        return True
    dv, hv = [float(x) for x in doc.split(",")], [float(x) for x in h]
    if len(dv) == 1 and len(hv) > 1:  # "0" documents the list 0,0
        dv = dv * len(hv)
    return dv != hv


def choices(text, option):
    """The choice list PETSc prints for an FList option: '(one of) a b c'."""
    for line in text.splitlines():
        if re.match(r"^\s+-%s\b" % option, line):
            m = re.search(r"\(one of\) ([^()]*)\(", line)
            if m:
                return m.group(1).split()
    return []


def documented(path):
    """{option: line number} of the first cells of doc/options.md's tables, and the rows with a wrong cell count."""
    docs, bad, cells_default = {}, [], {}
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            if not line.startswith("|") or re.match(r"^\|[\s:|-]+\|\s*$", line):
                continue
            cells = [c.strip() for c in re.split(r"(?<!\\)\|", line.strip())[1:-1]]
            names = re.findall(r"`-([A-Za-z][A-Za-z0-9_]*)", cells[0]) if cells else []
            if not names:
                continue
            if len(cells) != 4 or not all(cells[1:]):
                bad.append("%s:%d: a row needs four non-empty cells (option, default, meaning, bad values), "
                           "found %d: %s" % (os.path.relpath(path, ROOT), n, len(cells), line.strip()[:100]))
            for name in names:
                docs.setdefault(name, n)
            if len(names) == 1 and len(cells) == 4:
                cells_default[names[0]] = cells[1]
    return docs, bad, cells_default


def collect(exe, listed, problems, helpdefaults):
    """Run -help on every configuration; fill listed {option: configuration}; (exit of -help alone, its options,
    the runs, the obstacle types)."""
    with tempfile.TemporaryDirectory() as tmp:
        rc, alone = run_help(exe, [])
        obstacle_types = choices(alone, "obstacle_type")
        if not obstacle_types:  # -help alone does not create the obstacle: ask a problem that does
            obstacle_types = choices(run_help(exe, ["-dirichlet_ids", "3", "-contact_ids", "1"])[1], "obstacle_type")
        if not obstacle_types:
            problems.append("-help lists no choices for -obstacle_type: cannot cover the obstacle types")
        runs = configurations(tmp, obstacle_types)
        for name, args in runs:
            code, text = (rc, alone) if not args else run_help(exe, args)
            if "Contact solver (SgCont) options" not in text:
                problems.append("-help (%s) did not list the controller's options (exit %d): %s" % (name, code, text[-300:]))
            for o in sorted(our_options(text)):
                listed.setdefault(o, name)
            for o, v in defaults(text).items():
                helpdefaults.setdefault(o, v)
    if rc != 0:
        problems.append("bin/signorini -help alone exited %d, not 0" % rc)
    return rc, our_options(alone), runs, obstacle_types


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default=os.path.join(ROOT, "bin", "signorini"))
    ap.add_argument("--doc", default=os.path.join(ROOT, "doc", "options.md"))
    ap.add_argument("--out", help="JSON summary of the check (for the test harness)")
    ap.add_argument("--listed", help="take the options -help lists from this JSON summary of an earlier run (its "
                    "'listed_options') instead of running -help again: checks a changed doc cheaply")
    opt = ap.parse_args()

    problems = []
    listed = {}  # option -> the first configuration that listed it
    helpdefaults = {}  # option -> its default as -help prints it
    rc, alone_options, runs, obstacle_types = 0, set(), [], ["(from --listed)"]
    if opt.listed:
        with open(opt.listed) as f:
            old = json.load(f)
        listed = old["listed_options"]
        helpdefaults = old.get("help_defaults", {})
        rc, alone_options, runs = old["help_alone_exit"], set(o[1:] for o in old["help_alone_list"]), [(n, None) for n in old["configurations"]]
    else:
        rc, alone_options, runs, obstacle_types = collect(opt.bin, listed, problems, helpdefaults)
    doc = os.path.relpath(opt.doc, ROOT)
    docs, bad, docdefaults = documented(opt.doc)
    problems += bad
    add = sorted(set(listed) - set(docs))
    remove = sorted(set(docs) - set(listed))
    for o in add:
        problems.append("option -%s is listed by bin/signorini -help (%s) but not documented: add a row for `-%s` to a "
                        "table of %s" % (o, listed[o], o, doc))
    for o in remove:
        problems.append("option -%s is documented (%s:%d) but bin/signorini -help does not list it: remove "
                        "its row, or register the option" % (o, doc, docs[o]))
    compared = 0
    for o in sorted(set(docdefaults) & set(listed)):
        if o in helpdefaults and helpdefaults[o]:
            compared += comparable(docdefaults[o])
            if default_differs(docdefaults[o], helpdefaults[o]):
                problems.append("option -%s: %s gives the default '%s', bin/signorini -help says '%s': correct the row"
                                % (o, doc, docdefaults[o], helpdefaults[o]))
    for p in problems:
        print("not ok " + p)
    summary = {"listed": len(listed), "documented": len(docs), "add": ["-" + o for o in add],
               "remove": ["-" + o for o in remove], "problems": len(problems), "help_alone_exit": rc,
               "help_alone_options": len(alone_options), "help_alone_list": ["-" + o for o in sorted(alone_options)],
               "listed_options": listed, "help_defaults": {o: helpdefaults[o] for o in listed if o in helpdefaults},
               "defaults_compared": compared,
               "not_listed_by_help_alone": ["-" + o for o in sorted(set(listed) - alone_options)],
               "configurations": [n for n, _ in runs] if obstacle_types else []}
    print("%d options of ours listed by -help over %d runs, %d documented, %d to add, %d to remove, %d problems"
          % (len(listed), len(summary["configurations"]), len(docs), len(add), len(remove), len(problems)))
    if opt.out:
        with open(opt.out, "w") as f:
            json.dump(summary, f, indent=1)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
