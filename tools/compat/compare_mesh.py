#!/usr/bin/env python3
"""Compare a Fracas run of one of LMGC90's meshed decks with what LMGC90 wrote.

  compare_mesh.py outbox OURS_OUTBOX STEP REF_OUTBOX N [--floor F] [--rel Q=R ...] [--only Q ...]
      DOF.OUT, GPV.OUT and Vloc_Rloc.OUT of our step STEP against LMGC90's write N,
      value by value. Default tolerance, the printed precision: LMGC90 prints D14.7,
      so a value agrees when |ours - lmgc90| <= one unit of its 7th significant digit
      (of the larger of the two) + F * S, S the largest magnitude of the same quantity
      over all of LMGC90's writes of the case (F = 1e-8 by default: values far below
      their field's scale carry its absolute round-off, e.g. a node velocity of 6e-3 in
      a field of 15 m/s, or stresses of 1e-11 Pa in free flight).
      --rel Q=R replaces the tolerance of quantity Q by R * S_n (a documented,
      looser agreement; S_n the largest magnitude of Q in LMGC90's write N). Quantities: X, V (DOF), stress, strain, internals (GPV; for
      J2, the internals line: Cp^-1 or eps_p, p, von Mises), rl (rlt/H, rln/H), vl,
      gap, normal, point, czm_L, czm_ut, czm_un, czm_beta, czm_TPSini (cohesive
      internals of Vloc_Rloc). Same bodies, elements and contacts
      are required, and the same status for every contact (--status-diff K allows K).
  compare_mesh.py sets DATBOX OURS_OUTBOX REF_POSTPRO FIRST LAST [--every K] [--floor F]
                  [--rel R] [--columns C ...]
      LMGC90's POSTPRO node-set files Dep_k / Fint_k over steps FIRST..LAST against
      the same quantities computed from our per-step files (run with
      output_dof_every 1): mean u, v of each set from DOF.OUT; Reac from Vloc_Rloc.OUT
      (CLxxx points by their weights, ALpxx segments at the projection of the contact
      point), Fint = sum B^T sigma from GPV.OUT, Finert = M (V - V_begin) / H
      (lumped), Fext = M g, Res = Fint + Finert - Reac - Fext. Default tolerance, the
      printed precision: the rounding of every value of ours that enters the
      quantity (one unit of its 7th digit, propagated linearly) + one unit of LMGC90's
      8th digit + F * S (S: the column group's largest magnitude over the run in
      LMGC90's file; F = 1e-12). --rel R: |ours - lmgc90| <= R * S instead, or with
      --rel-to value, R * max(|lmgc90|, F * S). Columns: ux uy vx vy Rx Ry Fix Fiy Mx My Fex Fey Resx Resy
      (Mx, My: Finert).
  compare_mesh.py czm DATBOX OURS_OUTBOX LAST REF_DIR --spec FILE
      Post-damage cohesive phase: robust physical quantities against LMGC90's (see
      check_czm and the spec file of the case).
Prints one line per check and exits 1 if any fails.
"""
import argparse
import json
import os
import sys
from pathlib import Path

import numpy as np

from mesh_records import (NodeSets, read_dof, read_gpv, read_vloc, ulp7, ulp8)  # noqa: E402
from fracas_tools.checks import Checker  # noqa: E402

checker = None          # the run's Checker (main)


def report(name, ok, detail):
    checker.true(name, ok, note=detail)


def _ratio(ours, ref, q, a):
    """Deviation / tolerance for arrays of one quantity."""
    ours = np.asarray(ours, dtype=float)
    ref = np.asarray(ref, dtype=float)
    if q in a.rel_map:
        # A documented agreement: relative to the quantity's scale in this write.
        scale = float(np.abs(ref).max())
        tol = a.rel_map[q] * scale + np.zeros_like(ref)
    else:
        scale = a.scales.get(q, 0.0)
        tol = np.maximum(ulp7(ours), ulp7(ref)) + a.floor * scale
    dev = np.abs(ours - ref)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.where(tol > 0, dev / tol, np.where(dev > 0, np.inf, 0.0))
    return r, dev, scale


