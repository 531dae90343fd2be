/* cont.c: the continuation controller registry (-cont_type), what every controller shares, and the type "none". */
#include "signorini.h"
#include <stdarg.h>

PetscFunctionList SgContList = NULL;

PetscErrorCode SgContRegister(const char name[], PetscErrorCode (*create)(SgCont))
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListAdd(&SgContList, name, create));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContCreate(SgProblem p, SgContact c, SgCont *cont)
{
  SgCont ct;
  PetscErrorCode (*create)(SgCont) = NULL;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&ct));
  ct->comm      = p->comm;
  ct->prob      = p;
  ct->c         = c;
  ct->kkt_tol   = 1e-10;
  ct->max_outer = 50;
  ct->gamma_max = 1e20;
  ct->stall_its = 10;
  ct->converged = PETSC_FALSE;
  ct->problem   = c ? "P" : "elasticity";
  ct->residual  = SG_NAN;
  PetscCall(PetscStrcpy(ct->type, "none"));
  PetscCall(PetscStrcpy(ct->reason, "NOT_RUN"));
  PetscCall(SgHistoryCreate(&ct->hist));
  PetscCall(SgSummaryCreate(&ct->sum));
  PetscOptionsBegin(p->comm, NULL, "Continuation controller", NULL);
  PetscCall(PetscOptionsFList("-cont_type", "Controller: none (one (P_gamma)), alm, pf, ipf, or the baselines pdas and vi", NULL, SgContList, ct->type, ct->type, sizeof(ct->type), NULL));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-cont_kkt_tol", "Stop when the KKT residual of (P) (dimensionless: relative to the force and displacement scales) is below this; for none, the tolerance of the equilibrium residual of (P_gamma)", &ct->kkt_tol, NULL));
  PetscCall(SgOptionsIntValue(PetscOptionsObject, "-cont_max_it", "Maximum number of outer (continuation) steps", &ct->max_outer, NULL));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-cont_gamma_max", "Stop with GAMMA_OVERFLOW when gamma would exceed this", &ct->gamma_max, NULL));
  PetscCall(PetscOptionsString("-checkpoint_file", "HDF5 file with the continuation state, rewritten after every outer step", NULL, ct->ckfile, ct->ckfile, sizeof(ct->ckfile), NULL));
  PetscCall(PetscOptionsString("-restart_file", "Resume from a checkpoint (alm, pf, ipf; any number of ranks)", NULL, ct->rsfile, ct->rsfile, sizeof(ct->rsfile), NULL));
  PetscCall(SgOptionsIntValue(PetscOptionsObject, "-cont_stall_it", "Stop with STALLED after this many outer steps without progress in the KKT residual", &ct->stall_its, NULL));
  PetscCall(PetscFunctionListFind(SgContList, ct->type, &create));
  PetscCheck(create, p->comm, PETSC_ERR_USER_INPUT, "-cont_type: unknown controller '%s' (see -help for the list)", ct->type);
  PetscCall(create(ct));
  if (ct->setfromoptions) PetscCall(ct->setfromoptions(ct, PetscOptionsObject));
  PetscOptionsEnd();
  PetscCheck(PetscIsNormalReal(ct->kkt_tol) && ct->kkt_tol > 0, p->comm, PETSC_ERR_USER_INPUT, "-cont_kkt_tol: must be positive and finite, got %g", (double)ct->kkt_tol);
  PetscCheck(ct->max_outer > 0, p->comm, PETSC_ERR_USER_INPUT, "-cont_max_it: must be positive, got %" PetscInt_FMT, ct->max_outer);
  PetscCheck(PetscIsNormalReal(ct->gamma_max) && ct->gamma_max > 0, p->comm, PETSC_ERR_USER_INPUT, "-cont_gamma_max: must be positive and finite, got %g", (double)ct->gamma_max);
  PetscCheck(ct->stall_its > 0, p->comm, PETSC_ERR_USER_INPUT, "-cont_stall_it: must be positive, got %" PetscInt_FMT, ct->stall_its);
  PetscCheck(c || !strcmp(ct->type, "none"), p->comm, PETSC_ERR_USER_INPUT, "-cont_type %s needs a contact boundary: give -contact_label and/or -contact_ids", ct->type);
  PetscCall(SgFileCheckWritable(p->comm, "-checkpoint_file", ct->ckfile));
  PetscCall(DMCreateGlobalVector(p->dm, &ct->y));
  PetscCall(PetscObjectSetName((PetscObject)ct->y, "displacement"));
  PetscCall(PetscCalloc1(c ? c->n : 0, &ct->lam));
  PetscCall(SgSSNCreate(p, c, &ct->ssn));
  ct->ssn->hist = ct->hist;
  *cont         = ct;
  PetscFunctionReturn(0);
}

