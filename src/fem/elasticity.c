/* elasticity.c: the linear elasticity object: its options (material, boundary parts), set-up, view, accessors and
   destruction. */
#include "fem/femimpl.h"

static PetscErrorCode ProblemOptions(SgElasticity p, const SgElasticitySettings *set)
{
  PetscFunctionBeginUser;
  p->E  = set && set->material_set ? set->E : 1.0;
  p->nu = set && set->material_set ? set->nu : 0.3;
  PetscOptionsBegin(p->comm, p->prefix, "Linear elasticity", NULL);
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-E", "Young's modulus", &p->E, NULL));
  PetscCall(SgOptionsRealValue(PetscOptionsObject, "-nu", "Poisson's ratio in [0, 0.5) (plane strain in 2D)", &p->nu, NULL));
  p->nbody_force = 0;
  PetscCall(SgOptionsRealList(PetscOptionsObject, "-body_force", "Constant body force f (dim numbers)", 3, p->body_force, &p->nbody_force, NULL));
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
  PetscCheck(PetscIsNormalReal(p->E) && p->E > 0, p->comm, PETSC_ERR_USER_INPUT, "-E: Young's modulus must be positive and finite, got %g", (double)p->E);
  /* nu = 0 (no lateral contraction) is a valid material; nu -> 1/2 is incompressible */
  PetscCheck(!PetscIsInfOrNanReal(p->nu) && p->nu >= 0 && p->nu < 0.5, p->comm, PETSC_ERR_USER_INPUT, "-nu: Poisson's ratio must lie in [0, 0.5), got %g", (double)p->nu);
  for (PetscInt d = 0; d < p->nbody_force; d++) PetscCheck(PetscIsNormalReal(p->body_force[d]) || p->body_force[d] == 0, p->comm, PETSC_ERR_USER_INPUT, "-body_force: entry %" PetscInt_FMT " is %g, must be finite", d, (double)p->body_force[d]);
  PetscCheck(!p->rigid_shift_set || (PetscIsNormalReal(p->rigid_shift) && p->rigid_shift > 0) || p->rigid_shift == 0, p->comm, PETSC_ERR_USER_INPUT, "-elasticity_rigid_shift: must be finite and >= 0, got %g", (double)p->rigid_shift);
  PetscCall(SgLame(p->E, p->nu, &p->lambda, &p->mu));
  /* nu -> 1/2: lambda / mu = 2 nu / (1 - 2 nu) grows without bound; once the shear part of K is below 1e3 rounding
     units of the volumetric part, K is singular to working precision (a factorization meets zero pivots) and no
     tolerance the KKT measures could certify is left (their round-off, SgKKT.roundoff, is larger still) */
  PetscCheck((PetscIsNormalReal(p->lambda) || p->lambda == 0) && p->lambda / p->mu <= 1e-3 / PETSC_MACHINE_EPSILON, p->comm, PETSC_ERR_USER_INPUT, "-nu %.16g (E %g): lambda/mu = %.3g, too nearly incompressible for double precision (the shear stiffness is lost in the rounding of the volumetric one, K is singular to working precision); nu <= 0.4999999999 (lambda/mu 5e9) can be solved to tolerances that the run's KKT measures state", (double)p->nu, (double)p->E, (double)(p->lambda / p->mu));
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
  } else PetscCall(SgMeshCreateDM(comm, p->prefix, &p->dm));
  PetscCall(DMGetDimension(p->dm, &p->dim));
  PetscCheck(p->nbody_force == 0 || p->nbody_force == p->dim, comm, PETSC_ERR_USER_INPUT, "-body_force: give %" PetscInt_FMT " numbers for this %" PetscInt_FMT "D mesh, got %" PetscInt_FMT, p->dim, p->dim, p->nbody_force);
  PetscCall(BoundaryValueOptions(p));
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
  PetscCall(PetscViewerASCIIPrintf(viewer, "linear elasticity (P1, %s): %" PetscInt_FMT "D, %" PetscInt_FMT " cells, %" PetscInt_FMT " unknowns, E %g, nu %g\n", p->dim == 2 ? "plane strain" : "3D", p->dim, nc, p->ndofs, (double)p->E, (double)p->nu));
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
