"""fracas_tools.mesh: MAILx bodies and exploded meshes from gmsh meshes or arrays.

References: hand counts of edges and points on small structured meshes; LMGC90's own
explodeMeshedAvatar2D output (../shared/lmgc90_decks/mesh_exploded_beam) and its
contactor layouts (mesh_t3_pair_czm, mesh_block_drop), reproduced byte for byte."""

import sys
from collections import Counter
from pathlib import Path

import numpy as np
import pytest


from fracas_tools import Case, read_case  # noqa: E402
from fracas_tools.mesh import (explode, family_colors, mecax_sets, mesh_from_arrays,  # noqa: E402
                               phase_codes)
from fracas_tools.postpro_deck import PostPro, mecax_set_rows  # noqa: E402

DECKS = Path(__file__).resolve().parents[2] / ".." / "shared" / "lmgc90_decks"
needs_decks = pytest.mark.skipif(not DECKS.is_dir(), reason="../shared/lmgc90_decks not present")

# Two phases side by side, 2 x 2 quadrangles each; the lower half of their interface
# is a notch (physical curve), a physical point sits at the notch tip.
TWO_PHASES_GEO = """
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {2, 0, 0};
Point(4) = {2, 1, 0}; Point(5) = {1, 1, 0}; Point(6) = {0, 1, 0}; Point(7) = {1, 0.5, 0};
Line(1) = {1, 2}; Line(2) = {2, 7}; Line(3) = {7, 5}; Line(4) = {5, 6}; Line(5) = {6, 1};
Line(6) = {2, 3}; Line(7) = {3, 4}; Line(8) = {4, 5};
Curve Loop(1) = {1, 2, 3, 4, 5}; Plane Surface(1) = {1};
Curve Loop(2) = {6, 7, 8, -3, -2}; Plane Surface(2) = {2};
Transfinite Curve{1, 4, 5, 6, 7, 8} = 3; Transfinite Curve{2, 3} = 2;
Transfinite Surface{1} = {1, 2, 5, 6}; Transfinite Surface{2} = {2, 3, 4, 5};
Recombine Surface{1, 2};
Physical Surface("matrix") = {1}; Physical Surface("hydride") = {2};
Physical Curve("notch") = {2}; Physical Curve("bottom") = {1, 6}; Physical Curve("top") = {4, 8};
Physical Point("tip") = {7};
"""


def grid(nx, ny, h=1.0, kind="T3", phases=None):
    """A structured grid of nx x ny squares (Q4, or cut into 2 T3 along the
    diagonal from bottom-left to top-right) with edge groups left/right/bottom/top."""
    def nid(i, j):
        return j * (nx + 1) + i
    nodes = [(i * h, j * h) for j in range(ny + 1) for i in range(nx + 1)]
    els, ph = [], []
    for j in range(ny):
        for i in range(nx):
            a, b, c, d = nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1)
            p = phases(i, j) if phases else "mesh"
            if kind == "Q4":
                els.append((a, b, c, d))
                ph.append(p)
            else:
                els += [(a, b, c), (a, c, d)]
                ph += [p, p]
    eg = {"bottom": [(nid(i, 0), nid(i + 1, 0)) for i in range(nx)],
          "top": [(nid(i, ny), nid(i + 1, ny)) for i in range(nx)],
          "left": [(nid(0, j), nid(0, j + 1)) for j in range(ny)],
          "right": [(nid(nx, j), nid(nx, j + 1)) for j in range(ny)]}
    return mesh_from_arrays(nodes, els, ph, edge_groups=eg)


def elastic_case(*names):
    c = Case(gravity=(0.0, 0.0))
    for n in names or ("STONE",):
        c.add_material(n, 2500.0, "ELAS", young=1e10, poisson=0.25)
    return c


