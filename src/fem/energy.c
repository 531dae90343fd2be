/* energy.c: the measures of a displacement and a residual: the energy V(y) in compensated sums (with its long double
   debug reference) and the discrete dual norm. */
#include "fem/femimpl.h"

/* Neumaier's compensated sum: s + c carries the sum of the added terms to about one rounding of the result. */
typedef struct {
  PetscReal s, c;
} SgSum;

static inline void SumAdd(SgSum *a, PetscReal x)
{
  const PetscReal t = a->s + x;
  if (PetscAbsReal(a->s) >= PetscAbsReal(x)) a->c += (a->s - t) + x;
  else a->c += (x - t) + a->s;
  a->s = t;
}

typedef struct {
  long double s, c;
} SgSumL;

static inline void SumAddL(SgSumL *a, long double x)
{
  const long double t = a->s + x;
  if (fabsl(a->s) >= fabsl(x)) a->c += (a->s - t) + x;
  else a->c += (x - t) + a->s;
  a->s = t;
}

/* Debug reference of the energy (-elasticity_energy_check): per element 1/2 w^T K_e w with K_e built in long double
   from the coordinates and w = u_e - u_0 (K_e annihilates translations), the load work and the foundation in long
   double; partial sums gathered as pairs of doubles. */
static PetscErrorCode EnergyReference(SgElasticity p, const PetscScalar ya[], const PetscScalar fa[], Vec y, long double *Vref)
{
  const SgMesh  *m   = &p->mesh;
  const PetscInt dim = p->dim, nv = dim + 1;
  SgSumL         el = {0, 0}, ld = {0, 0}, tot = {0, 0};
  PetscInt       nloc, n;
  double         part[4], *all;
  PetscMPIInt    size;

  PetscFunctionBeginUser;
  for (PetscInt c = 0; c < m->nc; c++) {
    const PetscInt *cv = &m->cellv[c * nv];
    long double     J[3][3], Ji[3][3], det, G[4][3], w[12], vol, e = 0;
    PetscReal       lambda, mu;

    SgElasticityCellLame(p, c, &lambda, &mu);

    for (PetscInt a = 0; a < dim; a++)
      for (PetscInt d = 0; d < dim; d++) J[d][a] = (long double)m->x[cv[a + 1] * dim + d] - (long double)m->x[cv[0] * dim + d];
    if (dim == 2) {
      det      = J[0][0] * J[1][1] - J[0][1] * J[1][0];
      Ji[0][0] = J[1][1] / det;
      Ji[0][1] = -J[0][1] / det;
      Ji[1][0] = -J[1][0] / det;
      Ji[1][1] = J[0][0] / det;
      vol      = fabsl(det) / 2;
    } else {
      det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) + J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
      for (PetscInt i = 0; i < 3; i++)
        for (PetscInt j = 0; j < 3; j++) Ji[i][j] = (J[(j + 1) % 3][(i + 1) % 3] * J[(j + 2) % 3][(i + 2) % 3] - J[(j + 1) % 3][(i + 2) % 3] * J[(j + 2) % 3][(i + 1) % 3]) / det;
      vol = fabsl(det) / 6;
    }
    for (PetscInt d = 0; d < dim; d++) {
      G[0][d] = 0;
      for (PetscInt a = 1; a <= dim; a++) {
        G[a][d] = Ji[a - 1][d];
        G[0][d] -= Ji[a - 1][d];
      }
    }
    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt d = 0; d < dim; d++) w[a * dim + d] = (long double)PetscRealPart(ya[m->loff[cv[a]] + d]) - (long double)PetscRealPart(ya[m->loff[cv[0]] + d]);
    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt i = 0; i < dim; i++)
        for (PetscInt b = 0; b < nv; b++)
          for (PetscInt j = 0; j < dim; j++) {
            long double gg = 0, K;
            for (PetscInt k = 0; k < dim; k++) gg += G[a][k] * G[b][k];
            K = vol * ((long double)lambda * G[a][i] * G[b][j] + (long double)mu * (G[a][j] * G[b][i] + (i == j ? gg : 0)));
            e += w[a * dim + i] * K * w[b * dim + j];
          }
    SumAddL(&el, e / 2);
  }
  PetscCall(VecGetLocalSize(p->fpart, &nloc));
  for (PetscInt i = 0; i < nloc; i++) SumAddL(&ld, (long double)PetscRealPart(fa[i]) * (long double)PetscRealPart(ya[i]));
  if (p->rigid_shift > 0) {
    const PetscScalar *yg, *mg;
    const long double  cs = (long double)p->rigid_shift * p->E / ((long double)p->diam * p->diam);
    PetscCall(VecGetLocalSize(y, &n));
    PetscCall(VecGetArrayRead(y, &yg));
    PetscCall(VecGetArrayRead(p->mass, &mg));
    for (PetscInt i = 0; i < n; i++) SumAddL(&el, cs * PetscRealPart(mg[i]) * PetscRealPart(yg[i]) * PetscRealPart(yg[i]) / 2);
    PetscCall(VecRestoreArrayRead(y, &yg));
    PetscCall(VecRestoreArrayRead(p->mass, &mg));
  }
  {
    const long double E = el.s + el.c, W = ld.s + ld.c;
    part[0] = (double)E;
    part[1] = (double)(E - (long double)part[0]);
    part[2] = (double)W;
    part[3] = (double)(W - (long double)part[2]);
  }
  PetscCallMPI(MPI_Comm_size(p->comm, &size));
  PetscCall(PetscMalloc1(4 * size, &all));
  PetscCallMPI(MPI_Allgather(part, 4, MPI_DOUBLE, all, 4, MPI_DOUBLE, p->comm));
  for (PetscMPIInt r = 0; r < size; r++) {
    SumAddL(&tot, all[4 * r]);
    SumAddL(&tot, all[4 * r + 1]);
    SumAddL(&tot, -(long double)all[4 * r + 2]);
    SumAddL(&tot, -(long double)all[4 * r + 3]);
  }
  PetscCall(PetscFree(all));
  *Vref = tot.s + tot.c;
  PetscFunctionReturn(0);
}

