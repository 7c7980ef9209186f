"""Cohesive zone laws in Python: the one implementation of the laws of the solver
(modules/behaviours/fracas_czm.f90), and the deck helpers of exploded meshes.

Laws (ctest validation.czm_law_mirror runs the solver on a driven pair for every law and
compares its traction, damage and energies with Law, so that a drift of either is red):

    from fracas_tools.cohesive import Law
    law = Law.mac(cn=1e10, ct=1e11, b=0.0, w=40.0)
    law.peak(1), law.d_peak(1), law.fracture_energy(1)    # mode 1: opening, 2: sliding
    law.sigma(d, 1)                                       # quasi-static traction curve
    law.work(d, 1), law.stored(d, 1), law.damage(d, 1)    # per unit length, up to d
    law.update(beta_old, ut, un, h)                       # the solver's beta update, mirrored
    law.stored_energy(beta, ut, un), law.damage_energy(beta, ut, un), law.step_dissipation(...)
    Law.of_deck(contact_law)                              # from a TACT_BEHAV law (fracas_tools.datbox)

References (stated in doc/czm.md): ../shared/reference/czm.md §1.2-1.3 and
../shared/reference/lmgc90.md §5.3. (fracas_tools.czm_closed_forms holds the same curves
written independently from czm.md, the validation cases' reference.)

* MAC (Monerie-Acary / RCC), b = 0: beta = min(1, w/(c d^2)); sigma = beta^2 c d;
  peak sqrt(c w) at d0 = sqrt(w/c); sigma = w^2/(c d^3) beyond; work to d
  w - (w/2)(d0/d)^2, stored (w/2)(d0/d)^2, damage w (1 - (d0/d)^2).
  b > 0: b beta' = -(w - beta Y)^-, Y = cn <un>+^2 + ct ut^2 (rate dependent).
* MP3: di = (smax/2)(1/cn + 1/ct), dk = 1.5 (w/smax - di/2),
  beta = (di/d)(1 - ((d - di)/dk)^2) on [di, di + dk], then 0.
* MAL: the MP3 shape with di = s/c and dk = 1.5 (G/s - di/2), per mode.
* TH: di = s/c, plateau s to dp, linear to 0 at du = 2G/s - dp + di.
* EXPO: di = s/c, then s exp(phi (di - d)), phi = s/(G - s di/2), cut at
  du = di - ln(eta)/phi: work G - eta (G - s di/2).
* ABP: tri-linear, di = s/c, then to (dp, sp), then to (du, 0): sp = 2G (1 - phi)/du,
  dp = (2 G phi + sp di)/s, so that the work is G.
Mode 1 uses (cn, s1, G1, dp1, du1), mode 2 (ct, s2, G2, dp2, du2); mixed jumps blend them linearly
with the mixity m = ut^2/(ut^2 + <un>+^2) (Fracas's rule).

Deck helpers (doc/fracture.md §1): the node perturbation that breaks a regular mesh's
straight lines, the widest safe alert distance of the see rules, the full-separation
opening of an MP3_CZM interface and a smooth drive ramp.

    from fracas_tools.cohesive import perturb_nodes, safe_alert, mp3_separation_opening, see_alert
    c = 50 * young / h                                    # cohesive stiffness, C h / E = 50 (doc/fracture.md §2)
    alert = see_alert(mesh, mp3_separation_opening(gc, smax, c))
"""

import math

import numpy as np

from .mailx import ELEMENT_CORNERS, element_edges

__all__ = ["Law", "mac_rate_curve", "ramp_schedule", "BETA_BROKEN",
           "perturb_nodes", "safe_alert", "mp3_separation_opening", "see_alert", "smooth_ramp"]


