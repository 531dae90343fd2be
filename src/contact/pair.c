/* A contact pair between two elastic bodies of one mesh (pair.h): the slave surface stays on its ranks, the master
   surface is gathered on every rank (it is a surface: small against the volume), the mortar integrals are computed
   per rank for its slave facets and assembled into the free displacement's numbering. */
#include "contact/pair.h"

static PetscLogEvent pair_events[SG_PAIR_NEVENTS];
static PetscBool     pair_registered = PETSC_FALSE;

PetscErrorCode SgPairLogEvent(SgPairPhase ph, PetscBool begin)
{
  PetscFunctionBeginUser;
  if (!pair_registered) {
    const char *const names[SG_PAIR_NEVENTS] = {"SgPairCollect", "SgPairGather", "SgPairMortar", "SgPairCheck", "SgPairAssemble", "SgPairBuildB", "SgPairPattern"};
    PetscClassId      cid;
    PetscCall(PetscClassIdRegister("SgContactPair", &cid));
    for (PetscInt k = 0; k < SG_PAIR_NEVENTS; k++) PetscCall(PetscLogEventRegister(names[k], cid, &pair_events[k]));
    pair_registered = PETSC_TRUE;
  }
  if (begin) PetscCall(PetscLogEventBegin(pair_events[ph], 0, 0, 0, 0));
  else PetscCall(PetscLogEventEnd(pair_events[ph], 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The facets of one side on this rank: per facet its dim vertices' coordinates (x: dim * dim reals), its outward unit
   normal (nrm: dim), measure (meas) and the vertices' free blocks (blk: dim, -1 for a vertex without dofs). */
typedef struct {
  PetscInt   nf;
  PetscReal *x, *nrm, *meas;
  PetscInt  *blk;
} Side;

static PetscErrorCode SideDestroy(Side *s)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree4(s->x, s->nrm, s->meas, s->blk));
  PetscFunctionReturn(0);
}

static PetscErrorCode SideCollect(DM dm, const SgMesh *m, const SgBoundary *bnd, Side *s)
{
  const PetscInt dim = m->dim;
  PetscInt      *facets, *part;

  PetscFunctionBeginUser;
  PetscCall(SgBoundaryGetFacets(dm, bnd, &s->nf, &facets, &part));
  PetscCall(PetscMalloc4(s->nf * dim * dim + 1, &s->x, s->nf * dim + 1, &s->nrm, s->nf + 1, &s->meas, s->nf * dim + 1, &s->blk));
  for (PetscInt f = 0; f < s->nf; f++) {
    PetscInt fv[3], nfv;
    PetscCall(SgFacetGeometry(dm, m, facets[f], &nfv, fv, &s->meas[f], &s->nrm[f * dim]));
    for (PetscInt a = 0; a < dim; a++) {
      for (PetscInt c = 0; c < dim; c++) s->x[(f * dim + a) * dim + c] = m->x[fv[a] * dim + c];
      s->blk[f * dim + a] = m->gblock[fv[a]];
    }
  }
  PetscCall(PetscFree2(facets, part));
  PetscFunctionReturn(0);
}

/* counts and displacements of per entries per facet */
static PetscErrorCode Counts(PetscMPIInt size, const PetscMPIInt cnt[], const PetscMPIInt dsp[], PetscInt per, PetscMPIInt c2[], PetscMPIInt d2[])
{
  PetscFunctionBeginUser;
  for (PetscMPIInt r = 0; r < size; r++) {
    PetscCall(PetscMPIIntCast(cnt[r] * per, &c2[r]));
    PetscCall(PetscMPIIntCast(dsp[r] * per, &d2[r]));
  }
  PetscFunctionReturn(0);
}

/* Every rank's facets of the side on every rank */
static PetscErrorCode SideGather(MPI_Comm comm, PetscInt dim, const Side *loc, Side *all)
{
  PetscMPIInt size, *cnt, *dsp, n = (PetscMPIInt)loc->nf;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscMalloc2(size, &cnt, size + 1, &dsp));
  PetscCallMPI(MPI_Allgather(&n, 1, MPI_INT, cnt, 1, MPI_INT, comm));
  dsp[0] = 0;
  for (PetscMPIInt r = 0; r < size; r++) dsp[r + 1] = dsp[r] + cnt[r];
  all->nf = dsp[size];
  PetscCall(PetscMalloc4(all->nf * dim * dim + 1, &all->x, all->nf * dim + 1, &all->nrm, all->nf + 1, &all->meas, all->nf * dim + 1, &all->blk));
  /* the four arrays have dim * dim, dim, 1 and dim entries per facet */
  {
    PetscMPIInt *c2, *d2;
    PetscCall(PetscMalloc2(size, &c2, size, &d2));
    PetscCall(Counts(size, cnt, dsp, dim * dim, c2, d2));
    PetscCallMPI(MPI_Allgatherv(loc->x, n * dim * dim, MPIU_REAL, all->x, c2, d2, MPIU_REAL, comm));
    PetscCall(Counts(size, cnt, dsp, dim, c2, d2));
    PetscCallMPI(MPI_Allgatherv(loc->nrm, n * dim, MPIU_REAL, all->nrm, c2, d2, MPIU_REAL, comm));
    PetscCallMPI(MPI_Allgatherv(loc->blk, n * dim, MPIU_INT, all->blk, c2, d2, MPIU_INT, comm));
    PetscCallMPI(MPI_Allgatherv(loc->meas, n, MPIU_REAL, all->meas, cnt, dsp, MPIU_REAL, comm));
    PetscCall(PetscFree2(c2, d2));
  }
  PetscCall(PetscFree2(cnt, dsp));
  PetscFunctionReturn(0);
}

