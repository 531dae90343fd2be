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
#include <petsc/private/petscimpl.h> /* an object's state (SetUp_L1GS) */

struct _n_SgTMG {
  SgSSN      ssn;
  SgSSN      host; /* SgTMGCreateBound: the SSN fields it reads, filled for a solver without an SSN (freed here) */
  KSP        ksp;  /* the KSP whose preconditioner it is (its options prefix: -<prefix>tmg_*) */
  PC         amg;  /* the configured AMG, set up once; destroyed after its interpolations are taken */
  PC         mg;   /* PCMG on the interpolations, coarse operators set here */
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
  PetscBool  gamg;      /* the AMG was GAMG: its smoother (Chebyshev, Jacobi); BoomerAMG: Gauss-Seidel */
  PetscBool  geo;       /* the interpolations of the mesh hierarchy (gmg.c), given at creation: no AMG */
  PetscBool  sor;       /* several ranks: PCSOR's local symmetric sweeps smooth (-ssn_pc_truncated_mg_local_sor), until a
                      failed solve puts the l1 Gauss-Seidel sweeps in their place (Fallback_TMG) */
  PetscBool  sym, glob; /* the l1 Gauss-Seidel sweeps' kind (Build), for that fallback */
  /* several ranks (UpdateRanks): kept from Build, so that an update makes no new pattern or communication */
  Mat          *D;    /* D[l]: the correction of level l, with AK[l]'s pattern */
  PetscObjectId klin; /* the Klin they were made from */
  Mat           Poth; /* the rows of P[n-1] at Klin's ghost columns (global coarse columns) */
  Vec           act;  /* 1 at the active normal dofs (Klin's column layout) */
  Vec           gact; /* its values at Klin's ghost columns */
  VecScatter    gsc;  /* act -> gact */
  PetscScalar  *acc;  /* a row of the correction over the coarse columns, */
  PetscBool    *mark; /* its touched columns, */
  PetscInt     *jw;   /* listed */
  PetscInt     *pj, *mj, pcap, mcap, vcap;
  PetscScalar  *pv, *mv, *vw;
  MatStructure *str;   /* str[l]: D[l]'s pattern against AK[l]'s (the same, checked once) */
  PetscBool    *touch; /* touch[l]: carry level l's correction down by its touched rows (TouchedPtAP) */
  PetscBool    *prod;  /* prod[l]: D[l] is MatPtAP's of D[l+1] (its symbolic product kept), not a copy's target */
  SgDefl        defl;  /* -ssn_pc_truncated_mg_deflate: CG's Ritz vectors deflated around the V-cycle (deflate.c) */
};

/* Several ranks: a level's correction is carried to the next coarser one over its touched rows (TouchedPtAP) from this
   many nonzeros of its kept operator up; below it the whole-pattern product with its symbolic part kept is cheaper
   (fewer messages: bench/nested.md, coarse27) */
#define SG_TMG_TOUCHED_NNZ 100000

/* The defaults of -ssn_pc_truncated_mg_l1gs_symmetric and _global for two bodies (a pair in the dual-mortar basis) on
   several ranks, one body keeping the single sweeps: off, as for one body; the symmetric sweep took 32 CG against 41
   at 299,316 unknowns on 2 ranks but 3.7-4.2 s against 3.5-3.8 s (bench/results.md, l1sym and the lead's section
   after it) */
#define SG_TMG_L1GS_SYM_PAIR    0
#define SG_TMG_L1GS_GLOBAL_PAIR 0

/* The default of -ssn_pc_truncated_mg_deflate for two bodies (one body: off). Off: fast, the default controller, gets
   nothing (its only long CG solve is its last: no Ritz vector before it), ipf/alm/pf take 8-45 % fewer CG iterations
   (bench/results.md, defl), not checked against the suite's counts on several ranks */
#define SG_TMG_DEFLATE_PAIR 0

/* The default of -ssn_pc_truncated_mg_local_sor for two bodies on several ranks: PCSOR's local symmetric sweeps (block
   Jacobi across ranks, no l1 terms: no guarantee of a positive definite V-cycle) smooth, and a failed linear solve
   puts the l1 Gauss-Seidel sweeps in their place and is redone (Fallback_TMG); 32 CG against 41 and np 2 speedup 1.60
   against 1.44-1.50 at 299,316 unknowns (bench/results.md, np2bal) */
#define SG_TMG_LOCAL_SOR_PAIR 1