def _compare_quantity(q, ours, ref, a, where):
    if a.only and q not in a.only:
        return
    r, dev, scale = _ratio(ours, ref, q, a)
    if not r.size:
        return
    k = int(np.argmax(r))
    tol_kind = f"{a.rel_map[q]:g} x scale" if q in a.rel_map else f"printed digits + {a.floor:g} x scale"
    report(f"{q} ({tol_kind})", r.max() <= 1.0,
           f"worst {r.max():.3g} x tolerance at {where[k]}: ours {ours.ravel()[k]:.7e} lmgc90 {ref.ravel()[k]:.7e}; "
           f"max |diff| {dev.max():.3e}, scale {scale:.3e}, {int((r > 1).sum())} of {r.size} over")


def _gpv_groups(g):
    """GPV lines grouped by kind: {kind: (values, labels)}. Lines per Gauss point:
    2 (stress, strain) for elastic models, 3 for J2 (the third holds the internals;
    LMGC90's finite-strain J2 prints zeros as strain and Cp^-1 first on the internals
    line: only the last two, p and von Mises, are compared)."""
    per = 3 if any(len(v) > 4 for lines in g.values() for v in lines) else 2
    out = {"stress": ([], []), "strain": ([], []), "internals": ([], [])}
    for k in sorted(g):
        for j, v in enumerate(g[k]):
            kind = ("stress", "strain", "internals")[j % per]
            if kind == "internals":
                v = v[-2:]
            out[kind][0].extend(v)
            out[kind][1].extend(f"body {k[0]} element {k[1]} line {j + 1} value {m + 1}" for m in range(len(v)))
    return out


VLOC_QUANTITIES = (("rl", "rl"), ("vl", "vl"), ("gap", "gap"), ("normal", "n"), ("point", "coo"))
# Cohesive internals (MAC_CZM & co): one quantity per column, each with its own scale.
CZM_COLUMNS = ("czm_L", "czm_ut", "czm_un", "czm_beta", "czm_TPSini")


def _czm_values(c, i):
    return c.internals[i:i + 1] if c.internals.size == len(CZM_COLUMNS) else np.array([])


def reference_scales(ref_outbox):
    """Largest magnitude of each quantity over all of LMGC90's writes of the case
    (the scale of a field whose one write may be all round-off, e.g. stresses in
    free flight)."""
    sc = {}

    def up(q, v):
        v = np.abs(np.asarray(v, dtype=float))
        if v.size:
            sc[q] = max(sc.get(q, 0.0), float(v.max()))
    rb = Path(ref_outbox)
    for f in rb.glob("DOF.OUT.*"):
        for x, v in read_dof(f)[2].values():
            up("X", x)
            up("V", v)
    for f in rb.glob("GPV.OUT.*"):
        for q, (vals, _) in _gpv_groups(read_gpv(f)).items():
            up(q, vals)
    for f in rb.glob("Vloc_Rloc.OUT.*"):
        for c in read_vloc(f).values():
            for q, attr in VLOC_QUANTITIES:
                up(q, getattr(c, attr))
            for i, q in enumerate(CZM_COLUMNS):
                up(q, _czm_values(c, i))
    return sc


