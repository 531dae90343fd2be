/* friction.c: the tangential terms of the SSN (friction, cv.friction): the projection lam_T = P_g(z) per contact
   vertex, its part of the residual and of the path values, its generalized derivative in the Jacobian, and the
   correction of Newton steps whose slips were linearized as stick (or sticks as slip). */
#include "solver/ssnimpl.h"

/* Friction at contact vertex i (uv: the contact vertices' displacements, SgContactVertexDisplacements: y_i, for two
   bodies the relative displacement (R y)_i; mN: the regularized normal multiplier there):
   z = T_i (lamhat_T,i + gamma_T u), u = T_i (y_i - yref_i) the slip since the start of the load step (yref = 0 at the
   first: quasi-static incremental friction), bound g = s (Tresca) or F mN (Coulomb), lam_T = P_g(z) the projection
   onto the ball of radius g; t = z/|z| (0 if z = 0). The state: free (g = 0), stick (|z| <= g), slip (|z| > g). */
static char FrictionAt(SgSSN s, PetscInt i, const PetscReal uv[], PetscReal mN, PetscReal lamT[], PetscReal u[], PetscReal t[], PetscReal *zn, PetscReal *gb)
{
  const SgContactView *c   = &s->cv;
  const PetscInt       dim = s->dim;
  const PetscReal     *n = &c->normal[i * dim], gT = c->fgfac * s->gamma;
  PetscReal            un = 0, zdn = 0, z[3], nz = 0, dy[3];

  for (PetscInt k = 0; k < dim; k++) {
    dy[k] = uv[i * dim + k] - c->yref[i * dim + k]; /* the load step's increment */
    un += n[k] * dy[k];
  }
  for (PetscInt k = 0; k < dim; k++) {
    u[k] = dy[k] - un * n[k];
    z[k] = s->lamhatT[i * dim + k] + gT * u[k];
    zdn += z[k] * n[k];
  }
  for (PetscInt k = 0; k < dim; k++) {
    z[k] -= zdn * n[k];
    nz += z[k] * z[k];
  }
  nz  = PetscSqrtReal(nz);
  *zn = nz;
  if (s->gfix) *gb = s->gfix[i]; /* Coulomb's fixed point: the bound frozen */
  else SgContactLawBound(c->law, i, mN, gb, NULL);
  for (PetscInt k = 0; k < dim; k++) t[k] = nz > 0 ? z[k] / nz : 0;
  if (!(*gb > 0)) {
    for (PetscInt k = 0; k < dim; k++) lamT[k] = 0;
    return SG_FRICTION_FREE;
  }
  if (nz <= *gb) {
    for (PetscInt k = 0; k < dim; k++) lamT[k] = z[k];
    return SG_FRICTION_STICK;
  }
  for (PetscInt k = 0; k < dim; k++) lamT[k] = *gb * t[k];
  return SG_FRICTION_SLIP;
}

/* F += sum_i w_i lam_T,i at y, with the normal multipliers mN; the states, the counts and, for the path values, the
   sums w_i (lam_T.u - |lam_T - lamhat_T|^2/(2 gamma_T)) (the regularized Tresca term of J(gamma, y): the value of
   sup_{|mu| <= g} mu.u - |mu - lamhat_T|^2/(2 gamma_T), whose gradient in u is lam_T) and its derivative in gamma,
   c w_i |lam_T - lamhat_T|^2 / (2 gamma_T^2) (for Coulomb the same terms with the bound frozen: no potential). Two
   bodies: the forces w_i lam_T,i act on the relative displacements (R^T, on both sides). */
