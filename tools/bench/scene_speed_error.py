#!/usr/bin/python3
"""Scene benchmark: speed against error of the NSCD solver on whole simulations.

For a granular deposit (the 1000 disks of test_cases/regression/deposit_1000, and a
generated deposit of random convex polygons), run the same physical time with
several NLGS tolerances (norms Quad and Maxm) and time steps, and measure, against a
tight reference run (smallest time step, tightest tolerance), errors that mean
something for a chaotic granular medium, versus the CPU time of the run:

  height      final packing height (max over grains of y + r; r the bounding radius)
  force       final mean normal force of the loaded contacts / mean grain weight
  dissipated  energy dissipated over the run
  positions   RMS distance between the grains' positions and the reference's at a
              short horizon (t_short, before the chaotic divergence), / mean radius;
              also against the dt = 1e-3, Quad 1e-5 run for the runs at dt = 1e-3
              (columns tpos*: the NLGS error alone, without the time-step error)
and, without a reference (accuracy of the run itself):
  statics     |sum of the vertical wall reactions / weight - 1| at the end (at rest)
  residual    mean over the steps of the natural-map residual ||F|| / ||q||

Per-grain quantities of a chaotic flow differ between any two equivalent runs: the
"chaos floor" of each error is measured as the largest difference between runs that
differ only in the contact order (stored, reversed, colored, shuffled) at dt = 1e-3
and Quad 1e-5; an error below the floor says nothing.

    build/release/bin/fracas-python tools/bench/scene_speed_error.py                  # runs (cached) + table
    build/release/bin/fracas-python tools/bench/scene_speed_error.py --plots --csv bench/results/scene_speed_error.csv
    options: --fracas BIN (default build/release/bin/fracas), --work DIR (default
    /tmp/fracas_scene_bench; finished runs are reused), --jobs N (parallel runs,
    default 2), --scenes disks,polygons, --rerun (ignore cached runs)

About 7 minutes on 2 shared cores with --jobs 2 (760 s of CPU in total, the disk
reference run alone 285 s). Results and their reading: doc/benchmarks.md section 3. Times are CPU time (user + system) of the whole fracas run,
from the child's rusage, so other jobs on a shared machine inflate them little.
"""

import argparse
import csv
import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]

SNAP_EVERY_T = 0.02          # snapshot period (s): same physical times for every dt
T_SHORT = (0.06, 0.10)       # short horizons for the positions (s)


# ----------------------------------------------------------------------------- scenes

def polygon_deposit(case_dir, n=300, seed=1):
    """n random convex polygons (4-7 vertices, circumradius 6-9 mm) dropped from a
    jittered lattice into a 0.2 m wide box of fixed JONCx walls; IQS_CLB mu 0.3 / 0.5,
    alert 3 mm."""
    from fracas_tools import Case, generators as gen
    rmin, rmax, width = 0.006, 0.009, 0.2
    case = Case(gravity=(0.0, -9.81, 0.0))
    case.add_material("STONE", density=2600.0)
    case.add_material("TDURx", density=1000.0)
    polys = gen.deposit_polygons(case, n, rmin, rmax, width, "STONE", "BLEUx", seed=seed)
    top = gen.top_of(case, polys)
    gen.box_walls(case, 0.0, width, 0.0, top + 4.0 * rmax, 0.01, "TDURx", "WALLx", top=True)
    gen.add_granular_laws(case, 0.3, 0.5, 0.003, grain_type="POLYG")
    case.run.set(time_step=1e-3, number_of_steps=100, theta=0.5, nlgs_check="Quad", nlgs_tolerance=1e-4,
                 nlgs_relaxation=1.0, nlgs_sweeps_per_check=50, nlgs_max_checks=400, nlgs_order="stored",
                 output_dof_every=0, output_vtk_every=0, output_hdf5_every=20, progress_every=0)
    case.write(case_dir)
    return case_dir


