/* cont/report.c: what a solve reports, apart from solving: the ASCII view, the JSON summary, the CSV history and the
   HDF5/XDMF fields of the result. */
#include "cont/contimpl.h"
#include <sys/resource.h>

/* Path data per outer step (the history's outer rows) as summary arrays path_<quantity>. */
static PetscErrorCode SummaryPath(SgCont ct, SgSummary sum)
{
  const char   *names[] = {"path_gamma", "path_V", "path_dVdgamma", "path_C1", "path_C2", "path_E", "path_ssn_iterations", "path_rho_F", "path_rho_C", "path_infeasibility", "path_kkt_residual"};
  PetscInt      n = 0, nrows;
  PetscReal    *a[11];
  SgHistoryRow *rows;

  PetscFunctionBeginUser;
  PetscCall(SgHistoryGetRows(ct->hist, &nrows, &rows));
  for (PetscInt j = 0; j < 11; j++) PetscCall(PetscMalloc1(nrows + 1, &a[j]));
  for (PetscInt i = 0; i < nrows; i++) {
    const SgHistoryRow *r = &rows[i];
    if (r->kind != 'o') continue;
    a[0][n]  = r->gamma;
    a[1][n]  = r->V;
    a[2][n]  = r->dV;
    a[3][n]  = r->C1;
    a[4][n]  = r->C2;
    a[5][n]  = r->Em;
    a[6][n]  = r->ssn_its;
    a[7][n]  = r->rhoF;
    a[8][n]  = r->rhoC;
    a[9][n]  = r->infeas;
    a[10][n] = r->kkt;
    n++;
  }
  for (PetscInt j = 0; j < 11; j++) {
    PetscCall(SgSummarySetRealArray(sum, names[j], n, a[j]));
    PetscCall(PetscFree(a[j]));
  }
  PetscFunctionReturn(0);
}

/* "KSP type + PC type (factorization package)" of the controller's linear solver */
static PetscErrorCode LinearSolverName(SgCont ct, char name[], size_t len)
{
  KSPType       kt;
  PCType        pt;
  PC            pc;
  MatSolverType st = NULL;
  PetscBool     factor;

  PetscFunctionBeginUser;
  PetscCall(KSPGetType(ct->ksp, &kt));
  PetscCall(KSPGetPC(ct->ksp, &pc));
  PetscCall(PCGetType(pc, &pt));
  PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &factor, PCLU, PCCHOLESKY, ""));
  if (factor) PetscCall(PCFactorGetMatSolverType(pc, &st));
  PetscCall(PetscSNPrintf(name, len, "%s + %s%s%s%s", kt ? kt : "(unset)", pt ? pt : "(unset)", st ? " (" : "", st ? st : "", st ? ")" : ""));
  PetscFunctionReturn(0);
}

