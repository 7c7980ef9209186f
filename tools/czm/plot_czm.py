#!/usr/bin/python3
"""Pictures and measured errors of the cohesive laws for doc/czm.md.

Runs the validation decks test_cases/validation/czm_*/ with fracas (into a scratch folder,
or reads the runs already there) and draws, over the closed forms of fracas_tools.cohesive:

    doc/img/czm_<law>.png      mode I traction-opening curve and beta (mac mp3 mal th expo abp)
    doc/img/czm_mode_II.png    shear under preload: cohesion then Coulomb (MAC, EXPO)
    doc/img/czm_cyclic.png     opening/closing cycles: secant unloading (MAC, MP3)
    doc/img/czm_rate.png       viscous MAC at three opening rates vs the damage ODE
    doc/img/czm_glued_wall.png final state of the glued_wall demo, broken interfaces

and prints the Markdown table of the measured peak and energy errors per law.

usage: plot_czm.py [--fracas BIN] [--runs DIR] [--out DIR] [--rerun]
"""
import argparse
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
from fracas_tools.cohesive import mac_rate_curve  # noqa: E402
from fracas_tools.results import Results  # noqa: E402

V = ROOT / "test_cases" / "validation"


def load_gen(folder):
    """The gen.py module of a validation case folder."""
    from fracas_tools.scripts import load
    return load(folder / "gen.py")


def run_case(fracas, deck, out, rerun, extra=()):
    h5 = out / "OUTBOX" / "fracas.h5"
    if rerun or not h5.exists():
        subprocess.run([fracas, "-q", "--overwrite", *extra, "--output", str(out), str(deck)], check=True)
    return out


def mode_one(args, plt, table):
    gen = load_gen(V / "czm_mode_I")
    for name, (law_name, law) in gen.LAWS.items():
        out = run_case(args.fracas, V / "czm_mode_I" / name, args.runs / f"mode_I_{name}", args.rerun)
        run = Results(out, bodies=False)
        p = run.pair(2, 1)
        sig = -p.total("rn") / gen.GLUED
        un = p.mean("un")
        beta = p.mean("beta")
        dpk, smax = law.d_peak(1), law.peak(1)
        x = np.linspace(0.0, un[-1], 4000)
        fig, ax = plt.subplots(1, 2, figsize=(10, 4))
        ax[0].plot(x / dpk, law.sigma(x, 1) / smax, "k-", lw=1.0, label="closed form")
        ax[0].plot(un / dpk, sig / smax, "r.", ms=2.0, label="fracas (every step)")
        ax[0].set_xlabel("opening u / d_peak")
        ax[0].set_ylabel("traction / σ_max")
        ax[0].set_title(f"{law_name}: mode I traction–opening")
        ax[0].legend()
        ax[1].plot(x / dpk, law.beta(x, 1), "k-", lw=1.0, label="closed form")
        ax[1].plot(un / dpk, beta, "b.", ms=2.0, label="fracas β")
        ax[1].set_xlabel("opening u / d_peak")
        ax[1].set_ylabel("β")
        ax[1].set_title("adhesion intensity")
        ax[1].legend()
        fig.tight_layout()
        fig.savefig(args.out / f"czm_{name}.png", dpi=110)
        plt.close(fig)
        dmg = run.series["damage_dissipated"][-1]
        table.append((law_name, sig.max() / smax - 1.0, dmg / (law.nominal_energy(1) * gen.GLUED) - 1.0,
                      dmg / (law.damage(un[-1], 1) * gen.GLUED) - 1.0))


def mode_two(args, plt):
    gen = load_gen(V / "czm_mode_II")
    fig, axes = plt.subplots(1, len(gen.LAWS), figsize=(5 * len(gen.LAWS), 4))
    for ax, (name, (law_name, law)) in zip(axes, gen.LAWS.items()):
        out = run_case(args.fracas, V / "czm_mode_II" / name, args.runs / f"mode_II_{name}", args.rerun)
        run = Results(out, bodies=False)
        p = run.pair(2, 1)
        L = p.total("L")
        tau = -p.total("rt") / L
        ut = p.mean("ut")
        x = np.linspace(0.0, ut[-1], 4000)
        b = law.beta(x, 2)
        coh = b ** law.k * law.ct * x
        fr = gen.MU * (1.0 - b) * gen.PRELOAD
        dpk, tmax = law.d_peak(2), law.peak(2)
        ax.plot(x / dpk, (coh + fr) / tmax, "k-", lw=1.0, label="closed form β^k ct u + μ(1−β)p")
        ax.plot(x / dpk, coh / tmax, "k:", lw=0.8, label="cohesive part")
        ax.plot(x / dpk, fr / tmax, "k--", lw=0.8, label="friction part")
        ax.plot(ut / dpk, tau / tmax, "r.", ms=2.0, label="fracas")
        ax.axhline(gen.MU * gen.PRELOAD / tmax, color="g", lw=0.6)
        ax.set_xlabel("slip u / d_peak")
        ax.set_ylabel("shear traction / τ_max")
        ax.set_title(f"{law_name}, mode II, p = {gen.PRELOAD:.0e} Pa, μ = {gen.MU}", fontsize=10)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out / "czm_mode_II.png", dpi=110)
    plt.close(fig)


