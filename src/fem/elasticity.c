/* elasticity.c: P1 linear elasticity: element kernels, assembly of K and the load, energy, stresses, manufactured solution. */
#include "fem/femimpl.h"

/* Lame constants (plane strain in 2D) from Young's modulus and Poisson's ratio. */
PetscErrorCode SgLame(PetscReal E, PetscReal nu, PetscReal *lambda, PetscReal *mu)
{
  PetscFunctionBeginUser;
  *mu     = E / (2 * (1 + nu));
  *lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  PetscFunctionReturn(0);
}

/* Gradients G[a*dim+d] of the barycentric functions of a simplex and its measure. */
PetscErrorCode SgSimplexGradients(PetscInt dim, const PetscReal x[], PetscReal G[], PetscReal *vol)
{
  PetscReal J[3][3], Ji[3][3], det;

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < dim; a++)
    for (PetscInt d = 0; d < dim; d++) J[d][a] = x[(a + 1) * dim + d] - x[d];
  if (dim == 2) {
    det      = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    Ji[0][0] = J[1][1] / det;
    Ji[0][1] = -J[0][1] / det;
    Ji[1][0] = -J[1][0] / det;
    Ji[1][1] = J[0][0] / det;
    *vol     = 0.5 * PetscAbsReal(det);
  } else {
    det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) + J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
    for (PetscInt i = 0; i < 3; i++)
      for (PetscInt j = 0; j < 3; j++) {
        const PetscInt i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
        Ji[i][j] = (J[i1][j1] * J[i2][j2] - J[i1][j2] * J[i2][j1]) / det;
      }
    *vol = PetscAbsReal(det) / 6.0;
  }
  PetscCheck(det != 0 && PetscIsNormalReal(det), PETSC_COMM_SELF, PETSC_ERR_USER_INPUT, "degenerate simplex (zero measure) in the mesh");
  /* grad phi_a (a >= 1) is row a-1 of J^{-1}; grad phi_0 = -sum of the others */
  for (PetscInt d = 0; d < dim; d++) {
    G[d] = 0;
    for (PetscInt a = 1; a <= dim; a++) {
      G[a * dim + d] = Ji[a - 1][d];
      G[d] -= Ji[a - 1][d];
    }
  }
  PetscFunctionReturn(0);
}

/* P1 element stiffness Ke[(a*dim+i)*(n*dim)+(b*dim+j)] = int lambda div(phi_b e_j) div(phi_a e_i) + 2 mu eps:eps. */
PetscErrorCode SgElementStiffness(PetscInt dim, const PetscReal x[], PetscReal lambda, PetscReal mu, PetscReal Ke[], PetscReal *vol)
{
  PetscReal      G[12];
  const PetscInt nv = dim + 1, n = nv * dim;

  PetscFunctionBeginUser;
  PetscCall(SgSimplexGradients(dim, x, G, vol));
  for (PetscInt a = 0; a < nv; a++)
    for (PetscInt b = 0; b < nv; b++) {
      PetscReal gg = 0;
      for (PetscInt k = 0; k < dim; k++) gg += G[a * dim + k] * G[b * dim + k];
      for (PetscInt i = 0; i < dim; i++)
        for (PetscInt j = 0; j < dim; j++) Ke[(a * dim + i) * n + b * dim + j] = *vol * (lambda * G[a * dim + i] * G[b * dim + j] + mu * (G[a * dim + j] * G[b * dim + i] + (i == j ? gg : 0)));
    }
  PetscFunctionReturn(0);
}

/* Manufactured solution u_k = A sin(pi a_k.x + phi_k) and the body force -div sigma(u) that produces it. */
static const PetscReal MMS_A = 0.01, MMS_a[3][3] = {
  {1.0,  0.5,  0.25},
  {0.5,  1.0,  0.75},
  {0.25, 0.75, 1.0 }
},
                       MMS_phi[3] = {0.1, 0.3, 0.7};

static void MMSExact(PetscInt dim, const PetscReal x[], PetscReal u[], PetscReal grad[])
{
  for (PetscInt k = 0; k < dim; k++) {
    PetscReal th = MMS_phi[k];
    for (PetscInt j = 0; j < dim; j++) th += PETSC_PI * MMS_a[k][j] * x[j];
    u[k] = MMS_A * PetscSinReal(th);
    if (grad)
      for (PetscInt j = 0; j < dim; j++) grad[k * dim + j] = MMS_A * PETSC_PI * MMS_a[k][j] * PetscCosReal(th);
  }
}

static void MMSForce(PetscInt dim, PetscReal lambda, PetscReal mu, const PetscReal x[], PetscReal f[])
{
  PetscReal s[3];
  for (PetscInt k = 0; k < dim; k++) {
    PetscReal th = MMS_phi[k];
    for (PetscInt j = 0; j < dim; j++) th += PETSC_PI * MMS_a[k][j] * x[j];
    s[k] = MMS_A * PETSC_PI * PETSC_PI * PetscSinReal(th);
  }
  /* f_l = mu |a_l|^2 s_l + (lambda+mu) sum_k a_kk a_kl s_k */
  for (PetscInt l = 0; l < dim; l++) {
    PetscReal al2 = 0, gd = 0;
    for (PetscInt j = 0; j < dim; j++) al2 += MMS_a[l][j] * MMS_a[l][j];
    for (PetscInt k = 0; k < dim; k++) gd += MMS_a[k][k] * MMS_a[k][l] * s[k];
    f[l] = mu * al2 * s[l] + (lambda + mu) * gd;
  }
}

/* Quadrature on a simplex of dimension dim, exact to degree 5: barycentric points and weights summing to 1. */
static PetscErrorCode SimplexQuadrature(PetscInt dim, PetscInt *nq, PetscReal **lam, PetscReal **w)
{
  PetscQuadrature  q;
  const PetscReal *pts, *wts;
  PetscReal        wsum = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscDTStroudConicalQuadrature(dim, 1, 3, -1.0, 1.0, &q));
  PetscCall(PetscQuadratureGetData(q, NULL, NULL, nq, &pts, &wts));
  PetscCall(PetscMalloc2(*nq * (dim + 1), lam, *nq, w));
  for (PetscInt i = 0; i < *nq; i++) wsum += wts[i];
  for (PetscInt i = 0; i < *nq; i++) {
    PetscReal s = 0;
    for (PetscInt d = 0; d < dim; d++) {
      (*lam)[i * (dim + 1) + d + 1] = 0.5 * (pts[i * dim + d] + 1);
      s += (*lam)[i * (dim + 1) + d + 1];
    }
    (*lam)[i * (dim + 1)] = 1 - s;
    (*w)[i]               = wts[i] / wsum;
  }
  PetscCall(PetscQuadratureDestroy(&q));
  PetscFunctionReturn(0);
}

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

/* Dirichlet value of vertex v (local number) */
/* the Dirichlet value at vertex v: from vals (dim per Dirichlet id; SgElasticitySetDirichletValues), or NULL: the
   given data (-dirichlet_values, or the manufactured field) */
static void DirichletValue(SgElasticity p, const PetscReal vals[], PetscInt v, PetscReal u[])
{
  if (p->mms) MMSExact(p->dim, &p->mesh.x[v * p->dim], u, NULL);
  for (PetscInt d = 0; d < p->dim; d++) {
    const PetscInt g = p->mesh.bcpart[v * p->dim + d];
    if (g < 0) u[d] = 0.0; /* a free component of a partly fixed vertex */
    else if (vals) u[d] = vals[g * p->dim + d];
    else if (!p->mms) u[d] = p->dirichlet.nvalues ? p->dirichlet.values[g * p->dim + d] : 0.0;
  }
}

/* The stiffness (BAIJ, block size dim) with its nonzero pattern from the mesh graph: block row v couples v with the
   vertices of its cells.
   Rows of vertices shared between ranks get the counts of every rank added, an upper bound only there (the other
   ranks' cells are not local). DMCreateMatrix() and MATPREALLOCATOR cost several times the assembly itself. */
