/* assembly.c: the assembly of the stiffness K (its pattern from the mesh graph), the load b with the Dirichlet lifting,
   the lumped volumes and the energy shift. */
#include "fem/femimpl.h"

/* The pattern of K's owned block rows from this rank's cells: block row r (owned, from 0) couples with the block
   columns bj[bi[r] .. bi[r+1]-1], in increasing order. On one rank K is filled through it (AddElementStiffness). */
typedef struct {
  PetscInt    *bi, *bj;
  PetscScalar *a; /* K's values (one rank: the whole pattern, rows of equal length within a block row) */
} KPattern;

/* The stiffness (AIJ, block size dim) with its nonzero pattern from the mesh graph: block row v couples v with the
   vertices of its cells.
   Rows of vertices shared between ranks get the counts of every rank added, an upper bound only there (the other
   ranks' cells are not local). DMCreateMatrix() and MATPREALLOCATOR cost several times the assembly itself.
   K was BAIJ, converted to AIJ (what MUMPS and hypre take) once assembled: the conversion took 65-95 % of the
   assembly at 1.1e6 unknowns and held two copies of K for a moment. AIJ's own insertion (MatSetValues) finds every
   scalar entry anew and took longer than both; so on one rank the pattern is set whole (sorted rows, zeros) and the
   cells add into K's values directly (*kp, AddElementStiffness), and on more ranks the owned rows' pattern is put in
   first (each row in increasing order, so that no insertion moves a row's tail). Either way every entry gets the same
   values in the same order of the cells as before (0 + a value is that value): the same K to the bit on one rank; on
   more ranks the other ranks' parts of a shared row are summed among themselves before they are added (PETSc's stash),
   in an order that differs from BAIJ's block stash by round-off (1 ulp seen in shared rows). */
