/* custom_types.c: the worked example of doc/developer-guide.md. A program that adds to libsignorini, without changing
   it, an obstacle type ("ramp") and a controller type ("penalty"), registers both, and checks them against the
   library's own:

   - "ramp" is the line (2D) or plane (3D) x_dim = height + slope x_1 below the body, written as a new type: its gap
     along a ray and its signed distance. The same surface is the built-in "plane" through (0, height) with the normal
     (-slope, 1), so both must give the same solution to round-off.
   - "penalty" is the plainest continuation: lamhat = 0 and gamma multiplied by -cont_penalty_factor each outer step
     (the quadratic penalty method made to converge by the shared outer loop's KKT test). It must reach the same
     solution as ipf to the KKT tolerance.

   A type is implemented against the library's private headers (the struct of an obstacle, the controller's hooks);
   everything else goes through the public header. It is built from the source tree against lib/libsignorini.a:
       make bin/custom_types && bin/custom_types [-nx 40 -ny 10] [-ramp_slope 0.02] [-agree_rtol 1e-7]
   and tests/manual.ini (man_custom_types) builds and runs it. Exit 0 when all checks hold, 1 otherwise. */
#include <signorini.h>
#include "contact/contactimpl.h" /* struct _n_SgObstacle: the hooks an obstacle type fills */
#include "cont/contimpl.h"       /* SgContOps: the hooks a controller type fills */

static const char help[] = "Registers an obstacle type and a controller type of its own and checks them against the library's.\n\n";

/* ---- the obstacle type "ramp": p[0] the height, p[1] the slope */
static PetscErrorCode Gap_Ramp(SgObstacle o, const PetscReal x[], const PetscReal n[], PetscReal *d)
{
  const PetscInt  up = o->dim - 1;
  const PetscReal h = o->p[0], s = o->p[1], den = n[up] - s * n[0];

  PetscFunctionBeginUser;
  /* the ray x + t n meets x_up = h + s x_0 at t = (h + s x_0 - x_up) / (n_up - s n_0); a ray that does not run towards
     the surface (den >= 0) never meets it: an infinite gap, as the built-in plane says */
  *d = den < -1e-12 ? (h + s * x[0] - x[up]) / den : PETSC_MAX_REAL;
  PetscFunctionReturn(0);
}

/* -contact_normal obstacle: the signed distance (> 0 above the surface) and the unit normal towards the body */
static PetscErrorCode Distance_Ramp(SgObstacle o, const PetscReal x[], PetscReal *g, PetscReal n[])
{
  const PetscInt  up = o->dim - 1;
  const PetscReal h = o->p[0], s = o->p[1], len = PetscSqrtReal(1 + s * s);

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < o->dim; k++) n[k] = 0;
  n[0]  = -s / len;
  n[up] = 1 / len;
  *g    = (x[up] - h - s * x[0]) / len;
  PetscFunctionReturn(0);
}

static PetscErrorCode SetFromOptions_Ramp(SgObstacle o, PetscOptionItems *PetscOptionsObject)
{
  PetscFunctionBeginUser;
  /* under the problem's prefix, named in any error with it (SgOptions*) */
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-obstacle_ramp_height", "Height of the ramp at x = 0", &o->p[0], NULL));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-obstacle_ramp_slope", "Slope of the ramp along x", &o->p[1], NULL));
  PetscCheck(PetscIsNormalReal(o->p[1]) || o->p[1] == 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_ramp_slope: must be finite, got %g", (double)o->p[1]);
  PetscCheck(PetscIsNormalReal(o->p[0]) || o->p[0] == 0, o->comm, PETSC_ERR_USER_INPUT, "-obstacle_ramp_height: must be finite, got %g", (double)o->p[0]);
  PetscFunctionReturn(0);
}

static PetscErrorCode ObstacleCreate_Ramp(SgObstacle o)
{
  PetscFunctionBeginUser;
  o->gap            = Gap_Ramp;
  o->distance       = Distance_Ramp;
  o->setfromoptions = SetFromOptions_Ramp;
  PetscFunctionReturn(0);
}

