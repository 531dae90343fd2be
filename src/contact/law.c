/* law.c: the contact law (registry: -friction_type, SgContactLawRegister). A law is the tangential part of the contact
   condition: none (frictionless), tresca (|lam_T| <= s), coulomb (|lam_T| <= F lam_N), or a caller's type. Each type
   owns its parameters (its options, its checks, its summary and checkpoint names) and supplies through its ops the
   bound g_i(lam_N) of |lam_T| at a contact vertex and its derivative in lam_N; the SSN, PDAS, the controllers and the
   output ask the law for them. What the law shares with every type: -friction_gamma_factor c (gamma_T = c gamma, the
   regularization of the tangential term in the SSN). The law owns its tangential state (the slip reference of its
   vertices, and each solver's SgContactLawState) and supplies the SSN's tangential terms through its ops
   (SgContactLawResidual etc.; law_regularized.c for a law with a bound, none for the frictionless law). */
#include "contact/contactimpl.h"

PetscFunctionList SgContactLawList = NULL;

/* ---- none: frictionless (no tangential term; the solvers keep their frictionless paths) */
static void Bound_None(SgContactLaw law, PetscInt i, PetscReal lamN, PetscReal *g, PetscReal *dg)
{
  (void)law;
  (void)i;
  (void)lamN;
  *g = 0;
  if (dg) *dg = 0;
}

static PetscErrorCode LawCreate_None(SgContactLaw law)
{
  PetscFunctionBeginUser;
  law->friction  = PETSC_FALSE;
  law->ops.bound = Bound_None; /* not asked (no tangential part), but defined */
  PetscFunctionReturn(0);
}

/* ---- tresca and coulomb: a law of one parameter p (its option, summary name, check and the bound from p) */
typedef struct {
  const char *option, *help, *name; /* "-friction_bound", its help, "friction_bound" (summary, checkpoint) */
  const char *bad, *missing, *desc; /* the messages for a bad value (%g) and a missing one; the description (%g) */
  PetscBool (*valid)(PetscReal);
  PetscReal p;
  PetscBool set;
} Law_One;

static PetscBool PositiveFinite(PetscReal v)
{
  return (PetscBool)(PetscIsNormalReal(v) && v > 0);
}

static PetscBool NonnegativeFinite(PetscReal v)
{
  return (PetscBool)((PetscIsNormalReal(v) || v == 0) && v >= 0);
}

/* tresca: g = s, a given traction */
static void Bound_Tresca(SgContactLaw law, PetscInt i, PetscReal lamN, PetscReal *g, PetscReal *dg)
{
  (void)i;
  (void)lamN;
  *g = ((Law_One *)law->data)->p;
  if (dg) *dg = 0;
}

/* coulomb: g = F max(0, lam_N), dg/dlam_N = F (the Jacobian's coupling t n^T: nonsymmetric) */
static void Bound_Coulomb(SgContactLaw law, PetscInt i, PetscReal lamN, PetscReal *g, PetscReal *dg)
{
  const PetscReal F = ((Law_One *)law->data)->p;

  (void)i;
  *g = F * PetscMax(0, lamN);
  if (dg) *dg = F;
}

static PetscErrorCode SetFromOptions_One(SgContactLaw law, PetscOptionItems *PetscOptionsObject)
{
  Law_One *o = (Law_One *)law->data;

  PetscFunctionBeginUser;
  PetscCall(SgOptionsRealValue(PetscOptionsObject, o->option, o->help, &o->p, &o->set));
  PetscCheck(!o->set || o->valid(o->p), law->comm, PETSC_ERR_USER_INPUT, o->bad, (double)o->p);
  PetscFunctionReturn(0);
}

static PetscErrorCode SetUp_One(SgContactLaw law)
{
  Law_One *o = (Law_One *)law->data;

  PetscFunctionBeginUser;
  PetscCheck(o->set, law->comm, PETSC_ERR_USER_INPUT, "%s", o->missing);
  PetscCall(PetscSNPrintf(law->desc, sizeof(law->desc), o->desc, (double)o->p));
  PetscFunctionReturn(0);
}

static PetscErrorCode GetParameters_One(SgContactLaw law, PetscInt *n, const char *const **names, const PetscReal **values)
{
  Law_One *o = (Law_One *)law->data;

  PetscFunctionBeginUser;
  *n      = 1;
  *names  = &o->name;
  *values = &o->p;
  PetscFunctionReturn(0);
}

