/* forces.c: the forces at a displacement, for the KKT measures: reactions on the Dirichlet part, support forces and
   loads, the scales of the data, and the residual on the fixed components of partly fixed vertices. */
#include "fem/femimpl.h"

/* The element force K_e u_e of cell c (nv dim numbers, vertex by vertex) at the local displacement ya, and the cell's
   volume: the support and reaction forces below are sums of these over the cells at fixed components. */
static PetscErrorCode CellForce(SgElasticity p, PetscInt c, const PetscScalar ya[], PetscReal fe[], PetscReal *vol)
{
  const SgMesh   *m   = &p->mesh;
  const PetscInt  dim = p->dim, nv = dim + 1, ne = nv * dim;
  const PetscInt *cv = &m->cellv[c * nv];
  PetscReal       xe[12], Ke[144], ue[12], lambda, mu;

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < nv; a++)
    for (PetscInt d = 0; d < dim; d++) {
      xe[a * dim + d] = m->x[cv[a] * dim + d];
      ue[a * dim + d] = PetscRealPart(ya[m->loff[cv[a]] + d]);
    }
  SgElasticityCellLame(p, c, &lambda, &mu);
  PetscCall(SgElementStiffness(dim, xe, lambda, mu, Ke, vol));
  for (PetscInt i = 0; i < ne; i++) {
    fe[i] = 0;
    for (PetscInt j = 0; j < ne; j++) fe[i] += Ke[i * ne + j] * ue[j];
  }
  PetscFunctionReturn(0);
}

/* Total reaction force on the Dirichlet vertices, sum_D (K u - f)_D (u with its Dirichlet values). With the contact
   forces it balances the loads: R = sum_i w_i lam_i n_i - sum f. */
PetscErrorCode SgElasticityReaction(SgElasticity p, Vec y, PetscReal R[3])
{
  const SgMesh      *m   = &p->mesh;
  const PetscInt     dim = p->dim, nv = dim + 1;
  Vec                yloc;
  const PetscScalar *ya;
  PetscReal          loc[3] = {0, 0, 0};

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(p->dm, &yloc));
  PetscCall(SgElasticityGlobalToLocal(p, y, yloc));
  PetscCall(VecGetArrayRead(yloc, &ya));
  /* every cell is on exactly one rank, so the element sums need no ownership bookkeeping */
  for (PetscInt c = 0; c < m->nc; c++) {
    const PetscInt *cv = &m->cellv[c * nv];
    PetscReal       fe[12], vol;
    PetscBool       has = PETSC_FALSE;

    for (PetscInt a = 0; a < nv; a++) has = (PetscBool)(has || m->bcmask[cv[a]]);
    if (!has) continue;
    PetscCall(CellForce(p, c, ya, fe, &vol));
    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt i = 0; i < dim; i++)
        if (SgMeshFixed(m, cv[a], i)) loc[i] += fe[a * dim + i] - vol / nv * p->body_force[i];
  }
  PetscCall(VecRestoreArrayRead(yloc, &ya));
  PetscCall(DMRestoreLocalVector(p->dm, &yloc));
  if (p->neumann.nvalues) { /* traction on the Neumann facets' Dirichlet vertices */
    PetscInt nfac, *facets, *part;
    PetscCall(SgBoundaryGetFacets(p->dm, &p->neumann, &nfac, &facets, &part));
    for (PetscInt f = 0; f < nfac; f++) {
      PetscInt  fv[3], nfv;
      PetscReal area, nrm[3];
      PetscCall(SgFacetGeometry(p->dm, m, facets[f], &nfv, fv, &area, nrm));
      for (PetscInt a = 0; a < nfv; a++)
        for (PetscInt d = 0; d < dim; d++)
          if (SgMeshFixed(m, fv[a], d)) loc[d] -= area / nfv * p->neumann.values[part[f] * dim + d];
    }
    PetscCall(PetscFree2(facets, part));
  }
  PetscCallMPI(MPI_Allreduce(loc, R, 3, MPIU_REAL, MPI_SUM, p->comm));
  PetscFunctionReturn(0);
}

/* The forces on the body at the displacement y (free dofs), for the force scale and the force balance of the KKT
   measures (SgContactKKT): fmax the largest nodal load on the free dofs, smax the largest nodal support force (K u - f
   on the Dirichlet-fixed components, and the elastic foundation of -elasticity_rigid_shift), fsum the resultant of
   loads and support forces on the body, fl1 the sum of their nodal magnitudes. A nodal force is the Euclidean length
   of a vertex's force vector (not its largest component), so that all of them are the same for the problem turned
   rigidly (SgVecVertexNormMax). Only the cells at the Dirichlet part are visited: the cost of the measures stays that
   of a product with K. */
