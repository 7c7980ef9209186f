#!/usr/bin/python3
"""Chaos floor of a regression case: how much its tags move when only the order of the
NLGS updates changes (same deck, same solver settings, same tolerance: a round-off-level
perturbation that the granular chaos amplifies). No tolerance can be tighter than this.

    build/release/bin/fracas-python tools/regression/chaos_floor.py --fracas BIN --work DIR CASE_DIR
        [--variants reversed shuffled:1 shuffled:2 shuffled:3 shuffled:4 colored] [--jobs 2]

Runs CASE_DIR with its own settings (the reference run) and once per variant
(nlgs_order, and nlgs_seed for shuffled), computes the tags of tagged.py for each, and
prints per tag: the reference value, the spread (largest |variant - reference|), the
spread relative to the reference, the tolerance of CASE_DIR/tolerances.txt and how many
times the spread it allows. doc/regression.md explains how tolerances follow from it.
"""

import argparse
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import tagged  # noqa: E402


def run(fracas, case, out, variant):
    sets = []
    if variant != "reference":
        order, _, seed = variant.partition(":")
        sets = ["--set", f"nlgs_order={order}"] + (["--set", f"nlgs_seed={seed}"] if seed else [])
    cmd = [fracas, "-q", "--overwrite", "--output", str(out)] + sets + [str(case)]
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        raise SystemExit(f"chaos_floor.py: {' '.join(cmd)} failed:\n{r.stdout}")
    return tagged.compute_tags(out, case)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--fracas", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--variants", nargs="+",
                   default=["reversed", "shuffled:1", "shuffled:2", "shuffled:3", "shuffled:4", "colored"])
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("case")
    a = p.parse_args()
    case = Path(a.case)
    work = Path(a.work)
    names = ["reference"] + a.variants
    with ThreadPoolExecutor(max_workers=a.jobs) as ex:
        tags = list(ex.map(lambda v: run(a.fracas, case, work / v.replace(":", "_"), v), names))
    ref = tags[0]
    tol = tagged.read_tolerances(case / "tolerances.txt") if (case / "tolerances.txt").exists() else {}
    print(f"{'tag':34s} {'reference':>14s} {'spread':>11s} {'rel':>8s} {'tolerance':>20s} {'x spread':>8s}")
    for k, v in ref.items():
        if isinstance(v, str):
            continue
        spread = max(abs(t[k] - v) for t in tags[1:])
        rel = spread / abs(v) if v else 0.0
        if k in tol:
            ab, rl = tol[k]
            allowed = ab + rl * abs(v)
            ts = f"{ab:g} + {rl:g} rel"
            times = f"{allowed / spread:.1f}" if spread else "-"
        else:
            ts, times = "-", "-"
        print(f"{k:34s} {v:14.6g} {spread:11.4g} {rel:8.2%} {ts:>20s} {times:>8s}")


if __name__ == "__main__":
    main()
