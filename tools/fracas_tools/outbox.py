"""State files in LMGC90's layout: DOF (DOF.INI, DOF.OUT.n), Gauss-point values
(GPV.INI, GPV.OUT.n) and contacts (Vloc_Rloc.INI, Vloc_Rloc.OUT.n), for rigid
(RBDY2) and meshed (MAILx) bodies.

Each file type has a reader returning an object whose ``text()`` gives the file
back. Two header styles exist: ``'pre'``, the one pylmgc90.pre writes for the .INI
files (empty lines, exponents ``e``), and ``'out'``, the one LMGC90's Fortran writers
use (lines of blanks, exponents ``D``); the reader records which one it found so that
read -> text() is byte-identical for the files of ../shared/lmgc90_decks.

    v = read_vloc_rloc("OUTBOX/Vloc_Rloc.OUT.1")
    for r in v.records:
        print(r.inter, r.cdbdy, r.icdbdy, r.cdtac, r.icdtac, r.rln, r.status, r.internals)
    d = read_dof_file("OUTBOX/DOF.OUT.1")
    d.get("MAILx", 1).x            # (n, 2) nodal displacements
"""

from dataclasses import dataclass, field

import numpy as np

from .fortran_io import DatboxError, d14, e14, field as col, parse_int, parse_real

__all__ = ["DofRecord", "DofFile", "read_dof_file", "GpvElement", "GpvBody", "GpvFile",
           "read_gpv", "ContactRecord", "VlocRloc", "read_vloc_rloc", "VLOC_LAYOUTS",
           "steps_line"]

RULE = "!" + "-" * 71
_END = "      "


def steps_line(step, time, style="pre"):
    """The '$steps' line. pylmgc90.pre writes step 0 right after '$steps' (cols
    7-13); LMGC90's Fortran writers use A6,I9 (number ending at col 15). Both read
    the same with I7 at 9-15."""
    if style == "pre" and step == 0:
        return f"$steps{step:7d}                time={d14(time)}"
    return f"$steps{step:9d}              time={d14(time)}"


def _raw_lines(path):
    with open(path, "r", encoding="latin-1") as f:
        return [l.rstrip("\n").rstrip("\r") for l in f]


class _Lines:
    """Raw lines with a cursor; comment ('!') and blank lines are skipped by
    next(), '#' lines are kept (they announce internal values in Vloc_Rloc)."""

    def __init__(self, path):
        self.path = str(path)
        self.lines = _raw_lines(path)
        self.i = 0

    def _skip(self):
        while self.i < len(self.lines):
            t = self.lines[self.i]
            if t.strip() and not t.startswith("!"):
                return
            self.i += 1

    def more(self):
        self._skip()
        return self.i < len(self.lines)

    def peek(self):
        self._skip()
        if self.i >= len(self.lines):
            return None, None
        return self.i + 1, self.lines[self.i]

    def next(self, what):
        self._skip()
        if self.i >= len(self.lines):
            raise DatboxError(self.path, len(self.lines) + 1, 1, f"unexpected end of file: expected {what}")
        self.i += 1
        return self.i, self.lines[self.i - 1]

    def expect(self, word, what):
        ln, t = self.next(what)
        if not t.startswith(word):
            raise self.err(ln, 1, f"expected {what} ({word!r}), found {t.strip()[:30]!r}")
        return ln, t

    def err(self, ln, c, msg):
        return DatboxError(self.path, ln, c, msg)

    def style(self):
        """'pre' when the file starts with an empty line (pylmgc90), else 'out'."""
        return "pre" if self.lines and self.lines[0] == "" else "out"


def _header(title, style, third):
    if style == "pre":
        return ["", f"! {title}", ""]
    return ["     ", f"! {title}", third]


def _steps(cur, ln, t):
    return (parse_int(t, 7, 15, cur.path, ln, "step"),
            parse_real(t, 35, 48, cur.path, ln, "time"))


def _body_line(cur):
    ln, t = cur.next("body line")
    return ln, col(t, 2, 6), parse_int(t, 7, 15, cur.path, ln, "body number")


def _reals(cur, ln, t, cols, what):
    return np.array([parse_real(t, c, c + 13, cur.path, ln, f"{what}({k + 1})")
                     for k, c in enumerate(cols)])


# --------------------------------------------------------------------------------------
# DOF.INI / DOF.OUT.n
# --------------------------------------------------------------------------------------

