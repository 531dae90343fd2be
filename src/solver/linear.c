/* solver/linear.c: the default linear solver, chosen from the problem when the options name none.
   A problem file alone must solve: PETSc's own default (GMRES + ILU(0)) does not converge on elasticity of any size
   worth solving. Without -<prefix>ksp_type and -<prefix>pc_type the solver is an exact sparse Cholesky factorization
   (MUMPS) for problems up to -cont_direct_max_unknowns unknowns, and CG + BoomerAMG with the settings of
   options/solver/hypre_l1gs.opts (relative tolerance 1e-8) above. The default threshold is measured
   (bench/perf_notes.md, "Default controller and linear solver"; contact solves with the default controller):
     2D, one rank: the factorization condensed onto the contact dofs (-ssn_condense) wins at every size measured (to
               6.2e5 unknowns); several ranks (no condensation there): plain MUMPS against CG + BoomerAMG crosses at
               about 2e4 unknowns;
     3D: with the truncated multigrid in the SSN steps, CG + BoomerAMG ties condensed MUMPS at 2,733 unknowns and
               takes 0.5-0.6x its time at 17,307 (3 interleaved rounds), so MUMPS is kept up to 5,000.
   The default is set on the objects (SgLinearSolverSetDefault: KSPSetType, PCSetType, PCFactorSetMatSolverType,
   KSPSetTolerances; the SSN's through SgSSNSetCondense/SgSSNSetTruncatedMG) before their SetFromOptions, so that every
   -ksp_* / -pc_* / -ssn_* option or options file still wins and nothing stays in PETSc's options database: a program
   that solves two problems gets each one's own default. */
#include "sg.h"
#include <petscsf.h>

/* condensation keeps a dense Schur complement on the contact dofs: not beyond this many of them */
#define SG_CONDENSE_MAX_DOFS 4000

static PetscErrorCode DirectMaxOption(PetscOptionItems *PetscOptionsObject, PetscInt *maxdirect)
{
  PetscFunctionBeginUser;
  PetscCall(SgOptionsIntValue(PetscOptionsObject, "-cont_direct_max_unknowns", "Without -ksp_type and -pc_type: problems up to this many unknowns are solved with MUMPS, larger ones with CG + BoomerAMG (default: 2D: all on one rank, 20000 on several and for two bodies without friction; 3D: 5000)", maxdirect, NULL));
  PetscFunctionReturn(0);
}

/* BoomerAMG's settings of the default (options/solver/hypre_l1gs.opts). PETSc 3.18's PCHYPRE has no setters for
   them: it reads them in PCSetFromOptions only, from the PC's options database. They are entered into the global
   database (where the user gave no value) for the one SetFromOptions that configures the KSP and taken out right after
   it (SgLinearSolverEndDefault); the PC keeps them, a later SetFromOptions (the SSN's SNES reads its KSP's options
   again) keeps what it finds set. An options object of the KSP's own (PetscObjectSetOptions) would replace the global
   database for it, not add to it: the user's -pc_hypre_* options would no longer reach the PC. */
static const char *const AMGDefaults[][2] = {
    {"pc_hypre_boomeramg_strong_threshold",                      "0.5"},
    {    "pc_hypre_boomeramg_coarsen_type",                     "HMIS"},
    {     "pc_hypre_boomeramg_interp_type",                    "ext+i"},
    {           "pc_hypre_boomeramg_P_max",                        "4"},
    {          "pc_hypre_boomeramg_agg_nl",                        "1"},
    { "pc_hypre_boomeramg_relax_type_down",          "l1-Gauss-Seidel"},
    {   "pc_hypre_boomeramg_relax_type_up", "backward-l1-Gauss-Seidel"}
};
#define SG_NAMG SG_LINEAR_DEFAULT_NAMG
_Static_assert(sizeof(AMGDefaults) / sizeof(AMGDefaults[0]) == SG_LINEAR_DEFAULT_NAMG, "SG_LINEAR_DEFAULT_NAMG");

/* The default def (none unless def->on) set on ksp before its SetFromOptions (or that of the SNES holding it);
   entered[SG_NAMG]: which BoomerAMG settings were entered into the options database for it (SgLinearSolverEndDefault
   takes them out). */
