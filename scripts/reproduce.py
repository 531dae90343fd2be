#!/usr/bin/python3
"""Reproduce the numbers of Stadler (2007) with bin/signorini and write them beside the paper's.

usage: reproduce.py [--only table1,alm,table2,ipf,ex2] [--out results/reproduction.md]
`make table1` writes results/table1.md (Table 1 only); `make reproduce` writes results/reproduction.md.
Every number in our columns is computed by the runs made here (logs and summaries under results/runs/).
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sgrun  # noqa: E402

RUNS = os.path.join(sgrun.ROOT, "results", "runs")
NUS = [0.4, 0.49, 0.499, 0.4999]
GAMMAS = ["1e2", "1e4", "1e6", "1e10"]
PAPER_T1 = {0.4: [4, 6, 7, 7], 0.49: [3, 7, 8, 8], 0.499: [4, 8, 12, 12], 0.4999: [4, 9, 25, 29]}
PAPER_T2 = {0.4: ([1.00e2, 1.62e3, 1.75e5, 1.75e8, 1.76e12], [3, 3, 6, 1, 1]),
            0.4999: ([1.00e2, 2.80e3, 3.23e5, 3.24e8, 3.24e12], [3, 4, 7, 3, 1])}
PAPER_PF02 = {0.4: (6, 17), 0.4999: (7, 18)}
PAPER_IPF = {0.4: 11, 0.4999: 15}


def table1():
    out = ["## Table 1: SSN iterations for (P_gamma), Example 1, 120 x 40, from the unconstrained start", "",
           "Each cell: **ours** (paper). Counting convention: the number of linear solves with a contact Jacobian, i.e. "
           "SNES iterations of `-cont_type none`; the initial unconstrained solve is not counted, and the solve that "
           "confirms the active set (A_{k+1} = A_k) is the last one counted. Mesh: every square split along the diagonal "
           "from its lower left to its upper right corner (`-box_diagonal right`). Linear solves exact (MUMPS Cholesky).", "",
           "| nu \\ gamma | " + " | ".join(GAMMAS) + " |", "|---|" + "---|" * len(GAMMAS)]
    counts = {}
    for nu in NUS:
        cells = []
        for j, g in enumerate(GAMMAS):
            s, _ = sgrun.run("%s -options_file options/cont/none.opts -nu %g -contact_gamma %s" % (sgrun.EX1, nu, g), "t1_nu%g_g%s" % (nu, g), RUNS)
            counts[(nu, g)] = s["ssn_iterations"]
            cells.append("**%d** (%d)" % (s["ssn_iterations"], PAPER_T1[nu][j]))
        out.append("| %g | %s |" % (nu, " | ".join(cells)))
    grow_g = all(counts[(nu, GAMMAS[0])] < counts[(nu, GAMMAS[-1])] for nu in NUS)
    grow_nu = all(counts[(NUS[0], g)] < counts[(NUS[-1], g)] for g in GAMMAS[2:])
    left = {}
    for nu in (0.4, 0.4999):
        for g in ("1e6", "1e10"):
            s, _ = sgrun.run("%s -options_file options/cont/none.opts -nu %g -contact_gamma %s -box_diagonal left" % (sgrun.EX1, nu, g), "t1L_nu%g_g%s" % (nu, g), RUNS)
            left[(nu, g)] = s["ssn_iterations"]
    out += ["", "Trend: counts grow with gamma for every nu: %s; at gamma >= 1e6 they grow from nu = 0.4 to 0.4999: %s." % (
        "yes" if grow_g else "NO", "yes" if grow_nu else "NO"), "",
        "Why the cells differ: the paper's mesh diagonal and its treatment of the boundary integral in the max-term are not "
        "stated. With the other diagonal (`-box_diagonal left`) the counts at gamma = 1e6, 1e10 are "
        "%d, %d (nu = 0.4) and %d, %d (nu = 0.4999) instead of %d, %d and %d, %d: a few iterations either way, "
        "the size of the differences to the paper. At gamma = 1e2 we need %s solves where the paper reports 3-4: counting "
        "active-set evaluations instead of solves would add one to every cell." % (
            left[(0.4, "1e6")], left[(0.4, "1e10")], left[(0.4999, "1e6")], left[(0.4999, "1e10")],
            counts[(0.4, "1e6")], counts[(0.4, "1e10")], counts[(0.4999, "1e6")], counts[(0.4999, "1e10")],
            "-".join(str(x) for x in sorted({counts[(nu, "1e2")] for nu in NUS}))), ""]
    return out


def first_below(rows, tol):
    for r in rows:
        if r["kind"] == "outer" and r["kkt"] is not None and r["kkt"] <= tol:
            return int(r["outer"]), int(sum(x["ssn_its"] for x in rows if x["kind"] == "outer" and x["outer"] <= r["outer"]))
    return None, None


def alm():
    out = ["## First-order augmented Lagrangian (ALM), Example 1, nu = 0.4", ""]
    s, h = sgrun.run("%s -options_file options/cont/alm.opts -cont_max_it 5000 -cont_stall_it 500" % sgrun.EX1, "alm_fixed", RUNS)
    g, hg = sgrun.run("%s -options_file options/cont/alm.opts -alm_gamma_factor 10" % sgrun.EX1, "alm_growing", RUNS)
    f5, hf5 = sgrun.run("%s -options_file options/cont/alm.opts -alm_gamma 1e5" % sgrun.EX1, "alm_fixed_1e5", RUNS)
    o6, s6 = first_below(h, 1e-6)
    o8, s8 = first_below(h, 1e-8)
    ratios = [r["kkt"] for r in h if r["kind"] == "outer"]
    rate = (ratios[-1] / ratios[-101]) ** (1 / 100.0) if len(ratios) > 101 else float("nan")
    out += ["| run | outer steps | SSN iterations | final KKT residual | paper |", "|---|---|---|---|---|",
            "| gamma fixed at 1e3 | %d | %d | %.2e | 27 iterations overall |" % (s["outer_iterations"], s["ssn_iterations"], s["kkt_residual"]),
            "| gamma fixed at 1e3, to KKT 1e-6 | %s | %s | | |" % (o6, s6),
            "| gamma fixed at 1e3, to KKT 1e-8 | %s | %s | | |" % (o8, s8),
            "| gamma fixed at 1e5 | %d | %d | %.2e | |" % (f5["outer_iterations"], f5["ssn_iterations"], f5["kkt_residual"]),
            "| gamma 1e3, x10 per step | %d | %d | %.2e | \"speeds it up significantly\" |" % (g["outer_iterations"], g["ssn_iterations"], g["kkt_residual"]), "",
            "With gamma fixed, the multiplier error contracts by a constant factor per step: we measure %.4f over the last 100 "
            "steps. ALM is the proximal point method on the dual, so the factor is 1/(1 + gamma mu) with mu the smallest "
            "eigenvalue of the contact compliance on the active set; for high-frequency pressure modes mu ~ h/E = 5e-6 and "
            "gamma mu ~ 5e-3 at gamma = 1e3. The paper's 27 iterations are close to our count at gamma = 1e5 (row 4), while its "
            "path-following gammas match ours to a few percent (Table 2), so the regularization scales agree; the paper's "
            "'L2-norm of the nonlinear residual' for ALM is probably a weaker measure than our KKT residual (which includes "
            "the primal infeasibility at 1e-8 of the displacement scale). Growing gamma with the multiplier update converges in a few steps, as the "
            "paper says." % rate, ""]
    return out


def table2():
    out = ["## Table 2: exact path-following (PF), gamma_1 = 1e2, tau_k = 10^-k", "",
           "Per path step: gamma_l and the SSN iterations, **ours** (paper). Each (P_gamma) is solved exactly by SSN warm-started "
           "from the previous solution; stop when the KKT residual of (P) is below %s (options/ex1.opts: the paper's absolute "
           "1e-10 at Example 1's scale; our measure is relative to the displacement scale)." % opts_value("options/ex1.opts", "-cont_kkt_tol"), ""]
    dev = []
    for nu in (0.4, 0.4999):
        s, _ = sgrun.run("%s -options_file options/cont/pf.opts -nu %g" % (sgrun.EX1, nu), "pf_nu%g" % nu, RUNS)
        pg, ps = PAPER_T2[nu]
        dev += [abs(a - b) / b for a, b in zip(s["gammas"], pg)]
        n = max(len(s["gammas"]), len(pg))
        cell = lambda a, i, fmt: (fmt % a[i]) if i < len(a) else "-"
        out += ["nu = %g (%d outer, %d SSN iterations; paper %d, %d; final KKT residual %.2e)" % (nu, s["outer_iterations"], s["ssn_iterations"], len(pg), sum(ps), s["kkt_residual"]), "",
                "| path step l | " + " | ".join(str(i + 1) for i in range(n)) + " |", "|---|" + "---|" * n,
                "| gamma_l | " + " | ".join("**%s** (%s)" % (cell(s["gammas"], i, "%.2e"), cell(pg, i, "%.2e")) for i in range(n)) + " |",
                "| SSN iterations | " + " | ".join("**%s** (%s)" % (cell(s["path_ssn_iterations"], i, "%d"), cell(ps, i, "%d")) for i in range(n)) + " |", ""]
    out += ["With tau_k = 0.2^k:", "", "| nu | outer steps | SSN iterations | paper (outer, SSN) |", "|---|---|---|---|"]
    for nu in (0.4, 0.4999):
        s, _ = sgrun.run("%s -options_file options/cont/pf.opts -pf_tau0 0.2 -nu %g" % (sgrun.EX1, nu), "pf02_nu%g" % nu, RUNS)
        out.append("| %g | **%d** | **%d** | %d, %d |" % (nu, s["outer_iterations"], s["ssn_iterations"], PAPER_PF02[nu][0], PAPER_PF02[nu][1]))
    out += ["", "Our gamma sequences differ from the paper's by at most %.1f %%: the model function and update (12) are the "
            "paper's, and V, V' come from the same discrete energy. SSN counts per step differ by one here and there, the "
            "counting and mesh differences of Table 1." % (100 * max(dev)), ""]
    return out


def ipf():
    out = ["## Inexact path-following (IPF), Example 1 (tau = 1e6, tau_1 = 5, q = 1.5, our tau_3 = 100)", "",
           "| nu | outer steps | SSN iterations overall | SSN per step | gamma per step | paper |", "|---|---|---|---|---|---|"]
    for nu in (0.4, 0.4999):
        s, _ = sgrun.run("%s -options_file options/cont/ipf.opts -nu %g" % (sgrun.EX1, nu), "ipf_nu%g" % nu, RUNS)
        out.append("| %g | %d | **%d** | %s | %s | %d overall; 1, 1, 3, 2, ... per step |" % (
            nu, s["outer_iterations"], s["ssn_iterations"], ", ".join("%d" % x for x in s["path_ssn_iterations"]),
            ", ".join("%.1e" % x for x in s["gammas"]), PAPER_IPF[nu]))
    t3 = {}
    for tau3 in (1, 10):
        s, _ = sgrun.run("%s -options_file options/cont/ipf.opts -ipf_tau3 %g -nu 0.4" % (sgrun.EX1, tau3), "ipf_tau3_%g" % tau3, RUNS, check=False)
        t3[tau3] = "%s outer steps, %s SSN iterations%s" % (s.get("outer_iterations"), s.get("ssn_iterations"), "" if s.get("converged") else " (" + s.get("reason", "failed") + ")")
    out += ["", "Differences: r1 is the discrete dual norm sqrt(sum_j R_j^2 / m_j) (lumped vertex volumes m_j) of the "
            "equilibrium residual with the multiplier of the last Newton step, which an exact linear solve makes zero, so "
            "the neighbourhood is decided by r2 = ||lam - max(0, gamma (tau_N y - d))||. The paper leaves open how IPF ends: "
            "we cap gamma at 10 ||lam|| / (tol Y sqrt|Gamma_c|), where the path meets the KKT tolerance, and solve that last problem exactly; "
            "its SSN iterations are the last entry of the per-step column. tau_3 is not given in the paper; we use 100, which "
            "also gives the paper's 7 steps in Example 2. For nu = 0.4, tau_3 = 1 gives %s; tau_3 = 10 gives %s." % (t3[1], t3[10]), ""]
    return out


def opts_value(path, option):
    """The value an options file gives an option (the last line that sets it)."""
    val = None
    with open(os.path.join(sgrun.ROOT, path)) as f:
        for line in f:
            w = line.split("#")[0].split()
            if len(w) >= 2 and w[0] == option:
                val = w[1]
    if val is None:
        raise SystemExit("reproduce.py: %s does not set %s" % (path, option))
    return val


def ex2():
    out = ["## Example 2 (3D): inexact path-following, tau = 1e8, tau_1 = 5, q = 1.5, CG + BoomerAMG", ""]
    s, h = sgrun.run("-options_file options/ex2.opts", "ex2_ipf", RUNS)
    m, _ = sgrun.run("-options_file options/ex2_problem.opts -options_file options/solver/mumps.opts -options_file options/cont/ipf.opts -ipf_tau 1e8", "ex2_ipf_mumps", RUNS)
    par = {np: sgrun.run("-options_file options/ex2.opts", "ex2_ipf_np%d" % np, RUNS, np=np)[0] for np in (2, 4)}
    outer = [r for r in h if r["kind"] == "outer"]
    at10 = next((r for r in outer if r["gamma"] >= 1e10), outer[-1])
    out += ["| | ours | paper |", "|---|---|---|",
            "| tetrahedra | %d | 31,453 |" % s["cells"],
            "| unknowns | %d | |" % s["dofs"],
            "| outer (IPF) iterations | **%d** | 7 |" % s["outer_iterations"],
            "| SSN iterations overall | **%d** | |" % s["ssn_iterations"],
            "| final gamma | **%.2e** | 1.02e10 |" % s["gammas"][-1],
            "| final residual | **%.2e** (KKT residual of (P)) | 3.85e-12 |" % s["kkt_residual"],
            "| at the first gamma >= 1e10 (step %d, gamma %.2e): KKT residual, infeasibility | %.2e, %.2e | |" % (at10["outer"], at10["gamma"], at10["kkt"], at10["infeasibility"]),
            "| same run with MUMPS: outer, SSN iterations | %d, %d | |" % (m["outer_iterations"], m["ssn_iterations"]),
            "| np 2 and np 4 (BoomerAMG): outer, SSN iterations | %d, %d and %d, %d | |" % (par[2]["outer_iterations"], par[2]["ssn_iterations"], par[4]["outer_iterations"], par[4]["ssn_iterations"]),
            "| energy np 1 / 2 / 4 | %.12e / %.12e / %.12e | |" % (s["energy"], par[2]["energy"], par[4]["energy"]),
            "| contact force, top reaction (z) | %.6e, %.6e | |" % (s["contact_force_vector"][-1], s["reaction_force"][-1]), "",
            "Per outer step (KSP iterations of each SSN step with CG + BoomerAMG, relative tolerance %s of the SSN residual, "
            "from options/solver/hypre.opts):" % opts_value("options/solver/hypre.opts", "-ksp_rtol"), "",
            "| step | gamma | SSN iterations | KSP iterations per SSN step | KKT residual | infeasibility |", "|---|---|---|---|---|---|"]
    for r in outer:
        ks = [int(x["ksp_its"]) for x in h if x["kind"] == "ssn" and x["outer"] == r["outer"]]
        out.append("| %d | %.2e | %d | %s | %.2e | %.2e |" % (r["outer"], r["gamma"], r["ssn_its"], ", ".join(map(str, ks)), r["kkt"], r["infeasibility"]))
    out += ["", "Why a larger final gamma than the paper: we stop on the KKT residual of (P) at 1e-10, whose infeasibility part "
            "||max(0, tau_N y - d)|| / (Y sqrt|Gamma_c|) is ||lam|| / (gamma Y sqrt|Gamma_c|) on the path (Y = 0.2, the top's "
            "displacement); the contact pressures here are ~%.0e, so it needs gamma "
            "~ 1e16, while the paper stops at gamma = 1.02e10, where our iterate's infeasibility is %.1e (and its KKT residual "
            "%.1e, from the active-set mismatch that one inexact SSN step leaves). The paper's residual 3.85e-12 cannot be an "
            "infeasibility of this problem at gamma = 1e10; it is presumably the residual of the last regularized problem. "
            "BoomerAMG holds up at gamma up to 1e16: the KSP counts per SSN step stay flat." % (
                max(1.0, s["contact_force"] / max(s["contact_area"], 1e-30)), at10["infeasibility"], at10["kkt"]), ""]
    return out


SECTIONS = {"table1": table1, "alm": alm, "table2": table2, "ipf": ipf, "ex2": ex2}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--only", default=",".join(SECTIONS))
    ap.add_argument("--out", default=os.path.join(sgrun.ROOT, "results", "reproduction.md"))
    opt = ap.parse_args()
    lines = ["# Reproduction of Stadler (2007) with bin/signorini", "",
             "Generated by `scripts/reproduce.py` (`make reproduce`) on %s. Ours in bold, the paper's in parentheses. "
             "Runs, logs and histories: results/runs/." % sgrun.machine(), ""]
    for name in opt.only.split(","):
        if name not in SECTIONS:
            sys.exit("reproduce.py: unknown section %s (have %s)" % (name, ", ".join(SECTIONS)))
        print("reproduce.py: %s" % name, flush=True)
        lines += SECTIONS[name]()
    sgrun.write_atomic(opt.out, "\n".join(lines) + "\n")
    print("wrote %s" % opt.out)


if __name__ == "__main__":
    main()
