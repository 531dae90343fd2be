#!/usr/bin/python3
"""The peer users would pick instead of us: FEniCSx (Debian's python3-dolfinx 0.5) with PETSc's SNESVI
(SNESVINEWTONRSLS, MUMPS) on the same discrete problem as bin/signorini's Example 1 (2D) and Example 2 (3D).

The same discrete problem: P1 elasticity on the same mesh (the 2D box built by dolfinx with the same diagonal and
checked cell by cell against ours with --ours; the 3D gmsh file read here), the same material, loads and Dirichlet
data, and the contact condition tau_N u <= d_i at the contact-boundary vertices with our gaps d_i (src/contact/
obstacle.c: parabola and half-ball along the contact normal). Both contact faces are flat with outward normal -e_dim
(averaged facet normals are exact there), so tau_N u = -u_dim and the condition is the bound u_dim >= -d_i on one dof
per vertex: exact for SNESVI's bounds, no change of variables. (P) is then: minimize 1/2 u^T K u - b^T u subject to
these bounds, the problem our KKT residual measures.

K and b are assembled once with the Dirichlet rows eliminated (dolfinx's lifting); F(u) = K u - b; the Jacobian is K
(a quadratic program: nothing to reassemble). Each Newton step of RSLS factors the inactive block of K with MUMPS.
Timed: assembly of K and b (forms already compiled, mesh already built) and SNES setup + solve, apart.

usage: peer_dolfinx.py ex1 --faces 120,40 [--ours RUN.h5] [--json OUT.json] [PETSc options]
       peer_dolfinx.py ex2 --mesh meshes/ex2.msh [--ours RUN.h5] [--json OUT.json] [PETSc options]
--ours: the HDF5 fields of our run on the same problem (-output_file): checks mesh, gaps and solution against them.
"""
import argparse
import json
import sys
import time

import numpy as np

T_START = time.perf_counter()  # the run's wall time (dolfinx's import, mesh, assembly, solve), to the summary

ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("problem", choices=("ex1", "ex2"))
ap.add_argument("--faces", default="120,40", help="ex1: squares along x,y")
ap.add_argument("--mesh", default="meshes/ex2.msh", help="ex2: gmsh 4.1 ASCII file")
ap.add_argument("--ours", help="our HDF5 fields of the same problem, to compare with")
ap.add_argument("--json", help="write the result here")
opt, petsc_args = ap.parse_known_args()

import petsc4py  # noqa: E402

petsc4py.init([sys.argv[0]] + petsc_args)
from petsc4py import PETSc  # noqa: E402
from mpi4py import MPI  # noqa: E402
import ufl  # noqa: E402
from dolfinx import fem, mesh as dmesh  # noqa: E402
import dolfinx.fem.petsc  # noqa: E402,F401

comm = MPI.COMM_WORLD
if comm.size != 1:
    sys.exit("peer_dolfinx.py: one rank only (the vertex-by-vertex checks gather nothing)")


def read_msh41(path):
    """Nodes and tetrahedra of an ASCII gmsh 4.1 file (what meshes/*.geo produce); our own small reader, since
    Debian's dolfinx 0.5 reads gmsh files only through the gmsh Python module, which Debian 12 does not ship."""
    with open(path) as f:
        lines = f.read().split("\n")
    i = 0
    tags, xyz, tets = [], [], []
    while i < len(lines):
        s = lines[i].strip()
        if s == "$MeshFormat":
            if not lines[i + 1].split()[0].startswith("4.1") or lines[i + 1].split()[1] != "0":
                sys.exit("%s: not an ASCII gmsh 4.1 file" % path)
        elif s == "$Nodes":
            nblocks = int(lines[i + 1].split()[0])
            i += 2
            for _ in range(nblocks):
                n = int(lines[i].split()[3])
                tags += [int(lines[i + 1 + k]) for k in range(n)]
                xyz += [[float(v) for v in lines[i + 1 + n + k].split()] for k in range(n)]
                i += 1 + 2 * n
            continue
        elif s == "$Elements":
            nblocks = int(lines[i + 1].split()[0])
            i += 2
            for _ in range(nblocks):
                _, _, etype, n = (int(v) for v in lines[i].split())
                if etype == 4:  # 4-node tetrahedron
                    tets += [[int(v) for v in lines[i + 1 + k].split()[1:5]] for k in range(n)]
                i += 1 + n
            continue
        i += 1
    index = {t: k for k, t in enumerate(tags)}
    cells = np.array([[index[t] for t in c] for c in tets], dtype=np.int64)
    used = np.unique(cells)  # nodes of the volume mesh only (PETSc's reader keeps the same)
    renum = -np.ones(len(tags), dtype=np.int64)
    renum[used] = np.arange(len(used))
    return np.array(xyz)[used], renum[cells]