def perturb_nodes(mesh, fraction, seed=1):
    """Move the interior nodes of a Mesh2D (not on the boundary nor on any edge
    group: notches and loaded edges stay straight) by a random offset uniform in a
    disc of radius fraction x the shortest edge at the node (seeded: the same mesh
    every time). Breaks the straight lines of a regular mesh, along which cracks
    would otherwise run (czm.md §4.2, nodal perturbation). Elements stay valid for
    fraction < 0.5; a node whose move would turn an element over is left in place."""
    from .mesh import Mesh2D
    rng = np.random.default_rng(seed)
    xy = mesh.nodes.copy()
    fixed = set()
    for key, sharing in mesh.edges().items():
        if len(sharing) == 1:
            fixed.update(key)
    for edges in mesh.edge_groups.values():
        for a, b in edges:
            fixed.update((a, b))
    shortest = np.full(len(xy), np.inf)
    around = [[] for _ in range(len(xy))]
    for e, (kind, nodes) in enumerate(mesh.elements):
        for a, b, _ in element_edges(kind, nodes):
            d = float(np.hypot(*(xy[a] - xy[b])))
            shortest[a] = min(shortest[a], d)
            shortest[b] = min(shortest[b], d)
            around[a].append(e)

    def area(e, pts):
        kind, nodes = mesh.elements[e]
        c = pts[list(nodes[:ELEMENT_CORNERS[kind]])]
        return 0.5 * np.sum(c[:, 0] * np.roll(c[:, 1], -1) - np.roll(c[:, 0], -1) * c[:, 1])

    for n in range(len(xy)):
        r = fraction * shortest[n] * np.sqrt(rng.random())
        phi = 2.0 * np.pi * rng.random()
        if n in fixed or not np.isfinite(shortest[n]):
            continue
        old = xy[n].copy()
        xy[n] = old + r * np.array([np.cos(phi), np.sin(phi)])
        if any(area(e, xy) <= 0.0 for e in around[n]):
            xy[n] = old
    return Mesh2D(xy, mesh.elements, mesh.phases, {k: v.tolist() for k, v in mesh.node_groups.items()},
                  mesh.edge_groups)


def safe_alert(mesh, apab=(0.25, 0.75)):
    """The largest alert distance that glues every CLxxx point of an exploded mesh
    to its own partner only: the smallest distance from a candidate point (at apab
    on an element edge) to another edge of an element sharing a corner with it.
    The see rules glue, at the first step, every candidate/antagonist pair of the
    family within the alert distance, whatever its gap: a wider alert glues a point
    to a neighbour's edge with a gap of the order of the alert, an initially
    stretched spring (a large spurious energy). The alert should also exceed the
    law's full-separation opening, so that a contact is not dropped before it is
    broken."""
    edges_at = {}
    for kind, nodes in mesh.elements:
        for a, b, _ in element_edges(kind, nodes):
            e = (a, b)
            for n in e:
                edges_at.setdefault(n, set()).add((min(e), max(e)))
    xy = mesh.nodes
    best = np.inf
    for (a, b), _ in mesh.edges().items():
        others = (edges_at[a] | edges_at[b]) - {(a, b)}
        for s in apab:
            p = (1.0 - s) * xy[a] + s * xy[b]
            for c, d in others:
                u = xy[d] - xy[c]
                t = np.clip(np.dot(p - xy[c], u) / np.dot(u, u), 0.0, 1.0)
                best = min(best, float(np.hypot(*(p - xy[c] - t * u))))
    return best


def mp3_separation_opening(gc, smax, c):
    """An upper bound of the opening at full separation of an MP3_CZM interface (energy
    gc, strength smax, stiffness c in both directions): smax / c + 1.5 gc / smax, the
    law's own opening Law.mp3(c, c, smax, gc).d_end(1) = 0.25 smax / c + 1.5 gc / smax
    plus 0.75 smax / c. Alert distances of the cohesive see rules are set from it (kept
    as the decks were generated with it; the law itself is Law)."""
    return 1.5 * gc / smax + smax / c


