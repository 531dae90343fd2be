// An elastic sphere on an elastic block, 3D (the two-body issue: options/twobody_sphere.opts, tests/tbout.ini): the
// quarter x >= 0, y >= 0 of a hemisphere of radius 1 centred at (0,0,1), its curved face down touching the block's top
// at the origin (the slave side), and the quarter of a block [0,1] x [0,1] x [-1,0] below it (its top the master side);
// each meshed on its own (the block 1.3 times coarser: the meshes do not match). The block's top lies 1e-12 below
// z = 0, so that gmsh keeps the two bodies' points at the origin apart. Tetrahedra refined towards the origin (h_min
// 0.02, h_max 0.25 at scale 1); `scale` divides every size:
//   gmsh -3 -setnumber scale 2 tb_sphere.geo -o tb_sphere_s2.msh
// "Face Sets": 20 sphere's curved face (slave), 2 sphere's top (z = 1), 6 sphere's x = 0, 3 sphere's y = 0;
// 10 block's top (master), 1 block's bottom (z = -1), 7 block's x = 0, 4 block's y = 0. "Cell Sets": 1 block, 2 sphere.
If (!Exists(scale)) scale = 1; EndIf
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 1, 1, -Pi / 2, 0, Pi / 2};
Box(2) = {0, 0, -1 - 1e-12, 1, 1, 1};
eps = 1e-6;
top() = Surface In BoundingBox {-eps, -eps, 1 - eps, 1 + eps, 1 + eps, 1 + eps};
sfront() = Surface In BoundingBox {-eps, -eps, -eps, 1 + eps, eps, 1 + eps};
sleft() = Surface In BoundingBox {-eps, -eps, -eps, eps, 1 + eps, 1 + eps};
btop() = Surface In BoundingBox {-eps, -eps, -eps, 1 + eps, 1 + eps, eps};
curved() = Surface In BoundingBox {-eps, -eps, -eps, 1 + eps, 1 + eps, 1 + eps};
curved() -= {top(), sfront(), sleft(), btop()};
bbottom() = Surface In BoundingBox {-eps, -eps, -1 - eps, 1 + eps, 1 + eps, -1 + eps};
bfront() = Surface In BoundingBox {-eps, -eps, -1 - eps, 1 + eps, eps, eps};
bleft() = Surface In BoundingBox {-eps, -eps, -1 - eps, eps, 1 + eps, eps};
If (#curved() != 1 || #top() != 1 || #sfront() != 1 || #sleft() != 1 || #btop() != 1 || #bbottom() != 1 || #bfront() != 1 || #bleft() != 1)
  Error("tb_sphere.geo: the faces of the quarter hemisphere and of the block were not found");
EndIf
Physical Surface(20) = {curved()};
Physical Surface(2) = {top()};
Physical Surface(6) = {sleft()};
Physical Surface(3) = {sfront()};
Physical Surface(10) = {btop()};
Physical Surface(1) = {bbottom()};
Physical Surface(7) = {bleft()};
Physical Surface(4) = {bfront()};
Physical Volume(2) = {1};
Physical Volume(1) = {2};
hmin = 0.02 / scale;
hmax = 0.25 / scale;
Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, %g + 0.3 * Sqrt(x^2 + y^2 + z^2) / %g) * (1.15 - 0.15 * z / (Abs(z) + 1e-12))", hmax, hmin, scale);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm3D = 1;
Mesh.Binary = 0;
