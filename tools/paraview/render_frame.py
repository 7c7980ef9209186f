"""Render one frame of a Fracas run (DISPLAY/fracas.pvd) to a PNG with ParaView, headless.

    xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" pvpython tools/paraview/render_frame.py RUN/DISPLAY/fracas.pvd frame.png \
        [--frame K | --time T] [--color ARRAY] [--size W H]

The .pvd is opened as ParaView opens it (every piece in one reader, Surface): disks and
polygons filled, meshes in their current configuration. --color colours it by a point or
cell array (e.g. von_mises, body, velocity); pieces without that array keep the solid
colour. The crack paths of the frame (cracks piece) are drawn on top as red lines; the
disks of a run written with `output_vtk_disks points` are drawn as filled circles of their
radius (Point Gaussian). Background white, 2-D camera fitted to the scene.
Debian: apt-get install python3-paraview xvfb (pvpython needs an X server: xvfb-run; without
-noreset pvpython's second connection can meet the server resetting: doc/output_layout.md §2).
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

from paraview import simple as pv


def frames(pvd):
    """[(time, {piece: path})] in time order, from the .pvd."""
    by_time = {}
    base = os.path.dirname(os.path.abspath(pvd))
    for d in ET.parse(pvd).getroot().iter("DataSet"):
        piece = d.get("file").rsplit("_", 1)[0]
        by_time.setdefault(float(d.get("timestep")), {})[piece] = os.path.join(base, d.get("file"))
    return sorted(by_time.items())


def arrays_of(source):
    """{name: association} of the arrays of a source."""
    out = {}
    for assoc, info in (("POINTS", source.PointData), ("CELLS", source.CellData)):
        for name in info.keys():
            out.setdefault(name, assoc)
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("pvd")
    ap.add_argument("png")
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--frame", type=int, default=-1, help="frame index (0 = first, -1 = last; default -1)")
    g.add_argument("--time", type=float, help="the frame nearest this time")
    ap.add_argument("--color", help="point or cell array to colour by (default: solid colour)")
    ap.add_argument("--size", type=int, nargs=2, default=(1200, 900), metavar=("W", "H"))
    a = ap.parse_args(argv)
    if not os.path.isfile(a.pvd):
        sys.exit(f"render_frame: {a.pvd}: no such file (a run's DISPLAY/fracas.pvd)")
    series = frames(a.pvd)
    if not series:
        sys.exit(f"render_frame: {a.pvd} lists no frame")
    if a.time is not None:
        k = min(range(len(series)), key=lambda i: abs(series[i][0] - a.time))
    else:
        k = a.frame if a.frame < 0 else min(a.frame, len(series) - 1)
    time, pieces = series[k]

    view = pv.CreateView("RenderView")
    view.ViewSize = list(a.size)
    view.OrientationAxesVisibility = 0
    view.Background = [1.0, 1.0, 1.0]
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.ViewTime = time

    reader = pv.PVDReader(FileName=os.path.abspath(a.pvd))
    reader.UpdatePipeline(time)
    shown = pv.Show(reader, view)
    shown.Representation = "Surface"
    shown.AmbientColor = shown.DiffuseColor = [0.55, 0.6, 0.7]
    if a.color:
        found = arrays_of(reader)
        if a.color not in found:
            sys.exit(f"render_frame: no array '{a.color}' in {a.pvd} (arrays: {', '.join(sorted(found))})")
        pv.ColorBy(shown, (found[a.color], a.color))
        shown.RescaleTransferFunctionToDataRange(True, False)
        lut = pv.GetColorTransferFunction(a.color)
        lut.ApplyPreset("Viridis (matplotlib)", True)

    if "disks" in pieces:       # output_vtk_disks points: filled circles of their radius
        disks = pv.XMLUnstructuredGridReader(FileName=[pieces["disks"]])
        d = pv.Show(disks, view)
        d.SetRepresentationType("Point Gaussian")
        d.ShaderPreset = "Plain circle"
        d.ScaleByArray = 1
        d.SetScaleArray = ["POINTS", "radius"]
        d.UseScaleFunction = 0
        d.GaussianRadius = 1.0
        d.AmbientColor = d.DiffuseColor = [0.55, 0.6, 0.7]
    if "cracks" in pieces:
        cracks = pv.XMLUnstructuredGridReader(FileName=[pieces["cracks"]])
        c = pv.Show(cracks, view)
        c.ColorArrayName = ["POINTS", ""]
        c.AmbientColor = c.DiffuseColor = [0.9, 0.0, 0.0]
        c.LineWidth = 4.0
        c.Position = [0.0, 0.0, 1e-6]      # above the mesh faces

    view.InteractionMode = "2D"
    view.CameraPosition = [0, 0, 1]
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 1, 0]
    view.ResetCamera(False)
    pv.Render(view)
    pv.SaveScreenshot(a.png, view, ImageResolution=list(a.size),
                      OverrideColorPalette="WhiteBackground")
    print(f"render_frame: frame {k % len(series)} (t={time:.6g}) of {a.pvd} -> {a.png}")


if __name__ == "__main__":
    main()