PetscErrorCode SgContDestroy(SgCont *cont)
{
  SgCont ct = *cont;

  PetscFunctionBeginUser;
  if (!ct) PetscFunctionReturn(0);
  if (ct->destroy) PetscCall(ct->destroy(ct)); /* what the controller's data holds */
  PetscCall(PetscFree(ct->data));
  PetscCall(SgSSNDestroy(&ct->ssn));
  PetscCall(VecDestroy(&ct->y));
  PetscCall(PetscFree(ct->lam));
  PetscCall(PetscFree(ct->gammas));
  PetscCall(SgHistoryDestroy(&ct->hist));
  PetscCall(SgSummaryDestroy(&ct->sum));
  PetscCall(PetscFree(*cont));
  PetscFunctionReturn(0);
}

/* Record a failure: the reason (printf-style) marks the run as not converged. */
PetscErrorCode SgContFail(SgCont ct, const char fmt[], ...)
{
  va_list ap;

  PetscFunctionBeginUser;
  va_start(ap, fmt);
  vsnprintf(ct->reason, sizeof(ct->reason), fmt, ap);
  va_end(ap);
  ct->converged = PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode SgContAddGamma(SgCont ct, PetscReal gamma)
{
  PetscFunctionBeginUser;
  if (ct->ngammas == ct->capgammas) {
    PetscReal *g;
    ct->capgammas = PetscMax(16, 2 * ct->capgammas);
    PetscCall(PetscMalloc1(ct->capgammas, &g));
    PetscCall(PetscArraycpy(g, ct->gammas, ct->ngammas));
    PetscCall(PetscFree(ct->gammas));
    ct->gammas = g;
  }
  ct->gammas[ct->ngammas++] = gamma;
  PetscFunctionReturn(0);
}

/* The start of every controller: y = the solution without contact (the paper's start) and V0 its energy, unless the
   state was read from -restart_file. ok = PETSC_FALSE (and the run failed) if that linear solve fails. */
PetscErrorCode SgContStart(SgCont ct, PetscBool *ok)
{
  PetscInt           its;
  KSPConvergedReason kr;

  PetscFunctionBeginUser;
  *ok = PETSC_TRUE;
  if (ct->c && !(ct->gamma <= ct->gamma_max)) { /* later steps are checked by SgContCheck */
    *ok = PETSC_FALSE;
    PetscCall(SgContFail(ct, "GAMMA_OVERFLOW: the first gamma %g exceeds -cont_gamma_max %g: no step taken", (double)ct->gamma, (double)ct->gamma_max));
    if (!ct->restarted) PetscCall(VecZeroEntries(ct->y));
    PetscCall(SgContMeasure(ct));
    PetscFunctionReturn(0);
  }
  if (ct->restarted && ct->outer >= ct->max_outer) { /* the checkpoint is at or beyond the limit: no step to take */
    *ok = PETSC_FALSE;
    PetscCall(SgContFail(ct, "MAX_IT: the checkpoint of -restart_file is at outer step %" PetscInt_FMT " >= -cont_max_it %" PetscInt_FMT ": no step taken", ct->outer, ct->max_outer));
  }
  if (ct->restarted && *ok) {
    /* V(0) belongs to the problem, not to the file: recomputed, so that a damaged value cannot bend the path model
       (one linear solve, not counted: the counters continue the checkpoint's) */
    Vec y0;
    PetscCall(VecDuplicate(ct->y, &y0));
    PetscCall(SgSSNSolveLinear(ct->ssn, y0, &its, &kr));
    if (kr >= 0) PetscCall(SgProblemEnergy(ct->prob, y0, &ct->V0));
    PetscCall(VecDestroy(&y0));
    if (kr < 0) {
      *ok = PETSC_FALSE;
      PetscCall(SgContFail(ct, "LINEAR_SOLVE_FAILED: the elasticity solve without contact stopped with KSP %s after %" PetscInt_FMT " iterations (check -ksp_type, -pc_type)", KSPConvergedReasons[kr], its));
    }
  }
  if (ct->restarted) PetscFunctionReturn(0);
  PetscCall(SgSSNSolveLinear(ct->ssn, ct->y, &its, &kr));
  ct->ksp_its += its;
  PetscCall(SgProblemEnergy(ct->prob, ct->y, &ct->V0));
  if (kr >= 0 && PetscIsInfOrNanReal(ct->V0)) {
    *ok = PETSC_FALSE;
    PetscCall(SgContFail(ct, "DIVERGED_NAN: the solution without contact is not finite (energy %g): the loads (-neumann_traction, -body_force, -dirichlet_values) are too large against -E for double precision", (double)ct->V0));
    if (ct->c) PetscCall(SgContMeasure(ct));
  } else if (kr < 0) {
    *ok = PETSC_FALSE;
    PetscCall(SgContFail(ct, "LINEAR_SOLVE_FAILED: the elasticity solve without contact stopped with KSP %s after %" PetscInt_FMT " iterations (check -ksp_type, -pc_type)", KSPConvergedReasons[kr], its));
    if (ct->c) PetscCall(SgContMeasure(ct));
  }
  PetscFunctionReturn(0);
}

/* What a user can change when an SSN solve fails: the options that act on it. */
static const char *SSNHint(SgSSNReason r)
{
  switch (r) {
  case SG_SSN_MAX_IT:
    return ": raise -snes_max_it, or take smaller gamma steps";
  case SG_SSN_CYCLING:
    return ": gamma may be too large for double precision here (see -cont_gamma_max and the controller's first gamma), or the linear solves too loose (-ksp_rtol)";
  case SG_SSN_LINEAR_SOLVE:
    return ": check -ksp_type, -pc_type, -ksp_max_it";
  case SG_SSN_NAN:
    return ": the iterate overflowed; check the magnitudes of -neumann_traction, -body_force, -dirichlet_values and -E";
  default:
    return ": see -snes_converged_reason and -ssn_monitor";
  }
}

/* One SSN solve of (P_gamma) (shift: c->lamhat) from the current y; lam = its multiplier. ok = PETSC_FALSE on failure. */
PetscErrorCode SgContSSN(SgCont ct, PetscReal gamma, PetscBool *ok)
{
  PetscInt            its, kits;
  SNESConvergedReason r;

  PetscFunctionBeginUser;
  PetscCall(SgContAddGamma(ct, gamma));
  PetscCall(SgSSNSolve(ct->ssn, gamma, ct->outer, ct->y, &its, &kits, &r));
  ct->ssn_its += its;
  ct->ksp_its += kits;
  PetscCall(PetscArraycpy(ct->lam, ct->ssn->m, ct->c->n));
  *ok = (PetscBool)(r > 0);
  if (!*ok) PetscCall(SgContFail(ct, "SSN_%s at gamma %g in outer step %" PetscInt_FMT " after %" PetscInt_FMT " iterations (SNES %s)%s", SgSSNReasons[ct->ssn->reason], (double)gamma, ct->outer, its, SNESConvergedReasons[r], SSNHint(ct->ssn->reason)));
  PetscFunctionReturn(0);
}

/* KKT measures of the iterate for the original problem. */
PetscErrorCode SgContMeasure(SgCont ct)
{
  PetscFunctionBeginUser;
  PetscCall(SgContactKKT(ct->c, ct->y, &ct->kkt));
  PetscFunctionReturn(0);
}

/* Path data per outer step (the history's outer rows) as summary arrays path_<quantity>. */
static PetscErrorCode SummaryPath(SgCont ct)
{
  const char *names[] = {"path_gamma", "path_V", "path_dVdgamma", "path_C1", "path_C2", "path_E", "path_ssn_iterations", "path_rho_F", "path_rho_C", "path_infeasibility", "path_kkt_residual"};
  PetscInt    n = 0;
  PetscReal  *a[11];

  PetscFunctionBeginUser;
  for (PetscInt j = 0; j < 11; j++) PetscCall(PetscMalloc1(ct->hist->n + 1, &a[j]));
  for (PetscInt i = 0; i < ct->hist->n; i++) {
    const SgHistoryRow *r = &ct->hist->rows[i];
    if (r->kind != 'o') continue;
    a[0][n]  = r->gamma;
    a[1][n]  = r->V;
    a[2][n]  = r->dV;
    a[3][n]  = r->C1;
    a[4][n]  = r->C2;
    a[5][n]  = r->Em;
    a[6][n]  = r->ssn_its;
    a[7][n]  = r->rhoF;
    a[8][n]  = r->rhoC;
    a[9][n]  = r->infeas;
    a[10][n] = r->kkt;
    n++;
  }
  for (PetscInt j = 0; j < 11; j++) {
    PetscCall(SgSummarySetRealArray(ct->sum, names[j], n, a[j]));
    PetscCall(PetscFree(a[j]));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SgContSolve(SgCont ct)
{
  PetscLogDouble t1;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&ct->t0));
  ct->ssn->t0 = ct->t0;
  PetscCall(SgCheckpointRead(ct));
  PetscCall(ct->solve(ct));
  PetscCall(PetscTime(&t1));
  PetscCall(SgProblemEnergy(ct->prob, ct->y, &ct->V));
  if (ct->c) {
    PetscCall(SgContMeasure(ct));
    if (!strcmp(ct->problem, "P")) ct->residual = ct->kkt.residual;
  }
  PetscCall(SgSummarySetString(ct->sum, "cont_type", ct->type));
  PetscCall(SgSummarySetBool(ct->sum, "converged", ct->converged));
  PetscCall(SgSummarySetString(ct->sum, "reason", ct->reason));
  PetscCall(SgSummarySetString(ct->sum, "problem", ct->problem));
  PetscCall(SgSummarySetReal(ct->sum, "residual", ct->residual));
  PetscCall(SgSummarySetReal(ct->sum, "residual_tol", ct->kkt_tol));
  PetscCall(SgSummarySetReal(ct->sum, "energy", ct->V));
  PetscCall(SgSummarySetReal(ct->sum, "energy_unconstrained", ct->V0));
  PetscCall(SgSummarySetInt(ct->sum, "ksp_iterations", ct->ksp_its));
  PetscCall(SgSummarySetReal(ct->sum, "solve_time", t1 - ct->t0));
  {
    PetscReal nrm[2];
    PetscCall(VecNorm(ct->y, NORM_2, &nrm[0]));
    PetscCall(VecNorm(ct->y, NORM_INFINITY, &nrm[1]));
    PetscCall(SgSummarySetReal(ct->sum, "displacement_norm", nrm[0]));
    PetscCall(SgSummarySetReal(ct->sum, "displacement_max", nrm[1]));
  }
  if (ct->c) {
    PetscCall(SgSummarySetInt(ct->sum, "ssn_iterations", ct->ssn_its));
    PetscCall(SgSummarySetInt(ct->sum, "outer_iterations", ct->outer));
    PetscCall(SgSummarySetRealArray(ct->sum, "gammas", ct->ngammas, ct->gammas));
    PetscCall(SgSummarySetReal(ct->sum, "kkt_residual", ct->kkt.residual));
    PetscCall(SgSummarySetReal(ct->sum, "infeasibility", ct->kkt.infeasibility));
    PetscCall(SgSummarySetReal(ct->sum, "complementarity", ct->kkt.complementarity));
    PetscCall(SgSummarySetReal(ct->sum, "equilibrium", ct->kkt.equilibrium));
    PetscCall(SgSummarySetReal(ct->sum, "dual_infeasibility", ct->kkt.dual));
    PetscCall(SgSummarySetReal(ct->sum, "penetration", ct->kkt.penetration));
    PetscCall(SgSummarySetReal(ct->sum, "displacement_scale", ct->kkt.uscale));
    PetscCall(SgSummarySetReal(ct->sum, "rho_F", ct->kkt.rhoF));
    PetscCall(SgSummarySetReal(ct->sum, "rho_C", ct->kkt.rhoC));
    PetscCall(SgSummarySetInt(ct->sum, "active_set_size", ct->kkt.nactive));
    PetscCall(SgSummarySetReal(ct->sum, "contact_force", ct->kkt.force));
    PetscCall(SgSummarySetInt(ct->sum, "contact_vertices", ct->c->nglobal));
    PetscCall(SgSummarySetReal(ct->sum, "contact_area", ct->c->area));
    PetscCall(SgSummarySetString(ct->sum, "obstacle", ct->c->obs->type));
    {
      /* the contact force on the body, sum_i w_i lam_i n_i, with the method's multiplier, against the reaction */
      const PetscInt dim = ct->prob->dim;
      PetscReal      F[3] = {0, 0, 0}, R[3];
      for (PetscInt i = 0; i < ct->c->n; i++)
        for (PetscInt d = 0; d < dim; d++) F[d] += ct->c->w[i] * ct->lam[i] * ct->c->normal[i * dim + d];
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, F, 3, MPIU_REAL, MPI_SUM, ct->comm));
      PetscCall(SgProblemReaction(ct->prob, ct->y, R));
      PetscCall(SgSummarySetRealArray(ct->sum, "contact_force_vector", dim, F));
      PetscCall(SgSummarySetRealArray(ct->sum, "reaction_force", dim, R));
    }
    PetscCall(SummaryPath(ct));
  }
  PetscFunctionReturn(0);
}

