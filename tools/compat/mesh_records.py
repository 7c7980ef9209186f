"""Readers of meshed (MAILx) decks and records for the LMGC90 compatibility checks,
and the node-set quantities LMGC90 writes in POSTPRO (Dep_*.DAT, Fint_*.DAT),
recomputed from a run's per-step OUTBOX files.

Only what compare_mesh.py needs: meshes of T3/Q4 elements (Q4P0x read as Q4),
CLxxx/ALpxx contactors, ELAS/ELAS_PLAS densities, DOF.OUT, GPV.OUT, Vloc_Rloc.OUT
(any interaction type) and POSTPRO.DAT's NEW MECAx SETS.

Printed precision: LMGC90 writes OUTBOX values as D14.7 (0.ddddddd D+ee, 7
significant digits) and POSTPRO values as ES14.7 (d.ddddddd E+ee, 8 digits).
:func:`ulp7` is one unit of the 7th significant digit of a value so printed.
"""
from pathlib import Path

import numpy as np

from fracas_tools import datbox as datbox_reader
from fracas_tools import outbox
from fracas_tools.mailx import ELEMENTS
from fracas_tools.postpro_deck import read_postpro


def ulp7(v):
    """One unit of the 7th significant digit of v printed as 0.ddddddd D e (0 for 0)."""
    a = np.abs(np.asarray(v, dtype=float))
    with np.errstate(divide="ignore"):
        e = np.where(a > 0, np.floor(np.log10(np.where(a > 0, a, 1.0))) + 1, -400)
    return np.where(a > 0, 10.0 ** (e - 7), 0.0)


def ulp8(v):
    """One unit of the 8th significant digit of v printed as d.ddddddd E e (POSTPRO)."""
    return ulp7(v) / 10.0


# ------------------------------------------------------------------------------------
# DATBOX: meshes, materials, node sets
# ------------------------------------------------------------------------------------

class Mesh:
    """One MAILx body: reference nodes (n, 2), elements [(kind, [0-based nodes], material)],
    candidates {number: (a, b, apab)} and polylines {number: [(a, b) per segment]}
    (0-based nodes, numbered as LMGC90 numbers them in Vloc_Rloc: one number per
    CLxxx point, one per ALpxx polyline, in $tacty order)."""

    def __init__(self, number):
        self.number = number
        self.nodes = []
        self.elements = []
        self.candidates = {}
        self.polylines = {}


def read_meshes(datbox):
    """BODIES.DAT -> dict MAILx body number -> Mesh (RBDY2 bodies skipped; T3xxx, Q4xxx
    and Q4P0x elements, the last read as Q4), read by fracas_tools.datbox."""
    meshes = {}
    for body in datbox_reader.read_bodies(Path(datbox, "BODIES.DAT")):
        if body.model != "MAILx":
            continue
        m = meshes[body.number] = Mesh(body.number)
        m.nodes = np.asarray(body.nodes, dtype=float)
        m.elements = [(e.kind[:2], [int(n) - 1 for n in e.nodes], e.material) for e in body.elements
                      if e.kind in ("T3xxx", "Q4xxx", "Q4P0x")]
        for rank, (c, k) in enumerate(body.tactors(), start=1):
            if k is None:
                m.polylines[rank] = [(int(a) - 1, int(b) - 1) for a, b in zip(c.nodes[:-1], c.nodes[1:])]
            else:
                a, b, apab = c.points[k]
                m.candidates[rank] = (int(a) - 1, int(b) - 1, float(apab))
    return meshes


def read_materials(datbox):
    """BULK_BEHAV.DAT -> (gravity (2,), dict name -> dict(rho[, E, nu])), read by
    fracas_tools.datbox."""
    g, materials = datbox_reader.read_bulk_behav(Path(datbox, "BULK_BEHAV.DAT"))
    mats = {}
    for name, m in materials.items():
        mats[name] = dict(rho=m.density)
        if m.young is not None:
            mats[name].update(E=m.young, nu=m.poisson)
    return np.asarray(g[:2], dtype=float), mats


def read_sets(datbox):
    """POSTPRO.DAT NEW MECAx SETS -> list of sets, each a list of (body, 0-based node),
    read by fracas_tools.postpro_deck."""
    p = Path(datbox, "POSTPRO.DAT")
    if not p.exists():
        return []
    cmd = next((c for c in read_postpro(p).commands if c.name == "NEW MECAx SETS"), None)
    if cmd is None:
        return []
    return [[(body, int(n) - 1) for body, nodes in groups for n in nodes] for groups in cmd.mecax_sets()]


