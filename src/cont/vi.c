/* cont_vi.c: baseline: PETSc's own variational-inequality Newton solvers (SNESVINEWTONRSLS / SNESVINEWTONSSLS) on the
   same discrete problem, as bounds on the normal displacement component. Where a contact normal is not a coordinate
   axis the problem is posed in each contact vertex's frame (SgContBoundFrame, solver/frame.c): y_f = Q^T y, the
   stiffness Q^T K Q, the load Q^T b, the bound on the frame's normal dof. Options: -vi_snes_*, -vi_ksp_*. */
#include "cont/contimpl.h"

typedef struct {
  SNES snes;
  Mat  J; /* SNESVINEWTONSSLS scales its Jacobian in place: never hand it the stiffness itself */
  Mat  K; /* the stiffness and load of the bound-constrained problem: K and b, or Q^T K Q and Q^T b in the frames */
  Vec  b;
} VI;

static PetscErrorCode Residual_VI(SNES snes, Vec y, Vec F, void *ctx)
{
  VI *vi = (VI *)ctx;

  PetscFunctionBeginUser;
  PetscCall(MatMult(vi->K, y, F));
  PetscCall(VecAXPY(F, -1.0, vi->b));
  PetscFunctionReturn(0);
}

static PetscErrorCode Jacobian_VI(SNES snes, Vec y, Mat J, Mat P, void *ctx)
{
  VI *vi = (VI *)ctx;

  PetscFunctionBeginUser;
  PetscCall(MatCopy(vi->K, P, SAME_NONZERO_PATTERN));
  PetscFunctionReturn(0);
}