def outward_ok(body):
    """Every CLxxx/ALpxx segment of a body: the outward normal (-t_y, t_x) of the
    segment walked from noda to nodb points away from the centroid of the element
    that owns the edge (elements are convex here)."""
    n_seg = 0
    for c in body.contactors:
        segs = c.segments if c.kind == "ALpxx" else [(a, b) for a, b, _ in c.points]
        for a, b in segs:
            owner = next(e for e in body.elements if a in e.nodes and b in e.nodes)
            centroid = body.nodes[[n - 1 for n in owner.nodes]].mean(axis=0)
            t = body.nodes[b - 1] - body.nodes[a - 1]
            mid = 0.5 * (body.nodes[a - 1] + body.nodes[b - 1])
            if np.dot([-t[1], t[0]], mid - centroid) <= 0.0:
                return False
            n_seg += 1
    return n_seg


# --------------------------------------------------------------------------------------
# explode: counts, families, notch, groups
# --------------------------------------------------------------------------------------

@pytest.mark.parametrize("nx, ny, kind, internal, boundary", [
    (2, 2, "T3", 2 * 1 + 1 * 2 + 4, 8),       # horizontal + vertical + diagonals
    (3, 2, "Q4", 3 * 1 + 2 * 2, 10),
    (12, 2, "T3", 12 + 22 + 24, 28),          # the mesh_exploded_beam mesh: 58 (case.md)
])
def test_explode_counts(nx, ny, kind, internal, boundary):
    c = elastic_case()
    m = grid(nx, ny, kind=kind)
    r = explode(c, m, "STONE")
    n_el = nx * ny * (2 if kind == "T3" else 1)
    assert len(r.bodies) == len(c.bodies) == n_el
    assert (r.internal_edges, r.cohesive_edges, r.boundary_edges) == (internal, internal, boundary)
    assert r.points == 2 * internal
    cl = sum(len(cc.points) for b in r.bodies for cc in b.contactors if cc.kind == "CLxxx")
    alp = [cc for b in r.bodies for cc in b.contactors if cc.kind == "ALpxx"]
    assert cl == 2 * internal and len(alp) == internal and all(len(p.segments) == 1 for p in alp)
    assert all(b.n_nodes == (3 if kind == "T3" else 4) for b in r.bodies)
    assert sum(outward_ok(b) for b in r.bodies) == 3 * internal      # 2 CL points + 1 ALp per edge
    assert c.models["M2D" + kind].element == kind + "xxx"


def test_explode_families_and_notch(tmp_path):
    """Two phases (4 Q4 each): 4 matrix/matrix, 4 hydride/hydride and 2 interface
    edges, one of them a notch left open: 9 glued edges, 18 points."""
    gmsh_mesh = pytest.importorskip("fracas_tools.mesh")
    pytest.importorskip("gmsh")
    (tmp_path / "two.geo").write_text(TWO_PHASES_GEO)
    m = gmsh_mesh.mesh_geo(tmp_path / "two.geo")
    assert Counter(k for k, _ in m.elements) == {"Q4xxx": 8}
    c = elastic_case("MATRX", "HYDRx")
    r = explode(c, m, {"matrix": "MATRX", "hydride": "HYDRx"}, cracks=["notch"])
    assert (r.internal_edges, r.crack_edges, r.cohesive_edges, r.points, r.boundary_edges) == (10, 1, 9, 18, 12)
    assert r.families == {("hydride", "hydride"): "HY_HY", ("hydride", "matrix"): "HY_MA",
                          ("matrix", "matrix"): "MA_MA"}
    assert Counter(r.edge_family.values()) == {("matrix", "matrix"): 4, ("hydride", "hydride"): 4,
                                               ("hydride", "matrix"): 1}
    per_colour = Counter(cc.color for b in r.bodies for cc in b.contactors if cc.kind == "ALpxx")
    assert per_colour == {"MA_MA": 4, "HY_HY": 4, "HY_MA": 1}
    # no contactor on the notch (x = 1, y in [0, 0.5])
    for b in r.bodies:
        for cc in b.contactors:
            segs = cc.segments if cc.kind == "ALpxx" else [(p, q) for p, q, _ in cc.points]
            for p, q in segs:
                xa, xb = b.nodes[p - 1], b.nodes[q - 1]
                assert not (xa[0] == xb[0] == 1.0 and max(xa[1], xb[1]) <= 0.5)
        assert outward_ok(b) is not False
    # materials follow the phases; the notch tip node is in 4 bodies (all its copies)
    assert {b.elements[0].material for b in r.bodies} == {"MATRX", "HYDRx"}
    assert len(r.bodies_with("tip")) == 4
    # bottom: a curve group, its nodes on the 4 bottom bodies (they own its edges)
    assert len(r.bodies_with("bottom")) == 4
    r.fix("bottom")
    r.impose_velocity("top", 2, ct=1e-3)
    r.add_see(c, {("matrix", "matrix"): "czmmm", ("matrix", "hydride"): "czmmh", "HY_HY": "czmhh"}, 1e-3)
    assert sorted((s.cdcol, s.behav) for s in c.see_rules) == [("HY_HY", "czmhh"), ("HY_MA", "czmmh"),
                                                              ("MA_MA", "czmmm")]


