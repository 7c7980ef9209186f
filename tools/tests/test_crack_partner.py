"""Crack tracking follows the contact that glued a point, not any contact of that point.

Two glued triangles A, B (an exploded two-element mesh, interface family MA_MA) and a
third element C whose ALpxx edge (colour MA_MA, so B's cohesive points see it) is
driven through A (no rule joins A and C) up to within the alert distance of the A-B
interface. B's points then see two antagonists within the alert distance; as LMGC90
they keep one contact each, with the nearest (A's edge, gap 0), so C makes none. The
A-B interface is intact: it must stay unbroken with beta 1 and
no damage energy, the damage per family equal to the solver's damage_dissipated (0).
Reference: nothing loads the interface (A fixed, B free, C never touches B).
"""
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from fracas_tools import Case  # noqa: E402
from fracas_tools.mesh import mesh_from_arrays  # noqa: E402

h5py = pytest.importorskip("h5py")
ROOT = Path(__file__).resolve().parents[2]


def fracas_bin():
    for c in (os.environ.get("FRACAS_BIN"), ROOT / "build/release/bin/fracas", ROOT / "build/debug/bin/fracas"):
        if c and Path(c).is_file():
            return str(c)
    pytest.skip("no fracas binary")


def test_second_contact_of_a_glued_point_does_not_break_it(tmp_path):
    L, alert, d0, v, dt, steps = 1e-3, 1e-5, 5e-5, 1.0, 1e-6, 30
    mesh = mesh_from_arrays([[0, 0], [L, 0], [L, L], [0, L]], [(0, 1, 3), (1, 2, 3)], ["matrix", "matrix"],
                            node_groups={"a": [0, 1, 3]})
    case = Case(gravity=(0.0, 0.0))
    case.add_material("STEEL", 7800.0, "ELAS", young=2e11, poisson=0.3)
    parts = case.add_exploded_mesh(mesh, "STEEL")
    assert list(parts.families.values()) == ["MA_MA"]
    parts.bodies[0].impose_velocity([1, 2, 3], (1, 2), ct=0.0)          # A fixed
    # C: its edge parallel to the A-B interface (x + y = L), d0 (normal) away on A's side,
    # walked with C on the right (outward normal (1, 1)/sqrt(2), towards B)
    s = d0 / np.sqrt(2.0)
    pts = np.array([[1.1 * L, -0.1 * L], [-0.1 * L, 1.1 * L], [-0.1 * L, -0.1 * L]]) - s
    c = case.add_mesh_body(pts, [(1, 2, 3)], model="M2DT3", material="STEEL")
    c.add_polyline([2, 1], "MA_MA")
    c.impose_velocity([1, 2, 3], (1, 2), ct=v)                         # towards B, normal speed v sqrt(2)
    case.add_law("czmmm", "MAL_CZM", dyfr=0.3, stfr=0.3, cn=1e15, ct=1e15, s1=1e8, s2=1e8, G1=10.0, G2=10.0)
    parts.add_see(case, {"MA_MA": "czmmm"}, alert=alert)
    case.run.set(time_step=dt, number_of_steps=steps, output_hdf5_every=1, plane="strain")
    case.write(tmp_path)
    r = subprocess.run([fracas_bin(), "-q", str(tmp_path)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with h5py.File(tmp_path / "OUTBOX" / "fracas.h5", "r") as f:
        last = f["snapshots"][sorted(f["snapshots"])[-1]]
        # C's edge came within the alert, but B's points keep their nearest antagonist, A
        cd = last["contacts/cd_body"][:]
        assert len(cd) == 2
        assert last["contacts/an_body"][:].tolist() == [1, 1]
        gap = d0 - np.sqrt(2.0) * v * dt * steps
        assert 0 < gap < alert
        cr = last["cracks"]
        assert cr["edge_broken_step"][:].tolist() == [0]
        assert cr["edge_beta"][:].tolist() == [1.0]
        assert cr["damage_per_family"][:].tolist() == [0.0]
        assert f["series/damage_dissipated"][-1] == 0.0
        assert f["series/broken_interfaces"][-1] == 0.0
