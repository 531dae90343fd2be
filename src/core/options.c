/* core/options.c: option parsers that name the option, with its prefix, in every message (PETSc 3.18's own parsers
   report an empty value as "not set" and a bad number without the option's name). */
#include "sg.h"
#include <errno.h>
#include <stdlib.h>

/* "-" prefix opt-without-its-dash: the name a user types */
PetscErrorCode SgOptionsName(const char prefix[], const char opt[], char name[], size_t len)
{
  PetscFunctionBeginUser;
  SgValidPointer(opt, 2);
  SgValidPointer(name, 3);
  PetscCheck(len > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "SgOptionsName: the buffer for the name has length 0");
  PetscCall(PetscSNPrintf(name, len, "-%s%s", prefix ? prefix : "", opt[0] == '-' ? opt + 1 : opt));
  PetscFunctionReturn(0);
}

/* The value that names no file: the default documented for every file option. */
PetscBool SgFileNameIsNone(const char name[])
{
  return (PetscBool)(name && !strcmp(name, "none"));
}

/* -opt as a file name into file[len] (its value on entry is the default): "none" is no file (file[0] = 0, *set
   false), the same as leaving the option unset, so that the command line turns off a result file an options file
   names; -help shows "none" for no file. An empty value stays empty and set (the caller's "given without a file"). */
PetscErrorCode SgOptionsFileName(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], char file[], size_t len, PetscBool *set)
{
  char      help[2048], def[PETSC_MAX_PATH_LEN];
  PetscBool flg;

  PetscFunctionBeginUser;
  PetscCheck(PetscOptionsObject, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "SgOptionsFileName: argument 1 (PetscOptionsObject) is NULL: call it between PetscOptionsBegin and PetscOptionsEnd");
  PetscCheck(opt && opt[0], PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "SgOptionsFileName: argument 2 (the option's name) is NULL or empty");
  SgValidPointer(text, 3);
  SgValidPointer(file, 4);
  PetscCheck(len > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "SgOptionsFileName: the buffer for the file name has length 0");
  PetscCall(PetscSNPrintf(help, sizeof(help), "%s (none: no file)", text));
  PetscCall(PetscStrncpy(def, file[0] ? file : "none", sizeof(def)));
  PetscCall(PetscOptionsString(opt, help, NULL, def, file, len, &flg));
  if (SgFileNameIsNone(file)) {
    file[0] = 0;
    flg     = PETSC_FALSE;
  }
  if (set) *set = flg;
  PetscFunctionReturn(0);
}

/* The arguments of the readers: between PetscOptionsBegin and PetscOptionsEnd, an option name, n in [0, max] and
   room for max values */
static PetscErrorCode CheckReaderArgs(PetscOptionItems *obj, const char opt[], PetscInt max, const void *vals, const PetscInt *n, const char fn[])
{
  PetscFunctionBeginUser;
  PetscCheck(obj, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "%s: argument 1 (PetscOptionsObject) is NULL: call it between PetscOptionsBegin and PetscOptionsEnd", fn);
  PetscCheck(opt && opt[0], PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "%s: argument 2 (the option's name) is NULL or empty", fn);
  PetscCheck(max >= 1 && max <= SG_OPT_MAX, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "%s: %" PetscInt_FMT " entries; lists hold 1 to %d", fn, max, SG_OPT_MAX);
  PetscCheck(vals, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "%s: the array of values is NULL", fn);
  PetscCheck(n, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "%s: the count (number of default values in, of values read out) is NULL", fn);
  PetscCheck(*n >= 0 && *n <= max, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "%s: %" PetscInt_FMT " default values, must lie in [0, %" PetscInt_FMT "]", fn, *n, max);
  PetscFunctionReturn(0);
}

