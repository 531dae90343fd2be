/* contact_pair.c: two elastic bodies as a contact of their own (-contact_master_ids): the options of the pair, the
   contact vertices from its mortar operator (pair.c), and the gap, force and Jacobian terms the contact object's
   public functions hand over to here when it is a pair (contact.c) */
#include "contact/contactimpl.h"

/* Two bodies: -contact_master_ids (values of -contact_label: the master side; the -contact_ids are the slave side)
   and -contact_pair_distance (how far along the slave normal a master facet may be to face a slave facet) */
PetscErrorCode SgContactPairFromOptions(PetscOptionItems *PetscOptionsObject, SgContact c)
{
  PetscInt  n = c->master.nids; /* given through the interface (SG_BOUNDARY_CONTACT_MASTER), or 0 */
  PetscBool set;

  PetscFunctionBeginUser;
  c->master.what = "contact_master";
  PetscCall(SgOptionsIntList(PetscOptionsObject, "-contact_master_ids", "Two elastic bodies in contact: values of -contact_label marking the master side (the other body's surface); the -contact_ids are then the slave side, coupled to it by dual mortar (frictionless, or with -friction_type on the relative slip; the SSN-based controllers with CG/AMG or MUMPS, and pdas)", SG_MAX_IDS, c->master.ids, &n, &set));
  if (set) c->master.nids = n, c->master.active = PETSC_TRUE;
  n            = c->obnd.nids; /* given through the interface (SG_BOUNDARY_CONTACT_OBSTACLE), or 0 */
  c->obnd.what = "contact_obstacle";
  PetscCall(SgOptionsIntList(PetscOptionsObject, "-contact_obstacle_ids", "Two bodies and a rigid obstacle in one run: values of -contact_label marking the faces that may touch the obstacle (-obstacle_type); without -contact_master_ids the -contact_ids are those faces", SG_MAX_IDS, c->obnd.ids, &n, &set));
  if (set) c->obnd.nids = n, c->obnd.active = PETSC_TRUE;
  PetscCheck(!c->obnd.nids || c->master.nids, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "-contact_obstacle_ids is for a run with a two-body pair (-contact_master_ids); without one, the -contact_ids are the faces that may touch the obstacle");
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-contact_pair_distance", "Two bodies: the largest distance along the slave normal at which a master facet faces a slave facet (default: a tenth of the mesh's diameter; larger than the initial gap, smaller than a body's thickness)", &c->pairdist, &set));
  PetscCheck(!set || c->pairdist > 0, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "-contact_pair_distance: must be positive, got %g", (double)c->pairdist);
  PetscCheck(!set || c->master.nids, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "-contact_pair_distance is given without -contact_master_ids (two-body contact)");
  {
    const char *const kinds[] = {"slave", "average"};
    PetscInt          k       = c->pairavg ? 1 : 0;
    PetscCall(PetscOptionsEList("-contact_pair_normal", "Two bodies: the direction of the pair's condition at a slave vertex: slave (the slave's normal) or average (the mean of the slave's normal and the master's opposite one: symmetric in the two sides)", NULL, kinds, 2, kinds[k], &k, &set));
    PetscCheck(!set || c->master.nids, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "-contact_pair_normal is given without -contact_master_ids (two-body contact)");
    c->pairavg = (PetscBool)(k == 1);
  }
  {
    const char *const kinds[] = {"grid", "brute"};
    PetscInt          k       = c->pairbrute ? 1 : 0;
    PetscCall(PetscOptionsEList("-contact_pair_search", "Two bodies: how the mortar integrals find the master facets opposite a slave facet: grid (buckets over the master facets) or brute (every master facet against every slave facet: the reference, quadratic in the mesh size)", NULL, kinds, 2, kinds[k], &k, &set));
    PetscCheck(!set || c->master.nids, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "-contact_pair_search is given without -contact_master_ids (two-body contact)");
    c->pairbrute = (PetscBool)(k == 1);
  }
  if (!c->master.nids) PetscFunctionReturn(0);
  PetscCheck(!c->obnd.label[0] || !strcmp(c->obnd.label, c->bnd.label), PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "SgProblemSetBoundary: the obstacle's faces' label '%s' is not the contact part's '%s' (the faces are values of one label)", c->obnd.label, c->bnd.label);
  PetscCheck(!c->master.label[0] || !strcmp(c->master.label, c->bnd.label), PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "SgProblemSetBoundary: the master side's label '%s' is not the contact part's '%s' (both sides are values of one label)", c->master.label, c->bnd.label);
  PetscCheck(c->bnd.nids > 0, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "-contact_master_ids needs -contact_ids (the slave side): without it every value of '%s' would be the slave side, the master's too", c->bnd.label);
  for (PetscInt a = 0; a < c->master.nids; a++)
    for (PetscInt b = 0; b < c->bnd.nids; b++) PetscCheck(c->master.ids[a] != c->bnd.ids[b], PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "-contact_master_ids: the value %" PetscInt_FMT " is in -contact_ids too: a side is either slave or master", c->master.ids[a]);
  { /* a rigid obstacle besides the pair: the faces that may touch it are named apart from the pair's sides */
    PetscBool obst = (PetscBool)(c->obstype[0] != 0);
    if (!obst) PetscCall(PetscOptionsHasName(PetscOptionsObject->options, PetscOptionsObject->prefix, "-obstacle_type", &obst));
    PetscCheck(!obst || c->obnd.nids, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "-contact_master_ids with a rigid obstacle (-obstacle_type or SgProblemSetObstacleType): name the faces that may touch the obstacle with -contact_obstacle_ids (values of -contact_label '%s'; the -contact_ids are the pair's slave side)", c->bnd.label);
    PetscCheck(obst || !c->obnd.nids, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "-contact_obstacle_ids is given without a rigid obstacle: give -obstacle_type (and its options)");
    for (PetscInt a = 0; a < c->obnd.nids; a++) {
      for (PetscInt b = 0; b < c->bnd.nids; b++) PetscCheck(c->obnd.ids[a] != c->bnd.ids[b], PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "-contact_obstacle_ids: the value %" PetscInt_FMT " is in -contact_ids too: a face touches either the other body (slave side) or the obstacle", c->obnd.ids[a]);
      for (PetscInt b = 0; b < c->master.nids; b++) PetscCheck(c->obnd.ids[a] != c->master.ids[b], PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "-contact_obstacle_ids: the value %" PetscInt_FMT " is in -contact_master_ids too: a face touches either the other body (master side) or the obstacle", c->obnd.ids[a]);
    }
  }
  PetscFunctionReturn(0);
}