/* Every key of the summary: the run's result, the problem's data and sizes, times and memory. */
static PetscErrorCode SummaryFill(SgCont ct, SgSummary sum)
{
  PetscMPIInt    size;
  PetscInt       ndofs, ncells, dim;
  PetscBool      mms;
  PetscLogDouble t_assembly, t, tc;
  PetscReal      E, nu;

  PetscFunctionBeginUser;
  PetscCall(SgSummarySetString(sum, "cont_type", ct->type));
  PetscCall(SgSummarySetBool(sum, "cont_type_default", ct->type_default));
  if (ct->ksp) {
    char name[128];
    PetscCall(LinearSolverName(ct, name, sizeof(name)));
    PetscCall(SgSummarySetString(sum, "linear_solver", name));
    PetscCall(SgSummarySetString(sum, "linear_solver_choice", ct->solver_desc));
  }
  PetscCall(SgSummarySetBool(sum, "converged", ct->converged));
  PetscCall(SgSummarySetString(sum, "reason", ct->reason));
  PetscCall(SgSummarySetString(sum, "problem", ct->problem));
  PetscCall(SgSummarySetReal(sum, "residual", ct->residual));
  PetscCall(SgSummarySetReal(sum, "residual_tol", ct->kkt_tol));
  PetscCall(SgSummarySetReal(sum, "energy", ct->V));
  PetscCall(SgSummarySetReal(sum, "energy_unconstrained", ct->V0));
  PetscCall(SgSummarySetInt(sum, "ksp_iterations", ct->ksp_its));
  PetscCall(SgSummarySetReal(sum, "solve_time", ct->t1 - ct->t0));
  {
    PetscReal nrm[2];
    PetscCall(VecNorm(ct->y, NORM_2, &nrm[0]));
    PetscCall(VecNorm(ct->y, NORM_INFINITY, &nrm[1]));
    PetscCall(SgSummarySetReal(sum, "displacement_norm", nrm[0]));
    PetscCall(SgSummarySetReal(sum, "displacement_max", nrm[1]));
  }
  PetscCall(SgElasticityGetDimension(ct->prob, &dim));
  if (ct->c) {
    const char *obstype;
    PetscCall(SgSummarySetInt(sum, "ssn_iterations", ct->ssn_its));
    PetscCall(SgSummarySetInt(sum, "outer_iterations", ct->outer));
    PetscCall(SgSummarySetRealArray(sum, "gammas", ct->ngammas, ct->gammas));
    PetscCall(SgSummarySetReal(sum, "kkt_residual", ct->kkt.residual));
    PetscCall(SgSummarySetReal(sum, "infeasibility", ct->kkt.infeasibility));
    PetscCall(SgSummarySetReal(sum, "complementarity", ct->kkt.complementarity));
    PetscCall(SgSummarySetReal(sum, "equilibrium", ct->kkt.equilibrium));
    PetscCall(SgSummarySetReal(sum, "dual_infeasibility", ct->kkt.dual));
    PetscCall(SgSummarySetReal(sum, "penetration", ct->kkt.penetration));
    PetscCall(SgSummarySetReal(sum, "displacement_scale", ct->kkt.uscale));
    PetscCall(SgSummarySetReal(sum, "rho_F", ct->kkt.rhoF));
    PetscCall(SgSummarySetReal(sum, "rho_C", ct->kkt.rhoC));
    PetscCall(SgSummarySetInt(sum, "active_set_size", ct->kkt.nactive));
    PetscCall(SgSummarySetReal(sum, "contact_force", ct->kkt.force));
    PetscCall(SgSummarySetInt(sum, "contact_vertices", ct->cv.nglobal));
    PetscCall(SgSummarySetReal(sum, "contact_area", ct->cv.area));
    PetscCall(SgContactGetObstacleType(ct->c, &obstype));
    PetscCall(SgSummarySetString(sum, "obstacle", obstype));
    {
      /* the contact force on the body, sum_i w_i lam_i n_i, with the method's multiplier, against the reaction */
      PetscReal F[3] = {0, 0, 0}, R[3];
      for (PetscInt i = 0; i < ct->cv.n; i++)
        for (PetscInt d = 0; d < dim; d++) F[d] += ct->cv.w[i] * ct->lam[i] * ct->cv.normal[i * dim + d];
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, F, 3, MPIU_REAL, MPI_SUM, ct->comm));
      PetscCall(SgElasticityReaction(ct->prob, ct->y, R));
      PetscCall(SgSummarySetRealArray(sum, "contact_force_vector", dim, F));
      PetscCall(SgSummarySetRealArray(sum, "reaction_force", dim, R));
    }
    PetscCall(SummaryPath(ct, sum));
  }
  PetscCallMPI(MPI_Comm_size(ct->comm, &size));
  PetscCall(SgElasticityGetInfo(ct->prob, &ndofs, &ncells, &mms, &t_assembly));
  PetscCall(SgElasticityGetMaterial(ct->prob, &E, &nu));
  PetscCall(SgSummarySetInt(sum, "dofs", ndofs));
  PetscCall(SgSummarySetInt(sum, "ranks", size));
  PetscCall(SgSummarySetInt(sum, "dim", dim));
  PetscCall(SgSummarySetInt(sum, "cells", ncells));
  PetscCall(SgSummarySetReal(sum, "E", E));
  PetscCall(SgSummarySetReal(sum, "nu", nu));
  PetscCall(SgSummarySetReal(sum, "assembly_time", t_assembly));
  /* one linear elasticity solve with the same solver, in this run: the yardstick of the contact solve's cost */
  PetscCall(SgSummarySetReal(sum, "linear_setup_time", ct->t_linear_setup));
  PetscCall(SgSummarySetReal(sum, "linear_solve_time", ct->t_linear_setup + ct->t_linear_solve));
  {
    struct rusage ru;
    PetscReal     mb[2];
    getrusage(RUSAGE_SELF, &ru);
    mb[0] = mb[1] = ru.ru_maxrss / 1024.0; /* Linux: kilobytes */
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &mb[0], 1, MPIU_REAL, MPI_SUM, ct->comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &mb[1], 1, MPIU_REAL, MPI_MAX, ct->comm));
    PetscCall(SgSummarySetReal(sum, "peak_rss_mb", mb[0]));
    PetscCall(SgSummarySetReal(sum, "peak_rss_mb_max_rank", mb[1]));
  }
  if (mms) {
    PetscReal l2, h1;
    PetscCall(SgElasticityMMSErrors(ct->prob, ct->y, &l2, &h1));
    PetscCall(SgSummarySetReal(sum, "l2_error", l2));
    PetscCall(SgSummarySetReal(sum, "h1_error", h1));
  }
  /* since the problem was created: the library's part of the run */
  PetscCall(SgProblemGetCreationTime(ct->problem_obj, &tc));
  PetscCall(PetscTime(&t));
  PetscCall(SgSummarySetReal(sum, "wall_time", t - tc));
  PetscFunctionReturn(0);
}