static PetscErrorCode View_One(SgContactLaw law, PetscViewer v)
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(v, "%s friction: %s, gamma_T = %g gamma\n", law->type, law->desc, (double)law->gfac));
  PetscFunctionReturn(0);
}

static PetscErrorCode LawCreate_One(SgContactLaw law, const Law_One *def, void (*bound)(SgContactLaw, PetscInt, PetscReal, PetscReal *, PetscReal *), PetscBool coupled)
{
  Law_One *o;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&o));
  *o                      = *def;
  law->data               = o;
  law->friction           = PETSC_TRUE;
  law->coupled            = coupled;
  law->ops.bound          = bound;
  law->ops.setfromoptions = SetFromOptions_One;
  law->ops.setup          = SetUp_One;
  law->ops.getparameters  = GetParameters_One;
  law->ops.view           = View_One;
  PetscFunctionReturn(0);
}

static PetscErrorCode LawCreate_Tresca(SgContactLaw law)
{
  const Law_One def = {"-friction_bound", "Tresca friction bound s > 0: |lam_T| <= s (a traction)", "friction_bound", "-friction_bound: the Tresca bound must be positive and finite, got %g", "-friction_type tresca needs the bound: give -friction_bound s > 0", "Tresca s = %g", PositiveFinite, 0, PETSC_FALSE};

  PetscFunctionBeginUser;
  PetscCall(LawCreate_One(law, &def, Bound_Tresca, PETSC_FALSE));
  PetscFunctionReturn(0);
}

static PetscErrorCode LawCreate_Coulomb(SgContactLaw law)
{
  const Law_One def = {"-friction_coefficient", "Coulomb friction coefficient F >= 0: |lam_T| <= F lam_N", "friction_coefficient", "-friction_coefficient: the Coulomb coefficient must be finite and >= 0, got %g", "-friction_type coulomb needs the coefficient: give -friction_coefficient F >= 0", "Coulomb F = %g", NonnegativeFinite, 0, PETSC_FALSE};

  PetscFunctionBeginUser;
  PetscCall(LawCreate_One(law, &def, Bound_Coulomb, PETSC_TRUE));
  PetscFunctionReturn(0);
}

/* ---- the registry */
static PetscErrorCode SgContactLawFinalizePackage(void)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&SgContactLawList));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactLawRegisterAll(void)
{
  static PetscBool done = PETSC_FALSE;

  PetscFunctionBeginUser;
  if (done) PetscFunctionReturn(0);
  done = PETSC_TRUE;
  PetscCall(PetscRegisterFinalize(SgContactLawFinalizePackage));
  /* the order gives the built-in laws their numbers in checkpoints (0 none, 1 tresca, 2 coulomb) */
  PetscCall(SgContactLawRegister(SGLAWNONE, LawCreate_None));
  PetscCall(SgContactLawRegister(SGLAWTRESCA, LawCreate_Tresca));
  PetscCall(SgContactLawRegister(SGLAWCOULOMB, LawCreate_Coulomb));
  PetscFunctionReturn(0);
}

/* A law type of the caller's: create sets the ops and the flags of struct _n_SgContactLaw (contact/contactimpl.h). */
PetscErrorCode SgContactLawRegister(const char name[], PetscErrorCode (*create)(SgContactLaw))
{
  size_t len;

  PetscFunctionBeginUser;
  PetscCheck(name && name[0], PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "SgContactLawRegister: a type name is needed");
  SgValidPointer(create, 2);
  PetscCall(PetscStrlen(name, &len));
  PetscCheck(len < sizeof(((SgContactLaw)0)->type), PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "SgContactLawRegister: the type name has %zu characters, at most %zu", len, sizeof(((SgContactLaw)0)->type) - 1);
  PetscCall(SgContactLawRegisterAll()); /* ours first, so that a caller's type of the same name replaces ours */
  PetscCall(PetscFunctionListAdd(&SgContactLawList, name, create));
  PetscFunctionReturn(0);
}

