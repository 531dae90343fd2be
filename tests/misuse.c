/* misuse.c: libsignorini's public functions called wrongly, through the public header only: NULL handles, pointers
   and arrays, DMs of the wrong kind, values out of range, calls out of order, a problem destroyed before its controller
   is used, the caller's DM changed after it was handed over. Each wrong call must return an error code (with a message
   naming what is wrong), never crash or touch freed memory; each right call around them must still work.

   -case NAME runs one group of cases (problem, cont, options, files, order, refcount, dm_copy, materials, pair), without it all of
   them in sequence (-case defaults, the default linear solver of two problems, only when named). PETSc's errors return to us meanwhile (an error handler that records the message). The JSON
   summary (-summary_file) holds the number of cases checked ("cases") and of cases that misbehaved ("bad"), and what
   the right calls computed; the program exits nonzero if any case misbehaved. */
#include <signorini.h>
#include <stdlib.h>
#include <petscdmda.h>

static const char help[] = "Misuse of libsignorini's public functions: every wrong call must return an error.\n\n";

static char     LastError[2048];
static PetscInt Cases, Bad;

/* records the message of the first error of a wrong call; the error code goes back up the caller's chain */
static PetscErrorCode RecordError(MPI_Comm comm, int line, const char *fn, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  if (p == PETSC_ERROR_INITIAL && !LastError[0]) snprintf(LastError, sizeof(LastError), "%s", mess ? mess : "");
  return n;
}

/* The outcome of a wrong call: an error (of the class `code` unless it is 0) whose message contains `want`. */
static PetscErrorCode Expect(const char what[], PetscErrorCode ierr, PetscErrorCode code, const char want[])
{
  PetscBool ok    = (PetscBool)(ierr != 0 && (!code || ierr == code));
  char     *found = NULL;

  PetscFunctionBeginUser;
  if (ok && want) {
    PetscCall(PetscStrstr(LastError, want, &found));
    ok = (PetscBool)(found != NULL);
  }
  Cases++;
  if (!ok) Bad++;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s %s: error %d (want %d%s%s%s): %s\n", ok ? "ok" : "not ok", what, (int)ierr, (int)code, want ? ", message with '" : "", want ? want : "", want ? "'" : "", LastError));
  PetscFunctionReturn(0);
}

/* a right call that must succeed (and a check that must hold) */
static PetscErrorCode Check(const char what[], PetscBool ok)
{
  PetscFunctionBeginUser;
  Cases++;
  if (!ok) Bad++;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s %s\n", ok ? "ok" : "not ok", what));
  PetscFunctionReturn(0);
}

