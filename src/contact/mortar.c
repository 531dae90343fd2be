/* Dual mortar integrals between a slave and a master surface (mortar.h): segment-to-segment in 2D, clipped triangles
   in 3D, projected along each slave facet's normal in the reference configuration. */
#include "contact/mortar.h"

/* An overlap below this part of the slave facet is no overlap: mesh generators place the vertices of two sides that
   end at one point 1e-12 apart (gmsh), and such a sliver would give a slave vertex a row of rounding errors. */
#define SG_MORTAR_SLIVER 1e-9

/* growing triplet list */
typedef struct {
  PetscInt   n, cap;
  PetscInt  *row, *col;
  PetscReal *val;
  PetscReal  behind; /* the current slave facet: the deepest facing overlap farther than dmax behind it (g < -dmax), or 0 */
  PetscBool  beyond; /* the current slave facet: a facing overlap farther than dmax ahead of it (g > dmax) */
} Triplets;

static PetscErrorCode TripletsAdd(Triplets *t, PetscInt r, PetscInt c, PetscReal v)
{
  PetscFunctionBeginUser;
  if (t->n == t->cap) {
    PetscInt   cap = t->cap ? 2 * t->cap : 64, *row, *col;
    PetscReal *val;
    PetscCall(PetscMalloc1(cap, &row));
    PetscCall(PetscMalloc1(cap, &col));
    PetscCall(PetscMalloc1(cap, &val));
    if (t->n) {
      PetscCall(PetscArraycpy(row, t->row, t->n));
      PetscCall(PetscArraycpy(col, t->col, t->n));
      PetscCall(PetscArraycpy(val, t->val, t->n));
    }
    PetscCall(PetscFree(t->row));
    PetscCall(PetscFree(t->col));
    PetscCall(PetscFree(t->val));
    t->row = row, t->col = col, t->val = val, t->cap = cap;
  }
  t->row[t->n] = r, t->col[t->n] = c, t->val[t->n] = v, t->n++;
  PetscFunctionReturn(0);
}

static PetscReal Dot(PetscInt dim, const PetscReal a[], const PetscReal b[])
{
  PetscReal d = 0;
  for (PetscInt c = 0; c < dim; c++) d += a[c] * b[c];
  return d;
}

/* One quadrature point of the pair (slave facet sv[], nb vertices): weight w, slave basis phi[], master basis phim[],
   distance g along the slave normal. Adds to D, g0 and the pair's block Mloc[nb * a + b]. */
static void AddPoint(PetscInt nb, const PetscInt sv[], PetscReal w, const PetscReal phi[], const PetscReal phim[], PetscReal g, PetscReal D[], PetscReal g0[], PetscReal Mloc[])
{
  for (PetscInt a = 0; a < nb; a++) {
    PetscReal psi = nb == 2 ? 2 * phi[a] - phi[1 - a] : 4 * phi[a] - 1; /* the dual basis: biorthogonal to phi */
    D[sv[a]] += w * psi;
    g0[sv[a]] += w * psi * g;
    for (PetscInt b = 0; b < nb; b++) Mloc[nb * a + b] += w * psi * phim[b];
  }
}

/* A facing master facet overlaps the slave facet farther than dmax along its normal: ahead (apart) or behind (the
   slave facet inside the master body) */
static void Beyond(Triplets *t, PetscReal g, PetscReal dmax)
{
  if (g > dmax) t->beyond = PETSC_TRUE;
  else if (g < -dmax) t->behind = PetscMin(t->behind, g);
}

/* The pair's block of M as triplets */
static PetscErrorCode AddBlock(PetscInt nb, const PetscInt sv[], const PetscInt mv[], const PetscReal Mloc[], Triplets *t)
{
  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < nb; a++)
    for (PetscInt b = 0; b < nb; b++) PetscCall(TripletsAdd(t, sv[a], mv[b], Mloc[nb * a + b]));
  PetscFunctionReturn(0);
}

/* 2D: slave segment (a, b) and master segment (p, q); the master points project orthogonally onto the slave line at
   xi = (x - a).t / L, and on the overlap the master coordinate eta is affine in xi. Two Gauss points are exact. */
