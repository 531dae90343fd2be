/* cont/cont_loop.c: the outer loop every continuation controller shares (SgContSolveContinuation) and its verdicts:
   the stopping tests after each step (SgContCheck) and the baselines' (SgContCheckBaseline), the best iterate kept
   and restored, the Coulomb fallback on the shifted path, the word for the end of a run (SgContVerdict). */
#include "cont/contimpl.h"

/* After an outer step (ct->gamma and ct->state already hold the next step's): converged (KKT residual below the
   tolerance), or failed because the outer-step limit is reached, the next gamma overflows, or the KKT residual has not
   improved for -cont_stall_it steps. Then the checkpoint, if asked for. */
PetscErrorCode SgContCheck(SgCont ct, PetscBool *stop)
{
  const PetscReal gamma_next = ct->gamma, gamma_now = ct->ngammas ? ct->gammas[ct->ngammas - 1] : SG_NAN;
  PetscReal       gdp   = PETSC_MAX_REAL;
  PetscBool       atcap = PETSC_FALSE;

  PetscFunctionBeginUser;
  *stop = PETSC_TRUE;
  if (ct->c && ct->ssn && ct->kkt.residual > ct->kkt_tol) {
    /* no step past the gamma where double precision ends (SgContGammaPrecision): the next step there, or the honest
       failure below if this step was there already */
    PetscCall(SgContGammaPrecision(ct, &gdp));
    /* this step was at the cap and the type would take a larger gamma: a path-following type (lamhat = 0) can only
       repeat this step's solution */
    atcap = (PetscBool)(SgContAtGammaPrecision(gamma_now, gdp) && gamma_next > gamma_now && !ct->ops.shifts);
    if (gamma_next > gdp && !atcap) {
      SNES snes;
      PetscCall(SgSSNGetSNES(ct->ssn, &snes));
      PetscCall(PetscInfo(snes, "outer step %" PetscInt_FMT ": the next gamma %g capped at %g, the largest double precision resolves here\n", ct->outer, (double)gamma_next, (double)PetscMax(gdp, gamma_now)));
      ct->gamma = PetscMax(gdp, gamma_now);
    }
  }
  if (ct->kkt.residual <= ct->kkt_tol) {
    ct->converged = PETSC_TRUE;
    PetscCall(PetscSNPrintf(ct->reason, sizeof(ct->reason), "KKT_RESIDUAL_BELOW_TOL: %.3e <= %.3e after %" PetscInt_FMT " outer steps", (double)ct->kkt.residual, (double)ct->kkt_tol, ct->outer));
    PetscCall(SgContCheckpointWrite(ct));
    PetscFunctionReturn(0);
  }
  if (ct->kkt.residual < 0.99 * ct->best_kkt || ct->outer == 1) {
    ct->best_kkt  = ct->kkt.residual;
    ct->best_step = ct->outer;
  }
  if (PetscIsInfOrNanReal(ct->kkt.residual)) PetscCall(SgContFail(ct, "DIVERGED_NAN: the KKT residual is not a number after outer step %" PetscInt_FMT " (check the magnitudes of -neumann_traction, -body_force, -dirichlet_values and -E)", ct->outer));
  else if (ct->outer - ct->best_step >= ct->stall_its) PetscCall(SgContFail(ct, "STALLED: no progress in the KKT residual (%.3e, best %.3e at step %" PetscInt_FMT ") for %" PetscInt_FMT " outer steps (-cont_stall_it); a larger first gamma may help", (double)ct->kkt.residual, (double)ct->best_kkt, ct->best_step, ct->outer - ct->best_step));
  else if (atcap) PetscCall(SgContFail(ct, "PRECISION_LIMIT: -cont_kkt_tol %.3e is not met up to gamma %g, the largest at which double precision resolves the regularized multipliers of this problem (their round-off gamma eps |y| is 1e-2 of the largest multiplier or friction bound there; beyond it the SSN decides states on round-off); the KKT residual reached is %.3e (infeasibility %.3e, complementarity %.3e, equilibrium %.3e); -cont_type alm, which moves the shift instead of gamma, can get below it", (double)ct->kkt_tol, (double)gamma_now, (double)ct->kkt.residual, (double)ct->kkt.infeasibility, (double)ct->kkt.complementarity, (double)ct->kkt.equilibrium));
  else if (!(ct->gamma <= ct->gamma_max)) PetscCall(SgContFail(ct, "GAMMA_OVERFLOW: the next gamma %g exceeds -cont_gamma_max %g (KKT residual %.3e)", (double)ct->gamma, (double)ct->gamma_max, (double)ct->kkt.residual));
  else if (ct->outer >= ct->max_outer) PetscCall(SgContFail(ct, "MAX_IT: %" PetscInt_FMT " outer steps (-cont_max_it) with KKT residual %.3e > %.3e", ct->outer, (double)ct->kkt.residual, (double)ct->kkt_tol));
  else *stop = PETSC_FALSE;
  PetscCall(SgContCheckpointWrite(ct));
  if (!strncmp(ct->reason, "CHECKPOINT_FAILED", 17)) *stop = PETSC_TRUE; /* the disk is full, say: stop, keep the summary */
  PetscFunctionReturn(0);
}