static PetscErrorCode CreateStiffness(SgElasticity p)
{
  const SgMesh  *m = &p->mesh;
  const PetscInt dim = p->dim, nv = dim + 1;
  PetscInt       n, N, bstart, bend, *vcoff, *vcell, *mark, *dnz, *onz;
  const PetscInt *ranges;
  PetscMPIInt    size;
  Vec            cloc, cglob;
  PetscScalar   *ca;
  PetscSection   vs;

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(p->b, &n));
  PetscCall(VecGetSize(p->b, &N));
  PetscCall(VecGetOwnershipRange(p->b, &bstart, &bend));
  bstart /= dim;
  bend /= dim;
  PetscCall(VecGetOwnershipRanges(p->b, &ranges));
  PetscCallMPI(MPI_Comm_size(p->comm, &size));
  /* vertex -> cells */
  PetscCall(PetscCalloc3(m->nv + 1, &vcoff, m->nc * nv, &vcell, m->nv, &mark));
  for (PetscInt c = 0; c < m->nc * nv; c++) vcoff[m->cellv[c] + 1]++;
  for (PetscInt v = 0; v < m->nv; v++) vcoff[v + 1] += vcoff[v];
  for (PetscInt c = 0; c < m->nc; c++)
    for (PetscInt a = 0; a < nv; a++) vcell[vcoff[m->cellv[c * nv + a]] + mark[m->cellv[c * nv + a]]++] = c;
  for (PetscInt v = 0; v < m->nv; v++) mark[v] = -1;
  /* local counts of distinct free neighbours (diagonal / off-diagonal block columns), summed over ranks */
  PetscCall(DMGetLocalVector(p->dmVec, &cloc));
  PetscCall(VecZeroEntries(cloc));
  PetscCall(DMGetLocalSection(p->dmVec, &vs));
  PetscCall(VecGetArray(cloc, &ca));
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt off, d = 0, o = 0, lo, hi, r = 0;
    if (m->gblock[v] < 0) continue;
    /* diagonal or off-diagonal block is decided by the owner of row v */
    while (r < size - 1 && m->gblock[v] * dim >= ranges[r + 1]) r++;
    lo = ranges[r] / dim;
    hi = ranges[r + 1] / dim;
    for (PetscInt k = vcoff[v]; k < vcoff[v + 1]; k++)
      for (PetscInt a = 0; a < nv; a++) {
        const PetscInt u = m->cellv[vcell[k] * nv + a], g = m->gblock[u];
        if (g < 0 || mark[u] == v) continue;
        mark[u] = v;
        if (g >= lo && g < hi) d++;
        else o++;
      }
    PetscCall(PetscSectionGetOffset(vs, m->vStart + v, &off));
    ca[off]     = d;
    ca[off + 1] = o;
  }
  PetscCall(VecRestoreArray(cloc, &ca));
  PetscCall(DMGetGlobalVector(p->dmVec, &cglob));
  PetscCall(VecZeroEntries(cglob));
  PetscCall(DMLocalToGlobal(p->dmVec, cloc, ADD_VALUES, cglob));
  PetscCall(DMGlobalToLocal(p->dmVec, cglob, INSERT_VALUES, cloc));
  PetscCall(DMRestoreGlobalVector(p->dmVec, &cglob));
  PetscCall(PetscMalloc2(n / dim, &dnz, n / dim, &onz));
  PetscCall(VecGetArray(cloc, &ca));
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt off;
    if (m->goff[v] < 0) continue; /* owned free vertices have rows here */
    PetscCall(PetscSectionGetOffset(vs, m->vStart + v, &off));
    dnz[m->goff[v] / dim] = PetscMin((PetscInt)PetscRealPart(ca[off]), bend - bstart);
    onz[m->goff[v] / dim] = PetscMin((PetscInt)PetscRealPart(ca[off + 1]), N / dim - (bend - bstart));
  }
  PetscCall(VecRestoreArray(cloc, &ca));
  PetscCall(DMRestoreLocalVector(p->dmVec, &cloc));
  PetscCall(MatCreate(p->comm, &p->K));
  PetscCall(MatSetSizes(p->K, n, n, N, N));
  PetscCall(MatSetBlockSize(p->K, dim));
  PetscCall(MatSetType(p->K, MATBAIJ)); /* blocked insertion; converted to AIJ (what MUMPS and hypre take) once assembled */
  PetscCall(MatXAIJSetPreallocation(p->K, dim, dnz, onz, NULL, NULL));
  PetscCall(MatSetOption(p->K, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PetscCall(PetscFree2(dnz, onz));
  PetscCall(PetscFree3(vcoff, vcell, mark));
  PetscFunctionReturn(0);
}

/* no load on the fixed components of partly fixed vertices: their unknowns stay 0 (fa: a local vector's array) */
static void ZeroFixedComponents(const SgMesh *m, PetscInt dim, PetscScalar fa[])
{
  for (PetscInt v = 0; v < m->nv; v++)
    if (SgMeshPartial(m, v))
      for (PetscInt d = 0; d < dim; d++)
        if (SgMeshFixed(m, v, d)) fa[m->loff[v] + d] = 0;
}

static PetscErrorCode Assemble(SgElasticity p)
{
  const SgMesh   *m = &p->mesh;
  const PetscInt  dim = p->dim, nv = dim + 1, ne = nv * dim;
  Vec             floc, mloc, xg, xloc;
  PetscScalar    *fa, *ma, *ua, *xa, *pa;
  PetscReal       shift = 0, *lq = NULL, *wq = NULL;
  PetscInt        nq = 0, nfac, *facets, *part;
  PetscLogDouble  t0, t1;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(SG_Assembly, 0, 0, 0, 0));
  PetscCall(PetscTime(&t0));
  PetscCall(DMCreateGlobalVector(p->dm, &p->b));
  PetscCall(PetscObjectSetName((PetscObject)p->b, "load"));
  PetscCall(CreateStiffness(p));
  PetscCall(PetscObjectSetName((PetscObject)p->K, "K"));
  PetscCall(VecDuplicate(p->b, &p->mass));
  PetscCall(DMCreateLocalVector(p->dm, &p->ubc));
  PetscCall(DMCreateLocalVector(p->dm, &p->fpart));
  PetscCall(VecZeroEntries(p->fpart));
  PetscCall(DMGetLocalVector(p->dm, &floc));
  PetscCall(DMGetLocalVector(p->dm, &mloc));
  PetscCall(VecZeroEntries(floc));
  PetscCall(VecZeroEntries(mloc));
  PetscCall(VecZeroEntries(p->ubc));
  if (p->mms) PetscCall(SimplexQuadrature(dim, &nq, &lq, &wq));

  PetscCall(VecGetArray(p->ubc, &ua));
  for (PetscInt v = 0; v < m->nv; v++)
    if (m->bcmask[v]) {
      PetscReal u[3];
      DirichletValue(p, NULL, v, u);
      for (PetscInt d = 0; d < dim; d++) ua[m->loff[v] + d] = u[d];
    }
  PetscCall(VecGetArray(floc, &fa));
  PetscCall(VecGetArray(mloc, &ma));
  PetscCall(VecGetArray(p->fpart, &pa));
  for (PetscInt c = 0; c < m->nc; c++) {
    const PetscInt *cv = &m->cellv[c * nv];
    PetscReal       xe[12], Ke[144], Kd[144], fe[12], ud[12], vol;
    PetscInt        gb[4];
    PetscBool       lift = PETSC_FALSE, partial = PETSC_FALSE;

    for (PetscInt a = 0; a < nv; a++) {
      gb[a] = m->gblock[cv[a]];
      for (PetscInt d = 0; d < dim; d++) {
        xe[a * dim + d] = m->x[cv[a] * dim + d];
        ud[a * dim + d] = PetscRealPart(ua[m->loff[cv[a]] + d]);
      }
      if (m->bcmask[cv[a]]) lift = PETSC_TRUE;
      if (SgMeshPartial(m, cv[a])) partial = PETSC_TRUE;
    }
    PetscCall(SgElementStiffness(dim, xe, p->lambda, p->mu, Ke, &vol));
    if (partial) {
      /* a fixed component of a partly fixed vertex: its row and column decoupled, its diagonal kept (the scale of
         its neighbours for the preconditioners), so that its unknown stays 0; its value enters by the lifting */
      PetscCall(PetscArraycpy(Kd, Ke, ne * ne));
      for (PetscInt a = 0; a < nv; a++)
        for (PetscInt i = 0; i < dim; i++) {
          const PetscInt r = a * dim + i;
          if (gb[a] < 0 || !SgMeshFixed(m, cv[a], i)) continue;
          for (PetscInt j = 0; j < ne; j++)
            if (j != r) Kd[r * ne + j] = Kd[j * ne + r] = 0;
        }
      PetscCall(MatSetValuesBlocked(p->K, nv, gb, nv, gb, Kd, ADD_VALUES));
    } else PetscCall(MatSetValuesBlocked(p->K, nv, gb, nv, gb, Ke, ADD_VALUES));
    if (p->mms) {
      PetscCall(PetscArrayzero(fe, ne));
      for (PetscInt q = 0; q < nq; q++) {
        PetscReal xq[3] = {0, 0, 0}, f[3];
        for (PetscInt a = 0; a < nv; a++)
          for (PetscInt d = 0; d < dim; d++) xq[d] += lq[q * nv + a] * xe[a * dim + d];
        MMSForce(dim, p->lambda, p->mu, xq, f);
        for (PetscInt a = 0; a < nv; a++)
          for (PetscInt d = 0; d < dim; d++) fe[a * dim + d] += vol * wq[q] * lq[q * nv + a] * f[d];
      }
    } else
      for (PetscInt a = 0; a < nv; a++)
        for (PetscInt d = 0; d < dim; d++) fe[a * dim + d] = vol / nv * p->body_force[d];
    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt d = 0; d < dim; d++) pa[m->loff[cv[a]] + d] += fe[a * dim + d];
    if (lift) {
      for (PetscInt i = 0; i < ne; i++) {
        PetscReal Ku = 0;
        for (PetscInt j = 0; j < ne; j++) Ku += Ke[i * ne + j] * ud[j];
        shift += 0.5 * ud[i] * Ku - fe[i] * ud[i];
        fe[i] -= Ku;
      }
    }
    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt d = 0; d < dim; d++) {
        fa[m->loff[cv[a]] + d] += fe[a * dim + d];
        ma[m->loff[cv[a]] + d] += vol / nv;
      }
  }
  /* Neumann: constant traction per label value, exact P1 load on each facet */
  if (p->neumann.nvalues) {
    PetscCall(SgBoundaryGetFacets(p->dm, &p->neumann, &nfac, &facets, &part));
    for (PetscInt i = 0; i < nfac; i++) {
      PetscInt  fv[3], nfv;
      PetscReal area, nrm[3];
      PetscCall(SgFacetGeometry(p->dm, m, facets[i], &nfv, fv, &area, nrm));
      for (PetscInt a = 0; a < nfv; a++)
        for (PetscInt d = 0; d < dim; d++) {
          const PetscReal t = area / nfv * p->neumann.values[part[i] * dim + d];
          fa[m->loff[fv[a]] + d] += t;
          pa[m->loff[fv[a]] + d] += t;
          shift -= t * PetscRealPart(ua[m->loff[fv[a]] + d]);
        }
    }
    PetscCall(PetscFree2(facets, part));
  }
  ZeroFixedComponents(m, dim, fa);
  PetscCall(VecRestoreArray(floc, &fa));
  PetscCall(VecRestoreArray(mloc, &ma));
  PetscCall(VecRestoreArray(p->fpart, &pa));
  PetscCall(VecRestoreArray(p->ubc, &ua));
  PetscCall(PetscFree2(lq, wq));
  PetscCall(MatAssemblyBegin(p->K, MAT_FINAL_ASSEMBLY));
  PetscCall(VecZeroEntries(p->b));
  PetscCall(VecZeroEntries(p->mass));
  PetscCall(DMLocalToGlobal(p->dm, floc, ADD_VALUES, p->b));
  PetscCall(DMLocalToGlobal(p->dm, mloc, ADD_VALUES, p->mass));
  PetscCall(MatAssemblyEnd(p->K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatConvert(p->K, MATAIJ, MAT_INPLACE_MATRIX, &p->K));
  if (p->rigid_shift > 0) { /* an elastic foundation of modulus eps E/L^2 holds the otherwise free rigid motions */
    Vec sh;
    PetscCall(VecDuplicate(p->mass, &sh));
    PetscCall(VecCopy(p->mass, sh));
    PetscCall(VecScale(sh, p->rigid_shift * p->E / PetscSqr(p->diam)));
    PetscCall(MatDiagonalSet(p->K, sh, ADD_VALUES));
    PetscCall(VecDestroy(&sh));
  }
  PetscCall(DMRestoreLocalVector(p->dm, &floc));
  PetscCall(DMRestoreLocalVector(p->dm, &mloc));
  PetscCallMPI(MPI_Allreduce(&shift, &p->energy_shift, 1, MPIU_REAL, MPI_SUM, p->comm));
  PetscCall(VecNorm(p->b, NORM_2, &p->bnorm));
  PetscCall(VecNorm(p->b, NORM_INFINITY, &p->bnorm_inf));
  PetscCall(MatNorm(p->K, NORM_INFINITY, &p->Knorm));
  PetscCall(MatSetOption(p->K, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatSetOption(p->K, MAT_SPD, PETSC_TRUE));

  /* rigid-body near null space from the coordinates of the free vertices */
  PetscCall(DMGetLocalVector(p->dm, &xloc));
  PetscCall(VecGetArray(xloc, &xa));
  for (PetscInt v = 0; v < m->nv; v++)
    for (PetscInt d = 0; d < dim; d++) xa[m->loff[v] + d] = m->x[v * dim + d];
  PetscCall(VecRestoreArray(xloc, &xa));
  PetscCall(VecDuplicate(p->b, &xg));
  PetscCall(DMLocalToGlobal(p->dm, xloc, INSERT_VALUES, xg));
  PetscCall(DMRestoreLocalVector(p->dm, &xloc));
  PetscCall(VecSetBlockSize(xg, dim));
  PetscCall(MatNullSpaceCreateRigidBody(xg, &p->nearnull));
  if (p->use_nearnull) PetscCall(MatSetNearNullSpace(p->K, p->nearnull));
  PetscCall(VecDestroy(&xg));
  PetscCall(PetscTime(&t1));
  p->t_assembly = t1 - t0;
  PetscCall(PetscLogEventEnd(SG_Assembly, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* CheckRigidMotions for a Dirichlet part that fixes only some components (rollers): the rigid motions whose fixed
   components vanish at every Dirichlet vertex are free; the message names them. */
static PetscErrorCode CheckRigidMotionsPartial(SgElasticity p)
{
  const PetscInt dim = p->dim, nr = dim == 2 ? 3 : 6;
  PetscInt       nfree;
  PetscReal      modes[36], c[3];
  char           ids[256] = "", what[1024] = "";

  PetscFunctionBeginUser;
  PetscCall(SgMeshFreeRigidMotions(p->comm, &p->mesh, &nfree, modes, c));
  if (!nfree) PetscFunctionReturn(0);
  if (p->rigid_shift_set) {
    PetscCall(PetscInfo(p->dm, "the Dirichlet part leaves %" PetscInt_FMT " rigid motions free: regularized with -elasticity_rigid_shift %g\n", nfree, (double)p->rigid_shift));
    PetscFunctionReturn(0);
  }
  for (PetscInt i = 0; i < p->dirichlet.nids; i++) {
    size_t l;
    PetscCall(PetscStrlen(ids, &l));
    PetscCall(PetscSNPrintf(ids + l, sizeof(ids) - l, i ? ",%" PetscInt_FMT : "%" PetscInt_FMT, p->dirichlet.ids[i]));
  }
  for (PetscInt k = 0; k < nfree && k < 3; k++) {
    const PetscReal *q = &modes[k * nr];
    PetscReal        t[3] = {0, 0, 0}, w[3] = {0, 0, 0}, tn = 0, wn = 0, tw = 0, x0[3], ax[3];
    size_t           l;
    char             buf[256];

    for (PetscInt d = 0; d < dim; d++) t[d] = q[d];
    if (dim == 2) w[2] = q[2];
    else
      for (PetscInt d = 0; d < 3; d++) w[d] = q[3 + d];
    for (PetscInt d = 0; d < 3; d++) {
      tn += t[d] * t[d];
      wn += w[d] * w[d];
      tw += t[d] * w[d];
    }
    /* as a motion people picture: a translation, or a rotation about an axis through x0 (with a slide along the axis
       in 3D): t + w x (x - c) = t_par + w x (x - x0), x0 = c + w x t / |w|^2 */
    if (wn * PetscSqr(p->diam) <= 1e-16 * tn) {
      tn = PetscSqrtReal(tn);
      for (PetscInt d = 0; d < 3; d++)
        if (PetscAbsReal(t[d]) < 1e-10 * tn) t[d] = 0;
      PetscCall(PetscSNPrintf(buf, sizeof(buf), dim == 2 ? "the translation along (%.4g, %.4g)" : "the translation along (%.4g, %.4g, %.4g)", (double)(t[0] / tn), (double)(t[1] / tn), (double)(t[2] / tn)));
    } else {
      x0[0] = c[0] + (w[1] * t[2] - w[2] * t[1]) / wn;
      x0[1] = c[1] + (w[2] * t[0] - w[0] * t[2]) / wn;
      x0[2] = c[2] + (w[0] * t[1] - w[1] * t[0]) / wn;
      for (PetscInt d = 0; d < 3; d++) ax[d] = w[d] / PetscSqrtReal(wn);
      for (PetscInt d = 0; d < 3; d++)
        if (PetscAbsReal(x0[d]) < 1e-10 * p->diam) x0[d] = 0;
      if (dim == 2) PetscCall(PetscSNPrintf(buf, sizeof(buf), "the rotation about (%.4g, %.4g)", (double)x0[0], (double)x0[1]));
      else PetscCall(PetscSNPrintf(buf, sizeof(buf), "the rotation about the axis along (%.4g, %.4g, %.4g) through (%.4g, %.4g, %.4g)%s", (double)ax[0], (double)ax[1], (double)ax[2], (double)x0[0], (double)x0[1], (double)x0[2], PetscAbsReal(tw) > 1e-8 * PetscSqrtReal(tn * wn) ? " with a slide along it" : ""));
    }
    PetscCall(PetscStrlen(what, &l));
    PetscCall(PetscSNPrintf(what + l, sizeof(what) - l, "%s %s", k ? ";" : "", buf));
  }
  SETERRQ(p->comm, PETSC_ERR_USER_INPUT, "the Dirichlet part (-dirichlet_label '%s'%s%s with -dirichlet_components) leaves %" PetscInt_FMT " rigid motion%s free:%s%s, so the stiffness is singular and the body floats. Fix more components (e.g. a roller normal to a second face), or regularize on purpose with -elasticity_rigid_shift eps (adds eps E/L^2 times the lumped volumes to K)", p->dirichlet.label, p->dirichlet.nids ? " -dirichlet_ids " : "", ids, nfree, nfree > 1 ? "s" : "", what, nfree > 3 ? " and more" : "");
}

/* The Dirichlet part must fix all rigid motions: otherwise K is singular and any solution is garbage. A part that fixes
   every component of 2 distinct points (2D) or 3 non-collinear points (3D) does; contact with a frictionless obstacle
   does not count (it leaves the tangential motions free). -elasticity_rigid_shift accepts such a body on purpose. */
static PetscErrorCode CheckRigidMotions(SgElasticity p)
{
  const PetscInt dim = p->dim;
  PetscInt       adim;
  PetscReal      p0[3], dir[3];
  char           part[512], what[512], ids[256] = "";

  PetscFunctionBeginUser;
  PetscCall(SgMeshConstrainedDimension(p->comm, &p->mesh, &adim, p0, dir, &p->diam));
  /* the other extreme: a label of cells (or of every boundary part of a 1-layer mesh) leaves nothing to solve for */
  PetscCheck(p->mesh.nfree_glob > 0, p->comm, PETSC_ERR_USER_INPUT, "-dirichlet_label '%s': every vertex of the mesh is a Dirichlet vertex, nothing is left to solve for (give a label of boundary faces)", p->dirichlet.label);
  if (p->dirichlet.ncomps) {
    PetscBool partial = PETSC_FALSE;
    for (PetscInt i = 0; i < p->dirichlet.ncomps; i++) partial = (PetscBool)(partial || p->dirichlet.comps[i] != (1 << dim) - 1);
    if (partial) PetscFunctionReturn(CheckRigidMotionsPartial(p));
  }
  if (adim >= dim - 1) PetscFunctionReturn(0);
  if (p->rigid_shift_set) {
    PetscCall(PetscInfo(p->dm, "the Dirichlet part leaves rigid motions free (affine dimension %" PetscInt_FMT "): regularized with -elasticity_rigid_shift %g\n", adim, (double)p->rigid_shift));
    PetscFunctionReturn(0);
  }
  for (PetscInt i = 0; i < p->dirichlet.nids; i++) {
    size_t l;
    PetscCall(PetscStrlen(ids, &l));
    PetscCall(PetscSNPrintf(ids + l, sizeof(ids) - l, i ? ",%" PetscInt_FMT : "%" PetscInt_FMT, p->dirichlet.ids[i]));
  }
  if (!p->dirichlet.active) PetscCall(PetscSNPrintf(part, sizeof(part), "no Dirichlet part is given (-dirichlet_label/-dirichlet_ids)"));
  else PetscCall(PetscSNPrintf(part, sizeof(part), "the Dirichlet part (-dirichlet_label '%s'%s%s)", p->dirichlet.label, p->dirichlet.nids ? " -dirichlet_ids " : "", ids));
  if (adim < 0) PetscCall(PetscSNPrintf(what, sizeof(what), "%s%s", p->dirichlet.active ? " has no vertex: " : ": ", dim == 2 ? "both translations and the rotation are free" : "the three translations and the three rotations are free"));
  else if (adim == 0) {
    if (dim == 2) PetscCall(PetscSNPrintf(what, sizeof(what), " fixes the single point (%g, %g): the rotation about it is free", (double)p0[0], (double)p0[1]));
    else PetscCall(PetscSNPrintf(what, sizeof(what), " fixes the single point (%g, %g, %g): the three rotations about it are free", (double)p0[0], (double)p0[1], (double)p0[2]));
  } else PetscCall(PetscSNPrintf(what, sizeof(what), " fixes only points on the line through (%g, %g, %g) along (%.6g, %.6g, %.6g): the rotation about that line is free", (double)p0[0], (double)p0[1], (double)p0[2], (double)dir[0], (double)dir[1], (double)dir[2]));
  SETERRQ(p->comm, PETSC_ERR_USER_INPUT, "%s%s, so the stiffness is singular and the body floats. Fix every component of at least %s with -dirichlet_label/-dirichlet_ids (contact with a frictionless obstacle does not hold the body: tangential motions stay free), or regularize on purpose with -elasticity_rigid_shift eps (adds eps E/L^2 times the lumped volumes to K)", part, what, dim == 2 ? "2 distinct points" : "3 points not on one line");
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
  PetscCall(CheckRigidMotions(p));
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
  PetscCall(Assemble(p));
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

/* The data at factor 1 (b, the Dirichlet values, the unlifted load), copied once: a run without load steps is
   untouched. */
static PetscErrorCode KeepFullLoad(SgElasticity p)
{
  PetscFunctionBeginUser;
  if (p->b1) PetscFunctionReturn(0);
  PetscCall(VecDuplicate(p->b, &p->b1));
  PetscCall(VecDuplicate(p->ubc, &p->ubc1));
  PetscCall(VecDuplicate(p->fpart, &p->fpart1));
  PetscCall(VecCopy(p->b, p->b1));
  PetscCall(VecCopy(p->ubc, p->ubc1));
  PetscCall(VecCopy(p->fpart, p->fpart1));
  p->energy_shift1 = p->energy_shift;
  p->bnorm1        = p->bnorm;
  p->bnorm_inf1    = p->bnorm_inf;
  PetscFunctionReturn(0);
}

/* The lifting of the Dirichlet values ubc (local): bl = -K_FD u_D on the free dofs (0 on the fixed components of
   partly fixed vertices, as in Assemble), and uKu = u_D^T K_DD u_D summed over the ranks (for the energy shift). */
static PetscErrorCode Lifting(SgElasticity p, Vec ubc, Vec bl, PetscReal *uKu)
{
  const SgMesh      *m = &p->mesh;
  const PetscInt     dim = p->dim, nv = dim + 1, ne = nv * dim;
  const PetscScalar *ua;
  PetscScalar       *fa;
  PetscReal          s = 0;
  Vec                floc;

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(p->dm, &floc));
  PetscCall(VecZeroEntries(floc));
  PetscCall(VecGetArrayRead(ubc, &ua));
  PetscCall(VecGetArray(floc, &fa));
  for (PetscInt c = 0; c < m->nc; c++) {
    const PetscInt *cv = &m->cellv[c * nv];
    PetscReal       xe[12], Ke[144], ud[12], vol;
    PetscBool       lift = PETSC_FALSE;

    for (PetscInt a = 0; a < nv; a++) {
      for (PetscInt d = 0; d < dim; d++) {
        xe[a * dim + d] = m->x[cv[a] * dim + d];
        ud[a * dim + d] = PetscRealPart(ua[m->loff[cv[a]] + d]);
      }
      if (m->bcmask[cv[a]]) lift = PETSC_TRUE;
    }
    if (!lift) continue;
    PetscCall(SgElementStiffness(dim, xe, p->lambda, p->mu, Ke, &vol));
    for (PetscInt i = 0; i < ne; i++) {
      PetscReal Ku = 0;
      for (PetscInt j = 0; j < ne; j++) Ku += Ke[i * ne + j] * ud[j];
      s += ud[i] * Ku;
      fa[m->loff[cv[i / dim]] + i % dim] -= Ku;
    }
  }
  ZeroFixedComponents(m, dim, fa);
  PetscCall(VecRestoreArray(floc, &fa));
  PetscCall(VecRestoreArrayRead(ubc, &ua));
  PetscCall(VecZeroEntries(bl));
  PetscCall(DMLocalToGlobal(p->dm, floc, ADD_VALUES, bl));
  PetscCall(DMRestoreLocalVector(p->dm, &floc));
  PetscCallMPI(MPI_Allreduce(&s, uKu, 1, MPIU_REAL, MPI_SUM, p->comm));
  PetscFunctionReturn(0);
}

/* The data of the Dirichlet values set (SgElasticitySetDirichletValues) and the load factor: u_D = dvals,
   b = load (b1 - lifting of the given values) + lifting of dvals, the unlifted load load fpart1, and the energy shift
   1/2 u_D K u_D - f.u_D. */
static PetscErrorCode ApplyDirichletValues(SgElasticity p)
{
  const SgMesh *m = &p->mesh;
  PetscScalar  *ua;
  PetscReal     uKu, fu;
  PetscScalar   dot;
  Vec           bl;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(p->b, &bl));
  if (!p->bload1) { /* the load of factor 1 without the lifting of the given Dirichlet values */
    PetscCall(VecDuplicate(p->b, &p->bload1));
    PetscCall(Lifting(p, p->ubc1, bl, &uKu));
    PetscCall(VecWAXPY(p->bload1, -1.0, bl, p->b1));
  }
  PetscCall(VecGetArray(p->ubc, &ua));
  for (PetscInt v = 0; v < m->nv; v++)
    if (m->bcmask[v]) {
      PetscReal u[3];
      DirichletValue(p, p->dvals, v, u);
      for (PetscInt d = 0; d < p->dim; d++) ua[m->loff[v] + d] = u[d];
    }
  PetscCall(VecRestoreArray(p->ubc, &ua));
  PetscCall(Lifting(p, p->ubc, bl, &uKu));
  PetscCall(VecWAXPY(p->b, p->load, p->bload1, bl));
  PetscCall(VecAXPBY(p->fpart, p->load, 0.0, p->fpart1));
  PetscCall(VecDot(p->fpart, p->ubc, &dot)); /* local vectors: this rank's cells' part of the load */
  fu = PetscRealPart(dot);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &fu, 1, MPIU_REAL, MPI_SUM, p->comm));
  p->energy_shift = 0.5 * uKu - fu;
  PetscCall(VecNorm(p->b, NORM_2, &p->bnorm));
  PetscCall(VecNorm(p->b, NORM_INFINITY, &p->bnorm_inf));
  PetscCall(VecDestroy(&bl));
  PetscFunctionReturn(0);
}

/* The data at the load factor: the full data times it, or, with Dirichlet values set, those values and the loads
   times it. */
static PetscErrorCode ApplyLoad(SgElasticity p)
{
  const PetscReal t = p->load;

  PetscFunctionBeginUser;
  if (p->dvals_set) {
    PetscCall(ApplyDirichletValues(p));
    PetscFunctionReturn(0);
  }
  PetscCall(VecAXPBY(p->b, t, 0.0, p->b1));
  PetscCall(VecAXPBY(p->ubc, t, 0.0, p->ubc1));
  PetscCall(VecAXPBY(p->fpart, t, 0.0, p->fpart1));
  p->energy_shift = t * t * p->energy_shift1;
  PetscCall(VecNorm(p->b, NORM_2, &p->bnorm));
  PetscCall(VecNorm(p->b, NORM_INFINITY, &p->bnorm_inf));
  PetscFunctionReturn(0);
}

/* Quasi-static load stepping: the body force, the Neumann tractions and the Dirichlet values times t (t = 1: the
   data as given). b, the Dirichlet values, the load part of the energy and its shift scale with t (the shift with
   t^2); K does not change. The full data are copied on the first call, so a run without load steps is untouched.
   Once Dirichlet values were set (SgElasticitySetDirichletValues), t scales the loads only. */
PetscErrorCode SgElasticitySetLoadFactor(SgElasticity p, PetscReal t)
{
  PetscFunctionBeginUser;
  PetscCheck(p->setup, p->comm, PETSC_ERR_ORDER, "SgElasticitySetLoadFactor: call SgElasticitySetUp first");
  PetscCheck(PetscIsNormalReal(t) || t == 0, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "load factor %g: must be finite", (double)t);
  if (t == p->load) PetscFunctionReturn(0);
  PetscCall(KeepFullLoad(p));
  p->load = t;
  PetscCall(ApplyLoad(p));
  PetscFunctionReturn(0);
}

/* Non-proportional loading: the Dirichlet values of every id (dim per id, in the order of the ids) from now on,
   whatever the load factor (which then scales the loads only); NULL: back to the given values times the factor. */
PetscErrorCode SgElasticitySetDirichletValues(SgElasticity p, const PetscReal vals[])
{
  const PetscInt nv = p->dim * PetscMax(p->dirichlet.nids, 1);

  PetscFunctionBeginUser;
  PetscCheck(p->setup, p->comm, PETSC_ERR_ORDER, "SgElasticitySetDirichletValues: call SgElasticitySetUp first");
  if (vals) {
    PetscCheck(!p->mms, p->comm, PETSC_ERR_SUP, "Dirichlet values per load step: not with -mms (its Dirichlet data come from the manufactured field)");
    PetscCheck(p->dirichlet.active, p->comm, PETSC_ERR_ARG_WRONGSTATE, "Dirichlet values per load step: the problem has no Dirichlet part (-dirichlet_label, -dirichlet_ids)");
    for (PetscInt i = 0; i < nv; i++) PetscCheck(PetscIsNormalReal(vals[i]) || vals[i] == 0, p->comm, PETSC_ERR_ARG_OUTOFRANGE, "Dirichlet value %" PetscInt_FMT " is %g, must be finite", i, (double)vals[i]);
  } else if (!p->dvals_set) PetscFunctionReturn(0);
  PetscCall(KeepFullLoad(p));
  for (PetscInt i = 0; vals && i < nv; i++) p->dvals[i] = vals[i];
  p->dvals_set = (PetscBool)(vals != NULL);
  PetscCall(ApplyLoad(p));
  PetscFunctionReturn(0);
}

/* the values of SgElasticitySetDirichletValues (set: whether any were set; vals: SgElasticityGetDirichletSize numbers) */
PetscErrorCode SgElasticityGetDirichletValues(SgElasticity p, PetscBool *set, PetscReal vals[])
{
  PetscFunctionBeginUser;
  *set = p->dvals_set;
  if (p->dvals_set && vals)
    for (PetscInt i = 0; i < p->dim * PetscMax(p->dirichlet.nids, 1); i++) vals[i] = p->dvals[i];
  PetscFunctionReturn(0);
}

/* the number of Dirichlet values SgElasticitySetDirichletValues takes: dim per Dirichlet id (per part without ids) */
PetscErrorCode SgElasticityGetDirichletSize(SgElasticity p, PetscInt *n)
{
  PetscFunctionBeginUser;
  *n = p->dirichlet.active ? p->dim * PetscMax(p->dirichlet.nids, 1) : 0;
  PetscFunctionReturn(0);
}

PetscErrorCode SgElasticityGetLoadFactor(SgElasticity p, PetscReal *t)
{
  PetscFunctionBeginUser;
  *t = p->load;
  PetscFunctionReturn(0);
}

/* The data of the problem as given (factor 1), whatever the factor and the Dirichlet values set now: the load before
   the Dirichlet lifting (a local vector holding this rank's cells' and facets' part: summed over the ranks it is the
   whole load) and the Dirichlet values (local: at the constrained components, 0 elsewhere). Borrowed. */
PetscErrorCode SgElasticityGetFullData(SgElasticity p, Vec *f, Vec *ubc)
{
  PetscFunctionBeginUser;
  if (f) *f = p->fpart1 ? p->fpart1 : p->fpart;
  if (ubc) *ubc = p->ubc1 ? p->ubc1 : p->ubc;
  PetscFunctionReturn(0);
}

/* ||b||_2, ||b||_inf and the energy shift of the full load (factor 1), whatever the factor now */
PetscErrorCode SgElasticityGetFullLoadScales(SgElasticity p, PetscReal *bnorm, PetscReal *bnorm_inf, PetscReal *shift)
{
  const PetscBool full = (PetscBool)!p->b1;

  PetscFunctionBeginUser;
  if (bnorm) *bnorm = full ? p->bnorm : p->bnorm1;
  if (bnorm_inf) *bnorm_inf = full ? p->bnorm_inf : p->bnorm_inf1;
  if (shift) *shift = full ? p->energy_shift : p->energy_shift1;
  PetscFunctionReturn(0);
}

/* Neumaier's compensated sum: s + c carries the sum of the added terms to about one rounding of the result. */
typedef struct {
  PetscReal s, c;
} SgSum;

static inline void SumAdd(SgSum *a, PetscReal x)
{
  const PetscReal t = a->s + x;
  if (PetscAbsReal(a->s) >= PetscAbsReal(x)) a->c += (a->s - t) + x;
  else a->c += (x - t) + a->s;
  a->s = t;
}

typedef struct {
  long double s, c;
} SgSumL;

static inline void SumAddL(SgSumL *a, long double x)
{
  const long double t = a->s + x;
  if (fabsl(a->s) >= fabsl(x)) a->c += (a->s - t) + x;
  else a->c += (x - t) + a->s;
  a->s = t;
}

/* Debug reference of the energy (-elasticity_energy_check): per element 1/2 w^T K_e w with K_e built in long double
   from the coordinates and w = u_e - u_0 (K_e annihilates translations), the load work and the foundation in long
   double; partial sums gathered as pairs of doubles. */
static PetscErrorCode EnergyReference(SgElasticity p, const PetscScalar ya[], const PetscScalar fa[], Vec y, long double *Vref)
{
  const SgMesh      *m = &p->mesh;
  const PetscInt     dim = p->dim, nv = dim + 1;
  SgSumL             el = {0, 0}, ld = {0, 0}, tot = {0, 0};
  PetscInt           nloc, n;
  double             part[4], *all;
  PetscMPIInt        size;

  PetscFunctionBeginUser;
  for (PetscInt c = 0; c < m->nc; c++) {
    const PetscInt *cv = &m->cellv[c * nv];
    long double     J[3][3], Ji[3][3], det, G[4][3], w[12], vol, e = 0;

    for (PetscInt a = 0; a < dim; a++)
      for (PetscInt d = 0; d < dim; d++) J[d][a] = (long double)m->x[cv[a + 1] * dim + d] - (long double)m->x[cv[0] * dim + d];
    if (dim == 2) {
      det      = J[0][0] * J[1][1] - J[0][1] * J[1][0];
      Ji[0][0] = J[1][1] / det;
      Ji[0][1] = -J[0][1] / det;
      Ji[1][0] = -J[1][0] / det;
      Ji[1][1] = J[0][0] / det;
      vol      = fabsl(det) / 2;
    } else {
      det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) + J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
      for (PetscInt i = 0; i < 3; i++)
        for (PetscInt j = 0; j < 3; j++) Ji[i][j] = (J[(j + 1) % 3][(i + 1) % 3] * J[(j + 2) % 3][(i + 2) % 3] - J[(j + 1) % 3][(i + 2) % 3] * J[(j + 2) % 3][(i + 1) % 3]) / det;
      vol = fabsl(det) / 6;
    }
    for (PetscInt d = 0; d < dim; d++) {
      G[0][d] = 0;
      for (PetscInt a = 1; a <= dim; a++) {
        G[a][d] = Ji[a - 1][d];
        G[0][d] -= Ji[a - 1][d];
      }
    }
    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt d = 0; d < dim; d++) w[a * dim + d] = (long double)PetscRealPart(ya[m->loff[cv[a]] + d]) - (long double)PetscRealPart(ya[m->loff[cv[0]] + d]);
    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt i = 0; i < dim; i++)
        for (PetscInt b = 0; b < nv; b++)
          for (PetscInt j = 0; j < dim; j++) {
            long double gg = 0, K;
            for (PetscInt k = 0; k < dim; k++) gg += G[a][k] * G[b][k];
            K = vol * ((long double)p->lambda * G[a][i] * G[b][j] + (long double)p->mu * (G[a][j] * G[b][i] + (i == j ? gg : 0)));
            e += w[a * dim + i] * K * w[b * dim + j];
          }
    SumAddL(&el, e / 2);
  }
  PetscCall(VecGetLocalSize(p->fpart, &nloc));
  for (PetscInt i = 0; i < nloc; i++) SumAddL(&ld, (long double)PetscRealPart(fa[i]) * (long double)PetscRealPart(ya[i]));
  if (p->rigid_shift > 0) {
    const PetscScalar *yg, *mg;
    const long double  cs = (long double)p->rigid_shift * p->E / ((long double)p->diam * p->diam);
    PetscCall(VecGetLocalSize(y, &n));
    PetscCall(VecGetArrayRead(y, &yg));
    PetscCall(VecGetArrayRead(p->mass, &mg));
    for (PetscInt i = 0; i < n; i++) SumAddL(&el, cs * PetscRealPart(mg[i]) * PetscRealPart(yg[i]) * PetscRealPart(yg[i]) / 2);
    PetscCall(VecRestoreArrayRead(y, &yg));
    PetscCall(VecRestoreArrayRead(p->mass, &mg));
  }
  {
    const long double E = el.s + el.c, W = ld.s + ld.c;
    part[0] = (double)E;
    part[1] = (double)(E - (long double)part[0]);
    part[2] = (double)W;
    part[3] = (double)(W - (long double)part[2]);
  }
  PetscCallMPI(MPI_Comm_size(p->comm, &size));
  PetscCall(PetscMalloc1(4 * size, &all));
  PetscCallMPI(MPI_Allgather(part, 4, MPI_DOUBLE, all, 4, MPI_DOUBLE, p->comm));
  for (PetscMPIInt r = 0; r < size; r++) {
    SumAddL(&tot, all[4 * r]);
    SumAddL(&tot, all[4 * r + 1]);
    SumAddL(&tot, -(long double)all[4 * r + 2]);
    SumAddL(&tot, -(long double)all[4 * r + 3]);
  }
  PetscCall(PetscFree(all));
  *Vref = tot.s + tot.c;
  PetscFunctionReturn(0);
}