static PetscErrorCode Pair2D(const SgMortarSurface *s, PetscInt f, const SgMortarSurface *m, PetscInt e, PetscReal dmax, PetscReal D[], PetscReal g0[], Triplets *t, PetscReal *area)
{
  const PetscInt  *sv = s->facets + 2 * f, *mv = m->facets + 2 * e;
  const PetscReal *a = s->x + 2 * sv[0], *b = s->x + 2 * sv[1], *p = m->x + 2 * mv[0], *q = m->x + 2 * mv[1], *n = s->nrm + 2 * f;
  PetscReal        tv[2] = {b[0] - a[0], b[1] - a[1]}, L = PetscSqrtReal(Dot(2, tv, tv)), xp, xq, lo, hi, Mloc[4] = {0, 0, 0, 0};

  PetscFunctionBeginUser;
  if (Dot(2, n, m->nrm + 2 * e) >= 0 || L == 0) PetscFunctionReturn(0); /* not facing the slave */
  tv[0] /= L, tv[1] /= L;
  xp = ((p[0] - a[0]) * tv[0] + (p[1] - a[1]) * tv[1]) / L;
  xq = ((q[0] - a[0]) * tv[0] + (q[1] - a[1]) * tv[1]) / L;
  if (PetscAbsReal(xq - xp) <= 1e-12) PetscFunctionReturn(0); /* the master segment stands along the normal */
  lo = PetscMax(0, PetscMin(xp, xq)), hi = PetscMin(1, PetscMax(xp, xq));
  if (hi - lo <= SG_MORTAR_SLIVER) PetscFunctionReturn(0); /* a point, or rounding of the mesh generator's coordinates */
  {
    /* distance along n at the overlap's centre: the far side of a closed master body is not a partner */
    PetscReal xi = 0.5 * (lo + hi), eta = (xi - xp) / (xq - xp), g = 0;
    for (PetscInt c = 0; c < 2; c++) g += (p[c] + eta * (q[c] - p[c]) - (a[c] + xi * L * tv[c])) * n[c];
    if (PetscAbsReal(g) > dmax) {
      Beyond(t, g, dmax);
      PetscFunctionReturn(0);
    }
  }
  for (PetscInt k = 0; k < 2; k++) {
    PetscReal xi = lo + (hi - lo) * 0.5 * (1 + (k ? 1 : -1) / PetscSqrtReal(3.0)), eta = (xi - xp) / (xq - xp), g = 0;
    PetscReal phi[2] = {1 - xi, xi}, phim[2] = {1 - eta, eta};
    for (PetscInt c = 0; c < 2; c++) g += (p[c] + eta * (q[c] - p[c]) - (a[c] + xi * L * tv[c])) * n[c];
    AddPoint(2, sv, 0.5 * (hi - lo) * L, phi, phim, g, D, g0, Mloc);
  }
  PetscCall(AddBlock(2, sv, mv, Mloc, t));
  *area += (hi - lo) * L;
  PetscFunctionReturn(0);
}

