#!/usr/bin/python3
"""Plot and tabulate the linear-solver benchmark (bench/linear_solver_bench.f90).

    linear_solver_plot.py OUT.png RESULTS.csv [MORE.csv ...] [--table]

Reads the CSV files written by `fracas-linear-solver-bench --csv` (several runs or size
ranges may be given: for a (method, n) seen twice the smaller time of each column is
kept), draws factorization (build), refactorization (update) and solve times against n
for each method, and prints the crossovers between dense LAPACK and CHOLMOD: the size
from which CHOLMOD is faster at every larger measured size. With --table, prints the
markdown table used in doc/benchmarks.md.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

AUTO_DENSE_MAX_N = 32  # fracas_linear_solver's auto_dense_max_n
TIME_COLUMNS = ["t_assemble", "t_refill", "t_build", "t_update", "t_solve1", "t_solve10_per_rhs"]
LABELS = {
    "dense": "dense LAPACK dpotrf",
    "cholmod-metis": "CHOLMOD, METIS",
    "cholmod-amd": "CHOLMOD, AMD",
    "cholmod-best": "CHOLMOD, best of METIS/AMD",
    "umfpack": "UMFPACK LU",
}


def read_rows(paths):
    rows = {}
    for path in paths:
        with open(path, newline="") as handle:
            for row in csv.DictReader(handle):
                key = (row["method"], int(row["n"]))
                for column in TIME_COLUMNS + ["nnz_factor", "rel_error"]:
                    row[column] = float(row[column])
                if key in rows:
                    for column in TIME_COLUMNS:
                        rows[key][column] = min(rows[key][column], row[column])
                else:
                    rows[key] = row
    return rows


def crossover(rows, metric, challenger="cholmod-best"):
    """Smallest n from which the challenger beats dense at every larger n measured."""
    sizes = sorted(n for (m, n) in rows if m == "dense" and (challenger, n) in rows)
    cross = None
    for n in reversed(sizes):
        if rows[(challenger, n)][metric] < rows[("dense", n)][metric]:
            cross = n
        else:
            break
    return cross


def main(argv):
    table = "--table" in argv
    args = [a for a in argv if a != "--table"]
    if len(args) < 2:
        sys.exit(__doc__)
    out, paths = args[0], args[1:]
    rows = read_rows(paths)
    methods = [m for m in LABELS if any(k[0] == m for k in rows)]

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.8), sharex=True)
    panels = [("t_build", "factorization (analysis + numeric) [s]"),
              ("t_update", "numeric refactorization [s]"),
              ("t_solve1", "solve, one right-hand side [s]")]
    for ax, (metric, title) in zip(axes, panels):
        for m in methods:
            pts = sorted((n, r[metric]) for (mm, n), r in rows.items() if mm == m)
            ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", ms=3, label=LABELS[m])
        ax.axvline(AUTO_DENSE_MAX_N, color="grey", ls="--", lw=1)
        ax.set_title(title)
        ax.set_xlabel("unknowns n (2D lattice, Q4 pattern)")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].text(AUTO_DENSE_MAX_N * 1.1, axes[0].get_ylim()[1] / 3, "auto: dense up to here", fontsize=8, color="grey")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)

    for metric in ["t_build", "t_update", "t_solve1"]:
        for challenger in ["cholmod-amd", "cholmod-metis", "cholmod-best"]:
            print(f"crossover {metric} dense -> {challenger}: n = {crossover(rows, metric, challenger)}")

    if table:
        print()
        print("| n | nnz(A) | method | factor [s] | refactor [s] | solve [s] | solve/rhs, 10 rhs [s] "
              "| nnz(factor) | error |")
        print("|---|---|---|---|---|---|---|---|---|")
        for n in sorted({k[1] for k in rows}):
            for m in methods:
                r = rows.get((m, n))
                if r is None:
                    continue
                print(f"| {n} | {r['nnz_a']} | {m} | {r['t_build']:.3g} | {r['t_update']:.3g} | "
                      f"{r['t_solve1']:.3g} | {r['t_solve10_per_rhs']:.3g} | {r['nnz_factor']:.3g} | "
                      f"{r['rel_error']:.1e} |")
        print()
        print("| n | triplets | assemble (sparse_from_triplets) [s] | refill [s] |")
        print("|---|---|---|---|")
        for n in sorted({k[1] for k in rows}):
            r = next(rows[k] for k in rows if k[1] == n)
            print(f"| {n} | {r['triplets']} | {r['t_assemble']:.3g} | {r['t_refill']:.3g} |")


if __name__ == "__main__":
    main(sys.argv[1:])
