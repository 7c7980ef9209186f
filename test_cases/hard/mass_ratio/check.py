#!/usr/bin/python3
"""Check a mass_ratio run (heavy block on a light one, README.md): the normal
reactions converge to the weights, within the Gauss-Seidel error bound at every step;
prints the sweeps and times it took.

usage: check.py RUN_DIR VARIANT     (VARIANT: r1, r100 or r1000)
Prints one line per quantity and exits 1 if any check fails.
"""
import math
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
import gen          # noqa: E402  (the deck parameters)
from fracas_tools import polytools as pt  # noqa: E402

GROUND, LIGHT, HEAVY = 1, 2, 3
SETTLED = 500             # the last SETTLED steps are "settled"
TOL_SETTLED = 1.0e-6      # relative error of the settled reactions
TOL_V_SETTLED = 1.0e-6    # m/s: block speeds over the settled steps


def normal_gs_rate(m, M, a):
    """Spectral radius of Gauss-Seidel on the Delassus matrix of the 4 normal contacts
    (two points per face, at x = -a/2 and +a/2; blocks of side a, inertia m a^2/6)."""
    minv = np.diag([1 / m, 1 / m, 6 / (m * a * a), 1 / M, 1 / M, 6 / (M * a * a)])
    H = np.array([[0, 1, x, 0, 0, 0] for x in (-a / 2, a / 2)] +
                 [[0, -1, -x, 0, 1, x] for x in (-a / 2, a / 2)], dtype=float)
    W = H @ minv @ H.T
    L, U = np.tril(W), np.triu(W, 1)
    return float(max(abs(np.linalg.eigvals(-np.linalg.solve(L, U)))))


def main():
    if len(sys.argv) < 3 or sys.argv[2] not in gen.RATIOS:
        raise SystemExit(f"usage: check.py RUN_DIR {{{','.join(gen.RATIOS)}}}")
    variant = sys.argv[2]
    res = pt.Results(sys.argv[1])
    s = res.series
    g, h = gen.G, res.h
    m, M = res.mass[LIGHT - 1], res.mass[HEAVY - 1]
    ck = pt.Checker(f"mass_ratio {variant} (M/m = {M / m:g})")
    rho = normal_gs_rate(m, M, gen.A)
    eps = gen.NLGS_TOL / (1.0 - rho)          # error left by the stopping test
    n = len(res.time)
    top = np.array([res.normal_force_between(i, HEAVY, LIGHT) for i in range(n)])
    bot = np.array([res.normal_force_between(i, LIGHT, GROUND) for i in range(n)])
    e_top = (top - M * g) / (M * g)
    e_bot = (bot - (m + M) * g) / ((m + M) * g)
    err = np.maximum(np.abs(e_top), np.abs(e_bot))
    sw = s["sweeps"]
    ck.info("Gauss-Seidel rate of the normal problem rho", rho, note=f"M/(M+m) = {M / (M + m):.6f}")
    ck.info("sweeps, step 1 (cold start)", sw[0],
            note=f"ln(tol)/ln(rho) = {math.log(gen.NLGS_TOL) / math.log(rho):.0f}")
    ck.info("sweeps, mean over the run", sw.mean())
    ck.info("sweeps, max over the run", sw.max())
    below = np.nonzero(err > TOL_SETTLED)[0]
    first_ok = below[-1] + 1 if len(below) else 0
    ck.info("steps until the reactions stay within 1e-6", first_ok)
    ck.info("sweeps until then (total)", sw[:first_ok].sum())
    ck.info("NLGS solve time, whole run (s)", s["solve_time"].sum())
    ck.info("step time, whole run (s)", s["step_time"].sum())
    ck.true("every step converged", bool((s["converged"] == 1).all()),
            ours=f"{int((s['converged'] == 0).sum())} not")
    ck.at_most("max rel. reaction error, step 1", err[0], eps, note="tol/(1-rho)")
    ck.at_most("max rel. reaction error, whole run", err.max(), eps, note="tol/(1-rho)")
    ck.at_most(f"max rel. reaction error, last {SETTLED} steps", err[-SETTLED:].max(), TOL_SETTLED)
    ck.rel("settled R heavy/light = M g (N/m)", top[-1], M * g, TOL_SETTLED)
    ck.rel("settled R light/ground = (m+M) g (N/m)", bot[-1], (m + M) * g, TOL_SETTLED)
    ck.at_most(f"max block speed, last {SETTLED} steps (m/s)", np.abs(res.V[-SETTLED:, 1:, :2]).max(),
               TOL_V_SETTLED)
    bound = n * eps * g * h * h
    ck.at_most("max sinking of the heavy block (m)", np.abs(res.X[:, HEAVY - 1, 1]).max(), bound,
               note="N_steps tol/(1-rho) g h^2")
    ck.at_most("max |x| drift of the blocks (m)", np.abs(res.X[:, 1:, 0]).max(), bound)
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
