/* sg.h: the library's internal interface: the opaque handles and functions the layers (src/core, fem, contact,
   solver, io, cont) call across their borders. Each layer's structs are in its own *impl.h, included by that
   layer's files only (tests/check_layers.py checks it). */
#pragma once

#include <signorini.h>
#include <math.h>

#define SG_MAX_IDS 32               /* label values per boundary part */
#define SG_OPT_MAX (3 * SG_MAX_IDS) /* entries of a list option read by SgOptionsIntList/RealList */
#define SG_NAN     ((PetscReal)NAN) /* "not set" in tables and summaries */

/* ------------------------------------------------------------------ core: init.c, options.c */
extern PetscLogEvent SG_MeshSetUp, SG_Assembly, SG_ContactSetUp, SG_Residual, SG_Jacobian, SG_ActiveSet, SG_LinearSolve, SG_ContStep, SG_Output;
PetscErrorCode       SgLogEventsRegister(void);
/* Argument checks of the public functions. PETSc's PetscValid* macros compile to nothing in an optimized PETSc (as
   Debian's is), so these do the same checks always: a NULL or wrong argument is an error naming the function and the
   argument, never a segmentation fault. */
#define SgValidPointer(ptr, arg) PetscCheck((ptr) != NULL, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "%s: argument %d (" #ptr ") is NULL", PETSC_FUNCTION_NAME, (int)(arg))
PetscErrorCode SgValidObject(PetscObject, PetscClassId, const char[], const char[], int);
#define SgValidHeaderSpecific(obj, classid, cname, arg) PetscCall(SgValidObject((PetscObject)(obj), classid, cname, PETSC_FUNCTION_NAME, (int)(arg)))
/* Type options follow PETSc's rule (-ts_adapt_basic_clip): -<prefix>cont_<param> for what every controller has (the
   first gamma: -cont_gamma), -<prefix>cont_<type>_<param> for a type's own. The names before the rule are read with
   these, with a deprecation notice (options.c); *used names the option that set the value. */
#define SG_DEPRECATED_IN "0.2.0"
PetscErrorCode      SgOptionsRealRenamed(PetscOptionItems *, const char[], const char[], const char[], PetscReal *, const char **);
PetscErrorCode      SgOptionsIntRenamed(PetscOptionItems *, const char[], const char[], const char[], PetscInt *, const char **);
PetscErrorCode      SgOptionsBoolRenamed(PetscOptionItems *, const char[], const char[], const char[], PetscBool *, const char **);
extern PetscClassId SG_PROBLEM_CLASSID, SG_CONT_CLASSID; /* the PETSc classes of SgProblem and SgCont (SgLogEventsRegister) */
PetscErrorCode      SgValidProblem(SgProblem, const char[], int);
PetscErrorCode      SgValidCont(SgCont, const char[], int);
PetscErrorCode      SgOptionsPairDirectLimit2D(const char[], PetscBool *, PetscBool *); /* two bodies in 2D: in the dual-mortar basis; the limit SG_PAIR_DIRECT_MAX_2D applies (frictionless) */
/* matrix.c: S = A + C with the union of their patterns, one pass over A (C a correction on a few rows); W = A - I
   without its zeros (the rows where a near-identity A differs from I) */
PetscErrorCode SgMatAddSparse(Mat, Mat, Mat *);
PetscErrorCode SgMatOffIdentity(Mat, Mat *);

/* ------------------------------------------------------------------ fem: mesh.c, gmshcheck.c, elasticity.c */
/* A boundary part: the points of one DMLabel with the given values (nids = 0: every value). A part is empty
   unless its -<what>_label or -<what>_ids option was given.
   values[] holds ncomp numbers per id (Dirichlet displacement, Neumann traction); comps[] the components a Dirichlet
   part fixes per id (bits SG_COMPONENT_X/Y/Z; ncomps = 0: every component of every id). */
typedef struct {
  const char *what;       /* option prefix, e.g. "dirichlet" */
  PetscBool   active;     /* given by the options */
  char        label[256]; /* label name */
  PetscInt    nids;
  PetscInt    ids[SG_MAX_IDS];
  PetscInt    nvalues;
  PetscReal   values[3 * SG_MAX_IDS];
  PetscInt    ncomps;
  PetscInt    comps[SG_MAX_IDS];
} SgBoundary;

/* The P1 view of a distributed simplex mesh, flattened once for the assembly loops. */
typedef struct {
  PetscInt   dim;
  PetscInt   nv, nc; /* local vertices and cells */
  PetscInt   vStart, cStart;
  PetscInt  *cellv;      /* nc*(dim+1) local vertex numbers (0..nv-1) */
  PetscReal *x;          /* nv*dim vertex coordinates */
  PetscInt  *gblock;     /* global block (vertex) index of the free displacement, -1 if Dirichlet */
  PetscInt  *loff;       /* offset of the vertex in the local displacement vector */
  PetscInt  *goff;       /* offset in this rank's part of the global vector, -1 if not owned or Dirichlet */
  PetscInt  *bcgroup;    /* Dirichlet part (index into ids) fixing some component, or -1 */
  PetscInt  *bcmask;     /* components fixed (bit d: component d); all dim bits: the vertex is left out of the global
                           vector; some: its fixed components stay in it as decoupled unknowns that stay 0 ("rollers") */
  PetscInt  *bcpart;     /* nv*dim: the Dirichlet part whose value fixes component d of vertex v, or -1 */
  PetscInt   nowned;     /* vertices owned by this rank (free or not) */
  PetscInt   nfree_glob; /* global number of free vertices */
} SgMesh;

PetscErrorCode          SgMeshCreateDM(MPI_Comm, const char[], DM *);
PetscErrorCode          SgMeshCheckDM(MPI_Comm, const char[], DM);
PetscErrorCode          SgMeshPartitionWeights(PetscInt, const PetscReal[], PetscInt[]); /* mesh.c: real partition weights as PetscInt, scaled down to fit */
PetscErrorCode          SgBoundaryFromOptions(PetscOptionItems *, SgBoundary *, PetscInt, const char *, const char *);
PetscErrorCode          SgBoundaryComponentsFromOptions(PetscOptionItems *, SgBoundary *, PetscInt);
PetscErrorCode          SgBoundaryGetLabel(DM, const SgBoundary *, DMLabel *);
PetscErrorCode          SgBoundaryGetFacets(DM, const SgBoundary *, PetscInt *, PetscInt **, PetscInt **);
PetscErrorCode          SgMeshSetUp(DM, const SgBoundary *, SgMesh *);
PetscErrorCode          SgMeshDestroy(SgMesh *);
PetscErrorCode          SgMeshRefinementMap(DM, DM, const SgMesh *, const SgMesh *, const char[], PetscInt **, PetscInt *); /* mesh.c: a refined mesh's vertices as midpoints of the coarser one's */
PetscErrorCode          SgMeshConstrainedDimension(MPI_Comm, const SgMesh *, PetscInt *, PetscReal[3], PetscReal[3], PetscReal *);
PetscErrorCode          SgMeshFreeRigidMotions(MPI_Comm, const SgMesh *, PetscInt *, PetscReal[], PetscReal[3]);
static inline PetscBool SgMeshFixed(const SgMesh *m, PetscInt v, PetscInt d) { return (PetscBool)((m->bcmask[v] >> d) & 1); }
static inline PetscBool SgMeshPartial(const SgMesh *m, PetscInt v) { return (PetscBool)(m->bcmask[v] && m->bcmask[v] != (1 << m->dim) - 1); }
PetscErrorCode          SgFacetGeometry(DM, const SgMesh *, PetscInt, PetscInt *, PetscInt[], PetscReal *, PetscReal[]);
PetscErrorCode          SgGmshCheckFile(MPI_Comm, const char[]); /* gmshcheck.c: a .msh file's structure, before PETSc reads it */
/* geometry.c: gmsh started once per process (with the CAD obstacle), and the refined boundary moved onto the CAD
   geometry of -dm_refine_geometry */
