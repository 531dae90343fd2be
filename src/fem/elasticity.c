/* elasticity.c: the linear elasticity object: its options (material, boundary parts), set-up, view, accessors and
   destruction. */
#include "fem/femimpl.h"

/* The checks of one material (the options' names in the messages: "-E", "-nu"; of several, their entry k too) */
static PetscErrorCode CheckMaterial(SgElasticity p, PetscInt k, PetscReal E, PetscReal nu, PetscReal *lambda, PetscReal *mu)
{
  char which[128] = "";

  PetscFunctionBeginUser;
  if (k >= 0) PetscCall(PetscSNPrintf(which, sizeof(which), " entry %" PetscInt_FMT " (-material_ids %" PetscInt_FMT ")", k, p->matids[k]));
  PetscCheck(PetscIsNormalReal(E) && E > 0, p->comm, PETSC_ERR_USER_INPUT, "-E%s: Young's modulus must be positive and finite, got %g", which, (double)E);
  /* nu = 0 (no lateral contraction) is a valid material; nu -> 1/2 is incompressible */
  PetscCheck(!PetscIsInfOrNanReal(nu) && nu >= 0 && nu < 0.5, p->comm, PETSC_ERR_USER_INPUT, "-nu%s: Poisson's ratio must lie in [0, 0.5), got %g", which, (double)nu);
  PetscCall(SgLame(E, nu, lambda, mu));
  /* nu -> 1/2: lambda / mu = 2 nu / (1 - 2 nu) grows without bound; once the shear part of K is below 1e3 rounding
     units of the volumetric part, K is singular to working precision (a factorization meets zero pivots) and no
     tolerance the KKT measures could certify is left (their round-off, SgKKT.roundoff, is larger still) */
  PetscCheck((PetscIsNormalReal(*lambda) || *lambda == 0) && *lambda / *mu <= 1e-3 / PETSC_MACHINE_EPSILON, p->comm, PETSC_ERR_USER_INPUT, "-nu%s %.16g (E %g): lambda/mu = %.3g, too nearly incompressible for double precision (the shear stiffness is lost in the rounding of the volumetric one, K is singular to working precision); nu <= 0.4999999999 (lambda/mu 5e9) can be solved to tolerances that the run's KKT measures state", which, (double)nu, (double)E, (double)(*lambda / *mu));
  PetscFunctionReturn(0);
}

/* The material(s): one E and nu for every cell, or with -material_ids one of each per value of the cell label
   -material_label. A list given (option or SgProblemSetMaterials) has one entry per id; a value not given at all (the
   default, or SgProblemSetMaterial's) holds for every material. */
