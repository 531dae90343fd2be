/* mesh.c: the DMPlex mesh (structured simplex box or gmsh file), boundary parts and the P1 displacement layout. */
#include "signorini.h"

const char *const SgBoxDiagonals[] = {"right", "left", "SgBoxDiagonal", "SG_BOX_", NULL};
typedef enum { SG_BOX_RIGHT, SG_BOX_LEFT } SgBoxDiagonal;

/* Face markers follow DMPlexCreateBoxMesh(): 2D bottom 1, right 2, top 3, left 4;
   3D bottom 1, top 2, front 3, back 4, right 5, left 6 ("Face Sets"). */
static PetscInt BoxFaceMarker(PetscInt dim, PetscInt axis, PetscBool upper)
{
  static const PetscInt m2[2][2] = {
    {4, 2},
    {1, 3}
  };
  static const PetscInt m3[3][2] = {
    {6, 5},
    {3, 4},
    {1, 2}
  };
  return dim == 2 ? m2[axis][upper] : m3[axis][upper];
}

/* Structured simplex box: every square split in two triangles, every cube in the six Kuhn tetrahedra.
   PETSc 3.18 as packaged by Debian has no Triangle/TetGen, so DMPlexCreateBoxMesh() cannot make simplices. */
static PetscErrorCode BoxMeshCreate(MPI_Comm comm, PetscInt dim, const PetscInt faces[], const PetscReal lo[], const PetscReal hi[], SgBoxDiagonal diag, DM *dm)
{
  PetscMPIInt rank;
  PetscInt    nv = 0, nc = 0, *cells = NULL;
  PetscReal  *coords = NULL;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    const PetscInt nx = faces[0], ny = faces[1], nz = dim == 3 ? faces[2] : 1;
    PetscInt       c = 0;

    nv = (nx + 1) * (ny + 1) * (dim == 3 ? nz + 1 : 1);
    nc = dim == 2 ? 2 * nx * ny : 6 * nx * ny * nz;
    PetscCall(PetscMalloc2(nv * dim, &coords, nc * (dim + 1), &cells));
    for (PetscInt k = 0; k < (dim == 3 ? nz + 1 : 1); k++)
      for (PetscInt j = 0; j <= ny; j++)
        for (PetscInt i = 0; i <= nx; i++) {
          const PetscInt v = (k * (ny + 1) + j) * (nx + 1) + i;
          coords[v * dim + 0] = lo[0] + (hi[0] - lo[0]) * i / nx;
          coords[v * dim + 1] = lo[1] + (hi[1] - lo[1]) * j / ny;
          if (dim == 3) coords[v * dim + 2] = lo[2] + (hi[2] - lo[2]) * k / nz;
        }
    if (dim == 2) {
      for (PetscInt j = 0; j < ny; j++)
        for (PetscInt i = 0; i < nx; i++) {
          const PetscInt v00 = j * (nx + 1) + i, v10 = v00 + 1, v01 = v00 + nx + 1, v11 = v01 + 1;
          const PetscInt tr[2][2][3] = {
            {{v00, v10, v11}, {v00, v11, v01}},
            {{v00, v10, v01}, {v10, v11, v01}}
          };
          for (PetscInt t = 0; t < 2; t++)
            for (PetscInt a = 0; a < 3; a++) cells[c * 3 + t * 3 + a] = tr[diag][t][a];
          c += 2;
        }
    } else {
      /* Kuhn: the tetrahedra along the paths from corner (0,0,0) to (1,1,1); conforming across cubes */
      static const PetscInt perm[6][3] = {
        {0, 1, 2},
        {0, 2, 1},
        {1, 0, 2},
        {1, 2, 0},
        {2, 0, 1},
        {2, 1, 0}
      };
      for (PetscInt k = 0; k < nz; k++)
        for (PetscInt j = 0; j < ny; j++)
          for (PetscInt i = 0; i < nx; i++)
            for (PetscInt p = 0; p < 6; p++) {
              PetscInt ijk[3] = {i, j, k}, tv[4];
              for (PetscInt a = 0; a < 4; a++) {
                if (a > 0) ijk[perm[p][a - 1]]++;
                tv[a] = (ijk[2] * (ny + 1) + ijk[1]) * (nx + 1) + ijk[0];
              }
              /* odd permutations give negatively oriented tetrahedra: swap two vertices */
              if (p == 1 || p == 2 || p == 5) {
                const PetscInt t = tv[2];
                tv[2]            = tv[3];
                tv[3]            = t;
              }
              for (PetscInt a = 0; a < 4; a++) cells[c * 4 + a] = tv[a];
              c++;
            }
    }
  }
  PetscCall(DMPlexCreateFromCellListPetsc(comm, dim, nc, nv, dim + 1, PETSC_TRUE, cells, dim, coords, dm));
  PetscCall(PetscFree2(coords, cells));
  PetscCall(DMCreateLabel(*dm, "Face Sets"));
  if (rank == 0) {
    DMLabel         bd, fs;
    IS              is;
    const PetscInt *faces_;
    PetscInt        nf;
    Vec             cl;
    PetscSection    cs;
    const PetscScalar *ca;

    PetscInt        vStart, vEnd;

    PetscCall(DMPlexGetDepthStratum(*dm, 0, &vStart, &vEnd));
    PetscCall(DMLabelCreate(PETSC_COMM_SELF, "boundary", &bd));
    PetscCall(DMPlexMarkBoundaryFaces(*dm, 1, bd));
    PetscCall(DMGetLabel(*dm, "Face Sets", &fs));
    PetscCall(DMGetCoordinatesLocal(*dm, &cl));
    PetscCall(DMGetCoordinateSection(*dm, &cs));
    PetscCall(VecGetArrayRead(cl, &ca));
    PetscCall(DMLabelGetStratumIS(bd, 1, &is));
    PetscCall(ISGetLocalSize(is, &nf));
    PetscCall(ISGetIndices(is, &faces_));
    for (PetscInt f = 0; f < nf; f++) {
      PetscInt *cl_ = NULL, ncl, nfv = 0;
      PetscReal cen[3] = {0, 0, 0};

      PetscCall(DMPlexGetTransitiveClosure(*dm, faces_[f], PETSC_TRUE, &ncl, &cl_));
      for (PetscInt q = 0; q < 2 * ncl; q += 2) {
        PetscInt off;
        if (cl_[q] < vStart || cl_[q] >= vEnd) continue;
        PetscCall(PetscSectionGetOffset(cs, cl_[q], &off));
        for (PetscInt d = 0; d < dim; d++) cen[d] += PetscRealPart(ca[off + d]);
        nfv++;
      }
      PetscCall(DMPlexRestoreTransitiveClosure(*dm, faces_[f], PETSC_TRUE, &ncl, &cl_));
      for (PetscInt d = 0; d < dim; d++) {
        const PetscReal x = cen[d] / nfv, tol = 1e-8 * (hi[d] - lo[d]);
        if (PetscAbsReal(x - lo[d]) < tol) PetscCall(DMLabelSetValue(fs, faces_[f], BoxFaceMarker(dim, d, PETSC_FALSE)));
        if (PetscAbsReal(x - hi[d]) < tol) PetscCall(DMLabelSetValue(fs, faces_[f], BoxFaceMarker(dim, d, PETSC_TRUE)));
      }
    }
    PetscCall(ISRestoreIndices(is, &faces_));
    PetscCall(ISDestroy(&is));
    PetscCall(VecRestoreArrayRead(cl, &ca));
    PetscCall(DMLabelDestroy(&bd));
  }
  PetscFunctionReturn(0);
}

