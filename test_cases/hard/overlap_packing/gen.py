#!/usr/bin/python3
"""Write test_cases/hard/overlap_packing/DATBOX: 300 random convex POLYG grains (4 to 7
vertices, circumradius 8-12 mm) falling from a loose lattice into a 0.3 m wide box of
fixed JONCx walls and settling into a dense packing (IQS_CLB, mu 0.4 grain/grain,
0.5 grain/wall), 1.5 s, h = 5e-4 s (README.md; nscd_validation.md 3.9).
Bodies: 1..300 grains, 301 bottom, 302 left, 303 right wall. Seeded (SEED).
"""
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools import polytools as pt  # noqa: E402


SEED = 3
N = 300
RMIN, RMAX = 0.008, 0.012
WIDTH = 0.3
DT = 5.0e-4
N_STEPS = 3000
NLGS_CHECK = "Quad"
NLGS_TOL = 1.0e-4
HDF5_EVERY = 100
ALERT = 5.0e-3                  # m: grains fall at up to 3.4 m/s, 3.4 mm per step


def build():
    from fracas_tools import Case, generators as gen
    case = Case(gravity=(0.0, -9.81))
    case.add_material("STONE", density=2600.0)
    case.add_material("TDURx", density=1000.0)
    grains = gen.deposit_polygons(case, N, RMIN, RMAX, WIDTH, "STONE", seed=SEED)
    top = gen.top_of(case, grains)
    gen.box_walls(case, 0.0, WIDTH, 0.0, top + 0.05, 0.01, "TDURx")
    gen.add_granular_laws(case, fric_grains=0.4, fric_walls=0.5, alert=ALERT, grain_type="POLYG")
    case.run.set(time_step=DT, number_of_steps=N_STEPS, theta=0.5,
                 nlgs_check=NLGS_CHECK, nlgs_tolerance=NLGS_TOL, output_hdf5_every=HDF5_EVERY,
                 output_dof_every=0, output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    build().write(HERE)
    print(f"wrote {HERE / 'DATBOX'}")
