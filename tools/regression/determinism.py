#!/usr/bin/env python3
"""Determinism check: run one deck twice and require bit-identical results.

    build/release/bin/fracas-python tools/regression/determinism.py --fracas BIN --work DIR CASE_DIR \\
        [--set key=value ...]

Runs ``BIN -q --overwrite --output DIR/run_a CASE_DIR`` and the same into DIR/run_b
(with the given --set overrides, e.g. number_of_steps=200 to keep it cheap), then
requires: every tag of tagged.py identical to the last bit (including the SHA-256 of
the final positions, velocities and reactions) and the OUTBOX text files
(DOF.OUT.n, Vloc_Rloc.OUT.n) byte-identical. Exit 0 on success, 1 otherwise.
"""

import argparse
import filecmp
import subprocess
import sys
import time
from pathlib import Path

import compare  # noqa: E402
import tagged  # noqa: E402


def run(fracas, case, out, sets):
    cmd = [fracas, "-q", "--overwrite", "--output", str(out)]
    for s in sets:
        cmd += ["--set", s]
    cmd.append(str(case))
    t0 = time.perf_counter()
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    dt = time.perf_counter() - t0
    if r.returncode != 0:
        print(r.stdout)
        raise SystemExit(f"determinism.py: {' '.join(cmd)} failed with status {r.returncode}")
    print(f"run {out.name}: {dt:.2f} s")
    return dt


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("case", help="case directory (DATBOX/)")
    p.add_argument("--fracas", required=True, help="the fracas executable")
    p.add_argument("--work", required=True, help="directory for the two runs")
    p.add_argument("--set", action="append", default=[], help="COMMAND.DAT override (repeatable)")
    a = p.parse_args(argv)
    work = Path(a.work)
    work.mkdir(parents=True, exist_ok=True)
    ra, rb = work / "run_a", work / "run_b"
    for r in (ra, rb):
        run(a.fracas, a.case, r, a.set)
    A = tagged.compute_tags(ra, a.case, with_hash=True)
    B = tagged.compute_tags(rb, a.case, with_hash=True)
    lines, nfail = compare.compare(A, {}, B)
    print("\n".join(lines))
    texts = sorted(x.name for x in (ra / "OUTBOX").iterdir() if ".OUT." in x.name)
    for name in texts:
        same = filecmp.cmp(ra / "OUTBOX" / name, rb / "OUTBOX" / name, shallow=False)
        print(f"{'PASS' if same else 'FAIL'}  OUTBOX/{name} byte-identical")
        nfail += not same
    if not texts:
        print("note: no OUTBOX text files to compare")
    if nfail:
        print(f"determinism.py: {nfail} differences between two identical runs")
        return 1
    print("determinism.py: the two runs are bit-identical")
    return 0


if __name__ == "__main__":
    sys.exit(main())
