#!/usr/bin/python3
"""A plate with one weaker row of interfaces, pulled apart at large time steps (issue 17).

An exploded plate of 10 x 10 square cells, each cut into two T3 elements (200 MAILx
bodies), every shared edge an MAC_CZM interface: w = 10 J/m2 everywhere, except the
row of edges on the plate's mid-line y = L/2 (between the lower and the upper half:
family bb_tt), w = 6.4 J/m2. The bottom nodes are held, the top nodes pulled at
V = 0.05 m/s (raised smoothly over T_RAMP). Only the weak row breaks; it breaks whole,
so its damage energy is its law's energy w L (reference: the law's energy, doc/czm.md
§2.1, times the row's length).

The time step is given in element transits (c dt / h, c = sqrt(E / rho)): COURANT = 2
as LMGC90's users run such decks (issue 17's LMGC90-written plate: about 2 transits
per step). With LMGC90's explicit damage update the weak row dissipated 8.9 w L there.

    gen.py OUT_DIR [COURANT]     writes OUT_DIR/DATBOX
"""
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
from fracas_tools.fractools import Grid, smooth_ramp  # noqa: E402

E, NU, RHO = 7.0e10, 0.3, 2700.0          # c = sqrt(E / rho) = 5092 m/s
L, N = 0.1, 10                            # plate side, cells per side
H = L / N
W_STRONG, W_WEAK = 10.0, 6.4              # J/m2
CN = 1.0e14                               # interface stiffness (Pa/m): C h / E = 14
V, T_RAMP = 0.05, 2.0e-4
T_END = 2.4e-3
COURANT = 2.0


def build(courant=COURANT):
    from fracas_tools import Case
    from fracas_tools.mesh import mesh_from_arrays
    g = Grid(0.0, L, 0.0, L, N, N)
    elements, phases = [], []
    for k, (a, b, c, d) in enumerate(g.elements):
        phase = "bb" if k // N < N // 2 else "tt"
        elements += [(a, b, c), (a, c, d)]
        phases += [phase, phase]
    mesh = mesh_from_arrays(g.nodes, elements, phases,
                            node_groups={"bottom": g.side_nodes("bottom"), "top": g.side_nodes("top")})
    case = Case(gravity=(0.0, 0.0))
    case.add_material("ALUxx", RHO, "ELAS", young=E, poisson=NU)
    parts = case.add_exploded_mesh(mesh, "ALUxx")
    for b in parts.bodies_with("bottom"):
        b.impose_velocity("bottom", (1, 2))
    for b in parts.bodies_with("top"):
        b.impose_velocity("top", (1,))
        b.impose_evolution("top", 2, "vlocy", "pull.txt", smooth_ramp(T_RAMP) * [1.0, V])
    case.add_law("czmst", "MAC_CZM", dyfr=0.0, stfr=0.0, cn=CN, ct=CN, b=0.0, w=W_STRONG)
    case.add_law("czmwk", "MAC_CZM", dyfr=0.0, stfr=0.0, cn=CN, ct=CN, b=0.0, w=W_WEAK)
    parts.add_see(case, {("bb", "bb"): "czmst", ("tt", "tt"): "czmst", ("bb", "tt"): "czmwk"}, alert=1.0e-5)
    dt = courant * H / np.sqrt(E / RHO)
    steps = int(round(T_END / dt))
    case.run.set(time_step=dt, number_of_steps=steps, plane="stress", nlgs_tolerance=1e-6,
                 output_hdf5_every=max(1, steps // 20), output_dof_every=0, output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    out = Path(sys.argv[1])
    courant = float(sys.argv[2]) if len(sys.argv) > 2 else COURANT
    build(courant).write(out)
