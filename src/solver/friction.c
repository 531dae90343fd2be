/* friction.c: the SSN's side of the law's tangential terms (law_regularized.c for a law with a bound): what they read
   of the SSN (SgContactLawInput), the residual and Jacobian terms asked of the law, and the correction of Newton steps
   whose vertices the law linearized against their state (one more solve with the same operator). The frictionless
   law's terms do nothing. */
#include "solver/ssnimpl.h"

static void FrameToLocal(void *frame, PetscInt i, const PetscReal v[], PetscReal r[])
{
  SgFrameVectorToLocal((SgFrame)frame, i, v, r);
}

/* the law's view of the SSN now */
/* the law's Jacobian blocks into P: SgSSNAddBlocks (two bodies transformed: on the slave vertex's own dofs) */
static PetscErrorCode AddBlocks(void *ctx, const PetscReal blk[], Mat P)
{
  PetscFunctionBeginUser;
  PetscCall(SgSSNAddBlocks((SgSSN)ctx, blk, P));
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNLawInput(SgSSN s, SgContactLawInput *in)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(in, sizeof(*in)));
  in->c        = s->c;
  in->gamma    = s->gamma;
  in->lamhat   = s->lamhat;
  in->g        = s->g;
  in->actjac   = s->actjac;
  in->gfix     = s->gfix;
  in->havejac  = s->havejac;
  in->stagnant = s->stagnant;
  in->njac     = s->nhash;
  in->kroff    = s->kroff;
  in->udata    = s->udata;
  in->uv       = s->uv;
  in->ft       = s->ft;
  in->fforce   = s->fforce;
  in->nforce   = s->nforce;
  if (s->frame) {
    PetscCall(SgFrameGetAxes(s->frame, &in->faxis, &in->fsign, &in->frot));
    in->frame   = s->frame;
    in->tolocal = FrameToLocal;
  }
  in->addctx    = s;
  in->addblocks = AddBlocks;
  PetscFunctionReturn(0);
}

/* F += the law's tangential forces at y (ya) with the normal multipliers mN (two bodies: on both sides); loc: the
   path values' terms, the stick and slip counts, the changes of state and those beyond round-off (all ranks) */
PetscErrorCode SgSSNFrictionResidual(SgSSN s, const PetscScalar ya[], const PetscReal mN[], PetscScalar fa[], PetscReal loc[6])
{
  SgContactLawInput in;

  PetscFunctionBeginUser;
  PetscCall(SgSSNLawInput(s, &in));
  PetscCall(SgContactLawResidual(s->cv.law, &in, s->lst, ya, mN, fa, loc));
  PetscFunctionReturn(0);
}

/* P += the generalized derivative of the law's tangential forces at y (s->actjac: the normal active set of this
   Jacobian; after a Newton step that did not halve ||F|| the law reads F(y), s->r) */
PetscErrorCode SgSSNFrictionJacobian(SgSSN s, Vec y, Mat P)
{
  SgContactLawInput  in;
  const PetscScalar *ya, *fa = NULL;

  PetscFunctionBeginUser;
  PetscCall(SgSSNLawInput(s, &in));
  PetscCall(VecGetArrayRead(y, &ya));
  if (s->stagnant) PetscCall(VecGetArrayRead(s->r, &fa)); /* F(y): SNES evaluated it at y before this Jacobian */
  PetscCall(SgContactLawJacobian(s->cv.law, &in, s->lst, ya, fa, P));
  s->nforce = in.nforce;
  PetscCall(VecRestoreArrayRead(y, &ya));
  if (fa) PetscCall(VecRestoreArrayRead(s->r, &fa));
  PetscFunctionReturn(0);
}

/* The Newton step made consistent where the law linearized a vertex against its state (SgContactLawStepCorrection):
   the direction J^{-1} F grows by J^{-1} of the law's correction forces (one more solve with the same operator).
   SNES steps to y - Y. */
PetscErrorCode SgSSNFrictionPreCheck(SNESLineSearch ls, Vec X, Vec Y, PetscBool *changed, void *ctx)
{
  SgSSN              s = (SgSSN)ctx;
  SgContactLawInput  in;
  const PetscScalar *xa;
  PetscScalar       *ra;
  KSP                ksp;

  PetscFunctionBeginUser;
  *changed = PETSC_FALSE;
  if (!s->nforce) PetscFunctionReturn(0);
  if (!s->wpre) PetscCall(VecDuplicateVecs(X, 2, &s->wpre));
  PetscCall(VecZeroEntries(s->wpre[0]));
  PetscCall(SgSSNLawInput(s, &in));
  PetscCall(VecGetArrayRead(X, &xa));
  PetscCall(SgContactLawStepCorrection(s->cv.law, &in, s->lst, xa, s->ft));
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