def smooth_ramp(t_ramp, n=41, t_end=1.0e3):
    """(t, f) points of f = (1 - cos(pi t / t_ramp)) / 2 up to t_ramp, then 1: a drive
    that starts with zero acceleration and reaches its value without a kink (few
    waves excited)."""
    t = np.linspace(0.0, t_ramp, n)
    f = 0.5 * (1.0 - np.cos(np.pi * t / t_ramp))
    return np.vstack([np.append(t, t_end), np.append(f, 1.0)]).T


def see_alert(mesh, d_c, factor=10.0):
    """The alert distance of the cohesive see rules: factor x the full-separation
    opening d_c (a contact is not dropped before it is broken), capped at half of
    safe_alert(mesh) (no point glued to a neighbour's edge). The validation cases and
    the demos use it. Raises ValueError when even d_c does not fit under that cap (the
    mesh is too fine for the law: a smaller opening, or a coarser mesh)."""
    cap = 0.5 * safe_alert(mesh)
    if d_c >= cap:
        raise ValueError(f"the full-separation opening {d_c:g} does not fit under half the safe alert "
                         f"{cap:g} of this mesh: raise C or smax, or coarsen the mesh")
    return min(factor * d_c, cap)


# --------------------------------------------------------------------------------------
# the laws
# --------------------------------------------------------------------------------------

BETA_BROKEN = 1.0e-12


