"""Readers for LMGC90 DATBOX files (and our COMMAND.DAT) into fracas_tools.pre objects.

Fixed columns are read as LMGC90 reads them (see doc/tools.md). Lines whose first
column is '!' or '#' and blank lines are skipped. Errors raise
:class:`~fracas_tools.fortran_io.DatboxError` with file:line:column.

    case = read_case("my_case")          # a Case, as pre.Case.write wrote it
    case.write("copy_of_my_case")        # byte-identical DATBOX files
"""

from pathlib import Path

import numpy as np

from .fortran_io import DatboxError, field, parse_int, parse_real
from .mailx import ELEMENT_NODES, Candidates, Element, MeshBody, Model, Polyline
from .outbox import read_dof_file, read_gpv, read_vloc_rloc
from .postpro_deck import read_postpro
from .pre import (LAW_LAYOUT, Body, Case, ContactLaw, DrivenDof, Disk, Jonc, Material, Polygon,
                  RunControl, SeeRule, Xksid, polygon_area)

__all__ = ["read_bodies", "read_bulk_behav", "read_models", "read_tact_behav", "read_drv_dof",
           "read_dof", "read_dof_ini", "read_command", "read_evolution", "read_case", "find_datbox"]


def _data_lines(path):
    """(line number, text) of the lines LMGC90 reads: not blank, not a comment."""
    out = []
    with open(path, "r", encoding="latin-1") as f:
        for i, raw in enumerate(f, start=1):
            t = raw.rstrip("\n").rstrip("\r")
            if not t.strip() or t[0] in "!#":
                continue
            out.append((i, t))
    return out


class _Cursor:
    def __init__(self, path):
        self.path = str(path)
        self.lines = _data_lines(path)
        self.i = 0

    def more(self):
        return self.i < len(self.lines)

    def peek(self):
        return self.lines[self.i] if self.i < len(self.lines) else (None, None)

    def next(self, what):
        if self.i >= len(self.lines):
            last = self.lines[-1][0] if self.lines else 0
            raise DatboxError(self.path, last + 1, 1, f"unexpected end of file: expected {what}")
        r = self.lines[self.i]
        self.i += 1
        return r

    def err(self, ln, col, msg):
        return DatboxError(self.path, ln, col, msg)


def _keyword(t):
    return t[:6] if t.startswith("$") else None


def _top_level(cur, ln, t):
    """A line outside any record. LMGC90's readers scan for keywords and ignore
    such lines (its own echo files hold '  ! ...' comment lines with a blank
    column 1); an unknown '$' keyword is an error."""
    if t.startswith("$"):
        raise cur.err(ln, 1, f"unexpected keyword {t.strip()[:12]!r} here")


# --------------------------------------------------------------------------------------
# BODIES.DAT
# --------------------------------------------------------------------------------------

def _read_tactor(cur, ln, t):
    kind = field(t, 2, 6)
    color = field(t, 23, 27)
    p = cur.path
    try:
        if kind in ("DISKx", "xKSID"):
            r = parse_real(t, 35, 48, p, ln, "byrd (radius)", blank_ok=False)
            return Disk(r, color) if kind == "DISKx" else Xksid(r, color)
        if kind == "JONCx":
            a1 = parse_real(t, 35, 48, p, ln, "axe1 (half length)", blank_ok=False)
            a2 = parse_real(t, 56, 69, p, ln, "axe2 (half thickness)", blank_ok=False)
            return Jonc(a1, a2, color)
        if kind == "POLYG":
            nv = parse_int(t, 40, 46, p, ln, "nb_vertex")
            if nv < 3:
                raise cur.err(ln, 40, f"POLYG needs at least 3 vertices, got {nv}")
            v = np.zeros((nv, 2))
            for k in range(nv):
                lk, tk = cur.next(f"vertex {k + 1} of {nv} of the POLYG of line {ln}")
                if tk.startswith("$") or tk[:27].strip():
                    raise cur.err(lk, 1, f"expected vertex {k + 1} of {nv} (POLYG of line {ln})")
                v[k, 0] = parse_real(tk, 35, 48, p, lk, "vertex x", blank_ok=False)
                v[k, 1] = parse_real(tk, 56, 69, p, lk, "vertex y", blank_ok=False)
            if polygon_area(v) <= 0.0:
                raise cur.err(ln, 2, "POLYG vertices are not counter-clockwise (signed area <= 0)")
            return Polygon(v, color, check=False)
    except ValueError as e:
        if isinstance(e, DatboxError):
            raise
        raise cur.err(ln, 2, str(e)) from None
    raise cur.err(ln, 2, f"unknown contactor type {kind!r} (DISKx, xKSID, JONCx, POLYG)")