static PetscBool      tmg_registered = PETSC_FALSE;
static PetscLogEvent  SG_TMGBuild, SG_TMGUpdate, SG_TMGCorr, SG_TMGCoarse, SG_TMGMGSetUp, SG_TMGL1GS, SG_TMGL1GSSetUp;
static PetscErrorCode RegisterEvents(void);

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
   backward one up is symmetric positive definite; swept by vertex blocks (SetUp_L1GS), D is the blocks' diagonal
   (positive definite, as A's principal submatrices) and the same holds. With -ssn_pc_truncated_mg_l1gs_symmetric each
   application is a forward sweep then a backward one (Apply_L1GS), convergent too. A PCSHELL, so that KSPRICHARDSON applies it
   to its residual (x += W^-1 (b - A x)); on one rank the smoothers stay PCSOR (the same sweeps: no rows of other
   ranks). Two bodies on several ranks (-ssn_pc_truncated_mg_local_sor, SG_TMG_LOCAL_SOR_PAIR) smooth with PCSOR's
   local symmetric sweeps after all (with the pair partition they took fewer CG than one rank, and failed nowhere
   measured) and fall back on the l1 sweeps when a solve fails (Fallback_TMG, SgLinearSolverFallback). */
typedef struct {
  PetscScalar     *idiag; /* point sweep: 1 / (a_ii + l1_i) of the local rows; block sweep: the inverted blocks */
  PetscScalar     *w;     /* the symmetric sweep's kept right-hand sides (Sweep), m */
  PetscInt         m;     /* the number of local rows */
  PetscInt         bs;    /* 1: point by point; else by vertex blocks of bs rows (SetUp_L1GS) */
  PetscObjectId    id;    /* the operator they were made from, */
  PetscObjectState state; /* at this state of its values */
  PetscInt         refs;
} L1GSMat;

typedef struct {
  L1GSMat  *m;    /* shared by the level's two sweeps (SetL1GS) */
  PetscBool back; /* a backward sweep */
  PetscBool sym;  /* the symmetric sweep, forward then backward (Apply_L1GS; back ignored) */
  PetscBool glob; /* with sym: the whole residual updated in between (one product with the operator) */
  Vec       r, z; /* its work vectors */
} L1GS;

/* a <- a^-1 for a dense n x n matrix (row-major), Gauss-Jordan with partial pivoting; w: n ints. Returns PETSC_FALSE
   where a pivot is zero. */
static PetscBool InvertBlock(PetscInt n, PetscScalar *a, PetscInt *w)
{
  for (PetscInt k = 0; k < n; k++) {
    PetscInt    p   = k;
    PetscReal   big = PetscAbsScalar(a[k * n + k]);
    PetscScalar piv;
    for (PetscInt i = k + 1; i < n; i++)
      if (PetscAbsScalar(a[i * n + k]) > big) {
        big = PetscAbsScalar(a[i * n + k]);
        p   = i;
      }
    if (big == 0.0) return PETSC_FALSE;
    w[k] = p;
    if (p != k)
      for (PetscInt j = 0; j < n; j++) {
        PetscScalar t = a[k * n + j];
        a[k * n + j]  = a[p * n + j];
        a[p * n + j]  = t;
      }
    piv          = 1.0 / a[k * n + k];
    a[k * n + k] = 1.0;
    for (PetscInt j = 0; j < n; j++) a[k * n + j] *= piv;
    for (PetscInt i = 0; i < n; i++) {
      PetscScalar f;
      if (i == k) continue;
      f            = a[i * n + k];
      a[i * n + k] = 0.0;
      for (PetscInt j = 0; j < n; j++) a[i * n + j] -= f * a[k * n + j];
    }
  }
  for (PetscInt k = n - 1; k >= 0; k--) /* the row swaps undone as column swaps, last first */
    if (w[k] != k)
      for (PetscInt i = 0; i < n; i++) {
        PetscScalar t   = a[i * n + k];
        a[i * n + k]    = a[i * n + w[k]];
        a[i * n + w[k]] = t;
      }
  return PETSC_TRUE;
}

/* the first k in [lo, hi) with ja[k] >= c (hi if none), ja sorted */
static inline PetscInt First(const PetscInt ja[], PetscInt lo, PetscInt hi, PetscInt c)
{
  while (lo < hi) {
    const PetscInt mid = lo + (hi - lo) / 2;
    if (ja[mid] < c) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

/* Both sweeps of a level see the same operator: the first one set up makes the inverted diagonal, the second finds it
   made (the same operator at the same state). The sweeps run on the operator's own diagonal block with that diagonal
   (Apply_L1GS): every SSN step changes the operators' values, and a copy of each level's diagonal block with l1 added
   (for MatSOR) cost a copy of the finest Jacobian's local rows in time and memory at every step (asm27; before that a
   new duplicate per sweep and step, bench/nested.md par27).
   By vertex blocks where the operator has a block size bs > 1 and every rank's rows are whole blocks (the elasticity
   operators: bs = dim): each block's bs x bs diagonal block, l1_i added to its diagonal entries (the same rule as the
   point sweep's), inverted here and kept (bs^2 numbers a block, bs per row). That is the smoother MatSOR gave on the
   former copy (its inode sweep: a vertex's rows have one pattern) and on one rank: the point sweep cost 34 -> 39 CG
   iterations on the finest level of Example 2 at 1.1e6 unknowns on 2 ranks (bench/nested.md, gs28). Otherwise (no
   block size, or a rank's rows not whole blocks) point by point. */
static PetscErrorCode SetUp_L1GS(PC pc)
{
  L1GS              *g;
  L1GSMat           *lm;
  Mat                P, Ad, Ao;
  const PetscInt    *ia, *ja, *oi, *oj;
  const PetscScalar *aa, *va;
  PetscInt           m, nr, bs, rlo, w[16];
  PetscBool          done;
  PetscObjectId      id;
  PetscObjectState   state;
  PetscReal         *l1;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &g));
  lm = g->m;
  PetscCall(PCGetOperators(pc, NULL, &P));
  PetscCall(PetscObjectGetId((PetscObject)P, &id));
  state = ((PetscObject)P)->state;
  if (lm->idiag && lm->id == id && lm->state == state) PetscFunctionReturn(0); /* the level's other sweep made it */
  PetscCall(PetscLogEventBegin(SG_TMGL1GSSetUp, 0, 0, 0, 0));
  PetscCall(MatMPIAIJGetSeqAIJ(P, &Ad, &Ao, NULL));
  PetscCall(MatGetLocalSize(Ad, &m, NULL));
  PetscCall(MatGetBlockSize(P, &bs));
  PetscCall(MatGetOwnershipRange(P, &rlo, NULL));
  if (bs < 2 || bs > 16 || m % bs || rlo % bs) bs = 1; /* not whole vertex blocks: point by point */
  if (lm->m != m || lm->bs != bs) {
    PetscCall(PetscFree(lm->idiag));
    PetscCall(PetscFree(lm->w));
    PetscCall(PetscMalloc1(m * bs + 1, &lm->idiag));
    PetscCall(PetscMalloc1(m + 1, &lm->w));
    lm->m  = m;
    lm->bs = bs;
    PetscCall(PetscInfo(pc, "l1 Gauss-Seidel on %" PetscInt_FMT " local rows, by blocks of %" PetscInt_FMT "\n", m, bs));
  }
  PetscCall(MatGetRowIJ(Ad, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja, &done));
  PetscCheck(done && nr == m, PETSC_COMM_SELF, PETSC_ERR_PLIB, "l1 Gauss-Seidel: no rows of the diagonal block");
  PetscCall(MatGetRowIJ(Ao, 0, PETSC_FALSE, PETSC_FALSE, &nr, &oi, &oj, &done));
  PetscCheck(done && nr == m, PETSC_COMM_SELF, PETSC_ERR_PLIB, "l1 Gauss-Seidel: no rows of the off-diagonal block");
  PetscCall(MatSeqAIJGetArrayRead(Ad, &aa));
  PetscCall(MatSeqAIJGetArrayRead(Ao, &va));
  PetscCall(PetscMalloc1(m + 1, &l1));
  /* the rows' columns are sorted: a row's entries in [c, c + bs) start at First(.., c); the off-diagonal rows read
     in place (MatGetRow per row and scans of whole rows cost 3 products with the operator at every SSN step, prof27) */
  for (PetscInt i = 0; i < m; i++) { /* l1_i, kept where it exceeds |a_ii| / 3 */
    const PetscInt k = First(ja, ia[i], ia[i + 1], i);
    PetscReal      s = 0;
    PetscScalar    d = k < ia[i + 1] && ja[k] == i ? aa[k] : 0;
    for (PetscInt q = oi[i]; q < oi[i + 1]; q++) s += PetscAbsScalar(va[q]);
    l1[i] = s > PetscAbsScalar(d) / 3 ? s : 0;
    if (bs == 1) {
      d += l1[i];
      PetscCheck(d != 0.0, PETSC_COMM_SELF, PETSC_ERR_MAT_LU_ZRPVT, "l1 Gauss-Seidel: zero diagonal in local row %" PetscInt_FMT, i);
      lm->idiag[i] = 1.0 / d;
    }
  }
  if (bs > 1)
    for (PetscInt b = 0; b < m / bs; b++) {
      const PetscInt r0 = b * bs;
      PetscScalar   *a  = lm->idiag + (size_t)r0 * bs;
      for (PetscInt r = 0; r < bs; r++) {
        for (PetscInt c = 0; c < bs; c++) a[r * bs + c] = 0;
        for (PetscInt k = First(ja, ia[r0 + r], ia[r0 + r + 1], r0); k < ia[r0 + r + 1] && ja[k] < r0 + bs; k++) a[r * bs + ja[k] - r0] = aa[k];
        a[r * bs + r] += l1[r0 + r];
      }
      PetscCheck(InvertBlock(bs, a, w), PETSC_COMM_SELF, PETSC_ERR_MAT_LU_ZRPVT, "l1 Gauss-Seidel: singular diagonal block at local rows %" PetscInt_FMT "-%" PetscInt_FMT, r0, r0 + bs - 1);
    }
  PetscCall(MatSeqAIJRestoreArrayRead(Ao, &va));
  PetscCall(MatRestoreRowIJ(Ao, 0, PETSC_FALSE, PETSC_FALSE, &nr, &oi, &oj, &done));
  PetscCall(PetscFree(l1));
  PetscCall(MatSeqAIJRestoreArrayRead(Ad, &aa));
  PetscCall(MatRestoreRowIJ(Ad, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja, &done));
  lm->id    = id;
  lm->state = state;
  PetscCall(PetscLogEventEnd(SG_TMGL1GSSetUp, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* One sweep over the local rows of the operator's diagonal block (rows sorted by column), the diagonal replaced by
   a_ii + l1_i: point by point, or by vertex blocks (SetUp_L1GS): a block's right-hand side is x less the rows' entries
   at the columns before the block (forward; after it, backward) times the values already swept, its values the kept
   inverse times that; the entries inside the block are in the inverse. What MatSOR's inode sweep did on the former
   copy, without the copy. From a zero start, w NULL. The symmetric sweep (Apply_L1GS) passes w: forward keeps each
   block's right-hand side there (x less the columns before the block), and backward starts from it instead of x: those
   columns still hold the forward values when the backward sweep reaches the block, so the backward sweep from the
   forward one's values reads only the columns after the block, and the two together read the rows once (as SSOR's
   usual implementation). */
static void Sweep(PetscInt m, PetscInt bs, const PetscInt *ia, const PetscInt *ja, const PetscScalar *aa, const PetscScalar *idiag, const PetscScalar *xa, PetscScalar *ya, PetscBool back, PetscScalar *w)
{
  const PetscScalar *xb = back && w ? w : xa;

  if (bs == 3) { /* the 3D vertex block, unrolled */
    if (!back)
      for (PetscInt i = 0; i < m; i += 3) {
        PetscScalar        s0 = xa[i], s1 = xa[i + 1], s2 = xa[i + 2];
        const PetscScalar *d = idiag + (size_t)i * 3;
        for (PetscInt k = ia[i]; k < ia[i + 1] && ja[k] < i; k++) s0 -= aa[k] * ya[ja[k]];
        for (PetscInt k = ia[i + 1]; k < ia[i + 2] && ja[k] < i; k++) s1 -= aa[k] * ya[ja[k]];
        for (PetscInt k = ia[i + 2]; k < ia[i + 3] && ja[k] < i; k++) s2 -= aa[k] * ya[ja[k]];
        if (w) {
          w[i]     = s0;
          w[i + 1] = s1;
          w[i + 2] = s2;
        }
        ya[i]     = d[0] * s0 + d[1] * s1 + d[2] * s2;
        ya[i + 1] = d[3] * s0 + d[4] * s1 + d[5] * s2;
        ya[i + 2] = d[6] * s0 + d[7] * s1 + d[8] * s2;
      }
    else
      for (PetscInt i = m - 3; i >= 0; i -= 3) {
        PetscScalar        s0 = xb[i], s1 = xb[i + 1], s2 = xb[i + 2];
        const PetscScalar *d = idiag + (size_t)i * 3;
        for (PetscInt k = ia[i + 1] - 1; k >= ia[i] && ja[k] > i + 2; k--) s0 -= aa[k] * ya[ja[k]];
        for (PetscInt k = ia[i + 2] - 1; k >= ia[i + 1] && ja[k] > i + 2; k--) s1 -= aa[k] * ya[ja[k]];
        for (PetscInt k = ia[i + 3] - 1; k >= ia[i + 2] && ja[k] > i + 2; k--) s2 -= aa[k] * ya[ja[k]];
        ya[i]     = d[0] * s0 + d[1] * s1 + d[2] * s2;
        ya[i + 1] = d[3] * s0 + d[4] * s1 + d[5] * s2;
        ya[i + 2] = d[6] * s0 + d[7] * s1 + d[8] * s2;
      }
  } else if (bs > 1) {
    PetscScalar s[16];
    for (PetscInt b = 0; b < m / bs; b++) {
      const PetscInt     r0 = back ? m - (b + 1) * bs : b * bs;
      const PetscScalar *d  = idiag + (size_t)r0 * bs;
      for (PetscInt r = 0; r < bs; r++) {
        const PetscInt i = r0 + r;
        s[r]             = xb[i];
        if (!back) {
          for (PetscInt k = ia[i]; k < ia[i + 1] && ja[k] < r0; k++) s[r] -= aa[k] * ya[ja[k]];
          if (w) w[i] = s[r];
        } else
          for (PetscInt k = ia[i + 1] - 1; k >= ia[i] && ja[k] >= r0 + bs; k--) s[r] -= aa[k] * ya[ja[k]];
      }
      for (PetscInt r = 0; r < bs; r++) {
        PetscScalar v = 0;
        for (PetscInt c = 0; c < bs; c++) v += d[r * bs + c] * s[c];
        ya[r0 + r] = v;
      }
    }
  } else if (!back)
    for (PetscInt i = 0; i < m; i++) {
      PetscScalar s = xa[i];
      for (PetscInt k = ia[i]; k < ia[i + 1] && ja[k] < i; k++) s -= aa[k] * ya[ja[k]];
      if (w) w[i] = s;
      ya[i] = s * idiag[i];
    }
  else
    for (PetscInt i = m - 1; i >= 0; i--) {
      PetscScalar s = xb[i];
      PetscInt    k = ia[i + 1] - 1;
      for (; k >= ia[i] && ja[k] > i; k--) continue;
      for (k++; k < ia[i + 1]; k++) s -= aa[k] * ya[ja[k]];
      ya[i] = s * idiag[i];
    }
}

/* One application from a zero start: one sweep (forward or backward), or the symmetric sweep
   (-ssn_pc_truncated_mg_l1gs_symmetric): forward, then backward from the forward one's values, the residual of the
   rank's own rows updated in between (no communication: PCSOR's local symmetric sweep, with l1). Its M =
   (D1 + L) D1^-1 (D1 + U) = B + L D1^-1 L^T >= B, B the diagonal block with l1 added to its diagonal (D1 its vertex
   blocks), and B >= A where l1 is kept (the l1 sum dominates the rows of other ranks), so 2 M - A > 0: a convergent
   smoother, and the V-cycle with it down and up is symmetric positive definite, as with the single sweeps. With
   -ssn_pc_truncated_mg_l1gs_global the whole residual x - A y between the sweeps (one product with the operator), the
   backward sweep from zero on it added: I - M^-1 A = (I - W_b^-1 A)(I - W_f^-1 A), two convergent steps, M symmetric
   as W_b = W_f^T. */
static PetscErrorCode Apply_L1GS(PC pc, Vec x, Vec y)
{
  L1GS              *g;
  Mat                P, Ad;
  const PetscInt    *ia, *ja;
  const PetscScalar *xa, *aa;
  PetscScalar       *ya;
  PetscInt           m, bs;
  PetscBool          done;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(SG_TMGL1GS, 0, 0, 0, 0));
  PetscCall(PCShellGetContext(pc, &g));
  PetscCall(PCGetOperators(pc, NULL, &P));
  PetscCall(MatMPIAIJGetSeqAIJ(P, &Ad, NULL, NULL));
  PetscCall(MatGetRowIJ(Ad, 0, PETSC_FALSE, PETSC_FALSE, &m, &ia, &ja, &done));
  PetscCheck(done && m == g->m->m, PETSC_COMM_SELF, PETSC_ERR_PLIB, "l1 Gauss-Seidel: the operator changed after its set-up");
  PetscCall(MatSeqAIJGetArrayRead(Ad, &aa));
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArray(y, &ya));
  bs = g->m->bs;
  if (g->sym && g->glob) {
    PetscScalar *za;
    Sweep(m, bs, ia, ja, aa, g->m->idiag, xa, ya, PETSC_FALSE, NULL);
    PetscCall(VecRestoreArray(y, &ya));
    if (!g->r) PetscCall(MatCreateVecs(P, &g->z, &g->r));
    PetscCall(MatMult(P, y, g->r));
    PetscCall(VecAYPX(g->r, -1.0, x)); /* r = x - A y */
    PetscCall(VecGetArrayRead(g->r, &xa));
    PetscCall(VecGetArray(g->z, &za));
    Sweep(m, bs, ia, ja, aa, g->m->idiag, xa, za, PETSC_TRUE, NULL);
    PetscCall(VecRestoreArray(g->z, &za));
    PetscCall(VecRestoreArrayRead(g->r, &xa));
    PetscCall(VecAXPY(y, 1.0, g->z));
    PetscCall(VecGetArrayRead(x, &xa));
    PetscCall(VecGetArray(y, &ya));
  } else if (g->sym) {
    Sweep(m, bs, ia, ja, aa, g->m->idiag, xa, ya, PETSC_FALSE, g->m->w);
    Sweep(m, bs, ia, ja, aa, g->m->idiag, xa, ya, PETSC_TRUE, g->m->w);
  } else Sweep(m, bs, ia, ja, aa, g->m->idiag, xa, ya, g->back, NULL);
  PetscCall(PetscLogFlops((g->sym ? 2.0 : 1.0) * (ia[m] + (bs > 1 ? (2.0 * bs - 1) * m : 0))));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(MatSeqAIJRestoreArrayRead(Ad, &aa));
  PetscCall(MatRestoreRowIJ(Ad, 0, PETSC_FALSE, PETSC_FALSE, &m, &ia, &ja, &done));
  PetscCall(PetscLogEventEnd(SG_TMGL1GS, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_L1GS(PC pc)
{
  L1GS *g;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &g));
  PetscCall(VecDestroy(&g->r));
  PetscCall(VecDestroy(&g->z));
  if (--g->m->refs == 0) {
    PetscCall(PetscFree(g->m->idiag));
    PetscCall(PetscFree(g->m->w));
    PetscCall(PetscFree(g->m));
  }
  PetscCall(PetscFree(g));
  PetscFunctionReturn(0);
}

/* lm: the level's shared matrix (NULL: a new one, for the level's other sweep to share); sym: the symmetric sweep */
static PetscErrorCode SetL1GS(PC pc, PetscBool back, PetscBool sym, PetscBool glob, L1GSMat **lm)
{
  L1GS *g;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&g));
  if (!*lm) PetscCall(PetscNew(lm));
  g->m = *lm;
  g->m->refs++;
  g->back = back;
  g->sym  = sym;
  g->glob = glob;
  PetscCall(PCSetType(pc, PCSHELL));
  PetscCall(PCShellSetContext(pc, g));
  PetscCall(PCShellSetName(pc, sym ? "symmetric l1 Gauss-Seidel" : back ? "backward l1 Gauss-Seidel"
                                                                        : "l1 Gauss-Seidel"));
  PetscCall(PCShellSetSetUp(pc, SetUp_L1GS));
  PetscCall(PCShellSetApply(pc, Apply_L1GS));
  PetscCall(PCShellSetDestroy(pc, Destroy_L1GS));
  PetscFunctionReturn(0);
}