static PetscReal Cross2(const PetscReal o[], const PetscReal a[], const PetscReal b[])
{
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/* Barycentric coordinates of X in the plane triangle T (counter-clockwise or not: any non-degenerate one) */
static void Barycentric(const PetscReal T[3][2], const PetscReal X[2], PetscReal l[3])
{
  PetscReal A = Cross2(T[0], T[1], T[2]);
  l[0]        = Cross2(X, T[1], T[2]) / A;
  l[1]        = Cross2(T[0], X, T[2]) / A;
  l[2]        = 1 - l[0] - l[1];
}

/* Sutherland-Hodgman: the convex polygon P (np vertices, counter-clockwise) clipped by the half plane left of the
   directed edge (u, v); the result in Q (at most np + 1 vertices) */
static PetscInt ClipEdge(PetscInt np, PetscReal P[][2], const PetscReal u[], const PetscReal v[], PetscReal Q[][2])
{
  PetscInt nq = 0;
  for (PetscInt i = 0; i < np; i++) {
    const PetscReal *c = P[i], *d = P[(i + 1) % np];
    PetscReal        sc = Cross2(u, v, c), sd = Cross2(u, v, d);
    if (sc >= 0) Q[nq][0] = c[0], Q[nq][1] = c[1], nq++;
    if ((sc >= 0) != (sd >= 0)) {
      PetscReal r = sc / (sc - sd);
      Q[nq][0] = c[0] + r * (d[0] - c[0]), Q[nq][1] = c[1] + r * (d[1] - c[1]), nq++;
    }
  }
  return nq;
}

/* At the point X of the slave plane (coordinates e1, e2 from the slave facet's first vertex): the slave and master
   barycentric coordinates and the distance g from the slave point to the master triangle along the slave normal */
static void Point3D(const SgMortarSurface *s, PetscInt f, const SgMortarSurface *m, PetscInt e, const PetscReal S[3][2], const PetscReal M[3][2], const PetscReal e1[], const PetscReal e2[], const PetscReal X[], PetscReal ls[], PetscReal lm[], PetscReal *g)
{
  const PetscInt  *sv = s->facets + 3 * f, *mv = m->facets + 3 * e;
  const PetscReal *n = s->nrm + 3 * f, *a = s->x + 3 * sv[0];

  Barycentric(S, X, ls);
  Barycentric(M, X, lm);
  *g = 0;
  for (PetscInt c = 0; c < 3; c++) {
    PetscReal xs = a[c] + X[0] * e1[c] + X[1] * e2[c], xm = 0;
    for (PetscInt i = 0; i < 3; i++) xm += lm[i] * m->x[3 * mv[i] + c];
    *g += (xm - xs) * n[c];
  }
}

/* 3D: slave triangle and master triangle; both are written in the slave plane's coordinates (e1, e2, n), the master
   one by orthogonal projection; the overlap polygon is cut into triangles (a fan) and each is integrated with the
   edge-midpoint rule (exact for the degree-2 products psi_j phi^m_k and psi_j g). */
static PetscErrorCode Pair3D(const SgMortarSurface *s, PetscInt f, const SgMortarSurface *m, PetscInt e, PetscReal dmax, PetscReal D[], PetscReal g0[], Triplets *t, PetscReal *area)
{
  const PetscInt  *sv = s->facets + 3 * f, *mv = m->facets + 3 * e;
  const PetscReal *n = s->nrm + 3 * f, *a = s->x + 3 * sv[0];
  PetscReal        e1[3], e2[3], l, S[3][2], M[3][2], P[12][2], Q[12][2], A = 0, cen[2] = {0, 0}, Mloc[9] = {0};
  PetscInt         np = 3, so[3] = {0, 1, 2}, mo[3] = {0, 1, 2};

  PetscFunctionBeginUser;
  if (Dot(3, n, m->nrm + 3 * e) >= 0) PetscFunctionReturn(0);
  for (PetscInt c = 0; c < 3; c++) e1[c] = s->x[3 * sv[1] + c] - a[c];
  l = PetscSqrtReal(Dot(3, e1, e1));
  if (l == 0) PetscFunctionReturn(0);
  for (PetscInt c = 0; c < 3; c++) e1[c] /= l;
  e2[0] = n[1] * e1[2] - n[2] * e1[1], e2[1] = n[2] * e1[0] - n[0] * e1[2], e2[2] = n[0] * e1[1] - n[1] * e1[0];
  for (PetscInt i = 0; i < 3; i++) {
    PetscReal ds[3], dm[3];
    for (PetscInt c = 0; c < 3; c++) ds[c] = s->x[3 * sv[i] + c] - a[c], dm[c] = m->x[3 * mv[i] + c] - a[c];
    S[i][0] = Dot(3, ds, e1), S[i][1] = Dot(3, ds, e2);
    M[i][0] = Dot(3, dm, e1), M[i][1] = Dot(3, dm, e2);
  }
  {
    PetscReal as = Cross2(S[0], S[1], S[2]), am = Cross2(M[0], M[1], M[2]);
    if (PetscAbsReal(as) <= 1e-14 * l * l || PetscAbsReal(am) <= 1e-12 * l * l) PetscFunctionReturn(0); /* degenerate or edge-on */
    if (as < 0) so[1] = 2, so[2] = 1;                                                                   /* walk both counter-clockwise */
    if (am < 0) mo[1] = 2, mo[2] = 1;
  }
  for (PetscInt i = 0; i < 3; i++) P[i][0] = M[mo[i]][0], P[i][1] = M[mo[i]][1];
  for (PetscInt i = 0; i < 3 && np > 2; i++) {
    np = ClipEdge(np, P, S[so[i]], S[so[(i + 1) % 3]], Q);
    for (PetscInt k = 0; k < np; k++) P[k][0] = Q[k][0], P[k][1] = Q[k][1];
  }
  if (np < 3) PetscFunctionReturn(0);
  for (PetscInt k = 1; k + 1 < np; k++) A += 0.5 * Cross2(P[0], P[k], P[k + 1]);
  if (A <= SG_MORTAR_SLIVER * 0.5 * PetscAbsReal(Cross2(S[0], S[1], S[2]))) PetscFunctionReturn(0); /* an edge, a point or rounding */
  for (PetscInt k = 0; k < np; k++) cen[0] += P[k][0] / np, cen[1] += P[k][1] / np;
  {
    PetscReal ls[3], lm[3], g;
    Point3D(s, f, m, e, S, M, e1, e2, cen, ls, lm, &g);
    if (PetscAbsReal(g) > dmax) { /* the far side of a closed master body is not a partner */
      Beyond(t, g, dmax);
      PetscFunctionReturn(0);
    }
  }
  for (PetscInt k = 1; k + 1 < np; k++) {
    const PetscReal *tri[3] = {P[0], P[k], P[k + 1]};
    PetscReal        ta     = 0.5 * Cross2(P[0], P[k], P[k + 1]);
    for (PetscInt qp = 0; qp < 3; qp++) {
      PetscReal X[2] = {0.5 * (tri[qp][0] + tri[(qp + 1) % 3][0]), 0.5 * (tri[qp][1] + tri[(qp + 1) % 3][1])}, ls[3], lm[3], g;
      Point3D(s, f, m, e, S, M, e1, e2, X, ls, lm, &g);
      AddPoint(3, sv, ta / 3, ls, lm, g, D, g0, Mloc);
    }
  }
  PetscCall(AddBlock(3, sv, mv, Mloc, t));
  *area += A;
  PetscFunctionReturn(0);
}

/* A uniform grid of buckets over the master facets' bounding boxes, so that a slave facet meets only the master
   facets near it (those whose box meets its own box grown by dmax: every partner, which has a point within dmax of
   the slave facet along its normal, is among them) */
typedef struct {
  PetscInt   dim, n[3], *start, *item; /* bucket b holds item[start[b] .. start[b+1]) */
  PetscReal  lo[3], h;
  PetscReal *box;  /* per master facet: lo[dim], hi[dim] */
  PetscInt  *mark; /* per master facet: the last slave facet that took it (no duplicates) */
} Grid;

static void FacetBox(const SgMortarSurface *x, PetscInt f, PetscReal grow, PetscReal lo[], PetscReal hi[])
{
  for (PetscInt c = 0; c < x->dim; c++) lo[c] = PETSC_MAX_REAL, hi[c] = -PETSC_MAX_REAL;
  for (PetscInt i = 0; i < x->dim; i++)
    for (PetscInt c = 0; c < x->dim; c++) {
      PetscReal v = x->x[x->dim * x->facets[x->dim * f + i] + c];
      lo[c]       = PetscMin(lo[c], v - grow);
      hi[c]       = PetscMax(hi[c], v + grow);
    }
}

static void Cells(const Grid *g, const PetscReal lo[], const PetscReal hi[], PetscInt a[], PetscInt b[])
{
  for (PetscInt c = 0; c < 3; c++) a[c] = b[c] = 0;
  for (PetscInt c = 0; c < g->dim; c++) {
    /* clamped before the conversion: a box far outside the grid (or an empty master) stays a finite cell index */
    PetscReal x = PetscFloorReal((lo[c] - g->lo[c]) / g->h), y = PetscFloorReal((hi[c] - g->lo[c]) / g->h), top = (PetscReal)(g->n[c] - 1);
    a[c] = (PetscInt)PetscMin(PetscMax(x, 0), top);
    b[c] = (PetscInt)PetscMin(PetscMax(y, 0), top);
  }
}

static PetscErrorCode GridCreate(const SgMortarSurface *m, Grid *g)
{
  const PetscInt dim   = m->dim;
  PetscReal      hi[3] = {0, 0, 0}, ext = 0;
  PetscInt       nb, a[3], b[3], *cnt;

  PetscFunctionBeginUser;
  g->dim = dim;
  PetscCall(PetscMalloc2(2 * dim * m->nf + 1, &g->box, m->nf + 1, &g->mark));
  for (PetscInt c = 0; c < 3; c++) g->lo[c] = PETSC_MAX_REAL, hi[c] = -PETSC_MAX_REAL, g->n[c] = 1;
  for (PetscInt e = 0; e < m->nf; e++) {
    PetscReal *lo = g->box + 2 * dim * e, *up = lo + dim;
    FacetBox(m, e, 0, lo, up);
    g->mark[e] = -1;
    for (PetscInt c = 0; c < dim; c++) {
      g->lo[c] = PetscMin(g->lo[c], lo[c]);
      hi[c]    = PetscMax(hi[c], up[c]);
      ext      = PetscMax(ext, up[c] - lo[c]);
    }
  }
  /* buckets of the largest facet's size, at most about 8 per facet in all */
  g->h = ext > 0 ? ext : 1;
  for (;;) {
    nb = 1;
    for (PetscInt c = 0; c < dim; c++) nb *= (g->n[c] = m->nf ? (PetscInt)((hi[c] - g->lo[c]) / g->h) + 1 : 1);
    if (nb <= 8 * m->nf + 8) break;
    g->h *= 2;
  }
  PetscCall(PetscCalloc1(nb + 1, &g->start));
  PetscCall(PetscCalloc1(nb + 1, &cnt));
  for (PetscInt pass = 0; pass < 2; pass++) {
    if (pass) {
      for (PetscInt k = 0; k < nb; k++) g->start[k + 1] = g->start[k] + cnt[k], cnt[k] = 0;
      PetscCall(PetscMalloc1(g->start[nb] + 1, &g->item));
    }
    for (PetscInt e = 0; e < m->nf; e++) {
      Cells(g, g->box + 2 * dim * e, g->box + 2 * dim * e + dim, a, b);
      for (PetscInt i = a[0]; i <= b[0]; i++)
        for (PetscInt j = a[1]; j <= b[1]; j++)
          for (PetscInt k = a[2]; k <= b[2]; k++) {
            PetscInt q = (k * g->n[1] + j) * g->n[0] + i;
            if (pass) g->item[g->start[q] + cnt[q]] = e;
            cnt[q]++;
          }
    }
  }
  PetscCall(PetscFree(cnt));
  PetscFunctionReturn(0);
}

static PetscErrorCode GridDestroy(Grid *g)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree2(g->box, g->mark));
  PetscCall(PetscFree(g->start));
  PetscCall(PetscFree(g->item));
  PetscFunctionReturn(0);
}