def test_family_colour_naming():
    assert phase_codes(["matrix", "hydride", "martensite", "m"]) == \
        {"hydride": "HY", "m": "MX", "martensite": "MA", "matrix": "M1"}
    fam = family_colors(["matrix", "hydride"])
    assert fam == {("hydride", "hydride"): "HY_HY", ("hydride", "matrix"): "HY_MA",
                   ("matrix", "matrix"): "MA_MA"}
    assert all(len(v) == 5 for v in family_colors(["a", "b", "c"]).values())
    # codes in alphabetical order, whatever the order of the phase names
    assert family_colors(["matrix", "martensite"])[("martensite", "matrix")] == "M1_MA"


def test_group_copies_all_and_edge():
    """Left side of a 2 x 2 grid of squares cut into T3: 4 triangles hold a node of
    it, 2 own one of its edges. 'all' gives the group to the 4 (every copy of a
    group node), 'edge' (LMGC90's rule for curve groups) to the 2."""
    for mode, expect in (("all", 4), ("edge", 2)):
        c = elastic_case()
        r = explode(c, grid(2, 2), "STONE", group_copies=mode)
        assert len(r.bodies_with("left")) == expect, mode
    c = elastic_case()
    r = explode(c, grid(2, 2), "STONE")
    touched = r.fix("left")
    assert sum(len(b.driven) for b in touched) == 2 * sum(len(b.groups["left"]) for b in touched)
    c.postpro = PostPro()
    c.postpro.add("NEW MECAx SETS", rows=mecax_set_rows(mecax_sets(r.bodies, ["left", "right"])))
    sets = c.postpro.get("NEW MECAx SETS").mecax_sets()
    assert [len(s) for s in sets] == [4, 4]


def test_explode_quadratic():
    """Two T6 on a unit square: the shared diagonal is glued on its two halves (4
    points, one ALpxx of 2 segments through the mid node); Q8 likewise."""
    nodes = [(0, 0), (1, 0), (1, 1), (0, 1), (0.5, 0), (1, 0.5), (0.5, 0.5), (0.5, 1), (0, 0.5)]
    m = mesh_from_arrays(nodes, [(0, 1, 2, 4, 5, 6), (0, 2, 3, 6, 7, 8)])
    c = elastic_case()
    r = explode(c, m, "STONE")
    assert (r.internal_edges, r.points) == (1, 4)
    alp = r.bodies[0].contactors[0]
    assert alp.kind == "ALpxx" and len(alp.segments) == 2 and alp.nodes[1] == 6   # local mid node
    assert outward_ok(r.bodies[0]) == 2 and outward_ok(r.bodies[1]) == 4
    q8 = mesh_from_arrays([(0, 0), (1, 0), (2, 0), (2, 1), (1, 1), (0, 1), (0.5, 0), (1.5, 0),
                           (2, 0.5), (1.5, 1), (0.5, 1), (0, 0.5), (1, 0.5)],
                          [(0, 1, 4, 5, 6, 12, 10, 11), (1, 2, 3, 4, 7, 8, 9, 12)])
    r = explode(elastic_case(), q8, "STONE")
    assert (r.internal_edges, r.points) == (1, 4) and r.bodies[0].elements[0].kind == "Q8xxx"


def test_clockwise_elements_reordered():
    m = mesh_from_arrays([(0, 0), (1, 0), (0, 1)], [(0, 2, 1)])
    assert m.elements[0][1] == (0, 1, 2)
    t6 = mesh_from_arrays([(0, 0), (1, 0), (0, 1), (0.5, 0), (0.5, 0.5), (0, 0.5)], [(0, 2, 1, 5, 4, 3)])
    assert t6.elements[0][1] == (0, 1, 2, 3, 4, 5)


