/* rigid.c: rigid motions: those a Dirichlet part leaves free (the affine dimension of its vertices, the free motions of
   its fixed components, the refusal of a floating body) and the rigid-body modes given to the solvers. */
#include "fem/femimpl.h"
#include <petscblaslapack.h>
#include <petscsf.h>

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
  const PetscInt dim    = m->dim;
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
/* Add to the Gram matrix G the functionals of the fixed components of vertex v at x (about the centre, per length) */
static void AddFixedRows(const SgMesh *m, PetscInt v, const PetscReal x[3], PetscScalar G[])
{
  const PetscInt dim = m->dim, nr = dim == 2 ? 3 : 6;

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

/* The null space of the summed Gram matrix G (overwritten): the free motions, rotations per unit length (L) */
static PetscErrorCode GramNullModes(PetscInt dim, PetscScalar G[], PetscReal L, PetscInt *nfree, PetscReal modes[])
{
  const PetscInt nr = dim == 2 ? 3 : 6;
  PetscScalar    work[64];
  PetscReal      ev[6];
  PetscBLASInt   n, lwork = 64, info;

  PetscFunctionBeginUser;
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

PetscErrorCode SgMeshFreeRigidMotions(MPI_Comm comm, const SgMesh *m, PetscInt *nfree, PetscReal modes[], PetscReal c[3])
{
  const PetscInt dim    = m->dim;
  PetscReal      box[6] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, L = 0;
  PetscScalar    G[36] = {0};

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
    AddFixedRows(m, v, x, G);
  }
  /* a vertex shared by ranks counts on each of them for the fully fixed ones (they have no owner in goff): only the
     rank of the null space matters, not the weights */
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, G, 36, MPIU_SCALAR, MPIU_SUM, comm));
  PetscCall(GramNullModes(dim, G, L, nfree, modes));
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

/* The free rigid motions modes[] (SgMeshFreeRigidMotions' form, about c) as people picture them, "; "-separated, the
   first three */
static PetscErrorCode DescribeModes(PetscInt dim, PetscInt nfree, const PetscReal modes[], const PetscReal c[3], PetscReal diam, char what[], size_t len)
{
  const PetscInt nr = dim == 2 ? 3 : 6;

  PetscFunctionBeginUser;
  what[0] = 0;
  for (PetscInt k = 0; k < nfree && k < 3; k++) {
    const PetscReal *q    = &modes[k * nr];
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
    if (wn * PetscSqr(diam) <= 1e-16 * tn) {
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
        if (PetscAbsReal(x0[d]) < 1e-10 * diam) x0[d] = 0;
      if (dim == 2) PetscCall(PetscSNPrintf(buf, sizeof(buf), "the rotation about (%.4g, %.4g)", (double)x0[0], (double)x0[1]));
      else PetscCall(PetscSNPrintf(buf, sizeof(buf), "the rotation about the axis along (%.4g, %.4g, %.4g) through (%.4g, %.4g, %.4g)%s", (double)ax[0], (double)ax[1], (double)ax[2], (double)x0[0], (double)x0[1], (double)x0[2], PetscAbsReal(tw) > 1e-8 * PetscSqrtReal(tn * wn) ? " with a slide along it" : ""));
    }
    PetscCall(PetscStrlen(what, &l));
    PetscCall(PetscSNPrintf(what + l, len - l, "%s %s", k ? ";" : "", buf));
  }
  PetscFunctionReturn(0);
}

/* CheckRigidMotions for a Dirichlet part that fixes only some components (rollers): the rigid motions whose fixed
   components vanish at every Dirichlet vertex are free; the message names them. */
static PetscErrorCode CheckRigidMotionsPartial(SgElasticity p)
{
  const PetscInt dim = p->dim;
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
  PetscCall(DescribeModes(dim, nfree, modes, c, p->diam, what, sizeof(what)));
  SETERRQ(p->comm, PETSC_ERR_USER_INPUT, "the Dirichlet part (-dirichlet_label '%s'%s%s with -dirichlet_components) leaves %" PetscInt_FMT " rigid motion%s free:%s%s, so the stiffness is singular and the body floats. Fix more components (e.g. a roller normal to a second face), or regularize on purpose with -elasticity_rigid_shift eps (adds eps E/L^2 times the lumped volumes to K)", p->dirichlet.label, p->dirichlet.nids ? " -dirichlet_ids " : "", ids, nfree, nfree > 1 ? "s" : "", what, nfree > 3 ? " and more" : "");
}

