/* frame.c: a frame (n, t1, t2) per contact vertex, so that the linear solves see every contact normal as a coordinate
   axis (-ssn_frame).
   At a vertex whose normal n is not +-e_k the contact block gamma w n n^T couples its components with a gamma of
   1e8-1e18: an unknown-based AMG cannot smooth that, the truncated multigrid cannot truncate it and condensation must
   keep every component. In the vertex's own orthonormal frame Q_i = [n, t1, t2] the block is gamma w e_0 e_0^T, a
   diagonal entry. The linear systems J dy = F of the SSN are therefore solved as (Q^T J Q) z = Q^T F, dy = Q z, with
   Q block diagonal (Q_i at the rotated vertices, the identity elsewhere):
   - the rotated stiffness Q^T K Q is formed once (it does not change), with the rotated rigid-body modes as its near
     null space;
   - the SSN's Jacobians are assembled directly in the frames (the contact blocks on the normal dof: no round-off of
     gamma leaks into the tangential entries);
   - the KSP (Krylov method and the configured preconditioner: AMG, truncated multigrid, factorization, condensation)
     works on these matrices; its right-hand side is turned into the frames before the solve and its solution back
     after it (KSPSetPreSolve/PostSolve), so the SNES around it never sees the frames.
   Residuals, iterates, controllers and outputs stay in the original coordinates. At a roller (a fixed component e_f,
   the normal orthogonal to it) the frame keeps e_f in its place, so the Dirichlet rows stay rows of the identity;
   vertices whose normal is already +-e_k keep the identity. */
#include "solver/ssnimpl.h"

struct _n_SgFrame {
  MPI_Comm        comm;
  PetscInt        dim, n, nrot; /* contact vertices here; of those rotated (on all ranks: nrot_global) */
  PetscInt        nrot_global;
  const PetscInt *off;  /* dof offset of each contact vertex (the contact view's) */
  PetscReal      *Q;    /* Q_i row-major: column b is the frame's b-th vector in global components */
  PetscBool      *rot;  /* Q_i is not the identity */
  PetscInt       *axis; /* the frame dof of the normal */
  PetscReal      *sign; /* n = sign Q_i e_axis */
  Mat             Kr;   /* Q^T K Q */
  MatNullSpace    nsp;  /* the rotated near null space (NULL if the problem has none) */
  Vec             b;    /* a solve's right-hand side, kept to give it back (PreSolve_Frame) */
};

static PetscLogEvent SG_FrameSetUp;
static PetscBool     frame_registered = PETSC_FALSE;

/* The frame of a contact vertex with unit normal n: the rotation closest to the identity that turns e_k, k the
   component of n largest in size, into s n (s = sign n_k): Q = I + [u]x + [u]x^2 / (1 + c), u = e_k x s n, c = s n_k.
   Its columns stay near the coordinate axes they replace, so that the rotated dofs remain what an unknown-based AMG
   takes them for (the normal of a face turned from -e_z by 30 degrees is still dof z of its vertex), and a fixed
   component e_f of a roller (n orthogonal to it, so u along e_f) keeps its place. n = s Q e_k. */
static void VertexFrame(PetscInt dim, const PetscReal n[], PetscReal Q[], PetscInt *axis, PetscReal *sign)
{
  PetscInt  k    = 0;
  PetscReal v[3] = {0, 0, 0}, u[3], c, Ux[3][3], U2[3][3], e[3] = {0, 0, 0};

  for (PetscInt a = 1; a < dim; a++)
    if (PetscAbsReal(n[a]) > PetscAbsReal(n[k])) k = a;
  *sign = n[k] > 0 ? 1 : -1;
  *axis = k;
  for (PetscInt a = 0; a < dim; a++) v[a] = *sign * n[a];
  e[k]     = 1;
  u[0]     = e[1] * v[2] - e[2] * v[1];
  u[1]     = e[2] * v[0] - e[0] * v[2];
  u[2]     = e[0] * v[1] - e[1] * v[0];
  c        = v[k];
  Ux[0][0] = 0, Ux[0][1] = -u[2], Ux[0][2] = u[1];
  Ux[1][0] = u[2], Ux[1][1] = 0, Ux[1][2] = -u[0];
  Ux[2][0] = -u[1], Ux[2][1] = u[0], Ux[2][2] = 0;
  for (PetscInt a = 0; a < 3; a++)
    for (PetscInt b = 0; b < 3; b++) {
      U2[a][b] = 0;
      for (PetscInt m = 0; m < 3; m++) U2[a][b] += Ux[a][m] * Ux[m][b];
    }
  for (PetscInt a = 0; a < dim; a++)
    for (PetscInt b = 0; b < dim; b++) Q[a * dim + b] = (a == b) + Ux[a][b] + U2[a][b] / (1 + c);
  for (PetscInt a = 0; a < dim; a++) Q[a * dim + k] = v[a]; /* the normal's column exactly */
}

