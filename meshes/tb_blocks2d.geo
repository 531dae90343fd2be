// Two elastic blocks of one mesh that share no vertex (the two-body issue: tests/unit/kernels.ini, unit_pair): the lower
// block [0,1] x [0,0.5] (h 0.1), the upper one [0.2,0.8] x [0.55,1] (h 0.065), so the meshes of the facing sides do not
// match; 1 bottom, 2 top (Dirichlet), 10 the lower block's top (master), 20 the upper block's bottom (slave)
lc1 = 0.1; lc2 = 0.065;
Point(1) = {0, 0, 0, lc1}; Point(2) = {1, 0, 0, lc1}; Point(3) = {1, 0.5, 0, lc1}; Point(4) = {0, 0.5, 0, lc1};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Point(5) = {0.2, 0.55, 0, lc2}; Point(6) = {0.8, 0.55, 0, lc2}; Point(7) = {0.8, 1, 0, lc2}; Point(8) = {0.2, 1, 0, lc2};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Physical Curve("bottom", 1) = {1};
Physical Curve("master", 10) = {3};
Physical Curve("slave", 20) = {5};
Physical Curve("top", 2) = {7};
Physical Surface("lower", 1) = {1};
Physical Surface("upper", 2) = {2};
