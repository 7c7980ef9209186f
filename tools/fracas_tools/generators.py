"""Seeded scene generators: disk deposits, random convex polygons, box walls, a
running-bond masonry wall, a semicircular arch, and the demo decks.

Every random generator takes ``seed`` (an int, passed to numpy.random.default_rng,
or a numpy Generator) so that a deck is reproducible. Lengths in metres.

The ten-line 2000-disk deposit::

    from fracas_tools import Case, generators as gen
    case = Case(gravity=(0.0, -9.81))
    case.add_material("STONE", density=2600.0)
    case.add_material("TDURx", density=1000.0)
    radii = gen.uniform_radii(2000, 0.004, 0.006, seed=1)
    disks = gen.deposit_disks(case, radii, width=0.5, material="STONE", seed=1)
    gen.box_walls(case, 0.0, 0.5, 0.0, gen.top_of(case, disks) + 0.01, 0.01, "TDURx")
    gen.add_granular_laws(case, fric_grains=0.3, fric_walls=0.5, alert=0.5 * radii.max())
    case.run.set(time_step=1e-3, number_of_steps=1000, output_vtk_every=10)
    case.write("deposit_2000")
"""

import math

import numpy as np

from .pre import Case, polygon_area

__all__ = [
    "rng_from", "uniform_radii", "lattice_positions", "ballistic_positions", "deposit_disks",
    "top_of", "box_walls", "add_granular_laws", "random_convex_polygon", "regular_polygon",
    "deposit_polygons", "masonry_wall", "arch", "demo_deposit", "demo_masonry", "demo_arch",
    "deposit_case",
]


def rng_from(seed):
    """A numpy Generator from an int seed (or the Generator itself)."""
    if isinstance(seed, np.random.Generator):
        return seed
    if seed is None:
        raise ValueError("give an explicit seed (an int) so that the deck is reproducible")
    return np.random.default_rng(seed)


def uniform_radii(n, rmin, rmax, seed):
    """n radii uniform in [rmin, rmax]."""
    if not 0.0 < rmin <= rmax:
        raise ValueError(f"need 0 < rmin <= rmax, got {rmin}, {rmax}")
    return rng_from(seed).uniform(rmin, rmax, int(n))


# --------------------------------------------------------------------------------------
# disk positions
# --------------------------------------------------------------------------------------

def lattice_positions(radii, width, seed, x0=0.0, y0=0.0, spacing=None, shuffle=True):
    """Centres for disks of the given radii on a square lattice filling a strip
    [x0, x0 + width] row by row from y0 upwards, each disk jittered at random
    inside its own lattice cell (so no two disks overlap, and none crosses x0,
    x0 + width or y0). Cell size: ``spacing`` (default 2.02*max radius).
    Returns (n, 2) centres; the order of the disks is shuffled over the cells
    when ``shuffle`` (otherwise the radii fill the cells in order)."""
    radii = np.asarray(radii, dtype=float)
    rng = rng_from(seed)
    rmax = float(radii.max())
    s = 2.02 * rmax if spacing is None else float(spacing)
    if s < 2.0 * rmax:
        raise ValueError(f"lattice spacing {s} smaller than the largest diameter {2 * rmax}")
    ncol = int(math.floor(width / s))
    if ncol < 1:
        raise ValueError(f"width {width} too small for disks of radius {rmax}")
    n = len(radii)
    cells = np.arange(n)
    if shuffle:
        cells = rng.permutation(n)
    i, j = cells % ncol, cells // ncol
    margin = 0.5 * (width - ncol * s)          # centre the lattice in the strip
    cx = x0 + margin + (i + 0.5) * s
    cy = y0 + (j + 0.5) * s
    free = 0.5 * s - radii                      # room for the jitter
    cx = cx + rng.uniform(-1.0, 1.0, n) * free
    cy = cy + rng.uniform(-1.0, 1.0, n) * free
    return np.column_stack((cx, cy))


