"""Post-processing of Fracas results (OUTBOX/fracas.h5): reading, micro-mechanics
(packing fraction, coordination number, fabric tensor), plots and a Markdown report.

    from fracas_tools import post
    run = post.Run("my_case")                 # or "my_case/OUTBOX/fracas.h5"
    run.series["kinetic_energy"]              # one value per step
    snap = run.snapshot(-1)                   # last snapshot
    post.coordination(run, snap)              # {'z': ..., 'z_mech': ..., ...}
    post.fabric(run, snap)                    # {'F': 2x2, 'anisotropy': ..., ...}
    post.packing_fraction(run, snap)          # solid fraction in a window
    post.report("my_case")                    # my_case/report/report.md + PNGs

Units are SI. Bodies are 2D with unit thickness, so masses are kg/m, forces N/m and
energies J/m (per metre of thickness).

Positions: /bodies/reference holds the reference configuration (BODIES.DAT node
coordinates) and snapshot X the displacement from it (doc/output_layout.md, as
LMGC90's DOF files): position = reference + X. An attribute ``meaning`` or
``description`` on bodies/X saying 'position' (or Run(path, x_is='position'))
makes X read as absolute positions instead.

Series: all columns are read as float64 and cut to the shortest length (a run that
crashed between two flushes may leave them differing by one row).
"""

import math
from pathlib import Path

import numpy as np

# The one reader of fracas.h5 (fracas_tools.results); re-exported here for older scripts.
from .results import Run, Snapshot, open_run, _attr, _h5py, _resolve_h5, _strings  # noqa: F401

__all__ = ["Run", "Snapshot", "open_run", "particle_mask", "active_contacts", "coordination",
           "fabric", "packing_fraction", "microstructure_evolution", "summary",
           "summary_table", "plot_energy", "plot_energy_balance", "plot_solver", "plot_contacts",
           "plot_force_network", "plot_fabric", "plot_microstructure", "report", "check_h5",
           "body_outlines"]

ACTIVE_STATUS = {"stick", "slifw", "slibw", "Cstck", "Cslfw", "Cslbw", "Cnctc"}


def _plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


# --------------------------------------------------------------------------------------
# micro-mechanics
# --------------------------------------------------------------------------------------

