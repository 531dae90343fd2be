/* checkpoint.c: the checkpoint file (-checkpoint_file, -restart_file): the problem's fingerprint, atomic writing, and a
   writer and a reader through which each owner of a state saves and loads its own (src/cont/state.c). Vertex data are
   stored with the vertex coordinates and matched by them on reading, so a restart may use another number of ranks
   (another partition) than the run that wrote the file. */
#include "io/ioimpl.h"
#include <petscviewerhdf5.h>

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

/* What identifies the problem a checkpoint belongs to: a restart of another problem (another -E, -nu, load, Dirichlet
   data or obstacle) would resume a continuation path, and report an unconstrained energy, of a problem it is not. */
#define NPRINT 6
static const char *PrintNames[NPRINT] = {"E", "nu", "load_norm", "load_max", "dirichlet_energy", "gap_sum"};
static const char *PrintOptions[NPRINT] = {"-E", "-nu", "the loads (-body_force, -neumann_traction, ...)", "the loads (-body_force, -neumann_traction, ...)", "the Dirichlet data (-dirichlet_values)", "the obstacle (-obstacle_*) or the contact boundary"};

static PetscErrorCode ProblemPrint(SgElasticity el, SgContact c, PetscReal print[NPRINT])
{
  PetscReal gs = 0;

  PetscFunctionBeginUser;
  /* the full load and the obstacle at its full placement: the same problem at every load step */
  if (c) PetscCall(SgContactGapSum(c, 1.0, &gs));
  PetscCall(SgElasticityGetMaterial(el, &print[0], &print[1]));
  PetscCall(SgElasticityGetFullLoadScales(el, &print[2], &print[3], &print[4]));
  print[5] = gs;
  PetscFunctionReturn(0);
}

/* Several materials (-material_ids): their ids, E and nu (3 n numbers), named in a refusal (the stiffness moments
   below tell that K differs, not how) */
