/* checkpoint.c: the continuation state after every outer step (-checkpoint_file) and the restart from it
   (-restart_file). Vertex data are stored with the vertex coordinates and matched by them on reading, so a restart may
   use another number of ranks (another partition) than the run that wrote the file. */
#include "io/ioimpl.h"
#include <petscviewerhdf5.h>

#define NREAL 3    /* gamma, V0, best KKT (the controller's own state: the dataset "state", named by the attribute "state_names") */
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

/* The problem's identity beyond those numbers, blind to no sign or direction: weighted sums ("moments") of its data
   with fixed weight fields w_k(x) of the vertex coordinates (scaled to the mesh's bounding box), each with the sum of
   the absolute values of its terms (its size). They do not depend on the partition (each vertex, cell or facet is
   summed once) up to the round-off of parallel sums, and are compared to 1e-10 of the size. The groups: */
#define NMOM 6 /* weight fields */
#define NGROUP 6
static const char *MomentGroups[NGROUP] = {"the loads (-body_force, -neumann_traction, ...) differ", "the Dirichlet values (-dirichlet_values) differ", "the fixed components (-dirichlet_ids, -dirichlet_components) differ", "the stiffness (-E, -nu, -elasticity_rigid_shift) differs", "the contact boundary (-contact_ids, -contact_label) differs", "the obstacle (-obstacle_*) differs"};
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

static PetscErrorCode StateNames(const SgCheckpoint *ck, char names[], size_t len)
{
  PetscFunctionBeginUser;
  names[0] = 0;
  for (PetscInt i = 0; i < ck->nstate; i++) {
    size_t l;
    PetscCall(PetscStrlen(names, &l));
    PetscCall(PetscSNPrintf(names + l, len - l, i ? ",%s" : "%s", ck->state_names[i]));
  }
  PetscFunctionReturn(0);
}

typedef struct {
  SgCheckpoint *ck;
  Vec       v[7];
  PetscInt  ints[6];
  PetscReal print[NPRINT];
  Vec       steps; /* load steps (NULL without) */
  PetscInt  nkept;
  Vec      *kept;  /* 2 per kept step: displacement, multiplier */
  Vec       fr[3]; /* friction: lamhat_T, the slip reference of the unknowns and of the full displacement (NULL without) */
  PetscInt  friction;
  PetscReal fparams[3]; /* -friction_bound, -friction_coefficient, -friction_gamma_factor */
  Vec       dv;    /* the finished steps' Dirichlet values (NULL without) */
  Vec       fsteps; /* friction: each finished step's stick and slip sets, friction force and traction integral */
  PetscInt  nmom;   /* the problem's moments and their sizes (ProblemMoments) */
  Vec       mom;
} CkCtx;

static const char *FrictionParamNames[3] = {"friction_bound", "friction_coefficient", "friction_gamma_factor"};

static void StepToReals(const SgLoadStep *r, PetscReal a[])
{
  const PetscReal v[SG_LOADSTEP_NREAL] = {r->t, r->obstacle_displacement, r->normal_displacement_max, r->force, r->kkt, r->energy, r->time, r->outer, r->ssn_its, r->ksp_its, r->nactive, r->converged};
  for (PetscInt k = 0; k < SG_LOADSTEP_NREAL; k++) a[k] = v[k];
}

static void RealsToStep(const PetscReal a[], SgLoadStep *r)
{
  r->t                       = a[0];
  r->obstacle_displacement   = a[1];
  r->normal_displacement_max = a[2];
  r->force                   = a[3];
  r->kkt                     = a[4];
  r->energy                  = a[5];
  r->time                    = a[6];
  r->outer                   = (PetscInt)a[7];
  r->ssn_its                 = (PetscInt)a[8];
  r->ksp_its                 = (PetscInt)a[9];
  r->nactive                 = (PetscInt)a[10];
  r->converged               = (PetscBool)(a[11] != 0);
  r->nstick = r->nslip = 0; /* friction: from the dataset load_steps_friction */
  r->friction_force = r->friction_traction = SG_NAN;
}

static PetscErrorCode WriteBody(PetscViewer viewer, void *vctx)
{
  CkCtx      *ctx      = (CkCtx *)vctx;
  const char *names[6] = {"dim", "vertices", "outer", "ssn_iterations", "ksp_iterations", "best_step"};

  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/checkpoint"));
  for (PetscInt i = 0; i < 7; i++) PetscCall(VecView(ctx->v[i], viewer));
  for (PetscInt i = 0; i < 6; i++) PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/checkpoint", names[i], PETSC_INT, &ctx->ints[i]));
  for (PetscInt i = 0; i < NPRINT; i++) PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/checkpoint", PrintNames[i], PETSC_REAL, &ctx->print[i]));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/checkpoint", "cont_type", PETSC_STRING, ctx->ck->type));
  {
    char names[SG_STATE_MAX * 64];
    PetscCall(StateNames(ctx->ck, names, sizeof(names)));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/checkpoint", "state_names", PETSC_STRING, names));
  }
  if (ctx->steps) {
    const PetscInt open = ctx->ck->step_open;
    PetscCall(VecView(ctx->steps, viewer));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/checkpoint", "load_factor", PETSC_REAL, &ctx->ck->load));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/checkpoint", "load_steps_done", PETSC_INT, &ctx->ck->nsteps));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/checkpoint", "load_step_open", PETSC_INT, &open));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/checkpoint", "load_steps_kept", PETSC_INT, &ctx->nkept));
    for (PetscInt i = 0; i < 2 * ctx->nkept; i++) PetscCall(VecView(ctx->kept[i], viewer));
    if (ctx->dv) {
      PetscCall(VecView(ctx->dv, viewer));
      PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/checkpoint", "load_dirichlet_count", PETSC_INT, &ctx->ck->ndv));
    }
  }
  if (ctx->fsteps) PetscCall(VecView(ctx->fsteps, viewer));
  PetscCall(VecView(ctx->mom, viewer));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/checkpoint", "problem_moments", PETSC_INT, &ctx->nmom));
  if (ctx->fr[0]) {
    PetscCall(VecView(ctx->fr[0], viewer));
    PetscCall(VecView(ctx->fr[1], viewer));
    PetscCall(VecView(ctx->fr[2], viewer));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/checkpoint", "friction_type", PETSC_INT, &ctx->friction));
    for (PetscInt i = 0; i < 3; i++) PetscCall(PetscViewerHDF5WriteAttribute(viewer, "/checkpoint", FrictionParamNames[i], PETSC_REAL, &ctx->fparams[i]));
  }
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscFunctionReturn(0);
}

/* A displacement y and a per-contact-vertex array as vertex-ordered vectors (the owned vertices in local order, as the
   coordinates are written), for a kept load step. */
