#!/usr/bin/python3
"""Write test_cases/hard/column_100/DATBOX: a column of 100 equal square POLYG blocks
(side 0.125 m, exact in binary and in the deck) standing on a fixed JONCx ground,
exactly touching and aligned, at rest under gravity, for 10 000 steps (README.md;
nscd_validation.md 3.2). IQS_CLB mu = 0.5, two contact points per face; NLGS Maxm 1e-6,
contacts in shuffled order (seed 1).
Bodies: 1 ground, 2..101 the blocks from the bottom.
"""
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools import polytools as pt  # noqa: E402


G = 9.81
N = 100
A = 0.125
RHO = 2000.0
MU = 0.5
GROUND_HALF_THICK = 0.125
DT = 1.0e-3
N_STEPS = 10000
NLGS_CHECK = "Maxm"
NLGS_TOL = 1.0e-6
SWEEPS_PER_CHECK = 50
MAX_CHECKS = 1000
NLGS_ORDER = "shuffled"          # the stored (bottom-up) order does not converge (README.md)
NLGS_SEED = 1
HDF5_EVERY = 100
ALERT = 1.0e-3


def build():
    from fracas_tools import Case
    case = Case(gravity=(0.0, -G))
    case.add_material("STONE", density=RHO)
    case.add_material("TDURx", density=1000.0)
    case.add_law("iqs05", "IQS_CLB", fric=MU)
    case.add_see("POLYG", "BLEUx", "POLYG", "BLEUx", "iqs05", ALERT)
    case.add_see("POLYG", "BLEUx", "JONCx", "WALLx", "iqs05", ALERT)
    case.add_jonc((0.0, -GROUND_HALF_THICK), 1.0, GROUND_HALF_THICK, "TDURx").fix()
    for k in range(N):
        case.add_polygon(pt.rect(A, A), "STONE", center=(0.0, (k + 0.5) * A))
    case.run.set(time_step=DT, number_of_steps=N_STEPS, theta=0.5,
                 nlgs_check=NLGS_CHECK, nlgs_tolerance=NLGS_TOL,
                 nlgs_sweeps_per_check=SWEEPS_PER_CHECK, nlgs_max_checks=MAX_CHECKS,
                 nlgs_order=NLGS_ORDER, nlgs_seed=NLGS_SEED,
                 output_hdf5_every=HDF5_EVERY, output_dof_every=0, output_vtk_every=0,
                 progress_every=0)
    return case


if __name__ == "__main__":
    build().write(HERE)
    print(f"wrote {HERE / 'DATBOX'}")
