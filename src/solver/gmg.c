/* gmg.c: geometric multigrid on the mesh hierarchy (-ssn_pc_truncated_mg_interp geometric, issue 27): the
   interpolations of the truncated multigrid (tmg.c) taken from the refinement hierarchy of the mesh instead of an AMG.
   The mesh refined N times after distribution (-dm_refine N) keeps its coarser meshes (fem/mesh.c, "SgNestedLevel<k>",
   the same distribution); between two levels a fine vertex is a coarse vertex or the midpoint of a coarse edge
   (SgMeshRefinementMap, the transfer of nested iteration), so the P1 interpolation has one or two entries per row.
   The linear systems are on the free dofs (Dirichlet vertices left out), so P maps a coarse level's free dofs (its
   layout made as the problem's: SgMeshSetUp with the same Dirichlet boundary) to the finer one's; a fixed component of
   a partly fixed vertex (a decoupled unknown that stays 0) receives nothing from a free one, only from the same fixed
   component of the coinciding coarse vertex (so the coarse operators keep a positive diagonal there). In the contact
   frames (-ssn_frame) the finest P is Q^T P (rows of the rotated vertices turned into their frames); for two bodies
   in the pair's dual-mortar basis (-ssn_pair_transform) it is (T Q)^-1 P (SgFramePairInterpolation, as the AMG's
   finest interpolation there: the coarse operators are K's own, each body coarsened on its own mesh); the coarser
   levels stay in the global coordinates, but with the body in one frame R (-ssn_frame_global), where they are in R
   as the finest level is (VertexRows). Before, only the contact rows were turned (Q_i^T P) while the rest of the
   finest level's unknowns are in R too: the coarse corrections arrived turned by R against the contact rows, and the
   coarse operators' components coupled off the axes for the point smoothers (the turned Example 2 at 144,666
   unknowns: 52 CG on the finest level against the flat one's 24; bench/nested.md big27). tmg.c then truncates the finest P at the active normal dofs and forms the
   coarse operators by Galerkin products, as for the AMG's interpolations. */
#include "solver/ssnimpl.h"

/* The mesh hierarchy's DMs under dm, coarsest first: (*lv)[0..L-1], L in *nlv (0: none). */
static PetscErrorCode Hierarchy(DM dm, PetscInt *nlv, DM **lv)
{
  PetscInt L = 0;

  PetscFunctionBeginUser;
  for (;;) {
    PetscObject o;
    char        name[64];
    PetscCall(PetscSNPrintf(name, sizeof(name), "SgNestedLevel%" PetscInt_FMT, L + 1));
    PetscCall(PetscObjectQuery((PetscObject)dm, name, &o));
    if (!o) break;
    L++;
  }
  *nlv = L;
  PetscCall(PetscMalloc1(L + 1, lv));
  for (PetscInt k = 1; k <= L; k++) {
    PetscObject o;
    char        name[64];
    PetscCall(PetscSNPrintf(name, sizeof(name), "SgNestedLevel%" PetscInt_FMT, k));
    PetscCall(PetscObjectQuery((PetscObject)dm, name, &o));
    (*lv)[L - k] = (DM)o;
  }
  PetscFunctionReturn(0);
}

/* The entries of the rows of fine vertex v (owned and free) of the interpolation from mesh c to mesh f (the next
   refinement; map from SgMeshRefinementMap): *nr rows (global numbers row[a]), row a with nc[a] entries at columns
   col[a][.] (global) with values val[a][.]. With a frame (cidx[v] >= 0: its contact vertex, rotated), the rows of
   Q_i^T P. With the body in one frame R (-ssn_frame_global, Rg = R, else NULL) the levels' unknowns are in R as the
   finest level's are: the rows of F_v^T P F_p, F = R at every vertex but a partly fixed one (a roller: the identity,
   as frame.c leaves it) and the contact vertices' Q_i on the finest level. Between two vertices both in R, P's
   block w I commutes with R and stays w I, one entry per row as without frames. */
