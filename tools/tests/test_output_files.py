"""Fracas output files read by outside tools: fracas.h5 by h5py, .vtu/.pvd by an XML
parser, against the layout of doc/output_layout.md.

The files are made by the Fortran helper ``make_sample_results`` (built from
test_cases/unit/make_sample_results.f90). Its path comes from the environment
variable FRACAS_MAKE_SAMPLE (set by ctest), else from a build tree of the
repository (build/*/test_cases/unit/); without it the tests are skipped.

    FRACAS_MAKE_SAMPLE=build/release/test_cases/unit/make_sample_results \\
        build/release/bin/fracas-python -m pytest -q tools/tests/test_output_files.py
"""

import glob
import os
import subprocess
import xml.etree.ElementTree as ET
import zlib
from pathlib import Path

import h5py
import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]
NB, NC = 3, 2
COLUMNS = ["step", "time", "contacts", "sweeps", "converged", "kinetic_energy"]


def sample_program():
    exe = os.environ.get("FRACAS_MAKE_SAMPLE")
    if exe:
        return exe
    found = sorted(glob.glob(str(REPO / "build" / "*" / "test_cases" / "unit" / "make_sample_results")),
                   key=os.path.getmtime)
    if not found:
        pytest.skip("make_sample_results not built (set FRACAS_MAKE_SAMPLE)")
    return found[-1]


def run_sample(outdir, *options):
    return subprocess.run([sample_program(), str(outdir), *options], capture_output=True, text=True,
                          timeout=120)


@pytest.fixture(scope="module")
def sample(tmp_path_factory):
    outdir = tmp_path_factory.mktemp("sample")
    proc = run_sample(outdir)
    assert proc.returncode == 0, proc.stderr
    return outdir


# ----------------------------------------------------------------------------- fracas.h5

def test_root_attributes(sample):
    with h5py.File(sample / "fracas.h5", "r") as f:
        a = f.attrs
        assert a["program"] == "fracas"
        assert isinstance(a["version"], str)
        assert a["layout_version"] == 1
        assert a["case_dir"] == str(sample)
        assert a["complete"] == 1
        assert a["time_step"] == pytest.approx(1e-3)
        assert a["theta"] == pytest.approx(0.5)
        assert "T" in a["created"]


def test_bodies(sample):
    with h5py.File(sample / "fracas.h5", "r") as f:
        b = f["bodies"]
        assert b.attrs["model"] == "RBDY2"
        assert b.attrs["count"] == NB
        assert b["number"].dtype == np.int32 and list(b["number"][:]) == [1, 2, 3]
        for name in ("mass", "inertia", "radius"):
            assert b[name].shape == (NB,) and b[name].dtype == np.float64
        assert b["reference"].shape == (NB, 3)
        np.testing.assert_allclose(b["reference"][2], [1.0, 1.7, 0.0])
        np.testing.assert_allclose(b["radius"][:], [1.0, 1.0, 0.9])


def test_series(sample):
    with h5py.File(sample / "fracas.h5", "r") as f:
        s = f["series"]
        assert list(s) == COLUMNS                       # creation order kept
        assert s.attrs["columns"].split(",") == COLUMNS
        assert list(f["help/series_columns"].asstr()[:]) == COLUMNS
        for name in COLUMNS:
            assert s[name].shape == (4,) and s[name].dtype == np.float64
            assert s[name].maxshape == (None,)          # extendible
        np.testing.assert_array_equal(s["step"][:].astype(int), [1, 2, 3, 4])
        np.testing.assert_allclose(s["time"][:], [1e-3, 2e-3, 3e-3, 4e-3])
        np.testing.assert_allclose(s["sweeps"][:], [10, 20, 30, 40])


def test_snapshots(sample):
    with h5py.File(sample / "fracas.h5", "r") as f:
        snaps = f["snapshots"]
        assert snaps.attrs["count"] == 2
        assert sorted(snaps) == ["000001", "000002"]
        np.testing.assert_array_equal(f["snapshot_index/step"][:], [2, 4])
        np.testing.assert_allclose(f["snapshot_index/time"][:], [2e-3, 4e-3])
        for name, step in zip(sorted(snaps), (2, 4)):
            g = snaps[name]
            assert g.attrs["step"] == step
            assert g.attrs["time"] == pytest.approx(step * 1e-3)
            assert g["bodies"].attrs["count"] == NB
            assert g["bodies/X"].shape == (NB, 3) and g["bodies/V"].shape == (NB, 3)
            c = g["contacts"]
            assert c.attrs["count"] == NC
            for name_i in ("inter", "cd_body", "an_body", "cd_tactor", "an_tactor", "status", "law"):
                assert c[name_i].shape == (NC,) and c[name_i].dtype == np.int32, name_i
            for name_v in ("normal", "point", "reaction", "velocity"):
                assert c[name_v].shape == (NC, 2) and c[name_v].dtype == np.float64, name_v
            assert c["gap"].shape == (NC,)
            assert c["internals"].shape == (NC, 3)
        c = snaps["000002/contacts"]
        np.testing.assert_array_equal(c["cd_body"][:], [3, 3])
        np.testing.assert_array_equal(c["an_body"][:], [1, 2])
        np.testing.assert_allclose(c["reaction"][:, 1], [12.0, 11.5])      # rn
        np.testing.assert_allclose(c["normal"][0], [-0.5, 0.8660254])
        np.testing.assert_allclose(c["internals"][1], [1.0, 1e-3, 0.25])
        X = snaps["000002/bodies/X"][:]
        np.testing.assert_allclose(X[2], [1.0, 1.69, -0.2])                 # reference + displacement
        np.testing.assert_allclose(snaps["000002/bodies/V"][2], [0.0, -0.5, -2.0])


