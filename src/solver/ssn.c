/* ssn.c: semismooth Newton (primal-dual active set) solver for (P_gamma), handed to SNES.
   Residual F(y) = K y - b + sum_i w_i max(0, lamhat_i + gamma g_i(y)) n_i; Jacobian K + gamma sum_{A} w_i n_i n_i^T;
   full Newton steps; converged when the active set stops changing (and, for inexact linear solves, ||F|| is small).
   Here the object (options, create with its SNES, frames, condensation or truncated multigrid; destroy; accessors) and
   the solve; the residual is in residual.c, the Jacobian in jacobian.c, the friction terms in friction.c, the
   convergence test, reasons and monitor in convergence.c, what a failed solve does next (sparse LU, Coulomb's fixed
   point) in fallback.c, the linear solver in ksp.c. */
#include "solver/ssnimpl.h"

static const char *const SgTMGInterps[] = {"amg", "geometric"};

/* The SSN's options, their defaults in s, condense, tmg (and its interpolations: 0 the AMG's, 1 the mesh
   hierarchy's) and frame (also listed by SgSSNPrintHelp) */
static PetscErrorCode SSNOptions(PetscOptionItems *PetscOptionsObject, SgSSN s, PetscBool *condense, PetscBool *tmg, PetscInt *interp, PetscBool *frame)
{
  PetscBool tset, iset;

  PetscFunctionBeginUser;
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-ssn_monitor", "Print active-set size, changes, residuals and KSP iterations per SSN iteration", &s->monitor, NULL));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-ssn_condense", "Condense the linear solves onto the contact dofs: factor K once (MUMPS, with its Schur complement), then only a dense matrix per SSN step (one rank)", condense, NULL));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-ssn_pc_truncated_mg", "Precondition with multigrid on the interpolations of the AMG of the first solve (-pc_type hypre or gamg), the finest one truncated at the active normal dofs, coarse operators by Galerkin products: no new AMG setup per active set", tmg, &tset));
  PetscCall(PetscOptionsEList("-ssn_pc_truncated_mg_interp", "The truncated multigrid's interpolations: amg (of the KSP's AMG) or geometric (of the mesh hierarchy of -dm_refine N, N >= 1; turns -ssn_pc_truncated_mg on; the default of the iterative default solver where the mesh kept every level, as nested iteration's default does)", NULL, SgTMGInterps, 2, SgTMGInterps[*interp], interp, &iset));
  PetscCheck(!(iset && *interp == 1 && tset && !*tmg), PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "-ssn_pc_truncated_mg_interp geometric is the truncated multigrid on the mesh hierarchy: it contradicts -ssn_pc_truncated_mg false");
  if (*interp == 1) *tmg = PETSC_TRUE;
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-ssn_pc_truncated_mg_coarse_ptap", "Truncated multigrid on several ranks: carry each SSN step's correction of the coarse operators down the levels by MatPtAP over the kept operators' whole patterns instead of over the coarse rows it touches; the same operators to round-off, slower (a check of the default)", &s->tmg_coarse_ptap, NULL));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-ssn_pc_truncated_mg_l1gs_symmetric", "Truncated multigrid on several ranks: each application of the l1 Gauss-Seidel smoother is a forward sweep then a backward one over the rank's rows (symmetric, as PCSOR's local sweeps, with the l1 terms: still convergent) instead of one sweep (forward down, backward up); default off (fewer CG iterations, more time: bench/results.md l1sym); no effect on one rank (PCSOR)", &s->tmg_l1gs_sym, &s->tmg_l1gs_sym_set));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-ssn_pc_truncated_mg_local_sor", "Truncated multigrid on several ranks: smooth with PCSOR's local symmetric sweeps (block Jacobi across ranks: fewer CG iterations, no guarantee) and, when a linear solve fails, with the l1 Gauss-Seidel sweeps from then on, that solve redone; default on for two bodies (-contact_master_ids) in the dual-mortar basis unless -ssn_pc_truncated_mg_l1gs_symmetric or _global is given, off otherwise (the l1 Gauss-Seidel sweeps); no effect on one rank (PCSOR, one sweep each way) nor with GAMG", &s->tmg_sor, &s->tmg_sor_set));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-ssn_pc_truncated_mg_l1gs_global", "With the symmetric l1 Gauss-Seidel smoother (-ssn_pc_truncated_mg_l1gs_symmetric): update the whole residual between the forward and the backward sweep (one product with the operator and its communication per application: two l1 Gauss-Seidel steps composed, still convergent) instead of the rank's own rows' residual", &s->tmg_l1gs_glob, &s->tmg_l1gs_glob_set));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-ssn_pc_truncated_mg_deflate", "Truncated multigrid with CG: deflate the smallest eigenvalues of the preconditioned Jacobian, their vectors the Ritz vectors of the previous CG solve (balanced deflation: the preconditioner stays symmetric positive definite; a few vectors, no product with the Jacobian per iteration)", &s->tmg_defl, &s->tmg_defl_set));
  PetscCall(SgOptionsIntValue(PetscOptionsObject, "-ssn_pc_truncated_mg_deflate_max", "With -ssn_pc_truncated_mg_deflate: the deflation space's maximum size (1..64; the newest Ritz vectors kept)", &s->tmg_defl_max, NULL));
  PetscCheck(s->tmg_defl_max >= 1 && s->tmg_defl_max <= 64, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "-ssn_pc_truncated_mg_deflate_max %" PetscInt_FMT ": must be 1..64", s->tmg_defl_max);
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-ssn_pc_truncated_mg_deflate_ritz", "With -ssn_pc_truncated_mg_deflate: the Ritz values (of the preconditioned Jacobian, whose largest are about 1) below this join the deflation space", &s->tmg_defl_ritz, NULL));
  PetscCheck(s->tmg_defl_ritz > 0 && s->tmg_defl_ritz < 1, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "-ssn_pc_truncated_mg_deflate_ritz %g: must lie in (0, 1)", (double)s->tmg_defl_ritz);
  PetscCall(SgOptionsIntValue(PetscOptionsObject, "-ssn_coulomb_fp_max_it", "Coulomb: when the Newton iteration on the coupled law fails, at most this many steps of a fixed point on the Tresca bound s = F lam_N (0: none)", &s->fp_max_it, NULL));
  PetscCall(SgOptionsIntValue(PetscOptionsObject, "-ssn_coulomb_fp_m", "Coulomb: the number of past steps in the Anderson acceleration of that fixed point", &s->fp_m, NULL));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-ssn_coulomb_fp_omega", "Coulomb: the damping of that fixed point's steps (0 < omega <= 1)", &s->fp_omega, NULL));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-ssn_coulomb_fp_rtol", "Coulomb: that fixed point ends when |F lam_N - s| <= rtol max F lam_N", &s->fp_rtol, NULL));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-ssn_frame", "Solve the linear systems in each contact vertex's frame (n, t1, t2) where its normal is not a coordinate axis (curved or tilted contact): the contact term becomes a diagonal entry, which AMG, the truncated multigrid, condensation and the bound-constrained solvers need", frame, NULL));
  {
    PetscBool global = (PetscBool)!s->frame_local;
    PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-ssn_frame_global", "With -ssn_frame, where every contact normal is the same direction (a plane obstacle, a flat contact face): rotate the whole body into one frame (the normal and the body's principal axes), so that the AMG sees a body turned rigidly as the unturned one; false: the contact vertices alone", &global, NULL));
    s->frame_local = (PetscBool)!global;
  }
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-ssn_pair_transform", "Two bodies (-contact_master_ids): solve the linear systems in the dual-mortar basis u = T v (v_s = u_s - D^-1 M u_m at the slave contact vertices) and the frames of the slave normals, where every condition of the pair is one diagonal entry, as against a rigid obstacle: AMG and the truncated multigrid then apply (default: on with an iterative linear solver, off with a direct one)", &s->pair_transform, &s->pair_transform_set));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-ssn_pair_transform_ptap", "With -ssn_pair_transform: form the transformed stiffness (T Q)^T K (T Q) and the interpolations (T Q)^-1 P by general sparse products (MatPtAP, MatMatMult) instead of K's and P's values corrected on the pair's rows and columns; the same matrices to round-off, slower (a check of the default)", &s->pair_ptap, NULL));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-ssn_pair_amg_displacements", "Two bodies in the dual-mortar basis with the truncated multigrid: set its AMG up on the stiffness in the displacements (the two bodies apart) and take the finest interpolation into the basis, (T Q)^-1 P, so that its coarse operators are the bodies' own; false: the AMG of the transformed stiffness (T Q)^T K (T Q)", &s->pair_amg_u, NULL));
  PetscCall(SgOptionsIntValue(PetscOptionsObject, "-ssn_pc_reuse_its", "Within one (P_gamma), keep the previous step's preconditioner while the last linear solve took at most this many iterations (0: rebuild every step)", &s->pc_reuse_its, NULL));
  PetscFunctionReturn(0);
}

