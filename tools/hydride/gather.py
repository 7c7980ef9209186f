#!/usr/bin/python3
"""Gather a hydrided-plate campaign (campaign.py, or the SLURM array of slurm_array.sh)
into one table and a few figures.

    build/release/bin/fracas-python tools/hydride/gather.py ROOT [--out DIR] [--pictures SEED]

Reads ROOT/*/summary.json (and the runs' files for the curves and pictures), writes in
DIR (default ROOT):

    cases.csv             one row per case
    summary.md            Markdown tables: per bonding x element size the mean +-
                          standard deviation over seeds of the shares, energies and
                          runtimes; the paper's claim as
                          numbers (strong - weak share through hydrides, weak - strong
                          share along interfaces, per seed)
    hydride_shares.png    macro-crack shares per family, bonding x element size (bars: mean,
                          dots: seeds)
    hydride_curves.png    nominal stress - strain of every case
    hydride_energy.png    energy split (plastic, damage per family, friction) at the end
    hydride_cracks.png    final crack paths, weak | strong, for one seed at each element size
    hydride_scaling.png   processor time per step against the number of elements
"""
import argparse
import csv
import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
from fracas_tools.scripts import load  # noqa: E402
post = load(HERE / "hydride_post.py")

FAMILIES = list(post.FAMILY_LABEL)
BOND_COLOR = {"weak": "#f08c00", "strong": "#1f3fbf"}


def load(root):
    rows = []
    for p in sorted(Path(root).glob("*/summary.json")):
        s = json.loads(p.read_text())
        s["dir"] = str(p.parent)
        rows.append(s)
    if not rows:
        raise SystemExit(f"no */summary.json under {root}")
    return rows


def flat(s):
    c, e = s["crack"], s["energies"]
    r = dict(case=Path(s["dir"]).name, bonding=s["bonding"], h_um=s["h"] * 1e6, seed=s["seed"],
             elements=s["elements"], steps=s["steps"], separated=int(c["separated"]),
             reach=c.get("reach", 0.0), crack_um=c["path_length"] * 1e6)
    for f in FAMILIES:
        r[f"share_{f}"] = c["shares"][f]
    r.update(microcracks=c["microcracks"], microcrack_edges=c["microcrack_edges"],
             broken_edges=c["broken_edges"], peak_MPa=s["peak_stress"] / 1e6,
             strain_at_peak=s["strain_at_peak"], work=e["work_supports"], plastic=e["plastic"],
             damage=e["damage"])
    for f in FAMILIES:
        r[f"damage_{f}"] = e["damage_per_family"][f]
    r.update(friction=e["friction_and_numerical"], kinetic=e["kinetic"], elastic=e["elastic"],
             balance_rel=e["relative_balance_error"], cpu_s=s.get("cpu_seconds_process", s["cpu_seconds"]),
             step_cpu_s=s["cpu_seconds"], steps_wall_s=s.get("steps_wall_seconds", float("nan")), wall_s=s.get("wall_seconds", float("nan")),
             load=s.get("load_average", float("nan")), sweeps=s.get("sweeps", float("nan")))
    return r


def groups(rows):
    out = {}
    for r in rows:
        out.setdefault((r["bonding"], r["h_um"]), []).append(r)
    return dict(sorted(out.items(), key=lambda kv: (-kv[0][1], kv[0][0] != "weak")))


def pm(values, fmt="{:.0f}", scale=1.0):
    v = np.asarray(values, float) * scale
    return (fmt + " ± " + fmt).format(v.mean(), v.std(ddof=1) if len(v) > 1 else 0.0)


