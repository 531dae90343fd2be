/* signorini.h: types and prototypes of every module of the Signorini contact solver. */
#pragma once

#include <petscdmplex.h>
#include <petscsnes.h>

#define SG_MAX_IDS 32 /* label values per boundary part */

/* ------------------------------------------------------------------ events.c */
extern PetscLogEvent SG_MeshSetUp, SG_Assembly, SG_ContactSetUp, SG_Residual, SG_Jacobian, SG_ActiveSet, SG_LinearSolve, SG_ContStep, SG_Output;
PetscErrorCode SgRegisterAll(void);

/* ------------------------------------------------------------------ mesh.c */
/* A boundary part: the points of one DMLabel with the given values (nids = 0: every value).
   values[] holds ncomp numbers per id (Dirichlet displacement, Neumann traction). */
typedef struct {
  const char *what;       /* option prefix, e.g. "dirichlet" */
  char        label[256]; /* label name */
  PetscInt    nids;
  PetscInt    ids[SG_MAX_IDS];
  PetscInt    nvalues;
  PetscReal   values[3 * SG_MAX_IDS];
} SgBoundary;

/* The P1 view of a distributed simplex mesh, flattened once for the assembly loops. */
typedef struct {
  PetscInt   dim;
  PetscInt   nv, nc;    /* local vertices and cells */
  PetscInt   vStart, cStart;
  PetscInt  *cellv;     /* nc*(dim+1) local vertex numbers (0..nv-1) */
  PetscReal *x;         /* nv*dim vertex coordinates */
  PetscInt  *gblock;    /* global block (vertex) index of the free displacement, -1 if Dirichlet */
  PetscInt  *loff;      /* offset of the vertex in the local displacement vector */
  PetscInt  *goff;      /* offset in this rank's part of the global vector, -1 if not owned or Dirichlet */
  PetscInt  *bcgroup;   /* Dirichlet part (index into ids) or -1 */
  PetscInt   nowned;    /* vertices owned by this rank (free or not) */
  PetscInt   nfree_glob;/* global number of free vertices */
} SgMesh;

PetscErrorCode SgMeshCreateDM(MPI_Comm, DM *);
PetscErrorCode SgBoundaryFromOptions(PetscOptionItems *, SgBoundary *, PetscInt, const char *, const char *);
PetscErrorCode SgBoundaryGetLabel(DM, const SgBoundary *, DMLabel *);
PetscErrorCode SgBoundaryGetFacets(DM, const SgBoundary *, PetscInt *, PetscInt **, PetscInt **);
PetscErrorCode SgMeshSetUp(DM, const SgBoundary *, SgMesh *);
PetscErrorCode SgMeshDestroy(SgMesh *);
PetscErrorCode SgFacetGeometry(DM, const SgMesh *, PetscInt, PetscInt *, PetscInt[], PetscReal *, PetscReal[]);

/* ------------------------------------------------------------------ elasticity.c */
typedef struct _n_SgProblem *SgProblem;
struct _n_SgProblem {
  MPI_Comm     comm;
  DM           dm;      /* vertex P1 displacement, Dirichlet vertices constrained in the section */
  DM           dmCell;  /* one scalar per cell (cell fields) */
  DM           dmVert;  /* one scalar per vertex, no constraints (contact fields) */
  DM           dmVec;   /* dim values per vertex, no constraints (output of the full displacement) */
  SgMesh       mesh;
  PetscInt     dim;
  PetscReal    E, nu, lambda, mu;
  PetscReal    body_force[3];
  SgBoundary   dirichlet, neumann;
  PetscBool    mms;          /* manufactured solution: body force and Dirichlet data from a known field */
  Mat          K;            /* stiffness on the free dofs, block size dim */
  Vec          b;            /* load with the Dirichlet lifting */
  Vec          mass;         /* lumped volume of each free dof's vertex (for the discrete dual norm) */
  Vec          ubc;          /* local vector: Dirichlet values at constrained dofs, 0 elsewhere */
  PetscReal    energy_shift; /* 1/2 u_D K_DD u_D - f_D u_D: V(y) = 1/2 y K y - b y + energy_shift */
  PetscReal    bnorm;        /* ||b||_2 */
  MatNullSpace nearnull;
  PetscInt     ndofs;
  PetscLogDouble t_assembly;
};

PetscErrorCode SgProblemCreate(MPI_Comm, SgProblem *);
PetscErrorCode SgProblemDestroy(SgProblem *);
PetscErrorCode SgProblemEnergy(SgProblem, Vec, PetscReal *);
PetscErrorCode SgProblemGlobalToLocal(SgProblem, Vec, Vec);
PetscErrorCode SgProblemFullDisplacement(SgProblem, Vec, Vec);
PetscErrorCode SgProblemCellFields(SgProblem, Vec, Vec, Vec);
PetscErrorCode SgProblemMMSErrors(SgProblem, Vec, PetscReal *, PetscReal *);
PetscErrorCode SgProblemDualNorm(SgProblem, Vec, PetscReal *);
PetscErrorCode SgSimplexGradients(PetscInt, const PetscReal[], PetscReal[], PetscReal *);
PetscErrorCode SgElementStiffness(PetscInt, const PetscReal[], PetscReal, PetscReal, PetscReal[], PetscReal *);
PetscErrorCode SgLame(PetscReal, PetscReal, PetscReal *, PetscReal *);

/* ------------------------------------------------------------------ output.c */
typedef struct _n_SgSummary *SgSummary;
struct _n_SgSummary {
  PetscInt n, cap;
  char   **key, **val; /* values JSON-encoded */
};
PetscErrorCode SgFileTmpName(const char[], char[], size_t);
PetscErrorCode SgFileCommit(MPI_Comm, const char[]);
PetscErrorCode SgFileAbandon(MPI_Comm, const char[]);
PetscErrorCode SgFileOpen(MPI_Comm, const char[], const char[], FILE **);
PetscErrorCode SgFileClose(MPI_Comm, const char[], FILE **);
PetscErrorCode SgFileCheckWritable(MPI_Comm, const char[], const char[]);
PetscErrorCode SgSummaryCreate(SgSummary *);
PetscErrorCode SgSummaryDestroy(SgSummary *);
PetscErrorCode SgSummarySetRaw(SgSummary, const char[], const char[]);
PetscErrorCode SgSummarySetReal(SgSummary, const char[], PetscReal);
PetscErrorCode SgSummarySetInt(SgSummary, const char[], PetscInt);
PetscErrorCode SgSummarySetBool(SgSummary, const char[], PetscBool);
PetscErrorCode SgSummarySetString(SgSummary, const char[], const char[]);
PetscErrorCode SgSummarySetRealArray(SgSummary, const char[], PetscInt, const PetscReal[]);
PetscErrorCode SgSummarySetIntArray(SgSummary, const char[], PetscInt, const PetscInt[]);
PetscErrorCode SgSummaryWrite(MPI_Comm, SgSummary, const char[], const char[]);
PetscErrorCode SgOutputWrite(SgProblem, const char[], PetscInt, Vec[], PetscInt, Vec[], PetscReal);
