#!/usr/bin/env python3
"""Restart check (LMGC90's way): a run interrupted at step K and continued from its own
DOF.OUT / Vloc_Rloc.OUT (copied to DOF.INI / Vloc_Rloc.INI) must agree with the
uninterrupted run at step K+1 (the step right after the restart: a state the restart
lost, e.g. a cohesive beta reset, shows there even when the end state forgets it) and
at step N. The records hold 7 significant digits, so the continued run agrees to that
precision (tolerance: tol * (1 + |value|)), not to the last bit (fracas --restart from
fracas.h5 is bit-exact: tools/regression/restart_exact.py).

  restart_check.py FRACAS CASE_DIR WORK_DIR [--command COMMAND.DAT] --steps N --at K [--tol TOL]
                   [--tol-next TOL]
"""
import argparse
import os
import shutil
import subprocess
import sys

from fracas_tools.datbox import read_dof  # noqa: E402
from compare_lmgc90 import read_vloc  # noqa: E402


def run(fracas, case, out, settings, command):
    cmd = [fracas, "-q", "--overwrite", "--output", out] + (["--command", command] if command else []) + [case]
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
    p.add_argument("--tol-next", type=float, default=None, help="tolerance at step K+1 (default: --tol)")
    p.add_argument("--command", default=None, help="run-control deck (COMMAND.DAT) to use")
    a = p.parse_args()
    if os.path.exists(a.work):
        shutil.rmtree(a.work)
    tol_next = a.tol if a.tol_next is None else a.tol_next
    first = os.path.join(a.work, "first")
    second = os.path.join(a.work, "second")
    base = ["output_hdf5_every=0", "output_vtk_every=0", "output_dof_every=0"]
    run(a.fracas, a.case, first, base + [f"number_of_steps={a.at}"], a.command)
    # The continued case: same DATBOX, initial state from the first part's records.
    shutil.copytree(os.path.join(a.case, "DATBOX"), os.path.join(second, "DATBOX"))
    shutil.copy(os.path.join(first, "OUTBOX", "DOF.OUT.1"), os.path.join(second, "DATBOX", "DOF.INI"))
    shutil.copy(os.path.join(first, "OUTBOX", "Vloc_Rloc.OUT.1"), os.path.join(second, "DATBOX", "Vloc_Rloc.INI"))
    fails = checks = 0
    for label, steps, tol in ((f"step {a.at + 1} (right after the restart)", a.at + 1, tol_next),
                              (f"step {a.steps}", a.steps, a.tol)):
        whole = os.path.join(a.work, f"whole_{steps}")
        cont = os.path.join(a.work, f"continued_{steps}")
        run(a.fracas, a.case, whole, base + [f"number_of_steps={steps}"], a.command)
        run(a.fracas, second, cont, base + [f"number_of_steps={steps - a.at}"], a.command)
        f, c = compare(whole, cont, label, tol)
        fails += f
        checks += c
    print(f"{checks - fails} passed, {fails} failed")
    sys.exit(1 if fails else 0)


def compare(whole, cont, label, tol):
    """(failures, checks) of the continued run's last records against the whole run's."""
    s1, t1, ref = read_dof(os.path.join(whole, "OUTBOX", "DOF.OUT.1"))
    s2, t2, got = read_dof(os.path.join(cont, "OUTBOX", "DOF.OUT.1"))
    fails = 0
    ok = s1 == s2 and abs(t1 - t2) < 1e-12
    print(f"{'PASS' if ok else 'FAIL'} {label}: step/time continued {s2}/{t2} whole {s1}/{t1}")
    fails += not ok
    worst = 0.0
    for b in ref:
        for k in (0, 1):
            err = abs(got[b][k] - ref[b][k]) / (1.0 + abs(ref[b][k]))
            worst = max(worst, err.max())
    ok = worst <= tol
    print(f"{'PASS' if ok else 'FAIL'} {label}: max |continued - whole| / (1 + |whole|) over X and V: "
          f"{worst:.3e} tol {tol:.1e}")
    fails += not ok
    checks = 2
    # Cohesive state (L, ut, un, beta, TPSini): the damage continues where it stopped.
    vw = read_vloc(os.path.join(whole, "OUTBOX", "Vloc_Rloc.OUT.1"))
    vc = read_vloc(os.path.join(cont, "OUTBOX", "Vloc_Rloc.OUT.1"))
    # Reactions of every contact of the whole run.
    checks += 1
    worst_r = max((abs(vc[k][c] - vw[k][c]) / (1.0 + abs(vw[k][c])) for k in vw if k in vc for c in ("rlt", "rln")),
                  default=0.0)
    ok = worst_r <= tol and all(k in vc for k in vw)
    print(f"{'PASS' if ok else 'FAIL'} {label}: reactions of {len(vw)} contacts, max |continued - whole| / "
          f"(1 + |whole|): {worst_r:.3e} tol {tol:.1e}")
    fails += not ok
    keys = [k for k in vw if vw[k]["internals"]]
    if keys:
        checks += 1
        worst_i = max((abs(x - y) / (1.0 + abs(y)) for k in keys if k in vc
                       for x, y in zip(vc[k]["internals"], vw[k]["internals"])), default=float("inf"))
        ok = worst_i <= tol and all(k in vc for k in keys)
        betas = [vw[k]["internals"][3] for k in keys]
        print(f"{'PASS' if ok else 'FAIL'} {label}: cohesive internals (beta {min(betas):.4g}..{max(betas):.4g}), "
              f"max |continued - whole| / (1 + |whole|): {worst_i:.3e} tol {tol:.1e}")
        fails += not ok
    return fails, checks


if __name__ == "__main__":
    main()
