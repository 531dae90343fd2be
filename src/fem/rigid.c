/* rigid.c: rigid motions: those a Dirichlet part leaves free (the affine dimension of its vertices, the free motions of
   its fixed components, the refusal of a floating body) and the rigid-body modes given to the solvers. */
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

/* The Dirichlet ids, comma-separated, for the messages (ids: len bytes, empty on entry) */
static PetscErrorCode DirichletIds(SgElasticity p, char ids[], size_t len)
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < p->dirichlet.nids; i++) {
    size_t l;
    PetscCall(PetscStrlen(ids, &l));
    PetscCall(PetscSNPrintf(ids + l, len - l, i ? ",%" PetscInt_FMT : "%" PetscInt_FMT, p->dirichlet.ids[i]));
  }
  PetscFunctionReturn(0);
}

/* CheckRigidMotions for a Dirichlet part that fixes only some components (rollers): the rigid motions whose fixed
   components vanish at every Dirichlet vertex are free; the message names them. */
static PetscErrorCode CheckRigidMotionsPartial(SgElasticity p)
{
  const PetscInt dim = p->dim, nr = dim == 2 ? 3 : 6;
  PetscInt       nfree;
  PetscReal      modes[36], c[3];
  char           ids[256] = "", what[1024] = "";

  PetscFunctionBeginUser;
  PetscCall(SgMeshFreeRigidMotions(p->comm, &p->mesh, &nfree, modes, c));
  if (!nfree) PetscFunctionReturn(0);
  if (p->rigid_shift_set) {
    PetscCall(PetscInfo(p->dm, "the Dirichlet part leaves %" PetscInt_FMT " rigid motions free: regularized with -elasticity_rigid_shift %g\n", nfree, (double)p->rigid_shift));
    PetscFunctionReturn(0);
  }
  PetscCall(DirichletIds(p, ids, sizeof(ids)));
  for (PetscInt k = 0; k < nfree && k < 3; k++) {
    const PetscReal *q = &modes[k * nr];
    PetscReal        t[3] = {0, 0, 0}, w[3] = {0, 0, 0}, tn = 0, wn = 0, tw = 0, x0[3], ax[3];
    size_t           l;
    char             buf[256];

    for (PetscInt d = 0; d < dim; d++) t[d] = q[d];
    if (dim == 2) w[2] = q[2];
    else
      for (PetscInt d = 0; d < 3; d++) w[d] = q[3 + d];
    for (PetscInt d = 0; d < 3; d++) {
      tn += t[d] * t[d];
      wn += w[d] * w[d];
      tw += t[d] * w[d];
    }
    /* as a motion people picture: a translation, or a rotation about an axis through x0 (with a slide along the axis
       in 3D): t + w x (x - c) = t_par + w x (x - x0), x0 = c + w x t / |w|^2 */
    if (wn * PetscSqr(p->diam) <= 1e-16 * tn) {
      tn = PetscSqrtReal(tn);
      for (PetscInt d = 0; d < 3; d++)
        if (PetscAbsReal(t[d]) < 1e-10 * tn) t[d] = 0;
      PetscCall(PetscSNPrintf(buf, sizeof(buf), dim == 2 ? "the translation along (%.4g, %.4g)" : "the translation along (%.4g, %.4g, %.4g)", (double)(t[0] / tn), (double)(t[1] / tn), (double)(t[2] / tn)));
    } else {
      x0[0] = c[0] + (w[1] * t[2] - w[2] * t[1]) / wn;
      x0[1] = c[1] + (w[2] * t[0] - w[0] * t[2]) / wn;
      x0[2] = c[2] + (w[0] * t[1] - w[1] * t[0]) / wn;
      for (PetscInt d = 0; d < 3; d++) ax[d] = w[d] / PetscSqrtReal(wn);
      for (PetscInt d = 0; d < 3; d++)
        if (PetscAbsReal(x0[d]) < 1e-10 * p->diam) x0[d] = 0;
      if (dim == 2) PetscCall(PetscSNPrintf(buf, sizeof(buf), "the rotation about (%.4g, %.4g)", (double)x0[0], (double)x0[1]));
      else PetscCall(PetscSNPrintf(buf, sizeof(buf), "the rotation about the axis along (%.4g, %.4g, %.4g) through (%.4g, %.4g, %.4g)%s", (double)ax[0], (double)ax[1], (double)ax[2], (double)x0[0], (double)x0[1], (double)x0[2], PetscAbsReal(tw) > 1e-8 * PetscSqrtReal(tn * wn) ? " with a slide along it" : ""));
    }
    PetscCall(PetscStrlen(what, &l));
    PetscCall(PetscSNPrintf(what + l, sizeof(what) - l, "%s %s", k ? ";" : "", buf));
  }
  SETERRQ(p->comm, PETSC_ERR_USER_INPUT, "the Dirichlet part (-dirichlet_label '%s'%s%s with -dirichlet_components) leaves %" PetscInt_FMT " rigid motion%s free:%s%s, so the stiffness is singular and the body floats. Fix more components (e.g. a roller normal to a second face), or regularize on purpose with -elasticity_rigid_shift eps (adds eps E/L^2 times the lumped volumes to K)", p->dirichlet.label, p->dirichlet.nids ? " -dirichlet_ids " : "", ids, nfree, nfree > 1 ? "s" : "", what, nfree > 3 ? " and more" : "");
}

