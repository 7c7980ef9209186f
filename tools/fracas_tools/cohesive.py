"""Building cohesive (exploded-mesh) decks: what a deck needs besides fracas_tools.Case
(doc/fracture.md §1): the node perturbation that breaks a regular mesh's straight
lines, the widest safe alert distance of the see rules, the full-separation opening
of an MP3_CZM interface and a smooth drive ramp.

    from fracas_tools.cohesive import perturb_nodes, safe_alert, mp3_separation_opening, see_alert
    c = 50 * young / h                                    # cohesive stiffness, C h / E = 50 (doc/fracture.md §2)
    alert = see_alert(mesh, mp3_separation_opening(gc, smax, c))
"""

import numpy as np

__all__ = ["perturb_nodes", "safe_alert", "mp3_separation_opening", "see_alert", "smooth_ramp"]


def perturb_nodes(mesh, fraction, seed=1):
    """Move the interior nodes of a Mesh2D (not on the boundary nor on any edge
    group: notches and loaded edges stay straight) by a random offset uniform in a
    disc of radius fraction x the shortest edge at the node (seeded: the same mesh
    every time). Breaks the straight lines of a regular mesh, along which cracks
    would otherwise run (czm.md §4.2, nodal perturbation). Elements stay valid for
    fraction < 0.5; a node whose move would turn an element over is left in place."""
    from .mesh import Mesh2D
    rng = np.random.default_rng(seed)
    xy = mesh.nodes.copy()
    fixed = set()
    for key, sharing in mesh.edges().items():
        if len(sharing) == 1:
            fixed.update(key)
    for edges in mesh.edge_groups.values():
        for a, b in edges:
            fixed.update((a, b))
    shortest = np.full(len(xy), np.inf)
    around = [[] for _ in range(len(xy))]
    for e, (kind, nodes) in enumerate(mesh.elements):
        nc = 3 if kind.startswith("T") else 4
        c = nodes[:nc]
        for k in range(nc):
            a, b = c[k], c[(k + 1) % nc]
            d = float(np.hypot(*(xy[a] - xy[b])))
            shortest[a] = min(shortest[a], d)
            shortest[b] = min(shortest[b], d)
            around[a].append(e)

    def area(e, pts):
        kind, nodes = mesh.elements[e]
        c = pts[list(nodes[:3 if kind.startswith("T") else 4])]
        return 0.5 * np.sum(c[:, 0] * np.roll(c[:, 1], -1) - np.roll(c[:, 0], -1) * c[:, 1])

    for n in range(len(xy)):
        r = fraction * shortest[n] * np.sqrt(rng.random())
        phi = 2.0 * np.pi * rng.random()
        if n in fixed or not np.isfinite(shortest[n]):
            continue
        old = xy[n].copy()
        xy[n] = old + r * np.array([np.cos(phi), np.sin(phi)])
        if any(area(e, xy) <= 0.0 for e in around[n]):
            xy[n] = old
    return Mesh2D(xy, mesh.elements, mesh.phases, {k: v.tolist() for k, v in mesh.node_groups.items()},
                  mesh.edge_groups)


def safe_alert(mesh, apab=(0.25, 0.75)):
    """The largest alert distance that glues every CLxxx point of an exploded mesh
    to its own partner only: the smallest distance from a candidate point (at apab
    on an element edge) to another edge of an element sharing a corner with it.
    The see rules glue, at the first step, every candidate/antagonist pair of the
    family within the alert distance, whatever its gap: a wider alert glues a point
    to a neighbour's edge with a gap of the order of the alert, an initially
    stretched spring (a large spurious energy). The alert should also exceed the
    law's full-separation opening, so that a contact is not dropped before it is
    broken."""
    edges_at = {}
    for kind, nodes in mesh.elements:
        nc = 3 if kind.startswith("T") else 4
        c = nodes[:nc]
        for k in range(nc):
            e = (c[k], c[(k + 1) % nc])
            for n in e:
                edges_at.setdefault(n, set()).add((min(e), max(e)))
    xy = mesh.nodes
    best = np.inf
    for (a, b), _ in mesh.edges().items():
        others = (edges_at[a] | edges_at[b]) - {(a, b)}
        for s in apab:
            p = (1.0 - s) * xy[a] + s * xy[b]
            for c, d in others:
                u = xy[d] - xy[c]
                t = np.clip(np.dot(p - xy[c], u) / np.dot(u, u), 0.0, 1.0)
                best = min(best, float(np.hypot(*(p - xy[c] - t * u))))
    return best


def mp3_separation_opening(gc, smax, c):
    """Opening at full separation of an MP3_CZM interface (energy gc, strength smax,
    stiffness c): the elastic opening smax / c plus the softening branch's 1.5 gc / smax
    (czm.md). Alert distances of the cohesive see rules are set from it."""
    return 1.5 * gc / smax + smax / c


def smooth_ramp(t_ramp, n=41, t_end=1.0e3):
    """(t, f) points of f = (1 - cos(pi t / t_ramp)) / 2 up to t_ramp, then 1: a drive
    that starts with zero acceleration and reaches its value without a kink (few
    waves excited)."""
    t = np.linspace(0.0, t_ramp, n)
    f = 0.5 * (1.0 - np.cos(np.pi * t / t_ramp))
    return np.vstack([np.append(t, t_end), np.append(f, 1.0)]).T


def see_alert(mesh, d_c, factor=10.0):
    """The alert distance of the cohesive see rules: factor x the full-separation
    opening d_c (a contact is not dropped before it is broken), capped at half of
    safe_alert(mesh) (no point glued to a neighbour's edge). The validation cases and
    the demos use it. Raises ValueError when even d_c does not fit under that cap (the
    mesh is too fine for the law: a smaller opening, or a coarser mesh)."""
    cap = 0.5 * safe_alert(mesh)
    if d_c >= cap:
        raise ValueError(f"the full-separation opening {d_c:g} does not fit under half the safe alert "
                         f"{cap:g} of this mesh: raise C or smax, or coarsen the mesh")
    return min(factor * d_c, cap)
