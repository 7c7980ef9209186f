#!/usr/bin/python3
"""Hydrided Zircaloy-4 plate (issue 13, the showcase of the seed paper): a deck generator.

A rectangular plate of irradiated Zircaloy-4 (J2 matrix) holding horizontal rectangular
delta-hydrides (elastic), placed at random without overlap from a seed, meshed by gmsh's
Python API (T3, uniform element size), exploded into one MAILx body per element with a
frictional cohesive zone (MAL_CZM) on every shared edge. Three interface families:
MA_MA (matrix/matrix), HY_HY (inside a hydride), HY_MA (matrix/hydride, the bonding that
is weak or strong). Loading: the plate pulled apart by opposite x (or y) velocities on
two opposite edges, ramped ("pull") or sudden ("impact"). An optional notch (open edges)
starts the crack at the middle of the edge it cuts.

Materials, laws and their sources: doc/hydrided_zircaloy.md. Everything here is in SI.

    build/release/bin/fracas-python tools/hydride/hydride_plate.py CASE_DIR --seed 3 --bonding weak --h 0.5e-6

The same seed gives the same hydrides at any element size (the placement does not
depend on h), and the same deck byte for byte (gmsh runs on one thread).
"""
import argparse
import json
import math
import sys
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
from fracas_tools import Case  # noqa: E402
from fracas_tools.cohesive import Law  # noqa: E402
from fracas_tools.mesh import mecax_sets, mesh_from_gmsh  # noqa: E402
from fracas_tools.postpro_deck import PostPro, mecax_set_rows  # noqa: E402

#: phase names (their interface-family codes are MA and HY)
MATRIX, HYDRIDE = "matrix", "hydride"
FAMILIES = {"MA_MA": "matrix", "HY_HY": "hydride", "HY_MA": "interface"}


# --------------------------------------------------------------------------------------
# parameters
# --------------------------------------------------------------------------------------

@dataclass
class Geometry:
    """Plate and hydride population (lengths in m). Hydride thickness uniform in
    ``thickness``, aspect ratio (length / thickness) uniform in ``aspect``; hydrides
    are added until their area reaches ``area_fraction`` of the plate (the last one
    shortened to hit it), each at least ``clearance`` away from the others, the plate
    edges and the notch."""
    width: float = 32e-6
    height: float = 32e-6
    thickness: tuple = (2.0e-6, 3.0e-6)
    aspect: tuple = (5.0, 8.0)
    area_fraction: float = 0.20
    clearance: float = 1.0e-6
    notch: float = 4.0e-6            # notch length (0: none), across the edge it starts from
    max_tries: int = 200000


@dataclass
class Matrix:
    """Irradiated recrystallized Zircaloy-4, 293 K (doc/hydrided_zircaloy.md §2.1)."""
    density: float = 6520.0
    young: float = 100e9
    poisson: float = 0.36
    yield_stress: float = 750e6
    hardening: float = 1e9


@dataclass
class Hydride:
    """delta-hydride ZrH1.6, elastic (doc/hydrided_zircaloy.md §2.2)."""
    density: float = 5660.0
    young: float = 100e9
    poisson: float = 0.30


@dataclass
class Cohesion:
    """MAL_CZM per family: strength (Pa) and energy (J/m^2), the same in modes I and II;
    stiffness from the artificial-compliance rule (blal * E / (h (1 - 2 nu)), c_t / c_n =
    2 (1 - 2 nu) / (1 + 3 nu)). The matrix/hydride interface is alpha * hydride energy
    and sqrt(alpha) * hydride strength (a MAC-like interface at fixed stiffness)."""
    matrix_strength: float = 1.5e9
    matrix_energy: float = 20.0
    hydride_strength: float = 600e6
    hydride_energy: float = 10.0
    alpha: dict = field(default_factory=lambda: {"weak": 0.1, "strong": 1.0})
    friction: float = 0.3
    blal: float = 23.0


@dataclass
class Loading:
    """Opposite velocities +-velocity on the two edges normal to ``direction`` (x: left
    and right, y: bottom and top); 'pull' ramps them linearly over ``ramp_time``,
    'impact' applies them at once."""
    direction: str = "x"
    velocity: float = 10.0
    kind: str = "pull"
    ramp_time: float = 2e-9


