/* law_measures.c: what a law with a bound (law_regularized.c's laws: tresca, coulomb, a caller's type without ops of
   its own) measures of a displacement for SgContactKKT, the output fields and the summary: lam_T from the tangential
   residual, the slip of the load step and the state per vertex, the friction summary and its keys. law.c installs
   these ops (SgContactLawSetMeasureOps); the frictionless law has none, so contact.c, the controllers and the output
   ask the law and never branch on friction. */
#include "contact/contactimpl.h"

/* Friction at contact vertex i from its residual r = (K y - b)_i (on the fixed components: 0, or the reaction where a
   Dirichlet facet of Gamma_c fixes them), its load step's increment dy = u_i - uref_i of the full displacement (the
   Dirichlet data on fixed components) and the normal multiplier lamN: the tangential multiplier lam_T = -T_i r / w_i,
   the slip u = T_i dy, the bound g (s, or F max(0, lamN)), and the state. With Coulomb every active vertex (act) is
   stick or slip and the others free (a bound at the noise level, F = 0 or F lamN tiny, is met: slip); with Tresca a
   vertex is free where s is at the noise level. Slip: |lam_T| at the bound up to noise. A vertex whose tangential
   motion is prescribed (fixed components) is sliding when that motion is not zero: its friction is the bound along
   the slip (the support supplies the rest of its reaction); held by a Dirichlet facet of Gamma_c, it sticks while it
   does not move, with the reaction as its friction up to the bound (unoise: the displacement noise). */
static char FrictionFromResidual(SgContact c, PetscInt i, const PetscReal r[], const PetscReal dy[], PetscBool act, PetscReal lamN, PetscReal noise, PetscReal unoise, PetscReal lt[], PetscReal u[], PetscReal *gb, PetscReal *ntfree)
{
  const PetscInt   dim = c->dim;
  const PetscReal *n   = &c->normal[i * dim];
  const PetscInt   v   = c->vert[i];
  PetscReal        rn = 0, yn = 0, nt = 0, nu = 0, up = 0;
  PetscBool        partial;

  for (PetscInt k = 0; k < dim; k++) {
    rn += n[k] * r[k];
    yn += n[k] * dy[k];
  }
  for (PetscInt k = 0; k < dim; k++) {
    lt[k] = -(r[k] - rn * n[k]) / c->w[i];
    u[k]  = dy[k] - yn * n[k];
    nt += lt[k] * lt[k];
    nu += u[k] * u[k];
  }
  nt = PetscSqrtReal(nt);
  nu = PetscSqrtReal(nu);
  SgContactLawBound(c->law, i, lamN, gb, NULL);
  partial = (PetscBool)(c->haspartial && SgMeshPartial(c->mesh, v));
  *ntfree = nt; /* the part the solution must keep within the bound: that of the free components */
  if (partial) {
    *ntfree = 0;
    for (PetscInt k = 0; k < dim; k++) {
      if (SgMeshFixed(c->mesh, v, k)) up = PetscMax(up, PetscAbsReal(u[k]));
      else *ntfree += lt[k] * lt[k];
    }
    *ntfree = PetscSqrtReal(*ntfree);
  }
  if (c->law->coupled ? !act : *gb <= noise) return SG_FRICTION_FREE; /* a bound from lam_N: free out of contact */
  if (partial && (up > unoise || (c->dmask[i] && nu > unoise))) {     /* prescribed sliding */
    for (PetscInt k = 0; k < dim; k++) lt[k] = *gb * u[k] / nu;
    return SG_FRICTION_SLIP;
  }
  if (partial && c->dmask[i]) { /* held where it is: the reaction, at most the bound */
    if (nt > *gb)
      for (PetscInt k = 0; k < dim; k++) lt[k] *= *gb / nt;
    return SG_FRICTION_STICK;
  }
  return nt >= *gb - PetscMax(1e-10 * *gb, noise) ? SG_FRICTION_SLIP : SG_FRICTION_STICK;
}

