/* main.c: driver: options, mesh and problem, contact, controller, output. */
#include "signorini.h"
#include <sys/resource.h>

static const char help[] = "Frictionless contact of a linear elastic body with a rigid obstacle, solved with the semismooth Newton,\n"
                           "augmented Lagrangian and path-following methods of G. Stadler (J. Comput. Appl. Math. 203, 2007).\n"
                           "See README.md for the options; options/ holds ready-made option files.\n\n";

typedef struct {
  char      outfile[PETSC_MAX_PATH_LEN], sumfile[PETSC_MAX_PATH_LEN], histfile[PETSC_MAX_PATH_LEN];
  PetscReal magnification;
} Output;

static PetscErrorCode OutputOptions(MPI_Comm comm, Output *o)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(o, sizeof(*o)));
  o->magnification = 20;
  PetscOptionsBegin(comm, NULL, "Output", NULL);
  PetscCall(PetscOptionsString("-output_file", "HDF5 result file (fields for ParaView; an .xmf file is written beside it)", NULL, o->outfile, o->outfile, sizeof(o->outfile), NULL));
  PetscCall(PetscOptionsString("-summary_file", "JSON summary of the run", NULL, o->sumfile, o->sumfile, sizeof(o->sumfile), NULL));
  PetscCall(PetscOptionsString("-history_file", "CSV history: one row per SSN iteration and per outer step", NULL, o->histfile, o->histfile, sizeof(o->histfile), NULL));
  PetscCall(PetscOptionsReal("-output_magnification", "Displacement magnification stored for the pictures", NULL, o->magnification, &o->magnification, NULL));
  PetscOptionsEnd();
  PetscCheck(PetscIsNormalReal(o->magnification) && o->magnification > 0, comm, PETSC_ERR_USER_INPUT, "-output_magnification: must be positive and finite, got %g", (double)o->magnification);
  /* refuse unwritable locations before any work is done */
  PetscCall(SgFileCheckWritable(comm, "-output_file", o->outfile));
  PetscCall(SgFileCheckWritable(comm, "-summary_file", o->sumfile));
  PetscCall(SgFileCheckWritable(comm, "-history_file", o->histfile));
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteFields(SgCont ct, const Output *o)
{
  SgProblem   p = ct->prob;
  Vec         vf[6], cf[2];
  PetscInt    nv = 1;
  const char *cnames[2] = {"von_mises", "shear_energy_density"}, *vnames[4] = {"contact_pressure", "gap", "penetration", "active"};

  PetscFunctionBeginUser;
  PetscCall(DMCreateGlobalVector(p->dmVec, &vf[0]));
  PetscCall(PetscObjectSetName((PetscObject)vf[0], "displacement"));
  PetscCall(VecSetBlockSize(vf[0], p->dim));
  PetscCall(SgProblemFullDisplacement(p, ct->y, vf[0]));
  for (PetscInt i = 0; i < 2; i++) {
    PetscCall(DMCreateGlobalVector(p->dmCell, &cf[i]));
    PetscCall(PetscObjectSetName((PetscObject)cf[i], cnames[i]));
  }
  PetscCall(SgProblemCellFields(p, ct->y, cf[0], cf[1]));
  if (ct->c) {
    for (PetscInt i = 0; i < 4; i++) {
      PetscCall(DMCreateGlobalVector(p->dmVert, &vf[1 + i]));
      PetscCall(PetscObjectSetName((PetscObject)vf[1 + i], vnames[i]));
    }
    PetscCall(DMCreateGlobalVector(p->dmVec, &vf[5]));
    PetscCall(PetscObjectSetName((PetscObject)vf[5], "obstacle_offset"));
    PetscCall(VecSetBlockSize(vf[5], p->dim));
    PetscCall(SgContactFields(ct->c, ct->y, ct->lam, &vf[1], vf[5]));
    nv = 6;
  }
  PetscCall(SgOutputWrite(p, o->outfile, nv, vf, 2, cf, o->magnification));
  for (PetscInt i = 0; i < nv; i++) PetscCall(VecDestroy(&vf[i]));
  for (PetscInt i = 0; i < 2; i++) PetscCall(VecDestroy(&cf[i]));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  MPI_Comm       comm;
  Output         out;
  SgProblem      prob;
  SgContact      contact;
  SgCont         cont;
  PetscLogDouble t0, t1;
  PetscBool      converged;
  PetscMPIInt    size;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  comm = PETSC_COMM_WORLD;
  PetscCall(PetscTime(&t0));
  PetscCall(SgRegisterAll());
  PetscCall(OutputOptions(comm, &out));
  PetscCall(SgProblemCreate(comm, &prob));
  PetscCall(SgContactCreate(prob, &contact));
  PetscCall(SgContCreate(prob, contact, &cont));
  PetscCall(SgContSolve(cont));
  converged = cont->converged;

  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(SgSummarySetInt(cont->sum, "dofs", prob->ndofs));
  PetscCall(SgSummarySetInt(cont->sum, "ranks", size));
  PetscCall(SgSummarySetInt(cont->sum, "dim", prob->dim));
  {
    PetscInt nc = prob->mesh.nc;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nc, 1, MPIU_INT, MPI_SUM, comm));
    PetscCall(SgSummarySetInt(cont->sum, "cells", nc));
  }
  PetscCall(SgSummarySetReal(cont->sum, "E", prob->E));
  PetscCall(SgSummarySetReal(cont->sum, "nu", prob->nu));
  PetscCall(SgSummarySetReal(cont->sum, "assembly_time", prob->t_assembly));
  /* one linear elasticity solve with the same solver, in this run: the yardstick of the contact solve's cost */
  PetscCall(SgSummarySetReal(cont->sum, "linear_setup_time", cont->ssn->t_linear_setup));
  PetscCall(SgSummarySetReal(cont->sum, "linear_solve_time", cont->ssn->t_linear_setup + cont->ssn->t_linear_solve));
  {
    struct rusage ru;
    PetscReal     mb[2];
    getrusage(RUSAGE_SELF, &ru);
    mb[0] = mb[1] = ru.ru_maxrss / 1024.0; /* Linux: kilobytes */
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &mb[0], 1, MPIU_REAL, MPI_SUM, comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &mb[1], 1, MPIU_REAL, MPI_MAX, comm));
    PetscCall(SgSummarySetReal(cont->sum, "peak_rss_mb", mb[0]));
    PetscCall(SgSummarySetReal(cont->sum, "peak_rss_mb_max_rank", mb[1]));
  }
  if (prob->mms) {
    PetscReal l2, h1;
    PetscCall(SgProblemMMSErrors(prob, cont->y, &l2, &h1));
    PetscCall(SgSummarySetReal(cont->sum, "l2_error", l2));
    PetscCall(SgSummarySetReal(cont->sum, "h1_error", h1));
  }
  /* the history is kept whatever happened; the fields only for a converged solve */
  PetscCall(SgHistoryWrite(comm, cont->hist, "-history_file", out.histfile));
  if (converged && out.outfile[0]) PetscCall(WriteFields(cont, &out));
  PetscCall(PetscTime(&t1));
  PetscCall(SgSummarySetReal(cont->sum, "wall_time", t1 - t0));
  PetscCall(SgSummaryWrite(comm, cont->sum, "-summary_file", out.sumfile));
  if (contact)
    PetscCall(PetscPrintf(comm, "%s: %s. %s; %" PetscInt_FMT " outer, %" PetscInt_FMT " SSN iterations; KKT residual %.3e (infeasibility %.3e, complementarity %.3e, equilibrium %.3e); active %" PetscInt_FMT "/%" PetscInt_FMT " vertices; contact force %.6e; energy %.12e\n", cont->type, SgContVerdict(cont), cont->reason, cont->outer, cont->ssn_its, (double)cont->kkt.residual, (double)cont->kkt.infeasibility, (double)cont->kkt.complementarity, (double)cont->kkt.equilibrium, cont->kkt.nactive, contact->nglobal, (double)cont->kkt.force, (double)cont->V));
  else PetscCall(PetscPrintf(comm, "elasticity: %s; energy %.12e\n", cont->reason, (double)cont->V));
  PetscCall(SgContDestroy(&cont));
  PetscCall(SgContactDestroy(&contact));
  PetscCall(SgProblemDestroy(&prob));
  PetscCall(PetscFinalize());
  return converged ? 0 : 3;
}
