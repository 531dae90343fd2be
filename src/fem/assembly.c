/* assembly.c: the assembly of the stiffness K (its pattern from the mesh graph), the load b with the Dirichlet lifting,
   the lumped volumes and the energy shift. */
#include "fem/femimpl.h"

/* The stiffness (BAIJ, block size dim) with its nonzero pattern from the mesh graph: block row v couples v with the
   vertices of its cells.
   Rows of vertices shared between ranks get the counts of every rank added, an upper bound only there (the other
   ranks' cells are not local). DMCreateMatrix() and MATPREALLOCATOR cost several times the assembly itself. */
static PetscErrorCode CreateStiffness(SgElasticity p)
{
  const SgMesh   *m   = &p->mesh;
  const PetscInt  dim = p->dim, nv = dim + 1;
  PetscInt        n, N, bstart, bend, *vcoff, *vcell, *mark, *dnz, *onz;
  const PetscInt *ranges;
  PetscMPIInt     size;
  Vec             cloc, cglob;
  PetscScalar    *ca;
  PetscSection    vs;

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(p->b, &n));
  PetscCall(VecGetSize(p->b, &N));
  PetscCall(VecGetOwnershipRange(p->b, &bstart, &bend));
  bstart /= dim;
  bend /= dim;
  PetscCall(VecGetOwnershipRanges(p->b, &ranges));
  PetscCallMPI(MPI_Comm_size(p->comm, &size));
  /* vertex -> cells */
  PetscCall(PetscCalloc3(m->nv + 1, &vcoff, m->nc * nv, &vcell, m->nv, &mark));
  for (PetscInt c = 0; c < m->nc * nv; c++) vcoff[m->cellv[c] + 1]++;
  for (PetscInt v = 0; v < m->nv; v++) vcoff[v + 1] += vcoff[v];
  for (PetscInt c = 0; c < m->nc; c++)
    for (PetscInt a = 0; a < nv; a++) vcell[vcoff[m->cellv[c * nv + a]] + mark[m->cellv[c * nv + a]]++] = c;
  for (PetscInt v = 0; v < m->nv; v++) mark[v] = -1;
  /* local counts of distinct free neighbours (diagonal / off-diagonal block columns), summed over ranks */
  PetscCall(DMGetLocalVector(p->dmVec, &cloc));
  PetscCall(VecZeroEntries(cloc));
  PetscCall(DMGetLocalSection(p->dmVec, &vs));
  PetscCall(VecGetArray(cloc, &ca));
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt off, d = 0, o = 0, lo, hi, r = 0;
    if (m->gblock[v] < 0) continue;
    /* diagonal or off-diagonal block is decided by the owner of row v */
    while (r < size - 1 && m->gblock[v] * dim >= ranges[r + 1]) r++;
    lo = ranges[r] / dim;
    hi = ranges[r + 1] / dim;
    for (PetscInt k = vcoff[v]; k < vcoff[v + 1]; k++)
      for (PetscInt a = 0; a < nv; a++) {
        const PetscInt u = m->cellv[vcell[k] * nv + a], g = m->gblock[u];
        if (g < 0 || mark[u] == v) continue;
        mark[u] = v;
        if (g >= lo && g < hi) d++;
        else o++;
      }
    PetscCall(PetscSectionGetOffset(vs, m->vStart + v, &off));
    ca[off]     = d;
    ca[off + 1] = o;
  }
  PetscCall(VecRestoreArray(cloc, &ca));
  PetscCall(DMGetGlobalVector(p->dmVec, &cglob));
  PetscCall(VecZeroEntries(cglob));
  PetscCall(DMLocalToGlobal(p->dmVec, cloc, ADD_VALUES, cglob));
  PetscCall(DMGlobalToLocal(p->dmVec, cglob, INSERT_VALUES, cloc));
  PetscCall(DMRestoreGlobalVector(p->dmVec, &cglob));
  PetscCall(PetscMalloc2(n / dim, &dnz, n / dim, &onz));
  PetscCall(VecGetArray(cloc, &ca));
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt off;
    if (m->goff[v] < 0) continue; /* owned free vertices have rows here */
    PetscCall(PetscSectionGetOffset(vs, m->vStart + v, &off));
    dnz[m->goff[v] / dim] = PetscMin((PetscInt)PetscRealPart(ca[off]), bend - bstart);
    onz[m->goff[v] / dim] = PetscMin((PetscInt)PetscRealPart(ca[off + 1]), N / dim - (bend - bstart));
  }
  PetscCall(VecRestoreArray(cloc, &ca));
  PetscCall(DMRestoreLocalVector(p->dmVec, &cloc));
  PetscCall(MatCreate(p->comm, &p->K));
  PetscCall(MatSetSizes(p->K, n, n, N, N));
  PetscCall(MatSetBlockSize(p->K, dim));
  PetscCall(MatSetType(p->K, MATBAIJ)); /* blocked insertion; converted to AIJ (what MUMPS and hypre take) once assembled */
  PetscCall(MatXAIJSetPreallocation(p->K, dim, dnz, onz, NULL, NULL));
  PetscCall(MatSetOption(p->K, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PetscCall(PetscFree2(dnz, onz));
  PetscCall(PetscFree3(vcoff, vcell, mark));
  PetscFunctionReturn(0);
}

/* The element stiffness Ke of cell cv into K (block columns gb); partial: the cell has a partly fixed vertex, whose
   fixed components get their row and column decoupled, their diagonal kept (the scale of its neighbours for the
   preconditioners), so that their unknowns stay 0; their values enter by the lifting */
static PetscErrorCode AddElementStiffness(SgElasticity p, const PetscInt cv[], const PetscInt gb[], PetscBool partial, const PetscReal Ke[])
{
  const SgMesh  *m   = &p->mesh;
  const PetscInt dim = p->dim, nv = dim + 1, ne = nv * dim;
  PetscReal      Kd[144];

  PetscFunctionBeginUser;
  if (partial) {
    PetscCall(PetscArraycpy(Kd, Ke, ne * ne));
    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt i = 0; i < dim; i++) {
        const PetscInt r = a * dim + i;
        if (gb[a] < 0 || !SgMeshFixed(m, cv[a], i)) continue;
        for (PetscInt j = 0; j < ne; j++)
          if (j != r) Kd[r * ne + j] = Kd[j * ne + r] = 0;
      }
    PetscCall(MatSetValuesBlocked(p->K, nv, gb, nv, gb, Kd, ADD_VALUES));
  } else PetscCall(MatSetValuesBlocked(p->K, nv, gb, nv, gb, Ke, ADD_VALUES));
  PetscFunctionReturn(0);
}

