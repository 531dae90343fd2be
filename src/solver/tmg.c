/* tmg.c: truncated multigrid (-ssn_pc_truncated_mg), a preconditioner for the SSN's Jacobians
   J = K + gamma sum_{A} w_i n_i n_i^T that follows the active set A without a new AMG setup (truncated nonsmooth
   Newton multigrid, Graeser and Kornhuber). The configured AMG (the KSP's own -pc_type: BoomerAMG or GAMG) is set
   up once, on the first operator (K, in the unconstrained start solve); its interpolations P_l are kept. For each
   Jacobian, the finest level is J itself (its smoother sees gamma), the finest interpolation is truncated at the
   active normal dofs (their rows of P set to zero: coarse corrections leave the normal displacement of an active
   vertex to the smoother, where gamma fixes it), and the coarse operators are the Galerkin products P_t^T J P_t, made
   as a correction of K's Galerkin hierarchy (Update). With the truncation the gamma block drops out of the coarse
   operators: P_t^T J P_t = P_t^T K P_t.
   Normals must be axis-aligned (a zero row then is the projection (I - n n^T) of the row block): any normal is, in
   the contact frames (-ssn_frame, frame.c), where all of this works on Q^T J Q and Q^T K Q.
   With -ssn_pc_truncated_mg_interp geometric the interpolations are the mesh hierarchy's (gmg.c) and no AMG is set up;
   the rest is the same.
   Two bodies in the pair's dual-mortar basis (-ssn_pair_transform): the AMG is set up on K in the displacements and its
   finest interpolation taken into the basis ((T Q)^-1 P, SgFramePairInterpolation), so that the coarse operators are
   K's own (-ssn_pair_amg_displacements, on by default). */
#include "solver/ssnimpl.h"

struct _n_SgTMG {
  SgSSN      ssn;
  PC         amg; /* the configured AMG, set up once; destroyed after its interpolations are taken */
  PC         mg;  /* PCMG on the interpolations, coarse operators set here */
  PetscInt   nlevels;
  Mat       *P;    /* P[l]: interpolation from level l-1 to l (PCMG numbering, 0 coarsest); P[n-1] the finest */
  Mat        Pt;   /* the finest one truncated (held by mg) */
  Mat       *AK;   /* AK[l]: Galerkin operators of K with the whole interpolations, l < n-1 */
  Mat       *A;    /* A[l]: the coarse operators of the current Jacobian, l < n-1 */
  Mat        KP;   /* K P[n-1] */
  IS         cols; /* the owned columns of P[n-1] */
  PetscInt  *axis; /* normal axis of each contact vertex */
  PetscReal *sign;
  char      *want; /* the active set of the last Jacobian (SgTMGSetActiveSet) */
  char      *have; /* the set the coarse operators were made for */
  PetscBool  has_set, fresh;
  PetscBool  gamg; /* the AMG was GAMG: its smoother (Chebyshev, Jacobi); BoomerAMG: Gauss-Seidel */
  PetscBool  geo;  /* the interpolations of the mesh hierarchy (gmg.c), given at creation: no AMG */
};

static PetscBool     tmg_registered = PETSC_FALSE;
static PetscLogEvent SG_TMGBuild, SG_TMGUpdate;

/* BoomerAMG's interpolation of the rigid-body modes (-pc_hypre_boomeramg_vec_interp_variant 1-3, with nodal
   coarsening): PETSc hands hypre every vector of the operator's near null space, and hypre's GM interpolation wants
   the rotations alone (the translations are the per-component constants its unknown-based interpolation keeps
   already; given them too it returned NaN on Example 2). For the one setup the operator's near null space is the
   rotations, the last dim(dim-1)/2 vectors of the rigid-body basis (MatNullSpaceCreateRigidBody: translations first;
   in the contact frames the rotated ones, frame.c); *keep is the whole one, to be put back (NULL: nothing changed). */