/* The names of the registered laws as "none, tresca, coulomb, ..." for messages. */
static PetscErrorCode LawNames(char buf[], size_t len)
{
  const char **names;
  int          n;

  PetscFunctionBeginUser;
  buf[0] = 0;
  PetscCall(PetscFunctionListGet(SgContactLawList, &names, &n));
  for (int k = 0; k < n && names[k]; k++) { /* (PETSc counts the closing NULL in n) */
    if (k) PetscCall(PetscStrlcat(buf, ", ", len));
    PetscCall(PetscStrlcat(buf, names[k], len));
  }
  PetscCall(PetscFree(names));
  PetscFunctionReturn(0);
}

/* The law from the options (between the contact object's PetscOptionsBegin and End): -friction_type (default none),
   the type's own options, the common -friction_gamma_factor, the other types' options (read and checked, not kept),
   then the type's setup (what it needs). */
PetscErrorCode SgContactLawCreateFromOptions(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, PetscInt dim, SgContactLaw *out)
{
  SgContactLaw law;
  char         type[64] = SGLAWNONE, names[256];
  PetscBool    set;
  PetscErrorCode (*create)(SgContactLaw) = NULL;

  PetscFunctionBeginUser;
  PetscCall(SgContactLawRegisterAll());
  PetscCall(LawNames(names, sizeof(names)));
  PetscCall(PetscOptionsFList("-friction_type", "Friction law on the contact boundary: none, tresca (|lam_T| <= -friction_bound), coulomb (|lam_T| <= -friction_coefficient lam_N), or one of SgContactLawRegister", NULL, SgContactLawList, type, type, sizeof(type), &set));
  PetscCheck(!set || type[0], comm, PETSC_ERR_USER_INPUT, "-friction_type is given without a value (%s)", names);
  PetscCall(PetscFunctionListFind(SgContactLawList, type, &create));
  PetscCheck(create, comm, PETSC_ERR_USER_INPUT, "-friction_type: unknown friction law '%s' (%s)", type, names);
  PetscCall(PetscNew(&law));
  law->comm = comm;
  law->dim  = dim;
  law->gfac = 1;
  PetscCall(PetscStrncpy(law->type, type, sizeof(law->type)));
  PetscCall(PetscSNPrintf(law->desc, sizeof(law->desc), "friction law %s", type));
  {
    const char **all;
    int          n;
    PetscCall(PetscFunctionListGet(SgContactLawList, &all, &n));
    law->id = n;
    for (int k = 0; k < n && all[k]; k++)
      if (!strcmp(all[k], type)) law->id = k;
    PetscCall(PetscFree(all));
  }
  *out = law; /* the contact object's (SgContactDestroy) */
  PetscCall(create(law));
  PetscCheck(law->ops.bound, comm, PETSC_ERR_PLIB, "friction law %s: its create function set no bound op", type);
  if (law->ops.setfromoptions) PetscCall(law->ops.setfromoptions(law, PetscOptionsObject));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-friction_gamma_factor", "gamma_T = c gamma: the tangential regularization parameter against the normal one (c > 0)", &law->gfac, NULL));
  PetscCheck(PetscIsNormalReal(law->gfac) && law->gfac > 0, comm, PETSC_ERR_USER_INPUT, "-friction_gamma_factor: must be positive and finite, got %g", (double)law->gfac);
  /* the other types' options too, read into scratch laws and checked there: an option file of today (e.g. one with
     -friction_coefficient, run with -friction_type tresca) keeps working, a bad value is never silently ignored, and
     -help lists every type's options */
  {
    const char **all;
    int          n;
    PetscCall(PetscFunctionListGet(SgContactLawList, &all, &n));
    for (int k = 0; k < n && all[k]; k++) {
      SgContactLaw o;
      if (!strcmp(all[k], type)) continue;
      PetscCall(PetscNew(&o));
      o->comm = comm;
      o->dim  = dim;
      PetscCall(PetscStrncpy(o->type, all[k], sizeof(o->type)));
      PetscCall(PetscFunctionListFind(SgContactLawList, all[k], &create));
      PetscCall(create(o));
      if (o->ops.setfromoptions) PetscCall(o->ops.setfromoptions(o, PetscOptionsObject));
      PetscCall(SgContactLawDestroy(&o));
    }
    PetscCall(PetscFree(all));
  }
  if (law->ops.setup) PetscCall(law->ops.setup(law));
  if (law->friction) PetscCall(SgContactLawSetRegularizedOps(law)); /* the terms the type does not set itself */
  if (law->friction) PetscCall(SgContactLawSetMeasureOps(law));     /* and its measures, fields and summary keys */
  if (law->friction) PetscCall(SgContactLawSetPdasOps(law));        /* and its part of PDAS (law_pdas.c) */
  PetscFunctionReturn(0);
}

