// Two separate bodies in one 3D mesh (tests/*/materials.ini): the cubes [0,1]^3 (physical volume 1) and
// [1.5,2.5] x [0,1] x [0,1] (physical volume 2), no shared vertex. Unstructured tetrahedra.
// gmsh -3 mat_two3d.geo -o mat_two3d.msh
SetFactory("OpenCASCADE");
If (!Exists(lc)) lc = 0.5; EndIf
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {1.5, 0, 0, 1, 1, 1};
eps = 1e-6;
// "Face Sets": 1 bottom (z = 0) of the left cube, 2 bottom of the right one, 3 top (z = 1) of both
Physical Surface("bottom1", 1) = Surface In BoundingBox{-eps, -eps, -eps, 1 + eps, 1 + eps, eps};
Physical Surface("bottom2", 2) = Surface In BoundingBox{1.5 - eps, -eps, -eps, 2.5 + eps, 1 + eps, eps};
Physical Surface("top", 3) = Surface In BoundingBox{-eps, -eps, 1 - eps, 2.5 + eps, 1 + eps, 1 + eps};
// "Cell Sets": the two bodies
Physical Volume("left", 1) = {1};
Physical Volume("right", 2) = {2};
Mesh.CharacteristicLengthMax = lc;
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
