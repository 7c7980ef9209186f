#!/usr/bin/python3
"""Write test_cases/validation/czm_mode_I/<law>/DATBOX for <law> in mac, mp3, mal, th, expo, abp:
two 1 m x 1 m rigid POLYG blocks glued face to face at y = 0.5 (glued length 1 m,
two contact points of 0.5 m each); the lower block is fixed, the upper one is pulled
straight up by a driven velocity (its rotation is driven to 0, its x is free), no gravity.

The opening velocity (evolution file vy.dat) gives an opening of d_peak/250 per step up
to 0.95 d_peak (elastic), d_peak/1000 per step up to 1.25 d_peak (the peak), then an
opening growing by 1/400 of itself per step (geometric) until the end (20 d0 for MAC, 1.1 times full separation for the others): the one-step lag of
beta then changes the stress by at most 0.25 % near the peak (README.md). The parameters below are read by check.py
(import gen). Run once; the generated DATBOX folders are committed.

    gen.py [LAW ...]              the rigid decks (committed)
    gen.py --mesh OUT_DIR LAW [--shear]
                                  the same scene with meshed blocks: two 1 m x 1 m Q4
                                  MAILx bodies (E = 1e14 Pa, nu = 0: rigid next to the
                                  interface, no lateral contraction), glued by the gap law
                                  (MAC_CZM, MP3_CZM, ...) through CLALp contacts: two
                                  CLxxx points of L = 0.5 m on the upper block's bottom
                                  edge against the lower block's top edge (ALpxx);
                                  --shear: the upper block slides along x instead (its y
                                  held), the interface in pure mode II (gap law, u_n = 0):
                                  the lower block's bottom is held and its face's y too
"""
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
from fracas_tools.cohesive import Law, ramp_schedule  # noqa: E402

DT = 1.0e-4            # time step (s); the blocks are driven, only the opening per step matters
RHO = 2000.0           # density (kg/m^3), irrelevant (no free motion along the normal)
MU = 0.5               # friction (irrelevant in pure opening)
GLUED = 1.0            # glued length (m): face of the 1 m blocks
ALERT = 0.01           # see-rule alert distance (m)
ELASTIC = 4.0e-3       # opening per step / d_peak up to NEAR d_peak
NEAR = 0.95            # d / d_peak where the fine phase starts
FINE = 1.0e-3          # opening per step / d_peak from NEAR to SWITCH d_peak
GROWTH = 1.0 / 400.0   # opening per step / opening afterwards
SWITCH = 1.25          # d / d_peak where the velocity switches

# name: (LMGC90 law name, Law)
LAWS = {
    "mac": ("IQS_MAC_CZM", Law.mac(cn=1.0e10, ct=1.0e11, b=0.0, w=40.0)),
    "mp3": ("MP3_CZM", Law.mp3(cn=1.0e11, ct=1.0e11, smax=1.0e6, w=40.0)),
    "mal": ("IQS_MAL_CZM", Law.mal(cn=1.0e11, ct=5.0e10, s1=1.0e6, s2=2.0e6, G1=40.0, G2=100.0)),
    "th": ("IQS_TH_CZM", Law.th(cn=1.0e11, ct=5.0e10, s1=1.0e6, s2=2.0e6, G1=40.0, G2=100.0,
                                dp1=2.0e-5, dp2=6.0e-5)),
    "expo": ("IQS_EXPO_CZM", Law.expo(cn=1.0e11, ct=5.0e10, s1=1.0e6, s2=2.0e6, G1=40.0, G2=100.0,
                                      eta=1.0e-4)),
    "abp": ("IQS_ABP_CZM", Law.abp(cn=1.0e11, ct=5.0e10, s1=1.0e6, s2=2.0e6, G1=40.0, G2=100.0,
                                   du1=6.0e-5, du2=1.5e-4, phi=0.5)),
}


def schedule(name, mode=1):
    """(n1, n2, table): steps of the uniform phases (elastic, then fine) and of the
    geometric phase of the opening (mode 2: the slip), and the velocity table (t, v). In the geometric phase u(t) = u1 exp((t - t1)/tau),
    tau = DT/GROWTH, so v = u/tau."""
    law = LAWS[name][1]
    dpk = law.d_peak(mode)
    d_end = 20.0 * dpk if law.family == "MAC" else 1.1 * law.d_end(mode)
    return ramp_schedule(dpk, d_end, DT, ELASTIC, NEAR, FINE, SWITCH, GROWTH)


