#!/usr/bin/python3
"""Write test_cases/validation/arch_heyman/DATBOX: four semicircular arches of N = 20
POLYG voussoirs with radial joints on fixed POLYG supports, mean radius R = 1 m,
mu = 0.5 (IQS_CLB), under self-weight, released from rest, 0.8 s (README.md):

  arch  centre      t/R                 expected
  1     (-2, 0)     1.05 x 0.1075       stands
  2     (+2, 0)     0.95 x 0.1075       collapses
  3     (-2, 3)     1.02 x 0.1075       stands
  4     (+2, 3)     0.98 x 0.1075       collapses

0.1075 is the minimum thickness of a semicircular arch with radial joints under its
true self-weight (Milankovitch; Heyman/Couplet problem, nscd_validation.md 2.6). For
these 20 quadrilateral voussoirs our limit analysis
(tools/validation_polygons/arch_limit.py) gives t_min/R = 0.10758.

Bodies: arch 1 voussoirs 1..20 (from the right springer, counter-clockwise), its
supports 21 (left), 22 (right); arch 2: 23..42 and 43, 44; and so on (22 bodies per
arch). Each arch has its own colour and see rule, so arches cannot touch each other.
"""
import math
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools import polytools as pt  # noqa: E402


G = 9.81
RHO = 2500.0
N = 20
R = 1.0
T_MIN_REF = 0.1075                # t/R, Milankovitch / nscd_validation.md 2.6
MU = 0.5
ARCHES = [((-2.0, 0.0), 1.05 * T_MIN_REF, "BLEUx", "stand"),
          ((2.0, 0.0), 0.95 * T_MIN_REF, "VERTx", "collapse"),
          ((-2.0, 3.0), 1.02 * T_MIN_REF, "JAUNE", "stand"),
          ((2.0, 3.0), 0.98 * T_MIN_REF, "ROUGE", "collapse")]
DT = 1.0e-3
N_STEPS = 800
NLGS_CHECK = "Quad"
NLGS_TOL = 1.0e-6
ALERT = 1.0e-2                  # m: falling voussoirs move up to 6 mm per step
HDF5_EVERY = 10


def first_body(i):
    """Serial number of the first voussoir of arch i (0-based)."""
    return 1 + i * (N + 2)


def build():
    from fracas_tools import Case, generators as gen
    case = Case(gravity=(0.0, -G))
    case.add_material("STONE", density=RHO)
    for i, (centre, tr, color, _) in enumerate(ARCHES):
        law = f"iqs{i + 1:02d}"
        case.add_law(law, "IQS_CLB", fric=MU)
        case.add_see("POLYG", color, "POLYG", color, law, ALERT)
        gen.arch(case, N, R, tr * R, "STONE", color, center=centre)
    case.run.set(time_step=DT, number_of_steps=N_STEPS, theta=0.5,
                 nlgs_check=NLGS_CHECK, nlgs_tolerance=NLGS_TOL, output_hdf5_every=HDF5_EVERY,
                 output_dof_every=0, output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    build().write(HERE)
    print(f"wrote {HERE / 'DATBOX'}")
