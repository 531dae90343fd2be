/* obstacle_mesh_file.c: reading a meshed obstacle's file (-obstacle_cad_file): the format by extension and content,
   ASCII and binary STL, gmsh's ASCII .msh 2.2 and 4.1; the elements as read (a soup of vertex coordinates), welded and
   checked by obstacle_mesh_surface.c. */
#include "contact/obstacle_meshimpl.h"
#include <ctype.h>

/* the file's extension in lower case ("" if none) */
static void FileExtension(const char file[], char ext[], size_t len)
{
  const char *dot = strrchr(file, '.'), *slash = strrchr(file, '/');
  size_t      k = 0;

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
   file of another size), gmsh's $MeshFormat, or an ASCII STL ("solid"). *size: the file's size in bytes; *count
   (if not NULL): the triangle count of a binary STL header (bytes 80-83; 0 in a shorter file). */
static PetscErrorCode SniffFormat(const char file[], MeshFormat *fmt, long *size, unsigned long *count)
{
  FILE         *fp = fopen(file, "rb");
  unsigned char head[84];
  size_t        got;
  const char   *s;

  PetscFunctionBeginUser;
  *fmt  = MESH_NONE;
  *size = -1;
  if (count) *count = 0;
  if (!fp) PetscFunctionReturn(0);
  got = fread(head, 1, sizeof(head), fp);
  if (!fseek(fp, 0, SEEK_END)) *size = ftell(fp);
  fclose(fp);
  if (got == 84) {
    unsigned long n = (unsigned long)head[80] | (unsigned long)head[81] << 8 | (unsigned long)head[82] << 16 | (unsigned long)head[83] << 24;
    if (count) *count = n;
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
  PetscCall(SniffFormat(file, &fmt, &size, NULL));
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

/* The elements of file (STL, ASCII or binary, or gmsh's ASCII .msh) into s; a file that is empty, of neither format,
   an STL file for a 2D obstacle or one without elements is refused naming -obstacle_cad_file. */
PetscErrorCode SgObstacleMeshRead(SgObstacle o, const char file[], Soup *s)
{
  MeshFormat    fmt;
  long          size;
  unsigned long n;
  const char   *el = o->dim == 3 ? "triangles" : "line segments";

  PetscFunctionBeginUser;
  PetscCall(SniffFormat(file, &fmt, &size, &n));
  PetscCheck(size != 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: the file is empty: a meshed obstacle needs %s", file, el);
  PetscCheck(fmt != MESH_STL_BINARY_SIZE, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: a binary file of %ld bytes, but a binary STL of %lu triangles (its header's count) has 84 + 50 x %lu bytes: truncated or not an STL file", file, size, n, n);
  PetscCheck(fmt != MESH_NONE, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: neither an STL file (ASCII: 'solid ...'; binary: 84 + 50 n bytes) nor a gmsh .msh file ($MeshFormat)", file);
  PetscCheck(o->dim == 3 || fmt == MESH_MSH, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: an STL file holds triangles; a 2D obstacle is a curve of line segments: give a gmsh .msh file with line elements in the plane z = 0", file);
  if (fmt == MESH_STL_ASCII) PetscCall(ReadSTLAscii(o, file, s));
  else if (fmt == MESH_STL_BINARY) PetscCall(ReadSTLBinary(o, file, s));
  else PetscCall(ReadMsh(o, file, s));
  PetscCheck(s->n > 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_cad_file %s: the file has no %s%s: a %" PetscInt_FMT "D meshed obstacle is made of %s", file, el, fmt == MESH_MSH ? (o->dim == 3 ? " (gmsh element type 2)" : " (gmsh element type 1)") : "", o->dim, el);
  PetscFunctionReturn(0);
}
