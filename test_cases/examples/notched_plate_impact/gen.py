#!/usr/bin/python3
"""Generate the DATBOX of the demo notched_plate_impact: a notched plate broken by an
impact (doc/fracture.md). An 80 x 30 mm plate of a brittle glass-like solid
(E = 32 GPa, nu = 0.2, rho = 2450 kg/m3, G_c = 3 J/m2, strength 5 MPa: the Borden
et al. branching material), an 8 mm edge notch at the middle of its lower edge, held
vertically at two points 5 mm from the lower corners, struck at the middle of its
upper edge: a 4 mm segment driven down at 0.4 m/s (a half-cosine start over 2 us;
the impact stress rho c_d v = 3.7 MPa stays below the strength: the plate breaks in
bending, from the notch, not under the striker).
The plate is meshed by gmsh (plate.geo, T3, interior nodes perturbed), exploded (one
MAILx body per element) and every shared edge glued by MP3_CZM (C h / E = 50); the
notch lips are left uncohesive. Plane strain, dt = 0.25 us, 200 us; VTK and HDF5
every 8 us.

    build/release/bin/fracas-python test_cases/examples/notched_plate_impact/gen.py   # rewrites ./DATBOX
    build/release/bin/fracas --output build/notched_plate_impact test_cases/examples/notched_plate_impact
    paraview build/notched_plate_impact/DISPLAY/fracas.pvd             # about 30 s of run first

In ParaView: meshes_*.vtu coloured by von_mises, interfaces_*.vtu by beta (1 sound,
0 broken), cracks_*.vtu (the crack paths). The picture of doc/fracture.md comes from
tools/fracture/plot_cracks.py on OUTBOX/fracas.h5.
"""
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools.cohesive import mp3_separation_opening, perturb_nodes, see_alert, smooth_ramp  # noqa: E402

E, NU, RHO = 32.0e9, 0.2, 2450.0
GC, SMAX, CH_E = 3.0, 5.0e6, 50.0
LC = 2.0e-3
V_IMPACT, RISE = 0.4, 2.0e-6
DT, T_END, EVERY = 0.25e-6, 200e-6, 32


def build():
    from fracas_tools import Case
    from fracas_tools.mesh import mesh_geo
    mesh = perturb_nodes(mesh_geo(HERE / "plate.geo", size_factor=LC / 1.0e-3), 0.2)
    case = Case(gravity=(0.0, 0.0))
    case.add_material("GLASS", RHO, "ELAS", young=E, poisson=NU)
    parts = case.add_exploded_mesh(mesh, "GLASS", cracks=["notch"])
    parts.impose_velocity("support_left", (2,))
    parts.impose_velocity("support_right", (2,))
    parts.impose_velocity("support_left", (1,))
    for b in parts.bodies_with("impact"):
        b.impose_evolution("impact", 2, "vlocy", "impact.txt", smooth_ramp(RISE) * [1.0, -V_IMPACT])
    c = CH_E * E / LC
    case.add_law("czmgl", "MP3_CZM", dyfr=0.0, stfr=0.0, cn=c, ct=c, smax=SMAX, w=GC)
    d_c = mp3_separation_opening(GC, SMAX, c)
    parts.add_see(case, "czmgl", alert=see_alert(mesh, d_c))
    case.run.set(time_step=DT, final_time=T_END, plane="strain", nlgs_tolerance=1e-5,
                 nlgs_sweeps_per_check=5, output_hdf5_every=EVERY, output_dof_every=0,
                 output_vtk_every=EVERY, progress_every=0)
    return case


if __name__ == "__main__":
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else HERE
    build().write(out)
    print(f"wrote {out / 'DATBOX'}")
