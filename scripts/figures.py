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
  cattaneo.png, cattaneo.md  2D Cattaneo-Mindlin partial slip (options/cattaneo.opts): q(x)/(F p0) ours against
            Johnson's, the stick zones marked; the table of P, Q/(F P), a, c/a, the stick zone's offset and the
            profile error on the meshes CATTANEO_MESHES, and the Hertz half width against nu (with --only cattaneo)
  friction_ex1.png  Example 1 (240 x 80) with Coulomb F = 0.3 (options/ex1_friction.opts): along the contact boundary the
            normal pressure, the tangential traction in the band |lam_T| <= F lam_N, the stick/slip/free states
  friction_ex2.png  Example 2 with Coulomb F = 0.3 (options/ex2_friction.opts): the contact face, vertices coloured by
            state, tangential traction arrows (both with --only friction; scripts/plot_friction.py draws them)
  twobody.png  two elastic cylinders (options/twobody_hertz.opts on meshes/tb_cylinders2d_s2.msh): the bodies near the
            contact coloured by von Mises, and the pressure on the slave side (contact_pressure) and on the master side
            (master_pressure) against Hertz's at the run's force (with --only twobody; scripts/plot_twobody.py)

usage: figures.py [--only ex1,ex2,loadsteps,punch,friction,cattaneo,twobody]
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
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "tests"))
import cattaneo as cattaneo_check  # noqa: E402

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


def twobody():
    s, _ = sgrun.run("-options_file options/twobody_hertz.opts -dm_plex_filename meshes/tb_cylinders2d_s2.msh", "twobody", RUNS, fields=True)
    if not s.get("converged"):
        raise sgrun.RunError("twobody did not converge (%s), see results/runs/twobody.log" % s.get("reason"))
    # Hertz for two equal cylinders of radius 1 (R = 1/2, 1/E* = 2 (1 - nu^2) / E) at the whole pair's force, twice the half's
    estar = 1 / (2 * (1 - s["nu"] ** 2) / s["E"])
    subprocess.run([PY, os.path.join(sgrun.ROOT, "scripts", "plot_twobody.py"), os.path.join(RUNS, "twobody.h5"), os.path.join(RES, "twobody.png"),
                    "--estar", repr(estar), "--rhertz", "0.5", "--force", repr(2 * s["pair_force"]), "--window", "0.1",
                    "--title", "Two elastic cylinders (dual mortar, non-matching meshes)"], check=True)
    print("wrote results/twobody.png")


CATTANEO_MESHES = (1, 2, 4)  # meshes/cattaneo_s<k>.msh: vertex spacing 0.004 / k at the contact


def cattaneo_mesh(k):
    path = os.path.join(sgrun.ROOT, "meshes", "cattaneo_s%d.msh" % k)
    if not os.path.exists(path):
        subprocess.run(["make", "-s", "meshes/cattaneo_s%d.msh" % k], cwd=sgrun.ROOT, check=True)
    return "meshes/cattaneo_s%d.msh" % k


