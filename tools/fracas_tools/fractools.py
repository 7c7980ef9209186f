"""Helpers of the fracture validation cases (test_cases/validation_fracture/*/gen.py and
check.py): structured meshes, the energy-audit check, the reference of each case.

Results are read with fracas_tools.fracture.MeshRun (on top of fracas_tools.post.Run,
the one fracas.h5 reader); checks print one line per quantity with
fracas_tools.checks.Checker.
"""

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]     # the repository (tools/fracas_tools/ is two levels down)

from .checks import Checker  # noqa: F401
from .fracture import MeshRun  # noqa: F401
# Deck helpers of the package's cohesive module, re-exported for the gen.py scripts.
from .cohesive import mp3_separation_opening, perturb_nodes, safe_alert, smooth_ramp  # noqa: F401

__all__ = ["ROOT", "Checker", "MeshRun", "Grid", "structured_quads", "check_energy", "growth_energy",
           "run_dir_from_argv", "smooth_ramp", "edge_traction", "perturb_nodes", "safe_alert", "mp3_separation_opening",
           "tip_speed", "crack_arms", "crack_angle", "wave_speeds", "williams_chi"]


class Grid:
    """A structured grid of quadrilaterals on [x0, x1] x [y0, y1] (nx x ny cells):
    ``nodes`` (n, 2), ``elements`` (Q4 corners counter-clockwise, or Q8 corners then
    mid-sides), ``node(i, j)`` the node at grid point (i, j) of the (order*nx+1) x
    (order*ny+1) lattice (Q8: the cell-centre lattice points are not nodes), and
    ``edges(side)`` the corner pairs of the cell edges along a side ('bottom',
    'top', 'left', 'right'), optionally restricted to x or y ranges."""

    def __init__(self, x0, x1, y0, y1, nx, ny, order=1, first=0):
        self.x0, self.x1, self.y0, self.y1, self.nx, self.ny, self.order = x0, x1, y0, y1, nx, ny, order
        o = order
        xs = np.linspace(x0, x1, o * nx + 1)
        ys = np.linspace(y0, y1, o * ny + 1)
        self._id = -np.ones((o * nx + 1, o * ny + 1), dtype=int)
        nodes = []
        for j in range(o * ny + 1):
            for i in range(o * nx + 1):
                if o == 2 and i % 2 == 1 and j % 2 == 1:
                    continue                      # Q8: no node at the cell centre
                self._id[i, j] = first + len(nodes)
                nodes.append((xs[i], ys[j]))
        self.nodes = np.array(nodes)
        self.elements = []
        for j in range(ny):
            for i in range(nx):
                a, b = o * i, o * j
                corners = [self.node(a, b), self.node(a + o, b), self.node(a + o, b + o), self.node(a, b + o)]
                if o == 2:
                    corners += [self.node(a + 1, b), self.node(a + 2, b + 1), self.node(a + 1, b + 2),
                                self.node(a, b + 1)]
                self.elements.append(tuple(corners))

    def node(self, i, j):
        return int(self._id[i, j])

    def side_nodes(self, side):
        o = self.order
        if side == "bottom":
            return [self.node(i, 0) for i in range(o * self.nx + 1)]
        if side == "top":
            return [self.node(i, o * self.ny) for i in range(o * self.nx + 1)]
        if side == "left":
            return [self.node(0, j) for j in range(o * self.ny + 1)]
        if side == "right":
            return [self.node(o * self.nx, j) for j in range(o * self.ny + 1)]
        raise ValueError(side)

    def edges(self, side, lo=-np.inf, hi=np.inf):
        """Corner pairs (a, b) of the cell edges on a side whose middle lies in [lo, hi]
        (x for bottom/top, y for left/right)."""
        o = self.order
        out = []
        if side in ("bottom", "top"):
            j = 0 if side == "bottom" else o * self.ny
            for i in range(self.nx):
                xm = self.nodes[self.node(o * i, j) - self._first, 0] * 0.5 + \
                    self.nodes[self.node(o * i + o, j) - self._first, 0] * 0.5
                if lo <= xm <= hi:
                    out.append((self.node(o * i, j), self.node(o * i + o, j)))
        else:
            i = 0 if side == "left" else o * self.nx
            for j in range(self.ny):
                ym = 0.5 * (self.nodes[self.node(i, o * j) - self._first, 1] +
                            self.nodes[self.node(i, o * j + o) - self._first, 1])
                if lo <= ym <= hi:
                    out.append((self.node(i, o * j), self.node(i, o * j + o)))
        return out

    @property
    def _first(self):
        return int(self._id[0, 0])


