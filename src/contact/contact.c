/* contact.c: contact geometry on Gamma_c (vertex normals, lumped weights, gaps) and the discrete contact terms. */
#include "signorini.h"

/* Contact vertices are the owned, free vertices of the contact facets. Weights w_i = int_Gamma_c phi_i and
   area-weighted normals are summed over the facets of every rank, then read by the owner. */
PetscErrorCode SgContactCreate(SgProblem p, SgContact *contact)
{
  SgContact        c;
  const SgMesh    *m = &p->mesh;
  const PetscInt   dim = p->dim;
  PetscInt         nfac, *facets, *part, nloc = 0, nglob, nfglob;
  Vec              wl, nl, wg, ng;
  PetscScalar     *wa, *na;
  PetscSection     ws, ns;
  char             label[256] = "Face Sets";

  PetscFunctionBeginUser;
  *contact = NULL;
  PetscCall(PetscNew(&c));
  c->prob     = p;
  c->bnd.what = "contact";
  c->gamma    = 1e4;
  PetscCall(PetscStrcpy(c->bnd.label, label));
  PetscOptionsBegin(p->comm, NULL, "Contact boundary", NULL);
  PetscCall(SgBoundaryFromOptions(PetscOptionsObject, &c->bnd, 0, NULL, "possible contact"));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-contact_gamma", "Regularization parameter gamma of (P_gamma) (for -cont_type none)", &c->gamma, NULL));
  c->lamhat0 = 0;
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-contact_lamhat", "Constant shift lamhat of (P_gamma) (for -cont_type none)", &c->lamhat0, NULL));
  PetscOptionsEnd();
  if (!c->bnd.active) { /* no contact boundary: pure elasticity */
    PetscCall(PetscFree(c));
    PetscFunctionReturn(0);
  }
  PetscCheck(PetscIsNormalReal(c->gamma) && c->gamma > 0, p->comm, PETSC_ERR_USER_INPUT, "-contact_gamma: gamma must be positive and finite, got %g", (double)c->gamma);
  PetscCheck((PetscIsNormalReal(c->lamhat0) || c->lamhat0 == 0) && c->lamhat0 >= 0, p->comm, PETSC_ERR_USER_INPUT, "-contact_lamhat: the shift must be finite and >= 0, got %g", (double)c->lamhat0);
  PetscCall(PetscLogEventBegin(SG_ContactSetUp, 0, 0, 0, 0));
  PetscCall(SgObstacleCreate(p->comm, dim, &c->obs));

  PetscCall(SgBoundaryGetFacets(p->dm, &c->bnd, &nfac, &facets, &part));
  nfglob = nfac;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nfglob, 1, MPIU_INT, MPI_SUM, p->comm));
  PetscCheck(nfglob > 0, p->comm, PETSC_ERR_USER_INPUT, "-contact_label/-contact_ids: label '%s' marks no boundary facets: the contact boundary is empty", c->bnd.label);
  PetscCall(DMGetLocalVector(p->dmVert, &wl));
  PetscCall(DMGetLocalVector(p->dmVec, &nl));
  PetscCall(VecZeroEntries(wl));
  PetscCall(VecZeroEntries(nl));
  PetscCall(DMGetLocalSection(p->dmVert, &ws));
  PetscCall(DMGetLocalSection(p->dmVec, &ns));
  PetscCall(VecGetArray(wl, &wa));
  PetscCall(VecGetArray(nl, &na));
  for (PetscInt f = 0; f < nfac; f++) {
    PetscInt  fv[3], nfv, off;
    PetscReal area, nrm[3];
    PetscCall(SgFacetGeometry(p->dm, m, facets[f], &nfv, fv, &area, nrm));
    c->area += area;
    for (PetscInt a = 0; a < nfv; a++) {
      PetscCall(PetscSectionGetOffset(ws, m->vStart + fv[a], &off));
      wa[off] += area / nfv;
      PetscCall(PetscSectionGetOffset(ns, m->vStart + fv[a], &off));
      for (PetscInt k = 0; k < dim; k++) na[off + k] += area / nfv * nrm[k];
    }
  }
  PetscCall(VecRestoreArray(wl, &wa));
  PetscCall(VecRestoreArray(nl, &na));
  PetscCall(PetscFree2(facets, part));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &c->area, 1, MPIU_REAL, MPI_SUM, p->comm));
  /* sum over ranks, then every rank reads the totals of its vertices */
  PetscCall(DMGetGlobalVector(p->dmVert, &wg));
  PetscCall(DMGetGlobalVector(p->dmVec, &ng));
  PetscCall(VecZeroEntries(wg));
  PetscCall(VecZeroEntries(ng));
  PetscCall(DMLocalToGlobal(p->dmVert, wl, ADD_VALUES, wg));
  PetscCall(DMLocalToGlobal(p->dmVec, nl, ADD_VALUES, ng));
  PetscCall(DMGlobalToLocal(p->dmVert, wg, INSERT_VALUES, wl));
  PetscCall(DMGlobalToLocal(p->dmVec, ng, INSERT_VALUES, nl));
  PetscCall(DMRestoreGlobalVector(p->dmVert, &wg));
  PetscCall(DMRestoreGlobalVector(p->dmVec, &ng));

  PetscCall(VecGetArray(wl, &wa));
  PetscCall(VecGetArray(nl, &na));
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(ws, m->vStart + v, &off));
    if (PetscRealPart(wa[off]) > 0 && m->goff[v] >= 0) nloc++;
  }
  c->n = nloc;
  PetscCall(PetscMalloc5(nloc, &c->vert, nloc, &c->off, nloc * dim, &c->normal, nloc, &c->w, nloc, &c->d));
  PetscCall(PetscCalloc1(nloc, &c->lamhat));
  nloc = 0;
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt  off, noff;
    PetscReal nn = 0;
    PetscCall(PetscSectionGetOffset(ws, m->vStart + v, &off));
    if (!(PetscRealPart(wa[off]) > 0 && m->goff[v] >= 0)) continue;
    PetscCall(PetscSectionGetOffset(ns, m->vStart + v, &noff));
    c->vert[nloc] = v;
    c->off[nloc]  = m->goff[v];
    c->w[nloc]    = PetscRealPart(wa[off]);
    for (PetscInt k = 0; k < dim; k++) nn += PetscSqr(PetscRealPart(na[noff + k]));
    nn = PetscSqrtReal(nn);
    PetscCheck(nn > 1e-12 * c->w[nloc], PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "contact vertex %" PetscInt_FMT " has no defined normal (opposite facet normals cancel)", v);
    for (PetscInt k = 0; k < dim; k++) c->normal[nloc * dim + k] = PetscRealPart(na[noff + k]) / nn;
    PetscCall(SgObstacleGap(c->obs, &m->x[v * dim], &c->normal[nloc * dim], &c->d[nloc]));
    c->lamhat[nloc] = c->lamhat0;
    nloc++;
  }
  PetscCall(VecRestoreArray(wl, &wa));
  PetscCall(VecRestoreArray(nl, &na));
  PetscCall(DMRestoreLocalVector(p->dmVert, &wl));
  PetscCall(DMRestoreLocalVector(p->dmVec, &nl));
  nglob = c->n;
  PetscCallMPI(MPI_Allreduce(&nglob, &c->nglobal, 1, MPIU_INT, MPI_SUM, p->comm));
  PetscCheck(c->nglobal > 0, p->comm, PETSC_ERR_USER_INPUT, "-contact_label/-contact_ids: every vertex of the contact boundary '%s' is a Dirichlet vertex: nothing can come into contact", c->bnd.label);
  PetscCall(PetscLogEventEnd(SG_ContactSetUp, 0, 0, 0, 0));
  *contact = c;
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactDestroy(SgContact *c)
{
  PetscFunctionBeginUser;
  if (!*c) PetscFunctionReturn(0);
  PetscCall(PetscFree5((*c)->vert, (*c)->off, (*c)->normal, (*c)->w, (*c)->d));
  PetscCall(PetscFree((*c)->lamhat));
  PetscCall(SgObstacleDestroy(&(*c)->obs));
  PetscCall(PetscFree(*c));
  PetscFunctionReturn(0);
}

