/* checkpoint_read.c: the checkpoint reader of a restart (-restart_file): it opens the file, checks that it is a
   checkpoint of this problem (its fingerprint, fingerprint.c) and mesh, matches the file's vertices with the mesh's by their coordinates
   (any partition), and hands each owner of a state its datasets and attributes; a damaged file is refused naming
   -restart_file. */
#include "io/ioimpl.h"
#include <petscviewerhdf5.h>
#include <petscsf.h>

/* Run f(ctx) with PETSc's and HDF5's error printing off; *ierr is its error code, the same on every rank. */
static PetscErrorCode Quietly(MPI_Comm comm, PetscErrorCode (*f)(void *), void *ctx, PetscErrorCode *ierr)
{
  H5E_auto2_t efunc;
  void       *edata;
  int         e;

  PetscFunctionBeginUser;
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  (void)H5Eget_auto2(H5E_DEFAULT, &efunc, &edata);
  (void)H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  *ierr = f(ctx); /* not PetscCall: a damaged file is reported by the caller, naming -restart_file */
  (void)H5Eset_auto2(H5E_DEFAULT, efunc, edata);
  PetscCall(PetscPopErrorHandler());
  e = *ierr ? 1 : 0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &e, 1, MPI_INT, MPI_MAX, comm));
  *ierr = e ? PETSC_ERR_FILE_READ : 0;
  PetscFunctionReturn(0);
}

/* ---- the reader: opens the file, checks that it is a checkpoint of this problem and mesh and matches the vertices;
   the owners then take out their parts. Every refusal names -restart_file and the file; a reader that refuses is
   closed and freed first (the caller's handle is then gone: the error returns). */
struct _n_SgCheckpointReader {
  SgElasticity el;
  SgContact    c;
  MPI_Comm     comm;
  char         file[PETSC_MAX_PATH_LEN];
  PetscViewer  viewer;
  PetscInt     dim, nvert;
  PetscInt    *idx;    /* the file's vertex of each vertex of the mesh (-1: not in the file) */
  PetscInt     lo, hi; /* the file's vertices lo..hi-1: the rows of the vertex datasets this rank reads */
  PetscSF      sf;     /* from those rows (roots) to the mesh's vertices matched in the file (leaves) */
};

/* one read of the file, run quietly (a damaged file is reported by the caller) */
typedef struct {
  SgCheckpointReader r;
  const char        *name;
  PetscDataType      type;
  void              *value;
  PetscInt           n; /* a dataset's expected size (-1: any) */
  Vec                v;
  PetscBool          has;
} CkItem;

/* one read of this rank's rows of a vertex dataset, run quietly */
typedef struct {
  SgCheckpointReader r;
  const char        *name;
  PetscInt           bs;  /* numbers per vertex */
  PetscReal         *buf; /* rows lo..hi-1 */
} CkRows;

/* each rank opens the file alone, through a link of its own (SgFileReadAliasBegin: OMPIO's semaphore of the name) */
static PetscErrorCode ItemOpen(void *ctx)
{
  CkItem        *it = (CkItem *)ctx;
  char           alias[PETSC_MAX_PATH_LEN];
  size_t         maxlen;
  PetscBool      made;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  PetscCall(SgFileHDF5NameMax(PETSC_COMM_SELF, &maxlen));
  PetscCall(SgFileReadAliasBegin(it->r->file, maxlen, alias, sizeof(alias), &made));
  ierr = PetscViewerHDF5Open(PETSC_COMM_SELF, alias, FILE_MODE_READ, &it->r->viewer);
  if (made) PetscCall(SgFileReadAliasEnd(alias));
  PetscCall(ierr);
  PetscFunctionReturn(0);
}

static PetscErrorCode ItemClose(void *ctx)
{
  CkItem *it = (CkItem *)ctx;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerDestroy(&it->r->viewer));
  PetscFunctionReturn(0);
}

static PetscErrorCode ItemHasAttribute(void *ctx)
{
  CkItem *it = (CkItem *)ctx;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5HasAttribute(it->r->viewer, "/checkpoint", it->name, &it->has));
  PetscFunctionReturn(0);
}

static PetscErrorCode ItemAttribute(void *ctx)
{
  CkItem *it = (CkItem *)ctx;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5ReadAttribute(it->r->viewer, "/checkpoint", it->name, it->type, NULL, it->value));
  PetscFunctionReturn(0);
}

static PetscErrorCode ItemHasDataset(void *ctx)
{
  CkItem *it = (CkItem *)ctx;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5PushGroup(it->r->viewer, "/checkpoint"));
  PetscCall(PetscViewerHDF5HasDataset(it->r->viewer, it->name, &it->has));
  PetscCall(PetscViewerHDF5PopGroup(it->r->viewer));
  PetscFunctionReturn(0);
}