/* whether a row of the pair is a contact vertex: D_j > 0 and a normal (not all along fixed components) */
static PetscBool PairRow(PetscInt dim, PetscScalar D, const PetscScalar n[])
{
  return (PetscBool)(PetscRealPart(D) > 0 && (n[0] != 0 || n[1] != 0 || (dim == 3 && n[2] != 0)));
}

static PetscErrorCode PairBlocksProduct(SgContact, const PetscReal[], Mat *);


/* A slave vertex that starts behind the master side by more than the master's bodies are wide along its normal lies
   past them: the bodies overlap by more than a body (or one has gone through the other), and the pairing distance
   (-contact_pair_distance, larger than such a depth) reached across a body. An overlap within the pairing distance
   and less deep is solved (the bodies are pushed apart); one deeper than the distance is refused by the search
   (pair.c, CheckSearch). Collective. */
static PetscErrorCode CheckDepth(SgContact c)
{
  const PetscInt   dim = c->dim;
  const PetscReal *lo = c->pair->mbox, *hi = c->pair->mbox + 3;
  struct {
    double v;
    int    r;
  } loc, glob;
  PetscReal   info[5] = {0, 0, 0, 0, 0}; /* depth, width, the vertex */
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(c->comm, &rank));
  loc.v = -PETSC_MAX_REAL, loc.r = rank;
  for (PetscInt i = 0; i < c->n; i++) {
    PetscReal w = 0;
    if (c->obsrow[i]) continue; /* a rigid obstacle's row */
    for (PetscInt k = 0; k < dim; k++) w += PetscAbsReal(c->normal[i * dim + k]) * (hi[k] - lo[k]);
    if (-c->d[i] - w > loc.v) {
      loc.v   = (double)(-c->d[i] - w);
      info[0] = -c->d[i], info[1] = w;
      for (PetscInt k = 0; k < dim; k++) info[2 + k] = c->mesh->x[c->vert[i] * dim + k];
    }
  }
  PetscCallMPI(MPI_Allreduce(&loc, &glob, 1, MPI_DOUBLE_INT, MPI_MAXLOC, c->comm));
  if (glob.v < 0) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Bcast(info, 5, MPIU_REAL, glob.r, c->comm));
  {
    char ids[256], mids[256], at[96];
    SgPairIdList(&c->bnd, ids, sizeof(ids));
    SgPairIdList(&c->master, mids, sizeof(mids));
    if (dim == 3) PetscCall(PetscSNPrintf(at, sizeof(at), "(%g, %g, %g)", (double)info[2], (double)info[3], (double)info[4]));
    else PetscCall(PetscSNPrintf(at, sizeof(at), "(%g, %g)", (double)info[2], (double)info[3]));
    SETERRQ(c->comm, PETSC_ERR_USER_INPUT, "-contact_ids %s / -contact_master_ids %s: the bodies overlap at the start by more than a body: the slave vertex %s lies %g behind the master side, and the master's body is %g wide along its normal (the pairing distance -contact_pair_distance %g reaches across it; it must be smaller than a body's thickness): move the bodies apart in the mesh", ids, mids, at, (double)info[0], (double)info[1], (double)c->pairdist);
  }
}

