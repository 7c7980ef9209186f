#!/usr/bin/python3
"""Write test_cases/validation/czm_rate/DATBOX: three pairs of glued 1 m x 1 m rigid POLYG
blocks (as in czm_mode_I) side by side (3 m apart), glued by the same viscous
IQS_MAC_CZM law (b > 0), each upper block pulled up at its own constant velocity v_i
(rate parameter R_i = b v_i/(w u0) = 0.3, 1, 3). The peak stress grows with the rate as
the viscous damage law b beta' = -(w - beta Y)^- says (README.md). The parameters below
are read by check.py.
"""
import math
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
from fracas_tools.cohesive import Law  # noqa: E402

LAW = Law.mac(cn=1.0e10, ct=1.0e11, b=1.0e-2, w=40.0)   # tau_b = b/w = 2.5e-4 s
U0 = math.sqrt(LAW.w / LAW.cn)                          # 6.3246e-5 m
RATES = (0.3, 1.0, 3.0)                                 # R = b v/(w u0) = tau_b / (u0/v)
VELOCITIES = tuple(r * LAW.w * U0 / LAW.b for r in RATES)
DT = 2.0e-7            # time step (s): the fastest pair opens u0/417 per step, h = tau_b/1250
STEPS = 5500           # the slowest pair reaches 1.32 u0 (its peak is at 1.08 u0)
SPACING = 3.0          # x distance between the pairs (m)
RHO = 2000.0
MU = 0.5
GLUED = 1.0
ALERT = 0.01
EVERY = 4              # snapshot every EVERY steps (the viscous peak is smooth)


def build():
    from fracas_tools import Case
    case = Case(gravity=(0.0, 0.0))
    case.add_material("STONE", density=RHO)
    LAW.add_to(case, "macvb", "IQS_MAC_CZM", MU)
    case.add_see("POLYG", "BLEUx", "POLYG", "BLEUx", "macvb", ALERT)
    for i, v in enumerate(VELOCITIES):
        x = SPACING * i
        lower = case.add_polygon([(x - 0.5, -0.5), (x + 0.5, -0.5), (x + 0.5, 0.5), (x - 0.5, 0.5)], "STONE")
        lower.fix()
        upper = case.add_polygon([(x - 0.5, 0.5), (x + 0.5, 0.5), (x + 0.5, 1.5), (x - 0.5, 1.5)], "STONE")
        upper.impose_velocity(2, ct=v)
        upper.impose_velocity(3)
    case.run.set(time_step=DT, number_of_steps=STEPS, theta=0.5, nlgs_check="Quad",
                 nlgs_tolerance=1e-6, output_hdf5_every=EVERY, output_dof_every=0,
                 output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    build().write(HERE)
    print(f"wrote {HERE / 'DATBOX'}")