def test_help_tables(sample):
    with h5py.File(sample / "fracas.h5", "r") as f:
        status = list(f["help/status"].asstr()[:])
        inter = list(f["help/inter"].asstr()[:])
        law = list(f["help/law"].asstr()[:])
        assert status[:3] == ["noctc", "stick", "slifw"]
        assert inter[0] == "DKDKx"
        assert law == ["iqsc0", "IQS_C"]
        st = f["snapshots/000001/contacts/status"][:]
        assert [status[i - 1] for i in st] == ["stick", "slifw"]


def test_existing_file_needs_overwrite(sample, tmp_path):
    out = tmp_path / "again"
    assert run_sample(out).returncode == 0
    proc = run_sample(out)
    assert proc.returncode != 0
    assert "--overwrite" in proc.stderr and str(out / "fracas.h5") in proc.stderr
    assert run_sample(out, "--overwrite").returncode == 0


def test_incomplete_run_is_marked(tmp_path):
    proc = run_sample(tmp_path, "--incomplete")
    assert proc.returncode == 0, proc.stderr
    with h5py.File(tmp_path / "fracas.h5", "r") as f:
        assert f.attrs["complete"] == 0
        assert f["series/time"].shape == (4,)          # flushed data is readable
        assert f["snapshots"].attrs["count"] == 2


# ----------------------------------------------------------------------------- VTK

VTK_DTYPES = {"Float64": "<f8", "Float32": "<f4", "Int32": "<i4", "Int64": "<i8", "UInt8": "u1"}


def read_vtu(path):
    """Parse a .vtu into a dict: inline ascii arrays, or appended raw binary
    (UInt64 byte count + bytes) uncompressed or zlib-compressed in VTK's block
    layout ([nblocks][block size][last block size][compressed sizes] + blocks)."""
    data = Path(path).read_bytes()
    start = data.find(b"<AppendedData")
    xml_part = data if start < 0 else data[:start] + b"</VTKFile>"
    blob = b""
    if start >= 0:
        u = data.index(b"_", data.index(b">", start)) + 1
        blob = data[u:data.rindex(b"</AppendedData>")]
    root = ET.fromstring(xml_part)                     # raises on invalid XML
    assert root.tag == "VTKFile" and root.get("type") == "UnstructuredGrid"
    assert root.get("byte_order") == "LittleEndian"
    assert root.get("header_type") == "UInt64"
    zlib_blocks = root.get("compressor") == "vtkZLibDataCompressor"

    def values(da):
        dtype = np.dtype(VTK_DTYPES[da.get("type")])
        if da.get("format") == "ascii":
            text = (da.text or "").strip()
            return np.array(text.split(), dtype=float).astype(dtype) if text else np.zeros(0, dtype)
        assert da.get("format") == "appended"
        off = int(da.get("offset"))
        if not zlib_blocks:
            nbytes = int(np.frombuffer(blob[off:off + 8], "<u8")[0])
            return np.frombuffer(blob[off + 8:off + 8 + nbytes], dtype)
        nblocks, bsize, last = (int(x) for x in np.frombuffer(blob[off:off + 24], "<u8"))
        sizes = np.frombuffer(blob[off + 24:off + 24 + 8 * nblocks], "<u8")
        pos, raw = off + 24 + 8 * nblocks, b""
        for k, c in enumerate(sizes):
            chunk = zlib.decompress(blob[pos:pos + int(c)])
            assert len(chunk) == (last if (k == nblocks - 1 and last) else bsize)
            raw += chunk
            pos += int(c)
        return np.frombuffer(raw, dtype)

    piece = root.find("UnstructuredGrid/Piece")
    out = {"np": int(piece.get("NumberOfPoints")), "nc": int(piece.get("NumberOfCells")),
           "point": {}, "cell": {}, "field": {}}
    for da in root.findall("UnstructuredGrid/FieldData/DataArray"):
        out["field"][da.get("Name")] = values(da)
    for where, tag in (("point", "PointData"), ("cell", "CellData")):
        for da in piece.findall(f"{tag}/DataArray"):
            ncomp = int(da.get("NumberOfComponents", "1"))
            v = values(da)
            out[where][da.get("Name")] = v.reshape(-1, ncomp) if ncomp > 1 else v
    pts = piece.find("Points/DataArray")
    assert pts.get("NumberOfComponents") == "3"
    out["points"] = values(pts).reshape(-1, 3)
    for da in piece.findall("Cells/DataArray"):
        out[da.get("Name")] = values(da)
    return out


