/* cont/fast.c: a cheap path for iterative linear solves (the performance issue): one (P_gamma)
   at a gamma large enough for the KKT tolerance of (P), solved by SSN with
   - an inexact start: the unconstrained solve at a loose tolerance (-fast_start_rtol);
   - CG that stops as soon as its prospective Newton iterate y - dy changes the active set of the step (checked once
     the residual fell by -fast_ksp_loose), or keeps it and meets the KKT tolerance of (P) (-fast_ksp_kkt); otherwise
     it runs to -ksp_rtol, so the last step is accurate;
   - a preconditioner kept while gamma and the active set are unchanged (the Jacobian is then the same matrix);
   - a stop on the KKT residual of (P) itself (no ||F|| <= rtol ||F_0|| test: with loose solves and ||F_0|| ~ gamma
     times the initial penetration, that test accepts wrong answers).
   gamma: 10 ||lam~|| / (tol Y sqrt|Gamma_c|) as in IPF's cap, with lam~ = (normal diagonal stiffness) x (penetration
   of the start) / w, an estimate from above of the multiplier; if SSN settles with exact steps and only the
   infeasibility is above the tolerance, gamma is raised to IPF's cap from the multiplier found (fallback). If the
   inexact steps fail (cycling, too many steps), the same gamma is solved again with exact steps. The estimate is also
   capped by the precision limit (SgContGammaPrecision) at the start; where an exact step leaves states that change on
   round-off alone with ||F|| at its floor (a gamma too large for double precision: the SSN would cycle), the SSN stops
   and gamma is lowered (at least 4x, to the cap from the multiplier found and below the precision limit there) until
   the tolerance is met, or ends with PRECISION_LIMIT on the best iterate.
   With a direct solver (preonly, -ssn_condense included) every step is exact: no early stop; after too many steps
   the same gamma is continued once (with nu = 0.4999 in 2D the start's active set loses 1-2 vertices a step). */
#include "cont/contimpl.h"

typedef struct {
  PetscReal gamma;      /* > 0: fixed first gamma instead of the estimate */
  PetscReal start_rtol; /* tolerance of the unconstrained start */
  PetscReal loose;      /* the early CG stop is tested once ||r|| <= loose ||r_0|| */
  PetscBool early;      /* CG stops when the prospective active set changes */
  PetscBool margin;     /* ... counting a change only beyond its change since the last iterate */
  PetscBool kkt_stop;   /* CG stops when the prospective iterate meets the KKT tolerance of (P) */
  PetscInt  max_it;     /* SSN steps per (P_gamma) */
  /* run time */
  SgCont    ct;
  Vec       w;      /* the prospective Newton iterate */
  void     *defctx; /* KSPConvergedDefault's context */
  PetscReal rnorm0;
  PetscReal kkt_next; /* the KKT test waits until ||r|| / ||r_0|| falls below this */
  PetscBool on, last_full, stopped;
  PetscBool retry;         /* a failed SSN may be continued once at the same gamma */
  PetscBool raised;        /* gamma was raised (too small): no more lowering on round-off states */
  PetscInt  nearly, nfull; /* linear solves stopped early / run to -ksp_rtol or the KKT tolerance */
  PetscInt  nkkt;          /* linear solves stopped on the KKT tolerance */
} Fast;