# --------------------------------------------------------------------------------------
# microstructure
# --------------------------------------------------------------------------------------

def notch_segment(geo, direction):
    """The notch as ((x0, y0), (x1, y1)) or None: it starts at the middle of the edge
    parallel to the pulling direction (bottom for x pulling, left for y) and runs
    across the plate, normal to the load."""
    if geo.notch <= 0.0:
        return None
    if direction == "x":
        return (0.5 * geo.width, 0.0), (0.5 * geo.width, geo.notch)
    return (0.0, 0.5 * geo.height), (geo.notch, 0.5 * geo.height)


def place_hydrides(geo, seed, direction="x"):
    """Random sequential addition of axis-aligned horizontal rectangles (x, y, length,
    thickness), lower-left corners; deterministic for a seed (numpy PCG64). The last
    one is shortened to hit the area fraction exactly; when what is left is smaller
    than a hydride of the minimum thickness and twice that length, the last placed
    one is lengthened instead, or taken out and the placement goes on."""
    rng = np.random.default_rng(seed)
    plate = geo.width * geo.height
    target = geo.area_fraction * plate
    g = geo.clearance
    notch = notch_segment(geo, direction)
    placed, area, tries = [], 0.0, 0
    tmin = min(geo.thickness)

    def fits(x, y, length, t, others):
        if x < g * (1 - 1e-12) or x + length > (geo.width - g) * (1 + 1e-12):
            return False
        if notch is not None:
            (nx0, ny0), (nx1, ny1) = notch
            if (x - g < max(nx0, nx1) and min(nx0, nx1) < x + length + g
                    and y - g < max(ny0, ny1) and min(ny0, ny1) < y + t + g):
                return False
        return not any(x - g < px + pl and px < x + length + g and y - g < py + pt and py < y + t + g
                       for px, py, pl, pt in others)

    while area < target * (1.0 - 1e-9) and tries < geo.max_tries:
        tries += 1
        t = rng.uniform(*geo.thickness)
        length = t * rng.uniform(*geo.aspect)
        if area + length * t > target:          # the last one: shorten it to hit the fraction
            length = (target - area) / t
            if length < 2.0 * t:
                x, y, pl, pt = placed[-1]
                grow = (target - area) / pt
                if fits(x, y, pl + grow, pt, placed[:-1]):
                    placed[-1] = (x, y, pl + grow, pt)
                elif fits(x - grow, y, pl + grow, pt, placed[:-1]):
                    placed[-1] = (x - grow, y, pl + grow, pt)
                else:
                    placed.pop()
                    area -= pl * pt
                    continue
                area = target
                break
        if length > geo.width - 2 * g or t > geo.height - 2 * g:
            continue
        x = rng.uniform(g, geo.width - g - length)
        y = rng.uniform(g, geo.height - g - t)
        if not fits(x, y, length, t, placed):
            continue
        placed.append((x, y, length, t))
        area += length * t
    if area < target * 0.999:
        raise RuntimeError(f"only {area / plate:.3f} of the plate covered after {tries} tries "
                           f"(target {geo.area_fraction}): relax clearance or sizes")
    return placed


# --------------------------------------------------------------------------------------
# mesh
# --------------------------------------------------------------------------------------

def is_hydride_surface(bbox, boxes, tol):
    """Whether a surface of the fragmented plate is a hydride: its bounding box (gmsh's
    xmin, ymin, zmin, xmax, ymax, zmax) lies within a hydride rectangle (x, y, length,
    thickness). Not the centre of mass: the matrix, a plate with holes, may have its
    centre of mass inside a hydride (seed 4 of the default plate did)."""
    x0, y0, _, x1, y1, _ = bbox
    return any(x - tol <= x0 and x1 <= x + length + tol and y - tol <= y0 and y1 <= y + t + tol
               for x, y, length, t in boxes)


