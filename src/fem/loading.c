/* loading.c: the boundary data and the load: the Dirichlet values (given, manufactured or set per load step), their
   lifting, the data at a load factor and the data kept at factor 1. */
#include "fem/femimpl.h"

/* the Dirichlet value at vertex v: from vals (dim per Dirichlet id; SgElasticitySetDirichletValues), or NULL: the
   given data (-dirichlet_values, or the manufactured field) */
static void DirichletValue(SgElasticity p, const PetscReal vals[], PetscInt v, PetscReal u[])
{
  if (p->mms) SgMMSExact(p->dim, &p->mesh.x[v * p->dim], u, NULL);
  for (PetscInt d = 0; d < p->dim; d++) {
    const PetscInt g = p->mesh.bcpart[v * p->dim + d];
    if (g < 0) u[d] = 0.0; /* a free component of a partly fixed vertex */
    else if (vals) u[d] = vals[g * p->dim + d];
    else if (!p->mms) u[d] = p->dirichlet.nvalues ? p->dirichlet.values[g * p->dim + d] : 0.0;
  }
}

/* The Dirichlet values into ubc at the Dirichlet vertices: vals (SgElasticitySetDirichletValues) or NULL: the data. */
PetscErrorCode SgElasticityFillDirichletValues(SgElasticity p, const PetscReal vals[])
{
  const SgMesh *m = &p->mesh;
  PetscScalar  *ua;

  PetscFunctionBeginUser;
  PetscCall(VecGetArray(p->ubc, &ua));
  for (PetscInt v = 0; v < m->nv; v++)
    if (m->bcmask[v]) {
      PetscReal u[3];
      DirichletValue(p, vals, v, u);
      for (PetscInt d = 0; d < p->dim; d++) ua[m->loff[v] + d] = u[d];
    }
  PetscCall(VecRestoreArray(p->ubc, &ua));
  PetscFunctionReturn(0);
}

/* no load on the fixed components of partly fixed vertices: their unknowns stay 0 (fa: a local vector's array) */
void SgMeshZeroFixedComponents(const SgMesh *m, PetscInt dim, PetscScalar fa[])
{
  for (PetscInt v = 0; v < m->nv; v++)
    if (SgMeshPartial(m, v))
      for (PetscInt d = 0; d < dim; d++)
        if (SgMeshFixed(m, v, d)) fa[m->loff[v] + d] = 0;
}

/* The data at factor 1 (b, the Dirichlet values, the unlifted load), copied once: a run without load steps is
   untouched. */
static PetscErrorCode KeepFullLoad(SgElasticity p)
{
  PetscFunctionBeginUser;
  if (p->b1) PetscFunctionReturn(0);
  PetscCall(VecDuplicate(p->b, &p->b1));
  PetscCall(VecDuplicate(p->ubc, &p->ubc1));
  PetscCall(VecDuplicate(p->fpart, &p->fpart1));
  PetscCall(VecCopy(p->b, p->b1));
  PetscCall(VecCopy(p->ubc, p->ubc1));
  PetscCall(VecCopy(p->fpart, p->fpart1));
  p->energy_shift1 = p->energy_shift;
  p->bnorm1        = p->bnorm;
  p->bnorm_inf1    = p->bnorm_inf;
  PetscFunctionReturn(0);
}

/* The lifting of the Dirichlet values ubc (local): bl = -K_FD u_D on the free dofs (0 on the fixed components of
   partly fixed vertices, as in Assemble), and uKu = u_D^T K_DD u_D summed over the ranks (for the energy shift). */
