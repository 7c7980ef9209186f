#!/usr/bin/python3
"""Write test_cases/examples/masonry_wall/DATBOX: a running-bond wall of 14 courses of
0.2 x 0.1 m POLYG bricks (4 per course, half bricks at the ends of odd courses) on a
base slab shaken horizontally, vx(t) = AMP sin(OMEGA t) (DRV_DOF vlocy AMP/OMEGA/PHI),
vy = spin = 0. IQS_CLB mu = 0.6 brick/brick and 0.8 brick/base. 3 s, h = 1e-3 s; VTK
and HDF5 snapshots every 20 steps (README.md).
"""
import math
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools import polytools as pt  # noqa: E402


N_COURSES, PER_COURSE = 14, 4
L, H = 0.2, 0.1
FREQ = 2.0                       # Hz
OMEGA = 2.0 * math.pi * FREQ
AMP = 0.6                        # m/s: peak base velocity (peak acceleration 0.77 g)
DT = 1.0e-3
N_STEPS = 3000
EVERY = 20


def build():
    from fracas_tools import Case, generators as gen
    case = Case(gravity=(0.0, -9.81))
    case.add_material("BRICK", density=2000.0)
    case.add_material("TDURx", density=2500.0)
    wall = gen.masonry_wall(case, N_COURSES, PER_COURSE, L, H, "BRICK", "BLEUx", ground=False)
    length = PER_COURSE * L
    base = case.add_polygon(pt.rect(length + 1.0, 0.2, 0.5 * length, -0.1), "TDURx", color="BASEx")
    base.impose_velocity(1, ct=0.0, amp=AMP, omega=OMEGA, phi=-0.5 * math.pi)
    base.impose_velocity((2, 3), ct=0.0)
    case.add_law("iqsbb", "IQS_CLB", fric=0.6)
    case.add_law("iqsbg", "IQS_CLB", fric=0.8)
    case.add_see("POLYG", "BLEUx", "POLYG", "BLEUx", "iqsbb", 2e-3)
    case.add_see("POLYG", "BLEUx", "POLYG", "BASEx", "iqsbg", 2e-3)
    case.run.set(time_step=DT, number_of_steps=N_STEPS, theta=0.5, nlgs_check="QM/16",
                 nlgs_tolerance=1e-4, output_vtk_every=EVERY, output_hdf5_every=EVERY,
                 output_dof_every=N_STEPS // 3, progress_every=N_STEPS // 10)
    return case, wall


if __name__ == "__main__":
    case, _ = build()
    case.write(HERE)
    print(f"wrote {HERE / 'DATBOX'}")
