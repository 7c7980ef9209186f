#!/usr/bin/env python3
"""Energy of elastic meshes with theta = 0.5.

1. Free vibration: an elastic Q4 block (0.2 m x 0.1 m, 16 x 8, plane strain), no
   gravity, no support, started with a non-rigid velocity field, 1000 steps of 2e-6 s
   (about 8 periods of its first mode). The theta = 0.5 scheme is the trapezoidal
   rule: for a linear body it conserves kinetic + elastic energy exactly, so the
   total drifts by round-off only. Tolerance 1e-6 relative over the 1000 steps
   (series kinetic_energy + elastic_energy of fracas.h5, against the kinetic energy
   at t = 0, 1/2 v0^T M v0 with the element mass matrices of a rectangle computed
   here: lumped rho A / 4 per node, consistent rho A / 36 [4 2 1 2; ...]). Lumped and
   consistent mass.
2. Bouncing block: the same block (8 x 4) dropped from 0.1 mm onto a rigid wall
   (frictionless GAP_SGR_CLB, CLJCx at its bottom nodes), gravity, 800 steps of
   5e-5 s (first impact at step 91, then bounces and chatter). Total energy E = kinetic + elastic - work of gravity. Checks: at steps
   whose contacts carry no reaction, |E_n - E_(n-1)| <= 1e-10 E_scale; at steps with
   reactions E never grows (beyond the same round-off) and the energy lost equals the
   series 'dissipated' (contact dissipation -r.(u + u_begin)/2) to 1e-10 E_scale;
   balance_error stays below 1e-10 E_scale."""
import sys
from pathlib import Path

import numpy as np

from fracas_tools.valmesh import Case, one_based, quads, rect_grid  # noqa: E402
from fracas_tools.valmesh import Checker, args, run_fracas  # noqa: E402

E, NU, RHO = 1.0e9, 0.3, 2000.0
LX, LY = 0.2, 0.1


def vibration(case_dir, mass):
    nx, ny = 16, 8
    x = rect_grid(nx, ny, LX, LY)
    case = Case(gravity=(0.0, 0.0))
    case.add_material("BLOCK", RHO, "ELAS", young=E, poisson=NU)
    case.add_model("M2DQ4", "Q4xxx", mass_storage=mass)
    b = case.add_mesh_body(x, one_based(quads(nx, ny)), model="M2DQ4", material="BLOCK")
    # Bending-like and stretching velocities (m/s), rounded to be written exactly in DOF.INI.
    b.v0[:] = np.round(np.column_stack([0.05 * np.sin(np.pi * x[:, 0] / LX) * (x[:, 1] / LY - 0.5),
                                        0.1 * np.sin(np.pi * x[:, 0] / LX)]), 7)
    case.run.set(time_step=2.0e-6, number_of_steps=1000, theta=0.5, plane="strain", output_dof_every=0,
                 output_hdf5_every=0)
    case.write(case_dir)
    return x, quads(nx, ny), b.v0.copy()


def kinetic_energy(x, elements, v, mass):
    """1/2 v^T M v per unit thickness for rectangular Q4 elements (counter-clockwise
    nodes): lumped rho A / 4 per node (row sums), or the consistent mass
    rho A / 36 [[4 2 1 2], [2 4 2 1], [1 2 4 2], [2 1 2 4]] per direction."""
    consistent = np.array([[4, 2, 1, 2], [2, 4, 2, 1], [1, 2, 4, 2], [2, 1, 2, 4]]) / 36.0
    lumped = np.eye(4) / 4.0
    m = consistent if mass == "coher" else lumped
    ke = 0.0
    for e in elements:
        area = abs(x[e[1], 0] - x[e[0], 0]) * abs(x[e[3], 1] - x[e[0], 1])
        ve = v[e]
        ke += 0.5 * RHO * area * sum(ve[:, d] @ m @ ve[:, d] for d in (0, 1))
    return ke


