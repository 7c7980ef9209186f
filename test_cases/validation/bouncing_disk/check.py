#!/usr/bin/python3
"""Check the bouncing_disk run against Newton's restitution law (see README.md).

usage: check.py [RUN_DIR]   (RUN_DIR holds OUTBOX/fracas.h5; default: this folder)
Prints one line per quantity and exits 1 if any check fails.
"""
import math
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
import gen          # noqa: E402  (the deck parameters)
from fracas_tools import valtools     # noqa: E402

DISK, WALL = 2, 1           # body serial numbers (gen.py order)


def exact_apexes(k_max):
    """Exact apex heights e^(2k) h0 and times of apex k = 1..k_max."""
    s0 = math.sqrt(2.0 * gen.G * gen.H0)
    t_impact = math.sqrt(2.0 * gen.H0 / gen.G)
    out = []
    for k in range(1, k_max + 1):
        v = gen.E ** k * s0
        out.append((t_impact + v / gen.G, gen.E ** (2 * k) * gen.H0))
        t_impact += 2.0 * v / gen.G
    return out


def apex_tolerance(k, h):
    """A-priori bound of the Moreau-Jean (theta = 0.5) error on apex k (README.md):
    each impact adds at most (1-e)(2+e)/2 h s_j (s_j impact speed), earlier errors are
    scaled by e^2 per bounce; plus the sampling of the apex at step times, g h^2 / 8."""
    e, s0 = gen.E, math.sqrt(2.0 * gen.G * gen.H0)
    c = 0.5 * (1.0 - e) * (2.0 + e)
    tol = sum(e ** (2 * (k - j)) * c * h * e ** (j - 1) * s0 for j in range(1, k + 1))
    return tol + gen.G * h * h / 8.0


def analyse(res):
    """Quantities measured from a run: bottom height, apexes, rest time, energy."""
    h, g, e = res.h, gen.G, gen.E
    t = res.time
    y = res.position[:, DISK - 1, 1]
    vy = res.V[:, DISK - 1, 1]
    bottom = y - gen.R - gen.WALL_TOP
    rn = np.array([res.reaction_between(i, DISK, WALL) for i in range(len(t))])
    # apexes: local maxima of the bottom height during flights
    apex = [(t[i], bottom[i]) for i in range(1, len(t) - 1)
            if bottom[i] >= bottom[i - 1] and bottom[i] > bottom[i + 1] and bottom[i] > g * h * h]
    # rest: from then on |vy| <= g h (a bounce slower than that is shorter than 2 steps)
    moving = np.nonzero(np.abs(vy) > g * h)[0]
    i_rest = moving[-1] + 1 if len(moving) else 0
    t_rest = t[i_rest] if i_rest < len(t) else math.inf
    # mechanical energy (J per m of thickness): kinetic - work of gravity (E(0) = 0, at rest)
    ke = res.series["kinetic_energy"]
    wg = res.series["work_gravity"]
    energy = np.concatenate([[0.0], ke - wg])
    dE = np.diff(energy)
    return dict(t=t, bottom=bottom, vy=vy, rn=rn, apex=apex, t_rest=t_rest, i_rest=i_rest,
                energy=energy, dE=dE)


def main():
    run_dir = valtools.run_dir_from_argv(HERE)
    res = valtools.Results(run_dir)
    a = analyse(res)
    h, g, e = res.h, gen.G, gen.E
    m = res.mass[DISK - 1]
    ck = valtools.Checker("bouncing_disk")

    # 1. apex heights after bounces 1..4
    exact = exact_apexes(4)
    for k in range(1, 5):
        if len(a["apex"]) < k:
            ck.true(f"apex {k} found", False)
            continue
        ck.close(f"apex {k} (m) = e^{2 * k} h0", a["apex"][k - 1][1], exact[k - 1][1],
                 apex_tolerance(k, h), note="a-priori O(h) bound")
    # time of apex 1: the impact is applied in the step whose mid-step gap is <= 0, so it
    # lands within +-h/2 of the exact contact time; the apex time error is then in
    # [(1-e) h/2, (3+e) h/2], plus +-h/2 for sampling the apex at step times (README.md)
    ck.close("apex 1 time (s)", a["apex"][0][0], exact[0][0], (2.0 + 0.5 * e) * h,
             note="(2 + e/2) h")

    # 2. rest time
    t_inf = math.sqrt(2.0 * gen.H0 / g) * (1.0 + e) / (1.0 - e)
    s0 = math.sqrt(2.0 * g * gen.H0)
    n_bounces = math.ceil(math.log(g * h / s0) / math.log(e))   # bounces faster than g h
    tol_rest = (0.5 * n_bounces + 2.0 / (1.0 - e)) * h
    ck.close("rest time (s) = sqrt(2h0/g)(1+e)/(1-e)", a["t_rest"], t_inf, tol_rest,
             note=f"({n_bounces}/2 + 2/(1-e)) h")

    # 3. energy: conserved in flight, lost at each impact, never gained before rest
    e_scale = m * g * gen.H0
    before = a["dE"][: a["i_rest"]]
    ck.at_most("max energy increase per step before rest / (m g h0)",
               max(0.0, before.max()) / e_scale, 1e-12, note="round-off")
    flights = []          # energy of each flight (constant while rn == 0)
    cur = []
    for i in range(a["i_rest"]):
        if a["rn"][i] == 0.0:
            cur.append(a["energy"][i + 1])
        elif cur:
            flights.append(cur)
            cur = []
    spread = max((max(f) - min(f)) for f in flights) / e_scale
    ck.at_most("energy drift within a flight / (m g h0)", spread, 1e-12, note="round-off")
    fe = np.array([f[-1] for f in flights])     # energy per flight, relative to rest at h0 drop
    drops = np.diff(fe)
    ck.true(f"flight energies strictly decreasing ({len(fe)} flights)", bool(np.all(drops < 0.0)),
            ours=f"{len(fe)} flights")
    # after rest the Newton law with theta = 0.5 may add at most (1-e)(gh)^2/(8(1+e)) per
    # unit mass in one step while the velocity decays by e per step (README.md)
    bound = (1.0 - e) * (g * h) ** 2 / (8.0 * (1.0 + e)) * m
    ck.at_most("max energy increase per step at rest / (m g h0)",
               max(0.0, a["dE"][a["i_rest"]:].max()) / e_scale, bound / e_scale * (1 + 1e-6),
               note="(1-e)(gh)^2/(8(1+e)) g^-1 h0^-1")

    # 4. final state: at rest on the wall, penetration below one step of gravity
    ck.at_most("final |vy| (m/s)", abs(a["vy"][-1]), 1e-12)
    ck.at_most("final penetration (m)", max(0.0, -a["bottom"][-1]), g * h * h, note="g h^2")
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
