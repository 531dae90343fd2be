/* app/signorini.c: the command-line driver over the library (include/signorini.h): the options files' and result
   files' checks, the problem and the solver from the options, the results. */
#include <signorini.h>
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <strings.h>

static const char help[] = "Contact of linear elastic bodies, frictionless or with Tresca or Coulomb friction: one body against a rigid\n"
                           "obstacle (plane, parabola, ball, CAD model or meshed surface), or two elastic bodies (-contact_master_ids),\n"
                           "solved with the semismooth Newton, augmented Lagrangian and path-following methods of\n"
                           "G. Stadler (J. Comput. Appl. Math. 203, 2007). The mesh: a gmsh file (-dm_plex_filename F.msh, with\n"
                           "-dm_plex_gmsh_use_regions its physical names become labels) or a box (-box_*). README.md is the entry point,\n"
                           "doc/user-guide.md sets up a problem, doc/options.md describes every option; options/ holds ready-made\n"
                           "option files.\n\n";

typedef struct {
  char      outfile[PETSC_MAX_PATH_LEN], sumfile[PETSC_MAX_PATH_LEN], histfile[PETSC_MAX_PATH_LEN], curvefile[PETSC_MAX_PATH_LEN];
  PetscReal magnification;
  PetscBool quiet;
} Output;

/* quasi-static load stepping: n steps at the load factors t[0] < ... < t[n-1] = 1 */
#define SG_LOAD_STEPS_MAX 10000
typedef struct {
  PetscInt   n, stop;
  PetscReal  t[SG_LOAD_STEPS_MAX];
  char       dvstr[65536]; /* -load_dirichlet_values as given ("": none) */
  PetscInt   ndv;          /* Dirichlet values per step (dim per Dirichlet id), 0 without -load_dirichlet_values */
  PetscReal *dv;           /* n * ndv: the Dirichlet values of every step */
} LoadSteps;

/* ---- options files that include themselves
   PETSc's options parser follows -options_file lines recursively without a depth limit: a file that includes itself
   (directly or through others) recurses until the stack overflows (SEGV inside PetscInitialize). So before
   PetscInitialize the -options_file chains are followed here, with PETSc's own reading rules (a line is one option
   and its value; '#' starts a comment; tabs and CRs are blanks; values may be double-quoted), and a cycle is refused.
   PETSc is not initialized yet: the message goes to stderr directly. */
#define SG_INCLUDE_DEPTH 64

/* the options files read (their names as given), registered as inputs so that no result overwrites one */
#define SG_OPTIONS_FILES_MAX 32
static char OptionsFiles[SG_OPTIONS_FILES_MAX][PATH_MAX];
static int  NOptionsFiles = 0;

typedef struct {
  char path[SG_INCLUDE_DEPTH][PATH_MAX]; /* the real paths of the files being read, outermost first */
  char given[SG_INCLUDE_DEPTH][PATH_MAX];
  int  n;
} IncludeStack;

/* Next blank-separated token of *s (a double-quoted token may hold blanks; the quotes are removed); NULL at the end. */
static char *NextToken(char **s)
{
  char *p = *s, *t;

  while (*p == ' ') p++;
  if (!*p) return NULL;
  if (*p == '"') {
    t = ++p;
    while (*p && *p != '"') p++;
  } else {
    t = p;
    while (*p && *p != ' ') p++;
  }
  if (*p) *p++ = 0;
  *s = p;
  return t;
}

static int IsOptionsFileKey(const char *t)
{
  return !strcasecmp(t, "-options_file");
}

static int FollowOptionsFile(IncludeStack *st, const char *given);

/* The -options_file values of a string of options (the command line joined, or PETSC_OPTIONS). */
static int FollowString(IncludeStack *st, char *s)
{
  char *t;
  while ((t = NextToken(&s))) {
    if (IsOptionsFileKey(t)) {
      char *f = NextToken(&s);
      if (f && f[0] != '-') {
        int r = FollowOptionsFile(st, f);
        if (r) return r;
      }
    }
  }
  return 0;
}

