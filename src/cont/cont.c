/* cont/cont.c: SgCont, a solver of the contact problem: the registry of types (-cont_type), the object's life cycle,
   and the outer loop every continuation controller shares (the types fill the hooks of SgContOps, contimpl.h). */
#include "cont/contimpl.h"
#include <stdarg.h>

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

/* The options every controller has */
static PetscErrorCode CommonOptions(SgCont ct, PetscOptionItems *PetscOptionsObject)
{
  PetscFunctionBeginUser;
  {
    PetscBool set;
    PetscCall(PetscOptionsFList("-cont_type", "Controller: none (one (P_gamma)), alm, pf, ipf, fast (one capped (P_gamma) with inexact steps), or the baselines pdas and vi", NULL, SgContList, ct->type, ct->type, sizeof(ct->type), &set));
    if (set) ct->type_default = PETSC_FALSE;
  }
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-cont_kkt_tol", "Stop when the KKT residual of (P) (dimensionless: relative to the force and displacement scales) is below this; for none, the tolerance of the equilibrium residual of (P_gamma)", &ct->kkt_tol, NULL));
  PetscCall(SgOptionsIntValue(PetscOptionsObject, "-cont_max_it", "Maximum number of outer (continuation) steps", &ct->max_outer, NULL));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-cont_gamma_max", "Stop with GAMMA_OVERFLOW when gamma would exceed this (default: 1e14 x the largest normal stiffness per contact area, n^T K_ii n / w_i)", &ct->gamma_max, &ct->gamma_max_set));
  PetscCall(PetscOptionsString("-checkpoint_file", "HDF5 file with the continuation state, rewritten after every outer step", NULL, ct->ckfile, ct->ckfile, sizeof(ct->ckfile), NULL));
  PetscCall(PetscOptionsString("-restart_file", "Resume from a checkpoint (a continuation controller: alm, pf, ipf; any number of ranks)", NULL, ct->rsfile, ct->rsfile, sizeof(ct->rsfile), NULL));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-cont_monitor", "Print a line per outer step (gamma, SSN and KSP iterations, active set, KKT residual, time)", &ct->monitor, NULL));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-cont_coulomb_shifted_path", "Coulomb friction: when a regularized solve of pf or ipf fails, or the tolerance lies below the double-precision cap of gamma (PRECISION_LIMIT), solve again from the start on the shifted path (the augmented Lagrangian steps of alm, gamma doubled per step)", &ct->coulomb_shifted, NULL));
  PetscCall(SgOptionsIntValue(PetscOptionsObject, "-cont_stall_it", "Stop with STALLED after this many outer steps without progress in the KKT residual", &ct->stall_its, NULL));
  if (!ct->nested_inner) PetscCall(SgOptionsIntValue(PetscOptionsObject, "-cont_nested", "Nested iteration: solve first on the mesh refined this many times fewer (needs -dm_refine >= it), then on each finer one from the interpolated solution, multiplier shift and gamma (0: off)", &ct->nested, NULL));
  PetscFunctionReturn(0);
}

/* The options of the type under its heading (-help) */
static PetscErrorCode TypeOptions(SgCont ct, PetscOptionItems *PetscOptionsObject)
{
  char head[128];

  PetscFunctionBeginUser;
  if (!ct->ops.setfromoptions) PetscFunctionReturn(0);
  PetscCall(PetscSNPrintf(head, sizeof(head), "SgCont %s options (-cont_type %s)", ct->type, ct->type));
  PetscOptionsHeadBegin(PetscOptionsObject, head);
  PetscCall(ct->ops.setfromoptions(ct, PetscOptionsObject));
  PetscOptionsHeadEnd();
  PetscFunctionReturn(0);
}

/* With -help, the options of every other registered type too (each read into a scratch controller of that type, which
   is thrown away), so that -help lists them all whichever type runs. */
