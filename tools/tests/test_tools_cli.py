"""The command line (python3 -m fracas_tools, tools/fracas-tools), and an end-to-end run
deck -> fracas -> fracas.h5 -> check-h5 -> report when a built solver is found."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

TOOLS = Path(__file__).resolve().parents[1]
REPO = TOOLS.parent
# The LMGC90 decks: the path CMake was configured with (FRACAS_LMGC90_DECKS), else ../shared.
DECKS = Path(os.environ.get("FRACAS_LMGC90_DECKS", REPO / ".." / "shared" / "lmgc90_decks"))

from fracas_tools import read_case  # noqa: E402


def run_cli(*args, check=True):
    env = dict(os.environ, PYTHONPATH=str(TOOLS), MPLBACKEND="Agg")
    r = subprocess.run([sys.executable, "-m", "fracas_tools", *map(str, args)], env=env,
                       capture_output=True, text=True, timeout=120)
    if check and r.returncode != 0:
        raise AssertionError(f"exit {r.returncode}\nstdout:\n{r.stdout}\nstderr:\n{r.stderr}")
    return r


def test_deposit_command(tmp_path):
    r = run_cli("deposit", "--n", "2000", "--seed", "1", tmp_path / "dep")
    assert "2000 DISKx" in r.stdout
    case = read_case(tmp_path / "dep")
    assert len(case.bodies) == 2003
    assert case.run["time_step"] == 1e-3 and case.run["number_of_steps"] == 1000
    # same seed, same deck; another seed, another deck
    run_cli("deposit", "--n", "2000", "--seed", "1", tmp_path / "dep2")
    run_cli("deposit", "--n", "2000", "--seed", "2", tmp_path / "dep3")
    a = (tmp_path / "dep" / "DATBOX" / "BODIES.DAT").read_bytes()
    assert a == (tmp_path / "dep2" / "DATBOX" / "BODIES.DAT").read_bytes()
    assert a != (tmp_path / "dep3" / "DATBOX" / "BODIES.DAT").read_bytes()


def test_demo_info_rewrite(tmp_path):
    run_cli("demo", "deposit", tmp_path / "demo")
    r = run_cli("info", tmp_path / "demo")
    assert "403 bodies" in r.stdout and "warning" not in r.stdout
    run_cli("rewrite", tmp_path / "demo", tmp_path / "copy")
    for f in (tmp_path / "demo" / "DATBOX").iterdir():
        assert f.read_bytes() == (tmp_path / "copy" / "DATBOX" / f.name).read_bytes()


def test_check_h5_report_summary(tmp_path):
    run_cli("synthetic", "--nx", "4", "--ny", "2", tmp_path / "syn")
    h5 = tmp_path / "syn" / "OUTBOX" / "fracas.h5"
    r = run_cli("check-h5", h5)
    assert r.stdout.strip().endswith("OK")
    r = run_cli("report", tmp_path / "syn")
    assert Path(r.stdout.strip()) == tmp_path / "syn" / "report" / "report.md"
    assert (tmp_path / "syn" / "report" / "force_network.png").exists()
    r = run_cli("summary", h5, h5)
    assert r.stdout.count("\n") == 4
    bad = tmp_path / "bad.h5"
    bad.write_bytes(b"not hdf5")
    r = run_cli("check-h5", bad, check=False)
    assert r.returncode == 1 and "error" in r.stdout


def test_errors_are_reported_cleanly(tmp_path):
    r = run_cli("info", tmp_path, check=False)
    assert r.returncode == 2 and "no DATBOX/BODIES.DAT" in r.stderr
    d = tmp_path / "c" / "DATBOX"
    d.mkdir(parents=True)
    (d / "BODIES.DAT").write_text("$bdyty\n RBDY2      1\n$blmty\n PLAIN      1  behav  STONE  avrd= x\n")
    r = run_cli("info", tmp_path / "c", check=False)
    assert r.returncode == 2 and "BODIES.DAT:4:35:" in r.stderr


def test_wrapper_script(tmp_path):
    r = subprocess.run([str(TOOLS / "fracas-tools"), "demo", "arch", str(tmp_path / "arch")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "arch" / "DATBOX" / "COMMAND.DAT").exists()


@pytest.mark.skipif(not DECKS.is_dir(), reason=f"LMGC90 decks not found at {DECKS} (set FRACAS_LMGC90_DECKS)")
def test_rewrite_lmgc90_deck(tmp_path):
    run_cli("rewrite", DECKS / "drum", tmp_path / "drum")
    assert (tmp_path / "drum" / "DATBOX" / "BODIES.DAT").read_bytes() == \
        (DECKS / "drum" / "DATBOX" / "BODIES.DAT").read_bytes()


def _fracas_binary(deck):
    cands = [os.environ.get("FRACAS_BIN", "")] + sorted(str(p) for p in REPO.glob("build/*/bin/fracas"))
    for c in cands:
        if c and os.access(c, os.X_OK):
            r = subprocess.run([c, "--check", str(deck)], capture_output=True, text=True, timeout=60)
            if r.returncode == 0 and "check: OK" in r.stdout:
                return c
    return None


def test_end_to_end_with_fracas(tmp_path):
    """Deck written by fracas_tools, run by the solver, read back by the post tools."""
    from fracas_tools import generators as gen, post
    case = gen.deposit_case(n=60, seed=3, rmin=0.008, rmax=0.012, width=0.15, duration=0.05,
                            output_vtk_every=0, output_hdf5_every=10, output_dof_every=50)
    d = tmp_path / "e2e"
    case.write(d)
    exe = _fracas_binary(d)
    if exe is None:
        pytest.skip("no built fracas binary (set FRACAS_BIN or build the project)")
    r = subprocess.run([exe, str(d)], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stdout + r.stderr
    h5 = d / "OUTBOX" / "fracas.h5"
    errors, warns, info = post.check_h5(h5)
    assert errors == [], errors
    with post.Run(d) as run:
        assert run.complete and run.n_bodies == 63
        assert len(run.series["time"]) == 50
        assert run.deck() is not None
    # Timing attributes of the driver (doc/output_layout.md 1.1): the loop holds every
    # step; a single-threaded run's CPU time does not exceed its wall time.
    import h5py
    with h5py.File(h5, "r") as f:
        a = f.attrs
        for part in ("read", "setup", "loop"):
            assert 0.0 <= a[part + "_cpu_seconds"] <= a[part + "_seconds"] + 0.01, part
        assert a["loop_cpu_seconds"] > 0.0
        assert f["series/step_time"][:].sum() <= a["loop_seconds"]
        # rigid contacts: only those the law keeps active are swept, so the count of
        # local solves is at most (sweeps + one check pass per 50-sweep block) x contacts
        sw, nc, upd = (f["series/" + k][:] for k in ("sweeps", "contacts", "contact_updates"))
        assert upd.sum() > 0 and (upd <= (sw + sw / 50) * nc).all()
    with post.Run(d) as run:
        s = run.snapshot(-1)
        assert s.step == 50
        # the grains fell: positions = reference + displacement, below the reference
        ref = run.bodies["reference"][:60, 1]
        assert (s.pos[:60, 1] < ref).all()
    text = post.report(d).read_text()
    assert "force_network.png" in text


@pytest.mark.skipif(not (DECKS / "mesh_exploded_beam").is_dir(), reason=f"LMGC90 decks not found at {DECKS}")
def test_contact_updates_and_velocity_time(tmp_path):
    """Series contact_updates (doc/output_layout.md 1.3) counts every local solve of the
    NLGS exactly: on mesh_exploded_beam every one of the 116 cohesive contacts is swept in
    each of the step's sweeps and in the check pass after each block of 50 (LMGC90's
    convergence check), so a step costs (sweeps + sweeps / 50) x 116 updates. The final
    solve of the meshes' velocities (velocity_time) is part of solve_time."""
    cands = [os.environ.get("FRACAS_BIN", "")] + sorted(str(p) for p in REPO.glob("build/*/bin/fracas"))
    exe = next((c for c in cands if c and os.access(c, os.X_OK)), None)
    if exe is None:
        pytest.skip("no built fracas binary (set FRACAS_BIN or build the project)")
    cmd = REPO / "test_cases" / "compat" / "mesh_exploded_beam" / "run.dat"
    out = tmp_path / "beam"
    r = subprocess.run([exe, "-q", "--command", str(cmd), "--set", "number_of_steps=20",
                        str(DECKS / "mesh_exploded_beam"), "--output", str(out)],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stdout + r.stderr
    import h5py
    with h5py.File(out / "OUTBOX" / "fracas.h5", "r") as f:
        sw, nc, upd, vt, st = (f["series/" + k][:] for k in
                               ("sweeps", "contacts", "contact_updates", "velocity_time", "solve_time"))
    assert (nc == 116).all() and (sw % 50 == 0).all() and sw.min() >= 50
    assert (upd == (sw + sw // 50) * 116).all()
    assert (vt > 0.0).all() and (vt <= st).all()
