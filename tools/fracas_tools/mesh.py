"""Meshed decks from gmsh: MAILx bodies from a 2D mesh, and exploded meshes whose
elements are glued by cohesive interfaces.

A :class:`Mesh2D` is a 2D mesh with its physical groups: elements (T3, Q4, T6, Q8)
with a *phase* each (the name of their physical surface), named node groups
(physical points and curves) and named edge groups (physical curves). It comes from
gmsh (a .geo script, a .msh file of format 2.2 or 4.1, or a model built with gmsh's
Python API; gmsh reads the files) or from arrays.

    from fracas_tools import Case
    from fracas_tools.mesh import mesh_geo
    mesh = mesh_geo("plate.geo")                  # physical surfaces 'matrix', 'hydride'
    case = Case(gravity=(0, 0))
    case.add_material("MATRX", 6500., "ELAS", young=9.9e10, poisson=0.37)
    case.add_material("HYDRx", 5600., "ELAS", young=1.3e11, poisson=0.32)
    parts = case.add_exploded_mesh(mesh, {"matrix": "MATRX", "hydride": "HYDRx"},
                                   cracks=["notch"])
    parts.impose_velocity("bottom", (1, 2))       # a physical curve, all its node copies
    for family, color in parts.families.items():  # one cohesive law per interface family
        case.add_see("CLxxx", color, "ALpxx", color, law_of[family], 1e-4)

:meth:`fracas_tools.Case.add_mesh` makes one MAILx body per connected part of each
physical surface (or per group of phases the user gives) instead.

Conventions (LMGC90's, checked against ../shared/lmgc90_decks/mesh_*):
- element nodes counter-clockwise (reordered if gmsh gives them clockwise), T6/Q8
  corners first then mid-side nodes (edge k joins corners k and k+1);
- contactor edges are the element edges walked backwards, so that from noda to nodb
  the body lies on the right and the outward normal is (-t_y, t_x);
- on a quadratic edge (a, m, b) contactors use the two straight halves a-m and m-b.
"""

import warnings
from dataclasses import dataclass, field

import numpy as np

from .mailx import ELEMENT_CORNERS, ELEMENT_NODES, ELEMENTS, Element, MeshBody, element_edges

__all__ = ["Mesh2D", "mesh_from_arrays", "mesh_from_gmsh", "read_msh", "mesh_geo",
           "build_bodies", "explode", "Exploded", "family_colors", "phase_codes",
           "impose_on_group", "mecax_sets"]

#: gmsh element type -> LMGC90 element
GMSH_2D = {e.gmsh: k for k, e in ELEMENTS.items()}
GMSH_1D = {1: 2, 8: 3}          # line types -> nodes per line


# --------------------------------------------------------------------------------------
# the mesh
# --------------------------------------------------------------------------------------

@dataclass
class Mesh2D:
    """A 2D mesh. ``nodes`` (n, 2); ``elements`` list of (kind, node indices
    0-based, counter-clockwise); ``phases`` one name per element;
    ``node_groups`` name -> sorted node indices; ``edge_groups`` name -> list of
    edges (a, b) (corner indices, mesh-wide)."""
    nodes: np.ndarray
    elements: list
    phases: list
    node_groups: dict = field(default_factory=dict)
    edge_groups: dict = field(default_factory=dict)

    def __post_init__(self):
        self.nodes = np.asarray(self.nodes, dtype=float).reshape(-1, 2)
        els = []
        for kind, nodes in self.elements:
            if kind not in ELEMENT_NODES:
                raise ValueError(f"element kind {kind!r}: one of {', '.join(ELEMENT_NODES)}")
            nodes = tuple(int(n) for n in nodes)
            if len(nodes) != ELEMENT_NODES[kind]:
                raise ValueError(f"{kind} with {len(nodes)} nodes")
            els.append((kind, _counter_clockwise(kind, nodes, self.nodes)))
        self.elements = els
        self.phases = [str(p) for p in self.phases]
        if len(self.phases) != len(self.elements):
            raise ValueError("one phase per element")
        self.node_groups = {k: np.array(sorted(set(int(n) for n in v)), dtype=int)
                            for k, v in self.node_groups.items()}
        self.edge_groups = {k: [(int(a), int(b)) for a, b in v] for k, v in self.edge_groups.items()}
        for k, v in self.edge_groups.items():
            nodes = {n for e in v for n in e}
            if k in self.node_groups:
                nodes |= set(self.node_groups[k].tolist())
            self.node_groups[k] = np.array(sorted(nodes), dtype=int)

    @property
    def n_elements(self):
        return len(self.elements)

    def phase_names(self):
        return list(dict.fromkeys(self.phases))

    def edges(self):
        """{(min corner, max corner): [(element, local edge), ...]} over all elements."""
        out = {}
        for e, (kind, nodes) in enumerate(self.elements):
            for k, (a, b, _) in enumerate(element_edges(kind, nodes)):
                out.setdefault((min(a, b), max(a, b)), []).append((e, k))
        return out

    def __repr__(self):
        kinds = {}
        for k, _ in self.elements:
            kinds[k] = kinds.get(k, 0) + 1
        return (f"Mesh2D({len(self.nodes)} nodes, " + ", ".join(f"{n} {k}" for k, n in kinds.items())
                + f", phases {self.phase_names()}, node groups {list(self.node_groups)}, "
                f"edge groups {list(self.edge_groups)})")