typedef struct _n_SgGeometry *SgGeometry;
PetscErrorCode                SgGmshStart(MPI_Comm, PetscBool);
PetscErrorCode                SgGmshClosestPoint(int, int, const double[3], double[3], double[2], PetscBool *);
void                          SgGmshError(char[], size_t);
PetscErrorCode                SgGeometryCreate(DM, const char[], const char[], SgGeometry *);
PetscErrorCode                SgGeometrySnap(SgGeometry, DM, DM);
PetscErrorCode                SgGeometryCheck(SgGeometry, DM, PetscReal *);
PetscErrorCode                SgGeometryDestroy(SgGeometry *);

/* ------------------------------------------------------------------ elasticity.c */
typedef struct _n_SgElasticity *SgElasticity;

/* Settings given through the library's interface before the options are read (the options override them). */
typedef struct {
  PetscBool material_set;
  PetscReal E, nu;
  /* several materials (SgProblemSetMaterials): nmat > 0 values of the cell label matlabel, E and nu of each */
  PetscInt   nmat, matids[SG_MAX_IDS];
  PetscReal  matE[SG_MAX_IDS], matnu[SG_MAX_IDS];
  char       matlabel[256];
  SgBoundary dirichlet, neumann;
} SgElasticitySettings;
PetscErrorCode SgElasticityCreate(MPI_Comm, const char[], SgElasticity *);
PetscErrorCode SgElasticitySetFromOptions(SgElasticity, DM, const SgElasticitySettings *);
PetscErrorCode SgElasticitySetUp(SgElasticity);
PetscErrorCode SgElasticityDestroy(SgElasticity *);
PetscErrorCode SgElasticityView(SgElasticity, PetscViewer);
/* accessors: what the other layers read */
PetscErrorCode SgElasticityGetComm(SgElasticity, MPI_Comm *);
PetscErrorCode SgElasticityGetDimension(SgElasticity, PetscInt *);
PetscErrorCode SgElasticityGetDMs(SgElasticity, DM *, DM *, DM *, DM *); /* displacement, vertex scalar, vertex vector, cell scalar */
PetscErrorCode SgElasticityGetMesh(SgElasticity, const SgMesh **);
PetscErrorCode SgElasticityGetOperators(SgElasticity, Mat *, Vec *); /* K and b */
PetscErrorCode SgElasticityGetMass(SgElasticity, Vec *);
PetscErrorCode SgElasticityGetNearNullSpace(SgElasticity, MatNullSpace *);                                /* NULL when not attached */
PetscErrorCode SgElasticityGetScales(SgElasticity, PetscReal *, PetscReal *, PetscReal *);                /* ||K|| (SgMatVertexNorm), ||b||_2, the largest nodal force */
PetscErrorCode SgElasticityStiffnessDisplacementMax(SgElasticity, Vec, PetscInt, PetscReal, PetscReal *); /* max_v (E_v / E) |y_v| (one material: the given max_v |y_v|): times ||K|| it bounds an elastic nodal force */
PetscErrorCode SgElasticityGetNodalNormSize(SgElasticity, PetscInt *);                                    /* -contact_kkt_scale: dim (vertex) or 1 (component) */
PetscErrorCode SgElasticityGetEnergyShift(SgElasticity, PetscReal *);
PetscErrorCode SgElasticityGetMaterial(SgElasticity, PetscReal *, PetscReal *);                                                              /* the one material, or of several the stiffest (largest E, the first of equals) */
PetscErrorCode SgElasticityGetMaterials(SgElasticity, const char **, PetscInt *, const PetscInt **, const PetscReal **, const PetscReal **); /* -material_label, number of -material_ids (0: one material for every cell), the ids, E and nu of each */
PetscErrorCode SgElasticityGetInfo(SgElasticity, PetscInt *, PetscInt *, PetscBool *, PetscLogDouble *);                                     /* dofs, cells, mms, assembly time */
PetscErrorCode SgElasticityEnergy(SgElasticity, Vec, PetscReal *);
PetscErrorCode SgElasticitySetLoadFactor(SgElasticity, PetscReal); /* loads and Dirichlet values times the factor */
PetscErrorCode SgElasticityGetLoadFactor(SgElasticity, PetscReal *);
PetscErrorCode SgElasticitySetDirichletValues(SgElasticity, const PetscReal[]); /* dim per Dirichlet id, unscaled from now on */
PetscErrorCode SgElasticityGetDirichletSize(SgElasticity, PetscInt *);
PetscErrorCode SgElasticityGetDirichletValues(SgElasticity, PetscBool *, PetscReal[]);             /* those set, if any */
PetscErrorCode SgElasticityGetFullLoadScales(SgElasticity, PetscReal *, PetscReal *, PetscReal *); /* ||b||_2, ||b||_inf, energy shift at factor 1 */
PetscErrorCode SgElasticityGetFullData(SgElasticity, Vec *, Vec *);                                /* at factor 1, local: the load before the lifting (this rank's cells' part), the Dirichlet values */
PetscErrorCode SgElasticityGlobalToLocal(SgElasticity, Vec, Vec);
PetscErrorCode SgElasticityFullDisplacement(SgElasticity, Vec, Vec);
PetscErrorCode SgElasticityCellFields(SgElasticity, Vec, Vec, Vec);
PetscErrorCode SgElasticityMMSErrors(SgElasticity, Vec, PetscReal *, PetscReal *);
PetscErrorCode SgElasticityDualNorm(SgElasticity, Vec, PetscReal *);
PetscErrorCode SgElasticityReaction(SgElasticity, Vec, PetscReal[3]);
/* the connected bodies of the mesh: a cell field 1, 2, ... (NULL: none) and their number (rigid.c) */
PetscErrorCode SgElasticityBodyField(SgElasticity, Vec, PetscInt *);
/* the body of each local vertex (m->nv entries), numbered 0.. alike on every rank, and their number (rigid.c) */
PetscErrorCode SgElasticityVertexBodies(SgElasticity, PetscInt *, PetscInt[]);
PetscErrorCode SgElasticityFixedResidual(SgElasticity, Vec, Vec); /* K u - f on the fixed components of partly fixed vertices */
PetscErrorCode SgElasticityGetDirichletBoundary(SgElasticity, const SgBoundary **);
PetscErrorCode SgElasticityForces(SgElasticity, Vec, PetscReal *, PetscReal *, PetscReal[3], PetscReal *);               /* loads and support forces at y: largest nodal (per vertex), resultant, sum of nodal magnitudes */
PetscErrorCode SgElasticityGetDataScales(SgElasticity, PetscReal *, PetscReal *, PetscReal *, PetscReal *, PetscReal *); /* largest Dirichlet value now and at factor 1, ||b||_inf and the total load ||f||_1 at factor 1, mesh diameter */
/* rotation-invariant norms (vnorm.c): per vertex the Euclidean length of its dim entries, largest and summed; for K the
   largest block row sum of the blocks' spectral norms */
PetscErrorCode SgVecVertexNormMax(Vec, PetscInt, PetscReal *);
PetscErrorCode SgVecVertexNormSum(Vec, PetscInt, PetscReal *);
PetscErrorCode SgMatVertexNorm(Mat, PetscInt, PetscReal *);
PetscErrorCode SgSimplexGradients(PetscInt, const PetscReal[], PetscReal[], PetscReal *);
PetscErrorCode SgElementStiffness(PetscInt, const PetscReal[], PetscReal, PetscReal, PetscReal[], PetscReal *);
PetscErrorCode SgLame(PetscReal, PetscReal, PetscReal *, PetscReal *);

