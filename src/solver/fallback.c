/* fallback.c: what an SSN solve of (P_gamma) does when its Newton iteration fails: with friction and an iterative
   linear solver, the same (P_gamma) solved again with sparse LU (MUMPS); with Coulomb friction, a fixed point on the
   Tresca bound s = F lam_N, accelerated by Anderson mixing (-ssn_coulomb_fp_*). */
#include "solver/ssnimpl.h"

/* one more SNES solve from y with a fresh Jacobian and state (the repetition with sparse LU, the Coulomb fixed point's):
   its iterations added to *its and *kits, its own SSN iterations in *it */
static PetscErrorCode SolveAgain(SgSSN s, Vec y, SNESConvergedReason *reason, PetscInt *its, PetscInt *kits, PetscInt *it)
{
  PetscInt kit;

  PetscFunctionBeginUser;
  s->havejac  = PETSC_FALSE;
  s->nhash    = 0;
  s->stagnant = PETSC_FALSE;
  s->reason   = SG_SSN_ITERATING;
  PetscCall(SNESSolve(s->snes, NULL, y));
  PetscCall(SNESGetIterationNumber(s->snes, it));
  PetscCall(SNESGetLinearSolveIterations(s->snes, &kit));
  PetscCall(SNESGetConvergedReason(s->snes, reason));
  s->reason = SgSSNReasonOf(s, *reason);
  *its += *it;
  *kits += kit;
  PetscFunctionReturn(0);
}

/* the truncated multigrid with PCSOR's local sweeps on several ranks (tmg.c) after a failed linear solve: its
   smoothers become the l1 Gauss-Seidel sweeps (SgLinearSolverFallback, for the rest of the run) and this (P_gamma) is
   solved again from the same start, its iterations added; said on the output; *done: it was redone */
PetscErrorCode SgSSNSolveL1GS(SgSSN s, PetscReal gamma, Vec y, PetscInt *its, PetscInt *kits, SNESConvergedReason *reason, PetscBool *done)
{
  KSP      ksp;
  PetscInt its2;

  KSPConvergedReason kr;

  PetscFunctionBeginUser;
  PetscCall(SNESGetKSP(s->snes, &ksp));
  PetscCall(KSPGetConvergedReason(ksp, &kr)); /* the failed solve's */
  PetscCall(SgLinearSolverFallback(ksp, done));
  if (!*done) PetscFunctionReturn(0);
  PetscCall(PetscPrintf(s->comm, "  SSN at gamma %g: %s (KSP %s) with PCSOR's local smoothers after %" PetscInt_FMT " iterations; solved again with the l1 Gauss-Seidel smoothers, and so from here on\n", (double)gamma, SgSSNReasons[s->reason], KSPConvergedReasons[kr], *its));
  PetscCall(VecCopy(s->y0, y));
  PetscCall(SolveAgain(s, y, reason, its, kits, &its2));
  PetscFunctionReturn(0);
}

/* friction with an iterative linear solver: at a large gamma the slip blocks (Coulomb: the coupling F gamma t n^T,
   far from symmetric) defeat Krylov solvers with an AMG built for elasticity, which fail or whose inexact steps
   keep the SSN from converging (GMRES + BoomerAMG on the sliding block at gamma ~ 1e12): this (P_gamma) is solved
   again from the same start with sparse LU (MUMPS), and so are those at larger gammas; said on the output */
