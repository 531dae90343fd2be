/* cont/cont_solve.c: SgContSolve, one solve of the problem at its load factor: from the start, or warm from the last
   load step (a nested iteration's coarse levels, a restart file), the type's own solve or the outer loop, then the
   checks of the result and the record of the load step; the load steps' getters. */
#include "cont/contimpl.h"

/* A load step after the first: the counters of this step from zero, the first gamma the last one solved at; y, lamhat
   and the controller's state stay (the SSN's load scales are read again by SgContSolve before every solve). */
static PetscErrorCode PrepareWarm(SgCont ct)
{
  PetscReal t;

  PetscFunctionBeginUser;
  PetscCall(SgProblemGetLoadFactor(ct->problem_obj, &t));
  ct->outer = ct->ssn_its = ct->ksp_its = 0;
  ct->ngammas                           = 0;
  ct->best_kkt                          = 0;
  ct->best_step                         = 0;
  ct->converged                         = PETSC_FALSE;
  ct->residual                          = SG_NAN;
  PetscCall(PetscStrcpy(ct->reason, "NOT_RUN"));
  ct->gamma = ct->gamma_warm;
  if (ct->c && ct->ssn && !ct->ops.shifts && ct->nsteps && ct->steps[ct->nsteps - 1].t != t) {
    /* the last step ended at the double-precision cap: starting there, a type that only grows gamma would have no room
       (its first step at the cap is its last) while the new load moves the states, with friction the sticks whose
       force changes below gamma_T ulp(y) there; so it starts a thousandth below the cap and follows the path up (a
       solve again at the same load factor keeps its gamma: its answer is the last one) */
    PetscReal gdp;
    PetscCall(SgContGammaPrecision(ct, &gdp));
    if (SgContAtGammaPrecision(ct->gamma, gdp)) ct->gamma = 1e-3 * gdp;
  }
  PetscFunctionReturn(0);
}