/* The side as a mortar surface: each facet with vertices of its own (facet f, vertex a: f dim + a) */
static PetscErrorCode SideSurface(PetscInt dim, const Side *s, SgMortarSurface *ms, PetscInt **fac)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(s->nf * dim + 1, fac));
  for (PetscInt i = 0; i < s->nf * dim; i++) (*fac)[i] = i;
  ms->dim = dim, ms->nv = s->nf * dim, ms->nf = s->nf, ms->x = s->x, ms->facets = *fac, ms->nrm = s->nrm;
  PetscFunctionReturn(0);
}

/* B from the assembled scalar mortar matrix Ms (free vertex x free vertex), D and the normals N: row j (owned) =
   n_j^T (D_j e_j - sum_k M_jk e_k) in the free dofs; its columns of the fixed components of partly fixed vertices
   (rollers: decoupled unknowns that stay 0) are zeroed with the mask free (1 free, 0 fixed), so that the contact
   terms leave them alone: the master's (the slave normals are projected onto the free components already) */
static PetscErrorCode BuildB(SgContactPair p, Mat Ms, PetscInt nloc, Vec free)
{
  const PetscInt     dim = p->dim;
  PetscInt           rstart, cstart, cend, *bd, *bo, *rd, *ro;
  const PetscScalar *Da, *Na;

  PetscFunctionBeginUser;
  PetscCall(MatGetOwnershipRange(Ms, &rstart, NULL));
  PetscCall(VecGetOwnershipRange(free, &cstart, &cend));
  /* the exact row lengths (diagonal and off-diagonal blocks) of B and R: the rows of the slave vertices opposite the
     master only (a preallocation of the longest row on every row of the free vertices cost a pass over them all) */
  PetscCall(PetscCalloc4(nloc + 1, &bd, nloc + 1, &bo, nloc * dim + 1, &rd, nloc * dim + 1, &ro));
  PetscCall(VecGetArrayRead(p->D, &Da));
  PetscCall(VecGetArrayRead(p->N, &Na));
  for (PetscInt j = 0; j < nloc; j++) {
    const PetscInt    *cols;
    const PetscScalar *n = Na + j * dim;
    PetscInt           nc, row = rstart + j, nd = 1, no = 0;
    PetscCall(MatGetRow(Ms, row, &nc, &cols, NULL));
    if ((nc > 0 || PetscRealPart(Da[j]) != 0) && (n[0] != 0 || n[1] != 0 || (dim == 3 && n[2] != 0))) {
      for (PetscInt k = 0; k < nc; k++) {
        if (cols[k] * dim >= cstart && cols[k] * dim < cend) nd++;
        else no++;
      }
      bd[j] = nd * dim, bo[j] = no * dim;
      if (PetscRealPart(Da[j]) > 0)
        for (PetscInt c = 0; c < dim; c++) rd[j * dim + c] = nd, ro[j * dim + c] = no;
    }
    PetscCall(MatRestoreRow(Ms, row, &nc, &cols, NULL));
  }
  PetscCall(MatCreate(p->comm, &p->B));
  PetscCall(MatSetSizes(p->B, nloc, nloc * dim, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetType(p->B, MATAIJ));
  PetscCall(MatSeqAIJSetPreallocation(p->B, 0, bd));
  PetscCall(MatMPIAIJSetPreallocation(p->B, 0, bd, 0, bo));
  PetscCall(MatCreate(p->comm, &p->R));
  PetscCall(MatSetSizes(p->R, nloc * dim, nloc * dim, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetType(p->R, MATAIJ));
  PetscCall(MatSeqAIJSetPreallocation(p->R, 0, rd));
  PetscCall(MatMPIAIJSetPreallocation(p->R, 0, rd, 0, ro));
  PetscCall(PetscFree4(bd, bo, rd, ro));
  for (PetscInt j = 0; j < nloc; j++) {
    const PetscInt    *cols;
    const PetscScalar *vals;
    const PetscScalar *n = Na + j * dim;
    PetscInt           nc, row = rstart + j;
    PetscCall(MatGetRow(Ms, row, &nc, &cols, &vals));
    if ((nc > 0 || PetscRealPart(Da[j]) != 0) && (n[0] != 0 || n[1] != 0 || (dim == 3 && n[2] != 0))) { /* a slave vertex opposite the master (uncovered ones, and those whose normal is fixed, have no row) */
      p->nslave++;
      for (PetscInt c = 0; c < dim; c++) {
        PetscInt    col = row * dim + c;
        PetscScalar v   = Da[j] * n[c];
        PetscCall(MatSetValues(p->B, 1, &row, 1, &col, &v, ADD_VALUES));
      }
      for (PetscInt k = 0; k < nc; k++)
        for (PetscInt c = 0; c < dim; c++) {
          PetscInt    col = cols[k] * dim + c;
          PetscScalar v   = -vals[k] * n[c];
          PetscCall(MatSetValues(p->B, 1, &row, 1, &col, &v, ADD_VALUES));
        }
      if (PetscRealPart(Da[j]) > 0) /* a contact vertex: its relative displacement */
        for (PetscInt c = 0; c < dim; c++) {
          PetscInt    rr  = row * dim + c;
          PetscScalar one = 1.0;
          PetscCall(MatSetValues(p->R, 1, &rr, 1, &rr, &one, ADD_VALUES));
          for (PetscInt k = 0; k < nc; k++) {
            PetscInt    col = cols[k] * dim + c;
            PetscScalar v   = -vals[k] / Da[j];
            PetscCall(MatSetValues(p->R, 1, &rr, 1, &col, &v, ADD_VALUES));
          }
        }
    }
    PetscCall(MatRestoreRow(Ms, row, &nc, &cols, &vals));
  }
  PetscCall(VecRestoreArrayRead(p->D, &Da));
  PetscCall(VecRestoreArrayRead(p->N, &Na));
  PetscCall(MatAssemblyBegin(p->B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(p->B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatDiagonalScale(p->B, NULL, free));
  PetscCall(MatAssemblyBegin(p->R, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(p->R, MAT_FINAL_ASSEMBLY));
  PetscCall(MatDiagonalScale(p->R, free, free));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &p->nslave, 1, MPIU_INT, MPI_SUM, p->comm));
  PetscFunctionReturn(0);
}

/* Normalize the owned slave normals (area-weighted sums of facet normals). At a partly fixed vertex (a roller) only
   the free components move: the normal is its projection onto them, renormalized (as for the nodal conditions); a
   normal with no free part leaves the vertex out (N = 0: no row). */
static PetscErrorCode NormalizeNormals(SgContactPair p, Vec free)
{
  PetscScalar       *Na;
  const PetscScalar *fa;
  PetscInt           n;

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(p->N, &n));
  PetscCall(VecGetArray(p->N, &Na));
  PetscCall(VecGetArrayRead(free, &fa));
  for (PetscInt j = 0; j < n / p->dim; j++) {
    PetscReal len = 0, len0 = 0;
    for (PetscInt c = 0; c < p->dim; c++) {
      len0 += PetscSqr(PetscRealPart(Na[j * p->dim + c]));
      Na[j * p->dim + c] *= fa[j * p->dim + c];
      len += PetscSqr(PetscRealPart(Na[j * p->dim + c]));
    }
    len = PetscSqrtReal(len);
    for (PetscInt c = 0; c < p->dim; c++) Na[j * p->dim + c] = len > 1e-8 * PetscSqrtReal(len0) ? Na[j * p->dim + c] / len : 0;
  }
  PetscCall(VecRestoreArrayRead(free, &fa));
  PetscCall(VecRestoreArray(p->N, &Na));
  PetscFunctionReturn(0);
}

/* -contact_pair_normal average: the direction of each pair row j is the mean of the slave's unit normal n_j and the
   master's opposite one, -m_j, with m_j the master's vertex normals (facet normals averaged by area) averaged by the
   row's mortar weights, m_j ~ sum_k M_jk n_k: for two bodies mirrored about their interface the direction is the
   interface's normal, which the slave's normal alone is not (it leans by the angle of the slave's surface, an
   asymmetry of the order of the contact zone over the radius of curvature that does not shrink with h). Rows against
   a rigid obstacle and rows without a master partner keep theirs. On entry N holds the slave's area-weighted sums;
   NormalizeNormals follows. */
static PetscErrorCode AverageNormals(SgContactPair p, Mat Ms, const Side *ml)
{
  const PetscInt     dim = p->dim;
  Vec                Nm, comp, mcomp, Mbar;
  PetscScalar       *Na;
  const PetscScalar *Ma;
  PetscInt           n, rstart;

  PetscFunctionBeginUser;
  PetscCall(VecSetBlockSize(p->N, dim));
  PetscCall(VecDuplicate(p->N, &Nm));
  PetscCall(VecDuplicate(p->N, &Mbar));
  PetscCall(VecSet(Nm, 0));
  for (PetscInt f = 0; f < ml->nf; f++)
    for (PetscInt a = 0; a < dim; a++) {
      PetscInt b = ml->blk[f * dim + a];
      if (b < 0) continue; /* a fixed master vertex has no column of M */
      for (PetscInt c = 0; c < dim; c++) PetscCall(VecSetValue(Nm, b * dim + c, ml->meas[f] / dim * ml->nrm[f * dim + c], ADD_VALUES));
    }
  PetscCall(VecAssemblyBegin(Nm));
  PetscCall(VecAssemblyEnd(Nm));
  PetscCall(VecDuplicate(p->D, &comp));
  PetscCall(VecDuplicate(p->D, &mcomp));
  for (PetscInt c = 0; c < dim; c++) { /* Mbar = M Nm, component by component */
    PetscCall(VecStrideGather(Nm, c, comp, INSERT_VALUES));
    PetscCall(MatMult(Ms, comp, mcomp));
    PetscCall(VecStrideScatter(mcomp, c, Mbar, INSERT_VALUES));
  }
  PetscCall(MatGetOwnershipRange(Ms, &rstart, NULL));
  PetscCall(VecGetLocalSize(p->D, &n));
  PetscCall(VecGetArray(p->N, &Na));
  PetscCall(VecGetArrayRead(Mbar, &Ma));
  for (PetscInt j = 0; j < n; j++) {
    PetscScalar *ns = Na + j * dim;
    PetscReal    ls = 0, lm = 0, d[3], ld = 0;
    if (p->obsrow && p->obsrow[j]) continue;
    for (PetscInt c = 0; c < dim; c++) ls += PetscSqr(PetscRealPart(ns[c])), lm += PetscSqr(PetscRealPart(Ma[j * dim + c]));
    ls = PetscSqrtReal(ls), lm = PetscSqrtReal(lm);
    if (!(ls > 0) || !(lm > 0)) continue; /* off the slave surface, or no master partner */
    for (PetscInt c = 0; c < dim; c++) {
      d[c] = PetscRealPart(ns[c]) / ls - PetscRealPart(Ma[j * dim + c]) / lm;
      ld += d[c] * d[c];
    }
    if (!(ld > 3)) continue; /* n_j and -m_j more than 60 degrees apart: the sides do not face each other, keep n_j */
    for (PetscInt c = 0; c < dim; c++) ns[c] = d[c] / PetscSqrtReal(ld);
  }
  PetscCall(VecRestoreArrayRead(Mbar, &Ma));
  PetscCall(VecRestoreArray(p->N, &Na));
  PetscCall(VecDestroy(&comp));
  PetscCall(VecDestroy(&mcomp));
  PetscCall(VecDestroy(&Nm));
  PetscCall(VecDestroy(&Mbar));
  PetscFunctionReturn(0);
}

/* "a,b,c": a side's values (for the messages; pair.h) */
void SgPairIdList(const SgBoundary *b, char buf[], size_t len)
{
  size_t k = 0;
  buf[0]   = 0;
  for (PetscInt i = 0; i < b->nids && k + 24 < len; i++) k += (size_t)snprintf(buf + k, len - k, "%s%" PetscInt_FMT, i ? "," : "", b->ids[i]);
}

/* Marks on[k] = 1 for each body k (SgElasticityVertexBodies) that has a facet of the side on this rank */
static PetscErrorCode SideBodies(DM dm, const SgMesh *m, const SgBoundary *bnd, const PetscInt comp[], PetscInt on[])
{
  PetscInt nf, *facets, *part;

  PetscFunctionBeginUser;
  PetscCall(SgBoundaryGetFacets(dm, bnd, &nf, &facets, &part));
  for (PetscInt f = 0; f < nf; f++) {
    PetscInt  fv[3], nfv;
    PetscReal meas, nrm[3];
    PetscCall(SgFacetGeometry(dm, m, facets[f], &nfv, fv, &meas, nrm));
    on[comp[fv[0]]] = 1;
  }
  PetscCall(PetscFree2(facets, part));
  PetscFunctionReturn(0);
}

/* The values of a side (each alone) with a facet on body k, as "a,b" (for the message of CheckBodies). Collective. */
static PetscErrorCode SideIdsOnBody(DM dm, const SgMesh *m, const SgBoundary *bnd, const PetscInt comp[], PetscInt nb, PetscInt k, char buf[], size_t len)
{
  PetscInt  *on;
  size_t     n = 0;
  MPI_Comm   comm;
  SgBoundary one = *bnd;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)dm, &comm));
  PetscCall(PetscMalloc1(nb + 1, &on));
  buf[0]   = 0;
  one.nids = 1;
  for (PetscInt i = 0; i < bnd->nids; i++) {
    for (PetscInt b = 0; b < nb; b++) on[b] = 0;
    one.ids[0] = bnd->ids[i];
    PetscCall(SideBodies(dm, m, &one, comp, on));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, on, (PetscMPIInt)nb, MPIU_INT, MPI_MAX, comm));
    if (on[k] && n + 24 < len) n += (size_t)snprintf(buf + n, len - n, "%s%" PetscInt_FMT, n ? "," : "", bnd->ids[i]);
  }
  PetscCall(PetscFree(on));
  PetscFunctionReturn(0);
}

