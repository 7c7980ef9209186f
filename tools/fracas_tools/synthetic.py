"""A synthetic OUTBOX/fracas.h5 with the documented layout, for tests and demos of
the post-processing tools before (or without) a real run.

The scene: equal disks in a triangular (hexagonal) packing resting in a box of 3
fixed JONCx walls (floor, left, right), with roughly hydrostatic contact forces.
The time series mimic a settling run (kinetic energy decaying, gravity work
levelling off, dissipation = work - kinetic energy).

    from fracas_tools.synthetic import make_case
    make_case("/tmp/synthetic_case")      # DATBOX/ + OUTBOX/fracas.h5
    # python3 -m fracas_tools report /tmp/synthetic_case

Layout written (h5py shapes; Fortran writes the transposes):
  root attrs: program, version, case_dir, complete, time_step, theta (+ layout_version)
  /bodies/{number, mass, inertia, radius, reference (nb,3)}
  /series/<name> (nsteps,)
  /snapshots/000001.../ attrs step, time; bodies/{X, V} (nb,3);
      contacts/{inter, cd_body, an_body, cd_tactor, an_tactor, status, law (nc,),
                normal, point, reaction, velocity (nc,2), gap (nc,)}
  /help/{status_names, inter_names, law_names} (help_style='brief', the names of
      the tools brief) or /help/{status, inter, law} + /snapshot_index/{step,time}
      (help_style='writer', the names of modules/io/fracas_results_h5.f90).
"""

import math
from pathlib import Path

import numpy as np

STATUS_NAMES = ["noctc", "stick", "slifw", "slibw", "noact", "Cnctc", "Cstck", "Cslfw", "Cslbw"]
INTER_NAMES = ["DKDKx", "DKJCx", "DKKDx", "DKPLx", "PLPLx", "PLJCx"]
INTEGER_SERIES = {"step", "contacts", "active_contacts", "sweeps", "converged", "newton_iterations",
                  "broken_interfaces", "damaged_interfaces"}
SERIES = ["step", "time", "contacts", "sweeps", "converged", "residual_natural_map", "quad_dv",
          "maxm_dv", "kinetic_energy", "work_gravity", "work_driven", "dissipated",
          "balance_error", "mean_overlap", "max_overlap", "wall_time"]


def packing_geometry(nx=10, ny=6, radius=0.01):
    """Centres of nx*ny (alternate rows nx-1) equal disks in a triangular packing
    on the floor y = 0 between x = 0 and the returned width."""
    r = radius
    xs, ys = [], []
    for j in range(ny):
        y = r + j * r * math.sqrt(3.0)
        if j % 2 == 0:
            xs += [r + 2 * r * i for i in range(nx)]
            ys += [y] * nx
        else:
            xs += [2 * r + 2 * r * i for i in range(nx - 1)]
            ys += [y] * (nx - 1)
    width = 2 * r * nx
    return np.column_stack((xs, ys)), width


def scene(nx=10, ny=6, radius=0.01, wall_half_thickness=0.005):
    """(grain centres, width, height, wall list [(centre, ax1, ax2, angle)])."""
    c, width = packing_geometry(nx, ny, radius)
    height = float(c[:, 1].max() + radius)
    t = wall_half_thickness
    walls = [((0.5 * width, -t), 0.5 * width + 2 * t, t, 0.0),
             ((-t, 0.5 * height + 0.02), 0.5 * height + 0.02 + 2 * t, t, -0.5 * math.pi),
             ((width + t, 0.5 * height + 0.02), 0.5 * height + 0.02 + 2 * t, t, 0.5 * math.pi)]
    return c, width, height, walls


