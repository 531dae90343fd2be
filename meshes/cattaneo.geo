// The elastic block [-1,1] x [-1,0] standing for the half plane of the 2D (plane strain) Cattaneo-Mindlin check
// (options/cattaneo.opts, tests/cattaneo.py): a rigid cylinder (contact half width a about 0.04, a 25th of the
// block's half width and depth) indents the middle of its top face. Triangles in the plane z = 0: the top face's
// middle part |x| <= 0.08 (twice a) carries equally spaced vertices (spacing hmin), elsewhere the size grows
// linearly with the distance from that segment. `scale` divides every size:
//   gmsh -2 -setnumber scale 2 cattaneo.geo -o cattaneo_s2.msh
// Physical tags follow the 2D box face markers (values of "Face Sets"): 1 bottom, 2 right, 3 top (contact), 4 left.
If (!Exists(scale)) scale = 1; EndIf
L = 1;
b = 0.08;
hmin = 0.004 / scale;
hmax = 0.1 / scale;
Point(1) = {-L, -L, 0};
Point(2) = {L, -L, 0};
Point(3) = {L, 0, 0};
Point(4) = {b, 0, 0};
Point(5) = {-b, 0, 0};
Point(6) = {-L, 0, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Transfinite Curve{4} = Round(2 * b / hmin) + 1;
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Physical Curve("bottom", 1) = {1};
Physical Curve("right", 2) = {2};
Physical Curve("top", 3) = {3, 4, 5};
Physical Curve("left", 4) = {6};
Physical Surface("body", 10) = {1};
Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, %g + 0.1 * Sqrt(Max(Fabs(x) - %g, 0)^2 + y^2))", hmax, hmin, b);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Binary = 0;