/* V(y) = 1/2 a(u,u) - L(u) of the full field u (free values y, Dirichlet values from the data), exact to round-off:
   the elastic energy per element, vol (lambda/2 (div u)^2 + mu eps:eps) >= 0 from the displacement differences along
   the edges (no cancellation, as 1/2 y^T K y - b^T y has on fine meshes), the load work f.u with the unlifted load,
   each summed with compensation, and the partial sums of the ranks added in rank order (the same on any rank).
   Costs about one pass over the cells (no matrix product). */
PetscErrorCode SgElasticityEnergy(SgElasticity p, Vec y, PetscReal *V)
{
  const SgMesh      *m = &p->mesh;
  const PetscInt     dim = p->dim, nv = dim + 1;
  Vec                yloc;
  const PetscScalar *ya, *fa;
  SgSum              el = {0, 0}, ld = {0, 0}, tot = {0, 0};
  PetscInt           nloc;
  PetscReal          part[4], *all;
  PetscMPIInt        size;
  PetscLogDouble     t0, t1;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(DMGetLocalVector(p->dm, &yloc));
  PetscCall(SgElasticityGlobalToLocal(p, y, yloc));
  PetscCall(VecGetArrayRead(yloc, &ya));
  PetscCall(VecGetArrayRead(p->fpart, &fa));
  /* every cell is on exactly one rank (no overlap), as in the assembly */
  for (PetscInt c = 0; c < m->nc; c++) {
    const PetscInt *cv = &m->cellv[c * nv];
    PetscReal       xe[12], G[12], vol, H[3][3] = {{0}}, tr = 0, e2 = 0;

    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt d = 0; d < dim; d++) xe[a * dim + d] = m->x[cv[a] * dim + d];
    PetscCall(SgSimplexGradients(dim, xe, G, &vol));
    /* grad u = sum_{a>0} (u_a - u_0) grad phi_a, since the gradients sum to zero */
    for (PetscInt a = 1; a < nv; a++)
      for (PetscInt i = 0; i < dim; i++) {
        const PetscReal du = PetscRealPart(ya[m->loff[cv[a]] + i]) - PetscRealPart(ya[m->loff[cv[0]] + i]);
        for (PetscInt j = 0; j < dim; j++) H[i][j] += du * G[a * dim + j];
      }
    for (PetscInt i = 0; i < dim; i++) {
      tr += H[i][i];
      for (PetscInt j = 0; j < dim; j++) e2 += PetscSqr(0.5 * (H[i][j] + H[j][i]));
    }
    SumAdd(&el, vol * (0.5 * p->lambda * tr * tr + p->mu * e2));
  }
  PetscCall(VecGetLocalSize(p->fpart, &nloc));
  for (PetscInt i = 0; i < nloc; i++)
    if (fa[i] != 0) SumAdd(&ld, PetscRealPart(fa[i]) * PetscRealPart(ya[i]));
  if (p->rigid_shift > 0) { /* the foundation of -elasticity_rigid_shift, on the free dofs this rank owns */
    const PetscScalar *yg, *mg;
    const PetscReal    cs = p->rigid_shift * p->E / PetscSqr(p->diam);
    PetscInt           n;
    PetscCall(VecGetLocalSize(y, &n));
    PetscCall(VecGetArrayRead(y, &yg));
    PetscCall(VecGetArrayRead(p->mass, &mg));
    for (PetscInt i = 0; i < n; i++) SumAdd(&el, 0.5 * cs * PetscRealPart(mg[i]) * PetscSqr(PetscRealPart(yg[i])));
    PetscCall(VecRestoreArrayRead(y, &yg));
    PetscCall(VecRestoreArrayRead(p->mass, &mg));
  }
  part[0] = el.s;
  part[1] = el.c;
  part[2] = ld.s;
  part[3] = ld.c;
  PetscCallMPI(MPI_Comm_size(p->comm, &size));
  PetscCall(PetscMalloc1(4 * size, &all));
  PetscCallMPI(MPI_Allgather(part, 4, MPIU_REAL, all, 4, MPIU_REAL, p->comm));
  for (PetscMPIInt r = 0; r < size; r++) {
    SumAdd(&tot, all[4 * r]);
    SumAdd(&tot, all[4 * r + 1]);
    SumAdd(&tot, -all[4 * r + 2]);
    SumAdd(&tot, -all[4 * r + 3]);
  }
  PetscCall(PetscFree(all));
  *V = tot.s + tot.c;
  PetscCall(PetscTime(&t1));
  if (p->energy_check) {
    long double Vref = 0;
    Vec         Ky;
    PetscScalar yKy, by;
    PetscReal   Vold;

    PetscCall(EnergyReference(p, ya, fa, y, &Vref));
    PetscCall(VecDuplicate(y, &Ky));
    PetscCall(MatMult(p->K, y, Ky));
    PetscCall(VecDot(y, Ky, &yKy));
    PetscCall(VecDot(y, p->b, &by));
    PetscCall(VecDestroy(&Ky));
    Vold = 0.5 * PetscRealPart(yKy) - PetscRealPart(by) + p->energy_shift;
    PetscCall(PetscPrintf(p->comm, "energy check: compensated %.17e (%.3g s), y^T K y formula %.17e, long double reference %.17e; relative errors %.3e (compensated), %.3e (formula)\n", (double)*V, (double)(t1 - t0), (double)Vold, (double)Vref, (double)(fabsl((long double)*V - Vref) / fabsl(Vref)), (double)(fabsl((long double)Vold - Vref) / fabsl(Vref))));
  }
  PetscCall(VecRestoreArrayRead(p->fpart, &fa));
  PetscCall(VecRestoreArrayRead(yloc, &ya));
  PetscCall(DMRestoreLocalVector(p->dm, &yloc));
  PetscFunctionReturn(0);
}

