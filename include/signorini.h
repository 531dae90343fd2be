/* signorini.h: the public interface of libsignorini, frictionless contact of a linear elastic body with a rigid
   obstacle, solved with the semismooth Newton, augmented Lagrangian and path-following methods of G. Stadler (2007).

   Two objects, each with PETSc's life cycle Create -> Set... / SetOptionsPrefix -> SetFromOptions -> SetUp -> (Solve)
   -> View -> Destroy:
     SgProblem  the discrete problem: P1 elasticity on a DMPlex (ours from -dm_plex_filename / -box_*, or the caller's),
                its boundary parts (Dirichlet, Neumann, contact) and the rigid obstacle;
     SgCont     a solver of it: a continuation controller (none, alm, pf, ipf) around the semismooth Newton SNES, or a
                baseline that solves the contact problem directly (pdas, vi).
   Each reads the options under its own prefix, so several problems and solvers can live in one program.
   The implementation's headers (src/) are not needed to use the library; a new controller type needs them. */
#pragma once

#include <petscdmplex.h>
#include <petscsnes.h>

#if defined(__cplusplus)
extern "C" {
#endif

typedef struct _n_SgProblem    *SgProblem;
typedef struct _n_SgObstacle   *SgObstacle; /* a rigid obstacle type (SgObstacleRegister) */
typedef struct _n_SgCont       *SgCont;
typedef struct _n_SgContactLaw *SgContactLaw; /* a contact (friction) law type (SgContactLawRegister) */

/* Registers the log events, obstacle and controller types; called by the Create functions (PetscFinalize undoes it). */
PetscErrorCode SgInitializePackage(void);

/* Option readers for a driver's own options, between PetscOptionsBegin and PetscOptionsEnd: an empty, malformed or
   out-of-range value is an error naming the option with its prefix (PETSc 3.18's own readers take an empty value as
   "not set"). Lists are comma-separated, at most the given number of entries. */
PetscErrorCode SgOptionsIntList(PetscOptionItems *, const char[], const char[], PetscInt, PetscInt[], PetscInt *, PetscBool *);
PetscErrorCode SgOptionsRealList(PetscOptionItems *, const char[], const char[], PetscInt, PetscReal[], PetscInt *, PetscBool *);
PetscErrorCode SgOptionsRealValue(PetscOptionItems *, const char[], const char[], PetscReal *, PetscBool *);
PetscErrorCode SgOptionsIntValue(PetscOptionItems *, const char[], const char[], PetscInt *, PetscBool *);
PetscErrorCode SgOptionsBoolValue(PetscOptionItems *, const char[], const char[], PetscBool *, PetscBool *);
PetscErrorCode SgOptionsName(const char[], const char[], char[], size_t);
/* A file name: "none" (the documented default) is no file (name[0] = 0, *set false), as when the option is not
   given, so that a command line turns off a file that an options file names. */
PetscErrorCode SgOptionsFileName(PetscOptionItems *, const char[], const char[], char[], size_t, PetscBool *);
PetscBool      SgFileNameIsNone(const char[]);

/* Safe result files: a result is written to <name>.part and renamed when complete; these refuse, before any work, a
   location that cannot be written or is one of the run's inputs, and remove unfinished files on a fatal signal. */
PetscErrorCode SgFileCheckWritable(MPI_Comm, const char[], const char[]); /* refuse, before any work, a result file (option, name) that cannot be written or is an input */
PetscErrorCode SgFileCheckInput(MPI_Comm, const char[], const char[]);
PetscErrorCode SgFileInstallCleanup(void);

/* ---- SgProblem */
typedef enum {
  SG_BOUNDARY_DIRICHLET,       /* values: dim displacements per id */
  SG_BOUNDARY_NEUMANN,         /* values: dim tractions per id */
  SG_BOUNDARY_CONTACT,         /* values: none (NULL) */
  SG_BOUNDARY_CONTACT_MASTER,  /* values: none (NULL); two elastic bodies: the master side, ids of the contact part's
                                  label (the contact part's ids are then the slave side; default of -contact_master_ids) */
  SG_BOUNDARY_CONTACT_OBSTACLE /* values: none (NULL); two bodies and a rigid obstacle: the faces that may touch the
                                  obstacle, ids of the contact part's label (default of -contact_obstacle_ids) */
} SgBoundaryType;

PetscErrorCode SgProblemCreate(MPI_Comm, SgProblem *);             /* an empty problem on the communicator */
PetscErrorCode SgProblemCreateFromDM(DM, SgProblem *);             /* a problem on the caller's DMPlex (SgProblemCreate + SgProblemSetDM) */
PetscErrorCode SgProblemSetDM(SgProblem, DM);                      /* use the caller's mesh (a DMPLEX of triangles/tetrahedra, no overlap; it is copied, coordinates and labels, so later changes to the caller's DM do not reach the problem, and it is not changed) */
PetscErrorCode SgProblemSetOptionsPrefix(SgProblem, const char[]); /* prefix of the problem's options (-<prefix>E, -<prefix>contact_ids, ...) */
PetscErrorCode SgProblemGetOptionsPrefix(SgProblem, const char *[]);
PetscErrorCode SgProblemSetMaterial(SgProblem, PetscReal, PetscReal);                                                            /* Young's modulus E and Poisson's ratio nu (defaults of -E, -nu) */
PetscErrorCode SgProblemSetMaterials(SgProblem, const char[], PetscInt, const PetscInt[], const PetscReal[], const PetscReal[]); /* several materials: cell label (NULL: "Cell Sets", gmsh's physical volumes), n ids of it, E and nu of each (defaults of -material_label, -material_ids, -E, -nu; every cell needs one of the ids, n = 1: every cell has it) */
PetscErrorCode SgProblemSetBoundary(SgProblem, SgBoundaryType, const char[], PetscInt, const PetscInt[], const PetscReal[]);     /* a boundary part: label name, n ids (0: every value), values (dim per id, or NULL; before SgProblemSetDM the dimension is -box_dim's, 2 with a mesh file: call SgProblemSetDM first for a 3D file) */
/* Components fixed by the Dirichlet part (rollers, symmetry planes): one bit mask per id of SgProblemSetBoundary (one
   if it gave no ids), SG_COMPONENT_X | SG_COMPONENT_Y ...; the values of the free components are ignored. Without this
   call (or -dirichlet_components) every component is fixed. Call after SgProblemSetBoundary(SG_BOUNDARY_DIRICHLET). */
#define SG_COMPONENT_X 1
#define SG_COMPONENT_Y 2
#define SG_COMPONENT_Z 4
PetscErrorCode SgProblemSetDirichletComponents(SgProblem, PetscInt, const PetscInt[]);
PetscErrorCode SgProblemSetObstacleType(SgProblem, const char[]);                    /* plane, parabola, ball or cad (default of -obstacle_type), or one of SgObstacleRegister */
PetscErrorCode SgContactLawRegister(const char[], PetscErrorCode (*)(SgContactLaw)); /* a new friction law for -friction_type (none, tresca, coulomb are ours; its implementation fills the ops of src/contact/contactimpl.h) */
PetscErrorCode SgObstacleRegister(const char[], PetscErrorCode (*)(SgObstacle));     /* a new obstacle type for -obstacle_type / SgProblemSetObstacleType (its implementation fills the gap function of src/contact/contactimpl.h) */
PetscErrorCode SgProblemSetFromOptions(SgProblem);                                   /* read the options, make (or check) the mesh */
PetscErrorCode SgProblemSetUp(SgProblem);                                            /* layout, assembly of K and b, contact geometry */
PetscErrorCode SgProblemView(SgProblem, PetscViewer);                                /* ASCII description (NULL: stdout) */
PetscErrorCode SgProblemReference(SgProblem);                                        /* one more holder (SgContCreate takes one): SgProblemDestroy frees the problem when the last one lets it go */
PetscErrorCode SgProblemDestroy(SgProblem *);                                        /* lets the handle go (sets it to NULL; NULL: nothing to do); a controller of the problem keeps it alive */
PetscErrorCode SgProblemGetDM(SgProblem, DM *);                                      /* the displacement DM (global vectors: the free dofs) */
PetscErrorCode SgProblemGetDimension(SgProblem, PetscInt *);                         /* 2 or 3 */
PetscErrorCode SgProblemGetSizes(SgProblem, PetscInt *, PetscInt *, PetscInt *);     /* unknowns, cells, contact vertices (global) */
PetscErrorCode SgProblemHasContact(SgProblem, PetscBool *);                          /* a contact boundary was given */
PetscErrorCode SgProblemCreateVector(SgProblem, Vec *);                              /* a displacement vector */
PetscErrorCode SgProblemComputeEnergy(SgProblem, Vec, PetscReal *);                  /* potential energy V(y) */
PetscErrorCode SgProblemSetLoadFactor(SgProblem, PetscReal);                         /* load stepping: loads, Dirichlet values and obstacle translation times t >= 0 (1: the data as given; 0: unloaded; after SetUp) */
PetscErrorCode SgProblemGetLoadFactor(SgProblem, PetscReal *);                       /* 1 unless set */
PetscErrorCode SgProblemSetDirichletValues(SgProblem, const PetscReal[]);            /* non-proportional loading: the Dirichlet values of every id (dim per id) for the next solves, not scaled by the load factor (after SetUp); NULL: back to proportional */
PetscErrorCode SgProblemGetDirichletSize(SgProblem, PetscInt *);                     /* how many values SgProblemSetDirichletValues takes: dim per Dirichlet id */

/* ---- SgCont */
#define SGCONTNONE "none" /* one regularized problem (P_gamma), gamma from -contact_gamma */
#define SGCONTALM  "alm"  /* first-order augmented Lagrangian */
#define SGCONTPF   "pf"   /* exact path-following */
#define SGCONTIPF  "ipf"  /* inexact path-following */
#define SGCONTFAST "fast" /* one (P_gamma) at a capped gamma with inexact Newton steps (iterative solves) */
#define SGCONTPDAS "pdas" /* baseline: unregularized primal-dual active set */
#define SGCONTVI   "vi"   /* baseline: PETSc's SNESVI on the same discrete problem */

/* Measures of a displacement as a solution of the contact problem (P), each dimensionless (see SgContGetKKT): forces
   against fscale, the largest nodal force acting on the body (load, support or contact force), lengths against uscale
   (lscale = uscale sqrt|Gamma_c|); roundoff is the smallest force measure double precision can certify (eps ||K|| ||y||
   / fscale: above the tolerance the problem cannot be solved to it), balance the resultant of all forces on the body
   against their sum of magnitudes. */
typedef struct {
  PetscReal equilibrium, infeasibility, complementarity, dual, residual, rhoF, rhoC, force;
  PetscReal penetration, uscale, lscale;
  PetscInt  nactive;
  PetscReal fscale, roundoff, balance;
} SgKKT;

PetscErrorCode SgContCreate(SgProblem, SgCont *);            /* a solver of the problem, which it holds (SgProblemReference) until SgContDestroy (unless a type is set, SgContSetFromOptions picks the default for the problem: fast in 3D and with iterative solves, ipf in 2D with exact ones, none without contact) */
PetscErrorCode SgContSetType(SgCont, const char[]);          /* SGCONTIPF, ... (default of -cont_type) */
PetscErrorCode SgContGetType(SgCont, const char *[]);        /* the type (empty before SgContSetFromOptions if none was set) */
PetscErrorCode SgContSetOptionsPrefix(SgCont, const char[]); /* prefix of the solver's options (-<prefix>cont_type, -<prefix>ksp_type, ...) */
PetscErrorCode SgContGetOptionsPrefix(SgCont, const char *[]);
PetscErrorCode SgContSetTolerances(SgCont, PetscReal, PetscInt);                             /* KKT tolerance, outer-step limit (PETSC_DEFAULT keeps one) */
PetscErrorCode SgContSetMonitor(SgCont, PetscBool);                                          /* a line per outer step (default of -cont_monitor: PETSC_TRUE) */
PetscErrorCode SgContSetFromOptions(SgCont);                                                 /* read the options (sets the problem up first) */
PetscErrorCode SgContPrintHelp(SgCont);                                                      /* with -help: list the options of the controller and of every type now, before the problem is set up (SgContSetFromOptions does not list them again) */
PetscErrorCode SgContSetUp(SgCont);                                                          /* linear solver, SSN solver */
PetscErrorCode SgContSolve(SgCont);                                                          /* solve from the unconstrained start or -restart_file; called again (after SgProblemSetLoadFactor): a load step warm-started from the last solution and controller state */
PetscErrorCode SgContGetLoadSteps(SgCont, PetscInt *);                                       /* load steps solved so far (with those of a -restart_file checkpoint taken between load steps) */
PetscErrorCode SgContGetLoadStepDirichletValues(SgCont, PetscInt, PetscBool *, PetscReal[]); /* the Dirichlet values of a solved load step, if set for it (SgProblemSetDirichletValues) */
PetscErrorCode SgContGetLoadStepFactor(SgCont, PetscInt, PetscReal *);                       /* the load factor of solved load step k (0-based) */
PetscErrorCode SgContSetStoreSteps(SgCont, PetscBool);                                       /* keep every load step's solution, so that SgContWriteFields writes them all (an XDMF temporal collection) */
PetscErrorCode SgContWriteLoadCurve(SgCont, const char[]);                                   /* CSV: one row per load step (factor, obstacle displacement, contact force, ...) */
PetscErrorCode SgContGetSolution(SgCont, Vec *);                                             /* the displacement (borrowed: do not destroy) */
PetscErrorCode SgContGetConvergedReason(SgCont, PetscBool *, const char *[]);                /* converged to the tolerance, and why it stopped */
PetscErrorCode SgContGetIterationNumbers(SgCont, PetscInt *, PetscInt *, PetscInt *);        /* outer steps, SSN iterations, Krylov iterations */
PetscErrorCode SgContGetKKT(SgCont, SgKKT *);                                                /* the KKT measures of the result as a solution of (P) */
PetscErrorCode SgContGetEnergy(SgCont, PetscReal *);                                         /* V of the result */
PetscErrorCode SgContGetSNES(SgCont, SNES *);                                                /* the semismooth Newton SNES (NULL for pdas, vi and without contact) */
PetscErrorCode SgContView(SgCont, PetscViewer);                                              /* ASCII: settings before the solve, the result line after it */
PetscErrorCode SgContWriteSummary(SgCont, const char[]);                                     /* JSON summary of the solve */
PetscErrorCode SgContWriteHistory(SgCont, const char[]);                                     /* CSV history: a row per SSN iteration and per outer step */
PetscErrorCode SgContWriteFields(SgCont, const char[], PetscReal);                           /* HDF5 + XDMF fields for ParaView (converged solves), magnification */
PetscErrorCode SgContDestroy(SgCont *);
PetscErrorCode SgContRegister(const char[], PetscErrorCode (*)(SgCont)); /* a new controller type (its implementation needs src/cont/contimpl.h) */

#if defined(__cplusplus)
}
#endif
