"""Read the VTK files fracas writes (DISPLAY/*.vtu, DISPLAY/fracas.pvd) and draw
them with matplotlib: a picture of what ParaView shows, made without ParaView.

Only the subset fracas writes is read: UnstructuredGrid, inline DataArrays in
"ascii" or "binary" (base64 of a UInt64 byte count followed by the data).
"""
import base64
import struct
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

_DTYPES = {"Float64": "<f8", "Float32": "<f4", "Int32": "<i4", "Int64": "<i8", "UInt8": "u1",
           "UInt64": "<u8"}


def _array(el):
    """One DataArray element -> numpy array (n, ncomp) or (n,)."""
    dtype = np.dtype(_DTYPES[el.get("type")])
    ncomp = int(el.get("NumberOfComponents", "1"))
    text = (el.text or "").strip()
    if el.get("format", "ascii") == "binary":
        raw = base64.b64decode("".join(text.split()))
        nbytes = struct.unpack("<Q", raw[:8])[0]
        data = np.frombuffer(raw[8:8 + nbytes], dtype=dtype)
    else:
        data = np.array(text.split(), dtype=dtype)
    return data.reshape(-1, ncomp) if ncomp > 1 else data


def read_vtu(path):
    """path -> dict(points (np,3), connectivity, offsets, types, cell_data {name: array},
    point_data {name: array}, time)."""
    root = ET.parse(path).getroot()
    grid = root.find("UnstructuredGrid")
    piece = grid.find("Piece")
    out = {"time": None, "cell_data": {}, "point_data": {}}
    fd = grid.find("FieldData")
    if fd is not None:
        for el in fd.findall("DataArray"):
            if el.get("Name") == "TimeValue":
                out["time"] = float(_array(el).ravel()[0])
    out["points"] = _array(piece.find("Points").find("DataArray")).reshape(-1, 3)
    cells = {el.get("Name"): _array(el) for el in piece.find("Cells").findall("DataArray")}
    out["connectivity"] = cells["connectivity"]
    out["offsets"] = cells["offsets"]
    out["types"] = cells["types"]
    for tag, key in (("CellData", "cell_data"), ("PointData", "point_data")):
        sec = piece.find(tag)
        if sec is not None:
            for el in sec.findall("DataArray"):
                out[key][el.get("Name")] = _array(el)
    return out


def read_pvd(path):
    """DISPLAY/fracas.pvd -> list of (time, part, file path), in file order."""
    root = ET.parse(path).getroot()
    base = Path(path).parent
    return [(float(d.get("timestep")), int(d.get("part", "0")), base / d.get("file"))
            for d in root.find("Collection").findall("DataSet")]


def cells(vtu):
    """Point index lists of each cell."""
    off = np.r_[0, vtu["offsets"]]
    return [vtu["connectivity"][off[k]:off[k + 1]] for k in range(len(vtu["offsets"]))]


def render(display_dir, frame=-1, out=None, ax=None, force_scale=None, title=None):
    """Draw frame `frame` (index into the listed times; -1: last) of a DISPLAY folder:
    the contactor outlines (bodies_*.vtu) and, at each contact point, a segment along
    the normal with a width proportional to the normal force (contacts_*.vtu)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    entries = read_pvd(Path(display_dir) / "fracas.pvd")
    times = sorted({t for t, _, _ in entries})
    t = times[frame]
    parts = {p: f for tt, p, f in entries if tt == t}
    own = ax is None
    if own:
        fig, ax = plt.subplots(figsize=(8, 6))
    bodies = read_vtu(parts[0])
    for idx in cells(bodies):
        xy = bodies["points"][idx, :2]
        ax.plot(xy[1:, 0], xy[1:, 1], color="0.25", lw=0.6)      # outline (first point: centre)
        ax.plot(xy[:2, 0], xy[:2, 1], color="0.6", lw=0.4)       # spoke: rotation
    if 1 in parts:
        con = read_vtu(parts[1])
        rn = con["cell_data"].get("rn", np.zeros(0))
        if len(rn) and np.abs(rn).max() > 0:
            p = con["points"][:, :2]
            n = con["cell_data"]["normal"][:, :2]
            size = np.ptp(bodies["points"][:, :2], axis=0).max()
            scale = force_scale or np.abs(rn).max()
            for k in np.nonzero(rn > 0)[0]:
                seg = np.array([p[k] - 0.01 * size * n[k], p[k] + 0.01 * size * n[k]])
                ax.plot(seg[:, 0], seg[:, 1], color="firebrick", lw=0.5 + 3.0 * rn[k] / scale)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(title or f"{Path(display_dir).parent.name}: t = {t:.3g} s (from DISPLAY/*.vtu)")
    if own:
        fig.tight_layout()
        if out:
            fig.savefig(out, dpi=130)
        plt.close(fig)
    return t