def cattaneo():
    """2D Cattaneo-Mindlin: options/cattaneo.opts on the meshes CATTANEO_MESHES (tests/cattaneo.py measures), the Hertz
    part against nu."""
    E, R, F = 1.0, 1.0, 0.5
    rows, hertz = [], []
    for k in CATTANEO_MESHES:
        mesh = cattaneo_mesh(k)
        name = "cattaneo_s%d" % k
        s, _ = sgrun.run("-options_file options/cattaneo.opts -dm_plex_filename %s" % mesh, name, RUNS, fields=True)
        h5 = os.path.join(RUNS, name + ".h5")
        for st in cattaneo_check.steps(h5):
            r = cattaneo_check.measure(h5, E, 0.49, R, F, st)
            r.update(mesh=k, wall=s.get("wall_time"))
            rows.append(r)
    for nu in (0.3, 0.45, 0.49, 0.499):
        for k in CATTANEO_MESHES:
            name = "cattaneo_hertz_nu%g_s%d" % (nu, k)
            s, _ = sgrun.run("-options_file options/cattaneo_problem.opts -dm_plex_filename %s -nu %g" % (cattaneo_mesh(k), nu),
                             name, RUNS, check=False, fields=True)
            if not s.get("converged"):
                hertz.append({"nu": nu, "mesh": k, "failed": s.get("reason", "no summary")})
                continue
            r = cattaneo_check.measure(os.path.join(RUNS, name + ".h5"), E, nu, R)
            r.update(nu=nu, mesh=k)
            hertz.append(r)
    # nu = 0.3 (Dundurs' beta 0.167 instead of 0.0196) on s4: what the coupling does
    k = 4
    name = "cattaneo_nu0.3_s%d" % k
    sgrun.run("-options_file options/cattaneo.opts -dm_plex_filename %s -nu 0.3" % cattaneo_mesh(k), name, RUNS, fields=True)
    h5 = os.path.join(RUNS, name + ".h5")
    coupled = [cattaneo_check.measure(h5, E, 0.3, R, F, st) for st in cattaneo_check.steps(h5)]

    fine = [r for r in rows if r["mesh"] == CATTANEO_MESHES[-1]]
    fig, ax = plt.subplots(figsize=(8, 5))
    xx = np.linspace(-1.05, 1.05, 841)
    with cattaneo_check.h5py.File(os.path.join(RUNS, "cattaneo_s%d.h5" % CATTANEO_MESHES[-1]), "r") as f:
        xv = f["geometry/vertices"][()]
        g = f["vertex_fields"]
        for r, col in zip(fine[1:], ["C0", "C1", "C2", "C3", "C4"]):
            st = r["step"]
            lt = cattaneo_check.field(g, "tangential_traction", st)[:, 0]
            state = cattaneo_check.field(g, "friction_state", st).ravel().round()
            on = (np.abs(xv[:, 1]) < 1e-12) & (np.abs(xv[:, 0]) <= 1.1 * r["a_hertz"])
            o = np.argsort(xv[on, 0])
            xs, qs, ss = xv[on, 0][o] / r["a_hertz"], np.sign(r["Q"]) * lt[on][o] / (F * r["p0_hertz"]), state[on][o]
            lab = "Q/(FP) = %.2f" % r["Q_over_FP"]
            ax.plot(xx, cattaneo_check.theory_q(xx, 1.0, r["c_theory"] / r["a_hertz"]), "-", color=col, lw=1.2, label=lab + ": Cattaneo-Mindlin")
            ax.plot(xs[ss == 2], qs[ss == 2], "o", ms=3, mfc="none", color=col, label=lab + ": ours, slip vertices")
            ax.plot(xs[ss == 1], qs[ss == 1], "o", ms=3, color=col, label=lab + ": ours, stick vertices")
            lo, hi = (r["e_c"] - r["c"]) / r["a_hertz"], (r["e_c"] + r["c"]) / r["a_hertz"]
            ax.plot([lo, hi], [-0.04 - 0.03 * fine.index(r)] * 2, "-", color=col, lw=4, solid_capstyle="butt")
            ax.plot([-r["c_theory"] / r["a_hertz"], r["c_theory"] / r["a_hertz"]], [-0.04 - 0.03 * fine.index(r)] * 2, "|", color="k", ms=8)
    ax.plot(xx, cattaneo_check.theory_q(xx, 1.0, 0.0), "k:", lw=1, label="F p(x): full slip")
    ax.set_xlabel("x / a (a: Hertz's, from our P)")
    ax.set_ylabel("q(x) / (F p0)")
    ax.set_title("2D Cattaneo-Mindlin partial slip, nu = 0.49, F = 0.5, h/a = %.3f\n"
                 "bars below: our stick zones (black ticks: Cattaneo's +-c)" % fine[0]["h_over_a"])
    ax.set_xlim(-1.1, 1.1)
    ax.set_ylim(-0.05 - 0.03 * len(fine), 1.05)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    save(fig, "cattaneo.png")
    cattaneo_table(rows, hertz, coupled)


