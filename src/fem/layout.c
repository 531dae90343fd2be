/* layout.c: the P1 displacement layout: the Dirichlet vertices and components (agreed between ranks), the section and
   the flat mesh arrays (SgMesh). */
#include "fem/femimpl.h"
#include <petscsf.h>

/* A vertex shared by ranks may lie on a Dirichlet facet that only some of them hold (their cells touch the boundary
   at the vertex alone): every copy gets the union of the components fixed and, per component, the first part, so
   that the ranks agree on the layout and on which unknowns are decoupled. */
static PetscErrorCode SyncDirichletVertices(DM dm, SgMesh *m)
{
  const PetscInt dim = m->dim, ns = 1 + dim, big = PETSC_MAX_INT / 4;
  PetscSF        sf;
  PetscInt       pStart, pEnd, np, nchanged = 0, *a, *b;
  PetscMPIInt    size;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)dm), &size));
  if (size == 1) PetscFunctionReturn(0);
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  np = pEnd - pStart;
  /* per point, in ns arrays of np: the first part of any component (bcgroup) and of each component, "none" as big;
     the minimum over the copies (the parts are numbered in the order they are marked) */
  PetscCall(PetscMalloc2(ns * np, &a, ns * np, &b));
  for (PetscInt i = 0; i < ns * np; i++) a[i] = big;
  for (PetscInt v = 0; v < m->nv; v++) {
    const PetscInt p = m->vStart + v - pStart;
    a[p]             = m->bcgroup[v] >= 0 ? m->bcgroup[v] : big;
    for (PetscInt d = 0; d < dim; d++) a[(1 + d) * np + p] = m->bcpart[v * dim + d] >= 0 ? m->bcpart[v * dim + d] : big;
  }
  PetscCall(PetscArraycpy(b, a, ns * np));
  for (PetscInt k = 0; k < ns; k++) {
    PetscCall(PetscSFReduceBegin(sf, MPIU_INT, a + k * np, b + k * np, MPI_MIN));
    PetscCall(PetscSFReduceEnd(sf, MPIU_INT, a + k * np, b + k * np, MPI_MIN));
    PetscCall(PetscSFBcastBegin(sf, MPIU_INT, b + k * np, b + k * np, MPI_REPLACE));
    PetscCall(PetscSFBcastEnd(sf, MPIU_INT, b + k * np, b + k * np, MPI_REPLACE));
  }
  for (PetscInt v = 0; v < m->nv; v++) {
    const PetscInt p    = m->vStart + v - pStart;
    PetscInt       mask = 0;
    for (PetscInt d = 0; d < dim; d++) {
      const PetscInt g       = b[(1 + d) * np + p];
      m->bcpart[v * dim + d] = g < big ? g : -1;
      if (g < big) mask |= 1 << d;
    }
    if (mask != m->bcmask[v]) nchanged++;
    m->bcmask[v]  = mask;
    m->bcgroup[v] = b[p] < big ? b[p] : -1;
  }
  PetscCall(PetscFree2(a, b));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nchanged, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)dm)));
  PetscCall(PetscInfo(dm, "%" PetscInt_FMT " copies of shared Dirichlet vertices completed from other ranks\n", nchanged));
  PetscFunctionReturn(0);
}

