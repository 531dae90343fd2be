/* law_pdas.c: the law's part of PDAS (src/cont/pdas.c; Hueber-Stadler-Wohlmuth): per contact vertex the tangential
   state of the next solve (free, stick, slip), its bound and slip direction (the op pdasstate), and the rows these give
   PDAS's linear system (the op pdasrows): a stick vertex's tangential components fixed at the slip reference, a slip
   vertex's force g t (Coulomb, coupled: -F t times the normal equilibrium row of the same solve), in 3D a spring
   across the slip direction. The object SgContactLawPdas keeps them over PDAS's iterations, in PDAS's working
   coordinates. A law with a tangential part that sets neither op gets those of a law with a bound (below); the
   frictionless law has none and its object is empty: every call does nothing, and PDAS's frictionless path stays as
   it was, bit for bit. PDAS asks this object, never the law's properties. */
#include "contact/contactimpl.h"

struct _n_SgContactLawPdas {
  SgContactLaw          law;
  MPI_Comm              comm;
  SgContactLawPdasSetup s;       /* the caller's arrays (kept by it) */
  PetscBool             coupled; /* the rows may couple lam_N of the same solve (the law's coupled property and s.couple) */
  PetscInt              nspring; /* over all ranks: vertices with a spring, components with a coupled row */
  PetscInt              ncoupled;
  char                 *st;   /* n: SG_FRICTION_FREE/STICK/SLIP for the next solve */
  char                 *prev; /* n: the states an update after the first compares with (all free before the
                                     second: the start's states, from a guess, are not taken as known) */
  PetscInt              nupdate;
  PetscReal            *gb, *zn; /* n: the bound, |z| at the state test */
  PetscReal            *tdir;    /* n dim: the slip direction */
  PetscReal            *blk;     /* n dim dim: the springs (zero where none) */
  SgContactLawPdasRows *rows;    /* n */
  Vec                   R;       /* work: K y - b */
};

/* PDAS's state of vertex i for the next solve: the bound g = g_i(lamN); free (g = 0), stick (|z| <= g), slip
   (t = z/|z|). A slip whose direction turned by more than 90 degrees since the last solve sticks in the next one (its
   force then comes from the equilibrium, not from the old direction): with nearly every vertex slipping, the forces
   g t of the old directions can push the whole contact zone back and forth between +t and -t for ever (the same
   safeguard as the SSN's, law_regularized.c) */
static char PdasState_Bound(SgContactLaw law, PetscInt i, PetscReal lamN, PetscInt dim, const PetscReal z[], PetscReal nz, char st, PetscReal t[], PetscReal *g, PetscReal *dt)
{
  char s;

  SgContactLawBound(law, i, lamN, g, NULL);
  s = !(*g > 0) ? 0 : (nz <= *g ? 1 : 2);
  if (s == 2 && st == 2) {
    PetscReal tt = 0;
    for (PetscInt j = 0; j < dim; j++) tt += z[j] / nz * t[j];
    if (tt <= 0) s = 1;
  }
  *dt = 0;
  if (s == 2)
    for (PetscInt j = 0; j < dim; j++) {
      *dt  = PetscMax(*dt, PetscAbsReal(z[j] / nz - t[j]));
      t[j] = z[j] / nz;
    }
  return s;
}

/* The rows of vertex i in its state: stick, its tangential components fixed at the slip reference (no slip in this
   load step); slip, the force w g t (coupled: row j takes -dg t_j n_axis times the normal equilibrium row, w lam_N =
   -n_axis (K y - b)_axis, in the same solve) and in 3D the slip law lam_T = g z/|z| linearized at z = lam_T + c T y
   with lam_T eliminated: across t a spring w beta (T - t t^T), beta = c a / (1 - a), a = g/|z| < 1 (symmetric;
   without it the directions' fixed point does not converge where the slip turns, Example 2's body); free, nothing */