/* V(y) = 1/2 a(u,u) - L(u) of the full field u (free values y, Dirichlet values from the data), exact to round-off:
   the elastic energy per element, vol (lambda/2 (div u)^2 + mu eps:eps) >= 0 from the displacement differences along
   the edges (no cancellation, as 1/2 y^T K y - b^T y has on fine meshes), the load work f.u with the unlifted load,
   each summed with compensation, and the partial sums of the ranks added in rank order (the same on any rank).
   Costs about one pass over the cells (no matrix product). */
PetscErrorCode SgElasticityEnergy(SgElasticity p, Vec y, PetscReal *V)
{
  const SgMesh      *m   = &p->mesh;
  const PetscInt     dim = p->dim, nv = dim + 1;
  Vec                yloc;
  const PetscScalar *ya, *fa;
  SgSum              el = {0, 0}, ld = {0, 0}, tot = {0, 0};
  PetscInt           nloc;
  PetscReal          part[4], *all;
  PetscMPIInt        size;
  PetscLogDouble     t0, t1;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(DMGetLocalVector(p->dm, &yloc));
  PetscCall(SgElasticityGlobalToLocal(p, y, yloc));
  PetscCall(VecGetArrayRead(yloc, &ya));
  PetscCall(VecGetArrayRead(p->fpart, &fa));
  /* every cell is on exactly one rank (no overlap), as in the assembly */
  for (PetscInt c = 0; c < m->nc; c++) {
    const PetscInt *cv = &m->cellv[c * nv];
    PetscReal       xe[12], G[12], vol, H[3][3] = {{0}}, tr = 0, e2 = 0, lambda, mu;

    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt d = 0; d < dim; d++) xe[a * dim + d] = m->x[cv[a] * dim + d];
    PetscCall(SgSimplexGradients(dim, xe, G, &vol));
    /* grad u = sum_{a>0} (u_a - u_0) grad phi_a, since the gradients sum to zero */
    for (PetscInt a = 1; a < nv; a++)
      for (PetscInt i = 0; i < dim; i++) {
        const PetscReal du = PetscRealPart(ya[m->loff[cv[a]] + i]) - PetscRealPart(ya[m->loff[cv[0]] + i]);
        for (PetscInt j = 0; j < dim; j++) H[i][j] += du * G[a * dim + j];
      }
    for (PetscInt i = 0; i < dim; i++) {
      tr += H[i][i];
      for (PetscInt j = 0; j < dim; j++) e2 += PetscSqr(0.5 * (H[i][j] + H[j][i]));
    }
    SgElasticityCellLame(p, c, &lambda, &mu);
    SumAdd(&el, vol * (0.5 * lambda * tr * tr + mu * e2));
  }
  PetscCall(VecGetLocalSize(p->fpart, &nloc));
  for (PetscInt i = 0; i < nloc; i++)
    if (fa[i] != 0) SumAdd(&ld, PetscRealPart(fa[i]) * PetscRealPart(ya[i]));
  if (p->rigid_shift > 0) { /* the foundation of -elasticity_rigid_shift, on the free dofs this rank owns */
    const PetscScalar *yg, *mg;
    const PetscReal    cs = p->rigid_shift * p->E / PetscSqr(p->diam);
    PetscInt           n;
    PetscCall(VecGetLocalSize(y, &n));
    PetscCall(VecGetArrayRead(y, &yg));
    PetscCall(VecGetArrayRead(p->mass, &mg));
    for (PetscInt i = 0; i < n; i++) SumAdd(&el, 0.5 * cs * PetscRealPart(mg[i]) * PetscSqr(PetscRealPart(yg[i])));
    PetscCall(VecRestoreArrayRead(y, &yg));
    PetscCall(VecRestoreArrayRead(p->mass, &mg));
  }
  part[0] = el.s;
  part[1] = el.c;
  part[2] = ld.s;
  part[3] = ld.c;
  PetscCallMPI(MPI_Comm_size(p->comm, &size));
  PetscCall(PetscMalloc1(4 * size, &all));
  PetscCallMPI(MPI_Allgather(part, 4, MPIU_REAL, all, 4, MPIU_REAL, p->comm));
  for (PetscMPIInt r = 0; r < size; r++) {
    SumAdd(&tot, all[4 * r]);
    SumAdd(&tot, all[4 * r + 1]);
    SumAdd(&tot, -all[4 * r + 2]);
    SumAdd(&tot, -all[4 * r + 3]);
  }
  PetscCall(PetscFree(all));
  *V = tot.s + tot.c;
  PetscCall(PetscTime(&t1));
  if (p->energy_check) {
    long double Vref = 0;
    Vec         Ky;
    PetscScalar yKy, by;
    PetscReal   Vold;

    PetscCall(EnergyReference(p, ya, fa, y, &Vref));
    PetscCall(VecDuplicate(y, &Ky));
    PetscCall(MatMult(p->K, y, Ky));
    PetscCall(VecDot(y, Ky, &yKy));
    PetscCall(VecDot(y, p->b, &by));
    PetscCall(VecDestroy(&Ky));
    Vold = 0.5 * PetscRealPart(yKy) - PetscRealPart(by) + p->energy_shift;
    PetscCall(PetscPrintf(p->comm, "energy check: compensated %.17e (%.3g s), y^T K y formula %.17e, long double reference %.17e; relative errors %.3e (compensated), %.3e (formula)\n", (double)*V, (double)(t1 - t0), (double)Vold, (double)Vref, (double)(fabsl((long double)*V - Vref) / fabsl(Vref)), (double)(fabsl((long double)Vold - Vref) / fabsl(Vref))));
  }
  PetscCall(VecRestoreArrayRead(p->fpart, &fa));
  PetscCall(VecRestoreArrayRead(yloc, &ya));
  PetscCall(DMRestoreLocalVector(p->dm, &yloc));
  PetscFunctionReturn(0);
}

/* Discrete dual norm of a residual: sqrt(sum_j R_j^2 / m_j), m_j the lumped volume of dof j. */
PetscErrorCode SgElasticityDualNorm(SgElasticity p, Vec R, PetscReal *nrm)
{
  Vec w;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(R, &w));
  PetscCall(VecPointwiseMult(w, R, R));
  PetscCall(VecPointwiseDivide(w, w, p->mass));
  PetscCall(VecSum(w, nrm));
  *nrm = PetscSqrtReal(PetscMax(*nrm, 0));
  PetscCall(VecDestroy(&w));
  PetscFunctionReturn(0);
}