/* Check on rank 0 that a mesh file can be read, so a wrong path is reported with the option that named it. */
static PetscErrorCode CheckMeshFile(MPI_Comm comm, const char fname[])
{
  PetscMPIInt rank;
  PetscInt    status = 0; /* 0 ok, 1 missing, 2 empty */

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    FILE *fp = fopen(fname, "rb");
    if (!fp) status = 1;
    else {
      if (fgetc(fp) == EOF) status = 2;
      fclose(fp);
    }
  }
  PetscCallMPI(MPI_Bcast(&status, 1, MPIU_INT, 0, comm));
  PetscCheck(status != 1, comm, PETSC_ERR_FILE_OPEN, "-dm_plex_filename: cannot open mesh file '%s'", fname);
  PetscCheck(status != 2, comm, PETSC_ERR_FILE_UNEXPECTED, "-dm_plex_filename: mesh file '%s' is empty", fname);
  PetscFunctionReturn(0);
}

/* Create the distributed simplex mesh from a gmsh file (-dm_plex_filename) or the structured box (-box_*). */
PetscErrorCode SgMeshCreateDM(MPI_Comm comm, DM *dm)
{
  char             fname[PETSC_MAX_PATH_LEN] = "";
  PetscBool        file;
  PetscInt         dim = 2, nfaces = 3, nlo = 3, nhi = 3, faces[3] = {10, 10, 10};
  PetscReal        lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  SgBoxDiagonal    diag = SG_BOX_RIGHT;
  PetscPartitioner part;
  PetscInt         cStart, cEnd, ncells, cdim;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(SG_MeshSetUp, 0, 0, 0, 0));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-dm_plex_filename", fname, sizeof(fname), &file));
  PetscOptionsBegin(comm, NULL, "Structured simplex box mesh (used without -dm_plex_filename)", NULL);
  PetscCall(PetscOptionsRangeInt("-box_dim", "Spatial dimension of the box", NULL, dim, &dim, NULL, 2, 3));
  PetscCall(PetscOptionsIntArray("-box_faces", "Number of cells along each axis", NULL, faces, &nfaces, NULL));
  PetscCall(PetscOptionsRealArray("-box_lower", "Lower corner of the box", NULL, lo, &nlo, NULL));
  PetscCall(PetscOptionsRealArray("-box_upper", "Upper corner of the box", NULL, hi, &nhi, NULL));
  PetscCall(PetscOptionsEnum("-box_diagonal", "2D: direction of the diagonal splitting each square", NULL, SgBoxDiagonals, (PetscEnum)diag, (PetscEnum *)&diag, NULL));
  PetscOptionsEnd();

  if (file) {
    PetscErrorCode ierr;
    const char    *msg = NULL;
    char           why[512] = "";

    PetscCall(CheckMeshFile(comm, fname));
    /* a reader error (truncated or foreign file) is reported with the file's name instead of a bare traceback */
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = DMPlexCreateFromFile(comm, fname, "signorini", PETSC_TRUE, dm);
    PetscCall(PetscPopErrorHandler());
    if (ierr) {
      PetscErrorMessage(ierr, NULL, (char **)&msg);
      if (msg) PetscCall(PetscStrncpy(why, msg, sizeof(why)));
      SETERRQ(comm, PETSC_ERR_FILE_READ, "-dm_plex_filename: cannot read mesh file '%s': %s", fname, why[0] ? why : "the reader failed");
    }
  } else {
    for (PetscInt d = 0; d < dim; d++) {
      PetscCheck(faces[d] > 0, comm, PETSC_ERR_USER_INPUT, "-box_faces: entry %" PetscInt_FMT " is %" PetscInt_FMT ", must be positive", d, faces[d]);
      PetscCheck(PetscIsNormalReal(hi[d] - lo[d]) && hi[d] > lo[d], comm, PETSC_ERR_USER_INPUT, "-box_lower/-box_upper: axis %" PetscInt_FMT " has lower %g >= upper %g", d, (double)lo[d], (double)hi[d]);
    }
    PetscCall(BoxMeshCreate(comm, dim, faces, lo, hi, diag, dm));
  }
  PetscCall(PetscObjectSetName((PetscObject)*dm, "mesh"));
  PetscCall(DMGetDimension(*dm, &dim));
  PetscCall(DMGetCoordinateDim(*dm, &cdim));
  PetscCheck(dim == 2 || dim == 3, comm, PETSC_ERR_USER_INPUT, "mesh %s has dimension %" PetscInt_FMT ": only 2D and 3D meshes are supported", file ? fname : "(box)", dim);
  PetscCheck(cdim == dim, comm, PETSC_ERR_USER_INPUT, "mesh %s: coordinate dimension %" PetscInt_FMT " differs from the topological dimension %" PetscInt_FMT, file ? fname : "(box)", cdim, dim);
  PetscCall(DMPlexGetHeightStratum(*dm, 0, &cStart, &cEnd));
  ncells = cEnd - cStart;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ncells, 1, MPIU_INT, MPI_SUM, comm));
  PetscCheck(ncells > 0, comm, PETSC_ERR_USER_INPUT, "mesh %s has no cells", file ? fname : "(box)");
  if (cEnd > cStart) {
    DMPolytopeType ct;
    PetscCall(DMPlexGetCellType(*dm, cStart, &ct));
    PetscCheck(ct == (dim == 2 ? DM_POLYTOPE_TRIANGLE : DM_POLYTOPE_TETRAHEDRON), PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "mesh %s: cells are %s, P1 elasticity needs %s", file ? fname : "(box)", DMPolytopeTypes[ct], dim == 2 ? "triangles" : "tetrahedra");
  }
  /* PT-Scotch unless the user picks another partitioner; DMSetFromOptions() distributes and refines */
  PetscCall(DMPlexGetPartitioner(*dm, &part));
  PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERPTSCOTCH));
  PetscCall(DMSetFromOptions(*dm));
  PetscCall(DMViewFromOptions(*dm, NULL, "-dm_view"));
  PetscCall(PetscLogEventEnd(SG_MeshSetUp, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Read -<what>_label, -<what>_ids and (if ncomp > 0) -<what>_<valname>: ncomp numbers per id. */
PetscErrorCode SgBoundaryFromOptions(PetscOptionItems *PetscOptionsObject, SgBoundary *bnd, PetscInt ncomp, const char *valname, const char *help)
{
  char      opt[64], txt[256];
  PetscInt  n = SG_MAX_IDS;
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s_label", bnd->what));
  PetscCall(PetscSNPrintf(txt, sizeof(txt), "Label marking the %s boundary", help));
  PetscCall(PetscOptionsString(opt, txt, NULL, bnd->label, bnd->label, sizeof(bnd->label), &set));
  if (set) bnd->active = PETSC_TRUE;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s_ids", bnd->what));
  PetscCall(PetscSNPrintf(txt, sizeof(txt), "Values of the %s label making the %s boundary (none: every value)", bnd->what, help));
  PetscCall(PetscOptionsIntArray(opt, txt, NULL, bnd->ids, &n, &set));
  if (set) {
    bnd->nids   = n;
    bnd->active = PETSC_TRUE;
    PetscCheck(n > 0, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "%s: give at least one label value", opt);
  }
  if (ncomp > 0) {
    PetscInt nv = 3 * SG_MAX_IDS, need = ncomp * PetscMax(bnd->nids, 1);

    PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s_%s", bnd->what, valname));
    PetscCall(PetscSNPrintf(txt, sizeof(txt), "%s: %" PetscInt_FMT " numbers per label value", help, ncomp));
    PetscCall(PetscOptionsRealArray(opt, txt, NULL, bnd->values, &nv, &set));
    if (set) {
      PetscCheck(bnd->active, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "%s is given, but no -%s_label or -%s_ids says where", opt, bnd->what, bnd->what);
      PetscCheck(nv == need, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "%s: got %" PetscInt_FMT " numbers, need %" PetscInt_FMT " (%" PetscInt_FMT " per value of %s_ids)", opt, nv, need, ncomp, bnd->what);
      bnd->nvalues = nv;
      for (PetscInt i = 0; i < nv; i++) PetscCheck(PetscIsNormalReal(bnd->values[i]) || bnd->values[i] == 0, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "%s: entry %" PetscInt_FMT " is %g, must be finite", opt, i, (double)bnd->values[i]);
    }
  }
  PetscFunctionReturn(0);
}

/* The label of a boundary part; an error naming the option if the mesh lacks it or a requested value. */
PetscErrorCode SgBoundaryGetLabel(DM dm, const SgBoundary *bnd, DMLabel *label)
{
  MPI_Comm comm;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)dm, &comm));
  PetscCall(DMGetLabel(dm, bnd->label, label));
  PetscCheck(*label, comm, PETSC_ERR_USER_INPUT, "-%s_label: the mesh has no label '%s' (see -dm_view for its labels; gmsh physical names need -dm_plex_gmsh_use_regions)", bnd->what, bnd->label);
  for (PetscInt i = 0; i < bnd->nids; i++) {
    PetscInt n;
    PetscCall(DMLabelGetStratumSize(*label, bnd->ids[i], &n));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPIU_INT, MPI_SUM, comm));
    PetscCheck(n > 0, comm, PETSC_ERR_USER_INPUT, "-%s_ids: label '%s' has no points with value %" PetscInt_FMT, bnd->what, bnd->label, bnd->ids[i]);
  }
  PetscFunctionReturn(0);
}

