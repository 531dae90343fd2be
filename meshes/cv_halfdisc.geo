// Elastic half disc of radius 1, plane strain (tests/verification/curved.ini, bench/perf_curved.py): the disc of radius 1 centred at
// (0,1) cut by y <= 1, its arc down, touching the plane y = 0 at the origin, its flat side up (y = 1). By default the
// half x >= 0 of it (a roller u_x = 0 on x = 0); with -setnumber full 1 the whole half disc (no roller: the rigidly
// turned copies of tests/verification/curved.ini need Dirichlet data along the axes only). Triangles refined towards the origin
// (h_min 0.01, h_max 0.2 at scale 1); `scale` divides every size:
//   gmsh -2 -setnumber scale 2 cv_halfdisc.geo -o cv_halfdisc_s2.msh
// Physical tags, "Face Sets" values: 1 arc (contact), 2 top (y = 1), 6 left (x = 0, the roller; absent when full).
If (!Exists(scale)) scale = 1; EndIf
If (!Exists(full)) full = 0; EndIf
SetFactory("OpenCASCADE");
Point(1) = {0, 1, 0};
Point(2) = {1, 1, 0};
Point(3) = {0, 0, 0};
Point(4) = {-1, 1, 0};
Circle(1) = {2, 1, 3};
If (full)
  Circle(2) = {3, 1, 4};
  Line(3) = {4, 2};
  Curve Loop(1) = {1, 2, 3};
  Plane Surface(1) = {1};
  Physical Curve(1) = {1, 2};
  Physical Curve(2) = {3};
Else
  Line(2) = {3, 1};
  Line(3) = {1, 2};
  Curve Loop(1) = {1, 2, 3};
  Plane Surface(1) = {1};
  Physical Curve(1) = {1};
  Physical Curve(2) = {3};
  Physical Curve(6) = {2};
EndIf
Physical Surface(10) = {1};
hmin = 0.01 / scale;
hmax = 0.2 / scale;
Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, %g + 0.25 * Sqrt(x^2 + y^2) / %g)", hmax, hmin, scale);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Binary = 0;
