/* mesh.c: the distributed simplex mesh: read from a mesh file (checked first) or made as the box, checked, partitioned
   and distributed. */
#include "fem/femimpl.h"
#include <petscdmplextransform.h>

/* Check on rank 0 that a mesh file can be read, so a wrong path is reported with the option that named it. */
static PetscErrorCode CheckMeshFile(MPI_Comm comm, const char fname[])
{
  PetscMPIInt rank;
  PetscInt    status = 0; /* 0 ok, 1 missing, 2 empty */

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    FILE *fp = fopen(fname, "rb");
    if (!fp) status = 1;
    else {
      if (fgetc(fp) == EOF) status = 2;
      fclose(fp);
    }
  }
  PetscCallMPI(MPI_Bcast(&status, 1, MPIU_INT, 0, comm));
  PetscCheck(status != 1, comm, PETSC_ERR_FILE_OPEN, "-dm_plex_filename: cannot open mesh file '%s'", fname);
  PetscCheck(status != 2, comm, PETSC_ERR_FILE_UNEXPECTED, "-dm_plex_filename: mesh file '%s' is empty", fname);
  PetscFunctionReturn(0);
}

/* A 2D mesh read with 3D coordinates (gmsh writes x, y, z): exact if every z is the same, so z is dropped then; a
   surface in a tilted plane (or not planar) would be solved projected onto z = 0, a wrong result: refused. */
static PetscErrorCode MeshDropConstantZ(MPI_Comm comm, const char fname[], DM dm)
{
  Vec                cl, nc;
  PetscSection       cs, ns;
  const PetscScalar *ca;
  PetscScalar       *na;
  PetscInt           vStart, vEnd;
  PetscReal          r[6] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}; /* min x,y,z and -max x,y,z */
  PetscReal          ext;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMGetCoordinatesLocal(dm, &cl));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(VecGetArrayRead(cl, &ca));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(cs, v, &off));
    for (PetscInt d = 0; d < 3; d++) {
      r[d]     = PetscMin(r[d], PetscRealPart(ca[off + d]));
      r[3 + d] = PetscMin(r[3 + d], -PetscRealPart(ca[off + d]));
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, r, 6, MPIU_REAL, MPIU_MIN, comm));
  ext = PetscMax(-r[3] - r[0], -r[4] - r[1]);
  /* equal up to round-off of the coordinates themselves (gmsh interpolates nodes inside a plane surface) */
  PetscCheck(-r[5] - r[2] <= 1e-13 * PetscMax(ext, PetscMax(PetscAbsReal(r[2]), PetscAbsReal(r[5]))), comm, PETSC_ERR_USER_INPUT,
             "-dm_plex_filename: '%s' is a 2D mesh whose z coordinates range over [%.17g, %.17g] (x over [%g, %g], y over [%g, %g]): a surface that is not in a plane z = constant is not supported (a 2D mesh must lie in a plane z = constant; rotate it into one)", fname, (double)r[2], (double)-r[5], (double)r[0], (double)-r[3], (double)r[1], (double)-r[4]);
  PetscCall(PetscInfo(dm, "2D mesh %s in the plane z = %g: z dropped\n", fname, (double)r[2]));
  PetscCall(PetscSectionCreate(PetscObjectComm((PetscObject)dm), &ns));
  PetscCall(PetscSectionSetNumFields(ns, 1));
  PetscCall(PetscSectionSetFieldComponents(ns, 0, 2));
  PetscCall(PetscSectionSetChart(ns, vStart, vEnd));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscCall(PetscSectionSetDof(ns, v, 2));
    PetscCall(PetscSectionSetFieldDof(ns, v, 0, 2));
  }
  PetscCall(PetscSectionSetUp(ns));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 2 * (vEnd - vStart), &nc));
  PetscCall(VecSetBlockSize(nc, 2));
  PetscCall(PetscObjectSetName((PetscObject)nc, "coordinates"));
  PetscCall(VecGetArray(nc, &na));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt off, noff;
    PetscCall(PetscSectionGetOffset(cs, v, &off));
    PetscCall(PetscSectionGetOffset(ns, v, &noff));
    na[noff]     = ca[off];
    na[noff + 1] = ca[off + 1];
  }
  PetscCall(VecRestoreArray(nc, &na));
  PetscCall(VecRestoreArrayRead(cl, &ca));
  PetscCall(DMSetCoordinateDim(dm, 2));
  PetscCall(DMSetCoordinateSection(dm, 2, ns));
  PetscCall(DMSetCoordinatesLocal(dm, nc));
  PetscCall(PetscSectionDestroy(&ns));
  PetscCall(VecDestroy(&nc));
  PetscFunctionReturn(0);
}

/* Read a gmsh (or other) mesh file with the file's own coordinate dimension, so that a 2D mesh with z values is seen. */
static PetscErrorCode MeshReadFile(MPI_Comm comm, const char fname[], DM *dm)
{
  PetscErrorCode ierr;
  const char    *msg      = NULL;
  char           why[512] = "";
  PetscBool      userdim;
  PetscInt       dim, cdim;

  PetscFunctionBeginUser;
  PetscCall(CheckMeshFile(comm, fname));
  /* PETSc's gmsh reader trusts the file (a bad node tag is a segmentation fault): check its structure first */
  PetscCall(SgGmshCheckFile(comm, fname));
  /* PETSc's gmsh reader keeps only the first dim coordinates unless told the space dimension; an explicit
     -dm_plex_gmsh_spacedim from the user is left alone */
  PetscCall(PetscOptionsHasName(NULL, NULL, "-dm_plex_gmsh_spacedim", &userdim));
  if (!userdim) PetscCall(PetscOptionsSetValue(NULL, "-dm_plex_gmsh_spacedim", "3"));
  /* a reader error (truncated or foreign file) is reported with the file's name instead of a bare traceback */
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = DMPlexCreateFromFile(comm, fname, "signorini", PETSC_TRUE, dm);
  PetscCall(PetscPopErrorHandler());
  if (!userdim) PetscCall(PetscOptionsClearValue(NULL, "-dm_plex_gmsh_spacedim"));
  if (ierr) {
    PetscErrorMessage(ierr, NULL, (char **)&msg);
    if (msg) PetscCall(PetscStrncpy(why, msg, sizeof(why)));
    SETERRQ(comm, PETSC_ERR_FILE_READ, "-dm_plex_filename: cannot read mesh file '%s': %s", fname, why[0] ? why : "the reader failed");
  }
  PetscCall(DMGetDimension(*dm, &dim));
  PetscCall(DMGetCoordinateDim(*dm, &cdim));
  if (dim == 2 && cdim == 3) PetscCall(MeshDropConstantZ(comm, fname, *dm));
  PetscFunctionReturn(0);
}

