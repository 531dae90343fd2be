/* contact/contactimpl.h: the obstacle, the contact boundary and the problem (elasticity with contact); included by the files of src/contact only */
#pragma once

#include "sg.h"
#include "contact/pair.h"
#include <petsc/private/petscimpl.h> /* PetscHeaderCreate: SgProblem is a PetscObject */


struct _n_SgObstacle {
  MPI_Comm  comm;
  char      type[64];
  PetscInt  dim;
  PetscReal p[16];          /* shape parameters */
  PetscReal translation[3]; /* -obstacle_translation: a rigid translation of any obstacle at full load */
  PetscReal placement;      /* the part of it applied (the load factor; 1 without load steps) */
  PetscErrorCode (*gap)(SgObstacle, const PetscReal[], const PetscReal[], PetscReal *);
  /* -contact_normal obstacle: the signed distance g from x to the obstacle (> 0 outside) and the obstacle's unit
     outward normal n at the closest point (pointing towards the body); NULL: a type without it */
  PetscErrorCode (*distance)(SgObstacle, const PetscReal x[], PetscReal *g, PetscReal n[]);
  PetscErrorCode (*setfromoptions)(SgObstacle, PetscOptionItems *);
  PetscErrorCode (*destroy)(SgObstacle); /* NULL, or frees data */
  void *data;                            /* a type's own state (cad) */
};

/* obstacle_mesh.c (obstacle_mesh_file.c, obstacle_mesh_surface.c): triangulated surfaces (STL, .msh) given as -obstacle_cad_file */
PetscErrorCode SgObstacleMeshFileIs(const char[], PetscBool *);
PetscErrorCode SgObstacleSetUp_Mesh(SgObstacle, const char[], const PetscReal[], PetscReal);
PetscErrorCode SgObstacleMeshQuery(SgObstacle, PetscBool brute, const PetscReal[], const PetscReal[], PetscReal *, PetscReal *, PetscReal[]);

/* The scales of the KKT measures at y, from the forces acting on the body and the data, never from the volumetric
   stiffness lambda (||K|| ||y|| grows like lambda as nu -> 1/2, far beyond any force acting on the body):
   F       the force scale: the largest nodal force on the body, a load on the free dofs, a support force on the
           Dirichlet part (K u - f there) or a contact force (w_i |lam_i|; with friction the whole nodal force w_i |R_i|),
           and the shear part of ||K|| ||y||, 2 mu / (lambda + 2 mu) ||K|| ||y|| (all of it for nu = 0; a backward error
           scale that keeps the measures of compressible materials as independent of the mesh as the forces allow).
   Y       the displacement scale: max(||y||_inf, largest initial penetration, largest Dirichlet value).
   With no data at all at this load factor (no loads, Dirichlet values 0, no penetration; y = 0 then solves the
   frictionless problem) both are the data's at factor 1 (the largest Dirichlet value, obstacle translation or the
   displacement of the total load through the shear modulus; failing those the mesh diameter): a zero answer is
   measured against the problem, not 0/0, nor against its own round-off.
   rnoise  the round-off of a nodal force of R = K y - b formed in double precision, eps (||K|| ||y|| + ||b||)_inf;
           rnoise / F is the smallest equilibrium measure the arithmetic can certify.
   res, l1 the resultant of all forces on the body (loads, supports, contact) and the sum of their magnitudes: in
           equilibrium the resultant vanishes.
   R: K y - b with the rollers' fixed components zeroed, before the contact forces are taken out; lam from it. */
typedef struct {
  PetscReal F, Y, rnoise, res[3], l1;
  PetscBool zero;
} KKTScales;

/* what the op pdasrows reads of a contact vertex (law_pdas.c), in PDAS's working coordinates */
typedef struct {
  PetscInt         dim, axis; /* the normal's dof */
  PetscReal        nax, w, c; /* the normal's component on it, the lumped weight, the constant of the state test */
  PetscBool        couple;    /* the law's bound from lam_N may take lam_N of the same solve */
  char             st;        /* its state (SG_FRICTION_FREE/STICK/SLIP), bound, |z| at the state test, slip direction */
  PetscReal        g, zn;
  const PetscReal *t;
} SgContactLawPdasVertex;

/* law.c: the contact law, a type of the registry SgContactLawList (-friction_type, SgContactLawRegister). A type's
   create function sets its ops, data and the flags friction and coupled; the bound op is a pointwise kernel. */