/* The friction part of SgContactKKT. friction: lam_T balances the tangential residual; measured are the bound
   |lam_T| <= g (a force, with the dual part) and, as lengths with the complementarity: no slip where |lam_T| < g, slip
   u_T = a lam_T with a >= 0 where |lam_T| = g (the friction force -w lam_T on the body opposes the slip). On fixed
   components the displacement is the data (the slip prescribed) and the reaction of a Dirichlet facet of Gamma_c is a
   traction on it. In: ra = K y - b (the rollers' fixed components zeroed), lam the normal multipliers, ynrm
   ||y||_inf. Out: the numbers per contact vertex (klt, kslip, kst), the friction summary fsum, *slip2 (this rank's
   slip part of the complementarity^2), and ra without the tangential residual of the free components (what the friction
   balances). The op kkt of a law with a bound. */
static PetscErrorCode KKT_Regularized(SgContactLaw law, SgContact c, Vec y, PetscScalar ra[], const PetscReal lam[], PetscReal ynrm, const KKTScales *sc, PetscReal *slip2)
{
  const PetscInt     dim = c->dim;
  const PetscScalar *ya;
  PetscReal          f[8] = {0}, fm[2] = {0, 0}, unoise = ynrm, *uv, *ft = NULL;
  const PetscScalar *ul = NULL, *rfa = NULL;
  Vec                yloc = NULL, Rf = NULL;
  PetscInt           nd;

  PetscFunctionBeginUser;
  (void)law;
  if (c->haspartial) {
    PetscCall(DMGetLocalVector(c->dm, &yloc));
    PetscCall(SgElasticityGlobalToLocal(c->prob, y, yloc));
    PetscCall(VecGetArrayRead(yloc, &ul));
    PetscCall(SgElasticityGetNodalNormSize(c->prob, &nd));
    for (PetscInt i = 0; i < c->n; i++) { /* the largest vertex displacement (-contact_kkt_scale vertex: its length, the same turned) */
      PetscReal u2 = 0;
      for (PetscInt k = 0; k < dim; k++) {
        const PetscReal uk = PetscRealPart(ul[c->mesh->loff[c->vert[i]] + k]);
        if (nd > 1) u2 += uk * uk;
        else unoise = PetscMax(unoise, PetscAbsReal(uk));
      }
      if (nd > 1) unoise = PetscMax(unoise, PetscSqrtReal(u2));
    }
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &unoise, 1, MPIU_REAL, MPI_MAX, c->comm));
  }
  if (c->hasdface) {
    PetscCall(VecDuplicate(y, &Rf));
    PetscCall(SgElasticityFixedResidual(c->prob, y, Rf));
    PetscCall(VecGetArrayRead(Rf, &rfa));
  }
  unoise *= 1e-10;
  PetscCall(VecGetArrayRead(y, &ya));
  /* the vertices' displacements (two bodies: relative, R y) and, for a pair, the friction forces w lam_T on them */
  PetscCall(PetscMalloc1(c->n * dim + 1, &uv));
  PetscCall(SgContactVertexDisplacements(c, ya, uv));
  if (c->pair) PetscCall(PetscCalloc1(c->n * dim + 1, &ft));
  for (PetscInt i = 0; i < c->n; i++) {
    const PetscReal noise = ForceNoise(c, sc, i);
    const PetscInt  v     = c->vert[i];
    PetscReal       lt[3], u[3], gb, nt = 0, err = 0, a = 0, un = 0, r[3], dy[3], ntfree;
    char            st;
    for (PetscInt k = 0; k < dim; k++) {
      const PetscBool fixed = (PetscBool)(c->haspartial && SgMeshFixed(c->mesh, v, k));
      r[k]                  = fixed && c->dmask && (c->dmask[i] >> k & 1) ? PetscRealPart(rfa[c->off[i] + k]) : PetscRealPart(ra[c->off[i] + k]);
      dy[k]                 = fixed ? PetscRealPart(ul[c->mesh->loff[v] + k]) - c->ypref[i * dim + k] : uv[i * dim + k] - c->yref[i * dim + k];
      if (ul && !c->norecord) {
        c->ypfull[i * dim + k]          = PetscRealPart(ul[c->mesh->loff[v] + k]);
        c->ypfull[(c->n + i) * dim + k] = PetscRealPart(ya[c->off[i] + k]);
      }
    }
    st = FrictionFromResidual(c, i, r, dy, (PetscBool)c->kact[i], lam[i], noise, unoise, lt, u, &gb, &ntfree);
    for (PetscInt k = 0; k < dim; k++) {
      nt += lt[k] * lt[k];
      un += u[k] * u[k];
      f[2 + k] += c->w[i] * lt[k];
      c->klt[i * dim + k]   = lt[k];
      c->kslip[i * dim + k] = u[k];
    }
    c->kst[i] = st;
    if (ft) /* two bodies: the friction force acts on both sides (taken out below, R^T w lam_T) */
      for (PetscInt k = 0; k < dim; k++) ft[i * dim + k] = c->w[i] * lt[k];
    else { /* what the friction balances: the tangential residual on the free components */
      PetscReal rn = 0;
      for (PetscInt k = 0; k < dim; k++) rn += PetscRealPart(ra[c->off[i] + k]) * c->normal[i * dim + k];
      for (PetscInt k = 0; k < dim; k++)
        if (!(c->haspartial && SgMeshFixed(c->mesh, v, k))) ra[c->off[i] + k] = rn * c->normal[i * dim + k];
    }
    nt    = PetscSqrtReal(nt);
    un    = PetscSqrtReal(un);
    fm[0] = PetscMax(fm[0], c->w[i] * PetscMax(0, ntfree - gb));
    fm[1] = PetscMax(fm[1], un);
    f[5] += c->w[i] * nt;
    if (st == SG_FRICTION_STICK) err = un;
    else if (st == SG_FRICTION_SLIP && gb > noise) { /* a bound at the noise level (Coulomb, F lam_N tiny): no direction to measure */
      for (PetscInt k = 0; k < dim; k++) a += u[k] * lt[k] / nt;
      a = PetscMax(0, a);
      for (PetscInt k = 0; k < dim; k++) err += PetscSqr(u[k] - a * lt[k] / nt);
      err = PetscSqrtReal(err);
    }
    f[0] += (st == SG_FRICTION_STICK);
    f[1] += (st == SG_FRICTION_SLIP);
    f[6] += c->w[i] * err * err;
  }
  PetscCall(VecRestoreArrayRead(y, &ya));
  if (ft) PetscCall(SgContactAddVertexForces(c, ft, ra)); /* at the slave vertex: leaves its normal residual, as above */
  PetscCall(PetscFree(ft));
  PetscCall(PetscFree(uv));
  if (yloc) {
    PetscCall(VecRestoreArrayRead(yloc, &ul));
    PetscCall(DMRestoreLocalVector(c->dm, &yloc));
    if (!c->norecord) c->haverecord = PETSC_TRUE; /* the next load step's slip reference from this y takes these data */
  }
  if (Rf) {
    PetscCall(VecRestoreArrayRead(Rf, &rfa));
    PetscCall(VecDestroy(&Rf));
  }
  *slip2 = f[6]; /* the slip part of the complementarity^2 (summed by the caller) */
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, f, 8, MPIU_REAL, MPI_SUM, c->comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, fm, 2, MPIU_REAL, MPI_MAX, c->comm));
  c->fsum.nstick     = (PetscInt)f[0];
  c->fsum.nslip      = (PetscInt)f[1];
  c->fsum.force_norm = 0;
  for (PetscInt k = 0; k < 3; k++) {
    c->fsum.force[k] = k < dim ? f[2 + k] : 0;
    c->fsum.force_norm += PetscSqr(c->fsum.force[k]);
  }
  c->fsum.force_norm = PetscSqrtReal(c->fsum.force_norm);
  c->fsum.traction   = f[5];
  c->fsum.slip_max   = fm[1];
  c->fsum.bound      = SafeRatio(fm[0], sc->F);
  PetscFunctionReturn(0);
}