/* Local vector of the full displacement: free values from y, Dirichlet values from the data. */
PetscErrorCode SgElasticityGlobalToLocal(SgElasticity p, Vec y, Vec yloc)
{
  PetscFunctionBeginUser;
  PetscCall(VecCopy(p->ubc, yloc));
  PetscCall(DMGlobalToLocal(p->dm, y, INSERT_VALUES, yloc));
  if (p->npartial) { /* the fixed components of partly fixed vertices: the data, not their (zero) unknowns */
    const PetscScalar *ua;
    PetscScalar       *ya;
    PetscCall(VecGetArrayRead(p->ubc, &ua));
    PetscCall(VecGetArray(yloc, &ya));
    for (PetscInt i = 0; i < p->npartial; i++) ya[p->partial[i]] = ua[p->partial[i]];
    PetscCall(VecRestoreArray(yloc, &ya));
    PetscCall(VecRestoreArrayRead(p->ubc, &ua));
  }
  PetscFunctionReturn(0);
}

/* The displacement on every vertex (Dirichlet ones included) as a global vector of dmVec, for output. */
PetscErrorCode SgElasticityFullDisplacement(SgElasticity p, Vec y, Vec ufull)
{
  Vec                yloc, uloc;
  const PetscScalar *ya;
  PetscScalar       *ua;
  PetscSection       s;

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(p->dm, &yloc));
  PetscCall(DMGetLocalVector(p->dmVec, &uloc));
  PetscCall(SgElasticityGlobalToLocal(p, y, yloc));
  PetscCall(DMGetLocalSection(p->dmVec, &s));
  PetscCall(VecGetArrayRead(yloc, &ya));
  PetscCall(VecGetArray(uloc, &ua));
  for (PetscInt v = 0; v < p->mesh.nv; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(s, p->mesh.vStart + v, &off));
    for (PetscInt d = 0; d < p->dim; d++) ua[off + d] = ya[p->mesh.loff[v] + d];
  }
  PetscCall(VecRestoreArrayRead(yloc, &ya));
  PetscCall(VecRestoreArray(uloc, &ua));
  PetscCall(DMLocalToGlobal(p->dmVec, uloc, INSERT_VALUES, ufull));
  PetscCall(DMRestoreLocalVector(p->dm, &yloc));
  PetscCall(DMRestoreLocalVector(p->dmVec, &uloc));
  PetscFunctionReturn(0);
}

