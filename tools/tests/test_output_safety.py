"""Output is safe (issue 10, item 3): results of two runs never mix (a run refuses
to start over an earlier run's files, or removes them all with --overwrite), '.part'
files of a killed run are removed at the next start, and a run killed with SIGKILL
leaves a readable fracas.h5 (complete = 0) holding its series up to a recent step."""
import signal
import subprocess
import time

import h5py
import numpy as np

from fracas_run import ROOT, copy_deck, fracas_bin, run

POSTPRO = "SOLVER INFORMATIONS\nSTEP 1\nBODY TRACKING\nSTEP 10\n      1\n      1\nEND\n"


def names(folder):
    return sorted(p.name for p in folder.iterdir()) if folder.exists() else []


def test_overwrite_clears_what_the_new_run_writes(tmp_path):
    deck = copy_deck("driven_evolution", tmp_path)
    (deck / "DATBOX" / "POSTPRO.DAT").write_text(POSTPRO)
    out = tmp_path / "out"
    first = ["--set", "time_step=1e-3", "--set", "number_of_steps=40", "--set", "output_dof_every=4",
             "--set", "output_vtk_every=10", "--set", "output_hdf5_every=5", "--set", "output_vtk_disks=points"]
    p = run("-q", "--output", out, *first, deck)
    assert p.returncode == 0, p.stderr
    assert len([n for n in names(out / "OUTBOX") if n.startswith("DOF.OUT.")]) == 10
    assert "fracas.pvd" in names(out / "DISPLAY") and len(names(out / "DISPLAY")) == 1 + 3 * 5   # pvd; disks, shapes, contacts x 5 frames
    (out / "OUTBOX" / "notes.txt").write_text("mine")           # not a Fracas file: kept
    before = {d: names(out / d) for d in ("OUTBOX", "DISPLAY", "POSTPRO")}

    # without --overwrite: refused, nothing touched
    p = run("-q", "--output", out, *first, deck)
    assert p.returncode == 1
    assert "results of an earlier run in" in p.stderr and "--overwrite" in p.stderr and "(39 files)" in p.stderr
    assert {d: names(out / d) for d in before} == before

    # a shorter run without VTK and without POSTPRO.DAT: nothing of the first run stays
    (deck / "DATBOX" / "POSTPRO.DAT").unlink()
    p = run("-q", "--overwrite", "--output", out, "--set", "time_step=1e-3", "--set", "number_of_steps=8",
            "--set", "output_dof_every=4", deck)
    assert p.returncode == 0, p.stderr
    assert names(out / "OUTBOX") == ["DOF.OUT.1", "DOF.OUT.2", "Vloc_Rloc.OUT.1", "Vloc_Rloc.OUT.2",
                                     "fracas.h5", "notes.txt"]
    assert not (out / "DISPLAY").exists()                   # emptied, and this run writes none
    assert names(out / "POSTPRO") == []
    with h5py.File(out / "OUTBOX" / "fracas.h5") as f:
        assert f["series/step"].shape == (8,) and f.attrs["complete"] == 1


def test_part_files_of_a_killed_run_are_removed(tmp_path):
    deck = copy_deck("driven_evolution", tmp_path)
    out = tmp_path / "out"
    (out / "DISPLAY").mkdir(parents=True)
    for name in ("disks_000004.vtu.part", "fracas.pvd.part", "holiday.part"):
        (out / "DISPLAY" / name).write_text("half")
    p = run("-q", "--output", out, "--set", "time_step=1e-3", "--set", "number_of_steps=5", deck)
    assert p.returncode == 0, p.stderr                       # .part files are not results: no refusal
    assert names(out / "DISPLAY") == ["holiday.part"]        # ours gone, a stranger kept


def test_killed_run_keeps_a_readable_file(tmp_path):
    """A column of 100 disks for 10^6 steps, HDF5 snapshots off, killed with SIGKILL
    after 4 s: fracas.h5 opens, complete = 0, the run's description is there and the
    series holds consecutive steps 1..n up to the last flush (at most 2 s old)."""
    out = tmp_path / "out"
    proc = subprocess.Popen([fracas_bin(), "--output", str(out), "--set", "number_of_steps=1000000",
                             "--set", "output_hdf5_every=0", "--set", "progress_every=1",
                             str(ROOT / "test_cases" / "hard" / "column_100")],
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    start = time.monotonic()
    last_step = 0
    lines = []
    while time.monotonic() - start < 4.0:
        line = proc.stdout.readline()
        if not line:
            break
        lines.append((time.monotonic(), line))
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    killed_at = time.monotonic()
    steps = [(t, int(ln.split()[1].split("/")[0])) for t, ln in lines if ln.startswith("step ")]
    assert steps, "the run printed no progress line"
    last_step = steps[-1][1]
    # the latest step printed at least 3 s before the kill: the file must hold it
    # (flushes are at most 2 s apart; 1 s of margin for a loaded machine)
    old = [s for t, s in steps if t < killed_at - 3.0]
    with h5py.File(out / "OUTBOX" / "fracas.h5", "r") as f:
        assert f.attrs["complete"] == 0
        assert f["run"].attrs["number_of_steps"] == 1000000
        assert f["contactors/radius"].shape[0] == f["bodies/number"].shape[0]
        step = f["series/step"][:]
        n = len(step)
        assert n >= 1 and n <= last_step
        np.testing.assert_array_equal(step, np.arange(1, n + 1))
        assert all(len(f["series"][c]) >= n for c in f["series"])
        if old:
            assert n >= old[-1], (n, old[-1])
