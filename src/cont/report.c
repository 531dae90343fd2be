/* cont/report.c: what a solve reports, apart from solving: the ASCII view, the JSON summary, the CSV history and the
   HDF5/XDMF fields of the result. */
#include "cont/contimpl.h"
#include <sys/resource.h>

static PetscErrorCode SummaryLoadSteps(SgCont, SgSummary);

/* Path data per outer step (the history's outer rows) as summary arrays path_<quantity>. */
static PetscErrorCode SummaryPath(SgCont ct, SgSummary sum)
{
  const char   *names[] = {"path_gamma", "path_V", "path_dVdgamma", "path_C1", "path_C2", "path_E", "path_ssn_iterations", "path_rho_F", "path_rho_C", "path_infeasibility", "path_kkt_residual"};
  PetscInt      n       = 0, nrows;
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
  PetscBool     factor, shell;

  PetscFunctionBeginUser;
  PetscCall(KSPGetType(ct->ksp, &kt));
  PetscCall(KSPGetPC(ct->ksp, &pc));
  PetscCall(PCGetType(pc, &pt));
  PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &factor, PCLU, PCCHOLESKY, ""));
  if (factor) PetscCall(PCFactorGetMatSolverType(pc, &st));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCSHELL, &shell));
  if (shell) PetscCall(PCShellGetName(pc, &st)); /* the SSN's condensed solve (-ssn_condense) */
  PetscCall(PetscSNPrintf(name, len, "%s + %s%s%s%s", kt ? kt : "(unset)", pt ? pt : "(unset)", st ? " (" : "", st ? st : "", st ? ")" : ""));
  PetscFunctionReturn(0);
}

/* Two bodies (a contact pair): the number of bodies of the mesh and the forces of the pair (SgContactPairForces) */
/* the summary as the law's key writer (the law names its keys, SgContactLawSummary) */
static PetscErrorCode KeyInt(void *ctx, const char key[], PetscInt v)
{
  PetscFunctionBeginUser;
  PetscCall(SgSummarySetInt((SgSummary)ctx, key, v));
  PetscFunctionReturn(0);
}

static PetscErrorCode KeyReal(void *ctx, const char key[], PetscReal v)
{
  PetscFunctionBeginUser;
  PetscCall(SgSummarySetReal((SgSummary)ctx, key, v));
  PetscFunctionReturn(0);
}

static PetscErrorCode KeyIntArray(void *ctx, const char key[], PetscInt n, const PetscInt v[])
{
  PetscFunctionBeginUser;
  PetscCall(SgSummarySetIntArray((SgSummary)ctx, key, n, v));
  PetscFunctionReturn(0);
}

static PetscErrorCode KeyRealArray(void *ctx, const char key[], PetscInt n, const PetscReal v[])
{
  PetscFunctionBeginUser;
  PetscCall(SgSummarySetRealArray((SgSummary)ctx, key, n, v));
  PetscFunctionReturn(0);
}

static PetscErrorCode SummaryLawKeys(SgSummary sum, SgContactLawKeys *keys)
{
  PetscFunctionBeginUser;
  keys->ctx          = sum;
  keys->setint       = KeyInt;
  keys->setreal      = KeyReal;
  keys->setintarray  = KeyIntArray;
  keys->setrealarray = KeyRealArray;
  PetscFunctionReturn(0);
}