/* The JSON summary of the solve (file "" : none); what the type and the earlier writes recorded (a failed history
   or field write) is kept in it. */
PetscErrorCode SgContWriteSummary(SgCont ct, const char file[])
{
  PetscFunctionBeginUser;
  PetscCheck(ct->solved, ct->comm, PETSC_ERR_ORDER, "SgContWriteSummary: call SgContSolve first");
  PetscCall(SummaryFill(ct, ct->sum));
  PetscCall(SgSummaryWrite(ct->comm, ct->sum, "-summary_file", file ? file : ""));
  PetscFunctionReturn(0);
}

/* A failed write of a result is recorded in the summary, which is still written; the error is returned. */
static PetscErrorCode NoteError(SgCont ct, const char key[], PetscErrorCode ierr)
{
  const char *text;
  char       *specific = NULL;

  PetscFunctionBeginUser;
  if (!ierr) PetscFunctionReturn(0);
  PetscCall(PetscErrorMessage(ierr, &text, &specific));
  PetscCall(SgSummarySetString(ct->sum, key, specific ? specific : text));
  PetscCall(SgSummarySetBool(ct->sum, "results_complete", PETSC_FALSE));
  PetscFunctionReturn(0);
}

/* The CSV history: one row per SSN iteration and per outer step (kept whatever happened; file "": none). */
PetscErrorCode SgContWriteHistory(SgCont ct, const char file[])
{
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  ierr = SgHistoryWrite(ct->comm, ct->hist, "-history_file", file ? file : "");
  PetscCall(NoteError(ct, "history_error", ierr));
  PetscCall(ierr);
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteFields(SgCont ct, const char file[], PetscReal magnification)
{
  SgElasticity p = ct->prob;
  Vec          vf[6], cf[2];
  PetscInt     nv = 1, dim;
  DM           dmVec, dmCell, dmVert;
  const char  *cnames[2] = {"von_mises", "shear_energy_density"}, *vnames[4] = {"contact_pressure", "gap", "penetration", "active"};

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetDimension(p, &dim));
  PetscCall(SgElasticityGetDMs(p, NULL, &dmVert, &dmVec, &dmCell));
  PetscCall(DMCreateGlobalVector(dmVec, &vf[0]));
  PetscCall(PetscObjectSetName((PetscObject)vf[0], "displacement"));
  PetscCall(VecSetBlockSize(vf[0], dim));
  PetscCall(SgElasticityFullDisplacement(p, ct->y, vf[0]));
  for (PetscInt i = 0; i < 2; i++) {
    PetscCall(DMCreateGlobalVector(dmCell, &cf[i]));
    PetscCall(PetscObjectSetName((PetscObject)cf[i], cnames[i]));
  }
  PetscCall(SgElasticityCellFields(p, ct->y, cf[0], cf[1]));
  if (ct->c) {
    for (PetscInt i = 0; i < 4; i++) {
      PetscCall(DMCreateGlobalVector(dmVert, &vf[1 + i]));
      PetscCall(PetscObjectSetName((PetscObject)vf[1 + i], vnames[i]));
    }
    PetscCall(DMCreateGlobalVector(dmVec, &vf[5]));
    PetscCall(PetscObjectSetName((PetscObject)vf[5], "obstacle_offset"));
    PetscCall(VecSetBlockSize(vf[5], dim));
    PetscCall(SgContactFields(ct->c, ct->y, ct->lam, &vf[1], vf[5]));
    nv = 6;
  }
  PetscCall(SgOutputWrite(p, file, nv, vf, 2, cf, magnification));
  for (PetscInt i = 0; i < nv; i++) PetscCall(VecDestroy(&vf[i]));
  for (PetscInt i = 0; i < 2; i++) PetscCall(VecDestroy(&cf[i]));
  PetscFunctionReturn(0);
}

