// A tilted plane obstacle in 2D as CAD (built-in kernel): the region below the line through (0, -0.001) with normal
// (0.001, 1), i.e. y = -0.001 - 0.001 x, bounded by four lines in the plane z = 0 (tests/*/cad.ini).
Point(1) = {-1, 0, 0};
Point(2) = {4, -0.005, 0};
Point(3) = {4, -1, 0};
Point(4) = {-1, -1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
