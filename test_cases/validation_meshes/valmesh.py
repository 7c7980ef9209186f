"""Shared helpers of the meshed validation cases: running fracas and mesh_probe on a
generated case, reading OUTBOX/fracas.h5 series, reporting checks.

Each case script is called as  case.py --fracas BIN --probe BIN --out DIR [--long]
and exits 1 if a check fails."""
import argparse
import subprocess
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from meshdeck import read_probe  # noqa: E402,F401

results = []


def args(description):
    p = argparse.ArgumentParser(description=description)
    p.add_argument("--fracas", required=True)
    p.add_argument("--probe", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--long", action="store_true", help="the long version (finer meshes)")
    return p.parse_args()


def run_fracas(fracas, case_dir, *settings):
    cmd = [fracas, "-q", "--overwrite"] + [x for s in settings for x in ("--set", s)] + [str(case_dir)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"fracas failed on {case_dir}:\n{r.stdout}\n{r.stderr}")


def run_probe(probe, case_dir, out_file, every=0):
    cmd = [probe, str(case_dir), str(out_file)] + ([str(every)] if every else [])
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"mesh_probe failed on {case_dir}:\n{r.stdout}\n{r.stderr}")
    return read_probe(out_file)


def series(case_dir, *names):
    import h5py
    with h5py.File(Path(case_dir, "OUTBOX", "fracas.h5"), "r") as f:
        if f.attrs["complete"] != 1:
            sys.exit(f"{case_dir}: unfinished run")
        return [f["series"][n][:] for n in names]


def check(name, value, tol, detail=""):
    ok = bool(np.all(np.isfinite(value))) and value <= tol
    results.append(ok)
    print(f"{'PASS' if ok else 'FAIL'} {name}: {value:.3e} (tolerance {tol:.1e}){' ' + detail if detail else ''}")
    return ok


def finish():
    n_fail = results.count(False)
    print(f"{results.count(True)} passed, {n_fail} failed")
    sys.exit(1 if n_fail or not results else 0)
