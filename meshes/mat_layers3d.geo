// A layered block of two materials (tests/*/materials.ini): [0,1] x [0,1] x [0,1], cells of z < 0.4 in physical volume
// 1, of z > 0.4 in 2 (one mesh, the interface z = 0.4 shared). Unstructured tetrahedra.
// gmsh -3 mat_layers3d.geo -o mat_layers3d.msh
SetFactory("OpenCASCADE");
If (!Exists(lc)) lc = 0.25; EndIf
Box(1) = {0, 0, 0, 1, 1, 0.4};
Box(2) = {0, 0, 0.4, 1, 1, 0.6};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
eps = 1e-6;
// "Face Sets": 1 bottom (z = 0), 2 top (z = 1), 3 x = 0, 4 x = 1, 5 y = 0, 6 y = 1
Physical Surface("bottom", 1) = Surface In BoundingBox{-eps, -eps, -eps, 1 + eps, 1 + eps, eps};
Physical Surface("top", 2) = Surface In BoundingBox{-eps, -eps, 1 - eps, 1 + eps, 1 + eps, 1 + eps};
Physical Surface("x0", 3) = Surface In BoundingBox{-eps, -eps, -eps, eps, 1 + eps, 1 + eps};
Physical Surface("x1", 4) = Surface In BoundingBox{1 - eps, -eps, -eps, 1 + eps, 1 + eps, 1 + eps};
Physical Surface("y0", 5) = Surface In BoundingBox{-eps, -eps, -eps, 1 + eps, eps, 1 + eps};
Physical Surface("y1", 6) = Surface In BoundingBox{-eps, 1 - eps, -eps, 1 + eps, 1 + eps, 1 + eps};
// "Cell Sets": the two materials
Physical Volume("lower", 1) = Volume In BoundingBox{-eps, -eps, -eps, 1 + eps, 1 + eps, 0.4 + eps};
Physical Volume("upper", 2) = Volume In BoundingBox{-eps, -eps, 0.4 - eps, 1 + eps, 1 + eps, 1 + eps};
Mesh.CharacteristicLengthMax = lc;
Mesh.MshFileVersion = 4.1;
Mesh.Binary = 0;
