#!/usr/bin/python3
"""Check a czm_mode_II run: cohesive shear, then Coulomb friction as beta -> 0 (README.md).

usage: check.py RUN_DIR LAW     (LAW in mac expo)
Prints one line per quantity and exits 1 if any check fails.
"""
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
import gen          # noqa: E402  (the deck parameters)
from fracas_tools import valtools     # noqa: E402
from fracas_tools.results import Results  # noqa: E402
from fracas_tools import czm_closed_forms as cf  # noqa: E402  (independent closed forms, czm.md 1.2)

_trapz = getattr(np, "trapezoid", None) or np.trapz   # numpy 2 renamed trapz

LOWER, UPPER = 1, 2
PEAK_TOL = 5e-3
ENERGY_TOL = 1e-2
CURVE_TOL = 1e-2
MODE = 2                    # sliding


def tau_closed(law, u, p):
    """Quasi-static shear traction: cohesive beta^k ct u plus friction mu (1 - beta) p."""
    b = law.beta(u, MODE)
    return b ** law.k * law.ct * u + gen.MU * (1.0 - b) * p


def main():
    if len(sys.argv) < 3 or sys.argv[2] not in gen.LAWS:
        raise SystemExit(f"usage: check.py RUN_DIR LAW ({' '.join(gen.LAWS)})")
    name = sys.argv[2]
    # References from the closed forms of czm.md 1.2 (not the solver's update mirrored)
    law = cf.Closed.of(gen.LAWS[name][1])
    run = Results(sys.argv[1])
    ck = valtools.Checker(f"czm_mode_II/{name} ({gen.LAWS[name][0]})")
    pr = run.pair(UPPER, LOWER)
    n1, n2, _ = gen.schedule(name)
    ns = len(run.step)
    tmax, dpk, k = law.peak(MODE), law.d_peak(MODE), law.k
    P = gen.PRELOAD * gen.GLUED

    ck.true("run complete, a snapshot per step", run.complete == 1 and ns == n1 + n2, ours=f"{ns} snapshots")
    ck.true("NLGS converged at every step", bool(np.all(run.series["converged"] == 1)))
    ck.true("two glued points in every step", bool(np.all(pr.present) and pr.L.shape[1] == 2))

    L = pr.total("L")                      # glued length: the overlap of the faces, 1 - slip
    ut = pr.mean("ut")
    beta = pr.mean("beta")
    tau = -pr.total("rt") / L              # shear traction (rt < 0 opposes the slip)
    p = P / L                              # pressure on the glued length
    ck.rel("sum rn = preload P (N/m)", pr.total("rn").min(), P, 1e-9)
    ck.rel("sum rn = preload P (N/m), max", pr.total("rn").max(), P, 1e-9)
    ck.at_most("max normal jump |un| (m): closed in compression", np.abs(pr.un).max(), 1e-12)
    # the faces overlap on 1 - s, s the slip at the detection configuration X + h V/2
    v0 = gen.schedule(name)[2][0][1]          # driven slip velocity at t = 0
    xm = np.concatenate([[0.5 * run.h * v0], run.X[:-1, UPPER - 1, 0] + 0.5 * run.h * run.V[:-1, UPPER - 1, 0]])
    ck.at_most("max |L - (1 - slip)/2| per point (m)", np.abs(pr.L - 0.5 * (gen.GLUED - xm[:, None])).max(),
               1e-12 * gen.GLUED, note="face overlap shrinks with the slip")

    # 1. the law per point: beta closed form; reported -rt = beta_prev^k ct ut L + mu (1 - beta_prev) rn
    ck.at_most("max |beta - beta_closed(ut)|", np.abs(pr.beta - law.beta(pr.ut, MODE)).max(), 1e-12)
    bp = np.vstack([np.ones((1, 2)), pr.beta[:-1]])
    pred = bp ** k * law.ct * pr.ut * pr.L + gen.MU * (1.0 - bp) * pr.rn
    if run.cohesive_damage == "explicit":
        # LMGC90's update: the spring at the end jump with the start-of-step beta
        ck.at_most("max |-rt - (beta_prev^k ct ut L + mu(1-beta_prev) rn)| / (tau_max L)",
                   np.abs(-pr.rt - pred).max() / (tmax * gen.GLUED), 1e-9,
                   note="cohesive part + Coulomb mu(1-beta)")
    else:
        # damage within the step: the step's mean traction (doc/czm.md 3.2), not this identity
        ck.info("max |-rt - (beta_prev^k ct ut L + mu(1-beta_prev) rn)| / (tau_max L)",
                np.abs(-pr.rt - pred).max() / (tmax * gen.GLUED), note="explicit update's identity")

    # 2. peak: cohesive peak; friction adds nothing at the peak (beta = 1 there)
    grid = np.linspace(0.0, 3.0 * dpk, 300001)
    peak_ref = tau_closed(law, grid, gen.PRELOAD).max()
    ck.rel("closed-form shear peak = cohesive peak", peak_ref, tmax, 1e-9)
    i_pk = int(np.argmax(tau))
    ck.rel("shear peak (Pa)", tau[i_pk], peak_ref, PEAK_TOL, note="a-priori lag bound 0.1 %")
    ck.close("slip at peak / d_peak", ut[i_pk] / dpk, 1.0, 2.0e-3)

    # 3. curve with one step of lag
    closed = tau_closed(law, ut, p)
    ck.at_most("max |tau - tau_closed(ut)| / tau_max", np.abs(tau - closed).max() / tmax, CURVE_TOL)

    # 4. friction plateau
    mu_p = gen.MU * p[-1]
    if law.family == "MAC":
        ck.rel("final shear = closed form (beta_end > 0)", tau[-1], closed[-1], 1e-3)
        ck.rel("final shear ~ mu p (MAC: beta_end = 2.5e-3)", tau[-1], mu_p, 5e-3)
    else:
        i_cut = int(np.argmax(ut >= law.d_end(MODE)))
        ck.at_most("max |tau / (mu p) - 1| after the cut-off", np.abs(tau[i_cut + 1:] / (gen.MU * p[i_cut + 1:]) - 1.0).max(),
                   1e-9, note="plain Coulomb")
        ck.true("broken = 1 from the cut-off on", bool(np.all(pr.broken[i_cut:] == 1) and np.all(pr.broken[:i_cut] == 0)),
                ours=f"step {run.step[i_cut]}")
        after = set(run.status_name(pr.status[i_cut + 1:]).ravel())
        ck.true("statuses after breaking: plain sliding", after <= {"slifw", "slibw"}, ours=",".join(sorted(after)))
    before = set(run.status_name(pr.status[beta > 0]).ravel())
    # (a point whose share of the preload is zero carries only cohesion: Cstck)
    ck.true("statuses while glued: cohesive", before <= {"Cslfw", "Cslbw", "Cstck"}, ours=",".join(sorted(before)))

    # 5. energies: damage = closed form; friction = int mu (1 - beta) P du
    s = run.series
    dmg_ref = law.damage(ut[-1], MODE) * L.mean()
    ck.rel("damage_dissipated (J/m) = closed form", s["damage_dissipated"][-1], dmg_ref, ENERGY_TOL)
    ck.rel("damage_dissipated (J/m) = G2 L (nominal)", s["damage_dissipated"][-1],
           law.nominal_energy(MODE) * L.mean(), ENERGY_TOL)
    fine = np.linspace(0.0, ut[-1], 400001)
    fr_ref = _trapz(gen.MU * (1.0 - law.beta(fine, MODE)) * P, fine)
    friction = s["dissipated"][-1] - s["damage_dissipated"][-1]
    ck.rel("friction work (J/m) = int mu (1 - beta) P du", friction, fr_ref, ENERGY_TOL)
    ck.at_most("|balance_error| / work_supports", np.abs(s["balance_error"]).max() / s["work_supports"][-1], 1e-9)
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
