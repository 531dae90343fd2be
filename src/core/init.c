/* core/init.c: the log events (-log_view). The type registries belong to their layers (SgObstacleRegisterAll,
   SgContRegisterAll); SgInitializePackage (cont/cont.c) calls them all. */
#include "sg.h"

PetscClassId  SG_PROBLEM_CLASSID, SG_CONT_CLASSID;
PetscLogEvent SG_MeshSetUp, SG_Assembly, SG_ContactSetUp, SG_Residual, SG_Jacobian, SG_ActiveSet, SG_LinearSolve, SG_ContStep, SG_Output;

PetscErrorCode SgLogEventsRegister(void)
{
  static PetscBool done = PETSC_FALSE;
  PetscClassId     cid;

  PetscFunctionBeginUser;
  if (done) PetscFunctionReturn(0);
  done = PETSC_TRUE;
  PetscCall(PetscClassIdRegister("Signorini", &cid));
  PetscCall(PetscClassIdRegister("SgProblem", &SG_PROBLEM_CLASSID));
  PetscCall(PetscClassIdRegister("SgCont", &SG_CONT_CLASSID));
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

/* arg-th argument of fn must be a PETSc object of class classid (cname in the message): not NULL, not destroyed */
PetscErrorCode SgValidObject(PetscObject obj, PetscClassId classid, const char cname[], const char fn[], int arg)
{
  PetscClassId id;

  PetscFunctionBeginUser;
  PetscCheck(obj, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "%s: argument %d (a %s) is NULL", fn, arg, cname);
  PetscCall(PetscObjectGetClassId(obj, &id)); /* -1: PETSc's mark of a freed header (PETSCFREEDHEADER) */
  PetscCheck(id != (PetscClassId)-1, PETSC_COMM_SELF, PETSC_ERR_ARG_CORRUPT, "%s: argument %d (a %s) was already destroyed", fn, arg, cname);
  PetscCheck(id == classid, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "%s: argument %d is not a %s", fn, arg, cname);
  PetscFunctionReturn(0);
}
