// Two equal elastic half discs pressed together, mirror images of each other about y = 0 (the two-body issue's
// symmetry check, tests/verification/twobody_mirror.ini): the half x >= 0 of a disc of radius 1 centred at (0, 1 + g)
// with its arc down (the slave side) and its mirror image, mesh included, below y = 0 (the master side). The facing
// arcs' vertices match across the gap 2 g. Pressed by symmetric displacements of the flat sides, the answer is the
// mirror image of itself: u_x(x, -y) = u_x(x, y), u_y(x, -y) = -u_y(x, y).
//   gmsh -2 tb_mirror2d.geo -o tb_mirror2d.msh
// "Face Sets": 20 upper arc (slave), 2 upper top, 6 upper left (x = 0); 10 lower arc (master), 1 lower bottom, 7
// lower left. "Cell Sets": 2 upper, 1 lower.
If (!Exists(g)) g = 0.001; EndIf
If (!Exists(h)) h = 0.12; EndIf   // -setnumber h H: the size away from the tip
If (!Exists(ht)) ht = 0.01; EndIf // -setnumber ht T: the size at the tip, where the arcs touch
Point(1) = {0, 1 + g, 0, h};
Point(2) = {1, 1 + g, 0, h};
Point(3) = {0, g, 0, ht};
Circle(1) = {2, 1, 3};
Line(2) = {3, 1};
Line(3) = {1, 2};
Curve Loop(1) = {1, 2, 3};
Plane Surface(2) = {1};
low[] = Symmetry {0, 1, 0, 0} { Duplicata { Surface{2}; } };
lowb[] = Boundary { Surface{low[0]}; };
Physical Curve(20) = {1};
Physical Curve(2) = {3};
Physical Curve(6) = {2};
Physical Curve(10) = {Abs(lowb[0])};
Physical Curve(7) = {Abs(lowb[1])};
Physical Curve(1) = {Abs(lowb[2])};
Physical Surface(2) = {2};
Physical Surface(1) = {low[0]};
