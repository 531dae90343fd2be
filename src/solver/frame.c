/* frame.c: a frame (n, t1, t2) per contact vertex, so that the linear solves see every contact normal as a coordinate
   axis (-ssn_frame).
   At a vertex whose normal n is not +-e_k the contact block gamma w n n^T couples its components with a gamma of
   1e8-1e18: an unknown-based AMG cannot smooth that, the truncated multigrid cannot truncate it and condensation must
   keep every component. In the vertex's own orthonormal frame Q_i = [n, t1, t2] the block is gamma w e_0 e_0^T, a
   diagonal entry. The linear systems J dy = F of the SSN are therefore solved as (Q^T J Q) z = Q^T F, dy = Q z, with
   Q block diagonal (Q_i at the rotated vertices, the identity elsewhere):
   - the rotated stiffness Q^T K Q is formed once (it does not change);
   - the SSN's Jacobians are assembled directly in the frame (the contact blocks on the normal dof: no round-off of
     gamma leaks into the tangential entries), into the preconditioning matrix;
   - the Krylov method still iterates on the original vectors: its operator is Q (Q^T J Q) Q^T (a shell) and its
     preconditioner Q M^{-1} Q^T with M the configured preconditioner (AMG, truncated multigrid, factorization,
     condensation) of the rotated matrix, whose near null space gets the rotated rigid-body modes.
   Residuals, iterates, controllers and outputs stay in the original coordinates. At a roller (a fixed component e_k)
   the frame keeps e_k in its place, so the Dirichlet rows stay rows of the identity; vertices whose normal is already
   +-e_k keep the identity. */
#include "solver/ssnimpl.h"

struct _n_SgFrame {
  MPI_Comm     comm;
  PetscInt     refct;         /* the SSN, the shell operator and each wrapped KSP hold one */
  PetscInt     dim, n, nrot;  /* contact vertices here; of those rotated (on all ranks: nrot_global) */
  PetscInt     nrot_global;
  const PetscInt *off;        /* dof offset of each contact vertex (the contact view's) */
  PetscReal   *Q;             /* Q_i row-major: column b is the frame's b-th vector in global components */
  PetscBool   *rot;           /* Q_i is not the identity */
  PetscInt    *axis;          /* the frame dof of the normal */
  PetscReal   *sign;          /* n = sign Q_i e_axis */
  Mat          Kr;            /* Q^T K Q */
  MatNullSpace nsp;           /* the rotated near null space (NULL if the problem has none) */
  Vec          w;             /* work vector (the shell operator and preconditioner) */
  Mat          P;             /* the preconditioning matrix the shell operator multiplies with */
};

static PetscLogEvent SG_FrameSetUp;
static PetscBool     frame_registered = PETSC_FALSE;