/* The load fe of a cell (vertex coordinates xe, volume vol): the manufactured body force by the quadrature (nq points
   lq, weights wq), or the constant body force lumped to the vertices */
static PetscErrorCode ElementLoad(SgElasticity p, const PetscReal xe[], PetscReal vol, PetscInt nq, const PetscReal lq[], const PetscReal wq[], PetscReal fe[])
{
  const PetscInt dim = p->dim, nv = dim + 1, ne = nv * dim;

  PetscFunctionBeginUser;
  if (p->mms) {
    PetscCall(PetscArrayzero(fe, ne));
    for (PetscInt q = 0; q < nq; q++) {
      PetscReal xq[3] = {0, 0, 0}, f[3];
      for (PetscInt a = 0; a < nv; a++)
        for (PetscInt d = 0; d < dim; d++) xq[d] += lq[q * nv + a] * xe[a * dim + d];
      SgMMSForce(dim, p->lambda, p->mu, xq, f);
      for (PetscInt a = 0; a < nv; a++)
        for (PetscInt d = 0; d < dim; d++) fe[a * dim + d] += vol * wq[q] * lq[q * nv + a] * f[d];
    }
  } else
    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt d = 0; d < dim; d++) fe[a * dim + d] = vol / nv * p->body_force[d];
  PetscFunctionReturn(0);
}

/* The cells' part of K, of the load with the Dirichlet lifting (fa), of the lumped volumes (ma), of the unlifted load
   (pa) and of the energy shift 1/2 u_D K u_D - f u_D (added to shift); ua: the Dirichlet values (local arrays) */