static PetscErrorCode ItemDataset(void *ctx)
{
  CkItem *it = (CkItem *)ctx;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5PushGroup(it->r->viewer, "/checkpoint"));
  PetscCall(VecCreate(PETSC_COMM_SELF, &it->v));
  PetscCall(PetscObjectSetName((PetscObject)it->v, it->name));
  if (it->n >= 0) PetscCall(VecSetSizes(it->v, it->n, it->n));
  PetscCall(VecSetType(it->v, VECSEQ));
  PetscCall(VecLoad(it->v, it->r->viewer));
  PetscCall(PetscViewerHDF5PopGroup(it->r->viewer));
  PetscFunctionReturn(0);
}

/* Rows lo..hi-1 of a vertex dataset (bs numbers per vertex of the file, stored as nvert * bs numbers or nvert rows
   of bs) into buf: each rank reads its own rows, so that no rank holds a whole dataset. */
static PetscErrorCode ItemChunk(void *ctx)
{
  CkRows            *it = (CkRows *)ctx;
  SgCheckpointReader r  = it->r;
  hid_t              fid, dset, space = -1, mem = -1;
  hsize_t            dims[2] = {0, 0}, start[2] = {0, 0}, count[2] = {0, 0}, n = (hsize_t)((r->hi - r->lo) * it->bs);
  int                nd = -1;
  herr_t             st = -1;
  char               path[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5GetFileId(r->viewer, &fid));
  PetscCall(PetscSNPrintf(path, sizeof(path), "/checkpoint/%s", it->name));
  dset = H5Dopen2(fid, path, H5P_DEFAULT);
  if (dset >= 0) space = H5Dget_space(dset);
  if (space >= 0) nd = H5Sget_simple_extent_ndims(space);
  if ((nd == 1 || nd == 2) && H5Sget_simple_extent_dims(space, dims, NULL) == nd) {
    if (nd == 1 && dims[0] == (hsize_t)(r->nvert * it->bs)) start[0] = (hsize_t)(r->lo * it->bs), count[0] = n;
    else if (nd == 2 && dims[0] == (hsize_t)r->nvert && dims[1] == (hsize_t)it->bs) start[0] = (hsize_t)r->lo, count[0] = (hsize_t)(r->hi - r->lo), count[1] = (hsize_t)it->bs;
    else nd = -1; /* not of the expected size */
    if (nd > 0 && !n) st = 0;
    else if (nd > 0 && H5Sselect_hyperslab(space, H5S_SELECT_SET, start, NULL, count, NULL) >= 0 && (mem = H5Screate_simple(1, &n, NULL)) >= 0) st = H5Dread(dset, sizeof(PetscReal) == sizeof(float) ? H5T_NATIVE_FLOAT : H5T_NATIVE_DOUBLE, mem, space, H5P_DEFAULT, it->buf);
  }
  if (mem >= 0) (void)H5Sclose(mem);
  if (space >= 0) (void)H5Sclose(space);
  if (dset >= 0) (void)H5Dclose(dset);
  PetscCheck(st >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "cannot read the dataset %s", path);
  PetscFunctionReturn(0);
}

/* Close the file and free the reader, with error printing off (a damaged file can fail at H5Fclose): for a refusal,
   before the error is returned. */
PetscErrorCode SgCheckpointReaderAbandon(SgCheckpointReader *rp)
{
  SgCheckpointReader r  = *rp;
  CkItem             it = {r, NULL, PETSC_INT, NULL, -1, NULL, PETSC_FALSE};
  PetscErrorCode     ierr;

  PetscFunctionBeginUser;
  if (!r) PetscFunctionReturn(0);
  if (r->viewer) PetscCall(Quietly(r->comm, ItemClose, &it, &ierr));
  PetscCall(PetscFree(r->idx));
  PetscCall(PetscSFDestroy(&r->sf));
  PetscCall(PetscFree(*rp));
  PetscFunctionReturn(0);
}

/* the file's name, for the owners' messages */
PetscErrorCode SgCheckpointReaderGetFile(SgCheckpointReader r, const char **file)
{
  PetscFunctionBeginUser;
  *file = r->file;
  PetscFunctionReturn(0);
}

/* the reader freed, then: "-restart_file: 'file' is damaged: <what> is <val>" */
PetscErrorCode SgCheckpointReaderDamaged(SgCheckpointReader *rp, const char what[], PetscReal val)
{
  char     f[PETSC_MAX_PATH_LEN], w[256];
  MPI_Comm comm = (*rp)->comm;

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(f, (*rp)->file, sizeof(f)));
  PetscCall(PetscStrncpy(w, what, sizeof(w)));
  PetscCall(SgCheckpointReaderAbandon(rp));
  SETERRQ(comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is damaged: %s is %g", f, w, (double)val);
}

