#!/usr/bin/python3
"""Deck fuzzer: mutate the shipped decks, then ask Fracas to check and run them.

    build/release/bin/fracas-python tools/fuzz/fuzz_decks.py --fracas BIN [--decks N] [--seed S]
        [--steps 30] [--jobs 2] [--sources all|small] [--work DIR] [--keep-findings DIR]
        [--only I] [--json FILE]

Deck i of a batch is made from the seeded generator random.Random(f"{seed}:{i}"), so any
deck is rebuilt alone with --only i. A deck is one shipped case (test_cases/**/DATBOX,
and the LMGC90 decks of ../shared/lmgc90_decks with their run control from
test_cases/compat when present) with one to three mutations: extreme or scaled numbers
(kept in their fixed column, or spilling one column), sign flips, a number shifted one
column, characters inserted or deleted, lines dropped, doubled, swapped or cut, text
appended after the last field, a keyword or name replaced by another one, COMMAND.DAT
values pushed to their limits, an evolution file replaced by a directory; and, aimed at
meshed and exploded decks, extreme gravity, extreme DOF.INI velocities of mesh nodes,
extreme driven velocities of mesh nodes, NLGS relaxation near 2, a NEW MECAx SETS count
one off, and (with --restarts F) a corrupted restart point of an accepted run fed back
through --restart.

Each deck goes through ``fracas --check`` and, if accepted, a short run
(``--set number_of_steps=STEPS``). Outcomes:

    check   rejected (located: FILE:LINE[:COL]: message; or 'fracas: error:'), accepted,
            crash (a signal or an exit status other than 0/1, or no message), hang (timeout)
    run     ok (exit 0, fracas.h5 complete = 1, every number finite, every body within
            what double precision resolves at its size), stopped (exit 1 with a message and
            complete = 0), crash, hang, lie (exit 0 but nonsense or complete != 1),
            input error at the start of a run that --check accepted (inconsistent)
    restart (a fraction --restarts of the finished runs) refused (exit 1 naming the
            restart point's dataset), ok, crash, hang, lie (as a run)

Exit status 1 if any crash, hang, lie or inconsistency was found (the decks are copied to
--keep-findings with what was done to them), else 0. doc/fuzzing.md gives the counts of
the long batch.
"""

import argparse
import json
import math
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
from fracas_tools.results import Run  # noqa: E402  (the one reader of fracas.h5)

LMGC_CASES = ["disks_box", "drum", "driven_evolution", "polygons_ground", "mixed_disk_polygon", "glued_pair_czm",
              "mesh_block_drop", "mesh_disk_on_mesh", "mesh_exploded_beam", "mesh_plastic_bar", "mesh_t3_pair_czm"]

# Numbers: Fortran reals as DATBOX writes them (E/D exponents, or a bare-sign 3-digit exponent).
NUM_RE = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eEdD][-+]?\d+|[-+]\d{3})?")
EXTREMES = ["0", "-1", "1e308", "-1e308", "1e-308", "4.9e-324", "1e20", "-1e20", "1e100", "1e-100",
            "2147483647", "-2147483648", "99999999999", "1e300", "NaN", "Inf", "1e-20", "3", "1e400", "-1e-400"]
WORDS = ["RBDY2", "MAILx", "DISKx", "DISKb", "POLYG", "JONCx", "xKSID", "PLAIN", "NO3xx", "vlocy", "force",
         "IQS_CLB", "RST_CLB", "MAC_CZM", "IQS_MAC_CZM", "MP3_CZM", "TH_CZM", "EXPO_CZM", "GAP_SGR_CLB",
         "BLEUx", "WALLx", "STONE", "iqsdw", "noctc", "stick", "slifw", "$bdyty", "$$$$$$", "evolution"]
