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
sys.path.insert(0, str(ROOT / "tools"))
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
                    "--set", "output_vtk_every=20", "--set", "output_hdf5_every=20",
                    str(ROOT / "test_cases" / "examples" / "demo_deposit")], check=True)
    return out


def test_frames_match_hdf5(run):
    entries = vtu.read_pvd(run / "DISPLAY" / "fracas.pvd")
    times = sorted({t for t, _, _ in entries})
    assert len(times) == 3                               # initial state + 2 outputs
    last = {p: f for t, p, f in entries if t == times[-1]}
    bodies = vtu.read_vtu(last[0])
    contacts = vtu.read_vtu(last[1])
    with h5py.File(run / "OUTBOX" / "fracas.h5") as f:
        snap = f["snapshots"][sorted(f["snapshots"].keys())[-1]]
        assert bodies["time"] == pytest.approx(snap.attrs["time"], abs=1e-12)
        c = snap["contacts"]
        assert len(contacts["offsets"]) == len(c["inter"])
        np.testing.assert_allclose(contacts["cell_data"]["rn"], c["reaction"][:, 1], rtol=0, atol=1e-12)
        np.testing.assert_allclose(contacts["points"][:, :2], c["point"][:], atol=1e-15)
        v = snap["bodies/V"][:]
        body = bodies["cell_data"]["body"]
        np.testing.assert_allclose(bodies["cell_data"]["spin"], v[body - 1, 2], atol=1e-15)


def test_render_writes_png(run, tmp_path):
    out = tmp_path / "frame.png"
    t = vtu.render(run / "DISPLAY", -1, out)
    assert out.stat().st_size > 10000 and t > 0