static PetscInt FindRoot(PetscInt par[], PetscInt v)
{
  while (par[v] != v) v = par[v] = par[par[v]];
  return v;
}

/* The connected bodies of the mesh (cells joined through shared vertices), over all ranks: comp[v] in 0..ncomp-1 for
   each local vertex, the bodies ordered by their smallest global vertex number; rep[v]: v is that vertex (owned). A
   union-find on this rank's cells, then the ranks' smallest numbers exchanged at the shared vertices until no body
   label changes. */
static PetscErrorCode MeshBodies(DM dm, const SgMesh *m, PetscInt *ncomp, PetscInt comp[], PetscBool rep[])
{
  const PetscInt  nv = m->dim + 1, big = PETSC_MAX_INT;
  MPI_Comm        comm = PetscObjectComm((PetscObject)dm);
  IS              gis;
  const PetscInt *gn;
  PetscInt       *par, *lab, *a = NULL, *b = NULL, pStart, pEnd, np, nrep = 0, *reps, *all;
  PetscMPIInt     size, nr, *cnt, *dsp;
  PetscSF         sf;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(DMPlexGetVertexNumbering(dm, &gis));
  PetscCall(ISGetIndices(gis, &gn));
  PetscCall(PetscMalloc2(m->nv, &par, m->nv, &lab));
  for (PetscInt v = 0; v < m->nv; v++) par[v] = v;
  for (PetscInt c = 0; c < m->nc; c++) {
    const PetscInt r0 = FindRoot(par, m->cellv[c * nv]);
    for (PetscInt k = 1; k < nv; k++) {
      const PetscInt r = FindRoot(par, m->cellv[c * nv + k]);
      if (r != r0) par[r] = r0;
    }
  }
  for (PetscInt v = 0; v < m->nv; v++) lab[v] = big;
  for (PetscInt v = 0; v < m->nv; v++) {
    const PetscInt r = FindRoot(par, v), g = gn[v] < 0 ? -(gn[v] + 1) : gn[v];
    lab[r] = PetscMin(lab[r], g);
  }
  if (size > 1) {
    PetscCall(DMGetPointSF(dm, &sf));
    PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
    np = pEnd - pStart;
    PetscCall(PetscMalloc2(np, &a, np, &b));
    for (;;) {
      PetscInt changed = 0;
      for (PetscInt i = 0; i < np; i++) a[i] = big;
      for (PetscInt v = 0; v < m->nv; v++) a[m->vStart + v - pStart] = lab[FindRoot(par, v)];
      PetscCall(PetscArraycpy(b, a, np));
      PetscCall(PetscSFReduceBegin(sf, MPIU_INT, a, b, MPI_MIN));
      PetscCall(PetscSFReduceEnd(sf, MPIU_INT, a, b, MPI_MIN));
      PetscCall(PetscSFBcastBegin(sf, MPIU_INT, b, b, MPI_REPLACE));
      PetscCall(PetscSFBcastEnd(sf, MPIU_INT, b, b, MPI_REPLACE));
      for (PetscInt v = 0; v < m->nv; v++) {
        const PetscInt r = FindRoot(par, v), l = b[m->vStart + v - pStart];
        if (l < lab[r]) {
          lab[r] = l;
          changed++;
        }
      }
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &changed, 1, MPIU_INT, MPI_SUM, comm));
      if (!changed) break;
    }
    PetscCall(PetscFree2(a, b));
  }
  /* the bodies' numbers: the smallest vertex number of each, listed by the rank that owns that vertex */
  for (PetscInt v = 0; v < m->nv; v++) {
    rep[v] = (PetscBool)(gn[v] >= 0 && lab[FindRoot(par, v)] == gn[v]);
    if (rep[v]) nrep++;
  }
  PetscCall(PetscMalloc3(nrep + 1, &reps, size, &cnt, size + 1, &dsp));
  nrep = 0;
  for (PetscInt v = 0; v < m->nv; v++)
    if (rep[v]) reps[nrep++] = gn[v];
  PetscCall(PetscMPIIntCast(nrep, &nr));
  PetscCallMPI(MPI_Allgather(&nr, 1, MPI_INT, cnt, 1, MPI_INT, comm));
  dsp[0] = 0;
  for (PetscMPIInt r = 0; r < size; r++) dsp[r + 1] = dsp[r] + cnt[r];
  PetscCall(PetscMalloc1(dsp[size] + 1, &all));
  PetscCallMPI(MPI_Allgatherv(reps, nr, MPIU_INT, all, cnt, dsp, MPIU_INT, comm));
  *ncomp = dsp[size];
  PetscCall(PetscSortInt(*ncomp, all));
  for (PetscInt v = 0; v < m->nv; v++) PetscCall(PetscFindInt(lab[FindRoot(par, v)], *ncomp, all, &comp[v]));
  PetscCall(PetscFree(all));
  PetscCall(PetscFree3(reps, cnt, dsp));
  PetscCall(PetscFree2(par, lab));
  PetscCall(ISRestoreIndices(gis, &gn));
  PetscFunctionReturn(0);
}

