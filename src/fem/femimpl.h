/* fem/femimpl.h: the elasticity object of the fem layer and what its files share; included by the files of src/fem only */
#pragma once

#include "sg.h"

struct _n_SgElasticity {
  MPI_Comm  comm;
  char     *prefix; /* options prefix (may be NULL) */
  PetscBool setup;
  DM        dm;     /* vertex P1 displacement, Dirichlet vertices constrained in the section */
  DM        dmCell; /* one scalar per cell (cell fields) */
  DM        dmVert; /* one scalar per vertex, no constraints (contact fields) */
  DM        dmVec;  /* dim values per vertex, no constraints (output of the full displacement) */
  SgMesh    mesh;
  PetscInt  dim;
  PetscReal E, nu, lambda, mu; /* the material; of several (nmat > 0), the stiffest (largest E) */
  /* several materials (-material_ids): cell c has material cellmat[c] of the ids matids[] of the cell label matlabel;
     nmat = 0 (and cellmat NULL): E, nu above in every cell */
  PetscInt       nmat, matids[SG_MAX_IDS], *cellmat;
  PetscReal      matE[SG_MAX_IDS], matnu[SG_MAX_IDS], matlambda[SG_MAX_IDS], matmu[SG_MAX_IDS];
  char           matlabel[256];
  PetscReal      body_force[3];
  PetscInt       nbody_force; /* entries given with -body_force (must be dim) */
  SgBoundary     dirichlet, neumann;
  PetscBool      mms;              /* manufactured solution: body force and Dirichlet data from a known field */
  Mat            K;                /* stiffness on the free dofs, block size dim */
  Vec            b;                /* load with the Dirichlet lifting */
  Vec            mass;             /* lumped volume of each free dof's vertex (for the discrete dual norm) */
  Vec            ubc;              /* local vector: Dirichlet values at constrained dofs, 0 elsewhere */
  PetscReal      energy_shift;     /* 1/2 u_D K_DD u_D - f_D u_D: V(y) = 1/2 y K y - b y + energy_shift */
  PetscReal      bnorm, bnorm_inf; /* ||b||_2, the largest nodal force (SgVecVertexNormMax over SgNodalNormSize entries) */
  PetscReal      Knorm;            /* ||K|| per vertex block row (SgMatVertexNorm; ||K||_inf with -contact_kkt_scale component) */
  PetscBool      kkt_vertex;       /* -contact_kkt_scale vertex (PETSC_TRUE) or component: see SgNodalNormSize */
  Vec            fpart;            /* local: this rank's cells' and facets' part of the load without lifting (for the energy) */
  PetscReal      diam;             /* diameter of the mesh's bounding box */
  PetscReal      rigid_shift;      /* -elasticity_rigid_shift: K += rigid_shift E/diam^2 M (lumped volumes M) */
  PetscBool      rigid_shift_set;
  PetscBool      energy_check; /* -elasticity_energy_check: compare the energy with a long double evaluation */
  MatNullSpace   nearnull;     /* rigid-body modes */
  PetscBool      use_nearnull; /* attached to K and the Jacobians */
  PetscInt       ndofs;
  PetscInt       npartial, *partial; /* local offsets of the fixed components of partly fixed vertices */
  PetscLogDouble t_assembly;
  /* load stepping (SgElasticitySetLoadFactor): the loads above are the full ones times load; the full ones are kept
     here once a factor is set (NULL until then) */
  PetscReal load;
  Vec       b1, ubc1, fpart1;
  PetscReal energy_shift1, bnorm1, bnorm_inf1;
  /* non-proportional loading (SgElasticitySetDirichletValues): the Dirichlet values of every id, not scaled by load,
     and the load of factor 1 without the lifting of the given Dirichlet values (NULL until then) */
  PetscBool dvals_set;
  PetscReal dvals[3 * SG_MAX_IDS];
  Vec       bload1;
};

/* the number of entries a nodal norm takes together (vnorm.c): dim with -contact_kkt_scale vertex (a vertex's
   Euclidean length, the same for the problem turned rigidly), 1 with component (the component maxima and sums, the
   paper's scales) */
static inline PetscInt SgNodalNormSize(SgElasticity p)
{
  return p->kkt_vertex ? p->dim : 1;
}
/* What the files of the mesh share (box.c, mesh.c, boundary.c, layout.c) */
/* mirror: left in the lower half of x, right in the upper half, so that the mesh is symmetric about the box's middle
   x = (lower + upper) / 2 and its upper half is the -box_diagonal right mesh of that half (half models) */
typedef enum { SG_BOX_RIGHT,
               SG_BOX_LEFT,
               SG_BOX_MIRROR } SgBoxDiagonal;
/* the structured simplex box of the -box_* options: the entries given of each list (nfaces, nlo, nhi) are checked
   against the dimension when the box is made */
typedef struct {
  PetscInt      dim, nfaces, nlo, nhi, faces[SG_OPT_MAX];
  PetscReal     lo[SG_OPT_MAX], hi[SG_OPT_MAX];
  SgBoxDiagonal diag;
} SgBox;
PetscErrorCode SgBoxFromOptions(MPI_Comm, const char[], SgBox *);
PetscErrorCode SgBoxCreateDM(MPI_Comm, const SgBox *, DM *);
PetscErrorCode SgBoundaryMarkVertices(DM, const SgBoundary *, SgMesh *);

/* What the files of the elasticity share (element.c, mms.c, assembly.c, loading.c, rigid.c, elasticity.c) */
PetscErrorCode SgSimplexQuadrature(PetscInt, PetscInt *, PetscReal **, PetscReal **);
void           SgMMSExact(PetscInt, const PetscReal[], PetscReal[], PetscReal[]);
void           SgMMSForce(PetscInt, PetscReal, PetscReal, const PetscReal[], PetscReal[]);
PetscErrorCode SgElasticityFillDirichletValues(SgElasticity, const PetscReal[]);
void           SgMeshZeroFixedComponents(const SgMesh *, PetscInt, PetscScalar[]);
PetscErrorCode SgElasticityAssemble(SgElasticity);
PetscErrorCode SgElasticityCheckRigidMotions(SgElasticity);
PetscErrorCode SgElasticityCreateNearNullSpace(SgElasticity);
PetscErrorCode SgElasticitySetUpMaterials(SgElasticity);
/* the Lame constants of local cell c */
static inline void SgElasticityCellLame(SgElasticity p, PetscInt c, PetscReal *lambda, PetscReal *mu)
{
  if (p->cellmat) {
    *lambda = p->matlambda[p->cellmat[c]];
    *mu     = p->matmu[p->cellmat[c]];
  } else {
    *lambda = p->lambda;
    *mu     = p->mu;
  }
}
