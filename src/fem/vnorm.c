/* fem/vnorm.c: norms of displacement-like vectors and of the stiffness that do not change when the problem is turned
   rigidly. A component maximum (NORM_INFINITY) or sum (NORM_1) of a vector of nodal displacements or forces depends on
   the axes: a vertex moving by (0, 0, -0.2) has the largest component 0.2, turned by 30 degrees about (1,1,1) 0.182.
   Each vertex's dim components form one vector, and its Euclidean length is the same in any orthonormal axes; the
   scales and measures of the KKT test and of the controllers take the largest or the sum of these lengths. Likewise
   ||K||_inf (the largest row sum of |K_ij|) changes when K becomes Q^T K Q with Q block diagonal and orthogonal; the
   largest sum over a vertex's block row of the spectral norms of its dim x dim blocks does not. Every vector here is
   laid out with dim consecutive entries per vertex (the displacement section, global and local alike). */
#include <sg.h>

/* the largest (sum = false) or the sum (sum = true) of the Euclidean lengths of the vertices' dim consecutive entries
   of v, on v's communicator (a local vector: this rank's). One entry per "vertex" (dim <= 1, -contact_kkt_scale
   component), or a length that is not a multiple of dim (cannot happen with this layout): the component norm itself. */
static PetscErrorCode VecVertexNorm(Vec v, PetscInt dim, PetscBool sum, PetscReal *out)
{
  const PetscScalar *a;
  PetscInt           n;
  PetscReal          t = 0;

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(v, &n));
  if (dim <= 1 || n % dim) {
    PetscCall(VecNorm(v, sum ? NORM_1 : NORM_INFINITY, out));
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetArrayRead(v, &a));
  for (PetscInt i = 0; i < n; i += dim) {
    PetscReal s = 0;
    for (PetscInt k = 0; k < dim; k++) s += PetscSqr(PetscAbsScalar(a[i + k]));
    if (sum) t += PetscSqrtReal(s);
    else t = PetscMax(t, s);
  }
  PetscCall(VecRestoreArrayRead(v, &a));
  if (!sum) t = PetscSqrtReal(t);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &t, 1, MPIU_REAL, sum ? MPI_SUM : MPI_MAX, PetscObjectComm((PetscObject)v)));
  *out = t;
  PetscFunctionReturn(0);
}

/* the largest Euclidean length of a vertex's dim consecutive entries of v */
PetscErrorCode SgVecVertexNormMax(Vec v, PetscInt dim, PetscReal *mx)
{
  PetscFunctionBeginUser;
  PetscCall(VecVertexNorm(v, dim, PETSC_FALSE, mx));
  PetscFunctionReturn(0);
}

/* the sum over the vertices of the Euclidean lengths of their dim consecutive entries of v */
PetscErrorCode SgVecVertexNormSum(Vec v, PetscInt dim, PetscReal *sum)
{
  PetscFunctionBeginUser;
  PetscCall(VecVertexNorm(v, dim, PETSC_TRUE, sum));
  PetscFunctionReturn(0);
}

/* the largest singular value of the dim x dim block B (row major): the square root of the largest eigenvalue of
   B^T B, from its invariants (trace, second invariant, determinant), so that Q_I B Q_J^T gives the same up to
   round-off */
static PetscReal BlockNorm2(PetscInt dim, const PetscReal B[])
{
  PetscReal M[9] = {0}, l;

  for (PetscInt a = 0; a < dim; a++)
    for (PetscInt b = 0; b < dim; b++)
      for (PetscInt k = 0; k < dim; k++) M[a * dim + b] += B[k * dim + a] * B[k * dim + b];
  if (dim == 1) l = M[0];
  else if (dim == 2) {
    const PetscReal h = 0.5 * (M[0] + M[3]), d = 0.5 * (M[0] - M[3]);
    l = h + PetscSqrtReal(d * d + M[1] * M[2]);
  } else { /* symmetric 3 x 3: the trigonometric form of the largest root of the characteristic polynomial */
    const PetscReal q = (M[0] + M[4] + M[8]) / 3, p1 = M[1] * M[1] + M[2] * M[2] + M[5] * M[5];
    const PetscReal p2 = PetscSqr(M[0] - q) + PetscSqr(M[4] - q) + PetscSqr(M[8] - q) + 2 * p1, p = PetscSqrtReal(p2 / 6);
    if (!(p > 0)) l = q;
    else {
      PetscReal C[9], r, phi;
      for (PetscInt k = 0; k < 9; k++) C[k] = (M[k] - (k % 4 == 0 ? q : 0)) / p;
      r   = 0.5 * (C[0] * (C[4] * C[8] - C[5] * C[7]) - C[1] * (C[3] * C[8] - C[5] * C[6]) + C[2] * (C[3] * C[7] - C[4] * C[6]));
      phi = r <= -1 ? PETSC_PI / 3 : (r >= 1 ? 0 : PetscAcosReal(r) / 3);
      l   = q + 2 * p * PetscCosReal(phi);
    }
  }
  return PetscSqrtReal(PetscMax(l, 0));
}

/* max over the vertices' block rows I of sum_J ||K_IJ||_2, the blocks of dim rows and dim columns (global column c in
   block c / dim): a bound of the norm of K between the largest vertex displacements and the largest vertex forces,
   as ||K||_inf is between the largest components. The same for Q^T K Q with Q block diagonal orthogonal. */
PetscErrorCode SgMatVertexNorm(Mat K, PetscInt dim, PetscReal *nrm)
{
  PetscInt     rstart, rend, cap = 0, *key = NULL;
  PetscScalar *val = NULL; /* a scalar array for PetscSortIntWithScalarArray */
  PetscReal    m   = 0;

  PetscFunctionBeginUser;
  PetscCall(MatGetOwnershipRange(K, &rstart, &rend));
  if (dim <= 1 || dim > 3 || rstart % dim || rend % dim) { /* ||K||_inf itself (-contact_kkt_scale component) */
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
        PetscInt    *k2;
        PetscScalar *v2;
        cap = PetscMax(2 * cap, cnt + nc);
        PetscCall(PetscMalloc2(cap, &k2, cap, &v2));
        PetscCall(PetscArraycpy(k2, key, cnt));
        PetscCall(PetscArraycpy(v2, val, cnt));
        PetscCall(PetscFree2(key, val));
        key = k2;
        val = v2;
      }
      for (PetscInt j = 0; j < nc; j++) { /* the block, then the entry's place in it */
        key[cnt]   = (cols[j] / dim) * dim * dim + k * dim + cols[j] % dim;
        val[cnt++] = vals[j];
      }
      PetscCall(MatRestoreRow(K, r0 + k, &nc, &cols, &vals));
    }
    PetscCall(PetscSortIntWithScalarArray(cnt, key, val));
    for (PetscInt j = 0; j < cnt;) {
      PetscReal      B[9] = {0};
      const PetscInt b    = key[j] / (dim * dim);
      for (; j < cnt && key[j] / (dim * dim) == b; j++) B[key[j] % (dim * dim)] += PetscRealPart(val[j]);
      s += BlockNorm2(dim, B);
    }
    m = PetscMax(m, s);
  }
  PetscCall(PetscFree2(key, val));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &m, 1, MPIU_REAL, MPI_MAX, PetscObjectComm((PetscObject)K)));
  *nrm = m;
  PetscFunctionReturn(0);
}
