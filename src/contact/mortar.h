#pragma once
/* Dual mortar integrals between a slave and a master surface (the two-body issue, ../shared/ALGORITHMS.md section 9).
   Private to the library. The geometry is given as plain arrays (one rank's copy of both surfaces), so that the
   integrals can be tested apart from the meshes. */
#include <petscsys.h>

/* Surfaces of dimension dim-1 in R^dim: 2D segments (2 vertices per facet), 3D triangles (3 vertices per facet).
   Vertex coordinates are x[dim*v + c]; facets list local vertex numbers; nrm[dim*f + c] is the outward unit normal of
   facet f (outward of its body: on the slave surface it points toward the master). */
typedef struct {
  PetscInt         dim;
  PetscInt         nv, nf;
  const PetscReal *x;
  const PetscInt  *facets;
  const PetscReal *nrm;
} SgMortarSurface;

/* The mortar integrals of the slave surface s against the master surface m, projected along each slave facet's normal
   in the reference configuration (segment-to-segment: each slave facet is clipped against the projections of the
   master facets, and the pieces are integrated exactly with a degree-2 rule), psi_j the dual basis on the slave
   facets (2D: 2 phi_j - phi_other; 3D: 3 phi_j - the other two, i.e. 4 phi_j - 1). A master facet is paired with a
   slave facet where its projection overlaps the slave facet, it faces the slave (n_m . n_s < 0), and the distance
   along n_s at the overlap's centroid is at most dmax in size (a closed master body's far side is left out):
     D[j]   = int_{S covered} psi_j ds                    (= int phi_j over a fully covered facet)
     M[k]   = (Mrow[k], Mcol[k], Mval[k]): int_{S covered} psi_j (phi^m_k o pi) ds, j a slave and k a master vertex
     g0[j]  = int_{S covered} psi_j g ds, g the distance along the slave normal from the slave point to the master
              facet (> 0: apart)
   D sums the dual basis only where a master facet lies opposite, so that a rigid translation has no weighted jump:
   D[j] u - sum_k M_jk u = 0. On a fully covered slave facet this is the lumped weight int phi_j (biorthogonality);
   on a partly covered one D[j] may be small or even negative (the dual basis changes sign): the caller decides what
   such a vertex is (a contact vertex of its own, or one left out).
   *area returns the covered measure of the slave surface. The *nM triplets are allocated (PetscFree each array); a
   pair (j, k) may appear several times: add them. */
/* brute: every master facet is tried against every slave facet (the reference of the search: -contact_pair_search
   brute); else a grid of buckets over the master facets finds the candidates (the same integrals, added in the same order).
   *search (may be NULL) reports the slave facets that got no partner within dmax (the bad-input checks of the pair):
   nbeyond of them face a master facet farther than dmax ahead (the bodies apart), and overlap > 0 is the largest
   depth at which such a facet lies behind a facing master facet (the slave facet inside the master body: the bodies
   overlap), foverlap that facet (-1: none). */
typedef struct {
  PetscReal overlap;
  PetscInt  foverlap;
  PetscInt  nbeyond;
} SgMortarSearch;

PetscErrorCode SgMortarIntegrals(const SgMortarSurface *s, const SgMortarSurface *m, PetscReal dmax, PetscBool brute, PetscReal D[], PetscReal g0[], PetscInt *nM, PetscInt **Mrow, PetscInt **Mcol, PetscReal **Mval, PetscReal *area, SgMortarSearch *search);
