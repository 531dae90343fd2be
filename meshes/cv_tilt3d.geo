// Contact patch test on an inclined rigid plane, 3D (tests/verification/curved.ini): the block [0,1] x [0,1] x [0,0.5] turned by
// `angle` degrees (default 25) about the axis (1,2,0) through the origin, so that its bottom face lies on the plane
// through the origin with normal R e_z. Unstructured tetrahedra of size h = 0.2 / scale:
//   gmsh -3 -setnumber scale 1 cv_tilt3d.geo -o cv_tilt3d_s1.msh
// "Face Sets" (no -dm_plex_gmsh_use_regions): 1 bottom (contact), 2 top (pressure), 3 the four sides;
// "Vertex Sets" (-dm_plex_gmsh_mark_vertices): 11, 12, 13 the bottom corners (0,0,0), (1,0,0), (0,1,0) before the
// turn (pins given their exact displacements: options/cv_tilt3d.opts).
If (!Exists(scale)) scale = 1; EndIf
If (!Exists(angle)) angle = 25; EndIf
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 0.5};
eps = 1e-6;
bottom() = Surface In BoundingBox {-eps, -eps, -eps, 1 + eps, 1 + eps, eps};
top() = Surface In BoundingBox {-eps, -eps, 0.5 - eps, 1 + eps, 1 + eps, 0.5 + eps};
sides() = Surface{:};
sides() -= {bottom(), top()};
p1() = Point In BoundingBox {-eps, -eps, -eps, eps, eps, eps};
p2() = Point In BoundingBox {1 - eps, -eps, -eps, 1 + eps, eps, eps};
p3() = Point In BoundingBox {-eps, 1 - eps, -eps, eps, 1 + eps, eps};
Rotate {{1, 2, 0}, {0, 0, 0}, angle * Pi / 180} { Volume{1}; }
Physical Surface(1) = {bottom()};
Physical Surface(2) = {top()};
Physical Surface(3) = {sides()};
Physical Point(11) = {p1()};
Physical Point(12) = {p2()};
Physical Point(13) = {p3()};
Physical Volume(10) = {1};
Mesh.MeshSizeMax = 0.2 / scale;
Mesh.MeshSizeMin = 0.2 / scale;
Mesh.Algorithm3D = 1;
Mesh.Binary = 0;
