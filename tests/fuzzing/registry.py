"""The names the program registers, read from its own -help: the controller types (-cont_type) and the friction laws
(-friction_type). The fuzz test draws from these lists, so a type registered in the library is fuzzed without an edit
here (a law whose parameter the generators do not know is listed by the runner as not drawn).

-help needs a problem to reach the options of the contact and controller objects: a coarse Example 1 (under a second).
A choice list printed by PETSc ("(one of) a b c", "(choose one of) a b c") is read as it stands; without one (an option
read as a string), the names are the comma-separated words at the start of the option's description, as -help shows
them ("none, tresca (...), coulomb (...)")."""
import functools
import os
import re
import subprocess

from .common import ENV, ROOT

HELP_ARGS = ["-help", "-options_file", "tests/opts/ex1_coarse.opts", "-cont_monitor", "0"]


@functools.lru_cache(maxsize=None)
def help_text():
    exe = os.path.join(ROOT, "bin", "signorini")
    if not os.access(exe, os.X_OK):
        raise SystemExit("fuzz: bin/signorini is missing: run make all (the fuzz test reads its registries from -help)")
    try:
        p = subprocess.run([exe] + HELP_ARGS, cwd=ROOT, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=120)
    except (OSError, subprocess.SubprocessError) as e:
        raise SystemExit("fuzz: bin/signorini %s failed: %s" % (" ".join(HELP_ARGS), e))
    return p.stdout.decode("utf-8", errors="replace")  # -help may print a byte that is no UTF-8


def names_of(option, text=None):
    """The values -help lists for `option` (in the order printed), or [] when the option is not in the text."""
    text = help_text() if text is None else text
    m = re.search(r"^\s*%s <now [^>]*>:? ?(.*)$" % re.escape(option), text, re.M)
    if not m:
        return []
    line = m.group(1)
    c = re.search(r"\((?:choose )?one of\) ([\w ]+?)\s*(\(|$)", line)
    if c:
        return c.group(1).split()
    desc = line.split(":", 1)[1] if ":" in line else line
    desc = re.sub(r"\([^()]*\)", "", re.sub(r"\([^()]*\)", "", desc))  # nested parentheses: twice
    words = []
    for item in desc.split(","):
        w = item.split()
        if len(w) != 1 or not re.match(r"^[a-z][a-z0-9_]*$", w[0]):
            break
        words.append(w[0])
    return words


def controllers():
    names = names_of("-cont_type")
    if not names:
        raise SystemExit("fuzz: no -cont_type names in the output of bin/signorini %s" % " ".join(HELP_ARGS))
    return names


def friction_laws():
    names = names_of("-friction_type")
    if "none" not in names:
        raise SystemExit("fuzz: no -friction_type names in the output of bin/signorini %s" % " ".join(HELP_ARGS))
    return names
