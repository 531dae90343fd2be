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
     after it (KSPSetPreSolve/PostSolve), so the SNES around it never sees the frames. The SSN's own residual goes in
     by its frame form (SgFrameSetResidual: the normal contact force on the normal dof alone), not rotated whole.
   Residuals, iterates, controllers and outputs stay in the original coordinates. At a roller (a fixed component e_f,
   the normal orthogonal to it) the frame keeps e_f in its place, so the Dirichlet rows stay rows of the identity;
   vertices whose normal is already +-e_k keep the identity.
   Where every contact normal is the same direction (-ssn_frame_global, GlobalFrame), Q is one rotation R on every
   vertex of the body (rollers excepted), not only on the contact vertices: a rigidly turned body then gives the AMG
   the unturned stiffness, not one whose components couple off the axes away from the contact boundary. */
#include "solver/ssnimpl.h"
#include <petsc/private/petscimpl.h> /* an object's state (the residual's frame form, SgFrameSetResidual) */

struct _n_SgFrame {
  MPI_Comm         comm;
  PetscInt         dim, n, nrot; /* contact vertices here; of those rotated (on all ranks: nrot_global) */
  PetscInt         nrot_global;
  const PetscInt  *off;     /* dof offset of each contact vertex (the contact object's, SgContactGetVertices) */
  PetscInt         nglobal; /* contact vertices on all ranks */
  const PetscReal *normal;  /* their unit normals (SgContactGetNormals) */
  PetscReal       *Q;       /* Q_i row-major: column b is the frame's b-th vector in global components */
  PetscBool       *rot;     /* Q_i is not the identity */
  PetscInt        *axis;    /* the frame dof of the normal */
  PetscReal       *sign;    /* n = sign Q_i e_axis */
  PetscBool        global;  /* -ssn_frame_global: every vertex of the body in one frame R (GlobalFrame) */
  PetscReal        R[9];    /* that frame, row-major like Q_i */
  PetscInt         nb;      /* blocks (vertices) of the local part of a global vector */
  PetscInt        *bq;      /* per block: -1 the identity, -2 R, i >= 0 the frame Q_i of contact vertex i */
  Mat              Kr;      /* Q^T K Q */
  MatNullSpace     nsp;     /* the rotated near null space (NULL if the problem has none) */
  Vec              b;       /* a solve's right-hand side, kept to give it back (PreSolve_Frame) */
  Mat              T, Tinv; /* two bodies (-ssn_pair_transform, SgFrameCreatePair): the dual-mortar basis transformation
                              u = T v before the rotations (u = T Q z), and its inverse; NULL otherwise */
  PetscBool        ptap;    /* -ssn_pair_transform_ptap: (T Q)^T K (T Q) and (T Q)^-1 P by general products (MatPtAP) */
  Vec              w;       /* work for them */
  Vec              rnn;     /* the SSN's residual without its normal contact force (SgFrameResidualWork) */
  Vec              rloc;    /* that residual in the frames, the normal force on the normal dofs (SgFrameSetResidual) */
  Vec              rvec;    /* the residual vector it stands for, at the object state rstate */
  PetscObjectState rstate;
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

/* the frame of block (vertex) b of the local part of a global vector, NULL for the identity */
static inline const PetscReal *BlockFrame(SgFrame f, PetscInt b)
{
  const PetscInt q = f->bq[b];
  return q == -1 ? NULL : q == -2 ? f->R
                                  : &f->Q[q * f->dim * f->dim];
}

/* x_b <- Q_b^T x_b (to the frame) or Q_b x_b (back) at the rotated blocks of a local array */
static void RotateArray(SgFrame f, PetscScalar xa[], PetscBool back)
{
  const PetscInt dim = f->dim;
  for (PetscInt i = 0; i < f->nb; i++) {
    const PetscReal *Q = BlockFrame(f, i);
    PetscReal        x[3], r[3];
    if (!Q) continue;
    for (PetscInt a = 0; a < dim; a++) x[a] = PetscRealPart(xa[i * dim + a]);
    for (PetscInt a = 0; a < dim; a++) {
      r[a] = 0;
      for (PetscInt b = 0; b < dim; b++) r[a] += back ? Q[a * dim + b] * x[b] : Q[b * dim + a] * x[b];
    }
    for (PetscInt a = 0; a < dim; a++) xa[i * dim + a] = r[a];
  }
}

PetscErrorCode SgFrameToLocal(SgFrame f, Vec x)
{
  PetscScalar *xa;

  PetscFunctionBeginUser;
  if (f->T) { /* a displacement: z = Q^T T^-1 u */
    if (!f->w) PetscCall(VecDuplicate(x, &f->w));
    PetscCall(MatMult(f->Tinv, x, f->w));
    PetscCall(VecCopy(f->w, x));
  }
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
  if (f->T) { /* u = T Q z */
    if (!f->w) PetscCall(VecDuplicate(x, &f->w));
    PetscCall(MatMult(f->T, x, f->w));
    PetscCall(VecCopy(f->w, x));
  }
  PetscFunctionReturn(0);
}

/* a right-hand side (a force) into the frames: Q^T T^T b */
static PetscErrorCode ForceToLocal(SgFrame f, Vec b)
{
  PetscScalar *ba;

  PetscFunctionBeginUser;
  if (f->T) {
    if (!f->w) PetscCall(VecDuplicate(b, &f->w));
    PetscCall(MatMultTranspose(f->T, b, f->w));
    PetscCall(VecCopy(f->w, b));
  }
  PetscCall(VecGetArray(b, &ba));
  RotateArray(f, ba, PETSC_FALSE);
  PetscCall(VecRestoreArray(b, &ba));
  PetscFunctionReturn(0);
}

/* a force (a right-hand side) into the frames: Q^T b, with a pair's basis Q^T T^T b (the bound solvers' load) */
PetscErrorCode SgFrameForceToLocal(SgFrame f, Vec b)
{
  PetscFunctionBeginUser;
  PetscCall(ForceToLocal(f, b));
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

  PetscFunctionBeginUser;
  PetscCall(MatGetOwnershipRange(K, &rstart, &rend));
  m = rend - rstart;
  PetscCall(MatCreateAIJ(f->comm, m, m, PETSC_DETERMINE, PETSC_DETERMINE, bs, NULL, 0, NULL, Qm));
  PetscCall(MatSetBlockSize(*Qm, bs));
  PetscCall(MatSetOption(*Qm, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  for (PetscInt r = 0; r < m; r += bs) {
    const PetscReal *Q = BlockFrame(f, r / bs);
    PetscInt         idx[3];
    PetscScalar      v[9];
    for (PetscInt a = 0; a < bs; a++) idx[a] = rstart + r + a;
    for (PetscInt a = 0; a < bs; a++)
      for (PetscInt b = 0; b < bs; b++) v[a * bs + b] = Q ? Q[a * bs + b] : (a == b);
    PetscCall(MatSetValues(*Qm, bs, idx, bs, idx, v, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(*Qm, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*Qm, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* Q^T K Q in place on a copy of K, block by block: B_IJ <- Q_I^T B_IJ Q_J where Q_I or Q_J is not the identity (one
   pass over K's values; MatPtAP, its symbolic and numeric products, took 2-7 s at 124k unknowns), each block's
   products in MatPtAP's order (B Q_J, then Q_I^T), which gives its numbers to the bit (the solver paths of frictional
   problems follow round-off). For a sequential AIJ
   K whose rows come in blocks of dim with whole dim x dim blocks of columns (the P1 pattern of SgElasticity); *done
   false otherwise (MatPtAP then). */
static PetscErrorCode RotateStiffnessSeq(SgFrame f, Mat K, Mat *Kr, PetscBool *done)
{
  const PetscInt  bs = f->dim;
  const PetscInt *ia, *ja;
  PetscInt        nr;
  PetscBool       seq, flg, ok = PETSC_TRUE;
  PetscScalar    *v;

  PetscFunctionBeginUser;
  *done = PETSC_FALSE;
  PetscCall(PetscObjectTypeCompare((PetscObject)K, MATSEQAIJ, &seq));
  if (!seq) PetscFunctionReturn(0);
  PetscCall(MatGetRowIJ(K, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja, &flg));
  if (!flg) PetscFunctionReturn(0);
  ok = (PetscBool)(nr == f->nb * bs);
  for (PetscInt ib = 0; ok && ib < f->nb; ib++) {
    const PetscInt r0 = ib * bs, L = ia[r0 + 1] - ia[r0];
    if (L % bs) ok = PETSC_FALSE;
    for (PetscInt a = 0; ok && a < bs; a++) {
      if (ia[r0 + a + 1] - ia[r0 + a] != L) ok = PETSC_FALSE;
      for (PetscInt m = 0; ok && m < L; m++)
        if (ja[ia[r0 + a] + m] != ja[ia[r0] + m - m % bs] + m % bs || ja[ia[r0] + m - m % bs] % bs) ok = PETSC_FALSE;
    }
  }
  PetscCall(MatRestoreRowIJ(K, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja, &flg));
  if (!ok) PetscFunctionReturn(0);
  PetscCall(MatDuplicate(K, MAT_COPY_VALUES, Kr));
  PetscCall(MatGetRowIJ(*Kr, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja, &flg));
  PetscCall(MatSeqAIJGetArray(*Kr, &v));
  for (PetscInt ib = 0; ib < f->nb; ib++) {
    const PetscInt   r0 = ib * bs, L = ia[r0 + 1] - ia[r0];
    const PetscReal *QI = BlockFrame(f, ib);
    for (PetscInt m = 0; m < L; m += bs) {
      const PetscReal *QJ = BlockFrame(f, ja[ia[r0] + m] / bs);
      PetscReal        B[3][3], C[3][3];
      if (!QI && !QJ) continue;
      for (PetscInt a = 0; a < bs; a++)
        for (PetscInt b = 0; b < bs; b++) B[a][b] = PetscRealPart(v[ia[r0 + a] + m + b]);
      for (PetscInt a = 0; a < bs; a++) /* C = B Q_J, then Q_I^T C: the order of MatPtAP's products (A P, then P^T) */
        for (PetscInt b = 0; b < bs; b++) {
          C[a][b] = 0;
          for (PetscInt k = 0; k < bs; k++) C[a][b] += B[a][k] * (QJ ? QJ[k * bs + b] : (PetscReal)(k == b));
        }
      for (PetscInt a = 0; a < bs; a++)
        for (PetscInt b = 0; b < bs; b++) {
          PetscReal s = 0;
          for (PetscInt k = 0; k < bs; k++) s += (QI ? QI[k * bs + a] : (PetscReal)(k == a)) * C[k][b];
          v[ia[r0 + a] + m + b] = s;
        }
    }
  }
  PetscCall(MatSeqAIJRestoreArray(*Kr, &v));
  PetscCall(MatRestoreRowIJ(*Kr, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja, &flg));
  PetscCall(MatSetNearNullSpace(*Kr, NULL));
  *done = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* -ssn_frame_global: where every contact normal (on every rank) is the same direction n to 1e-8 (a plane obstacle with
   -contact_normal obstacle, a flat contact face with body), one frame R = [r_0, .., r_dim-1] for the whole body, n one
   of its columns: for a body turned rigidly by a rotation T (mesh, obstacle and data turned together) R = T S, S a
   signed permutation, so that Q^T K Q is the stiffness of the unturned body (S^T K_0 S: its unknowns in another order,
   some negated), which an unknown-based AMG treats as the unturned one; per contact vertex frames (R at the contact
   vertices only) leave the AMG a body whose components couple off the axes. The tangential axes in 3D are the
   principal axes of the body's second moments about its centroid, projected onto the plane normal to n (they turn
   with the body); where those two moments agree to 1e-6 (a body round about n) the minimal rotation of VertexFrame.
   Of the 2^dim dim! signed orders of the columns the one closest to the identity (largest trace). *ok false: the
   normals differ (or there are none). Collective. */
static PetscErrorCode GlobalFrame(SgFrame f, const SgMesh *m, PetscInt *kn, PetscReal *sn, PetscBool *ok)
{
  const PetscInt dim   = f->dim;
  PetscReal      ns[4] = {0, 0, 0, 0}, nb[3] = {0, 0, 0}, dev = 0, len = 0, F[9], Q0[9], s0;
  PetscInt       k0, perm[6][3] = {
                         {0, 1, 2},
                         {0, 2, 1},
                         {1, 0, 2},
                         {1, 2, 0},
                         {2, 0, 1},
                         {2, 1, 0}
  },
               np = dim == 2 ? 2 : 6, best = -1;
  PetscReal bestscore = -1;

  PetscFunctionBeginUser;
  *ok = PETSC_FALSE;
  for (PetscInt i = 0; i < f->n; i++) {
    for (PetscInt a = 0; a < dim; a++) ns[a] += f->normal[i * dim + a];
    ns[3] += 1;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, ns, 4, MPIU_REAL, MPIU_SUM, f->comm));
  for (PetscInt a = 0; a < dim; a++) len += ns[a] * ns[a];
  len = PetscSqrtReal(len);
  if (ns[3] < 1 || len < 0.5 * ns[3]) PetscFunctionReturn(0);
  for (PetscInt a = 0; a < dim; a++) nb[a] = ns[a] / len;
  for (PetscInt i = 0; i < f->n; i++)
    for (PetscInt a = 0; a < dim; a++) dev = PetscMax(dev, PetscAbsReal(f->normal[i * dim + a] - nb[a]));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &dev, 1, MPIU_REAL, MPIU_MAX, f->comm));
  if (dev > 1e-8) PetscFunctionReturn(0);
  VertexFrame(dim, nb, Q0, &k0, &s0);
  /* F: the columns (tangents..., n) */
  if (dim == 2) {
    for (PetscInt a = 0; a < 2; a++) F[a * 2 + 0] = Q0[a * 2 + (1 - k0)], F[a * 2 + 1] = nb[a];
  } else {
    PetscReal mom[4] = {0, 0, 0, 0}, C[6] = {0, 0, 0, 0, 0, 0}, ctr[3], ta[3], tb[3], M00 = 0, M01 = 0, M11 = 0;
    PetscInt  ia = (k0 + 1) % 3, ib = (k0 + 2) % 3;
    for (PetscInt pass = 0; pass < 2; pass++) { /* the centroid, then the second moments about it (P1 simplices exactly) */
      for (PetscInt c = 0; c < m->nc; c++) {
        const PetscInt *cv4 = &m->cellv[c * 4];
        PetscReal       x[4][3], e[3][3], vol, s[3] = {0, 0, 0};
        for (PetscInt j = 0; j < 4; j++)
          for (PetscInt a = 0; a < 3; a++) x[j][a] = m->x[cv4[j] * 3 + a] - (pass ? ctr[a] : 0);
        for (PetscInt j = 0; j < 3; j++)
          for (PetscInt a = 0; a < 3; a++) e[j][a] = x[j + 1][a] - x[0][a];
        vol = PetscAbsReal(e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) + e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) / 6;
        for (PetscInt j = 0; j < 4; j++)
          for (PetscInt a = 0; a < 3; a++) s[a] += x[j][a];
        if (!pass) {
          mom[3] += vol;
          for (PetscInt a = 0; a < 3; a++) mom[a] += vol * s[a] / 4;
        } else
          for (PetscInt a = 0, l = 0; a < 3; a++)
            for (PetscInt b = a; b < 3; b++, l++) {
              PetscReal xx = s[a] * s[b];
              for (PetscInt j = 0; j < 4; j++) xx += x[j][a] * x[j][b];
              C[l] += vol * xx / 20;
            }
      }
      if (!pass) {
        PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, mom, 4, MPIU_REAL, MPIU_SUM, f->comm));
        if (!(mom[3] > 0)) PetscFunctionReturn(0);
        for (PetscInt a = 0; a < 3; a++) ctr[a] = mom[a] / mom[3];
      } else PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, C, 6, MPIU_REAL, MPIU_SUM, f->comm));
    }
    for (PetscInt a = 0; a < 3; a++) ta[a] = Q0[a * 3 + ia], tb[a] = Q0[a * 3 + ib];
    {
      const PetscInt ix[3][3] = {
          {0, 1, 2},
          {1, 3, 4},
          {2, 4, 5}
      };
      for (PetscInt a = 0; a < 3; a++)
        for (PetscInt b = 0; b < 3; b++) {
          const PetscReal cab = C[ix[a][b]];
          M00 += ta[a] * cab * ta[b];
          M01 += ta[a] * cab * tb[b];
          M11 += tb[a] * cab * tb[b];
        }
    }
    if (PetscAbsReal(M00 - M11) + 2 * PetscAbsReal(M01) > 1e-6 * (M00 + M11)) { /* the principal axes in the plane */
      const PetscReal th = 0.5 * PetscAtan2Real(2 * M01, M00 - M11), cs = PetscCosReal(th), sn = PetscSinReal(th);
      for (PetscInt a = 0; a < 3; a++) {
        const PetscReal u = cs * ta[a] + sn * tb[a], v = -sn * ta[a] + cs * tb[a];
        ta[a] = u, tb[a] = v;
      }
    }
    for (PetscInt a = 0; a < 3; a++) F[a * 3 + 0] = ta[a], F[a * 3 + 1] = tb[a], F[a * 3 + 2] = nb[a];
  }
  /* the signed order of the columns closest to the identity: R e_j = sign F e_perm[j] */
  for (PetscInt p = 0; p < np; p++) {
    PetscReal score = 0;
    PetscInt  q[3]  = {perm[p][0], perm[p][1], perm[p][2]};
    if (dim == 2) q[0] = p, q[1] = 1 - p;
    for (PetscInt j = 0; j < dim; j++) score += PetscAbsReal(F[j * dim + q[j]]);
    if (score > bestscore + 1e-12) bestscore = score, best = p;
  }
  for (PetscInt j = 0; j < dim; j++) {
    const PetscInt  q  = dim == 2 ? (j ? 1 - best : best) : perm[best][j];
    const PetscReal sg = F[j * dim + q] < 0 ? -1 : 1;
    for (PetscInt a = 0; a < dim; a++) f->R[a * dim + j] = sg * F[a * dim + q];
    if (q == dim - 1) *kn = j, *sn = sg;
  }
  *ok = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* contact vertex i under the global frame: R, its normal column the vertex's own normal exactly (n = sign Q e_k) and
   the tangential columns R's made orthogonal to it (they differ from R's by the normals' round-off) */
static void GlobalVertexFrame(SgFrame f, const PetscReal n[], PetscInt k, PetscReal sign, PetscReal Q[])
{
  const PetscInt dim = f->dim;
  PetscInt       prev[3], np = 0;

  for (PetscInt a = 0; a < dim; a++) Q[a * dim + k] = sign * n[a];
  prev[np++] = k;
  for (PetscInt j = 0; j < dim; j++) {
    PetscReal len = 0;
    if (j == k) continue;
    for (PetscInt a = 0; a < dim; a++) Q[a * dim + j] = f->R[a * dim + j];
    for (PetscInt l = 0; l < np; l++) {
      PetscReal d = 0;
      for (PetscInt a = 0; a < dim; a++) d += Q[a * dim + j] * Q[a * dim + prev[l]];
      for (PetscInt a = 0; a < dim; a++) Q[a * dim + j] -= d * Q[a * dim + prev[l]];
    }
    for (PetscInt a = 0; a < dim; a++) len += Q[a * dim + j] * Q[a * dim + j];
    len = PetscSqrtReal(len);
    for (PetscInt a = 0; a < dim; a++) Q[a * dim + j] /= len;
    prev[np++] = j;
  }
}

/* The start of a frame's set-up (the log event begun): the object for the contact vertices of c, each with its own
   frame from its normal (the identity where the normal is an axis) */
static PetscErrorCode FrameStart(SgElasticity el, SgContact c, PetscInt *dim, SgFrame *frame)
{
  SgFrame f;

  PetscFunctionBeginUser;
  if (!frame_registered) {
    PetscCall(PetscLogEventRegister("SgFrameSetUp", MAT_CLASSID, &SG_FrameSetUp));
    frame_registered = PETSC_TRUE;
  }
  PetscCall(PetscLogEventBegin(SG_FrameSetUp, 0, 0, 0, 0));
  PetscCall(SgElasticityGetDimension(el, dim));
  PetscCall(PetscNew(&f));
  PetscCall(SgElasticityGetComm(el, &f->comm));
  f->dim = *dim;
  PetscCall(SgContactGetVertices(c, &f->n, &f->nglobal, NULL, &f->off));
  PetscCall(SgContactGetNormals(c, &f->normal));
  PetscCall(PetscMalloc4(f->n * *dim * *dim, &f->Q, f->n, &f->rot, f->n, &f->axis, f->n, &f->sign));
  for (PetscInt i = 0; i < f->n; i++) {
    const PetscInt   d = *dim;
    const PetscReal *n = &f->normal[i * d];
    PetscInt         k = -1;
    for (PetscInt a = 0; a < d; a++)
      if (PetscAbsReal(PetscAbsReal(n[a]) - 1) < 1e-10) k = a;
    if (k >= 0) { /* already an axis: the identity, the normal on dof k */
      for (PetscInt a = 0; a < d * d; a++) f->Q[i * d * d + a] = (a % (d + 1) == 0);
      f->rot[i]  = PETSC_FALSE;
      f->axis[i] = k;
      f->sign[i] = n[k] > 0 ? 1 : -1;
      continue;
    }
    VertexFrame(d, n, &f->Q[i * d * d], &f->axis[i], &f->sign[i]);
    f->rot[i] = PETSC_TRUE;
  }
  *frame = f;
  PetscFunctionReturn(0);
}

/* The near null space of the frame's stiffness Kr: the elasticity's rigid-body modes taken into the frame's unknowns
   (SgFrameToLocal: Q^T r, orthonormal still as Q is orthogonal; with the pair's basis (T Q)^-1 r, no longer
   orthonormal, which the AMG does not need); keepconst: keep the space's constant flag, else none */
static PetscErrorCode FrameNullSpace(SgFrame f, SgElasticity el, PetscBool keepconst)
{
  MatNullSpace nsp;
  PetscBool    has_const;
  PetscInt     nv;
  const Vec   *v;
  Vec          rv[6];

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetNearNullSpace(el, &nsp));
  if (!nsp) PetscFunctionReturn(0);
  PetscCall(MatNullSpaceGetVecs(nsp, &has_const, &nv, &v));
  for (PetscInt k = 0; k < nv; k++) {
    PetscCall(VecDuplicate(v[k], &rv[k]));
    PetscCall(VecCopy(v[k], rv[k]));
    PetscCall(SgFrameToLocal(f, rv[k]));
  }
  PetscCall(MatNullSpaceCreate(f->comm, keepconst && has_const, nv, rv, &f->nsp));
  for (PetscInt k = 0; k < nv; k++) PetscCall(VecDestroy(&rv[k]));
  PetscCall(MatSetNearNullSpace(f->Kr, f->nsp));
  PetscFunctionReturn(0);
}