# --------------------------------------------------------------------------------------
# against LMGC90
# --------------------------------------------------------------------------------------

def _mesh_of_exploded_deck(case):
    """The mesh behind LMGC90's exploded beam: bodies' nodes merged by position,
    elements in body order with LMGC90's node order; left/right edge groups."""
    index, nodes, elements = {}, [], []
    for b in case.bodies:
        el = []
        for x in b.nodes:
            k = tuple(np.round(x, 9))
            if k not in index:
                index[k] = len(nodes)
                nodes.append(x)
            el.append(index[k])
        elements.append(el)
    nodes = np.array(nodes)

    def side(x0):
        on = sorted((i for i in range(len(nodes)) if nodes[i, 0] == x0), key=lambda i: nodes[i, 1])
        return list(zip(on[:-1], on[1:]))
    return mesh_from_arrays(nodes, elements, edge_groups={"left": side(0.0), "right": side(0.12)})


@needs_decks
def test_explode_reproduces_lmgc90_exploded_beam(tmp_path):
    """LMGC90's mesh_exploded_beam, exploded again by us from its own mesh (one
    colour BLEUx, LMGC90's group rule): BODIES.DAT and DRV_DOF.DAT byte for byte."""
    ref = read_case(DECKS / "mesh_exploded_beam")
    c = Case(gravity=(0.0, 0.0))
    c.materials, c.models = ref.materials, ref.models
    r = explode(c, _mesh_of_exploded_deck(ref), "BEAMx", "M2DT3", color="BLEUx", group_copies="edge")
    assert (len(r.bodies), r.internal_edges, r.points) == (48, 58, 116)
    r.impose_velocity("left", (1, 2))
    r.impose_velocity("right", 2, ct=-0.05, rampi=0.0, ramp=500.0)
    src = DECKS / "mesh_exploded_beam" / "DATBOX"
    assert c.bodies_text() == (src / "BODIES.DAT").read_text()
    assert c.drv_dof_text() == (src / "DRV_DOF.DAT").read_text()


@needs_decks
def test_gmsh_beam_against_lmgc90():
    """The beam meshed by gmsh (transfinite 12 x 2, diagonals 'Left'): the same 48
    bodies in the same order, 58 glued edges, 116 points, each body with the same
    contactor edges (geometry, CLxxx or ALpxx) as LMGC90's. What differs is the
    first node of the upper triangle of each square (gmsh starts it at the top-left
    corner, pylmgc90 at the bottom-right one; same counter-clockwise cycle), hence
    its local node numbers and the order of its contactors."""
    gmsh = pytest.importorskip("gmsh")
    from fracas_tools.mesh import mesh_from_gmsh
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        g = gmsh.model.geo
        p = [g.addPoint(0, 0, 0), g.addPoint(0.12, 0, 0), g.addPoint(0.12, 0.02, 0), g.addPoint(0, 0.02, 0)]
        lines = [g.addLine(p[i], p[(i + 1) % 4]) for i in range(4)]
        s = g.addPlaneSurface([g.addCurveLoop(lines)])
        g.synchronize()
        for cv, n in zip(lines, (13, 3, 13, 3)):
            gmsh.model.mesh.setTransfiniteCurve(cv, n)
        gmsh.model.mesh.setTransfiniteSurface(s, "Left")
        for dim, tags, name in ((2, [s], "beam"), (1, [lines[3]], "left"), (1, [lines[1]], "right")):
            gmsh.model.setPhysicalName(dim, gmsh.model.addPhysicalGroup(dim, tags), name)
        gmsh.model.mesh.generate(2)
        mesh = mesh_from_gmsh()
    finally:
        gmsh.finalize()
    ref = read_case(DECKS / "mesh_exploded_beam")
    c = Case(gravity=(0.0, 0.0))
    c.materials, c.models = ref.materials, ref.models
    r = explode(c, mesh, "BEAMx", "M2DT3", color="BLEUx", group_copies="edge")
    assert (len(r.bodies), r.internal_edges, r.cohesive_edges, r.points) == (48, 58, 58, 116)

    def edges(b):
        out = set()
        for cc in b.contactors:
            segs = cc.segments if cc.kind == "ALpxx" else [(p, q) for p, q, _ in cc.points]
            out |= {(cc.kind, tuple(np.round(b.nodes[p - 1], 9)), tuple(np.round(b.nodes[q - 1], 9)))
                    for p, q in segs}
        return out
    rotated = 0
    for mine, theirs in zip(r.bodies, ref.bodies):
        mine_xy = np.round(mine.nodes, 9)          # gmsh's transfinite nodes are exact to ~1e-13
        assert sorted(map(tuple, mine_xy)) == sorted(map(tuple, theirs.nodes))
        assert edges(mine) == edges(theirs)
        shift = [k for k in range(3) if np.array_equal(np.roll(mine_xy, -k, axis=0), theirs.nodes)]
        assert len(shift) == 1
        rotated += shift[0] != 0
        assert (shift[0] != 0) == (mine.number % 2 == 0)       # the upper triangles
    assert rotated == 24
    assert [b.number for b in r.bodies_with("left")] == [1, 3]
    assert [b.number for b in r.bodies_with("right")] == [46, 48]


