"""The closed forms of test_cases/validation/czm_closed_forms.py (the references of the
cohesive validation cases) checked against themselves by numbers computed another way:
the peak is the maximum of the curve, the work of separation is its integral (Gauss-
Legendre quadrature piece by piece), the curve is continuous, and the damage energy after
a monotonic opening to d is the work minus the secant-stored energy. Parameters: the
decks of czm_mode_I (czm.md §1.2 for the formulas)."""

import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
from fracas_tools import czm_closed_forms as cf  # noqa: E402

LAWS = {
    "MAC": dict(cn=1.0e10, ct=1.0e11, b=0.0, w=40.0),
    "MP3": dict(cn=1.0e11, ct=1.0e11, smax=1.0e6, w=40.0),
    "MAL": dict(cn=1.0e11, ct=5.0e10, s1=1.0e6, s2=2.0e6, G1=40.0, G2=100.0),
    "TH": dict(cn=1.0e11, ct=5.0e10, s1=1.0e6, s2=2.0e6, G1=40.0, G2=100.0, dp1=2.0e-5, dp2=3.0e-5),
    "EXPO": dict(cn=1.0e11, ct=5.0e10, s1=1.0e6, s2=2.0e6, G1=40.0, G2=100.0, eta=1.0e-4),
}


def integral(c, a, b, n=200):
    """Gauss-Legendre quadrature of the curve on [a, b] in 64 pieces."""
    x, w = np.polynomial.legendre.leggauss(n)
    edges = np.linspace(a, b, 65)
    tot = 0.0
    for lo, hi in zip(edges[:-1], edges[1:]):
        xs = 0.5 * (hi - lo) * x + 0.5 * (hi + lo)
        tot += 0.5 * (hi - lo) * float(np.sum(w * c.sigma(xs)))
    return tot


@pytest.mark.parametrize("family", sorted(LAWS))
@pytest.mark.parametrize("mode", [1, 2])
def test_closed_forms(family, mode):
    p = LAWS[family]
    c = cf.curve(family, mode, **p)
    end = c.d_end if np.isfinite(c.d_end) else 1.0e4 * c.d_peak
    d = np.union1d(np.linspace(0.0, end * 1.02, 400001), [c.d_peak])
    s = c.sigma(d)
    # the peak is the maximum, at d_peak
    assert abs(s.max() - c.peak) <= 1e-12 * c.peak
    assert abs(float(c.sigma(c.d_peak)) - c.peak) <= 1e-12 * c.peak
    # continuous at its kinks (peak, TH's plateau end, cut-off), but EXPO's cut-off, where
    # the traction eta s drops to 0
    kinks = [c.d_peak] + ([c.d_end] if np.isfinite(c.d_end) else [])
    if family == "TH":
        kinks.append(max(c.d_peak, p["dp1"] if mode == 1 else p["dp2"]))
    for b in kinks:
        jump = abs(float(c.sigma(b * (1.0 - 1e-10))) - float(c.sigma(b * (1.0 + 1e-10))))
        expected = p["eta"] * c.peak if (family == "EXPO" and b == c.d_end) else 0.0
        assert abs(jump - expected) <= 1e-6 * c.peak, (b, jump)
    # the work of separation is the area under the curve
    pts = sorted({0.0, c.d_peak, end})
    area = sum(integral(c, a, b) for a, b in zip(pts[:-1], pts[1:]))
    if family == "MAC":            # w - (w/2)(u0/d)^2 up to d = end
        assert abs(area - c.work(end)) <= 1e-8 * c.total_work
        assert abs(c.total_work - p["w"]) <= 1e-12 * p["w"]
    else:
        assert abs(area - c.total_work) <= 1e-8 * c.total_work
    # the nominal energy: w (MAC, MP3 with cn = ct), G (MAL, TH); EXPO loses its cut tail
    g = cf.nominal_energy(family, mode, **p)
    if family == "EXPO":
        assert c.total_work < g and abs(c.total_work - g) <= p["eta"] * g
    elif not (family == "MP3" and p["cn"] != p["ct"]):
        assert abs(c.total_work - g) <= 1e-12 * g
    # damage = work - stored, stored = sigma d / 2 (secant unloading)
    for x in (0.5 * c.d_peak, 2.0 * c.d_peak, 0.5 * (c.d_peak + end)):
        assert abs(c.damage(x) - (integral(c, 0.0, min(x, c.d_peak)) +
                                  (integral(c, c.d_peak, x) if x > c.d_peak else 0.0) -
                                  0.5 * float(c.sigma(x)) * x)) <= 1e-8 * c.total_work