/* -help without a problem (bin/signorini -help): the SSN's options and their defaults, as SgSSNCreate reads them */
PetscErrorCode SgSSNPrintHelp(MPI_Comm comm, const char prefix[])
{
  struct _n_SgSSN s;
  PetscBool       help, condense = PETSC_FALSE, tmg = PETSC_FALSE, frame = PETSC_TRUE;
  PetscInt        interp = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  if (!help) PetscFunctionReturn(0);
  PetscCall(PetscMemzero(&s, sizeof(s)));
  s.fp_max_it     = 50;
  s.pair_amg_u    = PETSC_TRUE;
  s.fp_omega      = 1;
  s.fp_m          = 8;
  s.fp_rtol       = 1e-13;
  s.tmg_defl_max  = SG_DEFL_MAX;
  s.tmg_defl_ritz = SG_DEFL_RITZ;
  PetscOptionsBegin(comm, prefix, "Semismooth Newton (active set) solver", NULL);
  PetscCall(SSNOptions(PetscOptionsObject, &s, &condense, &tmg, &interp, &frame));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

/* A and B sequential AIJ with the same nonzero pattern (false if either is not SeqAIJ) */
PetscErrorCode SgSeqAIJSamePattern(Mat A, Mat B, PetscBool *same)
{
  PetscBool       sa, sb, fa, fb;
  const PetscInt *ia, *ja, *ib, *jb;
  PetscInt        na, nb;

  PetscFunctionBeginUser;
  *same = PETSC_FALSE;
  PetscCall(PetscObjectTypeCompare((PetscObject)A, MATSEQAIJ, &sa));
  PetscCall(PetscObjectTypeCompare((PetscObject)B, MATSEQAIJ, &sb));
  if (!sa || !sb) PetscFunctionReturn(0);
  PetscCall(MatGetRowIJ(A, 0, PETSC_FALSE, PETSC_FALSE, &na, &ia, &ja, &fa));
  PetscCall(MatGetRowIJ(B, 0, PETSC_FALSE, PETSC_FALSE, &nb, &ib, &jb, &fb));
  if (fa && fb && na == nb) {
    PetscCall(PetscArraycmp(ia, ib, na + 1, same));
    if (*same) PetscCall(PetscArraycmp(ja, jb, ia[na], same));
  }
  PetscCall(MatRestoreRowIJ(A, 0, PETSC_FALSE, PETSC_FALSE, &na, &ia, &ja, &fa));
  PetscCall(MatRestoreRowIJ(B, 0, PETSC_FALSE, PETSC_FALSE, &nb, &ib, &jb, &fb));
  PetscFunctionReturn(0);
}

/* -ssn_frame: the Jacobians are assembled in the contact frames into Pf (a copy of Q^T K Q) and the KSP solves with
   it in the frames (SgFrameAttachKSP); the elasticity solve without contact takes Q^T K Q (SgLinearSolveUnconstrained
   finds both on the KSP). Pf is the working matrix J itself where Q^T K Q has J's pattern (one rank: the frame rotates
   a copy of K in place): J, the controller's copy of K, has no other use in the frames, and one copy of K less is
   kept (about 12 % of the peak memory of Example 2 at 1.07e6 unknowns). */
static PetscErrorCode FrameSetUp(SgSSN s, KSP ksp)
{
  MatNullSpace nsp;
  PetscBool    same;

  PetscFunctionBeginUser;
  PetscCall(SgFrameGetStiffness(s->frame, &s->Klin));
  PetscCall(SgSeqAIJSamePattern(s->Klin, s->J, &same));
  if (same) {
    PetscCall(MatCopy(s->Klin, s->J, SAME_NONZERO_PATTERN));
    PetscCall(PetscObjectReference((PetscObject)s->J));
    s->Pf = s->J;
  } else PetscCall(MatDuplicate(s->Klin, MAT_COPY_VALUES, &s->Pf));
  PetscCall(MatGetNearNullSpace(s->Klin, &nsp));
  if (nsp) PetscCall(MatSetNearNullSpace(s->Pf, nsp));
  PetscCall(MatSetOption(s->Pf, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  if (s->cv.props.coupled) {
    PetscCall(MatSetOption(s->Pf, MAT_SPD, PETSC_FALSE));
    PetscCall(MatSetOption(s->Pf, MAT_SYMMETRIC, PETSC_FALSE));
  }
  PetscCall(SNESSetJacobian(s->snes, s->Pf, s->Pf, SgSSNJacobian, s));
  PetscCall(SgFrameAttachKSP(s->frame, ksp));
  PetscCall(PetscObjectCompose((PetscObject)ksp, "SgFrameStiffness", (PetscObject)s->Klin));
  PetscCall(PetscObjectCompose((PetscObject)ksp, "SgFramePmat", (PetscObject)s->Pf));
  PetscFunctionReturn(0);
}

/* x (a vector of the SSN's KSP during its solve, e.g. KSPBuildSolution's) in the original coordinates, in place */
PetscErrorCode SgSSNKSPVectorToGlobal(SgSSN s, Vec x)
{
  PetscFunctionBeginUser;
  if (s->frame) PetscCall(SgFrameToGlobal(s->frame, x));
  PetscFunctionReturn(0);
}

/* The SSN solver of (P_gamma) on the contact boundary c, its SNES (options under the prefix) solving with the linear
   solver ksp on the working matrix J (SgLinearSolverCreate); its options are read by SgSSNSetFromOptions, after the
   program's defaults (SgSSNSetCondense, SgSSNSetTruncatedMG). */
PetscErrorCode SgSSNCreate(SgElasticity p, SgContact c, const char prefix[], KSP ksp, Mat J, SgSSN *ssn)
{
  SgSSN          s;
  SNESLineSearch ls;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&s));
  s->prob  = p;
  s->c     = c;
  s->gamma = 1;
  PetscCall(SgElasticityGetComm(p, &s->comm));
  PetscCall(SgElasticityGetDimension(p, &s->dim));
  PetscCall(SgElasticityGetMesh(p, &s->mesh));
  PetscCall(SgElasticityGetOperators(p, &s->K, &s->b));
  PetscCall(SgElasticityGetMass(p, &s->mass));
  s->prob = p;
  PetscCall(SgSSNUpdateLoad(s));
  if (c) {
    PetscCall(SgContactGetView(c, &s->cv));
    PetscCall(SgContactGetVertices(c, &s->n, &s->nglobal, &s->vert, &s->off));
    PetscCall(SgContactGetWeights(c, &s->w));
    PetscCall(SgContactGetNormals(c, &s->normal));
    PetscCall(SgContactGetGaps(c, &s->d));
  }
  PetscCall(PetscTime(&s->t0));
  PetscCall(PetscObjectReference((PetscObject)J));
  s->J = J;
  if (s->cv.props.coupled) { /* the coupling t n^T of the slip set */
    PetscCall(MatSetOption(J, MAT_SPD, PETSC_FALSE));
    PetscCall(MatSetOption(J, MAT_SYMMETRIC, PETSC_FALSE));
  }
  PetscCall(VecDuplicate(s->b, &s->r));
  PetscCall(PetscMalloc5(s->n, &s->g, s->n, &s->m, s->n, &s->act, s->n, &s->actjac, s->n, &s->lamhat));
  for (PetscInt i = 0; i < s->n; i++) s->lamhat[i] = 0;
  if (c) { /* the law's tangential state, sized by it (no arrays without friction) */
    PetscCall(SgContactLawStateCreate(s->cv.law, &s->lst));
    PetscCall(SgContactLawStateGetArrays(s->lst, &s->lamhatT, &s->mT, &s->fst));
    PetscCall(SgContactLawStateGetJacobianArrays(s->lst, &s->fstjac, &s->tjac));
  }
  PetscCall(PetscCalloc2(s->n * s->dim + 1, &s->uv, s->n * s->dim + 1, &s->ft));
  PetscCall(PetscCalloc1(s->n + 1, &s->fforce));
  PetscCall(SNESCreate(s->comm, &s->snes));
  PetscCall(SNESSetOptionsPrefix(s->snes, prefix));
  PetscCall(SNESSetKSP(s->snes, ksp));
  PetscCall(SNESSetType(s->snes, SNESNEWTONLS));
  PetscCall(SNESGetLineSearch(s->snes, &ls));
  PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHBASIC));
  PetscCall(SNESSetFunction(s->snes, s->r, SgSSNResidual, s));
  PetscCall(SNESSetJacobian(s->snes, s->J, s->J, SgSSNJacobian, s));
  PetscCall(SNESSetConvergenceTest(s->snes, SgSSNConverged, s, NULL));
  PetscCall(SNESLineSearchSetPreCheck(ls, SgSSNFrictionPreCheck, s)); /* the law's step correction (none without friction) */
  PetscCall(SNESMonitorSet(s->snes, SgSSNMonitor, s, NULL));
  PetscCall(SNESSetTolerances(s->snes, PETSC_DEFAULT, 1e-10, PETSC_DEFAULT, 100, PETSC_DEFAULT));
  s->fp_max_it     = 50;
  s->pair_amg_u    = PETSC_TRUE;
  s->fp_omega      = 1;
  s->fp_m          = 8;
  s->fp_rtol       = 1e-13;
  s->tmg_defl_max  = SG_DEFL_MAX;
  s->tmg_defl_ritz = SG_DEFL_RITZ;
  *ssn             = s;
  PetscFunctionReturn(0);
}