static PetscErrorCode AssembleCells(SgElasticity p, const PetscScalar ua[], PetscScalar fa[], PetscScalar ma[], PetscScalar pa[], PetscReal *shift)
{
  const SgMesh  *m   = &p->mesh;
  const PetscInt dim = p->dim, nv = dim + 1, ne = nv * dim;
  PetscReal      s = *shift, *lq = NULL, *wq = NULL;
  PetscInt       nq = 0;

  PetscFunctionBeginUser;
  if (p->mms) PetscCall(SgSimplexQuadrature(dim, &nq, &lq, &wq));
  for (PetscInt c = 0; c < m->nc; c++) {
    const PetscInt *cv = &m->cellv[c * nv];
    PetscReal       xe[12], Ke[144], fe[12], ud[12], vol, lambda, mu;
    PetscInt        gb[4];
    PetscBool       lift = PETSC_FALSE, partial = PETSC_FALSE;

    for (PetscInt a = 0; a < nv; a++) {
      gb[a] = m->gblock[cv[a]];
      for (PetscInt d = 0; d < dim; d++) {
        xe[a * dim + d] = m->x[cv[a] * dim + d];
        ud[a * dim + d] = PetscRealPart(ua[m->loff[cv[a]] + d]);
      }
      if (m->bcmask[cv[a]]) lift = PETSC_TRUE;
      if (SgMeshPartial(m, cv[a])) partial = PETSC_TRUE;
    }
    SgElasticityCellLame(p, c, &lambda, &mu);
    PetscCall(SgElementStiffness(dim, xe, lambda, mu, Ke, &vol));
    PetscCall(AddElementStiffness(p, cv, gb, partial, Ke));
    PetscCall(ElementLoad(p, xe, vol, nq, lq, wq, fe));
    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt d = 0; d < dim; d++) pa[m->loff[cv[a]] + d] += fe[a * dim + d];
    if (lift) {
      for (PetscInt i = 0; i < ne; i++) {
        PetscReal Ku = 0;
        for (PetscInt j = 0; j < ne; j++) Ku += Ke[i * ne + j] * ud[j];
        s += 0.5 * ud[i] * Ku - fe[i] * ud[i];
        fe[i] -= Ku;
      }
    }
    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt d = 0; d < dim; d++) {
        fa[m->loff[cv[a]] + d] += fe[a * dim + d];
        ma[m->loff[cv[a]] + d] += vol / nv;
      }
  }
  PetscCall(PetscFree2(lq, wq));
  *shift = s;
  PetscFunctionReturn(0);
}

/* Neumann: constant traction per label value, exact P1 load on each facet (into fa, pa and shift as AssembleCells) */
static PetscErrorCode AssembleNeumann(SgElasticity p, const PetscScalar ua[], PetscScalar fa[], PetscScalar pa[], PetscReal *shift)
{
  const SgMesh  *m   = &p->mesh;
  const PetscInt dim = p->dim;
  PetscInt       nfac, *facets, *part;
  PetscReal      s = *shift;

  PetscFunctionBeginUser;
  if (!p->neumann.nvalues) PetscFunctionReturn(0);
  PetscCall(SgBoundaryGetFacets(p->dm, &p->neumann, &nfac, &facets, &part));
  for (PetscInt i = 0; i < nfac; i++) {
    PetscInt  fv[3], nfv;
    PetscReal area, nrm[3];
    PetscCall(SgFacetGeometry(p->dm, m, facets[i], &nfv, fv, &area, nrm));
    for (PetscInt a = 0; a < nfv; a++)
      for (PetscInt d = 0; d < dim; d++) {
        const PetscReal t = area / nfv * p->neumann.values[part[i] * dim + d];
        fa[m->loff[fv[a]] + d] += t;
        pa[m->loff[fv[a]] + d] += t;
        s -= t * PetscRealPart(ua[m->loff[fv[a]] + d]);
      }
  }
  PetscCall(PetscFree2(facets, part));
  *shift = s;
  PetscFunctionReturn(0);
}

/* K (converted to AIJ, with the foundation of -elasticity_rigid_shift), b and the lumped volumes summed over the ranks
   from the local floc and mloc, the energy shift from this rank's part, and the scales of K and b */