/* Add the row closing an outer step to the history. */
PetscErrorCode SgContOuterRow(SgCont ct, PetscInt ssn_its, PetscReal C1, PetscReal C2, PetscReal Em)
{
  SgHistoryRow   row;
  PetscLogDouble t;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t));
  PetscCall(SgHistoryRowInit(&row));
  row.kind    = 'o';
  row.outer   = ct->outer;
  row.gamma   = ct->ssn->gamma;
  row.active  = ct->kkt.nactive;
  row.fnorm   = ct->kkt.equilibrium;
  row.V       = ct->ssn->V;
  row.dV      = ct->ssn->dVdg;
  row.ssn_its = ssn_its;
  row.C1      = C1;
  row.C2      = C2;
  row.Em      = Em;
  row.rhoF    = ct->kkt.rhoF;
  row.rhoC    = ct->kkt.rhoC;
  row.infeas  = ct->kkt.infeasibility;
  row.kkt     = ct->kkt.residual;
  row.time    = t - ct->t0;
  PetscCall(SgHistoryAdd(ct->hist, &row));
  PetscFunctionReturn(0);
}

/* The model m(gamma) = C1 - C2/(E + gamma) through V(0), V(g) and V'(g), formula (9) of the paper.
   Returns PETSC_FALSE (and NaNs) if the data admit no such model (E must be positive and finite). */