PetscErrorCode SgSSNFrictionResidual(SgSSN s, const PetscScalar ya[], const PetscReal mN[], PetscScalar fa[], PetscReal loc[6])
{
  const SgContactView *c   = &s->cv;
  const PetscInt       dim = s->dim;
  const PetscReal      gT  = c->fgfac * s->gamma;

  PetscFunctionBeginUser;
  PetscCall(SgContactVertexDisplacements(s->c, ya, s->uv));
  for (PetscInt i = 0; i < c->n; i++) {
    PetscReal *lt = &s->mT[i * dim], u[3], t[3], zn, gb, lu = 0;
    const char st = FrictionAt(s, i, s->uv, mN[i], lt, u, t, &zn, &gb);
    s->fst[i]     = st;
    for (PetscInt k = 0; k < dim; k++) {
      s->ft[i * dim + k] = c->w[i] * lt[k];
      lu += lt[k] * u[k];
    }
    {
      PetscReal dd = 0; /* |lam_T - lamhat_T|^2 */
      for (PetscInt k = 0; k < dim; k++) dd += PetscSqr(lt[k] - s->lamhatT[i * dim + k]);
      loc[0] += c->w[i] * (lu - dd / (2 * gT));
      loc[1] += c->w[i] * c->fgfac * dd / (2 * gT * gT);
    }
    loc[2] += (st == SG_FRICTION_STICK);
    loc[3] += (st == SG_FRICTION_SLIP);
    /* a slip whose direction turned by more than 90 degrees since the Jacobian is a change of state too: in 2D the
       slip derivative is 0, and a vertex flipping between +g and -g would look settled */
    if (s->havejac) {
      PetscBool changed = (PetscBool)(st != s->fstjac[i]);
      if (!changed && st == SG_FRICTION_SLIP) {
        PetscReal tt = 0;
        for (PetscInt k = 0; k < dim; k++) tt += t[k] * s->tjac[i * dim + k];
        changed = (PetscBool)(tt <= 0);
      }
      loc[4] += changed;
      if (changed) { /* a change beyond round-off: |z| and the bound g differ by more than the round-off of forming them */
        PetscReal ymax = 0, lh = 0, ro;
        for (PetscInt k = 0; k < dim; k++) {
          ymax = PetscMax(ymax, PetscAbsReal(s->uv[i * dim + k]) + PetscAbsReal(c->yref[i * dim + k]));
          lh   = PetscMax(lh, PetscAbsReal(s->lamhatT[i * dim + k]));
        }
        const PetscReal roN = 8 * PETSC_MACHINE_EPSILON * (PetscAbsReal(s->lamhat[i]) + s->gamma * (PetscAbsReal(s->g[i] + c->d[i]) + PetscAbsReal(c->d[i]) + s->udata)) + s->kroff / c->w[i];
        PetscReal       gi, dg;
        SgContactLawBound(c->law, i, mN[i], &gi, &dg); /* the bound's round-off from lam_N's */
        ro = 8 * PETSC_MACHINE_EPSILON * (lh + gb + gT * ymax) + s->kroff / c->w[i] + (c->coupled ? dg * roN : 0);
        if (st == SG_FRICTION_FREE || s->fstjac[i] == SG_FRICTION_FREE) loc[5] += (PetscAbsReal(s->lamhat[i] + s->gamma * s->g[i]) > roN); /* the normal multiplier crossed 0 */
        else if (st != s->fstjac[i]) loc[5] += (PetscAbsReal(zn - gb) > ro);                                                               /* stick <-> slip */
        else loc[5] += (zn > ro);                                                                                                          /* a slip that reversed */
      }
    }
  }
  PetscCall(SgContactAddVertexForces(s->c, s->ft, fa));
  PetscFunctionReturn(0);
}

/* The generalized derivative of sum_i w_i lam_T,i at y (s->actjac: the normal active set of this Jacobian):
     stick: w gamma_T T_i;   slip: w (g/|z|) gamma_T (T_i - t t^T), and for Coulomb with an active normal also
     w F gamma t n_i^T (the bound F (lamhat + gamma (tau_N y - d)) moves with y: a nonsymmetric block);   free: 0. */
