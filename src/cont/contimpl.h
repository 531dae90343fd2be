/* cont/contimpl.h: the controller object and the interface a controller type implements; included by the files of src/cont
   only. A new controller is one file with its SgContCreate_<Type> (filling ops), one SgContRegister line in
   SgContRegisterAll (cont.c) and one options file. The object's files: cont.c (registry, life cycle, setters and
   getters), cont_options.c, cont_step.c (what the hooks call), cont_loop.c (the outer loop and its verdicts),
   cont_solve.c (SgContSolve and the load steps), report.c, state.c, nested.c.

   Continuation controllers (none of ops->solve set) run the outer loop of SgContSolve (cont_loop.c):
     ops->start     before the first step (not on a restart): the first gamma into ct->gamma and the shift lamhat
     -- the unconstrained solution y0 and V(0) = J(0, y0) --
     ops->started   after it (not on a restart), optional
     repeat: ops->prestep (optional), one SSN solve of (P_gamma) at ct->gamma, the KKT measures of (P),
             ops->model (optional: the path model's C1, C2, E and the measures for the history row),
             ops->update (only after a successful solve: the next gamma into *next, the shift lamhat),
             the stopping tests and the checkpoint (SgContCheck)
     ops->finish    after the loop, optional
   A solver that is not a continuation (none, and the baselines pdas and vi, which solve (P) directly without the SSN)
   sets ops->solve instead, and needs_ssn = PETSC_FALSE if it does not use the SSN.
   Checkpoints (cont/state.c, as PETSc's TSAdaptLoad): the object saves and loads its own state (type name, counters,
   gamma, y, lamhat, path, history), the friction state and the load steps, and calls ops->save/ops->load for the
   type's own (optional: a type without them keeps nothing). A type's numbers between outer steps go through
   SgContSaveState/SgContLoadState (the datasets "state" and "state_names": a file of another version of the type is
   refused); other data under names of its own.
   Load steps: a second SgContSolve (after SgProblemSetLoadFactor) is warm (ct->warm): SgContStart keeps y and takes
   V(0) = t^2 V0unit, ops->start and ops->started are skipped, ct->gamma = ct->gamma_warm (the last gamma solved at),
   and lamhat and the type's state stay as the last step left them; a type with ops->solve reads ct->warm itself. */
#pragma once

#include "sg.h"
#include <petsc/private/petscimpl.h> /* PetscHeaderCreate: SgCont is a PetscObject */

typedef struct {
  PetscErrorCode (*setfromoptions)(SgCont, PetscOptionItems *);
  PetscErrorCode (*start)(SgCont);
  PetscErrorCode (*started)(SgCont);
  PetscErrorCode (*prestep)(SgCont);
  PetscErrorCode (*model)(SgCont, SgHistoryRow *);
  PetscErrorCode (*update)(SgCont, PetscReal *);
  PetscErrorCode (*finish)(SgCont);
  PetscErrorCode (*solve)(SgCont);
  PetscErrorCode (*view)(SgCont, PetscViewer);        /* the type's parameters, continuing SgContView's first line ("; ...", no newline) */
  PetscErrorCode (*destroy)(SgCont);                  /* frees what data holds; SgContDestroy frees data itself */
  PetscErrorCode (*save)(SgCont, SgCheckpointWriter); /* the type's own state into a checkpoint, optional */
  PetscErrorCode (*load)(SgCont, SgCheckpointReader); /* and out of one (-restart_file) */
  PetscBool needs_ssn;
  PetscBool shifts; /* the type moves the shift lamhat between steps (alm): it progresses at a fixed gamma */
} SgContOps;

/* A PetscObject (class SG_CONT_CLASSID): its header holds the reference count, the options prefix (-<prefix>cont_*)
   and, once chosen, the type name (PetscObjectGetType); PetscObjectView/ViewFromOptions reach SgContView. */
