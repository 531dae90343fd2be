"""What the generators, the checks and the runner of the fuzz test share: the repository, the runs and cases, the
value pools, a case directory's snapshot."""
import math
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "scripts"))
import sgrun  # noqa: E402

ROOT = sgrun.ROOT
ENV = sgrun.mpi_env(single_copy=False)

DEFAULT_KKT_TOL = 1e-10
MEM_LIMIT = 2 << 30  # address space per process: an absurd mesh size fails fast instead of swapping the machine
SENTINEL = b"a file that was here before the run\n"
CRASH = re.compile(r"Caught signal|Segmentation|Signal received|signal number|exited on signal|buffer overflow detected|"
                   r"stack smashing|double free|corrupted|free\(\): invalid|malloc\(\): |Aborted \(core dumped\)")


# ---------------------------------------------------------------- value pools

def num(x):
    return x if isinstance(x, str) else "%.6g" % x


def pick_weird_number(rng, orig=None):
    """A number or a non-number for a field that held `orig`."""
    pool = ["0", "-1", "1e308", "-1e308", "1e-320", "nan", "inf", "-inf", "2147483648", "9223372036854775808",
            "abc", "", "1,2,3", "0x10", "1e999", "--", ",", "1,,2", "%d" % rng.randint(-1000, 100000)]
    if orig is not None:
        try:
            v = float(orig)
            pool += [num(v * 10 ** rng.randint(-8, 8)), num(-v), num(v * 1.0001), str(int(v) + rng.choice([-1, 1]))]
        except ValueError:
            pass
    return rng.choice(pool)


def log_uniform(rng, lo, hi):
    return 10 ** rng.uniform(math.log10(lo), math.log10(hi))


# ---------------------------------------------------------------- runs and cases

class Run:
    """One invocation of bin/signorini. args are relative to the repository, except files in the case directory."""

    def __init__(self, args, np_=1, kkt_tol=None, y0_admissible=False, inputs=(), tail=(), checkpoint=None, exe=None):
        self.args, self.np, self.tail = list(args), np_, list(tail)
        self.exe = exe  # another program than bin/signorini (bin/misuse_tests): judged by check_misuse
        self.judge = None  # judge(run, summary) -> [(class, detail)]: the generator's own checks of a run
        self.kkt_tol = kkt_tol
        self.y0_admissible = y0_admissible  # y = 0 is admissible: a solution's energy is <= 0
        self.inputs = list(inputs)  # files of the case directory the run reads
        self.checkpoint = checkpoint  # a -checkpoint_file in the case directory
        self.result = None
        self.must_converge = False  # a well-posed problem: anything but exit 0 is a failure
        self.contact = False  # contact was asked for: an exit 0 without contact has dropped it silently
        self.exact = not any(a in ("-ksp_rtol", "-ksp_type", "-pc_type") or "hypre" in a or "mumps_reuse" in a for a in self.args)


class Case:
    """twin: True for the units twin of gen_options (the same verdict), or a function (case, summaries) ->
    [(class, detail, run)] that compares the runs of the case (a fresh solve against a restart, two controllers)."""

    def __init__(self, gen, index, desc, runs, twin=False):
        self.gen, self.index, self.desc, self.runs, self.twin = gen, index, desc, runs, twin
        self.violations = []  # (class, detail, run)
        self.skipped = False
        self.seconds = 0.0


def output_args(T):
    return ["-output_file", os.path.join(T, "r.h5"), "-summary_file", os.path.join(T, "r.json"),
            "-history_file", os.path.join(T, "r.csv")]


def options_in(args, name, default=None):
    """The last value of option `name` in args, reading -options_file files as PETSc does (later wins)."""
    val = default

    def walk(tokens, depth):
        nonlocal val
        i = 0
        while i < len(tokens):
            t = tokens[i]
            nxt = tokens[i + 1] if i + 1 < len(tokens) else None
            if t == "-options_file" and nxt is not None and depth < 4:
                p = nxt if os.path.isabs(nxt) else os.path.join(ROOT, nxt)
                try:
                    with open(p, errors="replace") as f:
                        for line in f:
                            line = line.split("#", 1)[0].split()
                            if line:
                                walk([line[0], " ".join(line[1:])] if len(line) > 1 else line, depth + 1)
                except OSError:
                    pass
                i += 2
                continue
            if t == name:
                val = nxt if nxt is not None and not (nxt.startswith("-") and nxt[1:2].isalpha()) else ""
            i += 1
    walk(list(args), 0)
    return val



def snapshot(T):
    snap = {}
    for dp, dn, fn in os.walk(T):
        for f in fn:
            p = os.path.join(dp, f)
            with open(p, "rb") as fp:
                snap[p] = fp.read()
    return snap


