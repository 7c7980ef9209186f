"""Closed forms of the cohesive laws' pure-mode traction curves, written from
../shared/reference/czm.md §1.2 independently of the solver and of
fracas_tools.cohesive.Law (the one implementation of the laws, which mirrors the solver's
update; this module is no implementation of the laws but the tests' reference): the traction sigma(d) piece by piece, its peak, the
opening at the peak, the work of separation and the damage energy after a monotonic
opening to d. The validation checks compare the runs with these formulas, so an error
shared by the Fortran update and its Python mirror still shows.

    from fracas_tools import czm_closed_forms as cf
    curve = cf.curve("MP3", mode=1, cn=1e11, ct=1e11, smax=1e6, w=40.0)
    curve.sigma(d), curve.peak, curve.d_peak, curve.total_work, curve.damage(d)

Mode 1 is opening (cn, s1, G1, dp1), mode 2 sliding (ct, s2, G2, dp2).
"""

import math

import numpy as np


class Curve:
    """A pure-mode traction curve: elastic slope c to d_peak, then the law's softening."""

    def __init__(self, c, d_peak, peak, soften, d_end, total_work):
        self.c, self.d_peak, self.peak = c, d_peak, peak
        self._soften, self.d_end, self.total_work = soften, d_end, total_work

    def sigma(self, d):
        d = np.asarray(d, dtype=float)
        with np.errstate(all="ignore"):
            soft = self._soften(np.maximum(d, self.d_peak))
        out = np.where(d <= self.d_peak, self.c * d, np.where(d < self.d_end, soft, 0.0))
        return out

    def stored(self, d):
        """Elastic energy left at d after a monotonic opening: (1/2) sigma(d) d (secant unloading)."""
        return 0.5 * float(self.sigma(d)) * d

    def work(self, d):
        """Work of the traction up to d (the closed-form total beyond the cut-off)."""
        if d >= self.d_end:
            return self.total_work
        return self._work(d)

    def damage(self, d):
        """Energy dissipated by damage after a monotonic opening to d: work - stored."""
        return self.work(d) - self.stored(d)


def curve(family, mode, **p):
    """The curve of a law (family MAC, MP3, MAL, TH, EXPO or ABP) from its deck parameters."""
    f = family.upper()
    c = p["cn"] if mode == 1 else p["ct"]
    if f == "MAC":
        # sigma = c d up to u0 = sqrt(w/c), then w^2 / (c d^3); peak sqrt(c w); total w
        w = p["w"]
        u0 = math.sqrt(w / c)
        cv = Curve(c, u0, math.sqrt(c * w), lambda d: w * w / (c * d ** 3), math.inf, w)
        cv._work = lambda d: 0.5 * c * d * d if d <= u0 else w - 0.5 * w * u0 * u0 / (d * d)
        return cv
    if f == "MP3":
        s, g = p["smax"], p["w"]
        di = 0.5 * s * (1.0 / p["cn"] + 1.0 / p["ct"])
    else:
        s = p["s1"] if mode == 1 else p["s2"]
        g = p["G1"] if mode == 1 else p["G2"]
        di = s / c
    top = c * di                     # the peak: smax (MP3, cn = ct), s1/s2 (MAL, TH, EXPO)
    if f in ("MP3", "MAL"):
        # parabolic softening with zero slope at the peak, to 0 at di + dk: area (2/3) top dk
        dk = 1.5 * (g / s - 0.5 * di)
        total = 0.5 * top * di + 2.0 / 3.0 * top * dk
        cv = Curve(c, di, top, lambda d: top * (1.0 - ((d - di) / dk) ** 2), di + dk, total)

        def work(d):
            if d <= di:
                return 0.5 * c * d * d
            x = (d - di) / dk
            return 0.5 * top * di + top * dk * (x - x ** 3 / 3.0)
        cv._work = work
        return cv
    if f == "TH":
        # trapezoid: plateau at s from di to dp, linear to 0 at du = 2G/s - dp + di: area G
        dp = max(di, p["dp1"] if mode == 1 else p["dp2"])
        du = 2.0 * g / s - dp + di
        cv = Curve(c, di, s, lambda d: np.where(d <= dp, s, s * (du - d) / (du - dp)), du, g)

        def work(d):
            if d <= di:
                return 0.5 * c * d * d
            if d <= dp:
                return 0.5 * s * di + s * (d - di)
            return 0.5 * s * di + s * (dp - di) + 0.5 * (s + s * (du - d) / (du - dp)) * (d - dp)
        cv._work = work
        return cv
    if f == "EXPO":
        # s exp(phi (di - d)), phi = s / (G - s di / 2), cut at eta s: area G - eta (G - s di / 2)
        phi = s / (g - 0.5 * s * di)
        du = di - math.log(p["eta"]) / phi
        cv = Curve(c, di, s, lambda d: s * np.exp(phi * (di - d)), du, g - p["eta"] * (g - 0.5 * s * di))

        def work(d):
            if d <= di:
                return 0.5 * c * d * d
            return 0.5 * s * di + (s / phi) * (1.0 - math.exp(phi * (di - d)))
        cv._work = work
        return cv
    if f == "ABP":
        # three straight pieces: (0, 0) to (di, s), to (dp, sp), to (du, 0), with du given,
        # sp = 2G(1 - phi)/du and dp = (2 G phi + sp di)/s (lmgc90.md 5.3): area G
        du = p["du1"] if mode == 1 else p["du2"]
        sp = 2.0 * g * (1.0 - p["phi"]) / du
        dp = (2.0 * g * p["phi"] + sp * di) / s
        cv = Curve(c, di, s, lambda d: np.where(d <= dp, s + (sp - s) * (d - di) / (dp - di),
                                                sp * (du - d) / (du - dp)), du, g)

        def work(d):
            if d <= di:
                return 0.5 * c * d * d
            if d <= dp:
                return 0.5 * s * di + 0.5 * (d - di) * (2.0 * s + (sp - s) * (d - di) / (dp - di))
            return 0.5 * s * di + 0.5 * (dp - di) * (s + sp) + 0.5 * (d - dp) * (sp + sp * (du - d) / (du - dp))
        cv._work = work
        return cv
    raise ValueError(f"unknown cohesive law family {family!r}")


