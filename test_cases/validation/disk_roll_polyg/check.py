#!/usr/bin/python3
"""Check the disk_roll_polyg run: a disk on a POLYG incline (DKPLx) rolls without slip
when mu >= tan(alpha) k/(1+k) (k = I/(m R^2) = 1/2), and slips otherwise (README.md).

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

TOL_REL = 1.0e-8          # distances, speeds, spins (NLGS tolerance); constant accelerations: exact for theta = 0.5
TOL_X = 1.0e-9            # m: normal displacement (the disk stays on the incline)


def main():
    res = pt.Results(pt.run_dir_from_argv(HERE))
    g = gen.G
    t = res.time
    T = t[-1]
    ck = pt.Checker("disk_roll_polyg")
    dkpl = res.inter_names.index("DKPLx") + 1
    for k, (_, mu, expected) in enumerate(gen.SCENES):
        _, d, n, _, alpha = gen.frame(k)
        b = 2 * k + 2
        m, I = res.mass[b - 1], res.inertia[b - 1]
        r = gen.R
        kk = I / (m * r * r)                                   # 1/2 for a disk (8-digit deck gyrd)
        mu_c = math.tan(alpha) * kk / (1.0 + kk)
        tag = f"S{k + 1} {math.degrees(alpha):.0f}deg mu={mu} ({expected}):"
        s = -(res.X[:, b - 1, :2] @ d)                          # down the slope
        v = -(res.V[:, b - 1, :2] @ d)
        w = res.V[:, b - 1, 2]
        ck.true(f"{tag} DKPLx contact", bool(np.all(res.contacts[-1]["inter"][
            (res.contacts[-1]["cd"] == b) | (res.contacts[-1]["an"] == b)] == dkpl)))
        if expected == "roll":
            ck.at_least(f"{tag} mu >= tan(alpha) k/(1+k)", mu, mu_c, note=f"threshold {mu_c:.4f}")
            a = g * math.sin(alpha) / (1.0 + kk)
            ck.rel(f"{tag} s(T) = a T^2/2, a = g sin/(1+k) (m)", s[-1], 0.5 * a * T * T, TOL_REL,
                   note=f"a = {a:.6f} m/s2")
            ck.rel(f"{tag} spin(T) = v(T)/R (rad/s)", w[-1], v[-1] / r, TOL_REL, note="no slip")
            ck.at_most(f"{tag} max slip speed |v - omega R| (m/s)", np.abs(v - w * r).max(), TOL_REL * a * T)
        else:
            ck.true(f"{tag} mu < tan(alpha) k/(1+k)", mu < mu_c, ours=mu, note=f"threshold {mu_c:.4f}")
            a = g * (math.sin(alpha) - mu * math.cos(alpha))
            wdot = mu * m * g * math.cos(alpha) * r / I
            ck.rel(f"{tag} s(T) = a T^2/2, a = g (sin - mu cos) (m)", s[-1], 0.5 * a * T * T, TOL_REL,
                   note=f"a = {a:.6f} m/s2")
            ck.rel(f"{tag} spin(T) = mu m g cos(alpha) R T / I (rad/s)", w[-1], wdot * T, TOL_REL)
        ck.at_most(f"{tag} max normal displacement (m)", np.abs(res.X[:, b - 1, :2] @ n).max(), TOL_X)
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
