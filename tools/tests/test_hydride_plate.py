"""tools/hydride/hydride_plate.py: the hydride placement and the deck are deterministic
for a seed, hydrides do not overlap and cover the requested area fraction, the mesh
puts at least two elements across each hydride, the three interface families and
the laws come out as documented (doc/hydrided_zircaloy.md)."""
import filecmp
import math
import sys
from pathlib import Path

import numpy as np
import pytest

from fracas_tools.scripts import load

hp = load(Path(__file__).resolve().parents[1] / "hydride" / "hydride_plate.py")

pytest.importorskip("gmsh")

SMALL = hp.Geometry(width=16e-6, height=16e-6, thickness=(2e-6, 2.2e-6), aspect=(2.5, 3.5),
                    clearance=0.8e-6, notch=2.5e-6)


def test_placement_is_deterministic_and_valid():
    a = hp.place_hydrides(hp.Geometry(), 7)
    b = hp.place_hydrides(hp.Geometry(), 7)
    c = hp.place_hydrides(hp.Geometry(), 8)
    assert a == b
    assert a != c
    for g, hyd in ((hp.Geometry(), a), (hp.Geometry(), c), (SMALL, hp.place_hydrides(SMALL, 1))):
        area = sum(length * t for _, _, length, t in hyd)
        assert area / (g.width * g.height) == pytest.approx(g.area_fraction, rel=1e-6)
        for i, (x, y, length, t) in enumerate(hyd):
            assert g.clearance <= x and x + length <= g.width - g.clearance * (1 - 1e-12)
            assert g.clearance <= y and y + t <= g.height - g.clearance * (1 - 1e-12)
            assert g.thickness[0] * (1 - 1e-12) <= t <= g.thickness[1]
            for x2, y2, l2, t2 in hyd[i + 1:]:       # no overlap, clearance kept
                apart_x = x + length + g.clearance <= x2 + 1e-15 or x2 + l2 + g.clearance <= x + 1e-15
                apart_y = y + t + g.clearance <= y2 + 1e-15 or y2 + t2 + g.clearance <= y + 1e-15
                assert apart_x or apart_y
            # away from the notch (bottom edge, middle, length g.notch)
            assert not (x - g.clearance < g.width / 2 < x + length + g.clearance and y < g.notch + g.clearance)


def test_same_seed_same_deck(tmp_path):
    for name in ("a", "b"):
        hp.generate(tmp_path / name, 3, 1e-6, "weak", SMALL, steps=10)
    hp.generate(tmp_path / "c", 4, 1e-6, "weak", SMALL, steps=10)
    files = sorted(p.name for p in (tmp_path / "a" / "DATBOX").iterdir())
    assert "BODIES.DAT" in files and "POSTPRO.DAT" in files
    match, mismatch, errors = filecmp.cmpfiles(tmp_path / "a" / "DATBOX", tmp_path / "b" / "DATBOX", files,
                                               shallow=False)
    assert mismatch == [] and errors == []
    assert not filecmp.cmp(tmp_path / "a" / "DATBOX" / "BODIES.DAT", tmp_path / "c" / "DATBOX" / "BODIES.DAT",
                           shallow=False)


