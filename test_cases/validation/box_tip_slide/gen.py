#!/usr/bin/python3
"""Write test_cases/validation/box_tip_slide/DATBOX: rectangular POLYG boxes (width b,
height H) resting on rotated JONCx inclines, on both sides of the tipping threshold
tan(alpha) = b/H (with mu > b/H) and of the sliding threshold tan(alpha) = mu (with
mu < b/H) (README.md).

  scene  b x H (m)    mu    alpha                 expected
  1      0.1 x 0.2    0.8   atan(b/H) - 1 deg     rests
  2      0.1 x 0.2    0.8   atan(b/H) + 1 deg     tips (pivots on its lower corner, no slip)
  3      0.1 x 0.2    0.4   atan(mu) - 1 deg      rests
  4      0.1 x 0.2    0.4   atan(mu) + 1 deg      slides, a = g (sin a - mu cos a), no rotation
  5      0.1 x 0.2    0.4   35 deg (> atan(b/H))  slides without tipping (mu < b/H)
  6      0.2 x 0.1    0.8   atan(0.5) + 1 deg     rests (same angle as 2, wide box)

Scene k (1-based) has its incline as body 2k-1 and its box as body 2k. Each mu has
its own colour and law. The parameters below are also read by check.py.
"""
import math
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools import polytools as pt  # noqa: E402


G = 9.81
RHO = 2000.0
ONE_DEG = math.radians(1.0)
INCLINE_LENGTH = 3.0
JONC_HALF_THICK = 0.05
START = 1.2                  # box centre this far up the slope from the incline middle
SPACING = 3.5
DT = 1.0e-3
N_STEPS = 1000
NLGS_CHECK = "Maxm"
NLGS_TOL = 1.0e-8
ALERT = 1.0e-3
LAWS = {"iqs08": (0.8, "BLEUx"), "iqs04": (0.4, "VERTx")}

# (b, H, law, alpha, expected)
SCENES = [
    (0.1, 0.2, "iqs08", math.atan(0.5) - ONE_DEG, "rest"),
    (0.1, 0.2, "iqs08", math.atan(0.5) + ONE_DEG, "tip"),
    (0.1, 0.2, "iqs04", math.atan(0.4) - ONE_DEG, "rest"),
    (0.1, 0.2, "iqs04", math.atan(0.4) + ONE_DEG, "slide"),
    (0.1, 0.2, "iqs04", math.radians(35.0), "slide"),
    (0.2, 0.1, "iqs08", math.atan(0.5) + ONE_DEG, "rest"),
]


def frame(k):
    """(P, d, n, node, alpha): the incline surface middle P, the unit vector d up the
    slope, the normal n, the JONCx node and the angle of scene k (0-based) as the deck
    holds them (angle rounded to 8 digits, used for the incline and the box)."""
    alpha = pt.r8(SCENES[k][3])
    d, n = pt.unit(alpha), pt.unit(alpha + 0.5 * math.pi)
    node = pt.np.array([SPACING * (k - 2.5), 0.0])
    return node + JONC_HALF_THICK * n, d, n, node, alpha


def box_centre(k):
    b, H = SCENES[k][:2]
    P, d, n, _, _ = frame(k)
    c, _, _ = pt.snap_on_line(P, d, n, 0.5 * H, START)
    return c


def build():
    from fracas_tools import Case
    case = Case(gravity=(0.0, -G))
    case.add_material("STONE", density=RHO)
    case.add_material("TDURx", density=1000.0)
    for name, (mu, color) in LAWS.items():
        case.add_law(name, "IQS_CLB", fric=mu)
        case.add_see("POLYG", color, "JONCx", "WALLx", name, ALERT)
    for k, (b, H, law, _, _) in enumerate(SCENES):
        _, _, _, node, alpha = frame(k)
        case.add_jonc(tuple(node), 0.5 * INCLINE_LENGTH, JONC_HALF_THICK, "TDURx",
                      angle=alpha).fix()
        case.add_polygon(pt.rect(b, H), "STONE", color=LAWS[law][1],
                         center=tuple(box_centre(k))).rotate(alpha)
    case.run.set(time_step=DT, number_of_steps=N_STEPS, theta=0.5,
                 nlgs_check=NLGS_CHECK, nlgs_tolerance=NLGS_TOL, output_hdf5_every=1,
                 output_dof_every=0, output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    build().write(HERE)
    print(f"wrote {HERE / 'DATBOX'}")
