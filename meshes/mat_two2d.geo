// Two separate bodies in one mesh (tests/*/materials.ini): the squares [0,1]^2 (physical surface 1) and
// [1.5,2.5] x [0,1] (physical surface 2), no shared vertex. Unstructured triangles.
// gmsh -2 mat_two2d.geo -o mat_two2d.msh
If (!Exists(lc)) lc = 0.25; EndIf
Point(1) = {0, 0, 0, lc};
Point(2) = {1, 0, 0, lc};
Point(3) = {1, 1, 0, lc};
Point(4) = {0, 1, 0, lc};
Point(5) = {1.5, 0, 0, lc};
Point(6) = {2.5, 0, 0, lc};
Point(7) = {2.5, 1, 0, lc};
Point(8) = {1.5, 1, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {5, 6};
Line(6) = {6, 7};
Line(7) = {7, 8};
Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(2) = {2};
// "Face Sets": 1 bottom of the left body, 2 bottom of the right one, 3 top of the left, 4 top of the right, 5 sides
Physical Curve("bottom1", 1) = {1};
Physical Curve("bottom2", 2) = {5};
Physical Curve("top1", 3) = {3};
Physical Curve("top2", 4) = {7};
Physical Curve("sides", 5) = {2, 4, 6, 8};
// "Cell Sets": the two bodies
Physical Surface("left", 1) = {1};
Physical Surface("right", 2) = {2};
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