PetscErrorCode SgSSNFrictionJacobian(SgSSN s, Vec y, Mat P)
{
  const SgContactView *c   = &s->cv;
  const PetscInt       dim = s->dim;
  const PetscReal      gT  = c->fgfac * s->gamma;
  const PetscScalar   *ya, *fa = NULL;
  PetscReal           *blk;
  const PetscInt      *faxis = NULL;
  const PetscBool     *frot  = NULL;
  const PetscReal     *fsign = NULL;

  PetscFunctionBeginUser;
  if (s->frame) PetscCall(SgFrameGetAxes(s->frame, &faxis, &fsign, &frot));
  PetscCall(PetscCalloc1(c->n * dim * dim, &blk));
  s->nforce = 0;
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(SgContactVertexDisplacements(s->c, ya, s->uv));
  if (s->stagnant) PetscCall(VecGetArrayRead(s->r, &fa)); /* F(y): SNES evaluated it at y before this Jacobian */
  for (PetscInt i = 0; i < c->n; i++) {
    const PetscReal *n  = &c->normal[i * dim];
    const PetscReal  mN = s->actjac[i] ? s->lamhat[i] + s->gamma * s->g[i] : 0;
    PetscReal        lt[3], u[3], t[3], zn, gb, *B = &blk[i * dim * dim];
    char             st = FrictionAt(s, i, s->uv, mN, lt, u, t, &zn, &gb);
    /* a slip that reversed its direction since the last Jacobian of this solve is linearized as stick: with the slip
       derivative (0 in 2D) Newton can flip such a vertex between +g and -g forever when its solution sticks */
    if (s->nhash > 1 && st == SG_FRICTION_SLIP && s->fstjac[i] == SG_FRICTION_SLIP) { /* not the first Jacobian of the solve */
      PetscReal tt = 0;
      for (PetscInt k = 0; k < dim; k++) tt += t[k] * s->tjac[i * dim + k];
      if (tt <= 0) st = SG_FRICTION_STICK;
    }
    s->fforce[i] = (char)(st == SG_FRICTION_STICK && zn > gb);
    if (fa && st == SG_FRICTION_STICK && !s->fforce[i]) {
      /* the last Newton step did not halve ||F||: at a large gamma_T the stick force gamma_T T (y - yref) moves in
         steps of about q = 4 eps gamma_T |y_i|, and a correction below q is rounded away. A stick vertex whose
         tangential residual T F_i / w_i lies below q and whose equilibrium force lam_T - T F_i / w_i (the force the
         step should reach) lies beyond the bound slips: linearized as slip in the direction of that force (the step
         made consistent by SgSSNFrictionPreCheck) */
      PetscReal le[3], fn = 0, ln = 0, rt = 0, ym = 0;
      for (PetscInt k = 0; k < dim; k++) fn += n[k] * PetscRealPart(fa[c->off[i] + k]);
      for (PetscInt k = 0; k < dim; k++) {
        const PetscReal r = (PetscRealPart(fa[c->off[i] + k]) - fn * n[k]) / c->w[i];
        le[k]             = lt[k] - r;
        ln += le[k] * le[k];
        rt += r * r;
        ym = PetscMax(ym, PetscMax(PetscAbsReal(s->uv[i * dim + k]), PetscAbsReal(c->yref[i * dim + k])));
      }
      ln = PetscSqrtReal(ln);
      if (ln > gb && PetscSqrtReal(rt) <= 4 * PETSC_MACHINE_EPSILON * gT * ym) {
        st = SG_FRICTION_SLIP;
        zn = ln;
        for (PetscInt k = 0; k < dim; k++) t[k] = le[k] / ln;
        s->fforce[i] = 2;
      }
    }
    s->nforce += (s->fforce[i] != 0);
    s->fstjac[i] = st;
    for (PetscInt k = 0; k < dim; k++) s->tjac[i * dim + k] = t[k];
    if (st == SG_FRICTION_FREE) continue;
    {
      /* in the vertex's frame (-ssn_frame) the block Q^T B Q is made from n = e_axis and t in the frame */
      PetscReal nf[3] = {0, 0, 0}, tf[3], gi, dg = 0;
      if (c->coupled) SgContactLawBound(c->law, i, mN, &gi, &dg); /* the bound's derivative in lam_N */
      const PetscReal *nb = n, *tb = t;
      if (frot && frot[i]) {
        nf[faxis[i]] = fsign[i]; /* n = sign Q e_axis */
        SgFrameVectorToLocal(s->frame, i, t, tf);
        tf[faxis[i]] = 0;
        nb           = nf;
        tb           = tf;
      }
      for (PetscInt a = 0; a < dim; a++)
        for (PetscInt b = 0; b < dim; b++) {
          const PetscReal T = (a == b ? 1 : 0) - nb[a] * nb[b];
          if (st == SG_FRICTION_STICK) B[a * dim + b] = c->w[i] * gT * T;
          else {
            B[a * dim + b] = c->w[i] * (gb / zn) * gT * (T - tb[a] * tb[b]);
            if (c->coupled && s->actjac[i] && !s->gfix) B[a * dim + b] += c->w[i] * dg * s->gamma * tb[a] * nb[b];
          }
        }
    }
  }
  PetscCall(VecRestoreArrayRead(y, &ya));
  if (fa) PetscCall(VecRestoreArrayRead(s->r, &fa));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &s->nforce, 1, MPIU_INT, MPI_SUM, s->comm));
  PetscCall(SgSSNAddBlocks(s, blk, P)); /* two bodies transformed: nodal (jacobian.c) */
  PetscCall(PetscFree(blk));
  PetscFunctionReturn(0);
}

