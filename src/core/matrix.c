/* core/matrix.c: sparse matrix helpers shared by the layers. */
#include "sg.h"

/* a sequential AIJ's CSR arrays (NULL arrays for NULL): rows, columns, values */
typedef struct {
  Mat                M;
  PetscInt           n;
  const PetscInt    *i, *j, *map; /* map: the global column of each local one (the off-diagonal part), NULL: itself */
  const PetscScalar *a;
} CSR;

static PetscErrorCode CSRGet(Mat M, const PetscInt *map, CSR *c)
{
  PetscBool done;

  PetscFunctionBeginUser;
  c->M   = M;
  c->map = map;
  PetscCall(MatGetRowIJ(M, 0, PETSC_FALSE, PETSC_FALSE, &c->n, &c->i, &c->j, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "SgMatAddSparse: no CSR arrays of a matrix");
  PetscCall(MatSeqAIJGetArrayRead(M, &c->a));
  PetscFunctionReturn(0);
}

static PetscErrorCode CSRRestore(CSR *c)
{
  PetscBool done;

  PetscFunctionBeginUser;
  PetscCall(MatSeqAIJRestoreArrayRead(c->M, &c->a));
  PetscCall(MatRestoreRowIJ(c->M, 0, PETSC_FALSE, PETSC_FALSE, &c->n, &c->i, &c->j, &done));
  PetscFunctionReturn(0);
}

/* the row-wise union of two CSR (their columns mapped, increasing in both), values added: new arrays (PetscMalloc3) */
static PetscErrorCode CSRMerge(PetscInt m, const CSR *x, const CSR *y, PetscInt **si, PetscInt **sj, PetscScalar **sa)
{
  PetscInt nz = 0;

  PetscFunctionBeginUser;
  for (PetscInt pass = 0; pass < 2; pass++) {
    if (pass) PetscCall(PetscMalloc3(m + 1, si, nz + 1, sj, nz + 1, sa));
    nz = 0;
    for (PetscInt r = 0; r < m; r++) {
      PetscInt i = x->i[r], ie = x->i[r + 1], j = y->i[r], je = y->i[r + 1];
      if (pass) (*si)[r] = nz;
      if (j == je) { /* the usual row: x's alone */
        if (pass) {
          for (PetscInt k = i; k < ie; k++) (*sj)[nz + k - i] = x->map ? x->map[x->j[k]] : x->j[k];
          PetscCall(PetscArraycpy(*sa + nz, x->a + i, ie - i));
        }
        nz += ie - i;
        continue;
      }
      while (i < ie || j < je) {
        PetscInt    cx = i < ie ? (x->map ? x->map[x->j[i]] : x->j[i]) : PETSC_MAX_INT, cy = j < je ? (y->map ? y->map[y->j[j]] : y->j[j]) : PETSC_MAX_INT;
        PetscScalar v;
        if (cx < cy) v = x->a[i++];
        else if (cy < cx) v = y->a[j++];
        else v = x->a[i++] + y->a[j++];
        if (pass) {
          (*sj)[nz] = PetscMin(cx, cy);
          (*sa)[nz] = v;
        }
        nz++;
      }
    }
    if (pass) (*si)[m] = nz;
  }
  PetscFunctionReturn(0);
}

/* S = A + C for two AIJ matrices of the same layout, S's pattern the union of theirs: one pass over A's CSR arrays,
   each row merged with C's (empty in most rows where C is a correction on a few rows and columns), into arrays that a
   matrix wraps and a MatDuplicate copies (MatSetValues per entry cost 1.5 s at 3e5 unknowns, MatAXPY with
   DIFFERENT_NONZERO_PATTERN inserts both matrices' values so). A product P^T A P with P = I + W, W nonzero on a few rows,
   is A + (W^T A) + (W^T A)^T + (W^T A) W this way without MatPtAP's symbolic product over all of A. S's values are
   A's to the bit where C has none (rows and entries); elsewhere a + c. S has A's type and block sizes. Matrices of
   other types than (MPI/Seq)AIJ by MatAXPY. Collective. */
PetscErrorCode SgMatAddSparse(Mat A, Mat C, Mat *S)
{
  MPI_Comm  comm;
  PetscInt  m, n, M, N, bs, cbs;
  PetscBool seq;
  Mat       Sw;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)A, &comm));
  PetscCall(MatGetLocalSize(A, &m, &n));
  PetscCall(MatGetSize(A, &M, &N));
  {
    PetscInt mc, nc, Mc, Nc;
    PetscCall(MatGetLocalSize(C, &mc, &nc));
    PetscCall(MatGetSize(C, &Mc, &Nc));
    PetscCheck(mc == m && nc == n && Mc == M && Nc == N, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "SgMatAddSparse: the two matrices' layouts differ (%" PetscInt_FMT " x %" PetscInt_FMT " against %" PetscInt_FMT " x %" PetscInt_FMT ")", M, N, Mc, Nc);
  }
  PetscCall(MatGetBlockSizes(A, &bs, &cbs));
  PetscCall(PetscObjectTypeCompare((PetscObject)A, MATSEQAIJ, &seq));
  {
    PetscBool mpi, cs, cm;
    PetscCall(PetscObjectTypeCompare((PetscObject)A, MATMPIAIJ, &mpi));
    PetscCall(PetscObjectTypeCompare((PetscObject)C, MATSEQAIJ, &cs));
    PetscCall(PetscObjectTypeCompare((PetscObject)C, MATMPIAIJ, &cm));
    if (!(seq && cs) && !(mpi && cm)) { /* other types: PETSc's general sum */
      PetscCall(MatDuplicate(A, MAT_COPY_VALUES, S));
      PetscCall(MatAXPY(*S, 1.0, C, DIFFERENT_NONZERO_PATTERN));
      PetscFunctionReturn(0);
    }
  }
  if (seq) {
    CSR          a, c;
    PetscInt    *si, *sj;
    PetscScalar *sa;
    PetscCall(CSRGet(A, NULL, &a));
    PetscCall(CSRGet(C, NULL, &c));
    PetscCall(CSRMerge(m, &a, &c, &si, &sj, &sa));
    PetscCall(CSRRestore(&c));
    PetscCall(CSRRestore(&a));
    PetscCall(MatCreateSeqAIJWithArrays(comm, m, n, si, sj, sa, &Sw));
    PetscCall(MatDuplicate(Sw, MAT_COPY_VALUES, S));
    PetscCall(MatDestroy(&Sw));
    PetscCall(PetscFree3(si, sj, sa));
  } else {
    Mat             Ad, Ao, Cd, Co;
    const PetscInt *ag, *cg;
    CSR             ad, ao, cd, co;
    PetscInt       *di, *dj, *oi, *oj;
    PetscScalar    *da, *oa;
    PetscCall(MatMPIAIJGetSeqAIJ(A, &Ad, &Ao, &ag));
    PetscCall(MatMPIAIJGetSeqAIJ(C, &Cd, &Co, &cg));
    PetscCall(CSRGet(Ad, NULL, &ad));
    PetscCall(CSRGet(Cd, NULL, &cd));
    PetscCall(CSRMerge(m, &ad, &cd, &di, &dj, &da));
    PetscCall(CSRRestore(&cd));
    PetscCall(CSRRestore(&ad));
    PetscCall(CSRGet(Ao, ag, &ao));
    PetscCall(CSRGet(Co, cg, &co));
    PetscCall(CSRMerge(m, &ao, &co, &oi, &oj, &oa)); /* global columns, as the split arrays take them */
    PetscCall(CSRRestore(&co));
    PetscCall(CSRRestore(&ao));
    PetscCall(MatCreateMPIAIJWithSplitArrays(comm, m, n, M, N, di, dj, da, oi, oj, oa, &Sw));
    PetscCall(MatDuplicate(Sw, MAT_COPY_VALUES, S));
    PetscCall(MatDestroy(&Sw));
    PetscCall(PetscFree3(di, dj, da));
    PetscCall(PetscFree3(oi, oj, oa));
  }
  PetscCall(MatSetBlockSizes(*S, bs, cbs));
  PetscFunctionReturn(0);
}

