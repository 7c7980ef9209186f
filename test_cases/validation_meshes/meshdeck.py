"""Small writer of meshed (MAILx) decks for the validation cases of this folder:
structured or given meshes of T3/Q4 elements, rigid walls (JONCx), CLxxx/ALpxx
contactors, ELAS/ELAS_PLAS materials, driven dofs, initial states, contact laws and
COMMAND.DAT, in LMGC90's fixed-column layout (doc/input_reference.md).

    d = Deck()
    d.material("STEEL", rho=7800, E=2e11, nu=0.3)
    b = d.mesh(nodes, elements, model="M2DQ4", material="STEEL")   # elements: [("Q4", [i, j, k, l])]
    d.drive(b, node, dof, ct=...)            # or evolution=[(t, v), ...]
    d.command(time_step=1e-4, number_of_steps=100, plane="strain")
    d.write("case_dir")

Node and element numbers are 0-based here and 1-based in the files.
"""
from pathlib import Path

import numpy as np


def e14(x):
    return f"{x:14.7E}"


def rect_grid(nx, ny, lx, ly, x0=0.0, y0=0.0):
    """Nodes (numbered row by row, x fastest) of an (nx+1) x (ny+1) grid."""
    xs = np.linspace(x0, x0 + lx, nx + 1)
    ys = np.linspace(y0, y0 + ly, ny + 1)
    return np.array([[x, y] for y in ys for x in xs])


def node_id(i, j, nx):
    return j * (nx + 1) + i


def quads(nx, ny):
    """Q4 connectivity (counter-clockwise) of rect_grid."""
    return [("Q4", [node_id(i, j, nx), node_id(i + 1, j, nx), node_id(i + 1, j + 1, nx), node_id(i, j + 1, nx)])
            for j in range(ny) for i in range(nx)]


def triangles(nx, ny):
    """T3 connectivity of rect_grid, each square cut along alternating diagonals."""
    out = []
    for j in range(ny):
        for i in range(nx):
            a, b = node_id(i, j, nx), node_id(i + 1, j, nx)
            c, d = node_id(i + 1, j + 1, nx), node_id(i, j + 1, nx)
            if (i + j) % 2 == 0:
                out += [("T3", [a, b, c]), ("T3", [a, c, d])]
            else:
                out += [("T3", [a, b, d]), ("T3", [b, c, d])]
    return out


class MeshBody:
    def __init__(self, number, nodes, elements, model, material):
        self.number = number
        self.nodes = np.asarray(nodes, dtype=float)
        self.elements = elements
        self.model = model
        self.material = material
        self.tactors = []    # ("CL", color, [(a, b, apab), ...]) or ("AL", color, [n0, n1, ...])
        self.x0 = np.zeros_like(self.nodes)
        self.v0 = np.zeros_like(self.nodes)

    def candidates(self, points, color="BLEUx"):
        """CLxxx points: (a, b, apab) each, the point (1 - apab) x_a + apab x_b."""
        self.tactors.append(("CL", color, list(points)))

    def polyline(self, nodes, color="BLEUx"):
        self.tactors.append(("AL", color, list(nodes)))