/* The Newton step with the slips linearized as stick (SgSSNFrictionJacobian) made consistent: their linear model is
   lam_T = z(y) + gamma_T T d, not P_g(z(y)) + gamma_T T d, so the residual of the step takes z there: the direction
   J^{-1} F grows by J^{-1} sum w_i (z_i - P_g(z_i)) (one more solve with the same operator). SNES steps to y - Y. */
PetscErrorCode SgSSNFrictionPreCheck(SNESLineSearch ls, Vec X, Vec Y, PetscBool *changed, void *ctx)
{
  SgSSN                s   = (SgSSN)ctx;
  const SgContactView *c   = &s->cv;
  const PetscInt       dim = s->dim;
  const PetscScalar   *xa;
  PetscScalar         *ra;
  KSP                  ksp;

  PetscFunctionBeginUser;
  *changed = PETSC_FALSE;
  if (!s->nforce) PetscFunctionReturn(0);
  if (!s->wpre) PetscCall(VecDuplicateVecs(X, 2, &s->wpre));
  PetscCall(VecZeroEntries(s->wpre[0]));
  PetscCall(VecGetArrayRead(X, &xa));
  PetscCall(SgContactVertexDisplacements(s->c, xa, s->uv));
  PetscCall(PetscArrayzero(s->ft, c->n * dim));
  for (PetscInt i = 0; i < c->n; i++) {
    PetscReal lt[3], u[3], t[3], zn, gb;
    if (!s->fforce[i]) continue;
    (void)FrictionAt(s, i, s->uv, s->actjac[i] ? s->lamhat[i] + s->gamma * s->g[i] : 0, lt, u, t, &zn, &gb);
    if (s->fforce[i] == 2) /* a stick linearized as slip: its model is g t_jac, not z = lam_T */
      for (PetscInt k = 0; k < dim; k++) s->ft[i * dim + k] = c->w[i] * (gb * s->tjac[i * dim + k] - lt[k]);
    else
      for (PetscInt k = 0; k < dim; k++) s->ft[i * dim + k] = c->w[i] * (zn * t[k] - lt[k]);
  }
  PetscCall(VecGetArray(s->wpre[0], &ra));
  PetscCall(SgContactAddVertexForces(s->c, s->ft, ra)); /* two bodies: on both sides */
  PetscCall(VecRestoreArray(s->wpre[0], &ra));
  PetscCall(VecRestoreArrayRead(X, &xa));
  PetscCall(SNESGetKSP(s->snes, &ksp));
  PetscCall(KSPSolve(ksp, s->wpre[0], s->wpre[1]));
  PetscCall(VecAXPY(Y, 1.0, s->wpre[1]));
  *changed = PETSC_TRUE;
  PetscFunctionReturn(0);
}
