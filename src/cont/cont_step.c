/* cont/cont_step.c: the parts of an outer step every controller type calls (the hooks of contimpl.h): a failure's
   reason, the gammas of the steps, the start (the solution without contact, V(0), the default -cont_gamma_max), one
   SSN solve of (P_gamma), the KKT measures of (P), the history row of a step; and the path's model and the limits
   of gamma (the cap at the KKT tolerance, the largest gamma double precision resolves). */
#include "cont/contimpl.h"
#include <stdarg.h>

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

/* kn[i] = n_i^T K_ii n_i, the normal diagonal stiffness of each contact vertex: kn / w has the units of gamma */
PetscErrorCode SgContNormalStiffness(SgCont ct, PetscReal kn[])
{
  PetscInt dim, rstart;
  Mat      K;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetDimension(ct->prob, &dim));
  PetscCall(SgElasticityGetOperators(ct->prob, &K, NULL));
  PetscCall(MatGetOwnershipRange(K, &rstart, NULL));
  /* n^T K_ii n with the vertex's whole diagonal block: the same for the problem turned rigidly (with only the
     diagonal entries, sum_k n_k^2 K_kk, it was not: a turned problem got another gamma) */
  for (PetscInt i = 0; i < ct->n; i++) {
    const PetscReal *n = &ct->normal[i * dim];
    PetscInt         idx[3];
    PetscScalar      B[9];
    for (PetscInt a = 0; a < dim; a++) idx[a] = rstart + ct->off[i] + a;
    PetscCall(MatGetValues(K, dim, idx, dim, idx, B));
    kn[i] = 0;
    for (PetscInt a = 0; a < dim; a++)
      for (PetscInt b = 0; b < dim; b++) kn[i] += n[a] * PetscRealPart(B[a * dim + b]) * n[b];
  }
  PetscFunctionReturn(0);
}

/* The default -cont_gamma_max: 1e14 times the largest n^T K_ii n / w_i, the problem's own scale of gamma. Past it,
   gamma w_i leaves K's part of a contact row below round-off. It scales with the units: the absolute 1e20 used
   before made a valid problem with E = 1e12 stop with GAMMA_OVERFLOW (the gamma it needs scales with E). */
static PetscErrorCode DefaultGammaMax(SgCont ct)
{
  PetscReal *kn, s = 0;

  PetscFunctionBeginUser;
  if (ct->gamma_max_set || !ct->c) PetscFunctionReturn(0);
  PetscCall(PetscMalloc1(ct->n, &kn));
  PetscCall(SgContNormalStiffness(ct, kn));
  for (PetscInt i = 0; i < ct->n; i++) s = PetscMax(s, kn[i] / ct->w[i]);
  PetscCall(PetscFree(kn));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &s, 1, MPIU_REAL, MPI_MAX, ct->comm));
  if (PetscIsNormalReal(s) && s > 0 && PetscIsNormalReal(1e14 * s)) ct->gamma_max = 1e14 * s;
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
  PetscCall(DefaultGammaMax(ct));
  if (ct->c && !(ct->gamma <= ct->gamma_max)) { /* later steps are checked by SgContCheck */
    *ok = PETSC_FALSE;
    PetscCall(SgContFail(ct, "GAMMA_OVERFLOW: the first gamma %g exceeds -cont_gamma_max %g: no step taken", (double)ct->gamma, (double)ct->gamma_max));
    if (!ct->restarted) PetscCall(VecZeroEntries(ct->y));
    PetscCall(SgContMeasure(ct));
    PetscFunctionReturn(0);
  }
  if (ct->warm) { /* a load step: y is the last step's solution; the unconstrained one is linear in the factor */
    PetscReal t;
    PetscBool dset;
    PetscCall(SgProblemGetLoadFactor(ct->problem_obj, &t));
    PetscCall(SgElasticityGetDirichletValues(ct->prob, &dset, NULL));
    if (!dset) {
      ct->V0 = t * t * ct->V0unit;
      PetscFunctionReturn(0);
    }
    { /* non-proportional loading (Dirichlet values of the step's own): V(0) of this step solved for */
      Vec y0;
      PetscCall(VecDuplicate(ct->y, &y0));
      PetscCall(SgLinearSolveUnconstrained(ct->prob, ct->ksp, ct->J, y0, &its, &kr, &ct->t_linear_setup, &ct->t_linear_solve));
      ct->ksp_its += its;
      if (kr >= 0) PetscCall(SgElasticityEnergy(ct->prob, y0, &ct->V0));
      PetscCall(VecDestroy(&y0));
      if (kr < 0) {
        *ok = PETSC_FALSE;
        PetscCall(SgContFail(ct, "LINEAR_SOLVE_FAILED: the elasticity solve without contact stopped with KSP %s after %" PetscInt_FMT " iterations (check -ksp_type, -pc_type)", KSPConvergedReasons[kr], its));
      }
    }
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
    PetscCall(SgLinearSolveUnconstrained(ct->prob, ct->ksp, ct->J, y0, &its, &kr, &ct->t_linear_setup, &ct->t_linear_solve));
    if (kr >= 0) PetscCall(SgElasticityEnergy(ct->prob, y0, &ct->V0));
    PetscCall(VecDestroy(&y0));
    if (kr < 0) {
      *ok = PETSC_FALSE;
      PetscCall(SgContFail(ct, "LINEAR_SOLVE_FAILED: the elasticity solve without contact stopped with KSP %s after %" PetscInt_FMT " iterations (check -ksp_type, -pc_type)", KSPConvergedReasons[kr], its));
    }
  }
  if (ct->restarted) PetscFunctionReturn(0);
  PetscCall(SgLinearSolveUnconstrained(ct->prob, ct->ksp, ct->J, ct->y, &its, &kr, &ct->t_linear_setup, &ct->t_linear_solve));
  ct->ksp_its += its;
  PetscCall(SgElasticityEnergy(ct->prob, ct->y, &ct->V0));
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

