/* pair_fields.c: what a two-body pair (contact_pair.c, pair.c) shows of a solution: the slave's contact pressure
   carried over to the master side (a vertex field) and the forces the two bodies exert on each other (the summary).
   Both from the multiplier of SgContactKKT (the one of the fields' contact_pressure and of contact_force). */
#include "contact/contactimpl.h"

/* f = B^T lam in the free displacement's layout (the caller destroys it), lam the multiplier of SgContactKKT at y: the
   pair's term of the residual K y - b + B^T lam; on a slave contact vertex j it is D_j lam_j n_j, on a master vertex k
   -sum_j M_jk lam_j n_j (on its free components) */
static PetscErrorCode PairTerm(SgContact c, Vec y, Vec *f)
{
  PetscReal    F[3];
  PetscScalar *la;

  PetscFunctionBeginUser;
  PetscCall(SgContactForceVector(c, y, F)); /* SgContactKKT's multiplier into c->klam */
  PetscCall(VecZeroEntries(c->pl));
  PetscCall(VecGetArray(c->pl, &la));
  for (PetscInt i = 0; i < c->n; i++)
    if (!c->obsrow[i]) la[c->prow[i]] = c->klam[i]; /* a rigid obstacle's rows (-contact_obstacle_ids) are not the pair's */
  PetscCall(VecRestoreArray(c->pl, &la));
  PetscCall(MatCreateVecs(c->pair->B, f, NULL));
  PetscCall(MatMultTranspose(c->pair->B, c->pl, *f));
  PetscFunctionReturn(0);
}

/* Two bodies: the normal force sum_j D_j lam_j (= contact_force without a rigid obstacle besides the pair; its rows
   are left out here), the force the master exerts on the slave body
   (-sum_j D_j lam_j n_j) and the force the slave exerts on the master body (minus the master's part of B^T lam,
   sum_j lam_j n_j sum_k M_jk on the master's free components). They balance where the master's vertices opposite
   the slave are free (sum_k M_jk = D_j on a covered row): a master vertex with every component fixed takes its
   share into its support, which the master's sum then misses. Zeros without a pair. */
PetscErrorCode SgContactPairForces(SgContact c, Vec y, PetscReal *fn, PetscReal Fs[3], PetscReal Fm[3])
{
  Vec                f;
  const PetscScalar *fa;
  PetscReal          s[7] = {0, 0, 0, 0, 0, 0, 0};
  PetscInt           n;
  char              *slave;

  PetscFunctionBeginUser;
  *fn = 0;
  for (PetscInt k = 0; k < 3; k++) Fs[k] = Fm[k] = 0;
  if (!c || !c->pair) PetscFunctionReturn(0);
  PetscCall(PairTerm(c, y, &f));
  PetscCall(VecGetLocalSize(f, &n));
  PetscCall(PetscCalloc1(n / c->dim + 1, &slave));
  for (PetscInt i = 0; i < c->n; i++)
    if (!c->obsrow[i]) slave[c->off[i] / c->dim] = 1;
  PetscCall(VecGetArrayRead(f, &fa));
  for (PetscInt j = 0; j < n; j++) s[(slave[j / c->dim] ? 0 : 3) + j % c->dim] -= PetscRealPart(fa[j]);
  PetscCall(VecRestoreArrayRead(f, &fa));
  for (PetscInt i = 0; i < c->n; i++)
    if (!c->obsrow[i]) s[6] += c->w[i] * c->klam[i];
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, s, 7, MPIU_REAL, MPI_SUM, c->comm));
  for (PetscInt k = 0; k < c->dim; k++) {
    Fs[k] = s[k];
    Fm[k] = s[3 + k];
  }
  *fn = s[6];
  PetscCall(PetscFree(slave));
  PetscCall(VecDestroy(&f));
  PetscFunctionReturn(0);
}

/* Two bodies: the contact pressure of the slave side projected on the master side, a vertex field (pressure, > 0 in
   compression; 0 off the master surface). At a master vertex k with the lumped weight W_k = int phi_k over the master
   surface and the outward unit normal m_k (the area-weighted mean of its facets' normals),
       p_k = (B^T lam)_k . m_k / W_k,   (B^T lam)_k = -sum_j M_jk lam_j n_j,
   the pair's nodal force on k (its free components) as a traction along the master's normal: for a uniform slave
   pressure p facing a flat master surface it is p at every master vertex the slave covers fully, and its sum
   sum_k W_k p_k over a flat master is the slave's force sum_j D_j lam_j. A master vertex without dofs (every component
   fixed) shows 0, and a roller fixing a component along m_k shows only the free components' share. */
PetscErrorCode SgContactPairMasterPressure(SgContact c, Vec y, Vec mp)
{
  const PetscInt     dim = c->dim;
  const SgMesh      *m   = c->mesh;
  Vec                f, wl, nl, pl;
  const PetscScalar *fa, *wa, *na;
  PetscScalar       *pa;
  PetscInt          *facets, *part, nf;
  PetscSection       ss, vs;

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(mp));
  if (!c || !c->pair) PetscFunctionReturn(0);
  PetscCall(PairTerm(c, y, &f));
  /* W_k and W_k m_k (unnormalized) from this rank's master facets, summed over the ranks that share a vertex */
  PetscCall(DMGetLocalSection(c->dmVert, &ss));
  PetscCall(DMGetLocalSection(c->dmVec, &vs));
  PetscCall(DMGetLocalVector(c->dmVert, &wl));
  PetscCall(DMGetLocalVector(c->dmVec, &nl));
  PetscCall(SgBoundaryGetFacets(c->dm, &c->master, &nf, &facets, &part));
  PetscCall(SgContactLumpedSurface(c, nf, facets, wl, nl, NULL));
  PetscCall(PetscFree2(facets, part));
  /* p_k at the owned free master vertices (the others add zeros: the owner's value stays) */
  PetscCall(DMGetLocalVector(c->dmVert, &pl));
  PetscCall(VecZeroEntries(pl));
  PetscCall(VecGetArray(pl, &pa));
  PetscCall(VecGetArrayRead(wl, &wa));
  PetscCall(VecGetArrayRead(nl, &na));
  PetscCall(VecGetArrayRead(f, &fa));
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt  so, vo;
    PetscReal W, len = 0, fn = 0;
    if (m->goff[v] < 0) continue;
    PetscCall(PetscSectionGetOffset(ss, m->vStart + v, &so));
    PetscCall(PetscSectionGetOffset(vs, m->vStart + v, &vo));
    W = PetscRealPart(wa[so]);
    if (!(W > 0)) continue;
    for (PetscInt k = 0; k < dim; k++) {
      len += PetscSqr(PetscRealPart(na[vo + k]));
      fn += PetscRealPart(fa[m->goff[v] + k]) * PetscRealPart(na[vo + k]);
    }
    if (len > 0) pa[so] = fn / PetscSqrtReal(len) / W;
  }
  PetscCall(VecRestoreArrayRead(f, &fa));
  PetscCall(VecRestoreArrayRead(wl, &wa));
  PetscCall(VecRestoreArrayRead(nl, &na));
  PetscCall(VecRestoreArray(pl, &pa));
  PetscCall(DMLocalToGlobal(c->dmVert, pl, ADD_VALUES, mp));
  PetscCall(DMRestoreLocalVector(c->dmVert, &pl));
  PetscCall(DMRestoreLocalVector(c->dmVert, &wl));
  PetscCall(DMRestoreLocalVector(c->dmVec, &nl));
  PetscCall(VecDestroy(&f));
  PetscFunctionReturn(0);
}