static void VertexRows(const SgMesh *c, const SgMesh *f, const PetscInt map[], SgFrame frame, const PetscInt cidx[], const PetscReal *Rg, PetscInt v, PetscInt *nr, PetscInt row[3], PetscInt nc[3], PetscInt col[3][6], PetscReal val[3][6])
{
  const PetscInt  dim = f->dim, v0 = map[2 * v], v1 = map[2 * v + 1], np = v0 == v1 ? 1 : 2, par[2] = {v0, v1};
  const PetscReal w = v0 == v1 ? 1.0 : 0.5;
  PetscInt        cols[2][3]; /* the Cartesian row of component d: the column of parent k, or -1 */
  PetscReal       vals[2][3], qt[3][3];
  PetscBool       rotv = PETSC_FALSE, inR = PETSC_FALSE; /* the fine vertex in a frame (qt = F_v^T), in R itself */

  for (PetscInt d = 0; d < dim; d++)
    for (PetscInt k = 0; k < 2; k++) {
      const PetscInt p = par[k];
      cols[k][d]       = -1;
      vals[k][d]       = 0;
      if (k >= np || c->gblock[p] < 0) continue;
      if (SgMeshFixed(f, v, d) != SgMeshFixed(c, p, d)) continue; /* free from free, fixed from the same fixed one */
      if (SgMeshFixed(f, v, d) && np > 1) continue;
      cols[k][d] = c->gblock[p] * dim + d;
      vals[k][d] = w;
    }
  *nr = dim;
  if (cidx && cidx[v] >= 0) { /* row a of Q_i^T P: sum_d (Q_i^T)_{ad} (row d) */
    for (PetscInt d = 0; d < dim; d++) {
      PetscReal e[3] = {0, 0, 0}, r[3];
      e[d]           = 1;
      SgFrameVectorToLocal(frame, cidx[v], e, r);
      for (PetscInt a = 0; a < dim; a++) qt[a][d] = r[a];
    }
    rotv = PETSC_TRUE;
  } else if (Rg && !SgMeshPartial(f, v)) {
    for (PetscInt a = 0; a < dim; a++)
      for (PetscInt d = 0; d < dim; d++) qt[a][d] = Rg[d * dim + a];
    rotv = inR = PETSC_TRUE;
  }
  for (PetscInt a = 0; a < dim; a++) {
    row[a] = f->gblock[v] * dim + a;
    nc[a]  = 0;
  }
  for (PetscInt k = 0; k < np; k++) {
    const PetscInt  p  = par[k];
    const PetscBool rp = (PetscBool)(Rg && c->gblock[p] >= 0 && !SgMeshPartial(c, p)); /* the parent in R */
    if (rp && inR) {                                                                   /* both in R: w I */
      for (PetscInt a = 0; a < dim; a++)
        if (cols[k][a] >= 0) {
          col[a][nc[a]]   = cols[k][a];
          val[a][nc[a]++] = vals[k][a];
        }
      continue;
    }
    for (PetscInt a = 0; a < dim; a++)
      for (PetscInt b = 0; b < dim; b++) { /* (F_v^T P F_p)_{ab}: sum_d (F_v^T)_{ad} P_{dd} (F_p)_{db} */
        PetscReal x = 0;
        if (rp) {
          for (PetscInt d = 0; d < dim; d++)
            if (cols[k][d] >= 0) x += (rotv ? qt[a][d] : (PetscReal)(a == d)) * vals[k][d] * Rg[d * dim + b];
        } else if (cols[k][b] >= 0) x = rotv ? qt[a][b] * vals[k][b] : (PetscReal)(a == b) * vals[k][b];
        if (x != 0) {
          col[a][nc[a]]   = c->gblock[p] * dim + b;
          val[a][nc[a]++] = x;
        }
      }
  }
}

/* The interpolation from the free dofs of mesh c to those of mesh f (the next refinement; map from
   SgMeshRefinementMap); with a frame, the rows of the rotated contact vertices (ncv, their local vertex numbers cvert) in their frames.
   Preallocated exactly (each row's entries in the diagonal and off-diagonal blocks counted first): an AIJ matrix keeps
   the storage it was preallocated with, and a bound of 2 dim per row and block held 3-6 times the one or two entries
   of a row, twice on several ranks (the off-diagonal block), through the whole solve (bench/nested.md, mem27). */
