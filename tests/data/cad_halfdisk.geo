// The 2D half-ball (-obstacle_type ball in 2D): the half-disk of radius 5 centred at (2, -5.001) on the line
// y = -5.001, as the union of a disk and a rectangle in the plane z = 0 (tests/*/cad.ini).
SetFactory("OpenCASCADE");
Disk(1) = {2, -5.001, 0, 5};
Rectangle(2) = {-10, -7, 0, 24, 1.999};
BooleanUnion{ Surface{2}; Delete; }{ Surface{1}; Delete; }
