/* cont/nested.c: nested iteration (-cont_nested L, issue 27). The first solve of a run is preceded by solves of the
   same problem on the meshes refined L, L-1, ..., 1 times fewer than the given one (contact/coarse.c: the same file
   or box, the same distribution, -dm_refine lowered), each by a controller of the same type and options. Each level
   starts from the one below it, and the finest (the problem itself, unchanged) from the last coarse level:
   - the displacement: P1 interpolation through the regular refinement (DMPlexTransformGetSourcePoint: a fine vertex
     is a coarse vertex or the midpoint of a coarse edge; checked against the coordinates, so that a distribution or
     refinement that does not nest is refused rather than used);
   - the contact state: the multiplier lam is a pressure (an L2 function with lumped weights w_i, ALGORITHMS.md), so
     its nodal values are interpolated the same way, without scaling; it becomes the shift lamhat of a type that
     moves it (alm; with friction the tangential one too) and the multiplier estimate ct->lam (pdas' first active
     set); the path-following types keep lamhat = 0;
   - gamma: the coarse level's last one, where the finer level's controller continues as in a warm load step
     (PrepareWarm; the type's start hooks run, then SgContNestedResume puts gamma and the shift back);
   - V(0): the coarse level's (the finer one's would cost its unconstrained solve, the linear solve nesting saves; it
     enters only the path models of pf/ipf and the summary's V0).
   Only the finest level's steps are the run's counters, history and output; the coarse levels' SSN steps, linear
   iterations and time are in the summary (nested_*). A level that does not converge ends the nesting: the finest level
   then starts cold, as without -cont_nested, and says so. A restart (-restart_file) continues the finest level from
   its checkpoint: no coarse level is solved again; the coarse levels write no checkpoints. */
#include "cont/contimpl.h"
#include <petscdmplextransform.h>

/* The default of -cont_nested, before the options are read: with -dm_refine N >= 1 the problem is first solved on the
   unrefined mesh and on each refinement (N coarser levels), where the mesh kept them (fem/mesh.c: a contact boundary
   of one body, -cont_nested not given; 3D without friction, or 2D with friction or where the solver may be
   iterative) and, in 2D, the linear solver is
   iterative (iterative: SgLinearSolverDefaults' verdict) or there is friction. Not in 2D frictionless with a direct
   solver (with the default condensed MUMPS the coarse levels' factorizations cost what the saved SSN steps save: the
   same CPU time, 0.75-1.0x, at 1e4 ... 6.2e5 unknowns); with friction there is no condensation and every SSN step
   factors K (Example 1 with Coulomb at 1.5e5 unknowns: 0.56x the CPU time). Not with friction in 3D (the Coulomb
   block at 22,500 unknowns with BiCGStab + BoomerAMG: 2.9x the CPU time, its linear solves much harder from the
   nested start at a large gamma; Tresca there 0.38x). Two bodies (each level its own
   pair, contact/coarse.c) by the same rule: the sphere on a block at 121,128 unknowns, with the geometric multigrid
   mapped into the pair's basis (solver/gmg.c), 0.7x the CPU time of the run without (bench/results.md, branch pair3).
   Not for a mesh given by the program or a controller of a coarse level. Measured in bench/nested.md ("The default", "2D and
   friction"). */
