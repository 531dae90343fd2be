/* geometry.c: the refined boundary on the true geometry (-dm_refine_geometry FILE under the mesh's prefix, issue 30).
   A regular refinement (DMRefine, -dm_refine) puts a new vertex at the midpoint of an edge, so a refined curved face
   is the coarse mesh's facets and the error of the geometry does not shrink with h. With a CAD file (.geo, .step,
   .brep, read by gmsh) whose physical groups of dimension dim - 1 carry the mesh's "Face Sets" values, every
   refinement the mesh makes (fem/mesh.c, MeshRefineNested) is followed by SgGeometrySnap: each vertex of a boundary
   face of a value that is a group of the file moves to the closest point of that group's CAD faces (3D) or curves
   (2D). A vertex of faces of two groups (the sphere's rim on a symmetry plane) moves to the closest of the CAD
   entities one dimension lower (curves in 3D, points in 2D) that bound an entity of each of its groups; a vertex of
   three or more groups (a CAD corner, a vertex of the coarse mesh) or of two without a common CAD entity stays. The
   groups of a vertex are those of its faces on any rank (a reduction over the point SF), so a vertex shared by ranks
   moves to the same point on each. The unrefined mesh's vertices (gmsh's nodes) are checked, not moved.
   gmsh starts once per process (SgGmshStart, shared with the CAD obstacle, contact/obstacle_cad.c); the file is read
   into a model of its own (gmshModelAdd), removed when the mesh is made, the current model (a CAD obstacle's) restored
   with the mesh options a .geo may set. */
#include "fem/femimpl.h"
#include <petscsf.h>
#include <gmshc.h>

#define SNAP_MAX_GROUPS 30   /* groups of the file that are Face Sets values (a bit each in an int mask) */
#define SNAP_MAX_MOVE   0.25 /* a move longer than this fraction of the vertex's shortest edge: the wrong file */

static PetscBool gmsh_up = PETSC_FALSE;