/* One SSN solve of (P_gamma) (shift: lamhat) from the current y; lam = its multiplier. ok = PETSC_FALSE on failure. */
PetscErrorCode SgContSSN(SgCont ct, PetscReal gamma, PetscBool *ok)
{
  PetscInt            its, kits;
  SNESConvergedReason r;
  const PetscReal    *m;

  PetscFunctionBeginUser;
  PetscCall(SgContAddGamma(ct, gamma));
  PetscCall(SgSSNSolve(ct->ssn, gamma, ct->outer, ct->y, &its, &kits, &r));
  ct->ssn_its += its;
  ct->ksp_its += kits;
  PetscCall(SgSSNGetMultiplier(ct->ssn, &m));
  PetscCall(PetscArraycpy(ct->lam, m, ct->n));
  *ok = (PetscBool)(r > 0);
  if (!*ok) {
    SgSSNReason sr;
    PetscCall(SgSSNGetReason(ct->ssn, &sr));
    PetscCall(SgContFail(ct, "SSN_%s at gamma %g in outer step %" PetscInt_FMT " after %" PetscInt_FMT " iterations (SNES %s)%s", SgSSNReasons[sr], (double)gamma, ct->outer, its, SNESConvergedReasons[r], SSNHint(sr)));
  }
  PetscFunctionReturn(0);
}

/* KKT measures of the iterate for the original problem. */
/* The contact object's slip reference is a working array of the problem, shared by every controller on it: each
   controller copies its own reference into it before it solves or evaluates anything with friction. */
PetscErrorCode SgContUseSlipReference(SgCont ct)
{
  PetscReal *yref;
  PetscInt   dim;

  PetscFunctionBeginUser;
  if (!ct->yref) PetscFunctionReturn(0);
  PetscCall(SgElasticityGetDimension(ct->prob, &dim));
  PetscCall(SgContactGetSlipReference(ct->c, &yref));
  PetscCall(PetscArraycpy(yref, ct->yref, 2 * ct->n * dim));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContMeasure(SgCont ct)
{
  PetscFunctionBeginUser;
  PetscCall(SgContactKKT(ct->c, ct->y, &ct->kkt));
  PetscCall(SgContactGetFrictionSummary(ct->c, &ct->fsum)); /* the law's (zeros without friction) */
  PetscFunctionReturn(0);
}

/* Add the row closing an outer step to the history: the path values of the SSN, the KKT measures, and what the
   controller's model hook put into mdl (C1, C2, Em; rhoF and rhoC when not NaN). */
PetscErrorCode SgContOuterRow(SgCont ct, PetscInt ssn_its, const SgHistoryRow *mdl)
{
  SgHistoryRow   row;
  PetscLogDouble t;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t));
  PetscCall(SgHistoryRowInit(&row));
  row.kind  = 'o';
  row.outer = ct->outer;
  if (ct->ssn) PetscCall(SgSSNGetPathValues(ct->ssn, &row.gamma, &row.V, &row.dV));
  row.active  = ct->kkt.nactive;
  row.fnorm   = ct->kkt.equilibrium;
  row.ssn_its = ssn_its;
  row.C1      = mdl ? mdl->C1 : SG_NAN;
  row.C2      = mdl ? mdl->C2 : SG_NAN;
  row.Em      = mdl ? mdl->Em : SG_NAN;
  row.rhoF    = mdl && !PetscIsNanReal(mdl->rhoF) ? mdl->rhoF : ct->kkt.rhoF;
  row.rhoC    = mdl && !PetscIsNanReal(mdl->rhoC) ? mdl->rhoC : ct->kkt.rhoC;
  row.infeas  = ct->kkt.infeasibility;
  row.kkt     = ct->kkt.residual;
  row.time    = t - ct->t0;
  PetscCall(SgHistoryAdd(ct->hist, &row));
  if (ct->monitor) {
    char g[32] = "-";
    if (!PetscIsNanReal(row.gamma)) PetscCall(PetscSNPrintf(g, sizeof(g), "%.3e", (double)row.gamma));
    PetscCall(PetscPrintf(ct->comm, "  %s step %2" PetscInt_FMT ": gamma %s, SSN %" PetscInt_FMT " (total %" PetscInt_FMT "), KSP total %" PetscInt_FMT ", active %" PetscInt_FMT "/%" PetscInt_FMT ", KKT residual %.3e, %.2f s\n", ct->type, ct->outer, g, ssn_its, ct->ssn_its, ct->ksp_its, ct->kkt.nactive, ct->nglobal, (double)ct->kkt.residual, (double)row.time));
  }
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

