"""Fixed-column helpers for LMGC90 DATBOX files.

DATBOX records are Fortran fixed-column records: a value is identified by the
columns it occupies, not by the label written in front of it. Columns are
counted from 1 as in the format descriptions of doc/tools.md and
../shared/reference/lmgc90.md §2.
"""

import math
import re

__all__ = ["DatboxError", "e14", "d14", "field", "parse_real", "parse_int"]


class DatboxError(ValueError):
    """An error in a DATBOX file, located as file:line:column."""

    def __init__(self, path, line, col, msg):
        self.path, self.line, self.col, self.msg = str(path), line, col, msg
        super().__init__(f"{path}:{line}:{col}: {msg}")


def e14(x, letter="e"):
    """A real as Fortran-like E14.7 with a leading digit (as pylmgc90 writes it):
    ' 1.2345678e-02' (positive numbers start with a blank). letter: 'e' or 'E'."""
    x = float(x)
    if not math.isfinite(x):
        raise ValueError(f"cannot write a non-finite number ({x}) in a DATBOX file")
    s = "%14.7e" % x
    if letter != "e":
        s = s.replace("e", letter)
    return s


def d14(x):
    """A real as Fortran D14.7 (' 0.1234567D+01'), the format of LMGC90's own
    writers, used in the $steps header lines."""
    x = float(x)
    if not math.isfinite(x):
        raise ValueError(f"cannot write a non-finite number ({x}) in a DATBOX file")
    sign = "-" if math.copysign(1.0, x) < 0 else " "     # Fortran keeps the sign of -0.0
    if x == 0.0:
        return f"{sign}0.0000000D+00"
    m = "%.6E" % abs(x)           # d.ddddddE+xx, 7 significant digits
    digits = m[0] + m[2:8]
    expo = int(m[m.index("E") + 1:]) + 1
    esign = "+" if expo >= 0 else "-"
    if abs(expo) >= 100:          # Fortran drops the letter: 0.1234567-100
        return f"{sign}0.{digits}{esign}{abs(expo):03d}"
    return f"{sign}0.{digits}D{esign}{abs(expo):02d}"


def field(line, c1, c2):
    """Columns c1..c2 (1-based, inclusive) of a line, blank-padded."""
    return line[c1 - 1:c2].ljust(c2 - c1 + 1)


_BARE_EXPONENT = re.compile(r"^([+-]?(?:\d+\.?\d*|\.\d+))([+-]\d+)$")


def parse_real(line, c1, c2, path="?", lineno=0, what="value", blank_ok=True):
    """Read a real from columns c1..c2 like a Fortran D/E edit descriptor:
    blanks read as 0, 'D' or 'd' exponents accepted."""
    s = field(line, c1, c2).strip()
    if not s:
        if blank_ok:
            return 0.0
        raise DatboxError(path, lineno, c1, f"{what}: expected a number in columns {c1}-{c2}")
    t = s.replace(" ", "").replace("D", "E").replace("d", "E")
    m = _BARE_EXPONENT.match(t)          # Fortran's 0.1234567-100 (no exponent letter)
    if m:
        t = m.group(1) + "E" + m.group(2)
    try:
        x = float(t)
    except ValueError:
        x = None
    if x is None or not math.isfinite(x):
        raise DatboxError(path, lineno, c1,
                          f"{what}: cannot read {s!r} (columns {c1}-{c2}) as a number")
    return x


def parse_int(line, c1, c2, path="?", lineno=0, what="integer", blank_ok=False):
    """Read an integer from columns c1..c2 (Fortran I format)."""
    s = field(line, c1, c2).strip()
    if not s:
        if blank_ok:
            return 0
        raise DatboxError(path, lineno, c1, f"{what}: expected an integer in columns {c1}-{c2}")
    try:
        return int(s)
    except ValueError:
        raise DatboxError(path, lineno, c1,
                          f"{what}: cannot read {s!r} (columns {c1}-{c2}) as an integer") from None