/* the force on the body at a contact vertex for the force scale: with friction the whole nodal force */
static PetscReal ContactForce_Regularized(SgContactLaw law, PetscInt dim, const PetscScalar r[], const PetscReal n[], PetscReal rn, PetscReal wlam, PetscReal f[])
{
  PetscReal a = 0;

  (void)law;
  (void)n;
  (void)rn;
  (void)wlam;
  for (PetscInt k = 0; k < dim; k++) {
    f[k] = PetscRealPart(r[k]);
    a += f[k] * f[k];
  }
  return PetscSqrtReal(a);
}

static PetscErrorCode GetFields_Regularized(SgContactLaw law, PetscInt *n, const char *const **names, const PetscBool **vector)
{
  static const char *const nm[3]  = {"tangential_traction", "slip", "friction_state"};
  static const PetscBool   vec[3] = {PETSC_TRUE, PETSC_TRUE, PETSC_FALSE};

  PetscFunctionBeginUser;
  (void)law;
  *n      = 3;
  *names  = nm;
  *vector = vec;
  PetscFunctionReturn(0);
}

/* The fields of a law with a bound (the op fields): per contact vertex the tangential traction lam_T (from the
   tangential residual, as in SgContactKKT: the traction on the obstacle; the body feels -lam_T), the slip of the
   load step T_i (y_i - yref_i) (with load steps the last step's increment; the total T_i y_i without) and the state 0 free, 1 stick, 2 slip (the classification of SgContactKKT); zero elsewhere. */
