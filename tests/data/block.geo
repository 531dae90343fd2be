// A 3D block [0,2]x[0,1]x[0,1] with named faces and point groups (tests of Dirichlet parts that leave rigid motions
// free: a corner, three points on one edge, three points not on a line, a face). gmsh -3 block.geo -o block.msh
// Point groups are read by PETSc with -dm_plex_gmsh_use_regions -dm_plex_gmsh_mark_vertices.
lc = 0.5;
Point(1) = {0, 0, 0, lc};
Point(2) = {2, 0, 0, lc};
Point(3) = {2, 1, 0, lc};
Point(4) = {0, 1, 0, lc};
Point(5) = {0, 0, 1, lc};
Point(6) = {2, 0, 1, lc};
Point(7) = {2, 1, 1, lc};
Point(8) = {0, 1, 1, lc};
Point(9) = {0, 0, 0.5, lc}; // the middle of the edge x = y = 0
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {5, 6};
Line(6) = {6, 7};
Line(7) = {7, 8};
Line(8) = {8, 5};
Line(9) = {1, 9};
Line(13) = {9, 5};
Line(10) = {2, 6};
Line(11) = {3, 7};
Line(12) = {4, 8};
Curve Loop(1) = {1, 2, 3, 4};     Plane Surface(1) = {1};  // z = 0
Curve Loop(2) = {5, 6, 7, 8};     Plane Surface(2) = {2};  // z = 1
Curve Loop(3) = {1, 10, -5, -13, -9};  Plane Surface(3) = {3};  // y = 0
Curve Loop(4) = {3, 12, -7, -11}; Plane Surface(4) = {4};  // y = 1
Curve Loop(5) = {2, 11, -6, -10}; Plane Surface(5) = {5};  // x = 2
Curve Loop(6) = {4, 9, 13, -8, -12};  Plane Surface(6) = {6};  // x = 0
Surface Loop(1) = {1, 2, 3, 4, 5, 6};
Volume(1) = {1};
Physical Surface("left", 6) = {6};
Physical Surface("right", 5) = {5};
Physical Point("corner", 30) = {1};
Physical Point("line", 31) = {1, 9, 5};     // three points on the edge x = y = 0: the rotation about it is free
Physical Point("triangle", 32) = {1, 5, 4}; // three corners of the face x = 0: not on one line
Physical Volume("body", 10) = {1};