static PetscErrorCode Interpolation(MPI_Comm comm, const SgMesh *c, const SgMesh *f, const PetscInt map[], SgFrame frame, const PetscReal *Rg, PetscInt ncv, const PetscInt cvert[], Mat *P)
{
  const PetscInt   dim = f->dim;
  PetscInt         nr = 0, nc = 0, rstart = 0, cstart = 0, *cidx = NULL, *dnz, *onz;
  const PetscBool *rot = NULL;

  PetscFunctionBeginUser;
  for (PetscInt v = 0; v < f->nv; v++)
    if (f->goff[v] >= 0) nr += dim;
  for (PetscInt v = 0; v < c->nv; v++)
    if (c->goff[v] >= 0) nc += dim;
  PetscCallMPI(MPI_Exscan(&nr, &rstart, 1, MPIU_INT, MPI_SUM, comm));
  PetscCallMPI(MPI_Exscan(&nc, &cstart, 1, MPIU_INT, MPI_SUM, comm));
  {
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    if (!rank) rstart = cstart = 0; /* (MPI_Exscan leaves rank 0's undefined) */
  }
  if (frame) {
    PetscCall(SgFrameGetAxes(frame, NULL, NULL, &rot));
    PetscCall(PetscMalloc1(f->nv, &cidx));
    for (PetscInt v = 0; v < f->nv; v++) cidx[v] = -1;
    for (PetscInt i = 0; i < ncv; i++)
      if (rot[i]) cidx[cvert[i]] = i;
  }
  PetscCall(PetscCalloc2(nr, &dnz, nr, &onz));
  for (PetscInt v = 0; v < f->nv; v++) {
    PetscInt  n, row[3], cnt[3], col[3][6];
    PetscReal val[3][6];
    if (f->goff[v] < 0) continue;
    VertexRows(c, f, map, frame, cidx, Rg, v, &n, row, cnt, col, val);
    for (PetscInt a = 0; a < n; a++) {
      const PetscInt r = row[a] - rstart;
      PetscCheck(r >= 0 && r < nr, PETSC_COMM_SELF, PETSC_ERR_PLIB, "geometric multigrid: the row %" PetscInt_FMT " of an owned vertex is not this rank's (%" PetscInt_FMT " ... %" PetscInt_FMT ")", row[a], rstart, rstart + nr - 1);
      for (PetscInt k = 0; k < cnt[a]; k++) {
        if (col[a][k] >= cstart && col[a][k] < cstart + nc) dnz[r]++;
        else onz[r]++;
      }
    }
  }
  PetscCall(MatCreate(comm, P));
  PetscCall(MatSetSizes(*P, nr, nc, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetType(*P, MATAIJ));
  PetscCall(MatXAIJSetPreallocation(*P, 1, dnz, onz, NULL, NULL));
  PetscCall(PetscFree2(dnz, onz));
  for (PetscInt v = 0; v < f->nv; v++) {
    PetscInt  n, row[3], cnt[3], col[3][6];
    PetscReal val[3][6];
    if (f->goff[v] < 0) continue;
    VertexRows(c, f, map, frame, cidx, Rg, v, &n, row, cnt, col, val);
    for (PetscInt a = 0; a < n; a++)
      for (PetscInt k = 0; k < cnt[a]; k++) PetscCall(MatSetValue(*P, row[a], col[a][k], val[a][k], INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(*P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*P, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscFree(cidx));
  PetscFunctionReturn(0);
}

/* The interpolations of the hierarchy in PCMG's numbering: (*P)[l] from level l-1 to l, l = 1 .. n-1 ((*P)[0] NULL),
   level n-1 the problem's mesh. *n = 0 (nothing made) on the unrefined mesh of a hierarchy (the coarsest level of
   nested iteration, -cont_nested): the caller takes an AMG there. A mesh without a hierarchy is refused. */
PetscErrorCode SgGMGInterpolations(SgSSN s, PetscInt *n, Mat **P)
{
  DM                dm, *lv, *dmc;
  PetscInt          L = 0;
  SgMesh           *m;
  const SgBoundary *bd;
  const char       *prefix;
  const PetscBool   pair = SgFramePairTransform(s->frame);
  const PetscReal  *Rg   = NULL; /* -ssn_frame_global: every level in the body's rotation R (VertexRows) */

  PetscFunctionBeginUser;
  *n = 0;
  *P = NULL;
  PetscCall(SgElasticityGetDMs(s->prob, &dm, NULL, NULL, NULL));
  PetscCall(Hierarchy(dm, &L, &lv));
  if (!L) {
    PetscObject base;
    PetscCall(PetscFree(lv));
    PetscCall(PetscObjectQuery((PetscObject)dm, "SgNestedBase", &base));
    PetscCheck(base, s->comm, PETSC_ERR_USER_INPUT, "-ssn_pc_truncated_mg_interp geometric: the mesh has no refinement hierarchy; the geometric multigrid needs a mesh made from the options (-dm_plex_filename or -box_*) and refined after distribution (-dm_refine N, N >= 1); otherwise use -ssn_pc_truncated_mg_interp amg");
    PetscCall(PetscInfo(dm, "geometric multigrid: the unrefined mesh of the hierarchy, the AMG's interpolations instead\n"));
    PetscFunctionReturn(0);
  }
  PetscCall(SgElasticityGetDirichletBoundary(s->prob, &bd));
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)dm, &prefix));
  PetscCall(PetscCalloc2(L + 1, &m, L + 1, &dmc));
  PetscCall(PetscCalloc1(L + 1, P));
  for (PetscInt l = 0; l < L; l++) { /* each coarse level's layout on its own copy of the mesh (the section is the copy's) */
    PetscCall(DMClone(lv[l], &dmc[l]));
    PetscCall(SgMeshSetUp(dmc[l], bd, &m[l]));
  }
  m[L] = *s->mesh;
  if (!pair) PetscCall(SgFrameGetGlobalRotation(s->frame, &Rg));
  for (PetscInt l = 1; l <= L; l++) {
    PetscInt *map, bad;
    PetscCall(SgMeshRefinementMap(dmc[l - 1], l < L ? dmc[l] : dm, &m[l - 1], &m[l], prefix, &map, &bad));
    PetscCheck(!bad, s->comm, PETSC_ERR_SUP, "-ssn_pc_truncated_mg_interp geometric: the mesh refined %" PetscInt_FMT " times fewer, refined once, is not the next level's mesh vertex by vertex (%" PetscInt_FMT " vertices differ): the refinement does not nest here; use -ssn_pc_truncated_mg_interp amg", L - l + 1, bad);
    PetscCall(Interpolation(s->comm, &m[l - 1], &m[l], map, l == L && !pair ? s->frame : NULL, Rg, s->n, s->vert, &(*P)[l]));
    PetscCall(PetscFree(map));
    if (l == L && pair) { /* two bodies: the finest P taken into the pair's dual-mortar basis, as the AMG's (tmg.c) */
      Mat Pv;
      PetscCall(SgFramePairInterpolation(s->frame, (*P)[L], &Pv));
      PetscCall(MatDestroy(&(*P)[L]));
      (*P)[L] = Pv;
    }
  }
  {
    PetscInt nrow, nfine;
    PetscCall(MatGetLocalSize((*P)[L], &nrow, NULL));
    PetscCall(VecGetLocalSize(s->b, &nfine));
    PetscCheck(nrow == nfine, PETSC_COMM_SELF, PETSC_ERR_PLIB, "geometric multigrid: the finest interpolation has %" PetscInt_FMT " rows here, the problem %" PetscInt_FMT " unknowns", nrow, nfine);
  }
  for (PetscInt l = 0; l < L; l++) {
    PetscCall(SgMeshDestroy(&m[l]));
    PetscCall(DMDestroy(&dmc[l]));
  }
  PetscCall(PetscFree2(m, dmc));
  PetscCall(PetscFree(lv));
  *n = L + 1;
  PetscFunctionReturn(0);
}

/* The coarsest level's solver: sparse Cholesky (MUMPS; its ordering keeps the fill of a 3D mesh small), refactored
   for every active set; -tmg_mg_coarse_* (under the KSP's prefix) override. On several ranks every rank factors the
   whole coarse matrix (PCREDUNDANT, -tmg_mg_coarse_redundant_*; asm27): MUMPS spread over the ranks spent more in its
   messages than in the arithmetic of a few thousand unknowns, at every set-up and in every V-cycle's solve. */
PetscErrorCode SgGMGCoarseSolver(KSP ksp)
{
  PC          pc;
  PetscMPIInt size;

  PetscFunctionBeginUser;
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)ksp), &size));
  if (size > 1) {
    KSP inner;
    PetscCall(PCSetType(pc, PCREDUNDANT));
    PetscCall(PCRedundantGetKSP(pc, &inner));
    PetscCall(KSPSetType(inner, KSPPREONLY));
    PetscCall(KSPGetPC(inner, &pc));
  }
  PetscCall(PCSetType(pc, PCCHOLESKY));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscFunctionReturn(0);
}