class Deck:
    def __init__(self):
        self.materials = []   # lines of BULK_BEHAV.DAT $behav blocks
        self.gravity = (0.0, 0.0)
        self.models = {}
        self.rigid = []       # (center, axe1, axe2, material, color)
        self.meshes = []
        self.drives = []      # (model, body, node, kind, dof, params or evolution)
        self.laws = []
        self.see = []
        self.run = {}
        self.evolutions = {}

    # -- bulk ----------------------------------------------------------------------
    def material(self, name, rho, E=None, nu=None, sig0=None, hardening=None):
        lines = []
        if E is None:
            lines.append(f" {name}  {'RIGID':<30s}  Umas={rho:14.7e}")
        else:
            law = "ELAS" if sig0 is None else "ELAS_PLAS"
            lines.append(f" {name}  {law:<30s}  Umas={rho:14.7e}")
            lines.append(" " * 40 + "elas: standard     ")
            lines.append(" " * 40 + "ani_: isotropic    ")
            lines.append(" " * 40 + f"EYng={E:14.7e}  Epss={nu:14.7e}")
            if sig0 is not None:
                lines.append(" " * 40 + "crit: Von-Mises    ")
                lines.append(" " * 40 + "isoh: linear       ")
                lines.append(" " * 40 + f"SIG0={sig0:14.7e}  K___={hardening:14.7e}")
                lines.append(" " * 40 + "cinh: none         ")
                lines.append(" " * 40 + "visc: none         ")
        self.materials.append(lines)

    def model(self, name, element, mater="elas_", mass="lump_"):
        self.models[name] = (element, mater, mass)

    # -- bodies --------------------------------------------------------------------
    def wall(self, center, axe1, axe2, material="TDURx", color="WALLx"):
        """A fixed JONCx wall (RBDY2, all dofs driven to 0)."""
        self.rigid.append((tuple(center), axe1, axe2, material, color))
        n = len(self.rigid)
        for dof in (1, 2, 3):
            self.drives.append(("RBDY2", n, 0, "vlocy", dof, (0.0, 0.0, 0.0, 0.0, 1.0, 0.0)))
        return n

    def mesh(self, nodes, elements, model, material):
        b = MeshBody(len(self.meshes) + 1, nodes, elements, model, material)
        self.meshes.append(b)
        return b

    def drive(self, body, node, dof, kind="vlocy", ct=0.0, amp=0.0, omega=0.0, phi=0.0, rampi=1.0, ramp=0.0,
              evolution=None):
        """A driven dof of mesh node `node` (0-based). evolution: [(t, value), ...]."""
        if evolution is not None:
            fname = f"evo_{len(self.evolutions) + 1}.dat"
            self.evolutions[fname] = evolution
            params = fname
        else:
            params = (ct, amp, omega, phi, rampi, ramp)
        self.drives.append(("MAILx", body.number, node + 1, kind, dof, params))

    # -- contact -------------------------------------------------------------------
    def law(self, nick, name, lines):
        """lines: [[(label, value), ...], ...] (one or two values per line)."""
        self.laws.append((nick, name, lines))

    def see_rule(self, cd, cdtac, cdcol, law, an, antac, ancol, alert):
        self.see.append((cd, cdtac, cdcol, law, an, antac, ancol, alert))

    def command(self, **kw):
        self.run.update(kw)

    # -- files ---------------------------------------------------------------------
    def write(self, case_dir):
        d = Path(case_dir, "DATBOX")
        d.mkdir(parents=True, exist_ok=True)
        (d / "BODIES.DAT").write_text(self._bodies())
        bulk = ["$gravy", f"                   grv1={self.gravity[0]:14.7e}  grv2={self.gravity[1]:14.7e}"
                f"  grv3={0.0:14.7e}"]
        for lines in self.materials:
            bulk += ["$behav  lawty"] + lines
        (d / "BULK_BEHAV.DAT").write_text("\n".join(bulk) + "\n")
        models = ["$model  mdlty  finel  eleop  value"]
        for name, (el, mater, mass) in self.models.items():
            models += [f" {name}", f"        MECAx  {el}  kine_  small", f"                      mater  {mater}",
                       f"                      mstrg  {mass}", "                      aniso  iso__",
                       "                      isext  no___"]
        (d / "MODELS.DAT").write_text("\n".join(models) + "\n")
        (d / "TACT_BEHAV.DAT").write_text(self._tact())
        (d / "DRV_DOF.DAT").write_text(self._drv())
        (d / "DOF.INI").write_text(self._dof())
        (d / "GPV.INI").write_text("\n! Gauss Point Values\n\n$steps      0                time= 0.0000000D+00\n")
        for name, table in self.evolutions.items():
            (d / name).write_text("".join(f"{t:.17g} {v:.17g}\n" for t, v in table))
        (d / "COMMAND.DAT").write_text("".join(f"{k} {v}\n" for k, v in self.run.items()))

    def _bodies(self):
        out = []
        for k, (c, a1, a2, mat, col) in enumerate(self.rigid, 1):
            out += ["$bdyty", f" RBDY2{k:7d}", "$blmty",
                    f" PLAIN      1  behav  {mat}  avrd={e14(0.0)}  gyrd={e14(0.0)}", "$nodty",
                    f" NO3xx      1                coo1={e14(c[0])}  coo2={e14(c[1])}  coo3={e14(0.0)}",
                    "$tacty", f" JONCx      1  color  {col}  axe1={e14(a1)}  axe2={e14(a2)}", "$$$$$$"]
        for b in self.meshes:
            out += ["$bdyty", f" MAILx{b.number:7d}", "$blmty"]
            for k, (kind, conn) in enumerate(b.elements, 1):
                out.append(f" {kind}xxx{k:7d}  nodes" + "".join(f"{n + 1:7d}" for n in conn))
                out.append(f"               model  {b.model}  behav  {b.material}")
            out.append("$nodty")
            for k, (x, y) in enumerate(b.nodes, 1):
                out.append(f" NO2xx{k:7d}                coo1={e14(x)}  coo2={e14(y)}")
            if b.tactors:
                out.append("$tacty")
            rank = 0
            for kind, col, items in b.tactors:
                if kind == "CL":
                    for j, (a, bb, apab) in enumerate(items):
                        rank += 1
                        lead = " " if j == 0 else "+"
                        out.append(f"{lead}CLxxx{rank:7d}  color  {col}  noda={a + 1:5d}  nodb={bb + 1:5d}"
                                   f"  apab={e14(apab)}")
                else:
                    rank += 1
                    for j in range(len(items) - 1):
                        lead = " " if j == 0 else "+"
                        out.append(f"{lead}ALpxx{rank:7d}  color  {col}  noda={items[j] + 1:5d}"
                                   f"  nodb={items[j + 1] + 1:5d}")
            out.append("$$$$$$")
        return "\n".join(out) + "\n"

    def _tact(self):
        out = []
        for nick, name, lines in self.laws:
            for j, line in enumerate(lines):
                head = f" {nick}  {name:<30s}" if j == 0 else " " * 38
                body = "  ".join(f"{lab:<4s}={val:14.7e}" for lab, val in line)
                out.append(head + "  " + body)
        if not self.laws:
            out.append("! no contact law")
        else:
            out = ["$behav"] + out
        if self.see:
            out += ["$seety", " cdbdy  cdtac  cdcol  behav  anbdy  antac  ancol       alert"]
            for cd, ct, cc, law, an, at, ac, alert in self.see:
                out.append(f" {cd}  {ct}  {cc}  {law}  {an}  {at}  {ac}      {alert:14.7e}")
        return "\n".join(out) + "\n"

    def _drv(self):
        out = ["! DOF"]
        groups = {}
        for model, body, node, kind, dof, params in self.drives:
            groups.setdefault((model, body), {}).setdefault(node, []).append((kind, dof, params))
        for (model, body), nodes in groups.items():
            out += ["$bdyty", f" {model}{body:7d}"]
            if model == "MAILx":
                out += ["$model", " MECAx"]
            for node, lines in sorted(nodes.items()):
                out += ["$nodty", " NO3xx      1" if model == "RBDY2" else f" NO2xx{node:7d}", "$dofty"]
                for kind, dof, params in lines:
                    if isinstance(params, str):
                        out.append(f" {kind}{dof:7d} evolution {params}")
                    else:
                        out.append(f" {kind}{dof:7d}" + "".join(f" {p:14.7e}" for p in params))
            out.append("$$$$$$")
        return "\n".join(out) + "\n"

    def _dof(self):
        out = ["! DOF", "", "$steps      0                time= 0.0000000D+00", "",
               "!-----------------------------------------------------------------------"]
        for b in self.meshes:
            moving = [k for k in range(len(b.nodes)) if np.any(b.x0[k] != 0) or np.any(b.v0[k] != 0)]
            if not moving:
                continue
            out += ["$bdyty", f" MAILx{b.number:7d}", "$model", " MECAx", "$nodty"]
            for k in moving:
                out.append(f" NO2xx{k + 1:7d}                X(1)={b.x0[k, 0]:14.7e}  X(2)={b.x0[k, 1]:14.7e}")
                out.append(f"                             V(1)={b.v0[k, 0]:14.7e}  V(2)={b.v0[k, 1]:14.7e}")
            out.append("$$$$$$")
        return "\n".join(out) + "\n"


def read_probe(path):
    """mesh_probe output -> list of records dict(step, time, energy (3,), nodes (n, 6), gauss (ng, k))."""
    recs = []
    lines = Path(path).read_text().splitlines()
    i = 0
    while i < len(lines):
        w = lines[i].split()
        if w[0] == "step":
            rec = dict(step=int(w[1]), time=float(w[2]))
            recs.append(rec)
        elif w[0] == "energy":
            rec["energy"] = np.array([float(x) for x in w[1:4]])
        elif w[0] == "nodes":
            n = int(w[1])
            rec["nodes"] = np.array([[float(x) for x in lines[i + 1 + k].split()] for k in range(n)])
            i += n
        elif w[0] == "gauss":
            n = int(w[1])
            rec["gauss"] = np.array([[float(x) for x in lines[i + 1 + k].split()] for k in range(n)])
            i += n
        i += 1
    return recs
