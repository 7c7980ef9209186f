"""fracas_tools.post on synthetic fracas.h5 files with the documented layout
(doc/output_layout.md): reading, micro-mechanics, plots, report, layout check."""

import math
import sys
from pathlib import Path

import numpy as np
import pytest

h5py = pytest.importorskip("h5py")

from fracas_tools import post, synthetic  # noqa: E402


@pytest.fixture(scope="module")
def case_dir(tmp_path_factory):
    d = tmp_path_factory.mktemp("syn") / "case"
    synthetic.make_case(d, nx=10, ny=6, n_steps=120, snapshot_every=40)
    return d


@pytest.mark.parametrize("style", ["brief", "writer"])
def test_synthetic_file_passes_check(tmp_path, style):
    p = synthetic.make_h5(tmp_path / "f.h5", help_style=style)
    errors, warns, info = post.check_h5(p)
    assert errors == [] and warns == []
    with post.Run(p) as run:
        assert run.help["status"][1] == "stick" and run.help["inter"][:2] == ["DKDKx", "DKJCx"]
        assert run.complete and run.n_bodies == 60 and run.n_snapshots == 5


def test_run_reading(case_dir):
    with post.Run(case_dir) as run:          # a case directory resolves to OUTBOX/fracas.h5
        assert run.path.name == "fracas.h5"
        assert run.x_is == "displacement"
        assert len(run.series["time"]) == 120
        assert run.time_step == 1e-3
        assert run.deck() is not None and len(run.deck().bodies) == run.n_bodies
        s = run.snapshot(-1)
        assert s.step == 120 and s.time == pytest.approx(0.12)
        assert s.X.shape == (run.n_bodies, 3) and s.contacts["normal"].shape == (s.n_contacts, 2)
        first = run.snapshot(0)
        assert first.step == 1 and first.name == "000001"
        # positions = reference + X; grains end on the settled packing
        c, width, height, walls = synthetic.scene(10, 6, 0.01)
        ng = len(c)
        assert s.pos[:ng, :2] == pytest.approx(c, abs=2e-3)
        assert s.pos[ng + 1, 2] == pytest.approx(-math.pi / 2)     # left wall turned
        assert run.name_of("status", [1, 2, 3]) == ["noctc", "stick", "slifw"]
        assert run.body_index([1, ng + 3, 999]).tolist() == [0, ng + 2, -1]
        assert [t[0] for t in run.snapshot_times()] == [1, 40, 80, 120]


def test_position_mode(tmp_path):
    p = synthetic.make_h5(tmp_path / "p.h5", x_is="position")
    with h5py.File(p, "a") as f:
        f["snapshots/000001/bodies/X"].attrs["meaning"] = "absolute position"
    with post.Run(p) as run:
        assert run.x_is == "position"
        d = synthetic.make_h5(tmp_path / "d.h5")
        with post.Run(d) as rd:
            assert run.snapshot(-1).pos == pytest.approx(rd.snapshot(-1).pos)
    with post.Run(p, x_is="displacement") as run:
        assert run.x_is == "displacement"