class Law:
    """One cohesive law: family 'MAC', 'MP3', 'MAL', 'TH', 'EXPO' or 'ABP' and its parameters."""

    def __init__(self, family, **p):
        self.family = family.upper()
        self.p = dict(p)
        for k, v in p.items():
            setattr(self, k, float(v))

    # -- constructors with LMGC90's parameter names --
    @classmethod
    def mac(cls, cn, ct, b, w):
        return cls("MAC", cn=cn, ct=ct, b=b, w=w)

    @classmethod
    def mp3(cls, cn, ct, smax, w):
        return cls("MP3", cn=cn, ct=ct, smax=smax, w=w)

    @classmethod
    def mal(cls, cn, ct, s1, s2, G1, G2):
        return cls("MAL", cn=cn, ct=ct, s1=s1, s2=s2, G1=G1, G2=G2)

    @classmethod
    def th(cls, cn, ct, s1, s2, G1, G2, dp1, dp2):
        return cls("TH", cn=cn, ct=ct, s1=s1, s2=s2, G1=G1, G2=G2, dp1=dp1, dp2=dp2)

    @classmethod
    def expo(cls, cn, ct, s1, s2, G1, G2, eta):
        return cls("EXPO", cn=cn, ct=ct, s1=s1, s2=s2, G1=G1, G2=G2, eta=eta)

    @classmethod
    def abp(cls, cn, ct, s1, s2, G1, G2, du1, du2, phi):
        return cls("ABP", cn=cn, ct=ct, s1=s1, s2=s2, G1=G1, G2=G2, du1=du1, du2=du2, phi=phi)

    @property
    def k(self):
        """Exponent of beta in the traction beta^k C [u]."""
        return 2 if self.family == "MAC" else 1

    def c(self, mode):
        return self.cn if mode == 1 else self.ct

    # -- per-mode parameters of the envelope laws --
    def _mode(self, mode):
        """(c, s, G, di) in a pure mode for the envelope laws."""
        c = self.c(mode)
        if self.family == "MP3":
            s, g = self.smax, self.w
            di = 0.5 * s * (1.0 / self.cn + 1.0 / self.ct)
        else:
            s = self.s1 if mode == 1 else self.s2
            g = self.G1 if mode == 1 else self.G2
            di = s / c
        return c, s, g, di

    def breakpoints(self, mode):
        """Jumps where the quasi-static curve has a kink (peak, end of plateau, cut-off)."""
        if self.family == "MAC":
            return [math.sqrt(self.w / self.c(mode))]
        c, s, g, di = self._mode(mode)
        if self.family in ("MP3", "MAL"):
            return [di, di + 1.5 * (g / s - 0.5 * di)]
        if self.family == "TH":
            dp = max(di, self.dp1 if mode == 1 else self.dp2)
            return [di, dp, 2.0 * g / s - dp + di]
        if self.family == "ABP":
            dp, sp, du = self.abp_corners(1.0 if mode == 2 else 0.0, s, g, di)
            return [di, dp, du]
        phi = s / (g - 0.5 * s * di)
        return [di, di - math.log(self.eta) / phi]

    def d_peak(self, mode):
        """Jump at the peak stress (start of damage)."""
        return self.breakpoints(mode)[0]

    def d_end(self, mode):
        """Jump of full separation (math.inf for MAC, whose beta only tends to 0)."""
        return math.inf if self.family == "MAC" else self.breakpoints(mode)[-1]

    def beta(self, d, mode):
        """Quasi-static beta after a monotonic pure-mode path up to d (b = 0 for MAC)."""
        d = np.asarray(d, dtype=float)
        if self.family == "MAC":
            c = self.c(mode)
            with np.errstate(divide="ignore"):
                b = np.where(d > 0.0, np.minimum(1.0, self.w / (c * d * d)), 1.0)
            return np.where(b < BETA_BROKEN, 0.0, b)
        c, s, g, di = self._mode(mode)
        dd = np.maximum(d, 1e-300)
        if self.family in ("MP3", "MAL"):
            dk = 1.5 * (g / s - 0.5 * di)
            soft = (di / dd) * (1.0 - ((dd - di) / dk) ** 2)
            b = np.where(d <= di, 1.0, np.where(d < di + dk, soft, 0.0))
        elif self.family == "TH":
            dp = max(di, self.dp1 if mode == 1 else self.dp2)
            du = 2.0 * g / s - dp + di
            b = np.where(d <= di, 1.0, np.where(d <= dp, di / dd,
                         np.where(d < du, (di / dd) * (du - dd) / (du - dp), 0.0)))
        elif self.family == "ABP":
            dp, sp, du = self.abp_corners(1.0 if mode == 2 else 0.0, s, g, di)
            first = (s + (sp - s) * (dd - di) / max(dp - di, 1e-300)) / (c * dd)
            b = np.where(d <= di, 1.0, np.where(d <= dp, first,
                         np.where(d < du, sp * (du - dd) / ((du - dp) * c * dd), 0.0)))
        else:
            phi = s / (g - 0.5 * s * di)
            du = di - math.log(self.eta) / phi
            b = np.where(d <= di, 1.0, np.where(d < du, (s / (c * dd)) * np.exp(phi * (di - dd)), 0.0))
        return np.where(b < BETA_BROKEN, 0.0, b)

    def sigma(self, d, mode):
        """Quasi-static traction beta^k c d on a monotonic pure-mode path."""
        d = np.asarray(d, dtype=float)
        return self.beta(d, mode) ** self.k * self.c(mode) * d

    def peak(self, mode):
        """Peak stress: sqrt(c w) (MAC), smax (MP3 with cn = ct; cn di in general), s1/s2."""
        return float(self.sigma(self.d_peak(mode), mode))

    def fracture_energy(self, mode):
        """Work of full separation: w (MAC, MP3 with cn = ct), G1/G2 (MAL, TH, ABP),
        G - eta (G - s di/2) (EXPO, the cut-off tail removed)."""
        if self.family == "MAC":
            return self.w
        c, s, g, di = self._mode(mode)
        if self.family == "MP3":
            dk = 1.5 * (g / s - 0.5 * di)
            return 0.5 * c * di * di + 2.0 / 3.0 * c * di * dk
        if self.family == "EXPO":
            return g - self.eta * (g - 0.5 * s * di)
        return g

    def nominal_energy(self, mode):
        """The energy parameter of the law: w (MAC, MP3), G1 or G2 (MAL, TH, EXPO, ABP)."""
        if self.family in ("MAC", "MP3"):
            return self.w
        return self.G1 if mode == 1 else self.G2

    def work(self, d, mode):
        """Work int_0^d sigma on a monotonic path (closed form for MAC, quadrature else)."""
        if self.family == "MAC":
            c = self.c(mode)
            d0 = math.sqrt(self.w / c)
            return 0.5 * c * d * d if d <= d0 else self.w - 0.5 * self.w * (d0 / d) ** 2
        pts = sorted({0.0, *[b for b in self.breakpoints(mode) if b < d], d})
        tot = 0.0
        for a, b in zip(pts[:-1], pts[1:]):
            x, wts = np.polynomial.legendre.leggauss(40)
            xs = 0.5 * (b - a) * x + 0.5 * (a + b)
            tot += 0.5 * (b - a) * float(np.sum(wts * self.sigma(xs, mode)))
        return tot

    def stored(self, d, mode):
        """Energy left in the spring at d: (1/2) beta^k c d^2."""
        return 0.5 * float(self.beta(d, mode)) ** self.k * self.c(mode) * d * d

    def damage(self, d, mode):
        """Energy dissipated by damage up to d: work - stored (MAC: w (1 - (d0/d)^2))."""
        return self.work(d, mode) - self.stored(d, mode)

    # -- the solver's functions, mirrored line by line (modules/behaviours/fracas_czm.f90) --
    def envelope(self, ut, un):
        """(c, s, g, di, m) of an envelope law (not MAC) in the mode of the jump (ut, un):
        mixity m = ut^2/(ut^2 + <un>+^2), the mode I and II parameters blended linearly
        (fracas_czm: envelope)."""
        unp = max(un, 0.0)
        m = 0.0
        if ut != 0.0:
            m = ut * ut / (ut * ut + unp * unp)
        c = (1.0 - m) * self.cn + m * self.ct
        if self.family == "MP3":
            s, g = self.smax, self.w
            di = 0.5 * s * (1.0 / self.cn + 1.0 / self.ct)
        else:
            s = (1.0 - m) * self.s1 + m * self.s2
            g = (1.0 - m) * self.G1 + m * self.G2
            di = s / c
        return c, s, g, di, m

    def abp_corners(self, m, s, g, di):
        """ABP: (dp, sp, du) in the mode of mixity m, du blended linearly, dp kept in
        [di, du] (fracas_czm: czm_abp_corners)."""
        du = (1.0 - m) * self.du1 + m * self.du2
        sp = 2.0 * g * (1.0 - self.phi) / du
        dp = min(du, max(di, (2.0 * g * self.phi + sp * di) / s))
        return dp, sp, du

    def update(self, beta_old, ut, un, h):
        """beta at the end of a step of length h from beta_old and the end-of-step jumps
        (ut, un): never larger than beta_old, 0 below BETA_BROKEN (czm_beta_update)."""
        beta = beta_old
        if beta_old <= 0.0:
            return beta
        unp = max(un, 0.0)
        if self.family == "MAC":
            # implicit Euler of b beta' = -(w - beta Y)^-, Y = cn <un>+^2 + ct ut^2
            y = self.cn * unp * unp + self.ct * ut * ut
            if beta_old * y > self.w:
                beta = min(beta_old, (h * self.w + self.b * beta_old) / (self.b + h * y))
        else:
            d = math.sqrt(unp * unp + ut * ut)
            if d <= 0.0:
                return beta
            c, s, g, di, m = self.envelope(ut, un)
            if d <= di:
                return beta
            if self.family in ("MP3", "MAL"):
                dk = 1.5 * (g / s - 0.5 * di)
                beta = min(beta_old, (di / d) * (1.0 - ((d - di) / dk) ** 2)) if d < di + dk else 0.0
            elif self.family == "TH":
                dp = max(di, (1.0 - m) * self.dp1 + m * self.dp2)
                du = 2.0 * g / s - dp + di
                if d <= dp:
                    beta = min(beta_old, di / d)
                elif d < du:
                    beta = min(beta_old, (di / d) * (du - d) / (du - dp))
                else:
                    beta = 0.0
            elif self.family == "ABP":
                dp, sp, du = self.abp_corners(m, s, g, di)
                if d <= dp:
                    beta = min(beta_old, (s + (sp - s) * (d - di) / (dp - di)) / (c * d))
                elif d < du:
                    beta = min(beta_old, sp * (du - d) / ((du - dp) * c * d))
                else:
                    beta = 0.0
            else:
                phi = s / (g - 0.5 * s * di)
                du = di - math.log(self.eta) / phi
                beta = min(beta_old, (s / (c * d)) * math.exp(phi * (di - d))) if d < du else 0.0
        return 0.0 if beta < BETA_BROKEN else beta

    def stored_energy(self, beta, ut, un):
        """Energy per unit length in the springs: (1/2) beta^k (cn un^2 + ct ut^2)
        (czm_stored_energy; the springs act in both directions)."""
        return 0.5 * beta ** self.k * (self.cn * un * un + self.ct * ut * ut)

    def damage_energy(self, beta, ut, un):
        """Energy per unit length dissipated once the damage is beta, on a monotonic path
        in the mode of the jump (ut, un): the envelope's work up to the opening where it
        gives beta, less (1/2) beta c d^2; MAC: w (1 - beta) (czm_damage_energy)."""
        if self.family == "MAC":
            return self.w * (1.0 - beta)
        c, s, g, di, m = self.envelope(ut, un)
        if self.family in ("MP3", "MAL"):
            dk = 1.5 * (g / s - 0.5 * di)
            x = min(1.0, (-beta * dk + math.sqrt((beta * dk) ** 2 + 4.0 * di * di * (1.0 - beta))) / (2.0 * di))
            d = di + dk * x
            e = 0.5 * c * di * di + c * di * dk * (x - x ** 3 / 3.0) - 0.5 * beta * c * d * d
        elif self.family == "TH":
            dp = max(di, (1.0 - m) * self.dp1 + m * self.dp2)
            du = 2.0 * g / s - dp + di
            if beta * dp >= di:
                d = di / beta                                   # on the plateau
                e = 0.5 * s * di + s * (d - di)
            else:
                d = di * du / (beta * (du - dp) + di)            # on the linear decay
                e = 0.5 * s * di + s * (dp - di) + s * ((d - dp) - 0.5 * (d - dp) ** 2 / (du - dp))
            e = e - 0.5 * beta * c * d * d
        elif self.family == "ABP":
            dp, sp, du = self.abp_corners(m, s, g, di)
            if beta <= 0.0:
                e = g
            elif dp > di and beta * c * dp >= sp:
                a = (sp - s) / (dp - di)                     # on the first branch: beta c d = s + a (d - di)
                d = (s - a * di) / (beta * c - a)
                e = 0.5 * s * di + 0.5 * (d - di) * (s + beta * c * d) - 0.5 * beta * c * d * d
            else:
                d = sp * du / (beta * c * (du - dp) + sp)    # on the second: beta c d = sp (du - d)/(du - dp)
                e = (0.5 * s * di + 0.5 * (dp - di) * (s + sp) + 0.5 * (d - dp) * (sp + beta * c * d)
                     - 0.5 * beta * c * d * d)
        else:
            # EXPO: the opening of beta by Newton on log(c d beta / s) + phi (d - di) = 0, bracketed
            phi = s / (g - 0.5 * s * di)
            du = di - math.log(self.eta) / phi
            d = du
            if beta > 0.0:
                lo, hi, d = di, du, di
                for _ in range(100):
                    f = math.log(c * d * beta / s) + phi * (d - di)
                    if abs(f) <= 1.0e-14:
                        break
                    if f > 0.0:
                        hi = d
                    else:
                        lo = d
                    d = d - f / (1.0 / d + phi)
                    if d <= lo or d >= hi:
                        d = 0.5 * (lo + hi)
            e = 0.5 * s * di + (s / phi) * (1.0 - math.exp(phi * (di - d))) - 0.5 * beta * c * d * d
        return max(0.0, e)

    def step_dissipation(self, beta0, beta1, ut, un, h):
        """Energy per unit length dissipated by a step taking beta0 to beta1 at the
        end-of-step jump (ut, un): D(beta1) - D(beta0), plus b (beta0 - beta1)^2 / h for
        the viscous MAC law (czm_step_dissipation)."""
        if beta1 >= beta0:
            return 0.0
        e = max(0.0, self.damage_energy(beta1, ut, un) - self.damage_energy(beta0, ut, un))
        if self.family == "MAC":
            e += self.b * (beta0 - beta1) ** 2 / h
        return e

    def step_factor(self, beta0, beta1, u0, u1, h):
        """The factor f of the cohesive traction f C (u0 + u1)/2 of a step with damage
        solved within it (u0, u1: (ut, un) at the step's start and end): beta0^k while
        the step does not damage, else the value whose work over the step is the law's
        energy change plus dissipation, in [beta1^k, beta0^k] ([0, beta0^k] for a viscous
        MAC law); beta1^k where the springs are not stretched (czm_step_factor)."""
        f = beta0 ** self.k
        if beta1 >= beta0:
            return f
        den = 0.5 * (self.ct * (u1[0] ** 2 - u0[0] ** 2) + self.cn * (u1[1] ** 2 - u0[1] ** 2))
        if den <= 0.0:
            return beta1 ** self.k
        work = (self.stored_energy(beta1, u1[0], u1[1]) - self.stored_energy(beta0, u0[0], u0[1])
                + self.step_dissipation(beta0, beta1, u1[0], u1[1], h))
        # rate-independent: the mean of a factor falling from beta0^k to beta1^k lies
        # between them; a viscous MAC law damages at rest and may fall below beta1^k
        lo = 0.0 if self.family == "MAC" and self.b > 0.0 else beta1 ** self.k
        return min(beta0 ** self.k, max(lo, work / den))

    @classmethod
    def of_deck(cls, law):
        """The Law of a deck's cohesive contact law (a fracas_tools ContactLaw read from
        TACT_BEHAV.DAT: IQS_MAC_CZM, MAC_CZM, MP3_CZM, (IQS_)MAL_CZM, (IQS_)TH_CZM,
        (IQS_)EXPO_CZM, (IQS_)ABP_CZM)."""
        name = law.law.upper()
        family = name[4:] if name.startswith("IQS_") else name
        if not family.endswith("_CZM") or family[:-4] not in ("MAC", "MP3", "MAL", "TH", "EXPO", "ABP"):
            raise ValueError(f"{law.law}: not a cohesive law of the solver")
        family = family[:-4]
        keys = {"MAC": ("cn", "ct", "b", "w"), "MP3": ("cn", "ct", "smax", "w"),
                "MAL": ("cn", "ct", "s1", "s2", "G1", "G2"),
                "TH": ("cn", "ct", "s1", "s2", "G1", "G2", "dp1", "dp2"),
                "EXPO": ("cn", "ct", "s1", "s2", "G1", "G2", "eta"),
                "ABP": ("cn", "ct", "s1", "s2", "G1", "G2", "du1", "du2", "phi")}[family]
        # LMGC90's own decks label them 'S1  =', 'Du1 =', 'Phi =': case does not matter
        given = {k.lower(): v for k, v in law.params.items()}
        missing = [k for k in keys if k.lower() not in given]
        if missing:
            raise ValueError(f"{law.law} {law.name}: parameters {', '.join(missing)} not found")
        return cls(family, **{k: given[k.lower()] for k in keys})

    def lmgc90_params(self):
        """(law name suffix, parameters, layout) for fracas_tools Case.add_law."""
        f = self.family
        base = [["dyfr", "stfr"], ["cn", "ct"]]
        if f == "MAC":
            return base + [["b", "w"]], ["b", "w"]
        if f == "MP3":
            return base + [["smax", "w"]], ["smax", "w"]
        tail = [["s1", "s2"], ["G1", "G2"]]
        if f == "TH":
            return base + tail + [["dp1", "dp2"]], ["s1", "s2", "G1", "G2", "dp1", "dp2"]
        if f == "EXPO":
            return base + tail + [["eta"]], ["s1", "s2", "G1", "G2", "eta"]
        if f == "ABP":
            return base + tail + [["du1", "du2"], ["phi"]], ["s1", "s2", "G1", "G2", "du1", "du2", "phi"]
        return base + tail, ["s1", "s2", "G1", "G2"]

    def add_to(self, case, nickname, law_name, mu):
        """Add this law to a fracas_tools Case with LMGC90's layout (friction dyfr = stfr = mu)."""
        layout, keys = self.lmgc90_params()
        params = dict(dyfr=mu, stfr=mu, cn=self.cn, ct=self.ct)
        params.update({k: self.p[k] for k in keys})
        return case.add_law(nickname, law_name, layout=layout, **params)