/* Contact of a body with itself is out of scope (issue 28): the slave and the master side must lie on different
   bodies (connected parts of the mesh). Without this check such a pair ends in a message about overlap or about
   sides that face away, which names the symptom, not the cause. The check is per body, not per facing pair: a body
   with a slave side and a master side is refused even where they face other bodies (a middle body of a chain,
   measured with three stacked blocks); the message names the values on that body and how to give a chain. mbox: the
   bounding box of the bodies the master side lies on (lower corner, upper corner; 0 beyond the dimension).
   Collective. */
static PetscErrorCode CheckBodies(SgElasticity el, DM dm, const SgMesh *m, const SgBoundary *slave, const SgBoundary *master, PetscReal mbox[6])
{
  MPI_Comm comm;
  PetscInt nb, *comp, *on, same = -1;
  char     ids[256], mids[256], sk[256], mk[256];

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetComm(el, &comm));
  { /* a missing label or id is reported here, before the arrays below are taken (SideBodies would leave them) */
    DMLabel lab;
    PetscCall(SgBoundaryGetLabel(dm, slave, &lab));
    PetscCall(SgBoundaryGetLabel(dm, master, &lab));
  }
  PetscCall(PetscMalloc1(m->nv + 1, &comp));
  PetscCall(SgElasticityVertexBodies(el, &nb, comp));
  PetscCall(PetscCalloc1(2 * nb + 1, &on));
  PetscCall(SideBodies(dm, m, slave, comp, on));
  PetscCall(SideBodies(dm, m, master, comp, on + nb));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, on, (PetscMPIInt)(2 * nb), MPIU_INT, MPI_MAX, comm));
  for (PetscInt k = 0; k < nb && same < 0; k++)
    if (on[k] && on[nb + k]) same = k;
  for (PetscInt d = 0; d < 6; d++) mbox[d] = PETSC_MAX_REAL; /* the lower corner and minus the upper one */
  for (PetscInt v = 0; v < m->nv; v++)
    if (on[nb + comp[v]])
      for (PetscInt d = 0; d < m->dim; d++) {
        mbox[d]     = PetscMin(mbox[d], m->x[v * m->dim + d]);
        mbox[3 + d] = PetscMin(mbox[3 + d], -m->x[v * m->dim + d]);
      }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, mbox, 6, MPIU_REAL, MPIU_MIN, comm));
  for (PetscInt d = 0; d < 3; d++) {
    if (d < m->dim) mbox[3 + d] = -mbox[3 + d];
    else mbox[d] = mbox[3 + d] = 0;
  }
  PetscCall(PetscFree(on));
  if (same >= 0) {
    PetscCall(SideIdsOnBody(dm, m, slave, comp, nb, same, sk, sizeof(sk)));
    PetscCall(SideIdsOnBody(dm, m, master, comp, nb, same, mk, sizeof(mk)));
  }
  PetscCall(PetscFree(comp));
  if (same >= 0) {
    SgPairIdList(slave, ids, sizeof(ids));
    SgPairIdList(master, mids, sizeof(mids));
    SETERRQ(comm, PETSC_ERR_USER_INPUT, "-contact_ids %s / -contact_master_ids %s: the slave and the master side lie on the same body (a connected part of the mesh; it has %" PetscInt_FMT "): its slave side %s and its master side %s; contact of a body with itself is not supported, and a body carries slave sides or master sides, not both: name a master side on another body (in a chain of bodies, give both sides of a middle body as slave sides, the facing sides of its neighbours as master sides)", ids, mids, nb, sk, mk);
  }
  PetscFunctionReturn(0);
}

