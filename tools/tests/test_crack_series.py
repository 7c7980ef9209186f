"""The crack series of a run (end to end; the unit test test_crack_definitions.f90 checks
fracas_cracks on a hand-made interface): what a broken interface edge and the crack length are (doc/output_layout.md, fracas_cracks):
an edge is broken when all its glued points are broken (beta 0), and crack_length sums the
lengths of the broken edges; an edge with one point broken and one still holding is
damaged, not broken. (Marking an edge broken when any one of its points is, left every
fracture test but the long ones green: issue 17.)

Two glued triangles A, B of an exploded mesh (the interface: the diagonal from (L, 0) to
(0, L), two cohesive points at a quarter and three quarters of it), A held, B's nodes
driven. Reference: the driven kinematics. A rigid rotation of B about (L, 0) opens the
points by 1.4e-7 and 4.2e-7 m at the end: MAL_CZM (s 1e8 Pa, G 10 J/m^2, c 1e15 Pa/m)
separates at d_i + d_k = 1.75e-7 m, so one point is broken and the other softening (beta
0.51). A translation along the normal opens both by 4e-7 m: both broken.
"""
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

from fracas_tools import Case  # noqa: E402
from fracas_tools.mesh import mesh_from_arrays  # noqa: E402

h5py = pytest.importorskip("h5py")
ROOT = Path(__file__).resolve().parents[2]
L, DT, STEPS = 1e-3, 1e-7, 50


def fracas_bin():
    for c in (os.environ.get("FRACAS_BIN"), ROOT / "build/release/bin/fracas", ROOT / "build/debug/bin/fracas"):
        if c and Path(c).is_file():
            return str(c)
    pytest.skip("no fracas binary")


def run(tmp_path, omega, v_normal):
    """B driven at the rigid rotation omega about (L, 0) plus v_normal along (1, 1)/sqrt(2)."""
    mesh = mesh_from_arrays([[0, 0], [L, 0], [L, L], [0, L]], [(0, 1, 3), (1, 2, 3)], ["matrix", "matrix"])
    case = Case(gravity=(0.0, 0.0))
    case.add_material("STEEL", 7800.0, "ELAS", young=2e11, poisson=0.3)
    parts = case.add_exploded_mesh(mesh, "STEEL")
    a, b = parts.bodies
    a.impose_velocity([1, 2, 3], (1, 2), ct=0.0)
    t = v_normal / np.sqrt(2.0)
    for k, (vx, vy) in enumerate([(0.0, 0.0), (omega * L, 0.0), (omega * L, omega * L)], start=1):
        b.impose_velocity([k], (1,), ct=vx + t)
        b.impose_velocity([k], (2,), ct=vy + t)
    case.add_law("czmmm", "MAL_CZM", dyfr=0.3, stfr=0.3, cn=1e15, ct=1e15, s1=1e8, s2=1e8, G1=10.0, G2=10.0)
    parts.add_see(case, {"MA_MA": "czmmm"}, alert=1e-5)
    case.run.set(time_step=DT, number_of_steps=STEPS, output_hdf5_every=STEPS, plane="strain")
    case.write(tmp_path)
    r = subprocess.run([fracas_bin(), "-q", str(tmp_path)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    f = h5py.File(tmp_path / "OUTBOX" / "fracas.h5", "r")
    return f, f["snapshots"][sorted(f["snapshots"], key=int)[-1]]


def test_one_point_broken_is_not_a_broken_edge(tmp_path):
    f, last = run(tmp_path, omega=80.0, v_normal=0.0)
    with f:
        beta = sorted(last["contacts/internals"][:, 3])
        assert beta[0] == 0.0 and 0.4 < beta[1] < 0.6          # one point broken, one softening
        assert f["series/broken_interfaces"][-1] == 0
        assert f["series/crack_length"][-1] == 0.0
        assert last["cracks/edge_broken_step"][:].tolist() == [0]
        assert last["cracks/edge_beta"][:].tolist() == [0.0]     # the lowest beta of its points
        assert f["series/damaged_length"][-1] == pytest.approx(np.sqrt(2.0) * L, rel=1e-12)


def test_all_points_broken_is_a_broken_edge_of_its_length(tmp_path):
    f, last = run(tmp_path, omega=0.0, v_normal=0.08)
    with f:
        assert last["contacts/internals"][:, 3].tolist() == [0.0, 0.0]
        assert f["series/broken_interfaces"][-1] == 1
        assert f["series/crack_length"][-1] == pytest.approx(np.sqrt(2.0) * L, rel=1e-12)
        assert 0 < last["cracks/edge_broken_step"][0] <= STEPS
        assert f["series/damaged_length"][-1] == 0.0
