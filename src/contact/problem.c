/* contact/problem.c: SgProblem, the public object: linear elasticity on a mesh with a contact boundary and a rigid
   obstacle. The mesh is the caller's (SgProblemSetDM) or comes from the options; the material and the boundary parts
   may be given through the interface, and the options (under the problem's prefix) override them. */
#include "contact/contactimpl.h"

PetscErrorCode SgProblemCreate(MPI_Comm comm, SgProblem *prob)
{
  SgProblem p;

  PetscFunctionBeginUser;
  PetscCall(SgLogEventsRegister());
  PetscCall(SgObstacleRegisterAll());
  PetscCall(PetscNew(&p));
  p->comm = comm;
  PetscCall(PetscTime(&p->t_create));
  *prob = p;
  PetscFunctionReturn(0);
}

/* A problem on the caller's mesh: a DMPlex of triangles (2D) or tetrahedra (3D), distributed as the caller wants,
   without overlap; its labels name the boundary parts (SgProblemSetBoundary or -dirichlet_label, ...). */
PetscErrorCode SgProblemCreateFromDM(DM dm, SgProblem *prob)
{
  PetscFunctionBeginUser;
  PetscCall(SgProblemCreate(PetscObjectComm((PetscObject)dm), prob));
  PetscCall(SgProblemSetDM(*prob, dm));
  PetscFunctionReturn(0);
}

