#!/usr/bin/python3
"""Write test_cases/validation/czm_energy/DATBOX: a free rigid block (1 m x 0.2 m POLYG,
density 2000) glued by MP3_CZM on a fixed ground block, under gravity, pushed sideways by
a driven force F(t) = F0 min(1, t/T) applied at its centre. The glue breaks in shear
(mode II: the interface stays compressed, no tipping), then the block slides with
Coulomb friction mu m g and accelerates. Energy audit (README.md): work of F + work of
gravity = kinetic + cohesive stored + damage (w L) + friction, within 1 %.
The parameters below are read by check.py.
"""
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
from fracas_tools.cohesive import Law  # noqa: E402

G = 9.81
RHO = 2000.0           # block density: m = 400 kg/m, weight 3924 N/m
WIDTH, HEIGHT = 1.0, 0.2
MU = 0.5               # mu m g = 1962 N/m
LAW = Law.mp3(cn=1.0e7, ct=1.0e7, smax=6000.0, w=6.0)   # di = 6e-4 m, dk = 1.05e-3 m
F0 = 8000.0            # final push (N/m): above the strength smax L = 6000 N/m
T_RAMP = 0.3           # ramp time (s)
DT = 1.25e-4           # time step (s): omega h = 0.02 for the glued block (omega = sqrt(ct L/m))
STEPS = 4000           # 0.5 s
ALERT = 0.01


def build():
    from fracas_tools import Case
    case = Case(gravity=(0.0, -G))
    case.add_material("STONE", density=RHO)
    LAW.add_to(case, "mp3cz", "MP3_CZM", MU)
    case.add_see("POLYG", "BLEUx", "POLYG", "BLEUx", "mp3cz", ALERT)
    ground = case.add_polygon([(-1.0, -0.5), (2.0, -0.5), (2.0, 0.0), (-1.0, 0.0)], "STONE")
    ground.fix()
    block = case.add_polygon([(-0.5 * WIDTH, 0.0), (0.5 * WIDTH, 0.0), (0.5 * WIDTH, HEIGHT),
                              (-0.5 * WIDTH, HEIGHT)], "STONE")
    block.impose_force(1, ct=F0, rampi=0.0, ramp=1.0 / T_RAMP)
    case.run.set(time_step=DT, number_of_steps=STEPS, theta=0.5, nlgs_check="Quad",
                 nlgs_tolerance=1e-8, output_hdf5_every=1, output_dof_every=0,
                 output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    build().write(HERE)
    print(f"wrote {HERE / 'DATBOX'}")
