/* cont_ipf.c: inexact path-following (IPF), lamhat = 0: SSN for (P_gamma_k) stops as soon as the iterate lies in the
   neighbourhood ||(r1, r2)|| <= tau / sqrt(gamma) (formula (14)); the next gamma follows rule (15) from the
   infeasibility rho_F and complementarity rho_C, reduced by the model safeguard (16).
   The end (not specified in the paper): on the path the infeasibility is ||lam_gamma|| / gamma, so gamma is capped at
   10 ||lam|| / (tol Y sqrt|Gamma_c|) (Y sqrt|Gamma_c| the length scale of the KKT measures), where the path meets the
   KKT tolerance with a margin, and that last problem is solved exactly. */
#include "cont/contimpl.h"

typedef struct {
  PetscReal gamma1, tau, tau1, q, tau3;
  PetscReal gamma, J, dJ, C1, C2, E, rhoF, rhoC; /* the last step's path data (Model_IPF) */
  PetscReal state[2];                            /* between outer steps (checkpointed): J of the last step (J(0, y_0) = V(0) at first) and the
                         neighbourhood tau (0: the last problem, solved exactly; -1: the same, solved again at its gamma) */
} IPF;

static PetscErrorCode SetFromOptions_IPF(SgCont ct, PetscOptionItems *PetscOptionsObject)
{
  IPF        *ipf = (IPF *)ct->data;
  const char *o1, *o2, *o3, *o4, *o5;

  PetscFunctionBeginUser;
  PetscCall(SgOptionsRealRenamed(PetscOptionsObject, "-cont_gamma", "-ipf_gamma1", "gamma of the first path step", &ipf->gamma1, &o1));
  PetscCall(SgOptionsRealRenamed(PetscOptionsObject, "-cont_ipf_tau", "-ipf_tau", "Neighbourhood size: SSN stops when ||(r1,r2)|| <= tau/sqrt(gamma)", &ipf->tau, &o2));
  PetscCall(SgOptionsRealRenamed(PetscOptionsObject, "-cont_ipf_tau1", "-ipf_tau1", "Minimal growth factor of gamma in rule (15)", &ipf->tau1, &o3));
  PetscCall(SgOptionsRealRenamed(PetscOptionsObject, "-cont_ipf_q", "-ipf_q", "Exponent q of 1/max(rho_F, rho_C)^q in rule (15)", &ipf->q, &o4));
  PetscCall(SgOptionsRealRenamed(PetscOptionsObject, "-cont_ipf_tau3", "-ipf_tau3", "Safeguard (16): |tangent - model| <= tau3 |change of J|", &ipf->tau3, &o5));
  PetscCheck(PetscIsNormalReal(ipf->gamma1) && ipf->gamma1 > 0, ct->comm, PETSC_ERR_USER_INPUT, "%s: must be positive and finite, got %g", o1, (double)ipf->gamma1);
  PetscCheck(PetscIsNormalReal(ipf->tau) && ipf->tau > 0, ct->comm, PETSC_ERR_USER_INPUT, "%s: must be positive and finite, got %g", o2, (double)ipf->tau);
  PetscCheck(PetscIsNormalReal(ipf->tau1) && ipf->tau1 > 1, ct->comm, PETSC_ERR_USER_INPUT, "%s: must be > 1, got %g", o3, (double)ipf->tau1);
  PetscCheck(PetscIsNormalReal(ipf->q) && ipf->q >= 1, ct->comm, PETSC_ERR_USER_INPUT, "%s: must be >= 1, got %g", o4, (double)ipf->q);
  PetscCheck(PetscIsNormalReal(ipf->tau3) && ipf->tau3 > 0, ct->comm, PETSC_ERR_USER_INPUT, "%s: must be positive and finite, got %g", o5, (double)ipf->tau3);
  PetscFunctionReturn(0);
}

static PetscErrorCode Start_IPF(SgCont ct)
{
  IPF *ipf = (IPF *)ct->data;

  PetscFunctionBeginUser;
  ct->gamma     = ipf->gamma1;
  ipf->state[1] = ipf->tau; /* the neighbourhood tau (0: the last problem, solved exactly) */
  for (PetscInt i = 0; i < ct->n; i++) ct->lamhat[i] = 0;
  PetscFunctionReturn(0);
}

