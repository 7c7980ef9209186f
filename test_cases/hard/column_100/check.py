#!/usr/bin/python3
"""Check the column_100 run (README.md): a column of 100 blocks stays at rest over
10 000 steps and carries the weight above each interface; prints iterations and times.

usage: check.py [RUN_DIR]   (RUN_DIR holds OUTBOX/fracas.h5; default: this folder)
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

TOL_LATERAL = 1.0e-3      # x block side: lateral drift of any block
TOL_ROT = 1.0e-4          # rad: rotation of any block
TOL_MEAN_R = 1.0e-4       # relative error of the reactions averaged over the 2nd-half snapshots


def normal_rate(n, a):
    """Gauss-Seidel spectral radius of the normal contact problem of the column (two
    points per face at x = -a/2, +a/2; blocks of side a, inertia m a^2/6)."""
    nd = 3 * n
    minv = np.zeros((nd, nd))
    for k in range(n):
        minv[3 * k, 3 * k] = minv[3 * k + 1, 3 * k + 1] = 1.0
        minv[3 * k + 2, 3 * k + 2] = 6.0 / (a * a)
    rows = []
    for k in range(n):
        for x in (-a / 2, a / 2):
            r = np.zeros(nd)
            r[3 * k + 1], r[3 * k + 2] = 1.0, x
            if k > 0:
                r[3 * (k - 1) + 1], r[3 * (k - 1) + 2] = -1.0, -x
            rows.append(r)
    H = np.array(rows)
    W = H @ minv @ H.T
    L, U = np.tril(W), np.triu(W, 1)
    G = -np.linalg.solve(L, U)
    # power iteration (the matrix is 200 x 200, eigvals is fine too)
    return float(max(abs(np.linalg.eigvals(G))))


def main():
    res = pt.Results(pt.run_dir_from_argv(HERE))
    s = res.series
    g, h, N, a = gen.G, res.h, gen.N, gen.A
    ck = pt.Checker("column_100")
    m = res.mass[1:N + 1]
    above = np.cumsum((m * g)[::-1])[::-1]               # interface k carries blocks k..N
    rho = normal_rate(N, a)
    eps = gen.NLGS_TOL / (1.0 - rho)
    sw = s["sweeps"]
    ck.info("Gauss-Seidel rate of the normal problem rho", rho, note=f"1 - rho = {1 - rho:.2e}")
    ck.info("sweeps, step 1 (cold start)", sw[0])
    ck.info("sweeps, mean / median / max", sw.mean(), note=f"median {np.median(sw):.0f}, max {sw.max():.0f}")
    ck.info("NLGS solve time, whole run (s)", s["solve_time"].sum())
    ck.info("step time, whole run (s)", s["step_time"].sum())
    ck.true("every step converged", bool((s["converged"] == 1).all()),
            ours=f"{int((s['converged'] == 0).sum())} not")
    nsnap = len(res.time)
    R = np.array([[res.normal_force_between(i, k + 2, k + 1) for k in range(N)] for i in range(nsnap)])
    err = np.abs(R - above[None, :]) / above[None, :]
    ck.at_most("max rel. reaction error, any snapshot", err.max(), eps, note="tol/(1-rho)")
    mean_err = np.abs(R[nsnap // 2:].mean(axis=0) - above) / above
    ck.at_most("rel. error of the mean reactions, 2nd half", mean_err.max(), TOL_MEAN_R)
    X = res.X[:, 1:N + 1, :]
    n_steps = int(res.step[-1])
    settle = n_steps * eps * g * h * h
    ck.at_most("max vertical settlement (m)", np.abs(X[:, :, 1]).max(), settle,
               note="N_steps tol/(1-rho) g h^2")
    ck.at_most("max lateral drift / block side", np.abs(X[:, :, 0]).max() / a, TOL_LATERAL)
    ck.at_most("max rotation (rad)", np.abs(X[:, :, 2]).max(), TOL_ROT)
    ck.info("max block speed over the run (m/s)", np.abs(res.V[:, 1:N + 1, :2]).max())
    ck.info("kinetic energy, mean over the last 1000 steps (J/m)", s["kinetic_energy"][-1000:].mean(),
            note=f"potential energy scale m g a = {m[0] * g * a:.1f} J/m")
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