PetscErrorCode SgElasticityForces(SgElasticity p, Vec y, PetscReal *fmax, PetscReal *smax, PetscReal fsum[3], PetscReal *fl1)
{
  const SgMesh      *m   = &p->mesh;
  const PetscInt     dim = p->dim, nv = dim + 1, nd = SgNodalNormSize(p);
  Vec                yloc, sloc, sg, fg;
  const PetscScalar *ya, *pa, *fa;
  PetscScalar       *sa;
  PetscSection       vs;
  PetscReal          loc[7] = {0, 0, 0, 0, 0, 0, 0}, nrm[4];

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(p->dm, &yloc));
  PetscCall(SgElasticityGlobalToLocal(p, y, yloc));
  PetscCall(DMGetLocalSection(p->dmVec, &vs));
  PetscCall(DMGetLocalVector(p->dmVec, &sloc));
  PetscCall(VecZeroEntries(sloc));
  PetscCall(VecGetArrayRead(yloc, &ya));
  PetscCall(VecGetArrayRead(p->fpart, &pa));
  PetscCall(VecGetArray(sloc, &sa));
  /* support forces: every cell is on exactly one rank and fpart holds this rank's cells' and facets' loads, so the
     parts of a vertex shared by ranks add up to its force */
  for (PetscInt c = 0; c < m->nc; c++) {
    const PetscInt *cv = &m->cellv[c * nv];
    PetscReal       fe[12], vol;
    PetscBool       has = PETSC_FALSE;

    for (PetscInt a = 0; a < nv; a++) has = (PetscBool)(has || m->bcmask[cv[a]]);
    if (!has) continue;
    PetscCall(CellForce(p, c, ya, fe, &vol));
    for (PetscInt a = 0; a < nv; a++) {
      PetscInt off;
      if (!m->bcmask[cv[a]]) continue;
      PetscCall(PetscSectionGetOffset(vs, m->vStart + cv[a], &off));
      for (PetscInt i = 0; i < dim; i++)
        if (SgMeshFixed(m, cv[a], i)) sa[off + i] += fe[a * dim + i];
    }
  }
  /* K u = f + s on a fixed component: the support force on the body s = K u - f; with the load f there the
     resultant gains K u */
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt off;
    if (!m->bcmask[v]) continue;
    PetscCall(PetscSectionGetOffset(vs, m->vStart + v, &off));
    for (PetscInt d = 0; d < dim; d++)
      if (SgMeshFixed(m, v, d)) {
        loc[d] += PetscRealPart(sa[off + d]);
        sa[off + d] -= PetscRealPart(pa[m->loff[v] + d]);
      }
  }
  PetscCall(VecRestoreArray(sloc, &sa));
  PetscCall(VecRestoreArrayRead(p->fpart, &pa));
  PetscCall(VecRestoreArrayRead(yloc, &ya));
  PetscCall(DMRestoreLocalVector(p->dm, &yloc));
  PetscCall(DMGetGlobalVector(p->dmVec, &sg));
  PetscCall(VecZeroEntries(sg));
  PetscCall(DMLocalToGlobal(p->dmVec, sloc, ADD_VALUES, sg));
  PetscCall(DMRestoreLocalVector(p->dmVec, &sloc));
  PetscCall(SgVecVertexNormMax(sg, nd, &nrm[0]));
  PetscCall(SgVecVertexNormSum(sg, nd, &nrm[1]));
  PetscCall(DMRestoreGlobalVector(p->dmVec, &sg));
  /* the loads on the free dofs (those on the fixed components went into the support forces) */
  PetscCall(DMGetGlobalVector(p->dm, &fg));
  PetscCall(VecZeroEntries(fg));
  PetscCall(DMLocalToGlobal(p->dm, p->fpart, ADD_VALUES, fg));
  if (m->nfree_glob) {
    PetscScalar *ga;
    PetscCall(VecGetArray(fg, &ga));
    for (PetscInt v = 0; v < m->nv; v++)
      if (m->goff[v] >= 0 && SgMeshPartial(m, v))
        for (PetscInt d = 0; d < dim; d++)
          if (SgMeshFixed(m, v, d)) ga[m->goff[v] + d] = 0;
    for (PetscInt v = 0; v < m->nv; v++)
      if (m->goff[v] >= 0)
        for (PetscInt d = 0; d < dim; d++) loc[3 + d] += PetscRealPart(ga[m->goff[v] + d]);
    PetscCall(VecRestoreArray(fg, &ga));
  }
  PetscCall(SgVecVertexNormMax(fg, nd, &nrm[2]));
  PetscCall(SgVecVertexNormSum(fg, nd, &nrm[3]));
  if (p->rigid_shift > 0) { /* the foundation's force -k M y on the body is a support force */
    const PetscReal k   = p->rigid_shift * p->E / PetscSqr(p->diam);
    PetscReal       fmx = 0;
    PetscCall(VecPointwiseMult(fg, p->mass, y));
    PetscCall(VecGetArrayRead(fg, &fa));
    for (PetscInt v = 0; v < m->nv; v++)
      if (m->goff[v] >= 0) {
        PetscReal f2 = 0;
        for (PetscInt d = 0; d < dim; d++) {
          const PetscReal fd = k * PetscRealPart(fa[m->goff[v] + d]);
          loc[d] -= fd;
          if (nd > 1) f2 += PetscSqr(fd); /* -contact_kkt_scale vertex: the nodal force's length */
          else {
            loc[6] += PetscAbsReal(fd);
            fmx = PetscMax(fmx, PetscAbsReal(fd));
          }
        }
        if (nd > 1) {
          loc[6] += PetscSqrtReal(f2);
          fmx = PetscMax(fmx, PetscSqrtReal(f2));
        }
      }
    PetscCall(VecRestoreArrayRead(fg, &fa));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &fmx, 1, MPIU_REAL, MPI_MAX, p->comm));
    nrm[0] = PetscMax(nrm[0], fmx);
  }
  PetscCall(DMRestoreGlobalVector(p->dm, &fg));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, loc, 7, MPIU_REAL, MPI_SUM, p->comm));
  if (fmax) *fmax = nrm[2];
  if (smax) *smax = nrm[0];
  for (PetscInt d = 0; fsum && d < 3; d++) fsum[d] = d < dim ? loc[d] + loc[3 + d] : 0;
  if (fl1) *fl1 = nrm[1] + nrm[3] + loc[6];
  PetscFunctionReturn(0);
}

