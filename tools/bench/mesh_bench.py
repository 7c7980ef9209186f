#!/usr/bin/python3
"""Benchmark of meshed bodies: time per step and its split against the problem size.

Three studies (doc/benchmarks.md section 6):

  big       one large elastic body (Q4 block, 2:1, 1e3 to 1e5 nodes) resting on a rigid
            JONCx ground with one CLxxx candidate per bottom node (CLJCx, GAP_SGR_CLB
            mu 0.3) and sliding on it under gravity: the iteration matrix is assembled
            and factorized once (setup, CHOLMOD), each step costs a residual and two
            solves; the contact compliance of the bottom nodes is computed once (first
            step) by solves with the factorization.
  exploded  many small bodies: an exploded T3 plate (one MAILx body per element, 1e3 to
            1e5 elements, element size 1 mm) glued by MAC_CZM on every shared edge, in
            free vibration from a uniform stretching velocity v_y = rate * y (every
            contact loaded from the first step).
  lmgc90    the LMGC90 deck ../shared/lmgc90_decks/mesh_exploded_beam with LMGC90's own
            NLGS settings (test_cases/compat/mesh_exploded_beam/run.dat), against
            LMGC90's timing and sweep counts (case.md, POSTPRO/SOLVER_INFORMATIONS.DAT).

Each run's CPU time (user + system) comes from the child's rusage; the split of the
loop between the parts of a step comes from the wall-clock series of fracas.h5
(bodies_time, detect_time, prepare_time, solve_time, step_time), converted to CPU time
by the ratio loop_cpu_seconds / loop_seconds of the run (root attributes written by the
driver); setup and deck reading from setup_cpu_seconds and read_cpu_seconds. The load
average is recorded before and after every run.

    build/release/bin/fracas-python tools/bench/mesh_bench.py big            # runs + bench/results/mesh_big.json
    build/release/bin/fracas-python tools/bench/mesh_bench.py exploded       # bench/results/mesh_exploded.json
    build/release/bin/fracas-python tools/bench/mesh_bench.py lmgc90 --repeat 3
    build/release/bin/fracas-python tools/bench/mesh_bench.py plot           # doc/img/bench_mesh_*.png, tables
    options: --fracas BIN (default build/release/bin/fracas), --work DIR (default
    /tmp/fracas_mesh_bench), --sizes a,b,c (ny of the block, nx = ny of the plate),
    --steps N, --callgrind MAX_SIZE (also count instructions per steady step of each
    part with valgrind --tool=callgrind for the sizes up to MAX_SIZE: two short runs,
    --callgrind-steps A,B, and their difference; exact and load-independent)
"""

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
RESULTS = REPO / "bench" / "results"
IMG = REPO / "doc" / "img"
DECKS = REPO.parent / "shared" / "lmgc90_decks"

# Single-threaded linear algebra: CPU time then measures the work, not the threads.
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

PARTS = ("bodies", "detect", "prepare", "solve")
# The split reported: solve_time without velocity_time is the NLGS proper.
SPLIT = ("bodies", "detect", "prepare", "sweeps", "velocity", "end", "step")

# LMGC90 on mesh_exploded_beam (shared/lmgc90_decks/mesh_exploded_beam/case.md and
# POSTPRO/SOLVER_INFORMATIONS.DAT): loop and process times, sweeps over the 800 steps.
LMGC90_BEAM = {"loop_s": 9.2, "process_cpu_s": 10.6, "steps": 800, "contacts": 116}


# ----------------------------------------------------------------------------- decks