static PetscErrorCode GmshFinalize(void)
{
  int ierr;

  PetscFunctionBeginUser;
  if (gmsh_up) gmshFinalize(&ierr);
  gmsh_up = PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* gmsh once per process, quiet unless verbose; finalized by PetscFinalize */
PetscErrorCode SgGmshStart(MPI_Comm comm, PetscBool verbose)
{
  int ierr;

  PetscFunctionBeginUser;
  if (!gmsh_up) {
    gmshInitialize(0, NULL, 0, &ierr);
    PetscCheck(!ierr, comm, PETSC_ERR_LIB, "gmsh: gmshInitialize failed (%d)", ierr);
    gmsh_up = PETSC_TRUE;
    PetscCall(PetscRegisterFinalize(GmshFinalize));
  }
  gmshOptionSetNumber("General.Terminal", verbose ? 1 : 0, &ierr);
  gmshOptionSetNumber("General.Verbosity", verbose ? 5 : 0, &ierr);
  gmshLoggerStart(&ierr);
  PetscFunctionReturn(0);
}

/* gmsh's closest point cp to x on the entity (dim, tag) of the current model, with its first parametric coordinates
   (param[k] for k < min(2, gmsh's count); param may be NULL); found: PETSC_FALSE if gmsh found none (NULL: an error) */
PetscErrorCode SgGmshClosestPoint(int dim, int tag, const double x[3], double cp[3], double param[2], PetscBool *found)
{
  double   *c = NULL, *par = NULL;
  size_t    nc = 0, npar = 0;
  int       ierr;
  PetscBool ok;

  PetscFunctionBeginUser;
  gmshModelGetClosestPoint(dim, tag, (double *)x, 3, &c, &nc, &par, &npar, &ierr);
  ok = (PetscBool)(!ierr && nc == 3);
  if (ok) {
    for (int q = 0; q < 3; q++) cp[q] = c[q];
    for (size_t k = 0; param && k < npar && k < 2; k++) param[k] = par[k];
  }
  if (c) gmshFree(c);
  if (par) gmshFree(par);
  if (found) *found = ok;
  else PetscCheck(ok, PETSC_COMM_SELF, PETSC_ERR_LIB, "gmsh found no closest point to (%g, %g, %g) on the entity of dimension %d, tag %d", x[0], x[1], x[2], dim, tag);
  PetscFunctionReturn(0);
}

/* gmsh's last error message (or a general one) */
void SgGmshError(char msg[], size_t len)
{
  char *err = NULL;
  int   ierr;

  gmshLoggerGetLastError(&err, &ierr);
  if (!ierr && err && err[0]) snprintf(msg, len, "%s", err);
  else snprintf(msg, len, "gmsh could not read it");
  if (err) gmshFree(err);
}

/* the mesh options a .geo may set, kept for the CAD obstacle's tessellation (global in gmsh, not per model) */
static const char *const SnapKeptOptions[] = {"Mesh.MeshSizeExtendFromBoundary", "Mesh.MeshSizeFromPoints", "Mesh.MeshSizeFromCurvature", "Mesh.MeshSizeMin", "Mesh.MeshSizeMax", "Mesh.MeshSizeFactor", "Mesh.Algorithm", "Mesh.Algorithm3D", "Mesh.Binary", "Geometry.Tolerance"};
#define SNAP_NKEPT ((int)(sizeof(SnapKeptOptions) / sizeof(SnapKeptOptions[0])))

struct _n_SgGeometry {
  MPI_Comm  comm;
  char      file[PETSC_MAX_PATH_LEN];
  char      opt[300]; /* the option's name with the prefix, for messages */
  char      prev[256];
  PetscBool hadprev;
  double    kept[SNAP_NKEPT];
  PetscInt  dim, ngroups;
  int       tag[SNAP_MAX_GROUPS];
  int      *ent[SNAP_MAX_GROUPS], *bnd[SNAP_MAX_GROUPS]; /* the group's entities (dim - 1), their boundaries (dim - 2) */
  size_t    nent[SNAP_MAX_GROUPS], nbnd[SNAP_MAX_GROUPS];
  PetscInt  nmoved;  /* vertices moved by the last snap (all ranks) */
  PetscReal maxmove; /* their longest move, the unrefined mesh's largest distance (SgGeometryCheck) */
};

/* The file read into a model of its own; its groups of dimension dim - 1 that are values of dm's "Face Sets" (an
   error naming the option and the file if the file cannot be read or has none). */
PetscErrorCode SgGeometryCreate(DM dm, const char prefix[], const char file[], SgGeometry *geo)
{
  SgGeometry g;
  MPI_Comm   comm = PetscObjectComm((PetscObject)dm);
  int        ierr, *dt = NULL;
  size_t     ndt = 0;
  char       msg[512], *cur = NULL, have[256] = "";
  DMLabel    fs;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&g));
  *geo    = g;
  g->comm = comm;
  PetscCall(DMGetDimension(dm, &g->dim));
  PetscCall(PetscStrncpy(g->file, file, sizeof(g->file)));
  PetscCall(PetscSNPrintf(g->opt, sizeof(g->opt), "-%sdm_refine_geometry", prefix ? prefix : ""));
  {
    FILE *f = fopen(file, "r");
    PetscCheck(f, comm, PETSC_ERR_FILE_OPEN, "%s %s: cannot open the file", g->opt, file);
    fclose(f);
  }
  PetscCall(SgGmshStart(comm, PETSC_FALSE));
  for (int k = 0; k < SNAP_NKEPT; k++) gmshOptionGetNumber(SnapKeptOptions[k], &g->kept[k], &ierr);
  gmshModelGetCurrent(&cur, &ierr);
  if (!ierr && cur) {
    PetscCall(PetscStrncpy(g->prev, cur, sizeof(g->prev)));
    g->hadprev = PETSC_TRUE;
  }
  if (cur) gmshFree(cur);
  gmshModelAdd("sg_refine_geometry", &ierr);
  PetscCheck(!ierr, comm, PETSC_ERR_LIB, "%s %s: gmsh could not add a model", g->opt, file);
  gmshMerge(file, &ierr);
  if (ierr) SgGmshError(msg, sizeof(msg));
  PetscCheck(!ierr, comm, PETSC_ERR_USER_INPUT, "%s %s: %s", g->opt, file, msg);
  PetscCall(DMGetLabel(dm, "Face Sets", &fs));
  gmshModelGetPhysicalGroups(&dt, &ndt, (int)g->dim - 1, &ierr);
  for (size_t k = 0; k + 1 < ndt && !ierr; k += 2) {
    PetscInt n = 0, tag = dt[k + 1];
    if (fs) {
      IS is;
      PetscCall(DMLabelGetStratumIS(fs, tag, &is));
      if (is) PetscCall(ISGetLocalSize(is, &n));
      PetscCall(ISDestroy(&is));
    }
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPIU_INT, MPI_SUM, comm));
    {
      size_t len = strlen(have);
      PetscCall(PetscSNPrintf(have + len, sizeof(have) - len, "%s%d", len ? ", " : "", dt[k + 1]));
    }
    if (!n) continue;
    PetscCheck(g->ngroups < SNAP_MAX_GROUPS, comm, PETSC_ERR_SUP, "%s %s: more than %d of its physical groups are Face Sets values", g->opt, file, SNAP_MAX_GROUPS);
    g->tag[g->ngroups] = dt[k + 1];
    gmshModelGetEntitiesForPhysicalGroup((int)g->dim - 1, dt[k + 1], &g->ent[g->ngroups], &g->nent[g->ngroups], &ierr);
    PetscCheck(!ierr, comm, PETSC_ERR_LIB, "%s %s: gmsh gave no entities of physical group %d", g->opt, file, dt[k + 1]);
    { /* the entities one dimension lower that bound them */
      int   *in, *out = NULL;
      size_t nout = 0;
      PetscCall(PetscMalloc1(2 * g->nent[g->ngroups] + 1, &in));
      for (size_t e = 0; e < g->nent[g->ngroups]; e++) {
        in[2 * e]     = (int)g->dim - 1;
        in[2 * e + 1] = g->ent[g->ngroups][e];
      }
      gmshModelGetBoundary(in, 2 * g->nent[g->ngroups], &out, &nout, 0, 0, 0, &ierr);
      PetscCall(PetscFree(in));
      PetscCall(PetscMalloc1(nout / 2 + 1, &g->bnd[g->ngroups]));
      for (size_t e = 0; e + 1 < nout; e += 2) g->bnd[g->ngroups][g->nbnd[g->ngroups]++] = out[e + 1];
      if (out) gmshFree(out);
    }
    g->ngroups++;
  }
  if (dt) gmshFree(dt);
  PetscCheck(g->ngroups > 0, comm, PETSC_ERR_USER_INPUT, "%s %s: none of its physical %s (%s) is a value of the mesh's \"Face Sets\": the file is not this mesh's geometry", g->opt, file, g->dim == 3 ? "surfaces" : "curves", have[0] ? have : "none");
  PetscFunctionReturn(0);
}

