#!/usr/bin/python3
"""Check the artificial-compliance run (README.md): effective modulus of each exploded
bar against E / (1 + E / (C h)) within 1 %, the drives' reaction against the stress,
no damage, the energy audit."""
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
import gen  # noqa: E402
from fracas_tools.fractools import Checker, MeshRun, check_energy, run_dir_from_argv  # noqa: E402


def main():
    mr = MeshRun(run_dir_from_argv())
    ck = Checker("fracture compliance")
    states = [mr.state(i) for i in range(len(mr.snapshot_names))]
    t = np.array([s.time for s in states])
    fit = t >= gen.T_FIT - 1e-12
    for ph, y0, els in gen.bars():
        els = list(els)
        ratio = gen.RATIOS[ph]
        sigma, strain, reaction = [], [], []
        right = mr.nodes_at(None, 0.0, where=lambda x, y: (np.abs(x - gen.L) < 1e-9) & (y > y0 - 1e-9)
                            & (y < y0 + gen.H + 1e-9))
        for s in states:
            sigma.append(mr.element_mean(s.gp, "sxx")[els].mean())
            u = mr.element_displacement(s.X, [els[0], els[-1]])[:, 0]
            strain.append((u[1] - u[0]) / ((gen.N - 1) * gen.ELEMENT))
            reaction.append(s.F_support[right, 0].sum())
        sigma, strain, reaction = map(np.array, (sigma, strain, reaction))
        e_eff = np.polyfit(strain[fit], sigma[fit], 1)[0]
        ref = gen.E / (1.0 + 1.0 / ratio)
        ck.rel(f"C h/E = {ratio:g}: E_eff (GPa)", e_eff / 1e9, ref / 1e9, 0.01,
               note=f"loss 1 - E_eff/E = {1 - e_eff / gen.E:.4f}")
        ck.rel(f"C h/E = {ratio:g}: end reaction / (sigma H)", reaction[-1] / (sigma[-1] * gen.H), 1.0, 0.01)
    ck.close("damage dissipated (J/m)", mr.series["damage_dissipated"][-1], 0.0, 1e-12)
    check_energy(ck, mr.series)
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
