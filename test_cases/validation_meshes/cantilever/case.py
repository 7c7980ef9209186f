#!/usr/bin/env python3
"""Cantilever under a tip load, brought to rest: a Q4 beam (L = 1 m, H = 0.1 m, plane
stress, E = 1e9 Pa, nu = 0.3), its left end clamped (every node of x = 0 held), the
load P = 1000 N/m applied at x = L as the parabolic shear of beam theory (consistent
nodal forces), ramped in over 5 steps and held for 5, with theta = 1 and steps of 1 s,
long against the first bending period (0.062 s): every step is a static solve and the
beam is at rest at the end.

Reference: Timoshenko beam theory, deflection of the neutral axis at the tip
P L^3 / (3 E I) + P L / (kappa G H), I = H^3 / 12, G = E / (2 (1 + nu)), kappa = 5/6.
(The plane-stress elasticity solution of Timoshenko and Goodier, P L^3 / (3 E I) +
(4 + 5 nu) P L / (2 E H), differs from it by 0.01 %.) Measured: the vertical
displacement of the tip node at mid-height (mesh_probe, full precision) on three
meshes 40 x 4, 80 x 8, 160 x 16 (long version: 320 x 32). Tolerance 2 % on the
160 x 16 mesh; the error must fall with refinement."""
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from meshdeck import Deck, node_id, quads, rect_grid  # noqa: E402
from valmesh import args, check, finish, run_probe  # noqa: E402

E, NU, RHO = 1.0e9, 0.3, 1000.0
L, H, P = 1.0, 0.1, 1000.0
I = H ** 3 / 12
G = E / (2 * (1 + NU))
TIMOSHENKO = P * L ** 3 / (3 * E * I) + P * L / (5.0 / 6.0 * G * H)
GOODIER = P * L ** 3 / (3 * E * I) + (4 + 5 * NU) * P * L / (2 * E * H)


def shear_forces(ys):
    """Consistent nodal forces of tau(y) = 3 P / (2 H) (1 - (2 y / H - 1)^2) on the
    end edge with nodes at ys (linear shape functions; Simpson is exact: cubic)."""
    def tau(y):
        return 1.5 * P / H * (1 - (2 * y / H - 1) ** 2)
    f = np.zeros(len(ys))
    for k in range(len(ys) - 1):
        y0, y1 = ys[k], ys[k + 1]
        ym, le = 0.5 * (y0 + y1), y1 - y0
        # int tau N0 and int tau N1 over the edge (Simpson, exact for degree 3).
        f[k] += le / 6 * (tau(y0) * 1 + 4 * tau(ym) * 0.5 + tau(y1) * 0)
        f[k + 1] += le / 6 * (tau(y0) * 0 + 4 * tau(ym) * 0.5 + tau(y1) * 1)
    return f


def build(case_dir, nx, ny):
    x = rect_grid(nx, ny, L, H)
    d = Deck()
    d.material("BEAMx", rho=RHO, E=E, nu=NU)
    d.model("M2DQ4", "Q4xxx")
    b = d.mesh(x, quads(nx, ny), "M2DQ4", "BEAMx")
    for j in range(ny + 1):
        for dof in (1, 2):
            d.drive(b, node_id(0, j, nx), dof)
    f = shear_forces(x[[node_id(nx, j, nx) for j in range(ny + 1)], 1])
    h = 1.0
    for j in range(ny + 1):
        # Downward force ramped in over 5 steps: value = CT min(1, RAMP t).
        d.drive(b, node_id(nx, j, nx), 2, kind="force", ct=-f[j], rampi=0.0, ramp=1.0 / (5 * h))
    d.command(time_step=h, number_of_steps=10, theta=1.0, plane="stress", output_dof_every=0)
    d.write(case_dir)
    return node_id(nx, ny // 2, nx)


def main():
    a = args(__doc__)
    meshes = [(40, 4), (80, 8), (160, 16)] + ([(320, 32)] if a.long else [])
    errs = []
    for nx, ny in meshes:
        case = Path(a.out, f"m{nx}x{ny}")
        tip = build(case, nx, ny)
        recs = run_probe(a.probe, case, Path(a.out, f"m{nx}x{ny}.probe"), every=1)
        v = -recs[-1]["nodes"][tip, 3]
        rest = abs(recs[-1]["nodes"][tip, 3] - recs[-2]["nodes"][tip, 3]) / v
        err = abs(v / TIMOSHENKO - 1)
        errs.append(err)
        print(f"INFO {nx} x {ny}: tip deflection {v:.6e} m, Timoshenko {TIMOSHENKO:.6e} m "
              f"(Goodier {GOODIER:.6e}): error {err:.3e}; change over the last step {rest:.1e}")
    np.savetxt(Path(a.out, "convergence.txt"), np.column_stack([[m[0] for m in meshes], errs]),
               header="elements_along error_tip_deflection")
    k = meshes.index((160, 16))
    check("160 x 16 Q4: tip deflection against Timoshenko beam theory", errs[k], 0.02)
    check("the beam is at rest: relative change of the tip deflection over the last step", rest, 1e-6)
    check("the error falls with refinement (160 x 16 / 40 x 4)", errs[k] / errs[0], 1.0)
    finish()


if __name__ == "__main__":
    main()
