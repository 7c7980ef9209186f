#!/usr/bin/env python3
"""Elastic bar impact: a Q4 strip (length L = 1 m, width 0.05 m, one element across,
nu = 0 so that it is a 1D bar: c = sqrt(E / rho) = 1000 m/s) moving at v0 = 0.1 m/s hits
a rigid wall (JONCx) end-on at t = 0 (CLJCx at its two end nodes, frictionless
GAP_SGR_CLB), theta = 0.5, time step half the element transit time.

Reference (1D elastic wave): the end stays in contact for 2 L / c = 2 ms with the
compressive stress rho c v0 = 1e5 Pa, so a contact force rho c v0 w per unit thickness;
the bar then leaves at v0, its mean velocity, uniform and stress-free.
Measured on three meshes (25, 50, 100 elements along the bar; the long version adds
200): the contact duration (steps with a reaction times the step), the mean contact
force over the whole contact and over its middle half (the plateau), the rebound
velocity (momentum / mass after separation).
Tolerance at 100 elements: 2 % on each; the errors must fall as the mesh is refined
(coarsest > finest)."""
import sys
from pathlib import Path

import numpy as np

from fracas_tools.valmesh import Case, one_based, quads, rect_grid  # noqa: E402
from fracas_tools.valmesh import Checker, args, run_fracas  # noqa: E402

E, NU, RHO = 1.0e9, 0.0, 1000.0
L, W, V0 = 1.0, 0.05, 0.1
C = np.sqrt(E / RHO)


def build(case_dir, n):
    x = rect_grid(1, n, W, L)            # vertical bar, bottom end on the wall y = 0
    case = Case(gravity=(0.0, 0.0))
    case.add_material("BAR__", RHO, "ELAS", young=E, poisson=NU)
    case.add_material("TDURx", 1000.0)
    case.add_model("M2DQ4", "Q4xxx")
    case.add_jonc((W / 2, -0.01), W, 0.01, "TDURx").fix()
    b = case.add_mesh_body(x, one_based(quads(1, n)), model="M2DQ4", material="BAR__")
    b.set_velocity(0.0, -V0)
    # The two bottom nodes, on the edge 2 -> 1 (LMGC90's orientation: the body on the right).
    b.add_candidates([(2, 1, 1.0), (2, 1, 0.0)], "BLEUx")
    case.add_law("gap00", "GAP_SGR_CLB", fric=0.0)
    case.add_see("CLxxx", "BLEUx", "JONCx", "WALLx", "gap00", 1e-3)
    h = 0.5 * (L / n) / C
    steps = int(round(2.6 * L / C / h))
    case.run.set(time_step=h, number_of_steps=steps, theta=0.5, plane="stress", output_dof_every=0,
                 output_hdf5_every=1, nlgs_tolerance=1e-10, nlgs_max_checks=10000)
    case.write(case_dir)
    return h, steps


def measure(run, h):
    """Contact force per step (sum of the normal reactions, N/m), contact duration,
    mean force over the contact and over its middle half (the plateau), and the
    rebound velocity (momentum / mass after the run: lumped masses of a uniform strip
    one element across, end rows half)."""
    force = np.array([r[:, 1].sum() for r in run.snapshot_arrays("contacts/reaction")])
    on = np.nonzero(force > 0)[0]
    duration = (on[-1] - on[0] + 1) * h
    mean_force = force[on[0]:on[-1] + 1].mean()
    # The plateau: the middle half of the contact (away from the front's ringing).
    t = np.arange(1, len(force) + 1) * h
    mid = (t > 0.25 * 2 * L / C) & (t < 0.75 * 2 * L / C)
    v = run.snapshot(-1).mesh["V"][:, 1]
    m = np.ones(len(v))
    m[:2] = m[-2:] = 0.5
    return force, duration, mean_force, force[mid].mean(), np.sum(m * v) / np.sum(m)


def main():
    a = args(__doc__)
    ck = Checker("validation_meshes.bar_impact" + (".long" if a.long else ""))
    meshes = [25, 50, 100] + ([200] if a.long else [])
    f_ref = RHO * C * V0 * W
    rows = []
    for n in meshes:
        case = Path(a.out, f"n{n}")
        h, steps = build(case, n)
        with run_fracas(a.fracas, case) as run:
            force, duration, mean_force, plateau, v_reb = measure(run, h)
        rows.append((n, abs(duration / (2 * L / C) - 1), abs(mean_force / f_ref - 1), abs(v_reb / V0 - 1),
                     abs(plateau / f_ref - 1)))
        np.savetxt(Path(a.out, f"n{n}_force.txt"), np.column_stack([np.arange(1, len(force) + 1) * h, force]),
                   header=f"time contact_force (N/m), h = {h}")
        if n != 100:
            ck.info(f"{n} el: errors of duration, mean force, plateau, rebound",
                    "  ".join(f"{e:.2e}" for e in (rows[-1][1], rows[-1][2], rows[-1][4], rows[-1][3])))
            continue
        ck.rel(f"{n} el: contact duration (s) vs 2 L / c", duration, 2 * L / C, 0.02)
        ck.rel(f"{n} el: mean contact force (N/m) vs rho c v0 w", mean_force, f_ref, 0.02)
        ck.rel(f"{n} el: plateau force (middle half) vs rho c v0 w", plateau, f_ref, 0.02)
        ck.rel(f"{n} el: rebound velocity (m/s) vs v0", v_reb, V0, 0.02)
    np.savetxt(Path(a.out, "convergence.txt"), np.array(rows), fmt="%d %.6e %.6e %.6e %.6e",
               header="elements err_duration err_mean_force err_rebound_velocity err_plateau_force")
    r100 = rows[meshes.index(100)]
    for k, what in ((1, "duration"), (2, "mean contact force"), (3, "rebound velocity")):
        ck.at_most(f"{what}: error at 100 el / error at 25 el", r100[k] / max(rows[0][k], 1e-300), 1.0)
    sys.exit(ck.finish())


if __name__ == "__main__":
    main()