def outbox(a):
    ob, rb = Path(a.ours), Path(a.ref)
    a.scales = reference_scales(rb)
    _, _, do = read_dof(ob / f"DOF.OUT.{a.step}")
    _, _, dr = read_dof(rb / f"DOF.OUT.{a.n}")
    report("same bodies", set(do) == set(dr), f"{len(do)} against {len(dr)}")
    keys = sorted(dr)
    for q, i in (("X", 0), ("V", 1)):
        o = np.concatenate([do[k][i].ravel() for k in keys])
        r = np.concatenate([dr[k][i].ravel() for k in keys])
        where = [f"{k[0]} {k[1]} node {j // dr[k][i].shape[1] + 1} comp {j % dr[k][i].shape[1] + 1}"
                 for k in keys for j in range(dr[k][i].size)]
        _compare_quantity(q, o, r, a, where)
    if (rb / f"GPV.OUT.{a.n}").exists():
        go = read_gpv(ob / f"GPV.OUT.{a.step}")
        gr = read_gpv(rb / f"GPV.OUT.{a.n}")
        report("same elements", set(go) == set(gr), f"{len(go)} against {len(gr)}")
        go_g, gr_g = _gpv_groups(go), _gpv_groups(gr)
        for q in gr_g:
            if len(go_g[q][0]) != len(gr_g[q][0]):
                report(f"GPV {q} layout", False, f"{len(go_g[q][0])} values against {len(gr_g[q][0])}")
            elif gr_g[q][0]:
                _compare_quantity(q, np.array(go_g[q][0]), np.array(gr_g[q][0]), a, gr_g[q][1])
    if (rb / f"Vloc_Rloc.OUT.{a.n}").exists():
        vo = read_vloc(ob / f"Vloc_Rloc.OUT.{a.step}")
        vr = read_vloc(rb / f"Vloc_Rloc.OUT.{a.n}")
        report("same interactions", set(vo) == set(vr), f"{len(vo)} against {len(vr)}, "
               f"{len(set(vo) ^ set(vr))} not in both")
        common = [k for k in vr if k in vo]
        bad = [k for k in common if vo[k].status != vr[k].status]
        report("statuses", len(bad) <= a.status_diff,
               f"{len(common) - len(bad)} of {len(common)} equal (allowed to differ: {a.status_diff})"
               + (f"; first: {bad[0]} ours {vo[bad[0]].status} lmgc90 {vr[bad[0]].status}" if bad else ""))
        where = [f"contact {k}" for k in common]
        for q, attr in VLOC_QUANTITIES:
            o = [np.atleast_1d(getattr(vo[k], attr)) for k in common]
            r = [np.atleast_1d(getattr(vr[k], attr)) for k in common]
            if not r or not sum(x.size for x in r):
                continue
            w = [wk + f" value {m + 1}" for wk, x in zip(where, r) for m in range(x.size)]
            _compare_quantity(q, np.concatenate(o), np.concatenate(r), a, w)
        for i, q in enumerate(CZM_COLUMNS):
            o = [_czm_values(vo[k], i) for k in common]
            r = [_czm_values(vr[k], i) for k in common]
            if sum(x.size for x in r):
                _compare_quantity(q, np.concatenate(o), np.concatenate(r), a, where)


COLUMNS = ["ux", "uy", "vx", "vy", "Rx", "Ry", "Fix", "Fiy", "Mx", "My", "Fex", "Fey", "Resx", "Resy"]


def sets(a):
    ns = NodeSets(a.datbox, a.h, a.theta)
    steps = list(range(a.first, a.last + 1, a.every))
    cols = [COLUMNS.index(c) for c in (a.columns or COLUMNS)]
    forces = any(c >= 4 for c in cols)
    ours = {s: ns.at(a.ours, s, forces) for s in steps}
    for k in range(len(ns.sets)):
        if a.sets and k + 1 not in a.sets:
            continue
        dep = np.loadtxt(Path(a.ref, f"Dep_{k + 1:07d}.DAT"), ndmin=2)
        fint = np.loadtxt(Path(a.ref, f"Fint_{k + 1:07d}.DAT"), ndmin=2)
        ref_all = np.hstack([dep[:, 1:], fint[:, 1:]])
        # Column groups sharing a scale: displacements, velocities, forces.
        scale = np.array([np.abs(ref_all[:, 0:2]).max()] * 2 + [np.abs(ref_all[:, 2:4]).max()] * 2
                         + [np.abs(ref_all[:, 4:]).max()] * 10)
        worst = np.zeros(len(COLUMNS))
        at = np.zeros(len(COLUMNS), dtype=int)
        detail = [""] * len(COLUMNS)
        for s in steps:
            d, db, f, fb = ours[s][k]
            o = np.concatenate([d, f])
            b = np.concatenate([db, fb])
            r = ref_all[s - 1]
            if abs(dep[s - 1, 0] - s * a.h) > 1e-6 * a.h:
                report(f"set {k + 1} step {s}", False, f"LMGC90's line {s} is at t = {dep[s - 1, 0]}")
                continue
            if a.rel is None:
                tol = b + ulp8(r) + a.floor * scale
            elif a.rel_to == "scale":
                tol = a.rel * scale
            else:
                tol = a.rel * np.maximum(np.abs(r), a.floor * scale)
            with np.errstate(divide="ignore", invalid="ignore"):
                ratio = np.where(tol > 0, np.abs(o - r) / tol, np.where(o != r, np.inf, 0.0))
            for c in cols:
                if ratio[c] > worst[c] or at[c] == 0:
                    worst[c], at[c] = ratio[c], s
                    detail[c] = f"ours {o[c]:.7e} lmgc90 {r[c]:.7e}"
        tol_kind = (f"printed digits + {a.floor:g} x scale" if a.rel is None
                    else f"{a.rel:g} x scale" if a.rel_to == "scale"
                    else f"{a.rel:g} relative (floor {a.floor:g} x scale)")
        for c in cols:
            report(f"set {k + 1} {COLUMNS[c]} steps {a.first}-{a.last} ({tol_kind})", worst[c] <= 1.0,
                   f"worst {worst[c]:.3g} x tolerance at step {at[c]}: {detail[c]}")