def big_body_case(ny, steps, dt=1.0e-4):
    """A Q4 block 0.2 m x 0.1 m, 2 ny x ny elements ((2 ny + 1)(ny + 1) nodes), E 1e9,
    nu 0.3, rho 2000 (mesh_block_drop's block, refined), its bottom on a fixed JONCx
    ground (y = 0), one CLxxx per bottom node (GAP_SGR_CLB, mu 0.3), gravity, initial
    velocity (0.05, 0): it slides and slows down by friction, every bottom node in
    contact at every step."""
    from fracas_tools import Case
    from fracas_tools.mesh import mesh_from_arrays
    nx = 2 * ny
    xs = np.linspace(0.0, 0.2, nx + 1)
    ys = np.linspace(0.0, 0.1, ny + 1)
    nodes = np.array([[x, y] for y in ys for x in xs])

    def nid(i, j):
        return j * (nx + 1) + i
    els = [(nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1)) for j in range(ny) for i in range(nx)]
    bottom = [(nid(i + 1, 0), nid(i, 0)) for i in range(nx)]
    mesh = mesh_from_arrays(nodes, els, ["block"] * len(els),
                            node_groups={"bottom": [nid(i, 0) for i in range(nx + 1)]},
                            edge_groups={"bottom": bottom})
    case = Case(gravity=(0.0, -9.81))
    case.add_material("TDURx", 1000.0, "RIGID")
    case.add_material("BLOCK", 2000.0, "ELAS", young=1e9, poisson=0.3)
    case.add_jonc((0.1, -0.01), 0.2, 0.01, "TDURx").fix()
    (body,) = case.add_mesh(mesh, "BLOCK")
    body.add_candidates_on("bottom", "BLEUx", apab="nodes")
    body.v0[:, 0] = 0.05
    case.add_law("gapc3", "GAP_SGR_CLB", fric=0.3)
    case.add_see("CLxxx", "BLEUx", "JONCx", "WALLx", "gapc3", 5e-3)
    case.run.set(time_step=dt, number_of_steps=steps, theta=0.5, plane="strain",
                 nlgs_check="Quad", nlgs_tolerance=1e-4, nlgs_sweeps_per_check=50, nlgs_max_checks=400,
                 output_vtk_every=10, output_hdf5_every=10, output_dof_every=0)
    return case, {"nodes": len(nodes), "elements": len(els), "dofs": 2 * len(nodes), "contactors": nx + 1}


def exploded_case(n, steps, dt=2.0e-6, rate=10.0):
    """An n x n square plate of 1 mm squares cut in two T3 (2 n^2 elements), exploded
    (one MAILx body per element), MAC_CZM on every shared edge (cn = ct = 1e14 Pa/m,
    cn h / E = 10, w 10 J/m2, mu 0.3), E 1e10, nu 0.2, rho 2500 (mesh_exploded_beam's
    material), no gravity, no support, initial velocity v_y = rate * (y - H/2):
    free vibration from a uniform stretching rate, every contact loaded. dt = 2e-6:
    c dt / h = 4 (c = sqrt(E / rho)), as in LMGC90's mesh_exploded_beam."""
    from fracas_tools import Case
    from fracas_tools.mesh import mesh_from_arrays
    h = 1.0e-3
    xs = np.arange(n + 1) * h
    nodes = np.array([[x, y] for y in xs for x in xs])

    def nid(i, j):
        return j * (n + 1) + i
    els = []
    for j in range(n):
        for i in range(n):
            a, b, c, d = nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1)
            els += [(a, b, c), (a, c, d)]
    mesh = mesh_from_arrays(nodes, els, ["plate"] * len(els))
    case = Case(gravity=(0.0, 0.0))
    case.add_material("PLATE", 2500.0, "ELAS", young=1e10, poisson=0.2)
    parts = case.add_exploded_mesh(mesh, "PLATE", color="BLEUx")
    half = 0.5 * n * h
    for b in parts.bodies:
        b.v0[:, 1] = rate * (b.nodes[:, 1] - half)
    case.add_law("macz_", "MAC_CZM", dyfr=0.3, stfr=0.3, cn=1e14, ct=1e14, b=0.0, w=10.0)
    parts.add_see(case, "macz_", alert=1e-4)
    case.run.set(time_step=dt, number_of_steps=steps, theta=0.5, plane="strain",
                 nlgs_check="Quad", nlgs_tolerance=1e-4, nlgs_sweeps_per_check=50, nlgs_max_checks=400,
                 output_vtk_every=10, output_hdf5_every=10, output_dof_every=0)
    return case, {"elements": len(els), "nodes": 3 * len(els), "dofs": 6 * len(els),
                  "cohesive_points": parts.points}


# ----------------------------------------------------------------------------- runs

def loadavg():
    return round(os.getloadavg()[0], 2)