@needs_decks
def test_contactors_on_groups_reproduce_lmgc90_layouts():
    """build_bodies + add_polyline_on / add_candidates_on on the meshes of
    mesh_t3_pair_czm (ALpxx on the top of the lower block, CLxxx 0.25/0.75 on the
    bottom of the upper one) and mesh_block_drop (CLxxx at the bottom nodes): the
    BODIES.DAT records of LMGC90's decks, byte for byte."""
    for name in ("mesh_t3_pair_czm", "mesh_block_drop"):
        ref = read_case(DECKS / name)
        c = Case(gravity=(0.0, 0.0))
        c.materials, c.models = ref.materials, ref.models
        for rb in ref.bodies:
            if rb.model != "MAILx":
                c.append(rb)
                continue
            y = rb.nodes[:, 1]

            def side(yv):
                on = sorted(np.nonzero(np.isclose(y, yv))[0], key=lambda i: rb.nodes[i, 0])
                return list(zip(on[:-1], on[1:]))
            m = mesh_from_arrays(rb.nodes, [[n - 1 for n in e.nodes] for e in rb.elements],
                                 edge_groups={"bottom": side(y.min()), "top": side(y.max())})
            e0 = rb.elements[0]
            (b,) = c.add_mesh(m, e0.material, e0.model)
            for cc in rb.contactors:
                if cc.kind == "ALpxx":
                    b.add_polyline_on("top", cc.color)
                elif cc.points[0][2] == 0.25:
                    b.add_candidates_on("bottom", cc.color)
                else:
                    b.add_candidates_on("bottom", cc.color, apab="nodes")
            assert outward_ok(b)
        assert c.bodies_text() == (DECKS / name / "DATBOX" / "BODIES.DAT").read_text(), name


# --------------------------------------------------------------------------------------
# gmsh inputs, determinism, round trip
# --------------------------------------------------------------------------------------

def test_msh_formats_and_geo_agree(tmp_path):
    """The same model saved as .msh 2.2 and 4.1 reads back as the mesh of the .geo."""
    gmsh = pytest.importorskip("gmsh")
    from fracas_tools.mesh import mesh_geo, read_msh
    (tmp_path / "two.geo").write_text(TWO_PHASES_GEO)
    ref = mesh_geo(tmp_path / "two.geo")
    for version in (2.2, 4.1):
        gmsh.initialize()
        try:
            gmsh.option.setNumber("General.Terminal", 0)
            gmsh.open(str(tmp_path / "two.geo"))
            gmsh.model.mesh.generate(2)
            gmsh.option.setNumber("Mesh.MshFileVersion", version)
            gmsh.write(str(tmp_path / f"two_{version}.msh"))
        finally:
            gmsh.finalize()
        m = read_msh(tmp_path / f"two_{version}.msh")
        assert m.nodes == pytest.approx(ref.nodes, abs=1e-15), version      # 2.2 rounds to ~1e-17
        assert m.elements == ref.elements and m.phases == ref.phases
        assert {k: v.tolist() for k, v in m.node_groups.items()} == \
            {k: v.tolist() for k, v in ref.node_groups.items()}
        assert m.edge_groups == ref.edge_groups