def runs_for(scene):
    """(label, settings) of a scene: tolerance sweeps at dt = 1e-3, time-step sweep at
    Quad 1e-4, the order variants that give the chaos floor, and the reference."""
    r = []

    def add(dt, check, tol, order="stored", role="sweep"):
        label = f"dt{dt:g}_{check}{tol:g}_{order}"
        r.append((label, dict(dt=dt, check=check, tol=tol, order=order, role=role)))

    if scene == "disks":
        for tol in (1e-2, 1e-3, 1e-4, 1e-5):
            add(1e-3, "Quad", tol)
        for tol in (1e-2, 1e-3, 1e-4):
            add(1e-3, "Maxm", tol)
        for tol in (1e-3, 1e-4):
            add(1e-3, "Quad", tol, "colored")
        for dt in (2e-3, 5e-4, 2.5e-4):
            add(dt, "Quad", 1e-4)
        add(1e-3, "Quad", 1e-5, "reversed", "floor")
        add(1e-3, "Quad", 1e-5, "colored", "floor")
        add(1e-3, "Quad", 1e-5, "shuffled", "floor")
        add(2.5e-4, "Quad", 1e-6, "stored", "reference")
    else:
        for tol in (1e-2, 1e-3, 1e-4, 1e-5):
            add(1e-3, "Quad", tol)
        for tol in (1e-2, 1e-3, 1e-4):
            add(1e-3, "Maxm", tol)
        add(1e-3, "Quad", 1e-4, "colored")
        for dt in (2e-3, 5e-4, 2.5e-4):
            add(dt, "Quad", 1e-4)
        add(1e-3, "Quad", 1e-5, "reversed", "floor")
        add(1e-3, "Quad", 1e-5, "colored", "floor")
        add(1e-3, "Quad", 1e-5, "shuffled", "floor")
        add(2.5e-4, "Quad", 1e-6, "stored", "reference")
    return r


SCENES = {
    # name: (case dir or generator, physical duration)
    "disks": (REPO / "test_cases" / "regression" / "deposit_1000", 1.0),
    "polygons": (polygon_deposit, 0.8),
}


# ----------------------------------------------------------------------------- running

def command(fracas, case_dir, out, s, duration):
    nsteps = int(round(duration / s["dt"]))
    every = int(round(SNAP_EVERY_T / s["dt"]))
    sets = dict(time_step=repr(s["dt"]), number_of_steps=nsteps, nlgs_check=s["check"],
                nlgs_tolerance=repr(s["tol"]), nlgs_order=s["order"], output_hdf5_every=every,
                output_dof_every=0, output_vtk_every=0, progress_every=0)
    cmd = [str(fracas), "-q", "--overwrite", "--output", str(out)]
    for k, v in sets.items():
        cmd += ["--set", f"{k}={v}"]
    return cmd + [str(case_dir)]


def run_all(fracas, work, scenes, jobs, rerun):
    """Run what is not cached, `jobs` at a time; CPU time from each child's rusage."""
    todo, info = [], {}
    for scene in scenes:
        case, duration = SCENES[scene]
        if callable(case):
            case_dir = work / scene / "case"
            if not (case_dir / "DATBOX" / "BODIES.DAT").is_file():
                case(case_dir)
        else:
            case_dir = case
        for label, s in runs_for(scene):
            out = work / scene / label
            meta = out / "run.json"
            cmd = command(fracas, case_dir, out, s, duration)
            info[(scene, label)] = dict(s, out=str(out), case=str(case_dir))
            if meta.is_file() and not rerun:
                m = json.loads(meta.read_text())
                if m.get("cmd") == cmd:
                    info[(scene, label)]["cpu"] = m["cpu"]
                    continue
            todo.append((scene, label, cmd, out))
    # the long runs first
    todo.sort(key=lambda t: -cost_guess(info[(t[0], t[1])]))
    running = {}
    t0 = time.time()
    while todo or running:
        while todo and len(running) < jobs:
            scene, label, cmd, out = todo.pop(0)
            out.mkdir(parents=True, exist_ok=True)
            log = open(out / "run.log", "w")
            p = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT)
            running[p.pid] = (scene, label, cmd, out, log)
        pid, status, ru = os.wait4(-1, 0)
        if pid not in running:
            continue
        scene, label, cmd, out, log = running.pop(pid)
        log.close()
        if status != 0:
            raise SystemExit(f"scene_speed_error.py: run {scene}/{label} failed, see {out}/run.log")
        cpu = ru.ru_utime + ru.ru_stime
        (out / "run.json").write_text(json.dumps(dict(cmd=cmd, cpu=cpu)))
        info[(scene, label)]["cpu"] = cpu
        print(f"  [{time.time() - t0:6.0f} s] {scene}/{label}: {cpu:.1f} s CPU", flush=True)
    return info


def cost_guess(s):
    return (1e-3 / s["dt"]) * (1e-4 / s["tol"]) ** 0.6 * (3 if s["check"] == "Maxm" else 1)