static PetscErrorCode SetFromOptions_Fast(SgCont ct, PetscOptionItems *PetscOptionsObject)
{
  Fast       *f = (Fast *)ct->data;
  const char *o1, *o2, *o3, *o4, *o5, *o6;

  PetscFunctionBeginUser;
  PetscCall(SgOptionsRealRenamed(PetscOptionsObject, "-cont_gamma", "-fast_gamma", "gamma of (P_gamma) (0: estimated from the unconstrained start)", &f->gamma, &o1));
  PetscCall(SgOptionsRealRenamed(PetscOptionsObject, "-cont_fast_start_rtol", "-fast_start_rtol", "Relative tolerance of the unconstrained start solve", &f->start_rtol, &o2));
  {
    PetscBool geo; /* one V-cycle of the geometric multigrid already cuts ||r|| about 10x: tested at 0.1 the early stop
                      took steps of 1-2 CG iterations that cycled (2D Example 1, 9,840 unknowns: 38 SSN steps, not 8) */
    PetscCall(SgLinearSolverGeometricMG(PetscOptionsObject->prefix, &geo));
    if (ct->lin.on && ct->lin.tmg && ct->lin.geometric) geo = PETSC_TRUE; /* the default solver's (linear.c) */
    if (geo) f->loose = PetscMin(f->loose, 1e-2);
  }
  PetscCall(SgOptionsRealRenamed(PetscOptionsObject, "-cont_fast_ksp_loose", "-fast_ksp_loose", "CG stops when the prospective active set changes, tested once ||r|| <= this ||r_0||", &f->loose, &o3));
  PetscCall(SgOptionsBoolRenamed(PetscOptionsObject, "-cont_fast_early", "-fast_early", "Stop CG when its prospective iterate changes the active set", &f->early, &o4));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-cont_fast_early_margin", "The early CG stop counts a change of the active set only where the vertex's decision value lamhat + gamma g exceeds its change since the last CG iterate", &f->margin, NULL));
  PetscCall(SgOptionsBoolRenamed(PetscOptionsObject, "-cont_fast_ksp_kkt", "-fast_ksp_kkt", "Stop CG when its prospective iterate keeps the active set and meets the KKT tolerance of (P)", &f->kkt_stop, &o5));
  PetscCall(SgOptionsIntRenamed(PetscOptionsObject, "-cont_fast_max_it", "-fast_max_it", "Maximum number of SSN steps per (P_gamma)", &f->max_it, &o6));
  PetscCheck(f->gamma >= 0 && !PetscIsInfOrNanReal(f->gamma), ct->comm, PETSC_ERR_USER_INPUT, "%s: must be >= 0 and finite, got %g", o1, (double)f->gamma);
  PetscCheck(f->start_rtol > 0 && f->start_rtol < 1, ct->comm, PETSC_ERR_USER_INPUT, "%s: must be in (0, 1), got %g", o2, (double)f->start_rtol);
  PetscCheck(f->loose > 0 && f->loose <= 1, ct->comm, PETSC_ERR_USER_INPUT, "%s: must be in (0, 1], got %g", o3, (double)f->loose);
  PetscCheck(f->max_it > 0, ct->comm, PETSC_ERR_USER_INPUT, "%s: must be positive, got %" PetscInt_FMT, o6, f->max_it);
  PetscFunctionReturn(0);
}

/* CG's test: the default one, and, in an SSN step, once ||r|| <= loose ||r_0|| (preconditioned norms: the
   unpreconditioned one is dominated by the gamma rows), a look at the Newton iterate y - dy that CG would give now:
   - it has another active set than the Jacobian's: stop (an accurate step on a set about to change is wasted);
   - it keeps the set and meets the KKT tolerance of (P) with a margin of 2: stop, the SSN stops there too (the KKT
     residual is what the SSN's own test measures; -ksp_rtol would solve the last step to round-off, 3-4 orders of
     magnitude below the tolerance on Example 2). */