dim = 2 if opt.problem == "ex1" else 3
if opt.problem == "ex1":
    nx, ny = (int(v) for v in opt.faces.split(","))
    msh = dmesh.create_rectangle(comm, [np.array([0.0, 0.0]), np.array([3.0, 1.0])], [nx, ny], dmesh.CellType.triangle,
                                 diagonal=dmesh.DiagonalType.right)
    E, nu = 5000.0, 0.4
else:
    x, cells = read_msh41(opt.mesh)
    msh = dmesh.create_mesh(comm, cells, x, ufl.Mesh(ufl.VectorElement("Lagrange", ufl.tetrahedron, 1)))
    E, nu = 1e6, 0.45
lmbda, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))  # plane strain in 2D

V = fem.VectorFunctionSpace(msh, ("Lagrange", 1))
u, v = ufl.TrialFunction(V), ufl.TestFunction(V)


def eps(w):
    return ufl.sym(ufl.grad(w))


def sigma(w):
    return 2 * mu * eps(w) + lmbda * ufl.tr(eps(w)) * ufl.Identity(dim)


fdim = dim - 1
if opt.problem == "ex1":
    # left x = 0 clamped; traction (0, -2) on the right x = 3; contact at the bottom y = 0
    dir_facets = dmesh.locate_entities_boundary(msh, fdim, lambda p: np.isclose(p[0], 0.0))
    g = np.zeros(2)
    right = dmesh.locate_entities_boundary(msh, fdim, lambda p: np.isclose(p[0], 3.0))
    mt = dmesh.meshtags(msh, fdim, right, np.full(len(right), 2, dtype=np.int32))
    ds = ufl.Measure("ds", domain=msh, subdomain_data=mt)
    traction = fem.Constant(msh, np.array([0.0, -2.0]))
    Lform = ufl.inner(traction, v) * ds(2)
else:
    # top z = 0.5 moved by (0, 0, -0.2); sides and bottom traction free, no body force
    dir_facets = dmesh.locate_entities_boundary(msh, fdim, lambda p: np.isclose(p[2], 0.5))
    g = np.array([0.0, 0.0, -0.2])
    ds = ufl.ds
    Lform = ufl.inner(fem.Constant(msh, np.zeros(3)), v) * ufl.dx
bc = fem.dirichletbc(g, fem.locate_dofs_topological(V, fdim, dir_facets), V)
a = fem.form(ufl.inner(sigma(u), eps(v)) * ufl.dx)
L = fem.form(Lform)
uh = fem.Function(V)
energy = fem.form(0.5 * ufl.inner(sigma(uh), eps(uh)) * ufl.dx - ufl.replace(Lform, {v: uh}))

# contact vertices: the bottom face (normal -e_dim); our gaps d_i along that normal (src/contact/obstacle.c)
X = V.tabulate_dof_coordinates()[:, :dim]  # one row per vertex (block size dim)
bottom = 0.0 if opt.problem == "ex1" else -0.5
cv = np.flatnonzero(np.abs(X[:, dim - 1] - bottom) < 1e-12)
if opt.problem == "ex1":  # parabola d = a |x_t - c_t|^2 + offset, a = 0.003, offset 0.001, c = (1.5, 0)
    d = 0.003 * (X[cv, 0] - 1.5) ** 2 + 0.001
else:  # half-ball R = 0.5, c = (-0.3, 0, -1) on the plane z = -1: the ray x - t e_z
    R, c = 0.5, np.array([-0.3, 0.0, -1.0])
    xc = X[cv] - c
    b_ = -xc[:, 2]
    disc = b_ * b_ - ((xc * xc).sum(axis=1) - R * R)
    t = -b_ - np.sqrt(np.maximum(disc, 0))
    on_ball = (disc >= 0) & (xc[:, 2] - t >= 0)
    d = np.where(on_ball, t, xc[:, 2])  # else the plane z = -1 under the ball: its distance along -e_z
bs = V.dofmap.index_map_bs
ndofs = V.dofmap.index_map.size_local * bs
bcdofs = bc.dof_indices()[0]
is_dir = np.zeros(ndofs, dtype=bool)
is_dir[bcdofs] = True
contact = cv[~is_dir[cv * bs + dim - 1]]  # Dirichlet vertices are not contact vertices (as ours)
dcon = d[~is_dir[cv * bs + dim - 1]]
ndof_free = ndofs - int(is_dir.sum())

# ---- timed: assembly, then SNES setup + solve
t0 = time.perf_counter()
K = fem.petsc.assemble_matrix(a, bcs=[bc])
K.assemble()
b = fem.petsc.assemble_vector(L)
fem.petsc.apply_lifting(b, [a], bcs=[[bc]])
b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
fem.petsc.set_bc(b, [bc])
t_asm = time.perf_counter() - t0

t0 = time.perf_counter()
x = K.createVecRight()
xa = x.getArray()
xa[bcdofs] = g[bcdofs % dim]  # start: zero with the Dirichlet values
lb, ub = x.duplicate(), x.duplicate()
lba = np.full(ndofs, PETSc.NINFINITY)
lba[contact * bs + dim - 1] = -dcon
lb.setArray(lba)
ub.set(PETSc.INFINITY)
Fv = x.duplicate()


