/* law_regularized.c: the tangential terms of the SSN for a law with a bound g_i(lam_N) (tresca, coulomb, and a caller's
   law that sets no terms of its own): the regularized friction lam_T = P_g(lamhat_T + gamma_T T (y - yref)) per
   contact vertex, its part of the residual and of the path values, its generalized derivative in the Jacobian, the
   correction of Newton steps whose slips were linearized as stick (or sticks as slip), and its round-off floors. The
   SSN fills an SgContactLawInput and calls SgContactLawResidual etc. (law.c), which call these ops; the frictionless
   law has none. Two bodies: the law acts on the relative displacements R y and its forces on both sides (R^T). */
#include "contact/contactimpl.h"

/* Friction at contact vertex i (uv: the contact vertices' displacements, SgContactVertexDisplacements: y_i, for two
   bodies the relative displacement (R y)_i; mN: the regularized normal multiplier there):
   z = T_i (lamhat_T,i + gamma_T u), u = T_i (y_i - yref_i) the slip since the start of the load step (yref = 0 at the
   first: quasi-static incremental friction), bound g = g_i(mN) (the law's: s for Tresca, F mN for Coulomb), lam_T =
   P_g(z) the projection onto the ball of radius g; t = z/|z| (0 if z = 0). The state: free (g = 0), stick (|z| <= g),
   slip (|z| > g). */