static void PdasRows_Bound(SgContactLaw law, PetscInt i, const SgContactLawPdasVertex *v, SgContactLawPdasRows *r)
{
  const PetscInt dim = v->dim, ax = v->axis;

  if (v->st == SG_FRICTION_SLIP && dim == 3) {
    const PetscReal a = PetscMin(v->g / v->zn, 1 - 1e-8), beta = v->c * a / (1 - a);
    r->spring = PETSC_TRUE;
    for (PetscInt p = 0; p < dim; p++)
      for (PetscInt q = 0; q < dim; q++) {
        if (p == ax || q == ax) continue;
        r->B[p * dim + q] = v->w * beta * ((p == q ? 1 : 0) - v->t[p] * v->t[q]);
      }
  }
  for (PetscInt j = 0; j < dim; j++) {
    if (j == ax) continue;
    if (v->st == SG_FRICTION_STICK) r->kind[j] = SG_PDAS_ROW_FIXED;
    else if (v->st == SG_FRICTION_SLIP && v->couple) {
      PetscReal gi, dg;
      SgContactLawBound(law, i, 0, &gi, &dg);
      r->kind[j] = SG_PDAS_ROW_COUPLED;
      r->v[j]    = dg * v->t[j] * v->nax;
    } else if (v->st == SG_FRICTION_SLIP) {
      r->kind[j] = SG_PDAS_ROW_FORCE;
      r->v[j]    = v->w * v->g * v->t[j];
    }
  }
}

PetscErrorCode SgContactLawSetPdasOps(SgContactLaw law)
{
  PetscFunctionBeginUser;
  if (!law->ops.pdasstate) law->ops.pdasstate = PdasState_Bound;
  if (!law->ops.pdasrows) law->ops.pdasrows = PdasRows_Bound;
  PetscFunctionReturn(0);
}

/* PDAS's tangential part over its working coordinates (s: the caller's arrays, kept by it). Empty (no arrays) for a
   law without the op pdasstate: the frictionless law. */
PetscErrorCode SgContactLawPdasCreate(SgContactLaw law, MPI_Comm comm, const SgContactLawPdasSetup *s, SgContactLawPdas *lp)
{
  SgContactLawPdas p;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&p));
  p->law  = law;
  p->comm = comm;
  p->s    = *s;
  if (law && law->ops.pdasstate) {
    SgContactLawProperties props;
    const PetscInt         n = s->n, dim = s->dim;
    PetscCall(SgContactLawGetProperties(law, &props));
    p->coupled = (PetscBool)(props.coupled && s->couple);
    PetscCall(PetscCalloc5(n, &p->st, n, &p->prev, n, &p->gb, n, &p->zn, n * dim, &p->tdir));
    PetscCall(PetscCalloc2(n * dim * dim, &p->blk, n, &p->rows));
  } else p->s.n = 0;
  *lp = p;
  PetscFunctionReturn(0);
}

/* The rows of every vertex in its state (the op pdasrows), the springs into blk, and their counts over all ranks */
static PetscErrorCode PdasRows(SgContactLawPdas p)
{
  const PetscInt dim    = p->s.dim;
  PetscInt       cnt[2] = {0, 0};

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < p->s.n; i++) {
    SgContactLawPdasVertex v;
    PetscReal             *B = &p->blk[i * dim * dim];
    v.dim                    = dim;
    v.axis                   = p->s.axis[i];
    v.nax                    = p->s.nax[i];
    v.w                      = p->s.w[i];
    v.c                      = p->s.c;
    v.couple                 = p->coupled;
    v.st                     = p->st[i];
    v.g                      = p->gb[i];
    v.zn                     = p->zn[i];
    v.t                      = &p->tdir[i * dim];
    PetscCall(PetscMemzero(&p->rows[i], sizeof(p->rows[i])));
    p->law->ops.pdasrows(p->law, i, &v, &p->rows[i]);
    for (PetscInt q = 0; q < dim * dim; q++) B[q] = p->rows[i].spring ? p->rows[i].B[q] : 0;
    cnt[0] += p->rows[i].spring;
    for (PetscInt j = 0; j < dim; j++) cnt[1] += (p->rows[i].kind[j] == SG_PDAS_ROW_COUPLED);
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, cnt, 2, MPIU_INT, MPI_SUM, p->comm));
  p->nspring  = cnt[0];
  p->ncoupled = cnt[1];
  PetscFunctionReturn(0);
}

/* The states of the next solve from the iterate y (withlam: the multipliers from R = K y - b; else lam = 0, PDAS's
   cold start) and the next normal set act: lam_N = -R.n/w on act, lam_T = -T R / w, z = lam_T + c T (y - yref) (the
   load step's slip); the law gives the bound and the state (the op pdasstate), then the rows of the next system.
   changed (if not NULL): over all ranks the vertices whose state changed, or whose slip direction or bound moved by more
   than 1e-12 (relative) since the last call. Nothing (changed 0) for an empty object. */