static PetscErrorCode KSPConverged_Fast(KSP ksp, PetscInt it, PetscReal rnorm, KSPConvergedReason *reason, void *ctx)
{
  Fast *f = (Fast *)ctx;
  SgSSN s = f->ct->ssn;

  PetscFunctionBeginUser;
  PetscCall(KSPConvergedDefault(ksp, it, rnorm, reason, f->defctx));
  if (!f->on) PetscFunctionReturn(0);
  if (it == 0) {
    f->rnorm0   = rnorm;
    f->stopped  = PETSC_FALSE;
    f->kkt_next = f->loose;
  }
  if (*reason) {
    if (*reason > 0) f->last_full = PETSC_TRUE;
    PetscFunctionReturn(0);
  }
  if (it == 0 && f->early && f->margin) PetscCall(SgSSNCountSetChangesMargin(s, NULL, SG_SSN_MARGIN_START, NULL));
  /* with the margin, the iterates from 10 loose ||r_0|| on give the decision values the first test compares with */
  if ((f->early || f->kkt_stop) && it > 0 && rnorm <= (f->early && f->margin ? 10 : 1) * f->loose * f->rnorm0) {
    Vec       x, y;
    PetscInt  changed;
    SNES      snes;
    PetscBool test = (PetscBool)(rnorm <= f->loose * f->rnorm0);
    PetscCall(SgSSNGetSNES(s, &snes));
    PetscCall(KSPBuildSolution(ksp, NULL, &x));
    PetscCall(SNESGetSolution(snes, &y));
    PetscCall(VecCopy(x, f->w));
    PetscCall(SgSSNKSPVectorToGlobal(s, f->w)); /* the KSP iterates in the contact frames (-ssn_frame) */
    PetscCall(VecAYPX(f->w, -1.0, y));
    PetscCall(SgSSNCountSetChangesMargin(s, f->w, f->early && f->margin ? SG_SSN_MARGIN_ON : SG_SSN_MARGIN_OFF, &changed));
    if (!test) PetscFunctionReturn(0);
    if (changed && f->early) {
      *reason      = KSP_CONVERGED_RTOL;
      f->last_full = PETSC_FALSE;
      f->stopped   = PETSC_TRUE;
      PetscCall(PetscInfo(ksp, "CG stopped at iteration %" PetscInt_FMT " (||r||/||r0|| %g): the prospective iterate changes %" PetscInt_FMT " vertices of the active set\n", it, (double)(rnorm / f->rnorm0), changed));
    } else if (!changed && f->kkt_stop && rnorm <= f->kkt_next * f->rnorm0) {
      const PetscReal tol = 0.5 * f->ct->kkt_tol;
      SgKKT           kkt;
      PetscCall(SgContactKKT(f->ct->c, f->w, &kkt));
      /* the equilibrium part falls with ||r||: the next test waits until it should be below the tolerance (each test
         costs a product with K); the complementarity part drops to 0 only then, at most a few iterations later */
      if (kkt.equilibrium > tol) f->kkt_next = rnorm / f->rnorm0 * tol / kkt.equilibrium;
      if (kkt.residual <= tol) {
        *reason      = KSP_CONVERGED_RTOL;
        f->last_full = PETSC_TRUE;
        f->nkkt++;
        PetscCall(PetscInfo(ksp, "CG stopped at iteration %" PetscInt_FMT " (||r||/||r0|| %g): the prospective iterate keeps the active set and has KKT residual %g\n", it, (double)(rnorm / f->rnorm0), (double)kkt.residual));
      }
    }
  }
  PetscFunctionReturn(0);
}

/* SSN's stop: the KKT residual of (P) at the iterate; settled after a step to -ksp_rtol with only the infeasibility
   above the tolerance means gamma is too small (the controller raises it). Any other part above the tolerance: one
   more step (on an unchanged set with the same preconditioner), so loose -ksp_rtol only costs steps. */
