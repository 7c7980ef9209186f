#!/usr/bin/env python3
"""Finite-strain neo-Hookean meshes (LMGC90's 'mater neoh_' models: kine_ large, form_
TotaL, MatLib's NEOHOOKEAN, W = lambda/2 (ln J)^2 - mu ln J + mu/2 (tr C - 3)) through
the whole solver, against closed forms.

1. Uniaxial stretch, plane strain, to 60 %: a distorted 4 x 4 mesh (Q4 and T3) of a unit
   square, massless (quasi-static, as LMGC90's decks with Umas = 0); left edge held in x,
   bottom edge in y, top edge driven in y, right edge free, 8 steps of theta = 1. The
   exact solution is homogeneous, F = diag(t, s): s the imposed stretch and t the root of
   P_xx = 0, mu t^2 + lambda ln(s t) - mu = 0; Cauchy sigma_yy = (mu s^2 + lambda ln(st)
   - mu) / (s t), sigma_zz = lambda ln(st) / (st), sigma_xx = sigma_xy = 0. Checked at
   steps 4 and 8: node positions (relative to the largest displacement) and Gauss-point
   stresses (relative to sigma_yy), tolerance 1e-8 (Newton's tolerance is 1e-12).
   (The small-strain law, measured and printed: lateral stretch 0.7429 against 0.7970,
   sigma_yy 6.59e6 against 5.80e6 Pa at s = 1.6.)
2. Objectivity: a free Q4 block (1 m, rho 1000, E 1e9) set spinning at omega = pi/2 rad/s
   (DOF.INI: the rigid-rotation velocity omega x r), no gravity, 1000 steps of 1 ms (a
   quarter turn), theta = 0.5. The exact motion is the rigid rotation up to the
   centrifugal stretch rho omega^2 R^2 / E = 1.2e-6 and the scheme's phase error
   (omega h)^2 / 12 = 2e-7: nodes within 1e-5 m of R(omega t) X0, Gauss-point Cauchy
   stress below 10 rho omega^2 R^2 = 1.2e4 Pa. The same block with the small-strain law
   (kine_ small) is printed for comparison: the velocity field omega x r has no linear
   strain, so nothing holds the nodes on their circles; they run off along their
   tangents (0.79 m from the rigid rotation at the quarter turn, the block 1.86 times
   its size, stress-free).
3. An element turned inside out: the stretch deck compressed through zero height in one
   step (s = -0.2): fracas stops with exit status 1 and names the body and the element
   ("turned inside out"), not with a floating-point trap or a factorization message.
   (Before the check: "iteration matrix ... not positive definite", and a trap in the
   debug build.)"""
import subprocess
import sys
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

from fracas_tools.valmesh import Case, distorted_grid, one_based, quads, rect_grid, triangles  # noqa: E402
from fracas_tools.valmesh import Checker, args, run_fracas  # noqa: E402

E, NU = 1.0e7, 0.3
MU = E / (2 * (1 + NU))
LAM = E * NU / ((1 + NU) * (1 - 2 * NU))
N = 4
STRETCH, STEPS, H = 1.6, 8, 1.0


def lateral(s):
    """t with P_xx = 0 at F = diag(t, s), plane strain."""
    return brentq(lambda t: MU * t * t + LAM * np.log(s * t) - MU, 0.2, 1.5, xtol=1e-15)


def cauchy(t, s):
    j = s * t
    return np.array([0.0, (MU * s * s + LAM * np.log(j) - MU) / j, 0.0, LAM * np.log(j) / j])


def build_stretch(case_dir, kind, kinematic="large", stretch=STRETCH, steps=STEPS):
    x = distorted_grid(N, 1.0, seed=5, amplitude=0.25)
    elements = quads(N, N) if kind == "Q4" else triangles(N, N)
    case = Case(gravity=(0.0, 0.0))
    case.add_material("RUBBR", 0.0, "ELAS", young=E, poisson=NU)
    if kinematic == "large":
        case.add_model("M2D" + kind, kind + "xxx", kinematic="large", formulation="TotaL", material="neoh_",
                       external="MatL_")
    else:
        case.add_model("M2D" + kind, kind + "xxx")
    b = case.add_mesh_body(x, one_based(elements), model="M2D" + kind, material="RUBBR")
    v = (stretch - 1.0) / (steps * H)
    for k, (px, py) in enumerate(x):
        if px < 1e-12:
            b.impose_velocity([k + 1], 1, ct=0.0)
        if py < 1e-12:
            b.impose_velocity([k + 1], 2, ct=0.0)
        if py > 1.0 - 1e-12:
            b.impose_velocity([k + 1], 2, ct=v)
    case.run.set(time_step=H, number_of_steps=steps, theta=1.0, plane="strain", newton_tolerance=1e-12,
                 newton_max_iterations=30, output_dof_every=steps, output_hdf5_every=1)
    case.write(case_dir)
    return x