/* ------------------------------------------------------------------ io: output.c (files, summary, fields), history.c, checkpoint.c */
typedef struct _n_SgSummary *SgSummary;
PetscErrorCode               SgFileTmpName(const char[], char[], size_t);
PetscErrorCode               SgFileCommit(MPI_Comm, const char[]);
PetscErrorCode               SgFileAbandon(MPI_Comm, const char[]);
PetscErrorCode               SgFileOpen(MPI_Comm, const char[], const char[], FILE **);
PetscErrorCode               SgFileClose(MPI_Comm, const char[], FILE **);
PetscErrorCode               SgFileBegin(const char[]);
PetscErrorCode               SgFileBeginHDF5(MPI_Comm, const char[], char[], size_t);
PetscErrorCode               SgFileReadAliasBegin(const char[], size_t, char[], size_t, PetscBool *);
PetscErrorCode               SgFileReadAliasEnd(const char[]);
void                         SgFileCleanup(void);
const char                  *SgFileErrorCause(int, const char[]);
PetscErrorCode               SgFileHDF5NameMax(MPI_Comm, size_t *);
PetscErrorCode               SgFileWriteHDF5(MPI_Comm, const char[], const char[], PetscErrorCode (*)(PetscViewer, void *), void *, PetscBool, PetscBool *, char[], size_t);
PetscErrorCode               SgOutputXdmfName(const char[], char[], size_t);
PetscErrorCode               SgSummaryCreate(SgSummary *);
PetscErrorCode               SgSummaryDestroy(SgSummary *);
PetscErrorCode               SgSummarySetRaw(SgSummary, const char[], const char[]);
PetscErrorCode               SgSummarySetReal(SgSummary, const char[], PetscReal);
PetscErrorCode               SgSummarySetInt(SgSummary, const char[], PetscInt);
PetscErrorCode               SgSummarySetBool(SgSummary, const char[], PetscBool);
PetscErrorCode               SgSummarySetString(SgSummary, const char[], const char[]);
PetscErrorCode               SgSummarySetRealArray(SgSummary, const char[], PetscInt, const PetscReal[]);
PetscErrorCode               SgSummarySetIntArray(SgSummary, const char[], PetscInt, const PetscInt[]);
PetscErrorCode               SgSummaryWrite(MPI_Comm, SgSummary, const char[], const char[]);
PetscErrorCode               SgOutputWrite(SgElasticity, const char[], PetscInt, Vec[], PetscInt, Vec[], PetscReal);
typedef PetscErrorCode (*SgOutputFill)(void *, PetscInt, PetscInt, Vec[], PetscInt, Vec[]);
PetscErrorCode SgOutputWriteSteps(SgElasticity, const char[], PetscInt, const PetscInt[], const PetscReal[], SgOutputFill, void *, PetscInt, Vec[], PetscInt, Vec[], PetscReal);

/* ------------------------------------------------------------------ contact: obstacle.c, contact.c, problem.c */
extern PetscFunctionList SgObstacleList; /* SgObstacle and SgObstacleRegister: include/signorini.h */
PetscErrorCode           SgObstacleCreate(MPI_Comm, const char[], PetscInt, const char[], SgObstacle *);
PetscErrorCode           SgObstaclePrintHelp(MPI_Comm, const char[], PetscInt); /* -help: every type's options */
PetscErrorCode           SgObstacleGetType(SgObstacle, const char *[]);
PetscErrorCode           SgObstacleGap(SgObstacle, const PetscReal[], const PetscReal[], PetscReal *);
PetscErrorCode           SgObstacleDistance(SgObstacle, const PetscReal x[], PetscReal *g, PetscReal n[]); /* signed distance g (> 0 outside) and the unit outward normal n at the closest point */
PetscErrorCode           SgObstacleHasDistance(SgObstacle, PetscBool *);
PetscErrorCode           SgObstacleSetPlacement(SgObstacle, PetscReal);
PetscErrorCode           SgObstacleGetTranslation(SgObstacle, PetscReal[3]);
PetscErrorCode           SgObstacleDestroy(SgObstacle *);
PetscErrorCode           SgObstacleCreate_Plane(SgObstacle);
PetscErrorCode           SgObstacleCreate_Parabola(SgObstacle);
PetscErrorCode           SgObstacleCreate_Ball(SgObstacle);
PetscErrorCode           SgObstacleCreate_CAD(SgObstacle); /* obstacle_cad.c */

/* ------------------------------------------------------------------ contact.c */
typedef struct _n_SgContact *SgContact;


PetscErrorCode SgContactCreate(SgElasticity, const char[], const SgBoundary *, const SgBoundary *, const SgBoundary *, const char[], SgContact *); /* the contact part, the master side (two bodies) or NULL, the obstacle's faces besides a pair or NULL, the obstacle type */
PetscErrorCode SgContactSetUp(SgContact);
/* the contact law (law.c; -friction_type, SgContactLawRegister in include/signorini.h): the bound of |lam_T| and its
   derivative in lam_N at a contact vertex; "none" leaves the frictionless code paths untouched */
#define SGLAWNONE             "none"
#define SGLAWTRESCA           "tresca"
#define SGLAWCOULOMB          "coulomb"
#define SG_LAW_MAX_PARAMETERS 8
extern PetscFunctionList SgContactLawList;
PetscErrorCode           SgContactLawRegisterAll(void);
PetscErrorCode           SgContactLawCreateFromOptions(PetscOptionItems *, MPI_Comm, PetscInt, SgContactLaw *);
PetscErrorCode           SgContactLawSetVertices(SgContactLaw, PetscInt, const PetscReal[]);
void                     SgContactLawBound(SgContactLaw, PetscInt, PetscReal, PetscReal *, PetscReal *); /* at owned contact vertex i, lam_N: g and dg/dlam_N */
PetscErrorCode           SgContactLawBoundMax(SgContactLaw, PetscReal, PetscReal *);                     /* max_i g_i(lam_N) over all ranks */
PetscErrorCode           SgContactLawGammaPrecision(SgContactLaw, PetscReal, PetscReal, PetscReal *);    /* lowers the gamma cap of double precision (lam max, y max at the active vertices); nothing without friction */
PetscErrorCode           SgContactLawGetType(SgContactLaw, const char *[]);
const char              *SgLawName(SgContactLaw); /* its type name, for messages */
PetscErrorCode           SgContactLawGetId(SgContactLaw, PetscInt *);
PetscErrorCode           SgContactLawGetTypeName(PetscInt, const char **);
PetscErrorCode           SgContactLawGetInfo(SgContactLaw, PetscBool *, PetscBool *, PetscReal *);         /* friction, coupled (the bound depends on lam_N), gamma_T / gamma */
PetscErrorCode           SgContactLawGetParameters(SgContactLaw, PetscInt *, const char *[], PetscReal[]); /* names (summary, checkpoint) and values, at most SG_LAW_MAX_PARAMETERS */
PetscErrorCode           SgContactLawGetDescription(SgContactLaw, const char **);                          /* "Coulomb F = 0.3", for messages */
PetscErrorCode           SgContactLawView(SgContactLaw, PetscViewer);
PetscErrorCode           SgContactLawDestroy(SgContactLaw *);
PetscErrorCode           SgContactLawGetSlipReference(SgContactLaw, PetscReal **);   /* the law's: 2 n dim (NULL without a tangential part) */
PetscErrorCode           SgContactLawGetSlipReferenceSize(SgContactLaw, PetscInt *); /* its length: 2 n dim, or 0 */
/* What the solvers ask of a law (SgContactLawGetProperties): the SSN, the controllers and the output choose their
   policies from these properties and never test which law it is, so a new law is one file. A type states two facts
   when created (friction: a tangential part; coupled: its bound depends on lam_N) and gets the properties that follow
   from them; its op getproperties may change them. All false: the frictionless law (and a problem without contact),
   the frictionless code paths. */
