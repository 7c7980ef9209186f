#!/usr/bin/python3
"""Limit analysis of a semicircular arch of N rigid voussoirs with radial joints under
self-weight (safe theorem, symmetric thrust line), for the arch_heyman validation case.

Geometry as fracas_tools.generators.arch: voussoir k is the quadrilateral with
vertices at radii ri = R - t/2 and ro = R + t/2 on the rays pi k/N and pi (k+1)/N
(straight intrados and extrados); joints are the radial segments at
theta_j = pi j / N (j = 0 and N rest on fixed supports). Weights and moments are those
of these quadrilaterals (for large N they tend to the annular sectors of the
classical analysis: t_min/R -> 0.1075, Milankovitch).

By symmetry the thrust at the crown (theta = pi/2) is horizontal, H, at height y_c.
For the part of the right half between the crown and joint theta (weight W, first
moment M = W x_G about the vertical axis) moment equilibrium puts the resultant
(H, -W) through the joint at radius
    rho(theta) = (Q + M) / (W cos theta + H sin theta),   Q = y_c H.
The arch can stand (rigid blocks, no tension, Coulomb joints) iff some (H > 0, Q) gives
    ri <= rho(theta_j) <= ro                           at every joint of the half,
    |H cos theta_j - W sin theta_j| <= mu (H sin theta_j + W cos theta_j)  (no sliding),
and, for N even (a joint at the crown), ri <= y_c <= ro. All these are linear in
(H, Q): for each H the admissible Q form an interval, scanned over H.

    python3 arch_limit.py [N ...]      # prints t_min/R for these N and for N -> large
"""
import math
import sys

import numpy as np


def voussoir(N, R, t, k):
    """Vertices of voussoir k as fracas_tools.generators.arch makes it: a quadrilateral
    (straight intrados and extrados chords) between the joints at pi k/N, pi (k+1)/N."""
    ri, ro = R - 0.5 * t, R + 0.5 * t
    a0, a1 = math.pi * k / N, math.pi * (k + 1) / N
    return np.array([[ri * math.cos(a0), ri * math.sin(a0)], [ro * math.cos(a0), ro * math.sin(a0)],
                     [ro * math.cos(a1), ro * math.sin(a1)], [ri * math.cos(a1), ri * math.sin(a1)]])


def area_moment(v):
    """(area, first moment about the y axis = area * x_centroid) of a polygon."""
    x, y = v[:, 0], v[:, 1]
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    cr = x * y1 - x1 * y
    a = 0.5 * cr.sum()
    return a, (cr * (x + x1)).sum() / 6.0


def clip_right(v):
    """The part x >= 0 of a convex polygon (Sutherland-Hodgman, one half-plane)."""
    out = []
    n = len(v)
    for i in range(n):
        p, q = v[i], v[(i + 1) % n]
        if p[0] >= 0.0:
            out.append(p)
        if (p[0] >= 0.0) != (q[0] >= 0.0):
            s = p[0] / (p[0] - q[0])
            out.append(p + s * (q - p))
    return np.array(out)


def joint_loads(N, R, t):
    """Joints of the right half (theta < pi/2) with the weight W (per unit weight
    density) and first moment M (about the vertical axis) of the part of the arch
    between the joint and the crown; the keystone of an odd N is cut at x = 0."""
    parts = []
    for k in range(N):
        a0, a1 = math.pi * k / N, math.pi * (k + 1) / N
        if a1 <= 0.5 * math.pi + 1e-12:
            parts.append((a0, area_moment(voussoir(N, R, t, k))))
        elif a0 < 0.5 * math.pi - 1e-12:                       # keystone (odd N)
            parts.append((a0, area_moment(clip_right(voussoir(N, R, t, k)))))
    th = np.array([a0 for a0, _ in parts])
    W = np.array([sum(am[0] for a0, am in parts if a0 >= th_j - 1e-12) for th_j in th])
    M = np.array([sum(am[1] for a0, am in parts if a0 >= th_j - 1e-12) for th_j in th])
    return th, W, M


def admissible(N, R, t, mu=math.inf, n_h=4001, return_range=False):
    """True when a symmetric thrust line fits the joints (see the module doc)."""
    ri, ro = R - 0.5 * t, R + 0.5 * t
    th, W, M = joint_loads(N, R, t)
    c, s = np.cos(th), np.sin(th)
    # a generous range of H (per unit weight density): the thrust of a half arch is
    # at most its weight times a few
    Wh = 0.5 * math.pi * R * t
    H = np.linspace(1e-4 * Wh, 3.0 * Wh, n_h)[:, None]
    den = W[None, :] * c[None, :] + H * s[None, :]
    lo = (ri * den - M[None, :]).max(axis=1)
    hi = (ro * den - M[None, :]).min(axis=1)
    if N % 2 == 0:                                  # crown joint: ri <= y_c <= ro
        lo = np.maximum(lo, ri * H[:, 0])
        hi = np.minimum(hi, ro * H[:, 0])
    ok = lo <= hi
    if math.isfinite(mu):
        tang = np.abs(H * c[None, :] - W[None, :] * s[None, :])
        ok &= (tang <= mu * den).all(axis=1)
    if return_range:
        return H[ok, 0] / Wh
    return bool(ok.any())