/* The master facets in the buckets that meet the box [lo, hi], each once (stamp: a number of this query, not used
   before by another), appended to cand[*n..] */
static void GridCollect(Grid *g, const PetscReal lo[], const PetscReal hi[], PetscInt stamp, PetscBool boxes, PetscInt *n, PetscInt cand[])
{
  PetscInt a[3], b[3];

  Cells(g, lo, hi, a, b);
  for (PetscInt i = a[0]; i <= b[0]; i++)
    for (PetscInt j = a[1]; j <= b[1]; j++)
      for (PetscInt k = a[2]; k <= b[2]; k++) {
        PetscInt q = (k * g->n[1] + j) * g->n[0] + i;
        for (PetscInt r = g->start[q]; r < g->start[q + 1]; r++) {
          PetscInt         e   = g->item[r];
          const PetscReal *elo = g->box + 2 * g->dim * e, *ehi = elo + g->dim;
          PetscBool        hit = (PetscBool)(g->mark[e] != stamp);
          for (PetscInt c = 0; c < g->dim && hit && boxes; c++) hit = (PetscBool)(elo[c] <= hi[c] && ehi[c] >= lo[c]);
          if (!hit) continue;
          g->mark[e]   = stamp;
          cand[(*n)++] = e;
        }
      }
}