def residual(snes, y, f):
    K.mult(y, f)
    f.axpy(-1.0, b)


def jacobian(snes, y, J, P):
    pass  # K, assembled once


snes = PETSc.SNES().create(comm)
snes.setType("vinewtonrsls")
snes.setFunction(residual, Fv)
snes.setJacobian(jacobian, K, K)
snes.setVariableBounds(lb, ub)
# defaults (any PETSc option on the command line wins): full Newton steps (a quadratic program: the step is exact on
# the reduced space, a line search only costs residuals); MUMPS Cholesky of the inactive block, SPD as K is (LU took
# 2.3x its time on 2D 120x40 and 1.4x on ex2.msh; MUMPS's orderings METIS, AMF, PORD, SCOTCH were not faster than auto)
opts = PETSc.Options()
for k, val in (("snes_linesearch_type", "basic"), ("ksp_type", "preonly"), ("pc_type", "cholesky"),
               ("pc_factor_mat_solver_type", "mumps"), ("snes_rtol", "1e-10"), ("snes_atol", "1e-50"),
               ("snes_max_it", "100")):
    if not opts.hasName(k):
        opts[k] = val
ksp = snes.getKSP()
pc = ksp.getPC()
snes.setFromOptions()
snes.setSolution(x)  # the work vectors are made like it
snes.setUp()
snes.solve(None, x)
t_snes = time.perf_counter() - t0

# ---- the result, measured as ours measures it
reason = snes.getConvergedReason()
uh.x.array[:] = x.getArray()
V_energy = fem.assemble_scalar(energy)
residual(snes, x, Fv)  # K u - b: at a contact dof, w_i lam_i (n = -e_dim), elsewhere ~0
Fa = Fv.getArray()
xn = x.getArray()[contact * bs + dim - 1]
force = Fa[contact * bs + dim - 1]
umax = np.abs(x.getArray()).max()
at_bound = np.abs(xn + dcon) <= 1e-9 * umax
free = np.ones(ndofs, dtype=bool)
free[bcdofs] = False
free[contact * bs + dim - 1] = False
res = {
    "problem": opt.problem, "mesh": opt.faces if opt.problem == "ex1" else opt.mesh,
    "dofs": ndof_free, "contact_vertices": int(len(contact)),
    "snes_type": snes.getType(), "ksp_type": ksp.getType(), "pc_type": pc.getType(), "factor": pc.getFactorSolverType(),
    "converged": reason > 0, "snes_reason": int(reason),
    "newton_iterations": snes.getIterationNumber(), "ksp_iterations": snes.getLinearSolveIterations(),
    "assembly_time": t_asm, "snes_time": t_snes,
    "energy": V_energy, "contact_force": float(force.sum()),
    "active_set_size": int(at_bound.sum()), "active_with_pressure": int((at_bound & (force > 0)).sum()),
    "equilibrium_free_inf": float(np.abs(Fa[free]).max()),
    "penetration_max": float(max(0.0, (-(xn + dcon)).max())),
    "displacement_max": float(umax),
}

if opt.ours:
    import h5py
    with h5py.File(opt.ours, "r") as f:
        gx = f["geometry/vertices"][:]
        gc = f["viz/topology/cells"][:]
        gu = f["vertex_fields/displacement_vector"][:]
        goff = f["vertex_fields/obstacle_offset_vector"][:]
    from scipy.spatial import cKDTree
    # vertices matched by position: dolfinx's dof coordinates are pushed forward through the coordinate map, so
    # they may differ from the file's in the last bits (no exact keys); a match must be far below the mesh size
    tree = cKDTree(gx)

    def match(pts):
        dist, idx = tree.query(pts)
        return idx, dist.max()

    # the mesh: the same vertices, the same cells (as sets of our vertex numbers)
    mx = msh.geometry.x[:, :dim]
    midx, mdist = match(mx)
    mcells = msh.geometry.dofmap.array.reshape(-1, dim + 1)
    peer_set = {frozenset(midx[c]) for c in mcells}
    ours_set = {frozenset(c) for c in gc}
    res["same_mesh"] = bool(len(mx) == len(gx) and mdist < 1e-12 and peer_set == ours_set)
    perm, pdist = match(X)  # peer vertex -> our vertex
    res["same_mesh"] = res["same_mesh"] and bool(pdist < 1e-12)
    up = x.getArray().reshape(-1, dim)
    res["displacement_diff_rel"] = float(np.abs(up - gu[perm]).max() / np.abs(gu).max())
    dours = -goff[perm[contact], dim - 1]  # obstacle_offset = d n, n = -e_dim
    res["gap_diff_max"] = float(np.abs(dours - dcon).max())

res["wall_time"] = time.perf_counter() - T_START
print(json.dumps(res, indent=1))
if opt.json:
    with open(opt.json, "w") as f:
        json.dump(res, f, indent=1)
