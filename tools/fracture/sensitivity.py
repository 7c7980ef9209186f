#!/usr/bin/python3
"""Mesh and time-step sensitivity of one crack path (doc/fracture.md): the
Kalthoff-Winkler case (test_cases/validation_fracture/kalthoff) on four meshes
(lc = 3, 2.5, 2, 1.5 mm at dt = 0.25 us) and two time steps (dt = 0.25, 0.125 us at
lc = 2.5 mm): crack angle at the notch tip, where the tip is at 60 us, the tip speed,
the energy audit, the run time. Takes about 35 min on one idle core (not in ctest;
results committed in doc/fracture.md).

    sensitivity.py WORK_DIR [--fracas build/release/bin/fracas] [--png OUT.png] [--reuse]
    sensitivity.py WORK_DIR --seeds N [--sizes lc3.0_dt0.25,lc2.5_dt0.25,...] [--reuse]

--seeds N: mesh statistics instead: each mesh size with N node perturbations (seeds
1..N, gen.py's third argument), the angle's mean and spread per size (issue 17).
--topology: with --seeds, each seed also another triangulation (gmsh at an element size
within 5 % of the size's, drawn with the seed: gen.build(topology=True)).
A seed whose mesh gen.build refuses (alert below 1.5 full-separation openings: most
triangulations at lc = 1 mm, --sizes lc1.0_dt0.25) is skipped for the next one; the
table lists the seeds used.
"""
import argparse
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
from fracas_tools.scripts import load  # noqa: E402
gen = load(ROOT / "test_cases" / "validation_fracture" / "kalthoff" / "gen.py")   # the Kalthoff deck
from fracas_tools.fractools import MeshRun, crack_angle, tip_speed, wave_speeds  # noqa: E402


def measure(run_dir, p):
    mr = MeshRun(run_dir)
    cracks = mr.state(-1).cracks
    angle, n = crack_angle(cracks, gen.NOTCH_TIP, *gen.ANGLE_RANGE)
    speed = tip_speed(mr, gen.NOTCH_TIP, gen.SPEED_WINDOW, 2.0 * p["lc"])
    ends = speed["ends"][-1]
    far = ends[np.argmax(np.hypot(*(ends - gen.NOTCH_TIP).T))] if len(ends) else [np.nan, np.nan]
    s = mr.series
    work = np.abs(s["work_supports"]) + np.abs(s["work_forces"])
    held = s["kinetic_energy"] + s["elastic_energy"] + s["cohesive_energy"] + np.abs(s["dissipated"])
    closure = float(np.max(np.abs(s["balance_error"]))) / max(float(np.max(work)), float(np.max(held)))
    cr = wave_speeds(gen.E, gen.NU, gen.RHO)[2]
    out = dict(angle=angle, n=n, tip=far, t0=speed["t0"], mean=speed["mean"] / cr, max=speed["max"] / cr,
               closure=closure, bodies=len(mr.body_nodes), damage=float(s["damage_dissipated"][-1]))
    mr.close()
    return out, cracks


def mesh_statistics(a, work):
    """The crack angle on a.seeds meshes of each size (seeded node perturbations)."""
    print("| lc (mm) | seeds | angles (°) | mean (°) | spread (std, °) | run time per mesh (s) |")
    print("| --- | --- | --- | --- | --- | --- |")
    sizes = {}
    for name in a.sizes.split(","):
        p = gen.SENSITIVITY[name]
        angles, walls, paths, seeds = [], [], [], []
        seed = 0
        # Seeds in order until a.seeds meshes: a mesh whose worst element forbids an alert
        # above 1.5 full-separation openings is refused by gen.build (lc = 1 mm: most).
        while len(seeds) < a.seeds and seed < 10 * a.seeds:
            seed += 1
            d = work / f"{name}_{'topo' if a.topology else 'seed'}{seed}"
            t = time.time()
            if a.reuse and not (d / "OUTBOX").is_dir():
                continue
            if not a.reuse:
                try:
                    case = gen.build(name, seed, topology=a.topology)
                except SystemExit as refused:
                    print(f"{name} seed {seed}: no deck ({refused})", file=sys.stderr, flush=True)
                    continue
                case.write(d)
                subprocess.run([a.fracas, "-q", "--overwrite", str(d)], check=True)
            seeds.append(seed)
            walls.append(time.time() - t)
            m, cracks = measure(d, p)
            angles.append(m["angle"])
            paths.append(cracks)
        ang = np.array(angles)
        sizes[p["lc"]] = (ang, paths)
        print(f"| {p['lc'] * 1e3:g} | {', '.join(map(str, seeds))} | {', '.join(f'{x:.1f}' for x in ang)} | {np.nanmean(ang):.1f} | "
              f"{np.nanstd(ang, ddof=1):.1f} | {np.mean(walls):.0f} |", flush=True)
    if a.png:
        plot_statistics(sizes, a.png)


