#!/usr/bin/python3
"""File-handling cases of issue 10 (items 7-12), each a run of bin/signorini in a temporary directory with an expected
outcome: the message (naming the option or file), the exit status, the files left and not left.

usage: io_cases.py --group {paths,special,same,stale,diskfull,cycles,checkpoint} --out PREFIX
Writes PREFIX.json: {"cases": N, "failed": [...], "skipped": [...], "passed": [...]}. Nothing is written outside the
temporary directory (a symlink to /dev/null or /dev/full is made there; the device itself is never a target of a
rename with the fixed program, and the test then checks that the link is still a link).
"""
import argparse
import glob
import json
import math
import os
import re
import shutil
import signal
import struct
import subprocess
import sys
import time
import tempfile

import h5py

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
import sgrun  # noqa: E402

ROOT = sgrun.ROOT
ENV = sgrun.mpi_env()
ENV.pop("PETSC_OPTIONS", None)
BASE = ["-options_file", "tests/opts/ex1_coarse.opts", "-box_faces", "24,8", "-options_file", "options/cont/ipf.opts"]
CRASH = re.compile(r"Segmentation Violation|signal number 11|Caught signal|buffer overflow|HDF5-DIAG|core dumped")


class Cases:
    def __init__(self, tmp):
        self.tmp = tmp
        self.passed, self.failed, self.skipped = [], [], []

    def run(self, args, np=1, env=None, timeout=120):
        p = sgrun.execute(sgrun.command(args, np if np > 1 else None), env or ENV, timeout)
        return p.returncode, p.stdout

    def check(self, name, args, error=None, ok=True, np=1, env=None, absent=(), present=(), extra=None):
        """error: REGEX that must be in the output of a failing run (nonzero exit); else exit 0 (ok) is required.
        absent/present: paths that must not / must exist afterwards; extra(out) -> None or a failure text."""
        try:
            rc, out = self.run(args, np, env)
        except subprocess.TimeoutExpired:
            self.failed.append("%s: timed out" % name)
            return
        why = []
        if rc < 0 or rc > 128:
            why.append("killed by signal %d" % (-rc if rc < 0 else rc - 128))
        if CRASH.search(out):
            why.append("crashed or raw library trace: " + CRASH.search(out).group(0))
        if error is not None:
            if rc == 0:
                why.append("exit 0, expected a failure")
            if not re.search(error, out, re.S):
                why.append("output does not match /%s/" % error)
        elif ok and rc != 0:
            why.append("exit %d" % rc)
        for p in absent:
            if os.path.lexists(p):
                why.append("left behind: " + os.path.basename(p))
        for p in present:
            if not os.path.lexists(p):
                why.append("missing: " + os.path.basename(p))
        parts = [p for p in glob.glob(os.path.join(self.tmp, "**", "*.part"), recursive=True) if not os.path.isdir(p)]
        if parts:
            why.append(".part left: " + " ".join(os.path.basename(p) for p in parts))
            for p in parts:
                os.remove(p)
        if extra and not why:
            try:
                e = extra(out)
            except Exception as ex:  # a missing or unreadable file is a failed case
                e = "%s: %s" % (type(ex).__name__, ex)
            if e:
                why.append(e)
        if why:
            tail = " | ".join(l for l in out.strip().splitlines() if "ERROR: -" in l or ": CONVERGED" in l or ": FAILED" in l)[-300:]
            self.failed.append("%s: %s [%s]" % (name, "; ".join(why), tail))
        else:
            self.passed.append(name)

    def t(self, name):
        return os.path.join(self.tmp, name)


