// Contact patch test on an inclined rigid plane, 2D (tests/verification/curved.ini): the block [0,2] x [0,1] turned by `angle`
// degrees (default 20) about the origin, so that its bottom face lies on the plane through the origin with normal
// n = (-sin, cos). Unstructured triangles of size h = 0.25 / scale:
//   gmsh -2 -setnumber scale 1 cv_tilt2d.geo -o cv_tilt2d.msh
// "Face Sets" (no -dm_plex_gmsh_use_regions): 1 bottom (contact), 2 right, 3 top (pressure), 4 left;
// "Vertex Sets": 11 the bottom-left corner (the origin), 12 the bottom-right corner (pins that remove the rigid
// motions without disturbing the uniform exact solution: tests/verification/curved.ini gives their exact displacements).
If (!Exists(scale)) scale = 1; EndIf
If (!Exists(angle)) angle = 20; EndIf
SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 2, 1};
Rotate {{0, 0, 1}, {0, 0, 0}, angle * Pi / 180} { Surface{1}; }
// OpenCASCADE numbers the rectangle's curves bottom, right, top, left and its points from the bottom-left corner
Physical Curve(1) = {1};
Physical Curve(2) = {2};
Physical Curve(3) = {3};
Physical Curve(4) = {4};
Physical Point(11) = {1};
Physical Point(12) = {2};
Physical Surface(10) = {1};
Mesh.MeshSizeMax = 0.25 / scale;
Mesh.MeshSizeMin = 0.25 / scale;
Mesh.Algorithm = 5;
Mesh.Binary = 0;
