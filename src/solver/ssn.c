/* ssn.c: semismooth Newton (primal-dual active set) solver for (P_gamma), handed to SNES.
   Residual F(y) = K y - b + sum_i w_i max(0, lamhat_i + gamma g_i(y)) n_i; Jacobian K + gamma sum_{A} w_i n_i n_i^T;
   full Newton steps; converged when the active set stops changing (and, for inexact linear solves, ||F|| is small). */
#include "solver/ssnimpl.h"

const char *const SgSSNReasons[] = {"ITERATING", "ACTIVE_SET_SETTLED", "NEIGHBOURHOOD_REACHED", "INITIAL_RESIDUAL_ZERO", "ACTIVE_SET_CYCLING", "FNORM_NAN", "MAX_IT", "LINEAR_SOLVE_FAILED", "SNES_FAILED", "KKT_BELOW_TOL", "RESIDUAL_AT_ROUNDOFF"};

/* Friction at contact vertex i (ya: the local part of y, mN: the regularized normal multiplier there):
   z = T_i (lamhat_T,i + gamma_T u), u = T_i (y_i - yref_i) the slip since the start of the load step (yref = 0 at the
   first: quasi-static incremental friction), bound g = s (Tresca) or F mN (Coulomb), lam_T = P_g(z) the projection
   onto the ball of radius g; t = z/|z| (0 if z = 0). The state: free (g = 0), stick (|z| <= g), slip (|z| > g). */
static char FrictionAt(SgSSN s, PetscInt i, const PetscScalar ya[], PetscReal mN, PetscReal lamT[], PetscReal u[], PetscReal t[], PetscReal *zn, PetscReal *gb)
{
  const SgContactView *c   = &s->cv;
  const PetscInt       dim = s->dim;
  const PetscReal     *n   = &c->normal[i * dim], gT = c->fgfac * s->gamma;
  PetscReal            un = 0, zdn = 0, z[3], nz = 0, dy[3];

  for (PetscInt k = 0; k < dim; k++) {
    dy[k] = PetscRealPart(ya[c->off[i] + k]) - c->yref[i * dim + k]; /* the load step's increment */
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
   c w_i |lam_T - lamhat_T|^2 / (2 gamma_T^2) (for Coulomb the same terms with the bound frozen: no potential) */
static void FrictionResidual(SgSSN s, const PetscScalar ya[], const PetscReal mN[], PetscScalar fa[], PetscReal loc[6])
{
  const SgContactView *c   = &s->cv;
  const PetscInt       dim = s->dim;
  const PetscReal      gT  = c->fgfac * s->gamma;

  for (PetscInt i = 0; i < c->n; i++) {
    PetscReal *lt = &s->mT[i * dim], u[3], t[3], zn, gb, lu = 0;
    const char st = FrictionAt(s, i, ya, mN[i], lt, u, t, &zn, &gb);
    s->fst[i]     = st;
    for (PetscInt k = 0; k < dim; k++) {
      fa[c->off[i] + k] += c->w[i] * lt[k];
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
          ymax = PetscMax(ymax, PetscAbsReal(PetscRealPart(ya[c->off[i] + k])) + PetscAbsReal(c->yref[i * dim + k]));
          lh   = PetscMax(lh, PetscAbsReal(s->lamhatT[i * dim + k]));
        }
        const PetscReal roN = 8 * PETSC_MACHINE_EPSILON * (PetscAbsReal(s->lamhat[i]) + s->gamma * (PetscAbsReal(s->g[i] + c->d[i]) + PetscAbsReal(c->d[i]) + s->udata)) + s->kroff / c->w[i];
        PetscReal gi, dg;
        SgContactLawBound(c->law, i, mN[i], &gi, &dg); /* the bound's round-off from lam_N's */
        ro = 8 * PETSC_MACHINE_EPSILON * (lh + gb + gT * ymax) + s->kroff / c->w[i] + (c->coupled ? dg * roN : 0);
        if (st == SG_FRICTION_FREE || s->fstjac[i] == SG_FRICTION_FREE) loc[5] += (PetscAbsReal(s->lamhat[i] + s->gamma * s->g[i]) > roN); /* the normal multiplier crossed 0 */
        else if (st != s->fstjac[i]) loc[5] += (PetscAbsReal(zn - gb) > ro); /* stick <-> slip */
        else loc[5] += (zn > ro);                                              /* a slip that reversed */
      }
    }
  }
}

