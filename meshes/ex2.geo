// Example 2 of Stadler (2007): the block [-0.5,0.5] x [-1,1] x [-0.5,0.5] pressed onto a half-ball.
// Tetrahedra refined in and around the contact zone below (-0.3, 0): the size grows linearly with the distance
// from (-0.3, 0, -0.5). Default: about the paper's 31,453 tetrahedra. `scale` divides every size:
//   gmsh -3 ex2.geo -o ex2.msh                      (default)
//   gmsh -3 -setnumber scale 4 ex2.geo -o ex2_s4.msh (about 64 times more cells, over 1e6 unknowns)
If (!Exists(scale)) scale = 1; EndIf
SetFactory("OpenCASCADE");
Box(1) = {-0.5, -1, -0.5, 1, 2, 1};
// OpenCASCADE numbers the box faces x-, x+, y-, y+, z-, z+
Physical Surface("bottom", 1) = {5};
Physical Surface("top", 2) = {6};
Physical Surface("sides", 3) = {1, 2, 3, 4};
Physical Volume("body", 10) = {1};
hmin = 0.012 / scale;
hmax = 0.068 / scale;
Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, %g + 0.24 * Sqrt((x + 0.3)^2 + y^2 + (z + 0.5)^2) / %g)", hmax, hmin, scale);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm3D = 1;
Mesh.Binary = 0;
