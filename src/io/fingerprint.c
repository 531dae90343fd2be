/* fingerprint.c: the problem's fingerprint, which a checkpoint holds (SgCheckpointWriterCreate) and a restart checks
   against this run's (SgCheckpointReaderOpen). */
#include "io/ioimpl.h"

/* What identifies the problem a checkpoint belongs to: a restart of another problem (another -E, -nu, load, Dirichlet
   data or obstacle) would resume a continuation path, and report an unconstrained energy, of a problem it is not. */
const char *const SgFingerprintNames[SG_FINGERPRINT_NUMBERS]   = {"E", "nu", "load_norm", "load_max", "dirichlet_energy", "gap_sum"};
const char *const SgFingerprintOptions[SG_FINGERPRINT_NUMBERS] = {"-E", "-nu", "the loads (-body_force, -neumann_traction, ...)", "the loads (-body_force, -neumann_traction, ...)", "the Dirichlet data (-dirichlet_values)", "the obstacle (-obstacle_*) or the contact boundary"};

PetscErrorCode SgFingerprintNumbers(SgElasticity el, SgContact c, PetscReal print[SG_FINGERPRINT_NUMBERS])
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
#define NMOM   6 /* weight fields */
#define NGROUP 6
const char *const SgFingerprintGroups[NGROUP] = {"the loads (-body_force, -neumann_traction, ...) differ", "the Dirichlet values (-dirichlet_values) differ", "the fixed components (-dirichlet_ids, -dirichlet_components) differ", "the stiffness (-E, -nu, -material_ids, -material_label, -elasticity_rigid_shift) differs", "the contact boundary (-contact_ids, -contact_label) differs", "the obstacle (-obstacle_*) or the master side (-contact_master_ids) differs"};
#define MOM_MAX SG_FINGERPRINT_MOMENTS_MAX /* (3 * NMOM * 3 + 2 + 2 * NMOM) */

/* numbers per group in a dim-dimensional problem: loads, Dirichlet values and fixed components per weight and
   component, two quadratic forms of the stiffness, the contact boundary's and the gaps' moments per weight */
static void MomentGroupSizes(PetscInt dim, PetscInt len[NGROUP])
{
  len[0] = len[1] = len[2] = NMOM * dim;
  len[3]                   = 2;
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

/* the load's moments (this rank's cells' and facets' part at every vertex it has) and the Dirichlet data's (values and
   fixed components at the owned vertices), added to buf (values) and buf + MOM_MAX (sizes) */
static PetscErrorCode MomentsData(SgElasticity el, PetscInt dim, const PetscReal lo[3], const PetscReal hi[3], const PetscInt off[], PetscReal buf[])
{
  const SgMesh      *m;
  PetscReal          w[NMOM];
  DM                 dmVert;
  PetscSection       gs;
  Vec                f, ubc;
  const PetscScalar *fa, *ua;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetMesh(el, &m));
  PetscCall(SgElasticityGetDMs(el, NULL, &dmVert, NULL, NULL));
  PetscCall(DMGetGlobalSection(dmVert, &gs));
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
  PetscFunctionReturn(0);
}

/* the stiffness's: v^T K v for two smooth fields v that are no rigid motion */
static PetscErrorCode MomentsStiffness(SgElasticity el, PetscInt dim, const PetscReal lo[3], const PetscReal hi[3], const PetscInt off[], PetscReal buf[])
{
  const SgMesh *m;
  PetscReal     w[NMOM];
  DM            dm;
  Vec           K1, K2, KV;
  Mat           K;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetMesh(el, &m));
  PetscCall(SgElasticityGetDMs(el, &dm, NULL, NULL, NULL));
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
  PetscFunctionReturn(0);
}

