#!/usr/bin/env python3
"""Tagged regression values of a Fracas run (DFTB+ "tagged output" style).

From a run's OUTBOX/fracas.h5 (and the case's DATBOX/BODIES.DAT, to tell disks
from walls) compute named, physically meaningful statistics and write them one
per line as ``name : value``::

    build/release/bin/fracas-python tools/regression/tagged.py RUN_DIR [--case CASE_DIR] [-o run.tag]

RUN_DIR is the directory that holds OUTBOX/ (the case directory, or the
``--output`` directory of the run). CASE_DIR (default: the ``case_dir`` attribute
of fracas.h5, then RUN_DIR) holds DATBOX/.

A reference is made (never by hand) with tools/regression/regenerate.py (runs the
case, then calls this), or directly from a finished run::

    build/release/bin/fracas-python tools/regression/tagged.py RUN_DIR --case CASE_DIR \\
        --make-reference CASE_DIR/reference.tag --tolerances CASE_DIR/tolerances.txt

which writes the run's values together with the tolerance of every tag, read
from the hand-written tolerances file (``name  abs  rel  # why``). Every tag must
have a tolerance there, and every tolerance a tag. tools/regression/compare.py
compares a run with the reference.

The tags (all from the last snapshot unless said otherwise; forces are the
solver's reactions, i.e. impulse / time step; "loaded" contact: rn > 0):

  steps, final_time                 run length
  n_disks                           number of bodies carrying a DISKx
  contacts_listed_final             contacts in the solver's list (gap < alert) at the end
  contacts_loaded_final             loaded contacts at the end (disk/disk + disk/wall)
  contacts_disk_wall_final          loaded disk/wall contacts at the end
  coordination_mean                 2 * loaded disk/disk contacts / n_disks
  coordination_with_walls           (2 * disk/disk + disk/wall) loaded contacts / n_disks
  rattler_fraction                  disks with fewer than 2 loaded contacts (walls count)
  normal_force_mean, _std           over loaded contacts
  normal_force_over_mean_p90, _p99  90th and 99th percentiles of rn / <rn> (shape and tail of the
                                    force distribution; the maximum itself moves by 60 % between
                                    runs that differ only in the contact order)
  tangential_force_ratio_mean       mean |rt| / (mu rn) over loaded contacts (friction mobilisation)
  sliding_fraction                  fraction of loaded contacts with |rt| >= 0.999 mu rn
  weight_total                      total weight of the disks (m g)
  wall_vertical_force_over_weight   sum of vertical wall reactions / weight (1 at rest)
  floor_force_over_weight           vertical reaction of the lowest wall / weight (Janssen)
  packing_height                    95th percentile over disks of (y + r): the top of the packing
                                    (the single highest disk moves by 8 mm between order variants)
  com_height                        mass-weighted mean height of the disks
  solid_fraction_core               disk area fraction in the box interior window
                                    (from 5 rmax above the floor and off the side walls
                                    to 5 rmax below the packing's top, exact circle clipping)
  kinetic_energy_final              from /series
  kinetic_energy_peak               max of the series
  time_of_peak_kinetic_energy
  work_gravity_total, dissipated_total
  energy_balance_error_max          max |balance_error| over the run
  energy_balance_error_rel          energy_balance_error_max / work_gravity_total
  potential_energy_drop             m g (y_initial - y_final) summed over disks (= work of gravity, exact to O(dt))
  max_overlap                       largest interpenetration over the run
  max_overlap_final                 largest interpenetration at the end
  max_overlap_over_rmin             max_overlap / smallest disk radius
  mean_overlap_final
  sweeps_total, sweeps_mean_per_step, sweeps_max_per_step
  contact_sweeps_total              sum over steps of contacts x sweeps (NLGS work)
  nonconverged_steps                steps whose NLGS hit nlgs_max_checks
  residual_natural_map_max          worst natural-map residual over the run
  residual_natural_map_final
  settle_time                       first time after which the kinetic energy stays below
                                    1e-3 of its peak (lower thresholds are not robust: the
                                    slow creep of the last grains varies from run to run)

With ``--hash`` a tag ``state_sha256`` (SHA-256 of the bytes of the last snapshot's
X, V and contact reactions) is added: for determinism checks of two runs on one
machine only; it is never put into a reference.
"""

import argparse
import hashlib
import re
import sys
from pathlib import Path

import numpy as np

from fracas_tools import datbox  # noqa: E402  (the one DATBOX reader)
from fracas_tools.results import Run  # noqa: E402  (the one reader of fracas.h5)