static PetscErrorCode HelpTypes(SgCont ct, const char skip[], PetscOptionItems *PetscOptionsObject)
{
  PetscBool    help;
  int          n;
  const char **names;
  PetscErrorCode (*create)(SgCont);

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(PetscOptionsObject->options, &help));
  if (!help || !PetscOptionsObject->printhelp || PetscOptionsObject->alreadyprinted) PetscFunctionReturn(0);
  PetscCall(PetscFunctionListGet(SgContList, &names, &n));
  for (int i = 0; i < n && names[i]; i++) { /* (PETSc counts the array's closing NULL in n) */
    SgCont    tmp;
    PetscBool same;
    PetscCall(PetscStrcmp(names[i], skip, &same));
    if (same) continue;
    PetscCall(PetscFunctionListFind(SgContList, names[i], &create));
    if (!create) continue;
    PetscCall(PetscNew(&tmp));
    tmp->comm = ct->comm;
    PetscCall(PetscStrncpy(tmp->type, names[i], sizeof(tmp->type)));
    PetscCall(create(tmp));
    PetscCall(TypeOptions(tmp, PetscOptionsObject));
    if (tmp->ops.destroy) PetscCall(tmp->ops.destroy(tmp));
    PetscCall(PetscFree(tmp->data));
    PetscCall(PetscFree(tmp));
  }
  PetscCall(PetscFree(names));
  PetscFunctionReturn(0);
}

/* With -help: the controller's options, those of every type, printed now (before the problem is set up, whose
   options may be missing); SgContSetFromOptions does not print them again. A copy of the controller reads them, so
   that nothing is set yet. */
PetscErrorCode SgContPrintHelp(SgCont ct)
{
  PetscBool help;
  SgCont    tmp;

  PetscFunctionBeginUser;
  ValidCont(ct, 1);
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  if (!help) PetscFunctionReturn(0);
  PetscCall(PetscNew(&tmp));
  PetscCall(PetscMemcpy(tmp, ct, sizeof(*ct)));                                                        /* the settings' defaults (nothing of it is freed or called) */
  PetscOptionsBegin(ct->comm, ((PetscObject)ct)->prefix, "Contact solver (SgCont) options", "SgCont"); /* PetscObjectOptionsBegin's title: listed once */
  PetscCall(CommonOptions(tmp, PetscOptionsObject));
  PetscCall(HelpTypes(tmp, "", PetscOptionsObject));
  {
    PetscBool view = PETSC_FALSE;
    PetscCall(PetscOptionsName("-cont_view", "View the controller (its type and parameters) after its set-up", "SgContSetUp", &view));
  }
  PetscOptionsEnd();
  PetscCall(PetscFree(tmp));
  /* and those of the objects the controller makes or reads later, which a run without a problem never reaches (each
     section is printed once: the real reading later does not repeat it) */
  PetscCall(SgLinearSolverPrintHelp(ct->comm, ((PetscObject)ct)->prefix));
  PetscCall(SgSSNPrintHelp(ct->comm, ((PetscObject)ct)->prefix));
  { /* the mesh is not read yet: the box's dimension if given, else 2 (the default box) for the vectors' defaults */
    PetscInt dim = 2;
    PetscCall(PetscOptionsGetInt(NULL, ((PetscObject)ct->problem_obj)->prefix, "-box_dim", &dim, NULL));
    PetscCall(SgObstaclePrintHelp(ct->comm, ((PetscObject)ct->problem_obj)->prefix, dim == 3 ? 3 : 2));
  }
  PetscFunctionReturn(0);
}

/* The options under the prefix: -cont_type and the controller's own, the stopping tests, checkpoint and restart files.
   The problem is set up first (its options are read before the solver's). */