/* For every local vertex of mesh b (the next refinement of mesh a, dma: a's DM), the two local vertices of a it is
   the midpoint of (the same one twice: a vertex of a); the transform's options under the prefix. A vertex of b's DM
   dmb that -dm_refine_geometry moved onto the geometry (label "SgSnapped", fem/geometry.c) may lie up to a quarter of
   its edge from the midpoint. NULL in *map and
   the number of vertices that do not nest in *bad (on all ranks) if the refinement does not nest. Nested iteration's
   transfer (cont/nested.c) and the geometric multigrid's interpolations (solver/gmg.c). */
PetscErrorCode SgMeshRefinementMap(DM dma, DM dmb, const SgMesh *ma, const SgMesh *mb, const char prefix[], PetscInt **map, PetscInt *nbad)
{
  DMPlexTransform tr;
  PetscInt        eStart, eEnd, dim, bad = 0;
  PetscReal       scale   = 0;
  MPI_Comm        comm    = PetscObjectComm((PetscObject)dma);
  PetscBool      *snapped = NULL;

  PetscFunctionBeginUser;
  dim = ma->dim;
  PetscCall(PetscMalloc1(2 * mb->nv + 1, map));
  PetscCall(DMPlexGetDepthStratum(dma, 1, &eStart, &eEnd));
  for (PetscInt i = 0; i < ma->nv * dim; i++) scale = PetscMax(scale, PetscAbsReal(ma->x[i]));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &scale, 1, MPIU_REAL, MPIU_MAX, comm));
  {
    DMLabel lab = NULL;
    if (dmb) PetscCall(DMGetLabel(dmb, "SgSnapped", &lab));
    if (lab) {
      PetscCall(PetscCalloc1(mb->nv + 1, &snapped));
      for (PetscInt v = 0; v < mb->nv; v++) {
        PetscInt val;
        PetscCall(DMLabelGetValue(lab, mb->vStart + v, &val));
        snapped[v] = (PetscBool)(val == 1);
      }
    }
  }
  if (mb->nv != ma->nv + (eEnd - eStart)) bad = PetscMax(1, mb->nv);
  else {
    /* the transform DMRefine applies (DMPlex's regular refinement, or -dm_plex_transform_type) numbers the new points */
    PetscCall(DMPlexTransformCreate(comm, &tr));
    PetscCall(PetscObjectSetOptionsPrefix((PetscObject)tr, prefix));
    PetscCall(DMPlexTransformSetDM(tr, dma));
    PetscCall(DMPlexTransformSetFromOptions(tr));
    PetscCall(DMPlexTransformSetUp(tr));
    for (PetscInt v = 0; v < mb->nv; v++) {
      DMPolytopeType  ct, ctn;
      PetscInt        p, r, v0 = -1, v1 = -1;
      const PetscInt *cone;
      PetscCall(DMPlexTransformGetSourcePoint(tr, mb->vStart + v, &ct, &ctn, &p, &r));
      if (ct == DM_POLYTOPE_POINT) v0 = v1 = p - ma->vStart;
      else if (ct == DM_POLYTOPE_SEGMENT) {
        PetscCall(DMPlexGetCone(dma, p, &cone));
        v0 = cone[0] - ma->vStart;
        v1 = cone[1] - ma->vStart;
      }
      if (v0 < 0 || v0 >= ma->nv || v1 < 0 || v1 >= ma->nv) {
        bad++;
        v0 = v1 = 0;
      } else if (snapped && snapped[v]) {
        PetscReal r = 0, h = 0;
        for (PetscInt d = 0; d < dim; d++) {
          r += PetscSqr(mb->x[v * dim + d] - 0.5 * (ma->x[v0 * dim + d] + ma->x[v1 * dim + d]));
          h += PetscSqr(ma->x[v0 * dim + d] - ma->x[v1 * dim + d]);
        }
        if (!(PetscSqrtReal(r) <= 0.25 * PetscSqrtReal(h) + 1e-10 * scale)) bad++;
      } else
        for (PetscInt d = 0; d < dim; d++)
          if (!(PetscAbsReal(mb->x[v * dim + d] - 0.5 * (ma->x[v0 * dim + d] + ma->x[v1 * dim + d])) <= 1e-10 * scale)) {
            bad++;
            break;
          }
      (*map)[2 * v]     = v0;
      (*map)[2 * v + 1] = v1;
    }
    PetscCall(DMPlexTransformDestroy(&tr));
  }
  PetscCall(PetscFree(snapped));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_SUM, comm));
  if (bad) PetscCall(PetscFree(*map));
  *nbad = bad;
  PetscFunctionReturn(0);
}

/* The distributed mesh checked against the geometry (-dm_refine_geometry), then refined n times (not kept), each
   refinement's boundary vertices moved onto it. */
static PetscErrorCode MeshRefineOnGeometry(SgGeometry geo, PetscInt n, DM *dm)
{
  PetscFunctionBeginUser;
  PetscCall(SgGeometryCheck(geo, *dm, NULL));
  for (PetscInt r = 0; r < n; r++) {
    DM rdm;
    PetscCall(DMRefine(*dm, PetscObjectComm((PetscObject)*dm), &rdm));
    PetscCheck(rdm, PetscObjectComm((PetscObject)*dm), PETSC_ERR_PLIB, "-dm_refine_geometry: DMRefine made no mesh");
    PetscCall(SgGeometrySnap(geo, *dm, rdm));
    PetscCall(DMDestroy(dm));
    *dm = rdm;
    PetscCall(DMPlexSetRefinementUniform(*dm, PETSC_TRUE));
  }
  PetscFunctionReturn(0);
}

