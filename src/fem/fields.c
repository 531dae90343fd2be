/* fields.c: the fields of a displacement: the full local vector (Dirichlet values included), the displacement on every
   vertex for output, and the von Mises stress and shear energy density per cell. */
#include "fem/femimpl.h"

/* Local vector of the full displacement: free values from y, Dirichlet values from the data. */
PetscErrorCode SgElasticityGlobalToLocal(SgElasticity p, Vec y, Vec yloc)
{
  PetscFunctionBeginUser;
  PetscCall(VecCopy(p->ubc, yloc));
  PetscCall(DMGlobalToLocal(p->dm, y, INSERT_VALUES, yloc));
  if (p->npartial) { /* the fixed components of partly fixed vertices: the data, not their (zero) unknowns */
    const PetscScalar *ua;
    PetscScalar       *ya;
    PetscCall(VecGetArrayRead(p->ubc, &ua));
    PetscCall(VecGetArray(yloc, &ya));
    for (PetscInt i = 0; i < p->npartial; i++) ya[p->partial[i]] = ua[p->partial[i]];
    PetscCall(VecRestoreArray(yloc, &ya));
    PetscCall(VecRestoreArrayRead(p->ubc, &ua));
  }
  PetscFunctionReturn(0);
}

/* The displacement on every vertex (Dirichlet ones included) as a global vector of dmVec, for output. */
PetscErrorCode SgElasticityFullDisplacement(SgElasticity p, Vec y, Vec ufull)
{
  Vec                yloc, uloc;
  const PetscScalar *ya;
  PetscScalar       *ua;
  PetscSection       s;

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(p->dm, &yloc));
  PetscCall(DMGetLocalVector(p->dmVec, &uloc));
  PetscCall(SgElasticityGlobalToLocal(p, y, yloc));
  PetscCall(DMGetLocalSection(p->dmVec, &s));
  PetscCall(VecGetArrayRead(yloc, &ya));
  PetscCall(VecGetArray(uloc, &ua));
  for (PetscInt v = 0; v < p->mesh.nv; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(s, p->mesh.vStart + v, &off));
    for (PetscInt d = 0; d < p->dim; d++) ua[off + d] = ya[p->mesh.loff[v] + d];
  }
  PetscCall(VecRestoreArrayRead(yloc, &ya));
  PetscCall(VecRestoreArray(uloc, &ua));
  PetscCall(DMLocalToGlobal(p->dmVec, uloc, INSERT_VALUES, ufull));
  PetscCall(DMRestoreLocalVector(p->dm, &yloc));
  PetscCall(DMRestoreLocalVector(p->dmVec, &uloc));
  PetscFunctionReturn(0);
}

/* Per-cell von Mises stress and elastic shear (distortion) energy density mu |dev eps|^2 (plane strain: eps_33 = 0). */
PetscErrorCode SgElasticityCellFields(SgElasticity p, Vec y, Vec vm, Vec wshear)
{
  const SgMesh      *m   = &p->mesh;
  const PetscInt     dim = p->dim, nv = dim + 1;
  Vec                yloc, vml, wl;
  const PetscScalar *ya;
  PetscScalar       *va, *wa;
  PetscSection       cs;

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(p->dm, &yloc));
  PetscCall(SgElasticityGlobalToLocal(p, y, yloc));
  PetscCall(DMGetLocalVector(p->dmCell, &vml));
  PetscCall(DMGetLocalVector(p->dmCell, &wl));
  PetscCall(DMGetLocalSection(p->dmCell, &cs));
  PetscCall(VecGetArrayRead(yloc, &ya));
  PetscCall(VecGetArray(vml, &va));
  PetscCall(VecGetArray(wl, &wa));
  for (PetscInt c = 0; c < m->nc; c++) {
    PetscReal xe[12], G[12], vol, eps[3][3] = {{0}}, sig[3][3], tr = 0, dev2 = 0, lambda, mu;
    PetscInt  off;

    SgElasticityCellLame(p, c, &lambda, &mu);

    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt d = 0; d < dim; d++) xe[a * dim + d] = m->x[m->cellv[c * nv + a] * dim + d];
    PetscCall(SgSimplexGradients(dim, xe, G, &vol));
    for (PetscInt a = 0; a < nv; a++) {
      const PetscScalar *u = &ya[m->loff[m->cellv[c * nv + a]]];
      for (PetscInt i = 0; i < dim; i++)
        for (PetscInt j = 0; j < dim; j++) eps[i][j] += 0.5 * (PetscRealPart(u[i]) * G[a * dim + j] + PetscRealPart(u[j]) * G[a * dim + i]);
    }
    for (PetscInt i = 0; i < 3; i++) tr += eps[i][i];
    for (PetscInt i = 0; i < 3; i++)
      for (PetscInt j = 0; j < 3; j++) {
        const PetscReal de = eps[i][j] - (i == j ? tr / 3 : 0);
        sig[i][j]          = 2 * mu * eps[i][j] + (i == j ? lambda * tr : 0);
        dev2 += de * de;
      }
    PetscCall(PetscSectionGetOffset(cs, m->cStart + c, &off));
    va[off] = PetscSqrtReal(0.5 * (PetscSqr(sig[0][0] - sig[1][1]) + PetscSqr(sig[1][1] - sig[2][2]) + PetscSqr(sig[2][2] - sig[0][0])) + 3 * (PetscSqr(sig[0][1]) + PetscSqr(sig[1][2]) + PetscSqr(sig[0][2])));
    wa[off] = mu * dev2;
  }
  PetscCall(VecRestoreArrayRead(yloc, &ya));
  PetscCall(VecRestoreArray(vml, &va));
  PetscCall(VecRestoreArray(wl, &wa));
  PetscCall(DMLocalToGlobal(p->dmCell, vml, INSERT_VALUES, vm));
  PetscCall(DMLocalToGlobal(p->dmCell, wl, INSERT_VALUES, wshear));
  PetscCall(DMRestoreLocalVector(p->dmCell, &vml));
  PetscCall(DMRestoreLocalVector(p->dmCell, &wl));
  PetscCall(DMRestoreLocalVector(p->dm, &yloc));
  PetscFunctionReturn(0);
}
