/* checkpoint_write.c: the checkpoint writer: it collects the datasets and attributes each owner of a state puts in
   (vertex data with the vertex coordinates, numbers every rank has, attributes) and writes them atomically. */
#include "io/ioimpl.h"
#include <petscviewerhdf5.h>

/* A vector of n numbers held by rank 0 (n on every rank), for the data every rank has a copy of. */
static PetscErrorCode RootVec(MPI_Comm comm, const char name[], PetscInt n, const PetscReal a[], Vec *v)
{
  PetscMPIInt  rank;
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

/* bs numbers per vertex of the mesh (vals, m->nv * bs) as a vertex-ordered vector: the owned vertices in local order,
   as the coordinates are written */
static PetscErrorCode VertexVector(SgElasticity el, const char name[], PetscInt bs, const PetscReal vals[], Vec *V)
{
  const SgMesh *m;
  PetscInt      nown, k = 0;
  MPI_Comm      comm;
  DM            dmVert;
  PetscSection  gs;
  PetscScalar  *va;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetComm(el, &comm));
  PetscCall(SgElasticityGetMesh(el, &m));
  PetscCall(SgElasticityGetDMs(el, NULL, &dmVert, NULL, NULL));
  PetscCall(DMGetGlobalSection(dmVert, &gs));
  PetscCall(SgCheckpointOwnedVertices(el, &nown));
  PetscCall(VecCreateMPI(comm, nown * bs, PETSC_DETERMINE, V));
  PetscCall(PetscObjectSetName((PetscObject)*V, name));
  PetscCall(VecGetArray(*V, &va));
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(gs, m->vStart + v, &off));
    if (off < 0) continue;
    for (PetscInt d = 0; d < bs; d++) va[k * bs + d] = vals[v * bs + d];
    k++;
  }
  PetscCall(VecRestoreArray(*V, &va));
  PetscFunctionReturn(0);
}

/* ---- the writer: collects the datasets and attributes, written by SgCheckpointWriterCommit */
typedef struct {
  char          name[64];
  PetscDataType type;
  PetscInt      i;
  PetscReal     r;
  char         *s;
} CkAttr;

struct _n_SgCheckpointWriter {
  SgElasticity el;
  SgContact    c;
  MPI_Comm     comm;
  char         file[PETSC_MAX_PATH_LEN];
  PetscInt     nvec, capvec, natt, capatt;
  Vec         *vec;
  CkAttr      *att;
};

static PetscErrorCode WriterAddVec(SgCheckpointWriter w, Vec v)
{
  PetscFunctionBeginUser;
  if (w->nvec == w->capvec) {
    w->capvec = 2 * w->capvec + 8;
    PetscCall(PetscRealloc(sizeof(Vec) * w->capvec, &w->vec));
  }
  w->vec[w->nvec++] = v;
  PetscFunctionReturn(0);
}

/* an attribute of /checkpoint: type PETSC_INT (value a PetscInt *), PETSC_REAL (PetscReal *) or PETSC_STRING (char *) */
PetscErrorCode SgCheckpointWriterAttribute(SgCheckpointWriter w, const char name[], PetscDataType type, const void *value)
{
  CkAttr *a;

  PetscFunctionBeginUser;
  PetscCheck(type == PETSC_INT || type == PETSC_REAL || type == PETSC_STRING, w->comm, PETSC_ERR_SUP, "SgCheckpointWriterAttribute: %s: an integer, real or string", name);
  if (w->natt == w->capatt) {
    w->capatt = 2 * w->capatt + 16;
    PetscCall(PetscRealloc(sizeof(CkAttr) * w->capatt, &w->att));
  }
  a = &w->att[w->natt++];
  PetscCall(PetscMemzero(a, sizeof(*a)));
  PetscCall(PetscStrncpy(a->name, name, sizeof(a->name)));
  a->type = type;
  if (type == PETSC_INT) a->i = *(const PetscInt *)value;
  else if (type == PETSC_REAL) a->r = *(const PetscReal *)value;
  else PetscCall(PetscStrallocpy((const char *)value, &a->s));
  PetscFunctionReturn(0);
}

/* n numbers that every rank has (rank 0's are written) */
PetscErrorCode SgCheckpointWriterReals(SgCheckpointWriter w, const char name[], PetscInt n, const PetscReal a[])
{
  Vec v;

  PetscFunctionBeginUser;
  PetscCall(RootVec(w->comm, name, n, a, &v));
  PetscCall(WriterAddVec(w, v));
  PetscFunctionReturn(0);
}