/* The record of a finished load step (and its solution, if kept). */
static PetscErrorCode RecordStep(SgCont ct, PetscReal t)
{
  SgLoadStep *r;
  PetscReal   T[3] = {0, 0, 0};

  PetscFunctionBeginUser;
  if (ct->nsteps == ct->capsteps) {
    SgLoadStep *a;
    Vec        *ys;
    PetscReal **ls;
    ct->capsteps = PetscMax(8, 2 * ct->capsteps);
    PetscCall(PetscCalloc1(ct->capsteps, &a));
    PetscCall(PetscArraycpy(a, ct->steps, ct->nsteps));
    PetscCall(PetscFree(ct->steps));
    ct->steps = a;
    PetscCall(PetscCalloc2(ct->capsteps, &ys, ct->capsteps, &ls));
    if (ct->ysteps) {
      PetscCall(PetscArraycpy(ys, ct->ysteps, ct->nsteps));
      PetscCall(PetscArraycpy(ls, ct->lamsteps, ct->nsteps));
    }
    PetscCall(PetscFree2(ct->ysteps, ct->lamsteps));
    ct->ysteps   = ys;
    ct->lamsteps = ls;
    {
      PetscReal **yr;
      PetscCall(PetscCalloc1(ct->capsteps, &yr));
      if (ct->yrsteps) PetscCall(PetscArraycpy(yr, ct->yrsteps, ct->nsteps));
      PetscCall(PetscFree(ct->yrsteps));
      ct->yrsteps = yr;
    }
    if (ct->dvsteps) {
      PetscReal *dv;
      PetscCall(PetscMalloc1(ct->capsteps * ct->ndv + 1, &dv));
      for (PetscInt i = 0; i < ct->capsteps * ct->ndv; i++) dv[i] = i < ct->nsteps * ct->ndv ? ct->dvsteps[i] : SG_NAN;
      PetscCall(PetscFree(ct->dvsteps));
      ct->dvsteps = dv;
    }
  }
  r = &ct->steps[ct->nsteps];
  PetscCall(PetscMemzero(r, sizeof(*r)));
  r->t         = t;
  r->outer     = ct->outer;
  r->ssn_its   = ct->ssn_its;
  r->ksp_its   = ct->ksp_its;
  r->energy    = ct->V;
  r->time      = ct->t1 - ct->t0;
  r->converged = ct->converged;
  r->kkt       = ct->residual;
  if (ct->c) {
    PetscCall(SgContactGetObstacleTranslation(ct->c, T));
    r->obstacle_displacement = t * PetscSqrtReal(T[0] * T[0] + T[1] * T[1] + T[2] * T[2]);
    PetscCall(SgContactNormalDisplacementMax(ct->c, ct->y, &r->normal_displacement_max));
    r->force             = ct->kkt.force;
    r->nactive           = ct->kkt.nactive;
    r->nstick            = ct->fsum.nstick; /* the law's summary (zeros without friction) */
    r->nslip             = ct->fsum.nslip;
    r->friction_force    = ct->fsum.force_norm;
    r->friction_traction = ct->fsum.traction;
  }
  if (ct->store_steps) {
    PetscCall(VecDuplicate(ct->y, &ct->ysteps[ct->nsteps]));
    PetscCall(VecCopy(ct->y, ct->ysteps[ct->nsteps]));
    PetscCall(PetscMalloc1(ct->n + 1, &ct->lamsteps[ct->nsteps]));
    PetscCall(PetscArraycpy(ct->lamsteps[ct->nsteps], ct->lam, ct->n));
    if (ct->yref) { /* the step's slip reference, for its slip field */
      PetscInt dim;
      PetscCall(SgElasticityGetDimension(ct->prob, &dim));
      if (!ct->yrsteps) PetscCall(PetscCalloc1(ct->capsteps, &ct->yrsteps));
      PetscCall(PetscMalloc1(2 * ct->n * dim + 1, &ct->yrsteps[ct->nsteps])); /* of the unknowns, then of the full displacement */
      PetscCall(PetscArraycpy(ct->yrsteps[ct->nsteps], ct->yref, 2 * ct->n * dim));
    }
  }
  {
    PetscBool set;
    PetscCall(SgElasticityGetDirichletValues(ct->prob, &set, NULL));
    if (set && !ct->dvsteps) { /* non-proportional loading: the steps' Dirichlet values (fields, checkpoints) */
      PetscCall(SgElasticityGetDirichletSize(ct->prob, &ct->ndv));
      PetscCall(PetscMalloc1(ct->capsteps * ct->ndv + 1, &ct->dvsteps));
      for (PetscInt i = 0; i < ct->capsteps * ct->ndv; i++) ct->dvsteps[i] = SG_NAN;
    }
    if (set) PetscCall(SgElasticityGetDirichletValues(ct->prob, &set, &ct->dvsteps[ct->nsteps * ct->ndv]));
  }
  ct->nsteps++;
  PetscFunctionReturn(0);
}

/* What can be checked of a result beyond its KKT measures (after them, ct->kkt):
   - double precision: when forming K y - b rounds nodal forces by more than the tolerance times the largest force on the
     body (SgKKT.roundoff; lambda/mu large, a nearly incompressible material, with a fine mesh), no measure can certify
     the tolerance, whatever the controller reported: PRECISION_LIMIT, naming the material;
   - the energy: with y = 0 feasible (no initial penetration) the minimizer of (P) has V <= V(0) (frictionless; with
     friction (P) is no minimization of V), so a result above it, beyond the tolerance, is no solution: ENERGY_ABOVE_ZERO.
   A failure's earlier reason is kept at the end of the message. */
