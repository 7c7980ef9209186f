#!/usr/bin/python3
"""Check the czm_rate run: the peak stress of the viscous MAC law (b > 0) grows with the
opening rate as the damage law b beta' = -(w - beta Y)^- says (README.md).

usage: check.py RUN_DIR
Prints one line per quantity and exits 1 if any check fails.
"""
import math
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
import gen          # noqa: E402
from fracas_tools import valtools     # noqa: E402
from fracas_tools.cohesive import mac_rate_curve  # noqa: E402
from fracas_tools.results import Results  # noqa: E402

_trapz = getattr(np, "trapezoid", None) or np.trapz   # numpy 2 renamed trapz

PEAK_TOL = 5e-3
ENERGY_TOL = 1e-2


def replica(law, v, h, n):
    """The solver's discrete scheme along the imposed opening: jump u_k = v (k + 1/2) h
    (gap at the detection configuration + h v), beta frozen during step k (stress
    beta_{k-1}^2 c u_k), then the implicit Euler update. Returns u, beta, sigma (n,)."""
    u = v * (np.arange(1, n + 1) + 0.5) * h
    beta = np.empty(n)
    sig = np.empty(n)
    b = 1.0
    for k in range(n):
        sig[k] = b * b * law.cn * u[k]
        b = law.update(b, 0.0, u[k], h)
        beta[k] = b
    return u, beta, sig


def continuous(law, v, t_end):
    """b beta' = -(w - beta c u^2)^- along u = v t (RK4, 200000 steps): the peak stress,
    the opening at the peak, and the damage energy (work - stored) at t_end."""
    t, u, beta, sig = mac_rate_curve(law, lambda s: v * s, t_end, n=200000)
    i = int(np.argmax(sig))
    work = _trapz(sig, u)
    stored = 0.5 * beta[-1] ** 2 * law.cn * u[-1] ** 2
    return sig[i], u[i], work - stored


def main():
    run = Results(valtools.run_dir_from_argv(HERE))
    ck = valtools.Checker("czm_rate (IQS_MAC_CZM, b > 0)")
    law, u0, h = gen.LAW, gen.U0, run.h
    s_rate_free = math.sqrt(law.cn * law.w)
    ck.true("run complete", run.complete == 1 and run.step[-1] == gen.STEPS, ours=f"{run.step[-1]} steps")
    ck.true("NLGS converged at every step", bool(np.all(run.series["converged"] == 1)))
    peaks, dmg_ref = [], 0.0
    for i, rate in enumerate(gen.RATES):
        lower, upper = 2 * i + 1, 2 * i + 2
        pr = run.pair(upper, lower)
        v = run.V[-1, upper - 1, 1]                    # the driven velocity as written in DRV_DOF
        ck.rel(f"R={rate}: driven velocity (m/s)", v, gen.VELOCITIES[i], 1e-7)
        sig = -pr.total("rn") / gen.GLUED
        un = pr.mean("un")
        beta = pr.mean("beta")
        u_r, beta_r, sig_r = replica(law, v, h, gen.STEPS)
        k = run.step - 1                               # snapshot steps -> replica index
        ck.at_most(f"R={rate}: max |un - v (k + 1/2) h| / u0", np.abs(un - u_r[k]).max() / u0, 1e-9)
        ck.at_most(f"R={rate}: max |beta - implicit Euler replica|", np.abs(beta - beta_r[k]).max(), 1e-9,
                   note="(b beta + h w)/(b + h Y)")
        ck.at_most(f"R={rate}: max |sigma - beta_prev^2 c u| / sqrt(c w)", np.abs(sig - sig_r[k]).max() / s_rate_free,
                   1e-9)
        pk_c, upk_c, dmg_c = continuous(law, v, gen.STEPS * h)
        pk = sig.max()
        ck.rel(f"R={rate}: peak (Pa) = continuous b beta' = -(w - beta Y)^-", pk, pk_c, PEAK_TOL,
               note=f"peak/sqrt(cw) = {pk_c / s_rate_free:.4f} at u = {upk_c / u0:.3f} u0")
        ck.close(f"R={rate}: opening at peak / u0", un[int(np.argmax(sig))] / u0, upk_c / u0,
                 0.01 * upk_c / u0 + gen.EVERY * v * h / u0, note="1 % + one snapshot interval")
        peaks.append(pk)
        dmg_ref += dmg_c * gen.GLUED
    ck.true("peak grows with the rate", bool(np.all(np.diff(peaks) > 0.0)),
            ours=" < ".join(f"{p / s_rate_free:.4f}" for p in peaks))
    ck.at_most("slowest rate: peak/sqrt(c w) - 1 (small)", peaks[0] / s_rate_free - 1.0, 0.05,
               note="tends to the rate-free peak sqrt(c w)")
    ck.true("fastest rate: rate effect >> tolerance", peaks[-1] / s_rate_free - 1.0 > 20.0 * PEAK_TOL,
            ours=f"{peaks[-1] / s_rate_free - 1.0:.3f}")
    ck.rel("damage_dissipated (J/m), 3 pairs = continuous work - stored", run.series["damage_dissipated"][-1],
           dmg_ref, ENERGY_TOL)
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
