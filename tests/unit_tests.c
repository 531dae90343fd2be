/* unit_tests.c: unit tests of the kernels (element stiffness, rigid-body modes, obstacle gaps, model fit).
   Each test computes its numbers and writes them to -summary_file; tests/unit/kernels.ini holds the expected values. */
/* white-box tests: they read the elasticity object's fields (the one place outside src/fem that may) */
#include "fem/femimpl.h"
#include "cont/contimpl.h"
#include "contact/contactimpl.h"
#include "contact/mortar.h"
#include "contact/pair.h"
#include "solver/ssnimpl.h"

static const char help[] = "Unit tests: -test element2d|deflate|element3d|rigid|stiffness|gap|modelfit|rollerapi|controllers|meshtree|mortar|pair|pairapi|pairobstacleapi|lawproperties|mataddsparse|partitionweights -summary_file FILE\n";

/* Hand-computed stiffness of the reference triangle (0,0),(1,0),(0,1) with lambda = mu = 1, dofs (0x,0y,1x,1y,2x,2y):
   K = area (lambda G_ai G_bj + mu (G_aj G_bi + delta_ij G_a.G_b)), G_0 = (-1,-1), G_1 = (1,0), G_2 = (0,1), area = 1/2. */
static const PetscReal Kref2[36] = {2.0, 1.0, -1.5, -0.5, -0.5, -0.5, 1.0, 2.0, -0.5, -0.5, -0.5, -1.5, -1.5, -0.5, 1.5, 0.0, 0.0, 0.5,
                                    -0.5, -0.5, 0.0, 0.5, 0.5, 0.0, -0.5, -0.5, 0.0, 0.5, 0.5, 0.0, -0.5, -1.5, 0.5, 0.0, 0.0, 1.5};

static PetscErrorCode TestElement2D(SgSummary s)
{
  const PetscReal x[6] = {0, 0, 1, 0, 0, 1};
  PetscReal       K[36], vol, err = 0;

  PetscFunctionBeginUser;
  PetscCall(SgElementStiffness(2, x, 1.0, 1.0, K, &vol));
  for (PetscInt i = 0; i < 36; i++) err = PetscMax(err, PetscAbsReal(K[i] - Kref2[i]));
  PetscCall(SgSummarySetReal(s, "max_error", err));
  PetscCall(SgSummarySetReal(s, "volume", vol));
  /* a translated, scaled copy: K scales as h^(d-2) = 1 in 2D, so it must be unchanged */
  {
    const PetscReal y[6] = {3, 2, 5, 2, 3, 4};
    PetscReal       K2[36], e2 = 0;
    PetscCall(SgElementStiffness(2, y, 1.0, 1.0, K2, &vol));
    for (PetscInt i = 0; i < 36; i++) e2 = PetscMax(e2, PetscAbsReal(K2[i] - Kref2[i]));
    PetscCall(SgSummarySetReal(s, "scaled_max_error", e2));
  }
  PetscFunctionReturn(0);
}

/* Reference tetrahedron, lambda = 2, mu = 1, vol = 1/6: selected entries by hand
   K[(0x),(0x)] = (lambda + 4 mu)/6 = 1, K[(1x),(1x)] = (lambda + 2 mu)/6 = 2/3, K[(1x),(2y)] = lambda/6 = 1/3,
   K[(1y),(2x)] = mu/6 = 1/6, K[(0x),(1x)] = -(lambda + 2 mu)/6 = -2/3, K[(3z),(3z)] = 2/3, K[(2x),(2x)] = mu/6 = 1/6. */
static PetscErrorCode TestElement3D(SgSummary s)
{
  const PetscReal x[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const PetscInt  r[7] = {0, 3, 3, 4, 0, 11, 6}, c[7] = {0, 3, 7, 6, 3, 11, 6};
  const PetscReal v[7] = {1.0, 2.0 / 3, 1.0 / 3, 1.0 / 6, -2.0 / 3, 2.0 / 3, 1.0 / 6};
  PetscReal       K[144], vol, err = 0, asym = 0, rowsum = 0;

  PetscFunctionBeginUser;
  PetscCall(SgElementStiffness(3, x, 2.0, 1.0, K, &vol));
  for (PetscInt i = 0; i < 7; i++) err = PetscMax(err, PetscAbsReal(K[r[i] * 12 + c[i]] - v[i]));
  for (PetscInt i = 0; i < 12; i++) {
    for (PetscInt j = 0; j < 12; j++) asym = PetscMax(asym, PetscAbsReal(K[i * 12 + j] - K[j * 12 + i]));
    for (PetscInt d = 0; d < 3; d++) { /* translations are in the kernel */
      PetscReal t = 0;
      for (PetscInt a = 0; a < 4; a++) t += K[i * 12 + a * 3 + d];
      rowsum = PetscMax(rowsum, PetscAbsReal(t));
    }
  }
  PetscCall(SgSummarySetReal(s, "max_error", err));
  PetscCall(SgSummarySetReal(s, "asymmetry", asym));
  PetscCall(SgSummarySetReal(s, "translation_residual", rowsum));
  PetscCall(SgSummarySetReal(s, "volume", vol));
  PetscFunctionReturn(0);
}

/* The assembled stiffness without Dirichlet conditions annihilates the rigid-body modes (and nothing else of them). */
static PetscErrorCode TestRigid(SgSummary s)
{
  SgElasticity p;
  PetscInt     nvec;
  const Vec   *vecs;
  PetscBool    has;
  PetscReal    worst = 0, Knorm;
  Vec          Kz;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityCreate(PETSC_COMM_WORLD, NULL, &p));
  PetscCall(SgElasticitySetFromOptions(p, NULL, NULL));
  PetscCall(SgElasticitySetUp(p));
  PetscCall(MatNullSpaceGetVecs(p->nearnull, &has, &nvec, &vecs));
  PetscCall(MatNorm(p->K, NORM_INFINITY, &Knorm));
  PetscCall(VecDuplicate(p->b, &Kz));
  for (PetscInt i = 0; i < nvec; i++) {
    PetscReal r, z;
    PetscCall(MatMult(p->K, vecs[i], Kz));
    PetscCall(VecNorm(Kz, NORM_INFINITY, &r));
    PetscCall(VecNorm(vecs[i], NORM_INFINITY, &z));
    worst = PetscMax(worst, r / (Knorm * z));
  }
  PetscCall(SgSummarySetInt(s, "modes", nvec));
  PetscCall(SgSummarySetReal(s, "max_relative_residual", worst));
  PetscCall(VecDestroy(&Kz));
  PetscCall(SgElasticityDestroy(&p));
  PetscFunctionReturn(0);
}

/* The stiffness on any number of ranks (src/fem/assembly.c: one rank adds the cells into K's values through the mesh
   graph's pattern; more ranks into their owned rows and a buffer of their ghost rows, summed by the owners): K applied
   to a smooth field of the vertex coordinates (the same on every partition), K's nonzero count and Frobenius norm, and
   K u against K^T u; tests/parallel/asm27.ini compares them between rank counts. */
static PetscErrorCode TestStiffness(SgSummary s)
{
  SgElasticity p;
  Vec          u, y, yt;
  PetscScalar *ua;
  MatInfo      info;
  PetscReal    fro, ynorm, yinf, uKu, asym;
  PetscInt     N;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityCreate(PETSC_COMM_WORLD, NULL, &p));
  PetscCall(SgElasticitySetFromOptions(p, NULL, NULL));
  PetscCall(SgElasticitySetUp(p));
  PetscCall(VecDuplicate(p->b, &u));
  PetscCall(VecDuplicate(p->b, &y));
  PetscCall(VecDuplicate(p->b, &yt));
  PetscCall(VecGetArray(u, &ua));
  for (PetscInt v = 0; v < p->mesh.nv; v++) {
    const PetscReal *x  = p->mesh.x + v * p->dim;
    const PetscReal  x2 = p->dim > 2 ? x[2] : 0;
    if (p->mesh.goff[v] < 0) continue;
    for (PetscInt d = 0; d < p->dim; d++) ua[p->mesh.goff[v] + d] = PetscSinReal(1.3 * x[0] + 0.7 * x[1] + 0.4 * x2 + d) * PetscCosReal(0.9 * x[0] - 1.1 * x[1] + 0.5 * d);
  }
  PetscCall(VecRestoreArray(u, &ua));
  PetscCall(MatMult(p->K, u, y));
  PetscCall(MatMultTranspose(p->K, u, yt));
  PetscCall(VecNorm(y, NORM_2, &ynorm));
  PetscCall(VecNorm(y, NORM_INFINITY, &yinf));
  PetscCall(VecDot(u, y, &uKu));
  PetscCall(VecAXPY(yt, -1.0, y));
  PetscCall(VecNorm(yt, NORM_2, &asym));
  PetscCall(MatGetInfo(p->K, MAT_GLOBAL_SUM, &info));
  PetscCall(MatNorm(p->K, NORM_FROBENIUS, &fro));
  PetscCall(VecGetSize(u, &N));
  PetscCall(SgSummarySetInt(s, "dofs", N));
  PetscCall(SgSummarySetInt(s, "nonzeros", (PetscInt)info.nz_used));
  PetscCall(SgSummarySetReal(s, "frobenius", fro));
  PetscCall(SgSummarySetReal(s, "Ku_norm", ynorm));
  PetscCall(SgSummarySetReal(s, "Ku_max", yinf));
  PetscCall(SgSummarySetReal(s, "uKu", uKu));
  PetscCall(SgSummarySetReal(s, "asymmetry", asym / ynorm));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&y));
  PetscCall(VecDestroy(&yt));
  PetscCall(SgElasticityDestroy(&p));
  PetscFunctionReturn(0);
}

/* The truncated multigrid's l1 Gauss-Seidel sweep on several ranks (tmg.c SgTMGL1GSSweep), from a zero start:
   1. on a block-diagonal matrix of dense 3 x 3 blocks (block size 3; every rank's rows whole blocks, no coupling
      across ranks, so no l1) the block sweep forward and backward is the exact solve; the same values with block size 1
      (the point sweep) are not;
   2. on K of the options' mesh on one rank (no rows of other ranks, no l1), forward, backward and symmetric (forward
      then backward, -ssn_pc_truncated_mg_l1gs_symmetric) against MatSOR's zero-start local sweeps on K's SeqAIJ (its inode sweep by a vertex's rows), the smoother of one rank. */
