#!/usr/bin/python3
"""Results of a hydrided-plate run (tools/hydride/hydride_plate.py): the macro-crack and
where it runs, microcracks, force-displacement curve, energy split; a picture.

    build/release/bin/fracas-python tools/hydride/hydride_post.py CASE_DIR [--deck DECK_DIR] [--json OUT.json] [--png OUT.png]

Reads CASE_DIR/hydrides.json (the microstructure), CASE_DIR/OUTBOX/fracas.h5 (the
interface edges and their state, the energy series) and CASE_DIR/POSTPRO/Dep_, Fint_
(the two pulled edges).

Definitions (doc/hydrided_zircaloy.md §4):

* broken interface: an interface edge whose glued points all have beta = 0 (fracas'
  cracks/edge_broken_step > 0);
* macro-crack: the path of interface edges from the edge the notch cuts (or the
  notch itself) to the opposite edge that leaves the least length unbroken, and then
  is the shortest (reference lengths). A fully broken path across is exactly what
  separates the plate in two (``separated``); otherwise the unbroken length left on
  it is the ``ligament`` still bridging the crack;
* shares: the broken length of the macro-crack through hydrides (HY_HY edges), along
  matrix/hydride interfaces (HY_MA) and through the matrix (MA_MA), over its broken
  length;
* microcracks: broken edges off the macro-crack (count, length per family, and the
  number of connected clusters they form).
"""
import argparse
import json
import sys
from pathlib import Path

import numpy as np

from fracas_tools.results import Run  # noqa: E402

FAMILY_LABEL = {"HY_HY": "through hydrides", "HY_MA": "along matrix/hydride interfaces",
                "MA_MA": "through the matrix"}
FAMILY_COLOR = {"HY_HY": "#1f3fbf", "HY_MA": "#f08c00", "MA_MA": "#d62728"}
PHASE_COLOR = {"matrix": "#dcdcdc", "hydride": "#9ec5e8"}


class PlateRun:
    """One run's mesh, interfaces and final state (or snapshot ``snapshot``, 1-based,
    negative from the end), read with fracas_tools.results. case_dir holds OUTBOX/ and
    POSTPRO/; deck_dir (default case_dir) the generator's hydrides.json (the run may be
    written elsewhere with fracas --output)."""

    def __init__(self, case_dir, snapshot=-1, deck_dir=None):
        self.case_dir = Path(case_dir)
        self.info = json.loads((Path(deck_dir or case_dir) / "hydrides.json").read_text())
        with Run(self.case_dir) as run:
            self.complete = int(run.complete)
            m = run.mesh
            self.ref = m["reference"]                                      # (nn, 2)
            self.body_first_node = m["body_first_node"]                    # 1-based, nb + 1
            self.element_nodes = m["element_nodes"].reshape(-1, 3) - 1     # T3, 0-based
            self.families = run.mesh_attrs["interface_families"].split()
            self.edge_nodes = m["interface_edge_nodes"] - 1                 # (ne, 2) 0-based
            self.edge_family = np.array(self.families)[m["interface_edge_family"] - 1]
            self.edge_length = m["interface_edge_length"]
            self.series = run.series
            # CPU seconds of the process (reading, setup, time loop; the loop's only at a normal end)
            cpu = [run.attrs.get(k) for k in ("read_cpu_seconds", "setup_cpu_seconds", "loop_cpu_seconds")]
            self.cpu_seconds = float(sum(cpu)) if all(c is not None for c in cpu) else float("nan")
            snap = run.snapshot(snapshot if snapshot < 0 else snapshot - 1)
            self.step, self.time = snap.step, snap.time
            self.X = snap.mesh["X"]
            c = snap.mesh["cracks"]
            self.edge_broken_step = c["edge_broken_step"]
            self.edge_beta = c["edge_beta"]
            self.damage_per_family = dict(zip(self.families, c["damage_per_family"]))
            self.fragment_of_body = c["fragment_of_body"]
            self.gauss = snap.mesh["gauss_points"]
        nb = len(self.body_first_node) - 1
        self.node_body = np.repeat(np.arange(nb), np.diff(self.body_first_node))
        centroids = self.ref[self.element_nodes].mean(axis=1)
        self.phase = np.full(len(self.element_nodes), "matrix", dtype=object)
        for x, y, length, t in self.info["hydrides"]:
            inside = ((centroids[:, 0] > x) & (centroids[:, 0] < x + length)
                      & (centroids[:, 1] > y) & (centroids[:, 1] < y + t))
            self.phase[inside] = "hydride"

    @property
    def geometry(self):
        return self.info["geometry"]

    def broken(self):
        return self.edge_broken_step > 0


