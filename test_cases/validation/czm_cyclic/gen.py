#!/usr/bin/python3
"""Write test_cases/validation/czm_cyclic/<law>/DATBOX for <law> in mac, mp3: the glued
blocks of czm_mode_I opened and closed cyclically by a driven velocity +-v (evolution
file vy.dat): the opening goes 0 -> 2 -> 0.5 -> 3 -> 1 -> 4 d_peak, d_peak/300 per step.
Unloading must follow the secant (beta frozen), reloading must resume damage where it
stopped (README.md). The parameters below are read by check.py.
"""
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
from fracas_tools.cohesive import Law  # noqa: E402

DT = 1.0e-4            # time step (s)
RHO = 2000.0
MU = 0.5
GLUED = 1.0            # glued length (m)
ALERT = 0.01
STEP = 1.0 / 300.0     # opening per step / d_peak
TURNS = [2.0, 0.5, 3.0, 1.0, 4.0]   # successive targets of the opening / d_peak

LAWS = {
    "mac": ("IQS_MAC_CZM", Law.mac(cn=1.0e10, ct=1.0e11, b=0.0, w=40.0)),
    "mp3": ("MP3_CZM", Law.mp3(cn=1.0e11, ct=1.0e11, smax=1.0e6, w=40.0)),
}


def schedule(name):
    """(segments, table): steps and sign of each monotonic segment, and the (t, vy) table."""
    dpk = LAWS[name][1].d_peak(1)
    v = STEP * dpk / DT
    segs, prev = [], 0.0
    for target in TURNS:
        segs.append((int(round(abs(target - prev) / STEP)), 1.0 if target > prev else -1.0))
        prev = target
    table, n = [], 0
    for count, sign in segs:
        table.append([n * DT + (DT if n else 0.0), sign * v])
        n += count
        table.append([n * DT, sign * v])
    table.append([(n + 10) * DT, segs[-1][1] * v])
    return segs, table


def build(name):
    from fracas_tools import Case
    law_name, law = LAWS[name]
    segs, table = schedule(name)
    case = Case(gravity=(0.0, 0.0))
    case.add_material("STONE", density=RHO)
    law.add_to(case, "czm01", law_name, MU)
    case.add_see("POLYG", "BLEUx", "POLYG", "BLEUx", "czm01", ALERT)
    lower = case.add_polygon([(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)], "STONE")
    lower.fix()
    upper = case.add_polygon([(-0.5, 0.5), (0.5, 0.5), (0.5, 1.5), (-0.5, 1.5)], "STONE")
    upper.impose_evolution(2, "vlocy", "vy.dat", data=table)
    upper.impose_velocity(3)
    case.run.set(time_step=DT, number_of_steps=sum(c for c, _ in segs), theta=0.5, nlgs_check="Quad",
                 nlgs_tolerance=1e-6, output_hdf5_every=1, output_dof_every=0,
                 output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    for name in (sys.argv[1:] or LAWS):
        build(name).write(HERE / name)
        print(f"wrote {HERE / name / 'DATBOX'}  steps {sum(c for c, _ in schedule(name)[0])}")
