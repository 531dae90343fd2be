/* contact/obstacle_meshimpl.h: the meshed obstacle (a triangulated surface, obstacle_mesh.c): what its files share
   (obstacle_mesh.c the tree, the queries and the set-up; obstacle_mesh_file.c reading STL and .msh files;
   obstacle_mesh_surface.c the welded, checked and oriented surface); included by these files only */
#pragma once

#include "contact/contactimpl.h"

typedef struct {
  double   lo[3], hi[3];
  PetscInt left;         /* internal: the first child (the second is left + 1) */
  PetscInt start, count; /* leaf (count > 0): elements perm[start .. start + count) */
} MeshNode;

/* a growing list of element vertex coordinates (3 per vertex, nv vertices per element) */
typedef struct {
  double  *v;
  PetscInt n, cap; /* elements */
} Soup;

typedef struct {
  char      file[PETSC_MAX_PATH_LEN];
  PetscReal shift[3], scale; /* placement: a file point z sits at scale z + shift (-obstacle_cad_translation/scale) */
  PetscInt  nv;              /* vertices per element: 3 (triangles) or 2 (segments) */
  PetscInt  nel, nvert, nedge;
  double   *x;     /* vertex coordinates, 3 each */
  PetscInt *el;    /* element vertices, nv each */
  double   *nrm;   /* element unit normals, 3 each */
  PetscInt *eedge; /* 3D: edge k of triangle e joins its vertices k and k + 1 */
  double   *enrm;  /* 3D: edge pseudo-normals (sum of the adjacent faces' normals), 3 each */
  double   *vnrm;  /* vertex pseudo-normals (angle-weighted sum of the incident elements' normals), 3 each */
  MeshNode *node;
  PetscInt  nnode;
  PetscInt *perm;
  double    len;  /* diagonal of the bounding box */
  char     *vbnd; /* a vertex on the boundary of an open surface (3D: of a boundary edge; 2D: of one segment) */
  char     *ebnd; /* 3D: an edge of one triangle (the boundary of an open surface) */
  PetscInt  nquery;
  Soup      soup; /* the elements as read (freed after set-up) */
} Obstacle_Mesh;

typedef struct {
  double   key;
  PetscInt id;
} KeyId;

static inline int CompareKeyId(const void *a, const void *b)
{
  const KeyId *x = (const KeyId *)a, *y = (const KeyId *)b;
  return x->key < y->key ? -1 : x->key > y->key ? 1
                                                : (x->id > y->id) - (x->id < y->id);
}

static inline double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline const double *Vtx(const Obstacle_Mesh *m, PetscInt e, PetscInt k)
{
  return &m->x[3 * m->el[m->nv * e + k]];
}

PetscErrorCode SgObstacleMeshRead(SgObstacle, const char[], Soup *);                  /* obstacle_mesh_file.c: the elements of the file */
PetscErrorCode SgObstacleMeshBuildSurface(SgObstacle, Obstacle_Mesh *, const Soup *); /* obstacle_mesh_surface.c */
PetscErrorCode SgObstacleMeshOrient(SgObstacle, Obstacle_Mesh *);
