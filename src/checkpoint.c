/* checkpoint.c: the continuation state after every outer step (-checkpoint_file) and the restart from it
   (-restart_file). Vertex data are stored with the vertex coordinates and matched by them on reading, so a restart may
   use another number of ranks (another partition) than the run that wrote the file. */
#include "signorini.h"
#include <petscviewerhdf5.h>

#define NREAL 7    /* gamma, V0, best KKT, state[4] */
#define NHIST 22   /* numbers per history row */

static void RowToReals(const SgHistoryRow *r, PetscReal a[])
{
  const PetscReal v[NHIST] = {r->kind == 's' ? 0 : 1, r->outer, r->gamma, r->it, r->active, r->entered, r->left, r->fnorm, r->r1, r->r2, r->V, r->dV, r->ksp_its, r->time, r->ssn_its, r->C1, r->C2, r->Em, r->rhoF, r->rhoC, r->infeas, r->kkt};
  for (PetscInt k = 0; k < NHIST; k++) a[k] = v[k];
}

static void RealsToRow(const PetscReal a[], SgHistoryRow *r)
{
  r->kind    = a[0] == 0 ? 's' : 'o';
  r->outer   = (PetscInt)a[1];
  r->gamma   = a[2];
  r->it      = (PetscInt)a[3];
  r->active  = (PetscInt)a[4];
  r->entered = (PetscInt)a[5];
  r->left    = (PetscInt)a[6];
  r->fnorm   = a[7];
  r->r1      = a[8];
  r->r2      = a[9];
  r->V       = a[10];
  r->dV      = a[11];
  r->ksp_its = (PetscInt)a[12];
  r->time    = a[13];
  r->ssn_its = (PetscInt)a[14];
  r->C1      = a[15];
  r->C2      = a[16];
  r->Em      = a[17];
  r->rhoF    = a[18];
  r->rhoC    = a[19];
  r->infeas  = a[20];
  r->kkt     = a[21];
}

/* A vector of n numbers held by rank 0 (n on every rank), for the data every rank has a copy of. */
static PetscErrorCode RootVec(MPI_Comm comm, const char name[], PetscInt n, const PetscReal a[], Vec *v)
{
  PetscMPIInt rank;
  PetscScalar *va;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(VecCreateMPI(comm, rank ? 0 : n, PETSC_DETERMINE, v));
  PetscCall(PetscObjectSetName((PetscObject)*v, name));
  PetscCall(VecGetArray(*v, &va));
  if (!rank)
    for (PetscInt i = 0; i < n; i++) va[i] = a[i];
  PetscCall(VecRestoreArray(*v, &va));
  PetscFunctionReturn(0);
}

