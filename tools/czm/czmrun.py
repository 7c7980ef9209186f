"""Read a fracas.h5 of a cohesive run into numpy arrays (test_cases/validation/czm_*).

    run = CzmRun("path/to/run_dir")      # or the .h5 file
    run.series["damage_dissipated"]      # one value per step
    run.step, run.time                   # (ns,) per snapshot
    run.X, run.V                         # (ns, nb, 3)
    pair = run.pair(cd, an)              # contacts between bodies cd and an, per snapshot:
    pair.rn, pair.rt, pair.gap, pair.L, pair.ut, pair.un, pair.beta, pair.tpsini,
    pair.broken, pair.status             # (ns, npts) arrays (npts = points of the pair)

Snapshots are expected at every step (output_hdf5_every 1) and the pair is expected to
keep the same number of contact points in all snapshots (the glued faces here).
"""

import os
from pathlib import Path

import numpy as np

__all__ = ["CzmRun", "Pair"]


class Pair:
    """Per-snapshot arrays (ns, npts) of the contact points between two bodies."""

    def __init__(self, **kw):
        self.__dict__.update(kw)

    def total(self, name):
        """Sum over the points of the pair (ns,)."""
        return getattr(self, name).sum(axis=1)

    def mean(self, name):
        return getattr(self, name).mean(axis=1)


class CzmRun:
    def __init__(self, run_dir, bodies=True, full=False):
        """bodies: read X and V of every snapshot; full: also the contact velocities,
        gaps and normals (the pair arrays vt, vn, gap are 0 otherwise)."""
        import h5py
        path = Path(run_dir)
        if path.is_dir():
            path = path / "OUTBOX" / "fracas.h5"
        if not path.exists():
            raise SystemExit(f"no results file {path}: run the case first")
        os.environ.setdefault("HDF5_USE_FILE_LOCKING", "FALSE")
        self.path = path
        with h5py.File(path, "r") as f:
            self.complete = int(f.attrs["complete"])
            self.h = float(f.attrs["time_step"])
            self.theta = float(f.attrs["theta"])
            s = f["series"]
            cols = {k: s[k][:] for k in s}
            n = min(len(v) for v in cols.values())
            self.series = {k: v[:n] for k, v in cols.items()}
            self.mass = f["bodies/mass"][:]
            self.inertia = f["bodies/inertia"][:]
            self.ref = f["bodies/reference"][:]
            self.status_names = list(f["help/status"].asstr()[:])
            self.law_names = list(f["help/law"].asstr()[:])
            names = sorted(f["snapshots"])
            nb = len(self.mass)
            ns = len(names)
            self.step = np.zeros(ns, dtype=int)
            self.time = np.zeros(ns)
            self.X = np.zeros((ns, nb, 3))
            self.V = np.zeros((ns, nb, 3))
            self._contacts = []
            for i, name in enumerate(names):
                g = f["snapshots"][name]
                self.step[i] = int(g.attrs["step"])
                self.time[i] = float(g.attrs["time"])
                if bodies:
                    self.X[i] = g["bodies/X"][:]
                    self.V[i] = g["bodies/V"][:]
                c = g["contacts"]
                nc = int(c.attrs["count"])
                d = {"cd": c["cd_body"][:], "an": c["an_body"][:],
                     "reaction": c["reaction"][:].reshape(nc, 2),
                     "status": c["status"][:], "law": c["law"][:],
                     "point": c["point"][:].reshape(nc, 2)}
                if full:
                    d["gap"] = c["gap"][:]
                    d["normal"] = c["normal"][:].reshape(nc, 2)
                    d["velocity"] = c["velocity"][:].reshape(nc, 2)
                else:
                    d["gap"] = np.zeros(nc)
                    d["normal"] = np.zeros((nc, 2))
                    d["velocity"] = np.zeros((nc, 2))
                d["internals"] = (c["internals"][:].reshape(nc, -1) if "internals" in c
                                  else np.zeros((nc, 5)))
                d["broken"] = c["broken"][:] if "broken" in c else np.zeros(nc, dtype=int)
                self._contacts.append(d)
        if self.complete != 1:
            print(f"warning: {path} is not marked complete (unfinished run)")

    @property
    def pos(self):
        return self.ref[None, :, :] + self.X

    def contacts(self, i):
        return self._contacts[i]

    def pair(self, a, b, npts=None):
        """Contact points between bodies a and b (either order), ordered by x of the
        contact point, in every snapshot; snapshots with fewer points are padded with 0
        (their `present` is False)."""
        rows = []
        for d in self._contacts:
            m = np.nonzero(((d["cd"] == a) & (d["an"] == b)) | ((d["cd"] == b) & (d["an"] == a)))[0]
            m = m[np.argsort(d["point"][m, 0], kind="stable")]
            rows.append(m)
        n = npts if npts is not None else max((len(m) for m in rows), default=0)
        ns = len(rows)
        out = {k: np.zeros((ns, n)) for k in ("rt", "rn", "gap", "L", "ut", "un", "beta", "tpsini",
                                             "vt", "vn", "x", "y")}
        out["broken"] = np.zeros((ns, n), dtype=int)
        out["status"] = np.zeros((ns, n), dtype=int)
        out["present"] = np.zeros((ns, n), dtype=bool)
        for i, m in enumerate(rows):
            d = self._contacts[i]
            m = m[:n]
            k = len(m)
            out["rt"][i, :k] = d["reaction"][m, 0]
            out["rn"][i, :k] = d["reaction"][m, 1]
            out["vt"][i, :k] = d["velocity"][m, 0]
            out["vn"][i, :k] = d["velocity"][m, 1]
            out["gap"][i, :k] = d["gap"][m]
            out["x"][i, :k] = d["point"][m, 0]
            out["y"][i, :k] = d["point"][m, 1]
            for j, name in enumerate(("L", "ut", "un", "beta", "tpsini")):
                out[name][i, :k] = d["internals"][m, j]
            out["broken"][i, :k] = d["broken"][m]
            out["status"][i, :k] = d["status"][m]
            out["present"][i, :k] = True
        return Pair(**out)

    def status_name(self, ids):
        return np.array([self.status_names[i - 1] for i in np.ravel(ids)]).reshape(np.shape(ids))
