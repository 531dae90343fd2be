/* obstacle_mesh.c: a rigid obstacle given as a triangulated surface (STL, ASCII or binary; gmsh .msh, ASCII 2.2 or
   4.1: triangles in 3D, line segments in 2D), read from -obstacle_cad_file (obstacle type cad dispatches here by the
   file's extension and content). Here the set-up, the tree and the queries; the files are read in
   obstacle_mesh_file.c, the surface is made and oriented in obstacle_mesh_surface.c.

   Orientation: outside is the side the element normals point to: a triangle (a, b, c) faces (b - a) x (c - a) (counter-
   clockwise seen from outside, STL's convention), a segment (a, b) in 2D faces (t_y, -t_x), t = b - a (the obstacle to
   the left: a counter-clockwise boundary of the obstacle). The surface may be closed or open (then the side its
   normals point to is outside, everywhere); adjacent elements must traverse their shared edge (vertex) in opposite
   directions, checked on reading.

   Queries go through an axis-aligned bounding-box tree over the elements (median split on the longest axis of the
   element centres, up to 4 elements a leaf):
   - the signed distance g (> 0 outside) and the outward normal at the closest point (distance op). The sign comes
     from the angle-weighted pseudo-normal of the closest feature (face, edge or vertex), which tells inside from
     outside for a consistently oriented surface; the normal is the face's, or on an edge or a vertex the direction
     from the closest point to x (its pseudo-normal when x lies on the surface).
   - the gap d along a unit direction n (gap op), as for the analytic obstacles: the ray x + t n meets the surface
     where it enters the obstacle (n . m < 0, m the element's normal); outside (g >= 0) the first such crossing ahead,
     inside the last one behind (d < 0); PETSC_MAX_REAL if the ray meets none. */
#include "contact/obstacle_meshimpl.h"

static PetscLogEvent MESH_SetUp, MESH_Query;

/* the coordinates (s, t) of the projection of w = p - a onto the plane of a + s e1 + t e2 (a triangle's: inside when
   s, t >= 0 and s + t <= 1) */
static void Barycentric(const double e1[3], const double e2[3], const double w[3], double *s, double *t)
{
  const double d11 = Dot(e1, e1), d12 = Dot(e1, e2), d22 = Dot(e2, e2), p1 = Dot(w, e1), p2 = Dot(w, e2);
  const double det = d11 * d22 - d12 * d12;

  *s = (d22 * p1 - d12 * p2) / det;
  *t = (d11 * p2 - d12 * p1) / det;
}

/* ------------------------------------------------------------------------------------------------ the tree */

static void ElementBox(const Obstacle_Mesh *m, PetscInt e, double lo[3], double hi[3])
{
  for (int k = 0; k < 3; k++) {
    lo[k] = PETSC_MAX_REAL;
    hi[k] = -PETSC_MAX_REAL;
  }
  for (PetscInt a = 0; a < m->nv; a++)
    for (int k = 0; k < 3; k++) {
      lo[k] = PetscMin(lo[k], Vtx(m, e, a)[k]);
      hi[k] = PetscMax(hi[k], Vtx(m, e, a)[k]);
    }
}

static PetscErrorCode BuildNode(Obstacle_Mesh *m, PetscInt id, PetscInt start, PetscInt count, KeyId *work)
{
  MeshNode *nd     = &m->node[id];
  double    clo[3] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, chi[3] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL}, pad = 1e-12 * m->len;
  int       axis = 0;
  PetscInt  half;

  PetscFunctionBeginUser;
  for (int k = 0; k < 3; k++) {
    nd->lo[k] = PETSC_MAX_REAL;
    nd->hi[k] = -PETSC_MAX_REAL;
  }
  for (PetscInt i = start; i < start + count; i++) {
    double lo[3], hi[3];
    ElementBox(m, m->perm[i], lo, hi);
    for (int k = 0; k < 3; k++) {
      nd->lo[k] = PetscMin(nd->lo[k], lo[k] - pad);
      nd->hi[k] = PetscMax(nd->hi[k], hi[k] + pad);
      clo[k]    = PetscMin(clo[k], 0.5 * (lo[k] + hi[k]));
      chi[k]    = PetscMax(chi[k], 0.5 * (lo[k] + hi[k]));
    }
  }
  if (count <= 4) {
    nd->start = start;
    nd->count = count;
    nd->left  = -1;
    PetscFunctionReturn(0);
  }
  for (int k = 1; k < 3; k++)
    if (chi[k] - clo[k] > chi[axis] - clo[axis]) axis = k;
  for (PetscInt i = 0; i < count; i++) {
    double lo[3], hi[3];
    ElementBox(m, m->perm[start + i], lo, hi);
    work[i].key = 0.5 * (lo[axis] + hi[axis]);
    work[i].id  = m->perm[start + i];
  }
  qsort(work, (size_t)count, sizeof(KeyId), CompareKeyId);
  for (PetscInt i = 0; i < count; i++) m->perm[start + i] = work[i].id;
  half      = count / 2;
  nd->count = 0;
  nd->left  = m->nnode;
  m->nnode += 2;
  PetscCall(BuildNode(m, nd->left, start, half, work));
  PetscCall(BuildNode(m, m->node[id].left + 1, start + half, count - half, work));
  PetscFunctionReturn(0);
}

