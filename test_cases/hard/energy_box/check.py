#!/usr/bin/python3
"""Check the energy_box run (README.md): an elastic (e = 1), frictionless gas of
polygons in a closed box keeps its mechanical energy; prints iterations and times.

usage: check.py [RUN_DIR]   (RUN_DIR holds OUTBOX/fracas.h5; default: this folder)
Prints one line per quantity and exits 1 if any check fails.
"""
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
import gen          # noqa: E402  (the deck parameters)
from fracas_tools import polytools as pt  # noqa: E402

TOL_E = 1.0e-6            # |E(t) - E(0)| / E(0) over the whole run
TOL_BALANCE = 1.0e-9      # |balance_error| / E(0)
FIRST_GRAIN = 5


def main():
    res = pt.Results(pt.run_dir_from_argv(HERE), contacts=False)
    s = res.series
    ck = pt.Checker("energy_box")
    E = s["kinetic_energy"] - s["work_gravity"]        # + E_potential(0) (constant)
    E0 = E[0]
    n = len(E)
    dev = np.abs(E - E0) / E0
    sw = s["sweeps"]
    unconv = np.nonzero(s["converged"] == 0)[0]
    mean_size = 2.0 * np.mean(res.radius[FIRST_GRAIN - 1:])
    ck.info("steps", n, note=f"{n * res.h:g} s")
    ck.info("sweeps, mean / max", sw.mean(), note=f"max {sw.max():.0f}")
    ck.info("steps not converged", len(unconv),
            note=(f"worst natural-map residual {s['residual_natural_map'][unconv].max():.1e}; "
                  f"energy jump there {np.max(np.abs(np.diff(E)[unconv - 1])) / E0:.1e} E0")
            if len(unconv) else "")
    ck.info("active contacts per step, mean", s["active_contacts"].mean())
    ck.info("max overlap / mean grain size", s["max_overlap"].max() / mean_size,
            note="RST acts once a contact is closed: overlaps of about v h")
    ck.info("NLGS solve time, whole run (s)", s["solve_time"].sum())
    ck.info("step time, whole run (s)", s["step_time"].sum())
    ck.at_most("max |E(t) - E(0)| / E(0)", dev.max(), TOL_E, note="E = KE + PE")
    ck.at_most("|E(T) - E(0)| / E(0)", dev[-1], TOL_E)
    ck.at_most("|E(T) - E(T/2)| / E(0) (drift over the 2nd half)", abs(E[-1] - E[n // 2]) / E0, TOL_E)
    ck.at_most("max |balance_error| / E(0)", np.abs(s["balance_error"]).max() / E0, TOL_BALANCE)
    ck.at_most("energy created by contacts, -dissipated(T) / E(0)", -s["dissipated"][-1] / E0, TOL_E)
    pos = res.position[:, FIRST_GRAIN - 1:, :2]
    inside = bool((pos > 0.0).all() and (pos < gen.BOX).all())
    ck.true("all grain centres inside the box at every snapshot", inside,
            ours=f"[{pos.min():.3f}, {pos.max():.3f}]")
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