static PetscErrorCode RotationsOnly(SgTMG t, Mat A, MatNullSpace *keep)
{
  MatNullSpace nsp, rot;
  PetscInt     variant = 0, bs, nv;
  PetscBool    hc;
  const Vec   *v;
  const char  *prefix;
  PetscOptions opts;

  PetscFunctionBeginUser;
  *keep = NULL;
  if (t->gamg) PetscFunctionReturn(0);
  PetscCall(PCGetOptionsPrefix(t->amg, &prefix));
  PetscCall(PetscObjectGetOptions((PetscObject)t->amg, &opts));
  PetscCall(PetscOptionsGetInt(opts, prefix, "-pc_hypre_boomeramg_vec_interp_variant", &variant, NULL));
  PetscCall(MatGetNearNullSpace(A, &nsp));
  PetscCall(MatGetBlockSize(A, &bs));
  if (variant <= 0 || !nsp || bs < 2) PetscFunctionReturn(0);
  PetscCall(MatNullSpaceGetVecs(nsp, &hc, &nv, &v));
  if (hc || nv != bs + bs * (bs - 1) / 2) PetscFunctionReturn(0); /* not the rigid-body modes: as given */
  PetscCall(MatNullSpaceCreate(PetscObjectComm((PetscObject)A), PETSC_FALSE, nv - bs, v + bs, &rot));
  PetscCall(PetscObjectReference((PetscObject)nsp));
  *keep = nsp;
  PetscCall(MatSetNearNullSpace(A, rot));
  PetscCall(MatNullSpaceDestroy(&rot));
  PetscFunctionReturn(0);
}

/* On several ranks the smoothers' sweeps are l1 Gauss-Seidel (hypre's l1-GS, Baker, Falgout, Kolev and Yang 2011):
   each rank sweeps its own rows with the diagonal a_ii + l1_i, l1_i the sum of |a_ij| over the columns of other ranks
   (kept at 0 where that sum is at most a_ii / 3: their Remark 6.2, as hypre's l1 norms); PCSOR's local sweeps (a_ii
   alone) are Gauss-Seidel within a rank and Jacobi across ranks, whose multigrid is not positive definite where the
   coupling across ranks is strong: the stiffness in the pair's dual-mortar basis (frame.c), where a master vertex
   couples through the slave's rows to master vertices far away on other ranks, gave CG DIVERGED_INDEFINITE_PC on 2
   ranks (tests/parallel/twobody_ranks.ini). With W the sweep's lower (upper) triangle, W + W^T - A =
   D + 2 L1 - A_offrank is positive definite (diagonally dominant), so the V-cycle with a forward sweep down and a
   backward one up is symmetric positive definite. A PCSHELL, so that KSPRICHARDSON applies it to its residual (x += W^-1 (b - A x));
   on one rank the smoothers stay PCSOR (the same sweeps: no rows of other ranks). */
typedef struct {
  Mat       Ad;     /* the diagonal block of the smoother's matrix, its diagonal plus l1 */
  Vec       xl, yl; /* sequential views of the local parts */
  PetscBool back;   /* a backward sweep */
} L1GS;

static PetscErrorCode SetUp_L1GS(PC pc)
{
  L1GS              *g;
  Mat                P, Ad, Ao;
  Vec                d;
  PetscScalar       *da;
  const PetscScalar *va;
  PetscInt           m;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &g));
  PetscCall(PCGetOperators(pc, NULL, &P));
  PetscCall(MatMPIAIJGetSeqAIJ(P, &Ad, &Ao, NULL));
  PetscCall(MatDestroy(&g->Ad));
  PetscCall(MatDuplicate(Ad, MAT_COPY_VALUES, &g->Ad));
  PetscCall(MatGetLocalSize(Ad, &m, NULL));
  PetscCall(MatCreateVecs(g->Ad, &d, NULL));
  PetscCall(MatGetDiagonal(g->Ad, d));
  PetscCall(VecGetArray(d, &da));
  for (PetscInt i = 0; i < m; i++) {
    PetscInt  nc;
    PetscReal l1 = 0;
    PetscCall(MatGetRow(Ao, i, &nc, NULL, &va));
    for (PetscInt k = 0; k < nc; k++) l1 += PetscAbsScalar(va[k]);
    PetscCall(MatRestoreRow(Ao, i, &nc, NULL, &va));
    da[i] = l1 > PetscAbsScalar(da[i]) / 3 ? l1 : 0;
  }
  PetscCall(VecRestoreArray(d, &da));
  PetscCall(MatDiagonalSet(g->Ad, d, ADD_VALUES));
  PetscCall(VecDestroy(&d));
  if (!g->xl) {
    PetscCall(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, m, NULL, &g->xl));
    PetscCall(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, m, NULL, &g->yl));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode Apply_L1GS(PC pc, Vec x, Vec y)
{
  L1GS              *g;
  const PetscScalar *xa;
  PetscScalar       *ya;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &g));
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArray(y, &ya));
  PetscCall(VecPlaceArray(g->xl, xa));
  PetscCall(VecPlaceArray(g->yl, ya));
  PetscCall(MatSOR(g->Ad, g->xl, 1.0, (MatSORType)((g->back ? SOR_BACKWARD_SWEEP : SOR_FORWARD_SWEEP) | SOR_ZERO_INITIAL_GUESS), 0.0, 1, 1, g->yl));
  PetscCall(VecResetArray(g->xl));
  PetscCall(VecResetArray(g->yl));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(VecRestoreArray(y, &ya));
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_L1GS(PC pc)
{
  L1GS *g;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &g));
  PetscCall(MatDestroy(&g->Ad));
  PetscCall(VecDestroy(&g->xl));
  PetscCall(VecDestroy(&g->yl));
  PetscCall(PetscFree(g));
  PetscFunctionReturn(0);
}

