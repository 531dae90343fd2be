// Not an obstacle for a 3D problem: a single curve, no surface (tests/*/cad.ini: refused)
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Line(1) = {1, 2};