/* The master facets that may face slave facet f within dmax, in increasing order (the integrals add in the order of
   the full scan): those whose box meets the box of the slave facet swept along its normal n by -dmax .. dmax. A
   partner (Pair2D, Pair3D) has a point q = p + g n of the master facet with p on the slave facet and |g| <= dmax (the
   master point of the overlap's centre and the slave point it projects to along n): q lies in the swept box, and in
   the master facet's box. (The slave box grown by dmax in every direction, as before, held the same partners among
   about 300 candidates per slave facet at 40,866 unknowns of the sphere on a block, against about 25 now: 53,301 for
   2,096 slave facets.) The margin covers a normal of length 1 +- rounding and the rounding of the boxes. */
static PetscErrorCode GridQuery(Grid *g, const SgMortarSurface *s, PetscInt f, PetscReal dmax, PetscInt *n, PetscInt cand[])
{
  const PetscInt   dim = s->dim;
  const PetscReal *nrm = s->nrm + dim * f;
  PetscReal        lo[3], hi[3], ln = 0, t, pad;

  PetscFunctionBeginUser;
  *n = 0;
  FacetBox(s, f, 0, lo, hi);
  for (PetscInt c = 0; c < dim; c++) ln += nrm[c] * nrm[c];
  ln = PetscSqrtReal(ln);
  if (!(ln > 0)) PetscFunctionReturn(0); /* no normal: no partner (Pair2D, Pair3D take none) */
  t   = dmax / ln * (1 + 1e-6);
  pad = 1e-9 * (dmax + g->h);
  for (PetscInt c = 0; c < dim; c++) {
    PetscReal d = PetscAbsReal(t * nrm[c]);
    lo[c] -= d + pad, hi[c] += d + pad;
  }
  GridCollect(g, lo, hi, f, PETSC_TRUE, n, cand);
  PetscCall(PetscSortInt(*n, cand));
  PetscFunctionReturn(0);
}

