/* assembly.c: the assembly of the stiffness K (its pattern from the mesh graph), the load b with the Dirichlet lifting,
   the lumped volumes and the energy shift. */
#include "fem/femimpl.h"

/* Where the cells add K's values. Local block row r (a free local vertex v: r = row[v]; one rank: r = its global
   block row; more ranks: the owned vertices first, in global order, then the ghost ones) couples with the global block
   columns bj[bi[r] .. bi[r+1]-1], in increasing order. The first nlo[r] of them and those after the next nd[r] go to
   the scalar rows at vb[r] (stride Lb[r] from one scalar row of the block row to the next), the nd[r] in between to
   those at va[r] (stride La[r]): on more ranks the owned rows' values are K's off-diagonal and diagonal parts
   themselves (the columns below this rank's, its own, those above), the ghost rows' a buffer (all at va) that goes to
   their owners once the cells are done; one rank: K's values, all at va. */
typedef struct {
  PetscBool     ranks;      /* several ranks: K's two parts and the ghost buffer */
  PetscInt      nown, nrow; /* owned block rows, all local block rows (ghost rows after the owned) */
  PetscInt     *row, *bi, *bj, *nlo, *nd, *La, *Lb;
  PetscScalar **va, **vb;
  PetscScalar  *ghost;   /* the ghost rows' values */
  PetscScalar  *aa, *ba; /* one rank: K's values; more ranks: those of its diagonal and off-diagonal parts */
} KPattern;

/* the sizes of K's rows on this rank: n of N rows, the owned vertices [bstart, bend), the ranks */
static PetscErrorCode OwnedVertices(SgElasticity p, PetscInt *n, PetscInt *N, PetscInt *bstart, PetscInt *bend, PetscMPIInt *size)
{
  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(p->b, n));
  PetscCall(VecGetSize(p->b, N));
  PetscCall(VecGetOwnershipRange(p->b, bstart, bend));
  *bstart /= p->dim;
  *bend /= p->dim;
  PetscCallMPI(MPI_Comm_size(p->comm, size));
  PetscFunctionReturn(0);
}

/* The distinct free block columns of the local block rows, from this rank's cells: kp->bi (nrow + 1) and kp->bj,
   each row sorted */
static PetscErrorCode LocalPattern(SgElasticity p, const PetscInt vcoff[], const PetscInt vcell[], PetscInt mark[], KPattern *kp)
{
  const SgMesh  *m  = &p->mesh;
  const PetscInt nv = p->dim + 1;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(kp->nrow + 1, &kp->bi));
  for (PetscInt v = 0; v < m->nv; v++) mark[v] = -1;
  for (PetscInt v = 0; v < m->nv; v++) {
    if (kp->row[v] < 0) continue;
    for (PetscInt k = vcoff[v]; k < vcoff[v + 1]; k++)
      for (PetscInt a = 0; a < nv; a++) {
        const PetscInt u = m->cellv[vcell[k] * nv + a];
        if (m->gblock[u] < 0 || mark[u] == v) continue;
        mark[u] = v;
        kp->bi[kp->row[v] + 1]++;
      }
  }
  for (PetscInt r = 0; r < kp->nrow; r++) kp->bi[r + 1] += kp->bi[r];
  PetscCall(PetscMalloc1(kp->bi[kp->nrow] + 1, &kp->bj));
  for (PetscInt v = 0; v < m->nv; v++) mark[v] = -1;
  for (PetscInt v = 0; v < m->nv; v++) {
    const PetscInt r  = kp->row[v];
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
  PetscFunctionReturn(0);
}

/* Local block rows r0 .. r1-1 into K, each block row's scalar rows in one call, values val (NULL: zeros) in the
   layout of the ghost buffer (block row r at (bi[r] - bi[r0]) dim^2); first is the global block row of r0 (the owned rows: bstart; the ghost rows: -1, their
   global block rows from grow[]) */