def structured_quads(grids):
    """Concatenate Grids built with consecutive ``first`` offsets: (nodes, elements)."""
    nodes = np.vstack([g.nodes for g in grids])
    elements = [e for g in grids for e in g.elements]
    return nodes, elements


def edge_traction(bodies, group, traction):
    """Nodal forces of a uniform traction (Pa, vector (tx, ty)) on the boundary
    edges of an edge group: each edge of length l adds traction * l / 2 to its two
    node copies, on the body that owns it (exploded meshes: every element carries
    its own share). Constant force drives (DRV_DOF force, applied from t = 0).
    Returns the total force."""
    total = np.zeros(2)
    for b in bodies:
        forces = {}
        for p, q in b.edge_groups.get(group, []):
            length = float(np.hypot(*(b.nodes[q - 1] - b.nodes[p - 1])))
            for n in (p, q):
                forces[n] = forces.get(n, np.zeros(2)) + 0.5 * length * np.asarray(traction, dtype=float)
        for n, f in sorted(forces.items()):
            for dof in (1, 2):
                if f[dof - 1] != 0.0:
                    b.impose_force([n], (dof,), ct=float(f[dof - 1]))
            total += f
    return total


def williams_chi(young, poisson):
    """Williams's (1989) root-rotation factor chi of an isotropic beam arm (the crack
    length of beam theory is corrected to a + chi h for mode I, a + 0.42 chi h for ENF
    (Wang & Williams 1992)); the transverse shear modulus of the arm is E / (2 (1 + nu))."""
    g = young / (2.0 * (1.0 + poisson))
    gamma = 1.18 * young / g
    return np.sqrt(young / (11.0 * g)) * (3.0 - 2.0 * (gamma / (1.0 + gamma)) ** 2)


def ramped_displacement(t, t_ramp, v):
    """Displacement of a drive whose velocity follows smooth_ramp up to v: the integral
    of v (1 - cos(pi t / t_ramp)) / 2, then v (t - t_ramp / 2)."""
    return np.where(t < t_ramp, 0.5 * v * (t - t_ramp / np.pi * np.sin(np.pi * t / t_ramp)),
                    v * (t - 0.5 * t_ramp))


def load_from_work(t, work, delta, window):
    """Load P = dW/dDelta of a displacement drive from its work W(t), by central
    differences over `window` seconds either side (W is a time integral: the
    structure's vibration averages out). Returns the rows used and P there."""
    win = max(1, int(round(window / (t[1] - t[0]))))
    i = np.arange(win, len(t) - win)
    return i, (work[i + win] - work[i - win]) / (delta[i + win] - delta[i - win])


def growth_energy(series, window, gc):
    """Damage dissipated per broken length in units of gc: the slope of a least-squares
    line through (crack length, damage dissipated) at the steps where an interface point
    breaks (the process zone is then in the same state each time, which the ends of a
    window are not), among the steps of window (boolean, per step of the series).
    Returns (slope, break events, (first, last crack length))."""
    c, dd = series["crack_length"], series["damage_dissipated"]
    events = np.nonzero(np.diff(c) > 0.0)[0] + 1
    on = events[window[events]]
    slope = np.polyfit(c[on], dd[on] / gc, 1)[0]
    return float(slope), len(on), (c[on][0], c[on][-1])