def _contacts(c, radius, width, nb_grains, rng, density=2600.0, g=9.81, fric=0.3):
    """Contacts of the settled packing: (inter, cd, an, normal, point, rn, rt, status, law, gap)."""
    rows = []
    n = len(c)
    height = c[:, 1].max() + radius
    d = c[:, None, :] - c[None, :, :]
    dist = np.sqrt((d ** 2).sum(-1))
    for i in range(n):
        for j in range(i + 1, n):
            if dist[i, j] < 2 * radius * (1 + 1e-9):
                # lower index is candidate, normal from antagonist to candidate
                nrm = (c[i] - c[j]) / dist[i, j]
                pt = c[j] + nrm * radius
                rows.append((1, i, j, nrm, pt, 1))
            elif dist[i, j] < 2.05 * radius:         # inside the alert distance, open
                nrm = (c[i] - c[j]) / dist[i, j]
                pt = c[j] + nrm * radius
                rows.append((1, i, j, nrm, pt, 0))
    for i in range(n):
        if c[i, 1] - radius < 1e-12:                 # floor, body nb_grains
            rows.append((2, i, nb_grains, np.array([0.0, 1.0]), np.array([c[i, 0], 0.0]), 2))
        if c[i, 0] - radius < 1e-12:                 # left wall
            rows.append((2, i, nb_grains + 1, np.array([1.0, 0.0]), np.array([0.0, c[i, 1]]), 2))
        if width - c[i, 0] - radius < 1e-12:         # right wall
            rows.append((2, i, nb_grains + 2, np.array([-1.0, 0.0]), np.array([width, c[i, 1]]), 2))
    nc = len(rows)
    inter = np.array([r[0] for r in rows], dtype=np.int32)
    cd = np.array([r[1] for r in rows], dtype=np.int64)
    an = np.array([r[2] for r in rows], dtype=np.int64)
    normal = np.array([r[3] for r in rows]).reshape(nc, 2)
    point = np.array([r[4] for r in rows]).reshape(nc, 2)
    closed = np.array([r[5] > 0 for r in rows])
    law = np.array([r[5] if r[5] > 0 else 1 for r in rows], dtype=np.int32)
    # hydrostatic-like normal force: weight of the column above the contact, per contact
    w = density * math.pi * radius ** 2 * g
    depth = np.maximum(height - point[:, 1], radius)
    rn = np.where(closed, w * depth / (2.0 * radius) * rng.uniform(0.3, 1.7, nc)
                  * np.where(np.abs(normal[:, 1]) > 0.3, 1.0, 0.4), 0.0)
    ratio = rng.uniform(-1.0, 1.0, nc)
    rt = np.where(closed, fric * rn * np.clip(1.2 * ratio, -1.0, 1.0), 0.0)
    status = np.where(~closed, 1, np.where(ratio > 1 / 1.2, 3, np.where(ratio < -1 / 1.2, 4, 2)))
    gap = np.where(closed, -rng.uniform(0.0, 1e-6, nc) * radius, rng.uniform(0.0, 0.05, nc) * radius)
    return inter, cd, an, normal, point, rn, rt, status.astype(np.int32), law, gap


