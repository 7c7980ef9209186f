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
Both: plastic work int sigma : d eps_p = sigma_0 p + H p^2 / 2 (sigma : eps_p' =
sigma_y(p) p' on the yield surface). Tolerance 1e-8 relative to the largest stress
(or the final work)."""
import sys
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from meshdeck import Deck  # noqa: E402
from valmesh import args, check, finish, run_fracas, run_probe, series  # noqa: E402

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


def build(case_dir, plane):
    d = Deck()
    d.material("STEEL", rho=RHO, E=E, nu=NU, sig0=SIG0, hardening=HARD)
    d.model("M2DJ2", "Q4xxx", mater="J2iso")
    b = d.mesh([[0, 0], [1, 0], [1, 1], [0, 1]], [("Q4", [0, 1, 2, 3])], "M2DJ2", "STEEL")
    d.drive(b, 0, 1)
    d.drive(b, 0, 2)
    d.drive(b, 3, 1)
    # Velocity at each step end: the table holds the values at the step times.
    table, t = [(0.0, 0.0)], 0.0
    for sgn, n in SEGMENTS:
        table.append((t + H, sgn * DEPS / H))
        t += n * H
        table.append((t, sgn * DEPS / H))
    for node in (1, 2):
        d.drive(b, node, 1, evolution=table)
    d.command(time_step=H, number_of_steps=sum(n for _, n in SEGMENTS), theta=1.0, plane=plane,
              newton_tolerance=1e-13, newton_max_iterations=50, output_dof_every=0)
    d.write(case_dir)


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
    eps = strain_path()
    for plane in ("stress", "strain"):
        case = Path(a.out, f"plane_{plane}")
        build(case, plane)
        recs = run_probe(a.probe, case, Path(a.out, f"plane_{plane}.probe"), every=1)
        gp = np.array([r["gauss"] for r in recs])             # (steps + 1, 4, 13)
        steps = np.array([r["step"] for r in recs])
        x = np.array([r["nodes"][1, 2] for r in recs])        # right node displacement = eps_xx
        wp = np.array([r["energy"][2] for r in recs])
        name = f"plane {plane}"
        check(f"{name}: driven strain path (right node ux against the planned strains)", np.abs(x - eps).max(), 1e-15)
        check(f"{name}: the four Gauss points agree (homogeneous state)",
              np.abs(gp - gp[:, :1, :]).max() / np.abs(gp[:, :, 0]).max(), 1e-10)
        s = gp[:, 0, :]
        sxx, syy, sxy, szz, p = s[:, 0], s[:, 1], s[:, 2], s[:, 3], s[:, 12]
        if plane == "stress":
            ref_s, ref_p = plane_stress_reference(eps)
            ref = np.column_stack([ref_s, 0 * ref_s, 0 * ref_s, 0 * ref_s])
            e_el = E
            first_yield = SIG0
        else:
            r = plane_strain_reference(eps)
            ref_s, ref_p = r[:, 0], r[:, 3]
            ref = np.column_stack([r[:, 0], r[:, 1], 0 * ref_s, r[:, 2]])
            e_el = E / (1 - NU ** 2)
            first_yield = SIG0 / np.sqrt(1 - NU + NU ** 2)
        scale = np.abs(ref_s).max()
        check(f"{name}: stress (xx, yy, xy, zz) at every step against the reference",
              np.abs(np.column_stack([sxx, syy, sxy, szz]) - ref).max() / scale, 1e-8)
        check(f"{name}: equivalent plastic strain p at every step", np.abs(p - ref_p).max() / ref_p.max(), 1e-8)
        ny = int(np.argmax(p > 1e-9 * p.max()))     # first step with plastic flow (not round-off)
        check(f"{name}: elastic slope d sigma / d eps before yield against {e_el:.6e}",
              abs((sxx[ny - 1] - sxx[0]) / (eps[ny - 1] - eps[0]) / e_el - 1), 1e-8)
        if plane == "stress":
            check(f"{name}: first yield at sigma_0 (stress at the step end before the first plastic step)",
                  abs(sxx[ny - 1] / SIG0 - 1), 1e-8, f"(yield strain {SIG0 / E:.1e} = step {ny - 1})")
            plastic = (np.diff(p) > 0) & (np.roll(np.diff(p) > 0, 1))
            slopes = np.diff(sxx)[plastic] / np.diff(eps)[plastic]
            et = E * HARD / (E + HARD)
            check(f"{name}: hardening slope in {plastic.sum()} plastic steps against E H / (E + H) = {et:.6e}",
                  np.abs(slopes / et - 1).max(), 1e-8)
            unload = np.diff(p) == 0
            slopes = np.diff(sxx)[unload] / np.diff(eps)[unload]
            check(f"{name}: elastic unloading slope in {unload.sum()} steps against E",
                  np.abs(slopes / E - 1).max(), 1e-8)
        else:
            # The first yield falls inside step ny: the elastic line crosses
            # first_yield at eps_y; check the trial stress of that step instead.
            eps_y = first_yield / e_el
            check(f"{name}: first yield at sigma_0 / sqrt(1 - nu + nu^2) = {first_yield:.6e} "
                  f"(elastic stress at eps_y = {eps_y:.6e} on the computed elastic line)",
                  abs(sxx[ny - 1] / eps[ny - 1] * eps_y / first_yield - 1), 1e-8,
                  f"(yield between steps {ny - 1} and {ny})")
            print(f"INFO {name}: sigma_zz / sigma_xx = {szz[ny - 1] / sxx[ny - 1]:.4f} (nu) before yield, "
                  f"{szz[30] / sxx[30]:.4f} at the end of the first tension (tends to 1/2 under plastic flow)")
        w_ref = SIG0 * p + 0.5 * HARD * p ** 2
        check(f"{name}: plastic work int sigma : d eps_p against sigma_0 p + H p^2 / 2 (p of the run)",
              np.abs(wp - w_ref).max() / w_ref.max(), 1e-8, f"(final {wp[-1]:.6e} J per m)")
        w_ref2 = SIG0 * ref_p + 0.5 * HARD * ref_p ** 2
        check(f"{name}: plastic work against the same with the reference p",
              np.abs(wp - w_ref2).max() / w_ref2.max(), 1e-8)
        # The executable on the same deck: its series plastic_work.
        run_fracas(a.fracas, case)
        (wser,) = series(case, "plastic_work")
        check(f"{name}: fracas fracas.h5 plastic_work against the probe", np.abs(wser - wp[1:]).max() / wp.max(), 1e-12)
        np.savetxt(Path(a.out, f"plane_{plane}_curve.txt"), np.column_stack([steps, eps, sxx, p, wp, ref_s]),
                   header="step eps_xx sigma_xx p plastic_work reference_sigma_xx")
    finish()


if __name__ == "__main__":
    main()