def check_energy(ck, series, tol=0.01, what="energy audit"):
    """The energy audit of a run, against the energy in play (the largest of the
    external work and of kinetic + elastic + plastic + cohesive + dissipated):
    max |balance_error| below tol, and the contacts create no energy: the
    dissipation other than damage (friction, impacts; `dissipated` -
    `damage_dissipated`) never below -tol. The second check catches an NLGS left
    unconverged on a stiff cohesive network, whose impulses violate the laws while
    the audit still balances (the spurious work is booked as negative dissipation).
    Returns (balance ratio, lowest non-damage dissipation ratio)."""
    s = series
    work = np.abs(s["work_gravity"]) + np.abs(s["work_forces"]) + np.abs(s["work_supports"])
    held = s["kinetic_energy"] + s["elastic_energy"] + s["plastic_work"] + s["cohesive_energy"] + \
        np.abs(s["dissipated"])
    scale = max(float(np.max(work)), float(np.max(held)), 1e-300)
    ratio = float(np.max(np.abs(s["balance_error"]))) / scale
    ck.at_most(f"{what}: max |balance_error| / energy", ratio, tol,
               note=f"energy scale {scale:.4g} J/m")
    other = float(np.min(s["dissipated"] - s["damage_dissipated"])) / scale
    ck.at_most(f"{what}: -min(dissipated - damage) / energy", -other, tol,
               note="contacts create no energy")
    return ratio, other


def wave_speeds(young, poisson, rho):
    """(c_d, c_s, c_R) in m/s of an isotropic solid in plane strain: dilatational,
    shear, and Rayleigh speed, the root of (2 - x)^2 = 4 sqrt(1 - x) sqrt(1 - k x)
    with x = (c_R/c_s)^2, k = (c_s/c_d)^2."""
    g = young / (2.0 * (1.0 + poisson))
    cs = (g / rho) ** 0.5
    cd = (young * (1.0 - poisson) / ((1.0 + poisson) * (1.0 - 2.0 * poisson)) / rho) ** 0.5
    k = (cs / cd) ** 2

    def f(x):
        return (2.0 - x) ** 2 - 4.0 * np.sqrt(1.0 - x) * np.sqrt(1.0 - k * x)

    lo, hi = 0.5, 1.0 - 1e-12
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(lo) * f(mid) > 0 else (lo, mid)
    return cd, cs, cs * (0.5 * (lo + hi)) ** 0.5


def tip_speed(mr, start, window, radius, min_arm=None):
    """Crack tip speeds of a meshed run (MeshRun), branching cracks included: at each
    snapshot the crack ends (crack_arms: ends farther than ``radius`` from ``start``,
    the notch tip, side pieces shorter than min_arm pruned); an end's advance over a
    window of at least ``window`` is its distance to the nearest end of the earlier
    snapshot (a new branch counts from the tip it left), so the speed of every arm is
    followed even when the longest crack's tip switches arms. Straight-line advances
    between snapshots: a lower bound of the path speed on curved paths, an upper bound
    on zig-zags along element edges. Returns a dict: max (over ends and windows),
    mean (advance of the end farthest from start between the first and the last
    snapshot at which it moved, over that time), t0, t1, ends (per snapshot)."""
    t = mr.times
    ends = []
    for i in range(len(mr.snapshot_names)):
        cr = mr.state(i).cracks
        ends.append(np.array(crack_arms(cr, start, radius, min_arm)) if cr is not None and len(cr["segments"])
                    else np.zeros((0, 2)))
    have = [i for i, e in enumerate(ends) if len(e)]
    if len(have) < 2:
        return dict(mean=0.0, max=0.0, t0=np.nan, t1=np.nan, ends=ends)
    best = 0.0
    for a in have:
        b = next((k for k in have if t[k] - t[a] >= window * (1.0 - 1e-9)), None)
        if b is None:
            break
        adv = max(float(np.min(np.hypot(*(ends[a] - e).T))) for e in ends[b])
        best = max(best, adv / (t[b] - t[a]))
    far = np.array([np.max(np.hypot(*(ends[i] - start).T)) if len(ends[i]) else np.nan for i in range(len(t))])
    moved = [i for i in have[1:] if far[i] > far[have[0]]]
    t0, t1 = t[have[0]], t[moved[-1]] if moved else t[have[0]]
    mean = (far[moved[-1]] - far[have[0]]) / (t1 - t0) if moved else 0.0
    return dict(mean=mean, max=best, t0=t0, t1=t1, ends=ends)


