// A quarter of a plate with a hole, resting on a plane (options/newuser_holeplate.opts, doc/user-guide.md): the box
// [0,1] x [0,1] x [0,0.5] less the cylinder of radius 0.3 on the z axis (OpenCASCADE), its faces picked by their
// bounding boxes. Tags: bottom 1 (rests on the plane z = 0), top 2 (loaded), symmetry planes x = 0: 3, y = 0: 4;
// the body 10.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 0.5};
Cylinder(2) = {0, 0, -0.1, 0, 0, 0.7, 0.3};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
e = 1e-6;
bottom() = Surface In BoundingBox{-e, -e, -e, 1 + e, 1 + e, e};
top() = Surface In BoundingBox{-e, -e, 0.5 - e, 1 + e, 1 + e, 0.5 + e};
symx() = Surface In BoundingBox{-e, -e, -e, e, 1 + e, 0.5 + e};
symy() = Surface In BoundingBox{-e, -e, -e, 1 + e, e, 0.5 + e};
Physical Surface("bottom", 1) = {bottom()};
Physical Surface("top", 2) = {top()};
Physical Surface("symx", 3) = {symx()};
Physical Surface("symy", 4) = {symy()};
Physical Volume("plate", 10) = {3};
Mesh.MeshSizeMax = 0.1;
