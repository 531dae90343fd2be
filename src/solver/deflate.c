/* deflate.c: a small deflation space for CG with the truncated multigrid (-ssn_pc_truncated_mg_deflate, tmg.c).
   On one fine two-body mesh the preconditioned Jacobian of the last SSN steps has a few isolated small eigenvalues
   below the continuum (bench/results.md, tb1mesh: four from 1.3e-4 to 1.6e-2 under 0.04 at 117,693 unknowns), which
   CG resolves one by one (they sit on a slave vertex whose row of the pair's D^-1 M is 100 times the others', defl).
   Their vectors are taken from the previous solve's CG: the Lanczos matrix T of the
   preconditioned operator follows from CG's step lengths alpha and the ratios beta = rho_{j+1} / rho_j (rho = r^T z),
   its Lanczos vectors are the preconditioned residuals z_j / sqrt(rho_j) with alternating signs; the Ritz vectors of
   T's eigenvalues below a threshold join the space Z while it has room (the older ones stay). Each CG solve then uses
   the balanced (BNN) form M_d = Q + (I - Q J) M (I - J Q), Q = Z (Z^T J Z)^-1 Z^T, which is symmetric and positive
   definite for any Z, so CG stays CG; with W = J Z computed once per operator and Z J-orthonormalised, an application
   is the V-cycle, two multiple dot products and two multiple AXPYs (k <= the maximum, a few vectors) and no product
   with J. All vectors are the KSP's (distributed); the small dense matrices are formed from reductions and the same
   on every rank.
   CG's step lengths are not public: alpha_j = d_j^T r_j / rho_j with d_j = x_{j+1} - x_j the change of the KSP's
   solution between two applications (CG's p_j^T r_j = rho_j). */
#include "solver/ssnimpl.h"
#include <petscblaslapack.h>
#include <petsc/private/petscimpl.h> /* an object's state (the operator W = J Z was made for) */

struct _n_SgDefl {
  PetscInt         kmax;  /* the space's maximum size */
  PetscInt         mcap;  /* at most this many preconditioned residuals kept per solve */
  PetscReal        thr;   /* Ritz values below this join the space */
  PetscInt         k;     /* the space's size */
  Vec             *Z, *W; /* the space (J-orthonormal) and J Z */
  PetscObjectState Wstate;
  PetscObjectId    Wid;
  PetscBool        Wok;
  /* the current solve's CG: z_j, rho_j, alpha_j */
  PetscInt     m, na; /* z's kept, alphas known */
  PetscInt     its;   /* the iteration of the last application */
  PetscBool    rec;   /* recording (stopped by a breakdown or an unexpected order of applications) */
  Vec         *zs;
  PetscReal   *rho, *alpha;
  Vec          rprev, xprev, d, rt;
  PetscScalar *c, *c2;
  PetscInt     nritz; /* statistics: Ritz vectors taken */
  PetscReal    ritz0; /* the last Lanczos matrix's smallest eigenvalue */
};

PetscErrorCode SgDeflCreate(PetscInt kmax, PetscInt mcap, PetscReal thr, SgDefl *defl)
{
  SgDefl d;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&d));
  d->kmax = kmax;
  d->mcap = mcap;
  d->thr  = thr;
  PetscCall(PetscCalloc4(kmax, &d->Z, kmax, &d->W, mcap, &d->zs, 2 * kmax, &d->c));
  d->c2 = d->c + kmax;
  PetscCall(PetscMalloc2(mcap + 1, &d->rho, mcap + 1, &d->alpha));
  *defl = d;
  PetscFunctionReturn(0);
}

