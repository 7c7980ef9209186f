#!/usr/bin/python3
"""Check the disk_pyramid run: the three-cylinder pyramid holds at mu = 0.30 with the
static reactions, and collapses at mu = 0.25 with the initial accelerations of
rigid-body dynamics (README.md).

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

GROUND = 1
TOL_REST = 1.0e-8         # m, rad: motion of the holding pyramid (deck rounding of the top disk: 5e-9 m)
TOL_REL = 1.0e-7          # statics (10 x the NLGS tolerance: the top-contact split reaches 5.5e-9)
TOL_STEP1 = 1.0e-6        # reactions of the first step of the collapse vs the initial dynamics
TOL_ACC = 1.0e-3          # 2 x(t)/t^2 at t = T_ACC vs the initial acceleration (O(t^2) drift: 1.6e-4)
T_ACC = 0.01
COLLAPSE_T = 1.0          # s
COLLAPSE_DROP = 0.1       # x R: drop of the top disk at COLLAPSE_T
S3 = math.sqrt(3.0)


def initial_dynamics(m, r, g, mu):
    """Initial state of the collapse from rest (right half; top sliding on the bottom
    disks with friction mu N, bottom disks rolling without slip, no force between the
    bottom disks): returns dict(xdd, aT, N, G, H) - bottom disk acceleration (outwards),
    top disk vertical acceleration, normal force at a top contact, ground normal and
    tangential force under a bottom disk."""
    I = 0.5 * m * r * r
    e = np.array([-0.5, 0.5 * S3])          # bottom-right centre -> top centre
    t = np.array([0.5 * S3, 0.5])           # tangent at that contact
    # unknowns: xdd, alpha, aT, N, G, H; friction on the bottom disk fb = -mu N (along t)
    A = np.array([
        [m, 0, 0, e[0] + mu * t[0], 0, -1],            # bottom: x momentum
        [0, 0, 0, -e[1] - mu * t[1], 1, 0],            # bottom: y (no vertical motion)
        [0, I, 0, -r * mu, 0, -r],                     # bottom: moment
        [1, r, 0, 0, 0, 0],                            # rolling: xdd = -r alpha
        [0, 0, m, -2 * (e[1] + mu * t[1]), 0, 0],      # top: y momentum
        [1 / S3, 0, 1, 0, 0, 0]])                      # contact kept: aT = -xdd/sqrt(3)
    b = np.array([0, m * g, 0, 0, -m * g, 0])
    xdd, _, aT, N, G, H = np.linalg.solve(A, b)
    return dict(xdd=xdd, aT=aT, N=N, G=G, H=H)


def main():
    res = pt.Results(pt.run_dir_from_argv(HERE))
    g, r = gen.G, gen.R
    t = res.time
    ck = pt.Checker("disk_pyramid")
    for p, (x0, mu, _, expected) in enumerate(gen.PYRAMIDS):
        bl, br, tp = 2 + 3 * p, 3 + 3 * p, 4 + 3 * p
        m = res.mass[tp - 1]
        W = m * g
        tag = f"pyramid {p + 1} mu={mu} ({expected}):"
        disks = [bl - 1, br - 1, tp - 1]
        if expected == "hold":
            ck.at_most(f"{tag} max |displacement| (m)", np.abs(res.X[:, disks, :2]).max(), TOL_REST)
            ck.at_most(f"{tag} max |rotation| (rad)", np.abs(res.X[:, disks, 2]).max(), TOL_REST)
            i = len(t) - 1
            c = res.contacts[i]
            for name, b in (("left", bl), ("right", br)):
                ck.rel(f"{tag} ground normal force under {name} disk = 1.5 W (N/m)",
                       res.normal_force_between(i, b, GROUND), 1.5 * W, TOL_REL)
            Ftop = res.force_on(i, tp)
            ck.rel(f"{tag} top disk: support force = W (N/m)", Ftop[1], W, TOL_REL)
            mk = res.pair_mask(i, tp, br)
            N, f = float(c["rn"][mk][0]), abs(float(c["rt"][mk][0]))
            P = res.normal_force_between(i, bl, br)
            ck.at_least(f"{tag} force between the bottom disks P >= 0 (N/m)", P, -TOL_REL * W,
                        note="indeterminate, P in [0, 0.06 N] admissible")
            # equilibrium of a bottom disk: f (2 + sqrt(3))/2 = N/2 + P
            ck.rel(f"{tag} top contact f/N = (1/2 + P/N)/(1 + sqrt(3)/2)", f / N,
                   (0.5 + P / N) / (1.0 + 0.5 * S3), TOL_REL,
                   note=f"2 - sqrt(3) = {2 - S3:.6f} when P = 0")
            ck.at_most(f"{tag} top contact f/N <= mu", f / N, mu)
            ck.rel(f"{tag} top contact N (N/m)", N, (W - f) / S3, TOL_REL, note="N sqrt(3) + f = W")
        else:
            ref = initial_dynamics(m, r, g, mu)
            c = res.contacts[0]
            ck.rel(f"{tag} step 1: top contact N (N/m)", c["rn"][res.pair_mask(0, tp, br)][0], ref["N"], TOL_STEP1,
                   note="initial dynamics")
            ck.rel(f"{tag} step 1: top contact |f| = mu N (N/m)", abs(c["rt"][res.pair_mask(0, tp, br)][0]),
                   mu * ref["N"], TOL_STEP1)
            ck.rel(f"{tag} step 1: ground normal G (N/m)", res.normal_force_between(0, br, GROUND), ref["G"], TOL_STEP1)
            ck.rel(f"{tag} step 1: ground friction |H| (N/m)", abs(c["rt"][res.pair_mask(0, br, GROUND)][0]),
                   abs(ref["H"]), TOL_STEP1, note=f"H/G = {abs(ref['H'] / ref['G']):.4f} < mu: rolling")
            k = int(np.argmin(np.abs(t - T_ACC)))
            ck.rel(f"{tag} bottom disk 2x/t^2 at t = {t[k]:.3f} s (m/s2)", 2 * res.X[k, br - 1, 0] / t[k] ** 2,
                   ref["xdd"], TOL_ACC, note="initial acceleration")
            ck.rel(f"{tag} top disk -2y/t^2 at t = {t[k]:.3f} s (m/s2)", -2 * res.X[k, tp - 1, 1] / t[k] ** 2,
                   -ref["aT"], TOL_ACC)
            k = int(np.argmin(np.abs(t - COLLAPSE_T)))
            ck.at_least(f"{tag} top disk drop at t = {t[k]:.2f} s / R", -res.X[k, tp - 1, 1] / r, COLLAPSE_DROP)
            # the bottom disks roll without slipping on the ground while the top slides on them
            k5 = int(np.argmin(np.abs(t - 0.5)))
            slip = np.abs(res.X[:k5, br - 1, 0] + r * res.X[:k5, br - 1, 2]).max()
            ck.at_most(f"{tag} bottom disk slip on the ground, t <= 0.5 s (m)", slip, 1e-9)
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