static PetscErrorCode BlockDiagonal(PetscInt nb, PetscInt bs, Mat *A)
{
  PetscInt lo;

  PetscFunctionBeginUser;
  PetscCall(MatCreate(PETSC_COMM_WORLD, A));
  PetscCall(MatSetSizes(*A, 3 * nb, 3 * nb, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetType(*A, MATMPIAIJ));
  PetscCall(MatSetBlockSize(*A, bs));
  PetscCall(MatMPIAIJSetPreallocation(*A, 3, NULL, 0, NULL));
  PetscCall(MatGetOwnershipRange(*A, &lo, NULL));
  for (PetscInt b = 0; b < nb; b++) {
    const PetscInt r0 = lo + 3 * b, idx[3] = {r0, r0 + 1, r0 + 2};
    PetscScalar    v[9];
    for (PetscInt i = 0; i < 3; i++)
      for (PetscInt j = 0; j < 3; j++) v[i * 3 + j] = i == j ? 4.0 + (r0 + i) % 5 : 1.0 + 0.5 * PetscSinReal((PetscReal)(r0 + i + j));
    PetscCall(MatSetValues(*A, 3, idx, 3, idx, v, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(*A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*A, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

static PetscErrorCode SweepError(Mat A, PetscBool back, PetscBool sym, Vec u, PetscReal *err)
{
  Vec       b, y;
  PetscReal un;

  PetscFunctionBeginUser;
  PetscCall(MatCreateVecs(A, &y, &b));
  PetscCall(MatMult(A, u, b));
  PetscCall(SgTMGL1GSSweep(A, back, sym, b, y));
  PetscCall(VecAXPY(y, -1.0, u));
  PetscCall(VecNorm(y, NORM_2, err));
  PetscCall(VecNorm(u, NORM_2, &un));
  *err /= un;
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&y));
  PetscFunctionReturn(0);
}

static PetscErrorCode TestL1GS(SgSummary s)
{
  Mat         A, A1;
  Vec         u;
  PetscReal   e[5];
  PetscMPIInt size;
  PetscRandom r;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(BlockDiagonal(40, 3, &A));
  PetscCall(BlockDiagonal(40, 1, &A1));
  PetscCall(MatCreateVecs(A, &u, NULL));
  PetscCall(PetscRandomCreate(PETSC_COMM_WORLD, &r));
  PetscCall(PetscRandomSetInterval(r, -1.0, 1.0));
  PetscCall(VecSetRandom(u, r));
  PetscCall(PetscRandomDestroy(&r));
  PetscCall(SweepError(A, PETSC_FALSE, PETSC_FALSE, u, &e[0]));
  PetscCall(SweepError(A, PETSC_TRUE, PETSC_FALSE, u, &e[1]));
  PetscCall(SweepError(A1, PETSC_FALSE, PETSC_FALSE, u, &e[2]));
  PetscCall(SweepError(A1, PETSC_TRUE, PETSC_FALSE, u, &e[3]));
  PetscCall(SweepError(A, PETSC_FALSE, PETSC_TRUE, u, &e[4]));
  PetscCall(SgSummarySetReal(s, "block_forward_err", e[0]));
  PetscCall(SgSummarySetReal(s, "block_backward_err", e[1]));
  PetscCall(SgSummarySetReal(s, "point_forward_err", e[2]));
  PetscCall(SgSummarySetReal(s, "point_backward_err", e[3]));
  PetscCall(SgSummarySetReal(s, "block_symmetric_err", e[4]));
  PetscCall(VecDestroy(&u));
  PetscCall(MatDestroy(&A));
  PetscCall(MatDestroy(&A1));
  if (size == 1) {
    SgElasticity p;
    Mat          K;
    Vec          b, y, z;
    PetscReal    d[3], zn;
    PetscInt     bs;
    PetscCall(SgElasticityCreate(PETSC_COMM_WORLD, NULL, &p));
    PetscCall(SgElasticitySetFromOptions(p, NULL, NULL));
    PetscCall(SgElasticitySetUp(p));
    PetscCall(MatConvert(p->K, MATMPIAIJ, MAT_INITIAL_MATRIX, &K));
    PetscCall(MatGetBlockSize(K, &bs));
    PetscCall(VecDuplicate(p->b, &b));
    PetscCall(VecDuplicate(p->b, &y));
    PetscCall(VecDuplicate(p->b, &z));
    PetscCall(VecSet(y, 1.0));
    PetscCall(MatMult(p->K, y, b));
    PetscCall(VecAXPY(b, 1.0, p->b));
    for (PetscInt k = 0; k < 3; k++) {
      const MatSORType st = k == 2 ? SOR_LOCAL_SYMMETRIC_SWEEP : k ? SOR_LOCAL_BACKWARD_SWEEP
                                                                   : SOR_LOCAL_FORWARD_SWEEP;
      PetscCall(SgTMGL1GSSweep(K, (PetscBool)(k == 1), (PetscBool)(k == 2), b, y));
      PetscCall(MatSOR(p->K, b, 1.0, (MatSORType)(st | SOR_ZERO_INITIAL_GUESS), 0.0, 1, 1, z));
      PetscCall(VecNorm(z, NORM_2, &zn));
      PetscCall(VecAXPY(y, -1.0, z));
      PetscCall(VecNorm(y, NORM_2, &d[k]));
      d[k] /= zn;
    }
    PetscCall(SgSummarySetInt(s, "k_block_size", bs));
    PetscCall(SgSummarySetReal(s, "sor_forward_diff", d[0]));
    PetscCall(SgSummarySetReal(s, "sor_backward_diff", d[1]));
    PetscCall(SgSummarySetReal(s, "sor_symmetric_diff", d[2]));
    PetscCall(VecDestroy(&b));
    PetscCall(VecDestroy(&y));
    PetscCall(VecDestroy(&z));
    PetscCall(MatDestroy(&K));
    PetscCall(SgElasticityDestroy(&p));
  }
  PetscFunctionReturn(0);
}

/* Gaps of the registered obstacles at points with known distances. */
static PetscErrorCode GapAt(const char *type, const char *opts, PetscInt dim, const PetscReal x[], const PetscReal n[], PetscReal *d)
{
  SgObstacle o;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsInsertString(NULL, opts));
  PetscCall(PetscOptionsSetValue(NULL, "-obstacle_type", type));
  PetscCall(SgObstacleCreate(PETSC_COMM_WORLD, NULL, dim, NULL, &o));
  PetscCall(SgObstacleGap(o, x, n, d));
  PetscCall(SgObstacleDestroy(&o));
  PetscFunctionReturn(0);
}

static PetscErrorCode TestGap(SgSummary s)
{
  const char     *ball    = "-obstacle_ball_radius 0.5 -obstacle_ball_center -0.3,0,-1";
  const PetscReal down[3] = {0, 0, -1}, tilt[3] = {0.6, 0, -0.8};
  /* point, normal, expected: ball top, on the sphere 0.3 off axis (height -1 + 0.4), past the rim (floor plane),
     and along a tilted normal aimed at the centre from distance 1 (gap 1 - R) */
  const PetscReal p1[3] = {-0.3, 0, -0.5}, p2[3] = {0, 0, -0.5}, p3[3] = {0.5, 0.2, -0.5}, p4[3] = {-0.3 - 0.6, 0, -1 + 0.8};
  PetscReal       d, err = 0, e2d = 0;

  PetscFunctionBeginUser;
  PetscCall(GapAt("ball", ball, 3, p1, down, &d));
  err = PetscMax(err, PetscAbsReal(d - 0.0));
  PetscCall(GapAt("ball", ball, 3, p2, down, &d));
  err = PetscMax(err, PetscAbsReal(d - 0.1));
  PetscCall(GapAt("ball", ball, 3, p3, down, &d));
  err = PetscMax(err, PetscAbsReal(d - 0.5));
  PetscCall(GapAt("ball", ball, 3, p4, tilt, &d));
  err = PetscMax(err, PetscAbsReal(d - 0.5));
  PetscCall(SgSummarySetReal(s, "ball_max_error", err));
  {
    const PetscReal x[2] = {2.5, 0}, n[2] = {0, -1}, y[2] = {1.5, 0};
    PetscCall(GapAt("parabola", "-obstacle_parabola_a 0.003 -obstacle_parabola_offset 0.001 -obstacle_parabola_center 1.5,0", 2, x, n, &d));
    e2d = PetscMax(e2d, PetscAbsReal(d - 0.004));
    PetscCall(GapAt("parabola", "", 2, y, n, &d));
    e2d = PetscMax(e2d, PetscAbsReal(d - 0.001));
  }
  PetscCall(SgSummarySetReal(s, "parabola_max_error", e2d));
  {
    const PetscReal x[3] = {1, 2, 3}, n[3] = {0, 0, -1}, n45[3] = {0, -PetscSqrtReal(0.5), -PetscSqrtReal(0.5)};
    PetscReal       e = 0;
    PetscCall(GapAt("plane", "-obstacle_plane_point 0,0,1 -obstacle_plane_normal 0,0,1", 3, x, n, &d));
    e = PetscMax(e, PetscAbsReal(d - 2));
    PetscCall(GapAt("plane", "", 3, x, n45, &d));
    e = PetscMax(e, PetscAbsReal(d - 2 * PetscSqrtReal(2.0)));
    PetscCall(SgSummarySetReal(s, "plane_max_error", e));
  }
  PetscFunctionReturn(0);
}

/* The model m(gamma) = C1 - C2/(E + gamma) is recovered exactly from V(0), V(g), V'(g) of a synthetic V = m. */
static PetscErrorCode TestModelFit(SgSummary s)
{
  const PetscReal C1 = -0.0104, C2 = 3.7e-2, E = 350.0, g[3] = {1e2, 1e5, 1e9};
  PetscReal       err = 0;
  PetscBool       ok  = PETSC_TRUE;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < 3; i++) {
    const PetscReal V0 = C1 - C2 / E, V = C1 - C2 / (E + g[i]), dV = C2 / PetscSqr(E + g[i]);
    PetscReal       c1, c2, e;
    ok  = (PetscBool)(ok && SgModelFit(V0, g[i], V, dV, &c1, &c2, &e));
    err = PetscMax(err, PetscMax(PetscAbsReal(c1 - C1) / PetscAbsReal(C1), PetscMax(PetscAbsReal(c2 - C2) / C2, PetscAbsReal(e - E) / E)));
  }
  PetscCall(SgSummarySetBool(s, "fitted", ok));
  PetscCall(SgSummarySetReal(s, "max_relative_error", err));
  /* data no model of this form can fit (V decreasing in gamma) are refused */
  {
    PetscReal c1, c2, e;
    PetscCall(SgSummarySetBool(s, "refuses_bad_data", (PetscBool)!SgModelFit(1.0, 10.0, 0.5, 0.1, &c1, &c2, &e)));
  }
  PetscFunctionReturn(0);
}

/* Rollers through the public interface (SgProblemSetDirichletComponents): the box [0,2] x [0,1] on rollers (u_y = 0 at
   the bottom, u_x = 0 on the left) under the traction (0,-1) on the top is in uniaxial plane-strain stress, linear, so
   P1 is exact: V = -1/2 int_top t.u = -(1 - nu^2) / E * width / 2. -bad_mask M: pass M as the left face's mask. */
/* Solve the problem (set from the options too) with a controller from the options: "converged" and "energy" into the
   summary, the KKT measures into *kkt (if not NULL) */
static PetscErrorCode SolveRecord(SgProblem prob, SgSummary s, SgKKT *kkt)
{
  SgCont      ct;
  PetscReal   V;
  PetscBool   conv;
  const char *reason;

  PetscFunctionBeginUser;
  PetscCall(SgProblemSetFromOptions(prob));
  PetscCall(SgContCreate(prob, &ct));
  PetscCall(SgContSetFromOptions(ct));
  PetscCall(SgContSolve(ct));
  PetscCall(SgContGetConvergedReason(ct, &conv, &reason));
  PetscCall(SgContGetEnergy(ct, &V));
  if (kkt) PetscCall(SgContGetKKT(ct, kkt));
  PetscCall(SgSummarySetBool(s, "converged", conv));
  PetscCall(SgSummarySetReal(s, "energy", V));
  PetscCall(SgContDestroy(&ct));
  PetscFunctionReturn(0);
}

static PetscErrorCode TestRollerAPI(SgSummary s)
{
  SgProblem       prob;
  const PetscInt  ids[2] = {1, 4}, top[1] = {3};
  PetscInt        masks[2] = {SG_COMPONENT_Y, SG_COMPONENT_X};
  const PetscReal t[2]     = {0, -1};

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-bad_mask", &masks[1], NULL));
  PetscCall(SgProblemCreate(PETSC_COMM_WORLD, &prob));
  PetscCall(SgProblemSetMaterial(prob, 1000, 0.3));
  PetscCall(SgProblemSetBoundary(prob, SG_BOUNDARY_DIRICHLET, "Face Sets", 2, ids, NULL));
  PetscCall(SgProblemSetDirichletComponents(prob, 2, masks));
  PetscCall(SgProblemSetBoundary(prob, SG_BOUNDARY_NEUMANN, "Face Sets", 1, top, t));
  PetscCall(SolveRecord(prob, s, NULL));
  PetscCall(SgSummarySetReal(s, "energy_exact", -(1 - 0.09) / 1000 * 2 / 2));
  PetscCall(SgProblemDestroy(&prob));
  PetscFunctionReturn(0);
}

/* Controllers on one problem (issue 25): each SgCont owns the history of its solves (the friction slip reference,
   its last load step), so a new controller on a problem another one solved solves as on a fresh problem, and two
   controllers taking turns on one problem do not disturb each other. The problem comes from the options (-cont_type
   too); every solve's energy, contact force, friction force and displacement are compared with those of the same
   sequence of solves on a fresh problem. -report_file: A's summary, written after B solved, read back. */
typedef struct {
  PetscReal V, force, friction;
  Vec       y;
} CtlResult;

static PetscErrorCode CtlProblem(SgProblem *p)
{
  PetscFunctionBeginUser;
  PetscCall(SgProblemCreate(PETSC_COMM_WORLD, p));
  PetscCall(SgProblemSetFromOptions(*p));
  PetscCall(SgProblemSetUp(*p));
  PetscFunctionReturn(0);
}

static PetscErrorCode CtlCont(SgProblem p, SgCont *ct)
{
  PetscFunctionBeginUser;
  PetscCall(SgContCreate(p, ct));
  PetscCall(SgContSetFromOptions(*ct));
  PetscFunctionReturn(0);
}

/* solve at load factor t; r: the result (r->y allocated here); *nfail counts the solves that did not converge */
static PetscErrorCode CtlSolve(SgProblem p, SgCont ct, PetscReal t, CtlResult *r, PetscInt *nfail)
{
  SgContact c;
  SgKKT     kkt;
  PetscBool conv;
  Vec       y;

  PetscFunctionBeginUser;
  PetscCall(SgProblemSetLoadFactor(p, t));
  PetscCall(SgContSolve(ct));
  PetscCall(SgContGetConvergedReason(ct, &conv, NULL));
  if (!conv) (*nfail)++;
  PetscCall(SgContGetEnergy(ct, &r->V));
  PetscCall(SgContGetKKT(ct, &kkt));
  r->force    = kkt.force;
  r->friction = 0;
  PetscCall(SgProblemGetContact(p, &c));
  if (c) {
    SgContactView cv;
    PetscCall(SgContactGetView(c, &cv));
    if (cv.props.tangential) {
      SgFrictionSummary fs;
      PetscCall(SgContactGetFrictionSummary(c, &fs)); /* of the KKT measures of this solve's result */
      r->friction = fs.force_norm;
    }
  }
  PetscCall(SgContGetSolution(ct, &y));
  PetscCall(VecDuplicate(y, &r->y));
  PetscCall(VecCopy(y, r->y));
  PetscFunctionReturn(0);
}

static PetscReal CtlRel(PetscReal a, PetscReal b)
{
  return PetscAbsReal(a - b) / PetscMax(PetscMax(PetscAbsReal(a), PetscAbsReal(b)), 1e-300);
}

/* the largest relative difference of two results (energy, contact force, friction force, displacement: entry by entry
   on one rank; on more, where two problems may be partitioned differently, its 1-, 2- and max norms) */
static PetscErrorCode CtlDiff(const CtlResult *a, const CtlResult *b, PetscReal *d)
{
  PetscReal   nb, nd;
  PetscMPIInt size;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)a->y), &size));
  if (size == 1) {
    Vec w;
    PetscCall(VecDuplicate(a->y, &w));
    PetscCall(VecWAXPY(w, -1.0, b->y, a->y));
    PetscCall(VecNorm(w, NORM_INFINITY, &nd));
    PetscCall(VecNorm(b->y, NORM_INFINITY, &nb));
    PetscCall(VecDestroy(&w));
    nd /= PetscMax(nb, 1e-300);
  } else {
    const NormType types[3] = {NORM_1, NORM_2, NORM_INFINITY};
    nd                      = 0;
    for (PetscInt k = 0; k < 3; k++) {
      PetscReal na;
      PetscCall(VecNorm(a->y, types[k], &na));
      PetscCall(VecNorm(b->y, types[k], &nb));
      nd = PetscMax(nd, CtlRel(na, nb));
    }
  }
  *d = PetscMax(PetscMax(CtlRel(a->V, b->V), CtlRel(a->force, b->force)), nd);
  if (a->friction != 0 || b->friction != 0) *d = PetscMax(*d, CtlRel(a->friction, b->friction));
  PetscFunctionReturn(0);
}

