#!/usr/bin/env python3
"""Energy of elastic meshes with theta = 0.5.

1. Free vibration: an elastic Q4 block (0.2 m x 0.1 m, 16 x 8, plane strain), no
   gravity, no support, started with a non-rigid velocity field, 1000 steps of 2e-6 s
   (about 8 periods of its first mode). The theta = 0.5 scheme is the trapezoidal
   rule: for a linear body it conserves kinetic + elastic energy exactly, so the
   total drifts by round-off only. Tolerance 1e-6 relative over the 1000 steps
   (series kinetic_energy + elastic_energy of fracas.h5, against the kinetic energy
   at t = 0 from mesh_probe). Lumped and consistent mass.
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

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from meshdeck import Deck, quads, rect_grid  # noqa: E402
from valmesh import args, check, finish, run_fracas, run_probe, series  # noqa: E402

E, NU, RHO = 1.0e9, 0.3, 2000.0
LX, LY = 0.2, 0.1


def vibration(case_dir, mass):
    nx, ny = 16, 8
    x = rect_grid(nx, ny, LX, LY)
    d = Deck()
    d.material("BLOCK", rho=RHO, E=E, nu=NU)
    d.model("M2DQ4", "Q4xxx", mass=mass)
    b = d.mesh(x, quads(nx, ny), "M2DQ4", "BLOCK")
    # Bending-like and stretching velocities (m/s), zero mean momentum is not needed.
    b.v0 = np.column_stack([0.05 * np.sin(np.pi * x[:, 0] / LX) * (x[:, 1] / LY - 0.5),
                            0.1 * np.sin(np.pi * x[:, 0] / LX)])
    b.v0 = np.round(b.v0, 7)      # written exactly in DOF.INI
    d.command(time_step=2.0e-6, number_of_steps=1000, theta=0.5, plane="strain", output_dof_every=0)
    d.write(case_dir)


def bouncing(case_dir):
    nx, ny = 8, 4
    x = rect_grid(nx, ny, LX, LY, y0=1e-4)
    d = Deck()
    d.gravity = (0.0, -9.81)
    d.material("BLOCK", rho=RHO, E=E, nu=NU)
    d.material("TDURx", rho=1000.0)
    d.model("M2DQ4", "Q4xxx")
    d.wall((0.1, -0.01), 0.2, 0.01)
    b = d.mesh(x, quads(nx, ny), "M2DQ4", "BLOCK")
    b.candidates(bottom_candidates(nx))
    d.law("gapc0", "GAP_SGR_CLB", [[("fric", 0.0)]])
    d.see_rule("MAILx", "CLxxx", "BLEUx", "gapc0", "RBDY2", "JONCx", "WALLx", 5e-3)
    d.command(time_step=5.0e-5, number_of_steps=800, theta=0.5, plane="strain", output_dof_every=0,
              nlgs_tolerance=1e-10, nlgs_max_checks=10000)
    d.write(case_dir)


def bottom_candidates(nx):
    """CLxxx points at the bottom nodes of a rect_grid, on edges oriented as LMGC90's
    pre-processor writes them (outward normal on the right: right node first)."""
    pts = [(1, 0, 1.0)]
    pts += [(i + 1, i, 0.0) for i in range(nx)]
    return pts


def main():
    a = args(__doc__)
    for mass in ("lump_", "coher"):
        case = Path(a.out, f"vibration_{mass}")
        vibration(case, mass)
        e0 = run_probe(a.probe, case, Path(a.out, f"vibration_{mass}.probe"), every=1000)[0]["energy"]
        run_fracas(a.fracas, case)
        ke, el = series(case, "kinetic_energy", "elastic_energy")
        total = ke + el
        drift = np.abs(total - e0[0]).max() / e0[0]
        check(f"free vibration ({mass} mass): max |E(t) - E(0)| / E(0) over 1000 steps", drift, 1e-6,
              f"(E(0) = {e0[0]:.6e} J/m; elastic energy reaches {el.max() / e0[0]:.2f} E(0))")
    case = Path(a.out, "bouncing_block")
    bouncing(case)
    run_fracas(a.fracas, case)
    ke, el, wg, diss, act, bal = series(case, "kinetic_energy", "elastic_energy", "work_gravity", "dissipated",
                                        "active_contacts", "balance_error")
    # Initial kinetic energy 0 (the block starts at rest); E = KE + elastic - W_gravity.
    etot = np.concatenate([[0.0], ke + el - wg])
    dE = np.diff(etot)
    scale = wg.max()
    quiet = act == 0
    check(f"bouncing block: |Delta E| at the {quiet.sum()} steps without contact reaction / E_scale",
          np.abs(dE[quiet]).max() / scale, 1e-10, f"(E_scale = largest work of gravity {scale:.4e} J/m)")
    check(f"bouncing block: energy gain at the {(~quiet).sum()} steps with reactions / E_scale",
          max(dE[~quiet].max(), 0.0) / scale, 1e-10,
          f"(total lost {-dE[~quiet].sum():.4e} J/m = {-dE[~quiet].sum() / scale:.2%} of E_scale)")
    ddiss = np.diff(np.concatenate([[0.0], diss]))
    check("bouncing block: energy lost at each step = the step's contact dissipation (series dissipated)",
          np.abs(-dE - ddiss).max() / scale, 1e-10)
    check("bouncing block: balance_error / E_scale", np.abs(bal).max() / scale, 1e-10)
    n_impacts = int(np.sum(np.diff(np.concatenate([[0], (act > 0).astype(int)])) == 1))
    print(f"INFO bouncing block: {n_impacts} contact episodes, {(~quiet).sum()} steps with reactions")
    finish()


if __name__ == "__main__":
    main()