static PetscErrorCode MaterialOptions(PetscOptionItems *PetscOptionsObject, SgElasticity p, const SgElasticitySettings *set)
{
  PetscInt  nE = 1, nnu = 1, nids = 0;
  PetscBool Eset = PETSC_FALSE, nuset = PETSC_FALSE, idset;

  PetscFunctionBeginUser;
  p->matE[0]  = set && set->material_set ? set->E : 1.0;
  p->matnu[0] = set && set->material_set ? set->nu : 0.3;
  PetscCall(PetscStrcpy(p->matlabel, "Cell Sets"));
  if (set && set->nmat > 0) {
    nids = nE = nnu = set->nmat;
    Eset = nuset = PETSC_TRUE;
    for (PetscInt k = 0; k < nids; k++) {
      p->matids[k] = set->matids[k];
      p->matE[k]   = set->matE[k];
      p->matnu[k]  = set->matnu[k];
    }
    PetscCall(PetscStrncpy(p->matlabel, set->matlabel, sizeof(p->matlabel)));
  }
  PetscCall(PetscOptionsString("-material_label", "Cell label whose values -material_ids name (gmsh's physical volumes, 2D: surfaces, arrive in 'Cell Sets')", NULL, p->matlabel, p->matlabel, sizeof(p->matlabel), NULL));
  PetscCall(SgOptionsIntList(PetscOptionsObject, "-material_ids", "Values of -material_label, one per material (with -E, -nu of as many entries); every cell needs one of them", SG_MAX_IDS, p->matids, &nids, &idset));
  {
    PetscBool s;
    PetscCall(SgOptionsRealList(PetscOptionsObject, "-E", "Young's modulus (one per -material_ids)", SG_MAX_IDS, p->matE, &nE, &s));
    Eset = (PetscBool)(Eset || s);
    PetscCall(SgOptionsRealList(PetscOptionsObject, "-nu", "Poisson's ratio in [0, 0.5) (plane strain in 2D; one per -material_ids)", SG_MAX_IDS, p->matnu, &nnu, &s));
    nuset = (PetscBool)(nuset || s);
  }
  for (PetscInt k = 0; k < nids; k++) {
    PetscCheck(p->matids[k] >= 0, p->comm, PETSC_ERR_USER_INPUT, "-material_ids: entry %" PetscInt_FMT " is %" PetscInt_FMT ", label values of cells are >= 0", k, p->matids[k]);
    for (PetscInt j = 0; j < k; j++) PetscCheck(p->matids[j] != p->matids[k], p->comm, PETSC_ERR_USER_INPUT, "-material_ids: the id %" PetscInt_FMT " is given twice (entries %" PetscInt_FMT " and %" PetscInt_FMT ")", p->matids[k], j, k);
  }
  if (nids <= 1) { /* one material for every cell */
    PetscCheck(nE == 1, p->comm, PETSC_ERR_USER_INPUT, "-E: %" PetscInt_FMT " values need as many -material_ids (%s given)", nE, nids ? "1 is" : "none are");
    PetscCheck(nnu == 1, p->comm, PETSC_ERR_USER_INPUT, "-nu: %" PetscInt_FMT " values need as many -material_ids (%s given)", nnu, nids ? "1 is" : "none are");
  } else {
    if (!Eset && nE == 1)
      for (PetscInt k = 1; k < nids; k++) p->matE[k] = p->matE[0];
    else PetscCheck(nE == nids, p->comm, PETSC_ERR_USER_INPUT, "-E: %" PetscInt_FMT " values for %" PetscInt_FMT " -material_ids (one per id)", nE, nids);
    if (!nuset && nnu == 1)
      for (PetscInt k = 1; k < nids; k++) p->matnu[k] = p->matnu[0];
    else PetscCheck(nnu == nids, p->comm, PETSC_ERR_USER_INPUT, "-nu: %" PetscInt_FMT " values for %" PetscInt_FMT " -material_ids (one per id)", nnu, nids);
  }
  p->nmat = nids;
  PetscFunctionReturn(0);
}

