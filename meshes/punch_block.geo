// The elastic block of options/punch.opts: [-1,1] x [-1,1] x [-1,0], its top face the contact boundary, refined
// under the punch (the size grows with the distance from the centre of the top face).
SetFactory("OpenCASCADE");
Box(1) = {-1, -1, -1, 2, 2, 1};
// OpenCASCADE numbers the box faces x-, x+, y-, y+, z-, z+
Physical Surface("bottom", 1) = {5};
Physical Surface("top", 2) = {6};
Physical Surface("sides", 3) = {1, 2, 3, 4};
Physical Volume("body", 10) = {1};
Field[1] = MathEval;
Field[1].F = "Min(0.15, 0.02 + 0.12 * Sqrt(x^2 + y^2 + z^2))";
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm3D = 1;
Mesh.Binary = 0;
