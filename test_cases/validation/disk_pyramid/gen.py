#!/usr/bin/python3
"""Write test_cases/validation/disk_pyramid/DATBOX: two three-cylinder pyramids (two
equal disks on a fixed JONCx ground, exactly touching each other, a third one on top
touching both), all contacts IQS_CLB with the same mu (README.md; nscd_validation.md
2.5):

  pyramid  x centre   mu     expected (threshold 2 - sqrt(3) = 0.268 disk/disk)
  1        -0.5       0.30   holds
  2        +0.5       0.25   collapses (the top disk slides down, the bottom ones roll apart)

Bodies: 1 ground; pyramid p (0-based) has bottom-left 2+3p, bottom-right 3+3p, top 4+3p.
Each pyramid has its own colour, law and see rules.
"""
import math
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools import polytools as pt  # noqa: E402


G = 9.81
RHO = 1000.0
R = 0.1
GROUND_HALF_THICK = 0.05
PYRAMIDS = [(-0.5, 0.30, "BLEUx", "hold"), (0.5, 0.25, "VERTx", "collapse")]
DT = 1.0e-3
N_STEPS = 1000
NLGS_CHECK = "Maxm"
NLGS_TOL = 1.0e-8
ALERT = 5.0e-3                   # m: the falling top disk moves up to 2 mm per step


def centres(p):
    """Bottom-left, bottom-right and top centres of pyramid p (top y rounded as the
    deck holds it: it then overlaps or misses by < 1e-8 m)."""
    x0 = PYRAMIDS[p][0]
    return [(x0 - R, R), (x0 + R, R), (x0, pt.r8(R + math.sqrt(3.0) * R))]


def build():
    from fracas_tools import Case
    case = Case(gravity=(0.0, -G))
    case.add_material("PLEXx", density=RHO)
    case.add_material("TDURx", density=1000.0)
    case.add_jonc((0.0, -GROUND_HALF_THICK), 1.0, GROUND_HALF_THICK, "TDURx").fix()
    for p, (_, mu, color, _) in enumerate(PYRAMIDS):
        law = f"iqs{p + 1:02d}"
        case.add_law(law, "IQS_CLB", fric=mu)
        case.add_see("DISKx", color, "DISKx", color, law, ALERT)
        case.add_see("DISKx", color, "JONCx", "WALLx", law, ALERT)
        for c in centres(p):
            case.add_disk(c, R, "PLEXx", color)
    case.run.set(time_step=DT, number_of_steps=N_STEPS, theta=0.5,
                 nlgs_check=NLGS_CHECK, nlgs_tolerance=NLGS_TOL, output_hdf5_every=1,
                 output_dof_every=0, output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    build().write(HERE)
    print(f"wrote {HERE / 'DATBOX'}")
