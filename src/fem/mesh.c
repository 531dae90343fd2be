/* mesh.c: the DMPlex mesh (structured simplex box or gmsh file), boundary parts and the P1 displacement layout. */
#include "fem/femimpl.h"
#include <petscblaslapack.h>
#include <petscsf.h>
#include <errno.h>
#include <stdlib.h>
#include <unistd.h>

const char *const SgBoxDiagonals[] = {"right", "left", "mirror", "SgBoxDiagonal", "SG_BOX_", NULL};
/* mirror: left in the lower half of x, right in the upper half, so that the mesh is symmetric about the box's middle
   x = (lower + upper) / 2 and its upper half is the -box_diagonal right mesh of that half (half models) */
typedef enum { SG_BOX_RIGHT, SG_BOX_LEFT, SG_BOX_MIRROR } SgBoxDiagonal;

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
  PetscMPIInt    rank;
  PetscInt       nv = 0, nc = 0, *cells = NULL, failed = 0;
  PetscReal     *coords = NULL;
  PetscErrorCode ierr;
  char           fstr[128];
  double         bytes;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscSNPrintf(fstr, sizeof(fstr), dim == 2 ? "%" PetscInt_FMT ",%" PetscInt_FMT : "%" PetscInt_FMT ",%" PetscInt_FMT ",%" PetscInt_FMT, faces[0], faces[1], faces[2]));
  {
    /* sizes in floating point first: an impossible mesh is refused before any int overflow or allocation */
    const double nvd = (faces[0] + 1.0) * (faces[1] + 1.0) * (dim == 3 ? faces[2] + 1.0 : 1.0);
    const double ncd = dim == 2 ? 2.0 * faces[0] * faces[1] : 6.0 * faces[0] * faces[1] * faces[2];
    /* entries of the largest index arrays of the interpolated DMPlex (Euler: edges ~ vertices + cells; 3D faces ~ 2 cells):
       2D points 2V+2C, cones 2V+5C; 3D points 2V+4C, cones 2V+12C */
    const double idx = dim == 2 ? 2 * nvd + 5 * ncd : 2 * nvd + 12 * ncd;
    double       phys = (double)sysconf(_SC_PHYS_PAGES) * (double)sysconf(_SC_PAGE_SIZE);

    /* measured peak memory of building the box mesh on rank 0 and distributing it: about 265 B per triangle and 590 B per
       tetrahedron (a lower bound, without the solver); rank 0's machine decides, so every rank stops alike */
    bytes = (dim == 2 ? 250.0 : 550.0) * ncd;
    PetscCallMPI(MPI_Bcast(&phys, 1, MPI_DOUBLE, 0, comm));

    PetscCheck(idx <= (double)PETSC_MAX_INT, comm, PETSC_ERR_USER_INPUT, "-box_faces %s: the box mesh would have %.0f vertices and %.0f %s, beyond the range of PetscInt in this PETSc build (index arrays of about %.3g entries, at most %" PetscInt_FMT "); it would also need at least %.3g GB of memory", fstr, nvd, ncd, dim == 2 ? "triangles" : "tetrahedra", idx, (PetscInt)PETSC_MAX_INT, bytes / 1e9);
    PetscCheck(phys <= 0 || bytes <= phys, comm, PETSC_ERR_USER_INPUT, "-box_faces %s: the box mesh (%.0f vertices, %.0f %s) needs at least %.3g GB of memory to build on one rank, but this machine has %.3g GB", fstr, nvd, ncd, dim == 2 ? "triangles" : "tetrahedra", bytes / 1e9, phys / 1e9);
  }
  if (rank == 0) {
    const PetscInt nx = faces[0], ny = faces[1], nz = dim == 3 ? faces[2] : 1;

    nv = (nx + 1) * (ny + 1) * (dim == 3 ? nz + 1 : 1);
    nc = dim == 2 ? 2 * nx * ny : 6 * nx * ny * nz;
    /* an allocation failure is reported with the option that asked for the size */
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = PetscMalloc2((size_t)nv * dim, &coords, (size_t)nc * (dim + 1), &cells);
    PetscCall(PetscPopErrorHandler());
    if (ierr) failed = 1;
  }
  PetscCallMPI(MPI_Bcast(&failed, 1, MPIU_INT, 0, comm));
  PetscCheck(!failed, comm, PETSC_ERR_MEM, "-box_faces %s: out of memory allocating the box mesh (%.3g GB for its cell list and coordinates alone)", fstr, ((double)nv * dim * sizeof(PetscReal) + (double)nc * (dim + 1) * sizeof(PetscInt)) / 1e9);
  if (rank == 0) {
    const PetscInt nx = faces[0], ny = faces[1], nz = dim == 3 ? faces[2] : 1;
    PetscInt       c = 0;

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
          const PetscInt  k = diag == SG_BOX_MIRROR ? (2 * i < nx ? SG_BOX_LEFT : SG_BOX_RIGHT) : diag;
          for (PetscInt t = 0; t < 2; t++)
            for (PetscInt a = 0; a < 3; a++) cells[c * 3 + t * 3 + a] = tr[k][t][a];
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
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = DMPlexCreateFromCellListPetsc(comm, dim, nc, nv, dim + 1, PETSC_TRUE, cells, dim, coords, dm);
  PetscCall(PetscPopErrorHandler());
  PetscCall(PetscFree2(coords, cells));
  if (ierr) {
    const char *text = NULL;
    char       *spec = NULL;
    PetscErrorMessage(ierr, &text, &spec);
    SETERRQ(PETSC_COMM_SELF, ierr, "-box_faces %s: building the box mesh of %" PetscInt_FMT " vertices and %" PetscInt_FMT " cells failed (it needs about %.3g GB of memory; PETSc says: %s%s%s)", fstr, nv, nc, bytes / 1e9, text ? text : "", text && spec && spec[0] ? ", " : "", spec ? spec : "");
  }
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

/* A 2D mesh read with 3D coordinates (gmsh writes x, y, z): exact if every z is the same, so z is dropped then; a
   surface in a tilted plane (or not planar) would be solved projected onto z = 0, a wrong result: refused. */
static PetscErrorCode MeshDropConstantZ(MPI_Comm comm, const char fname[], DM dm)
{
  Vec                cl, nc;
  PetscSection       cs, ns;
  const PetscScalar *ca;
  PetscScalar       *na;
  PetscInt           vStart, vEnd;
  PetscReal          r[6] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}; /* min x,y,z and -max x,y,z */
  PetscReal          ext;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMGetCoordinatesLocal(dm, &cl));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(VecGetArrayRead(cl, &ca));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(cs, v, &off));
    for (PetscInt d = 0; d < 3; d++) {
      r[d]     = PetscMin(r[d], PetscRealPart(ca[off + d]));
      r[3 + d] = PetscMin(r[3 + d], -PetscRealPart(ca[off + d]));
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, r, 6, MPIU_REAL, MPIU_MIN, comm));
  ext = PetscMax(-r[3] - r[0], -r[4] - r[1]);
  /* equal up to round-off of the coordinates themselves (gmsh interpolates nodes inside a plane surface) */
  PetscCheck(-r[5] - r[2] <= 1e-13 * PetscMax(ext, PetscMax(PetscAbsReal(r[2]), PetscAbsReal(r[5]))), comm, PETSC_ERR_USER_INPUT,
             "-dm_plex_filename: '%s' is a 2D mesh whose z coordinates range over [%.17g, %.17g] (x over [%g, %g], y over [%g, %g]): a surface that is not in a plane z = constant is not supported (a 2D mesh must lie in a plane z = constant; rotate it into one)", fname, (double)r[2], (double)-r[5], (double)r[0], (double)-r[3], (double)r[1], (double)-r[4]);
  PetscCall(PetscInfo(dm, "2D mesh %s in the plane z = %g: z dropped\n", fname, (double)r[2]));
  PetscCall(PetscSectionCreate(PetscObjectComm((PetscObject)dm), &ns));
  PetscCall(PetscSectionSetNumFields(ns, 1));
  PetscCall(PetscSectionSetFieldComponents(ns, 0, 2));
  PetscCall(PetscSectionSetChart(ns, vStart, vEnd));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscCall(PetscSectionSetDof(ns, v, 2));
    PetscCall(PetscSectionSetFieldDof(ns, v, 0, 2));
  }
  PetscCall(PetscSectionSetUp(ns));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 2 * (vEnd - vStart), &nc));
  PetscCall(VecSetBlockSize(nc, 2));
  PetscCall(PetscObjectSetName((PetscObject)nc, "coordinates"));
  PetscCall(VecGetArray(nc, &na));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt off, noff;
    PetscCall(PetscSectionGetOffset(cs, v, &off));
    PetscCall(PetscSectionGetOffset(ns, v, &noff));
    na[noff]     = ca[off];
    na[noff + 1] = ca[off + 1];
  }
  PetscCall(VecRestoreArray(nc, &na));
  PetscCall(VecRestoreArrayRead(cl, &ca));
  PetscCall(DMSetCoordinateDim(dm, 2));
  PetscCall(DMSetCoordinateSection(dm, 2, ns));
  PetscCall(DMSetCoordinatesLocal(dm, nc));
  PetscCall(PetscSectionDestroy(&ns));
  PetscCall(VecDestroy(&nc));
  PetscFunctionReturn(0);
}

