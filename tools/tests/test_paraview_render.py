"""ParaView shows what a run wrote (issue 22): one frame of the demo deck and one of a
cracked notched plate rendered headless by tools/paraview/render_frame.py (pvpython on a
virtual X server, as doc/output_layout.md says), then the PNG checked against the geometry of the
frame's .vtu files: the area ParaView filled equals the area of the disks, walls and mesh
cells (disks drawn as 1-pixel dots would fill ~1 % of it), the cracks are drawn in red
over the length fracas.h5 gives, and the mesh is coloured by von_mises.
Skipped (with the reason) where pvpython or Xvfb is not installed
(Debian: apt-get install python3-paraview xvfb)."""
import os
import shutil
import subprocess
import xml.etree.ElementTree as ET

import h5py
import numpy as np
import pytest

from fracas_run import ROOT, run_example

PVPYTHON = shutil.which("pvpython")
if not PVPYTHON:
    pytest.skip("ParaView rendering: pvpython not installed "
                "(Debian: apt-get install python3-paraview xvfb)", allow_module_level=True)
vtkio = pytest.importorskip("vtkmodules.vtkIOXML")
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
plt = pytest.importorskip("matplotlib.pyplot")

SIZE = (1000, 800)


@pytest.fixture(scope="module")
def display():
    """A virtual X server of our own for the renders. Xvfb chooses a free display number
    itself and tells it through -displayfd (`xvfb-run -a` guesses one from the lock files
    in /tmp: two started at the same moment can take the same). -noreset: by default the
    server resets when its last client disconnects, and pvpython connects twice: its second
    connection, made during the reset, failed with 'bad X server connection' (measured:
    every time without -noreset on a bare Xvfb; the intermittent failure of this test
    under xvfb-run)."""
    xvfb = shutil.which("Xvfb")
    if xvfb is None:
        pytest.skip("ParaView rendering: Xvfb not installed (Debian: apt-get install xvfb)")
    rfd, wfd = os.pipe()
    server = subprocess.Popen([xvfb, "-displayfd", str(wfd), "-screen", "0", "1280x1024x24", "-nolisten", "tcp",
                               "-noreset"],
                              pass_fds=(wfd,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.close(wfd)
    with os.fdopen(rfd) as f:
        number = f.readline().strip()       # written once the server accepts connections
    assert number.isdigit(), f"Xvfb gave no display number (exit status {server.poll()})"
    yield ":" + number
    server.terminate()
    server.wait(timeout=30)


def render(display, pvd, png, *extra):
    p = subprocess.run([PVPYTHON, str(ROOT / "tools/paraview/render_frame.py"), str(pvd), str(png),
                        "--size", *map(str, SIZE), *extra], capture_output=True, text=True, timeout=300,
                       env={**os.environ, "DISPLAY": display})
    assert p.returncode == 0, p.stdout + p.stderr
    img = plt.imread(png)[:, :, :3]
    assert img.shape[:2] == (SIZE[1], SIZE[0])
    return img


def last_frame(out):
    """{piece: path} of the last frame of DISPLAY/fracas.pvd."""
    sets = list(ET.parse(out / "DISPLAY" / "fracas.pvd").getroot().iter("DataSet"))
    t = max(float(d.get("timestep")) for d in sets)
    return {d.get("file").rsplit("_", 1)[0]: out / "DISPLAY" / d.get("file")
            for d in sets if float(d.get("timestep")) == t}


def polygons(path):
    """Areas (shoelace) of the 2-D cells of a .vtu and its x, y bounds."""
    r = vtkio.vtkXMLUnstructuredGridReader()
    r.SetFileName(str(path))
    r.Update()
    g = r.GetOutput()
    xy = vtk_to_numpy(g.GetPoints().GetData())[:, :2].astype(float)
    areas = []
    for k in range(g.GetNumberOfCells()):
        c = g.GetCell(k)
        if c.GetCellDimension() != 2:
            continue
        p = xy[[c.GetPointId(j) for j in range(c.GetNumberOfPoints())]]
        x, y = p[:, 0], p[:, 1]
        areas.append(abs(0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)))
    return np.array(areas), xy.min(axis=0), xy.max(axis=0)


def filled_check(img, pieces):
    """Filled pixels against the cells' area, at the scale given by the content's extent.
    Returns (filled pixels, expected pixels, metres per pixel)."""
    area, lo, hi = 0.0, np.full(2, np.inf), np.full(2, -np.inf)
    for name in ("shapes", "meshes"):
        if name in pieces:
            a, l, h = polygons(pieces[name])
            area += a.sum()
            lo, hi = np.minimum(lo, l), np.maximum(hi, h)
    if "disks" in pieces:            # output_vtk_disks points: circles of their radius
        r = vtkio.vtkXMLUnstructuredGridReader()
        r.SetFileName(str(pieces["disks"]))
        r.Update()
        area += np.pi * np.sum(vtk_to_numpy(r.GetOutput().GetPointData().GetArray("radius")).astype(float) ** 2)
    ink = img.mean(axis=2) < 0.8      # more than half-way from the white background to the fill
    rows, cols = np.nonzero(ink)
    m_per_px = max((hi[0] - lo[0]) / (cols.max() - cols.min() + 1), (hi[1] - lo[1]) / (rows.max() - rows.min() + 1))
    return ink.sum(), area / m_per_px**2, m_per_px


@pytest.fixture(scope="module")
def demo(tmp_path_factory):
    """The demo deck (400 disks falling into a box), 200 steps, VTK every 150: the last
    frame (step 200) is written although 200 is not a multiple of 150."""
    return run_example(tmp_path_factory, "demo_deposit", "number_of_steps=200", "output_vtk_every=150")


def test_demo_frame_disks_filled(demo, display, tmp_path):
    times = [float(d.get("timestep")) for d in ET.parse(demo / "DISPLAY/fracas.pvd").getroot().iter("DataSet")]
    assert sorted(set(times)) == pytest.approx([0.0, 0.15, 0.2])     # 0, step 150, the last step 200
    img = render(display, demo / "DISPLAY/fracas.pvd", tmp_path / "demo.png")
    filled, expected, _ = filled_check(img, last_frame(demo))
    # Disks as 24-gons and the walls: ParaView fills what the cells cover (3 %: pixels
    # along the edges; measured 1.0 %; disks drawn as points would fill about 1 % of it).
    print(f"demo: {filled} pixels filled, {expected:.0f} expected")
    assert filled == pytest.approx(expected, rel=0.03)


@pytest.fixture(scope="module")
def plate(tmp_path_factory):
    """The fracture demo (notched plate struck at its top), 250 steps (62.5 µs): cracks."""
    return run_example(tmp_path_factory, "notched_plate_impact", "number_of_steps=250", "output_vtk_every=100")


def test_crack_frame(plate, display, tmp_path):
    img = render(display, plate / "DISPLAY/fracas.pvd", tmp_path / "plate.png", "--color", "von_mises")
    pieces = last_frame(plate)
    filled, expected, m_per_px = filled_check(img, pieces)
    print(f"plate: {filled} pixels filled, {expected:.0f} expected")
    assert filled == pytest.approx(expected, rel=0.03)
    # The cracks in red (lines 4 px wide) over the crack length fracas.h5 gives.
    with h5py.File(plate / "OUTBOX/fracas.h5") as f:
        length = f["series/crack_length"][-1]
    assert length > 5e-3
    red = (img[:, :, 0] > 0.8) & (img[:, :, 1] < 0.2) & (img[:, :, 2] < 0.2)
    print(f"plate: {red.sum()} red pixels, {4 * length / m_per_px:.0f} for {length * 1e3:.1f} mm of crack")
    assert red.sum() == pytest.approx(4 * length / m_per_px, rel=0.35)
    # The mesh coloured by von_mises (viridis): many colours, blue-green ones among them.
    mesh = (img.min(axis=2) < 0.95) & ~red
    colours = np.unique((img[mesh] * 32).astype(int), axis=0)
    assert len(colours) > 50
    assert np.any((img[:, :, 1] > 0.5) & (img[:, :, 0] < 0.3))     # viridis green