FORMAT_VERSION = 1


# ----------------------------------------------------------------------------
# small readers
# ----------------------------------------------------------------------------

def body_contactor_kinds(bodies_dat):
    """Per body (in BODIES.DAT order), the list of its contactor types (DISKx,
    JONCx, ...; a meshed body's CLxxx points and ALpxx segments one each), read by
    fracas_tools.datbox."""
    kinds = []
    for body in datbox.read_bodies(bodies_dat):
        if body.model == "MAILx":
            kinds.append([k for c in body.contactors for k in
                          (["CLxxx"] * len(c.points) if hasattr(c, "points") else ["ALpxx"] * (len(c.nodes) - 1))])
        else:
            kinds.append([c.kind for c in body.contactors])
    return kinds


def find_h5(run_dir):
    p = Path(run_dir)
    if p.is_file():
        return p
    for cand in (p / "OUTBOX" / "fracas.h5", p / "fracas.h5"):
        if cand.is_file():
            return cand
    raise SystemExit(f"tagged.py: no OUTBOX/fracas.h5 under {run_dir}")


def find_case(h5_path, run_dir, case):
    if case:
        return Path(case)
    with Run(h5_path) as f:
        c = f.attrs.get("case_dir")
    for cand in ([Path(c)] if c else []) + [Path(run_dir)]:
        if (cand / "DATBOX" / "BODIES.DAT").is_file():
            return cand
    raise SystemExit("tagged.py: cannot find DATBOX/BODIES.DAT; give --case CASE_DIR")


def _disk_rect_area(cx, cy, r, x0, x1, y0, y1, n=64):
    """Area of the disks (vectorised) inside the rectangle [x0,x1]x[y0,y1]:
    Gauss-Legendre integration over y of the clipped chord length (exact to
    round-off for n = 64 at these sizes)."""
    t, w = np.polynomial.legendre.leggauss(n)
    ylo = np.maximum(cy - r, y0)
    yhi = np.minimum(cy + r, y1)
    ok = yhi > ylo
    cx, cy, r, ylo, yhi = cx[ok], cy[ok], r[ok], ylo[ok], yhi[ok]
    half = 0.5 * (yhi - ylo)
    mid = 0.5 * (yhi + ylo)
    y = mid[:, None] + half[:, None] * t[None, :]
    h = np.sqrt(np.maximum(r[:, None] ** 2 - (y - cy[:, None]) ** 2, 0.0))
    a = np.maximum(cx[:, None] - h, x0)
    b = np.minimum(cx[:, None] + h, x1)
    chord = np.maximum(b - a, 0.0)
    return float(np.sum(half * (chord @ w)))


# ----------------------------------------------------------------------------
# the tags
# ----------------------------------------------------------------------------

