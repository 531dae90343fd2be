#!/usr/bin/env python3
"""The library's house rules, checked on the sources and the built objects.

1. The public header include/signorini.h compiles alone (C and C++), and the driver app/ and examples/ include only it.
2. A layer's structs live in its src/<layer>/*impl.h, included by that layer's files only (and by the white-box
   tests/unit_tests.c): no module reads another layer's struct.
3. The import graph between the layers, from the objects' symbols (who calls whom), has no circle.

usage: check_layers.py --out FILE.json   (the summary the harness checks: violations, layers, edges, order)
"""
import argparse
import glob
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def petsc_includes():
    """PETSc's include flags, from the Makefile's variables."""
    out = subprocess.run(["make", "-s", "-C", ROOT, "--no-print-directory", "print-cflags"], capture_output=True, text=True)
    return out.stdout.split()


def header_alone(cflags, violations):
    for lang, ext, cc in (("C", "c", "mpicc"), ("C++", "cc", "mpicxx")):
        with tempfile.TemporaryDirectory() as d:
            src = os.path.join(d, "alone." + ext)
            with open(src, "w") as f:
                f.write("#include <signorini.h>\nint main(void) { SgProblem p = NULL; SgCont c = NULL; (void)p; (void)c; return 0; }\n")
            r = subprocess.run([cc, "-fsyntax-only", "-Wall", "-Werror", "-I" + os.path.join(ROOT, "include")] + cflags + [src], capture_output=True, text=True)
            if r.returncode:
                violations.append("include/signorini.h does not compile alone as %s: %s" % (lang, r.stderr.strip()[:400]))


def includes(path):
    with open(path) as f:
        return re.findall(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]', f.read(), re.M)


def check_includes(violations):
    layers = sorted(os.path.basename(d) for d in glob.glob(os.path.join(ROOT, "src", "*")) if os.path.isdir(d))
    for path in sorted(glob.glob(os.path.join(ROOT, "src", "*", "*.[ch]"))):
        layer = os.path.basename(os.path.dirname(path))
        for inc in includes(path):
            m = re.match(r"(\w+)/\w+impl\.h$", inc)
            if m and m.group(1) != layer:
                violations.append("%s includes %s: another layer's structs" % (os.path.relpath(path, ROOT), inc))
    for path in sorted(glob.glob(os.path.join(ROOT, "app", "*.c")) + glob.glob(os.path.join(ROOT, "examples", "*.c"))):
        for inc in includes(path):
            if inc.endswith(".h") and not inc.startswith("petsc") and inc != "signorini.h" and "/" not in inc and not re.match(r"^(std|string|math|errno|limits|ctype|strings|unistd|sys/)", inc):
                violations.append("%s includes %s: a program over the library uses include/signorini.h only" % (os.path.relpath(path, ROOT), inc))
            if re.match(r"\w+/\w+impl\.h$", inc) or inc == "sg.h":
                violations.append("%s includes the library's private header %s" % (os.path.relpath(path, ROOT), inc))
    return layers


def symbols(obj):
    out = subprocess.run(["nm", "-g", obj], capture_output=True, text=True, check=True).stdout
    defined, undefined = set(), set()
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 3 and parts[1] in "TDBRC":
            defined.add(parts[2])
        elif len(parts) == 2 and parts[0] == "U":
            undefined.add(parts[1])
    return defined, undefined


def import_graph(layers, violations):
    owner, uses = {}, {l: set() for l in layers}
    for l in layers:
        for obj in glob.glob(os.path.join(ROOT, "build", l, "*.o")):
            d, u = symbols(obj)
            for s in d:
                owner[s] = l
            uses[l] |= u
    if not owner:
        violations.append("no objects in build/<layer>/: build first (make)")
    edges = sorted({(l, owner[s]) for l in layers for s in uses[l] if s in owner and owner[s] != l})
    # a topological order, or the circle
    order, left = [], set(layers)
    while left:
        free = sorted(l for l in left if not any(a == l and b in left for a, b in edges))
        if not free:
            violations.append("the layers %s import each other (a circle): %s" % (sorted(left), [e for e in edges if e[0] in left and e[1] in left]))
            break
        order += free
        left -= set(free)
    return edges, order


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    violations = []
    header_alone(petsc_includes(), violations)
    layers = check_includes(violations)
    edges, order = import_graph(layers, violations)
    summary = {"violations": violations, "layers": layers, "edges": ["%s -> %s" % e for e in edges], "order": order}
    with open(a.out, "w") as f:
        json.dump(summary, f, indent=1)
    for v in violations:
        print("violation:", v)
    print("layers, each using only those before it:", " < ".join(order))
    return 1 if violations else 0


if __name__ == "__main__":
    sys.exit(main())