def test_quadratic_from_geo(tmp_path):
    pytest.importorskip("gmsh")
    from fracas_tools.mesh import mesh_geo
    (tmp_path / "two.geo").write_text(TWO_PHASES_GEO)
    m = mesh_geo(tmp_path / "two.geo", order=2)
    assert Counter(k for k, _ in m.elements) == {"Q8xxx": 8}
    r = explode(elastic_case("MATRX", "HYDRx"), m, {"matrix": "MATRX", "hydride": "HYDRx"},
                cracks=["notch"])
    assert (r.cohesive_edges, r.points) == (9, 36)     # 2 halves x 2 points per glued edge
    assert all(outward_ok(b) for b in r.bodies)


def test_add_mesh_bodies_and_groups(tmp_path):
    """One body per connected part of each phase, or per group of phases; groups
    and edge groups on the bodies; candidates at nodes and polylines on groups."""
    m = grid(4, 2, kind="Q4", phases=lambda i, j: "left" if i < 2 else "right")
    c = elastic_case()
    b1, b2 = c.add_mesh(m, "STONE")
    assert (b1.n_nodes, len(b1.elements), b2.n_nodes) == (9, 4, 9)
    assert c.models["M2DQ4"].element == "Q4xxx"
    (one,) = elastic_case().add_mesh(m, "STONE", bodies=[["left", "right"]])
    assert one.n_nodes == 15 and len(one.elements) == 8
    # two islands of the same phase: two bodies
    isl = grid(3, 1, kind="Q4", phases=lambda i, j: "a" if i != 1 else "b")
    assert [len(b.elements) for b in elastic_case().add_mesh(isl, "STONE")] == [1, 1, 1]
    # polylines: the bottom walked right to left (body above, on the right)
    (p,) = one.add_polyline_on("bottom", "BOTxx")
    assert [tuple(one.nodes[n - 1]) for n in p.nodes] == [(4, 0), (3, 0), (2, 0), (1, 0), (0, 0)]
    cl = one.add_candidates_on("top", "TOPxx", apab="nodes")
    assert len(cl.points) == 5 and outward_ok(one) == 4 + 5
    one.fix("left")
    assert sorted({d.node for d in one.driven}) == one.groups["left"]
    with pytest.raises(ValueError, match="no edge group"):
        one.add_polyline_on("nowhere")


def test_deterministic_and_round_trip(tmp_path):
    pytest.importorskip("gmsh")
    from fracas_tools.mesh import mesh_geo
    (tmp_path / "two.geo").write_text(TWO_PHASES_GEO)
    texts = []
    for k in range(2):
        c = elastic_case("MATRX", "HYDRx")
        r = c.add_exploded_mesh(mesh_geo(tmp_path / "two.geo"), {"matrix": "MATRX", "hydride": "HYDRx"},
                                cracks=["notch"])
        r.fix("bottom")
        r.impose_velocity("top", 2, ct=1e-3, rampi=0.0, ramp=100.0)
        c.add_law("czmxx", "MAC_CZM", dyfr=0.3, stfr=0.3, cn=1e13, ct=1e13, b=0.0, w=10.0)
        r.add_see(c, "czmxx", 1e-3)
        c.run.set(time_step=1e-5, number_of_steps=10, plane="strain", newton_tolerance=1e-8,
                  newton_max_iterations=15, linear_solver="dense")
        c.write(tmp_path / f"case{k}")
        texts.append({f.name: f.read_bytes() for f in (tmp_path / f"case{k}" / "DATBOX").iterdir()})
    assert texts[0] == texts[1]
    back = read_case(tmp_path / "case0")
    back.write(tmp_path / "again")
    assert {f.name: f.read_bytes() for f in (tmp_path / "again" / "DATBOX").iterdir()} == texts[0]
    cmd = (tmp_path / "case0" / "DATBOX" / "COMMAND.DAT").read_text().splitlines()
    assert {"plane strain", "newton_tolerance 1e-08", "newton_max_iterations 15",
            "linear_solver dense"} <= set(cmd)
    assert back.run.values["plane"] == "strain"


