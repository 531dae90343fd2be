/* obstacle_mesh.c: a rigid obstacle given as a triangulated surface (STL, ASCII or binary; gmsh .msh, ASCII 2.2 or
   4.1: triangles in 3D, line segments in 2D), read from -obstacle_cad_file (obstacle type cad dispatches here by the
   file's extension and content).

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
#include "contact/contactimpl.h"
#include <ctype.h>

typedef struct {
  double   lo[3], hi[3];
  PetscInt left;         /* internal: the first child (the second is left + 1) */
  PetscInt start, count; /* leaf (count > 0): elements perm[start .. start + count) */
} MeshNode;

/* a growing list of element vertex coordinates (3 per vertex, nv vertices per element) */
typedef struct {
  double  *v;
  PetscInt n, cap; /* elements */
} Soup;

typedef struct {
  char      file[PETSC_MAX_PATH_LEN];
  PetscReal shift[3], scale; /* placement: a file point z sits at scale z + shift (-obstacle_cad_translation/scale) */
  PetscInt  nv;              /* vertices per element: 3 (triangles) or 2 (segments) */
  PetscInt  nel, nvert, nedge;
  double   *x;     /* vertex coordinates, 3 each */
  PetscInt *el;    /* element vertices, nv each */
  double   *nrm;   /* element unit normals, 3 each */
  PetscInt *eedge; /* 3D: edge k of triangle e joins its vertices k and k + 1 */
  double   *enrm;  /* 3D: edge pseudo-normals (sum of the adjacent faces' normals), 3 each */
  double   *vnrm;  /* vertex pseudo-normals (angle-weighted sum of the incident elements' normals), 3 each */
  MeshNode *node;
  PetscInt  nnode;
  PetscInt *perm;
  double    len; /* diagonal of the bounding box */
  PetscInt  nquery;
  Soup      soup; /* the elements as read (freed after set-up) */
} Obstacle_Mesh;

typedef struct {
  double   key;
  PetscInt id;
} KeyId;

static PetscLogEvent MESH_SetUp, MESH_Query;

static int CompareKeyId(const void *a, const void *b)
{
  const KeyId *x = (const KeyId *)a, *y = (const KeyId *)b;
  return x->key < y->key ? -1 : x->key > y->key ? 1 : (x->id > y->id) - (x->id < y->id);
}

/* ------------------------------------------------------------------------------------------------ file reading */

/* the file's extension in lower case ("" if none) */
static void FileExtension(const char file[], char ext[], size_t len)
{
  const char *dot = strrchr(file, '.'), *slash = strrchr(file, '/');
  size_t      k   = 0;

  ext[0] = 0;
  if (!dot || (slash && dot < slash) || strlen(dot + 1) >= len) return;
  for (k = 0; dot[1 + k]; k++) ext[k] = (char)tolower((unsigned char)dot[1 + k]);
  ext[k] = 0;
}

typedef enum {
  MESH_NONE,
  MESH_STL_ASCII,
  MESH_STL_BINARY,
  MESH_STL_BINARY_SIZE, /* binary bytes in the header, but not 84 + 50 n bytes */
  MESH_MSH
} MeshFormat;

/* The format by content: a binary STL (84 + 50 n bytes, n at byte 80; else a NUL in the first 84 bytes says a binary
   file of another size), gmsh's $MeshFormat, or an ASCII STL ("solid"). *size: the file's size in bytes. */