def _feasible_at(N, R, t, mu, H):
    """True when, for this thrust H, some crown height fits every joint."""
    ri, ro = R - 0.5 * t, R + 0.5 * t
    th, W, M = joint_loads(N, R, t)
    c, s = np.cos(th), np.sin(th)
    den = W * c + H * s
    lo = (ri * den - M).max()
    hi = (ro * den - M).min()
    if N % 2 == 0:
        lo, hi = max(lo, ri * H), min(hi, ro * H)
    ok = lo <= hi
    if math.isfinite(mu):
        ok &= bool((np.abs(H * c - W * s) <= mu * den).all())
    return bool(ok)


def thrust_range(N, R, t, mu=math.inf, n_h=4001):
    """(H_min, H_max): the horizontal thrusts (per unit weight density, i.e. divide a
    force by rho g) for which a symmetric thrust line fits the joints; the feasible
    thrusts form an interval (a convex set), whose ends are found by bisection to
    1e-12 relative. None when the arch cannot stand."""
    ok = admissible(N, R, t, mu, n_h=n_h, return_range=True)
    if len(ok) == 0:
        return None
    Wh = 0.5 * math.pi * R * t
    step = 3.0 * Wh / (n_h - 1)
    ends = []
    for inside, outside in ((ok.min() * Wh, ok.min() * Wh - step), (ok.max() * Wh, ok.max() * Wh + step)):
        for _ in range(60):
            mid = 0.5 * (inside + outside)
            if _feasible_at(N, R, t, mu, mid):
                inside = mid
            else:
                outside = mid
        ends.append(inside)
    return float(ends[0]), float(ends[1])


def hinges(N, R=1.0, mu=math.inf, rel=1.0e-6):
    """Joints where the thrust line touches the intrados ('i') or extrados ('e') at
    the minimum thickness: the hinges of the collapse mechanism. Returns a dict
    {joint number j (theta = pi j/N): 'i' or 'e'} for the whole arch (by symmetry)."""
    t = t_min(N, R, mu) * (1.0 + rel)
    ri, ro = R - 0.5 * t, R + 0.5 * t
    hr = thrust_range(N, R, t, mu)
    H = 0.5 * (hr[0] + hr[1])
    th, W, M = joint_loads(N, R, t)
    den = W * np.cos(th) + H * np.sin(th)
    lo = max((ri * den - M).max(), ri * H if N % 2 == 0 else -math.inf)
    hi = min((ro * den - M).min(), ro * H if N % 2 == 0 else math.inf)
    Q = 0.5 * (lo + hi)
    rho = (Q + M) / den
    out = {}
    tol = 1.0e-2 * t          # the other joints keep a margin > 0.05 t (N = 20)
    for th_j, r in zip(th, rho):
        j = int(round(th_j * N / math.pi))
        if r - ri < tol:
            out[j] = out[N - j] = "i"
        elif ro - r < tol:
            out[j] = out[N - j] = "e"
    if N % 2 == 0:
        yc = Q / H
        if yc - ri < tol:
            out[N // 2] = "i"
        elif ro - yc < tol:
            out[N // 2] = "e"
    return dict(sorted(out.items()))


def t_min(N, R=1.0, mu=math.inf, lo=0.05, hi=0.2, iters=40):
    """Minimum thickness t (bisection) for which the arch of N voussoirs can stand."""
    assert not admissible(N, R, lo * R, mu) and admissible(N, R, hi * R, mu)
    for _ in range(iters):
        mid = 0.5 * (lo + hi)
        if admissible(N, R, mid * R, mu):
            hi = mid
        else:
            lo = mid
    return hi * R


if __name__ == "__main__":
    Ns = [int(a) for a in sys.argv[1:]] or [11, 20, 21, 24, 30, 40, 41, 60, 1000]
    for N in Ns:
        print(f"N = {N:5d}: t_min/R = {t_min(N):.6f}   (mu = 0.5: {t_min(N, mu=0.5):.6f})"
              f"   hinges (joint: intrados/extrados) {hinges(N)}")