def compute_tags(run_dir, case=None, with_hash=False):
    """Return an ordered dict name -> value (int, float or str)."""
    h5_path = find_h5(run_dir)
    case_dir = find_case(h5_path, run_dir, case)
    kinds = body_contactor_kinds(case_dir / "DATBOX" / "BODIES.DAT")
    tags = {}
    with Run(h5_path) as f:
        if not f.complete:
            raise SystemExit(f"tagged.py: {h5_path} is an unfinished run (complete != 1)")
        nb = f.n_bodies
        if len(kinds) != nb:
            raise SystemExit(f"tagged.py: {case_dir}/DATBOX/BODIES.DAT has {len(kinds)} bodies, "
                             f"fracas.h5 {nb}")
        is_disk = np.array(["DISKx" in k for k in kinds])
        is_wall = np.array([("JONCx" in k) and ("DISKx" not in k) for k in kinds])
        mass = np.asarray(f.bodies["mass"], dtype=float)
        radius = np.asarray(f.bodies["radius"], dtype=float)
        ref = f.bodies["reference"]

        # -- series
        cols = f.series
        n = len(cols["step"])
        steps = cols["step"].astype(int)
        t = cols["time"]
        ke = cols["kinetic_energy"]
        sweeps = cols["sweeps"].astype(np.int64)
        ncont = cols["contacts"].astype(np.int64)

        # -- last snapshot (must be the last step)
        if not f.snapshot_names:
            raise SystemExit("tagged.py: no snapshot in fracas.h5 (output_hdf5_every 0?)")
        snap = f.snapshot(-1)
        if snap.step != int(steps[-1]):
            raise SystemExit(f"tagged.py: last snapshot is step {snap.step}, the run "
                             f"ends at step {int(steps[-1])}: make output_hdf5_every divide "
                             f"number_of_steps")
        X = snap.X
        V = snap.V
        c = snap.contacts
        nc = len(c["cd_body"])
        pos = ref + X
        if nc:
            cd = c["cd_body"] - 1
            an = c["an_body"] - 1
            rt, rn = c["reaction"][:, 0], c["reaction"][:, 1]
            nrm = c["normal"]
            law = c["law"] - 1
        else:
            cd = an = law = np.zeros(0, int)
            rt = rn = np.zeros(0)
            nrm = np.zeros((0, 2))
        mu_of_law = law_frictions(case_dir / "DATBOX" / "TACT_BEHAV.DAT", f.help.get("law", []))

        # initial positions (potential energy, floor): reference + DOF.INI displacements
        x0 = initial_displacements(case_dir / "DATBOX" / "DOF.INI", nb)

        g = gravity(case_dir / "DATBOX" / "BULK_BEHAV.DAT")

    # ---------------------------------------------------------------- run length
    tags["steps"] = int(steps[-1])
    tags["final_time"] = float(t[-1])
    nd = int(is_disk.sum())
    tags["n_disks"] = nd

    # ---------------------------------------------------------------- contacts
    loaded = rn > 0.0
    dd = loaded & is_disk[cd] & is_disk[an]
    dw = loaded & ((is_disk[cd] & is_wall[an]) | (is_wall[cd] & is_disk[an]))
    tags["contacts_listed_final"] = int(nc)
    tags["contacts_loaded_final"] = int(np.count_nonzero(dd | dw))
    tags["contacts_disk_wall_final"] = int(np.count_nonzero(dw))
    tags["coordination_mean"] = 2.0 * np.count_nonzero(dd) / nd
    tags["coordination_with_walls"] = (2.0 * np.count_nonzero(dd) + np.count_nonzero(dw)) / nd
    per_body = np.bincount(cd[dd | dw], minlength=nb) + np.bincount(an[dd | dw], minlength=nb)
    tags["rattler_fraction"] = float(np.count_nonzero(per_body[is_disk] < 2)) / nd

    rl = rn[loaded]
    if rl.size:
        mean = float(rl.mean())
        tags["normal_force_mean"] = mean
        tags["normal_force_std"] = float(rl.std())
        tags["normal_force_over_mean_p90"] = float(np.percentile(rl / mean, 90.0))
        tags["normal_force_over_mean_p99"] = float(np.percentile(rl / mean, 99.0))
        mu = mu_of_law[law[loaded]]
        ratio = np.abs(rt[loaded]) / np.where(mu > 0, mu * rl, np.inf)
        tags["tangential_force_ratio_mean"] = float(ratio.mean())
        tags["sliding_fraction"] = float(np.count_nonzero(ratio >= 0.999)) / rl.size
    else:
        for k in ("normal_force_mean", "normal_force_std",
                  "normal_force_over_mean_p90", "normal_force_over_mean_p99", "tangential_force_ratio_mean", "sliding_fraction"):
            tags[k] = 0.0

    # wall reactions: the global reaction on the candidate is R = rt t + rn n with
    # t = (ny, -nx); the wall (antagonist) gets -R, a wall candidate +R.
    Ry = rt * (-nrm[:, 0]) + rn * nrm[:, 1] if nc else np.zeros(0)
    on_wall_y = np.where(is_wall[an], -Ry, 0.0) + np.where(is_wall[cd], Ry, 0.0)
    weight = float(np.sum(mass[is_disk]) * abs(g[1]))
    tags["weight_total"] = weight
    # the force a disk exerts on the wall points down (negative y) on the floor
    tags["wall_vertical_force_over_weight"] = float(-np.sum(on_wall_y)) / weight if weight else 0.0
    walls = np.flatnonzero(is_wall)
    floor = walls[np.argmin(ref[walls, 1] + x0[walls, 1])] if walls.size else -1
    fl = (an == floor) | (cd == floor)
    tags["floor_force_over_weight"] = float(-np.sum(on_wall_y[fl])) / weight if weight else 0.0

    # ---------------------------------------------------------------- geometry
    yd = pos[is_disk, 1]
    rd = radius[is_disk]
    md = mass[is_disk]
    tags["packing_height"] = float(np.percentile(yd + rd, 95.0))
    tags["com_height"] = float(np.sum(md * yd) / np.sum(md))
    tags["solid_fraction_core"] = solid_fraction_core(pos, radius, is_disk, is_wall, kinds, ref, x0)

    # ---------------------------------------------------------------- energies
    tags["kinetic_energy_final"] = float(ke[-1])
    ipk = int(np.argmax(ke))
    tags["kinetic_energy_peak"] = float(ke[ipk])
    tags["time_of_peak_kinetic_energy"] = float(t[ipk])
    tags["work_gravity_total"] = float(cols["work_gravity"][-1])
    tags["dissipated_total"] = float(cols["dissipated"][-1])
    berr = float(np.max(np.abs(cols["balance_error"])))
    tags["energy_balance_error_max"] = berr
    tags["energy_balance_error_rel"] = berr / abs(tags["work_gravity_total"]) \
        if tags["work_gravity_total"] else berr
    y_init = ref[:, 1] + x0[:, 1]
    tags["potential_energy_drop"] = float(np.sum(md * abs(g[1]) * (y_init[is_disk] - yd)))
    above = np.flatnonzero(ke > 1e-3 * ke[ipk])
    tags["settle_time"] = float(t[above[-1] + 1]) if above.size and above[-1] + 1 < n else float(t[-1])

    # ---------------------------------------------------------------- overlaps
    tags["max_overlap"] = float(np.max(cols["max_overlap"]))
    tags["max_overlap_final"] = float(cols["max_overlap"][-1])
    tags["max_overlap_over_rmin"] = tags["max_overlap"] / float(rd.min())
    tags["mean_overlap_final"] = float(cols["mean_overlap"][-1])

    # ---------------------------------------------------------------- solver
    tags["sweeps_total"] = int(sweeps.sum())
    tags["sweeps_mean_per_step"] = float(sweeps.mean())
    tags["sweeps_max_per_step"] = int(sweeps.max())
    tags["contact_sweeps_total"] = int(np.sum(ncont * sweeps))
    tags["nonconverged_steps"] = int(np.count_nonzero(cols["converged"] < 0.5))
    tags["residual_natural_map_max"] = float(np.max(cols["residual_natural_map"]))
    tags["residual_natural_map_final"] = float(cols["residual_natural_map"][-1])

    if with_hash:
        h = hashlib.sha256()
        for a in (X, V, rt, rn):
            h.update(np.ascontiguousarray(a, dtype="<f8").tobytes())
        tags["state_sha256"] = h.hexdigest()
    return tags


