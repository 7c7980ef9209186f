"""Named checks that print one line each (quantity, ours, reference, error, tolerance,
PASS/FAIL), used by every validation, hard-case and regression check script.

    from fracas_tools.checks import Checker
    ck = Checker("bouncing_disk")
    ck.close("apex 1", ours, ref, tol)        # |ours - ref| <= tol (absolute)
    ck.rel("R floor", ours, ref, rtol)        # |ours - ref| <= rtol |ref|
    ck.at_most(...); ck.at_least(...); ck.true(name, ok); ck.info(name, value)
    sys.exit(ck.finish())                     # prints the summary, 0 if all passed
"""

import numpy as np

__all__ = ["Checker"]


class Checker:
    """Named checks, one printed line each; finish() prints the summary and returns
    the exit status (0: all passed)."""

    def __init__(self, case):
        self.case = case
        self.rows = []
        print(f"== {case}")
        print(f"{'quantity':<52} {'ours':>14} {'reference':>14} {'error':>10} {'tolerance':>10}  result")

    @staticmethod
    def _fmt(v):
        if isinstance(v, (float, int, np.floating, np.integer)):
            return f"{float(v):14.7g}"
        return f"{str(v):>14}"

    def _row(self, name, ours, ref, err, tol, ok, note=""):
        self.rows.append(dict(name=name, ours=ours, ref=ref, err=err, tol=tol, ok=ok, note=note))
        line = (f"{name:<52} {self._fmt(ours)} {self._fmt(ref)} {err:10.3e} {tol:10.3e}  "
                f"{'PASS' if ok else 'FAIL'}")
        if note:
            line += f"  ({note})"
        print(line, flush=True)
        return ok

    def close(self, name, ours, ref, tol, note=""):
        """|ours - ref| <= tol (absolute)."""
        ours, ref = float(ours), float(ref)
        err = abs(ours - ref)
        return self._row(name, ours, ref, err, tol, bool(err <= tol), note)

    def rel(self, name, ours, ref, rtol, note=""):
        """|ours - ref| <= rtol |ref| (the error column is relative)."""
        ours, ref = float(ours), float(ref)
        err = abs(ours - ref) / abs(ref)
        return self._row(name, ours, ref, err, rtol, bool(err <= rtol), note)

    def at_most(self, name, ours, bound, note=""):
        """ours <= bound."""
        ours = float(ours)
        return self._row(name, ours, "<= bound", ours, float(bound), bool(ours <= bound), note)

    def at_least(self, name, ours, bound, note=""):
        """ours >= bound."""
        ours = float(ours)
        return self._row(name, ours, ">= bound", ours, float(bound), bool(ours >= bound), note)

    def true(self, name, ok, ours="", ref="", note=""):
        """ok must hold (ours and ref: what to print)."""
        return self._row(name, ours if ours != "" else str(bool(ok)), ref or "True", 0.0, 0.0, bool(ok), note)

    def info(self, name, value, note=""):
        """A recorded (not asserted) figure, e.g. sweeps or wall time."""
        print(f"{name:<52} {self._fmt(value)} {'(info)':>14}" + (f"  ({note})" if note else ""),
              flush=True)

    def finish(self):
        nfail = sum(1 for r in self.rows if not r["ok"])
        print(f"== {self.case}: {len(self.rows) - nfail}/{len(self.rows)} checks passed"
              + (f", {nfail} FAILED" if nfail else ""))
        return 1 if nfail else 0
