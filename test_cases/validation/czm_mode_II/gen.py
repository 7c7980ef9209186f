#!/usr/bin/python3
"""Write test_cases/validation/czm_mode_II/<law>/DATBOX for <law> in mac, expo: two
1 m x 1 m rigid POLYG blocks glued face to face at y = 0.5 (glued length 1 m, two
contact points of 0.5 m); the lower block is fixed; the upper block is pressed down by a
driven force P = p L (compressive preload, its y is free), its x velocity is driven
(shear, evolution file vx.dat) and its rotation is driven to 0. No gravity.

Expected shear traction: tau = beta^k ct ut + mu (1 - beta) p: cohesion first, then
Coulomb friction mu p once beta -> 0 (README.md). The slip schedule is the one of
czm_mode_I (tools/czm/czmlaws.ramp_schedule). The parameters below are read by check.py.
"""
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
from fracas_tools.cohesive import Law, ramp_schedule  # noqa: E402

DT = 1.0e-4            # time step (s)
RHO = 2000.0           # density (kg/m^3)
MU = 0.5               # friction coefficient (dyfr = stfr)
PRELOAD = 4.0e5        # compressive normal stress p (Pa): mu p = 2e5 Pa
GLUED = 1.0            # glued length (m)
ALERT = 0.01           # see-rule alert distance (m)

LAWS = {
    "mac": ("IQS_MAC_CZM", Law.mac(cn=1.0e10, ct=1.0e11, b=0.0, w=40.0)),
    "expo": ("IQS_EXPO_CZM", Law.expo(cn=1.0e11, ct=5.0e10, s1=1.0e6, s2=2.0e6, G1=40.0, G2=100.0,
                                      eta=1.0e-4)),
}


def schedule(name):
    """(n1, n2, table) of the driven slip velocity (mode II: jump ut)."""
    law = LAWS[name][1]
    dpk = law.d_peak(2)
    d_end = 20.0 * dpk if law.family == "MAC" else 1.1 * law.d_end(2)
    return ramp_schedule(dpk, d_end, DT)


def build(name):
    from fracas_tools import Case
    law_name, law = LAWS[name]
    n1, n2, table = schedule(name)
    case = Case(gravity=(0.0, 0.0))
    case.add_material("STONE", density=RHO)
    law.add_to(case, "czm01", law_name, MU)
    case.add_see("POLYG", "BLEUx", "POLYG", "BLEUx", "czm01", ALERT)
    lower = case.add_polygon([(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)], "STONE")
    lower.fix()
    upper = case.add_polygon([(-0.5, 0.5), (0.5, 0.5), (0.5, 1.5), (-0.5, 1.5)], "STONE")
    upper.impose_evolution(1, "vlocy", "vx.dat", data=table)
    upper.impose_force(2, ct=-PRELOAD * GLUED)
    upper.impose_velocity(3)
    case.run.set(time_step=DT, number_of_steps=n1 + n2, theta=0.5, nlgs_check="Quad",
                 nlgs_tolerance=1e-6, output_hdf5_every=1, output_dof_every=0,
                 output_vtk_every=0, progress_every=0)
    return case


if __name__ == "__main__":
    for name in (sys.argv[1:] or LAWS):
        build(name).write(HERE / name)
        print(f"wrote {HERE / name / 'DATBOX'}  steps {sum(schedule(name)[:2])}")
