// The obstacle of Example 2 (-obstacle_type ball, options/ex2_problem.opts) as CAD: the half-ball of radius 0.5
// centred at (-0.3, 0, -1) on the plane z = -1, here a slab large enough for every ray from the block (tests/*/cad.ini).
SetFactory("OpenCASCADE");
Sphere(1) = {-0.3, 0, -1, 0.5};
Box(2) = {-3, -3, -2, 6, 6, 1};
BooleanUnion{ Volume{2}; Delete; }{ Volume{1}; Delete; }
