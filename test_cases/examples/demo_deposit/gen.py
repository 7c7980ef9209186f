#!/usr/bin/env python3
"""Generate the DATBOX of the demo deck demo_deposit (seeded: the same deck every time).

About 400 disks (radii 8-12 mm) in a loose jittered lattice fall into a 0.4 m wide box
of fixed JONCx walls under gravity; IQS_CLB friction 0.3 disk/disk, 0.5 disk/wall;
dt = 1e-3 s, 1000 steps; VTK (DISPLAY/) and HDF5 snapshots every 10 steps. This is
fracas_tools.generators.demo_deposit, written here as committed DATBOX files.

    build/release/bin/fracas-python test_cases/examples/demo_deposit/gen.py      # rewrites ./DATBOX
    build/release/bin/fracas --output build/demo test_cases/examples/demo_deposit   # then open build/demo/DISPLAY/fracas.pvd
"""

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent

from fracas_tools import generators as gen  # noqa: E402

if __name__ == "__main__":
    gen.demo_deposit(HERE, n=400, seed=1)
    print(f"wrote {HERE / 'DATBOX'}")