/* The default of -ssn_condense (the default linear solver's, linear.c); before SgSSNSetFromOptions */
PetscErrorCode SgSSNSetCondense(SgSSN s, PetscBool condense)
{
  PetscFunctionBeginUser;
  PetscCheck(!s->snes_setfromoptions, s->comm, PETSC_ERR_ORDER, "SgSSNSetCondense: call it before SgSSNSetFromOptions");
  s->condense_default = condense;
  PetscFunctionReturn(0);
}

/* The defaults of -ssn_pc_truncated_mg and of -ssn_pc_truncated_mg_interp (geometric: the mesh hierarchy's); before
   SgSSNSetFromOptions */
PetscErrorCode SgSSNSetTruncatedMG(SgSSN s, PetscBool tmg, PetscBool geometric)
{
  PetscFunctionBeginUser;
  PetscCheck(!s->snes_setfromoptions, s->comm, PETSC_ERR_ORDER, "SgSSNSetTruncatedMG: call it before SgSSNSetFromOptions");
  s->tmg_default    = tmg;
  s->interp_default = geometric ? 1 : 0;
  PetscFunctionReturn(0);
}

/* The SSN's options (their defaults as set), then what they choose: the contact frames, condensation or the
   truncated multigrid on the KSP */
PetscErrorCode SgSSNSetFromOptions(SgSSN s)
{
  PetscBool    condense = s->condense_default, tmg = s->tmg_default, frame = PETSC_TRUE;
  PetscInt     interp = s->interp_default;
  SgElasticity p      = s->prob;
  SgContact    c      = s->c;
  const char  *prefix;
  KSP          ksp;

  PetscFunctionBeginUser;
  PetscCheck(!s->snes_setfromoptions, s->comm, PETSC_ERR_ORDER, "SgSSNSetFromOptions: called twice");
  s->snes_setfromoptions = PETSC_TRUE;
  PetscCall(SNESGetOptionsPrefix(s->snes, &prefix));
  PetscCall(SNESGetKSP(s->snes, &ksp));
  PetscOptionsBegin(s->comm, prefix, "Semismooth Newton (active set) solver", NULL);
  PetscCall(SSNOptions(PetscOptionsObject, s, &condense, &tmg, &interp, &frame));
  PetscOptionsEnd();
  PetscCall(SgCheckSolverTypes(s->comm, prefix));
  {
    PetscErrorCode ierr;
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = SNESSetFromOptions(s->snes);
    PetscCall(PetscPopErrorHandler());
    PetscCall(SgSolverConfigured(s->comm, ierr));
  }
  PetscCheck(s->fp_max_it >= 0, s->comm, PETSC_ERR_USER_INPUT, "-ssn_coulomb_fp_max_it: must be >= 0, got %" PetscInt_FMT, s->fp_max_it);
  PetscCheck(s->fp_m >= 1 && s->fp_m <= 100, s->comm, PETSC_ERR_USER_INPUT, "-ssn_coulomb_fp_m: must be in [1, 100], got %" PetscInt_FMT, s->fp_m);
  PetscCheck(s->fp_omega > 0 && s->fp_omega <= 1, s->comm, PETSC_ERR_USER_INPUT, "-ssn_coulomb_fp_omega: must be in (0, 1], got %g", (double)s->fp_omega);
  PetscCheck(PetscIsNormalReal(s->fp_rtol) && s->fp_rtol > 0, s->comm, PETSC_ERR_USER_INPUT, "-ssn_coulomb_fp_rtol: must be positive and finite, got %g", (double)s->fp_rtol);
  PetscCheck(!(s->cv.props.nonlinear && condense), s->comm, PETSC_ERR_SUP, "-ssn_condense is not built for friction (-friction_type %s) yet: leave it out (the default solver does without it)", SgLawName(s->cv.law));
  PetscCheck(!(s->cv.props.nonlinear && tmg), s->comm, PETSC_ERR_SUP, "-ssn_pc_truncated_mg is not built for friction (-friction_type %s) yet: leave it out (the default solver does without it)", SgLawName(s->cv.law));
  s->Klin = s->K;
  if (!s->pair_transform_set) { /* the default: on for a pair solved iteratively (a factorization needs no help) */
    PetscBool pair, preonly;
    PetscCall(SgContactIsPair(c, &pair));
    PetscCall(PetscObjectTypeCompare((PetscObject)ksp, KSPPREONLY, &preonly));
    s->pair_transform = (PetscBool)(pair && !preonly && !condense);
  }
  if (s->pair_transform) {
    PetscBool pair;
    PetscCall(SgContactIsPair(c, &pair));
    PetscCheck(pair, s->comm, PETSC_ERR_USER_INPUT, "-ssn_pair_transform is for two-body contact (-contact_master_ids): this problem has no pair");
    PetscCheck(!condense, s->comm, PETSC_ERR_USER_INPUT, "-ssn_pair_transform with -ssn_condense: condensation is not available for two bodies; leave -ssn_condense out");
    /* the transformation refused: the SSN-based controllers solve the pair without it too */
    PetscCall(SgFrameCreatePair(p, c, "-ssn_pair_transform", s->pair_transform_set ? "turn -ssn_pair_transform off (-ssn_pair_transform false)" : "-ssn_pair_transform is on by default with an iterative linear solver: turn it off (-ssn_pair_transform false), or solve with MUMPS (-options_file options/solver/mumps.opts), which does without it", s->pair_ptap, &s->frame));
  } else if (frame && c) PetscCall(SgFrameCreate(p, c, (PetscBool)!s->frame_local, &s->frame));
  if (s->frame) PetscCall(FrameSetUp(s, ksp));
  if (condense) PetscCall(SgCondenseCreate(s, &s->cond));
  PetscCheck(!(tmg && condense), s->comm, PETSC_ERR_USER_INPUT, "-ssn_pc_truncated_mg is for iterative linear solves, not -ssn_condense");
  if (tmg) PetscCall(SgTMGCreate(s, ksp, (PetscBool)(interp == 1), &s->tmg));
  {
    char      name[256];
    PetscBool flg;
    PetscCall(PetscOptionsGetViewer(s->comm, NULL, prefix, "-snes_converged_reason", &s->reason_viewer, &s->reason_format, &flg));
    if (flg) {
      PetscCall(SgOptionsName(prefix, "-snes_converged_reason", name, sizeof(name)));
      PetscCall(PetscOptionsClearValue(NULL, name));
    }
    PetscCall(SNESConvergedReasonViewSet(s->snes, SgSSNReasonView, s, NULL));
  }
  {
    PetscBool preonly;
    PetscCall(PetscObjectTypeCompare((PetscObject)ksp, KSPPREONLY, &preonly));
    /* exact (direct) solves land on the auxiliary problem's solution: a settled active set is convergence */
    s->residual_test = (PetscBool)(!preonly || s->cv.props.nonlinear); /* slip: Newton steps converge, they do not land */
    s->iterative     = (PetscBool)!preonly;
    PetscCheck(s->pc_reuse_its >= 0, s->comm, PETSC_ERR_USER_INPUT, "-ssn_pc_reuse_its: must be >= 0, got %" PetscInt_FMT, s->pc_reuse_its);
    PetscCheck(!(s->pc_reuse_its > 0 && preonly), s->comm, PETSC_ERR_USER_INPUT, "-ssn_pc_reuse_its %" PetscInt_FMT " needs an iterative -ksp_type (e.g. cg): with preonly a kept factorization gives wrong Newton steps", s->pc_reuse_its);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNDestroy(SgSSN *ssn)
{
  SgSSN s = *ssn;

  PetscFunctionBeginUser;
  if (!s) PetscFunctionReturn(0);
  if (s->frame) { /* the KSP is the controller's: it forgets the frames */
    KSP ksp;
    PetscCall(SNESGetKSP(s->snes, &ksp));
    PetscCall(SgFrameDetachKSP(s->frame, ksp));
    PetscCall(PetscObjectCompose((PetscObject)ksp, "SgFrameStiffness", NULL));
    PetscCall(PetscObjectCompose((PetscObject)ksp, "SgFramePmat", NULL));
  }
  PetscCall(SNESDestroy(&s->snes));
  PetscCall(PetscViewerDestroy(&s->reason_viewer));
  PetscCall(SgCondenseDestroy(&s->cond));
  PetscCall(SgTMGDestroy(&s->tmg));
  PetscCall(MatDestroy(&s->J));
  PetscCall(MatDestroy(&s->Pf));
  PetscCall(SgFrameDestroy(&s->frame));
  PetscCall(VecDestroy(&s->r));
  PetscCall(PetscFree5(s->g, s->m, s->act, s->actjac, s->lamhat));
  PetscCall(PetscFree(s->gy));
  PetscCall(PetscFree(s->zy));
  PetscCall(SgContactLawStateDestroy(&s->lst));
  PetscCall(PetscFree2(s->uv, s->ft));
  PetscCall(PetscFree(s->fforce));
  PetscCall(PetscFree(s->gfixw));
  PetscCall(KSPDestroy(&s->kspd));
  PetscCall(VecDestroy(&s->y0));
  if (s->wpre) PetscCall(VecDestroyVecs(2, &s->wpre));
  PetscCall(PetscFree(s->hash));
  PetscCall(PetscFree(*ssn));
  PetscFunctionReturn(0);
}

/* The load scales and the energy shift read again after the problem's load factor changed (load stepping; b and the
   gaps are shared, not copied). A step without load (b = 0: unloaded to zero) keeps the scales of the full load, so
   that the stopping tests measure against the problem, not against 0. */
PetscErrorCode SgSSNUpdateLoad(SgSSN s)
{
  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetScales(s->prob, &s->Knorm, &s->bnorm, &s->bnorm_inf));
  PetscCall(SgElasticityGetNodalNormSize(s->prob, &s->nd));
  if (!(s->bnorm > 0)) PetscCall(SgElasticityGetFullLoadScales(s->prob, &s->bnorm, &s->bnorm_inf, NULL));
  { /* the displacement data: the largest Dirichlet value now and at load factor 1 (the round-off floors' scale) */
    PetscReal ucur, ufull;
    PetscCall(SgElasticityGetDataScales(s->prob, &ucur, &ufull, NULL, NULL, NULL));
    s->udata = PetscMax(ucur, ufull);
  }
  PetscCall(SgElasticityGetEnergyShift(s->prob, &s->energy_shift));
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNGetSNES(SgSSN s, SNES *snes)
{
  PetscFunctionBeginUser;
  *snes = s->snes;
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNGetShift(SgSSN s, PetscReal **lamhat)
{
  PetscFunctionBeginUser;
  *lamhat = s->lamhat;
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNGetMultiplier(SgSSN s, const PetscReal **m)
{
  PetscFunctionBeginUser;
  *m = s->m;
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNGetPathValues(SgSSN s, PetscReal *gamma, PetscReal *V, PetscReal *dVdg)
{
  PetscFunctionBeginUser;
  if (gamma) *gamma = s->gamma;
  if (V) *V = s->V;
  if (dVdg) *dVdg = s->dVdg;
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNGetReason(SgSSN s, SgSSNReason *reason)
{
  PetscFunctionBeginUser;
  *reason = s->reason;
  PetscFunctionReturn(0);
}

/* tau > 0: also stop in the neighbourhood ||(r1, r2)|| <= tau / sqrt(gamma) of the path (IPF); 0: solve exactly */
PetscErrorCode SgSSNSetNeighbourhood(SgSSN s, PetscReal tau)
{
  PetscFunctionBeginUser;
  s->nbhd_tau = tau;
  PetscFunctionReturn(0);
}

/* the history that receives a row per SSN iteration, and its time origin */
PetscErrorCode SgSSNSetHistory(SgSSN s, SgHistory hist, PetscLogDouble t0)
{
  PetscFunctionBeginUser;
  s->hist = hist;
  s->t0   = t0;
  PetscFunctionReturn(0);
}

/* a short progress line per SSN iteration (for controllers whose outer steps are long); -ssn_monitor prints more */
PetscErrorCode SgSSNSetProgress(SgSSN s, PetscBool progress)
{
  PetscFunctionBeginUser;
  s->progress = progress;
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNGetMonitor(SgSSN s, PetscBool *monitor)
{
  PetscFunctionBeginUser;
  *monitor = s->monitor;
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNSetStopTest(SgSSN s, SgSSNStopTest test, void *ctx)
{
  PetscFunctionBeginUser;
  s->stop_test = test;
  s->stop_ctx  = ctx;
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNSetReason(SgSSN s, SgSSNReason reason)
{
  PetscFunctionBeginUser;
  s->reason = reason;
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNSetKeepPCOnSameSet(SgSSN s, PetscBool flg)
{
  PetscFunctionBeginUser;
  s->pc_same_set = flg;
  PetscFunctionReturn(0);
}

/* The contact vertices whose state at y (active: lamhat + gamma g(y) > 0, the rule of the Jacobian) differs from the
   active set of the last Jacobian, summed over the ranks: whether a Newton iterate y would change the set. A change whose
   decision value |lamhat + gamma g(y)| lies below its own round-off (SgSSNDecisionRoundoff, the bound of the residual's
   count of hard changes) is not counted: at gamma 1e19 a vertex at the edge of the contact zone, with multiplier and gap
   both zero at the solution, is otherwise decided by the round-off of the arithmetic, which differs between a body and
   its turned copy, and each such flip stops fast's CG early (the turned Example 2 at 1.07e6 unknowns, in the scale31
   runs: one vertex left and entered in turn, 9 SSN steps against the unturned 7). */
PetscErrorCode SgSSNCountSetChanges(SgSSN s, Vec y, PetscInt *changed)
{
  PetscFunctionBeginUser;
  PetscCall(SgSSNCountSetChangesMargin(s, y, SG_SSN_MARGIN_OFF, changed));
  PetscFunctionReturn(0);
}

/* The same for the iterates of one linear solve, whose decision values are inexact (fast's early CG stop, cont/fast.c):
   SG_SSN_MARGIN_START forgets the last iterate's values (a new solve); SG_SSN_MARGIN_ON counts a change only where the
   decision value's size exceeds its change since the last iterate given (|z - z_last| < |z|, an estimate of its own
   error; every change where there is no last iterate) and keeps the values for the next call. Without it, a rim vertex
   whose multiplier at the solution is small is let go (or taken) by the error of an iterate accurate to 1e-2, and the
   next SSN step runs on a set it must undo (the quarter hemisphere on its refined geometry at 17,022 unknowns: decision
   value -0.014 after 3 CG iterations, the vertex active at the solution; 3 SSN steps instead of 1, bench/results.md
   hemi31). SG_SSN_MARGIN_OFF: every change beyond round-off, nothing kept. */
PetscErrorCode SgSSNCountSetChangesMargin(SgSSN s, Vec y, SgSSNMargin margin, PetscInt *changed)
{
  const PetscScalar *ya;
  const PetscBool    use = (PetscBool)(margin == SG_SSN_MARGIN_ON && s->zy_valid);

  PetscFunctionBeginUser;
  if (margin == SG_SSN_MARGIN_START) { /* (y and changed unused) */
    s->zy_valid = PETSC_FALSE;
    PetscFunctionReturn(0);
  }
  *changed = 0;
  if (!s->gy) PetscCall(PetscMalloc1(s->n, &s->gy));
  if (margin == SG_SSN_MARGIN_ON && !s->zy) PetscCall(PetscMalloc1(s->n, &s->zy));
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(SgContactGap(s->c, ya, s->gy));
  PetscCall(VecRestoreArrayRead(y, &ya));
  for (PetscInt i = 0; i < s->n; i++) {
    const PetscReal z = s->lamhat[i] + s->gamma * s->gy[i];
    if (!use || PetscAbsReal(z - s->zy[i]) < PetscAbsReal(z)) *changed += ((z > 0) != (s->actjac[i] != 0) && PetscAbsReal(z) > SgSSNDecisionRoundoff(s, i, s->gy[i]));
    if (margin == SG_SSN_MARGIN_ON) s->zy[i] = z;
  }
  if (margin == SG_SSN_MARGIN_ON) s->zy_valid = PETSC_TRUE;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, changed, 1, MPIU_INT, MPI_SUM, s->comm));
  PetscFunctionReturn(0);
}

/* rho_F = int max(0, g), rho_C = int_I max(0, g) + int_A -min(0, g) with A, I the active and inactive sets of the
   iterate (the sets of the last Newton step): the measures of the inexact path-following rule (15). */
PetscErrorCode SgSSNPathMeasures(SgSSN s, PetscReal *rhoF, PetscReal *rhoC)
{
  PetscReal r[2] = {0, 0};

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < s->n; i++) {
    const PetscBool act = (PetscBool)(s->havejac ? s->actjac[i] : s->act[i]);
    r[0] += s->w[i] * PetscMax(0, s->g[i]);
    r[1] += s->w[i] * (act ? -PetscMin(0, s->g[i]) : PetscMax(0, s->g[i]));
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, r, 2, MPIU_REAL, MPI_SUM, s->comm));
  *rhoF = r[0];
  *rhoC = r[1];
  PetscFunctionReturn(0);
}


/* Solve (P_gamma) with the current shift c->lamhat from the initial guess y (overwritten). */
PetscErrorCode SgSSNSolve(SgSSN s, PetscReal gamma, PetscInt outer, Vec y, PetscInt *its, PetscInt *kits, SNESConvergedReason *reason)
{
  PetscFunctionBeginUser;
  s->gamma   = gamma;
  s->outer   = outer;
  s->havejac = PETSC_FALSE;
  s->dmax    = 0;
  for (PetscInt i = 0; i < s->n; i++) s->dmax = PetscMax(s->dmax, PetscAbsReal(s->d[i]));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &s->dmax, 1, MPIU_REAL, MPI_MAX, s->comm));
  s->nhash    = 0;
  s->stagnant = PETSC_FALSE;
  if ((s->cv.props.nonlinear && s->iterative) || s->cv.props.coupled || s->tmg) { /* the start, for the fallbacks below */
    if (!s->y0) PetscCall(VecDuplicate(y, &s->y0));
    PetscCall(VecCopy(y, s->y0));
  }
  if (s->gamma_direct > 0 && gamma >= s->gamma_direct) { /* the iterative solver failed at a smaller gamma already */
    *its = *kits = 0;
    s->reason    = SG_SSN_LINEAR_SOLVE;
  } else {
    PetscCall(SNESSolve(s->snes, NULL, y));
    PetscCall(SNESGetIterationNumber(s->snes, its));
    PetscCall(SNESGetLinearSolveIterations(s->snes, kits));
    PetscCall(SNESGetConvergedReason(s->snes, reason));
    s->reason = SgSSNReasonOf(s, *reason);
  }
  /* a failed linear solve with the truncated multigrid's PCSOR smoothers on several ranks: this (P_gamma) again from
     the same start with its l1 Gauss-Seidel smoothers (fallback.c), and so from here on */
  if (s->tmg && (s->reason == SG_SSN_LINEAR_SOLVE || s->reason == SG_SSN_NAN)) {
    PetscBool done;
    PetscCall(SgSSNSolveL1GS(s, gamma, y, its, kits, reason, &done));
  }
  /* friction with an iterative linear solver that failed: this (P_gamma) again with sparse LU (fallback.c), from the
     solve's initial guess; also after an iterate that overflowed (two bodies with Coulomb friction: inexact steps at a
     large gamma can blow up before the iteration count runs out) */
  if (s->cv.props.nonlinear && s->iterative && (s->reason == SG_SSN_LINEAR_SOLVE || s->reason == SG_SSN_MAX_IT || s->reason == SG_SSN_NAN)) PetscCall(SgSSNSolveDirect(s, gamma, y, its, kits, reason));
  /* a bound from lam_N (Coulomb): a failure of the coupled Newton iteration (cycling states) gets the fixed point on the frozen bound */
  if (s->cv.props.coupled && s->fp_max_it > 0 && (s->reason == SG_SSN_MAX_IT || s->reason == SG_SSN_CYCLING || s->reason == SG_SSN_SNES_FAILED)) PetscCall(SgSSNCoulombFixedPoint(s, y, its, kits, reason));
  /* the basic line search evaluated F at the returned iterate: g, m and the active set describe it */
  PetscFunctionReturn(0);
}

/* friction: the tangential shift lamhat_T (n*dim, for the controller to set), the multiplier lam_T and the states at
   the last residual evaluation; NULLs without friction */
PetscErrorCode SgSSNGetLawState(SgSSN s, SgContactLawState *st)
{
  PetscFunctionBeginUser;
  *st = s ? s->lst : NULL; /* no SSN (no contact boundary): no state */
  PetscFunctionReturn(0);
}

PetscErrorCode SgSSNGetFriction(SgSSN s, PetscReal **lamhatT, const PetscReal **mT, const char **fst)
{
  PetscFunctionBeginUser;
  if (lamhatT) *lamhatT = s->lamhatT;
  if (mT) *mT = s->mT;
  if (fst) *fst = s->fst;
  PetscFunctionReturn(0);
}