/* Nested iteration (-cont_nested L under the mesh's prefix, with -dm_refine N >= L; cont/nested.c): the mesh refined
   N - L times by DMSetFromOptions (read or boxed, distributed), then L times more by DMRefine as DMSetFromOptions does
   (the same regular refinement of the same distributed mesh: the finest mesh is the one -dm_refine N gives). Each
   coarser mesh is kept with the finest, composed as "SgNestedLevel<k>" (the mesh refined k times fewer), so that the
   coarse levels of the solve have the fine mesh's distribution (a second partitioning of the file, by PT-Scotch on
   several ranks, can differ). Returns PETSC_FALSE in *done (nothing done) unless both options ask for it.
   The geometric multigrid (-ssn_pc_truncated_mg_interp geometric, solver/gmg.c) keeps every level (L = N); for it
   each level's DM holds its own coarser ones the same way, and the coarsest (unrefined) one is marked
   "SgNestedBase". Without -cont_nested, a 3D mesh refined with -dm_refine N >= 1 for a frictionless contact boundary
   (-contact_ids or -contact_label, one body or two, no -friction_type but none) keeps every level
   (L = N): nested iteration's default (SgContNestedDefault); so does a 2D one with friction, or where the linear solver may be iterative (2 x the
   fine mesh's vertices above the default's direct limit: 20000 on several ranks or -cont_direct_max_unknowns; or a
   Krylov -ksp_type): without friction SgContNestedDefault solves on them only if it is, a direct solve leaves them
   unused. Two bodies (-contact_master_ids) as one. -cont_nested 0 keeps none.
   With a geometry (geo, -dm_refine_geometry; fem/geometry.c) every refinement after distribution is made here, kept or
   not, each followed by SgGeometrySnap (DMSetFromOptions distributes only); the unrefined mesh is checked against it.
   Refinements before distribution (-dm_refine_pre) and -dm_refine_hierarchy are PETSc's and not snapped. */
