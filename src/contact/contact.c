/* contact.c: contact geometry on Gamma_c (vertex normals, lumped weights, gaps) and the discrete contact terms. */
#include "contact/contactimpl.h"

/* The friction law (law.c): -friction_type none|tresca|coulomb|(a registered type) with the options of that type and
   -friction_gamma_factor c > 0 (gamma_T = c gamma). */
static PetscErrorCode FrictionFromOptions(PetscOptionItems *PetscOptionsObject, SgContact c)
{
  PetscFunctionBeginUser;
  PetscCall(SgContactLawCreateFromOptions(PetscOptionsObject, c->comm, c->dim, &c->law));
  PetscCall(SgContactLawGetInfo(c->law, NULL, NULL, &c->fgfac));
  {
    SgContactLawProperties props;
    PetscCall(SgContactLawGetProperties(c->law, &props));
    c->tangpart = props.tangential;
  }
  PetscFunctionReturn(0);
}


/* The contact condition of vertex v at x with -contact_normal obstacle and the obstacle at its current placement: the
   normal -n_o and the gap d = g (the obstacle's signed distance and normal at the closest point: g + n_o.u >= 0). At a
   partly fixed vertex (a roller) only the free components move: the normal is the projection of -n_o onto them,
   renormalized, and d the distance along it to the obstacle's tangent plane, g / |projection| (nothing changes where
   n_o has no fixed component); *keep is false where the projection vanishes (the vertex cannot come into contact). */
static PetscErrorCode ObstacleCondition(SgContact c, PetscInt v, PetscReal nrm[], PetscReal *d, PetscBool *keep)
{
  const PetscInt dim = c->dim;
  PetscReal      g, no[3], s = 0;

  PetscFunctionBeginUser;
  PetscCall(SgObstacleDistance(c->obs, &c->mesh->x[v * dim], &g, no));
  *keep = PETSC_TRUE;
  for (PetscInt k = 0; k < dim; k++) nrm[k] = -no[k];
  *d = g;
  if (!SgMeshPartial(c->mesh, v)) PetscFunctionReturn(0);
  for (PetscInt k = 0; k < dim; k++) {
    if (SgMeshFixed(c->mesh, v, k)) nrm[k] = 0;
    s += nrm[k] * nrm[k];
  }
  if (s == 1) PetscFunctionReturn(0);
  if (s <= 1e-16) {
    *keep = PETSC_FALSE;
    PetscFunctionReturn(0);
  }
  s = PetscSqrtReal(s);
  for (PetscInt k = 0; k < dim; k++) nrm[k] /= s;
  *d = g / s;
  PetscFunctionReturn(0);
}


/* The contact boundary from the settings (bnd: the label and ids given through the interface, or NULL) and the
   options; *contact = NULL if no contact boundary is given (linear elasticity). The geometry comes in SgContactSetUp. */
PetscErrorCode SgContactCreate(SgElasticity p, const char prefix[], const SgBoundary *bnd, const SgBoundary *master, const SgBoundary *obnd, const char obstype[], SgContact *contact)
{
  SgContact c;
  char      nmode[64] = "";
  PetscBool nset      = PETSC_FALSE;

  PetscFunctionBeginUser;
  *contact = NULL;
  PetscCall(PetscNew(&c));
  *contact = c; /* the caller's from now on: an error below leaves it to SgContactDestroy, not leaked */
  c->prob  = p;
  PetscCall(SgElasticityGetComm(p, &c->comm));
  PetscCall(SgElasticityGetDimension(p, &c->dim));
  PetscCall(PetscStrallocpy(prefix, &c->prefix));
  PetscCall(PetscStrncpy(c->obstype, obstype ? obstype : "", sizeof(c->obstype)));
  if (bnd) c->bnd = *bnd;
  c->bnd.what = "contact";
  if (master) c->master = *master;
  if (obnd) c->obnd = *obnd;
  if (!c->bnd.label[0]) PetscCall(PetscStrcpy(c->bnd.label, "Face Sets"));
  PetscOptionsBegin(c->comm, prefix, "Contact boundary", NULL);
  PetscCall(SgBoundaryFromOptions(PetscOptionsObject, &c->bnd, 0, NULL, "possible contact"));
  PetscCall(FrictionFromOptions(PetscOptionsObject, c));
  PetscCall(PetscOptionsString("-contact_normal", "Direction of the contact condition: obstacle (g(x) + n_o.u >= 0, the obstacle's signed distance g and unit normal n_o at the closest point to the vertex; right at edges and corners of the contact boundary and on curved bodies) or body (the paper's tau_N: the body's vertex normal, averaged over the facets; at a corner of Gamma_c a vertex may move into the obstacle). Default: obstacle for a plane in any orientation (exact there: no vertex ends inside it, right at corners and on curved bodies; normals off the coordinate axes are solved in the contact frames, -ssn_frame), body for the curved obstacle types (ball, parabola, CAD, meshed: with body a deformed body can end inside them, with obstacle it cannot for a convex one, see doc/method.md; choose it there)", NULL, nmode, nmode, sizeof(nmode), &nset));
  PetscCall(SgContactPairFromOptions(PetscOptionsObject, c));
  PetscOptionsEnd();
  PetscCheck(!nset || !strcmp(nmode, "obstacle") || !strcmp(nmode, "body"), c->comm, PETSC_ERR_USER_INPUT, "-contact_normal: unknown value '%s' (obstacle, body)", nmode);
  PetscCheck(c->bnd.active || !c->tangpart, c->comm, PETSC_ERR_USER_INPUT, "-friction_type %s needs a contact boundary: give -contact_label and/or -contact_ids", c->law->type);
  if (!c->bnd.active) { /* no contact boundary: pure elasticity */
    PetscCall(SgContactDestroy(contact));
    PetscFunctionReturn(0);
  }
  PetscCall(SgObstacleCreate(c->comm, prefix, c->dim, c->obstype, &c->obs));
  {
    PetscBool has;
    PetscCall(SgObstacleHasDistance(c->obs, &has));
    c->obsnormal = nset ? (PetscBool)!strcmp(nmode, "obstacle") : (PetscBool)(has && !strcmp(c->obs->type, "plane") && (!c->master.nids || c->obnd.nids));
    PetscCheck(!c->master.nids || c->obnd.nids || !c->obsnormal, c->comm, PETSC_ERR_USER_INPUT, "-contact_normal obstacle: two-body contact (-contact_master_ids) takes the slave side's normals (-contact_normal body); with a rigid obstacle besides (-contact_obstacle_ids) it chooses the obstacle's conditions");
    PetscCheck(!c->obsnormal || has, c->comm, PETSC_ERR_USER_INPUT, "-contact_normal obstacle: the obstacle type '%s' has no signed distance; use -contact_normal body", c->obs->type);
  }
  PetscFunctionReturn(0);
}

/* Friction with Dirichlet components on contact vertices: which vertices have fixed components (haspartial), and the
   components that a Dirichlet facet which is a contact facet too fixes (dmask: their reaction is a traction on
   Gamma_c; a roller on another face, e.g. a symmetry plane, holds the vertex by a force that is no friction). */
