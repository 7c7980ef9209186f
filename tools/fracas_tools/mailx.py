"""Meshed (MAILx) bodies, their contactors and MODELS.DAT models.

A :class:`MeshBody` is one LMGC90 MAILx body: 2D nodes (NO2xx), elements (T3xxx,
Q4xxx, T6xxx, Q8xxx, each with a MODELS.DAT model and a BULK_BEHAV.DAT material),
contactors on its nodes (:class:`Candidates` = CLxxx, :class:`Polyline` = ALpxx),
driven dofs per node and an initial state per node. Node numbers are 1-based, as in
the files.

Contactor numbering. BODIES.DAT groups contactors as pylmgc90 writes them: one
``CLxxx`` line and its ``+`` lines are one :class:`Candidates` object (one rank in
BODIES.DAT), one ``ALpxx`` line and its ``+`` lines are one :class:`Polyline`. The
solver (LMGC90, and Fracas's Vloc_Rloc files) numbers them differently: each CLxxx
point (a first line or a ``+`` line) is its own contactor, a polyline is one
contactor, in order within the body. :meth:`MeshBody.tactors` gives that numbering.
"""

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from .fortran_io import e14

__all__ = ["ELEMENTS", "ElementKind", "ELEMENT_NODES", "ELEMENT_CORNERS", "VTK_CORNERS", "element_edges",
           "Element", "Candidates", "Polyline", "MeshBody", "Model", "MODEL_OPTION_ORDER"]

class ElementKind(NamedTuple):
    """One row of the element table: nodes (the geometry written in BODIES.DAT), corners
    (vertices: the first nodes, counter-clockwise; the others are mid-side nodes, that
    of edge k after the corners), gauss (points of the stiffness rule: the element's
    Gauss-point states), gauss_gpv (points LMGC90 prints per element in GPV.OUT: T3's
    one point three times), gmsh (gmsh's element type) and vtk (the VTK cell type of
    the DISPLAY files and /mesh/element_vtk_type)."""
    nodes: int
    corners: int
    gauss: int
    gauss_gpv: int
    gmsh: int
    vtk: int


#: The one element table of the Python tools: the solver's (modules/fe/fracas_elements.f90,
#: doc/mesh_mechanics.md); Q4P0x is a MODELS.DAT element on the Q4xxx geometry.
ELEMENTS = {"T3xxx": ElementKind(3, 3, 1, 3, 2, 5), "Q4xxx": ElementKind(4, 4, 4, 4, 3, 9),
            "T6xxx": ElementKind(6, 3, 3, 3, 9, 22), "Q8xxx": ElementKind(8, 4, 9, 9, 16, 23)}

#: Nodes per element kind (ELEMENTS).
ELEMENT_NODES = {k: e.nodes for k, e in ELEMENTS.items()}

#: Vertices (corner nodes) per element kind (ELEMENTS).
ELEMENT_CORNERS = {k: e.corners for k, e in ELEMENTS.items()}

#: Vertices (corner nodes) per VTK cell type of an element (ELEMENTS).
VTK_CORNERS = {e.vtk: e.corners for e in ELEMENTS.values()}


def element_edges(kind, nodes):
    """The edges of an element, counter-clockwise: [(corner a, corner b, mid-side node
    or None)], edge k from corner k to corner k + 1."""
    nc = ELEMENTS[kind].corners
    mids = list(nodes[nc:])
    return [(nodes[k], nodes[(k + 1) % nc], mids[k] if mids else None) for k in range(nc)]


def _check_name(name, what):
    if not isinstance(name, str) or len(name) != 5 or " " in name:
        raise ValueError(f"{what} {name!r} must be exactly 5 characters without blanks "
                         f"(LMGC90 nicknames, e.g. 'STONE', 'BLEUx', 'M2DT3')")
    return name