static PetscErrorCode Solve_VI(SgCont ct)
{
  VI                 *vi = (VI *)ct->data;
  PetscReal           Knorm, bnorm;
  char                prefix[256];
  Vec                 xl, xu, r;
  PetscInt           *axis, its, kits;
  PetscReal          *sign;
  PetscScalar        *la, *ua;
  SgFrame             f = NULL;
  Vec                 yw, bf = NULL; /* the iterate and the load in the frames (ct->y and b without) */
  SNESConvergedReason reason;
  PetscBool           ok;
  SgHistoryRow        row;
  PetscLogDouble      t;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetOperators(ct->prob, &vi->K, &vi->b));
  PetscCall(SgElasticityGetScales(ct->prob, &Knorm, &bnorm, NULL));
  PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "%svi_", ((PetscObject)ct)->prefix ? ((PetscObject)ct)->prefix : ""));
  PetscCall(PetscMalloc2(ct->n, &axis, ct->n, &sign));
  PetscCall(SgContBoundFrame(ct, "-cont_type vi", PETSC_FALSE, &f, axis, sign));
  PetscCall(SgContStart(ct, &ok));
  if (!ok) {
    PetscCall(SgFrameDestroy(&f));
    PetscCall(PetscFree2(axis, sign));
    PetscFunctionReturn(0);
  }
  yw = ct->y;
  if (f) { /* the problem in the frames: bounds on single dofs */
    PetscCall(SgFrameGetStiffness(f, &vi->K));
    PetscCall(VecDuplicate(vi->b, &bf));
    PetscCall(VecCopy(vi->b, bf));
    PetscCall(SgFrameToLocal(f, bf));
    vi->b = bf;
    PetscCall(VecDuplicate(ct->y, &yw));
    PetscCall(VecCopy(ct->y, yw));
    PetscCall(SgFrameToLocal(f, yw));
  }
  PetscCall(VecDuplicate(vi->b, &xl));
  PetscCall(VecDuplicate(vi->b, &xu));
  PetscCall(VecDuplicate(vi->b, &r));
  PetscCall(VecSet(xl, PETSC_NINFINITY));
  PetscCall(VecSet(xu, PETSC_INFINITY));
  PetscCall(VecGetArray(xl, &la));
  PetscCall(VecGetArray(xu, &ua));
  for (PetscInt i = 0; i < ct->n; i++) { /* sign * y_axis <= d */
    if (sign[i] > 0) ua[ct->off[i] + axis[i]] = ct->d[i];
    else la[ct->off[i] + axis[i]] = -ct->d[i];
  }
  PetscCall(VecRestoreArray(xl, &la));
  PetscCall(VecRestoreArray(xu, &ua));
  PetscCall(SNESDestroy(&vi->snes)); /* a load step's solve: a new SNESVI with the new bounds */
  PetscCall(MatDestroy(&vi->J));
  PetscCall(SNESCreate(ct->comm, &vi->snes));
  PetscCall(SgCheckSolverTypes(ct->comm, prefix));
  PetscCall(SNESSetOptionsPrefix(vi->snes, prefix));
  PetscCall(SNESSetType(vi->snes, SNESVINEWTONRSLS));
  {
    /* absolute floor at the round-off of the problem's force scale: from the unconstrained start of a problem that
       touches little or nothing, ||F_0|| is itself round-off and no relative decrease can be reached; positive even
       without any load, where F_0 = 0 must count as converged */
    PetscReal ynorm;
    PetscCall(VecNorm(ct->y, NORM_2, &ynorm));
    PetscCall(SNESSetTolerances(vi->snes, 100 * PETSC_MACHINE_EPSILON * (Knorm * ynorm + bnorm) + 1e-300, 1e-12, 0.0, 100, PETSC_DEFAULT));
  }
  PetscCall(SNESSetFunction(vi->snes, r, Residual_VI, vi));
  PetscCall(MatDuplicate(vi->K, MAT_COPY_VALUES, &vi->J));
  PetscCall(SNESSetJacobian(vi->snes, vi->J, vi->J, Jacobian_VI, vi));
  PetscCall(SNESVISetVariableBounds(vi->snes, xl, xu));
  {
    PetscErrorCode ierr;
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = SNESSetFromOptions(vi->snes);
    PetscCall(PetscPopErrorHandler());
    PetscCall(SgSolverConfigured(ct->comm, ierr));
  }
  ct->outer = 1;
  PetscCall(SgContAddGamma(ct, SG_NAN));
  PetscCall(PetscLogEventBegin(SG_ContStep, 0, 0, 0, 0));
  PetscCall(SNESSolve(vi->snes, NULL, yw));
  PetscCall(PetscLogEventEnd(SG_ContStep, 0, 0, 0, 0));
  PetscCall(SNESGetIterationNumber(vi->snes, &its));
  PetscCall(SNESGetLinearSolveIterations(vi->snes, &kits));
  PetscCall(SNESGetConvergedReason(vi->snes, &reason));
  ct->ssn_its += its;
  ct->ksp_its += kits;
  if (f) {
    PetscCall(VecCopy(yw, ct->y));
    PetscCall(SgFrameToGlobal(f, ct->y));
  }
  /* the multiplier balances the normal residual at the contact vertices */
  PetscCall(SgContactMultiplierFromResidual(ct->c, ct->y, ct->lam));
  PetscCall(SgContMeasure(ct));
  PetscCall(PetscTime(&t));
  PetscCall(SgHistoryRowInit(&row));
  row.kind    = 's';
  row.outer   = 1;
  row.it      = its;
  row.active  = ct->kkt.nactive;
  row.ksp_its = kits;
  row.time    = t - ct->t0;
  PetscCall(SgElasticityEnergy(ct->prob, ct->y, &row.V));
  PetscCall(SgHistoryAdd(ct->hist, &row));
  PetscCall(SgContOuterRow(ct, its, NULL));
  if (reason > 0) {
    ct->converged = PETSC_TRUE;
    PetscCall(PetscSNPrintf(ct->reason, sizeof(ct->reason), "VI_%s", SNESConvergedReasons[reason]));
  } else PetscCall(SgContFail(ct, "VI_%s after %" PetscInt_FMT " iterations (see -vi_snes_type, -vi_snes_max_it, -vi_ksp_type)", SNESConvergedReasons[reason], its));
  PetscCall(SgContCheckBaseline(ct));
  {
    SNESType type;
    PetscCall(SNESGetType(vi->snes, &type));
    PetscCall(SgSummarySetString(ct->sum, "vi_type", type));
  }
  PetscCall(VecDestroy(&xl));
  PetscCall(VecDestroy(&xu));
  PetscCall(VecDestroy(&r));
  if (f) PetscCall(VecDestroy(&yw));
  PetscCall(VecDestroy(&bf));
  vi->b = NULL;
  vi->K = NULL;
  PetscCall(SgFrameDestroy(&f));
  PetscCall(PetscFree2(axis, sign));
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_VI(SgCont ct)
{
  VI *vi = (VI *)ct->data;

  PetscFunctionBeginUser;
  PetscCall(SNESDestroy(&vi->snes));
  PetscCall(MatDestroy(&vi->J));
  PetscFunctionReturn(0);
}

static PetscErrorCode View_VI(SgCont ct, PetscViewer viewer)
{
  VI         *vi     = (VI *)ct->data;
  const char *prefix = ((PetscObject)ct)->prefix;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "; PETSc's SNESVI on the normal displacement components, its options -%svi_snes_*, -%svi_ksp_*\n", prefix ? prefix : "", prefix ? prefix : ""));
  if (vi->snes) {
    SNESType type;
    PetscCall(SNESGetType(vi->snes, &type));
    PetscCall(PetscViewerASCIIPrintf(viewer, " (%s)", type));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SgContCreate_VI(SgCont ct)
{
  VI *vi;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&vi));
  ct->data          = vi;
  ct->ops.solve     = Solve_VI;
  ct->ops.destroy   = Destroy_VI;
  ct->ops.view      = View_VI;
  ct->ops.needs_ssn = PETSC_FALSE; /* PETSc's SNESVI solves (P) itself */
  PetscFunctionReturn(0);
}