def _read_mesh_tactors(cur, tactors):
    """Mesh contactors after $tacty, up to the next keyword: a CLxxx line and its
    '+' lines make one Candidates, an ALpxx line and its '+' lines one Polyline
    (LMGC90's echo BODIES.OUT writes every CLxxx point on its own line and leaves
    the colour of '+' lines blank: both are read)."""
    p = cur.path
    while True:
        lt, tt = cur.peek()
        if tt is None or tt.startswith("$"):
            return
        cur.next("contactor")
        kind = field(tt, 2, 6)
        plus = tt.startswith("+")
        if kind not in ("CLxxx", "ALpxx"):
            raise cur.err(lt, 2, f"contactor type {kind!r} on a MAILx body (CLxxx or ALpxx)")
        if plus and (not tactors or tactors[-1].kind != kind):
            raise cur.err(lt, 1, f"'+{kind}' continuation line without a {kind} line before it")
        color = field(tt, 23, 27)
        if plus and not color.strip():
            color = tactors[-1].color
        a = parse_int(tt, 35, 39, p, lt, "noda")
        b = parse_int(tt, 47, 51, p, lt, "nodb")
        try:
            if kind == "CLxxx":
                pt = (a, b, parse_real(tt, 59, 72, p, lt, "apab", blank_ok=False))
                if plus:
                    tactors[-1].points.append(pt)
                else:
                    tactors.append(Candidates([pt], color))
            elif plus:
                if a != tactors[-1].nodes[-1]:
                    raise cur.err(lt, 35, f"ALpxx segment starts at node {a}, the previous one "
                                  f"ended at node {tactors[-1].nodes[-1]} (a polyline is continuous)")
                tactors[-1].nodes.append(b)
            else:
                tactors.append(Polyline([a, b], color))
        except ValueError as e:
            if isinstance(e, DatboxError):
                raise
            raise cur.err(lt, 2, str(e)) from None


def _read_mesh_body(cur, lm):
    """The rest of a MAILx $bdyty record, after its model line."""
    p = cur.path
    elements, coords, tactors = [], [], []
    while True:
        lk, tk = cur.next("$$$$$$ (end of body)")
        kw = _keyword(tk)
        if kw == "$$$$$$":
            break
        if kw == "$blmty":
            while True:
                le, te = cur.peek()
                if te is None or te.startswith("$"):
                    break
                cur.next("element")
                kind = field(te, 2, 6)
                if kind not in ELEMENT_NODES:
                    raise cur.err(le, 2, f"element {kind!r}: one of {', '.join(ELEMENT_NODES)}")
                if field(te, 16, 20) != "nodes":
                    raise cur.err(le, 16, "expected 'nodes' at columns 16-20")
                nodes = [parse_int(te, 21 + 7 * k, 27 + 7 * k, p, le, f"node {k + 1}")
                         for k in range(ELEMENT_NODES[kind])]
                lmod, tmod = cur.next(f"'model ... behav' line of the {kind} of line {le}")
                if field(tmod, 16, 20) != "model" or field(tmod, 30, 34) != "behav":
                    raise cur.err(lmod, 16, "expected 'model  XXXXX  behav  XXXXX' (columns 16-41)")
                try:
                    elements.append((le, Element(kind, nodes, field(tmod, 23, 27), field(tmod, 37, 41))))
                except ValueError as e:
                    raise cur.err(le, 2, str(e)) from None
        elif kw == "$nodty":
            while True:
                lnn, tn = cur.peek()
                if tn is None or tn.startswith("$"):
                    break
                cur.next("node")
                if field(tn, 2, 6) != "NO2xx":
                    raise cur.err(lnn, 2, f"expected a NO2xx node, found {field(tn, 2, 6)!r}")
                k = parse_int(tn, 7, 13, p, lnn, "node number")
                if k != len(coords) + 1:
                    raise cur.err(lnn, 7, f"node {k}: nodes must be numbered 1, 2, ... in order "
                                  f"(expected {len(coords) + 1})")
                coords.append((parse_real(tn, 35, 48, p, lnn, "coo1"), parse_real(tn, 56, 69, p, lnn, "coo2")))
        elif kw == "$tacty":
            _read_mesh_tactors(cur, tactors)
        else:
            raise cur.err(lk, 1, f"unexpected line in body record: {tk.strip()[:30]!r}")
    if not coords:
        raise cur.err(lm, 1, "MAILx body without $nodty NO2xx nodes")
    body = MeshBody(coords)
    for le, e in elements:
        try:
            body.add_element(e)
        except ValueError as err:
            raise cur.err(le, 21, str(err)) from None
    for c in tactors:
        bad = [n for n in c.node_numbers() if not 1 <= n <= body.n_nodes]
        if bad:
            raise cur.err(lm, 1, f"{c.kind} contactor on nodes {bad} outside 1..{body.n_nodes}")
    body.contactors = tactors
    return body