/* ---- the controller type "penalty": lamhat = 0, gamma_{k+1} = factor gamma_k */
typedef struct {
  PetscReal gamma, factor;
} Penalty;

static PetscErrorCode SetFromOptions_Penalty(SgCont ct, PetscOptionItems *PetscOptionsObject)
{
  Penalty *pn = (Penalty *)ct->data;

  PetscFunctionBeginUser;
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-cont_gamma", "gamma of the first step", &pn->gamma, NULL));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-cont_penalty_factor", "gamma_{k+1} = factor gamma_k", &pn->factor, NULL));
  PetscCheck(PetscIsNormalReal(pn->gamma) && pn->gamma > 0, ct->comm, PETSC_ERR_USER_INPUT, "-cont_gamma: must be positive and finite, got %g", (double)pn->gamma);
  PetscCheck(PetscIsNormalReal(pn->factor) && pn->factor > 1, ct->comm, PETSC_ERR_USER_INPUT, "-cont_penalty_factor: must be > 1, got %g", (double)pn->factor);
  PetscFunctionReturn(0);
}

/* before the first outer step: the first gamma and the shift */
static PetscErrorCode Start_Penalty(SgCont ct)
{
  Penalty *pn = (Penalty *)ct->data;

  PetscFunctionBeginUser;
  PetscCheck(!ct->cv.props.tangential, ct->comm, PETSC_ERR_SUP, "-cont_type penalty: not written for friction");
  ct->gamma = pn->gamma;
  for (PetscInt i = 0; i < ct->n; i++) ct->lamhat[i] = 0;
  PetscFunctionReturn(0);
}

/* after a successful SSN solve of (P_gamma) whose KKT residual of (P) is still above the tolerance: the next gamma */
static PetscErrorCode Update_Penalty(SgCont ct, PetscReal *next)
{
  Penalty *pn = (Penalty *)ct->data;

  PetscFunctionBeginUser;
  *next = ct->gamma * pn->factor;
  PetscFunctionReturn(0);
}

static PetscErrorCode View_Penalty(SgCont ct, PetscViewer viewer)
{
  Penalty *pn = (Penalty *)ct->data;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "; first gamma %g, growth factor %g", (double)pn->gamma, (double)pn->factor));
  PetscFunctionReturn(0);
}

static PetscErrorCode ContCreate_Penalty(SgCont ct)
{
  Penalty *pn;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&pn));
  pn->gamma              = 1e2;
  pn->factor             = 100;
  ct->data               = pn; /* SgContDestroy frees it */
  ct->ops.setfromoptions = SetFromOptions_Penalty;
  ct->ops.start          = Start_Penalty;
  ct->ops.update         = Update_Penalty;
  ct->ops.view           = View_Penalty;
  PetscFunctionReturn(0);
}

/* ---- the checks */
static PetscErrorCode SetDefault(const char name[], const char value[])
{
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasName(NULL, NULL, name, &set));
  if (!set) PetscCall(PetscOptionsSetValue(NULL, name, value));
  PetscFunctionReturn(0);
}

typedef struct {
  PetscBool converged;
  PetscReal energy, force;
  PetscInt  nactive, outer, ssn;
} Result;