/* The slave facets that found no partner within dmax (mortar.h's search): one that lies deeper than dmax behind a
   facing master facet means that the bodies overlap at the start: *depth > 0 (all ranks) and x the place, for the
   error the caller raises once its arrays are freed (OverlapError). Those that face the master farther than dmax
   ahead are counted (nbeyond, all ranks): if no slave vertex gets a row, the bodies are apart (the contact object
   warns and solves without contact), not facing away from each other. */
static PetscErrorCode CheckSearch(MPI_Comm comm, PetscInt dim, const Side *sl, const SgMortarSearch *sr, PetscInt *nbeyond, PetscReal *depth, PetscReal x[3])
{
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(&sr->nbeyond, nbeyond, 1, MPIU_INT, MPI_SUM, comm));
  *depth = sr->overlap;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, depth, 1, MPIU_REAL, MPI_MAX, comm));
  for (PetscInt c = 0; c < 3; c++) x[c] = -PETSC_MAX_REAL;
  if (!(*depth > 0)) PetscFunctionReturn(0);
  if (sr->foverlap >= 0 && sr->overlap == *depth) { /* the facet's centre, from the rank that has it */
    for (PetscInt c = 0; c < dim; c++) x[c] = 0;
    for (PetscInt i = 0; i < dim; i++)
      for (PetscInt c = 0; c < dim; c++) x[c] += sl->x[(sr->foverlap * dim + i) * dim + c] / dim;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, x, 3, MPIU_REAL, MPI_MAX, comm));
  PetscFunctionReturn(0);
}