def _signed_area(kind, nodes, xy):
    c = xy[list(nodes[:ELEMENT_CORNERS[kind]])]
    x, y = c[:, 0], c[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def _counter_clockwise(kind, nodes, xy):
    a = _signed_area(kind, nodes, xy)
    if a == 0.0:
        raise ValueError(f"degenerate {kind} element (zero area): nodes {nodes}")
    if a > 0.0:
        return nodes
    nc = ELEMENT_CORNERS[kind]
    corners = [nodes[0]] + list(nodes[1:nc][::-1])
    mids = list(nodes[nc:][::-1])      # mid of edge k (k, k+1) becomes mid of the reversed edge
    return tuple(corners + mids)


def mesh_from_arrays(nodes, elements, phases=None, node_groups=None, edge_groups=None):
    """A Mesh2D from arrays: elements as node lists (0-based; kind from the count: 3
    T3xxx, 4 Q4xxx, 6 T6xxx, 8 Q8xxx) or (kind, nodes); phases default 'mesh'."""
    kinds = {n: k for k, n in ELEMENT_NODES.items()}
    els = [e if isinstance(e[0], str) else (kinds.get(len(e), f"{len(e)}-node"), e) for e in elements]
    return Mesh2D(nodes, els, phases if phases is not None else ["mesh"] * len(els),
                  node_groups or {}, edge_groups or {})


# --------------------------------------------------------------------------------------
# gmsh
# --------------------------------------------------------------------------------------

def _gmsh():
    try:
        import gmsh
    except ImportError:
        raise ImportError("gmsh's Python API is needed (Debian: python3-gmsh)") from None
    return gmsh


def _group_name(gmsh, dim, tag):
    name = gmsh.model.getPhysicalName(dim, tag)
    return name if name else {0: "point", 1: "curve", 2: "surface"}[dim] + f"_{tag}"


def mesh_from_gmsh():
    """The 2D mesh of gmsh's current model (gmsh initialized and meshed by the caller):
    elements of dimension 2 (triangles, quadrangles, 6-node triangles, 8-node
    quadrangles), phases from physical surfaces (all 'mesh' when there is none),
    node groups from physical points and curves, edge groups from physical curves."""
    gmsh = _gmsh()
    tags, xyz, _ = gmsh.model.mesh.getNodes()
    xyz = np.asarray(xyz).reshape(-1, 3)
    if len(xyz) and np.max(np.abs(xyz[:, 2])) > 1e-12 * max(1.0, float(np.max(np.abs(xyz)))):
        raise ValueError("the mesh is not in the plane z = 0")
    index_of_tag = {int(t): i for i, t in enumerate(tags)}

    # 2D elements with their tags and entities
    elems = []                      # (element tag, kind, gmsh node tags, surface entity)
    for dim, ent in gmsh.model.getEntities(2):
        types, etags, enodes = gmsh.model.mesh.getElements(dim, ent)
        for t, et, en in zip(types, etags, enodes):
            if t not in GMSH_2D:
                name = gmsh.model.mesh.getElementProperties(t)[0]
                raise ValueError(f"gmsh element type {t} ({name}) on surface {ent}: supported are "
                                 "3-node triangles, 4-node quadrangles, 6-node triangles and 8-node "
                                 "quadrangles (Mesh.SecondOrderIncomplete = 1 for the latter)")
            kind = GMSH_2D[t]
            en = np.asarray(en, dtype=np.int64).reshape(-1, ELEMENT_NODES[kind])
            for tag, nodes in zip(et, en):
                elems.append((int(tag), kind, nodes, ent))
    if not elems:
        raise ValueError("gmsh's model has no 2D element: a .geo must be meshed (gmsh.model.mesh.generate(2)), "
                         "and gmsh writes into a .msh with physical groups (e.g. Physical Curves for the loads) only "
                         "their elements: give the surfaces a Physical Surface (one per phase), or save with "
                         "Mesh.SaveAll = 1")
    elems.sort(key=lambda e: e[0])

    phase_of_surface = {}
    for dim, ptag in gmsh.model.getPhysicalGroups(2):
        name = _group_name(gmsh, dim, ptag)
        for ent in gmsh.model.getEntitiesForPhysicalGroup(dim, ptag):
            if int(ent) in phase_of_surface and phase_of_surface[int(ent)] != name:
                raise ValueError(f"surface {ent} is in two physical surfaces "
                                 f"({phase_of_surface[int(ent)]!r}, {name!r})")
            phase_of_surface[int(ent)] = name
    if phase_of_surface:
        missing = sorted({e[3] for e in elems if e[3] not in phase_of_surface})
        if missing:
            raise ValueError(f"surfaces {missing} are meshed but in no physical surface: add them "
                             "to one (each physical surface is a phase)")

    used = sorted({int(n) for e in elems for n in e[2]})        # by node tag: the same from any file
    compact = {t: i for i, t in enumerate(used)}
    nodes = xyz[[index_of_tag[t] for t in used], :2]
    elements = [(kind, [compact[int(n)] for n in en]) for _, kind, en, _ in elems]
    phases = [phase_of_surface.get(ent, "mesh") for *_, ent in elems]

    node_groups, edge_groups = {}, {}
    for dim, ptag in gmsh.model.getPhysicalGroups(1) + gmsh.model.getPhysicalGroups(0):
        name = _group_name(gmsh, dim, ptag)
        gnodes = []
        for ent in gmsh.model.getEntitiesForPhysicalGroup(dim, ptag):
            types, _, enodes = gmsh.model.mesh.getElements(dim, int(ent))
            for t, en in zip(types, enodes):
                if dim == 1:
                    if t not in GMSH_1D:
                        raise ValueError(f"gmsh line type {t} on curve {ent}")
                    lines = np.asarray(en, dtype=np.int64).reshape(-1, GMSH_1D[t])
                    edge_groups.setdefault(name, []).extend(
                        (compact[int(l[0])], compact[int(l[1])]) for l in lines
                        if int(l[0]) in compact and int(l[1]) in compact)
                gnodes += [compact[int(n)] for n in en if int(n) in compact]
        node_groups[name] = sorted(set(node_groups.get(name, [])) | set(gnodes))
    return Mesh2D(nodes, elements, phases, node_groups, edge_groups)


def _quiet(gmsh):
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("General.NumThreads", 1)        # the same mesh every time


def read_msh(path):
    """A Mesh2D from a gmsh .msh file (format 2.2 or 4.1; gmsh reads it). Starts
    and stops gmsh: do not call it inside your own gmsh session (there, use
    gmsh.open(path) and mesh_from_gmsh())."""
    gmsh = _gmsh()
    gmsh.initialize()
    try:
        _quiet(gmsh)
        gmsh.open(str(path))
        return mesh_from_gmsh()
    finally:
        gmsh.finalize()


def mesh_geo(path, order=1, recombine=False, size_factor=None, options=None):
    """Mesh a gmsh .geo script in 2D and return the Mesh2D. ``order`` 2 gives T6
    (or Q8 with ``recombine``: incomplete second order); ``recombine`` makes
    quadrangles; ``size_factor`` scales the element sizes; ``options`` sets other
    gmsh options {name: value}. Starts and stops gmsh."""
    gmsh = _gmsh()
    gmsh.initialize()
    try:
        _quiet(gmsh)
        gmsh.open(str(path))
        if recombine:
            gmsh.option.setNumber("Mesh.RecombineAll", 1)
        if size_factor is not None:
            gmsh.option.setNumber("Mesh.MeshSizeFactor", float(size_factor))
        for k, v in (options or {}).items():
            if isinstance(v, str):
                gmsh.option.setString(k, v)
            else:
                gmsh.option.setNumber(k, float(v))
        gmsh.model.mesh.generate(2)
        if order == 2:
            gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1)
            gmsh.model.mesh.setOrder(2)
        elif order != 1:
            raise ValueError("order 1 or 2")
        return mesh_from_gmsh()
    finally:
        gmsh.finalize()