#define WRONG(call, code, want)                          \
  do {                                                   \
    PetscErrorCode e_;                                   \
    LastError[0] = 0;                                    \
    PetscCall(PetscPushErrorHandler(RecordError, NULL)); \
    e_ = (call);                                         \
    PetscCall(PetscPopErrorHandler());                   \
    PetscCall(Expect(#call, e_, code, want));            \
  } while (0)

#define RIGHT(call)                                                          \
  do {                                                                       \
    PetscErrorCode e_;                                                       \
    LastError[0] = 0;                                                        \
    PetscCall(PetscPushErrorHandler(RecordError, NULL));                     \
    e_ = (call);                                                             \
    PetscCall(PetscPopErrorHandler());                                       \
    if (e_) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "    %s\n", LastError)); \
    PetscCall(Check(#call, (PetscBool)(e_ == 0)));                           \
  } while (0)

/* A small problem on the options' box (-box_faces): the top (box marker 3) pushed down and to the side, the bottom
   (marker 1) on the default plane obstacle y = 0. */
static PetscErrorCode MakeProblem(SgProblem *p)
{
  const PetscInt  top = 3, bottom = 1;
  const PetscReal u[2] = {0.002, -0.01};

  PetscFunctionBeginUser;
  PetscCall(SgProblemCreate(PETSC_COMM_WORLD, p));
  PetscCall(SgProblemSetMaterial(*p, 1000, 0.3));
  PetscCall(SgProblemSetBoundary(*p, SG_BOUNDARY_DIRICHLET, "Face Sets", 1, &top, u));
  PetscCall(SgProblemSetBoundary(*p, SG_BOUNDARY_CONTACT, "Face Sets", 1, &bottom, NULL));
  PetscFunctionReturn(0);
}

/* A DM that is not a DMPlex: a 2D DMDA */
static PetscErrorCode MakeDMDA(DM *da)
{
  PetscFunctionBeginUser;
  PetscCall(DMDACreate2d(PETSC_COMM_WORLD, DM_BOUNDARY_NONE, DM_BOUNDARY_NONE, DMDA_STENCIL_STAR, 5, 5, PETSC_DECIDE, PETSC_DECIDE, 2, 1, NULL, NULL, da));
  PetscCall(DMSetUp(*da));
  PetscFunctionReturn(0);
}

/* The box [0,2]x[0,1] in nx x ny squares cut into triangles, on rank 0, distributed; label "sides": the bottom
   facets 1, the top facets 3 (as the box's "Face Sets"). */
static PetscErrorCode MakeBox(PetscInt nx, PetscInt ny, DM *dm)
{
  PetscMPIInt rank;
  PetscInt    nv = 0, nc = 0, *cells = NULL, fStart, fEnd;
  PetscReal  *xy = NULL;
  DMLabel     sides;
  DM          dist = NULL;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (!rank) {
    nv = (nx + 1) * (ny + 1);
    nc = 2 * nx * ny;
    PetscCall(PetscMalloc2(2 * nv, &xy, 3 * nc, &cells));
    for (PetscInt j = 0; j <= ny; j++)
      for (PetscInt i = 0; i <= nx; i++) {
        xy[2 * (j * (nx + 1) + i)]     = 2.0 * i / nx;
        xy[2 * (j * (nx + 1) + i) + 1] = 1.0 * j / ny;
      }
    for (PetscInt j = 0, c = 0; j < ny; j++)
      for (PetscInt i = 0; i < nx; i++, c += 2) {
        const PetscInt a = j * (nx + 1) + i, b = a + 1, d = a + nx + 1, e = d + 1;
        const PetscInt t[6] = {a, b, e, a, e, d};
        for (PetscInt k = 0; k < 6; k++) cells[3 * c + k] = t[k];
      }
  }
  PetscCall(DMPlexCreateFromCellListPetsc(PETSC_COMM_WORLD, 2, nc, nv, 3, PETSC_TRUE, cells, 2, xy, dm));
  PetscCall(PetscFree2(xy, cells));
  PetscCall(DMCreateLabel(*dm, "sides"));
  PetscCall(DMGetLabel(*dm, "sides", &sides));
  PetscCall(DMPlexGetHeightStratum(*dm, 1, &fStart, &fEnd));
  for (PetscInt f = fStart; f < fEnd; f++) {
    PetscInt  ns;
    PetscReal x[3];
    PetscCall(DMPlexGetSupportSize(*dm, f, &ns));
    if (ns != 1) continue;
    PetscCall(DMPlexComputeCellGeometryFVM(*dm, f, NULL, x, NULL));
    if (x[1] < 1e-12) PetscCall(DMLabelSetValue(sides, f, 1));
    else if (x[1] > 1 - 1e-12) PetscCall(DMLabelSetValue(sides, f, 3));
  }
  PetscCall(DMPlexDistribute(*dm, 0, NULL, &dist));
  if (dist) {
    PetscCall(DMDestroy(dm));
    *dm = dist;
  }
  PetscFunctionReturn(0);
}

/* SgProblem: creation, the DM, the setters and the getters, each called wrongly */
static PetscErrorCode CasesProblem(void)
{
  SgProblem   p = NULL, q = NULL;
  DM          da, plex, bare, quads;
  Vec         v, y;
  const char *s;
  PetscInt    n, ids[2] = {1, 3}, mask0 = 0, mask8 = 8, faces[2] = {2, 2};
  PetscReal   V, nanv = NAN, vals[4] = {0, 0, 0, 0}, bad[2] = {0, NAN};
  PetscBool   has;
  char        longname[400];

  PetscFunctionBeginUser;
  PetscCall(MakeDMDA(&da));
  PetscCall(MakeBox(4, 2, &plex));
  PetscCall(DMCreate(PETSC_COMM_WORLD, &bare));
  PetscCall(VecCreateMPI(PETSC_COMM_WORLD, PETSC_DECIDE, 7, &v));
  PetscCall(DMPlexCreateBoxMesh(PETSC_COMM_WORLD, 2, PETSC_FALSE, faces, NULL, NULL, NULL, PETSC_TRUE, &quads));
  for (size_t i = 0; i < sizeof(longname) - 1; i++) longname[i] = 'a';
  longname[sizeof(longname) - 1] = 0;

  WRONG(SgProblemCreate(PETSC_COMM_WORLD, NULL), PETSC_ERR_ARG_NULL, "SgProblemCreate");
  WRONG(SgProblemCreate(MPI_COMM_NULL, &q), PETSC_ERR_ARG_WRONG, "MPI_COMM_NULL");
  PetscCall(Check("SgProblemCreate(MPI_COMM_NULL) leaves the handle NULL", (PetscBool)!q));
  WRONG(SgProblemCreateFromDM(NULL, &q), PETSC_ERR_ARG_NULL, "DM");
  WRONG(SgProblemCreateFromDM(da, &q), PETSC_ERR_ARG_WRONG, "DMPLEX");
  WRONG(SgProblemCreateFromDM(bare, &q), PETSC_ERR_ARG_WRONG, "DMPLEX");
  WRONG(SgProblemCreateFromDM((DM)v, &q), PETSC_ERR_ARG_WRONG, "not a DM");
  WRONG(SgProblemCreateFromDM(plex, NULL), PETSC_ERR_ARG_NULL, "SgProblemCreateFromDM");
  PetscCall(Check("the failed creations leave the handle NULL", (PetscBool)!q));

  PetscCall(SgProblemCreate(PETSC_COMM_WORLD, &p));
  WRONG(SgProblemSetDM(NULL, plex), PETSC_ERR_ARG_NULL, "SgProblem");
  WRONG(SgProblemSetDM(p, NULL), PETSC_ERR_ARG_NULL, "DM");
  WRONG(SgProblemSetDM(p, da), PETSC_ERR_ARG_WRONG, "DMPLEX");
  WRONG(SgProblemSetOptionsPrefix(NULL, "a_"), PETSC_ERR_ARG_NULL, "SgProblem");
  WRONG(SgProblemSetOptionsPrefix(p, "-a_"), PETSC_ERR_ARG_WRONG, "hyphen");
  WRONG(SgProblemGetOptionsPrefix(p, NULL), PETSC_ERR_ARG_NULL, "prefix");
  WRONG(SgProblemGetOptionsPrefix(NULL, &s), PETSC_ERR_ARG_NULL, "SgProblem");
  WRONG(SgProblemSetMaterial(NULL, 1, 0.3), PETSC_ERR_ARG_NULL, "SgProblem");
  WRONG(SgProblemSetMaterial(p, 0, 0.3), PETSC_ERR_ARG_OUTOFRANGE, "Young");
  WRONG(SgProblemSetMaterial(p, -5, 0.3), PETSC_ERR_ARG_OUTOFRANGE, "Young");
  WRONG(SgProblemSetMaterial(p, nanv, 0.3), PETSC_ERR_ARG_OUTOFRANGE, "Young");
  WRONG(SgProblemSetMaterial(p, (PetscReal)INFINITY, 0.3), PETSC_ERR_ARG_OUTOFRANGE, "Young");
  WRONG(SgProblemSetMaterial(p, 1, 0.5), PETSC_ERR_ARG_OUTOFRANGE, "Poisson");
  WRONG(SgProblemSetMaterial(p, 1, 0.7), PETSC_ERR_ARG_OUTOFRANGE, "Poisson");
  WRONG(SgProblemSetMaterial(p, 1, -1.5), PETSC_ERR_ARG_OUTOFRANGE, "Poisson");
  WRONG(SgProblemSetMaterial(p, 1, nanv), PETSC_ERR_ARG_OUTOFRANGE, "Poisson");
  {
    const PetscInt  mids[2] = {1, 2}, dup[2] = {1, 1}, neg[1] = {-1};
    const PetscReal mE[2] = {1, 2}, mnu[2] = {0.3, 0.2}, bE[2] = {1, -2}, bnu[2] = {0.3, 0.5};
    WRONG(SgProblemSetMaterials(NULL, NULL, 2, mids, mE, mnu), PETSC_ERR_ARG_NULL, "SgProblem");
    WRONG(SgProblemSetMaterials(p, NULL, 0, mids, mE, mnu), PETSC_ERR_ARG_OUTOFRANGE, "0 materials");
    WRONG(SgProblemSetMaterials(p, NULL, 33, mids, mE, mnu), PETSC_ERR_ARG_OUTOFRANGE, "33 materials");
    WRONG(SgProblemSetMaterials(p, NULL, 2, NULL, mE, mnu), PETSC_ERR_ARG_NULL, "arrays");
    WRONG(SgProblemSetMaterials(p, NULL, 2, mids, mE, NULL), PETSC_ERR_ARG_NULL, "arrays");
    WRONG(SgProblemSetMaterials(p, NULL, 2, dup, mE, mnu), PETSC_ERR_ARG_WRONG, "id 1 is given twice");
    WRONG(SgProblemSetMaterials(p, NULL, 1, neg, mE, mnu), PETSC_ERR_ARG_OUTOFRANGE, ">= 0");
    WRONG(SgProblemSetMaterials(p, NULL, 2, mids, bE, mnu), PETSC_ERR_ARG_OUTOFRANGE, "Young's modulus of id 2");
    WRONG(SgProblemSetMaterials(p, NULL, 2, mids, mE, bnu), PETSC_ERR_ARG_OUTOFRANGE, "Poisson's ratio of id 2");
    RIGHT(SgProblemSetMaterials(p, "Cell Sets", 2, mids, mE, mnu));
    RIGHT(SgProblemSetMaterial(p, 1, 0.3)); /* one material again (the box below has no cell label) */
  }
  WRONG(SgProblemSetBoundary(NULL, SG_BOUNDARY_CONTACT, "Face Sets", 0, NULL, NULL), PETSC_ERR_ARG_NULL, "SgProblem");
  WRONG(SgProblemSetBoundary(p, SG_BOUNDARY_DIRICHLET, "Face Sets", -1, ids, NULL), PETSC_ERR_ARG_OUTOFRANGE, "ids");
  WRONG(SgProblemSetBoundary(p, SG_BOUNDARY_DIRICHLET, "Face Sets", 33, ids, NULL), PETSC_ERR_ARG_OUTOFRANGE, "ids");
  WRONG(SgProblemSetBoundary(p, SG_BOUNDARY_DIRICHLET, "Face Sets", 2, NULL, vals), PETSC_ERR_ARG_NULL, "NULL");
  WRONG(SgProblemSetBoundary(p, SG_BOUNDARY_DIRICHLET, NULL, 1, ids, NULL), PETSC_ERR_ARG_NULL, "label");
  WRONG(SgProblemSetBoundary(p, SG_BOUNDARY_DIRICHLET, "", 1, ids, NULL), PETSC_ERR_ARG_NULL, "label");
  WRONG(SgProblemSetBoundary(p, SG_BOUNDARY_DIRICHLET, longname, 1, ids, NULL), PETSC_ERR_ARG_SIZ, "label");
  WRONG(SgProblemSetBoundary(p, (SgBoundaryType)7, "Face Sets", 1, ids, NULL), PETSC_ERR_ARG_OUTOFRANGE, "type");
  WRONG(SgProblemSetBoundary(p, (SgBoundaryType)-1, "Face Sets", 1, ids, NULL), PETSC_ERR_ARG_OUTOFRANGE, "type");
  WRONG(SgProblemSetBoundary(p, SG_BOUNDARY_CONTACT, "Face Sets", 1, ids, vals), PETSC_ERR_ARG_WRONG, "no values");
  WRONG(SgProblemSetBoundary(p, SG_BOUNDARY_NEUMANN, "Face Sets", 1, ids, bad), PETSC_ERR_ARG_OUTOFRANGE, "finite");
  WRONG(SgProblemSetDirichletComponents(p, 1, &mask0), PETSC_ERR_ORDER, "Dirichlet part first");
  PetscCall(SgProblemSetBoundary(p, SG_BOUNDARY_DIRICHLET, "Face Sets", 2, ids, NULL));
  WRONG(SgProblemSetDirichletComponents(NULL, 2, ids), PETSC_ERR_ARG_NULL, "SgProblem");
  WRONG(SgProblemSetDirichletComponents(p, 2, NULL), PETSC_ERR_ARG_NULL, "NULL");
  WRONG(SgProblemSetDirichletComponents(p, 1, &mask0), PETSC_ERR_ARG_SIZ, "masks");
  WRONG(SgProblemSetDirichletComponents(p, -2, ids), PETSC_ERR_ARG_SIZ, "masks");
  {
    PetscInt m[2] = {1, 0};
    WRONG(SgProblemSetDirichletComponents(p, 2, m), PETSC_ERR_ARG_OUTOFRANGE, "mask");
    m[1] = mask8;
    WRONG(SgProblemSetDirichletComponents(p, 2, m), PETSC_ERR_ARG_OUTOFRANGE, "mask");
  }
  WRONG(SgProblemSetObstacleType(NULL, "plane"), PETSC_ERR_ARG_NULL, "SgProblem");
  WRONG(SgProblemSetObstacleType(p, longname), PETSC_ERR_ARG_SIZ, "type name");
  WRONG(SgProblemSetFromOptions(NULL), PETSC_ERR_ARG_NULL, "SgProblem");
  WRONG(SgProblemSetUp(NULL), PETSC_ERR_ARG_NULL, "SgProblem");
  WRONG(SgProblemView(NULL, NULL), PETSC_ERR_ARG_NULL, "SgProblem");
  WRONG(SgProblemView(p, (PetscViewer)v), PETSC_ERR_ARG_WRONG, "PetscViewer");
  WRONG(SgProblemDestroy(NULL), PETSC_ERR_ARG_NULL, "SgProblemDestroy");
  /* getters before the mesh exists */
  WRONG(SgProblemGetDM(p, &bare), PETSC_ERR_ORDER, "SgProblemSetUp");
  WRONG(SgProblemGetDimension(p, &n), PETSC_ERR_ORDER, "SgProblemSetFromOptions");
  WRONG(SgProblemGetSizes(p, &n, NULL, NULL), PETSC_ERR_ORDER, "SgProblemSetUp");
  WRONG(SgProblemHasContact(p, &has), PETSC_ERR_ORDER, "SgProblemSetFromOptions");
  WRONG(SgProblemCreateVector(p, &y), PETSC_ERR_ORDER, "SgProblemSetUp");
  WRONG(SgProblemComputeEnergy(p, v, &V), PETSC_ERR_ORDER, "SgProblemSetUp");
  WRONG(SgProblemGetDirichletSize(p, &n), PETSC_ERR_ORDER, "SgProblemSetUp");
  WRONG(SgProblemGetDM(NULL, &bare), PETSC_ERR_ARG_NULL, "SgProblem");
  WRONG(SgProblemGetSizes(NULL, &n, NULL, NULL), PETSC_ERR_ARG_NULL, "SgProblem");
  WRONG(SgProblemGetLoadFactor(NULL, &V), PETSC_ERR_ARG_NULL, "SgProblem");
  WRONG(SgProblemGetLoadFactor(p, NULL), PETSC_ERR_ARG_NULL, "SgProblemGetLoadFactor");
  RIGHT(SgProblemGetLoadFactor(p, &V));
  PetscCall(Check("the load factor is 1 before SetUp", (PetscBool)(V == 1)));
  PetscCall(SgProblemDestroy(&p));

  /* a problem set up: the getters' outputs, vectors of another layout, load factors and values out of range */
  PetscCall(MakeProblem(&p));
  RIGHT(SgProblemSetUp(p));
  WRONG(SgProblemSetMaterial(p, 1, 0.3), PETSC_ERR_ORDER, "before SgProblemSetFromOptions");
  WRONG(SgProblemSetDM(p, plex), PETSC_ERR_ORDER, "before SgProblemSetFromOptions");
  WRONG(SgProblemSetBoundary(p, SG_BOUNDARY_CONTACT, "Face Sets", 0, NULL, NULL), PETSC_ERR_ORDER, "before SgProblemSetFromOptions");
  WRONG(SgProblemSetFromOptions(p), PETSC_ERR_ORDER, "twice");
  WRONG(SgProblemGetDM(p, NULL), PETSC_ERR_ARG_NULL, "SgProblemGetDM");
  WRONG(SgProblemGetDimension(p, NULL), PETSC_ERR_ARG_NULL, "SgProblemGetDimension");
  WRONG(SgProblemHasContact(p, NULL), PETSC_ERR_ARG_NULL, "SgProblemHasContact");
  WRONG(SgProblemCreateVector(p, NULL), PETSC_ERR_ARG_NULL, "SgProblemCreateVector");
  WRONG(SgProblemGetDirichletSize(p, NULL), PETSC_ERR_ARG_NULL, "SgProblemGetDirichletSize");
  WRONG(SgProblemComputeEnergy(p, NULL, &V), PETSC_ERR_ARG_NULL, "Vec");
  WRONG(SgProblemComputeEnergy(p, (Vec)plex, &V), PETSC_ERR_ARG_WRONG, "not a Vec");
  WRONG(SgProblemComputeEnergy(p, v, &V), PETSC_ERR_ARG_SIZ, "SgProblemCreateVector");
  PetscCall(SgProblemCreateVector(p, &y));
  WRONG(SgProblemComputeEnergy(p, y, NULL), PETSC_ERR_ARG_NULL, "SgProblemComputeEnergy");
  RIGHT(SgProblemComputeEnergy(p, y, &V));
  PetscCall(Check("the energy of y = 0 is finite", (PetscBool)PetscIsNormalReal(V)));
  PetscCall(VecDestroy(&y));
  WRONG(SgProblemSetLoadFactor(NULL, 1), PETSC_ERR_ARG_NULL, "SgProblem");
  RIGHT(SgProblemSetLoadFactor(p, 0)); /* unloaded: y = 0 solves it (a load path back to zero) */
  WRONG(SgProblemSetLoadFactor(p, -1), PETSC_ERR_ARG_OUTOFRANGE, "finite and >= 0");
  WRONG(SgProblemSetLoadFactor(p, nanv), PETSC_ERR_ARG_OUTOFRANGE, "finite and >= 0");
  WRONG(SgProblemSetLoadFactor(p, (PetscReal)INFINITY), PETSC_ERR_ARG_OUTOFRANGE, "finite and >= 0");
  RIGHT(SgProblemSetLoadFactor(p, 1));
  WRONG(SgProblemSetDirichletValues(NULL, vals), PETSC_ERR_ARG_NULL, "SgProblem");
  WRONG(SgProblemSetDirichletValues(p, bad), PETSC_ERR_ARG_OUTOFRANGE, "finite");
  RIGHT(SgProblemGetDirichletSize(p, &n));
  PetscCall(Check("the Dirichlet size is 2 (one id, 2D)", (PetscBool)(n == 2)));
  RIGHT(SgProblemView(p, NULL));
  PetscCall(SgProblemDestroy(&p));
  PetscCall(Check("SgProblemDestroy sets the handle to NULL", (PetscBool)!p));
  RIGHT(SgProblemDestroy(&p)); /* a NULL handle: nothing to do */

  /* a mesh PETSc makes but the library cannot use (quadrilaterals): a clear error when the options are read */
  RIGHT(SgProblemCreateFromDM(quads, &p));
  WRONG(SgProblemSetFromOptions(p), PETSC_ERR_USER_INPUT, "triangles");
  PetscCall(SgProblemDestroy(&p));

  /* an empty DMPlex (no mesh in it): refused when the options are read */
  {
    DM empty;
    PetscCall(DMCreate(PETSC_COMM_WORLD, &empty));
    PetscCall(DMSetType(empty, DMPLEX));
    RIGHT(SgProblemCreateFromDM(empty, &p));
    PetscCall(DMDestroy(&empty));
    WRONG(SgProblemSetFromOptions(p), PETSC_ERR_USER_INPUT, "dimension");
    WRONG(SgProblemSetUp(p), PETSC_ERR_USER_INPUT, "dimension");
    PetscCall(SgProblemDestroy(&p));
  }

  /* values given before the mesh exists are read with -box_dim's dimension (2 here): a 3D box is then refused */
  PetscCall(SgProblemCreate(PETSC_COMM_WORLD, &p));
  PetscCall(SgProblemSetOptionsPrefix(p, "d3_"));
  PetscCall(SgProblemSetBoundary(p, SG_BOUNDARY_DIRICHLET, "Face Sets", 2, ids, vals));
  PetscCall(PetscOptionsSetValue(NULL, "-d3_box_dim", "3"));
  PetscCall(PetscOptionsSetValue(NULL, "-d3_box_faces", "2,2,2"));
  WRONG(SgProblemSetFromOptions(p), PETSC_ERR_ARG_INCOMP, "SgProblemSetDM");
  PetscCall(SgProblemDestroy(&p));
  PetscCall(PetscOptionsClearValue(NULL, "-d3_box_dim"));
  PetscCall(PetscOptionsClearValue(NULL, "-d3_box_faces"));

  PetscCall(VecDestroy(&v));
  PetscCall(DMDestroy(&quads));
  PetscCall(DMDestroy(&bare));
  PetscCall(DMDestroy(&plex));
  PetscCall(DMDestroy(&da));
  PetscFunctionReturn(0);
}

static PetscErrorCode MyCreate(SgCont ct)
{
  return 0;
}

/* SgCont: creation, settings, getters before and after a solve */
static PetscErrorCode CasesCont(void)
{
  SgProblem   p;
  SgCont      c = NULL;
  SgKKT       kkt;
  Vec         y, v;
  SNES        snes;
  const char *s;
  PetscInt    n;
  PetscReal   t, nanv = NAN;
  PetscBool   set;

  PetscFunctionBeginUser;
  PetscCall(MakeProblem(&p));
  PetscCall(VecCreateMPI(PETSC_COMM_WORLD, PETSC_DECIDE, 7, &v));
  WRONG(SgContCreate(NULL, &c), PETSC_ERR_ARG_NULL, "SgProblem");
  WRONG(SgContCreate(p, NULL), PETSC_ERR_ARG_NULL, "SgContCreate");
  PetscCall(Check("the failed creations leave the handle NULL", (PetscBool)!c));
  WRONG(SgContSolve(NULL), PETSC_ERR_ARG_NULL, "SgCont");
  WRONG(SgContSetFromOptions(NULL), PETSC_ERR_ARG_NULL, "SgCont");
  WRONG(SgContSetUp(NULL), PETSC_ERR_ARG_NULL, "SgCont");
  WRONG(SgContView(NULL, NULL), PETSC_ERR_ARG_NULL, "SgCont");
  WRONG(SgContDestroy(NULL), PETSC_ERR_ARG_NULL, "SgContDestroy");
  WRONG(SgContGetKKT(NULL, &kkt), PETSC_ERR_ARG_NULL, "SgCont");
  WRONG(SgContGetEnergy(NULL, &t), PETSC_ERR_ARG_NULL, "SgCont");
  WRONG(SgContGetConvergedReason(NULL, &set, &s), PETSC_ERR_ARG_NULL, "SgCont");
  WRONG(SgContGetIterationNumbers(NULL, &n, &n, &n), PETSC_ERR_ARG_NULL, "SgCont");
  WRONG(SgContWriteSummary(NULL, ""), PETSC_ERR_ARG_NULL, "SgCont");
  WRONG(SgContWriteHistory(NULL, ""), PETSC_ERR_ARG_NULL, "SgCont");
  WRONG(SgContWriteLoadCurve(NULL, ""), PETSC_ERR_ARG_NULL, "SgCont");
  WRONG(SgContWriteFields(NULL, "", 1), PETSC_ERR_ARG_NULL, "SgCont");
  WRONG(SgContSetStoreSteps(NULL, PETSC_TRUE), PETSC_ERR_ARG_NULL, "SgCont");
  WRONG(SgContGetLoadSteps(NULL, &n), PETSC_ERR_ARG_NULL, "SgCont");
  WRONG(SgContRegister(NULL, MyCreate), PETSC_ERR_ARG_NULL, "type name");
  WRONG(SgContRegister("mine", NULL), PETSC_ERR_ARG_NULL, "SgContRegister");

  PetscCall(SgContCreate(p, &c));
  /* PETSc objects: an object of the other class is refused by the class id of its header */
  WRONG(SgContSolve((SgCont)p), PETSC_ERR_ARG_WRONG, "is not a SgCont");
  WRONG(SgProblemSetUp((SgProblem)c), PETSC_ERR_ARG_WRONG, "is not a SgProblem");
  WRONG(SgProblemView((SgProblem)v, NULL), PETSC_ERR_ARG_WRONG, "is not a SgProblem");
  WRONG(SgContSetMonitor(NULL, PETSC_FALSE), PETSC_ERR_ARG_NULL, "SgCont");
  WRONG(SgContSetMonitor(c, 7), PETSC_ERR_ARG_OUTOFRANGE, "PETSC_TRUE");
  WRONG(SgContPrintHelp(NULL), PETSC_ERR_ARG_NULL, "SgCont");
  RIGHT(SgContPrintHelp(c)); /* without -help: nothing */
  WRONG(SgObstacleRegister(NULL, NULL), PETSC_ERR_ARG_NULL, "type name");
  WRONG(SgObstacleRegister("mine", NULL), PETSC_ERR_ARG_NULL, "SgObstacleRegister");
  {
    const char *cname = NULL;
    RIGHT(PetscObjectGetClassName((PetscObject)c, &cname));
    PetscCall(Check("an SgCont is a PetscObject of class SgCont", (PetscBool)(cname && !strcmp(cname, "SgCont"))));
    RIGHT(PetscObjectGetClassName((PetscObject)p, &cname));
    PetscCall(Check("an SgProblem is a PetscObject of class SgProblem", (PetscBool)(cname && !strcmp(cname, "SgProblem"))));
  }
  WRONG(SgContSetType(NULL, "ipf"), PETSC_ERR_ARG_NULL, "SgCont");
  WRONG(SgContSetType(c, NULL), PETSC_ERR_ARG_NULL, "type name");
  WRONG(SgContSetType(c, "nosuch"), PETSC_ERR_ARG_UNKNOWN_TYPE, "nosuch");
  WRONG(SgContGetType(c, NULL), PETSC_ERR_ARG_NULL, "SgContGetType");
  WRONG(SgContSetOptionsPrefix(NULL, "a_"), PETSC_ERR_ARG_NULL, "SgCont");
  WRONG(SgContSetOptionsPrefix(c, "-a_"), PETSC_ERR_ARG_WRONG, "hyphen");
  WRONG(SgContGetOptionsPrefix(c, NULL), PETSC_ERR_ARG_NULL, "SgContGetOptionsPrefix");
  WRONG(SgContSetTolerances(NULL, 1e-8, 10), PETSC_ERR_ARG_NULL, "SgCont");
  WRONG(SgContSetTolerances(c, 0, 10), PETSC_ERR_ARG_OUTOFRANGE, "tolerance");
  WRONG(SgContSetTolerances(c, -1e-8, 10), PETSC_ERR_ARG_OUTOFRANGE, "tolerance");
  WRONG(SgContSetTolerances(c, nanv, 10), PETSC_ERR_ARG_OUTOFRANGE, "tolerance");
  WRONG(SgContSetTolerances(c, 1e-8, 0), PETSC_ERR_ARG_OUTOFRANGE, "limit");
  WRONG(SgContSetTolerances(c, 1e-8, -5), PETSC_ERR_ARG_OUTOFRANGE, "limit");
  WRONG(SgContSetStoreSteps(c, 7), PETSC_ERR_ARG_OUTOFRANGE, "PETSC_TRUE");
  WRONG(SgContView(c, (PetscViewer)v), PETSC_ERR_ARG_WRONG, "PetscViewer");
  /* getters before the solve: an error where there is nothing to give, else the state "not run" */
  WRONG(SgContGetKKT(c, NULL), PETSC_ERR_ARG_NULL, "SgContGetKKT");
  WRONG(SgContGetKKT(c, &kkt), PETSC_ERR_ORDER, "SgContSolve first");
  WRONG(SgContGetEnergy(c, NULL), PETSC_ERR_ARG_NULL, "SgContGetEnergy");
  WRONG(SgContGetSolution(c, &y), PETSC_ERR_ORDER, "first");
  WRONG(SgContGetSolution(c, NULL), PETSC_ERR_ARG_NULL, "SgContGetSolution");
  WRONG(SgContGetSNES(c, NULL), PETSC_ERR_ARG_NULL, "SgContGetSNES");
  WRONG(SgContGetLoadSteps(c, NULL), PETSC_ERR_ARG_NULL, "SgContGetLoadSteps");
  WRONG(SgContGetLoadStepFactor(c, 0, &t), PETSC_ERR_ARG_OUTOFRANGE, "load step");
  WRONG(SgContGetLoadStepFactor(c, 0, NULL), PETSC_ERR_ARG_NULL, "SgContGetLoadStepFactor");
  WRONG(SgContGetLoadStepDirichletValues(c, 0, NULL, NULL), PETSC_ERR_ARG_NULL, "SgContGetLoadStepDirichletValues");
  WRONG(SgContGetLoadStepDirichletValues(c, -1, &set, NULL), PETSC_ERR_ARG_OUTOFRANGE, "load step");
  WRONG(SgContWriteSummary(c, ""), PETSC_ERR_ORDER, "SgContSolve first");
  WRONG(SgContWriteFields(c, "", 1), PETSC_ERR_ORDER, "SgContSolve first");
  WRONG(SgContWriteFields(c, "", nanv), PETSC_ERR_ARG_OUTOFRANGE, "magnification");
  RIGHT(SgContGetLoadSteps(c, &n));
  PetscCall(Check("no load steps before the solve", (PetscBool)(n == 0)));
  RIGHT(SgContGetType(c, &s));

  PetscCall(SgContSetType(c, SGCONTPDAS));
  RIGHT(SgContSolve(c)); /* SetFromOptions and SetUp on the way */
  {
    const char *type = NULL;
    RIGHT(PetscObjectGetType((PetscObject)c, &type));
    PetscCall(Check("PetscObjectGetType gives the controller's type", (PetscBool)(type && !strcmp(type, SGCONTPDAS))));
  }
  WRONG(SgContSetMonitor(c, PETSC_FALSE), PETSC_ERR_ORDER, "before SgContSetFromOptions");
  WRONG(SgContSetType(c, SGCONTIPF), PETSC_ERR_ORDER, "before SgContSetFromOptions");
  WRONG(SgContSetTolerances(c, 1e-8, 10), PETSC_ERR_ORDER, "before SgContSetFromOptions");
  WRONG(SgContSetFromOptions(c), PETSC_ERR_ORDER, "twice");
  WRONG(SgContSetStoreSteps(c, PETSC_TRUE), PETSC_ERR_ORDER, "before the first SgContSolve");
  WRONG(SgContGetLoadStepFactor(c, 1, &t), PETSC_ERR_ARG_OUTOFRANGE, "load step");
  WRONG(SgContGetLoadStepFactor(c, -1, &t), PETSC_ERR_ARG_OUTOFRANGE, "load step");
  WRONG(SgContGetLoadStepFactor(c, PETSC_MAX_INT, &t), PETSC_ERR_ARG_OUTOFRANGE, "load step");
  WRONG(SgContGetLoadStepDirichletValues(c, 5, &set, NULL), PETSC_ERR_ARG_OUTOFRANGE, "load step");
  RIGHT(SgContGetLoadStepFactor(c, 0, &t));
  PetscCall(Check("load step 0 at factor 1", (PetscBool)(t == 1)));
  RIGHT(SgContGetKKT(c, &kkt));
  PetscCall(Check("the pdas solve has an active set", (PetscBool)(kkt.nactive > 0)));
  RIGHT(SgContGetSNES(c, &snes));
  PetscCall(Check("pdas has no SNES", (PetscBool)!snes));
  RIGHT(SgContView(c, NULL));
  RIGHT(SgContWriteSummary(c, NULL));
  RIGHT(SgContWriteHistory(c, NULL));
  RIGHT(SgContWriteLoadCurve(c, NULL));
  RIGHT(SgContWriteFields(c, NULL, 1));
  PetscCall(SgContDestroy(&c));
  PetscCall(Check("SgContDestroy sets the handle to NULL", (PetscBool)!c));
  RIGHT(SgContDestroy(&c));
  PetscCall(SgProblemDestroy(&p));
  PetscCall(VecDestroy(&v));
  PetscFunctionReturn(0);
}

/* The option readers outside PetscOptionsBegin/End, and with wrong arrays and counts inside */
static PetscErrorCode CasesOptions(void)
{
  PetscInt  iv[3] = {1, 2, 3}, n, i1 = 0;
  PetscReal rv[3] = {0, 0, 0}, r1 = 0;
  PetscBool b = PETSC_FALSE;
  char      name[64];

  PetscFunctionBeginUser;
  n = 1;
  WRONG(SgOptionsIntList(NULL, "-misuse_list", "help", 3, iv, &n, NULL), PETSC_ERR_ARG_NULL, "PetscOptionsBegin");
  WRONG(SgOptionsRealList(NULL, "-misuse_list", "help", 3, rv, &n, NULL), PETSC_ERR_ARG_NULL, "PetscOptionsBegin");
  WRONG(SgOptionsRealValue(NULL, "-misuse_value", "help", &r1, NULL), PETSC_ERR_ARG_NULL, "PetscOptionsBegin");
  WRONG(SgOptionsIntValue(NULL, "-misuse_value", "help", &i1, NULL), PETSC_ERR_ARG_NULL, "PetscOptionsBegin");
  WRONG(SgOptionsBoolValue(NULL, "-misuse_value", "help", &b, NULL), PETSC_ERR_ARG_NULL, "PetscOptionsBegin");
  WRONG(SgOptionsFileName(NULL, "-misuse_file", "help", name, sizeof(name), NULL), PETSC_ERR_ARG_NULL, "PetscOptionsBegin");
  WRONG(SgOptionsName(NULL, NULL, name, sizeof(name)), PETSC_ERR_ARG_NULL, "SgOptionsName");
  WRONG(SgOptionsName(NULL, "-x", NULL, sizeof(name)), PETSC_ERR_ARG_NULL, "SgOptionsName");
  WRONG(SgOptionsName(NULL, "-x", name, 0), PETSC_ERR_ARG_SIZ, "length 0");
  RIGHT(SgOptionsName("p_", "-x", name, sizeof(name)));
  PetscCall(Check("SgOptionsName gives -p_x", (PetscBool)!strcmp(name, "-p_x")));
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "misuse", NULL);
  n = 1;
  WRONG(SgOptionsIntList(PetscOptionsObject, NULL, "help", 3, iv, &n, NULL), PETSC_ERR_ARG_NULL, "option's name");
  WRONG(SgOptionsFileName(PetscOptionsObject, NULL, "help", name, sizeof(name), NULL), PETSC_ERR_ARG_NULL, "option's name");
  WRONG(SgOptionsFileName(PetscOptionsObject, "-misuse_file", "help", NULL, sizeof(name), NULL), PETSC_ERR_ARG_NULL, "SgOptionsFileName");
  WRONG(SgOptionsFileName(PetscOptionsObject, "-misuse_file", "help", name, 0, NULL), PETSC_ERR_ARG_SIZ, "length 0");
  WRONG(SgOptionsIntList(PetscOptionsObject, "-misuse_list", "help", 3, NULL, &n, NULL), PETSC_ERR_ARG_NULL, "array");
  WRONG(SgOptionsIntList(PetscOptionsObject, "-misuse_list", "help", 3, iv, NULL, NULL), PETSC_ERR_ARG_NULL, "count");
  WRONG(SgOptionsIntList(PetscOptionsObject, "-misuse_list", "help", 0, iv, &n, NULL), PETSC_ERR_ARG_OUTOFRANGE, "entries");
  WRONG(SgOptionsIntList(PetscOptionsObject, "-misuse_list", "help", 100000, iv, &n, NULL), PETSC_ERR_ARG_OUTOFRANGE, "entries");
  n = -1;
  WRONG(SgOptionsIntList(PetscOptionsObject, "-misuse_list", "help", 3, iv, &n, NULL), PETSC_ERR_ARG_OUTOFRANGE, "default values");
  n = 4;
  WRONG(SgOptionsRealList(PetscOptionsObject, "-misuse_list", "help", 3, rv, &n, NULL), PETSC_ERR_ARG_OUTOFRANGE, "default values");
  n = 1;
  WRONG(SgOptionsRealList(PetscOptionsObject, "-misuse_list", "help", 3, NULL, &n, NULL), PETSC_ERR_ARG_NULL, "array");
  WRONG(SgOptionsRealValue(PetscOptionsObject, "-misuse_value", "help", NULL, NULL), PETSC_ERR_ARG_NULL, "SgOptionsRealValue");
  WRONG(SgOptionsIntValue(PetscOptionsObject, "-misuse_value", "help", NULL, NULL), PETSC_ERR_ARG_NULL, "SgOptionsIntValue");
  WRONG(SgOptionsBoolValue(PetscOptionsObject, "-misuse_value", "help", NULL, NULL), PETSC_ERR_ARG_NULL, "SgOptionsBoolValue");
  WRONG(SgOptionsBoolValue(PetscOptionsObject, NULL, "help", &b, NULL), PETSC_ERR_ARG_NULL, "option's name");
  n = 3;
  RIGHT(SgOptionsIntList(PetscOptionsObject, "-misuse_list", "help", 3, iv, &n, NULL));
  PetscOptionsEnd();
  PetscCall(Check("an option not given keeps the 3 defaults", (PetscBool)(n == 3 && iv[2] == 3)));
  PetscFunctionReturn(0);
}

/* The file checks: no option name, no communicator; a NULL file name means no file */
static PetscErrorCode CasesFiles(void)
{
  PetscFunctionBeginUser;
  WRONG(SgFileCheckWritable(PETSC_COMM_WORLD, NULL, "x.json"), PETSC_ERR_ARG_NULL, "option");
  WRONG(SgFileCheckWritable(PETSC_COMM_WORLD, "", "x.json"), PETSC_ERR_ARG_NULL, "option");
  WRONG(SgFileCheckWritable(MPI_COMM_NULL, "-misuse_file", "x.json"), PETSC_ERR_ARG_WRONG, "MPI_COMM_NULL");
  WRONG(SgFileCheckInput(PETSC_COMM_WORLD, NULL, "x.msh"), PETSC_ERR_ARG_NULL, "option");
  WRONG(SgFileCheckInput(MPI_COMM_NULL, "-misuse_file", "x.msh"), PETSC_ERR_ARG_WRONG, "MPI_COMM_NULL");
  RIGHT(SgFileCheckWritable(PETSC_COMM_WORLD, "-misuse_file", NULL));
  RIGHT(SgFileCheckWritable(PETSC_COMM_WORLD, "-misuse_file", ""));
  RIGHT(SgFileCheckInput(PETSC_COMM_WORLD, "-misuse_input", NULL));
  RIGHT(SgFileInstallCleanup());
  RIGHT(SgFileInstallCleanup()); /* twice: still one handler */
  PetscFunctionReturn(0);
}

/* Calls out of order that are fine: a solve without SetFromOptions/SetUp, the getters' "not run" values before it */
static PetscErrorCode CasesOrder(PetscReal *energy)
{
  SgProblem   p;
  SgCont      c;
  PetscBool   conv   = PETSC_TRUE;
  const char *reason = NULL;
  PetscReal   V      = 0;
  PetscInt    outer = -1, ssn = -1, ksp = -1;
  SgKKT       kkt;

  PetscFunctionBeginUser;
  PetscCall(MakeProblem(&p));
  PetscCall(SgContCreate(p, &c));
  RIGHT(SgContGetConvergedReason(c, &conv, &reason));
  PetscCall(Check("before the solve: not converged, NOT_RUN", (PetscBool)(!conv && reason && !strcmp(reason, "NOT_RUN"))));
  RIGHT(SgContGetConvergedReason(c, NULL, NULL));
  RIGHT(SgContGetEnergy(c, &V));
  PetscCall(Check("before the solve: the energy is NaN", (PetscBool)PetscIsNanReal(V)));
  RIGHT(SgContGetIterationNumbers(c, &outer, &ssn, &ksp));
  PetscCall(Check("before the solve: no iterations", (PetscBool)(outer == 0 && ssn == 0 && ksp == 0)));
  RIGHT(SgContGetIterationNumbers(c, NULL, NULL, NULL));
  RIGHT(SgContView(c, NULL));
  RIGHT(SgContSolve(c));
  RIGHT(SgContGetConvergedReason(c, &conv, &reason));
  PetscCall(Check("a solve without SgContSetFromOptions converges", conv));
  RIGHT(SgContGetEnergy(c, &V));
  RIGHT(SgContGetKKT(c, &kkt));
  PetscCall(Check("its energy is finite and positive (the clamped part is moved), its active set not empty", (PetscBool)(PetscIsNormalReal(V) && V > 0 && kkt.nactive > 0)));
  RIGHT(SgContSolve(c)); /* again at the same load: a warm start */
  *energy = V;
  PetscCall(SgContDestroy(&c));
  PetscCall(SgProblemDestroy(&p));

  /* a set-up that stops with an error (a contact id no facet has) is not retried on its half-made state */
  {
    const PetscInt top = 3, nosuch = 77;
    PetscCall(SgProblemCreate(PETSC_COMM_WORLD, &p));
    PetscCall(SgProblemSetBoundary(p, SG_BOUNDARY_DIRICHLET, "Face Sets", 1, &top, NULL));
    PetscCall(SgProblemSetBoundary(p, SG_BOUNDARY_CONTACT, "Face Sets", 1, &nosuch, NULL));
    PetscCall(SgContCreate(p, &c));
    WRONG(SgContSolve(c), PETSC_ERR_USER_INPUT, "77");
    WRONG(SgContSolve(c), PETSC_ERR_ORDER, "earlier");
    WRONG(SgContSetUp(c), PETSC_ERR_ORDER, "earlier");
    WRONG(SgProblemSetUp(p), 0, NULL);
    PetscCall(SgContDestroy(&c));
    PetscCall(SgProblemDestroy(&p));
  }
  PetscFunctionReturn(0);
}

/* The controller holds its problem: the caller's SgProblemDestroy before the controller's SetFromOptions lets only
   the handle go; the controller still solves, and SgContDestroy frees the problem. Two controllers of one problem
   destroyed in either order. */
static PetscErrorCode CasesRefcount(PetscReal *energy, PetscReal *energy_ref)
{
  SgProblem   p, q;
  SgCont      c, d;
  PetscBool   conv;
  const char *reason;

  PetscFunctionBeginUser;
  PetscCall(MakeProblem(&p));
  {
    PetscInt n1 = 0, n2 = 0, n3 = 0;
    RIGHT(PetscObjectGetReference((PetscObject)p, &n1));
    PetscCall(SgContCreate(p, &c));
    RIGHT(PetscObjectGetReference((PetscObject)p, &n2));
    q = p;
    RIGHT(SgProblemDestroy(&p));
    RIGHT(PetscObjectGetReference((PetscObject)q, &n3)); /* the controller's reference keeps it */
    PetscCall(Check("the controller holds a PETSc reference to its problem (1, 2, then 1 after the caller's destroy)", (PetscBool)(n1 == 1 && n2 == 2 && n3 == 1)));
  }
  PetscCall(Check("SgProblemDestroy sets the caller's handle to NULL", (PetscBool)!p));
  RIGHT(SgContSetFromOptions(c));
  RIGHT(SgContSolve(c));
  RIGHT(SgContGetConvergedReason(c, &conv, &reason));
  PetscCall(Check("the controller of a released problem converges", conv));
  RIGHT(SgContGetEnergy(c, energy));
  RIGHT(SgContDestroy(&c)); /* frees the problem too (valgrind / -malloc_dump see it) */
  (void)q;

  /* the reference: the same problem kept by the caller */
  PetscCall(MakeProblem(&p));
  PetscCall(SgContCreate(p, &c));
  PetscCall(SgContCreate(p, &d));
  RIGHT(SgContSolve(c));
  RIGHT(SgContGetEnergy(c, energy_ref));
  PetscCall(SgContDestroy(&c));
  RIGHT(SgProblemSetLoadFactor(p, 1)); /* the problem lives on */
  RIGHT(SgProblemDestroy(&p));
  RIGHT(SgContSolve(d)); /* and still, for the second controller */
  PetscCall(SgContDestroy(&d));
  PetscCall(Check("the energies agree", (PetscBool)(PetscAbsReal(*energy - *energy_ref) <= 1e-12 * PetscAbsReal(*energy_ref))));

  /* PetscObjectReference (the same as SgProblemReference) on a controller: two destroys needed, the first leaves it usable */
  PetscCall(MakeProblem(&p));
  PetscCall(SgContCreate(p, &c));
  PetscCall(SgProblemDestroy(&p));
  RIGHT(PetscObjectReference((PetscObject)c));
  d = c;
  RIGHT(SgContDestroy(&d));
  PetscCall(Check("SgContDestroy of one holder sets only its handle to NULL", (PetscBool)(!d && c)));
  RIGHT(SgContSolve(c));                        /* (not pdas: the first solve's default entered -ssn_condense into the options database) */
  RIGHT(PetscObjectDestroy((PetscObject *)&c)); /* PETSc's generic destroy reaches SgContDestroy */
  PetscCall(Check("PetscObjectDestroy sets the handle to NULL", (PetscBool)!c));

  /* SgProblemReference by hand: two destroys needed */
  PetscCall(MakeProblem(&p));
  RIGHT(SgProblemReference(p));
  q = p;
  RIGHT(SgProblemDestroy(&q));
  RIGHT(SgProblemSetUp(p));
  RIGHT(SgProblemDestroy(&p));
  WRONG(SgProblemReference(NULL), PETSC_ERR_ARG_NULL, "SgProblem");
  PetscFunctionReturn(0);
}

/* Energy and contact force of a solve of the problem on dm (label "sides": 3 clamped and moved, 1 in contact) with
   E = 1000, nu = 0.3 */
static PetscErrorCode SolveMaterials(SgProblem, PetscReal *, PetscReal *, PetscInt *);
static PetscErrorCode SolveOn(SgProblem p, PetscReal *V, PetscReal *force, PetscInt *nactive)
{
  PetscFunctionBeginUser;
  PetscCall(SgProblemSetMaterial(p, 1000, 0.3));
  PetscCall(SolveMaterials(p, V, force, nactive));
  PetscFunctionReturn(0);
}

/* The caller's DM changed after SgProblemCreateFromDM / SgProblemSetDM (its vertices moved, in the local and the
   global coordinates, and its label's values changed) must not change the problem: its solve equals that on an
   untouched copy of the mesh. A problem made from the changed DM sees the change (the test can fail). */
static PetscErrorCode CasesDMCopy(PetscReal res[6])
{
  DM        dmA, dmB;
  SgProblem pA, pA2, pB, pC;
  PetscReal VA, VA2, VB, VC, fA, fA2, fB, fC;
  PetscInt  nA, nA2, nB, nC;
  Vec       x;
  DMLabel   sides;
  PetscInt  fStart, fEnd;

  PetscFunctionBeginUser;
  PetscCall(MakeBox(8, 4, &dmA));
  PetscCall(MakeBox(8, 4, &dmB));
  PetscCall(SgProblemCreateFromDM(dmA, &pA));
  PetscCall(SgProblemCreate(PETSC_COMM_WORLD, &pA2));
  PetscCall(SgProblemSetDM(pA2, dmA));
  /* the caller moves its vertices: x stretched by 1.5, y by 0.8 (the local and the global coordinates) */
  PetscCall(DMGetCoordinatesLocal(dmA, &x));
  {
    PetscScalar *a;
    PetscInt     m;
    PetscCall(VecGetLocalSize(x, &m));
    PetscCall(VecGetArray(x, &a));
    for (PetscInt i = 0; i < m; i += 2) {
      a[i] *= 1.5;
      a[i + 1] *= 0.8;
    }
    PetscCall(VecRestoreArray(x, &a));
  }
  PetscCall(DMGetCoordinates(dmA, &x));
  {
    PetscScalar *a;
    PetscInt     m;
    PetscCall(VecGetLocalSize(x, &m));
    PetscCall(VecGetArray(x, &a));
    for (PetscInt i = 0; i < m; i += 2) {
      a[i] *= 1.5;
      a[i + 1] *= 0.8;
    }
    PetscCall(VecRestoreArray(x, &a));
  }
  /* and its label: the contact part (1) loses its first facets, which join the clamped part (3) */
  PetscCall(DMGetLabel(dmA, "sides", &sides));
  PetscCall(DMPlexGetHeightStratum(dmA, 1, &fStart, &fEnd));
  {
    PetscInt k = 0;
    for (PetscInt f = fStart; f < fEnd; f++) {
      PetscInt val;
      PetscCall(DMLabelGetValue(sides, f, &val));
      if (val == 1 && k++ < 3) {
        PetscCall(DMLabelClearValue(sides, f, 1));
        PetscCall(DMLabelSetValue(sides, f, 3));
      }
    }
  }
  { /* a DM on more ranks than the problem's communicator */
    PetscMPIInt size;
    SgProblem   pS;
    PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
    PetscCall(SgProblemCreate(PETSC_COMM_SELF, &pS));
    if (size > 1) WRONG(SgProblemSetDM(pS, dmB), PETSC_ERR_ARG_NOTSAMECOMM, "communicator");
    PetscCall(SgProblemDestroy(&pS));
  }
  PetscCall(SgProblemCreateFromDM(dmB, &pB)); /* the untouched mesh */
  PetscCall(SgProblemCreateFromDM(dmA, &pC)); /* the changed one */
  PetscCall(SolveOn(pA, &VA, &fA, &nA));
  PetscCall(SolveOn(pA2, &VA2, &fA2, &nA2));
  PetscCall(SolveOn(pB, &VB, &fB, &nB));
  PetscCall(SolveOn(pC, &VC, &fC, &nC));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "energies: changed DM %.15g (SetDM %.15g), untouched %.15g, made from the changed DM %.15g; active %" PetscInt_FMT " %" PetscInt_FMT " %" PetscInt_FMT " %" PetscInt_FMT "\n", (double)VA, (double)VA2, (double)VB, (double)VC, nA, nA2, nB, nC));
  PetscCall(Check("the problems of the changed DM solve as the untouched one", (PetscBool)(VA == VB && VA2 == VB && fA == fB && fA2 == fB && nA == nB && nA2 == nB)));
  PetscCall(Check("a problem made from the changed DM differs", (PetscBool)(PetscAbsReal(VC - VB) > 1e-3 * PetscAbsReal(VB))));
  res[0] = VA;
  res[1] = VA2;
  res[2] = VB;
  res[3] = VC;
  res[4] = fA;
  res[5] = fB;
  PetscCall(SgProblemDestroy(&pA));
  PetscCall(SgProblemDestroy(&pA2));
  PetscCall(SgProblemDestroy(&pB));
  PetscCall(SgProblemDestroy(&pC));
  PetscCall(DMDestroy(&dmA));
  PetscCall(DMDestroy(&dmB));
  PetscFunctionReturn(0);
}

