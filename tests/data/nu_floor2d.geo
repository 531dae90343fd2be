// A floor of finite extent in 2D: the rectangle [-3, 3] x [-1, 0] in the plane z = 0, whose top edge is the line
// y = 0 (tests/*/newuser.ini: the rays of a box's vertical sides miss it).
SetFactory("OpenCASCADE");
Rectangle(1) = {-3, -1, 0, 6, 1};
