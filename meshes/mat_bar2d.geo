// Two materials in series (tests/*/materials.ini): the bar [0,2] x [0,0.5], cells of x < 1 in physical surface 1, of
// x > 1 in 2 (one mesh, the interface x = 1 shared). Unstructured triangles.
// gmsh -2 mat_bar2d.geo -o mat_bar2d.msh
If (!Exists(lc)) lc = 0.125; EndIf
Point(1) = {0, 0, 0, lc};
Point(2) = {1, 0, 0, lc};
Point(3) = {2, 0, 0, lc};
Point(4) = {2, 0.5, 0, lc};
Point(5) = {1, 0.5, 0, lc};
Point(6) = {0, 0.5, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Line(7) = {2, 5};
Curve Loop(1) = {1, 7, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7};
Plane Surface(2) = {2};
// "Face Sets": 1 left (x = 0), 2 right (x = 2), 3 bottom (y = 0), 4 top (y = 0.5)
Physical Curve("left", 1) = {6};
Physical Curve("right", 2) = {3};
Physical Curve("bottom", 3) = {1, 2};
Physical Curve("top", 4) = {4, 5};
// "Cell Sets": the two materials
Physical Surface("soft", 1) = {1};
Physical Surface("stiff", 2) = {2};
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