@dataclass
class DofRecord:
    """State of one body: RBDY2 x, v of shape (3,) (displacement from the
    reference node, rotation, and velocity); MAILx x, v of shape (n, 2) for the
    nodes listed in ``nodes`` (1-based)."""
    model: str
    number: int
    x: np.ndarray
    v: np.ndarray
    nodes: list = None
    physics: str = "MECAx"


@dataclass
class DofFile:
    step: int = 0
    time: float = 0.0
    records: list = field(default_factory=list)
    style: str = "out"

    def get(self, model, number):
        for r in self.records:
            if r.model == model and r.number == number:
                return r
        raise KeyError(f"no {model} {number} in this DOF file")

    def text(self, style=None):
        style = style or self.style
        fmt = (lambda x: e14(x)) if style == "pre" else d14
        out = _header("DOF", style, "     ") + [steps_line(self.step, self.time, style),
                                                  "" if style == "pre" else " ", RULE]
        rigid = [r for r in self.records if r.model != "MAILx"]
        meshes = [r for r in self.records if r.model == "MAILx"]
        sep = [] if style == "pre" else [_END]
        for r in rigid:
            num = f"  {r.number:7d}" if style == "pre" else f"{r.number:9d}"
            out += ["$bdyty", f" {r.model}{num}", "$nodty",
                    " NO3xx      1" + " " * 16 + "  ".join(f"X({k + 1})={fmt(r.x[k])}" for k in range(3)),
                    " " * 29 + "  ".join(f"V({k + 1})={fmt(r.v[k])}" for k in range(3)),
                    "$$$$$$"] + sep
        if meshes and style == "out":
            out.append(RULE)
        for r in meshes:
            out += ["$bdyty", f" MAILx{r.number:7d}", "$model", f" {r.physics}", "$nodty"]
            for n, x, v in zip(r.nodes, r.x, r.v):
                out.append(f" NO2xx{n:7d}" + " " * 16 + f"X(1)={fmt(x[0])}  X(2)={fmt(x[1])}")
                out.append(" " * 29 + f"V(1)={fmt(v[0])}  V(2)={fmt(v[1])}")
            out += ["$$$$$$"] + sep
        out += [_END] if style == "pre" else [RULE, RULE]
        return "\n".join(out) + "\n"

    def write(self, path, style=None):
        with open(path, "w", newline="\n") as f:
            f.write(self.text(style))


def read_dof_file(path):
    """DOF.INI or DOF.OUT.n -> DofFile (RBDY2 and MAILx records in file order)."""
    cur = _Lines(path)
    d = DofFile(style=cur.style())
    while cur.more():
        ln, t = cur.next("keyword")
        if t.startswith("$steps"):
            d.step, d.time = _steps(cur, ln, t)
        elif t.startswith("$bdyty"):
            lm, model, num = _body_line(cur)
            if model == "RBDY2":
                cur.expect("$nodty", "$nodty")
                lx, tx = cur.next("X line")
                lv, tv = cur.next("V line")
                rec = DofRecord(model, num, _reals(cur, lx, tx, (35, 56, 77), "X"),
                                _reals(cur, lv, tv, (35, 56, 77), "V"))
            elif model == "MAILx":
                cur.expect("$model", "$model")
                _, tp = cur.next("physics line")
                nodes, xs, vs = [], [], []
                while True:
                    lk, tk = cur.peek()
                    if tk is None or tk.startswith("$$$$$$"):
                        break
                    cur.next("node")
                    if tk.startswith("$nodty"):
                        continue
                    if col(tk, 2, 6) != "NO2xx":
                        raise cur.err(lk, 2, f"expected a NO2xx node line, found {tk.strip()[:30]!r}")
                    nodes.append(parse_int(tk, 7, 13, cur.path, lk, "node number"))
                    xs.append(_reals(cur, lk, tk, (35, 56), "X"))
                    lv, tv = cur.next("V line")
                    vs.append(_reals(cur, lv, tv, (35, 56), "V"))
                rec = DofRecord(model, num, np.array(xs).reshape(-1, 2), np.array(vs).reshape(-1, 2),
                                nodes, col(tp, 2, 6))
            else:
                raise cur.err(lm, 2, f"body model {model!r}: RBDY2 or MAILx")
            cur.expect("$$$$$$", "end of body record '$$$$$$'")
            d.records.append(rec)
        elif t.startswith("$"):
            raise cur.err(ln, 1, f"unexpected keyword {t.strip()[:12]!r} (expected $steps or $bdyty)")
    return d


