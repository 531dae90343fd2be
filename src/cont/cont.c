/* cont/cont.c: SgCont, a solver of the contact problem: the registry of types (-cont_type), the object's life cycle
   (create, set-up, destroy), its setters and getters. The rest of the object has rooms of its own: its options
   (cont_options.c), the parts of an outer step the types call (cont_step.c), the outer loop of the continuation
   controllers and its verdicts (cont_loop.c), the solve and its load steps (cont_solve.c). */
#include "cont/contimpl.h"

PetscFunctionList SgContList = NULL;

static PetscErrorCode SgContFinalizePackage(void)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&SgContList));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContRegisterAll(void)
{
  static PetscBool done = PETSC_FALSE;

  PetscFunctionBeginUser;
  if (done) PetscFunctionReturn(0);
  done = PETSC_TRUE;
  PetscCall(PetscRegisterFinalize(SgContFinalizePackage));
  PetscCall(SgContRegister(SGCONTNONE, SgContCreate_None));
  PetscCall(SgContRegister(SGCONTALM, SgContCreate_ALM));
  PetscCall(SgContRegister(SGCONTPF, SgContCreate_PF));
  PetscCall(SgContRegister(SGCONTIPF, SgContCreate_IPF));
  PetscCall(SgContRegister(SGCONTFAST, SgContCreate_Fast));
  PetscCall(SgContRegister(SGCONTPDAS, SgContCreate_PDAS));
  PetscCall(SgContRegister(SGCONTVI, SgContCreate_VI));
  PetscFunctionReturn(0);
}

PetscErrorCode SgInitializePackage(void)
{
  PetscFunctionBeginUser;
  PetscCall(SgLogEventsRegister());
  PetscCall(SgObstacleRegisterAll());
  PetscCall(SgContRegisterAll());
  PetscFunctionReturn(0);
}

/* A controller type of the caller's: create fills the SgContOps of the object (see cont/contimpl.h). */
PetscErrorCode SgContRegister(const char name[], PetscErrorCode (*create)(SgCont))
{
  PetscFunctionBeginUser;
  PetscCheck(name && name[0], PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "SgContRegister: a type name is needed");
  SgValidPointer(create, 2);
  {
    size_t len;
    PetscCall(PetscStrlen(name, &len));
    PetscCheck(len < sizeof(((SgCont)0)->type), PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "SgContRegister: the type name has %zu characters, at most %zu", len, sizeof(((SgCont)0)->type) - 1);
  }
  PetscCall(SgContRegisterAll());
  PetscCall(PetscFunctionListAdd(&SgContList, name, create));
  PetscFunctionReturn(0);
}

/* arg-th argument of fn must be a live SgCont (not NULL, not destroyed): the class id of its PETSc header, checked also
   where PETSc's PetscValidHeaderSpecific compiles to nothing (an optimized PETSc) */
PetscErrorCode SgValidCont(SgCont ct, const char fn[], int arg)
{
  PetscFunctionBeginUser;
  PetscCall(SgValidObject((PetscObject)ct, SG_CONT_CLASSID, "SgCont", fn, arg));
  PetscValidHeaderSpecific(ct, SG_CONT_CLASSID, arg);
  PetscFunctionReturn(0);
}

/* The controller holds the problem (PetscObjectReference) until SgContDestroy: the caller may destroy its handle. */
PetscErrorCode SgContCreate(SgProblem prob, SgCont *cont)
{
  SgCont   ct;
  MPI_Comm comm;

  PetscFunctionBeginUser;
  SgValidPointer(cont, 2);
  *cont = NULL;
  PetscCall(SgValidProblem(prob, "SgContCreate", 1));
  PetscCall(SgInitializePackage());
  PetscCall(SgProblemGetComm(prob, &comm));
  PetscCall(PetscHeaderCreate(ct, SG_CONT_CLASSID, "SgCont", "Contact solver", "SgCont", comm, SgContDestroy, SgContView)); /* PetscObjectDestroy/View reach them */
  ct->comm = comm;
  PetscCall(PetscObjectReference((PetscObject)prob));
  ct->problem_obj     = prob;
  ct->kkt_tol         = 1e-10;
  ct->max_outer       = 50;
  ct->gamma_max       = 1e20;
  ct->stall_its       = 10;
  ct->nested_rim      = 0.3;
  ct->coulomb_shifted = PETSC_TRUE;
  ct->residual        = SG_NAN;
  ct->V0 = ct->V = SG_NAN;
  ct->monitor    = PETSC_TRUE;
  PetscCall(PetscStrcpy(ct->reason, "NOT_RUN"));
  PetscCall(SgHistoryCreate(&ct->hist));
  PetscCall(SgSummaryCreate(&ct->sum));
  *cont = ct;
  PetscFunctionReturn(0);
}