def build_mesh(geo, hydrides, h, direction="x", msh_path=None, unit=1e-6):
    """gmsh (OCC) plate with the hydride rectangles and the notch fragmented in, T3
    Frontal-Delaunay mesh of element size h. Physical surfaces matrix and hydride,
    physical curves left, right, bottom, top, notch. Returns a fracas_tools Mesh2D (in
    m). gmsh works in units of ``unit`` (OCC's tolerances, about 1e-7, must stay far
    below the hydride sizes)."""
    import gmsh
    s = 1.0 / unit
    gmsh.initialize(readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.model.add("hydrided_plate")
        occ = gmsh.model.occ
        W, H = geo.width * s, geo.height * s
        boxes = [(x * s, y * s, length * s, t * s) for x, y, length, t in hydrides]
        plate = occ.addRectangle(0.0, 0.0, 0.0, W, H)
        tools = [(2, occ.addRectangle(x, y, 0.0, length, t)) for x, y, length, t in boxes]
        notch = notch_segment(geo, direction)
        if notch is not None:
            notch = tuple((px * s, py * s) for px, py in notch)
            p0 = occ.addPoint(*notch[0], 0.0)
            p1 = occ.addPoint(*notch[1], 0.0)
            tools.append((1, occ.addLine(p0, p1)))
        occ.fragment([(2, plate)], tools)
        occ.synchronize()

        def physical(dim, tags, name):
            gmsh.model.setPhysicalName(dim, gmsh.model.addPhysicalGroup(dim, tags), name)

        hyd_surfaces, mat_surfaces = [], []
        for _, tag in gmsh.model.getEntities(2):
            box = gmsh.model.getBoundingBox(2, tag)
            (hyd_surfaces if is_hydride_surface(box, boxes, 1e-3 * h * s) else mat_surfaces).append(tag)
        physical(2, mat_surfaces, MATRIX)
        if hyd_surfaces:
            physical(2, hyd_surfaces, HYDRIDE)

        eps = 1e-3 * h * s
        def curves_in(x0, y0, x1, y1):
            return [c for _, c in gmsh.model.getEntitiesInBoundingBox(x0 - eps, y0 - eps, -eps,
                                                                       x1 + eps, y1 + eps, eps, 1)]
        for name, box in (("left", (0, 0, 0, H)), ("right", (W, 0, W, H)),
                          ("bottom", (0, 0, W, 0)), ("top", (0, H, W, H))):
            physical(1, curves_in(*box), name)
        if notch is not None:
            (x0, y0), (x1, y1) = notch
            edges = curves_in(0, 0, W, 0) + curves_in(0, 0, 0, H)
            inner = [c for c in curves_in(min(x0, x1), min(y0, y1), max(x0, x1), max(y0, y1))
                     if c not in edges]
            physical(1, inner, "notch")

        gmsh.option.setNumber("Mesh.MeshSizeMin", h * s)
        gmsh.option.setNumber("Mesh.MeshSizeMax", h * s)
        gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
        gmsh.option.setNumber("Mesh.Algorithm", 6)
        gmsh.option.setNumber("Mesh.RandomSeed", 1)
        gmsh.model.mesh.generate(2)
        if msh_path is not None:
            gmsh.write(str(msh_path))
        mesh = mesh_from_gmsh()
    finally:
        gmsh.finalize()
    mesh.nodes = mesh.nodes * unit
    return mesh


def mean_edge(mesh):
    """Edge of the equilateral triangle of the mean element area (Blal's h)."""
    xy = mesh.nodes
    area = 0.0
    for _, n in mesh.elements:
        a, b, c = xy[n[0]], xy[n[1]], xy[n[2]]
        area += 0.5 * abs((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]))
    return 2.0 * math.sqrt(area / (math.sqrt(3.0) * mesh.n_elements))


def spurious_distance(mesh, apab=(0.25, 0.75)):
    """The smallest distance from a cohesive point (at apab on an edge shared by two
    elements) to an element edge it is not glued to but touches at a vertex. A
    contact is detected within the alert distance: below this distance a point would
    also see an edge of a neighbour across a vertex (a glued contact with a gap of
    that size at the start, a spring loaded far beyond its strength). The alert must
    stay below it, and above the laws' critical openings."""
    xy = mesh.nodes
    edges = mesh.edges()
    edges_at = {}                       # vertex -> edges (a, b) of elements through it
    for key in edges:
        for v in key:
            edges_at.setdefault(v, []).append(key)
    best = math.inf
    for key, sharing in edges.items():
        if len(sharing) != 2:
            continue
        a, b = key
        for s in apab:
            p = (1.0 - s) * xy[a] + s * xy[b]
            for v in key:
                for other in edges_at[v]:
                    if other == key:
                        continue
                    q0, q1 = xy[other[0]], xy[other[1]]
                    d = q1 - q0
                    t = min(1.0, max(0.0, float(np.dot(p - q0, d) / np.dot(d, d))))
                    best = min(best, float(np.linalg.norm(p - q0 - t * d)))
    return best