static PetscErrorCode SetL1GS(PC pc, PetscBool back)
{
  L1GS *g;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&g));
  g->back = back;
  PetscCall(PCSetType(pc, PCSHELL));
  PetscCall(PCShellSetContext(pc, g));
  PetscCall(PCShellSetName(pc, back ? "backward l1 Gauss-Seidel" : "l1 Gauss-Seidel"));
  PetscCall(PCShellSetSetUp(pc, SetUp_L1GS));
  PetscCall(PCShellSetApply(pc, Apply_L1GS));
  PetscCall(PCShellSetDestroy(pc, Destroy_L1GS));
  PetscFunctionReturn(0);
}

/* The first set-up: the AMG on the operator, its interpolations into a PCMG, the Galerkin operators of K on every
   level (kept), and the smoothers: after BoomerAMG one Gauss-Seidel sweep forward before and one backward after the
   coarse correction (as hypre's l1-Gauss-Seidel pair; on several ranks l1 Gauss-Seidel itself, SetL1GS), after GAMG
   its own Chebyshev/Jacobi (Gauss-Seidel gave NaN there, as it diverges in GAMG itself, part A of
   bench/perf_notes.md); -<prefix>tmg_mg_levels_* override. */
static PetscErrorCode Build(SgTMG t, Mat A, Mat B)
{
  PetscInt    n, lo, hi;
  Mat        *P;
  const char *prefix;
  char        mgprefix[256];
  KSP         ksp;
  PetscMPIInt size;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(SG_TMGBuild, 0, 0, 0, 0));
  PetscCallMPI(MPI_Comm_size(t->ssn->comm, &size));
  if (t->geo) n = t->nlevels;
  else {
    /* the AMG of K (Klin), whatever the first operator: the unconstrained start's is K itself, but a solve started from a
       coarser level (-cont_nested) has no such solve and its first operator is a Jacobian with gamma in it */
    /* two bodies in the pair's basis (-ssn_pair_amg_displacements): the AMG of K in the displacements, its finest
       interpolation taken into the basis (SgFramePairInterpolation) */
    const PetscBool pu = (PetscBool)(t->ssn->pair_amg_u && SgFramePairTransform(t->ssn->frame));
    Mat             Ka = pu ? t->ssn->K : t->ssn->Klin;
    PetscCall(PCSetOperators(t->amg, Ka, Ka));
    {
      MatNullSpace keep = NULL;
      PetscCall(RotationsOnly(t, Ka, &keep));
      PetscCall(PCSetUp(t->amg));
      if (keep) {
        PetscCall(MatSetNearNullSpace(Ka, keep));
        PetscCall(MatNullSpaceDestroy(&keep));
      }
    }
    PetscCall(PCGetInterpolations(t->amg, &n, &P));
    PetscCall(PCDestroy(&t->amg));
    t->nlevels = n;
    PetscCall(PetscCalloc3(n, &t->P, n, &t->AK, n, &t->A));
    for (PetscInt l = 1; l < n; l++) t->P[l] = P[l - 1];
    PetscCall(PetscFree(P));
    if (pu) {
      Mat Pv;
      PetscCall(SgFramePairInterpolation(t->ssn->frame, t->P[n - 1], &Pv));
      PetscCall(MatDestroy(&t->P[n - 1]));
      t->P[n - 1] = Pv;
    }
  }
  /* the hierarchy of K: every later Jacobian differs from it by a few rows of the finest interpolation */
  PetscCall(MatMatMult(t->ssn->Klin, t->P[n - 1], MAT_INITIAL_MATRIX, PETSC_DEFAULT, &t->KP));
  PetscCall(MatTransposeMatMult(t->P[n - 1], t->KP, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &t->AK[n - 2]));
  for (PetscInt l = n - 2; l > 0; l--) PetscCall(MatPtAP(t->AK[l], t->P[l], MAT_INITIAL_MATRIX, PETSC_DEFAULT, &t->AK[l - 1]));
  for (PetscInt l = 0; l < n - 1; l++) PetscCall(MatDuplicate(t->AK[l], MAT_COPY_VALUES, &t->A[l]));
  PetscCall(MatGetOwnershipRangeColumn(t->P[n - 1], &lo, &hi));
  PetscCall(ISCreateStride(t->ssn->comm, hi - lo, lo, 1, &t->cols));
  PetscCall(MatDuplicate(t->P[n - 1], MAT_COPY_VALUES, &t->Pt));
  PetscCall(MatSetOption(t->Pt, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE));

  PetscCall(PCCreate(t->ssn->comm, &t->mg));
  PetscCall(SNESGetKSP(t->ssn->snes, &ksp));
  PetscCall(KSPGetOptionsPrefix(ksp, &prefix));
  PetscCall(PetscSNPrintf(mgprefix, sizeof(mgprefix), "%stmg_", prefix ? prefix : ""));
  PetscCall(PCSetOptionsPrefix(t->mg, mgprefix));
  PetscCall(PCSetType(t->mg, PCMG));
  PetscCall(PCMGSetLevels(t->mg, n, NULL));
  PetscCall(PCMGSetType(t->mg, PC_MG_MULTIPLICATIVE));
  PetscCall(PCMGSetGalerkin(t->mg, PC_MG_GALERKIN_NONE));
  for (PetscInt l = n - 1; l > 0; l--) PetscCall(PCMGSetInterpolation(t->mg, l, l == n - 1 ? t->Pt : t->P[l]));
  for (PetscInt l = 0; l < n; l++) {
    KSP sm[2];
    PC  spc;
    PetscCall(PCMGGetSmootherDown(t->mg, l, &sm[0]));
    if (l == 0) {
      PetscCall(KSPSetOperators(sm[0], t->A[0], t->A[0]));
      if (t->geo) PetscCall(SgGMGCoarseSolver(sm[0]));
      continue;
    }
    PetscCall(PCMGGetSmootherUp(t->mg, l, &sm[1]));
    for (PetscInt k = 0; k < 2; k++) {
      if (l < n - 1) PetscCall(KSPSetOperators(sm[k], t->A[l], t->A[l]));
      else PetscCall(KSPSetOperators(sm[k], A, B));
      if (t->gamg) {
        PetscCall(KSPSetType(sm[k], KSPCHEBYSHEV));
        PetscCall(KSPChebyshevEstEigSet(sm[k], PETSC_DECIDE, PETSC_DECIDE, PETSC_DECIDE, PETSC_DECIDE));
        PetscCall(KSPSetTolerances(sm[k], PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, 2));
        PetscCall(KSPSetNormType(sm[k], KSP_NORM_NONE));
        PetscCall(KSPGetPC(sm[k], &spc));
        PetscCall(PCSetType(spc, PCJACOBI));
        continue;
      }
      PetscCall(KSPSetType(sm[k], KSPRICHARDSON));
      PetscCall(KSPSetTolerances(sm[k], PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, 1));
      PetscCall(KSPSetNormType(sm[k], KSP_NORM_NONE));
      PetscCall(KSPGetPC(sm[k], &spc));
      if (size > 1) { /* l1 Gauss-Seidel (SetL1GS) */
        PetscCall(SetL1GS(spc, (PetscBool)(k == 1)));
        continue;
      }
      PetscCall(PCSetType(spc, PCSOR));
      PetscCall(PCSORSetSymmetric(spc, k == 0 ? SOR_LOCAL_FORWARD_SWEEP : SOR_LOCAL_BACKWARD_SWEEP));
    }
  }
  PetscCall(PCSetFromOptions(t->mg));
  PetscCall(PetscLogEventEnd(SG_TMGBuild, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* A coarse dof whose interpolation column lay only on active normal dofs has lost it to the truncation: its row and
   column of the coarse operator are zero up to round-off (seen on 2 ranks, where BoomerAMG coarsens otherwise). Its
   restricted residual is zero too, so any positive diagonal leaves it out of the correction: K's is taken, and the
   smoothers and the coarse LU see no zero pivot. */
static PetscErrorCode DeadDofs(Mat A, Mat AK)
{
  Vec                d, dk;
  PetscScalar       *da;
  const PetscScalar *dka;
  PetscInt           n, dead = 0;

  PetscFunctionBeginUser;
  PetscCall(MatCreateVecs(A, &d, &dk));
  PetscCall(MatGetDiagonal(A, d));
  PetscCall(MatGetDiagonal(AK, dk));
  PetscCall(VecGetLocalSize(d, &n));
  PetscCall(VecGetArray(d, &da));
  PetscCall(VecGetArrayRead(dk, &dka));
  for (PetscInt i = 0; i < n; i++)
    if (PetscAbsScalar(da[i]) <= 1e-8 * PetscAbsScalar(dka[i])) {
      da[i] = dka[i];
      dead++;
    }
  PetscCall(VecRestoreArrayRead(dk, &dka));
  PetscCall(VecRestoreArray(d, &da));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &dead, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)A)));
  if (dead) {
    PetscCall(PetscInfo(A, "truncated multigrid: %" PetscInt_FMT " coarse dofs cut off by the truncation\n", dead));
    PetscCall(MatDiagonalSet(A, d, INSERT_VALUES));
  }
  PetscCall(VecDestroy(&d));
  PetscCall(VecDestroy(&dk));
  PetscFunctionReturn(0);
}

