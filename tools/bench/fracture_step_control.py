#!/usr/bin/python3
"""Fracture benchmark: speed against error of fixed and controlled time steps.

For the fracture cases whose answers moved with the time step (issue 17), run each at its
own step h and at h/2, h/4, ... (fixed steps), and at h with the time-step control for
cracks (run control crack_step_limit L: a step in which a damaging cohesive zone's jump
changes by more than L softening lengths is done again in halves, doc/czm.md §9), and
measure against the CPU time of the run:

  hydride_weak, hydride_strong  the small hydrided plate (test_cases/validation/
                                hydrided_plate): peak nominal stress (MPa) and damage
                                energy (J/m) (tools/hydride/hydride_post.py)
  dcb                           the double cantilever beam, quick mesh (test_cases/
                                validation_fracture/dcb): critical load (N/m) and damage
                                energy per crack growth / G_c (its check.py)
  kalthoff                      Kalthoff-Winkler, quick mesh: the crack angle (deg)

The error of a run is its distance to the finest run of the case (the smallest fixed
step with the control at the smallest limit); dcb's energy is also compared with G_c.

    build/release/bin/fracas-python tools/bench/fracture_step_control.py [--cases a,b] [--work DIR]
        [--fracas BIN] [--csv FILE] [--plot PNG]

Finished runs in --work (default /tmp/fracas_fracture_bench) are reused. About 40 minutes
of CPU for all cases. Results and their reading: doc/benchmarks.md section 7.
"""
import argparse
import csv
import resource
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

FRACTURE = ROOT / "test_cases" / "validation_fracture"
HYDRIDE = ROOT / "test_cases" / "validation" / "hydrided_plate"


def checker_value(text, name):
    """The measured value of the Checker line that starts with name."""
    for line in text.splitlines():
        if name in line:
            for token in line.split(name, 1)[1].split():
                try:
                    return float(token)
                except ValueError:
                    continue
    raise ValueError(f"no line '{name}' in the check's output:\n{text}")


def hydride_metrics(bonding):
    def metrics(run_dir):
        from fracas_tools.scripts import load
        post = load(ROOT / "tools" / "hydride" / "hydride_post.py")
        s = post.summary(run_dir, deck_dir=HYDRIDE / bonding)
        return {"peak stress (MPa)": s["peak_stress"] / 1e6, "damage energy (J/m)": s["energies"]["damage"]}
    return metrics


def check_metrics(case, variant, names):
    def metrics(run_dir):
        out = subprocess.run([sys.executable, str(FRACTURE / case / "check.py"), str(run_dir), variant],
                             capture_output=True, text=True).stdout
        return {label: checker_value(out, name) for label, name in names.items()}
    return metrics


# name: (deck maker, base steps known from the deck, fixed halvings, control limits, metrics)
CASES = {
    "hydride_weak": dict(deck=lambda w: HYDRIDE / "weak", halvings=3, limits=[0.25, 0.1],
                         metrics=hydride_metrics("weak")),
    "hydride_strong": dict(deck=lambda w: HYDRIDE / "strong", halvings=3, limits=[0.25, 0.1],
                           metrics=hydride_metrics("strong")),
    "dcb": dict(deck=lambda w: generated("dcb", "quick", w), halvings=2, limits=[0.25, 0.1],
                metrics=check_metrics("dcb", "quick", {"critical load (N/m)": "critical load (N/m)",
                                                       "energy per growth / G_c": "damage dissipated per growth"})),
    "kalthoff": dict(deck=lambda w: generated("kalthoff", "quick", w), halvings=1, limits=[0.25],
                     metrics=check_metrics("kalthoff", "quick", {"crack angle (deg)": "crack angle from the notch"})),
}


def generated(case, variant, work):
    """The case's deck, written by its gen.py into work/deck_<case> once."""
    deck = work / f"deck_{case}"
    if not (deck / "DATBOX").is_dir():
        subprocess.run([sys.executable, str(FRACTURE / case / "gen.py"), str(deck), variant], check=True)
    return deck


def run_control(run_dir):
    """time_step and number_of_steps a finished run used (fracas.h5 /run)."""
    import h5py
    with h5py.File(run_dir / "OUTBOX" / "fracas.h5", "r") as f:
        r = f["run"].attrs
        return float(r["time_step"]), int(r["number_of_steps"])