def cattaneo_table(rows, hertz, coupled):
    L = ["# 2D Cattaneo-Mindlin partial slip: ours against K. L. Johnson, Contact Mechanics (1985)", "",
         "Written by `scripts/figures.py --only cattaneo` (`make figures`) from the runs it makes; measured with "
         "`tests/cattaneo.py`. %s." % sgrun.machine(), "",
         "Problem (`options/cattaneo.opts`, `meshes/cattaneo.geo`): a rigid cylinder, R = 1, of Hertz's parabolic profile "
         "d = x^2/(2R), on the top face of the elastic block [-1,1] x [-1,0] (plane strain, E = 1, nu = 0.49), which stands "
         "for the half plane (a is about 0.04, a 25th of the block's half width and depth). The obstacle is fixed; the "
         "block's bottom is moved: load step 1 up by 0.0029 (the cylinder indents, load P per unit thickness), steps 2-4 "
         "keep that and move it sideways (tangential load Q, the contact's tangential reaction). Coulomb friction F = 0.5 "
         "acts on the slip increment of each step. Theory (Johnson eqs. 4.45, 4.43, section 7.1), evaluated with our P "
         "and Q: a^2 = 4 P R (1 - nu^2) / (pi E), p0 = 2 P / (pi a), c/a = sqrt(1 - Q/(F P)), q(x) = F p0 sqrt(1 - x^2/a^2) "
         "in the slip zones c <= |x| <= a and F p0 [sqrt(1 - x^2/a^2) - (c/a) sqrt(1 - x^2/c^2)] in the stick zone |x| < c. "
         "Cattaneo's solution assumes that the normal and tangential problems decouple (Dundurs' beta = 0); a rigid "
         "indenter on an elastic body has beta = (1 - 2 nu)/(2 (1 - nu)) = 0.0196 at nu = 0.49.", "",
         "Measured: a = half the summed lumped weights of the active vertices (within h/2 of the zone's edges, h the "
         "vertex spacing), c the same of the stick vertices, e_c the stick zone's centre (its offset); a_fit and c_fit "
         "from least-squares quadratics through p^2 and (F p - |q|)^2 over the active and stick vertices, whose roots are "
         "the zones' edges (e_c,fit the centre of c_fit's roots); the profile error q_i - q(x_i) over the contact vertices in "
         "units of F p0 (rms, max), nodal and filtered by (1/4, 1/2, 1/4) over neighbouring vertices: near nu = 1/2 the "
         "P1 contact tractions oscillate from vertex to vertex about the profile (the locking's checkerboard mode), which "
         "the filter removes (the theory is filtered alike).", "",
         "![q(x)](cattaneo.png)", "",
         "| mesh | h/a | step | P | Q/(F P) | a | a (Hertz) | a_fit | c/a | c_fit/a_fit | c/a (Cattaneo) | e_c/a | e_c,fit/a | stick, slip vertices | q error rms, max | filtered q error rms, max |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        tang = r["step"] > 1
        L.append("| s%d | %.4f | %s | %.5e | %s | %.5f | %.5f | %.5f | %s | %s | %s | %s | %s | %d, %d | %.4f, %.4f | %.4f, %.4f |" % (
            r["mesh"], r["h_over_a"], r["step"], r["P"], "%.4f" % r["Q_over_FP"] if tang else "%.1e" % r["Q_over_FP"],
            r["a"], r["a_hertz"], r["a_fit"],
            *(("%.4f" % r["c_over_a"], "%.4f" % r["c_fit_over_a_fit"], "%.4f" % r["c_over_a_theory"], "%+.4f" % r["e_c_over_a"],
               "%+.4f" % r["e_c_fit_over_a"]) if tang else ("%.4f" % r["c_over_a"], "", "", "", "")),
            r["stick"], r["slip"], r["q_err_rms"], r["q_err_max"], r["q_err_smooth_rms"], r["q_err_smooth_max"]))
    L += ["", "Convergence, over the tangential steps 2-4 (Q/(F P) about 0.2, 0.5, 0.8) of each mesh:", "",
          "| mesh | h/a | largest abs(c/a - Cattaneo), stick vertices | largest abs(c_fit/a_fit - Cattaneo) | largest abs(e_c,fit)/a | filtered q error rms | nodal q error rms |",
          "|---|---|---|---|---|---|---|"]
    for k in CATTANEO_MESHES:
        t = [r for r in rows if r["mesh"] == k and r["step"] > 1]
        L.append("| s%d | %.4f | %.4f | %.4f | %.4f | %.4f-%.4f | %.4f-%.4f |" % (
            k, t[0]["h_over_a"], max(abs(r["c_over_a"] - r["c_over_a_theory"]) for r in t),
            max(abs(r["c_fit_over_a_fit"] - r["c_over_a_theory"]) for r in t), max(abs(r["e_c_fit_over_a"]) for r in t),
            min(r["q_err_smooth_rms"] for r in t), max(r["q_err_smooth_rms"] for r in t),
            min(r["q_err_rms"] for r in t), max(r["q_err_rms"] for r in t)))
    L += ["", "With nu = 0.3 (beta = 0.167, where Cattaneo's decoupling does not hold) on s4:", "",
          "| step | Q/(F P) | c/a | c/a (Cattaneo) | e_c/a | stick, slip | filtered q error rms, max |", "|---|---|---|---|---|---|---|"]
    for r in coupled:
        L.append("| %s | %.4f | %.4f | %.4f | %+.4f | %d, %d | %.4f, %.4f |" % (r["step"], r["Q_over_FP"], r["c_over_a"], r["c_over_a_theory"],
                                                                       r["e_c_over_a"], r["stick"], r["slip"], r["q_err_smooth_rms"], r["q_err_smooth_max"]))
    L += ["", "The normal part alone (`options/cattaneo_problem.opts`: frictionless, one step), a against Hertz's as nu -> 1/2 "
          "(P1 triangles lock):", "",
          "| nu | mesh | h/a | P | a | a (Hertz) | error | a_fit | error of a_fit |", "|---|---|---|---|---|---|---|---|---|"]
    for r in hertz:
        if "failed" in r:
            L.append("| %g | s%d | | failed: %s | | | | | |" % (r["nu"], r["mesh"], r["failed"]))
        else:
            L.append("| %g | s%d | %.4f | %.5e | %.5f | %.5f | %.2f %% | %.5f | %.2f %% |" % (
                r["nu"], r["mesh"], r["h_over_a"], r["P"], r["a"], r["a_hertz"], 100 * r["err_a"], r["a_fit"], 100 * r["err_a_fit"]))
    sgrun.write_atomic(os.path.join(RES, "cattaneo.md"), "\n".join(L) + "\n")
    print("wrote results/cattaneo.md")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--only", default="ex1")
    opt = ap.parse_args()
    for part in opt.only.split(","):
        {"ex1": ex1, "ex2": ex2, "loadsteps": loadsteps, "punch": punch, "friction": friction, "cattaneo": cattaneo, "twobody": twobody}[part]()


if __name__ == "__main__":
    main()
