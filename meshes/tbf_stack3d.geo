// The two-body friction patch test in 3D (tests/tbfric.ini): the boxes of tb_stack3d.geo (1 x 1 x 0.5, 0.01 apart,
// meshed independently: h 0.25 below, 0.18 above) with every side a part of its own, for the tractions of a uniform
// stress with shear: 1 bottom, 2 top, 3 the planes x = 0, 4 the planes y = 0, 5 the planes x = 1, 6 the planes y = 1,
// 10 the lower box's top (master), 20 the upper box's bottom (slave).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 0.5};
Box(2) = {0, 0, 0.51, 1, 1, 0.5};
MeshSize{PointsOf{Volume{1};}} = 0.25;
MeshSize{PointsOf{Volume{2};}} = 0.18;
Physical Surface("bottom", 1) = {5};
Physical Surface("top", 2) = {12};
Physical Surface("xmin", 3) = {1, 7};
Physical Surface("ymin", 4) = {3, 9};
Physical Surface("xmax", 5) = {2, 8};
Physical Surface("ymax", 6) = {4, 10};
Physical Surface("master", 10) = {6};
Physical Surface("slave", 20) = {11};
Physical Volume("lower", 1) = {1};
Physical Volume("upper", 2) = {2};