static PetscErrorCode ProblemOptions(SgElasticity p, const SgElasticitySettings *set)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(p->comm, p->prefix, "Linear elasticity", NULL);
  PetscCall(MaterialOptions(PetscOptionsObject, p, set));
  p->nbody_force = 0;
  PetscCall(SgOptionsRealList(PetscOptionsObject, "-body_force", "Constant body force f (dim numbers)", 3, p->body_force, &p->nbody_force, NULL));
  {
    char      mode[16] = "vertex";
    PetscBool mset;
    PetscCall(PetscOptionsString("-contact_kkt_scale", "Nodal sizes in the KKT measures' scales, the controllers' gamma estimates and the round-off floors: vertex (a vertex's displacement or force as its Euclidean length, ||K|| from the vertex blocks' spectral norms: the same for the problem turned rigidly) or component (the largest or summed components, ||K||_inf: the paper's, kept in its problem files; they change when the problem is turned)", NULL, mode, mode, sizeof(mode), &mset));
    PetscCheck(!mset || !strcmp(mode, "vertex") || !strcmp(mode, "component"), p->comm, PETSC_ERR_USER_INPUT, "-contact_kkt_scale: unknown value '%s' (vertex, component)", mode);
    p->kkt_vertex = (PetscBool)strcmp(mode, "component");
  }
  p->use_nearnull = PETSC_TRUE;
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-elasticity_near_null_space", "Attach the rigid-body modes to the stiffness as near null space (used by GAMG; hypre's use of them crashes in Debian's build)", &p->use_nearnull, NULL));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-mms", "Manufactured solution: body force and Dirichlet data from a known smooth field (verification)", &p->mms, NULL));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-elasticity_rigid_shift", "Accept a body whose Dirichlet part leaves rigid motions free: add eps E/L^2 M to K (M lumped volumes, L the mesh diameter); 0: no shift, singular K", &p->rigid_shift, &p->rigid_shift_set));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-elasticity_energy_check", "Debug: print the energy beside a long double evaluation and the former y^T K y formula", &p->energy_check, NULL));
  PetscOptionsEnd();
  if (set) {
    p->dirichlet = set->dirichlet;
    p->neumann   = set->neumann;
  }
  p->dirichlet.what = "dirichlet";
  p->neumann.what   = "neumann";
  if (!p->dirichlet.label[0]) PetscCall(PetscStrcpy(p->dirichlet.label, "Face Sets"));
  if (!p->neumann.label[0]) PetscCall(PetscStrcpy(p->neumann.label, "Face Sets"));
  /* the materials: one (today's messages), or each with its entry; E, nu, lambda, mu: the one, or the stiffest */
  if (p->nmat <= 1) {
    PetscCall(CheckMaterial(p, -1, p->matE[0], p->matnu[0], &p->matlambda[0], &p->matmu[0]));
  } else
    for (PetscInt k = 0; k < p->nmat; k++) PetscCall(CheckMaterial(p, k, p->matE[k], p->matnu[k], &p->matlambda[k], &p->matmu[k]));
  {
    PetscInt s = 0;
    for (PetscInt k = 1; k < p->nmat; k++)
      if (p->matE[k] > p->matE[s]) s = k;
    p->E      = p->matE[s];
    p->nu     = p->matnu[s];
    p->lambda = p->matlambda[s];
    p->mu     = p->matmu[s];
  }
  PetscCheck(!p->mms || p->nmat <= 1, p->comm, PETSC_ERR_USER_INPUT, "-mms: the manufactured solution is for one material, not the %" PetscInt_FMT " of -material_ids", p->nmat);
  for (PetscInt d = 0; d < p->nbody_force; d++) PetscCheck(PetscIsNormalReal(p->body_force[d]) || p->body_force[d] == 0, p->comm, PETSC_ERR_USER_INPUT, "-body_force: entry %" PetscInt_FMT " is %g, must be finite", d, (double)p->body_force[d]);
  PetscCheck(!p->rigid_shift_set || (PetscIsNormalReal(p->rigid_shift) && p->rigid_shift > 0) || p->rigid_shift == 0, p->comm, PETSC_ERR_USER_INPUT, "-elasticity_rigid_shift: must be finite and >= 0, got %g", (double)p->rigid_shift);
  PetscFunctionReturn(0);
}

/* The boundary parts' options (their values need the dimension, known only once the mesh exists). */
static PetscErrorCode BoundaryValueOptions(SgElasticity p)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(p->comm, p->prefix, "Boundary data", NULL);
  PetscCall(SgBoundaryFromOptions(PetscOptionsObject, &p->dirichlet, p->dim, "values", "Dirichlet displacement"));
  PetscCall(SgBoundaryComponentsFromOptions(PetscOptionsObject, &p->dirichlet, p->dim));
  PetscCall(SgBoundaryFromOptions(PetscOptionsObject, &p->neumann, p->dim, "traction", "Neumann traction"));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

/* A clone of the mesh with ncomp unconstrained values per cell (height 0) or per vertex (height dim). */
static PetscErrorCode CreateFieldDM(DM dm, PetscInt height, PetscInt ncomp, const char name[], DM *sdm)
{
  PetscSection s;
  PetscInt     pStart, pEnd, sStart, sEnd;

  PetscFunctionBeginUser;
  PetscCall(DMClone(dm, sdm));
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  if (height == 0) PetscCall(DMPlexGetHeightStratum(dm, 0, &sStart, &sEnd));
  else PetscCall(DMPlexGetDepthStratum(dm, 0, &sStart, &sEnd));
  PetscCall(PetscSectionCreate(PetscObjectComm((PetscObject)dm), &s));
  PetscCall(PetscSectionSetNumFields(s, 1));
  PetscCall(PetscSectionSetFieldName(s, 0, name));
  PetscCall(PetscSectionSetFieldComponents(s, 0, ncomp));
  PetscCall(PetscSectionSetChart(s, pStart, pEnd));
  for (PetscInt p = sStart; p < sEnd; p++) {
    PetscCall(PetscSectionSetDof(s, p, ncomp));
    PetscCall(PetscSectionSetFieldDof(s, p, 0, ncomp));
  }
  PetscCall(PetscSectionSetUp(s));
  PetscCall(DMSetLocalSection(*sdm, s));
  PetscCall(PetscSectionDestroy(&s));
  PetscFunctionReturn(0);
}

