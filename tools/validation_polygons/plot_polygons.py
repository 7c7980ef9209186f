#!/usr/bin/python3
"""Pictures of polygon runs drawn from the run output (fracas.h5 snapshots) and the
deck's geometry (DATBOX), for doc/validation_polygons.md (doc/img/poly_*.png).

    plot_polygons.py wall  CASE_DIR RUN_DIR OUT.png    # masonry_wall demo, 4 times
    plot_polygons.py arch  CASE_DIR RUN_DIR OUT.png    # arch demo, 3 times + forces
    plot_polygons.py heyman CASE_DIR RUN_DIR OUT.png   # arch_heyman: stand vs collapse
    plot_polygons.py all                               # runs the three decks into /tmp
                                                       # and redraws doc/img/poly_*.png
Needs numpy, h5py, matplotlib (the system /usr/bin/python3).
"""
import math
import subprocess
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools import polytools as pt  # noqa: E402

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection, LineCollection  # noqa: E402


def outlines(case, pos):
    """List of (body index, (n, 2) outline) of every contactor at positions pos (nb, 3)."""
    out = []
    for i, b in enumerate(case.bodies):
        x, y, a = pos[i]
        c, s = math.cos(a), math.sin(a)
        rot = np.array([[c, -s], [s, c]])
        for ct in b.contactors:
            if ct.kind == "POLYG":
                v = ct.vertices
            elif ct.kind == "JONCx":
                v = pt.rect(2 * ct.ax1, 2 * ct.ax2)
            elif ct.kind == "DISKx":
                t = np.linspace(0, 2 * np.pi, 33)[:-1]
                v = ct.radius * np.column_stack((np.cos(t), np.sin(t)))
            else:
                continue
            out.append((i, v @ rot.T + np.array([x, y])))
    return out


def driven_mask(case):
    return np.array([len(b.driven) >= 3 for b in case.bodies])


def draw(ax, case, res, k, colors=None, forces=False, title=None, lim=None):
    pos = res.position[k]
    fixed = driven_mask(case)
    polys, fc = [], []
    for i, v in outlines(case, pos):
        polys.append(v)
        if colors is not None:
            fc.append(colors[i])
        else:
            fc.append("0.55" if fixed[i] else "#d9a066")
    ax.add_collection(PolyCollection(polys, facecolors=fc, edgecolors="k", linewidths=0.4))
    if forces and res.contacts:
        c = res.contacts[k]
        rn = c["rn"]
        if len(rn) and rn.max() > 0:
            segs, lw = [], []
            for j in np.nonzero(rn > 0)[0]:
                for body in (c["cd"][j] - 1, c["an"][j] - 1):
                    if not fixed[body]:          # walls and supports: to the contact point only
                        segs.append([pos[body, :2], c["point"][j]])
                        lw.append(rn[j])
            lw = 3.0 * np.array(lw) / rn.max()
            ax.add_collection(LineCollection(segs, linewidths=lw, colors="darkred"))
    ax.set_aspect("equal")
    if lim is not None:
        ax.set_xlim(*lim[0])
        ax.set_ylim(*lim[1])
    else:
        ax.autoscale_view()
    ax.set_xticks([])
    ax.set_yticks([])
    if title:
        ax.set_title(title, fontsize=9)


def nearest(res, t):
    return int(np.argmin(np.abs(res.time - t)))


def plot_wall(case_dir, run_dir, out):
    from fracas_tools import datbox
    case = datbox.read_case(case_dir)
    res = pt.Results(run_dir)
    times = [0.0, 0.75, 1.25, 1.75, 3.0]
    fig, axes = plt.subplots(1, len(times), figsize=(13, 3.4))
    lim = ((-1.0, 1.9), (-0.25, 1.55))
    for ax, t in zip(axes, times):
        k = nearest(res, t)
        base = res.position[k, -1, 0] - res.ref[-1, 0]
        draw(ax, case, res, k, title=f"t = {res.time[k]:.2f} s, base at {100 * base:+.1f} cm", lim=lim)
    fig.suptitle("masonry_wall: 14 courses of bricks on a base shaken at 2 Hz, 0.6 m/s (0.77 g)", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def plot_arch(case_dir, run_dir, out):
    from fracas_tools import datbox
    case = datbox.read_case(case_dir)
    res = pt.Results(run_dir)
    times = [0.0, 0.48, 2.0]
    fig, axes = plt.subplots(1, len(times), figsize=(12, 3.8))
    lim = ((-1.9, 1.4), (-0.3, 1.45))
    for ax, t in zip(axes, times):
        k = nearest(res, t)
        draw(ax, case, res, k, forces=True, lim=lim,
             title=f"t = {res.time[k]:.2f} s (lines: contact forces)")
    fig.suptitle("arch: 25 voussoirs, t/R = 0.15, mu = 0.6; a 50 kg/m block dropped on the haunch",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def plot_heyman(case_dir, run_dir, out):
    from fracas_tools.scripts import load
    gen = load(Path(case_dir) / "gen.py")   # the arch_heyman deck parameters
    from fracas_tools import datbox
    case = datbox.read_case(case_dir)
    res = pt.Results(run_dir)
    times = [0.0, 0.3, 0.5]
    fig, axes = plt.subplots(2, len(times), figsize=(11, 5.2))
    for row, i in enumerate((0, 1)):
        (cx, cy), tr, _, kind = gen.ARCHES[i]
        lim = ((cx - 1.35, cx + 1.35), (cy - 0.35, cy + 1.2))
        for ax, t in zip(axes[row], times):
            k = nearest(res, t)
            draw(ax, case, res, k, lim=lim, forces=True,
                 title=f"t/R = {tr:.4f} ({kind}s), t = {res.time[k]:.2f} s")
    fig.suptitle("arch_heyman: 20 voussoirs, mu = 0.5, at 1.05 and 0.95 x 0.1075 R "
                 "(the thin one opens 5 hinges: springings, haunches, crown)", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def main():
    if len(sys.argv) >= 2 and sys.argv[1] == "all":
        root = pt.repo_root()
        img = root / "doc" / "img"
        jobs = [("wall", root / "test_cases/examples/masonry_wall", "poly_wall.png"),
                ("arch", root / "test_cases/examples/arch", "poly_arch.png"),
                ("heyman", root / "test_cases/validation/arch_heyman", "poly_arch_heyman.png")]
        for kind, case_dir, name in jobs:
            run = Path("/tmp") / f"poly_plot_{kind}"
            fracas = root / "build" / "release" / "bin" / "fracas"
            subprocess.run([str(fracas), "-q", "--overwrite", "--output", str(run), str(case_dir)], check=True)
            {"wall": plot_wall, "arch": plot_arch, "heyman": plot_heyman}[kind](case_dir, run, img / name)
            print(f"wrote {img / name}")
        return 0
    if len(sys.argv) != 5:
        print(__doc__)
        return 2
    kind, case_dir, run_dir, out = sys.argv[1:]
    {"wall": plot_wall, "arch": plot_arch, "heyman": plot_heyman}[kind](case_dir, run_dir, out)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