static PetscErrorCode AssembleOperators(SgElasticity p, Vec floc, Vec mloc, PetscReal shift)
{
  PetscFunctionBeginUser;
  PetscCall(MatAssemblyBegin(p->K, MAT_FINAL_ASSEMBLY));
  PetscCall(VecZeroEntries(p->b));
  PetscCall(VecZeroEntries(p->mass));
  PetscCall(DMLocalToGlobal(p->dm, floc, ADD_VALUES, p->b));
  PetscCall(DMLocalToGlobal(p->dm, mloc, ADD_VALUES, p->mass));
  PetscCall(MatAssemblyEnd(p->K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatConvert(p->K, MATAIJ, MAT_INPLACE_MATRIX, &p->K));
  if (p->rigid_shift > 0) { /* an elastic foundation of modulus eps E/L^2 holds the otherwise free rigid motions */
    Vec sh;
    PetscCall(VecDuplicate(p->mass, &sh));
    PetscCall(VecCopy(p->mass, sh));
    PetscCall(VecScale(sh, p->rigid_shift * p->E / PetscSqr(p->diam)));
    PetscCall(MatDiagonalSet(p->K, sh, ADD_VALUES));
    PetscCall(VecDestroy(&sh));
  }
  PetscCallMPI(MPI_Allreduce(&shift, &p->energy_shift, 1, MPIU_REAL, MPI_SUM, p->comm));
  PetscCall(VecNorm(p->b, NORM_2, &p->bnorm));
  /* the largest nodal force and ||K|| per vertex (Euclidean lengths, spectral norms of the vertex blocks): the scales
     of the KKT measures and the round-off estimates are then the same for the problem turned rigidly */
  PetscCall(SgVecVertexNormMax(p->b, p->dim, &p->bnorm_inf));
  PetscCall(SgMatVertexNorm(p->K, p->dim, &p->Knorm));
  PetscCall(MatSetOption(p->K, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatSetOption(p->K, MAT_SPD, PETSC_TRUE));
  PetscFunctionReturn(0);
}

/* K, b (with the Dirichlet lifting), the lumped volumes, the unlifted load of this rank's cells and facets, the energy
   shift and the near null space */
PetscErrorCode SgElasticityAssemble(SgElasticity p)
{
  const SgMesh      *m = &p->mesh;
  Vec                floc, mloc;
  const PetscScalar *ua;
  PetscScalar       *fa, *ma, *pa;
  PetscReal          shift = 0;
  PetscLogDouble     t0, t1;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(SG_Assembly, 0, 0, 0, 0));
  PetscCall(PetscTime(&t0));
  PetscCall(DMCreateGlobalVector(p->dm, &p->b));
  PetscCall(PetscObjectSetName((PetscObject)p->b, "load"));
  PetscCall(CreateStiffness(p));
  PetscCall(PetscObjectSetName((PetscObject)p->K, "K"));
  PetscCall(VecDuplicate(p->b, &p->mass));
  PetscCall(DMCreateLocalVector(p->dm, &p->ubc));
  PetscCall(DMCreateLocalVector(p->dm, &p->fpart));
  PetscCall(VecZeroEntries(p->fpart));
  PetscCall(DMGetLocalVector(p->dm, &floc));
  PetscCall(DMGetLocalVector(p->dm, &mloc));
  PetscCall(VecZeroEntries(floc));
  PetscCall(VecZeroEntries(mloc));
  PetscCall(VecZeroEntries(p->ubc));
  PetscCall(SgElasticityFillDirichletValues(p, NULL));
  PetscCall(VecGetArrayRead(p->ubc, &ua));
  PetscCall(VecGetArray(floc, &fa));
  PetscCall(VecGetArray(mloc, &ma));
  PetscCall(VecGetArray(p->fpart, &pa));
  PetscCall(AssembleCells(p, ua, fa, ma, pa, &shift));
  PetscCall(AssembleNeumann(p, ua, fa, pa, &shift));
  SgMeshZeroFixedComponents(m, p->dim, fa);
  PetscCall(VecRestoreArray(floc, &fa));
  PetscCall(VecRestoreArray(mloc, &ma));
  PetscCall(VecRestoreArray(p->fpart, &pa));
  PetscCall(VecRestoreArrayRead(p->ubc, &ua));
  PetscCall(AssembleOperators(p, floc, mloc, shift));
  PetscCall(DMRestoreLocalVector(p->dm, &floc));
  PetscCall(DMRestoreLocalVector(p->dm, &mloc));
  PetscCall(SgElasticityCreateNearNullSpace(p));
  PetscCall(PetscTime(&t1));
  p->t_assembly = t1 - t0;
  PetscCall(PetscLogEventEnd(SG_Assembly, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}
