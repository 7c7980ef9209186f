#!/usr/bin/python3
"""Time-step study of the small hydrided plate (README.md): the weak and strong decks at
their own step dt and at dt/2 (same final time), with damage within the step (the default)
and with LMGC90's explicit update, and the peak stress, the macro-crack's shares and the
damage energy of each run (tools/hydride/hydride_post.py). Issue 17's target: the peak
stress moves by less than 1 % from dt to dt/2 with the default.

usage: dt_study.py FRACAS OUT_DIR [--schemes implicit,explicit] [--halvings 1] [--bondings weak,strong]
                   [--limit L] [--check TOL]
--limit L: crack_step_limit of every run (default: the decks', 0.25; 0: fixed steps).
--check TOL: exit 1 if a default-scheme peak moves by more than TOL (relative) per halving,
or if a default-scheme run has a step that did not converge (series/converged = 0: the
damage passes that cycled at a round-off stretch before the step factor's bracket, 3 of
600 steps of the weak plate at dt/2).
"""
import argparse
import resource
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
from fracas_tools.scripts import load  # noqa: E402
post = load(HERE.parents[2] / "tools" / "hydride" / "hydride_post.py")

gen = load(HERE / "gen.py")
DT, STEPS = gen.DT, gen.STEPS      # the decks' run control (COMMAND.DAT, written by gen.py)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("fracas")
    ap.add_argument("out")
    ap.add_argument("--schemes", default="implicit,explicit")
    ap.add_argument("--halvings", type=int, default=1)
    ap.add_argument("--check", type=float, default=None)
    ap.add_argument("--bondings", default="weak,strong")
    ap.add_argument("--limit", type=float, default=None)
    a = ap.parse_args()
    bad = 0
    print(f"{'bonding':8s} {'scheme':9s} {'dt (s)':>9s} {'peak (MPa)':>11s} {'change':>8s} "
          f"{'HY_HY':>6s} {'HY_MA':>6s} {'damage (J/m)':>13s} {'CPU (s)':>8s} {'unconv':>6s}")
    for bonding in a.bondings.split(","):
        for scheme in a.schemes.split(","):
            prev = None
            for level in range(a.halvings + 1):
                dt, steps = DT / 2 ** level, STEPS * 2 ** level
                out = Path(a.out) / f"{bonding}_{scheme}_{level}"
                t0 = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime
                subprocess.run([a.fracas, "-q", "--overwrite", "--set", f"cohesive_damage={scheme}",
                                    "--set", f"time_step={dt}", "--set", f"number_of_steps={steps}",
                                    "--set", f"output_hdf5_every={steps}", "--output", str(out),
                                *([] if a.limit is None else ["--set", f"crack_step_limit={a.limit}"]),
                                str(HERE / bonding)], check=True)
                cpu = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime - t0
                s = post.summary(out, deck_dir=HERE / bonding)
                peak = s["peak_stress"]
                change = "" if prev is None else f"{peak / prev - 1:+.2%}"
                if prev is not None and scheme == "implicit" and a.check is not None and abs(peak / prev - 1) > a.check:
                    bad += 1
                    change += " <- off"
                unconverged = s["unconverged_steps"]
                if scheme == "implicit" and a.check is not None and unconverged:
                    bad += 1
                    change += f" <- {unconverged} steps unconverged"
                sh = s["crack"]["shares"]
                print(f"{bonding:8s} {scheme:9s} {dt:9.2e} {peak / 1e6:11.1f} {change:>8s} "
                      f"{sh.get('HY_HY', 0):6.0%} {sh.get('HY_MA', 0):6.0%} "
                      f"{s['energies']['damage']:13.4e} {cpu:8.1f} {unconverged:6d}", flush=True)
                prev = peak
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