PetscErrorCode SgContNestedDefault(SgCont ct, PetscBool iterative)
{
  PetscBool   own, given;
  PetscInt    nref, dim;
  DM          dm;
  PetscObject lv = NULL;
  char        name[64];

  PetscFunctionBeginUser;
  ct->nested_default = PETSC_FALSE;
  if (ct->nested_inner || !ct->c) PetscFunctionReturn(0);
  PetscCall(PetscOptionsHasName(((PetscObject)ct)->options, ((PetscObject)ct)->prefix, "-cont_nested", &given));
  if (given) PetscFunctionReturn(0);
  PetscCall(SgProblemGetRefinement(ct->problem_obj, &own, &nref));
  if (!own || nref < 1) PetscFunctionReturn(0);
  PetscCall(SgElasticityGetDimension(ct->prob, &dim));
  if (dim == 2 && !iterative && !ct->cv.props.nonlinear) PetscFunctionReturn(0); /* 2D direct, frictionless: the levels, if kept, stay unused */
  if (dim == 3 && ct->cv.props.tangential) PetscFunctionReturn(0);               /* (fem/mesh.c keeps no levels there) */
  PetscCall(SgElasticityGetDMs(ct->prob, &dm, NULL, NULL, NULL));
  PetscCall(PetscSNPrintf(name, sizeof(name), "SgNestedLevel%" PetscInt_FMT, nref));
  PetscCall(PetscObjectQuery((PetscObject)dm, name, &lv));
  if (!lv) PetscFunctionReturn(0); /* the mesh kept no hierarchy */
  ct->nested         = nref;
  ct->nested_default = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* -cont_nested against the problem (end of SgContSetFromOptions) */
PetscErrorCode SgContNestedCheck(SgCont ct)
{
  PetscBool own;
  PetscInt  nref;

  PetscFunctionBeginUser;
  if (ct->nested_inner) PetscFunctionReturn(0);
  PetscCheck(ct->nested >= 0, ct->comm, PETSC_ERR_USER_INPUT, "-cont_nested: must be >= 0 (the number of coarser levels solved first; 0: off), got %" PetscInt_FMT, ct->nested);
  if (!ct->nested) PetscFunctionReturn(0);
  PetscCheck(ct->c, ct->comm, PETSC_ERR_USER_INPUT, "-cont_nested %" PetscInt_FMT ": nested iteration solves the contact problem on coarser meshes first; this problem has no contact boundary", ct->nested);
  PetscCall(SgProblemGetRefinement(ct->problem_obj, &own, &nref));
  PetscCheck(own, ct->comm, PETSC_ERR_USER_INPUT, "-cont_nested %" PetscInt_FMT ": the mesh was given by the program (SgProblemSetDM); nested iteration needs a mesh made from the options and refined with -dm_refine", ct->nested);
  PetscCheck(ct->nested <= nref, ct->comm, PETSC_ERR_USER_INPUT, "-cont_nested %" PetscInt_FMT ": the mesh is refined %" PetscInt_FMT " times after distribution (-dm_refine %" PetscInt_FMT "); the coarsest level is the mesh refined -dm_refine - -cont_nested times, so -cont_nested must be at most -dm_refine", ct->nested, nref, nref);
  PetscFunctionReturn(0);
}

/* For every local vertex of b's mesh (the next refinement of a's), the two local vertices of a's mesh it is the
   midpoint of (the same one twice: a vertex of a's mesh). */
static PetscErrorCode VertexMap(SgCont a, SgCont b, PetscInt **map)
{
  DM            dma, dmb;
  const SgMesh *ma, *mb;
  const char   *prefix;
  PetscInt      bad;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetDMs(a->prob, &dma, NULL, NULL, NULL));
  PetscCall(SgElasticityGetDMs(b->prob, &dmb, NULL, NULL, NULL));
  PetscCall(SgElasticityGetMesh(a->prob, &ma));
  PetscCall(SgElasticityGetMesh(b->prob, &mb));
  PetscCall(SgProblemGetOptionsPrefix(a->problem_obj, &prefix));
  PetscCall(SgMeshRefinementMap(dma, dmb, ma, mb, prefix, map, &bad));
  PetscCheck(!bad, a->comm, PETSC_ERR_SUP, "-cont_nested: the mesh of a coarse level, refined once, is not the next level's mesh vertex by vertex (%" PetscInt_FMT " vertices differ): the distribution or the refinement does not nest here (a partitioner that gives another distribution each time, or a transform that reorders the mesh); run without -cont_nested", bad);
  PetscFunctionReturn(0);
}

/* A field of bs numbers per owned contact vertex of a (vals) as a local vector of the vertex DM dmv (bs dofs per
   vertex: a's vertex scalar or vector DM), zero off the contact boundary, ghost vertices included. */
