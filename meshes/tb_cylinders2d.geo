// Two elastic cylinders in contact, plane strain (the two-body issue: tests/verification/twobody.ini, options/twobody_hertz.opts):
// the half x >= 0 of two half discs of radius 1, the upper one centred at (0,1) with its arc down (the slave side),
// the lower one centred at (0,-1) with its arc up (the master side), touching at the origin; each meshed on its own
// (the arcs' vertices do not match: the lower one is meshed 1.3 times coarser). Triangles refined towards the origin
// (h_min 0.01, h_max 0.2 at scale 1); `scale` divides every size:
//   gmsh -2 -setnumber scale 2 tb_cylinders2d.geo -o tb_cylinders2d_s2.msh
// "Face Sets": 20 upper arc (slave), 2 upper top (y = 1), 6 upper left (x = 0); 10 lower arc (master), 1 lower bottom
// (y = -1), 7 lower left (x = 0). "Cell Sets": 2 upper, 1 lower.
If (!Exists(scale)) scale = 1; EndIf
SetFactory("OpenCASCADE");
Point(1) = {0, 1, 0};
Point(2) = {1, 1, 0};
Point(3) = {0, 0, 0};
Circle(1) = {2, 1, 3};
Line(2) = {3, 1};
Line(3) = {1, 2};
Curve Loop(1) = {1, 2, 3};
Plane Surface(2) = {1};
Point(11) = {0, -1, 0};
Point(12) = {1, -1, 0};
Point(13) = {0, -1e-12, 0};
Circle(11) = {13, 11, 12};
Line(12) = {12, 11};
Line(13) = {11, 13};
Curve Loop(11) = {11, 12, 13};
Plane Surface(1) = {11};
Physical Curve(20) = {1};
Physical Curve(2) = {3};
Physical Curve(6) = {2};
Physical Curve(10) = {11};
Physical Curve(1) = {12};
Physical Curve(7) = {13};
Physical Surface(2) = {2};
Physical Surface(1) = {1};
hmin = 0.01 / scale;
hmax = 0.2 / scale;
Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, %g + 0.25 * Sqrt(x^2 + y^2) / %g) * (1.15 - 0.15 * y / (Abs(y) + 1e-12))", hmax, hmin, scale);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
