#!/usr/bin/python3
"""Write test_cases/validation/disk_column/DATBOX: a column of 10 equal disks of
mixed densities (so the weights above each contact are not in arithmetic progression),
stacked vertically, exactly touching, on a fixed floor between two fixed vertical walls
with a clearance of 1e-6 m on each side (frictionless everywhere), at rest under gravity.

Disk lengths are multiples of 1/128 m, so the disk positions and the disk-disk and
disk-floor gaps are exact in binary and in BODIES.DAT's 8-digit fields: the column
starts exactly touching and exactly aligned. The walls are JONCx rotated by 1.5707963
rad (DOF.INI's 8 digits), 2.7e-8 rad off vertical: over the column that moves their
surface by less than 2e-8 m, well inside the 1e-6 m clearance.
A frictionless column of disks is an unstable equilibrium (each disk on the one below
is an inverted pendulum); the narrow walls keep it a column.

The parameters below are also read by check.py (import gen).
"""
import math
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools import valtools  # noqa: E402


G = 9.81
RHO = 1000.0                                       # walls (irrelevant)
U = 1.0 / 128.0                                    # length unit of the deck (m)
N = 10
R = 8 * U                                          # disk radius (m)
RADII = [R] * N
DENSITIES = [1000.0, 2500.0, 500.0, 7800.0, 1000.0, 3000.0, 600.0, 2000.0, 1200.0, 4000.0]
CLEARANCE = 1.0e-6                                 # wall clearance on each side (m)
FLOOR_HALF_LENGTH = 32 * U
WALL_HALF_THICK = 8 * U
FLOOR_TOP = WALL_HALF_THICK                        # floor centred at the origin
R_MAX = max(RADII)
HEIGHT = 2.0 * sum(RADII)
DT = 1.0e-3
N_STEPS = 1000
NLGS_CHECK = "Maxm"
NLGS_TOL = 1.0e-6
ALERT = 1.0e-3


def centres():
    """(x, y) of the disk centres, bottom to top."""
    out, y = [], FLOOR_TOP
    for r in RADII:
        out.append((0.0, y + r))
        y += 2.0 * r
    return out


def build():
    from fracas_tools import Case
    case = Case(gravity=(0.0, -G))
    for k, rho in enumerate(DENSITIES):
        case.add_material(f"DSK{k + 1:02d}", density=rho)
    case.add_material("WALLS", density=RHO)
    case.add_law("iqsf0", "IQS_CLB", fric=0.0)
    case.add_see("DISKx", "BLEUx", "DISKx", "BLEUx", "iqsf0", ALERT)
    case.add_see("DISKx", "BLEUx", "JONCx", "WALLx", "iqsf0", ALERT)
    # body 1: floor; bodies 2, 3: left and right walls
    case.add_jonc((0.0, 0.0), FLOOR_HALF_LENGTH, WALL_HALF_THICK, "WALLS").fix()
    half_h = 0.5 * HEIGHT + 8 * U
    for side in (-1.0, 1.0):
        case.add_jonc((side * (R_MAX + WALL_HALF_THICK + CLEARANCE), FLOOR_TOP + 0.5 * HEIGHT + 8 * U),
                      half_h, WALL_HALF_THICK, "WALLS", angle=0.5 * math.pi).fix()
    # bodies 4..13: the disks, bottom to top
    for k, ((x, y), r) in enumerate(zip(centres(), RADII)):
        case.add_disk((x, y), r, f"DSK{k + 1:02d}")
    case.run.set(time_step=DT, number_of_steps=N_STEPS, theta=0.5,
                 nlgs_check=NLGS_CHECK, nlgs_tolerance=NLGS_TOL, output_hdf5_every=1,
                 output_dof_every=0, output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    build().write(HERE)
    print(f"wrote {HERE / 'DATBOX'}")
