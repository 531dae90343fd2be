/* gmshcheck.c: validate a gmsh .msh file on rank 0 before PETSc's reader, which trusts it (a bad node tag crashes it). */
#include "fem/femimpl.h"
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* PETSc 3.18's DMPlexCreateGmsh() indexes its node map with every node tag an element names, sizes its arrays from
   the section headers, looks entities up without checking that they exist and copies names into fixed buffers: a
   wrong tag or count is a segmentation fault or a silently wrong cell, not an error. This reader checks, line by
   line and in one linear pass, what that reader relies on, for ASCII MSH 4.1 (what gmsh 4.x writes) and 2.2.
   MSH 4.0 and binary files are checked up to their header only and left to PETSc. Memory: the node tags (one
   PetscInt each) and a bit per tag of their range (or the sorted tags when the range is very sparse). */

typedef struct {
  int type, dim, nverts, nnodes;
} GmshType;

/* gmsh element types: dimension, corner vertices, nodes (gmsh manual, "MSH file format"; complete Lagrange and the
   serendipity 16/17; types missing here are refused, PETSc's reader knows no more) */
static const GmshType GmshTypes[] = {
    {15, 0, 1,   1},
    { 1, 1, 2,   2},
    { 8, 1, 2,   3},
    {26, 1, 2,   4},
    {27, 1, 2,   5},
    {28, 1, 2,   6},
    { 2, 2, 3,   3},
    { 9, 2, 3,   6},
    {21, 2, 3,  10},
    {23, 2, 3,  15},
    {25, 2, 3,  21},
    { 3, 2, 4,   4},
    {10, 2, 4,   9},
    {16, 2, 4,   8},
    {36, 2, 4,  16},
    {37, 2, 4,  25},
    { 4, 3, 4,   4},
    {11, 3, 4,  10},
    {29, 3, 4,  20},
    {30, 3, 4,  35},
    {31, 3, 4,  56},
    { 5, 3, 8,   8},
    {12, 3, 8,  27},
    {17, 3, 8,  20},
    {92, 3, 8,  64},
    {93, 3, 8, 125},
    { 6, 3, 6,   6},
    {13, 3, 6,  18},
    { 7, 3, 5,   5},
    {14, 3, 5,  14},
};

#define GMSH_MAX_ENTITY_TAGS 16   /* PETSc's GMSH_MAX_TAGS: physical tags per entity */
#define GMSH_MAX_NAME        127  /* characters of a physical name (gmsh's limit; PETSc copies into a small buffer) */
#define GMSH_V22_BUF         1000 /* PETSc reads an MSH 2.2 element (id, tags, nodes) into an int[1005] */

typedef struct {
  FILE       *fp;
  const char *fname;
  char       *buf; /* the current line, trailing white space removed */
  size_t      cap;
  long        line;
  PetscBool   unended; /* the current line is the file's last and has no newline: a truncated file */
  long long   fsize;   /* bytes: bounds every count in a header before anything is allocated for it */
  int         bad;
  char        msg[768];
  /* entities of MSH 4.1: sorted tags per dimension */
  PetscInt  nent[4];
  PetscInt *ent[4];
  /* nodes */
  PetscInt       nnodes, nmin, nmax;
  PetscInt      *tags;   /* all node tags, in file order (sorted when the range is sparse) */
  unsigned char *bits;   /* one bit per tag in [nmin, nmax] when the range is dense */
  PetscBool      sorted; /* lookup by binary search in tags[] instead of bits */
} GmshCheck;

#define GFAIL(p, ...)                    \
  do {                                   \
    PetscCall(GmshFail(p, __VA_ARGS__)); \
    PetscFunctionReturn(0);              \
  } while (0)
#define GCHECK(p, cond, ...)            \
  do {                                  \
    if (!(cond)) GFAIL(p, __VA_ARGS__); \
  } while (0)
#define GCALL(p, call)                    \
  do {                                    \
    PetscCall(call);                      \
    if ((p)->bad) PetscFunctionReturn(0); \
  } while (0)

static PetscErrorCode GmshFail(GmshCheck *p, const char fmt[], ...)
{
  char    what[600];
  size_t  len;
  va_list ap;

  PetscFunctionBeginUser;
  va_start(ap, fmt);
  PetscCall(PetscVSNPrintf(what, sizeof(what), fmt, &len, ap));
  va_end(ap);
  PetscCall(PetscSNPrintf(p->msg, sizeof(p->msg), "line %ld: %s%s", p->line, what, p->unended ? " (the file ends in this line: truncated?)" : ""));
  p->bad = 1;
  PetscFunctionReturn(0);
}

/* The current line for a message: shortened, other bytes than printable ASCII shown as '?'. */
static const char *Shown(GmshCheck *p)
{
  static char s[72];
  size_t      n = strlen(p->buf), m = PetscMin(n, sizeof(s) - 4);
  for (size_t i = 0; i < m; i++) s[i] = (p->buf[i] >= 32 && p->buf[i] < 127) ? p->buf[i] : '?';
  strcpy(s + m, n > m ? "..." : "");
  return s;
}

