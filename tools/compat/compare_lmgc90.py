#!/usr/bin/env python3
"""Compare Fracas OUTBOX files with those LMGC90 wrote for the same DATBOX.

  compare_lmgc90.py exact OURS_OUTBOX N_OURS REF_OUTBOX N_REF [--units U] [--xtol A] [--vtol R] [--rtol R]
      DOF.OUT and Vloc_Rloc.OUT of one write, body by body and contact by contact, to
      the printed precision: both files print 7 significant digits, so each X, V and
      reaction must agree within U units (default 1) of the 7th digit of the larger of
      the two values, i.e. the two roundings of one number. Values at round-off level
      (below 1e-12 times the largest of their kind, or below xfloor, vfloor, rfloor:
      reactions of bodies merely touching) count as zero. --xtol (absolute), --vtol or --rtol
      (relative to the largest of their kind) replace the printed precision for one
      quantity where the two codes legitimately differ more (a non-unique tangential
      split, a reported force convention), with the reason in the CMakeLists.txt.
      Also: the same set of interactions, the same statuses for contacts carrying a
      reaction, cohesive internals to itol (relative).
  compare_lmgc90.py stats OURS_OUTBOX N_OURS REF_OUTBOX N_REF [--ctol R] [--htol A]
                   [--cxtol A] [--cytol A]
      For chaotic granular flow, where per-body values are meaningless: number
      of body pairs with a reaction within max(ctol relative, 2 sqrt(count)), mean body height
      within htol (absolute, m), and the same total count of bodies. With --cxtol / --cytol
      the mean displacement of the moving bodies along x / y (the centroid of the pile)
      replaces the height check; tolerances from the chaos floor (chaos_floor.py outbox).
Prints one line per quantity and exits 1 if any fails.
"""
import argparse
import math
import os
import sys

from fracas_tools.datbox import read_dof  # noqa: E402
from fracas_tools.outbox import read_vloc_rloc  # noqa: E402

def read_vloc(path):
    """Vloc_Rloc.OUT.n -> dict key -> dict(status, rlt, rln, internals, coo); key = (type,
    cd body, cd contactor, cd vertex (polygon candidates, else 0), an body, an contactor).
    Read by fracas_tools.outbox (the one reader of those records)."""
    out = {}
    for r in read_vloc_rloc(path).records:
        cdver = r.cdver if r.inter.startswith("PL") and r.cdver is not None else 0
        key = (r.inter, r.icdbdy, r.icdtac, cdver, r.ianbdy, r.iantac)
        out[key] = dict(status=r.status, rlt=float(r.rloc[0]), rln=float(r.rloc[1]),
                        internals=[] if r.internals is None else [float(x) for x in r.internals],
                        coo=None if r.coor is None else [float(x) for x in r.coor[:2]])
    return out


results = []


def report(name, ours, ref, err, tol, ok):
    results.append(ok)
    print(f"{'PASS' if ok else 'FAIL'} {name}: ours={ours} ref={ref} err={err:.3e} tol={tol:.3e}")


def printed_unit(x):
    """One unit of the 7th significant digit of x (0 for 0): what D14.7 resolves."""
    x = abs(x)
    return 10.0 ** (math.floor(math.log10(x)) - 6) if x > 0 else 0.0


def worst_units(pairs, floor):
    """Largest |x - y| in printed units of max(|x|, |y|); values under floor count as 0."""
    worst, where = 0.0, None
    for key, x, y in pairs:
        if abs(x) < floor and abs(y) < floor:
            continue
        # (1 + 1e-6): the difference of two printed values is one unit up to binary round-off
        e = abs(x - y) / max(printed_unit(x), printed_unit(y), floor) / (1.0 + 1e-6)
        if e > worst:
            worst, where = e, (key, x, y)
    return worst, where