typedef struct {
  /* the bound g of |lam_T| at owned contact vertex i (coordinates law->x + i dim) for the normal multiplier lamN, and
     if dg is not NULL its derivative dg/dlamN (the Jacobian's coupling t n^T; 0 where g does not depend on lamN) */
  void (*bound)(SgContactLaw, PetscInt i, PetscReal lamN, PetscReal *g, PetscReal *dg);
  PetscErrorCode (*setfromoptions)(SgContactLaw, PetscOptionItems *); /* its own options (also called under -help for every type) */
  PetscErrorCode (*setup)(SgContactLaw);                              /* after the options: what must have been given */
  /* its parameters by their summary and checkpoint names (the law keeps both arrays) */
  PetscErrorCode (*getparameters)(SgContactLaw, PetscInt *, const char *const **, const PetscReal **);
  PetscErrorCode (*view)(SgContactLaw, PetscViewer);
  PetscErrorCode (*destroy)(SgContactLaw); /* NULL, or frees what data holds (data itself is freed after it) */
  /* the tangential terms of the SSN (SgContactLawResidual, SgContactLawJacobian, SgContactLawStepCorrection,
     SgContactLawFloor of sg.h, which describes them): NULL without a tangential part; a type with one that sets none
     gets the regularized friction of its bound (law_regularized.c) */
  PetscErrorCode (*residual)(SgContactLaw, SgContactLawInput *, SgContactLawState, const PetscScalar[], const PetscReal[], PetscScalar[], PetscReal[6]);
  PetscErrorCode (*jacobian)(SgContactLaw, SgContactLawInput *, SgContactLawState, const PetscScalar[], const PetscScalar[], Mat);
  PetscErrorCode (*stepcorrection)(SgContactLaw, SgContactLawInput *, SgContactLawState, const PetscScalar[], PetscReal[]);
  PetscReal (*floor)(SgContactLaw, const SgContactLawInput *, SgContactLawState, const PetscScalar[], PetscInt, PetscBool);
  /* the checkpoint of its tangential state (lamhat_T, the slip reference; SgContactLawSave/Load write and check the
     type and its parameters): NULL without one; a type with a tangential part that sets none gets law_regularized.c's */
  PetscErrorCode (*save)(SgContactLaw, const PetscReal[], const PetscReal[], SgContactLawWriter *);
  PetscErrorCode (*load)(SgContactLaw, PetscReal[], PetscReal[], SgContactLawReader *, PetscBool *);
  /* the checkpoint of its summaries of the finished load steps (n of them; SgContactLawStepSave/Load): stepload reads
     what the file holds into fs, filled beforehand with zero counts and NaN sizes. NULL: none; a type with a tangential
     part that sets none gets law_measures.c's (the dataset load_steps_friction) */
  PetscErrorCode (*stepsave)(SgContactLaw, PetscInt, const SgFrictionSummary[], SgContactLawWriter *);
  PetscErrorCode (*stepload)(SgContactLaw, PetscInt, SgFrictionSummary[], SgContactLawReader *);
  /* nested iteration (-cont_nested; SgContactLawTransferSize/Pack/Unpack): the state a finer level starts from, bs
     numbers per owned contact vertex, interpolated as a vector (vector true: bs = dim) or as bs scalars; pack writes
     them from a solver's state (NULL: no solver, zeros), unpack sets the next level's solver state from the
     interpolated ones. NULL: nothing to transfer (bs 0); a type with a tangential part that sets none gets
     law_regularized.c's (the multiplier lam_T, the next level's shift lamhat_T) */
  PetscErrorCode (*transfersize)(SgContactLaw, PetscInt *, PetscBool *);
  PetscErrorCode (*transferpack)(SgContactLaw, SgContactLawState, PetscReal[]);
  PetscErrorCode (*transferunpack)(SgContactLaw, SgContactLawState, const PetscReal[]);
  /* its part of the KKT measures of y (SgContactKKT; NULL: none, the frictionless law): in ra = K y - b (the rollers'
     fixed components zeroed), lam the normal multipliers, ynrm ||y||_inf, the scales; out the contact object's record
     per vertex (klt, kslip, kst), its summary c->fsum but the slip part, *slip2 this rank's part of the
     complementarity^2, and ra without what the law balances. A type with a tangential part that sets none gets
     law_measures.c's (the regularized law's lam_T from the tangential residual). */
  PetscErrorCode (*kkt)(SgContactLaw, SgContact, Vec, PetscScalar[], const PetscReal[], PetscReal, const KKTScales *, PetscReal *);
  /* the force of the contact on the body at a vertex for the KKT's force scale, from its residual r and normal part rn
     (n the normal; wlam = w |lam|), into f (dim), and its size (NULL: the normal force rn n, of size wlam) */
  PetscReal (*contactforce)(SgContactLaw, PetscInt, const PetscScalar[], const PetscReal[], PetscReal, PetscReal, PetscReal[]);
  /* its output fields: names and whether each is a vector (dim per vertex) or a scalar; and their values at the last
     SgContactKKT's record (zero off the contact vertices); NULL: none */
  PetscErrorCode (*getfields)(SgContactLaw, PetscInt *, const char *const **, const PetscBool **);
  PetscErrorCode (*fields)(SgContactLaw, SgContact, Vec[]);
  /* its summary keys, of one solve's summary (the last SgContactKKT's) and per load step; NULL: none */
  PetscErrorCode (*summary)(SgContactLaw, PetscInt, const SgFrictionSummary *, SgContactLawKeys *);
  PetscErrorCode (*stepsummary)(SgContactLaw, PetscInt, const SgFrictionSummary[], SgContactLawKeys *);
  /* PDAS (Hueber-Stadler-Wohlmuth): the state of vertex i for the next solve from lamN and z = lam_T + c T (y - yref)
     of length nz (dim components, the normal's axis component 0), its last state st and slip direction t (updated
     on slip; *dt its largest change); the bound into *g. NULL without a tangential part (SgContactLawPdasCreate:
     an empty object); a type with one gets law_pdas.c's unless it sets its own */
  char (*pdasstate)(SgContactLaw, PetscInt, PetscReal, PetscInt, const PetscReal[], PetscReal, char, PetscReal[], PetscReal *, PetscReal *);
  /* PDAS: the rows of vertex i in its state v->st (SgContactLawPdasRows of sg.h, zeroed before), a pointwise kernel.
     A type with a tangential part that does not set it gets law_pdas.c's (stick rows fixed, slip forces, springs) */
  void (*pdasrows)(SgContactLaw, PetscInt, const SgContactLawPdasVertex *, SgContactLawPdasRows *);
  /* the properties the solvers ask for (SgContactLawGetProperties; sg.h describes them), filled beforehand with those
     that follow from the flags friction and coupled; NULL: those */
  PetscErrorCode (*getproperties)(SgContactLaw, SgContactLawProperties *);
} SgContactLawOps;

