/* obstacle.c: rigid obstacles (registry): the gap d(x) measured from a boundary point along its outward normal. */
#include "contact/contactimpl.h"

PetscFunctionList SgObstacleList = NULL;

static PetscErrorCode CheckFinite(MPI_Comm comm, const char opt[], PetscInt n, const PetscReal v[])
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n; i++) PetscCheck(PetscIsNormalReal(v[i]) || v[i] == 0, comm, PETSC_ERR_USER_INPUT, "%s: entry %" PetscInt_FMT " is %g, must be finite", opt, i, (double)v[i]);
  PetscFunctionReturn(0);
}

static PetscErrorCode ReadVector(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char opt[], const char text[], PetscInt dim, PetscReal v[])
{
  PetscInt  n = dim;
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(SgOptionsRealList(PetscOptionsObject, opt, text, dim, v, &n, &set));
  PetscCheck(!set || n == dim, comm, PETSC_ERR_USER_INPUT, "%s: got %" PetscInt_FMT " numbers, need %" PetscInt_FMT, opt, n, dim);
  PetscCall(CheckFinite(comm, opt, dim, v));
  PetscFunctionReturn(0);
}

/* ---- plane: the surface through point p with unit normal m (pointing towards the body) */
static PetscErrorCode Gap_Plane(SgObstacle o, const PetscReal x[], const PetscReal n[], PetscReal *d)
{
  const PetscReal *p = o->p, *m = o->p + 3;
  PetscReal        num = 0, den = 0;

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < o->dim; k++) {
    num += (p[k] - x[k]) * m[k];
    den += n[k] * m[k];
  }
  /* the ray x + t n meets the plane at t = num/den; a normal parallel to the plane never meets it */
  *d = den < -1e-12 ? num / den : PETSC_MAX_REAL;
  PetscFunctionReturn(0);
}