PetscErrorCode SgElasticityCreate(MPI_Comm comm, const char prefix[], SgElasticity *prob)
{
  SgElasticity p;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&p));
  p->comm = comm;
  p->load = 1;
  PetscCall(PetscStrallocpy(prefix, &p->prefix));
  *prob = p;
  PetscFunctionReturn(0);
}

/* The material and the boundary parts from the settings and the options, and the mesh: the caller's dm (a clone of
   it: its own section stays untouched), or ours from -dm_plex_filename / -box_*. */
PetscErrorCode SgElasticitySetFromOptions(SgElasticity p, DM dm, const SgElasticitySettings *set)
{
  MPI_Comm comm = p->comm;

  PetscFunctionBeginUser;
  PetscCall(ProblemOptions(p, set));
  if (dm) {
    PetscCall(SgMeshCheckDM(comm, "(given to SgProblemSetDM)", dm));
    PetscCall(DMClone(dm, &p->dm));
    PetscCall(PetscObjectSetName((PetscObject)p->dm, "mesh"));
    for (PetscInt k = 0;; k++) { /* the mesh hierarchy a coarse level of nested iteration comes with (fem/mesh.c) */
      char        name[64];
      PetscObject o;
      if (k) PetscCall(PetscSNPrintf(name, sizeof(name), "SgNestedLevel%" PetscInt_FMT, k));
      else PetscCall(PetscStrncpy(name, "SgNestedBase", sizeof(name)));
      PetscCall(PetscObjectQuery((PetscObject)dm, name, &o));
      if (!o && k) break;
      if (o) PetscCall(PetscObjectCompose((PetscObject)p->dm, name, o));
    }
  } else PetscCall(SgMeshCreateDM(comm, p->prefix, &p->dm));
  PetscCall(DMGetDimension(p->dm, &p->dim));
  PetscCheck(p->nbody_force == 0 || p->nbody_force == p->dim, comm, PETSC_ERR_USER_INPUT, "-body_force: give %" PetscInt_FMT " numbers for this %" PetscInt_FMT "D mesh, got %" PetscInt_FMT, p->dim, p->dim, p->nbody_force);
  PetscCall(BoundaryValueOptions(p));
  PetscFunctionReturn(0);
}

/* The material of each local cell from its value of -material_label: every cell needs one of -material_ids (with
   one id, every cell has it), and every id has a cell somewhere. */