static PetscErrorCode ContactField(SgCont a, DM dmv, PetscInt bs, const PetscReal vals[], Vec loc)
{
  Vec           g;
  PetscSection  s;
  PetscScalar  *la;
  const SgMesh *ma;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetMesh(a->prob, &ma));
  PetscCall(DMGetLocalSection(dmv, &s));
  PetscCall(VecZeroEntries(loc));
  PetscCall(VecGetArray(loc, &la));
  for (PetscInt i = 0; i < a->n; i++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(s, ma->vStart + a->vert[i], &off));
    for (PetscInt k = 0; k < bs; k++) la[off + k] = vals[i * bs + k];
  }
  PetscCall(VecRestoreArray(loc, &la));
  PetscCall(DMGetGlobalVector(dmv, &g));
  PetscCall(DMLocalToGlobal(dmv, loc, INSERT_VALUES, g));
  PetscCall(DMGlobalToLocal(dmv, g, INSERT_VALUES, loc));
  PetscCall(DMRestoreGlobalVector(dmv, &g));
  PetscFunctionReturn(0);
}

/* The interpolation of a contact field of a (bs per owned contact vertex) at b's owned contact vertices */
static PetscErrorCode TransferContactField(SgCont a, SgCont b, const PetscInt map[], PetscBool vector, PetscInt bs, const PetscReal va[], PetscReal vb[])
{
  DM                 dmv;
  Vec                loc;
  PetscSection       s;
  const PetscScalar *la;
  const SgMesh      *ma, *mb;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetDMs(a->prob, NULL, vector ? NULL : &dmv, vector ? &dmv : NULL, NULL));
  PetscCall(SgElasticityGetMesh(a->prob, &ma));
  PetscCall(SgElasticityGetMesh(b->prob, &mb));
  PetscCall(DMGetLocalVector(dmv, &loc));
  PetscCall(ContactField(a, dmv, bs, va, loc));
  PetscCall(DMGetLocalSection(dmv, &s));
  PetscCall(VecGetArrayRead(loc, &la));
  for (PetscInt j = 0; j < b->n; j++) {
    const PetscInt v = b->vert[j];
    PetscInt       o0, o1;
    PetscCall(PetscSectionGetOffset(s, ma->vStart + map[2 * v], &o0));
    PetscCall(PetscSectionGetOffset(s, ma->vStart + map[2 * v + 1], &o1));
    for (PetscInt k = 0; k < bs; k++) vb[j * bs + k] = 0.5 * (PetscRealPart(la[o0 + k]) + PetscRealPart(la[o1 + k]));
  }
  PetscCall(VecRestoreArrayRead(loc, &la));
  PetscCall(DMRestoreLocalVector(dmv, &loc));
  PetscFunctionReturn(0);
}

/* The rim of the interpolated contact zone placed on b's mesh (-cont_nested_rim f > 0). The interpolated displacement
   y makes b's first active set {g_i > 0} (g: the penetration; the shift, if any, is negligible at the coarse level's
   gamma): where the coarse zone ends, a fine vertex between an active and an inactive coarse vertex has the
   interpolated multiplier lam_i > 0 and a small gap, and is left out, though the finer mesh, more flexible, closes
   most such gaps (Example 2 at 144,666 unknowns: 599 active at the start, 626 after the first step, 621 at the end).
   The test of the primal-dual active set method, with the vertex's own normal stiffness per area c_i = n^T K_ii n / w_i
   (the pressure that closes the gap by moving the vertex alone; the body around it yields, so the factor f < 1),
   takes vertex i in where lam_i + f c_i g_i > 0: its normal displacement is mirrored in the obstacle's surface
   (g_i -> -g_i). Not just onto it: the first step's early CG stop (fast) looks at an inexact iterate, whose error at
   the vertex keeps the sign of the start's; a vertex a hair inside was let go by that iterate where the exact step
   keeps it (the quarter hemisphere at 17,022 unknowns: 4 SSN steps, mirrored 1). Vertices that penetrate stay as
   they are; none is taken out; the start only: the answer does not depend on it. */
