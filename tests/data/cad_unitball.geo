// tests/data/cad_halfball.geo in other units and at the origin: a half-ball of radius 1 centred at (0, 0, 0) on a
// slab; with -obstacle_cad_scale 0.5 -obstacle_cad_translation -0.3,0,-1 it is Example 2's obstacle (tests/*/cad.ini).
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, 1};
Box(2) = {-6, -6, -2, 12, 12, 2};
BooleanUnion{ Volume{2}; Delete; }{ Volume{1}; Delete; }