/* The centre (the vertices' mean) and radius (the farthest vertex from it) of facet f of x */
static void FacetBall(const SgMortarSurface *x, PetscInt f, PetscReal c[], PetscReal *r)
{
  const PetscInt dim = x->dim;
  *r                 = 0;
  for (PetscInt k = 0; k < dim; k++) c[k] = 0;
  for (PetscInt i = 0; i < dim; i++)
    for (PetscInt k = 0; k < dim; k++) c[k] += x->x[dim * x->facets[dim * f + i] + k] / dim;
  for (PetscInt i = 0; i < dim; i++) {
    PetscReal d2 = 0;
    for (PetscInt k = 0; k < dim; k++) d2 += PetscSqr(x->x[dim * x->facets[dim * f + i] + k] - c[k]);
    *r = PetscMax(*r, PetscSqrtReal(d2));
  }
}

/* 3D: a slave facet meets only the master facets whose ball (centre cm, radius rm) reaches the line through the slave
   facet's centre cs along its unit normal n within rs + rm (rs: its radius), among the grid's candidates and in the
   full scan of a slave facet without a partner within dmax (for the report, beyond or behind dmax, mortar.h). A master facet whose projection along n
   overlaps the slave facet has a point q with q - p parallel to n for some point p of the slave facet, so the distance
   of cm from that line is at most |cm - q| + |p - cs| <= rm + rs: every facet that Pair3D could take passes (with a
   margin for rounding): the others add nothing (no overlap), the integrals add in the same order, the report is a
   maximum and a flag. This makes the scan of the facets far from the other body (most of the sphere's curved face) a few operations per master facet instead of
   Pair3D's projection and clipping: the contact set-up of the sphere on a block at 907,968 unknowns took 70.7 s of a
   245 s run before, 29.7 s of 255 s after (wall, loaded machine; bench/results.md, branch pair4). */
static PetscBool BallMeetsLine(PetscInt dim, const PetscReal cs[], PetscReal rs, const PetscReal n[], const PetscReal cm[], PetscReal rm)
{
  PetscReal d[3], t, d2 = 0, reach = 1.001 * (rs + rm);
  for (PetscInt k = 0; k < dim; k++) d[k] = cm[k] - cs[k];
  t = Dot(dim, d, n);
  for (PetscInt k = 0; k < dim; k++) d2 += PetscSqr(d[k] - t * n[k]);
  return (PetscBool)(d2 <= reach * reach);
}

