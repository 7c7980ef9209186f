#!/usr/bin/python3
"""Write test_cases/validation/tilting_table/DATBOX: blocks on tables that tilt slowly
at a constant rate; the angle at which each block starts to move is measured
(README.md; nscd_validation.md 2.7).

  table  block b x H (m)  mu    expected onset                    alpha_c
  1      0.1 x 0.1        0.5   slides when tan(alpha) = mu       26.565 deg
  2      0.1 x 0.25       0.8   tips when tan(alpha) = b/H        21.801 deg

Each table is a POLYG slab 1.0 x 0.1 m driven in velocity: vx = vy = 0 and a spin
about its node, which is on the table's top face right under the block centre. The
spin grows linearly from 0 to OMEGA = 3 deg/s over RAMP_TIME = 0.2 s (DRV_DOF RAMP: an
impulsive start makes the tall block rock), then stays constant. The table starts at
alpha_c - 1.5 deg, reaches alpha_c at t = 0.6 s and alpha_c + 1.2 deg at t = 1 s. The block starts at
rest on it, rotated with it. Bodies: table k = 2k-1, its block = 2k.
The parameters below are also read by check.py.
"""
import math
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools import polytools as pt  # noqa: E402


G = 9.81
RHO = 2000.0
TABLE_L, TABLE_H = 1.0, 0.1
START_BELOW = math.radians(1.5)       # the table starts this far below alpha_c
DURATION = 1.0                        # s
OMEGA = math.radians(3.0) / DURATION  # rad/s, tilting rate
RAMP_TIME = 0.2                       # s: the rate grows linearly from 0 to OMEGA (smooth start)
DT = 1.0e-3
N_STEPS = int(round(DURATION / DT))
NLGS_CHECK = "Maxm"
NLGS_TOL = 1.0e-8
ALERT = 1.0e-3
LAWS = {"iqs05": (0.5, "BLEUx"), "iqs08": (0.8, "VERTx")}

# (b, H, law, alpha_c, expected)
SCENES = [(0.1, 0.1, "iqs05", math.atan(0.5), "slide"),
          (0.1, 0.25, "iqs08", math.atan(0.1 / 0.25), "tip")]


def frame(k):
    """(node, alpha0): the table node (rotation axis, on the top face) and the
    initial table angle of scene k (0-based) as the deck holds it."""
    alpha0 = pt.r8(SCENES[k][3] - START_BELOW)
    return np.array([2.0 * k - 1.0, 0.0]), alpha0


def block_centre(k):
    b, H = SCENES[k][:2]
    node, alpha0 = frame(k)
    d, n = pt.unit(alpha0), pt.unit(alpha0 + 0.5 * math.pi)
    c, _, _ = pt.snap_on_line(node, d, n, 0.5 * H, 0.0)
    return c


def build():
    from fracas_tools import Case
    case = Case(gravity=(0.0, -G))
    case.add_material("STONE", density=RHO)
    case.add_material("TDURx", density=1000.0)
    for name, (mu, color) in LAWS.items():
        case.add_law(name, "IQS_CLB", fric=mu)
        case.add_see("POLYG", color, "POLYG", "TABLE", name, ALERT)
    for k, (b, H, law, _, _) in enumerate(SCENES):
        node, alpha0 = frame(k)
        slab = np.array([[-0.5 * TABLE_L, -TABLE_H], [0.5 * TABLE_L, -TABLE_H],
                         [0.5 * TABLE_L, 0.0], [-0.5 * TABLE_L, 0.0]])
        table = case.add_polygon(slab, "TDURx", color="TABLE", center=tuple(node))
        table.rotate(alpha0)
        table.impose_velocity((1, 2), ct=0.0)
        table.impose_velocity(3, ct=OMEGA, rampi=0.0, ramp=1.0 / RAMP_TIME)
        case.add_polygon(pt.rect(b, H), "STONE", color=LAWS[law][1],
                         center=tuple(block_centre(k))).rotate(alpha0)
    case.run.set(time_step=DT, number_of_steps=N_STEPS, theta=0.5,
                 nlgs_check=NLGS_CHECK, nlgs_tolerance=NLGS_TOL, output_hdf5_every=1,
                 output_dof_every=0, output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    build().write(HERE)
    print(f"wrote {HERE / 'DATBOX'}")