PetscErrorCode SgLinearSolverSetDefault(KSP ksp, const SgLinearDefault *def, PetscBool entered[])
{
  PC          pc;
  const char *prefix;

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < SG_NAMG; k++) entered[k] = PETSC_FALSE;
  if (!def || !def->on) PetscFunctionReturn(0);
  PetscCall(KSPGetOptionsPrefix(ksp, &prefix));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(KSPSetType(ksp, def->ksp));
  PetscCall(PCSetType(pc, def->pc));
  if (def->mumps) PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  if (!def->amg) PetscFunctionReturn(0);
  PetscCall(KSPSetTolerances(ksp, 1e-8, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT));
  for (PetscInt k = 0; k < SG_NAMG; k++) { /* BoomerAMG is PCHYPRE's default type (-pc_hypre_type still wins) */
    char      opt[256];
    PetscBool set;
    PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s%s", prefix ? prefix : "", AMGDefaults[k][0]));
    PetscCall(PetscOptionsHasName(NULL, NULL, opt, &set));
    if (!set) PetscCall(PetscOptionsSetValue(NULL, opt, AMGDefaults[k][1]));
    entered[k] = (PetscBool)!set;
  }
  PetscFunctionReturn(0);
}

/* After that SetFromOptions (also after its error): the settings entered for it taken out of the options database */
PetscErrorCode SgLinearSolverEndDefault(KSP ksp, const SgLinearDefault *def, PetscBool entered[])
{
  const char *prefix;

  PetscFunctionBeginUser;
  if (!def || !def->on || !def->amg) PetscFunctionReturn(0);
  PetscCall(KSPGetOptionsPrefix(ksp, &prefix));
  for (PetscInt k = 0; k < SG_NAMG; k++) {
    char opt[256];
    if (!entered[k]) continue;
    PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s%s", prefix ? prefix : "", AMGDefaults[k][0]));
    PetscCall(PetscOptionsClearValue(NULL, opt));
    entered[k] = PETSC_FALSE;
  }
  PetscFunctionReturn(0);
}

/* -<prefix>ssn_pc_truncated_mg_interp given (set) and geometric (the geometric multigrid, gmg.c; a bad value is
   reported by the SSN's reader) */
static PetscErrorCode InterpOption(const char prefix[], PetscBool *set, PetscBool *geo)
{
  const char *const list[] = {"amg", "geometric"};
  char              opt[256];
  PetscInt          v = 0;

  PetscFunctionBeginUser;
  *set = PETSC_FALSE;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%sssn_pc_truncated_mg_interp", prefix ? prefix : ""));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  if (PetscOptionsGetEList(NULL, NULL, opt, list, 2, &v, set)) *set = PETSC_FALSE;
  PetscCall(PetscPopErrorHandler());
  *geo = (PetscBool)(*set && v == 1);
  PetscFunctionReturn(0);
}

/* -<prefix>ssn_pc_truncated_mg_interp geometric given */
PetscErrorCode SgLinearSolverGeometricMG(const char prefix[], PetscBool *geo)
{
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(InterpOption(prefix, &set, geo));
  PetscFunctionReturn(0);
}

/* The largest coarsest level (unknowns, 3D) of the default geometric multigrid (DefaultGeometricMG) */
#define SG_GMG_COARSE_MAX_3D 50000
static PetscErrorCode GeometricMaxOption(PetscOptionItems *PetscOptionsObject, PetscInt *max)
{
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(SgOptionsIntValue(PetscOptionsObject, "-ssn_pc_truncated_mg_geometric_max_coarse", "3D, -dm_refine N with nested iteration's levels: the SSN steps of the iterative default use the geometric multigrid of the levels only if the unrefined mesh (its coarsest level, factored for every active set) has at most this many unknowns (3 x its vertices, Dirichlet ones included), otherwise BoomerAMG's truncated multigrid", max, &set));
  PetscCheck(!set || *max >= 0, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "-ssn_pc_truncated_mg_geometric_max_coarse: must be >= 0 (unknowns of the coarsest level), got %" PetscInt_FMT, *max);
  PetscFunctionReturn(0);
}