/* The full scan of a slave facet without a partner within dmax (centre cs, radius rs, unit normal n): the master
   facets whose ball (ball[(dim + 1) e ..]: centre, radius; rmax the largest radius) meets the line cs + t n within
   1.001 (rs + rm) (BallMeetsLine), in increasing order: found by walking the line through the grid, at steps of a
   bucket's size h inside the master's bounding box grown by the reach, each step taking the buckets within reach + h
   of its point. A facet whose ball meets the line has its centre cm (inside the facet: in the buckets of its box)
   within reach of a point of the line and within reach + h / 2 of a step's point. Instead of every master facet: a
   few buckets' worth per step (the full scans of the sphere's facets far from the block were 1.2 million ball tests
   of the 40,866 unknowns' set-up, quadratic in the mesh size). */
static PetscErrorCode GridLine(Grid *g, const PetscReal cs[], PetscReal rs, const PetscReal n[], const PetscReal ball[], PetscReal rmax, PetscInt stamp, PetscInt *nc, PetscInt cand[])
{
  const PetscInt dim   = g->dim;
  PetscReal      reach = 1.001 * (rs + rmax) + g->h, t0 = -PETSC_MAX_REAL, t1 = PETSC_MAX_REAL, glo[3], ghi[3];
  PetscInt       ns, k = 0;

  PetscFunctionBeginUser;
  *nc = 0;
  for (PetscInt c = 0; c < dim; c++) { /* the grid's box (g->lo .. the last bucket's end) grown by the reach */
    glo[c] = g->lo[c] - reach, ghi[c] = g->lo[c] + g->n[c] * g->h + reach;
    if (n[c] != 0) {
      PetscReal a = (glo[c] - cs[c]) / n[c], b = (ghi[c] - cs[c]) / n[c];
      t0 = PetscMax(t0, PetscMin(a, b)), t1 = PetscMin(t1, PetscMax(a, b));
    } else if (cs[c] < glo[c] || cs[c] > ghi[c]) t1 = -PETSC_MAX_REAL; /* parallel to the slab, outside it */
  }
  if (!(t1 >= t0)) PetscFunctionReturn(0);
  ns = (PetscInt)PetscCeilReal((t1 - t0) / g->h) + 1;
  for (PetscInt i = 0; i <= ns; i++) {
    PetscReal t = PetscMin(t0 + i * g->h, t1), lo[3], hi[3];
    for (PetscInt c = 0; c < dim; c++) lo[c] = cs[c] + t * n[c] - reach, hi[c] = cs[c] + t * n[c] + reach;
    GridCollect(g, lo, hi, stamp, PETSC_FALSE, nc, cand);
  }
  for (PetscInt i = 0; i < *nc; i++) /* the balls that meet the line */
    if (BallMeetsLine(dim, cs, rs, n, ball + (dim + 1) * cand[i], ball[(dim + 1) * cand[i] + dim])) cand[k++] = cand[i];
  *nc = k;
  PetscCall(PetscSortInt(*nc, cand));
  PetscFunctionReturn(0);
}

