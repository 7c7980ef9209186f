#!/usr/bin/python3
"""Check the box_tip_slide run: a box on an incline rests, tips or slides according
to tan(alpha) against b/H and mu (README.md).

usage: check.py [RUN_DIR]   (RUN_DIR holds OUTBOX/fracas.h5; default: this folder)
Prints one line per quantity and exits 1 if any check fails.
"""
import math
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
import gen          # noqa: E402  (the deck parameters)
from fracas_tools import polytools as pt  # noqa: E402

# Tolerances (README.md, "Tolerances and why")
TOL_REST_X = 1.0e-9       # m and rad: motion of a resting box
TOL_REL = 1.0e-8          # statics and slide kinematics (NLGS tolerance)
TOL_TIP_PHI = 5.0e-4      # rad: tipping angle vs the pivot ODE while phi_ref <= PHI_CMP
PHI_CMP = 0.5             # rad
TOL_PIVOT = 1.0e-5        # m: slip of the pivot corner while phi_ref <= PHI_CMP
TOL_FINAL = 1.0e-3        # rad: the tipped box lies on its side (rotation pi/2)


def pivot_ode(b, H, alpha, g, t_end, dt=1.0e-4):
    """Rotation phi(t) of a box pivoting about its lower downhill corner (RK4):
    I_P phi'' = m g (H/2 sin(phi + alpha) - b/2 cos(phi + alpha)), I_P = m (b^2 + H^2)/3."""
    ip = (b * b + H * H) / 3.0

    def f(y):
        return np.array([y[1], g * (0.5 * H * math.sin(y[0] + alpha) - 0.5 * b * math.cos(y[0] + alpha)) / ip])

    n = int(round(t_end / dt))
    y = np.zeros(2)
    out = np.zeros(n + 1)
    for i in range(n):
        k1 = f(y)
        k2 = f(y + 0.5 * dt * k1)
        k3 = f(y + 0.5 * dt * k2)
        k4 = f(y + dt * k3)
        y = y + dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        out[i + 1] = y[0]
    return np.arange(n + 1) * dt, out


def main():
    res = pt.Results(pt.run_dir_from_argv(HERE))
    g = gen.G
    t = res.time
    ck = pt.Checker("box_tip_slide")
    for k, (b, H, law, _, expected) in enumerate(gen.SCENES):
        mu = gen.LAWS[law][0]
        P, d, n, _, alpha = gen.frame(k)
        blk = 2 * k + 2
        tag = f"S{k + 1} {b}x{H} mu={mu} {math.degrees(alpha):.3f}deg {expected}:"
        m = res.mass[blk - 1]
        X = res.X[:, blk - 1, :]
        rot = X[:, 2] - alpha                      # rotation from the initial pose
        pos = res.position[:, blk - 1, :2]
        if expected in ("rest", "slide"):
            F = res.force_on(len(t) - 1, blk)
            Fn, Ft = F @ n, F @ d
            c = res.contacts[-1]
            sel = (c["cd"] == blk) | (c["an"] == blk)
            # contact points are those of the detection configuration q_m = q + (1 - theta) h v
            qm = pos[-2] + (1.0 - res.theta) * res.h * res.V[-2, blk - 1, :2]
            xcp = float(np.sum(c["rn"][sel] * ((c["point"][sel] - qm) @ d)) / np.sum(c["rn"][sel]))
            ck.rel(f"{tag} R_n = m g cos(alpha) (N/m)", Fn, m * g * math.cos(alpha), TOL_REL)
        if expected == "rest":
            ck.at_most(f"{tag} max |displacement| (m)", np.abs(X[:, :2]).max(), TOL_REST_X)
            ck.at_most(f"{tag} max |rotation change| (rad)", np.abs(rot).max(), TOL_REST_X)
            ck.rel(f"{tag} R_t = m g sin(alpha) (N/m)", Ft, m * g * math.sin(alpha), TOL_REL)
            ck.rel(f"{tag} centre of pressure = -(H/2) tan(alpha) (m)", xcp,
                   -0.5 * H * math.tan(alpha), TOL_REL, note=f"inside the base: |x| < b/2 = {b / 2}")
        elif expected == "slide":
            acc = g * (math.sin(alpha) - mu * math.cos(alpha))
            s = -(X[:, :2] @ d)
            ck.rel(f"{tag} s(T) = a T^2/2 (m)", s[-1], 0.5 * acc * t[-1] ** 2, TOL_REL,
                   note=f"a = {acc:.6f} m/s2")
            ck.at_most(f"{tag} max |rotation change| (rad)", np.abs(rot).max(), TOL_REST_X)
            ck.rel(f"{tag} R_t / R_n = mu (sliding)", Ft / Fn, mu, TOL_REL)
            ck.rel(f"{tag} centre of pressure = -(H/2) mu (m)", xcp, -0.5 * H * mu, TOL_REL,
                   note=f"inside the base: |x| < b/2 = {b / 2}, no tipping")
        else:   # tip
            T, phi = pivot_ode(b, H, alpha, g, t[-1])
            ref = np.interp(t, T, phi)
            win = ref <= PHI_CMP
            ck.at_most(f"{tag} max |phi - phi_ODE| while phi <= {PHI_CMP} (rad)",
                       np.abs(rot[win] - ref[win]).max(), TOL_TIP_PHI,
                       note=f"t <= {t[win][-1]:.3f} s")
            i1 = int(np.argmin(np.abs(t - 0.4)))
            ck.rel(f"{tag} phi(0.4 s) (rad)", rot[i1], ref[i1], 1.0e-3)
            # the downhill lower corner (pivot) in the global frame
            cr = np.array([-0.5 * b, -0.5 * H])
            ang = res.position[:, blk - 1, 2]
            corner = pos + np.column_stack((np.cos(ang) * cr[0] - np.sin(ang) * cr[1],
                                            np.sin(ang) * cr[0] + np.cos(ang) * cr[1]))
            ck.at_most(f"{tag} pivot slip while phi <= {PHI_CMP} (m)",
                       np.abs(corner[win] - corner[0]).max(), TOL_PIVOT)
            ck.close(f"{tag} final rotation: lies on its side (rad)", rot[-1], 0.5 * math.pi, TOL_FINAL)
            ck.at_most(f"{tag} final |v| (m/s)", np.abs(res.V[-1, blk - 1, :2]).max(), 1.0e-6)
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
