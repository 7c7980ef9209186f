#!/usr/bin/python3
"""End-notched flexure (ENF), mode II (README.md; czm.md §3.4).

A beam of two arms of thickness H (Q8 elements, one MAILx body each), span 2 L, on two
supports (lower arm's bottom corners: x = 0 pinned, x = 2L on a roller), loaded at
mid-span (upper arm's top node at x = L driven downward at V after a half-cosine
start). The arms are glued by MP3_CZM on x in [A0, 2L]; on the pre-crack x < A0 they
touch through frictionless contact (GAP_SGR_CLB, mu = 0), as beam theory assumes.
Plane stress, isotropic E, nu.

    gen.py OUT_DIR [h1|h2|h4|unstable]
"""
import sys
from pathlib import Path

sys.dont_write_bytecode = True
from fracas_tools.fractools import Grid, mp3_separation_opening, smooth_ramp  # noqa: E402

E, NU, RHO = 135.3e9, 0.3, 1500.0
GC = 280.0                             # mode II fracture energy (MP3: one w for all modes)
H = 1.5e-3                             # arm thickness (beam 2 H)
CH_E = 50.0                            # the exploded meshes' C h / E (doc/fracture.md section 2)
VARIANTS = {
    # Stable growth (a0^3 > L^3 / 3): the validation, one geometry at three time steps
    # h1, h2, h4 = 1e-6, 5e-7, 2.5e-7 s (README.md). grown: crack growth after which the
    # energy window opens; a_max: it closes where the LEFM crack length reaches a_max L.
    **{name: dict(half_span=30e-3, a0=22.5e-3, el=0.75e-3, ny=2, smax=100e6, c=1e15, v=0.5, t_ramp=0.3e-3,
                  dt=dt, delta_end=0.60e-3, every=every, window=10e-6, grown=1.5e-3, a_max=1.0)
       for name, dt, every in (("h1", 1e-6, 10), ("h2", 5e-7, 20), ("h4", 2.5e-7, 40))},
    # The first geometry (a0 = L / 2): the crack jumps; the time-step study of README.md.
    "unstable": dict(half_span=20e-3, a0=10e-3, el=0.5e-3, ny=2, smax=100e6, c=CH_E * E / 0.5e-3, v=0.5,
                     t_ramp=0.2e-3, dt=5e-7, delta_end=0.35e-3, every=10, window=10e-6),
}


def params(variant):
    return VARIANTS[variant]


def build(variant="h2"):
    import numpy as np
    from fracas_tools import Case
    from fracas_tools.mesh import mesh_from_arrays
    p = params(variant)
    span = 2.0 * p["half_span"]
    nx = int(round(span / p["el"]))
    up = Grid(0.0, span, 0.0, H, nx, p["ny"], order=2)
    lo = Grid(0.0, span, -H, 0.0, nx, p["ny"], order=2, first=len(up.nodes))
    mesh = mesh_from_arrays(
        np.vstack([up.nodes, lo.nodes]), up.elements + lo.elements,
        ["upper"] * len(up.elements) + ["lower"] * len(lo.elements),
        node_groups={"load": [up.node(nx, 2 * p["ny"])], "pin": [lo.node(0, 0)], "roller": [lo.node(2 * nx, 0)]},
        edge_groups={"bond_up": up.edges("bottom", p["a0"], span), "bond_lo": lo.edges("top", p["a0"], span),
                     "crack_up": up.edges("bottom", 0.0, p["a0"]), "crack_lo": lo.edges("top", 0.0, p["a0"])})
    case = Case(gravity=(0.0, 0.0))
    case.add_material("LAMIN", RHO, "ELAS", young=E, poisson=NU)
    bodies = case.add_mesh(mesh, "LAMIN")
    upper = next(b for b in bodies if "bond_up" in b.edge_groups)
    lower = next(b for b in bodies if "bond_lo" in b.edge_groups)
    upper.add_polyline_on("bond_up", "BONDx")
    lower.add_candidates_on("bond_lo", "BONDx")
    upper.add_polyline_on("crack_up", "CRACK")
    lower.add_candidates_on("crack_lo", "CRACK")
    upper.impose_evolution("load", 2, "vlocy", "load.txt", smooth_ramp(p["t_ramp"]) * [1.0, -p["v"]])
    lower.fix("pin")
    lower.impose_velocity("roller", (2,))
    c = p["c"]
    case.add_law("bondz", "MP3_CZM", dyfr=0.0, stfr=0.0, cn=c, ct=c, smax=p["smax"], w=GC)
    case.add_law("lipsz", "GAP_SGR_CLB", fric=0.0)
    d_c = mp3_separation_opening(GC, p["smax"], c)
    case.add_see("CLxxx", "BONDx", "ALpxx", "BONDx", "bondz", 3.0 * d_c)
    case.add_see("CLxxx", "CRACK", "ALpxx", "CRACK", "lipsz", 3.0 * d_c)
    t_end = p["t_ramp"] / 2.0 + p["delta_end"] / p["v"]
    case.run.set(time_step=p["dt"], final_time=t_end, plane="stress", nlgs_tolerance=1e-6,
                 nlgs_sweeps_per_check=5, nlgs_max_checks=4000, output_hdf5_every=p["every"],
                 output_dof_every=0, output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent
    variant = sys.argv[2] if len(sys.argv) > 2 else "h2"
    build(variant).write(out)
    print(f"wrote {out / 'DATBOX'} ({variant})")