COMMAND_VALUES = {
    "time_step": ["1e-300", "4.9e-324", "1e300", "1e-12", "10", "0.5"],
    "number_of_steps": ["1", "2147483647"],
    "final_time": ["1e300", "1e-300", "1e10"],
    "theta": ["0.5", "1", "0.5000001"],
    "detection_frequency": ["2", "7", "1000", "2147483647"],
    "nlgs_check": ["Quad", "Maxm", "QM/16"],
    "nlgs_tolerance": ["1e-300", "1e300", "1e-16", "0.5"],
    "nlgs_relaxation": ["1e-300", "1.999999", "0.01", "1.99", "1.95", "1.9"],
    "nlgs_sweeps_per_check": ["1", "2147483647", "1000"],
    "nlgs_max_checks": ["1", "2147483647", "100000"],
    "nlgs_order": ["stored", "reversed", "shuffled", "colored"],
    "nlgs_seed": ["-2147483648", "0", "2147483647"],
    "output_dof_every": ["1", "2147483647"],
    "output_hdf5_every": ["1", "0", "2147483647"],
    "progress_every": ["1", "2147483647"],
}
MESH_EXTREMES = ["1e100", "-1e100", "5e100", "1e20", "1e300", "-1e308", "1e10", "NaN"]
LOCATED = re.compile(r"^\S+:\d+(:\d+)?: ", re.M)
RESTART_LOCATED = re.compile(r"fracas: error: restart point \S+:/restart/\d+(/\S+)?: ")
# A whole-file error (unreadable, a directory, no END line) names the file without a line.
FILE_LEVEL = re.compile(r"^\S+\.(DAT|INI|OUT|dat|ini): ", re.M)
EPS = 2.220446049250313e-16


def source_decks(kind, lmgc_dir):
    """(name, case_dir, command file or None) of the decks to mutate."""
    out = []
    for datbox in sorted((ROOT / "test_cases").glob("**/DATBOX")):
        case = datbox.parent
        rel = case.relative_to(ROOT / "test_cases")
        if rel.parts[0] == "broken" and rel.name != "valid_minimal":
            continue
        if not (datbox / "COMMAND.DAT").exists():
            continue
        if kind == "small" and _count_bodies(datbox / "BODIES.DAT") > 30:
            continue
        out.append((str(rel), case, None))
    if kind == "all" and lmgc_dir and Path(lmgc_dir).is_dir():
        for c in LMGC_CASES:
            cmd = ROOT / "test_cases" / "compat" / c / "run.dat"
            if (Path(lmgc_dir) / c / "DATBOX").is_dir() and cmd.exists():
                out.append((f"lmgc90/{c}", Path(lmgc_dir) / c, cmd))
    return out


def _count_bodies(path):
    try:
        return path.read_text(errors="replace").count("$bdyty")
    except OSError:
        return 0


# ----------------------------------------------------------------------------- mutations

def _format_like(token, value):
    """value as text no wider than token (right-aligned), or its natural form if it cannot fit."""
    width = len(token)
    m = re.fullmatch(r"([-+]?)(\d+(?:\.\d*)?)[eE]([-+]?\d+)", value)
    if not m:
        return value.rjust(width)
    # Mantissa and exponent as text: values beyond double precision stay as written.
    sign, mant, ex = m.group(1), float(m.group(2)), int(m.group(3))
    if mant != 0.0:
        shift = math.floor(math.log10(mant))
        mant, ex = mant / 10.0 ** shift, ex + shift
    letter = "D" if "D" in token else "E"
    for prec in range(7, -1, -1):
        s = f"{sign}{mant:.{prec}f}{letter}{ex:+03d}"
        if len(s) <= width:
            return s.rjust(width)
    return f"{sign}{mant:.7f}{letter}{ex:+03d}"


def _numbers(line):
    return [m for m in NUM_RE.finditer(line) if not _inside_word(line, m)]


def _inside_word(line, m):
    a, b = m.span()
    return (a > 0 and (line[a - 1].isalpha() or line[a - 1] == "_")) or (b < len(line) and line[b].isalpha()
                                                                         and line[b] not in "eEdD")


