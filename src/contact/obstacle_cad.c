/* obstacle_cad.c: a rigid obstacle read from a CAD file by gmsh (.geo, .step, .brep), obstacle type "cad".

   The gap is the one of the analytic obstacles: d(x) = t where the ray x + t n from the boundary point x along its
   outward normal n meets the obstacle's surface, the entry point into the obstacle (negative if x already lies
   inside, PETSC_MAX_REAL if the ray misses). gmsh 4.8 projects onto a face's untrimmed surface only, and its
   parametric coordinates of OCC planes are unreliable, so a ray cannot be found from closest points alone: the faces
   (3D) or curves (2D) are tessellated once at set-up, the ray is cast against the tessellation (which face, and the
   first crossing), and the crossing is then made exact on the CAD face by Newton steps along the ray, each on the
   tangent plane at gmsh's closest point (gmshModelGetClosestPoint; exact in one step for a plane). A file with
   volumes (3D) or surfaces (2D) is a solid: a point is inside if the ray leaves it an odd number of times. */
#include "contact/contactimpl.h"
#include <gmshc.h>
#include <ctype.h>

typedef struct {
  char       file[PETSC_MAX_PATH_LEN];
  PetscReal  shift[3], scale; /* placement: a CAD point z sits at scale z + shift */
  PetscReal  msize;           /* tessellation size (CAD units) */
  PetscBool  solid;           /* volumes (3D) / surfaces (2D): inside by parity */
  PetscInt   nel;             /* tessellation: triangles (3D) or segments (2D) */
  double    *xyz;             /* their vertices, 3 coordinates each, dim vertices per element */
  int       *tag;             /* the CAD face (3D) or curve (2D) of each element */
  double     len;             /* the diagonal of the CAD model's bounding box */
  double    *dev;             /* per CAD entity tag: how far its tessellation strays from it (at element centres) */
  int        maxent;
  PetscReal *hit, *sorted, *roott; /* work: ray parameters of candidate and exact crossings and of refined ones */
  int       *hitel, *roottag;
  PetscInt   nquery, nnewton, nkept;
  double     rmax; /* the largest distance left between a refined crossing and the CAD face (CAD units) */
  double     hel;  /* the longest edge of the tessellation (0: not yet measured; -contact_normal obstacle) */
} Obstacle_CAD;

static PetscLogEvent CAD_SetUp, CAD_Gap;            /* -log_view: reading and tessellating the file; the gap queries */
static char          gmsh_file[PETSC_MAX_PATH_LEN]; /* the file gmsh's current model was read from */
static PetscBool     reset_registered = PETSC_FALSE;

