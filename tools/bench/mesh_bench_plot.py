#!/usr/bin/python3
"""Plots and Markdown tables of the meshed-body benchmark (tools/bench/mesh_bench.py):
reads bench/results/mesh_{big,exploded,lmgc90}.json, writes doc/img/bench_mesh_big.png,
doc/img/bench_mesh_exploded.png and bench/results/mesh_tables.md (the tables of
doc/benchmarks.md section 6).

    build/release/bin/fracas-python tools/bench/mesh_bench.py plot
"""

import json
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# Rigid packed kernel on the scene (doc/benchmarks.md section 2, deposit_1000, stored
# order, CPU time of the NLGS / (sweeps x contacts)).
RIGID_NS = 10.7

PART_LABELS = [("bodies", "free velocity (residual, solve)"), ("detect", "detection + history"),
               ("prepare", "W / G blocks, laws"), ("sweeps", "NLGS sweeps"),
               ("velocity", "final velocity solve"), ("end", "end of step (update, energy, cracks)"),
               ("output", "output (VTK, HDF5 every 10 steps)")]


def load(results, name):
    p = results / f"mesh_{name}.json"
    return json.loads(p.read_text()) if p.exists() else None


def loads(runs):
    lo = min(min(r["load_before"], r["load_after"]) for r in runs)
    hi = max(max(r["load_before"], r["load_after"]) for r in runs)
    return f"{lo:.0f}-{hi:.0f}"