/* Call fn(point, part) for every point of the boundary part. */
static PetscErrorCode BoundaryForEachPoint(DM dm, const SgBoundary *bnd, PetscErrorCode (*fn)(void *, PetscInt, PetscInt), void *ctx)
{
  DMLabel  label;
  IS       vis = NULL;
  PetscInt nvals;
  const PetscInt *vals;

  PetscFunctionBeginUser;
  if (!bnd->active) PetscFunctionReturn(0);
  PetscCall(SgBoundaryGetLabel(dm, bnd, &label));
  if (bnd->nids) {
    nvals = bnd->nids;
    vals  = bnd->ids;
  } else {
    PetscCall(DMLabelGetValueIS(label, &vis));
    PetscCall(ISGetLocalSize(vis, &nvals));
    PetscCall(ISGetIndices(vis, &vals));
  }
  for (PetscInt i = 0; i < nvals; i++) {
    IS              is;
    PetscInt        n;
    const PetscInt *pts;

    PetscCall(DMLabelGetStratumIS(label, vals[i], &is));
    if (!is) continue;
    PetscCall(ISGetLocalSize(is, &n));
    PetscCall(ISGetIndices(is, &pts));
    for (PetscInt p = 0; p < n; p++) PetscCall(fn(ctx, pts[p], bnd->nids ? i : 0));
    PetscCall(ISRestoreIndices(is, &pts));
    PetscCall(ISDestroy(&is));
  }
  if (vis) {
    PetscCall(ISRestoreIndices(vis, &vals));
    PetscCall(ISDestroy(&vis));
  }
  PetscFunctionReturn(0);
}

