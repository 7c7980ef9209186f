#!/usr/bin/python3
"""Time-step control for cracks (README.md): czm_step_size's glued blocks opened at N
softening lengths per step, run with crack_step_limit L. Asserts, per law and scheme:

* every kept (sub-)step opens a damaging zone by at most L softening lengths
  (series/crack_increment, the quantity the control bounds);
* the steps that damage are cut, and the steps after the break are not cut any more
  (the step grows back; MAC, whose damage goes on as its traction tends to 0: the
  last step is cut into fewer sub-steps than the most cut one);
* the run keeps its time grid: series/time = k time_step (1e-12 relative) and as
  many steps as without control;
* the damage energy equals the law's energy at the final opening (czm_closed_forms,
  written from czm.md independently of the solver) within TOL: 2 % for the default
  scheme (limit 0.5), and for LMGC90's explicit update, which alone books 7.8-290 times
  the law's energy at one softening length per step (czm_step_size/README.md), within
  10 % at the limit 0.05 (its error is first order in the limit: measured 1.03-1.09 at
  0.05, 1.05-1.15 at 0.1, 1.2-1.7 at 0.5).

usage: check.py FRACAS OUT_DIR [--steps N] [--limit L] [--limit-explicit L] [--tol T] [--tol-explicit T]
"""
import argparse
import math
import subprocess
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
from fracas_tools.scripts import load  # noqa: E402
from fracas_tools.results import Results  # noqa: E402
import numpy as np  # noqa: E402

study = load(HERE.parent / "czm_step_size" / "study.py")   # the deck, the law's energy, the interface work
gen, cf = study.gen, study.cf


AFTER = 5    # steps run after the break: the step must have grown back by then
CUTS = 14    # EXPO at 10 of czm_step_size's lengths (its cut-off) a step is 92 of its 1/phi


def run_case(fracas, name, n_soft, out, scheme, limit):
    law = study.deck(name, n_soft, out)
    d_end = study.MAC_END * law.d_peak(1) if law.family == "MAC" else law.d_end(1)
    steps = int(d_end / (n_soft * study.softening_length(law))) + 1 + AFTER
    subprocess.run([fracas, "-q", "--overwrite", "--set", f"cohesive_damage={scheme}",
                    "--set", f"crack_step_limit={limit}", "--set", f"crack_step_cuts={CUTS}",
                    "--set", f"number_of_steps={steps}", str(out)],
                   check=True)
    run = Results(out, bodies=False)
    _, d_end = study.interface_work(run)
    ref = cf.Closed.of(law).damage(d_end, 1) * gen.GLUED
    return run, run.series["damage_dissipated"][-1] / ref


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("fracas")
    ap.add_argument("out")
    ap.add_argument("--laws", default=",".join(gen.LAWS))
    ap.add_argument("--steps", type=float, default=10.0)
    ap.add_argument("--limit", type=float, default=0.5)
    ap.add_argument("--limit-explicit", type=float, default=0.05)
    ap.add_argument("--tol", type=float, default=0.02)
    ap.add_argument("--tol-explicit", type=float, default=0.10)
    a = ap.parse_args()
    bad = []
    print(f"opening {a.steps:g} softening lengths (czm_step_size's) per step, crack_step_limit {a.limit:g} "
          f"(explicit: {a.limit_explicit:g})")
    print(f"{'law':6s} {'scheme':9s} {'damage/law':>10s} {'max inc':>8s} {'cut steps':>9s} "
          f"{'sub-steps':>9s} {'rejected':>8s}")
    for name in a.laws.split(","):
        for scheme, limit, tol in (("implicit", a.limit, a.tol), ("explicit", a.limit_explicit, a.tol_explicit)):
            out = Path(a.out) / f"{name}_{scheme}"
            run, ratio = run_case(a.fracas, name, a.steps, out, scheme, limit)
            s = run.series
            inc, sub, rej = s["crack_increment"], s["substeps"], s["rejected_substeps"]
            damaging = np.diff(np.concatenate([[0.0], s["damage_dissipated"]])) > 0
            steps = len(s["step"])
            dt = gen.DT
            checks = {
                "energy": abs(ratio - 1) <= tol,
                "increments": inc.max() <= limit,
                "cut": sub[damaging].min() >= 2 if damaging.any() else False,
                # MAC's damage never ends (its traction tends to 0): it only grows less cut
                "grown back": sub[-1] < sub.max() if name == "mac" else sub[-1] == 1,
                "time grid": np.allclose(s["time"], dt * np.arange(1, steps + 1), rtol=1e-12, atol=0),
                "complete": run.complete,
            }
            failed = [k for k, ok in checks.items() if not ok]
            bad += [f"{name} {scheme}: {k}" for k in failed]
            print(f"{name:6s} {scheme:9s} {ratio:10.6f} {inc.max():8.3f} {int((sub > 1).sum()):9d} "
                  f"{int(sub.sum()):9d} {int(rej.sum()):8d}" + (f"  <- {', '.join(failed)}" if failed else ""))
    # The unit of the limit (doc/czm.md 9), from the laws' breakpoints (czmlaws, written
    # from czm.md): without control, opened at 0.25 of czm_step_size's lengths per step
    # (peak to separation), a law reports crack_increment = 0.25 x that length over its own
    # softening length at the steps inside its branch (1e-8).
    for name in ("mp3", "mal", "th", "expo"):
        if name not in a.laws.split(","):
            continue
        out = Path(a.out) / f"{name}_unit"
        run, _ = run_case(a.fracas, name, 0.25, out, "implicit", 0.0)
        law = gen.LAWS[name][1]
        bp = law.breakpoints(1)
        if law.family == "EXPO":
            _, s_, g_, di = law._mode(1)
            own = (g_ - 0.5 * s_ * di) / s_              # 1/phi
        else:
            own = bp[-1] - bp[-2]                        # the decay to separation (TH: after its plateau)
        want = 0.25 * (bp[-1] - bp[0]) / own
        inc = run.series["crack_increment"].max()
        ok = abs(inc / want - 1) <= 1e-8
        bad += [] if ok else [f"{name}: crack_increment {inc}, expected {want}"]
        print(f"{name:6s} no control, 0.25 lengths per step: largest crack_increment {inc:.12f} "
              f"(expected {want:.12f})" + ("" if ok else "  <- off"))
    # A limit that cannot be met (one halving allowed) with --fail-unconverged: exit status 3.
    out = Path(a.out) / "unmet"
    study.deck("mp3", a.steps, out)
    rc = subprocess.run([a.fracas, "-q", "--overwrite", "--fail-unconverged", "--set", f"crack_step_limit={a.limit}",
                         "--set", "crack_step_cuts=1", str(out)], capture_output=True, text=True)
    ok = rc.returncode == 3 and "crack_step_limit" in rc.stderr
    bad += [] if ok else [f"limit not met: exit status {rc.returncode}, expected 3"]
    print(f"limit not met (crack_step_cuts 1) with --fail-unconverged: exit status {rc.returncode}"
          + ("" if ok else "  <- expected 3"))
    print("== crack_step_control: " + ("all checks passed" if not bad else "FAILED: " + "; ".join(bad)))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