static PetscErrorCode MeshRefineNested(const char prefix[], SgGeometry geo, DM *dm, PetscBool *done)
{
  PetscInt          nest = 0, nref = 0, interp = 0;
  PetscBool         nset, rset, gset;
  char              opt[PETSC_MAX_PATH_LEN], was[32], now[32];
  DM               *lv;
  const char *const interps[] = {"amg", "geometric"};

  PetscFunctionBeginUser;
  *done = PETSC_FALSE;
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL)); /* a malformed value is reported by its reader */
  if (PetscOptionsGetInt(NULL, prefix, "-cont_nested", &nest, &nset)) nset = PETSC_FALSE;
  if (PetscOptionsGetInt(NULL, prefix, "-dm_refine", &nref, &rset)) rset = PETSC_FALSE;
  if (PetscOptionsGetEList(NULL, prefix, "-ssn_pc_truncated_mg_interp", interps, 2, &interp, &gset)) gset = PETSC_FALSE;
  PetscCall(PetscPopErrorHandler());
  if (!nset && rset && nref >= 1) { /* the default of -cont_nested (cont/nested.c): every level, a contact boundary, 3D,
                                        and in 2D with friction or where the linear solver may be iterative
                                        (SgContNestedDefault uses the levels only if it is) */
    PetscBool ids, label, fric3d = PETSC_FALSE, iter2d = PETSC_FALSE;
    PetscInt  dim;
    PetscCall(DMGetDimension(*dm, &dim));
    if (dim == 2) { /* the unknowns of the refined mesh at most 2 V_N (V_N its vertices, from the counts of the given
                       mesh: a regular refinement adds a vertex per edge, splits an edge in two and a triangle in four,
                       with three new edges) against the default's direct limit (solver/linear.c) */
      PetscMPIInt size;
      char        ksp[64] = "";
      PetscBool   kset, mset;
      PetscInt    maxdirect = PETSC_MAX_INT, pS, pE, n[3];
      PetscReal   V, E, F;
      PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)*dm), &size));
      if (size > 1) maxdirect = 20000;
      PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
      { /* two bodies in the pair's dual-mortar basis: solver/linear.c's limit of a pair (with friction the levels are
           kept anyway, below) */
        PetscBool pair = PETSC_FALSE, tx, limited = PETSC_FALSE;
        if (PetscOptionsHasName(NULL, prefix, "-contact_master_ids", &pair) || SgOptionsPairDirectLimit2D(prefix, &tx, &limited)) pair = PETSC_FALSE;
        if (pair && limited) maxdirect = SG_PAIR_DIRECT_MAX_2D;
      }
      if (PetscOptionsGetInt(NULL, prefix, "-cont_direct_max_unknowns", &maxdirect, &mset)) mset = PETSC_FALSE;
      PetscCall(PetscPopErrorHandler());
      PetscCall(PetscOptionsGetString(NULL, prefix, "-ksp_type", ksp, sizeof(ksp), &kset));
      for (PetscInt d = 0; d < 3; d++) {
        PetscCall(DMPlexGetDepthStratum(*dm, d, &pS, &pE));
        n[d] = pE - pS;
      }
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, n, 3, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)*dm)));
      V = n[0], E = n[1], F = n[2];
      for (PetscInt r = 0; r < nref; r++) {
        V += E;
        E = 2 * E + 3 * F;
        F *= 4;
      }
      iter2d = (PetscBool)(2 * V > maxdirect || (kset && strcmp(ksp, "preonly")));
    }
    PetscCall(PetscOptionsHasName(NULL, prefix, "-contact_ids", &ids));
    PetscCall(PetscOptionsHasName(NULL, prefix, "-contact_label", &label));
    { /* with friction in 2D with either solver (no condensation there, every SSN step is a factorization of K); not
         in 3D (Coulomb with BiCGStab + BoomerAMG: 2.9x the CPU time from the nested start, bench/nested.md) */
      char      law[64] = "";
      PetscBool fset;
      PetscCall(PetscOptionsGetString(NULL, prefix, "-friction_type", law, sizeof(law), &fset));
      if (fset && strcmp(law, "none")) {
        if (dim == 2) iter2d = PETSC_TRUE;
        else fric3d = PETSC_TRUE;
      }
    }
    if ((dim == 3 || iter2d) && (ids || label) && !fric3d) {
      nset = PETSC_TRUE;
      nest = nref;
    }
  }
  if (!nset || nest < 1 || nest > nref) nest = 0;
  if (gset && interp == 1 && rset && nref >= 1) nest = nref;
  if (!rset || nref < 1 || (nest < 1 && !geo)) PetscFunctionReturn(0);
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%sdm_refine", prefix ? prefix : ""));
  PetscCall(PetscSNPrintf(was, sizeof(was), "%" PetscInt_FMT, nref));
  PetscCall(PetscSNPrintf(now, sizeof(now), "%" PetscInt_FMT, geo ? 0 : nref - nest));
  PetscCall(PetscOptionsSetValue(NULL, opt, now));
  {
    PetscErrorCode ierr = DMSetFromOptions(*dm);
    PetscCall(PetscOptionsSetValue(NULL, opt, was));
    PetscCall(ierr);
  }
  PetscCall(DMPlexSetRefinementUniform(*dm, PETSC_TRUE));
  if (geo) PetscCall(MeshRefineOnGeometry(geo, nref - nest, dm));
  if (nest < 1) { /* the refinements on the geometry, none kept */
    PetscCall(PetscObjectSetName((PetscObject)*dm, "mesh"));
    PetscCall(PetscObjectSetOptionsPrefix((PetscObject)*dm, prefix));
    *done = PETSC_TRUE;
    PetscFunctionReturn(0);
  }
  PetscCall(PetscMalloc1(nest, &lv));
  for (PetscInt r = 0; r < nest; r++) {
    DM rdm;
    lv[r] = *dm;
    PetscCall(DMRefine(lv[r], PetscObjectComm((PetscObject)lv[r]), &rdm));
    PetscCheck(rdm, PetscObjectComm((PetscObject)lv[r]), PETSC_ERR_PLIB, "-cont_nested: DMRefine made no mesh");
    if (geo) PetscCall(SgGeometrySnap(geo, lv[r], rdm));
    *dm = rdm;
  }
  PetscCall(PetscObjectSetName((PetscObject)*dm, "mesh"));
  PetscCall(PetscObjectSetOptionsPrefix((PetscObject)*dm, prefix));
  if (nref - nest == 0) { /* the unrefined mesh: the geometric multigrid's mark of the bottom of the hierarchy */
    PetscContainer mark;
    PetscCall(PetscContainerCreate(PetscObjectComm((PetscObject)lv[0]), &mark));
    PetscCall(PetscObjectCompose((PetscObject)lv[0], "SgNestedBase", (PetscObject)mark));
    PetscCall(PetscContainerDestroy(&mark));
  }
  for (PetscInt r = 0; r < nest; r++) {
    char name[64];
    PetscCall(PetscSNPrintf(name, sizeof(name), "SgNestedLevel%" PetscInt_FMT, nest - r));
    PetscCall(PetscObjectCompose((PetscObject)*dm, name, (PetscObject)lv[r]));
    for (PetscInt q = 0; q < r; q++) { /* its coarser levels, for a coarse level's own multigrid */
      PetscCall(PetscSNPrintf(name, sizeof(name), "SgNestedLevel%" PetscInt_FMT, r - q));
      PetscCall(PetscObjectCompose((PetscObject)lv[r], name, (PetscObject)lv[q]));
    }
  }
  for (PetscInt r = 0; r < nest; r++) PetscCall(DMDestroy(&lv[r])); /* the finer meshes hold them */
  PetscCall(PetscFree(lv));
  *done = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* MeshPartitionPairs: the boundary faces with the given values of the label, their centroids (x, 3 a face) and cells
   (cell, numbered from cS) */
static PetscErrorCode PairFaces(DM dm, DMLabel label, const PetscInt ids[], PetscInt nid, PetscInt cS, PetscInt fS, PetscInt fE, PetscInt cell[], PetscReal x[], PetscInt *cnt)
{
  PetscInt dim;

  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  *cnt = 0;
  for (PetscInt k = 0; k < nid; k++) {
    IS              is;
    PetscInt        np;
    const PetscInt *p;
    PetscCall(DMLabelGetStratumIS(label, ids[k], &is));
    if (!is) continue;
    PetscCall(ISGetLocalSize(is, &np));
    PetscCall(ISGetIndices(is, &p));
    for (PetscInt q = 0; q < np; q++) {
      PetscInt        nsup;
      const PetscInt *sup;
      PetscReal       v, cen[3] = {0, 0, 0};
      if (p[q] < fS || p[q] >= fE) continue;
      PetscCall(DMPlexGetSupportSize(dm, p[q], &nsup));
      PetscCall(DMPlexGetSupport(dm, p[q], &sup));
      if (nsup < 1) continue;
      PetscCall(DMPlexComputeCellGeometryFVM(dm, p[q], &v, cen, NULL));
      cell[*cnt] = sup[0] - cS;
      for (PetscInt d = 0; d < 3; d++) x[3 * *cnt + d] = d < dim ? cen[d] : 0;
      (*cnt)++;
    }
    PetscCall(ISRestoreIndices(is, &p));
    PetscCall(ISDestroy(&is));
  }
  PetscFunctionReturn(0);
}

/* MeshPartitionPairs: each slave face's cell (sc) into the group of the nearest master face's cell (mc), by the face
   centroids; the master faces sorted along x and scanned outwards from the slave face's x */