static PetscErrorCode MaterialTable(SgElasticity el, PetscInt *n, PetscReal t[3 * SG_MAX_IDS])
{
  const PetscInt  *ids;
  const PetscReal *E, *nu;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetMaterials(el, NULL, n, &ids, &E, &nu));
  for (PetscInt k = 0; k < *n; k++) {
    t[3 * k]     = (PetscReal)ids[k];
    t[3 * k + 1] = E[k];
    t[3 * k + 2] = nu[k];
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode MaterialText(PetscInt n, const PetscReal t[], PetscBool hasE, PetscReal E, PetscReal nu, char txt[], size_t len)
{
  PetscFunctionBeginUser;
  if (!n) {
    if (hasE) PetscCall(PetscSNPrintf(txt, len, "one material, -E %g -nu %g", (double)E, (double)nu));
    else PetscCall(PetscSNPrintf(txt, len, "one material"));
    PetscFunctionReturn(0);
  }
  txt[0] = 0;
  for (PetscInt j = 0; j < 3; j++) {
    size_t l;
    PetscCall(PetscStrlen(txt, &l));
    PetscCall(PetscSNPrintf(txt + l, len - l, "%s", j == 0 ? "-material_ids " : (j == 1 ? " -E " : " -nu ")));
    for (PetscInt k = 0; k < n; k++) {
      PetscCall(PetscStrlen(txt, &l));
      if (j == 0) PetscCall(PetscSNPrintf(txt + l, len - l, "%s%" PetscInt_FMT, k ? "," : "", (PetscInt)t[3 * k]));
      else PetscCall(PetscSNPrintf(txt + l, len - l, "%s%g", k ? "," : "", (double)t[3 * k + j]));
    }
  }
  PetscFunctionReturn(0);
}

/* The problem's identity beyond those numbers, blind to no sign or direction: weighted sums ("moments") of its data
   with fixed weight fields w_k(x) of the vertex coordinates (scaled to the mesh's bounding box), each with the sum of
   the absolute values of its terms (its size). They do not depend on the partition (each vertex, cell or facet is
   summed once) up to the round-off of parallel sums, and are compared to 1e-10 of the size. The groups: */
#define NMOM 6 /* weight fields */
#define NGROUP 6
static const char *MomentGroups[NGROUP] = {"the loads (-body_force, -neumann_traction, ...) differ", "the Dirichlet values (-dirichlet_values) differ", "the fixed components (-dirichlet_ids, -dirichlet_components) differ", "the stiffness (-E, -nu, -material_ids, -material_label, -elasticity_rigid_shift) differs", "the contact boundary (-contact_ids, -contact_label) differs", "the obstacle (-obstacle_*) differs"};
#define MOM_MAX (3 * NMOM * 3 + 2 + 2 * NMOM)

/* numbers per group in a dim-dimensional problem: loads, Dirichlet values and fixed components per weight and
   component, two quadratic forms of the stiffness, the contact boundary's and the gaps' moments per weight */
static void MomentGroupSizes(PetscInt dim, PetscInt len[NGROUP])
{
  len[0] = len[1] = len[2] = NMOM * dim;
  len[3]               = 2;
  len[4] = len[5] = NMOM;
}

static void MomentWeights(PetscInt dim, const PetscReal lo[3], const PetscReal hi[3], const PetscReal x[], PetscReal w[NMOM])
{
  PetscReal h[3] = {0, 0, 0};

  for (PetscInt d = 0; d < dim; d++) h[d] = hi[d] > lo[d] ? (x[d] - lo[d]) / (hi[d] - lo[d]) : 0;
  w[0] = 1;
  w[1] = h[0];
  w[2] = h[1];
  w[3] = h[0] * h[1] + h[2];
  w[4] = PetscCosReal(0.9 + 2.7 * h[0] + 3.3 * h[1] + 2.1 * h[2]);
  w[5] = PetscSinReal(0.4 + 4.1 * h[0] - 2.9 * h[1] + 3.7 * h[2]);
}

/* the moments F[] and their sizes S[] (n of each) of the problem at factor 1 */
static PetscErrorCode ProblemMoments(SgElasticity el, SgContact c, PetscInt *n, PetscReal F[MOM_MAX], PetscReal S[MOM_MAX])
{
  const SgMesh      *m;
  MPI_Comm           comm;
  PetscInt           dim, len[NGROUP], off[NGROUP + 1];
  PetscReal          lo[3], hi[3], w[NMOM], buf[2 * MOM_MAX];
  DM                 dm, dmVert;
  PetscSection       gs;
  Vec                f, ubc, K1, K2, KV;
  Mat                K;
  const PetscScalar *fa, *ua;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetComm(el, &comm));
  PetscCall(SgElasticityGetDimension(el, &dim));
  PetscCall(SgElasticityGetMesh(el, &m));
  PetscCall(SgElasticityGetDMs(el, &dm, &dmVert, NULL, NULL));
  PetscCall(DMGetGlobalSection(dmVert, &gs));
  MomentGroupSizes(dim, len);
  off[0] = 0;
  for (PetscInt g = 0; g < NGROUP; g++) off[g + 1] = off[g] + len[g];
  *n = off[NGROUP];
  for (PetscInt i = 0; i < 2 * MOM_MAX; i++) buf[i] = 0;
  /* the bounding box (min and max: the same on any partition) */
  for (PetscInt d = 0; d < 3; d++) lo[d] = PETSC_MAX_REAL, hi[d] = PETSC_MIN_REAL;
  for (PetscInt v = 0; v < m->nv; v++)
    for (PetscInt d = 0; d < dim; d++) lo[d] = PetscMin(lo[d], m->x[v * dim + d]), hi[d] = PetscMax(hi[d], m->x[v * dim + d]);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, lo, 3, MPIU_REAL, MPI_MIN, comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, hi, 3, MPIU_REAL, MPI_MAX, comm));
  /* the load: this rank's cells' and facets' part at every vertex it has; the Dirichlet data at the owned vertices */
  PetscCall(SgElasticityGetFullData(el, &f, &ubc));
  PetscCall(VecGetArrayRead(f, &fa));
  PetscCall(VecGetArrayRead(ubc, &ua));
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt goff;
    MomentWeights(dim, lo, hi, &m->x[v * dim], w);
    for (PetscInt k = 0; k < NMOM; k++)
      for (PetscInt d = 0; d < dim; d++) {
        const PetscReal t = PetscRealPart(fa[m->loff[v] + d]) * w[k];
        buf[off[0] + k * dim + d] += t;
        buf[MOM_MAX + off[0] + k * dim + d] += PetscAbsReal(t);
      }
    PetscCall(PetscSectionGetOffset(gs, m->vStart + v, &goff));
    if (goff < 0 || !m->bcmask[v]) continue;
    for (PetscInt k = 0; k < NMOM; k++)
      for (PetscInt d = 0; d < dim; d++) {
        if (!SgMeshFixed(m, v, d)) continue;
        const PetscReal t = PetscRealPart(ua[m->loff[v] + d]) * w[k];
        buf[off[1] + k * dim + d] += t;
        buf[MOM_MAX + off[1] + k * dim + d] += PetscAbsReal(t);
        buf[off[2] + k * dim + d] += w[k];
        buf[MOM_MAX + off[2] + k * dim + d] += PetscAbsReal(w[k]);
      }
  }
  PetscCall(VecRestoreArrayRead(f, &fa));
  PetscCall(VecRestoreArrayRead(ubc, &ua));
  /* the stiffness: v^T K v for two smooth fields v that are no rigid motion */
  PetscCall(SgElasticityGetOperators(el, &K, NULL));
  PetscCall(DMCreateGlobalVector(dm, &K1));
  PetscCall(VecDuplicate(K1, &K2));
  PetscCall(VecDuplicate(K1, &KV));
  {
    PetscScalar *a1, *a2;
    PetscCall(VecGetArray(K1, &a1));
    PetscCall(VecGetArray(K2, &a2));
    for (PetscInt v = 0; v < m->nv; v++) {
      if (m->goff[v] < 0) continue;
      MomentWeights(dim, lo, hi, &m->x[v * dim], w);
      for (PetscInt d = 0; d < dim; d++) {
        a1[m->goff[v] + d] = d == 0 ? w[4] : (d == 1 ? w[5] : w[4] * w[5]);
        a2[m->goff[v] + d] = d == 0 ? w[5] * w[1] : (d == 1 ? w[4] + w[2] : w[3]);
      }
    }
    PetscCall(VecRestoreArray(K1, &a1));
    PetscCall(VecRestoreArray(K2, &a2));
  }
  for (PetscInt j = 0; j < 2; j++) {
    Vec                V = j ? K2 : K1;
    const PetscScalar *va, *kva;
    PetscInt           nloc;
    PetscCall(MatMult(K, V, KV));
    PetscCall(VecGetLocalSize(V, &nloc));
    PetscCall(VecGetArrayRead(V, &va));
    PetscCall(VecGetArrayRead(KV, &kva));
    for (PetscInt i = 0; i < nloc; i++) {
      const PetscReal t = PetscRealPart(va[i]) * PetscRealPart(kva[i]);
      buf[off[3] + j] += t;
      buf[MOM_MAX + off[3] + j] += PetscAbsReal(t);
    }
    PetscCall(VecRestoreArrayRead(V, &va));
    PetscCall(VecRestoreArrayRead(KV, &kva));
  }
  PetscCall(VecDestroy(&K1));
  PetscCall(VecDestroy(&K2));
  PetscCall(VecDestroy(&KV));
  /* the contact boundary (its weights) and the gaps with the obstacle at its full placement */
  if (c) {
    SgContactView cv;
    PetscReal    *gap;
    PetscCall(SgContactGetView(c, &cv));
    PetscCall(PetscMalloc1(cv.n + 1, &gap));
    PetscCall(SgContactGapsAt(c, 1.0, gap));
    for (PetscInt i = 0; i < cv.n; i++) {
      MomentWeights(dim, lo, hi, &m->x[cv.vert[i] * dim], w);
      for (PetscInt k = 0; k < NMOM; k++) {
        const PetscReal a = cv.w[i] * w[k], g = gap[i] < PETSC_MAX_REAL ? a * gap[i] : 0; /* a ray that misses: no gap */
        buf[off[4] + k] += a;
        buf[MOM_MAX + off[4] + k] += PetscAbsReal(a);
        buf[off[5] + k] += g;
        buf[MOM_MAX + off[5] + k] += PetscAbsReal(g);
      }
    }
    PetscCall(PetscFree(gap));
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, buf, 2 * MOM_MAX, MPIU_REAL, MPI_SUM, comm));
  for (PetscInt i = 0; i < *n; i++) F[i] = buf[i], S[i] = buf[MOM_MAX + i];
  PetscFunctionReturn(0);
}