static PetscErrorCode Started_IPF(SgCont ct)
{
  PetscFunctionBeginUser;
  ((IPF *)ct->data)->state[0] = ct->V0; /* J(gamma_0 = 0, y_0) = V(0) */
  PetscFunctionReturn(0);
}

static PetscErrorCode PreStep_IPF(SgCont ct)
{
  PetscFunctionBeginUser;
  PetscCall(SgSSNSetNeighbourhood(ct->ssn, PetscMax(((IPF *)ct->data)->state[1], 0)));
  PetscFunctionReturn(0);
}

/* the path data of the step: J(gamma_k, y_{k+1}), its derivative, the model (9), rho_F and rho_C (kept for the update) */
static PetscErrorCode Model_IPF(SgCont ct, SgHistoryRow *row)
{
  IPF *ipf = (IPF *)ct->data;

  PetscFunctionBeginUser;
  PetscCall(SgSSNGetPathValues(ct->ssn, &ipf->gamma, &ipf->J, &ipf->dJ));
  PetscCall(SgSSNPathMeasures(ct->ssn, &ipf->rhoF, &ipf->rhoC));
  (void)SgModelFit(ct->V0, ipf->gamma, ipf->J, ipf->dJ, &ipf->C1, &ipf->C2, &ipf->E);
  row->C1   = ipf->C1;
  row->C2   = ipf->C2;
  row->Em   = ipf->E;
  row->rhoF = ipf->rhoF;
  row->rhoC = ipf->rhoC;
  PetscFunctionReturn(0);
}

/* rule (15) with the safeguard (16), and the cap where the last problem is solved exactly */
static PetscErrorCode Update_IPF(SgCont ct, PetscReal *nextp)
{
  IPF            *ipf   = (IPF *)ct->data;
  PetscReal      *Jprev = &ipf->state[0], *nbhd = &ipf->state[1];
  const PetscReal gamma = ipf->gamma, J = ipf->J, dJ = ipf->dJ, C1 = ipf->C1, C2 = ipf->C2, E = ipf->E, rhoF = ipf->rhoF, rhoC = ipf->rhoC;
  PetscReal       next, dJk, cap, gdp;
  PetscInt        cuts = 0;
  SNES            snes;
  const PetscBool again = (PetscBool)(*nbhd < 0); /* this step solved the last problem again at its gamma */

  PetscFunctionBeginUser;
  if (again) *nbhd = 0;
  /* ||lam||^2 = 2 gamma^2 dJ/dgamma, formula (7) */
  if (!SgContGammaCap(ct, PetscSqrtReal(2 * gamma * gamma * dJ), &cap)) cap = PETSC_MAX_REAL;
  /* and no further than double precision resolves (SgContGammaPrecision): the last problem there, solved exactly */
  PetscCall(SgContGammaPrecision(ct, &gdp));
  cap = PetscMin(cap, gdp);
  /* rule (15) */
  next = PetscMax(gamma * PetscMax(ipf->tau1, rhoC > 0 ? rhoF / rhoC : PETSC_MAX_REAL), PetscMax(rhoF, rhoC) > 0 ? PetscPowReal(PetscMax(rhoF, rhoC), -ipf->q) : PETSC_MAX_REAL);
  next = PetscMin(next, PETSC_MAX_REAL);
  /* safeguard (16): while much larger than tau1 gamma, halve log(next/gamma) until the tangent and the model agree */
  dJk = PetscAbsReal(J - *Jprev);
  while (next > ipf->tau1 * gamma) {
    const PetscReal t = J + dJ * (next - gamma), mval = PetscIsNormalReal(E) ? C1 - C2 / (E + next) : SG_NAN;
    if (PetscAbsReal(t - mval) <= ipf->tau3 * dJk) break;
    next = PetscMax(ipf->tau1 * gamma, PetscSqrtReal(next) * PetscSqrtReal(gamma));
    cuts++;
  }
  if (next >= cap && cap > gamma) {
    next  = cap;
    *nbhd = 0; /* the last problem: solved exactly */
  } else if (cap <= gamma) {
    /* a solve started from a coarser level (-cont_nested) begins at that level's last gamma, which can lie at or past
       this mesh's cap: its inexact first step is then solved again exactly at the same gamma, as the last problem of
       the path, rather than gamma grown past the cap to where double precision ends (the 3D Tresca block stopped at
       PRECISION_LIMIT at gamma 4.3e16 so) */
    if (*nbhd > 0 && ct->nested_start) {
      next  = gamma;
      *nbhd = 0;
    } else if (*nbhd == 0 && !again && !SgContAtGammaPrecision(gamma, gdp)) {
      /* the last problem, solved exactly, missed the tolerance: solved once more at the same gamma from its solution
         (a Newton step of the size of the remaining error, iterative refinement) before gamma grows. A jump to the
         cap ends its one Newton step with a round-off of the jump's size: the 2D punch on an elastic block at
         -cont_kkt_tol 1e-12 went from gamma 1.3e6 to 5.2e12 in one step (ACTIVE_SET_SETTLED) with the KKT residual
         5.2e-8, where pf's path has 9e-14 there; gamma then grew to the precision cap, whose equilibrium round-off
         3.7e-11 ended the run with PRECISION_LIMIT; now 2.9e-12 after the repeat and 7e-15 at the next gamma. Not at
         the precision cap, where the round-off of any solve is the floor (the same punch at 1e-14: 1.3e-10, then
         3.6e-10 once more there). -1: solved exactly, and again at this gamma. */
      next  = gamma;
      *nbhd = -1;
    } else *nbhd = 0;
  }
  PetscCall(SgSSNGetSNES(ct->ssn, &snes));
  PetscCall(PetscInfo(snes, "IPF step %" PetscInt_FMT ": gamma %g -> %g (rho_F %g, rho_C %g, %" PetscInt_FMT " safeguard cuts, cap %g)", ct->outer, (double)gamma, (double)next, (double)rhoF, (double)rhoC, cuts, (double)cap));
  *Jprev = J;
  *nextp = next;
  PetscFunctionReturn(0);
}