def nominal_energy(family, mode, **p):
    """The energy parameter of the deck: w (MAC, MP3), G1 or G2."""
    if family.upper() in ("MAC", "MP3"):
        return p["w"]
    return p["G1"] if mode == 1 else p["G2"]


def beta_exponent(family):
    """k in sigma = beta^k c d: 2 for MAC/RCC, 1 for the MP family (czm.md §0)."""
    return 2 if family.upper() == "MAC" else 1


class Closed:
    """The closed forms of one law with the interface the validation checks use
    (mode 1: opening, 2: sliding), from the deck parameters only."""

    def __init__(self, family, **p):
        self.family = family.upper()
        self.p = dict(p)
        self.cn, self.ct = p["cn"], p["ct"]
        self.k = beta_exponent(family)
        self._curves = {m: curve(family, m, **p) for m in (1, 2)}

    @classmethod
    def of(cls, law):
        """From a deck law object with .family and .p (fracas_tools.cohesive.Law)."""
        return cls(law.family, **law.p)

    def c(self, mode):
        return self.cn if mode == 1 else self.ct

    def peak(self, mode):
        return self._curves[mode].peak

    def d_peak(self, mode):
        return self._curves[mode].d_peak

    def d_end(self, mode):
        return self._curves[mode].d_end

    def sigma(self, d, mode):
        return self._curves[mode].sigma(d)

    def beta(self, d, mode):
        """beta = (sigma / (c d))^(1/k), 1 at d = 0; 0 below 1e-12 (the solver's broken threshold)."""
        d = np.asarray(d, dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            b = np.where(d > 0.0, (self.sigma(d, mode) / (self.c(mode) * d)) ** (1.0 / self.k), 1.0)
        return np.where(b < 1.0e-12, 0.0, np.minimum(b, 1.0))

    def damage(self, d, mode):
        return self._curves[mode].damage(float(d))

    def stored(self, d, mode):
        return self._curves[mode].stored(float(d))

    def fracture_energy(self, mode):
        return self._curves[mode].total_work

    def nominal_energy(self, mode):
        return nominal_energy(self.family, mode, **self.p)
