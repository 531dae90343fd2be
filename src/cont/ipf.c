/* cont_ipf.c: inexact path-following (IPF), lamhat = 0: SSN for (P_gamma_k) stops as soon as the iterate lies in the
   neighbourhood ||(r1, r2)|| <= tau / sqrt(gamma) (formula (14)); the next gamma follows rule (15) from the
   infeasibility rho_F and complementarity rho_C, reduced by the model safeguard (16).
   The end (not specified in the paper): on the path the infeasibility is ||lam_gamma|| / gamma, so gamma is capped at
   10 ||lam|| / (tol Y sqrt|Gamma_c|) (Y sqrt|Gamma_c| the length scale of the KKT measures), where the path meets the
   KKT tolerance with a margin, and that last problem is solved exactly. */
#include "signorini.h"

typedef struct {
  PetscReal gamma1, tau, tau1, q, tau3;
} IPF;

static PetscErrorCode SetFromOptions_IPF(SgCont ct, PetscOptionItems *PetscOptionsObject)
{
  IPF *ipf = (IPF *)ct->data;

  PetscFunctionBeginUser;
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-ipf_gamma1", "gamma of the first path step", &ipf->gamma1, NULL));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-ipf_tau", "Neighbourhood size: SSN stops when ||(r1,r2)|| <= tau/sqrt(gamma)", &ipf->tau, NULL));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-ipf_tau1", "Minimal growth factor of gamma in rule (15)", &ipf->tau1, NULL));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-ipf_q", "Exponent q of 1/max(rho_F, rho_C)^q in rule (15)", &ipf->q, NULL));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-ipf_tau3", "Safeguard (16): |tangent - model| <= tau3 |change of J|", &ipf->tau3, NULL));
  PetscCheck(PetscIsNormalReal(ipf->gamma1) && ipf->gamma1 > 0, ct->comm, PETSC_ERR_USER_INPUT, "-ipf_gamma1: must be positive and finite, got %g", (double)ipf->gamma1);
  PetscCheck(PetscIsNormalReal(ipf->tau) && ipf->tau > 0, ct->comm, PETSC_ERR_USER_INPUT, "-ipf_tau: must be positive and finite, got %g", (double)ipf->tau);
  PetscCheck(PetscIsNormalReal(ipf->tau1) && ipf->tau1 > 1, ct->comm, PETSC_ERR_USER_INPUT, "-ipf_tau1: must be > 1, got %g", (double)ipf->tau1);
  PetscCheck(PetscIsNormalReal(ipf->q) && ipf->q >= 1, ct->comm, PETSC_ERR_USER_INPUT, "-ipf_q: must be >= 1, got %g", (double)ipf->q);
  PetscCheck(PetscIsNormalReal(ipf->tau3) && ipf->tau3 > 0, ct->comm, PETSC_ERR_USER_INPUT, "-ipf_tau3: must be positive and finite, got %g", (double)ipf->tau3);
  PetscFunctionReturn(0);
}

/* rho_F = int max(0, g), rho_C = int_I max(0, g) + int_A -min(0, g) with A, I the active and inactive sets of the
   iterate (the sets of the last Newton step). */
static PetscErrorCode Measures(SgCont ct, PetscReal *rhoF, PetscReal *rhoC)
{
  SgContact c = ct->c;
  SgSSN     s = ct->ssn;
  PetscReal r[2] = {0, 0};

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < c->n; i++) {
    const PetscBool act = (PetscBool)(s->havejac ? s->actjac[i] : s->act[i]);
    r[0] += c->w[i] * PetscMax(0, s->g[i]);
    r[1] += c->w[i] * (act ? -PetscMin(0, s->g[i]) : PetscMax(0, s->g[i]));
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, r, 2, MPIU_REAL, MPI_SUM, ct->comm));
  *rhoF = r[0];
  *rhoC = r[1];
  PetscFunctionReturn(0);
}

static PetscErrorCode Solve_IPF(SgCont ct)
{
  IPF       *ipf   = (IPF *)ct->data;
  PetscReal *Jprev = &ct->state[0], *nbhd = &ct->state[1]; /* J of the previous step; the neighbourhood tau (0: exact) */
  PetscBool  stop  = PETSC_FALSE, ok;

  PetscFunctionBeginUser;
  if (!ct->restarted) {
    ct->gamma = ipf->gamma1;
    *nbhd     = ipf->tau;
    for (PetscInt i = 0; i < ct->c->n; i++) ct->c->lamhat[i] = 0;
  }
  PetscCall(SgContStart(ct, &ok));
  if (!ct->restarted) *Jprev = ct->V0; /* J(gamma_0 = 0, y_0) = V(0) */
  while (ok && !stop) {
    const PetscReal gamma = ct->gamma;
    PetscInt        its0  = ct->ssn_its, cuts = 0;
    PetscReal       J, dJ, C1, C2, E, rhoF, rhoC, next, dJk, cap;

    ct->ssn->nbhd_tau = *nbhd;

    ct->outer++;
    PetscCall(PetscLogEventBegin(SG_ContStep, 0, 0, 0, 0));
    PetscCall(SgContSSN(ct, gamma, &ok));
    PetscCall(PetscLogEventEnd(SG_ContStep, 0, 0, 0, 0));
    PetscCall(SgContMeasure(ct));
    J   = ct->ssn->V; /* J(gamma_k, y_{k+1}) */
    dJ  = ct->ssn->dVdg;
    /* ||lam||^2 = 2 gamma^2 dJ/dgamma, formula (7) */
    cap = ct->kkt.lscale > 0 ? 10 * PetscSqrtReal(2 * gamma * gamma * dJ) / (ct->kkt_tol * ct->kkt.lscale) : PETSC_MAX_REAL;
    PetscCall(Measures(ct, &rhoF, &rhoC));
    (void)SgModelFit(ct->V0, gamma, J, dJ, &C1, &C2, &E);
    PetscCall(SgContOuterRow(ct, ct->ssn_its - its0, C1, C2, E));
    ct->hist->rows[ct->hist->n - 1].rhoF = rhoF;
    ct->hist->rows[ct->hist->n - 1].rhoC = rhoC;
    if (!ok) break;
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
    } else if (cap <= gamma) *nbhd = 0;
    PetscCall(PetscInfo(ct->ssn->snes, "IPF step %" PetscInt_FMT ": gamma %g -> %g (rho_F %g, rho_C %g, %" PetscInt_FMT " safeguard cuts, cap %g)\n", ct->outer, (double)gamma, (double)next, (double)rhoF, (double)rhoC, cuts, (double)cap));
    *Jprev    = J;
    ct->gamma = next;
    PetscCall(SgContCheck(ct, &stop));
  }
  ct->ssn->nbhd_tau = 0;
  PetscFunctionReturn(0);
}

PetscErrorCode SgContCreate_IPF(SgCont ct)
{
  IPF *ipf;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&ipf));
  ipf->gamma1        = 1e2;
  ipf->tau           = 1e6;
  ipf->tau1          = 5;
  ipf->q             = 1.5;
  ipf->tau3          = 100;
  ct->data           = ipf;
  ct->setfromoptions = SetFromOptions_IPF;
  ct->solve          = Solve_IPF;
  PetscFunctionReturn(0);
}