static PetscErrorCode Finish_IPF(SgCont ct)
{
  PetscFunctionBeginUser;
  PetscCall(SgSSNSetNeighbourhood(ct->ssn, 0));
  PetscFunctionReturn(0);
}

static PetscErrorCode View_IPF(SgCont ct, PetscViewer viewer)
{
  IPF *ipf = (IPF *)ct->data;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "; first gamma %g (-cont_gamma), neighbourhood tau %g (-cont_ipf_tau), growth rule (15): tau1 %g (-cont_ipf_tau1), q %g (-cont_ipf_q), safeguard (16): tau3 %g (-cont_ipf_tau3)", (double)ipf->gamma1, (double)ipf->tau, (double)ipf->tau1, (double)ipf->q, (double)ipf->tau3));
  PetscFunctionReturn(0);
}

/* the checkpoint: the path model's last J and the neighbourhood (gamma, y and the path are the controller's; the
   step's path data are computed again by the next step's Model_IPF) */
static const char *const StateNames_IPF[2] = {"J_previous", "neighbourhood_tau"};

static PetscErrorCode Save_IPF(SgCont ct, SgCheckpointWriter w)
{
  PetscFunctionBeginUser;
  PetscCall(SgContSaveState(ct, w, 2, StateNames_IPF, ((IPF *)ct->data)->state));
  PetscFunctionReturn(0);
}

static PetscErrorCode Load_IPF(SgCont ct, SgCheckpointReader r)
{
  PetscFunctionBeginUser;
  PetscCall(SgContLoadState(ct, r, 2, StateNames_IPF, ((IPF *)ct->data)->state));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContCreate_IPF(SgCont ct)
{
  IPF *ipf;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&ipf));
  ipf->gamma1            = 1e2;
  ipf->tau               = 1e6;
  ipf->tau1              = 5;
  ipf->q                 = 1.5;
  ipf->tau3              = 100;
  ct->data               = ipf;
  ct->ops.setfromoptions = SetFromOptions_IPF;
  ct->ops.view           = View_IPF;
  ct->ops.start          = Start_IPF;
  ct->ops.started        = Started_IPF;
  ct->ops.prestep        = PreStep_IPF;
  ct->ops.model          = Model_IPF;
  ct->ops.update         = Update_IPF;
  ct->ops.finish         = Finish_IPF;
  ct->ops.save           = Save_IPF;
  ct->ops.load           = Load_IPF;
  PetscFunctionReturn(0);
}