# --------------------------------------------------------------------------------------
# bodies
# --------------------------------------------------------------------------------------

def _pick(spec, phase, kind, what):
    if isinstance(spec, str):
        return spec
    if isinstance(spec, dict):
        for key in (phase, kind):
            if key in spec:
                return spec[key]
        raise ValueError(f"no {what} given for phase {phase!r} ({kind}): {what} = {spec}")
    raise ValueError(f"{what}: a nickname or a dict phase -> nickname")


def _ensure_models(case, mesh, model):
    """model None: one default model per element kind (M2DT3, M2DQ4, M2DT6, M2DQ8:
    small strain, elastic, lumped mass), created when the case has none of that name."""
    if model is not None:
        return model
    out = {}
    for kind, _ in mesh.elements:
        name = "M2D" + kind[:2]
        if name not in case.models:
            case.add_model(name, kind)
        out[kind] = name
    return out


def _sub_edges(a, b, m):
    """Straight pieces of an edge walked from a to b (through its mid node m)."""
    return [(a, b)] if m is None else [(a, m), (m, b)]


def _body_from_elements(mesh, elist, material, model, node_order=None):
    """A MeshBody of mesh elements ``elist``; its nodes are the mesh nodes in
    ``node_order`` (default: increasing mesh index). Returns (body, local of)."""
    if node_order is None:
        node_order = sorted({n for e in elist for n in mesh.elements[e][1]})
    local = {n: k + 1 for k, n in enumerate(node_order)}
    body = MeshBody(mesh.nodes[node_order])
    for e in elist:
        kind, nodes = mesh.elements[e]
        ph = mesh.phases[e]
        body.add_element(Element(kind, [local[n] for n in nodes], _pick(model, ph, kind, "model"),
                                 _pick(material, ph, kind, "material")))
    return body, local