/* The gamma where the path meets the KKT tolerance with a margin: on the path the infeasibility is ||lam|| / gamma, so
   gamma = 10 ||lam||_L2 / (tol Y sqrt|Gamma_c|), Y sqrt|Gamma_c| the length scale of the KKT measures (ct->kkt must
   be measured). PETSC_FALSE when there is no length scale yet (nothing to measure against). */
PetscBool SgContGammaCap(SgCont ct, PetscReal lamnorm, PetscReal *cap)
{
  if (!(ct->kkt.lscale > 0)) return PETSC_FALSE;
  *cap = 10 * lamnorm / (ct->kkt_tol * ct->kkt.lscale);
  return PETSC_TRUE;
}

/* The largest gamma double precision resolves on this problem (at the iterate y with multiplier lam): the gap
   n.y - d at a contact vertex carries the round-off eps (|y_i| + |d_i|), so the regularized multiplier gamma g carries
   gamma eps max (|y_i| + |d_i|), and with friction the tangential gamma_T T y carries gamma_T eps max |y_i|. Past the
   gamma where that reaches 1e-2 of the largest multiplier (of the largest friction bound), the state of the vertices
   with small multipliers is decided by round-off and the SSN cycles (Example 1 with pf at gamma 1.7e17); the
   infeasibility on the path there, ||lam|| / gamma, is about 1e2 eps relative to the displacements.
   PETSC_MAX_REAL when nothing is in contact. */
PetscErrorCode SgContGammaPrecision(SgCont ct, PetscReal *gdp)
{
  const SgContactView *c = &ct->cv;
  const PetscScalar   *ya;
  PetscReal            v[3] = {0, 0, 0};
  PetscInt             dim, nd;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetDimension(ct->prob, &dim));
  PetscCall(SgElasticityGetNodalNormSize(ct->prob, &nd));
  PetscCall(VecGetArrayRead(ct->y, &ya));
  for (PetscInt i = 0; i < ct->n; i++) {
    PetscReal yi = 0;
    if (!(ct->lam[i] > 0)) continue;
    for (PetscInt k = 0; k < dim; k++) {
      const PetscReal yk = PetscRealPart(ya[ct->off[i] + k]);
      if (nd > 1) yi += yk * yk; /* -contact_kkt_scale vertex: the vertex's displacement, its length (the same turned) */
      else yi = PetscMax(yi, PetscAbsReal(yk));
    }
    if (nd > 1) yi = PetscSqrtReal(yi);
    v[0] = PetscMax(v[0], ct->lam[i]);
    v[1] = PetscMax(v[1], yi + PetscAbsReal(ct->d[i]));
    v[2] = PetscMax(v[2], yi);
  }
  PetscCall(VecRestoreArrayRead(ct->y, &ya));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, v, 3, MPIU_REAL, MPI_MAX, ct->comm));
  *gdp = v[0] > 0 && v[1] > 0 ? 1e-2 * v[0] / (PETSC_MACHINE_EPSILON * v[1]) : PETSC_MAX_REAL;
  PetscCall(SgContactLawGammaPrecision(c->law, v[0], v[2], gdp)); /* the law's limit (none without friction) */
  PetscFunctionReturn(0);
}