/* The connected body of each local vertex (comp, m->nv entries, the caller's), numbered 0..nbodies-1 alike on every
   rank (MeshBodies: by the smallest global vertex number of each body); for checks that ask whether two boundary parts
   lie on one body (a contact pair's sides). Collective. */
PetscErrorCode SgElasticityVertexBodies(SgElasticity p, PetscInt *nbodies, PetscInt comp[])
{
  PetscBool *rep;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(p->mesh.nv + 1, &rep));
  PetscCall(MeshBodies(p->dm, &p->mesh, nbodies, comp, rep));
  PetscCall(PetscFree(rep));
  PetscFunctionReturn(0);
}

/* A mesh of several bodies (connected parts: two materials glued at an interface are one body): each must be held by
   the Dirichlet data on its own vertices, as the whole mesh is (contact does not count); the message names the first
   body that is not, by a vertex of it and its materials, and its free rigid motions. */
static PetscErrorCode CheckBodies(SgElasticity p)
{
  const SgMesh  *m   = &p->mesh;
  const PetscInt dim = p->dim, nr = dim == 2 ? 3 : 6, nv = dim + 1;
  PetscInt       ncomp = 0, *comp;
  PetscInt64    *mats; /* bit j: the body has cells of material j */
  PetscBool     *rep;
  PetscReal     *box, *xr;
  PetscScalar   *G;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(m->nv, &comp, m->nv, &rep));
  PetscCall(MeshBodies(p->dm, m, &ncomp, comp, rep));
  if (ncomp <= 1) {
    PetscCall(PetscFree2(comp, rep));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscInfo(p->dm, "%" PetscInt_FMT " bodies (connected parts of the mesh)\n", ncomp));
  PetscCall(PetscCalloc4(6 * ncomp, &box, 3 * ncomp, &xr, nr * nr * ncomp, &G, ncomp, &mats));
  for (PetscInt i = 0; i < 6 * ncomp; i++) box[i] = PETSC_MAX_REAL;
  for (PetscInt v = 0; v < m->nv; v++)
    for (PetscInt d = 0; d < dim; d++) {
      box[6 * comp[v] + d]     = PetscMin(box[6 * comp[v] + d], m->x[v * dim + d]);
      box[6 * comp[v] + 3 + d] = PetscMin(box[6 * comp[v] + 3 + d], -m->x[v * dim + d]);
      if (rep[v]) xr[3 * comp[v] + d] = m->x[v * dim + d];
    }
  for (PetscInt c = 0; c < m->nc; c++) mats[comp[m->cellv[c * nv]]] |= (PetscInt64)1 << (p->cellmat ? p->cellmat[c] : 0);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, box, 6 * ncomp, MPIU_REAL, MPIU_MIN, p->comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, xr, 3 * ncomp, MPIU_REAL, MPIU_SUM, p->comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, mats, ncomp, MPIU_INT64, MPI_BOR, p->comm));
  for (PetscInt v = 0; v < m->nv; v++) {
    const PetscReal *bx   = &box[6 * comp[v]];
    PetscReal        x[3] = {0, 0, 0}, L = 0;
    if (!m->bcmask[v] || (m->goff[v] < 0 && m->gblock[v] >= 0)) continue; /* as SgMeshFreeRigidMotions */
    for (PetscInt d = 0; d < dim; d++) L += PetscSqr(-bx[3 + d] - bx[d]);
    L = PetscSqrtReal(L);
    for (PetscInt d = 0; d < dim; d++) x[d] = (m->x[v * dim + d] - 0.5 * (bx[d] - bx[3 + d])) / L;
    AddFixedRows(m, v, x, &G[nr * nr * comp[v]]);
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, G, nr * nr * ncomp, MPIU_SCALAR, MPIU_SUM, p->comm));
  for (PetscInt k = 0; k < ncomp; k++) {
    const PetscReal *bx = &box[6 * k];
    PetscReal        modes[36], c[3] = {0, 0, 0}, L = 0;
    PetscInt         nfree;
    char             what[1024], ids[256] = "", mat[512] = "";

    for (PetscInt d = 0; d < dim; d++) {
      c[d] = 0.5 * (bx[d] - bx[3 + d]);
      L += PetscSqr(-bx[3 + d] - bx[d]);
    }
    L = PetscSqrtReal(L);
    PetscCall(GramNullModes(dim, &G[nr * nr * k], L, &nfree, modes));
    if (!nfree) continue;
    PetscCall(DescribeModes(dim, nfree, modes, c, L, what, sizeof(what)));
    PetscCall(DirichletIds(p, ids, sizeof(ids)));
    if (p->nmat > 1) {
      PetscCall(PetscSNPrintf(mat, sizeof(mat), ", of -material_label '%s' value%s", p->matlabel, (mats[k] & (mats[k] - 1)) ? "s" : ""));
      for (PetscInt j = 0, first = 1; j < p->nmat; j++)
        if (mats[k] >> j & 1) {
          size_t l;
          PetscCall(PetscStrlen(mat, &l));
          PetscCall(PetscSNPrintf(mat + l, sizeof(mat) - l, "%s %" PetscInt_FMT, first ? "" : ",", p->matids[j]));
          first = 0;
        }
    }
    {
      const PetscReal *x0 = &xr[3 * k];
      char             at[128];
      if (dim == 2) PetscCall(PetscSNPrintf(at, sizeof(at), "(%g, %g)", (double)x0[0], (double)x0[1]));
      else PetscCall(PetscSNPrintf(at, sizeof(at), "(%g, %g, %g)", (double)x0[0], (double)x0[1], (double)x0[2]));
      PetscCall(PetscFree4(box, xr, G, mats));
      PetscCall(PetscFree2(comp, rep));
      SETERRQ(p->comm, PETSC_ERR_USER_INPUT, "the mesh has %" PetscInt_FMT " separate bodies, and the Dirichlet part (-dirichlet_label '%s'%s%s) does not hold body %" PetscInt_FMT " of %" PetscInt_FMT " (the cells connected to the vertex %s%s): %" PetscInt_FMT " rigid motion%s of it %s free:%s%s, so the stiffness is singular and that body floats (contact does not hold it). Give it Dirichlet data of its own, or regularize on purpose with -elasticity_rigid_shift eps (adds eps E/L^2 times the lumped volumes to K)", ncomp, p->dirichlet.label, p->dirichlet.nids ? " -dirichlet_ids " : "", ids, k + 1, ncomp, at, mat, nfree, nfree > 1 ? "s" : "", nfree > 1 ? "are" : "is", what, nfree > 3 ? " and more" : "");
    }
  }
  PetscCall(PetscFree4(box, xr, G, mats));
  PetscCall(PetscFree2(comp, rep));
  PetscFunctionReturn(0);
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
  /* a mesh of several bodies first: the message then names the body that is not held and its own free motions, also
     when the whole mesh floats (the check of the whole mesh below named the motions left free for all bodies at once,
     fewer than the body's, and said "the body" of a mesh of two) */
  if (p->dirichlet.active && !p->rigid_shift_set) PetscCall(CheckBodies(p));
  if (p->dirichlet.ncomps) {
    PetscBool partial = PETSC_FALSE;
    for (PetscInt i = 0; i < p->dirichlet.ncomps; i++) partial = (PetscBool)(partial || p->dirichlet.comps[i] != (1 << dim) - 1);
    if (partial) {
      PetscCall(CheckRigidMotionsPartial(p));
      PetscFunctionReturn(0);
    }
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
  const SgMesh  *m   = &p->mesh;
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

/* The body of each cell as a cell field (output of a run with several bodies, e.g. a two-body contact pair): the
   connected parts of the mesh (MeshBodies) numbered 1, 2, ... in an order that does not depend on the partition: by
   the smallest value of the cell label -material_label (default "Cell Sets": gmsh's physical volumes; a cell without
   a value counts after every value) among the body's cells, then by the lowest corner of the body's bounding box
   (x first). A mesh of one physical volume per body, numbered 1..n, gets the volumes' numbers. cf: a global vector
   of the cell DM (NULL: only the count); nbodies: their number (NULL: not wanted). */
PetscErrorCode SgElasticityBodyField(SgElasticity p, Vec cf, PetscInt *nbodies)
{
  const SgMesh  *m   = &p->mesh;
  const PetscInt dim = p->dim, nv = dim + 1;
  PetscInt       ncomp, *comp, *order;
  PetscBool     *rep;
  PetscReal     *key; /* per body: smallest label value, then the bounding box's lowest corner (dim) */
  DMLabel        label = NULL;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(m->nv, &comp, m->nv, &rep));
  PetscCall(MeshBodies(p->dm, m, &ncomp, comp, rep));
  PetscCall(PetscMalloc2(4 * ncomp + 1, &key, ncomp + 1, &order));
  for (PetscInt i = 0; i < 4 * ncomp; i++) key[i] = PETSC_MAX_REAL;
  PetscCall(DMGetLabel(p->dm, p->matlabel[0] ? p->matlabel : "Cell Sets", &label));
  for (PetscInt c = 0; c < m->nc && label; c++) {
    PetscInt val;
    PetscCall(DMLabelGetValue(label, m->cStart + c, &val));
    if (val >= 0) key[4 * comp[m->cellv[c * nv]]] = PetscMin(key[4 * comp[m->cellv[c * nv]]], (PetscReal)val);
  }
  for (PetscInt v = 0; v < m->nv; v++)
    for (PetscInt d = 0; d < dim; d++) key[4 * comp[v] + 1 + d] = PetscMin(key[4 * comp[v] + 1 + d], m->x[v * dim + d]);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, key, 4 * ncomp, MPIU_REAL, MPIU_MIN, p->comm));
  /* order[k]: the body at place k (a insertion sort: a mesh has few bodies) */
  for (PetscInt k = 0; k < ncomp; k++) {
    PetscInt j = k;
    for (; j > 0; j--) {
      const PetscReal *a = &key[4 * order[j - 1]], *b = &key[4 * k];
      PetscInt         i = 0;
      while (i < 4 && a[i] == b[i]) i++;
      if (i == 4 || a[i] < b[i]) break;
      order[j] = order[j - 1];
    }
    order[j] = k;
  }
  if (cf) {
    Vec          cl;
    PetscScalar *ca;
    PetscSection cs;
    PetscInt    *place;
    PetscCall(PetscMalloc1(ncomp + 1, &place));
    for (PetscInt k = 0; k < ncomp; k++) place[order[k]] = k + 1;
    PetscCall(DMGetLocalSection(p->dmCell, &cs));
    PetscCall(DMGetLocalVector(p->dmCell, &cl));
    PetscCall(VecGetArray(cl, &ca));
    for (PetscInt c = 0; c < m->nc; c++) {
      PetscInt off;
      PetscCall(PetscSectionGetOffset(cs, m->cStart + c, &off));
      ca[off] = (PetscReal)place[comp[m->cellv[c * nv]]];
    }
    PetscCall(VecRestoreArray(cl, &ca));
    PetscCall(DMLocalToGlobal(p->dmCell, cl, INSERT_VALUES, cf));
    PetscCall(DMRestoreLocalVector(p->dmCell, &cl));
    PetscCall(PetscFree(place));
  }
  if (nbodies) *nbodies = ncomp;
  PetscCall(PetscFree2(key, order));
  PetscCall(PetscFree2(comp, rep));
  PetscFunctionReturn(0);
}