/* Split a comma-separated option value; an empty value or entry, or more than max entries, is an error naming opt. */
static PetscErrorCode SplitList(MPI_Comm comm, const char opt[], const char str[], PetscInt max, char tok[][64], PetscInt *n)
{
  const char *s = str;

  PetscFunctionBeginUser;
  *n = 0;
  while (*s == ' ' || *s == '\t') s++;
  PetscCheck(*s, comm, PETSC_ERR_USER_INPUT, "%s is given without a value", opt);
  for (;;) {
    const char *e = s;
    size_t      len;
    while (*e && *e != ',') e++;
    len = (size_t)(e - s);
    while (len > 0 && (s[len - 1] == ' ' || s[len - 1] == '\t')) len--;
    while (len > 0 && (*s == ' ' || *s == '\t')) {
      s++;
      len--;
    }
    PetscCheck(*n < max, comm, PETSC_ERR_USER_INPUT, "%s '%s': more than %" PetscInt_FMT " entries", opt, str, max);
    PetscCheck(len > 0, comm, PETSC_ERR_USER_INPUT, "%s '%s': entry %" PetscInt_FMT " is empty", opt, str, *n);
    PetscCheck(len < 64, comm, PETSC_ERR_USER_INPUT, "%s '%s': entry %" PetscInt_FMT " is too long", opt, str, *n);
    PetscCall(PetscMemcpy(tok[*n], s, len));
    tok[*n][len] = 0;
    (*n)++;
    if (!*e) break;
    s = e + 1;
  }
  PetscFunctionReturn(0);
}

/* -opt as a list of at most max integers: read as a string so that a bad entry is reported with the option's name
   (PETSc's own parser does not name it, and drops an option given without a value). */
PetscErrorCode SgOptionsIntList(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], PetscInt max, PetscInt vals[], PetscInt *n, PetscBool *set)
{
  char      def[2048] = "", str[4096], tok[SG_OPT_MAX][64];
  PetscInt  nt;
  PetscBool flg;

  MPI_Comm comm;
  char     name[256];

  PetscFunctionBeginUser;
  PetscCall(CheckReaderArgs(PetscOptionsObject, opt, max, vals, n, "SgOptionsIntList"));
  comm = PetscOptionsObject->comm;
  PetscCall(SgOptionsName(PetscOptionsObject->prefix, opt, name, sizeof(name)));
  for (PetscInt i = 0; i < *n; i++) {
    size_t l;
    PetscCall(PetscStrlen(def, &l));
    PetscCall(PetscSNPrintf(def + l, sizeof(def) - l, i ? ",%" PetscInt_FMT : "%" PetscInt_FMT, vals[i]));
  }
  PetscCall(PetscOptionsString(opt, text, NULL, def, str, sizeof(str), &flg));
  if (set) *set = flg;
  if (!flg) PetscFunctionReturn(0);
  PetscCall(SplitList(comm, name, str, max, tok, &nt));
  for (PetscInt i = 0; i < nt; i++) {
    char     *end;
    long long v;
    errno = 0;
    v     = strtoll(tok[i], &end, 10);
    PetscCheck(!*end && end != tok[i], comm, PETSC_ERR_USER_INPUT, "%s '%s': entry %" PetscInt_FMT " '%s' is not an integer", name, str, i, tok[i]);
    PetscCheck(errno != ERANGE && v >= PETSC_MIN_INT && v <= PETSC_MAX_INT, comm, PETSC_ERR_USER_INPUT, "%s '%s': entry %" PetscInt_FMT " '%s' is out of range (%" PetscInt_FMT " to %" PetscInt_FMT ")", name, str, i, tok[i], (PetscInt)PETSC_MIN_INT, (PetscInt)PETSC_MAX_INT);
    vals[i] = (PetscInt)v;
  }
  *n = nt;
  PetscFunctionReturn(0);
}

/* -opt as a list of at most max reals (see SgOptionsIntList); inf and nan are read, the caller decides on them. */
PetscErrorCode SgOptionsRealList(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], PetscInt max, PetscReal vals[], PetscInt *n, PetscBool *set)
{
  char      def[2048] = "", str[4096], tok[SG_OPT_MAX][64];
  PetscInt  nt;
  PetscBool flg;

  MPI_Comm comm;
  char     name[256];

  PetscFunctionBeginUser;
  PetscCall(CheckReaderArgs(PetscOptionsObject, opt, max, vals, n, "SgOptionsRealList"));
  comm = PetscOptionsObject->comm;
  PetscCall(SgOptionsName(PetscOptionsObject->prefix, opt, name, sizeof(name)));
  for (PetscInt i = 0; i < *n; i++) {
    size_t l;
    PetscCall(PetscStrlen(def, &l));
    PetscCall(PetscSNPrintf(def + l, sizeof(def) - l, i ? ",%g" : "%g", (double)vals[i]));
  }
  PetscCall(PetscOptionsString(opt, text, NULL, def, str, sizeof(str), &flg));
  if (set) *set = flg;
  if (!flg) PetscFunctionReturn(0);
  PetscCall(SplitList(comm, name, str, max, tok, &nt));
  for (PetscInt i = 0; i < nt; i++) {
    char *end;
    vals[i] = (PetscReal)strtod(tok[i], &end);
    PetscCheck(!*end && end != tok[i], comm, PETSC_ERR_USER_INPUT, "%s '%s': entry %" PetscInt_FMT " '%s' is not a number", name, str, i, tok[i]);
  }
  *n = nt;
  PetscFunctionReturn(0);
}

