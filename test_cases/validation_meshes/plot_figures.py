#!/usr/bin/env python3
"""Figures of doc/validation_meshes.md from the results committed in results/:

    plot_figures.py [--collect BUILD/test_cases/validation_meshes] [--out doc/img]

--collect first copies the tables and curves of a test run (the long versions for the
bar, the cantilever and Hertz: ctest -R validation_meshes, labels long included) into
results/, then the figures are drawn from results/: bar_impact_convergence.png,
mesh_convergence.png (cantilever and Hertz), hertz_pressure.png, j2_cycle.png."""
import argparse
import shutil
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = Path(__file__).resolve().parent
RESULTS = HERE / "results"
L, C, RHO, V0, W = 1.0, 1000.0, 1000.0, 0.1, 0.05
J2_CASES = ("plane_stress", "plane_strain", "plane_strain_uniaxial_strain")


def collect(build):
    """Copy a test run's outputs into results/ (names as committed)."""
    b = Path(build)
    RESULTS.mkdir(exist_ok=True)
    copies = {"bar_impact.long/convergence.txt": "bar_impact_convergence.txt",
              "cantilever.long/convergence.txt": "cantilever_convergence.txt",
              "hertz.long/convergence.txt": "hertz_convergence.txt",
              "hertz.long/a40_pressure.txt": "hertz_a40_pressure.txt"}
    copies.update({f"bar_impact.long/n{n}_force.txt": f"bar_impact_n{n}_force.txt" for n in (25, 50, 100, 200)})
    copies.update({f"j2_cycle/{c}_curve.txt": f"j2_{c}_curve.txt" for c in J2_CASES})
    for src, dst in copies.items():
        shutil.copyfile(b / src, RESULTS / dst)
        print(f"{b / src} -> {RESULTS / dst}")


def bar_impact(out):
    conv = np.loadtxt(RESULTS / "bar_impact_convergence.txt", ndmin=2)
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.2))
    for n in conv[:, 0].astype(int):
        t, f = np.loadtxt(RESULTS / f"bar_impact_n{n}_force.txt", unpack=True)
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


def mesh_convergence(out):
    cant = np.loadtxt(RESULTS / "cantilever_convergence.txt", ndmin=2)
    hz = np.loadtxt(RESULTS / "hertz_convergence.txt", ndmin=2)
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.2))
    a1.loglog(cant[:, 0], cant[:, 1], "o-", label="tip deflection vs Timoshenko")
    a1.loglog(cant[:, 0], np.abs(cant[:, 1] - 0.0018), "s--", ms=4,
              label="minus the extrapolated limit 0.18 %: slope -2")
    a1.axhline(0.02, color="gray", ls=":", label="tolerance at 160 x 16 (2 %)")
    a1.set_xlabel("Q4 elements along the beam (H / h = elements / 10)")
    a1.set_ylabel("relative error")
    a1.set_title("cantilever, Q4, plane stress")
    a1.legend(fontsize=8)
    mesh = hz[:3]
    for k, lab, mk in ((2, "a, deformed positions", "o-"), (3, "p0, deformed positions", "s-"),
                       (4, "a, reference positions", "o--"), (5, "p0, reference positions", "s--")):
        a2.semilogy(mesh[:, 1], np.abs(mesh[:, k]), mk, label=lab)
    a2.axhline(0.03, color="gray", ls=":", label="tolerance (3 %)")
    a2.set_xlabel("a / element size at the contact (a / R = 0.041)")
    a2.set_ylabel("|relative error|")
    a2.set_title("Hertz, T3: mesh convergence")
    a2.legend(fontsize=8)
    ins = a2.inset_axes([0.62, 0.1, 0.35, 0.3])
    rows = hz[np.argsort(hz[:, 0])]
    rows = rows[[0, 1, -1]] if len(rows) > 3 else rows
    ins.plot(rows[:, 0], np.abs(rows[:, 2]) * 100, "o-", ms=3)
    ins.plot(rows[:, 0], np.abs(rows[:, 4]) * 100, "o--", ms=3)
    ins.set_xlabel("a / R", fontsize=7)
    ins.set_ylabel("|err a| %", fontsize=7)
    ins.tick_params(labelsize=6)
    fig.tight_layout()
    fig.savefig(Path(out, "mesh_convergence.png"), dpi=110)
    plt.close(fig)


def j2_cycle(out):
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.2))
    for c, mk in zip(J2_CASES, "os^"):
        step, eps, sxx, p, wp, ref = np.loadtxt(RESULTS / f"j2_{c}_curve.txt", unpack=True)
        lab = c.replace("_", " ").replace("uniaxial strain", "eps_yy = 0")
        a1.plot(eps * 1e3, ref / 1e6, "-", lw=1, label=f"{lab}: reference")
        a1.plot(eps[::3] * 1e3, sxx[::3] / 1e6, mk, ms=3, mfc="none", label=f"{lab}: fracas")
        a2.plot(step, wp / 1e6, "-", label=f"{lab}: plastic work (fracas)")
        a2.plot(step[::5], (2e8 * p + 0.5 * 2e11 * p ** 2)[::5] / 1e6, mk, ms=3, mfc="none",
                label=f"{lab}: sigma_0 p + H p^2 / 2")
    a1.set_xlabel("eps_xx (1e-3)")
    a1.set_ylabel("sigma_xx (MPa)")
    a1.set_title("J2, one Q4 element: tension-compression cycle")
    a1.legend(fontsize=7)
    a2.set_xlabel("step")
    a2.set_ylabel("plastic work (MJ per m)")
    a2.set_title("plastic dissipation")
    a2.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(Path(out, "j2_cycle.png"), dpi=110)
    plt.close(fig)


def hertz(out):
    x, f = np.loadtxt(RESULTS / "hertz_a40_pressure.txt", unpack=True)
    P = f.sum()
    R, E, NU = 0.05, 2e11, 0.3
    a = np.sqrt(4 * P * R / (np.pi * E / (1 - NU ** 2)))
    p0 = 2 * P / (np.pi * a)
    trib = np.gradient(x)
    fig, ax = plt.subplots(figsize=(6, 4))
    xs = np.linspace(-a, a, 400)
    ax.plot(xs / a, p0 * np.sqrt(1 - (xs / a) ** 2) / 1e9, "k-", label="Hertz (plane strain, same load)")
    ax.plot(x / a, f / trib / 1e9, "o", ms=3, label="fracas, a / 40: nodal force / tributary length")
    ax.set_xlabel("x / a (deformed positions)")
    ax.set_ylabel("pressure (GPa)")
    ax.set_xlim(-1.6, 1.6)
    ax.set_title("elastic cylinder on a rigid plane")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(Path(out, "hertz_pressure.png"), dpi=110)
    plt.close(fig)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--collect", metavar="BUILD_DIR", help="copy a test run's outputs into results/ first")
    p.add_argument("--out", default=str(HERE.parents[1] / "doc" / "img"))
    a = p.parse_args()
    if a.collect:
        collect(a.collect)
    Path(a.out).mkdir(parents=True, exist_ok=True)
    bar_impact(a.out)
    mesh_convergence(a.out)
    j2_cycle(a.out)
    hertz(a.out)


if __name__ == "__main__":
    main()