/* The frames of the contact vertices, or NULL where every normal (on every rank) is a coordinate axis already. */
PetscErrorCode SgFrameCreate(SgElasticity el, SgContact c, PetscBool global, SgFrame *frame)
{
  SgFrame       f;
  const SgMesh *m;
  Mat           K, Qm;
  PetscInt      dim, mloc, kn = -1;
  PetscReal     sn = 1;
  PetscBool     aligned, ok = PETSC_FALSE, done;

  PetscFunctionBeginUser;
  *frame = NULL;
  if (!c) PetscFunctionReturn(0);
  PetscCall(SgContactNormalsAxisAligned(c, &aligned));
  if (aligned) PetscFunctionReturn(0);
  PetscCall(FrameStart(el, c, &dim, &f));
  PetscCall(SgElasticityGetMesh(el, &m));
  PetscCall(SgElasticityGetOperators(el, &K, NULL));
  PetscCall(MatGetLocalSize(K, &mloc, NULL));
  f->nb = mloc / dim;
  PetscCall(PetscMalloc1(f->nb, &f->bq));
  if (global) PetscCall(GlobalFrame(f, m, &kn, &sn, &ok));
  f->global = ok;
  for (PetscInt b = 0; b < f->nb; b++) f->bq[b] = ok ? -2 : -1;
  if (ok) { /* R on every block but at a roller (a partly fixed vertex: its fixed components must stay dofs of their
               own, the Dirichlet rows rows of the identity): there the frame of the contact vertex as above, else none */
    for (PetscInt v = 0; v < m->nv; v++)
      if (m->goff[v] >= 0 && SgMeshPartial(m, v)) f->bq[m->goff[v] / dim] = -1;
    for (PetscInt i = 0; i < f->n; i++) {
      if (f->bq[f->off[i] / dim] == -1) continue; /* a roller */
      GlobalVertexFrame(f, &f->normal[i * dim], kn, sn, &f->Q[i * dim * dim]);
      f->rot[i]  = PETSC_TRUE;
      f->axis[i] = kn;
      f->sign[i] = sn;
    }
  }
  f->nrot = 0;
  for (PetscInt i = 0; i < f->n; i++)
    if (f->rot[i]) f->bq[f->off[i] / dim] = i;
  for (PetscInt b = 0; b < f->nb; b++) f->nrot += f->bq[b] != -1;
  PetscCallMPI(MPI_Allreduce(&f->nrot, &f->nrot_global, 1, MPIU_INT, MPI_SUM, f->comm));
  PetscCall(RotateStiffnessSeq(f, K, &f->Kr, &done));
  if (!done) {
    PetscCall(FrameMatrix(f, K, &Qm));
    PetscCall(MatPtAP(K, Qm, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &f->Kr));
    PetscCall(MatDestroy(&Qm));
  }
  PetscCall(MatSetBlockSize(f->Kr, dim));
  PetscCall(FrameNullSpace(f, el, PETSC_TRUE));
  PetscCall(PetscLogEventEnd(SG_FrameSetUp, 0, 0, 0, 0));
  if (f->global && dim == 2) PetscCall(PetscInfo(NULL, "-ssn_frame: the body in one frame (-ssn_frame_global): %" PetscInt_FMT " vertices rotated, the normal on dof %" PetscInt_FMT ", R = [%g %g; %g %g]\n", f->nrot_global, kn, (double)f->R[0], (double)f->R[1], (double)f->R[2], (double)f->R[3]));
  else if (f->global) PetscCall(PetscInfo(NULL, "-ssn_frame: the body in one frame (-ssn_frame_global): %" PetscInt_FMT " vertices rotated, the normal on dof %" PetscInt_FMT ", R = [%g %g %g; %g %g %g; %g %g %g]\n", f->nrot_global, kn, (double)f->R[0], (double)f->R[1], (double)f->R[2], (double)f->R[3], (double)f->R[4], (double)f->R[5], (double)f->R[6], (double)f->R[7], (double)f->R[8]));
  else PetscCall(PetscInfo(NULL, "-ssn_frame: %" PetscInt_FMT " of %" PetscInt_FMT " contact vertices rotated into the frame of their normal\n", f->nrot_global, f->nglobal));
  *frame = f;
  PetscFunctionReturn(0);
}