static PetscErrorCode CreateStiffness(SgElasticity p, KPattern *kp)
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
  PetscCall(MatSetType(p->K, MATAIJ));
  { /* the owned block rows' neighbours, sorted */
    PetscInt nown = 0, nnzb = 0;
    for (PetscInt v = 0; v < m->nv; v++)
      if (m->goff[v] >= 0) nown++;
    PetscCheck(nown == bend - bstart, PETSC_COMM_SELF, PETSC_ERR_PLIB, "owned free vertices %" PetscInt_FMT " != block rows %" PetscInt_FMT, nown, bend - bstart);
    PetscCall(PetscCalloc1(nown + 1, &kp->bi));
    for (PetscInt v = 0; v < m->nv; v++) mark[v] = -1;
    for (PetscInt v = 0; v < m->nv; v++) {
      if (m->goff[v] < 0) continue;
      for (PetscInt k = vcoff[v]; k < vcoff[v + 1]; k++)
        for (PetscInt a = 0; a < nv; a++) {
          const PetscInt u = m->cellv[vcell[k] * nv + a];
          if (m->gblock[u] < 0 || mark[u] == v) continue;
          mark[u] = v;
          kp->bi[m->gblock[v] - bstart + 1]++;
        }
    }
    for (PetscInt r = 0; r < nown; r++) kp->bi[r + 1] += kp->bi[r];
    nnzb = kp->bi[nown];
    PetscCall(PetscMalloc1(nnzb + 1, &kp->bj));
    for (PetscInt v = 0; v < m->nv; v++) mark[v] = -1;
    for (PetscInt v = 0; v < m->nv; v++) {
      const PetscInt r  = m->goff[v] < 0 ? -1 : m->gblock[v] - bstart;
      PetscInt       nb = 0;
      if (r < 0) continue;
      for (PetscInt k = vcoff[v]; k < vcoff[v + 1]; k++)
        for (PetscInt a = 0; a < nv; a++) {
          const PetscInt u = m->cellv[vcell[k] * nv + a];
          if (m->gblock[u] < 0 || mark[u] == v) continue;
          mark[u]                  = v;
          kp->bj[kp->bi[r] + nb++] = m->gblock[u];
        }
      PetscCall(PetscSortInt(nb, kp->bj + kp->bi[r]));
    }
  }
  if (size == 1) { /* the exact row lengths, then the whole pattern, each block row's scalar rows in one call */
    const PetscInt nb = bend - bstart;
    PetscInt      *len, *cols, nmax = 0;
    PetscScalar   *zero;
    PetscCall(PetscMalloc1(n + 1, &len));
    for (PetscInt r = 0; r < nb; r++) {
      nmax = PetscMax(nmax, kp->bi[r + 1] - kp->bi[r]);
      for (PetscInt i = 0; i < dim; i++) len[r * dim + i] = (kp->bi[r + 1] - kp->bi[r]) * dim;
    }
    PetscCall(MatSeqAIJSetPreallocation(p->K, 0, len));
    PetscCall(PetscFree(len));
    PetscCall(MatSetOption(p->K, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
    PetscCall(PetscCalloc2(nmax * dim + 1, &cols, nmax * dim * dim + 1, &zero));
    for (PetscInt r = 0; r < nb; r++) {
      PetscInt rows[3], nc = kp->bi[r + 1] - kp->bi[r];
      for (PetscInt k = 0; k < nc; k++)
        for (PetscInt j = 0; j < dim; j++) cols[k * dim + j] = kp->bj[kp->bi[r] + k] * dim + j;
      for (PetscInt i = 0; i < dim; i++) rows[i] = r * dim + i;
      PetscCall(MatSetValues(p->K, dim, rows, nc * dim, cols, zero, INSERT_VALUES));
    }
    PetscCall(PetscFree2(cols, zero));
    PetscCall(MatAssemblyBegin(p->K, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(p->K, MAT_FINAL_ASSEMBLY));
    PetscCall(MatSeqAIJGetArray(p->K, &kp->a));
  } else { /* the owned rows' pattern, each row in increasing order */
    PetscInt    *cols, nmax = 0;
    PetscScalar *zero;
    PetscCall(MatXAIJSetPreallocation(p->K, dim, dnz, onz, NULL, NULL));
    PetscCall(MatSetOption(p->K, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
    for (PetscInt r = 0; r < bend - bstart; r++) nmax = PetscMax(nmax, kp->bi[r + 1] - kp->bi[r]);
    PetscCall(PetscCalloc2(nmax * dim + 1, &cols, nmax * dim * dim + 1, &zero));
    for (PetscInt r = 0; r < bend - bstart; r++) {
      PetscInt rows[3], nb = kp->bi[r + 1] - kp->bi[r];
      for (PetscInt k = 0; k < nb; k++)
        for (PetscInt j = 0; j < dim; j++) cols[k * dim + j] = kp->bj[kp->bi[r] + k] * dim + j;
      for (PetscInt i = 0; i < dim; i++) rows[i] = (bstart + r) * dim + i;
      PetscCall(MatSetValues(p->K, dim, rows, nb * dim, cols, zero, ADD_VALUES));
    }
    PetscCall(PetscFree2(cols, zero));
  }
  PetscCall(PetscFree2(dnz, onz));
  PetscCall(PetscFree3(vcoff, vcell, mark));
  PetscFunctionReturn(0);
}

/* The element stiffness Ke of cell cv into K (block columns gb); partial: the cell has a partly fixed vertex, whose
   fixed components get their row and column decoupled, their diagonal kept (the scale of its neighbours for the
   preconditioners), so that their unknowns stay 0; their values enter by the lifting. One rank: added into K's
   values at the places the pattern kp gives (each block row's scalar rows have the same columns) */
static PetscErrorCode AddElementStiffness(SgElasticity p, const KPattern *kp, const PetscInt cv[], const PetscInt gb[], PetscBool partial, const PetscReal Ke[])
{
  const SgMesh    *m   = &p->mesh;
  const PetscInt   dim = p->dim, nv = dim + 1, ne = nv * dim;
  PetscReal        Kd[144];
  const PetscReal *Ka = Ke;

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
    Ka = Kd;
  }
  if (!kp->a) {
    PetscCall(MatSetValuesBlocked(p->K, nv, gb, nv, gb, Ka, ADD_VALUES));
    PetscFunctionReturn(0);
  }
  for (PetscInt a = 0; a < nv; a++) {
    const PetscInt r = gb[a], lo = r < 0 ? 0 : kp->bi[r], L = r < 0 ? 0 : (kp->bi[r + 1] - lo) * dim;
    if (r < 0) continue;
    for (PetscInt b = 0; b < nv; b++) {
      PetscInt     k;
      PetscScalar *row;
      if (gb[b] < 0) continue;
      PetscCall(PetscFindInt(gb[b], kp->bi[r + 1] - lo, kp->bj + lo, &k));
      PetscCheck(k >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "block column %" PetscInt_FMT " not in the pattern of block row %" PetscInt_FMT, gb[b], r);
      row = kp->a + lo * dim * dim + k * dim;
      for (PetscInt i = 0; i < dim; i++)
        for (PetscInt j = 0; j < dim; j++) row[i * L + j] += Ka[(a * dim + i) * ne + b * dim + j];
    }
  }
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
static PetscErrorCode AssembleCells(SgElasticity p, const KPattern *kp, const PetscScalar ua[], PetscScalar fa[], PetscScalar ma[], PetscScalar pa[], PetscReal *shift)
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
    PetscCall(AddElementStiffness(p, kp, cv, gb, partial, Ke));
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

/* K (with the foundation of -elasticity_rigid_shift), b and the lumped volumes summed over the ranks
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
  PetscCall(SgVecVertexNormMax(p->b, SgNodalNormSize(p), &p->bnorm_inf));
  PetscCall(SgMatVertexNorm(p->K, SgNodalNormSize(p), &p->Knorm));
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
  KPattern           kp = {NULL, NULL, NULL};

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(SG_Assembly, 0, 0, 0, 0));
  PetscCall(PetscTime(&t0));
  PetscCall(DMCreateGlobalVector(p->dm, &p->b));
  PetscCall(PetscObjectSetName((PetscObject)p->b, "load"));
  PetscCall(CreateStiffness(p, &kp));
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
  PetscCall(AssembleCells(p, &kp, ua, fa, ma, pa, &shift));
  if (kp.a) PetscCall(MatSeqAIJRestoreArray(p->K, &kp.a));
  PetscCall(PetscFree(kp.bi));
  PetscCall(PetscFree(kp.bj));
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
