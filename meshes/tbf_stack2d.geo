// The two-body friction patch test (tests/tbfric.ini): the blocks of tb_stack2d.geo (width 1, height 0.5, 0.01 apart,
// meshed independently: h 0.1 below, 0.07 above) with every side a part of its own, for the tractions of a uniform
// stress with shear: 1 bottom, 2 top, 3 and 4 the left sides (x = 0) of the lower and upper block, 5 and 6 their right
// sides (x = 1), 10 the lower block's top (master), 20 the upper block's bottom (slave).
h1 = 0.1; h2 = 0.07; g0 = 0.01;
Point(1) = {0, 0, 0, h1}; Point(2) = {1, 0, 0, h1}; Point(3) = {1, 0.5, 0, h1}; Point(4) = {0, 0.5, 0, h1};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Point(5) = {0, 0.5 + g0, 0, h2}; Point(6) = {1, 0.5 + g0, 0, h2}; Point(7) = {1, 1 + g0, 0, h2}; Point(8) = {0, 1 + g0, 0, h2};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Physical Curve("bottom", 1) = {1};
Physical Curve("top", 2) = {7};
Physical Curve("left_lower", 3) = {4};
Physical Curve("left_upper", 4) = {8};
Physical Curve("right_lower", 5) = {2};
Physical Curve("right_upper", 6) = {6};
Physical Curve("master", 10) = {3};
Physical Curve("slave", 20) = {5};
Physical Surface("lower", 1) = {1};
Physical Surface("upper", 2) = {2};