static PetscErrorCode Lifting(SgElasticity p, Vec ubc, Vec bl, PetscReal *uKu)
{
  const SgMesh      *m   = &p->mesh;
  const PetscInt     dim = p->dim, nv = dim + 1, ne = nv * dim;
  const PetscScalar *ua;
  PetscScalar       *fa;
  PetscReal          s = 0;
  Vec                floc;

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(p->dm, &floc));
  PetscCall(VecZeroEntries(floc));
  PetscCall(VecGetArrayRead(ubc, &ua));
  PetscCall(VecGetArray(floc, &fa));
  for (PetscInt c = 0; c < m->nc; c++) {
    const PetscInt *cv = &m->cellv[c * nv];
    PetscReal       xe[12], Ke[144], ud[12], vol, lambda, mu;
    PetscBool       lift = PETSC_FALSE;

    for (PetscInt a = 0; a < nv; a++) {
      for (PetscInt d = 0; d < dim; d++) {
        xe[a * dim + d] = m->x[cv[a] * dim + d];
        ud[a * dim + d] = PetscRealPart(ua[m->loff[cv[a]] + d]);
      }
      if (m->bcmask[cv[a]]) lift = PETSC_TRUE;
    }
    if (!lift) continue;
    SgElasticityCellLame(p, c, &lambda, &mu);
    PetscCall(SgElementStiffness(dim, xe, lambda, mu, Ke, &vol));
    for (PetscInt i = 0; i < ne; i++) {
      PetscReal Ku = 0;
      for (PetscInt j = 0; j < ne; j++) Ku += Ke[i * ne + j] * ud[j];
      s += ud[i] * Ku;
      fa[m->loff[cv[i / dim]] + i % dim] -= Ku;
    }
  }
  SgMeshZeroFixedComponents(m, dim, fa);
  PetscCall(VecRestoreArray(floc, &fa));
  PetscCall(VecRestoreArrayRead(ubc, &ua));
  PetscCall(VecZeroEntries(bl));
  PetscCall(DMLocalToGlobal(p->dm, floc, ADD_VALUES, bl));
  PetscCall(DMRestoreLocalVector(p->dm, &floc));
  PetscCallMPI(MPI_Allreduce(&s, uKu, 1, MPIU_REAL, MPI_SUM, p->comm));
  PetscFunctionReturn(0);
}

/* The data of the Dirichlet values set (SgElasticitySetDirichletValues) and the load factor: u_D = dvals,
   b = load (b1 - lifting of the given values) + lifting of dvals, the unlifted load load fpart1, and the energy shift
   1/2 u_D K u_D - f.u_D. */
static PetscErrorCode ApplyDirichletValues(SgElasticity p)
{
  PetscReal   uKu, fu;
  PetscScalar dot;
  Vec         bl;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(p->b, &bl));
  if (!p->bload1) { /* the load of factor 1 without the lifting of the given Dirichlet values */
    PetscCall(VecDuplicate(p->b, &p->bload1));
    PetscCall(Lifting(p, p->ubc1, bl, &uKu));
    PetscCall(VecWAXPY(p->bload1, -1.0, bl, p->b1));
  }
  PetscCall(SgElasticityFillDirichletValues(p, p->dvals));
  PetscCall(Lifting(p, p->ubc, bl, &uKu));
  PetscCall(VecWAXPY(p->b, p->load, p->bload1, bl));
  PetscCall(VecAXPBY(p->fpart, p->load, 0.0, p->fpart1));
  PetscCall(VecDot(p->fpart, p->ubc, &dot)); /* local vectors: this rank's cells' part of the load */
  fu = PetscRealPart(dot);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &fu, 1, MPIU_REAL, MPI_SUM, p->comm));
  p->energy_shift = 0.5 * uKu - fu;
  PetscCall(VecNorm(p->b, NORM_2, &p->bnorm));
  PetscCall(SgVecVertexNormMax(p->b, SgNodalNormSize(p), &p->bnorm_inf)); /* per vertex: the same turned (assembly.c) */
  PetscCall(VecDestroy(&bl));
  PetscFunctionReturn(0);
}

/* The data at the load factor: the full data times it, or, with Dirichlet values set, those values and the loads
   times it. */
static PetscErrorCode ApplyLoad(SgElasticity p)
{
  const PetscReal t = p->load;

  PetscFunctionBeginUser;
  if (p->dvals_set) {
    PetscCall(ApplyDirichletValues(p));
    PetscFunctionReturn(0);
  }
  PetscCall(VecAXPBY(p->b, t, 0.0, p->b1));
  PetscCall(VecAXPBY(p->ubc, t, 0.0, p->ubc1));
  PetscCall(VecAXPBY(p->fpart, t, 0.0, p->fpart1));
  p->energy_shift = t * t * p->energy_shift1;
  PetscCall(VecNorm(p->b, NORM_2, &p->bnorm));
  PetscCall(SgVecVertexNormMax(p->b, SgNodalNormSize(p), &p->bnorm_inf)); /* per vertex: the same turned (assembly.c) */
  PetscFunctionReturn(0);
}

/* Quasi-static load stepping: the body force, the Neumann tractions and the Dirichlet values times t (t = 1: the
   data as given). b, the Dirichlet values, the load part of the energy and its shift scale with t (the shift with
   t^2); K does not change. The full data are copied on the first call, so a run without load steps is untouched.
   Once Dirichlet values were set (SgElasticitySetDirichletValues), t scales the loads only. */