/* The coarse operators for the active set `want`. With E the rows of the finest interpolation P at the active normal
   dofs (A), the truncated P_t = P - E gives P_t^T J P_t = P_t^T K P_t = P^T K P - E^T (K P) - (K P)^T E + E^T K_AA E:
   a correction of the kept Galerkin operator that only involves the rows in A. It is carried to the coarser levels by
   their (whole) interpolations. */
static PetscErrorCode Update(SgTMG t)
{
  const PetscInt n = t->nlevels;
  PetscInt       rstart, na = 0, nag, *rows;
  PetscBool      same = PETSC_TRUE;
  Mat            D    = NULL;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < t->ssn->n; i++) same = (PetscBool)(same && (t->want[i] != 0) == (t->have[i] != 0));
  same = (PetscBool)(same && !t->fresh);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPIU_BOOL, MPI_LAND, t->ssn->comm));
  if (same) PetscFunctionReturn(0);
  t->fresh = PETSC_FALSE;
  PetscCall(MatGetOwnershipRange(t->Pt, &rstart, NULL));
  PetscCall(PetscMalloc1(t->ssn->n, &rows));
  for (PetscInt i = 0; i < t->ssn->n; i++) {
    t->have[i] = t->want[i];
    if (t->want[i]) rows[na++] = rstart + t->ssn->off[i] + t->axis[i];
  }
  PetscCall(MPIU_Allreduce(&na, &nag, 1, MPIU_INT, MPI_SUM, t->ssn->comm));
  PetscCall(MatCopy(t->P[n - 1], t->Pt, SAME_NONZERO_PATTERN));
  PetscCall(MatZeroRows(t->Pt, na, rows, 0.0, NULL, NULL));
  if (nag > 0) {
    IS  isA;
    Mat E, KAA, M, C, Ct;
    PetscCall(ISCreateGeneral(t->ssn->comm, na, rows, PETSC_USE_POINTER, &isA));
    PetscCall(MatCreateSubMatrix(t->P[n - 1], isA, t->cols, MAT_INITIAL_MATRIX, &E));
    PetscCall(MatCreateSubMatrix(t->KP, isA, t->cols, MAT_INITIAL_MATRIX, &M));
    PetscCall(MatCreateSubMatrix(t->ssn->Klin, isA, isA, MAT_INITIAL_MATRIX, &KAA));
    PetscCall(MatPtAP(KAA, E, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &D));
    PetscCall(MatTransposeMatMult(E, M, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &C));
    PetscCall(MatTranspose(C, MAT_INITIAL_MATRIX, &Ct));
    PetscCall(MatAXPY(D, -1.0, C, DIFFERENT_NONZERO_PATTERN));
    PetscCall(MatAXPY(D, -1.0, Ct, DIFFERENT_NONZERO_PATTERN));
    PetscCall(MatDestroy(&KAA));
    PetscCall(MatDestroy(&M));
    PetscCall(MatDestroy(&C));
    PetscCall(MatDestroy(&Ct));
    PetscCall(MatDestroy(&E));
    PetscCall(ISDestroy(&isA));
  }
  PetscCall(PetscFree(rows));
  /* A[l] = AK[l] + D_l, D_{l-1} = P[l]^T D_l P[l]; the corrections' patterns lie in those of the kept operators */
  for (PetscInt l = n - 2; l >= 0; l--) {
    PetscCall(MatCopy(t->AK[l], t->A[l], SAME_NONZERO_PATTERN));
    if (D) {
      Mat Dc = NULL;
      PetscCall(MatAXPY(t->A[l], 1.0, D, SUBSET_NONZERO_PATTERN));
      if (l > 0) PetscCall(MatPtAP(D, t->P[l], MAT_INITIAL_MATRIX, PETSC_DEFAULT, &Dc));
      PetscCall(MatDestroy(&D));
      D = Dc;
      PetscCall(DeadDofs(t->A[l], t->AK[l]));
    }
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode SetUp_TMG(PC pc)
{
  SgTMG t;
  Mat   A, B;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &t));
  PetscCall(PCGetOperators(pc, &A, &B));
  if (!t->mg) PetscCall(Build(t, A, B));
  PetscCall(PetscLogEventBegin(SG_TMGUpdate, 0, 0, 0, 0));
  if (t->has_set) PetscCall(Update(t));
  PetscCall(PCSetOperators(t->mg, A, B));
  PetscCall(PCSetUp(t->mg));
  PetscCall(PetscLogEventEnd(SG_TMGUpdate, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

static PetscErrorCode Apply_TMG(PC pc, Vec x, Vec y)
{
  SgTMG t;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &t));
  PetscCall(PCApply(t->mg, x, y));
  PetscFunctionReturn(0);
}

