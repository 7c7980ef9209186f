#!/usr/bin/env python3
"""Run one of LMGC90's example decks (shared/lmgc90_examples/runs/<case>: DATBOX/ and
LMGC90's results in lmgc90/) with the settings LMGC90's own script passed (lmgc90/run.json),
and compare Fracas's last step with LMGC90's DOF.LAST / Vloc_Rloc.LAST.

    lmgc90_example.py run CASE_DIR OUT [--set KEY=VALUE ...] [--deck DIR]
    lmgc90_example.py compare OUT CASE_DIR [--pairs-differ N] [--count-differ N] [--sum-rn REL] [--sum-rn-vertical REL] [--force-y INTER=REL]
                                         [--gap-below G]
                                         [--unordered]
                                         [--max-rn V] [--max-x V] [--mean-x REL] [--mean-y REL]
                                         [--node B:N:DOF] [--gpv-stress REL] [--gpv-p ABS] [--gpv-vm REL]
    lmgc90_example.py points CASE_DIR OUT [--vmax V]
    lmgc90_example.py h5 OUT NAME=V1,V2,... [--rtol R] [--atol A]

`compare` checks the contacts (candidate body and contactor, antagonist body and contactor)
of both codes (their numbers, and at most N pairs in one code only; with --gap-below G only
the contacts whose gapTT is below G in each code; with --unordered a pair is the same
whichever side is the candidate), the summed normal
reaction over the common contacts (or the largest one of ours, where the sum is ~0), its
vertical part rln |n_y| over all contacts (what bed joints carry under gravity), the
vertical force one contact type carries (--force-y: the weight on a ground or a slab), and
the mean node displacement of meshed bodies (of the rigid bodies when there is no mesh; each
component relative to LMGC90's), and the meshes' Gauss-point values (GPV.LAST: the
largest stress difference relative to the largest stress, the largest difference of the
cumulative plastic strain p, 5th internal; the largest difference of the von Mises
stress, 6th internal, relative to its largest). `points` checks a mesh
deck's CLALp contacts: one per candidate point (LMGC90's rule), every point glued, no
node faster than V (a scene at rest stays at rest). `h5` compares the first values
of datasets of OUT/OUTBOX/fracas.h5 (e.g. bodies/mass) with closed-form values.
"""
import argparse
import json
import subprocess
import sys
from pathlib import Path

import re

import numpy as np

from fracas_tools.datbox import read_bodies  # noqa: E402
from fracas_tools.outbox import read_dof_file, read_vloc_rloc  # noqa: E402


NUM = re.compile(r"[-+]?\d*\.\d+[DE][-+]\d+")


def run_control(run_json):
    """Fracas's run control (COMMAND.DAT lines) from LMGC90's run.json."""
    r = json.loads(Path(run_json).read_text())
    solver, norm, tol, relax, it1, it2 = (str(x).strip() for x in r["exsolver"])
    lines = [f"time_step {r['dt']}", f"number_of_steps {r['steps']}", f"theta {r['theta']}",
             f"nlgs_check {norm}", f"nlgs_tolerance {tol}", f"nlgs_relaxation {relax}",
             f"nlgs_sweeps_per_check {it1}", f"nlgs_max_checks {it2}",
             "detection_approach no",          # LMGC90 detects from the gap alone
             "cohesive_damage lmgc90"]         # its damage update at the NLGS checks
    if r.get("quickscramble"):
        lines.append("nlgs_order shuffled")
    return "\n".join(lines) + "\n"


def cmd_run(a):
    case, out = Path(a.case), Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "run.dat").write_text(run_control(case / "lmgc90" / "run.json"))
    cmd = [a.fracas, "-q", "--overwrite", "--command", str(out / "run.dat"), "--output", str(out)]
    for s in a.set or []:
        cmd += ["--set", s]
    return subprocess.run(cmd + [a.deck or str(case)]).returncode


def last(outbox, stem):
    files = sorted(Path(outbox).glob(stem + ".OUT.*"), key=lambda p: int(p.suffix[1:]))
    return files[-1]


def contacts(path, gap_below=None, unordered=False):
    """{(candidate body, contactor, antagonist body, contactor): its records}; unordered:
    the two sides sorted (a pair is the same whichever is candidate)."""
    out = {}
    for r in read_vloc_rloc(path).records:
        if gap_below is None or r.gap < gap_below:
            cd, an = (r.icdbdy, r.icdtac), (r.ianbdy, r.iantac)
            out.setdefault(tuple(sorted((cd, an))) if unordered else cd + an, []).append(r)
    return out