typedef struct {
  PetscBool tangential;  /* a tangential part: the multipliers lam_T, lamhat_T, the stick/slip states and the slip
                            reference (the SSN's tangential state and monitor, the prescribed slip, the pair's
                            tangential blocks; the checkpoint and nested iteration call the law's ops instead) */
  PetscBool nonlinear;   /* its SSN terms are nonlinear on fixed sets (the slip direction z/|z|): Newton steps on settled
                            sets converge, they do not land (the residual test against the load, the stagnation test,
                            no cycle test, the matrix changes on the same set), an iterative solve that fails is repeated
                            by sparse LU; the solvers built on the normal active set alone (-ssn_condense,
                            -ssn_pc_truncated_mg, -cont_type fast and vi) do not apply: ipf is the default controller */
  PetscBool coupled;     /* its bound depends on lam_N (Coulomb): nonsymmetric Jacobians (LU, BiCGStab; no CG or
                            Cholesky), a failed Newton iteration gets the fixed point on the frozen bound, pf and ipf
                            fall back to the shifted path (-cont_coulomb_shifted_path), PDAS may couple the slip
                            force (-cont_pdas_coulomb_coupled) */
  PetscBool dissipative; /* it dissipates work: the solution does not minimize the elastic energy V alone (no energy
                            check of the solution) */
} SgContactLawProperties;
PetscErrorCode SgContactLawGetProperties(SgContactLaw, SgContactLawProperties *); /* a NULL law: all false */
enum { SG_FRICTION_FREE  = 0,
       SG_FRICTION_STICK = 1,
       SG_FRICTION_SLIP  = 2 }; /* the state of a contact vertex */
/* friction at a displacement y (SgContactKKT): the tangential multiplier lam_T,i = -T_i (K y - b)_i / w_i balancing the
   tangential residual, its states, and its resultant sum_i w_i lam_T,i (the friction force on the obstacle) */
typedef struct {
  PetscInt  nstick, nslip;
  PetscReal force[3], force_norm; /* the resultant and its length */
  PetscReal traction;             /* sum_i w_i |lam_T,i| */
  PetscReal slip_max;             /* max_i |T_i y_i| */
  PetscReal bound, slip;          /* the two friction parts of the KKT measures (dual and complementarity) */
} SgFrictionSummary;
PetscErrorCode SgContactGetFrictionSummary(SgContact, SgFrictionSummary *); /* the law's summary of the last SgContactKKT (zeros without friction) */
/* the law's output fields (none for the frictionless law): names, and per field a vector (dim) or a scalar; their
   values at y (SgContactLawFields: the record of SgContactKKT at y) */
#define SG_LAW_MAX_FIELDS 8
PetscErrorCode SgContactLawGetFields(SgContactLaw, PetscInt *, const char *const **, const PetscBool **);
PetscErrorCode SgContactLawFields(SgContact, Vec, Vec[]);
/* the law's summary keys (none for the frictionless law): of a solve, and per load step, written through the
   caller's key writer (the output layer's summary; the law names the keys) */
typedef struct {
  void *ctx;
  PetscErrorCode (*setint)(void *, const char[], PetscInt);
  PetscErrorCode (*setreal)(void *, const char[], PetscReal);
  PetscErrorCode (*setintarray)(void *, const char[], PetscInt, const PetscInt[]);
  PetscErrorCode (*setrealarray)(void *, const char[], PetscInt, const PetscReal[]);
} SgContactLawKeys;
PetscErrorCode SgContactLawSummary(SgContactLaw, PetscInt, const SgFrictionSummary *, SgContactLawKeys *);
PetscErrorCode SgContactLawStepSummary(SgContactLaw, PetscInt, const SgFrictionSummary[], SgContactLawKeys *);
/* The law's part of PDAS (law_pdas.c; src/cont/pdas.c): per owned contact vertex its tangential state for the next
   solve (free, stick, slip), bound and slip direction, and the rows these give PDAS's linear system, in PDAS's
   working coordinates (the law's ops pdasstate and pdasrows). Empty for a law without them (the frictionless law):
   every call then does nothing. */
typedef struct _n_SgContactLawPdas *SgContactLawPdas;
typedef struct {
  PetscInt         n, dim;
  const PetscInt  *off, *axis; /* per vertex: its first dof in the local part of a vector; the dof of its normal */
  const PetscReal *w, *nax;    /* its lumped weight; the normal's component on the axis dof */
  const PetscReal *yref;       /* the slip reference in the working coordinates, n dim (unused by an empty object) */
  PetscReal        c;          /* the constant of the state test z = lam_T + c T (y - yref) */
  PetscBool        couple;     /* a bound from lam_N may take lam_N of the same solve (-cont_pdas_coulomb_coupled) */
} SgContactLawPdasSetup;
enum { SG_PDAS_ROW_NONE    = 0,
       SG_PDAS_ROW_FIXED   = 1,   /* the component is fixed at the slip reference (stick) */
       SG_PDAS_ROW_FORCE   = 2,   /* the force v: rhs -= v (slip) */
       SG_PDAS_ROW_COUPLED = 3 }; /* the row takes -v times the row of the normal's dof of K, rhs -= v b there (slip, a bound from lam_N of the same solve) */
/* a vertex's rows: per component (the normal's is SG_PDAS_ROW_NONE) its kind and value, and a spring B (dim x dim,
   row-major) added to the matrix and, acting on the slip T (y - yref), B yref to the right-hand side */
typedef struct {
  char      kind[3];
  PetscReal v[3];
  PetscBool spring;
  PetscReal B[9];
} SgContactLawPdasRows;
PetscErrorCode SgContactLawPdasCreate(SgContactLaw, MPI_Comm, const SgContactLawPdasSetup *, SgContactLawPdas *);
PetscErrorCode SgContactLawPdasUpdate(SgContactLawPdas, Mat, Vec, Vec, PetscBool, const char[], PetscInt *);                                     /* the states from y (K y - b if the bool) and the normal set; then the rows */
PetscErrorCode SgContactLawPdasGetRows(SgContactLawPdas, PetscInt *, const SgContactLawPdasRows **, const PetscReal **, PetscInt *, PetscInt *); /* rows, springs, their global counts */
PetscErrorCode SgContactLawPdasGetInfo(SgContactLawPdas, PetscBool *, PetscBool *);                                                              /* keeps states; its states may change on round-off */
PetscErrorCode SgContactLawPdasDestroy(SgContactLawPdas *);
PetscErrorCode SgContactSetSlipReference(SgContact, Vec);                  /* the start of a load step's slip increment (NULL: zero) */
PetscErrorCode SgContactComputeSlipReference(SgContact, Vec, PetscReal[]); /* the same into the caller's 2 n dim array, not installed */
PetscErrorCode SgContactGetSlipReference(SgContact, PetscReal **);         /* its values, dim per contact vertex (NULL without friction), then those of the full displacement (2 n dim) */

/* the tangential state a solver keeps over the law's vertices (lamhat_T, lam_T, the states now and at the last Jacobian,
   the slip directions there): made and sized by the law, empty (NULL arrays) without a tangential part */
typedef struct _n_SgContactLawState *SgContactLawState;

PetscErrorCode SgContactLawStateCreate(SgContactLaw, SgContactLawState *);
PetscErrorCode SgContactLawStateGetArrays(SgContactLawState, PetscReal **, PetscReal **, char **); /* lamhat_T, lam_T (n dim), states (n) */
PetscErrorCode SgContactLawStateGetJacobianArrays(SgContactLawState, char **, PetscReal **);       /* the states and slip directions at the last Jacobian */
PetscErrorCode SgContactLawStateDestroy(SgContactLawState *);
PetscErrorCode SgContactLawStateZeroShift(SgContactLawState);   /* lamhat_T = 0: a new path (nothing without a tangential part) */
PetscErrorCode SgContactLawStateAcceptShift(SgContactLawState); /* lamhat_T = lam_T, the last multiplier: ALM's update */
/* What the law's tangential terms in the SSN read of it and write for it (SgContactLawResidual, SgContactLawJacobian,
   SgContactLawStepCorrection, SgContactLawFloor): the normal part at the contact vertices and the Newton bookkeeping;
   the SSN fills it before each call. The frictionless law's terms do nothing. */