static PetscErrorCode PlaceRim(SgCont b, const PetscReal lam[], PetscInt *added)
{
  PetscReal    *g, *kn;
  PetscScalar  *ya;
  PetscInt      dim, n = b->n;
  PetscBool     pair;
  const SgMesh *mb;

  PetscFunctionBeginUser;
  *added = 0;
  PetscCall(SgContactIsPair(b->c, &pair));
  if (!(b->nested_rim > 0) || pair) PetscFunctionReturn(0); /* two bodies: the gap is not one vertex's */
  PetscCall(SgElasticityGetDimension(b->prob, &dim));
  PetscCall(SgElasticityGetMesh(b->prob, &mb));
  PetscCall(PetscMalloc2(n, &g, n, &kn));
  PetscCall(SgContNormalStiffness(b, kn));
  PetscCall(VecGetArray(b->y, &ya));
  PetscCall(SgContactGap(b->c, ya, g));
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal *nv   = &b->normal[i * dim];
    const PetscInt   mask = mb->bcmask[b->vert[i]];
    PetscReal        free = 0, move;
    /* a ray that misses the obstacle (g about -PETSC_MAX_REAL) fails the test */
    if (!(g[i] <= 0) || !(lam[i] > 0) || !(lam[i] + b->nested_rim * kn[i] / b->w[i] * g[i] > 0)) continue;
    for (PetscInt k = 0; k < dim; k++)
      if (!((mask >> k) & 1)) free += nv[k] * nv[k];
    if (free < 0.25) continue; /* the fixed components (Dirichlet) stay; too little of the normal is free */
    move = -2 * g[i] / free;   /* along the free part of the normal: the mirror image in the obstacle's surface, g_i -> -g_i */
    for (PetscInt k = 0; k < dim; k++)
      if (!((mask >> k) & 1)) ya[b->off[i] + k] += move * nv[k];
    (*added)++;
  }
  PetscCall(VecRestoreArray(b->y, &ya));
  PetscCall(PetscFree2(g, kn));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, added, 1, MPIU_INT, MPI_SUM, b->comm));
  PetscFunctionReturn(0);
}

/* -info: how many of b's contact vertices start inside the obstacle (g > 0 at the interpolated displacement, before
   the rim is placed) and the deepest; and of the vertices that -dm_refine_geometry put on the geometry (label
   "SgSnapped" of b's DM), which the interpolation carries along with their move: where the coarse level touched, a
   moved vertex starts inside by about its chord's sagitta. Setting their gaps to the coarse level's interpolated ones
   instead was measured worse (bench/results.md "snap32"). Reads only; nothing without -info. */
static PetscErrorCode InfoStart(SgCont b)
{
  DM            dmb;
  DMLabel       lab = NULL;
  PetscScalar  *ya;
  PetscReal    *g, st[2] = {0, 0};  /* deepest, deepest on the geometry */
  PetscInt      cnt[3] = {0, 0, 0}; /* inside, on the geometry and inside, on the geometry */
  PetscBool     pair, info;
  const SgMesh *mb;

  PetscFunctionBeginUser;
  PetscCall(PetscInfoEnabled(SG_CONT_CLASSID, &info));
  PetscCall(SgContactIsPair(b->c, &pair));
  if (!info || pair) PetscFunctionReturn(0);
  PetscCall(SgElasticityGetDMs(b->prob, &dmb, NULL, NULL, NULL));
  PetscCall(DMGetLabel(dmb, "SgSnapped", &lab));
  PetscCall(SgElasticityGetMesh(b->prob, &mb));
  PetscCall(PetscMalloc1(b->n + 1, &g));
  PetscCall(VecGetArray(b->y, &ya));
  PetscCall(SgContactGap(b->c, ya, g));
  PetscCall(VecRestoreArray(b->y, &ya));
  for (PetscInt i = 0; i < b->n; i++) {
    PetscInt val = -1;
    if (lab) PetscCall(DMLabelGetValue(lab, mb->vStart + b->vert[i], &val));
    if (val == 1) cnt[2]++;
    if (!(g[i] > 0) || !(g[i] < 1e100)) continue;
    cnt[0]++, st[0] = PetscMax(st[0], g[i]);
    if (val == 1) cnt[1]++, st[1] = PetscMax(st[1], g[i]);
  }
  PetscCall(PetscFree(g));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, cnt, 3, MPIU_INT, MPI_SUM, b->comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, st, 2, MPIU_REAL, MPIU_MAX, b->comm));
  PetscCall(PetscInfo(b, "nested start: %" PetscInt_FMT " of %" PetscInt_FMT " contact vertices inside the obstacle (deepest %g); on the geometry %" PetscInt_FMT ", of them inside %" PetscInt_FMT " (deepest %g)\n", cnt[0], b->nglobal, (double)st[0], cnt[2], cnt[1], (double)st[1]));
  PetscFunctionReturn(0);
}

