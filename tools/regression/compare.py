#!/usr/bin/env python3
"""Compare a Fracas run's tagged values with a reference (made by tagged.py).

    build/release/bin/fracas-python tools/regression/compare.py REFERENCE RUN [--case CASE_DIR] [--write run.tag]
    build/release/bin/fracas-python tools/regression/compare.py --exact A B

REFERENCE is a reference.tag (``name : value : abs=A rel=R``). RUN is either a tag
file (``name : value``) or a run directory holding OUTBOX/fracas.h5, whose tags are
then computed with tagged.py (``--case`` names the case's DATBOX folder when the
run was written elsewhere with ``fracas --output``; ``--write`` keeps the tags).

One line per tag: PASS/FAIL, reference, run value, difference, allowed tolerance.
A tag passes when |run - ref| <= abs + rel*|ref| (string tags must be equal).
A tag of the reference missing from the run fails; extra run tags are listed.
Exit status 0 when every tag passes, 1 otherwise (2 for usage errors).

``--exact A B`` compares two tag files (or run directories) for bit-identical
values (determinism check: two runs of one deck on one machine).
"""

import argparse
import math
import sys
from pathlib import Path

import tagged  # noqa: E402


def load_run(path, case=None, with_hash=False):
    p = Path(path)
    if p.is_file() and p.suffix != ".h5":
        return tagged.read_tags(p)[0]
    return tagged.compute_tags(p, case, with_hash=with_hash)


def _fmt(v):
    if isinstance(v, str):
        return v if len(v) <= 16 else v[:13] + "..."
    if isinstance(v, int):
        return str(v)
    return f"{v:.9g}"


def compare(ref, tols, run):
    """Return (lines, n_failed)."""
    lines = []
    nfail = 0
    width = max([len(k) for k in ref] + [4])
    lines.append(f"{'':4}  {'tag'.ljust(width)}  {'reference':>16}  {'run':>16}  {'|diff|':>10}  {'allowed':>10}")
    for k, rv in ref.items():
        if k not in run:
            lines.append(f"FAIL  {k.ljust(width)}  {_fmt(rv):>16}  {'(missing)':>16}")
            nfail += 1
            continue
        v = run[k]
        if isinstance(rv, str) or isinstance(v, str):
            ok = str(rv) == str(v)
            diff, allowed = ("", "")
        else:
            a, r = tols.get(k, (0.0, 0.0))
            d = abs(float(v) - float(rv))
            tol = a + r * abs(float(rv))
            ok = math.isfinite(float(v)) and d <= tol
            diff, allowed = f"{d:.3g}", f"{tol:.3g}"
        nfail += not ok
        lines.append(f"{'PASS' if ok else 'FAIL'}  {k.ljust(width)}  {_fmt(rv):>16}  {_fmt(v):>16}  "
                     f"{diff:>10}  {allowed:>10}")
    extra = [k for k in run if k not in ref]
    if extra:
        lines.append("note: tags not in the reference (not compared): " + ", ".join(extra))
    return lines, nfail


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("reference", help="reference.tag (or, with --exact, the first run)")
    p.add_argument("run", help="the run's tag file or run directory (OUTBOX/fracas.h5)")
    p.add_argument("--case", help="case directory (DATBOX) of a run written with --output")
    p.add_argument("--write", metavar="TAGFILE", help="also write the run's tags there")
    p.add_argument("--exact", action="store_true",
                   help="both arguments are runs: every tag must be bit-identical")
    a = p.parse_args(argv)

    if a.exact:
        A = load_run(a.reference, a.case, with_hash=True)
        B = load_run(a.run, a.case, with_hash=True)
        ref, tols = A, {}
        run = B
        if a.write:
            tagged.write_tags(B, a.write)
    else:
        if not Path(a.reference).is_file():
            print(f"compare.py: no reference file {a.reference}", file=sys.stderr)
            return 2
        ref, tols = tagged.read_tags(a.reference)
        missing = [k for k in ref if k not in tols and not isinstance(ref[k], str)]
        if missing:
            print(f"compare.py: {a.reference}: no tolerance for {missing} (not a reference "
                  f"made by tagged.py --make-reference?)", file=sys.stderr)
            return 2
        run = load_run(a.run, a.case)
        if a.write:
            tagged.write_tags(run, a.write)
    lines, nfail = compare(ref, tols, run)
    print("\n".join(lines))
    what = "bit-identical" if a.exact else "within tolerance"
    if nfail:
        print(f"compare.py: {nfail} of {len(ref)} tags NOT {what}")
        return 1
    print(f"compare.py: all {len(ref)} tags {what}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