static PetscErrorCode OverlapError(MPI_Comm comm, PetscInt dim, const SgBoundary *slave, const SgBoundary *master, PetscReal dmax, PetscReal depth, const PetscReal x[3])
{
  char ids[256], mids[256], at[96];

  PetscFunctionBeginUser;
  SgPairIdList(slave, ids, sizeof(ids));
  SgPairIdList(master, mids, sizeof(mids));
  if (dim == 3) PetscCall(PetscSNPrintf(at, sizeof(at), "(%g, %g, %g)", (double)x[0], (double)x[1], (double)x[2]));
  else PetscCall(PetscSNPrintf(at, sizeof(at), "(%g, %g)", (double)x[0], (double)x[1]));
  SETERRQ(comm, PETSC_ERR_USER_INPUT, "-contact_ids %s / -contact_master_ids %s: the bodies overlap at the start: the slave side near %s lies %g inside the master side (behind a facing master facet, deeper than -contact_pair_distance %g): move the bodies apart in the mesh", ids, mids, at, (double)depth, (double)dmax);
}

/* The obstacle's rows (pair.h): at owned free vertices that have no row of the pair (no D, no M entry) */
static PetscErrorCode ObstacleRows(SgContactPair p, Mat Ms, PetscInt nloc, const SgPairObstacleRows *o)
{
  const PetscInt dim = p->dim;
  PetscScalar   *Da, *ga, *Na;
  PetscInt       rstart;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(nloc + 1, &p->obsrow));
  PetscCall(MatGetOwnershipRange(Ms, &rstart, NULL));
  PetscCall(VecGetArray(p->D, &Da));
  PetscCall(VecGetArray(p->g0, &ga));
  PetscCall(VecGetArray(p->N, &Na));
  for (PetscInt i = 0; i < o->n; i++) {
    PetscInt j = o->off[i] / dim, nc;
    PetscCall(MatGetRow(Ms, rstart + j, &nc, NULL, NULL));
    PetscCall(MatRestoreRow(Ms, rstart + j, &nc, NULL, NULL));
    if (nc > 0 || PetscRealPart(Da[j]) != 0) continue; /* the vertex faces the master: the pair's row */
    p->obsrow[j] = PETSC_TRUE;
    Da[j]        = o->w[i];
    ga[j]        = o->w[i] * o->d[i];
    for (PetscInt c = 0; c < dim; c++) Na[j * dim + c] = o->nrm[i * dim + c];
  }
  PetscCall(VecRestoreArray(p->D, &Da));
  PetscCall(VecRestoreArray(p->g0, &ga));
  PetscCall(VecRestoreArray(p->N, &Na));
  PetscFunctionReturn(0);
}

