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
displacement of the tip node at mid-height (fracas.h5, full precision) on three
meshes 40 x 4, 80 x 8, 160 x 16 (long version: 320 x 32). Tolerance 2 % on the
160 x 16 mesh; the error must fall with refinement."""
import sys
from pathlib import Path

import numpy as np

from fracas_tools.valmesh import Case, node_id, one_based, quads, rect_grid  # noqa: E402
from fracas_tools.valmesh import Checker, args, run_fracas  # noqa: E402

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
    case = Case(gravity=(0.0, 0.0))
    case.add_material("BEAMx", RHO, "ELAS", young=E, poisson=NU)
    case.add_model("M2DQ4", "Q4xxx")
    b = case.add_mesh_body(x, one_based(quads(nx, ny)), model="M2DQ4", material="BEAMx")
    b.fix([node_id(0, j, nx) + 1 for j in range(ny + 1)])
    f = shear_forces(x[[node_id(nx, j, nx) for j in range(ny + 1)], 1])
    h = 1.0
    for j in range(ny + 1):
        # Downward force ramped in over 5 steps: value = CT min(1, RAMP t).
        b.impose_force([node_id(nx, j, nx) + 1], 2, ct=-f[j], rampi=0.0, ramp=1.0 / (5 * h))
    case.run.set(time_step=h, number_of_steps=10, theta=1.0, plane="stress", output_dof_every=0,
                 output_hdf5_every=1)
    case.write(case_dir)
    return node_id(nx, ny // 2, nx)


def main():
    a = args(__doc__)
    ck = Checker("validation_meshes.cantilever" + (".long" if a.long else ""))
    meshes = [(40, 4), (80, 8), (160, 16)] + ([(320, 32)] if a.long else [])
    errs = []
    for nx, ny in meshes:
        case = Path(a.out, f"m{nx}x{ny}")
        tip = build(case, nx, ny)
        with run_fracas(a.fracas, case) as run:
            last, before = run.snapshot(-1).mesh["X"][tip, 1], run.snapshot(-2).mesh["X"][tip, 1]
        v = -last
        errs.append(abs(v / TIMOSHENKO - 1))
        if (nx, ny) != (160, 16):
            ck.info(f"{nx} x {ny}: error of the tip deflection", errs[-1])
            continue
        ck.info("Goodier's plane-stress solution (m)", GOODIER)
        ck.rel(f"{nx} x {ny}: tip deflection (m) vs Timoshenko beam", v, TIMOSHENKO, 0.02)
        ck.at_most(f"{nx} x {ny}: at rest: change over the last step / deflection", abs(last - before) / v, 1e-6)
    np.savetxt(Path(a.out, "convergence.txt"), np.column_stack([[m[0] for m in meshes], errs]), fmt="%d %.6e",
               header="elements_along error_tip_deflection")
    k = meshes.index((160, 16))
    ck.at_most("error at 160 x 16 / error at 40 x 4 (falls)", errs[k] / errs[0], 1.0)
    sys.exit(ck.finish())


if __name__ == "__main__":
    main()