/* the first moment or size (*what >= 0; -1: none) in which two problems differ beyond round-off; which group, and a
   description of it */
static void MomentsCompare(PetscInt dim, PetscInt n, const PetscReal F0[], const PetscReal S0[], const PetscReal F1[], const PetscReal S1[], PetscInt *group, char desc[], size_t len, PetscReal *a, PetscReal *b)
{
  PetscInt lens[NGROUP], g = 0, start = 0;

  *group = -1;
  MomentGroupSizes(dim, lens);
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal tol = 1e-10 * PetscMax(S0[i], S1[i]);
    const PetscBool same = (PetscBool)(PetscAbsReal(F0[i] - F1[i]) <= tol && PetscAbsReal(S0[i] - S1[i]) <= tol);
    while (g < NGROUP - 1 && i >= start + lens[g]) start += lens[g++];
    if (same) continue;
    {
      const PetscInt j = i - start, k = g < 3 ? j / dim : j;
      const PetscBool sz = (PetscBool)(PetscAbsReal(F0[i] - F1[i]) <= tol);
      if (g < 3) (void)PetscSNPrintf(desc, len, "%s %" PetscInt_FMT " of the %c components", sz ? "the size of weighted sum" : "weighted sum", k, "xyz"[j % dim]);
      else if (g == 3) (void)PetscSNPrintf(desc, len, "%s %" PetscInt_FMT, sz ? "the size of quadratic form" : "quadratic form", k);
      else (void)PetscSNPrintf(desc, len, "%s %" PetscInt_FMT, sz ? "the size of weighted sum" : "weighted sum", k);
      *group = g;
      *a     = sz ? S0[i] : F0[i];
      *b     = sz ? S1[i] : F1[i];
    }
    return;
  }
}

