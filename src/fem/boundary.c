/* boundary.c: the boundary parts (Dirichlet, Neumann, contact): their options, labels, points, facets and vertices,
   and the geometry of a boundary facet. */
#include "fem/femimpl.h"

/* Read -<what>_label, -<what>_ids and (if ncomp > 0) -<what>_<valname>: ncomp numbers per id. An option given without
   a value is an error (PETSc would report it as not set, and the part would silently vanish). */
PetscErrorCode SgBoundaryFromOptions(PetscOptionItems *PetscOptionsObject, SgBoundary *bnd, PetscInt ncomp, const char *valname, const char *help)
{
  char      opt[64], txt[256], name[256], pre[256];
  PetscInt  n = bnd->nids;
  PetscBool set;

  PetscFunctionBeginUser;
  /* messages name the option as the user types it: with the prefix */
  PetscCall(PetscSNPrintf(pre, sizeof(pre), "%s", PetscOptionsObject->prefix ? PetscOptionsObject->prefix : ""));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s_label", bnd->what));
  PetscCall(SgOptionsName(pre, opt, name, sizeof(name)));
  PetscCall(PetscSNPrintf(txt, sizeof(txt), "Label marking the %s boundary", help));
  PetscCall(PetscOptionsString(opt, txt, NULL, bnd->label, bnd->label, sizeof(bnd->label), &set));
  if (set) {
    PetscCheck(bnd->label[0], PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s is given without a value (a label name)", name);
    bnd->active = PETSC_TRUE;
  }
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s_ids", bnd->what));
  PetscCall(PetscSNPrintf(txt, sizeof(txt), "Values of the %s label making the %s boundary (none: every value)", bnd->what, help));
  PetscCall(SgOptionsIntList(PetscOptionsObject, opt, txt, SG_MAX_IDS, bnd->ids, &n, &set));
  if (set) {
    bnd->nids   = n;
    bnd->active = PETSC_TRUE;
  }
  if (ncomp > 0) {
    PetscInt nv = bnd->nvalues, need = ncomp * PetscMax(bnd->nids, 1);

    PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s_%s", bnd->what, valname));
    PetscCall(SgOptionsName(pre, opt, name, sizeof(name)));
    PetscCall(PetscSNPrintf(txt, sizeof(txt), "%s: %" PetscInt_FMT " numbers per label value", help, ncomp));
    PetscCall(SgOptionsRealList(PetscOptionsObject, opt, txt, 3 * SG_MAX_IDS, bnd->values, &nv, &set));
    if (set) {
      PetscCheck(bnd->active, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s is given, but no -%s%s_label or -%s%s_ids says where", name, pre, bnd->what, pre, bnd->what);
      PetscCheck(nv == need, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s: got %" PetscInt_FMT " numbers, need %" PetscInt_FMT " (%" PetscInt_FMT " per value of %s_ids)", name, nv, need, ncomp, bnd->what);
      bnd->nvalues = nv;
      for (PetscInt i = 0; i < nv; i++) PetscCheck(PetscIsNormalReal(bnd->values[i]) || bnd->values[i] == 0, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s: entry %" PetscInt_FMT " is %g, must be finite", name, i, (double)bnd->values[i]);
    }
  }
  PetscFunctionReturn(0);
}

/* -<what>_components: which components a Dirichlet part fixes, one word per id (one if the part has no ids), made of
   the letters x, y (and z in 3D): "xyz" fixes all (the default), "x" only u_x (a roller, a symmetry plane x = c). */
PetscErrorCode SgBoundaryComponentsFromOptions(PetscOptionItems *PetscOptionsObject, SgBoundary *bnd, PetscInt dim)
{
  char      opt[64], name[256], pre[256], *words[SG_MAX_IDS];
  PetscInt  n = SG_MAX_IDS, need = PetscMax(bnd->nids, 1);
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(pre, sizeof(pre), "%s", PetscOptionsObject->prefix ? PetscOptionsObject->prefix : ""));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s_components", bnd->what));
  PetscCall(SgOptionsName(pre, opt, name, sizeof(name)));
  PetscCall(PetscOptionsStringArray(opt, dim == 2 ? "Components fixed per label value: x, y or xy (default xy)" : "Components fixed per label value: letters of xyz, e.g. x, yz (default xyz)", NULL, words, &n, &set));
  {
    /* PETSc reads an empty value as not set and drops empty entries: both would silently fix every component */
    const char *val;
    PetscBool   has;
    size_t      len;
    PetscCall(PetscOptionsFindPair(NULL, PetscOptionsObject->prefix, opt, &val, &has));
    if (has) {
      PetscCheck(val && val[0], PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s is given without a value (x, y%s per id)", name, dim == 3 ? ", z, xy, ..." : " or xy");
      PetscCall(PetscStrlen(val, &len));
      PetscCheck(val[0] != ',' && val[len - 1] != ',' && !strstr(val, ",,"), PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s '%s': an entry is empty", name, val);
    }
  }
  if (!set) {
    /* SgProblemSetDirichletComponents: its masks must still fit the ids and the dimension */
    for (PetscInt i = 0; i < bnd->ncomps; i++) PetscCheck(bnd->comps[i] > 0 && bnd->comps[i] < (1 << dim), PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "SgProblemSetDirichletComponents: mask %" PetscInt_FMT " is %" PetscInt_FMT ", must be a nonzero sum of SG_COMPONENT_X, SG_COMPONENT_Y%s", i, bnd->comps[i], dim == 3 ? ", SG_COMPONENT_Z" : " (2D)");
    PetscCheck(!bnd->ncomps || bnd->ncomps == need, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "SgProblemSetDirichletComponents: got %" PetscInt_FMT " masks, need %" PetscInt_FMT " (one per Dirichlet id)", bnd->ncomps, need);
    PetscFunctionReturn(0);
  }
  PetscCheck(bnd->active, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s is given, but no -%s%s_label or -%s%s_ids says where", name, pre, bnd->what, pre, bnd->what);
  PetscCheck(n > 0, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s is given without a value (x, y%s per id)", name, dim == 3 ? ", z, xy, ..." : " or xy");
  for (PetscInt i = 0; i < n; i++) {
    PetscInt mask = 0;
    for (const char *c = words[i]; *c; c++) {
      const PetscInt d = *c == 'x' ? 0 : *c == 'y' ? 1
                                     : *c == 'z'   ? 2
                                                   : -1;
      PetscCheck(d >= 0 && d < dim, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s: entry %" PetscInt_FMT " '%s' has '%c': use the letters x, y%s", name, i, words[i], *c, dim == 3 ? ", z" : " (2D)");
      PetscCheck(!(mask & (1 << d)), PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s: entry %" PetscInt_FMT " '%s' names '%c' twice", name, i, words[i], *c);
      mask |= 1 << d;
    }
    PetscCheck(mask, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s: entry %" PetscInt_FMT " is empty (a part fixing nothing is no Dirichlet part)", name, i);
    bnd->comps[i] = mask;
  }
  for (PetscInt i = 0; i < n; i++) PetscCall(PetscFree(words[i]));
  PetscCheck(n == need, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s: got %" PetscInt_FMT " entries, need %" PetscInt_FMT " (one per value of -%s%s_ids)", name, n, need, pre, bnd->what);
  bnd->ncomps = n;
  PetscFunctionReturn(0);
}

/* The label of a boundary part; an error naming the option if the mesh lacks it or a requested value. */
PetscErrorCode SgBoundaryGetLabel(DM dm, const SgBoundary *bnd, DMLabel *label)
{
  MPI_Comm comm;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)dm, &comm));
  PetscCall(DMGetLabel(dm, bnd->label, label));
  PetscCheck(*label, comm, PETSC_ERR_USER_INPUT, "-%s_label: the mesh has no label '%s' (see -dm_view for its labels; gmsh physical names need -dm_plex_gmsh_use_regions)", bnd->what, bnd->label);
  for (PetscInt i = 0; i < bnd->nids; i++) {
    PetscInt n;
    PetscCall(DMLabelGetStratumSize(*label, bnd->ids[i], &n));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPIU_INT, MPI_SUM, comm));
    PetscCheck(n > 0, comm, PETSC_ERR_USER_INPUT, "-%s_ids: label '%s' has no points with value %" PetscInt_FMT, bnd->what, bnd->label, bnd->ids[i]);
  }
  PetscFunctionReturn(0);
}

/* Call fn(point, part) for every point of the boundary part. */
static PetscErrorCode BoundaryForEachPoint(DM dm, const SgBoundary *bnd, PetscErrorCode (*fn)(void *, PetscInt, PetscInt), void *ctx)
{
  DMLabel         label;
  IS              vis = NULL;
  PetscInt        nvals;
  const PetscInt *vals;

  PetscFunctionBeginUser;
  if (!bnd->active) PetscFunctionReturn(0);
  PetscCall(SgBoundaryGetLabel(dm, bnd, &label));
  if (bnd->nids) {
    nvals = bnd->nids;
    vals  = bnd->ids;
  } else {
    PetscCall(DMLabelGetValueIS(label, &vis));
    PetscCall(ISGetLocalSize(vis, &nvals));
    PetscCall(ISGetIndices(vis, &vals));
  }
  for (PetscInt i = 0; i < nvals; i++) {
    IS              is;
    PetscInt        n;
    const PetscInt *pts;

    PetscCall(DMLabelGetStratumIS(label, vals[i], &is));
    if (!is) continue;
    PetscCall(ISGetLocalSize(is, &n));
    PetscCall(ISGetIndices(is, &pts));
    for (PetscInt p = 0; p < n; p++) PetscCall(fn(ctx, pts[p], bnd->nids ? i : 0));
    PetscCall(ISRestoreIndices(is, &pts));
    PetscCall(ISDestroy(&is));
  }
  if (vis) {
    PetscCall(ISRestoreIndices(vis, &vals));
    PetscCall(ISDestroy(&vis));
  }
  PetscFunctionReturn(0);
}

typedef struct {
  DM              dm;
  PetscInt        fStart, fEnd, vStart, vEnd;
  PetscInt        n, *facets, *part;   /* facet collection */
  PetscInt       *vpart;               /* vertex marking */
  PetscInt        dim, *vmask, *vcomp; /* Dirichlet components: fixed per vertex (bits), part per vertex component */
  const PetscInt *comps;               /* components per part (NULL: all) */
} PointCollect;

static PetscErrorCode CollectFacet(void *ctx, PetscInt p, PetscInt part)
{
  PointCollect *pc = (PointCollect *)ctx;

  PetscFunctionBeginUser;
  if (p < pc->fStart || p >= pc->fEnd) PetscFunctionReturn(0);
  if (pc->facets) {
    pc->facets[pc->n] = p;
    pc->part[pc->n]   = part;
  }
  pc->n++;
  PetscFunctionReturn(0);
}

static PetscErrorCode MarkClosureVertices(void *ctx, PetscInt p, PetscInt part)
{
  PointCollect *pc = (PointCollect *)ctx;
  PetscInt     *cl = NULL, ncl;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetTransitiveClosure(pc->dm, p, PETSC_TRUE, &ncl, &cl));
  for (PetscInt q = 0; q < 2 * ncl; q += 2) {
    PetscInt i, mask;
    if (cl[q] < pc->vStart || cl[q] >= pc->vEnd) continue;
    i    = cl[q] - pc->vStart;
    mask = pc->comps ? pc->comps[part] : (1 << pc->dim) - 1;
    if (pc->vpart[i] < 0) pc->vpart[i] = part;
    if (!pc->vmask) continue;
    /* a component fixed by several parts takes the value of the first */
    for (PetscInt d = 0; d < pc->dim; d++)
      if ((mask >> d & 1) && pc->vcomp[i * pc->dim + d] < 0) pc->vcomp[i * pc->dim + d] = part;
    pc->vmask[i] |= mask;
  }
  PetscCall(DMPlexRestoreTransitiveClosure(pc->dm, p, PETSC_TRUE, &ncl, &cl));
  PetscFunctionReturn(0);
}

/* The local facets (codimension-1 points) of a boundary part and the index of the label value of each. */
PetscErrorCode SgBoundaryGetFacets(DM dm, const SgBoundary *bnd, PetscInt *n, PetscInt **facets, PetscInt **part)
{
  PointCollect pc = {dm, 0, 0, 0, 0, 0, NULL, NULL, NULL, 0, NULL, NULL, NULL};

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetHeightStratum(dm, 1, &pc.fStart, &pc.fEnd));
  PetscCall(BoundaryForEachPoint(dm, bnd, CollectFacet, &pc));
  PetscCall(PetscMalloc2(pc.n, facets, pc.n, part));
  pc.facets = *facets;
  pc.part   = *part;
  *n        = pc.n;
  pc.n      = 0;
  PetscCall(BoundaryForEachPoint(dm, bnd, CollectFacet, &pc));
  PetscFunctionReturn(0);
}

/* Mark the vertices in the closure of the part's points in the mesh arrays: the first part of each (bcgroup), the
   components it fixes (bcmask: the part's components, or all) and the first part fixing each component (bcpart). */
PetscErrorCode SgBoundaryMarkVertices(DM dm, const SgBoundary *bnd, SgMesh *m)
{
  PointCollect pc;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&pc, sizeof(pc)));
  pc.dm     = dm;
  pc.vStart = m->vStart;
  pc.vEnd   = m->vStart + m->nv;
  pc.vpart  = m->bcgroup;
  pc.dim    = m->dim;
  pc.vmask  = m->bcmask;
  pc.vcomp  = m->bcpart;
  pc.comps  = bnd->ncomps ? bnd->comps : NULL;
  PetscCall(BoundaryForEachPoint(dm, bnd, MarkClosureVertices, &pc));
  PetscFunctionReturn(0);
}

/* Vertices (local numbers), measure and outward unit normal of a boundary facet. */
PetscErrorCode SgFacetGeometry(DM dm, const SgMesh *m, PetscInt f, PetscInt *nfv, PetscInt fv[], PetscReal *area, PetscReal normal[])
{
  const PetscInt   dim = m->dim;
  PetscInt        *cl = NULL, ncl, k = 0, ns;
  const PetscInt  *supp;
  PetscReal        e[2][3] = {{0}}, nrm = 0, dir = 0;
  const PetscReal *x0;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetTransitiveClosure(dm, f, PETSC_TRUE, &ncl, &cl));
  for (PetscInt q = 0; q < 2 * ncl; q += 2)
    if (cl[q] >= m->vStart && cl[q] < m->vStart + m->nv) fv[k++] = cl[q] - m->vStart;
  PetscCall(DMPlexRestoreTransitiveClosure(dm, f, PETSC_TRUE, &ncl, &cl));
  PetscCheck(k == dim, PETSC_COMM_SELF, PETSC_ERR_PLIB, "facet %" PetscInt_FMT " has %" PetscInt_FMT " vertices", f, k);
  *nfv = k;
  x0   = &m->x[fv[0] * dim];
  for (PetscInt a = 1; a < dim; a++)
    for (PetscInt d = 0; d < dim; d++) e[a - 1][d] = m->x[fv[a] * dim + d] - x0[d];
  if (dim == 2) {
    normal[0] = e[0][1];
    normal[1] = -e[0][0];
  } else {
    normal[0] = e[0][1] * e[1][2] - e[0][2] * e[1][1];
    normal[1] = e[0][2] * e[1][0] - e[0][0] * e[1][2];
    normal[2] = e[0][0] * e[1][1] - e[0][1] * e[1][0];
  }
  for (PetscInt d = 0; d < dim; d++) nrm += normal[d] * normal[d];
  nrm   = PetscSqrtReal(nrm);
  *area = dim == 2 ? nrm : 0.5 * nrm;
  /* orient away from the cell: compare with the cell vertex opposite the facet */
  PetscCall(DMPlexGetSupportSize(dm, f, &ns));
  PetscCheck(ns == 1, PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "facet %" PetscInt_FMT " of a boundary part lies inside the mesh (%" PetscInt_FMT " cells)", f, ns);
  PetscCall(DMPlexGetSupport(dm, f, &supp));
  for (PetscInt a = 0; a <= dim; a++) {
    const PetscInt v   = m->cellv[(supp[0] - m->cStart) * (dim + 1) + a];
    PetscBool      onf = PETSC_FALSE;
    for (PetscInt b = 0; b < dim; b++) onf = (PetscBool)(onf || fv[b] == v);
    if (onf) continue;
    for (PetscInt d = 0; d < dim; d++) dir += (m->x[v * dim + d] - x0[d]) * normal[d];
  }
  for (PetscInt d = 0; d < dim; d++) normal[d] /= (dir > 0 ? -nrm : nrm);
  PetscFunctionReturn(0);
}
