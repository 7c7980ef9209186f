#!/usr/bin/python3
"""Write test_cases/validation/disk_roll_polyg/DATBOX: disks rolling or slipping down
POLYG inclines (DKPLx contacts), on both sides of the no-slip threshold
mu = tan(alpha)/3 of a uniform disk (README.md; nscd_validation.md 2.4, V4).

  scene  alpha   mu     expected (threshold tan(30 deg)/3 = 0.1925)
  1      30 deg  0.5    rolls: a = (2/3) g sin(alpha), omega = v / R
  2      30 deg  0.2    rolls (just above the threshold)
  3      30 deg  0.15   slips: a = g (sin - mu cos), omega' = 2 mu g cos / R

Each incline is a fixed POLYG slab 3 x 0.1 m rotated by alpha (DOF.INI), its node at an
exact decimal point; the disk (R = 0.05 m, 2000 kg/m3) starts at rest on it, its centre
placed so that the deck's 8-digit rounding leaves no gap. Scene k: slab 2k-1, disk 2k.
"""
import math
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools import polytools as pt  # noqa: E402


G = 9.81
R = 0.05
RHO = 2000.0
LENGTH, HALF_THICK = 3.0, 0.05
START = 1.2
SPACING = 3.5
DT = 1.0e-3
N_STEPS = 1000
NLGS_CHECK = "Maxm"
NLGS_TOL = 1.0e-8
ALERT = 1.0e-3
# (alpha, mu, expected)
SCENES = [(math.radians(30.0), 0.5, "roll"), (math.radians(30.0), 0.2, "roll"),
          (math.radians(30.0), 0.15, "slip")]


def frame(k):
    """(P, d, n, node, alpha) of scene k as the deck holds it (see block_incline)."""
    alpha = pt.r8(SCENES[k][0])
    d, n = pt.unit(alpha), pt.unit(alpha + 0.5 * math.pi)
    node = pt.np.array([SPACING * (k - 1), 0.0])
    return node + HALF_THICK * n, d, n, node, alpha


def build():
    from fracas_tools import Case
    case = Case(gravity=(0.0, -G))
    case.add_material("STEEL", density=RHO)
    case.add_material("TDURx", density=1000.0)
    for k, (_, mu, _) in enumerate(SCENES):
        law, color = f"iqs{k + 1:02d}", f"DSK{k + 1:02d}"
        case.add_law(law, "IQS_CLB", fric=mu)
        case.add_see("DISKx", color, "POLYG", "RAMPx", law, ALERT)
    for k, (_, _, _) in enumerate(SCENES):
        P, d, n, node, alpha = frame(k)
        case.add_polygon(pt.rect(LENGTH, 2.0 * HALF_THICK), "TDURx", color="RAMPx",
                         center=tuple(node)).rotate(alpha).fix()
        c, _, _ = pt.snap_on_line(P, d, n, R, START)
        case.add_disk(tuple(c), R, "STEEL", color=f"DSK{k + 1:02d}")
    case.run.set(time_step=DT, number_of_steps=N_STEPS, theta=0.5,
                 nlgs_check=NLGS_CHECK, nlgs_tolerance=NLGS_TOL, output_hdf5_every=10,
                 output_dof_every=0, output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    build().write(HERE)
    print(f"wrote {HERE / 'DATBOX'}")