/* The fields of the result for ParaView: file (.h5) and the .xmf beside it, with the displacement magnification stored
   for the pictures; written only for a converged solve (file "": none). */
PetscErrorCode SgContWriteFields(SgCont ct, const char file[], PetscReal magnification)
{
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  PetscCheck(ct->solved, ct->comm, PETSC_ERR_ORDER, "SgContWriteFields: call SgContSolve first");
  if (!ct->converged || !file || !file[0]) PetscFunctionReturn(0);
  ierr = WriteFields(ct, file, magnification);
  PetscCall(NoteError(ct, "output_error", ierr));
  PetscCall(ierr);
  PetscFunctionReturn(0);
}

/* ASCII: the type and tolerances, and after a solve the one-line result. */
PetscErrorCode SgContView(SgCont ct, PetscViewer viewer)
{
  PetscBool isascii;

  PetscFunctionBeginUser;
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(ct->comm, &viewer));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  if (!isascii) PetscFunctionReturn(0);
  if (!ct->solved) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "SgCont %s%s%s%s: KKT tolerance %g, at most %" PetscInt_FMT " outer steps\n", ct->type, ct->type_default ? " (the default; -cont_type changes it)" : "", ct->prefix ? " with prefix " : "", ct->prefix ? ct->prefix : "", (double)ct->kkt_tol, ct->max_outer));
    if (ct->ops.view) PetscCall(ct->ops.view(ct, viewer));
    if (ct->ksp) {
      char name[128];
      PetscCall(LinearSolverName(ct, name, sizeof(name)));
      PetscCall(PetscViewerASCIIPrintf(viewer, "  linear solver: %s, %s%s\n", name, ct->solver_desc, strcmp(ct->solver_desc, "from the options") ? "; -ksp_type, -pc_type or a file of options/solver/ change it" : ""));
    }
    PetscFunctionReturn(0);
  }
  if (ct->c) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "%s: %s. %s; %" PetscInt_FMT " outer, %" PetscInt_FMT " SSN iterations; KKT residual %.3e (infeasibility %.3e, complementarity %.3e, equilibrium %.3e); active %" PetscInt_FMT "/%" PetscInt_FMT " vertices; contact force %.6e; energy %.12e\n", ct->type, SgContVerdict(ct), ct->reason, ct->outer, ct->ssn_its, (double)ct->kkt.residual,
                                     (double)ct->kkt.infeasibility, (double)ct->kkt.complementarity, (double)ct->kkt.equilibrium, ct->kkt.nactive, ct->cv.nglobal, (double)ct->kkt.force, (double)ct->V));
  } else PetscCall(PetscViewerASCIIPrintf(viewer, "elasticity: %s; energy %.12e\n", ct->reason, (double)ct->V));
  PetscFunctionReturn(0);
}