static PetscErrorCode CheckResult(SgCont ct)
{
  char was[sizeof(ct->reason)];

  PetscFunctionBeginUser;
  if (!ct->c) PetscFunctionReturn(0);
  PetscCall(PetscStrncpy(was, ct->reason, sizeof(was)));
  if (!(ct->kkt.roundoff <= ct->kkt_tol)) {
    PetscReal E, nu, lambda, mu;
    PetscCall(SgElasticityGetMaterial(ct->prob, &E, &nu));
    PetscCall(SgLame(E, nu, &lambda, &mu));
    PetscCall(SgContFail(ct, "PRECISION_LIMIT: double precision cannot certify -cont_kkt_tol %.3e here: forming K y - b rounds the nodal forces by %.3e of the largest force on the body (lambda/mu = %.3g, -nu %.16g); no solver can reach or verify it (-cont_kkt_tol above %.1e, nu farther from 0.5 or a coarser mesh can be solved); the run: %s%s", (double)ct->kkt_tol, (double)ct->kkt.roundoff, (double)(lambda / mu), (double)nu, (double)(2 * ct->kkt.roundoff), ct->converged ? "CONVERGED, " : "", was));
    PetscFunctionReturn(0);
  }
  if (ct->converged && !ct->cv.props.dissipative && !strcmp(ct->problem, "P")) {
    PetscReal dmin = PETSC_MAX_REAL, V0, margin;
    PetscInt  ndofs;
    for (PetscInt i = 0; i < ct->n; i++) dmin = PetscMin(dmin, ct->d[i]);
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &dmin, 1, MPIU_REAL, MPI_MIN, ct->comm));
    if (dmin < 0) PetscFunctionReturn(0);
    PetscCall(SgElasticityGetEnergyShift(ct->prob, &V0)); /* V(0) */
    PetscCall(VecGetSize(ct->y, &ndofs));
    /* V(y) - V(y*) is first order in the tolerance (lam . g over Gamma_c) and in the rounding of the forces */
    margin = ct->kkt_tol * (PetscAbsReal(ct->V) + PetscAbsReal(V0) + ndofs * ct->kkt.fscale * ct->kkt.uscale);
    if (!(ct->V <= V0 + margin))
      PetscCall(SgContFail(ct, "ENERGY_ABOVE_ZERO: the result's energy %.6e exceeds V(0) = %.6e, although y = 0 is feasible (no initial penetration): it is no minimizer of (P) (KKT residual %.3e; the run: %s)", (double)ct->V, (double)V0, (double)ct->kkt.residual, was));
  }
  PetscFunctionReturn(0);
}

/* Solve: the controller's steps from the unconstrained start (or the restart file's state), then the energy and the
   KKT measures of the result. Called again (a load step, after SgProblemSetLoadFactor): the steps start from the last
   solution and controller state (see contimpl.h). Reporting is separate (SgContView, SgContWriteSummary, ...). */