def split_panel(ax, x, runs, xlabel):
    for key, label in PART_LABELS:
        y = [r["per_step_ms"][key] for r in runs]
        ax.loglog(x, y, "o-", label=label, ms=4)
    total = [r["per_step_ms"]["step"] + r["per_step_ms"]["output"] for r in runs]
    ax.loglog(x, total, "k.-", lw=2, label="step + output")
    ref = np.array([x[0], x[-1]], dtype=float)
    ax.loglog(ref, total[0] * ref / ref[0], "k:", lw=1, label="slope 1")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("CPU ms per step (steady steps)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)


def plot_big(big, img):
    runs = big["runs"]
    x = [r["nodes"] for r in runs]
    fig, axs = plt.subplots(1, 2, figsize=(12, 4.8))
    split_panel(axs[0], x, runs, "nodes of the body")
    axs[0].set_title("one elastic Q4 body sliding on a rigid ground: time per step")
    ax = axs[1]
    ax.loglog(x, [r["setup_cpu_seconds"] for r in runs], "o-", label="setup: assembly + factorization")
    ax.loglog(x, [r["read_cpu_seconds"] for r in runs], "s-", label="reading the deck")
    ax.loglog(x, [r["first_step_ms"]["prepare"] / 1e3 for r in runs], "^-",
              label="first step: contact compliance (2 solves per contact node)")
    ax.loglog(x, [(r["step_cpu_s"] + r["output_cpu_s"]) / (r["steps"] - 1) for r in runs], "k.-",
              label="one steady step (with output)")
    ref = np.array([x[0], x[-1]], dtype=float)
    s0 = runs[0]["setup_cpu_seconds"]
    ax.loglog(ref, s0 * ref / ref[0], "k:", lw=1, label="slope 1")
    ax.loglog(ref, s0 * (ref / ref[0]) ** 1.5, "k--", lw=1, label="slope 1.5")
    ax.set_xlabel("nodes of the body")
    ax.set_ylabel("CPU seconds")
    ax.set_title("once per run")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.suptitle(f"Fracas, meshed body benchmark ({big['machine']['cpu']}, load {loads(runs)} on "
                 f"{big['machine']['cores']} cores; CPU time), commit {big['machine']['commit']}", fontsize=9)
    fig.tight_layout()
    fig.savefig(img / "bench_mesh_big.png", dpi=110)
    plt.close(fig)


def plot_exploded(ex, lm, img):
    runs = ex["runs"]
    x = [r["elements"] for r in runs]
    fig, axs = plt.subplots(1, 2, figsize=(12, 4.8))
    split_panel(axs[0], x, runs, "elements (= MAILx bodies)")
    axs[0].set_title("exploded T3 plate, cohesive MAC_CZM: time per step")
    ax = axs[1]
    ax.loglog(x, [r["ns_per_update"] for r in runs], "o-", label="Fracas, exploded plate: NLGS sweeps CPU / updates")
    ax.loglog(x, [r["ns_per_update_loop"] for r in runs], "s--",
              label="Fracas, exploded plate: whole loop CPU / updates")
    if lm:
        med = lm["fracas_median"]
        ax.loglog([48], [med["ns_per_update"]], "*", ms=12, color="C0",
                  label="Fracas, mesh_exploded_beam (48 bodies): NLGS sweeps")
        ax.loglog([48], [med["ns_per_update_loop"]], "*", ms=12, color="C1",
                  label="Fracas, mesh_exploded_beam: loop")
        ax.loglog([48], [lm["lmgc90"]["ns_per_update_loop"]], "*", ms=12, color="C3",
                  label="LMGC90, mesh_exploded_beam: loop (case.md)")
    ax.axhline(RIGID_NS, color="k", ls=":", label=f"Fracas rigid packed sweep ({RIGID_NS} ns, deposit_1000, \u00a72)")
    ax.set_xlabel("elements (= MAILx bodies)")
    ax.set_ylabel("CPU ns per contact update")
    ax.set_title("cost per contact update")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.suptitle(f"Fracas, exploded meshes ({ex['machine']['cpu']}, load {loads(runs)} on "
                 f"{ex['machine']['cores']} cores; CPU time), commit {ex['machine']['commit']}", fontsize=9)
    fig.tight_layout()
    fig.savefig(img / "bench_mesh_exploded.png", dpi=110)
    plt.close(fig)


def table_split(runs, size_key, size_label):
    """Time per steady step and its split (CPU ms, medians of the repeats)."""
    head = (f"| {size_label} | dofs | contacts | sweeps / step | updates / step | read (s) | setup (s) | "
            "first step (s) | free velocity | detection | W / G blocks | NLGS sweeps | final velocity solve | "
            "end of step | output | **step + output** | ns / update (sweeps) | process CPU (s) | repeats | load |")
    lines = [head, "|" + "|".join(["---"] * (head.count("|") - 1)) + "|"]
    for r in runs:
        p = r["per_step_ms"]
        lines.append(
            f"| {r[size_key]:,} | {r['dofs']:,} | {r['contacts_mean']:.0f} | {r['sweeps_per_step']:.0f} | "
            f"{r['updates_per_step']:.3g} | {r['read_cpu_seconds']:.2f} | {r['setup_cpu_seconds']:.2f} | "
            f"{r['first_step_ms']['step'] / 1e3:.2f} | {p['bodies']:.3g} | {p['detect']:.3g} | {p['prepare']:.3g} | "
            f"{p['sweeps']:.3g} | {p['velocity']:.3g} | {p['end']:.3g} | {p['output']:.3g} | "
            f"**{p['step'] + p['output']:.3g}** | {r['ns_per_update'] or 0:.1f} | {r['process_cpu_s']:.2f} | "
            f"{r.get('repeats', 1)} | {r['load_before']:.0f}-{r['load_after']:.0f} |")
    return "\n".join(lines)


def table_callgrind(runs, size_key, size_label):
    keys = [("free_velocity", "free velocity"), ("detect_rough", "rough detection"),
            ("detect_fine", "fine detection"), ("prepare", "W / G blocks"), ("solve", "NLGS"),
            ("sweep_mesh", "of which sweeps"), ("mesh_velocities", "of which final solve"),
            ("end_step", "mesh end of step"), ("step", "whole step"), ("total", "whole run / step")]
    head = f"| {size_label} | read | setup | " + " | ".join(k[1] for k in keys) + " | instructions / update |"
    lines = [head, "|" + "|".join(["---"] * (head.count("|") - 1)) + "|"]
    for r in runs:
        cg = r.get("callgrind")
        if not cg:
            continue
        ps = cg["per_step"]
        lines.append(f"| {r[size_key]:,} | {cg['read'] / 1e6:.0f} | {cg['setup'] / 1e6:.0f} | " +
                     " | ".join(f"{ps[k] / 1e6:.3g}" for k, _ in keys) +
                     f" | {cg['sweep_mesh_per_update'] or 0:.0f} |")
    return "\n".join(lines)


def table_lmgc90(lm):
    l90 = lm["lmgc90"]
    runs = lm["fracas_runs"]
    med = lm["fracas_median"]
    lines = ["| | process CPU (s) | loop (s) | sweeps | check passes | contact updates | ns / update: loop | "
             "ns / update: NLGS sweeps | load |", "|---|---|---|---|---|---|---|---|---|"]
    lines.append(f"| LMGC90 (case.md: its run, time.perf_counter around the loop, process CPU) | "
                 f"{l90['process_cpu_s']} | {l90['loop_s']} (wall) | {l90['sweeps_total']:,} | {l90['checks_total']:,} | "
                 f"{l90['updates_total']:.4g} | {l90['ns_per_update_loop']:.1f} | | |")
    for i, r in enumerate(runs):
        lines.append(f"| Fracas run {i + 1} | {r['process_cpu_s']:.2f} | {r['loop_cpu_seconds']:.2f} (CPU) | "
                     f"{r['sweeps_total']:,} | {r['checks_total']:,} | {r['updates_total']:.4g} | "
                     f"{r['ns_per_update_loop']:.1f} | {r['ns_per_update']:.1f} | "
                     f"{r['load_before']:.1f}-{r['load_after']:.1f} |")
    lines.append(f"| **Fracas, median of {len(runs)}** | **{med['process_cpu_s']:.2f}** | {med['loop_cpu_seconds']:.2f} | "
                 f"{int(med['sweeps_total']):,} | {int(med['checks_total']):,} | {med['updates_total']:.4g} | "
                 f"{med['ns_per_update_loop']:.1f} | {med['ns_per_update']:.1f} | |")
    ratio_run = l90["process_cpu_s"] / med["process_cpu_s"]
    ratio_upd = l90["ns_per_update_loop"] / med["ns_per_update_loop"]
    text = "\n".join(lines)
    text += (f"\n\nRatio LMGC90 / Fracas: whole process CPU **{ratio_run:.2f}x**; per contact update over the "
             f"loop {ratio_upd:.2f}x (LMGC90's loop time is wall-clock; its process wall and CPU times are equal, 10.6 s, so it did not wait for the CPU). "
             f"Fracas needs {int(med['sweeps_total']):,} sweeps where LMGC90 needed {l90['sweeps_total']:,} "
             f"({med['sweeps_total'] / l90['sweeps_total']:.3f}x).")
    cg = lm.get("callgrind")
    if cg:
        text += (f" Instructions per contact update in the mesh sweep (callgrind, steps "
                 f"{cg['steps'][0] + 1}-{cg['steps'][1]}): {cg['sweep_mesh_per_update']:.0f}.")
    return text, ratio_run


def main(results, img):
    img.mkdir(parents=True, exist_ok=True)
    big, ex, lm = load(results, "big"), load(results, "exploded"), load(results, "lmgc90")
    out = []
    if big:
        plot_big(big, img)
        out += ["## One large elastic body (mesh_big.json)", "",
                table_split(big["runs"], "nodes", "nodes"), "",
                "Instructions (millions, callgrind) per steady step:", "",
                table_callgrind(big["runs"], "nodes", "nodes"), ""]
    if ex:
        plot_exploded(ex, lm, img)
        out += ["## Exploded plates (mesh_exploded.json)", "",
                table_split(ex["runs"], "elements", "elements"), "",
                "Instructions (millions, callgrind) per steady step:", "",
                table_callgrind(ex["runs"], "elements", "elements"), ""]
    if lm:
        text, _ = table_lmgc90(lm)
        out += ["## mesh_exploded_beam against LMGC90 (mesh_lmgc90.json)", "", text, ""]
    (results / "mesh_tables.md").write_text("\n".join(out))
    print("\n".join(out))
    # doc/benchmarks.md section 6 holds the same tables between markers, one pair per study.
    doc = img.parent / "benchmarks.md"
    text = doc.read_text()
    for name, table in (("big", big and table_split(big["runs"], "nodes", "nodes")),
                        ("big-callgrind", big and table_callgrind(big["runs"], "nodes", "nodes")),
                        ("exploded", ex and table_split(ex["runs"], "elements", "elements")),
                        ("exploded-callgrind", ex and table_callgrind(ex["runs"], "elements", "elements")),
                        ("lmgc90", lm and table_lmgc90(lm)[0])):
        begin, end = f"<!-- mesh-{name}:begin -->", f"<!-- mesh-{name}:end -->"
        if table and begin in text:
            i, j = text.index(begin) + len(begin), text.index(end)
            text = text[:i] + "\n" + table + "\n" + text[j:]
    doc.write_text(text)