def group_paths(c):
    """Item 7: long names are refused before any work (naming the option) or work; the limit is exact."""
    d = c.t("d")
    os.makedirs(d)
    prefix = d + "/"
    # the longest -output_file HDF5 (through OpenMPI-IO) accepts on 1 rank: 255 - len(".locktest.0") - the temporary
    # file's suffix ".<8 hex digits>.part"
    h5max = 255 - len(".locktest.") - 1 - len(".XXXXXXXX.part")
    ok_name = prefix + "x" * (h5max - len(prefix) - 3) + ".h5"
    long_name = prefix + "x" * (h5max - len(prefix) - 2) + ".h5"
    assert len(ok_name) == h5max and len(long_name) == h5max + 1
    c.check("output_at_limit", BASE + ["-output_file", ok_name], present=[ok_name, ok_name[:-3] + ".xmf"])
    c.check("output_above_limit", BASE + ["-output_file", long_name], error=r"-output_file: the file name '.*' is %d characters long; HDF5 .* at most %d" % (h5max + 1, h5max), absent=[long_name])
    # on 2 ranks the limit is the same (rank numbers < 10), and the checkpoint has it too
    ck = prefix + "c" * (h5max - len(prefix) - 2) + ".h5"
    c.check("checkpoint_above_limit_np2", BASE + ["-checkpoint_file", ck], np=2, error=r"-checkpoint_file: the file name .* is %d characters long" % (h5max + 1), absent=[ck])
    # 240 characters: the length of the original report (aborted after the solve with "buffer overflow detected")
    r240 = prefix + "r" * (240 - len(prefix) - 3) + ".h5"
    c.check("output_240_chars", BASE + ["-output_file", r240], error=r"-output_file: the file name .* is 240 characters long", absent=[r240])
    # text results go through fopen: a long path of short components works; over PETSC_MAX_PATH_LEN it is refused
    deep = d
    while len(deep) < 600:
        deep = os.path.join(deep, "s" * 50)
    os.makedirs(deep)
    c.check("summary_deep_path", BASE + ["-summary_file", os.path.join(deep, "s.json")], present=[os.path.join(deep, "s.json")])
    for n in (4090, 4096, 5000):
        name = prefix + "z" * (n - len(prefix))
        c.check("summary_%d_chars" % n, BASE + ["-summary_file", name], error=r"-summary_file: the file name is %d characters long, at most 4089" % n)
    c.check("history_component_too_long", BASE + ["-history_file", prefix + "h" * 300], error=r"-history_file: cannot write '.*': File name too long")
    # the restart file is read through HDF5 on one rank: the same library limit, without the temporary file's suffix
    h5in = 255 - len(".locktest.") - 1
    rs = prefix + "q" * (h5in + 1 - len(prefix))
    open(rs, "w").close()
    c.check("restart_above_limit", BASE + ["-restart_file", rs], error=r"-restart_file: the file name .* is %d characters long" % len(rs))
    rs = prefix + "q" * (h5in - len(prefix))
    open(rs, "w").close()
    c.check("restart_at_limit_empty_file", BASE + ["-restart_file", rs], error=r"-restart_file: '.*' is not a readable HDF5 file")


def group_special(c):
    """Item 9: a device, FIFO or symlink as a result path: never renamed over."""
    fifo = c.t("fifo")
    os.mkfifo(fifo)
    null = c.t("null")
    os.symlink("/dev/null", null)
    # HDF5 results need a regular file: refused before any work, the FIFO stays a FIFO
    c.check("output_fifo", BASE + ["-output_file", fifo], error=r"-output_file: '.*fifo' is a FIFO, not a regular file")
    c.check("checkpoint_devnull_link", BASE + ["-checkpoint_file", null], error=r"-checkpoint_file: '.*null' is a character device, not a regular file")
    # text results are written into a device directly: the link stays a link to /dev/null
    c.check("summary_history_devnull", BASE + ["-summary_file", null, "-history_file", null],
            extra=lambda out: None if os.path.islink(null) and os.readlink(null) == "/dev/null" else "the link was replaced")
    # a FIFO with a reader receives the summary
    got = c.t("from_fifo")
    reader = subprocess.Popen(["sh", "-c", 'cat "$0" > "$1"', fifo, got])
    c.check("summary_fifo", BASE + ["-summary_file", fifo],
            extra=lambda out: (reader.wait(timeout=30), None if json.load(open(got)).get("converged") is True and os.path.exists(fifo) and not os.path.isfile(fifo) else "the FIFO got no summary or was replaced")[1])
    # a symlink to a regular file is written through: the link stays, the target gets the new content
    target = c.t("target.json")
    open(target, "w").write("old")
    link = c.t("link.json")
    os.symlink(target, link)
    c.check("summary_symlink", BASE + ["-summary_file", link],
            extra=lambda out: None if os.path.islink(link) and json.load(open(target)).get("converged") is True else "the link was replaced or the target not written")
    dangling = c.t("dangling.json")
    os.symlink(c.t("missing/none.json"), dangling)
    c.check("summary_dangling_symlink", BASE + ["-summary_file", dangling], error=r"-summary_file: '.*dangling.json' is a symbolic link to a missing file")
    # /dev/full through a link: the write fails with ENOSPC, named; the link stays
    full = c.t("full")
    os.symlink("/dev/full", full)
    c.check("summary_devfull", BASE + ["-summary_file", full], error=r"error writing '.*full': no space left on device",
            extra=lambda out: None if os.path.islink(full) else "the link was replaced")
    c.check("output_directory", BASE + ["-output_file", c.tmp], error=r"-output_file: '.*' is a directory, not a file name")