/* -help without a problem: the option of the default linear solver (SgLinearSolverDefaults reads it) */
PetscErrorCode SgLinearSolverPrintHelp(MPI_Comm comm, const char prefix[])
{
  PetscBool help;
  PetscInt  maxdirect = 5000;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  if (!help) PetscFunctionReturn(0);
  PetscInt geomax = SG_GMG_COARSE_MAX_3D;
  PetscOptionsBegin(comm, prefix, "Default linear solver", NULL);
  PetscCall(DirectMaxOption(PetscOptionsObject, &maxdirect));
  PetscCall(GeometricMaxOption(PetscOptionsObject, &geomax));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

/* The default solver def (def->on) unless -<prefix>ksp_type or -<prefix>pc_type is given; iterative: the solver that will run is a Krylov method with a preconditioner (not preonly: the
   controller's default depends on it); desc says what was chosen and why (for the run's first lines). */
PetscErrorCode SgLinearSolverDefaults(SgElasticity el, const char prefix[], PetscBool nonsym, PetscBool pair, SgLinearDefault *def, PetscBool *iterative, char desc[], size_t len)
{
  char        opt[256], ktype[64] = "";
  PetscBool   kset, pset;
  PetscInt    dim, dofs, maxdirect;
  PetscMPIInt size;
  MPI_Comm    comm;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(def, sizeof(*def)));
  PetscCall(SgElasticityGetComm(el, &comm));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(SgElasticityGetDimension(el, &dim));
  PetscCall(SgElasticityGetInfo(el, &dofs, NULL, NULL, NULL));
  maxdirect = dim == 2 ? (size == 1 ? PETSC_MAX_INT : 20000) : 5000;
  /* two bodies: MUMPS at every size; CG + BoomerAMG on K + gamma B^T diag(act / D) B takes many more SSN steps on the
     flat pair (33 against 3) and does not converge on a curved 3D one (the sphere on a block from 4.4e3 unknowns on,
     bench/results.md "Two bodies") */
  if (pair) { /* ... unless the SSN solves in the dual-mortar basis (-ssn_pair_transform, on unless turned off: frame.c),
                 where every pair condition is nodal: then the one-body limits, except 2D on one rank: one body's
                 unlimited MUMPS there rests on the condensation onto the contact dofs, which a pair has not (every SSN
                 step factors K), so the limit of several ranks (no condensation either): the two cylinders at 32,700,
                 129,752 and 516,912 unknowns took 0.6-0.8x, 0.4x and 0.35-0.45x the CPU time of MUMPS in CG +
                 BoomerAMG with nested iteration (-dm_refine), 3-5 SSN steps against 7-9 (bench/results.md, pair4) */
    PetscBool tx, limited;
    PetscCall(SgOptionsPairDirectLimit2D(prefix, &tx, &limited)); /* limited: frictionless (friction: unmeasured, one body's rule, MUMPS) */
    if (!tx) maxdirect = PETSC_MAX_INT;
    else if (dim == 2 && size == 1 && limited) maxdirect = SG_PAIR_DIRECT_MAX_2D;
  }
  PetscOptionsBegin(comm, prefix, "Default linear solver", NULL);
  PetscCall(DirectMaxOption(PetscOptionsObject, &maxdirect));
  PetscOptionsEnd();
  PetscCheck(maxdirect >= 0, comm, PETSC_ERR_USER_INPUT, "-%scont_direct_max_unknowns: must be >= 0, got %" PetscInt_FMT, prefix ? prefix : "", maxdirect);
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%sksp_type", prefix ? prefix : ""));
  PetscCall(PetscOptionsHasName(NULL, NULL, opt, &kset));
  if (kset) PetscCall(PetscOptionsGetString(NULL, NULL, opt, ktype, sizeof(ktype), NULL));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%spc_type", prefix ? prefix : ""));
  PetscCall(PetscOptionsHasName(NULL, NULL, opt, &pset));
  def->on = (PetscBool) !(kset || pset);
  if (!def->on) {
    *iterative = (PetscBool)strcmp(ktype, KSPPREONLY); /* PETSc's default Krylov method is GMRES */
    if (nonsym) {                                      /* Coulomb friction: the SSN's matrices are nonsymmetric */
      char ptype[64] = "";
      PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%spc_type", prefix ? prefix : ""));
      if (pset) PetscCall(PetscOptionsGetString(NULL, NULL, opt, ptype, sizeof(ptype), NULL));
      PetscCheck(strcmp(ktype, KSPCG) && strcmp(ptype, PCCHOLESKY) && strcmp(ptype, PCICC), comm, PETSC_ERR_USER_INPUT, "-%sksp_type %s -%spc_type %s: Coulomb friction (-friction_type coulomb) makes the Jacobians nonsymmetric: use e.g. -pc_type lu or -ksp_type gmres", prefix ? prefix : "", kset ? ktype : "(default)", prefix ? prefix : "", pset ? ptype : "(default)");
    }
    PetscCall(PetscSNPrintf(desc, len, "from the options"));
    PetscFunctionReturn(0);
  }
  /* the user's SSN solver options decide where they need one kind: -ssn_condense a factorization, and
     -ssn_pc_truncated_mg an AMG */
  {
    PetscBool condense = PETSC_FALSE, tmg = PETSC_FALSE;
    PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%sssn_condense", prefix ? prefix : ""));
    PetscCall(PetscOptionsGetBool(NULL, NULL, opt, &condense, NULL));
    PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%sssn_pc_truncated_mg", prefix ? prefix : ""));
    PetscCall(PetscOptionsGetBool(NULL, NULL, opt, &tmg, NULL));
    if (!tmg) PetscCall(SgLinearSolverGeometricMG(prefix, &tmg)); /* the truncated multigrid on the mesh hierarchy */
    if (condense || tmg) maxdirect = condense ? PETSC_MAX_INT - 1 : 0;
  }
  *iterative = (PetscBool)(dofs > maxdirect);
  if (!*iterative && nonsym) { /* Coulomb friction: nonsymmetric Jacobians */
    def->ksp   = KSPPREONLY;
    def->pc    = PCLU;
    def->mumps = PETSC_TRUE;
    if (maxdirect == PETSC_MAX_INT) PetscCall(PetscSNPrintf(desc, len, "default for %" PetscInt_FMT "D on one rank with Coulomb friction (nonsymmetric Jacobians): sparse LU (MUMPS)", dim));
    else PetscCall(PetscSNPrintf(desc, len, "default up to %" PetscInt_FMT " unknowns (-cont_direct_max_unknowns) with Coulomb friction (nonsymmetric Jacobians): sparse LU (MUMPS)", maxdirect));
  } else if (!*iterative) {
    def->ksp   = KSPPREONLY;
    def->pc    = PCCHOLESKY;
    def->mumps = PETSC_TRUE;
    if (maxdirect == PETSC_MAX_INT) PetscCall(PetscSNPrintf(desc, len, "default for %" PetscInt_FMT "D on one rank: sparse Cholesky (MUMPS)", dim));
    else if (maxdirect == PETSC_MAX_INT - 1) PetscCall(PetscSNPrintf(desc, len, "default with -ssn_condense: sparse Cholesky (MUMPS)"));
    else PetscCall(PetscSNPrintf(desc, len, "default up to %" PetscInt_FMT " unknowns (-cont_direct_max_unknowns): sparse Cholesky (MUMPS)", maxdirect));
  } else {
    def->ksp = nonsym ? KSPBCGS : KSPCG;
    def->pc  = PCHYPRE;
    def->amg = PETSC_TRUE;
    PetscCall(PetscSNPrintf(desc, len, "default above %" PetscInt_FMT " unknowns (-cont_direct_max_unknowns%s): %s + BoomerAMG (options/solver/hypre_l1gs.opts)", maxdirect, maxdirect ? "" : " or -ssn_pc_truncated_mg", nonsym ? "BiCGStab (Coulomb friction: nonsymmetric)" : "CG"));
  }
  if (pair && !*iterative && maxdirect == PETSC_MAX_INT) PetscCall(PetscSNPrintf(desc, len, "default for two bodies (-contact_master_ids) at any size (-cont_direct_max_unknowns changes it): sparse %s (MUMPS)", nonsym ? "LU" : "Cholesky"));
  PetscFunctionReturn(0);
}