/* Displacement and force scales of the data, for the KKT measures when the displacement is (nearly) zero: the largest
   Dirichlet value now (ucur) and at factor 1 (ufull: the values given, whatever the load factor or the values set per
   step), ||b||_inf at factor 1 (bfull: the largest nodal force, with the lifting of the Dirichlet values), the total
   load at factor 1 (floads: ||f||_1 on the free dofs, without that lifting) and the diameter of the mesh. Values and
   forces per vertex as Euclidean lengths (the same for the problem turned rigidly; SgVecVertexNormMax). */
PetscErrorCode SgElasticityGetDataScales(SgElasticity p, PetscReal *ucur, PetscReal *ufull, PetscReal *bfull, PetscReal *floads, PetscReal *diam)
{
  PetscReal u[2] = {0, 0};
  Vec       fg;

  PetscFunctionBeginUser;
  PetscCall(SgVecVertexNormMax(p->ubc, SgNodalNormSize(p), &u[0])); /* local vectors: this rank's, the maximum below */
  PetscCall(SgVecVertexNormMax(p->ubc1 ? p->ubc1 : p->ubc, SgNodalNormSize(p), &u[1]));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, u, 2, MPIU_REAL, MPI_MAX, p->comm));
  if (ucur) *ucur = u[0];
  if (ufull) *ufull = u[1];
  if (bfull) *bfull = p->b1 ? p->bnorm_inf1 : p->bnorm_inf;
  if (floads) {
    PetscCall(DMGetGlobalVector(p->dm, &fg));
    PetscCall(VecZeroEntries(fg));
    PetscCall(DMLocalToGlobal(p->dm, p->fpart1 ? p->fpart1 : p->fpart, ADD_VALUES, fg));
    PetscCall(SgVecVertexNormSum(fg, SgNodalNormSize(p), floads));
    PetscCall(DMRestoreGlobalVector(p->dm, &fg));
  }
  if (diam) *diam = p->diam;
  PetscFunctionReturn(0);
}

/* The reactions on the fixed components of partly fixed vertices: R (a global vector like y) holds (K u - f) there, u
   the full displacement (the Dirichlet values on those components) and K, f unconstrained; 0 elsewhere. With the
   contact and friction forces (which the free components balance) they are what holds a vertex whose tangential
   motion is prescribed (friction with prescribed slip, SgContactKKT). */