/* ------------------------------------------------------------------ the file
   The group /checkpoint holds the vertex coordinates (by which a reader matches the vertices of any partition), the
   mesh size and the problem's fingerprint, written and checked here; beside them, whatever each owner of a state puts
   in through a writer and takes out through a reader (the controller, its type, the friction state, the load steps:
   src/cont/state.c). The file is written whole or not at all (SgFileWriteHDF5: a .part renamed). */

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

/* bs numbers per vertex of the mesh (vals, m->nv * bs) as a vertex-ordered vector: the owned vertices in local order,
   as the coordinates are written */
static PetscErrorCode OwnedVertices(SgElasticity el, PetscInt *nown)
{
  const SgMesh *m;
  DM            dmVert;
  PetscSection  gs;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetMesh(el, &m));
  PetscCall(SgElasticityGetDMs(el, NULL, &dmVert, NULL, NULL));
  PetscCall(DMGetGlobalSection(dmVert, &gs));
  *nown = 0;
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(gs, m->vStart + v, &off));
    if (off >= 0) (*nown)++;
  }
  PetscFunctionReturn(0);
}

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
  PetscCall(OwnedVertices(el, &nown));
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
    Vec *a;
    w->capvec = 2 * w->capvec + 8;
    PetscCall(PetscMalloc1(w->capvec, &a));
    PetscCall(PetscArraycpy(a, w->vec, w->nvec));
    PetscCall(PetscFree(w->vec));
    w->vec = a;
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
    CkAttr *b;
    w->capatt = 2 * w->capatt + 16;
    PetscCall(PetscMalloc1(w->capatt, &b));
    PetscCall(PetscArraycpy(b, w->att, w->natt));
    PetscCall(PetscFree(w->att));
    w->att = b;
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
  const SgMesh *m;
  SgContactView cv = {0};
  PetscReal    *vals;
  Vec           v;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetMesh(w->el, &m));
  if (w->c) PetscCall(SgContactGetView(w->c, &cv));
  PetscCall(PetscCalloc1(m->nv * bs + 1, &vals));
  for (PetscInt i = 0; a && i < cv.n; i++)
    for (PetscInt d = 0; d < bs; d++) vals[cv.vert[i] * bs + d] = a[i * bs + d];
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
  PetscCall(PetscMalloc1(NHIST * nh + 1, &a));
  for (PetscInt i = 0; i < nh; i++) RowToReals(&rows[i], &a[i * NHIST]);
  PetscCall(SgCheckpointWriterReals(w, "history", NHIST * nh, a));
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
   fingerprint (ProblemPrint, ProblemMoments). */