static PetscErrorCode SSNStop_Fast(SgSSN s, PetscInt it, PetscReal fnorm, PetscBool settled, SNESConvergedReason *reason, void *ctx)
{
  Fast     *f = (Fast *)ctx;
  SgKKT     kkt;
  Vec       y;
  SNES      snes;
  SgCont    ct = f->ct;
  PetscBool roundoff, revisited = PETSC_FALSE;

  PetscFunctionBeginUser;
  if (f->stopped) f->nearly++;
  else f->nfull++;
  PetscCall(SgSSNGetSNES(s, &snes));
  PetscCall(SNESGetSolution(snes, &y));
  PetscCall(SgContactKKT(ct->c, y, &kkt));
  PetscCall(SgSSNStatesAtRoundoff(s, fnorm, settled, &roundoff));
  if (roundoff && f->last_full) PetscCall(SgSSNSetRevisited(s, &revisited)); /* collective: both flags are global */
  PetscCall(PetscInfo(snes, "fast: SSN %" PetscInt_FMT " KKT %.3e (equilibrium %.3e dual %.3e infeasibility %.3e complementarity %.3e) settled %d round-off %d last CG %s\n", it, (double)kkt.residual, (double)kkt.equilibrium, (double)kkt.dual, (double)kkt.infeasibility, (double)kkt.complementarity, (int)settled, (int)roundoff, f->last_full ? "full" : "stopped early"));
  if (kkt.residual <= ct->kkt_tol) {
    *reason = SNES_CONVERGED_FNORM_ABS;
    PetscCall(SgSSNSetReason(s, SG_SSN_KKT));
  } else if (settled && f->last_full && PetscMax(PetscMax(kkt.equilibrium, kkt.dual), kkt.complementarity) <= ct->kkt_tol) {
    /* only the infeasibility ||lam|| / gamma is left: gamma too small */
    *reason = SNES_CONVERGED_FNORM_ABS;
    PetscCall(SgSSNSetReason(s, SG_SSN_SETTLED));
  } else if (roundoff && f->last_full && revisited) {
    /* the states that still change do so on round-off, ||F|| is at its floor, and the set was an earlier step's: the
       steps from here repeat the same sets in turn (a rim vertex let go and taken again, until -fast_max_it); the
       controller decides what the KKT residual reached means (Solve_Fast). Not on round-off alone: at a large gamma
       every change is within the round-off of a far iterate (Example 1 with nu = 0.4999999 at 2.6e19: the first step,
       KKT 4e-2, then 14 steps to the tolerance) */
    *reason = SNES_CONVERGED_FNORM_ABS;
    PetscCall(SgSSNSetReason(s, SG_SSN_ROUNDOFF));
  } else if (it >= f->max_it) {
    *reason = SNES_DIVERGED_MAX_IT;
    PetscCall(SgSSNSetReason(s, SG_SSN_MAX_IT));
  }
  PetscFunctionReturn(0);
}

/* Two bodies: the master side's normal compliance opposite each contact vertex i (units of 1 / gamma),
   C_i = sum_k (M_ik / D_i) w_k / (m_k^T K_kk m_k) over the master vertices k with a dof, where w_k m_k = (B^T 1)_k is
   the master's weighted normal there (|m_k| = 1): a vertex held by the Dirichlet data and a rigid obstacle's row add no
   compliance. C_i = (B z)_i / D_i with z_k = m_k w_k / (m_k^T K_kk m_k) on the master vertices (0 elsewhere). */
static PetscErrorCode MasterCompliance(SgCont ct, PetscReal C[])
{
  PetscInt     dim, rstart, nloc;
  Mat          K;
  Vec          b, z;
  PetscScalar *ba, *za;
  PetscReal   *one, *g0;
  PetscBool   *contact;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetDimension(ct->prob, &dim));
  PetscCall(SgElasticityGetOperators(ct->prob, &K, NULL));
  PetscCall(MatGetOwnershipRange(K, &rstart, NULL));
  PetscCall(VecDuplicate(ct->y, &b)); /* VecDuplicate leaves the entries unset */
  PetscCall(VecDuplicate(ct->y, &z));
  PetscCall(VecZeroEntries(b));
  PetscCall(VecZeroEntries(z));
  PetscCall(VecGetLocalSize(b, &nloc));
  PetscCall(PetscCalloc3(ct->n, &one, ct->n, &g0, nloc / dim + 1, &contact));
  for (PetscInt i = 0; i < ct->n; i++) {
    one[i]                    = 1;
    contact[ct->off[i] / dim] = PETSC_TRUE;
  }
  PetscCall(VecGetArray(b, &ba));
  PetscCall(SgContactAddForce(ct->c, one, ba)); /* b = B^T 1 */
  PetscCall(VecGetArray(z, &za));
  for (PetscInt v = 0; v < nloc / dim; v++) {
    PetscReal   bn = 0, m[3], kn = 0;
    PetscInt    idx[3];
    PetscScalar Kb[9];
    if (contact[v]) continue;
    for (PetscInt a = 0; a < dim; a++) bn += PetscSqr(PetscRealPart(ba[v * dim + a]));
    bn = PetscSqrtReal(bn);
    if (!(bn > 0)) continue;
    for (PetscInt a = 0; a < dim; a++) {
      m[a]   = PetscRealPart(ba[v * dim + a]) / bn;
      idx[a] = rstart + v * dim + a;
    }
    PetscCall(MatGetValues(K, dim, idx, dim, idx, Kb));
    for (PetscInt a = 0; a < dim; a++)
      for (PetscInt c = 0; c < dim; c++) kn += m[a] * PetscRealPart(Kb[a * dim + c]) * m[c];
    if (kn > 0)
      for (PetscInt a = 0; a < dim; a++) za[v * dim + a] = m[a] * bn / kn;
  }
  PetscCall(VecRestoreArray(b, &ba));
  PetscCall(SgContactGap(ct->c, za, C)); /* (B z)_i / D_i - d_i */
  PetscCall(VecRestoreArray(z, &za));
  PetscCall(VecZeroEntries(b));
  PetscCall(VecGetArray(b, &ba));
  PetscCall(SgContactGap(ct->c, ba, g0)); /* - d_i */
  PetscCall(VecRestoreArray(b, &ba));
  for (PetscInt i = 0; i < ct->n; i++) C[i] = PetscMax(0, C[i] - g0[i]);
  PetscCall(PetscFree3(one, g0, contact));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&z));
  PetscFunctionReturn(0);
}