/* the number after "key": in a JSON summary (NaN if missing) */
static PetscReal CtlJson(const char *buf, const char key[])
{
  char        pat[128];
  const char *q;

  (void)PetscSNPrintf(pat, sizeof(pat), "\"%s\": ", key);
  q = strstr(buf, pat);
  return q ? (PetscReal)strtod(q + strlen(pat), NULL) : (PetscReal)NAN;
}

static PetscErrorCode TestControllers(SgSummary s)
{
  SgProblem p1, p2, p3;
  SgCont    A, B, C, D;
  CtlResult rA[3], rB[3], rC[3], rD[3];
  PetscInt  nfail = 0;
  PetscReal d;
  char      file[PETSC_MAX_PATH_LEN] = "";

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetString(NULL, NULL, "-report_file", file, sizeof(file), NULL));
  PetscCall(CtlProblem(&p1));
  PetscCall(CtlProblem(&p2));
  PetscCall(CtlProblem(&p3));
  PetscCall(CtlCont(p1, &A));
  PetscCall(CtlCont(p1, &B));
  PetscCall(CtlCont(p2, &C));
  PetscCall(CtlCont(p3, &D));
  /* A loads to 1 and unloads to 0.5; then B, new, solves the same problem at 0.5 */
  PetscCall(CtlSolve(p1, A, 1.0, &rA[0], &nfail));
  PetscCall(CtlSolve(p1, A, 0.5, &rA[1], &nfail));
  PetscCall(CtlSolve(p1, B, 0.5, &rB[0], &nfail));
  /* references: a fresh problem solved at 0.5 (C), and the path 1, 0.5 on another (D) */
  PetscCall(CtlSolve(p2, C, 0.5, &rC[0], &nfail));
  PetscCall(CtlSolve(p3, D, 1.0, &rD[0], &nfail));
  PetscCall(CtlSolve(p3, D, 0.5, &rD[1], &nfail));
  PetscCall(CtlDiff(&rB[0], &rC[0], &d));
  PetscCall(SgSummarySetReal(s, "fresh_diff", d)); /* B as a new controller on a fresh problem */
  PetscCall(CtlDiff(&rA[1], &rC[0], &d));
  PetscCall(SgSummarySetReal(s, "path_diff", d)); /* unloading from 1 against loading to 0.5: the path matters with friction */
  PetscCall(CtlDiff(&rA[1], &rD[1], &d));
  PetscCall(SgSummarySetReal(s, "a_diff", d));
  /* taking turns on p1: B continues to 0.25 from its 0.5, A to 0.25 from its 0.5, B to 0.125 */
  PetscCall(CtlSolve(p1, B, 0.25, &rB[1], &nfail));
  PetscCall(CtlSolve(p2, C, 0.25, &rC[1], &nfail));
  PetscCall(CtlSolve(p1, A, 0.25, &rA[2], &nfail));
  PetscCall(CtlSolve(p3, D, 0.25, &rD[2], &nfail));
  PetscCall(CtlSolve(p1, B, 0.125, &rB[2], &nfail));
  PetscCall(CtlSolve(p2, C, 0.125, &rC[2], &nfail));
  PetscCall(CtlDiff(&rB[1], &rC[1], &d));
  PetscCall(SgSummarySetReal(s, "turns_b_diff", d));
  PetscCall(CtlDiff(&rA[2], &rD[2], &d));
  PetscCall(SgSummarySetReal(s, "turns_a_diff", d));
  PetscCall(CtlDiff(&rB[2], &rC[2], &d));
  PetscCall(SgSummarySetReal(s, "turns_b2_diff", d));
  /* A's summary, written after B's last solve, is A's result */
  if (file[0]) {
    FILE  *fp;
    char  *buf;
    size_t n;
    PetscCall(SgContWriteSummary(A, file));
    PetscCall(PetscFOpen(PETSC_COMM_SELF, file, "r", &fp));
    PetscCall(PetscMalloc1(1 << 16, &buf));
    n      = fread(buf, 1, (1 << 16) - 1, fp);
    buf[n] = 0;
    PetscCall(PetscFClose(PETSC_COMM_SELF, fp));
    {
      const PetscReal V = CtlJson(buf, "energy"), F = CtlJson(buf, "contact_force"), Ff = CtlJson(buf, "friction_force");
      PetscReal       e = PetscMax(CtlRel(V, rA[2].V), CtlRel(F, rA[2].force));
      if (rA[2].friction != 0) e = PetscMax(e, CtlRel(Ff, rA[2].friction));
      PetscCall(SgSummarySetReal(s, "report_a_diff", e));
    }
    PetscCall(PetscFree(buf));
  }
  PetscCall(SgSummarySetInt(s, "not_converged", nfail));
  PetscCall(SgSummarySetReal(s, "energy_half", rC[0].V));
  PetscCall(SgSummarySetReal(s, "force_half", rC[0].force));
  PetscCall(SgSummarySetReal(s, "friction_half", rC[0].friction));
  for (PetscInt k = 0; k < 3; k++) {
    PetscCall(VecDestroy(&rA[k].y));
    PetscCall(VecDestroy(&rB[k].y));
    PetscCall(VecDestroy(&rC[k].y));
  }
  for (PetscInt k = 0; k < 3; k++) PetscCall(VecDestroy(&rD[k].y));
  PetscCall(SgContDestroy(&A));
  PetscCall(SgContDestroy(&B));
  PetscCall(SgContDestroy(&C));
  PetscCall(SgContDestroy(&D));
  PetscCall(SgProblemDestroy(&p1));
  PetscCall(SgProblemDestroy(&p2));
  PetscCall(SgProblemDestroy(&p3));
  PetscFunctionReturn(0);
}

/* A second SgContSolve at the same load (issue 25, item 8): the warm start is the solution already; the run must say
   CONVERGED (the first solve's problem from the options, e.g. Coulomb friction) and keep the answer. -resolve_factor t:
   the load factor of both solves. */
static PetscErrorCode TestResolve(SgSummary s)
{
  SgProblem   prob;
  SgCont      ct;
  PetscReal   V[2], t = 1, kkt[2];
  PetscBool   conv[2];
  PetscInt    its[2];
  SgKKT       k;
  const char *reason;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-resolve_factor", &t, NULL));
  PetscCall(SgProblemCreate(PETSC_COMM_WORLD, &prob));
  PetscCall(SgProblemSetFromOptions(prob));
  PetscCall(SgContCreate(prob, &ct));
  PetscCall(SgContSetFromOptions(ct));
  for (PetscInt r = 0; r < 2; r++) {
    PetscCall(SgProblemSetLoadFactor(prob, t));
    PetscCall(SgContSolve(ct));
    PetscCall(SgContGetConvergedReason(ct, &conv[r], &reason));
    PetscCall(SgContGetEnergy(ct, &V[r]));
    PetscCall(SgContGetKKT(ct, &k));
    PetscCall(SgContGetIterationNumbers(ct, NULL, &its[r], NULL));
    kkt[r] = k.residual;
  }
  PetscCall(SgSummarySetBool(s, "converged1", conv[0]));
  PetscCall(SgSummarySetBool(s, "converged2", conv[1]));
  PetscCall(SgSummarySetString(s, "reason2", reason));
  PetscCall(SgSummarySetReal(s, "energy1", V[0]));
  PetscCall(SgSummarySetReal(s, "energy2", V[1]));
  PetscCall(SgSummarySetReal(s, "kkt1", kkt[0]));
  PetscCall(SgSummarySetReal(s, "kkt2", kkt[1]));
  PetscCall(SgSummarySetInt(s, "ssn2", its[1]));
  PetscCall(SgContDestroy(&ct));
  PetscCall(SgProblemDestroy(&prob));
  PetscFunctionReturn(0);
}

/* A load path through the library (SgProblemSetLoadFactor, SgContSolve per step) with factors from -factors (any
   order, 0 allowed: unloaded): the problem and the solver from the options. Per step: converged, the energy, the KKT
   residual and its scales, ||y||_inf, and the energy at factor 1 of a fresh solver (to compare a return to the load). */