/* the owned contact vertices (n) and their coordinates (n dim, kept by the contact object): a law may depend on x;
   with a tangential part the law (re)allocates its slip reference for them (zeros: the first load step's start) */
PetscErrorCode SgContactLawSetVertices(SgContactLaw law, PetscInt n, const PetscReal x[])
{
  PetscFunctionBeginUser;
  if (law->friction && (!law->yref || n != law->n)) {
    PetscCall(PetscFree(law->yref));
    PetscCall(PetscCalloc1(2 * n * law->dim + 1, &law->yref));
  }
  law->n = n;
  law->x = x;
  PetscFunctionReturn(0);
}

/* the slip reference (SgContactLawSetVertices): the unknowns' part (n dim), then the full displacement's (n dim) */
PetscErrorCode SgContactLawGetSlipReference(SgContactLaw law, PetscReal **yref)
{
  PetscFunctionBeginUser;
  *yref = law->yref;
  PetscFunctionReturn(0);
}

/* A solver's tangential state over the law's vertices (after SgContactLawSetVertices): zeros; no arrays without a
   tangential part */
PetscErrorCode SgContactLawStateCreate(SgContactLaw law, SgContactLawState *st)
{
  SgContactLawState t;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&t));
  if (law->friction) {
    t->n   = law->n;
    t->dim = law->dim;
    PetscCall(PetscCalloc2(t->n * t->dim, &t->lamhatT, t->n * t->dim, &t->lamT));
    PetscCall(PetscCalloc3(t->n, &t->state, t->n, &t->statejac, t->n * t->dim, &t->tjac));
  }
  *st = t;
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactLawStateGetArrays(SgContactLawState st, PetscReal **lamhatT, PetscReal **lamT, char **state)
{
  PetscFunctionBeginUser;
  if (lamhatT) *lamhatT = st->lamhatT;
  if (lamT) *lamT = st->lamT;
  if (state) *state = st->state;
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactLawStateGetJacobianArrays(SgContactLawState st, char **statejac, PetscReal **tjac)
{
  PetscFunctionBeginUser;
  if (statejac) *statejac = st->statejac;
  if (tjac) *tjac = st->tjac;
  PetscFunctionReturn(0);
}

/* the number of values of its slip reference: 2 n dim with a tangential part (of the unknowns, then of the full
   displacement), else 0 */
PetscErrorCode SgContactLawGetSlipReferenceSize(SgContactLaw law, PetscInt *m)
{
  PetscFunctionBeginUser;
  *m = law && law->yref ? 2 * law->n * law->dim : 0;
  PetscFunctionReturn(0);
}

/* the tangential shift lamhat_T: zero (the start of a path), or the last multiplier lam_T (ALM's update
   lamhat_T = P_g(lamhat_T + gamma_T T y)); nothing without a tangential part (no arrays) */
PetscErrorCode SgContactLawStateZeroShift(SgContactLawState st)
{
  PetscFunctionBeginUser;
  if (st) PetscCall(PetscArrayzero(st->lamhatT, st->n * st->dim));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactLawStateAcceptShift(SgContactLawState st)
{
  PetscFunctionBeginUser;
  if (st) PetscCall(PetscArraycpy(st->lamhatT, st->lamT, st->n * st->dim));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactLawStateDestroy(SgContactLawState *st)
{
  PetscFunctionBeginUser;
  if (!*st) PetscFunctionReturn(0);
  PetscCall(PetscFree2((*st)->lamhatT, (*st)->lamT));
  PetscCall(PetscFree3((*st)->state, (*st)->statejac, (*st)->tjac));
  PetscCall(PetscFree(*st));
  PetscFunctionReturn(0);
}

/* The bound g of |lam_T| at owned contact vertex i for the normal multiplier lamN and, if dg is not NULL, dg/dlam_N
   (0 for a law whose bound does not depend on lam_N). A pointwise kernel: no errors. */
void SgContactLawBound(SgContactLaw law, PetscInt i, PetscReal lamN, PetscReal *g, PetscReal *dg)
{
  law->ops.bound(law, i, lamN, g, dg);
}

/* The largest bound over all contact vertices (collective) with the normal multiplier lamN at each */
PetscErrorCode SgContactLawBoundMax(SgContactLaw law, PetscReal lamN, PetscReal *gmax)
{
  PetscReal g = 0, gi;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < law->n; i++) {
    law->ops.bound(law, i, lamN, &gi, NULL);
    g = PetscMax(g, gi);
  }
  PetscCallMPI(MPI_Allreduce(&g, gmax, 1, MPIU_REAL, MPIU_MAX, law->comm));
  PetscFunctionReturn(0);
}

/* The law's tangential terms in the SSN (its ops; nothing without a tangential part, where st has no arrays, or
   without a law: no contact boundary) */
PetscErrorCode SgContactLawResidual(SgContactLaw law, SgContactLawInput *in, SgContactLawState st, const PetscScalar ya[], const PetscReal mN[], PetscScalar fa[], PetscReal loc[6])
{
  PetscFunctionBeginUser;
  if (law && law->ops.residual) PetscCall(law->ops.residual(law, in, st, ya, mN, fa, loc));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactLawJacobian(SgContactLaw law, SgContactLawInput *in, SgContactLawState st, const PetscScalar ya[], const PetscScalar fa[], Mat P)
{
  PetscFunctionBeginUser;
  in->nforce = 0;
  if (law && law->ops.jacobian) PetscCall(law->ops.jacobian(law, in, st, ya, fa, P));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactLawStepCorrection(SgContactLaw law, SgContactLawInput *in, SgContactLawState st, const PetscScalar xa[], PetscReal ft[])
{
  PetscFunctionBeginUser;
  if (law && law->ops.stepcorrection) PetscCall(law->ops.stepcorrection(law, in, st, xa, ft));
  PetscFunctionReturn(0);
}

PetscReal SgContactLawFloor(SgContactLaw law, const SgContactLawInput *in, SgContactLawState st, const PetscScalar ya[], PetscInt i, PetscBool equil)
{
  return law && law->ops.floor ? law->ops.floor(law, in, st, ya, i, equil) : 0;
}

/* The law's limit of gamma in double precision (SgContGammaPrecision), lowering *gdp (collective): with the largest
   multiplier lammax and the largest displacement ymax at the active vertices, the regularized tangential term's
   round-off gamma_T eps ymax must stay below 1e-2 of the largest bound. A state decided on round-off changes a
   friction force by at most its bound, so a bound below 1e-2 of the largest multiplier (Coulomb with F = 1e-12) is held
   to the normal multipliers' margin instead: otherwise the cap would stop a path whose friction cannot matter. Nothing
   without a tangential part. */
PetscErrorCode SgContactLawGammaPrecision(SgContactLaw law, PetscReal lammax, PetscReal ymax, PetscReal *gdp)
{
  PetscReal gb;

  PetscFunctionBeginUser;
  if (!law || !law->friction || !(ymax > 0)) PetscFunctionReturn(0);
  PetscCall(SgContactLawBoundMax(law, lammax, &gb)); /* max_i g_i(max lam): s (Tresca), F max lam (Coulomb) */
  gb = PetscMax(gb, 1e-2 * lammax);
  if (gb > 0) *gdp = PetscMin(*gdp, 1e-2 * gb / (law->gfac * PETSC_MACHINE_EPSILON * ymax));
  PetscFunctionReturn(0);
}

/* The law's part of SgContactKKT (the op kkt; nothing without it: the frictionless law) */
PetscErrorCode SgContactLawKKT(SgContactLaw law, SgContact c, Vec y, PetscScalar ra[], const PetscReal lam[], PetscReal ynrm, const KKTScales *sc, PetscReal *slip2)
{
  PetscFunctionBeginUser;
  *slip2 = 0;
  if (law->ops.kkt) PetscCall(law->ops.kkt(law, c, y, ra, lam, ynrm, sc, slip2));
  PetscFunctionReturn(0);
}

/* the contact force on the body at a vertex for the KKT's force scale (the op contactforce; without it the normal
   force rn n, of size wlam = w |lam|) */
PetscReal SgContactLawContactForce(SgContactLaw law, PetscInt dim, const PetscScalar r[], const PetscReal n[], PetscReal rn, PetscReal wlam, PetscReal f[])
{
  if (law->ops.contactforce) return law->ops.contactforce(law, dim, r, n, rn, wlam, f);
  for (PetscInt k = 0; k < dim; k++) f[k] = rn * n[k];
  return wlam;
}

/* The law's output fields: their number (at most SG_LAW_MAX_FIELDS), names and whether each is a vector (dim per
   vertex) or a scalar field; none without the op */
PetscErrorCode SgContactLawGetFields(SgContactLaw law, PetscInt *n, const char *const **names, const PetscBool **vector)
{
  PetscFunctionBeginUser;
  *n = 0;
  if (names) *names = NULL;
  if (vector) *vector = NULL;
  if (law && law->ops.getfields) {
    const char *const *nm;
    const PetscBool   *vec;
    PetscCall(law->ops.getfields(law, n, &nm, &vec));
    PetscCheck(*n >= 0 && *n <= SG_LAW_MAX_FIELDS, law->comm, PETSC_ERR_SUP, "friction law %s: %" PetscInt_FMT " output fields, at most %d", law->type, *n, SG_LAW_MAX_FIELDS);
    if (names) *names = nm;
    if (vector) *vector = vec;
  }
  PetscFunctionReturn(0);
}

/* their values at the contact object's record (SgContactLawFields in contact.c makes it at y first) */
PetscErrorCode SgContactLawFillFields(SgContactLaw law, SgContact c, Vec fields[])
{
  PetscFunctionBeginUser;
  if (law->ops.fields) PetscCall(law->ops.fields(law, c, fields));
  PetscFunctionReturn(0);
}

/* The law's summary keys of a solve (fs: the last SgContactKKT's summary) and per load step (n steps); none without
   the ops (the frictionless law) */
PetscErrorCode SgContactLawSummary(SgContactLaw law, PetscInt dim, const SgFrictionSummary *fs, SgContactLawKeys *sum)
{
  PetscFunctionBeginUser;
  if (law && law->ops.summary) PetscCall(law->ops.summary(law, dim, fs, sum));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactLawStepSummary(SgContactLaw law, PetscInt n, const SgFrictionSummary fs[], SgContactLawKeys *sum)
{
  PetscFunctionBeginUser;
  if (law && law->ops.stepsummary) PetscCall(law->ops.stepsummary(law, n, fs, sum));
  PetscFunctionReturn(0);
}

/* The checkpoint's part of the law: its number in the registry (friction_type, 0 without friction or a law), its
   parameters by their names and, with a tangential part, its state (the op save) */
PetscErrorCode SgContactLawSave(SgContactLaw law, const PetscReal lamhatT[], const PetscReal yref[], SgContactLawWriter *w)
{
  PetscInt    id = 0, np = 0;
  const char *pn[SG_LAW_MAX_PARAMETERS];
  PetscReal   pv[SG_LAW_MAX_PARAMETERS];

  PetscFunctionBeginUser;
  if (!law || !law->friction) PetscFunctionReturn(0);
  PetscCall(SgContactLawGetId(law, &id)); /* the law's number in the registry, its parameters by their names */
  PetscCall(SgContactLawGetParameters(law, &np, pn, pv));
  if (law->ops.save) PetscCall(law->ops.save(law, lamhatT, yref, w));
  PetscCall(w->attribute(w->ctx, "friction_type", PETSC_INT, &id));
  for (PetscInt i = 0; i < np; i++) PetscCall(w->attribute(w->ctx, pn[i], PETSC_REAL, &pv[i]));
  PetscFunctionReturn(0);
}

/* The law of the file must be this one (law NULL: no contact boundary, as none), with the same parameters (a restart
   solves the same problem); then its state, into lamhatT (NULL: not kept) and yref. *full: the file held the full
   displacement's slip reference. */
PetscErrorCode SgContactLawLoad(SgContactLaw law, MPI_Comm comm, PetscReal lamhatT[], PetscReal yref[], SgContactLawReader *r, PetscBool *full)
{
  PetscInt    now = 0, id = 0, np = 0;
  const char *pn[SG_LAW_MAX_PARAMETERS], *name = NULL, *nowname = SGLAWNONE;
  PetscReal   pv[SG_LAW_MAX_PARAMETERS], fp;
  PetscBool   has, ok;
  char        f[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  *full = PETSC_FALSE;
  if (law) {
    nowname = law->type;
    if (law->friction) now = law->id;
    PetscCall(SgContactLawGetParameters(law, &np, pn, pv));
  }
  PetscCall(PetscStrncpy(f, r->file, sizeof(f))); /* (the reader's, freed by abandon) */
  PetscCall(r->hasattribute(r->ctx, "friction_type", &has));
  if (has) PetscCall(r->attribute(r->ctx, "friction_type", PETSC_INT, &id));
  ok = (PetscBool)(id == now);
  if (!ok) {
    PetscCall(SgContactLawGetTypeName(id, &name));
    PetscCall(r->abandon(r->ctx));
  }
  PetscCheck(ok, comm, PETSC_ERR_USER_INPUT, "-restart_file: '%s' was written with -friction_type %s, this run has -friction_type %s", f, name ? name : "(damaged)", nowname);
  for (PetscInt i = 0; now && i < np; i++) { /* the law's parameters, by the names it gives them */
    PetscCall(r->attribute(r->ctx, pn[i], PETSC_REAL, &fp));
    ok = (PetscBool)(PetscAbsReal(pv[i] - fp) <= 1e-12 * PetscMax(PetscAbsReal(pv[i]), PetscAbsReal(fp)));
    if (!ok) PetscCall(r->abandon(r->ctx));
    PetscCheck(ok, comm, PETSC_ERR_USER_INPUT, "-restart_file: '%s' was written for another problem: -%s differs (%.17g in the checkpoint, %.17g in this run); a restart must solve the same problem", f, pn[i], (double)fp, (double)pv[i]);
  }
  if (now && law->ops.load) PetscCall(law->ops.load(law, lamhatT, yref, r, full));
  PetscFunctionReturn(0);
}

/* The checkpoint's summaries of the finished load steps (the op stepsave; nothing without a law or the op) */
PetscErrorCode SgContactLawStepSave(SgContactLaw law, PetscInt n, const SgFrictionSummary fs[], SgContactLawWriter *w)
{
  PetscFunctionBeginUser;
  if (law && law->ops.stepsave) PetscCall(law->ops.stepsave(law, n, fs, w));
  PetscFunctionReturn(0);
}

/* and back (the op stepload): fs starts with zero counts and NaN sizes, which stay where the file holds none */
PetscErrorCode SgContactLawStepLoad(SgContactLaw law, PetscInt n, SgFrictionSummary fs[], SgContactLawReader *r)
{
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < n; k++) {
    PetscCall(PetscMemzero(&fs[k], sizeof(fs[k])));
    fs[k].force_norm = fs[k].traction = SG_NAN;
  }
  if (law && law->ops.stepload) PetscCall(law->ops.stepload(law, n, fs, r));
  PetscFunctionReturn(0);
}

/* Nested iteration: the numbers per contact vertex a finer level starts from (the op transfersize; 0 without it) */
PetscErrorCode SgContactLawTransferSize(SgContactLaw law, PetscInt *bs, PetscBool *vector)
{
  PetscFunctionBeginUser;
  *bs     = 0;
  *vector = PETSC_FALSE;
  if (law && law->ops.transfersize) PetscCall(law->ops.transfersize(law, bs, vector));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactLawTransferPack(SgContactLaw law, SgContactLawState st, PetscReal vals[])
{
  PetscFunctionBeginUser;
  if (law && law->ops.transferpack) PetscCall(law->ops.transferpack(law, st, vals));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactLawTransferUnpack(SgContactLaw law, SgContactLawState st, const PetscReal vals[])
{
  PetscFunctionBeginUser;
  if (law && st && law->ops.transferunpack) PetscCall(law->ops.transferunpack(law, st, vals));
  PetscFunctionReturn(0);
}

const char *SgLawName(SgContactLaw law)
{
  return law->type;
}

PetscErrorCode SgContactLawGetType(SgContactLaw law, const char *type[])
{
  PetscFunctionBeginUser;
  *type = law->type;
  PetscFunctionReturn(0);
}

/* the number of the type in the registry (0 none, 1 tresca, 2 coulomb, then the caller's in the order registered) */
PetscErrorCode SgContactLawGetId(SgContactLaw law, PetscInt *id)
{
  PetscFunctionBeginUser;
  *id = law->id;
  PetscFunctionReturn(0);
}

/* the name of the law of number id (NULL if there is none) */
PetscErrorCode SgContactLawGetTypeName(PetscInt id, const char **name)
{
  const char **all;
  int          n;

  PetscFunctionBeginUser;
  *name = NULL;
  PetscCall(SgContactLawRegisterAll());
  PetscCall(PetscFunctionListGet(SgContactLawList, &all, &n));
  for (int k = 0; k < n && all[k]; k++)
    if (k == id) *name = all[k]; /* the list's strings live as long as the registry */
  PetscCall(PetscFree(all));
  PetscFunctionReturn(0);
}

/* friction: the law has a tangential part; coupled: its bound depends on the normal multiplier (nonsymmetric
   Jacobians); gfac: gamma_T / gamma */
PetscErrorCode SgContactLawGetInfo(SgContactLaw law, PetscBool *friction, PetscBool *coupled, PetscReal *gfac)
{
  PetscFunctionBeginUser;
  if (friction) *friction = law->friction;
  if (coupled) *coupled = law->coupled;
  if (gfac) *gfac = law->gfac;
  PetscFunctionReturn(0);
}

/* What the solvers ask of the law: the properties that follow from its flags (a tangential part is nonlinear on fixed
   sets and dissipates; a bound from lam_N makes the Jacobians nonsymmetric), then the type's own (ops.getproperties) */
PetscErrorCode SgContactLawGetProperties(SgContactLaw law, SgContactLawProperties *p)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(p, sizeof(*p)));
  if (!law) PetscFunctionReturn(0);
  p->tangential  = law->friction;
  p->nonlinear   = law->friction;
  p->coupled     = law->coupled;
  p->dissipative = law->friction;
  if (law->ops.getproperties) PetscCall(law->ops.getproperties(law, p));
  PetscFunctionReturn(0);
}

/* the law's own parameters, by their summary and checkpoint names (friction_bound, friction_coefficient, ...), then
   friction_gamma_factor: at most SG_LAW_MAX_PARAMETERS */
PetscErrorCode SgContactLawGetParameters(SgContactLaw law, PetscInt *n, const char *names[], PetscReal values[])
{
  PetscInt           m = 0;
  const char *const *nm;
  const PetscReal   *v;

  PetscFunctionBeginUser;
  if (law->ops.getparameters) PetscCall(law->ops.getparameters(law, &m, &nm, &v));
  PetscCheck(m < SG_LAW_MAX_PARAMETERS, law->comm, PETSC_ERR_SUP, "friction law %s: %" PetscInt_FMT " parameters, at most %d", law->type, m, SG_LAW_MAX_PARAMETERS - 1);
  for (PetscInt k = 0; k < m; k++) {
    names[k]  = nm[k];
    values[k] = v[k];
  }
  names[m]  = "friction_gamma_factor";
  values[m] = law->gfac;
  *n        = m + 1;
  PetscFunctionReturn(0);
}

/* a short description with the parameters for messages ("Coulomb F = 0.3") */
PetscErrorCode SgContactLawGetDescription(SgContactLaw law, const char **desc)
{
  PetscFunctionBeginUser;
  *desc = law->desc;
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactLawView(SgContactLaw law, PetscViewer v)
{
  PetscFunctionBeginUser;
  if (law->ops.view) PetscCall(law->ops.view(law, v));
  else if (law->friction) PetscCall(PetscViewerASCIIPrintf(v, "friction law %s, gamma_T = %g gamma\n", law->type, (double)law->gfac));
  else PetscCall(PetscViewerASCIIPrintf(v, "frictionless (friction law %s)\n", law->type));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactLawDestroy(SgContactLaw *law)
{
  PetscFunctionBeginUser;
  if (!*law) PetscFunctionReturn(0);
  if ((*law)->ops.destroy) PetscCall((*law)->ops.destroy(*law));
  PetscCall(PetscFree((*law)->data));
  PetscCall(PetscFree((*law)->yref));
  PetscCall(PetscFree(*law));
  PetscFunctionReturn(0);
}
