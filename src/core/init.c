/* core/init.c: the log events (-log_view). The type registries belong to their layers (SgObstacleRegisterAll,
   SgContRegisterAll); SgInitializePackage (cont/cont.c) calls them all. */
#include "sg.h"

PetscLogEvent SG_MeshSetUp, SG_Assembly, SG_ContactSetUp, SG_Residual, SG_Jacobian, SG_ActiveSet, SG_LinearSolve, SG_ContStep, SG_Output;

PetscErrorCode SgLogEventsRegister(void)
{
  static PetscBool done = PETSC_FALSE;
  PetscClassId     cid;

  PetscFunctionBeginUser;
  if (done) PetscFunctionReturn(0);
  done = PETSC_TRUE;
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
  PetscFunctionReturn(0);
}