def run_fracas(fracas, args, out_dir):
    """Run fracas, return its CPU (user + system) and wall seconds and the load."""
    if out_dir.exists():
        shutil.rmtree(out_dir)
    load0 = loadavg()
    t0 = time.perf_counter()
    proc = subprocess.Popen([str(fracas), "-q", "--overwrite", *args, "--output", str(out_dir)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    _, status, ru = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t0
    err = proc.stderr.read()
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        raise RuntimeError(f"fracas {' '.join(args)} failed ({proc.returncode}):\n{err}")
    return {"process_cpu_s": ru.ru_utime + ru.ru_stime, "process_wall_s": wall, "max_rss_mb": ru.ru_maxrss / 1024,
            "load_before": load0, "load_after": loadavg()}


def read_h5(out_dir):
    """Totals and per-step figures of a run's fracas.h5: CPU seconds of each part
    (the wall-clock series times loop_cpu / loop wall), setup and reading."""
    from fracas_tools.results import Run         # the one reader of fracas.h5
    with Run(out_dir) as run:
        a = {k: float(v) for k, v in run.attrs.items() if k.endswith("seconds")}
        sweeps_per_check = int(run.file["run"].attrs["nlgs_sweeps_per_check"])
        s = {k: np.asarray(run.series[k], dtype=float) for k in ("contacts", "active_contacts", "sweeps",
             "contact_updates", "step_time", "velocity_time", *(p + "_time" for p in PARTS))}
    s["sweeps_time"] = s["solve_time"] - s["velocity_time"]
    scale = a["loop_cpu_seconds"] / a["loop_seconds"]
    nsteps = len(s["step_time"])
    r = {"steps": nsteps, "cpu_per_wall": scale, **a,
         "contacts_mean": float(s["contacts"].mean()), "active_mean": float(s["active_contacts"].mean()),
         "sweeps_total": int(s["sweeps"].sum()), "sweeps_per_step": float(s["sweeps"].mean()),
         "checks_total": int(np.ceil(s["sweeps"] / sweeps_per_check).sum()),
         "updates_total": float(s["contact_updates"].sum())}   # exact: every sweep and check pass
    # CPU seconds of each part, first step and the others (steady steps)
    for p in (*PARTS, "sweeps", "velocity", "step"):
        col = s[p + "_time"] * scale
        r[p + "_first_cpu_s"] = float(col[0])
        r[p + "_cpu_s"] = float(col[1:].sum()) if nsteps > 1 else float(col[0])
    rest = s["step_time"] - sum(s[p + "_time"] for p in PARTS)
    r["end_first_cpu_s"] = float(rest[0] * scale)
    r["end_cpu_s"] = float(rest[1:].sum() * scale) if nsteps > 1 else r["end_first_cpu_s"]
    r["output_cpu_s"] = (a["loop_seconds"] - float(s["step_time"].sum())) * scale
    steady = max(nsteps - 1, 1)
    r["per_step_ms"] = {p: 1e3 * r[p + "_cpu_s"] / steady for p in SPLIT}
    r["per_step_ms"]["output"] = 1e3 * r["output_cpu_s"] / nsteps
    r["first_step_ms"] = {p: 1e3 * r[p + "_first_cpu_s"] for p in SPLIT}
    upd = float(s["contact_updates"][1:].sum()) if nsteps > 1 else r["updates_total"]
    r["updates_per_step"] = upd / steady
    r["ns_per_update"] = 1e9 * r["sweeps_cpu_s"] / upd if upd > 0 else None
    r["ns_per_update_loop"] = 1e9 * a["loop_cpu_seconds"] / r["updates_total"] if r["updates_total"] > 0 else None
    return r


CG_FUNCTIONS = {
    "read": "__fracas_read_deck_MOD_read_deck", "setup": "__fracas_scene_MOD_scene_build",
    "step": "__fracas_scene_MOD_scene_step", "free_velocity": "__fracas_mailx_MOD_mailx_begin_step",
    "detect_rough": "__fracas_detection_MOD_detect_rough", "detect_fine": "__fracas_detection_MOD_detect_fine",
    "prepare": "__fracas_nlgs_MOD_nlgs_prepare", "solve": "__fracas_nlgs_MOD_nlgs_solve",
    "sweep_mesh": "__fracas_local_solver_MOD_gs_sweep_mesh",
    "mesh_velocities": "__fracas_mailx_MOD_mailx_velocity_from_impulses",
    "end_step": "__fracas_mailx_MOD_mailx_end_step", "history": "__fracas_contacts_MOD_history_from_contacts",
    "cracks": "__fracas_cracks_MOD_cracks_update", "output_series": "__fracas_output_MOD_output_series",
    "output_vtk": "__fracas_output_MOD_output_vtk", "output_snapshot": "__fracas_output_MOD_output_snapshot",
    "output_outbox": "__fracas_output_MOD_output_outbox", "total": "main"}


def callgrind_inclusive(fracas, args, work, tag):
    """Inclusive instruction counts (Ir) of the functions of CG_FUNCTIONS in one run
    under valgrind --tool=callgrind (exact and load-independent)."""
    out = work / f"cg_{tag}"
    cg = work / f"callgrind_{tag}.out"
    subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={cg}", str(fracas), "-q",
                    "--overwrite", *args, "--output", str(out)], check=True, capture_output=True)
    ann = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", str(cg)],
                         check=True, capture_output=True, text=True).stdout
    inc = {}
    for line in ann.splitlines():
        m = re.match(r"\s*([\d,]+) \([^)]*\)\s+(\S+) \[", line)
        if m:
            name = m.group(2).rsplit(":", 1)[-1]
            inc[name] = max(inc.get(name, 0), int(m.group(1).replace(",", "")))
    res = {k: inc.get(v, 0) for k, v in CG_FUNCTIONS.items()}
    series = read_h5(out)
    res["sweeps_total"] = series["sweeps_total"]
    res["updates_total"] = series["updates_total"]
    shutil.rmtree(out, ignore_errors=True)
    cg.unlink()
    return res


