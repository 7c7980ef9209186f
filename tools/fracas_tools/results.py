"""The one reader of Fracas results (OUTBOX/fracas.h5, layout in doc/output_layout.md),
used by every script of the repository.

    from fracas_tools.results import Run, Results
    run = Run("my_case")                     # or ".../OUTBOX/fracas.h5"; opened read-only
    run.series["kinetic_energy"]             # one value per step
    snap = run.snapshot(-1)                  # X, V (nb, ndof), contacts (dict of arrays)
    res = Results("my_case")                 # the same, read once into stacked arrays:
    res.X, res.V                             # (nsnap, nb, ndof)
    res.contacts[i]                          # dict of arrays of snapshot i (read on demand)
    res.force_on(i, body), res.pair(a, b)    # helpers of the validation checks

Nothing assumes rigid bodies beyond what the file says: body arrays take their shape from
the file (3 dofs per rigid 2D body), and a /mesh group (meshed bodies) is read as a dict of
arrays (Run.mesh, its attributes Run.mesh_attrs), and a snapshot's mesh_X, mesh_V,
mesh_gauss_points (or mesh group) as Snapshot.mesh["X"], ["V"], ["gauss_points"], its
cracks group (interfaces of exploded meshes) as Snapshot.mesh["cracks"].

Positions: /bodies/reference holds the reference configuration (BODIES.DAT node
coordinates) and snapshot X the displacement from it, as LMGC90's DOF files: position =
reference + X. An attribute ``meaning`` or ``description`` on bodies/X saying 'position'
(or Run(path, x_is='position')) makes X read as absolute positions instead.

Series: all columns are read as float64 and cut to the shortest length (a run that
stopped between two flushes may leave them differing by one row).
"""

import os
from pathlib import Path

import numpy as np

__all__ = ["Run", "Snapshot", "Results", "Pair", "open_run"]


def _h5py():
    import h5py
    return h5py


def _attr(v):
    """An HDF5 attribute as a Python scalar / str."""
    if isinstance(v, bytes):
        return v.decode("utf-8", "replace").rstrip()
    if isinstance(v, np.ndarray):
        if v.size == 1:
            return _attr(v.reshape(-1)[0])
        return v
    if isinstance(v, np.generic):
        return v.item()
    if isinstance(v, str):
        return v.rstrip()
    return v


def _strings(ds):
    """A string dataset (fixed or variable length) as a list of str."""
    a = ds[()]
    a = np.atleast_1d(a)
    out = []
    for x in a.reshape(-1):
        if isinstance(x, bytes):
            x = x.decode("utf-8", "replace")
        out.append(str(x).rstrip().rstrip("\x00"))
    return out


def _resolve_h5(path):
    p = Path(path)
    if p.is_dir():
        for cand in (p / "OUTBOX" / "fracas.h5", p / "fracas.h5"):
            if cand.exists():
                return cand
        raise FileNotFoundError(f"no OUTBOX/fracas.h5 under {p}")
    if not p.exists():
        raise FileNotFoundError(f"{p} does not exist")
    return p


class Snapshot:
    """One /snapshots/NNNNNN group: step, time, X, V (nb, ndof: 3 for rigid 2D bodies),
    contacts (dict of arrays, nc rows), pos (nb, ndof: for rigid bodies x, y and the
    rotation from the reference orientation), mesh (dict of the meshes' state, empty
    without meshed bodies: the snapshot's mesh_* datasets without their prefix, X and V
    (nn, 2) node displacements and velocities, gauss_points (ngp, 13) as fracas writes
    them, and the arrays of a mesh group if there is one)."""

    def __init__(self, name, step, time, X, V, contacts, pos, mesh=None):
        self.name, self.step, self.time = name, step, time
        self.X, self.V, self.contacts, self.pos = X, V, contacts, pos
        self.mesh = mesh or {}

    @property
    def n_contacts(self):
        return len(self.contacts["cd_body"])

    def __repr__(self):
        return f"Snapshot({self.name}, step={self.step}, time={self.time:g}, contacts={self.n_contacts})"


