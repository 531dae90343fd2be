/* cont_alm.c: first-order augmented Lagrangian method (ALM): solve (P_gamma) with lamhat = lam^l by SSN, then
   lam^{l+1} = max(0, lam^l + gamma_{l+1} (tau_N y - d)); gamma fixed or grown by a factor per step. */
#include "cont/contimpl.h"

typedef struct {
  PetscReal gamma, factor;
} ALM;

static PetscErrorCode SetFromOptions_ALM(SgCont ct, PetscOptionItems *PetscOptionsObject)
{
  ALM        *alm = (ALM *)ct->data;
  const char *o1, *o2;

  PetscFunctionBeginUser;
  PetscCall(SgOptionsRealRenamed(PetscOptionsObject, "-cont_gamma", "-alm_gamma", "gamma of the first step", &alm->gamma, &o1));
  PetscCall(SgOptionsRealRenamed(PetscOptionsObject, "-cont_alm_gamma_factor", "-alm_gamma_factor", "gamma_{l+1} = factor * gamma_l (1: gamma fixed)", &alm->factor, &o2));
  PetscCheck(PetscIsNormalReal(alm->gamma) && alm->gamma > 0, ct->comm, PETSC_ERR_USER_INPUT, "%s: must be positive and finite, got %g", o1, (double)alm->gamma);
  PetscCheck(PetscIsNormalReal(alm->factor) && alm->factor >= 1, ct->comm, PETSC_ERR_USER_INPUT, "%s: must be >= 1 (gamma may not decrease), got %g", o2, (double)alm->factor);
  PetscFunctionReturn(0);
}

static PetscErrorCode Start_ALM(SgCont ct)
{
  ALM              *alm = (ALM *)ct->data;
  SgContactLawState st;

  PetscFunctionBeginUser;
  ct->gamma = alm->gamma;
  for (PetscInt i = 0; i < ct->n; i++) ct->lamhat[i] = 0; /* lam^0 = 0 */
  PetscCall(SgSSNGetLawState(ct->ssn, &st));
  PetscCall(SgContactLawStateZeroShift(st)); /* lamhat_T^0 = 0 (nothing without friction) */
  PetscFunctionReturn(0);
}

/* the multiplier update: the SSN multiplier max(0, lamhat + gamma g) is lam^{l+1} */
static PetscErrorCode Update_ALM(SgCont ct, PetscReal *next)
{
  ALM              *alm = (ALM *)ct->data;
  SgContactLawState st;

  PetscFunctionBeginUser;
  PetscCall(PetscArraycpy(ct->lamhat, ct->lam, ct->n));
  PetscCall(SgSSNGetLawState(ct->ssn, &st));
  PetscCall(SgContactLawStateAcceptShift(st)); /* lamhat_T^{l+1} = P_g(lamhat_T^l + gamma_T T y): the law's */
  *next = ct->gamma * alm->factor;
  PetscFunctionReturn(0);
}

static PetscErrorCode View_ALM(SgCont ct, PetscViewer viewer)
{
  ALM *alm = (ALM *)ct->data;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "; first gamma %g (-cont_gamma), gamma growth factor %g (-cont_alm_gamma_factor)", (double)alm->gamma, (double)alm->factor));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContCreate_ALM(SgCont ct)
{
  ALM *alm;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&alm));
  alm->gamma             = 1e3;
  alm->factor            = 1;
  ct->data               = alm;
  ct->ops.setfromoptions = SetFromOptions_ALM;
  ct->ops.view           = View_ALM;
  ct->ops.start          = Start_ALM;
  ct->ops.update         = Update_ALM;
  ct->ops.shifts         = PETSC_TRUE;
  PetscFunctionReturn(0);
}
