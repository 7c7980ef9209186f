#!/usr/bin/python3
"""Exact restart check: a run restarted from a restart point of its fracas.h5 must do,
step for step and bit for bit, what the uninterrupted run did.

    restart_exact.py --fracas BIN --work DIR --steps N --at K [--set key=value ...]
                     [--command FILE] CASE_DIR

Runs CASE_DIR for N steps with a snapshot (and so a restart point) every step into
DIR/whole, then ``fracas --restart DIR/whole/OUTBOX/fracas.h5 --restart-step K`` into
DIR/restarted (steps K+1..N), and requires, for every step after K (the step right after
the restart first): body positions X and velocities V, every contact dataset (reactions,
velocities, gaps, statuses, cohesive internals and broken flags, ...) and every series
column except the wall times equal to the last bit. The restart step K is the step
number of the restart point (DOF.INI's step + steps done). Exit 0 on success, 1 otherwise.
"""

import argparse
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np

from fracas_tools.results import Run  # noqa: E402  (the one reader of fracas.h5)



def run(cmd):
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        print(r.stdout)
        sys.exit(f"restart_exact.py: {' '.join(cmd)} failed with status {r.returncode}")


def snapshots_by_step(run):
    """step -> the snapshot's HDF5 group (every dataset is compared, whatever it holds)."""
    return {s: run.file["snapshots"][name] for name, (s, _) in zip(run.snapshot_names, run.snapshot_times())}


def datasets(group):
    """path -> dataset of every dataset under a snapshot group (bodies, contacts, meshes, cracks)."""
    out = {}
    group.visititems(lambda name, obj: out.__setitem__(name, obj) if hasattr(obj, "shape") else None)
    return out


def compare(whole, restarted, at):
    """List of (step, what, max |difference|) for every value that is not identical."""
    bad = []
    sw, sr = snapshots_by_step(whole), snapshots_by_step(restarted)
    steps = sorted(s for s in sw if s > at)
    if sorted(sr) != steps:
        bad.append((at + 1, f"snapshot steps: restarted {sorted(sr)[:3]}..., whole {steps[:3]}...", np.inf))
        return bad, 0
    for s in steps:
        a, b = datasets(sw[s]), datasets(sr[s])
        if set(a) != set(b):
            bad.append((s, f"datasets differ ({sorted(set(a) ^ set(b))})", np.inf))
            continue
        for name in sorted(a):
            x, y = a[name][()], b[name][()]
            if x.shape != y.shape:
                bad.append((s, f"{name} shape {y.shape} instead of {x.shape}", np.inf))
            elif not np.array_equal(x, y):
                d = np.max(np.abs(x.astype(float) - y.astype(float))) if x.size else np.inf
                bad.append((s, name, d))
    step_w = whole.series["step"]
    step_r = restarted.series["step"]
    rows = step_w > at
    if not np.array_equal(step_w[rows], step_r):
        bad.append((at + 1, "series/step rows", np.inf))
    else:
        for name in whole.series:
            if name.endswith("_time"):   # wall-clock timers (step, solve, bodies, detect, ...)
                continue
            x, y = whole.series[name][rows], restarted.series[name]
            if not np.array_equal(x, y):
                k = int(np.argmax(x != y))
                bad.append((int(step_r[k]), f"series/{name}", float(np.max(np.abs(x - y)))))
    return bad, len(steps)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--fracas", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--steps", type=int, required=True)
    p.add_argument("--at", type=int, required=True, help="step of the restart point")
    p.add_argument("--set", action="append", default=[], dest="sets")
    p.add_argument("--command", default=None)
    p.add_argument("case")
    a = p.parse_args()
    work = Path(a.work)
    if work.exists():
        shutil.rmtree(work)
    common = ["-q", "--overwrite", "--set", f"number_of_steps={a.steps}", "--set", "output_hdf5_every=1",
              "--set", "output_vtk_every=0", "--set", "output_dof_every=0"]
    for s in a.sets:
        common += ["--set", s]
    if a.command:
        common += ["--command", a.command]
    run([a.fracas] + common + ["--output", str(work / "whole"), a.case])
    whole_h5 = work / "whole" / "OUTBOX" / "fracas.h5"
    run([a.fracas] + common + ["--restart", str(whole_h5), "--restart-step", str(a.at),
                               "--output", str(work / "restarted"), a.case])
    with Run(whole_h5) as w, Run(work / "restarted" / "OUTBOX" / "fracas.h5") as r:
        bad, nsteps = compare(w, r, a.at)
        internals = "internals" in snapshots_by_step(w)[a.at + 1]["contacts"]
        ncontacts = len(snapshots_by_step(w)[a.at + 1]["contacts/inter"])
        if internals:
            beta = snapshots_by_step(w)[a.at + 1]["contacts/internals"][()][:, 3]
            print(f"step {a.at + 1}: {ncontacts} contacts, cohesive beta in [{beta.min():.4g}, {beta.max():.4g}]")
        else:
            print(f"step {a.at + 1}: {ncontacts} contacts")
    first = [b for b in bad if b[0] == a.at + 1]
    print(f"{'FAIL' if first else 'PASS'} step {a.at + 1} (right after the restart): X, V, contacts, series "
          f"{'differ: ' + ', '.join(f'{w} ({d:.3g})' for _, w, d in first) if first else 'identical to the last bit'}")
    print(f"{'FAIL' if bad else 'PASS'} steps {a.at + 1}..{a.steps} ({nsteps} snapshots): "
          f"{len(bad)} differences" + (f", first at step {bad[0][0]}: {bad[0][1]}" if bad else ""))
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