def markdown(rows):
    g = groups(rows)
    out = ["| bonding | h (µm) | seeds | elements | across | through hydrides (HY_HY) | along interfaces (HY_MA) "
           "| through matrix (MA_MA) | microcracks (clusters) | broken edges off the path | peak stress (MPa) "
           "| CPU per case (s) |", "|" + " --- |" * 12]
    for (b, h), rs in g.items():
        out.append(f"| {b} | {h:.2g} | {len(rs)} | {np.mean([r['elements'] for r in rs]):.0f} | "
                   f"{sum(r['separated'] for r in rs)}/{len(rs)} | "
                   + " | ".join(pm([r[f'share_{f}'] for r in rs], '{:.0f} %', 100) for f in FAMILIES)
                   + f" | {pm([r['microcracks'] for r in rs])} | {pm([r['microcrack_edges'] for r in rs])} | "
                   f"{pm([r['peak_MPa'] for r in rs])} | {pm([r['cpu_s'] for r in rs])} |")
    out += ["", "Energy at the end (µJ per metre of thickness, 1e-6 J/m; mean over seeds):", "",
            "| bonding | h (µm) | work of the drives | plastic | damage MA_MA | damage HY_HY | damage HY_MA "
            "| friction + numerical | kinetic | elastic | balance error / work |", "|" + " --- |" * 11]
    for (b, h), rs in g.items():
        m = lambda k: np.mean([r[k] for r in rs]) * 1e6  # noqa: E731
        out.append(f"| {b} | {h:.2g} | {m('work'):.0f} | {m('plastic'):.0f} | {m('damage_MA_MA'):.1f} | "
                   f"{m('damage_HY_HY'):.1f} | {m('damage_HY_MA'):.1f} | {m('friction'):.1f} | {m('kinetic'):.1f} | "
                   f"{m('elastic'):.1f} | {max(r['balance_rel'] for r in rs):.1e} (max) |")
    out += ["", "Runtime (processor time of the fracas process; mean ± standard deviation over seeds):", "",
            "| bonding | h (µm) | elements | steps | processor time per case (s) | per element and step (s) "
            "| NLGS sweeps per step | wall time (s) |", "|" + " --- |" * 8]
    for (b, h), rs in g.items():
        per = [r["cpu_s"] / (r["elements"] * r["steps"]) for r in rs]
        out.append(f"| {b} | {h:.2g} | {np.mean([r['elements'] for r in rs]):.0f} | "
                   f"{np.mean([r['steps'] for r in rs]):.0f} | {pm([r['cpu_s'] for r in rs])} | "
                   f"{np.mean(per):.2e} | {pm([r['sweeps'] for r in rs])} | {pm([r['wall_s'] for r in rs])} |")
    # the claim, seed by seed (same microstructure for both bondings)
    out += ["", "The paper's claim, seed by seed (same hydrides, same mesh; percentage points):", "",
            "| h (µm) | seed | HY_HY share strong − weak | HY_MA share weak − strong |", "| --- | --- | --- | --- |"]
    for h in sorted({r["h_um"] for r in rows}, reverse=True):
        for seed in sorted({r["seed"] for r in rows}):
            pair = {r["bonding"]: r for r in rows if r["h_um"] == h and r["seed"] == seed}
            if "weak" in pair and "strong" in pair:
                out.append(f"| {h:.2g} | {seed} | {100 * (pair['strong']['share_HY_HY'] - pair['weak']['share_HY_HY']):+.0f} | "
                           f"{100 * (pair['weak']['share_HY_MA'] - pair['strong']['share_HY_MA']):+.0f} |")
    return "\n".join(out) + "\n"


def claim(rows):
    """Per element size: the seed-by-seed differences (strong - weak HY_HY share, weak -
    strong HY_MA share): mean, standard deviation, minimum."""
    res = {}
    for h in sorted({r["h_um"] for r in rows}, reverse=True):
        dh, di = [], []
        for seed in sorted({r["seed"] for r in rows}):
            pair = {r["bonding"]: r for r in rows if r["h_um"] == h and r["seed"] == seed}
            if "weak" in pair and "strong" in pair:
                dh.append(pair["strong"]["share_HY_HY"] - pair["weak"]["share_HY_HY"])
                di.append(pair["weak"]["share_HY_MA"] - pair["strong"]["share_HY_MA"])
        if dh:
            res[h] = dict(seeds=len(dh), through_hydrides=(np.mean(dh), np.std(dh, ddof=1) if len(dh) > 1 else 0,
                                                         np.min(dh)),
                          along_interfaces=(np.mean(di), np.std(di, ddof=1) if len(di) > 1 else 0, np.min(di)))
    return res