static PetscErrorCode PrescribedSetUp(SgContact c)
{
  const SgMesh     *m   = c->mesh;
  const PetscInt    dim = c->dim, all = (1 << dim) - 1;
  const SgBoundary *db;
  PetscInt          loc[2] = {0, 0}, fStart, fEnd, *mark, nd = 0, *dfac = NULL, *dpart = NULL, nfac, *facets, *part;
  Vec               ml, mg;
  PetscScalar      *ma;
  PetscSection      ns;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc4(c->n * dim + 1, &c->klt, c->n * dim + 1, &c->kslip, c->n + 1, &c->kst, c->n + 1, &c->dmask));
  PetscCall(PetscCalloc1(2 * c->n * dim + 1, &c->ypfull));
  for (PetscInt i = 0; i < c->n; i++) loc[0] += SgMeshPartial(m, c->vert[i]) ? 1 : 0;
  PetscCall(SgElasticityGetDirichletBoundary(c->prob, &db));
  PetscCall(DMPlexGetHeightStratum(c->dm, 1, &fStart, &fEnd));
  PetscCall(PetscCalloc1(fEnd - fStart + 1, &mark));
  if (db->active) PetscCall(SgBoundaryGetFacets(c->dm, db, &nd, &dfac, &dpart));
  for (PetscInt f = 0; f < nd; f++) mark[dfac[f] - fStart] |= db->ncomps ? db->comps[dpart[f]] : all;
  PetscCall(PetscFree2(dfac, dpart));
  PetscCall(DMGetLocalVector(c->dmVec, &ml));
  PetscCall(VecZeroEntries(ml));
  PetscCall(DMGetLocalSection(c->dmVec, &ns));
  PetscCall(VecGetArray(ml, &ma));
  PetscCall(SgBoundaryGetFacets(c->dm, &c->bnd, &nfac, &facets, &part));
  for (PetscInt f = 0; f < nfac; f++) {
    PetscInt  fv[3], nfv, off;
    PetscReal area, nrm[3];
    if (!mark[facets[f] - fStart]) continue;
    PetscCall(SgFacetGeometry(c->dm, m, facets[f], &nfv, fv, &area, nrm));
    for (PetscInt a = 0; a < nfv; a++) {
      PetscCall(PetscSectionGetOffset(ns, m->vStart + fv[a], &off));
      for (PetscInt k = 0; k < dim; k++)
        if (mark[facets[f] - fStart] >> k & 1) ma[off + k] += 1;
    }
  }
  PetscCall(PetscFree2(facets, part));
  PetscCall(PetscFree(mark));
  PetscCall(VecRestoreArray(ml, &ma));
  /* a facet held by another rank marks the vertex there: summed over the ranks */
  PetscCall(DMGetGlobalVector(c->dmVec, &mg));
  PetscCall(VecZeroEntries(mg));
  PetscCall(DMLocalToGlobal(c->dmVec, ml, ADD_VALUES, mg));
  PetscCall(DMGlobalToLocal(c->dmVec, mg, INSERT_VALUES, ml));
  PetscCall(DMRestoreGlobalVector(c->dmVec, &mg));
  PetscCall(VecGetArray(ml, &ma));
  for (PetscInt i = 0; i < c->n; i++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(ns, m->vStart + c->vert[i], &off));
    for (PetscInt k = 0; k < dim; k++)
      if (PetscRealPart(ma[off + k]) > 0 && SgMeshFixed(m, c->vert[i], k)) c->dmask[i] |= 1 << k;
    loc[1] += c->dmask[i] ? 1 : 0;
  }
  PetscCall(VecRestoreArray(ml, &ma));
  PetscCall(DMRestoreLocalVector(c->dmVec, &ml));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, loc, 2, MPIU_INT, MPI_MAX, c->comm));
  c->haspartial = (PetscBool)(loc[0] > 0);
  c->hasdface   = (PetscBool)(loc[1] > 0);
  PetscFunctionReturn(0);
}

/* Contact vertices are the owned, free vertices of the contact facets. Weights w_i = int_Gamma_c phi_i and
   area-weighted normals are summed over the facets of every rank, then read by the owner. */
/* The contact vertices are known (n, vert, off, normal, w, d): the law's coordinates, the global count, the arrays of
   the KKT measures */
static PetscErrorCode VerticesDone(SgContact c)
{
  const PetscInt dim = c->dim;
  PetscInt       nglob;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(c->n * dim + 1, &c->xc)); /* the law's vertices */
  for (PetscInt i = 0; i < c->n; i++)
    for (PetscInt k = 0; k < dim; k++) c->xc[i * dim + k] = c->mesh->x[c->vert[i] * dim + k];
  PetscCall(SgContactLawSetVertices(c->law, c->n, c->xc));
  PetscCall(SgContactLawGetSlipReference(c->law, &c->yref)); /* the law's (NULL without friction) */
  if (c->yref) c->ypref = c->yref + c->n * dim;
  nglob = c->n;
  PetscCallMPI(MPI_Allreduce(&nglob, &c->nglobal, 1, MPIU_INT, MPI_SUM, c->comm));
  PetscCheck(c->nglobal > 0 || c->pair, c->comm, PETSC_ERR_USER_INPUT, "-contact_label/-contact_ids: every vertex of the contact boundary '%s' is a Dirichlet vertex: nothing can come into contact", c->bnd.label);
  /* two bodies without a slave vertex opposite the master: farther apart than the pairing distance (a valid problem:
     solved without contact, with a warning), or sides that do not face each other (an error) */
  if (!c->nglobal && c->pair) { /* the messages name the ids of both sides */
    char ids[256], mids[256];
    SgPairIdList(&c->bnd, ids, sizeof(ids));
    SgPairIdList(&c->master, mids, sizeof(mids));
    if (c->pair->area > 0 && c->pair->ndrop == 0) { /* the sides face each other, but no slave vertex can move */
      const SgBoundary *db;
      char              dids[256] = "";
      PetscCall(SgElasticityGetDirichletBoundary(c->prob, &db));
      if (db->active) SgPairIdList(db, dids, sizeof(dids));
      SETERRQ(c->comm, PETSC_ERR_USER_INPUT, "-contact_ids %s / -contact_master_ids %s: the slave side faces the master side, but every slave vertex opposite it is a Dirichlet vertex (-dirichlet_label '%s'%s%s), or fixed along the side's normal (-dirichlet_components): nothing can come into contact; leave the slave side free, or make the held side the master (-contact_ids and -contact_master_ids swapped)", ids, mids, db->label, db->nids ? " -dirichlet_ids " : "", dids);
    }
    PetscCheck(c->pair->nbeyond > 0, c->comm, PETSC_ERR_USER_INPUT, "-contact_ids/-contact_master_ids: no slave facet of '%s' faces a master facet (the two sides face away from each other, or do not lie opposite each other): -contact_ids %s, -contact_master_ids %s", c->bnd.label, ids, mids);
    PetscCall(PetscPrintf(c->comm, "WARNING: -contact_ids/-contact_master_ids: the slave side of '%s' faces the master side only farther away than -contact_pair_distance %g: the pair has no contact vertices, and the problem is solved without contact (give a larger -contact_pair_distance if the bodies can come that close): -contact_ids %s, -contact_master_ids %s\n", c->bnd.label, (double)c->pairdist, ids, mids));
  }
  PetscCall(PetscCalloc2(c->n + 1, &c->klam, c->n + 1, &c->kact));
  PetscFunctionReturn(0);
}


static PetscErrorCode PairSetUp(SgContact);
static PetscErrorCode ObstacleVertices(SgContact, const SgBoundary *);