# ----------------------------------------------------------------------------- metrics

def load(out, case_dir):
    """What the error measures need from a run (fracas.h5 + BODIES.DAT)."""
    from fracas_tools.scripts import load as load_script
    tagged = load_script(REPO / "tools" / "regression" / "tagged.py")
    Run, body_contactor_kinds, gravity = tagged.Run, tagged.body_contactor_kinds, tagged.gravity
    kinds = body_contactor_kinds(Path(case_dir) / "DATBOX" / "BODIES.DAT")
    g = gravity(Path(case_dir) / "DATBOX" / "BULK_BEHAV.DAT")
    with Run(Path(out) / "OUTBOX" / "fracas.h5") as f:
        grain = np.array([("JONCx" not in k) for k in kinds])
        wall = ~grain
        mass = np.asarray(f.bodies["mass"], dtype=float)
        radius = np.asarray(f.bodies["radius"], dtype=float)
        ref = f.bodies["reference"]
        s = f.series
        snaps = {}
        for name in f.snapshot_names:
            sn = f.snapshot(name)
            t = round(sn.time / SNAP_EVERY_T) * SNAP_EVERY_T
            snaps[round(t, 6)] = (ref + sn.X)[:, :2]
        c = f.snapshot(-1).contacts
        cd, an = c["cd_body"] - 1, c["an_body"] - 1
        rt, rn = c["reaction"][:, 0], c["reaction"][:, 1]
        nrm = c["normal"]
    weight = float(np.sum(mass[grain]) * abs(g[1]))
    pos = snaps[max(snaps)]
    Ry = rt * (-nrm[:, 0]) + rn * nrm[:, 1]
    on_wall_y = np.where(wall[an], -Ry, 0.0) + np.where(wall[cd], Ry, 0.0)
    loaded = (rn > 0.0) & grain[cd] & (grain[an] | wall[an])
    return dict(
        height=float(np.max(pos[grain, 1] + radius[grain])),
        force=float(np.mean(rn[loaded])) / (weight / np.count_nonzero(grain)) if loaded.any() else 0.0,
        dissipated=float(s["dissipated"][-1]),
        statics=abs(float(-np.sum(on_wall_y)) / weight - 1.0),
        residual=float(np.mean(s["residual_natural_map"])),
        nonconv=int(np.count_nonzero(s["converged"] < 0.5)),
        sweeps=float(np.mean(s["sweeps"])),
        max_overlap=float(np.max(s["max_overlap"])),
        ke_final=float(s["kinetic_energy"][-1]),
        rmin=float(np.min(radius[grain])),
        snaps=snaps, grain=grain, rmean=float(np.mean(radius[grain])))


def errors(m, r):
    """Errors of run m against reference r (relative for the scalars)."""
    e = dict(height=abs(m["height"] - r["height"]) / r["height"],
             force=abs(m["force"] - r["force"]) / r["force"],
             dissipated=abs(m["dissipated"] - r["dissipated"]) / abs(r["dissipated"]),
             statics=m["statics"], residual=m["residual"], overlap=m["max_overlap"] / m["rmin"])
    for t in T_SHORT:
        a, b = m["snaps"].get(round(t, 6)), r["snaps"].get(round(t, 6))
        g = m["grain"]
        e[f"pos{t:g}"] = (float(np.sqrt(np.mean(np.sum((a[g] - b[g]) ** 2, axis=1)))) / m["rmean"]
                          if a is not None and b is not None else float("nan"))
    return e


METRICS = [("height", "packing height (rel.)"), ("force", "mean normal force / weight (rel.)"),
           ("dissipated", "energy dissipated (rel.)"), (f"pos{T_SHORT[0]:g}", f"positions at t = {T_SHORT[0]:g} s (/ r)"),
           (f"pos{T_SHORT[1]:g}", f"positions at t = {T_SHORT[1]:g} s (/ r)"),
           ("statics", "|wall reactions / weight - 1| at the end"), ("residual", "mean natural-map residual"),
           ("overlap", "largest overlap / smallest radius")]


ABSOLUTE = ("statics", "residual", "overlap")   # measured on the run itself, no reference


