"""Pre-processing: build a Fracas case (an LMGC90-compatible DATBOX) from Python.

A :class:`Case` holds materials, contact laws, visibility (see) rules, gravity,
RBDY2 bodies with their contactors (DISKx, xKSID, JONCx, POLYG, several per body
allowed), driven degrees of freedom, the initial state and the run control.
``Case.write(case_dir)`` writes ``case_dir/DATBOX/`` in LMGC90's fixed-column
formats (the layout pylmgc90.pre writes, column for column) plus our
``COMMAND.DAT``; :func:`fracas_tools.datbox.read_case` reads it back.

Example::

    from fracas_tools import Case
    case = Case(gravity=(0.0, -9.81))
    case.add_material("STONE", density=2600.0)
    b = case.add_disk((0.0, 0.1), 0.1, "STONE", color="BLEUx")
    b.set_velocity(1.0, 0.0, 0.0)
    ...
    case.run.set(time_step=1e-3, number_of_steps=1000)
    case.write("my_case")
"""

import math
import warnings
from pathlib import Path

import numpy as np

from .fortran_io import e14

__all__ = [
    "Case", "Scene", "Body", "Disk", "Xksid", "Jonc", "Polygon", "Material", "ContactLaw",
    "SeeRule", "DrivenDof", "RunControl", "LAW_LAYOUT", "BULK_LAYOUT", "COMMAND_KEYWORDS",
    "polygon_area", "polygon_centroid", "polygon_polar_moment", "is_convex",
]

# --------------------------------------------------------------------------------------
# contact laws: parameter names and LMGC90's line layout (pairs per line)
# --------------------------------------------------------------------------------------

#: Parameter layout per contact law, as LMGC90 reads them: one inner list per line
#: of TACT_BEHAV.DAT (one or two parameters per line), in LMGC90's parameter order.
LAW_LAYOUT = {
    "IQS_CLB": [["fric"]],
    "IQS_CLB_g0": [["fric"]],
    "GAP_SGR_CLB": [["fric"]],
    "VEL_SGR_CLB": [["fric"]],
    "IQS_DS_CLB": [["dyfr", "stfr"]],
    "GAP_SGR_DS_CLB": [["dyfr", "stfr"]],
    "RST_CLB": [["rstn", "rstt"], ["fric"]],
    "IQS_MAC_CZM": [["dyfr", "stfr"], ["cn", "ct"], ["b", "w"]],
    "MAC_CZM": [["dyfr", "stfr"], ["cn", "ct"], ["b", "w"]],
}

CONTACTOR_KINDS = ("DISKx", "xKSID", "JONCx", "POLYG")


def _label(key):
    """The 5-character label written in front of a value: 'fric=', 'cn  ='."""
    return (key[:4]).ljust(4) + "="


def _check_name(name, what):
    if not isinstance(name, str) or len(name) != 5 or " " in name:
        raise ValueError(f"{what} {name!r} must be exactly 5 characters without blanks "
                         f"(LMGC90 nicknames, e.g. 'STONE', 'BLEUx', 'iqsdd')")
    return name


# --------------------------------------------------------------------------------------
# polygon geometry (per unit area density)
# --------------------------------------------------------------------------------------