/* gamma from the start y: 10 ||lam~||_L2 / (tol Y sqrt|Gamma_c|), lam~_i = (n^T diag(K)_i n) max(0, g_i) / w_i; and
   gdp, the largest gamma double precision resolves (SgContGammaPrecision) with lam~ for the multiplier. Two bodies:
   n^T diag(K)_i n / w_i is the slave's stiffness alone, as if the master were rigid; where the master is softer than
   a tenth of it (its compliance C_i, MasterCompliance, above 10 w_i / kn_i) it is lowered to 10 / C_i. A slave 1e4
   times stiffer than its master otherwise got a gamma 1e4 times too large, and the SSN did not converge there (a stiff
   slave on a soft block); bodies of one material keep their gamma (a master at least a tenth as stiff). */
static PetscErrorCode EstimateGamma(SgCont ct, PetscReal *gamma, PetscReal *gdp)
{
  const PetscScalar *ya;
  PetscReal          s = 0, *g, *kn, *lam, E;
  PetscBool          pair;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetMaterial(ct->prob, &E, NULL));
  PetscCall(PetscMalloc3(ct->n, &g, ct->n, &kn, ct->n + 1, &lam));
  PetscCall(SgContNormalStiffness(ct, kn));
  PetscCall(SgContactIsPair(ct->c, &pair));
  if (pair) {
    PetscCall(MasterCompliance(ct, g));
    for (PetscInt i = 0; i < ct->n; i++)
      if (g[i] * kn[i] > 10 * ct->w[i]) kn[i] = 10 * ct->w[i] / g[i];
  }
  PetscCall(VecGetArrayRead(ct->y, &ya));
  PetscCall(SgContactGap(ct->c, ya, g));
  PetscCall(VecRestoreArrayRead(ct->y, &ya));
  for (PetscInt i = 0; i < ct->n; i++) {
    const PetscReal l = kn[i] * PetscMax(0, g[i]) / ct->w[i];
    s += ct->w[i] * l * l;
    lam[i] = l;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &s, 1, MPIU_REAL, MPI_SUM, ct->comm));
  if (!(s > 0 && SgContGammaCap(ct, PetscSqrtReal(s), gamma))) *gamma = E;
  { /* SgContGammaPrecision reads ct->lam: lam~ in its place for the call */
    PetscReal *keep = ct->lam;
    ct->lam         = lam;
    PetscCall(SgContGammaPrecision(ct, gdp));
    ct->lam = keep;
  }
  PetscCall(PetscFree3(g, kn, lam));
  PetscFunctionReturn(0);
}