/* run a read quietly; a failure is reported as "cannot read <what>" (the reader freed) */
static PetscErrorCode ReaderRun(SgCheckpointReader *rp, PetscErrorCode (*f)(void *), CkItem *it, const char what[])
{
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  PetscCall(Quietly((*rp)->comm, f, it, &ierr));
  if (ierr) {
    char     file[PETSC_MAX_PATH_LEN], w[128];
    MPI_Comm comm = (*rp)->comm;
    PetscCall(PetscStrncpy(file, (*rp)->file, sizeof(file)));
    PetscCall(PetscStrncpy(w, what, sizeof(w)));
    PetscCall(VecDestroy(&it->v));
    PetscCall(SgCheckpointReaderAbandon(rp));
    SETERRQ(comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is damaged: cannot read %s", file, w);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SgCheckpointReaderHasAttribute(SgCheckpointReader r, const char name[], PetscBool *has)
{
  CkItem it = {r, name, PETSC_INT, NULL, -1, NULL, PETSC_FALSE};

  PetscFunctionBeginUser;
  PetscCall(ReaderRun(&r, ItemHasAttribute, &it, name));
  *has = it.has;
  PetscFunctionReturn(0);
}

PetscErrorCode SgCheckpointReaderHasDataset(SgCheckpointReader r, const char name[], PetscBool *has)
{
  CkItem it = {r, name, PETSC_INT, NULL, -1, NULL, PETSC_FALSE};

  PetscFunctionBeginUser;
  PetscCall(ReaderRun(&r, ItemHasDataset, &it, name));
  *has = it.has;
  PetscFunctionReturn(0);
}

/* an attribute of /checkpoint (PETSC_INT: PetscInt *, PETSC_REAL: PetscReal *, PETSC_STRING: char ** to PetscFree) */
PetscErrorCode SgCheckpointReaderAttribute(SgCheckpointReader r, const char name[], PetscDataType type, void *value)
{
  CkItem it = {r, name, type, value, -1, NULL, PETSC_FALSE};

  PetscFunctionBeginUser;
  PetscCall(ReaderRun(&r, ItemAttribute, &it, name));
  PetscFunctionReturn(0);
}

/* a dataset of n numbers (n < 0: any number; *len says how many) into a (allocated here; PetscFree) */
PetscErrorCode SgCheckpointReaderReals(SgCheckpointReader r, const char name[], PetscInt n, PetscInt *len, PetscReal **a)
{
  CkItem             it = {r, name, PETSC_REAL, NULL, n, NULL, PETSC_FALSE};
  char               what[96];
  const PetscScalar *va;
  PetscInt           m;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(what, sizeof(what), "the dataset %s (of the expected size)", name));
  PetscCall(ReaderRun(&r, ItemDataset, &it, what));
  PetscCall(VecGetSize(it.v, &m));
  PetscCall(PetscMalloc1(m + 1, a));
  PetscCall(VecGetArrayRead(it.v, &va));
  for (PetscInt i = 0; i < m; i++) (*a)[i] = PetscRealPart(va[i]);
  PetscCall(VecRestoreArrayRead(it.v, &va));
  PetscCall(VecDestroy(&it.v));
  if (len) *len = m;
  PetscFunctionReturn(0);
}

/* this rank's rows lo..hi-1 of a dataset of bs numbers per vertex of the file, all finite (and >= 0 if nonneg; else
   refused as damaged, naming what and the first bad number in file order, as on one rank) (allocated here; PetscFree) */
static PetscErrorCode ReaderVertexRows(SgCheckpointReader *rp, const char name[], PetscInt bs, PetscBool nonneg, const char what[], PetscReal **a)
{
  SgCheckpointReader r   = *rp;
  CkRows             it  = {r, name, bs, NULL};
  const PetscInt     n   = (r->hi - r->lo) * bs;
  PetscInt           bad = PETSC_MAX_INT;
  PetscReal          val = 0;
  char               w[96];

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(n + 1, a));
  it.buf = *a;
  PetscCall(PetscSNPrintf(w, sizeof(w), "the dataset %s (of the expected size)", name));
  {
    PetscErrorCode ierr;
    PetscCall(Quietly(r->comm, ItemChunk, &it, &ierr));
    if (ierr) { /* as ReaderRun reports it */
      char     file[PETSC_MAX_PATH_LEN];
      MPI_Comm comm = r->comm;
      PetscCall(PetscFree(*a));
      PetscCall(PetscStrncpy(file, r->file, sizeof(file)));
      PetscCall(SgCheckpointReaderAbandon(rp));
      SETERRQ(comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is damaged: cannot read %s", file, w);
    }
  }
  for (PetscInt i = 0; bad == PETSC_MAX_INT && i < n; i++)
    if ((!PetscIsNormalReal((*a)[i]) && (*a)[i] != 0) || (nonneg && !((*a)[i] >= 0))) bad = r->lo * bs + i, val = (*a)[i];
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_MIN, r->comm));
  if (bad < PETSC_MAX_INT) {
    if (!(bad >= r->lo * bs && bad < r->hi * bs)) val = 0; /* the value of the first bad number, from its rank */
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &val, 1, MPIU_REAL, MPIU_SUM, r->comm));
    PetscCall(PetscFree(*a));
    PetscCall(SgCheckpointReaderDamaged(rp, what, val));
  }
  PetscFunctionReturn(0);
}