typedef struct {
  SgContact        c;
  PetscReal        gamma;        /* of the normal term; gamma_T = c gamma (the law's -friction_gamma_factor) */
  const PetscReal *lamhat, *g;   /* the normal shift, the gaps at the last residual (n) */
  const char      *actjac;       /* the normal active set of the last Jacobian */
  const PetscReal *gfix;         /* Coulomb's fixed point: the bound frozen per vertex, or NULL */
  PetscBool        havejac;      /* a Jacobian of this solve exists */
  PetscBool        stagnant;     /* the last Newton step did not halve ||F|| */
  PetscInt         njac;         /* the Jacobians of this solve, the next one included */
  PetscReal        kroff, udata; /* the round-off of K y at a vertex; the problem's displacement data */
  PetscReal       *uv, *ft;      /* work, n dim: the vertices' displacements (two bodies: relative) and forces */
  char            *fforce;       /* per vertex: 1 a reversed slip linearized as stick, 2 a stick linearized as slip */
  PetscInt         nforce;       /* their number on all ranks (set by SgContactLawJacobian) */
  const PetscInt  *faxis;        /* -ssn_frame: the normal's axis, its sign, the rotated vertices (NULL: none) */
  const PetscReal *fsign;
  const PetscBool *frot;
  void            *frame; /* and t -> Q_i^T t at vertex i */
  void (*tolocal)(void *, PetscInt, const PetscReal[], PetscReal[]);
  void *addctx; /* the Jacobian's dim x dim blocks per contact vertex into P (NULL: SgContactAddBlocks; two bodies
                   in the SSN's dual-mortar basis: on the slave vertex's own dofs) */
  PetscErrorCode (*addblocks)(void *, const PetscReal[], Mat);
} SgContactLawInput;
PetscErrorCode SgContactLawResidual(SgContactLaw, SgContactLawInput *, SgContactLawState, const PetscScalar[], const PetscReal[], PetscScalar[], PetscReal[6]); /* F += the tangential forces at y for the normal multipliers; the sums over all ranks */
PetscErrorCode SgContactLawJacobian(SgContactLaw, SgContactLawInput *, SgContactLawState, const PetscScalar[], const PetscScalar[], Mat);                       /* P += their generalized derivative at y (F(y) when stagnant) */
PetscErrorCode SgContactLawStepCorrection(SgContactLaw, SgContactLawInput *, SgContactLawState, const PetscScalar[], PetscReal[]);                              /* the forces w (z - P_g(z)) of the vertices linearized against their state */
PetscReal      SgContactLawFloor(SgContactLaw, const SgContactLawInput *, SgContactLawState, const PetscScalar[], PetscInt, PetscBool);                         /* the round-off of the tangential force at vertex i (PETSC_TRUE: of the equilibrium error) */
/* The checkpoint of the law and its state (SgContactLawSave, SgContactLawLoad): the controller hands the functions of
   its checkpoint writer or reader (the io layer's) with their context; the law names what it writes */
typedef struct {
  void *ctx;
  PetscErrorCode (*attribute)(void *, const char[], PetscDataType, const void *);
  PetscErrorCode (*contact)(void *, const char[], PetscInt, const PetscReal[]); /* dim per contact vertex (NULL: zeros) */
  PetscErrorCode (*reals)(void *, const char[], PetscInt, const PetscReal[]);   /* numbers every rank has */
} SgContactLawWriter;
typedef struct {
  void       *ctx;
  const char *file; /* for messages */
  PetscErrorCode (*hasattribute)(void *, const char[], PetscBool *);
  PetscErrorCode (*hasdataset)(void *, const char[], PetscBool *);
  PetscErrorCode (*attribute)(void *, const char[], PetscDataType, void *);
  PetscErrorCode (*contact)(void *, const char[], PetscInt, const char[], PetscReal[]); /* its name, dim, a description for messages */
  PetscErrorCode (*abandon)(void *);                                                    /* the reader freed before a refusal */
  PetscErrorCode (*reals)(void *, const char[], PetscInt, PetscReal **);                /* n numbers every rank has, allocated */
} SgContactLawReader;
PetscErrorCode SgContactLawSave(SgContactLaw, const PetscReal[], const PetscReal[], SgContactLawWriter *);            /* the law (NULL: none), its parameters, lamhat_T (NULL: zeros) and a slip reference (2 n dim) */
PetscErrorCode SgContactLawLoad(SgContactLaw, MPI_Comm, PetscReal[], PetscReal[], SgContactLawReader *, PetscBool *); /* checks the file's law and parameters against this one; lamhat_T, the slip reference; whether the file held its full part */
PetscErrorCode SgContactLawStepSave(SgContactLaw, PetscInt, const SgFrictionSummary[], SgContactLawWriter *);         /* its summaries of n finished load steps (law NULL or none: nothing) */
PetscErrorCode SgContactLawStepLoad(SgContactLaw, PetscInt, SgFrictionSummary[], SgContactLawReader *);               /* and back: zero counts and NaN sizes where the file holds none */
/* Nested iteration (-cont_nested): what a finer level starts from besides y and lam_N, bs numbers per contact vertex
   (0: nothing), a vector field (dim) or scalars; the controller interpolates them between the levels */
PetscErrorCode SgContactLawTransferSize(SgContactLaw, PetscInt *, PetscBool *);
PetscErrorCode SgContactLawTransferPack(SgContactLaw, SgContactLawState, PetscReal[]);         /* from a solver's state (NULL: zeros), n bs */
PetscErrorCode SgContactLawTransferUnpack(SgContactLaw, SgContactLawState, const PetscReal[]); /* the interpolated ones into the finer level's solver state */
/* The contact vertices owned by this rank, read-only (NULL for what is not wanted; the arrays are the contact
   object's, valid while it lives): their number here and in all, local vertex numbers and the offsets of their first
   dofs in the local part of a global displacement vector; the lumped boundary weights int_Gamma_c phi_i; the outward
   unit normals (n*dim); the gaps to the obstacle along the normals (at its current placement); |Gamma_c|. */
PetscErrorCode SgContactGetVertices(SgContact, PetscInt *, PetscInt *, const PetscInt *[], const PetscInt *[]);
PetscErrorCode SgContactGetWeights(SgContact, const PetscReal *[]);
PetscErrorCode SgContactGetNormals(SgContact, const PetscReal *[]);
PetscErrorCode SgContactGetGaps(SgContact, const PetscReal *[]);
PetscErrorCode SgContactGetArea(SgContact, PetscReal *);
/* The contact law on Gamma_c, a read-only view for the loops of the solvers (SgContactGetView). */
typedef struct {
  /* friction on Gamma_c (-friction_type): the law gives the bound of |lam_T| (SgContactLawBound) */
  SgContactLaw           law;
  SgContactLawProperties props; /* what the solvers ask of it (SgContactLawGetProperties) */
  /* the law's gamma_T / gamma and slip reference: SgContactLawGetInfo, SgContactLawGetSlipReference */
} SgContactView;
PetscErrorCode SgContactGetView(SgContact, SgContactView *);
PetscErrorCode SgContactGetObstacleType(SgContact, const char *[]);
PetscErrorCode SgContactGetNormalType(SgContact, const char *[]); /* -contact_normal: "obstacle" or "body" */
PetscErrorCode SgContactGetElasticity(SgContact, SgElasticity *);
PetscErrorCode SgContactActiveSetHash(SgContact, const char[], PetscInt64 *);
PetscErrorCode SgContactDestroy(SgContact *);
PetscErrorCode SgContactGap(SgContact, const PetscScalar[], PetscReal[]);
PetscErrorCode SgContactAddForce(SgContact, const PetscReal[], PetscScalar[]);
PetscErrorCode SgContactAddJacobian(SgContact, const char[], PetscReal, Mat);
PetscErrorCode SgContactAddBlocks(SgContact, const PetscReal[], Mat); /* J += a dim x dim block per contact vertex (two bodies: on its relative displacement, R^T B R) */
/* friction's view of a contact vertex: its displacement (n dim numbers from the local part of a global vector; two
   bodies: the relative displacement of the slave vertex against the master, R y, pair.h) and the nodal forces acting
   on it (F += f, two bodies: R^T f on both sides, equal and opposite) */
