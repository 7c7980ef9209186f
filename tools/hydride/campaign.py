#!/usr/bin/python3
"""The hydrided-plate campaign: seeds x bonding x element size, each case generated
(hydride_plate.py), run (fracas) and summarised (hydride_post.py) in its own folder.

    # everything on this machine, two runs at a time
    build/release/bin/fracas-python tools/hydride/campaign.py all --root runs/hydride --jobs 2
    # one case of the grid (a SLURM array task: tools/hydride/slurm_array.sh)
    build/release/bin/fracas-python tools/hydride/campaign.py one --root runs/hydride --index $SLURM_ARRAY_TASK_ID
    # the list of cases (index seed bonding h)
    build/release/bin/fracas-python tools/hydride/campaign.py list
    # a dry run of one case: its deck generated and checked (fracas --check), nothing run
    build/release/bin/fracas-python tools/hydride/campaign.py one --root /tmp/dry --index 0 --dry-run
    # summaries again (summary.json, crack.png) of the cases already run, nothing rerun
    build/release/bin/fracas-python tools/hydride/campaign.py summarize --root runs/hydride

Case folders are ROOT/<bonding>_h<h in nm>_s<seed>/ with DATBOX/, OUTBOX/, POSTPRO/,
DISPLAY/, hydrides.json, summary.json (hydride_post.summary plus the wall and processor
times of the run) and crack.png. tools/hydride/gather.py collects ROOT into one table
and figures. A case whose summary.json exists is skipped (rerun: --force).

Time step and length of a run follow the element size: dt = courant * h / c_p (c_p the
matrix P-wave speed, plane strain) and the run lasts final_time.
"""
import argparse
import itertools
import json
import math
import os
import shutil
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT_DIR = HERE.parents[1]
from fracas_tools.scripts import load  # noqa: E402
plate = load(HERE / "hydride_plate.py")

DEFAULTS = dict(seeds=[1, 2, 3, 4, 5], bondings=["weak", "strong"], sizes=[1.0e-6, 0.7e-6],
                final_time=160e-9, courant=1.0, output_time=10e-9, vtk_time=20e-9)


def grid(seeds, bondings, sizes):
    """The cases in array order: (seed, bonding, h), element size slowest."""
    return [(s, b, h) for h, b, s in itertools.product(sizes, bondings, seeds)]


def case_name(seed, bonding, h):
    return f"{bonding}_h{round(h * 1e9)}_s{seed}"


def p_wave_speed(m=plate.Matrix()):
    lam = m.young * m.poisson / ((1 + m.poisson) * (1 - 2 * m.poisson))
    mu = m.young / (2 * (1 + m.poisson))
    return math.sqrt((lam + 2 * mu) / m.density)


def find_fracas(given=None):
    for c in (given, os.environ.get("FRACAS_BIN"), ROOT_DIR / "build/release/bin/fracas"):
        if c and Path(c).is_file():
            return str(c)
    found = shutil.which("fracas")
    if found:
        return found
    raise SystemExit("fracas not found: build it (cmake --build --preset release) or pass --fracas")


def case_settings(h, a):
    dt = a.courant * h / p_wave_speed()
    return dict(dt=dt, steps=int(round(a.final_time / dt)), every=max(1, int(round(a.output_time / dt))),
                vtk=max(1, int(round(a.vtk_time / dt))))


def generate_case(root, seed, bonding, h, a):
    """The deck of one case (gmsh: main thread only). None when already summarised."""
    d = Path(root) / case_name(seed, bonding, h)
    if (d / "summary.json").is_file() and not a.force:
        return None
    if d.exists():
        shutil.rmtree(d)
    c = case_settings(h, a)
    geo = plate.Geometry(width=a.width, height=a.width)
    plate.generate(d, seed, h, bonding, geo, plate.Loading(velocity=a.velocity), time_step=c["dt"],
                   steps=c["steps"], output_every=c["every"], vtk_every=c["vtk"])
    return d


def run_fracas(d, fracas):
    """Run fracas on case folder d; returns (wall seconds, processor seconds of the run)."""
    t0 = time.time()
    with open(d / "run.log", "w") as log:
        p = subprocess.Popen([fracas, "-q", "--overwrite", str(d)], stdout=log, stderr=subprocess.STDOUT)
        _, status, usage = os.wait4(p.pid, 0)
    wall = time.time() - t0
    code = os.waitstatus_to_exitcode(status)
    if code != 0:
        raise RuntimeError(f"{d}: fracas failed (exit {code}), see {d / 'run.log'}")
    (d / "timing.json").write_text(json.dumps(dict(wall_seconds=wall, cpu_seconds_process=usage.ru_utime + usage.ru_stime,
                                                   load_average=os.getloadavg()[0])) + "\n")
    return wall, usage.ru_utime + usage.ru_stime