PetscErrorCode SgContactSetUp(SgContact c)
{
  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetDMs(c->prob, &c->dm, &c->dmVert, &c->dmVec, NULL));
  PetscCall(SgElasticityGetMesh(c->prob, &c->mesh));
  PetscCall(SgElasticityGetOperators(c->prob, &c->K, &c->b));
  PetscCall(PetscLogEventBegin(SG_ContactSetUp, 0, 0, 0, 0));
  if (c->master.nids) { /* two bodies: the pair's rows (and the obstacle's, -contact_obstacle_ids) */
    PetscCall(PairSetUp(c));
    PetscCall(VerticesDone(c));
    PetscCall(PetscLogEventEnd(SG_ContactSetUp, 0, 0, 0, 0));
    PetscFunctionReturn(0);
  }
  PetscCall(ObstacleVertices(c, &c->bnd));
  /* the first load step's slip: from y = 0; the reference of the unknowns, then (ypref) of the full displacement:
     the law's (VerticesDone) */
  PetscCall(VerticesDone(c));
  if (c->tangpart) PetscCall(PrescribedSetUp(c));
  PetscCall(PetscLogEventEnd(SG_ContactSetUp, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Two bodies: the pair's rows; with a rigid obstacle besides, its nodal conditions on the faces -contact_obstacle_ids
   first (as for one body), handed to the pair as rows of their own */
static PetscErrorCode PairSetUp(SgContact c)
{
  PetscInt   n = 0, *off = NULL;
  PetscReal *w = NULL, *nrm = NULL, *d = NULL, area = 0;
  PetscInt  *vert = NULL;

  PetscFunctionBeginUser;
  if (c->obnd.nids) {
    PetscCall(PetscStrncpy(c->obnd.label, c->bnd.label, sizeof(c->obnd.label)));
    PetscCall(ObstacleVertices(c, &c->obnd));
    { /* as for one body (VerticesDone): faces whose every vertex is held cannot touch the obstacle */
      PetscInt nglob = c->n;
      char     oids[256];
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nglob, 1, MPIU_INT, MPI_SUM, c->comm));
      SgPairIdList(&c->obnd, oids, sizeof(oids));
      PetscCheck(nglob > 0, c->comm, PETSC_ERR_USER_INPUT, "-contact_obstacle_ids %s: every vertex of these faces of '%s' is a Dirichlet vertex, or fixed along the obstacle's normal (-dirichlet_components): nothing can come into contact with the obstacle", oids, c->obnd.label);
    }
    n = c->n, vert = c->vert, off = c->off, nrm = c->normal, w = c->w, d = c->d, area = c->area;
    c->n = 0, c->vert = NULL, c->off = NULL, c->normal = NULL, c->w = NULL, c->d = NULL;
  }
  PetscCall(SgContactPairSetUp(c, n, off, w, nrm, d));
  c->area += area; /* the pair's covered slave surface and the obstacle's faces */
  PetscCall(PetscFree5(vert, off, nrm, w, d));
  PetscFunctionReturn(0);
}

/* The lumped weights w_v = sum over the facets at v of |f| / nv(f) and the area-weighted normal sums sum |f| / nv(f)
   n_f of the nfac facets of this rank, summed over the ranks that share a vertex, into the local vectors wl (of
   dmVert) and nl (of dmVec); *area += the facets' measure summed over the ranks (NULL: not wanted) */
PetscErrorCode SgContactLumpedSurface(SgContact c, PetscInt nfac, const PetscInt facets[], Vec wl, Vec nl, PetscReal *area)
{
  const SgMesh *m = c->mesh;
  PetscReal     a = 0;
  PetscScalar  *wa, *na;
  PetscSection  ws, ns;
  Vec           wg, ng;

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(wl));
  PetscCall(VecZeroEntries(nl));
  PetscCall(DMGetLocalSection(c->dmVert, &ws));
  PetscCall(DMGetLocalSection(c->dmVec, &ns));
  PetscCall(VecGetArray(wl, &wa));
  PetscCall(VecGetArray(nl, &na));
  for (PetscInt f = 0; f < nfac; f++) {
    PetscInt  fv[3], nfv, off;
    PetscReal meas, nrm[3];
    PetscCall(SgFacetGeometry(c->dm, m, facets[f], &nfv, fv, &meas, nrm));
    a += meas;
    for (PetscInt v = 0; v < nfv; v++) {
      PetscCall(PetscSectionGetOffset(ws, m->vStart + fv[v], &off));
      wa[off] += meas / nfv;
      PetscCall(PetscSectionGetOffset(ns, m->vStart + fv[v], &off));
      for (PetscInt k = 0; k < c->dim; k++) na[off + k] += meas / nfv * nrm[k];
    }
  }
  PetscCall(VecRestoreArray(wl, &wa));
  PetscCall(VecRestoreArray(nl, &na));
  if (area) {
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &a, 1, MPIU_REAL, MPI_SUM, c->comm));
    *area += a;
  }
  /* sum over ranks, then every rank reads the totals of its vertices */
  PetscCall(DMGetGlobalVector(c->dmVert, &wg));
  PetscCall(DMGetGlobalVector(c->dmVec, &ng));
  PetscCall(VecZeroEntries(wg));
  PetscCall(VecZeroEntries(ng));
  PetscCall(DMLocalToGlobal(c->dmVert, wl, ADD_VALUES, wg));
  PetscCall(DMLocalToGlobal(c->dmVec, nl, ADD_VALUES, ng));
  PetscCall(DMGlobalToLocal(c->dmVert, wg, INSERT_VALUES, wl));
  PetscCall(DMGlobalToLocal(c->dmVec, ng, INSERT_VALUES, nl));
  PetscCall(DMRestoreGlobalVector(c->dmVert, &wg));
  PetscCall(DMRestoreGlobalVector(c->dmVec, &ng));
  PetscFunctionReturn(0);
}