/* the box problem under prefix with the given obstacle type, solved by the given controller */
static PetscErrorCode Solve(MPI_Comm comm, const char prefix[], const char obstacle[], const char cont_type[], Result *r)
{
  SgProblem   prob;
  SgCont      cont;
  SgKKT       kkt;
  const char *reason;

  PetscFunctionBeginUser;
  PetscCall(SgProblemCreate(comm, &prob));
  PetscCall(SgProblemSetOptionsPrefix(prob, prefix));
  PetscCall(SgProblemSetObstacleType(prob, obstacle));
  PetscCall(SgProblemSetFromOptions(prob));
  PetscCall(SgContCreate(prob, &cont));
  PetscCall(SgProblemDestroy(&prob)); /* the controller holds it */
  PetscCall(SgContSetOptionsPrefix(cont, prefix));
  PetscCall(SgContSetType(cont, cont_type));
  PetscCall(SgContSetFromOptions(cont));
  PetscCall(SgContSolve(cont));
  PetscCall(SgContGetConvergedReason(cont, &r->converged, &reason));
  PetscCall(SgContGetEnergy(cont, &r->energy));
  PetscCall(SgContGetKKT(cont, &kkt));
  PetscCall(SgContGetIterationNumbers(cont, &r->outer, &r->ssn, NULL));
  r->force   = kkt.force;
  r->nactive = kkt.nactive;
  PetscCall(PetscPrintf(comm, "%-8s obstacle %-6s controller %-8s: %s, energy %.15e, contact force %.15e, active %" PetscInt_FMT ", outer %" PetscInt_FMT ", SSN %" PetscInt_FMT "\n", prefix, obstacle, cont_type, r->converged ? "converged" : "FAILED", (double)r->energy, (double)r->force, r->nactive, r->outer, r->ssn));
  if (!r->converged) PetscCall(PetscPrintf(comm, "  reason: %s\n", reason));
  PetscCall(SgContDestroy(&cont));
  PetscFunctionReturn(0);
}

static PetscReal RelDiff(PetscReal a, PetscReal b)
{
  PetscReal m = PetscMax(PetscAbsReal(a), PetscAbsReal(b));
  return m > 0 ? PetscAbsReal(a - b) / m : 0;
}

