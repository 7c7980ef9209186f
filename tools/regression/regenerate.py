#!/usr/bin/env python3
"""Regenerate a regression case's reference.tag (the only way to make one).

    build/release/bin/fracas-python tools/regression/regenerate.py --fracas build/release/bin/fracas \\
        test_cases/regression/deposit_1000 [--work DIR] [--run-dir DIR]

Runs the case (``fracas -q --overwrite --output WORK CASE``; WORK defaults to a
temporary directory) with its committed DATBOX/COMMAND.DAT, then calls
``tagged.py --make-reference CASE/reference.tag --tolerances CASE/tolerances.txt``.
With ``--run-dir`` an existing run is used instead of running again.
Use a release build: the reference is the release run's values, the tolerances
(CASE/tolerances.txt, hand-written and justified in CASE/README.md) cover the
differences of other builds and solver settings.
"""

import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import tagged  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("case", help="regression case directory (DATBOX/, tolerances.txt)")
    p.add_argument("--fracas", help="the fracas executable (release build)")
    p.add_argument("--work", help="where to write the run (default: a temporary directory)")
    p.add_argument("--run-dir", help="use this finished run instead of running the case")
    a = p.parse_args(argv)
    case = Path(a.case).resolve()
    tol_file = case / "tolerances.txt"
    if not tol_file.is_file():
        p.error(f"{tol_file} is missing")
    tmp = None
    if a.run_dir:
        run_dir = Path(a.run_dir)
    else:
        if not a.fracas:
            p.error("give --fracas BIN (or --run-dir)")
        if a.work:
            run_dir = Path(a.work)
        else:
            tmp = tempfile.TemporaryDirectory(prefix="fracas-ref-")
            run_dir = Path(tmp.name)
        cmd = [a.fracas, "-q", "--overwrite", "--output", str(run_dir), str(case)]
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True)
        print(f"regenerate.py: ran {case.name} in {time.perf_counter() - t0:.2f} s")
    tags = tagged.compute_tags(run_dir, case)
    rel = case.relative_to(ROOT) if case.is_relative_to(ROOT) else case
    command = f"build/release/bin/fracas-python tools/regression/regenerate.py --fracas build/release/bin/fracas {rel}"
    tagged.make_reference(tags, tagged.read_tolerances(tol_file), case / "reference.tag", command)
    print(f"regenerate.py: wrote {case / 'reference.tag'} ({len(tags)} tags)")
    if tmp:
        tmp.cleanup()
    return 0


if __name__ == "__main__":
    sys.exit(main())