PetscErrorCode SgContactVertexDisplacements(SgContact, const PetscScalar[], PetscReal[]);
PetscErrorCode SgContactAddVertexForces(SgContact, const PetscReal[], PetscScalar[]);
PetscErrorCode SgContactMultiplierFromResidual(SgContact, Vec, PetscReal[]);
/* SgContactKKT: measures of the original problem (P) for a displacement y and the multiplier lam_i = -(K y - b)_i.n_i / w_i, each
   dimensionless (the same for any load level, material scale and unit system), with the force scale F (the largest
   nodal force on the body: a load on the free dofs, a support force K u - f on the Dirichlet part, a contact force
   w_i |lam_i|; not ||K|| ||y||, which grows like lambda as nu -> 1/2) and the length scale Y sqrt|Gamma_c|,
   Y = max(largest vertex displacement, largest initial penetration, largest Dirichlet value); with no data at this load
   factor (the answer is y = 0) both are the data's at factor 1. Nodal quantities are a vertex's Euclidean length (the
   same for the problem turned rigidly, SgVecVertexNormMax):
   equilibrium     ||K y - b + B^T W lam|| / F                              (interior and tangential part)
   infeasibility   ||max(0, g)||_{L2(Gamma_c)} / (Y sqrt|Gamma_c|)
   complementarity (||max(0, g)||_{L2(I)} + ||min(0, g)||_{L2(A)}) / (Y sqrt|Gamma_c|), A = {lam > 0}, as an L2 sum of squares
   dual            max_i w_i max(0, -lam_i) / F                            (nodal force a pressure >= 0 cannot balance)
   residual        max(equilibrium, dual, infeasibility, complementarity): the stopping measure
   roundoff        eps (||K|| ||y|| + ||b||) / F: the round-off of forming K y - b, the least force measure that double
                   precision can certify (above the tolerance: the problem cannot be solved to it)
   balance         |loads + support forces + contact forces| / (sum of their magnitudes): the resultant on the body
   penetration     ||max(0, g)||_{L2(Gamma_c)} in the problem's units (the paper's infeasibility) */
PetscErrorCode SgContactKKT(SgContact, Vec, SgKKT *);
PetscErrorCode SgContactFields(SgContact, Vec, const PetscReal[], Vec[4], Vec);
PetscErrorCode SgContactForceVector(SgContact, Vec, PetscReal[3]); /* sum_i w_i lam_i n_i with SgContactKKT's multiplier */
PetscErrorCode SgContactAxisAligned(SgContact, const char[], PetscInt[], PetscReal[]);
PetscErrorCode SgContactNormalsAxisAligned(SgContact, PetscBool *);
PetscErrorCode SgContactIsPair(SgContact, PetscBool *);                                     /* two bodies (-contact_master_ids): the conditions are the rows of a mortar pair */
PetscErrorCode SgContactPairMasterWeights(SgContact, Vec *);                                /* two bodies: |B^T 1| on the master side, NULL without a pair */
PetscErrorCode SgContactPairTransform(SgContact, const char[], const char[], Mat *, Mat *); /* two bodies: the dual-mortar basis transformation T (u = T v: the pair's conditions nodal in v) and T^-1; who asks and the refusal's advice for it */
/* two bodies (pair_fields.c): y -> the slave's pressure projected on the master side (a vertex field); y -> sum D lam,
   the forces on the slave body and on the master body */
PetscErrorCode SgContactPairMasterPressure(SgContact, Vec, Vec);
PetscErrorCode SgContactPairForces(SgContact, Vec, PetscReal *, PetscReal[3], PetscReal[3]);
PetscErrorCode SgContactSetLoadFactor(SgContact, PetscReal); /* the obstacle at t times its translation, the gaps d anew */
PetscErrorCode SgContactGetObstacleTranslation(SgContact, PetscReal[3]);
PetscErrorCode SgContactGapSum(SgContact, PetscReal, PetscReal *);          /* sum_i w_i d_i with the obstacle at a placement t */
PetscErrorCode SgContactGapsAt(SgContact, PetscReal, PetscReal[]);          /* d_i per owned contact vertex with the obstacle at a placement t */
PetscErrorCode SgContactNormalDisplacementMax(SgContact, Vec, PetscReal *); /* max_i n_i . y_i */

PetscErrorCode SgProblemGetElasticity(SgProblem, SgElasticity *);
PetscErrorCode SgProblemGetContact(SgProblem, SgContact *); /* NULL without a contact boundary */
PetscErrorCode SgProblemGetComm(SgProblem, MPI_Comm *);
PetscErrorCode SgProblemGetCreationTime(SgProblem, PetscLogDouble *);
PetscErrorCode SgProblemHasLoadSteps(SgProblem, PetscBool *);
/* contact/coarse.c: the coarser problems of nested iteration (-cont_nested) */
PetscErrorCode SgProblemGetRefinement(SgProblem, PetscBool *, PetscInt *); /* mesh from the options?, its -dm_refine */
PetscErrorCode SgProblemCreateCoarse(SgProblem, PetscInt, SgProblem *);    /* the same problem on the mesh refined k times fewer */

/* ------------------------------------------------------------------ io: history.c */
typedef struct {
  char      kind; /* 's': an SSN iteration, 'o': the end of an outer (continuation) step */
  PetscInt  outer, it, active, entered, left, ksp_its, ssn_its;
  PetscReal gamma, fnorm, r1, r2, V, dV, C1, C2, Em, rhoF, rhoC, infeas, kkt, time;
} SgHistoryRow;
typedef struct _n_SgHistory *SgHistory;
PetscErrorCode               SgHistoryCreate(SgHistory *);
PetscErrorCode               SgHistoryDestroy(SgHistory *);
PetscErrorCode               SgHistoryRowInit(SgHistoryRow *);
PetscErrorCode               SgHistoryAdd(SgHistory, const SgHistoryRow *);
PetscErrorCode               SgHistoryWrite(MPI_Comm, SgHistory, const char[], const char[]);
PetscErrorCode               SgHistoryGetRows(SgHistory, PetscInt *, SgHistoryRow **);
PetscErrorCode               SgHistoryReset(SgHistory);

/* ------------------------------------------------------------------ io: checkpoint.c, checkpoint_write.c, checkpoint_read.c, fingerprint.c
   The checkpoint file: the problem's fingerprint and the vertex coordinates (a restart may use another partition),
   written atomically; each owner of a state (the controller, its type, the friction state, the load steps:
   cont/state.c) saves it through a writer and loads it through a reader, by names of its own. A reader that refuses
   (another problem or mesh, a damaged file) is freed before the error returns: the caller's handle is gone then. */