static PetscErrorCode SniffFormat(const char file[], MeshFormat *fmt, long *size)
{
  FILE         *fp = fopen(file, "rb");
  unsigned char head[84];
  size_t        got;
  const char   *s;

  PetscFunctionBeginUser;
  *fmt  = MESH_NONE;
  *size = -1;
  if (!fp) PetscFunctionReturn(0);
  got = fread(head, 1, sizeof(head), fp);
  if (!fseek(fp, 0, SEEK_END)) *size = ftell(fp);
  fclose(fp);
  if (got == 84) {
    unsigned long n = (unsigned long)head[80] | (unsigned long)head[81] << 8 | (unsigned long)head[82] << 16 | (unsigned long)head[83] << 24;
    if (*size >= 84 && (unsigned long)(*size - 84) == 50 * n) {
      *fmt = MESH_STL_BINARY;
      PetscFunctionReturn(0);
    }
  }
  for (size_t i = 0; i < got; i++)
    if (!head[i]) { /* text has no NUL; a binary STL's count has one below 2^24 triangles */
      *fmt = MESH_STL_BINARY_SIZE;
      PetscFunctionReturn(0);
    }
  s = (const char *)head;
  while (got && isspace((unsigned char)*s) && s < (const char *)head + got - 1) s++;
  if ((size_t)(s - (const char *)head) + 11 <= got && !strncmp(s, "$MeshFormat", 11)) *fmt = MESH_MSH;
  else if ((size_t)(s - (const char *)head) + 5 <= got && !strncmp(s, "solid", 5)) *fmt = MESH_STL_ASCII;
  PetscFunctionReturn(0);
}

/* Is the file a triangulated surface, to be read here? By extension .stl or .msh; the CAD extensions keep gmsh's
   path; any other file by its content. */
PetscErrorCode SgObstacleMeshFileIs(const char file[], PetscBool *ismesh)
{
  const char *cad[] = {"geo", "step", "stp", "brep", "iges", "igs", "xao"};
  char        ext[16];
  MeshFormat  fmt;
  long        size;

  PetscFunctionBeginUser;
  FileExtension(file, ext, sizeof(ext));
  *ismesh = (PetscBool)(!strcmp(ext, "stl") || !strcmp(ext, "msh"));
  if (*ismesh) PetscFunctionReturn(0);
  for (size_t i = 0; i < sizeof(cad) / sizeof(cad[0]); i++)
    if (!strcmp(ext, cad[i])) PetscFunctionReturn(0);
  PetscCall(SniffFormat(file, &fmt, &size));
  *ismesh = (PetscBool)(fmt != MESH_NONE && fmt != MESH_STL_BINARY_SIZE);
  PetscFunctionReturn(0);
}

static PetscErrorCode SoupAdd(Soup *s, PetscInt nv, const double v[])
{
  PetscFunctionBeginUser;
  if (s->n == s->cap) {
    s->cap = s->cap ? 2 * s->cap : 64;
    PetscCall(PetscRealloc(sizeof(double) * 3 * nv * s->cap, &s->v));
  }
  for (PetscInt k = 0; k < 3 * nv; k++) s->v[3 * nv * s->n + k] = v[k];
  s->n++;
  PetscFunctionReturn(0);
}

static PetscBool ParseReal(const char *tok, double *v)
{
  char *end;
  *v = strtod(tok, &end);
  return (PetscBool)(end != tok && *end == 0);
}

