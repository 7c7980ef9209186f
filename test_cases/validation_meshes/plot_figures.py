#!/usr/bin/env python3
"""Figures of doc/validation_meshes.md from the outputs the validation_meshes tests
leave in the build tree:

    plot_figures.py BUILD/test_cases/validation_meshes doc/img

(run the tests first; the bar impact uses the long version's 200-element run when
it is there)."""
import sys
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

L, C, RHO, V0, W = 1.0, 1000.0, 1000.0, 0.1, 0.05


def bar_impact(build, out):
    runs = [d for d in ("bar_impact.long", "bar_impact") if Path(build, d, "convergence.txt").exists()]
    if not runs:
        return
    base = Path(build, runs[0])
    conv = np.loadtxt(base / "convergence.txt", ndmin=2)
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.2))
    for n in conv[:, 0].astype(int):
        t, f = np.loadtxt(base / f"n{n}_force.txt", unpack=True)
        a1.plot(t / (2 * L / C), f / (RHO * C * V0 * W), lw=1, label=f"{n} elements")
    a1.plot([0, 0, 1, 1, 1.3], [0, 1, 1, 0, 0], "k--", lw=1.2, label="1D wave: rho c v0 for 2L/c")
    a1.set_xlabel("t / (2 L / c)")
    a1.set_ylabel("contact force / (rho c v0 w)")
    a1.set_title("Q4 bar hitting a rigid wall: contact force")
    a1.legend(fontsize=8)
    for k, lab in ((1, "contact duration"), (2, "mean contact stress"), (3, "rebound velocity"),
                   (4, "plateau contact stress")):
        a2.loglog(conv[:, 0], conv[:, k], "o-", label=lab)
    a2.axhline(0.02, color="gray", ls=":", label="tolerance at 100 elements (2 %)")
    a2.set_xlabel("elements along the bar")
    a2.set_ylabel("relative error")
    a2.set_title("convergence")
    a2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(Path(out, "bar_impact_convergence.png"), dpi=110)
    plt.close(fig)


def j2_cycle(build, out):
    base = Path(build, "j2_cycle")
    if not (base / "plane_stress_curve.txt").exists():
        return
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.2))
    for plane, mk in (("stress", "o"), ("strain", "s")):
        step, eps, sxx, p, wp, ref = np.loadtxt(base / f"plane_{plane}_curve.txt", unpack=True)
        a1.plot(eps * 1e3, ref / 1e6, "-", lw=1, label=f"plane {plane}: reference")
        a1.plot(eps[::3] * 1e3, sxx[::3] / 1e6, mk, ms=3, mfc="none", label=f"plane {plane}: fracas")
        a2.plot(step, wp / 1e6, "-", label=f"plane {plane}: plastic work (fracas)")
        a2.plot(step[::5], (2e8 * p + 0.5 * 2e11 * p ** 2)[::5] / 1e6, mk, ms=3, mfc="none",
                label=f"plane {plane}: sigma_0 p + H p^2 / 2")
    a1.set_xlabel("eps_xx (1e-3)")
    a1.set_ylabel("sigma_xx (MPa)")
    a1.set_title("J2, one Q4 element: tension-compression cycle")
    a1.legend(fontsize=8)
    a2.set_xlabel("step")
    a2.set_ylabel("plastic work (MJ per m)")
    a2.set_title("plastic dissipation")
    a2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(Path(out, "j2_cycle.png"), dpi=110)
    plt.close(fig)


def hertz(build, out):
    base = next((Path(build, d) for d in ("hertz.long", "hertz") if Path(build, d, "pressure.txt").exists()), None)
    if base is None:
        return
    x, f = np.loadtxt(base / "pressure.txt", unpack=True)
    P = f.sum()
    R, E, NU = 0.05, 2e11, 0.3
    a = np.sqrt(4 * P * R / (np.pi * E / (1 - NU ** 2)))
    p0 = 2 * P / (np.pi * a)
    trib = np.gradient(x)
    fig, ax = plt.subplots(figsize=(6, 4))
    xs = np.linspace(-a, a, 400)
    ax.plot(xs / a, p0 * np.sqrt(1 - (xs / a) ** 2) / 1e9, "k-", label="Hertz (plane strain, same load)")
    ax.plot(x / a, f / trib / 1e9, "o", ms=3, label="fracas: nodal force / tributary length")
    ax.set_xlabel("x / a")
    ax.set_ylabel("pressure (GPa)")
    ax.set_xlim(-1.6, 1.6)
    ax.set_title("elastic cylinder on a rigid plane")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(Path(out, "hertz_pressure.png"), dpi=110)
    plt.close(fig)


def main():
    build, out = sys.argv[1], sys.argv[2]
    Path(out).mkdir(parents=True, exist_ok=True)
    bar_impact(build, out)
    j2_cycle(build, out)
    hertz(build, out)


if __name__ == "__main__":
    main()