def figures(rows, out, picture_seed):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    g = groups(rows)
    # shares
    fig, ax = plt.subplots(figsize=(7.5, 3.6))
    keys = list(g)
    width = 0.8 / len(keys)
    for k, key in enumerate(keys):
        rs = g[key]
        for i, f in enumerate(FAMILIES):
            v = np.array([r[f"share_{f}"] for r in rs]) * 100
            x = i + (k - (len(keys) - 1) / 2) * width
            ax.bar(x, v.mean(), width * 0.9, color=BOND_COLOR[key[0]], alpha=0.45 if key[1] < max(
                kk[1] for kk in keys) else 0.85, label=f"{key[0]}, h {key[1]:.2g} µm" if i == 0 else None)
            ax.plot(np.full(len(v), x), v, "k.", ms=4)
    ax.set_xticks(range(len(FAMILIES)), [f"{post.FAMILY_LABEL[f]}\n({f})" for f in FAMILIES], fontsize=8)
    ax.set_ylabel("share of the macro-crack (%)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "hydride_shares.png", dpi=150)
    plt.close(fig)
    # curves
    sizes = sorted({r["h_um"] for r in rows}, reverse=True)
    fig, axes = plt.subplots(1, len(sizes), figsize=(4 * len(sizes), 3.2), squeeze=False, sharey=True)
    for ax, h in zip(axes[0], sizes):
        for r in rows:
            if r["h_um"] != h:
                continue
            fd = post.force_displacement(post.PlateRun(Path(r["dir"])))
            ax.plot(fd["strain"] * 100, fd["stress"] / 1e6, color=BOND_COLOR[r["bonding"]], lw=0.8,
                    label=r["bonding"] if r["seed"] == min(rr["seed"] for rr in rows) else None)
        ax.set_title(f"h {h:.2g} µm", fontsize=9)
        ax.set_xlabel("nominal strain (%)")
        ax.legend(fontsize=7)
    axes[0][0].set_ylabel("nominal stress (MPa)")
    fig.tight_layout()
    fig.savefig(out / "hydride_curves.png", dpi=150)
    plt.close(fig)
    # energies
    fig, ax = plt.subplots(figsize=(7, 3.4))
    parts = [("plastic", "plastic work", "#7f7f7f"), ("damage_MA_MA", "damage MA_MA", post.FAMILY_COLOR["MA_MA"]),
             ("damage_HY_HY", "damage HY_HY", post.FAMILY_COLOR["HY_HY"]),
             ("damage_HY_MA", "damage HY_MA", post.FAMILY_COLOR["HY_MA"]),
             ("friction", "friction + numerical", "#2ca02c"), ("kinetic", "kinetic", "#bcbd22"),
             ("elastic", "elastic", "#17becf")]
    for k, key in enumerate(keys):
        rs = g[key]
        bottom = 0.0
        for name, label, color in parts:
            v = np.mean([r[name] for r in rs]) * 1e6
            ax.bar(k, v, 0.6, bottom=bottom, color=color, label=label if k == 0 else None)
            bottom += v
    ax.set_xticks(range(len(keys)), [f"{b}\nh {h:.2g} µm" for b, h in keys], fontsize=8)
    ax.set_ylabel("energy at the end (µJ/m)")
    ax.legend(fontsize=7, bbox_to_anchor=(1.02, 1), loc="upper left")
    fig.tight_layout()
    fig.savefig(out / "hydride_energy.png", dpi=150)
    plt.close(fig)
    # scaling: processor time per step and per element-step
    fig, ax = plt.subplots(figsize=(4.5, 3.4))
    for b in ("weak", "strong"):
        rs = [r for r in rows if r["bonding"] == b]
        ax.loglog([r["elements"] for r in rs], [r["cpu_s"] / r["steps"] for r in rs], "o",
                  color=BOND_COLOR[b], label=b)
    ax.set_xlabel("elements")
    ax.set_ylabel("processor time per step (s)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "hydride_scaling.png", dpi=150)
    plt.close(fig)
    # pictures: weak | strong for one seed, a row per element size
    fig, axes = plt.subplots(len(sizes), 2, figsize=(9, 4.5 * len(sizes)), squeeze=False)
    for i, h in enumerate(sizes):
        for j, b in enumerate(("weak", "strong")):
            r = [r for r in rows if r["h_um"] == h and r["bonding"] == b and r["seed"] == picture_seed]
            ax = axes[i][j]
            if not r:
                ax.axis("off")
                continue
            run = post.PlateRun(Path(r[0]["dir"]))
            c = post.macro_crack(run)
            post.draw(run, ax, c, legend=(i == 0 and j == 1),
                      title=f"{b} bonding, seed {picture_seed}, h {h:.2g} µm\n" + ", ".join(
                          f"{f} {100 * c['shares'][f]:.0f} %" for f in FAMILIES))
    fig.tight_layout()
    fig.savefig(out / "hydride_cracks.png", dpi=130)
    plt.close(fig)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("root")
    p.add_argument("--out")
    p.add_argument("--pictures", type=int, default=1, help="seed of the crack pictures")
    p.add_argument("--no-figures", action="store_true")
    a = p.parse_args(argv)
    out = Path(a.out or a.root)
    out.mkdir(parents=True, exist_ok=True)
    rows = [flat(s) | {"dir": s["dir"]} for s in load(a.root)]
    with open(out / "cases.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=[k for k in rows[0] if k != "dir"], extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    text = markdown(rows)
    (out / "summary.md").write_text(text)
    print(text)
    for h, c in claim(rows).items():
        print(f"h {h:.2g} µm, {c['seeds']} seeds: strong - weak through hydrides "
              f"{100 * c['through_hydrides'][0]:+.0f} ± {100 * c['through_hydrides'][1]:.0f} points (min "
              f"{100 * c['through_hydrides'][2]:+.0f}); weak - strong along interfaces "
              f"{100 * c['along_interfaces'][0]:+.0f} ± {100 * c['along_interfaces'][1]:.0f} (min "
              f"{100 * c['along_interfaces'][2]:+.0f})")
    if not a.no_figures:
        figures(rows, out, a.pictures)
    return 0


if __name__ == "__main__":
    from fracas_tools.cli import run_main  # bad input: a message, not a traceback
    sys.exit(run_main(main, "gather.py"))
