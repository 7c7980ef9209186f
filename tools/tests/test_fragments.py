"""Fragments as results (issue 22): a 3 x 0.5 m plate cut across at x = 1 and x = 2 by
uncohesive cracks (the other edges glued by MP3_CZM) falls under gravity for 10 steps:
three fragments, each 1 x 0.5 m. References: mass rho x area (lumped masses sum to the
element masses: exact), centres (0.5, 0.25), (1.5, 0.25), (2.5, 0.25) shifted by the fall
-g t^2/2 (the theta = 0.5 scheme is exact for constant acceleration), velocity (0, -g t),
kinetic energy M (g t)^2 / 2; second moments of the rectangle M a^2/12, M b^2/12, 0 up to
the lumping error O(h^2) (6 % at h = 0.1; the lumped values themselves to round-off),
major axis along x. In fracas.h5 (snapshot group
cracks/fragments and series/fragments), as the VTK cell field `fragment` and in the
tools (fracas_tools.fracture.MeshRun.fragments, plot_fragment_sizes)."""
import sys

import numpy as np
import pytest

from fracas_run import ROOT, run


pytest.importorskip("gmsh")
vtkio = pytest.importorskip("vtkmodules.vtkIOXML")
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

RHO, G, DT, STEPS = 2000.0, 9.81, 1e-3, 10
GEO = """
lc = 0.1;
Point(1) = {0, 0, 0, lc}; Point(2) = {1, 0, 0, lc}; Point(3) = {2, 0, 0, lc}; Point(4) = {3, 0, 0, lc};
Point(5) = {3, 0.5, 0, lc}; Point(6) = {2, 0.5, 0, lc}; Point(7) = {1, 0.5, 0, lc}; Point(8) = {0, 0.5, 0, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6};
Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 1}; Line(9) = {2, 7}; Line(10) = {3, 6};
Curve Loop(1) = {1, 9, 7, 8}; Plane Surface(1) = {1};
Curve Loop(2) = {2, 10, 6, -9}; Plane Surface(2) = {2};
Curve Loop(3) = {3, 4, 5, -10}; Plane Surface(3) = {3};
Physical Surface("solid") = {1, 2, 3};
Physical Curve("cut") = {9, 10};
"""


@pytest.fixture(scope="module")
def case(tmp_path_factory):
    from fracas_tools import Case
    from fracas_tools.mesh import mesh_geo
    d = tmp_path_factory.mktemp("fragments")
    (d / "plate.geo").write_text(GEO)
    mesh = mesh_geo(d / "plate.geo")
    c = Case(gravity=(0.0, -G))
    c.add_material("SOLID", RHO, "ELAS", young=1e9, poisson=0.25)
    parts = c.add_exploded_mesh(mesh, "SOLID", cracks=["cut"])
    c.add_law("czmgl", "MP3_CZM", dyfr=0.0, stfr=0.0, cn=1e12, ct=1e12, smax=1e7, w=100.0)
    parts.add_see(c, "czmgl", alert=1e-3)
    c.run.set(time_step=DT, number_of_steps=STEPS, plane="strain", output_hdf5_every=5, output_vtk_every=5)
    c.write(d / "deck")
    p = run("-q", d / "deck")
    assert p.returncode == 0, p.stderr
    return d / "deck"


def test_three_fragments_as_bodies(case):
    from fracas_tools.fracture import MeshRun
    with MeshRun(case) as mr:
        assert list(mr.series["fragments"]) == [3] * STEPS
        fr = mr.fragments(-1)
        t = mr.times[-1]
    assert t == pytest.approx(STEPS * DT)
    order = np.argsort(fr["centre"][:, 0])
    m = RHO * 1.0 * 0.5
    np.testing.assert_allclose(fr["mass"][order], [m, m, m], rtol=1e-12)
    fall = -0.5 * G * t * t
    np.testing.assert_allclose(fr["centre"][order], [[0.5, 0.25 + fall], [1.5, 0.25 + fall], [2.5, 0.25 + fall]],
                               atol=1e-12)
    np.testing.assert_allclose(fr["velocity"], [[0.0, -G * t]] * 3, atol=1e-12)
    np.testing.assert_allclose(fr["kinetic_energy"], 0.5 * m * (G * t) ** 2, rtol=1e-10)
    # Second moments: the lumped masses (rho A_e / 3 at each corner) summed here from the
    # mesh (round-off), and within the lumping error O(h^2) (6 % at h = 0.1) of the
    # rectangle's M a^2 / 12.
    with MeshRun(case) as mr:
        x = mr.ref + mr.state(-1).X
        ref = np.zeros((3, 3))
        for nodes in mr.elements:
            p = x[nodes[:3]]
            area = 0.5 * abs(np.cross(p[1] - p[0], p[2] - p[0]))
            k = int(p[:, 0].mean())                       # fragment 0, 1, 2 by x
            d = p - fr["centre"][order[k]]
            ref[k] += RHO * area / 3 * np.array([np.sum(d[:, 0] ** 2), np.sum(d[:, 1] ** 2), np.sum(d[:, 0] * d[:, 1])])
    np.testing.assert_allclose(fr["second_moments"][order], ref, rtol=1e-10, atol=1e-10 * m)
    jxx, jyy, jxy = fr["second_moments"].T
    np.testing.assert_allclose(jxx, m * 1.0 / 12, rtol=0.08)
    np.testing.assert_allclose(jyy, m * 0.25 / 12, rtol=0.08)
    assert np.all(np.abs(jxy) < 0.03 * m / 12)
    np.testing.assert_allclose(fr["polar_moment"], jxx + jyy, rtol=1e-12)
    np.testing.assert_allclose(fr["principal_moments"][:, 0], jxx, rtol=0.01)
    assert np.all(np.abs(np.sin(fr["principal_angle"])) < 0.1)          # major axis along x
    assert fr["elements"].sum() == fr["bodies"].sum() == len(mr.elements)


def test_fragment_cell_field_and_plot(case, tmp_path):
    import xml.etree.ElementTree as ET
    sets = list(ET.parse(case / "DISPLAY/fracas.pvd").getroot().iter("DataSet"))
    last = [d.get("file") for d in sets if d.get("file").startswith("meshes_")][-1]
    r = vtkio.vtkXMLUnstructuredGridReader()
    r.SetFileName(str(case / "DISPLAY" / last))
    r.Update()
    g = r.GetOutput()
    frag = vtk_to_numpy(g.GetCellData().GetArray("fragment"))
    assert sorted(set(frag.tolist())) == [1, 2, 3]
    centres = vtk_to_numpy(g.GetPoints().GetData())[:, 0]
    # every element of fragment k lies on one side of the cuts
    for k in (1, 2, 3):
        xs = [centres[[g.GetCell(e).GetPointId(j) for j in range(3)]].mean() for e in np.nonzero(frag == k)[0]]
        assert max(xs) - min(xs) < 1.0
    from fracas_tools.fracture import MeshRun, plot_fragment_sizes
    with MeshRun(case) as mr:
        out = plot_fragment_sizes(mr, tmp_path / "sizes.png")
    assert out.stat().st_size > 5000
