/* convergence.c: when an SSN solve of (P_gamma) stops and what it says: the convergence test (settled active set,
   round-off, neighbourhood of the path, cycling), our reasons and -snes_converged_reason, and the line per Newton
   step (-ssn_monitor, progress, history rows). */
#include "solver/ssnimpl.h"

const char *const SgSSNReasons[] = {"ITERATING", "ACTIVE_SET_SETTLED", "NEIGHBOURHOOD_REACHED", "INITIAL_RESIDUAL_ZERO", "ACTIVE_SET_CYCLING", "FNORM_NAN", "MAX_IT", "LINEAR_SOLVE_FAILED", "SNES_FAILED", "KKT_BELOW_TOL", "RESIDUAL_AT_ROUNDOFF"};

/* Whether the states that still change at the last residual evaluation do so on round-off alone (SgSSNDecisionRoundoff:
   s->nhard counts the others) while F(y), with the states of y itself, is zero to the round-off of its gamma-scaled
   terms (s->ffloor): y solves (P_gamma) as far as double precision can tell, and more Newton steps only repeat the
   same states (SG_SSN_ROUNDOFF; a controller's own stop test asks it too, cont/fast.c) */
PetscErrorCode SgSSNStatesAtRoundoff(SgSSN s, PetscReal fnorm, PetscBool settled, PetscBool *flg)
{
  PetscFunctionBeginUser;
  *flg = (PetscBool)(!settled && s->nhard == 0 && fnorm <= s->ffloor);
  PetscFunctionReturn(0);
}

/* Whether the active set at the last residual evaluation was the Jacobian's set of an earlier Newton step of this
   solve (the cycle test below): with exact solves the steps from here repeat */