PetscErrorCode SgElasticitySetUpMaterials(SgElasticity p)
{
  const SgMesh *m = &p->mesh;
  DMLabel       lab;
  PetscInt      cnt[SG_MAX_IDS], has, bad[2] = {PETSC_MAX_INT, PETSC_MAX_INT}; /* the smallest value not listed, the cell without a value (-1 none) */
  PetscReal     xb[3] = {0, 0, 0};

  PetscFunctionBeginUser;
  if (p->nmat < 1) PetscFunctionReturn(0);
  PetscCall(DMGetLabel(p->dm, p->matlabel, &lab));
  has = lab ? 1 : 0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &has, 1, MPIU_INT, MPI_MAX, p->comm));
  PetscCheck(has, p->comm, PETSC_ERR_USER_INPUT, "-material_label '%s': the mesh has no such label (gmsh's physical volumes, in 2D surfaces, arrive in 'Cell Sets'; a mesh without physical groups of cells has none)", p->matlabel);
  PetscCall(PetscMalloc1(m->nc, &p->cellmat));
  for (PetscInt k = 0; k < SG_MAX_IDS; k++) cnt[k] = 0;
  for (PetscInt c = 0; c < m->nc; c++) {
    PetscInt val = -1, k;
    if (lab) PetscCall(DMLabelGetValue(lab, m->cStart + c, &val));
    for (k = 0; k < p->nmat; k++)
      if (p->matids[k] == val) break;
    if (k < p->nmat) cnt[k]++;
    else if (p->nmat == 1) k = 0;
    else if (val >= 0) bad[0] = PetscMin(bad[0], val);
    else if (bad[1] == PETSC_MAX_INT) {
      bad[1] = m->cStart + c;
      for (PetscInt a = 0; a <= p->dim; a++)
        for (PetscInt d = 0; d < p->dim; d++) xb[d] += m->x[m->cellv[c * (p->dim + 1) + a] * p->dim + d] / (p->dim + 1);
    }
    p->cellmat[c] = k < p->nmat ? k : 0;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, cnt, (PetscMPIInt)p->nmat, MPIU_INT, MPI_SUM, p->comm));
  {
    PetscInt g[2];
    PetscCallMPI(MPI_Allreduce(bad, g, 2, MPIU_INT, MPI_MIN, p->comm));
    PetscCheck(g[0] == PETSC_MAX_INT, p->comm, PETSC_ERR_USER_INPUT, "-material_label '%s': cells have the value %" PetscInt_FMT ", which is not among -material_ids (every cell needs a material: add the id with its -E and -nu)", p->matlabel, g[0]);
    if (g[1] < PETSC_MAX_INT) { /* the centroid of a cell without a value, from the rank that has one */
      PetscMPIInt rank, r;
      PetscCallMPI(MPI_Comm_rank(p->comm, &rank));
      r = bad[1] < PETSC_MAX_INT ? rank : PETSC_MPI_INT_MAX;
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &r, 1, MPI_INT, MPI_MIN, p->comm));
      PetscCallMPI(MPI_Bcast(xb, 3, MPIU_REAL, r, p->comm));
      if (p->dim == 2) SETERRQ(p->comm, PETSC_ERR_USER_INPUT, "-material_label '%s': the cell with centroid (%g, %g) has no value of the label, so no material of -material_ids (every cell needs one)", p->matlabel, (double)xb[0], (double)xb[1]);
      SETERRQ(p->comm, PETSC_ERR_USER_INPUT, "-material_label '%s': the cell with centroid (%g, %g, %g) has no value of the label, so no material of -material_ids (every cell needs one)", p->matlabel, (double)xb[0], (double)xb[1], (double)xb[2]);
    }
  }
  for (PetscInt k = 0; k < p->nmat; k++) PetscCheck(cnt[k] > 0, p->comm, PETSC_ERR_USER_INPUT, "-material_ids: no cell of the mesh has the value %" PetscInt_FMT " of -material_label '%s'", p->matids[k], p->matlabel);
  if (p->nmat == 1) PetscCall(PetscFree(p->cellmat)); /* every cell: E, nu */
  PetscFunctionReturn(0);
}