def make_h5(path, nx=10, ny=6, radius=0.01, n_steps=200, snapshot_every=50, time_step=1e-3,
            theta=0.5, seed=0, complete=True, missing=(), help_style="brief",
            x_is="displacement", case_dir="", drop=0.02, version="0.0.0-synthetic"):
    """Write a synthetic fracas.h5 at ``path`` (see the module docstring).
    ``missing``: series names to leave out; ``x_is``: 'displacement' (X = position
    - reference, as LMGC90's DOF files) or 'position'; the reference configuration
    is the settled packing lifted by ``drop`` metres. Returns the path."""
    import h5py

    rng = np.random.default_rng(seed)
    c, width, height, walls = scene(nx, ny, radius)
    ng = len(c)
    nb = ng + len(walls)
    density = 2600.0
    mass = np.empty(nb)
    inertia = np.empty(nb)
    rad = np.empty(nb)
    ref = np.zeros((nb, 3))
    mass[:ng] = density * math.pi * radius ** 2
    inertia[:ng] = mass[:ng] * radius ** 2 / 2
    rad[:ng] = radius
    ref[:ng, :2] = c + np.array([0.0, drop])
    for k, (cen, a1, a2, ang) in enumerate(walls):
        area = 4 * a1 * a2 + math.pi * a2 ** 2
        rad[ng + k] = math.sqrt(area / math.pi)
        mass[ng + k] = 1000.0 * area
        inertia[ng + k] = mass[ng + k] * (a1 ** 2 + a2 ** 2) / 3
        ref[ng + k, :2] = cen
    inter, cd, an, normal, point, rn, rt, status, law, gap = _contacts(c, radius, width, ng, rng, density)

    steps = np.arange(1, n_steps + 1)
    t = steps * time_step
    tau = 0.25 * n_steps * time_step
    w_grav = mass[:ng].sum() * 9.81 * drop * (1 - np.exp(-t / tau))
    ke = 0.5 * w_grav * np.exp(-t / (0.5 * tau)) + 1e-9
    diss = w_grav - ke
    bal = (w_grav - ke - diss) + rng.normal(0, 1e-9, n_steps)
    sweeps = rng.integers(50, 600, n_steps).astype(float)
    conv = np.ones(n_steps)
    conv[rng.choice(n_steps, max(1, n_steps // 50), replace=False)] = 0
    series = {
        "step": steps.astype(float), "time": t,
        "contacts": np.full(n_steps, float(len(inter))) - rng.integers(0, 5, n_steps),
        "sweeps": sweeps, "converged": conv,
        "residual_natural_map": 10 ** rng.uniform(-7, -4, n_steps),
        "quad_dv": rng.uniform(0.05, 1.0, n_steps), "maxm_dv": rng.uniform(0.5, 10.0, n_steps),
        "kinetic_energy": ke, "work_gravity": w_grav, "work_driven": np.zeros(n_steps),
        "dissipated": diss, "balance_error": bal,
        "mean_overlap": 10 ** rng.uniform(-9, -8, n_steps) * radius,
        "max_overlap": 10 ** rng.uniform(-7, -6, n_steps) * radius,
        "wall_time": np.cumsum(rng.uniform(1e-3, 3e-3, n_steps)),
    }
    names = [s for s in SERIES if s not in missing]

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with h5py.File(path, "w") as f:
        f.attrs["program"] = "fracas"
        f.attrs["version"] = version
        f.attrs["case_dir"] = str(case_dir)
        f.attrs["complete"] = np.int32(1 if complete else 0)
        f.attrs["time_step"] = float(time_step)
        f.attrs["theta"] = float(theta)
        if help_style == "writer":
            f.attrs["layout_version"] = np.int32(1)
        gb = f.create_group("bodies")
        gb.create_dataset("number", data=np.arange(1, nb + 1, dtype=np.int32))
        gb.create_dataset("mass", data=mass)
        gb.create_dataset("inertia", data=inertia)
        gb.create_dataset("radius", data=rad)
        gb.create_dataset("reference", data=ref)
        gs = f.create_group("series")
        gs.attrs["columns"] = ",".join(names)
        for s in names:
            data = np.asarray(series[s])
            if s in INTEGER_SERIES:      # as fracas writes them (doc/output_layout.md §1.3)
                data = data.astype(np.int32)
            gs.create_dataset(s, data=data, maxshape=(None,))
        gsn = f.create_group("snapshots")
        snap_steps = [s for s in steps if s % snapshot_every == 0]
        if not snap_steps or snap_steps[0] != 1:
            snap_steps = [1] + snap_steps
        for k, s in enumerate(snap_steps, start=1):
            time = s * time_step
            frac = math.exp(-time / (0.3 * tau))      # remaining height of the drop
            pos = np.zeros((nb, 3))
            pos[:ng, :2] = c + np.array([0.0, drop * frac])
            pos[:ng, 2] = rng.normal(0, 0.01, ng) * (1 - frac)
            pos[ng:, :2] = ref[ng:, :2]
            pos[ng:, 2] = [w[3] for w in walls]        # side walls turned by -/+ pi/2
            X = pos - ref if x_is == "displacement" else pos
            V = np.zeros((nb, 3))
            V[:ng, 1] = -drop * frac / (0.3 * tau)
            g = gsn.create_group("%06d" % k)
            g.attrs["step"] = np.int32(s)
            g.attrs["time"] = float(time)
            bg = g.create_group("bodies")
            bg.create_dataset("X", data=X)
            bg.create_dataset("V", data=V)
            cg = g.create_group("contacts")
            scale = 1.0 - frac
            cg.create_dataset("inter", data=inter)
            cg.create_dataset("cd_body", data=(cd + 1).astype(np.int32))
            cg.create_dataset("an_body", data=(an + 1).astype(np.int32))
            cg.create_dataset("cd_tactor", data=np.ones(len(inter), dtype=np.int32))
            cg.create_dataset("an_tactor", data=np.ones(len(inter), dtype=np.int32))
            cg.create_dataset("status", data=status)
            cg.create_dataset("law", data=law)
            cg.create_dataset("normal", data=normal)
            cg.create_dataset("point", data=point + np.array([0.0, drop * frac]))
            cg.create_dataset("reaction", data=np.column_stack((rt * scale, rn * scale)))
            cg.create_dataset("velocity", data=rng.normal(0, 1e-4, (len(inter), 2)))
            cg.create_dataset("gap", data=gap)
        gsn.attrs["count"] = np.int32(len(snap_steps))
        gh = f.create_group("help")
        sdt = h5py.string_dtype()
        keys = ("status_names", "inter_names", "law_names") if help_style == "brief" else \
            ("status", "inter", "law")
        gh.create_dataset(keys[0], data=np.array(STATUS_NAMES, dtype=object), dtype=sdt)
        gh.create_dataset(keys[1], data=np.array(INTER_NAMES, dtype=object), dtype=sdt)
        gh.create_dataset(keys[2], data=np.array(["iqsgg", "iqsgw"], dtype=object), dtype=sdt)
        if help_style == "writer":
            gh.create_dataset("series_columns", data=np.array(names, dtype="S32"))
            gi = f.create_group("snapshot_index")
            gi.create_dataset("step", data=np.array(snap_steps, dtype=np.int32))
            gi.create_dataset("time", data=np.array(snap_steps) * time_step)
    return path


def make_case(case_dir, nx=10, ny=6, radius=0.01, **kw):
    """A case directory matching the synthetic file: DATBOX written with pre.Case
    (the settled packing lifted by ``drop``, the 3 walls) and OUTBOX/fracas.h5."""
    from .pre import Case

    drop = kw.get("drop", 0.02)
    c, width, height, walls = scene(nx, ny, radius)
    case = Case(gravity=(0.0, -9.81))
    case.add_material("STONE", density=2600.0)
    case.add_material("TDURx", density=1000.0)
    for x, y in c:
        case.add_disk((x, y + drop), radius, "STONE", "BLEUx")
    for cen, a1, a2, ang in walls:
        case.add_jonc(cen, a1, a2, "TDURx", "WALLx", angle=ang).fix()
    case.add_law("iqsgg", "IQS_CLB", fric=0.3)
    case.add_law("iqsgw", "IQS_CLB", fric=0.5)
    case.add_see("DISKx", "BLEUx", "DISKx", "BLEUx", "iqsgg", 0.1 * radius)
    case.add_see("DISKx", "BLEUx", "JONCx", "WALLx", "iqsgw", 0.1 * radius)
    case.run.set(time_step=kw.get("time_step", 1e-3), number_of_steps=kw.get("n_steps", 200))
    case.write(case_dir)
    make_h5(Path(case_dir) / "OUTBOX" / "fracas.h5", nx, ny, radius, case_dir=str(case_dir), **kw)
    return Path(case_dir)
