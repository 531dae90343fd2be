/* box.c: the structured simplex box mesh (-box_*): its options, vertices, cells and face markers. */
#include "fem/femimpl.h"
#include <unistd.h>

const char *const SgBoxDiagonals[] = {"right", "left", "mirror", "SgBoxDiagonal", "SG_BOX_", NULL};

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

/* The sizes of the box mesh in floating point first: an impossible mesh is refused before any int overflow or
   allocation (fstr: -box_faces as given); nbytes: the memory building it takes. */
static PetscErrorCode BoxCheckSize(MPI_Comm comm, PetscInt dim, const PetscInt faces[], const char fstr[], double *nbytes)
{
  const double nvd = (faces[0] + 1.0) * (faces[1] + 1.0) * (dim == 3 ? faces[2] + 1.0 : 1.0);
  const double ncd = dim == 2 ? 2.0 * faces[0] * faces[1] : 6.0 * faces[0] * faces[1] * faces[2];
  /* entries of the largest index arrays of the interpolated DMPlex (Euler: edges ~ vertices + cells; 3D faces ~ 2 cells):
     2D points 2V+2C, cones 2V+5C; 3D points 2V+4C, cones 2V+12C */
  const double idx  = dim == 2 ? 2 * nvd + 5 * ncd : 2 * nvd + 12 * ncd;
  double       phys = (double)sysconf(_SC_PHYS_PAGES) * (double)sysconf(_SC_PAGE_SIZE), bytes;

  PetscFunctionBeginUser;
  /* measured peak memory of building the box mesh on rank 0 and distributing it: about 265 B per triangle and 590 B per
     tetrahedron (a lower bound, without the solver); rank 0's machine decides, so every rank stops alike */
  bytes = (dim == 2 ? 250.0 : 550.0) * ncd;
  PetscCallMPI(MPI_Bcast(&phys, 1, MPI_DOUBLE, 0, comm));

  PetscCheck(idx <= (double)PETSC_MAX_INT, comm, PETSC_ERR_USER_INPUT, "-box_faces %s: the box mesh would have %.0f vertices and %.0f %s, beyond the range of PetscInt in this PETSc build (index arrays of about %.3g entries, at most %" PetscInt_FMT "); it would also need at least %.3g GB of memory", fstr, nvd, ncd, dim == 2 ? "triangles" : "tetrahedra", idx, (PetscInt)PETSC_MAX_INT, bytes / 1e9);
  PetscCheck(phys <= 0 || bytes <= phys, comm, PETSC_ERR_USER_INPUT, "-box_faces %s: the box mesh (%.0f vertices, %.0f %s) needs at least %.3g GB of memory to build on one rank, but this machine has %.3g GB", fstr, nvd, ncd, dim == 2 ? "triangles" : "tetrahedra", bytes / 1e9, phys / 1e9);
  *nbytes = bytes;
  PetscFunctionReturn(0);
}

/* The vertices and cells of the box (on rank 0): each square split along its diagonal diag, each cube into the six Kuhn
   tetrahedra. */