typedef struct {
  DM        dm;
  PetscInt  fStart, fEnd, vStart, vEnd;
  PetscInt  n, *facets, *part; /* facet collection */
  PetscInt *vpart;             /* vertex marking */
} PointCollect;

static PetscErrorCode CollectFacet(void *ctx, PetscInt p, PetscInt part)
{
  PointCollect *pc = (PointCollect *)ctx;

  PetscFunctionBeginUser;
  if (p < pc->fStart || p >= pc->fEnd) PetscFunctionReturn(0);
  if (pc->facets) {
    pc->facets[pc->n] = p;
    pc->part[pc->n]   = part;
  }
  pc->n++;
  PetscFunctionReturn(0);
}

static PetscErrorCode MarkClosureVertices(void *ctx, PetscInt p, PetscInt part)
{
  PointCollect *pc = (PointCollect *)ctx;
  PetscInt     *cl = NULL, ncl;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetTransitiveClosure(pc->dm, p, PETSC_TRUE, &ncl, &cl));
  for (PetscInt q = 0; q < 2 * ncl; q += 2)
    if (cl[q] >= pc->vStart && cl[q] < pc->vEnd && pc->vpart[cl[q] - pc->vStart] < 0) pc->vpart[cl[q] - pc->vStart] = part;
  PetscCall(DMPlexRestoreTransitiveClosure(pc->dm, p, PETSC_TRUE, &ncl, &cl));
  PetscFunctionReturn(0);
}