def read_bodies(path):
    """BODIES.DAT -> list of pre.Body (RBDY2) and mailx.MeshBody (MAILx), numbered
    1.. within each model in order of appearance; avrd, gyrd, coordinates and
    contactors exactly as read."""
    cur = _Cursor(path)
    bodies = []
    while cur.more():
        ln, t = cur.next("$bdyty")
        if _keyword(t) != "$bdyty":
            _top_level(cur, ln, t)
            continue
        lm, tm = cur.next("body model line")
        model = field(tm, 2, 6)
        if model == "MAILx":
            body = _read_mesh_body(cur, lm)
            body.number = sum(1 for b in bodies if b.model == model) + 1
            body.source_line = lm
            bodies.append(body)
            continue
        if model != "RBDY2":
            raise cur.err(lm, 2, f"body model {model!r}: RBDY2 or MAILx")
        body = None
        behav = None
        avrd = gyrd = 0.0
        coor = None
        tactors = []
        while True:
            lk, tk = cur.next("$$$$$$ (end of body)")
            kw = _keyword(tk)
            if kw == "$$$$$$":
                break
            if kw == "$blmty":
                lb, tb = cur.next("PLAIN line")
                if field(tb, 2, 6) != "PLAIN":
                    raise cur.err(lb, 2, f"expected PLAIN bulk element, found {field(tb, 2, 6)!r}")
                behav = field(tb, 23, 27)
                avrd = parse_real(tb, 35, 48, cur.path, lb, "avrd")
                gyrd = parse_real(tb, 56, 69, cur.path, lb, "gyrd")
            elif kw == "$nodty":
                lnn, tn = cur.next("NO3xx line")
                if field(tn, 2, 6) != "NO3xx":
                    raise cur.err(lnn, 2, f"expected NO3xx node, found {field(tn, 2, 6)!r}")
                coor = [parse_real(tn, c, c + 13, cur.path, lnn, f"coo{k + 1}")
                        for k, c in enumerate((35, 56, 77))]
            elif kw == "$tacty":
                while True:
                    lt, tt = cur.peek()
                    if tt is None or tt.startswith("$"):
                        break
                    cur.next("contactor")
                    tactors.append(_read_tactor(cur, lt, tt))
            else:
                raise cur.err(lk, 1, f"unexpected line in body record: {tk.strip()[:30]!r}")
        if behav is None:
            raise cur.err(lm, 1, "body without $blmty PLAIN line")
        if coor is None:
            raise cur.err(lm, 1, "body without $nodty NO3xx line")
        if not tactors:
            raise cur.err(lm, 1, "body without contactor ($tacty)")
        try:
            body = Body(behav, coor[:2], coor[2], model=model, avrd=avrd, gyrd=gyrd)
        except ValueError as e:
            raise cur.err(lm, 1, str(e)) from None
        body.contactors = tactors
        body.number = sum(1 for b in bodies if b.model == model) + 1
        body.source_line = lm
        bodies.append(body)
    return bodies


# --------------------------------------------------------------------------------------
# BULK_BEHAV.DAT
# --------------------------------------------------------------------------------------