def analyse(info, scenes):
    rows = []
    for scene in scenes:
        runs = runs_for(scene)
        data = {lab: load(info[(scene, lab)]["out"], info[(scene, lab)]["case"]) for lab, _ in runs}
        ref_label = next(lab for lab, s in runs if s["role"] == "reference")
        ref = data[ref_label]
        # chaos floor: largest spread among the order variants at dt 1e-3, Quad 1e-5
        flo = [lab for lab, s in runs if s["role"] == "floor" or
               (s["dt"] == 1e-3 and s["tol"] == 1e-5 and s["check"] == "Quad" and s["order"] == "stored")]
        floor = {}
        for k in [m for m, _ in METRICS if m not in ABSOLUTE]:
            vals = [errors(data[a], data[b])[k] for i, a in enumerate(flo) for b in flo[i + 1:]]
            floor[k] = max(vals) if vals else float("nan")
        tight = data[next(lab for lab, s in runs if s["dt"] == 1e-3 and s["check"] == "Quad" and
                          s["tol"] == 1e-5 and s["order"] == "stored")]
        for lab, s in runs:
            e = errors(data[lab], ref)
            et = errors(data[lab], tight) if s["dt"] == 1e-3 else {}
            for t in T_SHORT:
                e[f"tpos{t:g}"] = et.get(f"pos{t:g}", float("nan"))
            rows.append(dict(scene=scene, label=lab, role=s["role"], dt=s["dt"], check=s["check"], tol=s["tol"],
                             order=s["order"], cpu=info[(scene, lab)]["cpu"], sweeps=data[lab]["sweeps"],
                             nonconv=data[lab]["nonconv"], max_overlap=data[lab]["max_overlap"],
                             ke_final=data[lab]["ke_final"],
                             height=data[lab]["height"], force=data[lab]["force"],
                             dissipated=data[lab]["dissipated"],
                             **{f"err_{k}": v for k, v in e.items()}))
        rows.append(dict(scene=scene, label="chaos_floor", role="floor_spread",
                         **{f"err_{k}": floor.get(k, float("nan")) for k, _ in METRICS}))
    return rows


# ----------------------------------------------------------------------------- output

def table(rows):
    keys = [m for m, _ in METRICS] + [f"tpos{t:g}" for t in T_SHORT]
    print("| scene | run | CPU (s) | sweeps/step | non-conv. | KE end (J) | " + " | ".join(keys) + " |")
    print("|---|---|---|---|---|---|" + "---|" * len(keys))
    for r in rows:
        if r["role"] == "floor_spread":
            print(f"| {r['scene']} | chaos floor (order spread) | | | | | " +
                  " | ".join("" if k in ABSOLUTE or k.startswith("t") else f"{r['err_' + k]:.1e}" for k in keys) + " |")
            continue
        lab = f"dt {r['dt']:g}, {r['check']} {r['tol']:g}" + ("" if r["order"] == "stored" else f", {r['order']}")
        if r["role"] == "reference":
            lab = "**reference** " + lab
        cells = []
        for k in keys:
            v = r["err_" + k]
            if r["role"] == "reference" and k not in ABSOLUTE and not k.startswith("t"):
                cells.append("0")
            else:
                cells.append("" if math.isnan(v) else f"{v:.1e}")
        print(f"| {r['scene']} | {lab} | {r['cpu']:.1f} | {r['sweeps']:.0f} | {r['nonconv']} | {r['ke_final']:.0e} | " +
              " | ".join(cells) + " |")


