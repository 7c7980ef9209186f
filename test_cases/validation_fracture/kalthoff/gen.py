#!/usr/bin/python3
"""Kalthoff-Winkler edge impact (README.md; czm.md §3.5): the upper half of the
200 x 100 mm double-notched plate (plate.geo; symmetry y = 0), maraging steel
E = 190 GPa, nu = 0.3, rho = 8000, G_c = 2.213e4 J/m2, the edge below the notch
driven at V0 = 16.5 m/s in x (half the projectile speed: equal impedances) after a
RISE-long half-cosine start. Plane strain. gmsh T3 mesh, interior nodes perturbed
(seeded), exploded; MAL_CZM on every interface (opening strength SMAX, sliding SHEAR x; C h / E = CH_E); the
notch lips uncohesive.

    gen.py OUT_DIR [quick|full|<sensitivity variant>] [SEED]
"""
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools.fractools import perturb_nodes, safe_alert, smooth_ramp  # noqa: E402

E, NU, RHO = 190.0e9, 0.3, 8000.0
GC = 2.213e4
SMAX = 1.0e9                       # cohesive strength in opening: E G_c / SMAX^2 = 4.2 mm
SHEAR = 3.0                        # strength and energy in sliding / in opening (MAL_CZM)
CH_E = 50.0
PERTURB = 0.2
V0 = 16.5
RISE = 1.0e-6
NOTCH_TIP = (0.05, 0.025)
ANGLE_RANGE = (4e-3, 20e-3)        # crack direction fitted between these distances from the notch tip
ANGLE_REF, ANGLE_TOL = 70.0, 10.0  # Kalthoff & Winkler's experiments; the spread of simulations (degrees)
SPEED_WINDOW = 6e-6                # tip speed measured over at least this time (3 snapshots of quick)
VARIANTS = {
    "quick": dict(lc=3.0e-3, dt=0.25e-6, t_end=60e-6, every=8),
    "full": dict(lc=2.5e-3, dt=0.25e-6, t_end=60e-6, every=8),
}
# mesh and time-step sensitivity (tools/fracture/sensitivity.py, doc/fracture.md)
SENSITIVITY = {
    "lc3.0_dt0.25": dict(lc=3.0e-3, dt=0.25e-6, t_end=60e-6, every=8),
    "lc2.5_dt0.25": dict(lc=2.5e-3, dt=0.25e-6, t_end=60e-6, every=8),
    "lc2.0_dt0.25": dict(lc=2.0e-3, dt=0.25e-6, t_end=60e-6, every=8),
    "lc2.5_dt0.125": dict(lc=2.5e-3, dt=0.125e-6, t_end=60e-6, every=16),
    "lc1.5_dt0.25": dict(lc=1.5e-3, dt=0.25e-6, t_end=60e-6, every=8),
    "lc1.0_dt0.25": dict(lc=1.0e-3, dt=0.25e-6, t_end=60e-6, every=8),
}


def params(variant):
    return VARIANTS[variant] if variant in VARIANTS else SENSITIVITY[variant]


#: Element size spread of the meshes of another topology (build(topology=True)).
LC_JITTER = 0.05


def build(variant="quick", seed=1, topology=False):
    """The deck of a variant; seed: the node perturbation's (another mesh of that size).
    topology: another triangulation too, gmsh's at an element size drawn (with seed)
    within LC_JITTER of the variant's: a node perturbation alone keeps the edges' pattern."""
    import numpy as np
    from fracas_tools import Case
    from fracas_tools.mesh import mesh_geo
    p = params(variant)
    lc = p["lc"]
    if topology:
        lc *= 1.0 + LC_JITTER * np.random.default_rng(seed).uniform(-1.0, 1.0)
    mesh = perturb_nodes(mesh_geo(HERE / "plate.geo", size_factor=lc / 1.0e-3), PERTURB, seed=seed)
    case = Case(gravity=(0.0, 0.0))
    case.add_material("STEEL", RHO, "ELAS", young=E, poisson=NU)
    parts = case.add_exploded_mesh(mesh, "STEEL", cracks=["notch"])
    ramp = smooth_ramp(RISE) * [1.0, V0]
    for b in parts.bodies_with("impact"):
        if b.nodes[:, 1].mean() > NOTCH_TIP[1]:
            continue                   # the upper lip's element at the notch mouth shares the corner node
        b.impose_evolution("impact", 1, "vlocy", "impact.txt", ramp)
    parts.impose_velocity("symmetry", (2,))
    c = CH_E * E / lc
    case.add_law("czmst", "MAL_CZM", dyfr=0.0, stfr=0.0, cn=c, ct=c, s1=SMAX, s2=SHEAR * SMAX,
                 G1=GC, G2=SHEAR * GC)
    d_c = 1.5 * SHEAR * GC / (SHEAR * SMAX) + SHEAR * SMAX / c
    alert = min(10.0 * d_c, 0.5 * safe_alert(mesh))
    # A glued point must stay detected until it has fully separated: the alert distance
    # exceeds the full-separation opening with a margin (1.5; the meshes of ctest have 2+).
    if alert < 1.5 * d_c:
        raise SystemExit(f"alert {alert:g} below 1.5 times the full-separation opening {d_c:g}")
    parts.add_see(case, "czmst", alert=alert)
    case.run.set(time_step=p["dt"], final_time=p["t_end"], plane="strain", nlgs_tolerance=1e-5,
                 nlgs_sweeps_per_check=5, output_hdf5_every=p["every"], output_dof_every=0,
                 output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else HERE
    variant = sys.argv[2] if len(sys.argv) > 2 else "quick"
    build(variant, int(sys.argv[3]) if len(sys.argv) > 3 else 1).write(out)
    print(f"wrote {out / 'DATBOX'} ({variant})")
