// Two elastic boxes of one mesh that share no vertex (the two-body issue: tests/unit/kernels.ini, unit_pair): the lower
// box [0,1]^2 x [0,0.4] (h 0.2), the upper one [0.2,0.8]^2 x [0.45,0.8] (h 0.13), non-matching facing sides; 1 bottom,
// 2 top (Dirichlet), 10 the lower box's top (master), 20 the upper box's bottom (slave)
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 0.4};
Box(2) = {0.2, 0.2, 0.45, 0.6, 0.6, 0.35};
MeshSize{PointsOf{Volume{1};}} = 0.2;
MeshSize{PointsOf{Volume{2};}} = 0.13;
Physical Surface("bottom", 1) = {5};
Physical Surface("master", 10) = {6};
Physical Surface("slave", 20) = {11};
Physical Surface("top", 2) = {12};
Physical Volume("lower", 1) = {1};
Physical Volume("upper", 2) = {2};