def mutate_file(rng, path, log):
    lines = path.read_text(errors="replace").split("\n")
    data = [i for i, l in enumerate(lines) if l.strip() and not l.lstrip().startswith(("!", "#"))]
    if not data:
        return
    kind = rng.choice(["extreme", "extreme", "scale", "sign", "shift", "char", "dropline", "dupline",
                       "swapline", "cut", "trail", "word"])
    i = rng.choice(data)
    line = lines[i]
    nums = _numbers(line)
    where = f"{path.name}:{i + 1}"
    if kind in ("extreme", "scale", "sign", "shift") and nums:
        m = rng.choice(nums)
        tok = m.group(0)
        if kind == "extreme":
            new = _format_like(tok, rng.choice(EXTREMES))
        elif kind == "scale":
            try:
                v = float(tok.replace("D", "E").replace("d", "e")) if re.search(r"[eEdD]", tok) else float(tok)
            except ValueError:
                v = 1.0
            mant, ex = f"{v if v else 1.0:.7E}".split("E")
            new = _format_like(tok, f"{mant}E{int(ex) + rng.randint(-320, 320):+03d}")
        elif kind == "sign":
            new = ("-" + tok.lstrip("+-")) if not tok.startswith("-") else tok[1:].rjust(len(tok))
        else:
            new = " " + tok if rng.random() < 0.5 else tok
            if new == tok and m.start() > 0 and line[m.start() - 1] == " ":
                lines[i] = line[:m.start() - 1] + tok + " " + line[m.end():]
                log.append(f"{where}: moved {tok!r} one column left")
                path.write_text("\n".join(lines))
                return
        lines[i] = line[:m.start()] + new + line[m.end():]
        log.append(f"{where}: {kind} {tok!r} -> {new!r}")
    elif kind == "char":
        k = rng.randrange(len(line) + 1)
        if rng.random() < 0.5 and line:
            k = min(k, len(line) - 1)
            lines[i] = line[:k] + line[k + 1:]
            log.append(f"{where}: deleted column {k + 1}")
        else:
            c = rng.choice("0123456789 .-+eEDx$=a")
            lines[i] = line[:k] + c + line[k:]
            log.append(f"{where}: inserted {c!r} at column {k + 1}")
    elif kind == "dropline":
        del lines[i]
        log.append(f"{where}: line dropped")
    elif kind == "dupline":
        lines.insert(i, line)
        log.append(f"{where}: line doubled")
    elif kind == "swapline":
        j = rng.choice(data)
        lines[i], lines[j] = lines[j], lines[i]
        log.append(f"{where}: swapped with line {j + 1}")
    elif kind == "cut":
        k = rng.randrange(len(line) + 1)
        lines[i] = line[:k]
        log.append(f"{where}: cut at column {k}")
    elif kind == "trail":
        lines[i] = line + rng.choice(["  0.5", " x", "  fric= 0.3000000e+00", "!", "\t1"])
        log.append(f"{where}: text appended")
    else:
        words = [m for m in re.finditer(r"[$A-Za-z_][A-Za-z0-9_$]*", line)]
        if not words:
            return
        m = rng.choice(words)
        new = rng.choice(WORDS)
        lines[i] = line[:m.start()] + new + line[m.end():]
        log.append(f"{where}: word {m.group(0)!r} -> {new!r}")
    path.write_text("\n".join(lines))


def _set_field(lines, i, m, value, log, what):
    """Number m of line i replaced by value in its columns."""
    tok = m.group(0)
    new = _format_like(tok, value)
    lines[i] = lines[i][:m.start()] + new + lines[i][m.end():]
    log.append(f"{what} (line {i + 1}): {tok!r} -> {new!r}")