static PetscErrorCode PairNearest(PetscInt nsf, const PetscInt sc[], const PetscReal sx[], PetscInt nmf, const PetscInt mc[], const PetscReal mx[], PetscInt grp[], PetscReal dist[])
{
  PetscInt  *ord;
  PetscReal *key;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(nmf, &ord, nmf, &key));
  for (PetscInt j = 0; j < nmf; j++) ord[j] = j, key[j] = mx[3 * j];
  PetscCall(PetscSortRealWithArrayInt(nmf, key, ord));
  for (PetscInt i = 0; i < nsf; i++) {
    PetscInt  lo = 0, hi = nmf, best = -1;
    PetscReal bd = PETSC_MAX_REAL;
    while (lo < hi) { /* the first key >= x */
      PetscInt mid = (lo + hi) / 2;
      if (key[mid] < sx[3 * i]) lo = mid + 1;
      else hi = mid;
    }
    for (PetscInt dir = 0; dir < 2; dir++)
      for (PetscInt j = dir ? lo - 1 : lo; j >= 0 && j < nmf; j += dir ? -1 : 1) {
        PetscReal dx = key[j] - sx[3 * i], d2 = 0;
        if (dx * dx >= bd) break;
        for (PetscInt d = 0; d < 3; d++) d2 += PetscSqr(mx[3 * ord[j] + d] - sx[3 * i + d]);
        if (d2 < bd) bd = d2, best = ord[j];
      }
    if (best >= 0 && grp[sc[i]] == sc[i]) grp[sc[i]] = mc[best];
    dist[i] = best >= 0 ? PetscSqrtReal(bd) : PETSC_MAX_REAL;
  }
  PetscCall(PetscFree2(ord, key));
  PetscFunctionReturn(0);
}

/* The partitioner's vertex weights from real ones (MeshPartitionPairs' groups: their refined vertices, in units of
   1/120 of a vertex, pass 2^31 from -dm_refine 9 on for a tetrahedron's share alone, and their sum, which the vertex
   section's offsets and PT-Scotch hold in PetscInt, from about 1.8e7 refined vertices on): the integers w[i] rounded
   when their sum stays below a quarter of PETSC_MAX_INT (then exactly those integers), otherwise scaled down by one
   factor for all so that it does; each at least 1 (PT-Scotch takes no zero weight). Public for the unit test. */
PetscErrorCode SgMeshPartitionWeights(PetscInt n, const PetscReal w[], PetscInt iw[])
{
  const PetscReal cap = 0.25 * (PetscReal)PETSC_MAX_INT;
  PetscReal       tot = 0, f = 1;

  PetscFunctionBeginUser;
  PetscCheck(n >= 0 && (PetscReal)n < 0.5 * cap, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "-contact_pair_partition: %" PetscInt_FMT " partition vertices, more than the weights' range %g holds", n, (double)(0.5 * cap));
  for (PetscInt i = 0; i < n; i++) {
    PetscCheck(w[i] >= 0 && PetscIsNormalReal(w[i] + 1), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "-contact_pair_partition: partition weight %g of vertex %" PetscInt_FMT " is not a finite number >= 0", (double)w[i], i);
    tot += PetscFloorReal(w[i] + 0.5);
  }
  if (tot + n > cap) f = (cap - n) / tot; /* the rounding and the minimum 1 add at most n */
  for (PetscInt i = 0; i < n; i++) iw[i] = (PetscInt)PetscMax(1, PetscFloorReal(f * w[i] + 0.5));
  PetscFunctionReturn(0);
}

/* MeshPartitionPairs: each cell's weight for the partition, in units of 1/120 of a vertex of the mesh refined -dm_refine
   R times: its share of that mesh's vertices (regular refinement: an edge gets 2^R - 1 new vertices, a triangle
   (2^R - 1)(2^R - 2)/2 inside, a tetrahedron (2^R - 1)(2^R - 2)(2^R - 3)/6; each point's shared equally by the cells
   around it), and for each slave face within the pairing distance (dist: to the nearest master face's centroid;
   -contact_pair_distance, by default a tenth of the mesh's diameter, as contact_pair.c) SG_PAIR_ROW_WEIGHT vertices
   more for each of its refined vertices ((2^R)^2 / 2 in 3D, 2^R in 2D): the rows of the pair's dual-mortar basis at
   the slave vertices opposite the master and at their master vertices are about four times as long as a body's
   (186 against 45 nonzeros at 40,866 unknowns, the sphere on a block: about 3 vertices more for each such vertex of
   either side); 6 halved the 2 ranks' nonzero imbalance there, 14 balanced it, 12 is taken (bench/results.md, pair8) */
#define SG_PAIR_ROW_WEIGHT 12.0

