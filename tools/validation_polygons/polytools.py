"""Shared helpers of the polygon and masonry cases (test_cases/validation/<poly cases>,
test_cases/hard/*, test_cases/examples/{masonry_wall,arch}): reading fracas.h5 into
numpy, named checks printing one line each, small geometry helpers.

    sys.path.insert(0, str(repo / "tools" / "validation_polygons"))
    import polytools as pt
    res = pt.Results(run_dir)                # run_dir/OUTBOX/fracas.h5
    F = res.force_on(isnap, body)            # (2,) resultant contact force on a body
    ck = pt.Checker("block_incline")
    ck.close(name, ours, ref, tol); ck.rel(...); ck.at_most(...); ck.at_least(...)
    sys.exit(ck.finish())

Only numpy and h5py (the system /usr/bin/python3). Body numbers are 1-based serial
numbers (BODIES.DAT order), as in the results file.
"""

import math
import os
import sys
from pathlib import Path

import numpy as np

__all__ = ["repo_root", "add_tools_path", "run_dir_from_argv", "Results", "Checker",
           "rot", "unit", "rect", "fmt_g"]


def repo_root():
    """The repository root (two levels above this file)."""
    return Path(__file__).resolve().parents[2]


def add_tools_path():
    """Make ``import fracas_tools`` work."""
    p = str(repo_root() / "tools")
    if p not in sys.path:
        sys.path.insert(0, p)


def run_dir_from_argv(default):
    """The run directory (holding OUTBOX/fracas.h5): argv[1] or ``default``."""
    return Path(sys.argv[1]) if len(sys.argv) > 1 else Path(default)


def rot(a):
    """2x2 rotation matrix of angle a (rad, counter-clockwise)."""
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s], [s, c]])


def unit(a):
    """Unit vector at angle a."""
    return np.array([math.cos(a), math.sin(a)])


def rect(w, h, cx=0.0, cy=0.0):
    """Counter-clockwise rectangle of width w, height h centred at (cx, cy)."""
    return np.array([[cx - 0.5 * w, cy - 0.5 * h], [cx + 0.5 * w, cy - 0.5 * h],
                     [cx + 0.5 * w, cy + 0.5 * h], [cx - 0.5 * w, cy + 0.5 * h]])


def fmt_g(v, digits=6):
    return f"{v:.{digits}g}"


class Results:
    """One fracas.h5 read into numpy arrays.

    Attributes: h, theta, complete, series (dict column -> array), mass, inertia,
    radius, ref (nb, 3); per snapshot: step, time (nsnap,), X, V (nsnap, nb, 3), and
    (with contacts=True) contacts: list of dicts of arrays cd, an, rt, rn, normal
    (nc, 2), point (nc, 2), gap, status, inter."""

    def __init__(self, run_dir, contacts=True, snapshots=True):
        import h5py
        path = Path(run_dir)
        if path.is_dir():
            path = path / "OUTBOX" / "fracas.h5"
        if not path.exists():
            raise SystemExit(f"no results file {path}: run the case first")
        self.path = path
        os.environ.setdefault("HDF5_USE_FILE_LOCKING", "FALSE")
        with h5py.File(path, "r") as f:
            self.complete = int(f.attrs["complete"])
            self.h = float(f.attrs["time_step"])
            self.theta = float(f.attrs["theta"])
            s = f["series"]
            cols = {k: s[k][:] for k in s}
            n = min(len(v) for v in cols.values()) if cols else 0
            self.series = {k: v[:n] for k, v in cols.items()}
            b = f["bodies"]
            self.mass = b["mass"][:]
            self.inertia = b["inertia"][:]
            self.radius = b["radius"][:]
            self.ref = b["reference"][:]
            self.status_names = list(f["help/status"].asstr()[:])
            self.inter_names = list(f["help/inter"].asstr()[:])
            names = sorted(f["snapshots"]) if snapshots else []
            nb = len(self.mass)
            self.step = np.zeros(len(names), dtype=int)
            self.time = np.zeros(len(names))
            self.X = np.zeros((len(names), nb, 3))
            self.V = np.zeros((len(names), nb, 3))
            for i, name in enumerate(names):
                g = f["snapshots"][name]
                self.step[i] = int(g.attrs["step"])
                self.time[i] = float(g.attrs["time"])
                g["bodies/X"].read_direct(self.X[i])
                g["bodies/V"].read_direct(self.V[i])
        self.contacts = _Contacts(path, names) if contacts else []
        if self.complete != 1:
            print(f"warning: {path} is not marked complete (unfinished run)")

    @property
    def position(self):
        """(nsnap, nb, 3) absolute x, y, angle."""
        return self.ref[None, :, :] + self.X

    def global_reactions(self, isnap):
        """(nc, 2) global reaction forces R = rt t + rn n (acting on the candidate)."""
        c = self.contacts[isnap]
        n = c["normal"]
        t = np.column_stack((n[:, 1], -n[:, 0]))
        return c["rt"][:, None] * t + c["rn"][:, None] * n

    def force_on(self, isnap, body, others=None):
        """Resultant contact force (2,) on ``body`` in snapshot isnap, from all its
        contacts or only those with the bodies in ``others``."""
        c = self.contacts[isnap]
        R = self.global_reactions(isnap)
        cd = c["cd"] == body
        an = c["an"] == body
        if others is not None:
            o = np.asarray(list(others))
            cd &= np.isin(c["an"], o)
            an &= np.isin(c["cd"], o)
        return R[cd].sum(axis=0) - R[an].sum(axis=0)

    def pair_mask(self, isnap, a, b):
        c = self.contacts[isnap]
        return ((c["cd"] == a) & (c["an"] == b)) | ((c["cd"] == b) & (c["an"] == a))

    def normal_force_between(self, isnap, a, b):
        """Sum of rn over the contacts between bodies a and b."""
        c = self.contacts[isnap]
        return float(np.sum(c["rn"][self.pair_mask(isnap, a, b)]))