# --------------------------------------------------------------------------------------
# the macro-crack
# --------------------------------------------------------------------------------------

def _vertices(points, tol):
    """Vertex index of each point, points closer than tol merged (copies of a node)."""
    keys = np.round(points / tol).astype(np.int64)
    _, index = np.unique(keys, axis=0, return_inverse=True)
    return index.reshape(-1)


#: weight of an unbroken interface edge on the macro-crack path, per unit length (a
#: broken edge weighs 1): the path takes the least unbroken length, then the shortest
LIGAMENT_WEIGHT = 1000.0


def macro_crack(run):
    """The macro-crack (module docstring): the path of interface edges across the plate,
    from the edge the notch cuts (or the notch) to the opposite edge, that leaves the
    least length unbroken, then the shortest. Edges weigh their length times 1 when
    broken, 1 + LIGAMENT_WEIGHT/2 when some of their points are broken (a hinge), 1 +
    LIGAMENT_WEIGHT when intact. Returns a dict: path edges (indices into the interface
    edges), length per family of its broken part and shares, the unbroken ligament left
    on it (separated when none), how far across the broken part reaches from the start
    (reach, 0..1), the microcracks (broken edges off the path, their clusters)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components, dijkstra

    geo = run.geometry
    direction = run.info["loading"]["direction"]
    across = 1 if direction == "x" else 0          # the crack crosses the plate along this axis
    extent = geo["height"] if direction == "x" else geo["width"]
    h = run.info["h_mean"]
    broken = run.broken()
    hinge = (run.edge_beta == 0.0) & ~broken
    ends = run.ref[run.edge_nodes].reshape(-1, 2)
    vert = _vertices(ends, 1e-3 * h).reshape(-1, 2)
    nv = int(vert.max()) + 1
    vpos = np.zeros((nv, 2))
    vpos[vert.reshape(-1)] = ends
    length = run.edge_length
    w = length * np.where(broken, 1.0, np.where(hinge, 1.0 + 0.5 * LIGAMENT_WEIGHT, 1.0 + LIGAMENT_WEIGHT))
    graph = coo_matrix((np.r_[w, w], (np.r_[vert[:, 0], vert[:, 1]], np.r_[vert[:, 1], vert[:, 0]])),
                       shape=(nv, nv)).tocsr()
    eps = 1e-3 * h
    a = vpos[:, across]
    sources = a < eps
    notch = geo.get("notch", 0.0)
    if notch > 0:
        other = 1 - across
        mid = 0.5 * (geo["width"] if other == 0 else geo["height"])
        sources |= (np.abs(vpos[:, other] - mid) < eps) & (a <= notch + eps)
    targets = a > extent - eps
    dist, pred, _ = dijkstra(graph, indices=np.nonzero(sources)[0], min_only=True, return_predecessors=True)
    end = int(np.argmin(np.where(targets, dist, np.inf)))
    pair_edge = {}
    for k, (p, q) in enumerate(vert):
        key = (min(p, q), max(p, q))
        if key not in pair_edge or w[k] < w[pair_edge[key]]:
            pair_edge[key] = k
    path = []
    v = end
    while pred[v] >= 0:
        u = pred[v]
        path.append(pair_edge[(min(u, v), max(u, v))])
        v = u
    path = np.array(path[::-1], dtype=int)           # from the start to the far edge
    on_broken = path[broken[path]]
    fam_len = {f: float(length[on_broken][run.edge_family[on_broken] == f].sum()) for f in FAMILY_LABEL}
    total = sum(fam_len.values())
    ligament = float(length[path[~broken[path]]].sum())
    # reach: how far across the broken part runs from the start without a gap
    reach = 0.0
    if len(path):
        first_gap = np.nonzero(~broken[path])[0]
        upto = path[:first_gap[0]] if len(first_gap) else path
        if len(upto):
            reach = float(vpos[vert[upto]].reshape(-1, 2)[:, across].max() / extent)
    off = broken.copy()
    off[path] = False
    micro_len = {f: float(length[off & (run.edge_family == f)].sum()) for f in FAMILY_LABEL}
    clusters = 0
    if off.any():
        used, inv = np.unique(vert[off].reshape(-1), return_inverse=True)
        inv = inv.reshape(-1, 2)
        g = coo_matrix((np.ones(len(inv)), (inv[:, 0], inv[:, 1])), shape=(len(used), len(used)))
        clusters = int(connected_components(g, directed=False)[0])
    return dict(step=run.step, time=run.time, broken_edges=int(broken.sum()),
                broken_length=float(length[broken].sum()), separated=ligament == 0.0,
                path_edges=path.tolist(), path_length=total, ligament=ligament,
                length_per_family=fam_len,
                shares={f: (fam_len[f] / total if total > 0 else 0.0) for f in FAMILY_LABEL},
                reach=reach if ligament > 0 else 1.0, tortuosity=(total + ligament) / extent,
                microcracks=clusters, microcrack_edges=int(off.sum()), microcrack_length_per_family=micro_len)


# --------------------------------------------------------------------------------------
# curves and energies
# --------------------------------------------------------------------------------------

def force_displacement(run):
    """Nominal stress (drive force of the pulled edge / plate section, Pa) against the
    nominal strain (edge opening / plate length) from POSTPRO/Dep_, Fint_ (set 1 the
    edge pulled back, set 2 the edge pulled forward)."""
    pp = run.case_dir / "POSTPRO"
    d1 = np.loadtxt(pp / "Dep_0000001.DAT", ndmin=2)
    d2 = np.loadtxt(pp / "Dep_0000002.DAT", ndmin=2)
    f2 = np.loadtxt(pp / "Fint_0000002.DAT", ndmin=2)
    f1 = np.loadtxt(pp / "Fint_0000001.DAT", ndmin=2)
    n = min(len(d1), len(d2), len(f1), len(f2))
    geo = run.geometry
    k = 0 if run.info["loading"]["direction"] == "x" else 1
    length = geo["width"] if k == 0 else geo["height"]
    section = geo["height"] if k == 0 else geo["width"]
    opening = d2[:n, 1 + k] - d1[:n, 1 + k]
    force = 0.5 * (f2[:n, 9 + k] - f1[:n, 9 + k])       # Res: the drives' force, both edges averaged
    return dict(time=d1[:n, 0], opening=opening, force=force, strain=opening / length,
                stress=force / section)


def energies(run):
    """Final energy split (J/m, per unit thickness)."""
    s = run.series
    last = {k: float(v[-1]) for k, v in s.items()}
    damage = dict(run.damage_per_family)
    out = dict(work_supports=last["work_supports"], kinetic=last["kinetic_energy"],
               elastic=last["elastic_energy"], cohesive_stored=last["cohesive_energy"],
               plastic=last["plastic_work"], damage=last["damage_dissipated"],
               damage_per_family={f: float(damage.get(f, 0.0)) for f in FAMILY_LABEL},
               friction_and_numerical=last["dissipated"] - last["damage_dissipated"],
               balance_error=last["balance_error"])
    out["relative_balance_error"] = abs(out["balance_error"]) / max(abs(out["work_supports"]), 1e-300)
    out["damage_family_sum_error"] = abs(sum(damage.values()) - out["damage"]) / max(out["damage"], 1e-300)
    return out


def summary(case_dir, deck_dir=None):
    run = PlateRun(case_dir, deck_dir=deck_dir)
    crack = macro_crack(run)
    fd = force_displacement(run)
    en = energies(run)
    i = int(np.argmax(fd["stress"]))
    s = run.series
    return dict(case=str(case_dir), seed=run.info["seed"], bonding=run.info["bonding"],
                h=run.info["h"], h_mean=run.info["h_mean"], elements=run.info["elements"],
                contact_points=run.info["contact_points"], steps=int(s["step"][-1]),
                complete=run.complete, crack={k: v for k, v in crack.items() if k != "path_edges"},
                peak_stress=float(fd["stress"][i]), strain_at_peak=float(fd["strain"][i]),
                energies=en, cpu_seconds=run.cpu_seconds,             # fracas's own CPU time
                steps_wall_seconds=float(np.sum(s["step_time"])),      # wall time of the steps (a loaded machine inflates it)
                newton_iterations=float(np.mean(s["newton_iterations"])),
                sweeps=float(np.mean(s["sweeps"])),
                unconverged_steps=int(np.sum(s["converged"] == 0)))


# --------------------------------------------------------------------------------------
# picture
# --------------------------------------------------------------------------------------

def draw(run, ax, crack=None, magnify=1.0, legend=True, title=None):
    """The final microstructure (deformed, displacements x magnify): matrix and
    hydride elements, broken interfaces coloured by family (dotted: partly broken),
    the macro-crack thick."""
    from matplotlib.collections import LineCollection, PolyCollection
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    crack = crack or macro_crack(run)
    um = 1e6
    xy = (run.ref + magnify * run.X) * um
    tri = xy[run.element_nodes]
    colors = [PHASE_COLOR[p] for p in run.phase]
    ax.add_collection(PolyCollection(tri, facecolors=colors, edgecolors=colors, linewidths=0.2))
    broken = np.nonzero(run.broken())[0]
    hinge = np.nonzero((run.edge_beta == 0.0) & ~run.broken())[0]
    path = set(crack.get("path_edges", []))
    for edges, on_path, lw, style in ((broken, False, 0.7, "solid"), (broken, True, 2.2, "solid"),
                                      (hinge, False, 0.7, "dotted"), (hinge, True, 2.2, "dotted")):
        sel = [e for e in edges if (e in path) == on_path]
        if not sel:
            continue
        seg = xy[run.edge_nodes[sel]]
        ax.add_collection(LineCollection(seg, colors=[FAMILY_COLOR[run.edge_family[e]] for e in sel],
                                         linewidths=lw, linestyles=style))
    g = run.geometry
    ax.set_xlim(-0.05 * g["width"] * um, 1.05 * g["width"] * um)
    ax.set_ylim(-0.05 * g["height"] * um, 1.05 * g["height"] * um)
    ax.set_aspect("equal")
    ax.set_xlabel("x (µm)")
    ax.set_ylabel("y (µm)")
    if title:
        ax.set_title(title, fontsize=9)
    if legend:
        handles = [Patch(color=PHASE_COLOR[p], label=p) for p in PHASE_COLOR]
        handles += [Line2D([], [], color=FAMILY_COLOR[f], lw=2, label=f"{f} ({FAMILY_LABEL[f]})")
                    for f in FAMILY_LABEL]
        ax.legend(handles=handles, fontsize=6, loc="upper right", framealpha=0.85)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("case_dir")
    p.add_argument("--deck", help="folder of hydrides.json when the run was written elsewhere (fracas --output)")
    p.add_argument("--json", help="write the summary there")
    p.add_argument("--png", help="draw the final crack path there")
    a = p.parse_args(argv)
    s = summary(a.case_dir, deck_dir=a.deck)
    c = s["crack"]
    print(f"{a.case_dir}: {s['bonding']} seed {s['seed']}, {s['elements']} elements, step {s['steps']}; "
          f"macro-crack {'across' if c['separated'] else '(ligament %.1f µm left)' % (1e6 * c['ligament'])} "
          f"{c['path_length'] * 1e6:.1f} µm: " + ", ".join(
              f"{100 * c['shares'][f]:.0f} % {FAMILY_LABEL[f]}" for f in FAMILY_LABEL)
          + f"; {c['microcrack_edges']} broken edges off it in {c['microcracks']} microcracks; "
          f"peak {s['peak_stress'] / 1e6:.0f} MPa; balance error {s['energies']['relative_balance_error']:.1e}")
    if a.json:
        Path(a.json).write_text(json.dumps(s, indent=1) + "\n")
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(5, 5))
        run = PlateRun(a.case_dir, deck_dir=a.deck)
        draw(run, ax, title=f"{s['bonding']} bonding, seed {s['seed']}, step {s['steps']}")
        fig.tight_layout()
        fig.savefig(a.png, dpi=150)
    return 0


if __name__ == "__main__":
    from fracas_tools.cli import run_main  # bad input: a message, not a traceback
    sys.exit(run_main(main, "hydride_post.py"))