@dataclass
class Element:
    """One element of a MAILx body: kind ('T3xxx', 'Q4xxx', 'T6xxx', 'Q8xxx'),
    node numbers (1-based, counter-clockwise corners first as LMGC90 orders them),
    model nickname (MODELS.DAT) and material nickname (BULK_BEHAV.DAT)."""
    kind: str
    nodes: tuple
    model: str
    material: str

    def __post_init__(self):
        if self.kind not in ELEMENT_NODES:
            raise ValueError(f"element kind {self.kind!r}: one of {', '.join(ELEMENT_NODES)}")
        self.nodes = tuple(int(n) for n in self.nodes)
        if len(self.nodes) != ELEMENT_NODES[self.kind]:
            raise ValueError(f"a {self.kind} element has {ELEMENT_NODES[self.kind]} nodes, "
                             f"got {len(self.nodes)}")
        if len(set(self.nodes)) != len(self.nodes):
            raise ValueError(f"{self.kind} element with a repeated node: {self.nodes}")
        _check_name(self.model, "model")
        _check_name(self.material, "material")

    @property
    def corners(self):
        return self.nodes[:ELEMENT_CORNERS[self.kind]]

    def edges(self):
        """The element's edges as (first corner, second corner, mid-side node or
        None), counter-clockwise when the element is."""
        c = self.corners
        nc = len(c)
        mids = self.nodes[nc:]
        return [(c[k], c[(k + 1) % nc], mids[k] if mids else None) for k in range(nc)]

    def lines(self, rank):
        return [f" {self.kind}{rank:7d}  nodes" + "".join(f"{n:7d}" for n in self.nodes),
                " " * 15 + f"model  {self.model}  behav  {self.material}"]


@dataclass
class Candidates:
    """CLxxx: candidate points on edges of the mesh. Each point is (noda, nodb,
    apab): the point (1 - apab) x_noda + apab x_nodb. Points at nodes use apab 0
    or 1. In LMGC90's numbering each point is its own contactor."""
    points: list
    color: str = "BLEUx"
    kind = "CLxxx"

    def __post_init__(self):
        _check_name(self.color, "colour")
        self.points = [(int(a), int(b), float(s)) for a, b, s in self.points]
        if not self.points:
            raise ValueError("a CLxxx contactor needs at least one candidate point")
        for a, b, s in self.points:
            if a == b:
                raise ValueError(f"CLxxx point on a degenerate edge ({a}, {b})")
            if not 0.0 <= s <= 1.0:
                raise ValueError(f"CLxxx apab {s} outside [0, 1]")

    @property
    def n_tactors(self):
        return len(self.points)

    def node_numbers(self):
        return sorted({n for a, b, _ in self.points for n in (a, b)})

    def lines(self, rank):
        return [("+" if k else " ") + f"CLxxx{rank:7d}  color  {self.color}  noda={a:5d}  nodb={b:5d}"
                f"  apab={e14(s, 'E')}" for k, (a, b, s) in enumerate(self.points)]


@dataclass
class Polyline:
    """ALpxx: an antagonist polyline through ``nodes`` (segment k joins nodes[k]
    and nodes[k+1]). LMGC90 orients it so that, walking from noda to nodb, the body
    lies on the right: with t the segment direction, the outward normal is
    (-t_y, t_x). A boundary walked that way is clockwise around the body, the
    reverse of the counter-clockwise element edges."""
    nodes: list
    color: str = "BLEUx"
    kind = "ALpxx"

    def __post_init__(self):
        _check_name(self.color, "colour")
        self.nodes = [int(n) for n in self.nodes]
        if len(self.nodes) < 2:
            raise ValueError("an ALpxx polyline needs at least 2 nodes")
        for a, b in zip(self.nodes[:-1], self.nodes[1:]):
            if a == b:
                raise ValueError(f"ALpxx segment of zero length ({a}, {b})")

    @property
    def n_tactors(self):
        return 1

    @property
    def segments(self):
        return list(zip(self.nodes[:-1], self.nodes[1:]))

    def node_numbers(self):
        return sorted(set(self.nodes))

    def lines(self, rank):
        return [("+" if k else " ") + f"ALpxx{rank:7d}  color  {self.color}  noda={a:5d}  nodb={b:5d}"
                for k, (a, b) in enumerate(self.segments)]