def read_bulk_behav(path):
    """BULK_BEHAV.DAT -> (gravity (3,), dict name -> pre.Material)."""
    cur = _Cursor(path)
    gravity = np.zeros(3)
    mats = {}
    while cur.more():
        ln, t = cur.next("keyword")
        kw = _keyword(t)
        if kw == "$gravy":
            lg, tg = cur.next("gravity line")
            gravity = np.array([parse_real(tg, c, c + 13, cur.path, lg, f"grv{k + 1}")
                                for k, c in enumerate((25, 46, 67))])
        elif kw == "$behav":
            lb, tb = cur.next("bulk behaviour line")
            name, law = field(tb, 2, 6), field(tb, 9, 38).strip()
            if not law:
                raise cur.err(lb, 9, "missing bulk law name (columns 9-38)")
            dens = parse_real(tb, 46, 59, cur.path, lb, "Umas (density)")
            # continuation lines: 'label: text' options and 'labl= value' numbers
            items = []
            while True:
                lc, tc = cur.peek()
                if tc is None or tc.startswith("$") or tc[:6].strip():
                    break
                cur.next("continuation")
                if field(tc, 45, 45) == ":":
                    items.append((field(tc, 41, 44), tc[46:].strip()))
                else:
                    items.append([(field(tc, cl, cl + 3), parse_real(tc, cv, cv + 13, cur.path, lc,
                                                                      field(tc, cl, cl + 3).strip(),
                                                                      blank_ok=False))
                                  for cl, cv in ((41, 46), (62, 67))
                                  if field(tc, cl, cv + 13).strip()])
            if name in mats:
                raise cur.err(lb, 2, f"material {name!r} defined twice")
            try:
                mats[name] = Material(name, dens, law, items=items)
            except ValueError as e:
                raise cur.err(lb, 2, str(e)) from None
        else:
            _top_level(cur, ln, t)
    return gravity, mats


# --------------------------------------------------------------------------------------
# MODELS.DAT
# --------------------------------------------------------------------------------------

def read_models(path):
    """MODELS.DAT -> dict name -> mailx.Model (options in the order read)."""
    cur = _Cursor(path)
    models = {}
    while cur.more():
        ln, t = cur.next("$model")
        if _keyword(t) != "$model":
            _top_level(cur, ln, t)
            continue
        lname, tname = cur.next("model nickname line")
        name = field(tname, 2, 6)
        lp, tp = cur.next("physics and element line")
        physics, element = field(tp, 9, 13), field(tp, 16, 20)
        options = {}
        lo, to = lp, tp
        while True:
            if field(to, 23, 27).strip():
                options[field(to, 23, 27)] = to[29:].strip()
            lo, to = cur.peek()
            if to is None or to.startswith("$") or to[:22].strip():
                break
            cur.next("model option")
        if name in models:
            raise cur.err(lname, 2, f"model {name!r} defined twice")
        try:
            models[name] = Model(name, element, physics=physics, options=options)
        except ValueError as e:
            raise cur.err(lp, 9, str(e)) from None
    return models


# --------------------------------------------------------------------------------------
# TACT_BEHAV.DAT
# --------------------------------------------------------------------------------------

def _pairs(cur, ln, t):
    """(label, value) pairs of a law line: labels at 41-45 / 62-66, values at 46-59 / 67-80."""
    out = []
    for cl, cv in ((41, 46), (62, 67)):
        lab = field(t, cl, cl + 4)
        val = field(t, cv, cv + 13)
        if not lab.strip() and not val.strip():
            continue
        out.append((lab, parse_real(t, cv, cv + 13, cur.path, ln, f"law parameter {lab.strip()}",
                                    blank_ok=False)))
    return out