static PetscErrorCode Solve_Fast(SgCont ct)
{
  Fast       *f   = (Fast *)ct->data;
  SgSSN       s   = ct->ssn;
  KSP         ksp = ct->ksp;
  SNES        snes;
  SgSSNReason sr;
  PetscReal   rtol, atol, dtol;
  PetscInt    maxits;
  PetscBool   ok, stop = PETSC_FALSE, exact;

  PetscFunctionBeginUser;
  PetscCall(SgSSNGetSNES(s, &snes));
  /* a direct solve (preonly; -ssn_condense sets it too) calls no convergence test: every step is a full one */
  PetscCall(PetscObjectTypeCompare((PetscObject)ksp, KSPPREONLY, &exact));
  f->retry  = (PetscBool)(f->early || exact);
  f->raised = PETSC_FALSE;
  if (exact) {
    f->early     = PETSC_FALSE;
    f->last_full = PETSC_TRUE;
  }
  for (PetscInt i = 0; i < ct->n; i++) ct->lamhat[i] = 0;
  PetscCall(KSPGetTolerances(ksp, &rtol, &atol, &dtol, &maxits));
  PetscCall(KSPSetTolerances(ksp, PetscMax(rtol, f->start_rtol), atol, dtol, maxits));
  ct->gamma = f->gamma > 0 ? f->gamma : 1; /* checked against -cont_gamma_max by SgContStart */
  PetscCall(SgContStart(ct, &ok));
  PetscCall(KSPSetTolerances(ksp, rtol, atol, dtol, maxits));
  if (!ok) PetscFunctionReturn(0);
  PetscCall(SgContMeasure(ct));
  if (f->gamma > 0) ct->gamma = f->gamma;
  else if (ct->warm) ct->gamma = ct->gamma_warm; /* a load step: the last step's gamma */
  else {
    /* the estimate is from above: where it passes -cont_gamma_max, the largest gamma allowed is tried (a gamma that
       proves too small is raised, and past -cont_gamma_max the run stops with GAMMA_OVERFLOW) */
    PetscReal gdp;
    PetscCall(EstimateGamma(ct, &ct->gamma, &gdp));
    PetscCall(PetscInfo(snes, "fast: gamma estimated %g, double precision's limit at the start %g\n", (double)ct->gamma, (double)gdp));
    /* past the precision limit the SSN decides states on round-off from its first step and cycles on iterates whose
       multipliers say nothing (the limit evaluated there was 3e24 on twobody_punch): the limit at the start, with the
       estimated multiplier (from above too), caps the estimate */
    ct->gamma = PetscMin(PetscMin(ct->gamma, gdp), ct->gamma_max);
  }
  PetscCall(PetscInfo(snes, "fast: gamma %g (KKT residual of the start %g)\n", (double)ct->gamma, (double)ct->kkt.residual));

  f->ct = ct;
  PetscCall(VecDuplicate(ct->y, &f->w));
  PetscCall(KSPConvergedDefaultCreate(&f->defctx));
  PetscCall(KSPSetConvergenceTest(ksp, KSPConverged_Fast, f, NULL));
  PetscCall(SgSSNSetStopTest(s, SSNStop_Fast, f));
  PetscCall(SgSSNSetKeepPCOnSameSet(s, PETSC_TRUE));
  PetscCall(SgSSNSetProgress(s, ct->monitor)); /* its one outer step is the whole solve: show the Newton steps */
  f->on = PETSC_TRUE;
  while (!stop) {
    const PetscReal gamma = ct->gamma;
    PetscInt        its0  = ct->ssn_its;
    PetscBool       ok1;

    if (!(gamma <= ct->gamma_max)) {
      PetscCall(SgContFail(ct, "GAMMA_OVERFLOW: gamma %g exceeds -cont_gamma_max %g", (double)gamma, (double)ct->gamma_max));
      break;
    }
    ct->outer++;
    PetscCall(PetscLogEventBegin(SG_ContStep, 0, 0, 0, 0));
    PetscCall(SgContSSN(ct, gamma, &ok1));
    PetscCall(PetscLogEventEnd(SG_ContStep, 0, 0, 0, 0));
    PetscCall(SgContMeasure(ct));
    PetscCall(SgContOuterRow(ct, ct->ssn_its - its0, NULL));
    PetscCall(SgContKeepBest(ct)); /* a lowered gamma's PRECISION_LIMIT can end on a worse iterate than an earlier one */
    PetscCall(SgSSNGetReason(s, &sr));
    if (!ok1 && f->retry && (sr == SG_SSN_MAX_IT || (f->early && sr == SG_SSN_CYCLING))) {
      /* fallback: the same gamma again, exact steps (already exact: only after MAX_IT, a revisited set would cycle) */
      f->retry = PETSC_FALSE;
      f->early = PETSC_FALSE;
      PetscCall(PetscInfo(snes, "fast: SSN failed (%s); the same gamma again, exact steps\n", SgSSNReasons[sr]));
    } else if (!ok1) break;
    else if (ct->kkt.residual > ct->kkt_tol && (sr == SG_SSN_SETTLED || sr == SG_SSN_ROUNDOFF)) {
      /* IPF's cap from the multiplier found */
      PetscReal       l2         = 0, cap;
      const PetscBool infeasible = (PetscBool)(PetscMax(PetscMax(ct->kkt.equilibrium, ct->kkt.dual), ct->kkt.complementarity) <= ct->kkt_tol);
      PetscBool       hascap;
      PetscReal       gdp = PETSC_MAX_REAL;
      for (PetscInt i = 0; i < ct->n; i++) l2 += ct->w[i] * PetscSqr(ct->lam[i]);
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &l2, 1, MPIU_REAL, MPI_SUM, ct->comm));
      hascap = SgContGammaCap(ct, PetscSqrtReal(l2), &cap);
      /* the precision limit at this iterate (its states settled up to round-off: a usable multiplier, unlike a cycling
         iterate's): a lowered gamma stays below it, else SgContCheck would lift it back to this gamma */
      if (sr == SG_SSN_ROUNDOFF) PetscCall(SgContGammaPrecision(ct, &gdp));
      if (sr == SG_SSN_SETTLED || infeasible) {
        /* only the infeasibility ||lam|| / gamma is left: gamma too small */
        ct->gamma = PetscMax(10 * gamma, hascap ? cap : 10 * gamma);
        f->raised = PETSC_TRUE;
        PetscCall(PetscInfo(snes, "fast: settled with KKT residual %g: gamma %g -> %g\n", (double)ct->kkt.residual, (double)gamma, (double)ct->gamma));
      } else if (!f->raised && hascap) {
        /* the states change on round-off: gamma lowered, to the cap from the multiplier found where the estimate was
           too large (it is from above; twobody_punch at -cont_kkt_tol 1e-12: 6.4e13 against 4.7e12), below the
           precision limit at this iterate, and at least 4x (the cap's margin of 10 on the infeasibility is a margin,
           not a need: twobody_punch meets 1e-13 at 2e13, where the cap asks for 4.6e13); never after a raise (no
           back and forth: a raised gamma that decides on round-off again ends with PRECISION_LIMIT below) */
        ct->gamma = PetscMin(PetscMin(cap, gdp), 0.25 * gamma);
        PetscCall(PetscInfo(snes, "fast: states decided on round-off with KKT residual %g: gamma %g -> %g (the cap from the multiplier found %g, the precision limit here %g)\n", (double)ct->kkt.residual, (double)gamma, (double)ct->gamma, (double)cap, (double)gdp));
      } else {
        PetscCall(SgContFail(ct, "PRECISION_LIMIT: -cont_kkt_tol %.3e is not met at gamma %g, where the SSN's states change on round-off alone with ||F|| at its round-off floor (more Newton steps repeat the same sets); KKT residual reached %.3e (infeasibility %.3e, complementarity %.3e, equilibrium %.3e); -cont_type alm, which moves the shift instead of gamma, can get below it", (double)ct->kkt_tol, (double)gamma, (double)ct->kkt.residual, (double)ct->kkt.infeasibility, (double)ct->kkt.complementarity, (double)ct->kkt.equilibrium));
        break;
      }
    }
    PetscCall(SgContCheck(ct, &stop));
  }
  PetscCall(SgContRestoreBest(ct));
  f->on = PETSC_FALSE;
  PetscCall(SgSSNSetStopTest(s, NULL, NULL));
  PetscCall(SgSSNSetKeepPCOnSameSet(s, PETSC_FALSE));
  PetscCall(SgSSNSetProgress(s, PETSC_FALSE));
  PetscCall(KSPSetConvergenceTest(ksp, KSPConvergedDefault, f->defctx, KSPConvergedDefaultDestroy));
  f->defctx = NULL;
  PetscCall(SgSummarySetInt(ct->sum, "fast_linear_solves_stopped_early", f->nearly));
  PetscCall(SgSummarySetInt(ct->sum, "fast_linear_solves_full", f->nfull));
  PetscCall(SgSummarySetInt(ct->sum, "fast_linear_solves_kkt", f->nkkt));
  PetscCall(VecDestroy(&f->w));
  PetscFunctionReturn(0);
}