def test_mesh_phases_families_and_laws(tmp_path):
    hyd = hp.place_hydrides(SMALL, 3)
    h = 1e-6
    mesh = hp.build_mesh(SMALL, hyd, h)
    # phases: element centroids inside a rectangle are hydride, the others matrix
    xy = mesh.nodes
    for (kind, nodes), phase in zip(mesh.elements, mesh.phases):
        cx, cy = xy[list(nodes)].mean(axis=0)
        inside = any(x < cx < x + length and y < cy < y + t for x, y, length, t in hyd)
        assert (phase == "hydride") == inside
    # hydride area from the mesh = the placed area
    area = sum(0.5 * abs(np.cross(xy[n[1]] - xy[n[0]], xy[n[2]] - xy[n[0]]))
               for (_, n), ph in zip(mesh.elements, mesh.phases) if ph == "hydride")
    assert area == pytest.approx(sum(length * t for _, _, length, t in hyd), rel=1e-9)
    # at least two elements across: every vertical line through a hydride crosses >= 2 elements
    for x, y, length, t in hyd:
        xs = x + 0.37 * length
        crossed = 0
        for (_, n), ph in zip(mesh.elements, mesh.phases):
            p = xy[list(n)]
            if ph == "hydride" and p[:, 0].min() < xs < p[:, 0].max() and y < p[:, 1].mean() < y + t:
                crossed += 1
        assert crossed >= 2
    # the notch is an open crack in the mesh, the edges are where they should be
    assert set(mesh.edge_groups) == {"left", "right", "bottom", "top", "notch"}
    notch = np.array(mesh.edge_groups["notch"])
    assert np.allclose(xy[notch.ravel(), 0], SMALL.width / 2)
    assert xy[notch.ravel(), 1].max() == pytest.approx(SMALL.notch)
    case, parts, laws, contact = hp.make_case(mesh, hp.mean_edge(mesh), bonding="strong", steps=10)
    assert set(parts.families.values()) == {"MA_MA", "HY_HY", "HY_MA"}
    assert parts.crack_edges == len(notch)
    # laws: MAL_CZM, Blal stiffness, interface = alpha G_h, sqrt(alpha) s_h
    coh = hp.Cohesion()
    for color, (name, p) in laws.items():
        assert case.laws[name].law == "MAL_CZM"
        assert p["s1"] == p["s2"] and p["G1"] == p["G2"]
    assert laws["HY_MA"][1]["G1"] == pytest.approx(coh.alpha["strong"] * coh.hydride_energy)
    weak = hp.family_laws(hp.Matrix(), hp.Hydride(), coh, "weak", h)
    assert weak["HY_MA"][1]["s1"] == pytest.approx(math.sqrt(coh.alpha["weak"]) * coh.hydride_strength)
    cn, ct = hp.blal_stiffness(100e9, 0.36, h, 23.0)
    assert weak["MA_MA"][1]["cn"] == pytest.approx(cn) and ct / cn == pytest.approx(2 * 0.28 / 2.08)
    # the alert sits between the laws' critical opening and the spurious distance
    assert contact["critical_opening"] < contact["alert"] < contact["spurious_distance"]


def test_thin_hydrides_refused(tmp_path):
    with pytest.raises(ValueError, match="two elements"):
        hp.generate(tmp_path / "x", 1, 1.5e-6, "weak", SMALL, steps=10)


def test_ctest_decks_are_the_generators(tmp_path):
    """The committed decks of validation.hydrided_plate are what gen.py writes today
    (a change of the generator that moves them shows here, not as a changed result)."""
    here = Path(__file__).resolve().parents[2] / "test_cases" / "validation" / "hydrided_plate"
    gen = load(here / "gen.py")
    gen.write(tmp_path / "weak", "weak")
    files = sorted(p.name for p in (here / "weak" / "DATBOX").iterdir())
    match, mismatch, errors = filecmp.cmpfiles(here / "weak" / "DATBOX", tmp_path / "weak" / "DATBOX", files,
                                               shallow=False)
    assert mismatch == [] and errors == []


def test_phases_when_the_matrix_centre_falls_in_a_hydride():
    """Seed 4 of the default plate puts a hydride over the plate's centre, where the
    matrix's centre of mass lies: the phases must still come out right (the hydride
    elements cover the placed area, 20 % of the plate)."""
    g = hp.Geometry()
    hyd = hp.place_hydrides(g, 4)
    assert any(x < g.width / 2 < x + length and y < g.height / 2 < y + t for x, y, length, t in hyd)
    mesh = hp.build_mesh(g, hyd, 1e-6)
    xy = mesh.nodes
    area = sum(0.5 * abs(np.cross(xy[n[1]] - xy[n[0]], xy[n[2]] - xy[n[0]]))
               for (_, n), ph in zip(mesh.elements, mesh.phases) if ph == "hydride")
    assert area / (g.width * g.height) == pytest.approx(g.area_fraction, rel=1e-9)


def test_hydride_surface_by_bounding_box():
    boxes = [(2.0, 2.0, 10.0, 2.0)]
    assert hp.is_hydride_surface((2.0, 2.0, 0.0, 12.0, 4.0, 0.0), boxes, 1e-6)
    assert not hp.is_hydride_surface((0.0, 0.0, 0.0, 32.0, 32.0, 0.0), boxes, 1e-6)   # the matrix
