#!/usr/bin/python3
"""Writes the meshed obstacles of tests/meshobstacle.ini (STL ASCII and binary, gmsh .msh 4.1 and 2.2) into DIR.

usage: meshobstacle_gen.py DIR

3D (Example 2's body, [-0.5,0.5] x [-1,1] x [-0.5,0.5]):
  plane2.stl          the plane z = -0.55 as two triangles of [-3,3]^2
  planefine.stl       the same plane, an irregular triangulation (grid 17 x 13 with moved inner vertices)
  plane0.stl          planefine at z = 0 (placed by translation options)
  plane0x2.stl        plane0 in units of a half (coordinates doubled; -obstacle_cad_scale 0.5)
  tilted.stl          planefine turned: through (0,0,-0.55) with normal (0.1,0.05,1)
  sphereL.stl         icosphere of level L (20 4^L triangles, vertices on the sphere) with centre (-0.3,0,-1),
                      radius 0.5 (Example 2's ball), L = 2, 3, 4;
                      sphere3.bin.stl and sphere3f.stl (ASCII) with the coordinates rounded to single precision;
                      sphere3_unit.stl the same at the origin with radius 1; sphere3_turned.stl turned about its centre
  halfopen.stl        the upper half of sphere3 only (an open surface)
  gsphere.msh/gsphere22.msh/gsphere.stl  the ball as gmsh 4.8 meshes it (2,268 triangles), as .msh 4.1, 2.2, STL
2D (Example 1's body on [0,3] x [0,1]):
  line.msh            the line through (0,-0.001) with normal (0.001,1), 40 segments over x in [-1,4];
                      line_shifted.msh the same moved by (1, 0.5)
  circleN.msh         a polygon of N vertices on the circle centre (2,-5.001), radius 5, N = 200, 800, 3200
Bad inputs: bad_*.stl / bad_*.msh
"""
import os
import struct
import subprocess
import sys

import numpy as np


def write_stl_ascii(path, tris):
    with open(path, "w") as f:
        f.write("solid test\n")
        for t in tris:
            n = np.cross(t[1] - t[0], t[2] - t[0])
            f.write("  facet normal %.17g %.17g %.17g\n    outer loop\n" % tuple(n))
            for v in t:
                f.write("      vertex %.17g %.17g %.17g\n" % tuple(v))
            f.write("    endloop\n  endfacet\n")
        f.write("endsolid test\n")


def write_stl_binary(path, tris):
    with open(path, "wb") as f:
        f.write(b"solid binary header".ljust(80, b" "))  # a header that starts with 'solid', as some writers do
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            n = np.cross(t[1] - t[0], t[2] - t[0])
            f.write(struct.pack("<12fH", *n, *t[0], *t[1], *t[2], 0))


def write_msh41(path, nodes, elems, etype):
    """nodes (n,3), elems (m,k) 0-based, one entity"""
    with open(path, "w") as f:
        f.write("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n")
        n = len(nodes)
        f.write("$Nodes\n1 %d 1 %d\n%d 1 0 %d\n" % (n, n, 2 if etype == 2 else 1, n))
        for i in range(n):
            f.write("%d\n" % (i + 1))
        for p in nodes:
            f.write("%.17g %.17g %.17g\n" % tuple(p))
        f.write("$EndNodes\n$Elements\n1 %d 1 %d\n%d 1 %d %d\n" % (len(elems), len(elems), 2 if etype == 2 else 1, etype, len(elems)))
        for i, e in enumerate(elems):
            f.write("%d %s\n" % (i + 1, " ".join(str(v + 1) for v in e)))
        f.write("$EndElements\n")


def tris_of(nodes, elems):
    return [nodes[list(e)] for e in elems]


