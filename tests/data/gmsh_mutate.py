#!/usr/bin/env python3
"""Write the damaged gmsh meshes tests/data/gmsh_*.msh used by tests/input/gmsh.ini.

Each is tests/data/plate_z0.msh (gmsh 4.8, MSH 4.1 ASCII, 56 nodes, 112 elements) with one change. The same plate
written by gmsh as MSH 2.2 (gmsh -2 -format msh22 tests/data/plate.geo -o tests/data/gmsh_plate_v22.msh) gives
gmsh_v22_node0.msh; gmsh_plate_bin.msh is it in binary MSH 4.1 (gmsh -2 -bin); both are valid inputs of the tests.
Run from the repository root: python3 tests/data/gmsh_mutate.py
"""
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def lines(name):
    with open(os.path.join(HERE, name), newline="") as f:
        return f.read().split("\n")


def index(ls, text, after=0):
    """Index of the first line equal to text (trailing blanks ignored) at or after `after`."""
    for i in range(after, len(ls)):
        if ls[i].rstrip() == text:
            return i
    raise SystemExit("line %r not found" % text)


def write(name, ls, eol="\n"):
    with open(os.path.join(HERE, name), "w", newline="") as f:
        f.write(eol.join(ls))


def main():
    base = lines("plate_z0.msh")
    nodes = index(base, "$Nodes")
    elems = index(base, "$Elements")
    last = index(base, "112 40 46 55")           # the last triangle
    block7 = index(base, "1 1 0 7", nodes)        # node block of curve 1: tags 5..11, then their coordinates
    tag8 = index(base, "8", block7)
    tag11 = index(base, "11", block7)
    coord5 = index(base, "0.2499999999995476 0 0", block7)
    coord7 = index(base, "0.7499999999980952 0 0", block7)
    eblock = index(base, "1 3 1 8", elems)        # element block of curve 3 (lines)

    def mutate(name, edits=(), delete=()):
        ls = list(base)
        for i, text in edits:
            ls[i] = text
        for i in sorted(delete, reverse=True):
            del ls[i]
        write(name, ls)

    mutate("gmsh_node0.msh", [(last, "112 40 0 55 ")])                  # node tag 0 in an element (PETSc: wrong cell)
    mutate("gmsh_node_undefined.msh", [(last, "112 40 57 55 ")])        # a node that does not exist (PETSc: SEGV)
    mutate("gmsh_deleted_tag_line.msh", delete=[tag8])                  # a node tag line deleted (PETSc: SEGV)
    mutate("gmsh_deleted_coord_line.msh", delete=[coord7])              # a coordinate line deleted
    mutate("gmsh_tag_beyond_max.msh", [(tag11, "57")])                  # a node tag beyond maxNodeTag 56
    mutate("gmsh_duplicate_tag.msh", [(tag11, "10")])                   # node tag 10 twice (11 missing)
    mutate("gmsh_elem_short.msh", [(last, "112 40 46 ")])               # a triangle with 2 nodes
    mutate("gmsh_elem_long.msh", [(last, "112 40 46 55 1 ")])           # a triangle with 4 nodes
    mutate("gmsh_elem_degenerate.msh", [(last, "112 40 40 55 ")])       # a triangle with a repeated corner
    mutate("gmsh_block_count.msh", [(elems + 1, "8 112 1 112")])        # 8 element blocks announced, 7 given
    mutate("gmsh_node_count.msh", [(nodes + 1, "9 57 1 57")])           # 57 nodes announced, 56 given
    mutate("gmsh_unknown_type.msh", [(eblock, "1 3 99 8")])             # element type 99
    mutate("gmsh_nan.msh", [(coord5, "nan 0 0")])                       # a NaN coordinate
    mutate("gmsh_no_end_elements.msh", delete=[index(base, "$EndElements")])
    mutate("gmsh_bad_entity.msh", [(eblock, "1 7 1 8")])                # curve 7 is not in $Entities
    mutate("gmsh_physical_count.msh", [(index(base, "$PhysicalNames") + 1, "8")])
    mutate("gmsh_version.msh", [(1, "3.0 0 8")])                        # MSH 3 does not exist
    # valid but unusual: CRLF line ends and a $Comments section (PETSc reads it; so must the check)
    ls = list(base)
    ls[index(ls, "$EndMeshFormat") + 1:index(ls, "$EndMeshFormat") + 1] = ["$Comments", "written on Windows", "$EndComments"]
    write("gmsh_plate_crlf.msh", ls, "\r\n")

    v22 = lines("gmsh_plate_v22.msh")
    e22 = index(v22, "$Elements")
    last22 = len(v22) - 3
    assert v22[last22 + 1].rstrip() == "$EndElements", v22[last22 + 1]
    f = v22[last22].split()
    f[-2] = "0"
    v22[last22] = " ".join(f)
    assert e22 < last22
    write("gmsh_v22_node0.msh", v22)


if __name__ == "__main__":
    main()