static PetscErrorCode TestLoadPath(SgSummary s)
{
  SgProblem prob;
  SgCont    ct;
  PetscReal f[16], V[16], r[16], ymax[16], us[16], fs[16], cv[16];
  PetscInt  n = 16;
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetRealArray(NULL, NULL, "-factors", f, &n, &set));
  PetscCheck(set && n > 0, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "-factors: give the load factors of the path");
  PetscCall(SgProblemCreate(PETSC_COMM_WORLD, &prob));
  PetscCall(SgProblemSetFromOptions(prob));
  PetscCall(SgContCreate(prob, &ct));
  PetscCall(SgContSetFromOptions(ct));
  for (PetscInt k = 0; k < n; k++) {
    SgKKT       kkt;
    PetscBool   conv;
    Vec         y;
    const char *reason;
    PetscCall(SgProblemSetLoadFactor(prob, f[k]));
    PetscCall(SgContSolve(ct));
    PetscCall(SgContGetConvergedReason(ct, &conv, &reason));
    PetscCall(SgContGetKKT(ct, &kkt));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "load factor %g: %s %s (KKT equilibrium %.3e, dual %.3e, infeasibility %.3e, complementarity %.3e)\n", (double)f[k], conv ? "CONVERGED" : "FAILED", reason, (double)kkt.equilibrium, (double)kkt.dual, (double)kkt.infeasibility, (double)kkt.complementarity));
    PetscCall(SgContGetEnergy(ct, &V[k]));
    PetscCall(SgContGetKKT(ct, &kkt));
    PetscCall(SgContGetSolution(ct, &y));
    PetscCall(VecNorm(y, NORM_INFINITY, &ymax[k]));
    cv[k] = conv;
    r[k]  = kkt.residual;
    us[k] = kkt.uscale;
    fs[k] = kkt.fscale;
  }
  PetscCall(SgSummarySetRealArray(s, "factors", n, f));
  PetscCall(SgSummarySetRealArray(s, "converged", n, cv));
  PetscCall(SgSummarySetRealArray(s, "energy", n, V));
  PetscCall(SgSummarySetRealArray(s, "kkt_residual", n, r));
  PetscCall(SgSummarySetRealArray(s, "displacement_max", n, ymax));
  PetscCall(SgSummarySetRealArray(s, "displacement_scale", n, us));
  PetscCall(SgSummarySetRealArray(s, "force_scale", n, fs));
  PetscCall(SgContDestroy(&ct));
  PetscCall(SgProblemDestroy(&prob));
  PetscFunctionReturn(0);
}

/* A meshed obstacle (-obstacle_cad_file, an approximation of the sphere -mesh_center c, -mesh_radius R) queried at
   random points along random directions (half of them aimed at the centre): the tree's gap and signed distance
   against brute force over all elements, and both against the exact sphere. */
static PetscErrorCode TestMeshTree(SgSummary s)
{
  PetscInt    dim = 3, npts = 2000, nc = 3, nhit = 0, nmiss = 0, nmismatch = 0, nsign = 0, ninside = 0;
  PetscReal   c[3] = {0, 0, 0}, R = 1, dgap = 0, ddist = 0, dnrm = 0, esph = 0, egap = 0;
  SgObstacle  o;
  PetscRandom rnd;

  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Meshed obstacle tree test", NULL);
  PetscCall(PetscOptionsInt("-mesh_dim", "Dimension", NULL, dim, &dim, NULL));
  PetscCall(PetscOptionsInt("-mesh_points", "Random points", NULL, npts, &npts, NULL));
  PetscCall(PetscOptionsRealArray("-mesh_center", "Centre of the sphere the mesh approximates", NULL, c, &nc, NULL));
  PetscCall(PetscOptionsReal("-mesh_radius", "Its radius", NULL, R, &R, NULL));
  PetscOptionsEnd();
  PetscCall(PetscOptionsSetValue(NULL, "-obstacle_type", "cad"));
  PetscCall(SgObstacleCreate(PETSC_COMM_WORLD, NULL, dim, NULL, &o));
  PetscCheck(o->distance, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "meshtree: the obstacle has no distance op");
  PetscCall(PetscRandomCreate(PETSC_COMM_SELF, &rnd));
  PetscCall(PetscRandomSetInterval(rnd, -1, 1));
  for (PetscInt i = 0; i < npts; i++) {
    PetscReal x[3] = {0, 0, 0}, n[3] = {0, 0, 0}, r = 0, nn = 0, dt, db, gt, gb, nt[3] = {0, 0, 0}, nb[3] = {0, 0, 0}, gx, b = 0, disc;
    for (PetscInt k = 0; k < dim; k++) {
      PetscReal v;
      PetscCall(PetscRandomGetValueReal(rnd, &v));
      x[k] = c[k] + 1.6 * R * v;
      r += PetscSqr(x[k] - c[k]);
      PetscCall(PetscRandomGetValueReal(rnd, &v));
      n[k] = i % 2 ? v : c[k] - x[k];
      nn += n[k] * n[k];
    }
    r = PetscSqrtReal(r);
    for (PetscInt k = 0; k < dim; k++) n[k] /= PetscSqrtReal(nn);
    PetscCall(SgObstacleGap(o, x, n, &dt));
    PetscCall(SgObstacleMeshQuery(o, PETSC_FALSE, x, NULL, NULL, &gt, nt)); /* the tree (o->distance adds the checks) */
    PetscCall(SgObstacleMeshQuery(o, PETSC_TRUE, x, n, &db, &gb, nb));
    if ((dt == PETSC_MAX_REAL) != (db == PETSC_MAX_REAL)) nmismatch++;
    else if (dt != PETSC_MAX_REAL) dgap = PetscMax(dgap, PetscAbsReal(dt - db));
    ddist = PetscMax(ddist, PetscAbsReal(gt - gb));
    for (PetscInt k = 0; k < dim; k++) dnrm = PetscMax(dnrm, PetscAbsReal(nt[k] - nb[k]));
    /* the sphere: signed distance |x - c| - R; the ray enters it at -b - sqrt(b^2 - (r^2 - R^2)), b = n.(x - c) */
    gx   = r - R;
    esph = PetscMax(esph, PetscAbsReal(gt - gx));
    if (PetscAbsReal(gx) > 0.05 * R && (gt < 0) != (gx < 0)) nsign++;
    ninside += gt < 0;
    for (PetscInt k = 0; k < dim; k++) b += n[k] * (x[k] - c[k]);
    disc = b * b - (r * r - R * R);
    if (dt != PETSC_MAX_REAL) {
      nhit++;
      if (disc > 0.1 * R * R) egap = PetscMax(egap, PetscAbsReal(dt - (-b - PetscSqrtReal(disc))));
    } else if (disc > 0.1 * R * R && (gx < 0 || b < 0)) nmiss++; /* the sphere is met well inside its outline, the mesh missed */
  }
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(SgObstacleDestroy(&o));
  PetscCall(SgSummarySetInt(s, "points", npts));
  PetscCall(SgSummarySetInt(s, "hits", nhit));
  PetscCall(SgSummarySetInt(s, "inside", ninside));
  PetscCall(SgSummarySetInt(s, "hit_mismatches", nmismatch));
  PetscCall(SgSummarySetInt(s, "missed_hits", nmiss));
  PetscCall(SgSummarySetInt(s, "sign_errors", nsign));
  PetscCall(SgSummarySetReal(s, "tree_gap_difference", dgap));
  PetscCall(SgSummarySetReal(s, "tree_distance_difference", ddist));
  PetscCall(SgSummarySetReal(s, "tree_normal_difference", dnrm));
  PetscCall(SgSummarySetReal(s, "sphere_distance_error", esph));
  PetscCall(SgSummarySetReal(s, "sphere_gap_error", egap));
  PetscFunctionReturn(0);
}

/* ---- mortar integrals (src/contact/mortar.c) ---- */

/* A structured surface: 2D, nx segments along x over [x0, x1] at height y = z0 + sx x; 3D, nx x ny cells (two
   triangles each) over [x0, x1] x [y0, y1], z = z0 + sx x + sy y, turned by angle rot about the z axis around the
   square's centre. Interior vertices are moved by up to jit of a cell (deterministic). Facet normals: (0, ..., up ? 1 :
   -1) up to the tilt (computed). */
typedef struct {
  PetscInt   dim, nv, nf;
  PetscReal *x, *nrm;
  PetscInt  *facets;
} TestSurface;

static PetscErrorCode TestSurfaceCreate(PetscInt dim, PetscInt nx, PetscInt ny, const PetscReal box[4], PetscReal z0, PetscReal sx, PetscReal sy, PetscReal rot, PetscReal jit, PetscBool up, TestSurface *t)
{
  PetscFunctionBeginUser;
  t->dim = dim;
  t->nv  = dim == 2 ? nx + 1 : (nx + 1) * (ny + 1);
  t->nf  = dim == 2 ? nx : 2 * nx * ny;
  PetscCall(PetscMalloc3(dim * t->nv, &t->x, dim * t->nf, &t->nrm, dim * t->nf, &t->facets));
  for (PetscInt j = 0; j <= (dim == 2 ? 0 : ny); j++)
    for (PetscInt i = 0; i <= nx; i++) {
      PetscInt  v  = j * (nx + 1) + i;
      PetscReal dx = (box[1] - box[0]) / nx, dy = dim == 3 ? (box[3] - box[2]) / ny : 0;
      PetscReal px = box[0] + i * dx, py = dim == 3 ? box[2] + j * dy : 0;
      if (i > 0 && i < nx && (dim == 2 || (j > 0 && j < ny))) {
        px += jit * dx * PetscSinReal(3.1 * v + 0.7);
        if (dim == 3) py += jit * dy * PetscCosReal(2.3 * v + 0.4);
      }
      if (dim == 3 && rot != 0) {
        PetscReal cx = 0.5 * (box[0] + box[1]), cy = 0.5 * (box[2] + box[3]), qx = px - cx, qy = py - cy;
        px = cx + PetscCosReal(rot) * qx - PetscSinReal(rot) * qy;
        py = cy + PetscSinReal(rot) * qx + PetscCosReal(rot) * qy;
      }
      t->x[dim * v] = px;
      if (dim == 2) t->x[2 * v + 1] = z0 + sx * px;
      else t->x[3 * v + 1] = py, t->x[3 * v + 2] = z0 + sx * px + sy * py;
    }
  for (PetscInt f = 0; f < t->nf; f++) {
    PetscReal *n = t->nrm + dim * f, len = 0;
    if (dim == 2) {
      t->facets[2 * f] = f, t->facets[2 * f + 1] = f + 1;
      n[0] = -sx, n[1] = 1; /* the upward normal of y = z0 + sx x */
    } else {
      PetscInt  c = f / 2, i = c % nx, j = c / nx, v = j * (nx + 1) + i;
      PetscInt *F = t->facets + 3 * f;
      if (f % 2 == 0) F[0] = v, F[1] = v + 1, F[2] = v + nx + 2;
      else F[0] = v, F[1] = v + nx + 2, F[2] = v + nx + 1;
      n[0] = -sx, n[1] = -sy, n[2] = 1;
    }
    for (PetscInt c = 0; c < dim; c++) len += n[c] * n[c];
    for (PetscInt c = 0; c < dim; c++) n[c] *= (up ? 1 : -1) / PetscSqrtReal(len);
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode TestSurfaceDestroy(TestSurface *t)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree3(t->x, t->nrm, t->facets));
  PetscFunctionReturn(0);
}

/* The lumped weights int phi_j of a surface (facet measure / number of its vertices, summed) */
static void TestLumped(const TestSurface *t, PetscReal w[])
{
  for (PetscInt v = 0; v < t->nv; v++) w[v] = 0;
  for (PetscInt f = 0; f < t->nf; f++) {
    const PetscInt *F = t->facets + t->dim * f;
    PetscReal       meas;
    if (t->dim == 2) meas = PetscSqrtReal(PetscSqr(t->x[2 * F[1]] - t->x[2 * F[0]]) + PetscSqr(t->x[2 * F[1] + 1] - t->x[2 * F[0] + 1]));
    else {
      PetscReal a[3], b[3], c[3];
      for (PetscInt k = 0; k < 3; k++) a[k] = t->x[3 * F[1] + k] - t->x[3 * F[0] + k], b[k] = t->x[3 * F[2] + k] - t->x[3 * F[0] + k];
      c[0] = a[1] * b[2] - a[2] * b[1], c[1] = a[2] * b[0] - a[0] * b[2], c[2] = a[0] * b[1] - a[1] * b[0];
      meas = 0.5 * PetscSqrtReal(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    }
    for (PetscInt k = 0; k < t->dim; k++) w[F[k]] += meas / t->dim;
  }
}

/* summary key PREFIX_NAME = v */
static PetscErrorCode SetKeyed(SgSummary sum, const char prefix[], const char name[], PetscReal v)
{
  char key[128];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(key, sizeof(key), "%s_%s", prefix, name));
  PetscCall(SgSummarySetReal(sum, key, v));
  PetscFunctionReturn(0);
}