/* The nodal conditions on the faces of bnd against the obstacle: the contact vertices (n, vert, off, normal, w, d) */
static PetscErrorCode ObstacleVertices(SgContact c, const SgBoundary *bnd)
{
  const SgMesh *m   = c->mesh;
  PetscInt      dim = c->dim;
  PetscInt      nfac, *facets, *part, nloc = 0, nfglob;
  Vec           wl, nl;
  PetscScalar  *wa, *na;
  PetscSection  ws, ns;

  PetscFunctionBeginUser;
  PetscCall(SgBoundaryGetFacets(c->dm, bnd, &nfac, &facets, &part));
  nfglob = nfac;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nfglob, 1, MPIU_INT, MPI_SUM, c->comm));
  PetscCheck(nfglob > 0, c->comm, PETSC_ERR_USER_INPUT, "-%s_label/-%s_ids: label '%s' marks no boundary facets: the contact boundary is empty", c->bnd.what, bnd->what, bnd->label);
  PetscCall(DMGetLocalVector(c->dmVert, &wl));
  PetscCall(DMGetLocalVector(c->dmVec, &nl));
  PetscCall(SgContactLumpedSurface(c, nfac, facets, wl, nl, &c->area));
  PetscCall(PetscFree2(facets, part));
  PetscCall(DMGetLocalSection(c->dmVert, &ws));
  PetscCall(DMGetLocalSection(c->dmVec, &ns));

  PetscCall(VecGetArray(wl, &wa));
  PetscCall(VecGetArray(nl, &na));
  /* at a partly fixed vertex (a roller) only the free components can move towards the obstacle: the normal is the
     projection onto them, renormalized (on a symmetry plane it is the normal of the whole model's mirror-symmetric
     mesh); a vertex whose free components are tangential cannot come into contact, as a fully fixed one */
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt  noff;
    PetscReal n0 = 0, n1 = 0;
    if (!SgMeshPartial(m, v) || c->obsnormal) continue; /* obstacle: from the obstacle's normal (ObstacleCondition) */
    PetscCall(PetscSectionGetOffset(ns, m->vStart + v, &noff));
    for (PetscInt k = 0; k < dim; k++) {
      n0 += PetscSqr(PetscRealPart(na[noff + k]));
      if (SgMeshFixed(m, v, k)) na[noff + k] = 0;
      n1 += PetscSqr(PetscRealPart(na[noff + k]));
    }
    if (n1 <= 1e-16 * n0) {
      PetscCall(PetscSectionGetOffset(ws, m->vStart + v, &noff));
      wa[noff] = 0;
    }
  }
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(ws, m->vStart + v, &off));
    if (PetscRealPart(wa[off]) > 0 && m->goff[v] >= 0) nloc++;
  }
  c->n = nloc;
  PetscCall(PetscMalloc5(nloc, &c->vert, nloc, &c->off, nloc * dim, &c->normal, nloc, &c->w, nloc, &c->d));
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
    if (c->obsnormal) {
      PetscBool keep;
      PetscCall(ObstacleCondition(c, v, &c->normal[nloc * dim], &c->d[nloc], &keep));
      if (keep) nloc++;
      continue;
    }
    for (PetscInt k = 0; k < dim; k++) nn += PetscSqr(PetscRealPart(na[noff + k]));
    nn = PetscSqrtReal(nn);
    PetscCheck(nn > 1e-12 * c->w[nloc], PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "contact vertex %" PetscInt_FMT " has no defined normal (opposite facet normals cancel)", v);
    for (PetscInt k = 0; k < dim; k++) c->normal[nloc * dim + k] = PetscRealPart(na[noff + k]) / nn;
    PetscCall(SgObstacleGap(c->obs, &m->x[v * dim], &c->normal[nloc * dim], &c->d[nloc]));
    nloc++;
  }
  c->n = nloc;
  PetscCall(VecRestoreArray(wl, &wa));
  PetscCall(VecRestoreArray(nl, &na));
  PetscCall(DMRestoreLocalVector(c->dmVert, &wl));
  PetscCall(DMRestoreLocalVector(c->dmVec, &nl));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactGetVertices(SgContact c, PetscInt *n, PetscInt *nglobal, const PetscInt *vert[], const PetscInt *off[])
{
  PetscFunctionBeginUser;
  if (n) *n = c->n;
  if (nglobal) *nglobal = c->nglobal;
  if (vert) *vert = c->vert;
  if (off) *off = c->off;
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactGetWeights(SgContact c, const PetscReal *w[])
{
  PetscFunctionBeginUser;
  *w = c->w;
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactGetNormals(SgContact c, const PetscReal *normal[])
{
  PetscFunctionBeginUser;
  *normal = c->normal;
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactGetGaps(SgContact c, const PetscReal *d[])
{
  PetscFunctionBeginUser;
  *d = c->d;
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactGetArea(SgContact c, PetscReal *area)
{
  PetscFunctionBeginUser;
  *area = c->area;
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactGetView(SgContact c, SgContactView *v)
{
  PetscFunctionBeginUser;
  v->law = c->law;
  PetscCall(SgContactLawGetProperties(c->law, &v->props));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactGetObstacleType(SgContact c, const char *type[])
{
  PetscFunctionBeginUser;
  if (c->master.nids && c->obnd.nids) { /* a rigid obstacle besides the pair */
    const char *ot;
    PetscCall(SgObstacleGetType(c->obs, &ot));
    PetscCall(PetscSNPrintf(c->obsdesc, sizeof(c->obsdesc), "%s (-contact_obstacle_ids) and two bodies (-contact_master_ids, mortar)", ot));
    *type = c->obsdesc;
  } else if (c->master.nids) *type = "none: two bodies (-contact_master_ids, mortar)";
  else PetscCall(SgObstacleGetType(c->obs, type));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactGetNormalType(SgContact c, const char *type[])
{
  PetscFunctionBeginUser;
  *type = c->obsnormal ? "obstacle" : "body";
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactGetElasticity(SgContact c, SgElasticity *el)
{
  PetscFunctionBeginUser;
  *el = c->prob;
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactDestroy(SgContact *c)
{
  PetscFunctionBeginUser;
  if (!*c) PetscFunctionReturn(0);
  PetscCall(PetscFree5((*c)->vert, (*c)->off, (*c)->normal, (*c)->w, (*c)->d));
  PetscCall(PetscFree2((*c)->klam, (*c)->kact));
  PetscCall(PetscFree4((*c)->klt, (*c)->kslip, (*c)->kst, (*c)->dmask));
  PetscCall(PetscFree((*c)->ypfull));
  PetscCall(PetscFree((*c)->xc));
  PetscCall(PetscFree((*c)->prow));
  PetscCall(PetscFree((*c)->obsrow));
  PetscCall(VecDestroy(&(*c)->pw));
  PetscCall(VecDestroy(&(*c)->pf));
  PetscCall(VecDestroy(&(*c)->pl));
  PetscCall(VecDestroy(&(*c)->pr));
  PetscCall(SgContactPairDestroy(&(*c)->pair));
  PetscCall(SgContactLawDestroy(&(*c)->law));
  PetscCall(PetscFree((*c)->prefix));
  PetscCall(SgObstacleDestroy(&(*c)->obs));
  PetscCall(PetscFree(*c));
  PetscFunctionReturn(0);
}

/* g_i = tau_N y - d at every contact vertex (ya: the local part of a global displacement vector). */
PetscErrorCode SgContactGap(SgContact c, const PetscScalar ya[], PetscReal g[])
{
  const PetscInt dim = c->dim;

  PetscFunctionBeginUser;
  if (c->pair) { /* two bodies: g_i = (B y)_i / D_i - d_i */
    PetscCall(SgContactPairGap(c, ya, g));
    PetscFunctionReturn(0);
  }
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
  const PetscInt dim = c->dim;

  PetscFunctionBeginUser;
  if (c->pair) { /* two bodies: F += B^T lam (both sides) */
    PetscCall(SgContactPairForce(c, lam, Fa));
    PetscFunctionReturn(0);
  }
  for (PetscInt i = 0; i < c->n; i++)
    for (PetscInt k = 0; k < dim; k++) Fa[c->off[i] + k] += c->w[i] * lam[i] * c->normal[i * dim + k];
  PetscFunctionReturn(0);
}

/* J += the dim x dim block b on the diagonal of contact vertex i (rstart: J's first owned row) */
static PetscErrorCode AddVertexBlock(SgContact c, Mat J, PetscInt rstart, PetscInt i, const PetscScalar b[])
{
  const PetscInt row = (rstart + c->off[i]) / c->dim;

  PetscFunctionBeginUser;
  PetscCall(MatSetValuesBlocked(J, 1, &row, 1, &row, b, ADD_VALUES));
  PetscFunctionReturn(0);
}


/* J += gamma w_i n_i n_i^T on the active vertices (J assembled afterwards by the caller). */
PetscErrorCode SgContactAddJacobian(SgContact c, const char active[], PetscReal gamma, Mat J)
{
  const PetscInt dim = c->dim;
  PetscInt       rstart;

  PetscFunctionBeginUser;
  if (c->pair) { /* two bodies: gamma B^T diag(act / D) B */
    PetscCall(SgContactPairJacobian(c, active, gamma, J));
    PetscFunctionReturn(0);
  }
  PetscCall(MatGetOwnershipRange(J, &rstart, NULL));
  for (PetscInt i = 0; i < c->n; i++) {
    PetscScalar blk[9];
    if (!active[i]) continue;
    for (PetscInt a = 0; a < dim; a++)
      for (PetscInt b = 0; b < dim; b++) blk[a * dim + b] = gamma * c->w[i] * c->normal[i * dim + a] * c->normal[i * dim + b];
    PetscCall(AddVertexBlock(c, J, rstart, i, blk));
  }
  PetscFunctionReturn(0);
}

/* J += B_i on the diagonal block of every contact vertex (blk: n blocks of dim x dim, row-major; J assembled by the
   caller); two bodies: R^T diag(B_i) R, on the relative displacements */
PetscErrorCode SgContactAddBlocks(SgContact c, const PetscReal blk[], Mat J)
{
  const PetscInt dim = c->dim;
  PetscInt       rstart;

  PetscFunctionBeginUser;
  if (c->pair) {
    PetscCall(SgContactPairBlocks(c, blk, J));
    PetscFunctionReturn(0);
  }
  PetscCall(MatGetOwnershipRange(J, &rstart, NULL));
  for (PetscInt i = 0; i < c->n; i++) {
    PetscScalar b[9];
    for (PetscInt k = 0; k < dim * dim; k++) b[k] = blk[i * dim * dim + k];
    PetscCall(AddVertexBlock(c, J, rstart, i, b));
  }
  PetscFunctionReturn(0);
}

/* u_i = y_i at every contact vertex, dim numbers each (ya: the local part of a global displacement vector); two
   bodies: the relative displacement (R y)_i of the slave vertex against the master surface */
PetscErrorCode SgContactVertexDisplacements(SgContact c, const PetscScalar ya[], PetscReal u[])
{
  PetscFunctionBeginUser;
  if (c->pair) {
    PetscCall(SgContactPairRelative(c, ya, u));
    PetscFunctionReturn(0);
  }
  for (PetscInt i = 0; i < c->n; i++)
    for (PetscInt k = 0; k < c->dim; k++) u[i * c->dim + k] = PetscRealPart(ya[c->off[i] + k]);
  PetscFunctionReturn(0);
}

/* F += f_i at every contact vertex (dim numbers each); two bodies: R^T f (the slave vertex and, opposite, the master's) */
PetscErrorCode SgContactAddVertexForces(SgContact c, const PetscReal f[], PetscScalar Fa[])
{
  PetscFunctionBeginUser;
  if (c->pair) {
    PetscCall(SgContactPairTangentialForce(c, f, Fa));
    PetscFunctionReturn(0);
  }
  for (PetscInt i = 0; i < c->n; i++)
    for (PetscInt k = 0; k < c->dim; k++) Fa[c->off[i] + k] += f[i * c->dim + k];
  PetscFunctionReturn(0);
}

/* Multiplier balancing the normal part of the equilibrium residual: lam_i = -(K y - b)_i . n_i / w_i. */
PetscErrorCode SgContactMultiplierFromResidual(SgContact c, Vec y, PetscReal lam[])
{
  const PetscInt     dim = c->dim;
  Vec                R;
  const PetscScalar *ra;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(y, &R));
  PetscCall(MatMult(c->K, y, R));
  PetscCall(VecAXPY(R, -1.0, c->b));
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

PetscErrorCode SgContactGetFrictionSummary(SgContact c, SgFrictionSummary *fs)
{
  PetscFunctionBeginUser;
  *fs = c->fsum;
  PetscFunctionReturn(0);
}

static PetscErrorCode ComputeScales(SgContact c, Vec y, const PetscScalar ra[], const PetscReal lam[], PetscReal pen, KKTScales *sc)
{
  const PetscInt dim = c->dim;
  PetscReal      fmax, smax, ucur, ufull, bfull, floads, Knorm, diam, bnorm_inf, ynorm, yk, T[3], cm = 0, cs[4] = {0, 0, 0, 0}, E, nu, lambda, mu;
  PetscInt       nd;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetNodalNormSize(c->prob, &nd));
  PetscCall(SgElasticityForces(c->prob, y, &fmax, &smax, sc->res, &sc->l1));
  for (PetscInt i = 0; i < c->n; i++) { /* the contact force on the body at vertex i */
    PetscReal       f[3], rn = 0, fm, a = 0;
    const PetscBool inner = (PetscBool)(c->pair && !c->obsrow[i]); /* two bodies: its equal and opposite acts on the master */
    for (PetscInt k = 0; k < dim; k++) rn += PetscRealPart(ra[c->off[i] + k]) * c->normal[i * dim + k];
    fm = SgContactLawContactForce(c->law, dim, &ra[c->off[i]], &c->normal[i * dim], rn, c->w[i] * PetscAbsReal(lam[i]), f); /* the law's: with friction the whole nodal force */
    for (PetscInt k = 0; k < dim; k++) {
      if (!inner) cs[k] += f[k]; /* between the bodies: no part of the resultant on the whole mesh */
      if (nd > 1) a += f[k] * f[k];
      else cs[3] += (inner ? 2 : 1) * PetscAbsReal(f[k]);
    }
    if (nd > 1) cs[3] += (inner ? 2 : 1) * PetscSqrtReal(a); /* -contact_kkt_scale vertex: its magnitude, the same turned */
    cm = PetscMax(cm, fm);
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, cs, 4, MPIU_REAL, MPI_SUM, c->comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &cm, 1, MPIU_REAL, MPI_MAX, c->comm));
  for (PetscInt k = 0; k < dim; k++) sc->res[k] += cs[k];
  sc->l1 += cs[3];
  PetscCall(SgVecVertexNormMax(y, nd, &ynorm));
  PetscCall(SgElasticityStiffnessDisplacementMax(c->prob, y, nd, ynorm, &yk)); /* ynorm with one material */
  PetscCall(SgElasticityGetScales(c->prob, &Knorm, NULL, &bnorm_inf));
  PetscCall(SgElasticityGetDataScales(c->prob, &ucur, &ufull, &bfull, &floads, &diam));
  PetscCall(SgElasticityGetMaterial(c->prob, &E, &nu));
  PetscCall(SgLame(E, nu, &lambda, &mu));
  sc->rnoise = PETSC_MACHINE_EPSILON * (Knorm * yk + bnorm_inf);
  sc->F      = PetscMax(PetscMax(fmax, smax), PetscMax(cm, 2 * mu / (lambda + 2 * mu) * Knorm * yk));
  sc->Y      = PetscMax(PetscMax(ynorm, PetscMax(pen, 0)), ucur);
  sc->zero   = (PetscBool)(fmax == 0 && ucur == 0 && !(pen > 0));
  if (sc->zero) {
    /* the full load's: its Dirichlet values, obstacle translation, and the displacement its total load ||f||_1 makes
       through the shear modulus (strain ||f||_1 / (mu L^(dim-1)) over the length L); the force scale of that */
    PetscReal Yf;
    PetscCall(SgObstacleGetTranslation(c->obs, T));
    Yf = PetscMax(PetscMax(ufull, PetscSqrtReal(T[0] * T[0] + T[1] * T[1] + T[2] * T[2])), floads / (mu * PetscPowReal(diam, dim - 2)));
    if (!(Yf > 0)) Yf = diam;
    sc->Y = PetscMax(sc->Y, Yf);
    sc->F = PetscMax(sc->F, PetscMax(bfull, 2 * mu / (lambda + 2 * mu) * Knorm * Yf));
  }
  PetscFunctionReturn(0);
}

/* KKT measures of the original problem (P) for a displacement y. The multiplier is the one that balances the normal
   residual at the contact vertices, lam_i = -(K y - b)_i.n_i / w_i: for the methods' own multipliers it agrees up to
   round-off, but it does not carry the round-off of gamma (tau_N y - d) at large gamma into the equilibrium measure.
   Every part is dimensionless, so that a tolerance means the same for any load level, material scale and unit system:
   forces are measured against the force scale F (the largest nodal force acting on the body, see ComputeScales),
   lengths against the displacement scale Y as root mean squares over Gamma_c. roundoff = eps (||K|| ||y|| + ||b||) / F
   is what double precision can certify of the force measures: above the tolerance the problem cannot be solved to it
   (a nearly incompressible material, lambda / mu large). */
PetscErrorCode SgContactKKT(SgContact c, Vec y, SgKKT *kkt)
{
  const PetscInt     dim = c->dim;
  Vec                R, Ky;
  PetscScalar       *ra;
  const PetscScalar *ya;
  PetscReal         *g, *lam, s[8] = {0}, mx[3] = {0, 0, 0}, nrm, ynrm, bal = 0, letgo = 0;
  KKTScales          sc;
  PetscInt           nd;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetNodalNormSize(c->prob, &nd));
  PetscCall(PetscMalloc2(c->n, &g, c->n, &lam));
  PetscCall(VecDuplicate(y, &R));
  PetscCall(VecDuplicate(y, &Ky));
  PetscCall(MatMult(c->K, y, Ky));
  PetscCall(VecWAXPY(R, -1.0, c->b, Ky));
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(SgContactGap(c, ya, g));
  PetscCall(VecRestoreArrayRead(y, &ya));
  PetscCall(VecGetArray(R, &ra));
  /* the fixed components of rollers are data: their decoupled unknowns (0 up to the linear solver's error) are no
     part of the equilibrium of the body */
  for (PetscInt v = 0; v < c->mesh->nv; v++)
    if (c->mesh->goff[v] >= 0 && SgMeshPartial(c->mesh, v))
      for (PetscInt k = 0; k < dim; k++)
        if (SgMeshFixed(c->mesh, v, k)) ra[c->mesh->goff[v] + k] = 0;
  for (PetscInt i = 0; i < c->n; i++) {
    PetscReal rn = 0;
    for (PetscInt k = 0; k < dim; k++) rn += PetscRealPart(ra[c->off[i] + k]) * c->normal[i * dim + k];
    lam[i] = -rn / c->w[i];
    mx[0]  = PetscMax(mx[0], PetscAbsReal(lam[i]));
    mx[1]  = PetscMax(mx[1], c->w[i] * PetscMax(0, -lam[i])); /* nodal force a pressure >= 0 cannot balance */
    mx[2]  = PetscMax(mx[2], -c->d[i]);                       /* initial penetration */
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, mx, 3, MPIU_REAL, MPI_MAX, c->comm));
  PetscCall(ComputeScales(c, y, ra, lam, mx[2], &sc));
  for (PetscInt k = 0; k < dim; k++) bal += PetscSqr(sc.res[k]);
  bal = PetscSqrtReal(bal);
  PetscCall(SgVecVertexNormMax(y, nd, &ynrm));
  for (PetscInt i = 0; i < c->n; i++) {
    /* pressure counts as acting above the round-off of the derived multiplier (ForceNoise) and a tiny fraction of
       the largest pressure. A pressure at an open gap violates complementarity either way: as a force (w lam / F, an
       unbalanced nodal force if the vertex is let go) or as a length (the gap, if it is held): the smaller counts, so
       that an inexact solve's tiny pressure at a far open gap, or a tiny gap under a real pressure, is measured for
       what it is. One definition: the fields and the friction states use these flags too. */
    const PetscReal rf = SafeRatio(c->w[i] * lam[i], sc.F), rg = SafeRatio(-PetscMin(0, g[i]), sc.Y);
    c->klam[i] = lam[i];
    c->kact[i] = (char)(lam[i] > PetscMax(1e-10 * mx[0], ForceNoise(c, &sc, i)) && !(rf < rg));
  }
  PetscCall(SgContactLawKKT(c->law, c, y, ra, lam, ynrm, &sc, &s[3])); /* the law's part (frictionless: none) */
  PetscCall(SgContactAddForce(c, lam, ra));                            /* what is left: interior (and, without friction, tangential) residual */
  PetscCall(VecRestoreArray(R, &ra));
  for (PetscInt i = 0; i < c->n; i++) {
    const PetscBool act = (PetscBool)c->kact[i]; /* the active set of the fields and of the friction states too */
    const PetscReal rf = SafeRatio(c->w[i] * lam[i], sc.F), rg = SafeRatio(-PetscMin(0, g[i]), sc.Y);
    if (!act && rf < rg) letgo = PetscMax(letgo, c->w[i] * lam[i]);                      /* let go: its force is unbalanced */
    s[0] += c->w[i] * PetscSqr(PetscMax(0, g[i]));                                       /* infeasibility^2 */
    s[1] += c->w[i] * (act ? PetscSqr(PetscMin(0, g[i])) : PetscSqr(PetscMax(0, g[i]))); /* complementarity^2 */
    s[4] += c->w[i] * PetscMax(0, g[i]);                                                 /* rho_F */
    s[5] += c->w[i] * (act ? -PetscMin(0, g[i]) : PetscMax(0, g[i]));                    /* rho_C */
    s[6] += c->w[i] * lam[i];                                                            /* contact force */
    s[7] += (act ? 1 : 0);
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, s, 8, MPIU_REAL, MPI_SUM, c->comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &letgo, 1, MPIU_REAL, MPI_MAX, c->comm));
  /* the largest nodal force left unbalanced (a vertex's Euclidean length), against the largest force acting: its
     round-off floor rnoise / F is reported beside it (kkt->roundoff) */
  PetscCall(SgVecVertexNormMax(R, nd, &nrm));
  kkt->uscale        = sc.Y;
  kkt->lscale        = sc.Y * PetscSqrtReal(c->area);
  kkt->fscale        = sc.F;
  kkt->roundoff      = SafeRatio(sc.rnoise, sc.F);
  kkt->balance       = SafeRatio(bal, sc.l1);
  kkt->penetration   = PetscSqrtReal(s[0]);
  kkt->equilibrium   = SafeRatio(nrm, sc.F);
  kkt->infeasibility = SafeRatio(PetscSqrtReal(s[0]), kkt->lscale);

  c->fsum.slip         = SafeRatio(PetscSqrtReal(s[3]), kkt->lscale); /* the law's parts (0 without friction) */
  kkt->complementarity = PetscMax(SafeRatio(PetscSqrtReal(s[1] + s[3]), kkt->lscale), SafeRatio(letgo, sc.F));
  kkt->dual            = PetscMax(SafeRatio(mx[1], sc.F), c->fsum.bound);
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
   the vector d n from each contact vertex to the obstacle (zero elsewhere; pictures draw the obstacle from it).
   Where the vertex's ray misses the obstacle (d = PETSC_MAX_REAL: a CAD or meshed obstacle of finite extent, a plane
   parallel to the normal) the gap and the vector are NaN, "no obstacle along the normal": 1.8e308 made ParaView hang
   on the gap's colour range and the pictures draw the obstacle thousands of lengths away. */
/* The per-vertex numbers of SgContactKKT at y (klam, kact, klt, kslip, kst) without touching the friction summary or
   the record of the last solve: the fields and the summary's vectors come from the same definitions as its measures. */
static PetscErrorCode ContactStateAt(SgContact c, Vec y)
{
  SgFrictionSummary fs = c->fsum;
  SgKKT             kkt;

  PetscFunctionBeginUser;
  c->norecord = PETSC_TRUE;
  PetscCall(SgContactKKT(c, y, &kkt));
  c->norecord = PETSC_FALSE;
  c->fsum     = fs;
  PetscFunctionReturn(0);
}

/* The contact force on the body sum_i w_i lam_i n_i at y, with SgContactKKT's multiplier (whose sum is its force) */
PetscErrorCode SgContactForceVector(SgContact c, Vec y, PetscReal F[3])
{
  PetscFunctionBeginUser;
  PetscCall(ContactStateAt(c, y));
  F[0] = F[1] = F[2] = 0;
  for (PetscInt i = 0; i < c->n; i++)
    for (PetscInt k = 0; k < c->dim; k++) F[k] += c->w[i] * c->klam[i] * c->normal[i * c->dim + k];
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, F, 3, MPIU_REAL, MPI_SUM, c->comm));
  PetscFunctionReturn(0);
}

/* (lam: unused; the pressure and the active flag are SgContactKKT's, so that the fields integrate to the summary) */
PetscErrorCode SgContactFields(SgContact c, Vec y, const PetscReal lam[], Vec flds[4], Vec obst)
{
  Vec                loc[4];
  PetscScalar       *la[4];
  const PetscScalar *ya;
  PetscReal         *g;
  PetscSection       s;

  PetscFunctionBeginUser;
  (void)lam;
  PetscCall(ContactStateAt(c, y));
  PetscCall(PetscMalloc1(c->n, &g));
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(SgContactGap(c, ya, g));
  PetscCall(VecRestoreArrayRead(y, &ya));
  PetscCall(DMGetLocalSection(c->dmVert, &s));
  for (PetscInt f = 0; f < 4; f++) {
    PetscCall(DMGetLocalVector(c->dmVert, &loc[f]));
    PetscCall(VecZeroEntries(loc[f]));
    PetscCall(VecGetArray(loc[f], &la[f]));
  }
  for (PetscInt i = 0; i < c->n; i++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(s, c->mesh->vStart + c->vert[i], &off));
    la[0][off] = c->klam[i];
    la[1][off] = c->d[i] < PETSC_MAX_REAL ? -g[i] : SG_NAN;
    la[2][off] = PetscMax(0, g[i]);
    la[3][off] = c->kact[i] ? 1 : 0;
  }
  for (PetscInt f = 0; f < 4; f++) {
    PetscCall(VecRestoreArray(loc[f], &la[f]));
    /* only owners hold contact vertices: adding the zeros of the other ranks keeps the owner's value */
    PetscCall(VecZeroEntries(flds[f]));
    PetscCall(DMLocalToGlobal(c->dmVert, loc[f], ADD_VALUES, flds[f]));
    PetscCall(DMRestoreLocalVector(c->dmVert, &loc[f]));
  }
  PetscCall(PetscFree(g));
  {
    Vec            ol;
    PetscScalar   *oa;
    PetscSection   vs;
    const PetscInt dim = c->dim;
    PetscCall(DMGetLocalSection(c->dmVec, &vs));
    PetscCall(DMGetLocalVector(c->dmVec, &ol));
    PetscCall(VecZeroEntries(ol));
    PetscCall(VecGetArray(ol, &oa));
    for (PetscInt i = 0; i < c->n; i++) {
      PetscInt off;
      PetscCall(PetscSectionGetOffset(vs, c->mesh->vStart + c->vert[i], &off));
      for (PetscInt k = 0; k < dim; k++) oa[off + k] = c->d[i] < PETSC_MAX_REAL ? PetscMin(c->d[i], 1e3 * c->area) * c->normal[i * dim + k] : SG_NAN;
    }
    PetscCall(VecRestoreArray(ol, &oa));
    PetscCall(VecZeroEntries(obst));
    PetscCall(DMLocalToGlobal(c->dmVec, ol, ADD_VALUES, obst));
    PetscCall(DMRestoreLocalVector(c->dmVec, &ol));
  }
  PetscFunctionReturn(0);
}

/* The law's output fields (SgContactLawGetFields) at y: the per-vertex record of SgContactKKT at y, written by the
   law's op (none for the frictionless law); zero elsewhere */
PetscErrorCode SgContactLawFields(SgContact c, Vec y, Vec fields[])
{
  PetscFunctionBeginUser;
  PetscCall(ContactStateAt(c, y));
  PetscCall(SgContactLawFillFields(c->law, c, fields));
  PetscFunctionReturn(0);
}

/* The slip reference of y into ref (2 n dim: of the unknowns, then of the full displacement, which is written only
   where components of contact vertices are prescribed and is left as it is otherwise; y NULL: zero, the first step's
   start), without installing it */
PetscErrorCode SgContactComputeSlipReference(SgContact c, Vec y, PetscReal ref[])
{
  const PetscScalar *ya;
  PetscReal         *pref = ref + c->n * c->dim;

  PetscFunctionBeginUser;
  if (!y) {
    PetscCall(PetscArrayzero(ref, 2 * c->n * c->dim));
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(SgContactVertexDisplacements(c, ya, ref)); /* two bodies: the relative displacements */
  if (c->haspartial) {
    /* prescribed components: the data of the step y solved, recorded by its SgContactKKT (by now the problem may
       hold the next step's data); otherwise the problem's current data */
    PetscInt same = c->haverecord ? 1 : 0;
    for (PetscInt i = 0; i < c->n * c->dim && same; i++) same = c->ypfull[c->n * c->dim + i] == ref[i];
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPIU_INT, MPI_MIN, c->comm));
    if (same) PetscCall(PetscArraycpy(pref, c->ypfull, c->n * c->dim));
    else {
      Vec                yloc;
      const PetscScalar *ul;
      PetscCall(DMGetLocalVector(c->dm, &yloc));
      PetscCall(SgElasticityGlobalToLocal(c->prob, y, yloc));
      PetscCall(VecGetArrayRead(yloc, &ul));
      for (PetscInt i = 0; i < c->n; i++)
        for (PetscInt k = 0; k < c->dim; k++) pref[i * c->dim + k] = PetscRealPart(ul[c->mesh->loff[c->vert[i]] + k]);
      PetscCall(VecRestoreArrayRead(yloc, &ul));
      PetscCall(DMRestoreLocalVector(c->dm, &yloc));
    }
  }
  PetscCall(VecRestoreArrayRead(y, &ya));
  PetscFunctionReturn(0);
}

