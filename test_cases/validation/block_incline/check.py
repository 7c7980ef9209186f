#!/usr/bin/python3
"""Check the block_incline run: stick below tan(alpha) = mu, slide with
a = g (sin(alpha) - mu cos(alpha)) above it (README.md).

usage: check.py [RUN_DIR [theta1]]   (RUN_DIR holds OUTBOX/fracas.h5; default: this folder)
With "theta1" the run was made with --set theta=1: the slide distance is then too long by
exactly a h t / 2 (README.md), which is what is checked.
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

# Tolerances (README.md, "Tolerances and why")
TOL_ANGLE = 1.0e-8        # rad: contact normal vs the incline surface read from the deck
TOL_X = 1.0e-9            # m: displacement of a sticking block, normal displacement of a sliding one
TOL_FORCE_REL = 1.0e-8    # resultant contact force vs statics (NLGS tolerance)
TOL_S_REL = 1.0e-8        # slide distance and velocity, relative to a T^2/2 and a T (NLGS tolerance)
TOL_ROT = 1.0e-8          # rad: change of the block's rotation


def main():
    res = pt.Results(pt.run_dir_from_argv(HERE))
    theta1 = len(sys.argv) > 2 and sys.argv[2] == "theta1"
    if abs(res.theta - (1.0 if theta1 else 0.5)) > 1e-12:
        raise SystemExit(f"run made with theta = {res.theta}, expected {1.0 if theta1 else 0.5}")
    h = res.h
    g = gen.G
    ck = pt.Checker("block_incline" + (" (theta = 1)" if theta1 else ""))
    for k, (kind, alpha, law, expected) in enumerate(gen.SCENES):
        inc, blk = 2 * k + 1, 2 * k + 2
        mu = gen.MU_OF[law]
        tag = f"S{k + 1} {kind} {math.degrees(alpha):.3f}deg mu={mu} {expected}:"
        m = res.mass[blk - 1]
        # the incline angle seen by the solver (contact normal of the first step)
        c0 = res.contacts[0]
        sel = (c0["cd"] == blk) | (c0["an"] == blk)
        nrm = c0["normal"][sel]
        nrm = np.where((c0["cd"][sel] == blk)[:, None], nrm, -nrm)   # from incline to block
        a_sol = math.atan2(-nrm[:, 0].mean(), nrm[:, 1].mean())
        _, d_deck, _, _ = gen.incline_frame(k)          # incline surface as read from the deck
        a_deck = math.atan2(d_deck[1], d_deck[0])
        ck.close(f"{tag} contact normal angle (rad)", a_sol, a_deck, TOL_ANGLE)
        ck.close(f"{tag} contacts per step (face on face, every 10th step)", np.mean(
            [np.sum(res.pair_mask(i, blk, inc)) for i in range(0, len(res.time), 10)]), 2, 0)
        d = pt.unit(a_deck)
        n = pt.unit(a_deck + 0.5 * math.pi)
        t = res.time
        X = res.X[:, blk - 1, :2]
        s = -(X @ d)                       # distance travelled down the slope
        rot = res.X[:, blk - 1, 2]
        F = np.array([res.force_on(i, blk) for i in (0, len(t) - 1)])
        Fn, Ft = F @ n, F @ d              # normal force and friction (up the slope), steps 1 and N
        if expected == "stick":
            ck.at_most(f"{tag} max |displacement| (m)", np.abs(X).max(), TOL_X)
            ck.at_most(f"{tag} max |v| (m/s), 2nd half", np.abs(res.V[len(t) // 2:, blk - 1, :]).max(), 1e-12)
            ck.rel(f"{tag} R_n = m g cos(alpha) (N/m)", Fn[-1], m * g * math.cos(a_deck), TOL_FORCE_REL)
            ck.rel(f"{tag} R_t = m g sin(alpha) (N/m)", Ft[-1], m * g * math.sin(a_deck), TOL_FORCE_REL)
            ck.at_most(f"{tag} R_t / (mu R_n)", Ft[-1] / (mu * Fn[-1]), 1.0,
                       note=f"ref {math.tan(a_deck) / mu:.4f}")
        else:
            acc = g * (math.sin(a_deck) - mu * math.cos(a_deck))
            T = t[-1]
            s_ref = 0.5 * acc * t * t + (0.5 * acc * h * t if theta1 else 0.0)
            what = "a T^2/2 + a h T/2" if theta1 else "a T^2/2"
            ck.rel(f"{tag} s(T) = {what} (m)", s[-1], s_ref[-1], TOL_S_REL,
                   note=f"a = {acc:.6f} m/s2")
            err = np.max(np.abs(s - s_ref)) / s_ref[-1]
            ck.at_most(f"{tag} max_t |s - s_ref(t)| / s(T)", err, TOL_S_REL)
            v = -(res.V[:, blk - 1, :2] @ d)
            ck.rel(f"{tag} v(T) = a T (m/s)", v[-1], acc * T, TOL_S_REL)
            ck.at_most(f"{tag} max |normal displacement| (m)", np.abs(X @ n).max(), TOL_X)
            ck.at_most(f"{tag} max |rotation change| (rad)", np.abs(rot - rot[0]).max(), TOL_ROT)
            ck.rel(f"{tag} R_n = m g cos(alpha) (N/m)", Fn[-1], m * g * math.cos(a_deck), TOL_FORCE_REL)
            ck.rel(f"{tag} R_t / R_n = mu (sliding)", Ft[-1] / Fn[-1], mu, TOL_FORCE_REL)
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