/* b (the next finer level) starts from a's solution: y, the multipliers, gamma and V(0) */
static PetscErrorCode Transfer(SgCont a, SgCont b)
{
  DM                 dma, dmb;
  Vec                ya, yb;
  const PetscScalar *pa;
  PetscScalar       *pb;
  const SgMesh      *ma, *mb;
  PetscInt          *map, dim = 0, n = b->n, bs;
  PetscReal         *lb;
  PetscBool          vector;

  PetscFunctionBeginUser;
  PetscCall(VertexMap(a, b, &map));
  PetscCall(SgElasticityGetDMs(a->prob, &dma, NULL, NULL, NULL));
  PetscCall(SgElasticityGetDMs(b->prob, &dmb, NULL, NULL, NULL));
  PetscCall(SgElasticityGetMesh(a->prob, &ma));
  PetscCall(SgElasticityGetMesh(b->prob, &mb));
  dim = ma->dim;
  /* the displacement, Dirichlet values included, at every local vertex; the fixed components of partly fixed vertices
     are unknowns that stay 0 */
  PetscCall(DMGetLocalVector(dma, &ya));
  PetscCall(DMGetLocalVector(dmb, &yb));
  PetscCall(SgElasticityGlobalToLocal(a->prob, a->y, ya));
  PetscCall(VecZeroEntries(yb));
  PetscCall(VecGetArrayRead(ya, &pa));
  PetscCall(VecGetArray(yb, &pb));
  for (PetscInt v = 0; v < mb->nv; v++)
    for (PetscInt d = 0; d < dim; d++) pb[mb->loff[v] + d] = (mb->bcmask[v] >> d) & 1 ? 0.0 : 0.5 * (pa[ma->loff[map[2 * v]] + d] + pa[ma->loff[map[2 * v + 1]] + d]);
  PetscCall(VecRestoreArray(yb, &pb));
  PetscCall(VecRestoreArrayRead(ya, &pa));
  PetscCall(DMLocalToGlobal(dmb, yb, INSERT_VALUES, b->y));
  PetscCall(DMRestoreLocalVector(dma, &ya));
  PetscCall(DMRestoreLocalVector(dmb, &yb));
  /* the multipliers: the normal one, then what the law's state starts from (friction: its tangential multiplier) */
  PetscCall(SgContactLawTransferSize(b->cv.law, &bs, &vector));
  PetscCall(PetscFree(b->nested_lamhat));
  PetscCall(PetscCalloc1(n * (1 + bs) + 1, &b->nested_lamhat));
  lb = b->nested_lamhat;
  PetscCall(TransferContactField(a, b, map, PETSC_FALSE, 1, a->lam, lb));
  PetscCall(PetscArraycpy(b->lam, lb, n));
  PetscCall(InfoStart(b));
  PetscCall(PlaceRim(b, lb, &b->nested_rim_added));
  if (bs > 0) {
    SgContactLawState st;
    PetscReal        *va;
    PetscCall(SgSSNGetLawState(a->ssn, &st)); /* (NULL without an SSN: zeros) */
    PetscCall(PetscMalloc1(a->n * bs + 1, &va));
    PetscCall(SgContactLawTransferPack(a->cv.law, st, va));
    PetscCall(TransferContactField(a, b, map, vector, bs, va, lb + n));
    PetscCall(PetscFree(va));
  }
  PetscCall(PetscFree(map));
  b->gamma_warm   = a->gamma_warm;
  b->V0unit       = a->V0unit;
  b->V0           = a->V0;
  b->nested_start = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* After the type's start hooks of a solve started from a coarser level: its last gamma, and for a type that moves the
   shift (alm) the interpolated multipliers as the shift */
PetscErrorCode SgContNestedResume(SgCont ct)
{
  SgContactLawState st;

  PetscFunctionBeginUser;
  ct->gamma = ct->gamma_warm;
  if (!ct->ssn || !ct->ops.shifts || !ct->nested_lamhat) PetscFunctionReturn(0);
  PetscCall(PetscArraycpy(ct->lamhat, ct->nested_lamhat, ct->n));
  PetscCall(SgSSNGetLawState(ct->ssn, &st));
  PetscCall(SgContactLawTransferUnpack(ct->cv.law, st, ct->nested_lamhat + ct->n)); /* friction: lamhat_T */
  PetscFunctionReturn(0);
}

/* The log stage of nested level `level` (1: the coarsest) with nunk unknowns, "Level 3: 144,666 unknowns", registered
   the first time: -log_view shows each level's events apart (doc/performance.md). A coarse level's stage holds its
   controller's set-up (the linear solver's included), the transfer to it and its solve; the finest level's, the
   transfer and its solve up to the end of SgContSolve. The meshes' and problems' set-up (assembly) stay in the stage
   around them (the Main Stage of the program). */
static PetscErrorCode PushLevelStage(PetscInt level, PetscInt nunk)
{
  char          name[64], num[32], sep[32];
  PetscLogStage stage;
  size_t        len, k = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(num, sizeof(num), "%" PetscInt_FMT, nunk));
  PetscCall(PetscStrlen(num, &len));
  for (size_t i = 0; i < len; i++) { /* thousands separated by commas, as in the bench notes */
    if (i > 0 && (len - i) % 3 == 0) sep[k++] = ',';
    sep[k++] = num[i];
  }
  sep[k] = 0;
  PetscCall(PetscSNPrintf(name, sizeof(name), "Level %" PetscInt_FMT ": %s unknowns", level, sep));
  PetscCall(PetscLogStageGetId(name, &stage));
  if (stage < 0) PetscCall(PetscLogStageRegister(name, &stage));
  PetscCall(PetscLogStagePush(stage));
  PetscFunctionReturn(0);
}