/* a dataset of bs numbers per vertex of the file, checked as ReaderVertexRows, at the vertices of the mesh (m->nv * bs,
   zeros at a vertex not in the file; allocated here; PetscFree): each rank reads its rows and sends them on */
static PetscErrorCode ReaderVertexData(SgCheckpointReader *rp, const char name[], PetscInt bs, PetscBool nonneg, const char what[], PetscReal **a)
{
  const SgMesh *m;
  PetscReal    *rows;
  MPI_Datatype  unit;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetMesh((*rp)->el, &m));
  PetscCall(ReaderVertexRows(rp, name, bs, nonneg, what, &rows));
  PetscCall(PetscCalloc1(m->nv * bs + 1, a));
  PetscCallMPI(MPI_Type_contiguous((PetscMPIInt)bs, MPIU_REAL, &unit));
  PetscCallMPI(MPI_Type_commit(&unit));
  PetscCall(PetscSFBcastBegin((*rp)->sf, unit, rows, *a, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd((*rp)->sf, unit, rows, *a, MPI_REPLACE));
  PetscCallMPI(MPI_Type_free(&unit));
  PetscCall(PetscFree(rows));
  PetscFunctionReturn(0);
}

/* a displacement per vertex into y (a global vector of the problem), matched by the coordinates; the prescribed
   components of y are 0 (the file holds the full displacement: a fixed component of a roller is data) */
PetscErrorCode SgCheckpointReaderDisplacement(SgCheckpointReader r, const char name[], const char what[], Vec y)
{
  const SgMesh  *m;
  const PetscInt dim = r->dim;
  PetscReal     *a;
  PetscScalar   *ya;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetMesh(r->el, &m));
  PetscCall(ReaderVertexData(&r, name, dim, PETSC_FALSE, what, &a));
  PetscCall(VecGetArray(y, &ya));
  for (PetscInt v = 0; v < m->nv; v++) {
    if (m->goff[v] < 0 || r->idx[v] < 0) continue;
    for (PetscInt d = 0; d < dim; d++) ya[m->goff[v] + d] = SgMeshFixed(m, v, d) ? 0 : a[v * dim + d];
  }
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(PetscFree(a));
  PetscFunctionReturn(0);
}

/* bs numbers per contact vertex into a (NULL: only checked), matched by the coordinates */
PetscErrorCode SgCheckpointReaderContact(SgCheckpointReader r, const char name[], PetscInt bs, PetscBool nonneg, const char what[], PetscReal a[])
{
  PetscInt        n    = 0;
  const PetscInt *vert = NULL;
  PetscReal      *f;

  PetscFunctionBeginUser;
  if (r->c) PetscCall(SgContactGetVertices(r->c, &n, NULL, &vert, NULL));
  PetscCall(ReaderVertexData(&r, name, bs, nonneg, what, &f));
  for (PetscInt i = 0; a && i < n; i++)
    for (PetscInt d = 0; d < bs; d++) a[i * bs + d] = f[vert[i] * bs + d]; /* 0 at a vertex not in the file */
  PetscCall(PetscFree(f));
  PetscFunctionReturn(0);
}

