#!/usr/bin/python3
"""Check a newton_cradle run against the NSCD impact answers (see README.md).

usage: check.py RUN_DIR [VARIANT]   VARIANT: touching (default), sequential, inelastic
Prints one line per quantity and exits 1 if any check fails.
"""
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
import gen          # noqa: E402  (the deck parameters)
from fracas_tools import valtools     # noqa: E402


def expected_velocities(variant):
    n, v = gen.N, gen.V
    if variant == "touching":          # simultaneous impact, Moreau's law, e = 1
        return np.array([-(n - 2) / n * v] + [2.0 * v / n] * (n - 1))
    if variant == "inelastic":         # simultaneous impact, e = 0
        return np.full(n, v / n)
    return np.array([0.0] * (n - 1) + [v])   # sequential binary impacts, e = 1


def main():
    run_dir = valtools.run_dir_from_argv(HERE)
    variant = sys.argv[2] if len(sys.argv) > 2 else "touching"
    if variant not in gen.VARIANTS:
        raise SystemExit(f"unknown variant {variant!r}: {', '.join(gen.VARIANTS)}")
    _, e, gap, dt, _ = gen.VARIANTS[variant]
    res = valtools.Results(run_dir)
    n, v = gen.N, gen.V
    m = res.mass
    h = res.h
    ck = valtools.Checker(f"newton_cradle ({variant})")
    ref = expected_velocities(variant)
    vx = res.V[:, :, 0]

    if variant in ("touching", "inelastic"):
        # One LCP with all N-1 contacts: the NLGS error is about tol/(1 - rho_GS).
        rho = valtools.chain_gauss_seidel_rate(m)
        tol = max(gen.NLGS_TOL / (1.0 - rho), 1e-14)
        note = f"V tol/(1-rho_GS), rho_GS = {rho:.4f}"
        for k in range(n):
            ck.close(f"v{k + 1} after the impact step / V", vx[0, k] / v, ref[k] / v, tol, note=note)
        ck.close("max |v - ref| / V at the end of the run", np.abs(vx[-1] - ref).max() / v, 0.0,
                 tol, note="no further impact")
        # impulses of the impact step: contact k (disk k | disk k+1) transmits the
        # momentum that ends in disks k+1..N: m sum_{j>k} v_j  (rn is a force: times h)
        active = int(np.count_nonzero(res.contacts[0]["rn"] > 0.0))
        ck.close("contacts with rn > 0 in the impact step", active, n - 1, 0,
                 note="simultaneous")
        for k in range(1, n):
            imp = res.reaction_between(0, k, k + 1) * h
            ck.close(f"impulse {k}|{k + 1} / (m V)", imp / (m[k] * v),
                     m[k:] @ ref[k:] / (m[k] * v), n * tol, note="N tol")
    else:
        # Sequential binary impacts: each is a one-contact problem, solved exactly.
        tol = 1e-12
        for k in range(n):
            ck.close(f"v{k + 1} at the end / V", vx[-1, k] / v, ref[k] / v, tol, note="round-off")
        # disk k+1 starts at the end of the step of impact k; exact contact time k G/V.
        # Each impact is applied in the first step whose mid-step gap is <= 0 and the
        # struck disk covers only h/2 in it: a lag in [0, h) per impact, so the step
        # end is in [t* + h/2, t* + (k + 1/2) h).
        for k in range(1, n):
            moving = np.nonzero(vx[:, k] > 0.5 * v)[0]
            t_start = res.time[moving[0]] if len(moving) else np.inf
            t_star = k * gap / v
            ck.close(f"disk {k + 1} set moving (s)", t_start, t_star + 0.5 * (k + 1) * h,
                     0.5 * k * h + 1e-12, note=f"t* = {t_star:.6g}, window [h/2, (k+1/2)h)")

    # conservation laws over the whole run
    p = vx @ m
    ck.close("momentum / (m V), max deviation", np.abs(p - m[0] * v).max() / (m[0] * v), 0.0, 1e-12,
             note="round-off")
    ke0 = 0.5 * m[0] * v * v
    ke = res.series["kinetic_energy"]
    ke_ref = ke0 if e == 1.0 else ke0 / n
    ck.close("kinetic energy at the end / KE0", ke[-1] / ke0, ke_ref / ke0,
             max(2.0 * tol, 1e-12), note="e = 1: conserved; e = 0: 1/N")
    ck.close("NLGS converged in every step", float(res.series["converged"].min()), 1.0, 0.0)
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