class Run:
    """A Fracas results file, opened read-only. ``path``: the .h5 file, or a case
    directory holding OUTBOX/fracas.h5."""

    CONTACT_FIELDS = ("inter", "cd_body", "an_body", "cd_tactor", "an_tactor", "status", "law",
                      "normal", "point", "reaction", "velocity", "gap")

    def __init__(self, path, x_is="auto"):
        h5py = _h5py()
        self.path = _resolve_h5(path)
        self.file = h5py.File(self.path, "r")
        f = self.file
        self.attrs = {k: _attr(v) for k, v in f.attrs.items()}
        self.bodies = {}
        if "bodies" in f:
            for k, ds in f["bodies"].items():
                if isinstance(ds, h5py.Dataset):
                    self.bodies[k] = ds[()]
        nb = self.n_bodies
        if "reference" not in self.bodies:
            self.bodies["reference"] = np.zeros((nb, 3 if self.body_model == "RBDY2" else 0))
        ref = np.asarray(self.bodies["reference"], dtype=float)
        if ref.ndim == 2 and ref.shape[0] != nb and ref.shape[1] == nb:
            ref = ref.T
        self.bodies["reference"] = ref
        if "number" not in self.bodies:
            self.bodies["number"] = np.arange(1, nb + 1)
        self._index = {int(n): i for i, n in enumerate(self.bodies["number"])}
        self.series = {}
        if "series" in f:
            for k, ds in f["series"].items():
                if isinstance(ds, h5py.Dataset) and ds.ndim == 1:
                    self.series[k] = np.asarray(ds[()])     # counts and flags int32, the rest float64
        if self.series:
            n = min(len(v) for v in self.series.values())
            self.series = {k: v[:n] for k, v in self.series.items()}
        self.help = {}
        if "help" in f:
            g = f["help"]
            for key in ("status", "inter", "law"):
                for name in (key + "_names", key):
                    if name in g:
                        self.help[key] = _strings(g[name])
                        break
        self.snapshot_names = []
        if "snapshots" in f:
            self.snapshot_names = sorted((k for k in f["snapshots"] if k.isdigit()), key=int)
        self.x_is = self._decide_x(x_is)

    # -- basics --
    @property
    def body_model(self):
        """The model of /bodies ('RBDY2' for rigid 2D bodies, 3 dofs each)."""
        if "bodies" in self.file and "model" in self.file["bodies"].attrs:
            return str(_attr(self.file["bodies"].attrs["model"]))
        return "RBDY2"

    @property
    def mesh(self):
        """The arrays of the /mesh group (meshed bodies: nodes, elements, ...; nested
        groups as nested dicts), empty without meshed bodies."""
        return _group_arrays(self.file["mesh"]) if "mesh" in self.file else {}
    @property
    def mesh_attrs(self):
        """The attributes of the /mesh group (plane, gauss_point_fields,
        interface_families, ...), empty without meshed bodies."""
        if "mesh" not in self.file:
            return {}
        return {k: _attr(v) for k, v in self.file["mesh"].attrs.items()}

    @property
    def n_bodies(self):
        for k in ("number", "mass", "radius"):
            if k in self.bodies:
                return len(self.bodies[k])
        return 0

    @property
    def complete(self):
        return int(self.attrs.get("complete", 0)) == 1

    @property
    def time_step(self):
        return self.attrs.get("time_step")

    @property
    def cohesive_damage(self):
        """The run's cohesive damage scheme: 'implicit' (solved within the step) or
        'explicit' (LMGC90's update after the step; files written before the choice existed)."""
        g = self.file.get("run")
        if g is None or "cohesive_damage" not in g.attrs:
            return "explicit"
        return str(_attr(g.attrs["cohesive_damage"]))

    @property
    def n_snapshots(self):
        return len(self.snapshot_names)

    @property
    def case_dir(self):
        """The case directory: the attribute case_dir if it exists on disk, else
        the folder above OUTBOX/."""
        cd = self.attrs.get("case_dir")
        if isinstance(cd, str) and cd and Path(cd).is_dir():
            return Path(cd)
        p = self.path.parent
        return p.parent if p.name == "OUTBOX" else p

    def close(self):
        self.file.close()

    def __enter__(self):
        return self

    def __exit__(self, *a):
        self.close()

    def body_index(self, numbers):
        """Row indices of body serial numbers (-1 for unknown numbers)."""
        return np.array([self._index.get(int(n), -1) for n in np.atleast_1d(numbers)], dtype=int)

    def name_of(self, table, ids):
        """Names of 1-based ids in a help table ('status', 'inter', 'law')."""
        names = self.help.get(table, [])
        return [names[i - 1] if 1 <= i <= len(names) else f"?{i}" for i in np.atleast_1d(ids)]

    # -- snapshots --
    def _decide_x(self, x_is):
        if x_is in ("displacement", "position"):
            return x_is
        if x_is != "auto":
            raise ValueError("x_is must be 'auto', 'displacement' or 'position'")
        if not self.snapshot_names:
            return "displacement"
        g = self.file["snapshots"][self.snapshot_names[0]]
        for obj in (g.get("bodies/X"), g.get("bodies")):
            if obj is None:
                continue
            for key in ("meaning", "description", "units"):
                if key in obj.attrs:
                    text = str(_attr(obj.attrs[key])).lower()
                    if "displacement" in text:
                        return "displacement"
                    if "position" in text or "absolute" in text:
                        return "position"
        return "displacement"

    def snapshot(self, which=-1):
        """A Snapshot by index in the snapshot list (negative from the end) or by
        group name ('000003')."""
        if not self.snapshot_names:
            raise IndexError(f"{self.path}: no snapshots")
        name = which if isinstance(which, str) else self.snapshot_names[which]
        g = self.file["snapshots"][name]
        nb = self.n_bodies
        ndof = self.bodies["reference"].shape[1] if self.bodies["reference"].ndim == 2 else 0
        X = np.asarray(g["bodies/X"][()], dtype=float) if "bodies/X" in g else np.zeros((nb, ndof))
        V = np.asarray(g["bodies/V"][()], dtype=float) if "bodies/V" in g else np.zeros_like(X)
        if X.ndim == 2 and X.shape[0] != nb and X.shape[1] == nb:
            X, V = X.T, V.T
        contacts = {}
        cg = g["contacts"] if "contacts" in g else {}
        for k in self.CONTACT_FIELDS + ("internals",):
            if k in cg:
                contacts[k] = np.asarray(cg[k][()])
        nc = len(contacts["cd_body"]) if "cd_body" in contacts else 0
        for k in self.CONTACT_FIELDS:
            if k not in contacts:
                shape = (nc, 2) if k in ("normal", "point", "reaction", "velocity") else (nc,)
                contacts[k] = np.zeros(shape, dtype=float if len(shape) == 2 or k == "gap" else int)
            elif k in ("normal", "point", "reaction", "velocity"):
                a = np.asarray(contacts[k], dtype=float).reshape(-1, 2) if contacts[k].size else \
                    np.zeros((nc, 2))
                contacts[k] = a
        ref = self.bodies["reference"]
        rigid = X.ndim == 2 and X.shape[1] == 3 and ref.shape == X.shape
        if self.x_is == "displacement":
            pos = ref + X if ref.shape == X.shape else X.copy()
            if rigid:
                pos[:, 2] = X[:, 2]              # rotation from the reference orientation
        else:
            pos = X.copy()
            if rigid:
                pos[:, 2] = X[:, 2] - ref[:, 2]
        step = int(_attr(g.attrs.get("step", 0)))
        time = float(_attr(g.attrs.get("time", float("nan"))))
        mesh = _group_arrays(g["mesh"]) if "mesh" in g else {}
        for k in g:
            if k.startswith("mesh_") and not hasattr(g[k], "keys"):
                mesh[k[len("mesh_"):]] = g[k][()]
        if "cracks" in g:
            mesh["cracks"] = _group_arrays(g["cracks"])
        return Snapshot(name, step, time, X, V, contacts, pos, mesh)

    def snapshot_arrays(self, name):
        """One dataset of every snapshot (e.g. 'mesh_X', 'contacts/reaction'), as a
        list of arrays in snapshot order: much faster than snapshot(i) for each i,
        which reads every field. Stack them with np.array when their shapes agree."""
        g = self.file["snapshots"]
        return [np.asarray(g[n][name][()]) for n in self.snapshot_names]

    def snapshot_times(self):
        out = []
        for n in self.snapshot_names:
            g = self.file["snapshots"][n]
            out.append((int(_attr(g.attrs.get("step", 0))), float(_attr(g.attrs.get("time", np.nan)))))
        return out

    # -- deck --
    def deck(self):
        """The Case read from the case's DATBOX when it exists and has as many
        bodies as the results file; else None."""
        if hasattr(self, "_deck"):
            return self._deck
        self._deck = None
        try:
            from .datbox import read_case
            case = read_case(self.case_dir)
            if len(case.bodies) == self.n_bodies:
                self._deck = case
        except (FileNotFoundError, ValueError, OSError):
            pass
        return self._deck

    def __repr__(self):
        return (f"Run({str(self.path)!r}, bodies={self.n_bodies}, steps={len(self.series.get('time', []))}, "
                f"snapshots={self.n_snapshots}, complete={self.complete})")