def _attach_groups(mesh, body, local, elist, curve_nodes_by_edges=False):
    """Node and edge groups of the mesh restricted to the body. Edge groups keep the
    edges of the group that are boundary edges of the body, oriented body on the
    right (quadratic edges as their two halves); with ``curve_nodes_by_edges`` a
    curve group's nodes are only taken on a body owning one of its edges."""
    owned = {}                      # (min, max) -> oriented sub-edges (local numbers)
    count = {}
    for e in elist:
        kind, nodes = mesh.elements[e]
        for a, b, m in element_edges(kind, nodes):
            key = (min(a, b), max(a, b))
            count[key] = count.get(key, 0) + 1
            owned[key] = [(local[p], local[q]) for p, q in _sub_edges(b, a, m)]
    for name, edges in mesh.edge_groups.items():
        oriented = [s for a, b in edges for s in owned.get((min(a, b), max(a, b)), [])
                    if count[(min(a, b), max(a, b))] == 1]
        if oriented:
            body.edge_groups[name] = oriented
    for name, nodes in mesh.node_groups.items():
        if curve_nodes_by_edges and name in mesh.edge_groups and name not in body.edge_groups:
            continue
        mine = sorted(local[n] for n in nodes.tolist() if n in local)
        if mine:
            body.groups[name] = mine


def build_bodies(case, mesh, material, model=None, bodies=None):
    """Add MAILx bodies for ``mesh`` to ``case``: one per connected part (elements
    sharing an edge) of each physical surface, or of each group of phases in
    ``bodies`` (a list of phase names or lists of phase names: the phases of one
    item form bodies together). ``material``, ``model``: a nickname, or a dict
    phase -> nickname (or element kind -> nickname); model None creates default
    models (M2DT3, M2DQ4, M2DT6, M2DQ8). Mesh groups become body.groups (node
    numbers) and body.edge_groups (boundary edges oriented as LMGC90's contactors,
    for body.add_candidates_on / add_polyline_on). Returns the bodies."""
    model = _ensure_models(case, mesh, model)
    phases = mesh.phase_names()
    if bodies is None:
        bodies = [[p] for p in phases]
    groups = [[b] if isinstance(b, str) else list(b) for b in bodies]
    unknown = sorted({p for g in groups for p in g} - set(phases))
    if unknown:
        raise ValueError(f"bodies: unknown phases {unknown} (mesh phases: {phases})")
    taken = [p for g in groups for p in g]
    if len(taken) != len(set(taken)):
        raise ValueError("bodies: a phase is in two groups")
    left = sorted(set(phases) - set(taken))
    if left:
        warnings.warn(f"phases {left} are in no body and are left out", stacklevel=2)
    edges = mesh.edges()
    out = []
    for g in groups:
        members = [e for e in range(mesh.n_elements) if mesh.phases[e] in g]
        # connected parts: union-find over shared edges
        parent = {e: e for e in members}

        def find(e):
            while parent[e] != e:
                parent[e] = parent[parent[e]]
                e = parent[e]
            return e
        for sharing in edges.values():
            es = [e for e, _ in sharing if e in parent]
            for e in es[1:]:
                ra, rb = find(es[0]), find(e)
                if ra != rb:
                    parent[max(ra, rb)] = min(ra, rb)
        parts = {}
        for e in members:
            parts.setdefault(find(e), []).append(e)
        for root in sorted(parts):
            elist = parts[root]
            body, local = _body_from_elements(mesh, elist, material, model)
            _attach_groups(mesh, body, local, elist)
            case.append(body)
            out.append(body)
    return out