PetscErrorCode SgContactLawSetRegularizedOps(SgContactLaw); /* law_regularized.c */
PetscErrorCode SgContactLawSetPdasOps(SgContactLaw);        /* law_pdas.c */

struct _n_SgContactLaw {
  MPI_Comm         comm;
  char             type[64];
  char             desc[96]; /* for messages: "Coulomb F = 0.3" (the type's setup may write it) */
  PetscInt         id;       /* its number in the registry (0 none, 1 tresca, 2 coulomb, ...): checkpoints */
  PetscInt         dim, n;   /* the owned contact vertices */
  const PetscReal *x;        /* their coordinates, n dim (SgContactLawSetVertices, kept by the contact object) */
  PetscReal        gfac;     /* -friction_gamma_factor c: gamma_T = c gamma (every law) */
  PetscBool        friction; /* a tangential part (false: frictionless, the solvers' frictionless paths) */
  PetscBool        coupled;  /* the bound depends on lam_N: nonsymmetric Jacobians, Coulomb's fallbacks */
  SgContactLawOps  ops;
  void            *data; /* the type's parameters */
  PetscReal       *yref; /* with a tangential part: the slip reference, 2 n dim (+1): the displacement (two bodies: the
                            relative one) at the start of the load step at the vertices' unknowns, then of the full
                            displacement (zeros at the first step); the contact object's working array */
};

/* the tangential state of a solver over the law's vertices (SgContactLawStateCreate): sized and freed by the law, one
   per solver (controllers sharing a contact object keep their own); empty without a tangential part */
struct _n_SgContactLawState {
  PetscInt   n, dim;
  PetscReal *lamhatT, *lamT; /* the tangential shift lamhat_T and multiplier lam_T, n dim */
  char      *state;          /* SG_FRICTION_FREE/STICK/SLIP at the last residual */
  char      *statejac;       /* and at the last Jacobian */
  PetscReal *tjac;           /* the slip direction z/|z| at the last Jacobian, n dim */
};

