"""The VTU reader against a real fracas run: the VTK files hold the same bodies and
contact forces as fracas.h5 (reference: the HDF5 snapshot of the same step)."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
from fracas_tools import vtu  # noqa: E402


def _fracas():
    env = os.environ.get("FRACAS_BIN")
    if env and Path(env).exists():
        return env
    found = sorted(ROOT.glob("build/*/bin/fracas"))
    return str(found[0]) if found else None


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    exe = _fracas()
    if exe is None:
        pytest.skip("no fracas binary built")
    out = tmp_path_factory.mktemp("vtu")
    subprocess.run([exe, "-q", "--overwrite", "--output", str(out), "--set", "number_of_steps=40",
                    "--set", "output_vtk_every=20", "--set", "output_hdf5_every=20", "--set", "output_vtk_disks=points",
                    str(ROOT / "test_cases" / "examples" / "demo_deposit")], check=True)
    return out


def test_frames_match_hdf5(run):
    entries = vtu.read_pvd(run / "DISPLAY" / "fracas.pvd")
    times = sorted({t for t, _, _ in entries})
    assert len(times) == 3                               # initial state + 2 outputs
    last = {vtu.piece_of(f): f for t, p, f in entries if t == times[-1]}
    assert set(last) == {"disks", "shapes", "contacts"}      # disks as points, walls as shapes
    disks = vtu.read_vtu(last["disks"])
    shapes = vtu.read_vtu(last["shapes"])
    contacts = vtu.read_vtu(last["contacts"])
    # DISPLAY reals are Float32 (output_vtk_precision single): 7 digits
    with h5py.File(run / "OUTBOX" / "fracas.h5") as f:
        snap = f["snapshots"][sorted(f["snapshots"].keys())[-1]]
        assert disks["time"] == pytest.approx(snap.attrs["time"], abs=1e-12)   # the time is Float64
        c = snap["contacts"]
        assert len(contacts["offsets"]) == len(c["inter"])
        rn = c["reaction"][:, 1]
        np.testing.assert_allclose(contacts["point_data"]["rn"], rn, rtol=1e-6, atol=1e-6 * np.abs(rn).max())
        np.testing.assert_allclose(contacts["points"][:, :2], c["point"][:], rtol=1e-6, atol=1e-7)
        v = snap["bodies/V"][:]
        x = f["bodies/reference"][:] + snap["bodies/X"][:]
        body = disks["point_data"]["body"]
        np.testing.assert_allclose(disks["point_data"]["spin"], v[body - 1, 2], rtol=1e-6,
                                   atol=1e-6 * np.abs(v[:, 2]).max())
        np.testing.assert_allclose(disks["points"][:, :2], x[body - 1, :2], rtol=1e-6, atol=1e-7)
        np.testing.assert_allclose(disks["point_data"]["radius"], f["contactors/radius"][:][
            f["contactors/kind"][:] == 1], rtol=1e-6)
        walls = shapes["cell_data"]["body"]
        assert len(walls) == int(np.sum(f["contactors/kind"][:] != 1))


def test_render_writes_png(run, tmp_path):
    out = tmp_path / "frame.png"
    t = vtu.render(run / "DISPLAY", -1, out)
    assert out.stat().st_size > 10000 and t > 0