/* The P1 layout with the Dirichlet constraints, the auxiliary field layouts and the assembly. */
PetscErrorCode SgElasticitySetUp(SgElasticity p)
{
  MPI_Comm comm = p->comm;
  PetscInt bs;

  PetscFunctionBeginUser;
  if (p->setup) PetscFunctionReturn(0);
  PetscCheck(p->dm, comm, PETSC_ERR_ORDER, "SgElasticitySetUp: the mesh is missing (SgElasticitySetFromOptions first)");
  PetscCall(SgMeshSetUp(p->dm, &p->dirichlet, &p->mesh));
  PetscCall(SgElasticitySetUpMaterials(p));
  PetscCall(SgElasticityCheckRigidMotions(p));
  for (PetscInt pass = 0; pass < 2; pass++) {
    p->npartial = 0;
    for (PetscInt v = 0; v < p->mesh.nv; v++)
      if (SgMeshPartial(&p->mesh, v))
        for (PetscInt d = 0; d < p->dim; d++)
          if (SgMeshFixed(&p->mesh, v, d)) {
            if (pass) p->partial[p->npartial] = p->mesh.loff[v] + d;
            p->npartial++;
          }
    if (!pass) PetscCall(PetscMalloc1(p->npartial, &p->partial));
  }
  PetscCall(CreateFieldDM(p->dm, 0, 1, "cell", &p->dmCell));
  PetscCall(CreateFieldDM(p->dm, p->dim, 1, "vertex", &p->dmVert));
  PetscCall(CreateFieldDM(p->dm, p->dim, p->dim, "vector", &p->dmVec));
  PetscCall(SgElasticityAssemble(p));
  PetscCall(VecGetSize(p->b, &p->ndofs));
  PetscCall(MatGetBlockSize(p->K, &bs));
  PetscCheck(bs == p->dim, comm, PETSC_ERR_PLIB, "stiffness block size %" PetscInt_FMT " differs from the dimension", bs);
  p->setup = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode SgElasticityView(SgElasticity p, PetscViewer viewer)
{
  PetscInt nc = p->mesh.nc;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nc, 1, MPIU_INT, MPI_SUM, p->comm));
  if (p->nmat <= 1) PetscCall(PetscViewerASCIIPrintf(viewer, "linear elasticity (P1, %s): %" PetscInt_FMT "D, %" PetscInt_FMT " cells, %" PetscInt_FMT " unknowns, E %g, nu %g\n", p->dim == 2 ? "plane strain" : "3D", p->dim, nc, p->ndofs, (double)p->E, (double)p->nu));
  else {
    PetscCall(PetscViewerASCIIPrintf(viewer, "linear elasticity (P1, %s): %" PetscInt_FMT "D, %" PetscInt_FMT " cells, %" PetscInt_FMT " unknowns, %" PetscInt_FMT " materials of label %s:\n", p->dim == 2 ? "plane strain" : "3D", p->dim, nc, p->ndofs, p->nmat, p->matlabel));
    for (PetscInt k = 0; k < p->nmat; k++) PetscCall(PetscViewerASCIIPrintf(viewer, "  id %" PetscInt_FMT ": E %g, nu %g\n", p->matids[k], (double)p->matE[k], (double)p->matnu[k]));
  }
  {
    char comps[SG_MAX_IDS * 5 + 32] = "";
    if (p->dirichlet.ncomps) {
      size_t l;
      PetscCall(PetscStrcpy(comps, " fixing "));
      for (PetscInt i = 0; i < p->dirichlet.ncomps; i++) {
        PetscCall(PetscStrlen(comps, &l));
        PetscCall(PetscSNPrintf(comps + l, sizeof(comps) - l, "%s%s%s%s", i ? "," : "", p->dirichlet.comps[i] & 1 ? "x" : "", p->dirichlet.comps[i] & 2 ? "y" : "", p->dirichlet.comps[i] & 4 ? "z" : ""));
      }
    }
    PetscCall(PetscViewerASCIIPrintf(viewer, "  Dirichlet part: %s%s%s, Neumann part: %s\n", p->dirichlet.active ? "label " : "none", p->dirichlet.active ? p->dirichlet.label : "", comps, p->neumann.nvalues ? p->neumann.label : "none"));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SgElasticityGetComm(SgElasticity p, MPI_Comm *comm)
{
  PetscFunctionBeginUser;
  *comm = p->comm;
  PetscFunctionReturn(0);
}

PetscErrorCode SgElasticityGetDimension(SgElasticity p, PetscInt *dim)
{
  PetscFunctionBeginUser;
  *dim = p->dim;
  PetscFunctionReturn(0);
}

PetscErrorCode SgElasticityGetDMs(SgElasticity p, DM *dm, DM *dmVert, DM *dmVec, DM *dmCell)
{
  PetscFunctionBeginUser;
  if (dm) *dm = p->dm;
  if (dmVert) *dmVert = p->dmVert;
  if (dmVec) *dmVec = p->dmVec;
  if (dmCell) *dmCell = p->dmCell;
  PetscFunctionReturn(0);
}

PetscErrorCode SgElasticityGetMesh(SgElasticity p, const SgMesh **m)
{
  PetscFunctionBeginUser;
  *m = &p->mesh;
  PetscFunctionReturn(0);
}

PetscErrorCode SgElasticityGetOperators(SgElasticity p, Mat *K, Vec *b)
{
  PetscFunctionBeginUser;
  if (K) *K = p->K;
  if (b) *b = p->b;
  PetscFunctionReturn(0);
}

PetscErrorCode SgElasticityGetMass(SgElasticity p, Vec *mass)
{
  PetscFunctionBeginUser;
  *mass = p->mass;
  PetscFunctionReturn(0);
}

PetscErrorCode SgElasticityGetNearNullSpace(SgElasticity p, MatNullSpace *nsp)
{
  PetscFunctionBeginUser;
  *nsp = p->use_nearnull ? p->nearnull : NULL;
  PetscFunctionReturn(0);
}

/* the number of entries the nodal norms of the KKT scales take together: dim (-contact_kkt_scale vertex) or 1
   (component); the argument of SgVecVertexNormMax and its kin */
PetscErrorCode SgElasticityGetNodalNormSize(SgElasticity p, PetscInt *nd)
{
  PetscFunctionBeginUser;
  *nd = SgNodalNormSize(p);
  PetscFunctionReturn(0);
}

PetscErrorCode SgElasticityGetScales(SgElasticity p, PetscReal *Knorm, PetscReal *bnorm, PetscReal *bnorm_inf)
{
  PetscFunctionBeginUser;
  if (Knorm) *Knorm = p->Knorm;
  if (bnorm) *bnorm = p->bnorm;
  if (bnorm_inf) *bnorm_inf = p->bnorm_inf;
  PetscFunctionReturn(0);
}

PetscErrorCode SgElasticityGetEnergyShift(SgElasticity p, PetscReal *shift)
{
  PetscFunctionBeginUser;
  *shift = p->energy_shift;
  PetscFunctionReturn(0);
}

PetscErrorCode SgElasticityGetMaterial(SgElasticity p, PetscReal *E, PetscReal *nu)
{
  PetscFunctionBeginUser;
  if (E) *E = p->E;
  if (nu) *nu = p->nu;
  PetscFunctionReturn(0);
}

PetscErrorCode SgElasticityGetMaterials(SgElasticity p, const char **label, PetscInt *n, const PetscInt **ids, const PetscReal **E, const PetscReal **nu)
{
  PetscFunctionBeginUser;
  if (label) *label = p->matlabel;
  if (n) *n = p->nmat;
  if (ids) *ids = p->matids;
  if (E) *E = p->matE;
  if (nu) *nu = p->matnu;
  PetscFunctionReturn(0);
}

/* unknowns (global), cells (global), manufactured solution, assembly time */
PetscErrorCode SgElasticityGetInfo(SgElasticity p, PetscInt *ndofs, PetscInt *ncells, PetscBool *mms, PetscLogDouble *t_assembly)
{
  PetscFunctionBeginUser;
  if (ndofs) *ndofs = p->ndofs;
  if (ncells) {
    *ncells = p->mesh.nc;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, ncells, 1, MPIU_INT, MPI_SUM, p->comm));
  }
  if (mms) *mms = p->mms;
  if (t_assembly) *t_assembly = p->t_assembly;
  PetscFunctionReturn(0);
}