static PetscErrorCode BuildTree(Obstacle_Mesh *m)
{
  KeyId *work;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(m->nel, &m->perm, 2 * m->nel + 1, &m->node));
  PetscCall(PetscMalloc1(m->nel, &work));
  for (PetscInt e = 0; e < m->nel; e++) m->perm[e] = e;
  m->nnode = 1;
  PetscCall(BuildNode(m, 0, 0, m->nel, work));
  PetscCall(PetscFree(work));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------------ queries */

typedef struct {
  double   d2;   /* squared distance */
  double   q[3]; /* the closest point */
  PetscInt e;    /* on this element */
  int      feat; /* 0: its interior; 1 + k: its edge k (3D); 4 + k: its vertex k */
} MeshClosest;

static void ClosestOnElement(const Obstacle_Mesh *m, PetscInt e, const double p[3], MeshClosest *c)
{
  const double  eps = 1e-12;
  const double *a = Vtx(m, e, 0), *b = Vtx(m, e, 1);

  c->e    = e;
  c->feat = 0;
  if (m->nv == 3) {
    const double *cc = Vtx(m, e, 2);
    double        e1[3], e2[3], w[3], s, t;
    for (int k = 0; k < 3; k++) {
      e1[k] = b[k] - a[k];
      e2[k] = cc[k] - a[k];
      w[k]  = p[k] - a[k];
    }
    Barycentric(e1, e2, w, &s, &t);
    if (s >= -eps && t >= -eps && s + t <= 1 + eps) { /* p projects onto the triangle */
      c->feat = 0;
      c->d2   = 0;
      for (int k = 0; k < 3; k++) {
        c->q[k] = a[k] + s * e1[k] + t * e2[k];
        c->d2 += PetscSqr(p[k] - c->q[k]);
      }
      return;
    }
    c->d2 = PETSC_MAX_REAL;
    for (int k = 0; k < 3; k++) { /* else the closest point lies on the boundary */
      const double *s0 = Vtx(m, e, k), *s1 = Vtx(m, e, (k + 1) % 3);
      double        u = 0, uu = 0, q[3], d2 = 0;
      for (int j = 0; j < 3; j++) {
        u += (p[j] - s0[j]) * (s1[j] - s0[j]);
        uu += PetscSqr(s1[j] - s0[j]);
      }
      u = PetscMin(1, PetscMax(0, u / uu));
      for (int j = 0; j < 3; j++) {
        q[j] = u == 1 ? s1[j] : s0[j] + u * (s1[j] - s0[j]);
        d2 += PetscSqr(p[j] - q[j]);
      }
      if (d2 < c->d2) {
        c->d2   = d2;
        c->feat = u <= 0 ? 4 + k : u >= 1 ? 4 + (k + 1) % 3
                                          : 1 + k;
        for (int j = 0; j < 3; j++) c->q[j] = q[j];
      }
    }
  } else {
    double u = 0, uu = 0;
    for (int j = 0; j < 2; j++) {
      u += (p[j] - a[j]) * (b[j] - a[j]);
      uu += PetscSqr(b[j] - a[j]);
    }
    u       = u / uu;
    c->feat = u <= 0 ? 4 : u >= 1 ? 5
                                  : 0;
    u       = PetscMin(1, PetscMax(0, u));
    c->d2   = 0;
    for (int j = 0; j < 3; j++) {
      c->q[j] = u == 1 ? b[j] : a[j] + u * (b[j] - a[j]);
      c->d2 += PetscSqr(p[j] - c->q[j]);
    }
  }
}