static PetscErrorCode Residual(SNES snes, Vec y, Vec F, void *ctx)
{
  SgSSN              s = (SgSSN)ctx;
  const SgContactView *c = &s->cv;
  const PetscInt     dim = s->dim;
  const PetscScalar *ya;
  PetscScalar       *fa, dots[2];
  PetscReal          loc[8] = {0}, glob[8], r1corr2, floc[6] = {0};
  Vec                vecs[2];

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(SG_Residual, 0, 0, 0, 0));
  {
    /* the round-off of the elastic force K y at a vertex, 8 eps ||K|| ||y||_inf: a change of a multiplier (times the
       vertex's weight) below it is invisible in the equilibrium, as when a body just touches (gaps of a few ulps).
       ||y|| at least the problem's displacement data (s->udata): a step unloaded to y = 0 has iterates of round-off
       size, whose gaps would otherwise flip the sets on numbers far below anything the problem can resolve */
    PetscReal ymax;
    PetscCall(VecNorm(y, NORM_INFINITY, &ymax));
    s->kroff = 8 * PETSC_MACHINE_EPSILON * s->Knorm * (ymax + s->dmax + s->udata);
  }
  PetscCall(MatMult(s->K, y, F));
  vecs[0] = F;
  vecs[1] = s->b;
  PetscCall(VecMDot(y, 2, vecs, dots));
  PetscCall(VecAXPY(F, -1.0, s->b));
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(SgContactGap(s->c, ya, s->g));
  PetscCall(VecRestoreArrayRead(y, &ya));
  PetscCall(PetscLogEventBegin(SG_ActiveSet, 0, 0, 0, 0));
  for (PetscInt i = 0; i < c->n; i++) {
    const PetscReal z = s->lamhat[i] + s->gamma * s->g[i];
    /* the multiplier of the last Newton step: lamhat + gamma g on the set it used, 0 elsewhere */
    const PetscReal lj = s->havejac ? (s->actjac[i] ? z : 0) : PetscMax(0, z);
    s->m[i]   = PetscMax(0, z);
    s->act[i] = (char)(z > 0);
    loc[0] += c->w[i] * s->m[i] * s->m[i];
    loc[1] += c->w[i] * s->m[i] * s->g[i];
    loc[2] += s->act[i];
    if (s->havejac) {
      loc[3] += (s->act[i] && !s->actjac[i]);
      loc[4] += (!s->act[i] && s->actjac[i]);
      /* a change beyond the round-off of forming lamhat + gamma (tau_N y - d) */
      if (s->act[i] != s->actjac[i]) loc[7] += (PetscAbsReal(z) > 8 * PETSC_MACHINE_EPSILON * (PetscAbsReal(s->lamhat[i]) + s->gamma * (PetscAbsReal(s->g[i] + c->d[i]) + PetscAbsReal(c->d[i]) + s->udata)) + s->kroff / c->w[i]);
    }
    loc[5] += c->w[i] * PetscSqr(lj - s->m[i]);
  }
  PetscCall(PetscLogEventEnd(SG_ActiveSet, 0, 0, 0, 0));
  PetscCall(VecGetArray(F, &fa));
  PetscCall(SgContactAddForce(s->c, s->m, fa));
  if (c->friction) {
    PetscCall(VecGetArrayRead(y, &ya));
    FrictionResidual(s, ya, s->m, fa, floc);
    PetscCall(VecRestoreArrayRead(y, &ya));
  }
  /* r1 is the dual norm of K y - b + B^T W lam_jac = F - B^T W (m - lam_jac): only contact dofs differ from F */
  r1corr2 = 0;
  {
    const PetscScalar *ma;
    PetscCall(VecGetArrayRead(s->mass, &ma));
    for (PetscInt i = 0; i < c->n; i++) {
      const PetscReal z = s->lamhat[i] + s->gamma * s->g[i], lj = s->havejac ? (s->actjac[i] ? z : 0) : s->m[i];
      for (PetscInt k = 0; k < dim; k++) {
        const PetscInt  j  = c->off[i] + k;
        const PetscReal fj = PetscRealPart(fa[j]), r = fj - c->w[i] * (s->m[i] - lj) * c->normal[i * dim + k];
        r1corr2 += (r * r - fj * fj) / PetscRealPart(ma[j]);
      }
    }
    PetscCall(VecRestoreArrayRead(s->mass, &ma));
  }
  loc[6] = r1corr2;
  PetscCall(VecRestoreArray(F, &fa));
  { /* the round-off of the gamma-scaled terms in F: forming gamma (tau_N y - d) on the active set (and the bound F lam_N
       of Coulomb) and gamma_T T (y - yref) on the stick set, eps gamma w (|tau_N y| + |d|) a vertex; summed in l2 like
       ||F||. A Newton step on a settled set that leaves ||F|| at this floor has nothing more to gain. */
    PetscReal fl2 = 0;
    PetscCall(VecGetArrayRead(y, &ya));
    for (PetscInt i = 0; i < c->n; i++) {
      PetscReal t = 0, ymax = 0;
      if (s->lamhat[i] + s->gamma * s->g[i] > 0) {
        PetscReal gi, dg = 0;
        if (c->coupled) SgContactLawBound(c->law, i, s->m[i], &gi, &dg); /* the bound dg lam_N */
        t = s->gamma * c->w[i] * (PetscAbsReal(s->g[i] + c->d[i]) + PetscAbsReal(c->d[i]) + s->udata) * (1 + (c->coupled ? dg : 0));
      }
      /* at stick lam_T = z; at slip g z/|z| is well-conditioned, except for the landing of a Newton step from another
         state on |z| = g (a stick linearization that lands at the slip bound) */
      if (c->friction && (s->fst[i] == SG_FRICTION_STICK || (s->havejac && s->fst[i] == SG_FRICTION_SLIP && s->fstjac[i] != SG_FRICTION_SLIP))) {
        for (PetscInt k = 0; k < dim; k++) ymax = PetscMax(ymax, PetscAbsReal(PetscRealPart(ya[c->off[i] + k])) + PetscAbsReal(c->yref[i * dim + k]));
        t += c->fgfac * s->gamma * c->w[i] * 2 * ymax;
      }
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
  }
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
  if (c->friction) {
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, floc, 6, MPIU_REAL, MPI_SUM, s->comm));
    s->V += floc[0];
    s->dVdg += floc[1];
    s->nstick    = (PetscInt)floc[2];
    s->nslip     = (PetscInt)floc[3];
    s->nfchanged = (PetscInt)floc[4];
    s->nhard += (PetscInt)floc[5];
  }
  PetscCall(PetscLogEventEnd(SG_Residual, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The generalized derivative of sum_i w_i lam_T,i at y (s->actjac: the normal active set of this Jacobian):
     stick: w gamma_T T_i;   slip: w (g/|z|) gamma_T (T_i - t t^T), and for Coulomb with an active normal also
     w F gamma t n_i^T (the bound F (lamhat + gamma (tau_N y - d)) moves with y: a nonsymmetric block);   free: 0. */
static PetscErrorCode FrictionJacobian(SgSSN s, Vec y, Mat P)
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
  if (s->stagnant) PetscCall(VecGetArrayRead(s->r, &fa)); /* F(y): SNES evaluated it at y before this Jacobian */
  for (PetscInt i = 0; i < c->n; i++) {
    const PetscReal *n  = &c->normal[i * dim];
    const PetscReal  mN = s->actjac[i] ? s->lamhat[i] + s->gamma * s->g[i] : 0;
    PetscReal        lt[3], u[3], t[3], zn, gb, *B = &blk[i * dim * dim];
    char             st = FrictionAt(s, i, ya, mN, lt, u, t, &zn, &gb);
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
         made consistent by PreCheck) */
      PetscReal le[3], fn = 0, ln = 0, rt = 0, ym = 0;
      for (PetscInt k = 0; k < dim; k++) fn += n[k] * PetscRealPart(fa[c->off[i] + k]);
      for (PetscInt k = 0; k < dim; k++) {
        const PetscReal r = (PetscRealPart(fa[c->off[i] + k]) - fn * n[k]) / c->w[i];
        le[k] = lt[k] - r;
        ln += le[k] * le[k];
        rt += r * r;
        ym = PetscMax(ym, PetscMax(PetscAbsReal(PetscRealPart(ya[c->off[i] + k])), PetscAbsReal(c->yref[i * dim + k])));
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
      PetscReal        nf[3] = {0, 0, 0}, tf[3], gi, dg = 0;
      if (c->coupled) SgContactLawBound(c->law, i, mN, &gi, &dg); /* the bound's derivative in lam_N */
      const PetscReal *nb = n, *tb = t;
      if (frot && frot[i]) {
        nf[faxis[i]] = fsign[i]; /* n = sign Q e_axis */
        SgFrameVectorToLocal(s->frame, i, t, tf);
        tf[faxis[i]] = 0;
        nb = nf;
        tb = tf;
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
  PetscCall(SgContactAddBlocks(s->c, blk, P));
  PetscCall(PetscFree(blk));
  PetscFunctionReturn(0);
}

/* gamma w_i n_i n_i^T on the active vertices, in the frames: gamma w_i on the normal's diagonal entry at a rotated
   vertex (exactly: nothing of gamma reaches its tangential entries), the block as without frames elsewhere */
static PetscErrorCode FrameContactJacobian(SgSSN s, Mat P)
{
  const SgContactView *c   = &s->cv;
  const PetscInt       dim = s->dim;
  const PetscInt      *axis;
  const PetscBool     *rot;
  PetscReal           *blk;

  PetscFunctionBeginUser;
  PetscCall(SgFrameGetAxes(s->frame, &axis, NULL, &rot));
  PetscCall(PetscCalloc1(c->n * dim * dim, &blk));
  for (PetscInt i = 0; i < c->n; i++) {
    PetscReal *B = &blk[i * dim * dim];
    if (!s->actjac[i]) continue;
    if (rot[i]) B[axis[i] * dim + axis[i]] = s->gamma * c->w[i];
    else
      for (PetscInt a = 0; a < dim; a++)
        for (PetscInt b = 0; b < dim; b++) B[a * dim + b] = s->gamma * c->w[i] * c->normal[i * dim + a] * c->normal[i * dim + b];
  }
  PetscCall(SgContactAddBlocks(s->c, blk, P));
  PetscCall(PetscFree(blk));
  PetscFunctionReturn(0);
}

static PetscErrorCode Jacobian(SNES snes, Vec y, Mat J, Mat P, void *ctx)
{
  SgSSN              s = (SgSSN)ctx;
  const SgContactView *c = &s->cv;
  const PetscScalar *ya;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(SG_Jacobian, 0, 0, 0, 0));
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(SgContactGap(s->c, ya, s->g));
  PetscCall(VecRestoreArrayRead(y, &ya));
  for (PetscInt i = 0; i < c->n; i++) s->actjac[i] = (char)(s->lamhat[i] + s->gamma * s->g[i] > 0);
  s->havejac = PETSC_TRUE;
  if (s->nhash == s->maxhash) {
    PetscInt64 *h;
    s->maxhash = PetscMax(64, 2 * s->maxhash);
    PetscCall(PetscMalloc1(s->maxhash, &h));
    PetscCall(PetscArraycpy(h, s->hash, s->nhash));
    PetscCall(PetscFree(s->hash));
    s->hash = h;
  }
  PetscCall(SgContactActiveSetHash(s->c, s->actjac, &s->hash[s->nhash++]));
  PetscCall(SgTMGSetActiveSet(s->tmg, s->actjac));
  /* within one (P_gamma) the Jacobians differ in the few vertices whose state changed: optionally keep the previous
     preconditioner (a factorization, or an AMG hierarchy) while the Krylov solver converges fast with it */
  if (s->pc_reuse_its > 0) {
    KSP      ksp;
    PetscInt kits = 0;
    PetscCall(SNESGetKSP(snes, &ksp));
    if (s->nhash > 1) PetscCall(KSPGetIterationNumber(ksp, &kits));
    /* SNES decides the reuse after this callback from its lag: -1 reuses, -2 rebuilds once */
    PetscCall(SNESSetLagPreconditioner(snes, s->nhash > 1 && kits <= s->pc_reuse_its ? -1 : -2));
  } else if (s->pc_same_set && !c->friction) { /* with slip the matrix changes on the same set */
    /* the same active set at the same gamma is the same matrix: keep its preconditioner */
    PetscCall(SNESSetLagPreconditioner(snes, s->nhash > 1 && s->hash[s->nhash - 1] == s->hash[s->nhash - 2] ? -1 : -2));
  }
  /* only the contact block changes: copy the stiffness (same pattern, so factorizations keep their symbolic phase) */
  PetscCall(MatCopy(s->Klin, P, SAME_NONZERO_PATTERN));
  if (s->frame) PetscCall(FrameContactJacobian(s, P));
  else PetscCall(SgContactAddJacobian(s->c, s->actjac, s->gamma, P));
  if (c->friction) PetscCall(FrictionJacobian(s, y, P));
  PetscCall(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscLogEventEnd(SG_Jacobian, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The Newton step with the slips linearized as stick (FrictionJacobian) made consistent: their linear model is
   lam_T = z(y) + gamma_T T d, not P_g(z(y)) + gamma_T T d, so the residual of the step takes z there: the direction
   J^{-1} F grows by J^{-1} sum w_i (z_i - P_g(z_i)) (one more solve with the same operator). SNES steps to y - Y. */
static PetscErrorCode PreCheck(SNESLineSearch ls, Vec X, Vec Y, PetscBool *changed, void *ctx)
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
  PetscCall(VecGetArray(s->wpre[0], &ra));
  for (PetscInt i = 0; i < c->n; i++) {
    PetscReal lt[3], u[3], t[3], zn, gb;
    if (!s->fforce[i]) continue;
    (void)FrictionAt(s, i, xa, s->actjac[i] ? s->lamhat[i] + s->gamma * s->g[i] : 0, lt, u, t, &zn, &gb);
    if (s->fforce[i] == 2) /* a stick linearized as slip: its model is g t_jac, not z = lam_T */
      for (PetscInt k = 0; k < dim; k++) ra[c->off[i] + k] = c->w[i] * (gb * s->tjac[i * dim + k] - lt[k]);
    else
      for (PetscInt k = 0; k < dim; k++) ra[c->off[i] + k] = c->w[i] * (zn * t[k] - lt[k]);
  }
  PetscCall(VecRestoreArray(s->wpre[0], &ra));
  PetscCall(VecRestoreArrayRead(X, &xa));
  PetscCall(SNESGetKSP(s->snes, &ksp));
  PetscCall(KSPSolve(ksp, s->wpre[0], s->wpre[1]));
  PetscCall(VecAXPY(Y, 1.0, s->wpre[1]));
  *changed = PETSC_TRUE;
  PetscFunctionReturn(0);
}

static PetscErrorCode Converged(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm, PetscReal fnorm, SNESConvergedReason *reason, void *ctx)
{
  SgSSN     s = (SgSSN)ctx;
  PetscReal atol, rtol;
  PetscBool settled, small;

  PetscFunctionBeginUser;
  *reason   = SNES_CONVERGED_ITERATING;
  s->reason = SG_SSN_ITERATING;
  PetscCall(SNESGetTolerances(snes, &atol, &rtol, NULL, NULL, NULL));
  if (PetscIsInfOrNanReal(fnorm)) {
    *reason   = SNES_DIVERGED_FNORM_NAN;
    s->reason = SG_SSN_NAN;
    PetscFunctionReturn(0);
  }
  if (it == 0) {
    s->fnorm0       = fnorm;
    s->prev_settled = PETSC_FALSE;
    s->stagnant     = PETSC_FALSE;
    if (fnorm <= atol) {
      *reason   = SNES_CONVERGED_FNORM_ABS;
      s->reason = SG_SSN_ZERO_RESIDUAL;
    }
    PetscFunctionReturn(0);
  }
  settled = (PetscBool)(s->nentered + s->nleft == 0 && (!s->cv.friction || s->nfchanged == 0));
  if (s->stop_test) { /* a controller's own test replaces the one below */
    PetscCall(s->stop_test(s, it, fnorm, settled, reason, s->stop_ctx));
    PetscFunctionReturn(0);
  }
  /* with inexact linear solves the residual must be small too: below rtol ||F_0||, or, when a Newton step on an
     unchanged active set no longer halves it, at the round-off floor of the (gamma-scaled) residual, which must
     lie below sqrt(rtol) max(||F_0||, ||b||) or at the floor of forming the gamma-scaled terms (s->ffloor: at large
     gamma that floor is above sqrt(rtol) ||b||, and the steps repeat the same iterate until -snes_max_it) */
  if (s->cv.friction) {
    /* friction: ||F_0|| grows with gamma (the penetration of the start) and says nothing about the slip set, where
       the Newton steps converge instead of landing: measured against the load ||b|| alone */
    small = (PetscBool)(fnorm <= PetscMax(atol, rtol * s->bnorm) || (settled && s->prev_settled && fnorm > 0.5 * s->prev_fnorm && fnorm <= PetscMax(PetscSqrtReal(rtol) * s->bnorm, s->ffloor)));
  } else small = (PetscBool)(!s->residual_test || fnorm <= PetscMax(atol, rtol * s->fnorm0) || (settled && s->prev_settled && fnorm > 0.5 * s->prev_fnorm && fnorm <= PetscMax(PetscSqrtReal(rtol) * PetscMax(s->fnorm0, s->bnorm), s->ffloor)));
  /* friction: the next Jacobian reclassifies the sticks from their equilibrium force (FrictionJacobian) */
  s->stagnant     = (PetscBool)(s->cv.friction && it > 1 && fnorm > 0.5 * s->prev_fnorm);
  s->prev_settled = settled;
  s->prev_fnorm   = fnorm;
  if (settled && small) {
    *reason   = SNES_CONVERGED_FNORM_ABS;
    s->reason = SG_SSN_SETTLED;
  } else if (!settled && s->nhard == 0 && fnorm <= s->ffloor) {
    /* the states that still change do so on round-off (a gap of a few ulps, a vertex at the slip bound after a tiny
       load increment: s->nhard counts the others) and F(y) (with the states of y itself) is zero to the round-off of
       its gamma-scaled terms: y solves (P_gamma) as far as double precision can tell; more steps only repeat them */
    *reason   = SNES_CONVERGED_FNORM_ABS;
    s->reason = SG_SSN_ROUNDOFF;
  } else if (s->nbhd_tau > 0 && PetscSqrtReal(s->r1 * s->r1 + s->r2 * s->r2) <= s->nbhd_tau / PetscSqrtReal(s->gamma)) {
    /* r1 measures the equilibrium residual, inexact linear solves included */
    *reason   = SNES_CONVERGED_FNORM_ABS;
    s->reason = SG_SSN_NEIGHBOURHOOD;
  } else if (!settled && !s->cv.friction) { /* with slip the iterate is no function of the sets: no cycle test */
    PetscInt64 h;
    PetscCall(SgContactActiveSetHash(s->c, s->act, &h));
    for (PetscInt j = 0; j < s->nhash - 1; j++)
      if (s->hash[j] == h) {
        /* with exact solves the iterate is a function of the active set: a revisited set repeats forever */
        *reason   = SNES_DIVERGED_LOCAL_MIN;
        s->reason = SG_SSN_CYCLING;
        PetscCall(PetscInfo(snes, "active set of Newton step %" PetscInt_FMT " revisited at iteration %" PetscInt_FMT "\n", j + 1, it));
        break;
      }
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode Monitor(SNES snes, PetscInt it, PetscReal fnorm, void *ctx)
{
  SgSSN     s = (SgSSN)ctx;
  KSP       ksp;
  PetscInt  kits = 0;
  PetscLogDouble t;

  PetscFunctionBeginUser;
  PetscCall(SNESGetKSP(snes, &ksp));
  if (it > 0) PetscCall(KSPGetIterationNumber(ksp, &kits));
  PetscCall(PetscTime(&t));
  if (s->monitor && s->cv.friction)
    PetscCall(PetscPrintf(s->comm, "  SSN %2" PetscInt_FMT " gamma %.3e |A| %" PetscInt_FMT " (+%" PetscInt_FMT " -%" PetscInt_FMT " next) stick %" PetscInt_FMT " slip %" PetscInt_FMT " (%" PetscInt_FMT " changed) ||F|| %.3e r1 %.3e r2 %.3e V %.10e KSP %" PetscInt_FMT "\n", it, (double)s->gamma, s->nact, s->nentered, s->nleft, s->nstick, s->nslip, s->nfchanged, (double)fnorm, (double)s->r1, (double)s->r2, (double)s->V, kits));
  else if (s->monitor)
    PetscCall(PetscPrintf(s->comm, "  SSN %2" PetscInt_FMT " gamma %.3e |A| %" PetscInt_FMT " (+%" PetscInt_FMT " -%" PetscInt_FMT " next) ||F|| %.3e r1 %.3e r2 %.3e V %.10e KSP %" PetscInt_FMT "\n", it, (double)s->gamma, s->nact, s->nentered, s->nleft, (double)fnorm, (double)s->r1, (double)s->r2, (double)s->V, kits));
  else if (s->progress && it > 0)
    PetscCall(PetscPrintf(s->comm, "    SSN %2" PetscInt_FMT ": active %" PetscInt_FMT " (+%" PetscInt_FMT " -%" PetscInt_FMT " next), ||F|| %.3e, KSP %" PetscInt_FMT ", %.2f s\n", it, s->nact, s->nentered, s->nleft, (double)fnorm, kits, (double)(t - s->t0)));
  if (it > 0 && s->hist) {
    SgHistoryRow row;
    PetscCall(SgHistoryRowInit(&row));
    row.kind     = 's';
    row.outer    = s->outer;
    row.gamma    = s->gamma;
    row.it       = it;
    row.active   = s->nact;
    row.entered  = s->nentered;
    row.left     = s->nleft;
    row.fnorm    = fnorm;
    row.r1       = s->r1;
    row.r2       = s->r2;
    row.V        = s->V;
    row.dV       = s->dVdg;
    row.ksp_its  = kits;
    row.time     = t - s->t0;
    PetscCall(SgHistoryAdd(s->hist, &row));
  }
  PetscFunctionReturn(0);
}

/* -<prefix>snes_type, -<prefix>ksp_type and -<prefix>pc_type name a registered method: checked before SetFromOptions,
   whose own message ("Unable to find requested KSP type ...") names neither the option nor a file. */
static PetscErrorCode TryType(MPI_Comm comm, PetscInt which, const char type[], PetscErrorCode *ierr)
{
  SNES snes = NULL;
  KSP  ksp  = NULL;
  PC   pc   = NULL;

  PetscFunctionBeginUser;
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  if (which == 0) {
    *ierr = SNESCreate(comm, &snes);
    if (!*ierr) *ierr = SNESSetType(snes, type);
  } else if (which == 1) {
    *ierr = KSPCreate(comm, &ksp);
    if (!*ierr) *ierr = KSPSetType(ksp, type);
  } else {
    *ierr = PCCreate(comm, &pc);
    if (!*ierr) *ierr = PCSetType(pc, type);
  }
  PetscCall(PetscPopErrorHandler());
  PetscCall(SNESDestroy(&snes));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(PCDestroy(&pc));
  PetscFunctionReturn(0);
}

/* ierr of a solver configuration step run under PetscReturnErrorHandler (SetFromOptions, the first set-up): a
   combination that cannot work (a factorization package without that factorization, an unknown
   -pc_factor_mat_solver_type) is reported naming the options to look at, with PETSc's message. */
PetscErrorCode SgSolverConfigured(MPI_Comm comm, PetscErrorCode ierr)
{
  int   bad = ierr ? 1 : 0;
  char *msg = NULL;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, comm));
  if (ierr) PetscErrorMessage(ierr, NULL, &msg);
  PetscCheck(!bad, comm, PETSC_ERR_USER_INPUT, "the solver options do not fit together (-ksp_type, -pc_type, -pc_factor_mat_solver_type, -snes_*): %s", msg ? msg : "(see the message of another rank)");
  PetscFunctionReturn(0);
}

PetscErrorCode SgCheckSolverTypes(MPI_Comm comm, const char prefix[])
{
  const char *what[3] = {"snes_type", "ksp_type", "pc_type"}, *kind[3] = {"nonlinear solver (SNES)", "Krylov method (KSP)", "preconditioner (PC)"};

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < 3; k++) {
    char           name[64], type[256];
    PetscBool      set;
    PetscErrorCode ierr = 0;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-%s%s", prefix ? prefix : "", what[k]));
    PetscCall(PetscOptionsGetString(NULL, NULL, name, type, sizeof(type), &set));
    if (!set) continue;
    PetscCheck(type[0], comm, PETSC_ERR_USER_INPUT, "%s is given without a value", name);
    PetscCall(TryType(comm, k, type, &ierr));
    PetscCheck(!ierr, comm, PETSC_ERR_USER_INPUT, "%s '%s': no such %s in this PETSc (see -help for the list)", name, type, kind[k]);
  }
  {
    char      name[64], type[256];
    PetscBool set, found = PETSC_FALSE, foundm = PETSC_FALSE;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-%spc_factor_mat_solver_type", prefix ? prefix : ""));
    PetscCall(PetscOptionsGetString(NULL, NULL, name, type, sizeof(type), &set));
    if (set) {
      PetscCheck(type[0], comm, PETSC_ERR_USER_INPUT, "%s is given without a value", name);
      /* a package registered for any matrix type and factorization (which combination fits is decided at set-up) */
      for (PetscInt f = MAT_FACTOR_LU; f <= MAT_FACTOR_QR && !found; f++) PetscCall(MatSolverTypeGet(type, MATSEQAIJ, (MatFactorType)f, &found, &foundm, NULL));
      PetscCheck(found, comm, PETSC_ERR_USER_INPUT, "%s '%s': no such factorization package in this PETSc (e.g. mumps, petsc, superlu, superlu_dist)", name, type);
    }
  }
  PetscFunctionReturn(0);
}

/* The linear solver of every step of a controller: a KSP with the options under the prefix on J, a working copy of K
   (with the rigid-body near null space if asked for); the types are checked first, and a combination that fails in
   KSPSetFromOptions is reported naming the solver options. */
PetscErrorCode SgLinearSolverCreate(SgElasticity el, const char prefix[], KSP *ksp, Mat *J)
{
  MPI_Comm       comm;
  Mat            K;
  MatNullSpace   nsp;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetComm(el, &comm));
  PetscCall(SgElasticityGetOperators(el, &K, NULL));
  PetscCall(SgElasticityGetNearNullSpace(el, &nsp));
  PetscCall(MatDuplicate(K, MAT_COPY_VALUES, J));
  if (nsp) PetscCall(MatSetNearNullSpace(*J, nsp));
  PetscCall(MatSetOption(*J, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  PetscCall(KSPCreate(comm, ksp));
  PetscCall(KSPSetOptionsPrefix(*ksp, prefix));
  PetscCall(KSPSetOperators(*ksp, *J, *J));
  PetscCall(SgCheckSolverTypes(comm, prefix));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = KSPSetFromOptions(*ksp);
  PetscCall(PetscPopErrorHandler());
  PetscCall(SgSolverConfigured(comm, ierr));
  PetscFunctionReturn(0);
}

/* The elasticity solve without contact, K y = b, with the controller's linear solver (so a factorization's symbolic
   phase is shared with the later steps); the times of the preconditioner set-up and of the solve. */
PetscErrorCode SgLinearSolveUnconstrained(SgElasticity el, KSP ksp, Mat J, Vec y, PetscInt *its, KSPConvergedReason *kr, PetscLogDouble *t_setup, PetscLogDouble *t_solve)
{
  MPI_Comm       comm;
  Mat            K;
  Vec            b;
  PetscErrorCode ierr;
  PetscLogDouble t0, t1, t2;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetComm(el, &comm));
  PetscCall(SgElasticityGetOperators(el, &K, &b));
  PetscCall(PetscLogEventBegin(SG_LinearSolve, 0, 0, 0, 0));
  PetscCall(MatCopy(K, J, SAME_NONZERO_PATTERN));
  {
    Mat Kf = NULL, Pf = NULL; /* the SSN's contact frames (FrameSetUp): the KSP solves with Q^T K Q */
    PetscCall(PetscObjectQuery((PetscObject)ksp, "SgFrameStiffness", (PetscObject *)&Kf));
    PetscCall(PetscObjectQuery((PetscObject)ksp, "SgFramePmat", (PetscObject *)&Pf));
    if (Pf) PetscCall(MatCopy(Kf, Pf, SAME_NONZERO_PATTERN));
    PetscCall(KSPSetOperators(ksp, Pf ? Pf : J, Pf ? Pf : J));
  }
  PetscCall(PetscTime(&t0));
  /* the first set-up of the linear solver is where some configurations that cannot work fail */
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = KSPSetUp(ksp);
  PetscCall(PetscPopErrorHandler());
  PetscCall(SgSolverConfigured(comm, ierr));
  PetscCall(PetscTime(&t1));
  PetscCall(KSPSolve(ksp, b, y));
  PetscCall(PetscTime(&t2));
  if (t_setup) *t_setup = t1 - t0;
  if (t_solve) *t_solve = t2 - t1;
  PetscCall(KSPGetIterationNumber(ksp, its));
  PetscCall(KSPGetConvergedReason(ksp, kr));
  PetscCall(PetscLogEventEnd(SG_LinearSolve, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* -snes_converged_reason for the SSN: our reasons (SgSSNReasons), which PETSc's closed list of SNES reasons cannot
   name: a settled active set would print as CONVERGED_FNORM_ABS and cycling as DIVERGED_LOCAL_MIN. The option is
   taken over at set-up (read into the SSN's viewer and removed), so PETSc does not print a second, misleading line;
   a SNES type of our own would have had to copy newtonls for the same effect. */
/* Our reason for a SNES reason: a failure our convergence test did not name is PETSc's (the iteration limit, ...). */
static SgSSNReason SSNReason(SgSSN s, SNESConvergedReason r)
{
  if (r >= 0 || s->reason != SG_SSN_ITERATING) return s->reason;
  return r == SNES_DIVERGED_MAX_IT ? SG_SSN_MAX_IT : (r == SNES_DIVERGED_LINEAR_SOLVE ? SG_SSN_LINEAR_SOLVE : (r == SNES_DIVERGED_FNORM_NAN ? SG_SSN_NAN : SG_SSN_SNES_FAILED));
}

static PetscErrorCode ReasonView(SNES snes, void *ctx)
{
  SgSSN               s = (SgSSN)ctx;
  SNESConvergedReason r;
  PetscInt            its, tab;
  PetscBool           isascii;

  PetscFunctionBeginUser;
  if (!s->reason_viewer) PetscFunctionReturn(0);
  PetscCall(PetscObjectGetTabLevel((PetscObject)snes, &tab));
  PetscCall(PetscObjectTypeCompare((PetscObject)s->reason_viewer, PETSCVIEWERASCII, &isascii));
  if (!isascii) PetscFunctionReturn(0);
  PetscCall(SNESGetConvergedReason(snes, &r));
  PetscCall(SNESGetIterationNumber(snes, &its));
  PetscCall(PetscViewerPushFormat(s->reason_viewer, s->reason_format));
  PetscCall(PetscViewerASCIIAddTab(s->reason_viewer, tab));
  if (r > 0) {
    if (s->reason_format != PETSC_VIEWER_FAILED) PetscCall(PetscViewerASCIIPrintf(s->reason_viewer, "SSN solve of (P_gamma) at gamma %g converged due to %s iterations %" PetscInt_FMT "\n", (double)s->gamma, SgSSNReasons[s->reason], its));
  } else PetscCall(PetscViewerASCIIPrintf(s->reason_viewer, "SSN solve of (P_gamma) at gamma %g did not converge due to %s (SNES %s) iterations %" PetscInt_FMT "\n", (double)s->gamma, SgSSNReasons[SSNReason(s, r)], SNESConvergedReasons[r], its));
  PetscCall(PetscViewerASCIISubtractTab(s->reason_viewer, tab));
  PetscCall(PetscViewerPopFormat(s->reason_viewer));
  PetscFunctionReturn(0);
}

/* The SSN's options, their defaults in s, condense, tmg and frame (also listed by SgSSNPrintHelp) */
static PetscErrorCode SSNOptions(PetscOptionItems *PetscOptionsObject, SgSSN s, PetscBool *condense, PetscBool *tmg, PetscBool *frame)
{
  PetscFunctionBeginUser;
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-ssn_monitor", "Print active-set size, changes, residuals and KSP iterations per SSN iteration", &s->monitor, NULL));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-ssn_condense", "Condense the linear solves onto the contact dofs: factor K once (MUMPS, with its Schur complement), then only a dense matrix per SSN step (one rank)", condense, NULL));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-ssn_pc_truncated_mg", "Precondition with multigrid on the interpolations of the AMG of the first solve (-pc_type hypre or gamg), the finest one truncated at the active normal dofs, coarse operators by Galerkin products: no new AMG setup per active set", tmg, NULL));
  PetscCall(SgOptionsIntValue(PetscOptionsObject, "-ssn_coulomb_fp_max_it", "Coulomb: when the Newton iteration on the coupled law fails, at most this many steps of a fixed point on the Tresca bound s = F lam_N (0: none)", &s->fp_max_it, NULL));
  PetscCall(SgOptionsIntValue(PetscOptionsObject, "-ssn_coulomb_fp_m", "Coulomb: the number of past steps in the Anderson acceleration of that fixed point", &s->fp_m, NULL));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-ssn_coulomb_fp_omega", "Coulomb: the damping of that fixed point's steps (0 < omega <= 1)", &s->fp_omega, NULL));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-ssn_coulomb_fp_rtol", "Coulomb: that fixed point ends when |F lam_N - s| <= rtol max F lam_N", &s->fp_rtol, NULL));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-ssn_frame", "Solve the linear systems in each contact vertex's frame (n, t1, t2) where its normal is not a coordinate axis (curved or tilted contact): the contact term becomes a diagonal entry, which AMG, the truncated multigrid, condensation and the bound-constrained solvers need", frame, NULL));
  PetscCall(SgOptionsIntValue(PetscOptionsObject, "-ssn_pc_reuse_its", "Within one (P_gamma), keep the previous step's preconditioner while the last linear solve took at most this many iterations (0: rebuild every step)", &s->pc_reuse_its, NULL));
  PetscFunctionReturn(0);
}

/* -help without a problem (bin/signorini -help): the SSN's options and their defaults, as SgSSNCreate reads them */
PetscErrorCode SgSSNPrintHelp(MPI_Comm comm, const char prefix[])
{
  struct _n_SgSSN s;
  PetscBool       help, condense = PETSC_FALSE, tmg = PETSC_FALSE, frame = PETSC_TRUE;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  if (!help) PetscFunctionReturn(0);
  PetscCall(PetscMemzero(&s, sizeof(s)));
  s.fp_max_it = 50;
  s.fp_omega  = 1;
  s.fp_m      = 8;
  s.fp_rtol   = 1e-13;
  PetscOptionsBegin(comm, prefix, "Semismooth Newton (active set) solver", NULL);
  PetscCall(SSNOptions(PetscOptionsObject, &s, &condense, &tmg, &frame));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

/* -ssn_frame: the Jacobians are assembled in the contact frames into Pf (a copy of Q^T K Q) and the KSP solves with
   it in the frames (SgFrameAttachKSP); the elasticity solve without contact takes Q^T K Q (SgLinearSolveUnconstrained
   finds both on the KSP) */
static PetscErrorCode FrameSetUp(SgSSN s, KSP ksp)
{
  MatNullSpace nsp;

  PetscFunctionBeginUser;
  PetscCall(SgFrameGetStiffness(s->frame, &s->Klin));
  PetscCall(MatDuplicate(s->Klin, MAT_COPY_VALUES, &s->Pf));
  PetscCall(MatGetNearNullSpace(s->Klin, &nsp));
  if (nsp) PetscCall(MatSetNearNullSpace(s->Pf, nsp));
  PetscCall(MatSetOption(s->Pf, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  if (s->cv.coupled) {
    PetscCall(MatSetOption(s->Pf, MAT_SPD, PETSC_FALSE));
    PetscCall(MatSetOption(s->Pf, MAT_SYMMETRIC, PETSC_FALSE));
  }
  PetscCall(SNESSetJacobian(s->snes, s->Pf, s->Pf, Jacobian, s));
  PetscCall(SgFrameAttachKSP(s->frame, ksp));
  PetscCall(PetscObjectCompose((PetscObject)ksp, "SgFrameStiffness", (PetscObject)s->Klin));
  PetscCall(PetscObjectCompose((PetscObject)ksp, "SgFramePmat", (PetscObject)s->Pf));
  PetscFunctionReturn(0);
}

/* x (a vector of the SSN's KSP during its solve, e.g. KSPBuildSolution's) in the original coordinates, in place */
PetscErrorCode SgSSNKSPVectorToGlobal(SgSSN s, Vec x)
{
  PetscFunctionBeginUser;
  if (s->frame) PetscCall(SgFrameToGlobal(s->frame, x));
  PetscFunctionReturn(0);
}

/* The SSN solver of (P_gamma) on the contact boundary c, its SNES (options under the prefix) solving with the linear
   solver ksp on the working matrix J (SgLinearSolverCreate). */
PetscErrorCode SgSSNCreate(SgElasticity p, SgContact c, const char prefix[], KSP ksp, Mat J, SgSSN *ssn)
{
  SgSSN          s;
  SNESLineSearch ls;
  PetscBool      condense = PETSC_FALSE, tmg = PETSC_FALSE, frame = PETSC_TRUE;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&s));
  s->prob  = p;
  s->c     = c;
  s->gamma = 1;
  PetscCall(SgElasticityGetComm(p, &s->comm));
  PetscCall(SgElasticityGetDimension(p, &s->dim));
  PetscCall(SgElasticityGetMesh(p, &s->mesh));
  PetscCall(SgElasticityGetOperators(p, &s->K, &s->b));
  PetscCall(SgElasticityGetMass(p, &s->mass));
  s->prob = p;
  PetscCall(SgSSNUpdateLoad(s));
  if (c) PetscCall(SgContactGetView(c, &s->cv));
  PetscCall(PetscTime(&s->t0));
  PetscCall(PetscObjectReference((PetscObject)J));
  s->J = J;
  if (s->cv.coupled) { /* the coupling t n^T of the slip set */
    PetscCall(MatSetOption(J, MAT_SPD, PETSC_FALSE));
    PetscCall(MatSetOption(J, MAT_SYMMETRIC, PETSC_FALSE));
  }
  PetscCall(VecDuplicate(s->b, &s->r));
  PetscCall(PetscMalloc5(s->cv.n, &s->g, s->cv.n, &s->m, s->cv.n, &s->act, s->cv.n, &s->actjac, s->cv.n, &s->lamhat));
  for (PetscInt i = 0; i < s->cv.n; i++) s->lamhat[i] = 0;
  if (s->cv.friction) {
    PetscCall(PetscCalloc2(s->cv.n * s->dim, &s->lamhatT, s->cv.n * s->dim, &s->mT));
    PetscCall(PetscCalloc4(s->cv.n, &s->fst, s->cv.n, &s->fstjac, s->cv.n * s->dim, &s->tjac, s->cv.n, &s->fforce));
  }
  PetscCall(SNESCreate(s->comm, &s->snes));
  PetscCall(SNESSetOptionsPrefix(s->snes, prefix));
  PetscCall(SNESSetKSP(s->snes, ksp));
  PetscCall(SNESSetType(s->snes, SNESNEWTONLS));
  PetscCall(SNESGetLineSearch(s->snes, &ls));
  PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHBASIC));
  PetscCall(SNESSetFunction(s->snes, s->r, Residual, s));
  PetscCall(SNESSetJacobian(s->snes, s->J, s->J, Jacobian, s));
  PetscCall(SNESSetConvergenceTest(s->snes, Converged, s, NULL));
  if (s->cv.friction) PetscCall(SNESLineSearchSetPreCheck(ls, PreCheck, s));
  PetscCall(SNESMonitorSet(s->snes, Monitor, s, NULL));
  PetscCall(SNESSetTolerances(s->snes, PETSC_DEFAULT, 1e-10, PETSC_DEFAULT, 100, PETSC_DEFAULT));
  s->fp_max_it = 50;
  s->fp_omega  = 1;
  s->fp_m      = 8;
  s->fp_rtol   = 1e-13;
  PetscOptionsBegin(s->comm, prefix, "Semismooth Newton (active set) solver", NULL);
  PetscCall(SSNOptions(PetscOptionsObject, s, &condense, &tmg, &frame));
  PetscOptionsEnd();
  PetscCall(SgCheckSolverTypes(s->comm, prefix));
  {
    PetscErrorCode ierr;
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = SNESSetFromOptions(s->snes);
    PetscCall(PetscPopErrorHandler());
    PetscCall(SgSolverConfigured(s->comm, ierr));
  }
  PetscCheck(s->fp_max_it >= 0, s->comm, PETSC_ERR_USER_INPUT, "-ssn_coulomb_fp_max_it: must be >= 0, got %" PetscInt_FMT, s->fp_max_it);
  PetscCheck(s->fp_m >= 1 && s->fp_m <= 100, s->comm, PETSC_ERR_USER_INPUT, "-ssn_coulomb_fp_m: must be in [1, 100], got %" PetscInt_FMT, s->fp_m);
  PetscCheck(s->fp_omega > 0 && s->fp_omega <= 1, s->comm, PETSC_ERR_USER_INPUT, "-ssn_coulomb_fp_omega: must be in (0, 1], got %g", (double)s->fp_omega);
  PetscCheck(PetscIsNormalReal(s->fp_rtol) && s->fp_rtol > 0, s->comm, PETSC_ERR_USER_INPUT, "-ssn_coulomb_fp_rtol: must be positive and finite, got %g", (double)s->fp_rtol);
  PetscCheck(!(s->cv.friction && condense), s->comm, PETSC_ERR_SUP, "-ssn_condense is not built for friction (-friction_type %s) yet: leave it out (the default solver does without it)", SgLawName(s->cv.law));
  PetscCheck(!(s->cv.friction && tmg), s->comm, PETSC_ERR_SUP, "-ssn_pc_truncated_mg is not built for friction (-friction_type %s) yet: leave it out (the default solver does without it)", SgLawName(s->cv.law));
  s->Klin = s->K;
  if (frame && c) PetscCall(SgFrameCreate(p, c, &s->frame));
  if (s->frame) PetscCall(FrameSetUp(s, ksp));
  if (condense) PetscCall(SgCondenseCreate(s, &s->cond));
  PetscCheck(!(tmg && condense), s->comm, PETSC_ERR_USER_INPUT, "-ssn_pc_truncated_mg is for iterative linear solves, not -ssn_condense");
  if (tmg) PetscCall(SgTMGCreate(s, ksp, &s->tmg));
  {
    char      name[256];
    PetscBool flg;
    PetscCall(PetscOptionsGetViewer(s->comm, NULL, prefix, "-snes_converged_reason", &s->reason_viewer, &s->reason_format, &flg));
    if (flg) {
      PetscCall(SgOptionsName(prefix, "-snes_converged_reason", name, sizeof(name)));
      PetscCall(PetscOptionsClearValue(NULL, name));
    }
    PetscCall(SNESConvergedReasonViewSet(s->snes, ReasonView, s, NULL));
  }
  {
    PetscBool preonly;
    PetscCall(PetscObjectTypeCompare((PetscObject)ksp, KSPPREONLY, &preonly));
    /* exact (direct) solves land on the auxiliary problem's solution: a settled active set is convergence */
    s->residual_test = (PetscBool)(!preonly || s->cv.friction); /* slip: Newton steps converge, they do not land */
    s->iterative     = (PetscBool)!preonly;
    PetscCheck(s->pc_reuse_its >= 0, s->comm, PETSC_ERR_USER_INPUT, "-ssn_pc_reuse_its: must be >= 0, got %" PetscInt_FMT, s->pc_reuse_its);
    PetscCheck(!(s->pc_reuse_its > 0 && preonly), s->comm, PETSC_ERR_USER_INPUT, "-ssn_pc_reuse_its %" PetscInt_FMT " needs an iterative -ksp_type (e.g. cg): with preonly a kept factorization gives wrong Newton steps", s->pc_reuse_its);
  }
  *ssn = s;
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNDestroy(SgSSN *ssn)
{
  SgSSN s = *ssn;

  PetscFunctionBeginUser;
  if (!s) PetscFunctionReturn(0);
  if (s->frame) { /* the KSP is the controller's: it forgets the frames */
    KSP ksp;
    PetscCall(SNESGetKSP(s->snes, &ksp));
    PetscCall(SgFrameDetachKSP(s->frame, ksp));
    PetscCall(PetscObjectCompose((PetscObject)ksp, "SgFrameStiffness", NULL));
    PetscCall(PetscObjectCompose((PetscObject)ksp, "SgFramePmat", NULL));
  }
  PetscCall(SNESDestroy(&s->snes));
  PetscCall(PetscViewerDestroy(&s->reason_viewer));
  PetscCall(SgCondenseDestroy(&s->cond));
  PetscCall(SgTMGDestroy(&s->tmg));
  PetscCall(MatDestroy(&s->J));
  PetscCall(MatDestroy(&s->Pf));
  PetscCall(SgFrameDestroy(&s->frame));
  PetscCall(VecDestroy(&s->r));
  PetscCall(PetscFree5(s->g, s->m, s->act, s->actjac, s->lamhat));
  PetscCall(PetscFree(s->gy));
  PetscCall(PetscFree2(s->lamhatT, s->mT));
  PetscCall(PetscFree4(s->fst, s->fstjac, s->tjac, s->fforce));
  PetscCall(PetscFree(s->gfixw));
  PetscCall(KSPDestroy(&s->kspd));
  PetscCall(VecDestroy(&s->y0));
  if (s->wpre) PetscCall(VecDestroyVecs(2, &s->wpre));
  PetscCall(PetscFree(s->hash));
  PetscCall(PetscFree(*ssn));
  PetscFunctionReturn(0);
}

/* The load scales and the energy shift read again after the problem's load factor changed (load stepping; b and the
   gaps are shared, not copied). A step without load (b = 0: unloaded to zero) keeps the scales of the full load, so
   that the stopping tests measure against the problem, not against 0. */
PetscErrorCode SgSSNUpdateLoad(SgSSN s)
{
  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetScales(s->prob, &s->Knorm, &s->bnorm, &s->bnorm_inf));
  if (!(s->bnorm > 0)) PetscCall(SgElasticityGetFullLoadScales(s->prob, &s->bnorm, &s->bnorm_inf, NULL));
  { /* the displacement data: the largest Dirichlet value now and at load factor 1 (the round-off floors' scale) */
    PetscReal ucur, ufull;
    PetscCall(SgElasticityGetDataScales(s->prob, &ucur, &ufull, NULL, NULL, NULL));
    s->udata = PetscMax(ucur, ufull);
  }
  PetscCall(SgElasticityGetEnergyShift(s->prob, &s->energy_shift));
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNGetSNES(SgSSN s, SNES *snes)
{
  PetscFunctionBeginUser;
  *snes = s->snes;
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNGetShift(SgSSN s, PetscReal **lamhat)
{
  PetscFunctionBeginUser;
  *lamhat = s->lamhat;
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNGetMultiplier(SgSSN s, const PetscReal **m)
{
  PetscFunctionBeginUser;
  *m = s->m;
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNGetPathValues(SgSSN s, PetscReal *gamma, PetscReal *V, PetscReal *dVdg)
{
  PetscFunctionBeginUser;
  if (gamma) *gamma = s->gamma;
  if (V) *V = s->V;
  if (dVdg) *dVdg = s->dVdg;
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNGetReason(SgSSN s, SgSSNReason *reason)
{
  PetscFunctionBeginUser;
  *reason = s->reason;
  PetscFunctionReturn(0);
}

/* tau > 0: also stop in the neighbourhood ||(r1, r2)|| <= tau / sqrt(gamma) of the path (IPF); 0: solve exactly */
PetscErrorCode SgSSNSetNeighbourhood(SgSSN s, PetscReal tau)
{
  PetscFunctionBeginUser;
  s->nbhd_tau = tau;
  PetscFunctionReturn(0);
}

/* the history that receives a row per SSN iteration, and its time origin */
PetscErrorCode SgSSNSetHistory(SgSSN s, SgHistory hist, PetscLogDouble t0)
{
  PetscFunctionBeginUser;
  s->hist = hist;
  s->t0   = t0;
  PetscFunctionReturn(0);
}

/* a short progress line per SSN iteration (for controllers whose outer steps are long); -ssn_monitor prints more */
PetscErrorCode SgSSNSetProgress(SgSSN s, PetscBool progress)
{
  PetscFunctionBeginUser;
  s->progress = progress;
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNGetMonitor(SgSSN s, PetscBool *monitor)
{
  PetscFunctionBeginUser;
  *monitor = s->monitor;
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNSetStopTest(SgSSN s, SgSSNStopTest test, void *ctx)
{
  PetscFunctionBeginUser;
  s->stop_test = test;
  s->stop_ctx  = ctx;
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNSetReason(SgSSN s, SgSSNReason reason)
{
  PetscFunctionBeginUser;
  s->reason = reason;
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNSetKeepPCOnSameSet(SgSSN s, PetscBool flg)
{
  PetscFunctionBeginUser;
  s->pc_same_set = flg;
  PetscFunctionReturn(0);
}

/* The contact vertices whose state at y (active: lamhat + gamma g(y) > 0, the rule of the Jacobian) differs from the
   active set of the last Jacobian, summed over the ranks: whether a Newton iterate y would change the set. */
PetscErrorCode SgSSNCountSetChanges(SgSSN s, Vec y, PetscInt *changed)
{
  const PetscScalar *ya;

  PetscFunctionBeginUser;
  if (!s->gy) PetscCall(PetscMalloc1(s->cv.n, &s->gy));
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(SgContactGap(s->c, ya, s->gy));
  PetscCall(VecRestoreArrayRead(y, &ya));
  *changed = 0;
  for (PetscInt i = 0; i < s->cv.n; i++) *changed += ((s->lamhat[i] + s->gamma * s->gy[i] > 0) != (s->actjac[i] != 0));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, changed, 1, MPIU_INT, MPI_SUM, s->comm));
  PetscFunctionReturn(0);
}

/* rho_F = int max(0, g), rho_C = int_I max(0, g) + int_A -min(0, g) with A, I the active and inactive sets of the
   iterate (the sets of the last Newton step): the measures of the inexact path-following rule (15). */
PetscErrorCode SgSSNPathMeasures(SgSSN s, PetscReal *rhoF, PetscReal *rhoC)
{
  const SgContactView *c    = &s->cv;
  PetscReal            r[2] = {0, 0};

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < c->n; i++) {
    const PetscBool act = (PetscBool)(s->havejac ? s->actjac[i] : s->act[i]);
    r[0] += c->w[i] * PetscMax(0, s->g[i]);
    r[1] += c->w[i] * (act ? -PetscMin(0, s->g[i]) : PetscMax(0, s->g[i]));
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, r, 2, MPIU_REAL, MPI_SUM, s->comm));
  *rhoF = r[0];
  *rhoC = r[1];
  PetscFunctionReturn(0);
}


/* one more SNES solve from y with a fresh Jacobian and state (the Coulomb fixed point's): its iterations added to *its
   and *kits, its own SSN iterations in *it */
static PetscErrorCode SolveAgain(SgSSN s, Vec y, SNESConvergedReason *reason, PetscInt *its, PetscInt *kits, PetscInt *it)
{
  PetscInt kit;

  PetscFunctionBeginUser;
  s->havejac  = PETSC_FALSE;
  s->nhash    = 0;
  s->stagnant = PETSC_FALSE;
  s->reason   = SG_SSN_ITERATING;
  PetscCall(SNESSolve(s->snes, NULL, y));
  PetscCall(SNESGetIterationNumber(s->snes, it));
  PetscCall(SNESGetLinearSolveIterations(s->snes, &kit));
  PetscCall(SNESGetConvergedReason(s->snes, reason));
  s->reason = SSNReason(s, *reason);
  *its += *it;
  *kits += kit;
  PetscFunctionReturn(0);
}
/* Coulomb when the Newton iteration on the coupled law failed: a fixed point on the Tresca bound. With the bound
   s_i = F lam_N,i frozen the friction law is Tresca's (a convex problem: no coupling F gamma t n^T in the Jacobian, and
   the SSN converges from anywhere); its solution y(s) gives new normal multipliers, G(s) = F max(0, lamhat + gamma
   g(y(s))), and a fixed point s = G(s) solves the Coulomb (P_gamma). G is continuous but, for a large F, not a
   contraction (more friction presses harder: an eigenvalue of G' above 1, which no relaxation damps), so the fixed
   point is found by Anderson acceleration (a secant method on G(s) - s over the last fp_m steps). */
static PetscErrorCode CoulombFixedPoint(SgSSN s, Vec y, PetscInt *its, PetscInt *kits, SNESConvergedReason *reason)
{
  const SgContactView *c = &s->cv;
  const PetscInt       n = c->n, m = s->fp_m;
  PetscReal            beta = s->fp_omega, *x, *f, *dX, *dF, *Mat_, *rhs, *gam;
  PetscInt             k, nh = 0;
  const PetscScalar   *ya;

  PetscFunctionBeginUser;
  if (!s->gfixw) PetscCall(PetscMalloc1(n, &s->gfixw));
  PetscCall(PetscMalloc7(n, &x, n, &f, n * m, &dX, n * m, &dF, m * m, &Mat_, m, &rhs, m, &gam));
  PetscCall(VecCopy(s->y0, y));
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(SgContactGap(s->c, ya, s->g));
  PetscCall(VecRestoreArrayRead(y, &ya));
  for (PetscInt i = 0; i < n; i++) SgContactLawBound(c->law, i, s->lamhat[i] + s->gamma * s->g[i], &s->gfixw[i], NULL);
  for (k = 0; k < s->fp_max_it; k++) {
    PetscInt  it2, jc;
    PetscReal d = 0, mx = 0;
    s->gfix = s->gfixw;
    PetscCall(SolveAgain(s, y, reason, its, kits, &it2));
    s->gfix = NULL;
    if (*reason <= 0) break;
    PetscCall(VecGetArrayRead(y, &ya));
    PetscCall(SgContactGap(s->c, ya, s->g));
    PetscCall(VecRestoreArrayRead(y, &ya));
    /* the residual f = G(s) - s; the history columns are differences to the previous step */
    jc = k > 0 ? (k - 1) % m : 0;
    for (PetscInt i = 0; i < n; i++) {
      PetscReal gi;
      SgContactLawBound(c->law, i, s->lamhat[i] + s->gamma * s->g[i], &gi, NULL);
      const PetscReal fi = gi - s->gfixw[i];
      d  = PetscMax(d, PetscAbsReal(fi));
      mx = PetscMax(mx, gi);
      if (k > 0) {
        dX[jc * n + i] = s->gfixw[i] - x[i];
        dF[jc * n + i] = fi - f[i];
      }
      x[i] = s->gfixw[i];
      f[i] = fi;
    }
    if (k > 0) nh = PetscMin(nh + 1, m);
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &d, 1, MPIU_REAL, MPI_MAX, s->comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &mx, 1, MPIU_REAL, MPI_MAX, s->comm));
    if (s->monitor) PetscCall(PetscPrintf(s->comm, "  Coulomb fixed point %" PetscInt_FMT " at gamma %g: %" PetscInt_FMT " SSN, |G(s) - s| %.3e of %.3e\n", k, (double)s->gamma, it2, (double)d, (double)mx));
    if (d <= s->fp_rtol * mx) break;
    /* gam = argmin |f - dF gam| (normal equations, a small ridge), s <- s + beta f - (dX + beta dF) gam, s >= 0 */
    for (PetscInt a = 0; a < nh; a++) {
      rhs[a] = 0;
      for (PetscInt i = 0; i < n; i++) rhs[a] += dF[a * n + i] * f[i];
      for (PetscInt b = 0; b < nh; b++) {
        Mat_[a * m + b] = 0;
        for (PetscInt i = 0; i < n; i++) Mat_[a * m + b] += dF[a * n + i] * dF[b * n + i];
      }
    }
    if (nh) {
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, rhs, (PetscMPIInt)nh, MPIU_REAL, MPI_SUM, s->comm));
      for (PetscInt a = 0; a < nh; a++) PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &Mat_[a * m], (PetscMPIInt)nh, MPIU_REAL, MPI_SUM, s->comm));
      {
        PetscReal tr = 0;
        for (PetscInt a = 0; a < nh; a++) tr += Mat_[a * m + a];
        for (PetscInt a = 0; a < nh; a++) Mat_[a * m + a] += 1e-12 * tr + PETSC_SMALL * PETSC_SMALL;
      }
      /* Gaussian elimination, symmetric positive definite: no pivoting */
      for (PetscInt a = 0; a < nh; a++) {
        for (PetscInt b = a + 1; b < nh; b++) {
          const PetscReal l = Mat_[b * m + a] / Mat_[a * m + a];
          for (PetscInt q = a; q < nh; q++) Mat_[b * m + q] -= l * Mat_[a * m + q];
          rhs[b] -= l * rhs[a];
        }
      }
      for (PetscInt a = nh - 1; a >= 0; a--) {
        PetscReal r = rhs[a];
        for (PetscInt q = a + 1; q < nh; q++) r -= Mat_[a * m + q] * gam[q];
        gam[a] = r / Mat_[a * m + a];
      }
    }
    for (PetscInt i = 0; i < n; i++) {
      PetscReal v = x[i] + beta * f[i];
      for (PetscInt a = 0; a < nh; a++) v -= (dX[a * n + i] + beta * dF[a * n + i]) * gam[a];
      s->gfixw[i] = PetscMax(0, v);
    }
  }
  PetscCall(PetscFree7(x, f, dX, dF, Mat_, rhs, gam));
  if (*reason > 0) { /* the coupled law from the fixed point */
    PetscInt it2;
    PetscCall(SolveAgain(s, y, reason, its, kits, &it2));
    if (s->monitor) PetscCall(PetscPrintf(s->comm, "  Coulomb after %" PetscInt_FMT " fixed-point steps at gamma %g: %s after %" PetscInt_FMT " SSN\n", k, (double)s->gamma, SgSSNReasons[s->reason], it2));
  }
  PetscCall(PetscPrintf(s->comm, "  SSN at gamma %g with Coulomb friction: the Newton iteration on the coupled law failed; solved again by a fixed point on the Tresca bound s = F lam_N (%" PetscInt_FMT " steps): %s\n", (double)s->gamma, k, *reason > 0 ? "converged" : SgSSNReasons[s->reason]));
  PetscFunctionReturn(0);
}

/* Solve (P_gamma) with the current shift c->lamhat from the initial guess y (overwritten). */
PetscErrorCode SgSSNSolve(SgSSN s, PetscReal gamma, PetscInt outer, Vec y, PetscInt *its, PetscInt *kits, SNESConvergedReason *reason)
{
  PetscFunctionBeginUser;
  s->gamma   = gamma;
  s->outer   = outer;
  s->havejac = PETSC_FALSE;
  s->dmax    = 0;
  for (PetscInt i = 0; i < s->cv.n; i++) s->dmax = PetscMax(s->dmax, PetscAbsReal(s->cv.d[i]));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &s->dmax, 1, MPIU_REAL, MPI_MAX, s->comm));
  s->nhash   = 0;
  s->stagnant = PETSC_FALSE;
  if (s->cv.friction && (s->iterative || s->cv.coupled)) {
    if (!s->y0) PetscCall(VecDuplicate(y, &s->y0));
    PetscCall(VecCopy(y, s->y0));
  }
  if (s->gamma_direct > 0 && gamma >= s->gamma_direct) { /* the iterative solver failed at a smaller gamma already */
    *its = *kits = 0;
    s->reason = SG_SSN_LINEAR_SOLVE;
  } else {
    PetscCall(SNESSolve(s->snes, NULL, y));
    PetscCall(SNESGetIterationNumber(s->snes, its));
    PetscCall(SNESGetLinearSolveIterations(s->snes, kits));
    PetscCall(SNESGetConvergedReason(s->snes, reason));
    s->reason = SSNReason(s, *reason);
  }
  if (s->cv.friction && s->iterative && (s->reason == SG_SSN_LINEAR_SOLVE || s->reason == SG_SSN_MAX_IT)) {
    /* friction with an iterative linear solver: at a large gamma the slip blocks (Coulomb: the coupling F gamma t n^T,
       far from symmetric) defeat Krylov solvers with an AMG built for elasticity, which fail or whose inexact steps
       keep the SSN from converging (GMRES + BoomerAMG on the sliding block at gamma ~ 1e12): this (P_gamma) is solved
       again from the same start with sparse LU (MUMPS), and so are those at larger gammas; said on the output */
    KSP      ksp;
    PetscInt its2, kits2;
    if (!s->kspd) {
      PC pc;
      PetscCall(KSPCreate(s->comm, &s->kspd));
      PetscCall(KSPSetType(s->kspd, KSPPREONLY));
      PetscCall(KSPGetPC(s->kspd, &pc));
      PetscCall(PCSetType(pc, PCLU));
      PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
      if (s->frame) PetscCall(SgFrameAttachKSP(s->frame, s->kspd));
    }
    if (!(s->gamma_direct > 0 && gamma >= s->gamma_direct)) {
      PetscCall(PetscPrintf(s->comm, "  SSN at gamma %g: %s with the iterative linear solver after %" PetscInt_FMT " iterations; solved again with sparse LU (MUMPS), and so from here on at gamma >= %g\n", (double)gamma, SgSSNReasons[s->reason], *its, (double)gamma));
      s->gamma_direct = gamma;
    }
    PetscCall(SNESGetKSP(s->snes, &ksp));
    PetscCall(PetscObjectReference((PetscObject)ksp));
    PetscCall(SNESSetKSP(s->snes, s->kspd));
    PetscCall(VecCopy(s->y0, y));
    s->havejac  = PETSC_FALSE;
    s->nhash    = 0;
    s->stagnant = PETSC_FALSE;
    s->reason   = SG_SSN_ITERATING;
    PetscCall(SNESSolve(s->snes, NULL, y));
    PetscCall(SNESGetIterationNumber(s->snes, &its2));
    PetscCall(SNESGetLinearSolveIterations(s->snes, &kits2));
    PetscCall(SNESGetConvergedReason(s->snes, reason));
    PetscCall(SNESSetKSP(s->snes, ksp));
    PetscCall(KSPDestroy(&ksp));
    s->reason = SSNReason(s, *reason);
    *its += its2;
    *kits += kits2;
  }
  /* a bound from lam_N (Coulomb): a failure of the coupled Newton iteration (cycling states) gets the fixed point on the frozen bound */
  if (s->cv.coupled && s->fp_max_it > 0 && (s->reason == SG_SSN_MAX_IT || s->reason == SG_SSN_CYCLING || s->reason == SG_SSN_SNES_FAILED)) PetscCall(CoulombFixedPoint(s, y, its, kits, reason));
  /* the basic line search evaluated F at the returned iterate: g, m and the active set describe it */
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
  const SgContactView *c   = &s->cv;
  Vec                F;
  PetscScalar       *fa;
  const PetscScalar *ya;
  PetscReal          floor = 0, nrm[2], *g, *m;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(c->n, &g, c->n, &m));
  PetscCall(VecDuplicate(y, &F));
  PetscCall(MatMult(s->K, y, F));
  PetscCall(VecAXPY(F, -1.0, s->b));
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(SgContactGap(s->c, ya, g));
  PetscCall(VecRestoreArrayRead(y, &ya));
  for (PetscInt i = 0; i < c->n; i++) {
    const PetscReal z = s->lamhat[i] + s->gamma * g[i];
    m[i]              = PetscMax(0, z);
    if (z > 0) floor = PetscMax(floor, s->gamma * c->w[i] * (PetscAbsReal(g[i] + c->d[i]) + PetscAbsReal(c->d[i])));
  }
  floor *= 4 * PETSC_MACHINE_EPSILON;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &floor, 1, MPIU_REAL, MPI_MAX, s->comm));
  PetscCall(VecGetArray(F, &fa));
  PetscCall(SgContactAddForce(s->c, m, fa));
  if (c->friction) {
    PetscReal floc[6] = {0}, fl = 0;
    PetscCall(VecGetArrayRead(y, &ya));
    FrictionResidual(s, ya, m, fa, floc);
    /* the round-off of gamma_T T y on the stick set */
    for (PetscInt i = 0; i < c->n; i++) {
      PetscReal yn = 0;
      if (s->fst[i] != SG_FRICTION_STICK) continue;
      for (PetscInt k = 0; k < s->dim; k++) yn = PetscMax(yn, PetscAbsReal(PetscRealPart(ya[c->off[i] + k])));
      fl = PetscMax(fl, c->fgfac * s->gamma * c->w[i] * 2 * yn);
    }
    PetscCall(VecRestoreArrayRead(y, &ya));
    fl *= 4 * PETSC_MACHINE_EPSILON;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &fl, 1, MPIU_REAL, MPI_MAX, s->comm));
    floor += fl;
  }
  PetscCall(VecRestoreArray(F, &fa));
  PetscCall(VecNorm(F, NORM_INFINITY, &nrm[0]));
  {
    const PetscReal scale = fscale, r = PetscMax(0, nrm[0] - floor);
    *err      = r > 0 ? (scale > 0 ? r / scale : PETSC_INFINITY) : nrm[0] - nrm[0]; /* NaN passed on */
    *roundoff = floor > 0 ? (scale > 0 ? floor / scale : PETSC_INFINITY) : 0;
  }
  PetscCall(VecDestroy(&F));
  PetscCall(PetscFree2(g, m));
  PetscFunctionReturn(0);
}

/* friction: the tangential shift lamhat_T (n*dim, for the controller to set), the multiplier lam_T and the states at
   the last residual evaluation; NULLs without friction */
PetscErrorCode SgSSNGetFriction(SgSSN s, PetscReal **lamhatT, const PetscReal **mT, const char **fst)
{
  PetscFunctionBeginUser;
  if (lamhatT) *lamhatT = s->lamhatT;
  if (mT) *mT = s->mT;
  if (fst) *fst = s->fst;
  PetscFunctionReturn(0);
}