/* The Dirichlet part must fix all rigid motions: otherwise K is singular and any solution is garbage. A part that fixes
   every component of 2 distinct points (2D) or 3 non-collinear points (3D) does; contact with a frictionless obstacle
   does not count (it leaves the tangential motions free). -elasticity_rigid_shift accepts such a body on purpose. */
PetscErrorCode SgElasticityCheckRigidMotions(SgElasticity p)
{
  const PetscInt dim = p->dim;
  PetscInt       adim;
  PetscReal      p0[3], dir[3];
  char           part[512], what[512], ids[256] = "";

  PetscFunctionBeginUser;
  PetscCall(SgMeshConstrainedDimension(p->comm, &p->mesh, &adim, p0, dir, &p->diam));
  /* the other extreme: a label of cells (or of every boundary part of a 1-layer mesh) leaves nothing to solve for */
  PetscCheck(p->mesh.nfree_glob > 0, p->comm, PETSC_ERR_USER_INPUT, "-dirichlet_label '%s': every vertex of the mesh is a Dirichlet vertex, nothing is left to solve for (give a label of boundary faces)", p->dirichlet.label);
  if (p->dirichlet.ncomps) {
    PetscBool partial = PETSC_FALSE;
    for (PetscInt i = 0; i < p->dirichlet.ncomps; i++) partial = (PetscBool)(partial || p->dirichlet.comps[i] != (1 << dim) - 1);
    if (partial) PetscFunctionReturn(CheckRigidMotionsPartial(p));
  }
  if (adim >= dim - 1) PetscFunctionReturn(0);
  if (p->rigid_shift_set) {
    PetscCall(PetscInfo(p->dm, "the Dirichlet part leaves rigid motions free (affine dimension %" PetscInt_FMT "): regularized with -elasticity_rigid_shift %g\n", adim, (double)p->rigid_shift));
    PetscFunctionReturn(0);
  }
  PetscCall(DirichletIds(p, ids, sizeof(ids)));
  if (!p->dirichlet.active) PetscCall(PetscSNPrintf(part, sizeof(part), "no Dirichlet part is given (-dirichlet_label/-dirichlet_ids)"));
  else PetscCall(PetscSNPrintf(part, sizeof(part), "the Dirichlet part (-dirichlet_label '%s'%s%s)", p->dirichlet.label, p->dirichlet.nids ? " -dirichlet_ids " : "", ids));
  if (adim < 0) PetscCall(PetscSNPrintf(what, sizeof(what), "%s%s", p->dirichlet.active ? " has no vertex: " : ": ", dim == 2 ? "both translations and the rotation are free" : "the three translations and the three rotations are free"));
  else if (adim == 0) {
    if (dim == 2) PetscCall(PetscSNPrintf(what, sizeof(what), " fixes the single point (%g, %g): the rotation about it is free", (double)p0[0], (double)p0[1]));
    else PetscCall(PetscSNPrintf(what, sizeof(what), " fixes the single point (%g, %g, %g): the three rotations about it are free", (double)p0[0], (double)p0[1], (double)p0[2]));
  } else PetscCall(PetscSNPrintf(what, sizeof(what), " fixes only points on the line through (%g, %g, %g) along (%.6g, %.6g, %.6g): the rotation about that line is free", (double)p0[0], (double)p0[1], (double)p0[2], (double)dir[0], (double)dir[1], (double)dir[2]));
  SETERRQ(p->comm, PETSC_ERR_USER_INPUT, "%s%s, so the stiffness is singular and the body floats. Fix every component of at least %s with -dirichlet_label/-dirichlet_ids (contact with a frictionless obstacle does not hold the body: tangential motions stay free), or regularize on purpose with -elasticity_rigid_shift eps (adds eps E/L^2 times the lumped volumes to K)", part, what, dim == 2 ? "2 distinct points" : "3 points not on one line");
}

/* The rigid-body modes from the coordinates of the free vertices: the near null space of K (attached to it unless
   -elasticity_near_null_space 0) */
PetscErrorCode SgElasticityCreateNearNullSpace(SgElasticity p)
{
  const SgMesh  *m = &p->mesh;
  const PetscInt dim = p->dim;
  Vec            xg, xloc;
  PetscScalar   *xa;

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(p->dm, &xloc));
  PetscCall(VecGetArray(xloc, &xa));
  for (PetscInt v = 0; v < m->nv; v++)
    for (PetscInt d = 0; d < dim; d++) xa[m->loff[v] + d] = m->x[v * dim + d];
  PetscCall(VecRestoreArray(xloc, &xa));
  PetscCall(VecDuplicate(p->b, &xg));
  PetscCall(DMLocalToGlobal(p->dm, xloc, INSERT_VALUES, xg));
  PetscCall(DMRestoreLocalVector(p->dm, &xloc));
  PetscCall(VecSetBlockSize(xg, dim));
  PetscCall(MatNullSpaceCreateRigidBody(xg, &p->nearnull));
  if (p->use_nearnull) PetscCall(MatSetNearNullSpace(p->K, p->nearnull));
  PetscCall(VecDestroy(&xg));
  PetscFunctionReturn(0);
}