/* The start of a load step's slip: yref = y at the contact vertices (NULL: zero, the first step's start). The
   tangential law of the step acts on the increment T_i (y_i - yref_i): quasi-static incremental friction. */
PetscErrorCode SgContactSetSlipReference(SgContact c, Vec y)
{
  PetscFunctionBeginUser;
  if (!c->yref) PetscFunctionReturn(0);
  PetscCall(SgContactComputeSlipReference(c, y, c->yref));
  PetscFunctionReturn(0);
}

/* the slip reference itself (dim per contact vertex; NULL without friction), for the checkpoint; 2 n dim numbers: of
   the unknowns (what the solvers use), then of the full displacement (the data on the prescribed components) */
PetscErrorCode SgContactGetSlipReference(SgContact c, PetscReal **yref)
{
  PetscFunctionBeginUser;
  *yref = c->yref;
  PetscFunctionReturn(0);
}

/* the axis k with normal i = +-e_k (and its sign), or -1 */
static PetscInt NormalAxis(SgContact c, PetscInt i, PetscReal *sign)
{
  for (PetscInt k = 0; k < c->dim; k++)
    if (PetscAbsReal(PetscAbsReal(c->normal[i * c->dim + k]) - 1) < 1e-10) {
      *sign = c->normal[i * c->dim + k] > 0 ? 1 : -1;
      return k;
    }
  return -1;
}