static PetscErrorCode View_TMG(PC pc, PetscViewer v)
{
  SgTMG t;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &t));
  PetscCall(PetscViewerASCIIPrintf(v, "truncated multigrid (-ssn_pc_truncated_mg): %" PetscInt_FMT " levels, interpolations %s, finest truncated at the active normal dofs\n", t->nlevels, t->geo ? "of the mesh hierarchy (-ssn_pc_truncated_mg_interp geometric)" : "of the AMG set up once"));
  if (t->mg) {
    PetscCall(PetscViewerASCIIPushTab(v));
    PetscCall(PCView(t->mg, v));
    PetscCall(PetscViewerASCIIPopTab(v));
  }
  PetscFunctionReturn(0);
}

/* The KSP's configured preconditioner becomes the AMG whose interpolations the truncated multigrid keeps (geometric:
   the mesh hierarchy's interpolations instead, gmg.c, and the KSP's preconditioner is not used); the KSP gets the
   truncated multigrid (a PCSHELL) instead. */
PetscErrorCode SgTMGCreate(SgSSN s, KSP ksp, PetscBool geometric, SgTMG *tmg)
{
  SgTMG     t;
  PC        pc;
  PetscBool hypre = PETSC_FALSE, gamg = PETSC_FALSE;
  PetscInt  ngeo = 0;
  Mat      *Pgeo = NULL;

  PetscFunctionBeginUser;
  if (!tmg_registered) {
    PetscCall(PetscLogEventRegister("SgTMGBuild", PC_CLASSID, &SG_TMGBuild));
    PetscCall(PetscLogEventRegister("SgTMGUpdate", PC_CLASSID, &SG_TMGUpdate));
    tmg_registered = PETSC_TRUE;
  }
  PetscCall(KSPGetPC(ksp, &pc));
  if (geometric) PetscCall(SgGMGInterpolations(s, &ngeo, &Pgeo));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCHYPRE, &hypre));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCGAMG, &gamg));
  PetscCheck(ngeo || hypre || gamg, s->comm, PETSC_ERR_USER_INPUT, "-ssn_pc_truncated_mg takes the interpolations of an AMG: -pc_type hypre (BoomerAMG) or gamg");
  PetscCall(PetscNew(&t));
  t->ssn   = s;
  t->gamg  = gamg;
  t->fresh = PETSC_TRUE;
  PetscCall(PetscMalloc4(s->n, &t->axis, s->n, &t->sign, s->n, &t->want, s->n, &t->have));
  for (PetscInt i = 0; i < s->n; i++) t->want[i] = t->have[i] = 0;
  if (s->frame) { /* every normal is the axis of its frame (frame.c) */
    const PetscInt  *axis;
    const PetscReal *sign;
    PetscCall(SgFrameGetAxes(s->frame, &axis, &sign, NULL));
    PetscCall(PetscArraycpy(t->axis, axis, s->n));
    PetscCall(PetscArraycpy(t->sign, sign, s->n));
  } else {
    PetscBool pair; /* two bodies have no frames: the refusal names the multigrid alone */
    PetscCall(SgContactIsPair(s->c, &pair));
    PetscCall(SgContactAxisAligned(s->c, pair ? "-ssn_pc_truncated_mg" : "-ssn_pc_truncated_mg with the contact frames turned off (-ssn_frame false)", t->axis, t->sign)); /* collective */
  }
  if (ngeo) {
    t->geo     = PETSC_TRUE;
    t->gamg    = PETSC_FALSE;
    t->nlevels = ngeo;
    PetscCall(PetscCalloc3(ngeo, &t->P, ngeo, &t->AK, ngeo, &t->A));
    for (PetscInt l = 1; l < ngeo; l++) t->P[l] = Pgeo[l];
    PetscCall(PetscFree(Pgeo));
  } else {
    PetscCall(PetscObjectReference((PetscObject)pc));
    t->amg = pc;
  }
  PetscCall(PCCreate(s->comm, &pc));
  PetscCall(PCSetType(pc, PCSHELL));
  PetscCall(PCShellSetContext(pc, t));
  PetscCall(PCShellSetName(pc, "truncated multigrid"));
  PetscCall(PCShellSetSetUp(pc, SetUp_TMG));
  PetscCall(PCShellSetApply(pc, Apply_TMG));
  PetscCall(PCShellSetView(pc, View_TMG));
  PetscCall(KSPSetPC(ksp, pc));
  PetscCall(PCDestroy(&pc));
  *tmg = t;
  PetscFunctionReturn(0);
}