static char FrictionAt(SgContactLaw law, const SgContactLawInput *in, SgContact c, SgContactLawState st, PetscInt i, const PetscReal uv[], PetscReal mN, PetscReal lamT[], PetscReal u[], PetscReal t[], PetscReal *zn, PetscReal *gb)
{
  const PetscInt   dim = law->dim;
  const PetscReal *n = &c->normal[i * dim], gT = law->gfac * in->gamma;
  PetscReal        un = 0, zdn = 0, z[3], nz = 0, dy[3];

  for (PetscInt k = 0; k < dim; k++) {
    dy[k] = uv[i * dim + k] - law->yref[i * dim + k]; /* the load step's increment */
    un += n[k] * dy[k];
  }
  for (PetscInt k = 0; k < dim; k++) {
    u[k] = dy[k] - un * n[k];
    z[k] = st->lamhatT[i * dim + k] + gT * u[k];
    zdn += z[k] * n[k];
  }
  for (PetscInt k = 0; k < dim; k++) {
    z[k] -= zdn * n[k];
    nz += z[k] * z[k];
  }
  nz  = PetscSqrtReal(nz);
  *zn = nz;
  if (in->gfix) *gb = in->gfix[i]; /* Coulomb's fixed point: the bound frozen */
  else law->ops.bound(law, i, mN, gb, NULL);
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

/* A change of state at vertex i since the Jacobian beyond round-off: |z| and the bound g differ by more than the
   round-off of forming them (or the normal multiplier crossed 0 beyond its own) */
static PetscBool HardChange(SgContactLaw law, const SgContactLawInput *in, SgContact c, SgContactLawState st, PetscInt i, PetscReal mN, char s, PetscReal zn, PetscReal gb)
{
  const PetscInt  dim  = law->dim;
  const PetscReal gT   = law->gfac * in->gamma;
  PetscReal       ymax = 0, lh = 0, ro;

  for (PetscInt k = 0; k < dim; k++) {
    ymax = PetscMax(ymax, PetscAbsReal(in->uv[i * dim + k]) + PetscAbsReal(law->yref[i * dim + k]));
    lh   = PetscMax(lh, PetscAbsReal(st->lamhatT[i * dim + k]));
  }
  const PetscReal roN = 8 * PETSC_MACHINE_EPSILON * (PetscAbsReal(in->lamhat[i]) + in->gamma * (PetscAbsReal(in->g[i] + c->d[i]) + PetscAbsReal(c->d[i]) + in->udata)) + in->kroff / c->w[i];
  PetscReal       gi, dg;
  law->ops.bound(law, i, mN, &gi, &dg); /* the bound's round-off from lam_N's */
  ro = 8 * PETSC_MACHINE_EPSILON * (lh + gb + gT * ymax) + in->kroff / c->w[i] + (law->coupled ? dg * roN : 0);
  if (s == SG_FRICTION_FREE || st->statejac[i] == SG_FRICTION_FREE) return (PetscBool)(PetscAbsReal(in->lamhat[i] + in->gamma * in->g[i]) > roN); /* the normal multiplier crossed 0 */
  else if (s != st->statejac[i]) return (PetscBool)(PetscAbsReal(zn - gb) > ro);                                                                  /* stick <-> slip */
  return (PetscBool)(zn > ro);                                                                                                                    /* a slip that reversed */
}

/* F += sum_i w_i lam_T,i at y, with the normal multipliers mN; the states, the counts and, for the path values, the
   sums w_i (lam_T.u - |lam_T - lamhat_T|^2/(2 gamma_T)) (the regularized Tresca term of J(gamma, y): the value of
   sup_{|mu| <= g} mu.u - |mu - lamhat_T|^2/(2 gamma_T), whose gradient in u is lam_T) and its derivative in gamma,
   c w_i |lam_T - lamhat_T|^2 / (2 gamma_T^2) (for Coulomb the same terms with the bound frozen: no potential); loc:
   those two sums, the stick and slip counts, the changes since the Jacobian and those beyond round-off (all ranks) */
static PetscErrorCode Residual_Regularized(SgContactLaw law, SgContactLawInput *in, SgContactLawState st, const PetscScalar ya[], const PetscReal mN[], PetscScalar fa[], PetscReal loc[6])
{
  const PetscInt  dim = law->dim;
  const PetscReal gT  = law->gfac * in->gamma;
  SgContact       c   = in->c; /* the contact object itself (this layer's) */

  PetscFunctionBeginUser;
  PetscCall(SgContactVertexDisplacements(in->c, ya, in->uv));
  for (PetscInt i = 0; i < c->n; i++) {
    PetscReal *lt = &st->lamT[i * dim], u[3], t[3], zn, gb, lu = 0;
    const char s = FrictionAt(law, in, c, st, i, in->uv, mN[i], lt, u, t, &zn, &gb);
    st->state[i] = s;
    for (PetscInt k = 0; k < dim; k++) {
      in->ft[i * dim + k] = c->w[i] * lt[k];
      lu += lt[k] * u[k];
    }
    {
      PetscReal dd = 0; /* |lam_T - lamhat_T|^2 */
      for (PetscInt k = 0; k < dim; k++) dd += PetscSqr(lt[k] - st->lamhatT[i * dim + k]);
      loc[0] += c->w[i] * (lu - dd / (2 * gT));
      loc[1] += c->w[i] * law->gfac * dd / (2 * gT * gT);
    }
    loc[2] += (s == SG_FRICTION_STICK);
    loc[3] += (s == SG_FRICTION_SLIP);
    /* a slip whose direction turned by more than 90 degrees since the Jacobian is a change of state too: in 2D the
       slip derivative is 0, and a vertex flipping between +g and -g would look settled */
    if (in->havejac) {
      PetscBool changed = (PetscBool)(s != st->statejac[i]);
      if (!changed && s == SG_FRICTION_SLIP) {
        PetscReal tt = 0;
        for (PetscInt k = 0; k < dim; k++) tt += t[k] * st->tjac[i * dim + k];
        changed = (PetscBool)(tt <= 0);
      }
      loc[4] += changed;
      if (changed) loc[5] += HardChange(law, in, c, st, i, mN[i], s, zn, gb);
    }
  }
  PetscCall(SgContactAddVertexForces(in->c, in->ft, fa));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, loc, 6, MPIU_REAL, MPI_SUM, law->comm));
  PetscFunctionReturn(0);
}

/* A stick vertex after a Newton step that did not halve ||F|| (fa: F(y)): at a large gamma_T the stick force
   gamma_T T (y - yref) moves in steps of about q = 4 eps gamma_T |y_i|, and a correction below q is rounded away. A
   stick vertex whose tangential residual T F_i / w_i lies below q and whose equilibrium force lam_T - T F_i / w_i (the
   force the step should reach) lies beyond the bound slips: linearized as slip in the direction of that force (the
   step made consistent by SgContactLawStepCorrection). True if so, with its t and |z|. */
