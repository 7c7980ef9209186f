#!/usr/bin/env python3
"""J2 one-element tension-compression cycle through the solver. One Q4 element (1 m x
1 m), left nodes held in x (and the corner in y), right nodes driven in x with
piecewise-constant velocities: strain steps of +-1e-4 through tension to 3e-3,
compression to -4e-3, tension to 5e-3 and unloading to zero stress (235 steps of 1 s,
theta = 1 so that a driven dof moves by h V_end and every yield or reversal falls on a
step end). The top and right faces are free: the state is uniaxial stress,
homogeneous (the four Gauss points agree). Density 1 kg/m3: inertia is below 1e-13 of
the stresses.

References. Plane stress: the closed form of uniaxial linear isotropic hardening
(yield at sigma_0, slope E H / (E + H), elastic unloading at E, reverse yield at
-(sigma_0 + H p)). Plane strain (eps_zz = 0): elastic slope E / (1 - nu^2), first yield
at sigma_0 / sqrt(1 - nu + nu^2); beyond it an independent material-point radial
return (3D small strain, the same strain steps, sigma_yy = 0 solved by root finding).
Plane strain with eps_yy = 0 too (the right and top nodes also held in y: uniaxial
strain): the closed form of uniaxial_strain_reference. All: plastic work
int sigma : d eps_p = sigma_0 p + H p^2 / 2 (sigma : eps_p' = sigma_y(p) p' on the
yield surface). Tolerance 1e-8 relative to the largest stress (or the final work)."""
import sys
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

from fracas_tools.valmesh import Case  # noqa: E402
from fracas_tools.valmesh import Checker, args, run_fracas  # noqa: E402

E, NU, SIG0, HARD, RHO = 2.0e11, 0.3, 2.0e8, 2.0e11, 1.0
H, DEPS = 1.0, 1.0e-4
# Segments: (strain rate sign, steps).
SEGMENTS = [(+1, 30), (-1, 70), (+1, 90), (-1, 45)]


def strain_path():
    eps = [0.0]
    for sgn, n in SEGMENTS:
        eps += [eps[-1] + sgn * DEPS * (k + 1) for k in range(n)]
    # Integer multiples of DEPS, as the solver adds them.
    return np.array(eps)


def build(case_dir, plane, lateral_held=False):
    case = Case(gravity=(0.0, 0.0))
    case.add_material("STEEL", RHO, "ELAS_PLAS", young=E, poisson=NU, yield_stress=SIG0, hardening=HARD)
    case.add_model("M2DJ2", "Q4xxx", material="J2iso")
    b = case.add_mesh_body(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]), [(1, 2, 3, 4)],
                           model="M2DJ2", material="STEEL")
    b.impose_velocity([1], (1, 2))
    b.impose_velocity([4], (1, 2) if lateral_held else 1)
    if lateral_held:
        b.impose_velocity([2, 3], 2)       # eps_yy = 0: uniaxial strain
    # Velocity at each step end: the table holds the values at the step times.
    table, t = [(0.0, 0.0)], 0.0
    for sgn, n in SEGMENTS:
        table.append((t + H, sgn * DEPS / H))
        t += n * H
        table.append((t, sgn * DEPS / H))
    b.impose_evolution([2, 3], 1, "vlocy", "strain_rate.dat", data=np.array(table))
    case.run.set(time_step=H, number_of_steps=sum(n for _, n in SEGMENTS), theta=1.0, plane=plane,
                 newton_tolerance=1e-13, newton_max_iterations=50, output_dof_every=0, output_hdf5_every=1)
    case.write(case_dir)


def plane_stress_reference(eps):
    """sigma_xx and p of uniaxial stress along the strain path (closed form per regime)."""
    sig, p, out_s, out_p = 0.0, 0.0, [0.0], [0.0]
    for de in np.diff(eps):
        trial = sig + E * de
        f = abs(trial) - (SIG0 + HARD * p)
        if f > 0:
            dp = f / (E + HARD)
            p += dp
            sig = trial - np.sign(trial) * E * dp
        else:
            sig = trial
        out_s.append(sig)
        out_p.append(p)
    return np.array(out_s), np.array(out_p)