/* a displacement (a global vector of the problem) per vertex: with its Dirichlet values (with_data), else with zeros
   in the prescribed components */
PetscErrorCode SgCheckpointWriterDisplacement(SgCheckpointWriter w, const char name[], Vec y, PetscBool with_data)
{
  const SgMesh      *m;
  PetscInt           dim;
  DM                 dm;
  Vec                yloc, v;
  PetscReal         *vals;
  const PetscScalar *ya;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetDimension(w->el, &dim));
  PetscCall(SgElasticityGetMesh(w->el, &m));
  PetscCall(SgElasticityGetDMs(w->el, &dm, NULL, NULL, NULL));
  PetscCall(DMGetLocalVector(dm, &yloc));
  if (with_data) PetscCall(SgElasticityGlobalToLocal(w->el, y, yloc));
  else {
    PetscCall(VecSet(yloc, 0));
    PetscCall(DMGlobalToLocal(dm, y, INSERT_VALUES, yloc)); /* the free values: the Dirichlet ones are not read back */
  }
  PetscCall(PetscMalloc1(m->nv * dim + 1, &vals));
  PetscCall(VecGetArrayRead(yloc, &ya));
  for (PetscInt v = 0; v < m->nv; v++)
    for (PetscInt d = 0; d < dim; d++) vals[v * dim + d] = PetscRealPart(ya[m->loff[v] + d]);
  PetscCall(VecRestoreArrayRead(yloc, &ya));
  PetscCall(DMRestoreLocalVector(dm, &yloc));
  PetscCall(VertexVector(w->el, name, dim, vals, &v));
  PetscCall(PetscFree(vals));
  PetscCall(WriterAddVec(w, v));
  PetscFunctionReturn(0);
}

/* bs numbers per contact vertex (a; NULL: zeros), zeros at the other vertices */
PetscErrorCode SgCheckpointWriterContact(SgCheckpointWriter w, const char name[], PetscInt bs, const PetscReal a[])
{
  const SgMesh   *m;
  PetscInt        n    = 0;
  const PetscInt *vert = NULL;
  PetscReal      *vals;
  Vec             v;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetMesh(w->el, &m));
  if (w->c) PetscCall(SgContactGetVertices(w->c, &n, NULL, &vert, NULL));
  PetscCall(PetscCalloc1(m->nv * bs + 1, &vals));
  for (PetscInt i = 0; a && i < n; i++)
    for (PetscInt d = 0; d < bs; d++) vals[vert[i] * bs + d] = a[i * bs + d];
  PetscCall(VertexVector(w->el, name, bs, vals, &v));
  PetscCall(PetscFree(vals));
  PetscCall(WriterAddVec(w, v));
  PetscFunctionReturn(0);
}

PetscErrorCode SgCheckpointWriterHistory(SgCheckpointWriter w, SgHistory hist)
{
  PetscInt      nh;
  SgHistoryRow *rows;
  PetscReal    *a;

  PetscFunctionBeginUser;
  PetscCall(SgHistoryGetRows(hist, &nh, &rows));
  PetscCall(PetscMalloc1(SG_HISTORY_NREALS * nh + 1, &a));
  for (PetscInt i = 0; i < nh; i++) SgHistoryRowToReals(&rows[i], &a[i * SG_HISTORY_NREALS]);
  PetscCall(SgCheckpointWriterReals(w, "history", SG_HISTORY_NREALS * nh, a));
  PetscCall(PetscFree(a));
  PetscFunctionReturn(0);
}

/* whether a dataset or attribute of this name was put in */
PetscErrorCode SgCheckpointWriterHas(SgCheckpointWriter w, const char name[], PetscBool *has)
{
  PetscFunctionBeginUser;
  *has = PETSC_FALSE;
  for (PetscInt i = 0; !*has && i < w->natt; i++) PetscCall(PetscStrcmp(w->att[i].name, name, has));
  for (PetscInt i = 0; !*has && i < w->nvec; i++) {
    const char *n;
    PetscCall(PetscObjectGetName((PetscObject)w->vec[i], &n));
    PetscCall(PetscStrcmp(n, name, has));
  }
  PetscFunctionReturn(0);
}

/* A writer for file with what identifies the problem and its mesh: the vertex coordinates, the mesh size and the
   fingerprint (SgFingerprintNumbers, SgFingerprintMoments). */
