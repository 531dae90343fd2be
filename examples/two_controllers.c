/* two_controllers.c: a PETSc program of its own that uses libsignorini through its public header only. It builds its
   DMPlex and a boundary label, hands both to the library, and solves the same contact problem with two controllers
   in one program, each under its own options prefix: inexact path-following ("a_") and the augmented Lagrangian
   ("b_"). Both solve the contact problem (P) to the same KKT tolerance, so their energies and contact forces agree;
   the program exits nonzero if they do not, or if either solve fails.

   The body is the box [0,2]x[0,1] in triangles; its top is clamped and pushed down by 0.01, its bottom may touch a
   rigid plane slightly tilted below it (gap 0.001 at x = 0, growing by 0.01 per unit of x): the left part of the
   bottom comes into contact, the right part does not.

   Build against an installed library (examples/Makefile): mpicc two_controllers.c $(pkg-config --cflags --libs signorini)
   Run: ./two_controllers [-nx 40 -ny 20] [-agree_rtol 1e-8] [-a_... -b_... -body_... options] */
#include <signorini.h>

static const char help[] = "Solves one contact problem with two controllers of libsignorini (prefixes a_ and b_) and checks that they agree.\n\n";

/* Face markers of our own label "sides" (any values would do: they are passed to SgProblemSetBoundary) */
#define BOTTOM 10
#define TOP    20

/* An option's value unless the command line gave one: the program's defaults, which the user can still override. */
static PetscErrorCode SetDefault(const char name[], const char value[])
{
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasName(NULL, NULL, name, &set));
  if (!set) PetscCall(PetscOptionsSetValue(NULL, name, value));
  PetscFunctionReturn(0);
}

/* The box [0,L]x[0,H] in nx x ny squares, each cut in two triangles, made on rank 0 and distributed. (PETSc's
   DMPlexCreateBoxMesh needs Triangle for simplices, which Debian's PETSc does not have.) The boundary facets of the
   bottom and the top are marked in the label "sides" before distribution, so every rank gets its part of it. */
static PetscErrorCode CreateBox(MPI_Comm comm, PetscInt nx, PetscInt ny, PetscReal L, PetscReal H, DM *dm)
{
  PetscMPIInt rank;
  PetscInt    nv = 0, nc = 0, *cells = NULL, fStart, fEnd;
  PetscReal  *xy = NULL;
  DMLabel     sides;
  DM          dist = NULL;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    nv = (nx + 1) * (ny + 1);
    nc = 2 * nx * ny;
    PetscCall(PetscMalloc2(2 * nv, &xy, 3 * nc, &cells));
    for (PetscInt j = 0; j <= ny; j++)
      for (PetscInt i = 0; i <= nx; i++) {
        xy[2 * (j * (nx + 1) + i)]     = L * i / nx;
        xy[2 * (j * (nx + 1) + i) + 1] = H * j / ny;
      }
    for (PetscInt j = 0, c = 0; j < ny; j++)
      for (PetscInt i = 0; i < nx; i++, c += 2) {
        const PetscInt v00 = j * (nx + 1) + i, v10 = v00 + 1, v01 = v00 + nx + 1, v11 = v01 + 1;
        const PetscInt tri[6] = {v00, v10, v11, v00, v11, v01}; /* counterclockwise */
        for (PetscInt k = 0; k < 6; k++) cells[3 * c + k] = tri[k];
      }
  }
  PetscCall(DMPlexCreateFromCellListPetsc(comm, 2, nc, nv, 3, PETSC_TRUE, cells, 2, xy, dm));
  PetscCall(PetscFree2(xy, cells));

  PetscCall(DMCreateLabel(*dm, "sides"));
  PetscCall(DMGetLabel(*dm, "sides", &sides));
  PetscCall(DMPlexGetHeightStratum(*dm, 1, &fStart, &fEnd));
  for (PetscInt f = fStart; f < fEnd; f++) {
    PetscInt  ns;
    PetscReal centroid[3];

    PetscCall(DMPlexGetSupportSize(*dm, f, &ns));
    if (ns != 1) continue; /* an interior edge (the mesh is still whole on rank 0) */
    PetscCall(DMPlexComputeCellGeometryFVM(*dm, f, NULL, centroid, NULL));
    if (centroid[1] < 1e-8 * H) PetscCall(DMLabelSetValue(sides, f, BOTTOM));
    else if (centroid[1] > H * (1 - 1e-8)) PetscCall(DMLabelSetValue(sides, f, TOP));
  }

  PetscCall(DMPlexDistribute(*dm, 0, NULL, &dist));
  if (dist) {
    PetscCall(DMDestroy(dm));
    *dm = dist;
  }
  PetscFunctionReturn(0);
}

