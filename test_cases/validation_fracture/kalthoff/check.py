#!/usr/bin/python3
"""Check the Kalthoff-Winkler run (README.md): a crack leaves the notch tip at the
angle the experiments show (~70 degrees from the notch line), its tip speed stays
below the Rayleigh speed, the energy audit.

    check.py RUN_DIR [quick|full]
"""
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
import gen  # noqa: E402
from fracas_tools.fractools import (Checker, MeshRun, check_energy, crack_angle, run_dir_from_argv, tip_speed,  # noqa: E402
                       wave_speeds)  # noqa: E402


def main():
    variant = sys.argv[2] if len(sys.argv) > 2 else "quick"
    p = gen.params(variant)
    mr = MeshRun(run_dir_from_argv())
    ck = Checker(f"fracture kalthoff ({variant})")
    last = mr.state(-1)
    angle, n = crack_angle(last.cracks, gen.NOTCH_TIP, *gen.ANGLE_RANGE)
    # the crack born at the notch tip: its ends (crack_arms) per snapshot; a short
    # crack may also open elsewhere (at the notch mouth, under the impact)
    speed = tip_speed(mr, gen.NOTCH_TIP, gen.SPEED_WINDOW, 2.0 * p["lc"])
    ends = speed["ends"][-1]
    far = ends[np.argmax(np.hypot(*(ends - gen.NOTCH_TIP).T))] if len(ends) else np.array([np.nan, np.nan])
    grown = float(np.hypot(*(far - gen.NOTCH_TIP))) if len(ends) else 0.0
    ck.at_least("crack from the notch tip: tip distance (m)", grown, gen.ANGLE_RANGE[1],
                note=f"tip ({far[0] * 1e3:.1f}, {far[1] * 1e3:.1f}) mm")
    ck.close("crack angle from the notch line (deg)", angle, gen.ANGLE_REF, gen.ANGLE_TOL,
             note=f"fitted on {n} crack vertices {gen.ANGLE_RANGE[0] * 1e3:g}-{gen.ANGLE_RANGE[1] * 1e3:g} mm "
                  f"from the notch tip; experiments ~70")
    ck.info("crack from the notch tip seen first: t (us)", speed["t0"] * 1e6)
    cd, cs, cr = wave_speeds(gen.E, gen.NU, gen.RHO)
    ck.info("mean tip speed / c_R", speed["mean"] / cr, note=f"{speed['mean']:.0f} m/s, c_R = {cr:.0f} m/s")
    ck.at_most(f"max tip speed over {gen.SPEED_WINDOW * 1e6:.0f} us / c_R", speed["max"] / cr, 1.0,
               note=f"{speed['max']:.0f} m/s")
    check_energy(ck, mr.series)
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