static PetscErrorCode View_Fast(SgCont ct, PetscViewer viewer)
{
  Fast *f = (Fast *)ct->data;

  PetscFunctionBeginUser;
  if (f->gamma > 0) PetscCall(PetscViewerASCIIPrintf(viewer, "; gamma %g (-cont_gamma)", (double)f->gamma));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "; gamma estimated from the unconstrained start (-cont_gamma 0)"));
  PetscCall(PetscViewerASCIIPrintf(viewer, ", start rtol %g (-cont_fast_start_rtol), early CG stop %s (-cont_fast_early) tested below %g ||r_0|| (-cont_fast_ksp_loose), KKT stop of CG %s (-cont_fast_ksp_kkt), at most %" PetscInt_FMT " SSN steps (-cont_fast_max_it)", (double)f->start_rtol, f->early ? "on" : "off", (double)f->loose, f->kkt_stop ? "on" : "off", f->max_it));
  PetscFunctionReturn(0);
}

/* the checkpoint (fast resumes from the end of a load step only): what a solve leaves to the next one, the counts of
   the linear solves (its summary keys count over all the load steps of a run) and whether the early CG stop is still on
   (a fallback to exact steps turns it off for the rest of the run); gamma, y and the path are the controller's. The
   dataset "fast_state" (a file without it: nothing counted, the options' early stop) */