/* one load step's result (quasi-static load stepping: SgProblemSetLoadFactor, SgContSolve again) */
typedef struct {
  PetscReal t, obstacle_displacement, normal_displacement_max, force, kkt, energy, time;
  PetscInt  outer, ssn_its, ksp_its, nactive;
  PetscBool converged;
  /* friction: stick and slip sets, |sum w lam_T|, sum w |lam_T| */
  PetscInt  nstick, nslip;
  PetscReal friction_force, friction_traction;
} SgLoadStep;
#define SG_LOADSTEP_NREAL 12
typedef struct _n_SgCheckpointWriter *SgCheckpointWriter;
typedef struct _n_SgCheckpointReader *SgCheckpointReader;
PetscErrorCode                        SgCheckpointWriterCreate(SgElasticity, SgContact, const char[], SgCheckpointWriter *);
PetscErrorCode                        SgCheckpointWriterAttribute(SgCheckpointWriter, const char[], PetscDataType, const void *); /* PETSC_INT, PETSC_REAL, PETSC_STRING */
PetscErrorCode                        SgCheckpointWriterReals(SgCheckpointWriter, const char[], PetscInt, const PetscReal[]);     /* numbers every rank has */
PetscErrorCode                        SgCheckpointWriterDisplacement(SgCheckpointWriter, const char[], Vec, PetscBool);           /* per vertex, with the Dirichlet values or zeros there */
PetscErrorCode                        SgCheckpointWriterContact(SgCheckpointWriter, const char[], PetscInt, const PetscReal[]);   /* bs per contact vertex (NULL: zeros) */
PetscErrorCode                        SgCheckpointWriterHistory(SgCheckpointWriter, SgHistory);
PetscErrorCode                        SgCheckpointWriterHas(SgCheckpointWriter, const char[], PetscBool *);
PetscErrorCode                        SgCheckpointWriterCommit(SgCheckpointWriter, PetscBool *, char[], size_t); /* ok, and why not */
PetscErrorCode                        SgCheckpointWriterDestroy(SgCheckpointWriter *);
PetscErrorCode                        SgCheckpointReaderOpen(SgElasticity, SgContact, const char[], SgCheckpointReader *);
PetscErrorCode                        SgCheckpointReaderGetFile(SgCheckpointReader, const char **);
PetscErrorCode                        SgCheckpointReaderHasAttribute(SgCheckpointReader, const char[], PetscBool *);
PetscErrorCode                        SgCheckpointReaderHasDataset(SgCheckpointReader, const char[], PetscBool *);
PetscErrorCode                        SgCheckpointReaderAttribute(SgCheckpointReader, const char[], PetscDataType, void *);          /* PETSC_STRING: a char ** to PetscFree */
PetscErrorCode                        SgCheckpointReaderReals(SgCheckpointReader, const char[], PetscInt, PetscInt *, PetscReal **); /* n (< 0: any), allocated */
PetscErrorCode                        SgCheckpointReaderDisplacement(SgCheckpointReader, const char[], const char[], Vec);
PetscErrorCode                        SgCheckpointReaderContact(SgCheckpointReader, const char[], PetscInt, PetscBool, const char[], PetscReal[]);
PetscErrorCode                        SgCheckpointReaderHistory(SgCheckpointReader, PetscInt, SgHistory);
PetscErrorCode                        SgCheckpointReaderDamaged(SgCheckpointReader *, const char[], PetscReal); /* frees the reader, returns the error */
PetscErrorCode                        SgCheckpointReaderAbandon(SgCheckpointReader *);                          /* frees the reader quietly, before a refusal */
PetscErrorCode                        SgCheckpointReaderDestroy(SgCheckpointReader *);

/* ------------------------------------------------------------------ solver: ssn.c (residual.c, jacobian.c, friction.c, convergence.c, fallback.c), ksp.c, condense.c */
typedef enum { SG_SSN_ITERATING,
               SG_SSN_SETTLED,
               SG_SSN_NEIGHBOURHOOD,
               SG_SSN_ZERO_RESIDUAL,
               SG_SSN_CYCLING,
               SG_SSN_NAN,
               SG_SSN_MAX_IT,
               SG_SSN_LINEAR_SOLVE,
               SG_SSN_SNES_FAILED,
               SG_SSN_KKT,
               SG_SSN_ROUNDOFF } SgSSNReason;
extern const char *const      SgSSNReasons[];
typedef struct _n_SgSSN      *SgSSN;
typedef struct _n_SgCondense *SgCondense;
typedef struct _n_SgTMG      *SgTMG;
typedef struct _n_SgFrame    *SgFrame;
/* the linear solver of the controller's steps (-<prefix>ksp_*, -<prefix>pc_*), shared by the unconstrained start, the
   SSN steps and the pdas baseline; J is the working matrix (a copy of K with its near null space) */
/* The default linear solver chosen for a problem (linear.c): set on the objects before their SetFromOptions, so that
   every option still wins and nothing is left in PETSc's options database */
typedef struct {
  PetscBool on;        /* the default applies (neither -ksp_type nor -pc_type given) */
  KSPType   ksp;       /* preonly, cg or bcgs */
  PCType    pc;        /* cholesky, lu or hypre */
  PetscBool mumps;     /* the factorization by MUMPS */
  PetscBool amg;       /* BoomerAMG with the settings of options/solver/hypre_l1gs.opts, -ksp_rtol 1e-8 */
  PetscBool condense;  /* the SSN's steps condensed (SgSSNSetCondense) */
  PetscBool tmg;       /* the SSN's truncated multigrid (SgSSNSetTruncatedMG) */
  PetscBool geometric; /* its interpolations of the mesh hierarchy */
} SgLinearDefault;
/* the default direct limit (-cont_direct_max_unknowns) of two bodies in 2D on one rank (solver/linear.c; fem/mesh.c
   predicts it for nested iteration's levels): no condensation of the pair's SSN steps, as on several ranks */
#define SG_PAIR_DIRECT_MAX_2D  20000
#define SG_LINEAR_DEFAULT_NAMG 7 /* the BoomerAMG settings (the size of SgLinearSolverSetDefault's entered[]) */
PetscErrorCode SgLinearSolverCreate(SgElasticity, const char[], const SgLinearDefault *, KSP *, Mat *);
PetscErrorCode SgLinearSolverSetDefault(KSP, const SgLinearDefault *, PetscBool[]);                                                      /* before the KSP's (or its SNES's) SetFromOptions ... */
PetscErrorCode SgLinearSolverEndDefault(KSP, const SgLinearDefault *, PetscBool[]);                                                      /* ... and after it (the BoomerAMG options entered for it taken out) */
PetscErrorCode SgLinearSolverPrintHelp(MPI_Comm, const char[]);                                                                          /* -help: the default solver's option */
PetscErrorCode SgLinearSolverDefaults(SgElasticity, const char[], PetscBool, PetscBool, SgLinearDefault *, PetscBool *, char[], size_t); /* linear.c: the default solver unless -ksp_type/-pc_type are given */
PetscErrorCode SgLinearSolverDefaultSSN(SgElasticity, SgContact, const char[], PetscBool, SgLinearDefault *, char[], size_t);
PetscErrorCode SgLinearSolverGeometricMG(const char[], PetscBool *); /* linear.c: -ssn_pc_truncated_mg_interp geometric given */
PetscErrorCode SgLinearSolveUnconstrained(SgElasticity, KSP, Mat, Vec, PetscInt *, KSPConvergedReason *, PetscLogDouble *, PetscLogDouble *);
PetscErrorCode SgLinearSolverFallback(KSP, PetscBool *);
PetscErrorCode SgSSNCreate(SgElasticity, SgContact, const char[], KSP, Mat, SgSSN *);
PetscErrorCode SgSSNSetCondense(SgSSN, PetscBool);               /* the default of -ssn_condense (before SgSSNSetFromOptions) */
PetscErrorCode SgSSNSetTruncatedMG(SgSSN, PetscBool, PetscBool); /* the defaults of -ssn_pc_truncated_mg and of its interpolations: geometric */
PetscErrorCode SgSSNSetFromOptions(SgSSN);                       /* the options, then the frames, condensation or truncated multigrid */
PetscErrorCode SgSSNDestroy(SgSSN *);
PetscErrorCode SgSSNSolve(SgSSN, PetscReal, PetscInt, Vec, PetscInt *, PetscInt *, SNESConvergedReason *);
PetscErrorCode SgSSNGetSNES(SgSSN, SNES *);
PetscErrorCode SgSSNUpdateLoad(SgSSN);                                           /* the load scales again after the load factor changed */
PetscErrorCode SgSSNGetShift(SgSSN, PetscReal **);                               /* lamhat per contact vertex, for the controller to set */
PetscErrorCode SgSSNGetMultiplier(SgSSN, const PetscReal **);                    /* max(0, lamhat + gamma g) at the last residual */
PetscErrorCode SgSSNGetPathValues(SgSSN, PetscReal *, PetscReal *, PetscReal *); /* gamma, J(gamma, y), dJ/dgamma there */
PetscErrorCode SgSSNGetReason(SgSSN, SgSSNReason *);
PetscErrorCode SgSSNSetNeighbourhood(SgSSN, PetscReal);
PetscErrorCode SgSSNSetHistory(SgSSN, SgHistory, PetscLogDouble);
PetscErrorCode SgSSNGetMonitor(SgSSN, PetscBool *);
PetscErrorCode SgSSNSetProgress(SgSSN, PetscBool);
PetscErrorCode SgSSNPathMeasures(SgSSN, PetscReal *, PetscReal *);
/* a controller's own stopping test, called after every Newton step instead of the SSN's (it sets the SNES reason and
   the SSN's): hook(ssn, iteration, ||F||, settled, &reason, ctx); NULL restores the SSN's test */
