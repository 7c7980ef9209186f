#!/usr/bin/python3
"""Check the disk_column run: static reactions of a column (see README.md).

usage: check.py [RUN_DIR]   (RUN_DIR holds OUTBOX/fracas.h5; default: this folder)
Prints one line per quantity and exits 1 if any check fails.
"""
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
import gen          # noqa: E402  (the deck parameters)
from fracas_tools import valtools     # noqa: E402

FLOOR, LEFT, RIGHT = 1, 2, 3
FIRST_DISK = 4              # disks are bodies 4..13, bottom to top


def column_reactions(res, isnap):
    """Normal force of contact k (0: floor - disk 1, k: disk k - disk k+1)."""
    n = len(gen.RADII)
    out = []
    for k in range(n):
        below = FLOOR if k == 0 else FIRST_DISK + k - 1
        out.append(res.reaction_between(isnap, FIRST_DISK + k, below))
    return np.array(out)


def main():
    run_dir = valtools.run_dir_from_argv(HERE)
    res = valtools.Results(run_dir)
    n = len(gen.RADII)
    disks = slice(FIRST_DISK - 1, FIRST_DISK - 1 + n)
    m = res.mass[disks]
    weight_above = np.cumsum((m * gen.G)[::-1])[::-1]        # contact k carries disks k..n
    tol = gen.NLGS_TOL
    rho = valtools.chain_gauss_seidel_rate(m, grounded=True)
    ck = valtools.Checker("disk_column")

    # 1. settled reactions (last step) = weight above, to the NLGS tolerance
    r_end = column_reactions(res, -1)
    for k in range(n):
        name = "R floor-disk 1 (N/m)" if k == 0 else f"R disk {k}-disk {k + 1} (N/m)"
        ck.rel(name + " settled", r_end[k], weight_above[k], tol, note="rel., nlgs_tolerance")
    # 2. first step (cold start): the error left when the Maxm test stops is about
    #    tol / (1 - rho_GS) (the remaining geometric series of sweep corrections)
    r_1 = column_reactions(res, 0)
    err_1 = np.max(np.abs(r_1 - weight_above) / weight_above)
    ck.at_most("max rel. error of R, step 1 (cold start)", err_1, tol / (1.0 - rho),
               note=f"tol/(1-rho_GS), rho_GS = {rho:.4f}")
    # 3. walls: no lateral load in an aligned frictionless column
    wall = max(abs(res.reaction_between(i, FIRST_DISK + k, w))
               for i in range(len(res.time)) for k in range(n) for w in (LEFT, RIGHT))
    ck.at_most("max wall reaction / total weight", wall / weight_above[0], 1e-12)
    # 4. no drift: vertical settlement from the cold-start error of the first steps
    #    (per step at most N eps_n g h^2, eps_1 <= tol/(1-rho), eps_n decays at least by
    #    rho^50 per step of 50 sweeps), lateral motion zero, rotations zero
    h = res.h
    drift_bound = n * gen.G * h * h * tol / ((1.0 - rho) * (1.0 - rho ** 50))
    X = res.X[:, disks, :]
    ck.at_most("max |y - y0| of the disks over the run (m)", np.abs(X[:, :, 1]).max(),
               drift_bound, note="N g h^2 tol/((1-rho)(1-rho^50))")
    ck.at_most("max |x - x0| of the disks over the run (m)", np.abs(X[:, :, 0]).max(),
               gen.CLEARANCE, note="wall clearance")
    ck.at_most("max |rotation| of the disks over the run", np.abs(X[:, :, 2]).max(), 1e-12)
    half = len(res.time) // 2
    settle = np.abs(X[half:, :, :] - X[-1, :, :]).max()
    ck.at_most("max position change over the 2nd half (m)", settle, 1e-12)
    ck.at_most("max |v| of the disks, 2nd half (m/s)", np.abs(res.V[half:, disks, :]).max(), 1e-12)
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