struct _n_SgContact {
  SgElasticity prob;
  /* read once from the elasticity object */
  MPI_Comm          comm;
  PetscInt          dim;
  DM                dm, dmVert, dmVec;
  const SgMesh     *mesh;
  Mat               K;
  Vec               b;
  char              obstype[64]; /* obstacle type given through the interface ("": plane unless -obstacle_type) */
  SgBoundary        bnd;
  SgObstacle        obs;
  PetscInt          n, nglobal; /* contact vertices owned here / in all */
  PetscInt         *vert;       /* local vertex number */
  PetscInt         *off;        /* offset of its first dof in the local part of a global displacement vector */
  PetscReal        *normal;     /* outward unit normals, n*dim */
  PetscReal        *w;          /* lumped boundary weights int_Gamma_c phi_i */
  PetscReal        *d;          /* gap to the obstacle along the normal (at the obstacle's current placement) */
  PetscBool         obsnormal;  /* -contact_normal obstacle: normal = -n_o and d = g, the obstacle's signed distance and
                            normal at the closest point (SgObstacleDistance); body: the facets' normal, d along it */
  PetscReal         area;
  char             *prefix;
  SgContactLaw      law;      /* -friction_type and its parameters */
  PetscBool         tangpart; /* the law's property tangential (SgContactLawGetProperties) */
  PetscReal         fgfac;    /* -friction_gamma_factor c: gamma_T = c gamma (the law's) */
  PetscReal        *xc;       /* the coordinates of the contact vertices, n dim (for the law) */
  SgFrictionSummary fsum;     /* of the last SgContactKKT */
  PetscReal        *yref;     /* friction: the law's slip reference (SgContactLawGetSlipReference), the displacement at the start of the load step, n*dim (0 at the first): the
                                tangential law acts on the slip increment T_i (y_i - yref_i) */
  /* prescribed tangential motion (friction): the fixed components of partly fixed contact vertices hold Dirichlet
     data, not unknowns; their slip is the data's increment, and where a Dirichlet facet is a contact facet too its
     reaction is a traction on Gamma_c (the friction force, up to the bound) */
  PetscBool  haspartial; /* some contact vertex, on some rank, has fixed components */
  PetscBool  hasdface;   /* some contact vertex has components fixed by a Dirichlet facet of Gamma_c */
  PetscInt  *dmask;      /* per contact vertex: those components (bits) */
  PetscReal *ypref;      /* the full displacement at the start of the load step, n*dim (used on fixed components):
                                the second half of yref */
  PetscReal *ypfull;     /* the full displacement of the last recorded SgContactKKT, n*dim, and (from n*dim on)
                                its y: SgContactSetSlipReference of that y takes the data of that call */
  PetscBool  haverecord;
  PetscBool  norecord; /* SgContactKKT for the fields: the friction summary and the record left alone */
  /* per contact vertex, of the last SgContactKKT: the multiplier, the active flag, and with friction lam_T, the slip
     and the state (the fields and the summary's vectors are these numbers) */
  PetscReal *klam, *klt, *kslip;
  char      *kact, *kst;
  /* two bodies (-contact_master_ids): the contact boundary is the slave side of a pair with the master side of the
     same label; its conditions are the rows of the pair's mortar operator B (pair.h): contact vertex i is the slave
     vertex of row prow[i] (local), w_i = D_i, d_i = g0_i / D_i, the gap (B y)_i / D_i - d_i, the force B^T lam and
     the Jacobian's term gamma B^T diag(act / D) B. NULL pair: the obstacle's nodal conditions. */
  SgBoundary    master;
  PetscReal     pairdist;
  PetscBool     pairavg;   /* -contact_pair_normal average */
  PetscBool     pairbrute; /* -contact_pair_search brute */
  SgContactPair pair;
  PetscInt     *prow;
  /* a rigid obstacle besides the pair (-contact_obstacle_ids, the faces that may touch it): its nodal conditions are
     rows of B too (w_i n_i^T e_i, d_i the obstacle's gap), marked obsrow[i]; their gaps follow the obstacle's
     placement */
  SgBoundary obnd;
  PetscBool *obsrow;
  char       obsdesc[160]; /* the obstacle's description then (SgContactGetObstacleType) */
  Vec        pw, pf, pl;   /* work: displacement and force wrappers (no array), B's row vector */
  Vec        pr;           /* with friction: R's row vector (pair.h: the relative displacements) */
};