/* A default SSN option that is on unless given: PETSC_TRUE if it is on (the user may have said false). */
static PetscErrorCode SetDefaultSSN(const char prefix[], const char name[], PetscBool *on)
{
  char opt[256];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s%s", prefix ? prefix : "", name));
  *on = PETSC_TRUE;
  PetscCall(PetscOptionsGetBool(NULL, NULL, opt, on, NULL));
  PetscFunctionReturn(0);
}

/* The truncated multigrid's interpolations: the mesh hierarchy's (-ssn_pc_truncated_mg_interp geometric) when the
   mesh kept every level of -dm_refine (fem/mesh.c: nested iteration's default or -cont_nested N = -dm_refine), unless
   the option is given. Ex2 at 144,666 unknowns: 0.5x the CG iterations of BoomerAMG's, no AMG setup; with nested
   iteration 3 SSN / 26 CG on the finest level against 3 / 51 (bench/nested.md). Not in 3D where the coarsest level
   (the unrefined mesh) has more unknowns than -ssn_pc_truncated_mg_geometric_max_coarse (*ncoarse: its unknowns, dim x
   its vertices, Dirichlet ones included; 0 if not counted): gmg.c factors it for every active set, and a 3D factorization grows like the square of the unknowns
   (the quarter hemisphere of 119,904 unknowns refined once: 10-40 s per SSN step in the factorization, the contact
   solve 1.5-2x the AMG's, bench/results.md); BoomerAMG's truncated multigrid then, nested iteration unchanged. */