/* the contact boundary's (its weights) and the gaps' with the obstacle at its full placement */
static PetscErrorCode MomentsContact(SgContact c, const SgMesh *m, PetscInt dim, const PetscReal lo[3], const PetscReal hi[3], const PetscInt off[], PetscReal buf[])
{
  PetscInt         n;
  const PetscInt  *vert;
  const PetscReal *cw;
  PetscReal        w[NMOM], *gap;

  PetscFunctionBeginUser;
  PetscCall(SgContactGetVertices(c, &n, NULL, &vert, NULL));
  PetscCall(SgContactGetWeights(c, &cw));
  PetscCall(PetscMalloc1(n + 1, &gap));
  PetscCall(SgContactGapsAt(c, 1.0, gap));
  for (PetscInt i = 0; i < n; i++) {
    MomentWeights(dim, lo, hi, &m->x[vert[i] * dim], w);
    for (PetscInt k = 0; k < NMOM; k++) {
      const PetscReal a = cw[i] * w[k], g = gap[i] < PETSC_MAX_REAL ? a * gap[i] : 0; /* a ray that misses: no gap */
      buf[off[4] + k] += a;
      buf[MOM_MAX + off[4] + k] += PetscAbsReal(a);
      buf[off[5] + k] += g;
      buf[MOM_MAX + off[5] + k] += PetscAbsReal(g);
    }
  }
  PetscCall(PetscFree(gap));
  { /* two bodies: the master side's share, in the obstacle's group (a rigid obstacle of the same gaps has none) */
    Vec                mw;
    const PetscScalar *ma;
    PetscCall(SgContactPairMasterWeights(c, &mw));
    if (mw) {
      PetscCall(VecGetArrayRead(mw, &ma));
      for (PetscInt v = 0; v < m->nv; v++) {
        PetscReal s = 0;
        if (m->goff[v] < 0) continue;
        for (PetscInt d = 0; d < dim; d++) s += PetscRealPart(ma[m->goff[v] + d]);
        if (s == 0) continue;
        MomentWeights(dim, lo, hi, &m->x[v * dim], w);
        for (PetscInt k = 0; k < NMOM; k++) {
          buf[off[5] + k] += s * w[k];
          buf[MOM_MAX + off[5] + k] += PetscAbsReal(s * w[k]);
        }
      }
      PetscCall(VecRestoreArrayRead(mw, &ma));
      PetscCall(VecDestroy(&mw));
    }
  }
  PetscFunctionReturn(0);
}

/* the moments F[] and their sizes S[] (n of each) of the problem at factor 1 */
PetscErrorCode SgFingerprintMoments(SgElasticity el, SgContact c, PetscInt *n, PetscReal F[MOM_MAX], PetscReal S[MOM_MAX])
{
  const SgMesh *m;
  MPI_Comm      comm;
  PetscInt      dim, len[NGROUP], off[NGROUP + 1];
  PetscReal     lo[3], hi[3], buf[2 * MOM_MAX];

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetComm(el, &comm));
  PetscCall(SgElasticityGetDimension(el, &dim));
  PetscCall(SgElasticityGetMesh(el, &m));
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
  PetscCall(MomentsData(el, dim, lo, hi, off, buf));
  PetscCall(MomentsStiffness(el, dim, lo, hi, off, buf));
  if (c) PetscCall(MomentsContact(c, m, dim, lo, hi, off, buf));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, buf, 2 * MOM_MAX, MPIU_REAL, MPI_SUM, comm));
  for (PetscInt i = 0; i < *n; i++) F[i] = buf[i], S[i] = buf[MOM_MAX + i];
  PetscFunctionReturn(0);
}

/* Several materials (-material_ids): their ids, E and nu (3 n numbers; n = 0: one material), named in a refusal (the
   stiffness moments tell that K differs, not how) */
PetscErrorCode SgFingerprintMaterials(SgElasticity el, PetscInt *n, PetscReal t[3 * SG_MAX_IDS])
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

/* the material table as the options that give it (n = 0: one material, with -E E -nu nu when hasE) */
PetscErrorCode SgFingerprintMaterialText(PetscInt n, const PetscReal t[], PetscBool hasE, PetscReal E, PetscReal nu, char txt[], size_t len)
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

/* the first moment or size (*what >= 0; -1: none) in which two problems differ beyond round-off; which group, and a
   description of it */
void SgFingerprintCompare(PetscInt dim, PetscInt n, const PetscReal F0[], const PetscReal S0[], const PetscReal F1[], const PetscReal S1[], PetscInt *group, char desc[], size_t len, PetscReal *a, PetscReal *b)
{
  PetscInt lens[NGROUP], g = 0, start = 0;

  *group = -1;
  MomentGroupSizes(dim, lens);
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal tol  = 1e-10 * PetscMax(S0[i], S1[i]);
    const PetscBool same = (PetscBool)(PetscAbsReal(F0[i] - F1[i]) <= tol && PetscAbsReal(S0[i] - S1[i]) <= tol);
    while (g < NGROUP - 1 && i >= start + lens[g]) start += lens[g++];
    if (same) continue;
    {
      const PetscInt  j = i - start, k = g < 3 ? j / dim : j;
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
