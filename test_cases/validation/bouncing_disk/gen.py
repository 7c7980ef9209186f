#!/usr/bin/python3
"""Write test_cases/validation/bouncing_disk/DATBOX: a disk dropped from rest onto a
fixed horizontal wall, Newton restitution (RST_CLB, e = 0.8, no friction).

The parameters below are also read by check.py (import gen), so the check and the
deck cannot disagree. Run once; the generated DATBOX is committed.
"""
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools import valtools  # noqa: E402


G = 9.81            # gravity (m/s^2)
H0 = 1.0            # drop height of the disk bottom above the wall top (m)
E = 0.8             # normal restitution
R = 0.1             # disk radius (m)
RHO = 1000.0        # density (kg/m^3; irrelevant for the kinematics)
WALL_HALF_LENGTH = 0.5
WALL_HALF_THICK = 0.05
WALL_TOP = WALL_HALF_THICK      # wall centred at the origin, horizontal
DT = 1.0e-3         # time step (s)
T_END = 5.0         # run time (s): the exact rest time is 4.0637 s
ALERT = 0.01        # see-rule alert distance (m)


def build():
    from fracas_tools import Case
    case = Case(gravity=(0.0, -G))
    case.add_material("STONE", density=RHO)
    case.add_material("WALLS", density=RHO)
    case.add_law("rstcl", "RST_CLB", rstn=E, rstt=0.0, fric=0.0)
    case.add_see("DISKx", "BLEUx", "JONCx", "WALLx", "rstcl", ALERT)
    wall = case.add_jonc((0.0, 0.0), WALL_HALF_LENGTH, WALL_HALF_THICK, "WALLS")
    wall.fix()
    case.add_disk((0.0, WALL_TOP + R + H0), R, "STONE")
    case.run.set(time_step=DT, number_of_steps=int(round(T_END / DT)), theta=0.5,
                 nlgs_check="Maxm", nlgs_tolerance=1e-8, output_hdf5_every=1,
                 output_dof_every=0, output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    build().write(HERE)
    print(f"wrote {HERE / 'DATBOX'}")
