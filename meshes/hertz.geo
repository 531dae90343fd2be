// Quarter of a block [0,2] x [0,2] x [0,2] indented at the corner (0,0,0) of its bottom face by a rigid ball (the
// Hertz check of tests/*/rollers.ini): the planes x = 0 and y = 0 are symmetry planes. Tetrahedra refined towards the
// corner: the size grows linearly with the distance from it. `scale` divides every size:
//   gmsh -3 -setnumber scale 2 hertz.geo -o hertz_s2.msh
// Physical tags follow the box face markers (no -dm_plex_gmsh_use_regions: they are values of "Face Sets"):
// 1 bottom (z = 0, contact), 2 top, 3 front (y = 0), 4 back, 5 right, 6 left (x = 0).
If (!Exists(scale)) scale = 1; EndIf
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 2, 2};
// OpenCASCADE numbers the box faces x-, x+, y-, y+, z-, z+
Physical Surface(1) = {5};
Physical Surface(2) = {6};
Physical Surface(3) = {3};
Physical Surface(4) = {4};
Physical Surface(5) = {2};
Physical Surface(6) = {1};
Physical Volume(10) = {1};
hmin = 0.025 / scale;
hmax = 0.5 / scale;
Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, %g + 0.3 * Sqrt(x^2 + y^2 + z^2) / %g)", hmax, hmin, scale);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm3D = 1;
Mesh.Binary = 0;
