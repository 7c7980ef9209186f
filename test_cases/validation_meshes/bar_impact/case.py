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

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from meshdeck import Deck, quads, rect_grid  # noqa: E402
from valmesh import args, check, finish, run_probe, run_fracas  # noqa: E402

E, NU, RHO = 1.0e9, 0.0, 1000.0
L, W, V0 = 1.0, 0.05, 0.1
C = np.sqrt(E / RHO)


def build(case_dir, n):
    x = rect_grid(1, n, W, L)            # vertical bar, bottom end on the wall y = 0
    d = Deck()
    d.material("BAR__", rho=RHO, E=E, nu=NU)
    d.material("TDURx", rho=1000.0)
    d.model("M2DQ4", "Q4xxx")
    d.wall((W / 2, -0.01), W, 0.01)
    b = d.mesh(x, quads(1, n), "M2DQ4", "BAR__")
    b.v0[:, 1] = -V0
    b.candidates([(1, 0, 1.0), (1, 0, 0.0)])     # the two bottom nodes (edge 2 -> 1, as LMGC90 orients it)
    d.law("gap00", "GAP_SGR_CLB", [[("fric", 0.0)]])
    d.see_rule("MAILx", "CLxxx", "BLEUx", "gap00", "RBDY2", "JONCx", "WALLx", 1e-3)
    h = 0.5 * (L / n) / C
    steps = int(round(2.6 * L / C / h))
    d.command(time_step=h, number_of_steps=steps, theta=0.5, plane="stress", output_dof_every=0,
              nlgs_tolerance=1e-10, nlgs_max_checks=10000)
    d.write(case_dir)
    return h, steps


def measure(case_dir, h, n):
    import h5py
    with h5py.File(Path(case_dir, "OUTBOX", "fracas.h5"), "r") as f:
        force = []
        for name in sorted(f["snapshots"]):
            rn = f["snapshots"][name]["contacts/reaction"][:, 1] if f["snapshots"][name]["contacts"].attrs["count"] else []
            force.append(float(np.sum(rn)))
    force = np.array(force)
    on = np.nonzero(force > 0)[0]
    duration = (on[-1] - on[0] + 1) * h
    mean_force = force[on[0]:on[-1] + 1].mean()
    # The plateau: the middle half of the contact (away from the front's ringing).
    t = np.arange(1, len(force) + 1) * h
    mid = (t > 0.25 * 2 * L / C) & (t < 0.75 * 2 * L / C)
    return force, duration, mean_force, force[mid].mean()


def main():
    a = args(__doc__)
    meshes = [25, 50, 100] + ([200] if a.long else [])
    rows = []
    for n in meshes:
        case = Path(a.out, f"n{n}")
        h, steps = build(case, n)
        run_fracas(a.fracas, case, "output_hdf5_every=1")
        force, duration, mean_force, plateau = measure(case, h, n)
        rec = run_probe(a.probe, case, Path(a.out, f"n{n}.probe"))[-1]
        v = rec["nodes"][:, 5]
        # Lumped masses of a uniform 1-across strip: end rows half.
        m = np.ones(len(v))
        m[:2] = m[-2:] = 0.5
        v_reb = np.sum(m * v) / np.sum(m)
        e_dur = abs(duration / (2 * L / C) - 1)
        e_force = abs(mean_force / (RHO * C * V0 * W) - 1)
        e_reb = abs(v_reb / V0 - 1)
        e_plateau = abs(plateau / (RHO * C * V0 * W) - 1)
        rows.append((n, e_dur, e_force, e_reb, e_plateau))
        np.savetxt(Path(a.out, f"n{n}_force.txt"), np.column_stack([np.arange(1, len(force) + 1) * h, force]),
                   header=f"time contact_force (N/m), h = {h}")
        print(f"INFO {n} elements: duration {duration * 1e3:.4f} ms (2L/c = {2 * L / C * 1e3:.4f}), "
              f"mean force {mean_force:.2f} N/m (rho c v0 w = {RHO * C * V0 * W:.2f}), rebound {v_reb:.5f} m/s: "
              f"errors {e_dur:.2e}, {e_force:.2e}, {e_reb:.2e}; plateau stress error {e_plateau:.2e}")
    np.savetxt(Path(a.out, "convergence.txt"), np.array(rows),
               header="elements err_duration err_mean_force err_rebound_velocity err_plateau_force")
    r100 = rows[meshes.index(100)]
    check("100 elements: contact duration against 2 L / c", r100[1], 0.02)
    check("100 elements: mean contact stress against rho c v0", r100[2], 0.02)
    check("100 elements: rebound velocity against v0", r100[3], 0.02)
    check("100 elements: plateau contact stress (middle half of the contact) against rho c v0", r100[4], 0.02)
    for k, what in ((1, "duration"), (2, "contact stress"), (3, "rebound velocity")):
        check(f"{what}: the error falls from 25 to 100 elements (ratio finest / coarsest)",
              rows[meshes.index(100)][k] / max(rows[0][k], 1e-300), 1.0)
    finish()


if __name__ == "__main__":
    main()
