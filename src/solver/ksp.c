/* ksp.c: the linear solver of a controller's steps: the KSP made from the options (its types checked first, a
   combination that cannot work reported naming the options), and the elasticity solve without contact. */
#include "sg.h"

/* -<prefix>snes_type, -<prefix>ksp_type and -<prefix>pc_type name a registered method: checked before SetFromOptions,
   whose own message ("Unable to find requested KSP type ...") names neither the option nor a file. */
static PetscErrorCode TryType(MPI_Comm comm, PetscInt which, const char type[], PetscErrorCode *ierr)
{
  SNES snes = NULL;
  KSP  ksp  = NULL;
  PC   pc   = NULL;

  PetscFunctionBeginUser;
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  if (which == 0) {
    *ierr = SNESCreate(comm, &snes);
    if (!*ierr) *ierr = SNESSetType(snes, type);
  } else if (which == 1) {
    *ierr = KSPCreate(comm, &ksp);
    if (!*ierr) *ierr = KSPSetType(ksp, type);
  } else {
    *ierr = PCCreate(comm, &pc);
    if (!*ierr) *ierr = PCSetType(pc, type);
  }
  PetscCall(PetscPopErrorHandler());
  PetscCall(SNESDestroy(&snes));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(PCDestroy(&pc));
  PetscFunctionReturn(0);
}

/* ierr of a solver configuration step run under PetscReturnErrorHandler (SetFromOptions, the first set-up): a
   combination that cannot work (a factorization package without that factorization, an unknown
   -pc_factor_mat_solver_type) is reported naming the options to look at, with PETSc's message. */
PetscErrorCode SgSolverConfigured(MPI_Comm comm, PetscErrorCode ierr)
{
  int   bad = ierr ? 1 : 0;
  char *msg = NULL;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, comm));
  if (ierr) PetscErrorMessage(ierr, NULL, &msg);
  PetscCheck(!bad, comm, PETSC_ERR_USER_INPUT, "the solver options do not fit together (-ksp_type, -pc_type, -pc_factor_mat_solver_type, -snes_*): %s", msg ? msg : "(see the message of another rank)");
  PetscFunctionReturn(0);
}

PetscErrorCode SgCheckSolverTypes(MPI_Comm comm, const char prefix[])
{
  const char *what[3] = {"snes_type", "ksp_type", "pc_type"}, *kind[3] = {"nonlinear solver (SNES)", "Krylov method (KSP)", "preconditioner (PC)"};

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < 3; k++) {
    char           name[64], type[256];
    PetscBool      set;
    PetscErrorCode ierr = 0;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-%s%s", prefix ? prefix : "", what[k]));
    PetscCall(PetscOptionsGetString(NULL, NULL, name, type, sizeof(type), &set));
    if (!set) continue;
    PetscCheck(type[0], comm, PETSC_ERR_USER_INPUT, "%s is given without a value", name);
    PetscCall(TryType(comm, k, type, &ierr));
    PetscCheck(!ierr, comm, PETSC_ERR_USER_INPUT, "%s '%s': no such %s in this PETSc (see -help for the list)", name, type, kind[k]);
  }
  {
    char      name[64], type[256];
    PetscBool set, found = PETSC_FALSE, foundm = PETSC_FALSE;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-%spc_factor_mat_solver_type", prefix ? prefix : ""));
    PetscCall(PetscOptionsGetString(NULL, NULL, name, type, sizeof(type), &set));
    if (set) {
      PetscCheck(type[0], comm, PETSC_ERR_USER_INPUT, "%s is given without a value", name);
      /* a package registered for any matrix type and factorization (which combination fits is decided at set-up) */
      for (PetscInt f = MAT_FACTOR_LU; f <= MAT_FACTOR_QR && !found; f++) PetscCall(MatSolverTypeGet(type, MATSEQAIJ, (MatFactorType)f, &found, &foundm, NULL));
      PetscCheck(found, comm, PETSC_ERR_USER_INPUT, "%s '%s': no such factorization package in this PETSc (e.g. mumps, petsc, superlu, superlu_dist)", name, type);
    }
  }
  PetscFunctionReturn(0);
}

/* The linear solver of every step of a controller: a KSP with the options under the prefix on J, a working copy of K
   (with the rigid-body near null space if asked for), def the problem's default solver (NULL: none); the types are
   checked first, and a combination that fails in
   KSPSetFromOptions is reported naming the solver options. */
