"""What ParaView shows (issue 9, item 6): the DISPLAY files of real runs read by VTK's
own XML reader (python3-vtk9, the reader ParaView uses), checked against fracas.h5
and the deck: cell counts and types, fields and their components, positions,
radii, polygon areas; the description of the run in fracas.h5 (/contactors against
BODIES.DAT, /run)."""

import h5py
import numpy as np
import pytest

from fracas_run import ROOT, lmgc90_decks, run

vtkio = pytest.importorskip("vtkmodules.vtkIOXML")
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

VTK_POLYGON, VTK_POLY_LINE, VTK_VERTEX = 7, 4, 1
DISK, XKSID, JONC, POLYG = 1, 2, 3, 4


def read(path):
    r = vtkio.vtkXMLUnstructuredGridReader()
    r.SetFileName(str(path))
    r.Update()
    return r.GetOutput()


def arrays(data):
    return {data.GetArrayName(i): vtk_to_numpy(data.GetArray(i)) for i in range(data.GetNumberOfArrays())}


def cells(g):
    out = []
    for k in range(g.GetNumberOfCells()):
        c = g.GetCell(k)
        ids = [c.GetPointId(j) for j in range(c.GetNumberOfPoints())]
        out.append((g.GetCellType(k), vtk_to_numpy(g.GetPoints().GetData())[ids, :2]))
    return out


def shoelace(p):
    x, y = p[:, 0], p[:, 1]
    return 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)


def frames(out):
    """{time: {piece: path}} from DISPLAY/fracas.pvd."""
    import xml.etree.ElementTree as ET
    res = {}
    for d in ET.parse(out / "DISPLAY" / "fracas.pvd").getroot().iter("DataSet"):
        piece = d.get("file").rsplit("_", 1)[0]
        res.setdefault(float(d.get("timestep")), {})[piece] = out / "DISPLAY" / d.get("file")
    return res


@pytest.fixture(scope="module")
def mixed(tmp_path_factory):
    """mixed_disk_polygon (7 disks, 6 polygons, walls): 20 steps, VTK and snapshots every 5,
    disks as points with their radius (output_vtk_disks points; the default, polygons, below)."""
    out = tmp_path_factory.mktemp("mixed")
    p = run("-q", "--output", out, "--set", "time_step=1e-3", "--set", "number_of_steps=20",
            "--set", "output_vtk_every=5", "--set", "output_vtk_disks=points", "--set", "output_hdf5_every=5", lmgc90_decks() / "mixed_disk_polygon")
    assert p.returncode == 0, p.stderr
    return out


def test_frames_and_pieces(mixed):
    fr = frames(mixed)
    assert len(fr) == 5                                          # the initial state + 4
    assert all(set(v) == {"disks", "shapes", "contacts"} for v in fr.values())


def test_pieces_against_fracas_h5(mixed):
    fr = frames(mixed)
    with h5py.File(mixed / "OUTBOX" / "fracas.h5") as f:
        kind = f["contactors/kind"][:]
        body = f["contactors/body"][:]
        radius = f["contactors/radius"][:]
        first, count = f["contactors/vertex_first"][:], f["contactors/vertex_count"][:]
        vert = f["contactors/vertices"][:]
        ref = f["bodies/reference"][:]
        snaps = {round(f["snapshots"][k].attrs["time"], 12): f["snapshots"][k] for k in f["snapshots"]}
        matched = 0
        for t, pieces in fr.items():
            disks, shapes, contacts = (read(pieces[k]) for k in ("disks", "shapes", "contacts"))
            # disks: one vertex per DISKx, its radius, body state as point data
            nd = int(np.sum(kind == DISK))
            assert disks.GetNumberOfPoints() == disks.GetNumberOfCells() == nd
            assert {disks.GetCellType(k) for k in range(nd)} == {VTK_VERTEX}
            pd = arrays(disks.GetPointData())
            assert {n: (v.shape[1] if v.ndim > 1 else 1) for n, v in pd.items()} == \
                {"radius": 1, "body": 1, "velocity": 3, "rotation": 1, "spin": 1, "orientation": 3}
            np.testing.assert_allclose(pd["radius"], radius[kind == DISK], rtol=1e-6)
            np.testing.assert_array_equal(pd["body"], body[kind == DISK])
            # shapes: every other contactor, polygons and walls filled
            others = np.nonzero(kind != DISK)[0]
            sc = cells(shapes)
            assert len(sc) == len(others)
            cd = arrays(shapes.GetCellData())
            assert set(cd) == {"body", "contactor_kind", "velocity", "rotation", "spin"}
            np.testing.assert_array_equal(cd["contactor_kind"], kind[others])
            for (ctype, pts), k in zip(sc, others):
                assert ctype == (VTK_POLY_LINE if kind[k] == XKSID else VTK_POLYGON)
                if kind[k] == POLYG:      # the polygon, counter-clockwise, of its area
                    assert len(pts) == count[k]
                    v = vert[first[k]:first[k] + count[k]]
                    assert shoelace(pts) == pytest.approx(shoelace(v), rel=1e-5)
                    assert shoelace(pts) > 0
            # contacts: one vertex each, the snapshot's contacts
            cp = arrays(contacts.GetPointData())
            assert set(cp) >= {"normal", "reaction", "rn", "rt", "gap", "status", "inter", "law", "cd_body",
                               "an_body"}
            key = round(t, 12)
            if key in snaps:
                matched += 1
                s = snaps[key]
                assert contacts.GetNumberOfPoints() == s["contacts"].attrs["count"]
                rn = s["contacts/reaction"][:, 1]
                np.testing.assert_allclose(cp["rn"], rn, rtol=1e-6, atol=1e-6 * max(1.0, np.abs(rn).max()))
                np.testing.assert_array_equal(cp["status"], s["contacts/status"][:])
                x = ref + s["bodies/X"][:]
                centre = vtk_to_numpy(disks.GetPoints().GetData())[:, :2]
                np.testing.assert_allclose(centre, x[body[kind == DISK] - 1, :2], rtol=1e-6, atol=1e-7)
        assert matched == 4                                     # every frame but the initial one