static PetscErrorCode SetRows(SgElasticity p, const KPattern *kp, PetscInt r0, PetscInt r1, PetscInt first, const PetscInt grow[], const PetscScalar *val)
{
  const PetscInt dim = p->dim;
  PetscInt      *cols, nmax = 0;
  PetscScalar   *zero;

  PetscFunctionBeginUser;
  for (PetscInt r = r0; r < r1; r++) nmax = PetscMax(nmax, kp->bi[r + 1] - kp->bi[r]);
  PetscCall(PetscMalloc1(nmax * dim + 1, &cols));
  PetscCall(PetscCalloc1(val ? 1 : nmax * dim * dim + 1, &zero));
  for (PetscInt r = r0; r < r1; r++) {
    const PetscInt g = first >= 0 ? first + r - r0 : grow[r - r0];
    PetscInt       rows[3], nb = kp->bi[r + 1] - kp->bi[r];
    for (PetscInt k = 0; k < nb; k++)
      for (PetscInt j = 0; j < dim; j++) cols[k * dim + j] = kp->bj[kp->bi[r] + k] * dim + j;
    for (PetscInt i = 0; i < dim; i++) rows[i] = g * dim + i;
    PetscCall(MatSetValues(p->K, dim, rows, nb * dim, cols, val ? val + (kp->bi[r] - kp->bi[r0]) * dim * dim : zero, ADD_VALUES));
  }
  PetscCall(PetscFree(cols));
  PetscCall(PetscFree(zero));
  PetscFunctionReturn(0);
}

/* Several ranks: K's preallocation, upper bounds of the owned rows' lengths: each rank's distinct free neighbours of
   its local rows, summed over the ranks by the owner of the row (diagonal or off-diagonal block column by the owner's
   range), exact where a row is not shared */
static PetscErrorCode PreallocateRanks(SgElasticity p, const KPattern *kp)
{
  const SgMesh   *m   = &p->mesh;
  const PetscInt  dim = p->dim;
  const PetscInt *ranges;
  PetscInt        n, N, bstart, bend, *dnz, *onz;
  PetscMPIInt     size;

  PetscFunctionBeginUser;
  PetscCall(OwnedVertices(p, &n, &N, &bstart, &bend, &size));
  PetscCall(VecGetOwnershipRanges(p->b, &ranges));
  PetscCall(PetscCalloc2(kp->nrow * 2 + 1, &dnz, n / dim + 1, &onz));
  for (PetscInt v = 0; v < m->nv; v++) {
    const PetscInt r = kp->row[v];
    PetscInt       o = 0, lo, hi;
    if (r < 0) continue;
    while (o < size - 1 && m->gblock[v] * dim >= ranges[o + 1]) o++;
    lo = ranges[o] / dim;
    hi = ranges[o + 1] / dim;
    for (PetscInt k = kp->bi[r]; k < kp->bi[r + 1]; k++) {
      if (kp->bj[k] >= lo && kp->bj[k] < hi) dnz[2 * r]++;
      else dnz[2 * r + 1]++;
    }
  }
  { /* summed by the owners through the vertex vectors of dim numbers (the first two used) */
    Vec          cloc, cglob;
    PetscScalar *ca;
    PetscSection vs;
    PetscCall(DMGetLocalVector(p->dmVec, &cloc));
    PetscCall(VecZeroEntries(cloc));
    PetscCall(DMGetLocalSection(p->dmVec, &vs));
    PetscCall(VecGetArray(cloc, &ca));
    for (PetscInt v = 0; v < m->nv; v++) {
      PetscInt off;
      if (kp->row[v] < 0) continue;
      PetscCall(PetscSectionGetOffset(vs, m->vStart + v, &off));
      ca[off]     = dnz[2 * kp->row[v]];
      ca[off + 1] = dnz[2 * kp->row[v] + 1];
    }
    PetscCall(VecRestoreArray(cloc, &ca));
    PetscCall(DMGetGlobalVector(p->dmVec, &cglob));
    PetscCall(VecZeroEntries(cglob));
    PetscCall(DMLocalToGlobal(p->dmVec, cloc, ADD_VALUES, cglob));
    PetscCall(DMGlobalToLocal(p->dmVec, cglob, INSERT_VALUES, cloc));
    PetscCall(DMRestoreGlobalVector(p->dmVec, &cglob));
    PetscCall(VecGetArray(cloc, &ca));
    for (PetscInt v = 0; v < m->nv; v++) {
      PetscInt off;
      if (m->goff[v] < 0) continue;
      PetscCall(PetscSectionGetOffset(vs, m->vStart + v, &off));
      dnz[kp->row[v]] = PetscMin((PetscInt)PetscRealPart(ca[off]), bend - bstart);
      onz[kp->row[v]] = PetscMin((PetscInt)PetscRealPart(ca[off + 1]), N / dim - (bend - bstart));
    }
    PetscCall(VecRestoreArray(cloc, &ca));
    PetscCall(DMRestoreLocalVector(p->dmVec, &cloc));
  }
  PetscCall(MatXAIJSetPreallocation(p->K, dim, dnz, onz, NULL, NULL));
  PetscCall(PetscFree2(dnz, onz));
  PetscFunctionReturn(0);
}