# --------------------------------------------------------------------------------------
# exploded meshes
# --------------------------------------------------------------------------------------

def phase_codes(phases):
    """Two-character code per phase: its first two letters or digits, upper case;
    when two phases share a code, the later one (in sorted order) takes its first
    letter and a digit 1..9."""
    codes = {}
    for p in sorted(phases):
        alnum = "".join(ch for ch in p if ch.isalnum()).upper() or "P"
        code = (alnum + "X")[:2]
        if code in codes.values():
            for d in "123456789":
                if alnum[0] + d not in codes.values():
                    code = alnum[0] + d
                    break
            else:
                raise ValueError("too many phases with the same first letter")
        codes[p] = code
    return codes


def family_colors(phases, codes=None):
    """Colour of each interface family {p, q} of ``phases`` (5 characters): the
    two phase codes in alphabetical order joined by '_', e.g. matrix/matrix 'MA_MA',
    hydride/matrix 'HY_MA', hydride/hydride 'HY_HY'. Keys are (p, q) with p <= q."""
    codes = codes or phase_codes(phases)
    out = {}
    ph = sorted(phases)
    for i, p in enumerate(ph):
        for q in ph[i:]:
            a, b = sorted((codes[p], codes[q]))
            out[(p, q)] = f"{a}_{b}"
    return out


@dataclass
class Exploded:
    """The result of explode(): ``bodies`` (body k = element k), ``families``
    {(phase, phase): colour} of the glued interfaces present, and counts:
    ``internal_edges`` (shared by two elements), ``cohesive_edges`` (glued),
    ``points`` (CLxxx candidate points), ``crack_edges`` (left open),
    ``boundary_edges``."""
    bodies: list
    families: dict
    internal_edges: int = 0
    cohesive_edges: int = 0
    points: int = 0
    crack_edges: int = 0
    boundary_edges: int = 0
    edge_family: dict = field(default_factory=dict)

    def impose_velocity(self, group, dofs=(1, 2), **values):
        """vlocy on every copy of the group's nodes (see impose_on_group)."""
        return impose_on_group(self.bodies, group, "vlocy", dofs, **values)

    def impose_force(self, group, dofs, **values):
        return impose_on_group(self.bodies, group, "force", dofs, **values)

    def fix(self, group):
        return impose_on_group(self.bodies, group, "vlocy", (1, 2))

    def bodies_with(self, group):
        return [b for b in self.bodies if group in b.groups]

    def add_see(self, case, laws, alert):
        """One see rule per family: laws is a law nickname or {(p, q): nickname}
        (keys in either order) or {colour: nickname}."""
        for fam, color in self.families.items():
            if isinstance(laws, str):
                law = laws
            else:
                law = laws.get(fam, laws.get(fam[::-1], laws.get(color)))
                if law is None:
                    raise ValueError(f"no law for interface family {fam} ({color})")
            case.add_see("CLxxx", color, "ALpxx", color, law, alert)


