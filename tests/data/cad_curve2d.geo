// A 2D obstacle given by a curve alone (no surface: a sheet; no vertex is inside it, d is the first crossing ahead):
// the tilted line y = -0.001 - 0.001 x of tests/data/cad_line.geo as a B-spline on collinear points (tests/*/cad.ini)
Point(1) = {-1, 0, 0};
Point(2) = {0.5, -0.0015, 0};
Point(3) = {2, -0.003, 0};
Point(4) = {4, -0.005, 0};
BSpline(1) = {1, 2, 3, 4};