/* Two bodies (-ssn_pair_transform): the dual-mortar basis transformation T of the pair (SgContactPairTransform), then
   the frame of each contact vertex's normal: the linear solves see (T Q)^T J (T Q), where every condition of the pair
   is a diagonal entry on its normal dof (B T Q z = D_j sign_j z_j,axis), as against a rigid obstacle; so the AMG, the
   truncated multigrid and the friction blocks of the one-body path apply. (T Q)^T K (T Q) is formed once; its near
   null space is (T Q)^-1 applied to the rigid-body modes. Made even where every normal is an axis (T alone). */
/* G^T K G for G = T Q, the identity but on the rows of the slave contact vertices: with W = G - I (those rows alone) and
   H = W^T K (nonzero on the rows of the slave vertices and of their master vertices),
   G^T K G = K + H + H^T + H W: K's values copied and corrected on the rows and columns of the pair's vertices
   (SgMatAddSparse), where MatPtAP formed the symbolic and numeric products over the whole of K (4.6 s of the 299,316
   unknowns' 4 levels, bench/results.md "pair5"). The same matrix to round-off (H^T stands for K W: K is symmetric);
   -ssn_pair_transform_ptap forms it by MatPtAP. */
static PetscErrorCode PairStiffness(Mat K, Mat G, Mat *Kr)
{
  Mat W, Wt, H, Ht, HW, C1, C;

  PetscFunctionBeginUser;
  PetscCall(SgMatOffIdentity(G, &W));
  PetscCall(MatTranspose(W, MAT_INITIAL_MATRIX, &Wt));
  PetscCall(MatMatMult(Wt, K, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &H));
  PetscCall(MatTranspose(H, MAT_INITIAL_MATRIX, &Ht));
  PetscCall(MatMatMult(H, W, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &HW));
  PetscCall(SgMatAddSparse(H, Ht, &C1)); /* not MatAXPY: that one passes over all rows by MatGetRow and MatSetValues */
  PetscCall(SgMatAddSparse(C1, HW, &C));
  PetscCall(SgMatAddSparse(K, C, Kr));
  PetscCall(MatDestroy(&C));
  PetscCall(MatDestroy(&C1));
  PetscCall(MatDestroy(&HW));
  PetscCall(MatDestroy(&Ht));
  PetscCall(MatDestroy(&H));
  PetscCall(MatDestroy(&Wt));
  PetscCall(MatDestroy(&W));
  PetscFunctionReturn(0);
}