PetscErrorCode SgCheckpointWriterCreate(SgElasticity el, SgContact c, const char file[], SgCheckpointWriter *wp)
{
  SgCheckpointWriter w;
  const SgMesh      *m;
  PetscInt           dim, nvert, nmom;
  PetscReal          print[NPRINT], F[MOM_MAX], Sz[MOM_MAX], a[2 * MOM_MAX];
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
  PetscCall(ProblemPrint(el, c, print));
  for (PetscInt i = 0; i < NPRINT; i++) PetscCall(SgCheckpointWriterAttribute(w, PrintNames[i], PETSC_REAL, &print[i]));
  PetscCall(ProblemMoments(el, c, &nmom, F, Sz));
  for (PetscInt i = 0; i < nmom; i++) a[i] = F[i], a[nmom + i] = Sz[i];
  PetscCall(SgCheckpointWriterReals(w, "problem_moments", 2 * nmom, a));
  PetscCall(SgCheckpointWriterAttribute(w, "problem_moments", PETSC_INT, &nmom));
  {
    PetscInt  nmat;
    PetscReal t[3 * SG_MAX_IDS];
    PetscCall(MaterialTable(el, &nmat, t));
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
  PetscInt    *idx; /* the file's vertex of each vertex of the mesh (-1: not in the file) */
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

static PetscErrorCode ItemOpen(void *ctx)
{
  CkItem *it = (CkItem *)ctx;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5Open(PETSC_COMM_SELF, it->r->file, FILE_MODE_READ, &it->r->viewer));
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

/* Close the file and free the reader, with error printing off (a damaged file can fail at H5Fclose): for a refusal,
   before the error is returned. */
PetscErrorCode SgCheckpointReaderAbandon(SgCheckpointReader *rp)
{
  SgCheckpointReader r = *rp;
  CkItem             it = {r, NULL, PETSC_INT, NULL, -1, NULL, PETSC_FALSE};
  PetscErrorCode     ierr;

  PetscFunctionBeginUser;
  if (!r) PetscFunctionReturn(0);
  if (r->viewer) PetscCall(Quietly(r->comm, ItemClose, &it, &ierr));
  PetscCall(PetscFree(r->idx));
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

/* a dataset of bs numbers per vertex of the file, all finite (and >= 0 if nonneg; else refused as damaged, naming
   what), in file order (allocated here; PetscFree) */
static PetscErrorCode ReaderVertexData(SgCheckpointReader *rp, const char name[], PetscInt bs, PetscBool nonneg, const char what[], PetscReal **a)
{
  PetscInt bad = -1, n;

  PetscFunctionBeginUser;
  PetscCall(SgCheckpointReaderReals(*rp, name, (*rp)->nvert * bs, &n, a));
  for (PetscInt i = 0; bad < 0 && i < n; i++)
    if ((!PetscIsNormalReal((*a)[i]) && (*a)[i] != 0) || (nonneg && !((*a)[i] >= 0))) bad = i;
  if (bad >= 0) {
    const PetscReal val = (*a)[bad];
    PetscCall(PetscFree(*a));
    PetscCall(SgCheckpointReaderDamaged(rp, what, val));
  }
  PetscFunctionReturn(0);
}

/* a displacement per vertex into y (a global vector of the problem), matched by the coordinates; the prescribed
   components of y are 0 (the file holds the full displacement: a fixed component of a roller is data) */
PetscErrorCode SgCheckpointReaderDisplacement(SgCheckpointReader r, const char name[], const char what[], Vec y)
{
  const SgMesh *m;
  const PetscInt dim = r->dim;
  PetscReal    *a;
  PetscScalar  *ya;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetMesh(r->el, &m));
  PetscCall(ReaderVertexData(&r, name, dim, PETSC_FALSE, what, &a));
  PetscCall(VecGetArray(y, &ya));
  for (PetscInt v = 0; v < m->nv; v++) {
    if (m->goff[v] < 0 || r->idx[v] < 0) continue;
    for (PetscInt d = 0; d < dim; d++) ya[m->goff[v] + d] = SgMeshFixed(m, v, d) ? 0 : a[r->idx[v] * dim + d];
  }
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(PetscFree(a));
  PetscFunctionReturn(0);
}

/* bs numbers per contact vertex into a (NULL: only checked), matched by the coordinates */
PetscErrorCode SgCheckpointReaderContact(SgCheckpointReader r, const char name[], PetscInt bs, PetscBool nonneg, const char what[], PetscReal a[])
{
  SgContactView cv = {0};
  PetscReal    *f;

  PetscFunctionBeginUser;
  if (r->c) PetscCall(SgContactGetView(r->c, &cv));
  PetscCall(ReaderVertexData(&r, name, bs, nonneg, what, &f));
  for (PetscInt i = 0; a && i < cv.n; i++)
    for (PetscInt d = 0; d < bs; d++) a[i * bs + d] = r->idx[cv.vert[i]] >= 0 ? f[r->idx[cv.vert[i]] * bs + d] : 0;
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
    if (nh % NHIST) what = "the length of the history", val = nh;
    for (PetscInt i = 0; !what && i < nh / NHIST; i++) {
      const PetscReal kind = ha[i * NHIST], outer = ha[i * NHIST + 1];
      if (!(kind == 0 || kind == 1)) what = "a history row kind", val = kind;
      else if (!(outer >= 0 && outer <= maxouter && outer == PetscFloorReal(outer))) what = "a history row's outer step", val = outer;
    }
    if (what) PetscCall(PetscFree(ha));
    if (what) PetscCall(SgCheckpointReaderDamaged(&r, what, val));
  }
  PetscCall(SgHistoryReset(hist));
  for (PetscInt i = 0; i < nh / NHIST; i++) {
    SgHistoryRow row;
    RealsToRow(&ha[i * NHIST], &row);
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

/* the file's coordinates (all finite) matched with the mesh's vertices: r->idx; every owned and every contact vertex
   must be in the file */
static PetscErrorCode ReaderMatchVertices(SgCheckpointReader *rp)
{
  SgCheckpointReader r = *rp;
  const SgMesh      *m;
  SgContactView      cv = {0};
  PetscReal         *x;
  PetscInt          *perm, nmiss = 0;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetMesh(r->el, &m));
  if (r->c) PetscCall(SgContactGetView(r->c, &cv));
  PetscCall(ReaderVertexData(rp, "coordinates", r->dim, PETSC_FALSE, "a vertex coordinate", &x));
  PetscCall(PetscMalloc1(r->nvert + 1, &perm));
  PetscCall(PetscMalloc1(m->nv + 1, &r->idx));
  for (PetscInt i = 0; i < r->nvert; i++) perm[i] = i;
  SortX   = x;
  SortDim = r->dim;
  qsort(perm, r->nvert, sizeof(PetscInt), CmpIndex);
  for (PetscInt v = 0; v < m->nv; v++) {
    FindVertex(perm, r->nvert, &m->x[v * r->dim], &r->idx[v]);
    if (r->idx[v] < 0 && m->goff[v] >= 0) nmiss++;
  }
  for (PetscInt i = 0; i < cv.n; i++)
    if (r->idx[cv.vert[i]] < 0) nmiss++;
  SortX = NULL;
  PetscCall(PetscFree(perm));
  PetscCall(PetscFree(x));
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
  PetscReal          print[NPRINT], now[NPRINT], F[MOM_MAX], Sz[MOM_MAX], *ma, a = 0, b = 0;
  char               f[PETSC_MAX_PATH_LEN], desc[128];
  MPI_Comm           comm = r->comm;

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(f, r->file, sizeof(f)));
  PetscCall(SgCheckpointReaderHasAttribute(r, PrintNames[0], &has));
  for (PetscInt i = 0; has && i < NPRINT; i++) PetscCall(SgCheckpointReaderAttribute(r, PrintNames[i], PETSC_REAL, &print[i]));
  if (has) PetscCall(ProblemPrint(r->el, r->c, now));
  { /* the materials first: another one changes the loads' lifting and the stiffness, and would be reported as those */
    PetscInt  nck = 0, nnow, len;
    PetscReal tnow[3 * SG_MAX_IDS], *tck = NULL;
    PetscBool hm, same;
    PetscCall(SgCheckpointReaderHasAttribute(r, "materials", &hm));
    if (hm) PetscCall(SgCheckpointReaderAttribute(r, "materials", PETSC_INT, &nck));
    if (hm && (nck < 1 || nck > SG_MAX_IDS)) PetscCall(SgCheckpointReaderDamaged(rp, "the number of materials", (PetscReal)nck));
    if (nck) PetscCall(SgCheckpointReaderReals(r, "materials", 3 * nck, &len, &tck));
    PetscCall(MaterialTable(r->el, &nnow, tnow));
    same = (PetscBool)(nck == nnow);
    for (PetscInt i = 0; same && i < 3 * nck; i++) same = (PetscBool)(tck[i] == tnow[i]);
    if (!same) {
      char a[1024], b[1024];
      PetscCall(MaterialText(nck, tck, has, print[0], print[1], a, sizeof(a)));
      PetscReal En, nun;
      PetscCall(SgElasticityGetMaterial(r->el, &En, &nun));
      PetscCall(MaterialText(nnow, tnow, PETSC_TRUE, En, nun, b, sizeof(b)));
      PetscCall(PetscFree(tck));
      PetscCall(SgCheckpointReaderAbandon(rp));
      SETERRQ(comm, PETSC_ERR_USER_INPUT, "-restart_file: '%s' was written for another problem: the materials (-material_ids, -E, -nu) differ (%s in the checkpoint, %s in this run); a restart must solve the same problem", f, a, b);
    }
    PetscCall(PetscFree(tck));
  }
  for (PetscInt i = 0; has && i < NPRINT; i++) {
    const PetscBool ok = (PetscBool)(PetscAbsReal(now[i] - print[i]) <= 1e-10 * PetscMax(PetscAbsReal(now[i]), PetscAbsReal(print[i])) + (i == 5 ? 1e-14 * PetscAbsReal(print[i]) : 0));
    if (!ok) PetscCall(SgCheckpointReaderAbandon(rp));
    PetscCheck(ok, comm, PETSC_ERR_USER_INPUT, "-restart_file: '%s' was written for another problem: %s differs (%s %.17g in the checkpoint, %.17g in this run); a restart must solve the same problem", f, PrintOptions[i], PrintNames[i], (double)print[i], (double)now[i]);
  }
  PetscCall(SgCheckpointReaderHasAttribute(r, "problem_moments", &has));
  if (!has) PetscFunctionReturn(0);
  PetscCall(SgCheckpointReaderAttribute(r, "problem_moments", PETSC_INT, &nmom));
  PetscCall(ProblemMoments(r->el, r->c, &n, F, Sz));
  if (nmom != n) PetscCall(SgCheckpointReaderAbandon(rp));
  PetscCheck(nmom == n, comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is damaged: it holds %" PetscInt_FMT " moments of the problem, a %" PetscInt_FMT "D problem has %" PetscInt_FMT, f, nmom, r->dim, n);
  PetscCall(SgCheckpointReaderReals(r, "problem_moments", 2 * n, NULL, &ma));
  for (PetscInt i = 0; bad < 0 && i < 2 * n; i++)
    if (!PetscIsNormalReal(ma[i]) && ma[i] != 0) bad = i;
  if (bad < 0) MomentsCompare(r->dim, n, ma, ma + n, F, Sz, &group, desc, sizeof(desc), &a, &b);
  else a = ma[bad];
  PetscCall(PetscFree(ma));
  if (bad >= 0) PetscCall(SgCheckpointReaderDamaged(rp, "a moment of the problem", a));
  if (group >= 0) PetscCall(SgCheckpointReaderAbandon(rp));
  PetscCheck(group < 0, comm, PETSC_ERR_USER_INPUT, "-restart_file: '%s' was written for another problem: %s (%s: %.17g in the checkpoint, %.17g in this run); a restart must solve the same problem", f, group >= 0 ? MomentGroups[group] : "", desc, (double)a, (double)b);
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
  PetscCall(OwnedVertices(el, &nvert));
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