def test_micro_mechanics_on_hexagonal_packing(case_dir):
    with post.Run(case_dir) as run:
        s = run.snapshot(-1)
        mask = post.particle_mask(run)
        assert mask.sum() == 57 and not mask[57:].any()
        c = post.coordination(run, s, mask)
        # triangular packing: count the neighbour pairs directly
        centres, width, height, walls = synthetic.scene(10, 6, 0.01)
        d = np.sqrt(((centres[:, None] - centres[None]) ** 2).sum(-1))
        pairs = int(((d < 0.02 * (1 + 1e-9)) & (d > 0)).sum() // 2)
        assert c["grain_contacts"] == pairs
        assert c["wall_contacts"] == 10 + 2 * 3 + 0  # floor row + side contacts of even rows
        assert c["z"] == pytest.approx((2 * pairs + c["wall_contacts"]) / 57)
        assert c["rattler_fraction"] == 0.0
        # packing fraction of a triangular packing of equal disks, inside the bulk
        phi = post.packing_fraction(run, s, (0.03, 0.17, 0.02, 0.07), mask)
        assert phi == pytest.approx(math.pi / (2 * math.sqrt(3)), rel=0.02)
        # fabric of the bulk directions 0, 60, 120 deg: nearly isotropic, horizontal excess
        fb = post.fabric(run, s, mask)
        assert np.trace(fb["F"]) == pytest.approx(1.0)
        assert 0.0 <= fb["anisotropy"] < 0.15
        evo = post.microstructure_evolution(run)
        assert len(evo["time"]) == 4 and np.all(np.isfinite(evo["packing_fraction"]))


class _Snap:
    def __init__(self, normals, rn, cd, an, pos):
        nc = len(rn)
        self.contacts = {"normal": np.array(normals, float).reshape(nc, 2),
                         "reaction": np.column_stack((np.zeros(nc), rn)),
                         "cd_body": np.array(cd), "an_body": np.array(an),
                         "point": np.zeros((nc, 2))}
        self.pos = np.array(pos, float)
        self.n_contacts = nc


class _Run:
    def __init__(self, n):
        self.n_bodies = n
        self.bodies = {"radius": np.ones(n)}

    def body_index(self, numbers):
        return np.atleast_1d(numbers) - 1


def test_fabric_and_coordination_by_hand():
    run = _Run(4)
    mask = np.array([True, True, True, False])
    # two vertical contacts and one horizontal; one contact with the wall (body 4)
    s = _Snap([[0, 1], [0, -1], [1, 0], [0, 1]], [1.0, 3.0, 2.0, 5.0], [1, 2, 1, 3], [2, 3, 3, 4],
              np.zeros((4, 3)))
    fb = post.fabric(run, s, mask)
    assert fb["F"] == pytest.approx(np.array([[1 / 3, 0], [0, 2 / 3]]))
    assert fb["anisotropy"] == pytest.approx(2 * (2 / 3 - 1 / 3))
    assert fb["direction"] == pytest.approx(math.pi / 2)
    fw = post.fabric(run, s, mask, weighted=True)
    assert fw["F"][1, 1] == pytest.approx(4 / 6)
    c = post.coordination(run, s, mask)
    # pairs (1,2) (2,3) (1,3) (3,4): body 3 has 3 contacts incl. the wall
    assert c["grain_contacts"] == 3 and c["wall_contacts"] == 1
    assert c["z"] == pytest.approx((2 + 2 + 3) / 3)
    # a zero-force contact does not count
    s.contacts["reaction"][2, 1] = 0.0
    assert post.coordination(run, s, mask)["grain_contacts"] == 2


def test_disk_and_polygon_areas_in_window():
    r = np.array([1.0, 1.0, 1.0, 1.0])
    a = post._disk_rect_area(np.array([0.0, 5.0, 0.0, 0.0]), np.array([0.0, 0.0, 0.0, 0.0]), r,
                             -10, 10, -10, 10)
    assert a[:2] == pytest.approx([math.pi, math.pi])
    half = post._disk_rect_area(np.array([0.0]), np.array([0.0]), np.array([1.0]), 0, 10, -10, 10)
    quarter = post._disk_rect_area(np.array([0.0]), np.array([0.0]), np.array([1.0]), 0, 10, 0, 10)
    assert half[0] == pytest.approx(math.pi / 2, rel=1e-10)
    assert quarter[0] == pytest.approx(math.pi / 4, rel=1e-10)
    # circular segment: chord at x = 0.5
    seg = post._disk_rect_area(np.array([0.0]), np.array([0.0]), np.array([1.0]), 0.5, 10, -10, 10)
    assert seg[0] == pytest.approx(math.acos(0.5) - 0.5 * math.sqrt(0.75), rel=1e-8)
    sq = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]], float)
    c = post._clip_polygon_rect(sq, 0, 5, 0, 5)
    xx, yy = c[:, 0], c[:, 1]
    assert 0.5 * abs(np.sum(xx * np.roll(yy, -1) - np.roll(xx, -1) * yy)) == pytest.approx(1.0)
    assert len(post._clip_polygon_rect(sq, 3, 5, 3, 5)) == 0