/* Read a gmsh (or other) mesh file with the file's own coordinate dimension, so that a 2D mesh with z values is seen. */
static PetscErrorCode MeshReadFile(MPI_Comm comm, const char fname[], DM *dm)
{
  PetscErrorCode ierr;
  const char    *msg = NULL;
  char           why[512] = "";
  PetscBool      userdim;
  PetscInt       dim, cdim;

  PetscFunctionBeginUser;
  PetscCall(CheckMeshFile(comm, fname));
  /* PETSc's gmsh reader trusts the file (a bad node tag is a segmentation fault): check its structure first */
  PetscCall(SgGmshCheckFile(comm, fname));
  /* PETSc's gmsh reader keeps only the first dim coordinates unless told the space dimension; an explicit
     -dm_plex_gmsh_spacedim from the user is left alone */
  PetscCall(PetscOptionsHasName(NULL, NULL, "-dm_plex_gmsh_spacedim", &userdim));
  if (!userdim) PetscCall(PetscOptionsSetValue(NULL, "-dm_plex_gmsh_spacedim", "3"));
  /* a reader error (truncated or foreign file) is reported with the file's name instead of a bare traceback */
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = DMPlexCreateFromFile(comm, fname, "signorini", PETSC_TRUE, dm);
  PetscCall(PetscPopErrorHandler());
  if (!userdim) PetscCall(PetscOptionsClearValue(NULL, "-dm_plex_gmsh_spacedim"));
  if (ierr) {
    PetscErrorMessage(ierr, NULL, (char **)&msg);
    if (msg) PetscCall(PetscStrncpy(why, msg, sizeof(why)));
    SETERRQ(comm, PETSC_ERR_FILE_READ, "-dm_plex_filename: cannot read mesh file '%s': %s", fname, why[0] ? why : "the reader failed");
  }
  PetscCall(DMGetDimension(*dm, &dim));
  PetscCall(DMGetCoordinateDim(*dm, &cdim));
  if (dim == 2 && cdim == 3) PetscCall(MeshDropConstantZ(comm, fname, *dm));
  PetscFunctionReturn(0);
}

