/* cont_pf.c: exact path-following (PF), lamhat = 0: solve (P_gamma) exactly by SSN, fit the model
   m(gamma) = C1 - C2/(E + gamma) to V(0), V(gamma_k), V'(gamma_k) (formula (9)), then
   gamma_{k+1} = C2/beta_k - E with beta_k = tau_k |C1 - V(gamma_k)| and tau_k = tau0^k (formula (12)). */
#include "cont/contimpl.h"

typedef struct {
  PetscReal gamma1, tau0, fallback;
  PetscReal tauk; /* tau_k = tau0^k: the state between outer steps (checkpointed) */
} PF;

static PetscErrorCode SetFromOptions_PF(SgCont ct, PetscOptionItems *PetscOptionsObject)
{
  PF         *pf = (PF *)ct->data;
  const char *o1, *o2, *o3;

  PetscFunctionBeginUser;
  PetscCall(SgOptionsRealRenamed(PetscOptionsObject, "-cont_gamma", "-pf_gamma1", "gamma of the first path step", &pf->gamma1, &o1));
  PetscCall(SgOptionsRealRenamed(PetscOptionsObject, "-cont_pf_tau0", "-pf_tau0", "tau_k = tau0^k: the model's predicted distance to V(infinity) shrinks by tau_k", &pf->tau0, &o2));
  PetscCall(SgOptionsRealRenamed(PetscOptionsObject, "-cont_pf_fallback_factor", "-pf_fallback_factor", "gamma growth when the model cannot be fitted (never needed in our runs)", &pf->fallback, &o3));
  PetscCheck(PetscIsNormalReal(pf->gamma1) && pf->gamma1 > 0, ct->comm, PETSC_ERR_USER_INPUT, "%s: must be positive and finite, got %g", o1, (double)pf->gamma1);
  PetscCheck(PetscIsNormalReal(pf->tau0) && pf->tau0 > 0 && pf->tau0 < 1, ct->comm, PETSC_ERR_USER_INPUT, "%s: must lie in (0, 1), got %g", o2, (double)pf->tau0);
  PetscCheck(PetscIsNormalReal(pf->fallback) && pf->fallback > 1, ct->comm, PETSC_ERR_USER_INPUT, "%s: must be > 1, got %g", o3, (double)pf->fallback);
  PetscFunctionReturn(0);
}

static PetscErrorCode Start_PF(SgCont ct)
{
  PF *pf = (PF *)ct->data;

  PetscFunctionBeginUser;
  ct->gamma = pf->gamma1;
  pf->tauk  = 1; /* tau_k = tau0^k */
  for (PetscInt i = 0; i < ct->n; i++) ct->lamhat[i] = 0;
  PetscFunctionReturn(0);
}

/* the model (9) through V(0), V(gamma_k) and V'(gamma_k) */
static PetscErrorCode Model_PF(SgCont ct, SgHistoryRow *row)
{
  PetscReal gamma, V, dV;

  PetscFunctionBeginUser;
  PetscCall(SgSSNGetPathValues(ct->ssn, &gamma, &V, &dV));
  (void)SgModelFit(ct->V0, gamma, V, dV, &row->C1, &row->C2, &row->Em);
  PetscFunctionReturn(0);
}

/* rule (12): gamma_{k+1} = C2/beta_k - E, beta_k = tau_k |C1 - V(gamma_k)| */
static PetscErrorCode Update_PF(SgCont ct, PetscReal *next)
{
  PF        *pf   = (PF *)ct->data;
  PetscReal *tauk = &pf->tauk;
  PetscReal  gamma, V, dV, C1, C2, E;
  SNES       snes;

  PetscFunctionBeginUser;
  PetscCall(SgSSNGetPathValues(ct->ssn, &gamma, &V, &dV));
  *tauk *= pf->tau0;
  if (SgModelFit(ct->V0, gamma, V, dV, &C1, &C2, &E)) *next = C2 / (*tauk * PetscAbsReal(C1 - V)) - E;
  else *next = SG_NAN;
  if (!(PetscIsNormalReal(*next) && *next > gamma)) {
    PetscCall(SgSSNGetSNES(ct->ssn, &snes));
    PetscCall(PetscInfo(snes, "PF step %" PetscInt_FMT ": no usable model update (%g), gamma grows by %g\n", ct->outer, (double)*next, (double)pf->fallback));
    *next = gamma * pf->fallback;
  }
  { /* no further than double precision resolves (SgContGammaPrecision): tau_k = tau0^k alone took Example 1 at
       -cont_kkt_tol 1e-10 from 1.7e12 (KKT 1.4e-10) to 1.7e17, where the SSN cycles on round-off. (The paper's rule
       is kept below it: capping at IPF's cap, where the path meets the tolerance, would change Table 2's path.) */
    PetscReal cap;
    PetscCall(SgContGammaPrecision(ct, &cap));
    if (*next > cap && cap > gamma) {
      PetscCall(SgSSNGetSNES(ct->ssn, &snes));
      PetscCall(PetscInfo(snes, "PF step %" PetscInt_FMT ": gamma %g capped at %g\n", ct->outer, (double)*next, (double)cap));
      *next = cap;
    }
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode View_PF(SgCont ct, PetscViewer viewer)
{
  PF *pf = (PF *)ct->data;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "; first gamma %g (-cont_gamma), tau0 %g (-cont_pf_tau0), fallback growth factor %g (-cont_pf_fallback_factor)", (double)pf->gamma1, (double)pf->tau0, (double)pf->fallback));
  PetscFunctionReturn(0);
}

/* the checkpoint: tau_k (gamma, y and the path are the controller's) */
static const char *const StateNames_PF[1] = {"tau_k"};

static PetscErrorCode Save_PF(SgCont ct, SgCheckpointWriter w)
{
  PetscFunctionBeginUser;
  PetscCall(SgContSaveState(ct, w, 1, StateNames_PF, &((PF *)ct->data)->tauk));
  PetscFunctionReturn(0);
}

static PetscErrorCode Load_PF(SgCont ct, SgCheckpointReader r)
{
  PetscFunctionBeginUser;
  PetscCall(SgContLoadState(ct, r, 1, StateNames_PF, &((PF *)ct->data)->tauk));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContCreate_PF(SgCont ct)
{
  PF *pf;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&pf));
  pf->gamma1             = 1e2;
  pf->tau0               = 0.1;
  pf->fallback           = 10;
  ct->data               = pf;
  ct->ops.setfromoptions = SetFromOptions_PF;
  ct->ops.view           = View_PF;
  ct->ops.start          = Start_PF;
  ct->ops.model          = Model_PF;
  ct->ops.update         = Update_PF;
  ct->ops.save           = Save_PF;
  ct->ops.load           = Load_PF;
  PetscFunctionReturn(0);
}
