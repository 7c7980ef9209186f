#!/usr/bin/python3
"""Write the DATBOX folders of test_cases/hard/mass_ratio: a heavy POLYG block on a
light one on a fixed JONCx ground, at rest (exactly touching) under gravity, mass
ratios M/m = 1, 100 and 1000 (README.md; nscd_validation.md 3.1).

  r1/DATBOX     M/m = 1     (baseline)
  r100/DATBOX   M/m = 100
  r1000/DATBOX  M/m = 1000

Blocks are 0.25 x 0.25 m squares (exact in binary and in the 8-digit deck fields), so
the stack starts exactly touching and aligned. Contacts: IQS_CLB mu = 0.5, two points
per interface (face on face). Bodies: 1 ground, 2 light block (m), 3 heavy block (M).
"""
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools import polytools as pt  # noqa: E402


G = 9.81
A = 0.25                        # block side (m)
RHO_LIGHT = 100.0               # kg/m3: m = 6.25 kg/m
RATIOS = {"r1": 1.0, "r100": 100.0, "r1000": 1000.0}
MU = 0.5
GROUND_HALF_THICK = 0.125
DT = 1.0e-3
N_STEPS = 2000
NLGS_CHECK = "Maxm"
NLGS_TOL = 1.0e-6
SWEEPS_PER_CHECK = 50
MAX_CHECKS = 1000               # 50 000 sweeps per step at most
ALERT = 1.0e-3


def build(ratio):
    from fracas_tools import Case
    case = Case(gravity=(0.0, -G))
    case.add_material("LIGHT", density=RHO_LIGHT)
    case.add_material("HEAVY", density=RHO_LIGHT * ratio)
    case.add_material("TDURx", density=1000.0)
    case.add_law("iqs05", "IQS_CLB", fric=MU)
    case.add_see("POLYG", "BLEUx", "POLYG", "BLEUx", "iqs05", ALERT)
    case.add_see("POLYG", "BLEUx", "JONCx", "WALLx", "iqs05", ALERT)
    case.add_jonc((0.0, -GROUND_HALF_THICK), 1.0, GROUND_HALF_THICK, "TDURx").fix()
    case.add_polygon(pt.rect(A, A), "LIGHT", center=(0.0, 0.5 * A))
    case.add_polygon(pt.rect(A, A), "HEAVY", center=(0.0, 1.5 * A))
    case.run.set(time_step=DT, number_of_steps=N_STEPS, theta=0.5,
                 nlgs_check=NLGS_CHECK, nlgs_tolerance=NLGS_TOL,
                 nlgs_sweeps_per_check=SWEEPS_PER_CHECK, nlgs_max_checks=MAX_CHECKS,
                 output_hdf5_every=1, output_dof_every=0, output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    for name, ratio in RATIOS.items():
        build(ratio).write(HERE / name)
        print(f"wrote {HERE / name / 'DATBOX'}")
