#!/usr/bin/python3
"""Write the Newton's cradle decks: N = 5 equal disks in a row on the x axis, no
gravity, frictionless RST_CLB, disk 1 moving at V toward the others at rest.

    newton_cradle/DATBOX             touching (gap 0), e = 1: simultaneous impact
    newton_cradle/sequential/DATBOX  gaps G > V h, e = 1: sequential binary impacts
    newton_cradle/inelastic/DATBOX   touching, e = 0: simultaneous, all end at V/N

The parameters below are also read by check.py (import gen).
"""
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools import valtools  # noqa: E402


N = 5               # disks
R = 0.5             # radius (m): touching centres 1 m apart, exact in binary
RHO = 1000.0
V = 1.0             # initial velocity of disk 1 (m/s, +x)
ALERT = 0.01        # alert distance (m), larger than the gaps of the sequential variant

# variant name -> (sub-folder, restitution, gap between neighbours, time step, steps)
VARIANTS = {
    "touching":   (".",          1.0, 0.0,    1.0e-3, 100),
    "sequential": ("sequential", 1.0, 1.025e-3, 1.0e-4, 100),
    "inelastic":  ("inelastic",  0.0, 0.0,    1.0e-3, 100),
}
NLGS_CHECK = "Maxm"
NLGS_TOL = 1.0e-10


def build(variant):
    from fracas_tools import Case
    _, e, gap, dt, steps = VARIANTS[variant]
    case = Case(gravity=(0.0, 0.0))
    case.add_material("STONE", density=RHO)
    case.add_law("rstcl", "RST_CLB", rstn=e, rstt=0.0, fric=0.0)
    case.add_see("DISKx", "BLEUx", "DISKx", "BLEUx", "rstcl", ALERT)
    for k in range(N):
        b = case.add_disk((k * (2.0 * R + gap), 0.0), R, "STONE")
        if k == 0:
            b.set_velocity(V, 0.0, 0.0)
    case.run.set(time_step=dt, number_of_steps=steps, theta=0.5,
                 nlgs_check=NLGS_CHECK, nlgs_tolerance=NLGS_TOL, output_hdf5_every=1,
                 output_dof_every=0, output_vtk_every=0, progress_every=0)
    return case


def case_dir(variant):
    return (HERE / VARIANTS[variant][0]).resolve()


if __name__ == "__main__":
    for name in VARIANTS:
        build(name).write(case_dir(name))
        print(f"wrote {case_dir(name) / 'DATBOX'}")