PetscErrorCode SgFrameCreatePair(SgElasticity el, SgContact c, const char who[], const char advice[], PetscBool ptap, SgFrame *frame)
{
  SgFrame  f;
  Mat      K, Qm, G;
  PetscInt dim, mloc;

  PetscFunctionBeginUser;
  *frame = NULL;
  PetscCall(FrameStart(el, c, &dim, &f));
  PetscCall(SgElasticityGetOperators(el, &K, NULL));
  PetscCall(MatGetLocalSize(K, &mloc, NULL));
  f->nb = mloc / dim;
  PetscCall(PetscMalloc1(f->nb, &f->bq));
  for (PetscInt b = 0; b < f->nb; b++) f->bq[b] = -1;
  for (PetscInt i = 0; i < f->n; i++)
    if (f->rot[i]) f->bq[f->off[i] / dim] = i;
  f->nrot = 0;
  for (PetscInt b = 0; b < f->nb; b++) f->nrot += f->bq[b] != -1;
  PetscCallMPI(MPI_Allreduce(&f->nrot, &f->nrot_global, 1, MPIU_INT, MPI_SUM, f->comm));
  PetscCall(SgContactPairTransform(c, who, advice, &f->T, &f->Tinv));
  PetscCall(FrameMatrix(f, K, &Qm));
  PetscCall(MatMatMult(f->T, Qm, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &G));
  f->ptap = ptap;
  if (ptap) PetscCall(MatPtAP(K, G, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &f->Kr));
  else PetscCall(PairStiffness(K, G, &f->Kr));
  PetscCall(MatDestroy(&G));
  PetscCall(MatDestroy(&Qm));
  PetscCall(MatSetBlockSize(f->Kr, dim));
  PetscCall(FrameNullSpace(f, el, PETSC_FALSE)); /* (T Q)^-1 r */
  PetscCall(PetscLogEventEnd(SG_FrameSetUp, 0, 0, 0, 0));
  PetscCall(PetscInfo(NULL, "-ssn_pair_transform: the pair's dual-mortar transformation, %" PetscInt_FMT " of %" PetscInt_FMT " contact vertices rotated into the frame of their normal\n", f->nrot_global, f->nglobal));
  *frame = f;
  PetscFunctionReturn(0);
}