PetscErrorCode SgSSNSolveDirect(SgSSN s, PetscReal gamma, Vec y, PetscInt *its, PetscInt *kits, SNESConvergedReason *reason)
{
  KSP      ksp;
  PetscInt its2;

  PetscFunctionBeginUser;
  if (!s->kspd) {
    PC pc;
    PetscCall(KSPCreate(s->comm, &s->kspd));
    PetscCall(KSPSetType(s->kspd, KSPPREONLY));
    PetscCall(KSPGetPC(s->kspd, &pc));
    PetscCall(PCSetType(pc, PCLU));
    PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
    if (s->frame) PetscCall(SgFrameAttachKSP(s->frame, s->kspd));
  }
  if (!(s->gamma_direct > 0 && gamma >= s->gamma_direct)) {
    PetscCall(PetscPrintf(s->comm, "  SSN at gamma %g: %s with the iterative linear solver after %" PetscInt_FMT " iterations; solved again with sparse LU (MUMPS), and so from here on at gamma >= %g\n", (double)gamma, SgSSNReasons[s->reason], *its, (double)gamma));
    s->gamma_direct = gamma;
  }
  PetscCall(SNESGetKSP(s->snes, &ksp));
  PetscCall(PetscObjectReference((PetscObject)ksp));
  PetscCall(SNESSetKSP(s->snes, s->kspd));
  PetscCall(VecCopy(s->y0, y));
  PetscCall(SolveAgain(s, y, reason, its, kits, &its2));
  PetscCall(SNESSetKSP(s->snes, ksp));
  PetscCall(KSPDestroy(&ksp));
  PetscFunctionReturn(0);
}

/* Coulomb when the Newton iteration on the coupled law failed: a fixed point on the Tresca bound. With the bound
   s_i = F lam_N,i frozen the friction law is Tresca's (a convex problem: no coupling F gamma t n^T in the Jacobian, and
   the SSN converges from anywhere); its solution y(s) gives new normal multipliers, G(s) = F max(0, lamhat + gamma
   g(y(s))), and a fixed point s = G(s) solves the Coulomb (P_gamma). G is continuous but, for a large F, not a
   contraction (more friction presses harder: an eigenvalue of G' above 1, which no relaxation damps), so the fixed
   point is found by Anderson acceleration (a secant method on G(s) - s over the last fp_m steps). */