class MeshBody:
    """A MAILx body. ``nodes`` (n, 2) reference coordinates; node numbers in
    elements, contactors and driven dofs are 1-based. ``x0``/``v0`` (n, 2): initial
    displacement and velocity per node (DOF.INI, written when one is non-zero).
    ``driven``: DrivenDof objects with their ``node``. ``groups``: named node sets;
    ``edge_groups``: named lists of boundary edges (noda, nodb), walked with the
    body on the right (both filled by fracas_tools.mesh from gmsh's physical
    groups; not written to any file)."""

    model = "MAILx"

    def __init__(self, nodes, elements=(), contactors=(), physics="MECAx"):
        v = np.array(nodes, dtype=float)
        if v.ndim != 2 or v.shape[1] != 2 or len(v) == 0:
            raise ValueError("MAILx nodes: an (n, 2) array of n >= 1 coordinates")
        self.nodes = v
        self.elements = []
        for e in elements:
            self.add_element(e)
        self.contactors = list(contactors)
        self.physics = _check_name(physics, "physics")
        self.x0 = np.zeros_like(v)
        self.v0 = np.zeros_like(v)
        self.driven = []
        self.groups = {}
        self.edge_groups = {}
        self.number = None

    # -- geometry --
    @property
    def n_nodes(self):
        return len(self.nodes)

    def add_element(self, element, nodes=None, model=None, material=None):
        """Add an Element, or add_element(kind, nodes, model, material)."""
        if not isinstance(element, Element):
            element = Element(element, nodes, model, material)
        bad = [n for n in element.nodes if not 1 <= n <= self.n_nodes]
        if bad:
            raise ValueError(f"element nodes {bad} outside 1..{self.n_nodes}")
        self.elements.append(element)
        return element

    def materials(self):
        """Material nicknames used by the elements, in order of first use."""
        return list(dict.fromkeys(e.material for e in self.elements))

    def model_names(self):
        return list(dict.fromkeys(e.model for e in self.elements))

    @property
    def material(self):
        """The material when all elements share one (else the first one)."""
        m = self.materials()
        return m[0] if m else None

    def _check_nodes(self, nodes):
        nodes = [int(n) for n in np.atleast_1d(nodes)]
        bad = [n for n in nodes if not 1 <= n <= self.n_nodes]
        if bad:
            raise ValueError(f"body {self.number}: nodes {bad[:5]} outside 1..{self.n_nodes}")
        return nodes

    def _nodes_of(self, nodes):
        """Node numbers from a list of numbers or a group name."""
        if isinstance(nodes, str):
            if nodes not in self.groups:
                raise ValueError(f"body {self.number}: no node group {nodes!r} "
                                 f"(groups: {', '.join(self.groups) or 'none'})")
            nodes = self.groups[nodes]
        return self._check_nodes(nodes)

    # -- contactors --
    def add_candidates(self, points, color="BLEUx"):
        """Add a CLxxx contactor: points [(noda, nodb, apab), ...]."""
        c = Candidates(points, color)
        self._check_nodes(c.node_numbers())
        self.contactors.append(c)
        return c

    def add_polyline(self, nodes, color="BLEUx"):
        """Add an ALpxx contactor through ``nodes`` (oriented: body on the right)."""
        c = Polyline(nodes, color)
        self._check_nodes(c.node_numbers())
        self.contactors.append(c)
        return c

    def _group_edges(self, group):
        if group not in self.edge_groups:
            raise ValueError(f"MAILx {self.number}: no edge group {group!r} "
                             f"(edge groups: {', '.join(self.edge_groups) or 'none'})")
        return list(self.edge_groups[group])

    def _chains(self, group):
        """The edges of an edge group joined into maximal polylines (walked in
        their direction; a closed loop ends on its first node), in group order."""
        edges = self._group_edges(group)
        nxt = {}
        ends = set()
        for a, b in edges:
            if a in nxt:
                raise ValueError(f"edge group {group!r} branches at node {a}")
            nxt[a] = b
            ends.add(b)
        used, chains = set(), []
        starts = [a for a, _ in edges if a not in ends] + [a for a, _ in edges]
        for a in starts:
            if a in used or a not in nxt:
                continue
            chain = [a]
            while chain[-1] in nxt and chain[-1] not in used:
                used.add(chain[-1])
                chain.append(nxt[chain[-1]])
            chains.append(chain)
        return chains

    def add_polyline_on(self, group, color="BLEUx"):
        """ALpxx polylines along an edge group (one per connected piece), walked
        with the body on the right as LMGC90 does. Returns them."""
        return [self.add_polyline(c, color) for c in self._chains(group)]

    def add_candidates_on(self, group, color="BLEUx", apab=(0.25, 0.75)):
        """One CLxxx contactor with points at ``apab`` on every edge of an edge
        group, in group order, each edge walked with the body on the right.
        apab='nodes' puts one point on each node of the group instead: apab 0 at
        each edge's noda, and apab 1 at an nodb that starts no edge (the end of an
        open piece), right after its edge's point (pylmgc90's layout)."""
        edges = self._group_edges(group)
        if apab == "nodes":
            starts = {a for a, _ in edges}
            pts, done = [], set()
            for a, b in edges:
                pts.append((a, b, 0.0))
                if b not in starts and b not in done:
                    pts.append((a, b, 1.0))
                    done.add(b)
        else:
            pts = [(a, b, float(s)) for a, b in edges for s in apab]
        return self.add_candidates(pts, color)

    def tactors(self):
        """The contactors as LMGC90 numbers them (rank k+1 = item k): a list of
        (contactor, point index) with point index None for a polyline."""
        out = []
        for c in self.contactors:
            if isinstance(c, Candidates):
                out += [(c, k) for k in range(len(c.points))]
            else:
                out.append((c, None))
        return out

    def tactor(self, rank):
        """(contactor, point index or None) of LMGC90 contactor ``rank`` (1-based)."""
        t = self.tactors()
        if not 1 <= rank <= len(t):
            raise IndexError(f"MAILx {self.number} has {len(t)} contactors, no {rank}")
        return t[rank - 1]

    def tactor_point(self, rank, displacement=None):
        """Coordinates of CLxxx contactor ``rank`` (with an optional (n, 2) nodal
        displacement added)."""
        c, k = self.tactor(rank)
        if k is None:
            raise ValueError(f"contactor {rank} of MAILx {self.number} is a polyline")
        x = self.nodes if displacement is None else self.nodes + displacement
        a, b, s = c.points[k]
        return (1.0 - s) * x[a - 1] + s * x[b - 1]

    # -- driven dofs and initial state --
    def _drive(self, nodes, dofs, kind, **kw):
        from .pre import DrivenDof
        for n in self._nodes_of(nodes):
            for d in np.atleast_1d(dofs):
                if int(d) not in (1, 2):
                    raise ValueError(f"a MAILx node has dofs 1 and 2, got {d}")
                dd = DrivenDof(int(d), kind, **kw)
                dd.node = n
                self.driven.append(dd)
        return self

    def impose_velocity(self, nodes, dofs=(1, 2), ct=0.0, amp=0.0, omega=0.0, phi=0.0,
                        rampi=1.0, ramp=0.0):
        """Drive the velocity of dofs (1: x, 2: y) of ``nodes`` (numbers or a group name)."""
        return self._drive(nodes, dofs, "vlocy", ct=ct, amp=amp, omega=omega, phi=phi,
                           rampi=rampi, ramp=ramp)

    def impose_force(self, nodes, dofs, ct=0.0, amp=0.0, omega=0.0, phi=0.0, rampi=1.0,
                     ramp=0.0):
        """Add a driven force on dofs of ``nodes`` (numbers or a group name)."""
        return self._drive(nodes, dofs, "force", ct=ct, amp=amp, omega=omega, phi=phi,
                           rampi=rampi, ramp=ramp)

    def impose_evolution(self, nodes, dof, kind, file, data=None):
        """Drive a dof of ``nodes`` from a DATBOX file of two columns (t, value)."""
        return self._drive(nodes, dof, kind, evolution=file, evolution_data=data)

    def fix(self, nodes):
        """Clamp ``nodes``: both velocities driven to zero."""
        return self.impose_velocity(nodes, (1, 2))

    def driven_by_node(self):
        """[(node, [DrivenDof, ...]), ...] in order of first appearance."""
        out = {}
        for d in self.driven:
            out.setdefault(d.node, []).append(d)
        return list(out.items())

    def set_velocity(self, vx=0.0, vy=0.0, nodes=None):
        """Initial velocity of ``nodes`` (all by default), written to DOF.INI."""
        idx = slice(None) if nodes is None else np.array(self._nodes_of(nodes)) - 1
        self.v0[idx] = (vx, vy)
        return self

    def set_displacement(self, dx=0.0, dy=0.0, nodes=None):
        idx = slice(None) if nodes is None else np.array(self._nodes_of(nodes)) - 1
        self.x0[idx] = (dx, dy)
        return self

    def has_state(self):
        return bool(np.any(self.x0 != 0.0) or np.any(self.v0 != 0.0))

    # -- text --
    def bodies_lines(self):
        """The $bdyty block of BODIES.DAT (pylmgc90's layout)."""
        out = ["$bdyty", f" MAILx{self.number:7d}", "$blmty"]
        for k, e in enumerate(self.elements, start=1):
            out += e.lines(k)
        out.append("$nodty")
        for k, (x, y) in enumerate(self.nodes, start=1):
            out.append(f" NO2xx{k:7d}" + " " * 16 + f"coo1={e14(x, 'E')}  coo2={e14(y, 'E')}  ")
        out.append("$tacty")
        for rank, c in enumerate(self.contactors, start=1):
            out += c.lines(rank)
        out += ["$$$$$$", ""]
        return out

    def drv_dof_lines(self, dof_header):
        if not self.driven:
            return []
        num = f"{self.number:7d}" if self.number < 100000 else f"  {self.number:7d}"
        out = ["$bdyty", f" MAILx{num}", "$model", f" {self.physics}"]
        for node, lst in self.driven_by_node():
            out += ["$nodty", f" NO2xx{node:7d}", dof_header]
            out += [d.line() for d in lst]
        out += ["$$$$$$", ""]
        return out

    def summary(self):
        kinds = {}
        for e in self.elements:
            kinds[e.kind] = kinds.get(e.kind, 0) + 1
        return (f"MAILx {self.number}: {self.n_nodes} nodes, "
                + ", ".join(f"{n} {k}" for k, n in kinds.items())
                + f", {len(self.tactors())} contactors")

    def __repr__(self):
        return (f"MeshBody(number={self.number}, nodes={self.n_nodes}, "
                f"elements={len(self.elements)}, contactors={len(self.contactors)})")