static PetscErrorCode PairCellWeights(DM dm, const char prefix[], PetscInt cS, PetscInt n, PetscInt nsf, const PetscInt sc[], const PetscReal dist[], PetscReal cw[])
{
  PetscInt  R = 0, pS, pE, *star, dim, depth;
  PetscReal k, per[4], dmax = 0;
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(DMPlexGetDepth(dm, &depth));
  if (depth != dim) { /* not interpolated (no edges, faces): the cells' counts */
    for (PetscInt c = 0; c < n; c++) cw[c] = 1;
    PetscFunctionReturn(0);
  }
  PetscCall(PetscOptionsGetInt(NULL, prefix, "-dm_refine", &R, NULL));
  k      = PetscPowReal(2.0, (PetscReal)PetscMax(0, PetscMin(R, 30))); /* reals: 120 k^3 / 6 passes 2^31 at k = 2^9 */
  per[0] = 1;
  per[1] = k - 1;
  per[2] = (k - 1) * (k - 2) / 2;
  per[3] = (k - 1) * (k - 2) * (k - 3) / 6;
  PetscCall(DMPlexGetChart(dm, &pS, &pE));
  PetscCall(PetscCalloc1(pE - pS + 1, &star));
  for (PetscInt pass = 0; pass < 2; pass++)
    for (PetscInt c = 0; c < n; c++) {
      PetscInt *cl = NULL, ncl;
      PetscReal w  = 0;
      PetscCall(DMPlexGetTransitiveClosure(dm, cS + c, PETSC_TRUE, &ncl, &cl));
      for (PetscInt q = 0; q < ncl; q++) {
        const PetscInt p = cl[2 * q] - pS;
        PetscInt       d;
        if (!pass) {
          star[p]++;
          continue;
        }
        PetscCall(DMPlexGetPointDepth(dm, cl[2 * q], &d));
        w += per[PetscMin(d, 3)] / star[p];
      }
      PetscCall(DMPlexRestoreTransitiveClosure(dm, cS + c, PETSC_TRUE, &ncl, &cl));
      if (pass) cw[c] = PetscMax(1, PetscFloorReal(120 * w + 0.5));
    }
  PetscCall(PetscFree(star));
  PetscCall(PetscOptionsGetReal(NULL, prefix, "-contact_pair_distance", &dmax, &set));
  if (!set) { /* a tenth of the mesh's diameter */
    Vec                coords;
    const PetscScalar *x;
    PetscInt           nx;
    PetscReal          lo[3] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, hi[3] = {PETSC_MIN_REAL, PETSC_MIN_REAL, PETSC_MIN_REAL}, d2 = 0;
    PetscCall(DMGetCoordinatesLocal(dm, &coords));
    PetscCall(VecGetLocalSize(coords, &nx));
    PetscCall(VecGetArrayRead(coords, &x));
    for (PetscInt i = 0; i < nx; i++) lo[i % dim] = PetscMin(lo[i % dim], PetscRealPart(x[i])), hi[i % dim] = PetscMax(hi[i % dim], PetscRealPart(x[i]));
    PetscCall(VecRestoreArrayRead(coords, &x));
    for (PetscInt d = 0; d < dim; d++) d2 += nx ? PetscSqr(hi[d] - lo[d]) : 0;
    dmax = 0.1 * PetscSqrtReal(d2);
  }
  for (PetscInt i = 0; i < nsf; i++)
    if (dist[i] <= dmax) cw[sc[i]] += PetscFloorReal(120 * SG_PAIR_ROW_WEIGHT * (dim == 3 ? k * k / 2 : k) + 0.5);
  PetscFunctionReturn(0);
}

/* Two bodies (-contact_master_ids) on several ranks: the partitioner's cell graph has no edge between the bodies, so
   PT-Scotch put the slave and master sides of the pair on different ranks (the sphere on a block: 8,128 of 8,384 slave
   facets on one rank), and the rows of the pair's dual-mortar basis, which couple a slave vertex to its master
   vertices, were coupled mostly across ranks: there the several-rank smoother (l1 Gauss-Seidel, solver/tmg.c) is
   weakest (bench/results.md, pair7: 37 CG against one rank's 22 at 40,866 unknowns). Here, on the undistributed mesh,
   each cell with a slave face is grouped with the cell of the master face nearest to it (face centroids), the groups
   partitioned as vertices of the contracted cell graph weighted by their cell counts (PT-Scotch, as before), and the
   partition handed to the DM's partitioner (shell). -contact_pair_partition false keeps PT-Scotch's own. */
