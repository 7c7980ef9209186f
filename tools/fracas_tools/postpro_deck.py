"""DATBOX/POSTPRO.DAT: LMGC90's post-processing commands.

The file is a list of commands: a name line ('SOLVER INFORMATIONS', 'BODY
TRACKING', 'NEW MECAx SETS', 'Dep EVOLUTION', ...), a 'STEP n' line (every n steps),
then rows of integers (the command's arguments), and 'END'. Fracas carries out
SOLVER INFORMATIONS, BODY TRACKING, TORQUE EVOLUTION, DISSIPATED ENERGY and, for
meshed bodies, NEW MECAx SETS with Dep EVOLUTION and Fint EVOLUTION (the Dep_/Fint_
files of each set); the file is kept so that a deck goes back to LMGC90 unchanged.

    pp = PostPro()
    pp.add("NEW MECAx SETS", rows=mecax_set_rows([[(2, [3, 6, 9])], [(1, [3, 6, 9])]]))
    pp.add("SOLVER INFORMATIONS")
    pp.add("Dep EVOLUTION")
    text = pp.text()          # 'END' is appended
"""

from dataclasses import dataclass, field

from .fortran_io import DatboxError

__all__ = ["PostProCommand", "PostPro", "read_postpro", "mecax_set_rows", "parse_mecax_sets",
           "body_list_rows"]


@dataclass
class PostProCommand:
    name: str
    step: int = 1
    rows: list = field(default_factory=list)     # tuples of ints

    def lines(self):
        out = [self.name.ljust(30), f"STEP {self.step}".ljust(30)]
        for row in self.rows:
            # one integer in I7, the next ones in I8; padded as pylmgc90 pads them
            s = f"{row[0]:7d}" + "".join(f"{x:8d}" for x in row[1:])
            out.append(s.ljust(30 + 4 * len(row)))
        return out

    def mecax_sets(self):
        """For 'NEW MECAx SETS': [[(body, [nodes]), ...] per set]."""
        return parse_mecax_sets(self.rows)

    def bodies(self):
        """For 'BODY TRACKING' / 'TORQUE EVOLUTION': the body numbers."""
        return [r[0] for r in self.rows[1:1 + self.rows[0][0]]] if self.rows else []


def mecax_set_rows(sets):
    """Rows of 'NEW MECAx SETS' from sets = [[(MAILx body, [nodes]), ...], ...]:
    number of sets; per set the number of (body, nodes) groups; per group
    'body n' then the n nodes."""
    rows = [(len(sets),)]
    for groups in sets:
        rows.append((len(groups),))
        for body, nodes in groups:
            nodes = list(nodes)
            rows.append((int(body), len(nodes)))
            rows += [(int(n),) for n in nodes]
    return rows


def parse_mecax_sets(rows):
    sets, k = [], 1
    for _ in range(rows[0][0]):
        groups = []
        ngroups = rows[k][0]
        k += 1
        for _ in range(ngroups):
            body, n = rows[k]
            groups.append((body, [r[0] for r in rows[k + 1:k + 1 + n]]))
            k += 1 + n
        sets.append(groups)
    return sets


def body_list_rows(bodies):
    """Rows of 'BODY TRACKING' / 'TORQUE EVOLUTION' (RBDY2 body numbers)."""
    return [(len(bodies),)] + [(int(b),) for b in bodies]


class PostPro:
    """The commands of POSTPRO.DAT in order ('END' is implicit)."""

    def __init__(self, commands=()):
        self.commands = list(commands)

    def add(self, name, step=1, rows=()):
        if not name or len(name) > 30:
            raise ValueError(f"post-processing command {name!r}: 1-30 characters")
        c = PostProCommand(name, int(step), [tuple(int(x) for x in r) for r in rows])
        self.commands.append(c)
        return c

    def get(self, name):
        for c in self.commands:
            if c.name == name:
                return c
        return None

    def text(self):
        out = []
        for c in self.commands:
            out += c.lines()
        out.append("END".ljust(30))
        return "\n".join(out) + "\n"

    def __repr__(self):
        return "PostPro(" + ", ".join(c.name for c in self.commands) + ")"


def read_postpro(path):
    """POSTPRO.DAT -> PostPro."""
    pp = PostPro()
    with open(path, "r", encoding="latin-1") as f:
        lines = [l.rstrip("\n").rstrip("\r") for l in f]
    cur = None
    for i, t in enumerate(lines, start=1):
        if t.startswith(("!", "#")):
            continue
        s = t.split(":", 1)[0].strip()       # LMGC90's decks: a comment after ':' (column 31)
        if not s:
            continue
        parts = s.split()
        if all(p.lstrip("-").isdigit() for p in parts):
            if cur is None:
                raise DatboxError(path, i, 1, "integers before any command")
            cur.rows.append(tuple(int(p) for p in parts))
        elif parts[0] == "STEP":
            if cur is None or len(parts) != 2 or not parts[1].isdigit():
                raise DatboxError(path, i, 1, "expected 'STEP n' after a command name")
            cur.step = int(parts[1])
        elif s == "END":
            break
        else:
            cur = PostProCommand(s)
            pp.commands.append(cur)
    return pp