/* the frame of contact vertex i with unit normal n, a fixed component (or -1) and whether it is aligned */
static void VertexFrame(PetscInt dim, const PetscReal n[], PetscInt fixed, PetscReal Q[], PetscInt *axis)
{
  for (PetscInt k = 0; k < dim * dim; k++) Q[k] = 0;
  if (dim == 2) { /* [n, t], t = n turned by 90 degrees */
    Q[0] = n[0], Q[2] = n[1];
    Q[1] = -n[1], Q[3] = n[0];
    *axis = 0;
    return;
  }
  if (fixed >= 0) { /* e_fixed stays; n and e_fixed x n fill the other two slots */
    const PetscInt j1 = fixed == 0 ? 1 : 0, j2 = fixed == 2 ? 1 : 2;
    PetscReal      t[3], e[3] = {0, 0, 0};
    e[fixed] = 1;
    t[0]     = e[1] * n[2] - e[2] * n[1];
    t[1]     = e[2] * n[0] - e[0] * n[2];
    t[2]     = e[0] * n[1] - e[1] * n[0];
    for (PetscInt a = 0; a < 3; a++) {
      Q[a * 3 + fixed] = e[a];
      Q[a * 3 + j1]    = n[a];
      Q[a * 3 + j2]    = t[a];
    }
    *axis = j1;
    return;
  }
  { /* t1: the coordinate axis least aligned with n, made orthogonal to it; t2 = n x t1 */
    PetscInt  m = 0;
    PetscReal t1[3], t2[3], nt = 0, tn = 0;
    for (PetscInt a = 1; a < 3; a++)
      if (PetscAbsReal(n[a]) < PetscAbsReal(n[m])) m = a;
    for (PetscInt a = 0; a < 3; a++) t1[a] = (a == m ? 1 : 0) - n[m] * n[a];
    for (PetscInt a = 0; a < 3; a++) nt += t1[a] * t1[a];
    nt = PetscSqrtReal(nt);
    for (PetscInt a = 0; a < 3; a++) t1[a] /= nt;
    t2[0] = n[1] * t1[2] - n[2] * t1[1];
    t2[1] = n[2] * t1[0] - n[0] * t1[2];
    t2[2] = n[0] * t1[1] - n[1] * t1[0];
    for (PetscInt a = 0; a < 3; a++) tn += t2[a] * t2[a];
    tn = PetscSqrtReal(tn);
    for (PetscInt a = 0; a < 3; a++) {
      Q[a * 3 + 0] = n[a];
      Q[a * 3 + 1] = t1[a];
      Q[a * 3 + 2] = t2[a] / tn;
    }
    *axis = 0;
  }
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
  PetscInt rstart, rend, m, bs = f->dim;
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
  f->refct = 1;
  f->dim   = dim;
  f->n     = cv.n;
  f->off = cv.off;
  PetscCall(PetscMalloc4(cv.n * dim * dim, &f->Q, cv.n, &f->rot, cv.n, &f->axis, cv.n, &f->sign));
  for (PetscInt i = 0; i < cv.n; i++) {
    const PetscReal *n = &cv.normal[i * dim];
    PetscInt         k = -1, fixed = -1;
    for (PetscInt a = 0; a < dim; a++)
      if (PetscAbsReal(PetscAbsReal(n[a]) - 1) < 1e-10) k = a;
    if (k >= 0) { /* already an axis: the identity, the normal on dof k */
      for (PetscInt a = 0; a < dim * dim; a++) f->Q[i * dim * dim + a] = (a % (dim + 1) == 0);
      f->rot[i]  = PETSC_FALSE;
      f->axis[i] = k;
      f->sign[i] = n[k] > 0 ? 1 : -1;
      continue;
    }
    for (PetscInt a = 0; a < dim; a++)
      if (SgMeshFixed(m, cv.vert[i], a)) fixed = a; /* the normal is orthogonal to it (contact.c); two fixed: an axis */
    VertexFrame(dim, n, fixed, &f->Q[i * dim * dim], &f->axis[i]);
    f->rot[i]  = PETSC_TRUE;
    f->sign[i] = 1;
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
  PetscCall(MatCreateVecs(f->Kr, &f->w, NULL));
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
  if (--f->refct > 0) PetscFunctionReturn(0);
  PetscCall(PetscFree4(f->Q, f->rot, f->axis, f->sign));
  PetscCall(MatDestroy(&f->Kr));
  PetscCall(MatNullSpaceDestroy(&f->nsp));
  PetscCall(VecDestroy(&f->w));
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

PetscErrorCode SgFrameGetRotatedCount(SgFrame f, PetscInt *nrot)
{
  PetscFunctionBeginUser;
  *nrot = f->nrot_global;
  PetscFunctionReturn(0);
}

/* --- the operator Q P Q^T (a shell on the frame's preconditioning matrix P) --- */
static PetscErrorCode MatMult_Frame(Mat A, Vec x, Vec y)
{
  SgFrame f;

  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(A, &f));
  PetscCall(VecCopy(x, f->w));
  PetscCall(SgFrameToLocal(f, f->w));
  PetscCall(MatMult(f->P, f->w, y));
  PetscCall(SgFrameToGlobal(f, y));
  PetscFunctionReturn(0);
}

static PetscErrorCode MatDestroy_Frame(Mat A)
{
  SgFrame f;

  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(A, &f));
  PetscCall(SgFrameDestroy(&f));
  PetscFunctionReturn(0);
}

static PetscErrorCode MatMultTranspose_Frame(Mat A, Vec x, Vec y)
{
  SgFrame f;

  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(A, &f));
  PetscCall(VecCopy(x, f->w));
  PetscCall(SgFrameToLocal(f, f->w));
  PetscCall(MatMultTranspose(f->P, f->w, y));
  PetscCall(SgFrameToGlobal(f, y));
  PetscFunctionReturn(0);
}

/* The operator of the Krylov method, Q P Q^T in the original coordinates, for the frame's matrix P (the SSN assembles
   its Jacobians into P). */