static PetscErrorCode MeshPartitionPairs(MPI_Comm comm, const char prefix[], DM dm, PetscPartitioner part)
{
  PetscMPIInt      size;
  PetscInt         sids[64], mids[64], ns = 64, nm = 64, cS, cE, n, nwith, fS, fE;
  PetscBool        sset, mset, on = PETSC_TRUE, set, bycells = PETSC_FALSE;
  char             lname[256] = "Face Sets";
  DMLabel          label;
  PetscInt        *grp, *gid, ng = 0, nv, *off = NULL, *adj = NULL, *goff, *gadj, ne = 0, *mark, *sizes, *pts;
  PetscReal       *sx, *mx;
  PetscInt        *sc, *mc, nsf = 0, nmf = 0, *iw;
  PetscReal       *sd, *cw, *gw;
  IS               gnum, partition;
  PetscSection     vsec, psec;
  PetscPartitioner gp;
  const PetscInt  *pv;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscOptionsBegin(comm, prefix, "Two bodies on several ranks", NULL);
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-contact_pair_partition", "Two bodies (-contact_master_ids) on several ranks: partition the mesh with each cell of a slave face grouped with the cell of the nearest master face (the pair's rows on one rank), instead of PT-Scotch's partition of the cell graph alone", &on, &set));
  PetscCall(SgOptionsBoolValue(PetscOptionsObject, "-contact_pair_partition_cells", "-contact_pair_partition: weigh the groups by their cells alone, not by the vertices of the refined mesh (-dm_refine) they hold and the denser rows of the pair's contact zone", &bycells, NULL));
  PetscOptionsEnd();
  if (size < 2) PetscFunctionReturn(0); /* one rank: nothing to partition (bit-identical runs) */
  PetscCall(PetscOptionsGetIntArray(NULL, prefix, "-contact_master_ids", mids, &nm, &mset));
  PetscCall(PetscOptionsGetIntArray(NULL, prefix, "-contact_ids", sids, &ns, &sset));
  if (!mset || !sset || nm < 1 || ns < 1) PetscFunctionReturn(0);
  if (!on) PetscFunctionReturn(0);
  PetscCall(PetscOptionsGetString(NULL, prefix, "-contact_label", lname, sizeof(lname), &set));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cS, &cE));
  n     = cE - cS;
  nwith = n > 0 ? 1 : 0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nwith, 1, MPIU_INT, MPI_SUM, comm));
  if (nwith != 1) PetscFunctionReturn(0); /* already distributed (or empty): PT-Scotch's partition as given */
  PetscCall(DMGetLabel(dm, lname, &label));
  PetscCall(DMPlexGetHeightStratum(dm, 1, &fS, &fE));
  /* the slave and master faces' centroids and cells (on the rank with the mesh) */
  PetscCall(PetscMalloc4(n > 0 ? fE - fS : 1, &sc, n > 0 ? fE - fS : 1, &mc, n > 0 ? 3 * (fE - fS) : 1, &sx, n > 0 ? 3 * (fE - fS) : 1, &mx));
  if (n > 0 && label) {
    PetscCall(PairFaces(dm, label, sids, ns, cS, fS, fE, sc, sx, &nsf));
    PetscCall(PairFaces(dm, label, mids, nm, cS, fS, fE, mc, mx, &nmf));
  }
  /* groups: a slave face's cell joins the group of the nearest master face's cell (each cell in one group) */
  PetscCall(PetscMalloc2(n + 1, &grp, n + 1, &gid));
  for (PetscInt c = 0; c < n; c++) grp[c] = c;
  PetscCall(PetscMalloc2(n + 1, &cw, nsf + 1, &sd));
  for (PetscInt i = 0; i < nsf; i++) sd[i] = PETSC_MAX_REAL;
  if (nsf && nmf) PetscCall(PairNearest(nsf, sc, sx, nmf, mc, mx, grp, sd));
  if (!bycells) PetscCall(PairCellWeights(dm, prefix, cS, n, nsf, sc, sd, cw));
  PetscCall(PetscFree4(sc, mc, sx, mx));
  for (PetscInt c = 0; c < n; c++) /* a cell with both sides' faces (one body's): in its own group */
    if (grp[grp[c]] != grp[c]) grp[c] = c;
  for (PetscInt c = 0; c < n; c++) gid[c] = -1;
  for (PetscInt c = 0; c < n; c++) /* the group's number: its master cell's (a cell is a slave cell or a group's head) */
    if (grp[c] == c) gid[c] = ng++;
  for (PetscInt c = 0; c < n; c++) gid[c] = gid[grp[c]];
  /* the contracted graph: groups adjacent where two of their cells share a face */
  PetscCall(DMPlexCreatePartitionerGraph(dm, 0, &nv, &off, &adj, &gnum));
  PetscCheck(nv == n, PETSC_COMM_SELF, PETSC_ERR_PLIB, "-contact_pair_partition: the cell graph has %" PetscInt_FMT " vertices for %" PetscInt_FMT " cells", nv, n);
  PetscCall(PetscCalloc3(ng + 1, &goff, n > 0 ? off[n] + 1 : 1, &gadj, ng + 1, &mark));
  {
    PetscInt *first, *next; /* the groups' cells as lists */
    PetscCall(PetscMalloc2(ng + 1, &first, n + 1, &next));
    for (PetscInt g = 0; g < ng; g++) first[g] = -1, mark[g] = -1;
    for (PetscInt c = n - 1; c >= 0; c--) next[c] = first[gid[c]], first[gid[c]] = c;
    for (PetscInt g = 0; g < ng; g++) {
      goff[g] = ne;
      for (PetscInt c = first[g]; c >= 0; c = next[c])
        for (PetscInt k = off[c]; k < off[c + 1]; k++) {
          const PetscInt h = gid[adj[k]];
          if (h != g && mark[h] != g) mark[h] = g, gadj[ne++] = h;
        }
      PetscCall(PetscSortInt(ne - goff[g], gadj + goff[g]));
    }
    goff[ng] = ne;
    PetscCall(PetscMalloc2(ng + 1, &gw, ng + 1, &iw));
    for (PetscInt g = 0; g < ng; g++) {
      gw[g] = 0;
      for (PetscInt c = first[g]; c >= 0; c = next[c]) gw[g] += bycells ? 1 : cw[c];
    }
    PetscCall(SgMeshPartitionWeights(ng, gw, iw));
    PetscCall(PetscSectionCreate(PETSC_COMM_SELF, &vsec));
    PetscCall(PetscSectionSetChart(vsec, 0, ng));
    for (PetscInt g = 0; g < ng; g++) PetscCall(PetscSectionSetDof(vsec, g, iw[g]));
    PetscCall(PetscSectionSetUp(vsec));
    PetscCall(PetscFree2(gw, iw));
    PetscCall(PetscFree2(first, next));
  }
  PetscCall(PetscFree(off));
  PetscCall(PetscFree(adj));
  PetscCall(ISDestroy(&gnum));
  /* PT-Scotch on the groups, then each cell in its group's part */
  PetscCall(PetscPartitionerCreate(comm, &gp));
  PetscCall(PetscPartitionerSetType(gp, PETSCPARTITIONERPTSCOTCH));
  PetscCall(PetscSectionCreate(comm, &psec));
  {
    PetscInt start[1] = {0};
    PetscCall(PetscPartitionerPartition(gp, size, ng, ng ? goff : start, gadj, vsec, NULL, psec, &partition));
  }
  PetscCall(PetscMalloc2(size, &sizes, n + 1, &pts));
  PetscCall(ISGetIndices(partition, &pv));
  {
    PetscInt *gpart, k = 0;
    PetscCall(PetscMalloc1(ng + 1, &gpart));
    for (PetscInt r = 0; r < size; r++) {
      PetscInt dof, o;
      PetscCall(PetscSectionGetDof(psec, r, &dof));
      PetscCall(PetscSectionGetOffset(psec, r, &o));
      for (PetscInt q = 0; q < dof; q++) gpart[pv[o + q]] = r;
    }
    for (PetscInt r = 0; r < size; r++) {
      sizes[r] = 0;
      for (PetscInt c = 0; c < n; c++)
        if (gpart[gid[c]] == r) pts[k++] = c, sizes[r]++;
    }
    PetscCall(PetscFree(gpart));
  }
  PetscCall(ISRestoreIndices(partition, &pv));
  PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERSHELL));
  PetscCall(PetscPartitionerShellSetPartition(part, size, sizes, pts));
  PetscCall(PetscFree2(sizes, pts));
  PetscCall(ISDestroy(&partition));
  PetscCall(PetscSectionDestroy(&psec));
  PetscCall(PetscSectionDestroy(&vsec));
  PetscCall(PetscPartitionerDestroy(&gp));
  PetscCall(PetscFree3(goff, gadj, mark));
  PetscCall(PetscFree2(cw, sd));
  PetscCall(PetscFree2(grp, gid));
  PetscFunctionReturn(0);
}

