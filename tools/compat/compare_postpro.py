#!/usr/bin/env python3
"""Compare the POSTPRO/*.DAT files of a Fracas run with LMGC90's for the same deck,
column by column.

    compare_postpro.py OURS_POSTPRO_DIR LMGC90_POSTPRO_DIR [--files F ...] [--rtol R] [--lines N]

Every file of LMGC90's folder that Fracas writes (SOLVER_INFORMATIONS.DAT,
BODY_*.DAT, TORQUE_*.DAT, DISSIPATED_ENERGY.DAT, and for meshed bodies Dep_*.DAT,
Fint_*.DAT) must exist in ours with the
same number of lines and columns, and the same line format (column widths).

Tolerance, to the printed precision: LMGC90 prints 8 significant digits (ES14.7,
the time ES15.8). A value agrees when |ours - lmgc90| <= 1 unit of its last printed
digit + rtol * S, where S is the largest magnitude in the column's group (columns of
the same quantity: positions, angles, velocities, forces, torques) over both files.
rtol = 1e-7 (default) is one unit of the 8th digit of the group's scale: it admits
the round-off of values far smaller than the group (a rotation of 1e-19 where the
other code has 0) and the 3e-8 relative difference between the two codes' weights
of a body (LMGC90's disk masses differ from pi r^2 rho in the 8th digit), nothing
more. Columns that compare NLGS norms at round-off level (both below 1e-6, both
converged) are not compared value by value; the sweep and contact counts are
compared exactly.

Exit status 0 when everything agrees; the worst deviation of each column is printed
in units of its tolerance.
"""
import argparse
import re
import sys
from pathlib import Path

import numpy as np

# Column groups (0-based) sharing a scale, per file kind; columns not listed are
# their own group. Counts are compared exactly.
GROUPS = {
    "BODY": [[1, 2, 4, 5], [3, 6], [7, 8], [9]],        # coor x,y + X x,y | angles | vx,vy | spin
    "TORQUE": [[1, 2, 4, 5], [3, 6]],                    # forces | torques
    "SOLVER_INFORMATIONS": [],
    "DISSIPATED_ENERGY": [[1, 2]],
    "Dep": [[1, 2], [3, 4]],                             # mean displacement | mean velocity
    "Fint": [list(range(1, 11))],                        # Reac, Fint, Finert, Fext, Res: forces
}
COUNT_COLUMNS = {"SOLVER_INFORMATIONS": [1, 5]}
NORM_COLUMNS = {"SOLVER_INFORMATIONS": [2, 3, 4]}
LINE_FORMAT = {  # widths of the fields of a line: ES15.8, then 1X + ES14.7 or 1X + I8
    "BODY": [15] + [15] * 9,
    "TORQUE": [15] + [15] * 6,
    "SOLVER_INFORMATIONS": [15, 9, 15, 15, 15, 9],
    "DISSIPATED_ENERGY": [15, 15, 15],
    "Dep": [15] * 5,
    "Fint": [15] * 11,
}


def kind_of(name):
    for k in GROUPS:
        if name.startswith(k):
            return k
    return None


def printed_ulp(values):
    """One unit of the 8th significant digit of each value as printed (ES14.7)."""
    a = np.abs(values)
    e = np.floor(np.log10(np.where(a > 0, a, 1.0)))
    return np.where(a > 0, 10.0 ** (e - 7), 0.0)


def check_line_format(path, widths):
    """Every line has the expected field widths (right-aligned values)."""
    for i, line in enumerate(Path(path).read_text().splitlines()[:50], 1):
        if len(line) != sum(widths):
            return f"{path.name}:{i}: line length {len(line)}, expected {sum(widths)}"
        pos = 0
        for w in widths:
            field = line[pos:pos + w]
            if not re.fullmatch(r" *-?[0-9.]+(E[+-][0-9]+)?", field):
                return f"{path.name}:{i}: field {field!r} at columns {pos + 1}-{pos + w}"
            pos += w
    return None


def compare_file(ours, ref, rtol, lines=None):
    kind = kind_of(ref.name)
    a = np.loadtxt(ours, ndmin=2)
    b = np.loadtxt(ref, ndmin=2)
    if lines:
        a, b = a[:lines], b[:lines]
    problems = []
    if a.shape != b.shape:
        return [f"{ref.name}: shape {a.shape}, LMGC90's {b.shape}"], []
    msg = check_line_format(ours, LINE_FORMAT[kind])
    if msg:
        problems.append("format: " + msg)
    ncol = b.shape[1]
    groups = [g for g in GROUPS[kind] if max(g) < ncol]
    grouped = {c for g in groups for c in g}
    groups += [[c] for c in range(ncol) if c not in grouped]
    report = []
    counts = COUNT_COLUMNS.get(kind, [])
    norms = NORM_COLUMNS.get(kind, [])
    for g in groups:
        scale = max(np.abs(a[:, g]).max(), np.abs(b[:, g]).max())
        for c in g:
            if c in counts:
                bad = np.nonzero(a[:, c] != b[:, c])[0]
                if len(bad):
                    k = bad[0]
                    problems.append(f"{ref.name} column {c + 1} (a count) differs at line {k + 1}: "
                                    f"{a[k, c]:g} against {b[k, c]:g} ({len(bad)} lines)")
                report.append((ref.name, c + 1, 0.0))
                continue
            if c in norms:
                both_tiny = (np.abs(a[:, c]) < 1e-6) & (np.abs(b[:, c]) < 1e-6)
                both_conv = (np.abs(a[:, c]) < 1) & (np.abs(b[:, c]) < 1)
                mask = ~both_tiny
                if not np.all(both_conv | mask):
                    problems.append(f"{ref.name} column {c + 1}: a step converged in one code only")
                col_a, col_b = a[mask, c], b[mask, c]
            else:
                col_a, col_b = a[:, c], b[:, c]
            tol = printed_ulp(col_b) + rtol * scale
            dev = np.abs(col_a - col_b)
            ratio = np.where(tol > 0, dev / np.where(tol > 0, tol, 1.0), np.where(dev > 0, np.inf, 0.0))
            worst = float(ratio.max()) if len(ratio) else 0.0
            report.append((ref.name, c + 1, worst))
            if worst > 1.0:
                k = int(np.argmax(ratio))
                problems.append(f"{ref.name} column {c + 1} line {k + 1}: {col_a[k]:.8e} against LMGC90's "
                                f"{col_b[k]:.8e} ({worst:.2f} x the tolerance)")
    return problems, report


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("ours", type=Path)
    p.add_argument("ref", type=Path)
    p.add_argument("--files", nargs="*", help="compare only these names (default: every LMGC90 file Fracas writes)")
    p.add_argument("--rtol", type=float, default=1e-7)
    p.add_argument("--lines", type=int, help="compare the first N lines only (a run shorter than LMGC90's)")
    a = p.parse_args(argv)
    names = a.files or sorted(f.name for f in a.ref.glob("*.DAT") if kind_of(f.name))
    if not names:
        print(f"no comparable files in {a.ref}")
        return 1
    problems = []
    for name in names:
        if not (a.ours / name).is_file():
            problems.append(f"{name}: missing in {a.ours}")
            continue
        pr, rep = compare_file(a.ours / name, a.ref / name, a.rtol, a.lines)
        problems += pr
        for fname, col, worst in rep:
            print(f"{fname} column {col}: worst deviation {worst:.3f} x tolerance")
    for pr in problems:
        print("FAIL: " + pr)
    print(f"{len(names)} file(s): {'OK' if not problems else f'{len(problems)} problem(s)'}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
