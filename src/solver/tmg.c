/* tmg.c: truncated multigrid (-ssn_pc_truncated_mg), a preconditioner for the SSN's Jacobians
   J = K + gamma sum_{A} w_i n_i n_i^T that follows the active set A without a new AMG setup (truncated nonsmooth
   Newton multigrid, Graeser and Kornhuber). The configured AMG (the KSP's own -pc_type: BoomerAMG or GAMG) is set
   up once, on the first operator (K, in the unconstrained start solve); its interpolations P_l are kept. For each
   Jacobian, the finest level is J itself (its smoother sees gamma), the finest interpolation is truncated at the
   active normal dofs (their rows of P set to zero: coarse corrections leave the normal displacement of an active
   vertex to the smoother, where gamma fixes it), and the coarse operators are recomputed by Galerkin products
   P^T A P (PCMG). With the truncation the gamma block drops out of the coarse operators: P_t^T J P_t = P_t^T K P_t.
   Normals must be axis-aligned (a zero row then is the projection (I - n n^T) of the row block). */
#include "solver/ssnimpl.h"

struct _n_SgTMG {
  SgSSN          ssn;
  PC             amg;     /* the configured AMG, set up once; destroyed after its interpolations are taken */
  PC             mg;      /* PCMG on the interpolations, Galerkin coarse operators */
  Mat            P0, Pt;  /* the finest interpolation and its truncated copy (held by mg) */
  PetscInt       nlevels;
  PetscInt      *axis;    /* normal axis of each contact vertex */
  PetscReal     *sign;
  char          *want;    /* the active set of the last Jacobian (SgTMGSetActiveSet) */
  char          *have;    /* the set Pt is truncated for */
  PetscBool      truncate, has_set;
};

static PetscBool     tmg_registered = PETSC_FALSE;
static PetscLogEvent SG_TMGBuild, SG_TMGUpdate;

/* The first set-up: the AMG on the operator, its interpolations into a PCMG with Galerkin coarse operators and the
   smoothers: one Gauss-Seidel sweep forward before and one backward after the coarse correction (as hypre's
   l1-Gauss-Seidel pair; -<prefix>tmg_mg_levels_* override). */
static PetscErrorCode Build(SgTMG t, Mat A, Mat B)
{
  PetscInt    n;
  Mat        *P;
  const char *prefix;
  char        mgprefix[256];

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(SG_TMGBuild, 0, 0, 0, 0));
  PetscCall(PCSetOperators(t->amg, A, B));
  PetscCall(PCSetUp(t->amg));
  PetscCall(PCGetInterpolations(t->amg, &n, &P));
  PetscCall(PCDestroy(&t->amg));
  t->nlevels = n;
  PetscCall(PCCreate(t->ssn->comm, &t->mg));
  {
    KSP ksp;
    PetscCall(SNESGetKSP(t->ssn->snes, &ksp));
    PetscCall(KSPGetOptionsPrefix(ksp, &prefix));
  }
  PetscCall(PetscSNPrintf(mgprefix, sizeof(mgprefix), "%stmg_", prefix ? prefix : ""));
  PetscCall(PCSetOptionsPrefix(t->mg, mgprefix));
  PetscCall(PCSetType(t->mg, PCMG));
  PetscCall(PCMGSetLevels(t->mg, n, NULL));
  PetscCall(PCMGSetType(t->mg, PC_MG_MULTIPLICATIVE));
  PetscCall(PCMGSetGalerkin(t->mg, PC_MG_GALERKIN_BOTH));
  t->P0 = P[n - 2];
  PetscCall(MatDuplicate(t->P0, MAT_COPY_VALUES, &t->Pt));
  PetscCall(MatSetOption(t->Pt, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE));
  for (PetscInt l = n - 1; l > 0; l--) {
    PetscCall(PCMGSetInterpolation(t->mg, l, l == n - 1 ? t->Pt : P[l - 1]));
    if (l < n - 1) PetscCall(MatDestroy(&P[l - 1]));
  }
  PetscCall(PetscFree(P));
  for (PetscInt l = 1; l < n; l++) {
    KSP sm[2];
    PC  spc;
    PetscCall(PCMGGetSmootherDown(t->mg, l, &sm[0]));
    PetscCall(PCMGGetSmootherUp(t->mg, l, &sm[1]));
    for (PetscInt k = 0; k < 2; k++) {
      PetscCall(KSPSetType(sm[k], KSPRICHARDSON));
      PetscCall(KSPSetTolerances(sm[k], PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, 1));
      PetscCall(KSPSetNormType(sm[k], KSP_NORM_NONE));
      PetscCall(KSPGetPC(sm[k], &spc));
      PetscCall(PCSetType(spc, PCSOR));
      PetscCall(PCSORSetSymmetric(spc, k == 0 ? SOR_LOCAL_FORWARD_SWEEP : SOR_LOCAL_BACKWARD_SWEEP));
    }
  }
  PetscCall(PCSetFromOptions(t->mg));
  PetscCall(PetscLogEventEnd(SG_TMGBuild, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Pt = P0 with the rows of the active normal dofs zeroed (the pattern kept, so the Galerkin products reuse their
   symbolic phase). */
static PetscErrorCode Truncate(SgTMG t)
{
  const SgContactView *c = &t->ssn->cv;
  PetscInt             rstart, nz = 0, *rows;
  PetscBool            same = PETSC_TRUE;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < c->n; i++) same = (PetscBool)(same && (t->want[i] != 0) == (t->have[i] != 0));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPIU_BOOL, MPI_LAND, t->ssn->comm));
  if (same) PetscFunctionReturn(0);
  PetscCall(MatGetOwnershipRange(t->Pt, &rstart, NULL));
  PetscCall(PetscMalloc1(c->n, &rows));
  for (PetscInt i = 0; i < c->n; i++) {
    t->have[i] = t->want[i];
    if (t->want[i]) rows[nz++] = rstart + c->off[i] + t->axis[i];
  }
  PetscCall(MatCopy(t->P0, t->Pt, SAME_NONZERO_PATTERN));
  PetscCall(MatZeroRows(t->Pt, nz, rows, 0.0, NULL, NULL));
  PetscCall(PetscFree(rows));
  PetscFunctionReturn(0);
}

