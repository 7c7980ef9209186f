#!/usr/bin/python3
"""The one Python implementation of the cohesive laws (fracas_tools.cohesive.Law) against
the solver's own output, for every cohesive law the solver runs (README.md).

usage: mirror.py FRACAS OUT_DIR [LAW ...]
For each law: writes a driven-pair deck into OUT_DIR/<law>, runs FRACAS on it with the
damage solved within the step (the default) and with LMGC90's explicit update, and
compares, at every step and contact point, the solver's damage beta, reactions and
energies with Law evaluated on the solver's own jumps. Prints one line per quantity and
exits 1 if any differs by more than its tolerance (round-off): a drift of either the
Fortran laws (modules/behaviours/fracas_czm.f90) or their Python mirror is red.
"""
import subprocess
import sys
from pathlib import Path

import numpy as np

from fracas_tools import Case
from fracas_tools.checks import Checker
from fracas_tools.cohesive import Law
from fracas_tools.results import Results

sys.dont_write_bytecode = True

DT = 1.0e-4              # time step (s)
STEPS = 200              # steps of the driven path
SLIP = 0.5               # ut / un along the path: mixity m = 0.2, both modes' parameters count
# Opening velocity factor against the step number: open, close back a little (secant
# unloading, beta frozen), open again past full separation. (No step of the path has a
# vanishing stretch: the turning step closes by half a step's opening. With damage solved
# within the step, a step that damages while the springs hardly stretch has an
# ill-conditioned traction factor, work / stretch with both ~0: a 1e-5 disagreement
# measured on TH_CZM with a turn of zero motion.)
PATH = [(0, 1.0), (100, 1.0), (101, -2.0), (110, -2.0), (111, 1.0), (STEPS + 1, 1.0)]

MAL = dict(cn=1.0e11, ct=5.0e10, s1=1.0e6, s2=2.0e6, G1=40.0, G2=100.0)
# Every cohesive law the solver runs (io/read_tact_behav.f90, solver flag), parameters of
# test_cases/validation/czm_mode_I (MAC_CZM viscous here, MP3 with cn != ct).
LAWS = {
    "IQS_MAC_CZM": Law.mac(cn=1.0e10, ct=1.0e11, b=0.0, w=40.0),
    "MAC_CZM": Law.mac(cn=1.0e10, ct=1.0e11, b=4.0e-3, w=40.0),
    "MP3_CZM": Law.mp3(cn=1.0e11, ct=5.0e10, smax=1.0e6, w=40.0),
    "MAL_CZM": Law.mal(**MAL),
    "IQS_MAL_CZM": Law.mal(**MAL),
    "TH_CZM": Law.th(**MAL, dp1=2.0e-5, dp2=6.0e-5),
    "IQS_TH_CZM": Law.th(**MAL, dp1=2.0e-5, dp2=6.0e-5),
    "EXPO_CZM": Law.expo(**MAL, eta=1.0e-4),
    "IQS_EXPO_CZM": Law.expo(**MAL, eta=1.0e-4),
    "ABP_CZM": Law.abp(**MAL, du1=6.0e-5, du2=1.5e-4, phi=0.5),
    "IQS_ABP_CZM": Law.abp(**MAL, du1=6.0e-5, du2=1.5e-4, phi=0.5),
}
# Tolerances: the same arithmetic in Fortran and Python, in double precision.
BETA_TOL = 1.0e-12       # |beta - Law.update(beta_prev, ut, un, h)|
FORCE_TOL = 1.0e-9       # reaction error / peak reaction
ENERGY_TOL = 1.0e-9      # energy error / (fracture energy x glued length)


def build(name, law):
    """Two 1 m x 1 m POLYG blocks glued along y = 0.5 (two contact points of 0.5 m),
    every dof driven: the lower held, the upper moved along (SLIP, 1) so that the jump
    goes to 1.2 x full separation (MAC: 10 x the peak opening) in STEPS steps, with a
    partial closing on the way (PATH). Frictionless: the reactions are the law's."""
    m = SLIP ** 2 / (1.0 + SLIP ** 2)
    d_peak = (1.0 - m) * law.d_peak(1) + m * law.d_peak(2)
    d_max = 10.0 * d_peak if law.family == "MAC" else 1.2 * max(law.d_end(1), law.d_end(2))
    v = d_max / (0.9 * STEPS * DT) / np.hypot(SLIP, 1.0)        # net opening: 90 % of the steps
    case = Case(gravity=(0.0, 0.0))
    case.add_material("STONE", density=2000.0)
    law.add_to(case, "czm01", name, 0.0)
    case.add_see("POLYG", "BLEUx", "POLYG", "BLEUx", "czm01", 0.01)
    case.add_polygon([(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)], "STONE").fix()
    upper = case.add_polygon([(-0.5, 0.5), (0.5, 0.5), (0.5, 1.5), (-0.5, 1.5)], "STONE")
    upper.impose_evolution(1, "vlocy", "vx.dat", data=[(k * DT, SLIP * v * s) for k, s in PATH])
    upper.impose_evolution(2, "vlocy", "vy.dat", data=[(k * DT, v * s) for k, s in PATH])
    upper.impose_velocity(3)
    case.run.set(time_step=DT, number_of_steps=STEPS, theta=0.5, nlgs_check="Quad",
                 nlgs_tolerance=1e-6, output_hdf5_every=1, output_dof_every=0,
                 output_vtk_every=0, progress_every=0)
    return case