PetscErrorCode SgSSNSetRevisited(SgSSN s, PetscBool *flg)
{
  PetscInt64 h;

  PetscFunctionBeginUser;
  *flg = PETSC_FALSE;
  PetscCall(SgContactActiveSetHash(s->c, s->act, &h));
  for (PetscInt j = 0; j < s->nhash - 1 && !*flg; j++) *flg = (PetscBool)(s->hash[j] == h);
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNConverged(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm, PetscReal fnorm, SNESConvergedReason *reason, void *ctx)
{
  SgSSN     s = (SgSSN)ctx;
  PetscReal atol, rtol;
  PetscBool settled, small, roundoff;

  PetscFunctionBeginUser;
  *reason   = SNES_CONVERGED_ITERATING;
  s->reason = SG_SSN_ITERATING;
  PetscCall(SNESGetTolerances(snes, &atol, &rtol, NULL, NULL, NULL));
  if (PetscIsInfOrNanReal(fnorm)) {
    *reason   = SNES_DIVERGED_FNORM_NAN;
    s->reason = SG_SSN_NAN;
    PetscFunctionReturn(0);
  }
  if (it == 0) {
    s->fnorm0       = fnorm;
    s->prev_settled = PETSC_FALSE;
    s->stagnant     = PETSC_FALSE;
    if (fnorm <= atol) {
      *reason   = SNES_CONVERGED_FNORM_ABS;
      s->reason = SG_SSN_ZERO_RESIDUAL;
    }
    PetscFunctionReturn(0);
  }
  settled = (PetscBool)(s->nentered + s->nleft == 0 && (!s->cv.props.tangential || s->nfchanged == 0));
  if (s->stop_test) { /* a controller's own test replaces the one below */
    PetscCall(s->stop_test(s, it, fnorm, settled, reason, s->stop_ctx));
    PetscFunctionReturn(0);
  }
  /* with inexact linear solves the residual must be small too: below rtol ||F_0||, or, when a Newton step on an
     unchanged active set no longer halves it, at the round-off floor of the (gamma-scaled) residual, which must
     lie below sqrt(rtol) max(||F_0||, ||b||) or at the floor of forming the gamma-scaled terms (s->ffloor: at large
     gamma that floor is above sqrt(rtol) ||b||, and the steps repeat the same iterate until -snes_max_it) */
  if (s->cv.props.nonlinear) {
    /* friction: ||F_0|| grows with gamma (the penetration of the start) and says nothing about the slip set, where
       the Newton steps converge instead of landing: measured against the load ||b|| alone */
    small = (PetscBool)(fnorm <= PetscMax(atol, rtol * s->bnorm) || (settled && s->prev_settled && fnorm > 0.5 * s->prev_fnorm && fnorm <= PetscMax(PetscSqrtReal(rtol) * s->bnorm, s->ffloor)));
  } else small = (PetscBool)(!s->residual_test || fnorm <= PetscMax(atol, rtol * s->fnorm0) || (settled && s->prev_settled && fnorm > 0.5 * s->prev_fnorm && fnorm <= PetscMax(PetscSqrtReal(rtol) * PetscMax(s->fnorm0, s->bnorm), s->ffloor)));
  /* friction: the next Jacobian reclassifies the sticks from their equilibrium force (SgSSNFrictionJacobian) */
  s->stagnant     = (PetscBool)(s->cv.props.nonlinear && it > 1 && fnorm > 0.5 * s->prev_fnorm);
  s->prev_settled = settled;
  s->prev_fnorm   = fnorm;
  PetscCall(SgSSNStatesAtRoundoff(s, fnorm, settled, &roundoff));
  if (settled && small) {
    *reason   = SNES_CONVERGED_FNORM_ABS;
    s->reason = SG_SSN_SETTLED;
  } else if (roundoff) {
    /* the states that still change do so on round-off (a gap of a few ulps, a vertex at the slip bound after a tiny
       load increment: s->nhard counts the others) and F(y) (with the states of y itself) is zero to the round-off of
       its gamma-scaled terms: y solves (P_gamma) as far as double precision can tell; more steps only repeat them */
    *reason   = SNES_CONVERGED_FNORM_ABS;
    s->reason = SG_SSN_ROUNDOFF;
  } else if (s->nbhd_tau > 0 && PetscSqrtReal(s->r1 * s->r1 + s->r2 * s->r2) <= s->nbhd_tau / PetscSqrtReal(s->gamma)) {
    /* r1 measures the equilibrium residual, inexact linear solves included */
    *reason   = SNES_CONVERGED_FNORM_ABS;
    s->reason = SG_SSN_NEIGHBOURHOOD;
  } else if (!settled && !s->cv.props.nonlinear) { /* with slip the iterate is no function of the sets: no cycle test */
    PetscInt64 h;
    PetscCall(SgContactActiveSetHash(s->c, s->act, &h));
    for (PetscInt j = 0; j < s->nhash - 1; j++)
      if (s->hash[j] == h) {
        /* with exact solves the iterate is a function of the active set: a revisited set repeats forever */
        *reason   = SNES_DIVERGED_LOCAL_MIN;
        s->reason = SG_SSN_CYCLING;
        PetscCall(PetscInfo(snes, "active set of Newton step %" PetscInt_FMT " revisited at iteration %" PetscInt_FMT "\n", j + 1, it));
        break;
      }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNMonitor(SNES snes, PetscInt it, PetscReal fnorm, void *ctx)
{
  SgSSN          s = (SgSSN)ctx;
  KSP            ksp;
  PetscInt       kits = 0;
  PetscLogDouble t;

  PetscFunctionBeginUser;
  PetscCall(SNESGetKSP(snes, &ksp));
  if (it > 0) PetscCall(KSPGetIterationNumber(ksp, &kits));
  PetscCall(PetscTime(&t));
  if (s->monitor && s->cv.props.tangential)
    PetscCall(PetscPrintf(s->comm, "  SSN %2" PetscInt_FMT " gamma %.3e |A| %" PetscInt_FMT " (+%" PetscInt_FMT " -%" PetscInt_FMT " next) stick %" PetscInt_FMT " slip %" PetscInt_FMT " (%" PetscInt_FMT " changed) ||F|| %.3e r1 %.3e r2 %.3e V %.10e KSP %" PetscInt_FMT "\n", it, (double)s->gamma, s->nact, s->nentered, s->nleft, s->nstick, s->nslip, s->nfchanged, (double)fnorm, (double)s->r1, (double)s->r2, (double)s->V, kits));
  else if (s->monitor)
    PetscCall(PetscPrintf(s->comm, "  SSN %2" PetscInt_FMT " gamma %.3e |A| %" PetscInt_FMT " (+%" PetscInt_FMT " -%" PetscInt_FMT " next) ||F|| %.3e r1 %.3e r2 %.3e V %.10e KSP %" PetscInt_FMT "\n", it, (double)s->gamma, s->nact, s->nentered, s->nleft, (double)fnorm, (double)s->r1, (double)s->r2, (double)s->V, kits));
  else if (s->progress && it > 0)
    PetscCall(PetscPrintf(s->comm, "    SSN %2" PetscInt_FMT ": active %" PetscInt_FMT " (+%" PetscInt_FMT " -%" PetscInt_FMT " next), ||F|| %.3e, KSP %" PetscInt_FMT ", %.2f s\n", it, s->nact, s->nentered, s->nleft, (double)fnorm, kits, (double)(t - s->t0)));
  if (it > 0 && s->hist) {
    SgHistoryRow row;
    PetscCall(SgHistoryRowInit(&row));
    row.kind    = 's';
    row.outer   = s->outer;
    row.gamma   = s->gamma;
    row.it      = it;
    row.active  = s->nact;
    row.entered = s->nentered;
    row.left    = s->nleft;
    row.fnorm   = fnorm;
    row.r1      = s->r1;
    row.r2      = s->r2;
    row.V       = s->V;
    row.dV      = s->dVdg;
    row.ksp_its = kits;
    row.time    = t - s->t0;
    PetscCall(SgHistoryAdd(s->hist, &row));
  }
  PetscFunctionReturn(0);
}

/* -snes_converged_reason for the SSN: our reasons (SgSSNReasons), which PETSc's closed list of SNES reasons cannot
   name: a settled active set would print as CONVERGED_FNORM_ABS and cycling as DIVERGED_LOCAL_MIN. The option is
   taken over at set-up (read into the SSN's viewer and removed), so PETSc does not print a second, misleading line;
   a SNES type of our own would have had to copy newtonls for the same effect. */
/* Our reason for a SNES reason: a failure our convergence test did not name is PETSc's (the iteration limit, ...). */
SgSSNReason SgSSNReasonOf(SgSSN s, SNESConvergedReason r)
{
  if (r >= 0 || s->reason != SG_SSN_ITERATING) return s->reason;
  return r == SNES_DIVERGED_MAX_IT ? SG_SSN_MAX_IT : (r == SNES_DIVERGED_LINEAR_SOLVE ? SG_SSN_LINEAR_SOLVE : (r == SNES_DIVERGED_FNORM_NAN ? SG_SSN_NAN : SG_SSN_SNES_FAILED));
}

PetscErrorCode SgSSNReasonView(SNES snes, void *ctx)
{
  SgSSN               s = (SgSSN)ctx;
  SNESConvergedReason r;
  PetscInt            its, tab;
  PetscBool           isascii;

  PetscFunctionBeginUser;
  if (!s->reason_viewer) PetscFunctionReturn(0);
  PetscCall(PetscObjectGetTabLevel((PetscObject)snes, &tab));
  PetscCall(PetscObjectTypeCompare((PetscObject)s->reason_viewer, PETSCVIEWERASCII, &isascii));
  if (!isascii) PetscFunctionReturn(0);
  PetscCall(SNESGetConvergedReason(snes, &r));
  PetscCall(SNESGetIterationNumber(snes, &its));
  PetscCall(PetscViewerPushFormat(s->reason_viewer, s->reason_format));
  PetscCall(PetscViewerASCIIAddTab(s->reason_viewer, tab));
  if (r > 0) {
    if (s->reason_format != PETSC_VIEWER_FAILED) PetscCall(PetscViewerASCIIPrintf(s->reason_viewer, "SSN solve of (P_gamma) at gamma %g converged due to %s iterations %" PetscInt_FMT "\n", (double)s->gamma, SgSSNReasons[s->reason], its));
  } else PetscCall(PetscViewerASCIIPrintf(s->reason_viewer, "SSN solve of (P_gamma) at gamma %g did not converge due to %s (SNES %s) iterations %" PetscInt_FMT "\n", (double)s->gamma, SgSSNReasons[SgSSNReasonOf(s, r)], SNESConvergedReasons[r], its));
  PetscCall(PetscViewerASCIISubtractTab(s->reason_viewer, tab));
  PetscCall(PetscViewerPopFormat(s->reason_viewer));
  PetscFunctionReturn(0);
}