/* SolveOn without its material: the one the problem was given (nactive may be NULL) */
static PetscErrorCode SolveMaterials(SgProblem p, PetscReal *V, PetscReal *force, PetscInt *nactive)
{
  const PetscInt  top = 3, bottom = 1;
  const PetscReal u[2] = {0.002, -0.01};
  SgCont          c;
  SgKKT           kkt;
  PetscBool       conv;

  PetscFunctionBeginUser;
  PetscCall(SgProblemSetBoundary(p, SG_BOUNDARY_DIRICHLET, "sides", 1, &top, u));
  PetscCall(SgProblemSetBoundary(p, SG_BOUNDARY_CONTACT, "sides", 1, &bottom, NULL));
  PetscCall(SgContCreate(p, &c));
  PetscCall(SgContSetType(c, SGCONTPDAS));
  PetscCall(SgContSolve(c));
  PetscCall(SgContGetConvergedReason(c, &conv, NULL));
  PetscCall(SgContGetEnergy(c, V));
  PetscCall(SgContGetKKT(c, &kkt));
  *force = kkt.force;
  if (nactive) *nactive = kkt.nactive;
  PetscCall(Check("the solve converges", conv));
  PetscCall(SgContDestroy(&c));
  PetscFunctionReturn(0);
}

/* SgProblemSetMaterials on the caller's DM with a cell label of its own ("mat": 1 for x < 1, 2 beyond): the same
   problem as the options (-m_material_*), equal materials the single material bit for bit, two materials another
   problem; an id the mesh lacks is refused at the set-up. */