/* x_i <- Q_i^T x_i (to the frame) or Q_i x_i (back) at the rotated vertices of a local array */
static void RotateArray(SgFrame f, PetscScalar xa[], PetscBool back)
{
  const PetscInt dim = f->dim;
  for (PetscInt i = 0; i < f->n; i++) {
    const PetscReal *Q = &f->Q[i * dim * dim];
    PetscReal        x[3], r[3];
    if (!f->rot[i]) continue;
    for (PetscInt a = 0; a < dim; a++) x[a] = PetscRealPart(xa[f->off[i] + a]);
    for (PetscInt a = 0; a < dim; a++) {
      r[a] = 0;
      for (PetscInt b = 0; b < dim; b++) r[a] += back ? Q[a * dim + b] * x[b] : Q[b * dim + a] * x[b];
    }
    for (PetscInt a = 0; a < dim; a++) xa[f->off[i] + a] = r[a];
  }
}

PetscErrorCode SgFrameToLocal(SgFrame f, Vec x)
{
  PetscScalar *xa;

  PetscFunctionBeginUser;
  PetscCall(VecGetArray(x, &xa));
  RotateArray(f, xa, PETSC_FALSE);
  PetscCall(VecRestoreArray(x, &xa));
  PetscFunctionReturn(0);
}

PetscErrorCode SgFrameToGlobal(SgFrame f, Vec x)
{
  PetscScalar *xa;

  PetscFunctionBeginUser;
  PetscCall(VecGetArray(x, &xa));
  RotateArray(f, xa, PETSC_TRUE);
  PetscCall(VecRestoreArray(x, &xa));
  PetscFunctionReturn(0);
}

/* v (dim components of contact vertex i, global) in the vertex's frame */
void SgFrameVectorToLocal(SgFrame f, PetscInt i, const PetscReal v[], PetscReal r[])
{
  const PetscInt   dim = f->dim;
  const PetscReal *Q   = &f->Q[i * dim * dim];
  for (PetscInt a = 0; a < dim; a++) {
    r[a] = 0;
    for (PetscInt b = 0; b < dim; b++) r[a] += Q[b * dim + a] * v[b];
  }
}