PetscErrorCode SgCheckpointWriterCreate(SgElasticity el, SgContact c, const char file[], SgCheckpointWriter *wp)
{
  SgCheckpointWriter w;
  const SgMesh      *m;
  PetscInt           dim, nvert, nmom;
  PetscReal          print[SG_FINGERPRINT_NUMBERS], F[SG_FINGERPRINT_MOMENTS_MAX], Sz[SG_FINGERPRINT_MOMENTS_MAX], a[2 * SG_FINGERPRINT_MOMENTS_MAX];
  Vec                X;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&w));
  w->el = el;
  w->c  = c;
  PetscCall(SgElasticityGetComm(el, &w->comm));
  PetscCall(PetscStrncpy(w->file, file, sizeof(w->file)));
  PetscCall(SgElasticityGetDimension(el, &dim));
  PetscCall(SgElasticityGetMesh(el, &m));
  PetscCall(VertexVector(el, "coordinates", dim, m->x, &X));
  PetscCall(WriterAddVec(w, X));
  PetscCall(VecGetSize(X, &nvert));
  nvert /= dim;
  PetscCall(SgCheckpointWriterAttribute(w, "dim", PETSC_INT, &dim));
  PetscCall(SgCheckpointWriterAttribute(w, "vertices", PETSC_INT, &nvert));
  PetscCall(SgFingerprintNumbers(el, c, print));
  for (PetscInt i = 0; i < SG_FINGERPRINT_NUMBERS; i++) PetscCall(SgCheckpointWriterAttribute(w, SgFingerprintNames[i], PETSC_REAL, &print[i]));
  PetscCall(SgFingerprintMoments(el, c, &nmom, F, Sz));
  for (PetscInt i = 0; i < nmom; i++) a[i] = F[i], a[nmom + i] = Sz[i];
  PetscCall(SgCheckpointWriterReals(w, "problem_moments", 2 * nmom, a));
  PetscCall(SgCheckpointWriterAttribute(w, "problem_moments", PETSC_INT, &nmom));
  {
    PetscInt  nmat;
    PetscReal t[3 * SG_MAX_IDS];
    PetscCall(SgFingerprintMaterials(el, &nmat, t));
    if (nmat) { /* absent: one material (as in the files of earlier versions) */
      PetscCall(SgCheckpointWriterReals(w, "materials", 3 * nmat, t));
      PetscCall(SgCheckpointWriterAttribute(w, "materials", PETSC_INT, &nmat));
    }
  }
  *wp = w;
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteBody(PetscViewer viewer, void *ctx)
{
  SgCheckpointWriter w = (SgCheckpointWriter)ctx;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/checkpoint"));
  for (PetscInt i = 0; i < w->nvec; i++) PetscCall(VecView(w->vec[i], viewer));
  for (PetscInt i = 0; i < w->natt; i++) {
    const CkAttr *a = &w->att[i];
    const void   *v = a->type == PETSC_INT ? (const void *)&a->i : (a->type == PETSC_REAL ? (const void *)&a->r : (const void *)a->s);
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/checkpoint", a->name, a->type, v));
  }
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscFunctionReturn(0);
}

/* Write the file (atomically). ok = PETSC_FALSE and msg say why if it could not be written (a full disk, say): the
   caller decides what that means for the run. */
PetscErrorCode SgCheckpointWriterCommit(SgCheckpointWriter w, PetscBool *ok, char msg[], size_t len)
{
  PetscFunctionBeginUser;
  PetscCall(SgFileWriteHDF5(w->comm, "-checkpoint_file", w->file, WriteBody, w, PETSC_TRUE, ok, msg, len));
  PetscFunctionReturn(0);
}

PetscErrorCode SgCheckpointWriterDestroy(SgCheckpointWriter *wp)
{
  SgCheckpointWriter w = *wp;

  PetscFunctionBeginUser;
  if (!w) PetscFunctionReturn(0);
  for (PetscInt i = 0; i < w->nvec; i++) PetscCall(VecDestroy(&w->vec[i]));
  for (PetscInt i = 0; i < w->natt; i++) PetscCall(PetscFree(w->att[i].s));
  PetscCall(PetscFree(w->vec));
  PetscCall(PetscFree(w->att));
  PetscCall(PetscFree(*wp));
  PetscFunctionReturn(0);
}