def ballistic_positions(radii, width, seed, x0=0.0, y0=0.0, tries=8, sort_desc=False):
    """Sequential ballistic deposit: each disk, in turn, falls vertically at a
    random abscissa in [x0 + r, x0 + width - r] until it touches the floor y0 or
    a disk already placed; of ``tries`` random abscissae the lowest resting place
    is kept (denser than one try). Disks touch (gap 0) but never overlap.
    Returns (n, 2) centres (disks are placed in the given order, or largest first
    when sort_desc)."""
    radii = np.asarray(radii, dtype=float)
    rng = rng_from(seed)
    n = len(radii)
    if 2.0 * radii.max() > width:
        raise ValueError(f"width {width} smaller than the largest diameter")
    order = np.argsort(-radii, kind="stable") if sort_desc else np.arange(n)
    X = np.empty(n)
    Y = np.empty(n)
    R = np.empty(n)
    placed = 0
    out = np.empty((n, 2))
    # column buckets: only disks whose x-interval meets the falling disk's matter
    for k in order:
        r = radii[k]
        xs = rng.uniform(x0 + r, x0 + width - r, int(tries))
        best_y, best_x = math.inf, xs[0]
        if placed:
            px, py, pr = X[:placed], Y[:placed], R[:placed]
        for x in xs:
            y = y0 + r
            if placed:
                dx = np.abs(px - x)
                s = pr + r
                m = dx < s
                if np.any(m):
                    y = max(y, float(np.max(py[m] + np.sqrt(s[m] ** 2 - dx[m] ** 2))))
            if y < best_y:
                best_y, best_x = y, x
        X[placed], Y[placed], R[placed] = best_x, best_y, r
        placed += 1
        out[k] = (best_x, best_y)
    return out


def deposit_disks(case, radii, width, material, color="BLEUx", seed=1, method="lattice",
                  x0=0.0, y0=0.0, velocity=None, **kw):
    """Add disks of the given radii to ``case``, placed without overlap above y0 in
    the strip [x0, x0 + width]: method 'lattice' (jittered square lattice, a loose
    cloud that then falls) or 'ballistic' (a dense-ish sequential deposit, disks
    touching). ``velocity`` (vx, vy, omega) or an (n, 3) array sets initial
    velocities. Returns the list of new bodies."""
    rng = rng_from(seed)
    if method == "lattice":
        c = lattice_positions(radii, width, rng, x0, y0, **kw)
    elif method == "ballistic":
        c = ballistic_positions(radii, width, rng, x0, y0, **kw)
    else:
        raise ValueError(f"method must be 'lattice' or 'ballistic', got {method!r}")
    bodies = []
    for k, (r, (x, y)) in enumerate(zip(radii, c)):
        b = case.add_disk((x, y), float(r), material, color)
        if velocity is not None:
            v = np.asarray(velocity, dtype=float)
            b.set_velocity(*(v[k] if v.ndim == 2 else v))
        bodies.append(b)
    return bodies


def top_of(case, bodies=None):
    """Highest point of the disks/polygons of ``bodies`` (default: all bodies)."""
    bodies = case.bodies if bodies is None else bodies
    top = -math.inf
    for b in bodies:
        for c in b.contactors:
            if c.kind == "DISKx":
                top = max(top, b.coor[1] + c.radius)
            elif c.kind == "POLYG":
                top = max(top, b.coor[1] + float(c.vertices[:, 1].max()))
    return top


# --------------------------------------------------------------------------------------
# walls
# --------------------------------------------------------------------------------------

def box_walls(case, xmin, xmax, ymin, ymax, half_thickness, material, color="WALLx", top=False,
              overlap=None):
    """Fixed JONCx walls whose inner faces are x = xmin, x = xmax, y = ymin (and
    y = ymax when ``top``). ``half_thickness`` is the JONCx ax2 (as pylmgc90's
    rigidJonc axe2). The side walls are JONCx rotated by -/+pi/2, the rotation being
    written to DOF.INI as in LMGC90 decks. ``overlap``: how far the floor (and
    roof) extend past the inner faces of the side walls (default 2*half_thickness).
    Returns a dict with keys 'bottom', 'left', 'right' (and 'top')."""
    t = float(half_thickness)
    ext = 2.0 * t if overlap is None else float(overlap)
    lx, ly = xmax - xmin, ymax - ymin
    if lx <= 0 or ly <= 0:
        raise ValueError("box_walls: need xmax > xmin and ymax > ymin")
    walls = {}
    walls["bottom"] = case.add_jonc((0.5 * (xmin + xmax), ymin - t), 0.5 * lx + ext, t, material, color)
    if top:
        walls["top"] = case.add_jonc((0.5 * (xmin + xmax), ymax + t), 0.5 * lx + ext, t, material, color)
    walls["left"] = case.add_jonc((xmin - t, 0.5 * (ymin + ymax)), 0.5 * ly + ext, t, material, color,
                                  angle=-0.5 * math.pi)
    walls["right"] = case.add_jonc((xmax + t, 0.5 * (ymin + ymax)), 0.5 * ly + ext, t, material, color,
                                   angle=0.5 * math.pi)
    for w in walls.values():
        w.fix()
    return walls