static PetscBool StickForcedToSlip(SgContactLaw law, const SgContactLawInput *in, SgContact c, PetscInt i, const PetscScalar fa[], const PetscReal lt[], PetscReal gb, PetscReal t[], PetscReal *zn)
{
  const PetscInt   dim = law->dim;
  const PetscReal *n = &c->normal[i * dim], gT = law->gfac * in->gamma;
  PetscReal        le[3], fn = 0, ln = 0, rt = 0, ym = 0;

  for (PetscInt k = 0; k < dim; k++) fn += n[k] * PetscRealPart(fa[c->off[i] + k]);
  for (PetscInt k = 0; k < dim; k++) {
    const PetscReal r = (PetscRealPart(fa[c->off[i] + k]) - fn * n[k]) / c->w[i];
    le[k]             = lt[k] - r;
    ln += le[k] * le[k];
    rt += r * r;
    ym = PetscMax(ym, PetscMax(PetscAbsReal(in->uv[i * dim + k]), PetscAbsReal(law->yref[i * dim + k])));
  }
  ln = PetscSqrtReal(ln);
  if (!(ln > gb && PetscSqrtReal(rt) <= 4 * PETSC_MACHINE_EPSILON * gT * ym)) return PETSC_FALSE;
  *zn = ln;
  for (PetscInt k = 0; k < dim; k++) t[k] = le[k] / ln;
  return PETSC_TRUE;
}

/* The block of vertex i in state s (nb, tb: the normal and slip direction, in the vertex's frame with -ssn_frame):
     stick: w gamma_T T_i;   slip: w (g/|z|) gamma_T (T_i - t t^T), and for a bound from lam_N with an active normal
     also w g'(lam_N) gamma t n_i^T (the bound moves with y: a nonsymmetric block);   free: 0. */
static void Block(SgContactLaw law, const SgContactLawInput *in, SgContact c, PetscInt i, char s, PetscReal mN, PetscReal gb, PetscReal zn, const PetscReal nb[], const PetscReal tb[], PetscReal B[])
{
  const PetscInt  dim = law->dim;
  const PetscReal gT  = law->gfac * in->gamma;
  PetscReal       gi, dg = 0;

  if (law->coupled) law->ops.bound(law, i, mN, &gi, &dg); /* the bound's derivative in lam_N */
  for (PetscInt a = 0; a < dim; a++)
    for (PetscInt b = 0; b < dim; b++) {
      const PetscReal T = (a == b ? 1 : 0) - nb[a] * nb[b];
      if (s == SG_FRICTION_STICK) B[a * dim + b] = c->w[i] * gT * T;
      else {
        B[a * dim + b] = c->w[i] * (gb / zn) * gT * (T - tb[a] * tb[b]);
        if (law->coupled && in->actjac[i] && !in->gfix) B[a * dim + b] += c->w[i] * dg * in->gamma * tb[a] * nb[b];
      }
    }
}

/* The generalized derivative of sum_i w_i lam_T,i at y (in->actjac: the normal active set of this Jacobian; fa: F(y)
   when in->stagnant, else NULL), P += it; the states and directions of this Jacobian, the vertices linearized against
   their state (in->fforce, in->nforce) */
static PetscErrorCode Jacobian_Regularized(SgContactLaw law, SgContactLawInput *in, SgContactLawState st, const PetscScalar ya[], const PetscScalar fa[], Mat P)
{
  const PetscInt dim = law->dim;
  SgContact      c   = in->c; /* the contact object itself (this layer's) */
  PetscReal     *blk;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(c->n * dim * dim, &blk));
  in->nforce = 0;
  PetscCall(SgContactVertexDisplacements(in->c, ya, in->uv));
  for (PetscInt i = 0; i < c->n; i++) {
    const PetscReal *n  = &c->normal[i * dim];
    const PetscReal  mN = in->actjac[i] ? in->lamhat[i] + in->gamma * in->g[i] : 0;
    PetscReal        lt[3], u[3], t[3], zn, gb, *B = &blk[i * dim * dim];
    char             s = FrictionAt(law, in, c, st, i, in->uv, mN, lt, u, t, &zn, &gb);
    /* a slip that reversed its direction since the last Jacobian of this solve is linearized as stick: with the slip
       derivative (0 in 2D) Newton can flip such a vertex between +g and -g forever when its solution sticks */
    if (in->njac > 1 && s == SG_FRICTION_SLIP && st->statejac[i] == SG_FRICTION_SLIP) { /* not the first Jacobian of the solve */
      PetscReal tt = 0;
      for (PetscInt k = 0; k < dim; k++) tt += t[k] * st->tjac[i * dim + k];
      if (tt <= 0) s = SG_FRICTION_STICK;
    }
    in->fforce[i] = (char)(s == SG_FRICTION_STICK && zn > gb);
    if (fa && s == SG_FRICTION_STICK && !in->fforce[i] && StickForcedToSlip(law, in, c, i, fa, lt, gb, t, &zn)) {
      s             = SG_FRICTION_SLIP;
      in->fforce[i] = 2;
    }
    in->nforce += (in->fforce[i] != 0);
    st->statejac[i] = s;
    for (PetscInt k = 0; k < dim; k++) st->tjac[i * dim + k] = t[k];
    if (s == SG_FRICTION_FREE) continue;
    {
      /* in the vertex's frame (-ssn_frame) the block Q^T B Q is made from n = e_axis and t in the frame */
      PetscReal        nf[3] = {0, 0, 0}, tf[3];
      const PetscReal *nb = n, *tb = t;
      if (in->frot && in->frot[i]) {
        nf[in->faxis[i]] = in->fsign[i]; /* n = sign Q e_axis */
        in->tolocal(in->frame, i, t, tf);
        tf[in->faxis[i]] = 0;
        nb               = nf;
        tb               = tf;
      }
      Block(law, in, c, i, s, mN, gb, zn, nb, tb, B);
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &in->nforce, 1, MPIU_INT, MPI_SUM, law->comm));
  if (in->addblocks) PetscCall(in->addblocks(in->addctx, blk, P));
  else PetscCall(SgContactAddBlocks(in->c, blk, P));
  PetscCall(PetscFree(blk));
  PetscFunctionReturn(0);
}