/* Create the distributed simplex mesh from a gmsh file (-dm_plex_filename) or the structured box (-box_*), options
   under the prefix. */
PetscErrorCode SgMeshCreateDM(MPI_Comm comm, const char prefix[], DM *dm)
{
  char             fname[PETSC_MAX_PATH_LEN] = "";
  PetscBool        file;
  PetscInt         dim = 2, nfaces, nlo, nhi, ndim = 1, faces[SG_OPT_MAX] = {10, 10, 10};
  PetscReal        lo[SG_OPT_MAX] = {0, 0, 0}, hi[SG_OPT_MAX] = {1, 1, 1};
  SgBoxDiagonal    diag = SG_BOX_RIGHT;
  PetscPartitioner part;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(SG_MeshSetUp, 0, 0, 0, 0));
  PetscCall(PetscOptionsGetString(NULL, prefix, "-dm_plex_filename", fname, sizeof(fname), &file));
  PetscCheck(!file || fname[0], comm, PETSC_ERR_USER_INPUT, "-dm_plex_filename is given without a value");
  PetscOptionsBegin(comm, prefix, "Structured simplex box mesh (used without -dm_plex_filename)", NULL);
  PetscCall(SgOptionsIntList(PetscOptionsObject, "-box_dim", "Spatial dimension of the box: 2 or 3", 1, &dim, &ndim, NULL));
  PetscCheck(dim == 2 || dim == 3, comm, PETSC_ERR_USER_INPUT, "-box_dim: the dimension must be 2 or 3, got %" PetscInt_FMT, dim);
  nfaces = nlo = nhi = dim;
  PetscCall(SgOptionsIntList(PetscOptionsObject, "-box_faces", "Number of cells along each axis (dim numbers)", SG_OPT_MAX, faces, &nfaces, NULL));
  PetscCall(SgOptionsRealList(PetscOptionsObject, "-box_lower", "Lower corner of the box (dim numbers)", SG_OPT_MAX, lo, &nlo, NULL));
  PetscCall(SgOptionsRealList(PetscOptionsObject, "-box_upper", "Upper corner of the box (dim numbers)", SG_OPT_MAX, hi, &nhi, NULL));
  PetscCall(PetscOptionsEnum("-box_diagonal", "2D: direction of the diagonal splitting each square (mirror: symmetric about the middle of x)", NULL, SgBoxDiagonals, (PetscEnum)diag, (PetscEnum *)&diag, NULL));
  PetscOptionsEnd();
  {
    /* PETSc keeps the default for an enum given without a value */
    const char *val;
    PetscBool   has;
    PetscCall(PetscOptionsFindPair(NULL, prefix, "-box_diagonal", &val, &has));
    PetscCheck(!has || (val && val[0]), comm, PETSC_ERR_USER_INPUT, "-box_diagonal is given without a value (right, left or mirror)");
  }

  if (file) PetscCall(MeshReadFile(comm, fname, dm));
  else {
    /* every entry from the user: a missing one would silently come from the default, an extra one be ignored */
    PetscCheck(nfaces == dim, comm, PETSC_ERR_USER_INPUT, "-box_faces: give %" PetscInt_FMT " numbers for -box_dim %" PetscInt_FMT ", got %" PetscInt_FMT, dim, dim, nfaces);
    PetscCheck(nlo == dim, comm, PETSC_ERR_USER_INPUT, "-box_lower: give %" PetscInt_FMT " numbers for -box_dim %" PetscInt_FMT ", got %" PetscInt_FMT, dim, dim, nlo);
    PetscCheck(nhi == dim, comm, PETSC_ERR_USER_INPUT, "-box_upper: give %" PetscInt_FMT " numbers for -box_dim %" PetscInt_FMT ", got %" PetscInt_FMT, dim, dim, nhi);
    for (PetscInt d = 0; d < dim; d++) {
      PetscCheck(faces[d] > 0, comm, PETSC_ERR_USER_INPUT, "-box_faces: entry %" PetscInt_FMT " is %" PetscInt_FMT ", must be positive", d, faces[d]);
      PetscCheck(PetscIsNormalReal(hi[d] - lo[d]) && hi[d] > lo[d], comm, PETSC_ERR_USER_INPUT, "-box_lower/-box_upper: axis %" PetscInt_FMT " has lower %g >= upper %g", d, (double)lo[d], (double)hi[d]);
    }
    PetscCheck(diag != SG_BOX_MIRROR || (dim == 2 && faces[0] % 2 == 0), comm, PETSC_ERR_USER_INPUT, "-box_diagonal mirror: needs -box_dim 2 and an even number of squares along x (-box_faces %" PetscInt_FMT ",...)", faces[0]);
    PetscCall(BoxMeshCreate(comm, dim, faces, lo, hi, diag, dm));
  }
  PetscCall(PetscObjectSetName((PetscObject)*dm, "mesh"));
  PetscCall(PetscObjectSetOptionsPrefix((PetscObject)*dm, prefix));
  /* PT-Scotch unless the user picks another partitioner; DMSetFromOptions() distributes and refines */
  PetscCall(DMPlexGetPartitioner(*dm, &part));
  PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERPTSCOTCH));
  PetscCall(SgMeshCheckDM(comm, file ? fname : "(box)", *dm));
  PetscCall(DMSetFromOptions(*dm));
  {
    /* the assembly and the energy visit every local cell once: cells shared by an overlap would count twice */
    PetscInt ov;
    PetscCall(DMPlexGetOverlap(*dm, &ov));
    PetscCheck(ov == 0, comm, PETSC_ERR_USER_INPUT, "-dm_distribute_overlap %" PetscInt_FMT ": an overlapping distribution is not supported (cells on several ranks would be assembled more than once); use 0", ov);
  }
  PetscCall(DMViewFromOptions(*dm, NULL, "-dm_view"));
  PetscCall(PetscLogEventEnd(SG_MeshSetUp, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* A mesh we can use: 2D triangles or 3D tetrahedra, coordinates of the mesh's dimension, no overlap (the caller's DM
   is checked by this too; name: how to call it in messages). */
PetscErrorCode SgMeshCheckDM(MPI_Comm comm, const char name[], DM dm)
{
  PetscInt dim, cdim, cStart, cEnd, ncells, ov;

  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(DMGetCoordinateDim(dm, &cdim));
  PetscCheck(dim == 2 || dim == 3, comm, PETSC_ERR_USER_INPUT, "mesh %s has dimension %" PetscInt_FMT ": only 2D and 3D meshes are supported", name, dim);
  PetscCheck(cdim == dim, comm, PETSC_ERR_USER_INPUT, "mesh %s: coordinate dimension %" PetscInt_FMT " differs from the topological dimension %" PetscInt_FMT, name, cdim, dim);
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  ncells = cEnd - cStart;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ncells, 1, MPIU_INT, MPI_SUM, comm));
  PetscCheck(ncells > 0, comm, PETSC_ERR_USER_INPUT, "mesh %s has no cells", name);
  if (cEnd > cStart) {
    DMPolytopeType ct;
    PetscCall(DMPlexGetCellType(dm, cStart, &ct));
    PetscCheck(ct == (dim == 2 ? DM_POLYTOPE_TRIANGLE : DM_POLYTOPE_TETRAHEDRON), PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "mesh %s: cells are %s, P1 elasticity needs %s", name, DMPolytopeTypes[ct], dim == 2 ? "triangles" : "tetrahedra");
  }
  PetscCall(DMPlexGetOverlap(dm, &ov));
  PetscCheck(ov == 0, comm, PETSC_ERR_USER_INPUT, "mesh %s: an overlapping distribution (overlap %" PetscInt_FMT ") is not supported (cells on several ranks would be assembled more than once); use 0", name, ov);
  PetscFunctionReturn(0);
}