# --------------------------------------------------------------------------------------
# GPV.INI / GPV.OUT.n
# --------------------------------------------------------------------------------------

@dataclass
class GpvElement:
    """Gauss-point values of one element: ``rows`` as LMGC90 writes them (per Gauss
    point, small strain: a stress line (xx, yy, xy, zz) and a strain line (xx, yy,
    2xy, zz); internal J2 adds a line of internal values)."""
    kind: str
    number: int
    rows: list
    physics: str = "MECAx"


@dataclass
class GpvBody:
    model: str
    number: int
    elements: list = field(default_factory=list)


@dataclass
class GpvFile:
    step: int = 0
    time: float = 0.0
    bodies: list = field(default_factory=list)
    style: str = "out"

    def text(self, style=None):
        style = style or self.style
        out = _header("Gauss Point Values", style, "      ") + [
            steps_line(self.step, self.time, style), "" if style == "pre" else " ", RULE]
        for b in self.bodies:
            out += ["$bdyty", f" {b.model}{b.number:7d}"]
            for e in b.elements:
                out += ["$blmty", f" {e.kind}{e.number:7d}", "$model", f" {e.physics}"]
                out += ["".join(d14(x) for x in row) for row in e.rows]
            out.append("$$$$$$")
        out.append(_END if style == "pre" else RULE)
        return "\n".join(out) + "\n"

    def write(self, path, style=None):
        with open(path, "w", newline="\n") as f:
            f.write(self.text(style))


def read_gpv(path):
    """GPV.INI or GPV.OUT.n -> GpvFile."""
    cur = _Lines(path)
    g = GpvFile(style=cur.style())
    while cur.more():
        ln, t = cur.next("keyword")
        if t.startswith("$steps"):
            g.step, g.time = _steps(cur, ln, t)
        elif t.startswith("$bdyty"):
            _, model, num = _body_line(cur)
            body = GpvBody(model, num)
            while True:
                lk, tk = cur.next("$blmty or $$$$$$")
                if tk.startswith("$$$$$$"):
                    break
                if not tk.startswith("$blmty"):
                    raise cur.err(lk, 1, f"expected $blmty, found {tk.strip()[:30]!r}")
                le, te = cur.next("element line")
                cur.expect("$model", "$model")
                _, tp = cur.next("physics line")
                rows = []
                while True:
                    lr, tr = cur.peek()
                    if tr is None or tr.startswith("$"):
                        break
                    cur.next("values")
                    n = len(tr.rstrip()) // 14
                    rows.append(np.array([parse_real(tr, 14 * k + 1, 14 * k + 14, cur.path, lr,
                                                     f"value {k + 1}") for k in range(n)]))
                body.elements.append(GpvElement(col(te, 2, 6), parse_int(te, 7, 13, cur.path, le, "element"),
                                                rows, col(tp, 2, 6)))
            g.bodies.append(body)
        elif t.startswith("$"):
            raise cur.err(ln, 1, f"unexpected keyword {t.strip()[:12]!r} (expected $steps or $bdyty)")
    return g


# --------------------------------------------------------------------------------------
# Vloc_Rloc.INI / Vloc_Rloc.OUT.n
# --------------------------------------------------------------------------------------

_HEAD = " cdbdy  numbr  cdtac  numbr"
_ID = [("cdbdy", 2, 0), ("icdbdy", 9, 5), ("cdtac", 16, 0), ("icdtac", 23, 5)]
_AN = [("anbdy", 37, 0), ("ianbdy", 44, 5), ("antac", 51, 0), ("iantac", 58, 5)]


def _shift(fields, d):
    return [(n, c + d, w) for n, c, w in fields]


