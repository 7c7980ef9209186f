"""Shared helpers of the meshed validation cases (test_cases/validation_meshes/*/case.py):
structured meshes (0-based node indices, as numpy indexes them; the decks are written
with fracas_tools.pre, 1-based), command line, running fracas on a
generated case and opening its results with the one reader (fracas_tools.results:
every fracas.h5 snapshot holds the meshes' node and Gauss-point states at full
precision, Snapshot.mesh["X"], ["V"], ["gauss_points"], or Run.snapshot_arrays
("mesh_X") for all snapshots); checks are fracas_tools.checks.Checker rows (Checker
is imported from here).

Each case script is called as  case.py --fracas BIN --out DIR [--long]
and exits 1 if a check fails.

    case = Case()
    x = rect_grid(nx, ny, lx, ly)
    b = case.add_mesh_body(x, one_based(quads(nx, ny)), model="M2DQ4", material="STEEL")
"""
import argparse
import subprocess
import sys

import numpy as np

from .checks import Checker  # noqa: F401  (re-exported for the case scripts)
from .pre import Case  # noqa: F401  (re-exported for the case scripts)
from .results import Run


def args(description):
    p = argparse.ArgumentParser(description=description)
    p.add_argument("--fracas", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--long", action="store_true", help="the long version (finer meshes)")
    return p.parse_args()


def run_fracas(fracas, case_dir, *settings):
    """Run fracas on case_dir (--set for each of settings) and return its results
    (a Run, to be closed; exits on failure or an unfinished run)."""
    # no restart points before the last step: the checks read snapshots and series only
    settings = ("output_restart_every=0",) + settings
    cmd = [fracas, "-q", "--overwrite"] + [x for s in settings for x in ("--set", s)] + [str(case_dir)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"fracas failed on {case_dir}:\n{r.stdout}\n{r.stderr}")
    run = Run(case_dir)
    if not run.complete:
        sys.exit(f"{case_dir}: unfinished run")
    return run


def rect_grid(nx, ny, lx, ly, x0=0.0, y0=0.0):
    """Nodes (numbered row by row, x fastest) of an (nx+1) x (ny+1) grid."""
    xs = np.linspace(x0, x0 + lx, nx + 1)
    ys = np.linspace(y0, y0 + ly, ny + 1)
    return np.array([[x, y] for y in ys for x in xs])


def distorted_grid(n, size, seed, amplitude):
    """rect_grid(n, n, size, size) with its interior nodes moved at random (seeded) by up
    to amplitude x the cell size, coordinates rounded to 1e-4 (the deck's 8-digit fields
    then hold them exactly)."""
    x = rect_grid(n, n, size, size)
    rng = np.random.default_rng(seed)
    h = size / n
    for j in range(1, n):
        for i in range(1, n):
            x[node_id(i, j, n)] += rng.uniform(-amplitude, amplitude, 2) * h
    return np.round(x, 4)


def node_id(i, j, nx):
    return j * (nx + 1) + i


def quads(nx, ny):
    """Q4 connectivity (counter-clockwise) of rect_grid."""
    return [[node_id(i, j, nx), node_id(i + 1, j, nx), node_id(i + 1, j + 1, nx), node_id(i, j + 1, nx)]
            for j in range(ny) for i in range(nx)]


def triangles(nx, ny):
    """T3 connectivity of rect_grid, each square cut along alternating diagonals."""
    out = []
    for j in range(ny):
        for i in range(nx):
            a, b = node_id(i, j, nx), node_id(i + 1, j, nx)
            c, d = node_id(i + 1, j + 1, nx), node_id(i, j + 1, nx)
            if (i + j) % 2 == 0:
                out += [[a, b, c], [a, c, d]]
            else:
                out += [[a, b, d], [b, c, d]]
    return out


def one_based(elements):
    """Node lists with 1-based numbers, as the deck files (and fracas_tools) number them."""
    return [tuple(int(n) + 1 for n in e) for e in elements]
