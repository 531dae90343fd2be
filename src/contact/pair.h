#pragma once
/* A contact pair between two elastic bodies of one mesh (the two-body issue): the slave surface (facets of label
   values) and the master surface (facets of other values of the same label), coupled by the dual mortar integrals of
   mortar.h. Private to the library. */
#include "sg.h"
#include "contact/mortar.h"

typedef struct _n_SgContactPair *SgContactPair;

/* The pair's operators, in the free displacement's numbering (the global vector of SgElasticity: vertex blocks
   gblock, Dirichlet vertices left out):
     D, g0     Vecs of one entry per free vertex: int psi_j over the covered slave surface and the weighted initial gap
               int psi_j g (mortar.h); 0 off the slave surface
     N         Vec of dim entries per free vertex: the row's unit direction: the slave vertex's normal (facet normals
               averaged by area, outward of the slave body), or with -contact_pair_normal average the mean of it and
               the master's opposite normal there; 0 off the slave surface
     B         Mat, one row per free vertex and one column per free dof: row j = n_j^T (D_j e_j - sum_k M_jk e_k), so
               that (B y)_j - g0_j ... is the weighted normal jump: (B y)_j = n_j . (D_j y_j - sum_k M_jk y_k), < 0 when
               the slave moves toward the master
     R         Mat, dim rows per free vertex and one column per free dof: the relative displacement of the slave vertex j
               against the master surface opposite, (R y)_j = y_j - sum_k (M_jk / D_j) y_k, on the rows of the contact
               vertices (D_j > 0 and a normal; the other rows are empty), so that (B y)_j = D_j n_j . (R y)_j; its rows
               and columns of fixed components (rollers) are zeroed like B's columns (friction: the tangential slip of
               the pair, T_j (R y)_j; a component held by a support carries no friction)
   Master vertices of a Dirichlet part that fixes all their components have no dof: their columns are left out (they
   do not move). */
struct _n_SgContactPair {
  MPI_Comm   comm;
  PetscInt   dim;
  PetscInt   nslave;  /* slave vertices opposite the master: the nonzero rows of B (all ranks) */
  PetscInt   ndrop;   /* slave vertices left without a row for a tiny D_j (DropTinyD, all ranks) */
  PetscReal  Ddrop;   /* the sum of their D_j (all ranks) */
  PetscReal  area;    /* covered measure of the slave surface */
  PetscBool *obsrow;  /* per owned free vertex: its row is an obstacle row (SgPairObstacleRows), or NULL */
  PetscInt   nbeyond; /* slave facets without a partner that face the master farther than the pairing distance (all ranks) */
  PetscReal  mbox[6]; /* the bounding box of the bodies the master side lies on: lower and upper corner (all ranks) */
  Vec        D, g0, N;
  Mat        B, R;
};

/* Nodal conditions against a rigid obstacle given to the pair as rows of their own (a rigid obstacle besides the
   pair): n vertices by their local dof offset off[i] (the free displacement's owned part), lumped weight w[i], unit
   normal nrm[dim i..] (outward of the body) and gap d[i]: row off[i] / dim of B becomes w_i n_i^T e_i, D = w_i,
   g0 = w_i d_i. A vertex that has a row of the pair (it faces the master) keeps that one. */
typedef struct {
  PetscInt         n;
  const PetscInt  *off;
  const PetscReal *w, *nrm, *d;
} SgPairObstacleRows;

/* slave, master: the two sides (label and values); dmax: the largest distance along the slave normal at which a
   master facet is a partner (larger than the initial gap, smaller than the bodies' thickness); average: the rows'
   directions the mean of the slave's normal and the master's opposite one (-contact_pair_normal average), else the
   slave's; brute: the mortar search's reference (SgMortarIntegrals); obst: rows against a rigid obstacle, or NULL */
PetscErrorCode SgContactPairCreate(SgElasticity, const SgBoundary *slave, const SgBoundary *master, PetscReal dmax, PetscBool average, PetscBool brute, const SgPairObstacleRows *obst, SgContactPair *);
PetscErrorCode SgContactPairDestroy(SgContactPair *);
void           SgPairIdList(const SgBoundary *, char[], size_t); /* "a,b,c": a side's values, for messages */

/* The phases of the pair's set-up as log events (-log_view; registered on first use): SgPairCollect (the local slave
   and master facets' geometry), SgPairGather (the master surface on every rank), SgPairMortar (the search and the
   mortar integrals of this rank's slave facets), SgPairCheck (the search's report, all ranks), SgPairAssemble (D, g0,
   the normals and M into the free numbering), SgPairBuildB (the normals' averaging and normalization, B and R),
   SgPairPattern (K's pattern extended by B^T B, contact_pair.c) */
typedef enum {
  SG_PAIR_COLLECT,
  SG_PAIR_GATHER,
  SG_PAIR_MORTAR,
  SG_PAIR_CHECK,
  SG_PAIR_ASSEMBLE,
  SG_PAIR_BUILDB,
  SG_PAIR_PATTERN,
  SG_PAIR_NEVENTS
} SgPairPhase;
PetscErrorCode SgPairLogEvent(SgPairPhase, PetscBool begin);
