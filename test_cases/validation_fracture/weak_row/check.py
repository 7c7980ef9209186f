#!/usr/bin/python3
"""Checks a run of the weak-row plate (gen.py, README.md):

1. the weak row (family BB_TT, the interfaces on the mid-line) is broken along its whole
   length;
2. its damage energy is its law's energy w L (MAC_CZM: D = w (1 - beta), beta -> 0 once
   broken; L = the plate's width) within TOL = 5 % (issue 17's target at Courant 2);
3. the energy audit closes (|balance_error| <= 1e-6 of the largest energy term) and the
   contacts create no energy (dissipated - damage >= -1e-6 of it).

    check.py RUN_DIR [COURANT]
"""
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.dont_write_bytecode = True
from fracas_tools.checks import Checker  # noqa: E402
from fracas_tools.results import Run  # noqa: E402
import gen  # noqa: E402

TOL = 0.05
AUDIT_TOL = 1e-6


def main(run_dir, courant):
    ck = Checker(f"weak_row (exploded plate, one weaker row, Courant {courant:g})")
    with Run(run_dir) as r:
        fams = r.mesh_attrs["interface_families"].split()
        m, s = r.mesh, r.series
        edge_fam = np.array(fams)[m["interface_edge_family"][:] - 1]
        length = m["interface_edge_length"][:]
        c = r.snapshot(-1).mesh["cracks"]
        broken = c["edge_broken_step"][:] > 0
        damage = dict(zip(fams, c["damage_per_family"][:]))
        row = edge_fam == "BB_TT"
        ck.close("weak row: length broken / its length", length[row & broken].sum() / length[row].sum(), 1.0,
                 1e-12, "the whole row")
        ck.rel("weak row: damage energy (J/m)", damage["BB_TT"], gen.W_WEAK * gen.L, TOL, "w L, MAC_CZM")
        for f in ("BB_BB", "TT_TT"):
            ck.info(f"{f}: broken length (m)", length[(edge_fam == f) & broken].sum())
            ck.info(f"{f}: damage energy (J/m)", damage[f])
        scale = max(abs(s[k][:]).max() for k in ("work_supports", "kinetic_energy", "elastic_energy",
                                                   "cohesive_energy", "dissipated"))
        ck.at_most("energy audit: max |balance_error| / energy", abs(s["balance_error"][:]).max() / scale, AUDIT_TOL)
        ck.at_most("energy audit: -min(dissipated - damage) / energy",
                   -min(0.0, (s["dissipated"][:] - s["damage_dissipated"][:]).min()) / scale, AUDIT_TOL,
                   "contacts create no energy")
        ck.info("steps at the sweep limit", int((s["converged"][:] == 0).sum()))
        ck.info("scheme", r.cohesive_damage)
    return ck.finish()


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], float(sys.argv[2]) if len(sys.argv) > 2 else gen.COURANT))