PetscErrorCode SgDeflDestroy(SgDefl *defl)
{
  SgDefl d = *defl;

  PetscFunctionBeginUser;
  if (!d) PetscFunctionReturn(0);
  for (PetscInt i = 0; i < d->kmax; i++) {
    PetscCall(VecDestroy(&d->Z[i]));
    PetscCall(VecDestroy(&d->W[i]));
  }
  for (PetscInt i = 0; i < d->mcap; i++) PetscCall(VecDestroy(&d->zs[i]));
  PetscCall(VecDestroy(&d->rprev));
  PetscCall(VecDestroy(&d->xprev));
  PetscCall(VecDestroy(&d->d));
  PetscCall(VecDestroy(&d->rt));
  PetscCall(PetscFree4(d->Z, d->W, d->zs, d->c));
  PetscCall(PetscFree2(d->rho, d->alpha));
  PetscCall(PetscFree(*defl));
  PetscFunctionReturn(0);
}

/* The Ritz vectors of the recorded solve with values below thr, put in front of Z (the oldest dropped beyond kmax) */
static PetscErrorCode Harvest(SgDefl d)
{
  PetscBLASInt n, lwork, info;
  PetscInt     nt = PetscMin(d->na, d->m), nnew = 0;
  PetscScalar *T, *w, *work, *coef;

  PetscFunctionBeginUser;
  if (nt < 2) PetscFunctionReturn(0);
  PetscCall(PetscBLASIntCast(nt, &n));
  lwork = 3 * n;
  PetscCall(PetscCalloc4(nt * nt, &T, nt, &w, lwork, &work, nt, &coef));
  for (PetscInt j = 0; j < nt; j++) { /* T_jj = 1/a_j + b_{j-1}/a_{j-1}, T_{j,j+1} = sqrt(b_j)/a_j, b_j = rho_{j+1}/rho_j */
    T[j * nt + j] = 1.0 / d->alpha[j] + (j > 0 ? d->rho[j] / d->rho[j - 1] / d->alpha[j - 1] : 0.0);
    if (j + 1 < nt) T[j * nt + j + 1] = T[(j + 1) * nt + j] = PetscSqrtReal(d->rho[j + 1] / d->rho[j]) / d->alpha[j];
  }
  PetscCall(PetscFPTrapPush(PETSC_FP_TRAP_OFF));
  PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "U", &n, T, &n, w, work, &lwork, &info));
  PetscCall(PetscFPTrapPop());
  PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "deflation: LAPACK syev of the Lanczos matrix failed (info %d)", (int)info);
  d->ritz0 = PetscRealPart(w[0]);
  for (PetscInt i = 0; i < nt && nnew < d->kmax && PetscRealPart(w[i]) < d->thr; i++) nnew++;
  nnew = PetscMin(nnew, d->kmax - d->k); /* a full space stays: its vectors were the smallest before (those replaced
                                            would come back in the next solve) */
  if (nnew > 0) {
    PetscInt keep = d->k;
    for (PetscInt i = keep - 1; i >= 0; i--) {
      d->Z[i + nnew] = d->Z[i];
      d->W[i + nnew] = d->W[i];
    }
    for (PetscInt i = 0; i < nnew; i++) {
      for (PetscInt j = 0; j < nt; j++) coef[j] = T[i * nt + j] * ((j % 2) ? -1.0 : 1.0) / PetscSqrtReal(d->rho[j]);
      PetscCall(VecDuplicate(d->zs[0], &d->Z[i]));
      PetscCall(VecDuplicate(d->zs[0], &d->W[i]));
      PetscCall(VecSet(d->Z[i], 0.0));
      PetscCall(VecMAXPY(d->Z[i], nt, coef, d->zs));
    }
    d->k = keep + nnew;
    d->nritz += nnew;
    d->Wok = PETSC_FALSE;
    PetscCall(PetscInfo(NULL, "deflation: %" PetscInt_FMT " Ritz vectors of %" PetscInt_FMT " steps taken (smallest value %g), space %" PetscInt_FMT "\n", nnew, nt, (double)PetscRealPart(w[0]), d->k));
  }
  PetscCall(PetscFree4(T, w, work, coef));
  PetscFunctionReturn(0);
}