static PetscErrorCode SetFromOptions_Plane(SgObstacle o, PetscOptionItems *PetscOptionsObject)
{
  PetscReal nrm = 0;

  PetscFunctionBeginUser;
  o->p[3 + o->dim - 1] = 1; /* default: the plane x_dim = 0 below the body */
  PetscCall(ReadVector(PetscOptionsObject, o->comm, "-obstacle_plane_point", "A point of the obstacle plane", o->dim, o->p));
  PetscCall(ReadVector(PetscOptionsObject, o->comm, "-obstacle_plane_normal", "Normal of the obstacle plane, pointing towards the body", o->dim, o->p + 3));
  for (PetscInt k = 0; k < o->dim; k++) nrm += o->p[3 + k] * o->p[3 + k];
  PetscCheck(nrm > 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_plane_normal: the normal must be nonzero");
  for (PetscInt k = 0; k < o->dim; k++) o->p[3 + k] /= PetscSqrtReal(nrm);
  PetscFunctionReturn(0);
}

/* the signed distance (x - p).m and the plane's normal m */
static PetscErrorCode Distance_Plane(SgObstacle o, const PetscReal x[], PetscReal *g, PetscReal n[])
{
  const PetscReal *p = o->p, *m = o->p + 3;

  PetscFunctionBeginUser;
  *g = 0;
  for (PetscInt k = 0; k < o->dim; k++) {
    *g += (x[k] - p[k]) * m[k];
    n[k] = m[k];
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SgObstacleCreate_Plane(SgObstacle o)
{
  PetscFunctionBeginUser;
  o->gap            = Gap_Plane;
  o->distance       = Distance_Plane;
  o->setfromoptions = SetFromOptions_Plane;
  PetscFunctionReturn(0);
}

/* ---- parabola: d = a |x_t - c_t|^2 + offset, x_t the tangential part (Example 1: 0.003 (x1 - 1.5)^2 + 0.001) */
static PetscErrorCode Gap_Parabola(SgObstacle o, const PetscReal x[], const PetscReal n[], PetscReal *d)
{
  const PetscReal a = o->p[0], off = o->p[1], *c = o->p + 2;
  PetscReal       r[3], rn = 0, rt2 = 0;

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < o->dim; k++) {
    r[k] = x[k] - c[k];
    rn += r[k] * n[k];
  }
  for (PetscInt k = 0; k < o->dim; k++) rt2 += PetscSqr(r[k] - rn * n[k]);
  *d = a * rt2 + off;
  PetscFunctionReturn(0);
}

/* The parabola's distance (-contact_normal obstacle), consistent with its gap on a flat face: the gap says that the
   obstacle lies a |x_t - c_t|^2 + offset below a vertex x of a flat face with the normal -u (u = -obstacle_parabola_up,
   default e_dim), i.e. it is the surface z.u = x.u - offset - a |z_t - c_t|^2 (z_t, x_t the parts normal to u), the
   face's height x.u taken from the vertex itself (as the gap takes it; the centre's component along u is ignored).
   Its closest point to x lies at the radius rho in [0, r], r = |x_t - c_t|, the root of 2 a^2 rho^3 + (1 + 2 a off)
   rho - r = 0 (increasing and convex for rho >= 0: Newton from the root of its linear part converges from the right);
   there x - z = (off + a rho^2) (u + 2 a rho e_r), along the surface's normal. Every x has a unique closest point. */
static PetscErrorCode Distance_Parabola(SgObstacle o, const PetscReal x[], PetscReal *g, PetscReal n[])
{
  const PetscReal a = o->p[0], off = o->p[1], *c = o->p + 2, *u = o->p + 5, b = 1 + 2 * a * off;
  PetscReal       rt[3], ru = 0, r = 0, rho, h, s = 0;

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < o->dim; k++) ru += (x[k] - c[k]) * u[k];
  for (PetscInt k = 0; k < o->dim; k++) {
    rt[k] = x[k] - c[k] - ru * u[k];
    r += rt[k] * rt[k];
  }
  r   = PetscSqrtReal(r);
  rho = r / b;
  for (PetscInt it = 0; it < 100 && rho > 0; it++) {
    const PetscReal f = (2 * a * a * rho * rho + b) * rho - r, step = f / (6 * a * a * rho * rho + b);
    rho -= step;
    if (PetscAbsReal(step) <= 1e-15 * rho) break;
  }
  rho = PetscMax(0, PetscMin(r, rho));
  h   = off + a * rho * rho;
  for (PetscInt k = 0; k < o->dim; k++) {
    n[k] = u[k] + (r > 0 ? 2 * a * rho * rt[k] / r : 0);
    s += n[k] * n[k];
  }
  s = PetscSqrtReal(s);
  for (PetscInt k = 0; k < o->dim; k++) n[k] /= s;
  *g = h * s;
  PetscFunctionReturn(0);
}

static PetscErrorCode SetFromOptions_Parabola(SgObstacle o, PetscOptionItems *PetscOptionsObject)
{
  PetscReal nrm = 0;

  PetscFunctionBeginUser;
  o->p[5 + o->dim - 1] = 1;
  o->p[0]              = 0.003;
  o->p[1]              = 0.001;
  o->p[2]              = 1.5;
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-obstacle_parabola_a", "Curvature coefficient a of d = a |x_t - c_t|^2 + offset", &o->p[0], NULL));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-obstacle_parabola_offset", "Gap at the vertex of the parabola", &o->p[1], NULL));
  PetscCall(ReadVector(PetscOptionsObject, o->comm, "-obstacle_parabola_center", "Vertex of the parabola (its normal component is ignored)", o->dim, o->p + 2));
  PetscCheck(PetscIsNormalReal(o->p[0]) || o->p[0] == 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_parabola_a: must be finite, got %g", (double)o->p[0]);
  PetscCheck(o->p[0] >= 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_parabola_a: must be >= 0 (an obstacle bending away from the body), got %g", (double)o->p[0]);
  PetscCheck((PetscIsNormalReal(o->p[1]) || o->p[1] == 0) && o->p[1] >= 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_parabola_offset: the initial gap must be finite and >= 0, got %g", (double)o->p[1]);
  PetscCall(ReadVector(PetscOptionsObject, o->comm, "-obstacle_parabola_up", "Direction from the parabola towards the body, for -contact_normal obstacle (the gap along the body's normal does not need it)", o->dim, o->p + 5));
  for (PetscInt k = 0; k < o->dim; k++) nrm += o->p[5 + k] * o->p[5 + k];
  PetscCheck(nrm > 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_parabola_up: the direction must be nonzero");
  for (PetscInt k = 0; k < o->dim; k++) o->p[5 + k] /= PetscSqrtReal(nrm);
  PetscFunctionReturn(0);
}

PetscErrorCode SgObstacleCreate_Parabola(SgObstacle o)
{
  PetscFunctionBeginUser;
  o->gap            = Gap_Parabola;
  o->distance       = Distance_Parabola;
  o->setfromoptions = SetFromOptions_Parabola;
  PetscFunctionReturn(0);
}

/* ---- ball: the half-ball {|z - c| <= R, (z - c).u >= 0} (flat side down for u = e_dim) standing on the
   plane (z - c).u = 0, which is the obstacle away from the ball (Example 2: c = (-0.3,0,-1), R = 0.5). */
static PetscErrorCode Gap_Ball(SgObstacle o, const PetscReal x[], const PetscReal n[], PetscReal *d)
{
  const PetscReal R = o->p[0], *c = o->p + 1, *u = o->p + 4;
  PetscReal       xc[3], b = 0, xc2 = 0, nu = 0, disc, t;

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < o->dim; k++) {
    xc[k] = x[k] - c[k];
    b += n[k] * xc[k];
    xc2 += xc[k] * xc[k];
    nu += n[k] * u[k];
  }
  /* first intersection of the ray x + t n with the sphere, kept if it lies on the upper half */
  disc = b * b - (xc2 - R * R);
  if (disc >= 0) {
    PetscReal h = 0;
    t           = -b - PetscSqrtReal(disc);
    for (PetscInt k = 0; k < o->dim; k++) h += (xc[k] + t * n[k]) * u[k];
    if (h >= 0) {
      *d = t;
      PetscFunctionReturn(0);
    }
  }
  if (nu < -1e-12) {
    PetscReal num = 0;
    for (PetscInt k = 0; k < o->dim; k++) num -= xc[k] * u[k];
    *d = num / nu;
  } else *d = PETSC_MAX_REAL;
  PetscFunctionReturn(0);
}

/* The half-ball's signed distance: that of the union of the ball and the half-space below its flat side, the smaller
   of |x - c| - R and (x - c).u (exact outside, where the closest point of the upper half-sphere is the one of the
   sphere; inside the deeper of the two). At the centre the closest point is not unique: an error. */
static PetscErrorCode Distance_Ball(SgObstacle o, const PetscReal x[], PetscReal *g, PetscReal n[])
{
  const PetscReal R = o->p[0], *c = o->p + 1, *u = o->p + 4;
  PetscReal       r = 0, h = 0;

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < o->dim; k++) {
    r += PetscSqr(x[k] - c[k]);
    h += (x[k] - c[k]) * u[k];
  }
  r = PetscSqrtReal(r);
  if (h < r - R) {
    *g = h;
    for (PetscInt k = 0; k < o->dim; k++) n[k] = u[k];
    PetscFunctionReturn(0);
  }
  PetscCheck(r > 1e-10 * R, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "-contact_normal obstacle: the contact vertex at (%g, %g, %g) lies at the centre of the ball (-obstacle_ball_center): its closest point on the obstacle is not unique, so the obstacle's normal is undefined there", (double)x[0], (double)x[1], (double)(o->dim == 3 ? x[2] : 0));
  *g = r - R;
  for (PetscInt k = 0; k < o->dim; k++) n[k] = (x[k] - c[k]) / r;
  PetscFunctionReturn(0);
}

static PetscErrorCode SetFromOptions_Ball(SgObstacle o, PetscOptionItems *PetscOptionsObject)
{
  PetscReal nrm = 0;

  PetscFunctionBeginUser;
  o->p[0]              = 0.5;
  o->p[4 + o->dim - 1] = 1;
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-obstacle_ball_radius", "Radius of the half-ball", &o->p[0], NULL));
  PetscCall(ReadVector(PetscOptionsObject, o->comm, "-obstacle_ball_center", "Centre of the half-ball (on its flat side)", o->dim, o->p + 1));
  PetscCall(ReadVector(PetscOptionsObject, o->comm, "-obstacle_ball_up", "Direction from the flat side towards the body", o->dim, o->p + 4));
  PetscCheck(PetscIsNormalReal(o->p[0]) && o->p[0] > 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_ball_radius: must be positive and finite, got %g", (double)o->p[0]);
  for (PetscInt k = 0; k < o->dim; k++) nrm += o->p[4 + k] * o->p[4 + k];
  PetscCheck(nrm > 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_ball_up: the direction must be nonzero");
  for (PetscInt k = 0; k < o->dim; k++) o->p[4 + k] /= PetscSqrtReal(nrm);
  PetscFunctionReturn(0);
}

PetscErrorCode SgObstacleCreate_Ball(SgObstacle o)
{
  PetscFunctionBeginUser;
  o->gap            = Gap_Ball;
  o->distance       = Distance_Ball;
  o->setfromoptions = SetFromOptions_Ball;
  PetscFunctionReturn(0);
}

PetscErrorCode SgObstacleRegister(const char name[], PetscErrorCode (*create)(SgObstacle))
{
  size_t len;

  PetscFunctionBeginUser;
  PetscCheck(name && name[0], PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "SgObstacleRegister: a type name is needed");
  SgValidPointer(create, 2);
  PetscCall(PetscStrlen(name, &len));
  PetscCheck(len < sizeof(((SgObstacle)0)->type), PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "SgObstacleRegister: the type name has %zu characters, at most %zu", len, sizeof(((SgObstacle)0)->type) - 1);
  PetscCall(SgObstacleRegisterAll()); /* ours first, so that a caller's type of the same name replaces ours */
  PetscCall(PetscFunctionListAdd(&SgObstacleList, name, create));
  PetscFunctionReturn(0);
}

/* The obstacle of type deftype ("" or NULL: plane) unless -obstacle_type says otherwise, options under the prefix. */
PetscErrorCode SgObstacleCreate(MPI_Comm comm, const char prefix[], PetscInt dim, const char deftype[], SgObstacle *obs)
{
  SgObstacle o;
  PetscErrorCode (*create)(SgObstacle) = NULL;
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&o));
  o->comm = comm;
  o->dim  = dim;
  PetscCall(PetscStrncpy(o->type, deftype && deftype[0] ? deftype : "plane", sizeof(o->type)));
  PetscOptionsBegin(comm, prefix, "Rigid obstacle", NULL);
  PetscCall(PetscOptionsFList("-obstacle_type", "Obstacle shape", NULL, SgObstacleList, o->type, o->type, sizeof(o->type), &set));
  PetscCall(PetscFunctionListFind(SgObstacleList, o->type, &create));
  PetscCheck(create, comm, PETSC_ERR_USER_INPUT, "-obstacle_type: unknown obstacle '%s' (see -help for the list)", o->type);
  PetscCall(create(o));
  PetscCall(o->setfromoptions(o, PetscOptionsObject));
  PetscCall(ReadVector(PetscOptionsObject, comm, "-obstacle_translation", "Rigid translation of the obstacle (any type); with -load_steps it is applied in proportion to the load factor", dim, o->translation));
  PetscOptionsEnd();
  o->placement = 1;
  *obs         = o;
  PetscFunctionReturn(0);
}

/* -help without a problem (bin/signorini -help): every registered obstacle type's options and their defaults (a type
   whose options cannot be read without more input lists what it has read until then) */
PetscErrorCode SgObstaclePrintHelp(MPI_Comm comm, const char prefix[], PetscInt dim)
{
  PetscBool    help;
  int          n;
  const char **names;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  if (!help) PetscFunctionReturn(0);
  PetscCall(PetscFunctionListGet(SgObstacleList, &names, &n));
  PetscOptionsBegin(comm, prefix, "Rigid obstacle", NULL);
  {
    char type[64] = "plane";
    PetscCall(PetscOptionsFList("-obstacle_type", "Obstacle shape", NULL, SgObstacleList, type, type, sizeof(type), NULL));
  }
  for (int i = 0; i < n && names[i]; i++) {
    PetscErrorCode (*create)(SgObstacle) = NULL;
    SgObstacle     o;
    PetscErrorCode ierr;
    PetscCall(PetscFunctionListFind(SgObstacleList, names[i], &create));
    if (!create) continue;
    PetscCall(PetscNew(&o));
    o->comm = comm;
    o->dim  = dim;
    PetscCall(PetscStrncpy(o->type, names[i], sizeof(o->type)));
    PetscCall(create(o));
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = o->setfromoptions(o, PetscOptionsObject);
    PetscCall(PetscPopErrorHandler());
    (void)ierr; /* the listing is what counts here; a real run reads the options again and reports */
    PetscCall(SgObstacleDestroy(&o));
  }
  {
    PetscReal t[3] = {0, 0, 0};
    PetscCall(ReadVector(PetscOptionsObject, comm, "-obstacle_translation", "Rigid translation of the obstacle (any type); with -load_steps it is applied in proportion to the load factor", dim, t));
  }
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

/* The gap of every type at its placement: the obstacle moved by s = placement * translation has at x the gap the
   unmoved one has at x - s (the ray's direction n is unchanged by a translation). */
PetscErrorCode SgObstacleGap(SgObstacle o, const PetscReal x[], const PetscReal n[], PetscReal *d)
{
  PetscReal xs[3];

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < o->dim; k++) xs[k] = x[k] - o->placement * o->translation[k];
  PetscCall(o->gap(o, xs, n, d));
  PetscFunctionReturn(0);
}

/* The signed distance g from x to the obstacle at its placement (> 0 outside) and the obstacle's unit outward normal n
   at the closest point (pointing towards the body): -contact_normal obstacle. A translation moves the closest point
   along and leaves the normal. */
PetscErrorCode SgObstacleDistance(SgObstacle o, const PetscReal x[], PetscReal *g, PetscReal n[])
{
  PetscReal xs[3], s = 0;

  PetscFunctionBeginUser;
  PetscCheck(o->distance, PETSC_COMM_SELF, PETSC_ERR_SUP, "-contact_normal obstacle: the obstacle type '%s' has no signed distance; use -contact_normal body", o->type);
  for (PetscInt k = 0; k < o->dim; k++) xs[k] = x[k] - o->placement * o->translation[k];
  PetscCall(o->distance(o, xs, g, n));
  for (PetscInt k = 0; k < o->dim; k++) s += n[k] * n[k];
  PetscCheck(PetscIsNormalReal(*g) || *g == 0, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "-contact_normal obstacle: the distance from the contact vertex at (%g, %g, %g) to the obstacle '%s' is %g", (double)x[0], (double)x[1], (double)(o->dim == 3 ? x[2] : 0), o->type, (double)*g);
  PetscCheck(PetscAbsReal(s - 1) < 1e-6, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "-contact_normal obstacle: the obstacle '%s' has no unit normal at the closest point of the contact vertex at (%g, %g, %g) (length %g)", o->type, (double)x[0], (double)x[1], (double)(o->dim == 3 ? x[2] : 0), (double)PetscSqrtReal(s));
  PetscFunctionReturn(0);
}

PetscErrorCode SgObstacleHasDistance(SgObstacle o, PetscBool *has)
{
  PetscFunctionBeginUser;
  *has = o->distance ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The obstacle moved by t times -obstacle_translation (load stepping). */
PetscErrorCode SgObstacleSetPlacement(SgObstacle o, PetscReal t)
{
  PetscFunctionBeginUser;
  o->placement = t;
  PetscFunctionReturn(0);
}

/* The translation at full placement (zero if none was given). */
PetscErrorCode SgObstacleGetTranslation(SgObstacle o, PetscReal T[3])
{
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < 3; k++) T[k] = k < o->dim ? o->translation[k] : 0;
  PetscFunctionReturn(0);
}

PetscErrorCode SgObstacleGetType(SgObstacle o, const char *type[])
{
  PetscFunctionBeginUser;
  *type = o->type;
  PetscFunctionReturn(0);
}

static PetscErrorCode SgObstacleFinalizePackage(void)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&SgObstacleList));
  PetscFunctionReturn(0);
}

PetscErrorCode SgObstacleRegisterAll(void)
{
  static PetscBool done = PETSC_FALSE;

  PetscFunctionBeginUser;
  if (done) PetscFunctionReturn(0);
  done = PETSC_TRUE;
  PetscCall(PetscRegisterFinalize(SgObstacleFinalizePackage));
  PetscCall(SgObstacleRegister("plane", SgObstacleCreate_Plane));
  PetscCall(SgObstacleRegister("parabola", SgObstacleCreate_Parabola));
  PetscCall(SgObstacleRegister("ball", SgObstacleCreate_Ball));
  PetscCall(SgObstacleRegister("cad", SgObstacleCreate_CAD));
  PetscFunctionReturn(0);
}

PetscErrorCode SgObstacleDestroy(SgObstacle *o)
{
  PetscFunctionBeginUser;
  if (*o && (*o)->destroy) PetscCall((*o)->destroy(*o));
  PetscCall(PetscFree(*o));
  PetscFunctionReturn(0);
}