static PetscErrorCode CasesMaterials(PetscReal res[4])
{
  const PetscInt  ids[2] = {1, 2}, bad[2] = {1, 5};
  const PetscReal E2[2] = {1000, 4000}, nu2[2] = {0.3, 0.2}, E1[2] = {1000, 1000}, nu1[2] = {0.3, 0.3};
  DM              dm;
  DMLabel         mat;
  PetscInt        cStart, cEnd;
  SgProblem       pA, pB, pC, pD, pE;
  PetscReal       VA, VB, VC, VD, fA, fB, fC, fD;

  PetscFunctionBeginUser;
  PetscCall(MakeBox(8, 4, &dm));
  PetscCall(DMCreateLabel(dm, "mat"));
  PetscCall(DMGetLabel(dm, "mat", &mat));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  for (PetscInt c = cStart; c < cEnd; c++) {
    PetscReal x[3];
    PetscCall(DMPlexComputeCellGeometryFVM(dm, c, NULL, x, NULL));
    PetscCall(DMLabelSetValue(mat, c, x[0] < 1 ? 1 : 2));
  }
  PetscCall(SgProblemCreateFromDM(dm, &pA));
  PetscCall(SgProblemSetMaterials(pA, "mat", 2, ids, E2, nu2));
  PetscCall(SolveMaterials(pA, &VA, &fA, NULL));
  PetscCall(SgProblemCreateFromDM(dm, &pB));
  PetscCall(SgProblemSetOptionsPrefix(pB, "m_"));
  PetscCall(PetscOptionsSetValue(NULL, "-m_material_label", "mat"));
  PetscCall(PetscOptionsSetValue(NULL, "-m_material_ids", "1,2"));
  PetscCall(PetscOptionsSetValue(NULL, "-m_E", "1000,4000"));
  PetscCall(PetscOptionsSetValue(NULL, "-m_nu", "0.3,0.2"));
  PetscCall(SolveMaterials(pB, &VB, &fB, NULL));
  PetscCall(SgProblemCreateFromDM(dm, &pC));
  PetscCall(SgProblemSetMaterials(pC, "mat", 2, ids, E1, nu1));
  PetscCall(SolveMaterials(pC, &VC, &fC, NULL));
  PetscCall(SgProblemCreateFromDM(dm, &pD));
  PetscCall(SgProblemSetMaterial(pD, 1000, 0.3));
  PetscCall(SolveMaterials(pD, &VD, &fD, NULL));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "energies: materials %.15g (options %.15g), equal materials %.15g, one material %.15g\n", (double)VA, (double)VB, (double)VC, (double)VD));
  PetscCall(Check("SgProblemSetMaterials solves as the options -material_*", (PetscBool)(VA == VB && fA == fB)));
  PetscCall(Check("equal materials are the single material", (PetscBool)(VC == VD && fC == fD)));
  PetscCall(Check("two materials are another problem", (PetscBool)(PetscAbsReal(VA - VD) > 1e-2 * PetscAbsReal(VD))));
  PetscCall(SgProblemCreateFromDM(dm, &pE));
  PetscCall(SgProblemSetMaterials(pE, "mat", 2, bad, E2, nu2));
  WRONG(SgProblemSetUp(pE), PETSC_ERR_USER_INPUT, "-material_label 'mat': cells have the value 2, which is not among -material_ids");
  { /* a label on some cells only: the others have no material */
    DMLabel   half;
    SgProblem pF;
    PetscCall(DMCreateLabel(dm, "half"));
    PetscCall(DMGetLabel(dm, "half", &half));
    for (PetscInt c = cStart; c < cEnd; c++) {
      PetscReal x[3];
      PetscCall(DMPlexComputeCellGeometryFVM(dm, c, NULL, x, NULL));
      if (x[0] < 1) PetscCall(DMLabelSetValue(half, c, 1));
    }
    PetscCall(SgProblemCreateFromDM(dm, &pF));
    PetscCall(SgProblemSetMaterials(pF, "half", 2, ids, E2, nu2));
    WRONG(SgProblemSetUp(pF), PETSC_ERR_USER_INPUT, "has no value of the label, so no material of -material_ids");
    PetscCall(SgProblemDestroy(&pF));
  }
  res[0] = VA;
  res[1] = VB;
  res[2] = VC;
  res[3] = VD;
  PetscCall(SgProblemDestroy(&pA));
  PetscCall(SgProblemDestroy(&pB));
  PetscCall(SgProblemDestroy(&pC));
  PetscCall(SgProblemDestroy(&pD));
  PetscCall(SgProblemDestroy(&pE));
  PetscCall(DMDestroy(&dm));
  PetscFunctionReturn(0);
}