def mesh_x(path):
    """Node displacements of the meshed bodies, or (no mesh) the rigid bodies' translations."""
    recs = read_dof_file(path).records
    if any(r.model == "MAILx" for r in recs):
        return np.concatenate([r.x for r in recs if r.model == "MAILx"])
    return np.array([r.x[:2] for r in recs if r.model == "RBDY2"]).reshape(-1, 2)


def report(name, ok, detail):
    print(f"{'ok  ' if ok else 'FAIL'} {name}: {detail}")
    return ok


def cmd_compare(a):
    ours_box, ref = Path(a.out) / "OUTBOX", Path(a.case) / "lmgc90"
    co = contacts(last(ours_box, "Vloc_Rloc"), a.gap_below, a.unordered)
    cr = contacts(ref / "Vloc_Rloc.LAST", a.gap_below, a.unordered)
    no, nr = sum(map(len, co.values())), sum(map(len, cr.values()))
    only = len(set(co) ^ set(cr))
    which = "contacts" if a.gap_below is None else f"contacts with gapTT < {a.gap_below:g}"
    ok = report(which, only <= a.pairs_differ and abs(no - nr) <= a.count_differ,
                f"{no} ours, {nr} LMGC90's (at most {a.count_differ} apart), {only} pairs in one code only "
                f"(at most {a.pairs_differ})")
    common = sorted(set(co) & set(cr))
    if a.sum_rn is not None and common:
        so = sum(r.rloc[1] for k in common for r in co[k])
        sr = sum(r.rloc[1] for k in common for r in cr[k])
        rel = abs(so - sr) / max(abs(sr), 1e-300)
        ok &= report("summed rln/H", rel <= a.sum_rn, f"{so:.6e} ours, {sr:.6e} LMGC90's: {rel:.2e} apart "
                     f"(tolerance {a.sum_rn:g})")
    if a.sum_rn_vertical is not None:
        # The vertical part of the normal reactions: in a wall under gravity the bed
        # joints carry the weight above them (statically determined), whichever side
        # is candidate; the head joints' thrusts (hyperstatic) do not enter.
        so, sr = (sum(r.rloc[1] * abs(r.normal[1]) for rs in cc.values() for r in rs) for cc in (co, cr))
        rel = abs(so - sr) / max(abs(sr), 1e-300)
        ok &= report("summed rln/H |n_y|", rel <= a.sum_rn_vertical, f"{so:.6e} ours, {sr:.6e} LMGC90's: "
                     f"{rel:.2e} apart (tolerance {a.sum_rn_vertical:g})")
    for spec in a.force_y or []:
        # The vertical force the contacts of one type carry (on their candidates): where it
        # is the weight of what they hold up (a wall on its ground, disks on a slab) it is
        # statically determined, whatever the hyperstatic forces between the bodies.
        inter, tol = spec.split("=")
        fo, fr = (sum(r.rloc[1] * r.normal[1] - r.rloc[0] * r.normal[0]
                      for rs in cc.values() for r in rs if r.inter == inter) for cc in (co, cr))
        rel = abs(fo - fr) / max(abs(fr), 1e-300)
        ok &= report(f"vertical force of the {inter} contacts", rel <= float(tol),
                     f"{fo:.6e} ours, {fr:.6e} LMGC90's: {rel:.2e} apart (tolerance {float(tol):g})")
    if a.max_rn is not None:
        big = max((abs(r.rloc[1]) for rs in co.values() for r in rs), default=0.0)
        ref_big = max((abs(r.rloc[1]) for rs in cr.values() for r in rs), default=0.0)
        ok &= report("largest |rln/H|", big <= a.max_rn, f"{big:.3e} ours, {ref_big:.3e} LMGC90's "
                     f"(at most {a.max_rn:g})")
    if a.max_x is not None:
        big = max((np.abs(np.asarray(r.x)[..., :2]).max() for r in read_dof_file(last(ours_box, "DOF")).records),
                  default=0.0)
        ref_big = max((np.abs(np.asarray(r.x)[..., :2]).max() for r in read_dof_file(ref / "DOF.LAST").records),
                      default=0.0)
        ok &= report("largest displacement", big <= a.max_x, f"{big:.3e} ours, {ref_big:.3e} LMGC90's "
                     f"(at most {a.max_x:g})")
    for j, tol in enumerate((a.mean_x, a.mean_y)):
        if tol is None:
            continue
        xo, xr = mesh_x(last(ours_box, "DOF"))[:, j].mean(), mesh_x(ref / "DOF.LAST")[:, j].mean()
        rel = abs(xo - xr) / max(abs(xr), 1e-300)
        ok &= report(f"mean node displacement X({j + 1})", rel <= tol,
                     f"{xo:.6e} ours, {xr:.6e} LMGC90's: {rel:.2e} apart (tolerance {tol:g})")
    for spec in a.node or []:
        body, node, dof = (int(x) for x in spec.split(":"))
        xo = node_x(last(ours_box, "DOF"), body, node)[dof - 1]
        xr = node_x(ref / "DOF.LAST", body, node)[dof - 1]
        unit = 10.0 ** (np.floor(np.log10(abs(xr))) - 6)      # 7th significant digit
        err = abs(xo - xr)
        what = f"MAILx {body} node {node}" if node else f"RBDY2 {body}"
        ok &= report(f"X({dof}) of {what}", err <= unit,
                     f"{xo} ours, {xr} LMGC90's: {err:.2e} apart (one printed unit: {unit:.0e})")
    if a.gpv_stress is not None or a.gpv_p is not None or a.gpv_vm is not None:
        go, gr = gauss_values(last(ours_box, "GPV")), gauss_values(ref / "GPV.LAST")
        same = go.keys() == gr.keys() and all(len(go[k]) == len(gr[k]) for k in gr)
        ok &= report("Gauss points", same, f"{sum(len(v) for v in go.values())} lines ours, "
                     f"{sum(len(v) for v in gr.values())} LMGC90's")
        if same:
            so = np.array([ln for v in go.values() for ln in v[0::3]])
            sr = np.array([ln for v in gr.values() for ln in v[0::3]])
            if a.gpv_stress is not None:
                rel = np.abs(so - sr).max() / max(np.abs(sr).max(), 1e-300)
                ok &= report("Gauss-point stress", rel <= a.gpv_stress, f"largest difference {rel:.2e} of the "
                             f"largest stress {np.abs(sr).max():.4e} (tolerance {a.gpv_stress:g})")
            if a.gpv_p is not None:
                po = np.array([ln[4] for v in go.values() for ln in v[2::3]])
                pr = np.array([ln[4] for v in gr.values() for ln in v[2::3]])
                d = np.abs(po - pr).max()
                ok &= report("cumulative plastic strain p", d <= a.gpv_p, f"largest difference {d:.2e} "
                             f"(largest p {pr.max():.4f}, mean {po.mean():.6f} ours, {pr.mean():.6f} LMGC90's; "
                             f"tolerance {a.gpv_p:g})")
            if a.gpv_vm is not None:
                vo = np.array([ln[5] for v in go.values() for ln in v[2::3]])
                vr = np.array([ln[5] for v in gr.values() for ln in v[2::3]])
                rel = np.abs(vo - vr).max() / max(vr.max(), 1e-300)
                ok &= report("von Mises stress", rel <= a.gpv_vm, f"largest difference {rel:.2e} of the largest "
                             f"{vr.max():.4e} (tolerance {a.gpv_vm:g})")
    return 0 if ok else 1