PetscErrorCode SgElasticityFixedResidual(SgElasticity p, Vec y, Vec R)
{
  const SgMesh      *m   = &p->mesh;
  const PetscInt     dim = p->dim, nv = dim + 1;
  Vec                yloc, rloc;
  const PetscScalar *ya, *fa;
  PetscScalar       *ra;

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(R));
  PetscCall(DMGetLocalVector(p->dm, &yloc));
  PetscCall(DMGetLocalVector(p->dm, &rloc));
  PetscCall(SgElasticityGlobalToLocal(p, y, yloc));
  PetscCall(VecZeroEntries(rloc));
  PetscCall(VecGetArrayRead(yloc, &ya));
  PetscCall(VecGetArrayRead(p->fpart, &fa));
  PetscCall(VecGetArray(rloc, &ra));
  for (PetscInt c = 0; c < m->nc; c++) {
    const PetscInt *cv = &m->cellv[c * nv];
    PetscReal       fe[12], vol;
    PetscBool       has = PETSC_FALSE;

    for (PetscInt a = 0; a < nv; a++) has = (PetscBool)(has || SgMeshPartial(m, cv[a]));
    if (!has) continue;
    PetscCall(CellForce(p, c, ya, fe, &vol));
    for (PetscInt a = 0; a < nv; a++) {
      if (!SgMeshPartial(m, cv[a])) continue;
      for (PetscInt i = 0; i < dim; i++)
        if (SgMeshFixed(m, cv[a], i)) ra[m->loff[cv[a]] + i] += fe[a * dim + i];
    }
  }
  /* the loads of this rank's cells and facets (the unlifted load): subtracted once per local copy */
  for (PetscInt v = 0; v < m->nv; v++)
    if (SgMeshPartial(m, v))
      for (PetscInt d = 0; d < dim; d++)
        if (SgMeshFixed(m, v, d)) ra[m->loff[v] + d] -= fa[m->loff[v] + d];
  PetscCall(VecRestoreArray(rloc, &ra));
  PetscCall(VecRestoreArrayRead(p->fpart, &fa));
  PetscCall(VecRestoreArrayRead(yloc, &ya));
  PetscCall(DMLocalToGlobal(p->dm, rloc, ADD_VALUES, R));
  PetscCall(DMRestoreLocalVector(p->dm, &yloc));
  PetscCall(DMRestoreLocalVector(p->dm, &rloc));
  PetscFunctionReturn(0);
}

/* The displacement that, times ||K|| (the stiffest material's), bounds an elastic nodal force: the largest over the
   vertices of (E_v / E) |y_v|, with E_v the largest E of the cells at v, E the stiffest material's
   (SgElasticityGetMaterial) and |y_v| the length of the vertex's nd unknowns as in SgVecVertexNormMax (a fixed
   component counts 0, as its unknown is). With one material it is ynorm, the caller's SgVecVertexNormMax(y, nd),
   not formed again. ||K|| times the largest |y_v| alone put the stiff body's stiffness against the soft body's
   displacement: two bodies of E 1e8 and 1, the soft one moved 1e-2, gave a force scale 1e6 times every force of the
   problem, and a KKT test that passed 15 % of the contact force left as tension at one vertex. Each cell is on one rank, so the largest over the ranks is the same on
   any partition. */
PetscErrorCode SgElasticityStiffnessDisplacementMax(SgElasticity p, Vec y, PetscInt nd, PetscReal ynorm, PetscReal *s)
{
  const SgMesh      *m   = &p->mesh;
  const PetscInt     dim = p->dim, nv = dim + 1;
  Vec                yloc;
  const PetscScalar *ya;
  PetscReal         *fv, mx = 0;

  PetscFunctionBeginUser;
  if (!p->cellmat) {
    *s = ynorm;
    PetscFunctionReturn(0);
  }
  PetscCall(PetscCalloc1(m->nv, &fv));
  for (PetscInt c = 0; c < m->nc; c++)
    for (PetscInt a = 0; a < nv; a++) fv[m->cellv[c * nv + a]] = PetscMax(fv[m->cellv[c * nv + a]], p->matE[p->cellmat[c]] / p->E);
  PetscCall(DMGetLocalVector(p->dm, &yloc));
  PetscCall(SgElasticityGlobalToLocal(p, y, yloc));
  PetscCall(VecGetArrayRead(yloc, &ya));
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscReal l2 = 0;
    for (PetscInt d = 0; d < dim; d++) {
      const PetscReal u = SgMeshFixed(m, v, d) ? 0 : PetscAbsReal(PetscRealPart(ya[m->loff[v] + d]));
      if (nd > 1) l2 += u * u;
      else mx = PetscMax(mx, fv[v] * u);
    }
    if (nd > 1) mx = PetscMax(mx, fv[v] * PetscSqrtReal(l2));
  }
  PetscCall(VecRestoreArrayRead(yloc, &ya));
  PetscCall(DMRestoreLocalVector(p->dm, &yloc));
  PetscCall(PetscFree(fv));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &mx, 1, MPIU_REAL, MPI_MAX, p->comm));
  *s = mx;
  PetscFunctionReturn(0);
}
