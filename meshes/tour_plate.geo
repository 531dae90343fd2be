// meshes/tour_plate.geo: the README's own-mesh tour. A plate 2 x 0.5 in 2D whose bottom may touch a ball below it, top pushed down
lc = 0.05;
Point(1) = {0, 0, 0, lc}; Point(2) = {2, 0, 0, lc}; Point(3) = {2, 0.5, 0, lc}; Point(4) = {0, 0.5, 0, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Physical Curve("bottom", 1) = {1};
Physical Curve("top", 2) = {3};
Physical Surface("plate", 10) = {1};