/* The file's model removed, the previous current model and the kept mesh options restored. */
PetscErrorCode SgGeometryDestroy(SgGeometry *geo)
{
  SgGeometry g = *geo;
  int        ierr;

  PetscFunctionBeginUser;
  if (!g) PetscFunctionReturn(0);
  for (PetscInt k = 0; k < g->ngroups; k++) {
    if (g->ent[k]) gmshFree(g->ent[k]);
    PetscCall(PetscFree(g->bnd[k]));
  }
  gmshModelSetCurrent("sg_refine_geometry", &ierr);
  if (!ierr) gmshModelRemove(&ierr);
  if (g->hadprev) gmshModelSetCurrent(g->prev, &ierr);
  for (int k = 0; k < SNAP_NKEPT; k++) gmshOptionSetNumber(SnapKeptOptions[k], g->kept[k], &ierr);
  PetscCall(PetscFree(*geo));
  PetscFunctionReturn(0);
}

/* The closest point z to x of the entities tags[0..n-1] of dimension d (points by their coordinates); PETSC_FALSE if
   gmsh found none */
static PetscBool Closest(int d, const int tags[], size_t n, const double x[3], double z[3])
{
  double best = PETSC_MAX_REAL;

  for (size_t e = 0; e < n; e++) {
    double c[3], r = 0;
    int    ierr;
    if (d == 0) {
      double hi[3];
      gmshModelGetBoundingBox(0, tags[e], &c[0], &c[1], &c[2], &hi[0], &hi[1], &hi[2], &ierr);
    } else {
      PetscBool found;
      ierr = SgGmshClosestPoint(d, tags[e], x, c, NULL, &found) || !found; /* none: the next entity */
    }
    if (ierr) continue;
    for (int q = 0; q < 3; q++) r += (c[q] - x[q]) * (c[q] - x[q]);
    if (r < best) {
      best = r;
      for (int q = 0; q < 3; q++) z[q] = c[q];
    }
  }
  return (PetscBool)(best < PETSC_MAX_REAL);
}