#: Column layout of the id line per interaction type: header line, fields
#: (attribute, first column, width; width 0 is a 5-character word, a name
#: starting with "'" is a constant label) and line width.
VLOC_LAYOUTS = {
    "default": (_HEAD + "  behav  anbdy  numbr  antac  numbr  sttus   iadj",
                _ID + [("behav", 30, 0)] + _AN + [("status", 65, 0), ("iadj", 72, 5)], 76),
    # ALpxx antagonist: the segment hit
    "CLALp": (_HEAD + "  behav  anbdy  numbr  antac  numbr  segmt  sttus   iadj",
              _ID + [("behav", 30, 0)] + _AN + [("anseg", 65, 5), ("status", 72, 0), ("iadj", 79, 5)], 83),
    "DKALp": (_HEAD + "  behav  anbdy  numbr  antac  numbr                sttus iadj ",
              _ID + [("behav", 30, 0)] + _AN + [("anseg", 65, 5), ("status", 79, 0), ("iadj", 84, 6)], 89),
    # polygons: candidate vertex, antagonist segment
    "PLPLx": (_HEAD + "  vertx  numbr  behav  anbdy  numbr  antac  numbr  segmt  numbr",
              _ID + [("'CDVER", 30, 0), ("cdver", 37, 5), ("behav", 44, 0)] + _shift(_AN, 14)
              + [("'ANSEG", 79, 0), ("anseg", 86, 5), ("status", 93, 0), ("iadj", 98, 6)], 103),
    "PLJCx": (_HEAD + "  vertx  numbr  behav  anbdy  numbr  antac  numbr                sttus iadj ",
              _ID + [("'CDVER", 30, 0), ("cdver", 37, 5), ("behav", 44, 0)] + _shift(_AN, 14)
              + [("status", 93, 0), ("iadj", 98, 6)], 103),
    # polygon vertex against an ALpxx segment (the layout of modules/io/read_vloc_rloc.f90)
    "PLALp": (_HEAD + "  vertx  numbr  behav  anbdy  numbr  antac  numbr                sttus iadj ",
              _ID + [("'CDVER", 30, 0), ("cdver", 37, 5), ("behav", 44, 0)] + _shift(_AN, 14)
              + [("anseg", 79, 5), ("status", 93, 0), ("iadj", 98, 6)], 103),
    "DKPLx": (_HEAD + "  behav  anbdy  numbr  antac  numbr  vertx  numbr                sttus iadj ",
              _ID + [("behav", 30, 0)] + _AN + [("'CDVER", 65, 0), ("cdver", 72, 5),
                                                ("status", 93, 0), ("iadj", 98, 6)], 103),
}
#: Interaction types with the default layout.
_DEFAULT_TYPES = ("DKDKx", "DKJCx", "DKKDx", "CLJCx")


def _layout(inter):
    if inter in VLOC_LAYOUTS:
        return VLOC_LAYOUTS[inter]
    if inter in _DEFAULT_TYPES:
        return VLOC_LAYOUTS["default"]
    return None


@dataclass
class ContactRecord:
    """One $icdan record. Reactions ``rloc`` are forces (impulse / H), as LMGC90
    writes them (rlt/H, rln/H, rls/H); ``vloc`` = (vlt, vln, vls). Contactor
    numbers (icdtac, iantac) follow LMGC90's numbering within the body (see
    fracas_tools.mailx: each CLxxx point is one contactor, a polyline is one);
    ``anseg`` is the ALpxx segment (CLALp, DKALp) or polygon side (PLPLx),
    ``cdver`` the polygon vertex (PLPLx, PLJCx, DKPLx)."""
    inter: str
    number: int
    cdbdy: str
    icdbdy: int
    cdtac: str
    icdtac: int
    behav: str
    anbdy: str
    ianbdy: int
    antac: str
    iantac: int
    status: str
    iadj: int
    cdver: int = None
    anseg: int = None
    rloc: np.ndarray = field(default_factory=lambda: np.zeros(3))
    vloc: np.ndarray = field(default_factory=lambda: np.zeros(3))
    gap: float = 0.0
    normal: np.ndarray = None
    coor: np.ndarray = None
    internal_names: list = None
    internals: np.ndarray = None

    @property
    def rlt(self):
        return self.rloc[0]

    @property
    def rln(self):
        return self.rloc[1]

    @property
    def vlt(self):
        return self.vloc[0]

    @property
    def vln(self):
        return self.vloc[1]

    def internal(self, name):
        """An internal value by the name of the comment line ('beta', 'saut_de_un' ...)."""
        return self.internals[self.internal_names.index(name)]

    def lines(self):
        header, fields, width = _layout(self.inter)
        s = [" "] * width
        for name, c, w in fields:
            if name.startswith("'"):
                txt = name[1:]
            elif w == 0:
                txt = getattr(self, name).ljust(5)[:5]
            else:
                txt = f"{getattr(self, name) or 0:{w}d}"
            s[c - 1:c - 1 + len(txt)] = txt
        rls = "rls =" if self.inter == "DKKDx" else "rls/H"
        pad = " " * 29
        out = [f"$icdan  {self.inter}{self.number:9d}", header, "".join(s),
               pad + f"rlt/H{d14(self.rloc[0])}  rln/H{d14(self.rloc[1])}  {rls}{d14(self.rloc[2])}",
               pad + f"vlt ={d14(self.vloc[0])}  vln ={d14(self.vloc[1])}  vls ={d14(self.vloc[2])}",
               pad + f"gapTT{d14(self.gap)}"]
        if self.normal is not None:
            out.append(pad + "  ".join(f"n({k + 1})={d14(self.normal[k])}" for k in range(3)))
        if self.coor is not None:
            out.append(pad + "  ".join(f"coo{k + 1}={d14(self.coor[k])}" for k in range(3)))
        if self.internal_names is not None:
            out.append(("#" + "".join(n.ljust(15) for n in self.internal_names)).ljust(285))
            vals = list(self.internals) if self.internals is not None else []
            for k in range(0, len(vals), 6):
                out.append("".join(" " + d14(x) for x in vals[k:k + 6]))
        out.append(" ")
        return out


