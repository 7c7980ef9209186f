#!/usr/bin/python3
"""The paper's claim on the small hydrided plate over microstructures and meshes: the
plate of the ctest case (test_cases/validation/hydrided_plate: 16 x 16 um, hydrides
2-2.2 um thick, aspect 2.5-3.5, notch 2.5 um, pulled at -+10 m/s for 60 ns) for several
seeds (each its own hydrides) at two element sizes (each seed's hydrides meshed twice),
weak and strong bonding, with the converged settings (damage within the step,
crack_step_limit 0.25, dt = 2e-10 s x h / 1 um). Prints the macro-crack shares per run,
their mean and spread per bonding and size, and the seed-by-seed differences of the
claim, and says which hold on every seed and both sizes.

    build/release/bin/fracas-python tools/hydride/mesh_study.py WORK [--seeds 1 2 3] [--sizes 1e-6 0.7e-6] [--fracas BIN] [--json OUT] [--png OUT]

Runs whose summary exists in WORK are reused. About 15 min of CPU for 3 seeds.
"""
import argparse
import json
import resource
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
from fracas_tools.scripts import load  # noqa: E402

small = load(ROOT / "test_cases" / "validation" / "hydrided_plate" / "gen.py")   # the ctest plate's geometry
hp = load(HERE / "hydride_plate.py")
post = load(HERE / "hydride_post.py")

FINAL_TIME = 60e-9
FAMILIES = ("HY_HY", "HY_MA", "MA_MA")


def run_case(work, fracas, seed, bonding, h):
    d = work / f"{bonding}_h{round(h * 1e9)}_s{seed}"
    summary = d / "summary.json"
    if summary.exists():
        return json.loads(summary.read_text())
    dt = small.DT * h / 1e-6
    steps = round(FINAL_TIME / dt)
    hp.generate(d, seed, h, bonding, small.GEOMETRY, hp.Loading(velocity=10.0), time_step=dt, steps=steps,
                output_every=steps)
    t0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([fracas, "-q", "--overwrite", str(d)], check=True)
    t1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    s = post.summary(d)
    out = dict(seed=seed, bonding=bonding, h=h, elements=s["elements"], shares=s["crack"]["shares"],
               separated=s["crack"]["separated"], peak=s["peak_stress"] / 1e6,
               balance=s["energies"]["relative_balance_error"], cpu=t1.ru_utime - t0.ru_utime)
    summary.write_text(json.dumps(out, indent=1) + "\n")
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("work")
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument("--sizes", type=float, nargs="+", default=[1e-6, 0.7e-6])
    ap.add_argument("--fracas", default=str(ROOT / "build" / "release" / "bin" / "fracas"))
    ap.add_argument("--json", default=None)
    ap.add_argument("--png", default=None, help="shares per bonding and size, one dot per seed")
    a = ap.parse_args()
    work = Path(a.work)
    runs = [run_case(work, a.fracas, s, b, h) for h in a.sizes for s in a.seeds for b in ("weak", "strong")]
    print("| h (um) | seed | bonding | elements | HY_HY | HY_MA | MA_MA | separated | peak (MPa) | CPU (s) |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for r in runs:
        sh = r["shares"]
        print(f"| {r['h'] * 1e6:g} | {r['seed']} | {r['bonding']} | {r['elements']} | "
              + " | ".join(f"{sh.get(f, 0):.0%}" for f in FAMILIES)
              + f" | {'yes' if r['separated'] else 'no'} | {r['peak']:.0f} | {r['cpu']:.0f} |")
    print("\nmean +- sample std over seeds:")
    print("| h (um) | bonding | HY_HY | HY_MA | MA_MA | peak (MPa) |")
    print("| --- | --- | --- | --- | --- | --- |")
    for h in a.sizes:
        for b in ("weak", "strong"):
            rs = [r for r in runs if r["h"] == h and r["bonding"] == b]
            cells = []
            for f in FAMILIES:
                x = np.array([r["shares"].get(f, 0.0) for r in rs]) * 100
                cells.append(f"{x.mean():.0f} ± {x.std(ddof=1) if len(x) > 1 else 0:.0f} %")
            pk = np.array([r["peak"] for r in rs])
            print(f"| {h * 1e6:g} | {b} | " + " | ".join(cells) + f" | {pk.mean():.0f} ± {pk.std(ddof=1):.0f} |")
    print("\nthe claim seed by seed (percentage points):")
    print("| h (um) | seed | HY_HY strong - weak | HY_MA weak - strong |")
    print("| --- | --- | --- | --- |")
    diffs = []
    for h in a.sizes:
        for s in a.seeds:
            w = next(r for r in runs if r["h"] == h and r["seed"] == s and r["bonding"] == "weak")
            st = next(r for r in runs if r["h"] == h and r["seed"] == s and r["bonding"] == "strong")
            d1 = 100 * (st["shares"].get("HY_HY", 0) - w["shares"].get("HY_HY", 0))
            d2 = 100 * (w["shares"].get("HY_MA", 0) - st["shares"].get("HY_MA", 0))
            diffs.append((d1, d2))
            print(f"| {h * 1e6:g} | {s} | {d1:+.0f} | {d2:+.0f} |")
    d = np.array(diffs)
    print(f"\nHY_HY strong - weak > 0 on {int((d[:, 0] > 0).sum())} of {len(d)} (seed, size); "
          f"HY_MA weak - strong > 0 on {int((d[:, 1] > 0).sum())} of {len(d)}")
    if a.json:
        Path(a.json).write_text(json.dumps(runs, indent=1) + "\n")
    if a.png:
        plot(runs, a.sizes, a.png)


def plot(runs, sizes, png):
    """Macro-crack shares per family: bars the mean over seeds, dots the seeds, lines
    joining each seed's weak and strong runs (the claim is the difference on one mesh)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(FAMILIES), figsize=(3.4 * len(FAMILIES), 3.4), sharey=True)
    for ax, fam in zip(axes, FAMILIES):
        for i, h in enumerate(sizes):
            for j, b in enumerate(("weak", "strong")):
                vals = [100 * r["shares"].get(fam, 0.0) for r in runs if r["h"] == h and r["bonding"] == b]
                ax.bar(3 * i + j, np.mean(vals), color=("C0" if b == "weak" else "C3"), alpha=0.5,
                       label=b if i == 0 else None)
            for s in sorted({r["seed"] for r in runs}):
                pair = [100 * next(r for r in runs if r["h"] == h and r["seed"] == s and r["bonding"] == b)
                        ["shares"].get(fam, 0.0) for b in ("weak", "strong")]
                ax.plot([3 * i, 3 * i + 1], pair, "k.-", lw=0.6, ms=4)
        ax.set_xticks([3 * i + 0.5 for i in range(len(sizes))])
        ax.set_xticklabels([f"h {h * 1e6:g} um" for h in sizes])
        ax.set_title(fam, fontsize=9)
    axes[0].set_ylabel("share of the macro-crack (%)")
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