/* g_i = tau_N y - d at every contact vertex (ya: the local part of a global displacement vector). */
PetscErrorCode SgContactGap(SgContact c, const PetscScalar ya[], PetscReal g[])
{
  const PetscInt dim = c->prob->dim;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < c->n; i++) {
    PetscReal un = 0;
    for (PetscInt k = 0; k < dim; k++) un += c->normal[i * dim + k] * PetscRealPart(ya[c->off[i] + k]);
    g[i] = un - c->d[i];
  }
  PetscFunctionReturn(0);
}

/* F += sum_i w_i lam_i n_i */
PetscErrorCode SgContactAddForce(SgContact c, const PetscReal lam[], PetscScalar Fa[])
{
  const PetscInt dim = c->prob->dim;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < c->n; i++)
    for (PetscInt k = 0; k < dim; k++) Fa[c->off[i] + k] += c->w[i] * lam[i] * c->normal[i * dim + k];
  PetscFunctionReturn(0);
}

/* J += gamma w_i n_i n_i^T on the active vertices (J assembled afterwards by the caller). */
PetscErrorCode SgContactAddJacobian(SgContact c, const char active[], PetscReal gamma, Mat J)
{
  const PetscInt dim = c->prob->dim;
  PetscInt       rstart;

  PetscFunctionBeginUser;
  PetscCall(MatGetOwnershipRange(J, &rstart, NULL));
  for (PetscInt i = 0; i < c->n; i++) {
    PetscScalar    blk[9];
    const PetscInt row = (rstart + c->off[i]) / dim;
    if (!active[i]) continue;
    for (PetscInt a = 0; a < dim; a++)
      for (PetscInt b = 0; b < dim; b++) blk[a * dim + b] = gamma * c->w[i] * c->normal[i * dim + a] * c->normal[i * dim + b];
    PetscCall(MatSetValuesBlocked(J, 1, &row, 1, &row, blk, ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

/* Multiplier balancing the normal part of the equilibrium residual: lam_i = -(K y - b)_i . n_i / w_i. */
PetscErrorCode SgContactMultiplierFromResidual(SgContact c, Vec y, PetscReal lam[])
{
  const PetscInt     dim = c->prob->dim;
  Vec                R;
  const PetscScalar *ra;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(y, &R));
  PetscCall(MatMult(c->prob->K, y, R));
  PetscCall(VecAXPY(R, -1.0, c->prob->b));
  PetscCall(VecGetArrayRead(R, &ra));
  for (PetscInt i = 0; i < c->n; i++) {
    PetscReal rn = 0;
    for (PetscInt k = 0; k < dim; k++) rn += PetscRealPart(ra[c->off[i] + k]) * c->normal[i * dim + k];
    lam[i] = -rn / c->w[i];
  }
  PetscCall(VecRestoreArrayRead(R, &ra));
  PetscCall(VecDestroy(&R));
  PetscFunctionReturn(0);
}

/* a / b for a measure a >= 0 against its scale b >= 0: 0 when there is nothing to measure, infinite when the scale
   vanishes but the measure does not */
static PetscReal SafeRatio(PetscReal a, PetscReal b)
{
  if (!(a > 0)) return a == 0 ? 0 : a; /* 0, or NaN passed on */
  return b > 0 ? a / b : PETSC_INFINITY;
}

/* KKT measures of the original problem (P) for a displacement y. The multiplier is the one that balances the normal
   residual at the contact vertices, lam_i = -(K y - b)_i.n_i / w_i: for the methods' own multipliers it agrees up to
   round-off, but it does not carry the round-off of gamma (tau_N y - d) at large gamma into the equilibrium measure.
   Every part is dimensionless, so that a tolerance means the same for any load level, material scale and unit system:
   forces are measured against the equilibrium scale ||K|| ||y|| + ||b|| (a backward error), lengths against the
   displacement scale Y = max(||y||_inf, largest initial penetration) as root mean squares over Gamma_c. */
PetscErrorCode SgContactKKT(SgContact c, Vec y, SgKKT *kkt)
{
  SgProblem          p   = c->prob;
  const PetscInt     dim = p->dim;
  Vec                R, Ky;
  PetscScalar       *ra;
  const PetscScalar *ya;
  PetscReal         *g, *lam, s[8] = {0}, mx[3] = {0, 0, 0}, nrm[2], fscale;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(c->n, &g, c->n, &lam));
  PetscCall(VecDuplicate(y, &R));
  PetscCall(VecDuplicate(y, &Ky));
  PetscCall(MatMult(p->K, y, Ky));
  PetscCall(VecWAXPY(R, -1.0, p->b, Ky));
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(SgContactGap(c, ya, g));
  PetscCall(VecRestoreArrayRead(y, &ya));
  PetscCall(VecGetArray(R, &ra));
  for (PetscInt i = 0; i < c->n; i++) {
    PetscReal rn = 0;
    for (PetscInt k = 0; k < dim; k++) rn += PetscRealPart(ra[c->off[i] + k]) * c->normal[i * dim + k];
    lam[i] = -rn / c->w[i];
    mx[0]  = PetscMax(mx[0], PetscAbsReal(lam[i]));
    mx[1]  = PetscMax(mx[1], c->w[i] * PetscMax(0, -lam[i])); /* nodal force a pressure >= 0 cannot balance */
    mx[2]  = PetscMax(mx[2], -c->d[i]);                       /* initial penetration */
  }
  PetscCall(SgContactAddForce(c, lam, ra)); /* what is left: interior and tangential residual */
  PetscCall(VecRestoreArray(R, &ra));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, mx, 3, MPIU_REAL, MPI_MAX, p->comm));
  PetscCall(VecNorm(y, NORM_INFINITY, &nrm[1]));
  fscale = p->Knorm * nrm[1] + p->bnorm_inf;
  for (PetscInt i = 0; i < c->n; i++) {
    /* pressure counts as acting above the round-off of the derived multiplier: 1e4 eps of the equilibrium scale
       (||K|| ||y|| + ||b||) / w_i, and a tiny fraction of the largest pressure */
    const PetscReal noise = 1e-12 * fscale / c->w[i];
    const PetscBool act   = (PetscBool)(lam[i] > PetscMax(1e-10 * mx[0], noise));
    s[0] += c->w[i] * PetscSqr(PetscMax(0, g[i]));                                      /* infeasibility^2 */
    s[1] += c->w[i] * (act ? PetscSqr(PetscMin(0, g[i])) : PetscSqr(PetscMax(0, g[i]))); /* complementarity^2 */
    s[4] += c->w[i] * PetscMax(0, g[i]);                                                /* rho_F */
    s[5] += c->w[i] * (act ? -PetscMin(0, g[i]) : PetscMax(0, g[i]));                   /* rho_C */
    s[6] += c->w[i] * lam[i];                                                           /* contact force */
    s[7] += (act ? 1 : 0);
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, s, 8, MPIU_REAL, MPI_SUM, p->comm));
  /* normwise backward error of the equilibrium equations: ||R|| / (||K|| ||y|| + ||b||), infinity norms; it stays at
     round-off level for nearly incompressible materials, where ||R|| / ||b|| cannot go below eps ||K|| ||y|| / ||b|| */
  PetscCall(VecNorm(R, NORM_INFINITY, &nrm[0]));
  kkt->uscale          = PetscMax(nrm[1], PetscMax(0, mx[2]));
  kkt->lscale          = kkt->uscale * PetscSqrtReal(c->area);
  kkt->penetration     = PetscSqrtReal(s[0]);
  kkt->equilibrium     = nrm[0] / PetscMax(fscale, PETSC_SMALL);
  kkt->infeasibility   = SafeRatio(PetscSqrtReal(s[0]), kkt->lscale);
  kkt->complementarity = SafeRatio(PetscSqrtReal(s[1]), kkt->lscale);
  kkt->dual            = SafeRatio(mx[1], fscale);
  kkt->rhoF            = s[4];
  kkt->rhoC            = s[5];
  kkt->force           = s[6];
  kkt->nactive         = (PetscInt)s[7];
  kkt->residual        = PetscMax(PetscMax(kkt->equilibrium, kkt->dual), PetscMax(kkt->infeasibility, kkt->complementarity));
  PetscCall(VecDestroy(&R));
  PetscCall(VecDestroy(&Ky));
  PetscCall(PetscFree2(g, lam));
  PetscFunctionReturn(0);
}