/* better: nearer, or as near on an element of smaller number (the tree and the brute force agree on ties) */
static PetscBool Better(const MeshClosest *c, const MeshClosest *best)
{
  return (PetscBool)(c->d2 < best->d2 || (c->d2 == best->d2 && c->e < best->e));
}

/* the squared distance from p to a tree node's bounding box (0 inside it) */
static double BoxDist2(const MeshNode *nd, const double p[3])
{
  double d2 = 0;
  for (int k = 0; k < 3; k++) d2 += PetscSqr(PetscMax(0, PetscMax(nd->lo[k] - p[k], p[k] - nd->hi[k])));
  return d2;
}

static void ClosestTree(const Obstacle_Mesh *m, const double p[3], MeshClosest *best)
{
  PetscInt stack[256], sp = 0;

  PetscMemzero(best, sizeof(*best));
  best->d2    = PETSC_MAX_REAL;
  best->e     = PETSC_MAX_INT;
  stack[sp++] = 0;
  while (sp) {
    const MeshNode *nd = &m->node[stack[--sp]];
    if (BoxDist2(nd, p) > best->d2) continue;
    if (nd->count) {
      for (PetscInt i = nd->start; i < nd->start + nd->count; i++) {
        MeshClosest c;
        ClosestOnElement(m, m->perm[i], p, &c);
        if (Better(&c, best)) *best = c;
      }
    } else if (sp + 2 <= 256) {
      const double dl = BoxDist2(&m->node[nd->left], p), dr = BoxDist2(&m->node[nd->left + 1], p);
      /* the nearer child is visited first (pushed last) */
      stack[sp++] = dl <= dr ? nd->left + 1 : nd->left;
      stack[sp++] = dl <= dr ? nd->left : nd->left + 1;
    }
  }
}

static void ClosestBrute(const Obstacle_Mesh *m, const double p[3], MeshClosest *best)
{
  PetscMemzero(best, sizeof(*best));
  best->d2 = PETSC_MAX_REAL;
  best->e  = PETSC_MAX_INT;
  for (PetscInt e = 0; e < m->nel; e++) {
    MeshClosest c;
    ClosestOnElement(m, e, p, &c);
    if (Better(&c, best)) *best = c;
  }
}

/* the signed distance (> 0 outside: on the side the pseudo-normal of the closest feature points to) and the outward
   unit normal: the face's; on an edge or a vertex the direction from the closest point to p (its pseudo-normal when
   p is on the surface) */
static void SignedDistance(const Obstacle_Mesh *m, const double p[3], const MeshClosest *c, double *g, double n[3])
{
  const double *pn;
  double        r[3], d = PetscSqrtReal(c->d2), sg, pp;

  if (c->feat == 0) pn = &m->nrm[3 * c->e];
  else if (c->feat < 4) pn = &m->enrm[3 * m->eedge[3 * c->e + c->feat - 1]];
  else pn = &m->vnrm[3 * m->el[m->nv * c->e + c->feat - 4]];
  for (int k = 0; k < 3; k++) r[k] = p[k] - c->q[k];
  sg = Dot(r, pn) < 0 ? -1 : 1;
  *g = sg * d;
  if (c->feat == 0) {
    for (int k = 0; k < 3; k++) n[k] = pn[k];
  } else if (d > 1e-8 * m->len) {
    for (int k = 0; k < 3; k++) n[k] = sg * r[k] / d;
  } else {
    pp = PetscSqrtReal(Dot(pn, pn));
    for (int k = 0; k < 3; k++) n[k] = pp > 0 ? pn[k] / pp : 0;
  }
}

