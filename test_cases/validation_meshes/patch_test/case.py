#!/usr/bin/env python3
"""Patch test through the whole solver: a distorted T3 or Q4 mesh of a square whose
nodes all start with the affine velocity v = L x and whose boundary nodes are driven at
it. The exact solution of the discrete problem is the affine motion X = L x t, V = L x
(the internal forces of a uniform stress vanish at interior nodes, so nothing
accelerates) with the uniform strain sym(L) t and stress D sym(L) t at every Gauss
point. Measured: the largest deviation relative to the largest exact value, after 50
steps of the theta-scheme, from fracas.h5 (full precision); tolerance 1e-10. The
executable's GPV.OUT is checked against the same exact stress to its 7 printed
digits."""
import sys
from pathlib import Path

import numpy as np

from fracas_tools import valmesh  # noqa: E402
from fracas_tools.valmesh import Case, one_based, quads, triangles  # noqa: E402
from fracas_tools.valmesh import Checker, args, run_fracas  # noqa: E402
from fracas_tools.outbox import read_gpv  # noqa: E402

E, NU, RHO = 2.0e11, 0.3, 7800.0
L = np.array([[2.0e-3, 1.0e-3], [-0.5e-3, -1.0e-3]])   # velocity gradient (1/s)
SIZE, N = 0.1, 4
H, STEPS = 1.0e-5, 50
STATIC_H = 1.0e3


def distorted_grid(seed):
    # Coordinates on a 1e-4 grid: the affine data L x then has few digits and is
    # written exactly in the deck's 8-digit fields (DOF.INI, DRV_DOF.DAT).
    return valmesh.distorted_grid(N, SIZE, seed, 0.3)


def exact_stress(eps, plane):
    exx, eyy, gxy = eps
    if plane == "strain":
        lam = E * NU / ((1 + NU) * (1 - 2 * NU))
        mu = E / (2 * (1 + NU))
        tr = exx + eyy
        return np.array([lam * tr + 2 * mu * exx, lam * tr + 2 * mu * eyy, mu * gxy, lam * tr]), 0.0
    c = E / (1 - NU ** 2)
    return (np.array([c * (exx + NU * eyy), c * (eyy + NU * exx), E / (2 * (1 + NU)) * gxy, 0.0]),
            -NU / (1 - NU) * (exx + eyy))


def build_static(case_dir, kind, plane, rho=RHO, steps=1):
    """The static patch test: every node starts at rest; the boundary nodes are
    driven at V = L x / (steps h) for steps of h = 1000 s / steps with theta = 1, so
    their displacement is L x (1 s) at the end; the interior nodes are free, and each
    step's (M / h^2 + K) X = ... is a static solve up to rho SIZE^2 / (E h^2) = 4e-16
    (with h = 1 s the inertia left 2e-11, measured): the interior nodes must land on
    the affine field, found by the stiffness alone. With rho = 0 (a massless,
    quasi-static mesh, as LMGC90's decks with Umas = 0) there is no inertia at all."""
    x = distorted_grid(seed=11)
    elements = quads(N, N) if kind == "Q4" else triangles(N, N)
    case = Case(gravity=(0.0, 0.0))
    case.add_material("STEEL", rho, "ELAS", young=E, poisson=NU)
    case.add_model("M2D" + kind, kind + "xxx")
    b = case.add_mesh_body(x, one_based(elements), model="M2D" + kind, material="STEEL")
    v = x @ L.T / STATIC_H
    for k, (px, py) in enumerate(x):
        if min(px, py) < 1e-12 or max(px, py) > SIZE - 1e-12:
            for dof in (1, 2):
                b.impose_velocity([k + 1], dof, ct=v[k, dof - 1])
    case.run.set(time_step=STATIC_H / steps, number_of_steps=steps, theta=1.0, plane=plane, output_dof_every=steps,
                 output_hdf5_every=1)
    case.write(case_dir)
    return x


def build(case_dir, kind, plane, mass):
    x = distorted_grid(seed=7)
    elements = quads(N, N) if kind == "Q4" else triangles(N, N)
    case = Case(gravity=(0.0, 0.0))
    case.add_material("STEEL", RHO, "ELAS", young=E, poisson=NU)
    case.add_model("M2D" + kind, kind + "xxx", mass_storage=mass)
    b = case.add_mesh_body(x, one_based(elements), model="M2D" + kind, material="STEEL")
    b.v0[:] = x @ L.T
    for k, (px, py) in enumerate(x):
        if min(px, py) < 1e-12 or max(px, py) > SIZE - 1e-12:
            for dof in (1, 2):
                b.impose_velocity([k + 1], dof, ct=b.v0[k, dof - 1])
    case.run.set(time_step=H, number_of_steps=STEPS, theta=0.5, plane=plane, output_dof_every=STEPS,
                 output_hdf5_every=STEPS)
    case.write(case_dir)
    return x