/* One l1 Gauss-Seidel sweep of the smoothers on several ranks (SetL1GS) on an MPIAIJ A from a zero start, y = W^-1 b,
   on any number of ranks (tests/unit_tests.c: the block sweep against the exact solve and against MatSOR); sym: the
   symmetric sweep (back ignored) */
PetscErrorCode SgTMGL1GSSweep(Mat A, PetscBool back, PetscBool sym, Vec b, Vec y)
{
  PC       pc;
  L1GSMat *lm = NULL;

  PetscFunctionBeginUser;
  PetscCall(RegisterEvents());
  PetscCall(PCCreate(PetscObjectComm((PetscObject)A), &pc));
  PetscCall(SetL1GS(pc, back, sym, PETSC_FALSE, &lm));
  PetscCall(PCSetOperators(pc, A, A));
  PetscCall(PCSetUp(pc));
  PetscCall(PCApply(pc, b, y));
  PetscCall(PCDestroy(&pc));
  PetscFunctionReturn(0);
}

/* The first set-up: the AMG on the operator, its interpolations into a PCMG, the Galerkin operators of K on every
   level (kept), and the smoothers: after BoomerAMG one Gauss-Seidel sweep forward before and one backward after the
   coarse correction (as hypre's l1-Gauss-Seidel pair; on several ranks l1 Gauss-Seidel itself, SetL1GS), after GAMG
   its own Chebyshev/Jacobi (Gauss-Seidel gave NaN there, as it diverges in GAMG itself, part A of
   bench/perf_notes.md); -<prefix>tmg_mg_levels_* override. */
