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

typedef struct _n_SgProblem *SgProblem;
typedef struct _n_SgCont    *SgCont;

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

/* Safe result files: a result is written to <name>.part and renamed when complete; these refuse, before any work, a
   location that cannot be written or is one of the run's inputs, and remove unfinished files on a fatal signal. */
PetscErrorCode SgFileCheckWritable(MPI_Comm, const char[], const char[]); /* option name (for messages), file name */
PetscErrorCode SgFileCheckInput(MPI_Comm, const char[], const char[]);
PetscErrorCode SgFileInstallCleanup(void);

/* ---- SgProblem */
typedef enum {
  SG_BOUNDARY_DIRICHLET, /* values: dim displacements per id */
  SG_BOUNDARY_NEUMANN,   /* values: dim tractions per id */
  SG_BOUNDARY_CONTACT    /* values: none (NULL) */
} SgBoundaryType;

PetscErrorCode SgProblemCreate(MPI_Comm, SgProblem *);
PetscErrorCode SgProblemCreateFromDM(DM, SgProblem *);
PetscErrorCode SgProblemSetDM(SgProblem, DM);
PetscErrorCode SgProblemSetOptionsPrefix(SgProblem, const char[]);
PetscErrorCode SgProblemGetOptionsPrefix(SgProblem, const char *[]);
PetscErrorCode SgProblemSetMaterial(SgProblem, PetscReal, PetscReal);
PetscErrorCode SgProblemSetBoundary(SgProblem, SgBoundaryType, const char[], PetscInt, const PetscInt[], const PetscReal[]);
PetscErrorCode SgProblemSetObstacleType(SgProblem, const char[]);
PetscErrorCode SgProblemSetFromOptions(SgProblem);
PetscErrorCode SgProblemSetUp(SgProblem);
PetscErrorCode SgProblemView(SgProblem, PetscViewer);
PetscErrorCode SgProblemDestroy(SgProblem *);
PetscErrorCode SgProblemGetDM(SgProblem, DM *);
PetscErrorCode SgProblemGetDimension(SgProblem, PetscInt *);
PetscErrorCode SgProblemGetSizes(SgProblem, PetscInt *, PetscInt *, PetscInt *);
PetscErrorCode SgProblemHasContact(SgProblem, PetscBool *);
PetscErrorCode SgProblemCreateVector(SgProblem, Vec *);
PetscErrorCode SgProblemComputeEnergy(SgProblem, Vec, PetscReal *);

/* ---- SgCont */
#define SGCONTNONE "none" /* one regularized problem (P_gamma), gamma from -contact_gamma */
#define SGCONTALM  "alm"  /* first-order augmented Lagrangian */
#define SGCONTPF   "pf"   /* exact path-following */
#define SGCONTIPF  "ipf"  /* inexact path-following */
#define SGCONTPDAS "pdas" /* baseline: unregularized primal-dual active set */
#define SGCONTVI   "vi"   /* baseline: PETSc's SNESVI on the same discrete problem */

/* Measures of a displacement as a solution of the contact problem (P), each dimensionless (see SgContGetKKT). */
typedef struct {
  PetscReal equilibrium, infeasibility, complementarity, dual, residual, rhoF, rhoC, force;
  PetscReal penetration, uscale, lscale;
  PetscInt  nactive;
} SgKKT;

PetscErrorCode SgContCreate(SgProblem, SgCont *);
PetscErrorCode SgContSetType(SgCont, const char[]);
PetscErrorCode SgContGetType(SgCont, const char *[]);
PetscErrorCode SgContSetOptionsPrefix(SgCont, const char[]);
PetscErrorCode SgContGetOptionsPrefix(SgCont, const char *[]);
PetscErrorCode SgContSetTolerances(SgCont, PetscReal, PetscInt);
PetscErrorCode SgContSetFromOptions(SgCont);
PetscErrorCode SgContSetUp(SgCont);
PetscErrorCode SgContSolve(SgCont);
PetscErrorCode SgContGetSolution(SgCont, Vec *);
PetscErrorCode SgContGetConvergedReason(SgCont, PetscBool *, const char *[]);
PetscErrorCode SgContGetIterationNumbers(SgCont, PetscInt *, PetscInt *, PetscInt *);
PetscErrorCode SgContGetKKT(SgCont, SgKKT *);
PetscErrorCode SgContGetEnergy(SgCont, PetscReal *);
PetscErrorCode SgContGetSNES(SgCont, SNES *);
PetscErrorCode SgContView(SgCont, PetscViewer);
PetscErrorCode SgContWriteSummary(SgCont, const char[]);
PetscErrorCode SgContWriteHistory(SgCont, const char[]);
PetscErrorCode SgContWriteFields(SgCont, const char[], PetscReal);
PetscErrorCode SgContDestroy(SgCont *);
PetscErrorCode SgContRegister(const char[], PetscErrorCode (*)(SgCont));

#if defined(__cplusplus)
}
#endif
