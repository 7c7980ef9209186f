#!/usr/bin/python3
"""Check a czm_cyclic run: secant unloading with beta frozen, damage resumed on reloading
past the previous maximum opening (README.md).

usage: check.py RUN_DIR LAW     (LAW in mac mp3)
Prints one line per quantity and exits 1 if any check fails.
"""
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
import gen          # noqa: E402
from fracas_tools import valtools     # noqa: E402
from fracas_tools.results import Results  # noqa: E402
from fracas_tools import czm_closed_forms as cf  # noqa: E402  (independent closed forms, czm.md 1.2)

LOWER, UPPER = 1, 2
ENERGY_TOL = 1e-2


def main():
    if len(sys.argv) < 3 or sys.argv[2] not in gen.LAWS:
        raise SystemExit(f"usage: check.py RUN_DIR LAW ({' '.join(gen.LAWS)})")
    name = sys.argv[2]
    # References from the closed forms of czm.md 1.2 (not the solver's update mirrored)
    law = cf.Closed.of(gen.LAWS[name][1])
    run = Results(sys.argv[1], bodies=False)
    ck = valtools.Checker(f"czm_cyclic/{name} ({gen.LAWS[name][0]}, cohesive_damage {run.cohesive_damage})")
    segs, _ = gen.schedule(name)
    pr = run.pair(UPPER, LOWER)
    sig = -pr.total("rn") / gen.GLUED
    un = pr.mean("un")
    beta = pr.mean("beta")
    smax, dpk, k, c = law.peak(1), law.d_peak(1), law.k, law.cn
    ns = len(sig)

    ck.true("run complete, a snapshot per step", run.complete == 1 and ns == sum(n for n, _ in segs),
            ours=f"{ns} snapshots")
    ck.true("NLGS converged at every step", bool(np.all(run.series["converged"] == 1)))
    ck.true("two glued points of L = 0.5 m in every step",
            bool(np.all(pr.present) and np.all(pr.L == 0.5 * gen.GLUED)))

    # the turning points of the opening, as imposed
    ends = np.cumsum([n for n, _ in segs]) - 1
    turns = un[ends] / dpk
    ck.at_most("max |opening at the turns / d_peak - target|", np.abs(turns - np.array(gen.TURNS)).max(),
               1.0 * gen.STEP, note="within one step (u = gap + h v/2)")

    # 1. beta is a function of the largest opening so far (irreversible, resumed)
    umax = np.maximum.accumulate(un)
    ck.at_most("max |beta - beta_closed(max opening so far)|", np.abs(beta - law.beta(umax, 1)).max(), 1e-12)
    growth = np.diff(beta).max()
    ck.at_most("largest increase of beta between steps", max(0.0, growth), 0.0, note="never heals")

    # 2. secant: below the previous maximum beta is frozen and sigma = beta^k c u, u the
    # end jump (LMGC90's explicit update) or the mean of the step's start and end jumps
    # (damage within the step: midpoint springs, doc/czm.md 3.2)
    implicit = run.cohesive_damage == "implicit"
    if implicit:
        uu = 0.5 * (np.concatenate([[0.0], un[:-1]]) + un)
    else:
        uu = un
    prev_max = np.concatenate([[0.0], umax[:-1]])
    below = un <= prev_max
    below[0] = False
    frozen = np.abs(np.diff(beta))[below[1:]]
    ck.at_most("max |beta change| while below the previous maximum", frozen.max(), 0.0,
               note=f"{below.sum()} steps unloading or reloading")
    sec = np.abs(sig - beta ** k * c * uu)[below].max() / smax
    ck.at_most("secant: max |sigma - beta^k c u| / sigma_max", sec, 1e-9)
    for j, (lo, hi) in enumerate(((ends[0], ends[1]), (ends[2], ends[3]))):
        seg = slice(lo + 1, hi + 1)
        slope = sig[seg] / uu[seg]
        ref = law.beta(un[lo], 1) ** k * c
        ck.rel(f"unloading {j + 1}: slope sigma/u = beta(u_turn)^k c (Pa/m)", slope.mean(), ref, 1e-9)
        ck.at_most(f"unloading {j + 1}: slope spread / slope", (slope.max() - slope.min()) / ref, 1e-9)
        ck.at_most(f"unloading {j + 1}: sigma at u -> 0 extrapolates to 0 (Pa)",
                   abs(np.polyfit(uu[seg], sig[seg], 1)[1]), 1e-6 * smax)

    # 3. reloading past the maximum: the monotonic curve again (explicit: one step of lag)
    closed = law.sigma(un, 1)
    if not implicit:
        lagged = law.beta(prev_max, 1) ** k * c * un            # frozen beta of the step
        ck.at_most("reported sigma = beta_prev^k c u at every step / sigma_max",
                   np.abs(sig - lagged).max() / smax, 1e-9)
    for j, lo in enumerate((ends[1], ends[3])):
        i0 = lo + 1 + int(np.argmax(un[lo + 1:] > umax[lo]))   # first step past the old maximum
        ck.true(f"reload {j + 1}: damage resumes at the old maximum {umax[lo] / dpk:.3f} d_peak",
                beta[i0] < beta[i0 - 1] and np.all(beta[lo:i0] == beta[lo]),
                ours=f"u = {un[i0] / dpk:.3f} d_peak")
        seg = slice(i0 + 1, (ends[2] if j == 0 else ends[4]) + 1)
        ck.at_most(f"reload {j + 1} past the maximum: max |sigma - sigma_closed(u)| / sigma_max",
                   np.abs(sig[seg] - closed[seg]).max() / smax, 4.0 * gen.STEP * (1 + k),
                   note="one-step lag, (1+k) 4 du/d_peak")

    # 4. energies: the loops add only the O(h) dissipation of the implicit spring
    dmg = run.series["damage_dissipated"]
    du = np.diff(np.concatenate([[0.0], un]))
    for j, (lo, hi) in enumerate(((ends[0], ends[2]), (ends[2], ends[4]))):
        i_back = lo + 1 + int(np.argmax(un[lo + 1:] > umax[lo]))   # back at the old maximum
        seg = slice(lo + 1, i_back)
        kb = beta[lo] ** k * c * gen.GLUED
        bound = 0.5 * kb * (np.sum(du[seg] ** 2) + np.sum(un[seg] * np.abs(np.diff(du[lo:i_back]))))
        ck.at_most(f"loop {j + 1}: |damage_dissipated change| / (G L)", abs(dmg[i_back - 1] - dmg[lo]) / (law.fracture_energy(1) * gen.GLUED),
                   1.02 * bound / (law.fracture_energy(1) * gen.GLUED),
                   note="(kb/2)(sum du^2 + sum u |d du|), O(h)")
    ref = law.damage(umax[-1], 1) * gen.GLUED
    GL = law.fracture_energy(1) * gen.GLUED
    ck.close("damage_dissipated at the end = monotonic closed form at max u", dmg[-1], ref, ENERGY_TOL * GL,
             note="tolerance 1 % of G L")
    ck.close("cohesive_energy at the end = (L/2) beta^k c u^2", run.series["cohesive_energy"][-1],
             0.5 * beta[-1] ** k * c * un[-1] ** 2 * gen.GLUED, 1e-9 * ref)
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
