#!/usr/bin/python3
"""Add to a gmsh mesh (ASCII format 2.2) its mirror image about the plane x_last = 0, mesh included, as a second body.

gmsh meshes a mirrored copy of a volume on its own, not as the mirror image of the original's mesh; a symmetry check
of two bodies (tests/verification/twobody_mirror.ini, meshes/tb_mirror3d.geo) needs the image exactly. Each mirrored
element gets the physical tag given by --tags (FROM:TO for facets, FROMv:TO for cells; tags not named keep theirs);
its vertex order is reversed in one pair so that its orientation stays positive. The mesh must lie on one side of the
plane (no vertex on it): the two bodies do not share vertices.

usage: mirror_msh.py --tags 20:10,2:1,2v:1 IN.msh OUT.msh
"""
import argparse
import os
import sys

CELL_TYPES = {2: 2, 4: 3}  # gmsh element type -> dimension: triangles (2D cells or 3D facets), tetrahedra
FACET_TYPES = {1: 2, 2: 3}  # segments (2D facets), triangles (3D facets)


def read(path):
    with open(path) as f:
        lines = f.read().split("\n")
    i = lines.index("$MeshFormat")
    if not lines[i + 1].startswith("2.2 0"):
        sys.exit("%s: not a gmsh ASCII mesh of format 2.2 (write it with gmsh -format msh22)" % path)
    i = lines.index("$Nodes")
    n = int(lines[i + 1])
    nodes = [lines[i + 2 + k].split() for k in range(n)]
    i = lines.index("$Elements")
    m = int(lines[i + 1])
    elems = [list(map(int, lines[i + 2 + k].split())) for k in range(m)]
    return [(int(a[0]), [float(v) for v in a[1:4]]) for a in nodes], elems


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tags", required=True)
    ap.add_argument("inp")
    ap.add_argument("out")
    a = ap.parse_args()
    ftag, ctag = {}, {}
    for item in a.tags.split(","):
        src, dst = item.split(":")
        (ctag if src.endswith("v") else ftag)[int(src.rstrip("v"))] = int(dst)
    nodes, elems = read(a.inp)
    dim = 3 if any(e[1] == 4 for e in elems) else 2
    axis = dim - 1
    if any(x[axis] == 0 for _, x in nodes):
        sys.exit("%s: a vertex lies on the mirror plane" % a.inp)
    off = max(i for i, _ in nodes)
    out_nodes = list(nodes)
    for i, x in nodes:
        y = list(x)
        y[axis] = -y[axis]
        out_nodes.append((i + off, y))
    cell = 4 if dim == 3 else 2
    facet = 2 if dim == 3 else 1
    out_elems = []
    for e in elems:
        if e[1] in (cell, facet):
            out_elems.append(e)
    n0 = len(out_elems)
    for e in out_elems[:n0]:
        typ, ntag = e[1], e[2]
        tags = list(e[3:3 + ntag])
        vs = e[3 + ntag:]
        table = ctag if typ == cell else ftag
        tags[0] = table.get(tags[0], tags[0])
        if ntag > 1:  # the elementary entity: one of its own
            tags[1] += 100000
        vs = [v + off for v in vs]
        vs[0], vs[1] = vs[1], vs[0]
        out_elems.append([0, typ, ntag] + tags + vs)
    tmp = a.out + ".tmp"
    with open(tmp, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(out_nodes))
        for i, x in out_nodes:
            f.write("%d %.17g %.17g %.17g\n" % (i, x[0], x[1], x[2]))
        f.write("$EndNodes\n$Elements\n%d\n" % len(out_elems))
        for k, e in enumerate(out_elems):
            f.write(" ".join(str(v) for v in [k + 1] + e[1:]) + "\n")
        f.write("$EndElements\n")
    os.replace(tmp, a.out)


if __name__ == "__main__":
    main()
