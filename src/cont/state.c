/* cont/state.c: a controller's checkpoint (-checkpoint_file) and its restart (-restart_file), each part saved and
   loaded by its owner, as PETSc's TSAdaptLoad reads the type name and then calls the type's load: the continuation's
   common state (Base), the type's own (ops->save, ops->load; SgContSaveState for its numbers between outer steps), the
   friction state (Friction) and the load steps (LoadSteps). The file, the problem's fingerprint and the matching of
   the vertices are io/checkpoint.c's. */
#include "cont/contimpl.h"

#define NREAL 3 /* gamma, V0, best KKT residual: the dataset "reals" */
static const char *IntNames[4] = {"outer", "ssn_iterations", "ksp_iterations", "best_step"};

/* ---- the type's numbers between outer steps: the dataset "state", named by the attribute "state_names" */
static PetscErrorCode StateNames(PetscInt n, const char *const names[], char s[], size_t len)
{
  PetscFunctionBeginUser;
  s[0] = 0;
  for (PetscInt i = 0; i < n; i++) {
    size_t l;
    PetscCall(PetscStrlen(s, &l));
    PetscCall(PetscSNPrintf(s + l, len - l, i ? ",%s" : "%s", names[i]));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SgContSaveState(SgCont ct, SgCheckpointWriter w, PetscInt n, const char *const names[], const PetscReal v[])
{
  char s[512];

  PetscFunctionBeginUser;
  PetscCall(StateNames(n, names, s, sizeof(s)));
  PetscCall(SgCheckpointWriterReals(w, "state", n, v));
  PetscCall(SgCheckpointWriterAttribute(w, "state_names", PETSC_STRING, s));
  PetscFunctionReturn(0);
}

/* the type's n numbers by their names: a file of another version of the type (other names) is refused */
PetscErrorCode SgContLoadState(SgCont ct, SgCheckpointReader r, PetscInt n, const char *const names[], PetscReal v[])
{
  char        s[512], was[512], f[PETSC_MAX_PATH_LEN], what[128];
  char       *fs = NULL;
  const char *file;
  PetscBool   same;
  PetscReal  *a;
  PetscInt    m;

  PetscFunctionBeginUser;
  PetscCall(StateNames(n, names, s, sizeof(s)));
  PetscCall(SgCheckpointReaderGetFile(r, &file));
  PetscCall(PetscStrncpy(f, file, sizeof(f)));
  PetscCall(SgCheckpointReaderAttribute(r, "state_names", PETSC_STRING, &fs));
  PetscCall(PetscStrcmp(fs, s, &same));
  PetscCall(PetscStrncpy(was, fs, sizeof(was)));
  PetscCall(PetscFree(fs));
  if (!same) PetscCall(SgCheckpointReaderAbandon(&r));
  PetscCheck(same, ct->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' holds the controller state (%s), -cont_type %s keeps (%s)", f, was, ct->type, s);
  PetscCall(SgCheckpointReaderReals(r, "state", -1, &m, &a));
  if (m != n) PetscCall(PetscFree(a));
  if (m != n) PetscCall(SgCheckpointReaderDamaged(&r, "the number of controller state values", m));
  for (PetscInt i = 0; i < n; i++) {
    if (!PetscIsNormalReal(a[i]) && a[i] != 0) {
      const PetscReal val = a[i];
      PetscCall(PetscFree(a));
      PetscCall(PetscSNPrintf(what, sizeof(what), "the controller state %s", names[i]));
      PetscCall(SgCheckpointReaderDamaged(&r, what, val));
    }
    v[i] = a[i];
  }
  PetscCall(PetscFree(a));
  PetscFunctionReturn(0);
}

/* ---- the continuation's common state: type name, counters, gamma, V(0), progress watch, path, history, y, lamhat */
static PetscErrorCode SaveBase(SgCont ct, SgCheckpointWriter w)
{
  const PetscReal reals[NREAL] = {ct->gamma, ct->V0, ct->best_kkt};
  const PetscInt  ints[4]      = {ct->outer, ct->ssn_its, ct->ksp_its, ct->best_step};

  PetscFunctionBeginUser;
  PetscCall(SgCheckpointWriterAttribute(w, "cont_type", PETSC_STRING, ct->type));
  for (PetscInt i = 0; i < 4; i++) PetscCall(SgCheckpointWriterAttribute(w, IntNames[i], PETSC_INT, &ints[i]));
  PetscCall(SgCheckpointWriterReals(w, "reals", NREAL, reals));
  PetscCall(SgCheckpointWriterReals(w, "gammas", ct->ngammas, ct->gammas));
  PetscCall(SgCheckpointWriterHistory(w, ct->hist));
  PetscCall(SgCheckpointWriterDisplacement(w, "displacement", ct->y, PETSC_TRUE));
  /* without SSN (pdas, vi): the multiplier, the next load step's start */
  PetscCall(SgCheckpointWriterContact(w, "lamhat", 1, ct->lamhat ? ct->lamhat : ct->lam));
  PetscFunctionReturn(0);
}

/* the type that wrote the file is this run's */
static PetscErrorCode LoadType(SgCont ct, SgCheckpointReader r)
{
  char       *type = NULL, was[64], f[PETSC_MAX_PATH_LEN];
  const char *file;
  PetscBool   same;

  PetscFunctionBeginUser;
  PetscCall(SgCheckpointReaderGetFile(r, &file));
  PetscCall(PetscStrncpy(f, file, sizeof(f)));
  PetscCall(SgCheckpointReaderAttribute(r, "cont_type", PETSC_STRING, &type));
  PetscCall(PetscStrcmp(type, ct->type, &same));
  PetscCall(PetscStrncpy(was, type, sizeof(was)));
  PetscCall(PetscFree(type));
  if (!same) PetscCall(SgCheckpointReaderAbandon(&r));
  PetscCheck(same, ct->comm, PETSC_ERR_USER_INPUT, "-restart_file: '%s' was written by -cont_type %s, this run has -cont_type %s", f, was, ct->type);
  PetscFunctionReturn(0);
}

/* the counters (a checkpoint is written after an outer step): above a quarter of PetscInt's range a count is damage
   (HDF5 saturates larger stored values), and adding the resumed run's iterations would overflow */
static PetscErrorCode LoadCounters(SgCont ct, SgCheckpointReader r, PetscInt ints[4])
{
  const PetscInt big  = PETSC_MAX_INT / 4;
  const char    *what = NULL, *file;
  PetscInt       val  = 0;
  char           f[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < 4; i++) PetscCall(SgCheckpointReaderAttribute(r, IntNames[i], PETSC_INT, &ints[i]));
  if (ints[0] < 1 || ints[0] > big) what = IntNames[0], val = ints[0];
  else if (ints[1] < 0 || ints[1] > big) what = IntNames[1], val = ints[1];
  else if (ints[2] < 0 || ints[2] > big) what = IntNames[2], val = ints[2];
  else if (ints[3] < 0 || ints[3] > ints[0]) what = IntNames[3], val = ints[3];
  if (!what) PetscFunctionReturn(0);
  PetscCall(SgCheckpointReaderGetFile(r, &file));
  PetscCall(PetscStrncpy(f, file, sizeof(f)));
  PetscCall(SgCheckpointReaderAbandon(&r));
  SETERRQ(ct->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is damaged: %s = %" PetscInt_FMT " is impossible (outer step %" PetscInt_FMT ")", f, what, val, ints[0]);
}

/* step_end: the file is the end of a load step (of a solver without gamma too: pdas and vi have none to check);
   loadsteps: written by a run with load steps, whose history holds every step's rows (their outer steps start anew) */
static PetscErrorCode LoadBase(SgCont ct, SgCheckpointReader r, PetscBool step_end, PetscBool loadsteps)
{
  PetscInt    ints[4], ng;
  PetscReal  *reals, *g;
  const char *what = NULL;
  PetscReal   val  = 0;

  PetscFunctionBeginUser;
  PetscCall(LoadCounters(ct, r, ints));
  PetscCall(SgCheckpointReaderReals(r, "reals", NREAL, NULL, &reals));
  PetscCall(SgCheckpointReaderReals(r, "gammas", -1, &ng, &g));
  if (!step_end && !(PetscIsNormalReal(reals[0]) && reals[0] > 0)) what = "gamma (must be positive)", val = reals[0];
  else if (!PetscIsNormalReal(reals[1]) && reals[1] != 0) what = "the unconstrained energy", val = reals[1];
  else if (!(PetscIsNormalReal(reals[2]) || reals[2] == 0) || !(reals[2] >= 0)) what = "the best KKT residual", val = reals[2];
  else if (ng != ints[0]) what = "the number of gammas (must be the number of outer steps)", val = ng;
  for (PetscInt i = 0; !what && !step_end && i < ng; i++)
    if (!(g[i] > 0)) what = "a gamma of the path (must be positive)", val = g[i];
  if (what) {
    PetscCall(PetscFree(reals));
    PetscCall(PetscFree(g));
    PetscCall(SgCheckpointReaderDamaged(&r, what, val));
  }
  PetscCall(SgCheckpointReaderHistory(r, loadsteps ? PETSC_MAX_INT : ints[0], ct->hist));
  PetscCall(SgCheckpointReaderDisplacement(r, "displacement", "a displacement", ct->y));
  /* a baseline's multiplier (no SSN) may lie a round-off below 0 */
  if (ct->lamhat) PetscCall(SgCheckpointReaderContact(r, "lamhat", 1, PETSC_TRUE, "a multiplier shift lamhat (must be >= 0)", ct->lamhat));
  else PetscCall(SgCheckpointReaderContact(r, "lamhat", 1, PETSC_FALSE, "a multiplier", ct->lam));
  ct->gamma     = reals[0];
  ct->V0        = reals[1];
  ct->best_kkt  = reals[2];
  ct->outer     = ints[0];
  ct->ssn_its   = ints[1];
  ct->ksp_its   = ints[2];
  ct->best_step = ints[3];
  ct->ngammas   = 0;
  for (PetscInt i = 0; i < ng; i++) PetscCall(SgContAddGamma(ct, g[i]));
  PetscCall(PetscFree(reals));
  PetscCall(PetscFree(g));
  PetscFunctionReturn(0);
}

/* ---- the friction state: the law and its parameters (the contact object's: compared on reading), the tangential
   shift lamhat_T (the SSN's; none without an SSN: pdas) and this controller's slip reference, of the unknowns and of
   the full displacement (2 dim per contact vertex). At a load step's end the next step's reference, with the data of
   the step solved: prescribed components of the contact vertices take the next step's data once the problem changes,
   so a restart could not recompute it. */
static PetscErrorCode WriterAttribute(void *w, const char name[], PetscDataType t, const void *v)
{
  PetscFunctionBeginUser;
  PetscCall(SgCheckpointWriterAttribute((SgCheckpointWriter)w, name, t, v));
  PetscFunctionReturn(0);
}

static PetscErrorCode WriterContact(void *w, const char name[], PetscInt bs, const PetscReal a[])
{
  PetscFunctionBeginUser;
  PetscCall(SgCheckpointWriterContact((SgCheckpointWriter)w, name, bs, a));
  PetscFunctionReturn(0);
}

static PetscErrorCode WriterReals(void *w, const char name[], PetscInt n, const PetscReal a[])
{
  PetscFunctionBeginUser;
  PetscCall(SgCheckpointWriterReals((SgCheckpointWriter)w, name, n, a));
  PetscFunctionReturn(0);
}

static PetscErrorCode FrictionSave(SgCont ct, SgCheckpointWriter w, PetscBool step_open)
{
  PetscReal         *lhT = NULL, *yref = ct->yref, *next = NULL;
  PetscInt           dim;
  SgContactLawWriter lw = {w, WriterAttribute, WriterContact, WriterReals};

  PetscFunctionBeginUser;
  if (!ct->c) PetscFunctionReturn(0);
  PetscCall(SgElasticityGetDimension(ct->prob, &dim));
  if (ct->ssn) PetscCall(SgSSNGetFriction(ct->ssn, &lhT, NULL, NULL));
  if (!step_open && yref) {
    PetscCall(PetscCalloc1(2 * ct->n * dim + 1, &next)); /* the second half is written with prescribed components only */
    PetscCall(SgContactComputeSlipReference(ct->c, ct->y, next));
    yref = next;
  }
  PetscCall(SgContactLawSave(ct->cv.law, lhT, yref, &lw)); /* the law, its parameters and state (nothing without friction) */
  PetscCall(PetscFree(next));
  PetscFunctionReturn(0);
}

static PetscErrorCode ReaderHasAttribute(void *r, const char name[], PetscBool *has)
{
  PetscFunctionBeginUser;
  PetscCall(SgCheckpointReaderHasAttribute((SgCheckpointReader)r, name, has));
  PetscFunctionReturn(0);
}

static PetscErrorCode ReaderHasDataset(void *r, const char name[], PetscBool *has)
{
  PetscFunctionBeginUser;
  PetscCall(SgCheckpointReaderHasDataset((SgCheckpointReader)r, name, has));
  PetscFunctionReturn(0);
}

static PetscErrorCode ReaderAttribute(void *r, const char name[], PetscDataType t, void *v)
{
  PetscFunctionBeginUser;
  PetscCall(SgCheckpointReaderAttribute((SgCheckpointReader)r, name, t, v));
  PetscFunctionReturn(0);
}

static PetscErrorCode ReaderContact(void *r, const char name[], PetscInt bs, const char desc[], PetscReal a[])
{
  PetscFunctionBeginUser;
  PetscCall(SgCheckpointReaderContact((SgCheckpointReader)r, name, bs, PETSC_FALSE, desc, a));
  PetscFunctionReturn(0);
}

static PetscErrorCode ReaderAbandon(void *r)
{
  SgCheckpointReader rd = (SgCheckpointReader)r;

  PetscFunctionBeginUser;
  PetscCall(SgCheckpointReaderAbandon(&rd));
  PetscFunctionReturn(0);
}

static PetscErrorCode ReaderReals(void *r, const char name[], PetscInt n, PetscReal **a)
{
  PetscFunctionBeginUser;
  PetscCall(SgCheckpointReaderReals((SgCheckpointReader)r, name, n, NULL, a));
  PetscFunctionReturn(0);
}

/* the law's reader on the checkpoint's */
static PetscErrorCode LawReader(SgCheckpointReader r, SgContactLawReader *lr)
{
  const SgContactLawReader l = {r, NULL, ReaderHasAttribute, ReaderHasDataset, ReaderAttribute, ReaderContact, ReaderAbandon, ReaderReals};

  PetscFunctionBeginUser;
  *lr = l;
  PetscCall(SgCheckpointReaderGetFile(r, &lr->file));
  PetscFunctionReturn(0);
}

/* *full: the file held the full displacement's slip reference (older files did not: then a copy of the unknowns') */
static PetscErrorCode FrictionLoad(SgCont ct, SgCheckpointReader r, PetscBool *full)
{
  PetscReal         *lhT = NULL;
  SgContactLawReader lr;

  PetscFunctionBeginUser;
  PetscCall(LawReader(r, &lr));
  if (ct->ssn) PetscCall(SgSSNGetFriction(ct->ssn, &lhT, NULL, NULL));                        /* (NULL without friction) */
  PetscCall(SgContactLawLoad(ct->c ? ct->cv.law : NULL, ct->comm, lhT, ct->yref, &lr, full)); /* checks the file's law, reads its state */
  PetscFunctionReturn(0);
}

/* ---- the load steps: the load factor of y, the finished steps' results, whether y is inside a step (an outer step's
   checkpoint) or a step's end, the finished steps' solutions when they are kept for the fields, their Dirichlet
   values (non-proportional loading) and friction numbers. A run without load steps writes none of it. */
static PetscErrorCode LoadStepsSave(SgCont ct, SgCheckpointWriter w, PetscBool step_open)
{
  PetscBool         loadsteps, kept;
  PetscReal         load, *a;
  PetscInt          open = step_open, nkept;
  const SgLoadStep *s    = ct->steps;

  PetscFunctionBeginUser;
  PetscCall(SgProblemHasLoadSteps(ct->problem_obj, &loadsteps));
  if (!loadsteps) PetscFunctionReturn(0);
  PetscCall(SgProblemGetLoadFactor(ct->problem_obj, &load));
  kept = (PetscBool)(ct->store_steps && ct->ysteps && ct->nsteps > 0);
  for (PetscInt k = 0; kept && k < ct->nsteps; k++)
    if (!ct->ysteps[k]) kept = PETSC_FALSE;
  nkept = kept ? ct->nsteps : 0;
  PetscCall(PetscMalloc1(SG_LOADSTEP_NREAL * ct->nsteps + 1, &a));
  for (PetscInt i = 0; i < ct->nsteps; i++) {
    const PetscReal v[SG_LOADSTEP_NREAL] = {s[i].t, s[i].obstacle_displacement, s[i].normal_displacement_max, s[i].force, s[i].kkt, s[i].energy, s[i].time, s[i].outer, s[i].ssn_its, s[i].ksp_its, s[i].nactive, s[i].converged};
    for (PetscInt k = 0; k < SG_LOADSTEP_NREAL; k++) a[i * SG_LOADSTEP_NREAL + k] = v[k];
  }
  PetscCall(SgCheckpointWriterReals(w, "load_steps", SG_LOADSTEP_NREAL * ct->nsteps, a));
  PetscCall(PetscFree(a));
  PetscCall(SgCheckpointWriterAttribute(w, "load_factor", PETSC_REAL, &load));
  PetscCall(SgCheckpointWriterAttribute(w, "load_steps_done", PETSC_INT, &ct->nsteps));
  PetscCall(SgCheckpointWriterAttribute(w, "load_step_open", PETSC_INT, &open));
  PetscCall(SgCheckpointWriterAttribute(w, "load_steps_kept", PETSC_INT, &nkept));
  for (PetscInt k = 0; k < nkept; k++) {
    char name[64];
    PetscCall(PetscSNPrintf(name, sizeof(name), "step_displacement_%" PetscInt_FMT, k));
    PetscCall(SgCheckpointWriterDisplacement(w, name, ct->ysteps[k], PETSC_FALSE));
    PetscCall(PetscSNPrintf(name, sizeof(name), "step_multiplier_%" PetscInt_FMT, k));
    PetscCall(SgCheckpointWriterContact(w, name, 1, ct->lamsteps[k]));
  }
  if (ct->dvsteps && ct->ndv > 0) {
    PetscCall(SgCheckpointWriterReals(w, "load_dirichlet_values", ct->ndv * ct->nsteps, ct->dvsteps));
    PetscCall(SgCheckpointWriterAttribute(w, "load_dirichlet_count", PETSC_INT, &ct->ndv));
  }
  if (ct->c) { /* the law's summaries of the steps (friction: the stick and slip sets, the friction resultant, traction) */
    SgFrictionSummary *fs;
    SgContactLawWriter lw = {w, WriterAttribute, WriterContact, WriterReals};
    PetscCall(PetscCalloc1(ct->nsteps + 1, &fs));
    for (PetscInt i = 0; i < ct->nsteps; i++) {
      fs[i].nstick     = s[i].nstick;
      fs[i].nslip      = s[i].nslip;
      fs[i].force_norm = s[i].friction_force;
      fs[i].traction   = s[i].friction_traction;
    }
    PetscCall(SgContactLawStepSave(ct->cv.law, ct->nsteps, fs, &lw));
    PetscCall(PetscFree(fs));
  }
  PetscFunctionReturn(0);
}

typedef struct {
  PetscBool has; /* written by a run with load steps; else the full load, inside its only step */
  PetscReal load;
  PetscInt  nsteps, open, nkept, ndv;
} LoadHeader;

static PetscErrorCode LoadStepsHeader(SgCont ct, SgCheckpointReader r, LoadHeader *h)
{
  const char *file;
  char        f[PETSC_MAX_PATH_LEN];
  PetscBool   has, ok;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(h, sizeof(*h)));
  h->load = 1;
  h->open = 1;
  PetscCall(SgCheckpointReaderHasAttribute(r, "load_factor", &h->has));
  if (!h->has) PetscFunctionReturn(0);
  PetscCall(SgCheckpointReaderAttribute(r, "load_factor", PETSC_REAL, &h->load));
  PetscCall(SgCheckpointReaderAttribute(r, "load_steps_done", PETSC_INT, &h->nsteps));
  PetscCall(SgCheckpointReaderAttribute(r, "load_step_open", PETSC_INT, &h->open));
  PetscCall(SgCheckpointReaderAttribute(r, "load_steps_kept", PETSC_INT, &h->nkept));
  PetscCall(SgCheckpointReaderHasAttribute(r, "load_dirichlet_count", &has));
  if (has) PetscCall(SgCheckpointReaderAttribute(r, "load_dirichlet_count", PETSC_INT, &h->ndv));
  ok = (PetscBool)(PetscIsNormalReal(h->load) && h->load > 0 && h->nsteps >= 0 && h->nsteps <= PETSC_MAX_INT / (4 * SG_LOADSTEP_NREAL) && (h->open == 0 || h->open == 1) && (h->nkept == 0 || h->nkept == h->nsteps) && h->ndv >= 0 && h->ndv <= 3 * SG_MAX_IDS);
  if (ok) PetscFunctionReturn(0);
  PetscCall(SgCheckpointReaderGetFile(r, &file));
  PetscCall(PetscStrncpy(f, file, sizeof(f)));
  PetscCall(SgCheckpointReaderAbandon(&r));
  SETERRQ(ct->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart_file: '%s' is damaged: its load steps (factor %g, %" PetscInt_FMT " steps done, %" PetscInt_FMT " kept, open %" PetscInt_FMT ", %" PetscInt_FMT " Dirichlet values each) are impossible", f, (double)h->load, h->nsteps, h->nkept, h->open, h->ndv);
}

/* the kept steps' displacements and multipliers, matched by the coordinates as y and lamhat */
static PetscErrorCode LoadKeptSteps(SgCont ct, SgCheckpointReader r, PetscInt n)
{
  PetscFunctionBeginUser;
  PetscCall(PetscCalloc2(n, &ct->ysteps, n, &ct->lamsteps));
  for (PetscInt k = 0; k < n; k++) {
    char name[64];
    PetscCall(VecDuplicate(ct->y, &ct->ysteps[k]));
    PetscCall(VecSet(ct->ysteps[k], 0));
    PetscCall(PetscMalloc1(ct->n + 1, &ct->lamsteps[k]));
    PetscCall(PetscSNPrintf(name, sizeof(name), "step_displacement_%" PetscInt_FMT, k));
    PetscCall(SgCheckpointReaderDisplacement(r, name, "a displacement of a kept load step", ct->ysteps[k]));
    PetscCall(PetscSNPrintf(name, sizeof(name), "step_multiplier_%" PetscInt_FMT, k));
    PetscCall(SgCheckpointReaderContact(r, name, 1, PETSC_FALSE, "a multiplier of a kept load step", ct->lamsteps[k]));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode LoadStepsData(SgCont ct, SgCheckpointReader r, const LoadHeader *h)
{
  SgLoadStep        *steps = NULL;
  PetscReal         *a;
  SgFrictionSummary *fs;
  SgContactLawReader lr;

  PetscFunctionBeginUser;
  if (h->has) {
    PetscCall(SgCheckpointReaderReals(r, "load_steps", SG_LOADSTEP_NREAL * h->nsteps, NULL, &a));
    PetscCall(PetscMalloc1(h->nsteps + 1, &steps));
    for (PetscInt i = 0; i < h->nsteps; i++) {
      const PetscReal *v = &a[i * SG_LOADSTEP_NREAL];
      SgLoadStep      *s = &steps[i];
      s->t = v[0], s->obstacle_displacement = v[1], s->normal_displacement_max = v[2], s->force = v[3], s->kkt = v[4], s->energy = v[5], s->time = v[6];
      s->outer = (PetscInt)v[7], s->ssn_its = (PetscInt)v[8], s->ksp_its = (PetscInt)v[9], s->nactive = (PetscInt)v[10];
      s->converged = (PetscBool)(v[11] != 0);
    }
    PetscCall(PetscFree(a));
    PetscCall(PetscMalloc1(h->nsteps + 1, &fs)); /* the law's summaries of the steps (zeros and NaN: none) */
    PetscCall(LawReader(r, &lr));
    PetscCall(SgContactLawStepLoad(ct->c ? ct->cv.law : NULL, h->nsteps, fs, &lr));
    for (PetscInt i = 0; i < h->nsteps; i++) {
      steps[i].nstick            = fs[i].nstick;
      steps[i].nslip             = fs[i].nslip;
      steps[i].friction_force    = fs[i].force_norm;
      steps[i].friction_traction = fs[i].traction;
    }
    PetscCall(PetscFree(fs));
  }
  PetscCall(PetscFree(ct->steps));
  ct->steps  = steps;
  ct->nsteps = ct->capsteps = h->has ? h->nsteps : 0;
  if (h->nkept > 0) PetscCall(LoadKeptSteps(ct, r, h->nkept)); /* the fields of the steps before the restart */
  if (h->ndv > 0) {                                            /* the finished steps' Dirichlet values */
    PetscInt m;
    PetscCall(SgElasticityGetDirichletSize(ct->prob, &m));
    if (h->ndv != m) PetscCall(SgCheckpointReaderAbandon(&r));
    PetscCheck(h->ndv == m, ct->comm, PETSC_ERR_USER_INPUT, "-restart_file: the checkpoint holds %" PetscInt_FMT " Dirichlet values per load step, this problem has %" PetscInt_FMT, h->ndv, m);
    PetscCall(PetscFree(ct->dvsteps));
    PetscCall(SgCheckpointReaderReals(r, "load_dirichlet_values", h->ndv * h->nsteps, NULL, &ct->dvsteps));
    ct->ndv = h->ndv;
  }
  PetscFunctionReturn(0);
}

/* ---- the checkpoint */
static PetscErrorCode CheckpointWrite(SgCont ct, PetscBool step_open)
{
  SgCheckpointWriter w;
  PetscBool          ok, has;
  char               msg[PETSC_MAX_PATH_LEN + 256];

  PetscFunctionBeginUser;
  if (!ct->ckfile[0]) PetscFunctionReturn(0);
  PetscCall(SgCheckpointWriterCreate(ct->prob, ct->c, ct->ckfile, &w));
  PetscCall(SaveBase(ct, w));
  if (ct->ops.save) PetscCall(ct->ops.save(ct, w));
  PetscCall(SgCheckpointWriterHas(w, "state", &has));
  if (!has) PetscCall(SgContSaveState(ct, w, 0, NULL, NULL)); /* a type that keeps no numbers */
  PetscCall(FrictionSave(ct, w, step_open));
  PetscCall(LoadStepsSave(ct, w, step_open));
  PetscCall(SgCheckpointWriterCommit(w, &ok, msg, sizeof(msg)));
  PetscCall(SgCheckpointWriterDestroy(&w));
  if (!ok) {
    /* the run stops (SgContCheck) and reports this as its reason; the summary and history are still written */
    PetscCall(PetscPrintf(ct->comm, "checkpoint not written: %s\n", msg));
    PetscCall(SgContFail(ct, "CHECKPOINT_FAILED: %s", msg));
    ct->ckfile[0] = 0;
  }
  PetscFunctionReturn(0);
}

/* after an outer step */
PetscErrorCode SgContCheckpointWrite(SgCont ct)
{
  PetscFunctionBeginUser;
  PetscCall(CheckpointWrite(ct, PETSC_TRUE));
  PetscFunctionReturn(0);
}

/* at a load step's end: a restart from here starts the next step warm */
PetscErrorCode SgContCheckpointWriteStepEnd(SgCont ct)
{
  PetscFunctionBeginUser;
  PetscCall(CheckpointWrite(ct, PETSC_FALSE));
  PetscFunctionReturn(0);
}

/* The state of -restart_file (read once, by the first SgContSolve or SgContGetLoadSteps). A checkpoint taken after an
   outer step resumes that continuation (ct->restarted); one taken at the end of a load step holds that step's solution
   and controller state, from which the next SgContSolve is a warm start. */
PetscErrorCode SgContCheckpointRead(SgCont ct)
{
  SgCheckpointReader r;
  LoadHeader         h;
  PetscBool          full;

  PetscFunctionBeginUser;
  if (ct->rsread || !ct->rsfile[0]) PetscFunctionReturn(0);
  ct->rsread = PETSC_TRUE;
  PetscCall(SgContSetUp(ct));
  PetscCall(SgCheckpointReaderOpen(ct->prob, ct->c, ct->rsfile, &r));
  PetscCall(LoadType(ct, r));
  if (ct->ops.load) PetscCall(ct->ops.load(ct, r));
  else PetscCall(SgContLoadState(ct, r, 0, NULL, NULL));
  PetscCall(LoadStepsHeader(ct, r, &h));
  /* any type resumes after a load step; inside one, only a continuation has outer steps to resume */
  if (ct->ops.solve && h.open) PetscCall(SgCheckpointReaderAbandon(&r));
  PetscCheck(!ct->ops.solve || !h.open, ct->comm, PETSC_ERR_USER_INPUT, "-restart_file: -cont_type %s has no outer steps to resume (the continuation controllers alm, pf and ipf have; any type resumes from the end of a load step)", ct->type);
  PetscCall(LoadBase(ct, r, (PetscBool)(h.has && !h.open), h.has));
  PetscCall(FrictionLoad(ct, r, &full));
  PetscCall(LoadStepsData(ct, r, &h));
  PetscCall(SgCheckpointReaderDestroy(&r));
  ct->rsload = h.load;
  if (h.load != 0) ct->V0unit = ct->V0 / (h.load * h.load); /* a step unloaded to 0 says nothing of it */
  if (h.open) ct->restarted = PETSC_TRUE;
  else {
    ct->yref_read  = full; /* the next step's slip reference (ct->yref), when the file holds all of it */
    ct->have_state = PETSC_TRUE;
    ct->gamma_warm = ct->ngammas && PetscIsNormalReal(ct->gammas[ct->ngammas - 1]) ? ct->gammas[ct->ngammas - 1] : ct->gamma;
  }
  PetscCall(PetscInfo(NULL, "restarted from %s after outer step %" PetscInt_FMT " (gamma %g)\n", ct->rsfile, ct->outer, (double)ct->gamma));
  PetscFunctionReturn(0);
}
