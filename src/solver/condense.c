/* condense.c: SSN linear solves condensed onto the contact dofs (-ssn_condense, one rank, MUMPS).
   K is factored once, with its Schur complement S_K on the contact dofs; a contact Jacobian K + gamma sum_A w n n^T
   differs from K only there, so its Schur complement is S_K + the contact blocks: each SSN step factors that small
   dense matrix instead of the whole stiffness, and MUMPS's condensation/expansion solves do the rest. */
#include "solver/ssnimpl.h"

struct _n_SgCondense {
  SgSSN     ssn;
  Mat       F;     /* MUMPS factor of K with the Schur complement on the contact dofs */
  Mat       S0;    /* S_K, kept to restart every update from */
  PetscInt  ncomp; /* 1: the normal component of each contact vertex (axis-aligned normals), dim: all components */
  PetscInt *axis;  /* axis of each contact vertex's normal (ncomp = 1) */
  PetscBool ready;
  /* the sparse right-hand side [0; r_C] of the steps whose interior rows are round-off (PCApply_Condense) */
  PetscInt     nc;             /* number of condensed dofs */
  PetscInt    *cidx;           /* their local indices, ascending */
  PetscBool   *isc;            /* isc[i]: local dof i is condensed */
  Mat          Bt;             /* 1 x n AIJ: the transpose of [0; r_C] */
  PetscScalar *bv;             /* its values */
  PetscInt     nsparse, nfull; /* solves by the sparse right-hand side and by the whole one */
  PetscInt    *ia, *ja;        /* Bt's row pointers and columns (cidx) */
};

static PetscErrorCode CondenseUpdate(SgCondense cd)
{
  SgSSN                s   = cd->ssn;
  const PetscInt       dim = s->dim;
  Mat                  S;
  MatFactorSchurStatus status;
  PetscScalar         *sa;
  const PetscScalar   *s0;
  PetscInt             lda, lda0, n;

  PetscFunctionBeginUser;
  PetscCall(MatFactorGetSchurComplement(cd->F, &S, &status));
  PetscCall(MatSetUnfactored(S)); /* it holds the factors of the previous step: start again from S_K */
  PetscCall(MatGetSize(S, &n, NULL));
  PetscCall(MatDenseGetLDA(S, &lda));
  PetscCall(MatDenseGetLDA(cd->S0, &lda0));
  PetscCall(MatDenseGetArray(S, &sa));
  PetscCall(MatDenseGetArrayRead(cd->S0, &s0));
  for (PetscInt j = 0; j < n; j++) PetscCall(PetscArraycpy(sa + j * lda, s0 + j * lda0, n));
  PetscCall(MatDenseRestoreArrayRead(cd->S0, &s0));
  if (s->havejac)
    for (PetscInt i = 0; i < s->n; i++) {
      if (!s->actjac[i]) continue;
      if (cd->ncomp == 1) sa[i * lda + i] += s->gamma * s->w[i];
      else
        for (PetscInt a = 0; a < dim; a++)
          for (PetscInt b = 0; b < dim; b++) sa[(i * dim + b) * lda + i * dim + a] += s->gamma * s->w[i] * s->normal[i * dim + a] * s->normal[i * dim + b];
    }
  PetscCall(MatDenseRestoreArray(S, &sa));
  /* K is SPD (assembly.c; MUMPS factors it without pivoting), so is S_K, and the contact blocks are positive
     semidefinite: the dense factorization is then LAPACK's Cholesky (potrf) instead of Bunch-Kaufman (sytrf),
     which PETSc picks for a Cholesky-type factor of a matrix not flagged SPD */
  PetscCall(MatSetOption(S, MAT_SPD, PETSC_TRUE));
  PetscCall(MatFactorRestoreSchurComplement(cd->F, &S, MAT_FACTOR_SCHUR_UNFACTORED));
  PetscCall(MatFactorFactorizeSchurComplement(cd->F));
  PetscFunctionReturn(0);
}