/* Build the P1 displacement section (dim dofs per vertex, Dirichlet vertices constrained) and the flat mesh arrays. */
PetscErrorCode SgMeshSetUp(DM dm, const SgBoundary *dirichlet, SgMesh *m)
{
  PetscSection       s, gs, cs;
  PetscInt           pStart, pEnd, vEnd, cEnd, dim;
  Vec                cl;
  const PetscScalar *ca;
  PetscInt           cidx[3] = {0, 1, 2};

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(m, sizeof(*m)));
  PetscCall(DMGetDimension(dm, &dim));
  m->dim = dim;
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &m->vStart, &vEnd));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &m->cStart, &cEnd));
  m->nv = vEnd - m->vStart;
  m->nc = cEnd - m->cStart;
  PetscCall(PetscMalloc6(m->nc * (dim + 1), &m->cellv, m->nv * dim, &m->x, m->nv, &m->gblock, m->nv, &m->loff, m->nv, &m->goff, m->nv, &m->bcgroup));
  PetscCall(PetscCalloc2(m->nv, &m->bcmask, m->nv * dim, &m->bcpart));
  for (PetscInt v = 0; v < m->nv; v++) m->bcgroup[v] = -1;
  for (PetscInt i = 0; i < m->nv * dim; i++) m->bcpart[i] = -1;

  /* Dirichlet vertices: closure of the labelled points */
  PetscCall(SgBoundaryMarkVertices(dm, dirichlet, m));
  PetscCall(SyncDirichletVertices(dm, m));

  PetscCall(PetscSectionCreate(PetscObjectComm((PetscObject)dm), &s));
  PetscCall(PetscSectionSetNumFields(s, 1));
  PetscCall(PetscSectionSetFieldName(s, 0, "displacement"));
  PetscCall(PetscSectionSetFieldComponents(s, 0, dim));
  PetscCall(PetscSectionSetChart(s, pStart, pEnd));
  for (PetscInt v = m->vStart; v < vEnd; v++) {
    PetscCall(PetscSectionSetDof(s, v, dim));
    PetscCall(PetscSectionSetFieldDof(s, v, 0, dim));
    if (m->bcmask[v - m->vStart] == (1 << dim) - 1) { /* partly fixed vertices keep their block (see bcmask) */
      PetscCall(PetscSectionSetConstraintDof(s, v, dim));
      PetscCall(PetscSectionSetFieldConstraintDof(s, v, 0, dim));
    }
  }
  PetscCall(PetscSectionSetUp(s));
  for (PetscInt v = m->vStart; v < vEnd; v++)
    if (m->bcmask[v - m->vStart] == (1 << dim) - 1) {
      PetscCall(PetscSectionSetConstraintIndices(s, v, cidx));
      PetscCall(PetscSectionSetFieldConstraintIndices(s, v, 0, cidx));
    }
  PetscCall(DMSetLocalSection(dm, s));
  PetscCall(PetscSectionDestroy(&s));
  PetscCall(DMGetLocalSection(dm, &s));
  PetscCall(DMGetGlobalSection(dm, &gs));

  {
    PetscInt rstart, gdof, goff;
    Vec      g;

    PetscCall(DMGetGlobalVector(dm, &g));
    PetscCall(VecGetOwnershipRange(g, &rstart, NULL));
    PetscCall(VecGetSize(g, &m->nfree_glob));
    m->nfree_glob /= dim;
    PetscCall(DMRestoreGlobalVector(dm, &g));
    for (PetscInt v = m->vStart; v < vEnd; v++) {
      const PetscInt i = v - m->vStart;
      PetscCall(PetscSectionGetOffset(s, v, &m->loff[i]));
      PetscCall(PetscSectionGetDof(gs, v, &gdof));
      PetscCall(PetscSectionGetOffset(gs, v, &goff));
      if (gdof >= 0) m->nowned++; /* owned (possibly constrained: gdof 0) */
      if (m->bcmask[i] == (1 << dim) - 1) {
        m->gblock[i] = -1;
        m->goff[i]   = -1;
      } else {
        if (goff < 0) goff = -(goff + 1);
        m->gblock[i] = goff / dim;
        m->goff[i]   = gdof > 0 ? goff - rstart : -1;
      }
    }
  }

  PetscCall(DMGetCoordinatesLocal(dm, &cl));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(VecGetArrayRead(cl, &ca));
  for (PetscInt v = m->vStart; v < vEnd; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(cs, v, &off));
    for (PetscInt d = 0; d < dim; d++) m->x[(v - m->vStart) * dim + d] = PetscRealPart(ca[off + d]);
  }
  PetscCall(VecRestoreArrayRead(cl, &ca));

  for (PetscInt c = m->cStart; c < cEnd; c++) {
    PetscInt *clo = NULL, ncl, k = 0;
    PetscCall(DMPlexGetTransitiveClosure(dm, c, PETSC_TRUE, &ncl, &clo));
    for (PetscInt q = 0; q < 2 * ncl; q += 2)
      if (clo[q] >= m->vStart && clo[q] < vEnd) m->cellv[(c - m->cStart) * (dim + 1) + k++] = clo[q] - m->vStart;
    PetscCall(DMPlexRestoreTransitiveClosure(dm, c, PETSC_TRUE, &ncl, &clo));
    PetscCheck(k == dim + 1, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "cell %" PetscInt_FMT " has %" PetscInt_FMT " vertices: not a simplex", c, k);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SgMeshDestroy(SgMesh *m)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree6(m->cellv, m->x, m->gblock, m->loff, m->goff, m->bcgroup));
  PetscCall(PetscFree2(m->bcmask, m->bcpart));
  PetscFunctionReturn(0);
}