static PetscErrorCode Fields_Regularized(SgContactLaw law, SgContact c, Vec v[])
{
  const PetscInt dim = c->dim;
  Vec            lt, ls, lst;
  PetscScalar   *ta, *sa, *qa;
  PetscSection   vs, ss;

  PetscFunctionBeginUser;
  (void)law;
  PetscCall(DMGetLocalSection(c->dmVec, &vs));
  PetscCall(DMGetLocalSection(c->dmVert, &ss));
  PetscCall(DMGetLocalVector(c->dmVec, &lt));
  PetscCall(DMGetLocalVector(c->dmVec, &ls));
  PetscCall(DMGetLocalVector(c->dmVert, &lst));
  PetscCall(VecZeroEntries(lt));
  PetscCall(VecZeroEntries(ls));
  PetscCall(VecZeroEntries(lst));
  PetscCall(VecGetArray(lt, &ta));
  PetscCall(VecGetArray(ls, &sa));
  PetscCall(VecGetArray(lst, &qa));
  for (PetscInt i = 0; i < c->n; i++) {
    PetscInt off, soff;
    PetscCall(PetscSectionGetOffset(vs, c->mesh->vStart + c->vert[i], &off));
    PetscCall(PetscSectionGetOffset(ss, c->mesh->vStart + c->vert[i], &soff));
    for (PetscInt k = 0; k < dim; k++) {
      ta[off + k] = c->klt[i * dim + k];
      sa[off + k] = c->kslip[i * dim + k];
    }
    qa[soff] = c->kst[i];
  }
  PetscCall(VecRestoreArray(lt, &ta));
  PetscCall(VecRestoreArray(ls, &sa));
  PetscCall(VecRestoreArray(lst, &qa));
  /* only owners hold contact vertices: adding the zeros of the other ranks keeps the owner's value */
  PetscCall(VecZeroEntries(v[0]));
  PetscCall(VecZeroEntries(v[1]));
  PetscCall(VecZeroEntries(v[2]));
  PetscCall(DMLocalToGlobal(c->dmVec, lt, ADD_VALUES, v[0]));
  PetscCall(DMLocalToGlobal(c->dmVec, ls, ADD_VALUES, v[1]));
  PetscCall(DMLocalToGlobal(c->dmVert, lst, ADD_VALUES, v[2]));
  PetscCall(DMRestoreLocalVector(c->dmVec, &lt));
  PetscCall(DMRestoreLocalVector(c->dmVec, &ls));
  PetscCall(DMRestoreLocalVector(c->dmVert, &lst));
  PetscFunctionReturn(0);
}

/* the summary keys of a solve: the law's parameters by their names, the stick and slip sets, the friction resultant,
   traction integral and largest slip, and the two friction parts of the KKT measures */
static PetscErrorCode Summary_Regularized(SgContactLaw law, PetscInt dim, const SgFrictionSummary *fs, SgContactLawKeys *sum)
{
  const char *pn[SG_LAW_MAX_PARAMETERS];
  PetscReal   pv[SG_LAW_MAX_PARAMETERS];
  PetscInt    np;

  PetscFunctionBeginUser;
  PetscCall(SgContactLawGetParameters(law, &np, pn, pv));
  for (PetscInt k = 0; k < np; k++) PetscCall(sum->setreal(sum->ctx, pn[k], pv[k]));
  PetscCall(sum->setint(sum->ctx, "stick_size", fs->nstick));
  PetscCall(sum->setint(sum->ctx, "slip_size", fs->nslip));
  PetscCall(sum->setreal(sum->ctx, "friction_force", fs->force_norm));
  PetscCall(sum->setrealarray(sum->ctx, "friction_force_vector", dim, fs->force));
  PetscCall(sum->setreal(sum->ctx, "friction_traction_integral", fs->traction));
  PetscCall(sum->setreal(sum->ctx, "slip_max", fs->slip_max));
  PetscCall(sum->setreal(sum->ctx, "friction_bound_violation", fs->bound));
  PetscCall(sum->setreal(sum->ctx, "friction_complementarity", fs->slip));
  PetscFunctionReturn(0);
}