/* the active set of the Jacobian about to be solved with (read at the next set-up) */
PetscErrorCode SgTMGSetActiveSet(SgTMG t, const char act[])
{
  PetscFunctionBeginUser;
  if (!t) PetscFunctionReturn(0);
  PetscCall(PetscArraycpy(t->want, act, t->ssn->n));
  t->has_set = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode SgTMGDestroy(SgTMG *tmg)
{
  SgTMG t = *tmg;

  PetscFunctionBeginUser;
  if (!t) PetscFunctionReturn(0);
  PetscCall(PCDestroy(&t->amg));
  PetscCall(PCDestroy(&t->mg));
  for (PetscInt l = 0; l < t->nlevels; l++) {
    PetscCall(MatDestroy(&t->P[l]));
    PetscCall(MatDestroy(&t->AK[l]));
    PetscCall(MatDestroy(&t->A[l]));
  }
  PetscCall(PetscFree3(t->P, t->AK, t->A));
  PetscCall(MatDestroy(&t->KP));
  PetscCall(ISDestroy(&t->cols));
  PetscCall(MatDestroy(&t->Pt));
  PetscCall(PetscFree4(t->axis, t->sign, t->want, t->have));
  PetscCall(PetscFree(*tmg));
  PetscFunctionReturn(0);
}
