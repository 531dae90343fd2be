/* cont/cont_options.c: the options of SgCont: those every controller has, the type's own under its heading, -help
   for every registered type (SgContPrintHelp), and SgContSetFromOptions, which chooses the default type. */
#include "cont/contimpl.h"

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
  PetscCall(SgOptionsFileName(PetscOptionsObject, "-checkpoint_file", "HDF5 file with the continuation state, rewritten after every outer step", ct->ckfile, sizeof(ct->ckfile), NULL));
  PetscCall(SgOptionsFileName(PetscOptionsObject, "-restart_file", "Resume from a checkpoint (a continuation controller: alm, pf, ipf; any number of ranks)", ct->rsfile, sizeof(ct->rsfile), NULL));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-cont_monitor", "Print a line per outer step (gamma, SSN and KSP iterations, active set, KKT residual, time)", &ct->monitor, NULL));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-cont_coulomb_shifted_path", "Coulomb friction: when a regularized solve of pf or ipf fails, or the tolerance lies below the double-precision cap of gamma (PRECISION_LIMIT), solve again from the start on the shifted path (the augmented Lagrangian steps of alm, gamma doubled per step)", &ct->coulomb_shifted, NULL));
  PetscCall(SgOptionsIntValue(PetscOptionsObject, "-cont_stall_it", "Stop with STALLED after this many outer steps without progress in the KKT residual", &ct->stall_its, NULL));
  if (!ct->nested_inner) {
    PetscBool set;
    PetscCall(SgOptionsIntValue(PetscOptionsObject, "-cont_nested", "Nested iteration: solve first on the mesh refined this many times fewer (needs -dm_refine >= it), then on each finer one from the interpolated solution, multiplier shift and gamma (0: off; default with -dm_refine N >= 1 and a contact boundary (one body or a pair), in 3D without friction and in 2D with friction or an iterative linear solver: N, and with an iterative default solver the SSN steps preconditioned by the geometric multigrid of the levels)", &ct->nested, &set));
    if (set) ct->nested_default = PETSC_FALSE;
  }
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-cont_nested_rim", "Nested iteration: a finer level's first active set also takes the contact vertices whose interpolated multiplier outweighs this factor times their normal stiffness per area (n^T K_ii n / w_i) times their gap on the finer mesh (the rim of the coarse contact zone placed on the finer mesh; 0: only the interpolated displacement's penetration)", &ct->nested_rim, NULL));
  PetscCheck(ct->nested_rim >= 0, ct->comm, PETSC_ERR_USER_INPUT, "-cont_nested_rim: must be >= 0 (0: off), got %g", (double)ct->nested_rim);
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
  if (ct->c) {
    PetscCall(SgContactGetView(ct->c, &ct->cv));
    PetscCall(SgContactGetVertices(ct->c, &ct->n, &ct->nglobal, &ct->vert, &ct->off));
    PetscCall(SgContactGetWeights(ct->c, &ct->w));
    PetscCall(SgContactGetNormals(ct->c, &ct->normal));
    PetscCall(SgContactGetGaps(ct->c, &ct->d));
    PetscCall(SgContactGetArea(ct->c, &ct->area));
  }
  ct->problem = ct->c ? "P" : "elasticity";
  /* the default solves the problem given: the contact problem (P) with the default controller, or the elasticity
     problem alone (none) without a contact boundary */
  /* the linear solver first (its default depends on the problem's size), then the controller's default from it:
     fast (one capped (P_gamma), inexact steps) in 3D and for iterative solves, ipf in 2D with exact solves, where fast
     can take many more steps (nearly incompressible: 31 against 18; bench/perf_notes.md) */
  {
    PetscBool pair = PETSC_FALSE;
    if (ct->c) PetscCall(SgContactIsPair(ct->c, &pair));
    if (ct->lin_inherited) { /* a coarse level of -cont_nested: the finest level's default, SSN settings included */
      iterative = (PetscBool)strcmp(ct->lin.ksp, KSPPREONLY);
      PetscCall(PetscSNPrintf(ct->solver_desc, sizeof(ct->solver_desc), "the finest level's default (-cont_nested)"));
    } else PetscCall(SgLinearSolverDefaults(ct->prob, ((PetscObject)ct)->prefix, (PetscBool)(ct->c && ct->cv.props.coupled), pair, &ct->lin, &iterative, ct->solver_desc, sizeof(ct->solver_desc)));
    solver_default = (PetscBool)(ct->lin.on && !ct->lin_inherited);
  }
  PetscCall(SgElasticityGetDimension(ct->prob, &dim));
  ct->type_default = (PetscBool)!ct->type[0];
  /* fast is not built for friction: ipf there */
  if (ct->type_default) PetscCall(PetscStrcpy(ct->type, !ct->c ? SGCONTNONE : ((dim == 3 || iterative) && !ct->cv.props.nonlinear ? SGCONTFAST : SGCONTIPF)));
  PetscCall(SgContNestedDefault(ct, iterative));
  PetscObjectOptionsBegin((PetscObject)ct);
  PetscCall(CommonOptions(ct, PetscOptionsObject));
  PetscCall(PetscFunctionListFind(SgContList, ct->type, &create));
  PetscCheck(create, ct->comm, PETSC_ERR_USER_INPUT, "-cont_type: unknown controller '%s' (see -help for the list)", ct->type);
  ct->ops.needs_ssn = PETSC_TRUE;
  PetscCall(create(ct));
  PetscCall(PetscObjectChangeTypeName((PetscObject)ct, ct->type));
  /* the SSN's defaults before the type's options: fast's -cont_fast_ksp_loose follows the geometric multigrid */
  if (solver_default && ct->ops.needs_ssn) PetscCall(SgLinearSolverDefaultSSN(ct->prob, ct->c, ((PetscObject)ct)->prefix, iterative, &ct->lin, ct->solver_desc, sizeof(ct->solver_desc)));
  PetscCall(TypeOptions(ct, PetscOptionsObject));
  PetscCall(HelpTypes(ct, ct->type, PetscOptionsObject));
  PetscOptionsEnd();
  PetscCheck(PetscIsNormalReal(ct->kkt_tol) && ct->kkt_tol > 0, ct->comm, PETSC_ERR_USER_INPUT, "-cont_kkt_tol: must be positive and finite, got %g", (double)ct->kkt_tol);
  PetscCheck(ct->max_outer > 0, ct->comm, PETSC_ERR_USER_INPUT, "-cont_max_it: must be positive, got %" PetscInt_FMT, ct->max_outer);
  PetscCheck(PetscIsNormalReal(ct->gamma_max) && ct->gamma_max > 0, ct->comm, PETSC_ERR_USER_INPUT, "-cont_gamma_max: must be positive and finite, got %g", (double)ct->gamma_max);
  PetscCheck(ct->stall_its > 0, ct->comm, PETSC_ERR_USER_INPUT, "-cont_stall_it: must be positive, got %" PetscInt_FMT, ct->stall_its);
  if (ct->c && ct->cv.props.nonlinear) {
    /* the controllers that drive the SSN of (P_gamma) with friction: none, alm, pf, ipf */
    PetscCheck(strcmp(ct->type, SGCONTFAST) && strcmp(ct->type, SGCONTVI), ct->comm, PETSC_ERR_SUP, "-cont_type %s is not built for friction (-friction_type %s) yet: use none, alm, pf, ipf or the baseline pdas", ct->type, SgLawName(ct->cv.law));
  }
  PetscCheck(ct->c || !strcmp(ct->type, SGCONTNONE), ct->comm, PETSC_ERR_USER_INPUT, "-cont_type %s needs a contact boundary: give -contact_label and/or -contact_ids", ct->type);
  PetscCall(SgFileCheckWritable(ct->comm, "-checkpoint_file", ct->ckfile));
  PetscCall(SgContNestedCheck(ct));
  ct->setup_failed          = PETSC_FALSE;
  ct->setfromoptions_called = PETSC_TRUE;
  PetscFunctionReturn(0);
}