def open_run(path, x_is="auto"):
    return Run(path, x_is)


def _group_arrays(g):
    """The datasets of an HDF5 group as a dict of arrays (nested groups as dicts)."""
    h5py = _h5py()
    out = {}
    for k, obj in g.items():
        out[k] = _group_arrays(obj) if isinstance(obj, h5py.Group) else obj[()]
    return out


class Pair:
    """Per-snapshot arrays (nsnap, npts) of the contact points between two bodies
    (Results.pair): rt, rn, gap, L, ut, un, beta, tpsini (cohesive internals), vt, vn,
    x, y (contact point), broken, status, present."""

    def __init__(self, **kw):
        self.__dict__.update(kw)

    def total(self, name):
        """Sum over the points of the pair (nsnap,)."""
        return getattr(self, name).sum(axis=1)

    def mean(self, name):
        return getattr(self, name).mean(axis=1)


class _Contacts:
    """Lazy list of the snapshots' contacts (read on first access, then cached):
    contacts[i] is a dict of arrays: cd, an (body numbers), cd_tactor, an_tactor, rt, rn,
    reaction (nc, 2), normal (nc, 2), point (nc, 2), velocity (nc, 2), gap, status, law,
    inter, internals (nc, nint; nint = 0 without cohesive laws), broken (nc)."""

    def __init__(self, run, names):
        self.run, self.names, self.cache = run, names, {}

    def __len__(self):
        return len(self.names)

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[k] for k in range(*i.indices(len(self)))]
        i = range(len(self.names))[i]
        if i not in self.cache:
            c = self.run.snapshot(self.names[i]).contacts
            nc = len(c["cd_body"])
            d = {"cd": c["cd_body"], "an": c["an_body"], "cd_tactor": c["cd_tactor"],
                 "an_tactor": c["an_tactor"], "reaction": c["reaction"], "rt": c["reaction"][:, 0],
                 "rn": c["reaction"][:, 1], "normal": c["normal"], "point": c["point"],
                 "velocity": c["velocity"], "gap": c["gap"], "status": c["status"], "law": c["law"],
                 "inter": c["inter"]}
            d["internals"] = (np.asarray(c["internals"], dtype=float).reshape(nc, -1) if "internals" in c
                              else np.zeros((nc, 0)))
            d["broken"] = (self.run.file["snapshots"][self.names[i]]["contacts"]["broken"][()]
                           if "broken" in self.run.file["snapshots"][self.names[i]]["contacts"]
                           else np.zeros(nc, dtype=int))
            self.cache[i] = d
        return self.cache[i]

    def __iter__(self):
        return (self[i] for i in range(len(self)))


