// A rigid punch with rounded edges (the CAD obstacle of options/punch.opts): a box of 0.8 x 0.8 x 0.4 whose four
// vertical and four bottom edges are rounded with radius 0.1. Bottom face at z = 0, centred on the z axis; the
// options place it with -obstacle_cad_translation.
SetFactory("OpenCASCADE");
Box(1) = {-0.4, -0.4, 0, 0.8, 0.8, 0.4};
// the edges of the box except the four of its top face (z = 0.4)
e() = Abs(Boundary{ Surface{1, 2, 3, 4, 5}; });
top() = Abs(Boundary{ Surface{6}; });
e() -= top();
e() = Unique(e());
Fillet{1}{e()}{0.1}
