/* element.c: the P1 element kernels: Lame constants, simplex gradients, the element stiffness and a simplex quadrature. */
#include "fem/femimpl.h"

/* Lame constants (plane strain in 2D) from Young's modulus and Poisson's ratio. */
PetscErrorCode SgLame(PetscReal E, PetscReal nu, PetscReal *lambda, PetscReal *mu)
{
  PetscFunctionBeginUser;
  *mu     = E / (2 * (1 + nu));
  *lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  PetscFunctionReturn(0);
}

/* Gradients G[a*dim+d] of the barycentric functions of a simplex and its measure. */
PetscErrorCode SgSimplexGradients(PetscInt dim, const PetscReal x[], PetscReal G[], PetscReal *vol)
{
  PetscReal J[3][3], Ji[3][3], det;

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < dim; a++)
    for (PetscInt d = 0; d < dim; d++) J[d][a] = x[(a + 1) * dim + d] - x[d];
  if (dim == 2) {
    det      = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    Ji[0][0] = J[1][1] / det;
    Ji[0][1] = -J[0][1] / det;
    Ji[1][0] = -J[1][0] / det;
    Ji[1][1] = J[0][0] / det;
    *vol     = 0.5 * PetscAbsReal(det);
  } else {
    det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) + J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
    for (PetscInt i = 0; i < 3; i++)
      for (PetscInt j = 0; j < 3; j++) {
        const PetscInt i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
        Ji[i][j] = (J[i1][j1] * J[i2][j2] - J[i1][j2] * J[i2][j1]) / det;
      }
    *vol = PetscAbsReal(det) / 6.0;
  }
  PetscCheck(det != 0 && PetscIsNormalReal(det), PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "degenerate simplex (zero measure) in the mesh");
  /* grad phi_a (a >= 1) is row a-1 of J^{-1}; grad phi_0 = -sum of the others */
  for (PetscInt d = 0; d < dim; d++) {
    G[d] = 0;
    for (PetscInt a = 1; a <= dim; a++) {
      G[a * dim + d] = Ji[a - 1][d];
      G[d] -= Ji[a - 1][d];
    }
  }
  PetscFunctionReturn(0);
}

/* P1 element stiffness Ke[(a*dim+i)*(n*dim)+(b*dim+j)] = int lambda div(phi_b e_j) div(phi_a e_i) + 2 mu eps:eps. */
PetscErrorCode SgElementStiffness(PetscInt dim, const PetscReal x[], PetscReal lambda, PetscReal mu, PetscReal Ke[], PetscReal *vol)
{
  PetscReal      G[12];
  const PetscInt nv = dim + 1, n = nv * dim;

  PetscFunctionBeginUser;
  PetscCall(SgSimplexGradients(dim, x, G, vol));
  for (PetscInt a = 0; a < nv; a++)
    for (PetscInt b = 0; b < nv; b++) {
      PetscReal gg = 0;
      for (PetscInt k = 0; k < dim; k++) gg += G[a * dim + k] * G[b * dim + k];
      for (PetscInt i = 0; i < dim; i++)
        for (PetscInt j = 0; j < dim; j++) Ke[(a * dim + i) * n + b * dim + j] = *vol * (lambda * G[a * dim + i] * G[b * dim + j] + mu * (G[a * dim + j] * G[b * dim + i] + (i == j ? gg : 0)));
    }
  PetscFunctionReturn(0);
}

/* Quadrature on a simplex of dimension dim, exact to degree 5: barycentric points and weights summing to 1. */
PetscErrorCode SgSimplexQuadrature(PetscInt dim, PetscInt *nq, PetscReal **lam, PetscReal **w)
{
  PetscQuadrature  q;
  const PetscReal *pts, *wts;
  PetscReal        wsum = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscDTStroudConicalQuadrature(dim, 1, 3, -1.0, 1.0, &q));
  PetscCall(PetscQuadratureGetData(q, NULL, NULL, nq, &pts, &wts));
  PetscCall(PetscMalloc2(*nq * (dim + 1), lam, *nq, w));
  for (PetscInt i = 0; i < *nq; i++) wsum += wts[i];
  for (PetscInt i = 0; i < *nq; i++) {
    PetscReal s = 0;
    for (PetscInt d = 0; d < dim; d++) {
      (*lam)[i * (dim + 1) + d + 1] = 0.5 * (pts[i * dim + d] + 1);
      s += (*lam)[i * (dim + 1) + d + 1];
    }
    (*lam)[i * (dim + 1)] = 1 - s;
    (*w)[i]               = wts[i] / wsum;
  }
  PetscCall(PetscQuadratureDestroy(&q));
  PetscFunctionReturn(0);
}