def mutate_meshed(rng, dest, log):
    """A mutation aimed at meshed decks (issue 23): gravity, a mesh node's DOF.INI
    velocity, a driven mesh node's velocity, or the NEW MECAx SETS count of POSTPRO.DAT.
    Returns False when the deck has nothing of the kind chosen."""
    dat = dest / "DATBOX"
    kind = rng.choice(["gravity", "node_velocity", "driven_node", "sets_count"])
    if kind == "gravity":
        p = dat / "BULK_BEHAV.DAT"
        lines = p.read_text(errors="replace").split("\n")
        for i, line in enumerate(lines):
            if "grv2=" in line:
                nums = _numbers(line)
                if len(nums) >= 2:
                    _set_field(lines, i, nums[rng.choice([0, 1])], rng.choice(MESH_EXTREMES), log, "gravity")
                    p.write_text("\n".join(lines))
                    return True
        return False
    if kind in ("node_velocity", "driven_node"):
        # a V line of a mesh node in DOF.INI (V(1) or V(2)), or the CT of a driven mesh dof
        name, what = (("DOF.INI", "DOF.INI mesh node velocity") if kind == "node_velocity" else
                      ("DRV_DOF.DAT", "DRV_DOF.DAT mesh node CT"))
        p = dat / name
        if not p.exists():
            return False
        lines = p.read_text(errors="replace").split("\n")
        model, rows = None, []
        for i, line in enumerate(lines):
            if line.startswith((" MAILx", " RBDY2")):
                model = line.split()[0]
            elif model == "MAILx" and ("V(1)=" in line if kind == "node_velocity"
                                       else line.lstrip().startswith(("vlocy", "force"))):
                rows.append(i)
        if not rows:
            return False
        i = rng.choice(rows)
        nums = _numbers(lines[i])
        if len(nums) < 2:
            return False
        m = rng.choice(nums[-2:]) if kind == "node_velocity" else nums[1]
        _set_field(lines, i, m, rng.choice(MESH_EXTREMES), log, what)
        p.write_text("\n".join(lines))
        return True
    p = dat / "POSTPRO.DAT"
    if not p.exists():
        return False
    lines = p.read_text(errors="replace").split("\n")
    for i, line in enumerate(lines):
        if line.startswith("NEW MECAx SETS") and i + 2 < len(lines):
            n = int(lines[i + 2].split()[0]) if lines[i + 2].split() and lines[i + 2].split()[0].isdigit() else 1
            new = max(0, n + rng.choice([-1, 1]))
            lines[i + 2] = f"{new:7d}"
            log.append(f"POSTPRO.DAT:{i + 3}: NEW MECAx SETS count {n} -> {new}")
            p.write_text("\n".join(lines))
            return True
    return False


def mutate_command(rng, path, log):
    text = path.read_text(errors="replace")
    key = rng.choice(sorted(COMMAND_VALUES))
    value = rng.choice(COMMAND_VALUES[key])
    lines = [l for l in text.split("\n") if not re.match(rf"\s*{key}\b", l, re.I)]
    if key == "final_time":
        lines = [l for l in lines if not re.match(r"\s*number_of_steps\b", l, re.I)]
    if key == "number_of_steps":
        lines = [l for l in lines if not re.match(r"\s*final_time\b", l, re.I)]
    lines.append(f"{key} {value}")
    path.write_text("\n".join(lines) + "\n")
    log.append(f"COMMAND: {key} {value}")


def make_deck(seed, i, sources, work):
    """Deck i: a copy of one source case with 1-3 mutations; returns (case, command, log)."""
    rng = random.Random(f"{seed}:{i}")
    name, case, cmd = rng.choice(sources)
    dest = work / f"deck_{i:06d}"
    if dest.exists():
        shutil.rmtree(dest)
    shutil.copytree(case / "DATBOX", dest / "DATBOX")
    for p in (dest / "DATBOX").rglob("*"):
        p.chmod(0o755 if p.is_dir() else 0o644)
    command = None
    if cmd is not None:
        command = dest / "run.dat"
        shutil.copy(cmd, command)
        command.chmod(0o644)
    log = [f"source {name}"]
    for _ in range(rng.choice([1, 1, 2, 3])):
        files = [p for p in sorted((dest / "DATBOX").iterdir()) if p.is_file() and p.suffix.upper() in (".DAT", ".INI")]
        r = rng.random()
        cfile = command if command is not None else dest / "DATBOX" / "COMMAND.DAT"
        if r < 0.2 and cfile.exists():
            mutate_command(rng, cfile, log)
        elif r < 0.45 and "MAILx" in (dest / "DATBOX" / "BODIES.DAT").read_text(errors="replace") \
                and mutate_meshed(rng, dest, log):
            pass
        elif r < 0.23:
            evo = [p for p in files if p.name not in ("BODIES.DAT", "BULK_BEHAV.DAT", "TACT_BEHAV.DAT",
                                                      "DRV_DOF.DAT", "COMMAND.DAT", "DOF.INI", "Vloc_Rloc.INI")]
            if evo:
                p = rng.choice(evo)
                p.unlink()
                p.mkdir()
                log.append(f"{p.name}: replaced by a directory")
        else:
            mutate_file(rng, rng.choice(files), log)
    return dest, command, log


