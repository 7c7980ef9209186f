#!/usr/bin/env python3
"""2D Hertz contact: an elastic half-disk (radius R = 0.05 m, plane strain, E = 2e11,
nu = 0.3, T3 mesh from gmsh refined to a / 25 at the contact) pressed on a rigid
plane (JONCx, frictionless GAP_SGR_CLB at the nodes of its arc near the contact). Its
flat face (the diameter, y = R) is driven down by delta in 20 steps and held for 5,
with theta = 1 and steps of 10 ms, long against the disk's periods (1e-5 s): each step
is a static solve (the inertia term M / h^2 is 1e-6 of the stiffness).

Reference, the plane-strain Hertz solution for a cylinder on a rigid plane under the
load P per unit length: half-width a = sqrt(4 P R / (pi E*)), E* = E / (1 - nu^2),
peak pressure p0 = 2 P / (pi a), pressure p0 sqrt(1 - x^2 / a^2). Measured from the
contact reactions of the last step (fracas.h5 snapshot, full precision): P = sum of
the normal forces; a = 2 sqrt(sum F_i x_i^2 / sum F_i) (the Hertz distribution has
<x^2> = a^2 / 4); p0 = the force of the central node over its tributary length (half
the distance to its neighbours). Tolerance 3 % on a and p0."""
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from meshdeck import Case, one_based  # noqa: E402
from valmesh import Checker, args, run_fracas  # noqa: E402

E, NU, RHO, R = 2.0e11, 0.3, 7800.0, 0.05
E_STAR = E / (1 - NU ** 2)
A_TARGET = 0.04 * R          # half-width the drive is chosen for


def half_disk_mesh(h_contact, h_far):
    """T3 mesh of the half-disk below its diameter (centre (0, R), contact point at
    the origin), refined near the bottom. Returns nodes (n, 2), triangles (m, 3),
    the arc's node sequence from right to left, and the diameter's nodes."""
    import gmsh
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("half_disk")
    occ = gmsh.model.occ
    c = occ.addPoint(0, R, 0)
    pr = occ.addPoint(R, R, 0)
    pb = occ.addPoint(0, 0, 0)
    pl = occ.addPoint(-R, R, 0)
    arc1 = occ.addCircleArc(pr, c, pb)
    arc2 = occ.addCircleArc(pb, c, pl)
    diam = occ.addLine(pl, pr)
    loop = occ.addCurveLoop([arc1, arc2, diam])
    occ.addPlaneSurface([loop])
    occ.synchronize()
    f = gmsh.model.mesh.field
    dist = f.add("Distance")
    f.setNumbers(dist, "PointsList", [pb])
    thr = f.add("Threshold")
    f.setNumber(thr, "InField", dist)
    f.setNumber(thr, "SizeMin", h_contact)
    f.setNumber(thr, "SizeMax", h_far)
    f.setNumber(thr, "DistMin", 2.0 * A_TARGET)
    f.setNumber(thr, "DistMax", 0.6 * R)
    f.setAsBackgroundMesh(thr)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    gmsh.model.mesh.generate(2)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    index = {t: k for k, t in enumerate(tags)}
    nodes = coords.reshape(-1, 3)[:, :2]
    et, en = gmsh.model.mesh.getElementsByType(2)
    tri = np.array([index[t] for t in en]).reshape(-1, 3)

    def curve_nodes(curve):
        t, _, _ = gmsh.model.mesh.getNodes(1, curve, includeBoundary=True)
        return [index[x] for x in t]
    arc_nodes = set(curve_nodes(arc1)) | set(curve_nodes(arc2))
    diam_nodes = curve_nodes(diam)
    gmsh.finalize()
    # Counter-clockwise triangles.
    x = nodes[tri]
    area = (x[:, 1, 0] - x[:, 0, 0]) * (x[:, 2, 1] - x[:, 0, 1]) - (x[:, 2, 0] - x[:, 0, 0]) * (x[:, 1, 1] - x[:, 0, 1])
    tri[area < 0] = tri[area < 0][:, [0, 2, 1]]
    # Keep the nodes of the triangles only (gmsh also returns the arcs' centre).
    used = np.unique(tri)
    new = -np.ones(len(nodes), dtype=int)
    new[used] = np.arange(len(used))
    nodes, tri = nodes[used], new[tri]
    arc = sorted((new[k] for k in arc_nodes), key=lambda k: -nodes[k, 0])       # right to left
    return nodes, tri, arc, [new[k] for k in diam_nodes]