static PetscErrorCode SummaryPair(SgCont ct, SgSummary sum, PetscInt dim)
{
  PetscBool pair;
  PetscReal fn, Fs[3], Fm[3], bal = 0, mag = 0;
  PetscInt  nb;

  PetscFunctionBeginUser;
  PetscCall(SgContactIsPair(ct->c, &pair));
  if (!pair) PetscFunctionReturn(0);
  PetscCall(SgElasticityBodyField(ct->prob, NULL, &nb));
  PetscCall(SgContactPairForces(ct->c, ct->y, &fn, Fs, Fm));
  for (PetscInt k = 0; k < dim; k++) {
    bal += PetscSqr(Fs[k] + Fm[k]);
    mag += PetscSqr(Fs[k]);
  }
  PetscCall(SgSummarySetInt(sum, "bodies", nb));
  PetscCall(SgSummarySetReal(sum, "pair_force", fn));
  PetscCall(SgSummarySetRealArray(sum, "pair_force_slave", dim, Fs));
  PetscCall(SgSummarySetRealArray(sum, "pair_force_master", dim, Fm));
  PetscCall(SgSummarySetReal(sum, "pair_force_balance", mag > 0 ? PetscSqrtReal(bal / mag) : 0));
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
    const char      *obstype;
    SgContactLawKeys keys;
    PetscCall(SgSummarySetInt(sum, "ssn_iterations", ct->ssn_its));
    PetscCall(SgSummarySetInt(sum, "outer_iterations", ct->outer));
    PetscCall(SgSummarySetRealArray(sum, "gammas", ct->ngammas, ct->gammas));
    PetscCall(SgSummarySetReal(sum, "gamma_max", ct->gamma_max));
    PetscCall(SgSummarySetReal(sum, "kkt_residual", ct->kkt.residual));
    PetscCall(SgSummarySetReal(sum, "infeasibility", ct->kkt.infeasibility));
    PetscCall(SgSummarySetReal(sum, "complementarity", ct->kkt.complementarity));
    PetscCall(SgSummarySetReal(sum, "equilibrium", ct->kkt.equilibrium));
    PetscCall(SgSummarySetReal(sum, "dual_infeasibility", ct->kkt.dual));
    PetscCall(SgSummarySetReal(sum, "penetration", ct->kkt.penetration));
    PetscCall(SgSummarySetReal(sum, "displacement_scale", ct->kkt.uscale));
    PetscCall(SgSummarySetReal(sum, "force_scale", ct->kkt.fscale));
    PetscCall(SgSummarySetReal(sum, "kkt_roundoff", ct->kkt.roundoff));
    PetscCall(SgSummarySetReal(sum, "force_balance", ct->kkt.balance));
    PetscCall(SgSummarySetReal(sum, "rho_F", ct->kkt.rhoF));
    PetscCall(SgSummarySetReal(sum, "rho_C", ct->kkt.rhoC));
    PetscCall(SgSummarySetInt(sum, "active_set_size", ct->kkt.nactive));
    PetscCall(SgSummarySetReal(sum, "contact_force", ct->kkt.force));
    PetscCall(SgSummarySetInt(sum, "contact_vertices", ct->nglobal));
    PetscCall(SgSummarySetReal(sum, "contact_area", ct->area));
    PetscCall(SgContactGetObstacleType(ct->c, &obstype));
    PetscCall(SgSummarySetString(sum, "obstacle", obstype));
    PetscCall(SgContactGetNormalType(ct->c, &obstype));
    PetscCall(SgSummarySetString(sum, "contact_normal", obstype));
    PetscCall(SgSummarySetString(sum, "friction_type", SgLawName(ct->cv.law)));
    PetscCall(SummaryLawKeys(sum, &keys));
    PetscCall(SgContactLawSummary(ct->cv.law, dim, &ct->fsum, &keys)); /* the law's keys, of this controller's last KKT measures (SgContMeasure) */
    {
      /* the contact force on the body, sum_i w_i lam_i n_i, with the multiplier of contact_force (SgContactKKT's),
         against the reaction */
      PetscReal F[3] = {0, 0, 0}, R[3];
      PetscCall(SgContactForceVector(ct->c, ct->y, F));
      PetscCall(SgElasticityReaction(ct->prob, ct->y, R));
      PetscCall(SgSummarySetRealArray(sum, "contact_force_vector", dim, F));
      PetscCall(SgSummarySetRealArray(sum, "reaction_force", dim, R));
    }
    PetscCall(SummaryPair(ct, sum, dim));
    PetscCall(SummaryPath(ct, sum));
  }
  PetscCall(SummaryLoadSteps(ct, sum));
  PetscCallMPI(MPI_Comm_size(ct->comm, &size));
  PetscCall(SgElasticityGetInfo(ct->prob, &ndofs, &ncells, &mms, &t_assembly));
  PetscCall(SgElasticityGetMaterial(ct->prob, &E, &nu));
  PetscCall(SgSummarySetInt(sum, "dofs", ndofs));
  PetscCall(SgSummarySetInt(sum, "ranks", size));
  PetscCall(SgSummarySetInt(sum, "dim", dim));
  PetscCall(SgSummarySetInt(sum, "cells", ncells));
  PetscCall(SgSummarySetReal(sum, "E", E));
  PetscCall(SgSummarySetReal(sum, "nu", nu));
  { /* several materials (E, nu above: the stiffest) */
    const char      *label;
    PetscInt         nmat;
    const PetscInt  *ids;
    const PetscReal *Em, *num;
    PetscCall(SgElasticityGetMaterials(ct->prob, &label, &nmat, &ids, &Em, &num));
    if (nmat > 0) {
      PetscCall(SgSummarySetString(sum, "material_label", label));
      PetscCall(SgSummarySetIntArray(sum, "material_ids", nmat, ids));
      PetscCall(SgSummarySetRealArray(sum, "material_E", nmat, Em));
      PetscCall(SgSummarySetRealArray(sum, "material_nu", nmat, num));
    }
  }
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
  ValidCont(ct, 1);
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
  ValidCont(ct, 1);
  ierr = SgHistoryWrite(ct->comm, ct->hist, "-history_file", file ? file : "");
  PetscCall(NoteError(ct, "history_error", ierr));
  PetscCall(ierr);
  PetscFunctionReturn(0);
}