def _betas(vloc):
    return {k: c.internals[3] for k, c in vloc.items() if c.internals.size >= 5}


def _first_steps(outbox, first, last, broken):
    """Steps of the first damaged (beta < 1) and first broken (beta < broken) contact."""
    fd = fb = None
    for s in range(first, last + 1):
        b = np.array(list(_betas(read_vloc(Path(outbox, f"Vloc_Rloc.OUT.{s}"))).values()))
        if fd is None and (b < 1.0).any():
            fd = s
        if (b < broken).any():
            fb = s
            break
    return fd, fb


def check_czm(a):
    """Robust quantities of a damaging cohesive run against LMGC90's. The spec (JSON,
    test_cases/compat/<case>/czm.json) gives LMGC90's steps from its case.md, the
    quantities and their tolerances, each with its reason ("why")."""
    spec = json.loads(Path(a.spec).read_text())
    ns = NodeSets(a.datbox, spec["h"], spec.get("theta", 0.5))
    ref = Path(a.ref)
    w, broken = spec["w"], spec["broken"]
    fd = spec["first_damage"]
    ours_steps = dict(zip(("first_damage", "first_broken"), _first_steps(a.ours, fd["from"], a.last, broken)))
    ref_steps = {"first_damage": fd["lmgc90"], "first_broken": fd.get("lmgc90_broken")}
    for key, tol in (("first_damage", fd["step_tol"]), ("first_broken", fd.get("broken_tol"))):
        o, r = ours_steps[key], ref_steps[key]
        if r is None:
            print(f"INFO {key.replace('_', ' ')} step: ours {o} (LMGC90's is not known: not compared)")
            continue
        report(key.replace("_", " ") + " step", o is not None and abs(o - r) <= tol,
               f"ours {o}, lmgc90 {r} (tolerance {tol} steps: {fd['why']})")

    def column(run, k, col, steps):
        if run == "ref":
            fint = np.loadtxt(ref / "POSTPRO" / f"Fint_{k + 1:07d}.DAT", ndmin=2)
            dep = np.loadtxt(ref / "POSTPRO" / f"Dep_{k + 1:07d}.DAT", ndmin=2)
            return np.hstack([dep[:, 1:], fint[:, 1:]])[np.array(steps) - 1, col]
        return np.array([np.concatenate([ns.at(a.ours, s, col >= 4)[k][0], ns.at(a.ours, s, col >= 4)[k][2]])[col]
                         for s in steps])

    # Force peaks (a node-set column with a sign) over a window whose end may be a
    # run's own first damaged or first broken step; or the value at that step.
    for pk in spec.get("peaks", []):
        k, col, sign = pk["set"] - 1, COLUMNS.index(pk["column"]), pk["sign"]
        vals = {}
        for run, steps in (("ours", ours_steps), ("ref", ref_steps)):
            lo, hi = pk["steps"]
            hi = steps[hi] if isinstance(hi, str) else hi
            if hi is None:
                report(f"peak {pk['name']}", False, f"{run}: no {pk['steps'][1]} step")
                break
            if pk.get("at_end"):
                lo = hi
            st = list(range(lo, hi + 1))
            v = sign * column(run, k, col, st)
            i = int(np.argmax(v))
            vals[run] = (v[i], st[i])
        else:
            (vo, so), (vr, sr) = vals["ours"], vals["ref"]
            rel = abs(vo - vr) / abs(vr)
            report(f"{pk['name']}", rel <= pk["rtol"],
                   f"ours {vo:.6g} at step {so}, lmgc90 {vr:.6g} at step {sr}: {rel:.2e} relative "
                   f"(tolerance {pk['rtol']:g}: {pk['why']})")
            if "step_tol" in pk:
                report(f"step of {pk['name']}", abs(so - sr) <= pk["step_tol"],
                       f"ours {so}, lmgc90 {sr} (tolerance {pk['step_tol']} steps)")
    # At the end: the same contacts broken, betas, energy released by damage.
    end = spec["end"]
    lo = read_vloc(Path(a.ours, f"Vloc_Rloc.OUT.{a.last}"))
    vr = read_vloc(ref / "OUTBOX" / f"Vloc_Rloc.OUT.{end['n']}")
    bo, br = _betas(lo), _betas(vr)
    broken_o = {k for k, b in bo.items() if b < broken}
    broken_r = {k for k, b in br.items() if b < broken}
    report(f"broken contacts (beta < {broken:g}) at the end", broken_o == broken_r and len(broken_r) == end["broken"],
           f"ours {len(broken_o)}, lmgc90 {len(broken_r)} (case.md: {end['broken']}), "
           f"{len(broken_o ^ broken_r)} not in both")
    if "beta_rtol" in end:
        dev = max(abs(bo[k] - br[k]) / br[k] for k in broken_r) if broken_r else 0.0
        report("beta of the broken contacts at the end", dev <= end["beta_rtol"],
               f"max relative difference {dev:.3e} (tolerance {end['beta_rtol']:g}: {end['why_beta']})")
    # Energy released by damage, sum of w (1 - beta) L (MAC_CZM: the energy the
    # damage dissipated; over a fully opened interface it tends to the work of
    # separation w L): over the broken contacts (robust), and over all contacts.
    def released(v, keys):
        return sum(w * (1.0 - v[k].internals[3]) * v[k].internals[0] for k in keys)
    for what, keys, tol, why in (("broken contacts", broken_r & broken_o, end["energy_rtol"], end["why_energy"]),
                                 ("all contacts", set(vr) & set(lo), end["energy_all_rtol"], end["why_energy_all"])):
        eo, er = released(lo, keys), released(vr, keys)
        rel = abs(eo - er) / max(er, 1e-300)
        report(f"energy released by damage over the {what}, sum w (1 - beta) L", rel <= tol,
               f"ours {eo:.6g} J, lmgc90 {er:.6g} J: {rel:.2e} relative (tolerance {tol:g}: {why})")
    if "energy_expected" in end:
        eo = released(lo, broken_o)
        ex = end["energy_expected"]
        rel = abs(eo - ex) / ex
        report("energy released by the broken contacts against the work of separation", rel <= end["energy_expected_rtol"],
               f"ours {eo:.6g} J, {ex:g} J: {rel:.2e} relative (tolerance {end['energy_expected_rtol']:g}: "
               f"{end['why_expected']})")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="mode", required=True)
    o = sub.add_parser("outbox")
    o.add_argument("ours")
    o.add_argument("step", type=int)
    o.add_argument("ref")
    o.add_argument("n", type=int)
    o.add_argument("--floor", type=float, default=1e-8)
    o.add_argument("--rel", nargs="*", default=[], metavar="Q=R")
    o.add_argument("--only", nargs="*", default=[])
    o.add_argument("--status-diff", type=int, default=0)
    s = sub.add_parser("sets")
    s.add_argument("datbox")
    s.add_argument("ours")
    s.add_argument("ref")
    s.add_argument("first", type=int)
    s.add_argument("last", type=int)
    s.add_argument("--h", type=float, required=True)
    s.add_argument("--theta", type=float, default=0.5)
    s.add_argument("--every", type=int, default=1)
    s.add_argument("--floor", type=float, default=1e-12)
    s.add_argument("--rel", type=float)
    s.add_argument("--rel-to", choices=["scale", "value"], default="scale")
    s.add_argument("--columns", nargs="*")
    s.add_argument("--sets", nargs="*", type=int)
    c = sub.add_parser("czm")
    c.add_argument("datbox")
    c.add_argument("ours")
    c.add_argument("last", type=int)
    c.add_argument("ref")
    c.add_argument("--spec", required=True)
    a = p.parse_args()
    global checker
    checker = Checker(f"compare_mesh {a.mode}")
    if a.mode == "outbox":
        a.rel_map = {kv.split("=")[0]: float(kv.split("=")[1]) for kv in a.rel}
        outbox(a)
    elif a.mode == "sets":
        sets(a)
    else:
        check_czm(a)
    if not checker.rows:
        checker.true("at least one comparison made", False)
    sys.exit(checker.finish())


if __name__ == "__main__":
    main()