def exact(a):
    _, _, ours = read_dof(os.path.join(a.ours, f"DOF.OUT.{a.n_ours}"))
    _, _, ref = read_dof(os.path.join(a.ref, f"DOF.OUT.{a.n_ref}"))
    report("same bodies", len(ours), len(ref), float(len(set(ours) ^ set(ref))), 0.0, set(ours) == set(ref))
    for j, name, tol, floor in ((0, "X", a.xtol, a.xfloor), (1, "V", a.vtol, a.vfloor)):
        scale = max(abs(v[j]).max() for v in ref.values())
        if tol is None:
            pairs = [((b, k), ours[b][j][k], ref[b][j][k]) for b in ref for k in range(3)]
            e, where = worst_units(pairs, max(1e-12 * scale, floor))
            report(f"{name}: worst |{name} - {name}ref| in printed units (7 digits)",
                   where[1] if where else "", where[2] if where else "", e, a.units, e <= a.units)
        elif j == 0:
            ex = max(abs(ours[b][0] - ref[b][0]).max() for b in ref)
            report("max |X - Xref|", "", "", ex, tol, ex <= tol)
        else:
            vmax = max(scale, a.vfloor)
            ev = max(abs(ours[b][1] - ref[b][1]).max() for b in ref)
            report("max |V - Vref| / max|Vref|", "", "", ev / vmax, tol, ev / vmax <= tol)
    vo = read_vloc(os.path.join(a.ours, f"Vloc_Rloc.OUT.{a.n_ours}"))
    vr = read_vloc(os.path.join(a.ref, f"Vloc_Rloc.OUT.{a.n_ref}"))
    report("same interactions", len(vo), len(vr), float(len(set(vo) ^ set(vr))), 0.0, set(vo) == set(vr))
    common = set(vo) & set(vr)
    # Reactions below rfloor (N) are round-off (bodies merely touching).
    rmax = max([max(abs(r["rlt"]), abs(r["rln"])) for r in vr.values()] + [a.rfloor])
    if a.rtol is None:
        pairs = [((k, c), vo[k][c], vr[k][c]) for k in common for c in ("rlt", "rln")]
        e, where = worst_units(pairs, max(1e-12 * rmax, a.rfloor))
        report("R: worst |R - Rref| in printed units (7 digits)", where[1] if where else "",
               where[2] if where else "", e, a.units, e <= a.units)
        rel = a.units * 1e-6
    else:
        er = max([max(abs(vo[k]["rlt"] - vr[k]["rlt"]), abs(vo[k]["rln"] - vr[k]["rln"])) for k in common] + [0.0])
        report("max |R - Rref| / max|Rref|", "", "", er / rmax, a.rtol, er / rmax <= a.rtol)
        rel = a.rtol
    # Contact points of a disk (where both files give them): LMGC90 puts them on
    # the candidate disk's surface (DKDKx) or on the polygon's boundary (DKPLx).
    # (Polygon pairs' points are not compared.)
    with_coo = [k for k in common if vo[k]["coo"] and vr[k]["coo"] and k[0].startswith("DK")]
    if with_coo:
        cmax = max(abs(c) for k in with_coo for c in vr[k]["coo"])
        pairs = [((k, d), vo[k]["coo"][d], vr[k]["coo"][d]) for k in with_coo for d in (0, 1)]
        e, where = worst_units(pairs, 1e-12 * cmax)
        report("contact points: worst |coo - cooref| in printed units (7 digits)", where[1] if where else "",
               where[2] if where else "", e, a.units, e <= a.units)
    # Statuses only mean something where the reaction is not negligible.
    bad = [k for k in common if abs(vr[k]["rln"]) > max(rel * rmax, a.rfloor) and vo[k]["status"] != vr[k]["status"]]
    report("statuses of loaded contacts", len(common) - len(bad), len(common), float(len(bad)), 0.0, not bad)
    # Cohesive internals (L, ut, un, beta, TPSini): relative to each value.
    with_int = [k for k in common if vr[k]["internals"]]
    if with_int:
        ei = max(abs(x - y) / max(abs(y), 1e-30) if abs(y) > 1e-12 else abs(x - y)
                 for k in with_int for x, y in zip(vo[k]["internals"], vr[k]["internals"]))
        report("cohesive internals (L, ut, un, beta, TPSini), relative", "", "", ei, a.itol, ei <= a.itol)