struct _n_SgCont {
  struct _p_PetscObject hdr;
  MPI_Comm              comm;             /* the problem's communicator */
  char                  type[64];         /* empty until set: then the default for the problem (SgContSetFromOptions) */
  PetscBool             monitor;          /* -cont_monitor: a line per outer step */
  PetscBool             type_default;     /* the type is the default for the problem (neither SgContSetType nor -cont_type) */
  char                  solver_desc[256]; /* which linear solver runs, and why (SgLinearSolverDefaults) */
  SgLinearDefault       lin;              /* the default linear solver for the problem (lin.on: it applies) */
  PetscBool             lin_inherited;    /* lin is the finest level's (a coarse level of -cont_nested) */
  SgProblem             problem_obj;
  SgElasticity          prob;
  SgContact             c;
  SgContactView         cv;         /* the contact law; the contact vertices read once (SgContactGetVertices, ...): */
  PetscInt              n, nglobal; /* owned here, in all (0 without contact) */
  const PetscInt       *vert, *off; /* local vertex numbers, offsets of their first dofs in the local vector */
  const PetscReal      *w, *normal; /* boundary weights, outward unit normals (n*dim) */
  const PetscReal      *d;          /* gaps to the obstacle along the normals */
  PetscReal             area;       /* |Gamma_c| */
  KSP                   ksp;        /* the linear solver of every step (-<prefix>ksp_*, -<prefix>pc_*) */
  Mat                   J;          /* its working matrix */
  SgSSN                 ssn;        /* NULL for the baselines */
  PetscReal            *lamhat;     /* the SSN's shift (NULL without SSN) */
  Vec                   y;          /* the iterate, finally the solution */
  PetscReal            *lam;        /* the multiplier at y */
  PetscReal             kkt_tol;
  PetscReal             gamma;     /* gamma of the next outer step */
  PetscBool             restarted; /* the state comes from -restart_file */
  char                  ckfile[PETSC_MAX_PATH_LEN], rsfile[PETSC_MAX_PATH_LEN];
  PetscInt              max_outer, stall_its;
  PetscReal             gamma_max;
  PetscBool             gamma_max_set; /* -cont_gamma_max given; else 1e14 x the normal stiffness per contact area (SgContStart) */
  PetscReal             best_kkt;      /* progress watch */
  PetscInt              best_step;
  Vec                   ybest;           /* the iterate of least KKT residual of this solve, its multiplier, residual and step */
  Vec                   ystart;          /* Coulomb: the iterate this solve started from (for CoulombShiftedPath) */
  PetscBool             coulomb_shifted; /* Coulomb: after a failed SSN, solve again on the shifted path (-cont_coulomb_shifted_path) */
  PetscReal            *lambest;
  PetscReal             kktbest;
  PetscInt              outerbest;
  PetscInt              outer, ssn_its, ksp_its;
  PetscInt              ngammas, capgammas;
  PetscReal            *gammas; /* gamma of every outer step */
  PetscBool             setfromoptions_called, setup, solved;
  PetscBool             setup_failed; /* SgContSetFromOptions or SgContSetUp stopped with an error: not used again */
  PetscBool             converged;    /* the problem named by `problem` was solved to -cont_kkt_tol */
  char                  reason[512];
  const char           *problem;  /* what the run solves: "P" (contact), "P_gamma" (one regularized problem), "elasticity" */
  PetscReal             residual; /* the measure of that problem: the KKT residual of (P), the equilibrium residual of (P_gamma) or the backward error of K y = b */
  SgKKT                 kkt;
  PetscReal             V0, V;                          /* energy of the unconstrained solution and of the result */
  PetscLogDouble        t_linear_setup, t_linear_solve; /* the unconstrained solve: preconditioner setup and solve */
  SgHistory             hist;
  SgSummary             sum; /* what the solver adds to the summary beside the standard keys (report.c) */
  PetscLogDouble        t0, t1;
  void                 *data;
  SgContOps             ops;
  /* load stepping: SgContSolve called again after SgProblemSetLoadFactor */
  PetscBool   warm;       /* this solve starts from the last load step's solution and controller state */
  PetscBool   have_state; /* a load step was solved (or restored from a checkpoint taken between load steps) */
  PetscBool   rsread;     /* -restart_file was read */
  PetscBool   yref_read;  /* the next load step's slip reference came from a step-end -restart_file */
  PetscReal   gamma_warm; /* the last gamma solved at: the warm start's first */
  PetscReal   V0unit;     /* V(0) / t^2 (the unconstrained solution is linear in the load factor t) */
  PetscReal   rsload;     /* the load factor of -restart_file's state */
  PetscInt    nsteps, capsteps;
  SgLoadStep *steps;
  PetscBool   store_steps; /* keep each step's y and lam for the fields (SgContSetStoreSteps) */
  Vec        *ysteps;
  PetscReal **lamsteps;
  PetscReal **yrsteps; /* capsteps: with friction, each kept step's slip reference (dim per contact vertex) */
  PetscInt    ndv;     /* Dirichlet values per step (dim per Dirichlet id) */
  PetscReal  *dvsteps; /* capsteps x ndv: each step's Dirichlet values when they were set (SgProblemSetDirichletValues),
                                NaN rows for steps without; NULL while none was set */
  /* friction: the state of this controller's solves, not the problem's (another controller on the same problem has its
     own): the slip reference of its load step (2 n dim: of the unknowns, then of the full displacement; 0 until its first load step ends), copied into
     the contact object's working array before each use (SgContUseSlipReference), and the friction summary of its last
     KKT measures */
  PetscReal        *yref;
  SgFrictionSummary fsum;
  /* nested iteration (cont/nested.c): the first solve of the run starts from the solution of the same problem on
     coarser meshes (the fine one refined -cont_nested times fewer), interpolated, with the coarse controller's last
     gamma and shift */
  PetscInt       nested;                         /* -cont_nested: coarse levels (0: none) */
  PetscBool      nested_inner;                   /* the controller of a coarse level: -cont_nested is not read */
  PetscBool      nested_default;                 /* ct->nested is the default of -dm_refine (SgContNestedDefault) */
  PetscBool      nested_start;                   /* this solve starts from a coarser level (y, nested_lamhat, gamma_warm, V0unit) */
  PetscReal     *nested_lamhat;                  /* the interpolated shift: n, then with friction the tangential one, n dim */
  PetscInt       nested_done;                    /* coarse levels solved */
  PetscInt       nested_ssn_its, nested_ksp_its; /* their SSN steps and linear iterations */
  PetscLogDouble nested_time;                    /* their time, set-up included */
  PetscReal      nested_rim;                     /* -cont_nested_rim: the rim test's factor of n^T K_ii n / w_i (0: off) */
  PetscInt       nested_rim_added;               /* contact vertices the rim test moved onto the obstacle (PlaceRim) */
  PetscBool      nested_stage;                   /* the finest level's log stage is pushed (SgContNestedStart), popped after its solve */
};

