#!/usr/bin/env python3
"""Generate the DATBOX of the regression case deposit_1000 (seeded: the same deck every time).

1000 disks, radii uniform in [4, 6] mm (seed 1), placed without overlap on a jittered
square lattice in a 0.266 m wide box of four fixed JONCx walls (floor, two sides, lid
well above the cloud), falling under gravity; IQS_CLB friction 0.3 disk/disk and 0.5
disk/wall, alert distance 2 mm (rmin/2); dt = 1e-3 s.

    build/release/bin/fracas-python test_cases/regression/deposit_1000/gen.py     # rewrites ./DATBOX
    build/release/bin/fracas-python test_cases/regression/deposit_1000/gen.py --seed 2 --out /tmp/d2
                                          # another sample of the same deck (sensitivity study)

The committed DATBOX is the output of this script; change the script, not the files.
"""

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent

from fracas_tools import Case                      # noqa: E402
from fracas_tools import generators as gen         # noqa: E402

N = 1000
SEED = 1
RMIN, RMAX = 0.004, 0.006
WIDTH = 0.266
NSTEPS = 1000
TIME_STEP = 1.0e-3


def build(seed=SEED):
    case = Case(gravity=(0.0, -9.81, 0.0))
    case.add_material("STONE", density=2600.0)
    case.add_material("TDURx", density=1000.0)
    rng = gen.rng_from(seed)
    radii = gen.uniform_radii(N, RMIN, RMAX, rng)
    disks = gen.deposit_disks(case, radii, WIDTH, "STONE", "BLEUx", rng, method="lattice")
    top = gen.top_of(case, disks)
    # four walls: floor, left, right and a lid 4 rmax above the initial cloud
    gen.box_walls(case, 0.0, WIDTH, 0.0, top + 4.0 * RMAX, 0.01, "TDURx", "WALLx", top=True)
    gen.add_granular_laws(case, fric_grains=0.3, fric_walls=0.5, alert=0.5 * RMIN)
    case.run.set(time_step=TIME_STEP, number_of_steps=NSTEPS, theta=0.5,
                 nlgs_check="Quad", nlgs_tolerance=1e-4, nlgs_relaxation=1.0,
                 nlgs_sweeps_per_check=50, nlgs_max_checks=400, nlgs_order="stored",
                 output_dof_every=0, output_vtk_every=0, output_hdf5_every=100,
                 progress_every=100)
    return case


if __name__ == "__main__":
    import argparse
    p = argparse.ArgumentParser(description="write the deposit_1000 DATBOX")
    p.add_argument("--seed", type=int, default=SEED, help=f"generator seed (default {SEED})")
    p.add_argument("--out", default=str(HERE), help="case directory (default: this folder)")
    a = p.parse_args()
    build(a.seed).write(a.out)
    print(f"wrote {Path(a.out) / 'DATBOX'}")
