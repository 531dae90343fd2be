// The upper body of the two-body issue's 3D symmetry check (tests/verification/twobody_mirror.ini): the quarter
// x, y >= 0 of the lower half of a ball of radius 1 centred at (0, 0, 1 + g), its round side down (the slave side),
// g above the plane z = 0. The lower body is its mirror image about z = 0, mesh included, made by
// tests/mirror_msh.py (gmsh does not mesh a mirrored copy of a volume as the mirror image of the original's mesh):
//   gmsh -3 -format msh22 tb_mirror3d.geo -o upper.msh
//   tests/mirror_msh.py --tags 20:10,2:1,6:7,8:9,2v:1 upper.msh tb_mirror3d.msh
// "Face Sets": 20 upper round side (slave), 2 upper top (z = 1 + g), 6 upper x = 0, 8 upper y = 0; their mirror
// images 10 (master), 1, 7, 9. "Cell Sets": 2 upper, 1 lower.
If (!Exists(g)) g = 0.001; EndIf
If (!Exists(h)) h = 0.25; EndIf   // -setnumber h H: the size away from the tip
If (!Exists(ht)) ht = 0.03; EndIf // -setnumber ht T: the size at the tip, where the bodies touch
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 1 + g, 1, -Pi / 2, 0, Pi / 2};
up[] = Boundary { Volume{1}; };
e = 1e-6;
top[] = Surface In BoundingBox {-e, -e, 1 + g - e, 1 + e, 1 + e, 1 + g + e};
ux[] = Surface In BoundingBox {-e, -e, g - e, e, 1 + e, 1 + g + e};
uy[] = Surface In BoundingBox {-e, -e, g - e, 1 + e, e, 1 + g + e};
ur[] = up[];
ur[] -= {top[], ux[], uy[]};
Physical Surface(20) = {ur[]};
Physical Surface(2) = {top[]};
Physical Surface(6) = {ux[]};
Physical Surface(8) = {uy[]};
Physical Volume(2) = {1};
Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, %g + 0.5 * Sqrt(x^2 + y^2 + (z - %g)^2))", h, ht, g);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