PetscErrorCode SgSSNCoulombFixedPoint(SgSSN s, Vec y, PetscInt *its, PetscInt *kits, SNESConvergedReason *reason)
{
  const SgContactView *c = &s->cv;
  const PetscInt       n = s->n, m = s->fp_m;
  PetscReal            beta = s->fp_omega, *x, *f, *dX, *dF, *Mat_, *rhs, *gam;
  PetscInt             k, nh = 0;
  const PetscScalar   *ya;

  PetscFunctionBeginUser;
  if (!s->gfixw) PetscCall(PetscMalloc1(n, &s->gfixw));
  PetscCall(PetscMalloc7(n, &x, n, &f, n * m, &dX, n * m, &dF, m * m, &Mat_, m, &rhs, m, &gam));
  PetscCall(VecCopy(s->y0, y));
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(SgContactGap(s->c, ya, s->g));
  PetscCall(VecRestoreArrayRead(y, &ya));
  for (PetscInt i = 0; i < n; i++) SgContactLawBound(c->law, i, s->lamhat[i] + s->gamma * s->g[i], &s->gfixw[i], NULL);
  for (k = 0; k < s->fp_max_it; k++) {
    PetscInt  it2, jc;
    PetscReal d = 0, mx = 0;
    s->gfix = s->gfixw;
    PetscCall(SolveAgain(s, y, reason, its, kits, &it2));
    s->gfix = NULL;
    if (*reason <= 0) break;
    PetscCall(VecGetArrayRead(y, &ya));
    PetscCall(SgContactGap(s->c, ya, s->g));
    PetscCall(VecRestoreArrayRead(y, &ya));
    /* the residual f = G(s) - s; the history columns are differences to the previous step */
    jc = k > 0 ? (k - 1) % m : 0;
    for (PetscInt i = 0; i < n; i++) {
      PetscReal gi;
      SgContactLawBound(c->law, i, s->lamhat[i] + s->gamma * s->g[i], &gi, NULL);
      const PetscReal fi = gi - s->gfixw[i];
      d                  = PetscMax(d, PetscAbsReal(fi));
      mx                 = PetscMax(mx, gi);
      if (k > 0) {
        dX[jc * n + i] = s->gfixw[i] - x[i];
        dF[jc * n + i] = fi - f[i];
      }
      x[i] = s->gfixw[i];
      f[i] = fi;
    }
    if (k > 0) nh = PetscMin(nh + 1, m);
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &d, 1, MPIU_REAL, MPI_MAX, s->comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &mx, 1, MPIU_REAL, MPI_MAX, s->comm));
    if (s->monitor) PetscCall(PetscPrintf(s->comm, "  Coulomb fixed point %" PetscInt_FMT " at gamma %g: %" PetscInt_FMT " SSN, |G(s) - s| %.3e of %.3e\n", k, (double)s->gamma, it2, (double)d, (double)mx));
    if (d <= s->fp_rtol * mx) break;
    /* gam = argmin |f - dF gam| (normal equations, a small ridge), s <- s + beta f - (dX + beta dF) gam, s >= 0 */
    for (PetscInt a = 0; a < nh; a++) {
      rhs[a] = 0;
      for (PetscInt i = 0; i < n; i++) rhs[a] += dF[a * n + i] * f[i];
      for (PetscInt b = 0; b < nh; b++) {
        Mat_[a * m + b] = 0;
        for (PetscInt i = 0; i < n; i++) Mat_[a * m + b] += dF[a * n + i] * dF[b * n + i];
      }
    }
    if (nh) {
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, rhs, (PetscMPIInt)nh, MPIU_REAL, MPI_SUM, s->comm));
      for (PetscInt a = 0; a < nh; a++) PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &Mat_[a * m], (PetscMPIInt)nh, MPIU_REAL, MPI_SUM, s->comm));
      {
        PetscReal tr = 0;
        for (PetscInt a = 0; a < nh; a++) tr += Mat_[a * m + a];
        for (PetscInt a = 0; a < nh; a++) Mat_[a * m + a] += 1e-12 * tr + PETSC_SMALL * PETSC_SMALL;
      }
      /* Gaussian elimination, symmetric positive definite: no pivoting */
      for (PetscInt a = 0; a < nh; a++) {
        for (PetscInt b = a + 1; b < nh; b++) {
          const PetscReal l = Mat_[b * m + a] / Mat_[a * m + a];
          for (PetscInt q = a; q < nh; q++) Mat_[b * m + q] -= l * Mat_[a * m + q];
          rhs[b] -= l * rhs[a];
        }
      }
      for (PetscInt a = nh - 1; a >= 0; a--) {
        PetscReal r = rhs[a];
        for (PetscInt q = a + 1; q < nh; q++) r -= Mat_[a * m + q] * gam[q];
        gam[a] = r / Mat_[a * m + a];
      }
    }
    for (PetscInt i = 0; i < n; i++) {
      PetscReal v = x[i] + beta * f[i];
      for (PetscInt a = 0; a < nh; a++) v -= (dX[a * n + i] + beta * dF[a * n + i]) * gam[a];
      s->gfixw[i] = PetscMax(0, v);
    }
  }
  PetscCall(PetscFree7(x, f, dX, dF, Mat_, rhs, gam));
  if (*reason > 0) { /* the coupled law from the fixed point */
    PetscInt it2;
    PetscCall(SolveAgain(s, y, reason, its, kits, &it2));
    if (s->monitor) PetscCall(PetscPrintf(s->comm, "  Coulomb after %" PetscInt_FMT " fixed-point steps at gamma %g: %s after %" PetscInt_FMT " SSN\n", k, (double)s->gamma, SgSSNReasons[s->reason], it2));
  }
  PetscCall(PetscPrintf(s->comm, "  SSN at gamma %g with Coulomb friction: the Newton iteration on the coupled law failed; solved again by a fixed point on the Tresca bound s = F lam_N (%" PetscInt_FMT " steps): %s\n", (double)s->gamma, k, *reason > 0 ? "converged" : SgSSNReasons[s->reason]));
  PetscFunctionReturn(0);
}