PetscErrorCode SgElasticityDestroy(SgElasticity *prob)
{
  SgElasticity p = *prob;

  PetscFunctionBeginUser;
  if (!p) PetscFunctionReturn(0);
  PetscCall(MatDestroy(&p->K));
  PetscCall(VecDestroy(&p->b));
  PetscCall(VecDestroy(&p->mass));
  PetscCall(VecDestroy(&p->ubc));
  PetscCall(VecDestroy(&p->fpart));
  PetscCall(VecDestroy(&p->b1));
  PetscCall(VecDestroy(&p->ubc1));
  PetscCall(VecDestroy(&p->fpart1));
  PetscCall(VecDestroy(&p->bload1));
  PetscCall(MatNullSpaceDestroy(&p->nearnull));
  PetscCall(SgMeshDestroy(&p->mesh));
  PetscCall(PetscFree(p->partial));
  PetscCall(PetscFree(p->cellmat));
  PetscCall(DMDestroy(&p->dmCell));
  PetscCall(DMDestroy(&p->dmVert));
  PetscCall(DMDestroy(&p->dmVec));
  PetscCall(DMDestroy(&p->dm));
  PetscCall(PetscFree(p->prefix));
  PetscCall(PetscFree(*prob));
  PetscFunctionReturn(0);
}

/* the Dirichlet part (its label, ids and the components fixed per id) */
PetscErrorCode SgElasticityGetDirichletBoundary(SgElasticity p, const SgBoundary **bnd)
{
  PetscFunctionBeginUser;
  *bnd = &p->dirichlet;
  PetscFunctionReturn(0);
}
