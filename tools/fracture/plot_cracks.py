#!/usr/bin/python3
"""Draw the crack paths of a meshed run (fracas.h5) over the mesh, for the doc.

    plot_cracks.py RUN_DIR OUT.png [--snapshot -1] [--field von_mises|none]
                   [--deform 0] [--title TEXT]

The elements are coloured by the field (von Mises stress, mean over each element's
Gauss points) in the current configuration scaled by --deform (0: reference), the
broken interfaces drawn as black lines (the crack polylines of /snapshots/N/cracks),
the notch/pre-crack edges are simply the gaps the mesh leaves.
"""
import argparse
import sys
from pathlib import Path

import numpy as np

from fracas_tools.fractools import MeshRun  # noqa: E402


def draw(mr, ax, which=-1, field="von_mises", deform=0.0, cmap="viridis", vmax=None, crack_color="k",
         linewidth=1.2):
    """Draw one snapshot on a matplotlib axis; returns the collection (for a colour bar)."""
    from matplotlib.collections import LineCollection, PolyCollection
    s = mr.state(which)
    xy = mr.ref + deform * s.X
    polys = [xy[n[:4] if len(n) in (4, 8) else n[:3]] for n in mr.elements]
    coll = None
    if field != "none":
        vals = mr.element_von_mises(s.gp) if field == "von_mises" else mr.element_mean(s.gp, field)
        coll = PolyCollection(polys, array=vals, cmap=cmap, edgecolors="none")
        if vmax is not None:
            coll.set_clim(0.0, vmax)
        ax.add_collection(coll)
    else:
        ax.add_collection(PolyCollection(polys, facecolors="0.85", edgecolors="0.6", linewidths=0.2))
    cr = s.cracks
    if cr is not None and len(cr["segments"]):
        pts = cr["points"] if deform == 1.0 else None
        if pts is None:
            # crack vertices are written in the current configuration: map back by
            # the mean displacement of the nearest nodes is overkill; redraw from the
            # current points shifted to the chosen deformation scale
            cur = cr["points"]
            # nearest reference node of each vertex (crack vertices are mesh nodes)
            idx = np.array([np.argmin(np.sum((mr.ref + s.X - p) ** 2, axis=1)) for p in cur])
            pts = mr.ref[idx] + deform * s.X[idx]
        segs = pts[cr["segments"]]
        ax.add_collection(LineCollection(segs, colors=crack_color, linewidths=linewidth))
    lo, hi = mr.ref.min(axis=0), mr.ref.max(axis=0)
    pad = 0.02 * (hi - lo).max()
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    return coll, s


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run")
    ap.add_argument("out")
    ap.add_argument("--snapshot", type=int, default=-1)
    ap.add_argument("--field", default="von_mises")
    ap.add_argument("--deform", type=float, default=0.0)
    ap.add_argument("--title", default=None)
    ap.add_argument("--mm", action="store_true", help="axes in mm")
    a = ap.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    mr = MeshRun(a.run)
    fig, ax = plt.subplots(figsize=(7, 5))
    coll, s = draw(mr, ax, a.snapshot, a.field, a.deform)
    if coll is not None:
        fig.colorbar(coll, ax=ax, label="von Mises stress (Pa)" if a.field == "von_mises" else a.field)
    if a.mm:
        from matplotlib.ticker import FuncFormatter
        mm = FuncFormatter(lambda v, _: f"{v * 1e3:g}")
        ax.xaxis.set_major_formatter(mm)
        ax.yaxis.set_major_formatter(mm)
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
    ax.set_title(a.title or f"t = {s.time * 1e6:.1f} us")
    fig.tight_layout()
    fig.savefig(a.out, dpi=120)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    from fracas_tools.cli import run_main  # bad input: a message, not a traceback
    sys.exit(run_main(main, "plot_cracks.py"))