def test_disks_as_polygons_in_double_precision(tmp_path):
    out = tmp_path / "poly"
    p = run("-q", "--output", out, "--set", "time_step=1e-3", "--set", "number_of_steps=4",
            "--set", "output_vtk_every=4", "--set", "output_hdf5_every=4", "--set", "output_vtk_disks=polygons",
            "--set", "output_vtk_precision=double", lmgc90_decks() / "mixed_disk_polygon")
    assert p.returncode == 0, p.stderr
    fr = frames(out)
    last = fr[max(fr)]
    assert set(last) == {"shapes", "contacts"}
    g = read(last["shapes"])
    with h5py.File(out / "OUTBOX" / "fracas.h5") as f:
        kind = f["contactors/kind"][:]
        radius = f["contactors/radius"][:]
        s = f["snapshots"][sorted(f["snapshots"])[-1]]
        c = read(last["contacts"])
        np.testing.assert_array_equal(arrays(c.GetPointData())["rn"], s["contacts/reaction"][:, 1])  # Float64: exact
    sc = cells(g)
    assert len(sc) == len(kind)
    for (ctype, pts), k, r in zip(sc, kind, radius):
        if k == DISK:     # a filled 24-gon inscribed in the disk
            assert ctype == VTK_POLYGON and len(pts) == 24
            assert shoelace(pts) == pytest.approx(0.5 * 24 * r * r * np.sin(2 * np.pi / 24), rel=1e-12)


def test_drum_is_an_open_circle(tmp_path):
    out = tmp_path / "drum"
    p = run("-q", "--output", out, "--set", "time_step=1e-3", "--set", "number_of_steps=2",
            "--set", "output_vtk_every=1", "--set", "output_vtk_disks=points", lmgc90_decks() / "drum")
    assert p.returncode == 0, p.stderr
    g = read(frames(out)[max(frames(out))]["shapes"])
    (ctype, pts), = cells(g)
    assert ctype == VTK_POLY_LINE and len(pts) == 25
    np.testing.assert_allclose(pts[0], pts[-1], atol=1e-12)                 # closed


def test_contactors_in_fracas_h5_match_bodies_dat(mixed):
    """/contactors against BODIES.DAT read by fracas_tools.datbox (not the solver's reader)."""
    from fracas_tools.datbox import read_bodies
    tactors = [c for b in read_bodies(lmgc90_decks() / "mixed_disk_polygon" / "DATBOX" / "BODIES.DAT")
               for c in b.contactors]
    byrd = [c.radius for c in tactors if c.kind == "DISKx"]
    nvert = [len(c.vertices) for c in tactors if c.kind == "POLYG"]
    with h5py.File(mixed / "OUTBOX" / "fracas.h5") as f:
        kind = f["contactors/kind"][:]
        names = list(f["contactors/kind_names"].asstr()[:])
        assert names[:4] == ["DISKx", "xKSID", "JONCx", "POLYG"]
        np.testing.assert_allclose(f["contactors/radius"][:][kind == DISK], byrd)
        np.testing.assert_array_equal(f["contactors/vertex_count"][:][kind == POLYG], nvert)
        assert f["contactors/vertices"].shape == (sum(nvert), 2)
        assert f["run"].attrs["output_vtk_every"] == 5


def test_meshed_deck_pieces_and_contactors(tmp_path):
    """A meshed block dropped on a rigid ground (mesh_block_drop): the shapes piece
    holds the rigid ground only (the CLxxx points of the mesh are drawn with the
    mesh), the meshes piece the 32 Q4 elements; /contactors gives every contactor's
    model, its body, and for the mesh ones their nodes."""
    out = tmp_path / "mesh"
    p = run("-q", "--output", out, "--command", ROOT / "test_cases" / "compat" / "mesh_block_drop" / "run.dat",
            "--set", "number_of_steps=4", "--set", "output_vtk_every=4", "--set", "output_hdf5_every=4",
            lmgc90_decks() / "mesh_block_drop")
    assert p.returncode == 0, p.stderr
    last = frames(out)[max(frames(out))]
    shapes = read(last["shapes"])
    assert shapes.GetNumberOfCells() == 1 and shapes.GetCellType(0) == VTK_POLYGON
    assert read(last["meshes"]).GetNumberOfCells() == 32
    with h5py.File(out / "OUTBOX" / "fracas.h5") as f:
        g = f["contactors"]
        model, kind = g["model"][:], g["kind"][:]
        assert list(g["kind_names"].asstr()[:]) == ["DISKx", "xKSID", "JONCx", "POLYG", "CLxxx", "ALpxx"]
        assert np.all(model[kind == JONC] == 1) and np.all(model[kind == 5] == 2)
        cl = np.nonzero(kind == 5)[0]
        assert np.all(g["node_count"][:][cl] == 2)          # a CLxxx point on an edge (noda, nodb)
        assert g["nodes"].shape == (int(g["node_count"][:].sum()),)
