/* cont_alm.c: first-order augmented Lagrangian method (ALM): solve (P_gamma) with lamhat = lam^l by SSN, then
   lam^{l+1} = max(0, lam^l + gamma_{l+1} (tau_N y - d)); gamma fixed or grown by a factor per step. */
#include "signorini.h"

typedef struct {
  PetscReal gamma, factor;
} ALM;

static PetscErrorCode SetFromOptions_ALM(SgCont ct, PetscOptionItems *PetscOptionsObject)
{
  ALM *alm = (ALM *)ct->data;

  PetscFunctionBeginUser;
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-alm_gamma", "gamma of the first step", &alm->gamma, NULL));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-alm_gamma_factor", "gamma_{l+1} = factor * gamma_l (1: gamma fixed)", &alm->factor, NULL));
  PetscCheck(PetscIsNormalReal(alm->gamma) && alm->gamma > 0, ct->comm, PETSC_ERR_USER_INPUT, "-alm_gamma: must be positive and finite, got %g", (double)alm->gamma);
  PetscCheck(PetscIsNormalReal(alm->factor) && alm->factor >= 1, ct->comm, PETSC_ERR_USER_INPUT, "-alm_gamma_factor: must be >= 1 (gamma may not decrease), got %g", (double)alm->factor);
  PetscFunctionReturn(0);
}

static PetscErrorCode Solve_ALM(SgCont ct)
{
  ALM      *alm  = (ALM *)ct->data;
  SgContact c    = ct->c;
  PetscBool stop = PETSC_FALSE, ok;

  PetscFunctionBeginUser;
  if (!ct->restarted) {
    ct->gamma = alm->gamma;
    for (PetscInt i = 0; i < c->n; i++) c->lamhat[i] = 0; /* lam^0 = 0 */
  }
  PetscCall(SgContStart(ct, &ok));
  while (ok && !stop) {
    PetscInt its0 = ct->ssn_its;

    ct->outer++;
    PetscCall(PetscLogEventBegin(SG_ContStep, 0, 0, 0, 0));
    PetscCall(SgContSSN(ct, ct->gamma, &ok));
    PetscCall(PetscLogEventEnd(SG_ContStep, 0, 0, 0, 0));
    PetscCall(SgContMeasure(ct));
    PetscCall(SgContOuterRow(ct, ct->ssn_its - its0, SG_NAN, SG_NAN, SG_NAN));
    if (!ok) break;
    /* the multiplier update: the SSN multiplier max(0, lamhat + gamma g) is lam^{l+1} */
    PetscCall(PetscArraycpy(c->lamhat, ct->lam, c->n));
    ct->gamma *= alm->factor;
    PetscCall(SgContCheck(ct, &stop));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SgContCreate_ALM(SgCont ct)
{
  ALM *alm;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&alm));
  alm->gamma         = 1e3;
  alm->factor        = 1;
  ct->data           = alm;
  ct->setfromoptions = SetFromOptions_ALM;
  ct->solve          = Solve_ALM;
  PetscFunctionReturn(0);
}