static PetscErrorCode StepVectors(SgElasticity el, SgContact c, Vec y, const PetscReal lam[], PetscInt step, Vec *U, Vec *L)
{
  const SgMesh      *m;
  SgContactView      cv = {0};
  PetscInt           dim, nown = 0, k = 0;
  MPI_Comm           comm;
  DM                 dm, dmVert;
  PetscSection       gs;
  PetscReal         *vl;
  Vec                yloc;
  PetscScalar       *ua, *la;
  const PetscScalar *ya;
  char               name[64];

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetComm(el, &comm));
  PetscCall(SgElasticityGetDimension(el, &dim));
  PetscCall(SgElasticityGetMesh(el, &m));
  PetscCall(SgElasticityGetDMs(el, &dm, &dmVert, NULL, NULL));
  if (c) PetscCall(SgContactGetView(c, &cv));
  PetscCall(DMGetGlobalSection(dmVert, &gs));
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(gs, m->vStart + v, &off));
    if (off >= 0) nown++;
  }
  PetscCall(PetscCalloc1(m->nv, &vl));
  for (PetscInt i = 0; i < cv.n; i++) vl[cv.vert[i]] = lam[i];
  PetscCall(VecCreateMPI(comm, nown * dim, PETSC_DETERMINE, U));
  PetscCall(VecCreateMPI(comm, nown, PETSC_DETERMINE, L));
  PetscCall(PetscSNPrintf(name, sizeof(name), "step_displacement_%" PetscInt_FMT, step));
  PetscCall(PetscObjectSetName((PetscObject)*U, name));
  PetscCall(PetscSNPrintf(name, sizeof(name), "step_multiplier_%" PetscInt_FMT, step));
  PetscCall(PetscObjectSetName((PetscObject)*L, name));
  PetscCall(DMGetLocalVector(dm, &yloc));
  PetscCall(VecSet(yloc, 0));
  PetscCall(DMGlobalToLocal(dm, y, INSERT_VALUES, yloc)); /* the free values: the Dirichlet ones are not read back */
  PetscCall(VecGetArrayRead(yloc, &ya));
  PetscCall(VecGetArray(*U, &ua));
  PetscCall(VecGetArray(*L, &la));
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(gs, m->vStart + v, &off));
    if (off < 0) continue;
    for (PetscInt d = 0; d < dim; d++) ua[k * dim + d] = ya[m->loff[v] + d];
    la[k++] = vl[v];
  }
  PetscCall(VecRestoreArray(*U, &ua));
  PetscCall(VecRestoreArray(*L, &la));
  PetscCall(VecRestoreArrayRead(yloc, &ya));
  PetscCall(DMRestoreLocalVector(dm, &yloc));
  PetscCall(PetscFree(vl));
  PetscFunctionReturn(0);
}

/* dim numbers per contact vertex (a, NULL: zeros) as a vertex-ordered vector (the owned vertices in local order, as the
   coordinates are written; zeros off the contact boundary) */
static PetscErrorCode ContactVector(SgElasticity el, const SgContactView *cv, const PetscReal a[], const char name[], Vec *V)
{
  const SgMesh *m;
  PetscInt      dim, nown = 0, k = 0, *ci;
  MPI_Comm      comm;
  DM            dmVert;
  PetscSection  gs;
  PetscScalar  *va;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetComm(el, &comm));
  PetscCall(SgElasticityGetDimension(el, &dim));
  PetscCall(SgElasticityGetMesh(el, &m));
  PetscCall(SgElasticityGetDMs(el, NULL, &dmVert, NULL, NULL));
  PetscCall(DMGetGlobalSection(dmVert, &gs));
  PetscCall(PetscMalloc1(m->nv + 1, &ci));
  for (PetscInt v = 0; v < m->nv; v++) ci[v] = -1;
  for (PetscInt i = 0; i < cv->n; i++) ci[cv->vert[i]] = i;
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(gs, m->vStart + v, &off));
    if (off >= 0) nown++;
  }
  PetscCall(VecCreateMPI(comm, nown * dim, PETSC_DETERMINE, V));
  PetscCall(PetscObjectSetName((PetscObject)*V, name));
  PetscCall(VecGetArray(*V, &va));
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(gs, m->vStart + v, &off));
    if (off < 0) continue;
    for (PetscInt d = 0; d < dim; d++) va[k * dim + d] = ci[v] >= 0 && a ? a[ci[v] * dim + d] : 0;
    k++;
  }
  PetscCall(VecRestoreArray(*V, &va));
  PetscCall(PetscFree(ci));
  PetscFunctionReturn(0);
}

/* Write the state ck to file (atomically). ok = PETSC_FALSE and msg say why if the file could not be written (a full
   disk, say): the caller decides what that means for the run. */