def explode(case, mesh, material, model=None, apab=(0.25, 0.75), cracks=(), color=None,
            codes=None, boundary_color=None, boundary_apab=(0.25, 0.75), group_copies="all"):
    """Explode ``mesh`` into ``case``: each element becomes a MAILx body with its own
    copy of its nodes (in the element's node order), as LMGC90's
    explodeMeshedAvatar2D. Every edge shared by two elements carries a cohesive
    interface: CLxxx points at ``apab`` on the body with the higher number, a
    one-segment ALpxx on the other, both walked with their body on the right, in the
    order of the element edges. Their colour names the interface family (phases on
    both sides, see family_colors; ``color`` forces one colour for all). Edges of
    the edge groups named in ``cracks`` are left open (no contactor). Free boundary
    edges get nothing, or CLxxx points at ``boundary_apab`` with ``boundary_color``
    (for contact with rigid walls). Node groups follow the copies: with
    group_copies 'all' a group node becomes all its copies; with 'edge' the nodes of
    a curve group are only taken on bodies that own one of its edges (LMGC90's
    rule). Returns an Exploded."""
    if group_copies not in ("all", "edge"):
        raise ValueError("group_copies: 'all' or 'edge'")
    model = _ensure_models(case, mesh, model)
    unknown = sorted(set(cracks) - set(mesh.edge_groups))
    if unknown:
        raise ValueError(f"cracks: no edge group {unknown} (edge groups: {list(mesh.edge_groups)})")
    crack_keys = {(min(a, b), max(a, b)) for g in cracks for a, b in mesh.edge_groups[g]}
    fam_colors = family_colors(mesh.phase_names(), codes)
    edges = mesh.edges()
    bodies, locals_ = [], []
    for e, (kind, nodes) in enumerate(mesh.elements):
        body, local = _body_from_elements(mesh, [e], material, model, node_order=list(nodes))
        _attach_groups(mesh, body, local, [e], curve_nodes_by_edges=(group_copies == "edge"))
        bodies.append(body)
        locals_.append(local)
    res = Exploded(bodies, {})
    for e, (kind, nodes) in enumerate(mesh.elements):
        body, local = bodies[e], locals_[e]
        for a, b, m in element_edges(kind, nodes):
            key = (min(a, b), max(a, b))
            sharing = edges[key]
            pieces = [(local[p], local[q]) for p, q in _sub_edges(b, a, m)]
            if len(sharing) == 1:
                if boundary_color is not None:
                    body.add_candidates([(p, q, s) for p, q in pieces for s in boundary_apab],
                                        boundary_color)
                continue
            if len(sharing) > 2:
                raise ValueError(f"edge {key} is shared by {len(sharing)} elements")
            other = sharing[0][0] if sharing[1][0] == e else sharing[1][0]
            if key in crack_keys:
                continue
            fam = tuple(sorted((mesh.phases[e], mesh.phases[other])))
            col = color or fam_colors[fam]
            res.families[fam] = col
            if e > other:
                body.add_candidates([(p, q, s) for p, q in pieces for s in apab], col)
            else:
                body.add_polyline([p for p, _ in pieces] + [pieces[-1][1]], col)
    for key, sharing in edges.items():
        if len(sharing) == 1:
            res.boundary_edges += 1
            continue
        res.internal_edges += 1
        if key in crack_keys:
            res.crack_edges += 1
        else:
            res.cohesive_edges += 1
            res.edge_family[key] = tuple(sorted(mesh.phases[e] for e, _ in sharing))
    res.points = sum(len(c.points) for b in bodies for c in b.contactors
                     if c.kind == "CLxxx" and c.color != boundary_color)
    for b in bodies:
        case.append(b)
    res.families = dict(sorted(res.families.items()))
    return res


# --------------------------------------------------------------------------------------
# groups across bodies
# --------------------------------------------------------------------------------------

def impose_on_group(bodies, group, kind="vlocy", dofs=(1, 2), **values):
    """Drive dofs of the nodes of ``group`` on every body that has it; returns the
    bodies touched (an error when none has the group)."""
    touched = [b for b in bodies if group in b.groups]
    if not touched:
        raise ValueError(f"no body has the node group {group!r}")
    for b in touched:
        if kind == "vlocy":
            b.impose_velocity(group, dofs, **values)
        elif kind == "force":
            b.impose_force(group, dofs, **values)
        else:
            raise ValueError("kind: 'vlocy' or 'force'")
    return touched


def mecax_sets(bodies, groups):
    """Sets for POSTPRO.DAT 'NEW MECAx SETS' (postpro_deck.mecax_set_rows), one per
    group name: [(body number, group nodes), ...] over the bodies that have it."""
    out = []
    for g in groups:
        s = [(b.number, b.groups[g]) for b in bodies if g in b.groups]
        if not s:
            raise ValueError(f"no body has the node group {g!r}")
        out.append(s)
    return out


def element_area(kind, nodes, xy):
    """Area of a straight-sided element (corners)."""
    return abs(_signed_area(kind, nodes, xy))
