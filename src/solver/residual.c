/* residual.c: the SSN's residual F(y) = K y - b + sum_i w_i max(0, lamhat_i + gamma g_i(y)) n_i (+ the friction terms), with
   the active set, the path values J(gamma, y) and dJ/dgamma, the residuals r1, r2 and the round-off floors of the
   stopping tests; and the equilibrium error of a single regularized solve. */
#include "solver/ssnimpl.h"

/* s->ffloor, the round-off floor of ||F|| at y (from the gaps, multipliers and friction states of its residual). The
   round-off of the gamma-scaled terms in F: forming gamma (tau_N y - d) on the active set (and the bound F lam_N
   of Coulomb) and gamma_T T (y - yref) on the stick set, eps gamma w (|tau_N y| + |d|) a vertex; summed in l2 like
   ||F||. A Newton step on a settled set that leaves ||F|| at this floor has nothing more to gain. */
static PetscErrorCode ResidualFloor(SgSSN s, Vec y)
{
  const SgContactView *c = &s->cv;
  const PetscScalar   *ya;
  PetscReal            fl2 = 0;
  SgContactLawInput    in;

  PetscFunctionBeginUser;
  PetscCall(SgSSNLawInput(s, &in));
  PetscCall(VecGetArrayRead(y, &ya));
  for (PetscInt i = 0; i < s->n; i++) {
    PetscReal t = 0;
    if (s->lamhat[i] + s->gamma * s->g[i] > 0) {
      PetscReal gi, dg = 0;
      SgContactLawBound(c->law, i, s->m[i], &gi, &dg); /* the bound's coupling dg lam_N (0 unless it depends on lam_N) */
      t = s->gamma * s->w[i] * (PetscAbsReal(s->g[i] + s->d[i]) + PetscAbsReal(s->d[i]) + s->udata) * (1 + dg);
    }
    t += SgContactLawFloor(c->law, &in, s->lst, ya, i, PETSC_FALSE); /* the law's tangential term (0 without) */
    fl2 += t * t;
  }
  PetscCall(VecRestoreArrayRead(y, &ya));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &fl2, 1, MPIU_REAL, MPI_SUM, s->comm));
  s->ffloor = 4 * PETSC_MACHINE_EPSILON * PetscSqrtReal(fl2);
  { /* and of K y - b itself (a body that just touches: gaps of a few ulps, nothing gamma-scaled) */
    PetscReal ynorm;
    PetscCall(VecNorm(y, NORM_2, &ynorm));
    s->ffloor += 8 * PETSC_MACHINE_EPSILON * (s->Knorm * (ynorm + s->udata) + s->bnorm);
  }
  PetscFunctionReturn(0);
}

/* whether the Newton steps take F's frame form (frame.c, SgFrameSetResidual): with frames, one body against an
   obstacle, no tangential law */
