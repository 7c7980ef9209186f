#!/usr/bin/python3
"""Write test_cases/hard/wedged_block/DATBOX: trapezoidal POLYG wedges in V-shaped slots
between two fixed POLYG walls whose faces lean BETA = 10 deg from the vertical, with the
wedge sides parallel to the walls; IQS_CLB mu = 0.5 > tan(BETA), so the wedge is
self-locking and its wall reactions are not unique: any normal force
N >= W / (2 (sin BETA + mu cos BETA)) per side is in equilibrium (README.md;
nscd_validation.md 3.3).

  slot  x centre  wedge                               what it tests
  1     -0.5      placed exactly touching, at rest    cold start on an indeterminate problem
  2     +0.5      dropped from LIFT = 2 mm above      jamming impact, then rest

Bodies: slot k (0-based) has its left wall 3k+1, right wall 3k+2 and wedge 3k+3.
"""
import math
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools import polytools as pt  # noqa: E402
from fracas_tools.pre import polygon_area  # noqa: E402  (tools path set by polytools users)

G = 9.81
RHO = 2000.0
BETA = math.radians(10.0)
MU = 0.5
WB, H = 0.1, 0.1                       # wedge bottom width and height (m)
WT = WB + 2.0 * H * math.tan(BETA)     # top width
SLOTS = [(-0.5, 0.0, "placed"), (0.5, 2.0e-3, "dropped")]
WALL_LOW, WALL_HIGH, WALL_W = -0.1, 0.25, 0.2
DT = 1.0e-3
N_STEPS = 2000
NLGS_CHECK = "Maxm"
NLGS_TOL = 1.0e-6
HDF5_EVERY = 1
ALERT = 5.0e-3


def ccw(v):
    v = np.asarray(v, dtype=float)
    return v if polygon_area(v) > 0 else v[::-1]


def wall(x0, side):
    """The left (side = -1) or right (+1) wall of the slot centred at x0: a quadrilateral
    whose inner face is the line through (x0 + side WB/2, 0) leaning BETA outwards."""
    p0 = np.array([x0 + side * 0.5 * WB, 0.0])
    d = np.array([side * math.sin(BETA), math.cos(BETA)])     # up the face
    f1 = p0 + (WALL_LOW / math.cos(BETA)) * d
    f2 = p0 + (WALL_HIGH / math.cos(BETA)) * d
    out = np.array([side * WALL_W, 0.0])
    return ccw([f1, f2, f2 + out, f1 + out])


def wedge(x0, lift):
    return ccw([[x0 - 0.5 * WB, lift], [x0 + 0.5 * WB, lift],
                [x0 + 0.5 * WT, lift + H], [x0 - 0.5 * WT, lift + H]])


def build():
    from fracas_tools import Case
    case = Case(gravity=(0.0, -G))
    case.add_material("STONE", density=RHO)
    case.add_material("TDURx", density=1000.0)
    case.add_law("iqs05", "IQS_CLB", fric=MU)
    case.add_see("POLYG", "BLEUx", "POLYG", "WALLx", "iqs05", ALERT)
    for x0, lift, _ in SLOTS:
        case.add_polygon(wall(x0, -1), "TDURx", color="WALLx").fix()
        case.add_polygon(wall(x0, +1), "TDURx", color="WALLx").fix()
        case.add_polygon(wedge(x0, lift), "STONE", color="BLEUx")
    case.run.set(time_step=DT, number_of_steps=N_STEPS, theta=0.5,
                 nlgs_check=NLGS_CHECK, nlgs_tolerance=NLGS_TOL, output_hdf5_every=HDF5_EVERY,
                 output_dof_every=0, output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    build().write(HERE)
    print(f"wrote {HERE / 'DATBOX'}")
