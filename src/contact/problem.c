/* contact/problem.c: SgProblem, the public object: linear elasticity on a mesh with a contact boundary and a rigid
   obstacle. The mesh is the caller's (SgProblemSetDM) or comes from the options; the material and the boundary parts
   may be given through the interface, and the options (under the problem's prefix) override them. */
#include "contact/contactimpl.h"

/* arg-th argument of fn must be a live SgProblem (not NULL, not destroyed): the class id of its PETSc header, checked
   also where PETSc's PetscValidHeaderSpecific compiles to nothing (an optimized PETSc) */
PetscErrorCode SgValidProblem(SgProblem p, const char fn[], int arg)
{
  PetscFunctionBeginUser;
  PetscCall(SgValidObject((PetscObject)p, SG_PROBLEM_CLASSID, "SgProblem", fn, arg));
  PetscValidHeaderSpecific(p, SG_PROBLEM_CLASSID, arg);
  PetscFunctionReturn(0);
}

#define ValidProblem(p, arg) PetscCall(SgValidProblem(p, PETSC_FUNCTION_NAME, arg))

PetscErrorCode SgProblemCreate(MPI_Comm comm, SgProblem *prob)
{
  SgProblem p;

  PetscFunctionBeginUser;
  SgValidPointer(prob, 2);
  *prob = NULL;
  PetscCheck(comm != MPI_COMM_NULL, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "SgProblemCreate: the communicator is MPI_COMM_NULL");
  PetscCall(SgLogEventsRegister());
  PetscCall(SgObstacleRegisterAll());
  PetscCall(PetscHeaderCreate(p, SG_PROBLEM_CLASSID, "SgProblem", "Contact problem", "SgProblem", comm, SgProblemDestroy, SgProblemView)); /* PetscObjectDestroy/View reach them */
  p->comm = comm;
  PetscCall(PetscTime(&p->t_create));
  *prob = p;
  PetscFunctionReturn(0);
}

/* the caller's mesh must be a DMPlex (DMPlex functions on another DM type read the wrong struct) */
static PetscErrorCode CheckDM(DM dm, const char fn[], int arg)
{
  PetscBool isplex;
  DMType    type;

  PetscFunctionBeginUser;
  PetscCall(SgValidObject((PetscObject)dm, DM_CLASSID, "DM", fn, arg));
  PetscCall(PetscObjectTypeCompare((PetscObject)dm, DMPLEX, &isplex));
  PetscCall(DMGetType(dm, &type));
  PetscCheck(isplex, PetscObjectComm((PetscObject)dm), PETSC_ERR_ARG_WRONG, "%s: the DM is of type %s; the library needs a DMPLEX of triangles or tetrahedra", fn, type ? type : "(not set)");
  PetscFunctionReturn(0);
}

/* A problem on the caller's mesh: a DMPlex of triangles (2D) or tetrahedra (3D), distributed as the caller wants,
   without overlap; its labels name the boundary parts (SgProblemSetBoundary or -dirichlet_label, ...). */
PetscErrorCode SgProblemCreateFromDM(DM dm, SgProblem *prob)
{
  SgProblem      p;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  SgValidPointer(prob, 2);
  *prob = NULL;
  PetscCall(CheckDM(dm, PETSC_FUNCTION_NAME, 1));
  PetscCall(SgProblemCreate(PetscObjectComm((PetscObject)dm), &p));
  ierr = SgProblemSetDM(p, dm);
  if (ierr) PetscCall(SgProblemDestroy(&p)); /* nothing half-made is handed out */
  PetscCall(ierr);
  *prob = p;
  PetscFunctionReturn(0);
}

static PetscErrorCode CheckNotSetUp(SgProblem p, const char fn[])
{
  PetscFunctionBeginUser;
  PetscCall(SgValidProblem(p, fn, 1));
  PetscCheck(!p->setfromoptions && !p->setup, p->comm, PETSC_ERR_ORDER, "%s: call it before SgProblemSetFromOptions/SgProblemSetUp", fn);
  PetscFunctionReturn(0);
}

/* Our own copy of the caller's mesh, so that the caller's later changes to its DM do not reach the problem. DMClone
   shares the topology (which PETSc never changes after setup) and copies the labels' values, but (PETSc 3.18) it
   shares the local coordinate vector: a caller moving its vertices would move ours. The coordinates are copied. */