/* Several ranks, after the first assembly: the owned rows' whole pattern (every rank's cells) read back from K's two
   parts (columns of the off-diagonal part: garray, increasing), the places of their values there, and the ghost
   rows' buffer (their local pattern) */
static PetscErrorCode OwnedRows(SgElasticity p, KPattern *kp)
{
  const PetscInt  dim = p->dim, nown = kp->nown;
  const PetscInt *ia, *ja, *ib, *jb, *garray;
  PetscInt        n, bstart, *bi, *bj, na, nb;
  PetscBool       done;
  Mat             A, B;

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(p->b, &n));
  PetscCall(VecGetOwnershipRange(p->b, &bstart, NULL));
  bstart /= dim;
  kp->ranks = PETSC_TRUE;
  PetscCall(MatMPIAIJGetSeqAIJ(p->K, &A, &B, &garray));
  PetscCall(MatGetRowIJ(A, 0, PETSC_FALSE, PETSC_FALSE, &na, &ia, &ja, &done));
  PetscCheck(done && na == n, PETSC_COMM_SELF, PETSC_ERR_PLIB, "no rows of K's diagonal part");
  PetscCall(MatGetRowIJ(B, 0, PETSC_FALSE, PETSC_FALSE, &nb, &ib, &jb, &done));
  PetscCheck(done && nb == n, PETSC_COMM_SELF, PETSC_ERR_PLIB, "no rows of K's off-diagonal part");
  PetscCall(MatSeqAIJGetArray(A, &kp->aa));
  PetscCall(MatSeqAIJGetArray(B, &kp->ba));
  PetscCall(PetscMalloc1(kp->nrow + 1, &bi));
  bi[0] = 0;
  for (PetscInt r = 0; r < nown; r++) bi[r + 1] = bi[r] + (ia[r * dim + 1] - ia[r * dim] + ib[r * dim + 1] - ib[r * dim]) / dim;
  for (PetscInt r = nown; r < kp->nrow; r++) bi[r + 1] = bi[r] + kp->bi[r + 1] - kp->bi[r];
  PetscCall(PetscMalloc1(bi[kp->nrow] + 1, &bj));
  for (PetscInt r = 0; r < nown; r++) {
    const PetscInt la = ia[r * dim + 1] - ia[r * dim], lb = ib[r * dim + 1] - ib[r * dim];
    PetscInt       nlo = 0, q = bi[r];
    for (PetscInt i = 1; i < dim; i++)
      PetscCheck(ia[r * dim + i + 1] - ia[r * dim + i] == la && ib[r * dim + i + 1] - ib[r * dim + i] == lb, PETSC_COMM_SELF, PETSC_ERR_PLIB, "the scalar rows of block row %" PetscInt_FMT " differ", bstart + r);
    while (nlo * dim < lb && garray[jb[ib[r * dim] + nlo * dim]] < bstart * dim) nlo++;
    for (PetscInt k = 0; k < nlo; k++) bj[q++] = garray[jb[ib[r * dim] + k * dim]] / dim;
    for (PetscInt k = 0; k < la / dim; k++) bj[q++] = bstart + ja[ia[r * dim] + k * dim] / dim;
    for (PetscInt k = nlo; k < lb / dim; k++) bj[q++] = garray[jb[ib[r * dim] + k * dim]] / dim;
    kp->nlo[r] = nlo;
    kp->nd[r]  = la / dim;
    kp->La[r]  = la;
    kp->Lb[r]  = lb;
    kp->va[r]  = kp->aa + ia[r * dim];
    kp->vb[r]  = kp->ba + ib[r * dim];
  }
  PetscCall(MatRestoreRowIJ(A, 0, PETSC_FALSE, PETSC_FALSE, &na, &ia, &ja, &done));
  PetscCall(MatRestoreRowIJ(B, 0, PETSC_FALSE, PETSC_FALSE, &nb, &ib, &jb, &done));
  PetscCall(PetscArraycpy(bj + bi[nown], kp->bj + kp->bi[nown], bi[kp->nrow] - bi[nown]));
  PetscCall(PetscFree(kp->bi));
  PetscCall(PetscFree(kp->bj));
  kp->bi = bi;
  kp->bj = bj;
  PetscCall(PetscCalloc1((bi[kp->nrow] - bi[nown]) * dim * dim + 1, &kp->ghost));
  for (PetscInt r = nown; r < kp->nrow; r++) {
    kp->nlo[r] = 0;
    kp->nd[r]  = bi[r + 1] - bi[r];
    kp->La[r] = kp->Lb[r] = kp->nd[r] * dim;
    kp->va[r] = kp->vb[r] = kp->ghost + (bi[r] - bi[nown]) * dim * dim;
  }
  PetscFunctionReturn(0);
}