/* Two bodies (a contact pair): the vertex field master_pressure (the slave's contact pressure projected on the
   master side: SgContactPairMasterPressure) after the others, and the cell field body (SgElasticityBodyField) */
static PetscErrorCode PairFieldsCreate(SgElasticity p, PetscInt *nv, Vec vf[], PetscInt *nc, Vec cf[])
{
  DM dmCell, dmVert;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetDMs(p, NULL, &dmVert, NULL, &dmCell));
  PetscCall(DMCreateGlobalVector(dmVert, &vf[*nv]));
  PetscCall(PetscObjectSetName((PetscObject)vf[*nv], "master_pressure"));
  (*nv)++;
  PetscCall(DMCreateGlobalVector(dmCell, &cf[*nc]));
  PetscCall(PetscObjectSetName((PetscObject)cf[*nc], "body"));
  (*nc)++;
  PetscFunctionReturn(0);
}

/* the pair's fields of PairFieldsCreate at y: the last of the nv vertex fields and the third cell field (none without
   a pair) */
static PetscErrorCode PairFieldsFill(SgCont ct, Vec y, PetscInt nv, Vec vf[], Vec cf[])
{
  PetscBool pair = PETSC_FALSE;

  PetscFunctionBeginUser;
  if (ct->c) PetscCall(SgContactIsPair(ct->c, &pair));
  if (!pair) PetscFunctionReturn(0);
  PetscCall(SgContactPairMasterPressure(ct->c, y, vf[nv - 1]));
  PetscCall(SgElasticityBodyField(ct->prob, cf[2], NULL));
  PetscFunctionReturn(0);
}