/* A single real -opt (see SgOptionsIntList). */
PetscErrorCode SgOptionsRealValue(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], PetscReal *val, PetscBool *set)
{
  PetscInt n = 1;

  PetscFunctionBeginUser;
  SgValidPointer(val, 4);
  PetscCall(SgOptionsRealList(PetscOptionsObject, opt, text, 1, val, &n, set));
  PetscFunctionReturn(0);
}

/* A logical -opt as PETSc reads it (alone: true; true/false, yes/no, on/off, 1/0 in any case), but a bad value is
   reported with the option's name (PETSc says only "Unknown logical value"). */
PetscErrorCode SgOptionsBoolValue(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], PetscBool *val, PetscBool *set)
{
  static const char *const yes[] = {"", "true", "yes", "on", "1"}, *const no[] = {"false", "no", "off", "0"};
  char      str[256], name[256];
  PetscBool flg, match;

  PetscFunctionBeginUser;
  PetscCheck(PetscOptionsObject, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "SgOptionsBoolValue: argument 1 (PetscOptionsObject) is NULL: call it between PetscOptionsBegin and PetscOptionsEnd");
  PetscCheck(opt && opt[0], PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "SgOptionsBoolValue: argument 2 (the option's name) is NULL or empty");
  SgValidPointer(val, 4);
  PetscCall(SgOptionsName(PetscOptionsObject->prefix, opt, name, sizeof(name)));
  PetscCall(PetscOptionsString(opt, text, NULL, *val ? "true" : "false", str, sizeof(str), &flg));
  if (set) *set = flg;
  if (!flg) {
    /* PetscOptionsString reports a bare option as not set: look for the name itself */
    PetscCall(PetscOptionsHasName(PetscOptionsObject->options, PetscOptionsObject->prefix, opt, &flg));
    if (set) *set = flg;
    if (flg) *val = PETSC_TRUE;
    PetscFunctionReturn(0);
  }
  for (size_t k = 0; k < sizeof(yes) / sizeof(yes[0]); k++) {
    PetscCall(PetscStrcasecmp(str, yes[k], &match));
    if (match) {
      *val = PETSC_TRUE;
      PetscFunctionReturn(0);
    }
  }
  for (size_t k = 0; k < sizeof(no) / sizeof(no[0]); k++) {
    PetscCall(PetscStrcasecmp(str, no[k], &match));
    if (match) {
      *val = PETSC_FALSE;
      PetscFunctionReturn(0);
    }
  }
  SETERRQ(PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s '%s': not a logical value (true or false, yes or no, on or off, 1 or 0)", name, str);
}

/* A single integer -opt (see SgOptionsIntList). */
PetscErrorCode SgOptionsIntValue(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], PetscInt *val, PetscBool *set)
{
  PetscInt n = 1;

  PetscFunctionBeginUser;
  SgValidPointer(val, 4);
  PetscCall(SgOptionsIntList(PetscOptionsObject, opt, text, 1, val, &n, set));
  PetscFunctionReturn(0);
}


/* Renamed options: the new name and the old one, still accepted with a notice (PetscOptionsDeprecated; silenced by
   -options_suppress_deprecated_warnings). The old name's value goes through the same reader (the numbers are
   identical, and an error names the option as it was given). When both are given the old name wins, as with PETSc's
   own PetscOptionsDeprecated (which copies the old value over the new name): a command line of today with an old name
   keeps overriding an options file that uses the new one. *used: the name that set the value (the new one when
   neither did), for the caller's messages. */
