"""Run bin/signorini and read what it wrote: the one home of these helpers for the scripts here and for tests/*.py
(which put this directory on sys.path)."""
import csv
import json
import os
import shlex
import subprocess
import xml.etree.ElementTree as ET

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SIGNORINI = os.path.join(ROOT, "bin", "signorini")
EX1 = "-options_file options/ex1.opts -options_file options/solver/mumps.opts"


def mpi_env(oversubscribe=True, single_copy=True):
    """The environment of a run: mpiexec may run as root (containers, CI), one OpenBLAS thread per rank; with
    oversubscribe more ranks than cores; without single_copy OpenMPI's shared memory does not use single-copy
    transfers (CMA), which some containers refuse."""
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    if oversubscribe:
        env["OMPI_MCA_rmaps_base_oversubscribe"] = "1"
    if not single_copy:
        env["OMPI_MCA_btl_vader_single_copy_mechanism"] = "none"
    env["OPENBLAS_NUM_THREADS"] = "1"
    return env


ENV = mpi_env()


class RunError(RuntimeError):
    pass


def command(args, np=1, exe=SIGNORINI, wrapper=(), summary=None, history=None):
    """The command line of a run of exe with args: under `mpiexec -n np` (np None: without mpiexec, as an MPI
    singleton), wrapper (e.g. valgrind) in front of exe, then -summary_file and -history_file if given."""
    cmd = ([] if np is None else ["mpiexec", "-n", str(np)]) + list(wrapper) + [exe] + list(args)
    if summary:
        cmd += ["-summary_file", summary]
    if history:
        cmd += ["-history_file", history]
    return cmd


def execute(cmd, env=ENV, timeout=None):
    """Run cmd in the repository; the CompletedProcess has stdout and stderr together in .stdout (text)."""
    return subprocess.run(cmd, cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          timeout=timeout)


def run(args, name, outdir, np=1, check=True, fields=False):
    """Run the solver with the given option string; return (summary dict, history rows)."""
    os.makedirs(outdir, exist_ok=True)
    base = os.path.join(outdir, name)
    cmd = command(shlex.split(args), np, summary=base + ".json", history=base + ".csv")
    if fields:
        cmd += ["-output_file", base + ".h5"]
    p = execute(cmd)
    with open(base + ".log", "w") as f:
        f.write(" ".join(shlex.quote(c) for c in cmd) + "\n" + p.stdout)
    if check and p.returncode != 0:
        raise RunError("%s failed (exit %d), see %s.log" % (name, p.returncode, base))
    return summary(base + ".json"), history(base + ".csv")


def summary(path):
    """The JSON summary a run wrote, {} if there is none (ValueError if it is not JSON)."""
    if not os.path.exists(path):
        return {}
    with open(path) as f:
        return json.load(f)


def history(path):
    """The CSV history a run wrote, one dict a row (numbers as floats, empty cells None), [] if there is none."""
    rows = []
    if os.path.exists(path):
        with open(path) as f:
            for r in csv.DictReader(f):
                rows.append({k: (v if k == "kind" else (float(v) if v != "" else None)) for k, v in r.items()})
    return rows


def result_problem(path, complete=False, width=None):
    """None if path is a readable result file of its kind (by its ending: summary .json, history .csv, XDMF .xmf,
    fields or checkpoint .h5), else why not. complete: also what only a finished run writes (the summary's
    converged and wall_time, the history's last "outer" row, the fields' viz group). width: at most this many
    characters of a read error's text."""
    if not os.path.exists(path):
        return "missing"
    try:
        if path.endswith(".json"):
            with open(path) as f:
                d = json.load(f)
            return None if not complete or ("converged" in d and "wall_time" in d) else "incomplete summary"
        if path.endswith(".csv"):
            with open(path) as f:
                rows = list(csv.reader(f))
            ok = rows and rows[0] and rows[0][0] == "kind" and all(len(r) == len(rows[0]) for r in rows)
            return None if ok and (not complete or rows[-1][0] == "outer") else "incomplete history"
        if path.endswith(".xmf"):
            ET.parse(path)
            return None
        if path.endswith(".h5"):
            import h5py  # only here: the scripts that never read HDF5 files do not need it
            with h5py.File(path, "r") as f:
                if "checkpoint" in f:
                    return None if "displacement" in f["checkpoint"] and "cont_type" in f["checkpoint"].attrs else "incomplete checkpoint"
                ok = "vertex_fields" in f and "cell_fields" in f and (not complete or "viz" in f)
                return None if ok else "incomplete fields"
    except Exception as e:  # any read error is a broken file
        return "%s: %s" % (type(e).__name__, str(e)[:width])
    return "unknown kind"


def write_atomic(path, text):
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    tmp = path + ".part"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def machine():
    """One line naming the machine and the PETSc version, for every table."""
    model = "unknown CPU"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    petsc = "PETSc (version unknown)"
    try:
        for line in open("/usr/lib/petsc/include/petscversion.h"):
            if "#define PETSC_VERSION_MAJOR" in line:
                major = line.split()[-1]
            elif "#define PETSC_VERSION_MINOR" in line:
                minor = line.split()[-1]
            elif "#define PETSC_VERSION_SUBMINOR" in line:
                sub = line.split()[-1]
        petsc = "PETSc %s.%s.%s" % (major, minor, sub)
    except (OSError, NameError):
        pass
    return "%d cores (%s), %s" % (os.cpu_count() or 0, model, petsc)
