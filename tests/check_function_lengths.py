#!/usr/bin/env python3
"""The length of every function of the library (src/*/*.c), from the first line of its signature to its closing brace
(the files are in the style of .clang-format: a function's braces stand alone at column 0). A function of more than
about 150 lines usually holds two concerns (issue 26, item 3): the summary lists those over the limit.

usage: check_function_lengths.py --out FILE.json [--limit 150]
   summary: functions (how many were found), lengths ({"file:name": lines}), over ([file:name, ...] above the limit),
            longest ([file:name, lines]), files ({file: lines})
"""
import argparse
import glob
import json
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SIGNATURE = re.compile(r"^[A-Za-z_][^;(]*?\b([A-Za-z_]\w*)\s*\(")


def functions(path):
    """(name, first line, lines) of each function defined in the file"""
    found, cand, start = [], None, None
    with open(path) as f:
        lines = f.read().split("\n")
    for i, line in enumerate(lines):
        m = SIGNATURE.match(line)
        if m and not line.rstrip().endswith(";") and not line.startswith(("typedef", "struct", "#")):
            cand = (m.group(1), i)
        elif line == "{" and cand:
            start = cand
        elif line.startswith("}") and start:
            found.append((start[0], start[1] + 1, i - start[1] + 1))
            cand = start = None
    return found


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True)
    ap.add_argument("--limit", type=int, default=150)
    a = ap.parse_args()
    lengths, files = {}, {}
    for path in sorted(glob.glob(os.path.join(ROOT, "src", "*", "*.c"))):
        rel = os.path.relpath(path, ROOT)
        with open(path) as f:
            files[rel] = f.read().count("\n")
        for name, first, n in functions(path):
            lengths["%s:%s" % (rel, name)] = n
    over = sorted(k for k, n in lengths.items() if n > a.limit)
    longest = max(lengths.items(), key=lambda kv: kv[1]) if lengths else ["", 0]
    summary = {"functions": len(lengths), "limit": a.limit, "over": over, "longest": list(longest), "lengths": lengths, "files": files}
    with open(a.out, "w") as f:
        json.dump(summary, f, indent=1)
    for k in over:
        print("over %d lines: %s (%d)" % (a.limit, k, lengths[k]))
    print("%d functions, the longest %s with %d lines" % (len(lengths), longest[0], longest[1]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