PetscErrorCode SgContSolve(SgCont ct)
{
  PetscReal t;
  PetscBool loadsteps;

  PetscFunctionBeginUser;
  ValidCont(ct, 1);
  PetscCall(SgContSetUp(ct));
  PetscCall(SgProblemGetLoadFactor(ct->problem_obj, &t));
  PetscCall(SgProblemHasLoadSteps(ct->problem_obj, &loadsteps));
  PetscCall(PetscTime(&ct->t0));
  if (ct->ssn) {
    PetscCall(SgSSNSetHistory(ct->ssn, ct->hist, ct->t0));
    PetscCall(SgSSNUpdateLoad(ct->ssn));
  }
  PetscCall(SgContCheckpointRead(ct));
  PetscCheck(!ct->restarted || PetscAbsReal(t - ct->rsload) <= 1e-12 * t, ct->comm, PETSC_ERR_USER_INPUT, "-restart_file: the checkpoint is inside load step %" PetscInt_FMT " at load factor %.17g, but this run solves that step at %.17g (give the same -load_steps and -load_factors)", ct->nsteps + 1, (double)ct->rsload, (double)t);
  ct->warm = (PetscBool)(ct->have_state && !ct->restarted);
  /* quasi-static friction: a load step's tangential law acts on the slip since the last converged step (the warm
     start y); the first step's slip is from y = 0 */
  if (ct->warm && ct->yref && ct->yref_read) ct->yref_read = PETSC_FALSE; /* read from -restart_file into ct->yref */
  else if (ct->warm && ct->yref) {
    PetscReal *yref;
    PetscInt   dim;
    PetscCall(SgElasticityGetDimension(ct->prob, &dim));
    PetscCall(SgContactSetSlipReference(ct->c, ct->y)); /* with the prescribed components' data of the step y solved */
    PetscCall(SgContactGetSlipReference(ct->c, &yref));
    PetscCall(PetscArraycpy(ct->yref, yref, 2 * ct->n * dim)); /* this controller's */
  }
  PetscCall(SgContUseSlipReference(ct)); /* this controller's, not the last one's that solved the problem */
  /* nested iteration: the first solve starts from the coarse levels' solution (a coarse level's controller from the
     level below it, set by SgContNestedStart of the finest) like a warm load step, slip reference and all kept */
  if (ct->nested && !ct->warm && !ct->restarted && !ct->have_state) PetscCall(SgContNestedStart(ct));
  if (ct->nested_start) ct->warm = PETSC_TRUE;
  if (ct->warm) PetscCall(PrepareWarm(ct));
  if (ct->ops.solve) PetscCall(ct->ops.solve(ct));
  else PetscCall(SgContSolveContinuation(ct));
  if (ct->nested_stage) PetscCall(PetscLogStagePop()); /* the finest level's stage (SgContNestedStart) */
  ct->nested_stage = PETSC_FALSE;
  ct->nested_start = PETSC_FALSE; /* the next solve (a load step) is warm from this one */
  PetscCall(PetscTime(&ct->t1));
  PetscCall(SgElasticityEnergy(ct->prob, ct->y, &ct->V));
  if (ct->c) {
    PetscCall(SgContMeasure(ct));
    if (!strcmp(ct->problem, "P")) ct->residual = ct->kkt.residual;
    PetscCall(CheckResult(ct));
  }
  ct->solved     = PETSC_TRUE;
  ct->restarted  = PETSC_FALSE;
  ct->warm       = PETSC_FALSE;
  ct->have_state = PETSC_TRUE;
  if (t != 0) ct->V0unit = ct->V0 / (t * t); /* a step unloaded to 0 says nothing of it */
  if (ct->ngammas && PetscIsNormalReal(ct->gammas[ct->ngammas - 1])) ct->gamma_warm = ct->gammas[ct->ngammas - 1];
  PetscCall(RecordStep(ct, t));
  /* a load step's end: a restart from here starts the next step warm */
  if (loadsteps && ct->converged) PetscCall(SgContCheckpointWriteStepEnd(ct));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContGetLoadSteps(SgCont ct, PetscInt *n)
{
  PetscFunctionBeginUser;
  ValidCont(ct, 1);
  SgValidPointer(n, 2);
  PetscCall(SgContCheckpointRead(ct));
  *n = ct->nsteps;
  PetscFunctionReturn(0);
}

PetscErrorCode SgContGetLoadStepFactor(SgCont ct, PetscInt k, PetscReal *t)
{
  PetscFunctionBeginUser;
  ValidCont(ct, 1);
  SgValidPointer(t, 3);
  PetscCall(SgContCheckpointRead(ct));
  PetscCheck(k >= 0 && k < ct->nsteps, ct->comm, PETSC_ERR_ARG_OUTOFRANGE, "SgContGetLoadStepFactor: load step %" PetscInt_FMT " of %" PetscInt_FMT " solved", k, ct->nsteps);
  *t = ct->steps[k].t;
  PetscFunctionReturn(0);
}

/* the Dirichlet values of a solved load step (SgProblemGetDirichletSize numbers), if they were set for it
   (SgProblemSetDirichletValues; set = PETSC_FALSE: the given values times the step's factor) */
PetscErrorCode SgContGetLoadStepDirichletValues(SgCont ct, PetscInt k, PetscBool *set, PetscReal values[])
{
  PetscFunctionBeginUser;
  ValidCont(ct, 1);
  SgValidPointer(set, 3);
  PetscCall(SgContCheckpointRead(ct));
  PetscCheck(k >= 0 && k < ct->nsteps, ct->comm, PETSC_ERR_ARG_OUTOFRANGE, "SgContGetLoadStepDirichletValues: load step %" PetscInt_FMT " of %" PetscInt_FMT " solved", k, ct->nsteps);
  *set = (PetscBool)(ct->dvsteps && !PetscIsNanReal(ct->dvsteps[k * ct->ndv]));
  for (PetscInt i = 0; *set && values && i < ct->ndv; i++) values[i] = ct->dvsteps[k * ct->ndv + i];
  PetscFunctionReturn(0);
}

PetscErrorCode SgContSetStoreSteps(SgCont ct, PetscBool store)
{
  PetscFunctionBeginUser;
  ValidCont(ct, 1);
  PetscCheck(store == PETSC_TRUE || store == PETSC_FALSE, ct->comm, PETSC_ERR_ARG_OUTOFRANGE, "SgContSetStoreSteps: %d is neither PETSC_TRUE nor PETSC_FALSE", (int)store);
  /* the fields of every step need every step's solution: steps solved before would have none */
  PetscCheck(!ct->nsteps || store == ct->store_steps, ct->comm, PETSC_ERR_ORDER, "SgContSetStoreSteps: call it before the first SgContSolve (%" PetscInt_FMT " load steps are solved)", ct->nsteps);
  ct->store_steps = store;
  PetscFunctionReturn(0);
}