/* Two bodies: the pair of the slave side (the contact boundary) and the master side; the contact vertices are the
   owned slave vertices with D_j > 0 (a slave vertex whose facets are only partly opposite the master can get D_j <= 0
   from the dual basis: it is left out, as an uncovered one). The stiffness matrix gets the pattern of B^T B (explicit
   zeros), so that the Jacobians K + gamma B^T diag(act / D) B keep one pattern (factorizations keep their symbolic
   phase; the preconditioners and the SSN's copies of K are made after this). */
PetscErrorCode SgContactPairSetUp(SgContact c, PetscInt nobs, const PetscInt ooff[], const PetscReal ow[], const PetscReal onrm[], const PetscReal od[])
{
  SgPairObstacleRows obst = {nobs, ooff, ow, onrm, od};
  const PetscInt     dim  = c->dim;
  const SgMesh      *m    = c->mesh;
  PetscInt           rstart, rend, nrow, *vof;
  const PetscScalar *Da, *ga, *Na;
  Mat                BtB;

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(c->master.label, c->bnd.label, sizeof(c->master.label)));
  if (!(c->pairdist > 0)) {
    PetscReal diam;
    PetscCall(SgElasticityGetDataScales(c->prob, NULL, NULL, NULL, NULL, &diam));
    c->pairdist = 0.1 * diam;
  }
  PetscCall(SgContactPairCreate(c->prob, &c->bnd, &c->master, c->pairdist, c->pairavg, c->pairbrute, c->obnd.nids ? &obst : NULL, &c->pair));
  c->area = c->pair->area;
  PetscCall(MatGetOwnershipRange(c->pair->B, &rstart, &rend));
  nrow = rend - rstart;
  /* the owned vertex of each local row (free block rstart + j: the vertex with goff = j dim) */
  PetscCall(PetscMalloc1(nrow + 1, &vof));
  for (PetscInt j = 0; j < nrow; j++) vof[j] = -1;
  for (PetscInt v = 0; v < m->nv; v++)
    if (m->goff[v] >= 0) vof[m->goff[v] / dim] = v;
  PetscCall(VecGetArrayRead(c->pair->D, &Da));
  PetscCall(VecGetArrayRead(c->pair->g0, &ga));
  PetscCall(VecGetArrayRead(c->pair->N, &Na));
  c->n = 0;
  for (PetscInt j = 0; j < nrow; j++) c->n += PairRow(dim, Da[j], &Na[j * dim]);
  PetscCall(PetscMalloc5(c->n, &c->vert, c->n, &c->off, c->n * dim, &c->normal, c->n, &c->w, c->n, &c->d));
  PetscCall(PetscMalloc1(c->n + 1, &c->prow));
  PetscCall(PetscCalloc1(c->n + 1, &c->obsrow));
  c->n = 0;
  for (PetscInt j = 0; j < nrow; j++) {
    if (!PairRow(dim, Da[j], &Na[j * dim])) continue;
    PetscCheck(vof[j] >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "free block %" PetscInt_FMT " has no owned vertex", rstart + j);
    c->prow[c->n]   = j;
    c->obsrow[c->n] = (PetscBool)(c->pair->obsrow && c->pair->obsrow[j]);
    c->vert[c->n]   = vof[j];
    c->off[c->n]    = j * dim;
    c->w[c->n]      = PetscRealPart(Da[j]);
    c->d[c->n]      = PetscRealPart(ga[j]) / c->w[c->n];
    for (PetscInt k = 0; k < dim; k++) c->normal[c->n * dim + k] = PetscRealPart(Na[j * dim + k]);
    c->n++;
  }
  PetscCall(VecRestoreArrayRead(c->pair->D, &Da));
  PetscCall(VecRestoreArrayRead(c->pair->g0, &ga));
  PetscCall(VecRestoreArrayRead(c->pair->N, &Na));
  PetscCall(PetscFree(vof));
  PetscCall(CheckDepth(c));
  /* the Jacobian's pattern: K's and B^T B's (with friction that of R^T diag(B_i) R with full dim x dim blocks B_i,
     which holds B^T B's: B = diag(D) N^T R) */
  PetscCall(SgPairLogEvent(SG_PAIR_PATTERN, PETSC_TRUE));
  if (c->tangpart) PetscCall(PairBlocksProduct(c, NULL, &BtB));
  else PetscCall(MatTransposeMatMult(c->pair->B, c->pair->B, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &BtB));
  PetscCall(MatZeroEntries(BtB));
  {
    /* replacing K's data and header (as MatAXPY with a new pattern did), PETSc 3.18 loses (leaks) the near null space
       attached to it: it is taken off and put back around */
    MatNullSpace nsp, sp;
    PetscCall(MatGetNearNullSpace(c->K, &nsp));
    PetscCall(MatGetNullSpace(c->K, &sp));
    PetscCall(PetscObjectReference((PetscObject)nsp));
    PetscCall(PetscObjectReference((PetscObject)sp));
    PetscCall(MatSetNearNullSpace(c->K, NULL));
    PetscCall(MatSetNullSpace(c->K, NULL));
    { /* K + 0 B^T B by one pass over K's arrays, not MatAXPY's insertion of every value (2 s of the 299,316 unknowns'
         4 levels): the same matrix, K's values to the bit */
      Mat S;
      PetscCall(SgMatAddSparse(c->K, BtB, &S));
      PetscCall(MatHeaderReplace(c->K, &S));
    }
    PetscCall(MatSetNearNullSpace(c->K, nsp));
    PetscCall(MatSetNullSpace(c->K, sp));
    PetscCall(MatNullSpaceDestroy(&nsp));
    PetscCall(MatNullSpaceDestroy(&sp));
  }
  PetscCall(MatDestroy(&BtB));
  PetscCall(SgPairLogEvent(SG_PAIR_PATTERN, PETSC_FALSE));
  PetscCall(VecCreateMPIWithArray(c->comm, 1, nrow * dim, PETSC_DETERMINE, NULL, &c->pw));
  PetscCall(VecDuplicate(c->pw, &c->pf));
  PetscCall(MatCreateVecs(c->pair->B, NULL, &c->pl));
  if (c->tangpart) {
    /* the friction arrays of contact.c (PrescribedSetUp for an obstacle): the slip reference is the relative
       displacement R y at the start of the load step (the law's, allocated in VerticesDone); no vertex has prescribed
       tangential motion (the components a support fixes are out of R) */
    PetscCall(MatCreateVecs(c->pair->R, NULL, &c->pr));
    PetscCall(PetscCalloc4(c->n * dim + 1, &c->klt, c->n * dim + 1, &c->kslip, c->n + 1, &c->kst, c->n + 1, &c->dmask));
    PetscCall(PetscCalloc1(2 * c->n * dim + 1, &c->ypfull));
    c->haspartial = c->hasdface = PETSC_FALSE;
  }
  PetscFunctionReturn(0);
}