def group_same(c):
    """Item 10: one file named by two options is refused before any work; restart = checkpoint is allowed."""
    os.makedirs(c.t("sub"))
    s = c.t("s.json")
    c.check("summary_eq_history", BASE + ["-summary_file", s, "-history_file", c.t("sub/../s.json")],
            error=r"-summary_file '.*s.json' and -history_file '.*sub/../s.json' name the same file", absent=[s])
    c.check("output_eq_checkpoint", BASE + ["-output_file", c.t("r.h5"), "-checkpoint_file", c.t("r.h5")],
            error=r"-output_file '.*r.h5' and -checkpoint_file '.*r.h5' name the same file", absent=[c.t("r.h5")])
    c.check("xmf_eq_summary", BASE + ["-output_file", c.t("r.h5"), "-summary_file", c.t("r.xmf")],
            error=r"-output_file \(its .xmf file\) '.*r.xmf' and -summary_file '.*r.xmf' name the same file")
    mesh = c.t("beam.msh")
    shutil.copy(os.path.join(ROOT, "meshes", "beam.msh"), mesh)
    before = open(mesh, "rb").read()
    c.check("summary_eq_mesh", ["-dm_plex_filename", mesh, "-dm_plex_gmsh_use_regions", "-dirichlet_label", "clamped", "-summary_file", mesh],
            error=r"-dm_plex_filename '.*beam.msh' and -summary_file '.*beam.msh' name the same file: an input would be overwritten",
            extra=lambda out: None if open(mesh, "rb").read() == before else "the mesh was changed")
    opts = c.t("c.opts")
    shutil.copy(os.path.join(ROOT, "tests", "opts", "ex1_coarse.opts"), opts)
    before_o = open(opts).read()
    c.check("history_eq_options_file", ["-options_file", opts, "-history_file", opts],
            error=r"-options_file '.*c.opts' and -history_file '.*c.opts' name the same file",
            extra=lambda out: None if open(opts).read() == before_o else "the options file was changed")
    # a hard link is the same file too
    open(c.t("a.csv"), "w").write("x")
    os.link(c.t("a.csv"), c.t("b.json"))
    c.check("hardlink", BASE + ["-history_file", c.t("a.csv"), "-summary_file", c.t("b.json")], error=r"-summary_file '.*b.json' and -history_file '.*a.csv' name the same file")
    # symlink to another output
    os.symlink(c.t("h.csv"), c.t("hl.csv"))
    open(c.t("h.csv"), "w").write("x")
    c.check("symlink_to_other_output", BASE + ["-history_file", c.t("h.csv"), "-summary_file", c.t("hl.csv")], error=r"name the same file")
    # resuming from and rewriting one checkpoint: allowed, and it converges like the run without restart
    ck = c.t("ck.h5")
    c.check("restart_eq_checkpoint_part", BASE + ["-checkpoint_file", ck, "-cont_max_it", "2"], error=r"MAX_IT", present=[ck])
    c.check("restart_eq_checkpoint_resume", BASE + ["-checkpoint_file", ck, "-restart_file", ck], present=[ck],
            extra=lambda out: None if "ipf: CONVERGED" in out and h5py.File(ck, "r")["checkpoint"].attrs["outer"] > 2 else "did not converge or the checkpoint was not rewritten")
    # two devices are fine (both into /dev/null)
    # (only through links in the temporary directory: a program that renames over its targets replaces the links, never
    # the device)
    os.symlink("/dev/null", c.t("n1"))
    os.symlink("/dev/null", c.t("n2"))
    c.check("two_outputs_devnull", BASE + ["-summary_file", c.t("n1"), "-history_file", c.t("n2")],
            extra=lambda out: None if os.path.islink(c.t("n1")) and os.path.islink(c.t("n2")) else "a link was replaced")