static int FollowOptionsFile(IncludeStack *st, const char *given)
{
  char   real[PATH_MAX], fname[PATH_MAX], *line = NULL;
  size_t cap = 0, len = strlen(given);
  FILE  *fp;
  int    r = 0;

  /* YAML files (".yml", ".yaml", ":yaml") include nothing; ~/ as PETSc expands it */
  if ((len > 4 && !strcmp(given + len - 4, ".yml")) || (len > 5 && (!strcmp(given + len - 5, ".yaml") || !strcmp(given + len - 5, ":yaml")))) return 0;
  if (given[0] == '~' && given[1] == '/' && getenv("HOME")) snprintf(fname, sizeof(fname), "%s%s", getenv("HOME"), given + 1);
  else snprintf(fname, sizeof(fname), "%s", given);
  if (!realpath(fname, real)) return 0; /* a missing file is PETSc's to report */
  for (int i = 0; i < st->n; i++)
    if (!strcmp(st->path[i], real)) {
      fprintf(stderr, "[0]PETSC ERROR: --------------------- Error Message --------------------------------------------------------------\n");
      fprintf(stderr, "[0]PETSC ERROR: -options_file: '%s' includes itself:", given);
      for (int j = i; j < st->n; j++) fprintf(stderr, " %s ->", st->given[j]);
      fprintf(stderr, " %s\n[0]PETSC ERROR: (PETSc would follow the cycle until it crashes; remove one of these -options_file lines)\n", given);
      return 1;
    }
  if (st->n == SG_INCLUDE_DEPTH) {
    fprintf(stderr, "[0]PETSC ERROR: --------------------- Error Message --------------------------------------------------------------\n");
    fprintf(stderr, "[0]PETSC ERROR: -options_file: more than %d nested options files (at '%s')\n", SG_INCLUDE_DEPTH, given);
    return 1;
  }
  if (!(fp = fopen(fname, "r"))) return 0;
  if (NOptionsFiles < SG_OPTIONS_FILES_MAX) snprintf(OptionsFiles[NOptionsFiles++], PATH_MAX, "%s", fname);
  snprintf(st->path[st->n], PATH_MAX, "%s", real);
  snprintf(st->given[st->n], PATH_MAX, "%s", given);
  st->n++;
  while (!r && getline(&line, &cap, fp) >= 0) {
    char *s = line, *c = strchr(line, '#'), *t;
    if (c) *c = 0;
    for (char *q = line; *q; q++)
      if (*q == '\t' || *q == '\r' || *q == '\n') *q = ' ';
    t = NextToken(&s);
    if (t && IsOptionsFileKey(t)) {
      char *f = NextToken(&s);
      if (f && f[0] != '-') r = FollowOptionsFile(st, f);
    }
  }
  free(line);
  fclose(fp);
  st->n--;
  return r;
}

/* 0, or 1 after printing the cycle: every -options_file of the command line, of PETSC_OPTIONS and of the petscrc
   files PETSc reads. */
static int CheckOptionsFileCycles(int argc, char **argv)
{
  static IncludeStack st; /* large: not on the stack */
  int                 skiprc = 0, r = 0;
  const char         *env = getenv("PETSC_OPTIONS");

  for (int i = 1; i < argc; i++)
    if (!strcasecmp(argv[i], "-skip_petscrc")) skiprc = 1;
  st.n = 0;
  if (!skiprc) {
    char rc[PATH_MAX];
    if (getenv("HOME")) {
      snprintf(rc, sizeof(rc), "%s/.petscrc", getenv("HOME"));
      r = r ? r : FollowOptionsFile(&st, rc);
    }
    r = r ? r : FollowOptionsFile(&st, ".petscrc");
    r = r ? r : FollowOptionsFile(&st, "petscrc");
  }
  if (!r && env) {
    char *copy = strdup(env);
    if (copy) {
      r = FollowString(&st, copy);
      free(copy);
    }
  }
  for (int i = 1; !r && i < argc - 1; i++)
    if (IsOptionsFileKey(argv[i]) && argv[i + 1][0] != '-') r = FollowOptionsFile(&st, argv[i + 1]);
  return r;
}