/* Two bodies with friction: the relative displacement (R y)_i of every contact vertex, dim numbers each (ya: the
   local part of a global displacement vector) */
PetscErrorCode SgContactPairRelative(SgContact c, const PetscScalar ya[], PetscReal u[])
{
  const PetscScalar *ra;

  PetscFunctionBeginUser;
  PetscCall(VecPlaceArray(c->pw, ya));
  PetscCall(MatMult(c->pair->R, c->pw, c->pr));
  PetscCall(VecResetArray(c->pw));
  PetscCall(VecGetArrayRead(c->pr, &ra));
  for (PetscInt i = 0; i < c->n; i++)
    for (PetscInt k = 0; k < c->dim; k++) u[i * c->dim + k] = PetscRealPart(ra[c->prow[i] * c->dim + k]);
  PetscCall(VecRestoreArrayRead(c->pr, &ra));
  PetscFunctionReturn(0);
}

/* Two bodies with friction: F += R^T f for the nodal forces f (dim per contact vertex) that act on the relative
   displacement: f on the slave vertex, -M_jk / D_j f on the master's (equal and opposite) */
PetscErrorCode SgContactPairTangentialForce(SgContact c, const PetscReal f[], PetscScalar Fa[])
{
  PetscScalar *ra;

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(c->pr));
  PetscCall(VecGetArray(c->pr, &ra));
  for (PetscInt i = 0; i < c->n; i++)
    for (PetscInt k = 0; k < c->dim; k++) ra[c->prow[i] * c->dim + k] = f[i * c->dim + k];
  PetscCall(VecRestoreArray(c->pr, &ra));
  PetscCall(VecPlaceArray(c->pf, Fa));
  PetscCall(MatMultTransposeAdd(c->pair->R, c->pr, c->pf, c->pf));
  PetscCall(VecResetArray(c->pf));
  PetscFunctionReturn(0);
}

