#!/usr/bin/python3
"""Write test_cases/validation/block_incline/DATBOX: square POLYG blocks on inclines,
on both sides of the sliding threshold tan(alpha) = mu (README.md).

Five independent scenes, 3.5 m apart, in one deck (no see rule between the scenes'
blocks, and the scenes are far apart):

  scene  incline                      alpha              mu    expected
  1      rotated JONCx (PLJCx)        atan(0.5) - 1 deg  0.5   sticks
  2      rotated JONCx (PLJCx)        atan(0.5) + 1 deg  0.5   slides
  3      rotated POLYG slab (PLPLx)     atan(0.5) - 1 deg  0.5   sticks
  4      rotated POLYG slab (PLPLx)     atan(0.5) + 1 deg  0.5   slides
  5      rotated JONCx (PLJCx)        30 deg             0.3   slides (a = 2.356 m/s2)

Bodies: scene k has its incline as body 2k-1 and its block as body 2k.
The parameters below are also read by check.py (import gen).
"""
import math
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools import polytools as pt  # noqa: E402


G = 9.81
RHO = 2000.0                      # block density (kg/m3): m = 20 kg/m for a = 0.1
A = 0.1                           # block side (m)
MU = 0.5
MU5 = 0.3
ALPHA_C = math.atan(MU)           # 26.565 deg
D_ALPHA = math.radians(1.0)
INCLINE_LENGTH = 3.0              # m (JONCx 2*ax1, ramp hypotenuse)
JONC_HALF_THICK = 0.05
START = 1.2                       # block centre: this far up the slope from the incline middle
SPACING = 3.5                     # x distance between scenes (nodes at x = -7 ... 7)
DT = 1.0e-3
N_STEPS = 1000
NLGS_CHECK = "Maxm"
NLGS_TOL = 1.0e-8
ALERT = 1.0e-3

# (incline kind, alpha, law, expected)
SCENES = [
    ("JONCx", ALPHA_C - D_ALPHA, "iqs05", "stick"),
    ("JONCx", ALPHA_C + D_ALPHA, "iqs05", "slide"),
    ("POLYG", ALPHA_C - D_ALPHA, "iqs05", "stick"),
    ("POLYG", ALPHA_C + D_ALPHA, "iqs05", "slide"),
    ("JONCx", math.radians(30.0), "iqs03", "slide"),
]
MU_OF = {"iqs05": MU, "iqs03": MU5}
BLOCK_COLOR = {"iqs05": "BLEUx", "iqs03": "VERTx"}


def r8(x):
    """x as written in the DATBOX files (8 significant digits, %.7E)."""
    return float(f"{x:.7E}")


def deck_alpha(k):
    """The incline angle of scene k as the deck holds it (8 digits)."""
    return r8(SCENES[k][1])


def incline_frame(k):
    """(P, d, n): a point P on the incline surface (middle of the incline), the unit
    vector d up the slope and the unit normal n of scene k (0-based), as the solver
    reads them from the deck. Both inclines (JONCx, or POLYG slab of the same size)
    have their node at an exact decimal point and are rotated by alpha through
    DOF.INI X(3), rounded to 8 digits; the block is rotated by the same number, so
    block face and incline surface are exactly parallel."""
    alpha = deck_alpha(k)
    d, n = pt.unit(alpha), pt.unit(alpha + 0.5 * math.pi)
    node = np.array([SPACING * (k - 2), 0.0])          # x = -7, -3.5, 0, 3.5, 7
    return node + JONC_HALF_THICK * n, d, n, node


def block_centre(k):
    """The block centre of scene k: START up the slope from the incline middle, on the
    surface, with START adjusted within 1e-3 m so that the 8-digit rounding of the
    centre in BODIES.DAT leaves a gap error below 1e-12 m (the rounding moves the
    centre by up to 5e-8 m; only its normal component matters)."""
    P, d, n, _ = incline_frame(k)
    starts = START + np.linspace(0.0, 1.0e-3, 200001)
    c = P[None, :] + starts[:, None] * d[None, :] + 0.5 * A * n[None, :]
    cr = np.vectorize(r8)(c)
    err = np.abs((cr - c) @ n)
    i = int(np.argmin(err))
    return cr[i], float(err[i])


def build():
    from fracas_tools import Case
    case = Case(gravity=(0.0, -G))
    case.add_material("STONE", density=RHO)
    case.add_material("TDURx", density=1000.0)
    case.add_law("iqs05", "IQS_CLB", fric=MU)
    case.add_law("iqs03", "IQS_CLB", fric=MU5)
    case.add_see("POLYG", "BLEUx", "JONCx", "WALLx", "iqs05", ALERT)
    case.add_see("POLYG", "BLEUx", "POLYG", "RAMPx", "iqs05", ALERT)
    case.add_see("POLYG", "VERTx", "JONCx", "WALLx", "iqs03", ALERT)
    for k, (kind, _, law, _) in enumerate(SCENES):
        alpha = deck_alpha(k)
        _, _, _, node = incline_frame(k)
        if kind == "JONCx":
            case.add_jonc(tuple(node), 0.5 * INCLINE_LENGTH, JONC_HALF_THICK, "TDURx",
                          angle=alpha).fix()
        else:      # a POLYG slab 3 m x 0.1 m, the same size as the JONCx without round ends
            case.add_polygon(pt.rect(INCLINE_LENGTH, 2.0 * JONC_HALF_THICK), "TDURx",
                             color="RAMPx", center=tuple(node)).rotate(alpha).fix()
        c, _ = block_centre(k)
        case.add_polygon(pt.rect(A, A), "STONE", color=BLOCK_COLOR[law],
                         center=tuple(c)).rotate(alpha)
    case.run.set(time_step=DT, number_of_steps=N_STEPS, theta=0.5,
                 nlgs_check=NLGS_CHECK, nlgs_tolerance=NLGS_TOL, output_hdf5_every=1,
                 output_dof_every=0, output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    build().write(HERE)
    print(f"wrote {HERE / 'DATBOX'}")