PetscErrorCode SgContactLawPdasUpdate(SgContactLawPdas p, Mat K, Vec b, Vec y, PetscBool withlam, const char act[], PetscInt *changed)
{
  const SgContactLawPdasSetup *s = &p->s;
  const PetscScalar           *ya, *ra = NULL;
  const PetscInt               dim = s->dim;
  char                        *last;
  PetscInt                     nch  = 0;
  PetscReal                    gmax = 0;

  PetscFunctionBeginUser;
  if (changed) *changed = 0;
  if (!p->st) PetscFunctionReturn(0);
  last = p->nupdate++ ? p->prev : p->st; /* the states compared with and updated */
  if (withlam) {
    if (!p->R) PetscCall(VecDuplicate(b, &p->R));
    PetscCall(MatMult(K, y, p->R));
    PetscCall(VecAXPY(p->R, -1.0, b));
    PetscCall(VecGetArrayRead(p->R, &ra));
  }
  PetscCall(VecGetArrayRead(y, &ya));
  for (PetscInt i = 0; i < s->n; i++) gmax = PetscMax(gmax, p->gb[i]);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &gmax, 1, MPIU_REAL, MPI_MAX, p->comm));
  for (PetscInt i = 0; i < s->n; i++) {
    const PetscInt  off = s->off[i], ax = s->axis[i];
    const PetscReal lamN = ra && act[i] ? -PetscRealPart(ra[off + ax]) * s->nax[i] / s->w[i] : 0;
    PetscReal       g, z[3] = {0, 0, 0}, nz = 0, dt;
    char            st;
    for (PetscInt j = 0; j < dim; j++) {
      if (j == ax) continue;
      z[j] = (ra ? -PetscRealPart(ra[off + j]) / s->w[i] : 0) + s->c * (PetscRealPart(ya[off + j]) - s->yref[i * dim + j]);
      nz += z[j] * z[j];
    }
    nz = PetscSqrtReal(nz);
    dt = 0;
    st = p->law->ops.pdasstate(p->law, i, lamN, dim, z, nz, last[i], &p->tdir[i * dim], &g, &dt);
    nch += (st != last[i] || (st == SG_FRICTION_SLIP && (dt > 1e-12 || PetscAbsReal(g - p->gb[i]) > 1e-12 * gmax)));
    p->zn[i] = nz;
    last[i]  = st;
    p->gb[i] = g;
  }
  if (last != p->st) PetscCall(PetscArraycpy(p->st, last, s->n));
  if (ra) PetscCall(VecRestoreArrayRead(p->R, &ra));
  PetscCall(VecRestoreArrayRead(y, &ya));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nch, 1, MPIU_INT, MPI_SUM, p->comm));
  if (changed) *changed = nch;
  PetscCall(PdasRows(p));
  PetscFunctionReturn(0);
}

/* The rows of the last update: per vertex (n of them: 0 for an empty object), the springs (n dim dim, for
   SgContactAddBlocks) and, over all ranks, the vertices with a spring and the coupled rows (0: nothing to add or
   assemble) */
PetscErrorCode SgContactLawPdasGetRows(SgContactLawPdas p, PetscInt *n, const SgContactLawPdasRows **rows, const PetscReal **blk, PetscInt *nspring, PetscInt *ncoupled)
{
  PetscFunctionBeginUser;
  *n = p->s.n;
  if (rows) *rows = p->rows;
  if (blk) *blk = p->blk;
  if (nspring) *nspring = p->nspring;
  if (ncoupled) *ncoupled = p->ncoupled;
  PetscFunctionReturn(0);
}

/* What PDAS's verdicts need to know of it: states, it keeps tangential states, so PDAS's iterate depends on their
   bounds and directions, not on the sets alone (no cycle test of the normal sets; the monitor's line of changes);
   roundoff, its rows couple lam_N of the same solve, whose slip states may change on round-off for ever (stop at the
   KKT tolerance once it no longer halves) */
PetscErrorCode SgContactLawPdasGetInfo(SgContactLawPdas p, PetscBool *states, PetscBool *roundoff)
{
  PetscFunctionBeginUser;
  if (states) *states = (PetscBool)(p->st != NULL);
  if (roundoff) *roundoff = p->coupled;
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactLawPdasDestroy(SgContactLawPdas *p)
{
  PetscFunctionBeginUser;
  if (!*p) PetscFunctionReturn(0);
  PetscCall(PetscFree5((*p)->st, (*p)->prev, (*p)->gb, (*p)->zn, (*p)->tdir));
  PetscCall(PetscFree2((*p)->blk, (*p)->rows));
  PetscCall(VecDestroy(&(*p)->R));
  PetscCall(PetscFree(*p));
  PetscFunctionReturn(0);
}