static PetscErrorCode OldName(PetscOptionItems *PetscOptionsObject, const char newname[], const char oldname[], PetscBool *given)
{
  char text[256];

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasName(PetscOptionsObject->options, PetscOptionsObject->prefix, oldname, given));
  if (!*given) PetscFunctionReturn(0);
  PetscCall(PetscSNPrintf(text, sizeof(text), "Use -%s%s instead (the same meaning and value).", PetscOptionsObject->prefix ? PetscOptionsObject->prefix : "", newname + 1));
  PetscCall(PetscOptionsDeprecated(oldname, NULL, SG_DEPRECATED_IN, text));
  PetscFunctionReturn(0);
}

typedef PetscErrorCode (*Reader)(PetscOptionItems *, const char[], const char[], void *, PetscBool *);
static PetscErrorCode ReadReal(PetscOptionItems *o, const char opt[], const char text[], void *val, PetscBool *set) { return SgOptionsRealValue(o, opt, text, (PetscReal *)val, set); }
static PetscErrorCode ReadInt(PetscOptionItems *o, const char opt[], const char text[], void *val, PetscBool *set) { return SgOptionsIntValue(o, opt, text, (PetscInt *)val, set); }
static PetscErrorCode ReadBool(PetscOptionItems *o, const char opt[], const char text[], void *val, PetscBool *set) { return SgOptionsBoolValue(o, opt, text, (PetscBool *)val, set); }

static PetscErrorCode Renamed(PetscOptionItems *PetscOptionsObject, const char newname[], const char oldname[], const char text[], Reader read, void *val, const char **used)
{
  PetscBool old;

  PetscFunctionBeginUser;
  *used = newname;
  PetscCall(read(PetscOptionsObject, newname, text, val, NULL));
  PetscCall(OldName(PetscOptionsObject, newname, oldname, &old));
  if (old) {
    PetscCall(read(PetscOptionsObject, oldname, text, val, NULL));
    *used = oldname;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SgOptionsRealRenamed(PetscOptionItems *PetscOptionsObject, const char newname[], const char oldname[], const char text[], PetscReal *val, const char **used)
{
  PetscFunctionBeginUser;
  PetscCall(Renamed(PetscOptionsObject, newname, oldname, text, ReadReal, val, used));
  PetscFunctionReturn(0);
}

PetscErrorCode SgOptionsIntRenamed(PetscOptionItems *PetscOptionsObject, const char newname[], const char oldname[], const char text[], PetscInt *val, const char **used)
{
  PetscFunctionBeginUser;
  PetscCall(Renamed(PetscOptionsObject, newname, oldname, text, ReadInt, val, used));
  PetscFunctionReturn(0);
}

PetscErrorCode SgOptionsBoolRenamed(PetscOptionItems *PetscOptionsObject, const char newname[], const char oldname[], const char text[], PetscBool *val, const char **used)
{
  PetscFunctionBeginUser;
  PetscCall(Renamed(PetscOptionsObject, newname, oldname, text, ReadBool, val, used));
  PetscFunctionReturn(0);
}

/* Two bodies (-contact_master_ids) in 2D: the default solver's rule for the pair's direct limit SG_PAIR_DIRECT_MAX_2D,
   in one place for the solver (solver/linear.c) and the mesh's nested levels (fem/mesh.c, which must foresee it):
   *tx whether the SSN solves in the dual-mortar basis (-ssn_pair_transform, on unless false), *limited whether the limit
   applies on one rank (in the basis and frictionless: -friction_type unset or none; with friction one body's rule).
   A malformed value is an error (PETSc's reader's). */
PetscErrorCode SgOptionsPairDirectLimit2D(const char prefix[], PetscBool *tx, PetscBool *limited)
{
  char      law[64] = "";
  PetscBool fset;

  PetscFunctionBeginUser;
  *tx = PETSC_TRUE;
  PetscCall(PetscOptionsGetBool(NULL, prefix, "-ssn_pair_transform", tx, NULL));
  PetscCall(PetscOptionsGetString(NULL, prefix, "-friction_type", law, sizeof(law), &fset));
  *limited = (PetscBool)(*tx && (!fset || !strcmp(law, "none")));
  PetscFunctionReturn(0);
}