def main():
    a = args(__doc__)
    ck = Checker("validation_meshes.patch_test")
    for kind, plane, mass in (("T3", "strain", "lump_"), ("Q4", "strain", "coher"),
                              ("T3", "stress", "coher"), ("Q4", "stress", "lump_")):
        name = f"{kind}_plane_{plane}_{mass}"
        case = Path(a.out, name)
        x = build(case, kind, plane, mass)
        t = STEPS * H
        with run_fracas(a.fracas, case) as run:
            snap = run.snapshot(-1)
        ck.true(f"{name}: last snapshot at step {STEPS}", snap.step == STEPS, snap.step, STEPS)
        xs, vs, gp = snap.mesh["X"], snap.mesh["V"], snap.mesh["gauss_points"]
        x_ex, v_ex = x @ L.T * t, x @ L.T
        eps = np.array([L[0, 0], L[1, 1], L[0, 1] + L[1, 0]]) * t
        sig, ezz = exact_stress(eps, plane)
        ck.at_most(f"{name}: max |X - L x t| / max |L x t|", np.abs(xs - x_ex).max() / np.abs(x_ex).max(), 1e-10)
        ck.at_most(f"{name}: max |V - L x| / max |L x|", np.abs(vs - v_ex).max() / np.abs(v_ex).max(), 1e-10)
        ck.at_most(f"{name}: {len(gp)} Gauss pts, max |sig - D eps| / max |D eps|",
                   np.abs(gp[:, 0:4] - sig).max() / np.abs(sig).max(), 1e-10)
        strain_ex = np.array([eps[0], eps[1], eps[2], ezz])
        ck.at_most(f"{name}: max |eps - sym(L) t| / max |sym(L) t|",
                   np.abs(gp[:, 4:8] - strain_ex).max() / np.abs(strain_ex).max(), 1e-10)
        # The executable's GPV.OUT at its printed digits.
        gpv = read_gpv(Path(case, "OUTBOX", "GPV.OUT.1"))
        # stress lines (the strain line follows each)
        vals = np.array([row for b in gpv.bodies for e in b.elements for row in e.rows[0::2]])
        ck.at_most(f"{name}: GPV.OUT stress (7 digits) vs D eps",
                   np.abs(vals - sig).max() / np.abs(sig).max(), 1e-6)
    for kind, plane in (("T3", "strain"), ("Q4", "stress")):
        name = f"{kind}_static_plane_{plane}"
        case = Path(a.out, name)
        x = build_static(case, kind, plane)
        with run_fracas(a.fracas, case) as run:
            snap = run.snapshot(-1)
        xs, gp = snap.mesh["X"], snap.mesh["gauss_points"]
        x_ex = x @ L.T
        eps = np.array([L[0, 0], L[1, 1], L[0, 1] + L[1, 0]])
        sig, _ = exact_stress(eps, plane)
        ck.at_most(f"{name}: max |X - L x| / max |L x|", np.abs(xs - x_ex).max() / np.abs(x_ex).max(), 1e-10)
        ck.at_most(f"{name}: max |sig - D eps| / max |D eps|", np.abs(gp[:, 0:4] - sig).max() / np.abs(sig).max(),
                   1e-10)
    # Massless (density 0): static at every step, to round-off (1e-12).
    for kind, plane in (("Q4", "strain"), ("T3", "stress")):
        name = f"{kind}_massless_plane_{plane}"
        case = Path(a.out, name)
        x = build_static(case, kind, plane, rho=0.0, steps=4)
        eps1 = np.array([L[0, 0], L[1, 1], L[0, 1] + L[1, 0]])
        with run_fracas(a.fracas, case) as run:
            for step in (2, 4):
                snap = run.snapshot(step - 1)
                ck.true(f"{name}: snapshot {step - 1} is step {step}", snap.step == step, snap.step, step)
                frac = step / 4
                x_ex = x @ L.T * frac
                sig, _ = exact_stress(eps1 * frac, plane)
                ck.at_most(f"{name}, step {step}: max |X - L x t| / max |L x t|",
                           np.abs(snap.mesh["X"] - x_ex).max() / np.abs(x_ex).max(), 1e-12)
                ck.at_most(f"{name}, step {step}: max |sig - D eps| / max |D eps|",
                           np.abs(snap.mesh["gauss_points"][:, 0:4] - sig).max() / np.abs(sig).max(), 1e-12)
    sys.exit(ck.finish())


if __name__ == "__main__":
    main()