PetscErrorCode SgLinearSolverCreate(SgElasticity el, const char prefix[], const SgLinearDefault *def, KSP *ksp, Mat *J)
{
  MPI_Comm       comm;
  Mat            K;
  MatNullSpace   nsp;
  PetscErrorCode ierr;
  PetscBool      entered[SG_LINEAR_DEFAULT_NAMG];

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetComm(el, &comm));
  PetscCall(SgElasticityGetOperators(el, &K, NULL));
  PetscCall(SgElasticityGetNearNullSpace(el, &nsp));
  PetscCall(MatDuplicate(K, MAT_COPY_VALUES, J));
  if (nsp) PetscCall(MatSetNearNullSpace(*J, nsp));
  PetscCall(MatSetOption(*J, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  PetscCall(KSPCreate(comm, ksp));
  PetscCall(KSPSetOptionsPrefix(*ksp, prefix));
  PetscCall(KSPSetOperators(*ksp, *J, *J));
  PetscCall(SgCheckSolverTypes(comm, prefix));
  PetscCall(SgLinearSolverSetDefault(*ksp, def, entered)); /* the problem's default solver (linear.c), if it applies */
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = KSPSetFromOptions(*ksp);
  PetscCall(PetscPopErrorHandler());
  PetscCall(SgLinearSolverEndDefault(*ksp, def, entered));
  PetscCall(SgSolverConfigured(comm, ierr));
  PetscFunctionReturn(0);
}

/* After a failed solve: the KSP's preconditioner, if it has a safer configuration to fall back on (the truncated
   multigrid's l1 Gauss-Seidel smoothers in place of PCSOR's local sweeps on several ranks, tmg.c), takes it; *done
   says whether it did (then the solve is worth redoing) */
PetscErrorCode SgLinearSolverFallback(KSP ksp, PetscBool *done)
{
  PC pc;
  PetscErrorCode (*f)(PC, PetscBool *) = NULL;

  PetscFunctionBeginUser;
  *done = PETSC_FALSE;
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectQueryFunction((PetscObject)pc, "SgLinearSolverFallback_C", &f));
  if (f) PetscCall((*f)(pc, done));
  PetscFunctionReturn(0);
}

/* The elasticity solve without contact, K y = b, with the controller's linear solver (so a factorization's symbolic
   phase is shared with the later steps); the times of the preconditioner set-up and of the solve. */
PetscErrorCode SgLinearSolveUnconstrained(SgElasticity el, KSP ksp, Mat J, Vec y, PetscInt *its, KSPConvergedReason *kr, PetscLogDouble *t_setup, PetscLogDouble *t_solve)
{
  MPI_Comm       comm;
  Mat            K;
  Vec            b;
  PetscErrorCode ierr;
  PetscLogDouble t0, t1, t2;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetComm(el, &comm));
  PetscCall(SgElasticityGetOperators(el, &K, &b));
  PetscCall(PetscLogEventBegin(SG_LinearSolve, 0, 0, 0, 0));
  PetscCall(MatCopy(K, J, SAME_NONZERO_PATTERN));
  {
    Mat Kf = NULL, Pf = NULL; /* the SSN's contact frames (FrameSetUp): the KSP solves with Q^T K Q */
    PetscCall(PetscObjectQuery((PetscObject)ksp, "SgFrameStiffness", (PetscObject *)&Kf));
    PetscCall(PetscObjectQuery((PetscObject)ksp, "SgFramePmat", (PetscObject *)&Pf));
    if (Pf) PetscCall(MatCopy(Kf, Pf, SAME_NONZERO_PATTERN));
    PetscCall(KSPSetOperators(ksp, Pf ? Pf : J, Pf ? Pf : J));
  }
  PetscCall(PetscTime(&t0));
  /* the first set-up of the linear solver is where some configurations that cannot work fail */
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = KSPSetUp(ksp);
  PetscCall(PetscPopErrorHandler());
  PetscCall(SgSolverConfigured(comm, ierr));
  PetscCall(PetscTime(&t1));
  PetscCall(KSPSolve(ksp, b, y));
  PetscCall(KSPGetIterationNumber(ksp, its));
  PetscCall(KSPGetConvergedReason(ksp, kr));
  if (*kr < 0) { /* a fallback of the preconditioner (SgLinearSolverFallback): the solve again, its iterations added */
    PetscBool done, nz;
    PetscInt  its2;
    PetscCall(SgLinearSolverFallback(ksp, &done));
    if (done) {
      PetscCall(PetscPrintf(comm, "  the elasticity solve without contact: KSP %s after %" PetscInt_FMT " iterations with PCSOR's local smoothers; solved again with the l1 Gauss-Seidel smoothers, and so from here on\n", KSPConvergedReasons[*kr], *its));
      PetscCall(KSPGetInitialGuessNonzero(ksp, &nz));
      if (!nz) PetscCall(VecZeroEntries(y));
      PetscCall(KSPSolve(ksp, b, y));
      PetscCall(KSPGetIterationNumber(ksp, &its2));
      PetscCall(KSPGetConvergedReason(ksp, kr));
      *its += its2;
    }
  }
  PetscCall(PetscTime(&t2));
  if (t_setup) *t_setup = t1 - t0;
  if (t_solve) *t_solve = t2 - t1;
  PetscCall(PetscLogEventEnd(SG_LinearSolve, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}