/* Discrete dual norm of a residual: sqrt(sum_j R_j^2 / m_j), m_j the lumped volume of dof j. */
PetscErrorCode SgElasticityDualNorm(SgElasticity p, Vec R, PetscReal *nrm)
{
  Vec w;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(R, &w));
  PetscCall(VecPointwiseMult(w, R, R));
  PetscCall(VecPointwiseDivide(w, w, p->mass));
  PetscCall(VecSum(w, nrm));
  *nrm = PetscSqrtReal(PetscMax(*nrm, 0));
  PetscCall(VecDestroy(&w));
  PetscFunctionReturn(0);
}

/* Per-cell von Mises stress and elastic shear (distortion) energy density mu |dev eps|^2 (plane strain: eps_33 = 0). */
PetscErrorCode SgElasticityCellFields(SgElasticity p, Vec y, Vec vm, Vec wshear)
{
  const SgMesh      *m = &p->mesh;
  const PetscInt     dim = p->dim, nv = dim + 1;
  Vec                yloc, vml, wl;
  const PetscScalar *ya;
  PetscScalar       *va, *wa;
  PetscSection       cs;

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(p->dm, &yloc));
  PetscCall(SgElasticityGlobalToLocal(p, y, yloc));
  PetscCall(DMGetLocalVector(p->dmCell, &vml));
  PetscCall(DMGetLocalVector(p->dmCell, &wl));
  PetscCall(DMGetLocalSection(p->dmCell, &cs));
  PetscCall(VecGetArrayRead(yloc, &ya));
  PetscCall(VecGetArray(vml, &va));
  PetscCall(VecGetArray(wl, &wa));
  for (PetscInt c = 0; c < m->nc; c++) {
    PetscReal xe[12], G[12], vol, eps[3][3] = {{0}}, sig[3][3], tr = 0, dev2 = 0;
    PetscInt  off;

    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt d = 0; d < dim; d++) xe[a * dim + d] = m->x[m->cellv[c * nv + a] * dim + d];
    PetscCall(SgSimplexGradients(dim, xe, G, &vol));
    for (PetscInt a = 0; a < nv; a++) {
      const PetscScalar *u = &ya[m->loff[m->cellv[c * nv + a]]];
      for (PetscInt i = 0; i < dim; i++)
        for (PetscInt j = 0; j < dim; j++) eps[i][j] += 0.5 * (PetscRealPart(u[i]) * G[a * dim + j] + PetscRealPart(u[j]) * G[a * dim + i]);
    }
    for (PetscInt i = 0; i < 3; i++) tr += eps[i][i];
    for (PetscInt i = 0; i < 3; i++)
      for (PetscInt j = 0; j < 3; j++) {
        const PetscReal de = eps[i][j] - (i == j ? tr / 3 : 0);
        sig[i][j]          = 2 * p->mu * eps[i][j] + (i == j ? p->lambda * tr : 0);
        dev2 += de * de;
      }
    PetscCall(PetscSectionGetOffset(cs, m->cStart + c, &off));
    va[off] = PetscSqrtReal(0.5 * (PetscSqr(sig[0][0] - sig[1][1]) + PetscSqr(sig[1][1] - sig[2][2]) + PetscSqr(sig[2][2] - sig[0][0])) + 3 * (PetscSqr(sig[0][1]) + PetscSqr(sig[1][2]) + PetscSqr(sig[0][2])));
    wa[off] = p->mu * dev2;
  }
  PetscCall(VecRestoreArrayRead(yloc, &ya));
  PetscCall(VecRestoreArray(vml, &va));
  PetscCall(VecRestoreArray(wl, &wa));
  PetscCall(DMLocalToGlobal(p->dmCell, vml, INSERT_VALUES, vm));
  PetscCall(DMLocalToGlobal(p->dmCell, wl, INSERT_VALUES, wshear));
  PetscCall(DMRestoreLocalVector(p->dmCell, &vml));
  PetscCall(DMRestoreLocalVector(p->dmCell, &wl));
  PetscCall(DMRestoreLocalVector(p->dm, &yloc));
  PetscFunctionReturn(0);
}