/* The coarse levels, coarsest first, each from the one below it; then ct (the finest) starts from the last one. */
PetscErrorCode SgContNestedStart(SgCont ct)
{
  SgCont         prev = NULL;
  PetscLogDouble t0, t1;
  const char    *prefix;
  PetscInt       nref;
  PetscBool      own, ok = PETSC_TRUE;
  PetscInt      *nunk;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(SgProblemGetRefinement(ct->problem_obj, &own, &nref));
  PetscCall(SgContGetOptionsPrefix(ct, &prefix));
  PetscCall(PetscCalloc1(ct->nested + 1, &nunk));
  ct->nested_done = ct->nested_ssn_its = ct->nested_ksp_its = 0;
  for (PetscInt k = ct->nested; k >= 1 && ok; k--) {
    SgProblem   pc;
    SgCont      cc;
    PetscBool   conv;
    const char *reason;

    PetscCall(SgProblemCreateCoarse(ct->problem_obj, k, &pc));
    PetscCall(SgContCreate(pc, &cc));
    PetscCall(SgProblemDestroy(&pc)); /* the controller holds it */
    cc->nested_inner = PETSC_TRUE;
    if (prefix) PetscCall(SgContSetOptionsPrefix(cc, prefix));
    PetscCall(SgContSetType(cc, ct->type));
    PetscCall(SgContSetMonitor(cc, ct->monitor));
    PetscCall(SgContSetTolerances(cc, ct->kkt_tol, ct->max_outer));
    if (ct->lin.on) { /* the finest level's default linear solver on every level (its size does not choose another) */
      cc->lin           = ct->lin;
      cc->lin_inherited = PETSC_TRUE;
    }
    PetscCall(SgContSetFromOptions(cc));
    cc->ckfile[0] = cc->rsfile[0] = 0; /* the finest level's files */
    PetscCall(SgProblemGetSizes(cc->problem_obj, &nunk[ct->nested - k], NULL, NULL));
    PetscCall(PushLevelStage(ct->nested - k + 1, nunk[ct->nested - k]));
    PetscCall(SgContSetUp(cc));
    if (ct->monitor) PetscCall(PetscPrintf(ct->comm, "  nested level %" PetscInt_FMT " of %" PetscInt_FMT ": %" PetscInt_FMT " unknowns (-dm_refine %" PetscInt_FMT ")\n", ct->nested - k + 1, ct->nested + 1, nunk[ct->nested - k], nref - k));
    if (prev) PetscCall(Transfer(prev, cc));
    PetscCall(SgContDestroy(&prev));
    PetscCall(SgContSolve(cc));
    PetscCall(PetscLogStagePop());
    ct->nested_ssn_its += cc->ssn_its;
    ct->nested_ksp_its += cc->ksp_its;
    PetscCall(SgContGetConvergedReason(cc, &conv, &reason));
    if (!conv) {
      PetscCall(PetscPrintf(ct->comm, "  nested level %" PetscInt_FMT " (-dm_refine %" PetscInt_FMT ") did not converge (%s): the finest level starts from the unconstrained solution, as without -cont_nested\n", ct->nested - k + 1, nref - k, reason));
      ok = PETSC_FALSE;
    } else ct->nested_done++;
    prev = cc;
  }
  PetscCall(SgProblemGetSizes(ct->problem_obj, &nunk[ct->nested], NULL, NULL));
  PetscCall(PushLevelStage(ct->nested + 1, nunk[ct->nested])); /* popped by SgContSolve after the finest level's solve */
  ct->nested_stage = PETSC_TRUE;
  if (ok) {
    if (ct->monitor) PetscCall(PetscPrintf(ct->comm, "  nested level %" PetscInt_FMT " of %" PetscInt_FMT ": %" PetscInt_FMT " unknowns (-dm_refine %" PetscInt_FMT "), from the interpolated solution at gamma %g\n", ct->nested + 1, ct->nested + 1, nunk[ct->nested], nref, (double)prev->gamma_warm));
    PetscCall(Transfer(prev, ct));
    if (ct->monitor && ct->nested_rim > 0) PetscCall(PetscPrintf(ct->comm, "  nested rim: %" PetscInt_FMT " contact vertices of the finest level moved onto the obstacle (-cont_nested_rim %g)\n", ct->nested_rim_added, (double)ct->nested_rim));
  }
  PetscCall(SgContDestroy(&prev));
  PetscCall(PetscTime(&t1));
  ct->nested_time = t1 - t0;
  PetscCall(SgSummarySetInt(ct->sum, "nested_levels", ct->nested));
  PetscCall(SgSummarySetBool(ct->sum, "nested_default", ct->nested_default));
  PetscCall(SgSummarySetInt(ct->sum, "nested_levels_solved", ct->nested_done));
  PetscCall(SgSummarySetBool(ct->sum, "nested_used", ok));
  PetscCall(SgSummarySetInt(ct->sum, "nested_coarse_ssn_its", ct->nested_ssn_its));
  PetscCall(SgSummarySetInt(ct->sum, "nested_rim_added", ok ? ct->nested_rim_added : 0));
  PetscCall(SgSummarySetInt(ct->sum, "nested_coarse_ksp_its", ct->nested_ksp_its));
  PetscCall(SgSummarySetReal(ct->sum, "nested_coarse_time", (PetscReal)ct->nested_time));
  PetscCall(SgSummarySetIntArray(ct->sum, "nested_unknowns", ct->nested_done + (ok ? 1 : 0), nunk));
  PetscCall(PetscFree(nunk));
  PetscFunctionReturn(0);
}