/* Every contact normal must be +-e_k (for the bound-constrained baselines and the truncated multigrid without the
   contact frames); returns k and the sign per vertex. Collective: the verdict is global, so every rank stops with the
   same error (naming the first offending vertex of the lowest rank that has one), also a rank without such a vertex
   or without any contact vertex, which would otherwise go on into the next collective call and wait there. */
PetscErrorCode SgContactAxisAligned(SgContact c, const char who[], PetscInt axis[], PetscReal sign[])
{
  const PetscInt dim = c->dim;
  PetscInt       bad = -1;
  PetscMPIInt    rank, size, owner;
  PetscReal      xn[6] = {0, 0, 0, 0, 0, 0}; /* the offending vertex and its normal */

  PetscFunctionBeginUser;
  PetscCheck(!c->pair, c->comm, PETSC_ERR_SUP, "%s is not available for two-body contact (-contact_master_ids): its conditions couple the two sides; use an SSN-based controller (fast, ipf, pf, alm) with the default linear solver or MUMPS, or the baseline pdas (in the pair's basis)", who);
  for (PetscInt i = 0; i < c->n; i++) {
    axis[i] = NormalAxis(c, i, &sign[i]);
    if (axis[i] < 0 && bad < 0) bad = i;
  }
  PetscCallMPI(MPI_Comm_rank(c->comm, &rank));
  PetscCallMPI(MPI_Comm_size(c->comm, &size));
  owner = bad >= 0 ? rank : size;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &owner, 1, MPI_INT, MPI_MIN, c->comm));
  if (owner == size) PetscFunctionReturn(0);
  if (rank == owner)
    for (PetscInt a = 0; a < dim; a++) {
      xn[a]     = c->mesh->x[c->vert[bad] * dim + a];
      xn[3 + a] = c->normal[bad * dim + a];
    }
  PetscCallMPI(MPI_Bcast(xn, 6, MPIU_REAL, owner, c->comm));
  SETERRQ(c->comm, PETSC_ERR_USER_INPUT, "%s needs contact normals along a coordinate axis; the vertex at (%g, %g, %g) has normal (%g, %g, %g)%s", who, (double)xn[0], (double)xn[1], (double)xn[2], (double)xn[3], (double)xn[4], (double)xn[5], c->obsnormal ? " (the obstacle's, -contact_normal obstacle)" : " (the body's, averaged over its contact facets: -contact_normal obstacle takes the obstacle's)");
}