def build(name, table=None, steps=None):
    """The rigid deck of law `name`; table, steps: another opening velocity schedule
    (t, v) and its step count (czm_step_size) instead of the ramp."""
    from fracas_tools import Case
    law_name, law = LAWS[name]
    n1, n2, ramp = schedule(name)
    table = ramp if table is None else table
    steps = n1 + n2 if steps is None else steps
    case = Case(gravity=(0.0, 0.0))
    case.add_material("STONE", density=RHO)
    law.add_to(case, "czm01", law_name, MU)
    case.add_see("POLYG", "BLEUx", "POLYG", "BLEUx", "czm01", ALERT)
    lower = case.add_polygon([(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)], "STONE")
    lower.fix()
    upper = case.add_polygon([(-0.5, 0.5), (0.5, 0.5), (0.5, 1.5), (-0.5, 1.5)], "STONE")
    upper.impose_evolution(2, "vlocy", "vy.dat", data=table)
    upper.impose_velocity(3)
    case.run.set(time_step=DT, number_of_steps=steps, theta=0.5, nlgs_check="Quad",
                 nlgs_tolerance=1e-6, output_hdf5_every=1, output_dof_every=0,
                 output_vtk_every=0, progress_every=0)
    return case


MESH_E = 1.0e14        # Young's modulus of the meshed blocks (Pa): E/h = 1000 cn


def build_mesh(name, shear=False):
    """The scene with two Q4 MAILx blocks and the gap variant of the law (README.md);
    shear: the upper block driven along x (mode II schedule), y held."""
    import numpy as np
    from fracas_tools import Case
    from fracas_tools.mesh import mesh_from_arrays
    law_name, law = LAWS[name]
    n1, n2, table = schedule(name, 2 if shear else 1)
    nodes = np.array([(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5),
                      (-0.5, 0.5), (0.5, 0.5), (0.5, 1.5), (-0.5, 1.5)])
    mesh = mesh_from_arrays(nodes, [(0, 1, 2, 3), (4, 5, 6, 7)], ["lower", "upper"],
                            node_groups={"bottom": [0, 1], "corner": [0], "face": [2, 3], "upper": [4, 5, 6, 7]},
                            edge_groups={"face_lo": [(3, 2)], "face_up": [(4, 5)]})
    case = Case(gravity=(0.0, 0.0))
    case.add_material("STIFF", RHO, "ELAS", young=MESH_E, poisson=0.0)
    lower, upper = case.add_mesh(mesh, "STIFF")
    law.add_to(case, "czm01", law_name.replace("IQS_", ""), MU)
    upper.add_candidates_on("face_up", "BLEUx")
    lower.add_polyline_on("face_lo", "BLEUx")
    case.add_see("CLxxx", "BLEUx", "ALpxx", "BLEUx", "czm01", ALERT)
    lower.impose_velocity("bottom", (2,))
    if shear:
        # The shear load would tilt the lower block's face (one point pressed, one
        # opened, friction on the pressed one): its y is held, its x left free, so the
        # slip still passes through the block's compliance.
        lower.impose_velocity("bottom", (1,))
        lower.impose_velocity("face", (2,))
    else:
        lower.impose_velocity("corner", (1,))
    driven, held = (1, 2) if shear else (2, 1)
    upper.impose_evolution("upper", driven, "vlocy", "v.dat", data=table)
    upper.impose_velocity("upper", (held,))
    case.run.set(time_step=DT, number_of_steps=n1 + n2, theta=0.5, nlgs_check="Quad",
                 nlgs_tolerance=1e-6, output_hdf5_every=1, output_dof_every=0,
                 output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    if sys.argv[1:2] == ["--mesh"]:
        build_mesh(sys.argv[3], "--shear" in sys.argv[4:]).write(Path(sys.argv[2]))
        print(f"wrote {sys.argv[2]}/DATBOX (meshed, {sys.argv[3]}{', shear' if '--shear' in sys.argv else ''})")
        sys.exit(0)
    for name in (sys.argv[1:] or LAWS):
        build(name).write(HERE / name)
        print(f"wrote {HERE / name / 'DATBOX'}  steps {sum(schedule(name)[:2])}")