@dataclass
class VlocRloc:
    step: int = 0
    time: float = 0.0
    records: list = field(default_factory=list)
    style: str = "out"

    def text(self, style=None):
        style = style or self.style
        out = _header("Vloc_Rloc", style, "      ") + [steps_line(self.step, self.time, style),
                                                        "" if style == "pre" else " ", RULE]
        for r in self.records:
            out += r.lines()
        if style == "pre":
            out.append(_END)
        return "\n".join(out) + "\n"

    def write(self, path, style=None):
        with open(path, "w", newline="\n") as f:
            f.write(self.text(style))


def _read_contact(cur, ln, t):
    inter = col(t, 9, 13)
    lay = _layout(inter)
    if lay is None:
        known = sorted(set(VLOC_LAYOUTS) - {"default"} | set(_DEFAULT_TYPES))
        raise cur.err(ln, 9, f"unknown interaction type {inter!r} (known: {', '.join(known)})")
    number = parse_int(t, 14, max(22, len(t)), cur.path, ln, "interaction number")
    lh, th = cur.next("column header line")
    if col(th, 2, 6) != "cdbdy":
        raise cur.err(lh, 2, "expected the column header line (' cdbdy  numbr ...')")
    li, ti = cur.next("id line")
    vals = {}
    for name, c, w in lay[1]:
        if name.startswith("'"):
            continue
        if w == 0:
            vals[name] = col(ti, c, c + 4)
        else:
            vals[name] = parse_int(ti, c, c + w - 1, cur.path, li, name)
    r = ContactRecord(inter=inter, number=number, **vals)
    lr, tr = cur.next("rlt/H line")
    r.rloc = _reals(cur, lr, tr, (35, 56, 77), "rloc")
    lv, tv = cur.next("vlt line")
    r.vloc = _reals(cur, lv, tv, (35, 56, 77), "vloc")
    lg, tg = cur.next("gapTT line")
    if col(tg, 30, 34) != "gapTT":
        raise cur.err(lg, 30, "expected the 'gapTT' line")
    r.gap = parse_real(tg, 35, 48, cur.path, lg, "gapTT")
    while True:
        lk, tk = cur.peek()
        if tk is None or tk.startswith("$"):
            break
        cur.next("contact line")
        label = col(tk, 30, 34)
        if label == "n(1)=":
            r.normal = _reals(cur, lk, tk, (35, 56, 77), "n")
        elif label == "coo1=":
            r.coor = _reals(cur, lk, tk, (35, 56, 77), "coo")
        elif tk.startswith("#"):
            r.internal_names = tk[1:].split()
            r.internals = np.zeros(0)
        else:
            if r.internal_names is None:
                raise cur.err(lk, 1, "internal values without their '#' comment line of names")
            n = len(tk.rstrip()) // 15
            more = [parse_real(tk, 15 * k + 1, 15 * k + 15, cur.path, lk, f"internal {k + 1}")
                    for k in range(n)]
            r.internals = np.concatenate([r.internals, more])
    return r


def read_vloc_rloc(path):
    """Vloc_Rloc.INI or Vloc_Rloc.OUT.n -> VlocRloc (records in file order)."""
    cur = _Lines(path)
    v = VlocRloc(style=cur.style())
    while cur.more():
        ln, t = cur.next("keyword")
        if t.startswith("$steps"):
            v.step, v.time = _steps(cur, ln, t)
        elif t.startswith("$icdan"):
            v.records.append(_read_contact(cur, ln, t))
        elif t.startswith("$"):
            raise cur.err(ln, 1, f"unexpected keyword {t.strip()[:12]!r} (expected $steps or $icdan)")
    return v