#: The order pylmgc90 writes model options in.
MODEL_OPTION_ORDER = ("aniso", "isext", "form_", "kine_", "mstrg", "mater")


class Model:
    """A MODELS.DAT model: nickname, physics ('MECAx'), element ('T3xxx', 'Q4xxx',
    'T6xxx', 'Q8xxx', 'Q4P0x', 'Rxx2D' for rigid bodies ...) and options, e.g.
    Model('M2DT3', 'T3xxx') is small-strain elastic with lumped mass;
    Model('M2DJ2', 'Q4P0x', kinematic='large', formulation='UpdtL', material='J2iso')."""

    def __init__(self, name, element, physics="MECAx", kinematic="small", material="elas_",
                 mass_storage="lump_", anisotropy="iso__", external="no___", formulation=None,
                 options=None):
        self.name = _check_name(name, "model")
        self.element = _check_name(element, "element")
        self.physics = _check_name(physics, "physics")
        if options is not None:
            self.options = dict(options)
        elif element in ("Rxx2D", "Rxx3D"):
            self.options = {}
        else:
            given = {"aniso": anisotropy, "isext": external, "form_": formulation,
                     "kine_": kinematic, "mstrg": mass_storage, "mater": material}
            self.options = {k: given[k] for k in MODEL_OPTION_ORDER if given[k] is not None}
        for k, v in self.options.items():
            _check_name(k, "model option")
            if not v or len(v) > 30:
                raise ValueError(f"model option {k}: value {v!r} of 1-30 characters")

    def lines(self):
        out = ["$model  mdlty  finel  eleop  value   ", f" {self.name}"]
        head = f"        {self.physics}  {self.element}  "
        if not self.options:
            return out + [head.rstrip() + " "]
        for k, (opt, val) in enumerate(self.options.items()):
            out.append((head if k == 0 else " " * 22) + f"{opt}  {val}")
        return out + [" " * 21]

    def __repr__(self):
        return f"Model({self.name!r}, {self.element!r}, {self.options})"