/* The Newton step with the slips linearized as stick (Jacobian_Regularized) made consistent: their linear model is
   lam_T = z(y) + gamma_T T d, not P_g(z(y)) + gamma_T T d, so the residual of the step takes z there: ft = the forces
   w_i (z_i - P_g(z_i)) at those vertices (the SSN adds J^{-1} of them to the step), 0 elsewhere */
static PetscErrorCode StepCorrection_Regularized(SgContactLaw law, SgContactLawInput *in, SgContactLawState st, const PetscScalar xa[], PetscReal ft[])
{
  const PetscInt dim = law->dim;
  SgContact      c   = in->c; /* the contact object itself (this layer's) */

  PetscFunctionBeginUser;
  PetscCall(SgContactVertexDisplacements(in->c, xa, in->uv));
  PetscCall(PetscArrayzero(ft, c->n * dim));
  for (PetscInt i = 0; i < c->n; i++) {
    PetscReal lt[3], u[3], t[3], zn, gb;
    if (!in->fforce[i]) continue;
    (void)FrictionAt(law, in, c, st, i, in->uv, in->actjac[i] ? in->lamhat[i] + in->gamma * in->g[i] : 0, lt, u, t, &zn, &gb);
    if (in->fforce[i] == 2) /* a stick linearized as slip: its model is g t_jac, not z = lam_T */
      for (PetscInt k = 0; k < dim; k++) ft[i * dim + k] = c->w[i] * (gb * st->tjac[i * dim + k] - lt[k]);
    else
      for (PetscInt k = 0; k < dim; k++) ft[i * dim + k] = c->w[i] * (zn * t[k] - lt[k]);
  }
  PetscFunctionReturn(0);
}

/* The round-off of the tangential force at vertex i, ya the local part of y: for the SSN's floor of ||F|| (equil
   false) gamma_T w 2 max_k (|y_k| + |yref_k|) at stick (lam_T = z; at slip g z/|z| is well-conditioned, except for
   the landing of a Newton step from another state on |z| = g, a stick linearization that lands at the slip bound);
   for the equilibrium error of a solve (equil true) gamma_T w 2 max_k |y_k| at stick */
static PetscReal Floor_Regularized(SgContactLaw law, const SgContactLawInput *in, SgContactLawState st, const PetscScalar ya[], PetscInt i, PetscBool equil)
{
  const PetscInt dim  = law->dim;
  SgContact      c    = in->c; /* the contact object itself (this layer's) */
  PetscReal      ymax = 0;

  if (equil) {
    if (st->state[i] != SG_FRICTION_STICK) return 0;
    for (PetscInt k = 0; k < dim; k++) ymax = PetscMax(ymax, PetscAbsReal(PetscRealPart(ya[c->off[i] + k])));
    return law->gfac * in->gamma * c->w[i] * 2 * ymax;
  }
  if (!(st->state[i] == SG_FRICTION_STICK || (in->havejac && st->state[i] == SG_FRICTION_SLIP && st->statejac[i] != SG_FRICTION_SLIP))) return 0;
  for (PetscInt k = 0; k < dim; k++) ymax = PetscMax(ymax, PetscAbsReal(PetscRealPart(ya[c->off[i] + k])) + PetscAbsReal(law->yref[i * dim + k]));
  return law->gfac * in->gamma * c->w[i] * 2 * ymax;
}