# --------------------------------------------------------------------------------------
# deck
# --------------------------------------------------------------------------------------

def blal_stiffness(young, poisson, h, factor):
    """(c_n, c_t) of the artificial-compliance rule used in LMGC90's examples (Blal)."""
    cn = factor * young / (h * (1.0 - 2.0 * poisson))
    return cn, 2.0 * (1.0 - 2.0 * poisson) / (1.0 + 3.0 * poisson) * cn


def critical_opening(params):
    """Opening at which a MAL_CZM point is broken in mode I: s/c + 1.5 (G/s - s/(2c))
    (the law's full-separation opening, fracas_tools.cohesive.Law)."""
    return Law.mal(*(params[k] for k in ("cn", "ct", "s1", "s2", "G1", "G2"))).d_end(1)


def choose_alert(laws, mesh):
    """The alert distance: between the largest critical opening of the laws (a point
    must stay in contact until it is broken) and the spurious distance of the mesh
    (spurious_distance), their geometric mean; an error when there is no room."""
    opening = max(critical_opening(p) for _, p in laws.values())
    spurious = spurious_distance(mesh)
    if 1.2 * opening > 0.8 * spurious:
        raise ValueError(f"the laws break at openings up to {opening:.3g} m but points see a neighbour's "
                         f"edge across a vertex from {spurious:.3g} m: coarsen the mesh or lower G/s")
    return math.sqrt(opening * spurious), opening, spurious


def family_laws(matrix, hydride, coh, bonding, h):
    """{colour: (law nickname, MAL_CZM parameters)} for the three families."""
    cm = blal_stiffness(matrix.young, matrix.poisson, h, coh.blal)
    ch = blal_stiffness(hydride.young, hydride.poisson, h, coh.blal)
    ci = (min(cm[0], ch[0]), min(cm[1], ch[1]))
    alpha = coh.alpha[bonding] if isinstance(bonding, str) else float(bonding)
    fam = {"MA_MA": ("czmmm", cm, coh.matrix_strength, coh.matrix_energy),
           "HY_HY": ("czmhh", ch, coh.hydride_strength, coh.hydride_energy),
           "HY_MA": ("czmhm", ci, math.sqrt(alpha) * coh.hydride_strength, alpha * coh.hydride_energy)}
    out = {}
    for color, (name, (cn, ct), s, g) in fam.items():
        out[color] = (name, dict(dyfr=coh.friction, stfr=coh.friction, cn=cn, ct=ct, s1=s, s2=s, G1=g, G2=g))
    return out