/* Two bodies: an interpolation P into K's unknowns (the displacements u) taken into the pair's basis, (T Q)^-1 P =
   Q^T T^-1 P, so that the Galerkin product with the transformed stiffness is K's own:
   ((T Q)^-1 P)^T (T Q)^T K (T Q) (T Q)^-1 P = P^T K P. An AMG of K coarsens each body apart and keeps each body's
   rigid motions; in the basis these are not smooth (v_s = u_s - D^-1 M u_m jumps at the slave surface), so the AMG of
   the transformed stiffness does not find them. Sparse: T^-1 is the identity but at the slave rows. */
PetscErrorCode SgFramePairInterpolation(SgFrame f, Mat P, Mat *Pv)
{
  Mat G, Qm;

  PetscFunctionBeginUser;
  PetscCheck(f && f->Tinv, PETSC_COMM_SELF, PETSC_ERR_PLIB, "SgFramePairInterpolation: the frame has no pair transformation");
  if (f->ptap) {
    PetscCall(MatMatMult(f->Tinv, P, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &G));
    PetscCall(FrameMatrix(f, G, &Qm));
    PetscCall(MatTransposeMatMult(Qm, G, MAT_INITIAL_MATRIX, PETSC_DEFAULT, Pv));
  } else { /* P + W P, W = Q^T T^-1 - I: nonzero on the slave rows alone, so W P costs those rows (not P's all) */
    Mat Qt, W, WP;
    PetscCall(FrameMatrix(f, f->Tinv, &Qm));
    PetscCall(MatTranspose(Qm, MAT_INITIAL_MATRIX, &Qt));
    PetscCall(MatMatMult(Qt, f->Tinv, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &G));
    PetscCall(SgMatOffIdentity(G, &W));
    PetscCall(MatMatMult(W, P, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &WP));
    PetscCall(SgMatAddSparse(P, WP, Pv));
    PetscCall(MatDestroy(&WP));
    PetscCall(MatDestroy(&W));
    PetscCall(MatDestroy(&Qt));
  }
  PetscCall(MatDestroy(&Qm));
  PetscCall(MatDestroy(&G));
  PetscFunctionReturn(0);
}

