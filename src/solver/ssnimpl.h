/* solver/ssnimpl.h: the semismooth Newton solver of (P_gamma); included by the files of src/solver only */
#pragma once

#include "sg.h"


struct _n_SgSSN {
  SgElasticity  prob;
  SgContact     c;  /* NULL without a contact boundary */
  SgContactView cv; /* its law */
  /* read once from the contact object (SgContactGetVertices, ...; NULL and 0 without it) */
  PetscInt         n, nglobal; /* contact vertices owned here, in all */
  const PetscInt  *vert, *off; /* their local vertex numbers, the offsets of their first dofs in the local vector */
  const PetscReal *w, *normal; /* boundary weights, outward unit normals (n*dim) */
  const PetscReal *d;          /* gaps to the obstacle along the normals */
  /* read once from the elasticity object */
  MPI_Comm          comm;
  PetscInt          dim;
  PetscInt          nd; /* the nodal norms' size (SgElasticityGetNodalNormSize: dim or 1) */
  const SgMesh     *mesh;
  Mat               K;
  Vec               b, mass;
  PetscReal         Knorm, bnorm, bnorm_inf, energy_shift;
  PetscReal        *lamhat; /* the shift of (P_gamma), set by the controller (SgSSNGetShift) */
  SNES              snes;
  Mat               J;
  Vec               r;
  PetscReal         gamma;
  PetscReal        *g, *m;        /* gap and max(0, lamhat + gamma g) at the last residual evaluation */
  char             *act, *actjac; /* active set there, and the one the last Jacobian used */
  PetscBool         havejac;
  PetscInt          nact, nentered, nleft;
  PetscReal         kroff;   /* the round-off of K y at a vertex, 8 eps ||K|| (||y|| + max |d|), per vertex, at the last residual evaluation */
  PetscReal         dmax;    /* max |d| over the contact vertices (SgSSNSolve) */
  PetscReal         udata;   /* the largest Dirichlet value now and at load factor 1 (SgSSNUpdateLoad) */
  PetscInt          nhard;   /* the changes of state (normal and friction) beyond round-off at the last residual evaluation */
  PetscReal         V, dVdg; /* J(gamma, y) and dJ/dgamma at the last residual evaluation */
  PetscReal         r1, r2, fdual, fnorm0, prev_fnorm;
  PetscReal         ffloor; /* the round-off floor of ||F|| at the last residual evaluation (the gamma-scaled terms) */
  PetscBool         prev_settled;
  PetscInt          nhash, maxhash; /* hashes of the active sets of this solve's Newton steps */
  PetscInt64       *hash;
  PetscBool         residual_test;       /* inexact linear solves: also require a small residual */
  PetscInt          pc_reuse_its;        /* > 0: keep the preconditioner within a solve while the Krylov solver needs <= this */
  SgCondense        cond;                /* -ssn_condense: linear solves condensed onto the contact dofs */
  SgTMG             tmg;                 /* -ssn_pc_truncated_mg: the preconditioner follows the active set (tmg.c) */
  PetscBool         condense_default;    /* the defaults of -ssn_condense and -ssn_pc_truncated_mg (SgSSNSetCondense, */
  PetscBool         tmg_default;         /* SgSSNSetTruncatedMG: the default linear solver's, linear.c) and of its */
  PetscInt          interp_default;      /* interpolations (1: geometric) */
  PetscBool         snes_setfromoptions; /* SgSSNSetFromOptions was called */
  SgFrame           frame;               /* -ssn_frame: the linear solves in each contact vertex's frame (frame.c), or NULL */
  PetscBool         frame_local;         /* -ssn_frame_global false: frames at the contact vertices alone, never the whole body's */
  PetscBool         pair_transform;      /* -ssn_pair_transform: two bodies solved in the dual-mortar basis (frame.c) */
  PetscBool         pair_transform_set;  /* given (else on for a pair solved iteratively) */
  PetscBool         pair_ptap;           /* -ssn_pair_transform_ptap: the basis's products by MatPtAP (frame.c) */
  PetscBool         tmg_coarse_ptap;     /* -ssn_pc_truncated_mg_coarse_ptap: several ranks, the coarse corrections by whole-pattern MatPtAP (tmg.c) */
  PetscBool         tmg_l1gs_sym;        /* -ssn_pc_truncated_mg_l1gs_symmetric: several ranks, symmetric l1 sweeps (tmg.c) */
  PetscBool         tmg_l1gs_glob;       /* -ssn_pc_truncated_mg_l1gs_global: with them, the whole residual between */
  PetscBool         tmg_l1gs_sym_set;    /* given (else on for a pair) */
  PetscBool         tmg_sor;             /* -ssn_pc_truncated_mg_local_sor: several ranks, PCSOR's local sweeps with a fallback (tmg.c) */
  PetscBool         tmg_sor_set;         /* given (else SG_TMG_LOCAL_SOR_PAIR for a pair, tmg.c) */
  PetscBool         tmg_l1gs_glob_set;   /* given (else SG_TMG_L1GS_GLOBAL_PAIR for a pair, tmg.c) */
  PetscBool         tmg_defl;            /* -ssn_pc_truncated_mg_deflate: CG's Ritz vectors deflated (deflate.c) */
  PetscBool         tmg_defl_set;        /* given (else SG_TMG_DEFLATE_PAIR for a pair, tmg.c) */
  PetscInt          tmg_defl_max;        /* -ssn_pc_truncated_mg_deflate_max: the space's maximum size */
  PetscReal         tmg_defl_ritz;       /* -ssn_pc_truncated_mg_deflate_ritz: Ritz values below it join the space */
  PetscBool         pair_amg_u;          /* -ssn_pair_amg_displacements: the truncated multigrid of a pair takes K's AMG, mapped */
  Mat               Klin;                /* the stiffness the linear solves start from: K, or Q^T K Q in the frames */
  Mat               Pf;                  /* with frames: the Jacobian assembled in them (the KSP's matrices) */
  PetscReal         nbhd_tau;            /* > 0: also stop in the neighbourhood ||(r1,r2)|| <= tau/sqrt(gamma) (IPF) */
  SgSSNReason       reason;
  PetscBool         monitor;
  PetscBool         progress;      /* a short line per iteration when -ssn_monitor is off (SgSSNSetProgress) */
  PetscViewer       reason_viewer; /* -snes_converged_reason, taken over (SgSSNReasonView in convergence.c) */
  PetscViewerFormat reason_format;
  SgHistory         hist;
  PetscInt          outer;
  PetscLogDouble    t0;        /* the history's time origin */
  SgSSNStopTest     stop_test; /* a controller's own stopping test (SgSSNSetStopTest) */
  void             *stop_ctx;
  PetscBool         pc_same_set; /* keep the preconditioner on an unchanged active set (SgSSNSetKeepPCOnSameSet) */
  PetscReal        *gy;          /* gaps of a prospective iterate (SgSSNCountSetChanges) */
  PetscReal        *zy;          /* decision values lamhat + gamma g of the last prospective iterate (SgSSNCountSetChangesMargin) */
  PetscBool         zy_valid;
  /* friction (cv.props.tangential: the law has a tangential part): lam_T = P_g(lamhat_T + gamma_T T y), gamma_T = cv.fgfac gamma */
  PetscReal *lamhatT, *mT; /* tangential shift and multiplier at the last residual evaluation, n*dim */
  PetscReal *uv, *ft;      /* work, n*dim: the contact vertices' displacements (two bodies: relative) and forces on them */
  char      *fst, *fstjac; /* friction state (SG_FRICTION_FREE/STICK/SLIP) there and at the last Jacobian */
  PetscReal *tjac;         /* the slip direction z/|z| at the last Jacobian, n*dim */
  char      *fforce;       /* 1: slips that reversed, linearized as stick at the last Jacobian; 2: sticks whose
                                 equilibrium force exceeds the bound, linearized as slip (SgSSNFrictionJacobian) */
  PetscBool  iterative;    /* the linear solver is not preonly */
  KSP        kspd;         /* friction: sparse LU (MUMPS), made when an iterative solve fails (SgSSNSolve) */
  Vec        y0;           /* the initial guess of the solve, kept for that repetition */
  PetscReal  gamma_direct; /* the gamma of the first such repetition (0: none): solves at or above it use kspd */
  PetscBool  stagnant;     /* friction: the last Newton step did not halve ||F|| (SgSSNConverged) */
  PetscInt   nforce;       /* their number, on all ranks */
  Vec       *wpre;         /* two work vectors of the step's correction for them (SgSSNFrictionPreCheck) */
  PetscInt   nstick, nslip, nfchanged;
  PetscReal *gfix;  /* Coulomb: the bound F lam_N frozen per vertex (a Tresca problem) while not NULL (SgSSNCoulombFixedPoint) */
  PetscReal *gfixw; /* its storage, n */
  PetscInt   fp_max_it, fp_m;
  PetscReal  fp_omega, fp_rtol;
  /* the law's tangential state of this solver (SgContactLawStateCreate), whose arrays lamhatT, mT, fst, fstjac, tjac are */
  SgContactLawState lst;
};