/* the line x + t n enters the obstacle through element e at *t (n . m < 0, the crossing inside the element) */
static PetscBool RayHit(const Obstacle_Mesh *m, PetscInt e, const double x[3], const double n[3], double *t)
{
  const double eps = 1e-12, *mm = &m->nrm[3 * e], *a = Vtx(m, e, 0), *b = Vtx(m, e, 1);
  double       dn = Dot(n, mm), ax[3], y[3], w[3], e1[3];

  if (!(dn < -1e-12)) return PETSC_FALSE;
  for (int k = 0; k < 3; k++) ax[k] = a[k] - x[k];
  *t = Dot(ax, mm) / dn; /* the plane's crossing, as for the analytic plane */
  for (int k = 0; k < 3; k++) {
    y[k]  = x[k] + *t * n[k];
    w[k]  = y[k] - a[k];
    e1[k] = b[k] - a[k];
  }
  if (m->nv == 2) {
    double u = Dot(w, e1) / Dot(e1, e1);
    return (PetscBool)(u >= -eps && u <= 1 + eps);
  } else {
    const double *c = Vtx(m, e, 2);
    double        e2[3], s, r;
    for (int k = 0; k < 3; k++) e2[k] = c[k] - a[k];
    Barycentric(e1, e2, w, &s, &r);
    return (PetscBool)(s >= -eps && r >= -eps && s + r <= 1 + eps);
  }
}

/* outside: the first entering crossing at t >= -tol; inside: the last one at t <= tol */
static PetscBool Better_t(PetscBool inside, double t, double tol, PetscBool found, double best)
{
  if (inside ? t > tol : t < -tol) return PETSC_FALSE;
  return (PetscBool)(!found || (inside ? t > best : t < best));
}

static void RayTree(const Obstacle_Mesh *m, const double x[3], const double n[3], PetscBool inside, double tol, PetscBool *found, double *best)
{
  PetscInt stack[256], sp = 0;

  *found      = PETSC_FALSE;
  stack[sp++] = 0;
  while (sp) {
    const MeshNode *nd   = &m->node[stack[--sp]];
    double          tmin = inside ? (*found ? *best : -PETSC_MAX_REAL) : -tol, tmax = inside ? tol : (*found ? *best : PETSC_MAX_REAL);
    PetscBool       miss = PETSC_FALSE;
    for (int k = 0; k < 3 && !miss; k++) {
      if (n[k] != 0) {
        double t1 = (nd->lo[k] - x[k]) / n[k], t2 = (nd->hi[k] - x[k]) / n[k];
        tmin = PetscMax(tmin, PetscMin(t1, t2));
        tmax = PetscMin(tmax, PetscMax(t1, t2));
      } else if (x[k] < nd->lo[k] || x[k] > nd->hi[k]) miss = PETSC_TRUE;
    }
    if (miss || tmin > tmax) continue;
    if (nd->count) {
      for (PetscInt i = nd->start; i < nd->start + nd->count; i++) {
        double t;
        if (RayHit(m, m->perm[i], x, n, &t) && Better_t(inside, t, tol, *found, *best)) {
          *best  = t;
          *found = PETSC_TRUE;
        }
      }
    } else if (sp + 2 <= 256) {
      stack[sp++] = nd->left + 1;
      stack[sp++] = nd->left;
    }
  }
}

static void RayBrute(const Obstacle_Mesh *m, const double x[3], const double n[3], PetscBool inside, double tol, PetscBool *found, double *best)
{
  *found = PETSC_FALSE;
  for (PetscInt e = 0; e < m->nel; e++) {
    double t;
    if (RayHit(m, e, x, n, &t) && Better_t(inside, t, tol, *found, *best)) {
      *best  = t;
      *found = PETSC_TRUE;
    }
  }
}

/* a point of the mesh's own frame (file units) */
static void ToFile(SgObstacle o, const Obstacle_Mesh *m, const PetscReal xb[], double x[3])
{
  x[2] = 0;
  for (PetscInt k = 0; k < o->dim; k++) x[k] = (xb[k] - m->shift[k]) / m->scale;
}

/* The query behind every op: the closest element c to xb (p: xb in file coordinates), the signed distance g and the
   normal nrm there, and with nb the gap d along the ray xb + t nb; g, nrm, d, cc, p may be NULL */
