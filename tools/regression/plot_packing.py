#!/usr/bin/env python3
"""Picture of a disk packing from a Fracas run: disks as circles, JONCx walls as
rounded bars, and the force chains (segments between the centres of the two
bodies of each loaded contact, width proportional to the normal force).

    build/release/bin/fracas-python tools/regression/plot_packing.py RUN_DIR --case CASE_DIR -o out.png
        [--snapshot -1] [--no-forces] [--title TEXT] [--series series.png]

With ``--series`` a second figure shows the time series of the run: kinetic energy,
contacts (listed and loaded), NLGS sweeps per step and solve time per step.
"""

import argparse
import math
import sys
from pathlib import Path

import numpy as np

import tagged  # noqa: E402
from fracas_tools import datbox  # noqa: E402  (the one DATBOX reader)


def read_contactors(bodies_dat):
    """Per body: list of (type, values) of its rigid contactors (DISKx: radius; JONCx:
    ax1, ax2; others: none), read by fracas_tools.datbox."""
    out = []
    for body in datbox.read_bodies(bodies_dat):
        cs = []
        for c in getattr(body, "contactors", []):
            kind = getattr(c, "kind", None)
            if kind == "DISKx":
                cs.append((kind, [c.radius]))
            elif kind == "JONCx":
                cs.append((kind, [c.ax1, c.ax2]))
            elif kind is not None:
                cs.append((kind, []))
        out.append(cs)
    return out


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("run_dir")
    p.add_argument("--case", required=True)
    p.add_argument("-o", "--output", required=True)
    p.add_argument("--snapshot", type=int, default=-1, help="snapshot index (default: last)")
    p.add_argument("--no-forces", action="store_true")
    p.add_argument("--title")
    p.add_argument("--dpi", type=int, default=150)
    p.add_argument("--series", metavar="PNG", help="also plot the time series into PNG")
    a = p.parse_args(argv)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection, PatchCollection
    from matplotlib.patches import Circle, Polygon

    case = Path(a.case)
    tact = read_contactors(case / "DATBOX" / "BODIES.DAT")
    with tagged.Run(tagged.find_h5(a.run_dir)) as f:
        ref = f.bodies["reference"]
        s = f.snapshot(a.snapshot)
        step, time = s.step, s.time
        X = s.X
        c = s.contacts
        cd = c["cd_body"] - 1
        an = c["an_body"] - 1
        rn = c["reaction"][:, 1]
        pt = c["point"]
    nc = len(rn)
    if len(tact) != len(ref):
        raise SystemExit("plot_packing.py: BODIES.DAT and fracas.h5 disagree on the number of bodies")
    pos = ref + X
    # X is the displacement from the reference (it includes DOF.INI rotations of the walls)

    fig, ax = plt.subplots(figsize=(6.4, 7.2))
    disks, walls = [], []
    is_disk = np.zeros(len(tact), bool)
    for i, cs in enumerate(tact):
        for kind, vals in cs:
            if kind == "DISKx":
                disks.append(Circle((pos[i, 0], pos[i, 1]), vals[0]))
                is_disk[i] = True
            elif kind == "JONCx":
                ax1, ax2 = vals[0], vals[1]
                th = pos[i, 2]
                ct, st = math.cos(th), math.sin(th)
                corners = np.array([[-ax1, -ax2], [ax1, -ax2], [ax1, ax2], [-ax1, ax2]])
                R = np.array([[ct, -st], [st, ct]])
                walls.append(Polygon(corners @ R.T + pos[i, :2], closed=True))
    ax.add_collection(PatchCollection(walls, facecolor="0.55", edgecolor="0.3", linewidth=0.5))
    ax.add_collection(PatchCollection(disks, facecolor="#d9e6f2", edgecolor="#5b7fa6", linewidth=0.3))
    if not a.no_forces and nc:
        loaded = rn > 0
        segs, widths = [], []
        rmax = rn[loaded].max() if loaded.any() else 1.0
        for k in np.flatnonzero(loaded):
            i, j = cd[k], an[k]
            p0 = pos[i, :2] if is_disk[i] else pt[k]
            p1 = pos[j, :2] if is_disk[j] else pt[k]
            segs.append([p0, p1])
            widths.append(0.2 + 3.0 * rn[k] / rmax)
        ax.add_collection(LineCollection(segs, linewidths=widths, colors="#b2182b",
                                         capstyle="round"))
    allx = np.concatenate([p.get_xy()[:, 0] for p in walls] + [pos[is_disk, 0]])
    ally = np.concatenate([p.get_xy()[:, 1] for p in walls] + [pos[is_disk, 1]])
    top = float(np.max(pos[is_disk, 1])) + 0.05 * (allx.max() - allx.min())
    ax.set_xlim(allx.min(), allx.max())
    ax.set_ylim(ally.min(), min(ally.max(), top))
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    title = a.title or f"{case.name}: step {step}, t = {time:.3f} s"
    if not a.no_forces:
        title += "\nforce chains: width ∝ normal force"
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    Path(a.output).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(a.output, dpi=a.dpi)
    print(f"plot_packing.py: wrote {a.output}")
    if a.series:
        plot_series(a.run_dir, a.series, a.dpi)
    return 0


def plot_series(run_dir, out, dpi=100):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    with tagged.Run(tagged.find_h5(run_dir)) as f:
        s = f.series
    t = s["time"]
    fig, axs = plt.subplots(3, 1, figsize=(6.4, 6.4), sharex=True)
    axs[0].semilogy(t, np.maximum(s["kinetic_energy"], 1e-16), color="k")
    axs[0].set_ylabel("kinetic energy")
    axs[1].plot(t, s["contacts"], label="listed (gap < alert)")
    if "active_contacts" in s:
        axs[1].plot(t, s["active_contacts"], label="loaded (r != 0)")
    axs[1].set_ylabel("contacts")
    axs[1].legend(fontsize=8)
    axs[2].semilogy(t, s["sweeps"], color="C2", label="sweeps per step")
    axs[2].set_ylabel("NLGS sweeps", color="C2")
    if "solve_time" in s:
        ax2 = axs[2].twinx()
        ax2.semilogy(t, np.maximum(s["solve_time"], 1e-6), color="C3", lw=0.6)
        ax2.set_ylabel("solve time per step (s)", color="C3")
    axs[2].set_xlabel("time (s)")
    fig.tight_layout()
    fig.savefig(out, dpi=dpi)
    print(f"plot_packing.py: wrote {out}")


if __name__ == "__main__":
    sys.exit(main())