/* One case: the slave surface below a master surface, or the master below; prefix names the summary keys:
   PREFIX_area                covered measure (expected: given)
   PREFIX_rowsum_error        max_j |sum_k M_jk - D_j|                 (rigid translations have no jump)
   PREFIX_linear_error        max_j, c |sum_k M_jk x^m_kc - D_j x_jc|  (linear fields along the surface: covered vertices)
   PREFIX_lumped_error        max_j |D_j - int phi_j|                  (fully covered slave facets: biorthogonality)
   PREFIX_gap_error           max_j |g0_j - D_j g(x_j)|                (g affine: the weighted gap is exact)
   PREFIX_diagonal_error      max |M_jk - delta_jk D_j| (matching meshes only: the projection is the identity) */
static PetscErrorCode TestMortarCase(SgSummary sum, const char prefix[], const TestSurface *ts, const TestSurface *tm, PetscReal dmax, PetscBool covered, PetscBool matching, const PetscReal gcoef[3])
{
  SgMortarSurface s = {ts->dim, ts->nv, ts->nf, ts->x, ts->facets, ts->nrm}, m = {tm->dim, tm->nv, tm->nf, tm->x, tm->facets, tm->nrm};
  PetscInt        dim = ts->dim, nM, *Mr, *Mc;
  PetscReal      *D, *g0, *Mv, *w, *rs, *lin, area, erow = 0, elin = 0, elump = 0, egap = 0, ediag = 0;
  char            key[128];

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc5(ts->nv, &D, ts->nv, &g0, ts->nv, &w, ts->nv, &rs, dim * ts->nv, &lin));
  PetscCall(SgMortarIntegrals(&s, &m, dmax, PETSC_FALSE, D, g0, &nM, &Mr, &Mc, &Mv, &area, NULL));
  TestLumped(ts, w);
  PetscCall(PetscArrayzero(rs, ts->nv));
  PetscCall(PetscArrayzero(lin, dim * ts->nv));
  for (PetscInt k = 0; k < nM; k++) {
    rs[Mr[k]] += Mv[k];
    for (PetscInt c = 0; c < dim - 1; c++) lin[dim * Mr[k] + c] += Mv[k] * tm->x[dim * Mc[k] + c];
  }
  if (matching) { /* M summed per (j, k) must be diag(D) */
    PetscReal *Md;
    PetscCall(PetscCalloc1(ts->nv * tm->nv, &Md));
    for (PetscInt k = 0; k < nM; k++) Md[tm->nv * Mr[k] + Mc[k]] += Mv[k];
    for (PetscInt j = 0; j < ts->nv; j++)
      for (PetscInt k = 0; k < tm->nv; k++) ediag = PetscMax(ediag, PetscAbsReal(Md[tm->nv * j + k] - (j == k ? D[j] : 0)));
    PetscCall(PetscFree(Md));
  }
  for (PetscInt j = 0; j < ts->nv; j++) {
    PetscReal gx = gcoef[0] + gcoef[1] * ts->x[dim * j] + (dim == 3 ? gcoef[2] * ts->x[dim * j + 1] : 0);
    erow         = PetscMax(erow, PetscAbsReal(rs[j] - D[j]));
    if (covered) {
      elump = PetscMax(elump, PetscAbsReal(D[j] - w[j]));
      egap  = PetscMax(egap, PetscAbsReal(g0[j] - D[j] * gx));
      for (PetscInt c = 0; c < dim - 1; c++) elin = PetscMax(elin, PetscAbsReal(lin[dim * j + c] - D[j] * ts->x[dim * j + c]));
    }
  }
  PetscCall(SetKeyed(sum, prefix, "area", area));
  PetscCall(SetKeyed(sum, prefix, "rowsum_error", erow));
  PetscCall(PetscSNPrintf(key, sizeof(key), "%s_pairs", prefix));
  PetscCall(SgSummarySetInt(sum, key, nM));
  if (covered) {
    PetscCall(SetKeyed(sum, prefix, "lumped_error", elump));
    PetscCall(SetKeyed(sum, prefix, "linear_error", elin));
    PetscCall(SetKeyed(sum, prefix, "gap_error", egap));
  }
  if (matching) PetscCall(SetKeyed(sum, prefix, "diagonal_error", ediag));
  PetscCall(PetscFree(Mr));
  PetscCall(PetscFree(Mc));
  PetscCall(PetscFree(Mv));
  PetscCall(PetscFree5(D, g0, w, rs, lin));
  PetscFunctionReturn(0);
}

/* The slave surface is y = 0 (2D) or z = 0 (3D) over the unit interval/square, its body above (outward normal down);
   the master surfaces lie below, facing up. Distances along the slave normal: g = -(z_master) at the slave point. */
static PetscErrorCode TestMortar(SgSummary sum)
{
  const PetscReal unit[4] = {0, 1, 0, 1}, wide[4] = {-0.2, 1.3, -0.15, 1.2}, part[4] = {0.25, 0.75, 0.25, 0.75}, far[4] = {-1, 2, -1, 2};
  TestSurface     s2, s2j, m2, m2t, m2p, m2far, s3, s3j, m3, m3t, m3p;

  PetscFunctionBeginUser;
  /* 2D */
  PetscCall(TestSurfaceCreate(2, 5, 0, unit, 0, 0, 0, 0, 0, PETSC_FALSE, &s2));
  PetscCall(TestSurfaceCreate(2, 5, 0, unit, -0.1, 0, 0, 0, 0, PETSC_TRUE, &m2));
  {
    const PetscReal g[3] = {0.1, 0, 0};
    PetscCall(TestMortarCase(sum, "matching2d", &s2, &m2, 1.0, PETSC_TRUE, PETSC_TRUE, g));
  }
  PetscCall(TestSurfaceCreate(2, 7, 0, unit, 0, 0, 0, 0, 0.3, PETSC_FALSE, &s2j));
  PetscCall(TestSurfaceCreate(2, 5, 0, wide, -0.1, -0.05, 0, 0, 0.3, PETSC_TRUE, &m2t));
  {
    const PetscReal g[3] = {0.1, 0.05, 0};
    PetscCall(TestMortarCase(sum, "nonmatching2d", &s2j, &m2t, 1.0, PETSC_TRUE, PETSC_FALSE, g));
  }
  PetscCall(TestSurfaceCreate(2, 3, 0, part, -0.1, 0, 0, 0, 0.2, PETSC_TRUE, &m2p));
  {
    const PetscReal g[3] = {0.1, 0, 0};
    PetscCall(TestMortarCase(sum, "partial2d", &s2j, &m2p, 1.0, PETSC_FALSE, PETSC_FALSE, g));
  }
  /* a second master surface far below (a closed body's inner face or another part) and one facing down: neither pairs */
  {
    TestSurface down;
    PetscCall(TestSurfaceCreate(2, 4, 0, far, -5, 0, 0, 0, 0, PETSC_TRUE, &m2far));
    PetscCall(TestSurfaceCreate(2, 4, 0, far, -0.05, 0, 0, 0, 0, PETSC_FALSE, &down));
    PetscCall(TestMortarCase(sum, "far2d", &s2j, &m2far, 1.0, PETSC_FALSE, PETSC_FALSE, (PetscReal[3]){0, 0, 0}));
    PetscCall(TestMortarCase(sum, "facing2d", &s2j, &down, 1.0, PETSC_FALSE, PETSC_FALSE, (PetscReal[3]){0, 0, 0}));
    PetscCall(TestSurfaceDestroy(&down));
  }
  /* 3D */
  PetscCall(TestSurfaceCreate(3, 3, 3, unit, 0, 0, 0, 0, 0, PETSC_FALSE, &s3));
  PetscCall(TestSurfaceCreate(3, 3, 3, unit, -0.1, 0, 0, 0, 0, PETSC_TRUE, &m3));
  {
    const PetscReal g[3] = {0.1, 0, 0};
    PetscCall(TestMortarCase(sum, "matching3d", &s3, &m3, 1.0, PETSC_TRUE, PETSC_TRUE, g));
  }
  PetscCall(TestSurfaceCreate(3, 4, 4, unit, 0, 0, 0, 0, 0.25, PETSC_FALSE, &s3j));
  PetscCall(TestSurfaceCreate(3, 3, 5, wide, -0.1, -0.02, -0.03, 0.3, 0.25, PETSC_TRUE, &m3t));
  {
    const PetscReal g[3] = {0.1, 0.02, 0.03};
    PetscCall(TestMortarCase(sum, "nonmatching3d", &s3j, &m3t, 1.0, PETSC_TRUE, PETSC_FALSE, g));
  }
  PetscCall(TestSurfaceCreate(3, 2, 3, part, -0.1, 0, 0, 0, 0.2, PETSC_TRUE, &m3p));
  {
    const PetscReal g[3] = {0.1, 0, 0};
    PetscCall(TestMortarCase(sum, "partial3d", &s3j, &m3p, 1.0, PETSC_FALSE, PETSC_FALSE, g));
  }
  PetscCall(TestSurfaceDestroy(&s2));
  PetscCall(TestSurfaceDestroy(&s2j));
  PetscCall(TestSurfaceDestroy(&m2));
  PetscCall(TestSurfaceDestroy(&m2t));
  PetscCall(TestSurfaceDestroy(&m2p));
  PetscCall(TestSurfaceDestroy(&m2far));
  PetscCall(TestSurfaceDestroy(&s3));
  PetscCall(TestSurfaceDestroy(&s3j));
  PetscCall(TestSurfaceDestroy(&m3));
  PetscCall(TestSurfaceDestroy(&m3t));
  PetscCall(TestSurfaceDestroy(&m3p));
  PetscFunctionReturn(0);
}

/* A contact pair on a mesh of two bodies (src/contact/pair.c): the problem comes from the options (its mesh, labels and
   Dirichlet data); -pair_slave_ids and -pair_master_ids name the two sides (values of -pair_label, "Face Sets"),
   -pair_dmax the pairing distance. The sides must be parallel planes at distance -pair_gap, the slave fully covered.
   Computed: the covered measure, the slave rows, and the errors of what the mortar operator must reproduce: no jump
   for a rigid translation, -g D_j n^T A n for the linear field A x, g0_j = g D_j, unit normals. */