/* the history rows (of outer steps up to maxouter) into hist */
PetscErrorCode SgCheckpointReaderHistory(SgCheckpointReader r, PetscInt maxouter, SgHistory hist)
{
  PetscReal *ha;
  PetscInt   nh;

  PetscFunctionBeginUser;
  PetscCall(SgCheckpointReaderReals(r, "history", -1, &nh, &ha));
  {
    const char *what = NULL;
    PetscReal   val  = 0;
    if (nh % SG_HISTORY_NREALS) what = "the length of the history", val = nh;
    for (PetscInt i = 0; !what && i < nh / SG_HISTORY_NREALS; i++) {
      const PetscReal kind = ha[i * SG_HISTORY_NREALS], outer = ha[i * SG_HISTORY_NREALS + 1];
      if (!(kind == 0 || kind == 1)) what = "a history row kind", val = kind;
      else if (!(outer >= 0 && outer <= maxouter && outer == PetscFloorReal(outer))) what = "a history row's outer step", val = outer;
    }
    if (what) PetscCall(PetscFree(ha));
    if (what) PetscCall(SgCheckpointReaderDamaged(&r, what, val));
  }
  PetscCall(SgHistoryReset(hist));
  for (PetscInt i = 0; i < nh / SG_HISTORY_NREALS; i++) {
    SgHistoryRow row;
    SgHistoryRowFromReals(&ha[i * SG_HISTORY_NREALS], &row);
    PetscCall(SgHistoryAdd(hist, &row));
  }
  PetscCall(PetscFree(ha));
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

static void FindVertex(const PetscInt perm[], PetscInt n, const PetscReal x[], PetscInt *idx)
{
  PetscInt lo = 0, hi = n - 1;

  *idx = -1;
  while (lo <= hi) {
    const PetscInt mid = (lo + hi) / 2;
    const int      c   = CmpPoint(&SortX[perm[mid] * SortDim], x);
    if (!c) {
      *idx = perm[mid];
      return;
    }
    if (c < 0) lo = mid + 1;
    else hi = mid - 1;
  }
}

/* the rank that matches the vertices at point x (of the file and of the meshes of all ranks): a hash of its
   coordinates (-0 and 0 alike, as they compare equal) */
static PetscMPIInt PointRank(const PetscReal x[], PetscInt dim, PetscMPIInt size)
{
  unsigned long long h = 1469598103934665603ULL; /* FNV-1a */

  for (PetscInt d = 0; d < dim; d++) {
    const PetscReal c = x[d] == 0 ? 0 : x[d];
    unsigned char   b[sizeof(PetscReal)];
    memcpy(b, &c, sizeof(c));
    for (size_t k = 0; k < sizeof(c); k++) h = (h ^ b[k]) * 1099511628211ULL;
  }
  return (PetscMPIInt)(h % (unsigned long long)size);
}

/* send cnt[p] items of w numbers (buf, in rank order) to each rank p; *rbuf (allocated here; PetscFree) gets the
   items sent to this rank, rcnt[p] from rank p, in rank order */
static PetscErrorCode Exchange(MPI_Comm comm, MPI_Datatype type, size_t tsize, PetscInt w, const PetscMPIInt cnt[], const void *buf, PetscMPIInt rcnt[], PetscInt *nrecv, void **rbuf)
{
  PetscMPIInt size, *sc, *sd, *rc, *rd;
  PetscInt    sn = 0, rn = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Alltoall((void *)cnt, 1, MPI_INT, rcnt, 1, MPI_INT, comm));
  PetscCall(PetscMalloc4(size, &sc, size, &sd, size, &rc, size, &rd));
  for (PetscMPIInt p = 0; p < size; p++) {
    PetscCall(PetscMPIIntCast(cnt[p] * w, &sc[p]));
    PetscCall(PetscMPIIntCast(rcnt[p] * w, &rc[p]));
    PetscCall(PetscMPIIntCast(sn, &sd[p]));
    PetscCall(PetscMPIIntCast(rn, &rd[p]));
    sn += sc[p];
    rn += rc[p];
  }
  PetscCall(PetscMalloc(tsize * (size_t)(rn + 1), rbuf));
  PetscCallMPI(MPI_Alltoallv((void *)buf, sc, sd, type, *rbuf, rc, rd, type, comm));
  PetscCall(PetscFree4(sc, sd, rc, rd));
  *nrecv = rn / w;
  PetscFunctionReturn(0);
}

/* the file's coordinates (all finite) matched with the mesh's vertices: r->idx and r->sf; every owned and every
   contact vertex must be in the file. Each rank reads the file's vertices lo..hi-1; they and the mesh's vertices
   meet on the rank their coordinates hash to (PointRank), which answers each mesh vertex with its file vertex, so
   that no rank holds the whole file. */
