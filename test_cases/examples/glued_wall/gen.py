#!/usr/bin/env python3
"""Generate the DATBOX of the demo deck glued_wall: a small running-bond wall of rigid
POLYG bricks (5 courses, 0.4 m x 0.2 m bricks, 1.2 m wide), glued brick to brick and to a
fixed ground block by IQS_MAC_CZM (cn = ct = 1e8 Pa/m, w = 5 J/m^2, friction 0.6), under
gravity. A driven block (0.3 m x 0.35 m, IQS_CLB friction 0.5 against the bricks) starts
2 cm to the left of the two top courses and moves right at 0.5 m/s: it shears the top
courses off the wall. Interfaces touching at the start are glued (beta = 1); the pusher
touches later, so it is never glued. dt = 5e-4 s, 2000 steps (1 s); VTK (DISPLAY/) and
HDF5 snapshots every 20 steps.

    build/release/bin/fracas-python test_cases/examples/glued_wall/gen.py      # rewrites ./DATBOX
    build/release/bin/fracas --output build/glued_wall test_cases/examples/glued_wall   # then open build/glued_wall/DISPLAY/fracas.pvd

In ParaView colour the contact points (contacts_*.vtu, part 1) by `beta` (1 sound, 0
broken) or `broken`; fracas.h5 lists the broken interfaces in each snapshot
(contacts/broken, with contacts/cd_body and an_body).
"""

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent

from fracas_tools import Case, generators as gen  # noqa: E402

BRICK_L, BRICK_H = 0.4, 0.2
COURSES, PER_COURSE = 5, 3
V_PUSH = 0.5


def build():
    case = Case(gravity=(0.0, -9.81))
    case.add_material("STONE", density=2000.0)
    case.add_material("STEEL", density=7800.0)
    glue = dict(dyfr=0.6, stfr=0.6, cn=1.0e8, ct=1.0e8, b=0.0, w=5.0)
    case.add_law("glue1", "IQS_MAC_CZM", **glue)
    case.add_law("glue2", "IQS_MAC_CZM", **glue)
    case.add_law("iqspu", "IQS_CLB", fric=0.5)
    # ground first: the lowest body number is the antagonist of a polygon pair
    ground = case.add_polygon([(-1.0, -0.3), (2.2, -0.3), (2.2, 0.0), (-1.0, 0.0)], "STONE", color="GRNDx")
    ground.fix()
    gen.masonry_wall(case, COURSES, PER_COURSE, BRICK_L, BRICK_H, "STONE", color="BLEUx", ground=False)
    y0 = (COURSES - 2) * BRICK_H + 0.03
    pusher = case.add_polygon([(-0.32, y0), (-0.02, y0), (-0.02, y0 + 0.35), (-0.32, y0 + 0.35)], "STEEL",
                              color="PUSHx")
    pusher.impose_velocity(1, ct=V_PUSH)
    pusher.impose_velocity((2, 3))
    alert = 1.0e-2
    case.add_see("POLYG", "BLEUx", "POLYG", "BLEUx", "glue1", alert)
    case.add_see("POLYG", "BLEUx", "POLYG", "GRNDx", "glue2", alert)
    case.add_see("POLYG", "PUSHx", "POLYG", "BLEUx", "iqspu", alert)
    case.run.set(time_step=5.0e-4, number_of_steps=2000, theta=0.5, nlgs_check="Quad",
                 nlgs_tolerance=1e-4, output_vtk_every=20, output_hdf5_every=20,
                 output_dof_every=500)
    return case


if __name__ == "__main__":
    build().write(HERE)
    print(f"wrote {HERE / 'DATBOX'}")
