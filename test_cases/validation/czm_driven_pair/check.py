#!/usr/bin/python3
"""Check the fully driven cohesive pair (README.md) against the closed form of its law.

usage: check.py RUN_DIR     (RUN_DIR holds OUTBOX/fracas.h5)
Prints one line per quantity and exits 1 if any check fails.
"""
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
ROOT = Path(__file__).resolve().parents[3]
from fracas_tools import czm_closed_forms as cf  # noqa: E402
from fracas_tools.results import Results  # noqa: E402

H, V, THETA = 1.0e-4, 1.0e-2, 0.5      # COMMAND.DAT, DRV_DOF.DAT
CN, W, L = 1.0e10, 40.0, 0.5           # TACT_BEHAV.DAT (IQS_MAC_CZM, b = 0); L: half the 1 m face
REL = 1e-10                            # round-off of the closed form
LAW = cf.Closed("MAC", cn=CN, ct=1.0e11, b=0.0, w=W)   # the closed forms of czm.md (fracas_tools)


def closed_form(nsteps):
    """Opening, beta at the end of each step and the normal reaction per point (force),
    as the law gives them when both sides are driven: un_k = (k + 1/2) h v (the gap at the
    detection configuration plus h v, the upper block starting at its imposed velocity),
    beta_k = min(beta_{k-1}, w / (cn un_k^2)), and the reaction of step k, computed with the
    beta of the step's start: rn_k / h = -L beta_{k-1}^2 cn un_k."""
    k = np.arange(1, nsteps + 1)
    un = (k + 0.5) * H * V
    beta = np.minimum.accumulate(LAW.beta(un, 1))          # min(1, w / (cn u^2)), irreversible
    beta_start = np.concatenate([[1.0], beta[:-1]])
    return un, beta, -L * beta_start**2 * CN * un


def main():
    run = Results(sys.argv[1])
    pair = run.pair(2, 1)
    un, beta, rn = closed_form(len(run.step))
    k = run.step - 1
    ok = True

    def check(name, got, want, tol):
        nonlocal ok
        err = np.max(np.abs(got - want) / np.maximum(np.abs(want), 1e-300))
        good = err <= tol
        ok &= good
        print(f"{'ok  ' if good else 'FAIL'} {name}: max relative error {err:.2e} (tolerance {tol:g})")

    npts = pair.un.shape[1]
    print(f"{'ok  ' if npts == 2 else 'FAIL'} contact points between the driven blocks: {npts} (expected 2)")
    ok &= npts == 2
    check("opening un", pair.un, un[k, None], REL)
    check("beta", pair.beta, beta[k, None], REL)
    check("normal reaction rn/h per point", pair.rn, rn[k, None], REL)
    # Energy released by damage up to the end: the work of the law's force
    # w (1 - u0^2 / (2 u^2)) minus what the springs still hold, w u0^2 / (2 u^2), per
    # unit length: w (1 - u0^2 / u^2), u0^2 = w / cn; two points of length L.
    # The step-by-step release is exact: at step k the springs (opening un_k) lose
    # 1/2 cn un_k^2 L (beta_{k-1}^2 - beta_k^2); the continuum value differs by O(h v / u0).
    s = run.series
    damage = s["damage_dissipated"][-1]
    u_end = un[-1]
    beta_start = np.concatenate([[1.0], beta[:-1]])
    damage_discrete = 2 * np.sum(0.5 * CN * un**2 * L * (beta_start**2 - beta**2))
    damage_closed = W * 2 * L * (1.0 - (W / CN) / u_end**2)
    check("damage released, step by step", np.array([damage]), np.array([damage_discrete]), REL)
    step_ratio = H * V / np.sqrt(W / CN)           # opening increment / u0 = 1.6 %
    check("damage released against the continuum law", np.array([damage]), np.array([damage_closed]), step_ratio)
    print("fully driven cohesive pair:", "passed" if ok else "FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
