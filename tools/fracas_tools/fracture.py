"""Meshed bodies and cracks in a Fracas results file (OUTBOX/fracas.h5), on top of
:class:`fracas_tools.results.Run` (the one reader of fracas.h5; this module only adds the
groups meshed runs write: /mesh, and per snapshot mesh_X, mesh_V, mesh_gauss_points,
cracks; doc/output_layout.md and doc/fracture.md).

    from fracas_tools.fracture import MeshRun
    mr = MeshRun("case_dir")                  # or a post.Run, or the .h5 path
    mr.series["crack_length"]                 # per step (post.Run.series)
    s = mr.state(-1)                          # last snapshot: X, V (nn, 2), gp (ngp, 13)
    s.cracks["main_tip"], s.cracks["crack_length"]
    mr.element_mean(s.gp, "sxx")              # one value per element
    t, tip = mr.tip_history()                 # main crack tip (reference) per snapshot

Arrays are 0-based numpy arrays in Python's row order: nodes (nn, 2), Gauss points
(ngp, nfields), element connectivity as a list of node index arrays.
"""

from dataclasses import dataclass

import numpy as np

from .mailx import VTK_CORNERS
from .results import Run, _attr

__all__ = ["MeshRun", "MeshState", "von_mises", "plot_fragment_sizes"]


def _rows(a, ncols):
    """A Fortran (ncols, n) array as read by h5py, as (n, ncols)."""
    a = np.asarray(a, dtype=float)
    if a.ndim == 1:
        return a.reshape(-1, ncols)
    if a.shape[-1] != ncols and a.shape[0] == ncols:
        return a.T
    return a


@dataclass
class MeshState:
    """One snapshot of the meshed bodies: step, time, nodal displacement X and
    velocity V (nn, 2), Gauss-point values gp (ngp, nfields), the cracks group
    as a dict (None when the run has no cohesive interfaces), and F_support
    (nn, 2), the force the velocity drives apply on their nodes (zero on free
    dofs; None when nothing is driven)."""
    name: str
    step: int
    time: float
    X: np.ndarray
    V: np.ndarray
    gp: np.ndarray
    cracks: dict
    F_support: np.ndarray = None


def von_mises(gp, fields):
    """Von Mises stress of Gauss-point rows (plane: sxx, syy, sxy, szz)."""
    i = {f: k for k, f in enumerate(fields)}
    sx, sy, sxy, sz = gp[:, i["sxx"]], gp[:, i["syy"]], gp[:, i["sxy"]], gp[:, i["szz"]]
    return np.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2) + 3.0 * sxy ** 2)