def read_tact_behav(path):
    """TACT_BEHAV.DAT -> (dict name -> pre.ContactLaw, list of pre.SeeRule)."""
    cur = _Cursor(path)
    laws, rules = {}, []
    while cur.more():
        ln, t = cur.next("keyword")
        kw = _keyword(t)
        if kw == "$behav":
            lb, tb = cur.next("contact law line")
            name, law = field(tb, 2, 6), field(tb, 9, 38).strip()
            if not law:
                raise cur.err(lb, 9, "missing contact law name (columns 9-38)")
            lines = [_pairs(cur, lb, tb)]
            while True:
                lc, tc = cur.peek()
                if tc is None or tc.startswith("$") or tc[:40].strip():
                    break
                cur.next("law parameters")
                lines.append(_pairs(cur, lc, tc))
            lines = [l for l in lines if l]
            counts = [len(l) for l in lines]
            if law in LAW_LAYOUT:
                layout = LAW_LAYOUT[law]
                if counts != [len(l) for l in layout]:
                    raise cur.err(lb, 41, f"law {law}: expected parameters "
                                  f"{' / '.join(' '.join(l) for l in layout)} "
                                  f"({[len(l) for l in layout]} per line), found {counts} per line")
            else:
                layout, used = [], set()
                for l in lines:
                    keys = []
                    for lab, _ in l:
                        k = lab.replace("=", "").strip() or "p"
                        base, n = k, 2
                        while k in used:
                            k, n = f"{base}{n}", n + 1
                        used.add(k)
                        keys.append(k)
                    layout.append(keys)
            params, labels = {}, {}
            for keys, l in zip(layout, lines):
                for k, (lab, val) in zip(keys, l):
                    params[k], labels[k] = val, lab
            if name in laws:
                raise cur.err(lb, 2, f"contact law {name!r} defined twice")
            try:
                laws[name] = ContactLaw(name, law, layout=layout, labels=labels, **params)
            except ValueError as e:
                raise cur.err(lb, 2, str(e)) from None
        elif kw == "$seety":
            while True:
                ls, ts = cur.peek()
                if ts is None or ts.startswith("$"):
                    break
                cur.next("see rule")
                if field(ts, 2, 6) == "cdbdy":
                    continue                       # column header
                if ts.startswith("+"):
                    if not rules:
                        raise cur.err(ls, 1, "'+' global alert line without a see rule")
                    rules[-1].global_alert = parse_real(ts, 55, 68, cur.path, ls, "global alert",
                                                        blank_ok=False)
                    continue
                try:
                    rules.append(SeeRule(cdbdy=field(ts, 2, 6), cdtac=field(ts, 9, 13),
                                         cdcol=field(ts, 16, 20), behav=field(ts, 23, 27),
                                         anbdy=field(ts, 30, 34), antac=field(ts, 37, 41),
                                         ancol=field(ts, 44, 48),
                                         alert=parse_real(ts, 55, 68, cur.path, ls, "alert",
                                                          blank_ok=False)))
                except ValueError as e:
                    if isinstance(e, DatboxError):
                        raise
                    raise cur.err(ls, 2, str(e)) from None
                rules[-1].source_line = ls
        else:
            _top_level(cur, ln, t)
    return laws, rules


# --------------------------------------------------------------------------------------
# DRV_DOF.DAT and evolution files
# --------------------------------------------------------------------------------------

def read_evolution(path):
    """A two-column (t, value) evolution file -> (n, 2) array (free format)."""
    rows = []
    with open(path, "r", encoding="latin-1") as f:
        for i, raw in enumerate(f, start=1):
            s = raw.strip()
            if not s or s[0] in "!#":
                continue
            parts = s.replace("D", "E").replace("d", "E").split()
            if len(parts) < 2:
                raise DatboxError(path, i, 1, "expected two columns: time value")
            try:
                rows.append((float(parts[0]), float(parts[1])))
            except ValueError:
                raise DatboxError(path, i, 1, f"cannot read {s!r} as two numbers") from None
    d = np.array(rows, dtype=float).reshape(-1, 2)
    if len(d) == 0:
        raise DatboxError(path, 1, 1, "empty evolution file")
    if np.any(np.diff(d[:, 0]) <= 0.0):
        raise DatboxError(path, 1, 1, "evolution times must be strictly increasing")
    return d