/* R^T diag(B_i) R for dim x dim blocks B_i per contact vertex (row-major; NULL: blocks of ones, for the pattern) */
static PetscErrorCode PairBlocksProduct(SgContact c, const PetscReal blk[], Mat *C)
{
  const PetscInt dim = c->dim;
  PetscInt       rstart, nloc;
  Mat            Bd;

  PetscFunctionBeginUser;
  PetscCall(MatGetLocalSize(c->pair->R, &nloc, NULL));
  PetscCall(MatGetOwnershipRange(c->pair->R, &rstart, NULL));
  PetscCall(MatCreateAIJ(c->comm, nloc, nloc, PETSC_DETERMINE, PETSC_DETERMINE, dim, NULL, 0, NULL, &Bd));
  for (PetscInt i = 0; i < c->n; i++) {
    PetscInt    idx[3];
    PetscScalar b[9];
    for (PetscInt a = 0; a < dim; a++) idx[a] = rstart + c->prow[i] * dim + a;
    for (PetscInt k = 0; k < dim * dim; k++) b[k] = blk ? blk[i * dim * dim + k] : 1.0;
    PetscCall(MatSetValues(Bd, dim, idx, dim, idx, b, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(Bd, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Bd, MAT_FINAL_ASSEMBLY));
  PetscCall(MatPtAP(Bd, c->pair->R, MAT_INITIAL_MATRIX, PETSC_DEFAULT, C));
  PetscCall(MatDestroy(&Bd));
  PetscFunctionReturn(0);
}

/* Two bodies with friction: J += R^T diag(blk_i) R for dim x dim blocks blk_i per contact vertex (row-major; J has the
   pattern of R^T diag(1) R: PairSetUp). J is assembled here. */
PetscErrorCode SgContactPairBlocks(SgContact c, const PetscReal blk[], Mat J)
{
  Mat C;

  PetscFunctionBeginUser;
  PetscCall(PairBlocksProduct(c, blk, &C));
  PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAXPY(J, 1.0, C, SUBSET_NONZERO_PATTERN));
  PetscCall(MatDestroy(&C));
  PetscFunctionReturn(0);
}

/* Two bodies: J += gamma B^T diag(act_i / D_i) B (J has the pattern of B^T B: PairSetUp). J is assembled here: the
   caller's assembly after it is a no-op. */
PetscErrorCode SgContactPairJacobian(SgContact c, const char active[], PetscReal gamma, Mat J)
{
  Mat          Bs, C;
  Vec          sc;
  PetscScalar *sa;

  PetscFunctionBeginUser;
  PetscCall(MatDuplicate(c->pair->B, MAT_COPY_VALUES, &Bs));
  PetscCall(VecDuplicate(c->pl, &sc));
  PetscCall(VecZeroEntries(sc));
  PetscCall(VecGetArray(sc, &sa));
  for (PetscInt i = 0; i < c->n; i++) sa[c->prow[i]] = active[i] ? PetscSqrtReal(gamma / c->w[i]) : 0;
  PetscCall(VecRestoreArray(sc, &sa));
  PetscCall(MatDiagonalScale(Bs, sc, NULL));
  PetscCall(MatTransposeMatMult(Bs, Bs, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &C));
  PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAXPY(J, 1.0, C, SUBSET_NONZERO_PATTERN));
  PetscCall(MatDestroy(&C));
  PetscCall(MatDestroy(&Bs));
  PetscCall(VecDestroy(&sc));
  PetscFunctionReturn(0);
}

