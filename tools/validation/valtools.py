"""Shared helpers of the validation cases (test_cases/validation/*/check.py, gen.py).

    from valtools import Results, Checker, repo_root
    res = Results("path/to/run_dir")          # reads run_dir/OUTBOX/fracas.h5
    X, V = res.X, res.V                       # (nsnap, nb, 3) displacement, velocity
    ck = Checker("bouncing_disk")
    ck.close("apex 1", ours, ref, tol)        # |ours - ref| <= tol  (absolute)
    ck.rel("R floor", ours, ref, rtol)        # |ours - ref| <= rtol |ref|
    ck.true("energy decreasing", ok, detail)
    sys.exit(ck.finish())                     # prints the summary, 0 if all PASS

Every check prints one line: name, ours, reference, error, tolerance, PASS/FAIL.
Only h5py and numpy are needed (the system /usr/bin/python3).
"""

import os
import sys
from pathlib import Path

import numpy as np

__all__ = ["repo_root", "add_tools_path", "Results", "Checker", "run_dir_from_argv",
           "chain_gauss_seidel_rate"]


def repo_root():
    """The repository root (two levels above this file)."""
    return Path(__file__).resolve().parents[2]


def add_tools_path():
    """Make ``import fracas_tools`` work (tools/ on sys.path)."""
    p = str(repo_root() / "tools")
    if p not in sys.path:
        sys.path.insert(0, p)


def run_dir_from_argv(default):
    """The run directory (holding OUTBOX/fracas.h5): argv[1] or ``default``."""
    return Path(sys.argv[1]) if len(sys.argv) > 1 else Path(default)


def chain_gauss_seidel_rate(masses, grounded=False):
    """Spectral radius of Gauss-Seidel on the Delassus matrix of a frictionless chain
    of bodies in a line (contact k between body k and k+1, normals along the line).
    grounded=True adds a first contact between a fixed support and body 0 (a column
    on the floor). The NLGS error left when a sweep changes the reactions by a
    relative tol is about tol / (1 - rho)."""
    m = np.asarray(masses, dtype=float)
    if grounded:
        inv = np.concatenate([[0.0], 1.0 / m])          # the support has no mobility
    else:
        inv = 1.0 / m
    nc = len(inv) - 1
    w = np.zeros((nc, nc))
    for k in range(nc):
        w[k, k] = inv[k] + inv[k + 1]
        if k > 0:
            w[k, k - 1] = w[k - 1, k] = -inv[k]
    lower = np.tril(w)
    upper = np.triu(w, 1)
    return float(max(abs(np.linalg.eigvals(-np.linalg.solve(lower, upper)))))


class Results:
    """Everything of one fracas.h5 the checks need, read once into numpy arrays.

    Attributes: h (time step), theta, series (dict column -> array), mass, inertia,
    radius, ref (nb, 3); per snapshot: step, time (nsnap,), X, V (nsnap, nb, 3) and
    contacts (list of dicts with cd, an, rn, rt, gap, status arrays)."""

    def __init__(self, run_dir, contacts=True):
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
            names = sorted(f["snapshots"])
            nb = len(self.mass)
            self.step = np.zeros(len(names), dtype=int)
            self.time = np.zeros(len(names))
            self.X = np.zeros((len(names), nb, 3))
            self.V = np.zeros((len(names), nb, 3))
            self.contacts = []
            for i, name in enumerate(names):
                g = f["snapshots"][name]
                self.step[i] = int(g.attrs["step"])
                self.time[i] = float(g.attrs["time"])
                self.X[i] = g["bodies/X"][:]
                self.V[i] = g["bodies/V"][:]
                if contacts:
                    c = g["contacts"]
                    r = c["reaction"][:].reshape(-1, 2)
                    self.contacts.append({
                        "cd": c["cd_body"][:], "an": c["an_body"][:],
                        "rt": r[:, 0], "rn": r[:, 1], "gap": c["gap"][:],
                        "status": c["status"][:]})
        if self.complete != 1:
            print(f"warning: {path} is not marked complete (unfinished run)")

    @property
    def position(self):
        """(nsnap, nb, 3) absolute x, y, angle."""
        return self.ref[None, :, :] + self.X

    def reaction_between(self, isnap, a, b):
        """Normal force rn between bodies a and b (1-based serial numbers) in
        snapshot isnap, 0.0 when they have no contact; sums several contacts."""
        c = self.contacts[isnap]
        m = ((c["cd"] == a) & (c["an"] == b)) | ((c["cd"] == b) & (c["an"] == a))
        return float(np.sum(c["rn"][m]))


class Checker:
    """Collects named checks and prints one line per quantity."""

    def __init__(self, case):
        self.case = case
        self.rows = []
        print(f"== {case}")
        print(f"{'quantity':<44} {'ours':>15} {'reference':>15} {'error':>10} {'tolerance':>10}  result")

    def _row(self, name, ours, ref, err, tol, ok, note=""):
        self.rows.append((name, ours, ref, err, tol, ok))
        fmt = lambda v: f"{v:15.8g}" if isinstance(v, (float, int, np.floating, np.integer)) else f"{str(v):>15}"
        line = (f"{name:<44} {fmt(ours)} {fmt(ref)} {err:10.3e} {tol:10.3e}  "
                f"{'PASS' if ok else 'FAIL'}")
        if note:
            line += f"  ({note})"
        print(line)
        return ok

    def close(self, name, ours, ref, tol, note=""):
        """Absolute check |ours - ref| <= tol."""
        ours, ref = float(ours), float(ref)
        err = abs(ours - ref)
        return self._row(name, ours, ref, err, tol, bool(err <= tol), note)

    def rel(self, name, ours, ref, rtol, note=""):
        """Relative check |ours - ref| <= rtol |ref| (error printed relative)."""
        ours, ref = float(ours), float(ref)
        err = abs(ours - ref) / abs(ref)
        return self._row(name, ours, ref, err, rtol, bool(err <= rtol), note)

    def at_most(self, name, ours, bound, note=""):
        """ours <= bound (the error column shows ours, the tolerance the bound)."""
        ours = float(ours)
        return self._row(name, ours, "<= bound", ours, float(bound), bool(ours <= bound), note)

    def true(self, name, ok, ours="", ref="", note=""):
        return self._row(name, ours if ours != "" else str(bool(ok)), ref or "True", 0.0, 0.0,
                         bool(ok), note)

    def finish(self):
        nfail = sum(1 for r in self.rows if not r[5])
        print(f"== {self.case}: {len(self.rows) - nfail}/{len(self.rows)} checks passed"
              + (f", {nfail} FAILED" if nfail else ""))
        return 1 if nfail else 0