static PetscErrorCode PCSetUp_Condense(PC pc)
{
  SgCondense cd;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &cd));
  if (!cd->ready) { /* the one sparse factorization, with the Schur complement on the contact dofs */
    const PetscInt       dim = cd->ssn->dim;
    PetscInt            *idx, rstart;
    IS                   is;
    MatFactorInfo        info;
    MatFactorSchurStatus status;

    PetscCall(MatGetOwnershipRange(cd->ssn->Klin, &rstart, NULL));
    PetscCall(PetscMalloc1(cd->ssn->n * cd->ncomp, &idx));
    for (PetscInt i = 0; i < cd->ssn->n; i++)
      for (PetscInt k = 0; k < cd->ncomp; k++) idx[i * cd->ncomp + k] = rstart + cd->ssn->off[i] + (cd->ncomp == 1 ? cd->axis[i] : k);
    {
      PetscInt nloc, *ia, *ja;
      PetscCall(MatGetLocalSize(cd->ssn->Klin, &nloc, NULL));
      cd->nc = cd->ssn->n * cd->ncomp;
      PetscCall(PetscMalloc1(cd->nc, &cd->cidx));
      PetscCall(PetscCalloc1(nloc, &cd->isc));
      for (PetscInt k = 0; k < cd->nc; k++) cd->isc[idx[k] - rstart] = PETSC_TRUE;
      for (PetscInt i = 0, k = 0; i < nloc; i++)
        if (cd->isc[i]) cd->cidx[k++] = i;
      PetscCall(PetscMalloc1(2, &ia));
      PetscCall(PetscMalloc1(cd->nc, &ja));
      PetscCall(PetscCalloc1(cd->nc, &cd->bv));
      ia[0] = 0;
      ia[1] = cd->nc;
      PetscCall(PetscArraycpy(ja, cd->cidx, cd->nc));
      PetscCall(MatCreateSeqAIJWithArrays(PETSC_COMM_SELF, 1, nloc, ia, ja, cd->bv, &cd->Bt));
      cd->ia = ia;
      cd->ja = ja;
    }
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, cd->ssn->n * cd->ncomp, idx, PETSC_OWN_POINTER, &is));
    PetscCall(MatGetFactor(cd->ssn->Klin, MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &cd->F));
    PetscCall(MatFactorSetSchurIS(cd->F, is));
    PetscCall(ISDestroy(&is));
    PetscCall(MatFactorInfoInitialize(&info));
    PetscCall(MatCholeskyFactorSymbolic(cd->F, cd->ssn->Klin, NULL, &info));
    PetscCall(MatCholeskyFactorNumeric(cd->F, cd->ssn->Klin, &info));
    PetscCall(MatFactorCreateSchurComplement(cd->F, &cd->S0, &status));
    cd->ready = PETSC_TRUE;
    (void)dim;
  }
  PetscCall(CondenseUpdate(cd));
  PetscFunctionReturn(0);
}

/* Apply J^{-1}. After the first exact solve the SSN's right-hand sides are zero, to round-off, on every row but the
   contact dofs' (K is linear and the steps exact; only the contact rows change with the active set and gamma). Then
   [0; r_C] is passed as a sparse right-hand side (MUMPS ICNTL(20) = 1 through MatMatTransposeSolve): MUMPS prunes
   the forward elimination to the paths from those rows to the root, where the condensed dofs are, so a step costs
   the backward sweep (the expansion) and the dense solve instead of two sweeps through the whole factor. The rows
   dropped are round-off: 1e-14 .. 1e-10 of the contact rows (max norms) measured on Example 1 at 120 x 40 ... 960 x
   320; the test, below SG_CONDENSE_INTERIOR_TOL times the contact rows, leaves a margin. A right-hand side with more
   off the contact dofs (the first, unconstrained solve) is solved whole. */