/* whether the frame carries the pair's transformation (its contact blocks are nodal: SgSSNAddBlocks) */
PetscBool SgFramePairTransform(SgFrame f)
{
  return (PetscBool)(f && f->T);
}

/* the one rotation R of the whole body (-ssn_frame_global; row-major, column b the frame's b-th vector), NULL where
   the frames are the contact vertices' alone */
PetscErrorCode SgFrameGetGlobalRotation(SgFrame f, const PetscReal **R)
{
  PetscFunctionBeginUser;
  *R = f && f->global ? f->R : NULL;
  PetscFunctionReturn(0);
}

PetscErrorCode SgFrameDestroy(SgFrame *frame)
{
  SgFrame f = *frame;

  PetscFunctionBeginUser;
  if (!f) PetscFunctionReturn(0);
  *frame = NULL;
  PetscCall(PetscFree4(f->Q, f->rot, f->axis, f->sign));
  PetscCall(PetscFree(f->bq));
  PetscCall(MatDestroy(&f->Kr));
  PetscCall(MatNullSpaceDestroy(&f->nsp));
  PetscCall(VecDestroy(&f->b));
  PetscCall(MatDestroy(&f->T));
  PetscCall(MatDestroy(&f->Tinv));
  PetscCall(VecDestroy(&f->w));
  PetscCall(VecDestroy(&f->rnn));
  PetscCall(VecDestroy(&f->rloc));
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

/* The SSN's residual F = K y - b + sum_i w_i m_i n_i in the frames, for the right-hand side of its Newton step. Rotating
   F itself (ForceToLocal) mixes the normal force into the tangential dofs: w m is gamma g w, up to 1e12 after a step that
   changed the active set, and Q_i^T n_i = sign (e_k + O(eps)), so the tangential rows of Q^T F carry eps w m (the rounding
   of F's components and the O(eps) of Q_i^T n_i), which the Jacobian (gamma w on the normal's diagonal only,
   jacobian.c) does not have: the step is off by that much and the next one must correct it (Example 2 turned at 17k
   unknowns: 6 SSN steps against 5 flat). Here the normal force goes onto the normal dof alone, sign w m, and the
   rest, Q^T (K y - b), is rotated without it: the tangential rows are exactly what the Jacobian differentiates. At a
   contact vertex the frame leaves as it is (its normal an axis to 1e-10) the force is added as SgContactAddForce does.
   Frictionless one-body contact only (the SSN calls it so): rnn, from SgFrameResidualWork, holds K y - b. */
PetscErrorCode SgFrameResidualWork(SgFrame f, Vec F, Vec *rnn)
{
  PetscFunctionBeginUser;
  if (!f->rnn) PetscCall(VecDuplicate(F, &f->rnn));
  *rnn = f->rnn;
  PetscFunctionReturn(0);
}

/* F: the residual just formed (its state is recorded: the KSP's PreSolve takes the frame form only for that F);
   w, m: the weights and multipliers of its normal forces */
PetscErrorCode SgFrameSetResidual(SgFrame f, Vec F, const PetscReal w[], const PetscReal m[])
{
  const PetscInt dim = f->dim;
  PetscScalar   *ra;

  PetscFunctionBeginUser;
  PetscCheck(f->rnn && !f->T, f->comm, PETSC_ERR_PLIB, "SgFrameSetResidual: no residual work vector, or a pair's frame");
  if (!f->rloc) PetscCall(VecDuplicate(F, &f->rloc));
  PetscCall(VecCopy(f->rnn, f->rloc));
  PetscCall(VecGetArray(f->rloc, &ra));
  RotateArray(f, ra, PETSC_FALSE);
  for (PetscInt i = 0; i < f->n; i++) {
    if (f->rot[i]) ra[f->off[i] + f->axis[i]] += w[i] * m[i] * f->sign[i];
    else
      for (PetscInt k = 0; k < dim; k++) ra[f->off[i] + k] += w[i] * m[i] * f->normal[i * dim + k];
  }
  PetscCall(VecRestoreArray(f->rloc, &ra));
  f->rvec = F;
  PetscCall(PetscObjectStateGet((PetscObject)F, &f->rstate));
  PetscFunctionReturn(0);
}

/* --- a KSP solving in the frames: J x = b becomes (Q^T J Q) z = Q^T b, x = Q z; its matrices are the frame's --- */
static PetscErrorCode PreSolve_Frame(KSP ksp, Vec b, Vec x, void *ctx)
{
  SgFrame f = (SgFrame)ctx;

  PetscObjectState st;

  PetscFunctionBeginUser;
  if (!f->b) PetscCall(VecDuplicate(b, &f->b));
  PetscCall(VecCopy(b, f->b)); /* the caller's right-hand side, given back unchanged after the solve */
  if (b == f->rvec) PetscCall(PetscObjectStateGet((PetscObject)b, &st));
  if (b == f->rvec && st == f->rstate) PetscCall(VecCopy(f->rloc, b)); /* the SSN's residual: its frame form */
  else PetscCall(ForceToLocal(f, b));
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