def run(fracas, deck, out, sets):
    """Run once (reused when finished); CPU seconds of fracas (from fracas.h5's timings)."""
    h5 = out / "OUTBOX" / "fracas.h5"
    if not h5.exists():
        t0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        cmd = [fracas, "-q", "--overwrite", "--output", str(out)]
        for s in sets:
            cmd += ["--set", s]
        subprocess.run(cmd + [str(deck)], check=True)
        t1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        (out / "cpu_seconds").write_text(f"{t1.ru_utime + t1.ru_stime - t0.ru_utime - t0.ru_stime:.3f}\n")
    return float((out / "cpu_seconds").read_text())


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--work", default="/tmp/fracas_fracture_bench")
    ap.add_argument("--fracas", default=str(ROOT / "build" / "release" / "bin" / "fracas"))
    ap.add_argument("--csv", default=None)
    ap.add_argument("--plot", default=None)
    ap.add_argument("--from-csv", default=None, help="plot the rows of a CSV written before; nothing run")
    a = ap.parse_args()
    if a.from_csv:
        with open(a.from_csv) as f:
            rows = [dict(r, cpu_s=float(r["cpu_s"]), rel_error=float(r["rel_error"])) for r in csv.DictReader(f)]
        plot(rows, a.plot)
        return
    work = Path(a.work)
    work.mkdir(parents=True, exist_ok=True)
    rows = []
    for name in a.cases.split(","):
        c = CASES[name]
        deck = c["deck"](work)
        base = work / name / "fixed_0"
        run(a.fracas, deck, base, ["crack_step_limit=0"])
        h, n = run_control(base)
        variants = [(f"fixed h/{2 ** k}", f"fixed_{k}", k, 0.0) for k in range(c["halvings"] + 1)]
        variants += [(f"control {lim:g} at h", f"control_{lim:g}", 0, lim) for lim in c["limits"]]
        finest = min(c["limits"])
        variants.append((f"reference: control {finest:g} at h/{2 ** c['halvings']}", "reference", c["halvings"], finest))
        results = []
        for label, tag, k, lim in variants:
            sets = [f"time_step={h / 2 ** k!r}", f"number_of_steps={n * 2 ** k}", f"crack_step_limit={lim}"]
            out = work / name / tag
            cpu = run(a.fracas, deck, out, sets)
            results.append((label, cpu, c["metrics"](out)))
            print(f"{name}: {label}: {cpu:.1f} s CPU, {results[-1][2]}", flush=True)
        ref = results[-1][2]
        for label, cpu, m in results:
            for key, value in m.items():
                rows.append(dict(case=name, run=label, cpu_s=round(cpu, 2), quantity=key, value=value,
                                 reference=ref[key], rel_error=abs(value / ref[key] - 1) if ref[key] else 0.0))
    print(f"\n| case | run | CPU (s) | quantity | value | error vs reference |\n| --- | --- | --- | --- | --- | --- |")
    for r in rows:
        print(f"| {r['case']} | {r['run']} | {r['cpu_s']:.1f} | {r['quantity']} | {r['value']:.5g} | "
              f"{r['rel_error']:.2%} |")
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
    if a.plot:
        plot(rows, a.plot)


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    keys = sorted({(r["case"], r["quantity"]) for r in rows})
    ncol = (len(keys) + 1) // 2
    fig, axes = plt.subplots(2, ncol, figsize=(3.3 * ncol, 6.4), squeeze=False)
    for ax in axes.flat[len(keys):]:
        ax.axis("off")
    for ax, (case, q) in zip(axes.flat, keys):
        # runs identical to the reference (error 0) have no place on a log scale
        rs = [r for r in rows if r["case"] == case and r["quantity"] == q and r["rel_error"] > 0]
        fixed = [r for r in rs if r["run"].startswith("fixed")]
        ctl = [r for r in rs if r["run"].startswith("control")]
        ax.loglog([r["cpu_s"] for r in fixed], [r["rel_error"] for r in fixed], "o-", label="fixed h, h/2, ...")
        ax.loglog([r["cpu_s"] for r in ctl], [r["rel_error"] for r in ctl], "s", label="crack_step_limit at h")
        for r in ctl:
            ax.annotate(r["run"].split()[1], (r["cpu_s"], r["rel_error"]), fontsize=7, xytext=(3, 3),
                        textcoords="offset points")
        ax.set_title(f"{case}\n{q}", fontsize=8)
        ax.set_xlabel("CPU (s)", fontsize=8)
        ax.tick_params(labelsize=7)
    for row in axes:
        row[0].set_ylabel("relative error vs reference", fontsize=8)
    axes[0][0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