/* Q as a matrix (block diagonal, dim x dim blocks) for the product Q^T K Q */
static PetscErrorCode FrameMatrix(SgFrame f, Mat K, Mat *Qm)
{
  PetscInt  rstart, rend, m, bs = f->dim;
  PetscInt *rowv;

  PetscFunctionBeginUser;
  PetscCall(MatGetOwnershipRange(K, &rstart, &rend));
  m = rend - rstart;
  PetscCall(MatCreateAIJ(f->comm, m, m, PETSC_DETERMINE, PETSC_DETERMINE, bs, NULL, 0, NULL, Qm));
  PetscCall(MatSetBlockSize(*Qm, bs));
  PetscCall(MatSetOption(*Qm, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PetscCall(PetscCalloc1(m, &rowv));
  for (PetscInt i = 0; i < f->n; i++) rowv[f->off[i]] = i + 1; /* which contact vertex starts at this local dof */
  for (PetscInt r = 0; r < m; r += bs) {
    PetscInt    idx[3];
    PetscScalar v[9];
    for (PetscInt a = 0; a < bs; a++) idx[a] = rstart + r + a;
    for (PetscInt a = 0; a < bs; a++)
      for (PetscInt b = 0; b < bs; b++) v[a * bs + b] = (a == b);
    if (rowv[r] && f->rot[rowv[r] - 1])
      for (PetscInt k = 0; k < bs * bs; k++) v[k] = f->Q[(rowv[r] - 1) * bs * bs + k];
    PetscCall(MatSetValues(*Qm, bs, idx, bs, idx, v, INSERT_VALUES));
  }
  PetscCall(PetscFree(rowv));
  PetscCall(MatAssemblyBegin(*Qm, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*Qm, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* The frames of the contact vertices, or NULL where every normal (on every rank) is a coordinate axis already. */
PetscErrorCode SgFrameCreate(SgElasticity el, SgContact c, SgFrame *frame)
{
  SgFrame       f;
  SgContactView cv;
  const SgMesh *m;
  Mat           K, Qm;
  MatNullSpace  nsp;
  PetscInt      dim;
  PetscBool     aligned;

  PetscFunctionBeginUser;
  *frame = NULL;
  if (!c) PetscFunctionReturn(0);
  PetscCall(SgContactNormalsAxisAligned(c, &aligned));
  if (aligned) PetscFunctionReturn(0);
  if (!frame_registered) {
    PetscCall(PetscLogEventRegister("SgFrameSetUp", MAT_CLASSID, &SG_FrameSetUp));
    frame_registered = PETSC_TRUE;
  }
  PetscCall(PetscLogEventBegin(SG_FrameSetUp, 0, 0, 0, 0));
  PetscCall(SgContactGetView(c, &cv));
  PetscCall(SgElasticityGetDimension(el, &dim));
  PetscCall(SgElasticityGetMesh(el, &m));
  PetscCall(PetscNew(&f));
  PetscCall(SgElasticityGetComm(el, &f->comm));
  f->dim = dim;
  f->n   = cv.n;
  f->off = cv.off;
  PetscCall(PetscMalloc4(cv.n * dim * dim, &f->Q, cv.n, &f->rot, cv.n, &f->axis, cv.n, &f->sign));
  for (PetscInt i = 0; i < cv.n; i++) {
    const PetscReal *n = &cv.normal[i * dim];
    PetscInt         k = -1;
    for (PetscInt a = 0; a < dim; a++)
      if (PetscAbsReal(PetscAbsReal(n[a]) - 1) < 1e-10) k = a;
    if (k >= 0) { /* already an axis: the identity, the normal on dof k */
      for (PetscInt a = 0; a < dim * dim; a++) f->Q[i * dim * dim + a] = (a % (dim + 1) == 0);
      f->rot[i]  = PETSC_FALSE;
      f->axis[i] = k;
      f->sign[i] = n[k] > 0 ? 1 : -1;
      continue;
    }
    VertexFrame(dim, n, &f->Q[i * dim * dim], &f->axis[i], &f->sign[i]);
    f->rot[i] = PETSC_TRUE;
    f->nrot++;
  }
  PetscCallMPI(MPI_Allreduce(&f->nrot, &f->nrot_global, 1, MPIU_INT, MPI_SUM, f->comm));
  PetscCall(SgElasticityGetOperators(el, &K, NULL));
  PetscCall(FrameMatrix(f, K, &Qm));
  PetscCall(MatPtAP(K, Qm, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &f->Kr));
  PetscCall(MatSetBlockSize(f->Kr, dim));
  PetscCall(MatDestroy(&Qm));
  PetscCall(SgElasticityGetNearNullSpace(el, &nsp));
  if (nsp) { /* the rigid-body modes in the frame (Q is orthogonal: they stay orthonormal) */
    PetscBool  has_const;
    PetscInt   nv;
    const Vec *v;
    Vec        rv[6];
    PetscCall(MatNullSpaceGetVecs(nsp, &has_const, &nv, &v));
    for (PetscInt k = 0; k < nv; k++) {
      PetscCall(VecDuplicate(v[k], &rv[k]));
      PetscCall(VecCopy(v[k], rv[k]));
      PetscCall(SgFrameToLocal(f, rv[k]));
    }
    PetscCall(MatNullSpaceCreate(f->comm, has_const, nv, rv, &f->nsp));
    for (PetscInt k = 0; k < nv; k++) PetscCall(VecDestroy(&rv[k]));
    PetscCall(MatSetNearNullSpace(f->Kr, f->nsp));
  }
  PetscCall(PetscLogEventEnd(SG_FrameSetUp, 0, 0, 0, 0));
  PetscCall(PetscInfo(NULL, "-ssn_frame: %" PetscInt_FMT " of %" PetscInt_FMT " contact vertices rotated into the frame of their normal\n", f->nrot_global, cv.nglobal));
  *frame = f;
  PetscFunctionReturn(0);
}

PetscErrorCode SgFrameDestroy(SgFrame *frame)
{
  SgFrame f = *frame;

  PetscFunctionBeginUser;
  if (!f) PetscFunctionReturn(0);
  *frame = NULL;
  PetscCall(PetscFree4(f->Q, f->rot, f->axis, f->sign));
  PetscCall(MatDestroy(&f->Kr));
  PetscCall(MatNullSpaceDestroy(&f->nsp));
  PetscCall(VecDestroy(&f->b));
  PetscCall(PetscFree(f));
  PetscFunctionReturn(0);
}

/* the stiffness in the frame, Q^T K Q (with the rotated near null space) */
PetscErrorCode SgFrameGetStiffness(SgFrame f, Mat *Kr)
{
  PetscFunctionBeginUser;
  *Kr = f->Kr;
  PetscFunctionReturn(0);
}

/* per contact vertex: the frame dof of its normal, the sign (n = sign Q_i e_axis) and whether it is rotated */
PetscErrorCode SgFrameGetAxes(SgFrame f, const PetscInt *axis[], const PetscReal *sign[], const PetscBool *rot[])
{
  PetscFunctionBeginUser;
  if (axis) *axis = f->axis;
  if (sign) *sign = f->sign;
  if (rot) *rot = f->rot;
  PetscFunctionReturn(0);
}

/* --- a KSP solving in the frames: J x = b becomes (Q^T J Q) z = Q^T b, x = Q z; its matrices are the frame's --- */
static PetscErrorCode PreSolve_Frame(KSP ksp, Vec b, Vec x, void *ctx)
{
  SgFrame f = (SgFrame)ctx;

  PetscFunctionBeginUser;
  if (!f->b) PetscCall(VecDuplicate(b, &f->b));
  PetscCall(VecCopy(b, f->b)); /* the caller's right-hand side, given back unchanged after the solve */
  PetscCall(SgFrameToLocal(f, b));
  PetscCall(SgFrameToLocal(f, x)); /* a nonzero initial guess */
  PetscFunctionReturn(0);
}

static PetscErrorCode PostSolve_Frame(KSP ksp, Vec b, Vec x, void *ctx)
{
  SgFrame f = (SgFrame)ctx;

  PetscFunctionBeginUser;
  PetscCall(VecCopy(f->b, b));
  PetscCall(SgFrameToGlobal(f, x));
  PetscFunctionReturn(0);
}

/* The KSP (whose operators will be the frame's matrices: Q^T K Q, the SSN's Jacobians assembled in the frames) takes
   and returns vectors in the original coordinates, and iterates in the frames: its residuals, its preconditioner
   (AMG, truncated multigrid, factorization, condensation) and its stopping test all see the rotated system, where
   gamma sits on the normal dofs' diagonal only (the original coordinates would mix the round-off of gamma w, 1e8-1e15,
   into the tangential residual). The iterate of KSPBuildSolution during the solve is in the frames. */
PetscErrorCode SgFrameAttachKSP(SgFrame f, KSP ksp)
{
  PetscFunctionBeginUser;
  PetscCall(KSPSetPreSolve(ksp, PreSolve_Frame, f));
  PetscCall(KSPSetPostSolve(ksp, PostSolve_Frame, f));
  PetscFunctionReturn(0);
}

PetscErrorCode SgFrameDetachKSP(SgFrame f, KSP ksp)
{
  PetscFunctionBeginUser;
  (void)f;
  PetscCall(KSPSetPreSolve(ksp, NULL, NULL));
  PetscCall(KSPSetPostSolve(ksp, NULL, NULL));
  PetscFunctionReturn(0);
}
