/* rigid.c: the rigid motions a Dirichlet part leaves free: the affine dimension of its vertices and the free motions
   of its fixed components. */
#include "fem/femimpl.h"
#include <petscblaslapack.h>

/* The farthest point of this rank's set from a reference (dist(x) >= 0), over all ranks: its distance and coordinates. */
typedef PetscReal (*PointDist)(const PetscReal[], const PetscReal[], const PetscReal[], PetscInt);

static PetscReal DistPoint(const PetscReal x[], const PetscReal p0[], const PetscReal e[], PetscInt dim)
{
  PetscReal s = 0;
  for (PetscInt d = 0; d < dim; d++) s += PetscSqr(x[d] - p0[d]);
  return PetscSqrtReal(s);
}

static PetscReal DistLine(const PetscReal x[], const PetscReal p0[], const PetscReal e[], PetscInt dim)
{
  PetscReal t = 0, s = 0;
  for (PetscInt d = 0; d < dim; d++) t += (x[d] - p0[d]) * e[d];
  for (PetscInt d = 0; d < dim; d++) s += PetscSqr(x[d] - p0[d] - t * e[d]);
  return PetscSqrtReal(s);
}

static PetscErrorCode FarthestConstrained(MPI_Comm comm, const SgMesh *m, PointDist dist, const PetscReal p0[], const PetscReal e[], PetscReal *dmax, PetscReal x[])
{
  struct {
    double v;
    int    r;
  } loc = {-1.0, 0}, glob;
  PetscMPIInt rank;
  PetscInt    best = -1;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscReal dv;
    if (m->bcmask[v] != (1 << m->dim) - 1) continue;
    dv = dist(&m->x[v * m->dim], p0, e, m->dim);
    if (dv > loc.v) {
      loc.v = (double)dv;
      best  = v;
    }
  }
  loc.r = rank;
  PetscCallMPI(MPI_Allreduce(&loc, &glob, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm));
  for (PetscInt d = 0; d < 3; d++) x[d] = 0;
  if (glob.r == rank && best >= 0)
    for (PetscInt d = 0; d < m->dim; d++) x[d] = m->x[best * m->dim + d];
  PetscCallMPI(MPI_Bcast(x, 3, MPIU_REAL, glob.r, comm));
  *dmax = (PetscReal)glob.v;
  PetscFunctionReturn(0);
}

/* Affine dimension of the set of Dirichlet vertices (each fixes every component), over all ranks: -1 no vertex, 0 one
   point, 1 collinear points, 2 not collinear. Distances below 1e-10 of the mesh's diameter count as zero.
   p0: a Dirichlet vertex; dir: the direction of the line when adim = 1; diam: the diameter of the mesh's bounding box. */
PetscErrorCode SgMeshConstrainedDimension(MPI_Comm comm, const SgMesh *m, PetscInt *adim, PetscReal p0[3], PetscReal dir[3], PetscReal *diam)
{
  const PetscInt dim = m->dim;
  PetscReal      box[6] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, d1, d2, p1[3], p2[3], tol;
  PetscMPIInt    rank, size, first;
  PetscInt       v0 = -1;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  for (PetscInt v = 0; v < m->nv; v++) {
    for (PetscInt d = 0; d < dim; d++) {
      box[d]     = PetscMin(box[d], m->x[v * dim + d]);
      box[3 + d] = PetscMin(box[3 + d], -m->x[v * dim + d]);
    }
    if (v0 < 0 && m->bcmask[v] == (1 << dim) - 1) v0 = v;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, box, 6, MPIU_REAL, MPIU_MIN, comm));
  *diam = 0;
  for (PetscInt d = 0; d < dim; d++) *diam += PetscSqr(-box[3 + d] - box[d]);
  *diam = PetscSqrtReal(*diam);
  tol   = 1e-10 * *diam;
  for (PetscInt d = 0; d < 3; d++) p0[d] = dir[d] = 0;
  first = v0 >= 0 ? rank : size;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, comm));
  if (first == size) {
    *adim = -1;
    PetscFunctionReturn(0);
  }
  if (rank == first)
    for (PetscInt d = 0; d < dim; d++) p0[d] = m->x[v0 * dim + d];
  PetscCallMPI(MPI_Bcast(p0, 3, MPIU_REAL, first, comm));
  PetscCall(FarthestConstrained(comm, m, DistPoint, p0, dir, &d1, p1));
  if (d1 <= tol) {
    *adim = 0;
    PetscFunctionReturn(0);
  }
  for (PetscInt d = 0; d < dim; d++) dir[d] = (p1[d] - p0[d]) / d1;
  PetscCall(FarthestConstrained(comm, m, DistLine, p0, dir, &d2, p2));
  *adim = d2 <= tol ? 1 : 2;
  PetscFunctionReturn(0);
}