/* a JSON number, or null for NaN */
/* The default linear solver is each problem's own (issue 26): a program that solves a larger problem (above
   -cont_direct_max_unknowns: CG + BoomerAMG, the truncated multigrid in the SSN steps), then a smaller one (MUMPS,
   condensed), then each again, gets each problem's default every time, with the same result; nothing of the defaults
   is left in PETSc's options database (which a later problem would read as the user's). res: the larger problem's
   energy at its first and its second solve, the smaller one's at both. */
static PetscErrorCode SolveDefault(PetscInt nx, PetscInt ny, const char want_ksp[], PetscReal *V)
{
  const PetscInt    top = 3, bottom = 1;
  const PetscReal   u[2]    = {0.002, -0.01};
  const char *const names[] = {"-ksp_type", "-pc_type", "-pc_factor_mat_solver_type", "-ksp_rtol", "-pc_hypre_type", "-pc_hypre_boomeramg_strong_threshold", "-pc_hypre_boomeramg_relax_type_down", "-ssn_condense", "-ssn_pc_truncated_mg", "-ssn_pc_truncated_mg_interp"};
  DM                dm;
  SgProblem         p;
  SgCont            c;
  SNES              snes;
  KSP               ksp;
  KSPType           kt;
  PetscBool         conv, left = PETSC_FALSE, same;
  char              what[256];

  PetscFunctionBeginUser;
  PetscCall(MakeBox(nx, ny, &dm));
  PetscCall(SgProblemCreateFromDM(dm, &p));
  PetscCall(DMDestroy(&dm));
  PetscCall(SgProblemSetMaterial(p, 1000, 0.3));
  PetscCall(SgProblemSetBoundary(p, SG_BOUNDARY_DIRICHLET, "sides", 1, &top, u));
  PetscCall(SgProblemSetBoundary(p, SG_BOUNDARY_CONTACT, "sides", 1, &bottom, NULL));
  PetscCall(SgContCreate(p, &c));
  PetscCall(SgProblemDestroy(&p));
  PetscCall(SgContSetFromOptions(c));
  PetscCall(SgContSolve(c));
  PetscCall(SgContGetConvergedReason(c, &conv, NULL));
  PetscCall(SgContGetEnergy(c, V));
  PetscCall(SgContGetSNES(c, &snes));
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPGetType(ksp, &kt));
  PetscCall(PetscStrcmp(kt, want_ksp, &same));
  PetscCall(PetscSNPrintf(what, sizeof(what), "%" PetscInt_FMT "x%" PetscInt_FMT ": the default Krylov method is %s (got %s), converged", nx, ny, want_ksp, kt));
  PetscCall(Check(what, (PetscBool)(same && conv)));
  for (size_t k = 0; k < sizeof(names) / sizeof(names[0]); k++) {
    PetscBool has;
    PetscCall(PetscOptionsHasName(NULL, NULL, names[k], &has));
    if (has) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "    %s is in the options database\n", names[k]));
    left = (PetscBool)(left || has);
  }
  PetscCall(PetscSNPrintf(what, sizeof(what), "%" PetscInt_FMT "x%" PetscInt_FMT ": nothing of the default solver left in the options database", nx, ny));
  PetscCall(Check(what, (PetscBool)!left));
  PetscCall(SgContDestroy(&c));
  PetscFunctionReturn(0);
}

