#!/usr/bin/python3
"""Output benchmark: bytes and seconds per output frame, and memory over many frames.

Each measurement runs the same deck twice, with and without one kind of output, and
divides the differences by the number of outputs written:

  vtk       a 2000-disk deposit (fracas-tools deposit --n 2000, 1000 steps of 1 ms):
            DISPLAY every 10 steps (101 frames: disks, walls, ~5000 contacts at the end)
  hdf5      the same deposit, HDF5 snapshots every 10 steps (100 snapshots)
  snapshot  one disk pushed along the ground (LMGC90 deck driven_evolution),
            4500 steps, an HDF5 snapshot every step against none; and the run
            without snapshots (its cost is the step and the per-step series row)
  memory    a 1000-disk deposit, 400 steps with a DISPLAY frame every step:
            largest resident set against the same run without VTK

Seconds are CPU time (user + system; the single-disk runs also report wall time,
which holds the waits for the disk) of the fracas process, from its rusage, so that
other jobs on a shared machine inflate them little; the largest resident set comes
from the same rusage. The difference of two whole runs is noisy on a loaded
machine; fracas also times its own writes (the line 'fracas: output: ...' at the end
of a run: CPU time per kind), kept as own_account_* (the figures to trust). Bytes are the sizes of the files
written.

    build/release/bin/fracas-python tools/bench/output_cost.py [--fracas BIN] [--work DIR] [--only vtk,hdf5,...]
                                                [--json OUT.json] [--legacy]

--legacy: the binary predates output_vtk_precision (the keys this script sets are
then left out). About 3 minutes of CPU in all. Results: doc/benchmarks.md section 4.
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

ROOT = Path(__file__).resolve().parents[2]


LAST_OUTPUT_LINE = {}


def rusage_run(cmd):
    """Run cmd; return (cpu seconds, max RSS in kB) of that child alone. The
    run's own account of its output ('fracas: output: ...', wall time per kind)
    is kept in LAST_OUTPUT_LINE['line']."""
    # os.wait4 gives the rusage of the one child (RUSAGE_CHILDREN would accumulate)
    start = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    out, err = proc.stdout.read().decode(), proc.stderr.read().decode()
    _, status, ru = os.wait4(proc.pid, 0)
    LAST_OUTPUT_LINE["wall"] = time.monotonic() - start
    proc.stdout.close()
    proc.stderr.close()
    if os.waitstatus_to_exitcode(status) != 0:
        raise RuntimeError(f"{' '.join(map(str, cmd))} failed:\n{err}")
    LAST_OUTPUT_LINE["line"] = next((ln for ln in out.splitlines() if ln.startswith("fracas: output:")), "")
    return ru.ru_utime + ru.ru_stime, ru.ru_maxrss


def own_account(kind):
    """Wall ms per write of KIND ('VTK frames', 'HDF5 snapshots') from the last run's
    output line (None for a fracas that does not print one)."""
    m = re.search(rf"(\d+) {kind} [\d.]+ s CPU \(([\d.]+) ms each\)", LAST_OUTPUT_LINE.get("line", ""))
    return float(m.group(2)) if m else None


def folder_bytes(path):
    return sum(p.stat().st_size for p in Path(path).rglob("*") if p.is_file())


def deposit(work, n):
    case = Path(work) / f"deposit_{n}"
    if not (case / "DATBOX" / "COMMAND.DAT").exists():
        subprocess.run([str(ROOT / "tools" / "fracas-tools"), "deposit", str(case), "--n", str(n),
                        "--vtk-every", "0", "--hdf5-every", "0"], check=True, stdout=subprocess.DEVNULL)
    return case


def fracas_run(fracas, case, out, settings):
    cmd = [fracas, "--overwrite", "--output", str(out)]
    for s in settings:
        cmd += ["--set", s]
    return rusage_run(cmd + [str(case)])


def measure_vtk(a, fracas):
    case = deposit(a.work, 2000)
    extra = [] if a.legacy else ["output_vtk_precision=single"]
    base = ["output_hdf5_every=0", "output_dof_every=0"]
    t0, _ = fracas_run(fracas, case, Path(a.work) / "vtk_off", base + ["output_vtk_every=0"])
    t1, _ = fracas_run(fracas, case, Path(a.work) / "vtk_on", base + ["output_vtk_every=10"] + extra)
    wall_ms = own_account("VTK frames")
    frames = 101
    nbytes = folder_bytes(Path(a.work) / "vtk_on" / "DISPLAY")
    res = {"frames": frames, "bytes_total": nbytes, "bytes_per_frame": nbytes / frames,
           "cpu_without": t0, "cpu_with": t1, "seconds_per_frame": (t1 - t0) / frames,
           "step_seconds": t0 / 1000, "own_account_cpu_ms_per_frame": wall_ms}
    if not a.legacy:
        t2, _ = fracas_run(fracas, case, Path(a.work) / "vtk_double", base + ["output_vtk_every=10",
                                                                            "output_vtk_precision=double"])
        nb2 = folder_bytes(Path(a.work) / "vtk_double" / "DISPLAY")
        res.update({"double_bytes_per_frame": nb2 / frames, "double_seconds_per_frame": (t2 - t0) / frames})
    return res


def measure_hdf5(a, fracas):
    case = deposit(a.work, 2000)
    base = ["output_vtk_every=0", "output_dof_every=0"]
    t0, _ = fracas_run(fracas, case, Path(a.work) / "h5_off", base + ["output_hdf5_every=0"])
    t1, _ = fracas_run(fracas, case, Path(a.work) / "h5_on", base + ["output_hdf5_every=10"])
    wall_ms = own_account("HDF5 snapshots")
    f0 = (Path(a.work) / "h5_off" / "OUTBOX" / "fracas.h5").stat().st_size
    f1 = (Path(a.work) / "h5_on" / "OUTBOX" / "fracas.h5").stat().st_size
    return {"snapshots": 100, "bytes_per_snapshot": (f1 - f0) / 100, "file_without": f0, "file_with": f1,
            "cpu_without": t0, "cpu_with": t1, "seconds_per_snapshot": (t1 - t0) / 100,
            "own_account_cpu_ms_per_snapshot": wall_ms}


def measure_snapshot(a, fracas):
    deck = Path(os.environ.get("FRACAS_LMGC90_DECKS", ROOT.parent / "shared" / "lmgc90_decks")) / "driven_evolution"
    base = ["output_vtk_every=0"]
    command = Path(a.work) / "single_disk.dat"     # a file, for a fracas that needs one
    command.write_text("time_step 1e-3\nnumber_of_steps 4500\n")
    runs = {}
    for name, every in (("none", 0), ("every_step", 1)):
        out = Path(a.work) / f"single_{name}"
        cmd = [fracas, "--overwrite", "--command", str(command), "--output", str(out)]
        for s in base + [f"output_hdf5_every={every}"]:
            cmd += ["--set", s]
        t, _ = rusage_run(cmd + [str(deck)])
        runs[name] = (t, (out / "OUTBOX" / "fracas.h5").stat().st_size, LAST_OUTPUT_LINE["wall"])
    (t0, b0, w0), (t1, b1, w1) = runs["none"], runs["every_step"]
    return {"steps": 4500, "cpu_without": t0, "file_without": b0, "cpu_with": t1, "file_with": b1,
            "wall_without": w0, "wall_with": w1,
            "seconds_per_snapshot": (t1 - t0) / 4500, "bytes_per_snapshot": (b1 - b0) / 4500,
            "seconds_per_step_without": t0 / 4500}


def measure_memory(a, fracas):
    case = deposit(a.work, 1000)
    base = ["number_of_steps=400", "output_hdf5_every=0", "output_dof_every=0"]
    t0, rss0 = fracas_run(fracas, case, Path(a.work) / "mem_off", base + ["output_vtk_every=0"])
    t1, rss1 = fracas_run(fracas, case, Path(a.work) / "mem_on", base + ["output_vtk_every=1"])
    nbytes = folder_bytes(Path(a.work) / "mem_on" / "DISPLAY")
    return {"frames": 401, "rss_kb_without": rss0, "rss_kb_with": rss1,
            "kb_per_frame": (rss1 - rss0) / 401, "cpu_without": t0, "cpu_with": t1,
            "seconds_per_frame": (t1 - t0) / 401, "bytes_per_frame": nbytes / 401,
            "own_account_cpu_ms_per_frame": own_account("VTK frames")}


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--fracas", default=str(ROOT / "build" / "release" / "bin" / "fracas"))
    p.add_argument("--work", default="/tmp/fracas_output_bench")
    p.add_argument("--only", default="vtk,hdf5,snapshot,memory")
    p.add_argument("--json", help="write the results here")
    p.add_argument("--legacy", action="store_true", help="a fracas without output_vtk_precision")
    a = p.parse_args(argv)
    Path(a.work).mkdir(parents=True, exist_ok=True)
    fracas = shutil.which(a.fracas) or a.fracas
    results = {"fracas": fracas}
    for name in a.only.split(","):
        results[name] = {"vtk": measure_vtk, "hdf5": measure_hdf5, "snapshot": measure_snapshot,
                         "memory": measure_memory}[name](a, fracas)
        print(name, json.dumps(results[name], indent=1), flush=True)
    if a.json:
        Path(a.json).write_text(json.dumps(results, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