static PetscErrorCode OutputOptions(MPI_Comm comm, Output *o)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(o, sizeof(*o)));
  o->magnification = 20;
  PetscOptionsBegin(comm, NULL, "Output", NULL);
  PetscCall(SgOptionsFileName(PetscOptionsObject, "-output_file", "HDF5 result file (fields for ParaView; an .xmf file is written beside it)", o->outfile, sizeof(o->outfile), NULL));
  PetscCall(SgOptionsFileName(PetscOptionsObject, "-summary_file", "JSON summary of the run", o->sumfile, sizeof(o->sumfile), NULL));
  PetscCall(SgOptionsFileName(PetscOptionsObject, "-history_file", "CSV history: one row per SSN iteration and per outer step", o->histfile, sizeof(o->histfile), NULL));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-output_magnification", "Displacement magnification stored for the pictures", &o->magnification, NULL));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-quiet", "Print the results only: neither the settings nor a line per outer step (-cont_monitor false)", &o->quiet, NULL));
  PetscCall(SgOptionsFileName(PetscOptionsObject, "-load_curve_file", "CSV load-displacement curve: one row per load step (with -load_steps)", o->curvefile, sizeof(o->curvefile), NULL));
  PetscOptionsEnd();
  PetscCheck(PetscIsNormalReal(o->magnification) && o->magnification > 0, comm, PETSC_ERR_USER_INPUT, "-output_magnification: must be positive and finite, got %g", (double)o->magnification);
  /* refuse unwritable locations before any work is done */
  PetscCall(SgFileCheckWritable(comm, "-output_file", o->outfile));
  PetscCall(SgFileCheckWritable(comm, "-summary_file", o->sumfile));
  PetscCall(SgFileCheckWritable(comm, "-history_file", o->histfile));
  PetscCall(SgFileCheckWritable(comm, "-load_curve_file", o->curvefile));
  PetscFunctionReturn(0);
}

/* -load_steps N and -load_factors t1,...,tN (default k/N): increasing, positive, the last 1. */
static PetscErrorCode LoadStepOptions(MPI_Comm comm, LoadSteps *ls)
{
  PetscInt  n = 1, nf = 0; /* -load_factors: no default list (the default is k/N) */
  PetscBool nset, fset;

  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Quasi-static load stepping", NULL);
  PetscCall(SgOptionsIntValue(PetscOptionsObject, "-load_steps", "Number of load steps: loads, Dirichlet values and -obstacle_translation scaled from 0 to their full value, each step warm-started from the last", &n, &nset));
  PetscCall(SgOptionsRealList(PetscOptionsObject, "-load_factors", "Load factors of the steps, increasing, the last 1 (default: k/N; at most 96 factors)", 96, ls->t, &nf, &fset));
  ls->dvstr[0] = 0;
  PetscCall(PetscOptionsString("-load_dirichlet_values", "Non-proportional loading: the Dirichlet values of every load step, one full -dirichlet_values list (dim numbers per Dirichlet id) per step, the steps in order (N x ids x dim numbers with -load_steps N); the load factor then scales the loads and -obstacle_translation only", NULL, ls->dvstr, ls->dvstr, sizeof(ls->dvstr), NULL));
  ls->stop = 0;
  PetscCall(SgOptionsIntValue(PetscOptionsObject, "-load_step_stop", "Stop after this load step (a run split over several jobs: the next one continues with -restart_file from -checkpoint_file); 0: run all", &ls->stop, NULL));
  PetscOptionsEnd();
  PetscCheck(ls->stop >= 0, comm, PETSC_ERR_USER_INPUT, "-load_step_stop: must be >= 0, got %" PetscInt_FMT, ls->stop);
  PetscCheck(n >= 1 && n <= SG_LOAD_STEPS_MAX, comm, PETSC_ERR_USER_INPUT, "-load_steps: must be between 1 and %d, got %" PetscInt_FMT, SG_LOAD_STEPS_MAX, n);
  if (fset) {
    PetscCheck(!nset || nf == n, comm, PETSC_ERR_USER_INPUT, "-load_factors: %" PetscInt_FMT " factors given for -load_steps %" PetscInt_FMT, nf, n);
    n = nf;
    for (PetscInt k = 0; k < n; k++) {
      PetscCheck(PetscIsNormalReal(ls->t[k]) && ls->t[k] > 0, comm, PETSC_ERR_USER_INPUT, "-load_factors: factor %" PetscInt_FMT " is %g, must be positive and finite", k + 1, (double)ls->t[k]);
      PetscCheck(k == 0 || ls->t[k] > ls->t[k - 1], comm, PETSC_ERR_USER_INPUT, "-load_factors: must increase, but factor %" PetscInt_FMT " (%g) follows %g", k + 1, (double)ls->t[k], (double)ls->t[k - 1]);
    }
    PetscCheck(PetscAbsReal(ls->t[n - 1] - 1) <= 1e-12, comm, PETSC_ERR_USER_INPUT, "-load_factors: the last factor must be 1 (the full load), got %.17g", (double)ls->t[n - 1]);
    ls->t[n - 1] = 1;
  } else
    for (PetscInt k = 0; k < n; k++) ls->t[k] = (PetscReal)(k + 1) / n;
  ls->n = n;
  PetscFunctionReturn(0);
}