def particle_mask(run):
    """Bodies that are grains (not walls, drums or fully driven bodies). With the
    case's DATBOX: bodies whose contactors are DISKx/POLYG and whose three
    velocities are not all driven. Without it, from /bodies: a grain has a radius
    at most 4 times the median radius and a compact shape, sqrt(inertia/mass)
    <= 1.2 avrd (0.71 avrd for a disk, 0.7-0.85 avrd for usual polygons and
    bricks, more for elongated JONCx walls)."""
    nb = run.n_bodies
    case = run.deck()
    if case is not None:
        m = np.zeros(nb, dtype=bool)
        for i, b in enumerate(case.bodies):
            kinds = {c.kind for c in b.contactors}
            driven = {d.dof for d in b.driven if d.kind == "vlocy"}
            m[i] = kinds <= {"DISKx", "POLYG"} and driven != {1, 2, 3}
        return m
    r = np.asarray(run.bodies.get("radius", np.ones(nb)), dtype=float)
    if len(r) == 0:
        return np.zeros(0, dtype=bool)
    m = r <= 4.0 * np.median(r)
    if "mass" in run.bodies and "inertia" in run.bodies:
        mass = np.asarray(run.bodies["mass"], dtype=float)
        inertia = np.asarray(run.bodies["inertia"], dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            k = np.sqrt(inertia / mass) / r
        m &= ~(np.isfinite(k) & (k > 1.2))
    return m


def active_contacts(snap):
    """Contacts carrying a force (non-zero reaction)."""
    R = snap.contacts["reaction"]
    if len(R) == 0:
        return np.zeros(0, dtype=bool)
    return (R[:, 0] != 0.0) | (R[:, 1] != 0.0)


def _pair_indices(run, snap):
    ci = run.body_index(snap.contacts["cd_body"]) if snap.n_contacts else np.zeros(0, int)
    ai = run.body_index(snap.contacts["an_body"]) if snap.n_contacts else np.zeros(0, int)
    return ci, ai


def coordination(run, snap, mask=None):
    """Coordination numbers of the grains at a snapshot, counting force-carrying
    contacts and distinct body pairs (two contact points of a polygon face count
    once). z: mean number of contacts (grain and wall) per grain; z_grains: mean
    grain-grain contacts per grain; z_mech: z over grains with at least 2
    contacts (rattlers removed); rattler_fraction."""
    mask = particle_mask(run) if mask is None else mask
    ng = int(mask.sum())
    out = {"n_grains": ng, "z": float("nan"), "z_grains": float("nan"), "z_mech": float("nan"),
           "rattler_fraction": float("nan"), "grain_contacts": 0, "wall_contacts": 0}
    if ng == 0:
        return out
    act = active_contacts(snap)
    ci, ai = _pair_indices(run, snap)
    ok = act & (ci >= 0) & (ai >= 0)
    ci, ai = ci[ok], ai[ok]
    pairs = {(min(a, b), max(a, b)) for a, b in zip(ci, ai) if a != b}
    count = np.zeros(run.n_bodies, dtype=int)
    cgrain = np.zeros(run.n_bodies, dtype=int)
    ngg = nwall = 0
    for a, b in pairs:
        ga, gb = mask[a], mask[b]
        if ga and gb:
            ngg += 1
            cgrain[a] += 1
            cgrain[b] += 1
        elif ga or gb:
            nwall += 1
        if ga:
            count[a] += 1
        if gb:
            count[b] += 1
    cg = count[mask]
    out.update(z=float(cg.mean()), z_grains=float(cgrain[mask].mean()),
               grain_contacts=ngg, wall_contacts=nwall)
    nonr = cg >= 2
    out["rattler_fraction"] = float(1.0 - nonr.mean())
    out["z_mech"] = float(cg[nonr].mean()) if nonr.any() else float("nan")
    return out


def fabric(run, snap, mask=None, weighted=False):
    """Fabric tensor of the force-carrying grain-grain contacts:
    F = <n (x) n> (trace 1), eigenvalues l1 >= l2, anisotropy a = 2 (l1 - l2)
    (so that the orientation density is (1 + a cos 2(theta - theta_c)) / (2 pi)),
    major direction theta_c (rad, in [0, pi)). With ``weighted``, each contact
    is weighted by its normal force."""
    mask = particle_mask(run) if mask is None else mask
    act = active_contacts(snap)
    ci, ai = _pair_indices(run, snap)
    ok = act & (ci >= 0) & (ai >= 0)
    ok[ok] &= mask[ci[ok]] & mask[ai[ok]]
    n = snap.contacts["normal"][ok]
    rn = np.abs(snap.contacts["reaction"][ok, 1])
    out = {"n_contacts": int(ok.sum()), "F": np.full((2, 2), np.nan), "eigenvalues": (np.nan, np.nan),
           "anisotropy": float("nan"), "direction": float("nan"), "normals": n}
    if len(n) == 0:
        return out
    w = rn if weighted else np.ones(len(n))
    if w.sum() <= 0:
        return out
    F = np.einsum("k,ki,kj->ij", w, n, n) / w.sum()
    vals, vecs = np.linalg.eigh(F)
    l2, l1 = vals
    v1 = vecs[:, 1]
    out.update(F=F, eigenvalues=(float(l1), float(l2)), anisotropy=float(2.0 * (l1 - l2) / (l1 + l2)),
               direction=float(math.atan2(v1[1], v1[0]) % math.pi))
    return out


def _disk_rect_area(cx, cy, r, x0, x1, y0, y1, nq=48):
    """Area of disks (vectorised) inside the rectangle [x0,x1]x[y0,y1]
    (Gauss-Legendre in the angle-like variable s = cx + r sin(phi))."""
    cx, cy, r = map(np.atleast_1d, (cx, cy, r))
    a = np.clip((x0 - cx) / r, -1.0, 1.0)
    b = np.clip((x1 - cx) / r, -1.0, 1.0)
    pa, pb = np.arcsin(a), np.arcsin(b)
    xg, wg = np.polynomial.legendre.leggauss(nq)
    phi = 0.5 * (pb - pa)[:, None] * xg[None, :] + 0.5 * (pb + pa)[:, None]
    h = r[:, None] * np.cos(phi)                    # half chord
    lo = np.maximum(cy[:, None] - h, y0)
    hi = np.minimum(cy[:, None] + h, y1)
    chord = np.maximum(hi - lo, 0.0)
    integrand = chord * r[:, None] * np.cos(phi)     # ds = r cos(phi) dphi
    return 0.5 * (pb - pa) * (integrand * wg[None, :]).sum(axis=1)


def _clip_polygon_rect(v, x0, x1, y0, y1):
    """Sutherland-Hodgman clipping of a polygon by an axis-aligned rectangle."""
    def clip(poly, inside, inter):
        out = []
        for k in range(len(poly)):
            p, q = poly[k - 1], poly[k]
            ip, iq = inside(p), inside(q)
            if iq:
                if not ip:
                    out.append(inter(p, q))
                out.append(q)
            elif ip:
                out.append(inter(p, q))
        return out

    def ix(c):
        return lambda p, q: (c, p[1] + (q[1] - p[1]) * (c - p[0]) / (q[0] - p[0]))

    def iy(c):
        return lambda p, q: (p[0] + (q[0] - p[0]) * (c - p[1]) / (q[1] - p[1]), c)

    poly = [tuple(p) for p in v]
    for inside, inter in ((lambda p: p[0] >= x0, ix(x0)), (lambda p: p[0] <= x1, ix(x1)),
                          (lambda p: p[1] >= y0, iy(y0)), (lambda p: p[1] <= y1, iy(y1))):
        if not poly:
            break
        poly = clip(poly, inside, inter)
    return np.array(poly) if poly else np.zeros((0, 2))


def _rotate(v, angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.column_stack((c * v[:, 0] - s * v[:, 1], s * v[:, 0] + c * v[:, 1]))


def body_outlines(run, snap, n_arc=40):
    """Per body, a list of (kind, data) in world coordinates: ('disk', (x, y, r)),
    ('xksid', (x, y, r)) or ('poly', vertices (n, 2)) from the case's DATBOX; or
    a disk of radius /bodies/radius for every body when the deck is not found."""
    case = run.deck()
    pos = snap.pos
    out = []
    if case is None:
        r = run.bodies.get("radius", np.zeros(run.n_bodies))
        return [[("disk", (pos[i, 0], pos[i, 1], float(r[i])))] for i in range(run.n_bodies)]
    for i, b in enumerate(case.bodies):
        x, y, th = pos[i]
        shapes = []
        for c in b.contactors:
            if c.kind == "DISKx":
                shapes.append(("disk", (x, y, c.radius)))
            elif c.kind == "xKSID":
                shapes.append(("xksid", (x, y, c.radius)))
            elif c.kind == "POLYG":
                shapes.append(("poly", _rotate(c.vertices, th) + (x, y)))
            elif c.kind == "JONCx":
                a1, a2 = c.ax1, c.ax2
                t1 = np.linspace(-0.5 * math.pi, 0.5 * math.pi, n_arc // 2)
                right = np.column_stack((a1 + a2 * np.cos(t1), a2 * np.sin(t1)))
                left = np.column_stack((-a1 - a2 * np.cos(t1), -a2 * np.sin(t1)))
                shapes.append(("poly", _rotate(np.vstack((right, left)), th) + (x, y)))
        out.append(shapes)
    return out


def _grain_extent(run, snap, mask):
    r = np.asarray(run.bodies.get("radius", np.zeros(run.n_bodies)), dtype=float)
    p = snap.pos[mask]
    rr = r[mask]
    return (float((p[:, 0] - rr).min()), float((p[:, 0] + rr).max()),
            float((p[:, 1] - rr).min()), float((p[:, 1] + rr).max()))


def default_window(run, snap, mask=None):
    """The grains' bounding box shrunk by 10 % of its size at the sides and bottom
    and by 25 % at the top (away from walls and the free surface)."""
    mask = particle_mask(run) if mask is None else mask
    x0, x1, y0, y1 = _grain_extent(run, snap, mask)
    lx, ly = x1 - x0, y1 - y0
    return (x0 + 0.1 * lx, x1 - 0.1 * lx, y0 + 0.1 * ly, y1 - 0.25 * ly)


def packing_fraction(run, snap, window=None, mask=None):
    """Solid fraction of the grains inside window = (xmin, xmax, ymin, ymax)
    (default: default_window). Disks are exact; polygons are clipped exactly when
    the case's DATBOX is found, else taken as disks of radius avrd (equal area)."""
    mask = particle_mask(run) if mask is None else mask
    if not mask.any():
        return float("nan")
    x0, x1, y0, y1 = default_window(run, snap, mask) if window is None else window
    if not (x1 > x0 and y1 > y0):
        return float("nan")
    case = run.deck()
    r = np.asarray(run.bodies.get("radius", np.zeros(run.n_bodies)), dtype=float)
    pos = snap.pos
    solid = 0.0
    disk_idx, disk_r = [], []
    outlines = body_outlines(run, snap) if case is not None else None
    for i in np.nonzero(mask)[0]:
        if outlines is None:
            disk_idx.append(i)
            disk_r.append(r[i])
            continue
        for kind, data in outlines[i]:
            if kind == "disk":
                disk_idx.append(i)
                disk_r.append(data[2])
            elif kind == "poly":
                v = data
                if v[:, 0].max() < x0 or v[:, 0].min() > x1 or v[:, 1].max() < y0 or v[:, 1].min() > y1:
                    continue
                cpoly = _clip_polygon_rect(v, x0, x1, y0, y1)
                if len(cpoly) >= 3:
                    xx, yy = cpoly[:, 0], cpoly[:, 1]
                    solid += 0.5 * abs(np.sum(xx * np.roll(yy, -1) - np.roll(xx, -1) * yy))
    if disk_idx:
        di = np.array(disk_idx)
        dr = np.array(disk_r)
        cx, cy = pos[di, 0], pos[di, 1]
        near = (cx + dr > x0) & (cx - dr < x1) & (cy + dr > y0) & (cy - dr < y1)
        if near.any():
            solid += float(_disk_rect_area(cx[near], cy[near], dr[near], x0, x1, y0, y1).sum())
    return solid / ((x1 - x0) * (y1 - y0))


def microstructure_evolution(run, max_snapshots=40, window=None):
    """Packing fraction, coordination and fabric anisotropy over (at most
    max_snapshots evenly chosen) snapshots: dict of arrays."""
    n = run.n_snapshots
    idx = np.unique(np.linspace(0, n - 1, min(n, max_snapshots)).round().astype(int)) if n else []
    mask = particle_mask(run)
    rows = {"step": [], "time": [], "packing_fraction": [], "z": [], "z_mech": [],
            "rattler_fraction": [], "anisotropy": [], "contacts": []}
    for k in idx:
        s = run.snapshot(int(k))
        c = coordination(run, s, mask)
        fb = fabric(run, s, mask)
        rows["step"].append(s.step)
        rows["time"].append(s.time)
        rows["packing_fraction"].append(packing_fraction(run, s, window, mask))
        rows["z"].append(c["z"])
        rows["z_mech"].append(c["z_mech"])
        rows["rattler_fraction"].append(c["rattler_fraction"])
        rows["anisotropy"].append(fb["anisotropy"])
        rows["contacts"].append(s.n_contacts)
    return {k: np.array(v) for k, v in rows.items()}


# --------------------------------------------------------------------------------------
# summary
# --------------------------------------------------------------------------------------

def _fmt(v):
    if v is None:
        return "-"
    if isinstance(v, (bool, np.bool_)):
        return "yes" if v else "no"
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    if isinstance(v, (float, np.floating)):
        if not math.isfinite(v):
            return "-"
        if v == 0:
            return "0"
        if 1e-3 <= abs(v) < 1e5:
            return f"{v:.4g}"
        return f"{v:.3e}"
    return str(v)


def summary(run):
    """One run's key figures (an ordered dict of name -> value, None if unknown)."""
    s = run.series
    n_steps = len(s["time"]) if "time" in s else (len(next(iter(s.values()))) if s else 0)

    def last(k):
        return float(s[k][-1]) if k in s and len(s[k]) else None

    def mx(k, absval=False):
        if k not in s or not len(s[k]):
            return None
        a = np.abs(s[k]) if absval else s[k]
        return float(np.nanmax(a))

    works = [np.abs(s[k]) for k in ("work_gravity", "work_driven", "work_forces", "work_supports")
             if k in s and len(s[k])]
    wmax = float(np.nanmax(np.sum(works, axis=0))) if works else None
    bal = mx("balance_error", absval=True)
    out = {
        "file": str(run.path),
        "program": run.attrs.get("program"),
        "version": run.attrs.get("version"),
        "complete": run.complete,
        "bodies": run.n_bodies,
        "meshed bodies": len(run.file["mesh"]["body_first_node"]) - 1 if "mesh" in run.file else 0,
        "time step [s]": run.attrs.get("time_step"),
        "theta": run.attrs.get("theta"),
        "steps": n_steps,
        "final time [s]": last("time"),
        "snapshots": run.n_snapshots,
        "contacts (last step)": int(last("contacts")) if last("contacts") is not None else None,
        "NLGS sweeps mean": float(np.mean(s["sweeps"])) if "sweeps" in s and len(s["sweeps"]) else None,
        "NLGS sweeps max": mx("sweeps"),
        "steps not converged": int(np.sum(s["converged"] == 0)) if "converged" in s else None,
        "natural-map residual max": mx("residual_natural_map"),
        "kinetic energy final [J/m]": last("kinetic_energy"),
        "balance error max [J/m]": bal,
        "balance error / work": (bal / wmax) if bal is not None and wmax else None,
        "max overlap [m]": mx("max_overlap"),
        "wall time [s]": (float(np.sum(s["step_time"])) if "step_time" in s else last("wall_time")),
    }
    return out


def summary_table(summaries, keys=None):
    """A Markdown table with one row per run summary."""
    if isinstance(summaries, dict):
        summaries = [summaries]
    keys = keys or [k for k in summaries[0] if k not in ("program",)]
    head = "| " + " | ".join(keys) + " |"
    sep = "| " + " | ".join("---" for _ in keys) + " |"
    rows = ["| " + " | ".join(_fmt(s.get(k)) for k in keys) + " |" for s in summaries]
    return "\n".join([head, sep] + rows)


def _vertical_table(d):
    lines = ["| quantity | value |", "| --- | --- |"]
    lines += [f"| {k} | {_fmt(v)} |" for k, v in d.items()]
    return "\n".join(lines)


# --------------------------------------------------------------------------------------
# plots
# --------------------------------------------------------------------------------------

def _time_axis(run):
    s = run.series
    if "time" in s:
        return s["time"], "time [s]"
    n = len(next(iter(s.values()))) if s else 0
    if "step" in s:
        return s["step"], "step"
    return np.arange(1, n + 1), "step"


def _save(fig, out):
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=120)
    _plt().close(fig)
    return out


def _maybe_log(ax, *arrays):
    vals = np.concatenate([np.asarray(a, dtype=float).ravel() for a in arrays]) if arrays else []
    vals = vals[np.isfinite(vals)]
    if len(vals) and np.all(vals > 0) and vals.max() / vals.min() > 1e3:
        ax.set_yscale("log")


def plot_energy(run, out):
    """Kinetic energy per step. Returns the PNG path, or None if the series is missing."""
    s = run.series
    if "kinetic_energy" not in s:
        return None
    plt = _plt()
    t, tl = _time_axis(run)
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(t, s["kinetic_energy"], color="C0", lw=1.2)
    _maybe_log(ax, s["kinetic_energy"])
    ax.set_xlabel(tl)
    ax.set_ylabel("kinetic energy [J/m]")
    ax.set_title("Kinetic energy")
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    return _save(fig, out)


def plot_energy_balance(run, out):
    """Energy audit terms per step and the balance error."""
    s = run.series
    terms = [("work_gravity", "work of gravity"), ("work_driven", "work of driven dofs"),
             ("work_forces", "work of driven forces"), ("work_supports", "work of supports"),
             ("kinetic_energy", "kinetic energy"), ("elastic_energy", "elastic energy"),
             ("dissipated", "dissipated")]
    have = [(k, lab) for k, lab in terms if k in s]
    if not have and "balance_error" not in s:
        return None
    plt = _plt()
    t, tl = _time_axis(run)
    fig, axes = plt.subplots(2, 1, figsize=(7, 6), sharex=True,
                             gridspec_kw={"height_ratios": [2, 1]})
    for k, lab in have:
        axes[0].plot(t, s[k], lw=1.2, label=lab)
    axes[0].set_ylabel("energy [J/m]")
    axes[0].set_title("Energy balance: work = kinetic + dissipated")
    axes[0].grid(True, alpha=0.3)
    if have:
        axes[0].legend(fontsize=8)
    if "balance_error" in s:
        axes[1].plot(t, s["balance_error"], color="C3", lw=1.0)
    axes[1].set_ylabel("balance error [J/m]")
    axes[1].set_xlabel(tl)
    axes[1].grid(True, alpha=0.3)
    fig.tight_layout()
    return _save(fig, out)


def plot_solver(run, out):
    """NLGS sweeps, residuals and wall time per step."""
    s = run.series
    if not any(k in s for k in ("sweeps", "residual_natural_map", "quad_dv", "maxm_dv", "wall_time")):
        return None
    plt = _plt()
    t, tl = _time_axis(run)
    fig, axes = plt.subplots(3, 1, figsize=(7, 8), sharex=True)
    ax = axes[0]
    if "sweeps" in s:
        ax.plot(t, s["sweeps"], lw=0.8, color="C0", label="sweeps")
        if "converged" in s:
            bad = s["converged"] == 0
            if bad.any():
                ax.plot(t[bad], s["sweeps"][bad], "x", color="C3", ms=5,
                        label=f"not converged ({int(bad.sum())} steps)")
        ax.legend(fontsize=8)
    ax.set_ylabel("NLGS sweeps per step")
    ax.set_title("Solver")
    ax.grid(True, alpha=0.3)
    ax = axes[1]
    plotted = []
    for k, lab in (("residual_natural_map", "natural-map residual |F|/|q|"),
                   ("residual_onepq", "residual_onepq"),
                   ("quad_dv", "QuadDV (tol. units)"), ("maxm_dv", "MaxmDV (tol. units)"),
                   ("mean_dvor", "|MeanDVoR| (tol. units)")):
        if k in s:
            y = np.abs(s[k])
            # Values at round-off level (first steps, bodies merely touching) would
            # stretch the axis over tens of decades: show from 1e-16 up.
            y = np.where(y > 1e-16, y, np.nan)
            ax.plot(t, y, lw=0.8, label=lab)
            plotted.append(y)
    if plotted and np.any(np.isfinite(np.concatenate(plotted))):
        ax.set_yscale("log")
        ax.legend(fontsize=8)
    ax.set_ylabel("residual [-]")
    ax.grid(True, alpha=0.3, which="both")
    ax = axes[2]
    if "step_time" in s:          # seconds of each step (detection, solve, update)
        ax.plot(t, s["step_time"] * 1e3, lw=0.8, color="C2", label="step")
        if "solve_time" in s:
            ax.plot(t, s["solve_time"] * 1e3, lw=0.8, color="C1", label="NLGS solve")
        ax.legend(fontsize=8)
    elif "wall_time" in s:        # older files: cumulative seconds since the start
        ax.plot(t, np.diff(s["wall_time"], prepend=0.0) * 1e3, lw=0.8, color="C2")
    ax.set_ylabel("wall time per step [ms]")
    ax.set_xlabel(tl)
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    return _save(fig, out)


def plot_contacts(run, out):
    """Number of contacts and overlaps per step."""
    s = run.series
    if not any(k in s for k in ("contacts", "mean_overlap", "max_overlap")):
        return None
    plt = _plt()
    t, tl = _time_axis(run)
    fig, axes = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    for k, lab in (("contacts", "contacts"), ("active_contacts", "active contacts")):
        if k in s:
            axes[0].plot(t, s[k], lw=1.0, label=lab)
    if "active_contacts" in s:
        axes[0].legend(fontsize=8)
    axes[0].set_ylabel("contacts")
    axes[0].set_title("Contacts and overlaps")
    axes[0].grid(True, alpha=0.3)
    ov = []
    for k, lab in (("mean_overlap", "mean overlap"), ("max_overlap", "max overlap")):
        if k in s:
            y = np.where(s[k] > 0, s[k], np.nan)
            axes[1].plot(t, y, lw=0.8, label=lab)
            ov.append(y)
    if ov and np.any(np.isfinite(np.concatenate(ov))):
        axes[1].set_yscale("log")
        axes[1].legend(fontsize=8)
    axes[1].set_ylabel("overlap [m]")
    axes[1].set_xlabel(tl)
    axes[1].grid(True, alpha=0.3, which="both")
    fig.tight_layout()
    return _save(fig, out)


def plot_force_network(run, out, snapshot=-1, window=None, max_width=None):
    """Contact force network at a snapshot: a line between the centres of two
    grains in contact (from the grain centre to the contact point for a wall),
    line width proportional to the normal force, over the body outlines.
    Compressive forces dark red, tensile (cohesive) forces blue."""
    plt = _plt()
    from matplotlib.collections import LineCollection, PatchCollection
    from matplotlib.patches import Circle, Polygon as MPoly

    snap = run.snapshot(snapshot)
    mask = particle_mask(run)
    outlines = body_outlines(run, snap)
    fig, ax = plt.subplots(figsize=(7, 7))
    grain_patches, wall_patches = [], []
    for i, shapes in enumerate(outlines):
        if run.deck() is None and not mask[i]:
            continue                      # walls unknown without the deck
        for kind, data in shapes:
            if kind in ("disk", "xksid"):
                p = Circle((data[0], data[1]), data[2])
            else:
                p = MPoly(data, closed=True)
            (grain_patches if mask[i] else wall_patches).append(p)
    if grain_patches:
        ax.add_collection(PatchCollection(grain_patches, facecolor="0.93", edgecolor="0.6", lw=0.4))
    if wall_patches:
        ax.add_collection(PatchCollection(wall_patches, facecolor="0.75", edgecolor="0.4", lw=0.6))
    c = snap.contacts
    ci, ai = _pair_indices(run, snap)
    rn = c["reaction"][:, 1] if snap.n_contacts else np.zeros(0)
    ok = (rn != 0) & (ci >= 0) & (ai >= 0)
    segs, widths, colors = [], [], []
    fmax = float(np.abs(rn[ok]).max()) if ok.any() else 0.0
    if fmax > 0:
        # widest line about one grain radius, in points (figure about 7 in wide)
        r = np.asarray(run.bodies.get("radius", np.ones(run.n_bodies)), dtype=float)
        rg = float(np.median(r[mask])) if mask.any() else float(np.median(r))
        ext = _grain_extent(run, snap, mask) if mask.any() else (0.0, 1.0, 0.0, 1.0)
        span = max(ext[1] - ext[0], ext[3] - ext[2], 1e-300)
        wmax = max_width or float(np.clip(rg / span * 5.5 * 72.0, 0.8, 6.0))
        for k in np.nonzero(ok)[0]:
            a, b = ci[k], ai[k]
            pa = snap.pos[a, :2]
            if mask[a] and mask[b]:
                pb = snap.pos[b, :2]
            else:
                pb = c["point"][k]
                if not mask[a] and mask[b]:
                    pa = snap.pos[b, :2]
            segs.append([pa, pb])
            widths.append(0.2 + wmax * abs(rn[k]) / fmax)
            colors.append("darkred" if rn[k] > 0 else "royalblue")
        ax.add_collection(LineCollection(segs, linewidths=widths, colors=colors, capstyle="round"))
    # limits: the grains (and walls) with a margin
    pts = [p.get_path().transformed(p.get_patch_transform()).vertices
           for p in grain_patches + wall_patches]
    if pts:
        allp = np.vstack(pts)
        lo, hi = allp.min(axis=0), allp.max(axis=0)
        pad = 0.03 * max(hi - lo)
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
    if window is not None:
        ax.add_patch(plt.Rectangle((window[0], window[2]), window[1] - window[0],
                                   window[3] - window[2], fill=False, ls="--", color="C0", lw=1))
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(f"Force network, step {snap.step}, t = {snap.time:.4g} s\n"
                 f"{int(ok.sum())} loaded contacts; line width ~ normal force "
                 f"(max {fmax:.3g} N/m)", fontsize=10)
    fig.tight_layout()
    return _save(fig, out)


def plot_fabric(run, out, snapshot=-1, bins=36):
    """Rose diagram of the grain-grain contact normal orientations with the
    second-order fit (1 + a cos 2(theta - theta_c)) / (2 pi)."""
    plt = _plt()
    snap = run.snapshot(snapshot)
    fb = fabric(run, snap)
    n = fb["normals"]
    fig = plt.figure(figsize=(6, 6))
    ax = fig.add_subplot(111, projection="polar")
    if len(n):
        ang = np.arctan2(n[:, 1], n[:, 0])
        ang = np.concatenate((ang, ang + math.pi)) % (2 * math.pi)
        h, edges = np.histogram(ang, bins=bins, range=(0, 2 * math.pi), density=True)
        ax.bar(edges[:-1], h, width=edges[1] - edges[0], align="edge", alpha=0.5,
               edgecolor="0.3", label="contact normals")
        th = np.linspace(0, 2 * math.pi, 361)
        fit = (1 + fb["anisotropy"] * np.cos(2 * (th - fb["direction"]))) / (2 * math.pi)
        ax.plot(th, fit, color="C3", lw=1.5, label="(1 + a cos 2(θ-θc)) / 2π")
        ax.legend(loc="lower left", fontsize=8, bbox_to_anchor=(-0.1, -0.12))
    ax.set_title(f"Contact orientations (probability density [1/rad]), step {snap.step}\n"
                 f"{fb['n_contacts']} contacts, anisotropy a = {_fmt(fb['anisotropy'])}, "
                 f"θc = {_fmt(math.degrees(fb['direction']) if math.isfinite(fb['direction']) else None)}°",
                 fontsize=10)
    fig.tight_layout()
    return _save(fig, out)


def plot_microstructure(evo, out):
    """Packing fraction, coordination number and anisotropy against time."""
    if evo is None or not len(evo["time"]):
        return None
    plt = _plt()
    fig, axes = plt.subplots(3, 1, figsize=(7, 7), sharex=True)
    t = evo["time"]
    axes[0].plot(t, evo["packing_fraction"], "o-", ms=3)
    axes[0].set_ylabel("packing fraction [-]")
    axes[0].set_title("Microstructure")
    axes[1].plot(t, evo["z"], "o-", ms=3, label="z (all grains)")
    axes[1].plot(t, evo["z_mech"], "s-", ms=3, label="z without rattlers")
    axes[1].set_ylabel("coordination [-]")
    axes[1].legend(fontsize=8)
    axes[2].plot(t, evo["anisotropy"], "o-", ms=3, color="C3")
    axes[2].set_ylabel("fabric anisotropy a [-]")
    axes[2].set_xlabel("time [s]")
    for ax in axes:
        ax.grid(True, alpha=0.3)
    fig.tight_layout()
    return _save(fig, out)


# --------------------------------------------------------------------------------------
# report
# --------------------------------------------------------------------------------------

def report(case_dir, h5=None, out_dir=None, snapshot=-1, window=None, x_is="auto"):
    """Write out_dir (default CASE_DIR/report)/report.md with PNG plots of the run.
    Returns the path of report.md."""
    case_dir = Path(case_dir)
    h5path = Path(h5) if h5 else _resolve_h5(case_dir)
    out_dir = Path(out_dir) if out_dir else case_dir / "report"
    out_dir.mkdir(parents=True, exist_ok=True)
    lines = []
    with Run(h5path, x_is=x_is) as run:
        summ = summary(run)
        lines += [f"# Fracas run report: {case_dir.resolve().name}", "",
                  f"- results file: `{h5path}`",
                  f"- program: {run.attrs.get('program', '?')} {run.attrs.get('version', '')}",
                  f"- bodies: {run.n_bodies} rigid{_meshed_bodies(run)}, snapshots: {run.n_snapshots}, "
                  f"snapshot X read as {run.x_is}"]
        if not run.complete:
            lines += ["", "> **Warning: the run is not complete** (root attribute `complete` = 0):"
                      " it is still running or it stopped early."]
        missing = [k for k in ("kinetic_energy", "work_gravity", "dissipated", "balance_error",
                               "sweeps", "residual_natural_map", "contacts") if k not in run.series]
        if missing:
            lines += ["", "Series not in the file: " + ", ".join(f"`{m}`" for m in missing) + "."]
        lines += ["", "## Summary", "", _vertical_table(summ), ""]
        plots = [("Kinetic energy", plot_energy, "energy.png"),
                 ("Energy balance", plot_energy_balance, "energy_balance.png"),
                 ("Solver: NLGS sweeps and residuals", plot_solver, "solver.png"),
                 ("Contacts and overlaps", plot_contacts, "contacts.png")]
        lines += ["## Time series", ""]
        for title, fn, name in plots:
            p = fn(run, out_dir / name)
            if p is not None:
                lines += [f"### {title}", "", f"![{title}]({name})", ""]
        if "mesh" in run.file:
            lines += _cracks_section(run, out_dir, snapshot)
        if run.n_snapshots and run.n_bodies == 0:
            pass                     # meshed bodies only: no grains, no microstructure
        elif run.n_snapshots:
            snap = run.snapshot(snapshot)
            mask = particle_mask(run)
            lines += ["## Microstructure", ""]
            if mask.any():
                win = window or default_window(run, snap, mask)
                coord = coordination(run, snap, mask)
                fb = fabric(run, snap, mask)
                fbw = fabric(run, snap, mask, weighted=True)
                phi = packing_fraction(run, snap, win, mask)
                micro = {
                    "snapshot (step, time [s])": f"{snap.step}, {snap.time:.6g}",
                    "grains": coord["n_grains"],
                    "window [m] (xmin, xmax, ymin, ymax)": ", ".join(f"{w:.4g}" for w in win),
                    "packing fraction in window": phi,
                    "coordination z": coord["z"],
                    "grain-grain coordination": coord["z_grains"],
                    "z without rattlers": coord["z_mech"],
                    "rattler fraction": coord["rattler_fraction"],
                    "loaded grain-grain contacts": coord["grain_contacts"],
                    "loaded grain-wall contacts": coord["wall_contacts"],
                    "fabric anisotropy a": fb["anisotropy"],
                    "fabric direction [deg]": math.degrees(fb["direction"])
                    if math.isfinite(fb["direction"]) else None,
                    "force-weighted anisotropy": fbw["anisotropy"],
                }
                F = fb["F"]
                lines += [_vertical_table(micro), "",
                          f"Fabric tensor F = <n⊗n> = [[{_fmt(F[0, 0])}, {_fmt(F[0, 1])}], "
                          f"[{_fmt(F[1, 0])}, {_fmt(F[1, 1])}]]", ""]
                p = plot_force_network(run, out_dir / "force_network.png", snapshot, window=win)
                lines += ["### Force network", "", "![Force network](force_network.png)", "",
                          "Dashed box: the packing-fraction window.", ""]
                plot_fabric(run, out_dir / "fabric.png", snapshot)
                lines += ["### Fabric", "", "![Fabric](fabric.png)", ""]
                if run.n_snapshots > 1:
                    evo = microstructure_evolution(run, window=window)
                    plot_microstructure(evo, out_dir / "microstructure.png")
                    lines += ["### Evolution", "", "![Microstructure](microstructure.png)", ""]
            else:
                lines += ["No grains found (all bodies look like walls or driven bodies).", ""]
        else:
            lines += ["## Microstructure", "", "No snapshot in the file.", ""]
        if run.n_bodies and run.deck() is None:
            lines += ["Note: the case's DATBOX was not found or does not match the file; "
                      "bodies are drawn as disks of radius avrd and walls are guessed.", ""]
    path = out_dir / "report.md"
    path.write_text("\n".join(lines) + "\n")
    return path


def _meshed_bodies(run):
    """', M meshed (E elements)' for a run with meshed bodies, else ''."""
    if "mesh" not in run.file:
        return ""
    g = run.file["mesh"]
    return (f", {len(g['body_first_node']) - 1} meshed ({len(g['element_first_node']) - 1} elements, "
            f"{len(g['reference'])} nodes)")


def _cracks_section(run, out_dir, snapshot):
    """Report lines on the cracks and fragments of a meshed run, with a plot of the
    crack length over time."""
    from .fracture import MeshRun
    mr = MeshRun(run)
    s = run.series
    lines = ["## Cracks and fragments", ""]
    if "crack_length" not in s or not len(s["crack_length"]):
        return lines + ["No crack series in the file.", ""]
    table = {"crack length (broken interfaces) [length]": s["crack_length"][-1],
             "damaged length [length]": s["damaged_length"][-1] if "damaged_length" in s else None,
             "broken interface edges": int(s["broken_interfaces"][-1]) if "broken_interfaces" in s else None,
             "energy dissipated by damage [energy]": s["damage_dissipated"][-1] if "damage_dissipated" in s
             else None}
    if mr.snapshot_names:
        st = mr.state(snapshot)
        if st.cracks is not None:
            table[f"fragments (snapshot at step {st.step})"] = st.cracks["fragments"]
            per = np.atleast_1d(st.cracks.get("broken_length_per_family", []))
            for name, v in zip(mr.families, per):
                table[f"broken length, family {name} (step {st.step}) [length]"] = v
    lines += [_vertical_table(table), ""]
    plt = _plt()
    t, tl = _time_axis(run)
    fig, ax = plt.subplots(figsize=(6.5, 3.5))
    ax.plot(t, s["crack_length"], label="crack length")
    if "damaged_length" in s:
        ax.plot(t, s["damaged_length"], "--", label="damaged length")
    ax.set_xlabel(tl)
    ax.set_ylabel("length")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    _save(fig, out_dir / "cracks.png")
    from .fracture import plot_fragment_sizes
    plot_fragment_sizes(mr, out_dir / "fragments.png")
    lines += ["![Crack length](cracks.png)", "", "### Fragments", "",
              "Number of fragments over time and the fragment-mass distribution at a few snapshots "
              "(per-fragment mass, centre, velocity, kinetic energy, inertia: "
              "`MeshRun.fragments(snapshot)`, `/snapshots/N/cracks/fragments` in fracas.h5).", "",
              "![Fragments](fragments.png)", ""]
    return lines + [
                    "Pictures of the cracks: `tools/fracture/plot_cracks.py RUN OUT.png`, or DISPLAY/fracas.pvd "
                    "in ParaView (`tools/paraview/render_frame.py`).", ""]


# --------------------------------------------------------------------------------------
# layout check
# --------------------------------------------------------------------------------------

def check_h5(path):
    """Check a fracas.h5 against the documented layout. Returns (errors,
    warnings, info) lists of strings."""
    h5py = _h5py()
    errors, warns, info = [], [], []
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        return [f"cannot open {path} as HDF5: {e}"], [], []
    with f:
        for a in ("program", "version", "complete", "time_step", "theta"):
            if a not in f.attrs:
                errors.append(f"root attribute '{a}' missing")
        if "case_dir" not in f.attrs:
            warns.append("root attribute 'case_dir' missing")
        attrs = {k: _attr(v) for k, v in f.attrs.items()}
        info.append(f"program {attrs.get('program')} {attrs.get('version')}, "
                    f"layout_version {attrs.get('layout_version', '-')}, complete {attrs.get('complete')}")
        if attrs.get("complete") not in (0, 1, None):
            errors.append(f"attribute complete = {attrs.get('complete')!r}, expected 0 or 1")
        elif attrs.get("complete") == 0:
            warns.append("complete = 0: the run is unfinished (running, crashed or killed)")
        nb = None
        if "bodies" not in f:
            errors.append("group /bodies missing")
        else:
            g = f["bodies"]
            for k in ("number", "mass", "inertia", "radius", "reference"):
                if k not in g:
                    errors.append(f"/bodies/{k} missing")
            if "number" in g:
                nb = len(g["number"])
                num = g["number"][()]
                if len(np.unique(num)) != nb:
                    errors.append("/bodies/number has duplicates")
            for k in ("mass", "inertia", "radius"):
                if k in g and nb is not None and g[k].shape != (nb,):
                    errors.append(f"/bodies/{k} shape {g[k].shape}, expected ({nb},)")
                if k in g and not np.all(np.isfinite(g[k][()])):
                    errors.append(f"/bodies/{k} has non-finite values")
            if "reference" in g and nb is not None and g["reference"].shape != (nb, 3):
                errors.append(f"/bodies/reference shape {g['reference'].shape}, expected ({nb}, 3)")
            info.append(f"{nb} bodies")
        nrows = None
        if "series" not in f:
            errors.append("group /series missing")
        else:
            g = f["series"]
            lens = {k: g[k].shape for k in g if isinstance(g[k], h5py.Dataset)}
            bad = {k: s for k, s in lens.items() if len(s) != 1}
            for k, s in bad.items():
                errors.append(f"/series/{k} is not 1-D (shape {s})")
            sizes = {s[0] for k, s in lens.items() if len(s) == 1}
            if len(sizes) > 1:
                msg = "/series datasets have different lengths: " + \
                    ", ".join(f"{k}={s[0]}" for k, s in lens.items() if len(s) == 1)
                if attrs.get("complete") == 0 and max(sizes) - min(sizes) <= 1:
                    warns.append(msg + " (unfinished run: use the shortest)")
                else:
                    errors.append(msg)
            nrows = max(sizes) if sizes else 0
            for k in ("step", "time"):
                if k not in g:
                    warns.append(f"/series/{k} missing")
            expected = ["contacts", "sweeps", "converged", "residual_natural_map", "quad_dv",
                        "maxm_dv", "kinetic_energy", "work_gravity", "work_driven", "dissipated",
                        "balance_error", "mean_overlap", "max_overlap", "wall_time",
                        "step_time", "solve_time"]
            absent = [k for k in expected if k not in g]
            if absent:
                info.append("series not in the file: " + ", ".join(absent))
            if "time" in g and g["time"].ndim == 1 and len(g["time"]) > 1:
                t = g["time"][()]
                if np.any(np.diff(t) <= 0):
                    errors.append("/series/time is not increasing")
            if "step" in g and g["step"].ndim == 1 and len(g["step"]) > 1:
                if np.any(np.diff(g["step"][()]) <= 0):
                    errors.append("/series/step is not increasing")
            for k in lens:
                if len(lens[k]) == 1 and lens[k][0] and not np.all(np.isfinite(g[k][()])):
                    warns.append(f"/series/{k} has non-finite values")
            info.append(f"{nrows} steps in /series ({len(lens)} series)")
        help_names = {}
        if "help" not in f:
            errors.append("group /help missing")
        else:
            for key in ("status", "inter", "law"):
                for name in (key + "_names", key):
                    if name in f["help"]:
                        help_names[key] = _strings(f["help"][name])
                        break
                else:
                    errors.append(f"/help/{key}_names (or /help/{key}) missing")
        if "snapshots" not in f:
            errors.append("group /snapshots missing")
        else:
            names = [k for k in f["snapshots"]]
            nonnum = [k for k in names if not k.isdigit()]
            if nonnum:
                errors.append(f"/snapshots has non-numeric groups: {nonnum[:5]}")
            names = sorted((k for k in names if k.isdigit()), key=int)
            if names and [int(k) for k in names] != list(range(1, len(names) + 1)):
                warns.append("/snapshots are not numbered 1, 2, ... without gaps")
            last_step = None
            for k in names:
                g = f["snapshots"][k]
                where = f"/snapshots/{k}"
                for a in ("step", "time"):
                    if a not in g.attrs:
                        errors.append(f"{where}: attribute '{a}' missing")
                st = int(_attr(g.attrs.get("step", -1)))
                if last_step is not None and st <= last_step:
                    errors.append(f"{where}: step {st} not after the previous snapshot's {last_step}")
                last_step = st
                for d in ("bodies/X", "bodies/V"):
                    if d not in g:
                        errors.append(f"{where}/{d} missing")
                    elif nb is not None and g[d].shape != (nb, 3):
                        errors.append(f"{where}/{d} shape {g[d].shape}, expected ({nb}, 3)")
                    elif not np.all(np.isfinite(g[d][()])):
                        errors.append(f"{where}/{d} has non-finite values")
                if "contacts" not in g:
                    errors.append(f"{where}/contacts missing")
                    continue
                cg = g["contacts"]
                nc = len(cg["cd_body"]) if "cd_body" in cg else None
                for fld in Run.CONTACT_FIELDS:
                    if fld not in cg:
                        errors.append(f"{where}/contacts/{fld} missing")
                        continue
                    shape = cg[fld].shape
                    want = (nc, 2) if fld in ("normal", "point", "reaction", "velocity") else (nc,)
                    if nc is not None and shape != want and not (nc == 0 and np.prod(shape) == 0):
                        errors.append(f"{where}/contacts/{fld} shape {shape}, expected {want}")
                if nc and all(fld in cg for fld in Run.CONTACT_FIELDS):
                    if nb is not None and "number" in f["bodies"]:
                        known = set(int(x) for x in f["bodies/number"][()])
                        for fld in ("cd_body", "an_body"):
                            vals = set(int(x) for x in np.unique(cg[fld][()]))
                            if not vals <= known:
                                errors.append(f"{where}/contacts/{fld}: unknown body numbers "
                                              f"{sorted(vals - known)[:5]}")
                    for key in ("status", "inter", "law"):
                        if key in help_names and cg[key].shape == (nc,):
                            v = cg[key][()]
                            if v.min() < 1 or v.max() > len(help_names[key]):
                                errors.append(f"{where}/contacts/{key}: ids outside 1..{len(help_names[key])}")
                    for fld in ("normal", "point", "reaction", "velocity", "gap"):
                        if cg[fld].shape[:1] == (nc,) and not np.all(np.isfinite(cg[fld][()])):
                            errors.append(f"{where}/contacts/{fld} has non-finite values")
                    nrm = cg["normal"][()]
                    if nrm.shape == (nc, 2):
                        dev = np.abs(np.hypot(nrm[:, 0], nrm[:, 1]) - 1.0).max()
                        if dev > 1e-6:
                            warns.append(f"{where}/contacts/normal: not unit vectors (max deviation {dev:.2e})")
            info.append(f"{len(names)} snapshots" + (f", last at step {last_step}" if names else ""))
    return errors, warns, info
