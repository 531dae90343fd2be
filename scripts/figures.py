#!/usr/bin/python3
"""The paper's figures from our runs (matplotlib, Debian's Python): PNG files under results/.

  fig4.png  Example 1, deformed mesh (displacement and gap x20) coloured by the elastic shear energy density, nu = 0.49, gamma = 1e10
  fig5.png  Example 1, path value V(gamma) on a sweep of gamma against the models fitted at g* = 1e2, 1e3, 1e5 (nu = 0.4, 0.4999)
  fig6.png  Example 1, V along the IPF iterates against the path, log gamma axis
  fig7.png  Example 2, V(gamma) against the models fitted at g* = 1e6, 1e8, 1e10       (with --only ex2)
  fig8.png  Example 2, deformed mesh coloured by von Mises stress; fig8_pressure.png the contact pressure on the bottom
  loadcurve.png  coarse Example 2 in 10 load steps, the ball moved 0.02 up: contact force against load factor and
            indentation (with --only loadsteps)
  punch_pressure.png  the CAD punch with rounded edges (options/punch.opts): contact pressure on the block's top face
            (with --only punch)

  friction_ex1.png  Example 1 (240 x 80) with Coulomb F = 0.3 (options/ex1_friction.opts): along the contact boundary the
            normal pressure, the tangential traction in the band |lam_T| <= F lam_N, the stick/slip/free states
  friction_ex2.png  Example 2 with Coulomb F = 0.3 (options/ex2_friction.opts): the contact face, vertices coloured by
            state, tangential traction arrows (both with --only friction; scripts/plot_friction.py draws them)

usage: figures.py [--only ex1,ex2,loadsteps,punch,friction]
"""
import argparse
import os
import subprocess
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sgrun  # noqa: E402

RES = os.path.join(sgrun.ROOT, "results")
RUNS = os.path.join(RES, "runs")
PY = "/usr/bin/python3"


def save(fig, name):
    path = os.path.join(RES, name)
    fig.savefig(path + ".part.png", dpi=150, bbox_inches="tight")
    os.replace(path + ".part.png", path)
    plt.close(fig)
    print("wrote results/%s" % name)


def model(V0, g, V, dV):
    E = g * g * dV / (V - V0 - g * dV)
    C2 = E * (E + g) * (V - V0) / g
    C1 = V0 + C2 / E
    return lambda x: C1 - C2 / (E + x)


def sweep(base, name, exps):
    """V(gamma) and V'(gamma) on the path (each (P_gamma) solved exactly from the unconstrained start)."""
    rows = []
    for e in exps:
        s, _ = sgrun.run("%s -options_file options/cont/none.opts -contact_gamma %.6g" % (base, 10.0 ** e), "%s_g%+.2f" % (name, e), RUNS)
        rows.append((10.0 ** e, s["path_value"], s["path_derivative"], s["energy_unconstrained"]))
    data = np.array(rows)
    np.savetxt(os.path.join(RES, name + ".csv"), data, delimiter=",", header="gamma,V,dVdgamma,V0", comments="")
    return data


def value_figure(data_sets, stars, title, name):
    fig, axes = plt.subplots(1, len(data_sets), figsize=(6 * len(data_sets), 4.5))
    axes = np.atleast_1d(axes)
    for ax, (label, d) in zip(axes, data_sets):
        g, V, dV, V0 = d[:, 0], d[:, 1], d[:, 2], d[:, 3][0]
        ax.semilogx(g, V, "k-", lw=2, label="V(gamma)")
        for gs, style in zip(stars, ["--", "-.", ":"]):
            i = int(np.argmin(np.abs(np.log10(g) - np.log10(gs))))
            m = model(V0, g[i], V[i], dV[i])
            ax.semilogx(g, m(g), style, lw=1.5, label="model at g* = %.0e" % g[i])
            ax.plot(g[i], V[i], "o", color=ax.lines[-1].get_color())
        ax.set_xlabel("gamma")
        ax.set_ylabel("V")
        ax.set_title(label)
        ax.legend(fontsize=8)
        lo, hi = V.min(), V.max()
        ax.set_ylim(lo - 0.1 * (hi - lo), hi + 0.1 * (hi - lo))
    fig.suptitle(title)
    save(fig, name)