static PetscErrorCode FrameResidual(SgSSN s, PetscBool *on)
{
  PetscBool pair = PETSC_FALSE;

  PetscFunctionBeginUser;
  *on = PETSC_FALSE;
  if (!s->frame || SgFramePairTransform(s->frame) || s->cv.props.tangential) PetscFunctionReturn(0);
  PetscCall(SgContactIsPair(s->c, &pair));
  *on = (PetscBool)!pair;
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNResidual(SNES snes, Vec y, Vec F, void *ctx)
{
  SgSSN              s   = (SgSSN)ctx;
  const PetscInt     dim = s->dim;
  const PetscScalar *ya;
  PetscScalar       *fa, dots[2];
  PetscReal          loc[8] = {0}, glob[8], r1corr2, floc[6] = {0};
  Vec                vecs[2];
  PetscBool          framed;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(SG_Residual, 0, 0, 0, 0));
  {
    /* the round-off of the elastic force K y at a vertex, 8 eps ||K|| ||y|| (per vertex): a change of a multiplier (times the
       vertex's weight) below it is invisible in the equilibrium, as when a body just touches (gaps of a few ulps).
       ||y|| at least the problem's displacement data (s->udata): a step unloaded to y = 0 has iterates of round-off
       size, whose gaps would otherwise flip the sets on numbers far below anything the problem can resolve */
    PetscReal ymax;
    PetscCall(SgVecVertexNormMax(y, s->nd, &ymax)); /* the largest vertex displacement: the same turned */
    s->kroff = 8 * PETSC_MACHINE_EPSILON * s->Knorm * (ymax + s->dmax + s->udata);
  }
  PetscCall(MatMult(s->K, y, F));
  vecs[0] = F;
  vecs[1] = s->b;
  PetscCall(VecMDot(y, 2, vecs, dots));
  PetscCall(VecAXPY(F, -1.0, s->b));
  PetscCall(FrameResidual(s, &framed));
  if (framed) { /* K y - b, for the frame form of F (SgFrameSetResidual) */
    Vec rnn;
    PetscCall(SgFrameResidualWork(s->frame, F, &rnn));
    PetscCall(VecCopy(F, rnn));
  }
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(SgContactGap(s->c, ya, s->g));
  PetscCall(VecRestoreArrayRead(y, &ya));
  PetscCall(PetscLogEventBegin(SG_ActiveSet, 0, 0, 0, 0));
  for (PetscInt i = 0; i < s->n; i++) {
    const PetscReal z = s->lamhat[i] + s->gamma * s->g[i];
    /* the multiplier of the last Newton step: lamhat + gamma g on the set it used, 0 elsewhere */
    const PetscReal lj = s->havejac ? (s->actjac[i] ? z : 0) : PetscMax(0, z);
    s->m[i]            = PetscMax(0, z);
    s->act[i]          = (char)(z > 0);
    loc[0] += s->w[i] * s->m[i] * s->m[i];
    loc[1] += s->w[i] * s->m[i] * s->g[i];
    loc[2] += s->act[i];
    if (s->havejac) {
      loc[3] += (s->act[i] && !s->actjac[i]);
      loc[4] += (!s->act[i] && s->actjac[i]);
      /* a change beyond the round-off of forming lamhat + gamma (tau_N y - d) */
      if (s->act[i] != s->actjac[i]) loc[7] += (PetscAbsReal(z) > SgSSNDecisionRoundoff(s, i, s->g[i]));
    }
    loc[5] += s->w[i] * PetscSqr(lj - s->m[i]);
  }
  PetscCall(PetscLogEventEnd(SG_ActiveSet, 0, 0, 0, 0));
  PetscCall(VecGetArray(F, &fa));
  PetscCall(SgContactAddForce(s->c, s->m, fa));
  PetscCall(VecGetArrayRead(y, &ya)); /* the law's tangential forces (none without friction) */
  PetscCall(SgSSNFrictionResidual(s, ya, s->m, fa, floc));
  PetscCall(VecRestoreArrayRead(y, &ya));
  /* r1 is the dual norm of K y - b + B^T W lam_jac = F - B^T W (m - lam_jac): only contact dofs differ from F */
  r1corr2 = 0;
  {
    const PetscScalar *ma;
    PetscCall(VecGetArrayRead(s->mass, &ma));
    for (PetscInt i = 0; i < s->n; i++) {
      const PetscReal z = s->lamhat[i] + s->gamma * s->g[i], lj = s->havejac ? (s->actjac[i] ? z : 0) : s->m[i];
      for (PetscInt k = 0; k < dim; k++) {
        const PetscInt  j  = s->off[i] + k;
        const PetscReal fj = PetscRealPart(fa[j]), r = fj - s->w[i] * (s->m[i] - lj) * s->normal[i * dim + k];
        r1corr2 += (r * r - fj * fj) / PetscRealPart(ma[j]);
      }
    }
    PetscCall(VecRestoreArrayRead(s->mass, &ma));
  }
  loc[6] = r1corr2;
  PetscCall(VecRestoreArray(F, &fa));
  if (framed) PetscCall(SgFrameSetResidual(s->frame, F, s->w, s->m));
  PetscCall(ResidualFloor(s, y));
  PetscCallMPI(MPI_Allreduce(loc, glob, 8, MPIU_REAL, MPI_SUM, s->comm));
  PetscCall(SgElasticityDualNorm(s->prob, F, &s->fdual));
  s->r1       = PetscSqrtReal(PetscMax(0, s->fdual * s->fdual + glob[6]));
  s->r2       = PetscSqrtReal(glob[5]);
  s->nact     = (PetscInt)glob[2];
  s->nentered = (PetscInt)glob[3];
  s->nleft    = (PetscInt)glob[4];
  s->nhard    = (PetscInt)glob[7];
  s->V        = 0.5 * PetscRealPart(dots[0]) - PetscRealPart(dots[1]) + s->energy_shift + glob[0] / (2 * s->gamma);
  s->dVdg     = glob[1] / s->gamma - glob[0] / (2 * s->gamma * s->gamma);
  s->V += floc[0]; /* the law's terms, summed over the ranks (0 without friction) */
  s->dVdg += floc[1];
  s->nstick    = (PetscInt)floc[2];
  s->nslip     = (PetscInt)floc[3];
  s->nfchanged = (PetscInt)floc[4];
  s->nhard += (PetscInt)floc[5];
  PetscCall(PetscLogEventEnd(SG_Residual, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The measure of a single regularized solve: the equilibrium residual of (P_gamma) at y, ||F(y)||_inf, relative to the
   force scale fscale of the KKT measures of (P) (SgKKT.fscale, the largest nodal force on the body), after discounting the round-off of forming
   gamma (tau_N y - d) on the active set (4 eps max_A gamma w_i (|tau_N y_i| + |d_i|), which at gamma ~ 1e16 is not small).
   Scaling by gamma w instead would hide inexact linear solves: a relative error of 1e-11 there is a pressure error of
   1e-11 gamma |d|. roundoff: that discount relative to the force scale; above the tolerance the error cannot be
   resolved in double precision at this gamma. */
PetscErrorCode SgSSNEquilibriumError(SgSSN s, Vec y, PetscReal fscale, PetscReal *err, PetscReal *roundoff)
{
  const SgContactView *c = &s->cv;
  Vec                  F;
  PetscScalar         *fa;
  const PetscScalar   *ya;
  PetscReal            floor = 0, nrm[2], *g, *m;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(s->n, &g, s->n, &m));
  PetscCall(VecDuplicate(y, &F));
  PetscCall(MatMult(s->K, y, F));
  PetscCall(VecAXPY(F, -1.0, s->b));
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(SgContactGap(s->c, ya, g));
  PetscCall(VecRestoreArrayRead(y, &ya));
  for (PetscInt i = 0; i < s->n; i++) {
    const PetscReal z = s->lamhat[i] + s->gamma * g[i];
    m[i]              = PetscMax(0, z);
    if (z > 0) floor = PetscMax(floor, s->gamma * s->w[i] * (PetscAbsReal(g[i] + s->d[i]) + PetscAbsReal(s->d[i])));
  }
  floor *= 4 * PETSC_MACHINE_EPSILON;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &floor, 1, MPIU_REAL, MPI_MAX, s->comm));
  PetscCall(VecGetArray(F, &fa));
  PetscCall(SgContactAddForce(s->c, m, fa));
  {
    PetscReal         floc[6] = {0}, fl = 0;
    SgContactLawInput in;
    PetscCall(VecGetArrayRead(y, &ya));
    PetscCall(SgSSNFrictionResidual(s, ya, m, fa, floc)); /* the law's tangential forces (none without friction) */
    /* the round-off of gamma_T T y on the stick set */
    PetscCall(SgSSNLawInput(s, &in));
    for (PetscInt i = 0; i < s->n; i++) fl = PetscMax(fl, SgContactLawFloor(c->law, &in, s->lst, ya, i, PETSC_TRUE));
    PetscCall(VecRestoreArrayRead(y, &ya));
    fl *= 4 * PETSC_MACHINE_EPSILON;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &fl, 1, MPIU_REAL, MPI_MAX, s->comm));
    floor += fl;
  }
  PetscCall(VecRestoreArray(F, &fa));
  PetscCall(SgVecVertexNormMax(F, s->nd, &nrm[0])); /* the largest nodal force (its length: the same turned) */
  {
    const PetscReal scale = fscale, r = PetscMax(0, nrm[0] - floor);
    *err      = r > 0 ? (scale > 0 ? r / scale : PETSC_INFINITY) : nrm[0] - nrm[0]; /* NaN passed on */
    *roundoff = floor > 0 ? (scale > 0 ? floor / scale : PETSC_INFINITY) : 0;
  }
  PetscCall(VecDestroy(&F));
  PetscCall(PetscFree2(g, m));
  PetscFunctionReturn(0);
}