PetscErrorCode SgCheckpointWrite(SgElasticity el, SgContact c, const char file[], SgCheckpoint *ck, PetscBool *ok, char msg[], size_t len)
{
  const SgMesh      *m;
  SgContactView      cv = {0};
  PetscInt           dim;
  MPI_Comm           comm;
  DM                 dm, dmVert;
  PetscSection       gs;
  PetscInt           nown = 0, k = 0, nvert, ints[6], nh;
  PetscReal         *vl, reals[NREAL], *hist;
  SgHistoryRow      *rows;
  Vec                X, U, L, R, G, H, S, yloc;
  PetscScalar       *xa, *ua, *la;
  const PetscScalar *ya;

  PetscFunctionBeginUser;
  *ok = PETSC_TRUE;
  PetscCall(SgElasticityGetComm(el, &comm));
  PetscCall(SgElasticityGetDimension(el, &dim));
  PetscCall(SgElasticityGetMesh(el, &m));
  PetscCall(SgElasticityGetDMs(el, &dm, &dmVert, NULL, NULL));
  if (c) PetscCall(SgContactGetView(c, &cv));
  PetscCall(DMGetGlobalSection(dmVert, &gs));
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(gs, m->vStart + v, &off));
    if (off >= 0) nown++;
  }
  PetscCall(PetscCalloc1(m->nv, &vl));
  for (PetscInt i = 0; i < cv.n; i++) vl[cv.vert[i]] = ck->lamhat[i];
  PetscCall(VecCreateMPI(comm, nown * dim, PETSC_DETERMINE, &X));
  PetscCall(VecCreateMPI(comm, nown * dim, PETSC_DETERMINE, &U));
  PetscCall(VecCreateMPI(comm, nown, PETSC_DETERMINE, &L));
  PetscCall(PetscObjectSetName((PetscObject)X, "coordinates"));
  PetscCall(PetscObjectSetName((PetscObject)U, "displacement"));
  PetscCall(PetscObjectSetName((PetscObject)L, "lamhat"));
  PetscCall(DMGetLocalVector(dm, &yloc));
  PetscCall(SgElasticityGlobalToLocal(el, ck->y, yloc));
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
  PetscCall(DMRestoreLocalVector(dm, &yloc));
  PetscCall(PetscFree(vl));

  reals[0] = ck->gamma;
  reals[1] = ck->V0;
  reals[2] = ck->best_kkt;
  PetscCall(SgHistoryGetRows(ck->hist, &nh, &rows));
  PetscCall(PetscMalloc1(NHIST * nh + 1, &hist));
  for (PetscInt i = 0; i < nh; i++) RowToReals(&rows[i], &hist[i * NHIST]);
  PetscCall(RootVec(comm, "reals", NREAL, reals, &R));
  PetscCall(RootVec(comm, "state", ck->nstate, ck->state, &S));
  PetscCall(RootVec(comm, "gammas", ck->ngammas, ck->gammas, &G));
  PetscCall(RootVec(comm, "history", NHIST * nh, hist, &H));
  PetscCall(PetscFree(hist));
  PetscCall(VecGetSize(L, &nvert));
  ints[0] = dim;
  ints[1] = nvert;
  ints[2] = ck->outer;
  ints[3] = ck->ssn_its;
  ints[4] = ck->ksp_its;
  ints[5] = ck->best_step;

  {
    CkCtx ctx = {ck, {X, U, L, R, S, G, H}, {0}, {0}, NULL, 0, NULL, {NULL, NULL}, 0, {0, 0, 0}, NULL, NULL, 0, NULL};
    for (PetscInt i = 0; i < 6; i++) ctx.ints[i] = ints[i];
    PetscCall(ProblemPrint(el, c, ctx.print));
    {
      PetscReal F[MOM_MAX], Sz[MOM_MAX], a[2 * MOM_MAX];
      PetscCall(ProblemMoments(el, c, &ctx.nmom, F, Sz));
      for (PetscInt i = 0; i < ctx.nmom; i++) a[i] = F[i], a[ctx.nmom + i] = Sz[i];
      PetscCall(RootVec(comm, "problem_moments", 2 * ctx.nmom, a, &ctx.mom));
    }
    if (c && cv.friction) {
      ctx.friction   = cv.friction;
      ctx.fparams[0] = cv.fbound;
      ctx.fparams[1] = cv.fcoef;
      ctx.fparams[2] = cv.fgfac;
      PetscCall(ContactVector(el, &cv, ck->lamhatT, "lamhat_t", &ctx.fr[0]));
      PetscCall(ContactVector(el, &cv, ck->yref, "slip_reference", &ctx.fr[1]));
      /* the second half: the full displacement at the step's start, which prescribed tangential components slip from */
      PetscCall(ContactVector(el, &cv, ck->yref ? ck->yref + cv.n * dim : NULL, "slip_reference_full", &ctx.fr[2]));
    }
    if (ck->loadsteps) {
      PetscReal *a;
      PetscCall(PetscMalloc1(SG_LOADSTEP_NREAL * ck->nsteps + 1, &a));
      for (PetscInt i = 0; i < ck->nsteps; i++) StepToReals(&ck->steps[i], &a[i * SG_LOADSTEP_NREAL]);
      PetscCall(RootVec(comm, "load_steps", SG_LOADSTEP_NREAL * ck->nsteps, a, &ctx.steps));
      PetscCall(PetscFree(a));
      if (ck->ndv > 0) PetscCall(RootVec(comm, "load_dirichlet_values", ck->ndv * ck->nsteps, ck->dvsteps, &ctx.dv));
      if (ctx.friction) {
        PetscCall(PetscMalloc1(4 * ck->nsteps + 1, &a));
        for (PetscInt i = 0; i < ck->nsteps; i++) {
          a[4 * i]     = ck->steps[i].nstick;
          a[4 * i + 1] = ck->steps[i].nslip;
          a[4 * i + 2] = ck->steps[i].friction_force;
          a[4 * i + 3] = ck->steps[i].friction_traction;
        }
        PetscCall(RootVec(comm, "load_steps_friction", 4 * ck->nsteps, a, &ctx.fsteps));
        PetscCall(PetscFree(a));
      }
      if (ck->kept) {
        ctx.nkept = ck->nsteps;
        PetscCall(PetscMalloc1(2 * ck->nsteps + 1, &ctx.kept));
        for (PetscInt i = 0; i < ck->nsteps; i++) PetscCall(StepVectors(el, c, ck->ysteps[i], ck->lamsteps[i], i, &ctx.kept[2 * i], &ctx.kept[2 * i + 1]));
      }
    }
    PetscCall(SgFileWriteHDF5(comm, "-checkpoint_file", file, WriteBody, &ctx, PETSC_TRUE, ok, msg, len));
    PetscCall(VecDestroy(&ctx.steps));
    PetscCall(VecDestroy(&ctx.dv));
    PetscCall(VecDestroy(&ctx.fsteps));
    PetscCall(VecDestroy(&ctx.mom));
    PetscCall(VecDestroy(&ctx.fr[0]));
    PetscCall(VecDestroy(&ctx.fr[1]));
    PetscCall(VecDestroy(&ctx.fr[2]));
    for (PetscInt i = 0; i < 2 * ctx.nkept; i++) PetscCall(VecDestroy(&ctx.kept[i]));
    PetscCall(PetscFree(ctx.kept));
  }
  PetscCall(VecDestroy(&X));
  PetscCall(VecDestroy(&U));
  PetscCall(VecDestroy(&L));
  PetscCall(VecDestroy(&R));
  PetscCall(VecDestroy(&S));
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

typedef struct {
  PetscInt    nvert, dim, ints[6];
  char       *type;
  const char *what; /* what was being read, for the message */
  const char *file;
  PetscViewer viewer;
  PetscBool   hasprint;
  PetscReal   print[NPRINT];
  char       *state_names;
  Vec         X, U, L, R, S, G, H;
  PetscBool   hasload; /* written by a run with load steps */
  PetscReal   load;
  PetscInt    nsteps, open, nkept;
  Vec         LS;
  Vec        *kept; /* 2 per kept step */
  PetscInt    ndv;  /* Dirichlet values per finished step (0: none) */
  Vec         DV;
  PetscInt    friction; /* the friction law (0 in a file of a run without friction) and its parameters */
  PetscReal   fparams[3];
  Vec         FT, FY;   /* lamhat_T and the slip reference */
  Vec         FYP;      /* the slip reference of the full displacement (NULL in a file without it) */
  Vec         FS;       /* the finished steps' friction numbers */
  PetscInt    nmom;     /* the problem's moments (0 in a file without them) */
  Vec         MOM;
} CkRead;