def bouncing(case_dir):
    nx, ny = 8, 4
    x = rect_grid(nx, ny, LX, LY, y0=1e-4)
    case = Case(gravity=(0.0, -9.81))
    case.add_material("BLOCK", RHO, "ELAS", young=E, poisson=NU)
    case.add_material("TDURx", 1000.0)
    case.add_model("M2DQ4", "Q4xxx")
    case.add_jonc((0.1, -0.01), 0.2, 0.01, "TDURx").fix()
    b = case.add_mesh_body(x, one_based(quads(nx, ny)), model="M2DQ4", material="BLOCK")
    b.add_candidates(bottom_candidates(nx), "BLEUx")
    case.add_law("gapc0", "GAP_SGR_CLB", fric=0.0)
    case.add_see("CLxxx", "BLEUx", "JONCx", "WALLx", "gapc0", 5e-3)
    case.run.set(time_step=5.0e-5, number_of_steps=800, theta=0.5, plane="strain", output_dof_every=0,
                 output_hdf5_every=0, nlgs_tolerance=1e-10, nlgs_max_checks=10000)
    case.write(case_dir)


def bottom_candidates(nx):
    """CLxxx points (1-based) at the bottom nodes of a rect_grid, on edges oriented as
    LMGC90's pre-processor writes them (walking noda -> nodb the body is on the right:
    right node first)."""
    return [(2, 1, 1.0)] + [(i + 2, i + 1, 0.0) for i in range(nx)]


def main():
    a = args(__doc__)
    ck = Checker("validation_meshes.energy")
    for mass in ("lump_", "coher"):
        case = Path(a.out, f"vibration_{mass}")
        x, elements, v0 = vibration(case, mass)
        e0 = kinetic_energy(x, elements, v0, mass)
        with run_fracas(a.fracas, case) as run:
            ke, el = run.series["kinetic_energy"], run.series["elastic_energy"]
        total = ke + el
        k = int(np.argmax(np.abs(total - e0)))
        ck.true(f"free vibration ({mass}): 1000 steps", len(total) == 1000, len(total), 1000)
        ck.rel(f"free vibration ({mass}): worst KE + elastic over 1000 steps", total[k], e0, 1e-6,
               f"step {k + 1}; E(0) = 1/2 v0 M v0; elastic reaches {el.max() / e0:.2f} E(0)")
    case = Path(a.out, "bouncing_block")
    bouncing(case)
    with run_fracas(a.fracas, case) as run:
        ke, el, wg, diss, act, bal = (run.series[k] for k in ("kinetic_energy", "elastic_energy", "work_gravity",
                                                               "dissipated", "active_contacts", "balance_error"))
    # Initial kinetic energy 0 (the block starts at rest); E = KE + elastic - W_gravity.
    etot = np.concatenate([[0.0], ke + el - wg])
    dE = np.diff(etot)
    scale = wg.max()
    quiet = act == 0
    ck.info("bouncing block: energy scale (largest work of gravity), J/m", scale)
    ck.at_most(f"bouncing: max |dE| / scale, {quiet.sum()} steps without reaction",
               np.abs(dE[quiet]).max() / scale, 1e-10)
    ck.at_most(f"bouncing: max gain / scale, {(~quiet).sum()} steps with reactions",
               max(dE[~quiet].max(), 0.0) / scale, 1e-10)
    ddiss = np.diff(np.concatenate([[0.0], diss]))
    ck.at_most("bouncing: |loss - contact dissipation| / scale, each step",
               np.abs(-dE - ddiss).max() / scale, 1e-10)
    ck.at_most("bouncing: max |balance_error| / scale", np.abs(bal).max() / scale, 1e-10)
    n_impacts = int(np.sum(np.diff(np.concatenate([[0], (act > 0).astype(int)])) == 1))
    ck.info("bouncing block: contact episodes", n_impacts)
    ck.info("bouncing block: energy lost in contacts / scale", -dE[~quiet].sum() / scale)
    sys.exit(ck.finish())


if __name__ == "__main__":
    main()