/* The element force K_e u_e of cell c (nv dim numbers, vertex by vertex) at the local displacement ya, and the cell's
   volume: the support and reaction forces below are sums of these over the cells at fixed components. */
static PetscErrorCode CellForce(SgElasticity p, PetscInt c, const PetscScalar ya[], PetscReal fe[], PetscReal *vol)
{
  const SgMesh   *m = &p->mesh;
  const PetscInt  dim = p->dim, nv = dim + 1, ne = nv * dim;
  const PetscInt *cv  = &m->cellv[c * nv];
  PetscReal       xe[12], Ke[144], ue[12];

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < nv; a++)
    for (PetscInt d = 0; d < dim; d++) {
      xe[a * dim + d] = m->x[cv[a] * dim + d];
      ue[a * dim + d] = PetscRealPart(ya[m->loff[cv[a]] + d]);
    }
  PetscCall(SgElementStiffness(dim, xe, p->lambda, p->mu, Ke, vol));
  for (PetscInt i = 0; i < ne; i++) {
    fe[i] = 0;
    for (PetscInt j = 0; j < ne; j++) fe[i] += Ke[i * ne + j] * ue[j];
  }
  PetscFunctionReturn(0);
}

/* Total reaction force on the Dirichlet vertices, sum_D (K u - f)_D (u with its Dirichlet values). With the contact
   forces it balances the loads: R = sum_i w_i lam_i n_i - sum f. */