def group_stale(c):
    """A run killed inside OpenMPI's MPI-IO file open leaves the machine-wide semaphore "OMPIO_<base name>" (in
    /dev/shm) taken; every later open of a file of that base name waited for it for ever (the suite's CI run hung on
    "ck.h5.part"). Such semaphores are made here, taken, for the names the program wrote its HDF5 results through
    before ("<name>.part" of the checkpoint and of the fields) and for the restart file's own name (read through
    MPI-IO too): the runs write, resume (on 1 and 2 ranks) and finish as without them."""
    shm = "/dev/shm"
    if not (os.path.isdir(shm) and os.access(shm, os.W_OK)):
        print("# skipping: %s is not a writable directory" % shm)
        c.skipped.append("no writable " + shm)
        return
    base = "sgstale%d_%s" % (os.getpid(), os.urandom(4).hex())
    ck, out = c.t(base + "_ck.h5"), c.t(base + "_r.h5")
    taken = struct.pack("<QiI16x", 0, 128, 0)  # glibc's sem_t of a shared semaphore with the value 0 (nobody waiting)
    sems = [os.path.join(shm, "sem.OMPIO_%s.part" % os.path.basename(f)) for f in (ck, out)] + [os.path.join(shm, "sem.OMPIO_%s" % os.path.basename(ck))]
    try:
        for f in sems:
            with open(f, "wb") as g:
                g.write(taken)
        args = BASE + ["-checkpoint_file", ck, "-output_file", out]
        c.check("write_beside_taken_semaphores", args + ["-cont_max_it", "2"], error=r"MAX_IT", present=[ck])
        c.check("resume_beside_taken_semaphores", args + ["-restart_file", ck], present=[ck, out, out[:-3] + ".xmf"],
                extra=lambda out_: None if "ipf: CONVERGED" in out_ else "did not converge")
        c.check("np2_beside_taken_semaphores", args + ["-cont_max_it", "2"], np=2, error=r"MAX_IT", present=[ck])

        def resumed(out_):
            links = [f for f in os.listdir(os.path.dirname(ck) or ".") if f.endswith(".read")]
            if "ipf: CONVERGED" not in out_:
                return "did not converge"
            if links:
                return "links to the restart file left: %s" % links
            if not all(open(f, "rb").read(4) == b"\0\0\0\0" for f in sems):
                return "a planted semaphore is no longer taken: the test did not test"
            return None
        c.check("np2_resume_beside_taken_semaphores", args + ["-restart_file", ck], np=2, present=[ck, out], extra=resumed)
    finally:
        for f in sems:
            if os.path.exists(f):
                os.remove(f)


def can_mount(tmp):
    d = os.path.join(tmp, "probe")
    os.makedirs(d, exist_ok=True)
    r = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", d], capture_output=True, text=True)
    if r.returncode == 0:
        subprocess.run(["umount", d])
        return None
    return (r.stderr or r.stdout).strip() or "mount failed"