/* Read -<what>_label, -<what>_ids and (if ncomp > 0) -<what>_<valname>: ncomp numbers per id. An option given without
   a value is an error (PETSc would report it as not set, and the part would silently vanish). */
PetscErrorCode SgBoundaryFromOptions(PetscOptionItems *PetscOptionsObject, SgBoundary *bnd, PetscInt ncomp, const char *valname, const char *help)
{
  char      opt[64], txt[256], name[256], pre[256];
  PetscInt  n = bnd->nids;
  PetscBool set;

  PetscFunctionBeginUser;
  /* messages name the option as the user types it: with the prefix */
  PetscCall(PetscSNPrintf(pre, sizeof(pre), "%s", PetscOptionsObject->prefix ? PetscOptionsObject->prefix : ""));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s_label", bnd->what));
  PetscCall(SgOptionsName(pre, opt, name, sizeof(name)));
  PetscCall(PetscSNPrintf(txt, sizeof(txt), "Label marking the %s boundary", help));
  PetscCall(PetscOptionsString(opt, txt, NULL, bnd->label, bnd->label, sizeof(bnd->label), &set));
  if (set) {
    PetscCheck(bnd->label[0], PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s is given without a value (a label name)", name);
    bnd->active = PETSC_TRUE;
  }
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s_ids", bnd->what));
  PetscCall(PetscSNPrintf(txt, sizeof(txt), "Values of the %s label making the %s boundary (none: every value)", bnd->what, help));
  PetscCall(SgOptionsIntList(PetscOptionsObject, opt, txt, SG_MAX_IDS, bnd->ids, &n, &set));
  if (set) {
    bnd->nids   = n;
    bnd->active = PETSC_TRUE;
  }
  if (ncomp > 0) {
    PetscInt nv = bnd->nvalues, need = ncomp * PetscMax(bnd->nids, 1);

    PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s_%s", bnd->what, valname));
    PetscCall(SgOptionsName(pre, opt, name, sizeof(name)));
    PetscCall(PetscSNPrintf(txt, sizeof(txt), "%s: %" PetscInt_FMT " numbers per label value", help, ncomp));
    PetscCall(SgOptionsRealList(PetscOptionsObject, opt, txt, 3 * SG_MAX_IDS, bnd->values, &nv, &set));
    if (set) {
      PetscCheck(bnd->active, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s is given, but no -%s%s_label or -%s%s_ids says where", name, pre, bnd->what, pre, bnd->what);
      PetscCheck(nv == need, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s: got %" PetscInt_FMT " numbers, need %" PetscInt_FMT " (%" PetscInt_FMT " per value of %s_ids)", name, nv, need, ncomp, bnd->what);
      bnd->nvalues = nv;
      for (PetscInt i = 0; i < nv; i++) PetscCheck(PetscIsNormalReal(bnd->values[i]) || bnd->values[i] == 0, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s: entry %" PetscInt_FMT " is %g, must be finite", name, i, (double)bnd->values[i]);
    }
  }
  PetscFunctionReturn(0);
}

/* -<what>_components: which components a Dirichlet part fixes, one word per id (one if the part has no ids), made of
   the letters x, y (and z in 3D): "xyz" fixes all (the default), "x" only u_x (a roller, a symmetry plane x = c). */
PetscErrorCode SgBoundaryComponentsFromOptions(PetscOptionItems *PetscOptionsObject, SgBoundary *bnd, PetscInt dim)
{
  char      opt[64], name[256], pre[256], *words[SG_MAX_IDS];
  PetscInt  n = SG_MAX_IDS, need = PetscMax(bnd->nids, 1);
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(pre, sizeof(pre), "%s", PetscOptionsObject->prefix ? PetscOptionsObject->prefix : ""));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s_components", bnd->what));
  PetscCall(SgOptionsName(pre, opt, name, sizeof(name)));
  PetscCall(PetscOptionsStringArray(opt, dim == 2 ? "Components fixed per label value: x, y or xy (default xy)" : "Components fixed per label value: letters of xyz, e.g. x, yz (default xyz)", NULL, words, &n, &set));
  {
    /* PETSc reads an empty value as not set and drops empty entries: both would silently fix every component */
    const char *val;
    PetscBool   has;
    size_t      len;
    PetscCall(PetscOptionsFindPair(NULL, PetscOptionsObject->prefix, opt, &val, &has));
    if (has) {
      PetscCheck(val && val[0], PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s is given without a value (x, y%s per id)", name, dim == 3 ? ", z, xy, ..." : " or xy");
      PetscCall(PetscStrlen(val, &len));
      PetscCheck(val[0] != ',' && val[len - 1] != ',' && !strstr(val, ",,"), PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s '%s': an entry is empty", name, val);
    }
  }
  if (!set) {
    /* SgProblemSetDirichletComponents: its masks must still fit the ids and the dimension */
    for (PetscInt i = 0; i < bnd->ncomps; i++) PetscCheck(bnd->comps[i] > 0 && bnd->comps[i] < (1 << dim), PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "SgProblemSetDirichletComponents: mask %" PetscInt_FMT " is %" PetscInt_FMT ", must be a nonzero sum of SG_COMPONENT_X, SG_COMPONENT_Y%s", i, bnd->comps[i], dim == 3 ? ", SG_COMPONENT_Z" : " (2D)");
    PetscCheck(!bnd->ncomps || bnd->ncomps == need, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "SgProblemSetDirichletComponents: got %" PetscInt_FMT " masks, need %" PetscInt_FMT " (one per Dirichlet id)", bnd->ncomps, need);
    PetscFunctionReturn(0);
  }
  PetscCheck(bnd->active, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s is given, but no -%s%s_label or -%s%s_ids says where", name, pre, bnd->what, pre, bnd->what);
  PetscCheck(n > 0, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s is given without a value (x, y%s per id)", name, dim == 3 ? ", z, xy, ..." : " or xy");
  for (PetscInt i = 0; i < n; i++) {
    PetscInt mask = 0;
    for (const char *c = words[i]; *c; c++) {
      const PetscInt d = *c == 'x' ? 0 : *c == 'y' ? 1 : *c == 'z' ? 2 : -1;
      PetscCheck(d >= 0 && d < dim, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s: entry %" PetscInt_FMT " '%s' has '%c': use the letters x, y%s", name, i, words[i], *c, dim == 3 ? ", z" : " (2D)");
      PetscCheck(!(mask & (1 << d)), PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s: entry %" PetscInt_FMT " '%s' names '%c' twice", name, i, words[i], *c);
      mask |= 1 << d;
    }
    PetscCheck(mask, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s: entry %" PetscInt_FMT " is empty (a part fixing nothing is no Dirichlet part)", name, i);
    bnd->comps[i] = mask;
  }
  for (PetscInt i = 0; i < n; i++) PetscCall(PetscFree(words[i]));
  PetscCheck(n == need, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s: got %" PetscInt_FMT " entries, need %" PetscInt_FMT " (one per value of -%s%s_ids)", name, n, need, pre, bnd->what);
  bnd->ncomps = n;
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
  PetscInt  dim, *vmask, *vcomp; /* Dirichlet components: fixed per vertex (bits), part per vertex component */
  const PetscInt *comps;         /* components per part (NULL: all) */
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
  for (PetscInt q = 0; q < 2 * ncl; q += 2) {
    PetscInt i, mask;
    if (cl[q] < pc->vStart || cl[q] >= pc->vEnd) continue;
    i    = cl[q] - pc->vStart;
    mask = pc->comps ? pc->comps[part] : (1 << pc->dim) - 1;
    if (pc->vpart[i] < 0) pc->vpart[i] = part;
    if (!pc->vmask) continue;
    /* a component fixed by several parts takes the value of the first */
    for (PetscInt d = 0; d < pc->dim; d++)
      if ((mask >> d & 1) && pc->vcomp[i * pc->dim + d] < 0) pc->vcomp[i * pc->dim + d] = part;
    pc->vmask[i] |= mask;
  }
  PetscCall(DMPlexRestoreTransitiveClosure(pc->dm, p, PETSC_TRUE, &ncl, &cl));
  PetscFunctionReturn(0);
}

/* The local facets (codimension-1 points) of a boundary part and the index of the label value of each. */
PetscErrorCode SgBoundaryGetFacets(DM dm, const SgBoundary *bnd, PetscInt *n, PetscInt **facets, PetscInt **part)
{
  PointCollect pc = {dm, 0, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL, NULL, NULL};

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

/* A vertex shared by ranks may lie on a Dirichlet facet that only some of them hold (their cells touch the boundary
   at the vertex alone): every copy gets the union of the components fixed and, per component, the first part, so
   that the ranks agree on the layout and on which unknowns are decoupled. */
static PetscErrorCode SyncDirichletVertices(DM dm, SgMesh *m)
{
  const PetscInt dim = m->dim, ns = 1 + dim, big = PETSC_MAX_INT / 4;
  PetscSF        sf;
  PetscInt       pStart, pEnd, np, nchanged = 0, *a, *b;
  PetscMPIInt    size;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)dm), &size));
  if (size == 1) PetscFunctionReturn(0);
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  np = pEnd - pStart;
  /* per point, in ns arrays of np: the first part of any component (bcgroup) and of each component, "none" as big;
     the minimum over the copies (the parts are numbered in the order they are marked) */
  PetscCall(PetscMalloc2(ns * np, &a, ns * np, &b));
  for (PetscInt i = 0; i < ns * np; i++) a[i] = big;
  for (PetscInt v = 0; v < m->nv; v++) {
    const PetscInt p = m->vStart + v - pStart;
    a[p] = m->bcgroup[v] >= 0 ? m->bcgroup[v] : big;
    for (PetscInt d = 0; d < dim; d++) a[(1 + d) * np + p] = m->bcpart[v * dim + d] >= 0 ? m->bcpart[v * dim + d] : big;
  }
  PetscCall(PetscArraycpy(b, a, ns * np));
  for (PetscInt k = 0; k < ns; k++) {
    PetscCall(PetscSFReduceBegin(sf, MPIU_INT, a + k * np, b + k * np, MPI_MIN));
    PetscCall(PetscSFReduceEnd(sf, MPIU_INT, a + k * np, b + k * np, MPI_MIN));
    PetscCall(PetscSFBcastBegin(sf, MPIU_INT, b + k * np, b + k * np, MPI_REPLACE));
    PetscCall(PetscSFBcastEnd(sf, MPIU_INT, b + k * np, b + k * np, MPI_REPLACE));
  }
  for (PetscInt v = 0; v < m->nv; v++) {
    const PetscInt p    = m->vStart + v - pStart;
    PetscInt       mask = 0;
    for (PetscInt d = 0; d < dim; d++) {
      const PetscInt g = b[(1 + d) * np + p];
      m->bcpart[v * dim + d] = g < big ? g : -1;
      if (g < big) mask |= 1 << d;
    }
    if (mask != m->bcmask[v]) nchanged++;
    m->bcmask[v]  = mask;
    m->bcgroup[v] = b[p] < big ? b[p] : -1;
  }
  PetscCall(PetscFree2(a, b));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nchanged, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)dm)));
  PetscCall(PetscInfo(dm, "%" PetscInt_FMT " copies of shared Dirichlet vertices completed from other ranks\n", nchanged));
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
  PetscCall(PetscCalloc2(m->nv, &m->bcmask, m->nv * dim, &m->bcpart));
  for (PetscInt v = 0; v < m->nv; v++) m->bcgroup[v] = -1;
  for (PetscInt i = 0; i < m->nv * dim; i++) m->bcpart[i] = -1;

  /* Dirichlet vertices: closure of the labelled points */
  PetscCall(PetscMemzero(&pc, sizeof(pc)));
  pc.dm     = dm;
  pc.vStart = m->vStart;
  pc.vEnd   = vEnd;
  pc.vpart  = m->bcgroup;
  pc.dim    = dim;
  pc.vmask  = m->bcmask;
  pc.vcomp  = m->bcpart;
  pc.comps  = dirichlet->ncomps ? dirichlet->comps : NULL;
  PetscCall(BoundaryForEachPoint(dm, dirichlet, MarkClosureVertices, &pc));
  PetscCall(SyncDirichletVertices(dm, m));

  PetscCall(PetscSectionCreate(PetscObjectComm((PetscObject)dm), &s));
  PetscCall(PetscSectionSetNumFields(s, 1));
  PetscCall(PetscSectionSetFieldName(s, 0, "displacement"));
  PetscCall(PetscSectionSetFieldComponents(s, 0, dim));
  PetscCall(PetscSectionSetChart(s, pStart, pEnd));
  for (PetscInt v = m->vStart; v < vEnd; v++) {
    PetscCall(PetscSectionSetDof(s, v, dim));
    PetscCall(PetscSectionSetFieldDof(s, v, 0, dim));
    if (m->bcmask[v - m->vStart] == (1 << dim) - 1) { /* partly fixed vertices keep their block (see bcmask) */
      PetscCall(PetscSectionSetConstraintDof(s, v, dim));
      PetscCall(PetscSectionSetFieldConstraintDof(s, v, 0, dim));
    }
  }
  PetscCall(PetscSectionSetUp(s));
  for (PetscInt v = m->vStart; v < vEnd; v++)
    if (m->bcmask[v - m->vStart] == (1 << dim) - 1) {
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
      if (m->bcmask[i] == (1 << dim) - 1) {
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
  const PetscInt dim = m->dim;
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
PetscErrorCode SgMeshFreeRigidMotions(MPI_Comm comm, const SgMesh *m, PetscInt *nfree, PetscReal modes[], PetscReal c[3])
{
  const PetscInt dim = m->dim, nr = dim == 2 ? 3 : 6;
  PetscReal      box[6] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, L = 0;
  PetscScalar    G[36] = {0}, work[64];
  PetscReal      ev[6];
  PetscBLASInt   n, lwork = 64, info;

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
  /* a vertex shared by ranks counts on each of them for the fully fixed ones (they have no owner in goff): only the
     rank of the null space matters, not the weights */
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, G, 36, MPIU_SCALAR, MPIU_SUM, comm));
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

PetscErrorCode SgMeshDestroy(SgMesh *m)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree6(m->cellv, m->x, m->gblock, m->loff, m->goff, m->bcgroup));
  PetscCall(PetscFree2(m->bcmask, m->bcpart));
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
