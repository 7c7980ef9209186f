"""Shared helpers of the polygon and masonry cases (test_cases/validation/<poly cases>,
test_cases/hard/*, test_cases/examples/{masonry_wall,arch}): small geometry and
deck-precision helpers; Results (the one reader of fracas.h5) and Checker come from
fracas_tools (results, checks) and are re-exported here.

    from fracas_tools import polytools as pt
    res = pt.Results(run_dir)                # run_dir/OUTBOX/fracas.h5
    F = res.force_on(isnap, body)            # (2,) resultant contact force on a body
    ck = pt.Checker("block_incline")
    ck.close(name, ours, ref, tol); ck.rel(...); ck.at_most(...); ck.at_least(...)
    sys.exit(ck.finish())

Only numpy and h5py (the system /usr/bin/python3). Body numbers are 1-based serial
numbers (BODIES.DAT order), as in the results file.
"""

import math
import sys
from pathlib import Path

import numpy as np

__all__ = ["repo_root", "run_dir_from_argv", "Results", "Checker",
           "rot", "unit", "rect", "fmt_g"]


def repo_root():
    """The repository root (two levels above this file: tools/fracas_tools/)."""
    return Path(__file__).resolve().parents[2]


from .checks import Checker  # noqa: F401  (the one Checker)
from .results import Results  # noqa: F401  (the one reader of fracas.h5)


def run_dir_from_argv(default):
    """The run directory (holding OUTBOX/fracas.h5): argv[1] or ``default``."""
    return Path(sys.argv[1]) if len(sys.argv) > 1 else Path(default)


def rot(a):
    """2x2 rotation matrix of angle a (rad, counter-clockwise)."""
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s], [s, c]])


def unit(a):
    """Unit vector at angle a."""
    return np.array([math.cos(a), math.sin(a)])


def rect(w, h, cx=0.0, cy=0.0):
    """Counter-clockwise rectangle of width w, height h centred at (cx, cy)."""
    return np.array([[cx - 0.5 * w, cy - 0.5 * h], [cx + 0.5 * w, cy - 0.5 * h],
                     [cx + 0.5 * w, cy + 0.5 * h], [cx - 0.5 * w, cy + 0.5 * h]])


def fmt_g(v, digits=6):
    return f"{v:.{digits}g}"


# --------------------------------------------------------------------------------------
# deck-precision helpers
# --------------------------------------------------------------------------------------

def r8(x):
    """x as the DATBOX files hold it (8 significant digits, %.7E)."""
    return float(f"{x:.7E}")


def snap_on_line(P, d, n, offset_n, start, search=1.0e-3, samples=200001):
    """A body centre P + s d + offset_n n with s in [start, start + search] chosen so
    that, once rounded to the DATBOX's 8 significant digits, its distance to the line
    (P, d) is still offset_n to round-off: only the normal component of the rounding
    error opens or closes a gap, and a 1-D search along d finds a point where it is
    below 1e-12 m. Returns (rounded centre (2,), normal error, s)."""
    P, d, n = (np.asarray(v, dtype=float) for v in (P, d, n))
    s = start + np.linspace(0.0, search, samples)
    c = P[None, :] + s[:, None] * d[None, :] + offset_n * n[None, :]
    cr = np.vectorize(r8)(c)
    err = np.abs((cr - c) @ n)
    i = int(np.argmin(err))
    return cr[i], float(err[i]), float(s[i])