static PetscErrorCode BuildRanks(SgTMG);

static PetscBool IsMPIAIJ(Mat A)
{
  PetscBool is = PETSC_FALSE;
  if (PetscObjectTypeCompare((PetscObject)A, MATMPIAIJ, &is)) return PETSC_FALSE;
  return is;
}

/* K P at the rows of the contact vertices' normal dofs (K's rows there, the others empty; K's row layout): the rows of
   the whole product that UpdateRanks reads (the active normal dofs), each the same row of K times P */
static PetscErrorCode ContactRowsTimesP(SgTMG t, Mat *KP)
{
  const PetscInt n = t->nlevels;
  Mat            K = t->ssn->Klin, Kc, Kd, Ko;
  PetscInt       m, mc, rstart, *dnz, *onz;

  PetscFunctionBeginUser;
  PetscCall(MatGetLocalSize(K, &m, &mc));
  PetscCall(MatGetOwnershipRange(K, &rstart, NULL));
  PetscCall(MatMPIAIJGetSeqAIJ(K, &Kd, &Ko, NULL));
  PetscCall(PetscCalloc2(m + 1, &dnz, m + 1, &onz));
  for (PetscInt i = 0; i < t->ssn->n; i++) {
    const PetscInt r = t->ssn->off[i] + t->axis[i];
    PetscInt       nc;
    PetscCall(MatGetRow(Kd, r, &nc, NULL, NULL));
    dnz[r] = nc; /* (MatRestoreRow zeroes the count) */
    PetscCall(MatRestoreRow(Kd, r, &nc, NULL, NULL));
    PetscCall(MatGetRow(Ko, r, &nc, NULL, NULL));
    onz[r] = nc;
    PetscCall(MatRestoreRow(Ko, r, &nc, NULL, NULL));
  }
  PetscCall(MatCreate(PetscObjectComm((PetscObject)K), &Kc));
  PetscCall(MatSetSizes(Kc, m, mc, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetType(Kc, MATMPIAIJ));
  PetscCall(MatMPIAIJSetPreallocation(Kc, 0, dnz, 0, onz));
  PetscCall(PetscFree2(dnz, onz));
  for (PetscInt i = 0; i < t->ssn->n; i++) {
    const PetscInt     row = rstart + t->ssn->off[i] + t->axis[i];
    PetscInt           nc;
    const PetscInt    *cols;
    const PetscScalar *vals;
    PetscCall(MatGetRow(K, row, &nc, &cols, &vals));
    PetscCall(MatSetValues(Kc, 1, &row, nc, cols, vals, INSERT_VALUES));
    PetscCall(MatRestoreRow(K, row, &nc, &cols, &vals));
  }
  PetscCall(MatAssemblyBegin(Kc, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Kc, MAT_FINAL_ASSEMBLY));
  PetscCall(MatMatMult(Kc, t->P[n - 1], MAT_INITIAL_MATRIX, PETSC_DEFAULT, KP));
  PetscCall(MatDestroy(&Kc));
  PetscFunctionReturn(0);
}

static PetscErrorCode Build(SgTMG t, Mat A, Mat B)
{
  PetscInt    n, lo, hi;
  Mat        *P;
  const char *prefix;
  char        mgprefix[256];
  PetscMPIInt size;
  PetscBool   sym, glob;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(SG_TMGBuild, 0, 0, 0, 0));
  PetscCallMPI(MPI_Comm_size(t->ssn->comm, &size));
  /* the several-rank smoother's symmetric sweep and its whole residual between the sweeps (Apply_L1GS): as set, else
     SG_TMG_L1GS_SYM_PAIR and SG_TMG_L1GS_GLOBAL_PAIR for a pair */
  sym     = t->ssn->tmg_l1gs_sym_set ? t->ssn->tmg_l1gs_sym : (PetscBool)(SG_TMG_L1GS_SYM_PAIR && SgFramePairTransform(t->ssn->frame));
  glob    = t->ssn->tmg_l1gs_glob_set ? t->ssn->tmg_l1gs_glob : (PetscBool)(SG_TMG_L1GS_GLOBAL_PAIR && SgFramePairTransform(t->ssn->frame));
  t->sym  = sym;
  t->glob = glob;
  /* PCSOR's local sweeps: as set, else SG_TMG_LOCAL_SOR_PAIR for a pair unless the l1 sweeps' kind was asked for */
  t->sor = (PetscBool)(size > 1 && !t->gamg && (t->ssn->tmg_sor_set ? t->ssn->tmg_sor : (PetscBool)(SG_TMG_LOCAL_SOR_PAIR && SgFramePairTransform(t->ssn->frame) && !t->ssn->tmg_l1gs_sym_set && !t->ssn->tmg_l1gs_glob_set)));
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
  if (size > 1 && n > 1 && IsMPIAIJ(t->ssn->Klin) && IsMPIAIJ(t->P[n - 1])) {
    /* several ranks: P^T K P by one PtAP, and K P only at the rows a truncation can take (UpdateRanks reads no others):
       MatTransposeMatMult of P and the whole K P cost each rank 3 times one rank's product at 144,666 unknowns (CPU
       time; bench/nested.md, prof27), and the whole K P was a matrix of 40 entries a row */
    PetscCall(ContactRowsTimesP(t, &t->KP));
    PetscCall(MatPtAP(t->ssn->Klin, t->P[n - 1], MAT_INITIAL_MATRIX, PETSC_DEFAULT, &t->AK[n - 2]));
  } else {
    PetscCall(MatMatMult(t->ssn->Klin, t->P[n - 1], MAT_INITIAL_MATRIX, PETSC_DEFAULT, &t->KP));
    PetscCall(MatTransposeMatMult(t->P[n - 1], t->KP, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &t->AK[n - 2]));
  }
  for (PetscInt l = n - 2; l > 0; l--) PetscCall(MatPtAP(t->AK[l], t->P[l], MAT_INITIAL_MATRIX, PETSC_DEFAULT, &t->AK[l - 1]));
  /* the products are never recomputed in place (a later update patches rows): drop the data PETSc keeps for a reuse, on
     several ranks a local copy of K P's rows (bench/nested.md, mem27: 79 MB of 2 ranks' peak at 144,666 unknowns) */
  for (PetscInt l = 0; l < n - 1; l++) PetscCall(MatProductClear(t->AK[l]));
  PetscCall(MatProductClear(t->KP));
  for (PetscInt l = 0; l < n - 1; l++) PetscCall(MatDuplicate(t->AK[l], MAT_COPY_VALUES, &t->A[l]));
  PetscCall(MatGetOwnershipRangeColumn(t->P[n - 1], &lo, &hi));
  PetscCall(ISCreateStride(t->ssn->comm, hi - lo, lo, 1, &t->cols));
  PetscCall(MatDuplicate(t->P[n - 1], MAT_COPY_VALUES, &t->Pt));
  PetscCall(MatSetOption(t->Pt, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE));
  if (size > 1 && n > 1 && IsMPIAIJ(t->ssn->Klin) && IsMPIAIJ(t->P[n - 1]) && IsMPIAIJ(t->KP)) PetscCall(BuildRanks(t));

  PetscCall(PCCreate(t->ssn->comm, &t->mg));
  PetscCall(KSPGetOptionsPrefix(t->ksp, &prefix));
  PetscCall(PetscSNPrintf(mgprefix, sizeof(mgprefix), "%stmg_", prefix ? prefix : ""));
  PetscCall(PCSetOptionsPrefix(t->mg, mgprefix));
  PetscCall(PCSetType(t->mg, PCMG));
  if (t->sor) PetscCall(PetscInfo(t->mg, "truncated multigrid: PCSOR's local symmetric sweeps smooth (the l1 Gauss-Seidel sweeps after a failed solve)\n"));
  else if (size > 1 && !t->gamg) PetscCall(PetscInfo(t->mg, "truncated multigrid: %s l1 Gauss-Seidel smoothers\n", sym ? (glob ? "symmetric (whole residual between the sweeps)" : "symmetric (local residual between the sweeps)") : "single-sweep"));
  PetscCall(PCMGSetLevels(t->mg, n, NULL));
  PetscCall(PCMGSetType(t->mg, PC_MG_MULTIPLICATIVE));
  PetscCall(PCMGSetGalerkin(t->mg, PC_MG_GALERKIN_NONE));
  for (PetscInt l = n - 1; l > 0; l--) PetscCall(PCMGSetInterpolation(t->mg, l, l == n - 1 ? t->Pt : t->P[l]));
  for (PetscInt l = 0; l < n; l++) {
    KSP      sm[2];
    PC       spc;
    L1GSMat *lm;
    PetscCall(PCMGGetSmootherDown(t->mg, l, &sm[0]));
    if (l == 0) {
      PetscCall(KSPSetOperators(sm[0], t->A[0], t->A[0]));
      if (t->geo) PetscCall(SgGMGCoarseSolver(sm[0]));
      continue;
    }
    PetscCall(PCMGGetSmootherUp(t->mg, l, &sm[1]));
    lm = NULL;
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
      if (t->sor) { /* PCSOR's local symmetric sweep, down and up (its default), until Fallback_TMG */
        PetscCall(PCSetType(spc, PCSOR));
        continue;
      }
      if (size > 1) { /* l1 Gauss-Seidel (SetL1GS) */
        PetscCall(SetL1GS(spc, (PetscBool)(k == 1), sym, glob, &lm));
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

/* Several ranks (UpdateRanks): the rows of the finest interpolation at Klin's ghost columns, the scatter of the active
   flags to those columns, and the corrections' matrices with the kept operators' patterns, made once. */
static PetscErrorCode BuildRanks(SgTMG t)
{
  const PetscInt  n = t->nlevels;
  Mat             Ko, Pd, Po, *sub;
  const PetscInt *garray;
  PetscInt        ng, Nc;
  IS              isr, isc;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetId((PetscObject)t->ssn->Klin, &t->klin));
  PetscCall(MatMPIAIJGetSeqAIJ(t->ssn->Klin, NULL, &Ko, &garray));
  PetscCall(MatGetLocalSize(Ko, NULL, &ng));
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, ng, garray, PETSC_COPY_VALUES, &isr));
  PetscCall(MatGetSize(t->P[n - 1], NULL, &Nc));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, Nc, 0, 1, &isc));
  PetscCall(MatCreateSubMatrices(t->P[n - 1], 1, &isr, &isc, MAT_INITIAL_MATRIX, &sub));
  t->Poth = sub[0];
  PetscCall(PetscObjectReference((PetscObject)t->Poth));
  PetscCall(MatDestroySubMatrices(1, &sub));
  PetscCall(MatCreateVecs(t->ssn->Klin, &t->act, NULL));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, ng, &t->gact));
  PetscCall(VecScatterCreate(t->act, isr, t->gact, NULL, &t->gsc));
  PetscCall(ISDestroy(&isr));
  PetscCall(ISDestroy(&isc));
  PetscCall(PetscCalloc3(Nc, &t->acc, Nc, &t->mark, Nc, &t->jw));
  PetscCall(PetscCalloc4(n, &t->D, n, &t->str, n, &t->touch, n, &t->prod));
  for (PetscInt l = 1; l < n - 1; l++) { /* TouchedPtAP from the levels of at least SG_TMG_TOUCHED_NNZ nonzeros */
    MatInfo info;
    PetscCall(MatGetInfo(t->AK[l], MAT_GLOBAL_SUM, &info));
    t->touch[l] = (PetscBool)(info.nz_used >= SG_TMG_TOUCHED_NNZ);
  }
  PetscCall(MatDuplicate(t->AK[n - 2], MAT_DO_NOT_COPY_VALUES, &t->D[n - 2]));
  PetscCall(MatSetOption(t->D[n - 2], MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  t->str[n - 2] = SAME_NONZERO_PATTERN;
  for (PetscInt l = 0; l < n - 1; l++) PetscCall(MatSetOption(t->A[l], MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  /* the truncation zeroes rows in Pt's own blocks: its pattern must stay */
  PetscCall(MatMPIAIJGetSeqAIJ(t->Pt, &Pd, &Po, NULL));
  PetscCall(MatSetOption(Pd, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE));
  PetscCall(MatSetOption(Po, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE));
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

/* X's and Y's patterns (MPIAIJ) the same, on every rank: their blocks' rows, columns and ghost columns */
static PetscErrorCode SamePattern(Mat X, Mat Y, PetscBool *same)
{
  Mat             xb[2], yb[2];
  const PetscInt *gx, *gy;
  PetscInt        nx, ny;

  PetscFunctionBeginUser;
  PetscCall(MatMPIAIJGetSeqAIJ(X, &xb[0], &xb[1], &gx));
  PetscCall(MatMPIAIJGetSeqAIJ(Y, &yb[0], &yb[1], &gy));
  PetscCall(MatGetLocalSize(xb[1], NULL, &nx));
  PetscCall(MatGetLocalSize(yb[1], NULL, &ny));
  *same = (PetscBool)(nx == ny);
  for (PetscInt c = 0; *same && c < nx; c++) *same = (PetscBool)(gx[c] == gy[c]);
  for (PetscInt k = 0; k < 2 && *same; k++) PetscCall(SgSeqAIJSamePattern(xb[k], yb[k], same));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, same, 1, MPIU_BOOL, MPI_LAND, PetscObjectComm((PetscObject)X)));
  PetscFunctionReturn(0);
}

/* row i of an MPIAIJ's local blocks (Bd: columns c0 + c; Bo: garray[c]) into *j, *v (global columns), grown to fit */
static PetscErrorCode LocalRow(Mat Bd, Mat Bo, PetscInt c0, const PetscInt garray[], PetscInt i, PetscInt *nr, PetscInt **j, PetscScalar **v, PetscInt *cap)
{
  PetscInt           nd, no;
  const PetscInt    *cd, *co;
  const PetscScalar *vd, *vo;

  PetscFunctionBeginUser;
  PetscCall(MatGetRow(Bd, i, &nd, &cd, &vd));
  PetscCall(MatGetRow(Bo, i, &no, &co, &vo));
  if (nd + no > *cap) {
    PetscCall(PetscFree2(*j, *v));
    *cap = 2 * (nd + no);
    PetscCall(PetscMalloc2(*cap, j, *cap, v));
  }
  for (PetscInt a = 0; a < nd; a++) {
    (*j)[a] = c0 + cd[a];
    (*v)[a] = vd[a];
  }
  for (PetscInt b = 0; b < no; b++) {
    (*j)[nd + b] = garray[co[b]];
    (*v)[nd + b] = vo[b];
  }
  *nr = nd + no;
  PetscCall(MatRestoreRow(Bd, i, &nd, &cd, &vd));
  PetscCall(MatRestoreRow(Bo, i, &no, &co, &vo));
  PetscFunctionReturn(0);
}

static PetscErrorCode GrowValues(SgTMG t, PetscInt need)
{
  PetscFunctionBeginUser;
  if (need <= t->vcap) PetscFunctionReturn(0);
  PetscCall(PetscFree(t->vw));
  t->vcap = 2 * need;
  PetscCall(PetscMalloc1(t->vcap, &t->vw));
  PetscFunctionReturn(0);
}

/* acc[J] += v, J listed in jw[0 .. *nt) the first time it is touched (the row of UpdateRanks' correction) */
static inline void Accumulate(SgTMG t, PetscInt J, PetscScalar v, PetscInt *nt)
{
  if (!t->mark[J]) {
    t->mark[J]     = PETSC_TRUE;
    t->jw[(*nt)++] = J;
  }
  t->acc[J] += v;
}

/* Several ranks: the next coarser level's correction P^T D P from the rows of D that hold a nonzero and the same
   columns (D is symmetric): D is zero away from the contact zone, and the product over D's whole pattern (the kept
   operator's, MatPtAP with its symbolic product kept) cost each SSN step about what the kept operator's own product
   costs (bench/nested.md, coarse27: 144,666 unknowns on 2 ranks, 0.123 s against 0.043 s for two SSN steps, loaded).
   Zero rows and columns add nothing: the whole product up to the order of its sums (on Example 2 equal to the bit).
   *Dc NULL where D is zero; *done false (nothing made) where more than half of D's rows are touched. */
static PetscErrorCode TouchedPtAP(Mat D, Mat P, Mat *Dc, PetscBool *done)
{
  Mat      Db[2], Ds, Ps;
  PetscInt m, N, rstart, ns = 0, nsg, *sr;
  IS       is;
  MPI_Comm comm = PetscObjectComm((PetscObject)D);

  PetscFunctionBeginUser;
  *Dc = NULL;
  PetscCall(MatMPIAIJGetSeqAIJ(D, &Db[0], &Db[1], NULL));
  PetscCall(MatGetLocalSize(D, &m, NULL));
  PetscCall(MatGetOwnershipRange(D, &rstart, NULL));
  PetscCall(PetscMalloc1(m, &sr));
  for (PetscInt i = 0; i < m; i++) {
    PetscBool nz = PETSC_FALSE;
    for (PetscInt k = 0; k < 2 && !nz; k++) {
      PetscInt           nc;
      const PetscScalar *v;
      PetscCall(MatGetRow(Db[k], i, &nc, NULL, &v));
      for (PetscInt a = 0; a < nc && !nz; a++) nz = (PetscBool)(v[a] != 0.0);
      PetscCall(MatRestoreRow(Db[k], i, &nc, NULL, &v));
    }
    if (nz) sr[ns++] = rstart + i;
  }
  PetscCall(MPIU_Allreduce(&ns, &nsg, 1, MPIU_INT, MPI_SUM, comm));
  PetscCall(MatGetSize(D, &N, NULL));
  *done = (PetscBool)(2 * nsg <= N);
  if (nsg == 0 || !*done) {
    PetscCall(PetscFree(sr));
    PetscFunctionReturn(0);
  }
  PetscCall(ISCreateGeneral(comm, ns, sr, PETSC_OWN_POINTER, &is));
  PetscCall(MatCreateSubMatrix(D, is, is, MAT_INITIAL_MATRIX, &Ds));
  PetscCall(MatCreateSubMatrix(P, is, NULL, MAT_INITIAL_MATRIX, &Ps));
  PetscCall(MatPtAP(Ds, Ps, MAT_INITIAL_MATRIX, PETSC_DEFAULT, Dc));
  PetscCall(MatDestroy(&Ds));
  PetscCall(MatDestroy(&Ps));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(0);
}

/* Update's correction on several ranks, from each rank's own active rows i and the kept data (BuildRanks):
   D = E^T K_AA E - E^T M - M^T E = sum_{i in A} P_i^T (g_i - M_i) - M_i^T P_i, with P_i, M_i = (K P)_i the rows of P
   and K P and g_i = sum_{j in A} K_ij P_j (P_j of a ghost column j from Poth, whether j is active from the scattered
   flags); added into D[n-2] (AK[n-2]'s pattern: the products' patterns hold every term) and carried to the coarser
   levels: a large level by the rows its correction touches (TouchedPtAP), a small one by MatPtAP over its whole pattern
   with the symbolic product kept (-ssn_pc_truncated_mg_coarse_ptap: every level so). The sum is Update's in another
   order: the same operator up to round-off. Update's general path (submatrices, products and transposes of new
   patterns, MatZeroRows' routing) made new patterns and communication at every SSN step: 9x the 1-rank update time on
   2 ranks (bench/nested.md par27). */
static PetscErrorCode UpdateRanks(SgTMG t, PetscInt na, const PetscInt rows[], PetscInt nag)
{
  const PetscInt     n  = t->nlevels;
  Mat                Dn = t->D[n - 2], Kd, Ko, Bd, Bo, Md, Mo, Pd, Po;
  const PetscInt    *pg, *mg;
  PetscInt           rstart, c0, *lrows;
  PetscScalar       *fa;
  const PetscScalar *la, *ga;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(SG_TMGCorr, 0, 0, 0, 0));
  PetscCall(MatGetOwnershipRange(t->Pt, &rstart, NULL));
  PetscCall(MatGetOwnershipRangeColumn(t->Pt, &c0, NULL));
  /* the truncation in Pt's own blocks (MatZeroRows would route the rows to their owners: they are ours) */
  PetscCall(PetscMalloc1(na, &lrows));
  for (PetscInt k = 0; k < na; k++) lrows[k] = rows[k] - rstart;
  PetscCall(MatCopy(t->P[n - 1], t->Pt, SAME_NONZERO_PATTERN));
  PetscCall(MatMPIAIJGetSeqAIJ(t->Pt, &Pd, &Po, NULL));
  PetscCall(MatZeroRows(Pd, na, lrows, 0.0, NULL, NULL));
  PetscCall(MatZeroRows(Po, na, lrows, 0.0, NULL, NULL));
  PetscCall(PetscObjectStateIncrease((PetscObject)t->Pt));
  PetscCall(PetscFree(lrows));
  if (nag == 0) {
    for (PetscInt l = n - 2; l >= 0; l--) PetscCall(MatCopy(t->AK[l], t->A[l], SAME_NONZERO_PATTERN));
    PetscCall(PetscLogEventEnd(SG_TMGCorr, 0, 0, 0, 0));
    PetscFunctionReturn(0);
  }
  PetscCall(VecSet(t->act, 0.0));
  PetscCall(VecGetArray(t->act, &fa));
  for (PetscInt k = 0; k < na; k++) fa[rows[k] - rstart] = 1.0;
  PetscCall(VecRestoreArray(t->act, &fa));
  PetscCall(VecScatterBegin(t->gsc, t->act, t->gact, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(t->gsc, t->act, t->gact, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(MatMPIAIJGetSeqAIJ(t->ssn->Klin, &Kd, &Ko, NULL));
  PetscCall(MatMPIAIJGetSeqAIJ(t->P[n - 1], &Bd, &Bo, &pg));
  PetscCall(MatMPIAIJGetSeqAIJ(t->KP, &Md, &Mo, &mg));
  PetscCall(MatZeroEntries(Dn));
  PetscCall(VecGetArrayRead(t->act, &la));
  PetscCall(VecGetArrayRead(t->gact, &ga));
  for (PetscInt k = 0; k < na; k++) {
    const PetscInt     i  = rows[k] - rstart;
    PetscInt           np = 0, nm = 0, nt = 0, nc;
    const PetscInt    *cc;
    const PetscScalar *cv;

    PetscCall(LocalRow(Bd, Bo, c0, pg, i, &np, &t->pj, &t->pv, &t->pcap));
    PetscCall(LocalRow(Md, Mo, c0, mg, i, &nm, &t->mj, &t->mv, &t->mcap));
    /* -M_i^T P_i */
    PetscCall(GrowValues(t, nm * np));
    for (PetscInt a = 0; a < nm; a++)
      for (PetscInt b = 0; b < np; b++) t->vw[a * np + b] = -t->mv[a] * t->pv[b];
    PetscCall(MatSetValues(Dn, nm, t->mj, np, t->pj, t->vw, ADD_VALUES));
    /* h = g_i - M_i over the touched coarse columns */
    for (PetscInt a = 0; a < nm; a++) {
      Accumulate(t, t->mj[a], -t->mv[a], &nt);
    }
    PetscCall(MatGetRow(Kd, i, &nc, &cc, &cv));
    for (PetscInt a = 0; a < nc; a++) {
      PetscInt           nq;
      const PetscInt    *qd, *qo;
      const PetscScalar *vd, *vo;
      if (la[cc[a]] == 0.0) continue;
      PetscCall(MatGetRow(Bd, cc[a], &nq, &qd, &vd));
      for (PetscInt b = 0; b < nq; b++) {
        Accumulate(t, c0 + qd[b], cv[a] * vd[b], &nt);
      }
      PetscCall(MatRestoreRow(Bd, cc[a], &nq, &qd, &vd));
      PetscCall(MatGetRow(Bo, cc[a], &nq, &qo, &vo));
      for (PetscInt b = 0; b < nq; b++) {
        Accumulate(t, pg[qo[b]], cv[a] * vo[b], &nt);
      }
      PetscCall(MatRestoreRow(Bo, cc[a], &nq, &qo, &vo));
    }
    PetscCall(MatRestoreRow(Kd, i, &nc, &cc, &cv));
    PetscCall(MatGetRow(Ko, i, &nc, &cc, &cv));
    for (PetscInt a = 0; a < nc; a++) {
      PetscInt           nq;
      const PetscInt    *q;
      const PetscScalar *vq;
      if (ga[cc[a]] == 0.0) continue;
      PetscCall(MatGetRow(t->Poth, cc[a], &nq, &q, &vq));
      for (PetscInt b = 0; b < nq; b++) {
        Accumulate(t, q[b], cv[a] * vq[b], &nt);
      }
      PetscCall(MatRestoreRow(t->Poth, cc[a], &nq, &q, &vq));
    }
    PetscCall(MatRestoreRow(Ko, i, &nc, &cc, &cv));
    /* P_i^T h */
    PetscCall(GrowValues(t, np * nt));
    for (PetscInt b = 0; b < np; b++)
      for (PetscInt a = 0; a < nt; a++) t->vw[b * nt + a] = t->pv[b] * t->acc[t->jw[a]];
    PetscCall(MatSetValues(Dn, np, t->pj, nt, t->jw, t->vw, ADD_VALUES));
    for (PetscInt a = 0; a < nt; a++) {
      t->acc[t->jw[a]]  = 0;
      t->mark[t->jw[a]] = PETSC_FALSE;
    }
  }
  PetscCall(VecRestoreArrayRead(t->act, &la));
  PetscCall(VecRestoreArrayRead(t->gact, &ga));
  PetscCall(MatAssemblyBegin(Dn, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Dn, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscLogEventEnd(SG_TMGCorr, 0, 0, 0, 0));
  PetscCall(PetscLogEventBegin(SG_TMGCoarse, 0, 0, 0, 0));
  {
    /* A[l] = AK[l] + D_l; D_{l-1} = P[l]^T D_l P[l] over D_l's touched rows where the level is large (TouchedPtAP), else
       over AK[l]'s whole pattern into D[l-1] (the symbolic product made at the first update); D_l is D[l] itself where
       `full` (D[n-2], the products over the whole pattern), else the touched product (AK[l]'s pattern in part) */
    Mat       Dl   = t->D[n - 2];
    PetscBool full = PETSC_TRUE;
    PetscCall(PetscObjectReference((PetscObject)Dl));
    for (PetscInt l = n - 2; l >= 0; l--) {
      Mat       Dc    = NULL;
      PetscBool cfull = PETSC_FALSE, done = PETSC_FALSE;
      PetscCall(MatCopy(t->AK[l], t->A[l], SAME_NONZERO_PATTERN));
      if (Dl) {
        PetscCall(MatAXPY(t->A[l], 1.0, Dl, full ? t->str[l] : SUBSET_NONZERO_PATTERN));
        if (l > 0 && t->touch[l] && !t->ssn->tmg_coarse_ptap) PetscCall(TouchedPtAP(Dl, t->P[l], &Dc, &done));
        if (l > 0 && !done) {
          if (!full) { /* the touched product into a matrix of AK[l]'s pattern */
            if (!t->D[l]) {
              PetscCall(MatDuplicate(t->AK[l], MAT_DO_NOT_COPY_VALUES, &t->D[l]));
              PetscCall(MatSetOption(t->D[l], MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
              t->str[l] = SAME_NONZERO_PATTERN;
            }
            PetscCall(MatZeroEntries(t->D[l]));
            PetscCall(MatAXPY(t->D[l], 1.0, Dl, SUBSET_NONZERO_PATTERN));
          }
          if (t->D[l - 1] && !t->prod[l - 1]) PetscCall(MatDestroy(&t->D[l - 1])); /* a copy's target: no product kept */
          if (t->D[l - 1]) PetscCall(MatPtAP(t->D[l], t->P[l], MAT_REUSE_MATRIX, PETSC_DEFAULT, &t->D[l - 1]));
          else {
            PetscBool same;
            PetscCall(MatPtAP(t->D[l], t->P[l], MAT_INITIAL_MATRIX, PETSC_DEFAULT, &t->D[l - 1]));
            PetscCall(SamePattern(t->D[l - 1], t->AK[l - 1], &same));
            t->str[l - 1]  = same ? SAME_NONZERO_PATTERN : SUBSET_NONZERO_PATTERN;
            t->prod[l - 1] = PETSC_TRUE;
          }
          Dc = t->D[l - 1];
          PetscCall(PetscObjectReference((PetscObject)Dc));
          cfull = PETSC_TRUE;
        }
      }
      PetscCall(MatDestroy(&Dl));
      Dl   = Dc;
      full = cfull;
      PetscCall(DeadDofs(t->A[l], t->AK[l]));
    }
  }
  PetscCall(PetscLogEventEnd(SG_TMGCoarse, 0, 0, 0, 0));
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
  if (t->D) {
    PetscObjectId klin;
    PetscCall(PetscObjectGetId((PetscObject)t->ssn->Klin, &klin));
    PetscCheck(klin == t->klin, t->ssn->comm, PETSC_ERR_PLIB, "truncated multigrid: the stiffness changed after its set-up");
    PetscCall(UpdateRanks(t, na, rows, nag));
    PetscCall(PetscFree(rows));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscLogEventBegin(SG_TMGCorr, 0, 0, 0, 0));
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
  PetscCall(PetscLogEventEnd(SG_TMGCorr, 0, 0, 0, 0));
  PetscCall(PetscLogEventBegin(SG_TMGCoarse, 0, 0, 0, 0));
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
  PetscCall(PetscLogEventEnd(SG_TMGCoarse, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* A linear solve with PCSOR's local sweeps failed (CG: DIVERGED_INDEFINITE_PC where block Jacobi across ranks made the
   V-cycle indefinite, or any other failure): every level's smoothers become the l1 Gauss-Seidel sweeps (SetL1GS, the
   V-cycle SPD), for the rest of the run; *done says whether that happened (the caller redoes its solve). A
   smoother's Richardson scale is reset to 1 (-tmg_mg_levels_ksp_richardson_scale -1 is how the tests make SOR fail). */
static PetscErrorCode Fallback_TMG(PC pc, PetscBool *done)
{
  SgTMG t;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &t));
  *done = PETSC_FALSE;
  if (!t->sor || !t->mg || t->nlevels < 2) PetscFunctionReturn(0);
  { /* smoothers of the user's (-tmg_mg_levels_pc_type) are theirs: no fallback */
    KSP       sm;
    PC        spc;
    PetscBool is;
    PetscCall(PCMGGetSmootherDown(t->mg, t->nlevels - 1, &sm));
    PetscCall(KSPGetPC(sm, &spc));
    PetscCall(PetscObjectTypeCompare((PetscObject)spc, PCSOR, &is));
    if (!is) PetscFunctionReturn(0);
  }
  for (PetscInt l = 1; l < t->nlevels; l++) {
    KSP      sm[2];
    L1GSMat *lm = NULL;
    PetscCall(PCMGGetSmootherDown(t->mg, l, &sm[0]));
    PetscCall(PCMGGetSmootherUp(t->mg, l, &sm[1]));
    for (PetscInt k = 0; k < 2; k++) {
      PC spc;
      PetscCall(KSPSetType(sm[k], KSPRICHARDSON));
      PetscCall(KSPRichardsonSetScale(sm[k], 1.0));
      PetscCall(KSPSetTolerances(sm[k], PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, 1));
      PetscCall(KSPSetNormType(sm[k], KSP_NORM_NONE));
      PetscCall(KSPGetPC(sm[k], &spc));
      PetscCall(SetL1GS(spc, (PetscBool)(k == 1), t->sym, t->glob, &lm));
      PetscCall(PCSetUp(spc)); /* its operators stay; the new type's set-up now (the KSP's is done) */
    }
  }
  t->sor = PETSC_FALSE;
  *done  = PETSC_TRUE;
  PetscCall(PetscInfo(t->mg, "truncated multigrid: a failed linear solve with PCSOR's local sweeps; the l1 Gauss-Seidel sweeps from here on\n"));
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
  PetscCall(PetscLogEventBegin(SG_TMGMGSetUp, 0, 0, 0, 0));
  PetscCall(PCSetUp(t->mg));
  PetscCall(PetscLogEventEnd(SG_TMGMGSetUp, 0, 0, 0, 0));
  PetscCall(PetscLogEventEnd(SG_TMGUpdate, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The deflation around the V-cycle (deflate.c), made at the first application: on where asked, else for a pair by
   SG_TMG_DEFLATE_PAIR */
static PetscErrorCode ApplyDeflated(SgTMG t, Vec x, Vec y)
{
  KSP ksp;
  Mat A;

  PetscFunctionBeginUser;
  if (!t->defl) {
    const PetscBool on = t->ssn->tmg_defl_set ? t->ssn->tmg_defl : (PetscBool)(SG_TMG_DEFLATE_PAIR && SgFramePairTransform(t->ssn->frame));
    if (!on) {
      PetscCall(PCApply(t->mg, x, y));
      PetscFunctionReturn(0);
    }
    PetscCall(SgDeflCreate(t->ssn->tmg_defl_max, SG_DEFL_MCAP, t->ssn->tmg_defl_ritz, &t->defl));
  }
  PetscCall(SNESGetKSP(t->ssn->snes, &ksp));
  PetscCall(PCGetOperators(t->mg, &A, NULL));
  PetscCall(SgDeflApply(t->defl, ksp, A, t->mg, x, y));
  PetscFunctionReturn(0);
}

static PetscErrorCode Apply_TMG(PC pc, Vec x, Vec y)
{
  SgTMG t;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &t));
  PetscCall(ApplyDeflated(t, x, y));
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

static PetscErrorCode RegisterEvents(void)
{
  PetscFunctionBeginUser;
  if (tmg_registered) PetscFunctionReturn(0);
  PetscCall(PetscLogEventRegister("SgTMGBuild", PC_CLASSID, &SG_TMGBuild));
  PetscCall(PetscLogEventRegister("SgTMGUpdate", PC_CLASSID, &SG_TMGUpdate));
  PetscCall(PetscLogEventRegister("SgTMGCorr", PC_CLASSID, &SG_TMGCorr));
  PetscCall(PetscLogEventRegister("SgTMGCoarse", PC_CLASSID, &SG_TMGCoarse));
  PetscCall(PetscLogEventRegister("SgTMGMGSetUp", PC_CLASSID, &SG_TMGMGSetUp));
  PetscCall(PetscLogEventRegister("SgTMGL1GS", PC_CLASSID, &SG_TMGL1GS));           /* the l1 Gauss-Seidel sweeps (Apply_L1GS) */
  PetscCall(PetscLogEventRegister("SgTMGL1GSSetUp", PC_CLASSID, &SG_TMGL1GSSetUp)); /* their inverted diagonal blocks (SetUp_L1GS) */
  tmg_registered = PETSC_TRUE;
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
  PetscCall(RegisterEvents());
  PetscCall(KSPGetPC(ksp, &pc));
  if (geometric) PetscCall(SgGMGInterpolations(s, &ngeo, &Pgeo));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCHYPRE, &hypre));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCGAMG, &gamg));
  PetscCheck(ngeo || hypre || gamg, s->comm, PETSC_ERR_USER_INPUT, "-ssn_pc_truncated_mg takes the interpolations of an AMG: -pc_type hypre (BoomerAMG) or gamg");
  PetscCall(PetscNew(&t));
  t->ssn   = s;
  t->ksp   = ksp;
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
  PetscCall(PetscObjectComposeFunction((PetscObject)pc, "SgLinearSolverFallback_C", Fallback_TMG)); /* SgLinearSolverFallback */
  PetscCall(KSPSetPC(ksp, pc));
  PetscCall(PCDestroy(&pc));
  *tmg = t;
  PetscFunctionReturn(0);
}

/* The truncated multigrid for the bound-constrained solves of a controller without an SSN (pdas, cont/pdas.c): each
   system is Klin with the active normal dofs eliminated (their rows and columns zeroed, a positive diagonal), so that
   with the finest interpolation truncated there the coarse operators are P_t^T Klin P_t, as for the SSN's Jacobians.
   Klin: the working stiffness (K, or Q^T K Q in frame's coordinates: the contact frames or a pair's dual-mortar basis,
   where a pair's AMG is set up on K in the displacements as with -ssn_pair_amg_displacements, its default); frame
   NULL where every normal is a coordinate axis. As SgTMGCreate: the KSP's preconditioner (hypre or gamg) becomes the
   AMG, or with geometric the interpolations of the mesh hierarchy (gmg.c); the smoothers' defaults (one body's or a
   pair's). */
PetscErrorCode SgTMGCreateBound(SgElasticity p, SgContact c, KSP ksp, Mat Klin, SgFrame frame, PetscBool geometric, SgTMG *tmg)
{
  SgSSN s;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&s));
  s->prob = p;
  s->c    = c;
  PetscCall(SgElasticityGetComm(p, &s->comm));
  PetscCall(SgElasticityGetDimension(p, &s->dim));
  PetscCall(SgElasticityGetMesh(p, &s->mesh));
  PetscCall(SgElasticityGetOperators(p, &s->K, &s->b));
  PetscCall(SgContactGetVertices(c, &s->n, &s->nglobal, &s->vert, &s->off));
  s->Klin       = Klin;
  s->frame      = frame;
  s->pair_amg_u = PETSC_TRUE;
  /* the l1 Gauss-Seidel sweeps on several ranks, not the pair's local SOR: a solver without an SSN has no fallback
     (SgSSNSolveL1GS) to catch SOR's breakdown */
  s->tmg_sor_set = PETSC_TRUE;
  s->tmg_sor     = PETSC_FALSE;
  PetscCall(SgTMGCreate(s, ksp, geometric, tmg));
  (*tmg)->host = s;
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
  PetscCall(PetscFree(t->host));
  PetscCall(SgDeflDestroy(&t->defl));
  if (t->D) {
    for (PetscInt l = 0; l < t->nlevels; l++) PetscCall(MatDestroy(&t->D[l]));
    PetscCall(PetscFree4(t->D, t->str, t->touch, t->prod));
    PetscCall(MatDestroy(&t->Poth));
    PetscCall(VecDestroy(&t->act));
    PetscCall(VecDestroy(&t->gact));
    PetscCall(VecScatterDestroy(&t->gsc));
    PetscCall(PetscFree3(t->acc, t->mark, t->jw));
    PetscCall(PetscFree2(t->pj, t->pv));
    PetscCall(PetscFree2(t->mj, t->mv));
    PetscCall(PetscFree(t->vw));
  }
  PetscCall(PetscFree(*tmg));
  PetscFunctionReturn(0);
}