def compare(ck, name, law, run, explicit):
    """One run against Law, step by step, on the solver's jumps."""
    p = run.pair(2, 1)
    ns, npts = p.un.shape
    ck.true(f"{name}: two glued points at every step", npts == 2 and bool(np.all(p.present)),
            ours=f"{npts} points")
    h = run.h
    L, ut, un, beta = p.L, p.ut, p.un, p.beta
    beta0 = np.vstack([np.ones((1, npts)), beta[:-1]])
    u0t = np.vstack([np.zeros((1, npts)), ut[:-1]])
    u0n = np.vstack([np.zeros((1, npts)), un[:-1]])
    mirror = np.vectorize(lambda b, t, n: law.update(b, t, n, h))(beta0, ut, un)
    ck.at_most(f"{name}: max |beta - Law.update(beta_prev, ut, un, h)|", np.abs(beta - mirror).max(), BETA_TOL)
    ck.true(f"{name}: the path damages the interface (beta_end < 0.5)", float(beta[-1].max()) < 0.5,
            ours=f"beta_end {beta[-1].max():.3g}")
    # reactions (forces per point): -L f C u, u the end jump (explicit: f = beta_prev^k)
    # or the step's mean jump (within the step: f = Law.step_factor)
    if explicit:
        f = beta0 ** law.k
        jt, jn = ut, un
    else:
        f = np.vectorize(lambda b0, b1, a, b, c, d: law.step_factor(b0, b1, (a, b), (c, d), h))(
            beta0, beta, u0t, u0n, ut, un)
        jt, jn = 0.5 * (u0t + ut), 0.5 * (u0n + un)
    peak = np.abs(p.rn).max()
    ck.at_most(f"{name}: max |rn + L f cn un| / peak", np.abs(p.rn + L * f * law.cn * jn).max() / peak, FORCE_TOL)
    ck.at_most(f"{name}: max |rt + L f ct ut| / peak", np.abs(p.rt + L * f * law.ct * jt).max() / peak, FORCE_TOL)
    # energies (J/m): stored at the end of each step, released by damage per step
    scale = max(law.fracture_energy(1), law.fracture_energy(2)) * float(L[0].sum())
    stored = (L * np.vectorize(law.stored_energy)(beta, ut, un)).sum(axis=1)
    ck.at_most(f"{name}: max |cohesive_energy - sum L Law.stored_energy| / (G L)",
               np.abs(run.series["cohesive_energy"][:ns] - stored).max() / scale, ENERGY_TOL)
    if explicit:     # LMGC90's update: the drop of the stored energy when beta falls
        step = L * (np.vectorize(law.stored_energy)(beta0, ut, un) - np.vectorize(law.stored_energy)(beta, ut, un))
    else:            # the law's dissipation D(beta1) - D(beta0) (+ viscous part)
        step = L * np.vectorize(lambda b0, b1, t, n: law.step_dissipation(b0, b1, t, n, h))(beta0, beta, ut, un)
    released = np.cumsum(step.sum(axis=1))
    ck.at_most(f"{name}: max |damage_dissipated - sum of Law's step releases| / (G L)",
               np.abs(run.series["damage_dissipated"][:ns] - released).max() / scale, ENERGY_TOL,
               note=f"total {released[-1]:.6g} J/m")


def main():
    if len(sys.argv) < 3:
        raise SystemExit(__doc__)
    fracas, out = sys.argv[1], Path(sys.argv[2])
    names = sys.argv[3:] or list(LAWS)
    ck = Checker("czm_law_mirror (fracas_tools.cohesive.Law against the solver)")
    for name in names:
        law = LAWS[name]
        deck = out / name
        build(name, law).write(deck)
        for scheme in ("implicit", "explicit"):
            run_dir = out / f"{name}_{scheme}"
            cmd = [fracas, "-q", "--overwrite", "--set", f"cohesive_damage={scheme}", "--output", str(run_dir), str(deck)]
            r = subprocess.run(cmd, capture_output=True, text=True)
            if r.returncode != 0:
                ck.true(f"{name} ({scheme}): fracas ran", False, ours=f"exit {r.returncode}: {r.stderr.strip()[:200]}")
                continue
            compare(ck, f"{name} ({scheme})", law, Results(run_dir, bodies=False), scheme == "explicit")
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