class _Contacts:
    """Lazy list of the snapshots' contacts (read on first access, then cached):
    contacts[i] is a dict of arrays cd, an, rt, rn, normal (nc, 2), point (nc, 2),
    gap, status, inter."""

    def __init__(self, path, names):
        self.path, self.names, self.cache = path, names, {}

    def __len__(self):
        return len(self.names)

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[k] for k in range(*i.indices(len(self)))]
        i = range(len(self.names))[i]
        if i not in self.cache:
            import h5py
            with h5py.File(self.path, "r") as f:
                c = f["snapshots"][self.names[i]]["contacts"]
                r = c["reaction"][:].reshape(-1, 2)
                self.cache[i] = {
                    "cd": c["cd_body"][:], "an": c["an_body"][:],
                    "rt": r[:, 0], "rn": r[:, 1],
                    "normal": c["normal"][:].reshape(-1, 2),
                    "point": c["point"][:].reshape(-1, 2),
                    "gap": c["gap"][:], "status": c["status"][:],
                    "inter": c["inter"][:]}
        return self.cache[i]

    def __iter__(self):
        return (self[i] for i in range(len(self)))


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

    def true(self, name, ok, ours="", note=""):
        return self._row(name, ours if ours != "" else str(bool(ok)), "True", 0.0, 0.0, bool(ok), note)

    def info(self, name, value, note=""):
        """A recorded (not asserted) figure, e.g. sweeps or wall time."""
        print(f"{name:<52} {self._fmt(value)} {'(info)':>14}" + (f"  ({note})" if note else ""),
              flush=True)

    def finish(self):
        nfail = sum(1 for r in self.rows if not r["ok"])
        print(f"== {self.case}: {len(self.rows) - nfail}/{len(self.rows)} checks passed"
              + (f", {nfail} FAILED" if nfail else ""))
        return 1 if nfail else 0


# --------------------------------------------------------------------------------------
# deck-precision helpers
# --------------------------------------------------------------------------------------

def r8(x):
    """x as the DATBOX files hold it (8 significant digits, %.7E)."""
    return float(f"{x:.7E}")


def snap_on_line(P, d, n, offset_n, start, search=1.0e-3, samples=200001):
    """A body centre P + s d + offset_n n with s in [start, start + search] chosen so
    that, once rounded to the DATBOX's 8 significant digits, its distance to the line
    (P, d) is still offset_n to round-off: only the normal component of the rounding
    error opens or closes a gap, and a 1-D search along d finds a point where it is
    below 1e-12 m. Returns (rounded centre (2,), normal error, s)."""
    P, d, n = (np.asarray(v, dtype=float) for v in (P, d, n))
    s = start + np.linspace(0.0, search, samples)
    c = P[None, :] + s[:, None] * d[None, :] + offset_n * n[None, :]
    cr = np.vectorize(r8)(c)
    err = np.abs((cr - c) @ n)
    i = int(np.argmin(err))
    return cr[i], float(err[i]), float(s[i])