/* The local facets (codimension-1 points) of a boundary part and the index of the label value of each. */
PetscErrorCode SgBoundaryGetFacets(DM dm, const SgBoundary *bnd, PetscInt *n, PetscInt **facets, PetscInt **part)
{
  PointCollect pc = {dm, 0, 0, 0, 0, 0, NULL, NULL, NULL};

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetHeightStratum(dm, 1, &pc.fStart, &pc.fEnd));
  PetscCall(BoundaryForEachPoint(dm, bnd, CollectFacet, &pc));
  PetscCall(PetscMalloc2(pc.n, facets, pc.n, part));
  pc.facets = *facets;
  pc.part   = *part;
  *n        = pc.n;
  pc.n      = 0;
  PetscCall(BoundaryForEachPoint(dm, bnd, CollectFacet, &pc));
  PetscFunctionReturn(0);
}

/* Build the P1 displacement section (dim dofs per vertex, Dirichlet vertices constrained) and the flat mesh arrays. */
PetscErrorCode SgMeshSetUp(DM dm, const SgBoundary *dirichlet, SgMesh *m)
{
  PetscSection    s, gs, cs;
  PetscInt        pStart, pEnd, vEnd, cEnd, dim;
  PointCollect    pc;
  Vec             cl;
  const PetscScalar *ca;
  PetscInt        cidx[3] = {0, 1, 2};

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(m, sizeof(*m)));
  PetscCall(DMGetDimension(dm, &dim));
  m->dim = dim;
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &m->vStart, &vEnd));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &m->cStart, &cEnd));
  m->nv = vEnd - m->vStart;
  m->nc = cEnd - m->cStart;
  PetscCall(PetscMalloc6(m->nc * (dim + 1), &m->cellv, m->nv * dim, &m->x, m->nv, &m->gblock, m->nv, &m->loff, m->nv, &m->goff, m->nv, &m->bcgroup));
  for (PetscInt v = 0; v < m->nv; v++) m->bcgroup[v] = -1;

  /* Dirichlet vertices: closure of the labelled points */
  pc.dm     = dm;
  pc.vStart = m->vStart;
  pc.vEnd   = vEnd;
  pc.vpart  = m->bcgroup;
  PetscCall(BoundaryForEachPoint(dm, dirichlet, MarkClosureVertices, &pc));

  PetscCall(PetscSectionCreate(PetscObjectComm((PetscObject)dm), &s));
  PetscCall(PetscSectionSetNumFields(s, 1));
  PetscCall(PetscSectionSetFieldName(s, 0, "displacement"));
  PetscCall(PetscSectionSetFieldComponents(s, 0, dim));
  PetscCall(PetscSectionSetChart(s, pStart, pEnd));
  for (PetscInt v = m->vStart; v < vEnd; v++) {
    PetscCall(PetscSectionSetDof(s, v, dim));
    PetscCall(PetscSectionSetFieldDof(s, v, 0, dim));
    if (m->bcgroup[v - m->vStart] >= 0) {
      PetscCall(PetscSectionSetConstraintDof(s, v, dim));
      PetscCall(PetscSectionSetFieldConstraintDof(s, v, 0, dim));
    }
  }
  PetscCall(PetscSectionSetUp(s));
  for (PetscInt v = m->vStart; v < vEnd; v++)
    if (m->bcgroup[v - m->vStart] >= 0) {
      PetscCall(PetscSectionSetConstraintIndices(s, v, cidx));
      PetscCall(PetscSectionSetFieldConstraintIndices(s, v, 0, cidx));
    }
  PetscCall(DMSetLocalSection(dm, s));
  PetscCall(PetscSectionDestroy(&s));
  PetscCall(DMGetLocalSection(dm, &s));
  PetscCall(DMGetGlobalSection(dm, &gs));

  {
    PetscInt rstart, gdof, goff;
    Vec      g;

    PetscCall(DMGetGlobalVector(dm, &g));
    PetscCall(VecGetOwnershipRange(g, &rstart, NULL));
    PetscCall(VecGetSize(g, &m->nfree_glob));
    m->nfree_glob /= dim;
    PetscCall(DMRestoreGlobalVector(dm, &g));
    for (PetscInt v = m->vStart; v < vEnd; v++) {
      const PetscInt i = v - m->vStart;
      PetscCall(PetscSectionGetOffset(s, v, &m->loff[i]));
      PetscCall(PetscSectionGetDof(gs, v, &gdof));
      PetscCall(PetscSectionGetOffset(gs, v, &goff));
      if (gdof >= 0) m->nowned++; /* owned (possibly constrained: gdof 0) */
      if (m->bcgroup[i] >= 0) {
        m->gblock[i] = -1;
        m->goff[i]   = -1;
      } else {
        if (goff < 0) goff = -(goff + 1);
        m->gblock[i] = goff / dim;
        m->goff[i]   = gdof > 0 ? goff - rstart : -1;
      }
    }
  }

  PetscCall(DMGetCoordinatesLocal(dm, &cl));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(VecGetArrayRead(cl, &ca));
  for (PetscInt v = m->vStart; v < vEnd; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(cs, v, &off));
    for (PetscInt d = 0; d < dim; d++) m->x[(v - m->vStart) * dim + d] = PetscRealPart(ca[off + d]);
  }
  PetscCall(VecRestoreArrayRead(cl, &ca));

  for (PetscInt c = m->cStart; c < cEnd; c++) {
    PetscInt *clo = NULL, ncl, k = 0;
    PetscCall(DMPlexGetTransitiveClosure(dm, c, PETSC_TRUE, &ncl, &clo));
    for (PetscInt q = 0; q < 2 * ncl; q += 2)
      if (clo[q] >= m->vStart && clo[q] < vEnd) m->cellv[(c - m->cStart) * (dim + 1) + k++] = clo[q] - m->vStart;
    PetscCall(DMPlexRestoreTransitiveClosure(dm, c, PETSC_TRUE, &ncl, &clo));
    PetscCheck(k == dim + 1, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "cell %" PetscInt_FMT " has %" PetscInt_FMT " vertices: not a simplex", c, k);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SgMeshDestroy(SgMesh *m)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree6(m->cellv, m->x, m->gblock, m->loff, m->goff, m->bcgroup));
  PetscFunctionReturn(0);
}

