#!/usr/bin/env python3
"""Restart check: a run interrupted at step K and continued from its own
DOF.OUT / Vloc_Rloc.OUT (copied to DOF.INI / Vloc_Rloc.INI) must end where the
uninterrupted run ends. The records hold 7 significant digits, so the continued
run agrees to that precision (tolerance: tol * (1 + |value|)), not to the last bit.

  restart_check.py FRACAS CASE_DIR WORK_DIR --command COMMAND.DAT --steps N --at K [--tol TOL]
"""
import argparse
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
from fracas_tools.datbox import read_dof  # noqa: E402
from compare_lmgc90 import read_vloc  # noqa: E402


def run(fracas, case, out, settings, command):
    cmd = [fracas, "-q", "--overwrite", "--output", out, "--command", command, case]
    for s in settings:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("fracas")
    p.add_argument("case")
    p.add_argument("work")
    p.add_argument("--steps", type=int, required=True)
    p.add_argument("--at", type=int, required=True)
    p.add_argument("--tol", type=float, default=1e-6)
    p.add_argument("--command", required=True, help="run-control deck (COMMAND.DAT) to use")
    a = p.parse_args()
    if os.path.exists(a.work):
        shutil.rmtree(a.work)
    whole = os.path.join(a.work, "whole")
    first = os.path.join(a.work, "first")
    second = os.path.join(a.work, "second")
    base = ["output_hdf5_every=0"]
    run(a.fracas, a.case, whole, base + [f"number_of_steps={a.steps}", "output_dof_every=0"], a.command)
    run(a.fracas, a.case, first, base + [f"number_of_steps={a.at}", "output_dof_every=0"], a.command)
    # The continued case: same DATBOX, initial state from the first part's records.
    shutil.copytree(os.path.join(a.case, "DATBOX"), os.path.join(second, "DATBOX"))
    shutil.copy(os.path.join(first, "OUTBOX", "DOF.OUT.1"), os.path.join(second, "DATBOX", "DOF.INI"))
    shutil.copy(os.path.join(first, "OUTBOX", "Vloc_Rloc.OUT.1"), os.path.join(second, "DATBOX", "Vloc_Rloc.INI"))
    run(a.fracas, second, second, base + [f"number_of_steps={a.steps - a.at}", "output_dof_every=0"], a.command)
    s1, t1, ref = read_dof(os.path.join(whole, "OUTBOX", "DOF.OUT.1"))
    s2, t2, got = read_dof(os.path.join(second, "OUTBOX", "DOF.OUT.1"))
    fails = 0
    ok = s1 == s2 and abs(t1 - t2) < 1e-12
    print(f"{'PASS' if ok else 'FAIL'} final step/time: continued {s2}/{t2} whole {s1}/{t1}")
    fails += not ok
    worst = 0.0
    for b in ref:
        for k in (0, 1):
            err = abs(got[b][k] - ref[b][k]) / (1.0 + abs(ref[b][k]))
            worst = max(worst, err.max())
    ok = worst <= a.tol
    print(f"{'PASS' if ok else 'FAIL'} max |continued - whole| / (1 + |whole|) over X and V: {worst:.3e} tol {a.tol:.1e}")
    fails += not ok
    checks = 2
    # Cohesive state (L, ut, un, beta, TPSini): the damage continues where it stopped.
    vw = read_vloc(os.path.join(whole, "OUTBOX", "Vloc_Rloc.OUT.1"))
    vc = read_vloc(os.path.join(second, "OUTBOX", "Vloc_Rloc.OUT.1"))
    keys = [k for k in vw if vw[k]["internals"]]
    if keys:
        checks += 1
        worst_i = max((abs(x - y) / (1.0 + abs(y)) for k in keys if k in vc
                       for x, y in zip(vc[k]["internals"], vw[k]["internals"])), default=float("inf"))
        ok = worst_i <= a.tol and all(k in vc for k in keys)
        print(f"{'PASS' if ok else 'FAIL'} cohesive internals, max |continued - whole| / (1 + |whole|): "
              f"{worst_i:.3e} tol {a.tol:.1e}")
        fails += not ok
    print(f"{checks - fails} passed, {fails} failed")
    sys.exit(1 if fails else 0)


if __name__ == "__main__":
    main()