/* A baseline that solves (P) itself (pdas, vi) has converged only if its result meets the KKT tolerance too:
   a settled active set after inexact linear solves can still be far from it. */
PetscErrorCode SgContCheckBaseline(SgCont ct)
{
  PetscFunctionBeginUser;
  if (ct->converged && !(ct->kkt.residual <= ct->kkt_tol)) {
    char was[sizeof(ct->reason)];
    PetscCall(PetscStrncpy(was, ct->reason, sizeof(was)));
    PetscCall(SgContFail(ct, "KKT_RESIDUAL_ABOVE_TOL: %.3e > %.3e (-cont_kkt_tol) after %s; tighten the linear solves", (double)ct->kkt.residual, (double)ct->kkt_tol, was));
  }
  PetscFunctionReturn(0);
}

/* The iterate of least KKT residual of this solve (a step at a larger gamma can be worse: round-off) */
PetscErrorCode SgContKeepBest(SgCont ct)
{
  PetscFunctionBeginUser;
  if (!PetscIsNormalReal(ct->kkt.residual) && ct->kkt.residual != 0) PetscFunctionReturn(0);
  if (ct->outerbest > 0 && !(ct->kkt.residual < ct->kktbest)) PetscFunctionReturn(0);
  if (!ct->ybest) PetscCall(VecDuplicate(ct->y, &ct->ybest));
  if (!ct->lambest) PetscCall(PetscMalloc1(ct->n + 1, &ct->lambest));
  PetscCall(VecCopy(ct->y, ct->ybest));
  PetscCall(PetscArraycpy(ct->lambest, ct->lam, ct->n));
  ct->kktbest   = ct->kkt.residual;
  ct->outerbest = ct->outer;
  PetscFunctionReturn(0);
}

/* An SSN solve that failed (cycling, iteration limit, ...) on an iterate that meets the KKT tolerance of (P): the run
   has solved (P), whatever the regularized problem's Newton steps did */
static PetscErrorCode AcceptFailedSSN(SgCont ct)
{
  PetscFunctionBeginUser;
  if (!(ct->kkt.residual <= ct->kkt_tol)) PetscFunctionReturn(0);
  {
    SgSSNReason sr;
    PetscCall(SgSSNGetReason(ct->ssn, &sr));
    ct->converged = PETSC_TRUE;
    PetscCall(PetscSNPrintf(ct->reason, sizeof(ct->reason), "KKT_RESIDUAL_BELOW_TOL: %.3e <= %.3e after %" PetscInt_FMT " outer steps (the last regularized solve, at gamma %g, stopped with SSN_%s on an iterate that meets the tolerance)", (double)ct->kkt.residual, (double)ct->kkt_tol, ct->outer, (double)ct->gammas[ct->ngammas - 1], SgSSNReasons[sr]));
  }
  PetscFunctionReturn(0);
}

/* A failed run ends on the best iterate rather than the last, when that is better; if it meets the tolerance, the run
   converged (at that outer step). */