static PetscErrorCode TestPair(SgSummary sum)
{
  SgProblem          prob;
  SgElasticity       el;
  SgContactPair      pair;
  SgBoundary         sl, ms;
  const SgMesh      *m;
  Mat                K;
  Vec                Y, T, BY, BT;
  PetscInt           ns = SG_MAX_IDS, nm = SG_MAX_IDS, nloc, dim;
  PetscReal          dmax = 0.2, gap = 0, A[9] = {0.3, -0.2, 0.1, 0.5, 0.7, -0.4, 0.2, 0.6, 0.9}, etr = 0, elin = 0, egap = 0, enrm = 0, Dsum = 0;
  const PetscScalar *by, *bt, *Da, *ga, *Na;
  PetscScalar       *ya, *ta;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&sl, sizeof(sl)));
  PetscCall(PetscMemzero(&ms, sizeof(ms)));
  PetscCall(PetscStrncpy(sl.label, "Face Sets", sizeof(sl.label)));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-pair_label", sl.label, sizeof(sl.label), NULL));
  PetscCall(PetscStrncpy(ms.label, sl.label, sizeof(ms.label)));
  PetscCall(PetscOptionsGetIntArray(NULL, NULL, "-pair_slave_ids", sl.ids, &ns, NULL));
  PetscCall(PetscOptionsGetIntArray(NULL, NULL, "-pair_master_ids", ms.ids, &nm, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-pair_dmax", &dmax, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-pair_gap", &gap, NULL));
  sl.nids = ns, ms.nids = nm, sl.active = ms.active = PETSC_TRUE, sl.what = "pair_slave", ms.what = "pair_master";
  PetscCall(SgProblemCreate(PETSC_COMM_WORLD, &prob));
  PetscCall(SgProblemSetFromOptions(prob));
  PetscCall(SgProblemSetUp(prob));
  PetscCall(SgProblemGetElasticity(prob, &el));
  PetscCall(SgElasticityGetMesh(el, &m));
  PetscCall(SgElasticityGetOperators(el, &K, NULL));
  dim = m->dim;
  PetscCall(SgContactPairCreate(el, &sl, &ms, dmax, PETSC_FALSE, PETSC_FALSE, NULL, &pair));
  /* Y = A x and T = a translation, in the free dofs */
  PetscCall(MatCreateVecs(K, &Y, NULL));
  PetscCall(VecDuplicate(Y, &T));
  PetscCall(VecGetArray(Y, &ya));
  PetscCall(VecGetArray(T, &ta));
  for (PetscInt v = 0; v < m->nv; v++) {
    if (m->goff[v] < 0) continue;
    for (PetscInt a = 0; a < dim; a++) {
      ya[m->goff[v] + a] = 0;
      for (PetscInt b = 0; b < dim; b++) ya[m->goff[v] + a] += A[3 * a + b] * m->x[v * dim + b];
      ta[m->goff[v] + a] = 0.1 * (a + 1);
    }
  }
  PetscCall(VecRestoreArray(Y, &ya));
  PetscCall(VecRestoreArray(T, &ta));
  PetscCall(MatCreateVecs(pair->B, NULL, &BY));
  PetscCall(VecDuplicate(BY, &BT));
  PetscCall(MatMult(pair->B, Y, BY));
  PetscCall(MatMult(pair->B, T, BT));
  PetscCall(VecGetLocalSize(BY, &nloc));
  PetscCall(VecGetArrayRead(BY, &by));
  PetscCall(VecGetArrayRead(BT, &bt));
  PetscCall(VecGetArrayRead(pair->D, &Da));
  PetscCall(VecGetArrayRead(pair->g0, &ga));
  PetscCall(VecGetArrayRead(pair->N, &Na));
  for (PetscInt j = 0; j < nloc; j++) {
    const PetscScalar *n   = Na + j * dim;
    PetscReal          nAn = 0, nn = 0;
    if (PetscRealPart(Da[j]) == 0) continue;
    for (PetscInt a = 0; a < dim; a++) {
      nn += PetscSqr(PetscRealPart(n[a]));
      for (PetscInt b = 0; b < dim; b++) nAn += PetscRealPart(n[a]) * A[3 * a + b] * PetscRealPart(n[b]);
    }
    Dsum += PetscRealPart(Da[j]);
    etr  = PetscMax(etr, PetscAbsScalar(bt[j]));
    elin = PetscMax(elin, PetscAbsReal(PetscRealPart(by[j]) + gap * PetscRealPart(Da[j]) * nAn));
    egap = PetscMax(egap, PetscAbsReal(PetscRealPart(ga[j]) - gap * PetscRealPart(Da[j])));
    enrm = PetscMax(enrm, PetscAbsReal(nn - 1));
  }
  PetscCall(VecRestoreArrayRead(BY, &by));
  PetscCall(VecRestoreArrayRead(BT, &bt));
  PetscCall(VecRestoreArrayRead(pair->D, &Da));
  PetscCall(VecRestoreArrayRead(pair->g0, &ga));
  PetscCall(VecRestoreArrayRead(pair->N, &Na));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &Dsum, 1, MPIU_REAL, MPI_SUM, PETSC_COMM_WORLD));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &etr, 1, MPIU_REAL, MPI_MAX, PETSC_COMM_WORLD));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &elin, 1, MPIU_REAL, MPI_MAX, PETSC_COMM_WORLD));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &egap, 1, MPIU_REAL, MPI_MAX, PETSC_COMM_WORLD));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &enrm, 1, MPIU_REAL, MPI_MAX, PETSC_COMM_WORLD));
  PetscCall(SgSummarySetReal(sum, "area", pair->area));
  PetscCall(SgSummarySetReal(sum, "D_sum", Dsum));
  PetscCall(SgSummarySetInt(sum, "slave_rows", pair->nslave));
  PetscCall(SgSummarySetInt(sum, "dropped_rows", pair->ndrop));
  PetscCall(SgSummarySetReal(sum, "D_dropped", pair->Ddrop));
  PetscCall(SgSummarySetReal(sum, "translation_error", etr));
  PetscCall(SgSummarySetReal(sum, "linear_error", elin));
  PetscCall(SgSummarySetReal(sum, "gap_error", egap));
  PetscCall(SgSummarySetReal(sum, "normal_error", enrm));
  PetscCall(VecDestroy(&Y));
  PetscCall(VecDestroy(&T));
  PetscCall(VecDestroy(&BY));
  PetscCall(VecDestroy(&BT));
  PetscCall(SgContactPairDestroy(&pair));
  PetscCall(SgProblemDestroy(&prob));
  PetscFunctionReturn(0);
}

/* Two bodies through the library (SG_BOUNDARY_CONTACT_MASTER): the 2D patch test of tests/opts/tb_stack2d.opts with its
   contact part and master side set by SgProblemSetBoundary (the mesh and the Dirichlet data from the options); the
   energy and force against the exact uniform compression */
static PetscErrorCode TestPairAPI(SgSummary s)
{
  SgProblem      prob;
  const PetscInt slave[1] = {20}, master[1] = {10};
  SgKKT          kkt;

  PetscFunctionBeginUser;
  PetscCall(SgProblemCreate(PETSC_COMM_WORLD, &prob));
  PetscCall(SgProblemSetBoundary(prob, SG_BOUNDARY_CONTACT, "Face Sets", 1, slave, NULL));
  PetscCall(SgProblemSetBoundary(prob, SG_BOUNDARY_CONTACT_MASTER, "Face Sets", 1, master, NULL));
  PetscCall(SolveRecord(prob, s, &kkt));
  PetscCall(SgSummarySetReal(s, "energy_exact", 0.5 * 0.04 * 0.04 / 0.91));
  PetscCall(SgSummarySetReal(s, "force", kkt.force));
  PetscCall(SgSummarySetReal(s, "force_exact", 0.04 / 0.91));
  PetscCall(SgProblemDestroy(&prob));
  PetscFunctionReturn(0);
}

/* Two bodies and a rigid obstacle through the library (SG_BOUNDARY_CONTACT_OBSTACLE, SgProblemSetObstacleType): the
   2D patch test with the lower block resting on a rigid plane (its point from the options); the exact energy, and the
   force carried by the pair and by the plane alike */
static PetscErrorCode TestPairObstacleAPI(SgSummary s)
{
  SgProblem      prob;
  const PetscInt slave[1] = {20}, master[1] = {10}, obst[1] = {1};
  SgKKT          kkt;

  PetscFunctionBeginUser;
  PetscCall(SgProblemCreate(PETSC_COMM_WORLD, &prob));
  PetscCall(SgProblemSetBoundary(prob, SG_BOUNDARY_CONTACT, "Face Sets", 1, slave, NULL));
  PetscCall(SgProblemSetBoundary(prob, SG_BOUNDARY_CONTACT_MASTER, "Face Sets", 1, master, NULL));
  PetscCall(SgProblemSetBoundary(prob, SG_BOUNDARY_CONTACT_OBSTACLE, "Face Sets", 1, obst, NULL));
  PetscCall(SgProblemSetObstacleType(prob, "plane"));
  PetscCall(SolveRecord(prob, s, &kkt));
  PetscCall(SgSummarySetReal(s, "energy_exact", 0.5 * 0.04 * 0.04 / 0.91));
  PetscCall(SgSummarySetReal(s, "force", kkt.force));
  PetscCall(SgSummarySetReal(s, "force_exact", 2 * 0.04 / 0.91));
  PetscCall(SgProblemDestroy(&prob));
  PetscFunctionReturn(0);
}

/* The law's properties (SgContactLawGetProperties) for every registered law, with what they are checked against,
   computed from the law itself: the slip reference and the solver's tangential state it sizes (a tangential part),
   and its bound at two normal multipliers and its derivative (a bound from lam_N). h7_linear, registered here, is a
   law that states its own properties through ops.getproperties (a tangential part that is linear on fixed sets). */
static void Bound_H7Linear(SgContactLaw law, PetscInt i, PetscReal lamN, PetscReal *g, PetscReal *dg)
{
  (void)law;
  (void)i;
  (void)lamN;
  *g = 0.25;
  if (dg) *dg = 0;
}

static PetscErrorCode GetProperties_H7Linear(SgContactLaw law, SgContactLawProperties *p)
{
  PetscFunctionBeginUser;
  (void)law;
  p->nonlinear = PETSC_FALSE;
  PetscFunctionReturn(0);
}

static PetscErrorCode LawCreate_H7Linear(SgContactLaw law)
{
  PetscFunctionBeginUser;
  law->friction          = PETSC_TRUE;
  law->coupled           = PETSC_FALSE;
  law->ops.bound         = Bound_H7Linear;
  law->ops.getproperties = GetProperties_H7Linear;
  PetscFunctionReturn(0);
}

static PetscErrorCode TestLawProperties(SgSummary s)
{
  SgContactLawProperties p;
  const PetscReal        x[2]  = {0.5, 0};
  PetscInt               nlaws = 0;
  const char            *name  = NULL;
  char                   key[64];

  PetscFunctionBeginUser;
  PetscCall(SgContactLawGetProperties(NULL, &p)); /* no law (no contact): the frictionless paths */
  PetscCall(SgSummarySetBool(s, "null_any", (PetscBool)(p.tangential || p.nonlinear || p.coupled || p.dissipative)));
  PetscCall(SgContactLawRegister("h7_linear", LawCreate_H7Linear));
  PetscCall(PetscOptionsSetValue(NULL, "-friction_bound", "0.2"));
  PetscCall(PetscOptionsSetValue(NULL, "-friction_coefficient", "0.3"));
  for (PetscInt k = 0;; k++) {
    SgContactLaw      law = NULL;
    SgContactLawState st;
    PetscReal         g1, g2, dg, *lamT;
    PetscInt          m;

    PetscCall(SgContactLawGetTypeName(k, &name));
    if (!name) break;
    PetscCall(PetscOptionsSetValue(NULL, "-friction_type", name));
    PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Law properties", NULL);
    PetscCall(SgContactLawCreateFromOptions(PetscOptionsObject, PETSC_COMM_WORLD, 2, &law));
    PetscOptionsEnd();
    PetscCall(SgContactLawSetVertices(law, 1, x));
    PetscCall(SgContactLawGetProperties(law, &p));
    PetscCall(SgContactLawGetSlipReferenceSize(law, &m));
    PetscCall(SgContactLawStateCreate(law, &st));
    PetscCall(SgContactLawStateGetArrays(st, NULL, &lamT, NULL));
    SgContactLawBound(law, 0, 1.0, &g1, &dg);
    SgContactLawBound(law, 0, 2.0, &g2, NULL);
#define H7KEY(what) (PetscSNPrintf(key, sizeof(key), "law%" PetscInt_FMT "_%s", k, what), key)
    PetscCall(SgSummarySetString(s, H7KEY("name"), name));
    PetscCall(SgSummarySetBool(s, H7KEY("tangential"), p.tangential));
    PetscCall(SgSummarySetBool(s, H7KEY("nonlinear"), p.nonlinear));
    PetscCall(SgSummarySetBool(s, H7KEY("coupled"), p.coupled));
    PetscCall(SgSummarySetBool(s, H7KEY("dissipative"), p.dissipative));
    PetscCall(SgSummarySetInt(s, H7KEY("slipref_size"), m));
    PetscCall(SgSummarySetBool(s, H7KEY("has_lamT"), (PetscBool)(lamT != NULL)));
    PetscCall(SgSummarySetReal(s, H7KEY("g1"), g1));
    PetscCall(SgSummarySetReal(s, H7KEY("g2"), g2));
    PetscCall(SgSummarySetReal(s, H7KEY("dg"), dg));
#undef H7KEY
    PetscCall(SgContactLawStateDestroy(&st));
    PetscCall(SgContactLawDestroy(&law));
    nlaws++;
  }
  PetscCall(SgSummarySetInt(s, "nlaws", nlaws));
  PetscCall(PetscOptionsClearValue(NULL, "-friction_type"));
  PetscCall(PetscOptionsClearValue(NULL, "-friction_bound"));
  PetscCall(PetscOptionsClearValue(NULL, "-friction_coefficient"));
  PetscFunctionReturn(0);
}