def group_diskfull(c):
    """Item 11: disk full in HDF5 results and checkpoints, text results; killed runs leave no .part."""
    why = can_mount(c.tmp)
    fs = c.t("fs")
    if why:
        print("# skipping the tmpfs cases: cannot mount a small tmpfs (%s)" % why)
        c.skipped.append("tmpfs: " + why)
    else:
        os.makedirs(fs)
        subprocess.run(["mount", "-t", "tmpfs", "-o", "size=40k", "tmpfs", fs], check=True)
        try:
            s = c.t("s.json")
            c.check("output_disk_full", BASE + ["-output_file", os.path.join(fs, "r.h5"), "-summary_file", s],
                    error=r"-output_file: cannot write '.*r.h5': no space left on device", absent=[os.path.join(fs, "r.h5"), os.path.join(fs, "r.xmf")], present=[s],
                    extra=lambda out: None if json.load(open(s)).get("converged") is True and "no space left on device" in json.load(open(s)).get("output_error", "") else "the summary lacks the failed write")
            os.remove(s)
            ck = os.path.join(fs, "ck.h5")
            c.check("checkpoint_disk_full", BASE + ["-checkpoint_file", ck, "-summary_file", s], error=r"CHECKPOINT_FAILED: -checkpoint_file: cannot write '.*ck.h5': no space left on device", present=[s],
                    extra=lambda out: None if json.load(open(s)).get("converged") is False and json.load(open(s))["reason"].startswith("CHECKPOINT_FAILED") else "the summary lacks the failure")
            for f in os.listdir(fs):
                os.remove(os.path.join(fs, f))
            fd = os.open(os.path.join(fs, "pad"), os.O_WRONLY | os.O_CREAT)  # fill the file system
            try:
                while os.write(fd, b"x" * 1024) > 0:
                    pass
            except OSError:
                pass
            os.close(fd)
            c.check("history_disk_full", BASE + ["-history_file", os.path.join(fs, "h.csv"), "-summary_file", s],
                    error=r"error writing '.*h.csv': no space left on device", present=[s], absent=[os.path.join(fs, "h.csv")],
                    extra=lambda out: None if "history_error" in json.load(open(s)) else "the summary lacks the failed write")
        finally:
            subprocess.run(["umount", fs])
    # the pair is committed together: make the .xmf write fail (its .part name is a directory) and check that the
    # previous .h5 and .xmf both stay unchanged
    r = c.t("pair")
    os.makedirs(r)
    c.check("pair_first", BASE + ["-output_file", os.path.join(r, "x.h5")], present=[os.path.join(r, "x.h5"), os.path.join(r, "x.xmf")])
    h5_before = open(os.path.join(r, "x.h5"), "rb").read()
    os.makedirs(os.path.join(r, "x.xmf.part"))
    c.check("xmf_fails_h5_not_committed", BASE + ["-output_file", os.path.join(r, "x.h5"), "-E", "2"], error=r"cannot write '.*x.xmf'",
            extra=lambda out: None if open(os.path.join(r, "x.h5"), "rb").read() == h5_before and not glob.glob(os.path.join(r, "x.h5*.part")) else "the .h5 was replaced without its .xmf")
    os.rmdir(os.path.join(r, "x.xmf.part"))
    # SIGTERM and SIGINT during the HDF5 output of a larger run: no .part left
    for sig in (signal.SIGTERM, signal.SIGINT):
        d = c.t("sig%d" % sig)
        os.makedirs(d)
        args = ["-options_file", "tests/opts/ex1_coarse.opts", "-options_file", "options/cont/ipf.opts", "-box_faces", "120,40",
                "-output_file", os.path.join(d, "r.h5"), "-checkpoint_file", os.path.join(d, "ck.h5"), "-summary_file", os.path.join(d, "s.json"), "-history_file", os.path.join(d, "h.csv")]
        left, killed = [], 0
        # kill at fractions of an undisturbed run's duration, so that the kills land mid-run on any machine speed
        t0 = time.time()
        subprocess.run([sgrun.SIGNORINI] + args, cwd=ROOT, env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        full = time.time() - t0
        for f in os.listdir(d):
            os.remove(os.path.join(d, f))
        for delay in [full * x for x in (0.1, 0.25, 0.4, 0.55, 0.7, 0.85)]:
            p = subprocess.Popen([sgrun.SIGNORINI] + args, cwd=ROOT, env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
            try:
                p.wait(timeout=delay)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, sig)
                killed += 1
            p.wait()
            left += [f for f in os.listdir(d) if f.endswith(".part")]
        if left or killed < 3:
            c.failed.append("%s: %d of 6 runs killed, .part left: %s" % (signal.Signals(sig).name, killed, left))
        else:
            c.passed.append("killed_by_%s" % signal.Signals(sig).name)


def group_cycles(c):
    """Item 8: options files that include themselves are refused before PETSc reads them; ordinary files still work."""
    a, b, s = c.t("a.opts"), c.t("b.opts"), c.t("self.opts")
    open(s, "w").write("-E 2\n-options_file %s\n" % s)
    c.check("self_include", BASE + ["-options_file", s], error=r"-options_file: '.*self.opts' includes itself: .*self.opts -> .*self.opts")
    open(a, "w").write("# a comment -options_file nothing.opts\n-nu 0.3   # trailing comment\n-options_file\t\"%s\"\n" % b)
    open(b, "w").write("-options_file %s\n" % a)
    c.check("two_file_cycle", BASE + ["-options_file", a], error=r"includes itself: .*a.opts -> .*b.opts -> .*a.opts")
    env = dict(ENV, PETSC_OPTIONS="-options_file %s" % s)
    c.check("cycle_in_PETSC_OPTIONS", BASE, env=env, error=r"self.opts' includes itself")
    # relative spelling of the same file
    rel = os.path.relpath(s, ROOT)
    c.check("self_include_relative", BASE + ["-options_file", rel], error=r"includes itself")
    # not a cycle: one file included twice, comments naming -options_file, a quoted value with blanks
    x, y = c.t("x.opts"), c.t("y.opts")
    open(y, "w").write("-nu 0.3\n")
    open(x, "w").write("-options_file %s\n# -options_file %s\n-options_file %s\n-summary_file \"%s\"\n" % (y, x, y, c.t("with blank.json")))
    c.check("include_twice_not_a_cycle", BASE + ["-options_file", x], present=[c.t("with blank.json")])
    # deep but finite nesting works
    prev = None
    for i in range(20):
        f = c.t("n%d.opts" % i)
        open(f, "w").write(("-options_file %s\n" % prev) if prev else "-nu 0.3\n")
        prev = f
    c.check("nested_20", BASE + ["-options_file", prev])


def checkpoint_copy(src, dst, edit):
    shutil.copy(src, dst)
    with h5py.File(dst, "r+") as f:
        edit(f["checkpoint"])


def group_checkpoint(c):
    """Item 12 and the restart items: damaged or impossible checkpoints are refused naming -restart_file and the value."""
    ck = c.t("ck.h5")
    c.check("write_checkpoint", BASE + ["-checkpoint_file", ck, "-cont_max_it", "3", "-summary_file", c.t("part.json")], error=r"MAX_IT: 3 outer steps", present=[ck])
    full = c.t("full.json")
    c.check("full_run", BASE + ["-summary_file", full])
    data = open(ck, "rb").read()
    for n, frac in (("truncated_half", 0.5), ("truncated_header", 0.002)):
        f = c.t(n + ".h5")
        open(f, "wb").write(data[:int(len(data) * frac)])
        c.check(n, BASE + ["-restart_file", f], error=r"-restart_file: '.*%s.h5' is (not a readable HDF5 file|damaged)" % n)
    f = c.t("garbage.h5")
    open(f, "wb").write(bytes((i * 37) % 256 for i in range(4096)))
    c.check("garbage", BASE + ["-restart_file", f], error=r"-restart_file: '.*garbage.h5' is not a readable HDF5 file")
    # flipped bytes in the middle of the data: either unreadable or impossible values, never a raw trace
    f = c.t("flipped.h5")
    b = bytearray(data)
    for i in range(len(b) // 3, len(b) // 3 + 64):
        b[i] ^= 0xFF
    open(f, "wb").write(bytes(b))
    c.check("flipped_bytes", BASE + ["-restart_file", f], ok=False)

    def setattr_(name, val):
        return lambda g: g.attrs.modify(name, val)

    def setdata(name, idx, val):
        def e(g):
            d = g[name][...]
            d.flat[idx] = val
            g[name][...] = d
        return e

    edits = [
        ("outer_negative", setattr_("outer", -4), r"outer = -4 is impossible"),
        ("ssn_negative", setattr_("ssn_iterations", -1), r"ssn_iterations = -1 is impossible"),
        ("best_step_beyond", setattr_("best_step", 99), r"best_step = 99 is impossible"),
        ("gamma_nan", setdata("reals", 0, float("nan")), r"gamma \(must be positive\) is nan"),
        ("gamma_negative", setdata("reals", 0, -5.0), r"gamma \(must be positive\) is -5"),
        ("lamhat_negative", setdata("lamhat", 3, -1.0), r"a multiplier shift lamhat \(must be >= 0\) is -1"),
        ("lamhat_nan", setdata("lamhat", 3, float("nan")), r"a multiplier shift lamhat .* is nan"),
        ("y_nan", setdata("displacement", 5, float("nan")), r"a displacement is nan"),
        ("y_inf", setdata("displacement", 5, float("inf")), r"a displacement is inf"),
        ("coordinate_nan", setdata("coordinates", 0, float("nan")), r"a vertex coordinate is nan"),
        ("state_nan", setdata("state", 0, float("nan")), r"the controller state J_previous is nan"),
        ("path_gamma_zero", setdata("gammas", 0, 0.0), r"a gamma of the path \(must be positive\) is 0"),
        ("history_kind", setdata("history", 0, 7.0), r"a history row kind is 7"),
        ("dataset_missing", lambda g: g.__delitem__("lamhat"), r"cannot read the dataset lamhat"),
        ("attribute_missing", lambda g: g.attrs.__delitem__("outer"), r"cannot read outer"),
    ]
    for name, edit, msg in edits:
        f = c.t(name + ".h5")
        checkpoint_copy(ck, f, edit)
        c.check(name, BASE + ["-restart_file", f], error=r"-restart_file: '.*%s.h5' is damaged: " % name + msg)
    # another problem: refused naming the option and both values
    for opt, val, msg in (("-nu", "0.35", r"-nu differs \(nu 0.40000000000000002 in the checkpoint, 0.34999999999999998 in this run\)"),
                          ("-E", "2", r"-E differs \(E 5000 in the checkpoint, 2 in this run\)"),
                          ("-neumann_traction", "0,-3", r"the loads .* differ"),
                          ("-obstacle_parabola_offset", "0.002", r"the obstacle .* differs")):
        c.check("restart_other" + opt.replace("-", "_"), BASE + ["-restart_file", ck, opt, val], error=r"-restart_file: '.*ck.h5' was written for another problem: " + msg)
    # -cont_max_it at or below the checkpoint's step: MAX_IT at once, no step taken
    s = c.t("maxit.json")
    c.check("restart_max_it_below", BASE + ["-restart_file", ck, "-cont_max_it", "2", "-summary_file", s], error=r"MAX_IT: the checkpoint of -restart_file is at outer step 3 >= -cont_max_it 2: no step taken",
            extra=lambda out: None if json.load(open(s))["outer_iterations"] == 3 else "a step was taken")
    c.check("restart_max_it_equal", BASE + ["-restart_file", ck, "-cont_max_it", "3", "-summary_file", s], error=r"MAX_IT: the checkpoint .* at outer step 3 >= -cont_max_it 3",
            extra=lambda out: None if json.load(open(s))["outer_iterations"] == 3 else "a step was taken")
    # the intact checkpoint still resumes to the full run's result, with its unconstrained energy
    c.check("restart_ok", BASE + ["-restart_file", ck, "-summary_file", s],
            extra=lambda out: None if json.load(open(s))["energy_unconstrained"] == json.load(open(full))["energy_unconstrained"] and math.isclose(json.load(open(s))["energy"], json.load(open(full))["energy"], rel_tol=1e-10) else "other energies than the full run")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--group", required=True)
    ap.add_argument("--out", required=True)
    opt = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="sg_io_")
    c = Cases(tmp)
    try:
        globals()["group_" + opt.group](c)
    except Exception as e:  # the script itself failed: a failed test, with the reason
        c.failed.append("io_cases.py: %s: %s" % (type(e).__name__, e))
    finally:
        subprocess.run(["umount", os.path.join(tmp, "fs")], capture_output=True)
        shutil.rmtree(tmp, ignore_errors=True)
    res = {"cases": len(c.passed) + len(c.failed), "passed": c.passed, "failed": c.failed, "skipped": c.skipped}
    with open(opt.out + ".json", "w") as f:
        json.dump(res, f, indent=1)
    print(json.dumps(res, indent=1))


if __name__ == "__main__":
    main()