def plot_statistics(sizes, png):
    """Angle per mesh against the element size (mean and sample std), and the crack paths
    of every mesh of each size."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection
    fig, axes = plt.subplots(1, len(sizes) + 1, figsize=(3.6 * (len(sizes) + 1), 3.8))
    ax = axes[0]
    ax.axhspan(65, 75, color="0.9", label="70 ± 5 (experiments)")
    for lc, (ang, _) in sorted(sizes.items()):
        ax.plot([lc * 1e3] * len(ang), ang, "o", color="C0", alpha=0.6)
        ax.errorbar(lc * 1e3 + 0.08, np.nanmean(ang), yerr=np.nanstd(ang, ddof=1), fmt="s", color="C3", capsize=4)
    ax.set_xlabel("element size lc (mm)")
    ax.set_ylabel("crack angle (deg)")
    ax.set_title("one dot per mesh; mean ± std", fontsize=9)
    ax.legend(fontsize=7, loc="lower left")
    for ax, (lc, (ang, paths)) in zip(axes[1:], sorted(sizes.items(), reverse=True)):
        for k, cr in enumerate(paths):
            ax.add_collection(LineCollection(cr["points"][cr["segments"]] * 1e3, colors=[plt.cm.tab10(k)],
                                             linewidths=1.0))
        ax.plot([0, 50], [25, 25], "k", lw=2)
        th = np.radians(70.0)
        ax.plot([50, 50 + 40 * np.cos(th)], [25, 25 + 40 * np.sin(th)], "k--", lw=0.8)
        ax.set_xlim(30, 100)
        ax.set_ylim(10, 100)
        ax.set_aspect("equal")
        ax.set_title(f"lc {lc * 1e3:g} mm: {', '.join(f'{x:.0f}' for x in ang)} deg", fontsize=9)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    print(f"wrote {png}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("work")
    ap.add_argument("--fracas", default=str(ROOT / "build" / "release" / "bin" / "fracas"))
    ap.add_argument("--png", default=None)
    ap.add_argument("--reuse", action="store_true", help="measure the runs already in WORK_DIR")
    ap.add_argument("--seeds", type=int, default=0, help="mesh statistics: N meshes per size")
    ap.add_argument("--sizes", default="lc3.0_dt0.25,lc2.5_dt0.25,lc2.0_dt0.25")
    ap.add_argument("--topology", action="store_true", help="with --seeds: another triangulation per seed")
    a = ap.parse_args()
    work = Path(a.work)
    if a.seeds:
        return mesh_statistics(a, work)
    rows, paths = [], {}
    for name, p in gen.SENSITIVITY.items():
        d = work / name
        t = time.time()
        if not a.reuse:
            gen.build(name).write(d)
            subprocess.run([a.fracas, "-q", "--overwrite", str(d)], check=True)
        wall = time.time() - t
        m, cracks = measure(d, p)
        paths[name] = cracks
        m.update(name=name, lc=p["lc"], dt=p["dt"], wall=wall)
        rows.append(m)
        print(f"{name}: angle {m['angle']:.1f} deg ({m['n']} vertices), tip at 60 us ({m['tip'][0] * 1e3:.1f}, "
              f"{m['tip'][1] * 1e3:.1f}) mm, seen first {m['t0'] * 1e6:.0f} us, speed mean {m['mean']:.2f} "
              f"max {m['max']:.2f} c_R, closure {m['closure']:.1e}, {m['bodies']} bodies, {wall:.0f} s", flush=True)
    print("\n| lc (mm) | dt (µs) | elements | angle (°) | tip at 60 µs (mm) | crack seen first (µs) | "
          "mean / max tip speed (c_R) | energy closure | run time (s) |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for m in rows:
        print(f"| {m['lc'] * 1e3:g} | {m['dt'] * 1e6:g} | {m['bodies']} | {m['angle']:.1f} | "
              f"({m['tip'][0] * 1e3:.1f}, {m['tip'][1] * 1e3:.1f}) | {m['t0'] * 1e6:.0f} | "
              f"{m['mean']:.2f} / {m['max']:.2f} | {m['closure']:.1e} | {m['wall']:.0f} |")
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 6))
        for name, cr in paths.items():
            segs = cr["points"][cr["segments"]] * 1e3
            from matplotlib.collections import LineCollection
            color = plt.cm.tab10(list(paths).index(name))
            ax.add_collection(LineCollection(segs, colors=[color], linewidths=1.2, label=name))
        ax.plot([0, 50], [25, 25], "k", lw=2)
        th = np.radians(70.0)
        ax.plot([50, 50 + 40 * np.cos(th)], [25, 25 + 40 * np.sin(th)], "k--", lw=0.8, label="70 deg")
        ax.set_xlim(0, 100)
        ax.set_ylim(0, 100)
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
        ax.legend(loc="upper left", fontsize=8)
        ax.set_title("Kalthoff-Winkler: crack paths at 60 us")
        fig.tight_layout()
        fig.savefig(a.png, dpi=110)
        print(f"wrote {a.png}")


if __name__ == "__main__":
    main()