def _crack_graph(cracks):
    """Adjacency (dict vertex -> set of vertices) of all crack segments."""
    adj = {}
    for a, b in np.asarray(cracks["segments"], dtype=int):
        adj.setdefault(int(a), set()).add(int(b))
        adj.setdefault(int(b), set()).add(int(a))
    return adj


def crack_arms(cracks, start, radius, min_arm=None):
    """The ends of the cracks that come within ``radius`` of ``start`` (the notch
    tip), farther than ``radius`` from it, once dangling side pieces shorter than ``min_arm`` (default radius)
    are pruned (single broken edges beside a zig-zag path are not branches). A
    straight crack has one arm; a branched one two or more. Returns the end points."""
    min_arm = radius if min_arm is None else min_arm
    pts = np.asarray(cracks["points"], dtype=float)
    adj = _crack_graph(cracks)
    # only the cracks that reach the start (within radius): others are not its arms
    todo = [v for v in adj if np.hypot(*(pts[v] - start)) <= radius]
    keep = set(todo)
    while todo:
        v = todo.pop()
        for w in adj[v]:
            if w not in keep:
                keep.add(w)
                todo.append(w)
    adj = {v: n for v, n in adj.items() if v in keep}
    changed = True
    while changed:
        changed = False
        for leaf in [v for v, n in adj.items() if len(n) == 1]:
            if leaf not in adj or len(adj[leaf]) != 1:
                continue
            chain, length, v, came = [leaf], 0.0, leaf, None
            while True:
                nxt = [w for w in adj[v] if w != came]
                if len(adj[v]) > 2 or not nxt or (v != leaf and len(adj[v]) == 1):
                    break
                came, v = v, nxt[0]
                length += float(np.hypot(*(pts[v] - pts[came])))
                chain.append(v)
            if len(adj[v]) > 2 and length < min_arm:
                for a, b in zip(chain[:-1], chain[1:]):
                    adj[a].discard(b)
                    adj[b].discard(a)
                for w in chain[:-1]:
                    if not adj.get(w):
                        adj.pop(w, None)
                changed = True
    ends = [v for v, n in adj.items() if len(n) == 1 and np.hypot(*(pts[v] - start)) > radius]
    return [pts[v] for v in ends]


def crack_angle(cracks, start, r_min, r_max):
    """Direction (degrees from +x, counter-clockwise) of the crack leaving ``start``:
    the angle of the least-squares line through the crack vertices between r_min and
    r_max from start, within the crack containing the vertex nearest start; also the
    number of vertices used. Returns (angle, n)."""
    pts = np.asarray(cracks["points"], dtype=float)
    if len(pts) == 0:
        return np.nan, 0
    adj = _crack_graph(cracks)
    first = int(np.argmin(np.hypot(*(pts - start).T)))
    seen, todo = {first}, [first]
    while todo:
        v = todo.pop()
        for w in adj.get(v, ()):
            if w not in seen:
                seen.add(w)
                todo.append(w)
    sel = np.array(sorted(seen))
    d = pts[sel] - start
    r = np.hypot(d[:, 0], d[:, 1])
    d = d[(r >= r_min) & (r <= r_max)]
    if len(d) < 2:
        return np.nan, len(d)
    # direction through start: principal direction of the offsets, oriented outwards
    u = np.linalg.svd(d, full_matrices=False)[2][0]
    if np.dot(d.mean(axis=0), u) < 0:
        u = -u
    return float(np.degrees(np.arctan2(u[1], u[0]))), len(d)


def run_dir_from_argv(default=None):
    if len(sys.argv) > 1:
        return Path(sys.argv[1])
    if default is None:
        raise SystemExit("usage: check.py RUN_DIR")
    return Path(default)
