#!/usr/bin/python3
"""Check the ENF run (README.md) against beam theory / LEFM in mode II: initial
compliance, the critical load at which the crack starts (unstable in displacement
control for a0 < 0.7 L), the energy the broken length cost; the energy audit.

    check.py RUN_DIR [quick|full]
"""
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import gen  # noqa: E402
from fractools import (Checker, MeshRun, check_energy, load_from_work, ramped_displacement,  # noqa: E402
                       run_dir_from_argv)

E, H, GC = gen.E, gen.H, gen.GC


def williams_chi(nu):
    g = E / (2.0 * (1.0 + nu))
    gamma = 1.18 * E / g
    return np.sqrt(E / (11.0 * g)) * (3.0 - 2.0 * (gamma / (1.0 + gamma)) ** 2)


def compliance(a, half_span):
    """ENF compliance (unit width), beam theory: (2 L^3 + 3 a^3) / (8 E H^3)."""
    return (2.0 * half_span ** 3 + 3.0 * a ** 3) / (8.0 * E * H ** 3)


def critical_load(a):
    """G_II = 9 P^2 a^2 / (16 E H^3) = G_c."""
    return 4.0 / (3.0 * a) * np.sqrt(E * H ** 3 * GC)


def main():
    variant = sys.argv[2] if len(sys.argv) > 2 else "quick"
    p = gen.params(variant)
    mr = MeshRun(run_dir_from_argv())
    ck = Checker(f"fracture enf ({variant})")
    s = mr.series
    t = s["time"]
    delta = ramped_displacement(t, p["t_ramp"], p["v"])     # the imposed mid-span deflection
    work = s["work_supports"]
    i, load = load_from_work(t, work, delta, 10e-6)
    ipk = int(np.argmax(load))
    p_peak, d_peak = load[ipk], delta[i][ipk]
    lin = (delta > 0.2 * d_peak) & (delta < 0.6 * d_peak)
    c0 = 1.0 / (2.0 * np.polyfit(delta[lin] ** 2, work[lin], 1)[0])
    chi = williams_chi(gen.NU)
    a_corr = p["a0"] + 0.42 * chi * H              # Wang & Williams (1992) ENF correction
    ck.rel("initial compliance (m/(N/m))", c0, compliance(a_corr, p["half_span"]), 0.05,
           note=f"beam theory with a0 + 0.42 chi h; plain a0: {compliance(p['a0'], p['half_span']):.4g}")
    ck.rel("critical load (N/m)", p_peak, critical_load(a_corr), 0.05,
           note=f"at deflection {d_peak * 1e3:.4f} mm; plain a0: {critical_load(p['a0']):.1f} N/m")
    _, _, lengths = mr.tip_history()
    broken = lengths[-1]
    ck.true("the crack grows", broken > 5.0 * p["el"], ours=f"{broken * 1e3:.2f} mm", ref="> 5 elements")
    dd = s["damage_dissipated"][-1]
    damaged = s["damaged_length"][-1]
    ck.info("damaged (not broken) length at the end (mm)", damaged * 1e3,
            note=f"damage dissipated / G_c = {dd / GC * 1e3:.2f} mm; broken + damaged = "
                 f"{(broken + damaged) * 1e3:.2f} mm")
    ck.rel("damage dissipated / (G_c x broken length)", dd / (GC * broken), 1.0, 0.05,
           note="includes the damaged process zone ahead of the arrested tip")
    check_energy(ck, s)
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