static PetscErrorCode CheckNotSetUp(SgCont ct, const char fn[])
{
  PetscFunctionBeginUser;
  PetscCall(SgValidCont(ct, fn, 1));
  PetscCheck(!ct->setfromoptions_called && !ct->setup, ct->comm, PETSC_ERR_ORDER, "%s: call it before SgContSetFromOptions/SgContSetUp", fn);
  PetscFunctionReturn(0);
}

PetscErrorCode SgContSetType(SgCont ct, const char type[])
{
  PetscFunctionBeginUser;
  PetscCall(CheckNotSetUp(ct, "SgContSetType"));
  PetscCheck(type && type[0], ct->comm, PETSC_ERR_ARG_NULL, "SgContSetType: a type name is needed");
  PetscCall(SgContRegisterAll());
  {
    PetscErrorCode (*create)(SgCont) = NULL;
    PetscCall(PetscFunctionListFind(SgContList, type, &create));
    PetscCheck(create, ct->comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "SgContSetType: unknown controller '%s' (none, alm, pf, ipf, fast, pdas, vi, or one of SgContRegister)", type);
  }
  PetscCall(PetscStrncpy(ct->type, type, sizeof(ct->type)));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContGetType(SgCont ct, const char *type[])
{
  PetscFunctionBeginUser;
  ValidCont(ct, 1);
  SgValidPointer(type, 2);
  *type = ct->type;
  PetscFunctionReturn(0);
}

PetscErrorCode SgContSetOptionsPrefix(SgCont ct, const char prefix[])
{
  PetscFunctionBeginUser;
  PetscCall(CheckNotSetUp(ct, "SgContSetOptionsPrefix"));
  PetscCheck(!prefix || prefix[0] != '-', ct->comm, PETSC_ERR_ARG_WRONG, "SgContSetOptionsPrefix: the prefix '%s' must not begin with a hyphen", prefix);
  PetscCall(PetscObjectSetOptionsPrefix((PetscObject)ct, prefix));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContGetOptionsPrefix(SgCont ct, const char *prefix[])
{
  PetscFunctionBeginUser;
  ValidCont(ct, 1);
  SgValidPointer(prefix, 2);
  *prefix = ((PetscObject)ct)->prefix;
  PetscFunctionReturn(0);
}

/* the KKT tolerance of (P) (of the equilibrium residual of (P_gamma) for none) and the outer-step limit (the defaults
   of -cont_kkt_tol and -cont_max_it; PETSC_DEFAULT keeps a value) */
PetscErrorCode SgContSetTolerances(SgCont ct, PetscReal kkt_tol, PetscInt max_it)
{
  PetscFunctionBeginUser;
  PetscCall(CheckNotSetUp(ct, "SgContSetTolerances"));
  PetscCheck(kkt_tol == (PetscReal)PETSC_DEFAULT || (PetscIsNormalReal(kkt_tol) && kkt_tol > 0), ct->comm, PETSC_ERR_ARG_OUTOFRANGE, "SgContSetTolerances: the KKT tolerance must be positive and finite (or PETSC_DEFAULT), got %g", (double)kkt_tol);
  PetscCheck(max_it == PETSC_DEFAULT || max_it > 0, ct->comm, PETSC_ERR_ARG_OUTOFRANGE, "SgContSetTolerances: the outer-step limit must be positive (or PETSC_DEFAULT), got %" PetscInt_FMT, max_it);
  if (kkt_tol != (PetscReal)PETSC_DEFAULT) ct->kkt_tol = kkt_tol;
  if (max_it != PETSC_DEFAULT) ct->max_outer = max_it;
  PetscFunctionReturn(0);
}

/* a line per outer step: the default of -cont_monitor (a program's setting, the option still wins) */
PetscErrorCode SgContSetMonitor(SgCont ct, PetscBool on)
{
  PetscFunctionBeginUser;
  PetscCall(CheckNotSetUp(ct, "SgContSetMonitor"));
  PetscCheck(on == PETSC_TRUE || on == PETSC_FALSE, ct->comm, PETSC_ERR_ARG_OUTOFRANGE, "SgContSetMonitor: the flag must be PETSC_TRUE or PETSC_FALSE, got %d", (int)on);
  ct->monitor = on;
  PetscFunctionReturn(0);
}

/* The iterate, the linear solver of every step and, for the controllers that use it, the SSN solver (reads the
   options first if SgContSetFromOptions was not called). */
PetscErrorCode SgContSetUp(SgCont ct)
{
  DM dm;

  PetscFunctionBeginUser;
  ValidCont(ct, 1);
  if (ct->setup) PetscFunctionReturn(0);
  PetscCheck(!ct->setup_failed, ct->comm, PETSC_ERR_ORDER, "SgContSetUp: an earlier call (or SgContSetFromOptions) stopped with an error; destroy the controller and make a new one");
  if (!ct->setfromoptions_called) PetscCall(SgContSetFromOptions(ct));
  ct->setup_failed = PETSC_TRUE;
  PetscCall(SgElasticityGetDMs(ct->prob, &dm, NULL, NULL, NULL));
  PetscCall(DMCreateGlobalVector(dm, &ct->y));
  PetscCall(PetscObjectSetName((PetscObject)ct->y, "displacement"));
  PetscCall(PetscCalloc1(ct->n, &ct->lam));
  if (ct->c) { /* this controller's copy of the law's slip reference (none without friction): zero, the first load step's start */
    PetscInt   m;
    PetscReal *lref;
    PetscCall(SgContactLawGetSlipReference(ct->cv.law, &lref)); /* (on every rank, also one without contact vertices) */
    PetscCall(SgContactLawGetSlipReferenceSize(ct->cv.law, &m));
    if (lref) PetscCall(PetscCalloc1(m + 1, &ct->yref)); /* of the unknowns, then of the full displacement */
  }
  PetscCall(SgLinearSolverCreate(ct->prob, ((PetscObject)ct)->prefix, &ct->lin, &ct->ksp, &ct->J));
  if (ct->ops.needs_ssn && ct->c) {
    PetscCall(SgSSNCreate(ct->prob, ct->c, ((PetscObject)ct)->prefix, ct->ksp, ct->J, &ct->ssn));
    if (ct->lin.on) { /* the default solver's SSN settings (the options still win) */
      PetscCall(SgSSNSetCondense(ct->ssn, ct->lin.condense));
      PetscCall(SgSSNSetTruncatedMG(ct->ssn, ct->lin.tmg, ct->lin.geometric));
    }
    PetscCall(SgSSNSetFromOptions(ct->ssn));
    PetscCall(SgSSNGetShift(ct->ssn, &ct->lamhat));
  }
  ct->setup_failed = PETSC_FALSE;
  ct->setup        = PETSC_TRUE;
  PetscCall(PetscObjectViewFromOptions((PetscObject)ct, NULL, "-cont_view")); /* the type and its parameters */
  PetscFunctionReturn(0);
}

PetscErrorCode SgContDestroy(SgCont *cont)
{
  SgCont ct;

  PetscFunctionBeginUser;
  SgValidPointer(cont, 1);
  ct = *cont;
  if (!ct) PetscFunctionReturn(0);
  ValidCont(ct, 1);
  *cont = NULL;
  if (--((PetscObject)ct)->refct > 0) PetscFunctionReturn(0);
  if (ct->ops.destroy) PetscCall(ct->ops.destroy(ct)); /* what the controller's data holds */
  PetscCall(PetscFree(ct->data));
  PetscCall(SgSSNDestroy(&ct->ssn));
  PetscCall(KSPDestroy(&ct->ksp));
  PetscCall(MatDestroy(&ct->J));
  PetscCall(VecDestroy(&ct->y));
  PetscCall(PetscFree(ct->lam));
  PetscCall(PetscFree(ct->yref));
  PetscCall(VecDestroy(&ct->ybest));
  PetscCall(VecDestroy(&ct->ystart));
  PetscCall(PetscFree(ct->lambest));
  PetscCall(PetscFree(ct->gammas));
  PetscCall(SgHistoryDestroy(&ct->hist));
  PetscCall(SgSummaryDestroy(&ct->sum));
  for (PetscInt k = 0; k < ct->nsteps && ct->ysteps; k++) {
    PetscCall(VecDestroy(&ct->ysteps[k]));
    PetscCall(PetscFree(ct->lamsteps[k]));
  }
  for (PetscInt k = 0; k < ct->nsteps && ct->yrsteps; k++) PetscCall(PetscFree(ct->yrsteps[k]));
  PetscCall(PetscFree(ct->yrsteps));
  PetscCall(PetscFree(ct->dvsteps));
  PetscCall(PetscFree2(ct->ysteps, ct->lamsteps));
  PetscCall(PetscFree(ct->steps));
  PetscCall(PetscFree(ct->nested_lamhat));
  PetscCall(SgProblemDestroy(&ct->problem_obj)); /* the controller's hold on it: freed if the caller let it go */
  PetscCall(PetscHeaderDestroy(&ct));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContGetSolution(SgCont ct, Vec *y)
{
  PetscFunctionBeginUser;
  ValidCont(ct, 1);
  SgValidPointer(y, 2);
  PetscCheck(ct->setup, ct->comm, PETSC_ERR_ORDER, "SgContGetSolution: call SgContSetUp or SgContSolve first");
  *y = ct->y;
  PetscFunctionReturn(0);
}

/* converged: the problem the type solves ((P), or (P_gamma) for none) was solved to the tolerance; reason: why it
   stopped, with the measures reached */
PetscErrorCode SgContGetConvergedReason(SgCont ct, PetscBool *converged, const char *reason[])
{
  PetscFunctionBeginUser;
  ValidCont(ct, 1);
  if (converged) *converged = ct->converged;
  if (reason) *reason = ct->reason;
  PetscFunctionReturn(0);
}

PetscErrorCode SgContGetIterationNumbers(SgCont ct, PetscInt *outer, PetscInt *ssn, PetscInt *ksp)
{
  PetscFunctionBeginUser;
  ValidCont(ct, 1);
  if (outer) *outer = ct->outer;
  if (ssn) *ssn = ct->ssn_its;
  if (ksp) *ksp = ct->ksp_its;
  PetscFunctionReturn(0);
}

/* SgContactKKT's measures of the result as a solution of (P) (dimensionless; see src/sg.h) */
PetscErrorCode SgContGetKKT(SgCont ct, SgKKT *kkt)
{
  PetscFunctionBeginUser;
  ValidCont(ct, 1);
  SgValidPointer(kkt, 2);
  PetscCheck(ct->solved, ct->comm, PETSC_ERR_ORDER, "SgContGetKKT: call SgContSolve first");
  PetscCheck(ct->c, ct->comm, PETSC_ERR_ARG_WRONGSTATE, "SgContGetKKT: the problem has no contact boundary");
  *kkt = ct->kkt;
  PetscFunctionReturn(0);
}

PetscErrorCode SgContGetEnergy(SgCont ct, PetscReal *V)
{
  PetscFunctionBeginUser;
  ValidCont(ct, 1);
  SgValidPointer(V, 2);
  *V = ct->V;
  PetscFunctionReturn(0);
}

/* the SSN's SNES (NULL for the baselines and without contact): for monitors and -snes_* settings in code */
PetscErrorCode SgContGetSNES(SgCont ct, SNES *snes)
{
  PetscFunctionBeginUser;
  ValidCont(ct, 1);
  SgValidPointer(snes, 2);
  PetscCall(SgContSetUp(ct));
  *snes = NULL;
  if (ct->ssn) PetscCall(SgSSNGetSNES(ct->ssn, snes));
  PetscFunctionReturn(0);
}