/* c = a x b (3D) */
static inline void SgCross3(const double a[3], const double b[3], double c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/* a / b for a measure a >= 0 against its scale b >= 0: 0 when there is nothing to measure, infinite when the scale
   vanishes but the measure does not */
static inline PetscReal SafeRatio(PetscReal a, PetscReal b)
{
  if (!(a > 0)) return a == 0 ? 0 : a; /* 0, or NaN passed on */
  return b > 0 ? a / b : PETSC_INFINITY;
}

/* the force below which a nodal force at contact vertex i is round-off: 1e-12 of the force scale, and at least a few
   times the round-off of forming the residual */
static inline PetscReal ForceNoise(SgContact c, const KKTScales *sc, PetscInt i)
{
  return PetscMax(1e-12 * sc->F, 4 * sc->rnoise) / c->w[i];
}

/* law_measures.c: the KKT part, fields and summary of a law with a bound; contact.c: the per-vertex record at y */
PetscErrorCode SgContactLawSetMeasureOps(SgContactLaw);
PetscErrorCode SgContactLawKKT(SgContactLaw, SgContact, Vec, PetscScalar[], const PetscReal[], PetscReal, const KKTScales *, PetscReal *); /* law.c: the op kkt */
PetscReal      SgContactLawContactForce(SgContactLaw, PetscInt, const PetscScalar[], const PetscReal[], PetscReal, PetscReal, PetscReal[]);
PetscErrorCode SgContactLawFillFields(SgContactLaw, SgContact, Vec[]);

/* contact.c: a surface's lumped weights and area-weighted normal sums, summed over the ranks (local vectors) */
PetscErrorCode SgContactLumpedSurface(SgContact, PetscInt, const PetscInt[], Vec, Vec, PetscReal *);

/* contact_pair.c: the contact object as a two-body pair (its fields master, pairdist, pair, prow, pw, pf, pl) */
PetscErrorCode SgContactPairFromOptions(PetscOptionItems *, SgContact);
PetscErrorCode SgContactPairSetUp(SgContact, PetscInt, const PetscInt[], const PetscReal[], const PetscReal[], const PetscReal[]);
PetscErrorCode SgContactPairGap(SgContact, const PetscScalar[], PetscReal[]);
PetscErrorCode SgContactPairForce(SgContact, const PetscReal[], PetscScalar[]);
PetscErrorCode SgContactPairJacobian(SgContact, const char[], PetscReal, Mat);
PetscErrorCode SgContactPairRelative(SgContact, const PetscScalar[], PetscReal[]);
PetscErrorCode SgContactPairTangentialForce(SgContact, const PetscReal[], PetscScalar[]);
PetscErrorCode SgContactPairBlocks(SgContact, const PetscReal[], Mat);

/* A PetscObject (class SG_PROBLEM_CLASSID): its header holds the reference count (the caller's handle and each
   controller's PetscObjectReference), the options prefix and the name; PetscObjectView/ViewFromOptions reach
   SgProblemView through it. */
struct _n_SgProblem {
  struct _p_PetscObject hdr;
  MPI_Comm              comm;         /* the caller's communicator (the header keeps PETSc's duplicate) */
  DM                    dm;           /* the caller's mesh (SgProblemSetDM), or NULL: from the options */
  SgElasticitySettings  settings;     /* material and boundary parts given through the interface */
  SgBoundary            contact;      /* the contact boundary given through the interface */
  SgBoundary            master;       /* two bodies: the master side given through the interface (SG_BOUNDARY_CONTACT_MASTER) */
  SgBoundary            obnd;         /* two bodies and an obstacle: its faces given through the interface (SG_BOUNDARY_CONTACT_OBSTACLE) */
  char                  obstacle[64]; /* obstacle type given through the interface ("" : from the options) */
  SgElasticity          el;
  SgContact             c; /* NULL: no contact boundary (linear elasticity) */
  PetscBool             setfromoptions, setup;
  PetscBool             setup_failed; /* SgProblemSetUp stopped with an error: its half-made state is not used again */
  PetscBool             load_set;     /* SgProblemSetLoadFactor or SgProblemSetDirichletValues was called: a run with load steps */
  PetscLogDouble        t_create;
  PetscInt              values_dim[5]; /* the dimension SgProblemSetBoundary read its values with, per SgBoundaryType (0: none given) */
};