def add_granular_laws(case, fric_grains=0.3, fric_walls=0.5, alert=1e-3, grain_type="DISKx",
                      grain_color="BLEUx", wall_type="JONCx", wall_color="WALLx",
                      law="IQS_CLB", names=("iqsgg", "iqsgw")):
    """The two usual laws and see rules of a granular sample in a box:
    grain/grain (fric_grains) and grain/wall (fric_walls), both ``law``."""
    lg = case.add_law(names[0], law, fric=fric_grains)
    lw = case.add_law(names[1], law, fric=fric_walls)
    case.add_see(grain_type, grain_color, grain_type, grain_color, lg, alert)
    case.add_see(grain_type, grain_color, wall_type, wall_color, lw, alert)
    return lg, lw


# --------------------------------------------------------------------------------------
# polygons
# --------------------------------------------------------------------------------------

def regular_polygon(n_vertices, radius, angle=0.0):
    """A regular polygon inscribed in a circle of ``radius``, centred at the origin,
    first vertex at ``angle``; counter-clockwise."""
    a = angle + 2.0 * math.pi * np.arange(int(n_vertices)) / int(n_vertices)
    return np.column_stack((radius * np.cos(a), radius * np.sin(a)))


def random_convex_polygon(n_vertices, radius, seed, jitter=0.3, centered=True):
    """A random convex polygon of n vertices on a circle of ``radius``: vertex k at
    angle a0 + 2*pi*(k + u_k)/n with u_k uniform in [-jitter, jitter] (jitter < 0.5
    keeps the angles increasing, hence a convex, counter-clockwise polygon) and a
    random orientation a0. With ``centered`` the centroid is moved to the origin."""
    if n_vertices < 3:
        raise ValueError("a polygon needs at least 3 vertices")
    if not 0.0 <= jitter < 0.5:
        raise ValueError("jitter must be in [0, 0.5)")
    rng = rng_from(seed)
    n = int(n_vertices)
    a = rng.uniform(0.0, 2.0 * math.pi) + 2.0 * math.pi * (np.arange(n) + rng.uniform(-jitter, jitter, n)) / n
    v = np.column_stack((radius * np.cos(a), radius * np.sin(a)))
    if polygon_area(v) <= 0.0:           # cannot happen for jitter < 0.5; be safe
        v = v[::-1]
    if centered:
        from .pre import polygon_centroid
        v = v - polygon_centroid(v)
    return v


def deposit_polygons(case, n, rmin, rmax, width, material, color="BLEUx", seed=1,
                     n_vertices=(4, 7), x0=0.0, y0=0.0, jitter=0.3):
    """n random convex polygons (circumradius uniform in [rmin, rmax], vertex count
    uniform in n_vertices[0]..n_vertices[1]) on a jittered lattice above y0 in
    [x0, x0 + width], without overlap. Returns the new bodies."""
    rng = rng_from(seed)
    polys = []
    for r in rng.uniform(rmin, rmax, int(n)):
        nv = int(rng.integers(n_vertices[0], n_vertices[1] + 1))
        polys.append(random_convex_polygon(nv, r, rng, jitter))
    # bounding radius about the centroid (can exceed the circumradius once centred)
    bound = np.array([np.hypot(v[:, 0], v[:, 1]).max() for v in polys])
    centres = lattice_positions(bound, width, rng, x0, y0)
    return [case.add_polygon(v + c, material, color) for v, c in zip(polys, centres)]


# --------------------------------------------------------------------------------------
# masonry
# --------------------------------------------------------------------------------------

def _rect(x0, y0, x1, y1):
    return np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], dtype=float)