static PetscErrorCode QueryClosest(SgObstacle o, PetscBool brute, const PetscReal xb[], const PetscReal nb[], PetscReal *d, PetscReal *g, PetscReal nrm[], MeshClosest *cc, double p[3])
{
  Obstacle_Mesh *m = (Obstacle_Mesh *)o->data;
  double         x[3], n[3] = {0, 0, 0}, gm, nm[3], t = 0;
  MeshClosest    c;
  PetscBool      found;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(MESH_Query, 0, 0, 0, 0));
  m->nquery++;
  ToFile(o, m, xb, x);
  if (brute) ClosestBrute(m, x, &c);
  else ClosestTree(m, x, &c);
  SignedDistance(m, x, &c, &gm, nm);
  if (g) *g = m->scale * gm;
  if (nrm)
    for (PetscInt k = 0; k < o->dim; k++) nrm[k] = nm[k];
  if (d) {
    for (PetscInt k = 0; k < o->dim; k++) n[k] = nb[k];
    if (brute) RayBrute(m, x, n, (PetscBool)(gm < 0), 1e-10 * m->len, &found, &t);
    else RayTree(m, x, n, (PetscBool)(gm < 0), 1e-10 * m->len, &found, &t);
    *d = found ? m->scale * t : PETSC_MAX_REAL;
  }
  if (cc) *cc = c;
  if (p)
    for (int k = 0; k < 3; k++) p[k] = x[k];
  PetscCall(PetscLogEventEnd(MESH_Query, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

static PetscErrorCode Query(SgObstacle o, PetscBool brute, const PetscReal xb[], const PetscReal nb[], PetscReal *d, PetscReal *g, PetscReal nrm[])
{
  PetscFunctionBeginUser;
  PetscCall(QueryClosest(o, brute, xb, nb, d, g, nrm, NULL, NULL));
  PetscFunctionReturn(0);
}

static PetscErrorCode Gap_Mesh(SgObstacle o, const PetscReal x[], const PetscReal n[], PetscReal *d)
{
  PetscFunctionBeginUser;
  PetscCall(Query(o, PETSC_FALSE, x, n, d, NULL, NULL));
  PetscFunctionReturn(0);
}

/* the closest point lies on the rim of an open surface: a boundary edge or vertex (3D), an end vertex (2D) */
static PetscBool OnBoundary(const Obstacle_Mesh *m, const MeshClosest *c)
{
  if (c->feat >= 4) return (PetscBool)(m->vbnd[m->el[m->nv * c->e + c->feat - 4]] != 0);
  if (c->feat >= 1) return (PetscBool)(m->ebnd[m->eedge[3 * c->e + c->feat - 1]] != 0);
  return PETSC_FALSE;
}

/* elements e and f share a vertex */
static PetscBool Adjacent(const Obstacle_Mesh *m, PetscInt e, PetscInt f)
{
  for (PetscInt i = 0; i < m->nv; i++)
    for (PetscInt j = 0; j < m->nv; j++)
      if (m->el[m->nv * e + i] == m->el[m->nv * f + j]) return PETSC_TRUE;
  return PETSC_FALSE;
}

/* another point of the surface as near to p as the closest one, best, (within tol), not the same point (farther
   than sep from it) and on an element that shares no vertex with best's: then the closest point is not unique (p on
   the medial axis, e.g. the centre of a triangulated sphere or of a regular polygon) and the normal is undefined.
   Neighbouring elements are left out: inside a faceted curved surface every point on the bisector of two neighbours
   has two closest points, whose normals differ by the facets' angle only (the faceting's, not the obstacle's). The
   tree pruned at the distance d + tol. */
static PetscBool SecondClosest(const Obstacle_Mesh *m, const double p[3], const MeshClosest *best, double tol, double sep, double q2[3])
{
  const double reach = PetscSqr(PetscSqrtReal(best->d2) + tol);
  PetscInt     stack[256], sp = 0;

  stack[sp++] = 0;
  while (sp) {
    const MeshNode *nd = &m->node[stack[--sp]];
    if (BoxDist2(nd, p) > reach) continue;
    if (nd->count) {
      for (PetscInt i = nd->start; i < nd->start + nd->count; i++) {
        MeshClosest c;
        double      s2 = 0;
        ClosestOnElement(m, m->perm[i], p, &c);
        if (c.d2 > reach || Adjacent(m, c.e, best->e)) continue;
        for (int k = 0; k < 3; k++) s2 += PetscSqr(c.q[k] - best->q[k]);
        if (s2 > sep * sep) {
          for (int k = 0; k < 3; k++) q2[k] = c.q[k];
          return PETSC_TRUE;
        }
      }
    } else if (sp + 2 <= 256) {
      stack[sp++] = nd->left + 1;
      stack[sp++] = nd->left;
    }
  }
  return PETSC_FALSE;
}

/* -contact_normal obstacle at a contact vertex, x in the obstacle's frame (p in the file's, c its closest element, gm
   its signed distance there in file units; Distance_Mesh): as for the analytic ball and the CAD obstacles, an error naming
   the file and the vertex where the obstacle's normal is undefined. Before, the tree's first element won: for a
   vertex at the centre of a triangulated sphere or regular polygon one facet's normal, and behind the rim of an open
   surface the rim's face decided inside and outside (a vertex there counted as deep inside, pushed sideways).
   - behind the rim: the closest point on a boundary edge or vertex of an open surface and x on its inner side (not on
     the surface itself): an open surface has no inside there;
   - two closest points (x on the medial axis) on elements that share no vertex (SecondClosest). */
static PetscErrorCode CheckClosest(SgObstacle o, const PetscReal x[], const double p[3], const MeshClosest *c, double gm)
{
  const Obstacle_Mesh *m     = (const Obstacle_Mesh *)o->data;
  PetscReal            xv[3] = {0, 0, 0}; /* the contact vertex: x moved back by the obstacle's placement */
  double               q2[3];

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < o->dim; k++) xv[k] = x[k] + o->placement * o->translation[k];
  PetscCheck(!(gm < 0 && PetscSqrtReal(c->d2) > 1e-8 * m->len && OnBoundary(m, c)), PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "-contact_normal obstacle: -obstacle_cad_file %s: the contact vertex at (%g, %g, %g) lies behind the boundary of the open surface (its closest point (%g, %g, %g), file coordinates, is on the surface's rim): an open surface has no inside there, so the sign of its distance is undefined; close the surface or extend it beyond the body", m->file, (double)xv[0], (double)xv[1], (double)(o->dim == 3 ? xv[2] : 0), c->q[0], c->q[1], c->q[2]);
  PetscCheck(!SecondClosest(m, p, c, 1e-9 * m->len, 1e-6 * m->len, q2), PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "-contact_normal obstacle: -obstacle_cad_file %s: the contact vertex at (%g, %g, %g) has two closest points on the obstacle, (%g, %g, %g) and (%g, %g, %g) (file coordinates): its normal is undefined", m->file, (double)xv[0], (double)xv[1], (double)(o->dim == 3 ? xv[2] : 0), c->q[0], c->q[1], c->q[2], q2[0], q2[1], q2[2]);
  PetscFunctionReturn(0);
}

/* -contact_normal obstacle: the plain query, then where the obstacle's normal is undefined an error naming the file and
   the contact vertex (CheckClosest), from the same closest element */
static PetscErrorCode Distance_Mesh(SgObstacle o, const PetscReal x[], PetscReal *g, PetscReal n[])
{
  const Obstacle_Mesh *m = (const Obstacle_Mesh *)o->data;
  MeshClosest          c;
  double               p[3];

  PetscFunctionBeginUser;
  PetscCall(QueryClosest(o, PETSC_FALSE, x, NULL, NULL, g, n, &c, p));
  PetscCall(CheckClosest(o, x, p, &c, *g / m->scale));
  PetscFunctionReturn(0);
}

/* The gap along n, the signed distance and the normal of a meshed obstacle, by the tree or by brute force over all
   elements (the unit test of the tree: tests/unit_tests.c), without the checks of -contact_normal obstacle. x in the
   obstacle's frame, as the ops take it. */
PetscErrorCode SgObstacleMeshQuery(SgObstacle o, PetscBool brute, const PetscReal x[], const PetscReal n[], PetscReal *d, PetscReal *g, PetscReal nrm[])
{
  PetscFunctionBeginUser;
  PetscCheck(o->gap == Gap_Mesh, o->comm, PETSC_ERR_ARG_WRONG, "SgObstacleMeshQuery: not a meshed obstacle");
  PetscCall(Query(o, brute, x, n, d, g, nrm));
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_Mesh(SgObstacle o)
{
  Obstacle_Mesh *m = (Obstacle_Mesh *)o->data;

  PetscFunctionBeginUser;
  if (!m) PetscFunctionReturn(0);
  PetscCall(PetscInfo(NULL, "meshed obstacle %s: %" PetscInt_FMT " queries\n", m->file, m->nquery));
  PetscCall(PetscFree2(m->x, m->el));
  PetscCall(PetscFree2(m->nrm, m->vnrm));
  PetscCall(PetscFree(m->eedge));
  PetscCall(PetscFree2(m->vbnd, m->ebnd));
  PetscCall(PetscFree(m->enrm));
  PetscCall(PetscFree2(m->perm, m->node));
  PetscCall(PetscFree(m->soup.v));
  PetscCall(PetscFree(o->data));
  PetscFunctionReturn(0);
}

/* The obstacle becomes the triangulated surface of the file (called by the cad type's options for a mesh file, see
   SgObstacleMeshFileIs): a file point z sits at scale z + shift. Its ops (gap, distance, destroy) and data replace
   the obstacle's; the caller has freed its own. */
PetscErrorCode SgObstacleSetUp_Mesh(SgObstacle o, const char file[], const PetscReal shift[], PetscReal scale)
{
  Obstacle_Mesh *m;
  PetscInt       nbnd = 0;
  const char    *el   = o->dim == 3 ? "triangles" : "line segments";

  PetscFunctionBeginUser;
  if (!MESH_SetUp) {
    PetscClassId cid;
    PetscCall(PetscClassIdRegister("SgObstacleMesh", &cid));
    PetscCall(PetscLogEventRegister("SgMeshObsSetUp", cid, &MESH_SetUp));
    PetscCall(PetscLogEventRegister("SgMeshObsQuery", cid, &MESH_Query));
  }
  PetscCall(PetscLogEventBegin(MESH_SetUp, 0, 0, 0, 0));
  PetscCall(PetscNew(&m));
  PetscCall(PetscStrncpy(m->file, file, sizeof(m->file)));
  for (PetscInt k = 0; k < 3; k++) m->shift[k] = k < o->dim ? shift[k] : 0;
  m->scale    = scale;
  m->nv       = o->dim;
  o->data     = m;
  o->destroy  = Destroy_Mesh;
  o->gap      = Gap_Mesh;
  o->distance = Distance_Mesh;
  PetscCall(SgObstacleMeshRead(o, file, &m->soup));
  PetscCall(SgObstacleMeshBuildSurface(o, m, &m->soup));
  PetscCall(PetscFree(m->soup.v));
  m->soup.n = m->soup.cap = 0;
  PetscCall(SgObstacleMeshOrient(o, m));
  PetscCall(BuildTree(m));
  PetscCall(PetscCalloc2(m->nvert, &m->vbnd, o->dim == 3 ? m->nedge : 0, &m->ebnd));
  if (o->dim == 3) {
    PetscInt *cnt;
    PetscCall(PetscCalloc1(m->nedge, &cnt));
    for (PetscInt i = 0; i < 3 * m->nel; i++) cnt[m->eedge[i]]++;
    for (PetscInt i = 0; i < m->nedge; i++) nbnd += m->ebnd[i] = cnt[i] == 1;
    for (PetscInt e = 0; e < m->nel; e++)
      for (PetscInt k = 0; k < 3; k++)
        if (cnt[m->eedge[3 * e + k]] == 1) m->vbnd[m->el[3 * e + k]] = m->vbnd[m->el[3 * e + (k + 1) % 3]] = 1;
    PetscCall(PetscFree(cnt));
  } else {
    for (PetscInt i = 0; i < 2 * m->nel; i++) m->vbnd[m->el[i]]++;
    for (PetscInt v = 0; v < m->nvert; v++) m->vbnd[v] = m->vbnd[v] == 1;
    nbnd = 2 * m->nvert - 2 * m->nel; /* vertices of one segment */
  }
  PetscCall(PetscInfo(NULL, "meshed obstacle %s: %" PetscInt_FMT " %s, %" PetscInt_FMT " vertices, %s surface (%" PetscInt_FMT " boundary %s), %" PetscInt_FMT " tree nodes\n", file, m->nel, el, m->nvert, nbnd ? "open" : "closed", nbnd, o->dim == 3 ? "edges" : "vertices", m->nnode));
  PetscCall(PetscLogEventEnd(MESH_SetUp, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}
