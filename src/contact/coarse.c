/* contact/coarse.c: the coarser problems of nested iteration (-cont_nested, cont/nested.c). The fine problem's mesh
   is made from the options (SgMeshCreateDM: read or boxed, distributed, then refined -dm_refine times by
   DMSetFromOptions); a problem k levels coarser is the same problem on that mesh refined k times fewer (the same file
   or box, the same distribution), so that its next refinement is the fine problem's mesh point by point (checked by
   the transfer, cont/nested.c). Everything else (material, boundary parts, obstacle, load factor, Dirichlet values) is
   the fine problem's. */
#include "contact/contactimpl.h"

/* The refinement the problem's mesh came with: own = PETSC_FALSE if the caller gave the mesh (SgProblemSetDM), else
   the -dm_refine count (0 if not given). */
PetscErrorCode SgProblemGetRefinement(SgProblem p, PetscBool *own, PetscInt *nrefine)
{
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(SgValidProblem(p, "SgProblemGetRefinement", 1));
  *own     = (PetscBool)!p->dm;
  *nrefine = 0;
  if (p->dm) PetscFunctionReturn(0);
  PetscCall(PetscOptionsGetInt(NULL, ((PetscObject)p)->prefix, "-dm_refine", nrefine, &set));
  if (!set) *nrefine = 0;
  PetscFunctionReturn(0);
}

/* The problem on the mesh refined `down` times fewer than p's (1 <= down <= p's -dm_refine), set up. The options
   database's -<prefix>dm_refine is changed while its mesh is made and put back afterwards (also after an error). */
PetscErrorCode SgProblemCreateCoarse(SgProblem p, PetscInt down, SgProblem *coarse)
{
  SgProblem      q;
  PetscBool      own;
  PetscInt       nref;
  char           opt[PETSC_MAX_PATH_LEN], was[64], now[64];
  const char    *prefix = ((PetscObject)p)->prefix;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  *coarse = NULL;
  PetscCheck(p->setup, p->comm, PETSC_ERR_ORDER, "SgProblemCreateCoarse: the problem is not set up");
  PetscCall(SgProblemGetRefinement(p, &own, &nref));
  PetscCheck(own, p->comm, PETSC_ERR_USER_INPUT, "-cont_nested: the mesh was given by the program (SgProblemSetDM); nested iteration needs a mesh made from the options and refined with -dm_refine");
  PetscCheck(down >= 1 && down <= nref, p->comm, PETSC_ERR_USER_INPUT, "-cont_nested %" PetscInt_FMT ": the mesh is refined %" PetscInt_FMT " times after distribution (-%sdm_refine %" PetscInt_FMT "); nested iteration needs -dm_refine >= -cont_nested", down, nref, prefix ? prefix : "", nref);
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%sdm_refine", prefix ? prefix : ""));
  PetscCall(PetscSNPrintf(was, sizeof(was), "%" PetscInt_FMT, nref));
  PetscCall(PetscSNPrintf(now, sizeof(now), "%" PetscInt_FMT, nref - down));
  PetscCall(SgProblemCreate(p->comm, &q));
  if (prefix) PetscCall(SgProblemSetOptionsPrefix(q, prefix));
  q->settings = p->settings;
  q->contact  = p->contact;
  q->master   = p->master; /* two bodies through the interface: the same sides (and obstacle faces) on every level */
  q->obnd     = p->obnd;
  PetscCall(PetscArraycpy(q->values_dim, p->values_dim, (PetscInt)(sizeof(q->values_dim) / sizeof(q->values_dim[0]))));
  PetscCall(PetscStrncpy(q->obstacle, p->obstacle, sizeof(q->obstacle)));
  { /* the coarser mesh kept with the fine one when it was made (fem/mesh.c, MeshRefineNested): its distribution */
    DM          dm;
    PetscObject lv = NULL;
    char        name[64];
    PetscCall(SgElasticityGetDMs(p->el, &dm, NULL, NULL, NULL));
    PetscCall(PetscSNPrintf(name, sizeof(name), "SgNestedLevel%" PetscInt_FMT, down));
    PetscCall(PetscObjectQuery((PetscObject)dm, name, &lv));
    if (lv) q->dm = (DM)lv;
    if (lv) PetscCall(PetscObjectReference(lv));
  }
  if (!q->dm) PetscCall(PetscOptionsSetValue(NULL, opt, now)); /* else the mesh again, refined fewer times */
  ierr = SgProblemSetUp(q);
  if (!q->dm) PetscCall(PetscOptionsSetValue(NULL, opt, was));
  if (ierr) PetscCall(SgProblemDestroy(&q));
  PetscCall(ierr);
  if (p->load_set) { /* the fine problem's load step */
    PetscReal t, *dv = NULL;
    PetscInt  ndv;
    PetscBool dset;
    PetscCall(SgElasticityGetLoadFactor(p->el, &t));
    PetscCall(SgProblemSetLoadFactor(q, t));
    PetscCall(SgElasticityGetDirichletSize(p->el, &ndv));
    PetscCall(PetscMalloc1(ndv + 1, &dv));
    PetscCall(SgElasticityGetDirichletValues(p->el, &dset, dv));
    if (dset) PetscCall(SgProblemSetDirichletValues(q, dv));
    PetscCall(PetscFree(dv));
  }
  *coarse = q;
  PetscFunctionReturn(0);
}