PetscErrorCode SgMortarIntegrals(const SgMortarSurface *s, const SgMortarSurface *m, PetscReal dmax, PetscBool brute, PetscReal D[], PetscReal g0[], PetscInt *nM, PetscInt **Mrow, PetscInt **Mcol, PetscReal **Mval, PetscReal *area, SgMortarSearch *search)
{
  const PetscInt dim = s ? s->dim : 0;
  Triplets       t   = {0, 0, NULL, NULL, NULL, 0, PETSC_FALSE};
  SgMortarSearch sr  = {0, -1, 0};
  Grid           grid;
  PetscInt      *cand, nc;
  PetscReal     *ball = NULL, rmax = 0;            /* the master facets' balls (centre, radius: dim + 1 each), the largest radius */
  PetscInt       nnone = 0, ntried = 0, nscan = 0; /* -info: slave facets without a partner, pairs tried near and in the full scans */

  PetscFunctionBeginUser;
  PetscCheck(s && m && s->dim == m->dim && (s->dim == 2 || s->dim == 3), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "SgMortarIntegrals: the two surfaces must be given, of the same dimension 2 or 3");
  PetscCheck(dmax > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "SgMortarIntegrals: the pairing distance must be positive, not %g", (double)dmax);
  PetscCall(PetscArrayzero(D, s->nv));
  PetscCall(PetscArrayzero(g0, s->nv));
  *area = 0;
  PetscCall(GridCreate(m, &grid));
  PetscCall(PetscMalloc1(m->nf + 1, &cand));
  PetscCall(PetscMalloc1((dim + 1) * m->nf + 1, &ball));
  for (PetscInt e = 0; e < m->nf; e++) {
    FacetBall(m, e, ball + (dim + 1) * e, ball + (dim + 1) * e + dim);
    rmax = PetscMax(rmax, ball[(dim + 1) * e + dim]);
  }
  for (PetscInt f = 0; f < s->nf; f++) {
    PetscReal a0 = *area;
    PetscReal cs[3], rs = 0, n[3], ln = 0;
    t.behind = 0, t.beyond = PETSC_FALSE;
    if (brute) { /* -contact_pair_search brute: every master facet */
      for (PetscInt e = 0; e < m->nf; e++) cand[e] = e;
      nc = m->nf;
    } else PetscCall(GridQuery(&grid, s, f, dmax, &nc, cand));
    /* the slave facet's ball and unit normal for the master facets' balls (BallMeetsLine) */
    FacetBall(s, f, cs, &rs);
    ln = PetscSqrtReal(Dot(dim, s->nrm + dim * f, s->nrm + dim * f));
    for (PetscInt k = 0; k < dim; k++) n[k] = ln > 0 ? s->nrm[dim * f + k] / ln : 0;
    for (PetscInt i = 0; i < nc; i++) {
      if (dim == 2) PetscCall(Pair2D(s, f, m, cand[i], dmax, D, g0, &t, area));
      else if (ln == 0 || BallMeetsLine(3, cs, rs, n, ball + 4 * cand[i], ball[4 * cand[i] + 3])) PetscCall(Pair3D(s, f, m, cand[i], dmax, D, g0, &t, area));
    }
    ntried += nc;
    if (*area > a0) continue; /* a partner within dmax */
    /* none: the master facets along the normal's line (GridLine; every one with -contact_pair_search brute), for
       what lies farther than dmax (the report on the bodies' placement; it adds nothing to the integrals: no
       partner within dmax exists). A facet without a normal takes no partner (Pair2D, Pair3D). */
    nnone++;
    if (brute) {
      for (PetscInt e = 0; e < m->nf; e++) cand[e] = e;
      nc = m->nf;
    } else if (ln > 0) PetscCall(GridLine(&grid, cs, rs, n, ball, rmax, s->nf + f, &nc, cand));
    else nc = 0;
    nscan += nc;
    for (PetscInt i = 0; i < nc; i++) {
      if (dim == 2) PetscCall(Pair2D(s, f, m, cand[i], dmax, D, g0, &t, area));
      else if (ln == 0 || BallMeetsLine(3, cs, rs, n, ball + 4 * cand[i], ball[4 * cand[i] + 3])) PetscCall(Pair3D(s, f, m, cand[i], dmax, D, g0, &t, area));
    }
    if (t.beyond) sr.nbeyond++;
    if (-t.behind > sr.overlap) sr.overlap = -t.behind, sr.foverlap = f;
  }
  PetscCall(PetscInfo(NULL, "%" PetscInt_FMT " slave facets, %" PetscInt_FMT " master facets: %" PetscInt_FMT " pairs near, %" PetscInt_FMT " slave facets without a partner within the distance, %" PetscInt_FMT " pairs of their full scans\n", s->nf, m->nf, ntried, nnone, nscan));
  PetscCall(PetscFree(cand));
  PetscCall(PetscFree(ball));
  PetscCall(GridDestroy(&grid));
  *nM = t.n, *Mrow = t.row, *Mcol = t.col, *Mval = t.val;
  if (search) *search = sr;
  PetscFunctionReturn(0);
}