static PetscErrorCode CasesDefaults(PetscReal res[4])
{
  PetscBool small_first = PETSC_FALSE, given; /* -defaults_small_first: the other order */

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-defaults_small_first", &small_first, NULL));
  /* the sizes below are chosen about -cont_direct_max_unknowns 300 (tests/features/solver_defaults.ini gives it): the
     group sets it itself when run alone (tests/fuzz.py picks groups at random), and removes it afterwards */
  PetscCall(PetscOptionsHasName(NULL, NULL, "-cont_direct_max_unknowns", &given));
  if (!given) PetscCall(PetscOptionsSetValue(NULL, "-cont_direct_max_unknowns", "300"));
  if (small_first) PetscCall(SolveDefault(8, 4, KSPPREONLY, &res[2])); /* 90 unknowns */
  PetscCall(SolveDefault(24, 12, KSPCG, &res[0]));                     /* 650 */
  if (!small_first) PetscCall(SolveDefault(8, 4, KSPPREONLY, &res[2]));
  PetscCall(SolveDefault(24, 12, KSPCG, &res[1]));
  PetscCall(SolveDefault(8, 4, KSPPREONLY, &res[3]));
  if (!given) PetscCall(PetscOptionsClearValue(NULL, "-cont_direct_max_unknowns"));
  PetscFunctionReturn(0);
}