int main(int argc, char **argv)
{
  MPI_Comm    comm;
  PetscInt    nx = 40, ny = 10;
  PetscReal   slope = 0.02, height = -0.001, rtol = 1e-7;
  char        value[64];
  const char *prefixes[] = {"ref_", "ramp_", "pen_"};
  Result      ref, ramp, pen;
  PetscBool   ok = PETSC_TRUE;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  comm = PETSC_COMM_WORLD;
  /* register before any problem or controller reads -obstacle_type or -cont_type */
  PetscCall(SgObstacleRegister("ramp", ObstacleCreate_Ramp));
  PetscCall(SgContRegister("penalty", ContCreate_Penalty));

  PetscOptionsBegin(comm, NULL, "custom_types: an obstacle and a controller of one's own", NULL);
  PetscCall(PetscOptionsInt("-nx", "Cells along x", NULL, nx, &nx, NULL));
  PetscCall(PetscOptionsInt("-ny", "Cells along y", NULL, ny, &ny, NULL));
  PetscCall(PetscOptionsReal("-ramp_slope", "Slope of the obstacle", NULL, slope, &slope, NULL));
  PetscCall(PetscOptionsReal("-agree_rtol", "Largest relative difference of penalty against ipf", NULL, rtol, &rtol, NULL));
  PetscOptionsEnd();
  PetscCheck(nx > 0 && ny > 0, comm, PETSC_ERR_USER_INPUT, "-nx, -ny: need positive numbers of cells");

  /* the same body under each prefix: the box [0,4]x[0,1], top pushed down by 0.01, bottom on the obstacle */
  for (PetscInt i = 0; i < 3; i++) {
    char        name[64];
    const char *opts[][2] = {
        {                "box_upper",      "4,1"},
        {            "dirichlet_ids",        "3"},
        {         "dirichlet_values",  "0,-0.01"},
        {              "contact_ids",        "1"},
        {                        "E",     "1000"},
        {                       "nu",      "0.3"},
        {                 "ksp_type",  "preonly"},
        {                  "pc_type", "cholesky"},
        {"pc_factor_mat_solver_type",    "mumps"},
        {             "cont_kkt_tol",    "1e-10"},
        {             "cont_monitor",    "false"},
        {           "contact_normal", "obstacle"}  /* the plane's default: the ramp takes it through its distance op */
    };
    PetscCall(PetscSNPrintf(value, sizeof(value), "%" PetscInt_FMT ",%" PetscInt_FMT, nx, ny));
    PetscCall(PetscSNPrintf(name, sizeof(name), "-%sbox_faces", prefixes[i]));
    PetscCall(SetDefault(name, value));
    for (size_t k = 0; k < sizeof(opts) / sizeof(opts[0]); k++) {
      PetscCall(PetscSNPrintf(name, sizeof(name), "-%s%s", prefixes[i], opts[k][0]));
      PetscCall(SetDefault(name, opts[k][1]));
    }
  }
  /* the built-in plane and the ramp describe the same surface */
  PetscCall(PetscSNPrintf(value, sizeof(value), "0,%.17g", (double)height));
  PetscCall(SetDefault("-ref_obstacle_plane_point", value));
  PetscCall(PetscSNPrintf(value, sizeof(value), "%.17g,1", (double)-slope));
  PetscCall(SetDefault("-ref_obstacle_plane_normal", value));
  for (PetscInt i = 1; i < 3; i++) {
    char name[64];
    PetscCall(PetscSNPrintf(name, sizeof(name), "-%sobstacle_ramp_height", prefixes[i]));
    PetscCall(PetscSNPrintf(value, sizeof(value), "%.17g", (double)height));
    PetscCall(SetDefault(name, value));
    PetscCall(PetscSNPrintf(name, sizeof(name), "-%sobstacle_ramp_slope", prefixes[i]));
    PetscCall(PetscSNPrintf(value, sizeof(value), "%.17g", (double)slope));
    PetscCall(SetDefault(name, value));
  }

  PetscCall(Solve(comm, "ref_", "plane", SGCONTIPF, &ref));
  PetscCall(Solve(comm, "ramp_", "ramp", SGCONTIPF, &ramp));
  PetscCall(Solve(comm, "pen_", "ramp", "penalty", &pen));

  if (!ref.converged || !ramp.converged || !pen.converged) {
    PetscCall(PetscPrintf(comm, "FAILED: a solve did not converge\n"));
    ok = PETSC_FALSE;
  }
  if (ref.nactive == 0 || ref.nactive == (nx + 1)) { /* no contact, or all of the bottom: the check would be weak */
    PetscCall(PetscPrintf(comm, "FAILED: the reference has %" PetscInt_FMT " of %" PetscInt_FMT " bottom vertices active: choose another slope\n", ref.nactive, nx + 1));
    ok = PETSC_FALSE;
  }
  PetscCall(PetscPrintf(comm, "obstacle ramp against plane (ipf): energy %.3e, contact force %.3e, active %" PetscInt_FMT " and %" PetscInt_FMT " (tolerance 1e-12)\n", (double)RelDiff(ramp.energy, ref.energy), (double)RelDiff(ramp.force, ref.force), ramp.nactive, ref.nactive));
  if (!(RelDiff(ramp.energy, ref.energy) <= 1e-12 && RelDiff(ramp.force, ref.force) <= 1e-12 && ramp.nactive == ref.nactive)) {
    PetscCall(PetscPrintf(comm, "FAILED: the ramp obstacle does not reproduce the plane\n"));
    ok = PETSC_FALSE;
  }
  PetscCall(PetscPrintf(comm, "controller penalty against ipf: energy %.3e, contact force %.3e (tolerance %.1e), %" PetscInt_FMT " outer steps\n", (double)RelDiff(pen.energy, ramp.energy), (double)RelDiff(pen.force, ramp.force), (double)rtol, pen.outer));
  if (!(RelDiff(pen.energy, ramp.energy) <= rtol && RelDiff(pen.force, ramp.force) <= rtol && pen.nactive == ramp.nactive && pen.outer > 1)) {
    PetscCall(PetscPrintf(comm, "FAILED: the penalty controller does not reach ipf's solution\n"));
    ok = PETSC_FALSE;
  }
  if (ok) PetscCall(PetscPrintf(comm, "custom types: all checks hold\n"));
  PetscCall(PetscFinalize());
  return ok ? 0 : 1;
}