/* The stiffness (AIJ, block size dim) with its nonzero pattern from the mesh graph: block row v couples v with the
   vertices of its cells; the places of the cells' values in kp (see KPattern).
   K was BAIJ, converted to AIJ (what MUMPS and hypre take) once assembled: the conversion took 65-95 % of the
   assembly at 1.1e6 unknowns and held two copies of K for a moment. AIJ's own insertion (MatSetValues) finds every
   scalar entry anew and took longer than both; so the pattern is put in whole first (zeros, each block row's scalar
   rows in one call, in increasing order, so that no insertion moves a row's tail), and the cells add into K's values
   directly (AddElementStiffness). One rank: the exact row lengths; every entry gets the same values in the same order
   of the cells as with MatSetValues (0 + a value is that value): the same K to the bit.
   More ranks: rows of vertices shared between ranks get the counts of every rank added, an upper bound only there
   (the other ranks' cells are not local; DMCreateMatrix() and MATPREALLOCATOR cost several times the assembly
   itself). Each rank puts in its owned rows' pattern and sends the ghost rows' pattern to their owners (PETSc's
   stash), so that after the first assembly every owned row holds the whole pattern of the cells of every rank; the
   cells then add into the owned rows' values in K's diagonal and off-diagonal parts and into the ghost buffer, which
   is summed into the owners' rows by a second assembly, one call per ghost block row (before: one
   MatSetValuesBlocked per cell into the MPIAIJ matrix and the stash, the owned rows' scalar entries each searched
   anew: no faster on 2 ranks than on one). The sums in shared rows come in another order than on one rank
   (round-off). */
