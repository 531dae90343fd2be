/* cont/none.c: one regularized problem (P_gamma) for -contact_gamma and -contact_lamhat, from the unconstrained start.
   It solves (P_gamma), not (P): converged means the equilibrium residual of (P_gamma) (SgSSNEquilibriumError) is below
   -cont_kkt_tol (a settled active set after loose linear solves is not enough); the KKT residual of (P) is reported
   beside it. Without a contact boundary: the linear elasticity solve. */
#include "cont/contimpl.h"

typedef struct {
  PetscReal gamma, lamhat;
} None;

static PetscErrorCode SetFromOptions_None(SgCont ct, PetscOptionItems *PetscOptionsObject)
{
  None       *nn = (None *)ct->data;
  const char *o1, *o2;

  PetscFunctionBeginUser;
  PetscCall(SgOptionsRealRenamed(PetscOptionsObject, "-cont_gamma", "-contact_gamma", "Regularization parameter gamma of (P_gamma)", &nn->gamma, &o1));
  PetscCall(SgOptionsRealRenamed(PetscOptionsObject, "-cont_none_lamhat", "-contact_lamhat", "Constant shift lamhat of (P_gamma)", &nn->lamhat, &o2));
  if (!ct->c) PetscFunctionReturn(0); /* read, but unused: linear elasticity */
  PetscCheck(PetscIsNormalReal(nn->gamma) && nn->gamma > 0, ct->comm, PETSC_ERR_USER_INPUT, "%s: gamma must be positive and finite, got %g", o1, (double)nn->gamma);
  PetscCheck((PetscIsNormalReal(nn->lamhat) || nn->lamhat == 0) && nn->lamhat >= 0, ct->comm, PETSC_ERR_USER_INPUT, "%s: the shift must be finite and >= 0, got %g", o2, (double)nn->lamhat);
  PetscFunctionReturn(0);
}

static PetscErrorCode Solve_None(SgCont ct)
{
  None       *nn = (None *)ct->data;
  PetscBool   ok;
  PetscInt    its0 = ct->ssn_its;
  PetscReal   roundoff, V, dV;
  SgSSNReason sr;

  PetscFunctionBeginUser;
  if (ct->c) {
    ct->gamma = nn->gamma;
    for (PetscInt i = 0; i < ct->n; i++) ct->lamhat[i] = nn->lamhat;
  }
  PetscCall(SgContStart(ct, &ok));
  if (!ok) PetscFunctionReturn(0);
  if (!ct->c) {
    PetscReal nrm[2], Knorm, bnorm_inf;
    PetscInt  dim;
    Vec       R, b;
    Mat       K;
    PetscCall(SgElasticityGetOperators(ct->prob, &K, &b));
    PetscCall(SgElasticityGetNodalNormSize(ct->prob, &dim));
    PetscCall(SgElasticityGetScales(ct->prob, &Knorm, NULL, &bnorm_inf));
    PetscCall(VecDuplicate(ct->y, &R));
    PetscCall(MatMult(K, ct->y, R));
    PetscCall(VecAXPY(R, -1.0, b));
    PetscCall(SgVecVertexNormMax(R, dim, &nrm[0])); /* per vertex: the same turned */
    PetscCall(SgVecVertexNormMax(ct->y, dim, &nrm[1]));
    PetscCall(VecDestroy(&R));
    ct->residual  = nrm[0] > 0 ? nrm[0] / (Knorm * nrm[1] + bnorm_inf) : 0;
    ct->converged = PETSC_TRUE;
    PetscCall(PetscStrcpy(ct->reason, "LINEAR_SOLVE"));
    PetscFunctionReturn(0);
  }
  ct->outer = 1;
  PetscCall(PetscLogEventBegin(SG_ContStep, 0, 0, 0, 0));
  PetscCall(SgContSSN(ct, ct->gamma, &ok));
  PetscCall(PetscLogEventEnd(SG_ContStep, 0, 0, 0, 0));
  PetscCall(SgContMeasure(ct));
  PetscCall(SgContOuterRow(ct, ct->ssn_its - its0, NULL));
  PetscCall(SgSSNEquilibriumError(ct->ssn, ct->y, ct->kkt.fscale, &ct->residual, &roundoff));
  PetscCall(SgSSNGetReason(ct->ssn, &sr));
  if (ok && roundoff > ct->kkt_tol) {
    PetscCall(SgContFail(ct, "PGAMMA_UNVERIFIABLE: SSN_%s at gamma %g, but the round-off of gamma (tau_N y - d) is %.3e of the force scale, above -cont_kkt_tol %.3e: (P_gamma) cannot be checked to that tolerance in double precision (lower -contact_gamma, or solve (P) with -cont_type ipf); as a solution of (P) the KKT residual is %.3e", SgSSNReasons[sr], (double)ct->gamma, (double)roundoff, (double)ct->kkt_tol, (double)ct->kkt.residual));
  } else if (ok && ct->residual <= ct->kkt_tol) {
    ct->converged = PETSC_TRUE;
    PetscCall(PetscSNPrintf(ct->reason, sizeof(ct->reason), "PGAMMA_SOLVED: SSN_%s at gamma %g, equilibrium residual of (P_gamma) %.3e <= %.3e; as a solution of (P) its KKT residual is %.3e (%s -cont_kkt_tol)", SgSSNReasons[sr], (double)ct->gamma, (double)ct->residual, (double)ct->kkt_tol, (double)ct->kkt.residual, ct->kkt.residual <= ct->kkt_tol ? "within" : "above"));
  } else if (ok) {
    PetscCall(SgContFail(ct, "PGAMMA_RESIDUAL_ABOVE_TOL: SSN_%s at gamma %g, but the equilibrium residual of (P_gamma) is %.3e > %.3e (-cont_kkt_tol); tighten the linear solves", SgSSNReasons[sr], (double)ct->gamma, (double)ct->residual, (double)ct->kkt_tol));
  }
  PetscCall(SgSSNGetPathValues(ct->ssn, NULL, &V, &dV));
  PetscCall(SgSummarySetReal(ct->sum, "path_value", V));
  PetscCall(SgSummarySetReal(ct->sum, "path_derivative", dV));
  PetscFunctionReturn(0);
}

static PetscErrorCode View_None(SgCont ct, PetscViewer viewer)
{
  None *nn = (None *)ct->data;

  PetscFunctionBeginUser;
  if (!ct->c) PetscFunctionReturn(0); /* linear elasticity: no gamma */
  PetscCall(PetscViewerASCIIPrintf(viewer, "; one (P_gamma) at gamma %g (-cont_gamma), shift lamhat %g (-cont_none_lamhat)", (double)nn->gamma, (double)nn->lamhat));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContCreate_None(SgCont ct)
{
  None *nn;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&nn));
  nn->gamma              = 1e4;
  ct->data               = nn;
  ct->ops.setfromoptions = SetFromOptions_None;
  ct->ops.view           = View_None;
  ct->ops.solve          = Solve_None;
  ct->problem            = ct->c ? "P_gamma" : "elasticity";
  PetscFunctionReturn(0);
}