def callgrind_steps(fracas, args, work, steps):
    """Instructions per steady step (steps[0] + 1 .. steps[1]) of each part, from two
    callgrind runs of steps[0] and steps[1] steps; setup and reading from the first."""
    a = callgrind_inclusive(fracas, ["--set", f"number_of_steps={steps[0]}", *args], work, "a")
    b = callgrind_inclusive(fracas, ["--set", f"number_of_steps={steps[1]}", *args], work, "b")
    n = steps[1] - steps[0]
    per_step = {k: (b[k] - a[k]) / n for k in CG_FUNCTIONS if k not in ("read", "setup")}
    upd = b["updates_total"] - a["updates_total"]
    return {"steps": list(steps), "read": a["read"], "setup": a["setup"], "per_step": per_step,
            "sweep_mesh_per_update": (b["sweep_mesh"] - a["sweep_mesh"]) / upd if upd else None}


# ----------------------------------------------------------------------------- studies

def median_record(reps):
    """Field by field median of the records of repeated runs (nested dicts too);
    counts (sweeps, updates) are identical between repeats of a deterministic run."""
    out = {}
    for k, v in reps[0].items():
        if isinstance(v, dict):
            out[k] = median_record([r[k] for r in reps])
        elif isinstance(v, (int, float)) and not isinstance(v, bool) and all(r.get(k) is not None for r in reps):
            out[k] = float(np.median([r[k] for r in reps]))
        else:
            out[k] = v
    return out


def study(kind, sizes, steps, fracas, work, callgrind_max, cg_steps, repeat, save=None):
    results = []
    for n in sizes:
        if kind == "big":
            case, info = big_body_case(n, steps)
        else:
            case, info = exploded_case(n, steps[n] if isinstance(steps, dict) else steps)
        d = work / f"{kind}_{n}"
        t0 = time.perf_counter()
        if d.exists():
            shutil.rmtree(d)
        case.write(d)
        info["deck_write_s"] = time.perf_counter() - t0
        reps = []
        for _ in range(repeat):
            one = run_fracas(fracas, [str(d)], d / "run")
            one.update(read_h5(d / "run"))
            reps.append(one)
        rec = {"size": n, **info, **median_record(reps), "repeats": len(reps),
               "process_cpu_all_s": [r["process_cpu_s"] for r in reps],
               "load_before": min(r["load_before"] for r in reps), "load_after": max(r["load_after"] for r in reps)}
        if n <= callgrind_max:
            rec["callgrind"] = callgrind_steps(fracas, [str(d)], d, cg_steps)
        shutil.rmtree(d / "run", ignore_errors=True)
        print(f"{kind} {n}: " + ", ".join(f"{k} {rec[k]}" for k in ("elements", "nodes") if k in rec) +
              f", CPU {rec['process_cpu_s']:.2f} s (setup {rec['setup_cpu_seconds']:.2f}, read "
              f"{rec['read_cpu_seconds']:.2f}), per step ms {fmt(rec['per_step_ms'])}, first {fmt(rec['first_step_ms'])}, "
              f"sweeps/step {rec['sweeps_per_step']:.0f}, active {rec['active_mean']:.0f}, ns/update "
              f"{rec['ns_per_update'] or 0:.1f}, load {rec['load_before']}-{rec['load_after']}", flush=True)
        results.append(rec)
        shutil.rmtree(d, ignore_errors=True)
        if save:
            save({"runs": results})     # what ran so far survives a stopped study
    return results


def fmt(d):
    return "{" + ", ".join(f"{k} {v:.3g}" for k, v in d.items()) + "}"


