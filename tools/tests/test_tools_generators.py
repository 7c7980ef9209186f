"""fracas_tools.generators: seeded, non-overlapping, counter-clockwise, ready-to-run decks."""

import math
import sys
import time
from pathlib import Path

import numpy as np
import pytest


from fracas_tools import Case, read_case  # noqa: E402
from fracas_tools import generators as gen  # noqa: E402
from fracas_tools.pre import is_convex, polygon_area  # noqa: E402


def _min_gap(centres, radii):
    d = np.sqrt(((centres[:, None, :] - centres[None, :, :]) ** 2).sum(-1))
    s = radii[:, None] + radii[None, :]
    np.fill_diagonal(d, np.inf)
    return float((d - s).min())


def test_ten_line_deposit_of_2000_disks(tmp_path):
    t0 = time.perf_counter()
    case = Case(gravity=(0.0, -9.81))
    case.add_material("STONE", density=2600.0)
    case.add_material("TDURx", density=1000.0)
    radii = gen.uniform_radii(2000, 0.004, 0.006, seed=1)
    disks = gen.deposit_disks(case, radii, width=0.5, material="STONE", seed=1)
    gen.box_walls(case, 0.0, 0.5, 0.0, gen.top_of(case, disks) + 0.01, 0.01, "TDURx")
    gen.add_granular_laws(case, fric_grains=0.3, fric_walls=0.5, alert=0.5 * radii.max())
    case.run.set(time_step=1e-3, number_of_steps=1000, output_vtk_every=10)
    case.write(tmp_path / "deposit_2000")
    assert time.perf_counter() - t0 < 5.0
    c = np.array([b.coor[:2] for b in disks])
    assert _min_gap(c, radii) > 0.0
    assert (c[:, 0] - radii).min() >= 0.0 and (c[:, 0] + radii).max() <= 0.5
    assert (c[:, 1] - radii).min() >= 0.0
    back = read_case(tmp_path / "deposit_2000")
    assert len(back.bodies) == 2003
    assert back.run["number_of_steps"] == 1000
    assert sum(1 for b in back.bodies if b.driven) == 3


def test_seeded_reproducible(tmp_path):
    a = gen.deposit_case(n=300, seed=5)
    b = gen.deposit_case(n=300, seed=5)
    c = gen.deposit_case(n=300, seed=6)
    assert a.bodies_text() == b.bodies_text()
    assert a.bodies_text() != c.bodies_text()
    p1 = gen.random_convex_polygon(6, 1.0, seed=3)
    p2 = gen.random_convex_polygon(6, 1.0, seed=3)
    assert np.array_equal(p1, p2)
    with pytest.raises(ValueError, match="seed"):
        gen.uniform_radii(3, 1, 2, seed=None)


def test_ballistic_deposit_touches_without_overlap():
    r = gen.uniform_radii(500, 0.01, 0.02, seed=2)
    c = gen.ballistic_positions(r, 0.4, seed=2)
    assert _min_gap(c, r) > -1e-12
    assert (c[:, 0] - r).min() >= 0.0 and (c[:, 0] + r).max() <= 0.4 + 1e-15
    assert np.isclose((c[:, 1] - r).min(), 0.0)
    top = (c[:, 1] + r).max()
    phi = (math.pi * r ** 2).sum() / (0.4 * top)
    assert 0.4 < phi < 0.85                          # a real deposit, not a cloud


def test_lattice_deposit_bounds():
    r = gen.uniform_radii(101, 0.5, 1.0, seed=0)
    c = gen.lattice_positions(r, 10.0, seed=0, x0=2.0, y0=-1.0)
    assert _min_gap(c, r) > 0.0
    assert (c[:, 0] - r).min() >= 2.0 and (c[:, 0] + r).max() <= 12.0
    assert (c[:, 1] - r).min() >= -1.0
    with pytest.raises(ValueError):
        gen.lattice_positions(r, 1.0, seed=0)


def test_random_and_regular_polygons():
    rng = np.random.default_rng(0)
    for n in range(3, 12):
        v = gen.random_convex_polygon(n, 0.1, rng)
        assert v.shape == (n, 2)
        assert polygon_area(v) > 0 and is_convex(v)
        assert np.allclose(np.mean(v, axis=0) * 0, 0)
        assert np.hypot(v[:, 0], v[:, 1]).max() <= 0.2
    h = gen.regular_polygon(6, 1.0)
    assert polygon_area(h) == pytest.approx(1.5 * math.sqrt(3))
    case = Case()
    case.add_material("STONE", 2600.0)
    bodies = gen.deposit_polygons(case, 50, 0.02, 0.04, 0.5, "STONE", seed=4)
    assert len(bodies) == 50
    assert all(4 <= len(b.contactors[0].vertices) <= 7 for b in bodies)
    # circumscribed circles do not overlap -> polygons do not overlap
    cen = np.array([b.coor[:2] for b in bodies])
    rad = np.array([np.hypot(*b.contactors[0].vertices.T).max() for b in bodies])
    assert _min_gap(cen, rad) > 0.0