/* The work vectors of the fields: vf displacement and (with contact) the contact fields, cf the cell fields */
static PetscErrorCode FieldsCreate(SgCont ct, PetscInt *nv, Vec vf[7 + SG_LAW_MAX_FIELDS], PetscInt *nc, Vec cf[3])
{
  SgElasticity p = ct->prob;
  PetscInt     dim;
  DM           dmVec, dmCell, dmVert;
  const char  *cnames[2] = {"von_mises", "shear_energy_density"}, *vnames[4] = {"contact_pressure", "gap", "penetration", "active"};

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetDimension(p, &dim));
  PetscCall(SgElasticityGetDMs(p, NULL, &dmVert, &dmVec, &dmCell));
  PetscCall(DMCreateGlobalVector(dmVec, &vf[0]));
  PetscCall(PetscObjectSetName((PetscObject)vf[0], "displacement"));
  PetscCall(VecSetBlockSize(vf[0], dim));
  for (PetscInt i = 0; i < 2; i++) {
    PetscCall(DMCreateGlobalVector(dmCell, &cf[i]));
    PetscCall(PetscObjectSetName((PetscObject)cf[i], cnames[i]));
  }
  *nv = 1;
  if (ct->c) {
    for (PetscInt i = 0; i < 4; i++) {
      PetscCall(DMCreateGlobalVector(dmVert, &vf[1 + i]));
      PetscCall(PetscObjectSetName((PetscObject)vf[1 + i], vnames[i]));
    }
    PetscCall(DMCreateGlobalVector(dmVec, &vf[5]));
    PetscCall(PetscObjectSetName((PetscObject)vf[5], "obstacle_offset"));
    PetscCall(VecSetBlockSize(vf[5], dim));
    *nv = 6;
    { /* the law's fields (friction: tangential traction, slip, and the state 0 free, 1 stick, 2 slip) */
      PetscInt           nl;
      const char *const *names;
      const PetscBool   *vector;
      PetscCall(SgContactLawGetFields(ct->cv.law, &nl, &names, &vector));
      for (PetscInt k = 0; k < nl; k++) {
        PetscCall(DMCreateGlobalVector(vector[k] ? dmVec : dmVert, &vf[6 + k]));
        PetscCall(PetscObjectSetName((PetscObject)vf[6 + k], names[k]));
        if (vector[k]) PetscCall(VecSetBlockSize(vf[6 + k], dim));
      }
      *nv = 6 + nl;
    }
  }
  *nc = 2;
  {
    PetscBool pair = PETSC_FALSE;
    if (ct->c) PetscCall(SgContactIsPair(ct->c, &pair));
    if (pair) PetscCall(PairFieldsCreate(p, nv, vf, nc, cf));
  }
  PetscFunctionReturn(0);
}

/* the fields of the displacement y with the multiplier lam, at the problem's current load factor */
static PetscErrorCode FieldsFill(SgCont ct, Vec y, const PetscReal lam[], PetscInt nv, Vec vf[], Vec cf[])
{
  PetscFunctionBeginUser;
  PetscCall(SgElasticityFullDisplacement(ct->prob, y, vf[0]));
  PetscCall(SgElasticityCellFields(ct->prob, y, cf[0], cf[1]));
  if (ct->c) PetscCall(SgContactFields(ct->c, y, lam, &vf[1], vf[5]));
  if (ct->c) PetscCall(SgContactLawFields(ct->c, y, &vf[6])); /* the law's (none without friction) */
  PetscCall(PairFieldsFill(ct, y, nv, vf, cf));
  PetscFunctionReturn(0);
}

typedef struct {
  SgCont          ct;
  const PetscInt *idx; /* the kept load steps */
} StepsCtx;