/* The law's part of PDAS (src/contact/law_pdas.c) for every built-in law on two contact vertices in 3D (normal on dof
   2, weights 0.5 and 1, c = 4), with K = I and b = 0, so that R = y: lam_N = -y_2 / w, z = -y_T / w + c y_T. Vertex 0
   (y = (0.01, 0.02, -1): lam_N = 2, |z| = 0.02 sqrt 5) sticks under Tresca s = 0.2 and Coulomb F = 0.3; vertex 1
   (y = (0.3, -0.4, -0.5): lam_N = 0.5, z = (0.9, -1.2)) slips. Recorded: the rows (kinds, values, springs) for the ini
   to compare with the formulas, and the changes counted by the updates after the start. */
static PetscErrorCode TestLawPdas(SgSummary s)
{
  const PetscInt  off[2] = {0, 3}, axis[2] = {2, 2};
  const PetscReal w[2] = {0.5, 1}, nax[2] = {1, 1}, yref[6] = {0, 0, 0, 0, 0, 0}, x[6] = {0, 0, 0, 1, 0, 0};
  const PetscReal yv[6]    = {0.01, 0.02, -1, 0.3, -0.4, -0.5};
  const char      act[2]   = {1, 1};
  const char     *names[3] = {SGLAWNONE, SGLAWTRESCA, SGLAWCOULOMB};
  char            key[64];
  Mat             K;
  Vec             b, y;

  PetscFunctionBeginUser;
  PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, 6, 6, 1, NULL, &K));
  for (PetscInt i = 0; i < 6; i++) PetscCall(MatSetValue(K, i, i, 1.0, INSERT_VALUES));
  PetscCall(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateVecs(K, &y, &b));
  PetscCall(VecZeroEntries(b));
  for (PetscInt i = 0; i < 6; i++) PetscCall(VecSetValue(y, i, yv[i], INSERT_VALUES));
  PetscCall(VecAssemblyBegin(y));
  PetscCall(VecAssemblyEnd(y));
  PetscCall(PetscOptionsSetValue(NULL, "-friction_bound", "0.2"));
  PetscCall(PetscOptionsSetValue(NULL, "-friction_coefficient", "0.3"));
  for (PetscInt k = 0; k < 3; k++) {
    SgContactLaw                law = NULL;
    SgContactLawPdas            lp;
    SgContactLawPdasSetup       su = {2, 3, off, axis, w, nax, yref, 4.0, PETSC_TRUE};
    const SgContactLawPdasRows *rows;
    const PetscReal            *blk;
    PetscInt                    n, nspring, ncoupled, ch[2], kinds[6] = {0, 0, 0, 0, 0, 0}, spring[2] = {0, 0};
    PetscReal                   v[6] = {0, 0, 0, 0, 0, 0}, B[18];
    PetscBool                   states, roundoff;

    PetscCall(PetscOptionsSetValue(NULL, "-friction_type", names[k]));
    PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Law PDAS", NULL);
    PetscCall(SgContactLawCreateFromOptions(PetscOptionsObject, PETSC_COMM_WORLD, 3, &law));
    PetscOptionsEnd();
    PetscCall(SgContactLawSetVertices(law, 2, x));
    PetscCall(SgContactLawPdasCreate(law, PETSC_COMM_SELF, &su, &lp));
    PetscCall(SgContactLawPdasGetInfo(lp, &states, &roundoff));
    PetscCall(SgContactLawPdasUpdate(lp, K, b, y, PETSC_TRUE, act, NULL)); /* the start */
    PetscCall(SgContactLawPdasUpdate(lp, K, b, y, PETSC_TRUE, act, &ch[0]));
    PetscCall(SgContactLawPdasUpdate(lp, K, b, y, PETSC_TRUE, act, &ch[1]));
    PetscCall(SgContactLawPdasGetRows(lp, &n, &rows, &blk, &nspring, &ncoupled));
    for (PetscInt i = 0; i < n; i++) {
      spring[i] = rows[i].spring;
      for (PetscInt j = 0; j < 3; j++) {
        kinds[3 * i + j] = rows[i].kind[j];
        v[3 * i + j]     = rows[i].v[j];
      }
    }
    for (PetscInt q = 0; q < 18; q++) B[q] = n ? blk[q] : 0;
#define LPKEY(what) (PetscSNPrintf(key, sizeof(key), "%s_%s", names[k], what), key)
    PetscCall(SgSummarySetBool(s, LPKEY("states"), states));
    PetscCall(SgSummarySetBool(s, LPKEY("roundoff"), roundoff));
    PetscCall(SgSummarySetInt(s, LPKEY("nrows"), n));
    PetscCall(SgSummarySetInt(s, LPKEY("nspring"), nspring));
    PetscCall(SgSummarySetInt(s, LPKEY("ncoupled"), ncoupled));
    PetscCall(SgSummarySetIntArray(s, LPKEY("changed"), 2, ch));
    PetscCall(SgSummarySetIntArray(s, LPKEY("kind"), 6, kinds));
    PetscCall(SgSummarySetIntArray(s, LPKEY("spring"), 2, spring));
    PetscCall(SgSummarySetRealArray(s, LPKEY("v"), 6, v));
    PetscCall(SgSummarySetRealArray(s, LPKEY("blk"), 18, B));
#undef LPKEY
    PetscCall(SgContactLawPdasDestroy(&lp));
    PetscCall(SgContactLawDestroy(&law));
  }
  PetscCall(PetscOptionsClearValue(NULL, "-friction_type"));
  PetscCall(PetscOptionsClearValue(NULL, "-friction_bound"));
  PetscCall(PetscOptionsClearValue(NULL, "-friction_coefficient"));
  PetscCall(VecDestroy(&y));
  PetscCall(VecDestroy(&b));
  PetscCall(MatDestroy(&K));
  PetscFunctionReturn(0);
}

/* core/matrix.c: SgMatAddSparse (A + C, the union of their patterns, one pass over A's arrays) against MatAXPY with
   DIFFERENT_NONZERO_PATTERN, and SgMatOffIdentity (A - I without its zeros) against its definition, on a banded A of
   60 rows per rank with a C on a few rows whose columns reach other ranks (on several ranks the off-diagonal parts) and
   a near-identity I + E (E on a few rows, stored zeros on the others' diagonal blocks). Keys: the largest absolute
   difference of the values, the nonzero counts of both results. */
/* SgMeshPartitionWeights (src/fem/mesh.c, -contact_pair_partition's group weights): small weights kept as their rounded
   integers (the partitions of the runs so far unchanged); weights of a mesh refined 11 times (a tetrahedron's share
   120 (2^11)^3 / 6 = 1.7e11 sixtieths of vertices, a contact cell's 120 * 12 * (2^11)^2 / 2 more, 5,000 groups: sum
   8.6e14) scaled into PetscInt with their proportions kept, each at least 1, the sum below PETSC_MAX_INT */
static PetscErrorCode TestPartitionWeights(SgSummary s)
{
  const PetscInt n = 5000;
  PetscReal     *w, k = 2048, tw = 0, ti = 0, err = 0;
  PetscInt      *iw, exact = 1, minw = PETSC_MAX_INT;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(n, &w, n, &iw));
  for (PetscInt i = 0; i < n; i++) w[i] = 1 + (i % 977) + 0.3;
  PetscCall(SgMeshPartitionWeights(n, w, iw));
  for (PetscInt i = 0; i < n; i++) exact = exact && iw[i] == (PetscInt)(w[i] + 0.5);
  for (PetscInt i = 0; i < n; i++) w[i] = 120 * (k - 1) * (k - 2) * (k - 3) / 6 * (1 + 0.5 * (i % 7)) + (i % 10 == 0 ? 120 * 12 * k * k / 2 : 0);
  w[n - 1] = 0; /* a weight 0 becomes 1 */
  PetscCall(SgMeshPartitionWeights(n, w, iw));
  for (PetscInt i = 0; i < n; i++) tw += w[i], ti += iw[i], minw = PetscMin(minw, iw[i]);
  for (PetscInt i = 0; i < n - 1; i++) err = PetscMax(err, PetscAbsReal(iw[i] / ti - w[i] / tw) / (w[i] / tw));
  PetscCall(SgSummarySetBool(s, "small_exact", (PetscBool)exact));
  PetscCall(SgSummarySetReal(s, "large_weight_sum", tw));
  PetscCall(SgSummarySetReal(s, "scaled_sum", ti));
  PetscCall(SgSummarySetReal(s, "max_int", (PetscReal)PETSC_MAX_INT));
  PetscCall(SgSummarySetInt(s, "scaled_min", minw));
  PetscCall(SgSummarySetReal(s, "scaled_max_share_error", err));
  PetscCall(PetscFree2(w, iw));
  PetscFunctionReturn(0);
}

