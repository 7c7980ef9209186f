#!/usr/bin/python3
"""Artificial compliance of an exploded mesh (doc/fracture.md §2, czm.md §3.3 and §4.1).

Three bars of N = 10 square Q4 elements (h = 10 mm, one row), each element its own
MAILx body glued to its neighbours by MP3_CZM interfaces of stiffness C = r E / h with
r = C h / E = 5, 20, 100 (one interface family and law per bar; the strength is far
above the stresses reached, so nothing is damaged). The left end is held (x on the
end nodes, y on one corner), the right end pulled at a velocity that rises smoothly
(half cosine over T_RAMP) to V: a slow tension, plane stress, nu = 0.3.

Reference: N elements of length h in series with N - 1 interfaces of stiffness C: the
strain measured between the centres of the first and last elements spans N - 1 cells
of one element and one interface each, so stress / strain = E / (1 + E / (C h))
exactly in quasi-statics (the lateral contraction is the same in every element: no
shear in the interfaces).

    gen.py OUT_DIR        writes OUT_DIR/DATBOX
"""
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
from fracas_tools.fractools import Grid, smooth_ramp  # noqa: E402

E, NU, RHO = 7.0e10, 0.3, 2700.0          # aluminium-like; c = sqrt(E/rho) = 5092 m/s
L, H, N = 0.1, 0.01, 10                   # bar length, height, elements
ELEMENT = L / N
RATIOS = {"aa": 5.0, "bb": 20.0, "cc": 100.0}   # phase -> C h / E
GAP_Y = 2.0 * H                           # bars stacked 2 H apart (no contact between them)
V = 0.05                                  # final pulling velocity (m/s): strain rate 0.5 /s
T_RAMP = 4.0e-4                           # 5 periods of the fixed-free bar (4 L / c = 79 us)
DT = 1.0e-6
T_END = 6.0e-4
T_FIT = 4.5e-4                            # stress-strain slope fitted on t >= T_FIT
EVERY = 10


def bars():
    """(phase, y0, element index range) of each bar."""
    return [(ph, k * GAP_Y, range(k * N, (k + 1) * N)) for k, ph in enumerate(RATIOS)]


def build():
    from fracas_tools import Case
    from fracas_tools.mesh import mesh_from_arrays
    nodes, elements, phases, groups = [], [], [], {}
    for ph, y0, _ in bars():
        g = Grid(0.0, L, y0, y0 + H, N, 1, first=len(nodes))
        nodes += g.nodes.tolist()
        elements += g.elements
        phases += [ph] * N
        groups[f"left_{ph}"] = g.side_nodes("left")
        groups[f"corner_{ph}"] = [g.node(0, 0)]
        groups[f"right_{ph}"] = g.side_nodes("right")
    mesh = mesh_from_arrays(np.array(nodes), elements, phases, node_groups=groups)
    case = Case(gravity=(0.0, 0.0))
    case.add_material("ALUxx", RHO, "ELAS", young=E, poisson=NU)
    parts = case.add_exploded_mesh(mesh, "ALUxx")
    ramp = smooth_ramp(T_RAMP) * [1.0, V]
    for ph, r in RATIOS.items():
        c = r * E / ELEMENT
        case.add_law("czm" + ph, "MP3_CZM", dyfr=0.0, stfr=0.0, cn=c, ct=c, smax=1.0e10, w=1.0e4)
        for b in parts.bodies_with(f"left_{ph}"):
            b.impose_velocity(f"left_{ph}", (1,))
        for b in parts.bodies_with(f"corner_{ph}"):
            b.impose_velocity(f"corner_{ph}", (2,))
        for b in parts.bodies_with(f"right_{ph}"):
            b.impose_evolution(f"right_{ph}", 1, "vlocy", "pull.txt", ramp)
    parts.add_see(case, {(ph, ph): "czm" + ph for ph in RATIOS}, alert=1.0e-5)
    case.run.set(time_step=DT, final_time=T_END, plane="stress", nlgs_tolerance=1e-6,
                 nlgs_sweeps_per_check=10, output_hdf5_every=EVERY, output_dof_every=0,
                 output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent
    build().write(out)
    print(f"wrote {out / 'DATBOX'}")
