#!/usr/bin/python3
"""Check the wedged_block run (README.md): bounded wall reactions whose resultant is the
weight, no energy gain, no blow-up; prints the iterations and times.

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

TOL_RESULTANT = 1.0e-6    # resultant of the wall reactions vs the weight (rel., settled)
TOL_ENERGY = 1.0e-6       # energy gain, relative to m g LIFT
BOUND_FACTOR = 3.0        # normal force per side <= 3 x the least force that can stop the wedge
SETTLED = 1000            # the last SETTLED steps must be at rest


def main():
    res = pt.Results(pt.run_dir_from_argv(HERE))
    s = res.series
    g, h = gen.G, res.h
    sb, cb = math.sin(gen.BETA), math.cos(gen.BETA)
    ck = pt.Checker("wedged_block")
    sw = s["sweeps"]
    unconv = np.nonzero(s["converged"] == 0)[0]
    ck.info("sweeps, step 1", sw[0])
    ck.info("sweeps, mean / max", sw.mean(), note=f"max {sw.max():.0f}")
    ck.info("steps not converged", len(unconv),
            note=(f"steps {unconv[0] + 1}..{unconv[-1] + 1}, worst natural-map residual "
                  f"{s['residual_natural_map'][unconv].max():.1e}") if len(unconv) else "")
    ck.info("NLGS solve time, whole run (s)", s["solve_time"].sum())
    ck.info("step time, whole run (s)", s["step_time"].sum())
    # energy: E = KE - work of gravity (E(0) = 0, at rest); never above its past minimum
    E = s["kinetic_energy"] - s["work_gravity"]
    scale = max(res.mass[3 * k + 2] for k in range(len(gen.SLOTS))) * g * gen.SLOTS[1][1]
    gain = np.max(E - np.minimum.accumulate(np.concatenate([[0.0], E]))[1:])
    ck.at_most("max E(t) - E(0) (J/m)", E.max(), TOL_ENERGY * scale, note="E = KE - W_gravity")
    ck.at_most("max energy gain after a minimum (J/m)", gain, TOL_ENERGY * scale,
               note=f"dissipated {s['dissipated'][-1]:.4f} J/m")
    ck.at_most("max |balance_error| (J/m)", np.abs(s["balance_error"]).max(), 1e-9 * scale)
    for k, (x0, lift, kind) in enumerate(gen.SLOTS):
        lw, rw, w = 3 * k + 1, 3 * k + 2, 3 * k + 3
        m = res.mass[w - 1]
        W = m * g
        n_min = W / (2.0 * (sb + gen.MU * cb))          # least normal force per side at rest
        v_imp = math.sqrt(2.0 * g * lift)
        n_stop = n_min + m * v_imp / (2.0 * h * (sb + gen.MU * cb))  # least to stop it in one step
        tag = f"wedge {k + 1} ({kind}):"
        n = len(res.time)
        side = np.array([[res.normal_force_between(i, w, lw), res.normal_force_between(i, w, rw)]
                         for i in range(n)])
        F = res.force_on(n - 1, w)
        ck.close(f"{tag} settled resultant R_x / W", F[0] / W, 0.0, TOL_RESULTANT)
        ck.rel(f"{tag} settled resultant R_y = W (N/m)", F[1], W, TOL_RESULTANT)
        ck.at_least(f"{tag} settled N per side / N_min (admissible >= 1)", side[-1].min() / n_min,
                    1.0 - TOL_RESULTANT, note="N_min = W / (2 (sin b + mu cos b))")
        ck.at_most(f"{tag} max N per side over the run / N_stop", side.max() / n_stop, BOUND_FACTOR,
                   note=f"N_stop = {n_stop / W:.2f} W (least force stopping it in one step)")
        ck.info(f"{tag} settled N per side / N_min", side[-1].max() / n_min)
        ck.at_most(f"{tag} max speed over the last {SETTLED} steps (m/s)",
                   np.abs(res.V[-SETTLED:, w - 1, :2]).max(), 1e-9)
        ck.close(f"{tag} final vertical displacement (m)", res.X[-1, w - 1, 1], -lift, 1e-6,
                 note="seated on the walls")
        ck.at_most(f"{tag} max |displacement change| over the last {SETTLED} steps (m)",
                   np.abs(res.X[-SETTLED:, w - 1, :] - res.X[-1, w - 1, :]).max(), 1e-9)
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