/* Vertices (local numbers), measure and outward unit normal of a boundary facet. */
PetscErrorCode SgFacetGeometry(DM dm, const SgMesh *m, PetscInt f, PetscInt *nfv, PetscInt fv[], PetscReal *area, PetscReal normal[])
{
  const PetscInt  dim = m->dim;
  PetscInt       *cl  = NULL, ncl, k = 0, ns;
  const PetscInt *supp;
  PetscReal       e[2][3] = {{0}}, nrm = 0, dir = 0;
  const PetscReal *x0;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetTransitiveClosure(dm, f, PETSC_TRUE, &ncl, &cl));
  for (PetscInt q = 0; q < 2 * ncl; q += 2)
    if (cl[q] >= m->vStart && cl[q] < m->vStart + m->nv) fv[k++] = cl[q] - m->vStart;
  PetscCall(DMPlexRestoreTransitiveClosure(dm, f, PETSC_TRUE, &ncl, &cl));
  PetscCheck(k == dim, PETSC_COMM_SELF, PETSC_ERR_PLIB, "facet %" PetscInt_FMT " has %" PetscInt_FMT " vertices", f, k);
  *nfv = k;
  x0   = &m->x[fv[0] * dim];
  for (PetscInt a = 1; a < dim; a++)
    for (PetscInt d = 0; d < dim; d++) e[a - 1][d] = m->x[fv[a] * dim + d] - x0[d];
  if (dim == 2) {
    normal[0] = e[0][1];
    normal[1] = -e[0][0];
  } else {
    normal[0] = e[0][1] * e[1][2] - e[0][2] * e[1][1];
    normal[1] = e[0][2] * e[1][0] - e[0][0] * e[1][2];
    normal[2] = e[0][0] * e[1][1] - e[0][1] * e[1][0];
  }
  for (PetscInt d = 0; d < dim; d++) nrm += normal[d] * normal[d];
  nrm   = PetscSqrtReal(nrm);
  *area = dim == 2 ? nrm : 0.5 * nrm;
  /* orient away from the cell: compare with the cell vertex opposite the facet */
  PetscCall(DMPlexGetSupportSize(dm, f, &ns));
  PetscCheck(ns == 1, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "facet %" PetscInt_FMT " of a boundary part lies inside the mesh (%" PetscInt_FMT " cells)", f, ns);
  PetscCall(DMPlexGetSupport(dm, f, &supp));
  for (PetscInt a = 0; a <= dim; a++) {
    const PetscInt v = m->cellv[(supp[0] - m->cStart) * (dim + 1) + a];
    PetscBool      onf = PETSC_FALSE;
    for (PetscInt b = 0; b < dim; b++) onf = (PetscBool)(onf || fv[b] == v);
    if (onf) continue;
    for (PetscInt d = 0; d < dim; d++) dir += (m->x[v * dim + d] - x0[d]) * normal[d];
  }
  for (PetscInt d = 0; d < dim; d++) normal[d] /= (dir > 0 ? -nrm : nrm);
  PetscFunctionReturn(0);
}
