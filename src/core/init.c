/* events.c: log events (-log_view) and the registration of every registry. */
#include "signorini.h"

PetscLogEvent SG_MeshSetUp, SG_Assembly, SG_ContactSetUp, SG_Residual, SG_Jacobian, SG_ActiveSet, SG_LinearSolve, SG_ContStep, SG_Output;

static PetscErrorCode SgFinalizePackage(void)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&SgObstacleList));
  PetscCall(PetscFunctionListDestroy(&SgContList));
  PetscFunctionReturn(0);
}

PetscErrorCode SgRegisterAll(void)
{
  static PetscBool done = PETSC_FALSE;
  PetscClassId     cid;

  PetscFunctionBeginUser;
  if (done) PetscFunctionReturn(0);
  done = PETSC_TRUE;
  PetscCall(PetscRegisterFinalize(SgFinalizePackage));
  PetscCall(PetscClassIdRegister("Signorini", &cid));
  PetscCall(PetscLogEventRegister("SgMeshSetUp", cid, &SG_MeshSetUp));
  PetscCall(PetscLogEventRegister("SgAssembly", cid, &SG_Assembly));
  PetscCall(PetscLogEventRegister("SgContactSetUp", cid, &SG_ContactSetUp));
  PetscCall(PetscLogEventRegister("SgResidual", cid, &SG_Residual));
  PetscCall(PetscLogEventRegister("SgJacobian", cid, &SG_Jacobian));
  PetscCall(PetscLogEventRegister("SgActiveSet", cid, &SG_ActiveSet));
  PetscCall(PetscLogEventRegister("SgLinearSolve", cid, &SG_LinearSolve));
  PetscCall(PetscLogEventRegister("SgContStep", cid, &SG_ContStep));
  PetscCall(PetscLogEventRegister("SgOutput", cid, &SG_Output));
  PetscCall(SgObstacleRegister("plane", SgObstacleCreate_Plane));
  PetscCall(SgObstacleRegister("parabola", SgObstacleCreate_Parabola));
  PetscCall(SgObstacleRegister("ball", SgObstacleCreate_Ball));
  PetscCall(SgContRegister("none", SgContCreate_None));
  PetscCall(SgContRegister("alm", SgContCreate_ALM));
  PetscCall(SgContRegister("pf", SgContCreate_PF));
  PetscCall(SgContRegister("ipf", SgContCreate_IPF));
  PetscCall(SgContRegister("pdas", SgContCreate_PDAS));
  PetscCall(SgContRegister("vi", SgContCreate_VI));
  PetscFunctionReturn(0);
}