def polygon_area(v):
    """Signed area of a polygon (positive when counter-clockwise)."""
    v = np.asarray(v, dtype=float)
    x, y = v[:, 0], v[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def polygon_centroid(v):
    """Centroid of a simple polygon."""
    v = np.asarray(v, dtype=float)
    x, y = v[:, 0], v[:, 1]
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    c = x * y1 - x1 * y
    a = 0.5 * np.sum(c)
    if a == 0.0:
        raise ValueError("degenerate polygon (zero area)")
    return np.array([np.sum((x + x1) * c) / (6.0 * a), np.sum((y + y1) * c) / (6.0 * a)])


def polygon_polar_moment(v):
    """Polar second moment of area about the origin (for a counter-clockwise polygon)."""
    v = np.asarray(v, dtype=float)
    x, y = v[:, 0], v[:, 1]
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    c = x * y1 - x1 * y
    return float(np.sum(c * (x * x + x * x1 + x1 * x1 + y * y + y * y1 + y1 * y1)) / 12.0)


def is_convex(v, tol=1e-12):
    """True if the counter-clockwise polygon v is convex (collinear vertices allowed)."""
    v = np.asarray(v, dtype=float)
    e = np.roll(v, -1, axis=0) - v
    cross = e[:, 0] * np.roll(e, -1, axis=0)[:, 1] - e[:, 1] * np.roll(e, -1, axis=0)[:, 0]
    scale = float(np.max(np.abs(v))) ** 2 if len(v) else 1.0
    return bool(np.all(cross >= -tol * max(scale, 1e-300)))


# --------------------------------------------------------------------------------------
# contactors
# --------------------------------------------------------------------------------------

class Disk:
    """DISKx contactor centred on the body node."""
    kind = "DISKx"

    def __init__(self, radius, color="BLEUx"):
        if not radius > 0.0:
            raise ValueError(f"disk radius must be positive, got {radius}")
        self.radius = float(radius)
        self.color = _check_name(color, "colour")

    def area(self):
        return math.pi * self.radius ** 2

    def polar_moment(self):
        return 0.5 * math.pi * self.radius ** 4

    def lines(self, rank):
        return [f" DISKx{rank:7d}  color  {self.color}  byrd={e14(self.radius, 'E')}"]

    def __repr__(self):
        return f"Disk(radius={self.radius!r}, color={self.color!r})"


class Xksid:
    """xKSID contactor: the inner boundary of a hollow disk (a drum) of this radius."""
    kind = "xKSID"

    def __init__(self, radius, color="DRUMx"):
        if not radius > 0.0:
            raise ValueError(f"xKSID radius must be positive, got {radius}")
        self.radius = float(radius)
        self.color = _check_name(color, "colour")

    def area(self):
        return None      # no mass properties: pylmgc90 writes avrd = gyrd = 0

    def polar_moment(self):
        return None

    def lines(self, rank):
        return [f" xKSID{rank:7d}  color  {self.color}  byrd={e14(self.radius, 'E')}"]

    def __repr__(self):
        return f"Xksid(radius={self.radius!r}, color={self.color!r})"


class Jonc:
    """JONCx contactor: a wall of half length ax1 (along the body x axis) and half
    thickness ax2 with rounded ends, centred on the body node."""
    kind = "JONCx"

    def __init__(self, ax1, ax2, color="WALLx"):
        if not (ax1 > 0.0 and ax2 > 0.0):
            raise ValueError(f"JONCx half sizes must be positive, got {ax1}, {ax2}")
        self.ax1, self.ax2 = float(ax1), float(ax2)
        self.color = _check_name(color, "colour")

    def area(self):
        return 4.0 * self.ax1 * self.ax2 + math.pi * self.ax2 ** 2

    def polar_moment(self):
        # pylmgc90.pre's convention (reproduced so that avrd/gyrd match its decks):
        # rectangle part 4*a1*a2*(a1^2 + a2^2)/2, plus a disk of radius a2 at distance a1.
        a1, a2 = self.ax1, self.ax2
        return 2.0 * a1 * a2 * (a1 * a1 + a2 * a2) + math.pi * a2 * a2 * (a1 * a1 + 0.5 * a2 * a2)

    def lines(self, rank):
        return [f" JONCx{rank:7d}  color  {self.color}  axe1={e14(self.ax1, 'E')}"
                f"  axe2={e14(self.ax2, 'E')}"]

    def __repr__(self):
        return f"Jonc(ax1={self.ax1!r}, ax2={self.ax2!r}, color={self.color!r})"


class Polygon:
    """POLYG contactor: convex polygon, vertices counter-clockwise, relative to the
    body node (in the body's reference orientation)."""
    kind = "POLYG"

    def __init__(self, vertices, color="BLEUx", check=True):
        v = np.array(vertices, dtype=float)
        if v.ndim != 2 or v.shape[1] != 2 or v.shape[0] < 3:
            raise ValueError("a polygon needs an (n, 2) array of n >= 3 vertices")
        if check:
            a = polygon_area(v)
            if a <= 0.0:
                raise ValueError("polygon vertices must be counter-clockwise (signed area "
                                 f"{a:.6g} <= 0); reverse them, e.g. vertices[::-1]")
            if not is_convex(v):
                raise ValueError("POLYG contactors must be convex; split a non-convex shape "
                                 "into convex parts on one body (add_polygon_cluster)")
        self.vertices = v
        self.color = _check_name(color, "colour")

    def area(self):
        return polygon_area(self.vertices)

    def polar_moment(self):
        return polygon_polar_moment(self.vertices)

    def lines(self, rank):
        out = [f" POLYG{rank:7d}  color  {self.color}  nb_vertex={len(self.vertices):7d}"]
        for x, y in self.vertices:
            out.append(" " * 29 + f"coo1={e14(x, 'E')}  coo2={e14(y, 'E')}")
        return out

    def __repr__(self):
        return f"Polygon({len(self.vertices)} vertices, color={self.color!r})"


# --------------------------------------------------------------------------------------
# driven dofs, bodies
# --------------------------------------------------------------------------------------

class DrivenDof:
    """An imposed velocity ('vlocy') or added force ('force') on one dof (1: x, 2: y,
    3: rotation). value(t) = (ct + amp*cos(omega*t + phi)) * min(1, rampi + ramp*t),
    or, if ``evolution`` names a file in DATBOX, the piecewise-linear interpolation
    of its two columns (t, value); ``evolution_data`` (n, 2), if given, is written to
    that file by Case.write."""

    def __init__(self, dof, kind="vlocy", ct=0.0, amp=0.0, omega=0.0, phi=0.0, rampi=1.0,
                 ramp=0.0, evolution=None, evolution_data=None):
        if dof not in (1, 2, 3):
            raise ValueError(f"RBDY2 dof must be 1, 2 or 3, got {dof}")
        if kind not in ("vlocy", "force"):
            raise ValueError(f"driven dof kind must be 'vlocy' or 'force', got {kind!r}")
        self.dof, self.kind = int(dof), kind
        self.node = None             # node number (1-based) on a MAILx body; None on RBDY2
        self.ct, self.amp, self.omega, self.phi = float(ct), float(amp), float(omega), float(phi)
        self.rampi, self.ramp = float(rampi), float(ramp)
        self.evolution = evolution
        if evolution is not None:
            if not evolution or len(evolution) > 40 or " " in evolution:
                raise ValueError(f"evolution file name {evolution!r}: 1-40 characters, no blanks")
        self.evolution_data = None
        self.evolution_text = None    # the file text as read, rewritten unchanged
        if evolution_data is not None:
            d = np.array(evolution_data, dtype=float)
            if d.ndim != 2 or d.shape[1] != 2:
                raise ValueError("evolution_data must be an (n, 2) array of (t, value)")
            if np.any(np.diff(d[:, 0]) <= 0.0):
                raise ValueError("evolution times must be strictly increasing")
            self.evolution_data = d

    def value(self, t):
        """The imposed value at time t (numpy-vectorised)."""
        t = np.asarray(t, dtype=float)
        if self.evolution is not None:
            if self.evolution_data is None:
                raise ValueError(f"evolution file {self.evolution} was not loaded")
            d = self.evolution_data
            if len(d) == 1:
                return np.full_like(t, d[0, 1])
            # piecewise linear, end segments extrapolated (as LMGC90)
            i = np.clip(np.searchsorted(d[:, 0], t) - 1, 0, len(d) - 2)
            t0, t1, v0, v1 = d[i, 0], d[i + 1, 0], d[i, 1], d[i + 1, 1]
            return v0 + (v1 - v0) * (t - t0) / (t1 - t0)
        return (self.ct + self.amp * np.cos(self.omega * t + self.phi)) * \
            np.minimum(1.0, self.rampi + self.ramp * t)

    def line(self):
        if self.evolution is not None:
            return f" {self.kind}{self.dof:7d} evolution {self.evolution}"
        vals = (self.ct, self.amp, self.omega, self.phi, self.rampi, self.ramp)
        return f" {self.kind}{self.dof:7d}" + "".join(" " + e14(x) for x in vals)

    def __repr__(self):
        if self.node is not None:
            return f"DrivenDof(node={self.node}, {self.dof}, {self.kind!r}, ct={self.ct}, ramp={self.ramp})"
        if self.evolution:
            return f"DrivenDof({self.dof}, {self.kind!r}, evolution={self.evolution!r})"
        return (f"DrivenDof({self.dof}, {self.kind!r}, ct={self.ct}, amp={self.amp}, "
                f"omega={self.omega}, phi={self.phi}, rampi={self.rampi}, ramp={self.ramp})")


class Body:
    """An RBDY2 body: a material, a reference node (x, y, angle), one or more
    contactors, an initial state (displacement X and velocity V from the reference,
    written to DOF.INI when non-zero) and driven dofs.

    avrd/gyrd (average and gyration radius, mass = density*pi*avrd^2, inertia =
    mass*gyrd^2) are computed from the contactors when left to None (as pylmgc90.pre
    does); a value read from a file is kept as read."""

    def __init__(self, material, center=(0.0, 0.0), angle=0.0, model="RBDY2",
                 avrd=None, gyrd=None):
        self.material = _check_name(material, "material")
        self.model = model
        self.coor = np.array([float(center[0]), float(center[1]), float(angle)])
        self.contactors = []
        self.avrd, self.gyrd = avrd, gyrd
        self.x0 = np.zeros(3)
        self.v0 = np.zeros(3)
        self.driven = []
        self.number = None        # serial number, set when added to a Case

    # -- contactors --
    def add_disk(self, radius, color="BLEUx"):
        self.contactors.append(Disk(radius, color))
        return self

    def add_xksid(self, radius, color="DRUMx"):
        self.contactors.append(Xksid(radius, color))
        return self

    def add_jonc(self, ax1, ax2, color="WALLx"):
        self.contactors.append(Jonc(ax1, ax2, color))
        return self

    def add_polygon(self, vertices, color="BLEUx"):
        """Add a POLYG with vertices relative to the body node."""
        self.contactors.append(Polygon(vertices, color))
        return self

    # -- mass properties --
    def mass_properties(self):
        """(area, polar moment about the node) per unit density, or None when a
        contactor (xKSID) has none."""
        if not self.contactors:
            return None
        a = j = 0.0
        for c in self.contactors:
            ca = c.area()
            if ca is None:
                return None
            a += ca
            j += c.polar_moment()
        return a, j

    def radii(self):
        """(avrd, gyrd) as written in BODIES.DAT."""
        if self.avrd is not None and self.gyrd is not None:
            return float(self.avrd), float(self.gyrd)
        mp = self.mass_properties()
        if mp is None:
            av, gy = 0.0, 0.0
        else:
            a, j = mp
            av, gy = math.sqrt(a / math.pi), math.sqrt(j / a)
        return (float(self.avrd) if self.avrd is not None else av,
                float(self.gyrd) if self.gyrd is not None else gy)

    def mass(self, density):
        av, _ = self.radii()
        return density * math.pi * av * av

    # -- initial state --
    def set_velocity(self, vx=0.0, vy=0.0, omega=0.0):
        """Initial velocity (vx, vy, spin), written to DOF.INI."""
        self.v0 = np.array([vx, vy, omega], dtype=float)
        return self

    def set_displacement(self, dx=0.0, dy=0.0, rotation=0.0):
        """Initial displacement from the reference node (DOF.INI X)."""
        self.x0 = np.array([dx, dy, rotation], dtype=float)
        return self

    def rotate(self, angle):
        """Rotate the body about its node by ``angle`` (rad, counter-clockwise), the
        LMGC90 way: the geometry in BODIES.DAT stays unrotated and the angle goes to
        DOF.INI as X(3)."""
        self.x0[2] += float(angle)
        return self

    # -- driven dofs --
    def impose_velocity(self, dofs=(1, 2, 3), ct=0.0, amp=0.0, omega=0.0, phi=0.0,
                        rampi=1.0, ramp=0.0):
        """Drive the velocity of one dof or a list of dofs (1: x, 2: y, 3: rotation)."""
        for d in np.atleast_1d(dofs):
            self.driven.append(DrivenDof(int(d), "vlocy", ct, amp, omega, phi, rampi, ramp))
        return self

    def impose_force(self, dofs, ct=0.0, amp=0.0, omega=0.0, phi=0.0, rampi=1.0, ramp=0.0):
        """Add a driven force on one dof or a list of dofs."""
        for d in np.atleast_1d(dofs):
            self.driven.append(DrivenDof(int(d), "force", ct, amp, omega, phi, rampi, ramp))
        return self

    def impose_evolution(self, dof, kind, file, data=None):
        """Drive a dof from a DATBOX file of two columns (t, value); ``data`` (n, 2)
        is written to DATBOX/file by Case.write."""
        self.driven.append(DrivenDof(dof, kind, evolution=file, evolution_data=data))
        return self

    def fix(self):
        """Clamp the body: the three velocities driven to zero."""
        return self.impose_velocity((1, 2, 3))

    @property
    def center(self):
        return self.coor[:2].copy()

    def __repr__(self):
        return (f"Body(number={self.number}, material={self.material!r}, "
                f"center=({self.coor[0]:.6g}, {self.coor[1]:.6g}), contactors={self.contactors})")


# --------------------------------------------------------------------------------------
# materials, laws, see rules
# --------------------------------------------------------------------------------------

#: Continuation lines of the bulk laws, as pylmgc90 writes them: an option line
#: ('elas', 'standard') or a line of one or two numbers [labels]. Numbers are
#: given by keyword: young (EYng), poisson (Epss), yield_stress (SIG0), hardening
#: (K___, linear isotropic hardening: sigma_y = SIG0 + K___ p).
BULK_LAYOUT = {
    "RIGID": [],
    "ELAS": [("elas", "standard"), ("ani_", "isotropic"), ["EYng", "Epss"]],
    "ELAS_PLAS": [("elas", "standard"), ("ani_", "isotropic"), ["EYng", "Epss"],
                  ("crit", "Von-Mises"), ("isoh", "linear"), ["SIG0", "K___"],
                  ("cinh", "none"), ("visc", "none")],
}
_BULK_KEYS = {"young": "EYng", "poisson": "Epss", "yield_stress": "SIG0", "hardening": "K___"}


class Material:
    """A bulk behaviour of BULK_BEHAV.DAT: 'RIGID' with a density for rigid bodies,
    'ELAS' (young, poisson) or 'ELAS_PLAS' (young, poisson, yield_stress, hardening:
    von Mises with linear isotropic hardening) for meshed bodies.

    ``items`` holds the continuation lines in order: ('label', 'text') options and
    lists of (label, value) numbers; a file read back keeps them as read, so unknown
    laws and options are rewritten unchanged."""

    def __init__(self, name, density, law="RIGID", items=None, **params):
        self.name = _check_name(name, "material")
        self.law = law
        self.density = float(density)
        if len(law) > 30:
            raise ValueError("bulk law name longer than 30 characters")
        if items is not None:
            if params:
                raise ValueError("give either items or parameters")
            self.items = [i if isinstance(i, tuple) else [(l, float(v)) for l, v in i] for i in items]
            return
        unknown = set(params) - set(_BULK_KEYS)
        if unknown:
            raise ValueError(f"unknown material parameters {sorted(unknown)}; known: {list(_BULK_KEYS)}")
        if law not in BULK_LAYOUT:
            if params:
                raise ValueError(f"bulk law {law}: parameters by keyword only for "
                                 f"{', '.join(BULK_LAYOUT)} (else give items)")
            self.items = []
            return
        labels = {_BULK_KEYS[k]: v for k, v in params.items()}
        need = [l for line in BULK_LAYOUT[law] if isinstance(line, list) for l in line]
        missing = [k for k, l in _BULK_KEYS.items() if l in need and l not in labels]
        extra = [k for k, l in _BULK_KEYS.items() if l in labels and l not in need]
        if missing or extra:
            raise ValueError(f"bulk law {law}: "
                             + (f"missing {missing} " if missing else "")
                             + (f"unexpected {extra}" if extra else ""))
        self.items = [line if isinstance(line, tuple) else [(l, float(labels[l])) for l in line]
                      for line in BULK_LAYOUT[law]]
        if law != "RIGID":
            if not self.young > 0.0:
                raise ValueError(f"material {name}: young must be positive")
            if not -1.0 < self.poisson < 0.5:
                raise ValueError(f"material {name}: poisson must be in (-1, 0.5)")

    def param(self, label):
        """A number by its label ('EYng', 'Epss', 'SIG0', 'K___'; case-insensitive)."""
        for it in self.items:
            if isinstance(it, list):
                for lab, v in it:
                    if lab.lower() == label.lower():
                        return v
        return None

    def option(self, label):
        """An option by its label ('elas', 'ani_', 'crit', 'isoh' ...)."""
        for it in self.items:
            if isinstance(it, tuple) and it[0].lower() == label.lower():
                return it[1]
        return None

    young = property(lambda self: self.param("EYng"))
    poisson = property(lambda self: self.param("Epss"))
    yield_stress = property(lambda self: self.param("SIG0"))
    hardening = property(lambda self: self.param("K___"))

    def lines(self):
        out = [f" {self.name}  {self.law.ljust(30)}  Umas={e14(self.density)}"]
        for it in self.items:
            if isinstance(it, tuple):
                out.append(" " * 40 + f"{it[0]}: {it[1]:<13}")
            else:
                out.append(" " * 40 + "  ".join(f"{lab}={e14(v)}" for lab, v in it))
        return out

    def __repr__(self):
        extra = "".join(f", {k}={getattr(self, k)!r}" for k in _BULK_KEYS if getattr(self, k) is not None)
        return f"Material({self.name!r}, density={self.density!r}, law={self.law!r}{extra})"


class ContactLaw:
    """A contact law of TACT_BEHAV.DAT: nickname (5 chars), LMGC90 law name and
    parameters in LMGC90's order. ``layout`` gives the lines (lists of 1 or 2 keys);
    it defaults to LAW_LAYOUT for the known laws. ``labels`` maps a key to the
    5-character label written before its value (default 'fric=', 'cn  =', ...)."""

    def __init__(self, name, law, layout=None, labels=None, **params):
        self.name = _check_name(name, "contact law")
        if not law or len(law) > 30:
            raise ValueError(f"law name {law!r}: 1 to 30 characters")
        self.law = law
        if layout is None:
            if law in LAW_LAYOUT:
                layout = LAW_LAYOUT[law]
            else:
                keys = list(params)
                layout = [keys[i:i + 2] for i in range(0, len(keys), 2)]
        self.layout = [list(line) for line in layout]
        keys = [k for line in self.layout for k in line]
        if any(len(line) not in (1, 2) for line in self.layout):
            raise ValueError("each parameter line holds 1 or 2 parameters")
        missing = [k for k in keys if k not in params]
        extra = [k for k in params if k not in keys]
        if missing or extra:
            raise ValueError(f"law {law}: parameters must be exactly {keys}"
                             + (f"; missing {missing}" if missing else "")
                             + (f"; unexpected {extra}" if extra else ""))
        self.params = {k: float(params[k]) for k in keys}
        self.labels = {k: _label(k) for k in keys}
        if labels:
            for k, lab in labels.items():
                if len(lab) != 5:
                    raise ValueError(f"label {lab!r} must be 5 characters")
                self.labels[k] = lab

    def lines(self):
        out = []
        for i, line in enumerate(self.layout):
            head = f" {self.name}  {self.law.ljust(30)}  " if i == 0 else " " * 40
            pairs = "  ".join(f"{self.labels[k]}{e14(self.params[k])}" for k in line)
            out.append(head + pairs)
        return out

    def __getitem__(self, key):
        return self.params[key]

    def __repr__(self):
        p = ", ".join(f"{k}={v!r}" for k, v in self.params.items())
        return f"ContactLaw({self.name!r}, {self.law!r}, {p})"


class SeeRule:
    """A $seety visibility rule: candidate (body, contactor, colour) sees antagonist
    (body, contactor, colour) through law ``behav`` within ``alert``."""

    def __init__(self, cdtac, cdcol, behav, antac, ancol, alert, cdbdy="RBDY2",
                 anbdy="RBDY2", global_alert=None):
        self.cdbdy, self.anbdy = _check_name(cdbdy, "body model"), _check_name(anbdy, "body model")
        self.cdtac, self.antac = _check_name(cdtac, "contactor type"), _check_name(antac, "contactor type")
        self.cdcol, self.ancol = _check_name(cdcol, "colour"), _check_name(ancol, "colour")
        self.behav = _check_name(behav, "contact law")
        self.alert = float(alert)
        if not self.alert > 0.0:
            raise ValueError(f"alert distance must be positive, got {alert}")
        self.global_alert = None if global_alert is None else float(global_alert)

    def lines(self):
        out = ["$seety",
               " cdbdy  cdtac  cdcol  behav  anbdy  antac  ancol       alert",
               f" {self.cdbdy}  {self.cdtac}  {self.cdcol}  {self.behav}  {self.anbdy}  "
               f"{self.antac}  {self.ancol}      {e14(self.alert)}"]
        if self.global_alert is not None:
            out.append("+" + " " * 53 + e14(self.global_alert))
        return out

    def __repr__(self):
        return (f"SeeRule({self.cdtac}/{self.cdcol} -> {self.antac}/{self.ancol}, "
                f"law={self.behav!r}, alert={self.alert!r})")


# --------------------------------------------------------------------------------------
# run control (COMMAND.DAT)
# --------------------------------------------------------------------------------------

#: COMMAND.DAT keywords in the order they are written, with their type and the
#: accepted values for the string keywords.
COMMAND_KEYWORDS = {
    "time_step": float,
    "number_of_steps": int,
    "final_time": float,
    "theta": float,
    "detection_frequency": int,
    "nlgs_check": ("Quad", "Maxm", "QM/16"),
    "nlgs_tolerance": float,
    "nlgs_relaxation": float,
    "nlgs_sweeps_per_check": int,
    "nlgs_max_checks": int,
    "nlgs_order": ("stored", "reversed", "shuffled", "colored"),
    "nlgs_seed": int,
    "output_dof_every": int,
    "output_vtk_every": int,
    "output_hdf5_every": int,
    "output_restart_every": int,
    "progress_every": int,
    "nlgs_unconverged": ("warn", "fail", "stop"),
    "output_vtk_disks": ("points", "polygons"),
    "output_vtk_precision": ("single", "double"),
    "cohesive_damage": ("implicit", "explicit", "lmgc90"),
    "crack_step_limit": float,
    "crack_step_cuts": int,
    # meshed bodies
    "plane": ("strain", "stress", "axisym"),
    "newton_tolerance": float,
    "newton_max_iterations": int,
    "linear_solver": ("auto", "dense", "cholmod"),
}

_POSITIVE = {"time_step", "number_of_steps", "final_time", "detection_frequency", "crack_step_cuts",
             "nlgs_tolerance", "nlgs_sweeps_per_check", "nlgs_max_checks",
             "newton_tolerance", "newton_max_iterations"}
_NONNEGATIVE = {"output_dof_every", "output_vtk_every", "output_hdf5_every", "output_restart_every",
                "progress_every", "crack_step_limit"}


class RunControl:
    """The run-control deck DATBOX/COMMAND.DAT: only the keywords set are written
    (the solver has defaults for the others); time_step and number_of_steps or
    final_time are required."""

    def __init__(self, **kw):
        self.values = {}
        self.set(**kw)

    def set(self, **kw):
        """Set keywords; setting number_of_steps drops final_time and the other way
        round (as the solver's --set does)."""
        for k, v in kw.items():
            k = k.lower()
            self.values[k] = self._convert(k, v)
            other = {"number_of_steps": "final_time", "final_time": "number_of_steps"}.get(k)
            if other:
                self.values.pop(other, None)
        return self

    @staticmethod
    def _convert(k, v, where=""):
        if k not in COMMAND_KEYWORDS:
            raise ValueError(f"{where}unknown COMMAND.DAT keyword {k!r}; known: "
                             + ", ".join(COMMAND_KEYWORDS))
        t = COMMAND_KEYWORDS[k]
        if isinstance(t, tuple):
            canon = {x.lower(): x for x in t}
            if not isinstance(v, str) or v.lower() not in canon:
                raise ValueError(f"{where}{k} must be one of {', '.join(t)}, got {v!r}")
            return canon[v.lower()]
        try:
            if t is int:
                if isinstance(v, str):
                    v = int(v)
                elif float(v) != int(v):
                    raise ValueError
                v = int(v)
            else:
                v = float(str(v).replace("D", "e").replace("d", "e")) if isinstance(v, str) else float(v)
        except (TypeError, ValueError, OverflowError):
            raise ValueError(f"{where}{k} needs {'an integer' if t is int else 'a real'} value, "
                             f"got {v!r}") from None
        if t is float and not math.isfinite(v):
            raise ValueError(f"{where}{k} must be finite, got {v!r}")
        if k in _POSITIVE and not v > 0:
            raise ValueError(f"{where}{k} must be positive, got {v!r}")
        if k in _NONNEGATIVE and v < 0:
            raise ValueError(f"{where}{k} must be >= 0, got {v!r}")
        if k == "theta" and not 0.5 <= v <= 1.0:
            raise ValueError(f"{where}theta must be in [0.5, 1], got {v!r}")
        if k == "nlgs_relaxation" and not 0.0 < v < 2.0:
            raise ValueError(f"{where}nlgs_relaxation must be in (0, 2), got {v!r}")
        return v

    def __getitem__(self, k):
        return self.values[k]

    def get(self, k, default=None):
        return self.values.get(k, default)

    def is_empty(self):
        return not self.values

    def check(self):
        if "time_step" not in self.values:
            raise ValueError("COMMAND.DAT: time_step is required (case.run.set(time_step=...))")
        if "number_of_steps" not in self.values and "final_time" not in self.values:
            raise ValueError("COMMAND.DAT: number_of_steps or final_time is required")

    @staticmethod
    def format_value(v):
        if isinstance(v, str):
            return v
        if isinstance(v, int):
            return str(v)
        return repr(float(v))

    def lines(self):
        self.check()
        out = ["! Fracas run control (keyword value; '!' or '#' start a comment)"]
        for k in COMMAND_KEYWORDS:
            if k in self.values:
                out.append(f"{k} {self.format_value(self.values[k])}")
        return out

    def __repr__(self):
        return "RunControl(" + ", ".join(f"{k}={v!r}" for k, v in self.values.items()) + ")"


# --------------------------------------------------------------------------------------
# the case
# --------------------------------------------------------------------------------------

_DOF_HEADER = ("$dofty  numbr [CT......+......AMP..*..cos.(..OMEGA.*.time.+.PHI..)]...*..."
               "[RAMPI.....+.....RAMP.*.time]")


class Case:
    """A complete case: DATBOX content plus run control.

    Attributes: gravity (3 values), materials (dict name -> Material), laws (dict
    name -> ContactLaw), see_rules (list), bodies (list of Body (RBDY2) and
    MeshBody (MAILx) in file order; numbered 1.. within each model, as LMGC90
    does), models (dict name -> Model, MODELS.DAT), run (RunControl),
    dof_step/dof_time (DOF.INI header), postpro (PostPro or None: POSTPRO.DAT),
    vloc_ini / gpv_ini (VlocRloc / GpvFile read from Vloc_Rloc.INI / GPV.INI, or
    None: header only)."""

    def __init__(self, gravity=(0.0, -9.81, 0.0)):
        g = list(gravity) + [0.0] * (3 - len(gravity))
        self.gravity = np.array(g[:3], dtype=float)
        self.materials = {}
        self.models = {}
        self.laws = {}
        self.see_rules = []
        self.bodies = []
        self.run = RunControl()
        self.dof_step, self.dof_time = 0, 0.0
        self.postpro = None
        self.vloc_ini = None
        self.gpv_ini = None

    # -- materials, laws, rules --
    def add_material(self, name, density, law="RIGID", **params):
        """A bulk material: add_material('STONE', 2600.0) (rigid),
        add_material('BLOCK', 2000.0, 'ELAS', young=1e9, poisson=0.3),
        add_material('STEEL', 7800.0, 'ELAS_PLAS', young=2e11, poisson=0.3,
        yield_stress=2e8, hardening=2e9)."""
        if name in self.materials:
            raise ValueError(f"material {name!r} already defined")
        m = Material(name, density, law, **params)
        self.materials[name] = m
        return m

    def add_model(self, name, element, **options):
        """A MODELS.DAT model for meshed bodies, e.g. add_model('M2DT3', 'T3xxx')
        (small strain, elastic, lumped mass), add_model('M2DJ2', 'Q4P0x',
        kinematic='large', formulation='UpdtL', material='J2iso'); see mailx.Model."""
        from .mailx import Model
        if name in self.models:
            raise ValueError(f"model {name!r} already defined")
        m = Model(name, element, **options)
        self.models[name] = m
        return m

    def add_law(self, name, law, **params):
        """Add a contact law, e.g. add_law('iqsdd', 'IQS_CLB', fric=0.3),
        add_law('iqsds', 'IQS_DS_CLB', dyfr=0.4, stfr=0.5),
        add_law('rstcw', 'RST_CLB', rstn=0.3, rstt=0.0, fric=0.5),
        add_law('gapcl', 'GAP_SGR_CLB', fric=0.3),
        add_law('macz1', 'IQS_MAC_CZM', dyfr=.73, stfr=.73, cn=1e10, ct=1e11, b=0., w=40.)."""
        if name in self.laws:
            raise ValueError(f"contact law {name!r} already defined")
        c = ContactLaw(name, law, **params)
        self.laws[name] = c
        return c

    def add_see(self, cdtac, cdcol, antac, ancol, law, alert, cdbdy=None, anbdy=None,
                global_alert=None):
        """Candidate contactors (cdtac, cdcol) see antagonists (antac, ancol) through
        contact law ``law`` (name or ContactLaw) within distance ``alert``. The body
        models default to MAILx for CLxxx/ALpxx contactors, RBDY2 otherwise."""
        def model_of(tac):
            return "MAILx" if tac in ("CLxxx", "ALpxx") else "RBDY2"
        cdbdy = cdbdy or model_of(cdtac)
        anbdy = anbdy or model_of(antac)
        name = law.name if isinstance(law, ContactLaw) else law
        r = SeeRule(cdtac, cdcol, name, antac, ancol, alert, cdbdy, anbdy, global_alert)
        self.see_rules.append(r)
        return r

    def set_gravity(self, gx, gy, gz=0.0):
        self.gravity = np.array([gx, gy, gz], dtype=float)

    # -- bodies --
    def add_body(self, material, center=(0.0, 0.0), angle=0.0, avrd=None, gyrd=None):
        """Add an empty RBDY2 body at ``center``; give it contactors with
        body.add_disk / add_jonc / add_polygon / add_xksid."""
        b = Body(material, center, angle, avrd=avrd, gyrd=gyrd)
        return self.append(b)

    def _new(self, material, center, contactor):
        """Append a body with one contactor (built first, so that an invalid
        contactor leaves the case unchanged)."""
        b = Body(material, center)
        b.contactors.append(contactor)
        return self.append(b)

    def append(self, body):
        """Add a Body or MeshBody; its number is its rank within its model."""
        self.bodies.append(body)
        # Bodies per model, kept between calls (an exploded mesh appends 1e5 bodies:
        # counting them all each time was quadratic); recounted if bodies were added
        # to the list directly.
        counts = getattr(self, "_model_counts", None)
        if counts is None or self._counted != len(self.bodies) - 1:
            counts = {}
            for b in self.bodies[:-1]:
                counts[b.model] = counts.get(b.model, 0) + 1
        counts[body.model] = counts.get(body.model, 0) + 1
        body.number = counts[body.model]
        self._model_counts, self._counted = counts, len(self.bodies)
        return body

    def body(self, model, number):
        """The body ``number`` of ``model`` ('RBDY2' or 'MAILx')."""
        for b in self.bodies:
            if b.model == model and b.number == number:
                return b
        raise KeyError(f"no {model} body {number}")

    def mesh_bodies(self):
        return [b for b in self.bodies if b.model == "MAILx"]

    def add_mesh_body(self, nodes, elements=(), model=None, material=None):
        """A MAILx body from nodes (n, 2) and elements: Element objects, or node
        lists (1-based; kind from the node count: 3 T3xxx, 4 Q4xxx, 6 T6xxx,
        8 Q8xxx) given ``model`` and ``material``. Add contactors with
        body.add_candidates / add_polyline (see fracas_tools.mesh for gmsh meshes)."""
        from .mailx import ELEMENT_NODES, Element, MeshBody
        kinds = {n: k for k, n in ELEMENT_NODES.items()}
        b = MeshBody(nodes)
        for e in elements:
            if not isinstance(e, Element):
                e = Element(kinds.get(len(e), "?"), e, model, material)
            b.add_element(e)
        return self.append(b)

    def add_mesh(self, mesh, material, model=None, bodies=None):
        """MAILx bodies from a mesh.Mesh2D (e.g. mesh.mesh_geo('part.geo')): one
        body per connected part of each physical surface (or per group of phases in
        ``bodies``); ``material``/``model`` a nickname or {phase: nickname}; model
        None adds default models M2DT3/M2DQ4/M2DT6/M2DQ8. Physical curves and points
        become body.groups / body.edge_groups. Returns the list of bodies."""
        from .mesh import build_bodies
        return build_bodies(self, mesh, material, model, bodies)

    def add_exploded_mesh(self, mesh, material, model=None, **options):
        """One MAILx body per element of a mesh.Mesh2D, every shared edge glued by a
        CLxxx/ALpxx pair coloured by its interface family; see mesh.explode for
        the options (apab, cracks, color, boundary_color, group_copies). Returns a
        mesh.Exploded (bodies, families, counts)."""
        from .mesh import explode
        return explode(self, mesh, material, model, **options)

    def add_disk(self, center, radius, material, color="BLEUx"):
        """A rigid disk (DISKx) centred at ``center``."""
        return self._new(material, center, Disk(radius, color))

    def add_xksid(self, center, radius, material, color="DRUMx"):
        """A hollow disk (drum) of inner radius ``radius`` (xKSID)."""
        return self._new(material, center, Xksid(radius, color))

    def add_jonc(self, center, half_length, half_thickness, material, color="WALLx", angle=0.0):
        """A JONCx wall; ``angle`` rotates it (written as DOF.INI X(3), like pylmgc90)."""
        b = self._new(material, center, Jonc(half_length, half_thickness, color))
        if angle:
            b.rotate(angle)
        return b

    def add_polygon(self, vertices, material, color="BLEUx", center=None):
        """A rigid convex polygon (POLYG). ``vertices`` (n, 2), counter-clockwise,
        in absolute coordinates; the body node is put at the polygon centroid.
        With ``center`` given, the vertices are relative to that node instead."""
        v = np.asarray(vertices, dtype=float)
        if center is None:
            c = polygon_centroid(v) if polygon_area(v) > 0.0 else v.mean(axis=0)
            return self._new(material, c, Polygon(v - c, color))
        return self._new(material, center, Polygon(v, color))

    def add_polygon_cluster(self, polygons, material, color="BLEUx"):
        """One rigid body made of several convex polygons (absolute vertices), e.g.
        a non-convex block; the node is put at the centroid of the union."""
        polys = [np.asarray(p, dtype=float) for p in polygons]
        areas = np.array([polygon_area(p) for p in polys])
        cents = np.array([polygon_centroid(p) for p in polys])
        c = (areas[:, None] * cents).sum(axis=0) / areas.sum()
        b = Body(material, c)
        for p in polys:
            b.add_polygon(p - c, color)
        return self.append(b)

    # -- checks --
    def check(self):
        """Consistency checks; returns a list of warnings, raises on errors."""
        warns = []
        for b in self.bodies:
            if b.model == "MAILx":
                self._check_mesh_body(b)
                continue
            if b.material not in self.materials:
                raise ValueError(f"body {b.number}: material {b.material!r} is not defined "
                                 f"(add_material)")
            if not b.contactors:
                raise ValueError(f"body {b.number} has no contactor")
            for c in b.contactors:
                if c.kind == "POLYG" and polygon_area(c.vertices) <= 0.0:
                    raise ValueError(f"body {b.number}: POLYG vertices are not counter-clockwise")
            seen = set()
            for d in b.driven:
                if (d.kind, d.dof) in seen:
                    raise ValueError(f"body {b.number}: dof {d.dof} driven twice ({d.kind})")
                seen.add((d.kind, d.dof))
        for r in self.see_rules:
            if r.behav not in self.laws:
                raise ValueError(f"see rule {r}: contact law {r.behav!r} is not defined (add_law)")
        used = {(c.kind, c.color) for b in self.bodies for c in b.contactors}
        covered = {(r.cdtac, r.cdcol) for r in self.see_rules} | \
                  {(r.antac, r.ancol) for r in self.see_rules}
        for kind, color in sorted(used - covered):
            warns.append(f"no see rule mentions {kind}/{color}: those contactors never interact")
        names = [r.behav for r in self.see_rules]
        for name in self.laws:
            if name not in names:
                warns.append(f"contact law {name!r} is used by no see rule")
        return warns

    def _check_mesh_body(self, b):
        if not b.elements:
            raise ValueError(f"MAILx {b.number} has no element")
        for m in b.materials():
            if m not in self.materials:
                raise ValueError(f"MAILx {b.number}: material {m!r} is not defined (add_material)")
            if self.materials[m].law == "RIGID":
                raise ValueError(f"MAILx {b.number}: material {m!r} is RIGID; meshed bodies need "
                                 f"ELAS or ELAS_PLAS")
        for m in b.model_names():
            if m not in self.models:
                raise ValueError(f"MAILx {b.number}: model {m!r} is not defined (add_model)")
        # as the solver's MODELS.DAT check: the model suits the element's geometry,
        # the material law suits the model's 'mater' option
        for e in b.elements:
            model = self.models[e.model]
            geometry = "Q4xxx" if model.element == "Q4P0x" else model.element
            if geometry != e.kind:
                raise ValueError(f"MAILx {b.number}: model {e.model!r} ({model.element}) is not for "
                                 f"{e.kind} elements")
            need = "ELAS_PLAS" if model.options.get("mater") == "J2iso" else "ELAS"
            if self.materials[e.material].law != need:
                raise ValueError(f"MAILx {b.number}: material {e.material!r} "
                                 f"({self.materials[e.material].law}) does not suit model {e.model!r}: "
                                 f"'mater {model.options.get('mater')}' needs an {need} material")
        seen = set()
        for d in b.driven:
            if d.dof not in (1, 2):
                raise ValueError(f"MAILx {b.number} node {d.node}: dof {d.dof} (a node has dofs 1, 2)")
            if (d.node, d.kind, d.dof) in seen:
                raise ValueError(f"MAILx {b.number} node {d.node}: dof {d.dof} driven twice ({d.kind})")
            seen.add((d.node, d.kind, d.dof))

    # -- text of each file --
    def bodies_text(self):
        out = []
        for b in self.bodies:
            if b.model == "MAILx":
                out += b.bodies_lines()
                continue
            av, gy = b.radii()
            out += ["$bdyty", f" {b.model}{b.number:7d}", "$blmty",
                    f" PLAIN      1  behav  {b.material}  avrd={e14(av, 'E')}  gyrd={e14(gy, 'E')}",
                    "$nodty",
                    " NO3xx      1" + " " * 16 + f"coo1={e14(b.coor[0], 'E')}  coo2={e14(b.coor[1], 'E')}"
                    f"  coo3={e14(b.coor[2], 'E')}  ",
                    "$tacty" + " " * 66]
            for rank, c in enumerate(b.contactors, start=1):
                out += c.lines(rank)
            out.append("$$$$$$")
        out.append("      ")
        return "\n".join(out) + "\n"

    def bulk_behav_text(self):
        out = ["! File BEHAVIOUR (written by fracas_tools)",
               "",
               "! '$gravy': gravity components at columns 25-38, 46-59, 67-80.",
               "! '$behav': material nickname (columns 2-6), bulk law (9-38),",
               "!           density 'Umas=' value at columns 46-59.",
               "!",
               "",
               " " * 72,
               "$gravy  ",
               " " * 19 + f"grv1={e14(self.gravity[0])}  grv2={e14(self.gravity[1])}"
               f"  grv3={e14(self.gravity[2])}"]
        for m in self.materials.values():
            out += ["$behav  lawty"] + m.lines()
        out.append("      ")
        return "\n".join(out) + "\n"

    def models_text(self):
        out = ["! File MODELS (written by fracas_tools)",
               "!",
               "! '$model': nickname (columns 2-6) on its own line, then physics (9-13),",
               "!           finite element (16-20), options (23-27) and values (30-).",
               ""]
        for m in self.models.values():
            out += m.lines()
        out.append("      ")
        return "\n".join(out) + "\n"

    def tact_behav_text(self):
        out = [""]
        for law in self.laws.values():
            out += ["$behav "] + law.lines() + ["      "]
        for r in self.see_rules:
            out += r.lines() + ["      "]
        out.append("      ")
        return "\n".join(out) + "\n"

    def drv_dof_text(self):
        out = ["! DOF"]
        for b in self.bodies:
            if not b.driven:
                continue
            if b.model == "MAILx":
                out += b.drv_dof_lines(_DOF_HEADER)
                continue
            # pylmgc90 ends the number at column 13; LMGC90 reads I7 at 9-15, so
            # numbers of 6 digits or more use that layout
            num = f"{b.number:7d}" if b.number < 100000 else f"  {b.number:7d}"
            out += ["$bdyty", f" {b.model}{num}", "$nodty", " NO3xx      1", _DOF_HEADER]
            out += [d.line() for d in b.driven]
            out += ["$$$$$$", ""]
        out.append("      ")
        return "\n".join(out) + "\n"

    def dof_ini_text(self):
        """DOF.INI: the bodies with a non-zero initial state (all nodes of a MAILx body)."""
        from .outbox import DofFile, DofRecord
        d = DofFile(self.dof_step, self.dof_time, style="pre")
        for b in self.bodies:
            if b.model == "MAILx":
                if b.has_state():
                    d.records.append(DofRecord("MAILx", b.number, b.x0, b.v0,
                                               list(range(1, b.n_nodes + 1)), b.physics))
            elif np.any(b.x0 != 0.0) or np.any(b.v0 != 0.0):
                d.records.append(DofRecord(b.model, b.number, b.x0, b.v0))
        return d.text()

    def vloc_rloc_ini_text(self):
        from .outbox import VlocRloc
        v = self.vloc_ini if self.vloc_ini is not None else VlocRloc(self.dof_step, self.dof_time,
                                                                     style="pre")
        return v.text()

    def gpv_ini_text(self):
        from .outbox import GpvFile
        g = self.gpv_ini if self.gpv_ini is not None else GpvFile(self.dof_step, self.dof_time,
                                                                  style="pre")
        return g.text()

    def command_text(self):
        return "\n".join(self.run.lines()) + "\n"

    def write(self, case_dir, command=None):
        """Write case_dir/DATBOX/{BODIES.DAT, BULK_BEHAV.DAT, TACT_BEHAV.DAT,
        DRV_DOF.DAT, DOF.INI, Vloc_Rloc.INI, COMMAND.DAT} and the evolution files;
        with meshed bodies also MODELS.DAT (when models exist) and GPV.INI, and
        POSTPRO.DAT when case.postpro is set.
        COMMAND.DAT is written when run settings exist (command=None) or always
        (command=True, an error if time_step/number_of_steps are missing) or
        never (command=False). Returns the DATBOX path."""
        for w in self.check():
            warnings.warn(w, stacklevel=2)
        if command is None:
            command = not self.run.is_empty()
        if command:
            self.run.check()
        datbox = Path(case_dir) / "DATBOX"
        datbox.mkdir(parents=True, exist_ok=True)
        files = {"BODIES.DAT": self.bodies_text(), "BULK_BEHAV.DAT": self.bulk_behav_text(),
                 "TACT_BEHAV.DAT": self.tact_behav_text(), "DRV_DOF.DAT": self.drv_dof_text(),
                 "DOF.INI": self.dof_ini_text(), "Vloc_Rloc.INI": self.vloc_rloc_ini_text()}
        if self.models:
            files["MODELS.DAT"] = self.models_text()
        if self.mesh_bodies() or self.gpv_ini is not None:
            files["GPV.INI"] = self.gpv_ini_text()
        if self.postpro is not None:
            files["POSTPRO.DAT"] = self.postpro.text()
        if command:
            files["COMMAND.DAT"] = self.command_text()
        for b in self.bodies:
            for d in b.driven:
                if d.evolution is None:
                    continue
                if getattr(d, "evolution_text", None):
                    files[d.evolution] = d.evolution_text
                elif d.evolution_data is not None:
                    files[d.evolution] = "".join("%14.7e %14.7e\n" % (t, y)
                                                 for t, y in d.evolution_data)
                elif not (datbox / d.evolution).exists():
                    warnings.warn(f"body {b.number}: evolution file {d.evolution} has no data "
                                  f"and does not exist in {datbox}", stacklevel=2)
        for name, text in files.items():
            with open(datbox / name, "w", newline="\n") as f:
                f.write(text)
        if not command:
            warnings.warn("no run settings: COMMAND.DAT not written "
                          "(case.run.set(time_step=..., number_of_steps=...))", stacklevel=2)
        return datbox

    # -- reading --
    @classmethod
    def read(cls, case_dir):
        """Read case_dir/DATBOX back into a Case (see fracas_tools.datbox.read_case)."""
        from .datbox import read_case
        return read_case(case_dir)

    # -- summaries --
    def body_kinds(self):
        """Per body, the set of its contactor kinds."""
        return [{c.kind for c in b.contactors} for b in self.bodies]

    def summary(self):
        kinds = {}
        for b in self.bodies:
            k = "+".join(sorted({c.kind for c in b.contactors}))
            if b.model == "MAILx":
                k = "MAILx" + (f" ({k})" if k else "")
            kinds[k] = kinds.get(k, 0) + 1
        lines = [f"{len(self.bodies)} bodies: " + ", ".join(f"{n} {k}" for k, n in kinds.items()),
                 f"gravity: {tuple(float(g) for g in self.gravity)}",
                 "materials: " + ", ".join(f"{m.name} ({m.law}, {m.density:g})"
                                           for m in self.materials.values()),
                 *([ "models: " + ", ".join(f"{m.name} ({m.element})" for m in self.models.values())]
                   if self.models else []),
                 *self._mesh_summary(),
                 "laws: " + ", ".join(f"{l.name} {l.law} " +
                                      " ".join(f"{k}={v:g}" for k, v in l.params.items())
                                      for l in self.laws.values()),
                 f"see rules: {len(self.see_rules)}",
                 f"driven bodies: {sum(1 for b in self.bodies if b.driven)}",
                 f"bodies with an initial state: "
                 f"{sum(1 for b in self.bodies if np.any(b.x0 != 0) or np.any(b.v0 != 0))}",
                 "run: " + (", ".join(f"{k}={v}" for k, v in self.run.values.items()) or "(none)")]
        return "\n".join(lines)

    def _mesh_summary(self):
        meshes = self.mesh_bodies()
        if not meshes:
            return []
        kinds = {}
        for b in meshes:
            for e in b.elements:
                kinds[e.kind] = kinds.get(e.kind, 0) + 1
        return [f"MAILx: {len(meshes)} bodies, {sum(b.n_nodes for b in meshes)} nodes, "
                + ", ".join(f"{n} {k}" for k, n in kinds.items())
                + f", {sum(len(b.tactors()) for b in meshes)} contactors"]

    def __repr__(self):
        return (f"Case({len(self.bodies)} bodies, {len(self.materials)} materials, "
                f"{len(self.laws)} laws, {len(self.see_rules)} see rules)")


#: Alias: a Scene is a Case.
Scene = Case
