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
the distance to its neighbours); x in the reference configuration (Hertz's theory is
linear elasticity) and, also checked, in the deformed one. Tolerance 3 % on a and p0.
The long version: a / 40, and the tables of mesh convergence (a / 12, 25, 40) and of
the contact size (a / R = 0.015, 0.04, 0.1)."""
import sys
from pathlib import Path

import numpy as np

from fracas_tools.valmesh import Case, one_based  # noqa: E402
from fracas_tools.valmesh import Checker, args, run_fracas  # noqa: E402

E, NU, RHO, R = 2.0e11, 0.3, 7800.0, 0.05
E_STAR = E / (1 - NU ** 2)
A_REF, DELTA_REF = 0.0405 * R, 1.6e-4   # a measured for the descent DELTA_REF of the flat face


def descent_for(a_target):
    """Descent of the flat face giving a close to a_target: scaled from the measured
    (A_REF, DELTA_REF) by the 2D approach law delta ~ a^2 (2 ln(4 R / a) - 1)."""
    def law(a):
        return a * a * (2 * np.log(4 * R / a) - 1)
    return DELTA_REF * law(a_target) / law(A_REF)


def half_disk_mesh(h_contact, h_far, a_target):
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
    f.setNumber(thr, "DistMin", 2.0 * a_target)
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


def build(case_dir, a_target, per_a):
    """The case with the contact refined to a_target / per_a; returns the mesh sizes
    and the reference x of each candidate (contactor rank order)."""
    h_contact = a_target / per_a
    delta = descent_for(a_target)
    nodes, tri, arc, diam = half_disk_mesh(h_contact, R / 8, a_target)
    nodes = np.round(nodes, 12)
    case = Case(gravity=(0.0, 0.0))
    case.add_material("DISKx", RHO, "ELAS", young=E, poisson=NU)
    case.add_material("TDURx", 1000.0)
    case.add_model("M2DT3", "T3xxx")
    case.add_jonc((0.0, -0.005), 2 * R, 0.005, "TDURx").fix()
    b = case.add_mesh_body(nodes, one_based(tri), model="M2DT3", material="DISKx")
    # Candidate points at the arc nodes within 3 a of the bottom, each on its edge
    # towards the left neighbour (right node first, as LMGC90 orients a lower edge).
    near = [k for k in range(len(arc) - 1) if abs(nodes[arc[k], 0]) < 3 * a_target]
    b.add_candidates([(arc[k] + 1, arc[k + 1] + 1, 0.0) for k in near], "BLEUx")
    case.add_law("gap00", "GAP_SGR_CLB", fric=0.0)
    case.add_see("CLxxx", "BLEUx", "JONCx", "WALLx", "gap00", 0.2 * a_target)
    h, n_load, n_hold = 1.0e-2, 20, 5
    table = [(0.0, 0.0), (h, -delta / (n_load * h)), (n_load * h, -delta / (n_load * h)), ((n_load + 1) * h, 0.0),
             ((n_load + n_hold) * h, 0.0)]
    top = [k + 1 for k in diam]
    b.impose_velocity(top, 1)
    b.impose_evolution(top, 2, "vlocy", "descent.dat", data=np.array(table))
    case.run.set(time_step=h, number_of_steps=n_load + n_hold, theta=1.0, plane="strain", output_dof_every=0,
                 output_hdf5_every=n_load + n_hold, nlgs_tolerance=1e-8, nlgs_max_checks=20000)
    case.write(case_dir)
    return len(nodes), len(tri), h_contact, np.array([nodes[arc[k], 0] for k in near])


def measure(run, x_ref):
    """P, a, p0 from the last snapshot's contacts; a also from the candidates'
    reference positions (the contact points move sideways as the disk is squeezed)."""
    s = run.snapshot(-1)
    rn, xs = s.contacts["reaction"][:, 1], s.contacts["point"][:, 0]
    x0 = x_ref[s.contacts["cd_tactor"] - 1]
    P = rn.sum()
    a_cur = 2.0 * np.sqrt(np.sum(rn * xs ** 2) / P)
    a_ref = 2.0 * np.sqrt(np.sum(rn * x0 ** 2) / P)
    order = np.argsort(xs)
    xs, x0, rn = xs[order], x0[order], rn[order]
    k = int(np.argmin(np.abs(xs)))
    p0 = rn[k] / (0.5 * (xs[k + 1] - xs[k - 1]))
    p0_ref = rn[k] / (0.5 * (x0[k + 1] - x0[k - 1]))
    return P, a_cur, p0, a_ref, p0_ref, xs, rn


def run_case(a, ck, label, a_target, per_a):
    case = Path(a.out, label)
    nn, ne, h_contact, x_ref = build(case, a_target, per_a)
    with run_fracas(a.fracas, case) as run:
        P, a_m, p0_m, a_r, p0_r, xs, rn = measure(run, x_ref)
    a_h = np.sqrt(4 * P * R / (np.pi * E_STAR))
    p0_h = 2 * P / (np.pi * a_h)
    ck.info(f"{label}: {nn} nodes, {ne} T3, {len(x_ref)} candidates; a / R", a_h / R)
    ck.info(f"{label}: element size at the contact a / n, n =", a_h / h_contact)
    np.savetxt(Path(a.out, f"{label}_pressure.txt"), np.column_stack([xs, rn]),
               header=f"x (m) nodal force (N/m); P = {P}")
    return ((a_h / R, a_h / h_contact, a_m / a_h - 1, p0_m / p0_h - 1, a_r / a_h - 1, p0_r / p0_h - 1),
            (a_m, a_h, p0_m, p0_h, a_r, p0_r))


def main():
    a = args(__doc__)
    ck = Checker("validation_meshes.hertz" + (".long" if a.long else ""))
    checked = 40 if a.long else 25
    row, (a_m, a_h, p0_m, p0_h, a_r, p0_r) = run_case(a, ck, f"a{checked}", A_REF, checked)
    # Hertz's theory is linear elasticity: its a and p0 are in the reference
    # configuration (positions of the nodes in BODIES.DAT); the deformed contact
    # points have moved sideways by about p0 / E* = a / (2 R) of their distance.
    ck.rel(f"a / {checked}: half-width a (m), reference positions", a_r, a_h, 0.03)
    ck.rel(f"a / {checked}: peak pressure p0 (Pa), reference positions", p0_r, p0_h, 0.03)
    ck.rel(f"a / {checked}: half-width a (m), deformed positions", a_m, a_h, 0.03)
    ck.rel(f"a / {checked}: peak pressure p0 (Pa), deformed positions", p0_m, p0_h, 0.03)
    if a.long:
        # Mesh convergence at a / R = 0.04, then the size of the contact at a / 25.
        rows = [run_case(a, ck, f"a{n}", A_REF, n)[0] for n in (12, 25)] + [row]
        rows += [run_case(a, ck, f"aR{ar:g}_a25", ar * R, 25)[0] for ar in (0.015, 0.1)]
        for r in rows:
            ck.info(f"a/R {r[0]:.3f}, a/{r[1]:.0f}: err a, p0 (deformed; reference)",
                    "  ".join(f"{e:+.2e}" for e in r[2:]))
        np.savetxt(Path(a.out, "convergence.txt"), np.array(rows), fmt="%.5f %.2f %+.5e %+.5e %+.5e %+.5e",
                   header="a/R a/element_size err_a err_p0 (deformed positions) err_a err_p0 (reference positions) "
                          "(rows 1-3: mesh convergence; 4-5: contact size)")
    sys.exit(ck.finish())


if __name__ == "__main__":
    main()
