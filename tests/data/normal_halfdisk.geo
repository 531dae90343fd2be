// An elastic half-disk of radius 1 (the lower half of the disk centred at (0, 1)), its arc touching the plane y = 0 at
// the origin (tests/normal.ini: a curved body on a plane): "arc" the possible contact boundary, "top" its flat side.
// gmsh -2 normal_halfdisk.geo -o normal_halfdisk.msh -format msh22
SetFactory("OpenCASCADE");
Disk(1) = {0, 1, 0, 1};
Rectangle(2) = {-2, 1, 0, 4, 2};
BooleanDifference{ Surface{1}; Delete; }{ Surface{2}; Delete; }
Mesh.MeshSizeMax = 0.08;
e() = Boundary{ Surface{1}; };
Physical Surface("body", 10) = {1};
Physical Curve("arc", 1) = {e(0)};
Physical Curve("top", 2) = {e(1)};