def stats(a):
    _, _, ours = read_dof(os.path.join(a.ours, f"DOF.OUT.{a.n_ours}"))
    _, _, ref = read_dof(os.path.join(a.ref, f"DOF.OUT.{a.n_ref}"))
    report("same bodies", len(ours), len(ref), float(len(set(ours) ^ set(ref))), 0.0, set(ours) == set(ref))
    free = [b for b in ref if abs(ref[b][0]).max() > 0 or abs(ref[b][1]).max() > 0]
    if a.cxtol is None and a.cytol is None:
        ho = sum(ours[b][0][1] for b in free) / len(free)
        hr = sum(ref[b][0][1] for b in free) / len(free)
        report("mean vertical displacement of moving bodies (m)", f"{ho:.5f}", f"{hr:.5f}", abs(ho - hr), a.htol,
               abs(ho - hr) <= a.htol)
    for k, name, tol in ((0, "x", a.cxtol), (1, "y", a.cytol)):
        if tol is None:
            continue
        co = sum(ours[b][0][k] for b in free) / len(free)
        cr = sum(ref[b][0][k] for b in free) / len(free)
        report(f"mean {name} displacement of the moving bodies (m)", f"{co:.5f}", f"{cr:.5f}", abs(co - cr), tol,
               abs(co - cr) <= tol)
    vo = read_vloc(os.path.join(a.ours, f"Vloc_Rloc.OUT.{a.n_ours}"))
    vr = read_vloc(os.path.join(a.ref, f"Vloc_Rloc.OUT.{a.n_ref}"))
    # Body pairs in contact (a face-to-face polygon pair counts once, whether it
    # carries one or two contact points at this instant).
    co = len({(k[1], k[4]) for k, r in vo.items() if r["rln"] != 0.0})
    cr = len({(k[1], k[4]) for k, r in vr.items() if r["rln"] != 0.0})
    # Allowed difference: ctol relative, but not below 2 sqrt(count) (counting
    # noise of a small chaotic pile).
    tol = max(a.ctol * cr, 2.0 * cr ** 0.5)
    report("body pairs with a reaction", co, cr, abs(co - cr), tol, abs(co - cr) <= tol)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("mode", choices=["exact", "stats"])
    p.add_argument("ours")
    p.add_argument("n_ours", type=int)
    p.add_argument("ref")
    p.add_argument("n_ref", type=int)
    p.add_argument("--units", type=float, default=1.0, help="printed units (7th digit) allowed")
    p.add_argument("--xtol", type=float, default=None)
    p.add_argument("--vtol", type=float, default=None)
    p.add_argument("--rtol", type=float, default=None)
    p.add_argument("--xfloor", type=float, default=1e-15, help="positions below this are round-off (m, rad)")
    p.add_argument("--vfloor", type=float, default=1e-12, help="velocities below this are round-off")
    p.add_argument("--rfloor", type=float, default=1e-9)
    p.add_argument("--itol", type=float, default=1e-6)
    p.add_argument("--ctol", type=float, default=0.15)
    p.add_argument("--htol", type=float, default=0.005)
    p.add_argument("--cxtol", type=float, default=None)
    p.add_argument("--cytol", type=float, default=None)
    a = p.parse_args()
    exact(a) if a.mode == "exact" else stats(a)
    n_fail = results.count(False)
    print(f"{results.count(True)} passed, {n_fail} failed")
    sys.exit(1 if n_fail else 0)


if __name__ == "__main__":
    main()