def plots(rows, scenes, img_dir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    for scene in scenes:
        rs = [r for r in rows if r["scene"] == scene and r["role"] != "floor_spread"]
        floor = next(r for r in rows if r["scene"] == scene and r["role"] == "floor_spread")
        fig, axes = plt.subplots(3, 3, figsize=(13, 11))
        axes = axes.ravel()
        series = [("Quad, dt 1e-3", lambda r: r["check"] == "Quad" and r["dt"] == 1e-3 and r["order"] == "stored"
                   and r["role"] == "sweep", "C0", "-o", "tol"),
                  ("Maxm, dt 1e-3", lambda r: r["check"] == "Maxm", "C1", "-s", "tol"),
                  ("Quad, dt 1e-3, colored", lambda r: r["order"] == "colored" and r["role"] == "sweep", "C2", "-^",
                   "tol"),
                  ("Quad 1e-4, dt sweep", lambda r: r["check"] == "Quad" and r["tol"] == 1e-4 and
                   r["order"] == "stored", "C3", "--D", "dt"),
                  ("order variants (dt 1e-3, Quad 1e-5)", lambda r: r["role"] == "floor", "C7", "x", "order")]
        for ax, (key, title) in zip(axes, METRICS):
            for name, sel, col, sty, ann in series:
                pts = sorted([r for r in rs if sel(r) and r["role"] != "reference"], key=lambda r: r["cpu"])
                if not pts:
                    continue
                x = [r["cpu"] for r in pts]
                y = [max(r["err_" + key], 1e-16) for r in pts]
                ax.loglog(x, y, sty, color=col, label=name, ms=5)
                for r, xx, yy in zip(pts, x, y):
                    txt = f"{r['tol']:g}" if ann == "tol" else (f"{r['dt']:g}" if ann == "dt" else r["order"][:3])
                    ax.annotate(txt, (xx, yy), fontsize=6, xytext=(3, 3), textcoords="offset points")
            if key.startswith("pos"):
                pts = sorted([r for r in rs if r["dt"] == 1e-3 and r["check"] == "Quad" and r["order"] == "stored"
                              and r["role"] == "sweep" and r["tol"] > 1e-5], key=lambda r: r["cpu"])
                ax.loglog([r["cpu"] for r in pts], [max(r["err_t" + key], 1e-16) for r in pts], ":o", color="C0",
                          mfc="none", ms=5, label="Quad, dt 1e-3, against Quad 1e-5 at dt 1e-3 (NLGS error alone)")
                for r in pts:
                    ax.annotate(f"{r['tol']:g}", (r["cpu"], max(r["err_t" + key], 1e-16)), fontsize=6,
                                xytext=(3, -8), textcoords="offset points")
                if key == f"pos{T_SHORT[0]:g}":
                    ax.legend(fontsize=6, loc="lower left")
            if key in ABSOLUTE:
                ref = next(r for r in rs if r["role"] == "reference")
                ax.loglog([ref["cpu"]], [max(ref["err_" + key], 1e-16)], "k*", ms=9, label="reference")
            elif np.isfinite(floor["err_" + key]):
                ax.axhline(max(floor["err_" + key], 1e-16), color="grey", ls=":", label="chaos floor")
            ax.set_title(title, fontsize=9)
            ax.grid(True, which="both", alpha=0.3)
            ax.set_xlabel("CPU time of the run (s)", fontsize=8)
            ax.tick_params(labelsize=7)
        axes[0].legend(fontsize=6)
        # last panel: sweeps per step against tolerance
        ax = axes[-1]
        for name, sel, col, sty, ann in series[:3]:
            pts = sorted([r for r in rs if sel(r)], key=lambda r: r["tol"])
            if pts:
                ax.loglog([r["tol"] for r in pts], [r["sweeps"] for r in pts], sty, color=col, label=name, ms=5)
        ax.set_xlabel("NLGS tolerance", fontsize=8)
        ax.set_title("mean sweeps per step (dt 1e-3)", fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        ax.tick_params(labelsize=7)
        ax.legend(fontsize=6)
        ref = next(r for r in rs if r["role"] == "reference")
        fig.suptitle(f"{scene}: error against CPU time (reference: dt {ref['dt']:g}, {ref['check']} "
                     f"{ref['tol']:g}, {ref['cpu']:.0f} s)", fontsize=11)
        fig.tight_layout()
        png = Path(img_dir) / f"bench_scene_{scene}.png"
        fig.savefig(png, dpi=90)
        print(f"wrote {png}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--fracas", default=str(REPO / "build" / "release" / "bin" / "fracas"))
    ap.add_argument("--work", default="/tmp/fracas_scene_bench")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--scenes", default="disks,polygons")
    ap.add_argument("--rerun", action="store_true")
    ap.add_argument("--plots", action="store_true", help="write doc/img/bench_scene_<scene>.png")
    ap.add_argument("--img-dir", default=str(REPO / "doc" / "img"))
    ap.add_argument("--csv", help="write all rows to this CSV")
    a = ap.parse_args()
    scenes = [s for s in a.scenes.split(",") if s]
    work = Path(a.work)
    info = run_all(Path(a.fracas).resolve(), work, scenes, a.jobs, a.rerun)
    rows = analyse(info, scenes)
    table(rows)
    if a.csv:
        keys = sorted({k for r in rows for k in r}, key=lambda k: (k.startswith("err_"), k))
        with open(a.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=keys)
            w.writeheader()
            for r in rows:
                w.writerow(r)
        print(f"wrote {a.csv}")
    if a.plots:
        plots(rows, scenes, a.img_dir)


if __name__ == "__main__":
    main()