PetscErrorCode SgElasticityReaction(SgElasticity p, Vec y, PetscReal R[3])
{
  const SgMesh      *m = &p->mesh;
  const PetscInt     dim = p->dim, nv = dim + 1;
  Vec                yloc;
  const PetscScalar *ya;
  PetscReal          loc[3] = {0, 0, 0};

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(p->dm, &yloc));
  PetscCall(SgElasticityGlobalToLocal(p, y, yloc));
  PetscCall(VecGetArrayRead(yloc, &ya));
  /* every cell is on exactly one rank, so the element sums need no ownership bookkeeping */
  for (PetscInt c = 0; c < m->nc; c++) {
    const PetscInt *cv = &m->cellv[c * nv];
    PetscReal       fe[12], vol;
    PetscBool       has = PETSC_FALSE;

    for (PetscInt a = 0; a < nv; a++) has = (PetscBool)(has || m->bcmask[cv[a]]);
    if (!has) continue;
    PetscCall(CellForce(p, c, ya, fe, &vol));
    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt i = 0; i < dim; i++)
        if (SgMeshFixed(m, cv[a], i)) loc[i] += fe[a * dim + i] - vol / nv * p->body_force[i];
  }
  PetscCall(VecRestoreArrayRead(yloc, &ya));
  PetscCall(DMRestoreLocalVector(p->dm, &yloc));
  if (p->neumann.nvalues) { /* traction on the Neumann facets' Dirichlet vertices */
    PetscInt nfac, *facets, *part;
    PetscCall(SgBoundaryGetFacets(p->dm, &p->neumann, &nfac, &facets, &part));
    for (PetscInt f = 0; f < nfac; f++) {
      PetscInt  fv[3], nfv;
      PetscReal area, nrm[3];
      PetscCall(SgFacetGeometry(p->dm, m, facets[f], &nfv, fv, &area, nrm));
      for (PetscInt a = 0; a < nfv; a++)
        for (PetscInt d = 0; d < dim; d++)
          if (SgMeshFixed(m, fv[a], d)) loc[d] -= area / nfv * p->neumann.values[part[f] * dim + d];
    }
    PetscCall(PetscFree2(facets, part));
  }
  PetscCallMPI(MPI_Allreduce(loc, R, 3, MPIU_REAL, MPI_SUM, p->comm));
  PetscFunctionReturn(0);
}

/* The forces on the body at the displacement y (free dofs), for the force scale and the force balance of the KKT
   measures (SgContactKKT): fmax the largest nodal load component on the free dofs, smax the largest nodal support force
   component (K u - f on the Dirichlet-fixed components, and the elastic foundation of -elasticity_rigid_shift), fsum
   the resultant of loads and support forces on the body, fl1 the sum of their nodal components' magnitudes. Only the
   cells at the Dirichlet part are visited: the cost of the measures stays that of a product with K. */
PetscErrorCode SgElasticityForces(SgElasticity p, Vec y, PetscReal *fmax, PetscReal *smax, PetscReal fsum[3], PetscReal *fl1)
{
  const SgMesh      *m = &p->mesh;
  const PetscInt     dim = p->dim, nv = dim + 1;
  Vec                yloc, sloc, sg, fg;
  const PetscScalar *ya, *pa, *fa;
  PetscScalar       *sa;
  PetscSection       vs;
  PetscReal          loc[7] = {0, 0, 0, 0, 0, 0, 0}, nrm[4];

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(p->dm, &yloc));
  PetscCall(SgElasticityGlobalToLocal(p, y, yloc));
  PetscCall(DMGetLocalSection(p->dmVec, &vs));
  PetscCall(DMGetLocalVector(p->dmVec, &sloc));
  PetscCall(VecZeroEntries(sloc));
  PetscCall(VecGetArrayRead(yloc, &ya));
  PetscCall(VecGetArrayRead(p->fpart, &pa));
  PetscCall(VecGetArray(sloc, &sa));
  /* support forces: every cell is on exactly one rank and fpart holds this rank's cells' and facets' loads, so the
     parts of a vertex shared by ranks add up to its force */
  for (PetscInt c = 0; c < m->nc; c++) {
    const PetscInt *cv = &m->cellv[c * nv];
    PetscReal       fe[12], vol;
    PetscBool       has = PETSC_FALSE;

    for (PetscInt a = 0; a < nv; a++) has = (PetscBool)(has || m->bcmask[cv[a]]);
    if (!has) continue;
    PetscCall(CellForce(p, c, ya, fe, &vol));
    for (PetscInt a = 0; a < nv; a++) {
      PetscInt off;
      if (!m->bcmask[cv[a]]) continue;
      PetscCall(PetscSectionGetOffset(vs, m->vStart + cv[a], &off));
      for (PetscInt i = 0; i < dim; i++)
        if (SgMeshFixed(m, cv[a], i)) sa[off + i] += fe[a * dim + i];
    }
  }
  /* K u = f + s on a fixed component: the support force on the body s = K u - f; with the load f there the
     resultant gains K u */
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt off;
    if (!m->bcmask[v]) continue;
    PetscCall(PetscSectionGetOffset(vs, m->vStart + v, &off));
    for (PetscInt d = 0; d < dim; d++)
      if (SgMeshFixed(m, v, d)) {
        loc[d] += PetscRealPart(sa[off + d]);
        sa[off + d] -= PetscRealPart(pa[m->loff[v] + d]);
      }
  }
  PetscCall(VecRestoreArray(sloc, &sa));
  PetscCall(VecRestoreArrayRead(p->fpart, &pa));
  PetscCall(VecRestoreArrayRead(yloc, &ya));
  PetscCall(DMRestoreLocalVector(p->dm, &yloc));
  PetscCall(DMGetGlobalVector(p->dmVec, &sg));
  PetscCall(VecZeroEntries(sg));
  PetscCall(DMLocalToGlobal(p->dmVec, sloc, ADD_VALUES, sg));
  PetscCall(DMRestoreLocalVector(p->dmVec, &sloc));
  PetscCall(VecNorm(sg, NORM_INFINITY, &nrm[0]));
  PetscCall(VecNorm(sg, NORM_1, &nrm[1]));
  PetscCall(DMRestoreGlobalVector(p->dmVec, &sg));
  /* the loads on the free dofs (those on the fixed components went into the support forces) */
  PetscCall(DMGetGlobalVector(p->dm, &fg));
  PetscCall(VecZeroEntries(fg));
  PetscCall(DMLocalToGlobal(p->dm, p->fpart, ADD_VALUES, fg));
  if (m->nfree_glob) {
    PetscScalar *ga;
    PetscCall(VecGetArray(fg, &ga));
    for (PetscInt v = 0; v < m->nv; v++)
      if (m->goff[v] >= 0 && SgMeshPartial(m, v))
        for (PetscInt d = 0; d < dim; d++)
          if (SgMeshFixed(m, v, d)) ga[m->goff[v] + d] = 0;
    for (PetscInt v = 0; v < m->nv; v++)
      if (m->goff[v] >= 0)
        for (PetscInt d = 0; d < dim; d++) loc[3 + d] += PetscRealPart(ga[m->goff[v] + d]);
    PetscCall(VecRestoreArray(fg, &ga));
  }
  PetscCall(VecNorm(fg, NORM_INFINITY, &nrm[2]));
  PetscCall(VecNorm(fg, NORM_1, &nrm[3]));
  if (p->rigid_shift > 0) { /* the foundation's force -k M y on the body is a support force */
    const PetscReal k = p->rigid_shift * p->E / PetscSqr(p->diam);
    PetscReal       fmx = 0;
    PetscCall(VecPointwiseMult(fg, p->mass, y));
    PetscCall(VecGetArrayRead(fg, &fa));
    for (PetscInt v = 0; v < m->nv; v++)
      if (m->goff[v] >= 0)
        for (PetscInt d = 0; d < dim; d++) {
          loc[d] -= k * PetscRealPart(fa[m->goff[v] + d]);
          loc[6] += k * PetscAbsReal(PetscRealPart(fa[m->goff[v] + d]));
          fmx = PetscMax(fmx, k * PetscAbsReal(PetscRealPart(fa[m->goff[v] + d])));
        }
    PetscCall(VecRestoreArrayRead(fg, &fa));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &fmx, 1, MPIU_REAL, MPI_MAX, p->comm));
    nrm[0] = PetscMax(nrm[0], fmx);
  }
  PetscCall(DMRestoreGlobalVector(p->dm, &fg));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, loc, 7, MPIU_REAL, MPI_SUM, p->comm));
  if (fmax) *fmax = nrm[2];
  if (smax) *smax = nrm[0];
  for (PetscInt d = 0; fsum && d < 3; d++) fsum[d] = d < dim ? loc[d] + loc[3 + d] : 0;
  if (fl1) *fl1 = nrm[1] + nrm[3] + loc[6];
  PetscFunctionReturn(0);
}