def cyclic(args, plt):
    gen = load_gen(V / "czm_cyclic")
    fig, axes = plt.subplots(1, len(gen.LAWS), figsize=(5 * len(gen.LAWS), 4))
    for ax, (name, (law_name, law)) in zip(axes, gen.LAWS.items()):
        out = run_case(args.fracas, V / "czm_cyclic" / name, args.runs / f"cyclic_{name}", args.rerun)
        run = Results(out, bodies=False)
        p = run.pair(2, 1)
        sig = -p.total("rn") / gen.GLUED
        un = p.mean("un")
        dpk, smax = law.d_peak(1), law.peak(1)
        x = np.linspace(0.0, un.max(), 4000)
        ax.plot(x / dpk, law.sigma(x, 1) / smax, "k-", lw=1.0, label="monotonic closed form")
        ax.plot(un / dpk, sig / smax, "r-", lw=0.8, label="fracas: 0→2→0.5→3→1→5 d_peak")
        ax.set_xlabel("opening u / d_peak")
        ax.set_ylabel("traction / σ_max")
        ax.set_title(f"{law_name}: secant unloading, damage resumed")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out / "czm_cyclic.png", dpi=110)
    plt.close(fig)


def rate(args, plt):
    gen = load_gen(V / "czm_rate")
    out = run_case(args.fracas, V / "czm_rate", args.runs / "rate", args.rerun)
    run = Results(out)
    law, u0 = gen.LAW, gen.U0
    s0 = np.sqrt(law.cn * law.w)
    fig, ax = plt.subplots(figsize=(6, 4.2))
    x = np.linspace(0.0, 4.0 * u0, 2000)
    from fracas_tools.cohesive import Law
    ax.plot(x / u0, Law.mac(law.cn, law.ct, 0.0, law.w).sigma(x, 1) / s0, "k-", lw=1.0, label="b = 0 (rate-free)")
    for i, (r, col) in enumerate(zip(gen.RATES, ("tab:blue", "tab:orange", "tab:red"))):
        p = run.pair(2 * i + 2, 2 * i + 1)
        v = run.V[-1, 2 * i + 1, 1]
        t, u, beta, sig = mac_rate_curve(law, lambda s: v * s, gen.STEPS * run.h, n=100000)
        ax.plot(u / u0, sig / s0, "-", color=col, lw=1.0, label=f"R = {r}: b β' = −(w − βY)⁻")
        ax.plot(p.mean("un") / u0, -p.total("rn") / gen.GLUED / s0, ".", color=col, ms=2.0)
    ax.set_xlim(0.0, 4.0)
    ax.set_xlabel("opening u / u0")
    ax.set_ylabel("traction / √(cn w)")
    ax.set_title("IQS_MAC_CZM, b > 0: lines ODE, dots fracas")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out / "czm_rate.png", dpi=110)
    plt.close(fig)


def wall(args, plt):
    deck = ROOT / "test_cases" / "examples" / "glued_wall"
    out = run_case(args.fracas, deck, args.runs / "glued_wall", args.rerun,
                   extra=("--set", "output_vtk_every=0"))
    from fracas_tools.datbox import read_case
    case = read_case(deck)
    run = Results(out)
    fig, axes = plt.subplots(1, 2, figsize=(11, 3.6), constrained_layout=True)
    for ax, isnap, title in ((axes[0], 0, "start: all joints glued"), (axes[1], -1, "end (t = 1 s)")):
        pos = run.pos[isnap]
        for k, body in enumerate(case.bodies):
            for ct in body.contactors:
                v = np.asarray(ct.vertices, dtype=float)
                c, s = np.cos(pos[k, 2]), np.sin(pos[k, 2])
                xy = v @ np.array([[c, s], [-s, c]]) + pos[k, :2]
                ax.fill(xy[:, 0], xy[:, 1], facecolor="0.85" if ct.color != "PUSHx" else "0.5",
                        edgecolor="k", lw=0.6)
        d = run.contacts[isnap]
        beta = d["internals"][:, 3]
        glue = np.isin(d["law"], [run.law_names.index(n) + 1 for n in ("glue1", "glue2")])
        sc = ax.scatter(d["point"][glue, 0], d["point"][glue, 1], c=beta[glue], cmap="RdYlGn", vmin=0, vmax=1,
                        s=18, zorder=3)
        br = d["broken"] == 1
        ax.plot(d["point"][br, 0], d["point"][br, 1], "kx", ms=6, zorder=4, label="broken (glued at start)")
        ax.set_aspect("equal")
        ax.set_xlim(-0.5, 2.0)
        ax.set_ylim(-0.35, 1.25)
        ax.set_title(title)
    fig.colorbar(sc, ax=axes, label="β at the cohesive contact points", shrink=0.9)
    axes[1].legend(loc="upper right")
    fig.savefig(args.out / "czm_glued_wall.png", dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fracas", default=os.environ.get("FRACAS_BIN", str(ROOT / "build" / "release" / "bin" / "fracas")))
    ap.add_argument("--runs", type=Path, default=Path("/tmp/fracas_czm_runs"))
    ap.add_argument("--out", type=Path, default=ROOT / "doc" / "img")
    ap.add_argument("--rerun", action="store_true", help="run again even if results exist")
    args = ap.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    args.runs.mkdir(parents=True, exist_ok=True)
    args.out.mkdir(parents=True, exist_ok=True)
    table = []
    mode_one(args, plt, table)
    mode_two(args, plt)
    cyclic(args, plt)
    rate(args, plt)
    wall(args, plt)
    print("| law | peak error | damage / (G L) − 1 | damage / closed form at u_end − 1 |")
    print("| --- | --- | --- | --- |")
    for name, pk, e1, e2 in table:
        print(f"| {name} | {pk:+.3%} | {e1:+.3%} | {e2:+.3%} |")


if __name__ == "__main__":
    main()