class MeshRun:
    """The meshed part of a run. ``source``: a post.Run, a case directory or the
    fracas.h5 path. Attributes: run (the post.Run), series, ref (nn, 2) reference
    node coordinates, body_nodes (list of node index ranges per body),
    elements (list of 0-based node index arrays), element_body, element_gp
    (first Gauss point per element, + end), gauss_fields (names), families
    (interface family names, index 0 = family 1 of the outputs), plane."""

    def __init__(self, source):
        self.run = source if isinstance(source, Run) else Run(source)
        f = self.run.file
        if "mesh" not in f:
            raise ValueError(f"{self.run.path}: no /mesh group (no meshed bodies)")
        g = f["mesh"]
        self.series = self.run.series
        self.ref = _rows(g["reference"][()], 2)
        bfn = np.asarray(g["body_first_node"][()], dtype=int) - 1
        bfe = np.asarray(g["body_first_element"][()], dtype=int) - 1
        efn = np.asarray(g["element_first_node"][()], dtype=int) - 1
        en = np.asarray(g["element_nodes"][()], dtype=int) - 1
        self.body_nodes = [np.arange(bfn[b], bfn[b + 1]) for b in range(len(bfn) - 1)]
        self.elements = [en[efn[e]:efn[e + 1]] for e in range(len(efn) - 1)]
        self.element_body = np.repeat(np.arange(len(bfe) - 1), np.diff(bfe))
        self.element_gp = np.asarray(g["element_first_gauss_point"][()], dtype=int) - 1
        self.element_vtk_type = np.asarray(g["element_vtk_type"][()], dtype=int)
        self.element_material = np.asarray(g["element_material"][()], dtype=int)
        attrs = {k: _attr(v) for k, v in g.attrs.items()}
        self.gauss_fields = str(attrs.get("gauss_point_fields", "")).split()
        self.families = str(attrs.get("interface_families", "")).split()
        self.plane = attrs.get("plane", "strain")
        self.snapshot_names = self.run.snapshot_names
        self.times = np.array([t for _, t in self.run.snapshot_times()])
        self.steps = np.array([s for s, _ in self.run.snapshot_times()], dtype=int)

    @property
    def n_nodes(self):
        return len(self.ref)

    @property
    def n_elements(self):
        return len(self.elements)

    def field(self, name):
        """Column index of a Gauss-point field ('sxx', 'p', ...)."""
        return self.gauss_fields.index(name)

    def state(self, which=-1):
        """The MeshState of a snapshot (index, negative from the end, or group name)."""
        name = which if isinstance(which, str) else self.snapshot_names[which]
        g = self.run.file["snapshots"][name]
        X = _rows(g["mesh_X"][()], 2)
        V = _rows(g["mesh_V"][()], 2)
        gp = _rows(g["mesh_gauss_points"][()], len(self.gauss_fields)) if "mesh_gauss_points" in g \
            else np.zeros((0, len(self.gauss_fields)))
        cracks = None
        if "cracks" in g:
            c = g["cracks"]
            cracks = {k: np.asarray(c[k][()]) for k in c if hasattr(c[k], "shape")}   # datasets (not fragments/)
            cracks["points"] = _rows(cracks["points"], 2) if cracks["points"].size else np.zeros((0, 2))
            cracks["segments"] = (np.asarray(cracks["segments"], dtype=int).reshape(-1, 2) - 1
                                  if cracks["segments"].size else np.zeros((0, 2), dtype=int))
            cracks["fragments"] = int(_attr(c.attrs.get("fragments", 0)))
        fs = _rows(g["mesh_F_support"][()], 2) if "mesh_F_support" in g else None
        return MeshState(name, int(_attr(g.attrs.get("step", 0))), float(_attr(g.attrs.get("time", np.nan))),
                         X, V, gp, cracks, fs)

    def nodes_at(self, xy, tol, where=None):
        """Indices of the nodes whose reference position satisfies ``where``
        (a function of x, y arrays returning a mask), or lies within ``tol`` of
        the point ``xy`` when where is None. Exploded meshes copy a node per
        element: all copies are returned."""
        x, y = self.ref[:, 0], self.ref[:, 1]
        mask = where(x, y) if where is not None else np.hypot(x - xy[0], y - xy[1]) <= tol
        return np.flatnonzero(mask)

    def positions(self, state):
        """Current node positions (nn, 2)."""
        return self.ref + state.X

    def element_mean(self, gp, name):
        """Mean of a Gauss-point field over each element's Gauss points."""
        col = gp[:, self.field(name)] if isinstance(name, str) else np.asarray(name)
        sums = np.add.reduceat(col, self.element_gp[:-1])
        return sums / np.diff(self.element_gp)

    def element_von_mises(self, gp):
        """Von Mises stress per element (mean over its Gauss points)."""
        return self.element_mean(gp, von_mises(gp, self.gauss_fields))

    def element_centroids(self, X=None):
        """Mean of each element's corner nodes (reference, or displaced by X)."""
        xy = self.ref if X is None else self.ref + X
        return np.array([xy[n[:VTK_CORNERS[t]]].mean(axis=0) for n, t in zip(self.elements, self.element_vtk_type)])

    def element_displacement(self, X, elements):
        """Mean nodal displacement of the corner nodes of each element listed."""
        out = []
        for e in np.atleast_1d(elements):
            n = self.elements[e][:VTK_CORNERS[self.element_vtk_type[e]]]
            out.append(X[n].mean(axis=0))
        return np.array(out)

    def tip_history(self):
        """(times, tips (ns, 2), lengths (ns,)): the main crack's tip and length
        per snapshot (reference configuration); NaN where no crack exists yet."""
        tips, lengths = [], []
        for name in self.snapshot_names:
            g = self.run.file["snapshots"][name]
            if "cracks" not in g or g["cracks/crack_length"].size == 0:
                tips.append([np.nan, np.nan])
                lengths.append(0.0)
                continue
            tips.append(np.asarray(g["cracks/main_tip"][()], dtype=float))
            lengths.append(float(np.asarray(g["cracks/crack_length"][()])[0]))
        return self.times.copy(), np.array(tips).reshape(-1, 2), np.array(lengths)

    def fragments(self, which=-1):
        """The fragments of a snapshot (index, negative from the end, or group name) as
        {name: array}, one row per fragment (doc/output_layout.md §5): bodies,
        elements, mass, centre (nf, 2), velocity (nf, 2), kinetic_energy,
        second_moments (nf, 3: Jxx, Jyy, Jxy), polar_moment, principal_moments
        (nf, 2), principal_angle. Empty dict when the snapshot has none."""
        name = which if isinstance(which, str) else self.snapshot_names[which]
        g = self.run.file["snapshots"][name]
        if "cracks/fragments" not in g:
            return {}
        f = g["cracks/fragments"]
        out = {k: np.asarray(f[k][()]) for k in f}
        for k, nc in (("centre", 2), ("velocity", 2), ("second_moments", 3), ("principal_moments", 2)):
            out[k] = _rows(out[k], nc)
        return out

    def close(self):
        self.run.close()

    def __enter__(self):
        return self

    def __exit__(self, *a):
        self.close()


def plot_fragment_sizes(mr, out, max_curves=6):
    """The fragment-size distribution over time: the number of fragments per step
    (series fragments) and, for up to max_curves snapshots, the fraction of fragments
    of mass at least m against m / total mass. Returns the PNG path."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from pathlib import Path
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    s = mr.series
    if "fragments" in s and "time" in s:
        a1.step(s["time"], s["fragments"], where="post")
    a1.set_xlabel("time")
    a1.set_ylabel("fragments")
    a1.grid(True, alpha=0.3)
    names = mr.snapshot_names
    picks = sorted(set(np.linspace(0, len(names) - 1, min(len(names), max_curves)).round().astype(int))) \
        if names else []
    for i in picks:
        fr = mr.fragments(i)
        if not fr:
            continue
        m = np.sort(fr["mass"])[::-1]
        a2.step(m / m.sum(), np.arange(1, len(m) + 1) / len(m), where="post",
                label=f"t = {mr.times[i]:.3g} ({len(m)})")
    a2.set_xscale("log")
    a2.set_xlabel("fragment mass / total mass")
    a2.set_ylabel("fraction of fragments at least that heavy")
    a2.grid(True, alpha=0.3)
    if a2.lines:
        a2.legend(fontsize=8)
    fig.tight_layout()
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=120)
    plt.close(fig)
    return out