/* Two bodies through SgProblemSetBoundary(SG_BOUNDARY_CONTACT_MASTER) on the caller's mesh (meshes/tb_stack2d.msh: two
   blocks 0.01 apart, the slave side 20 the upper block's bottom, the master side 10 the lower block's top): master
   sides that do not exist, lie on the slave's body, face away, or a slave side held by the Dirichlet data, and
   overlapping blocks (meshes/tb_overlap2d.msh) are errors of SgProblemSetUp that leave nothing behind (-malloc_dump);
   a problem whose SetUp failed refuses a second one; setters after SetUp are refused; the right pair solves the patch
   test (exact energy 0.5 0.04^2 / 0.91). */
static PetscErrorCode PairProblem(DM dm, PetscInt master, PetscBool held, SgProblem *p)
{
  const PetscInt  dids[5] = {1, 2, 3, 4, 20}, masks[5] = {SG_COMPONENT_Y, SG_COMPONENT_Y, SG_COMPONENT_X, SG_COMPONENT_X, SG_COMPONENT_X | SG_COMPONENT_Y}, slave = 20;
  const PetscReal dvals[10] = {0, 0, 0, -0.05, 0, 0, 0, 0, 0, 0};

  PetscFunctionBeginUser;
  PetscCall(SgProblemCreateFromDM(dm, p));
  PetscCall(SgProblemSetBoundary(*p, SG_BOUNDARY_DIRICHLET, "Face Sets", held ? 5 : 4, dids, dvals));
  PetscCall(SgProblemSetDirichletComponents(*p, held ? 5 : 4, masks));
  PetscCall(SgProblemSetBoundary(*p, SG_BOUNDARY_CONTACT, "Face Sets", 1, &slave, NULL));
  PetscCall(SgProblemSetBoundary(*p, SG_BOUNDARY_CONTACT_MASTER, "Face Sets", 1, &master, NULL));
  PetscFunctionReturn(0);
}

