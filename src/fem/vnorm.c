/* fem/vnorm.c: norms of displacement-like vectors and of the stiffness that do not change when the problem is turned
   rigidly. A component maximum (NORM_INFINITY) or sum (NORM_1) of a vector of nodal displacements or forces depends on
   the axes: a vertex moving by (0, 0, -0.2) has the largest component 0.2, turned by 30 degrees about (1,1,1) 0.182.
   Each vertex's dim components form one vector, and its Euclidean length is the same in any orthonormal axes; the
   scales and measures of the KKT test and of the controllers take the largest or the sum of these lengths. Likewise
   ||K||_inf (the largest row sum of |K_ij|) changes when K becomes Q^T K Q with Q block diagonal and orthogonal; the
   largest sum over a vertex's block row of the Frobenius norms of its dim x dim blocks does not. Every vector here is
   laid out with dim consecutive entries per vertex (the displacement section, global and local alike). */
#include <sg.h>

/* the largest Euclidean length of a vertex's dim consecutive entries of v (on v's communicator; a local vector: this
   rank's). A length that is not a multiple of dim cannot happen with this layout; then the component maximum. */
PetscErrorCode SgVecVertexNormMax(Vec v, PetscInt dim, PetscReal *mx)
{
  const PetscScalar *a;
  PetscInt           n;
  PetscReal          m = 0;

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(v, &n));
  if (dim < 1 || n % dim) {
    PetscCall(VecNorm(v, NORM_INFINITY, mx));
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetArrayRead(v, &a));
  for (PetscInt i = 0; i < n; i += dim) {
    PetscReal s = 0;
    for (PetscInt k = 0; k < dim; k++) s += PetscSqr(PetscAbsScalar(a[i + k]));
    m = PetscMax(m, s);
  }
  PetscCall(VecRestoreArrayRead(v, &a));
  m = PetscSqrtReal(m);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &m, 1, MPIU_REAL, MPI_MAX, PetscObjectComm((PetscObject)v)));
  *mx = m;
  PetscFunctionReturn(0);
}

/* the sum over the vertices of the Euclidean lengths of their dim consecutive entries of v (on v's communicator) */
PetscErrorCode SgVecVertexNormSum(Vec v, PetscInt dim, PetscReal *sum)
{
  const PetscScalar *a;
  PetscInt           n;
  PetscReal          t = 0;

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(v, &n));
  if (dim < 1 || n % dim) {
    PetscCall(VecNorm(v, NORM_1, sum));
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetArrayRead(v, &a));
  for (PetscInt i = 0; i < n; i += dim) {
    PetscReal s = 0;
    for (PetscInt k = 0; k < dim; k++) s += PetscSqr(PetscAbsScalar(a[i + k]));
    t += PetscSqrtReal(s);
  }
  PetscCall(VecRestoreArrayRead(v, &a));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &t, 1, MPIU_REAL, MPI_SUM, PetscObjectComm((PetscObject)v)));
  *sum = t;
  PetscFunctionReturn(0);
}

/* max over the vertices' block rows I of sum_J ||K_IJ||_F, the blocks of dim rows and dim columns (global column c in
   block c / dim). The same for Q^T K Q with Q block diagonal orthogonal; between ||K||_inf / sqrt(dim) and
   sqrt(dim) ||K||_inf. */
PetscErrorCode SgMatVertexNorm(Mat K, PetscInt dim, PetscReal *nrm)
{
  PetscInt     rstart, rend, cap = 0, *blk = NULL;
  PetscScalar *sq = NULL; /* squares (a scalar array for PetscSortIntWithScalarArray) */
  PetscReal    m  = 0;

  PetscFunctionBeginUser;
  PetscCall(MatGetOwnershipRange(K, &rstart, &rend));
  if (dim < 1 || rstart % dim || rend % dim) {
    PetscCall(MatNorm(K, NORM_INFINITY, nrm));
    PetscFunctionReturn(0);
  }
  for (PetscInt r0 = rstart; r0 < rend; r0 += dim) {
    PetscInt  cnt = 0;
    PetscReal s   = 0;
    for (PetscInt k = 0; k < dim; k++) {
      PetscInt           nc;
      const PetscInt    *cols;
      const PetscScalar *vals;
      PetscCall(MatGetRow(K, r0 + k, &nc, &cols, &vals));
      if (cnt + nc > cap) {
        PetscInt    *b2;
        PetscScalar *s2;
        cap = PetscMax(2 * cap, cnt + nc);
        PetscCall(PetscMalloc2(cap, &b2, cap, &s2));
        PetscCall(PetscArraycpy(b2, blk, cnt));
        PetscCall(PetscArraycpy(s2, sq, cnt));
        PetscCall(PetscFree2(blk, sq));
        blk = b2;
        sq  = s2;
      }
      for (PetscInt j = 0; j < nc; j++) {
        blk[cnt]  = cols[j] / dim;
        sq[cnt++] = PetscSqr(PetscAbsScalar(vals[j]));
      }
      PetscCall(MatRestoreRow(K, r0 + k, &nc, &cols, &vals));
    }
    PetscCall(PetscSortIntWithScalarArray(cnt, blk, sq));
    for (PetscInt j = 0; j < cnt;) {
      PetscReal f = 0;
      PetscInt  b = blk[j];
      for (; j < cnt && blk[j] == b; j++) f += PetscRealPart(sq[j]);
      s += PetscSqrtReal(f);
    }
    m = PetscMax(m, s);
  }
  PetscCall(PetscFree2(blk, sq));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &m, 1, MPIU_REAL, MPI_MAX, PetscObjectComm((PetscObject)K)));
  *nrm = m;
  PetscFunctionReturn(0);
}