static PetscErrorCode CadForget(void)
{
  PetscFunctionBeginUser;
  gmsh_file[0]     = 0;
  reset_registered = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* gmsh once per process (fem/geometry.c, shared with -dm_refine_geometry), quiet unless -obstacle_cad_verbose; the
   file read is forgotten by PetscFinalize, which finalizes gmsh */
static PetscErrorCode GmshStart(MPI_Comm comm, PetscBool verbose)
{
  PetscFunctionBeginUser;
  PetscCall(SgGmshStart(comm, verbose));
  if (!reset_registered) PetscCall(PetscRegisterFinalize(CadForget));
  reset_registered = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* gmsh's current model is the one of this obstacle's file (several CAD obstacles share one gmsh) */
static PetscErrorCode CadLoad(SgObstacle o, Obstacle_CAD *cad)
{
  int  ierr;
  char msg[512];

  PetscFunctionBeginUser;
  if (!strcmp(gmsh_file, cad->file)) PetscFunctionReturn(0);
  gmshClear(&ierr);
  gmsh_file[0] = 0;
  gmshOpen(cad->file, &ierr);
  if (ierr) SgGmshError(msg, sizeof(msg));
  PetscCheck(!ierr, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: %s", cad->file, msg);
  PetscCall(PetscStrncpy(gmsh_file, cad->file, sizeof(gmsh_file)));
  PetscFunctionReturn(0);
}

/* A mesh file (STL, gmsh's .msh, ...) by its extension: gmsh reads it as discrete entities, which have no geometry to
   project onto, so the tessellation is empty; meshed obstacles are not supported (only CAD geometry). */
static PetscErrorCode CadRefuseMeshFile(SgObstacle o, const char file[])
{
  const char *mesh[] = {"stl", "msh", "vtk", "vtu", "unv", "mesh", "bdf", "nas", "inp", "med", "cgns", "ply", "ply2", "off", "obj", "su2", "wrl", "vrml", "x3d", "p3d", "diff"};
  const char *dot = strrchr(file, '.'), *slash = strrchr(file, '/');
  char        ext[16];
  size_t      k;

  PetscFunctionBeginUser;
  if (!dot || (slash && dot < slash) || strlen(dot + 1) >= sizeof(ext)) PetscFunctionReturn(0);
  for (k = 0; dot[1 + k]; k++) ext[k] = (char)tolower((unsigned char)dot[1 + k]);
  ext[k] = 0;
  for (size_t i = 0; i < sizeof(mesh) / sizeof(mesh[0]); i++)
    PetscCheck(strcmp(ext, mesh[i]), o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: a mesh file (.%s) is not supported as the obstacle: of the mesh files only STL and gmsh .msh are read as meshed obstacles; else CAD geometry (.geo, .step, .stp, .brep, .iges) that gmsh can project onto", file, ext);
  PetscFunctionReturn(0);
}

/* gmsh's closest point c to x on the obstacle's entity tag (and its parameters, as SgGmshClosestPoint's) */
static PetscErrorCode CadClosest(SgObstacle o, const Obstacle_CAD *cad, int tag, const double x[3], double c[3], double par[2])
{
  PetscBool found;

  PetscFunctionBeginUser;
  PetscCall(SgGmshClosestPoint((int)o->dim - 1, tag, x, c, par, &found));
  PetscCheck(found, o->comm, PETSC_ERR_LIB, "-obstacle_cad_file %s: gmsh found no closest point on entity %d", cad->file, tag);
  PetscFunctionReturn(0);
}

/* The file read, checked and tessellated; errors name the option and the file. */
static PetscErrorCode CadSetUp(SgObstacle o, Obstacle_CAD *cad)
{
  PetscInt dim = o->dim, sdim = dim - 1, nv = dim; /* the obstacle's boundary: faces in 3D, curves in 2D */
  int     *ents = NULL, *vols = NULL, ierr;
  size_t   nents, nvols, *ntags = NULL, nntags, maxtag = 0;
  double  *ncoord = NULL, *npar = NULL, lo[3], hi[3];
  size_t   nncoord, nnpar, *index = NULL;
  char     msg[512];

  PetscFunctionBeginUser;
  PetscCall(CadLoad(o, cad));
  gmshModelGetEntities(&ents, &nents, (int)sdim, &ierr);
  gmshModelGetEntities(&vols, &nvols, (int)dim, &ierr);
  cad->solid = nvols > 0 ? PETSC_TRUE : PETSC_FALSE;
  if (vols) gmshFree(vols);
  /* a model of discrete entities (a mesh merged by a .geo, or a mesh file under another name) has no geometry */
  for (size_t k = 0; k < nents; k += 2) {
    char     *type = NULL;
    PetscBool discrete;
    gmshModelGetType(ents[k], ents[k + 1], &type, &ierr);
    discrete = (PetscBool)(!ierr && type && strstr(type, "Discrete"));
    if (type) gmshFree(type);
    if (discrete) {
      gmshFree(ents);
      SETERRQ(o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: gmsh reads it as a mesh (discrete %s), not as CAD geometry: give a meshed obstacle as the STL or .msh file itself, or CAD geometry (.geo, .step, .stp, .brep, .iges) that gmsh can project onto", cad->file, dim == 3 ? "surfaces" : "curves");
    }
  }
  if (!nents) {
    if (ents) gmshFree(ents);
    SETERRQ(o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: the file has no %s: a %" PetscInt_FMT "D obstacle is bounded by %s", cad->file, dim == 3 ? "surfaces" : "curves", dim, dim == 3 ? "surfaces" : "curves in the plane z = 0");
  }
  gmshModelGetBoundingBox(-1, -1, &lo[0], &lo[1], &lo[2], &hi[0], &hi[1], &hi[2], &ierr);
  cad->len = PetscSqrtReal(PetscSqr(hi[0] - lo[0]) + PetscSqr(hi[1] - lo[1]) + PetscSqr(hi[2] - lo[2]));
  PetscCheck(!ierr && cad->len > 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: the model has an empty bounding box", cad->file);
  PetscCheck(dim == 3 || PetscMax(PetscAbsReal(lo[2]), PetscAbsReal(hi[2])) <= 1e-5 * cad->len, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: a 2D obstacle lies in the plane z = 0, the model reaches z in [%g, %g]", cad->file, lo[2], hi[2]);
  /* the tessellation: fine on curved parts (elements per 2 pi), at most msize */
  if (cad->msize <= 0) cad->msize = cad->len / 20;
  gmshOptionSetNumber("Mesh.MeshSizeMax", cad->msize, &ierr);
  gmshOptionSetNumber("Mesh.MeshSizeFromCurvature", 36, &ierr);
  gmshModelMeshClear(NULL, 0, &ierr);
  gmshModelMeshGenerate((int)sdim, &ierr);
  if (ierr) SgGmshError(msg, sizeof(msg));
  PetscCheck(!ierr, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: gmsh could not tessellate the obstacle's %s: %s", cad->file, dim == 3 ? "surfaces" : "curves", msg);
  gmshModelMeshGetNodes(&ntags, &nntags, &ncoord, &nncoord, &npar, &nnpar, -1, -1, 0, 0, &ierr);
  PetscCheck(!ierr, o->comm, PETSC_ERR_LIB, "-obstacle_cad_file %s: gmsh gave no nodes", cad->file);
  for (size_t i = 0; i < nntags; i++) maxtag = PetscMax(maxtag, ntags[i]);
  PetscCall(PetscMalloc1(maxtag + 1, &index));
  for (size_t i = 0; i < nntags; i++) index[ntags[i]] = i;
  /* count, then copy, the elements of every face / curve */
  cad->nel = 0;
  for (int pass = 0; pass < 2; pass++) {
    PetscInt e = 0;
    for (size_t k = 0; k < nents; k += 2) {
      size_t *etags = NULL, netags, *enodes = NULL, nenodes;
      gmshModelMeshGetElementsByType(dim == 3 ? 2 : 1, &etags, &netags, &enodes, &nenodes, ents[k + 1], 0, 1, &ierr);
      PetscCheck(!ierr, o->comm, PETSC_ERR_LIB, "-obstacle_cad_file %s: gmsh gave no elements", cad->file);
      if (pass == 1) {
        for (size_t j = 0; j < netags; j++, e++) {
          cad->tag[e] = ents[k + 1];
          for (PetscInt a = 0; a < nv; a++)
            for (PetscInt q = 0; q < 3; q++) cad->xyz[(e * nv + a) * 3 + q] = ncoord[3 * index[enodes[j * nv + a]] + q];
        }
      } else cad->nel += (PetscInt)netags;
      if (etags) gmshFree(etags);
      if (enodes) gmshFree(enodes);
    }
    if (pass == 0) PetscCall(PetscMalloc7(cad->nel * nv * 3, &cad->xyz, cad->nel, &cad->tag, cad->nel, &cad->hit, cad->nel, &cad->sorted, cad->nel, &cad->hitel, cad->nel, &cad->roott, cad->nel, &cad->roottag));
  }
  PetscCall(PetscFree(index));
  /* how far each entity's tessellation strays from it: the distance of its element centres to the CAD entity */
  cad->maxent = 0;
  for (size_t k = 0; k < nents; k += 2) cad->maxent = PetscMax(cad->maxent, ents[k + 1]);
  PetscCall(PetscCalloc1(cad->maxent + 1, &cad->dev));
  for (PetscInt e = 0; e < cad->nel; e++) {
    double g[3] = {0, 0, 0}, c[3], r = 0;
    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt q = 0; q < 3; q++) g[q] += cad->xyz[(e * nv + a) * 3 + q] / nv;
    PetscCall(CadClosest(o, cad, cad->tag[e], g, c, NULL));
    for (PetscInt q = 0; q < 3; q++) r += PetscSqr(g[q] - c[q]);
    cad->dev[cad->tag[e]] = PetscMax(cad->dev[cad->tag[e]], PetscSqrtReal(r));
  }
  gmshFree(ntags);
  gmshFree(ncoord);
  if (npar) gmshFree(npar);
  gmshFree(ents);
  PetscCheck(cad->nel > 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: gmsh made no %s of the obstacle's %s", cad->file, dim == 3 ? "triangles" : "segments", dim == 3 ? "surfaces" : "curves");
  PetscCall(PetscInfo(NULL, "CAD obstacle %s: %" PetscInt_FMT " %s (size %g), %s\n", cad->file, cad->nel, dim == 3 ? "triangles" : "segments", (double)cad->msize, cad->solid ? "solid" : "sheet"));
  PetscFunctionReturn(0);
}

/* The line x + t n against the plane of element v: *t, and how far outside the element the crossing lies
   (*out <= 0: inside; in barycentric units); PETSC_FALSE if the line is parallel to the element. */
static PetscBool RayElement(PetscInt dim, const double *v, const double x[], const double n[], double *t, double *out)
{
  if (dim == 2) {
    double e0 = v[3] - v[0], e1 = v[4] - v[1], w0 = v[0] - x[0], w1 = v[1] - x[1];
    double det = e0 * n[1] - n[0] * e1, u;
    if (PetscAbsReal(det) <= 1e-14 * (PetscAbsReal(e0) + PetscAbsReal(e1))) return PETSC_FALSE;
    u    = (n[0] * w1 - n[1] * w0) / det;
    *t   = (e0 * w1 - w0 * e1) / det;
    *out = PetscMax(-u, u - 1);
    return PETSC_TRUE;
  } else {
    double e1[3], e2[3], p[3], s[3], q[3], det = 0, u = 0, w = 0, tt = 0, h = 0;
    for (int k = 0; k < 3; k++) {
      e1[k] = v[3 + k] - v[k];
      e2[k] = v[6 + k] - v[k];
      s[k]  = x[k] - v[k];
    }
    SgCross3(n, e2, p);
    for (int k = 0; k < 3; k++) {
      det += e1[k] * p[k];
      h += e1[k] * e1[k] + e2[k] * e2[k];
    }
    if (PetscAbsReal(det) <= 1e-14 * h) return PETSC_FALSE;
    SgCross3(s, e1, q);
    for (int k = 0; k < 3; k++) {
      u += s[k] * p[k];
      w += n[k] * q[k];
      tt += e2[k] * q[k];
    }
    u /= det;
    w /= det;
    *t   = tt / det;
    *out = PetscMax(PetscMax(-u, -w), u + w - 1);
    return PETSC_TRUE;
  }
}

/* the closest point q to p on the segment [a, b] */
static void ClosestSegment(const double p[3], const double a[3], const double b[3], double q[3])
{
  double ab = 0, ap = 0, s;
  for (int k = 0; k < 3; k++) {
    ab += (b[k] - a[k]) * (b[k] - a[k]);
    ap += (p[k] - a[k]) * (b[k] - a[k]);
  }
  s = ab > 0 ? PetscMin(1, PetscMax(0, ap / ab)) : 0;
  for (int k = 0; k < 3; k++) q[k] = a[k] + s * (b[k] - a[k]);
}

static double Dist3(const double a[3], const double b[3])
{
  return PetscSqrtReal(PetscSqr(a[0] - b[0]) + PetscSqr(a[1] - b[1]) + PetscSqr(a[2] - b[2]));
}

/* the closest point q to p on the element v (a segment in 2D, a triangle in 3D: its plane's if p projects inside,
   else the nearest of its edges') */
static void ClosestElement(PetscInt dim, const double *v, const double p[3], double q[3])
{
  double e1[3], e2[3], m[3], mm = 0, h = 0, best = PETSC_MAX_REAL, qe[3];
  if (dim == 2) {
    ClosestSegment(p, v, v + 3, q);
    return;
  }
  for (int k = 0; k < 3; k++) {
    e1[k] = v[3 + k] - v[k];
    e2[k] = v[6 + k] - v[k];
  }
  SgCross3(e1, e2, m);
  for (int k = 0; k < 3; k++) {
    mm += m[k] * m[k];
    h += (p[k] - v[k]) * m[k];
  }
  if (mm > 0) {
    PetscBool in = PETSC_TRUE;
    for (int k = 0; k < 3; k++) q[k] = p[k] - h / mm * m[k];
    for (int e = 0; e < 3 && in; e++) { /* q on the inner side of the three edges */
      const double *s0 = v + 3 * e, *s1 = v + 3 * ((e + 1) % 3);
      double        w[3], g[3], side = 0;
      for (int k = 0; k < 3; k++) w[k] = q[k] - s0[k];
      g[0] = (s1[1] - s0[1]) * w[2] - (s1[2] - s0[2]) * w[1];
      g[1] = (s1[2] - s0[2]) * w[0] - (s1[0] - s0[0]) * w[2];
      g[2] = (s1[0] - s0[0]) * w[1] - (s1[1] - s0[1]) * w[0];
      for (int k = 0; k < 3; k++) side += g[k] * m[k];
      if (side < 0) in = PETSC_FALSE;
    }
    if (in) return;
  }
  for (int e = 0; e < 3; e++) {
    double d;
    ClosestSegment(p, v + 3 * e, v + 3 * ((e + 1) % 3), qe);
    d = Dist3(p, qe);
    if (d < best) {
      best = d;
      for (int k = 0; k < 3; k++) q[k] = qe[k];
    }
  }
}

/* distance from p to the tessellation of the CAD entity tag */
static double DistTessellation(Obstacle_CAD *cad, PetscInt dim, int tag, const double p[3])
{
  double dmin = PETSC_MAX_REAL;
  for (PetscInt e = 0; e < cad->nel; e++) {
    double q[3];
    if (cad->tag[e] != tag) continue;
    ClosestElement(dim, &cad->xyz[e * dim * 3], p, q);
    dmin = PetscMin(dmin, Dist3(p, q));
  }
  return dmin;
}

static int CompareHits(const void *a, const void *b)
{
  PetscReal x = *(const PetscReal *)a, y = *(const PetscReal *)b;
  return x < y ? -1 : x > y;
}

/* The crossing t0 on the entity tag made exact. f(t) = +-|y - c| (y = x + t n, c gmsh's closest point on the face;
   + once y is beyond the face seen along n) has its root at the crossing and the slope |n.(y - c)|/|y - c|:
   Newton's step is the ray's meeting with the tangent plane at c (exact in one step for a plane), kept inside the
   bracket of the root found so far, bisection otherwise (rays nearly tangent to the face). Stops at the accuracy of
   gmsh's projection (its closest point comes no nearer in 3 steps). */
static PetscErrorCode Refine(SgObstacle o, Obstacle_CAD *cad, int tag, const double x[], const double n[], double *t, double *rfinal)
{
  int    stall = 0;
  double t0 = *t, tt = t0, tbest = t0, rbest = PETSC_MAX_REAL, a = -PETSC_MAX_REAL, b = PETSC_MAX_REAL;

  PetscFunctionBeginUser;
  for (int it = 0; it < 60; it++) {
    double y[3], c[3], r = 0, rn = 0, tn;
    for (int k = 0; k < 3; k++) y[k] = x[k] + tt * n[k];
    PetscCall(CadClosest(o, cad, tag, y, c, NULL));
    for (int k = 0; k < 3; k++) {
      r += PetscSqr(y[k] - c[k]);
      rn += (y[k] - c[k]) * n[k];
    }
    r = PetscSqrtReal(r);
    cad->nnewton++;
    if (r < 0.5 * rbest) stall = 0;
    else if (++stall >= 3) break;
    if (r < rbest) {
      tbest = tt;
      rbest = r;
    }
    if (r <= 1e-14 * cad->len) break;
    if (rn > 0) b = PetscMin(b, tt);
    else a = PetscMax(a, tt);
    tn = PetscAbsReal(rn) > 1e-6 * r ? tt - r * r / rn : PETSC_MAX_REAL;
    if (tn > a && tn < b) tt = tn;
    else if (a > -PETSC_MAX_REAL && b < PETSC_MAX_REAL) tt = 0.5 * (a + b);
    else break; /* no bracket and no Newton step: keep the best so far */
    if (b - a <= 1e-14 * cad->len) break;
  }
  *t      = tbest;
  *rfinal = rbest;
  PetscFunctionReturn(0);
}

static PetscErrorCode Gap_CAD(SgObstacle o, const PetscReal xb[], const PetscReal nb[], PetscReal *d)
{
  Obstacle_CAD *cad = (Obstacle_CAD *)o->data;
  PetscInt      dim = o->dim, ncand = 0, nexact = 0, nroot = 0, near = -1;
  double        x[3] = {0, 0, 0}, n[3] = {0, 0, 0}, t, out, tol = 1e-9 * cad->len, best = 0, texact = 0, tnear = 0;
  PetscBool     inside = PETSC_FALSE, found = PETSC_FALSE, fexact = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(CAD_Gap, 0, 0, 0, 0));
  PetscCall(CadLoad(o, cad));
  cad->nquery++;
  for (PetscInt k = 0; k < dim; k++) {
    x[k] = (xb[k] - cad->shift[k]) / cad->scale;
    n[k] = nb[k];
  }
  /* crossings with the tessellation (exact), and the elements the line passes close to (candidates: near an edge of
     a curved face its tessellation misses a sliver of it) */
  for (PetscInt e = 0; e < cad->nel; e++) {
    if (!RayElement(dim, &cad->xyz[e * dim * 3], x, n, &t, &out) || out > 0.25) continue;
    cad->hit[ncand]   = t;
    cad->hitel[ncand] = (int)e;
    ncand++;
    if (out <= 1e-9) {
      if (near < 0 || PetscAbsReal(t) < PetscAbsReal(tnear)) {
        near  = e;
        tnear = t;
      }
      cad->sorted[nexact++] = t;
    }
  }
  if (cad->solid) { /* inside if the ray leaves the solid an odd number of times (one count per distinct crossing) */
    PetscReal *ts   = cad->sorted;
    PetscInt   nout = 0;
    qsort(ts, (size_t)nexact, sizeof(PetscReal), CompareHits);
    for (PetscInt i = 0; i < nexact; i++)
      if (ts[i] > tol && (i == 0 || ts[i] - ts[i - 1] > tol)) nout++;
    inside = nout % 2 ? PETSC_TRUE : PETSC_FALSE;
    /* a vertex nearer to a curved face than the tessellation's distance to it may lie on the other side of the
       tessellation than of the face: then the nearest crossing, made exact, moves across the vertex */
    if (near >= 0 && PetscAbsReal(tnear) <= 4 * cad->dev[cad->tag[near]] + tol) {
      double tx = tnear, r;
      PetscCall(Refine(o, cad, cad->tag[near], x, n, &tx, &r));
      if (r <= 1e-8 * cad->len && (tnear > tol) != (tx > tol)) inside = inside ? PETSC_FALSE : PETSC_TRUE;
    }
  }
  /* outside: the first crossing ahead; inside: the last one behind (where the ray entered) */
  for (PetscInt i = 0; i < nexact; i++) {
    t = cad->sorted[i];
    if (inside ? t > tol : t < -tol) continue;
    if (!fexact || (inside ? t > texact : t < texact)) texact = t;
    fexact = PETSC_TRUE;
  }
  /* each candidate made exact on its CAD entity (once per crossing), kept if it lies on the entity's tessellated,
     trimmed part (within the tessellation's own distance to it) */
  for (PetscInt i = 0; i < ncand; i++) {
    int       tag   = cad->tag[cad->hitel[i]];
    double    slack = 4 * cad->dev[tag] + tol, r, y[3];
    PetscBool seen  = PETSC_FALSE;
    t               = cad->hit[i];
    if (inside ? t > slack : t < -slack) continue;
    for (PetscInt j = 0; j < nroot && !seen; j++) seen = (PetscBool)(cad->roottag[j] == tag && PetscAbsReal(cad->roott[j] - t) <= slack);
    if (seen) continue;
    PetscCall(Refine(o, cad, tag, x, n, &t, &r));
    cad->roott[nroot]   = t;
    cad->roottag[nroot] = tag;
    nroot++;
    if (r > 1e-8 * cad->len || (inside ? t > tol : t < -tol)) continue;
    for (PetscInt k = 0; k < 3; k++) y[k] = x[k] + t * n[k];
    if (DistTessellation(cad, dim, tag, y) > slack) continue;
    if (!found || (inside ? t > best : t < best)) best = t;
    cad->rmax = PetscMax(cad->rmax, r);
    found     = PETSC_TRUE;
  }
  if (!found && fexact) { /* no candidate made exact: the tessellation's crossing */
    best  = texact;
    found = PETSC_TRUE;
    cad->nkept++;
  }
  *d = found ? cad->scale * best : PETSC_MAX_REAL;
  PetscCall(PetscLogEventEnd(CAD_Gap, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* ---- the signed distance (-contact_normal obstacle) */

/* whether x lies inside the solid: the parity of the distinct crossings of the tessellation by a ray from x, in two
   generic directions (a third decides when they disagree: a ray through an edge of the tessellation) */
static PetscBool InsideSolid(Obstacle_CAD *cad, PetscInt dim, const double x[3])
{
  const double dirs[3][3] = {
      { 0.5236,  0.6471,  0.5539},
      {-0.6133,  0.2719, -0.7417},
      { 0.3013, -0.8429,  0.4458}
  };
  const double dirs2[3][3] = {
      { 0.8316,  0.5554, 0},
      {-0.4226,  0.9063, 0},
      {-0.7071, -0.7071, 0}
  };
  double tol  = 1e-9 * cad->len, t, out;
  int    vote = 0;

  for (int r = 0; r < 3; r++) {
    double     n[3];
    PetscInt   nh = 0, nout = 0;
    PetscReal *ts = cad->sorted;
    for (int k = 0; k < 3; k++) n[k] = dim == 3 ? dirs[r][k] : dirs2[r][k];
    if (dim == 3) {
      double l = PetscSqrtReal(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      for (int k = 0; k < 3; k++) n[k] /= l;
    }
    for (PetscInt e = 0; e < cad->nel; e++)
      if (RayElement(dim, &cad->xyz[e * dim * 3], x, n, &t, &out) && out <= 1e-9 && t > tol) ts[nh++] = t;
    qsort(ts, (size_t)nh, sizeof(PetscReal), CompareHits);
    for (PetscInt i = 0; i < nh; i++)
      if (i == 0 || ts[i] - ts[i - 1] > tol) nout++;
    vote += nout % 2;
    if (r == 1 && vote != 1) break; /* the two agree */
  }
  return vote >= 2 ? PETSC_TRUE : PETSC_FALSE;
}

/* The signed distance: the closest point of the tessellation, made exact on the CAD entities that come near it (gmsh's
   closest point on an entity, kept if it lies on the entity's tessellated, trimmed part); where none is kept (an
   edge or corner of the obstacle, straight in the tessellation) the tessellation's point. Away from the surface the
   normal is x - z (sign from the solid's inside), on it the entity's own normal, oriented by the inside just
   outside of it. A sheet (no volume) has no inside: a vertex on it has no normal, an error. Two closest points as
   near but apart: the normal is undefined, an error. */
/* The closest point z of the obstacle to x (CAD units, xb the vertex in the mesh's units for the messages) at the
   distance h: the tessellation's, made exact on the CAD entities that come near it (gmsh's closest point on an
   entity, kept if it lies on its tessellated, trimmed part); where none is kept (an edge or corner of the obstacle,
   straight in the tessellation) the tessellation's point (*btag = -1). Two entities' closest points as near but apart:
   an error. */
static PetscErrorCode ClosestCAD(SgObstacle o, Obstacle_CAD *cad, double x[3], const PetscReal xb[], double z[3], double *h, int *btag_, double bpar[2])
{
  PetscInt  dim  = o->dim;
  int       btag = -1, ntag = 0, tags[64];
  double    q[3], zt[3] = {0, 0, 0}, dbest = PETSC_MAX_REAL, dt = PETSC_MAX_REAL, tol = 1e-9 * cad->len, z2[3] = {0, 0, 0}, d2 = PETSC_MAX_REAL;
  PetscBool found = PETSC_FALSE;

  PetscFunctionBeginUser;
  for (PetscInt e = 0; e < cad->nel; e++) { /* the tessellation's closest point */
    double d;
    ClosestElement(dim, &cad->xyz[e * dim * 3], x, q);
    d = Dist3(x, q);
    if (d < dt) {
      dt = d;
      for (int k = 0; k < 3; k++) zt[k] = q[k];
    }
  }
  for (PetscInt e = 0; e < cad->nel && ntag < 64; e++) { /* the entities near it */
    int       tag  = cad->tag[e];
    PetscBool seen = PETSC_FALSE;
    ClosestElement(dim, &cad->xyz[e * dim * 3], x, q);
    if (Dist3(x, q) > dt + 8 * cad->dev[tag] + tol) continue;
    for (int j = 0; j < ntag && !seen; j++) seen = (PetscBool)(tags[j] == tag);
    if (!seen) tags[ntag++] = tag;
  }
  for (int j = 0; j < ntag; j++) {               /* each made exact on its CAD entity */
    double d, y[3], par[2] = {bpar[0], bpar[1]}; /* gmsh's count of parameters: the rest kept */
    PetscCall(CadClosest(o, cad, tags[j], x, y, par));
    cad->nnewton++;
    d = Dist3(x, y);
    if (DistTessellation(cad, dim, tags[j], y) <= 4 * cad->dev[tags[j]] + tol) {
      if (d < dbest) {
        if (found) {
          d2 = dbest;
          for (int k = 0; k < 3; k++) z2[k] = z[k];
        }
        dbest = d;
        btag  = tags[j];
        for (int k = 0; k < 3; k++) z[k] = y[k];
        for (int k = 0; k < 2; k++) bpar[k] = par[k];
        found = PETSC_TRUE;
      } else if (d < d2) {
        d2 = d;
        for (int k = 0; k < 3; k++) z2[k] = y[k];
      }
    }
  }
  if (!found || dbest > dt + 4 * cad->dev[btag] + tol) { /* an edge or corner: the tessellation's point */
    btag  = -1;
    dbest = dt;
    for (int k = 0; k < 3; k++) z[k] = zt[k];
  }
  PetscCheck(btag < 0 || !(d2 - dbest <= 1e-9 * cad->len && Dist3(z, z2) > 1e-6 * cad->len), PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "-contact_normal obstacle: -obstacle_cad_file %s: the contact vertex at (%g, %g, %g) has two closest points on the obstacle, (%g, %g, %g) and (%g, %g, %g): its normal is undefined", cad->file, (double)xb[0], (double)xb[1], (double)(dim == 3 ? xb[2] : 0), z[0], z[1], z[2], z2[0], z2[1], z2[2]);
  *h     = dbest;
  *btag_ = btag;
  PetscFunctionReturn(0);
}

/* The signed distance from ClosestCAD's point z: away from the surface the normal is x - z (its sign from the solid's
   inside), on it the entity's own normal, oriented by the inside just outside of it. A sheet (no volume) has no
   inside: a vertex on it has no normal, an error. Inside the solid the closest point is checked for uniqueness: the
   closest points of points 1e-6 of the model's size away in the axes' directions stay near z (within two elements of
   the tessellation, whose point may stand in for the exact one near an edge) unless x lies where two parts of the
   surface are as near (the centre of a ball: an error). */
static PetscErrorCode Distance_CAD(SgObstacle o, const PetscReal xb[], PetscReal *g, PetscReal nb[])
{
  Obstacle_CAD *cad = (Obstacle_CAD *)o->data;
  PetscInt      dim = o->dim;
  int           btag;
  double        x[3] = {0, 0, 0}, z[3] = {0, 0, 0}, nrm[3] = {0, 0, 0}, h, bpar[2] = {0, 0}, off;
  PetscBool     inside = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(CAD_Gap, 0, 0, 0, 0));
  PetscCall(CadLoad(o, cad));
  cad->nquery++;
  for (PetscInt k = 0; k < dim; k++) x[k] = (xb[k] - cad->shift[k]) / cad->scale;
  if (cad->hel == 0)
    for (PetscInt e = 0; e < cad->nel; e++)
      for (PetscInt a = 0; a < dim; a++) cad->hel = PetscMax(cad->hel, Dist3(&cad->xyz[(e * dim + a) * 3], &cad->xyz[(e * dim + (a + 1) % dim) * 3]));
  PetscCall(ClosestCAD(o, cad, x, xb, z, &h, &btag, bpar));
  off = 8 * (btag >= 0 ? cad->dev[btag] : 0) + 1e-6 * cad->len;
  if (h > 1e-7 * cad->len) {
    if (cad->solid) { /* the side of x; near a curved face, where x and the tessellation may lie on either side of each
                         other, the side of the point off along the same normal line */
      double y[3];
      for (int k = 0; k < 3; k++) y[k] = h < off ? z[k] + off * (x[k] - z[k]) / h : x[k];
      inside = InsideSolid(cad, dim, y);
    }
    if (inside) {
      for (PetscInt k = 0; k < dim; k++) {
        for (int sgn = -1; sgn <= 1; sgn += 2) {
          double y[3] = {x[0], x[1], x[2]}, zy[3], hy, py[2];
          int    ty;
          y[k] += sgn * 1e-6 * cad->len;
          PetscCall(ClosestCAD(o, cad, y, xb, zy, &hy, &ty, py));
          PetscCheck(Dist3(z, zy) <= PetscMax(1e-3 * cad->len, 2 * cad->hel), PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "-contact_normal obstacle: -obstacle_cad_file %s: the contact vertex at (%g, %g, %g) lies inside the obstacle where its closest point on the surface is not unique ((%g, %g, %g) and, 1e-6 of the model's size away, (%g, %g, %g)): its normal is undefined", cad->file, (double)xb[0], (double)xb[1], (double)(dim == 3 ? xb[2] : 0), z[0], z[1], z[2], zy[0], zy[1], zy[2]);
        }
      }
    }
    for (int k = 0; k < 3; k++) nrm[k] = (inside ? -1 : 1) * (x[k] - z[k]) / h;
    *g = cad->scale * (inside ? -h : h);
  } else { /* on the surface: the normal from the closest points of points delta away along the axes (their offset
              x + delta e_k - z_k is delta (e_k.n) n), oriented by the side of the point off along it */
    double best = 0, y[3], dot = 0, delta = 1e-5 * cad->len;
    PetscCheck(btag >= 0 && cad->solid, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "-contact_normal obstacle: -obstacle_cad_file %s: the contact vertex at (%g, %g, %g) lies on %s, where the obstacle's normal cannot be computed", cad->file, (double)xb[0], (double)xb[1], (double)(dim == 3 ? xb[2] : 0), btag < 0 ? "an edge or corner of the obstacle" : "a sheet (a model without volumes has no inside to orient it)");
    for (PetscInt k = 0; k < dim; k++) {
      double yk[3] = {x[0], x[1], x[2]}, zy[3], hy, py[2];
      int    ty;
      yk[k] += delta;
      PetscCall(ClosestCAD(o, cad, yk, xb, zy, &hy, &ty, py));
      if (hy > best) {
        best = hy;
        for (int q = 0; q < 3; q++) nrm[q] = (yk[q] - zy[q]) / hy;
      }
    }
    PetscCheck(best > 0.1 * delta, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "-contact_normal obstacle: -obstacle_cad_file %s: the obstacle has no normal at the closest point (%g, %g, %g) of the contact vertex at (%g, %g, %g)", cad->file, z[0], z[1], z[2], (double)xb[0], (double)xb[1], (double)(dim == 3 ? xb[2] : 0));
    for (int k = 0; k < 3; k++) y[k] = z[k] + off * nrm[k];
    if (InsideSolid(cad, dim, y))
      for (int k = 0; k < 3; k++) nrm[k] = -nrm[k];
    for (int k = 0; k < 3; k++) dot += nrm[k] * (x[k] - z[k]);
    *g = cad->scale * dot;
  }
  for (PetscInt k = 0; k < dim; k++) nb[k] = nrm[k];
  PetscCall(PetscLogEventEnd(CAD_Gap, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

static PetscErrorCode SetFromOptions_CAD(SgObstacle o, PetscOptionItems *PetscOptionsObject)
{
  Obstacle_CAD *cad = (Obstacle_CAD *)o->data;
  PetscBool     set, fileset, verbose = PETSC_FALSE, exists, ismesh;
  PetscInt      n = o->dim;

  PetscFunctionBeginUser;
  PetscCall(SgOptionsFileName(PetscOptionsObject, "-obstacle_cad_file", "CAD file of the obstacle (.geo, .step, .brep; read by gmsh), or a triangulated surface: STL (ASCII or binary) or gmsh ASCII .msh (triangles in 3D, line segments in z = 0 in 2D), closed or open, consistently oriented, its outside where the triangle normals point (a segment a->b faces (b-a) turned clockwise)", cad->file, sizeof(cad->file), &fileset));
  PetscCall(SgOptionsRealList(PetscOptionsObject, "-obstacle_cad_translation", "Translation of the CAD model, x,y[,z]", 3, cad->shift, &n, &set));
  PetscCheck(!set || n == o->dim, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_translation: got %" PetscInt_FMT " numbers, need %" PetscInt_FMT, n, o->dim);
  for (PetscInt k = 0; k < o->dim; k++) PetscCheck(PetscIsNormalReal(cad->shift[k]) || cad->shift[k] == 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_translation: entry %" PetscInt_FMT " is %g, must be finite", k, (double)cad->shift[k]);
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-obstacle_cad_scale", "Length of one CAD unit in the mesh's units (applied before the translation)", &cad->scale, NULL));
  PetscCheck(PetscIsNormalReal(cad->scale) && cad->scale > 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_scale: must be positive and finite, got %g", (double)cad->scale);
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-obstacle_cad_mesh_size", "Largest element of the tessellation the rays are cast against (CAD units; default the model's diagonal / 20)", &cad->msize, NULL));
  PetscCheck((PetscIsNormalReal(cad->msize) || cad->msize == 0) && cad->msize >= 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_mesh_size: must be >= 0 and finite, got %g", (double)cad->msize);
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-obstacle_cad_verbose", "Let gmsh print its messages", &verbose, NULL));
  {
    PetscBool help;
    PetscCall(PetscOptionsHasHelp(NULL, &help));
    if (help && !(fileset && cad->file[0])) PetscFunctionReturn(0); /* -help lists the options (SgObstaclePrintHelp) */
  }
  PetscCheck(fileset && cad->file[0], o->comm, PETSC_ERR_USER_INPUT, "-obstacle_type cad: needs -obstacle_cad_file");
  PetscCall(PetscTestFile(cad->file, 'r', &exists));
  PetscCheck(exists, o->comm, PETSC_ERR_FILE_OPEN, "-obstacle_cad_file %s: no such file, or not readable", cad->file);
  PetscCall(SgObstacleMeshFileIs(cad->file, &ismesh));
  if (ismesh) { /* a triangulated surface (obstacle_mesh.c) takes this obstacle over, with the same placement */
    char      file[PETSC_MAX_PATH_LEN];
    PetscReal shift[3], scale = cad->scale;
    PetscCall(PetscStrncpy(file, cad->file, sizeof(file)));
    for (PetscInt k = 0; k < 3; k++) shift[k] = cad->shift[k];
    PetscCall(PetscFree(o->data)); /* nothing of it allocated yet */
    o->destroy = NULL;
    PetscCall(SgObstacleSetUp_Mesh(o, file, shift, scale));
    PetscFunctionReturn(0);
  }
  PetscCall(CadRefuseMeshFile(o, cad->file));
  PetscCall(PetscLogEventBegin(CAD_SetUp, 0, 0, 0, 0));
  PetscCall(GmshStart(o->comm, verbose));
  PetscCall(CadSetUp(o, cad));
  PetscCall(PetscLogEventEnd(CAD_SetUp, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

static PetscErrorCode Destroy_CAD(SgObstacle o)
{
  Obstacle_CAD *cad = (Obstacle_CAD *)o->data;

  PetscFunctionBeginUser;
  if (!cad) PetscFunctionReturn(0);
  PetscCall(PetscInfo(NULL, "CAD obstacle %s: %" PetscInt_FMT " gap queries, %" PetscInt_FMT " closest-point calls, %" PetscInt_FMT " crossings kept from the tessellation, largest distance left to the CAD face %g\n", cad->file, cad->nquery, cad->nnewton, cad->nkept, cad->rmax));
  PetscCall(PetscFree7(cad->xyz, cad->tag, cad->hit, cad->sorted, cad->hitel, cad->roott, cad->roottag));
  PetscCall(PetscFree(cad->dev));
  PetscCall(PetscFree(o->data));
  PetscFunctionReturn(0);
}

PetscErrorCode SgObstacleCreate_CAD(SgObstacle o)
{
  Obstacle_CAD *cad;

  PetscFunctionBeginUser;
  if (!CAD_SetUp) {
    PetscClassId cid;
    PetscCall(PetscClassIdRegister("SgObstacleCAD", &cid));
    PetscCall(PetscLogEventRegister("SgCadSetUp", cid, &CAD_SetUp));
    PetscCall(PetscLogEventRegister("SgCadGap", cid, &CAD_Gap));
  }
  PetscCall(PetscNew(&cad));
  cad->scale        = 1;
  o->data           = cad;
  o->gap            = Gap_CAD;
  o->distance       = Distance_CAD;
  o->setfromoptions = SetFromOptions_CAD;
  o->destroy        = Destroy_CAD;
  PetscFunctionReturn(0);
}