# ------------------------------------------------------------------------------------
# OUTBOX records
# ------------------------------------------------------------------------------------

# LMGC90's OUTBOX files are parsed by fracas_tools.outbox (the one reader of those
# records); these adapters give compare_mesh.py the shapes it compares.

def read_dof(path):
    """DOF.OUT.n / DOF.INI -> (step, time, dict (model, body) -> (X (n, k), V (n, k)))."""
    d = outbox.read_dof_file(path)
    return d.step, d.time, {(r.model, r.number): (np.atleast_2d(np.asarray(r.x, dtype=float)),
                                                  np.atleast_2d(np.asarray(r.v, dtype=float)))
                            for r in d.records}


def read_gpv(path):
    """GPV.OUT.n -> dict (body, element) -> list of value lines (np arrays), in file order."""
    g = outbox.read_gpv(path)
    return {(b.number, e.number): [np.asarray(row, dtype=float) for row in e.rows]
            for b in g.bodies for e in b.elements}


class Contact:
    __slots__ = ("inter", "key", "status", "rl", "vl", "gap", "n", "coo", "internals", "segment")


def read_vloc(path):
    """Vloc_Rloc.OUT.n -> dict key -> Contact; key = (inter, cd model, cd body, cd tactor,
    an model, an body, an tactor, segment or 0). rl = (rlt/H, rln/H), vl = (vlt, vln)."""
    out = {}
    for r in outbox.read_vloc_rloc(path).records:
        c = Contact()
        c.inter = r.inter
        # CLALp/DKALp: the antagonist segment of the ALpxx polyline
        c.segment = r.anseg if (r.antac == "ALpxx" and r.anseg is not None) else 0
        c.status = r.status
        c.key = (r.inter, r.cdbdy, r.icdbdy, r.icdtac, r.anbdy, r.ianbdy, r.iantac, c.segment)
        c.rl = np.asarray(r.rloc[:2], dtype=float)
        c.vl = np.asarray(r.vloc[:2], dtype=float)
        c.gap = float(r.gap)
        c.n = np.asarray(r.normal[:2], dtype=float)
        c.coo = np.asarray(r.coor[:2], dtype=float)
        c.internals = np.asarray(r.internals if r.internals is not None else [], dtype=float)
        out[c.key] = c
    return out


# ------------------------------------------------------------------------------------
# Elements (small strain, reference geometry, plane: per unit thickness)
# ------------------------------------------------------------------------------------

G2 = 1.0 / np.sqrt(3.0)
# LMGC90's Q4 Gauss order (that of GPV.OUT): (-,-), (+,-), (-,+), (+,+), weights 1.
Q4_GAUSS = [(-G2, -G2), (G2, -G2), (-G2, G2), (G2, G2)]


def _grad_q4(x, xi, eta):
    dn = 0.25 * np.array([[-(1 - eta), (1 - eta), (1 + eta), -(1 + eta)],
                          [-(1 - xi), -(1 + xi), (1 + xi), (1 - xi)]])
    jac = dn @ x            # (2, 2): d x_j / d xi_i
    det = np.linalg.det(jac)
    return np.linalg.solve(jac, dn), det


def gauss_gradients(kind, x):
    """[(dN/dx (2, nn), weight * det J)] per Gauss point of the element (LMGC90 order)."""
    if kind == "T3":
        dn = np.array([[-1.0, 1.0, 0.0], [-1.0, 0.0, 1.0]])
        jac = dn @ x
        det = np.linalg.det(jac)
        return [(np.linalg.solve(jac, dn), 0.5 * det)]
    return [(g, det) for g, det in (_grad_q4(x, a, b) for a, b in Q4_GAUSS)]


def mesh_gradients(mesh):
    """gauss_gradients of every element of the mesh (reference geometry)."""
    return [gauss_gradients(kind, mesh.nodes[conn]) for kind, conn, _ in mesh.elements]


def internal_forces(mesh, stress, grads=None):
    """Nodal internal forces (n, 2) = sum over Gauss points of B^T sigma w det J, from
    stress[element] = list of (sxx, syy, sxy) per Gauss point of the element."""
    f = np.zeros_like(mesh.nodes)
    grads = grads or mesh_gradients(mesh)
    for e, (kind, conn, _) in enumerate(mesh.elements):
        gps = grads[e]
        # T3: GPV repeats its one point three times; take the first.
        for g, ((dnx, wdet), s) in enumerate(zip(gps, stress[e])):
            sxx, syy, sxy = s
            f[conn, 0] += wdet * (dnx[0] * sxx + dnx[1] * sxy)
            f[conn, 1] += wdet * (dnx[0] * sxy + dnx[1] * syy)
    return f


