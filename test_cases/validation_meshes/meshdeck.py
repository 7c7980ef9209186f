"""Structured meshes for the validation cases of this folder (0-based node indices,
as numpy indexes them; the decks are written with fracas_tools.pre, 1-based).

    case = Case()
    x = rect_grid(nx, ny, lx, ly)
    b = case.add_mesh_body(x, one_based(quads(nx, ny)), model="M2DQ4", material="STEEL")
"""
import sys
from pathlib import Path

import numpy as np

TOOLS = Path(__file__).resolve().parents[2] / "tools"
if str(TOOLS) not in sys.path:
    sys.path.insert(0, str(TOOLS))
from fracas_tools.pre import Case  # noqa: E402

__all__ = ["Case", "rect_grid", "node_id", "quads", "triangles", "one_based", "distorted_grid"]


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