/* Two bodies: |B^T 1| on the master side (per free dof; 0 on the slave contact vertices), the master's share of the
   pair for the checkpoint's fingerprint (a pair and a rigid obstacle of the same gaps differ there); NULL without a
   pair. The caller destroys it. */
PetscErrorCode SgContactPairMasterWeights(SgContact c, Vec *mw)
{
  Vec          one;
  PetscScalar *a;

  PetscFunctionBeginUser;
  *mw = NULL;
  if (!c || !c->pair) PetscFunctionReturn(0);
  PetscCall(MatCreateVecs(c->pair->B, mw, &one));
  PetscCall(VecSet(one, 1.0));
  PetscCall(MatMultTranspose(c->pair->B, one, *mw));
  PetscCall(VecDestroy(&one));
  PetscCall(VecGetArray(*mw, &a));
  for (PetscInt i = 0; i < c->n; i++)
    for (PetscInt k = 0; k < c->dim; k++) a[c->off[i] + k] = 0;
  PetscCall(VecRestoreArray(*mw, &a));
  PetscCall(VecAbs(*mw));
  PetscFunctionReturn(0);
}

PetscErrorCode SgContactIsPair(SgContact c, PetscBool *pair)
{
  PetscFunctionBeginUser;
  *pair = (PetscBool)(c && c->pair);
  PetscFunctionReturn(0);
}

/* Two bodies: g_i = (B y)_i / D_i - d_i at every contact vertex (ya: the local part of a global displacement vector) */
PetscErrorCode SgContactPairGap(SgContact c, const PetscScalar ya[], PetscReal g[])
{
  const PetscScalar *la;

  PetscFunctionBeginUser;
  PetscCall(VecPlaceArray(c->pw, ya));
  PetscCall(MatMult(c->pair->B, c->pw, c->pl));
  PetscCall(VecResetArray(c->pw));
  PetscCall(VecGetArrayRead(c->pl, &la));
  for (PetscInt i = 0; i < c->n; i++) g[i] = PetscRealPart(la[c->prow[i]]) / c->w[i] - c->d[i];
  PetscCall(VecRestoreArrayRead(c->pl, &la));
  PetscFunctionReturn(0);
}

/* Two bodies: F += B^T lam (on both sides: equal and opposite) */
PetscErrorCode SgContactPairForce(SgContact c, const PetscReal lam[], PetscScalar Fa[])
{
  PetscScalar *la;

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(c->pl));
  PetscCall(VecGetArray(c->pl, &la));
  for (PetscInt i = 0; i < c->n; i++) la[c->prow[i]] = lam[i];
  PetscCall(VecRestoreArray(c->pl, &la));
  PetscCall(VecPlaceArray(c->pf, Fa));
  PetscCall(MatMultTransposeAdd(c->pair->B, c->pl, c->pf, c->pf));
  PetscCall(VecResetArray(c->pf));
  PetscFunctionReturn(0);
}

