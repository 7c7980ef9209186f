#!/usr/bin/python3
"""Restart of a J2 meshed body from its OUTBOX text files (LMGC90's way): run the plastic
bar deck 200 steps in one go, and 60 steps then 140 more from DOF.OUT/GPV.OUT copied to
DOF.INI/GPV.INI; the restarted run must continue the plastic state.

usage: restart_mesh_gpv.py FRACAS DECK_DIR RUN_CONTROL WORK_DIR [--no-gpv]
(--no-gpv leaves GPV.INI out: the plastic state is lost; then the check passes only when
fracas warns that it is lost and the results do differ from the uninterrupted run, or
the run stops because they do: with finite-strain J2 (the deck's kine_ large Q4P0x) an
element of the bar turns inside out at step 37 (the run stops naming it); with small
strain its Newton loop diverged near step 100 and the state guard stopped the run at
step 153.)

References: the uninterrupted run. Tolerances: the restart reads values printed with 7
digits; the plastic state of finite-strain J2 is printed as LMGC90 prints it, Cp^-1,
whose entries near 1 carry the plastic strain (about 2e-3 here) to 5e-8 absolute, 2.5e-5
relative: node displacements agree within 2e-5 relative (measured 6.9e-6) and the
cumulative plastic strain p of every Gauss point within 2e-4 relative (measured 6.6e-5)
at step 200. (With the small-strain law, which prints the plastic strain itself, they
agreed within 1e-6 and 1e-5.)
"""
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np

from fracas_tools.outbox import read_dof_file, read_gpv


def run(fracas, case, cmd, steps, out, check=True):
    """Runs fracas; returns what it wrote on stderr (warnings) and its exit status."""
    done = subprocess.run([fracas, "-q", "--overwrite", "--command", str(cmd), "--set", f"number_of_steps={steps}",
                           "--set", "output_dof_every=0", "--output", str(out), str(case)], check=check,
                          stderr=subprocess.PIPE, text=True)
    sys.stderr.write(done.stderr)
    return done.stderr, done.returncode


def node_x(path):
    """Every X value of DOF.OUT, in file order (fracas_tools.outbox)."""
    return [float(v) for r in read_dof_file(path).records for v in np.ravel(r.x)]


def p_values(path):
    """The cumulative plastic strain p of every Gauss point of GPV.OUT: the 5th value of
    its internals line (the line of 6 values, third of each Gauss point)."""
    return [float(row[4]) for b in read_gpv(path).bodies for e in b.elements for row in e.rows if len(row) == 6]


def main():
    fracas, deck, cmd, work = sys.argv[1:5]
    with_gpv = "--no-gpv" not in sys.argv
    work = Path(work)
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    run(fracas, deck, cmd, 200, work / "whole")
    run(fracas, deck, cmd, 60, work / "first")
    case = work / "restart"
    shutil.copytree(Path(deck) / "DATBOX", case / "DATBOX")
    for name in ("Vloc_Rloc.INI", "POSTPRO.DAT", "GPV.INI"):
        (case / "DATBOX" / name).unlink(missing_ok=True)
    shutil.copy(work / "first" / "OUTBOX" / "DOF.OUT.1", case / "DATBOX" / "DOF.INI")
    if with_gpv:
        shutil.copy(work / "first" / "OUTBOX" / "GPV.OUT.1", case / "DATBOX" / "GPV.INI")
    err, status = run(fracas, case, cmd, 140, work / "second", check=with_gpv)
    warned = "GPV.INI gives no Gauss-point values" in err
    if status != 0:
        stopped = status == 1 and re.search(r"step \d+ \(t=.*\): MAILx body 1(?: ran away|: element \d+ turned "
                                            r"inside out)", err) is not None
        print(f"{'ok  ' if warned else 'FAIL'} without GPV.INI fracas warns that the plastic state is lost")
        print(f"{'ok  ' if stopped else 'FAIL'} the restarted run stopped by the state guard (exit {status})")
        return 0 if warned and stopped else 1
    x_whole = node_x(work / "whole" / "OUTBOX" / "DOF.OUT.1")
    x_rest = node_x(work / "second" / "OUTBOX" / "DOF.OUT.1")
    scale = max(abs(v) for v in x_whole)
    dx = max(abs(a - b) for a, b in zip(x_whole, x_rest)) / scale
    p_whole = p_values(work / "whole" / "OUTBOX" / "GPV.OUT.1")
    p_rest = p_values(work / "second" / "OUTBOX" / "GPV.OUT.1")
    dp = max(abs(a - b) for a, b in zip(p_whole, p_rest)) / max(p_whole)
    ok_x, ok_p = dx <= 2e-5 and len(x_whole) == len(x_rest), dp <= 2e-4 and len(p_whole) == len(p_rest) > 0
    print(f"{'ok  ' if ok_x else 'FAIL'} node displacements at step 200: max relative difference {dx:.2e} (2e-5)")
    print(f"{'ok  ' if ok_p else 'FAIL'} cumulative plastic strain p at step 200: max relative difference {dp:.2e} (2e-4),"
          f" {len(p_whole)} Gauss points")
    if not with_gpv:
        print(f"{'ok  ' if warned else 'FAIL'} without GPV.INI fracas warns that the plastic state is lost")
        return 0 if warned and not (ok_x and ok_p) else 1
    print(f"{'FAIL' if warned else 'ok  '} with GPV.INI no lost-state warning")
    return 0 if ok_x and ok_p and not warned else 1


if __name__ == "__main__":
    sys.exit(main())