def solid_fraction_core(pos, radius, is_disk, is_wall, kinds, ref, x0):
    """Disk area fraction in a window inside the packing: x from the inner face
    of the left wall + 5 rmax to the right wall - 5 rmax, y from the floor + 5 rmax
    to the packing top - 5 rmax. The inner faces are taken from the disks' extent
    (min x - r, max x + r, min y - r), which at rest touch the walls."""
    xd, yd, rd = pos[is_disk, 0], pos[is_disk, 1], radius[is_disk]
    rmax = float(rd.max())
    xl, xr = float(np.min(xd - rd)), float(np.max(xd + rd))
    yb, yt = float(np.min(yd - rd)), float(np.max(yd + rd))
    x0w, x1w = xl + 5 * rmax, xr - 5 * rmax
    y0w, y1w = yb + 5 * rmax, yt - 5 * rmax
    if x1w <= x0w or y1w <= y0w:
        return 0.0
    a = _disk_rect_area(xd, yd, rd, x0w, x1w, y0w, y1w)
    return a / ((x1w - x0w) * (y1w - y0w))


def law_frictions(tact_behav, law_names):
    """Friction coefficient per law id (TACT_BEHAV.DAT order = /help/law): the law's
    'fric' (or dynamic 'dyfr') parameter; 0 if none (read by fracas_tools.datbox)."""
    laws, _ = datbox.read_tact_behav(tact_behav)
    fr = {}
    for law in laws.values():
        for key in ("fric", "dyfr"):
            if law.params.get(key) is not None:
                fr.setdefault(law.name, float(law.params[key]))
                break
    return np.array([fr.get(n, 0.0) for n in law_names])


def gravity(bulk_behav):
    """The $gravy vector of BULK_BEHAV.DAT (0 if absent), read by fracas_tools.datbox."""
    return np.asarray(datbox.read_bulk_behav(bulk_behav)[0], dtype=float)


def initial_displacements(dof_ini, nb):
    """(nb, 3) displacements X of the RBDY2 bodies in DOF.INI (0 for bodies not listed /
    no file), read by fracas_tools.datbox."""
    x = np.zeros((nb, 3))
    if not dof_ini.is_file():
        return x
    for key, state in datbox.read_dof(dof_ini)[2].items():
        if isinstance(key, int) and 1 <= key <= nb:
            x[key - 1] = state[0]
    return x


