#!/usr/bin/python3
"""Check the tilting_table run: the table angle at which each block starts to move
(README.md).

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

TOL_BRIEF = 0.5           # deg: onset angle vs alpha_c (the project's requirement)
TOL_ONSET = 0.01          # deg: onset angle vs alpha_c + detection lag, and static onset vs alpha_c
DELTA_SLIP = 1.0e-8       # m: relative slip that marks the start of sliding
DELTA_ROT = 1.0e-8        # rad: relative rotation that marks the start of tipping
T_REF = 0.3               # s: motion is measured from this time (after the spin ramp, before onset)
TOL_REST = 1.0e-8         # m, rad: relative motion of the block before alpha_c


def lag_angle(kind, b, H, mu, alpha_c, omega, g, delta, dt=1.0e-6):
    """Table angle beyond alpha_c at which the motion reaches delta, for a table turning
    at omega: slide, s'' = g (sin a - mu cos a); tip, I_P phi'' = m g (H/2 sin(phi + a)
    - b/2 cos(phi + a)), with a = alpha_c + omega tau (table frame; centrifugal and
    Coriolis terms are below 1e-5 g here and neglected)."""
    ip = (b * b + H * H) / 3.0
    x = v = tau = 0.0
    while x < delta:
        a = alpha_c + omega * tau
        if kind == "slide":
            acc = g * (math.sin(a) - mu * math.cos(a))
        else:
            acc = g * (0.5 * H * math.sin(x + a) - 0.5 * b * math.cos(x + a)) / ip
        v += acc * dt
        x += v * dt
        tau += dt
    return omega * tau


def main():
    res = pt.Results(pt.run_dir_from_argv(HERE))
    g = gen.G
    t = res.time
    ck = pt.Checker("tilting_table")
    for k, (b, H, law, alpha_c, kind) in enumerate(gen.SCENES):
        mu = gen.LAWS[law][0]
        tb, bl = 2 * k + 1, 2 * k + 2
        tag = f"table {k + 1} {b}x{H} mu={mu} ({kind}):"
        pos = res.position
        al = pos[:, tb - 1, 2]                                  # table angle
        rel = pos[:, bl - 1, :2] - pos[:, tb - 1, :2]
        tang = np.cos(al) * rel[:, 0] + np.sin(al) * rel[:, 1]  # block centre along the table
        rrot = pos[:, bl - 1, 2] - al                           # block rotation relative to the table
        i0 = int(np.argmin(np.abs(t - T_REF)))
        motion = np.abs(tang - tang[i0]) if kind == "slide" else np.abs(rrot - rrot[i0])
        delta = DELTA_SLIP if kind == "slide" else DELTA_ROT
        ck.close(f"{tag} alpha_c (deg)", math.degrees(alpha_c),
                 math.degrees(math.atan(mu if kind == "slide" else b / H)), 1e-12,
                 note="tan = mu" if kind == "slide" else "tan = b/H")
        before = (al < alpha_c) & (t >= T_REF)
        ck.at_most(f"{tag} relative motion before alpha_c (m or rad)", motion[before].max(), TOL_REST)
        # static onset: friction saturated (slide) or the uphill contact unloaded (tip)
        static = None
        for i in range(i0, len(t)):
            c = res.contacts[i]
            m = res.pair_mask(i, bl, tb)
            if kind == "slide":
                F = res.force_on(i, bl)
                n = np.array([-math.sin(al[i]), math.cos(al[i])])
                d = np.array([math.cos(al[i]), math.sin(al[i])])
                if abs(F @ d) >= mu * (F @ n) * (1.0 - 1e-9):
                    static = i
                    break
            else:
                pts = c["point"][m]
                up = np.argmax(pts @ np.array([math.cos(al[i]), math.sin(al[i])]))
                if c["rn"][m][up] <= 0.0 or np.sum(m) < 2:
                    static = i
                    break
        # the step's detection angle is the table angle at mid-step
        a_static = 0.5 * (al[static] + al[static - 1])
        what = "friction saturated" if kind == "slide" else "uphill corner unloaded"
        ck.close(f"{tag} {what} at alpha (deg)", math.degrees(a_static), math.degrees(alpha_c),
                 TOL_ONSET, note=f"table turns {math.degrees(gen.OMEGA * res.h):.4f} deg per step")
        # kinematic onset: first step where the block has moved by delta on the table
        moved = np.nonzero((motion > delta) & (t >= T_REF))[0]
        a_kin = al[moved[0]]
        lag = lag_angle(kind, b, H, mu, alpha_c, gen.OMEGA, g, delta)
        ck.close(f"{tag} onset of motion alpha (deg)", math.degrees(a_kin), math.degrees(alpha_c),
                 TOL_BRIEF, note="tan(alpha_c) = " + ("mu" if kind == "slide" else "b/H"))
        ck.close(f"{tag} onset alpha vs alpha_c + lag (deg)", math.degrees(a_kin),
                 math.degrees(alpha_c + lag), TOL_ONSET,
                 note=f"lag {math.degrees(lag):.4f} deg to move by {delta:g}")
        ck.at_least(f"{tag} motion at the end (m or rad)", motion[-1], 1.0e-3)
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
