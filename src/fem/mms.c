/* mms.c: the manufactured solution (-mms, verification): the field, the body force that produces it and the errors of a
   discrete solution against it. */
#include "fem/femimpl.h"

/* Manufactured solution u_k = A sin(pi a_k.x + phi_k) and the body force -div sigma(u) that produces it. */
static const PetscReal MMS_A = 0.01, MMS_a[3][3] = {
                                         { 1.0,  0.5, 0.25},
                                         { 0.5,  1.0, 0.75},
                                         {0.25, 0.75,  1.0}
},
                       MMS_phi[3] = {0.1, 0.3, 0.7};

void SgMMSExact(PetscInt dim, const PetscReal x[], PetscReal u[], PetscReal grad[])
{
  for (PetscInt k = 0; k < dim; k++) {
    PetscReal th = MMS_phi[k];
    for (PetscInt j = 0; j < dim; j++) th += PETSC_PI * MMS_a[k][j] * x[j];
    u[k] = MMS_A * PetscSinReal(th);
    if (grad)
      for (PetscInt j = 0; j < dim; j++) grad[k * dim + j] = MMS_A * PETSC_PI * MMS_a[k][j] * PetscCosReal(th);
  }
}

void SgMMSForce(PetscInt dim, PetscReal lambda, PetscReal mu, const PetscReal x[], PetscReal f[])
{
  PetscReal s[3];
  for (PetscInt k = 0; k < dim; k++) {
    PetscReal th = MMS_phi[k];
    for (PetscInt j = 0; j < dim; j++) th += PETSC_PI * MMS_a[k][j] * x[j];
    s[k] = MMS_A * PETSC_PI * PETSC_PI * PetscSinReal(th);
  }
  /* f_l = mu |a_l|^2 s_l + (lambda+mu) sum_k a_kk a_kl s_k */
  for (PetscInt l = 0; l < dim; l++) {
    PetscReal al2 = 0, gd = 0;
    for (PetscInt j = 0; j < dim; j++) al2 += MMS_a[l][j] * MMS_a[l][j];
    for (PetscInt k = 0; k < dim; k++) gd += MMS_a[k][k] * MMS_a[k][l] * s[k];
    f[l] = mu * al2 * s[l] + (lambda + mu) * gd;
  }
}

/* L2 and H1-seminorm errors against the manufactured solution. */
PetscErrorCode SgElasticityMMSErrors(SgElasticity p, Vec y, PetscReal *l2, PetscReal *h1)
{
  const SgMesh      *m   = &p->mesh;
  const PetscInt     dim = p->dim, nv = dim + 1;
  Vec                yloc;
  const PetscScalar *ya;
  PetscReal          e[2] = {0, 0}, *lq, *wq;
  PetscInt           nq;

  PetscFunctionBeginUser;
  PetscCheck(p->mms, p->comm, PETSC_ERR_ARG_WRONGSTATE, "errors need -mms");
  PetscCall(SgSimplexQuadrature(dim, &nq, &lq, &wq));
  PetscCall(DMGetLocalVector(p->dm, &yloc));
  PetscCall(SgElasticityGlobalToLocal(p, y, yloc));
  PetscCall(VecGetArrayRead(yloc, &ya));
  for (PetscInt c = 0; c < m->nc; c++) {
    PetscReal xe[12], ue[12], G[12], vol, gh[9] = {0};
    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt d = 0; d < dim; d++) {
        xe[a * dim + d] = m->x[m->cellv[c * nv + a] * dim + d];
        ue[a * dim + d] = PetscRealPart(ya[m->loff[m->cellv[c * nv + a]] + d]);
      }
    PetscCall(SgSimplexGradients(dim, xe, G, &vol));
    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt k = 0; k < dim; k++)
        for (PetscInt j = 0; j < dim; j++) gh[k * dim + j] += ue[a * dim + k] * G[a * dim + j];
    for (PetscInt q = 0; q < nq; q++) {
      PetscReal xq[3] = {0, 0, 0}, u[3], g[9], uh[3] = {0, 0, 0};
      for (PetscInt a = 0; a < nv; a++)
        for (PetscInt d = 0; d < dim; d++) {
          xq[d] += lq[q * nv + a] * xe[a * dim + d];
          uh[d] += lq[q * nv + a] * ue[a * dim + d];
        }
      SgMMSExact(dim, xq, u, g);
      for (PetscInt d = 0; d < dim; d++) e[0] += vol * wq[q] * PetscSqr(u[d] - uh[d]);
      for (PetscInt d = 0; d < dim * dim; d++) e[1] += vol * wq[q] * PetscSqr(g[d] - gh[d]);
    }
  }
  PetscCall(VecRestoreArrayRead(yloc, &ya));
  PetscCall(DMRestoreLocalVector(p->dm, &yloc));
  PetscCall(PetscFree2(lq, wq));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, e, 2, MPIU_REAL, MPI_SUM, p->comm));
  *l2 = PetscSqrtReal(e[0]);
  *h1 = PetscSqrtReal(e[1]);
  PetscFunctionReturn(0);
}
