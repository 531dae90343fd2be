// Cattaneo-Mindlin between two elastic bodies (tests/tbfric.ini): a half disc of radius 1 (centre (0,1), its arc
// down: the slave side) on the block [-1,1] x [-1,0] (its top: the master side), touching at the origin, each meshed on
// its own (the block 1.3 times coarser: the sides do not match). Triangles refined towards the origin (h_min 0.01, growing by a tenth of the distance, up to
// h_max 0.2 at scale 1); `scale` divides every size:
//   gmsh -2 -setnumber scale 2 tbf_cattaneo.geo -o tbf_cattaneo_s2.msh
// "Face Sets": 20 the arc (slave), 2 the disc's top (y = 1); 10 the block's top (master), 1 its bottom. "Cell Sets":
// 2 the disc, 1 the block.
If (!Exists(scale)) scale = 1; EndIf
Point(1) = {0, 1, 0};
Point(2) = {-1, 1, 0};
Point(3) = {0, 0, 0};
Point(4) = {1, 1, 0};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Line(3) = {4, 2};
Curve Loop(1) = {1, 2, 3};
Plane Surface(2) = {1};
Point(11) = {-1, -1e-12, 0};
Point(12) = {0, -1e-12, 0};
Point(13) = {1, -1e-12, 0};
Point(14) = {1, -1, 0};
Point(15) = {-1, -1, 0};
Line(11) = {11, 12};
Line(12) = {12, 13};
Line(13) = {13, 14};
Line(14) = {14, 15};
Line(15) = {15, 11};
Curve Loop(11) = {11, 12, 13, 14, 15};
Plane Surface(1) = {11};
Physical Curve(20) = {1, 2};
Physical Curve(2) = {3};
Physical Curve(10) = {11, 12};
Physical Curve(1) = {14};
Physical Surface(2) = {2};
Physical Surface(1) = {1};
hmin = 0.01 / scale;
hmax = 0.2 / scale;
Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, %g + 0.1 * Sqrt(x^2 + y^2) / %g) * (1.15 - 0.15 * y / (Abs(y) + 1e-12))", hmax, hmin, scale);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
