#!/usr/bin/python3
"""Checks the two runs of the small hydrided plate (README.md):

1. the paper's claim (Dubois, after Perales et al.: strong matrix/hydride bonding
   sends the crack through the hydrides, weak bonding along their boundaries): the
   macro-crack's share through hydrides (HY_HY) is larger with strong bonding than
   with weak bonding by at least MARGIN, and its share along matrix/hydride
   interfaces (HY_MA) larger with weak bonding by at least MARGIN;
2. the energy audit of each run: |balance_error| <= AUDIT_TOL x work of the drives
   (kinetic + elastic + plastic + stored cohesive + dissipated = work of the drives);
3. the damage energy per interface family adds up to the solver's damage_dissipated
   (to 1e-9);
4. magnitudes: the peak stress, the macro-crack's shares and the damage energy per
   family against the same deck run with half the time step (REFERENCE), within the
   measured change of the default scheme over that halving plus headroom (TOLERANCES).

    check.py WEAK_RUN_DIR STRONG_RUN_DIR
"""
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
from fracas_tools.scripts import load  # noqa: E402
post = load(HERE.parents[2] / "tools" / "hydride" / "hydride_post.py")
from fracas_tools.checks import Checker  # noqa: E402

# Measured (Fracas, this deck, after the merge of main's check pass): HY_HY share 0 % weak
# / 15 % strong, HY_MA share 76 % weak / 31 % strong, balance error 8e-4 of the work. The
# margin asks for a clear difference (the campaign of doc/hydrided_zircaloy.md gives the
# spread over seeds); the audit tolerance covers the NLGS tolerance (1e-4) and the Newton
# tolerance of the J2 matrix accumulated over 600 steps.
MARGIN = 0.10
AUDIT_TOL = 2e-3
FAMILY_SUM_TOL = 1e-9

# The tighter run: each deck with its run control (damage within the step, steps cut
# where a crack runs: crack_step_limit 0.25) but dt/2 = 5e-11 s and 1200 steps
# (test_cases/validation/hydrided_plate/dt_study.py; Fracas 2026-11-27, commit 5625aa7):
# peak stress (MPa), macro-crack shares, damage energy per family (J/m).
REFERENCE = {
    "weak": dict(peak=475.40, shares=dict(HY_HY=0.000, HY_MA=0.716, MA_MA=0.284),
                 damage=dict(HY_HY=1.796e-7, HY_MA=6.638e-5, MA_MA=2.170e-4)),
    "strong": dict(peak=708.50, shares=dict(HY_HY=0.143, HY_MA=0.451, MA_MA=0.406),
                   damage=dict(HY_HY=7.477e-5, HY_MA=2.323e-4, MA_MA=3.625e-4)),
}
# Measured at the deck's dt (1e-10 s: a wave crosses an element in about two steps)
# against REFERENCE: peak -0.28 % weak, -0.17 % strong; shares within 0.040; family
# energies within 0.053 of the run's total damage energy. At the former step (2e-10 s) the
# strong plate's peak was 1.0 % below (the bulk's time discretization: doc/czm.md 9).
# Tolerances: issue 17's 1 % on the peak; shares and energies with headroom over the
# scheme's own time-step change, so that a bug that moves a figure by more turns this red
# (LMGC90's explicit update, first order in dt, is about 20 % above on the peaks at a
# step of this size: doc/czm.md 3.2).
TOLERANCES = dict(peak=0.01, share=0.05, damage_of_total=0.10)


def main(weak_dir, strong_dir):
    ck = Checker("hydrided_plate (paper: strong bonding through hydrides, weak along interfaces)")
    res = {}
    for name, d in (("weak", weak_dir), ("strong", strong_dir)):
        s = post.summary(d, deck_dir=HERE / name)      # outputs in d, hydrides.json with the deck
        res[name] = s
        e, c = s["energies"], s["crack"]
        ck.info(f"{name}: ligament left (um)", 1e6 * c["ligament"])
        ck.at_most(f"{name}: |balance error| / work of the drives", e["relative_balance_error"], AUDIT_TOL,
                   "kinetic + elastic + plastic + stored cohesive + dissipated = work")
        ck.at_most(f"{name}: damage per family sum vs damage_dissipated", e["damage_family_sum_error"],
                   FAMILY_SUM_TOL, "relative")
        ref = REFERENCE[name]
        ck.rel(f"{name}: peak stress (MPa)", s["peak_stress"] / 1e6, ref["peak"], TOLERANCES["peak"], "dt/2 run")
        for f in post.FAMILY_LABEL:
            ck.close(f"{name}: macro-crack share {f}", c["shares"][f], ref["shares"][f], TOLERANCES["share"],
                     "dt/2 run")
            ck.close(f"{name}: damage energy {f} (J/m)", e["damage_per_family"][f], ref["damage"][f],
                     TOLERANCES["damage_of_total"] * sum(ref["damage"].values()), "dt/2 run; tol: of the total")
    dh = res["strong"]["crack"]["shares"]["HY_HY"] - res["weak"]["crack"]["shares"]["HY_HY"]
    di = res["weak"]["crack"]["shares"]["HY_MA"] - res["strong"]["crack"]["shares"]["HY_MA"]
    ck.at_least("share through hydrides: strong - weak", dh, MARGIN, "the paper's Fig. 1")
    ck.at_least("share along interfaces: weak - strong", di, MARGIN, "the paper's Fig. 2")
    return ck.finish()


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2]))