/* W = J Z and Z, W J-orthonormalised (Z^T J Z = I; directions with Z^T J Z's eigenvalues below 1e-10 of the largest
   dropped) */
static PetscErrorCode SpaceForOperator(SgDefl d, Mat A)
{
  PetscInt     k = d->k, kk = 0;
  PetscBLASInt n, lwork, info;
  PetscScalar *E, *ev, *work;
  Vec         *Zn, *Wn;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < k; i++) PetscCall(MatMult(A, d->Z[i], d->W[i]));
  PetscCall(PetscCalloc3(k * k, &E, k, &ev, 3 * k, &work));
  for (PetscInt i = 0; i < k; i++) PetscCall(VecMDot(d->W[i], k, d->Z, E + i * k));
  for (PetscInt i = 0; i < k; i++)
    for (PetscInt j = 0; j < i; j++) E[i * k + j] = E[j * k + i] = 0.5 * (E[i * k + j] + E[j * k + i]);
  PetscCall(PetscBLASIntCast(k, &n));
  lwork = 3 * n;
  PetscCall(PetscFPTrapPush(PETSC_FP_TRAP_OFF));
  PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "U", &n, E, &n, ev, work, &lwork, &info));
  PetscCall(PetscFPTrapPop());
  PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "deflation: LAPACK syev of Z^T J Z failed (info %d)", (int)info);
  PetscCall(PetscCalloc2(k, &Zn, k, &Wn));
  for (PetscInt i = k - 1; i >= 0; i--) { /* largest first: the kept ones */
    PetscScalar col[64];
    if (!(PetscRealPart(ev[i]) > 1e-10 * PetscRealPart(ev[k - 1]))) break;
    for (PetscInt j = 0; j < k; j++) col[j] = E[i * k + j] / PetscSqrtReal(PetscRealPart(ev[i]));
    PetscCall(VecDuplicate(d->Z[0], &Zn[kk]));
    PetscCall(VecDuplicate(d->Z[0], &Wn[kk]));
    PetscCall(VecSet(Zn[kk], 0.0));
    PetscCall(VecSet(Wn[kk], 0.0));
    PetscCall(VecMAXPY(Zn[kk], k, col, d->Z));
    PetscCall(VecMAXPY(Wn[kk], k, col, d->W));
    kk++;
  }
  for (PetscInt i = 0; i < k; i++) {
    PetscCall(VecDestroy(&d->Z[i]));
    PetscCall(VecDestroy(&d->W[i]));
  }
  for (PetscInt i = 0; i < kk; i++) {
    d->Z[i] = Zn[i];
    d->W[i] = Wn[i];
  }
  d->k = kk;
  PetscCall(PetscFree2(Zn, Wn));
  PetscCall(PetscFree3(E, ev, work));
  PetscCall(PetscObjectStateGet((PetscObject)A, &d->Wstate));
  PetscCall(PetscObjectGetId((PetscObject)A, &d->Wid));
  d->Wok = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* Record CG's application j (residual r, preconditioned z, the KSP's solution x = x_j) */