PetscErrorCode SgContRestoreBest(SgCont ct)
{
  PetscFunctionBeginUser;
  if (ct->converged || ct->outerbest <= 0 || !ct->ybest || !(ct->kktbest < ct->kkt.residual || PetscIsNanReal(ct->kkt.residual))) {
    ct->outerbest = 0;
    PetscFunctionReturn(0);
  }
  PetscCall(VecCopy(ct->ybest, ct->y));
  PetscCall(PetscArraycpy(ct->lam, ct->lambest, ct->n));
  PetscCall(SgContMeasure(ct));
  {
    char was[sizeof(ct->reason)];
    PetscCall(PetscStrncpy(was, ct->reason, sizeof(was)));
    if (ct->kkt.residual <= ct->kkt_tol) {
      ct->converged = PETSC_TRUE;
      PetscCall(PetscSNPrintf(ct->reason, sizeof(ct->reason), "KKT_RESIDUAL_BELOW_TOL: %.3e <= %.3e at outer step %" PetscInt_FMT " of %" PetscInt_FMT " (the result is that step's iterate; the run went on and stopped with: %.200s)", (double)ct->kkt.residual, (double)ct->kkt_tol, ct->outerbest, ct->outer, was));
    } else {
      PetscCall(PetscSNPrintf(ct->reason, sizeof(ct->reason), "%.400s; the result is the best iterate, of outer step %" PetscInt_FMT " (KKT residual %.3e)", was, ct->outerbest, (double)ct->kkt.residual));
    }
  }
  ct->outerbest = 0;
  PetscFunctionReturn(0);
}

/* Coulomb friction when a regularized solve of the path (pf, ipf: lamhat = 0, gamma grown towards 1e13) failed. Beyond a
   friction coefficient that depends on the mesh (about 5.7 on the sliding block with nu = 0 and 40 x 20 cells) the
   discrete Coulomb problem has no solution with a connected contact zone: its solutions contact at every other vertex
   of the slip zone (the others lift off by 1e-5), a mode of the mesh that the SSN at a large gamma cannot reach: its
   Newton steps peel the edge of the contact zone vertex by vertex and cycle. The shifted path reaches it: from the
   solve's start, lamhat = 0 and the first gamma of the path, each (P_gamma) solved exactly, the shift set to its
   multipliers (normal and tangential) and gamma doubled (the steps of -cont_type alm -alm_gamma_factor 2), until the
   KKT tolerance of (P). Said on the output and in the reason; the shift is 0 again afterwards (the path's). */
static PetscErrorCode CoulombShiftedPath(SgCont ct)
{
  PetscReal         gamma;
  PetscBool         stop = PETSC_FALSE, ok = PETSC_TRUE;
  PetscInt          outer0 = ct->outer;
  char              was[sizeof(ct->reason)];
  SgContactLawState st;

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(was, ct->reason, sizeof(was)));
  PetscCall(SgSSNGetLawState(ct->ssn, &st));
  gamma = ct->gammas[0];
  PetscCall(PetscPrintf(ct->comm, "  %s with Coulomb friction: %.200s; solved again from the start on the shifted path (lamhat = the last multipliers, gamma doubled per step from %g)\n", ct->type, was, (double)gamma));
  PetscCall(SgSSNSetNeighbourhood(ct->ssn, 0)); /* exact solves */
  PetscCall(VecCopy(ct->ystart, ct->y));
  PetscCall(PetscArrayzero(ct->lamhat, ct->n));
  PetscCall(SgContactLawStateZeroShift(st)); /* lamhat_T = 0: the law's */
  ct->converged = PETSC_FALSE;
  ct->best_kkt  = PETSC_MAX_REAL;
  ct->best_step = ct->outer;
  while (ok && !stop) {
    const PetscInt its0 = ct->ssn_its;
    ct->outer++;
    PetscCall(SgContSSN(ct, gamma, &ok));
    PetscCall(SgContMeasure(ct));
    PetscCall(SgContOuterRow(ct, ct->ssn_its - its0, NULL));
    PetscCall(SgContKeepBest(ct));
    if (!ok) {
      PetscCall(AcceptFailedSSN(ct));
      break;
    }
    PetscCall(PetscArraycpy(ct->lamhat, ct->lam, ct->n));
    PetscCall(SgContactLawStateAcceptShift(st)); /* lamhat_T = lam_T: the law's */
    gamma *= 2;
    ct->gamma = gamma;
    PetscCall(SgContCheck(ct, &stop));
  }
  PetscCall(PetscArrayzero(ct->lamhat, ct->n));
  PetscCall(SgContactLawStateZeroShift(st));
  if (ct->converged) {
    char now[sizeof(ct->reason)];
    PetscCall(PetscStrncpy(now, ct->reason, sizeof(now)));
    PetscCall(PetscSNPrintf(ct->reason, sizeof(ct->reason), "%.200s on the shifted path (outer steps %" PetscInt_FMT "-%" PetscInt_FMT ", after %.250s)", now, outer0 + 1, ct->outer, was));
  } else {
    /* neither path: say that the shifted one failed too, and what is known of such problems, not only the last
       SSN's advice (more iterations, smaller steps), which the fallbacks have tried */
    char        now[sizeof(ct->reason)], *advice;
    const char *desc;
    PetscCall(SgContactLawGetDescription(ct->cv.law, &desc));
    PetscCall(PetscStrncpy(now, ct->reason, sizeof(now)));
    PetscCall(PetscStrstr(now, ": raise -snes_max_it", &advice));
    if (advice) *advice = 0; /* tried */
    PetscCall(PetscSNPrintf(ct->reason, sizeof(ct->reason), "%.150s on the shifted path, after %.60s...; %s: above a mesh-dependent F the discrete problem can have several solutions or none (a smaller F, a coarser mesh or Tresca can be solved)", now, was, desc));
  }
  PetscFunctionReturn(0);
}