def plane_fine(z=0.0):
    """an irregular triangulation of [-3,3]^2 at height z (normals +z)"""
    nx, ny = 17, 13
    xs, ys = np.linspace(-3, 3, nx), np.linspace(-3, 3, ny)
    rng = np.random.default_rng(7)
    nodes = []
    for j, y in enumerate(ys):
        for i, x in enumerate(xs):
            dx = dy = 0.0
            if 0 < i < nx - 1 and 0 < j < ny - 1:
                dx, dy = rng.uniform(-0.12, 0.12, 2)
            nodes.append((x + dx, y + dy, z))
    elems = []
    for j in range(ny - 1):
        for i in range(nx - 1):
            a, b, c, d = j * nx + i, j * nx + i + 1, (j + 1) * nx + i + 1, (j + 1) * nx + i
            elems += [(a, b, c), (a, c, d)] if (i + j) % 2 else [(a, b, d), (b, c, d)]
    return np.array(nodes), np.array(elems)


def icosphere(level, centre, radius):
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    verts = [np.array(p, float) / np.linalg.norm(p) for p in v]
    for _ in range(level):
        mid, nf = {}, []
        for a, b, c in f:
            m = []
            for p, q in ((a, b), (b, c), (c, a)):
                k = (min(p, q), max(p, q))
                if k not in mid:
                    w = verts[p] + verts[q]
                    verts.append(w / np.linalg.norm(w))
                    mid[k] = len(verts) - 1
                m.append(mid[k])
            nf += [(a, m[0], m[2]), (b, m[1], m[0]), (c, m[2], m[1]), (m[0], m[1], m[2])]
        f = nf
    nodes = np.array(verts)
    elems = np.array(f)
    for i, (a, b, c) in enumerate(elems):  # outward
        if np.dot(np.cross(nodes[b] - nodes[a], nodes[c] - nodes[a]), nodes[a] + nodes[b] + nodes[c]) < 0:
            elems[i] = (a, c, b)
    return centre + radius * nodes, elems