def gauss_values(path):
    """GPV file: {(body, element): array of its Gauss-point lines} (stress, strain,
    internals for J2 elements: 3 lines per point), values as printed."""
    out, key, body = {}, None, 0
    lines = Path(path).read_text().splitlines()
    for k, ln in enumerate(lines):
        if ln.startswith(" MAILx"):
            body = int(ln.split()[1])
        elif ln.startswith("$blmty") and k + 1 < len(lines):
            key = (body, int(lines[k + 1].split()[1]))
            out[key] = []
        elif key and ln.strip() and not ln.startswith(("$", " MECAx", " Q4", " T3", " T6", " Q8", "!")):
            out[key].append([float(v.replace("D", "E")) for v in NUM.findall(ln)])
    return out


def node_x(path, body, node):
    """X of node NODE of meshed body BODY, or of rigid body BODY (node 0)."""
    if node == 0:
        return next(r for r in read_dof_file(path).records if r.model == "RBDY2" and r.number == body).x
    r = next(r for r in read_dof_file(path).records if r.model == "MAILx" and r.number == body)
    return r.x[list(r.nodes).index(node)]


def cl_points(bodies):
    """Number of CLxxx candidate points of BODIES.DAT (each line, continuation lines too)."""
    return sum(len(c.points) for b in read_bodies(bodies) if b.model == "MAILx"
               for c in b.contactors if hasattr(c, "points"))