PetscErrorCode SgElasticitySetLoadFactor(SgElasticity p, PetscReal t)
{
  PetscFunctionBeginUser;
  PetscCheck(p->setup, p->comm, PETSC_ERR_ORDER, "SgElasticitySetLoadFactor: call SgElasticitySetUp first");
  PetscCheck(PetscIsNormalReal(t) || t == 0, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "load factor %g: must be finite", (double)t);
  if (t == p->load) PetscFunctionReturn(0);
  PetscCall(KeepFullLoad(p));
  p->load = t;
  PetscCall(ApplyLoad(p));
  PetscFunctionReturn(0);
}

/* Non-proportional loading: the Dirichlet values of every id (dim per id, in the order of the ids) from now on,
   whatever the load factor (which then scales the loads only); NULL: back to the given values times the factor. */
PetscErrorCode SgElasticitySetDirichletValues(SgElasticity p, const PetscReal vals[])
{
  const PetscInt nv = p->dim * PetscMax(p->dirichlet.nids, 1);

  PetscFunctionBeginUser;
  PetscCheck(p->setup, p->comm, PETSC_ERR_ORDER, "SgElasticitySetDirichletValues: call SgElasticitySetUp first");
  if (vals) {
    PetscCheck(!p->mms, p->comm, PETSC_ERR_SUP, "Dirichlet values per load step: not with -mms (its Dirichlet data come from the manufactured field)");
    PetscCheck(p->dirichlet.active, p->comm, PETSC_ERR_ARG_WRONGSTATE, "Dirichlet values per load step: the problem has no Dirichlet part (-dirichlet_label, -dirichlet_ids)");
    for (PetscInt i = 0; i < nv; i++) PetscCheck(PetscIsNormalReal(vals[i]) || vals[i] == 0, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "Dirichlet value %" PetscInt_FMT " is %g, must be finite", i, (double)vals[i]);
  } else if (!p->dvals_set) PetscFunctionReturn(0);
  PetscCall(KeepFullLoad(p));
  for (PetscInt i = 0; vals && i < nv; i++) p->dvals[i] = vals[i];
  p->dvals_set = (PetscBool)(vals != NULL);
  PetscCall(ApplyLoad(p));
  PetscFunctionReturn(0);
}

/* the values of SgElasticitySetDirichletValues (set: whether any were set; vals: SgElasticityGetDirichletSize numbers) */
PetscErrorCode SgElasticityGetDirichletValues(SgElasticity p, PetscBool *set, PetscReal vals[])
{
  PetscFunctionBeginUser;
  *set = p->dvals_set;
  if (p->dvals_set && vals)
    for (PetscInt i = 0; i < p->dim * PetscMax(p->dirichlet.nids, 1); i++) vals[i] = p->dvals[i];
  PetscFunctionReturn(0);
}

/* the number of Dirichlet values SgElasticitySetDirichletValues takes: dim per Dirichlet id (per part without ids) */
PetscErrorCode SgElasticityGetDirichletSize(SgElasticity p, PetscInt *n)
{
  PetscFunctionBeginUser;
  *n = p->dirichlet.active ? p->dim * PetscMax(p->dirichlet.nids, 1) : 0;
  PetscFunctionReturn(0);
}

PetscErrorCode SgElasticityGetLoadFactor(SgElasticity p, PetscReal *t)
{
  PetscFunctionBeginUser;
  *t = p->load;
  PetscFunctionReturn(0);
}

/* The data of the problem as given (factor 1), whatever the factor and the Dirichlet values set now: the load before
   the Dirichlet lifting (a local vector holding this rank's cells' and facets' part: summed over the ranks it is the
   whole load) and the Dirichlet values (local: at the constrained components, 0 elsewhere). Borrowed. */
PetscErrorCode SgElasticityGetFullData(SgElasticity p, Vec *f, Vec *ubc)
{
  PetscFunctionBeginUser;
  if (f) *f = p->fpart1 ? p->fpart1 : p->fpart;
  if (ubc) *ubc = p->ubc1 ? p->ubc1 : p->ubc;
  PetscFunctionReturn(0);
}

/* ||b||_2, ||b||_inf and the energy shift of the full load (factor 1), whatever the factor now */
PetscErrorCode SgElasticityGetFullLoadScales(SgElasticity p, PetscReal *bnorm, PetscReal *bnorm_inf, PetscReal *shift)
{
  const PetscBool full = (PetscBool)!p->b1;

  PetscFunctionBeginUser;
  if (bnorm) *bnorm = full ? p->bnorm : p->bnorm1;
  if (bnorm_inf) *bnorm_inf = full ? p->bnorm_inf : p->bnorm_inf1;
  if (shift) *shift = full ? p->energy_shift : p->energy_shift1;
  PetscFunctionReturn(0);
}