static PetscErrorCode ReaderMatchVertices(SgCheckpointReader *rp)
{
  SgCheckpointReader r = *rp;
  const SgMesh      *m;
  PetscInt           ncv   = 0; /* the contact vertices */
  const PetscInt    *cvert = NULL;
  const PetscInt     dim   = r->dim;
  PetscReal         *x, *fx, *qx, *rfx, *rqx, *px;
  PetscInt          *perm, *pg, *ans, *rans, *order, nmiss = 0, nrf, nrq, nr, nleaves = 0, *ilocal;
  PetscMPIInt        size, *fc, *qc, *rfc, *rqc;
  PetscLayout        layout;
  const PetscInt    *range;
  PetscSFNode       *iremote;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetMesh(r->el, &m));
  if (r->c) PetscCall(SgContactGetVertices(r->c, &ncv, NULL, &cvert, NULL));
  PetscCallMPI(MPI_Comm_size(r->comm, &size));
  PetscCall(PetscLayoutCreate(r->comm, &layout));
  PetscCall(PetscLayoutSetSize(layout, r->nvert));
  PetscCall(PetscLayoutSetUp(layout));
  PetscCall(PetscLayoutGetRange(layout, &r->lo, &r->hi));
  PetscCall(PetscLayoutGetRanges(layout, &range));
  PetscCall(ReaderVertexRows(rp, "coordinates", dim, PETSC_FALSE, "a vertex coordinate", &x));
  /* the file's vertices (coordinates and number) and the mesh's (coordinates) to the ranks of their points */
  PetscCall(PetscCalloc4(size, &fc, size, &qc, size, &rfc, size, &rqc));
  PetscCall(PetscMalloc1((r->hi - r->lo) * (dim + 1) + 1, &fx));
  PetscCall(PetscMalloc1(m->nv * dim + 1, &qx));
  PetscCall(PetscMalloc1(m->nv + 1, &order));
  for (PetscInt i = 0; i < r->hi - r->lo; i++) fc[PointRank(&x[i * dim], dim, size)]++;
  for (PetscInt v = 0; v < m->nv; v++) qc[PointRank(&m->x[v * dim], dim, size)]++;
  {
    PetscInt *fo, *qo;
    PetscCall(PetscCalloc2(size + 1, &fo, size + 1, &qo));
    for (PetscMPIInt p = 0; p < size; p++) fo[p + 1] = fo[p] + fc[p], qo[p + 1] = qo[p] + qc[p];
    for (PetscInt i = 0; i < r->hi - r->lo; i++) {
      const PetscInt k = fo[PointRank(&x[i * dim], dim, size)]++;
      for (PetscInt d = 0; d < dim; d++) fx[k * (dim + 1) + d] = x[i * dim + d];
      fx[k * (dim + 1) + dim] = (PetscReal)(r->lo + i); /* exact below 2^53 */
    }
    for (PetscInt v = 0; v < m->nv; v++) {
      const PetscInt k = qo[PointRank(&m->x[v * dim], dim, size)]++;
      for (PetscInt d = 0; d < dim; d++) qx[k * dim + d] = m->x[v * dim + d];
      order[k] = v;
    }
    PetscCall(PetscFree2(fo, qo));
  }
  PetscCall(PetscFree(x));
  PetscCall(Exchange(r->comm, MPIU_REAL, sizeof(PetscReal), dim + 1, fc, fx, rfc, &nrf, (void **)&rfx));
  PetscCall(PetscFree(fx));
  PetscCall(Exchange(r->comm, MPIU_REAL, sizeof(PetscReal), dim, qc, qx, rqc, &nrq, (void **)&rqx));
  PetscCall(PetscFree(qx));
  /* here: the file's vertices sorted by their coordinates, the mesh vertices sent here looked up among them */
  PetscCall(PetscMalloc4(nrf * dim + 1, &px, nrf + 1, &pg, nrf + 1, &perm, nrq + 1, &ans));
  for (PetscInt i = 0; i < nrf; i++) {
    for (PetscInt d = 0; d < dim; d++) px[i * dim + d] = rfx[i * (dim + 1) + d];
    pg[i]   = (PetscInt)rfx[i * (dim + 1) + dim];
    perm[i] = i;
  }
  PetscCall(PetscFree(rfx));
  SortX   = px;
  SortDim = dim;
  qsort(perm, nrf, sizeof(PetscInt), CmpIndex);
  for (PetscInt k = 0; k < nrq; k++) {
    PetscInt i;
    FindVertex(perm, nrf, &rqx[k * dim], &i);
    ans[k] = i < 0 ? -1 : pg[i];
  }
  SortX = NULL;
  /* the answers back, in the order of the questions */
  PetscCall(Exchange(r->comm, MPIU_INT, sizeof(PetscInt), 1, rqc, ans, qc, &nr, (void **)&rans));
  PetscCall(PetscMalloc1(m->nv + 1, &r->idx));
  for (PetscInt k = 0; k < m->nv; k++) r->idx[order[k]] = rans[k];
  PetscCall(PetscFree4(px, pg, perm, ans));
  PetscCall(PetscFree(rqx));
  PetscCall(PetscFree(rans));
  PetscCall(PetscFree(order));
  PetscCall(PetscFree4(fc, qc, rfc, rqc));
  for (PetscInt v = 0; v < m->nv; v++) {
    if (r->idx[v] < 0 && m->goff[v] >= 0) nmiss++;
    if (r->idx[v] >= 0) nleaves++;
  }
  for (PetscInt i = 0; i < ncv; i++)
    if (r->idx[cvert[i]] < 0) nmiss++;
  /* the rows lo..hi-1 of each rank are the roots, the matched vertices of the mesh the leaves */
  PetscCall(PetscMalloc1(nleaves + 1, &ilocal));
  PetscCall(PetscMalloc1(nleaves + 1, &iremote));
  nleaves = 0;
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscMPIInt owner;
    if (r->idx[v] < 0) continue;
    PetscCall(PetscLayoutFindOwner(layout, r->idx[v], &owner));
    ilocal[nleaves]        = v;
    iremote[nleaves].rank  = owner;
    iremote[nleaves].index = r->idx[v] - range[owner];
    nleaves++;
  }
  PetscCall(PetscSFCreate(r->comm, &r->sf));
  PetscCall(PetscSFSetGraph(r->sf, r->hi - r->lo, nleaves, ilocal, PETSC_OWN_POINTER, iremote, PETSC_OWN_POINTER));
  PetscCall(PetscSFSetUp(r->sf));
  PetscCall(PetscLayoutDestroy(&layout));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nmiss, 1, MPIU_INT, MPI_SUM, r->comm));
  if (nmiss) {
    char     f[PETSC_MAX_PATH_LEN];
    MPI_Comm comm = r->comm;
    PetscCall(PetscStrncpy(f, r->file, sizeof(f)));
    PetscCall(SgCheckpointReaderAbandon(rp));
    SETERRQ(comm, PETSC_ERR_USER_INPUT, "-restart_file: %" PetscInt_FMT " vertices of this mesh are not in '%s': it was written for another mesh", nmiss, f);
  }
  PetscFunctionReturn(0);
}

