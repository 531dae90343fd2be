// The 2D half-ball (-obstacle_type ball in 2D): the half-disk of radius 0.499 centred at (1.5, -0.5) on the line
// y = -0.5, as the union of a disk and a rectangle in the plane z = 0 (tests/cad.ini).
SetFactory("OpenCASCADE");
Disk(1) = {1.5, -0.5, 0, 0.499};
Rectangle(2) = {-3, -1.5, 0, 9, 1};
BooleanUnion{ Surface{2}; Delete; }{ Surface{1}; Delete; }
