#!/usr/bin/python3
"""Double cantilever beam, mode I (README.md; czm.md §3.4).

Two arms of thickness H (Q8 elements, each arm one MAILx body) glued along the bond
line x in [A0, L] by MP3_CZM (strength SMAX, energy GC; CLxxx points on the lower
arm, ALpxx on the upper one); the pre-crack x < A0 is open. The mid node of each
arm's left face is pinned in x and driven in y at +-V/2 (a half-cosine start over
T_RAMP), so the arms open by Delta(t) and turn freely about the pins. Plane stress,
isotropic E, nu.

    gen.py OUT_DIR [quick|full]
"""
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
from fracas_tools.fractools import Grid, mp3_separation_opening, smooth_ramp  # noqa: E402

E, NU, RHO = 135.3e9, 0.3, 1500.0      # the Alfano-Crisfield laminate's E11, isotropic here
GC = 280.0                             # J/m2
H = 1.5e-3                             # arm thickness
VARIANTS = {
    # a0, L, element (Q8 side), elements through an arm, strength, opening rate,
    # ramp, time step, end opening, snapshots every
    "quick": dict(a0=15e-3, length=30e-3, el=0.75e-3, ny=2, smax=30e6, v=2.0, t_ramp=0.2e-3,
                  dt=5e-7, delta_end=1.05e-3, every=10),
    "full": dict(a0=20e-3, length=45e-3, el=0.5e-3, ny=3, smax=30e6, v=1.0, t_ramp=0.4e-3,
                 dt=5e-7, delta_end=2.0e-3, every=10),
}
CH_E = 50.0                            # cohesive stiffness C = CH_E E / el


def params(variant):
    return VARIANTS[variant]


def build(variant="quick"):
    from fracas_tools import Case
    from fracas_tools.mesh import mesh_from_arrays
    p = params(variant)
    nx = int(round(p["length"] / p["el"]))
    up = Grid(0.0, p["length"], 0.0, H, nx, p["ny"], order=2)
    lo = Grid(0.0, p["length"], -H, 0.0, nx, p["ny"], order=2, first=len(up.nodes))
    nodes = np.vstack([up.nodes, lo.nodes])
    mid = p["ny"]                       # lattice row of the face's mid node (Q8: 2 ny + 1 rows)
    mesh = mesh_from_arrays(
        nodes, up.elements + lo.elements, ["upper"] * len(up.elements) + ["lower"] * len(lo.elements),
        node_groups={"pin_up": [up.node(0, mid)], "pin_lo": [lo.node(0, mid)]},
        edge_groups={"bond_up": up.edges("bottom", p["a0"], p["length"]),
                     "bond_lo": lo.edges("top", p["a0"], p["length"])})
    case = Case(gravity=(0.0, 0.0))
    case.add_material("LAMIN", RHO, "ELAS", young=E, poisson=NU)
    bodies = case.add_mesh(mesh, "LAMIN")
    upper = next(b for b in bodies if "bond_up" in b.edge_groups)
    lower = next(b for b in bodies if "bond_lo" in b.edge_groups)
    upper.add_polyline_on("bond_up", "BONDx")
    lower.add_candidates_on("bond_lo", "BONDx")
    ramp = smooth_ramp(p["t_ramp"])
    upper.impose_velocity("pin_up", (1,))
    upper.impose_evolution("pin_up", 2, "vlocy", "open_up.txt", ramp * [1.0, 0.5 * p["v"]])
    lower.impose_velocity("pin_lo", (1,))
    lower.impose_evolution("pin_lo", 2, "vlocy", "open_lo.txt", ramp * [1.0, -0.5 * p["v"]])
    c = CH_E * E / p["el"]
    case.add_law("bondz", "MP3_CZM", dyfr=0.0, stfr=0.0, cn=c, ct=c, smax=p["smax"], w=GC)
    d_c = mp3_separation_opening(GC, p["smax"], c)
    case.add_see("CLxxx", "BONDx", "ALpxx", "BONDx", "bondz", 3.0 * d_c)
    t_end = p["t_ramp"] / 2.0 + p["delta_end"] / p["v"]  # the ramp loses t_ramp/2 of opening
    case.run.set(time_step=p["dt"], final_time=t_end, plane="stress", nlgs_tolerance=1e-6,
                 nlgs_sweeps_per_check=5, nlgs_max_checks=4000, output_hdf5_every=p["every"],
                 output_dof_every=0, output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent
    variant = sys.argv[2] if len(sys.argv) > 2 else "quick"
    build(variant).write(out)
    print(f"wrote {out / 'DATBOX'} ({variant})")
