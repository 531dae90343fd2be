/* solver/linear.c: the default linear solver, chosen from the problem when the options name none.
   A problem file alone must solve: PETSc's own default (GMRES + ILU(0)) does not converge on elasticity of any size
   worth solving. Without -<prefix>ksp_type and -<prefix>pc_type the solver is
     - an exact sparse Cholesky factorization (MUMPS) in 2D, and in 3D up to -cont_direct_max_unknowns unknowns;
     - CG + BoomerAMG with the settings of options/solver/hypre_l1gs.opts (relative tolerance 1e-8) above that.
   The threshold is measured (bench/perf_notes.md, "Default controller and linear solver"): the size where the
   contact solve with CG + BoomerAMG becomes faster than with MUMPS on Example 2. Each default is entered into the
   options database only where the user gave no value, so every -ksp_* / -pc_* option or options file still wins. */
#include "sg.h"

/* the default of -cont_direct_max_unknowns: 3D problems up to this many unknowns are solved with MUMPS (see the header) */
#define SG_DIRECT_MAX_DOFS_3D 60000

static PetscErrorCode SetDefault(const char prefix[], const char name[], const char value[])
{
  char      opt[256];
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s%s", prefix ? prefix : "", name));
  PetscCall(PetscOptionsHasName(NULL, NULL, opt, &set));
  if (!set) PetscCall(PetscOptionsSetValue(NULL, opt, value));
  PetscFunctionReturn(0);
}

/* Enter the default solver's options unless -<prefix>ksp_type or -<prefix>pc_type is given; desc says what was chosen
   and why (for the run's first lines). */
PetscErrorCode SgLinearSolverDefaults(SgElasticity el, const char prefix[], char desc[], size_t len)
{
  char      opt[256];
  PetscBool kset, pset;
  PetscInt  dim, dofs;

  PetscInt  maxdirect = SG_DIRECT_MAX_DOFS_3D;
  MPI_Comm  comm;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetComm(el, &comm));
  PetscOptionsBegin(comm, prefix, "Default linear solver", NULL);
  PetscCall(SgOptionsIntValue(PetscOptionsObject, "-cont_direct_max_unknowns", "Without -ksp_type and -pc_type: 3D problems up to this many unknowns are solved with MUMPS, larger ones with CG + BoomerAMG (2D: always MUMPS)", &maxdirect, NULL));
  PetscOptionsEnd();
  PetscCheck(maxdirect >= 0, comm, PETSC_ERR_USER_INPUT, "-%scont_direct_max_unknowns: must be >= 0, got %" PetscInt_FMT, prefix ? prefix : "", maxdirect);
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%sksp_type", prefix ? prefix : ""));
  PetscCall(PetscOptionsHasName(NULL, NULL, opt, &kset));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%spc_type", prefix ? prefix : ""));
  PetscCall(PetscOptionsHasName(NULL, NULL, opt, &pset));
  if (kset || pset) {
    PetscCall(PetscSNPrintf(desc, len, "from the options"));
    PetscFunctionReturn(0);
  }
  PetscCall(SgElasticityGetDimension(el, &dim));
  PetscCall(SgElasticityGetInfo(el, &dofs, NULL, NULL, NULL));
  if (dim == 2 || dofs <= maxdirect) {
    PetscCall(SetDefault(prefix, "ksp_type", "preonly"));
    PetscCall(SetDefault(prefix, "pc_type", "cholesky"));
    PetscCall(SetDefault(prefix, "pc_factor_mat_solver_type", "mumps"));
    if (dim == 2) PetscCall(PetscSNPrintf(desc, len, "default for 2D: sparse Cholesky (MUMPS)"));
    else PetscCall(PetscSNPrintf(desc, len, "default for 3D up to %" PetscInt_FMT " unknowns (-cont_direct_max_unknowns): sparse Cholesky (MUMPS)", maxdirect));
  } else {
    PetscCall(SetDefault(prefix, "ksp_type", "cg"));
    PetscCall(SetDefault(prefix, "ksp_rtol", "1e-8"));
    PetscCall(SetDefault(prefix, "pc_type", "hypre"));
    PetscCall(SetDefault(prefix, "pc_hypre_type", "boomeramg"));
    PetscCall(SetDefault(prefix, "pc_hypre_boomeramg_strong_threshold", "0.5"));
    PetscCall(SetDefault(prefix, "pc_hypre_boomeramg_coarsen_type", "HMIS"));
    PetscCall(SetDefault(prefix, "pc_hypre_boomeramg_interp_type", "ext+i"));
    PetscCall(SetDefault(prefix, "pc_hypre_boomeramg_P_max", "4"));
    PetscCall(SetDefault(prefix, "pc_hypre_boomeramg_agg_nl", "1"));
    PetscCall(SetDefault(prefix, "pc_hypre_boomeramg_relax_type_down", "l1-Gauss-Seidel"));
    PetscCall(SetDefault(prefix, "pc_hypre_boomeramg_relax_type_up", "backward-l1-Gauss-Seidel"));
    PetscCall(PetscSNPrintf(desc, len, "default for 3D above %" PetscInt_FMT " unknowns (-cont_direct_max_unknowns): CG + BoomerAMG (options/solver/hypre_l1gs.opts)", maxdirect));
  }
  PetscFunctionReturn(0);
}