static PetscErrorCode ReadSTLAscii(SgObstacle o, const char file[], Soup *s)
{
  FILE    *fp = fopen(file, "r");
  char     tok[256];
  double   v[9];
  PetscInt nvf = -1; /* vertices in the current facet; -1 outside a facet */

  PetscFunctionBeginUser;
  PetscCheck(fp, o->comm, PETSC_ERR_FILE_OPEN, "-obstacle_cad_file %s: cannot open it", file);
  while (fscanf(fp, "%255s", tok) == 1) {
    if (!strcmp(tok, "facet")) {
      if (nvf >= 0) fclose(fp);
      PetscCheck(nvf < 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: ASCII STL facet %" PetscInt_FMT " has no endfacet", file, s->n + 1);
      nvf = 0;
    } else if (!strcmp(tok, "vertex")) {
      PetscBool ok = (PetscBool)(nvf >= 0 && nvf < 3);
      for (int k = 0; k < 3 && ok; k++) ok = (PetscBool)(fscanf(fp, "%255s", tok) == 1 && ParseReal(tok, &v[3 * nvf + k]));
      if (!ok) fclose(fp);
      PetscCheck(ok, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: ASCII STL facet %" PetscInt_FMT ": a vertex needs 3 numbers inside a facet of 3 vertices", file, s->n + 1);
      nvf++;
    } else if (!strcmp(tok, "endfacet")) {
      if (nvf != 3) fclose(fp);
      PetscCheck(nvf == 3, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: ASCII STL facet %" PetscInt_FMT " has %" PetscInt_FMT " vertices, need 3", file, s->n + 1, PetscMax(nvf, 0));
      PetscCall(SoupAdd(s, 3, v));
      nvf = -1;
    }
  }
  fclose(fp);
  PetscCheck(nvf < 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: ASCII STL truncated inside facet %" PetscInt_FMT, file, s->n + 1);
  PetscFunctionReturn(0);
}

static PetscErrorCode ReadSTLBinary(SgObstacle o, const char file[], Soup *s)
{
  FILE         *fp = fopen(file, "rb");
  unsigned char head[84], rec[50];
  unsigned long n;

  PetscFunctionBeginUser;
  PetscCheck(fp, o->comm, PETSC_ERR_FILE_OPEN, "-obstacle_cad_file %s: cannot open it", file);
  if (fread(head, 1, 84, fp) != 84) {
    fclose(fp);
    SETERRQ(o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: binary STL shorter than its header", file);
  }
  n = (unsigned long)head[80] | (unsigned long)head[81] << 8 | (unsigned long)head[82] << 16 | (unsigned long)head[83] << 24;
  for (unsigned long i = 0; i < n; i++) {
    double v[9];
    if (fread(rec, 1, 50, fp) != 50) {
      fclose(fp);
      SETERRQ(o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: binary STL truncated at triangle %lu", file, i + 1);
    }
    for (int k = 0; k < 9; k++) { /* little-endian IEEE floats after the 3 of the stored normal */
      uint32_t b = (uint32_t)rec[12 + 4 * k] | (uint32_t)rec[13 + 4 * k] << 8 | (uint32_t)rec[14 + 4 * k] << 16 | (uint32_t)rec[15 + 4 * k] << 24;
      float    f;
      memcpy(&f, &b, sizeof(f));
      v[k] = (double)f;
    }
    PetscCall(SoupAdd(s, 3, v));
  }
  fclose(fp);
  PetscFunctionReturn(0);
}

/* reading a .msh file: a problem found stops the reading, reported once the file is closed */
typedef struct {
  FILE     *fp;
  double    version;
  double   *nx;     /* node coordinates, 3 each */
  long     *idx;    /* node tag -> position in nx (-1: none) */
  long      maxtag; /* the largest node tag */
  PetscBool truncated, badtag, badnode;
  long      tag, eltag; /* the bad node tag; the element that names it */
  char      what[64];   /* the section being read */
} MshReader;

/* $Nodes: 4.1 in entity blocks (the tags, then the coordinates with any parametric ones), 2.2 "tag x y z" lines */
static PetscErrorCode MshNodes(MshReader *r)
{
  long nb = 1, nnodes = 0, mint = 0, nn = 0, *tags = NULL;
  char tok[256];

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(r->what, "$Nodes", sizeof(r->what)));
  PetscCall(PetscFree(r->nx));
  PetscCall(PetscFree(r->idx));
  r->maxtag = -1;
  if (r->version >= 4) r->truncated = (PetscBool)(fscanf(r->fp, "%ld %ld %ld %ld", &nb, &nnodes, &mint, &r->maxtag) != 4);
  else r->truncated = (PetscBool)(fscanf(r->fp, "%ld", &nnodes) != 1);
  /* at most 1e8 nodes and node tags (far beyond an obstacle's surface) */
  if (r->truncated || nnodes < 0 || nb < 0 || nnodes > 100000000 || r->maxtag > 100000000) {
    r->truncated = PETSC_TRUE;
    PetscFunctionReturn(0);
  }
  PetscCall(PetscMalloc1(3 * nnodes + 1, &r->nx));
  PetscCall(PetscMalloc1(nnodes + 1, &tags));
  for (long b = 0; b < nb && !r->truncated; b++) {
    int  edim = 0, etag, par = 0;
    long nin = nnodes;
    if (r->version >= 4 && (fscanf(r->fp, "%d %d %d %ld", &edim, &etag, &par, &nin) != 4 || nin < 0 || nn + nin > nnodes)) r->truncated = PETSC_TRUE;
    for (long i = nn; i < nn + nin && !r->truncated; i++) {
      r->truncated = (PetscBool)(fscanf(r->fp, "%ld", &tags[i]) != 1);
      for (int k = 0; k < 3 && !r->truncated && r->version < 4; k++) r->truncated = (PetscBool)(fscanf(r->fp, "%255s", tok) != 1 || !ParseReal(tok, &r->nx[3 * i + k]));
      if (!r->truncated && r->version < 4) r->maxtag = PetscMax(r->maxtag, tags[i]);
    }
    for (long i = nn; i < nn + nin && !r->truncated && r->version >= 4; i++) {
      for (int k = 0; k < 3 && !r->truncated; k++) r->truncated = (PetscBool)(fscanf(r->fp, "%255s", tok) != 1 || !ParseReal(tok, &r->nx[3 * i + k]));
      for (int k = 0; k < par * edim && !r->truncated; k++) r->truncated = (PetscBool)(fscanf(r->fp, "%255s", tok) != 1);
    }
    if (!r->truncated) nn += nin;
  }
  if (!r->truncated && (r->maxtag < 0 || r->maxtag > 100000000)) r->truncated = PETSC_TRUE;
  if (!r->truncated) {
    PetscCall(PetscMalloc1(r->maxtag + 1, &r->idx));
    for (long t = 0; t <= r->maxtag; t++) r->idx[t] = -1;
    for (long i = 0; i < nn && !r->badtag; i++) {
      if (tags[i] < 0 || tags[i] > r->maxtag) {
        r->badtag = PETSC_TRUE;
        r->tag    = tags[i];
      } else r->idx[tags[i]] = i;
    }
  }
  PetscCall(PetscFree(tags));
  PetscFunctionReturn(0);
}

/* $Elements: the triangles (type 2) in 3D or 2-node lines (type 1) in 2D, one line each; 4.1 in entity blocks of one
   type ("tag n1 n2 ..."), 2.2 "tag type ntags tags... n1 n2 ..." */
static PetscErrorCode MshElements(SgObstacle o, MshReader *r, Soup *s)
{
  PetscInt want = o->dim == 3 ? 2 : 1, nv = o->dim;
  long     nb = 1, nel = 0, a, b;
  char     line[4096];

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(r->what, "$Elements", sizeof(r->what)));
  if (r->version >= 4) r->truncated = (PetscBool)(fscanf(r->fp, "%ld %ld %ld %ld", &nb, &nel, &a, &b) != 4);
  else r->truncated = (PetscBool)(fscanf(r->fp, "%ld", &nel) != 1);
  if (!r->truncated) r->truncated = (PetscBool)!fgets(line, sizeof(line), r->fp); /* the end of the header line */
  for (long blk = 0; blk < nb && !r->truncated && !r->badnode; blk++) {
    int  edim, etag, type = 0;
    long nin = nel;
    if (r->version >= 4 && (!fgets(line, sizeof(line), r->fp) || sscanf(line, "%d %d %d %ld", &edim, &etag, &type, &nin) != 4 || nin < 0)) r->truncated = PETSC_TRUE;
    for (long i = 0; i < nin && !r->truncated && !r->badnode; i++) {
      char  *p = line, *end;
      long   tok[64];
      int    ntok = 0, first = 1; /* the position of the first node tag */
      double v[9];
      if (!fgets(line, sizeof(line), r->fp)) {
        r->truncated = PETSC_TRUE;
        break;
      }
      for (long t = strtol(p, &end, 10); end != p && ntok < 64; t = strtol(p, &end, 10)) {
        tok[ntok++] = t;
        p           = end;
      }
      if (r->version < 4) {
        if (ntok < 3) {
          r->truncated = PETSC_TRUE;
          break;
        }
        type  = (int)tok[1];
        first = 3 + (int)tok[2];
      }
      if (type != want) continue;
      if (first < 1 || ntok < first + nv) {
        r->truncated = PETSC_TRUE;
        break;
      }
      for (PetscInt q = 0; q < nv && !r->badnode; q++) {
        long t = tok[first + q];
        if (t < 0 || t > r->maxtag || r->idx[t] < 0) {
          r->badnode = PETSC_TRUE;
          r->tag     = t;
          r->eltag   = tok[0];
        } else
          for (int k = 0; k < 3; k++) v[3 * q + k] = r->nx[3 * r->idx[t] + k];
      }
      if (!r->badnode) PetscCall(SoupAdd(s, nv, v));
    }
  }
  PetscFunctionReturn(0);
}

/* gmsh's ASCII .msh (2.2 or 4.1): the nodes, and the triangles (3D) or 2-node lines (2D) */
static PetscErrorCode ReadMsh(SgObstacle o, const char file[], Soup *s)
{
  MshReader r;
  char      line[4096];
  int       ft = 0, ds = 0;
  PetscBool binary = PETSC_FALSE, badversion = PETSC_FALSE, early = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&r, sizeof(r)));
  r.maxtag = -1;
  r.fp     = fopen(file, "r");
  PetscCheck(r.fp, o->comm, PETSC_ERR_FILE_OPEN, "-obstacle_cad_file %s: cannot open it", file);
  while (!r.truncated && !r.badtag && !r.badnode && !binary && !badversion && !early && fgets(line, sizeof(line), r.fp)) {
    if (!strncmp(line, "$MeshFormat", 11)) {
      PetscCall(PetscStrncpy(r.what, "$MeshFormat", sizeof(r.what)));
      r.truncated = (PetscBool)(!fgets(line, sizeof(line), r.fp) || sscanf(line, "%lf %d %d", &r.version, &ft, &ds) != 3);
      binary      = (PetscBool)(!r.truncated && ft != 0);
      badversion  = (PetscBool)(!r.truncated && !((r.version >= 2 && r.version < 3) || (r.version >= 4 && r.version < 5)));
    } else if (!strncmp(line, "$Nodes", 6)) PetscCall(MshNodes(&r));
    else if (!strncmp(line, "$Elements", 9)) {
      if (!r.idx) early = PETSC_TRUE;
      else PetscCall(MshElements(o, &r, s));
    }
  }
  fclose(r.fp);
  PetscCall(PetscFree(r.nx));
  PetscCall(PetscFree(r.idx));
  PetscCheck(!binary, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: a binary .msh file is not read as an obstacle: save it as ASCII (gmsh -save -format msh41 without -bin, or Mesh.Binary = 0)", file);
  PetscCheck(!badversion, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: .msh version %g is not read (2.2 or 4.1)", file, r.version);
  PetscCheck(!early, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: $Elements before any $Nodes", file);
  PetscCheck(!r.truncated, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: the %s section is truncated or malformed", file, r.what);
  PetscCheck(!r.badtag, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: node tag %ld out of range", file, r.tag);
  PetscCheck(!r.badnode, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: element %ld names node %ld, which $Nodes does not define", file, r.eltag, r.tag);
  PetscCheck(r.version > 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: no $MeshFormat section: not a gmsh .msh file", file);
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------------ geometry */

static void Cross(const double a[3], const double b[3], double c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

static double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* the coordinates (s, t) of the projection of w = p - a onto the plane of a + s e1 + t e2 (a triangle's: inside when
   s, t >= 0 and s + t <= 1) */
static void Barycentric(const double e1[3], const double e2[3], const double w[3], double *s, double *t)
{
  const double d11 = Dot(e1, e1), d12 = Dot(e1, e2), d22 = Dot(e2, e2), p1 = Dot(w, e1), p2 = Dot(w, e2);
  const double det = d11 * d22 - d12 * d12;

  *s = (d22 * p1 - d12 * p2) / det;
  *t = (d11 * p2 - d12 * p1) / det;
}

static const double *Vtx(const Obstacle_Mesh *m, PetscInt e, PetscInt k)
{
  return &m->x[3 * m->el[m->nv * e + k]];
}

/* Vertices welded (equal coordinates are one vertex), checks, normals, edges and pseudo-normals. */
static PetscErrorCode BuildSurface(SgObstacle o, Obstacle_Mesh *m, const Soup *s)
{
  PetscInt nv = m->nv, np = s->n * nv, dim = o->dim;
  KeyId   *key;
  double   lo[3] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, hi[3] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL};
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
      Cross(t1, t2, c);
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
static PetscErrorCode Orient(SgObstacle o, Obstacle_Mesh *m)
{
  PetscInt nel = m->nel;

  PetscFunctionBeginUser;
  if (o->dim == 2) {
    PetscInt *from, *to; /* per vertex: the segment starting / ending there */
    PetscCall(PetscMalloc2(m->nvert, &from, m->nvert, &to));
    for (PetscInt v = 0; v < m->nvert; v++) from[v] = to[v] = -1;
    for (PetscInt e = 0; e < nel; e++) {
      PetscInt a = m->el[2 * e], b = m->el[2 * e + 1], fa = from[a], tb = to[b];
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
        const double *x = &m->x[3 * a0];
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
  MeshNode *nd = &m->node[id];
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
  const double eps = 1e-12;
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
        c->feat = u <= 0 ? 4 + k : u >= 1 ? 4 + (k + 1) % 3 : 1 + k;
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
    c->feat = u <= 0 ? 4 : u >= 1 ? 5 : 0;
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

static void ClosestTree(const Obstacle_Mesh *m, const double p[3], MeshClosest *best)
{
  PetscInt stack[256], sp = 0;

  PetscMemzero(best, sizeof(*best));
  best->d2 = PETSC_MAX_REAL;
  best->e  = PETSC_MAX_INT;
  stack[sp++] = 0;
  while (sp) {
    const MeshNode *nd = &m->node[stack[--sp]];
    double          d2 = 0;
    for (int k = 0; k < 3; k++) d2 += PetscSqr(PetscMax(0, PetscMax(nd->lo[k] - p[k], p[k] - nd->hi[k])));
    if (d2 > best->d2) continue;
    if (nd->count) {
      for (PetscInt i = nd->start; i < nd->start + nd->count; i++) {
        MeshClosest c;
        ClosestOnElement(m, m->perm[i], p, &c);
        if (Better(&c, best)) *best = c;
      }
    } else if (sp + 2 <= 256) {
      const MeshNode *l = &m->node[nd->left], *r = &m->node[nd->left + 1];
      double          dl = 0, dr = 0;
      for (int k = 0; k < 3; k++) {
        dl += PetscSqr(PetscMax(0, PetscMax(l->lo[k] - p[k], p[k] - l->hi[k])));
        dr += PetscSqr(PetscMax(0, PetscMax(r->lo[k] - p[k], p[k] - r->hi[k])));
      }
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
  const double  eps = 1e-12, *mm = &m->nrm[3 * e], *a = Vtx(m, e, 0), *b = Vtx(m, e, 1);
  double        dn = Dot(n, mm), ax[3], y[3], w[3], e1[3];

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

static PetscErrorCode Query(SgObstacle o, PetscBool brute, const PetscReal xb[], const PetscReal nb[], PetscReal *d, PetscReal *g, PetscReal nrm[])
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
  PetscCall(PetscLogEventEnd(MESH_Query, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

static PetscErrorCode Gap_Mesh(SgObstacle o, const PetscReal x[], const PetscReal n[], PetscReal *d)
{
  PetscFunctionBeginUser;
  PetscCall(Query(o, PETSC_FALSE, x, n, d, NULL, NULL));
  PetscFunctionReturn(0);
}

static PetscErrorCode Distance_Mesh(SgObstacle o, const PetscReal x[], PetscReal *g, PetscReal n[])
{
  PetscFunctionBeginUser;
  PetscCall(Query(o, PETSC_FALSE, x, NULL, NULL, g, n));
  PetscFunctionReturn(0);
}

/* The gap along n, the signed distance and the normal of a meshed obstacle by brute force over all elements, the
   tree left out (unit test of the tree: tests/unit_tests.c). x in the obstacle's frame, as the ops take it. */
PetscErrorCode SgObstacleMeshQueryBrute(SgObstacle o, const PetscReal x[], const PetscReal n[], PetscReal *d, PetscReal *g, PetscReal nrm[])
{
  PetscFunctionBeginUser;
  PetscCheck(o->gap == Gap_Mesh, o->comm, PETSC_ERR_ARG_WRONG, "SgObstacleMeshQueryBrute: not a meshed obstacle");
  PetscCall(Query(o, PETSC_TRUE, x, n, d, g, nrm));
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
  MeshFormat     fmt;
  long           size;
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
  PetscCall(SniffFormat(file, &fmt, &size));
  PetscCheck(size != 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: the file is empty: a meshed obstacle needs %s", file, el);
  if (fmt == MESH_STL_BINARY_SIZE) {
    unsigned char head[84] = {0};
    FILE         *fp = fopen(file, "rb");
    unsigned long n  = 0;
    if (fp) {
      if (fread(head, 1, 84, fp) == 84) n = (unsigned long)head[80] | (unsigned long)head[81] << 8 | (unsigned long)head[82] << 16 | (unsigned long)head[83] << 24;
      fclose(fp);
    }
    SETERRQ(o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: a binary file of %ld bytes, but a binary STL of %lu triangles (its header's count) has 84 + 50 x %lu bytes: truncated or not an STL file", file, size, n, n);
  }
  PetscCheck(fmt != MESH_NONE, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: neither an STL file (ASCII: 'solid ...'; binary: 84 + 50 n bytes) nor a gmsh .msh file ($MeshFormat)", file);
  PetscCheck(o->dim == 3 || fmt == MESH_MSH, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: an STL file holds triangles; a 2D obstacle is a curve of line segments: give a gmsh .msh file with line elements in the plane z = 0", file);
  if (fmt == MESH_STL_ASCII) PetscCall(ReadSTLAscii(o, file, &m->soup));
  else if (fmt == MESH_STL_BINARY) PetscCall(ReadSTLBinary(o, file, &m->soup));
  else PetscCall(ReadMsh(o, file, &m->soup));
  PetscCheck(m->soup.n > 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: the file has no %s%s: a %" PetscInt_FMT "D meshed obstacle is made of %s", file, el, fmt == MESH_MSH ? (o->dim == 3 ? " (gmsh element type 2)" : " (gmsh element type 1)") : "", o->dim, el);
  PetscCall(BuildSurface(o, m, &m->soup));
  PetscCall(PetscFree(m->soup.v));
  m->soup.n = m->soup.cap = 0;
  PetscCall(Orient(o, m));
  PetscCall(BuildTree(m));
  if (o->dim == 3) {
    PetscInt *cnt;
    PetscCall(PetscCalloc1(m->nedge, &cnt));
    for (PetscInt i = 0; i < 3 * m->nel; i++) cnt[m->eedge[i]]++;
    for (PetscInt i = 0; i < m->nedge; i++) nbnd += cnt[i] == 1;
    PetscCall(PetscFree(cnt));
  } else nbnd = 2 * m->nvert - 2 * m->nel; /* vertices of one segment */
  PetscCall(PetscInfo(NULL, "meshed obstacle %s: %" PetscInt_FMT " %s, %" PetscInt_FMT " vertices, %s surface (%" PetscInt_FMT " boundary %s), %" PetscInt_FMT " tree nodes\n", file, m->nel, el, m->nvert, nbnd ? "open" : "closed", nbnd, o->dim == 3 ? "edges" : "vertices", m->nnode));
  PetscCall(PetscLogEventEnd(MESH_SetUp, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}