static PetscErrorCode DefaultGeometricMG(SgElasticity el, const char prefix[], PetscBool *geo, PetscInt *ncoarse)
{
  DM          dm;
  PetscObject lv = (PetscObject)NULL, base = NULL;
  char        name[64];
  PetscBool   set;
  PetscInt    max = SG_GMG_COARSE_MAX_3D;

  PetscFunctionBeginUser;
  *ncoarse = 0;
  PetscCall(SgElasticityGetDMs(el, &dm, NULL, NULL, NULL));
  PetscOptionsBegin(PetscObjectComm((PetscObject)dm), prefix, "Default linear solver", NULL);
  PetscCall(GeometricMaxOption(PetscOptionsObject, &max));
  PetscOptionsEnd();
  PetscCall(InterpOption(prefix, &set, geo));
  if (set) PetscFunctionReturn(0);
  for (PetscInt k = 1;; k++) { /* the coarsest level kept */
    PetscObject q = NULL;
    PetscCall(PetscSNPrintf(name, sizeof(name), "SgNestedLevel%" PetscInt_FMT, k));
    PetscCall(PetscObjectQuery((PetscObject)dm, name, &q));
    if (!q) break;
    lv = q;
  }
  if (lv) PetscCall(PetscObjectQuery(lv, "SgNestedBase", &base));
  *geo = (PetscBool)(base != NULL);
  if (*geo) {
    PetscInt        dim, pS, pE, n, nleaves;
    const PetscInt *ilocal;
    PetscSF         sf;
    PetscCall(DMGetDimension((DM)lv, &dim));
    PetscCall(DMPlexGetDepthStratum((DM)lv, 0, &pS, &pE)); /* this rank's vertices, less those another rank owns */
    PetscCall(DMGetPointSF((DM)lv, &sf));
    PetscCall(PetscSFGetGraph(sf, NULL, &nleaves, &ilocal, NULL));
    n = pE - pS;
    for (PetscInt l = 0; l < PetscMax(nleaves, 0); l++) {
      const PetscInt p = ilocal ? ilocal[l] : l;
      if (p >= pS && p < pE) n--;
    }
    n *= dim;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPIU_INT, MPI_SUM, PetscObjectComm(lv)));
    *ncoarse = n;
    if (dim == 3 && n > max) {
      *geo = PETSC_FALSE;
      PetscCall(PetscInfo(dm, "geometric multigrid not the default: its coarsest level has %" PetscInt_FMT " unknowns (> %" PetscInt_FMT ")\n", n, max));
    }
  }
  PetscFunctionReturn(0);
}

/* The SSN's part of the default solver, for a controller that runs the SSN:
   - direct, one rank: the steps condensed onto the contact dofs (-ssn_condense: K factored once), unless the dense
     Schur complement would be large;
   - iterative (BoomerAMG): the truncated multigrid (-ssn_pc_truncated_mg, tmg.c: one AMG setup on K, no new one per
     active set; 0.61x the contact solve's time of a BoomerAMG setup per set on 124,128 unknowns, bench/perf_notes.md
     part D) where the contact normals are coordinate axes, which it needs. */