def cmd_points(a):
    box = Path(a.out) / "OUTBOX"
    recs = [r for rs in contacts(last(box, "Vloc_Rloc")).values() for r in rs if r.inter == "CLALp"]
    per_point = {}
    for r in recs:
        per_point[(r.icdbdy, r.icdtac)] = per_point.get((r.icdbdy, r.icdtac), 0) + 1
    npts = cl_points(Path(a.case) / "DATBOX" / "BODIES.DAT")
    ok = report("one contact per candidate point", max(per_point.values(), default=0) == 1 and len(recs) == npts,
                f"{len(recs)} CLALp contacts for {npts} candidate points, at most "
                f"{max(per_point.values(), default=0)} per point")
    v = np.abs(np.concatenate([r.v for r in read_dof_file(last(box, "DOF")).records])).max()
    ok &= report("at rest", v <= a.vmax, f"largest node speed {v:.3e} m/s (at most {a.vmax:g})")
    return 0 if ok else 1


def cmd_h5(a):
    import h5py
    ok = True
    with h5py.File(Path(a.out) / "OUTBOX" / "fracas.h5", "r") as f:
        for spec in a.expect:
            name, values = spec.split("=", 1)
            want = np.array([float(v) for v in values.split(",")])
            got = np.asarray(f[name][()], dtype=float).ravel()[:len(want)]   # the first values
            good = got.shape == want.shape and np.allclose(got, want, rtol=a.rtol, atol=a.atol)
            ok &= report(name, good, f"{got} against {want} (rtol {a.rtol:g}, atol {a.atol:g})")
    return 0 if ok else 1


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("case"); r.add_argument("out")
    r.add_argument("--fracas", default="fracas")
    r.add_argument("--set", action="append")
    r.add_argument("--deck", help="run this case directory (its DATBOX) instead of CASE_DIR's, "
                   "with CASE_DIR's run.json (e.g. the deck as LMGC90 ships it)")
    c = sub.add_parser("compare")
    c.add_argument("out"); c.add_argument("case")
    c.add_argument("--pairs-differ", type=int, default=0)
    c.add_argument("--sum-rn", type=float)
    c.add_argument("--count-differ", type=int, default=0)
    c.add_argument("--gap-below", type=float, help="compare only the contacts with gapTT below this (both codes)")
    c.add_argument("--unordered", action="store_true",
                   help="a pair is the same whichever side is candidate (polygons: the reference face)")
    c.add_argument("--sum-rn-vertical", type=float,
                   help="summed rln/H |n_y| of all contacts (the weight carried by bed joints) within REL")
    c.add_argument("--force-y", action="append", metavar="INTER=REL",
                   help="summed vertical force (rln n_y + rlt t_y) of the INTER contacts within REL")
    c.add_argument("--max-rn", type=float, help="largest |rln/H| of our contacts at most this")
    c.add_argument("--max-x", type=float, help="largest |X(1)|, |X(2)| of our bodies and nodes at most this")
    c.add_argument("--mean-x", type=float)
    c.add_argument("--mean-y", type=float)
    c.add_argument("--node", action="append", metavar="BODY:NODE:DOF",
                   help="X(DOF) of this MAILx node (NODE 0: of rigid body BODY), to the printed digit")
    c.add_argument("--gpv-stress", type=float, help="largest Gauss-point stress difference / largest stress")
    c.add_argument("--gpv-p", type=float, help="largest difference of p (cumulative plastic strain)")
    c.add_argument("--gpv-vm", type=float, help="largest von Mises difference / largest von Mises")
    q = sub.add_parser("points")
    q.add_argument("case"); q.add_argument("out")
    q.add_argument("--vmax", type=float, default=1e-9)
    h = sub.add_parser("h5")
    h.add_argument("out"); h.add_argument("expect", nargs="+")
    h.add_argument("--atol", type=float, default=0.0)
    h.add_argument("--rtol", type=float, default=1e-12)
    a = p.parse_args(argv)
    return {"run": cmd_run, "compare": cmd_compare, "points": cmd_points, "h5": cmd_h5}[a.cmd](a)


if __name__ == "__main__":
    sys.exit(main())