def test_plots_and_report(case_dir):
    out = post.report(case_dir)
    assert out == case_dir / "report" / "report.md"
    text = out.read_text()
    for png in ("energy.png", "energy_balance.png", "solver.png", "contacts.png",
                "force_network.png", "fabric.png", "microstructure.png"):
        assert f"]({png})" in text
        p = case_dir / "report" / png
        assert p.stat().st_size > 5000
        assert p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "packing fraction in window" in text and "| coordination z |" in text
    assert "not complete" not in text
    with post.Run(case_dir) as run:
        table = post.summary_table([post.summary(run), post.summary(run)])
    assert table.count("\n") == 3 and "| steps |" in table and "| 120 |" in table


def test_incomplete_run_and_missing_series(tmp_path):
    d = tmp_path / "c"
    synthetic.make_case(d, nx=6, ny=3, complete=False,
                        missing=("wall_time", "quad_dv", "maxm_dv", "balance_error", "work_driven",
                                 "residual_natural_map", "mean_overlap", "max_overlap"))
    # one column one row longer, as after a crash between two flushes
    with h5py.File(d / "OUTBOX" / "fracas.h5", "a") as f:
        ds = f["series/kinetic_energy"]
        ds.resize((ds.shape[0] + 1,))
    errors, warns, info = post.check_h5(d / "OUTBOX" / "fracas.h5")
    assert errors == []
    assert any("complete = 0" in w for w in warns)
    assert any("different lengths" in w for w in warns)
    assert any("wall_time" in i for i in info)
    with post.Run(d) as run:
        assert len({len(v) for v in run.series.values()}) == 1
    text = post.report(d).read_text()
    assert "not complete" in text and "`balance_error`" in text
    assert "wall time [s] | - |" in text


def test_report_without_deck_and_without_snapshots(tmp_path):
    p = synthetic.make_h5(tmp_path / "alone" / "OUTBOX" / "fracas.h5", nx=6, ny=3, n_steps=20,
                          snapshot_every=20)
    text = post.report(tmp_path / "alone").read_text()
    assert "DATBOX was not found" in text and "force_network.png" in text
    with post.Run(p) as run:
        assert post.particle_mask(run).sum() == 6 * 2 + 5   # walls guessed from their radius
    q = tmp_path / "nosnap.h5"
    synthetic.make_h5(q, nx=4, ny=2, n_steps=20)
    with h5py.File(q, "a") as f:
        del f["snapshots"]
        f.create_group("snapshots")
    text = post.report(tmp_path / "ns", h5=q).read_text()
    assert "No snapshot" in text


def test_check_h5_finds_layout_errors(tmp_path):
    p = synthetic.make_h5(tmp_path / "bad.h5")
    with h5py.File(p, "a") as f:
        del f.attrs["theta"]
        del f["snapshots/000002/bodies/V"]
        f["snapshots/000002/bodies"].create_dataset("V", data=np.zeros((3, 3)))
        st = f["snapshots/000003/contacts/status"]
        st[0] = 42
        cb = f["snapshots/000004/contacts/cd_body"]
        cb[0] = 9999
        del f["series/time"]
        f["series"].create_dataset("time", data=np.zeros(7))
        nrm = f["snapshots/000005/contacts/normal"]
        nrm[0, :] = [2.0, 0.0]
    errors, warns, info = post.check_h5(p)
    text = "\n".join(errors)
    assert "'theta' missing" in text
    assert "000002/bodies/V shape" in text
    assert "000003/contacts/status: ids outside" in text
    assert "000004/contacts/cd_body: unknown body numbers [9999]" in text
    assert "different lengths" in text
    assert any("not unit vectors" in w for w in warns)
    errors, _, _ = post.check_h5(tmp_path / "missing.h5")
    assert errors and "cannot open" in errors[0]