# ----------------------------------------------------------------------------- running

def run(cmd, timeout):
    t0 = time.perf_counter()
    try:
        r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, errors="replace",
                           timeout=timeout)
        return r.returncode, r.stdout, r.stderr, time.perf_counter() - t0
    except subprocess.TimeoutExpired:
        return None, "", "", time.perf_counter() - t0


def classify_check(rc, out, err):
    if rc is None:
        return "hang"
    if rc == 0 and "check: OK" in out:
        return "accepted"
    if rc == 1 and (LOCATED.search(err) or FILE_LEVEL.search(err)):
        return "rejected_located"
    if rc == 1 and "fracas: error:" in err:
        return "rejected_unlocated"
    return "crash"


def results_sound(h5path, steps):
    """'' if fracas.h5 is complete and sensible, else what is wrong."""
    import numpy as np
    try:
        f = Run(h5path)
    except OSError as e:
        return f"cannot open fracas.h5: {e}"
    with f:
        if not f.complete:
            return "complete != 1 after exit 0"
        for name, v in f.series.items():
            if not np.all(np.isfinite(v)):
                return f"series/{name} is not finite"
        if len(f.series.get("step", [])) != steps:
            return f"{len(f.series.get('step', []))} rows in the series for {steps} steps"
        radius = np.asarray(f.bodies.get("radius", []), dtype=float)
        ref = f.bodies["reference"]
        for name in f.snapshot_names:
            snap = f.snapshot(name)
            for what, v in [("bodies/X", snap.X), ("bodies/V", snap.V)] + \
                           [("contacts/" + k, a) for k, a in snap.contacts.items()]:
                v = np.asarray(v)
                if v.dtype.kind == "f" and not np.all(np.isfinite(v)):
                    return f"snapshot {name}: {what} is not finite"
            for k, v in snap.mesh.items():
                v = np.asarray(v) if not isinstance(v, dict) else np.zeros(0)
                if v.dtype.kind == "f" and not np.all(np.isfinite(v)):
                    return f"snapshot {name}: mesh_{k} is not finite"
            if "X" in snap.mesh and "reference" in f.mesh:
                bad = _mesh_runaway(f.mesh, np.asarray(snap.mesh["X"]))
                if bad:
                    return f"snapshot {name}: {bad}"
            if radius.size and ref.shape == snap.X.shape and ref.shape[1] == 3:
                pos = np.abs(ref[:, :2] + snap.X[:, :2]).max(axis=-1)
                lim = 1e-3 * radius / EPS
                if np.any(pos > lim):
                    b = int(np.argmax(pos / lim))
                    return f"snapshot {name}: body {b + 1} at {pos[b]:.3g}, beyond what double precision resolves"
    return ""


def _mesh_runaway(mesh, x):
    """'' if every node of every meshed body is within what double precision resolves at
    the body's size (half the diagonal of its reference box), else which is not."""
    import numpy as np
    ref = np.asarray(mesh["reference"])
    first = np.asarray(mesh["body_first_node"])
    for b in range(len(first) - 1):
        r = ref[first[b] - 1:first[b + 1] - 1]
        size = 0.5 * float(np.linalg.norm(r.max(axis=0) - r.min(axis=0)))
        pos = np.abs(r + x[first[b] - 1:first[b + 1] - 1]).max()
        if pos > 1e-3 * size / EPS:
            return f"MAILx body {b + 1} has a node at {pos:.3g}, beyond what double precision resolves"
    return ""


def corrupt_restart(rng, src, dest, log):
    """A copy of fracas.h5 whose latest restart point has one dataset corrupted: a row
    more or fewer, a NaN, or an index of 2^31 - 1 / -1. Returns the step, or None."""
    import h5py
    import numpy as np
    shutil.copy(src, dest)
    with h5py.File(dest, "r+") as f:
        if "restart" not in f:
            return None
        step = int(f["restart"].attrs["last"])
        g = f["restart"][str(step)]
        names = []
        g.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) and o.size > 0 else None)
        if not names:
            return None
        name = rng.choice(sorted(names))
        a = g[name][()]
        how = rng.choice(["row_more", "row_less", "bad_value"])
        if how == "row_more":
            a = np.concatenate([a, a[-1:]], axis=0)
        elif how == "row_less":
            a = a[:-1]
        elif a.dtype.kind == "f":
            a = a.copy()
            a.flat[rng.randrange(a.size)] = rng.choice([np.nan, np.inf, -1e308])
        else:
            a = a.copy()
            a.flat[rng.randrange(a.size)] = rng.choice([2**31 - 1, -1, 0])
        del g[name]
        g[name] = a
        log.append(f"restart point {step}: {name} {how}")
    return step


