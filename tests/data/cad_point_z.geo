// Not an obstacle: a point off the plane z = 0, no curve (tests/*/cad.ini: refused in 2D)
Point(1) = {0, 0, 1};
