"""Read the VTK files fracas writes (DISPLAY/*.vtu, DISPLAY/fracas.pvd) and draw
them with matplotlib: a picture of what ParaView shows, made without ParaView.

Only the subset fracas writes is read: UnstructuredGrid with DataArrays inline
("ascii" text, or "binary": base64 of a UInt64 byte count and the data) or
"appended" raw binary, uncompressed or zlib-compressed (VTK's block layout).
"""
import base64
import struct
import xml.etree.ElementTree as ET
import zlib
from pathlib import Path

import numpy as np

from .mailx import VTK_CORNERS

_DTYPES = {"Float64": "<f8", "Float32": "<f4", "Int32": "<i4", "Int64": "<i8", "UInt8": "u1",
           "UInt64": "<u8"}


def _appended_bytes(blob, offset, compressed):
    """The bytes of one appended array at offset in the appended data."""
    if not compressed:
        nbytes = struct.unpack("<Q", blob[offset:offset + 8])[0]
        return blob[offset + 8:offset + 8 + nbytes]
    nblocks = struct.unpack("<Q", blob[offset:offset + 8])[0]
    sizes = struct.unpack(f"<{nblocks}Q", blob[offset + 24:offset + 24 + 8 * nblocks])
    pos, parts = offset + 24 + 8 * nblocks, []
    for c in sizes:
        parts.append(zlib.decompress(blob[pos:pos + c]))
        pos += c
    return b"".join(parts)


def _array(el, blob=b"", compressed=False):
    """One DataArray element -> numpy array (n, ncomp) or (n,)."""
    dtype = np.dtype(_DTYPES[el.get("type")])
    ncomp = int(el.get("NumberOfComponents", "1"))
    fmt = el.get("format", "ascii")
    if fmt == "appended":
        data = np.frombuffer(_appended_bytes(blob, int(el.get("offset")), compressed), dtype=dtype)
    elif fmt == "binary":
        raw = base64.b64decode("".join((el.text or "").split()))
        nbytes = struct.unpack("<Q", raw[:8])[0]
        data = np.frombuffer(raw[8:8 + nbytes], dtype=dtype)
    else:
        data = np.array((el.text or "").split(), dtype=dtype)
    return data.reshape(-1, ncomp) if ncomp > 1 else data


def read_vtu(path):
    """path -> dict(points (np,3), connectivity, offsets, types, cell_data {name: array},
    point_data {name: array}, time)."""
    raw = Path(path).read_bytes()
    start = raw.find(b"<AppendedData")
    blob = b""
    if start >= 0:
        u = raw.index(b"_", raw.index(b">", start)) + 1
        blob = raw[u:raw.rindex(b"</AppendedData>")]
        raw = raw[:start] + b"</VTKFile>"
    root = ET.fromstring(raw)
    compressed = root.get("compressor") == "vtkZLibDataCompressor"
    grid = root.find("UnstructuredGrid")
    piece = grid.find("Piece")
    out = {"time": None, "cell_data": {}, "point_data": {}}

    def arr(el):
        return _array(el, blob, compressed)

    fd = grid.find("FieldData")
    if fd is not None:
        for el in fd.findall("DataArray"):
            if el.get("Name") == "TimeValue":
                out["time"] = float(arr(el).ravel()[0])
    out["points"] = arr(piece.find("Points").find("DataArray")).reshape(-1, 3)
    cells = {el.get("Name"): arr(el) for el in piece.find("Cells").findall("DataArray")}
    out["connectivity"] = cells["connectivity"]
    out["offsets"] = cells["offsets"]
    out["types"] = cells["types"]
    for tag, key in (("CellData", "cell_data"), ("PointData", "point_data")):
        sec = piece.find(tag)
        if sec is not None:
            for el in sec.findall("DataArray"):
                out[key][el.get("Name")] = arr(el)
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


def piece_of(path):
    """The piece a DISPLAY file holds, from its name: 'disks', 'shapes', 'contacts'
    (or 'bodies' in the outline files of older versions)."""
    return Path(path).name.rsplit("_", 1)[0]


def render(display_dir, frame=-1, out=None, ax=None, force_scale=None, title=None):
    """Draw frame `frame` (index into the listed times; -1: last) of a DISPLAY folder:
    the disks (disks_*.vtu: filled circles of their radius), the other contactors
    (shapes_*.vtu: filled polygons, drum circles), the elements of meshed bodies
    (meshes_*.vtu) and, at each contact point, a
    segment along the normal with a width proportional to the normal force
    (contacts_*.vtu)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import EllipseCollection, PolyCollection
    entries = read_pvd(Path(display_dir) / "fracas.pvd")
    times = sorted({t for t, _, _ in entries})
    t = times[frame]
    files = {piece_of(f): f for tt, _, f in entries if tt == t}
    own = ax is None
    if own:
        fig, ax = plt.subplots(figsize=(8, 6))
    extent = []
    if "disks" in files:
        d = read_vtu(files["disks"])
        xy, r = d["points"][:, :2], d["point_data"]["radius"]
        ax.add_collection(EllipseCollection(2 * r, 2 * r, 0.0, units="xy", offsets=xy,
                                            transOffset=ax.transData, facecolor="0.8", edgecolor="0.25",
                                            linewidth=0.4))
        extent += [xy - r[:, None], xy + r[:, None]]
    for key in ("shapes", "bodies"):
        if key in files:
            g = read_vtu(files[key])
            polys = [g["points"][idx, :2] for idx in cells(g)]
            filled = [p for p, ty in zip(polys, g["types"]) if ty == 7 and key == "shapes"]
            lines = [p for p, ty in zip(polys, g["types"]) if not (ty == 7 and key == "shapes")]
            ax.add_collection(PolyCollection(filled, facecolor="0.7", edgecolor="0.25", linewidth=0.4))
            for p in lines:
                ax.plot(p[:, 0], p[:, 1], color="0.25", lw=0.6)
            extent.append(g["points"][:, :2])
    if "meshes" in files:          # meshed bodies: element outlines (corners of quadratic cells)
        g = read_vtu(files["meshes"])
        corners = {**VTK_CORNERS, 7: None}      # 7: a polygon cell, all its points
        polys = [g["points"][idx[:corners.get(int(ty)) or len(idx)], :2] for idx, ty in zip(cells(g), g["types"])]
        ax.add_collection(PolyCollection(polys, facecolor="0.85", edgecolor="0.35", linewidth=0.3))
        extent.append(g["points"][:, :2])
    if "contacts" in files:
        con = read_vtu(files["contacts"])
        data = con["point_data"] or con["cell_data"]
        rn = data.get("rn", np.zeros(0))
        if len(rn) and np.abs(rn).max() > 0:
            p = con["points"][:, :2]
            n = data["normal"][:, :2]
            allpts = np.vstack(extent) if extent else p
            size = np.ptp(allpts, axis=0).max()
            scale = force_scale or np.abs(rn).max()
            for k in np.nonzero(rn > 0)[0]:
                seg = np.array([p[k] - 0.01 * size * n[k], p[k] + 0.01 * size * n[k]])
                ax.plot(seg[:, 0], seg[:, 1], color="firebrick", lw=0.5 + 3.0 * rn[k] / scale)
    if extent:
        allpts = np.vstack(extent)
        lo, hi = allpts.min(axis=0), allpts.max(axis=0)
        pad = 0.02 * (hi - lo).max()
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
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