/* Everything the checkpoint holds, into rd; an error (a damaged file) is caught by the caller. */
static PetscErrorCode ReadBody(PetscViewer viewer, CkRead *rd)
{
  PetscBool   exists;
  const char *names[6] = {"dim", "vertices", "outer", "ssn_iterations", "ksp_iterations", "best_step"};

  PetscFunctionBeginUser;
  rd->what = "the attribute cont_type";
  PetscCall(PetscViewerHDF5HasAttribute(viewer, "/checkpoint", "cont_type", &exists));
  if (!exists) PetscFunctionReturn(0);
  PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/checkpoint", "cont_type", PETSC_STRING, NULL, &rd->type));
  for (PetscInt i = 0; i < 6; i++) {
    rd->what = names[i];
    PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/checkpoint", names[i], PETSC_INT, NULL, &rd->ints[i]));
  }
  rd->what = "the attribute state_names";
  PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/checkpoint", "state_names", PETSC_STRING, NULL, &rd->state_names));
  rd->what = "the problem data";
  PetscCall(PetscViewerHDF5HasAttribute(viewer, "/checkpoint", PrintNames[0], &rd->hasprint));
  for (PetscInt i = 0; rd->hasprint && i < NPRINT; i++) PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/checkpoint", PrintNames[i], PETSC_REAL, NULL, &rd->print[i]));
  rd->what = "the load steps";
  PetscCall(PetscViewerHDF5HasAttribute(viewer, "/checkpoint", "load_factor", &rd->hasload));
  if (rd->hasload) {
    PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/checkpoint", "load_factor", PETSC_REAL, NULL, &rd->load));
    PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/checkpoint", "load_steps_done", PETSC_INT, NULL, &rd->nsteps));
    PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/checkpoint", "load_step_open", PETSC_INT, NULL, &rd->open));
    PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/checkpoint", "load_steps_kept", PETSC_INT, NULL, &rd->nkept));
    PetscCall(PetscViewerHDF5HasAttribute(viewer, "/checkpoint", "load_dirichlet_count", &exists));
    if (exists) PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/checkpoint", "load_dirichlet_count", PETSC_INT, NULL, &rd->ndv));
  }
  rd->what = "the attribute problem_moments";
  PetscCall(PetscViewerHDF5HasAttribute(viewer, "/checkpoint", "problem_moments", &exists));
  if (exists) PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/checkpoint", "problem_moments", PETSC_INT, NULL, &rd->nmom));
  rd->what = "the friction law";
  PetscCall(PetscViewerHDF5HasAttribute(viewer, "/checkpoint", "friction_type", &exists));
  if (exists) {
    PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/checkpoint", "friction_type", PETSC_INT, NULL, &rd->friction));
    for (PetscInt i = 0; i < 3; i++) PetscCall(PetscViewerHDF5ReadAttribute(viewer, "/checkpoint", FrictionParamNames[i], PETSC_REAL, NULL, &rd->fparams[i]));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode ReadMoments(PetscViewer viewer, CkRead *rd)
{
  PetscFunctionBeginUser;
  rd->what = "problem_moments";
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/checkpoint"));
  PetscCall(LoadSeq(viewer, "problem_moments", 2 * rd->nmom, &rd->MOM));
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscFunctionReturn(0);
}

static PetscErrorCode ReadVectors(PetscViewer viewer, CkRead *rd)
{
  PetscBool full;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5PushGroup(viewer, "/checkpoint"));
  rd->what = "coordinates";
  PetscCall(LoadSeq(viewer, "coordinates", rd->nvert * rd->dim, &rd->X));
  rd->what = "displacement";
  PetscCall(LoadSeq(viewer, "displacement", rd->nvert * rd->dim, &rd->U));
  rd->what = "lamhat";
  PetscCall(LoadSeq(viewer, "lamhat", rd->nvert, &rd->L));
  rd->what = "reals";
  PetscCall(LoadSeq(viewer, "reals", NREAL, &rd->R));
  rd->what = "state";
  PetscCall(LoadSeq(viewer, "state", -1, &rd->S));
  rd->what = "gammas";
  PetscCall(LoadSeq(viewer, "gammas", -1, &rd->G));
  rd->what = "history";
  PetscCall(LoadSeq(viewer, "history", -1, &rd->H));
  if (rd->hasload) {
    rd->what = "load_steps";
    PetscCall(LoadSeq(viewer, "load_steps", -1, &rd->LS));
    rd->what = "the kept load steps";
    PetscCheck(rd->nkept == 0 || rd->nkept == rd->nsteps, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "kept steps");
    PetscCall(PetscCalloc1(2 * rd->nkept + 1, &rd->kept));
    for (PetscInt i = 0; i < rd->nkept; i++) {
      char name[64];
      PetscCall(PetscSNPrintf(name, sizeof(name), "step_displacement_%" PetscInt_FMT, i));
      PetscCall(LoadSeq(viewer, name, rd->nvert * rd->dim, &rd->kept[2 * i]));
      PetscCall(PetscSNPrintf(name, sizeof(name), "step_multiplier_%" PetscInt_FMT, i));
      PetscCall(LoadSeq(viewer, name, rd->nvert, &rd->kept[2 * i + 1]));
    }
    rd->what = "load_dirichlet_values";
    PetscCheck(rd->ndv >= 0 && rd->ndv <= 3 * SG_MAX_IDS, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "Dirichlet values");
    if (rd->ndv > 0) PetscCall(LoadSeq(viewer, "load_dirichlet_values", rd->ndv * rd->nsteps, &rd->DV));
  }
  if (rd->friction && rd->hasload) {
    rd->what = "load_steps_friction";
    PetscCall(LoadSeq(viewer, "load_steps_friction", 4 * rd->nsteps, &rd->FS));
  }
  if (rd->friction) {
    rd->what = "lamhat_t";
    PetscCall(LoadSeq(viewer, "lamhat_t", rd->nvert * rd->dim, &rd->FT));
    rd->what = "slip_reference";
    PetscCall(LoadSeq(viewer, "slip_reference", rd->nvert * rd->dim, &rd->FY));
    rd->what = "slip_reference_full";
    PetscCall(PetscViewerHDF5HasDataset(viewer, "slip_reference_full", &full));
    if (full) PetscCall(LoadSeq(viewer, "slip_reference_full", rd->nvert * rd->dim, &rd->FYP));
  }
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscFunctionReturn(0);
}

/* Run a read step with PETSc's and HDF5's error printing off; *ierr is its error code, the same on every rank. */
static PetscErrorCode Quietly(MPI_Comm comm, PetscErrorCode (*f)(PetscViewer, CkRead *), PetscViewer viewer, CkRead *rd, PetscErrorCode *ierr)
{
  H5E_auto2_t efunc;
  void       *edata;
  int         e;

  PetscFunctionBeginUser;
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  (void)H5Eget_auto2(H5E_DEFAULT, &efunc, &edata);
  (void)H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  *ierr = f(viewer, rd); /* not PetscCall: a damaged file is reported by the caller, naming -restart_file */
  (void)H5Eset_auto2(H5E_DEFAULT, efunc, edata);
  PetscCall(PetscPopErrorHandler());
  e = *ierr ? 1 : 0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &e, 1, MPI_INT, MPI_MAX, comm));
  *ierr = e ? PETSC_ERR_FILE_READ : 0;
  PetscFunctionReturn(0);
}

static PetscErrorCode DestroyViewer(PetscViewer unused, CkRead *rd)
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerDestroy(&rd->viewer));
  PetscFunctionReturn(0);
}

static PetscErrorCode OpenQuietly(PetscViewer unused, CkRead *rd)
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5Open(PETSC_COMM_SELF, rd->file, FILE_MODE_READ, &rd->viewer));
  PetscFunctionReturn(0);
}