static PetscErrorCode Record(SgDefl d, PetscInt j, Vec r, Vec z, Vec x)
{
  PetscScalar rho, dr = 0;

  PetscFunctionBeginUser;
  if (j == 0) {
    d->m = d->na = 0;
    d->rec       = PETSC_TRUE;
    if (!d->rprev) {
      PetscCall(VecDuplicate(r, &d->rprev));
      PetscCall(VecDuplicate(r, &d->xprev));
      PetscCall(VecDuplicate(r, &d->d));
    }
  } else if (!d->rec || j != d->its + 1 || d->na != j - 1) {
    d->rec = PETSC_FALSE;
    PetscFunctionReturn(0);
  }
  d->its = j;
  if (j > 0) {
    PetscCall(VecWAXPY(d->d, -1.0, d->xprev, x));
    PetscCall(VecDotBegin(d->d, d->rprev, &dr));
  }
  PetscCall(VecDotBegin(r, z, &rho));
  if (j > 0) PetscCall(VecDotEnd(d->d, d->rprev, &dr));
  PetscCall(VecDotEnd(r, z, &rho));
  if (j > 0) {
    d->alpha[j - 1] = PetscRealPart(dr) / d->rho[j - 1];
    if (!(d->alpha[j - 1] > 0)) {
      d->rec = PETSC_FALSE;
      PetscFunctionReturn(0);
    }
    d->na = j;
  }
  if (!(PetscRealPart(rho) > 0) || j >= d->mcap) {
    d->rec = PETSC_FALSE;
    PetscFunctionReturn(0);
  }
  d->rho[j] = PetscRealPart(rho);
  if (!d->zs[j]) PetscCall(VecDuplicate(z, &d->zs[j]));
  PetscCall(VecCopy(z, d->zs[j]));
  d->m = j + 1;
  PetscCall(VecCopy(r, d->rprev));
  PetscCall(VecCopy(x, d->xprev));
  PetscFunctionReturn(0);
}

/* y = M_d r for the KSP's operator A, M the preconditioner pc (the V-cycle); ksp: the CG solve being recorded (NULL:
   none) */
PetscErrorCode SgDeflApply(SgDefl d, KSP ksp, Mat A, PC pc, Vec r, Vec y)
{
  PetscInt its = -1;
  Vec      x   = NULL;

  PetscFunctionBeginUser;
  if (ksp) {
    PetscBool cg;
    PetscCall(PetscObjectTypeCompare((PetscObject)ksp, KSPCG, &cg));
    if (cg) {
      PetscCall(KSPGetIterationNumber(ksp, &its));
      PetscCall(KSPGetSolution(ksp, &x));
    }
  }
  if (its == 0) { /* a new solve: the previous one's Ritz vectors join the space */
    PetscCall(Harvest(d));
    d->m = d->na = 0;
  }
  if (d->k && d->Wok) {
    PetscObjectState st;
    PetscObjectId    id;
    PetscCall(PetscObjectStateGet((PetscObject)A, &st));
    PetscCall(PetscObjectGetId((PetscObject)A, &id));
    if (st != d->Wstate || id != d->Wid) d->Wok = PETSC_FALSE;
  }
  if (d->k && !d->Wok) PetscCall(SpaceForOperator(d, A));
  if (!d->k) PetscCall(PCApply(pc, r, y));
  else { /* c = Z^T r, v = M (r - W c), y = v + Z (c - W^T v) */
    if (!d->rt) PetscCall(VecDuplicate(r, &d->rt));
    PetscCall(VecMDot(r, d->k, d->Z, d->c));
    PetscCall(VecCopy(r, d->rt));
    for (PetscInt i = 0; i < d->k; i++) d->c2[i] = -d->c[i];
    PetscCall(VecMAXPY(d->rt, d->k, d->c2, d->W));
    PetscCall(PCApply(pc, d->rt, y));
    PetscCall(VecMDot(y, d->k, d->W, d->c2));
    for (PetscInt i = 0; i < d->k; i++) d->c2[i] = d->c[i] - d->c2[i];
    PetscCall(VecMAXPY(y, d->k, d->c2, d->Z));
  }
  if (its >= 0) PetscCall(Record(d, its, r, y, x));
  PetscFunctionReturn(0);
}

/* the space (k vectors Z, J-orthonormal once applied), the Ritz vectors taken so far and the smallest eigenvalue of the
   last Lanczos matrix (0 before any) */
PetscErrorCode SgDeflGetSpace(SgDefl d, PetscInt *k, const Vec **Z, PetscInt *nritz, PetscReal *ritz0)
{
  PetscFunctionBeginUser;
  if (k) *k = d ? d->k : 0;
  if (Z) *Z = d ? d->Z : NULL;
  if (nritz) *nritz = d ? d->nritz : 0;
  if (ritz0) *ritz0 = d ? d->ritz0 : 0;
  PetscFunctionReturn(0);
}