PetscErrorCode SgContSetFromOptions(SgCont ct)
{
  PetscErrorCode (*create)(SgCont) = NULL;
  SgProblem p;
  PetscBool solver_default, iterative;
  PetscInt  dim;

  PetscFunctionBeginUser;
  ValidCont(ct, 1);
  p = ct->problem_obj;
  PetscCheck(!ct->setfromoptions_called, ct->comm, PETSC_ERR_ORDER, "SgContSetFromOptions: called twice");
  PetscCheck(!ct->setup_failed, ct->comm, PETSC_ERR_ORDER, "SgContSetFromOptions: an earlier call (or SgContSetUp) stopped with an error; destroy the controller and make a new one");
  ct->setup_failed = PETSC_TRUE; /* until the end is reached */
  PetscCall(SgProblemSetUp(p));
  PetscCall(SgProblemGetElasticity(p, &ct->prob));
  PetscCall(SgProblemGetContact(p, &ct->c));
  if (ct->c) PetscCall(SgContactGetView(ct->c, &ct->cv));
  ct->problem = ct->c ? "P" : "elasticity";
  /* the default solves the problem given: the contact problem (P) with the default controller, or the elasticity
     problem alone (none) without a contact boundary */
  /* the linear solver first (its default depends on the problem's size), then the controller's default from it:
     fast (one capped (P_gamma), inexact steps) in 3D and for iterative solves, ipf in 2D with exact solves, where fast
     can take many more steps (nearly incompressible: 31 against 18; bench/perf_notes.md) */
  PetscCall(SgLinearSolverDefaults(ct->prob, ((PetscObject)ct)->prefix, (PetscBool)(ct->c && ct->cv.coupled), &solver_default, &iterative, ct->solver_desc, sizeof(ct->solver_desc)));
  PetscCall(SgElasticityGetDimension(ct->prob, &dim));
  ct->type_default = (PetscBool)!ct->type[0];
  /* fast is not built for friction: ipf there */
  if (ct->type_default) PetscCall(PetscStrcpy(ct->type, !ct->c ? SGCONTNONE : ((dim == 3 || iterative) && !ct->cv.friction ? SGCONTFAST : SGCONTIPF)));
  PetscObjectOptionsBegin((PetscObject)ct);
  PetscCall(CommonOptions(ct, PetscOptionsObject));
  PetscCall(PetscFunctionListFind(SgContList, ct->type, &create));
  PetscCheck(create, ct->comm, PETSC_ERR_USER_INPUT, "-cont_type: unknown controller '%s' (see -help for the list)", ct->type);
  ct->ops.needs_ssn = PETSC_TRUE;
  PetscCall(create(ct));
  PetscCall(PetscObjectChangeTypeName((PetscObject)ct, ct->type));
  PetscCall(TypeOptions(ct, PetscOptionsObject));
  PetscCall(HelpTypes(ct, ct->type, PetscOptionsObject));
  PetscOptionsEnd();
  if (solver_default && ct->ops.needs_ssn) PetscCall(SgLinearSolverDefaultSSN(ct->prob, ct->c, ((PetscObject)ct)->prefix, iterative, ct->solver_desc, sizeof(ct->solver_desc)));
  PetscCheck(PetscIsNormalReal(ct->kkt_tol) && ct->kkt_tol > 0, ct->comm, PETSC_ERR_USER_INPUT, "-cont_kkt_tol: must be positive and finite, got %g", (double)ct->kkt_tol);
  PetscCheck(ct->max_outer > 0, ct->comm, PETSC_ERR_USER_INPUT, "-cont_max_it: must be positive, got %" PetscInt_FMT, ct->max_outer);
  PetscCheck(PetscIsNormalReal(ct->gamma_max) && ct->gamma_max > 0, ct->comm, PETSC_ERR_USER_INPUT, "-cont_gamma_max: must be positive and finite, got %g", (double)ct->gamma_max);
  PetscCheck(ct->stall_its > 0, ct->comm, PETSC_ERR_USER_INPUT, "-cont_stall_it: must be positive, got %" PetscInt_FMT, ct->stall_its);
  if (ct->c && ct->cv.friction) {
    /* the controllers that drive the SSN of (P_gamma) with friction: none, alm, pf, ipf */
    PetscBool pair;
    PetscCall(SgContactIsPair(ct->c, &pair)); /* two bodies: pdas is refused for the pair itself */
    PetscCheck(strcmp(ct->type, SGCONTFAST) && strcmp(ct->type, SGCONTVI), ct->comm, PETSC_ERR_SUP, "-cont_type %s is not built for friction (-friction_type %s) yet: use none, alm, pf, ipf%s", ct->type, SgLawName(ct->cv.law), pair ? " (two bodies: not pdas either)" : " or the baseline pdas");
  }
  PetscCheck(ct->c || !strcmp(ct->type, SGCONTNONE), ct->comm, PETSC_ERR_USER_INPUT, "-cont_type %s needs a contact boundary: give -contact_label and/or -contact_ids", ct->type);
  PetscCall(SgFileCheckWritable(ct->comm, "-checkpoint_file", ct->ckfile));
  PetscCall(SgContNestedCheck(ct));
  ct->setup_failed          = PETSC_FALSE;
  ct->setfromoptions_called = PETSC_TRUE;
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
  PetscCall(PetscCalloc1(ct->cv.n, &ct->lam));
  if (ct->c && ct->cv.friction) { /* this controller's slip reference: zero, the first load step's start */
    PetscInt dim;
    PetscCall(SgElasticityGetDimension(ct->prob, &dim));
    PetscCall(PetscCalloc1(2 * ct->cv.n * dim + 1, &ct->yref)); /* of the unknowns, then of the full displacement */
  }
  PetscCall(SgLinearSolverCreate(ct->prob, ((PetscObject)ct)->prefix, &ct->ksp, &ct->J));
  if (ct->ops.needs_ssn && ct->c) {
    PetscCall(SgSSNCreate(ct->prob, ct->c, ((PetscObject)ct)->prefix, ct->ksp, ct->J, &ct->ssn));
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
  const SgContactView *c = &ct->cv;
  PetscInt             dim, rstart;
  Mat                  K;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetDimension(ct->prob, &dim));
  PetscCall(SgElasticityGetOperators(ct->prob, &K, NULL));
  PetscCall(MatGetOwnershipRange(K, &rstart, NULL));
  /* n^T K_ii n with the vertex's whole diagonal block: the same for the problem turned rigidly (with only the
     diagonal entries, sum_k n_k^2 K_kk, it was not: a turned problem got another gamma) */
  for (PetscInt i = 0; i < c->n; i++) {
    const PetscReal *n = &c->normal[i * dim];
    PetscInt         idx[3];
    PetscScalar      B[9];
    for (PetscInt a = 0; a < dim; a++) idx[a] = rstart + c->off[i] + a;
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
  PetscCall(PetscMalloc1(ct->cv.n, &kn));
  PetscCall(SgContNormalStiffness(ct, kn));
  for (PetscInt i = 0; i < ct->cv.n; i++) s = PetscMax(s, kn[i] / ct->cv.w[i]);
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
  PetscCall(PetscArraycpy(ct->lam, m, ct->cv.n));
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
  PetscCall(PetscArraycpy(yref, ct->yref, 2 * ct->cv.n * dim));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContMeasure(SgCont ct)
{
  PetscFunctionBeginUser;
  PetscCall(SgContactKKT(ct->c, ct->y, &ct->kkt));
  if (ct->cv.friction) PetscCall(SgContactGetFrictionSummary(ct->c, &ct->fsum));
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
    PetscCall(PetscPrintf(ct->comm, "  %s step %2" PetscInt_FMT ": gamma %s, SSN %" PetscInt_FMT " (total %" PetscInt_FMT "), KSP total %" PetscInt_FMT ", active %" PetscInt_FMT "/%" PetscInt_FMT ", KKT residual %.3e, %.2f s\n", ct->type, ct->outer, g, ssn_its, ct->ssn_its, ct->ksp_its, ct->kkt.nactive, ct->cv.nglobal, (double)ct->kkt.residual, (double)row.time));
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
  PetscInt             dim;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetDimension(ct->prob, &dim));
  PetscCall(VecGetArrayRead(ct->y, &ya));
  for (PetscInt i = 0; i < c->n; i++) {
    PetscReal yi = 0;
    if (!(ct->lam[i] > 0)) continue;
    for (PetscInt k = 0; k < dim; k++) yi = PetscMax(yi, PetscAbsReal(PetscRealPart(ya[c->off[i] + k])));
    v[0] = PetscMax(v[0], ct->lam[i]);
    v[1] = PetscMax(v[1], yi + PetscAbsReal(c->d[i]));
    v[2] = PetscMax(v[2], yi);
  }
  PetscCall(VecRestoreArrayRead(ct->y, &ya));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, v, 3, MPIU_REAL, MPI_MAX, ct->comm));
  *gdp = v[0] > 0 && v[1] > 0 ? 1e-2 * v[0] / (PETSC_MACHINE_EPSILON * v[1]) : PETSC_MAX_REAL;
  if (c->friction && v[2] > 0) {
    /* the largest bound: s (Tresca) or F max lam (Coulomb); a state decided on round-off changes a friction force by
       at most its bound, so a bound below 1e-2 of the largest multiplier (Coulomb with F = 1e-12) is held to the
       normal multipliers' margin instead: otherwise the cap would stop a path whose friction cannot matter */
    PetscReal gb;
    PetscCall(SgContactLawBoundMax(c->law, v[0], &gb)); /* max_i g_i(max lam) */
    gb = PetscMax(gb, 1e-2 * v[0]);
    if (gb > 0) *gdp = PetscMin(*gdp, 1e-2 * gb / (c->fgfac * PETSC_MACHINE_EPSILON * v[2]));
  }
  PetscFunctionReturn(0);
}

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
    atcap = (PetscBool)(gamma_now >= 0.999 * gdp && gamma_next > gamma_now && !ct->ops.shifts);
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
static PetscErrorCode KeepBest(SgCont ct)
{
  PetscFunctionBeginUser;
  if (!PetscIsNormalReal(ct->kkt.residual) && ct->kkt.residual != 0) PetscFunctionReturn(0);
  if (ct->outerbest > 0 && !(ct->kkt.residual < ct->kktbest)) PetscFunctionReturn(0);
  if (!ct->ybest) PetscCall(VecDuplicate(ct->y, &ct->ybest));
  if (!ct->lambest) PetscCall(PetscMalloc1(ct->cv.n + 1, &ct->lambest));
  PetscCall(VecCopy(ct->y, ct->ybest));
  PetscCall(PetscArraycpy(ct->lambest, ct->lam, ct->cv.n));
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
static PetscErrorCode RestoreBest(SgCont ct)
{
  PetscFunctionBeginUser;
  if (ct->converged || ct->outerbest <= 0 || !ct->ybest || !(ct->kktbest < ct->kkt.residual || PetscIsNanReal(ct->kkt.residual))) {
    ct->outerbest = 0;
    PetscFunctionReturn(0);
  }
  PetscCall(VecCopy(ct->ybest, ct->y));
  PetscCall(PetscArraycpy(ct->lam, ct->lambest, ct->cv.n));
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
  PetscReal gamma, *lhT;
  PetscBool stop = PETSC_FALSE, ok = PETSC_TRUE;
  PetscInt  dim, outer0            = ct->outer;
  char      was[sizeof(ct->reason)];

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(was, ct->reason, sizeof(was)));
  PetscCall(SgElasticityGetDimension(ct->prob, &dim));
  PetscCall(SgSSNGetFriction(ct->ssn, &lhT, NULL, NULL));
  gamma = ct->gammas[0];
  PetscCall(PetscPrintf(ct->comm, "  %s with Coulomb friction: %.200s; solved again from the start on the shifted path (lamhat = the last multipliers, gamma doubled per step from %g)\n", ct->type, was, (double)gamma));
  PetscCall(SgSSNSetNeighbourhood(ct->ssn, 0)); /* exact solves */
  PetscCall(VecCopy(ct->ystart, ct->y));
  PetscCall(PetscArrayzero(ct->lamhat, ct->cv.n));
  PetscCall(PetscArrayzero(lhT, ct->cv.n * dim));
  ct->converged = PETSC_FALSE;
  ct->best_kkt  = PETSC_MAX_REAL;
  ct->best_step = ct->outer;
  while (ok && !stop) {
    const PetscInt   its0 = ct->ssn_its;
    const PetscReal *mT;
    ct->outer++;
    PetscCall(SgContSSN(ct, gamma, &ok));
    PetscCall(SgContMeasure(ct));
    PetscCall(SgContOuterRow(ct, ct->ssn_its - its0, NULL));
    PetscCall(KeepBest(ct));
    if (!ok) {
      PetscCall(AcceptFailedSSN(ct));
      break;
    }
    PetscCall(PetscArraycpy(ct->lamhat, ct->lam, ct->cv.n));
    PetscCall(SgSSNGetFriction(ct->ssn, &lhT, &mT, NULL));
    PetscCall(PetscArraycpy(lhT, mT, ct->cv.n * dim));
    gamma *= 2;
    ct->gamma = gamma;
    PetscCall(SgContCheck(ct, &stop));
  }
  PetscCall(PetscArrayzero(ct->lamhat, ct->cv.n));
  PetscCall(PetscArrayzero(lhT, ct->cv.n * dim));
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
static PetscErrorCode SolveContinuation(SgCont ct)
{
  PetscBool       stop = PETSC_FALSE, ok, ssnfail = PETSC_FALSE;
  const PetscBool shifted = (PetscBool)(ct->c && ct->cv.coupled && ct->coulomb_shifted && !ct->ops.shifts && !ct->restarted && (!strcmp(ct->type, SGCONTPF) || !strcmp(ct->type, SGCONTIPF)));

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
    PetscCall(KeepBest(ct));
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
  PetscCall(RestoreBest(ct));
  if (ct->ops.finish) PetscCall(ct->ops.finish(ct));
  PetscFunctionReturn(0);
}

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
    if (ct->gamma >= 0.999 * gdp) ct->gamma = 1e-3 * gdp;
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
    r->force   = ct->kkt.force;
    r->nactive = ct->kkt.nactive;
    if (ct->cv.friction) {
      r->nstick            = ct->fsum.nstick;
      r->nslip             = ct->fsum.nslip;
      r->friction_force    = ct->fsum.force_norm;
      r->friction_traction = ct->fsum.traction;
    }
  }
  if (ct->store_steps) {
    PetscCall(VecDuplicate(ct->y, &ct->ysteps[ct->nsteps]));
    PetscCall(VecCopy(ct->y, ct->ysteps[ct->nsteps]));
    PetscCall(PetscMalloc1(ct->cv.n + 1, &ct->lamsteps[ct->nsteps]));
    PetscCall(PetscArraycpy(ct->lamsteps[ct->nsteps], ct->lam, ct->cv.n));
    if (ct->yref) { /* the step's slip reference, for its slip field */
      PetscInt dim;
      PetscCall(SgElasticityGetDimension(ct->prob, &dim));
      if (!ct->yrsteps) PetscCall(PetscCalloc1(ct->capsteps, &ct->yrsteps));
      PetscCall(PetscMalloc1(2 * ct->cv.n * dim + 1, &ct->yrsteps[ct->nsteps])); /* of the unknowns, then of the full displacement */
      PetscCall(PetscArraycpy(ct->yrsteps[ct->nsteps], ct->yref, 2 * ct->cv.n * dim));
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
  if (ct->converged && !ct->cv.friction && !strcmp(ct->problem, "P")) {
    PetscReal dmin = PETSC_MAX_REAL, V0, margin;
    PetscInt  ndofs;
    for (PetscInt i = 0; i < ct->cv.n; i++) dmin = PetscMin(dmin, ct->cv.d[i]);
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
    PetscCall(PetscArraycpy(ct->yref, yref, 2 * ct->cv.n * dim)); /* this controller's */
  }
  PetscCall(SgContUseSlipReference(ct)); /* this controller's, not the last one's that solved the problem */
  /* nested iteration: the first solve starts from the coarse levels' solution (a coarse level's controller from the
     level below it, set by SgContNestedStart of the finest) like a warm load step, slip reference and all kept */
  if (ct->nested && !ct->warm && !ct->restarted && !ct->have_state) PetscCall(SgContNestedStart(ct));
  if (ct->nested_start) ct->warm = PETSC_TRUE;
  if (ct->warm) PetscCall(PrepareWarm(ct));
  if (ct->ops.solve) PetscCall(ct->ops.solve(ct));
  else PetscCall(SolveContinuation(ct));
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

/* The word for the end of a run: a solve of (P) converged, one (P_gamma) solved, or failed. */
const char *SgContVerdict(SgCont ct)
{
  if (!ct->converged) return "FAILED";
  return strcmp(ct->problem, "P_gamma") ? "CONVERGED" : "SOLVED (P_gamma)";
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
