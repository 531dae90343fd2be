// a .geo that merges a surface mesh: gmsh makes discrete surfaces of it, no CAD geometry (refused as an obstacle)
Merge "obstacle_square.stl";
