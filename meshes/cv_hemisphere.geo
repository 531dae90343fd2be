// Quarter of an elastic hemisphere of radius 1 (tests/verification/curved.ini, bench/perf_curved.py): the ball of radius 1 centred
// at (0,0,1) cut by z <= 1, x >= 0, y >= 0; its curved face down, touching the plane z = 0 at the origin; its flat face
// up (z = 1). Tetrahedra refined towards the origin: the size grows linearly with the distance from it (h_min 0.02,
// h_max 0.25 at scale 1). `scale` divides every size:
//   gmsh -3 -setnumber scale 2 cv_hemisphere.geo -o cv_hemisphere_s2.msh
// Physical tags, "Face Sets" values (no -dm_plex_gmsh_use_regions): 1 curved face (contact), 2 top (z = 1),
// 3 front (y = 0, roller u_y = 0), 6 left (x = 0, roller u_x = 0); as meshes/hertz.geo.
If (!Exists(scale)) scale = 1; EndIf
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 1, 1, -Pi / 2, 0, Pi / 2};
eps = 1e-6;
top() = Surface In BoundingBox {-eps, -eps, 1 - eps, 1 + eps, 1 + eps, 1 + eps};
front() = Surface In BoundingBox {-eps, -eps, -eps, 1 + eps, eps, 1 + eps};
left() = Surface In BoundingBox {-eps, -eps, -eps, eps, 1 + eps, 1 + eps};
curved() = Surface{:};
curved() -= {top(), front(), left()};
If (#curved() != 1 || #top() != 1 || #front() != 1 || #left() != 1)
  Error("cv_hemisphere.geo: the faces of the quarter hemisphere were not found");
EndIf
Physical Surface(1) = {curved()};
Physical Surface(2) = {top()};
Physical Surface(3) = {front()};
Physical Surface(6) = {left()};
Physical Volume(10) = {1};
hmin = 0.02 / scale;
hmax = 0.25 / scale;
Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, %g + 0.3 * Sqrt(x^2 + y^2 + z^2) / %g)", hmax, hmin, scale);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm3D = 1;
Mesh.Binary = 0;