/* The checkpoint of the tangential state: the tangential shift lamhat_T (NULL: zeros, a controller without an SSN)
   and the slip reference, of the unknowns and of the full displacement (2 dim per contact vertex) */
static PetscErrorCode Save_Regularized(SgContactLaw law, const PetscReal lamhatT[], const PetscReal yref[], SgContactLawWriter *w)
{
  PetscFunctionBeginUser;
  PetscCall(w->contact(w->ctx, "lamhat_t", law->dim, lamhatT));
  PetscCall(w->contact(w->ctx, "slip_reference", law->dim, yref));
  PetscCall(w->contact(w->ctx, "slip_reference_full", law->dim, yref ? yref + law->n * law->dim : NULL));
  PetscFunctionReturn(0);
}

/* *full: the file held the full displacement's slip reference (older files did not: then a copy of the unknowns') */
static PetscErrorCode Load_Regularized(SgContactLaw law, PetscReal lamhatT[], PetscReal yref[], SgContactLawReader *r, PetscBool *full)
{
  const PetscInt dim = law->dim;

  PetscFunctionBeginUser;
  PetscCall(r->contact(r->ctx, "lamhat_t", dim, "a tangential shift lamhat_t", lamhatT));
  PetscCall(r->contact(r->ctx, "slip_reference", dim, "a slip reference", yref));
  PetscCall(r->hasdataset(r->ctx, "slip_reference_full", full));
  if (*full) PetscCall(r->contact(r->ctx, "slip_reference_full", dim, "a slip reference of the full displacement", yref ? yref + law->n * dim : NULL));
  else if (yref) PetscCall(PetscArraycpy(yref + law->n * dim, yref, law->n * dim)); /* exact without prescribed components */
  PetscFunctionReturn(0);
}

/* Nested iteration: the multiplier lam_T of the coarser level's solve (a vector per vertex) becomes the finer level's
   tangential shift lamhat_T (as lam_N becomes lamhat) */
static PetscErrorCode TransferSize_Regularized(SgContactLaw law, PetscInt *bs, PetscBool *vector)
{
  PetscFunctionBeginUser;
  *bs     = law->dim;
  *vector = PETSC_TRUE;
  PetscFunctionReturn(0);
}

static PetscErrorCode TransferPack_Regularized(SgContactLaw law, SgContactLawState st, PetscReal vals[])
{
  PetscFunctionBeginUser;
  if (st) PetscCall(PetscArraycpy(vals, st->lamT, law->n * law->dim));
  else PetscCall(PetscArrayzero(vals, law->n * law->dim));
  PetscFunctionReturn(0);
}

static PetscErrorCode TransferUnpack_Regularized(SgContactLaw law, SgContactLawState st, const PetscReal vals[])
{
  PetscFunctionBeginUser;
  PetscCall(PetscArraycpy(st->lamhatT, vals, law->n * law->dim));
  PetscFunctionReturn(0);
}

/* the ops of a law with a bound (law.c installs them for a type with a tangential part that sets none of its own) */
PetscErrorCode SgContactLawSetRegularizedOps(SgContactLaw law)
{
  PetscFunctionBeginUser;
  if (!law->ops.residual) law->ops.residual = Residual_Regularized;
  if (!law->ops.jacobian) law->ops.jacobian = Jacobian_Regularized;
  if (!law->ops.stepcorrection) law->ops.stepcorrection = StepCorrection_Regularized;
  if (!law->ops.floor) law->ops.floor = Floor_Regularized;
  if (!law->ops.save) law->ops.save = Save_Regularized;
  if (!law->ops.load) law->ops.load = Load_Regularized;
  if (!law->ops.transfersize && !law->ops.transferpack && !law->ops.transferunpack) {
    law->ops.transfersize   = TransferSize_Regularized;
    law->ops.transferpack   = TransferPack_Regularized;
    law->ops.transferunpack = TransferUnpack_Regularized;
  }
  PetscFunctionReturn(0);
}
