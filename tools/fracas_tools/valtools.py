"""Shared helpers of the validation cases (test_cases/validation/*/check.py, gen.py);
Results (the one reader of fracas.h5) and Checker come from fracas_tools and are
re-exported here.

    from fracas_tools.valtools import Results, Checker, repo_root
    res = Results("path/to/run_dir")          # reads run_dir/OUTBOX/fracas.h5
    X, V = res.X, res.V                       # (nsnap, nb, 3) displacement, velocity
    ck = Checker("bouncing_disk")
    ck.close("apex 1", ours, ref, tol)        # |ours - ref| <= tol  (absolute)
    ck.rel("R floor", ours, ref, rtol)        # |ours - ref| <= rtol |ref|
    ck.true("energy decreasing", ok, detail)
    sys.exit(ck.finish())                     # prints the summary, 0 if all PASS

Every check prints one line: name, ours, reference, error, tolerance, PASS/FAIL.
Only h5py and numpy are needed (the system /usr/bin/python3).
"""

import sys
from pathlib import Path

import numpy as np

__all__ = ["repo_root", "Results", "Checker", "run_dir_from_argv",
           "chain_gauss_seidel_rate"]


def repo_root():
    """The repository root (two levels above this file: tools/fracas_tools/)."""
    return Path(__file__).resolve().parents[2]


from .checks import Checker  # noqa: F401  (the one Checker)
from .results import Results  # noqa: F401  (the one reader of fracas.h5)


def run_dir_from_argv(default):
    """The run directory (holding OUTBOX/fracas.h5): argv[1] or ``default``."""
    return Path(sys.argv[1]) if len(sys.argv) > 1 else Path(default)


def chain_gauss_seidel_rate(masses, grounded=False):
    """Spectral radius of Gauss-Seidel on the Delassus matrix of a frictionless chain
    of bodies in a line (contact k between body k and k+1, normals along the line).
    grounded=True adds a first contact between a fixed support and body 0 (a column
    on the floor). The NLGS error left when a sweep changes the reactions by a
    relative tol is about tol / (1 - rho)."""
    m = np.asarray(masses, dtype=float)
    if grounded:
        inv = np.concatenate([[0.0], 1.0 / m])          # the support has no mobility
    else:
        inv = 1.0 / m
    nc = len(inv) - 1
    w = np.zeros((nc, nc))
    for k in range(nc):
        w[k, k] = inv[k] + inv[k + 1]
        if k > 0:
            w[k, k - 1] = w[k - 1, k] = -inv[k]
    lower = np.tril(w)
    upper = np.triu(w, 1)
    return float(max(abs(np.linalg.eigvals(-np.linalg.solve(lower, upper)))))