def summarize_case(d, a):
    """summary.json (hydride_post.summary, the timing and the run settings) and crack.png."""
    import hydride_post as post
    s = post.summary(d)
    s.update(json.loads((d / "timing.json").read_text()))
    c = case_settings(s["h"], a)
    s.update(dt=c["dt"], final_time=a.final_time, velocity=a.velocity)
    (d / "summary.json").write_text(json.dumps(s, indent=1) + "\n")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(5, 5))
        post.draw(post.PlateRun(d), ax, title=f"{s['bonding']} bonding, seed {s['seed']}, h {s['h'] * 1e6:.2g} µm")
        fig.tight_layout()
        fig.savefig(d / "crack.png", dpi=120)
        plt.close(fig)
    except Exception as e:          # a picture is not worth failing the case
        print(f"{d}: no picture ({e})", file=sys.stderr)
    return s


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("what", choices=("all", "one", "list", "summarize"))
    p.add_argument("--root", default="runs/hydride")
    p.add_argument("--index", type=int, help="case index for 'one' (SLURM_ARRAY_TASK_ID)")
    p.add_argument("--seeds", type=int, nargs="+", default=DEFAULTS["seeds"])
    p.add_argument("--bondings", nargs="+", default=DEFAULTS["bondings"])
    p.add_argument("--sizes", type=float, nargs="+", default=DEFAULTS["sizes"], help="element sizes h (m)")
    p.add_argument("--width", type=float, default=plate.Geometry.width, help="plate side (m)")
    p.add_argument("--velocity", type=float, default=plate.Loading.velocity)
    p.add_argument("--final-time", type=float, default=DEFAULTS["final_time"])
    p.add_argument("--courant", type=float, default=DEFAULTS["courant"], help="dt = courant h / c_p")
    p.add_argument("--output-time", type=float, default=DEFAULTS["output_time"])
    p.add_argument("--vtk-time", type=float, default=DEFAULTS["vtk_time"])
    p.add_argument("--jobs", type=int, default=1)
    p.add_argument("--fracas")
    p.add_argument("--force", action="store_true")
    p.add_argument("--dry-run", action="store_true",
                   help="generate the decks and check them with fracas --check, run nothing")
    a = p.parse_args(argv)
    cases = grid(a.seeds, a.bondings, a.sizes)
    if a.what == "list":
        for k, c in enumerate(cases):
            print(k, *c, case_name(*c))
        return 0
    if a.what == "summarize":
        for c in cases:
            d = Path(a.root) / case_name(*c)
            if (d / "timing.json").is_file():
                summarize_case(d, a)
                print(f"{case_name(*c)}: summarised", flush=True)
        return 0
    fracas = find_fracas(a.fracas)
    Path(a.root).mkdir(parents=True, exist_ok=True)
    if a.what == "one":
        if a.index is None or not 0 <= a.index < len(cases):
            raise SystemExit(f"--index: 0 to {len(cases) - 1}")
        cases = [cases[a.index]]

    # decks first (gmsh in the main thread), then the runs (jobs at a time), then the summaries
    todo = [(c, generate_case(a.root, *c, a)) for c in cases]
    todo = [(c, d) for c, d in todo if d is not None]
    if a.dry_run:          # the interpreter, gmsh, the generator and fracas work: nothing is run
        for c, d in todo:
            p = subprocess.run([fracas, "--check", str(d)], capture_output=True, text=True)
            if p.returncode != 0:
                raise SystemExit(f"{d}: fracas --check failed: {p.stderr.strip()}")
            st = case_settings(c[2], a)
            print(f"{case_name(*c)}: {p.stdout.strip()}, dt {st['dt']:.3g} s; deck in {d}", flush=True)
        return 0

    def run(item):
        c, d = item
        wall, cpu = run_fracas(d, fracas)
        print(f"{case_name(*c)}: ran in {wall:.0f} s wall, {cpu:.0f} s processor", flush=True)

    if a.jobs > 1:
        with ThreadPoolExecutor(a.jobs) as pool:
            list(pool.map(run, todo))
    else:
        for item in todo:
            run(item)
    for c, d in todo:
        s = summarize_case(d, a)
        cr = s["crack"]
        print(f"{case_name(*c)}: {'across' if cr['separated'] else 'ligament %.1f µm left' % (1e6 * cr['ligament'])}"
              ", shares " + " ".join(f"{k} {100 * v:.0f}%" for k, v in cr["shares"].items()), flush=True)
    return 0


if __name__ == "__main__":
    from fracas_tools.cli import run_main  # bad input: a message, not a traceback
    sys.exit(run_main(main, "campaign.py"))
