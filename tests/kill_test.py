#!/usr/bin/python3
"""Atomic results: kill runs with SIGTERM and SIGKILL at many moments and check that the result files of the previous
complete run (HDF5, XDMF, summary, history, checkpoint) are never left half-written.

usage: kill_test.py --out PREFIX [--signals TERM,KILL]   (writes PREFIX.json with the counts; used by tests/*/runs.ini
       and, with --signals TERM,INT, by tests/input/files.ini)

SIGTERM and SIGINT are caught: the run removes its ".part" files before it ends, so none may be left after them
("left_part_files_caught"). SIGKILL cannot be caught: its ".part" files are counted apart and removed before the next run.
"""
import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
import sgrun  # noqa: E402

ROOT = sgrun.ROOT
ENV = sgrun.mpi_env(oversubscribe=False)


def valid(path):
    """A complete result file of its kind (of a finished run), or the reason it is not."""
    return sgrun.result_problem(path, complete=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", required=True)
    ap.add_argument("--signals", default="TERM,KILL", help="comma-separated signal names, without SIG")
    opt = ap.parse_args()
    work = opt.out + "_files"
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    names = {k: os.path.join(work, "r" + k) for k in (".h5", ".xmf", ".json", ".csv")}
    names["ck"] = os.path.join(work, "ck.h5")
    cmd = [sgrun.SIGNORINI, "-options_file", "tests/opts/ex1_coarse.opts", "-options_file", "options/cont/ipf.opts",
           "-box_faces", "240,80", "-output_file", names[".h5"], "-summary_file", names[".json"], "-history_file", names[".csv"],
           "-checkpoint_file", names["ck"]]
    t0 = time.time()
    base = subprocess.run(cmd, cwd=ROOT, env=ENV, capture_output=True, text=True)
    T = time.time() - t0
    result = {"baseline_exit": base.returncode, "baseline_seconds": T, "kills": 0, "killed_running": 0, "invalid": [], "left_part_files": 0,
              "left_part_files_caught": 0, "left_part_names": []}
    files = list(names.values())
    result["baseline_invalid"] = [f for f in files if valid(f)]
    for sig in [getattr(signal, "SIG" + n) for n in opt.signals.split(",")]:
        for frac in (0.02, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.85, 0.9, 0.95, 1.0):
            p = subprocess.Popen(cmd, cwd=ROOT, env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
            t1 = time.time()
            while p.poll() is None and time.time() - t1 < frac * T:
                time.sleep(0.005)
            running = p.poll() is None
            if running:
                os.killpg(p.pid, sig)
            else:  # the machine got faster than during the baseline: the later kills aim at this run's length
                T = min(T, time.time() - t1)
            p.wait()
            result["kills"] += 1
            result["killed_running"] += int(running)
            for f in files:
                why = valid(f)
                if why:
                    result["invalid"].append("%s at %.0f%% of the run: %s %s" % (signal.Signals(sig).name, 100 * frac, os.path.basename(f), why))
            parts = [f for f in os.listdir(work) if f.endswith(".part")]
            result["left_part_files"] += len(parts)
            if sig != signal.SIGKILL:
                result["left_part_files_caught"] += len(parts)
                result["left_part_names"] += ["%s at %.0f%%: %s" % (signal.Signals(sig).name, 100 * frac, f) for f in parts]
            for f in parts:  # a stale .part is not the next run's
                os.remove(os.path.join(work, f))
    with open(opt.out + ".json", "w") as f:
        json.dump(result, f, indent=1)
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
