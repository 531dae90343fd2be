"""Runs scripts/render.py under xvfb-run and pvpython for the checkers of the manual and of the .xmf files.

Xvfb's GLX sometimes refuses the window (vtkXOpenGLRenderWindow aborts in SupportsOpenGL or CreateAWindow, or
GLXBadContext), more often when several X servers start at once. Such a start is tried again, twice; after three
refusals the render is reported as an environment failure ("gl"), never as a success.
"""
import os
import re
import shutil
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GL_FAILED = re.compile(r"SupportsOpenGL|CreateAWindow|GLXBad|X Error|Could not find a decent|bad X server connection")


def available():
    """(pvpython, xvfb-run) paths, or None for the missing ones."""
    return shutil.which("pvpython"), shutil.which("xvfb-run")


def blank(png):
    """True when the picture has a single colour (nothing drawn); without an image library: its size is tiny."""
    try:
        import matplotlib.image as mpimg
        import numpy as np
        a = mpimg.imread(png)
        return bool(np.all(a == a[0, 0]))
    except ImportError:
        return os.path.getsize(png) < 2000


def render(argv, png, attempts=3, cwd=ROOT, env=None, log=print):
    """Runs `xvfb-run -a -s "-screen 0 1280x1024x24" pvpython scripts/render.py ARGV...` (ARGV: the result, PNG and
    options). Returns (verdict, output): "ok" (exit 0 and a PNG that is not blank), "gl" (the X server's GL refused
    the window ATTEMPTS times) or "failed"."""
    pvpython, xvfb = available()
    out, rc = "", 1
    for attempt in range(attempts):
        r = subprocess.run([xvfb, "-a", "-s", "-screen 0 1280x1024x24", pvpython, os.path.join(ROOT, "scripts", "render.py")] + argv,
                           cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=300)
        out, rc = r.stdout.decode(errors="replace"), r.returncode
        if rc == 0 or not GL_FAILED.search(out):
            break
        log("render.py: the X server's GL failed (attempt %d of %d)%s" % (attempt + 1, attempts,
                                                                           ": trying again" if attempt + 1 < attempts else ""))
    if rc != 0 and GL_FAILED.search(out):
        return "gl", out
    if rc != 0 or not os.path.isfile(png) or blank(png):
        return "failed", out
    return "ok", out