class Results(Run):
    """A results file read once into stacked numpy arrays, for checks and plots.

    Attributes: complete (True for a finished run), h (time step), theta, series (dict column -> array), mass,
    inertia, radius, ref (nb, ndof), status_names, inter_names, law_names; per snapshot:
    step, time (nsnap,), X, V (nsnap, nb, ndof) (with bodies=True), contacts (lazy list
    of dicts, see _Contacts; with contacts=True). snapshots=False reads no snapshot."""

    def __init__(self, run_dir, contacts=True, snapshots=True, bodies=True, x_is="auto"):
        os.environ.setdefault("HDF5_USE_FILE_LOCKING", "FALSE")
        try:
            super().__init__(run_dir, x_is)
        except FileNotFoundError as e:
            raise SystemExit(f"no results file: {e} (run the case first)")
        self.h = float(self.attrs["time_step"])
        self.theta = float(self.attrs["theta"])
        b = self.bodies
        self.mass = np.asarray(b.get("mass", np.zeros(self.n_bodies)), dtype=float)
        self.inertia = np.asarray(b.get("inertia", np.zeros(self.n_bodies)), dtype=float)
        self.radius = np.asarray(b.get("radius", np.zeros(self.n_bodies)), dtype=float)
        self.ref = np.asarray(b["reference"], dtype=float)
        self.status_names = self.help.get("status", [])
        self.inter_names = self.help.get("inter", [])
        self.law_names = self.help.get("law", [])
        names = self.snapshot_names if snapshots else []
        ns, nb = len(names), self.n_bodies
        ndof = self.ref.shape[1] if self.ref.ndim == 2 else 0
        self.step = np.zeros(ns, dtype=int)
        self.time = np.zeros(ns)
        self.X = np.zeros((ns, nb, ndof))
        self.V = np.zeros((ns, nb, ndof))
        g = self.file["snapshots"] if ns else None
        for i, name in enumerate(names):
            s = g[name]
            self.step[i] = int(_attr(s.attrs["step"]))
            self.time[i] = float(_attr(s.attrs["time"]))
            if bodies and "bodies/X" in s:
                s["bodies/X"].read_direct(self.X[i])
                s["bodies/V"].read_direct(self.V[i])
        self.contacts = _Contacts(self, names) if contacts else []
        if not self.complete:
            print(f"warning: {self.path} is not marked complete (unfinished run)")

    @property
    def position(self):
        """(nsnap, nb, ndof) absolute coordinates (x, y, angle for rigid bodies)."""
        return self.ref[None, :, :] + self.X

    pos = position

    def global_reactions(self, isnap):
        """(nc, 2) global reaction forces R = rt t + rn n (acting on the candidate)."""
        c = self.contacts[isnap]
        n = c["normal"]
        t = np.column_stack((n[:, 1], -n[:, 0]))
        return c["rt"][:, None] * t + c["rn"][:, None] * n

    def force_on(self, isnap, body, others=None):
        """Resultant contact force (2,) on ``body`` (serial number) in snapshot isnap,
        from all its contacts or only those with the bodies in ``others``."""
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
        """Sum of rn over the contacts between bodies a and b (0.0 without contact)."""
        c = self.contacts[isnap]
        return float(np.sum(c["rn"][self.pair_mask(isnap, a, b)]))

    reaction_between = normal_force_between

    def status_name(self, ids):
        """Names of 1-based status ids, same shape."""
        return np.array([self.status_names[i - 1] for i in np.ravel(ids)]).reshape(np.shape(ids))

    def pair(self, a, b, npts=None):
        """Contact points between bodies a and b (either order), ordered by x of the
        contact point, in every snapshot; snapshots with fewer points are padded with 0
        (their ``present`` is False). Cohesive internals L, ut, un, beta, tpsini are 0
        without cohesive laws."""
        rows = []
        for d in self.contacts:
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
            d = self.contacts[i]
            m = m[:n]
            k = len(m)
            out["rt"][i, :k] = d["rt"][m]
            out["rn"][i, :k] = d["rn"][m]
            out["vt"][i, :k] = d["velocity"][m, 0]
            out["vn"][i, :k] = d["velocity"][m, 1]
            out["gap"][i, :k] = d["gap"][m]
            out["x"][i, :k] = d["point"][m, 0]
            out["y"][i, :k] = d["point"][m, 1]
            for j, name in enumerate(("L", "ut", "un", "beta", "tpsini")):
                if d["internals"].shape[1] > j:
                    out[name][i, :k] = d["internals"][m, j]
            out["broken"][i, :k] = d["broken"][m]
            out["status"][i, :k] = d["status"][m]
            out["present"][i, :k] = True
        return Pair(**out)