#define NSTATE_FAST 5

static PetscErrorCode Save_Fast(SgCont ct, SgCheckpointWriter w)
{
  Fast           *f              = (Fast *)ct->data;
  const PetscReal v[NSTATE_FAST] = {f->nearly, f->nfull, f->nkkt, f->early, f->last_full};

  PetscFunctionBeginUser;
  PetscCall(SgContSaveState(ct, w, 0, NULL, NULL));
  PetscCall(SgCheckpointWriterReals(w, "fast_state", NSTATE_FAST, v));
  PetscFunctionReturn(0);
}

static PetscErrorCode Load_Fast(SgCont ct, SgCheckpointReader r)
{
  Fast      *f = (Fast *)ct->data;
  PetscBool  has;
  PetscReal *v;

  PetscFunctionBeginUser;
  PetscCall(SgContLoadState(ct, r, 0, NULL, NULL));
  PetscCall(SgCheckpointReaderHasDataset(r, "fast_state", &has));
  if (!has) PetscFunctionReturn(0);
  PetscCall(SgCheckpointReaderReals(r, "fast_state", NSTATE_FAST, NULL, &v));
  for (PetscInt i = 0; i < NSTATE_FAST; i++)
    if (!(v[i] >= 0 && v[i] <= (i < 3 ? PETSC_MAX_INT / 4 : 1) && v[i] == PetscFloorReal(v[i]))) {
      const PetscReal bad = v[i];
      PetscCall(PetscFree(v));
      PetscCall(SgCheckpointReaderDamaged(&r, "a number of fast_state", bad));
    }
  f->nearly    = (PetscInt)v[0];
  f->nfull     = (PetscInt)v[1];
  f->nkkt      = (PetscInt)v[2];
  f->early     = (PetscBool)(v[3] != 0);
  f->last_full = (PetscBool)(v[4] != 0);
  PetscCall(PetscFree(v));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContCreate_Fast(SgCont ct)
{
  Fast *f;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&f));
  f->gamma               = 0;
  f->start_rtol          = 1e-2;
  f->loose               = 1e-1;
  f->early               = PETSC_TRUE;
  f->margin              = PETSC_TRUE;
  f->kkt_stop            = PETSC_TRUE;
  f->max_it              = 30;
  ct->data               = f;
  ct->ops.setfromoptions = SetFromOptions_Fast;
  ct->ops.view           = View_Fast;
  ct->ops.save           = Save_Fast;
  ct->ops.load           = Load_Fast;
  ct->ops.solve          = Solve_Fast; /* its own loop: one (P_gamma), gamma raised only if it proves too small */
  PetscFunctionReturn(0);
}