PetscErrorCode SgCheckpointWrite(SgCont ct)
{
  SgProblem          p = ct->prob;
  SgContact          c = ct->c;
  const SgMesh      *m = &p->mesh;
  const PetscInt     dim = p->dim;
  PetscSection       gs;
  PetscInt           nown = 0, k = 0, nvert, ints[6];
  PetscReal         *vl, reals[NREAL], *hist;
  Vec                X, U, L, R, G, H, yloc;
  PetscScalar       *xa, *ua, *la;
  const PetscScalar *ya;
  PetscViewer        viewer;
  char               tmp[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  if (!ct->ckfile[0]) PetscFunctionReturn(0);
  PetscCall(DMGetGlobalSection(p->dmVert, &gs));
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(gs, m->vStart + v, &off));
    if (off >= 0) nown++;
  }
  PetscCall(PetscCalloc1(m->nv, &vl));
  for (PetscInt i = 0; c && i < c->n; i++) vl[c->vert[i]] = c->lamhat[i];
  PetscCall(VecCreateMPI(p->comm, nown * dim, PETSC_DETERMINE, &X));
  PetscCall(VecCreateMPI(p->comm, nown * dim, PETSC_DETERMINE, &U));
  PetscCall(VecCreateMPI(p->comm, nown, PETSC_DETERMINE, &L));
  PetscCall(PetscObjectSetName((PetscObject)X, "coordinates"));
  PetscCall(PetscObjectSetName((PetscObject)U, "displacement"));
  PetscCall(PetscObjectSetName((PetscObject)L, "lamhat"));
  PetscCall(DMGetLocalVector(p->dm, &yloc));
  PetscCall(SgProblemGlobalToLocal(p, ct->y, yloc));
  PetscCall(VecGetArrayRead(yloc, &ya));
  PetscCall(VecGetArray(X, &xa));
  PetscCall(VecGetArray(U, &ua));
  PetscCall(VecGetArray(L, &la));
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(gs, m->vStart + v, &off));
    if (off < 0) continue;
    for (PetscInt d = 0; d < dim; d++) {
      xa[k * dim + d] = m->x[v * dim + d];
      ua[k * dim + d] = ya[m->loff[v] + d];
    }
    la[k++] = vl[v];
  }
  PetscCall(VecRestoreArray(X, &xa));
  PetscCall(VecRestoreArray(U, &ua));
  PetscCall(VecRestoreArray(L, &la));
  PetscCall(VecRestoreArrayRead(yloc, &ya));
  PetscCall(DMRestoreLocalVector(p->dm, &yloc));
  PetscCall(PetscFree(vl));

  reals[0] = ct->gamma;
  reals[1] = ct->V0;
  reals[2] = ct->best_kkt;
  for (PetscInt i = 0; i < 4; i++) reals[3 + i] = ct->state[i];
  PetscCall(PetscMalloc1(NHIST * ct->hist->n + 1, &hist));
  for (PetscInt i = 0; i < ct->hist->n; i++) RowToReals(&ct->hist->rows[i], &hist[i * NHIST]);
  PetscCall(RootVec(p->comm, "reals", NREAL, reals, &R));
  PetscCall(RootVec(p->comm, "gammas", ct->ngammas, ct->gammas, &G));
  PetscCall(RootVec(p->comm, "history", NHIST * ct->hist->n, hist, &H));
  PetscCall(PetscFree(hist));
  PetscCall(VecGetSize(L, &nvert));
  ints[0] = dim;
  ints[1] = nvert;
  ints[2] = ct->outer;
  ints[3] = ct->ssn_its;
  ints[4] = ct->ksp_its;
  ints[5] = ct->best_step;

  PetscCall(SgFileTmpName(ct->ckfile, tmp, sizeof(tmp)));
  PetscCall(PetscViewerHDF5Open(p->comm, tmp, FILE_MODE_WRITE, &viewer));
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/checkpoint"));
  PetscCall(VecView(X, viewer));
  PetscCall(VecView(U, viewer));
  PetscCall(VecView(L, viewer));
  PetscCall(VecView(R, viewer));
  PetscCall(VecView(G, viewer));
  PetscCall(VecView(H, viewer));
  {
    const char *names[6] = {"dim", "vertices", "outer", "ssn_iterations", "ksp_iterations", "best_step"};
    for (PetscInt i = 0; i < 6; i++) PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/checkpoint", names[i], PETSC_INT, &ints[i]));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/checkpoint", "cont_type", PETSC_STRING, ct->type));
  }
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscCall(SgFileCommit(p->comm, ct->ckfile));
  PetscCall(VecDestroy(&X));
  PetscCall(VecDestroy(&U));
  PetscCall(VecDestroy(&L));
  PetscCall(VecDestroy(&R));
  PetscCall(VecDestroy(&G));
  PetscCall(VecDestroy(&H));
  PetscFunctionReturn(0);
}

/* vertices of the checkpoint sorted by their coordinates */
static const PetscReal *SortX;
static PetscInt         SortDim;

static int CmpPoint(const PetscReal *a, const PetscReal *b)
{
  for (PetscInt d = 0; d < SortDim; d++)
    if (a[d] != b[d]) return a[d] < b[d] ? -1 : 1;
  return 0;
}

static int CmpIndex(const void *a, const void *b)
{
  return CmpPoint(&SortX[*(const PetscInt *)a * SortDim], &SortX[*(const PetscInt *)b * SortDim]);
}