/* Vertex fields for output: contact pressure, gap d - tau_N y, penetration max(0, tau_N y - d), active flag, and
   the vector d n from each contact vertex to the obstacle (zero elsewhere; pictures draw the obstacle from it). */
PetscErrorCode SgContactFields(SgContact c, Vec y, const PetscReal lam[], Vec flds[4], Vec obst)
{
  SgProblem          p = c->prob;
  Vec                loc[4];
  PetscScalar       *la[4];
  const PetscScalar *ya;
  PetscReal         *g;
  PetscSection       s;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(c->n, &g));
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(SgContactGap(c, ya, g));
  PetscCall(VecRestoreArrayRead(y, &ya));
  PetscCall(DMGetLocalSection(p->dmVert, &s));
  for (PetscInt f = 0; f < 4; f++) {
    PetscCall(DMGetLocalVector(p->dmVert, &loc[f]));
    PetscCall(VecZeroEntries(loc[f]));
    PetscCall(VecGetArray(loc[f], &la[f]));
  }
  for (PetscInt i = 0; i < c->n; i++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(s, p->mesh.vStart + c->vert[i], &off));
    la[0][off] = lam[i];
    la[1][off] = -g[i];
    la[2][off] = PetscMax(0, g[i]);
    la[3][off] = lam[i] > 0 ? 1 : 0;
  }
  for (PetscInt f = 0; f < 4; f++) {
    PetscCall(VecRestoreArray(loc[f], &la[f]));
    /* only owners hold contact vertices: adding the zeros of the other ranks keeps the owner's value */
    PetscCall(VecZeroEntries(flds[f]));
    PetscCall(DMLocalToGlobal(p->dmVert, loc[f], ADD_VALUES, flds[f]));
    PetscCall(DMRestoreLocalVector(p->dmVert, &loc[f]));
  }
  PetscCall(PetscFree(g));
  {
    Vec          ol;
    PetscScalar *oa;
    PetscSection vs;
    const PetscInt dim = p->dim;
    PetscCall(DMGetLocalSection(p->dmVec, &vs));
    PetscCall(DMGetLocalVector(p->dmVec, &ol));
    PetscCall(VecZeroEntries(ol));
    PetscCall(VecGetArray(ol, &oa));
    for (PetscInt i = 0; i < c->n; i++) {
      PetscInt off;
      PetscCall(PetscSectionGetOffset(vs, p->mesh.vStart + c->vert[i], &off));
      for (PetscInt k = 0; k < dim; k++) oa[off + k] = PetscMin(c->d[i], 1e3 * c->area) * c->normal[i * dim + k];
    }
    PetscCall(VecRestoreArray(ol, &oa));
    PetscCall(VecZeroEntries(obst));
    PetscCall(DMLocalToGlobal(p->dmVec, ol, ADD_VALUES, obst));
    PetscCall(DMRestoreLocalVector(p->dmVec, &ol));
  }
  PetscFunctionReturn(0);
}

/* Every contact normal must be +-e_k (for the bound-constrained baselines); returns k and the sign per vertex. */
PetscErrorCode SgContactAxisAligned(SgContact c, const char who[], PetscInt axis[], PetscReal sign[])
{
  const PetscInt dim = c->prob->dim;
  PetscInt       bad = -1;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < c->n && bad < 0; i++) {
    axis[i] = -1;
    for (PetscInt k = 0; k < dim; k++)
      if (PetscAbsReal(PetscAbsReal(c->normal[i * dim + k]) - 1) < 1e-10) {
        axis[i] = k;
        sign[i] = c->normal[i * dim + k] > 0 ? 1 : -1;
      }
    if (axis[i] < 0) bad = i;
  }
  if (bad >= 0) {
    const PetscReal *x = &c->prob->mesh.x[c->vert[bad] * dim], *n = &c->normal[bad * dim];
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_SUP, "%s needs contact normals along a coordinate axis; the vertex at (%g, %g, %g) has normal (%g, %g, %g)", who, (double)x[0], (double)x[1], (double)(dim == 3 ? x[2] : 0), (double)n[0], (double)n[1], (double)(dim == 3 ? n[2] : 0));
  }
  PetscFunctionReturn(0);
}