/* The rigid motions u(x) = t + w x (x - c) that every fixed component of the Dirichlet vertices leaves free (that
   part of the data is u_d(x_v) = (t + w x (x_v - c))_d = 0), for parts that fix only some components: the null space
   of the Gram matrix of those linear functionals, in the coordinates of the bounding box's centre c scaled by its
   diameter. nfree modes of nr = 3 (2D: t_x, t_y, w) or 6 (3D: t, w) numbers each, translations in units of length,
   rotations per unit length (so that both move the body by about as much). */
PetscErrorCode SgMeshFreeRigidMotions(MPI_Comm comm, const SgMesh *m, PetscInt *nfree, PetscReal modes[], PetscReal c[3])
{
  const PetscInt dim = m->dim, nr = dim == 2 ? 3 : 6;
  PetscReal      box[6] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, L = 0;
  PetscScalar    G[36] = {0}, work[64];
  PetscReal      ev[6];
  PetscBLASInt   n, lwork = 64, info;

  PetscFunctionBeginUser;
  for (PetscInt v = 0; v < m->nv; v++)
    for (PetscInt d = 0; d < dim; d++) {
      box[d]     = PetscMin(box[d], m->x[v * dim + d]);
      box[3 + d] = PetscMin(box[3 + d], -m->x[v * dim + d]);
    }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, box, 6, MPIU_REAL, MPIU_MIN, comm));
  for (PetscInt d = 0; d < 3; d++) c[d] = d < dim ? 0.5 * (box[d] - box[3 + d]) : 0;
  for (PetscInt d = 0; d < dim; d++) L += PetscSqr(-box[3 + d] - box[d]);
  L = PetscSqrtReal(L);
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscReal x[3] = {0, 0, 0};
    if (!m->bcmask[v] || (m->goff[v] < 0 && m->gblock[v] >= 0)) continue; /* each owned vertex once (fixed ones: see below) */
    for (PetscInt d = 0; d < dim; d++) x[d] = (m->x[v * dim + d] - c[d]) / L;
    for (PetscInt d = 0; d < dim; d++) {
      PetscReal r[6] = {0, 0, 0, 0, 0, 0};
      if (!SgMeshFixed(m, v, d)) continue;
      r[d] = 1;
      if (dim == 2) r[2] = d == 0 ? -x[1] : x[0];
      else { /* e_d . (w x x) = w . (x x e_d) */
        const PetscInt d1 = (d + 1) % 3, d2 = (d + 2) % 3;
        r[3 + d1] = x[d2];
        r[3 + d2] = -x[d1];
      }
      for (PetscInt a = 0; a < nr; a++)
        for (PetscInt b = 0; b < nr; b++) G[a * nr + b] += r[a] * r[b];
    }
  }
  /* a vertex shared by ranks counts on each of them for the fully fixed ones (they have no owner in goff): only the
     rank of the null space matters, not the weights */
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, G, 36, MPIU_SCALAR, MPIU_SUM, comm));
  PetscCall(PetscBLASIntCast(nr, &n));
  PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "U", &n, G, &n, ev, work, &lwork, &info));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK syev failed: %d", (int)info);
  /* ascending eigenvalues: the ones below 1e-12 of the largest (round-off of the sums) span the free motions */
  *nfree = 0;
  for (PetscInt k = 0; k < nr; k++) {
    if (ev[k] > 1e-12 * ev[nr - 1]) break;
    for (PetscInt a = 0; a < nr; a++) modes[*nfree * nr + a] = PetscRealPart(G[k * nr + a]) * (a < dim ? 1 : 1 / L);
    (*nfree)++;
  }
  PetscFunctionReturn(0);
}