def masonry_wall(case, n_courses, bricks_per_course, brick_length, brick_height, material,
                 color="BLEUx", x0=0.0, y0=0.0, joint=0.0, ground=True, ground_material=None,
                 ground_color="WALLx", ground_thickness=None):
    """A running-bond wall of POLYG bricks standing on y = y0 from x = x0:
    odd courses (counting from 0) are offset by half a brick, with half bricks at
    both ends, so the wall has straight vertical edges. ``joint`` is an empty gap
    left between neighbouring bricks and courses (0: bricks touch). With
    ``ground``, a fixed JONCx ground (top face y = y0) is added.
    Returns dict(bricks=[[bodies of course 0], ...], ground=body or None)."""
    L, H, j = float(brick_length), float(brick_height), float(joint)
    length = bricks_per_course * L + (bricks_per_course - 1) * j
    courses = []
    for k in range(int(n_courses)):
        yb = y0 + k * (H + j)
        if k % 2 == 0:
            xs = [(x0 + i * (L + j), x0 + i * (L + j) + L) for i in range(bricks_per_course)]
        else:
            half = 0.5 * (L - j)
            xs = [(x0, x0 + half)]
            x = x0 + half + j
            for i in range(bricks_per_course - 1):
                xs.append((x, x + L))
                x += L + j
            xs.append((x, x0 + length))
        courses.append([case.add_polygon(_rect(a, yb, b, yb + H), material, color) for a, b in xs])
    g = None
    if ground:
        t = 0.5 * H if ground_thickness is None else float(ground_thickness)
        g = case.add_jonc((x0 + 0.5 * length, y0 - t), 0.5 * length + 2.0 * L, t,
                          ground_material or material, ground_color)
        g.fix()
    return {"bricks": courses, "ground": g}


def arch(case, n_voussoirs, mean_radius, thickness, material, color="BLEUx", center=(0.0, 0.0),
         supports=True, support_material=None, support_color=None, support_height=None,
         support_width=None):
    """A semicircular arch of N voussoirs of radial thickness t around a circle of
    mean radius R centred at ``center`` (springing line y = center_y): voussoir k
    spans the angles [pi*k/N, pi*(k+1)/N] between radii R - t/2 and R + t/2, with
    radial joints (4-vertex POLYG, counter-clockwise). With ``supports``, two fixed
    rectangular POLYG blocks carry the springers (top faces on the springing line).
    Returns dict(voussoirs=[...], supports=[left, right] or [])."""
    R, t = float(mean_radius), float(thickness)
    if not 0.0 < t < 2.0 * R:
        raise ValueError("need 0 < thickness < 2*mean_radius")
    cx, cy = center
    ri, ro = R - 0.5 * t, R + 0.5 * t
    vous = []
    for k in range(int(n_voussoirs)):
        a0, a1 = math.pi * k / n_voussoirs, math.pi * (k + 1) / n_voussoirs
        c0, s0, c1, s1 = math.cos(a0), math.sin(a0), math.cos(a1), math.sin(a1)
        v = np.array([[cx + ri * c0, cy + ri * s0], [cx + ro * c0, cy + ro * s0],
                      [cx + ro * c1, cy + ro * s1], [cx + ri * c1, cy + ri * s1]])
        vous.append(case.add_polygon(v, material, color))
    sup = []
    if supports:
        h = t if support_height is None else float(support_height)
        w = 2.0 * t if support_width is None else float(support_width)
        for xc in (cx - R, cx + R):
            b = case.add_polygon(_rect(xc - 0.5 * w, cy - h, xc + 0.5 * w, cy),
                                 support_material or material, support_color or color)
            b.fix()
            sup.append(b)
    return {"voussoirs": vous, "supports": sup}


# --------------------------------------------------------------------------------------
# ready-made decks
# --------------------------------------------------------------------------------------