def check_grid(g):
    assert g["points"].shape == (g["np"], 3)
    assert len(g["offsets"]) == len(g["types"]) == g["nc"]
    assert np.all(np.diff(g["offsets"]) >= 0) and g["offsets"][-1] == len(g["connectivity"])
    assert g["connectivity"].min() >= 0 and g["connectivity"].max() < g["np"]
    assert set(g["types"].tolist()) <= {1, 3, 4, 5, 7, 9}
    for name, v in g["point"].items():
        assert len(v) == g["np"], name
    for name, v in g["cell"].items():
        assert len(v) == g["nc"], name


def test_disks_vtu(sample):
    g = read_vtu(sample / "disks_000001.vtu")          # appended, zlib
    check_grid(g)
    assert (g["np"], g["nc"]) == (3, 3)
    assert list(g["types"]) == [1, 1, 1]
    np.testing.assert_allclose(g["point"]["radius"], [1.0, 1.0, 0.9])
    np.testing.assert_allclose(g["points"][2, :2], [1.0, 1.69])
    np.testing.assert_allclose(g["point"]["velocity"][2], [0.0, -0.5, 0.0])
    assert g["point"]["body"].dtype == np.int32 and list(g["point"]["body"]) == [1, 2, 3]
    np.testing.assert_allclose(g["field"]["TimeValue"], [4e-3])


def test_shapes_vtu(sample):
    g = read_vtu(sample / "shapes_000001.vtu")         # appended, raw
    check_grid(g)
    assert (g["np"], g["nc"]) == (3 * 16, 3)
    assert list(g["types"]) == [7, 7, 7]
    assert list(g["offsets"]) == [16, 32, 48]
    assert g["cell"]["velocity"].shape == (3, 3)
    np.testing.assert_allclose(g["cell"]["velocity"][2], [0.0, -0.5, 0.0])
    np.testing.assert_allclose(g["cell"]["spin"], [0.0, 1.0, -2.0])
    assert g["cell"]["body"].dtype == np.int32 and list(g["cell"]["body"]) == [1, 2, 3]
    # outline of disk 3: radius 0.9 about (1, 1.69)
    ring = g["points"][32:48, :2] - [1.0, 1.69]
    np.testing.assert_allclose(np.hypot(ring[:, 0], ring[:, 1]), 0.9, rtol=1e-12)


def test_contacts_vtu(sample):
    g = read_vtu(sample / "contacts_000001.vtu")       # inline ascii
    check_grid(g)
    assert (g["np"], g["nc"]) == (2, 2)
    assert list(g["types"]) == [1, 1]
    c = g["point"]
    np.testing.assert_allclose(c["rn"], [12.0, 11.5])
    np.testing.assert_allclose(c["rt"], [0.1, -0.1])
    n = c["normal"][:, :2]
    t = np.stack([n[:, 1], -n[:, 0]], axis=1)
    np.testing.assert_allclose(c["reaction"][:, :2], c["rt"][:, None] * t + c["rn"][:, None] * n)
    assert list(c["status"]) == [2, 3]
    np.testing.assert_allclose(c["gap"], [-1e-4, 2e-5])


def test_vtk_library_reads_them(sample):
    """VTK's own XML reader (python3-vtk9, what ParaView uses) loads every file."""
    vtk = pytest.importorskip("vtkmodules.vtkIOXML")
    from vtkmodules.util.numpy_support import vtk_to_numpy
    for name, n_points, n_cells, field in (("disks_000001.vtu", 3, 3, "radius"),
                                           ("shapes_000001.vtu", 48, 3, "spin"),
                                           ("contacts_000001.vtu", 2, 2, "rn")):
        r = vtk.vtkXMLUnstructuredGridReader()
        r.SetFileName(str(sample / name))
        r.Update()
        g = r.GetOutput()
        assert (g.GetNumberOfPoints(), g.GetNumberOfCells()) == (n_points, n_cells), name
        arr = g.GetPointData().GetArray(field) or g.GetCellData().GetArray(field)
        assert arr is not None, (name, field)
        np.testing.assert_allclose(vtk_to_numpy(arr), read_vtu(sample / name)["point" if
                                   g.GetPointData().GetArray(field) else "cell"][field])


def test_pvd(sample):
    root = ET.parse(sample / "fracas.pvd").getroot()
    assert root.get("type") == "Collection"
    sets = root.findall("Collection/DataSet")
    assert [d.get("file") for d in sets] == ["disks_000001.vtu", "shapes_000001.vtu", "contacts_000001.vtu"]
    assert [d.get("part") for d in sets] == ["0", "1", "2"]
    assert all(float(d.get("timestep")) == pytest.approx(4e-3) for d in sets)
    assert all((sample / d.get("file")).is_file() for d in sets)
    assert not list(sample.glob("*.part"))