static PetscErrorCode CheckNotSetUp(SgProblem p, const char fn[])
{
  PetscFunctionBeginUser;
  PetscCheck(!p->setfromoptions && !p->setup, p->comm, PETSC_ERR_ORDER, "%s: call it before SgProblemSetFromOptions/SgProblemSetUp", fn);
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemSetDM(SgProblem p, DM dm)
{
  PetscFunctionBeginUser;
  PetscCall(CheckNotSetUp(p, "SgProblemSetDM"));
  PetscCall(PetscObjectReference((PetscObject)dm));
  PetscCall(DMDestroy(&p->dm));
  p->dm = dm;
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemSetOptionsPrefix(SgProblem p, const char prefix[])
{
  PetscFunctionBeginUser;
  PetscCall(CheckNotSetUp(p, "SgProblemSetOptionsPrefix"));
  PetscCheck(!prefix || prefix[0] != '-', p->comm, PETSC_ERR_ARG_WRONG, "SgProblemSetOptionsPrefix: the prefix '%s' must not begin with a hyphen", prefix);
  PetscCall(PetscFree(p->prefix));
  PetscCall(PetscStrallocpy(prefix, &p->prefix));
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemGetOptionsPrefix(SgProblem p, const char *prefix[])
{
  PetscFunctionBeginUser;
  *prefix = p->prefix;
  PetscFunctionReturn(0);
}

/* Young's modulus and Poisson's ratio (the defaults of -E and -nu) */
PetscErrorCode SgProblemSetMaterial(SgProblem p, PetscReal E, PetscReal nu)
{
  PetscFunctionBeginUser;
  PetscCall(CheckNotSetUp(p, "SgProblemSetMaterial"));
  p->settings.material_set = PETSC_TRUE;
  p->settings.E            = E;
  p->settings.nu           = nu;
  PetscFunctionReturn(0);
}

/* A boundary part: the points of the label `label` with the values ids[0..n-1] (n = 0: every value); values holds dim
   numbers per id (per part if n = 0) for Dirichlet and Neumann parts, NULL for zero data and for the contact part. */
PetscErrorCode SgProblemSetBoundary(SgProblem p, SgBoundaryType type, const char label[], PetscInt n, const PetscInt ids[], const PetscReal values[])
{
  SgBoundary *b = type == SG_BOUNDARY_DIRICHLET ? &p->settings.dirichlet : (type == SG_BOUNDARY_NEUMANN ? &p->settings.neumann : &p->contact);
  PetscInt    dim = 3, nv;

  PetscFunctionBeginUser;
  PetscCall(CheckNotSetUp(p, "SgProblemSetBoundary"));
  PetscCheck(type >= SG_BOUNDARY_DIRICHLET && type <= SG_BOUNDARY_CONTACT, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "SgProblemSetBoundary: unknown boundary type %d", (int)type);
  PetscCheck(label && label[0], p->comm, PETSC_ERR_ARG_NULL, "SgProblemSetBoundary: a label name is needed");
  PetscCheck(n >= 0 && n <= SG_MAX_IDS, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "SgProblemSetBoundary: %" PetscInt_FMT " ids, at most %d are supported", n, SG_MAX_IDS);
  if (p->dm) PetscCall(DMGetDimension(p->dm, &dim));
  PetscCheck(type != SG_BOUNDARY_CONTACT || !values, p->comm, PETSC_ERR_ARG_WRONG, "SgProblemSetBoundary: the contact part takes no values");
  PetscCall(PetscMemzero(b, sizeof(*b)));
  PetscCall(PetscStrncpy(b->label, label, sizeof(b->label)));
  b->active = PETSC_TRUE;
  b->nids   = n;
  for (PetscInt i = 0; i < n; i++) b->ids[i] = ids[i];
  nv = values ? dim * PetscMax(n, 1) : 0;
  for (PetscInt i = 0; i < nv; i++) {
    PetscCheck(PetscIsNormalReal(values[i]) || values[i] == 0, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "SgProblemSetBoundary: value %" PetscInt_FMT " is %g, must be finite", i, (double)values[i]);
    b->values[i] = values[i];
  }
  b->nvalues = nv;
  PetscFunctionReturn(0);
}

/* The components the Dirichlet part fixes, one mask per id (SG_COMPONENT_X | ...; the default of
   -dirichlet_components); checked against the dimension when the options are read. */
PetscErrorCode SgProblemSetDirichletComponents(SgProblem p, PetscInt n, const PetscInt masks[])
{
  SgBoundary *b = &p->settings.dirichlet;

  PetscFunctionBeginUser;
  PetscCall(CheckNotSetUp(p, "SgProblemSetDirichletComponents"));
  PetscCheck(b->active, p->comm, PETSC_ERR_ORDER, "SgProblemSetDirichletComponents: set the Dirichlet part first (SgProblemSetBoundary)");
  PetscCheck(n == PetscMax(b->nids, 1), p->comm, PETSC_ERR_ARG_SIZ, "SgProblemSetDirichletComponents: %" PetscInt_FMT " masks, need %" PetscInt_FMT " (one per id of the Dirichlet part)", n, PetscMax(b->nids, 1));
  for (PetscInt i = 0; i < n; i++) {
    PetscCheck(masks[i] > 0 && masks[i] <= (SG_COMPONENT_X | SG_COMPONENT_Y | SG_COMPONENT_Z), p->comm, PETSC_ERR_ARG_OUTOFRANGE, "SgProblemSetDirichletComponents: mask %" PetscInt_FMT " is %" PetscInt_FMT ", must be a nonzero sum of SG_COMPONENT_X, _Y, _Z", i, masks[i]);
    b->comps[i] = masks[i];
  }
  b->ncomps = n;
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemSetObstacleType(SgProblem p, const char type[])
{
  PetscFunctionBeginUser;
  PetscCall(CheckNotSetUp(p, "SgProblemSetObstacleType"));
  PetscCall(PetscStrncpy(p->obstacle, type ? type : "", sizeof(p->obstacle)));
  PetscFunctionReturn(0);
}

/* The options under the prefix (material, mesh, boundary parts, obstacle), the mesh made or checked. */
PetscErrorCode SgProblemSetFromOptions(SgProblem p)
{
  PetscFunctionBeginUser;
  PetscCheck(!p->setfromoptions, p->comm, PETSC_ERR_ORDER, "SgProblemSetFromOptions: called twice");
  PetscCall(SgElasticityCreate(p->comm, p->prefix, &p->el));
  PetscCall(SgElasticitySetFromOptions(p->el, p->dm, &p->settings));
  PetscCall(SgContactCreate(p->el, p->prefix, p->contact.active ? &p->contact : NULL, p->obstacle, &p->c));
  p->setfromoptions = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The layout, the assembly of K and b, and the contact geometry (reads the options first if SgProblemSetFromOptions
   was not called: the mesh has to come from somewhere). */
PetscErrorCode SgProblemSetUp(SgProblem p)
{
  PetscFunctionBeginUser;
  if (p->setup) PetscFunctionReturn(0);
  if (!p->setfromoptions) PetscCall(SgProblemSetFromOptions(p));
  PetscCall(SgElasticitySetUp(p->el));
  if (p->c) PetscCall(SgContactSetUp(p->c));
  p->setup = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemView(SgProblem p, PetscViewer viewer)
{
  PetscBool isascii;

  PetscFunctionBeginUser;
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(p->comm, &viewer));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  if (!isascii || !p->setup) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer, "SgProblem%s%s:\n", p->prefix ? " with prefix " : "", p->prefix ? p->prefix : ""));
  PetscCall(PetscViewerASCIIPushTab(viewer));
  PetscCall(SgElasticityView(p->el, viewer));
  if (p->c) {
    const char   *type;
    SgContactView cv;
    PetscCall(SgContactGetView(p->c, &cv));
    PetscCall(SgContactGetObstacleType(p->c, &type));
    PetscCall(PetscViewerASCIIPrintf(viewer, "contact boundary: %" PetscInt_FMT " vertices, area %g; obstacle %s\n", cv.nglobal, (double)cv.area, type));
  } else PetscCall(PetscViewerASCIIPrintf(viewer, "no contact boundary\n"));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemDestroy(SgProblem *prob)
{
  SgProblem p = *prob;

  PetscFunctionBeginUser;
  if (!p) PetscFunctionReturn(0);
  PetscCall(SgContactDestroy(&p->c));
  PetscCall(SgElasticityDestroy(&p->el));
  PetscCall(DMDestroy(&p->dm));
  PetscCall(PetscFree(p->prefix));
  PetscCall(PetscFree(*prob));
  PetscFunctionReturn(0);
}

static PetscErrorCode CheckSetUp(SgProblem p, const char fn[])
{
  PetscFunctionBeginUser;
  PetscCheck(p->setup, p->comm, PETSC_ERR_ORDER, "%s: call SgProblemSetUp first", fn);
  PetscFunctionReturn(0);
}

/* the displacement DM: its global vectors hold the free (non-Dirichlet) dofs */
PetscErrorCode SgProblemGetDM(SgProblem p, DM *dm)
{
  PetscFunctionBeginUser;
  PetscCall(CheckSetUp(p, "SgProblemGetDM"));
  PetscCall(SgElasticityGetDMs(p->el, dm, NULL, NULL, NULL));
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemGetDimension(SgProblem p, PetscInt *dim)
{
  PetscFunctionBeginUser;
  PetscCheck(p->el, p->comm, PETSC_ERR_ORDER, "SgProblemGetDimension: call SgProblemSetFromOptions first");
  PetscCall(SgElasticityGetDimension(p->el, dim));
  PetscFunctionReturn(0);
}

/* unknowns, cells and contact vertices, each summed over the ranks */
PetscErrorCode SgProblemGetSizes(SgProblem p, PetscInt *ndofs, PetscInt *ncells, PetscInt *ncontact)
{
  PetscFunctionBeginUser;
  PetscCall(CheckSetUp(p, "SgProblemGetSizes"));
  PetscCall(SgElasticityGetInfo(p->el, ndofs, ncells, NULL, NULL));
  if (ncontact) *ncontact = p->c ? p->c->nglobal : 0;
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemHasContact(SgProblem p, PetscBool *has)
{
  PetscFunctionBeginUser;
  PetscCheck(p->setfromoptions, p->comm, PETSC_ERR_ORDER, "SgProblemHasContact: call SgProblemSetFromOptions first");
  *has = p->c ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemCreateVector(SgProblem p, Vec *y)
{
  DM dm;

  PetscFunctionBeginUser;
  PetscCall(SgProblemGetDM(p, &dm));
  PetscCall(DMCreateGlobalVector(dm, y));
  PetscFunctionReturn(0);
}

/* V(y) = 1/2 y K y - b y + the Dirichlet part: the potential energy of the displacement y */
PetscErrorCode SgProblemComputeEnergy(SgProblem p, Vec y, PetscReal *V)
{
  PetscFunctionBeginUser;
  PetscCall(CheckSetUp(p, "SgProblemComputeEnergy"));
  PetscCall(SgElasticityEnergy(p->el, y, V));
  PetscFunctionReturn(0);
}

/* Quasi-static load stepping: the loads (body force, Neumann tractions), the Dirichlet values and the obstacle's
   translation (-obstacle_translation) times t; t = 1 is the problem as given. A solver that solved the problem before
   continues from its last solution when SgContSolve is called again (a warm start). */
PetscErrorCode SgProblemSetLoadFactor(SgProblem p, PetscReal t)
{
  PetscFunctionBeginUser;
  PetscCall(SgProblemSetUp(p));
  PetscCheck((PetscIsNormalReal(t) && t > 0) || t == 0, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "SgProblemSetLoadFactor: the factor must be finite and >= 0 (0: unloaded), got %g", (double)t);
  PetscCall(SgElasticitySetLoadFactor(p->el, t));
  if (p->c) PetscCall(SgContactSetLoadFactor(p->c, t));
  p->load_set = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* Non-proportional loading: the Dirichlet values of every id (dim numbers per Dirichlet id, in the order of the ids;
   SgProblemGetDirichletSize numbers in all) for the next solve and the later ones until set again; the load factor
   then scales the loads and the obstacle's translation only (values NULL: back to the given values times the
   factor). With SgContSolve after each call a program drives any load path (a normal load first, a tangential one
   after it). */
PetscErrorCode SgProblemSetDirichletValues(SgProblem p, const PetscReal values[])
{
  PetscFunctionBeginUser;
  PetscCall(SgProblemSetUp(p));
  PetscCall(SgElasticitySetDirichletValues(p->el, values));
  if (p->c) { /* the load scale of the contact's KKT measures */
    PetscReal t;
    PetscCall(SgElasticityGetLoadFactor(p->el, &t));
    PetscCall(SgContactSetLoadFactor(p->c, t));
  }
  p->load_set = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* the number of values SgProblemSetDirichletValues takes (0 without a Dirichlet part) */
PetscErrorCode SgProblemGetDirichletSize(SgProblem p, PetscInt *n)
{
  PetscFunctionBeginUser;
  PetscCall(CheckSetUp(p, "SgProblemGetDirichletSize"));
  PetscCall(SgElasticityGetDirichletSize(p->el, n));
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemGetLoadFactor(SgProblem p, PetscReal *t)
{
  PetscFunctionBeginUser;
  *t = 1;
  if (p->el) PetscCall(SgElasticityGetLoadFactor(p->el, t));
  PetscFunctionReturn(0);
}

/* whether SgProblemSetLoadFactor or SgProblemSetDirichletValues was called (the run has load steps) */
PetscErrorCode SgProblemHasLoadSteps(SgProblem p, PetscBool *has)
{
  PetscFunctionBeginUser;
  *has = p->load_set;
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemGetElasticity(SgProblem p, SgElasticity *el)
{
  PetscFunctionBeginUser;
  *el = p->el;
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemGetContact(SgProblem p, SgContact *c)
{
  PetscFunctionBeginUser;
  *c = p->c;
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemGetComm(SgProblem p, MPI_Comm *comm)
{
  PetscFunctionBeginUser;
  *comm = p->comm;
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemGetCreationTime(SgProblem p, PetscLogDouble *t)
{
  PetscFunctionBeginUser;
  *t = p->t_create;
  PetscFunctionReturn(0);
}