OMEGA, RHO, E_SPIN, H_SPIN, STEPS_SPIN = np.pi / 2, 1000.0, 1.0e9, 1.0e-3, 1000


def build_spin(case_dir, kinematic):
    x = rect_grid(N, N, 1.0, 1.0, -0.5, -0.5)
    case = Case(gravity=(0.0, 0.0))
    case.add_material("BLOCK", RHO, "ELAS", young=E_SPIN, poisson=NU)
    if kinematic == "large":
        case.add_model("M2DQ4", "Q4xxx", kinematic="large", formulation="TotaL", material="neoh_", external="MatL_")
    else:
        case.add_model("M2DQ4", "Q4xxx")
    b = case.add_mesh_body(x, one_based(quads(N, N)), model="M2DQ4", material="BLOCK")
    b.v0[:] = OMEGA * np.column_stack([-x[:, 1], x[:, 0]])
    case.run.set(time_step=H_SPIN, number_of_steps=STEPS_SPIN, theta=0.5, plane="strain", newton_tolerance=1e-10,
                 newton_max_iterations=30, output_dof_every=STEPS_SPIN, output_hdf5_every=STEPS_SPIN)
    case.write(case_dir)
    return x


def main():
    a = args(__doc__)
    ck = Checker("validation_meshes.neohooke")
    for kind in ("Q4", "T3"):
        name = f"stretch_{kind}"
        case = Path(a.out, name)
        x = build_stretch(case, kind)
        with run_fracas(a.fracas, case) as run:
            for step in (4, 8):
                snap = run.snapshot(step - 1)
                ck.true(f"{name}: snapshot {step - 1} is step {step}", snap.step == step, snap.step, step)
                s = 1.0 + (STRETCH - 1.0) * step / STEPS
                t = lateral(s)
                x_ex = x * np.array([t - 1.0, s - 1.0])
                sig = cauchy(t, s)
                ck.at_most(f"{name}, step {step} (stretch {s:.2f}, t {t:.6f}): max |X - X_exact| / max |X_exact|",
                           np.abs(snap.mesh["X"] - x_ex).max() / np.abs(x_ex).max(), 1e-8)
                ck.at_most(f"{name}, step {step}: max |sigma - sigma_exact| / sigma_yy",
                           np.abs(snap.mesh["gauss_points"][:, 0:4] - sig).max() / sig[1], 1e-8)
        # the same stretch with the small-strain law, for the record
        small = Path(a.out, name + "_small_strain")
        build_stretch(small, kind, kinematic="small")
        with run_fracas(a.fracas, small) as run:
            snap = run.snapshot(STEPS - 1)
        t = lateral(STRETCH)
        xr = snap.mesh["X"][np.argmax(x[:, 0] + x[:, 1])]
        print(f"  (small strain, {kind}: lateral stretch {1 + xr[0]:.4f} against {t:.4f} at finite strain, "
              f"sigma_yy {snap.mesh['gauss_points'][:, 1].mean():.4e} against {cauchy(t, STRETCH)[1]:.4e})")
    for kinematic in ("large", "small"):
        name = f"spin_{kinematic}"
        case = Path(a.out, name)
        x = build_spin(case, kinematic)
        with run_fracas(a.fracas, case) as run:
            snap = run.snapshot(-1)
        ang = OMEGA * STEPS_SPIN * H_SPIN
        r = np.array([[np.cos(ang), -np.sin(ang)], [np.sin(ang), np.cos(ang)]])
        dev = np.abs(snap.mesh["X"] - (x @ r.T - x)).max()
        smax = np.abs(snap.mesh["gauss_points"][:, 0:4]).max()
        if kinematic == "large":
            ck.true(f"{name}: last snapshot at step {STEPS_SPIN}", snap.step == STEPS_SPIN, snap.step, STEPS_SPIN)
            ck.at_most(f"{name}: quarter turn, max |X - (R - I) X0| (m)", dev, 1e-5)
            ck.at_most(f"{name}: max |sigma| (Pa)", smax, 10 * RHO * OMEGA ** 2 * 0.5)
        else:
            print(f"  (small strain, the same spin: max |X - (R - I) X0| = {dev:.3e} m, max |sigma| = {smax:.3e} Pa)")
    inverted = Path(a.out, "inverted")
    build_stretch(inverted, "Q4", stretch=-0.2, steps=1)
    r = subprocess.run([a.fracas, "-q", "--overwrite", str(inverted)], capture_output=True, text=True)
    ck.true("compressed through zero height: exit 1, 'element ... turned inside out'",
            r.returncode == 1 and "turned inside out" in r.stderr, f"exit {r.returncode}", "exit 1")
    sys.exit(ck.finish())


if __name__ == "__main__":
    main()
