"""The one reader of fracas.h5 (fracas_tools.results), the one Checker
(fracas_tools.checks) and the helpers of the validation scripts (tools/validation/valtools,
tools/validation_polygons/polytools), against numbers known by construction: a synthetic
results file (fracas_tools.synthetic), the same file given meshed-body data (a /mesh group
and bodies of 2 dofs: nothing may assume rigid (nb, 3) arrays), a Gauss-Seidel rate known
in closed form and geometry helpers with exact answers."""

import sys
from pathlib import Path

import numpy as np
import pytest

TOOLS = Path(__file__).resolve().parents[1]

h5py = pytest.importorskip("h5py")
from fracas_tools import synthetic  # noqa: E402
from fracas_tools.checks import Checker  # noqa: E402
from fracas_tools.results import Results, Run  # noqa: E402
from fracas_tools import polytools  # noqa: E402
from fracas_tools import valtools  # noqa: E402


@pytest.fixture()
def h5(tmp_path):
    p = tmp_path / "OUTBOX" / "fracas.h5"
    p.parent.mkdir()
    synthetic.make_h5(p, nx=4, ny=3, n_steps=20, snapshot_every=5, help_style="writer")
    return p


def test_run_and_results_agree(h5):
    with Run(h5) as run:
        nb, names = run.n_bodies, run.snapshot_names
        last = run.snapshot(-1)
        series = {k: v.copy() for k, v in run.series.items()}
        with h5py.File(h5, "r") as f:
            raw_x = f["snapshots"][names[-1]]["bodies/X"][()]
            raw_r = f["snapshots"][names[-1]]["contacts/reaction"][()]
    res = Results(h5.parent.parent)                 # a run directory resolves to OUTBOX/fracas.h5
    assert res.complete and len(res.step) == len(names) == 5      # steps 0, 5, .., 20
    assert res.X.shape == (5, nb, 3) and np.array_equal(res.X[-1], raw_x) and np.array_equal(last.X, raw_x)
    assert np.array_equal(res.contacts[-1]["reaction"], raw_r)
    assert np.array_equal(res.contacts[-1]["rn"], raw_r[:, 1])
    assert all(np.array_equal(series[k], res.series[k]) for k in series)
    assert res.contacts[-1]["internals"].shape == (len(raw_r), 0)     # no cohesive law
    # the resultant on a body is the sum of its contacts' global reactions, signed by role
    c = res.contacts[-1]
    b = int(c["cd"][0])
    R = res.global_reactions(-1)
    ref = R[c["cd"] == b].sum(axis=0) - R[c["an"] == b].sum(axis=0)
    assert np.allclose(res.force_on(-1, b), ref, rtol=0, atol=0)
    assert res.mesh == {} and res.body_model == "RBDY2"


def test_meshed_layout_is_read(h5):
    """Bodies of 2 dofs (mesh nodes) and a /mesh group: read as they are."""
    with h5py.File(h5, "r+") as f:
        nb = len(f["bodies/number"])
        del f["bodies/reference"]
        f["bodies/reference"] = np.arange(2.0 * nb).reshape(nb, 2)
        f["bodies"].attrs["model"] = "MAILx"
        m = f.create_group("mesh")
        m["nodes"] = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
        m["elements"] = np.array([[1, 2, 3]])
        m.attrs["interface_families"] = "MA_MA HY_MA"
        for name in f["snapshots"]:
            g = f["snapshots"][name]
            for k in ("X", "V"):
                a = g["bodies"][k][()][:, :2].copy()
                del g["bodies"][k]
                g["bodies"][k] = a
            g.create_group("mesh")["stress"] = np.ones((1, 4))
            g["mesh_X"] = np.full((3, 2), 0.5)              # as fracas writes the meshes' state
            g["mesh_gauss_points"] = np.zeros((1, 13))
            g.create_group("cracks")["edge_beta"] = np.array([1.0, 0.0])
    res = Results(h5)
    assert res.body_model == "MAILx"
    assert res.X.shape[2] == 2 and res.position.shape == res.X.shape
    assert np.array_equal(res.position[-1], res.ref + res.X[-1])
    assert res.mesh["elements"].tolist() == [[1, 2, 3]]
    snap = res.snapshot(-1)
    assert snap.X.shape == (nb, 2) and snap.mesh["stress"].shape == (1, 4)
    assert snap.mesh["X"].tolist() == [[0.5, 0.5]] * 3 and snap.mesh["gauss_points"].shape == (1, 13)
    xs = res.snapshot_arrays("mesh_X")
    assert len(xs) == res.n_snapshots and all(np.array_equal(x, snap.mesh["X"]) for x in xs)
    assert snap.mesh["cracks"]["edge_beta"].tolist() == [1.0, 0.0]
    assert res.mesh_attrs["interface_families"] == "MA_MA HY_MA"


def test_checker_counts():
    ck = Checker("unit")
    assert ck.close("a", 1.0, 1.0 + 1e-12, 1e-9)
    assert not ck.rel("b", 1.1, 1.0, 0.05)
    assert ck.at_most("c", 0.5, 1.0) and ck.at_least("d", 2.0, 1.0) and ck.true("e", True)
    assert ck.finish() == 1                       # one failure -> exit status 1


def test_chain_gauss_seidel_rate():
    # two contacts between three equal masses: W = [[2, -1], [-1, 2]] / m; Gauss-Seidel
    # iterates with -L^-1 U = [[0, 1/2], [0, 1/4]]: spectral radius 1/4
    assert valtools.chain_gauss_seidel_rate([1.0, 1.0, 1.0]) == pytest.approx(0.25, abs=1e-14)
    # one contact: Gauss-Seidel solves it in one sweep
    assert valtools.chain_gauss_seidel_rate([2.0, 3.0]) == pytest.approx(0.0, abs=1e-15)


def test_polytools_geometry():
    r = polytools.rect(2.0, 1.0, 1.0, 0.5)
    area = 0.5 * np.sum(r[:, 0] * np.roll(r[:, 1], -1) - np.roll(r[:, 0], -1) * r[:, 1])
    assert area == pytest.approx(2.0, abs=1e-15)      # counter-clockwise, 2 x 1
    assert np.allclose(polytools.rot(np.pi / 2) @ polytools.unit(0.0), polytools.unit(np.pi / 2), atol=1e-16)
    assert polytools.r8(1.234567891234) == 1.2345679
    c, err, _ = polytools.snap_on_line([0.0, 0.0], [np.cos(0.3), np.sin(0.3)],
                                       [-np.sin(0.3), np.cos(0.3)], 0.1, 0.5)
    assert err < 1e-12 and all(polytools.r8(x) == x for x in c)
