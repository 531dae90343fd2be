/* app/signorini.c: the command-line driver over the library (include/signorini.h): the options files' and result
   files' checks, the problem and the solver from the options, the results. */
#include <signorini.h>
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <strings.h>

static const char help[] = "Frictionless contact of a linear elastic body with a rigid obstacle, solved with the semismooth Newton,\n"
                           "augmented Lagrangian and path-following methods of G. Stadler (J. Comput. Appl. Math. 203, 2007).\n"
                           "See README.md for the options; options/ holds ready-made option files.\n\n";

typedef struct {
  char      outfile[PETSC_MAX_PATH_LEN], sumfile[PETSC_MAX_PATH_LEN], histfile[PETSC_MAX_PATH_LEN];
  PetscReal magnification;
} Output;

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
  const char         *env    = getenv("PETSC_OPTIONS");

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
  PetscCall(PetscOptionsString("-output_file", "HDF5 result file (fields for ParaView; an .xmf file is written beside it)", NULL, o->outfile, o->outfile, sizeof(o->outfile), NULL));
  PetscCall(PetscOptionsString("-summary_file", "JSON summary of the run", NULL, o->sumfile, o->sumfile, sizeof(o->sumfile), NULL));
  PetscCall(PetscOptionsString("-history_file", "CSV history: one row per SSN iteration and per outer step", NULL, o->histfile, o->histfile, sizeof(o->histfile), NULL));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-output_magnification", "Displacement magnification stored for the pictures", &o->magnification, NULL));
  PetscOptionsEnd();
  PetscCheck(PetscIsNormalReal(o->magnification) && o->magnification > 0, comm, PETSC_ERR_USER_INPUT, "-output_magnification: must be positive and finite, got %g", (double)o->magnification);
  /* refuse unwritable locations before any work is done */
  PetscCall(SgFileCheckWritable(comm, "-output_file", o->outfile));
  PetscCall(SgFileCheckWritable(comm, "-summary_file", o->sumfile));
  PetscCall(SgFileCheckWritable(comm, "-history_file", o->histfile));
  PetscFunctionReturn(0);
}

/* Every file option, checked before any work: names too long, files not ours to replace, one file named twice. The
   values are taken as given (PetscOptionsString would cut them at PETSC_MAX_PATH_LEN - 1 characters). */
static PetscErrorCode CheckFileOptions(MPI_Comm comm)
{
  const char *inputs[3] = {"-dm_plex_filename", "-restart_file", "-obstacle_cad_file"}, *results[4] = {"-output_file", "-summary_file", "-history_file", "-checkpoint_file"};

  PetscFunctionBeginUser;
  for (int i = 0; i < NOptionsFiles; i++) PetscCall(SgFileCheckInput(comm, "-options_file", OptionsFiles[i]));
  for (PetscInt k = 0; k < 7; k++) {
    const char *opt = k < 3 ? inputs[k] : results[k - 3], *val = NULL;
    PetscBool   set;
    size_t      len;
    PetscCall(PetscOptionsFindPair(NULL, NULL, opt, &val, &set));
    if (!set || !val || !val[0]) continue;
    PetscCall(PetscStrlen(val, &len));
    PetscCheck(len < PETSC_MAX_PATH_LEN - 6, comm, PETSC_ERR_USER_INPUT, "%s: the file name is %zu characters long, at most %d are supported", opt, len, PETSC_MAX_PATH_LEN - 7);
    if (k < 3) PetscCall(SgFileCheckInput(comm, opt, val));
    else PetscCall(SgFileCheckWritable(comm, opt, val));
  }
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  MPI_Comm       comm;
  Output         out;
  SgProblem      prob;
  SgCont         cont;
  PetscBool      converged;
  PetscErrorCode ierr_fields = 0, ierr_hist;

  if (CheckOptionsFileCycles(argc, argv)) return PETSC_ERR_USER_INPUT;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  comm = PETSC_COMM_WORLD;
  PetscCall(SgFileInstallCleanup());
  PetscCall(CheckFileOptions(comm));
  PetscCall(OutputOptions(comm, &out));
  PetscCall(SgProblemCreate(comm, &prob));
  PetscCall(SgProblemSetFromOptions(prob));
  PetscCall(SgProblemSetUp(prob));
  PetscCall(SgContCreate(prob, &cont));
  PetscCall(SgContSetFromOptions(cont));
  PetscCall(SgContSetUp(cont));
  PetscCall(SgContSolve(cont));
  PetscCall(SgContGetConvergedReason(cont, &converged, NULL));
  /* the history is kept whatever happened, the fields only for a converged solve; a failed write (a full disk, say)
     is recorded in the summary, which is still written, and the run then exits with that error */
  ierr_hist = SgContWriteHistory(cont, out.histfile);
  if (converged && out.outfile[0]) ierr_fields = SgContWriteFields(cont, out.outfile, out.magnification);
  PetscCall(SgContWriteSummary(cont, out.sumfile));
  PetscCall(ierr_hist);
  PetscCall(ierr_fields);
  PetscCall(SgContView(cont, PETSC_VIEWER_STDOUT_(comm)));
  PetscCall(SgContDestroy(&cont));
  PetscCall(SgProblemDestroy(&prob));
  PetscCall(PetscFinalize());
  return converged ? 0 : 3;
}