def ex1():
    base = sgrun.EX1
    s, _ = sgrun.run("%s -options_file options/cont/none.opts -nu 0.49 -contact_gamma 1e10 -output_magnification 20" % base, "fig4", RUNS, fields=True)
    subprocess.run([PY, os.path.join(sgrun.ROOT, "scripts", "plot_mesh.py"), os.path.join(RUNS, "fig4.h5"), os.path.join(RES, "fig4.png"),
                    "--title", "Example 1: deformed mesh (displacement and gap x20), elastic shear energy density, nu = 0.49, gamma = 1e10"], check=True)
    print("wrote results/fig4.png")
    exps = np.arange(0, 12.01, 0.5)
    d4 = sweep(base + " -nu 0.4", "fig5_nu0.4", exps)
    d9 = sweep(base + " -nu 0.4999", "fig5_nu0.4999", exps)
    value_figure([("nu = 0.4", d4), ("nu = 0.4999", d9)], [1e2, 1e3, 1e5], "Example 1: path value V(gamma) and models m(gamma)", "fig5.png")
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    for ax, nu, d in zip(axes, (0.4, 0.4999), (d4, d9)):
        _, h = sgrun.run("%s -options_file options/cont/ipf.opts -nu %g" % (base, nu), "fig6_ipf_nu%g" % nu, RUNS)
        it = [(r["gamma"], r["V"]) for r in h if r["kind"] == "outer"]
        ax.semilogx(d[:, 0], d[:, 1], "k-", lw=2, label="path value V(gamma)")
        ax.semilogx([a for a, _ in it], [b for _, b in it], "rs--", label="J(gamma_k, y_k+1) at the IPF iterates")
        for k, (a, b) in enumerate(it):
            ax.annotate("gamma_%d" % (k + 1), (a, b), textcoords="offset points", xytext=(4, -12), fontsize=7)
        ax.set_xlabel("gamma")
        ax.set_ylabel("V")
        ax.set_title("nu = %g" % nu)
        ax.legend(fontsize=8)
    fig.suptitle("Example 1: inexact path-following iterates against the path")
    save(fig, "fig6.png")


def ex2():
    base = "-options_file options/ex2.opts"
    s, _ = sgrun.run(base + " -output_magnification 1", "fig8", RUNS, fields=True)
    subprocess.run([PY, os.path.join(sgrun.ROOT, "scripts", "plot_mesh.py"), os.path.join(RUNS, "fig8.h5"), os.path.join(RES, "fig8.png"),
                    "--field", "von_mises", "--magnify", "1", "--title", "Example 2: deformed mesh coloured by von Mises stress"], check=True)
    subprocess.run([PY, os.path.join(sgrun.ROOT, "scripts", "plot_pressure.py"), os.path.join(RUNS, "fig8.h5"), os.path.join(RES, "fig8_pressure.png")], check=True)
    print("wrote results/fig8.png, results/fig8_pressure.png")
    d = sweep("-options_file options/ex2_problem.opts -options_file options/solver/mumps.opts", "fig7_ex2", np.arange(4, 14.01, 0.5))
    value_figure([("Example 2", d)], [1e6, 1e8, 1e10], "Example 2: path value V(gamma) and models m(gamma)", "fig7.png")


def loadsteps():
    name = "loadcurve"
    sgrun.run("-options_file options/ex2_problem.opts -dm_plex_filename meshes/ex2_coarse.msh -options_file options/solver/mumps.opts "
              "-options_file options/cont/ipf.opts -obstacle_translation 0,0,0.02 -load_steps 10 -load_curve_file %s"
              % os.path.join(RUNS, name + "_curve.csv"), name, RUNS)
    subprocess.run([PY, os.path.join(sgrun.ROOT, "scripts", "load_curve.py"), os.path.join(RUNS, name + "_curve.csv"), os.path.join(RES, name + ".png"),
                    "--title", "Coarse Example 2 in 10 load steps (Dirichlet values and the ball's 0.02 lift scaled together)"], check=True)
    print("wrote results/%s.png" % name)


def punch():
    base = "-options_file options/punch.opts -options_file options/solver/mumps.opts -options_file options/cont/pdas.opts"
    sgrun.run(base, "punch", RUNS, fields=True)
    subprocess.run([PY, os.path.join(sgrun.ROOT, "scripts", "plot_pressure.py"), os.path.join(RUNS, "punch.h5"), os.path.join(RES, "punch_pressure.png"),
                    "CAD punch: pressure on the top face"], check=True)
    print("wrote results/punch_pressure.png")


def friction():
    for name, args, title in (("friction_ex1", "-options_file options/ex1_friction.opts -box_faces 240,80", "Example 1 (240 x 80), Coulomb F = 0.3"),
                              ("friction_ex2", "-options_file options/ex2_friction.opts", "Example 2, Coulomb F = 0.3")):
        s, _ = sgrun.run(args, name, RUNS, fields=True)
        if not s.get("converged"):
            raise sgrun.RunError("%s did not converge (%s), see results/runs/%s.log" % (name, s.get("reason"), name))
        subprocess.run([PY, os.path.join(sgrun.ROOT, "scripts", "plot_friction.py"), os.path.join(RUNS, name + ".h5"), os.path.join(RES, name + ".png"),
                        "--coefficient", "%g" % s["friction_coefficient"], "--title", title], check=True)
        print("wrote results/%s.png" % name)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--only", default="ex1")
    opt = ap.parse_args()
    for part in opt.only.split(","):
        {"ex1": ex1, "ex2": ex2, "loadsteps": loadsteps, "punch": punch, "friction": friction}[part]()


if __name__ == "__main__":
    main()
