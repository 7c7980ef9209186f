#!/usr/bin/python3
"""Write test_cases/examples/arch/DATBOX: a semicircular arch of 25 POLYG voussoirs with
radial joints (mean radius 1 m, thickness 0.15 m, t/R = 0.15 > 0.1075) on two fixed
POLYG supports, IQS_CLB mu = 0.6, and a 50 kg/m block dropped onto the left haunch
from 0.3 m above: the arch takes the impact and stands; the block bounces off the
extrados and lands on a fixed JONCx ground.
2 s, h = 1e-3 s; VTK and HDF5 snapshots every 20 steps (README.md).
"""
import math
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools import polytools as pt  # noqa: E402


N = 25
R, T = 1.0, 0.15
MU = 0.6
DROP_ANGLE = math.radians(120.0)    # where the block lands (from the right springer)
DROP_HEIGHT = 0.3
BLOCK = 0.1                         # side of the dropped block (m), 5000 kg/m3 -> 50 kg/m
DT = 1.0e-3
N_STEPS = 2000
EVERY = 20


def build():
    from fracas_tools import Case, generators as gen
    case = Case(gravity=(0.0, -9.81))
    case.add_material("STONE", density=2500.0)
    case.add_material("STEEL", density=5000.0)
    arch = gen.arch(case, N, R, T, "STONE", "BLEUx")
    ro = R + 0.5 * T
    cx, cy = ro * math.cos(DROP_ANGLE), ro * math.sin(DROP_ANGLE) + DROP_HEIGHT + 0.5 * BLOCK
    case.add_polygon(pt.rect(BLOCK, BLOCK), "STEEL", color="BLEUx", center=(cx, cy))
    # a fixed ground 1 cm below the supports (no contact between fixed bodies)
    case.add_jonc((0.0, -T - 0.01 - 0.05), 2.0, 0.05, "STONE", color="WALLx").fix()
    case.add_law("iqsvv", "IQS_CLB", fric=MU)
    case.add_see("POLYG", "BLEUx", "POLYG", "BLEUx", "iqsvv", 5e-3)
    case.add_see("POLYG", "BLEUx", "JONCx", "WALLx", "iqsvv", 5e-3)
    case.run.set(time_step=DT, number_of_steps=N_STEPS, theta=0.5, nlgs_check="QM/16",
                 nlgs_tolerance=1e-5, output_vtk_every=EVERY, output_hdf5_every=EVERY,
                 output_dof_every=N_STEPS // 2, progress_every=N_STEPS // 10)
    return case, arch


if __name__ == "__main__":
    case, _ = build()
    case.write(HERE)
    print(f"wrote {HERE / 'DATBOX'}")