static PetscErrorCode FillStep(void *vctx, PetscInt k, PetscInt nv, Vec vf[], PetscInt nc, Vec cf[])
{
  StepsCtx *sc = (StepsCtx *)vctx;
  SgCont    ct = sc->ct;
  PetscInt  j  = sc->idx[k];

  PetscFunctionBeginUser;
  PetscCall(SgProblemSetLoadFactor(ct->problem_obj, ct->steps[j].t));
  if (ct->dvsteps) PetscCall(SgProblemSetDirichletValues(ct->problem_obj, PetscIsNanReal(ct->dvsteps[j * ct->ndv]) ? NULL : &ct->dvsteps[j * ct->ndv]));
  /* the law's slip reference (none without friction): the step's slip is the increment from its reference (kept
     with it, or the step before's solution) */
  if (ct->c) {
    if (ct->yrsteps && ct->yrsteps[j]) {
      PetscReal *yref;
      PetscInt   m;
      PetscCall(SgContactGetSlipReference(ct->c, &yref));
      PetscCall(SgContactLawGetSlipReferenceSize(ct->cv.law, &m));
      PetscCall(PetscArraycpy(yref, ct->yrsteps[j], m));
    } else PetscCall(SgContactSetSlipReference(ct->c, j > 0 ? ct->ysteps[j - 1] : NULL));
  }
  PetscCall(FieldsFill(ct, ct->ysteps[j], ct->lamsteps[j], nv, vf, cf));
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteFields(SgCont ct, const char file[], PetscReal magnification)
{
  Vec       vf[7 + SG_LAW_MAX_FIELDS], cf[3]; /* 6 of the contact, the law's, the pair's */
  PetscInt  nv = 0, nc = 2, nkept = 0;
  PetscBool loadsteps;

  PetscFunctionBeginUser;
  PetscCall(SgContUseSlipReference(ct)); /* the slip of this controller's step, whoever solved the problem last */
  PetscCall(FieldsCreate(ct, &nv, vf, &nc, cf));
  PetscCall(SgProblemHasLoadSteps(ct->problem_obj, &loadsteps));
  for (PetscInt k = 0; ct->ysteps && k < ct->nsteps; k++) nkept += ct->ysteps[k] ? 1 : 0;
  if (loadsteps && nkept) {
    /* a temporal collection of the kept load steps (time: the load factor), the problem's factor restored after */
    PetscInt  *idx, *num, m, my = 0;
    PetscReal *times, t, *dv = NULL, *yr = NULL;
    PetscBool  dset;
    StepsCtx   sc;
    PetscCall(SgProblemGetLoadFactor(ct->problem_obj, &t));
    if (ct->c) { /* the law's slip reference of the last step (none without friction), restored after */
      PetscReal *yref;
      PetscCall(SgContactGetSlipReference(ct->c, &yref));
      PetscCall(SgContactLawGetSlipReferenceSize(ct->cv.law, &my));
      PetscCall(PetscMalloc1(my + 1, &yr));
      PetscCall(PetscArraycpy(yr, yref, my));
    }
    PetscCall(SgElasticityGetDirichletSize(ct->prob, &m));
    PetscCall(PetscMalloc1(m + 1, &dv));
    PetscCall(SgElasticityGetDirichletValues(ct->prob, &dset, dv));
    PetscCall(PetscMalloc3(nkept, &idx, nkept, &num, nkept, &times));
    nkept = 0;
    for (PetscInt k = 0; k < ct->nsteps; k++)
      if (ct->ysteps[k]) {
        idx[nkept]   = k;
        num[nkept]   = k + 1;
        times[nkept] = ct->steps[k].t;
        nkept++;
      }
    sc.ct  = ct;
    sc.idx = idx;
    PetscCall(SgOutputWriteSteps(ct->prob, file, nkept, num, times, FillStep, &sc, nv, vf, nc, cf, magnification));
    PetscCall(SgProblemSetLoadFactor(ct->problem_obj, t));
    if (ct->dvsteps) PetscCall(SgProblemSetDirichletValues(ct->problem_obj, dset ? dv : NULL)); /* the problem's values restored too */
    if (yr) {
      PetscReal *yref;
      PetscCall(SgContactGetSlipReference(ct->c, &yref));
      PetscCall(PetscArraycpy(yref, yr, my));
      PetscCall(PetscFree(yr));
    }
    PetscCall(PetscFree(dv));
    PetscCall(PetscFree3(idx, num, times));
  } else {
    PetscCall(FieldsFill(ct, ct->y, ct->lam, nv, vf, cf));
    PetscCall(SgOutputWrite(ct->prob, file, nv, vf, nc, cf, magnification));
  }
  for (PetscInt i = 0; i < nv; i++) PetscCall(VecDestroy(&vf[i]));
  for (PetscInt i = 0; i < nc; i++) PetscCall(VecDestroy(&cf[i]));
  PetscFunctionReturn(0);
}

/* The load-displacement curve: a CSV row per load step (file "": none). */
PetscErrorCode SgContWriteLoadCurve(SgCont ct, const char file[])
{
  FILE          *fp;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  ValidCont(ct, 1);
  if (!file || !file[0]) PetscFunctionReturn(0);
  PetscCall(SgFileOpen(ct->comm, "-load_curve_file", file, &fp));
  if (fp) {
    fprintf(fp, "step,load_factor,obstacle_displacement,normal_displacement_max,contact_force,active,outer_iterations,ssn_iterations,ksp_iterations,kkt_residual,energy,converged,time\n");
    for (PetscInt k = 0; k < ct->nsteps; k++) {
      const SgLoadStep *r = &ct->steps[k];
      fprintf(fp, "%" PetscInt_FMT ",%.17g,%.17g,%.17g,%.17g,%" PetscInt_FMT ",%" PetscInt_FMT ",%" PetscInt_FMT ",%" PetscInt_FMT ",%.6e,%.17g,%d,%.6e\n", k + 1, (double)r->t, (double)r->obstacle_displacement, (double)r->normal_displacement_max, (double)r->force, r->nactive, r->outer, r->ssn_its, r->ksp_its, (double)r->kkt, (double)r->energy, (int)r->converged, (double)r->time);
    }
  }
  ierr = SgFileClose(ct->comm, file, &fp);
  PetscCall(NoteError(ct, "load_curve_error", ierr));
  PetscCall(ierr);
  PetscFunctionReturn(0);
}

/* Per load step arrays in the summary (only for a run with load steps: a run without keeps its summary). */
static PetscErrorCode SummaryLoadSteps(SgCont ct, SgSummary sum)
{
  PetscReal  *a[7];
  PetscInt   *b[5], tot[3] = {0, 0, 0};
  PetscBool   loadsteps;
  const char *rn[7] = {"load_factors", "load_step_obstacle_displacement", "load_step_normal_displacement_max", "load_step_contact_force", "load_step_kkt_residual", "load_step_energy", "load_step_time"};
  const char *in[5] = {"load_step_outer_iterations", "load_step_ssn_iterations", "load_step_ksp_iterations", "load_step_active_set_size", "load_step_converged"};

  PetscFunctionBeginUser;
  PetscCall(SgProblemHasLoadSteps(ct->problem_obj, &loadsteps));
  if (!loadsteps) PetscFunctionReturn(0);
  for (PetscInt j = 0; j < 7; j++) PetscCall(PetscMalloc1(ct->nsteps + 1, &a[j]));
  for (PetscInt j = 0; j < 5; j++) PetscCall(PetscMalloc1(ct->nsteps + 1, &b[j]));
  for (PetscInt k = 0; k < ct->nsteps; k++) {
    const SgLoadStep *r = &ct->steps[k];
    a[0][k]             = r->t;
    a[1][k]             = r->obstacle_displacement;
    a[2][k]             = r->normal_displacement_max;
    a[3][k]             = r->force;
    a[4][k]             = r->kkt;
    a[5][k]             = r->energy;
    a[6][k]             = r->time;
    b[0][k]             = r->outer;
    b[1][k]             = r->ssn_its;
    b[2][k]             = r->ksp_its;
    b[3][k]             = r->nactive;
    b[4][k]             = r->converged;
    tot[0] += r->outer;
    tot[1] += r->ssn_its;
    tot[2] += r->ksp_its;
  }
  PetscCall(SgSummarySetInt(sum, "load_steps", ct->nsteps));
  for (PetscInt j = 0; j < 7; j++) PetscCall(SgSummarySetRealArray(sum, rn[j], ct->nsteps, a[j]));
  for (PetscInt j = 0; j < 5; j++) PetscCall(SgSummarySetIntArray(sum, in[j], ct->nsteps, b[j]));
  if (ct->c) { /* the law's keys per step (friction: the stick and slip sets, the friction resultant and traction) */
    SgFrictionSummary *fs;
    SgContactLawKeys   keys;
    PetscCall(PetscCalloc1(ct->nsteps + 1, &fs));
    for (PetscInt k = 0; k < ct->nsteps; k++) {
      fs[k].nstick     = ct->steps[k].nstick;
      fs[k].nslip      = ct->steps[k].nslip;
      fs[k].force_norm = ct->steps[k].friction_force;
      fs[k].traction   = ct->steps[k].friction_traction;
    }
    PetscCall(SummaryLawKeys(sum, &keys));
    PetscCall(SgContactLawStepSummary(ct->cv.law, ct->nsteps, fs, &keys));
    PetscCall(PetscFree(fs));
  }
  PetscCall(SgSummarySetInt(sum, "load_steps_outer_iterations", tot[0]));
  PetscCall(SgSummarySetInt(sum, "load_steps_ssn_iterations", tot[1]));
  PetscCall(SgSummarySetInt(sum, "load_steps_ksp_iterations", tot[2]));
  for (PetscInt j = 0; j < 7; j++) PetscCall(PetscFree(a[j]));
  for (PetscInt j = 0; j < 5; j++) PetscCall(PetscFree(b[j]));
  PetscFunctionReturn(0);
}

/* The fields of the result for ParaView: file (.h5) and the .xmf beside it, with the displacement magnification stored
   for the pictures; written only for a converged solve (file "": none). */
PetscErrorCode SgContWriteFields(SgCont ct, const char file[], PetscReal magnification)
{
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  ValidCont(ct, 1);
  PetscCheck(PetscIsNormalReal(magnification) || magnification == 0, ct->comm, PETSC_ERR_ARG_OUTOFRANGE, "SgContWriteFields: the magnification must be finite, got %g", (double)magnification);
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
  ValidCont(ct, 1);
  if (viewer) SgValidHeaderSpecific(viewer, PETSC_VIEWER_CLASSID, "PetscViewer", 2);
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(ct->comm, &viewer));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  if (!isascii) PetscFunctionReturn(0);
  if (!ct->solved) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "SgCont %s%s%s%s: KKT tolerance %g, at most %" PetscInt_FMT " outer steps", ct->type, ct->type_default ? " (the default; -cont_type changes it)" : "", ((PetscObject)ct)->prefix ? " with prefix " : "", ((PetscObject)ct)->prefix ? ((PetscObject)ct)->prefix : "", (double)ct->kkt_tol, ct->max_outer));
    PetscCall(PetscViewerASCIIUseTabs(viewer, PETSC_FALSE)); /* the type's parameters continue the line */
    if (ct->ops.view) PetscCall(ct->ops.view(ct, viewer));
    PetscCall(PetscViewerASCIIPrintf(viewer, "\n"));
    PetscCall(PetscViewerASCIIUseTabs(viewer, PETSC_TRUE));
    if (ct->ksp) {
      char name[128];
      PetscCall(LinearSolverName(ct, name, sizeof(name)));
      PetscCall(PetscViewerASCIIPrintf(viewer, "  linear solver: %s, %s%s\n", name, ct->solver_desc, strcmp(ct->solver_desc, "from the options") ? "; -ksp_type, -pc_type or a file of options/solver/ change it" : ""));
    }
    if (ct->nested) PetscCall(PetscViewerASCIIPrintf(viewer, "  nested iteration: %" PetscInt_FMT " coarser level%s solved first (%s)\n", ct->nested, ct->nested > 1 ? "s" : "", ct->nested_default ? "the default with -dm_refine; -cont_nested 0 turns it off" : "-cont_nested"));
    PetscFunctionReturn(0);
  }
  if (ct->c) {
    char steps[160] = "";
    if (ct->nsteps > 1) { /* the counts are the last load step's: say so, and give the run's */
      PetscInt outer = 0, ssn = 0;
      for (PetscInt k = 0; k < ct->nsteps; k++) outer += ct->steps[k].outer, ssn += ct->steps[k].ssn_its;
      PetscCall(PetscSNPrintf(steps, sizeof(steps), " in load step %" PetscInt_FMT " (all %" PetscInt_FMT " load steps: %" PetscInt_FMT " outer, %" PetscInt_FMT " SSN iterations)", ct->nsteps, ct->nsteps, outer, ssn));
    }
    PetscCall(PetscViewerASCIIPrintf(viewer, "%s: %s. %s; %" PetscInt_FMT " outer, %" PetscInt_FMT " SSN iterations%s; KKT residual %.3e (infeasibility %.3e, complementarity %.3e, equilibrium %.3e); active %" PetscInt_FMT "/%" PetscInt_FMT " vertices; contact force %.6e; energy %.12e\n", ct->type, SgContVerdict(ct), ct->reason, ct->outer, ct->ssn_its, steps, (double)ct->kkt.residual,
                                     (double)ct->kkt.infeasibility, (double)ct->kkt.complementarity, (double)ct->kkt.equilibrium, ct->kkt.nactive, ct->nglobal, (double)ct->kkt.force, (double)ct->V));
  } else PetscCall(PetscViewerASCIIPrintf(viewer, "elasticity: %s; energy %.12e\n", ct->reason, (double)ct->V));
  PetscFunctionReturn(0);
}