/* the problem's numbers (E, nu, load and Dirichlet scales, gap sum; a file of an older version may lack them) and
   moments (the data with their signs and directions; an older file may lack them) against this run's */
static PetscErrorCode ReaderCheckProblem(SgCheckpointReader *rp)
{
  SgCheckpointReader r = *rp;
  PetscBool          has;
  PetscInt           nmom = 0, n, group = -1, bad = -1;
  PetscReal          print[SG_FINGERPRINT_NUMBERS], now[SG_FINGERPRINT_NUMBERS], F[SG_FINGERPRINT_MOMENTS_MAX], Sz[SG_FINGERPRINT_MOMENTS_MAX], *ma, a = 0, b = 0;
  char               f[PETSC_MAX_PATH_LEN], desc[128];
  MPI_Comm           comm = r->comm;

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(f, r->file, sizeof(f)));
  PetscCall(SgCheckpointReaderHasAttribute(r, SgFingerprintNames[0], &has));
  for (PetscInt i = 0; has && i < SG_FINGERPRINT_NUMBERS; i++) PetscCall(SgCheckpointReaderAttribute(r, SgFingerprintNames[i], PETSC_REAL, &print[i]));
  if (has) PetscCall(SgFingerprintNumbers(r->el, r->c, now));
  { /* the materials first: another one changes the loads' lifting and the stiffness, and would be reported as those */
    PetscInt  nck = 0, nnow, len;
    PetscReal tnow[3 * SG_MAX_IDS], *tck = NULL;
    PetscBool hm, same;
    PetscCall(SgCheckpointReaderHasAttribute(r, "materials", &hm));
    if (hm) PetscCall(SgCheckpointReaderAttribute(r, "materials", PETSC_INT, &nck));
    if (hm && (nck < 1 || nck > SG_MAX_IDS)) PetscCall(SgCheckpointReaderDamaged(rp, "the number of materials", (PetscReal)nck));
    if (nck) PetscCall(SgCheckpointReaderReals(r, "materials", 3 * nck, &len, &tck));
    PetscCall(SgFingerprintMaterials(r->el, &nnow, tnow));
    same = (PetscBool)(nck == nnow);
    for (PetscInt i = 0; same && i < 3 * nck; i++) same = (PetscBool)(tck[i] == tnow[i]);
    if (!same) {
      char      a[1024], b[1024];
      PetscReal En, nun;
      PetscCall(SgFingerprintMaterialText(nck, tck, has, print[0], print[1], a, sizeof(a)));
      PetscCall(SgElasticityGetMaterial(r->el, &En, &nun));
      PetscCall(SgFingerprintMaterialText(nnow, tnow, PETSC_TRUE, En, nun, b, sizeof(b)));
      PetscCall(PetscFree(tck));
      PetscCall(SgCheckpointReaderAbandon(rp));
      SETERRQ(comm, PETSC_ERR_USER_INPUT, "-restart_file: '%s' was written for another problem: the materials (-material_ids, -E, -nu) differ (%s in the checkpoint, %s in this run); a restart must solve the same problem", f, a, b);
    }
    PetscCall(PetscFree(tck));
  }
  for (PetscInt i = 0; has && i < SG_FINGERPRINT_NUMBERS; i++) {
    const PetscBool ok = (PetscBool)(PetscAbsReal(now[i] - print[i]) <= 1e-10 * PetscMax(PetscAbsReal(now[i]), PetscAbsReal(print[i])) + (i == 5 ? 1e-14 * PetscAbsReal(print[i]) : 0));
    if (!ok) PetscCall(SgCheckpointReaderAbandon(rp));
    PetscCheck(ok, comm, PETSC_ERR_USER_INPUT, "-restart_file: '%s' was written for another problem: %s differs (%s %.17g in the checkpoint, %.17g in this run); a restart must solve the same problem", f, SgFingerprintOptions[i], SgFingerprintNames[i], (double)print[i], (double)now[i]);
  }
  PetscCall(SgCheckpointReaderHasAttribute(r, "problem_moments", &has));
  if (!has) PetscFunctionReturn(0);
  PetscCall(SgCheckpointReaderAttribute(r, "problem_moments", PETSC_INT, &nmom));
  PetscCall(SgFingerprintMoments(r->el, r->c, &n, F, Sz));
  if (nmom != n) PetscCall(SgCheckpointReaderAbandon(rp));
  PetscCheck(nmom == n, comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is damaged: it holds %" PetscInt_FMT " moments of the problem, a %" PetscInt_FMT "D problem has %" PetscInt_FMT, f, nmom, r->dim, n);
  PetscCall(SgCheckpointReaderReals(r, "problem_moments", 2 * n, NULL, &ma));
  for (PetscInt i = 0; bad < 0 && i < 2 * n; i++)
    if (!PetscIsNormalReal(ma[i]) && ma[i] != 0) bad = i;
  if (bad < 0) SgFingerprintCompare(r->dim, n, ma, ma + n, F, Sz, &group, desc, sizeof(desc), &a, &b);
  else a = ma[bad];
  PetscCall(PetscFree(ma));
  if (bad >= 0) PetscCall(SgCheckpointReaderDamaged(rp, "a moment of the problem", a));
  if (group >= 0) PetscCall(SgCheckpointReaderAbandon(rp));
  PetscCheck(group < 0, comm, PETSC_ERR_USER_INPUT, "-restart_file: '%s' was written for another problem: %s (%s: %.17g in the checkpoint, %.17g in this run); a restart must solve the same problem", f, group >= 0 ? SgFingerprintGroups[group] : "", desc, (double)a, (double)b);
  PetscFunctionReturn(0);
}

