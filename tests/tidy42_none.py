#!/usr/bin/python3
"""The file options' value `none` is no file (doc/options.md, "Results, checkpoints, output"): runs of bin/signorini
whose options file names every result file, with `none` for each on the command line, against a run that names none
of them. Cases (tests/io_cases.py's runner: exit status, message, files left and not left):
  ref        no file option: the reference summary
  off        an options file names the fields, history, load curve and checkpoint; `none` on the command line for each
             (and for -restart_file, -dm_refine_geometry): no file named none (in the repository, where the run
             runs) nor none.xmf, none of the options file's files, and the summary equal to ref's but for timings
  nosummary  -summary_file none over an options file's summary: neither file written
  cad        -obstacle_type cad with -obstacle_cad_file none: refused as without the option
  help       -help shows none as the default of every file option and says "none: no file"

usage: tidy42_none.py --out PREFIX     (writes PREFIX.json: {"cases": N, "failed": [...], "passed": [...]})
"""
import argparse
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import io_cases  # noqa: E402

ROOT = io_cases.ROOT
BASE = io_cases.BASE + ["-load_steps", "2", "-options_left"]
FILES = ("-output_file", "-history_file", "-load_curve_file", "-checkpoint_file", "-summary_file", "-restart_file", "-obstacle_cad_file", "-dm_refine_geometry")
TIMES = re.compile(r"time|seconds|rss|memory")  # measured, not computed


def same_summary(a, b):
    """None if the two summaries agree in every key but the timings, else the first key that differs."""
    ja, jb = json.load(open(a)), json.load(open(b))
    for k in sorted(set(ja) | set(jb)):
        if TIMES.search(k):
            continue
        if ja.get(k) != jb.get(k):
            return "summary key %s: %r against %r" % (k, jb.get(k), ja.get(k))
    return None


def left_parts():
    """A temporary file of a result named none in the repository (an HDF5 result's is "none.<tag>.part"), or None."""
    got = glob.glob(os.path.join(ROOT, "none*.part"))
    return ("left behind: " + " ".join(os.path.basename(q) for q in got)) if got else None


def cases(c, tmp):
    strays = [os.path.join(ROOT, n) for n in ("none", "none.xmf", "none.part", "none.xmf.part")]
    strays += [q for q in glob.glob(os.path.join(ROOT, "none*.part")) if q not in strays]
    for p in strays:
        if os.path.lexists(p):
            c.failed.append("a file %s is in the repository before the runs: remove it" % os.path.basename(p))
            return
    ref, got = c.t("ref.json"), c.t("off.json")
    c.check("ref", BASE + ["-summary_file", ref], present=[ref])
    opts = c.t("files.opts")
    named = [c.t(n) for n in ("f.h5", "f.xmf", "f.csv", "curve.csv", "ck.h5", "s0.json")]
    with open(opts, "w") as f:
        f.write("-output_file %s\n-history_file %s\n-load_curve_file %s\n-checkpoint_file %s\n-summary_file %s\n" % (named[0], named[2], named[3], named[4], named[5]))
    off = ["-output_file", "none", "-history_file", "none", "-load_curve_file", "none", "-checkpoint_file", "none", "-restart_file", "none", "-dm_refine_geometry", "none"]
    c.check("off", BASE + ["-options_file", opts] + off + ["-summary_file", got], absent=strays + named, present=[got],
            extra=lambda out: same_summary(ref, got) or ("Option left" in out and "an option was not used") or left_parts())
    c.check("nosummary", BASE + ["-options_file", opts, "-output_file", "none", "-history_file", "none", "-load_curve_file", "none", "-checkpoint_file", "none", "-summary_file", "none"],
            absent=strays + named, extra=lambda out: left_parts())
    c.check("cad", BASE + ["-obstacle_type", "cad", "-obstacle_cad_file", "none"], error=r"-obstacle_type cad: needs -obstacle_cad_file", absent=strays,
            extra=lambda out: left_parts())
    # -help prints bytes that are not UTF-8 (PETSc 3.18's -dm_plex_boundary_label default): read them as bytes
    p = subprocess.run(io_cases.sgrun.command(BASE + ["-help"], None), cwd=ROOT, env=io_cases.ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=120)
    out = p.stdout.decode("utf-8", "replace")
    why = ["exit %d" % p.returncode] if p.returncode else []
    why += ["%s does not show none: no file" % o for o in FILES if not re.search(r"^\s*%s <now none : formerly none>: .*\(none: no file\)" % o, out, re.M)]
    why += ["left behind: " + os.path.basename(q) for q in strays if os.path.lexists(q)]
    why += [left_parts()] if left_parts() else []
    if why:
        c.failed.append("help: " + "; ".join(why))
    else:
        c.passed.append("help")

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", required=True)
    opt = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="sg_tidy42_")
    c = io_cases.Cases(tmp)
    try:
        cases(c, tmp)
    except Exception as e:  # the script itself failed: a failed test, with the reason
        c.failed.append("tidy42_none.py: %s: %s" % (type(e).__name__, e))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    res = {"cases": len(c.passed) + len(c.failed), "passed": c.passed, "failed": c.failed}
    with open(opt.out + ".json", "w") as f:
        json.dump(res, f, indent=1)
    print(json.dumps(res, indent=1))


if __name__ == "__main__":
    main()