/* The round-off of a contact vertex's decision value lamhat_i + gamma g_i (its state: active where it is > 0) at the
   gap g_i: forming gamma (tau_N y - d) rounds by eps gamma (|tau_N y| + |d|) (the displacement data udata bounds |y|
   from below), and the multiplier it stands for is seen in the equilibrium only above the round-off of K y at the
   vertex (kroff, per unit weight). A value below it is a state that the arithmetic, not the problem, decides: it differs
   between a problem and its rigidly turned copy (rotation-invariant: lengths only). */
static inline PetscReal SgSSNDecisionRoundoff(SgSSN s, PetscInt i, PetscReal g)
{
  return 8 * PETSC_MACHINE_EPSILON * (PetscAbsReal(s->lamhat[i]) + s->gamma * (PetscAbsReal(g + s->d[i]) + PetscAbsReal(s->d[i]) + s->udata)) + s->kroff / s->w[i];
}

/* What the files of the SSN share (ssn.c the object and its solve, residual.c, jacobian.c, friction.c, convergence.c,
   fallback.c): the SNES callbacks set in SgSSNCreate and the steps one file takes from another */
PetscErrorCode SgSSNResidual(SNES, Vec, Vec, void *);
PetscErrorCode SgSeqAIJSamePattern(Mat, Mat, PetscBool *);
/* deflate.c: a deflation space from CG's Ritz vectors for the truncated multigrid */
typedef struct _n_SgDefl *SgDefl;
#define SG_DEFL_MAX  8    /* -ssn_pc_truncated_mg_deflate_max's default */
#define SG_DEFL_RITZ 0.05 /* -ssn_pc_truncated_mg_deflate_ritz's: under the continuum's start (0.04-0.05 on tb_sphere_s7) */
#define SG_DEFL_MCAP 80   /* preconditioned residuals kept per CG solve for the Ritz vectors */
PetscErrorCode SgDeflCreate(PetscInt, PetscInt, PetscReal, SgDefl *);
PetscErrorCode SgDeflApply(SgDefl, KSP, Mat, PC, Vec, Vec);
PetscErrorCode SgDeflGetSpace(SgDefl, PetscInt *, const Vec **, PetscInt *, PetscReal *);
PetscErrorCode SgDeflDestroy(SgDefl *); /* ssn.c: two SeqAIJ matrices' patterns equal (tmg.c compares MPIAIJ blocks with it) */
PetscErrorCode SgSSNJacobian(SNES, Vec, Mat, Mat, void *);
PetscErrorCode SgSSNConverged(SNES, PetscInt, PetscReal, PetscReal, PetscReal, SNESConvergedReason *, void *);
PetscErrorCode SgSSNMonitor(SNES, PetscInt, PetscReal, void *);
PetscErrorCode SgSSNReasonView(SNES, void *);
SgSSNReason    SgSSNReasonOf(SgSSN, SNESConvergedReason); /* ours for a SNES reason (a failure our test did not name: PETSc's) */
PetscErrorCode SgSSNLawInput(SgSSN, SgContactLawInput *); /* friction.c: what the law's tangential terms read of the SSN */
PetscErrorCode SgSSNFrictionResidual(SgSSN, const PetscScalar[], const PetscReal[], PetscScalar[], PetscReal[6]);
PetscErrorCode SgSSNFrictionJacobian(SgSSN, Vec, Mat);
PetscErrorCode SgSSNAddBlocks(SgSSN, const PetscReal[], Mat); /* jacobian.c: contact blocks, nodal under -ssn_pair_transform */
PetscErrorCode SgSSNFrictionPreCheck(SNESLineSearch, Vec, Vec, PetscBool *, void *);
PetscErrorCode SgSSNSolveDirect(SgSSN, PetscReal, Vec, PetscInt *, PetscInt *, SNESConvergedReason *);
PetscErrorCode SgSSNSolveL1GS(SgSSN, PetscReal, Vec, PetscInt *, PetscInt *, SNESConvergedReason *, PetscBool *);
PetscErrorCode SgGMGInterpolations(SgSSN, PetscInt *, Mat **); /* gmg.c: the mesh hierarchy's interpolations between free-dof spaces */
PetscErrorCode SgGMGCoarseSolver(KSP);                         /* gmg.c: the coarsest level's solver */
PetscErrorCode SgSSNCoulombFixedPoint(SgSSN, Vec, PetscInt *, PetscInt *, SNESConvergedReason *);