/* Move (move = PETSC_TRUE: after a refinement) or measure (the unrefined mesh) the vertices of the groups' faces;
   the longest move against the vertex's shortest edge is checked on all ranks. */
static PetscErrorCode Snap(SgGeometry g, DM dm, PetscBool move)
{
  const PetscInt dim = g->dim;
  DMLabel        fs;
  PetscInt       pStart, pEnd, vStart, vEnd, eStart, eEnd, nmoved = 0;
  int           *mask, *root;
  PetscReal     *hmin;
  PetscSection   cs;
  Vec            cl;
  PetscScalar   *xa;
  PetscSF        sf;
  struct {
    double r;
    int    rank;
  } worst        = {0, 0};
  double   wx[5] = {0, 0, 0, 0, 0}, dmax = 0; /* the worst vertex: x, move, edge */
  MPI_Comm comm = g->comm;

  PetscFunctionBeginUser;
  PetscCall(DMGetLabel(dm, "Face Sets", &fs));
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 1, &eStart, &eEnd));
  PetscCall(PetscCalloc2(pEnd - pStart, &mask, pEnd - pStart, &root));
  for (PetscInt k = 0; k < g->ngroups && fs; k++) {
    IS              is;
    const PetscInt *f;
    PetscInt        nf = 0;
    PetscCall(DMLabelGetStratumIS(fs, g->tag[k], &is));
    if (!is) continue;
    PetscCall(ISGetLocalSize(is, &nf));
    PetscCall(ISGetIndices(is, &f));
    for (PetscInt i = 0; i < nf; i++) {
      PetscInt *cl = NULL, ncl;
      PetscCall(DMPlexGetTransitiveClosure(dm, f[i], PETSC_TRUE, &ncl, &cl));
      for (PetscInt j = 0; j < ncl; j++)
        if (cl[2 * j] >= vStart && cl[2 * j] < vEnd) mask[cl[2 * j] - pStart] |= 1 << k;
      PetscCall(DMPlexRestoreTransitiveClosure(dm, f[i], PETSC_TRUE, &ncl, &cl));
    }
    PetscCall(ISRestoreIndices(is, &f));
    PetscCall(ISDestroy(&is));
  }
  /* the groups of a vertex from every rank's faces: or-reduced to the owner, sent back to the ghosts */
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscArraycpy(root, mask, pEnd - pStart));
  PetscCall(PetscSFReduceBegin(sf, MPI_INT, mask, root, MPI_BOR));
  PetscCall(PetscSFReduceEnd(sf, MPI_INT, mask, root, MPI_BOR));
  PetscCall(PetscSFBcastBegin(sf, MPI_INT, root, mask, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(sf, MPI_INT, root, mask, MPI_REPLACE));
  /* each vertex's shortest edge */
  PetscCall(PetscMalloc1(vEnd - vStart, &hmin));
  for (PetscInt v = 0; v < vEnd - vStart; v++) hmin[v] = PETSC_MAX_REAL;
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &cl));
  PetscCall(VecGetArray(cl, &xa));
  for (PetscInt e = eStart; e < eEnd; e++) {
    const PetscInt *cone;
    PetscInt        o0, o1;
    PetscReal       h = 0;
    PetscCall(DMPlexGetCone(dm, e, &cone));
    PetscCall(PetscSectionGetOffset(cs, cone[0], &o0));
    PetscCall(PetscSectionGetOffset(cs, cone[1], &o1));
    for (PetscInt d = 0; d < dim; d++) h += PetscSqr(PetscRealPart(xa[o0 + d] - xa[o1 + d]));
    h                      = PetscSqrtReal(h);
    hmin[cone[0] - vStart] = PetscMin(hmin[cone[0] - vStart], h);
    hmin[cone[1] - vStart] = PetscMin(hmin[cone[1] - vStart], h);
  }
  for (PetscInt v = vStart; v < vEnd; v++) {
    const int m  = mask[v - pStart];
    int       ng = 0, k0 = -1, *cand = NULL;
    size_t    ncand = 0;
    double    x[3] = {0, 0, 0}, z[3], r = 0;
    PetscInt  off;
    PetscBool found;
    if (!m) continue;
    for (int k = 0; k < g->ngroups; k++)
      if (m & (1 << k)) {
        if (k0 < 0) k0 = k;
        ng++;
      }
    if (ng > 2) continue; /* a CAD corner */
    PetscCall(PetscSectionGetOffset(cs, v, &off));
    for (PetscInt d = 0; d < dim; d++) x[d] = PetscRealPart(xa[off + d]);
    if (ng == 1) found = Closest((int)dim - 1, g->ent[k0], g->nent[k0], x, z);
    else { /* the entities bounding both groups */
      int k1 = k0 + 1;
      while (!(m & (1 << k1))) k1++;
      PetscCall(PetscMalloc1(g->nbnd[k0] + 1, &cand));
      for (size_t a = 0; a < g->nbnd[k0]; a++)
        for (size_t b = 0; b < g->nbnd[k1]; b++)
          if (g->bnd[k0][a] == g->bnd[k1][b]) {
            cand[ncand++] = g->bnd[k0][a];
            break;
          }
      found = ncand ? Closest((int)dim - 2, cand, ncand, x, z) : PETSC_FALSE;
      PetscCall(PetscFree(cand));
    }
    if (!found) continue;
    if (dim == 2) z[2] = 0;
    for (PetscInt d = 0; d < dim; d++) r += PetscSqr(z[d] - x[d]);
    r    = PetscSqrtReal(r);
    dmax = PetscMax(dmax, r);
    if (r / hmin[v - vStart] > worst.r) {
      worst.r = r / hmin[v - vStart];
      for (int q = 0; q < 3; q++) wx[q] = x[q];
      wx[3] = r;
      wx[4] = hmin[v - vStart];
    }
    if (move) {
      for (PetscInt d = 0; d < dim; d++) xa[off + d] = z[d];
      PetscCall(DMSetLabelValue(dm, "SgSnapped", v, 1));
      nmoved++;
    }
  }
  PetscCall(VecRestoreArray(cl, &xa));
  PetscCall(PetscFree(hmin));
  PetscCall(PetscFree2(mask, root));
  { /* the worst vertex on all ranks, for the message */
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    worst.rank = rank;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &worst, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm));
    PetscCallMPI(MPI_Bcast(wx, 5, MPI_DOUBLE, worst.rank, comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &dmax, 1, MPI_DOUBLE, MPI_MAX, comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nmoved, 1, MPIU_INT, MPI_SUM, comm));
  }
  PetscCheck(worst.r <= SNAP_MAX_MOVE, comm, PETSC_ERR_USER_INPUT, "%s %s: the mesh's vertex (%g, %g, %g) on its faces of the file's physical groups is %g from them, %g times its shortest edge %g (at most %g %s): the file is not this mesh's geometry", g->opt, g->file, wx[0], wx[1], wx[2], wx[3], worst.r, wx[4], SNAP_MAX_MOVE, move ? "after a refinement" : "in the unrefined mesh");
  g->nmoved  = nmoved;
  g->maxmove = dmax;
  if (move) {
    PetscCall(DMCreateLabel(dm, "SgSnapped")); /* on every rank, moved vertices or not */
    PetscCall(DMSetCoordinatesLocal(dm, cl));  /* the global coordinates again from the local ones */
    PetscCall(PetscInfo(dm, "%s: %" PetscInt_FMT " vertices moved onto the geometry, by at most %g (%g of the shortest edge)\n", g->opt, nmoved, dmax, worst.r));
  } else PetscCall(PetscInfo(dm, "%s: the unrefined mesh's boundary vertices are at most %g from the geometry (%g of the shortest edge)\n", g->opt, dmax, worst.r));
  PetscFunctionReturn(0);
}

/* After a refinement: the groups' vertices onto the geometry, and marked in the fine mesh's label "SgSnapped" (value
   1), which SgMeshRefinementMap reads (a moved vertex is no longer its edge's midpoint; DMClone keeps labels, composed
   objects not). */
PetscErrorCode SgGeometrySnap(SgGeometry g, DM coarse, DM fine)
{
  PetscFunctionBeginUser;
  (void)coarse;
  PetscCall(Snap(g, fine, PETSC_TRUE));
  PetscFunctionReturn(0);
}

/* The unrefined mesh: its vertices on the groups' faces within SNAP_MAX_MOVE of their shortest edge of the geometry
   (else the file is the wrong one); the largest distance in *dist. */
PetscErrorCode SgGeometryCheck(SgGeometry g, DM dm, PetscReal *dist)
{
  PetscFunctionBeginUser;
  PetscCall(Snap(g, dm, PETSC_FALSE));
  if (dist) *dist = g->maxmove;
  PetscFunctionReturn(0);
}