/* Displacement and force scales of the data, for the KKT measures when the displacement is (nearly) zero: the largest
   Dirichlet value now (ucur) and at factor 1 (ufull: the values given, whatever the load factor or the values set per
   step), ||b||_inf at factor 1 (bfull: the largest nodal force, with the lifting of the Dirichlet values), the total
   load at factor 1 (floads: ||f||_1 on the free dofs, without that lifting) and the diameter of the mesh. */
PetscErrorCode SgElasticityGetDataScales(SgElasticity p, PetscReal *ucur, PetscReal *ufull, PetscReal *bfull, PetscReal *floads, PetscReal *diam)
{
  PetscReal u[2] = {0, 0};
  Vec       fg;

  PetscFunctionBeginUser;
  PetscCall(VecNorm(p->ubc, NORM_INFINITY, &u[0]));
  PetscCall(VecNorm(p->ubc1 ? p->ubc1 : p->ubc, NORM_INFINITY, &u[1]));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, u, 2, MPIU_REAL, MPI_MAX, p->comm));
  if (ucur) *ucur = u[0];
  if (ufull) *ufull = u[1];
  if (bfull) *bfull = p->b1 ? p->bnorm_inf1 : p->bnorm_inf;
  if (floads) {
    PetscCall(DMGetGlobalVector(p->dm, &fg));
    PetscCall(VecZeroEntries(fg));
    PetscCall(DMLocalToGlobal(p->dm, p->fpart1 ? p->fpart1 : p->fpart, ADD_VALUES, fg));
    PetscCall(VecNorm(fg, NORM_1, floads));
    PetscCall(DMRestoreGlobalVector(p->dm, &fg));
  }
  if (diam) *diam = p->diam;
  PetscFunctionReturn(0);
}

/* L2 and H1-seminorm errors against the manufactured solution. */
PetscErrorCode SgElasticityMMSErrors(SgElasticity p, Vec y, PetscReal *l2, PetscReal *h1)
{
  const SgMesh      *m = &p->mesh;
  const PetscInt     dim = p->dim, nv = dim + 1;
  Vec                yloc;
  const PetscScalar *ya;
  PetscReal          e[2] = {0, 0}, *lq, *wq;
  PetscInt           nq;

  PetscFunctionBeginUser;
  PetscCheck(p->mms, p->comm, PETSC_ERR_ARG_WRONGSTATE, "errors need -mms");
  PetscCall(SimplexQuadrature(dim, &nq, &lq, &wq));
  PetscCall(DMGetLocalVector(p->dm, &yloc));
  PetscCall(SgElasticityGlobalToLocal(p, y, yloc));
  PetscCall(VecGetArrayRead(yloc, &ya));
  for (PetscInt c = 0; c < m->nc; c++) {
    PetscReal xe[12], ue[12], G[12], vol, gh[9] = {0};
    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt d = 0; d < dim; d++) {
        xe[a * dim + d] = m->x[m->cellv[c * nv + a] * dim + d];
        ue[a * dim + d] = PetscRealPart(ya[m->loff[m->cellv[c * nv + a]] + d]);
      }
    PetscCall(SgSimplexGradients(dim, xe, G, &vol));
    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt k = 0; k < dim; k++)
        for (PetscInt j = 0; j < dim; j++) gh[k * dim + j] += ue[a * dim + k] * G[a * dim + j];
    for (PetscInt q = 0; q < nq; q++) {
      PetscReal xq[3] = {0, 0, 0}, u[3], g[9], uh[3] = {0, 0, 0};
      for (PetscInt a = 0; a < nv; a++)
        for (PetscInt d = 0; d < dim; d++) {
          xq[d] += lq[q * nv + a] * xe[a * dim + d];
          uh[d] += lq[q * nv + a] * ue[a * dim + d];
        }
      MMSExact(dim, xq, u, g);
      for (PetscInt d = 0; d < dim; d++) e[0] += vol * wq[q] * PetscSqr(u[d] - uh[d]);
      for (PetscInt d = 0; d < dim * dim; d++) e[1] += vol * wq[q] * PetscSqr(g[d] - gh[d]);
    }
  }
  PetscCall(VecRestoreArrayRead(yloc, &ya));
  PetscCall(DMRestoreLocalVector(p->dm, &yloc));
  PetscCall(PetscFree2(lq, wq));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, e, 2, MPIU_REAL, MPI_SUM, p->comm));
  *l2 = PetscSqrtReal(e[0]);
  *h1 = PetscSqrtReal(e[1]);
  PetscFunctionReturn(0);
}

/* The reactions on the fixed components of partly fixed vertices: R (a global vector like y) holds (K u - f) there, u
   the full displacement (the Dirichlet values on those components) and K, f unconstrained; 0 elsewhere. With the
   contact and friction forces (which the free components balance) they are what holds a vertex whose tangential
   motion is prescribed (friction with prescribed slip, SgContactKKT). */
PetscErrorCode SgElasticityFixedResidual(SgElasticity p, Vec y, Vec R)
{
  const SgMesh      *m = &p->mesh;
  const PetscInt     dim = p->dim, nv = dim + 1;
  Vec                yloc, rloc;
  const PetscScalar *ya, *fa;
  PetscScalar       *ra;

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(R));
  PetscCall(DMGetLocalVector(p->dm, &yloc));
  PetscCall(DMGetLocalVector(p->dm, &rloc));
  PetscCall(SgElasticityGlobalToLocal(p, y, yloc));
  PetscCall(VecZeroEntries(rloc));
  PetscCall(VecGetArrayRead(yloc, &ya));
  PetscCall(VecGetArrayRead(p->fpart, &fa));
  PetscCall(VecGetArray(rloc, &ra));
  for (PetscInt c = 0; c < m->nc; c++) {
    const PetscInt *cv = &m->cellv[c * nv];
    PetscReal       fe[12], vol;
    PetscBool       has = PETSC_FALSE;

    for (PetscInt a = 0; a < nv; a++) has = (PetscBool)(has || SgMeshPartial(m, cv[a]));
    if (!has) continue;
    PetscCall(CellForce(p, c, ya, fe, &vol));
    for (PetscInt a = 0; a < nv; a++) {
      if (!SgMeshPartial(m, cv[a])) continue;
      for (PetscInt i = 0; i < dim; i++)
        if (SgMeshFixed(m, cv[a], i)) ra[m->loff[cv[a]] + i] += fe[a * dim + i];
    }
  }
  /* the loads of this rank's cells and facets (the unlifted load): subtracted once per local copy */
  for (PetscInt v = 0; v < m->nv; v++)
    if (SgMeshPartial(m, v))
      for (PetscInt d = 0; d < dim; d++)
        if (SgMeshFixed(m, v, d)) ra[m->loff[v] + d] -= fa[m->loff[v] + d];
  PetscCall(VecRestoreArray(rloc, &ra));
  PetscCall(VecRestoreArrayRead(p->fpart, &fa));
  PetscCall(VecRestoreArrayRead(yloc, &ya));
  PetscCall(DMLocalToGlobal(p->dm, rloc, ADD_VALUES, R));
  PetscCall(DMRestoreLocalVector(p->dm, &yloc));
  PetscCall(DMRestoreLocalVector(p->dm, &rloc));
  PetscFunctionReturn(0);
}

/* the Dirichlet part (its label, ids and the components fixed per id) */
PetscErrorCode SgElasticityGetDirichletBoundary(SgElasticity p, const SgBoundary **bnd)
{
  PetscFunctionBeginUser;
  *bnd = &p->dirichlet;
  PetscFunctionReturn(0);
}
