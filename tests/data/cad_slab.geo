// A plane obstacle as CAD: a slab whose top face is the plane z = 0 (placed with -obstacle_cad_translation;
// tests/*/cad.ini compares it with -obstacle_type plane).
SetFactory("OpenCASCADE");
Box(1) = {-3, -3, -1, 6, 6, 1};
