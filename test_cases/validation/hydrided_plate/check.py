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
   (to 1e-9).

    check.py WEAK_RUN_DIR STRONG_RUN_DIR
"""
import json
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[2] / "tools" / "hydride"))
import hydride_post as post  # noqa: E402

# Measured (Fracas, this deck): HY_HY share 0 % weak / 26 % strong, HY_MA share 76 % weak
# / 26 % strong, balance error 4e-4 and 3e-4 of the work. The margin asks for a clear
# difference (the 5-seed campaign of doc/hydrided_zircaloy.md gives the spread); the
# audit tolerance covers the NLGS tolerance (1e-4) and the Newton tolerance of the J2
# matrix accumulated over 300 steps.
MARGIN = 0.10
AUDIT_TOL = 2e-3


def main(weak_dir, strong_dir):
    failures = []
    res = {}
    for name, d in (("weak", weak_dir), ("strong", strong_dir)):
        s = post.summary(d, deck_dir=HERE / name)      # outputs in d, hydrides.json with the deck
        res[name] = s
        e = s["energies"]
        c = s["crack"]
        print(f"{name}: shares " + ", ".join(f"{f} {100 * c['shares'][f]:.1f} %" for f in post.FAMILY_LABEL)
              + f"; ligament left {c['ligament'] * 1e6:.2f} µm; balance error {e['relative_balance_error']:.2e} "
              f"of the work; damage per family sum error {e['damage_family_sum_error']:.1e}")
        if e["relative_balance_error"] > AUDIT_TOL:
            failures.append(f"{name}: energy balance error {e['relative_balance_error']:.2e} > {AUDIT_TOL}")
        if e["damage_family_sum_error"] > 1e-9:
            failures.append(f"{name}: damage per family does not add up ({e['damage_family_sum_error']:.1e})")
    dh = res["strong"]["crack"]["shares"]["HY_HY"] - res["weak"]["crack"]["shares"]["HY_HY"]
    di = res["weak"]["crack"]["shares"]["HY_MA"] - res["strong"]["crack"]["shares"]["HY_MA"]
    print(f"through hydrides: strong - weak = {100 * dh:+.1f} points; along interfaces: weak - strong = "
          f"{100 * di:+.1f} points (needed: > {100 * MARGIN:.0f})")
    if dh < MARGIN:
        failures.append(f"share through hydrides, strong - weak = {dh:.3f} < {MARGIN}")
    if di < MARGIN:
        failures.append(f"share along interfaces, weak - strong = {di:.3f} < {MARGIN}")
    for f in failures:
        print("FAIL: " + f)
    print("OK" if not failures else f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2]))