def internal_force_bounds(mesh, stress_ulp, grads=None):
    """Bound (n, 2) on the change of internal_forces when each stress component moves
    by up to stress_ulp[element][gp] (3,) (linear propagation of the rounding)."""
    f = np.zeros_like(mesh.nodes)
    grads = grads or mesh_gradients(mesh)
    for e, (kind, conn, _) in enumerate(mesh.elements):
        for (dnx, wdet), u in zip(grads[e], stress_ulp[e]):
            f[conn, 0] += abs(wdet) * (abs(dnx[0]) * u[0] + abs(dnx[1]) * u[2])
            f[conn, 1] += abs(wdet) * (abs(dnx[0]) * u[2] + abs(dnx[1]) * u[1])
    return f


def lumped_masses(mesh, mats):
    """Row-sum lumped nodal masses (n,) (equal shares on the decks' rectangles and right
    triangles, where row sum and HRZ agree)."""
    m = np.zeros(len(mesh.nodes))
    for kind, conn, mat in mesh.elements:
        x = mesh.nodes[conn]
        area = sum(wdet for _, wdet in gauss_gradients(kind, x))
        m[conn] += mats[mat]["rho"] * area / len(conn)
    return m


# ------------------------------------------------------------------------------------
# Node-set quantities of LMGC90's POSTPRO (Dep EVOLUTION, Fint EVOLUTION)
# ------------------------------------------------------------------------------------

def _segment_weight(xa, xb, p):
    d = xb - xa
    s = float(np.dot(p - xa, d) / np.dot(d, d))
    return min(max(s, 0.0), 1.0)


def contact_nodal_forces(meshes, dof_begin, contacts, h, theta):
    """Nodal contact forces (impulse / H) {body: (n, 2)} and their rounding bounds from
    Vloc_Rloc contacts: the candidate point of a CLxxx carries R = rlt t + rln n with
    weights (1 - apab, apab); an ALpxx segment carries -R split at the projection of the
    contact point (coo) on the segment in the detection configuration
    x_ref + X_begin + (1 - theta) h V_begin."""
    f = {b: np.zeros_like(m.nodes) for b, m in meshes.items()}
    fb = {b: np.zeros_like(m.nodes) for b, m in meshes.items()}
    for c in contacts.values():
        n = c.n
        t = np.array([n[1], -n[0]])
        r = c.rl[0] * t + c.rl[1] * n
        rb = (ulp7(c.rl[0]) + ulp7(c.rl[1])) + np.hypot(*c.rl) * float(np.max(ulp7(n)))
        _, cdm, cdb, cdt, anm, anb, ant, seg = c.key
        if cdm == "MAILx":
            a, b, apab = meshes[cdb].candidates[cdt]
            for node, w in ((a, 1.0 - apab), (b, apab)):
                f[cdb][node] += w * r
                fb[cdb][node] += w * rb
        if anm == "MAILx":
            a, b = meshes[anb].polylines[ant][max(seg, 1) - 1]
            X, V = dof_begin[("MAILx", anb)]
            x = meshes[anb].nodes + X + (1.0 - theta) * h * V
            s = _segment_weight(x[a], x[b], c.coo)
            for node, w in ((a, 1.0 - s), (b, s)):
                f[anb][node] -= w * r
                fb[anb][node] += w * rb
    return f, fb