/* file (relative to the repository) read from the working directory, else from the repository this program was built
   in (bin/..: the random robustness test, tests/fuzz.py, runs it in a directory of its own) */
static PetscErrorCode ReadMesh(const char file[], DM *dm)
{
  DM        dist = NULL;
  char      path[PETSC_MAX_PATH_LEN], exe[PETSC_MAX_PATH_LEN];
  PetscBool found;

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(path, file, sizeof(path)));
  PetscCall(PetscTestFile(path, 'r', &found));
  if (!found && realpath("/proc/self/exe", exe)) { /* <repository>/bin/misuse_tests */
    char *slash = strrchr(exe, '/');
    if (slash) *slash = 0;
    slash = strrchr(exe, '/');
    if (slash) *slash = 0;
    PetscCall(PetscSNPrintf(path, sizeof(path), "%s/%s", exe, file));
  }
  PetscCall(DMPlexCreateFromFile(PETSC_COMM_WORLD, path, "mesh", PETSC_TRUE, dm));
  PetscCall(DMPlexDistribute(*dm, 0, NULL, &dist));
  if (dist) {
    PetscCall(DMDestroy(dm));
    *dm = dist;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode CasesPair(PetscReal *energy)
{
  DM        dm, dmo;
  SgProblem p;
  SgCont    c;
  PetscInt  bad = 99;
  PetscReal V;

  PetscFunctionBeginUser;
  PetscCall(ReadMesh("meshes/tb_stack2d.msh", &dm));
  PetscCall(PairProblem(dm, 99, PETSC_FALSE, &p));
  WRONG(SgProblemSetUp(p), PETSC_ERR_USER_INPUT, "-contact_master_ids: label 'Face Sets' has no points with value 99");
  WRONG(SgProblemSetUp(p), PETSC_ERR_ORDER, "an earlier call stopped with an error");
  PetscCall(SgProblemDestroy(&p));
  PetscCall(PairProblem(dm, 2, PETSC_FALSE, &p));
  WRONG(SgProblemSetUp(p), PETSC_ERR_USER_INPUT, "the slave and the master side lie on the same body");
  PetscCall(SgProblemDestroy(&p));
  PetscCall(PairProblem(dm, 1, PETSC_FALSE, &p));
  WRONG(SgProblemSetUp(p), PETSC_ERR_USER_INPUT, "no slave facet of 'Face Sets' faces a master facet");
  PetscCall(SgProblemDestroy(&p));
  PetscCall(PairProblem(dm, 10, PETSC_TRUE, &p));
  WRONG(SgProblemSetUp(p), PETSC_ERR_USER_INPUT, "every slave vertex opposite it is a Dirichlet vertex");
  PetscCall(SgProblemDestroy(&p));
  PetscCall(ReadMesh("meshes/tb_overlap2d.msh", &dmo));
  PetscCall(PairProblem(dmo, 10, PETSC_FALSE, &p));
  WRONG(SgProblemSetUp(p), PETSC_ERR_USER_INPUT, "the bodies overlap at the start");
  PetscCall(SgProblemDestroy(&p));
  PetscCall(DMDestroy(&dmo));
  /* the right pair; setters after SetUp are refused */
  PetscCall(PairProblem(dm, 10, PETSC_FALSE, &p));
  PetscCall(SgProblemSetUp(p));
  WRONG(SgProblemSetBoundary(p, SG_BOUNDARY_CONTACT_MASTER, "Face Sets", 1, &bad, NULL), PETSC_ERR_ORDER, "before SgProblemSetFromOptions/SgProblemSetUp");
  WRONG(SgProblemSetObstacleType(p, "plane"), PETSC_ERR_ORDER, "before SgProblemSetFromOptions/SgProblemSetUp");
  PetscCall(SgContCreate(p, &c));
  PetscCall(SgProblemDestroy(&p));
  PetscCall(SgProblemDestroy(&p)); /* NULL: nothing to do */
  PetscCall(SgContSetFromOptions(c));
  PetscCall(SgContSolve(c));
  PetscCall(SgContGetEnergy(c, &V));
  PetscCall(Check("the pair set through SgProblemSetBoundary solves the patch test", (PetscBool)(PetscAbsReal(V / (0.5 * 0.04 * 0.04 / 0.91) - 1) < 1e-8)));
  PetscCall(SgContDestroy(&c));
  PetscCall(SgContDestroy(&c));
  PetscCall(DMDestroy(&dm));
  *energy = V;
  PetscFunctionReturn(0);
}

static PetscErrorCode JSONReal(FILE *fp, const char key[], PetscReal v, const char end[])
{
  PetscFunctionBeginUser;
  if (PetscIsNanReal(v)) PetscCall(PetscFPrintf(PETSC_COMM_WORLD, fp, "\"%s\": null%s", key, end));
  else PetscCall(PetscFPrintf(PETSC_COMM_WORLD, fp, "\"%s\": %.17g%s", key, (double)v, end));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  char      which[64] = "", file[PETSC_MAX_PATH_LEN] = "";
  PetscBool all, is;
  PetscReal e_order = NAN, e_ref = NAN, e_ref2 = NAN, dmres[6] = {NAN, NAN, NAN, NAN, NAN, NAN}, matres[4] = {NAN, NAN, NAN, NAN}, defres[4] = {NAN, NAN, NAN, NAN}, e_pair = NAN;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-case", which, sizeof(which), NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-summary_file", file, sizeof(file), NULL));
  all = (PetscBool)!which[0];
  if (PetscStrcmp(which, "problem", &is) == 0 && (all || is)) PetscCall(CasesProblem());
  if (PetscStrcmp(which, "cont", &is) == 0 && (all || is)) PetscCall(CasesCont());
  if (PetscStrcmp(which, "options", &is) == 0 && (all || is)) PetscCall(CasesOptions());
  if (PetscStrcmp(which, "files", &is) == 0 && (all || is)) PetscCall(CasesFiles());
  if (PetscStrcmp(which, "order", &is) == 0 && (all || is)) PetscCall(CasesOrder(&e_order));
  if (PetscStrcmp(which, "refcount", &is) == 0 && (all || is)) PetscCall(CasesRefcount(&e_ref, &e_ref2));
  if (PetscStrcmp(which, "dm_copy", &is) == 0 && (all || is)) PetscCall(CasesDMCopy(dmres));
  if (PetscStrcmp(which, "materials", &is) == 0 && (all || is)) PetscCall(CasesMaterials(matres));
  if (PetscStrcmp(which, "pair", &is) == 0 && (all || is)) PetscCall(CasesPair(&e_pair));
  if (PetscStrcmp(which, "defaults", &is) == 0 && is) PetscCall(CasesDefaults(defres)); /* only when asked: it needs -cont_direct_max_unknowns */
  PetscCheck(Cases > 0, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "-case '%s': no such group (problem, cont, options, files, order, refcount, dm_copy, materials, pair, defaults)", which);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%" PetscInt_FMT " cases, %" PetscInt_FMT " misbehaved\n", Cases, Bad));
  if (file[0]) {
    FILE *fp;
    PetscCall(PetscFOpen(PETSC_COMM_WORLD, file, "w", &fp));
    PetscCall(PetscFPrintf(PETSC_COMM_WORLD, fp, "{\"case\": \"%s\", \"cases\": %" PetscInt_FMT ", \"bad\": %" PetscInt_FMT ", ", all ? "all" : which, Cases, Bad));
    PetscCall(JSONReal(fp, "energy_order", e_order, ", "));
    PetscCall(JSONReal(fp, "energy_released", e_ref, ", "));
    PetscCall(JSONReal(fp, "energy_kept", e_ref2, ", "));
    PetscCall(JSONReal(fp, "energy_changed_dm", dmres[0], ", "));
    PetscCall(JSONReal(fp, "energy_changed_dm_setdm", dmres[1], ", "));
    PetscCall(JSONReal(fp, "energy_untouched", dmres[2], ", "));
    PetscCall(JSONReal(fp, "energy_from_changed", dmres[3], ", "));
    PetscCall(JSONReal(fp, "force_changed_dm", dmres[4], ", "));
    PetscCall(JSONReal(fp, "force_untouched", dmres[5], ", "));
    PetscCall(JSONReal(fp, "energy_materials", matres[0], ", "));
    PetscCall(JSONReal(fp, "energy_materials_options", matres[1], ", "));
    PetscCall(JSONReal(fp, "energy_equal_materials", matres[2], ", "));
    PetscCall(JSONReal(fp, "energy_one_material", matres[3], ", "));
    PetscCall(JSONReal(fp, "energy_pair", e_pair, ", "));
    PetscCall(JSONReal(fp, "energy_default_large", defres[0], ", "));
    PetscCall(JSONReal(fp, "energy_default_large_again", defres[1], ", "));
    PetscCall(JSONReal(fp, "energy_default_small", defres[2], ", "));
    PetscCall(JSONReal(fp, "energy_default_small_again", defres[3], "}\n"));
    PetscCall(PetscFClose(PETSC_COMM_WORLD, fp));
  }
  PetscCall(PetscFinalize());
  return Bad ? 1 : 0;
}
