#!/usr/bin/python3
"""Check the spall run (README.md): per bar, where and when the first interface is
damaged and the first one breaks, against the wave analysis (one element, 5 % in
time); nothing damaged while the compressive pulse travels; the energy audit.

    check.py RUN_DIR [quick|fine]
"""
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
import gen  # noqa: E402
from fracas_tools.fractools import Checker, MeshRun, check_energy, run_dir_from_argv  # noqa: E402


def main():
    variant = sys.argv[2] if len(sys.argv) > 2 else "quick"
    n = gen.VARIANTS[variant]["n"]
    element = gen.L / n
    mr = MeshRun(run_dir_from_argv())
    ck = Checker(f"fracture spall ({variant})")
    # reference x of each body (exploded: body = element) and its bar
    cent = mr.element_centroids()
    body_x = np.array([cent[mr.element_body == b, 0].mean() for b in range(len(mr.body_nodes))])
    body_bar = np.array([int(cent[mr.element_body == b, 1].mean() // (3 * gen.H)) for b in range(len(mr.body_nodes))])
    bars = list(gen.BARS)
    first_damage, first_break = {}, {}
    for i in range(len(mr.snapshot_names)):
        snap = mr.run.snapshot(i)
        c = snap.contacts
        beta = c["internals"][:, 3]
        cd, an = c["cd_body"] - 1, c["an_body"] - 1
        x_if = 0.5 * (body_x[cd] + body_x[an])          # the interface between the two elements
        gone = {}
        cr = mr.state(i).cracks
        for k, ph in enumerate(bars):
            mine = body_bar[cd] == k
            damaged = mine & (beta < 1.0)
            if ph not in first_damage and damaged.any():
                first_damage[ph] = (snap.time, np.unique(np.round(x_if[damaged] / element)) * element)
        if cr is not None and len(cr["segments"]):
            mid = cr["points"][cr["segments"]].mean(axis=1)
            for k, ph in enumerate(bars):
                mine = (mid[:, 1] > 3 * k * gen.H - gen.H) & (mid[:, 1] < 3 * k * gen.H + 2 * gen.H)
                if ph not in first_break and mine.any():
                    # broken edges in the current configuration: back to the interface grid
                    first_break[ph] = (snap.time, np.unique(np.round(mid[mine, 0] / element)) * element)
        del gone
    t_reflect = gen.L / gen.C_WAVE
    for ph in bars:
        x_ref, t_ref = gen.prediction(ph)
        t2, q = gen.BARS[ph]
        tag = f"bar T2 = {t2 * 1e6:g} us, q = {q:g}"
        if ph not in first_damage or ph not in first_break:
            ck.true(f"{tag}: the bar breaks", False)
            continue
        td, xd = first_damage[ph]
        tb, xb = first_break[ph]
        ck.true(f"{tag}: no damage before the reflection", td > t_reflect, ours=f"{td * 1e6:.2f} us",
                ref=f"> {t_reflect * 1e6:.2f} us")
        ck.close(f"{tag}: first damage x (mm)", xd.mean() * 1e3, x_ref * 1e3, element * 1e3,
                 note=f"interfaces {', '.join(f'{v * 1e3:.1f}' for v in xd)} mm")
        ck.rel(f"{tag}: first damage t (us)", td * 1e6, t_ref * 1e6, 0.05)
        ck.close(f"{tag}: first break x (mm)", xb.mean() * 1e3, x_ref * 1e3, element * 1e3,
                 note=f"interfaces {', '.join(f'{v * 1e3:.1f}' for v in xb)} mm")
        ck.rel(f"{tag}: first break t (us)", tb * 1e6, t_ref * 1e6, 0.05)
    last = mr.state(-1).cracks
    ck.true("fragments at the end", last["fragments"] >= 4, ours=last["fragments"], ref=">= 4 (2 per bar)")
    check_energy(ck, mr.series)
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