/* Create the distributed simplex mesh from a gmsh file (-dm_plex_filename) or the structured box (-box_*), options
   under the prefix. */
PetscErrorCode SgMeshCreateDM(MPI_Comm comm, const char prefix[], DM *dm)
{
  char             fname[PETSC_MAX_PATH_LEN] = "";
  PetscBool        file;
  SgBox            box;
  PetscPartitioner part;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(SG_MeshSetUp, 0, 0, 0, 0));
  PetscCall(PetscOptionsGetString(NULL, prefix, "-dm_plex_filename", fname, sizeof(fname), &file));
  PetscCheck(!file || fname[0], comm, PETSC_ERR_USER_INPUT, "-dm_plex_filename is given without a value");
  PetscCall(SgBoxFromOptions(comm, prefix, &box));
  if (file) PetscCall(MeshReadFile(comm, fname, dm));
  else PetscCall(SgBoxCreateDM(comm, &box, dm));
  PetscCall(PetscObjectSetName((PetscObject)*dm, "mesh"));
  PetscCall(PetscObjectSetOptionsPrefix((PetscObject)*dm, prefix));
  /* PT-Scotch unless the user picks another partitioner; DMSetFromOptions() distributes and refines. Scotch 7 runs
     its partitioning in as many threads as the machine has cores, and the threads' order changes the partition from run
     to run (Example 2 at 19,371 unknowns on 2 ranks: 3,647 or 3,641 or 3,678 ... vertices on rank 0, and 24-41 CG
     iterations for the same answer). One thread, unless the user asks otherwise, makes a run on several ranks
     repeatable; the partitioning is a small part of the set-up. */
  if (!getenv("SCOTCH_PTHREAD_NUMBER")) PetscCheck(!setenv("SCOTCH_PTHREAD_NUMBER", "1", 0), comm, PETSC_ERR_SYS, "setenv(SCOTCH_PTHREAD_NUMBER) failed");
  PetscCall(DMPlexGetPartitioner(*dm, &part));
  PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERPTSCOTCH));
  PetscCall(SgMeshCheckDM(comm, file ? fname : "(box)", *dm));
  PetscCall(MeshPartitionPairs(comm, prefix, *dm, part));
  {
    PetscBool  nested;
    SgGeometry geo                       = NULL;
    char       gfile[PETSC_MAX_PATH_LEN] = "";
    PetscBool  gset                      = PETSC_FALSE;
    PetscOptionsBegin(comm, prefix, "Refined boundary on the geometry", NULL);
    PetscCall(SgOptionsFileName(PetscOptionsObject, "-dm_refine_geometry", "CAD file (.geo, .step, .brep) of the mesh: after each refinement (-dm_refine), the vertices of the boundary faces whose \"Face Sets\" value is a physical group of the file move to the closest point of its surfaces (2D: curves)", gfile, sizeof(gfile), &gset));
    PetscOptionsEnd();
    PetscCheck(!gset || gfile[0], comm, PETSC_ERR_USER_INPUT, "-%sdm_refine_geometry is given without a file", prefix ? prefix : "");
    if (gset) PetscCall(SgGeometryCreate(*dm, prefix, gfile, &geo));
    PetscCall(MeshRefineNested(prefix, geo, dm, &nested));
    if (!nested) PetscCall(DMSetFromOptions(*dm));
    if (!nested && geo) PetscCall(SgGeometryCheck(geo, *dm, NULL)); /* not refined (-dm_refine 0) */
    PetscCall(SgGeometryDestroy(&geo));
  }
  {
    /* the assembly and the energy visit every local cell once: cells shared by an overlap would count twice */
    PetscInt ov;
    PetscCall(DMPlexGetOverlap(*dm, &ov));
    PetscCheck(ov == 0, comm, PETSC_ERR_USER_INPUT, "-dm_distribute_overlap %" PetscInt_FMT ": an overlapping distribution is not supported (cells on several ranks would be assembled more than once); use 0", ov);
  }
  PetscCall(DMViewFromOptions(*dm, NULL, "-dm_view"));
  PetscCall(PetscLogEventEnd(SG_MeshSetUp, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* A mesh we can use: 2D triangles or 3D tetrahedra, coordinates of the mesh's dimension, no overlap (the caller's DM
   is checked by this too; name: how to call it in messages). */
PetscErrorCode SgMeshCheckDM(MPI_Comm comm, const char name[], DM dm)
{
  PetscInt dim, cdim, cStart, cEnd, ncells, ov;

  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(DMGetCoordinateDim(dm, &cdim));
  PetscCheck(dim == 2 || dim == 3, comm, PETSC_ERR_USER_INPUT, "mesh %s has dimension %" PetscInt_FMT ": only 2D and 3D meshes are supported", name, dim);
  PetscCheck(cdim == dim, comm, PETSC_ERR_USER_INPUT, "mesh %s: coordinate dimension %" PetscInt_FMT " differs from the topological dimension %" PetscInt_FMT, name, cdim, dim);
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  ncells = cEnd - cStart;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ncells, 1, MPIU_INT, MPI_SUM, comm));
  PetscCheck(ncells > 0, comm, PETSC_ERR_USER_INPUT, "mesh %s has no cells", name);
  if (cEnd > cStart) {
    DMPolytopeType ct;
    PetscCall(DMPlexGetCellType(dm, cStart, &ct));
    PetscCheck(ct == (dim == 2 ? DM_POLYTOPE_TRIANGLE : DM_POLYTOPE_TETRAHEDRON), PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "mesh %s: cells are %s, P1 elasticity needs %s", name, DMPolytopeTypes[ct], dim == 2 ? "triangles" : "tetrahedra");
  }
  PetscCall(DMPlexGetOverlap(dm, &ov));
  PetscCheck(ov == 0, comm, PETSC_ERR_USER_INPUT, "mesh %s: an overlapping distribution (overlap %" PetscInt_FMT ") is not supported (cells on several ranks would be assembled more than once); use 0", name, ov);
  PetscFunctionReturn(0);
}