def test_doc_example_runs(tmp_path, monkeypatch):
    """The example of doc/tools.md 'Meshed decks from gmsh', run as written on the
    two-phase plate above."""
    pytest.importorskip("gmsh")
    doc = (Path(__file__).resolve().parents[2] / "doc" / "tools.md").read_text()
    section = doc[doc.index("### Meshed decks from gmsh"):]
    code = section[section.index("```python") + len("```python"):]
    code = code[:code.index("```")]
    assert len(code.strip().splitlines()) <= 14
    (tmp_path / "plate.geo").write_text(TWO_PHASES_GEO)
    monkeypatch.chdir(tmp_path)
    env = {}
    exec(compile(code, "tools.md", "exec"), env)
    case = read_case(tmp_path / "hydride_plate")
    assert len(case.mesh_bodies()) == 8
    assert sorted(r.cdcol for r in case.see_rules) == ["HY_HY", "HY_MA", "MA_MA"]
    assert case.run.values["plane"] == "strain"
    assert sum(len(c.points) for b in case.bodies for c in b.contactors if c.kind == "CLxxx") == 18


def _fracas():
    import os
    exe = os.environ.get("FRACAS_BIN")
    if not exe:
        found = sorted(Path(__file__).resolve().parents[2].glob("build/*/bin/fracas"),
                       key=lambda p: p.stat().st_mtime)
        exe = str(found[-1]) if found else None
    if not exe or not os.access(exe, os.X_OK):
        pytest.skip("no built fracas binary (set FRACAS_BIN or build the project)")
    return exe


def test_generated_mesh_decks_pass_fracas_check(tmp_path):
    """Decks written by fracas_tools are read by the solver's Fortran readers
    (fracas --check): an exploded two-phase gmsh mesh with families and a notch,
    a Q4 block from add_mesh on a rigid ground, and the T3/Q8/T6/ELAS_PLAS case of
    test_tools_mailx."""
    import subprocess
    from test_tools_mailx import mesh_case      # tools/tests is on sys.path under pytest
    exe = _fracas()
    decks = []
    mesh_case().write(tmp_path / "api")
    decks.append(tmp_path / "api")
    c = elastic_case("BLOCK")
    c.add_material("TDURx", 1000.0)
    (b,) = c.add_mesh(grid(8, 4, h=0.025, kind="Q4"), "BLOCK")
    b.add_candidates_on("bottom", "BLEUx", apab="nodes")
    b.set_velocity(0.05, 0.0)
    c.add_jonc((0.1, -0.01), 0.2, 0.01, "TDURx", "WALLx").fix()
    c.add_law("gapc3", "GAP_SGR_CLB", fric=0.3)
    c.add_see("CLxxx", "BLEUx", "JONCx", "WALLx", "gapc3", 5e-3)
    c.run.set(time_step=1e-4, number_of_steps=10, plane="strain", linear_solver="auto")
    c.write(tmp_path / "block")
    decks.append(tmp_path / "block")
    if __import__("importlib").util.find_spec("gmsh"):
        from fracas_tools.mesh import mesh_geo
        (tmp_path / "two.geo").write_text(TWO_PHASES_GEO)
        c = elastic_case("MATRX", "HYDRx")
        r = c.add_exploded_mesh(mesh_geo(tmp_path / "two.geo"), {"matrix": "MATRX", "hydride": "HYDRx"},
                                cracks=["notch"])
        r.fix("bottom")
        r.impose_velocity("top", 2, ct=1e-3)
        c.add_law("czmxx", "MAC_CZM", dyfr=0.3, stfr=0.3, cn=1e13, ct=1e13, b=0.0, w=10.0)
        r.add_see(c, "czmxx", 1e-3)
        c.run.set(time_step=1e-6, number_of_steps=10, plane="strain")
        c.write(tmp_path / "exploded")
        decks.append(tmp_path / "exploded")
    for d in decks:
        p = subprocess.run([exe, "--check", str(d)], capture_output=True, text=True, timeout=60)
        assert p.returncode == 0 and "check: OK" in p.stdout, (d.name, p.stdout + p.stderr)