/* all finite, and >= lo when check_lo; the index of the first bad one in *bad (-1: none) */
static void CheckReals(const PetscScalar a[], PetscInt n, PetscBool check_lo, PetscReal lo, PetscInt *bad)
{
  *bad = -1;
  for (PetscInt i = 0; i < n; i++)
    if (!PetscIsNormalReal(PetscRealPart(a[i])) && PetscRealPart(a[i]) != 0) {
      *bad = i;
      return;
    } else if (check_lo && !(PetscRealPart(a[i]) >= lo)) {
      *bad = i;
      return;
    }
}

/* Close the viewer with error printing off (a damaged file can fail at H5Fclose); *ierr, if asked for, says whether it did. */
static PetscErrorCode CloseQuietly(MPI_Comm comm, CkRead *rd, PetscViewer *viewer, PetscErrorCode *ierr)
{
  PetscErrorCode e = 0;

  PetscFunctionBeginUser;
  rd->viewer = *viewer;
  *viewer    = NULL;
  PetscCall(Quietly(comm, DestroyViewer, NULL, rd, &e));
  if (ierr) *ierr = e;
  PetscFunctionReturn(0);
}

/* Read the state of file into ck: ck->type, nstate and state_names say what this run's controller is and keeps;
   ck->y and ck->lamhat (per contact vertex) receive the vertex data, gammas (allocated here) and hist the path.
   Every refusal (another controller, problem or mesh, a damaged file) names -restart_file and the file. */