/* Two bodies: the dual-mortar basis transformation (-ssn_pair_transform) and its inverse. T is the identity but on the
   free components of the contact vertices, where u_j = v_j + sum_k (M_jk / D_j) v_k (the master vertices k opposite);
   then (R T v)_j = v_j and (B T v)_j = D_j n_j . v_j: in v every condition of the pair is nodal, as against a rigid
   obstacle. T^-1 has -M_jk / D_j there (T = I + E with E^2 = 0: no master vertex of a contact row is a contact vertex
   of the pair itself, which is checked: such a mesh is refused). Rows of an obstacle besides the pair (R = e_j) and of
   slave vertices left out (D_j <= 0: no row of R) stay the identity. The caller destroys both. who (the option or
   controller that asked) and advice (what it can do without the transformation) make the refusal's message. */
PetscErrorCode SgContactPairTransform(SgContact c, const char who[], const char advice[], Mat *T, Mat *Tinv)
{
  PetscInt rstart, rend, maxc = 0;
  Mat      E, E2;

  PetscFunctionBeginUser;
  PetscCheck(c && c->pair, PETSC_COMM_SELF, PETSC_ERR_PLIB, "no two-body pair");
  PetscCall(MatGetOwnershipRange(c->pair->R, &rstart, &rend));
  for (PetscInt r = rstart; r < rend; r++) {
    PetscInt nc;
    PetscCall(MatGetRow(c->pair->R, r, &nc, NULL, NULL));
    maxc = PetscMax(maxc, nc);
    PetscCall(MatRestoreRow(c->pair->R, r, &nc, NULL, NULL));
  }
  PetscCall(MatCreateAIJ(c->comm, rend - rstart, rend - rstart, PETSC_DETERMINE, PETSC_DETERMINE, maxc + 1, NULL, maxc + 1, NULL, &E));
  for (PetscInt r = rstart; r < rend; r++) {
    const PetscInt    *cols;
    const PetscScalar *vals;
    PetscInt           nc;
    PetscScalar        zero = 0;
    PetscCall(MatSetValues(E, 1, &r, 1, &r, &zero, INSERT_VALUES)); /* the diagonal's place, for the shifts below */
    PetscCall(MatGetRow(c->pair->R, r, &nc, &cols, &vals));
    for (PetscInt k = 0; k < nc; k++)
      if (cols[k] != r && vals[k] != 0) {
        PetscScalar v = -vals[k];
        PetscCall(MatSetValues(E, 1, &r, 1, &cols[k], &v, INSERT_VALUES));
      }
    PetscCall(MatRestoreRow(c->pair->R, r, &nc, &cols, &vals));
  }
  PetscCall(MatAssemblyBegin(E, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(E, MAT_FINAL_ASSEMBLY));
  PetscCall(MatMatMult(E, E, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &E2));
  {
    PetscReal n2, n1;
    PetscCall(MatNorm(E2, NORM_INFINITY, &n2));
    PetscCall(MatNorm(E, NORM_INFINITY, &n1));
    PetscCall(MatDestroy(&E2));
    if (n2 > 0) PetscCall(MatDestroy(&E));
    PetscCheck(n2 == 0, c->comm, PETSC_ERR_SUP, "%s needs the dual-mortar transformation, and a master vertex of the pair (-contact_master_ids) is also a slave contact vertex (-contact_ids): the transformation needs the two sides apart (|E^2| = %g of |E| = %g); %s", who, (double)n2, (double)n1, advice);
  }
  PetscCall(MatDuplicate(E, MAT_COPY_VALUES, T));
  PetscCall(MatShift(*T, 1.0));
  PetscCall(MatScale(E, -1.0));
  PetscCall(MatShift(E, 1.0));
  *Tinv = E;
  PetscFunctionReturn(0);
}
