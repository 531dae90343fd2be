// A 2D plate [0,2]x[0,1] written with 3D coordinates, in the plane z = z0 + tilt*y (tests of 2D meshes with z values).
// gmsh -2 -setnumber z0 5 plate.geo -o plate_z5.msh; -setnumber tilt 0.5 for a tilted plane (refused by signorini).
// plate_bent.msh is plate_z0.msh with one interior node moved to z = 0.01 (a surface that is not planar).
If (!Exists(z0)) z0 = 0; EndIf
If (!Exists(tilt)) tilt = 0; EndIf
lc = 0.25;
Point(1) = {0, 0, z0, lc};
Point(2) = {2, 0, z0, lc};
Point(3) = {2, 1, z0 + tilt, lc};
Point(4) = {0, 1, z0 + tilt, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
// tags follow the box face markers: 1 bottom, 2 right, 3 top, 4 left; the corner point groups (Dirichlet parts of
// points) are read by PETSc with -dm_plex_gmsh_use_regions -dm_plex_gmsh_mark_vertices
Physical Curve("bottom", 1) = {1};
Physical Curve("right", 2) = {2};
Physical Curve("top", 3) = {3};
Physical Curve("left", 4) = {4};
Physical Point("corner", 11) = {1};
Physical Point("corners", 12) = {1, 3};
Physical Surface("body", 10) = {1};
