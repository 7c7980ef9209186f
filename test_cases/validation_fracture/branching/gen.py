#!/usr/bin/python3
"""Dynamic crack speed and branching (README.md; czm.md §3.6): the Borden et al.
(2012) plate, 100 x 40 mm with a 50 mm notch from the left edge at mid-height
(plate.geo), E = 32 GPa, nu = 0.2, rho = 2450, G_c = 3 J/m2, a step traction of
1 MPa on the top and bottom edges from t = 0. Plane strain. gmsh T3 mesh, interior
nodes perturbed (seeded) so that cracks do not follow the straight lines of the
mesh, exploded; MP3_CZM on every interface (strength SMAX, C h / E = CH_E).

    gen.py OUT_DIR [quick|full]
"""
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools.fractools import edge_traction, mp3_separation_opening, perturb_nodes, safe_alert, wave_speeds  # noqa: E402

E, NU, RHO = 32.0e9, 0.2, 2450.0
GC = 3.0
TRACTION = 1.0e6
SMAX = 5.0e6                       # cohesive strength: E G_c / SMAX^2 = 3.8 mm
CH_E = 50.0
PERTURB = 0.2
NOTCH_TIP = (0.05, 0.02)
SPEED_WINDOW = 6e-6                # tip speed measured over at least this time (3 snapshots of quick)
BRANCH_RADIUS = 5e-3               # crack arms counted beyond this distance from the notch tip
VARIANTS = {
    "quick": dict(lc=2.0e-3, dt=2.0e-7, t_end=60e-6, every=10),
    "full": dict(lc=1.0e-3, dt=1.0e-7, t_end=80e-6, every=10),
}


def build(variant="quick"):
    from fracas_tools import Case
    from fracas_tools.mesh import mesh_geo
    p = VARIANTS[variant]
    mesh = perturb_nodes(mesh_geo(HERE / "plate.geo", size_factor=p["lc"] / 1.0e-3), PERTURB)
    case = Case(gravity=(0.0, 0.0))
    case.add_material("GLASS", RHO, "ELAS", young=E, poisson=NU)
    parts = case.add_exploded_mesh(mesh, "GLASS", cracks=["notch"])
    edge_traction(parts.bodies, "top", (0.0, TRACTION))
    edge_traction(parts.bodies, "bottom", (0.0, -TRACTION))
    c = CH_E * E / p["lc"]
    case.add_law("czmgl", "MP3_CZM", dyfr=0.0, stfr=0.0, cn=c, ct=c, smax=SMAX, w=GC)
    d_c = mp3_separation_opening(GC, SMAX, c)
    alert = 10.0 * d_c
    if alert > 0.5 * safe_alert(mesh):
        raise SystemExit(f"alert {alert:g} too wide for the mesh (safe {safe_alert(mesh):g})")
    parts.add_see(case, "czmgl", alert=alert)
    case.run.set(time_step=p["dt"], final_time=p["t_end"], plane="strain", nlgs_tolerance=1e-5,
                 nlgs_sweeps_per_check=5, output_hdf5_every=p["every"], output_dof_every=0,
                 output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else HERE
    variant = sys.argv[2] if len(sys.argv) > 2 else "quick"
    build(variant).write(out)
    print(f"wrote {out / 'DATBOX'} ({variant}); c_d, c_s, c_R = {wave_speeds(E, NU, RHO)}")