/* A slave vertex whose slave facets are only partly covered by the master (at the rim of the coupling: the pairing
   distance dmax keeps some master facets and drops their neighbours, or the master surface ends) integrates its dual
   basis psi_j, which is negative on part of each facet, over the covered part only: D_j may be near zero or negative
   while its row of M stays of the order of the facets' measure. Such a row of D^-1 M is huge (the sphere on a block
   at 117,693 unknowns: a row sum of |M_jk| / D_j of 130 against a median of 1.24) and gives the preconditioned
   Jacobian isolated tiny eigenvalues (4 at that size; the last SSN step's CG 65 instead of about 25). Such a vertex
   is given no row, as an uncovered vertex has none: D_j, g0_j and its row of M are dropped when D_j is below
   SG_PAIR_DMIN of int phi_j over its slave facets (a fully covered vertex has D_j = int phi_j). What is lost: the
   vertex is not held against the master and may penetrate it by O(h) at the rim of the coverage (in the sphere and
   Hertz examples the rim is at the distance cut, far from the contact zone); the pair rows of its neighbours stay
   exact for a rigid motion (each row's D_j u - sum_k M_jk u = 0 is untouched). */
#define SG_PAIR_DMIN 0.1
static PetscErrorCode DropTinyD(SgContactPair p, Mat Ms, PetscInt dim, const Side *work, PetscInt nv)
{
  Vec          F;
  PetscScalar *Da, *ga;
  PetscInt     n, rstart, *rows, nd = 0, ndrop;
  PetscReal    worst = PETSC_MAX_REAL;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(p->D, &F));
  PetscCall(VecSet(F, 0));
  for (PetscInt v = 0; v < nv; v++)
    if (work->blk[v] >= 0) PetscCall(VecSetValue(F, work->blk[v], work->meas[v / dim] / dim, ADD_VALUES));
  PetscCall(VecAssemblyBegin(F));
  PetscCall(VecAssemblyEnd(F));
  PetscCall(VecGetLocalSize(p->D, &n));
  PetscCall(MatGetOwnershipRange(Ms, &rstart, NULL));
  PetscCall(PetscMalloc1(n + 1, &rows));
  {
    const PetscScalar *Fa;
    PetscCall(VecGetArrayRead(F, &Fa));
    PetscCall(VecGetArray(p->D, &Da));
    PetscCall(VecGetArray(p->g0, &ga));
    for (PetscInt j = 0; j < n; j++) {
      PetscReal d = PetscRealPart(Da[j]), f = PetscRealPart(Fa[j]);
      PetscInt  nc;
      PetscCall(MatGetRow(Ms, rstart + j, &nc, NULL, NULL));
      PetscCall(MatRestoreRow(Ms, rstart + j, &nc, NULL, NULL));
      if (f <= 0 || (nc == 0 && d == 0)) continue; /* not a slave vertex, or one without a partner */
      if (d < SG_PAIR_DMIN * f) {
        rows[nd++] = rstart + j;
        worst      = PetscMin(worst, d / f);
        p->Ddrop += d;
        Da[j] = 0, ga[j] = 0;
      }
    }
    PetscCall(VecRestoreArray(p->g0, &ga));
    PetscCall(VecRestoreArray(p->D, &Da));
    PetscCall(VecRestoreArrayRead(F, &Fa));
  }
  PetscCall(MatZeroRows(Ms, nd, rows, 0.0, NULL, NULL));
  PetscCall(PetscFree(rows));
  PetscCall(VecDestroy(&F));
  PetscCallMPI(MPI_Allreduce(&nd, &ndrop, 1, MPIU_INT, MPI_SUM, p->comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &p->Ddrop, 1, MPIU_REAL, MPI_SUM, p->comm));
  p->ndrop = ndrop;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &worst, 1, MPIU_REAL, MPI_MIN, p->comm));
  PetscCall(PetscInfo(NULL, "%" PetscInt_FMT " slave vertices partly covered with D_j below %g of int phi_j (the least %g) left without a row\n", ndrop, (double)SG_PAIR_DMIN, ndrop ? (double)worst : 1.0));
  PetscFunctionReturn(0);
}