/* The outer loop of every continuation controller (see cont/contimpl.h for the order of the hooks). */
PetscErrorCode SgContSolveContinuation(SgCont ct)
{
  PetscBool       stop = PETSC_FALSE, ok, ssnfail = PETSC_FALSE;
  const PetscBool shifted = (PetscBool)(ct->c && ct->cv.props.coupled && ct->coulomb_shifted && !ct->ops.shifts && !ct->restarted && (!strcmp(ct->type, SGCONTPF) || !strcmp(ct->type, SGCONTIPF)));

  PetscFunctionBeginUser;
  if (!ct->restarted && (!ct->warm || ct->nested_start)) PetscCall(ct->ops.start(ct));
  PetscCall(SgContStart(ct, &ok)); /* V(0) */
  if (shifted && ok) {
    if (!ct->ystart) PetscCall(VecDuplicate(ct->y, &ct->ystart));
    PetscCall(VecCopy(ct->y, ct->ystart));
  }
  if (!ct->restarted && (!ct->warm || ct->nested_start) && ct->ops.started) PetscCall(ct->ops.started(ct));
  if (ct->nested_start) PetscCall(SgContNestedResume(ct)); /* the coarse level's gamma and shift */
  while (ok && !stop) {
    const PetscInt its0 = ct->ssn_its;
    SgHistoryRow   mdl;
    PetscReal      next = SG_NAN;

    if (ct->ops.prestep) PetscCall(ct->ops.prestep(ct));
    ct->outer++;
    PetscCall(PetscLogEventBegin(SG_ContStep, 0, 0, 0, 0));
    PetscCall(SgContSSN(ct, ct->gamma, &ok));
    PetscCall(PetscLogEventEnd(SG_ContStep, 0, 0, 0, 0));
    PetscCall(SgContMeasure(ct));
    PetscCall(SgHistoryRowInit(&mdl));
    if (ct->ops.model) PetscCall(ct->ops.model(ct, &mdl));
    PetscCall(SgContOuterRow(ct, ct->ssn_its - its0, &mdl));
    PetscCall(SgContKeepBest(ct));
    if (!ok) {
      PetscCall(AcceptFailedSSN(ct));
      ssnfail = (PetscBool)!ct->converged;
      break;
    }
    PetscCall(ct->ops.update(ct, &next));
    ct->gamma = next;
    PetscCall(SgContCheck(ct, &stop));
  }
  if (shifted && ssnfail && ct->ngammas) {
    SgSSNReason sr;
    PetscCall(SgSSNGetReason(ct->ssn, &sr));
    if (sr == SG_SSN_MAX_IT || sr == SG_SSN_CYCLING || sr == SG_SSN_SNES_FAILED) PetscCall(CoulombShiftedPath(ct));
  } else if (shifted && !ct->converged && ct->ngammas && !strncmp(ct->reason, "PRECISION_LIMIT", 15)) {
    /* the tolerance lies below what gamma can reach in double precision (a small load step's slip): the shift moves */
    PetscCall(CoulombShiftedPath(ct));
  }
  PetscCall(SgContRestoreBest(ct));
  if (ct->ops.finish) PetscCall(ct->ops.finish(ct));
  PetscFunctionReturn(0);
}

/* The word for the end of a run: a solve of (P) converged, one (P_gamma) solved, or failed. */
const char *SgContVerdict(SgCont ct)
{
  if (!ct->converged) return "FAILED";
  return strcmp(ct->problem, "P_gamma") ? "CONVERGED" : "SOLVED (P_gamma)";
}