def make_case(mesh, h, matrix=Matrix(), hydride=Hydride(), coh=Cohesion(), bonding="weak",
              loading=Loading(), time_step=1e-10, steps=400, alert=None, output_every=20,
              vtk_every=None, nlgs_tolerance=1e-4, theta=0.5, notch=True, crack_step_limit=0.25):
    """The fracas_tools Case of an exploded hydrided plate, its Exploded parts, the laws
    per family and the contact distances (alert, critical opening, spurious distance)."""
    case = Case(gravity=(0.0, 0.0))
    case.add_material("MATRX", matrix.density, "ELAS_PLAS", young=matrix.young, poisson=matrix.poisson,
                      yield_stress=matrix.yield_stress, hardening=matrix.hardening)
    case.add_material("HYDRx", hydride.density, "ELAS", young=hydride.young, poisson=hydride.poisson)
    case.add_model("M2DJ3", "T3xxx", material="J2iso")
    case.add_model("M2DT3", "T3xxx")
    cracks = ["notch"] if notch and "notch" in mesh.edge_groups else []
    parts = case.add_exploded_mesh(mesh, {MATRIX: "MATRX", HYDRIDE: "HYDRx"},
                                   model={MATRIX: "M2DJ3", HYDRIDE: "M2DT3"}, cracks=cracks)
    lo, hi = ("left", "right") if loading.direction == "x" else ("bottom", "top")
    dof = 1 if loading.direction == "x" else 2
    if loading.kind == "pull":
        ramp = dict(rampi=0.0, ramp=1.0 / loading.ramp_time)
    elif loading.kind == "impact":
        ramp = dict(rampi=1.0, ramp=0.0)
    else:
        raise ValueError("loading kind: pull or impact")
    parts.impose_velocity(lo, dof, ct=-loading.velocity, **ramp)
    parts.impose_velocity(hi, dof, ct=loading.velocity, **ramp)
    # POSTPRO: set 1 the pulled-back edge, set 2 the pulled-forward one (Dep_, Fint_ files:
    # the opening and the force the drives apply, tools/hydride/hydride_post.py)
    case.postpro = PostPro()
    case.postpro.add("NEW MECAx SETS", rows=mecax_set_rows(mecax_sets(parts.bodies, [lo, hi])))
    case.postpro.add("Dep EVOLUTION")
    case.postpro.add("Fint EVOLUTION")
    laws = family_laws(matrix, hydride, coh, bonding, h)
    for color, (name, params) in laws.items():
        if color in parts.families.values():
            case.add_law(name, "MAL_CZM", **params)
    opening = max(critical_opening(p) for _, p in laws.values())
    spurious = None
    if alert is None:
        alert, opening, spurious = choose_alert(laws, mesh)
    parts.add_see(case, {c: name for c, (name, _) in laws.items()}, alert=alert)
    run = dict(time_step=time_step, number_of_steps=steps, theta=theta, plane="strain",
               nlgs_tolerance=nlgs_tolerance, output_hdf5_every=output_every, output_dof_every=0)
    if vtk_every:
        run["output_vtk_every"] = vtk_every
    # Steps cut where a crack runs (doc/czm.md 9): the weak plate's peak within 0.02 %
    # of a run at half the step, for 5 % more CPU.
    if crack_step_limit:
        run["crack_step_limit"] = crack_step_limit
    case.run.set(**run)
    return case, parts, laws, dict(alert=alert, critical_opening=opening, spurious_distance=spurious)


def generate(case_dir, seed, h, bonding, geo=Geometry(), loading=Loading(), **options):
    """Microstructure, mesh and deck in case_dir (DATBOX/, plus hydrides.json describing
    the microstructure, families and parameters for the post-processing)."""
    if min(geo.thickness) < 2.0 * h * (1.0 - 1e-9):
        raise ValueError(f"hydrides from {min(geo.thickness):.3g} m thick need h <= {min(geo.thickness) / 2:.3g} m "
                         f"(at least two elements across), not {h:.3g} m")
    case_dir = Path(case_dir)
    case_dir.mkdir(parents=True, exist_ok=True)
    hydrides = place_hydrides(geo, seed, loading.direction)
    mesh = build_mesh(geo, hydrides, h, loading.direction)
    hmean = mean_edge(mesh)
    case, parts, laws, contact = make_case(mesh, hmean, bonding=bonding, loading=loading, **options)
    case.write(case_dir)
    phases = np.array([p == HYDRIDE for p in mesh.phases])
    info = dict(seed=seed, h=h, h_mean=hmean, bonding=bonding, geometry=asdict(geo),
                loading=asdict(loading), hydrides=hydrides,
                hydride_area_fraction=float(sum(l * t for _, _, l, t in hydrides)
                                            / (geo.width * geo.height)),
                elements=mesh.n_elements, hydride_elements=int(phases.sum()),
                cohesive_edges=parts.cohesive_edges, contact_points=parts.points, **contact,
                families={c: FAMILIES[c] for c in parts.families.values()},
                laws={c: dict(nickname=n, **p) for c, (n, p) in laws.items()},
                matrix=asdict(options.get("matrix", Matrix())), hydride=asdict(options.get("hydride", Hydride())),
                cohesion=asdict(options.get("coh", Cohesion())),
                options={k: v for k, v in options.items() if isinstance(v, (int, float, str))})
    (case_dir / "hydrides.json").write_text(json.dumps(info, indent=1, default=float) + "\n")
    return info