def deposit_case(n=2000, seed=1, rmin=None, rmax=None, width=None, fric_grains=0.3,
                 fric_walls=0.5, density=2600.0, time_step=1e-3, duration=1.0,
                 method="lattice", output_vtk_every=None, output_dof_every=None,
                 output_hdf5_every=None, alert=None):
    """A ready-to-run deposit: n disks (radii uniform in [rmin, rmax]) placed
    without overlap in a box and falling under gravity, fixed JONCx walls, IQS_CLB
    friction, run control for ``duration`` seconds. Defaults scale with n: radii
    [0.004, 0.006] m for n >= 1000, [0.008, 0.012] m below; a box about
    sqrt(n)*0.8 diameters wide."""
    if rmin is None or rmax is None:
        rmin, rmax = (0.004, 0.006) if n >= 1000 else (0.008, 0.012)
    dmean = rmin + rmax
    if width is None:
        width = round(max(8.0, 0.8 * math.sqrt(n)) * dmean * 1.05, 3)
    case = Case(gravity=(0.0, -9.81, 0.0))
    case.add_material("STONE", density=density)
    case.add_material("TDURx", density=1000.0)
    rng = rng_from(seed)
    radii = uniform_radii(n, rmin, rmax, rng)
    disks = deposit_disks(case, radii, width, "STONE", "BLEUx", rng, method=method)
    top = top_of(case, disks)
    box_walls(case, 0.0, width, 0.0, top + 4.0 * rmax, 0.5 * rmax + 0.005, "TDURx", "WALLx")
    if alert is None:
        # A pair must be seen before it touches: the alert distance must exceed
        # what a disk travels in one step at its impact speed sqrt(2 g top).
        alert = max(0.25 * rmin, 1.2 * math.sqrt(2.0 * 9.81 * top) * time_step)
    add_granular_laws(case, fric_grains, fric_walls, alert)
    nsteps = int(round(duration / time_step))
    vtk = output_vtk_every if output_vtk_every is not None else max(1, nsteps // 100)
    dof = output_dof_every if output_dof_every is not None else max(1, nsteps // 10)
    h5 = output_hdf5_every if output_hdf5_every is not None else max(1, nsteps // 100)
    case.run.set(time_step=time_step, number_of_steps=nsteps, theta=0.5,
                 nlgs_check="Quad", nlgs_tolerance=1e-4, nlgs_relaxation=1.0,
                 nlgs_sweeps_per_check=50, nlgs_max_checks=400,
                 output_dof_every=dof, output_vtk_every=vtk, output_hdf5_every=h5,
                 progress_every=max(1, nsteps // 20))
    return case


def demo_deposit(case_dir, n=400, seed=1):
    """The project's default demo deck: n disks (radii 8-12 mm) in a loose jittered
    lattice falling into a 0.4 m wide box of fixed JONCx walls; IQS_CLB friction
    0.3 (disk/disk) and 0.5 (disk/wall); dt = 1e-3 s, 1000 steps (1 s); VTK and
    HDF5 snapshots every 10 steps, DOF/Vloc_Rloc files every 100 steps.
    Writes case_dir/DATBOX and returns the Case."""
    case = deposit_case(n=n, seed=seed, rmin=0.008, rmax=0.012,
                        width=0.4 if n <= 600 else None, time_step=1e-3, duration=1.0,
                        output_vtk_every=10, output_dof_every=100, output_hdf5_every=10)
    case.write(case_dir)
    return case


def demo_masonry(case_dir, n_courses=8, bricks_per_course=6):
    """A running-bond wall of 0.2 x 0.1 m bricks on a fixed ground (IQS_CLB 0.6),
    standing under gravity for 0.5 s (dt 1e-3). Writes case_dir and returns the Case."""
    case = Case(gravity=(0.0, -9.81))
    case.add_material("BRICK", density=2000.0)
    case.add_material("TDURx", density=1000.0)
    masonry_wall(case, n_courses, bricks_per_course, 0.2, 0.1, "BRICK", "BLEUx",
                 ground_material="TDURx")
    case.add_law("iqsbb", "IQS_CLB", fric=0.6)
    case.add_law("iqsbg", "IQS_CLB", fric=0.8)
    case.add_see("POLYG", "BLEUx", "POLYG", "BLEUx", "iqsbb", 1e-3)
    case.add_see("POLYG", "BLEUx", "JONCx", "WALLx", "iqsbg", 1e-3)
    case.run.set(time_step=1e-3, number_of_steps=500, output_vtk_every=10, output_hdf5_every=10)
    case.write(case_dir)
    return case


def demo_arch(case_dir, n_voussoirs=11, mean_radius=1.0, thickness=0.15):
    """A semicircular arch of voussoirs on two fixed supports (IQS_CLB 0.7), under
    gravity for 1 s (dt 1e-3). t/R = 0.15 is above the minimum thickness of a
    semicircular arch (about 0.107 R), so it should stand."""
    case = Case(gravity=(0.0, -9.81))
    case.add_material("STONE", density=2500.0)
    arch(case, n_voussoirs, mean_radius, thickness, "STONE", "BLEUx")
    case.add_law("iqsvv", "IQS_CLB", fric=0.7)
    case.add_see("POLYG", "BLEUx", "POLYG", "BLEUx", "iqsvv", 1e-3)
    case.run.set(time_step=1e-3, number_of_steps=1000, output_vtk_every=10, output_hdf5_every=10)
    case.write(case_dir)
    return case
