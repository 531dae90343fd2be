/* signorini.h: types and prototypes of every module of the Signorini contact solver. */
#pragma once

#include <petscdmplex.h>
#include <petscsnes.h>
#include <math.h>

#define SG_MAX_IDS 32 /* label values per boundary part */
#define SG_OPT_MAX (3 * SG_MAX_IDS) /* entries of a list option read by SgOptionsIntList/RealList */
#define SG_NAN     ((PetscReal)NAN) /* "not set" in tables and summaries */

/* ------------------------------------------------------------------ events.c */
extern PetscLogEvent SG_MeshSetUp, SG_Assembly, SG_ContactSetUp, SG_Residual, SG_Jacobian, SG_ActiveSet, SG_LinearSolve, SG_ContStep, SG_Output;
PetscErrorCode SgRegisterAll(void);

/* ------------------------------------------------------------------ mesh.c */
/* A boundary part: the points of one DMLabel with the given values (nids = 0: every value). A part is empty
   unless its -<what>_label or -<what>_ids option was given.
   values[] holds ncomp numbers per id (Dirichlet displacement, Neumann traction). */
typedef struct {
  const char *what;       /* option prefix, e.g. "dirichlet" */
  PetscBool   active;     /* given by the options */
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

PetscErrorCode SgOptionsIntList(PetscOptionItems *, const char[], const char[], PetscInt, PetscInt[], PetscInt *, PetscBool *);
PetscErrorCode SgOptionsRealList(PetscOptionItems *, const char[], const char[], PetscInt, PetscReal[], PetscInt *, PetscBool *);
PetscErrorCode SgOptionsRealValue(PetscOptionItems *, const char[], const char[], PetscReal *, PetscBool *);
PetscErrorCode SgOptionsIntValue(PetscOptionItems *, const char[], const char[], PetscInt *, PetscBool *);
PetscErrorCode SgOptionsBoolValue(PetscOptionItems *, const char[], const char[], PetscBool *, PetscBool *);
PetscErrorCode SgMeshCreateDM(MPI_Comm, DM *);
PetscErrorCode SgBoundaryFromOptions(PetscOptionItems *, SgBoundary *, PetscInt, const char *, const char *);
PetscErrorCode SgBoundaryGetLabel(DM, const SgBoundary *, DMLabel *);
PetscErrorCode SgBoundaryGetFacets(DM, const SgBoundary *, PetscInt *, PetscInt **, PetscInt **);
PetscErrorCode SgMeshSetUp(DM, const SgBoundary *, SgMesh *);
PetscErrorCode SgMeshDestroy(SgMesh *);
PetscErrorCode SgMeshConstrainedDimension(MPI_Comm, const SgMesh *, PetscInt *, PetscReal[3], PetscReal[3], PetscReal *);
PetscErrorCode SgFacetGeometry(DM, const SgMesh *, PetscInt, PetscInt *, PetscInt[], PetscReal *, PetscReal[]);
PetscErrorCode SgGmshCheckFile(MPI_Comm, const char[]); /* gmshcheck.c: a .msh file's structure, before PETSc reads it */

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
  PetscInt     nbody_force;  /* entries given with -body_force (must be dim) */
  SgBoundary   dirichlet, neumann;
  PetscBool    mms;          /* manufactured solution: body force and Dirichlet data from a known field */
  Mat          K;            /* stiffness on the free dofs, block size dim */
  Vec          b;            /* load with the Dirichlet lifting */
  Vec          mass;         /* lumped volume of each free dof's vertex (for the discrete dual norm) */
  Vec          ubc;          /* local vector: Dirichlet values at constrained dofs, 0 elsewhere */
  PetscReal    energy_shift; /* 1/2 u_D K_DD u_D - f_D u_D: V(y) = 1/2 y K y - b y + energy_shift */
  PetscReal    bnorm, bnorm_inf; /* ||b||_2, ||b||_inf */
  PetscReal    Knorm;        /* ||K||_inf */
  Vec          fpart;        /* local: this rank's cells' and facets' part of the load without lifting (for the energy) */
  PetscReal    diam;         /* diameter of the mesh's bounding box */
  PetscReal    rigid_shift;  /* -elasticity_rigid_shift: K += rigid_shift E/diam^2 M (lumped volumes M) */
  PetscBool    rigid_shift_set;
  PetscBool    energy_check; /* -elasticity_energy_check: compare the energy with a long double evaluation */
  MatNullSpace nearnull;     /* rigid-body modes */
  PetscBool    use_nearnull; /* attached to K and the Jacobians */
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
PetscErrorCode SgProblemReaction(SgProblem, Vec, PetscReal[3]);
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
PetscErrorCode SgFileCheckInput(MPI_Comm, const char[], const char[]);
PetscErrorCode SgFileBegin(const char[]);
PetscErrorCode SgFileInstallCleanup(void);
void           SgFileCleanup(void);
const char    *SgFileErrorCause(int, const char[]);
PetscErrorCode SgFileHDF5NameMax(MPI_Comm, size_t *);
PetscErrorCode SgFileWriteHDF5(MPI_Comm, const char[], const char[], PetscErrorCode (*)(PetscViewer, void *), void *, PetscBool, PetscBool *, char[], size_t);
PetscErrorCode SgOutputXdmfName(const char[], char[], size_t);
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

/* ------------------------------------------------------------------ obstacle.c */
typedef struct _n_SgObstacle *SgObstacle;
struct _n_SgObstacle {
  MPI_Comm  comm;
  char      type[64];
  PetscInt  dim;
  PetscReal p[16]; /* shape parameters */
  PetscErrorCode (*gap)(SgObstacle, const PetscReal[], const PetscReal[], PetscReal *);
  PetscErrorCode (*setfromoptions)(SgObstacle, PetscOptionItems *);
};
extern PetscFunctionList SgObstacleList;
PetscErrorCode SgObstacleRegister(const char[], PetscErrorCode (*)(SgObstacle));
PetscErrorCode SgObstacleCreate(MPI_Comm, PetscInt, SgObstacle *);
PetscErrorCode SgObstacleGap(SgObstacle, const PetscReal[], const PetscReal[], PetscReal *);
PetscErrorCode SgObstacleDestroy(SgObstacle *);
PetscErrorCode SgObstacleCreate_Plane(SgObstacle);
PetscErrorCode SgObstacleCreate_Parabola(SgObstacle);
PetscErrorCode SgObstacleCreate_Ball(SgObstacle);

/* ------------------------------------------------------------------ contact.c */
typedef struct _n_SgContact *SgContact;
struct _n_SgContact {
  SgProblem  prob;
  SgBoundary bnd;
  SgObstacle obs;
  PetscInt   n, nglobal; /* contact vertices owned here / in all */
  PetscInt  *vert;       /* local vertex number */
  PetscInt  *off;        /* offset of its first dof in the local part of a global displacement vector */
  PetscReal *normal;     /* outward unit normals, n*dim */
  PetscReal *w;          /* lumped boundary weights int_Gamma_c phi_i */
  PetscReal *d;          /* gap to the obstacle along the normal */
  PetscReal *lamhat;     /* shift of (P_gamma) */
  PetscReal  lamhat0, gamma, area;
};

/* Measures of the original problem (P) for a displacement y and the multiplier lam_i = -(K y - b)_i.n_i / w_i, each
   dimensionless (the same for any load level, material scale and unit system), with the force scale
   ||K|| ||y|| + ||b|| (infinity norms) and the length scale Y sqrt|Gamma_c|, Y = max(||y||_inf, largest initial
   penetration):
   equilibrium     ||K y - b + B^T W lam|| / (||K|| ||y|| + ||b||)          (backward error; interior and tangential part)
   infeasibility   ||max(0, g)||_{L2(Gamma_c)} / (Y sqrt|Gamma_c|)
   complementarity (||max(0, g)||_{L2(I)} + ||min(0, g)||_{L2(A)}) / (Y sqrt|Gamma_c|), A = {lam > 0}, as an L2 sum of squares
   dual            max_i w_i max(0, -lam_i) / (||K|| ||y|| + ||b||)        (nodal force a pressure >= 0 cannot balance)
   residual        max(equilibrium, dual, infeasibility, complementarity): the stopping measure
   penetration     ||max(0, g)||_{L2(Gamma_c)} in the problem's units (the paper's infeasibility) */
typedef struct {
  PetscReal equilibrium, infeasibility, complementarity, dual, residual, rhoF, rhoC, force;
  PetscReal penetration, uscale, lscale;
  PetscInt  nactive;
} SgKKT;

PetscErrorCode SgContactCreate(SgProblem, SgContact *);
PetscErrorCode SgContactDestroy(SgContact *);
PetscErrorCode SgContactGap(SgContact, const PetscScalar[], PetscReal[]);
PetscErrorCode SgContactAddForce(SgContact, const PetscReal[], PetscScalar[]);
PetscErrorCode SgContactAddJacobian(SgContact, const char[], PetscReal, Mat);
PetscErrorCode SgContactMultiplierFromResidual(SgContact, Vec, PetscReal[]);
PetscErrorCode SgContactKKT(SgContact, Vec, SgKKT *);
PetscErrorCode SgContactFields(SgContact, Vec, const PetscReal[], Vec[4], Vec);
PetscErrorCode SgContactAxisAligned(SgContact, const char[], PetscInt[], PetscReal[]);

/* ------------------------------------------------------------------ history.c */
typedef struct {
  char      kind; /* 's': an SSN iteration, 'o': the end of an outer (continuation) step */
  PetscInt  outer, it, active, entered, left, ksp_its, ssn_its;
  PetscReal gamma, fnorm, r1, r2, V, dV, C1, C2, Em, rhoF, rhoC, infeas, kkt, time;
} SgHistoryRow;
typedef struct _n_SgHistory *SgHistory;
struct _n_SgHistory {
  PetscInt      n, cap;
  SgHistoryRow *rows;
};
PetscErrorCode SgHistoryCreate(SgHistory *);
PetscErrorCode SgHistoryDestroy(SgHistory *);
PetscErrorCode SgHistoryRowInit(SgHistoryRow *);
PetscErrorCode SgHistoryAdd(SgHistory, const SgHistoryRow *);
PetscErrorCode SgHistoryWrite(MPI_Comm, SgHistory, const char[], const char[]);

/* ------------------------------------------------------------------ ssn.c */
typedef enum { SG_SSN_ITERATING, SG_SSN_SETTLED, SG_SSN_NEIGHBOURHOOD, SG_SSN_ZERO_RESIDUAL, SG_SSN_CYCLING, SG_SSN_NAN, SG_SSN_MAX_IT, SG_SSN_LINEAR_SOLVE, SG_SSN_SNES_FAILED } SgSSNReason;
extern const char *const SgSSNReasons[];
typedef struct _n_SgSSN      *SgSSN;
typedef struct _n_SgCondense *SgCondense;
struct _n_SgSSN {
  SgProblem   prob;
  SgContact   c;
  SNES        snes;
  Mat         J;
  Vec         r;
  PetscReal   gamma;
  PetscReal  *g, *m;          /* gap and max(0, lamhat + gamma g) at the last residual evaluation */
  char       *act, *actjac;   /* active set there, and the one the last Jacobian used */
  PetscBool   havejac;
  PetscInt    nact, nentered, nleft;
  PetscReal   V, dVdg;        /* J(gamma, y) and dJ/dgamma at the last residual evaluation */
  PetscReal   r1, r2, fdual, fnorm0, prev_fnorm;
  PetscBool   prev_settled;
  PetscInt    nhash, maxhash; /* hashes of the active sets of this solve's Newton steps */
  PetscInt64 *hash;
  PetscBool   residual_test;  /* inexact linear solves: also require a small residual */
  PetscInt    pc_reuse_its;   /* > 0: keep the preconditioner within a solve while the Krylov solver needs <= this */
  SgCondense  cond;           /* -ssn_condense: linear solves condensed onto the contact dofs */
  PetscReal   nbhd_tau;       /* > 0: also stop in the neighbourhood ||(r1,r2)|| <= tau/sqrt(gamma) (IPF) */
  SgSSNReason reason;
  PetscBool   monitor;
  SgHistory   hist;
  PetscInt    outer;
  PetscLogDouble t0, t_linear_setup, t_linear_solve; /* the unconstrained solve: preconditioner setup and solve */
};
PetscErrorCode SgSSNCreate(SgProblem, SgContact, SgSSN *);
PetscErrorCode SgSSNDestroy(SgSSN *);
PetscErrorCode SgSSNSolveLinear(SgSSN, Vec, PetscInt *, KSPConvergedReason *);
PetscErrorCode SgSSNActiveSetHash(SgSSN, const char[], PetscInt64 *);
PetscErrorCode SgSSNEquilibriumError(SgSSN, Vec, PetscReal *, PetscReal *);
PetscErrorCode SgCheckSolverTypes(MPI_Comm, const char[]);
PetscErrorCode SgSolverConfigured(MPI_Comm, PetscErrorCode);

/* ------------------------------------------------------------------ condense.c */
PetscErrorCode SgCondenseCreate(SgSSN, SgCondense *);
PetscErrorCode SgCondenseDestroy(SgCondense *);
PetscErrorCode SgSSNSolve(SgSSN, PetscReal, PetscInt, Vec, PetscInt *, PetscInt *, SNESConvergedReason *);

/* ------------------------------------------------------------------ cont.c and cont_*.c */
typedef struct _n_SgCont *SgCont;
struct _n_SgCont {
  MPI_Comm   comm;
  char       type[64];
  SgProblem  prob;
  SgContact  c;
  SgSSN      ssn;
  Vec        y;            /* the iterate, finally the solution */
  PetscReal *lam;          /* the multiplier at y */
  PetscReal  kkt_tol;
  PetscReal  gamma;        /* gamma of the next outer step */
  PetscReal  state[4];     /* a controller's own state between outer steps (checkpointed) */
  PetscBool  restarted;    /* the state comes from -restart_file */
  char       ckfile[PETSC_MAX_PATH_LEN], rsfile[PETSC_MAX_PATH_LEN];
  PetscInt   max_outer, stall_its;
  PetscReal  gamma_max;
  PetscReal  best_kkt;     /* progress watch */
  PetscInt   best_step;
  PetscInt   outer, ssn_its, ksp_its;
  PetscInt   ngammas, capgammas;
  PetscReal *gammas;       /* gamma of every outer step */
  PetscBool  converged;    /* the problem named by `problem` was solved to -cont_kkt_tol */
  char       reason[512];
  const char *problem;     /* what the run solves: "P" (contact), "P_gamma" (one regularized problem), "elasticity" */
  PetscReal  residual;     /* the measure of that problem: the KKT residual of (P), the equilibrium residual of (P_gamma) or the backward error of K y = b */
  SgKKT      kkt;
  PetscReal  V0, V;        /* energy of the unconstrained solution and of the result */
  SgHistory  hist;
  SgSummary  sum;
  PetscLogDouble t0;
  void      *data;
  PetscErrorCode (*setfromoptions)(SgCont, PetscOptionItems *);
  PetscErrorCode (*solve)(SgCont);
  PetscErrorCode (*destroy)(SgCont); /* optional: frees what data holds; SgContDestroy frees data itself */
};
extern PetscFunctionList SgContList;
PetscErrorCode SgContRegister(const char[], PetscErrorCode (*)(SgCont));
PetscErrorCode SgContCreate(SgProblem, SgContact, SgCont *);
PetscErrorCode SgContSolve(SgCont);
PetscErrorCode SgContDestroy(SgCont *);
PetscErrorCode SgContStart(SgCont, PetscBool *);
PetscErrorCode SgContSSN(SgCont, PetscReal, PetscBool *);
PetscErrorCode SgContMeasure(SgCont);
PetscErrorCode SgContAddGamma(SgCont, PetscReal);
PetscErrorCode SgContFail(SgCont, const char[], ...);
PetscErrorCode SgContOuterRow(SgCont, PetscInt, PetscReal, PetscReal, PetscReal);
PetscErrorCode SgContCheck(SgCont, PetscBool *);
PetscErrorCode SgCheckpointWrite(SgCont);
PetscErrorCode SgCheckpointRead(SgCont);
PetscErrorCode SgContCheckBaseline(SgCont);
const char    *SgContVerdict(SgCont);
PetscBool      SgModelFit(PetscReal, PetscReal, PetscReal, PetscReal, PetscReal *, PetscReal *, PetscReal *);
PetscErrorCode SgContCreate_ALM(SgCont);
PetscErrorCode SgContCreate_PF(SgCont);
PetscErrorCode SgContCreate_IPF(SgCont);
PetscErrorCode SgContCreate_None(SgCont);
PetscErrorCode SgContCreate_PDAS(SgCont);
PetscErrorCode SgContCreate_VI(SgCont);
