#!/usr/bin/python3
"""Writes weak/DATBOX and strong/DATBOX: the small hydrided plate of the ctest case
(README.md), with tools/hydride/hydride_plate.py. Same seed, same mesh, same loading;
only the matrix/hydride interface law differs."""
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
from fracas_tools.scripts import load  # noqa: E402
hp = load(HERE.parents[2] / "tools" / "hydride" / "hydride_plate.py")

GEOMETRY = hp.Geometry(width=16e-6, height=16e-6, thickness=(2e-6, 2.2e-6), aspect=(2.5, 3.5),
                       clearance=0.8e-6, notch=2.5e-6)
SEED, H, DT, STEPS = 2, 1e-6, 1e-10, 600



def write(case_dir, bonding):
    """The deck of one bonding case in case_dir (DATBOX/ and hydrides.json)."""
    return hp.generate(case_dir, SEED, H, bonding, GEOMETRY, hp.Loading(velocity=10.0),
                       time_step=DT, steps=STEPS, output_every=STEPS)


if __name__ == "__main__":
    for bonding in ("weak", "strong"):
        info = write(HERE / bonding, bonding)
        print(f"{bonding}: {info['elements']} elements, {len(info['hydrides'])} hydrides, "
              f"alert {info['alert']:.3g} m")