extern PetscFunctionList SgContList;
PetscErrorCode           SgContStart(SgCont, PetscBool *);
PetscErrorCode           SgContNormalStiffness(SgCont, PetscReal[]);
PetscErrorCode           SgContSSN(SgCont, PetscReal, PetscBool *);
PetscErrorCode           SgContMeasure(SgCont);
PetscErrorCode           SgContUseSlipReference(SgCont);
PetscErrorCode           SgContAddGamma(SgCont, PetscReal);
PetscErrorCode           SgContFail(SgCont, const char[], ...);
PetscErrorCode           SgContOuterRow(SgCont, PetscInt, const SgHistoryRow *);
PetscErrorCode           SgContCheck(SgCont, PetscBool *);
PetscErrorCode           SgContKeepBest(SgCont);    /* the iterate of least KKT residual of this solve, kept (cont_loop.c) ... */
PetscErrorCode           SgContRestoreBest(SgCont); /* ... and made the result of a failed solve when it is better */
PetscErrorCode           SgContCheckBaseline(SgCont);
PetscErrorCode           SgContSolveContinuation(SgCont);                                                       /* cont_loop.c: the outer loop of the types without ops->solve */
PetscErrorCode           SgContBoundFrame(SgCont, const char[], PetscBool, SgFrame *, PetscInt[], PetscReal[]); /* pdas.c: the contact frames of pdas and vi */
PetscErrorCode           SgContCheckpointWrite(SgCont);
PetscErrorCode           SgContCheckpointWriteStepEnd(SgCont);
PetscErrorCode           SgContCheckpointRead(SgCont);
PetscErrorCode           SgContSaveState(SgCont, SgCheckpointWriter, PetscInt, const char *const[], const PetscReal[]);
PetscErrorCode           SgContLoadState(SgCont, SgCheckpointReader, PetscInt, const char *const[], PetscReal[]);
const char              *SgContVerdict(SgCont);
PetscBool                SgModelFit(PetscReal, PetscReal, PetscReal, PetscReal, PetscReal *, PetscReal *, PetscReal *);
PetscBool                SgContGammaCap(SgCont, PetscReal, PetscReal *);
#define ValidCont(ct, arg) PetscCall(SgValidCont(ct, PETSC_FUNCTION_NAME, arg))
PetscErrorCode SgContGammaPrecision(SgCont, PetscReal *);
/* gamma at the double-precision cap gdp of SgContGammaPrecision: within 1e-3 below it (the cap is computed again from
   each iterate, a step taken at the cap finds it moved a little) */
static inline PetscBool SgContAtGammaPrecision(PetscReal gamma, PetscReal gdp)
{
  return (PetscBool)(gamma >= 0.999 * gdp);
}
PetscErrorCode SgContCreate_None(SgCont);
PetscErrorCode SgContCreate_ALM(SgCont);
PetscErrorCode SgContCreate_PF(SgCont);
PetscErrorCode SgContCreate_IPF(SgCont);
PetscErrorCode SgContCreate_Fast(SgCont);
PetscErrorCode SgContCreate_PDAS(SgCont);
PetscErrorCode SgContCreate_VI(SgCont);
PetscErrorCode SgContNestedCheck(SgCont);              /* nested.c: -cont_nested against the problem (SgContSetFromOptions) */
PetscErrorCode SgContNestedDefault(SgCont, PetscBool); /* nested.c: the default of -cont_nested with -dm_refine (SgContSetFromOptions) */
PetscErrorCode SgContNestedStart(SgCont);              /* nested.c: solve the coarse levels, start this solve from them */
PetscErrorCode SgContNestedResume(SgCont);             /* nested.c: after the type's start, the coarse level's gamma and shift */
