#!/usr/bin/python3
"""Check the dynamic crack run (README.md): the crack starts at the notch tip, its tip
speed stays below the Rayleigh wave speed (reported as a fraction of c_R), branching
(reported; required in the full variant), the energy audit.

    check.py RUN_DIR [quick|full]
"""
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
import gen  # noqa: E402
from fracas_tools.fractools import Checker, MeshRun, check_energy, crack_arms, run_dir_from_argv, tip_speed, \
    wave_speeds  # noqa: E402


def main():
    variant = sys.argv[2] if len(sys.argv) > 2 else "quick"
    p = gen.VARIANTS[variant]
    mr = MeshRun(run_dir_from_argv())
    ck = Checker(f"fracture branching ({variant})")
    cd, cs, cr = wave_speeds(gen.E, gen.NU, gen.RHO)
    t, tips, lengths = mr.tip_history()
    started = np.flatnonzero(lengths > 0.0)
    ck.true("a crack grows", len(started) > 0 and lengths[-1] > 5.0 * p["lc"],
            ours=f"{lengths[-1] * 1e3:.1f} mm", ref="> 5 elements")
    origin = mr.state(-1).cracks["main_origin"]
    ck.at_most("crack origin: distance to the notch tip (m)", float(np.hypot(*(origin - gen.NOTCH_TIP))),
               2.0 * p["lc"], note=f"origin ({origin[0] * 1e3:.1f}, {origin[1] * 1e3:.1f}) mm")
    speed = tip_speed(mr, gen.NOTCH_TIP, gen.SPEED_WINDOW, gen.BRANCH_RADIUS)
    ck.info("t at crack initiation (us)", t[started[0]] * 1e6)
    ck.info("mean tip speed / c_R", speed["mean"] / cr,
            note=f"{speed['mean']:.0f} m/s from {speed['t0'] * 1e6:.0f} to {speed['t1'] * 1e6:.0f} us, "
                 f"c_R = {cr:.0f} m/s")
    ck.at_most(f"max tip speed over {gen.SPEED_WINDOW * 1e6:.0f} us / c_R", speed["max"] / cr, 1.0,
               note=f"{speed['max']:.0f} m/s; c_s = {cs:.0f}, c_d = {cd:.0f} m/s")
    arms = crack_arms(mr.state(-1).cracks, gen.NOTCH_TIP, radius=gen.BRANCH_RADIUS)
    note = "; ".join(f"({a[0] * 1e3:.1f}, {a[1] * 1e3:.1f})" for a in arms) + " mm"
    ck.at_least("crack arms beyond the branching radius", len(arms), 2, note=note)
    for i in range(len(mr.snapshot_names)):
        s = mr.state(i)
        if s.cracks is not None and len(crack_arms(s.cracks, gen.NOTCH_TIP, radius=gen.BRANCH_RADIUS)) >= 2:
            ck.info("first snapshot with two arms: t (us)", s.time * 1e6,
                    note=f"main tip then at x = {tips[i][0] * 1e3:.1f} mm")
            break
    check_energy(ck, mr.series)
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