def turn(nodes, normal, point):
    """the rotation taking e_z to normal, then a shift by point"""
    n = np.asarray(normal, float) / np.linalg.norm(normal)
    z = np.array([0, 0, 1.0])
    v, c = np.cross(z, n), np.dot(z, n)
    vx = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    R = np.eye(3) + vx + vx @ vx / (1 + c)
    return nodes @ R.T + point


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    P = lambda name: os.path.join(out, name)  # noqa: E731
    # ---- 3D planes
    sq = np.array([(-3, -3, -0.55), (3, -3, -0.55), (3, 3, -0.55), (-3, 3, -0.55)])
    write_stl_ascii(P("plane2.stl"), [sq[[0, 1, 2]], sq[[0, 2, 3]]])
    nodes, elems = plane_fine(-0.55)
    write_stl_ascii(P("planefine.stl"), tris_of(nodes, elems))
    n0, e0 = plane_fine(0.0)
    write_stl_ascii(P("plane0.stl"), tris_of(n0, e0))
    write_stl_ascii(P("plane0x2.stl"), tris_of(2 * n0, e0))
    write_stl_ascii(P("tilted.stl"), tris_of(turn(n0, (0.1, 0.05, 1), (0, 0, -0.55)), e0))
    # ---- spheres (Example 2's ball)
    for L in (2, 3, 4):
        nodes, elems = icosphere(L, np.array([-0.3, 0, -1]), 0.5)
        write_stl_ascii(P("sphere%d.stl" % L), tris_of(nodes, elems))
        if L == 3:
            up = [e for e in elems if nodes[e][:, 2].mean() > -1]
            write_stl_ascii(P("halfopen.stl"), tris_of(nodes, up))
            n32 = nodes.astype(np.float32).astype(float)  # binary STL holds floats: the ASCII twin has the same values
            write_stl_binary(P("sphere3.bin.stl"), tris_of(n32, elems))
            write_stl_ascii(P("sphere3f.stl"), tris_of(n32, elems))
            unit, _ = icosphere(L, np.zeros(3), 1.0)
            write_stl_ascii(P("sphere3_unit.stl"), tris_of(unit, elems))
            a, b = 0.7, 0.4  # turned about the centre: another triangulation of the same sphere
            Rz = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
            Rx = np.array([[1, 0, 0], [0, np.cos(b), -np.sin(b)], [0, np.sin(b), np.cos(b)]])
            write_stl_ascii(P("sphere3_turned.stl"), tris_of(np.array([-0.3, 0, -1]) + 0.5 * unit @ (Rx @ Rz).T, elems))
    # ---- gmsh's own files of Example 2's ball (an OpenCASCADE sphere meshed by gmsh 4.8, outward triangles)
    with open(P("gsphere.geo"), "w") as f:
        f.write('SetFactory("OpenCASCADE");\nSphere(1) = {-0.3, 0, -1, 0.5};\nMesh.MeshSizeMax = 0.06;\n')
    for name, fmt in (("gsphere.msh", ["-format", "msh41"]), ("gsphere22.msh", ["-format", "msh22"]), ("gsphere.stl", [])):
        subprocess.run(["gmsh", "-2", P("gsphere.geo"), "-o", P(name)] + fmt, check=True, stdout=subprocess.DEVNULL)
    # ---- 2D: the line of tests/cad.ini's plane2d, run from right to left (the obstacle below, to its left)
    d = np.array([1, -0.001]) / np.linalg.norm([1, -0.001])
    s = np.linspace(4, -1, 41)
    pts = np.array([(0 + t * d[0], -0.001 + t * d[1], 0) for t in s])
    write_msh41(P("line.msh"), pts, [(i, i + 1) for i in range(len(pts) - 1)], 1)
    write_msh41(P("line_shifted.msh"), pts + np.array([1.0, 0.5, 0]), [(i, i + 1) for i in range(len(pts) - 1)], 1)
    for N in (200, 800, 3200):  # counter-clockwise around the disk
        a = 2 * np.pi * np.arange(N) / N
        pts = np.array([(2 + 5 * np.cos(t), -5.001 + 5 * np.sin(t), 0) for t in a])
        write_msh41(P("circle%d.msh" % N), pts, [(i, (i + 1) % N) for i in range(N)], 1)
    # ---- bad inputs
    open(P("bad_empty.stl"), "w").close()
    with open(P("bad_notri.stl"), "w") as f:
        f.write("solid nothing\nendsolid nothing\n")
    tri = [sq[[0, 1, 2]], sq[[0, 2, 3]]]
    write_stl_ascii(P("bad_flip.stl"), [sq[[0, 1, 2]], sq[[0, 3, 2]]])  # the second turned: edge 0-2 twice the same way
    write_stl_ascii(P("bad_degenerate.stl"), tri + [np.array([(3, 3, -0.55), (4, 4, -0.55), (5, 5, -0.55)])])
    write_stl_ascii(P("bad_nonmanifold.stl"), tri + [np.array([(0, 0, 0), (-3, -3, -0.55), (3, 3, -0.55)])])
    with open(P("bad_nan.stl"), "w") as f:
        f.write("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 nan\nvertex 0 1 0\nendloop\nendfacet\nendsolid x\n")
    with open(P("sphere3.bin.stl"), "rb") as f, open(P("bad_truncated.stl"), "wb") as g:
        g.write(f.read(5000))
    with open(P("bad_garbage.stl"), "w") as f:
        f.write("this is not a mesh\n")
    nodes, elems = icosphere(1, np.array([0, 0, 0]), 1)
    write_msh41(P("bad_lines3d.msh"), nodes, [(a, b) for a, b, c in elems], 1)  # 3D: lines only, no triangles
    pts = np.array([(0, 0, 0), (1, 0, 0), (2, 0, 0)])
    write_msh41(P("bad_flip2d.msh"), pts, [(1, 0), (1, 2)], 1)  # both start at vertex 1
    write_msh41(P("bad_undefined_node.msh"), np.array([(0, 0, 0), (1, 0, 0), (0, 1, 0)]), [(0, 1, 2), (1, 8, 2)], 2)  # node 9
    write_msh41(P("bad_tri2d.msh"), np.array([(0, 0, 0), (1, 0, 0), (0, 1, 0)]), [(0, 1, 2)], 2)  # 2D: no lines
    with open(P("bad_binary.msh"), "w") as f:
        f.write("$MeshFormat\n4.1 1 8\n$EndMeshFormat\n")


if __name__ == "__main__":
    main()