def read_drv_dof(path, datbox_dir=None):
    """DRV_DOF.DAT -> dict body -> list of pre.DrivenDof; the key is the body number
    for RBDY2 bodies and ('MAILx', number) for meshed bodies, whose DrivenDof carry
    their ``node``. Evolution files are loaded from ``datbox_dir`` (default: the
    folder of path) when they exist; their text is kept so that writing the case
    again reproduces them unchanged."""
    cur = _Cursor(path)
    datbox_dir = Path(datbox_dir) if datbox_dir is not None else Path(path).parent
    out = {}
    while cur.more():
        ln, t = cur.next("$bdyty")
        if _keyword(t) != "$bdyty":
            _top_level(cur, ln, t)
            continue
        lm, tm = cur.next("body line")
        model = field(tm, 2, 6)
        if model not in ("RBDY2", "MAILx"):
            raise cur.err(lm, 2, f"body model {model!r}: RBDY2 or MAILx")
        num = parse_int(tm, 7, 15, cur.path, lm, "body number")
        lst = out.setdefault(num if model == "RBDY2" else (model, num), [])
        node = None
        while True:
            lk, tk = cur.next("$$$$$$ (end of body)")
            kw = _keyword(tk)
            if kw == "$$$$$$":
                break
            if kw == "$model":
                cur.next("physics line")
            elif kw == "$nodty":
                lnn, tn = cur.next("node line")
                want = "NO3xx" if model == "RBDY2" else "NO2xx"
                if field(tn, 2, 6) != want:
                    raise cur.err(lnn, 2, f"expected a {want} node line, found {field(tn, 2, 6)!r}")
                if model == "MAILx":
                    node = parse_int(tn, 7, 13, cur.path, lnn, "node number")
            elif kw == "$dofty":
                while True:
                    ld, td = cur.peek()
                    if td is None or td.startswith("$"):
                        break
                    cur.next("driven dof")
                    kind = field(td, 2, 6)
                    if kind not in ("vlocy", "force"):
                        raise cur.err(ld, 2, f"driven dof kind {kind!r}: 'vlocy' or 'force'")
                    dof = parse_int(td, 7, 13, cur.path, ld, "dof number")
                    if model == "RBDY2" and dof not in (1, 2, 3):
                        raise cur.err(ld, 9, f"RBDY2 dof must be 1, 2 or 3, got {dof}")
                    if model == "MAILx" and dof not in (1, 2):
                        raise cur.err(ld, 9, f"a MAILx node has dofs 1 and 2, got {dof}")
                    if model == "MAILx" and node is None:
                        raise cur.err(ld, 1, "driven dof before the $nodty line of its node")
                    if field(td, 15, 23) == "evolution":
                        fname = td[24:64].strip()
                        if not fname:
                            raise cur.err(ld, 25, "missing evolution file name (columns 25-64)")
                        fpath = datbox_dir / fname
                        data = text = None
                        if fpath.exists():
                            data = read_evolution(fpath)
                            text = fpath.read_text(encoding="latin-1")
                        d = DrivenDof(dof, kind, evolution=fname, evolution_data=data)
                        d.evolution_text = text
                    else:
                        vals = [parse_real(td, c, c + 13, cur.path, ld, name)
                                for c, name in zip((15, 30, 45, 60, 75, 90),
                                                   ("CT", "AMP", "OMEGA", "PHI", "RAMPI", "RAMP"))]
                        d = DrivenDof(dof, kind, *vals)
                    d.source_line = ld
                    d.node = node
                    lst.append(d)
            else:
                raise cur.err(lk, 1, f"unexpected line in DRV_DOF body record: {tk.strip()[:30]!r}")
    return out


# --------------------------------------------------------------------------------------
# DOF.INI / DOF.OUT.n
# --------------------------------------------------------------------------------------

def read_dof(path):
    """DOF.INI or DOF.OUT.n -> (step, time, states): states maps an RBDY2 body
    number to (X (3,), V (3,)) and ('MAILx', number) to (X (n, 2), V (n, 2), nodes).
    outbox.read_dof_file gives the records with their order and layout."""
    d = read_dof_file(path)
    states = {}
    for r in d.records:
        if r.model == "RBDY2":
            states[r.number] = (r.x, r.v)
        else:
            states[(r.model, r.number)] = (r.x, r.v, r.nodes)
    return d.step, d.time, states


read_dof_ini = read_dof


# --------------------------------------------------------------------------------------
# COMMAND.DAT
# --------------------------------------------------------------------------------------