def build(case_dir, h_contact, delta):
    nodes, tri, arc, diam = half_disk_mesh(h_contact, R / 8)
    nodes = np.round(nodes, 12)
    case = Case(gravity=(0.0, 0.0))
    case.add_material("DISKx", RHO, "ELAS", young=E, poisson=NU)
    case.add_material("TDURx", 1000.0)
    case.add_model("M2DT3", "T3xxx")
    case.add_jonc((0.0, -0.005), 2 * R, 0.005, "TDURx").fix()
    b = case.add_mesh_body(nodes, one_based(tri), model="M2DT3", material="DISKx")
    # Candidate points at the arc nodes within 3 a of the bottom, each on its edge
    # towards the left neighbour (right node first, as LMGC90 orients a lower edge).
    near = [k for k in range(len(arc) - 1) if abs(nodes[arc[k], 0]) < 3 * A_TARGET]
    b.add_candidates([(arc[k] + 1, arc[k + 1] + 1, 0.0) for k in near], "BLEUx")
    case.add_law("gap00", "GAP_SGR_CLB", fric=0.0)
    case.add_see("CLxxx", "BLEUx", "JONCx", "WALLx", "gap00", 0.2 * A_TARGET)
    h, n_load, n_hold = 1.0e-2, 20, 5
    table = [(0.0, 0.0), (h, -delta / (n_load * h)), (n_load * h, -delta / (n_load * h)), ((n_load + 1) * h, 0.0),
             ((n_load + n_hold) * h, 0.0)]
    top = [k + 1 for k in diam]
    b.impose_velocity(top, 1)
    b.impose_evolution(top, 2, "vlocy", "descent.dat", data=np.array(table))
    case.run.set(time_step=h, number_of_steps=n_load + n_hold, theta=1.0, plane="strain", output_dof_every=0,
                 output_hdf5_every=n_load + n_hold, nlgs_tolerance=1e-8, nlgs_max_checks=20000)
    case.write(case_dir)
    return len(nodes), len(tri), len(near)


def measure(run):
    s = run.snapshot(-1)
    rn, xs = s.contacts["reaction"][:, 1], s.contacts["point"][:, 0]
    on = rn > 0
    order = np.argsort(xs)
    xs, rn = xs[order], rn[order]
    P = rn.sum()
    a = 2.0 * np.sqrt(np.sum(rn * xs ** 2) / P)
    k = int(np.argmin(np.abs(xs)))
    trib = 0.5 * (xs[k + 1] - xs[k - 1])
    p0 = rn[k] / trib
    return P, a, p0, xs, rn, int(on.sum())


def main():
    a = args(__doc__)
    h_contact = A_TARGET / (40 if a.long else 25)
    # The flat face's descent that gives a close to A_TARGET (found by a first run).
    delta = 1.6e-4
    case = Path(a.out, "long" if a.long else "quick")
    nn, ne, nc = build(case, h_contact, delta)
    with run_fracas(a.fracas, case) as run:
        P, a_m, p0_m, xs, rn, n_on = measure(run)
    a_h = np.sqrt(4 * P * R / (np.pi * E_STAR))
    p0_h = 2 * P / (np.pi * a_h)
    ck = Checker("validation_meshes.hertz" + (".long" if a.long else ""))
    ck.info(f"mesh: {nn} nodes, {ne} T3, element size at the contact a / n", a_h / h_contact)
    ck.info(f"candidate nodes {nc}, carrying a force", n_on)
    ck.info("load P (N/m)", P)
    ck.info("a / R", a_h / R)
    np.savetxt(Path(a.out, "pressure.txt"), np.column_stack([xs, rn]), header=f"x (m) nodal force (N/m); P = {P}")
    ck.rel("half-width a (m) vs sqrt(4 P R / (pi E*))", a_m, a_h, 0.03)
    ck.rel("peak pressure p0 (Pa) vs 2 P / (pi a)", p0_m, p0_h, 0.03)
    sys.exit(ck.finish())


if __name__ == "__main__":
    main()
