#!/usr/bin/python3
"""A rigidly turned copy of a gmsh mesh (ASCII format 4.1) for the rotation-invariance checks of tests/verification/curved.ini and
bench/perf_curved.py: every node x becomes R x (R the rotation by ANGLE degrees about the axis AXIS through the
origin, right-handed); the elements, their numbering and the physical groups stay as they are, so the turned problem
is the same discrete problem in other coordinates. (gmsh 4.8 cannot transform a mesh it has read, and meshing a
turned geometry gives another unstructured mesh: its answers would agree only to the discretization error.)
The geometric points and bounding boxes of $Entities are turned too (the boxes as the boxes of the turned boxes).
A 2D mesh (every z = 0) must be turned about the z axis.

    rotate_msh.py --axis AX,AY,AZ --angle DEG IN.msh OUT.msh     the turned mesh
    rotate_msh.py --axis AX,AY,AZ --angle DEG --vector V1,V2[,V3]  print R v (Dirichlet values, centres, normals)
"""
import argparse
import math
import os
import sys


def rotation(axis, deg):
    """Rodrigues' formula: the rotation by deg degrees about axis (right-handed)."""
    n = math.sqrt(sum(a * a for a in axis))
    if n == 0:
        sys.exit("rotate_msh.py: --axis is the zero vector")
    k = [a / n for a in axis]
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    K = [[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]]
    KK = [[sum(K[i][m] * K[m][j] for m in range(3)) for j in range(3)] for i in range(3)]
    return [[(1.0 if i == j else 0.0) + s * K[i][j] + (1 - c) * KK[i][j] for j in range(3)] for i in range(3)]


def apply(R, x):
    return [R[i][0] * x[0] + R[i][1] * x[1] + R[i][2] * x[2] for i in range(3)]


def fmt(v):
    return repr(float(v)) if v != 0 else "0"


def turn_box(R, lo, hi):
    corners = [apply(R, [(lo, hi)[i & 1][0], (lo, hi)[i >> 1 & 1][1], (lo, hi)[i >> 2 & 1][2]]) for i in range(8)]
    return [min(c[d] for c in corners) for d in range(3)], [max(c[d] for c in corners) for d in range(3)]


def turn(lines, R):
    out, i, n = [], 0, len(lines)
    while i < n:
        line = lines[i]
        out.append(line)
        i += 1
        if line.strip() == "$MeshFormat":
            if not lines[i].split()[0].startswith("4") or lines[i].split()[1] != "0":
                sys.exit("rotate_msh.py: only ASCII gmsh format 4.x meshes (Mesh.Binary = 0)")
        elif line.strip() == "$Entities":
            counts = [int(a) for a in lines[i].split()]
            out.append(lines[i])
            i += 1
            for _ in range(counts[0]):  # points: tag x y z nphys tags...
                f = lines[i].split()
                x = apply(R, [float(a) for a in f[1:4]])
                out.append(" ".join([f[0]] + [fmt(a) for a in x] + f[4:]) + " \n")
                i += 1
            for _ in range(sum(counts[1:])):  # curves, surfaces, volumes: tag minx miny minz maxx maxy maxz ...
                f = lines[i].split()
                lo, hi = turn_box(R, [float(a) for a in f[1:4]], [float(a) for a in f[4:7]])
                out.append(" ".join([f[0]] + [fmt(a) for a in lo + hi] + f[7:]) + " \n")
                i += 1
        elif line.strip() == "$Nodes":
            nblocks = int(lines[i].split()[0])
            out.append(lines[i])
            i += 1
            for _ in range(nblocks):
                head = lines[i].split()
                out.append(lines[i])
                i += 1
                if head[2] != "0":
                    sys.exit("rotate_msh.py: parametric nodes are not supported")
                m = int(head[3])
                out.extend(lines[i:i + m])  # the node tags
                i += m
                for j in range(m):
                    x = apply(R, [float(a) for a in lines[i + j].split()])
                    out.append(" ".join(fmt(a) for a in x) + "\n")
                i += m
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--axis", required=True)
    ap.add_argument("--angle", type=float, required=True)
    ap.add_argument("--vector", help="print R v (2 or 3 numbers) instead of turning a mesh")
    ap.add_argument("files", nargs="*")
    a = ap.parse_args()
    R = rotation([float(v) for v in a.axis.split(",")], a.angle)
    if a.vector:
        v = [float(t) for t in a.vector.split(",")]
        if len(v) == 2 and (abs(R[2][2] - 1) > 0 or R[0][2] != 0 or R[1][2] != 0):
            sys.exit("rotate_msh.py: a 2D vector turns about the z axis only")
        w = apply(R, v + [0.0] * (3 - len(v)))[:len(v)]
        print(",".join(fmt(t) for t in w))
        return
    if len(a.files) != 2:
        sys.exit(__doc__)
    with open(a.files[0]) as f:
        lines = f.readlines()
    out = turn(lines, R)
    tmp = a.files[1] + ".tmp"
    with open(tmp, "w") as f:
        f.writelines(out)
    os.replace(tmp, a.files[1])  # no half-written mesh


if __name__ == "__main__":
    main()