PetscErrorCode SgFrameCreateOperator(SgFrame f, Mat P, Mat *A)
{
  PetscInt m, M;

  PetscFunctionBeginUser;
  f->P = P;
  PetscCall(MatGetLocalSize(P, &m, NULL));
  PetscCall(MatGetSize(P, &M, NULL));
  PetscCall(MatCreateShell(f->comm, m, m, M, M, f, A));
  PetscCall(MatShellSetOperation(*A, MATOP_MULT, (void (*)(void))MatMult_Frame));
  PetscCall(MatShellSetOperation(*A, MATOP_MULT_TRANSPOSE, (void (*)(void))MatMultTranspose_Frame));
  PetscCall(MatShellSetOperation(*A, MATOP_DESTROY, (void (*)(void))MatDestroy_Frame));
  f->refct++;
  PetscCall(MatSetBlockSize(*A, f->dim));
  PetscCall(PetscObjectSetName((PetscObject)*A, "Q J_frame Q^T"));
  PetscFunctionReturn(0);
}

/* --- the preconditioner Q M^{-1} Q^T, M the KSP's configured preconditioner on the frame's matrix --- */
typedef struct {
  SgFrame f;
  PC      inner;
  Vec     w;
} FramePC;

static PetscErrorCode PCSetUp_Frame(PC pc)
{
  FramePC *fp;
  Mat      A, P;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &fp));
  PetscCall(PCGetOperators(pc, &A, &P));
  PetscCall(PCSetOperators(fp->inner, P, P));
  PetscCall(PCSetUp(fp->inner));
  if (!fp->w) PetscCall(MatCreateVecs(P, &fp->w, NULL));
  PetscFunctionReturn(0);
}

static PetscErrorCode PCApply_Frame(PC pc, Vec r, Vec x)
{
  FramePC *fp;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &fp));
  PetscCall(VecCopy(r, fp->w));
  PetscCall(SgFrameToLocal(fp->f, fp->w));
  PetscCall(PCApply(fp->inner, fp->w, x));
  PetscCall(SgFrameToGlobal(fp->f, x));
  PetscFunctionReturn(0);
}

static PetscErrorCode PCApplyTranspose_Frame(PC pc, Vec r, Vec x)
{
  FramePC *fp;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &fp));
  PetscCall(VecCopy(r, fp->w));
  PetscCall(SgFrameToLocal(fp->f, fp->w));
  PetscCall(PCApplyTranspose(fp->inner, fp->w, x));
  PetscCall(SgFrameToGlobal(fp->f, x));
  PetscFunctionReturn(0);
}

static PetscErrorCode PCView_Frame(PC pc, PetscViewer v)
{
  FramePC *fp;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &fp));
  PetscCall(PetscViewerASCIIPrintf(v, "contact frames (-ssn_frame): %" PetscInt_FMT " contact vertices rotated into (n, t); the preconditioner of the rotated matrix:\n", fp->f->nrot_global));
  PetscCall(PetscViewerASCIIPushTab(v));
  PetscCall(PCView(fp->inner, v));
  PetscCall(PetscViewerASCIIPopTab(v));
  PetscFunctionReturn(0);
}

static PetscErrorCode PCDestroy_Frame(PC pc)
{
  FramePC *fp;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &fp));
  PetscCall(PCDestroy(&fp->inner));
  PetscCall(VecDestroy(&fp->w));
  PetscCall(SgFrameDestroy(&fp->f));
  PetscCall(PetscFree(fp));
  PetscFunctionReturn(0);
}

/* The KSP's preconditioner (whatever it is configured to: AMG, the truncated multigrid, a factorization, the
   condensation) moves inside Q M^{-1} Q^T: it is set up on the frame's matrix, the KSP's preconditioning matrix. */
PetscErrorCode SgFrameWrapKSP(SgFrame f, KSP ksp)
{
  FramePC *fp;
  PC       pc, inner;

  PetscFunctionBeginUser;
  PetscCall(KSPGetPC(ksp, &inner));
  PetscCall(PetscObjectReference((PetscObject)inner));
  PetscCall(PetscNew(&fp));
  fp->f     = f;
  fp->inner = inner;
  f->refct++;
  PetscCall(PCCreate(f->comm, &pc));
  PetscCall(PCSetType(pc, PCSHELL));
  PetscCall(PCShellSetContext(pc, fp));
  PetscCall(PCShellSetName(pc, "contact frames"));
  PetscCall(PCShellSetSetUp(pc, PCSetUp_Frame));
  PetscCall(PCShellSetApply(pc, PCApply_Frame));
  PetscCall(PCShellSetApplyTranspose(pc, PCApplyTranspose_Frame));
  PetscCall(PCShellSetView(pc, PCView_Frame));
  PetscCall(PCShellSetDestroy(pc, PCDestroy_Frame));
  PetscCall(KSPSetPC(ksp, pc));
  PetscCall(PCDestroy(&pc));
  PetscFunctionReturn(0);
}