PetscErrorCode SgLinearSolverDefaultSSN(SgElasticity el, SgContact c, const char prefix[], PetscBool iterative, SgLinearDefault *def, char desc[], size_t len)
{
  PetscMPIInt   size;
  MPI_Comm      comm;
  SgContactView cv;
  PetscInt      dim, ncond, nglobal;
  PetscBool     aligned = PETSC_FALSE, on;
  size_t        n;

  PetscFunctionBeginUser;
  if (!c) PetscFunctionReturn(0);
  PetscCall(SgContactGetView(c, &cv));
  if (cv.props.nonlinear) PetscFunctionReturn(0); /* neither condensation nor the truncated multigrid is built for friction */
  PetscCall(SgContactIsPair(c, &on));
  if (on) { /* nor for two bodies (a condition couples both sides); iterative: the SSN's dual-mortar basis (ssn.c) */
    char      opt[256];
    PetscBool tx = PETSC_TRUE;
    PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%sssn_pair_transform", prefix ? prefix : ""));
    PetscCall(PetscOptionsGetBool(NULL, NULL, opt, &tx, NULL));
    if (!iterative || !tx) PetscFunctionReturn(0);
    /* there every pair condition is nodal: the truncated multigrid applies (sphere on a block, 117,693 unknowns:
       4 SSN steps and 37 s against 7 and 72 s with a BoomerAMG setup per step, bench/results.md "Two bodies") */
    PetscCall(SetDefaultSSN(prefix, "ssn_pc_truncated_mg", &on));
    def->tmg = on;
    if (on) { /* the mesh hierarchy's interpolations where the mesh kept its levels, as for one body (gmg.c maps the
                 finest one into the pair's basis) */
      PetscInt ncoarse;
      PetscCall(DefaultGeometricMG(el, prefix, &def->geometric, &ncoarse));
    }
    PetscCall(PetscStrlen(desc, &n));
    PetscCall(PetscSNPrintf(desc + n, len - n, ", the SSN steps in the pair's dual-mortar basis (-ssn_pair_transform)%s", !on ? "" : def->geometric ? " preconditioned by the geometric multigrid of the mesh hierarchy truncated at the active set (-ssn_pc_truncated_mg_interp geometric)"
                                                                                                                                                    : " preconditioned by its multigrid kept from one setup and truncated at the active set (-ssn_pc_truncated_mg)"));
    PetscFunctionReturn(0);
  }
  PetscCall(SgElasticityGetComm(el, &comm));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(SgElasticityGetDimension(el, &dim));
  PetscCall(SgContactNormalsAxisAligned(c, &aligned));
  if (!aligned) { /* the contact frames (-ssn_frame, on unless turned off) make every normal an axis of its frame */
    char      opt[256];
    PetscBool frame = PETSC_TRUE;
    PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%sssn_frame", prefix ? prefix : ""));
    PetscCall(PetscOptionsGetBool(NULL, NULL, opt, &frame, NULL));
    aligned = frame;
  }
  PetscCall(PetscStrlen(desc, &n));
  if (iterative) {
    if (!aligned) PetscFunctionReturn(0);
    PetscCall(SetDefaultSSN(prefix, "ssn_pc_truncated_mg", &on));
    def->tmg = on;
    if (on) {
      PetscBool geo = PETSC_FALSE;
      PetscInt  ncoarse;
      PetscCall(DefaultGeometricMG(el, prefix, &geo, &ncoarse));
      def->geometric = geo;
      if (geo) PetscCall(PetscSNPrintf(desc + n, len - n, ", the SSN steps preconditioned by the geometric multigrid of the mesh hierarchy truncated at the active set (-ssn_pc_truncated_mg_interp geometric)"));
      else if (ncoarse) PetscCall(PetscSNPrintf(desc + n, len - n, ", the SSN steps preconditioned by its multigrid truncated at the active set (-ssn_pc_truncated_mg; coarsest mesh: %" PetscInt_FMT " vertices)", ncoarse / 3));
      else PetscCall(PetscSNPrintf(desc + n, len - n, ", the SSN steps preconditioned by its multigrid kept from one setup and truncated at the active set (-ssn_pc_truncated_mg)"));
    }
    PetscFunctionReturn(0);
  }
  PetscCall(SgContactGetVertices(c, NULL, &nglobal, NULL, NULL));
  ncond = nglobal * (aligned ? 1 : dim); /* axis-aligned normals condense one component (condense.c) */
  if (size > 1 || ncond > SG_CONDENSE_MAX_DOFS) PetscFunctionReturn(0);
  PetscCall(SetDefaultSSN(prefix, "ssn_condense", &on));
  def->condense = on;
  if (on) PetscCall(PetscSNPrintf(desc + n, len - n, ", the SSN steps condensed onto the %" PetscInt_FMT " contact dofs (-ssn_condense)", ncond));
  PetscFunctionReturn(0);
}