#define SG_CONDENSE_INTERIOR_TOL 1e-8
static PetscErrorCode PCApply_Condense(PC pc, Vec r, Vec x)
{
  SgCondense         cd;
  const PetscScalar *ra;
  PetscReal          ri = 0, rc = 0;
  PetscInt           nloc;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &cd));
  PetscCall(VecGetLocalSize(r, &nloc));
  PetscCall(VecGetArrayRead(r, &ra));
  for (PetscInt i = 0; i < nloc; i++) {
    if (cd->isc[i]) rc = PetscMax(rc, PetscAbsScalar(ra[i]));
    else ri = PetscMax(ri, PetscAbsScalar(ra[i]));
  }
  if (rc > 0 && ri <= SG_CONDENSE_INTERIOR_TOL * rc) {
    Mat          X;
    PetscScalar *xa;

    for (PetscInt k = 0; k < cd->nc; k++) cd->bv[k] = ra[cd->cidx[k]];
    PetscCall(VecRestoreArrayRead(r, &ra));
    PetscCall(VecGetArrayWrite(x, &xa));
    PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, nloc, 1, xa, &X));
    PetscCall(MatMatTransposeSolve(cd->F, cd->Bt, X));
    PetscCall(MatDestroy(&X));
    PetscCall(VecRestoreArrayWrite(x, &xa));
    cd->nsparse++;
    PetscCall(PetscInfo(pc, "condensed solve %" PetscInt_FMT ": interior rows %g of the contact rows' %g: sparse right-hand side (no forward sweep)\n", cd->nsparse + cd->nfull, (double)ri, (double)rc));
    PetscFunctionReturn(0);
  }
  PetscCall(VecRestoreArrayRead(r, &ra));
  PetscCall(MatSolve(cd->F, r, x));
  cd->nfull++;
  PetscCall(PetscInfo(pc, "condensed solve %" PetscInt_FMT ": interior rows %g of the contact rows' %g: whole right-hand side\n", cd->nsparse + cd->nfull, (double)ri, (double)rc));
  PetscFunctionReturn(0);
}

/* Replace the SSN's linear solver by the condensed one. */
PetscErrorCode SgCondenseCreate(SgSSN s, SgCondense *cond)
{
  SgCondense     cd;
  PetscMPIInt    size;
  KSP            ksp;
  PC             pc;
  PetscBool      aligned = PETSC_TRUE;
  const PetscInt dim     = s->dim;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(s->comm, &size));
  PetscCheck(size == 1, s->comm, PETSC_ERR_SUP, "-ssn_condense runs on one rank (PETSc's MUMPS interface has no distributed Schur complements); got %d ranks", size);
  PetscCheck(s->c, s->comm, PETSC_ERR_USER_INPUT, "-ssn_condense needs a contact boundary");
  PetscCall(SgContactIsPair(s->c, &aligned));
  PetscCheck(!aligned, s->comm, PETSC_ERR_SUP, "-ssn_condense is not available for two-body contact (-contact_master_ids): its conditions couple the two sides; leave it out (MUMPS without it, or the iterative default)");
  aligned = PETSC_TRUE;
  PetscCall(PetscNew(&cd));
  cd->ssn = s;
  PetscCall(PetscMalloc1(s->n, &cd->axis));
  if (s->frame) { /* in the contact frames every normal is an axis (frame.c) */
    const PetscInt *axis;
    PetscCall(SgFrameGetAxes(s->frame, &axis, NULL, NULL));
    PetscCall(PetscArraycpy(cd->axis, axis, s->n));
  } else {
    for (PetscInt i = 0; i < s->n; i++) {
      cd->axis[i] = -1;
      for (PetscInt k = 0; k < dim; k++)
        if (PetscAbsReal(PetscAbsReal(s->normal[i * dim + k]) - 1) < 1e-12) cd->axis[i] = k;
      if (cd->axis[i] < 0) aligned = PETSC_FALSE;
    }
  }
  /* axis-aligned normals: the contact block only touches the normal components, so only they are condensed */
  cd->ncomp = aligned ? 1 : dim;
  PetscCall(SNESGetKSP(s->snes, &ksp));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCSHELL));
  PetscCall(PCShellSetContext(pc, cd));
  PetscCall(PCShellSetSetUp(pc, PCSetUp_Condense));
  PetscCall(PCShellSetApply(pc, PCApply_Condense));
  PetscCall(PCShellSetName(pc, "contact-boundary condensation (MUMPS Schur complement)"));
  *cond = cd;
  PetscFunctionReturn(0);
}

PetscErrorCode SgCondenseDestroy(SgCondense *cond)
{
  PetscFunctionBeginUser;
  if (!*cond) PetscFunctionReturn(0);
  PetscCall(MatDestroy(&(*cond)->F));
  PetscCall(MatDestroy(&(*cond)->S0));
  PetscCall(MatDestroy(&(*cond)->Bt));
  PetscCall(PetscFree((*cond)->ia));
  PetscCall(PetscFree((*cond)->ja));
  PetscCall(PetscFree((*cond)->bv));
  PetscCall(PetscFree((*cond)->cidx));
  PetscCall(PetscFree((*cond)->isc));
  PetscCall(PetscFree((*cond)->axis));
  PetscCall(PetscFree(*cond));
  PetscFunctionReturn(0);
}
