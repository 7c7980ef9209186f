#!/usr/bin/python3
"""Run (if needed) the validation cases of test_cases/validation and draw the plots of
doc/validation.md.

usage: plot_validation.py [--fracas BIN] [--runs DIR] [--out DIR] [--rerun]

    --fracas BIN   the solver (default build/release/bin/fracas)
    --runs DIR     where the runs go (default /tmp/fracas_validation); a case whose
                   DIR/<case>/OUTBOX/fracas.h5 exists is not rerun unless --rerun
    --out DIR      where the PNGs go (default doc/img)

Writes validation_bouncing_disk.png, validation_disk_column.png,
validation_newton_cradle.png.
"""
import argparse
import math
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
VAL = ROOT / "test_cases" / "validation"
from fracas_tools import valtools  # noqa: E402

CASES = {   # run name -> case directory
    "bouncing_disk": VAL / "bouncing_disk",
    "disk_column": VAL / "disk_column",
    "newton_cradle": VAL / "newton_cradle",
    "newton_cradle_sequential": VAL / "newton_cradle" / "sequential",
    "newton_cradle_inelastic": VAL / "newton_cradle" / "inelastic",
}


def load_gen(case):
    """The gen.py module of a case folder (its parameters)."""
    from fracas_tools.scripts import load
    return load(VAL / case / "gen.py")


def run_cases(fracas, runs, rerun):
    for name, case_dir in CASES.items():
        out = runs / name
        if (out / "OUTBOX" / "fracas.h5").exists() and not rerun:
            continue
        t0 = time.time()
        subprocess.run([str(fracas), "-q", "--overwrite", "--output", str(out), str(case_dir)],
                       check=True)
        print(f"ran {name} in {time.time() - t0:.1f} s")


def plot_bouncing(runs, out, plt):
    gen = load_gen("bouncing_disk")
    res = valtools.Results(runs / "bouncing_disk", contacts=False)
    y = res.position[:, 1, 1] - gen.R - gen.WALL_TOP
    g, e, h0 = gen.G, gen.E, gen.H0
    # exact trajectory and apexes
    s0 = math.sqrt(2 * g * h0)
    t_imp = math.sqrt(2 * h0 / g)
    tt = np.linspace(0, t_imp, 200)
    ex_t, ex_y = [tt], [h0 - 0.5 * g * tt ** 2]
    apex_t, apex_y = [], []
    for k in range(1, 40):
        v = e ** k * s0
        tf = 2 * v / g
        tt = np.linspace(0, tf, 200)
        ex_t.append(t_imp + tt)
        ex_y.append(v * tt - 0.5 * g * tt ** 2)
        apex_t.append(t_imp + v / g)
        apex_y.append(e ** (2 * k) * h0)
        t_imp += tf
    t_inf = math.sqrt(2 * h0 / g) * (1 + e) / (1 - e)
    fig, ax = plt.subplots(figsize=(8, 4.2))
    ax.plot(np.concatenate(ex_t), np.concatenate(ex_y), color="0.6", lw=2.5,
            label="exact (Newton, e = 0.8)")
    ax.plot(np.concatenate([[0.0], res.time]), np.concatenate([[h0], y]), color="C0", lw=1,
            label=f"Fracas, RST_CLB, h = {res.h:g} s")
    ax.plot(apex_t[:4], apex_y[:4], "o", mfc="none", mec="C3", ms=8,
            label=r"apex $e^{2k} h_0$, k = 1..4 (checked)")
    ax.axvline(t_inf, color="C2", ls="--", lw=1, label=r"rest time $\sqrt{2h_0/g}\,(1+e)/(1-e)$")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("height of the disk bottom (m)")
    ax.set_title("bouncing_disk: drop from h0 = 1 m on a fixed wall")
    ax.set_xlim(0, 4.5)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "validation_bouncing_disk.png", dpi=110)
    plt.close(fig)