typedef struct {
  const char *prefix;
  char        type[64], reason[512]; /* copies: the controller's own strings go with it */
  PetscBool   converged;
  PetscReal   energy;
  SgKKT       kkt;
  PetscInt    its[3];
} Result;

/* One controller on the problem, under its own prefix: it reads -<prefix>cont_*, -<prefix>ksp_type and so on. */
static PetscErrorCode SolveWith(SgProblem prob, Result *r)
{
  SgCont      cont;
  const char *type, *reason;

  PetscFunctionBeginUser;
  PetscCall(SgContCreate(prob, &cont));
  PetscCall(SgContSetOptionsPrefix(cont, r->prefix));
  PetscCall(SgContSetType(cont, r->type));
  PetscCall(SgContSetFromOptions(cont)); /* -<prefix>cont_type may still change it */
  PetscCall(SgContSolve(cont));
  PetscCall(SgContGetType(cont, &type));
  PetscCall(PetscStrncpy(r->type, type, sizeof(r->type)));
  PetscCall(SgContGetConvergedReason(cont, &r->converged, &reason));
  PetscCall(PetscStrncpy(r->reason, reason, sizeof(r->reason)));
  PetscCall(SgContGetEnergy(cont, &r->energy));
  PetscCall(SgContGetKKT(cont, &r->kkt));
  PetscCall(SgContGetIterationNumbers(cont, &r->its[0], &r->its[1], &r->its[2]));
  PetscCall(SgContDestroy(&cont));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  MPI_Comm        comm;
  DM              dm;
  SgProblem       prob;
  PetscInt        nx = 40, ny = 20, nc, nv, ncontact;
  PetscReal       rtol     = 1e-8, de, df;
  const PetscInt  bottom[] = {BOTTOM}, top[] = {TOP};
  const PetscReal push[] = {0, -0.01}; /* displacement of the top (x, y) */
  Result          res[2] = {
               {.prefix = "a_", .type = SGCONTIPF},
               {.prefix = "b_", .type = SGCONTALM}
  };
  PetscBool ok = PETSC_TRUE;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  comm = PETSC_COMM_WORLD;
  PetscOptionsBegin(comm, NULL, "two_controllers: one problem, two controllers", NULL);
  PetscCall(PetscOptionsInt("-nx", "Cells along x", NULL, nx, &nx, NULL));
  PetscCall(PetscOptionsInt("-ny", "Cells along y", NULL, ny, &ny, NULL));
  PetscCall(PetscOptionsReal("-agree_rtol", "Largest relative difference of the two energies and contact forces", NULL, rtol, &rtol, NULL));
  PetscOptionsEnd();
  PetscCheck(nx > 0 && ny > 0, comm, PETSC_ERR_USER_INPUT, "-nx, -ny: need positive numbers of cells");

  /* The obstacle and both controllers' solvers, as a user's options file could give them */
  PetscCall(SetDefault("-body_obstacle_plane_point", "0,-0.001"));
  PetscCall(SetDefault("-body_obstacle_plane_normal", "0.01,1")); /* towards the body; the plane drops to the right */
  for (PetscInt i = 0; i < 2; i++) {
    char name[64];

    PetscCall(PetscSNPrintf(name, sizeof(name), "-%sksp_type", res[i].prefix));
    PetscCall(SetDefault(name, "preonly"));
    PetscCall(PetscSNPrintf(name, sizeof(name), "-%spc_type", res[i].prefix));
    PetscCall(SetDefault(name, "cholesky"));
    PetscCall(PetscSNPrintf(name, sizeof(name), "-%spc_factor_mat_solver_type", res[i].prefix));
    PetscCall(SetDefault(name, "mumps"));
    PetscCall(PetscSNPrintf(name, sizeof(name), "-%scont_kkt_tol", res[i].prefix));
    PetscCall(SetDefault(name, "1e-10"));
  }
  PetscCall(SetDefault("-b_alm_gamma", "1e6")); /* ALM's rate grows with gamma: its default 1e3 took more than 50 steps here */

  /* Our mesh and label, handed to the library: the problem takes its own reference to the DM */
  PetscCall(CreateBox(comm, nx, ny, 2.0, 1.0, &dm));
  PetscCall(SgProblemCreateFromDM(dm, &prob));
  PetscCall(DMDestroy(&dm));
  PetscCall(SgProblemSetOptionsPrefix(prob, "body_"));
  PetscCall(SgProblemSetMaterial(prob, 5000.0, 0.4));
  PetscCall(SgProblemSetBoundary(prob, SG_BOUNDARY_DIRICHLET, "sides", 1, top, push));
  PetscCall(SgProblemSetBoundary(prob, SG_BOUNDARY_CONTACT, "sides", 1, bottom, NULL));
  PetscCall(SgProblemSetObstacleType(prob, "plane"));
  PetscCall(SgProblemSetFromOptions(prob));
  PetscCall(SgProblemSetUp(prob));
  PetscCall(SgProblemGetSizes(prob, &nv, &nc, &ncontact));
  PetscCall(PetscPrintf(comm, "problem: %" PetscInt_FMT " vertices, %" PetscInt_FMT " cells, %" PetscInt_FMT " contact vertices\n", nv, nc, ncontact));

  for (PetscInt i = 0; i < 2; i++) {
    Result *r = &res[i];

    PetscCall(SolveWith(prob, r));
    PetscCall(PetscPrintf(comm, "%s (%s): %s, energy %.12e, contact force %.10e, %" PetscInt_FMT " active, iterations %" PetscInt_FMT " %" PetscInt_FMT " %" PetscInt_FMT "\n", r->prefix, r->type, r->reason, (double)r->energy, (double)r->kkt.force, r->kkt.nactive, r->its[0], r->its[1], r->its[2]));
    if (!r->converged) {
      PetscCall(PetscPrintf(comm, "FAILED: controller %s (%s) did not converge\n", r->prefix, r->type));
      ok = PETSC_FALSE;
    }
    if (r->kkt.nactive == 0) { /* without contact the two would agree trivially */
      PetscCall(PetscPrintf(comm, "FAILED: controller %s (%s) found no contact\n", r->prefix, r->type));
      ok = PETSC_FALSE;
    }
  }
  de = PetscAbsReal(res[0].energy - res[1].energy) / PetscMax(PetscAbsReal(res[0].energy), PetscAbsReal(res[1].energy));
  df = PetscAbsReal(res[0].kkt.force - res[1].kkt.force) / PetscMax(PetscAbsReal(res[0].kkt.force), PetscAbsReal(res[1].kkt.force));
  PetscCall(PetscPrintf(comm, "relative differences: energy %.3e, contact force %.3e (tolerance %.1e)\n", (double)de, (double)df, (double)rtol));
  if (!(de <= rtol && df <= rtol)) { /* NaN fails too */
    PetscCall(PetscPrintf(comm, "FAILED: the two controllers disagree\n"));
    ok = PETSC_FALSE;
  }
  if (ok) PetscCall(PetscPrintf(comm, "agree: yes\n"));
  PetscCall(SgProblemDestroy(&prob));
  PetscCall(PetscFinalize());
  return ok ? 0 : 1;
}