/* SgContactPairCreate's work arrays and sides, freed at its end or before its overlap error (sall: on several ranks) */
static PetscErrorCode CreateWorkFree(PetscMPIInt size, PetscInt *Mr, PetscInt *Mc, PetscReal *Mv, PetscReal *Dl, PetscReal *gl, PetscInt *sfac, PetscInt *mfac, Side *sl, Side *ml, Side *mall, Side *sall)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(Mr));
  PetscCall(PetscFree(Mc));
  PetscCall(PetscFree(Mv));
  PetscCall(PetscFree2(Dl, gl));
  PetscCall(PetscFree(sfac));
  PetscCall(PetscFree(mfac));
  PetscCall(SideDestroy(sl));
  PetscCall(SideDestroy(ml));
  PetscCall(SideDestroy(mall));
  if (size > 1) PetscCall(SideDestroy(sall));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactPairCreate(SgElasticity el, const SgBoundary *slave, const SgBoundary *master, PetscReal dmax, PetscBool average, PetscBool brute, const SgPairObstacleRows *obst, SgContactPair *pair)
{
  SgContactPair   p;
  DM              dm;
  const SgMesh   *m;
  Mat             K, Ms;
  Side            sl, ml, mall, sall, work;
  PetscMPIInt     size, rank;
  SgMortarSurface ss, ms;
  SgMortarSearch  search;
  PetscInt        dim, nloc, *sfac, *mfac, nM, *Mr, *Mc;
  PetscReal      *Dl, *gl, *Mv, depth, xdeep[3];

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&p));
  *pair = p; /* the caller's from now on: an error below (sides of one body, overlap) leaves it to SgContactPairDestroy */
  PetscCall(SgElasticityGetComm(el, &p->comm));
  PetscCall(SgElasticityGetDMs(el, &dm, NULL, NULL, NULL));
  PetscCall(SgElasticityGetMesh(el, &m));
  PetscCall(SgElasticityGetOperators(el, &K, NULL));
  dim = p->dim = m->dim;
  PetscCall(MatGetLocalSize(K, &nloc, NULL));
  nloc /= dim;
  PetscCall(SgPairLogEvent(SG_PAIR_COLLECT, PETSC_TRUE));
  PetscCall(CheckBodies(el, dm, m, slave, master, p->mbox));
  PetscCall(SideCollect(dm, m, slave, &sl));
  PetscCall(SideCollect(dm, m, master, &ml));
  PetscCall(SgPairLogEvent(SG_PAIR_COLLECT, PETSC_FALSE));
  PetscCall(SgPairLogEvent(SG_PAIR_GATHER, PETSC_TRUE));
  PetscCall(SideGather(p->comm, dim, &ml, &mall));
  /* the slave facets of all ranks in equal shares: the partition need not spread the slave surface (the sphere on a
     block on 2 ranks: 64 and 2,032 of its facets at 40,866 unknowns), and the mortar integrals are a slave facet's
     work; its rows go to the ranks that own them (D, g0, N and M by ADD_VALUES) */
  PetscCallMPI(MPI_Comm_size(p->comm, &size));
  PetscCallMPI(MPI_Comm_rank(p->comm, &rank));
  if (size > 1) {
    PetscInt f0, f1;
    PetscCall(SideGather(p->comm, dim, &sl, &sall));
    f0 = (PetscInt)((PetscInt64)sall.nf * rank / size), f1 = (PetscInt)((PetscInt64)sall.nf * (rank + 1) / size);
    work.nf = f1 - f0, work.x = sall.x + f0 * dim * dim, work.nrm = sall.nrm + f0 * dim, work.meas = sall.meas + f0, work.blk = sall.blk + f0 * dim;
  } else work = sl;
  PetscCall(SgPairLogEvent(SG_PAIR_GATHER, PETSC_FALSE));
  PetscCall(SgPairLogEvent(SG_PAIR_MORTAR, PETSC_TRUE));
  PetscCall(SideSurface(dim, &work, &ss, &sfac));
  PetscCall(SideSurface(dim, &mall, &ms, &mfac));
  PetscCall(PetscMalloc2(ss.nv + 1, &Dl, ss.nv + 1, &gl));
  PetscCall(SgMortarIntegrals(&ss, &ms, dmax, brute, Dl, gl, &nM, &Mr, &Mc, &Mv, &p->area, &search));
  PetscCall(SgPairLogEvent(SG_PAIR_MORTAR, PETSC_FALSE));
  PetscCall(SgPairLogEvent(SG_PAIR_CHECK, PETSC_TRUE));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &p->area, 1, MPIU_REAL, MPI_SUM, p->comm));
  PetscCall(CheckSearch(p->comm, dim, &work, &search, &p->nbeyond, &depth, xdeep));
  PetscCall(SgPairLogEvent(SG_PAIR_CHECK, PETSC_FALSE));
  if (depth > 0) { /* the bodies overlap: the error once this function's arrays are freed */
    PetscCall(CreateWorkFree(size, Mr, Mc, Mv, Dl, gl, sfac, mfac, &sl, &ml, &mall, &sall));
    PetscCall(OverlapError(p->comm, dim, slave, master, dmax, depth, xdeep));
  }

  PetscCall(SgPairLogEvent(SG_PAIR_ASSEMBLE, PETSC_TRUE));
  PetscCall(VecCreateMPI(p->comm, nloc, PETSC_DETERMINE, &p->D));
  PetscCall(VecDuplicate(p->D, &p->g0));
  PetscCall(VecCreateMPI(p->comm, nloc * dim, PETSC_DETERMINE, &p->N));
  { /* Ms's rows: at most as many entries as the row has triplets on all ranks (counted in a Vec); 16 on every row of
       the free vertices, most of them off the slave side, cost an allocation and a compression of them all */
    Vec                cnt;
    const PetscScalar *ca;
    PetscInt           N, *dz, *oz;
    PetscCall(VecDuplicate(p->D, &cnt));
    PetscCall(VecSet(cnt, 0));
    for (PetscInt k = 0; k < nM; k++) {
      PetscInt r = work.blk[Mr[k]], c = mall.blk[Mc[k]];
      if (r >= 0 && c >= 0) PetscCall(VecSetValue(cnt, r, 1.0, ADD_VALUES));
    }
    PetscCall(VecAssemblyBegin(cnt));
    PetscCall(VecAssemblyEnd(cnt));
    PetscCall(VecGetSize(cnt, &N));
    PetscCall(PetscMalloc2(nloc + 1, &dz, nloc + 1, &oz));
    PetscCall(VecGetArrayRead(cnt, &ca));
    for (PetscInt j = 0; j < nloc; j++) {
      PetscInt t = (PetscInt)PetscRealPart(ca[j]);
      dz[j] = PetscMin(t, nloc), oz[j] = PetscMin(t, N - nloc);
    }
    PetscCall(VecRestoreArrayRead(cnt, &ca));
    PetscCall(VecDestroy(&cnt));
    PetscCall(MatCreateAIJ(p->comm, nloc, nloc, PETSC_DETERMINE, PETSC_DETERMINE, 0, dz, 0, oz, &Ms));
    PetscCall(PetscFree2(dz, oz));
  }
  PetscCall(MatSetOption(Ms, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  for (PetscInt v = 0; v < ss.nv; v++) {
    PetscInt  b = work.blk[v], f = v / dim;
    PetscReal wn[3];
    if (b < 0) continue; /* a slave vertex without dofs has no row */
    PetscCall(VecSetValue(p->D, b, Dl[v], ADD_VALUES));
    PetscCall(VecSetValue(p->g0, b, gl[v], ADD_VALUES));
    for (PetscInt c = 0; c < dim; c++) {
      wn[c] = work.meas[f] / dim * work.nrm[f * dim + c];
      PetscCall(VecSetValue(p->N, b * dim + c, wn[c], ADD_VALUES));
    }
  }
  for (PetscInt k = 0; k < nM; k++) {
    PetscInt r = work.blk[Mr[k]], c = mall.blk[Mc[k]];
    if (r < 0 || c < 0) continue; /* a fixed master vertex does not move */
    PetscCall(MatSetValue(Ms, r, c, Mv[k], ADD_VALUES));
  }
  PetscCall(VecAssemblyBegin(p->D));
  PetscCall(VecAssemblyEnd(p->D));
  PetscCall(VecAssemblyBegin(p->g0));
  PetscCall(VecAssemblyEnd(p->g0));
  PetscCall(VecAssemblyBegin(p->N));
  PetscCall(VecAssemblyEnd(p->N));
  PetscCall(MatAssemblyBegin(Ms, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Ms, MAT_FINAL_ASSEMBLY));
  PetscCall(DropTinyD(p, Ms, dim, &work, ss.nv));
  PetscCall(SgPairLogEvent(SG_PAIR_ASSEMBLE, PETSC_FALSE));
  PetscCall(SgPairLogEvent(SG_PAIR_BUILDB, PETSC_TRUE));
  if (obst) PetscCall(ObstacleRows(p, Ms, nloc, obst));
  if (average) PetscCall(AverageNormals(p, Ms, &ml));
  {
    Vec          free;
    PetscScalar *fa;
    PetscCall(MatCreateVecs(K, &free, NULL));
    PetscCall(VecSet(free, 1.0));
    PetscCall(VecGetArray(free, &fa));
    for (PetscInt v = 0; v < m->nv; v++)
      if (m->goff[v] >= 0 && SgMeshPartial(m, v))
        for (PetscInt c = 0; c < dim; c++)
          if (SgMeshFixed(m, v, c)) fa[m->goff[v] + c] = 0;
    PetscCall(VecRestoreArray(free, &fa));
    PetscCall(NormalizeNormals(p, free));
    PetscCall(BuildB(p, Ms, nloc, free));
    PetscCall(VecDestroy(&free));
  }
  PetscCall(SgPairLogEvent(SG_PAIR_BUILDB, PETSC_FALSE));

  PetscCall(MatDestroy(&Ms));
  PetscCall(CreateWorkFree(size, Mr, Mc, Mv, Dl, gl, sfac, mfac, &sl, &ml, &mall, &sall));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactPairDestroy(SgContactPair *pair)
{
  PetscFunctionBeginUser;
  if (!*pair) PetscFunctionReturn(0);
  PetscCall(VecDestroy(&(*pair)->D));
  PetscCall(VecDestroy(&(*pair)->g0));
  PetscCall(VecDestroy(&(*pair)->N));
  PetscCall(MatDestroy(&(*pair)->B));
  PetscCall(PetscFree((*pair)->obsrow));
  PetscCall(MatDestroy(&(*pair)->R));
  PetscCall(PetscFree(*pair));
  PetscFunctionReturn(0);
}
