// A .geo with a syntax error (tests/*/cad.ini: gmsh's message is passed on)
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1;
