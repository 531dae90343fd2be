// The elastic block [-1,1] x [-1,0] standing for the half plane of the 2D (plane strain) Cattaneo-Mindlin check
// (options/cattaneo.opts, tests/cattaneo.py): a rigid cylinder (contact half width a about 0.04, a 25th of the
// block's half width and depth) indents the middle of its top face. Triangles in the plane z = 0. Under the contact,
// the rectangle |x| <= 0.08 (twice a), -0.06 <= y <= 0 is a structured mesh of squares of side hmin, each split by a
// diagonal in alternating directions (symmetric about x = 0). An unstructured mesh of the same spacing at the contact
// (h/a = 0.05) gave nodal shear tractions 0.11-0.12 F p0 (rms) off Cattaneo's profile, this one 0.05-0.10, and a
// stick zone 0.025 a off centre (one vertex), here 0. Elsewhere the size grows linearly with the distance from that
// rectangle. `scale` divides every size:
//   gmsh -2 -setnumber scale 2 cattaneo.geo -o cattaneo_s2.msh
// Physical tags follow the 2D box face markers (values of "Face Sets"): 1 bottom, 2 right, 3 top (contact), 4 left.
If (!Exists(scale)) scale = 1; EndIf
L = 1;
b = 0.08;
d = 0.06;
hmin = 0.004 / scale;
hmax = 0.1 / scale;
Point(1) = {-L, -L, 0};
Point(2) = {L, -L, 0};
Point(3) = {L, 0, 0};
Point(4) = {b, 0, 0};
Point(5) = {-b, 0, 0};
Point(6) = {-L, 0, 0};
Point(7) = {b, -d, 0};
Point(8) = {-b, -d, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Line(7) = {4, 7};
Line(8) = {7, 8};
Line(9) = {8, 5};
Transfinite Curve{4, 8} = Round(2 * b / hmin) + 1;
Transfinite Curve{7, 9} = Round(d / hmin) + 1;
Curve Loop(1) = {1, 2, 3, 7, 8, 9, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {4, -9, -8, -7};
Plane Surface(2) = {2};
Transfinite Surface{2} = {4, 5, 8, 7} Alternate;
Physical Curve("bottom", 1) = {1};
Physical Curve("right", 2) = {2};
Physical Curve("top", 3) = {3, 4, 5};
Physical Curve("left", 4) = {6};
Physical Surface("body", 10) = {1, 2};
Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, %g + 0.1 * Sqrt(Max(Fabs(x) - %g, 0)^2 + Max(-y - %g, 0)^2))", hmax, hmin, b, d);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Binary = 0;