static PetscErrorCode TestMatAddSparse(SgSummary s)
{
  PetscMPIInt rank, size;
  PetscInt    m = 60, rs, re, N;
  Mat         A, C, S, R, G, W, X;
  PetscReal   d1, d2;
  MatInfo     is, ir, iw;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, m, m, PETSC_DETERMINE, PETSC_DETERMINE, 7, NULL, 7, NULL, &A));
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, m, m, PETSC_DETERMINE, PETSC_DETERMINE, 6, NULL, 6, NULL, &C));
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, m, m, PETSC_DETERMINE, PETSC_DETERMINE, 6, NULL, 6, NULL, &G));
  PetscCall(MatGetOwnershipRange(A, &rs, &re));
  PetscCall(MatGetSize(A, &N, NULL));
  for (PetscInt r = rs; r < re; r++) {
    for (PetscInt k = -3; k <= 3; k++) {
      PetscInt    c = r + k;
      PetscScalar v = 1.0 / (1 + r + 2 * PetscAbsInt(k)) + (k == 0 ? 4 : 0);
      if (c >= 0 && c < N) PetscCall(MatSetValues(A, 1, &r, 1, &c, &v, INSERT_VALUES));
    }
    for (PetscInt b = 0; b < 3; b++) { /* G: 3 x 3 diagonal blocks of the identity, stored whole */
      PetscInt    c = r - r % 3 + b;
      PetscScalar v = c == r;
      PetscCall(MatSetValues(G, 1, &r, 1, &c, &v, ADD_VALUES));
    }
    if (r % 7 == 2) { /* C and E on every 7th row: the band (a shared entry), far columns (new ones, other ranks') */
      PetscInt    cols[4] = {r, (r + 17) % N, (r + m + 5) % N, (r + N / 2) % N};
      PetscScalar v[4]    = {0.5, -1.25, 2.0, 0.125};
      for (PetscInt k = 0; k < 4; k++) PetscCall(MatSetValues(C, 1, &r, 1, &cols[k], &v[k], ADD_VALUES));
      for (PetscInt k = 1; k < 4; k++)
        if (cols[k] / 3 != r / 3) PetscCall(MatSetValues(G, 1, &r, 1, &cols[k], &v[k], ADD_VALUES));
    }
  }
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyBegin(C, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(C, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyBegin(G, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(G, MAT_FINAL_ASSEMBLY));
  PetscCall(SgMatAddSparse(A, C, &S));
  PetscCall(MatDuplicate(A, MAT_COPY_VALUES, &R));
  PetscCall(MatAXPY(R, 1.0, C, DIFFERENT_NONZERO_PATTERN));
  PetscCall(MatGetInfo(S, MAT_GLOBAL_SUM, &is));
  PetscCall(MatGetInfo(R, MAT_GLOBAL_SUM, &ir));
  PetscCall(MatDuplicate(R, MAT_COPY_VALUES, &X));
  PetscCall(MatAXPY(X, -1.0, S, DIFFERENT_NONZERO_PATTERN));
  PetscCall(MatNorm(X, NORM_MAX, &d1));
  PetscCall(MatDestroy(&X));
  PetscCall(SgSummarySetReal(s, "add_max_difference", d1));
  PetscCall(SgSummarySetReal(s, "add_nonzeros", is.nz_used));
  PetscCall(SgSummarySetReal(s, "axpy_nonzeros", ir.nz_used));
  {
    PetscReal na;
    PetscCall(MatNorm(A, NORM_FROBENIUS, &na));
    PetscCall(SgSummarySetReal(s, "a_norm", na));
  }
  PetscCall(SgMatOffIdentity(G, &W));
  PetscCall(MatGetInfo(W, MAT_GLOBAL_SUM, &iw));
  PetscCall(MatDuplicate(G, MAT_COPY_VALUES, &X)); /* G - I - W */
  PetscCall(MatShift(X, -1.0));
  PetscCall(MatAXPY(X, -1.0, W, DIFFERENT_NONZERO_PATTERN));
  PetscCall(MatNorm(X, NORM_MAX, &d2));
  PetscCall(MatDestroy(&X));
  PetscCall(SgSummarySetReal(s, "offidentity_max_difference", d2));
  PetscCall(SgSummarySetReal(s, "offidentity_nonzeros", iw.nz_used));
  {
    PetscInt rows = 0, all;
    for (PetscInt r = rs; r < re; r++) rows += r % 7 == 2;
    PetscCallMPI(MPI_Allreduce(&rows, &all, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
    PetscCall(SgSummarySetInt(s, "correction_rows", all));
  }
  PetscCall(MatDestroy(&W));
  PetscCall(MatDestroy(&R));
  PetscCall(MatDestroy(&S));
  PetscCall(MatDestroy(&G));
  PetscCall(MatDestroy(&C));
  PetscCall(MatDestroy(&A));
  PetscFunctionReturn(0);
}

/* The deflation of the truncated multigrid (src/solver/deflate.c) around a Jacobi preconditioner on the 1D Laplacian
   (n = 300, distributed; condition about 160): CG records its preconditioned residuals; at the next solve the Lanczos matrix rebuilt from
   CG's step lengths must have PETSc's smallest Ritz value (KSPComputeEigenvalues of the same solve), the Ritz vectors
   below 0.03 form the space (8 of them), the balanced form must be exact on it (M_d J z = z), symmetric, and the deflated solve
   must take fewer iterations to the same solution. */
typedef struct {
  SgDefl d;
  KSP    ksp;
  Mat    A;
  PC     jac;
} DeflCtx;

static PetscErrorCode ApplyDeflTest(PC pc, Vec x, Vec y)
{
  DeflCtx *c;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &c));
  PetscCall(SgDeflApply(c->d, c->ksp, c->A, c->jac, x, y));
  PetscFunctionReturn(0);
}

static PetscErrorCode TestDeflate(SgSummary s)
{
  const PetscInt n = 300;
  PetscInt       lo, hi, its[2], neig, k, nritz;
  Mat            A;
  Vec            b, x0, x1, u, v, w;
  KSP            ksp;
  PC             pc;
  DeflCtx        c;
  PetscReal     *er, *ei, emin, ritz0, exact = 0, nrm, dif;
  PetscScalar    s1, s2;
  const Vec     *Z;
  PetscRandom    r;

  PetscFunctionBeginUser;
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, n, n, 3, NULL, 2, NULL, &A));
  PetscCall(MatGetOwnershipRange(A, &lo, &hi));
  for (PetscInt i = lo; i < hi; i++) {
    const PetscScalar di = 2.05 + 0.05 * PetscSinReal((PetscReal)i); /* > 2, varying: Jacobi is not trivial */
    PetscCall(MatSetValue(A, i, i, di, INSERT_VALUES));
    if (i > 0) PetscCall(MatSetValue(A, i, i - 1, -1.0, INSERT_VALUES));
    if (i < n - 1) PetscCall(MatSetValue(A, i, i + 1, -1.0, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateVecs(A, &x0, &b));
  PetscCall(VecDuplicate(b, &x1));
  PetscCall(VecDuplicate(b, &u));
  PetscCall(VecDuplicate(b, &v));
  PetscCall(VecDuplicate(b, &w));
  PetscCall(PetscRandomCreate(PETSC_COMM_WORLD, &r));
  PetscCall(PetscRandomSetInterval(r, -1.0, 1.0));
  PetscCall(VecSetRandom(b, r));
  PetscCall(SgDeflCreate(8, 300, 0.03, &c.d)); /* every step kept: the same Lanczos matrix as PETSc's */
  c.A = A;
  PetscCall(PCCreate(PETSC_COMM_WORLD, &c.jac));
  PetscCall(PCSetType(c.jac, PCJACOBI));
  PetscCall(PCSetOperators(c.jac, A, A));
  PetscCall(PCSetUp(c.jac));
  PetscCall(KSPCreate(PETSC_COMM_WORLD, &ksp));
  c.ksp = ksp;
  PetscCall(KSPSetType(ksp, KSPCG));
  PetscCall(KSPSetOperators(ksp, A, A));
  PetscCall(KSPSetTolerances(ksp, 1e-10, 1e-50, PETSC_DEFAULT, 200));
  PetscCall(KSPSetComputeEigenvalues(ksp, PETSC_TRUE));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCSHELL));
  PetscCall(PCShellSetContext(pc, &c));
  PetscCall(PCShellSetApply(pc, ApplyDeflTest));
  PetscCall(KSPSolve(ksp, b, x0));
  PetscCall(KSPGetIterationNumber(ksp, &its[0]));
  PetscCall(PetscMalloc2(its[0], &er, its[0], &ei));
  PetscCall(KSPComputeEigenvalues(ksp, its[0], er, ei, &neig));
  emin = er[0];
  for (PetscInt i = 1; i < neig; i++) emin = PetscMin(emin, er[i]);
  PetscCall(PetscFree2(er, ei));
  PetscCall(KSPSolve(ksp, b, x1)); /* the first application takes the previous solve's Ritz vectors */
  PetscCall(KSPGetIterationNumber(ksp, &its[1]));
  PetscCall(SgDeflGetSpace(c.d, &k, &Z, &nritz, &ritz0));
  /* after the second solve the recording holds its own Lanczos matrix; ritz0 is the first solve's */
  for (PetscInt i = 0; i < k; i++) { /* M_d J z = z on the space */
    PetscCall(MatMult(A, Z[i], u));
    PetscCall(SgDeflApply(c.d, NULL, A, c.jac, u, v));
    PetscCall(VecAXPY(v, -1.0, Z[i]));
    PetscCall(VecNorm(v, NORM_2, &dif));
    PetscCall(VecNorm(Z[i], NORM_2, &nrm));
    exact = PetscMax(exact, dif / nrm);
  }
  PetscCall(VecSetRandom(u, r)); /* symmetry: u^T M_d v = v^T M_d u */
  PetscCall(VecSetRandom(v, r));
  PetscCall(SgDeflApply(c.d, NULL, A, c.jac, v, w));
  PetscCall(VecDot(u, w, &s1));
  PetscCall(SgDeflApply(c.d, NULL, A, c.jac, u, w));
  PetscCall(VecDot(v, w, &s2));
  PetscCall(VecAXPY(x1, -1.0, x0));
  PetscCall(VecNorm(x1, NORM_2, &dif));
  PetscCall(VecNorm(x0, NORM_2, &nrm));
  PetscCall(SgSummarySetInt(s, "cg_plain", its[0]));
  PetscCall(SgSummarySetInt(s, "cg_deflated", its[1]));
  PetscCall(SgSummarySetInt(s, "space", k));
  PetscCall(SgSummarySetInt(s, "ritz_taken", nritz));
  PetscCall(SgSummarySetReal(s, "ritz_min_petsc", emin));
  PetscCall(SgSummarySetReal(s, "ritz_min_rel_diff", PetscAbsReal(ritz0 - emin) / emin));
  PetscCall(SgSummarySetReal(s, "exact_on_space", exact));
  PetscCall(SgSummarySetReal(s, "symmetry_rel", PetscAbsScalar(s1 - s2) / PetscMax(PetscAbsScalar(s1), PetscAbsScalar(s2))));
  PetscCall(SgSummarySetReal(s, "solution_rel_diff", dif / nrm));
  PetscCall(PetscRandomDestroy(&r));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(PCDestroy(&c.jac));
  PetscCall(SgDeflDestroy(&c.d));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&x0));
  PetscCall(VecDestroy(&x1));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&v));
  PetscCall(VecDestroy(&w));
  PetscCall(MatDestroy(&A));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  char      test[64] = "", file[PETSC_MAX_PATH_LEN] = "";
  SgSummary s;
  PetscBool eq;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(SgInitializePackage());
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Unit tests", NULL);
  PetscCall(PetscOptionsString("-test", "Test to run", NULL, test, test, sizeof(test), NULL));
  PetscCall(PetscOptionsString("-summary_file", "JSON file for the computed values", NULL, file, file, sizeof(file), NULL));
  PetscOptionsEnd();
  PetscCall(SgSummaryCreate(&s));
  PetscCall(SgSummarySetString(s, "test", test));
  if (PetscStrcmp(test, "element2d", &eq) == 0 && eq) PetscCall(TestElement2D(s));
  else if (PetscStrcmp(test, "element3d", &eq) == 0 && eq) PetscCall(TestElement3D(s));
  else if (PetscStrcmp(test, "rigid", &eq) == 0 && eq) PetscCall(TestRigid(s));
  else if (PetscStrcmp(test, "stiffness", &eq) == 0 && eq) PetscCall(TestStiffness(s));
  else if (PetscStrcmp(test, "l1gs", &eq) == 0 && eq) PetscCall(TestL1GS(s));
  else if (PetscStrcmp(test, "deflate", &eq) == 0 && eq) PetscCall(TestDeflate(s));
  else if (PetscStrcmp(test, "gap", &eq) == 0 && eq) PetscCall(TestGap(s));
  else if (PetscStrcmp(test, "modelfit", &eq) == 0 && eq) PetscCall(TestModelFit(s));
  else if (PetscStrcmp(test, "rollerapi", &eq) == 0 && eq) PetscCall(TestRollerAPI(s));
  else if (PetscStrcmp(test, "controllers", &eq) == 0 && eq) PetscCall(TestControllers(s));
  else if (PetscStrcmp(test, "resolve", &eq) == 0 && eq) PetscCall(TestResolve(s));
  else if (PetscStrcmp(test, "loadpath", &eq) == 0 && eq) PetscCall(TestLoadPath(s));
  else if (PetscStrcmp(test, "meshtree", &eq) == 0 && eq) PetscCall(TestMeshTree(s));
  else if (PetscStrcmp(test, "mortar", &eq) == 0 && eq) PetscCall(TestMortar(s));
  else if (PetscStrcmp(test, "pair", &eq) == 0 && eq) PetscCall(TestPair(s));
  else if (PetscStrcmp(test, "pairapi", &eq) == 0 && eq) PetscCall(TestPairAPI(s));
  else if (PetscStrcmp(test, "pairobstacleapi", &eq) == 0 && eq) PetscCall(TestPairObstacleAPI(s));
  else if (PetscStrcmp(test, "lawproperties", &eq) == 0 && eq) PetscCall(TestLawProperties(s));
  else if (PetscStrcmp(test, "lawpdas", &eq) == 0 && eq) PetscCall(TestLawPdas(s));
  else if (PetscStrcmp(test, "mataddsparse", &eq) == 0 && eq) PetscCall(TestMatAddSparse(s));
  else if (PetscStrcmp(test, "partitionweights", &eq) == 0 && eq) PetscCall(TestPartitionWeights(s));
  else SETERRQ(PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "-test: unknown unit test '%s'", test);
  PetscCall(SgSummaryWrite(PETSC_COMM_WORLD, s, "-summary_file", file));
  PetscCall(SgSummaryDestroy(&s));
  PetscCall(PetscFinalize());
  return 0;
}