/* W = A - I without its zeros: the rows and entries where A differs from the identity (A square, AIJ). A near-identity
   A (a change of basis that is the identity but on a few rows, stored with its whole diagonal and blocks) gives a W
   with entries on those rows alone, whose products with a large matrix cost as little as those rows. Collective. */
PetscErrorCode SgMatOffIdentity(Mat A, Mat *W)
{
  MPI_Comm comm;
  PetscInt rs, re, cs, ce, m, n, M, N, *dnz, *onz;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)A, &comm));
  PetscCall(MatGetOwnershipRange(A, &rs, &re));
  PetscCall(MatGetOwnershipRangeColumn(A, &cs, &ce));
  PetscCall(MatGetLocalSize(A, &m, &n));
  PetscCall(MatGetSize(A, &M, &N));
  PetscCall(PetscCalloc2(m + 1, &dnz, m + 1, &onz));
  for (PetscInt pass = 0; pass < 2; pass++) {
    if (pass) {
      PetscCall(MatCreate(comm, W));
      PetscCall(MatSetSizes(*W, m, n, M, N));
      PetscCall(MatSetBlockSizesFromMats(*W, A, A));
      PetscCall(MatSetType(*W, MATAIJ));
      PetscCall(MatXAIJSetPreallocation(*W, 1, dnz, onz, NULL, NULL));
      PetscCall(MatSetOption(*W, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
    }
    for (PetscInt r = rs; r < re; r++) {
      const PetscInt    *ja;
      const PetscScalar *av;
      PetscInt           na;
      PetscCall(MatGetRow(A, r, &na, &ja, &av));
      for (PetscInt k = 0; k < na; k++) {
        PetscScalar w = ja[k] == r ? av[k] - 1 : av[k];
        if (w == 0) continue;
        if (pass) PetscCall(MatSetValues(*W, 1, &r, 1, &ja[k], &w, INSERT_VALUES));
        else if (ja[k] >= cs && ja[k] < ce) dnz[r - rs]++;
        else onz[r - rs]++;
      }
      PetscCall(MatRestoreRow(A, r, &na, &ja, &av));
    }
  }
  PetscCall(PetscFree2(dnz, onz));
  PetscCall(MatAssemblyBegin(*W, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*W, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}