def plot_column(runs, out, plt):
    gen = load_gen("disk_column")
    res = valtools.Results(runs / "disk_column")
    n = len(gen.RADII)
    m = res.mass[3:3 + n]
    w_above = np.cumsum((m * gen.G)[::-1])[::-1]

    def reactions(i):
        return np.array([res.reaction_between(i, 4 + k, 1 if k == 0 else 3 + k) for k in range(n)])

    err = np.array([np.max(np.abs(reactions(i) - w_above) / w_above) for i in range(len(res.time))])
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(9, 4))
    k = np.arange(n)
    a1.plot(w_above, k, "s", ms=9, mfc="none", mec="0.4", label="weight above (exact)")
    a1.plot(reactions(-1), k, "x", color="C3", label="Fracas, last step")
    a1.set_yticks(k)
    a1.set_yticklabels(["floor|1"] + [f"{j}|{j + 1}" for j in range(1, n)])
    a1.set_xlabel("normal force (N/m)")
    a1.set_ylabel("contact")
    a1.set_title("disk_column: reactions")
    a1.legend(fontsize=8)
    steps = np.arange(1, len(err) + 1)
    a2.semilogy(steps, np.maximum(err, 1e-17), color="C0")
    rho = valtools.chain_gauss_seidel_rate(m, grounded=True)
    a2.axhline(gen.NLGS_TOL, color="C2", ls="--", lw=1, label="nlgs_tolerance")
    a2.axhline(gen.NLGS_TOL / (1 - rho), color="C3", ls=":", lw=1, label=r"tol/(1-$\rho_{GS}$)")
    a2.set_xscale("log")
    a2.set_xlabel("step")
    a2.set_ylabel("max relative error of the reactions")
    a2.set_title("warm-started NLGS, Maxm 1e-6")
    a2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "validation_disk_column.png", dpi=110)
    plt.close(fig)


def plot_cradle(runs, out, plt):
    gen = load_gen("newton_cradle")
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.8), sharey=True)
    titles = {"newton_cradle": "touching, e = 1 (simultaneous)",
              "newton_cradle_sequential": "gaps > V h, e = 1 (sequential)",
              "newton_cradle_inelastic": "touching, e = 0"}
    for ax, name in zip(axes, titles):
        res = valtools.Results(runs / name, contacts=False)
        t = np.concatenate([[0.0], res.time]) * 1e3
        for k in range(gen.N):
            v0 = gen.V if k == 0 else 0.0
            ax.step(t, np.concatenate([[v0], res.V[:, k, 0]]), where="post", lw=1.5,
                    label=f"disk {k + 1}")
        ax.set_title(titles[name], fontsize=10)
        ax.set_xlabel("time (ms)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("velocity / V")
    for yv in (-0.6, 0.4):
        axes[0].axhline(yv, color="0.5", ls=":", lw=1)
    axes[2].axhline(0.2, color="0.5", ls=":", lw=1)
    axes[0].set_xlim(0, 10)
    axes[2].set_xlim(0, 10)
    axes[1].legend(fontsize=8)
    fig.suptitle("newton_cradle: N = 5 disks, disk 1 at V (dotted: NSCD references)", fontsize=11)
    fig.tight_layout()
    fig.savefig(out / "validation_newton_cradle.png", dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fracas", default=str(ROOT / "build" / "release" / "bin" / "fracas"))
    ap.add_argument("--runs", default="/tmp/fracas_validation")
    ap.add_argument("--out", default=str(ROOT / "doc" / "img"))
    ap.add_argument("--rerun", action="store_true")
    a = ap.parse_args()
    runs, out = Path(a.runs), Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    run_cases(a.fracas, runs, a.rerun)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plot_bouncing(runs, out, plt)
    plot_column(runs, out, plt)
    plot_cradle(runs, out, plt)
    print(f"wrote {out}/validation_*.png")


if __name__ == "__main__":
    main()