def cohesion_from(settings):
    """A Cohesion from 'key=value' strings (alpha_weak, alpha_strong set the two bondings)."""
    coh = Cohesion()
    for item in settings:
        key, _, value = item.partition("=")
        if key.startswith("alpha_"):
            coh.alpha[key[6:]] = float(value)
        elif key in Cohesion.__dataclass_fields__ and key != "alpha":
            setattr(coh, key, float(value))
        else:
            raise SystemExit(f"--cohesion: unknown field {key!r}")
    return coh


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("case_dir")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--h", type=float, default=1.0e-6, help="element size (m)")
    p.add_argument("--bonding", default="weak", help="weak, strong or alpha (interface/hydride energy)")
    p.add_argument("--width", type=float, default=Geometry.width)
    p.add_argument("--height", type=float, default=Geometry.height)
    p.add_argument("--thickness", type=float, nargs=2, default=Geometry.thickness)
    p.add_argument("--aspect", type=float, nargs=2, default=Geometry.aspect)
    p.add_argument("--fraction", type=float, default=Geometry.area_fraction)
    p.add_argument("--clearance", type=float, default=Geometry.clearance)
    p.add_argument("--notch", type=float, default=Geometry.notch, help="notch length (0: none)")
    p.add_argument("--direction", choices=("x", "y"), default="x")
    p.add_argument("--loading", choices=("pull", "impact"), default="pull")
    p.add_argument("--velocity", type=float, default=Loading.velocity, help="edge speed (m/s)")
    p.add_argument("--ramp-time", type=float, default=Loading.ramp_time)
    p.add_argument("--dt", type=float, default=1e-10)
    p.add_argument("--alert", type=float, help="alert distance (default: choose_alert)")
    p.add_argument("--steps", type=int, default=400)
    p.add_argument("--output-every", type=int, default=20)
    p.add_argument("--vtk-every", type=int, default=0,
                   help="a DISPLAY frame (ParaView) every N steps and at the last one (0: no DISPLAY)")
    p.add_argument("--theta", type=float, default=0.5)
    p.add_argument("--nlgs-tolerance", type=float, default=1e-4)
    p.add_argument("--crack-step-limit", type=float, default=0.25,
                   help="time-step control for cracks: softening lengths per step at most (0: off; doc/czm.md 9)")
    p.add_argument("--cohesion", nargs="*", default=[], metavar="KEY=VALUE",
                   help="Cohesion fields, e.g. matrix_strength=1.5e9 alpha_weak=0.1")
    a = p.parse_args(argv)
    coh = cohesion_from(a.cohesion)
    bonding = a.bonding if a.bonding in ("weak", "strong") else float(a.bonding)
    geo = Geometry(width=a.width, height=a.height, thickness=tuple(a.thickness), aspect=tuple(a.aspect),
                   area_fraction=a.fraction, clearance=a.clearance, notch=a.notch)
    loading = Loading(direction=a.direction, velocity=a.velocity, kind=a.loading, ramp_time=a.ramp_time)
    info = generate(a.case_dir, a.seed, a.h, bonding, geo, loading, time_step=a.dt, steps=a.steps,
                    output_every=a.output_every, vtk_every=a.vtk_every, theta=a.theta, alert=a.alert, coh=coh,
                    nlgs_tolerance=a.nlgs_tolerance, crack_step_limit=a.crack_step_limit)
    print(f"{a.case_dir}: {info['elements']} elements ({info['hydride_elements']} hydride), "
          f"{len(info['hydrides'])} hydrides, fraction {info['hydride_area_fraction']:.3f}, "
          f"{info['cohesive_edges']} cohesive edges, h_mean {info['h_mean']:.3g} m, alert {info['alert']:.3g} m "
          f"(critical opening {info['critical_opening']:.3g}, spurious {info['spurious_distance']:.3g})")


if __name__ == "__main__":
    from fracas_tools.cli import run_main  # bad input: a message, not a traceback
    sys.exit(run_main(main, "hydride_plate.py"))
