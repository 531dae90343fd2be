/* obstacle_mesh_surface.c: a meshed obstacle's surface from the elements as read: vertices welded, elements checked,
   normals, edges, the orientation of adjacent elements checked, pseudo-normals of edges and vertices. */
#include "contact/obstacle_meshimpl.h"

/* Vertices welded (equal coordinates are one vertex), checks, normals, edges and pseudo-normals. */
PetscErrorCode SgObstacleMeshBuildSurface(SgObstacle o, Obstacle_Mesh *m, const Soup *s)
{
  PetscInt  nv = m->nv, np = s->n * nv, dim = o->dim;
  KeyId    *key;
  double    lo[3] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, hi[3] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL};
  PetscInt *order;

  PetscFunctionBeginUser;
  m->nel = s->n;
  for (PetscInt e = 0; e < s->n; e++)
    for (PetscInt k = 0; k < 3 * nv; k++) PetscCheck(PetscIsNormalReal(s->v[3 * nv * e + k]) || s->v[3 * nv * e + k] == 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: %s %" PetscInt_FMT " has a coordinate that is not a finite number (%g)", m->file, dim == 3 ? "triangle" : "segment", e + 1, s->v[3 * nv * e + k]);
  for (PetscInt i = 0; i < np; i++)
    for (int k = 0; k < 3; k++) {
      lo[k] = PetscMin(lo[k], s->v[3 * i + k]);
      hi[k] = PetscMax(hi[k], s->v[3 * i + k]);
    }
  m->len = PetscSqrtReal(PetscSqr(hi[0] - lo[0]) + PetscSqr(hi[1] - lo[1]) + PetscSqr(hi[2] - lo[2]));
  PetscCheck(m->len > 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: all vertices coincide", m->file);
  PetscCheck(dim == 3 || PetscMax(PetscAbsReal(lo[2]), PetscAbsReal(hi[2])) <= 1e-5 * m->len, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: a 2D obstacle lies in the plane z = 0, the segments reach z in [%g, %g]", m->file, lo[2], hi[2]);
  /* weld: sort the element corners by their coordinates */
  PetscCall(PetscMalloc2(np, &order, np, &key));
  for (PetscInt i = 0; i < np; i++) order[i] = i;
  for (int k = 2; k >= 0; k--) { /* stable lexicographic sort: by x last (qsort on (key, previous rank)) */
    for (PetscInt i = 0; i < np; i++) {
      key[i].key = s->v[3 * order[i] + k];
      key[i].id  = i;
    }
    qsort(key, (size_t)np, sizeof(KeyId), CompareKeyId);
    {
      PetscInt *tmp;
      PetscCall(PetscMalloc1(np, &tmp));
      for (PetscInt i = 0; i < np; i++) tmp[i] = order[key[i].id];
      PetscCall(PetscArraycpy(order, tmp, np));
      PetscCall(PetscFree(tmp));
    }
  }
  PetscCall(PetscMalloc2(3 * np, &m->x, nv * m->nel, &m->el));
  m->nvert = 0;
  for (PetscInt i = 0; i < np; i++) {
    const double *p = &s->v[3 * order[i]];
    if (!m->nvert || p[0] != m->x[3 * (m->nvert - 1)] || p[1] != m->x[3 * (m->nvert - 1) + 1] || p[2] != m->x[3 * (m->nvert - 1) + 2]) {
      for (int k = 0; k < 3; k++) m->x[3 * m->nvert + k] = dim == 2 && k == 2 ? 0 : p[k];
      m->nvert++;
    }
    m->el[order[i]] = m->nvert - 1;
  }
  PetscCall(PetscFree2(order, key));
  /* normals; degenerate elements refused */
  PetscCall(PetscCalloc2(3 * m->nel, &m->nrm, 3 * m->nvert, &m->vnrm));
  for (PetscInt e = 0; e < m->nel; e++) {
    const double *a = Vtx(m, e, 0), *b = Vtx(m, e, 1);
    double        t1[3], c[3], nc;
    for (int k = 0; k < 3; k++) t1[k] = b[k] - a[k];
    if (dim == 3) {
      const double *cc = Vtx(m, e, 2);
      double        t2[3];
      for (int k = 0; k < 3; k++) t2[k] = cc[k] - a[k];
      SgCross3(t1, t2, c);
      nc = PetscSqrtReal(Dot(c, c));
      PetscCheck(nc > 1e-12 * (Dot(t1, t1) + Dot(t2, t2)) && m->el[3 * e] != m->el[3 * e + 1] && m->el[3 * e + 1] != m->el[3 * e + 2] && m->el[3 * e] != m->el[3 * e + 2], o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: triangle %" PetscInt_FMT " is degenerate (vertices (%g, %g, %g), (%g, %g, %g), (%g, %g, %g): no area)", m->file, e + 1, a[0], a[1], a[2], b[0], b[1], b[2], cc[0], cc[1], cc[2]);
    } else {
      c[0] = t1[1];
      c[1] = -t1[0];
      c[2] = 0;
      nc   = PetscSqrtReal(Dot(c, c));
      PetscCheck(nc > 1e-12 * m->len && m->el[2 * e] != m->el[2 * e + 1], o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: segment %" PetscInt_FMT " is degenerate (vertices (%g, %g) and (%g, %g): no length)", m->file, e + 1, a[0], a[1], b[0], b[1]);
    }
    for (int k = 0; k < 3; k++) m->nrm[3 * e + k] = c[k] / nc;
  }
  PetscFunctionReturn(0);
}

/* Adjacent elements traverse their shared edge (3D) or vertex (2D) in opposite directions; edge and vertex
   pseudo-normals. */
PetscErrorCode SgObstacleMeshOrient(SgObstacle o, Obstacle_Mesh *m)
{
  PetscInt nel = m->nel;

  PetscFunctionBeginUser;
  if (o->dim == 2) {
    PetscInt *from, *to; /* per vertex: the segment starting / ending there */
    PetscCall(PetscMalloc2(m->nvert, &from, m->nvert, &to));
    for (PetscInt v = 0; v < m->nvert; v++) from[v] = to[v] = -1;
    for (PetscInt e = 0; e < nel; e++) {
      PetscInt      a = m->el[2 * e], b = m->el[2 * e + 1], fa = from[a], tb = to[b];
      const double *x = &m->x[3 * a], *y = &m->x[3 * b];
      if (fa >= 0 || tb >= 0) PetscCall(PetscFree2(from, to));
      PetscCheck(fa < 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: segments %" PetscInt_FMT " and %" PetscInt_FMT " both start at the vertex (%g, %g): the curve is not consistently oriented (or branches); each vertex must end one segment and start the next", m->file, fa + 1, e + 1, x[0], x[1]);
      PetscCheck(tb < 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: segments %" PetscInt_FMT " and %" PetscInt_FMT " both end at the vertex (%g, %g): the curve is not consistently oriented (or branches); each vertex must end one segment and start the next", m->file, tb + 1, e + 1, y[0], y[1]);
      from[a] = e;
      to[b]   = e;
      for (int k = 0; k < 3; k++) {
        m->vnrm[3 * a + k] += m->nrm[3 * e + k];
        m->vnrm[3 * b + k] += m->nrm[3 * e + k];
      }
    }
    PetscCall(PetscFree2(from, to));
    PetscFunctionReturn(0);
  }
  {
    KeyId   *he; /* half-edges keyed by their undirected edge */
    PetscInt ne = 0;
    PetscCall(PetscMalloc1(3 * nel, &he));
    PetscCall(PetscMalloc1(3 * nel, &m->eedge));
    for (PetscInt e = 0; e < nel; e++)
      for (PetscInt k = 0; k < 3; k++) {
        PetscInt a = m->el[3 * e + k], b = m->el[3 * e + (k + 1) % 3];
        he[3 * e + k].key = (double)PetscMin(a, b) * (double)m->nvert + (double)PetscMax(a, b); /* exact below 2^53 */
        he[3 * e + k].id  = 3 * e + k;
      }
    qsort(he, (size_t)(3 * nel), sizeof(KeyId), CompareKeyId);
    for (PetscInt i = 0; i < 3 * nel;) {
      PetscInt j = i + 1;
      while (j < 3 * nel && he[j].key == he[i].key) j++;
      if (j - i >= 2) {
        PetscInt      h0 = he[i].id, h1 = he[i + 1].id, a0 = m->el[h0], a1 = m->el[h1]; /* where each half-edge starts */
        const double *x  = &m->x[3 * a0];
        PetscBool     ok = (PetscBool)(j - i == 2 && a0 != a1);
        if (!ok) {
          PetscInt h2 = j - i > 2 ? he[i + 2].id : -1;
          PetscCall(PetscFree(he));
          if (h2 >= 0) SETERRQ(o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: triangles %" PetscInt_FMT ", %" PetscInt_FMT " and %" PetscInt_FMT " share one edge (at the vertex (%g, %g, %g)): the surface is not a manifold, its outside is not defined", m->file, h0 / 3 + 1, h1 / 3 + 1, h2 / 3 + 1, x[0], x[1], x[2]);
          SETERRQ(o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: triangles %" PetscInt_FMT " and %" PetscInt_FMT " traverse their shared edge (from the vertex (%g, %g, %g)) in the same direction: the surface is not consistently oriented (adjacent triangles must run through a shared edge in opposite directions; the triangle normals point outside)", m->file, h0 / 3 + 1, h1 / 3 + 1, x[0], x[1], x[2]);
        }
      }
      for (PetscInt q = i; q < j; q++) m->eedge[he[q].id] = ne;
      ne++;
      i = j;
    }
    PetscCall(PetscFree(he));
    m->nedge = ne;
    PetscCall(PetscCalloc1(3 * ne, &m->enrm));
    for (PetscInt e = 0; e < nel; e++)
      for (PetscInt k = 0; k < 3; k++) {
        const double *p = Vtx(m, e, k), *q = Vtx(m, e, (k + 1) % 3), *r = Vtx(m, e, (k + 2) % 3);
        double        u[3], w[3], cu, ang;
        for (int c = 0; c < 3; c++) {
          m->enrm[3 * m->eedge[3 * e + k] + c] += m->nrm[3 * e + c];
          u[c] = q[c] - p[c];
          w[c] = r[c] - p[c];
        }
        cu  = Dot(u, w) / PetscSqrtReal(Dot(u, u) * Dot(w, w));
        ang = PetscAcosReal(PetscMax(-1.0, PetscMin(1.0, cu)));
        for (int c = 0; c < 3; c++) m->vnrm[3 * m->el[3 * e + k] + c] += ang * m->nrm[3 * e + c];
      }
  }
  PetscFunctionReturn(0);
}