def uniaxial_strain_reference(eps):
    """Closed form of uniaxial strain (eps_yy = eps_zz = 0): the deviatoric strain
    eps (2/3, -1/3, -1/3) keeps its direction, so J2 with linear isotropic hardening
    is a 1D law on t = s_xx (s_yy = s_zz = -t/2, von Mises q = 3/2 |t|): elastic
    dt = 4/3 mu d eps; at q = sigma_0 + H p, dp = 2 mu |d eps| / (3 mu + H); the mean
    stress K eps stays elastic. The regime changes inside a step are split exactly.
    Returns sigma_xx, sigma_yy (= sigma_zz), p along the path."""
    mu, k = E / (2 * (1 + NU)), E / (3 * (1 - 2 * NU))
    t, p, out = 0.0, 0.0, [(0.0, 0.0, 0.0)]
    for e0, e1 in zip(eps[:-1], eps[1:]):
        de = e1 - e0
        # elastic part of the increment: until 3/2 |t| reaches sigma_0 + H p
        limit = np.sign(de) * (SIG0 + HARD * p) / 1.5
        de_el = min(abs(de), max((limit - t) / (4.0 / 3.0 * mu) * np.sign(de), 0.0)) * np.sign(de)
        t += 4.0 / 3.0 * mu * de_el
        de_pl = de - de_el
        dp = 2 * mu * abs(de_pl) / (3 * mu + HARD)
        p += dp
        t += np.sign(de) * 1.5 ** -1 * HARD * dp
        out.append((k * e1 + t, k * e1 - t / 2, p))
    return np.array(out)


def radial_return(eps, eps_p, p):
    """3D small-strain J2, linear isotropic hardening: stress, plastic strain and p
    at total strain eps (3x3) from the state (eps_p, p) of the start of the step."""
    g = E / (2 * (1 + NU))
    k = E / (3 * (1 - 2 * NU))
    ee = eps - eps_p
    s_tr = 2 * g * (ee - np.trace(ee) / 3 * np.eye(3))
    q = np.sqrt(1.5 * np.sum(s_tr * s_tr))
    f = q - (SIG0 + HARD * p)
    if f > 0:
        dp = f / (3 * g + HARD)
        n = 1.5 * s_tr / q
        eps_p = eps_p + dp * n
        p = p + dp
        s_tr = s_tr * (1 - 3 * g * dp / q)
    return s_tr + k * np.trace(ee) * np.eye(3), eps_p, p


def plane_strain_reference(eps_xx):
    """sigma (xx, yy, zz), p along the path with eps_zz = 0, sigma_yy = 0."""
    ep, p, eyy = np.zeros((3, 3)), 0.0, 0.0
    out = [(0.0, 0.0, 0.0, 0.0)]
    for exx in eps_xx[1:]:
        def syy(y):
            e = np.diag([exx, y, 0.0])
            return radial_return(e, ep, p)[0][1, 1]
        eyy = brentq(syy, eyy - 1e-2, eyy + 1e-2, xtol=1e-18, rtol=1e-15, maxiter=200)
        s, ep, p = radial_return(np.diag([exx, eyy, 0.0]), ep, p)
        out.append((s[0, 0], s[1, 1], s[2, 2], p))
    return np.array(out)