/* whether every contact normal, on every rank, is +-e_k (the question of SgContactAxisAligned, without the error) */
PetscErrorCode SgContactNormalsAxisAligned(SgContact c, PetscBool *aligned)
{
  PetscInt  ok = 1;
  PetscReal sign;

  PetscFunctionBeginUser;
  if (c->pair) { /* two bodies: no contact frames of their own (a row couples both sides): pdas takes the pair's basis (SgContBoundFrame), vi is refused in SgContactAxisAligned */
    *aligned = PETSC_TRUE;
    PetscFunctionReturn(0);
  }
  for (PetscInt i = 0; i < c->n && ok; i++)
    if (NormalAxis(c, i, &sign) < 0) ok = 0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPIU_INT, MPI_MIN, c->comm));
  *aligned = (PetscBool)ok;
  PetscFunctionReturn(0);
}


static inline PetscInt64 Mix64(PetscInt64 x)
{
  uint64_t z = (uint64_t)x + 0x9e3779b97f4a7c15ULL;
  z          = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z          = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return (PetscInt64)(z ^ (z >> 31));
}

/* Order-independent hash of a set of contact vertices (act[i] != 0), over global vertex numbers: identical on every
   rank and for every partition (cycle detection of the active-set methods). */
PetscErrorCode SgContactActiveSetHash(SgContact c, const char act[], PetscInt64 *h)
{
  uint64_t loc = 0;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < c->n; i++)
    if (act[i]) loc += (uint64_t)Mix64(c->mesh->gblock[c->vert[i]]);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &loc, 1, MPI_UINT64_T, MPI_SUM, c->comm));
  *h = (PetscInt64)loc;
  PetscFunctionReturn(0);
}