def mac_rate_curve(law, u_of_t, t_end, n=200000, mode=1):
    """MAC with viscosity b > 0 along an imposed jump u(t) (continuous in time):
    integrate b beta' = -(w - beta Y)^-, Y = c u^2, with RK4 on n steps of [0, t_end].
    Returns t, u, beta, sigma = beta^2 c u (numpy arrays)."""
    c = law.c(mode)
    t = np.linspace(0.0, t_end, n + 1)
    dt = t[1] - t[0]

    def f(tt, bb):
        u = u_of_t(tt)
        return -max(0.0, bb * c * u * u - law.w) / law.b

    beta = np.empty(n + 1)
    beta[0] = 1.0
    b = 1.0
    for i in range(n):
        ti = t[i]
        k1 = f(ti, b)
        k2 = f(ti + 0.5 * dt, b + 0.5 * dt * k1)
        k3 = f(ti + 0.5 * dt, b + 0.5 * dt * k2)
        k4 = f(ti + dt, b + dt * k3)
        b = min(b, b + dt * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0)
        beta[i + 1] = b
    u = np.array([u_of_t(x) for x in t])
    return t, u, beta, beta ** 2 * c * u


def ramp_schedule(d_peak, d_end, dt, elastic=4.0e-3, near=0.95, fine=1.0e-3, switch=1.25,
                  growth=1.0 / 400.0):
    """Driven jump velocity for a monotonic test: a jump increment of elastic*d_peak per
    step up to near*d_peak, fine*d_peak per step up to switch*d_peak, then growing by
    `growth` of itself per step (u = u1 exp((t - t1)/tau), tau = dt/growth) to d_end.
    Returns (n1, n2, table): steps of the uniform phases and of the geometric phase, and
    the (t, v) table of the evolution file (a few points past the end)."""
    ne = int(round(near / elastic))
    nf = int(round((switch - near) / fine))
    n1 = ne + nf
    n2 = int(math.ceil(math.log(d_end / (switch * d_peak)) / growth))
    ve, vf = elastic * d_peak / dt, fine * d_peak / dt
    tau = dt / growth
    table = [[0.0, ve], [ne * dt, ve], [(ne + 1) * dt, vf], [n1 * dt, vf]]
    table += [[(n1 + j) * dt, switch * d_peak / tau * math.exp(j * growth)] for j in range(1, n2 + 11)]
    return n1, n2, table
