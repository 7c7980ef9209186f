#!/usr/bin/python3
"""Reproducer (reported, not a ctest): energy booking of a compressed cohesive spring.

Two glued 1 m x 1 m POLYG blocks, lower fixed, upper driven in y and rotation (x free; y velocity
-1e-4 m/s for 100 steps of 1e-4 s, i.e. pressed 1e-6 m into the lower one, then +1e-4 m/s
back for 100 steps). Signorini cannot act between two driven bodies, so the cohesive
normal spring -h L beta^k cn un acts on the negative jump un and pushes back
(rn = cn |un| L). Its energy (L/2) beta^k cn un^2 is not counted in cohesive_energy
(czm_stored_energy uses <un>+), so it is booked as damage_dissipated with beta = 1 (no
damage), and damage_dissipated then DEcreases when the spring is released.
Expected: cohesive_energy = (L/2) beta^k cn un^2 (0.0505 J/m at the deepest point),
damage_dissipated ~ 0 (only the O(h) spring term) and never decreasing.

usage: repro_gap_compression.py FRACAS_BIN [WORK_DIR]
"""
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parents[0])]
from czmlaws import Law  # noqa: E402
from fracas_tools import Case  # noqa: E402


def main():
    import h5py
    fracas = sys.argv[1]
    work = Path(sys.argv[2] if len(sys.argv) > 2 else "/tmp/fracas_czm_repro")
    for name, law_name, law in (("mp3", "MP3_CZM", Law.mp3(cn=1e11, ct=1e11, smax=1e6, w=40.0)),
                                ("iqs_mac", "IQS_MAC_CZM", Law.mac(cn=1e11, ct=1e11, b=0.0, w=40.0))):
        case = Case(gravity=(0.0, 0.0))
        case.add_material("STONE", density=2000.0)
        law.add_to(case, "czm01", law_name, 0.5)
        case.add_see("POLYG", "BLEUx", "POLYG", "BLEUx", "czm01", 0.01)
        case.add_polygon([(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)], "STONE").fix()
        up = case.add_polygon([(-0.5, 0.5), (0.5, 0.5), (0.5, 1.5), (-0.5, 1.5)], "STONE")
        v = 1e-4
        up.impose_evolution(2, "vlocy", "vy.dat", data=[[0, -v], [0.01, -v], [0.0101, v], [0.03, v]])
        up.impose_velocity(3)
        case.run.set(time_step=1e-4, number_of_steps=200, theta=0.5, output_hdf5_every=1,
                     output_dof_every=0, progress_every=0)
        case.write(work / name)
        subprocess.run([fracas, "-q", "--overwrite", str(work / name)], check=True)
        with h5py.File(work / name / "OUTBOX" / "fracas.h5", "r") as f:
            s, sn = f["series"], f["snapshots"]
            keys = sorted(sn)
            print(f"== {law_name}")
            for i in (0, 99, 199):
                c = sn[keys[i]]["contacts"]
                print(f"step {i + 1:3d}: un = {c['internals'][0, 2]: .4e}  beta = {c['internals'][0, 3]:.3f}  "
                      f"sum rn = {c['reaction'][:, 1].sum(): .4e}  cohesive_energy = {s['cohesive_energy'][i]:.4e}  "
                      f"damage_dissipated = {s['damage_dissipated'][i]:.4e}")


if __name__ == "__main__":
    main()