/* Open file for a restart of this problem (el, c): a checkpoint of it, of this mesh (its vertices matched by their
   coordinates, on any partition). Refusals (no such file, not HDF5, another mesh or problem, damage) name
   -restart_file and the file. */
PetscErrorCode SgCheckpointReaderOpen(SgElasticity el, SgContact c, const char file[], SgCheckpointReader *rp)
{
  SgCheckpointReader r;
  PetscBool          exists;
  PetscErrorCode     ierr;
  PetscInt           dim, nvert;
  char               f[PETSC_MAX_PATH_LEN];
  MPI_Comm           comm0;

  PetscFunctionBeginUser;
  *rp = NULL;
  PetscCall(PetscStrncpy(f, file, sizeof(f)));
  PetscCall(SgElasticityGetComm(el, &comm0));
  PetscCall(PetscTestFile(file, 'r', &exists));
  PetscCheck(exists, comm0, PETSC_ERR_FILE_OPEN, "-restart_file: cannot read '%s'", f);
  PetscCall(PetscNew(&r));
  r->el   = el;
  r->c    = c;
  r->comm = comm0;
  PetscCall(PetscStrncpy(r->file, file, sizeof(r->file)));
  {
    /* a truncated or overwritten file fails here or in the reads below: the message names the option and the file */
    CkItem   it   = {r, NULL, PETSC_INT, NULL, -1, NULL, PETSC_FALSE};
    MPI_Comm comm = r->comm;
    PetscCall(Quietly(r->comm, ItemOpen, &it, &ierr));
    if (ierr) PetscCall(SgCheckpointReaderAbandon(&r)); /* a viewer whose file did not open fails its flush: quietly */
    PetscCheck(!ierr, comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is not a readable HDF5 file (truncated or damaged?)", f);
  }
  PetscCall(SgCheckpointReaderHasAttribute(r, "vertices", &exists));
  if (!exists) {
    MPI_Comm comm = r->comm;
    PetscCall(SgCheckpointReaderAbandon(&r));
    SETERRQ(comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is not a checkpoint of this program", f);
  }
  PetscCall(SgCheckpointReaderAttribute(r, "dim", PETSC_INT, &r->dim));
  PetscCall(SgCheckpointReaderAttribute(r, "vertices", PETSC_INT, &r->nvert));
  PetscCall(SgElasticityGetDimension(el, &dim));
  PetscCall(SgCheckpointOwnedVertices(el, &nvert));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nvert, 1, MPIU_INT, MPI_SUM, r->comm));
  if (!(r->dim == dim && r->nvert == nvert)) {
    MPI_Comm       comm = r->comm;
    const PetscInt fd = r->dim, fn = r->nvert;
    PetscCall(SgCheckpointReaderAbandon(&r));
    SETERRQ(comm, PETSC_ERR_USER_INPUT, "-restart_file: '%s' holds a %" PetscInt_FMT "D mesh of %" PetscInt_FMT " vertices, this run has a %" PetscInt_FMT "D mesh of %" PetscInt_FMT, f, fd, fn, dim, nvert);
  }
  PetscCall(ReaderCheckProblem(&r));
  PetscCall(ReaderMatchVertices(&r));
  *rp = r;
  PetscFunctionReturn(0);
}

/* Close the file (a failure there: the file is damaged) and free the reader. */
PetscErrorCode SgCheckpointReaderDestroy(SgCheckpointReader *rp)
{
  SgCheckpointReader r = *rp;
  CkItem             it;

  PetscFunctionBeginUser;
  if (!r) PetscFunctionReturn(0);
  it = (CkItem){r, NULL, PETSC_INT, NULL, -1, NULL, PETSC_FALSE};
  if (r->viewer) PetscCall(ReaderRun(rp, ItemClose, &it, "the file's end (closing it failed)"));
  PetscCall(SgCheckpointReaderAbandon(rp));
  PetscFunctionReturn(0);
}