/* the gap d of contact vertex i along its normal with the obstacle at its current placement: body, along the ray;
   obstacle, to the tangent plane at the closest point (the normal is the one of the set-up: a translation does not
   turn the obstacle; the closest point moves along) */
static PetscErrorCode VertexGap(SgContact c, PetscInt i, PetscReal *d)
{
  const PetscInt   dim = c->dim;
  const PetscReal *x = &c->mesh->x[c->vert[i] * dim], *n = &c->normal[i * dim];

  PetscFunctionBeginUser;
  if (c->pair && !c->obsrow[i]) { /* two bodies: the weighted gap of the reference configuration, at every placement */
    *d = c->d[i];
    PetscFunctionReturn(0);
  }
  if (c->obsnormal) {
    PetscReal nrm[3], dd, dot = 0;
    PetscBool keep;
    PetscCall(ObstacleCondition(c, c->vert[i], nrm, &dd, &keep));
    for (PetscInt k = 0; k < dim; k++) dot += nrm[k] * n[k];
    *d = keep && dot > 0 ? dd / dot : PETSC_MAX_REAL;
  } else PetscCall(SgObstacleGap(c->obs, x, n, d));
  PetscFunctionReturn(0);
}

/* Load stepping: the obstacle at t times its translation (-obstacle_translation), the gaps d recomputed from it (for
   every obstacle type: the translation is applied in SgObstacleGap), and the load scale of the KKT measures (the
   elasticity object's loads must be scaled first). */
PetscErrorCode SgContactSetLoadFactor(SgContact c, PetscReal t)
{
  PetscReal T[3];
  PetscBool moves;

  PetscFunctionBeginUser;
  PetscCall(SgObstacleGetTranslation(c->obs, T));
  moves = (PetscBool)(T[0] != 0 || T[1] != 0 || T[2] != 0);
  PetscCall(SgObstacleSetPlacement(c->obs, t));
  /* the gaps change only with a translation (a CAD obstacle's queries cost about 0.6 ms a vertex); a pair's rows do
     not (its obstacle rows do) */
  if (moves)
    for (PetscInt i = 0; i < c->n; i++)
      if (!c->pair || c->obsrow[i]) PetscCall(VertexGap(c, i, &c->d[i]));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactGetObstacleTranslation(SgContact c, PetscReal T[3])
{
  PetscFunctionBeginUser;
  PetscCall(SgObstacleGetTranslation(c->obs, T));
  PetscFunctionReturn(0);
}

/* sum_i w_i d_i with the obstacle placed at t (the placement is restored): a fingerprint of the obstacle for the
   checkpoint, the same at every load step */
PetscErrorCode SgContactGapSum(SgContact c, PetscReal t, PetscReal *sum)
{
  PetscReal s = 0, d, now = c->obs->placement;

  PetscFunctionBeginUser;
  PetscCall(SgObstacleSetPlacement(c->obs, t));
  for (PetscInt i = 0; i < c->n; i++) {
    if (t == now) d = c->d[i];
    else PetscCall(VertexGap(c, i, &d));
    if (d < PETSC_MAX_REAL) s += c->w[i] * d; /* a ray that misses the obstacle (d = PETSC_MAX_REAL) would make it inf */
  }
  PetscCall(SgObstacleSetPlacement(c->obs, now));
  PetscCallMPI(MPI_Allreduce(&s, sum, 1, MPIU_REAL, MPI_SUM, c->comm));
  PetscFunctionReturn(0);
}

/* the gaps d_i of this rank's contact vertices with the obstacle at a placement t (PETSC_MAX_REAL where a ray misses
   it); the obstacle stays where it is */
PetscErrorCode SgContactGapsAt(SgContact c, PetscReal t, PetscReal d[])
{
  const PetscReal now = c->obs->placement;

  PetscFunctionBeginUser;
  PetscCall(SgObstacleSetPlacement(c->obs, t));
  for (PetscInt i = 0; i < c->n; i++) {
    if (t == now) d[i] = c->d[i];
    else PetscCall(VertexGap(c, i, &d[i]));
  }
  PetscCall(SgObstacleSetPlacement(c->obs, now));
  PetscFunctionReturn(0);
}

/* the largest normal displacement n_i . y_i over the contact vertices (towards the obstacle: positive) */
PetscErrorCode SgContactNormalDisplacementMax(SgContact c, Vec y, PetscReal *mx)
{
  const PetscScalar *ya;
  PetscReal          m = PETSC_MIN_REAL;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(y, &ya));
  for (PetscInt i = 0; i < c->n; i++) {
    PetscReal un = 0;
    for (PetscInt k = 0; k < c->dim; k++) un += c->normal[i * c->dim + k] * PetscRealPart(ya[c->off[i] + k]);
    m = PetscMax(m, un);
  }
  PetscCall(VecRestoreArrayRead(y, &ya));
  PetscCallMPI(MPI_Allreduce(&m, mx, 1, MPIU_REAL, MPI_MAX, c->comm));
  PetscFunctionReturn(0);
}