def main():
    a = args(__doc__)
    ck = Checker("validation_meshes.j2_cycle")
    eps = strain_path()
    mu, k = E / (2 * (1 + NU)), E / (3 * (1 - 2 * NU))
    for plane, held in (("stress", False), ("strain", False), ("strain", True)):
        label = f"plane_{plane}" + ("_uniaxial_strain" if held else "")
        case = Path(a.out, label)
        build(case, plane, held)
        with run_fracas(a.fracas, case) as run:
            steps = np.array([0] + [s for s, _ in run.snapshot_times()])
            gp = np.array(run.snapshot_arrays("mesh_gauss_points"))
            x = np.concatenate([[0.0], [X[1, 0] for X in run.snapshot_arrays("mesh_X")]])   # right node ux = eps_xx
            wp = np.concatenate([[0.0], run.series["plastic_work"]])
            newton, converged = run.series["newton_iterations"], run.series["converged"]
        # Step 0 (the initial state) is not a snapshot: zero displacement and stress.
        gp = np.concatenate([np.zeros_like(gp[:1]), gp])
        name = f"plane {plane}" + (", eps_yy = 0" if held else "")
        ck.true(f"{name}: a snapshot at every step", np.array_equal(steps, np.arange(len(eps))), len(steps),
                len(eps))
        ck.at_most(f"{name}: driven strain path (right node ux)", np.abs(x - eps).max(), 1e-15)
        # Newton to 1e-13 (relative) converges in 2 iterations, or 4 at a yield step.
        ck.at_most(f"{name}: most Newton iterations of a step", newton.max(), 10)
        ck.true(f"{name}: every step converged (series converged)", converged.min() == 1, converged.min(), 1)
        ck.at_most(f"{name}: the 4 Gauss points agree (homogeneous)",
                   np.abs(gp - gp[:, :1, :]).max() / np.abs(gp[:, :, 0]).max(), 1e-10)
        s = gp[:, 0, :]
        sxx, syy, sxy, szz, p = s[:, 0], s[:, 1], s[:, 2], s[:, 3], s[:, 12]
        # Slopes d sigma_xx / d eps_xx of the closed forms: elastic, hardening.
        if plane == "stress":
            ref_s, ref_p = plane_stress_reference(eps)
            ref = np.column_stack([ref_s, 0 * ref_s, 0 * ref_s, 0 * ref_s])
            e_el, e_t = E, E * HARD / (E + HARD)
            first_yield = SIG0
        elif held:
            r = uniaxial_strain_reference(eps)
            ref_s, ref_p = r[:, 0], r[:, 2]
            ref = np.column_stack([r[:, 0], r[:, 1], 0 * ref_s, r[:, 1]])
            e_el, e_t = k + 4 * mu / 3, k + 4 * mu * HARD / (3 * (3 * mu + HARD))
            first_yield = (k + 4 * mu / 3) * SIG0 / (2 * mu)
        else:
            r = plane_strain_reference(eps)
            ref_s, ref_p = r[:, 0], r[:, 3]
            ref = np.column_stack([r[:, 0], r[:, 1], 0 * ref_s, r[:, 2]])
            e_el, e_t = E / (1 - NU ** 2), None
            first_yield = SIG0 / np.sqrt(1 - NU + NU ** 2)
        scale = np.abs(ref_s).max()
        ck.at_most(f"{name}: stress xx yy xy zz, every step / max|sig|",
                   np.abs(np.column_stack([sxx, syy, sxy, szz]) - ref).max() / scale, 1e-8)
        ck.at_most(f"{name}: p at every step / max p", np.abs(p - ref_p).max() / ref_p.max(), 1e-8)
        ny = int(np.argmax(p > 1e-9 * p.max()))     # first step with plastic flow (not round-off)
        ck.rel(f"{name}: elastic slope before yield", (sxx[ny - 1] - sxx[0]) / (eps[ny - 1] - eps[0]), e_el, 1e-8)
        if plane == "stress":
            ck.rel(f"{name}: first yield at sigma_0 (step {ny - 1})", sxx[ny - 1], SIG0, 1e-8)
        else:
            # The first yield falls inside step ny: the elastic line crosses
            # first_yield at eps_y; the stress it predicts there must be first_yield.
            eps_y = first_yield / e_el
            ck.rel(f"{name}: first yield sigma_xx", sxx[ny - 1] / eps[ny - 1] * eps_y,
                   first_yield, 1e-8, f"between steps {ny - 1} and {ny}")
        if e_t is not None:
            # steps wholly plastic (the step before also plastic) and wholly elastic
            plastic = (np.diff(p) > 0) & (np.roll(np.diff(p) > 0, 1))
            slopes = np.diff(sxx)[plastic] / np.diff(eps)[plastic]
            worst = slopes[np.argmax(np.abs(slopes / e_t - 1))]
            ck.rel(f"{name}: hardening slope, worst of {plastic.sum()}", worst, e_t, 1e-8,
                   "E H/(E+H)" if plane == "stress" else "K + 4 mu H/(3 (3 mu + H))")
            unload = np.diff(p) == 0
            slopes = np.diff(sxx)[unload] / np.diff(eps)[unload]
            worst = slopes[np.argmax(np.abs(slopes / e_el - 1))]
            ck.rel(f"{name}: elastic unloading slope, worst of {unload.sum()}", worst, e_el, 1e-8)
        if held:
            ck.at_most(f"{name}: mean stress = K eps (plastic flow isochoric)",
                       np.abs((sxx + syy + szz) / 3 - k * eps).max() / scale, 1e-8)
        if plane == "strain" and not held:
            ck.info(f"{name}: sigma_zz / sigma_xx before yield (nu)", szz[ny - 1] / sxx[ny - 1])
            ck.info(f"{name}: sigma_zz / sigma_xx end of 1st tension", szz[30] / sxx[30], "tends to 1/2")
        w_ref = SIG0 * p + 0.5 * HARD * p ** 2
        ck.at_most(f"{name}: plastic work vs sig0 p + H p^2/2 (run's p)",
                   np.abs(wp - w_ref).max() / w_ref.max(), 1e-8)
        w_ref2 = SIG0 * ref_p + 0.5 * HARD * ref_p ** 2
        ck.rel(f"{name}: final plastic work (reference p), J/m", wp[-1], w_ref2[-1], 1e-8)
        ck.at_most(f"{name}: plastic work, every step (reference p)", np.abs(wp - w_ref2).max() / w_ref2.max(), 1e-8)
        np.savetxt(Path(a.out, f"{label}_curve.txt"), np.column_stack([steps, eps, sxx, p, wp, ref_s]),
                   header="step eps_xx sigma_xx p plastic_work reference_sigma_xx")
    sys.exit(ck.finish())


if __name__ == "__main__":
    main()