PetscBool SgModelFit(PetscReal V0, PetscReal g, PetscReal V, PetscReal dV, PetscReal *C1, PetscReal *C2, PetscReal *E)
{
  const PetscReal den = V - V0 - g * dV;

  *E  = den != 0 ? g * g * dV / den : SG_NAN;
  *C2 = *E * (*E + g) * (V - V0) / g;
  *C1 = V0 + *C2 / *E;
  if (!(PetscIsNormalReal(*E) && *E > 0 && PetscIsNormalReal(*C1) && PetscIsNormalReal(*C2))) {
    *E = *C1 = *C2 = SG_NAN;
    return PETSC_FALSE;
  }
  return PETSC_TRUE;
}

/* After an outer step (ct->gamma and ct->state already hold the next step's): converged (KKT residual below the
   tolerance), or failed because the outer-step limit is reached, the next gamma overflows, or the KKT residual has not
   improved for -cont_stall_it steps. Then the checkpoint, if asked for. */
PetscErrorCode SgContCheck(SgCont ct, PetscBool *stop)
{
  const PetscReal gamma_next = ct->gamma;

  PetscFunctionBeginUser;
  *stop = PETSC_TRUE;
  if (ct->kkt.residual <= ct->kkt_tol) {
    ct->converged = PETSC_TRUE;
    PetscCall(PetscSNPrintf(ct->reason, sizeof(ct->reason), "KKT_RESIDUAL_BELOW_TOL: %.3e <= %.3e after %" PetscInt_FMT " outer steps", (double)ct->kkt.residual, (double)ct->kkt_tol, ct->outer));
    PetscCall(SgCheckpointWrite(ct));
    PetscFunctionReturn(0);
  }
  if (ct->kkt.residual < 0.99 * ct->best_kkt || ct->outer == 1) {
    ct->best_kkt  = ct->kkt.residual;
    ct->best_step = ct->outer;
  }
  if (PetscIsInfOrNanReal(ct->kkt.residual)) PetscCall(SgContFail(ct, "DIVERGED_NAN: the KKT residual is not a number after outer step %" PetscInt_FMT " (check the magnitudes of -neumann_traction, -body_force, -dirichlet_values and -E)", ct->outer));
  else if (ct->outer - ct->best_step >= ct->stall_its) PetscCall(SgContFail(ct, "STALLED: no progress in the KKT residual (%.3e, best %.3e at step %" PetscInt_FMT ") for %" PetscInt_FMT " outer steps (-cont_stall_it); a larger first gamma may help", (double)ct->kkt.residual, (double)ct->best_kkt, ct->best_step, ct->outer - ct->best_step));
  else if (!(gamma_next <= ct->gamma_max)) PetscCall(SgContFail(ct, "GAMMA_OVERFLOW: the next gamma %g exceeds -cont_gamma_max %g (KKT residual %.3e)", (double)gamma_next, (double)ct->gamma_max, (double)ct->kkt.residual));
  else if (ct->outer >= ct->max_outer) PetscCall(SgContFail(ct, "MAX_IT: %" PetscInt_FMT " outer steps (-cont_max_it) with KKT residual %.3e > %.3e", ct->outer, (double)ct->kkt.residual, (double)ct->kkt_tol));
  else *stop = PETSC_FALSE;
  PetscCall(SgCheckpointWrite(ct));
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

/* ---- none: one regularized problem (P_gamma) for -contact_gamma and -contact_lamhat, from the unconstrained start.
   It solves (P_gamma), not (P): converged means the equilibrium residual of (P_gamma) (SgSSNEquilibriumError) is below
   -cont_kkt_tol (a settled active set after loose linear solves is not enough); the KKT residual of (P) is reported
   beside it. */
static PetscErrorCode Solve_None(SgCont ct)
{
  PetscBool ok;
  PetscInt  its0 = ct->ssn_its;
  PetscReal roundoff;

  PetscFunctionBeginUser;
  if (ct->c) ct->gamma = ct->c->gamma;
  PetscCall(SgContStart(ct, &ok));
  if (!ok) PetscFunctionReturn(0);
  if (!ct->c) {
    PetscReal nrm[2];
    Vec       R;
    PetscCall(VecDuplicate(ct->y, &R));
    PetscCall(MatMult(ct->prob->K, ct->y, R));
    PetscCall(VecAXPY(R, -1.0, ct->prob->b));
    PetscCall(VecNorm(R, NORM_INFINITY, &nrm[0]));
    PetscCall(VecNorm(ct->y, NORM_INFINITY, &nrm[1]));
    PetscCall(VecDestroy(&R));
    ct->residual  = nrm[0] > 0 ? nrm[0] / (ct->prob->Knorm * nrm[1] + ct->prob->bnorm_inf) : 0;
    ct->converged = PETSC_TRUE;
    PetscCall(PetscStrcpy(ct->reason, "LINEAR_SOLVE"));
    PetscFunctionReturn(0);
  }
  ct->outer = 1;
  PetscCall(PetscLogEventBegin(SG_ContStep, 0, 0, 0, 0));
  PetscCall(SgContSSN(ct, ct->gamma, &ok));
  PetscCall(PetscLogEventEnd(SG_ContStep, 0, 0, 0, 0));
  PetscCall(SgContMeasure(ct));
  PetscCall(SgContOuterRow(ct, ct->ssn_its - its0, SG_NAN, SG_NAN, SG_NAN));
  PetscCall(SgSSNEquilibriumError(ct->ssn, ct->y, &ct->residual, &roundoff));
  if (ok && roundoff > ct->kkt_tol) {
    PetscCall(SgContFail(ct, "PGAMMA_UNVERIFIABLE: SSN_%s at gamma %g, but the round-off of gamma (tau_N y - d) is %.3e of the force scale, above -cont_kkt_tol %.3e: (P_gamma) cannot be checked to that tolerance in double precision (lower -contact_gamma, or solve (P) with -cont_type ipf); as a solution of (P) the KKT residual is %.3e", SgSSNReasons[ct->ssn->reason], (double)ct->gamma, (double)roundoff, (double)ct->kkt_tol, (double)ct->kkt.residual));
  } else if (ok && ct->residual <= ct->kkt_tol) {
    ct->converged = PETSC_TRUE;
    PetscCall(PetscSNPrintf(ct->reason, sizeof(ct->reason), "PGAMMA_SOLVED: SSN_%s at gamma %g, equilibrium residual of (P_gamma) %.3e <= %.3e; as a solution of (P) its KKT residual is %.3e (%s -cont_kkt_tol)", SgSSNReasons[ct->ssn->reason], (double)ct->gamma, (double)ct->residual, (double)ct->kkt_tol, (double)ct->kkt.residual, ct->kkt.residual <= ct->kkt_tol ? "within" : "above"));
  } else if (ok) {
    PetscCall(SgContFail(ct, "PGAMMA_RESIDUAL_ABOVE_TOL: SSN_%s at gamma %g, but the equilibrium residual of (P_gamma) is %.3e > %.3e (-cont_kkt_tol); tighten the linear solves", SgSSNReasons[ct->ssn->reason], (double)ct->gamma, (double)ct->residual, (double)ct->kkt_tol));
  }
  PetscCall(SgSummarySetReal(ct->sum, "path_value", ct->ssn->V));
  PetscCall(SgSummarySetReal(ct->sum, "path_derivative", ct->ssn->dVdg));
  PetscFunctionReturn(0);
}

/* The word for the end of a run: a solve of (P) converged, one (P_gamma) solved, or failed. */
const char *SgContVerdict(SgCont ct)
{
  if (!ct->converged) return "FAILED";
  return strcmp(ct->problem, "P_gamma") ? "CONVERGED" : "SOLVED (P_gamma)";
}

PetscErrorCode SgContCreate_None(SgCont ct)
{
  PetscFunctionBeginUser;
  ct->solve   = Solve_None;
  ct->problem = ct->c ? "P_gamma" : "elasticity";
  PetscFunctionReturn(0);
}