def one_restart(args, deck, opt, h5, steps, rng, res):
    """Feed a corrupted copy of the run's latest restart point back through --restart."""
    bad = deck / "corrupt.h5"
    log = []
    at = corrupt_restart(rng, h5, bad, log)
    if at is None:
        return
    res["log"] += log
    out = deck / "out_restart"
    total = steps + 5
    cmd = [args.fracas, "-q", "--overwrite", "--set", f"number_of_steps={total}", "--restart", str(bad),
           "--output", str(out)] + opt + [str(deck)]
    rc, _, err, _ = run(cmd, args.run_timeout)
    res["restart_stderr"] = err.strip()[-400:]
    if rc is None:
        res["restart"] = "hang"
    elif rc == 1 and RESTART_LOCATED.search(err):
        res["restart"] = "refused"
    elif rc == 1 and "fracas: error:" in err:
        res["restart"] = "stopped"
    elif rc == 0:
        sound = results_sound(out / "OUTBOX" / "fracas.h5", total - at)
        res["restart"] = "lie" if sound else "ok"
        if sound:
            res["lie"] = sound
    else:
        res["restart"] = "crash"
        res["exit"] = rc


def one_deck(args, sources, work, i):
    deck, command, log = make_deck(args.seed, i, sources, work)
    base = [args.fracas]
    opt = ["--command", str(command)] if command is not None else []
    rc, out, err, _ = run(base + ["--check"] + opt + [str(deck)], args.check_timeout)
    res = {"deck": i, "log": log, "check": classify_check(rc, out, err), "check_stderr": err.strip()[-400:],
           "run": None}
    if res["check"] == "accepted":
        steps = args.steps
        m = re.search(r"(\d+) steps\)", out)
        if m:
            steps = min(steps, int(m.group(1)))
        outdir = deck / "out"
        cmd = base + ["-q", "--overwrite", "--set", f"number_of_steps={steps}", "--set", "output_vtk_every=10",
                      "--output", str(outdir)] + opt + [str(deck)]
        rc, out, err, dt = run(cmd, args.run_timeout)
        res["run_seconds"] = round(dt, 3)
        res["run_stderr"] = err.strip()[-400:]
        h5 = outdir / "OUTBOX" / "fracas.h5"
        if rc is None:
            res["run"] = "hang"
        elif rc == 0:
            bad = results_sound(h5, steps)
            res["run"] = "lie" if bad else "ok"
            if bad:
                res["lie"] = bad
            rng = random.Random(f"{args.seed}:{i}:restart")
            if not bad and rng.random() < args.restarts:
                one_restart(args, deck, opt, h5, steps, rng, res)
        elif rc == 1 and "fracas: error:" in err:
            res["run"] = "stopped"
            if h5.exists():
                try:
                    with Run(h5) as f:
                        if f.complete:
                            res["run"] = "lie"
                            res["lie"] = "stopped with complete = 1"
                except OSError:
                    pass
        elif rc == 1 and LOCATED.search(err):
            res["run"] = "inconsistent"
        else:
            res["run"] = "crash"
            res["exit"] = rc
    bad = res["check"] in ("crash", "hang") or res["run"] in ("crash", "hang", "lie", "inconsistent") or \
        res.get("restart") in ("crash", "hang", "lie")
    if bad and args.keep_findings:
        dest = Path(args.keep_findings) / deck.name
        if dest.exists():
            shutil.rmtree(dest)
        shutil.copytree(deck, dest, ignore=shutil.ignore_patterns("out"))
        (dest / "finding.json").write_text(json.dumps(res, indent=1))
    if not args.keep_decks:
        shutil.rmtree(deck, ignore_errors=True)
    return res


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--fracas", default=str(ROOT / "build" / "release" / "bin" / "fracas"))
    ap.add_argument("--decks", type=int, default=100)
    ap.add_argument("--seed", default="1")
    ap.add_argument("--steps", type=int, default=30)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--sources", choices=["all", "small"], default="all")
    ap.add_argument("--lmgc90-decks", default=os.environ.get("FRACAS_LMGC90_DECKS",
                                                             str(ROOT.parent / "shared" / "lmgc90_decks")))
    ap.add_argument("--work", default=None, help="where decks are made (default: a temporary folder)")
    ap.add_argument("--keep-findings", default=None, help="copy decks that crash, hang or lie here")
    ap.add_argument("--keep-decks", action="store_true")
    ap.add_argument("--only", type=int, default=None, help="make and test deck I only")
    ap.add_argument("--first", type=int, default=0,
                    help="decks FIRST .. FIRST+DECKS-1 (a long batch run in chunks: same seed, same decks)")
    ap.add_argument("--check-timeout", type=float, default=30.0)
    ap.add_argument("--run-timeout", type=float, default=120.0)
    ap.add_argument("--json", default=None, help="write every outcome here")
    ap.add_argument("--match", default=None, help="mutate only source decks whose name contains this text")
    ap.add_argument("--restarts", type=float, default=0.0,
                    help="fraction of finished runs whose restart point is corrupted and fed back through --restart")
    args = ap.parse_args()

    sources = source_decks(args.sources, args.lmgc90_decks)
    if args.match:
        sources = [s for s in sources if args.match in s[0]]
    if not sources:
        sys.exit("fuzz_decks.py: no source decks found")
    tmp = None
    if args.work:
        work = Path(args.work)
        work.mkdir(parents=True, exist_ok=True)
    else:
        tmp = tempfile.TemporaryDirectory(prefix="fracas_fuzz_")
        work = Path(tmp.name)
    ids = [args.only] if args.only is not None else list(range(args.first, args.first + args.decks))
    t0 = time.perf_counter()
    with ThreadPoolExecutor(max_workers=max(1, args.jobs)) as ex:
        results = list(ex.map(lambda i: one_deck(args, sources, work, i), ids))
    elapsed = time.perf_counter() - t0

    count = {}
    for r in results:
        count["check_" + r["check"]] = count.get("check_" + r["check"], 0) + 1
        if r["run"]:
            count["run_" + r["run"]] = count.get("run_" + r["run"], 0) + 1
        if r.get("restart"):
            count["restart_" + r["restart"]] = count.get("restart_" + r["restart"], 0) + 1
    findings = [r for r in results if r["check"] in ("crash", "hang")
                or r["run"] in ("crash", "hang", "lie", "inconsistent") or r.get("restart") in ("crash", "hang", "lie")]
    print(f"fuzz_decks: seed {args.seed}, {len(results)} decks from {len(sources)} sources, "
          f"{args.steps} steps per run, {elapsed:.0f} s")
    for k in ["check_rejected_located", "check_rejected_unlocated", "check_accepted", "check_crash", "check_hang",
              "run_ok", "run_stopped", "run_crash", "run_hang", "run_lie", "run_inconsistent",
              "restart_refused", "restart_ok", "restart_stopped", "restart_crash", "restart_hang", "restart_lie"]:
        print(f"  {k:26s} {count.get(k, 0)}")
    for r in findings:
        print(f"FINDING deck {r['deck']}: check {r['check']}, run {r['run']}, restart {r.get('restart')}: "
              f"{'; '.join(r['log'])}")
        if r.get("lie"):
            print(f"    {r['lie']}")
        if r.get("restart_stderr") or r.get("run_stderr") or r.get("check_stderr"):
            print(f"    {(r.get('restart_stderr') or r.get('run_stderr') or r.get('check_stderr'))[-300:]}")
    if args.json:
        Path(args.json).write_text(json.dumps({"seed": args.seed, "counts": count, "seconds": elapsed,
                                               "results": results}, indent=1))
    if tmp:
        tmp.cleanup()
    sys.exit(1 if findings else 0)


if __name__ == "__main__":
    main()