static PetscErrorCode FindVertex(const PetscInt perm[], PetscInt n, const PetscReal x[], PetscInt *idx)
{
  PetscInt lo = 0, hi = n - 1;

  PetscFunctionBeginUser;
  *idx = -1;
  while (lo <= hi) {
    const PetscInt mid = (lo + hi) / 2;
    const int      c   = CmpPoint(&SortX[perm[mid] * SortDim], x);
    if (!c) {
      *idx = perm[mid];
      break;
    }
    if (c < 0) lo = mid + 1;
    else hi = mid - 1;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode LoadSeq(PetscViewer viewer, const char name[], PetscInt n, Vec *v)
{
  PetscFunctionBeginUser;
  PetscCall(VecCreate(PETSC_COMM_SELF, v));
  PetscCall(PetscObjectSetName((PetscObject)*v, name));
  if (n >= 0) PetscCall(VecSetSizes(*v, n, n));
  PetscCall(VecSetType(*v, VECSEQ));
  PetscCall(VecLoad(*v, viewer));
  PetscFunctionReturn(0);
}

PetscErrorCode SgCheckpointRead(SgCont ct)
{
  SgProblem          p = ct->prob;
  SgContact          c = ct->c;
  const SgMesh      *m = &p->mesh;
  const PetscInt     dim = p->dim;
  PetscViewer        viewer;
  PetscInt           ints[6], nvert = 0, *perm, nmiss = 0, nh;
  char              *type = NULL;
  Vec                X, U, L, R, G, H;
  const PetscScalar *xa, *ua, *la, *ra, *ga, *ha;
  PetscScalar       *ya;
  PetscBool          exists, same;
  const char        *names[6] = {"dim", "vertices", "outer", "ssn_iterations", "ksp_iterations", "best_step"};

  PetscFunctionBeginUser;
  if (!ct->rsfile[0]) PetscFunctionReturn(0);
  PetscCall(PetscTestFile(ct->rsfile, 'r', &exists));
  PetscCheck(exists, p->comm, PETSC_ERR_FILE_OPEN, "-restart_file: cannot read '%s'", ct->rsfile);
  PetscCheck(!strcmp(ct->type, "alm") || !strcmp(ct->type, "pf") || !strcmp(ct->type, "ipf"), p->comm, PETSC_ERR_USER_INPUT, "-restart_file: -cont_type %s has no outer steps to resume (alm, pf and ipf have)", ct->type);
  PetscCall(PetscViewerHDF5Open(PETSC_COMM_SELF, ct->rsfile, FILE_MODE_READ, &viewer));
  PetscCall(PetscViewerHDF5HasAttribute(viewer, "/checkpoint", "cont_type", &exists));
  PetscCheck(exists, p->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is not a checkpoint of this program", ct->rsfile);
  PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/checkpoint", "cont_type", PETSC_STRING, NULL, &type));
  PetscCall(PetscStrcmp(type, ct->type, &same));
  PetscCheck(same, p->comm, PETSC_ERR_USER_INPUT, "-restart_file: '%s' was written by -cont_type %s, this run has -cont_type %s", ct->rsfile, type, ct->type);
  PetscCall(PetscFree(type));
  for (PetscInt i = 0; i < 6; i++) PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/checkpoint", names[i], PETSC_INT, NULL, &ints[i]));
  {
    PetscSection gs;
    PetscCall(DMGetGlobalSection(p->dmVert, &gs));
    for (PetscInt v = 0; v < m->nv; v++) {
      PetscInt off;
      PetscCall(PetscSectionGetOffset(gs, m->vStart + v, &off));
      if (off >= 0) nvert++;
    }
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nvert, 1, MPIU_INT, MPI_SUM, p->comm));
  }
  PetscCheck(ints[0] == dim && ints[1] == nvert, p->comm, PETSC_ERR_USER_INPUT, "-restart_file: '%s' holds a %" PetscInt_FMT "D mesh of %" PetscInt_FMT " vertices, this run has a %" PetscInt_FMT "D mesh of %" PetscInt_FMT, ct->rsfile, ints[0], ints[1], dim, nvert);
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/checkpoint"));
  PetscCall(LoadSeq(viewer, "coordinates", nvert * dim, &X));
  PetscCall(LoadSeq(viewer, "displacement", nvert * dim, &U));
  PetscCall(LoadSeq(viewer, "lamhat", nvert, &L));
  PetscCall(LoadSeq(viewer, "reals", NREAL, &R));
  PetscCall(LoadSeq(viewer, "gammas", -1, &G));
  PetscCall(LoadSeq(viewer, "history", -1, &H));
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscCall(PetscViewerDestroy(&viewer));

  PetscCall(VecGetArrayRead(X, &xa));
  PetscCall(VecGetArrayRead(U, &ua));
  PetscCall(VecGetArrayRead(L, &la));
  PetscCall(PetscMalloc1(nvert, &perm));
  for (PetscInt i = 0; i < nvert; i++) perm[i] = i;
  SortX   = (const PetscReal *)xa;
  SortDim = dim;
  qsort(perm, nvert, sizeof(PetscInt), CmpIndex);
  PetscCall(VecGetArray(ct->y, &ya));
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt idx;
    if (m->goff[v] < 0) continue;
    PetscCall(FindVertex(perm, nvert, &m->x[v * dim], &idx));
    if (idx < 0) {
      nmiss++;
      continue;
    }
    for (PetscInt d = 0; d < dim; d++) ya[m->goff[v] + d] = ua[idx * dim + d];
  }
  PetscCall(VecRestoreArray(ct->y, &ya));
  for (PetscInt i = 0; c && i < c->n; i++) {
    PetscInt idx;
    PetscCall(FindVertex(perm, nvert, &m->x[c->vert[i] * dim], &idx));
    if (idx < 0) nmiss++;
    else c->lamhat[i] = PetscRealPart(la[idx]);
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nmiss, 1, MPIU_INT, MPI_SUM, p->comm));
  PetscCheck(!nmiss, p->comm, PETSC_ERR_USER_INPUT, "-restart_file: %" PetscInt_FMT " vertices of this mesh are not in '%s': it was written for another mesh", nmiss, ct->rsfile);
  PetscCall(PetscFree(perm));
  PetscCall(VecRestoreArrayRead(X, &xa));
  PetscCall(VecRestoreArrayRead(U, &ua));
  PetscCall(VecRestoreArrayRead(L, &la));

  PetscCall(VecGetArrayRead(R, &ra));
  ct->gamma    = PetscRealPart(ra[0]);
  ct->V0       = PetscRealPart(ra[1]);
  ct->best_kkt = PetscRealPart(ra[2]);
  for (PetscInt i = 0; i < 4; i++) ct->state[i] = PetscRealPart(ra[3 + i]);
  PetscCall(VecRestoreArrayRead(R, &ra));
  ct->outer     = ints[2];
  ct->ssn_its   = ints[3];
  ct->ksp_its   = ints[4];
  ct->best_step = ints[5];
  ct->ngammas = 0;
  PetscCall(VecGetArrayRead(G, &ga));
  {
    PetscInt ng;
    PetscCall(VecGetSize(G, &ng));
    for (PetscInt i = 0; i < ng; i++) PetscCall(SgContAddGamma(ct, PetscRealPart(ga[i])));
  }
  PetscCall(VecRestoreArrayRead(G, &ga));
  PetscCall(VecGetSize(H, &nh));
  PetscCall(VecGetArrayRead(H, &ha));
  ct->hist->n = 0;
  for (PetscInt i = 0; i < nh / NHIST; i++) {
    SgHistoryRow r;
    PetscReal    a[NHIST];
    for (PetscInt k = 0; k < NHIST; k++) a[k] = PetscRealPart(ha[i * NHIST + k]);
    RealsToRow(a, &r);
    PetscCall(SgHistoryAdd(ct->hist, &r));
  }
  PetscCall(VecRestoreArrayRead(H, &ha));
  PetscCall(VecDestroy(&X));
  PetscCall(VecDestroy(&U));
  PetscCall(VecDestroy(&L));
  PetscCall(VecDestroy(&R));
  PetscCall(VecDestroy(&G));
  PetscCall(VecDestroy(&H));
  ct->restarted = PETSC_TRUE;
  PetscCall(PetscInfo(NULL, "restarted from %s after outer step %" PetscInt_FMT " (gamma %g)\n", ct->rsfile, ct->outer, (double)ct->gamma));
  PetscFunctionReturn(0);
}
