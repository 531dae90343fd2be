"""Run bin/signorini from the reproduction, figure and benchmark scripts and read what it wrote."""
import csv
import json
import os
import shlex
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1", OPENBLAS_NUM_THREADS="1")
EX1 = "-options_file options/ex1.opts -options_file options/solver/mumps.opts"


class RunError(RuntimeError):
    pass


def run(args, name, outdir, np=1, check=True, fields=False):
    """Run the solver with the given option string; return (summary dict, history rows)."""
    os.makedirs(outdir, exist_ok=True)
    base = os.path.join(outdir, name)
    cmd = ["mpiexec", "-n", str(np), os.path.join(ROOT, "bin", "signorini")] + shlex.split(args)
    cmd += ["-summary_file", base + ".json", "-history_file", base + ".csv"]
    if fields:
        cmd += ["-output_file", base + ".h5"]
    p = subprocess.run(cmd, cwd=ROOT, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    with open(base + ".log", "w") as f:
        f.write(" ".join(shlex.quote(c) for c in cmd) + "\n" + p.stdout)
    if check and p.returncode != 0:
        raise RunError("%s failed (exit %d), see %s.log" % (name, p.returncode, base))
    summary = json.load(open(base + ".json")) if os.path.exists(base + ".json") else {}
    return summary, history(base + ".csv")


def history(path):
    rows = []
    if os.path.exists(path):
        with open(path) as f:
            for r in csv.DictReader(f):
                rows.append({k: (v if k == "kind" else (float(v) if v != "" else None)) for k, v in r.items()})
    return rows


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