static PetscErrorCode CreateStiffness(SgElasticity p, KPattern *kp)
{
  const SgMesh  *m   = &p->mesh;
  const PetscInt dim = p->dim, nv = dim + 1;
  PetscInt       n, N, bstart, bend, *vcoff, *vcell, *mark, nown = 0, nghost = 0;
  PetscMPIInt    size;

  PetscFunctionBeginUser;
  PetscCall(OwnedVertices(p, &n, &N, &bstart, &bend, &size));
  /* vertex -> cells */
  PetscCall(PetscCalloc3(m->nv + 1, &vcoff, m->nc * nv, &vcell, m->nv, &mark));
  for (PetscInt c = 0; c < m->nc * nv; c++) vcoff[m->cellv[c] + 1]++;
  for (PetscInt v = 0; v < m->nv; v++) vcoff[v + 1] += vcoff[v];
  for (PetscInt c = 0; c < m->nc; c++)
    for (PetscInt a = 0; a < nv; a++) vcell[vcoff[m->cellv[c * nv + a]] + mark[m->cellv[c * nv + a]]++] = c;
  /* the local block rows: the owned ones by their global block row, then the ghost ones */
  PetscCall(PetscMalloc1(m->nv, &kp->row));
  for (PetscInt v = 0; v < m->nv; v++) {
    kp->row[v] = -1;
    if (m->goff[v] >= 0) {
      kp->row[v] = m->gblock[v] - bstart;
      nown++;
    }
  }
  PetscCheck(nown == bend - bstart, PETSC_COMM_SELF, PETSC_ERR_PLIB, "owned free vertices %" PetscInt_FMT " != block rows %" PetscInt_FMT, nown, bend - bstart);
  for (PetscInt v = 0; v < m->nv; v++)
    if (m->gblock[v] >= 0 && m->goff[v] < 0) kp->row[v] = nown + nghost++;
  kp->nown = nown;
  kp->nrow = nown + nghost;
  PetscCall(LocalPattern(p, vcoff, vcell, mark, kp));
  PetscCall(PetscMalloc6(kp->nrow, &kp->nlo, kp->nrow, &kp->nd, kp->nrow, &kp->La, kp->nrow, &kp->Lb, kp->nrow, &kp->va, kp->nrow, &kp->vb));
  PetscCall(MatCreate(p->comm, &p->K));
  PetscCall(MatSetSizes(p->K, n, n, N, N));
  PetscCall(MatSetBlockSize(p->K, dim));
  PetscCall(MatSetType(p->K, MATAIJ));
  if (size == 1) { /* the exact row lengths, then the whole pattern */
    PetscInt *len;
    PetscCall(PetscMalloc1(n + 1, &len));
    for (PetscInt r = 0; r < nown; r++)
      for (PetscInt i = 0; i < dim; i++) len[r * dim + i] = (kp->bi[r + 1] - kp->bi[r]) * dim;
    PetscCall(MatSeqAIJSetPreallocation(p->K, 0, len));
    PetscCall(PetscFree(len));
    PetscCall(MatSetOption(p->K, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
    PetscCall(SetRows(p, kp, 0, nown, 0, NULL, NULL));
    PetscCall(MatAssemblyBegin(p->K, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(p->K, MAT_FINAL_ASSEMBLY));
    PetscCall(MatSeqAIJGetArray(p->K, &kp->aa));
    for (PetscInt r = 0; r < nown; r++) {
      kp->nlo[r] = 0;
      kp->nd[r]  = kp->bi[r + 1] - kp->bi[r];
      kp->La[r] = kp->Lb[r] = kp->nd[r] * dim;
      kp->va[r] = kp->vb[r] = kp->aa + kp->bi[r] * dim * dim;
    }
  } else {
    PetscInt *grow;

    PetscCall(PreallocateRanks(p, kp));
    PetscCall(MatSetOption(p->K, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
    PetscCall(PetscMalloc1(nghost + 1, &grow));
    for (PetscInt v = 0; v < m->nv; v++)
      if (kp->row[v] >= nown) grow[kp->row[v] - nown] = m->gblock[v];
    PetscCall(SetRows(p, kp, 0, nown, bstart, NULL, NULL));
    PetscCall(SetRows(p, kp, nown, kp->nrow, -1, grow, NULL));
    PetscCall(PetscFree(grow));
    PetscCall(MatAssemblyBegin(p->K, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(p->K, MAT_FINAL_ASSEMBLY));
    PetscCall(OwnedRows(p, kp));
  }
  PetscCall(PetscFree3(vcoff, vcell, mark));
  PetscFunctionReturn(0);
}

/* The cells' values are in: K's arrays back, the ghost rows' values to their owners (into the stash: summed there by
   the assembly of AssembleOperators), kp freed */
static PetscErrorCode FinishStiffness(SgElasticity p, KPattern *kp)
{
  PetscFunctionBeginUser;
  if (kp->ranks) {
    Mat             A, B;
    const PetscInt *garray;
    PetscInt       *grow;
    PetscCall(MatMPIAIJGetSeqAIJ(p->K, &A, &B, &garray));
    PetscCall(MatSeqAIJRestoreArray(A, &kp->aa));
    PetscCall(MatSeqAIJRestoreArray(B, &kp->ba));
    PetscCall(PetscMalloc1(kp->nrow - kp->nown + 1, &grow));
    for (PetscInt v = 0; v < p->mesh.nv; v++)
      if (kp->row[v] >= kp->nown) grow[kp->row[v] - kp->nown] = p->mesh.gblock[v];
    PetscCall(SetRows(p, kp, kp->nown, kp->nrow, -1, grow, kp->ghost));
    PetscCall(PetscFree(grow));
  } else if (p->K) PetscCall(MatSeqAIJRestoreArray(p->K, &kp->aa));
  PetscCall(PetscFree(kp->row));
  PetscCall(PetscFree(kp->bi));
  PetscCall(PetscFree(kp->bj));
  PetscCall(PetscFree(kp->ghost));
  PetscCall(PetscFree6(kp->nlo, kp->nd, kp->La, kp->Lb, kp->va, kp->vb));
  PetscFunctionReturn(0);
}

/* The element stiffness Ke of cell cv into K (block columns gb); partial: the cell has a partly fixed vertex, whose
   fixed components get their row and column decoupled, their diagonal kept (the scale of its neighbours for the
   preconditioners), so that their unknowns stay 0; their values enter by the lifting. Added at the places kp gives
   (each block row's scalar rows have the same columns) */
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
  for (PetscInt a = 0; a < nv; a++) {
    const PetscInt r = kp->row[cv[a]];
    PetscInt       lo, nr;
    if (r < 0) continue;
    lo = kp->bi[r];
    nr = kp->bi[r + 1] - lo;
    for (PetscInt b = 0; b < nv; b++) {
      PetscInt     k, L;
      PetscScalar *row;
      if (gb[b] < 0) continue;
      PetscCall(PetscFindInt(gb[b], nr, kp->bj + lo, &k));
      PetscCheck(k >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "block column %" PetscInt_FMT " not in the pattern of block row %" PetscInt_FMT, gb[b], gb[a]);
      if (k < kp->nlo[r]) {
        row = kp->vb[r] + k * dim;
        L   = kp->Lb[r];
      } else if (k < kp->nlo[r] + kp->nd[r]) {
        row = kp->va[r] + (k - kp->nlo[r]) * dim;
        L   = kp->La[r];
      } else {
        row = kp->vb[r] + (k - kp->nd[r]) * dim;
        L   = kp->Lb[r];
      }
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
  KPattern           kp;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(SG_Assembly, 0, 0, 0, 0));
  PetscCall(PetscTime(&t0));
  PetscCall(PetscMemzero(&kp, sizeof(kp)));
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
  PetscCall(FinishStiffness(p, &kp));
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