static void BoxFill(PetscInt dim, const PetscInt faces[], const PetscReal lo[], const PetscReal hi[], SgBoxDiagonal diag, PetscReal coords[], PetscInt cells[])
{
  const PetscInt nx = faces[0], ny = faces[1], nz = dim == 3 ? faces[2] : 1;
  PetscInt       c = 0;

  for (PetscInt k = 0; k < (dim == 3 ? nz + 1 : 1); k++)
    for (PetscInt j = 0; j <= ny; j++)
      for (PetscInt i = 0; i <= nx; i++) {
        const PetscInt v    = (k * (ny + 1) + j) * (nx + 1) + i;
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
        const PetscInt k = diag == SG_BOX_MIRROR ? (2 * i < nx ? SG_BOX_LEFT : SG_BOX_RIGHT) : diag;
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

/* The "Face Sets" of the box (on rank 0, before the distribution): each boundary face by the side its centre lies on. */
static PetscErrorCode BoxMarkFaces(DM dm, PetscInt dim, const PetscReal lo[], const PetscReal hi[])
{
  DMLabel            bd, fs;
  IS                 is;
  const PetscInt    *faces_;
  PetscInt           nf;
  Vec                cl;
  PetscSection       cs;
  const PetscScalar *ca;
  PetscInt           vStart, vEnd;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMLabelCreate(PETSC_COMM_SELF, "boundary", &bd));
  PetscCall(DMPlexMarkBoundaryFaces(dm, 1, bd));
  PetscCall(DMGetLabel(dm, "Face Sets", &fs));
  PetscCall(DMGetCoordinatesLocal(dm, &cl));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(VecGetArrayRead(cl, &ca));
  PetscCall(DMLabelGetStratumIS(bd, 1, &is));
  PetscCall(ISGetLocalSize(is, &nf));
  PetscCall(ISGetIndices(is, &faces_));
  for (PetscInt f = 0; f < nf; f++) {
    PetscInt *cl_ = NULL, ncl, nfv = 0;
    PetscReal cen[3] = {0, 0, 0};

    PetscCall(DMPlexGetTransitiveClosure(dm, faces_[f], PETSC_TRUE, &ncl, &cl_));
    for (PetscInt q = 0; q < 2 * ncl; q += 2) {
      PetscInt off;
      if (cl_[q] < vStart || cl_[q] >= vEnd) continue;
      PetscCall(PetscSectionGetOffset(cs, cl_[q], &off));
      for (PetscInt d = 0; d < dim; d++) cen[d] += PetscRealPart(ca[off + d]);
      nfv++;
    }
    PetscCall(DMPlexRestoreTransitiveClosure(dm, faces_[f], PETSC_TRUE, &ncl, &cl_));
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
  PetscFunctionReturn(0);
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
  double         bytes = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscSNPrintf(fstr, sizeof(fstr), dim == 2 ? "%" PetscInt_FMT ",%" PetscInt_FMT : "%" PetscInt_FMT ",%" PetscInt_FMT ",%" PetscInt_FMT, faces[0], faces[1], faces[2]));
  PetscCall(BoxCheckSize(comm, dim, faces, fstr, &bytes));
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
  if (rank == 0) BoxFill(dim, faces, lo, hi, diag, coords, cells);
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
  if (rank == 0) PetscCall(BoxMarkFaces(*dm, dim, lo, hi));
  PetscFunctionReturn(0);
}

/* The box's options (registered even when a mesh file is given, so that -help lists them): dimension, cells per axis,
   corners, diagonals. */
PetscErrorCode SgBoxFromOptions(MPI_Comm comm, const char prefix[], SgBox *box)
{
  PetscInt ndim = 1;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(box, sizeof(*box))); /* the defaults: the unit square, 10 x 10 faces, right diagonals */
  box->dim  = 2;
  box->diag = SG_BOX_RIGHT;
  for (PetscInt k = 0; k < 3; k++) box->faces[k] = 10, box->hi[k] = 1;
  PetscOptionsBegin(comm, prefix, "Structured simplex box mesh (used without -dm_plex_filename)", NULL);
  PetscCall(SgOptionsIntList(PetscOptionsObject, "-box_dim", "Spatial dimension of the box: 2 or 3", 1, &box->dim, &ndim, NULL));
  PetscCheck(box->dim == 2 || box->dim == 3, comm, PETSC_ERR_USER_INPUT, "-box_dim: the dimension must be 2 or 3, got %" PetscInt_FMT, box->dim);
  box->nfaces = box->nlo = box->nhi = box->dim;
  PetscCall(SgOptionsIntList(PetscOptionsObject, "-box_faces", "Number of cells along each axis (dim numbers)", SG_OPT_MAX, box->faces, &box->nfaces, NULL));
  PetscCall(SgOptionsRealList(PetscOptionsObject, "-box_lower", "Lower corner of the box (dim numbers)", SG_OPT_MAX, box->lo, &box->nlo, NULL));
  PetscCall(SgOptionsRealList(PetscOptionsObject, "-box_upper", "Upper corner of the box (dim numbers)", SG_OPT_MAX, box->hi, &box->nhi, NULL));
  PetscCall(PetscOptionsEnum("-box_diagonal", "2D: direction of the diagonal splitting each square (mirror: symmetric about the middle of x)", NULL, SgBoxDiagonals, (PetscEnum)box->diag, (PetscEnum *)&box->diag, NULL));
  PetscOptionsEnd();
  {
    /* PETSc keeps the default for an enum given without a value */
    const char *val;
    PetscBool   has;
    PetscCall(PetscOptionsFindPair(NULL, prefix, "-box_diagonal", &val, &has));
    PetscCheck(!has || (val && val[0]), comm, PETSC_ERR_USER_INPUT, "-box_diagonal is given without a value (right, left or mirror)");
  }
  PetscFunctionReturn(0);
}

/* The box mesh of the options (on rank 0, not yet distributed); every entry must come from the user. */
PetscErrorCode SgBoxCreateDM(MPI_Comm comm, const SgBox *box, DM *dm)
{
  const PetscInt      dim = box->dim, *faces = box->faces;
  const PetscReal    *lo = box->lo, *hi = box->hi;
  const SgBoxDiagonal diag = box->diag;

  PetscFunctionBeginUser;
  /* every entry from the user: a missing one would silently come from the default, an extra one be ignored */
  PetscCheck(box->nfaces == dim, comm, PETSC_ERR_USER_INPUT, "-box_faces: give %" PetscInt_FMT " numbers for -box_dim %" PetscInt_FMT ", got %" PetscInt_FMT, dim, dim, box->nfaces);
  PetscCheck(box->nlo == dim, comm, PETSC_ERR_USER_INPUT, "-box_lower: give %" PetscInt_FMT " numbers for -box_dim %" PetscInt_FMT ", got %" PetscInt_FMT, dim, dim, box->nlo);
  PetscCheck(box->nhi == dim, comm, PETSC_ERR_USER_INPUT, "-box_upper: give %" PetscInt_FMT " numbers for -box_dim %" PetscInt_FMT ", got %" PetscInt_FMT, dim, dim, box->nhi);
  for (PetscInt d = 0; d < dim; d++) {
    PetscCheck(faces[d] > 0, comm, PETSC_ERR_USER_INPUT, "-box_faces: entry %" PetscInt_FMT " is %" PetscInt_FMT ", must be positive", d, faces[d]);
    PetscCheck(PetscIsNormalReal(hi[d] - lo[d]) && hi[d] > lo[d], comm, PETSC_ERR_USER_INPUT, "-box_lower/-box_upper: axis %" PetscInt_FMT " has lower %g >= upper %g", d, (double)lo[d], (double)hi[d]);
  }
  PetscCheck(diag != SG_BOX_MIRROR || (dim == 2 && faces[0] % 2 == 0), comm, PETSC_ERR_USER_INPUT, "-box_diagonal mirror: needs -box_dim 2 and an even number of squares along x (-box_faces %" PetscInt_FMT ",...)", faces[0]);
  PetscCall(BoxMeshCreate(comm, dim, faces, lo, hi, diag, dm));
  PetscFunctionReturn(0);
}