class NodeSets:
    """LMGC90's Dep_k / Fint_k quantities for the node sets of POSTPRO.DAT, computed
    from one run's OUTBOX files of consecutive steps (DOF.OUT, GPV.OUT, Vloc_Rloc.OUT
    for every step), with bounds from the rounding of those files (one unit of the 7th
    digit of every value read, propagated linearly)."""

    def __init__(self, datbox, h, theta=0.5):
        self.datbox = Path(datbox)
        self.meshes = read_meshes(datbox)
        self.gravity, self.mats = read_materials(datbox)
        self.sets = read_sets(datbox)
        self.h, self.theta = h, theta
        self.mass = {b: lumped_masses(m, self.mats) for b, m in self.meshes.items()}
        self._cache = {}
        self._dofs = {}
        self.grads = {b: mesh_gradients(m) for b, m in self.meshes.items()}

    def _dof(self, outbox, step):
        key = (str(outbox), step)
        if key not in self._dofs:
            if len(self._dofs) > 8:
                self._dofs.clear()
            self._dofs[key] = self._read_dof(outbox, step)
        return self._dofs[key]

    def _read_dof(self, outbox, step):
        if step == 0:
            ini = self.datbox / "DOF.INI"
            states = read_dof(ini)[2] if ini.exists() else {}
            out = {}
            for b, m in self.meshes.items():
                out[("MAILx", b)] = states.get(("MAILx", b), (np.zeros_like(m.nodes), np.zeros_like(m.nodes)))
            return out
        return read_dof(Path(outbox, f"DOF.OUT.{step}"))[2]

    def _stress(self, outbox, step, b):
        """Per element of body b: (sxx, syy, sxy) per Gauss point and their ulps."""
        gpv = self._gpv_cache
        mesh = self.meshes[b]
        st, su = [], []
        for e, (kind, conn, _) in enumerate(mesh.elements):
            rows = gpv[(b, e + 1)]
            el = ELEMENTS[kind + "xxx"]          # the element table: points printed, state points
            per_gp = len(rows) // el.gauss_gpv
            pts = rows[0::per_gp][:el.gauss]
            st.append([(p[0], p[1], p[2]) for p in pts])
            su.append([ulp7(p[:3]) for p in pts])
        return st, su

    def at(self, outbox, step, forces=True):
        """[(dep (4,), dep_bound (4,), fint (10,), fint_bound (10,))] per set at step,
        with LMGC90's columns: Dep: mean u (2), mean v (2); Fint: Reac, Fint, Finert,
        Fext, Res (2 each). Without forces, the Fint columns are NaN (Dep only: the
        GPV and Vloc_Rloc files are not read)."""
        key = (str(outbox), step, forces)
        if key in self._cache:
            return self._cache[key]
        dof = self._dof(outbox, step)
        if not forces:
            out = []
            for s in self.sets:
                u = np.array([dof[("MAILx", b)][0][n] for b, n in s])
                v = np.array([dof[("MAILx", b)][1][n] for b, n in s])
                nan = np.full(10, np.nan)
                out.append((np.concatenate([u.mean(0), v.mean(0)]),
                            np.concatenate([ulp7(u).mean(0), ulp7(v).mean(0)]), nan, nan))
            self._cache[key] = out
            return out
        dofb = self._dof(outbox, step - 1)
        self._gpv_cache = read_gpv(Path(outbox, f"GPV.OUT.{step}"))
        vloc_path = Path(outbox, f"Vloc_Rloc.OUT.{step}")
        contacts = read_vloc(vloc_path) if vloc_path.exists() else {}
        reac, reacb = contact_nodal_forces(self.meshes, dofb, contacts, self.h, self.theta)
        fint, fintb = {}, {}
        for b, m in self.meshes.items():
            st, su = self._stress(outbox, step, b)
            fint[b] = internal_forces(m, st, self.grads[b])
            fintb[b] = internal_force_bounds(m, su, self.grads[b])
        out = []
        for s in self.sets:
            u = np.array([dof[("MAILx", b)][0][n] for b, n in s])
            v = np.array([dof[("MAILx", b)][1][n] for b, n in s])
            vb = np.array([dofb[("MAILx", b)][1][n] for b, n in s])
            m = np.array([self.mass[b][n] for b, n in s])[:, None]
            dep = np.concatenate([u.mean(0), v.mean(0)])
            depb = np.concatenate([ulp7(u).mean(0), ulp7(v).mean(0)])
            finert = (m * (v - vb)).sum(0) / self.h
            finertb = (m * (ulp7(v) + ulp7(vb))).sum(0) / self.h
            fext = (m * self.gravity[None, :]).sum(0)
            r = np.sum([reac[b][n] for b, n in s], axis=0)
            rb = np.sum([reacb[b][n] for b, n in s], axis=0)
            fi = np.sum([fint[b][n] for b, n in s], axis=0)
            fib = np.sum([fintb[b][n] for b, n in s], axis=0)
            res = fi + finert - r - fext
            resb = fib + finertb + rb
            out.append((dep, depb, np.concatenate([r, fi, finert, fext, res]),
                        np.concatenate([rb, fib, finertb, np.zeros(2), resb])))
        self._cache[key] = out
        return out


def read_postpro_series(path):
    """A POSTPRO Dep_/Fint_ file -> array (steps, columns), time first."""
    return np.loadtxt(path)