static PetscErrorCode SetUp_TMG(PC pc)
{
  SgTMG t;
  Mat   A, B;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &t));
  PetscCall(PCGetOperators(pc, &A, &B));
  if (!t->mg) PetscCall(Build(t, A, B));
  PetscCall(PetscLogEventBegin(SG_TMGUpdate, 0, 0, 0, 0));
  if (t->truncate && t->has_set) PetscCall(Truncate(t));
  PetscCall(PCSetOperators(t->mg, A, B));
  PetscCall(PCSetUp(t->mg));
  PetscCall(PetscLogEventEnd(SG_TMGUpdate, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

static PetscErrorCode Apply_TMG(PC pc, Vec x, Vec y)
{
  SgTMG t;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &t));
  PetscCall(PCApply(t->mg, x, y));
  PetscFunctionReturn(0);
}

static PetscErrorCode View_TMG(PC pc, PetscViewer v)
{
  SgTMG t;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &t));
  PetscCall(PetscViewerASCIIPrintf(v, "truncated multigrid (-ssn_pc_truncated_mg): %" PetscInt_FMT " levels, interpolations of the AMG set up once%s\n", t->nlevels, t->truncate ? ", finest truncated at the active normal dofs" : ""));
  if (t->mg) {
    PetscCall(PetscViewerASCIIPushTab(v));
    PetscCall(PCView(t->mg, v));
    PetscCall(PetscViewerASCIIPopTab(v));
  }
  PetscFunctionReturn(0);
}

/* The KSP's configured preconditioner becomes the AMG whose interpolations the truncated multigrid keeps; the KSP
   gets the truncated multigrid (a PCSHELL) instead. truncate = PETSC_FALSE keeps P untruncated (for comparison). */
PetscErrorCode SgTMGCreate(SgSSN s, KSP ksp, PetscBool truncate, SgTMG *tmg)
{
  SgTMG     t;
  PC        pc;
  PetscBool hypre, gamg;

  PetscFunctionBeginUser;
  if (!tmg_registered) {
    PetscCall(PetscLogEventRegister("SgTMGBuild", PC_CLASSID, &SG_TMGBuild));
    PetscCall(PetscLogEventRegister("SgTMGUpdate", PC_CLASSID, &SG_TMGUpdate));
    tmg_registered = PETSC_TRUE;
  }
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCHYPRE, &hypre));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCGAMG, &gamg));
  PetscCheck(hypre || gamg, s->comm, PETSC_ERR_USER_INPUT, "-ssn_pc_truncated_mg takes the interpolations of an AMG: -pc_type hypre (BoomerAMG) or gamg");
  PetscCall(PetscNew(&t));
  t->ssn      = s;
  t->truncate = truncate;
  PetscCall(PetscMalloc4(s->cv.n, &t->axis, s->cv.n, &t->sign, s->cv.n, &t->want, s->cv.n, &t->have));
  for (PetscInt i = 0; i < s->cv.n; i++) t->want[i] = t->have[i] = 0;
  if (truncate) PetscCall(SgContactAxisAligned(s->c, "-ssn_pc_truncated_mg", t->axis, t->sign));
  PetscCall(PetscObjectReference((PetscObject)pc));
  t->amg = pc;
  PetscCall(PCCreate(s->comm, &pc));
  PetscCall(PCSetType(pc, PCSHELL));
  PetscCall(PCShellSetContext(pc, t));
  PetscCall(PCShellSetName(pc, "truncated multigrid"));
  PetscCall(PCShellSetSetUp(pc, SetUp_TMG));
  PetscCall(PCShellSetApply(pc, Apply_TMG));
  PetscCall(PCShellSetView(pc, View_TMG));
  PetscCall(KSPSetPC(ksp, pc));
  PetscCall(PCDestroy(&pc));
  *tmg = t;
  PetscFunctionReturn(0);
}

/* the active set of the Jacobian about to be solved with (read at the next set-up) */
PetscErrorCode SgTMGSetActiveSet(SgTMG t, const char act[])
{
  PetscFunctionBeginUser;
  if (!t) PetscFunctionReturn(0);
  PetscCall(PetscArraycpy(t->want, act, t->ssn->cv.n));
  t->has_set = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode SgTMGDestroy(SgTMG *tmg)
{
  SgTMG t = *tmg;

  PetscFunctionBeginUser;
  if (!t) PetscFunctionReturn(0);
  PetscCall(PCDestroy(&t->amg));
  PetscCall(PCDestroy(&t->mg));
  PetscCall(MatDestroy(&t->P0));
  PetscCall(MatDestroy(&t->Pt));
  PetscCall(PetscFree4(t->axis, t->sign, t->want, t->have));
  PetscCall(PetscFree(*tmg));
  PetscFunctionReturn(0);
}