def lmgc90_study(fracas, work, repeat, callgrind):
    deck = DECKS / "mesh_exploded_beam"
    cmd = REPO / "test_cases" / "compat" / "mesh_exploded_beam" / "run.dat"
    si = np.loadtxt(deck / "POSTPRO" / "SOLVER_INFORMATIONS.DAT", ndmin=2)
    lm = dict(LMGC90_BEAM)
    lm["sweeps_total"] = int(si[:, 1].sum())
    lm["sweeps_max"] = int(si[:, 1].max())
    # LMGC90's check after each block of 50 sweeps evaluates every contact once more
    # (what Fracas' check pass mirrors): (sweeps + blocks) x contacts local solves.
    lm["checks_total"] = int(np.ceil(si[:, 1] / 50).sum())
    lm["updates_total"] = (lm["sweeps_total"] + lm["checks_total"]) * lm["contacts"]
    lm["ns_per_update_loop"] = 1e9 * lm["loop_s"] / lm["updates_total"]
    lm["ns_per_update_process"] = 1e9 * lm["process_cpu_s"] / lm["updates_total"]
    runs = []
    for i in range(repeat):
        rec = run_fracas(fracas, ["--command", str(cmd), str(deck)], work / "beam")
        rec.update(read_h5(work / "beam"))
        sw = np.loadtxt(work / "beam" / "POSTPRO" / "SOLVER_INFORMATIONS.DAT", ndmin=2) \
            if (work / "beam" / "POSTPRO" / "SOLVER_INFORMATIONS.DAT").exists() else None
        if sw is not None:
            rec["postpro_sweeps_total"] = int(sw[:, 1].sum())
        rec["ns_per_update_process"] = 1e9 * rec["process_cpu_s"] / rec["updates_total"]
        runs.append(rec)
        print(f"beam run {i + 1}: CPU {rec['process_cpu_s']:.2f} s, loop CPU {rec['loop_cpu_seconds']:.2f} s, "
              f"sweeps {rec['sweeps_total']}, ns/update: solve {rec['ns_per_update']:.1f}, loop "
              f"{rec['ns_per_update_loop']:.1f}, process {rec['ns_per_update_process']:.1f}; load "
              f"{rec['load_before']}-{rec['load_after']}", flush=True)
    out = {"lmgc90": lm, "fracas_runs": runs, "fracas_median": median_record(runs)}
    if callgrind:
        out["callgrind"] = callgrind_steps(fracas, ["--command", str(cmd), str(deck)], work, (20, 100))
    return out


# ----------------------------------------------------------------------------- main

def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("what", choices=("big", "exploded", "lmgc90", "plot"))
    ap.add_argument("--fracas", default=str(REPO / "build" / "release" / "bin" / "fracas"))
    ap.add_argument("--work", default="/tmp/fracas_mesh_bench")
    ap.add_argument("--sizes", default=None)
    ap.add_argument("--steps", type=int, default=None)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--callgrind", type=int, default=0, metavar="MAX_SIZE",
                    help="also count instructions with callgrind for sizes up to MAX_SIZE (lmgc90: any > 0)")
    ap.add_argument("--callgrind-steps", default="2,5", help="steps of the two callgrind runs (difference = steady steps)")
    ap.add_argument("--tag", default="", help="suffix of the results file")
    a = ap.parse_args()
    work = Path(a.work)
    work.mkdir(parents=True, exist_ok=True)
    RESULTS.mkdir(parents=True, exist_ok=True)
    machine = {"cpu": cpu_name(), "cores": os.cpu_count(), "commit": git_commit(),
               "date": time.strftime("%Y-%m-%d %H:%M")}
    if a.what == "plot":
        import mesh_bench_plot
        mesh_bench_plot.main(RESULTS, IMG)
        return
    path = RESULTS / f"mesh_{a.what}{a.tag}.json"
    if a.what == "lmgc90":
        res = lmgc90_study(a.fracas, work, a.repeat, a.callgrind)
    else:
        default = {"big": "22,39,70,122,223", "exploded": "22,39,71,122,223"}[a.what]
        sizes = [int(s) for s in (a.sizes or default).split(",")]
        steps = a.steps or (50 if a.what == "big" else 20)
        cg_steps = tuple(int(x) for x in a.callgrind_steps.split(","))
        res = {"runs": study(a.what, sizes, steps, a.fracas, work, a.callgrind, cg_steps, a.repeat,
                             save=lambda r: path.write_text(json.dumps({**r, "machine": machine}, indent=1)))}
    res["machine"] = machine
    path.write_text(json.dumps(res, indent=1))
    print("wrote", path)


def cpu_name():
    for line in Path("/proc/cpuinfo").read_text().splitlines():
        if line.startswith("model name"):
            return line.split(":", 1)[1].strip()
    return "?"


def git_commit():
    try:
        return subprocess.run(["git", "-C", str(REPO), "rev-parse", "--short", "HEAD"], capture_output=True,
                              text=True).stdout.strip()
    except OSError:
        return "?"


if __name__ == "__main__":
    main()