/* per load step: the stick and slip sets, the friction resultant and traction integral */
static PetscErrorCode StepSummary_Regularized(SgContactLaw law, PetscInt n, const SgFrictionSummary fs[], SgContactLawKeys *sum)
{
  PetscInt  *b[2];
  PetscReal *a[2];

  PetscFunctionBeginUser;
  (void)law;
  PetscCall(PetscMalloc4(n + 1, &b[0], n + 1, &b[1], n + 1, &a[0], n + 1, &a[1]));
  for (PetscInt k = 0; k < n; k++) {
    b[0][k] = fs[k].nstick;
    b[1][k] = fs[k].nslip;
    a[0][k] = fs[k].force_norm;
    a[1][k] = fs[k].traction;
  }
  PetscCall(sum->setintarray(sum->ctx, "load_step_stick_size", n, b[0]));
  PetscCall(sum->setintarray(sum->ctx, "load_step_slip_size", n, b[1]));
  PetscCall(sum->setrealarray(sum->ctx, "load_step_friction_force", n, a[0]));
  PetscCall(sum->setrealarray(sum->ctx, "load_step_friction_traction_integral", n, a[1]));
  PetscCall(PetscFree4(b[0], b[1], a[0], a[1]));
  PetscFunctionReturn(0);
}

/* the checkpoint's per-step summaries: the stick and slip set sizes, the friction resultant and traction integral, 4
   numbers per step in the dataset load_steps_friction (a file without it, from a run without friction, leaves fs) */
static PetscErrorCode StepSave_Regularized(SgContactLaw law, PetscInt n, const SgFrictionSummary fs[], SgContactLawWriter *w)
{
  PetscReal *a;

  PetscFunctionBeginUser;
  (void)law;
  PetscCall(PetscMalloc1(4 * n + 1, &a));
  for (PetscInt i = 0; i < n; i++) {
    a[4 * i]     = fs[i].nstick;
    a[4 * i + 1] = fs[i].nslip;
    a[4 * i + 2] = fs[i].force_norm;
    a[4 * i + 3] = fs[i].traction;
  }
  PetscCall(w->reals(w->ctx, "load_steps_friction", 4 * n, a));
  PetscCall(PetscFree(a));
  PetscFunctionReturn(0);
}

static PetscErrorCode StepLoad_Regularized(SgContactLaw law, PetscInt n, SgFrictionSummary fs[], SgContactLawReader *r)
{
  PetscReal *a;
  PetscBool  has;

  PetscFunctionBeginUser;
  (void)law;
  PetscCall(r->hasdataset(r->ctx, "load_steps_friction", &has));
  if (!has) PetscFunctionReturn(0);
  PetscCall(r->reals(r->ctx, "load_steps_friction", 4 * n, &a));
  for (PetscInt i = 0; i < n; i++) {
    fs[i].nstick     = (PetscInt)a[4 * i];
    fs[i].nslip      = (PetscInt)a[4 * i + 1];
    fs[i].force_norm = a[4 * i + 2];
    fs[i].traction   = a[4 * i + 3];
  }
  PetscCall(PetscFree(a));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactLawSetMeasureOps(SgContactLaw law)
{
  PetscFunctionBeginUser;
  if (!law->ops.kkt) law->ops.kkt = KKT_Regularized;
  if (!law->ops.contactforce) law->ops.contactforce = ContactForce_Regularized;
  if (!law->ops.getfields && !law->ops.fields) {
    law->ops.getfields = GetFields_Regularized;
    law->ops.fields    = Fields_Regularized;
  }
  if (!law->ops.summary) law->ops.summary = Summary_Regularized;
  if (!law->ops.stepsummary) law->ops.stepsummary = StepSummary_Regularized;
  if (!law->ops.stepsave && !law->ops.stepload) {
    law->ops.stepsave = StepSave_Regularized;
    law->ops.stepload = StepLoad_Regularized;
  }
  PetscFunctionReturn(0);
}
