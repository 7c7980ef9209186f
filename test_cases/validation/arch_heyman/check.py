#!/usr/bin/python3
"""Check the arch_heyman run: the arch 5 % thicker than t_min = 0.1075 R stands, the
one 5 % thinner collapses with the 5-hinge mechanism of limit analysis (README.md).

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
from fracas_tools.scripts import load  # noqa: E402
arch_limit = load(HERE.parents[2] / "tools" / "validation_polygons" / "arch_limit.py")   # the reference

# "stands" and "collapses", numerically (README.md)
STAND_MAX_DISP = 1.0e-5       # x R: largest voussoir displacement over the run
STAND_MAX_V = 1.0e-6          # m/s: largest voussoir speed over the second half
COLLAPSE_T = 0.8              # s
COLLAPSE_DROP = 0.1           # x R: crown drop at COLLAPSE_T
HINGE_T = 0.2                 # s: time at which the hinges are read
HINGE_ROT = 1.0e-3            # rad: relative rotation that makes a joint a hinge
TOL_REL = 1.0e-6              # vertical support reaction (NLGS tolerance 1e-6)
TOL_THRUST = 1.0e-4           # relative margin on the admissible thrust range (8-digit deck)
# Published values (nscd_validation.md 2.6): Milankovitch's t_min/R = 0.1075 (radial joints,
# true self-weight; Makris & Alexakis 2013), given to 4 digits (+-5e-5), and the haunch
# hinge 54.50 deg from the crown (CCR 2011: 54.4963 deg).
PUBLISHED_TMIN = 0.1075
PUBLISHED_TMIN_TOL = 5.0e-5
PUBLISHED_HINGE_DEG = 54.5
N_FINE = 100                  # voussoirs for the limit analysis against the continuous value


def main():
    res = pt.Results(pt.run_dir_from_argv(HERE))
    g, N, R = gen.G, gen.N, gen.R
    ck = pt.Checker("arch_heyman")
    tmin = arch_limit.t_min(N, R, gen.MU)
    ref_hinges = arch_limit.hinges(N, R, gen.MU)
    ck.info("limit analysis: t_min/R, 20 quadrilateral voussoirs", tmin / R,
            note="0.1075 for N -> infinity (Milankovitch)")
    # The project's limit analysis against the published value: with many voussoirs it
    # must give Milankovitch's t_min to the digits published; with the deck's 20 it must
    # lie inside the deck's bracket (0.98 .. 1.02 x 0.1075), or the bracket tests nothing.
    ck.close(f"limit analysis: t_min/R with {N_FINE} voussoirs vs published 0.1075",
             arch_limit.t_min(N_FINE, R, gen.MU) / R, PUBLISHED_TMIN, PUBLISHED_TMIN_TOL,
             note="Milankovitch 1907 (Makris & Alexakis 2013), 4 digits")
    ck.true("limit analysis: t_min(20)/R inside the deck's bracket 0.98..1.02 x 0.1075",
            0.98 * PUBLISHED_TMIN < tmin / R < 1.02 * PUBLISHED_TMIN, ours=tmin / R)
    t = res.time
    for i, (centre, tr, color, expected) in enumerate(gen.ARCHES):
        b0 = gen.first_body(i)
        vous = slice(b0 - 1, b0 - 1 + N)
        thick = tr * R
        tag = f"arch {i + 1} t/R = {tr:.6f} ({thick / tmin:.3f} t_min):"
        X = res.X[:, vous, :]
        if expected == "stand":
            ck.at_most(f"{tag} max voussoir displacement / R", np.abs(X[:, :, :2]).max() / R,
                       STAND_MAX_DISP)
            half = len(t) // 2
            ck.at_most(f"{tag} max voussoir speed, 2nd half (m/s)",
                       np.abs(res.V[half:, vous, :2]).max(), STAND_MAX_V)
            # support reactions: the total vertical load is the weight (unique); the thrust
            # and the split of the vertical load between the supports are statically
            # indeterminate (fixed supports): the thrust must lie in the limit-analysis range
            weight = res.mass[vous].sum() * g
            left, right = b0 + N, b0 + N + 1
            others = range(b0, b0 + N)
            F_l = res.force_on(len(t) - 1, left, others)       # force of the arch on a support
            F_r = res.force_on(len(t) - 1, right, others)
            ck.rel(f"{tag} total vertical support load = weight (N/m)", -(F_l[1] + F_r[1]), weight, TOL_REL)
            ck.info(f"{tag} vertical loads left/right - 1", F_l[1] / F_r[1] - 1.0,
                    note="indeterminate; symmetric for a symmetric solution")
            hr = arch_limit.thrust_range(N, R, thick, gen.MU)
            rhog = gen.RHO * g
            H = -F_l[0]                                          # the arch pushes the left support outwards
            lo, hi = hr[0] * rhog, hr[1] * rhog
            ok = lo * (1.0 - TOL_THRUST) <= H <= hi * (1.0 + TOL_THRUST)
            ck.true(f"{tag} thrust H (N/m) in the admissible range", ok, ours=H,
                    note=f"limit analysis: [{lo:.4f}, {hi:.4f}] N/m, +-{TOL_THRUST:g} rel.")
            ck.info(f"{tag} (H - H_min) / H_min", (H - lo) / lo)
            ck.rel(f"{tag} thrusts on the two supports balance", F_r[0], H, TOL_REL)
        else:
            ck.true(f"{tag} no admissible thrust line (limit analysis)",
                    arch_limit.thrust_range(N, R, thick, gen.MU) is None)
            crown = [b0 - 1 + N // 2 - 1, b0 - 1 + N // 2]
            k = int(np.argmin(np.abs(t - COLLAPSE_T)))
            drop = -res.X[k, crown, 1].mean()
            ck.at_least(f"{tag} crown drop at t = {t[k]:.2f} s / R", drop / R, COLLAPSE_DROP)
            # hinges: joints whose two sides have turned relative to each other
            k = int(np.argmin(np.abs(t - HINGE_T)))
            rot = np.concatenate([[0.0], X[k, :, 2], [0.0]])    # supports do not turn
            rel = np.diff(rot)
            found = [j for j in range(N + 1) if abs(rel[j]) > HINGE_ROT]
            ck.true(f"{tag} hinge joints at t = {t[k]:.2f} s", found == list(ref_hinges),
                    ours=" ".join(map(str, found)),
                    note=f"limit analysis: {' '.join(map(str, ref_hinges))}; "
                         f"others turn < {np.max(np.abs(np.delete(rel, found))):.1e} rad")
            # the haunch hinges against the published angle: joint j is 180 j / N degrees
            # from the right springing; hinges can only form at joints, so within half a
            # joint spacing (4.5 deg for N = 20) of 54.5 deg from the crown
            haunch = [abs(90.0 - 180.0 * j / N) for j in found if j not in (0, N // 2, N)]
            ck.true(f"{tag} haunch hinges {PUBLISHED_HINGE_DEG} deg from the crown (published), "
                    f"within half a joint spacing", len(haunch) == 2 and
                    all(abs(a - PUBLISHED_HINGE_DEG) <= 90.0 / N for a in haunch),
                    ours=" ".join(f"{a:.1f}" for a in haunch), note=f"+-{90.0 / N:.1f} deg")
            # the side of each hinge: the loaded contact of the joint is at the extrados or intrados
            c = res.contacts[k]
            sides = []
            for j in found:
                # the two bodies on either side of joint j: right support (j = 0),
                # voussoirs j and j + 1 (1-based), left support (j = N)
                lower = b0 + N + 1 if j == 0 else b0 + j - 1
                upper = b0 + N if j == N else b0 + j
                a, bb = lower, upper
                m = res.pair_mask(k, a, bb) & (c["rn"] > 0.0)
                if not np.any(m):
                    sides.append("?")
                    continue
                r = np.hypot(*(c["point"][m] - np.array(centre)).T)
                rr = float(np.sum(r * c["rn"][m]) / np.sum(c["rn"][m]))
                sides.append("e" if rr > R else "i")
            ck.true(f"{tag} hinge sides (e: extrados, i: intrados)",
                    sides == [ref_hinges[j] for j in found], ours="".join(sides),
                    note=f"limit analysis: {''.join(ref_hinges[j] for j in found)}")
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