PetscErrorCode SgCheckpointRead(SgElasticity el, SgContact c, const char f[], SgCheckpoint *ck)
{
  const SgMesh      *m;
  SgContactView      cv = {0};
  PetscInt           dim;
  MPI_Comm           comm;
  DM                 dmVert;
  PetscViewer        viewer = NULL;
  PetscInt           nvert = 0, *perm, nmiss = 0, nbadf = 0, nh, ng, ns, bad, *ints;
  CkRead             rd;
  const PetscScalar *xa, *ua, *la, *ra, *sa, *ga, *ha;
  PetscScalar       *ya;
  PetscBool          exists, same;
  PetscErrorCode     ierr;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetComm(el, &comm));
  PetscCall(SgElasticityGetDimension(el, &dim));
  PetscCall(SgElasticityGetMesh(el, &m));
  PetscCall(SgElasticityGetDMs(el, NULL, &dmVert, NULL, NULL));
  if (c) PetscCall(SgContactGetView(c, &cv));
  PetscCall(PetscMemzero(&rd, sizeof(rd)));
  PetscCall(PetscTestFile(f, 'r', &exists));
  PetscCheck(exists, comm, PETSC_ERR_FILE_OPEN, "-restart_file: cannot read '%s'", f);
  /* a truncated or overwritten file fails here or in the reads below: the message names the option and the file */
  rd.file = f;
  PetscCall(Quietly(comm, OpenQuietly, NULL, &rd, &ierr));
  viewer = rd.viewer;
  if (ierr && viewer) { /* a viewer whose file did not open fails its flush: forget that error too */
    PetscErrorCode ierr2 = 0;
    PetscCall(Quietly(comm, DestroyViewer, NULL, &rd, &ierr2));
  }
  PetscCheck(!ierr, comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is not a readable HDF5 file (truncated or damaged?)", f);
  PetscCall(Quietly(comm, ReadBody, viewer, &rd, &ierr));
  if (ierr) {
    PetscCall(CloseQuietly(comm, &rd, &viewer, NULL));
    PetscCall(PetscFree(rd.type));
    PetscCall(PetscFree(rd.state_names));
    SETERRQ(comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is damaged: cannot read %s", f, rd.what);
  }
  if (!rd.type) PetscCall(CloseQuietly(comm, &rd, &viewer, NULL));
  PetscCheck(rd.type, comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is not a checkpoint of this program", f);
  PetscCall(PetscStrcmp(rd.type, ck->type, &same));
  if (!same) PetscCall(CloseQuietly(comm, &rd, &viewer, NULL));
  PetscCheck(same, comm, PETSC_ERR_USER_INPUT, "-restart_file: '%s' was written by -cont_type %s, this run has -cont_type %s", f, rd.type, ck->type);
  PetscCall(PetscFree(rd.type));
  {
    /* the controller's own numbers, by name: a file of another version of the controller is not resumed */
    char names[SG_STATE_MAX * 64];
    PetscCall(StateNames(ck, names, sizeof(names)));
    PetscCall(PetscStrcmp(rd.state_names, names, &same));
    if (!same) PetscCall(CloseQuietly(comm, &rd, &viewer, NULL));
    PetscCheck(same, comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' holds the controller state (%s), -cont_type %s keeps (%s)", f, rd.state_names, ck->type, names);
    PetscCall(PetscFree(rd.state_names));
  }
  ints = rd.ints;
  {
    PetscSection gs;
    PetscCall(DMGetGlobalSection(dmVert, &gs));
    for (PetscInt v = 0; v < m->nv; v++) {
      PetscInt off;
      PetscCall(PetscSectionGetOffset(gs, m->vStart + v, &off));
      if (off >= 0) nvert++;
    }
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nvert, 1, MPIU_INT, MPI_SUM, comm));
  }
  if (!(ints[0] == dim && ints[1] == nvert)) PetscCall(CloseQuietly(comm, &rd, &viewer, NULL));
  PetscCheck(ints[0] == dim && ints[1] == nvert, comm, PETSC_ERR_USER_INPUT, "-restart_file: '%s' holds a %" PetscInt_FMT "D mesh of %" PetscInt_FMT " vertices, this run has a %" PetscInt_FMT "D mesh of %" PetscInt_FMT, f, ints[0], ints[1], dim, nvert);
  /* the counters: a checkpoint is written after an outer step */
  {
    const char *what = NULL;
    PetscInt    val  = 0;
    /* above a quarter of PetscInt's range a count is damage (HDF5 saturates larger stored values), and adding the
       resumed run's iterations would overflow */
    const PetscInt big = PETSC_MAX_INT / 4;
    if (ints[2] < 1 || ints[2] > big) what = "outer", val = ints[2];
    else if (ints[3] < 0 || ints[3] > big) what = "ssn_iterations", val = ints[3];
    else if (ints[4] < 0 || ints[4] > big) what = "ksp_iterations", val = ints[4];
    else if (ints[5] < 0 || ints[5] > ints[2]) what = "best_step", val = ints[5];
    if (what) PetscCall(CloseQuietly(comm, &rd, &viewer, NULL));
    PetscCheck(!what, comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is damaged: %s = %" PetscInt_FMT " is impossible (outer step %" PetscInt_FMT ")", f, what, val, ints[2]);
  }
  /* a restart of another problem would continue a path that is not this problem's */
  if (rd.hasprint) {
    PetscReal now[NPRINT];
    PetscCall(ProblemPrint(el, c, now));
    for (PetscInt i = 0; i < NPRINT; i++) {
      const PetscBool ok = (PetscBool)(PetscAbsReal(now[i] - rd.print[i]) <= 1e-10 * PetscMax(PetscAbsReal(now[i]), PetscAbsReal(rd.print[i])) + (i == 5 ? 1e-14 * PetscAbsReal(rd.print[i]) : 0));
      if (!ok) PetscCall(CloseQuietly(comm, &rd, &viewer, NULL));
      PetscCheck(ok, comm, PETSC_ERR_USER_INPUT, "-restart_file: '%s' was written for another problem: %s differs (%s %.17g in the checkpoint, %.17g in this run); a restart must solve the same problem", f, PrintOptions[i], PrintNames[i], (double)rd.print[i], (double)now[i]);
    }
  }
  /* the friction law and its parameters: the state of another law is no state of this problem */
  {
    const PetscInt  now_fr = c ? (PetscInt)cv.friction : 0;
    const PetscReal now[3] = {cv.fbound, cv.fcoef, cv.fgfac};
    PetscBool       ok     = (PetscBool)(now_fr == rd.friction);
    if (!ok) PetscCall(CloseQuietly(comm, &rd, &viewer, NULL));
    PetscCheck(ok, comm, PETSC_ERR_USER_INPUT, "-restart_file: '%s' was written with -friction_type %s, this run has -friction_type %s", f, rd.friction >= 0 && rd.friction <= 2 ? SgFrictionTypes[rd.friction] : "(damaged)", SgFrictionTypes[now_fr]);
    for (PetscInt i = 0; now_fr && i < 3; i++) {
      ok = (PetscBool)(PetscAbsReal(now[i] - rd.fparams[i]) <= 1e-12 * PetscMax(PetscAbsReal(now[i]), PetscAbsReal(rd.fparams[i])));
      if (!ok) PetscCall(CloseQuietly(comm, &rd, &viewer, NULL));
      PetscCheck(ok, comm, PETSC_ERR_USER_INPUT, "-restart_file: '%s' was written for another problem: -%s differs (%.17g in the checkpoint, %.17g in this run); a restart must solve the same problem", f, FrictionParamNames[i], (double)rd.fparams[i], (double)now[i]);
    }
  }
  /* the problem's moments: its data with their signs and directions (a file of an older version has none) */
  if (rd.nmom) {
    PetscReal          F[MOM_MAX], Sz[MOM_MAX], a = 0, b = 0;
    PetscInt           n, group = -1;
    char               desc[128];
    const PetscScalar *ma;
    PetscCall(ProblemMoments(el, c, &n, F, Sz));
    if (rd.nmom != n) PetscCall(CloseQuietly(comm, &rd, &viewer, NULL));
    PetscCheck(rd.nmom == n, comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is damaged: it holds %" PetscInt_FMT " moments of the problem, a %" PetscInt_FMT "D problem has %" PetscInt_FMT, f, rd.nmom, dim, n);
    PetscCall(Quietly(comm, ReadMoments, viewer, &rd, &ierr));
    if (ierr) {
      PetscCall(VecDestroy(&rd.MOM));
      PetscCall(CloseQuietly(comm, &rd, &viewer, NULL));
      SETERRQ(comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is damaged: cannot read the dataset %s (of the expected size)", f, rd.what);
    }
    PetscCall(VecGetArrayRead(rd.MOM, &ma));
    CheckReals(ma, 2 * n, PETSC_FALSE, 0, &bad);
    if (bad < 0) {
      PetscReal M[2 * MOM_MAX];
      for (PetscInt i = 0; i < 2 * n; i++) M[i] = PetscRealPart(ma[i]);
      MomentsCompare(dim, n, M, M + n, F, Sz, &group, desc, sizeof(desc), &a, &b);
    } else a = PetscRealPart(ma[bad]);
    PetscCall(VecRestoreArrayRead(rd.MOM, &ma));
    PetscCall(VecDestroy(&rd.MOM));
    if (bad >= 0) PetscCall(CloseQuietly(comm, &rd, &viewer, NULL));
    PetscCheck(bad < 0, comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is damaged: a moment of the problem is %g", f, (double)a);
    if (group >= 0) PetscCall(CloseQuietly(comm, &rd, &viewer, NULL));
    PetscCheck(group < 0, comm, PETSC_ERR_USER_INPUT, "-restart_file: '%s' was written for another problem: %s (%s: %.17g in the checkpoint, %.17g in this run); a restart must solve the same problem", f, group >= 0 ? MomentGroups[group] : "", desc, (double)a, (double)b);
  }
  rd.nvert = nvert;
  rd.dim   = dim;
  PetscCall(Quietly(comm, ReadVectors, viewer, &rd, &ierr));
  {
    PetscErrorCode ierr2 = 0;
    PetscCall(CloseQuietly(comm, &rd, &viewer, &ierr2));
    if (ierr2 && !ierr) {
      ierr    = ierr2;
      rd.what = "the file's end (closing it failed)";
    }
  }
  if (ierr) {
    Vec *v[13] = {&rd.X, &rd.U, &rd.L, &rd.R, &rd.S, &rd.G, &rd.H, &rd.LS, &rd.DV, &rd.FT, &rd.FY, &rd.FS, &rd.FYP};
    for (PetscInt i = 0; i < 13; i++) PetscCall(VecDestroy(v[i]));
    SETERRQ(comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is damaged: cannot read the dataset %s (of the expected size)", f, rd.what);
  }

  /* every number read must be possible */
  PetscCall(VecGetArrayRead(rd.X, &xa));
  PetscCall(VecGetArrayRead(rd.U, &ua));
  PetscCall(VecGetArrayRead(rd.L, &la));
  PetscCall(VecGetArrayRead(rd.R, &ra));
  PetscCall(VecGetSize(rd.S, &ns));
  PetscCall(VecGetArrayRead(rd.S, &sa));
  PetscCall(VecGetSize(rd.G, &ng));
  PetscCall(VecGetArrayRead(rd.G, &ga));
  PetscCall(VecGetSize(rd.H, &nh));
  PetscCall(VecGetArrayRead(rd.H, &ha));
  {
    const char *what = NULL;
    PetscReal   val  = 0;
    char        statewhat[128];
    CheckReals(xa, nvert * dim, PETSC_FALSE, 0, &bad);
    if (bad >= 0) what = "a vertex coordinate", val = PetscRealPart(xa[bad]);
    if (!what) CheckReals(ua, nvert * dim, PETSC_FALSE, 0, &bad);
    if (!what && bad >= 0) what = "a displacement", val = PetscRealPart(ua[bad]);
    if (!what) CheckReals(la, nvert, PETSC_TRUE, 0, &bad);
    if (!what && bad >= 0) what = "a multiplier shift lamhat (must be >= 0)", val = PetscRealPart(la[bad]);
    /* the end of a load step of a solver without gamma (pdas, vi) holds no gamma to check */
    const PetscBool step_end = (PetscBool)(rd.hasload && !rd.open);
    if (!what && !step_end && !(PetscIsNormalReal(PetscRealPart(ra[0])) && PetscRealPart(ra[0]) > 0)) what = "gamma (must be positive)", val = PetscRealPart(ra[0]);
    if (!what && !PetscIsNormalReal(PetscRealPart(ra[1])) && PetscRealPart(ra[1]) != 0) what = "the unconstrained energy", val = PetscRealPart(ra[1]);
    if (!what) CheckReals(&ra[2], 1, PETSC_TRUE, 0, &bad);
    if (!what && bad >= 0) what = "the best KKT residual", val = PetscRealPart(ra[2]);
    if (!what && ns != ck->nstate) what = "the number of controller state values", val = ns;
    if (!what) CheckReals(sa, ns, PETSC_FALSE, 0, &bad);
    if (!what && bad >= 0) {
      PetscCall(PetscSNPrintf(statewhat, sizeof(statewhat), "the controller state %s", ck->state_names[bad]));
      what = statewhat, val = PetscRealPart(sa[bad]);
    }
    if (!what && ng != ints[2]) what = "the number of gammas (must be the number of outer steps)", val = ng;
    for (PetscInt i = 0; !what && !step_end && i < ng; i++)
      if (!(PetscRealPart(ga[i]) > 0)) what = "a gamma of the path (must be positive)", val = PetscRealPart(ga[i]);
    if (!what && nh % NHIST) what = "the length of the history", val = nh;
    for (PetscInt i = 0; !what && i < nh / NHIST; i++) {
      const PetscReal kind = PetscRealPart(ha[i * NHIST]), outer = PetscRealPart(ha[i * NHIST + 1]);
      if (!(kind == 0 || kind == 1)) what = "a history row kind", val = kind;
      else if (!(outer >= 0 && (outer <= ints[2] || rd.hasload) && outer == PetscFloorReal(outer))) what = "a history row's outer step", val = outer; /* with load steps the history holds every step's rows */
    }
    if (what) {
      PetscCall(VecRestoreArrayRead(rd.X, &xa));
      PetscCall(VecRestoreArrayRead(rd.U, &ua));
      PetscCall(VecRestoreArrayRead(rd.L, &la));
      PetscCall(VecRestoreArrayRead(rd.R, &ra));
      PetscCall(VecRestoreArrayRead(rd.S, &sa));
      PetscCall(VecRestoreArrayRead(rd.G, &ga));
      PetscCall(VecRestoreArrayRead(rd.H, &ha));
      {
        Vec *v[13] = {&rd.X, &rd.U, &rd.L, &rd.R, &rd.S, &rd.G, &rd.H, &rd.LS, &rd.DV, &rd.FT, &rd.FY, &rd.FS, &rd.FYP};
        for (PetscInt i = 0; i < 13; i++) PetscCall(VecDestroy(v[i]));
      }
      SETERRQ(comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is damaged: %s is %g", f, what, (double)val);
    }
  }

  PetscCall(PetscMalloc1(nvert, &perm));
  for (PetscInt i = 0; i < nvert; i++) perm[i] = i;
  SortX   = (const PetscReal *)xa;
  SortDim = dim;
  qsort(perm, nvert, sizeof(PetscInt), CmpIndex);
  PetscCall(VecGetArray(ck->y, &ya));
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt idx;
    if (m->goff[v] < 0) continue;
    PetscCall(FindVertex(perm, nvert, &m->x[v * dim], &idx));
    if (idx < 0) {
      nmiss++;
      continue;
    }
    /* the file holds the full displacement: a fixed component of a roller is data, its unknown stays 0 */
    for (PetscInt d = 0; d < dim; d++) ya[m->goff[v] + d] = SgMeshFixed(m, v, d) ? 0 : ua[idx * dim + d];
  }
  PetscCall(VecRestoreArray(ck->y, &ya));
  for (PetscInt i = 0; i < cv.n; i++) {
    PetscInt idx;
    PetscCall(FindVertex(perm, nvert, &m->x[cv.vert[i] * dim], &idx));
    if (idx < 0) nmiss++;
    else ck->lamhat[i] = PetscRealPart(la[idx]);
  }
  if (rd.friction) { /* lamhat_T and the slip reference, matched by the coordinates as lamhat */
    const PetscScalar *fta, *fya, *fpa = NULL;
    PetscCall(VecGetArrayRead(rd.FT, &fta));
    PetscCall(VecGetArrayRead(rd.FY, &fya));
    if (rd.FYP) PetscCall(VecGetArrayRead(rd.FYP, &fpa));
    for (PetscInt i = 0; i < cv.n; i++) {
      PetscInt idx;
      PetscCall(FindVertex(perm, nvert, &m->x[cv.vert[i] * dim], &idx));
      for (PetscInt d = 0; idx >= 0 && d < dim; d++) {
        const PetscReal a = PetscRealPart(fta[idx * dim + d]), b = PetscRealPart(fya[idx * dim + d]);
        if (!((PetscIsNormalReal(a) || a == 0) && (PetscIsNormalReal(b) || b == 0))) nbadf++;
        if (ck->lamhatT) ck->lamhatT[i * dim + d] = a;
        if (ck->yref) ck->yref[i * dim + d] = b;
        if (ck->yref) { /* a file without the full displacement's reference: the unknowns' (exact without prescribed components) */
          const PetscReal bp = fpa ? PetscRealPart(fpa[idx * dim + d]) : b;
          if (!(PetscIsNormalReal(bp) || bp == 0)) nbadf++;
          ck->yref[(cv.n + i) * dim + d] = bp;
        }
      }
    }
    PetscCall(VecRestoreArrayRead(rd.FT, &fta));
    PetscCall(VecRestoreArrayRead(rd.FY, &fya));
    if (rd.FYP) PetscCall(VecRestoreArrayRead(rd.FYP, &fpa));
    ck->yref_full = (PetscBool)(rd.FYP != NULL);
    PetscCall(VecDestroy(&rd.FT));
    PetscCall(VecDestroy(&rd.FY));
    PetscCall(VecDestroy(&rd.FYP));
  }
  /* the kept load steps' displacements and multipliers, matched by the coordinates as y and lamhat */
  ck->kept     = (PetscBool)(rd.nkept > 0);
  ck->ysteps   = NULL;
  ck->lamsteps = NULL;
  if (ck->kept) {
    PetscCall(PetscCalloc2(rd.nkept, &ck->ysteps, rd.nkept, &ck->lamsteps));
    for (PetscInt j = 0; j < rd.nkept; j++) {
      const PetscScalar *sua, *sla;
      PetscCall(VecDuplicate(ck->y, &ck->ysteps[j]));
      PetscCall(PetscMalloc1(cv.n + 1, &ck->lamsteps[j]));
      PetscCall(VecGetArrayRead(rd.kept[2 * j], &sua));
      PetscCall(VecGetArrayRead(rd.kept[2 * j + 1], &sla));
      PetscCall(VecGetArray(ck->ysteps[j], &ya));
      for (PetscInt v = 0; v < m->nv; v++) {
        PetscInt idx;
        if (m->goff[v] < 0) continue;
        PetscCall(FindVertex(perm, nvert, &m->x[v * dim], &idx));
        if (idx >= 0)
          for (PetscInt d = 0; d < dim; d++) ya[m->goff[v] + d] = sua[idx * dim + d];
      }
      PetscCall(VecRestoreArray(ck->ysteps[j], &ya));
      for (PetscInt i = 0; i < cv.n; i++) {
        PetscInt idx;
        PetscCall(FindVertex(perm, nvert, &m->x[cv.vert[i] * dim], &idx));
        ck->lamsteps[j][i] = idx >= 0 ? PetscRealPart(sla[idx]) : 0;
      }
      PetscCall(VecRestoreArrayRead(rd.kept[2 * j], &sua));
      PetscCall(VecRestoreArrayRead(rd.kept[2 * j + 1], &sla));
    }
  }
  for (PetscInt i = 0; i < 2 * rd.nkept && rd.kept; i++) PetscCall(VecDestroy(&rd.kept[i]));
  PetscCall(PetscFree(rd.kept));
  PetscCall(PetscFree(perm));
  PetscCall(VecRestoreArrayRead(rd.X, &xa));
  PetscCall(VecRestoreArrayRead(rd.U, &ua));
  PetscCall(VecRestoreArrayRead(rd.L, &la));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nmiss, 1, MPIU_INT, MPI_SUM, comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nbadf, 1, MPIU_INT, MPI_SUM, comm));
  if (nmiss || nbadf) { /* released before either error below */
    PetscCall(VecRestoreArrayRead(rd.R, &ra));
    PetscCall(VecRestoreArrayRead(rd.S, &sa));
    PetscCall(VecRestoreArrayRead(rd.G, &ga));
    PetscCall(VecRestoreArrayRead(rd.H, &ha));
  }
  PetscCheck(!nmiss, comm, PETSC_ERR_USER_INPUT, "-restart_file: %" PetscInt_FMT " vertices of this mesh are not in '%s': it was written for another mesh", nmiss, f);
  PetscCheck(!nbadf, comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is damaged: %" PetscInt_FMT " values of lamhat_t or slip_reference are not finite", f, nbadf);

  ck->gamma    = PetscRealPart(ra[0]);
  ck->V0       = PetscRealPart(ra[1]);
  ck->best_kkt = PetscRealPart(ra[2]);
  for (PetscInt i = 0; i < ns; i++) ck->state[i] = PetscRealPart(sa[i]);
  PetscCall(VecRestoreArrayRead(rd.R, &ra));
  PetscCall(VecRestoreArrayRead(rd.S, &sa));
  ck->outer     = ints[2];
  ck->ssn_its   = ints[3];
  ck->ksp_its   = ints[4];
  ck->best_step = ints[5];
  ck->ngammas   = ng;
  PetscCall(PetscMalloc1(ng + 1, &ck->gammas));
  for (PetscInt i = 0; i < ng; i++) ck->gammas[i] = PetscRealPart(ga[i]);
  PetscCall(VecRestoreArrayRead(rd.G, &ga));
  PetscCall(SgHistoryReset(ck->hist));
  for (PetscInt i = 0; i < nh / NHIST; i++) {
    SgHistoryRow r;
    PetscReal    a[NHIST];
    for (PetscInt k = 0; k < NHIST; k++) a[k] = PetscRealPart(ha[i * NHIST + k]);
    RealsToRow(a, &r);
    PetscCall(SgHistoryAdd(ck->hist, &r));
  }
  PetscCall(VecRestoreArrayRead(rd.H, &ha));
  /* the load steps: a file of a run without them is the full load, inside its only step */
  ck->load      = rd.hasload ? rd.load : 1;
  ck->nsteps    = 0;
  ck->step_open = PETSC_TRUE;
  ck->steps     = NULL;
  if (rd.hasload) {
    PetscInt           nls;
    const PetscScalar *lsa;
    PetscCall(VecGetSize(rd.LS, &nls));
    PetscCheck(PetscIsNormalReal(rd.load) && rd.load > 0 && rd.nsteps >= 0 && nls == SG_LOADSTEP_NREAL * rd.nsteps && (rd.open == 0 || rd.open == 1), comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is damaged: its load steps (factor %g, %" PetscInt_FMT " steps done, %" PetscInt_FMT " numbers) are impossible", f, (double)rd.load, rd.nsteps, nls);
    ck->nsteps    = rd.nsteps;
    ck->step_open = (PetscBool)rd.open;
    PetscCall(PetscMalloc1(rd.nsteps + 1, &ck->steps));
    PetscCall(VecGetArrayRead(rd.LS, &lsa));
    for (PetscInt i = 0; i < rd.nsteps; i++) {
      PetscReal a[SG_LOADSTEP_NREAL];
      for (PetscInt k = 0; k < SG_LOADSTEP_NREAL; k++) a[k] = PetscRealPart(lsa[i * SG_LOADSTEP_NREAL + k]);
      RealsToStep(a, &ck->steps[i]);
    }
    PetscCall(VecRestoreArrayRead(rd.LS, &lsa));
    PetscCall(VecDestroy(&rd.LS));
    if (rd.FS) {
      const PetscScalar *fsa;
      PetscCall(VecGetArrayRead(rd.FS, &fsa));
      for (PetscInt i = 0; i < rd.nsteps; i++) {
        ck->steps[i].nstick            = (PetscInt)PetscRealPart(fsa[4 * i]);
        ck->steps[i].nslip             = (PetscInt)PetscRealPart(fsa[4 * i + 1]);
        ck->steps[i].friction_force    = PetscRealPart(fsa[4 * i + 2]);
        ck->steps[i].friction_traction = PetscRealPart(fsa[4 * i + 3]);
      }
      PetscCall(VecRestoreArrayRead(rd.FS, &fsa));
    }
  }
  PetscCall(VecDestroy(&rd.FS));
  ck->ndv     = 0;
  ck->dvsteps = NULL;
  if (rd.DV) { /* the finished steps' Dirichlet values (non-proportional loading) */
    const PetscScalar *dva;
    ck->ndv = rd.ndv;
    PetscCall(PetscMalloc1(rd.ndv * rd.nsteps + 1, &ck->dvsteps));
    PetscCall(VecGetArrayRead(rd.DV, &dva));
    for (PetscInt i = 0; i < rd.ndv * rd.nsteps; i++) ck->dvsteps[i] = PetscRealPart(dva[i]);
    PetscCall(VecRestoreArrayRead(rd.DV, &dva));
    PetscCall(VecDestroy(&rd.DV));
  }
  PetscCall(VecDestroy(&rd.X));
  PetscCall(VecDestroy(&rd.U));
  PetscCall(VecDestroy(&rd.L));
  PetscCall(VecDestroy(&rd.R));
  PetscCall(VecDestroy(&rd.S));
  PetscCall(VecDestroy(&rd.G));
  PetscCall(VecDestroy(&rd.H));
  PetscCall(PetscInfo(NULL, "restarted from %s after outer step %" PetscInt_FMT " (gamma %g)\n", f, ck->outer, (double)ck->gamma));
  PetscFunctionReturn(0);
}