static PetscErrorCode CopyDM(DM dm, DM *copy)
{
  Vec x, xc;

  PetscFunctionBeginUser;
  PetscCall(DMClone(dm, copy));
  PetscCall(DMGetCoordinatesLocal(dm, &x));
  if (x) {
    PetscCall(VecDuplicate(x, &xc));
    PetscCall(VecCopy(x, xc));
    PetscCall(DMSetCoordinatesLocal(*copy, xc));
    PetscCall(VecDestroy(&xc));
  }
  PetscCall(DMGetCellCoordinatesLocal(dm, &x)); /* periodic meshes' cell coordinates: shared the same way */
  if (x) {
    PetscCall(VecDuplicate(x, &xc));
    PetscCall(VecCopy(x, xc));
    PetscCall(DMSetCellCoordinatesLocal(*copy, xc));
    PetscCall(VecDestroy(&xc));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemSetDM(SgProblem p, DM dm)
{
  DM copy;

  PetscFunctionBeginUser;
  PetscCall(CheckNotSetUp(p, "SgProblemSetDM"));
  PetscCall(CheckDM(dm, "SgProblemSetDM", 2));
  {
    PetscMPIInt cmp;
    PetscCallMPI(MPI_Comm_compare(p->comm, PetscObjectComm((PetscObject)dm), &cmp));
    PetscCheck(cmp == MPI_IDENT || cmp == MPI_CONGRUENT, PETSC_COMM_SELF, PETSC_ERR_ARG_NOTSAMECOMM, "SgProblemSetDM: the DM lives on another communicator than the problem (SgProblemCreate's)");
  }
  PetscCall(CopyDM(dm, &copy));
  PetscCall(DMDestroy(&p->dm));
  p->dm = copy;
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemSetOptionsPrefix(SgProblem p, const char prefix[])
{
  PetscFunctionBeginUser;
  PetscCall(CheckNotSetUp(p, "SgProblemSetOptionsPrefix"));
  PetscCheck(!prefix || prefix[0] != '-', p->comm, PETSC_ERR_ARG_WRONG, "SgProblemSetOptionsPrefix: the prefix '%s' must not begin with a hyphen", prefix);
  PetscCall(PetscObjectSetOptionsPrefix((PetscObject)p, prefix));
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemGetOptionsPrefix(SgProblem p, const char *prefix[])
{
  PetscFunctionBeginUser;
  ValidProblem(p, 1);
  SgValidPointer(prefix, 2);
  *prefix = ((PetscObject)p)->prefix;
  PetscFunctionReturn(0);
}

/* Young's modulus and Poisson's ratio (the defaults of -E and -nu) */
PetscErrorCode SgProblemSetMaterial(SgProblem p, PetscReal E, PetscReal nu)
{
  PetscFunctionBeginUser;
  PetscCall(CheckNotSetUp(p, "SgProblemSetMaterial"));
  /* the ranges of -E and -nu */
  PetscCheck(PetscIsNormalReal(E) && E > 0, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "SgProblemSetMaterial: Young's modulus must be positive and finite, got %g", (double)E);
  PetscCheck(!PetscIsInfOrNanReal(nu) && nu >= 0 && nu < 0.5, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "SgProblemSetMaterial: Poisson's ratio must lie in [0, 0.5), got %g", (double)nu);
  p->settings.material_set = PETSC_TRUE;
  p->settings.nmat         = 0; /* one material from now on */
  p->settings.E            = E;
  p->settings.nu           = nu;
  PetscFunctionReturn(0);
}

/* Several materials (the defaults of -material_label, -material_ids, -E, -nu): cell c has E[k], nu[k] when its value of
   the cell label `label` (NULL: "Cell Sets", gmsh's physical volumes) is ids[k]; n = 1: every cell has E[0], nu[0]. */
PetscErrorCode SgProblemSetMaterials(SgProblem p, const char label[], PetscInt n, const PetscInt ids[], const PetscReal E[], const PetscReal nu[])
{
  size_t len = 0;

  PetscFunctionBeginUser;
  PetscCall(CheckNotSetUp(p, "SgProblemSetMaterials"));
  PetscCheck(n >= 1 && n <= SG_MAX_IDS, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "SgProblemSetMaterials: %" PetscInt_FMT " materials, 1 to %d are supported", n, SG_MAX_IDS);
  PetscCheck(ids && E && nu, p->comm, PETSC_ERR_ARG_NULL, "SgProblemSetMaterials: the arrays of ids, E and nu are needed");
  if (label) PetscCall(PetscStrlen(label, &len));
  PetscCheck(len < sizeof(p->settings.matlabel), p->comm, PETSC_ERR_ARG_SIZ, "SgProblemSetMaterials: the label name has %zu characters, at most %zu are supported", len, sizeof(p->settings.matlabel) - 1);
  for (PetscInt k = 0; k < n; k++) {
    PetscCheck(ids[k] >= 0, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "SgProblemSetMaterials: id %" PetscInt_FMT " is %" PetscInt_FMT ", label values of cells are >= 0", k, ids[k]);
    for (PetscInt j = 0; j < k; j++) PetscCheck(ids[j] != ids[k], p->comm, PETSC_ERR_ARG_WRONG, "SgProblemSetMaterials: the id %" PetscInt_FMT " is given twice", ids[k]);
    PetscCheck(PetscIsNormalReal(E[k]) && E[k] > 0, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "SgProblemSetMaterials: Young's modulus of id %" PetscInt_FMT " must be positive and finite, got %g", ids[k], (double)E[k]);
    PetscCheck(!PetscIsInfOrNanReal(nu[k]) && nu[k] >= 0 && nu[k] < 0.5, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "SgProblemSetMaterials: Poisson's ratio of id %" PetscInt_FMT " must lie in [0, 0.5), got %g", ids[k], (double)nu[k]);
  }
  PetscCall(PetscStrncpy(p->settings.matlabel, label && label[0] ? label : "Cell Sets", sizeof(p->settings.matlabel)));
  for (PetscInt k = 0; k < n; k++) {
    p->settings.matids[k] = ids[k];
    p->settings.matE[k]   = E[k];
    p->settings.matnu[k]  = nu[k];
  }
  p->settings.nmat = n;
  PetscFunctionReturn(0);
}

/* A boundary part: the points of the label `label` with the values ids[0..n-1] (n = 0: every value); values holds dim
   numbers per id (per part if n = 0) for Dirichlet and Neumann parts, NULL for zero data and for the contact part. */
/* The dimension of the values SgProblemSetBoundary reads (dim per id) before the mesh is made: the caller's DM's, else
   the options' box's (-box_dim, 2 unless given). A mesh file's is not known before the file is read: 2, the smallest,
   so that no value past the caller's array is read; a 3D mesh then makes SgProblemSetFromOptions fail, saying so. */
static PetscErrorCode ValuesDimension(SgProblem p, PetscInt *dim)
{
  PetscBool file, set;
  PetscInt  d = 2;

  PetscFunctionBeginUser;
  *dim = 2;
  if (p->dm) {
    PetscCall(DMGetDimension(p->dm, dim));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscOptionsHasName(NULL, ((PetscObject)p)->prefix, "-dm_plex_filename", &file));
  if (file) PetscFunctionReturn(0);
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL)); /* a malformed -box_dim is reported when the mesh is made */
  if (PetscOptionsGetInt(NULL, ((PetscObject)p)->prefix, "-box_dim", &d, &set)) set = PETSC_FALSE;
  PetscCall(PetscPopErrorHandler());
  if (set && d == 3) *dim = 3;
  PetscFunctionReturn(0);
}

/* After the mesh is made: values read with another dimension than the mesh's (and not replaced by the options) */
static PetscErrorCode CheckValuesDimension(SgProblem p)
{
  const char *opt[2] = {"-dirichlet_values", "-neumann_traction"}, *name[2] = {"Dirichlet", "Neumann"};
  PetscInt    dim;

  PetscFunctionBeginUser;
  PetscCall(SgElasticityGetDimension(p->el, &dim));
  for (PetscInt t = 0; t < 2; t++) {
    PetscBool set;
    if (!p->values_dim[t] || p->values_dim[t] == dim) continue;
    PetscCall(PetscOptionsHasName(NULL, ((PetscObject)p)->prefix, opt[t], &set));
    PetscCheck(set, p->comm, PETSC_ERR_ARG_INCOMP, "SgProblemSetBoundary: the %s values were read as %" PetscInt_FMT " per id (the mesh did not exist yet), but the mesh is %" PetscInt_FMT "D: call SgProblemSetDM (or give -%sbox_dim %" PetscInt_FMT ") before SgProblemSetBoundary", name[t], p->values_dim[t], dim, ((PetscObject)p)->prefix ? ((PetscObject)p)->prefix : "", dim);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemSetBoundary(SgProblem p, SgBoundaryType type, const char label[], PetscInt n, const PetscInt ids[], const PetscReal values[])
{
  SgBoundary *b;
  PetscInt    dim, nv;
  size_t      len;

  PetscFunctionBeginUser;
  PetscCall(CheckNotSetUp(p, "SgProblemSetBoundary"));
  PetscCheck(type >= SG_BOUNDARY_DIRICHLET && type <= SG_BOUNDARY_CONTACT_OBSTACLE, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "SgProblemSetBoundary: unknown boundary type %d", (int)type);
  b = type == SG_BOUNDARY_DIRICHLET ? &p->settings.dirichlet : (type == SG_BOUNDARY_NEUMANN ? &p->settings.neumann : (type == SG_BOUNDARY_CONTACT ? &p->contact : (type == SG_BOUNDARY_CONTACT_MASTER ? &p->master : &p->obnd)));
  PetscCheck(label && label[0], p->comm, PETSC_ERR_ARG_NULL, "SgProblemSetBoundary: a label name is needed");
  PetscCall(PetscStrlen(label, &len));
  PetscCheck(len < sizeof(b->label), p->comm, PETSC_ERR_ARG_SIZ, "SgProblemSetBoundary: the label name has %zu characters, at most %zu are supported", len, sizeof(b->label) - 1);
  PetscCheck(n >= 0 && n <= SG_MAX_IDS, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "SgProblemSetBoundary: %" PetscInt_FMT " ids, at most %d are supported", n, SG_MAX_IDS);
  PetscCheck(!n || ids, p->comm, PETSC_ERR_ARG_NULL, "SgProblemSetBoundary: %" PetscInt_FMT " ids, but the array of ids is NULL", n);
  PetscCall(ValuesDimension(p, &dim));
  PetscCheck(type < SG_BOUNDARY_CONTACT || !values, p->comm, PETSC_ERR_ARG_WRONG, "SgProblemSetBoundary: the contact part takes no values");
  PetscCheck(type != SG_BOUNDARY_CONTACT_MASTER || n > 0, p->comm, PETSC_ERR_ARG_WRONG, "SgProblemSetBoundary: the master side (SG_BOUNDARY_CONTACT_MASTER) needs its ids (values of the contact part's label)");
  PetscCheck(type != SG_BOUNDARY_CONTACT_OBSTACLE || n > 0, p->comm, PETSC_ERR_ARG_WRONG, "SgProblemSetBoundary: the obstacle's faces (SG_BOUNDARY_CONTACT_OBSTACLE) need their ids (values of the contact part's label)");
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
  b->nvalues          = nv;
  p->values_dim[type] = nv ? dim : 0;
  PetscFunctionReturn(0);
}

/* The components the Dirichlet part fixes, one mask per id (SG_COMPONENT_X | ...; the default of
   -dirichlet_components); checked against the dimension when the options are read. */
PetscErrorCode SgProblemSetDirichletComponents(SgProblem p, PetscInt n, const PetscInt masks[])
{
  SgBoundary *b = &p->settings.dirichlet;

  PetscFunctionBeginUser;
  PetscCall(CheckNotSetUp(p, "SgProblemSetDirichletComponents"));
  PetscCheck(!n || masks, p->comm, PETSC_ERR_ARG_NULL, "SgProblemSetDirichletComponents: %" PetscInt_FMT " masks, but the array is NULL", n);
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
  if (type) {
    size_t len;
    PetscCall(PetscStrlen(type, &len));
    PetscCheck(len < sizeof(p->obstacle), p->comm, PETSC_ERR_ARG_SIZ, "SgProblemSetObstacleType: the type name has %zu characters, at most %zu", len, sizeof(p->obstacle) - 1);
  }
  PetscCall(PetscStrncpy(p->obstacle, type ? type : "", sizeof(p->obstacle)));
  PetscFunctionReturn(0);
}

/* The options under the prefix (material, mesh, boundary parts, obstacle), the mesh made or checked. */
PetscErrorCode SgProblemSetFromOptions(SgProblem p)
{
  PetscFunctionBeginUser;
  ValidProblem(p, 1);
  PetscCheck(!p->setfromoptions, p->comm, PETSC_ERR_ORDER, "SgProblemSetFromOptions: called twice");
  PetscCall(SgContactDestroy(&p->c)); /* of an earlier call that failed */
  PetscCall(SgElasticityDestroy(&p->el));
  PetscCall(SgElasticityCreate(p->comm, ((PetscObject)p)->prefix, &p->el));
  PetscCall(SgElasticitySetFromOptions(p->el, p->dm, &p->settings));
  PetscCall(CheckValuesDimension(p));
  PetscCall(SgContactCreate(p->el, ((PetscObject)p)->prefix, p->contact.active ? &p->contact : NULL, p->master.active ? &p->master : NULL, p->obnd.active ? &p->obnd : NULL, p->obstacle, &p->c));
  p->setfromoptions = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* The layout, the assembly of K and b, and the contact geometry (reads the options first if SgProblemSetFromOptions
   was not called: the mesh has to come from somewhere). */
PetscErrorCode SgProblemSetUp(SgProblem p)
{
  PetscFunctionBeginUser;
  ValidProblem(p, 1);
  if (p->setup) PetscFunctionReturn(0);
  PetscCheck(!p->setup_failed, p->comm, PETSC_ERR_ORDER, "SgProblemSetUp: an earlier call stopped with an error; destroy the problem and make a new one");
  if (!p->setfromoptions) PetscCall(SgProblemSetFromOptions(p));
  p->setup_failed = PETSC_TRUE; /* until the end is reached */
  PetscCall(SgElasticitySetUp(p->el));
  if (p->c) PetscCall(SgContactSetUp(p->c));
  p->setup_failed = PETSC_FALSE;
  p->setup        = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemView(SgProblem p, PetscViewer viewer)
{
  PetscBool isascii;

  PetscFunctionBeginUser;
  ValidProblem(p, 1);
  if (viewer) SgValidHeaderSpecific(viewer, PETSC_VIEWER_CLASSID, "PetscViewer", 2);
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(p->comm, &viewer));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &isascii));
  if (!isascii || !p->setup) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer, "SgProblem%s%s:\n", ((PetscObject)p)->prefix ? " with prefix " : "", ((PetscObject)p)->prefix ? ((PetscObject)p)->prefix : ""));
  PetscCall(PetscViewerASCIIPushTab(viewer));
  PetscCall(SgElasticityView(p->el, viewer));
  if (p->c) {
    const char *type;
    PetscInt    nglobal;
    PetscReal   area;
    PetscCall(SgContactGetVertices(p->c, NULL, &nglobal, NULL, NULL));
    PetscCall(SgContactGetArea(p->c, &area));
    PetscCall(SgContactGetObstacleType(p->c, &type));
    PetscCall(PetscViewerASCIIPrintf(viewer, "contact boundary: %" PetscInt_FMT " vertices, area %g; obstacle %s\n", nglobal, (double)area, type));
  } else PetscCall(PetscViewerASCIIPrintf(viewer, "no contact boundary\n"));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(0);
}

/* One more holder of the problem (a controller): SgProblemDestroy frees it when the last one lets it go. The same as
   PetscObjectReference((PetscObject)p), kept for the programs that call it. */
PetscErrorCode SgProblemReference(SgProblem p)
{
  PetscFunctionBeginUser;
  ValidProblem(p, 1);
  PetscCall(PetscObjectReference((PetscObject)p));
  PetscFunctionReturn(0);
}

/* Lets the caller's handle go (*prob = NULL); the problem is freed when no controller holds it any more. */
PetscErrorCode SgProblemDestroy(SgProblem *prob)
{
  SgProblem p;

  PetscFunctionBeginUser;
  SgValidPointer(prob, 1);
  p = *prob;
  if (!p) PetscFunctionReturn(0);
  ValidProblem(p, 1);
  *prob = NULL;
  if (--((PetscObject)p)->refct > 0) PetscFunctionReturn(0);
  PetscCall(SgContactDestroy(&p->c));
  PetscCall(SgElasticityDestroy(&p->el));
  PetscCall(DMDestroy(&p->dm));
  PetscCall(PetscHeaderDestroy(&p));
  PetscFunctionReturn(0);
}

static PetscErrorCode CheckSetUp(SgProblem p, const char fn[])
{
  PetscFunctionBeginUser;
  PetscCall(SgValidProblem(p, fn, 1));
  PetscCheck(p->setup, p->comm, PETSC_ERR_ORDER, "%s: call SgProblemSetUp first", fn);
  PetscFunctionReturn(0);
}

/* the displacement DM: its global vectors hold the free (non-Dirichlet) dofs */
PetscErrorCode SgProblemGetDM(SgProblem p, DM *dm)
{
  PetscFunctionBeginUser;
  PetscCall(CheckSetUp(p, "SgProblemGetDM"));
  SgValidPointer(dm, 2);
  PetscCall(SgElasticityGetDMs(p->el, dm, NULL, NULL, NULL));
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemGetDimension(SgProblem p, PetscInt *dim)
{
  PetscFunctionBeginUser;
  ValidProblem(p, 1);
  SgValidPointer(dim, 2);
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
  ValidProblem(p, 1);
  SgValidPointer(has, 2);
  PetscCheck(p->setfromoptions, p->comm, PETSC_ERR_ORDER, "SgProblemHasContact: call SgProblemSetFromOptions first");
  *has = p->c ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemCreateVector(SgProblem p, Vec *y)
{
  DM dm;

  PetscFunctionBeginUser;
  PetscCall(SgProblemGetDM(p, &dm));
  SgValidPointer(y, 2);
  PetscCall(DMCreateGlobalVector(dm, y));
  PetscFunctionReturn(0);
}

/* V(y) = 1/2 y K y - b y + the Dirichlet part: the potential energy of the displacement y */
PetscErrorCode SgProblemComputeEnergy(SgProblem p, Vec y, PetscReal *V)
{
  PetscFunctionBeginUser;
  PetscCall(CheckSetUp(p, "SgProblemComputeEnergy"));
  SgValidHeaderSpecific(y, VEC_CLASSID, "Vec", 2);
  SgValidPointer(V, 3);
  { /* a displacement of this problem (SgProblemCreateVector): its layout is read as one */
    DM       dm;
    PetscInt n, N, ny, Ny;
    Vec      g;
    PetscCall(SgProblemGetDM(p, &dm));
    PetscCall(DMGetGlobalVector(dm, &g));
    PetscCall(VecGetSize(g, &N));
    PetscCall(VecGetLocalSize(g, &n));
    PetscCall(DMRestoreGlobalVector(dm, &g));
    PetscCall(VecGetSize(y, &Ny));
    PetscCall(VecGetLocalSize(y, &ny));
    PetscCheck(Ny == N && ny == n, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "SgProblemComputeEnergy: the vector has %" PetscInt_FMT " entries (%" PetscInt_FMT " here), a displacement of this problem %" PetscInt_FMT " (%" PetscInt_FMT "): use SgProblemCreateVector", Ny, ny, N, n);
  }
  PetscCall(SgElasticityEnergy(p->el, y, V));
  PetscFunctionReturn(0);
}

/* Quasi-static load stepping: the loads (body force, Neumann tractions), the Dirichlet values and the obstacle's
   translation (-obstacle_translation) times t; t = 1 is the problem as given. A solver that solved the problem before
   continues from its last solution when SgContSolve is called again (a warm start). */
PetscErrorCode SgProblemSetLoadFactor(SgProblem p, PetscReal t)
{
  PetscFunctionBeginUser;
  ValidProblem(p, 1);
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
  ValidProblem(p, 1);
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
  SgValidPointer(n, 2);
  PetscCall(SgElasticityGetDirichletSize(p->el, n));
  PetscFunctionReturn(0);
}

PetscErrorCode SgProblemGetLoadFactor(SgProblem p, PetscReal *t)
{
  PetscFunctionBeginUser;
  ValidProblem(p, 1);
  SgValidPointer(t, 2);
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
