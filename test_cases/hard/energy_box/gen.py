#!/usr/bin/python3
"""Write test_cases/hard/energy_box/DATBOX: 24 random convex POLYG grains (4 to 7
vertices, circumradius 40-60 mm) in a closed 1 m x 1 m box of four fixed JONCx walls,
under gravity, with random initial velocities (|v| up to 2 m/s, spins up to 10 rad/s),
all contacts RST_CLB with e_n = 1, e_t = 0 and no friction: an elastic, frictionless
gas of polygons whose mechanical energy must stay constant (README.md;
nscd_validation.md 3.7). 100 s, h = 1e-3 s, theta = 0.5. Seeded (SEED).
Bodies: 1..4 the walls (bottom, top, left, right), 5..28 the grains.
"""
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools import polytools as pt  # noqa: E402


G = 9.81
SEED = 7
N_GRAINS = 24
RMIN, RMAX = 0.04, 0.06
BOX = 1.0
RHO = 2000.0
V_MAX, W_MAX = 2.0, 10.0
DT = 1.0e-3
N_STEPS = 100000
NLGS_CHECK = "Maxm"
NLGS_TOL = 1.0e-8
HDF5_EVERY = 1000
ALERT = 2.0e-2                  # m: grains move up to 3 mm per step


def build():
    from fracas_tools import Case, generators as gen
    rng = np.random.default_rng(SEED)
    case = Case(gravity=(0.0, -G))
    case.add_material("STONE", density=RHO)
    case.add_material("TDURx", density=1000.0)
    case.add_law("rst10", "RST_CLB", rstn=1.0, rstt=0.0, fric=0.0)
    case.add_see("POLYG", "BLEUx", "POLYG", "BLEUx", "rst10", ALERT)
    case.add_see("POLYG", "BLEUx", "JONCx", "WALLx", "rst10", ALERT)
    gen.box_walls(case, 0.0, BOX, 0.0, BOX, 0.05, "TDURx", top=True)
    grains = gen.deposit_polygons(case, N_GRAINS, RMIN, RMAX, 0.9 * BOX, "STONE", seed=rng,
                                  x0=0.05 * BOX, y0=0.05 * BOX)
    for b in grains:
        a = rng.uniform(0.0, 2.0 * np.pi)
        v = rng.uniform(0.2, 1.0) * V_MAX
        b.set_velocity(v * np.cos(a), v * np.sin(a), rng.uniform(-W_MAX, W_MAX))
    case.run.set(time_step=DT, number_of_steps=N_STEPS, theta=0.5,
                 nlgs_check=NLGS_CHECK, nlgs_tolerance=NLGS_TOL, output_hdf5_every=HDF5_EVERY,
                 output_dof_every=0, output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    build().write(HERE)
    print(f"wrote {HERE / 'DATBOX'}")
