// Example 1's body [0,3]x[0,1] as an unstructured triangle mesh with named boundary parts.
// gmsh -2 beam.geo -o beam.msh   (lc sets the mesh size; -setnumber lc 0.05 for a finer mesh)
If (!Exists(lc)) lc = 0.1; EndIf
Point(1) = {0, 0, 0, lc};
Point(2) = {3, 0, 0, lc};
Point(3) = {3, 1, 0, lc};
Point(4) = {0, 1, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
// tags follow the box face markers: 1 bottom, 2 right, 3 top, 4 left
Physical Curve("contact", 1) = {1};
Physical Curve("loaded", 2) = {2};
Physical Curve("free", 3) = {3};
Physical Curve("clamped", 4) = {4};
Physical Surface("body", 10) = {1};