# ----------------------------------------------------------------------------
# tag files
# ----------------------------------------------------------------------------

def format_value(v):
    if isinstance(v, str):
        return v
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    return repr(float(v))          # shortest round-trip repr: exact


def write_tags(tags, path=None, header=None):
    lines = []
    if header:
        lines += [f"# {h}" for h in header]
    width = max(len(k) for k in tags)
    lines += [f"{k.ljust(width)} : {format_value(v)}" for k, v in tags.items()]
    text = "\n".join(lines) + "\n"
    if path in (None, "-"):
        sys.stdout.write(text)
    else:
        Path(path).write_text(text)
    return text


def parse_value(s):
    s = s.strip()
    if re.fullmatch(r"[+-]?\d+", s):
        return int(s)
    try:
        return float(s)
    except ValueError:
        return s


def read_tags(path):
    """A tag file (``name : value`` lines, '#' comments) -> dict. Reference files
    add ``: abs=A rel=R`` after the value; those go into a second dict."""
    tags, tols = {}, {}
    for ln, line in enumerate(Path(path).read_text().splitlines(), 1):
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        parts = [p.strip() for p in line.split(" : ")]
        if len(parts) < 2:
            raise SystemExit(f"{path}:{ln}: expected 'name : value', got {line!r}")
        tags[parts[0]] = parse_value(parts[1])
        if len(parts) >= 3:
            m = re.fullmatch(r"abs=(\S+)\s+rel=(\S+)", parts[2])
            if not m:
                raise SystemExit(f"{path}:{ln}: expected 'abs=A rel=R' after the value")
            tols[parts[0]] = (float(m.group(1)), float(m.group(2)))
    return tags, tols


def read_tolerances(path):
    """The hand-written tolerances: ``name  abs  rel  # why`` per line."""
    tols = {}
    for ln, line in enumerate(Path(path).read_text().splitlines(), 1):
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        w = line.split()
        if len(w) != 3:
            raise SystemExit(f"{path}:{ln}: expected 'name abs rel', got {line!r}")
        tols[w[0]] = (float(w[1]), float(w[2]))
    return tols


def make_reference(tags, tolerances, path, command):
    missing = [k for k in tags if k not in tolerances]
    extra = [k for k in tolerances if k not in tags]
    if missing or extra:
        raise SystemExit("tagged.py: tolerances and tags differ: "
                         + (f"no tolerance for {missing}; " if missing else "")
                         + (f"tolerance for unknown tags {extra}" if extra else ""))
    width = max(len(k) for k in tags)
    vw = max(len(format_value(v)) for v in tags.values())
    lines = [f"# Fracas regression reference, tagged.py format {FORMAT_VERSION}.",
             "# GENERATED: do not edit. Regenerate with",
             f"#   {command}",
             "# name : value : abs=A rel=R   (pass when |run - value| <= A + R*|value|)"]
    for k, v in tags.items():
        a, r = tolerances[k]
        lines.append(f"{k.ljust(width)} : {format_value(v).ljust(vw)} : abs={a:.3g} rel={r:.3g}")
    Path(path).write_text("\n".join(lines) + "\n")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("run_dir", help="directory holding OUTBOX/fracas.h5 (or the .h5 file)")
    p.add_argument("--case", help="case directory holding DATBOX/ (default: from fracas.h5)")
    p.add_argument("-o", "--output", default="-", help="tag file to write (default: stdout)")
    p.add_argument("--hash", action="store_true", help="add state_sha256 (determinism checks)")
    p.add_argument("--make-reference", metavar="REF",
                   help="write a reference file with the tolerances of --tolerances")
    p.add_argument("--tolerances", metavar="FILE", help="hand-written tolerances (name abs rel)")
    a = p.parse_args(argv)
    tags = compute_tags(a.run_dir, a.case, with_hash=a.hash and not a.make_reference)
    if a.make_reference:
        if not a.tolerances:
            p.error("--make-reference needs --tolerances")
        cmd = ("build/release/bin/fracas-python tools/regression/tagged.py RUN_DIR --case CASE_DIR "
               "--make-reference CASE_DIR/reference.tag --tolerances CASE_DIR/tolerances.txt")
        make_reference(tags, read_tolerances(a.tolerances), a.make_reference, cmd)
        print(f"tagged.py: wrote {a.make_reference} ({len(tags)} tags)")
    else:
        write_tags(tags, a.output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