typedef PetscErrorCode (*SgSSNStopTest)(SgSSN, PetscInt, PetscReal, PetscBool, SNESConvergedReason *, void *);
PetscErrorCode SgSSNSetStopTest(SgSSN, SgSSNStopTest, void *);
PetscErrorCode SgSSNSetReason(SgSSN, SgSSNReason);
PetscErrorCode SgSSNStatesAtRoundoff(SgSSN, PetscReal, PetscBool, PetscBool *); /* (||F||, settled): the states still changing do so on round-off and ||F|| is at its round-off floor */
PetscErrorCode SgSSNSetRevisited(SgSSN, PetscBool *);                           /* the active set at the last residual was the Jacobian's of an earlier step of this solve */
PetscErrorCode SgSSNSetKeepPCOnSameSet(SgSSN, PetscBool);                       /* keep the preconditioner while gamma and the active set stay */
PetscErrorCode SgSSNCountSetChanges(SgSSN, Vec, PetscInt *);                    /* vertices whose state at y differs from the last Jacobian's set beyond round-off */
typedef enum {
  SG_SSN_MARGIN_OFF,
  SG_SSN_MARGIN_START,
  SG_SSN_MARGIN_ON
} SgSSNMargin;
PetscErrorCode SgSSNCountSetChangesMargin(SgSSN, Vec, SgSSNMargin, PetscInt *);          /* the same for a linear solve's iterates: a change counted only beyond its change since the last one */
PetscErrorCode SgSSNPrintHelp(MPI_Comm, const char[]);                                   /* -help without a problem: the SSN's options */
PetscErrorCode SgSSNKSPVectorToGlobal(SgSSN, Vec);                                       /* a vector of the KSP's solve (in the contact frames) back to the original coordinates */
PetscErrorCode SgSSNGetFriction(SgSSN, PetscReal **, const PetscReal **, const char **); /* lamhat_T, lam_T, states */
PetscErrorCode SgSSNGetLawState(SgSSN, SgContactLawState *);                             /* the law's tangential state of this solver */
PetscErrorCode SgSSNEquilibriumError(SgSSN, Vec, PetscReal, PetscReal *, PetscReal *);   /* (P_gamma)'s equilibrium residual against a force scale (SgKKT.fscale), and its round-off floor */
PetscErrorCode SgCheckSolverTypes(MPI_Comm, const char[]);
PetscErrorCode SgSolverConfigured(MPI_Comm, PetscErrorCode);
PetscErrorCode SgCondenseCreate(SgSSN, SgCondense *);
PetscErrorCode SgCondenseDestroy(SgCondense *);
PetscErrorCode SgTMGCreate(SgSSN, KSP, PetscBool, SgTMG *);                                      /* tmg.c: truncated multigrid on the KSP's AMG, or on the mesh hierarchy (PETSC_TRUE: gmg.c) */
PetscErrorCode SgTMGCreateBound(SgElasticity, SgContact, KSP, Mat, SgFrame, PetscBool, SgTMG *); /* tmg.c: the same for a solver without an SSN (pdas): its working stiffness and frame; PETSC_TRUE: the mesh hierarchy's interpolations */
PetscErrorCode SgTMGSetActiveSet(SgTMG, const char[]);
PetscErrorCode SgTMGDestroy(SgTMG *);
PetscErrorCode SgTMGL1GSSweep(Mat, PetscBool, PetscBool, Vec, Vec); /* tmg.c: one sweep of its several-rank smoother (tests/unit_tests.c) */
/* frame.c: a frame (n, t1, t2) per contact vertex for the linear solves (-ssn_frame); NULL where every normal is an axis */
PetscErrorCode SgFrameCreate(SgElasticity, SgContact, PetscBool, SgFrame *);                                 /* PETSC_TRUE: the body in one frame where the normals agree (-ssn_frame_global) */
PetscErrorCode SgFrameCreatePair(SgElasticity, SgContact, const char[], const char[], PetscBool, SgFrame *); /* two bodies: the dual-mortar transformation T, then the frames (-ssn_pair_transform); the advice of SgContactPairTransform; PETSC_TRUE: its products by MatPtAP (-ssn_pair_transform_ptap) */
PetscBool      SgFramePairTransform(SgFrame);                                                                /* the frame carries that transformation */
PetscErrorCode SgFrameGetGlobalRotation(SgFrame, const PetscReal **);                                        /* -ssn_frame_global: the body's one rotation R, else NULL */
PetscErrorCode SgFramePairInterpolation(SgFrame, Mat, Mat *);                                                /* an interpolation of K's unknowns taken into the pair's basis, (T Q)^-1 P */
PetscErrorCode SgFrameDestroy(SgFrame *);
PetscErrorCode SgFrameToLocal(SgFrame, Vec);      /* x_i <- Q_i^T x_i at the rotated contact vertices (a pair's frame: x <- Q^T T^-1 x) */
PetscErrorCode SgFrameForceToLocal(SgFrame, Vec); /* a force b_i <- Q_i^T b_i (a pair's frame: b <- Q^T T^T b) */
PetscErrorCode SgFrameToGlobal(SgFrame, Vec);     /* x_i <- Q_i x_i (a pair's frame: x <- T Q x) */
void           SgFrameVectorToLocal(SgFrame, PetscInt, const PetscReal[], PetscReal[]);
PetscErrorCode SgFrameGetStiffness(SgFrame, Mat *); /* Q^T K Q, with the rotated near null space */
PetscErrorCode SgFrameGetAxes(SgFrame, const PetscInt *[], const PetscReal *[], const PetscBool *[]);
PetscErrorCode SgFrameAttachKSP(SgFrame, KSP); /* the KSP solves in the frames, its vectors in the original coordinates */
PetscErrorCode SgFrameDetachKSP(SgFrame, KSP);
PetscErrorCode SgFrameResidualWork(SgFrame, Vec, Vec *);                               /* a vector for the SSN's K y - b (SgFrameSetResidual) */
PetscErrorCode SgFrameSetResidual(SgFrame, Vec, const PetscReal[], const PetscReal[]); /* the SSN's residual F in the frames, the normal forces w m on the normal dofs */

/* ------------------------------------------------------------------ cont: cont.c (the object), cont_options.c,
   cont_step.c, cont_loop.c (the outer loop), cont_solve.c (SgContSolve, load steps), report.c (views, summary,
   fields), none.c, alm.c, pf.c, ipf.c, pdas.c, vi.c: see cont/contimpl.h */
PetscErrorCode SgContRegisterAll(void);
PetscErrorCode SgObstacleRegisterAll(void);
