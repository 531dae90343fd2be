/* jacobian.c: the SSN's Jacobian K + gamma sum_{A} w_i n_i n_i^T (+ the friction blocks), in the contact frames with
   -ssn_frame; the active set it uses, and whether the preconditioner is kept. */
#include "solver/ssnimpl.h"

/* P += the dim x dim blocks blk_i per contact vertex: SgContactAddBlocks, but for two bodies with their dual-mortar
   transformation (-ssn_pair_transform, frame.c) on the contact vertex's own dofs (its conditions are nodal there),
   without the rows and columns of fixed components of a roller (the pair leaves them out: R's rows and columns) */
PetscErrorCode SgSSNAddBlocks(SgSSN s, const PetscReal blk[], Mat P)
{
  const PetscInt dim = s->dim;
  PetscInt       rstart;

  PetscFunctionBeginUser;
  if (!SgFramePairTransform(s->frame)) {
    PetscCall(SgContactAddBlocks(s->c, blk, P));
    PetscFunctionReturn(0);
  }
  PetscCall(MatGetOwnershipRange(P, &rstart, NULL));
  for (PetscInt i = 0; i < s->n; i++) {
    const PetscInt v = s->vert[i];
    PetscInt       idx[3];
    PetscScalar    b[9];
    for (PetscInt a = 0; a < dim; a++) idx[a] = rstart + s->off[i] + a;
    for (PetscInt a = 0; a < dim; a++)
      for (PetscInt k = 0; k < dim; k++) {
        const PetscBool fixed = (PetscBool)(SgMeshPartial(s->mesh, v) && (SgMeshFixed(s->mesh, v, a) || SgMeshFixed(s->mesh, v, k)));
        b[a * dim + k]        = fixed ? 0 : blk[i * dim * dim + a * dim + k];
      }
    PetscCall(MatSetValues(P, dim, idx, dim, idx, b, ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

/* gamma w_i n_i n_i^T on the active vertices, in the frames: gamma w_i on the normal's diagonal entry at a rotated
   vertex (exactly: nothing of gamma reaches its tangential entries), the block as without frames elsewhere */
static PetscErrorCode FrameContactJacobian(SgSSN s, Mat P)
{
  const PetscInt   dim = s->dim;
  const PetscInt  *axis;
  const PetscBool *rot;
  PetscReal       *blk;

  PetscFunctionBeginUser;
  PetscCall(SgFrameGetAxes(s->frame, &axis, NULL, &rot));
  PetscCall(PetscCalloc1(s->n * dim * dim, &blk));
  for (PetscInt i = 0; i < s->n; i++) {
    PetscReal *B = &blk[i * dim * dim];
    if (!s->actjac[i]) continue;
    if (rot[i]) B[axis[i] * dim + axis[i]] = s->gamma * s->w[i];
    else
      for (PetscInt a = 0; a < dim; a++)
        for (PetscInt b = 0; b < dim; b++) B[a * dim + b] = s->gamma * s->w[i] * s->normal[i * dim + a] * s->normal[i * dim + b];
  }
  PetscCall(SgSSNAddBlocks(s, blk, P));
  PetscCall(PetscFree(blk));
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNJacobian(SNES snes, Vec y, Mat J, Mat P, void *ctx)
{
  SgSSN                s = (SgSSN)ctx;
  const SgContactView *c = &s->cv;
  const PetscScalar   *ya;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(SG_Jacobian, 0, 0, 0, 0));
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(SgContactGap(s->c, ya, s->g));
  PetscCall(VecRestoreArrayRead(y, &ya));
  for (PetscInt i = 0; i < s->n; i++) s->actjac[i] = (char)(s->lamhat[i] + s->gamma * s->g[i] > 0);
  s->havejac = PETSC_TRUE;
  if (s->nhash == s->maxhash) {
    s->maxhash = PetscMax(64, 2 * s->maxhash);
    PetscCall(PetscRealloc(sizeof(PetscInt64) * s->maxhash, &s->hash));
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
  } else if (s->pc_same_set && !c->props.nonlinear) { /* with slip the matrix changes on the same set */
    /* the same active set at the same gamma is the same matrix: keep its preconditioner */
    PetscCall(SNESSetLagPreconditioner(snes, s->nhash > 1 && s->hash[s->nhash - 1] == s->hash[s->nhash - 2] ? -1 : -2));
  }
  /* only the contact block changes: copy the stiffness (same pattern, so factorizations keep their symbolic phase) */
  PetscCall(MatCopy(s->Klin, P, SAME_NONZERO_PATTERN));
  if (s->frame) PetscCall(FrameContactJacobian(s, P));
  else PetscCall(SgContactAddJacobian(s->c, s->actjac, s->gamma, P));
  PetscCall(SgSSNFrictionJacobian(s, y, P)); /* the law's tangential term (none without friction) */
  PetscCall(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscLogEventEnd(SG_Jacobian, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}
