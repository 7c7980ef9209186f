#!/usr/bin/python3
"""1D spall: a compressive pulse reflected at a free end as tension breaks an
exploded bar where and when the wave analysis says (README.md; czm.md §3.2).

Two steel bars (E = 200 GPa, nu = 0, rho = 8000: c = 5000 m/s), L = 100 mm, one row
of N square Q4 elements, every element glued to its neighbours (MP3_CZM, C h / E =
100, w = 50 J/m2). A pressure pulse p(t) is applied on the left end (nodal forces);
the right end is free. The pulse rises to P0 = 1 GPa with a half-cosine ramp of
T1 = 2 us, holds until T2 and falls back the same way. The bars differ by their
plateau T2 and strength SMAX = q P0.

Wave analysis (d'Alembert): at distance s from the free end the stress is
p(tau - s/c) - p(tau + s/c), tau = t - L/c: the reflected head meets the incident
tail. For a pulse symmetric in time, tension first appears where they cross, at
s* = c T2 / 2, and reaches q P0 there when the rise has reached (1 + q)/2:
t* = L/c + T2/2 + (T1/pi) arccos(-q). Before t = L/c every interface is in
compression (Signorini: rigid, undamaged).

    gen.py OUT_DIR [fine]     fine: N = 200 and half the time step (label long)
"""
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
from fracas_tools.fractools import Grid  # noqa: E402

E, NU, RHO = 2.0e11, 0.0, 8000.0
C_WAVE = (E / RHO) ** 0.5
L, H = 0.1, 0.001
P0 = 1.0e9
T1 = 2.0e-6
BARS = {"aa": (8.0e-6, 0.7), "bb": (5.0e-6, 0.5)}    # phase -> (T2, q = SMAX / P0)
W_SEP = 50.0
CH_E = 100.0
T_END = 35.0e-6
VARIANTS = {"quick": dict(n=100, dt=1.0e-7), "fine": dict(n=200, dt=5.0e-8)}


def prediction(phase):
    """(x of the spall plane from the loaded end, time) of the wave analysis."""
    t2, q = BARS[phase]
    return L - C_WAVE * t2 / 2.0, L / C_WAVE + t2 / 2.0 + T1 * np.arccos(-q) / np.pi


def pulse(t2, n=20):
    """(t, p/P0) points: half-cosine rise over T1, plateau to T2, half-cosine fall."""
    u = np.linspace(0.0, 1.0, n + 1)
    rise = 0.5 * (1.0 - np.cos(np.pi * u))
    t = np.concatenate([u * T1, t2 + u * T1, [1.0]])
    return np.vstack([t, np.concatenate([rise, 1.0 - rise, [0.0]])]).T


def build(variant="quick"):
    from fracas_tools import Case
    from fracas_tools.mesh import mesh_from_arrays
    n, dt = VARIANTS[variant]["n"], VARIANTS[variant]["dt"]
    nodes, elements, phases, groups = [], [], [], {}
    for k, ph in enumerate(BARS):
        g = Grid(0.0, L, 3 * k * H, 3 * k * H + H, n, 1, first=len(nodes))
        nodes += g.nodes.tolist()
        elements += g.elements
        phases += [ph] * n
        groups[f"left_{ph}"] = g.side_nodes("left")
    mesh = mesh_from_arrays(np.array(nodes), elements, phases, node_groups=groups)
    case = Case(gravity=(0.0, 0.0))
    case.add_material("STEEL", RHO, "ELAS", young=E, poisson=NU)
    parts = case.add_exploded_mesh(mesh, "STEEL")
    c = CH_E * E / (L / n)
    for ph, (t2, q) in BARS.items():
        force = pulse(t2) * [1.0, P0 * H / 2.0]          # two end nodes share p H
        for b in parts.bodies_with(f"left_{ph}"):
            b.impose_evolution(f"left_{ph}", 1, "force", f"pulse_{ph}.txt", force)
        case.add_law("czm" + ph, "MP3_CZM", dyfr=0.0, stfr=0.0, cn=c, ct=c, smax=q * P0, w=W_SEP)
    parts.add_see(case, {(ph, ph): "czm" + ph for ph in BARS}, alert=1.0e-5)
    case.run.set(time_step=dt, final_time=T_END, plane="strain", nlgs_tolerance=1e-6,
                 nlgs_sweeps_per_check=5, output_hdf5_every=1, output_dof_every=0,
                 output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent
    variant = sys.argv[2] if len(sys.argv) > 2 else "quick"
    build(variant).write(out)
    for ph in BARS:
        x, t = prediction(ph)
        print(f"bar {ph}: spall predicted at x = {x * 1e3:.2f} mm, t = {t * 1e6:.3f} us")
    print(f"wrote {out / 'DATBOX'}")
