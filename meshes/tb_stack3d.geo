// The two-body patch test in 3D (tests/features/twobody.ini): two boxes 1 x 1 x 0.5 stacked with a gap of 0.01,
// meshed independently (h 0.25 below, 0.18 above). 1 bottom, 2 top, 3 the planes x = 0, 4 the planes y = 0 (rollers:
// symmetry planes), 10 the lower box's top (master), 20 the upper box's bottom (slave). Pressed by a prescribed top
// displacement, the exact solution is a uniaxial compression.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 0.5};
If (!Exists(g0)) g0 = 0.01; EndIf // -setnumber g0 G: another gap (tb_far3d: apart, tb_overlap3d: overlapping)
Box(2) = {0, 0, 0.5 + g0, 1, 1, 0.5};
MeshSize{PointsOf{Volume{1};}} = 0.25;
MeshSize{PointsOf{Volume{2};}} = 0.18;
Physical Surface("bottom", 1) = {5};
Physical Surface("top", 2) = {12};
Physical Surface("xsym", 3) = {1, 7};
Physical Surface("ysym", 4) = {3, 9};
Physical Surface("master", 10) = {6};
Physical Surface("slave", 20) = {11};
Physical Volume("lower", 1) = {1};
Physical Volume("upper", 2) = {2};