def read_command(path):
    """COMMAND.DAT ('keyword value' or 'keyword = value' per line, keywords
    case-insensitive, '!' or '#' start a comment) -> pre.RunControl."""
    rc = RunControl()
    seen = {}
    with open(path, "r", encoding="latin-1") as f:
        for i, raw in enumerate(f, start=1):
            s = raw.rstrip("\n")
            cut = min([p for p in (s.find("!"), s.find("#")) if p >= 0], default=len(s))
            s = s[:cut]
            if not s.strip():
                continue
            col = len(s) - len(s.lstrip()) + 1
            body = s.strip()
            k = body.split()[0].split("=")[0]
            rest = body[len(k):].strip()
            if rest.startswith("="):
                rest = rest[1:].strip()
            if not rest or len(rest.split()) != 1:
                raise DatboxError(path, i, col, "expected 'keyword value'")
            k = k.lower()
            if k in seen:
                raise DatboxError(path, i, col, f"{k} already given on line {seen[k]}")
            pair = {"number_of_steps": "final_time", "final_time": "number_of_steps"}.get(k)
            if pair in seen:
                raise DatboxError(path, i, col, f"give either number_of_steps or final_time, not both "
                                  f"(the other is on line {seen[pair]})")
            try:
                rc.values[k] = RunControl._convert(k, rest)
            except ValueError as e:
                raise DatboxError(path, i, col, str(e)) from None
            seen[k] = i
    return rc


# --------------------------------------------------------------------------------------
# whole case
# --------------------------------------------------------------------------------------

def find_datbox(case_dir):
    """case_dir/DATBOX, or case_dir itself when it holds BODIES.DAT."""
    p = Path(case_dir)
    if (p / "DATBOX" / "BODIES.DAT").exists():
        return p / "DATBOX"
    if (p / "BODIES.DAT").exists():
        return p
    raise FileNotFoundError(f"no DATBOX/BODIES.DAT under {p}")


def read_case(case_dir):
    """Read a case directory (or a DATBOX folder) into a pre.Case."""
    d = find_datbox(case_dir)
    case = Case()
    for b in read_bodies(d / "BODIES.DAT"):
        case.bodies.append(b)
    if (d / "MODELS.DAT").exists():
        case.models = read_models(d / "MODELS.DAT")
    if (d / "BULK_BEHAV.DAT").exists():
        case.gravity, case.materials = read_bulk_behav(d / "BULK_BEHAV.DAT")
    else:
        case.gravity = np.zeros(3)
    if (d / "TACT_BEHAV.DAT").exists():
        case.laws, case.see_rules = read_tact_behav(d / "TACT_BEHAV.DAT")
    if (d / "DRV_DOF.DAT").exists():
        for key, lst in read_drv_dof(d / "DRV_DOF.DAT", d).items():
            model, num = key if isinstance(key, tuple) else ("RBDY2", key)
            try:
                body = case.body(model, num)
            except KeyError:
                raise DatboxError(d / "DRV_DOF.DAT", lst[0].source_line if lst else 0, 9,
                                  f"driven body {model} {num} does not exist") from None
            for dd in lst:
                if dd.node is not None and not 1 <= dd.node <= body.n_nodes:
                    raise DatboxError(d / "DRV_DOF.DAT", dd.source_line, 9,
                                      f"MAILx {num} has {body.n_nodes} nodes, no node {dd.node}")
            body.driven.extend(lst)
    if (d / "DOF.INI").exists():
        dof = read_dof_file(d / "DOF.INI")
        case.dof_step, case.dof_time = dof.step, dof.time
        for r in dof.records:
            try:
                body = case.body(r.model, r.number)
            except KeyError:
                raise DatboxError(d / "DOF.INI", 0, 9, f"body {r.model} {r.number} does not exist") from None
            if r.model == "MAILx":
                idx = np.array(r.nodes, dtype=int) - 1
                if len(idx) and (idx.min() < 0 or idx.max() >= body.n_nodes):
                    raise DatboxError(d / "DOF.INI", 0, 9, f"MAILx {r.number}: node numbers outside "
                                      f"1..{body.n_nodes}")
                body.x0[idx] = r.x
                body.v0[idx] = r.v
            else:
                body.x0, body.v0 = r.x, r.v
    if (d / "Vloc_Rloc.INI").exists():
        v = read_vloc_rloc(d / "Vloc_Rloc.INI")
        if v.records:
            case.vloc_ini = v
    if (d / "GPV.INI").exists():
        g = read_gpv(d / "GPV.INI")
        if g.bodies:
            case.gpv_ini = g
    if (d / "POSTPRO.DAT").exists():
        case.postpro = read_postpro(d / "POSTPRO.DAT")
    if (d / "COMMAND.DAT").exists():
        case.run = read_command(d / "COMMAND.DAT")
    return case