def test_masonry_wall_running_bond(tmp_path):
    case = Case()
    case.add_material("BRICK", 2000.0)
    case.add_material("TDURx", 1000.0)
    w = gen.masonry_wall(case, 5, 4, 0.2, 0.1, "BRICK", ground_material="TDURx")
    courses = w["bricks"]
    assert [len(c) for c in courses] == [4, 5, 4, 5, 4]
    assert len(case.bodies) == 4 * 3 + 5 * 2 + 1
    for k, course in enumerate(courses):
        xs = sorted((b.coor[0] + b.contactors[0].vertices[:, 0].min(),
                     b.coor[0] + b.contactors[0].vertices[:, 0].max()) for b in course)
        assert xs[0][0] == pytest.approx(0.0) and xs[-1][1] == pytest.approx(0.8)   # flush ends
        for (a0, a1), (b0, b1) in zip(xs, xs[1:]):
            assert b0 == pytest.approx(a1)                                       # bricks touch
        ys = [b.coor[1] for b in course]
        assert ys == pytest.approx([0.05 + 0.1 * k] * len(course))
        if k % 2:
            assert xs[0][1] == pytest.approx(0.1)                                # half brick
    total = sum(polygon_area(b.contactors[0].vertices) for c in courses for b in c)
    assert total == pytest.approx(5 * 0.8 * 0.1)
    g = w["ground"]
    assert g.contactors[0].kind == "JONCx" and len(g.driven) == 3
    assert g.coor[1] + g.contactors[0].ax2 == pytest.approx(0.0)
    gen.demo_masonry(tmp_path / "m")
    assert len(read_case(tmp_path / "m").bodies) == 8 * 6 + 4 + 1


def test_arch_geometry(tmp_path):
    case = Case()
    case.add_material("STONE", 2500.0)
    N, R, t = 9, 2.0, 0.3
    a = gen.arch(case, N, R, t, "STONE", center=(1.0, 0.5))
    v = a["voussoirs"]
    assert len(v) == N and len(a["supports"]) == 2
    total = 0.0
    for k, b in enumerate(v):
        verts = b.contactors[0].vertices + b.coor[:2]
        assert polygon_area(verts) > 0 and is_convex(verts)
        total += polygon_area(verts)
        rr = np.hypot(verts[:, 0] - 1.0, verts[:, 1] - 0.5)
        assert sorted(rr) == pytest.approx([R - t / 2] * 2 + [R + t / 2] * 2)
        ang = np.arctan2(verts[:, 1] - 0.5, verts[:, 0] - 1.0)
        ang = np.where(ang < -1e-9, ang + 2 * math.pi, ang)
        assert sorted(set(np.round(ang, 9))) == pytest.approx([math.pi * k / N, math.pi * (k + 1) / N])
    # area of the polygonal ring segment
    ro, ri = R + t / 2, R - t / 2
    assert total == pytest.approx(0.5 * N * math.sin(math.pi / N) * (ro ** 2 - ri ** 2))
    for s in a["supports"]:
        top = s.coor[1] + s.contactors[0].vertices[:, 1].max()
        assert top == pytest.approx(0.5) and len(s.driven) == 3
    # springers rest on the supports: lowest voussoir faces at the springing line
    assert (v[0].coor[1] + v[0].contactors[0].vertices[:, 1].min()) == pytest.approx(0.5)
    gen.demo_arch(tmp_path / "a")
    assert len(read_case(tmp_path / "a").bodies) == 13


def test_box_walls():
    case = Case()
    case.add_material("TDURx", 1000.0)
    w = gen.box_walls(case, 0.0, 1.0, 0.0, 2.0, 0.05, "TDURx", top=True)
    assert set(w) == {"bottom", "top", "left", "right"}
    assert w["bottom"].coor[1] + 0.05 == pytest.approx(0.0)
    assert w["top"].coor[1] - 0.05 == pytest.approx(2.0)
    assert w["left"].coor[0] + 0.05 == pytest.approx(0.0)
    assert w["left"].x0[2] == pytest.approx(-math.pi / 2)
    assert w["right"].x0[2] == pytest.approx(math.pi / 2)
    assert w["left"].contactors[0].ax1 >= 1.0
    assert all(len(b.driven) == 3 for b in w.values())


def test_demo_deposit(tmp_path):
    case = gen.demo_deposit(tmp_path / "demo", n=400, seed=1)
    back = read_case(tmp_path / "demo")
    assert len(back.bodies) == 403
    assert back.run["time_step"] == 1e-3 and back.run["number_of_steps"] == 1000
    assert back.run["output_vtk_every"] == 10
    grains = [b for b in back.bodies if b.contactors[0].kind == "DISKx"]
    r = np.array([b.contactors[0].radius for b in grains])
    c = np.array([b.coor[:2] for b in grains])
    assert _min_gap(c, r) > 0.0
    assert r.min() >= 0.008 - 1e-12 and r.max() <= 0.012 + 1e-12
    walls = [b for b in back.bodies if b.contactors[0].kind == "JONCx"]
    top_wall = max(b.coor[1] + b.contactors[0].ax1 for b in walls if b.x0[2] != 0)
    assert top_wall > (c[:, 1] + r).max()                 # side walls taller than the cloud
    assert not case.check()                              # no warnings