/* Next line that is not blank (PETSc reads tokens, so blank lines are harmless); *eof at the end of the file. */
static PetscErrorCode NextLine(GmshCheck *p, PetscBool *eof)
{
  PetscFunctionBeginUser;
  for (;;) {
    ssize_t n = getline(&p->buf, &p->cap, p->fp);
    char   *s;
    if (n < 0) {
      *eof       = PETSC_TRUE;
      p->unended = PETSC_FALSE;
      if (p->buf) p->buf[0] = 0;
      PetscFunctionReturn(0);
    }
    p->line++;
    p->unended = p->buf[n - 1] != '\n' ? PETSC_TRUE : PETSC_FALSE;
    GCHECK(p, (size_t)n == strlen(p->buf), "a NUL byte: not a text (ASCII) gmsh file");
    while (n > 0 && (p->buf[n - 1] == '\n' || p->buf[n - 1] == '\r' || p->buf[n - 1] == ' ' || p->buf[n - 1] == '\t')) p->buf[--n] = 0;
    for (s = p->buf; *s == ' ' || *s == '\t'; s++) {}
    if (*s) break;
  }
  *eof = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* A line that must exist; the end of the file inside `where` is an error. */
static PetscErrorCode Line(GmshCheck *p, const char where[])
{
  PetscBool eof;

  PetscFunctionBeginUser;
  GCALL(p, NextLine(p, &eof));
  GCHECK(p, !eof, "the file ends inside %s (truncated file?)", where);
  PetscFunctionReturn(0);
}

static const char *Trimmed(const char *s)
{
  while (*s == ' ' || *s == '\t') s++;
  return s;
}

/* The next section marker, skipping $Comments sections as PETSc does; *eof if none. */
static PetscErrorCode NextSection(GmshCheck *p, PetscBool *eof)
{
  PetscFunctionBeginUser;
  for (;;) {
    GCALL(p, NextLine(p, eof));
    if (*eof || strcmp(Trimmed(p->buf), "$Comments")) break;
    for (;;) {
      GCALL(p, Line(p, "$Comments"));
      if (!strcmp(Trimmed(p->buf), "$EndComments")) break;
    }
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode ExpectSection(GmshCheck *p, const char name[], const char after[])
{
  PetscBool eof;

  PetscFunctionBeginUser;
  GCALL(p, NextSection(p, &eof));
  GCHECK(p, !eof, "the file ends after %s: section %s is missing", after, name);
  GCHECK(p, !strcmp(Trimmed(p->buf), name), "expected section %s after %s, found '%s'", name, after, Shown(p));
  PetscFunctionReturn(0);
}

static PetscErrorCode ExpectEnd(GmshCheck *p, const char name[], const char what[])
{
  char sec[64];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(sec, sizeof(sec), "$%s", name + 4)); /* $EndNodes -> $Nodes */
  GCALL(p, Line(p, sec));
  GCHECK(p, !strcmp(Trimmed(p->buf), name), "expected %s after %s, found '%s'", name, what, Shown(p));
  PetscFunctionReturn(0);
}

/* Next whitespace-separated token of *s as an integer: 1 read, 0 none left, -1 not an integer. */
static int TokInt(const char **s, long long *v)
{
  const char *t = *s;
  char       *e;
  while (*t == ' ' || *t == '\t') t++;
  if (!*t) return 0;
  errno = 0;
  *v    = strtoll(t, &e, 10);
  if (e == t || errno == ERANGE || (*e && *e != ' ' && *e != '\t')) return -1;
  *s = e;
  return 1;
}

static int TokReal(const char **s, double *v)
{
  const char *t = *s;
  char       *e;
  while (*t == ' ' || *t == '\t') t++;
  if (!*t) return 0;
  *v = strtod(t, &e);
  if (e == t || (*e && *e != ' ' && *e != '\t')) return -1;
  *s = e;
  return 1;
}

static const char *NonFinite(double x)
{
  return isnan(x) ? "NaN" : x > 0 ? "+inf"
                                  : "-inf";
}

static int AtEnd(const char *s)
{
  return !*Trimmed(s);
}

/* The current line as exactly n integers in [lo, hi], named by names[] ("a b c") for the message. */
static PetscErrorCode LineInts(GmshCheck *p, int n, long long v[], const long long lo[], const long long hi[], const char what[], const char names[])
{
  const char *s = p->buf;

  PetscFunctionBeginUser;
  for (int i = 0; i < n; i++) {
    int r = TokInt(&s, &v[i]);
    GCHECK(p, r == 1, "%s: expected %d integers (%s), found '%s'", what, n, names, Shown(p));
    GCHECK(p, v[i] >= lo[i] && v[i] <= hi[i], "%s: integer %d (of %s) is %lld, outside [%lld, %lld]", what, i + 1, names, v[i], lo[i], hi[i]);
  }
  GCHECK(p, AtEnd(s), "%s: expected %d integers (%s), found more: '%s'", what, n, names, Shown(p));
  PetscFunctionReturn(0);
}

static const GmshType *FindType(long long type)
{
  for (size_t i = 0; i < sizeof(GmshTypes) / sizeof(GmshTypes[0]); i++)
    if (GmshTypes[i].type == type) return &GmshTypes[i];
  return NULL;
}

/* ------------------------------------------------------------------ sections */

/* $PhysicalNames: count, then `dim tag "name"` lines. */
static PetscErrorCode CheckPhysicalNames(GmshCheck *p)
{
  long long       n, v[2];
  const long long lo1[1] = {0}, hi1[1] = {p->fsize / 8};
  const long long lo[2] = {0, -(long long)PETSC_MAX_INT}, hi[2] = {3, PETSC_MAX_INT};

  PetscFunctionBeginUser;
  GCALL(p, Line(p, "$PhysicalNames"));
  GCALL(p, LineInts(p, 1, &n, lo1, hi1, "$PhysicalNames count", "numPhysicalNames"));
  for (long long i = 0; i < n; i++) {
    const char *s = p->buf, *q, *r;
    GCALL(p, Line(p, "$PhysicalNames"));
    GCHECK(p, strcmp(Trimmed(p->buf), "$EndPhysicalNames"), "$PhysicalNames: found $EndPhysicalNames after %lld of the %lld names its count announces", i, n);
    s = p->buf;
    for (int k = 0; k < 2; k++) {
      GCHECK(p, TokInt(&s, &v[k]) == 1, "physical name %lld: expected 'dim tag \"name\"', found '%s'", i + 1, Shown(p));
      GCHECK(p, v[k] >= lo[k] && v[k] <= hi[k], "physical name %lld: %s %lld is out of range", i + 1, k ? "tag" : "dimension", v[k]);
    }
    s = Trimmed(s);
    q = strrchr(s, '"');
    GCHECK(p, *s == '"' && q && q != s && AtEnd(q + 1), "physical name %lld: the name must be in double quotes, found '%s'", i + 1, Shown(p));
    r = q;
    GCHECK(p, r - s - 1 <= GMSH_MAX_NAME, "physical name %lld is %ld characters long, at most %d are allowed", i + 1, (long)(r - s - 1), GMSH_MAX_NAME);
  }
  GCALL(p, ExpectEnd(p, "$EndPhysicalNames", "the names its count announces"));
  PetscFunctionReturn(0);
}

static PetscErrorCode FindEntity(GmshCheck *p, long long dim, long long tag, PetscBool *found)
{
  PetscInt loc;

  PetscFunctionBeginUser;
  PetscCall(PetscFindInt((PetscInt)tag, p->nent[dim], p->ent[dim], &loc));
  *found = loc >= 0 ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* $Entities (MSH 4.1): counts per dimension, then one line per entity: tag, a box (a point for dim 0), physical tags,
   bounding entities (dim > 0). */
static PetscErrorCode CheckEntities(GmshCheck *p)
{
  long long          c[4];
  const long long    lo[4] = {0, 0, 0, 0}, hi[4] = {p->fsize / 8, p->fsize / 8, p->fsize / 8, p->fsize / 8};
  static const char *dname[4] = {"point", "curve", "surface", "volume"};

  PetscFunctionBeginUser;
  GCALL(p, Line(p, "$Entities"));
  GCALL(p, LineInts(p, 4, c, lo, hi, "$Entities header", "numPoints numCurves numSurfaces numVolumes"));
  for (int d = 0; d < 4; d++) {
    p->nent[d] = (PetscInt)c[d];
    PetscCall(PetscMalloc1(c[d], &p->ent[d]));
    for (long long i = 0; i < c[d]; i++) {
      const char *s;
      long long   tag, nt;
      double      x;
      GCALL(p, Line(p, "$Entities"));
      GCHECK(p, p->buf[0] != '$', "$Entities: found '%s' where %s %lld of the %lld its header announces was expected", Shown(p), dname[d], i + 1, c[d]);
      s = p->buf;
      GCHECK(p, TokInt(&s, &tag) == 1 && tag > 0 && tag <= PETSC_MAX_INT, "%s entity %lld: expected a positive tag, found '%s'", dname[d], i + 1, Shown(p));
      for (int k = 0; k < (d ? 6 : 3); k++) GCHECK(p, TokReal(&s, &x) == 1, "%s entity %lld (tag %lld): expected %d coordinates of its %s, found '%s'", dname[d], i + 1, tag, d ? 6 : 3, d ? "bounding box" : "position", Shown(p));
      GCHECK(p, TokInt(&s, &nt) == 1 && nt >= 0, "%s entity %lld (tag %lld): expected the number of physical tags, found '%s'", dname[d], i + 1, tag, Shown(p));
      GCHECK(p, nt <= GMSH_MAX_ENTITY_TAGS, "%s entity %lld (tag %lld) has %lld physical tags, PETSc's reader takes at most %d", dname[d], i + 1, tag, nt, GMSH_MAX_ENTITY_TAGS);
      for (long long k = 0; k < nt; k++) {
        long long t;
        GCHECK(p, TokInt(&s, &t) == 1 && t >= -(long long)PETSC_MAX_INT && t <= PETSC_MAX_INT, "%s entity %lld (tag %lld): expected %lld physical tags, found '%s'", dname[d], i + 1, tag, nt, Shown(p));
      }
      if (d) {
        long long nb, t;
        GCHECK(p, TokInt(&s, &nb) == 1 && nb >= 0 && nb <= p->fsize, "%s entity %lld (tag %lld): expected the number of bounding entities, found '%s'", dname[d], i + 1, tag, Shown(p));
        for (long long k = 0; k < nb; k++) GCHECK(p, TokInt(&s, &t) == 1, "%s entity %lld (tag %lld): expected %lld bounding entity tags, found '%s'", dname[d], i + 1, tag, nb, Shown(p));
      }
      GCHECK(p, AtEnd(s), "%s entity %lld (tag %lld): unexpected trailing data in '%s'", dname[d], i + 1, tag, Shown(p));
      p->ent[d][i] = (PetscInt)tag;
    }
    PetscCall(PetscSortInt(p->nent[d], p->ent[d]));
    for (PetscInt i = 1; i < p->nent[d]; i++) GCHECK(p, p->ent[d][i] != p->ent[d][i - 1], "$Entities: %s tag %" PetscInt_FMT " is defined twice", dname[d], p->ent[d][i]);
  }
  GCALL(p, ExpectEnd(p, "$EndEntities", "the entities its header announces"));
  PetscFunctionReturn(0);
}

/* The tag of the n-th node read; duplicates and the lookup structure are set up in NodesDone(). */
static PetscBool NodeDefined(GmshCheck *p, long long tag)
{
  if (!p->nnodes || tag < p->nmin || tag > p->nmax) return PETSC_FALSE;
  if (!p->sorted) {
    const long long o = tag - p->nmin;
    return (p->bits[o >> 3] >> (o & 7)) & 1 ? PETSC_TRUE : PETSC_FALSE;
  } else {
    PetscInt lo = 0, hi = p->nnodes - 1;
    while (lo <= hi) {
      const PetscInt mid = lo + (hi - lo) / 2;
      if (p->tags[mid] == tag) return PETSC_TRUE;
      if (p->tags[mid] < tag) lo = mid + 1;
      else hi = mid - 1;
    }
    return PETSC_FALSE;
  }
}

/* After $Nodes: the set of defined tags, a bit per tag of [min, max] if that costs at most about 8 bytes per node,
   else the sorted tags. A tag given twice is refused (PETSc would keep either node), with its line when known:
   lineOf(i) maps the index of a node in file order to its tag's line. */
static PetscErrorCode NodesDone(GmshCheck *p, long (*lineOf)(GmshCheck *, PetscInt, const long *), const long *ctx, long section)
{
  PetscInt n = p->nnodes;

  PetscFunctionBeginUser;
  if (!n) PetscFunctionReturn(0);
  p->nmin = PETSC_MAX_INT;
  p->nmax = 0;
  for (PetscInt i = 0; i < n; i++) {
    p->nmin = PetscMin(p->nmin, p->tags[i]);
    p->nmax = PetscMax(p->nmax, p->tags[i]);
  }
  if ((double)p->nmax - p->nmin + 1 <= 64.0 * n + 65536) {
    const size_t range = (size_t)(p->nmax - p->nmin) + 1;
    PetscCall(PetscCalloc1((range + 7) / 8, &p->bits));
    for (PetscInt i = 0; i < n; i++) {
      const size_t o = (size_t)(p->tags[i] - p->nmin);
      if ((p->bits[o >> 3] >> (o & 7)) & 1) {
        p->line = lineOf(p, i, ctx);
        GFAIL(p, "node tag %" PetscInt_FMT " is defined twice in $Nodes", p->tags[i]);
      }
      p->bits[o >> 3] |= (unsigned char)(1u << (o & 7));
    }
  } else {
    PetscCall(PetscSortInt(n, p->tags));
    p->sorted = PETSC_TRUE;
    for (PetscInt i = 1; i < n; i++) {
      p->line = section;
      GCHECK(p, p->tags[i] != p->tags[i - 1], "node tag %" PetscInt_FMT " is defined twice in the $Nodes section starting here", p->tags[i]);
    }
  }
  PetscFunctionReturn(0);
}

/* Line of node i in MSH 4.1: ctx holds, per block, the index of its first node and the line of its first tag. */
static long LineOf41(GmshCheck *p, PetscInt i, const long *ctx)
{
  long b = 0;
  while (ctx[2 * (b + 1)] <= i) b++;
  return ctx[2 * b + 1] + (i - ctx[2 * b]);
}

static long LineOf22(GmshCheck *p, PetscInt i, const long *ctx)
{
  return ctx[0] + i;
}

/* $Nodes (MSH 4.1): header, then per entity block a header, the node tags (one a line), their coordinates. */
static PetscErrorCode CheckNodes41(GmshCheck *p)
{
  long long       h[4], b[4];
  const long long lo[4] = {0, 0, 0, 0}, hi[4] = {p->fsize / 8, p->fsize / 8, PETSC_MAX_INT, PETSC_MAX_INT};
  const long long blo[4] = {0, 1, 0, 0}, bhi[4] = {3, PETSC_MAX_INT, 1, p->fsize / 8};
  long           *blk     = NULL; /* per block: first node index, line of its first tag; and a sentinel */
  long            section = p->line;
  PetscInt        node    = 0;

  PetscFunctionBeginUser;
  GCALL(p, Line(p, "$Nodes"));
  GCALL(p, LineInts(p, 4, h, lo, hi, "$Nodes header", "numEntityBlocks numNodes minNodeTag maxNodeTag"));
  GCHECK(p, h[1] > 0 || h[0] == 0, "$Nodes header: %lld entity blocks but no nodes", h[0]);
  GCHECK(p, h[1] == 0 || (h[2] >= 1 && h[2] <= h[3]), "$Nodes header: minNodeTag %lld and maxNodeTag %lld must satisfy 1 <= min <= max", h[2], h[3]);
  GCHECK(p, h[1] == 0 || h[3] - h[2] + 1 >= h[1], "$Nodes header: %lld nodes cannot have distinct tags in [%lld, %lld]", h[1], h[2], h[3]);
  GCHECK(p, h[0] <= h[1], "$Nodes header: %lld entity blocks for %lld nodes", h[0], h[1]);
  p->nnodes = (PetscInt)h[1];
  PetscCall(PetscMalloc1(p->nnodes, &p->tags));
  PetscCall(PetscMalloc1(2 * (h[0] + 1), &blk));
  for (long long k = 0; k < h[0]; k++) {
    PetscBool found;
    GCALL(p, Line(p, "$Nodes"));
    if (!strcmp(Trimmed(p->buf), "$EndNodes")) {
      PetscCall(PetscFree(blk));
      GFAIL(p, "found $EndNodes after %lld of the %lld entity blocks the $Nodes header announces", k, h[0]);
    }
    PetscCall(LineInts(p, 4, b, blo, bhi, "$Nodes entity block header", "entityDim entityTag parametric numNodesInBlock"));
    if (!p->bad && b[2]) PetscCall(GmshFail(p, "$Nodes block %lld: parametric coordinates (parametric = 1) are not supported by PETSc's gmsh reader", k + 1));
    if (!p->bad) {
      PetscCall(FindEntity(p, b[0], b[1], &found));
      if (!found) PetscCall(GmshFail(p, "$Nodes block %lld: entity (dim %lld, tag %lld) is not defined in $Entities", k + 1, b[0], b[1]));
    }
    if (!p->bad && node + b[3] > h[1]) PetscCall(GmshFail(p, "$Nodes block %lld: %lld more nodes exceed the %lld nodes of the $Nodes header", k + 1, b[3], h[1]));
    if (p->bad) {
      PetscCall(PetscFree(blk));
      PetscFunctionReturn(0);
    }
    blk[2 * k]     = node;
    blk[2 * k + 1] = p->line + 1;
    for (long long i = 0; i < b[3]; i++) {
      const char *s;
      long long   t;
      int         r;
      PetscCall(Line(p, "$Nodes"));
      if (!p->bad) {
        s = p->buf;
        r = TokInt(&s, &t);
        if (r != 1 || !AtEnd(s)) PetscCall(GmshFail(p, "$Nodes block %lld (entity dim %lld, tag %lld): expected the tag of node %lld of %lld (one integer), found '%s'", k + 1, b[0], b[1], i + 1, b[3], Shown(p)));
        else if (t < h[2] || t > h[3]) PetscCall(GmshFail(p, "$Nodes block %lld: node tag %lld is outside [minNodeTag, maxNodeTag] = [%lld, %lld] of the $Nodes header", k + 1, t, h[2], h[3]));
      }
      if (p->bad) {
        PetscCall(PetscFree(blk));
        PetscFunctionReturn(0);
      }
      p->tags[node + i] = (PetscInt)t;
    }
    for (long long i = 0; i < b[3]; i++) {
      const char *s;
      double      x;
      PetscCall(Line(p, "$Nodes"));
      s = p->buf;
      for (int d = 0; d < 3 && !p->bad; d++) {
        if (TokReal(&s, &x) != 1) PetscCall(GmshFail(p, "$Nodes block %lld: expected 3 coordinates of node %" PetscInt_FMT " (x y z), found '%s'", k + 1, p->tags[node + i], Shown(p)));
        else if (!isfinite(x)) PetscCall(GmshFail(p, "$Nodes block %lld: coordinate %d of node %" PetscInt_FMT " is %s, not a finite number", k + 1, d + 1, p->tags[node + i], NonFinite(x)));
      }
      if (!p->bad && !AtEnd(s)) PetscCall(GmshFail(p, "$Nodes block %lld: expected 3 coordinates of node %" PetscInt_FMT " (x y z), found more: '%s'", k + 1, p->tags[node + i], Shown(p)));
      if (p->bad) {
        PetscCall(PetscFree(blk));
        PetscFunctionReturn(0);
      }
    }
    node += (PetscInt)b[3];
  }
  blk[2 * h[0]] = node;
  if (node != h[1]) {
    PetscCall(PetscFree(blk));
    GFAIL(p, "$Nodes: the %lld entity blocks hold %" PetscInt_FMT " nodes, the header announces %lld", h[0], node, h[1]);
  }
  PetscCall(ExpectEnd(p, "$EndNodes", "the entity blocks its header announces"));
  if (!p->bad) PetscCall(NodesDone(p, LineOf41, blk, section));
  PetscCall(PetscFree(blk));
  PetscFunctionReturn(0);
}

/* $Nodes (MSH 2.2): count, then `tag x y z` lines. */
static PetscErrorCode CheckNodes22(GmshCheck *p)
{
  long long       n;
  const long long lo[1] = {0}, hi[1] = {p->fsize / 8};
  long            first;

  PetscFunctionBeginUser;
  GCALL(p, Line(p, "$Nodes"));
  GCALL(p, LineInts(p, 1, &n, lo, hi, "$Nodes count", "numNodes"));
  p->nnodes = (PetscInt)n;
  PetscCall(PetscMalloc1(p->nnodes, &p->tags));
  first = p->line + 1;
  for (long long i = 0; i < n; i++) {
    const char *s;
    long long   t;
    double      x;
    GCALL(p, Line(p, "$Nodes"));
    GCHECK(p, strcmp(Trimmed(p->buf), "$EndNodes"), "found $EndNodes after %lld of the %lld nodes its count announces", i, n);
    s = p->buf;
    GCHECK(p, TokInt(&s, &t) == 1, "$Nodes: expected 'tag x y z' of node %lld of %lld, found '%s'", i + 1, n, Shown(p));
    GCHECK(p, t >= 1 && t <= PETSC_MAX_INT, "$Nodes: node tag %lld is outside [1, %d]", t, (int)PETSC_MAX_INT);
    for (int d = 0; d < 3; d++) {
      GCHECK(p, TokReal(&s, &x) == 1, "$Nodes: expected 'tag x y z' of node %lld, found '%s'", t, Shown(p));
      GCHECK(p, isfinite(x), "$Nodes: coordinate %d of node %lld is %s, not a finite number", d + 1, t, NonFinite(x));
    }
    GCHECK(p, AtEnd(s), "$Nodes: expected 'tag x y z' of node %lld, found more: '%s'", t, Shown(p));
    p->tags[i] = (PetscInt)t;
  }
  GCALL(p, ExpectEnd(p, "$EndNodes", "the nodes its count announces"));
  GCALL(p, NodesDone(p, LineOf22, &first, first - 2));
  PetscFunctionReturn(0);
}

/* The nodes of one element from *s: exactly ty->nnodes tags defined in $Nodes, its corners distinct. */
static PetscErrorCode ElementNodes(GmshCheck *p, const GmshType *ty, long long etag, const char *s)
{
  long long v[8];

  PetscFunctionBeginUser;
  for (int i = 0; i < ty->nnodes; i++) {
    long long t;
    int       r = TokInt(&s, &t);
    GCHECK(p, r >= 0, "element %lld: node tag %d is not an integer: '%s'", etag, i + 1, Shown(p));
    GCHECK(p, r == 1, "element %lld has %d node tags, its type %d needs %d: '%s'", etag, i, ty->type, ty->nnodes, Shown(p));
    GCHECK(p, NodeDefined(p, t), "element %lld names node %lld, which is not defined in $Nodes", etag, t);
    if (i < ty->nverts) {
      for (int j = 0; j < i; j++) GCHECK(p, v[j] != t, "element %lld names node %lld twice (a degenerate cell)", etag, t);
      v[i] = t;
    }
  }
  if (!AtEnd(s)) {
    int n = ty->nnodes;
    for (long long t; TokInt(&s, &t) != 0 && n < 1000000; n++) {}
    GFAIL(p, "element %lld has %d%s node tags, its type %d needs %d: '%s'", etag, n, AtEnd(s) ? "" : " or more", ty->type, ty->nnodes, Shown(p));
  }
  PetscFunctionReturn(0);
}

/* $Elements (MSH 4.1): header, then per entity block a header and `tag node...` lines. */
static PetscErrorCode CheckElements41(GmshCheck *p)
{
  long long       h[4], b[4];
  const long long lo[4] = {0, 0, 0, 0}, hi[4] = {p->fsize / 4, p->fsize / 4, PETSC_MAX_INT, PETSC_MAX_INT};
  const long long blo[4] = {0, 1, 1, 0}, bhi[4] = {3, PETSC_MAX_INT, PETSC_MAX_INT, p->fsize / 4};
  long long       count = 0;

  PetscFunctionBeginUser;
  GCALL(p, Line(p, "$Elements"));
  GCALL(p, LineInts(p, 4, h, lo, hi, "$Elements header", "numEntityBlocks numElements minElementTag maxElementTag"));
  GCHECK(p, h[1] == 0 || (h[2] >= 1 && h[2] <= h[3]), "$Elements header: minElementTag %lld and maxElementTag %lld must satisfy 1 <= min <= max", h[2], h[3]);
  GCHECK(p, h[0] <= h[1], "$Elements header: %lld entity blocks for %lld elements", h[0], h[1]);
  for (long long k = 0; k < h[0]; k++) {
    const GmshType *ty;
    PetscBool       found;
    GCALL(p, Line(p, "$Elements"));
    GCHECK(p, strcmp(Trimmed(p->buf), "$EndElements"), "found $EndElements after %lld of the %lld entity blocks the $Elements header announces", k, h[0]);
    GCALL(p, LineInts(p, 4, b, blo, bhi, "$Elements entity block header", "entityDim entityTag elementType numElementsInBlock"));
    ty = FindType(b[2]);
    GCHECK(p, ty, "$Elements block %lld: unknown or unsupported element type %lld", k + 1, b[2]);
    GCHECK(p, ty->dim == b[0], "$Elements block %lld: element type %lld has dimension %d, the block's entity dimension is %lld", k + 1, b[2], ty->dim, b[0]);
    PetscCall(FindEntity(p, b[0], b[1], &found));
    GCHECK(p, found, "$Elements block %lld: entity (dim %lld, tag %lld) is not defined in $Entities", k + 1, b[0], b[1]);
    GCHECK(p, count + b[3] <= h[1], "$Elements block %lld: %lld more elements exceed the %lld elements of the $Elements header", k + 1, b[3], h[1]);
    for (long long i = 0; i < b[3]; i++) {
      const char *s;
      long long   t;
      GCALL(p, Line(p, "$Elements"));
      s = p->buf;
      GCHECK(p, TokInt(&s, &t) == 1, "$Elements block %lld: expected element %lld of %lld ('tag node...'), found '%s'", k + 1, i + 1, b[3], Shown(p));
      GCHECK(p, t >= h[2] && t <= h[3], "$Elements block %lld: element tag %lld is outside [minElementTag, maxElementTag] = [%lld, %lld] of the $Elements header", k + 1, t, h[2], h[3]);
      GCALL(p, ElementNodes(p, ty, t, s));
    }
    count += b[3];
  }
  GCHECK(p, count == h[1], "$Elements: the %lld entity blocks hold %lld elements, the header announces %lld", h[0], count, h[1]);
  GCALL(p, ExpectEnd(p, "$EndElements", "the entity blocks its header announces"));
  PetscFunctionReturn(0);
}

/* $Elements (MSH 2.2): count, then `tag type numTags tag... node...` lines. */
static PetscErrorCode CheckElements22(GmshCheck *p)
{
  long long       n;
  const long long lo[1] = {0}, hi[1] = {p->fsize / 4};

  PetscFunctionBeginUser;
  GCALL(p, Line(p, "$Elements"));
  GCALL(p, LineInts(p, 1, &n, lo, hi, "$Elements count", "numElements"));
  for (long long i = 0; i < n; i++) {
    const char     *s;
    long long       t, type, nt, x;
    const GmshType *ty;
    GCALL(p, Line(p, "$Elements"));
    GCHECK(p, strcmp(Trimmed(p->buf), "$EndElements"), "found $EndElements after %lld of the %lld elements its count announces", i, n);
    s = p->buf;
    GCHECK(p, TokInt(&s, &t) == 1 && TokInt(&s, &type) == 1 && TokInt(&s, &nt) == 1, "$Elements: expected 'tag type numTags tag... node...' of element %lld, found '%s'", i + 1, Shown(p));
    GCHECK(p, t >= 1 && t <= PETSC_MAX_INT, "$Elements: element tag %lld is outside [1, %d]", t, (int)PETSC_MAX_INT);
    ty = FindType(type);
    GCHECK(p, ty, "element %lld: unknown or unsupported element type %lld", t, type);
    GCHECK(p, nt >= 0 && 1 + nt + ty->nnodes <= GMSH_V22_BUF, "element %lld: %lld tags are more than PETSc's reader can hold", t, nt);
    for (long long k = 0; k < nt; k++) GCHECK(p, TokInt(&s, &x) == 1 && x >= -(long long)PETSC_MAX_INT && x <= PETSC_MAX_INT, "element %lld: expected %lld integer tags, found '%s'", t, nt, Shown(p));
    GCALL(p, ElementNodes(p, ty, t, s));
  }
  GCALL(p, ExpectEnd(p, "$EndElements", "the elements its count announces"));
  PetscFunctionReturn(0);
}

/* $Periodic (read by PETSc unless -dm_plex_gmsh_periodic 0): every node pair must name defined nodes. */
static PetscErrorCode CheckPeriodic(GmshCheck *p, PetscBool v41)
{
  long long       n, v[3];
  const long long lo1[1] = {0}, hi1[1] = {p->fsize / 4};
  const long long lo3[3] = {0, -(long long)PETSC_MAX_INT, -(long long)PETSC_MAX_INT}, hi3[3] = {3, PETSC_MAX_INT, PETSC_MAX_INT};

  PetscFunctionBeginUser;
  GCALL(p, Line(p, "$Periodic"));
  GCALL(p, LineInts(p, 1, &n, lo1, hi1, "$Periodic count", "numPeriodicLinks"));
  for (long long l = 0; l < n; l++) {
    long long   m, a, t[2];
    const char *s;
    double      x;
    GCALL(p, Line(p, "$Periodic"));
    GCALL(p, LineInts(p, 3, v, lo3, hi3, "$Periodic link", "entityDim entityTag entityTagPrimary"));
    GCALL(p, Line(p, "$Periodic"));
    s = p->buf;
    if (v41) {
      /* numAffine value... */
      GCHECK(p, TokInt(&s, &a) == 1 && a >= 0 && a <= 16, "$Periodic link %lld: expected 'numAffine value...', found '%s'", l + 1, Shown(p));
      for (long long k = 0; k < a; k++) GCHECK(p, TokReal(&s, &x) == 1, "$Periodic link %lld: expected %lld affine values, found '%s'", l + 1, a, Shown(p));
      GCHECK(p, AtEnd(s), "$Periodic link %lld: expected %lld affine values, found more: '%s'", l + 1, a, Shown(p));
      GCALL(p, Line(p, "$Periodic"));
    } else if (!strncmp(Trimmed(s), "Affine", 6)) {
      GCALL(p, Line(p, "$Periodic"));
    }
    GCALL(p, LineInts(p, 1, &m, lo1, hi1, "$Periodic node count", "numCorrespondingNodes"));
    for (long long k = 0; k < m; k++) {
      const long long lo2[2] = {1, 1}, hi2[2] = {PETSC_MAX_INT, PETSC_MAX_INT};
      GCALL(p, Line(p, "$Periodic"));
      GCALL(p, LineInts(p, 2, t, lo2, hi2, "$Periodic node pair", "nodeTag nodeTagPrimary"));
      GCHECK(p, NodeDefined(p, t[0]) && NodeDefined(p, t[1]), "$Periodic link %lld: node %lld is not defined in $Nodes", l + 1, NodeDefined(p, t[0]) ? t[1] : t[0]);
    }
  }
  GCALL(p, ExpectEnd(p, "$EndPeriodic", "the links its count announces"));
  PetscFunctionReturn(0);
}

/* The whole file, in PETSc's order: $MeshFormat, [$PhysicalNames], $Entities (4.1), $Nodes, $Elements, [$Periodic]. */
static PetscErrorCode CheckFile(GmshCheck *p)
{
  const char *s;
  double      version;
  long long   ftype, dsize;
  PetscBool   eof, v41;

  PetscFunctionBeginUser;
  GCALL(p, NextSection(p, &eof));
  GCHECK(p, !eof, "no $MeshFormat section: not a gmsh file");
  GCHECK(p, !strcmp(Trimmed(p->buf), "$MeshFormat"), "not a gmsh file: expected $MeshFormat, found '%s'", Shown(p));
  GCALL(p, Line(p, "$MeshFormat"));
  s = p->buf;
  GCHECK(p, TokReal(&s, &version) == 1 && TokInt(&s, &ftype) == 1 && TokInt(&s, &dsize) == 1, "$MeshFormat: expected 'version file-type data-size', found '%s'", Shown(p));
  if (version != 2.2 && version != 4.0 && version != 4.1) {
    char        v[32];
    const char *t = Trimmed(p->buf);
    size_t      n = strcspn(t, " \t");
    PetscCall(PetscStrncpy(v, t, PetscMin(n + 1, sizeof(v))));
    GFAIL(p, "$MeshFormat: version %s; PETSc's gmsh reader reads 2.2, 4.0 and 4.1 (gmsh -format msh41 or msh22)", v);
  }
  GCHECK(p, ftype == 0 || ftype == 1, "$MeshFormat: file-type %lld, must be 0 (ASCII) or 1 (binary)", ftype);
  GCHECK(p, dsize == 8 || (version == 4.1 && dsize == 4), "$MeshFormat: data-size %lld is not valid for this version (%s)", dsize, version == 4.1 ? "4 or 8" : "8");
  /* binary files: the header only, PETSc reads the rest (a binary reader would double this file); MSH 4.0 (obsolete,
     gmsh 4.0 only) likewise */
  if (ftype == 1 || version == 4.0) PetscFunctionReturn(0);
  GCHECK(p, AtEnd(s), "$MeshFormat: expected 'version file-type data-size', found more: '%s'", Shown(p));
  GCALL(p, ExpectEnd(p, "$EndMeshFormat", "the format line"));
  v41 = version == 4.1 ? PETSC_TRUE : PETSC_FALSE;

  GCALL(p, NextSection(p, &eof));
  GCHECK(p, !eof, "the file ends after $MeshFormat: no $Nodes and $Elements");
  if (!strcmp(Trimmed(p->buf), "$PhysicalNames")) {
    GCALL(p, CheckPhysicalNames(p));
    GCALL(p, NextSection(p, &eof));
    GCHECK(p, !eof, "the file ends after $PhysicalNames: no $Nodes and $Elements");
  }
  if (v41) {
    GCHECK(p, !strcmp(Trimmed(p->buf), "$Entities"), "expected section $Entities (MSH 4.1), found '%s'", Shown(p));
    GCALL(p, CheckEntities(p));
    GCALL(p, ExpectSection(p, "$Nodes", "$EndEntities"));
    GCALL(p, CheckNodes41(p));
  } else {
    GCHECK(p, !strcmp(Trimmed(p->buf), "$Nodes"), "expected section $Nodes, found '%s'", Shown(p));
    GCALL(p, CheckNodes22(p));
  }
  GCALL(p, ExpectSection(p, "$Elements", "$EndNodes"));
  if (v41) GCALL(p, CheckElements41(p));
  else GCALL(p, CheckElements22(p));
  /* PETSc reads a $Periodic section that follows and ignores everything else after $EndElements */
  GCALL(p, NextSection(p, &eof));
  if (!eof && !strcmp(Trimmed(p->buf), "$Periodic")) GCALL(p, CheckPeriodic(p, v41));
  PetscFunctionReturn(0);
}

/* Validate the gmsh file fname (a name ending in .msh, which DMPlexCreateFromFile() reads with DMPlexCreateGmsh())
   on rank 0; a structural error stops every rank with the file, the line and what is wrong. */
PetscErrorCode SgGmshCheckFile(MPI_Comm comm, const char fname[])
{
  PetscMPIInt rank;
  char        msg[sizeof(((GmshCheck *)0)->msg)] = "";
  PetscBool   gmsh;

  PetscFunctionBeginUser;
  PetscCall(PetscStrendswith(fname, ".msh", &gmsh));
  if (!gmsh) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    GmshCheck   p;
    struct stat st;

    PetscCall(PetscMemzero(&p, sizeof(p)));
    p.fname = fname;
    p.fp    = fopen(fname, "r");
    if (!p.fp) PetscCall(PetscSNPrintf(msg, sizeof(msg), "cannot open it: %s", strerror(errno)));
    else {
      p.fsize = fstat(fileno(p.fp), &st) == 0 ? (long long)st.st_size : (long long)PETSC_MAX_INT;
      PetscCall(CheckFile(&p));
      if (p.bad) PetscCall(PetscStrncpy(msg, p.msg, sizeof(msg)));
      fclose(p.fp);
    }
    free(p.buf);
    for (int d = 0; d < 4; d++) PetscCall(PetscFree(p.ent[d]));
    PetscCall(PetscFree(p.tags));
    PetscCall(PetscFree(p.bits));
  }
  PetscCallMPI(MPI_Bcast(msg, (PetscMPIInt)sizeof(msg), MPI_CHAR, 0, comm));
  PetscCheck(!msg[0], comm, PETSC_ERR_FILE_UNEXPECTED, "-dm_plex_filename: cannot read mesh file '%s': %s", fname, msg);
  PetscFunctionReturn(0);
}