/* -load_dirichlet_values v1,v2,...: the Dirichlet values of every load step (SgProblemGetDirichletSize numbers per
   step, the steps in order), read once the problem knows its dimension and Dirichlet ids. */
static PetscErrorCode LoadDirichletValues(MPI_Comm comm, SgProblem prob, LoadSteps *ls)
{
  const char *opt = "-load_dirichlet_values";
  PetscInt    m, dim, nv = 1, k = 0;
  char       *s, *tok, *save = NULL;

  PetscFunctionBeginUser;
  ls->ndv = 0;
  if (!ls->dvstr[0]) PetscFunctionReturn(0);
  PetscCall(SgProblemGetDirichletSize(prob, &m));
  PetscCall(SgProblemGetDimension(prob, &dim));
  PetscCheck(m > 0, comm, PETSC_ERR_USER_INPUT, "%s: the problem has no Dirichlet part (-dirichlet_label, -dirichlet_ids)", opt);
  for (const char *c = ls->dvstr; *c; c++) nv += (*c == ',');
  PetscCall(PetscMalloc1(nv, &ls->dv));
  s = ls->dvstr;
  for (tok = strtok_r(s, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
    char *end;
    while (*tok == ' ') tok++;
    ls->dv[k] = (PetscReal)strtod(tok, &end);
    while (*end == ' ') end++;
    PetscCheck(!*end && end != tok, comm, PETSC_ERR_USER_INPUT, "%s: entry %" PetscInt_FMT " '%s' is not a number", opt, k, tok);
    PetscCheck(PetscIsNormalReal(ls->dv[k]) || ls->dv[k] == 0, comm, PETSC_ERR_USER_INPUT, "%s: entry %" PetscInt_FMT " is %g, must be finite", opt, k, (double)ls->dv[k]);
    k++;
  }
  PetscCheck(k == ls->n * m, comm, PETSC_ERR_USER_INPUT, "%s: got %" PetscInt_FMT " numbers, need %" PetscInt_FMT " (-load_steps %" PetscInt_FMT " x %" PetscInt_FMT " Dirichlet ids x %" PetscInt_FMT " components)", opt, k, ls->n * m, ls->n, m / dim, dim);
  ls->ndv = m;
  PetscFunctionReturn(0);
}

/* The load steps the driver runs: one warm-started SgContSolve per factor, a line per step. A checkpoint taken
   between load steps (-restart_file) resumes after its last step. */
static PetscErrorCode SolveLoadSteps(MPI_Comm comm, SgProblem prob, SgCont cont, const LoadSteps *ls, PetscBool keep)
{
  PetscInt  k0;
  PetscBool contact;

  PetscFunctionBeginUser;
  PetscCall(SgProblemHasContact(prob, &contact));
  PetscCall(SgContSetStoreSteps(cont, keep));
  PetscCall(SgContGetLoadSteps(cont, &k0));
  PetscCheck(k0 < ls->n, comm, PETSC_ERR_USER_INPUT, "-restart_file: the checkpoint has %" PetscInt_FMT " load steps done, this run has -load_steps %" PetscInt_FMT ": nothing left to solve", k0, ls->n);
  for (PetscInt k = 0; k < k0; k++) { /* the steps done must be this run's first ones */
    PetscReal t;
    PetscCall(SgContGetLoadStepFactor(cont, k, &t));
    PetscCheck(PetscAbsReal(t - ls->t[k]) <= 1e-12 * ls->t[k], comm, PETSC_ERR_USER_INPUT, "-restart_file: the checkpoint's load step %" PetscInt_FMT " was solved at load factor %.15g, this run's step %" PetscInt_FMT " is at %.15g (give the same -load_steps and -load_factors)", k + 1, (double)t, k + 1, (double)ls->t[k]);
  }
  for (PetscInt k = 0; k < k0; k++) { /* and with the same Dirichlet values (-load_dirichlet_values) */
    PetscReal *dv;
    PetscInt   m;
    PetscBool  set;
    PetscCall(SgProblemGetDirichletSize(prob, &m));
    PetscCall(PetscMalloc1(m + 1, &dv));
    PetscCall(SgContGetLoadStepDirichletValues(cont, k, &set, dv));
    PetscCheck(set == (ls->ndv > 0), comm, PETSC_ERR_USER_INPUT, "-restart_file: the checkpoint's load steps were solved %s -load_dirichlet_values, this run has %s", set ? "with" : "without", ls->ndv ? "them" : "none");
    for (PetscInt i = 0; set && i < ls->ndv; i++) {
      const PetscReal a = dv[i], b = ls->dv[k * ls->ndv + i];
      PetscCheck(PetscAbsReal(a - b) <= 1e-12 * PetscMax(PetscAbsReal(a), PetscAbsReal(b)), comm, PETSC_ERR_USER_INPUT, "-restart_file: the checkpoint's load step %" PetscInt_FMT " had the Dirichlet value %.15g where this run's -load_dirichlet_values has %.15g (entry %" PetscInt_FMT ")", k + 1, (double)a, (double)b, k * ls->ndv + i);
    }
    PetscCall(PetscFree(dv));
  }
  if (k0) PetscCall(PetscPrintf(comm, "load steps: resuming after step %" PetscInt_FMT " of %" PetscInt_FMT " (-restart_file)\n", k0, ls->n));
  for (PetscInt k = k0; k < ls->n; k++) {
    PetscBool      converged;
    PetscInt       outer, ssn, ksp;
    PetscLogDouble t0, t1;
    SgKKT          kkt;

    PetscCall(PetscTime(&t0));
    PetscCall(SgProblemSetLoadFactor(prob, ls->t[k]));
    if (ls->ndv) PetscCall(SgProblemSetDirichletValues(prob, &ls->dv[k * ls->ndv]));
    PetscCall(SgContSolve(cont));
    PetscCall(PetscTime(&t1));
    PetscCall(SgContGetConvergedReason(cont, &converged, NULL));
    PetscCall(SgContGetIterationNumbers(cont, &outer, &ssn, &ksp));
    if (contact) {
      PetscCall(SgContGetKKT(cont, &kkt));
      PetscCall(PetscPrintf(comm, "load step %" PetscInt_FMT "/%" PetscInt_FMT ": factor %.6g, %" PetscInt_FMT " outer, %" PetscInt_FMT " SSN, %" PetscInt_FMT " KSP iterations, active %" PetscInt_FMT ", contact force %.6e, KKT %.3e, %.3g s%s\n", k + 1, ls->n, (double)ls->t[k], outer, ssn, ksp, kkt.nactive, (double)kkt.force, (double)kkt.residual, (double)(t1 - t0), converged ? "" : " FAILED"));
    } else PetscCall(PetscPrintf(comm, "load step %" PetscInt_FMT "/%" PetscInt_FMT ": factor %.6g, %" PetscInt_FMT " KSP iterations, %.3g s%s\n", k + 1, ls->n, (double)ls->t[k], ksp, (double)(t1 - t0), converged ? "" : " FAILED"));
    if (!converged) break; /* the next step would start from a failed one */
    if (ls->stop && k + 1 == ls->stop && k + 1 < ls->n) {
      PetscCall(PetscPrintf(comm, "load steps: stopped after step %" PetscInt_FMT " of %" PetscInt_FMT " (-load_step_stop); the next run continues with -restart_file\n", k + 1, ls->n));
      break;
    }
  }
  PetscFunctionReturn(0);
}

/* Every file option, checked before any work: names too long, files not ours to replace, one file named twice. The
   values are taken as given (PetscOptionsString would cut them at PETSC_MAX_PATH_LEN - 1 characters). */
static PetscErrorCode CheckFileOptions(MPI_Comm comm)
{
  const char *inputs[3] = {"-dm_plex_filename", "-restart_file", "-obstacle_cad_file"}, *results[5] = {"-output_file", "-summary_file", "-history_file", "-checkpoint_file", "-load_curve_file"};

  PetscFunctionBeginUser;
  for (int i = 0; i < NOptionsFiles; i++) PetscCall(SgFileCheckInput(comm, "-options_file", OptionsFiles[i]));
  for (PetscInt k = 0; k < 8; k++) {
    const char *opt = k < 3 ? inputs[k] : results[k - 3], *val = NULL;
    PetscBool   set;
    size_t      len;
    PetscCall(PetscOptionsFindPair(NULL, NULL, opt, &val, &set));
    if (!set || !val || !val[0] || SgFileNameIsNone(val)) continue; /* no file */
    PetscCall(PetscStrlen(val, &len));
    PetscCheck(len < PETSC_MAX_PATH_LEN - 6, comm, PETSC_ERR_USER_INPUT, "%s: the file name is %zu characters long, at most %d are supported", opt, len, PETSC_MAX_PATH_LEN - 7);
    if (k < 3) PetscCall(SgFileCheckInput(comm, opt, val));
    else PetscCall(SgFileCheckWritable(comm, opt, val));
  }
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  MPI_Comm         comm;
  Output           out;
  static LoadSteps ls; /* large: not on the stack */
  SgProblem        prob;
  SgCont           cont;
  PetscBool        converged, helponly;
  PetscErrorCode   ierr_fields = 0, ierr_hist;

  if (CheckOptionsFileCycles(argc, argv)) return PETSC_ERR_USER_INPUT;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  comm = PETSC_COMM_WORLD;
  PetscCall(SgFileInstallCleanup());
  PetscCall(CheckFileOptions(comm));
  PetscCall(OutputOptions(comm, &out));
  PetscCall(LoadStepOptions(comm, &ls));
  PetscCall(SgProblemCreate(comm, &prob));
  PetscCall(SgContCreate(prob, &cont)); /* the controller holds the problem (nothing read yet) */
  PetscCall(SgContPrintHelp(cont));     /* -help: the controllers' options, even when the problem's are missing */
  PetscCall(SgProblemSetFromOptions(prob));
  PetscCall(PetscOptionsHasHelp(NULL, &helponly));
  if (helponly) {
    /* -help without a complete problem (bin/signorini -help): the options are listed above; say what is missing and
       stop without an error (PETSc's own programs list their options and exit 0) */
    PetscErrorCode ierr;
    const char    *why = NULL;
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = SgProblemSetUp(prob);
    PetscCall(PetscPopErrorHandler());
    if (ierr) {
      (void)PetscErrorMessage(ierr, NULL, (char **)&why);
      PetscCall(PetscPrintf(comm, "-help: the options are listed above; no problem was set up, so nothing is solved (%s)\n", why && why[0] ? why : "the problem is incomplete"));
      PetscCall(SgContDestroy(&cont));
      PetscCall(SgProblemDestroy(&prob));
      PetscCall(PetscFinalize());
      return 0;
    }
  } else PetscCall(SgProblemSetUp(prob));
  PetscCall(LoadDirichletValues(comm, prob, &ls));
  if (out.quiet) PetscCall(SgContSetMonitor(cont, PETSC_FALSE)); /* -cont_monitor still decides */
  PetscCall(SgContSetFromOptions(cont));
  PetscCall(SgContSetUp(cont));
  if (!out.quiet) { /* what runs, and how to change it */
    PetscCall(SgProblemView(prob, NULL));
    PetscCall(SgContView(cont, NULL));
  }
  if (ls.n > 1) PetscCall(SolveLoadSteps(comm, prob, cont, &ls, (PetscBool)(out.outfile[0] != 0)));
  else {
    if (ls.ndv) PetscCall(SgProblemSetDirichletValues(prob, ls.dv));
    PetscCall(SgContSolve(cont));
  }
  PetscCall(SgContGetConvergedReason(cont, &converged, NULL));
  /* the history is kept whatever happened, the fields only for a converged solve; a failed write (a full disk, say)
     is recorded in the summary, which is still written, and the run then exits with that error */
  ierr_hist = SgContWriteHistory(cont, out.histfile);
  if (!ierr_hist) ierr_hist = SgContWriteLoadCurve(cont, out.curvefile);
  if (converged && out.outfile[0]) ierr_fields = SgContWriteFields(cont, out.outfile, out.magnification);
  PetscCall(SgContWriteSummary(cont, out.sumfile));
  PetscCall(ierr_hist);
  PetscCall(ierr_fields);
  PetscCall(SgContView(cont, PETSC_VIEWER_STDOUT_(comm)));
  PetscCall(SgContDestroy(&cont));
  PetscCall(SgProblemDestroy(&prob));
  PetscCall(PetscFree(ls.dv));
  PetscCall(PetscFinalize());
  return converged ? 0 : 3;
}
