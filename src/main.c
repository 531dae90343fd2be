/* main.c: driver: options, mesh and problem, solve, output. */
#include "signorini.h"

static const char help[] = "Frictionless contact of a linear elastic body with a rigid obstacle (Stadler 2007).\n";

int main(int argc, char **argv)
{
  SgProblem      prob;
  SgSummary      sum;
  KSP            ksp;
  Vec            y, u, vm, ws;
  char           outfile[PETSC_MAX_PATH_LEN] = "", sumfile[PETSC_MAX_PATH_LEN] = "";
  PetscReal      mag = 20, V;
  PetscInt       its;
  KSPConvergedReason reason;
  PetscLogDouble t0, t1;
  MPI_Comm       comm;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  comm = PETSC_COMM_WORLD;
  PetscCall(PetscTime(&t0));
  PetscCall(SgRegisterAll());
  PetscOptionsBegin(comm, NULL, "Output", NULL);
  PetscCall(PetscOptionsString("-output_file", "HDF5 result file (an .xmf file is written beside it)", NULL, outfile, outfile, sizeof(outfile), NULL));
  PetscCall(PetscOptionsString("-summary_file", "JSON summary of the run", NULL, sumfile, sumfile, sizeof(sumfile), NULL));
  PetscCall(PetscOptionsReal("-output_magnification", "Displacement magnification stored for the pictures", NULL, mag, &mag, NULL));
  PetscOptionsEnd();
  PetscCall(SgFileCheckWritable(comm, "-output_file", outfile));
  PetscCall(SgFileCheckWritable(comm, "-summary_file", sumfile));
  PetscCall(SgProblemCreate(comm, &prob));
  PetscCall(DMCreateGlobalVector(prob->dm, &y));
  PetscCall(KSPCreate(comm, &ksp));
  PetscCall(KSPSetOperators(ksp, prob->K, prob->K));
  PetscCall(KSPSetFromOptions(ksp));
  PetscCall(KSPSolve(ksp, prob->b, y));
  PetscCall(KSPGetIterationNumber(ksp, &its));
  PetscCall(KSPGetConvergedReason(ksp, &reason));
  PetscCall(SgProblemEnergy(prob, y, &V));
  PetscCall(PetscTime(&t1));
  PetscCall(SgSummaryCreate(&sum));
  PetscCall(SgSummarySetInt(sum, "dofs", prob->ndofs));
  PetscCall(SgSummarySetReal(sum, "energy", V));
  PetscCall(SgSummarySetInt(sum, "ksp_iterations", its));
  PetscCall(SgSummarySetReal(sum, "wall_time", t1 - t0));
  PetscCall(SgSummarySetBool(sum, "converged", reason > 0 ? PETSC_TRUE : PETSC_FALSE));
  PetscCall(SgSummarySetString(sum, "reason", KSPConvergedReasons[reason]));
  PetscCall(SgSummarySetReal(sum, "assembly_time", prob->t_assembly));
  if (prob->mms) {
    PetscReal l2, h1;
    PetscCall(SgProblemMMSErrors(prob, y, &l2, &h1));
    PetscCall(SgSummarySetReal(sum, "l2_error", l2));
    PetscCall(SgSummarySetReal(sum, "h1_error", h1));
  }
  PetscCall(DMCreateGlobalVector(prob->dmVec, &u));
  PetscCall(PetscObjectSetName((PetscObject)u, "displacement"));
  PetscCall(VecSetBlockSize(u, prob->dim));
  PetscCall(SgProblemFullDisplacement(prob, y, u));
  PetscCall(DMCreateGlobalVector(prob->dmCell, &vm));
  PetscCall(DMCreateGlobalVector(prob->dmCell, &ws));
  PetscCall(PetscObjectSetName((PetscObject)vm, "von_mises"));
  PetscCall(PetscObjectSetName((PetscObject)ws, "shear_energy_density"));
  PetscCall(SgProblemCellFields(prob, y, vm, ws));
  if (outfile[0]) {
    Vec cf[2] = {vm, ws};
    PetscCall(SgOutputWrite(prob, outfile, 1, &u, 2, cf, mag));
  }
  PetscCall(SgSummaryWrite(comm, sum, "-summary_file", sumfile));
  PetscCall(PetscPrintf(comm, "dofs %" PetscInt_FMT " energy %.12e ksp %" PetscInt_FMT " %s\n", prob->ndofs, (double)V, its, KSPConvergedReasons[reason]));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&vm));
  PetscCall(VecDestroy(&ws));
  PetscCall(VecDestroy(&y));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(SgSummaryDestroy(&sum));
  PetscCall(SgProblemDestroy(&prob));
  PetscCall(PetscFinalize());
  return 0;
}
