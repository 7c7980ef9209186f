"""Output is safe (issue 10, item 3): results of two runs never mix (a run refuses
to start over an earlier run's files, or removes them all with --overwrite), '.part'
files of a killed run are removed at the next start, and a run killed with SIGKILL
leaves a readable fracas.h5 (complete = 0) holding its series up to a recent step."""
import re
import shutil
import signal
import subprocess
import time
from pathlib import Path

import h5py
import numpy as np
import pytest

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


# Output errors are errors (issue 23, item 3). gfortran reports neither a failed flush
# nor a failed close: on a full disk every write "succeeded" and empty files were renamed
# into place until HDF5 failed; fracas now compares what each unit wrote with what
# reached the disk, and holds 1 MiB (OUTBOX/fracas.h5.reserve) freed before fracas.h5 is
# closed so that its last metadata writes find room.

def finished_files(out):
    """The result files renamed into place (not .part) under out."""
    return [p for d in ("OUTBOX", "DISPLAY", "POSTPRO") if (out / d).exists()
            for p in sorted((out / d).iterdir()) if not p.name.endswith(".part")]


def test_vanished_postpro_folder_stops_the_run(tmp_path):
    """POSTPRO/ removed while the run writes into it: the run stops at its next flush
    (at most 2 s later) naming the file, instead of finishing with exit 0."""
    deck = tmp_path / "column"
    shutil.copytree(ROOT / "test_cases" / "hard" / "column_100" / "DATBOX", deck / "DATBOX")
    (deck / "DATBOX" / "POSTPRO.DAT").write_text(POSTPRO)
    out = tmp_path / "out"
    proc = subprocess.Popen([fracas_bin(), "-q", "--output", str(out), "--set", "number_of_steps=1000000",
                             "--set", "output_hdf5_every=0", str(deck)],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    start = time.monotonic()
    while not (out / "POSTPRO" / "BODY_0000001.DAT").exists() and time.monotonic() - start < 20:
        time.sleep(0.05)
    shutil.rmtree(out / "POSTPRO")
    try:
        _, err = proc.communicate(timeout=60)
    finally:
        proc.kill()
    assert proc.returncode == 1, err
    # the stop message names the step it happened in, and fracas.h5 keeps it as end_reason
    m = re.search(r"fracas: error: (step \d+ \(t=\S+\): cannot write .*/POSTPRO/(BODY_0000001|SOLVER_INFORMATIONS)"
                  r"\.DAT: the file is gone.*)", err)
    assert m, err
    with h5py.File(out / "OUTBOX" / "fracas.h5", "r") as f:
        assert f.attrs["complete"] == 0
        assert f.attrs["end_reason"] == m.group(1)
    assert not (out / "OUTBOX" / "fracas.h5.reserve").exists()


def mounted_tmpfs(path, size):
    """A tmpfs of SIZE at PATH (root with CAP_SYS_ADMIN only); False if it cannot be mounted."""
    path.mkdir()
    return subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", str(path)],
                          capture_output=True).returncode == 0


def test_full_disk_stops_the_run_and_leaves_a_readable_file(tmp_path):
    """The exploded beam writing VTK, DOF/GPV/Vloc_Rloc.OUT, POSTPRO and fracas.h5 into a
    2 MiB file system: the first file that does not fit stops the run (exit 1, not a
    signal) naming it; no short or empty file was renamed into place; fracas.h5 opens
    with complete = 0. Skipped where a tmpfs cannot be mounted (needs root)."""
    small = tmp_path / "small"
    if not mounted_tmpfs(small, "2m"):
        pytest.skip("cannot mount a tmpfs here (needs root with CAP_SYS_ADMIN)")
    try:
        deck = copy_deck("mesh_exploded_beam", tmp_path)
        out = small / "out"
        p = run("-q", "--command", ROOT / "test_cases" / "compat" / "mesh_exploded_beam" / "run.dat",
                "--set", "number_of_steps=400", "--set", "output_dof_every=20", "--set", "output_vtk_every=20",
                "--output", out, deck, timeout=300)
        assert p.returncode == 1, (p.returncode, p.stderr)
        m = re.search(r"cannot write (\S+): (\d+) of its (\d+) bytes reached the disk \(disk full\?\)", p.stderr)
        assert m, p.stderr
        assert int(m.group(2)) < int(m.group(3))
        assert not Path(m.group(1)).exists()                    # the short file is removed
        sizes = {}
        for f in finished_files(out):
            assert f.stat().st_size > 0, f
            if f.suffix in (".vtu", ".pvd"):
                assert f.read_bytes().rstrip().endswith(b"</VTKFile>"), f
            elif f.name.startswith(("DOF.OUT.", "GPV.OUT.")):     # fixed layout: every write the same size
                sizes.setdefault(f.name.split(".OUT.")[0], set()).add(f.stat().st_size)
        assert sizes and all(len(v) == 1 for v in sizes.values()), sizes
        with h5py.File(out / "OUTBOX" / "fracas.h5", "r") as f:
            assert f.attrs["complete"] == 0
            assert f["series/step"].shape[0] >= 1
        assert not (out / "OUTBOX" / "fracas.h5.reserve").exists()
    finally:
        subprocess.run(["umount", str(small)])


def test_a_running_run_locks_its_output_folder(tmp_path):
    """A second run into the folder of a running one is refused, even with --overwrite
    (it used to remove the first run's files and mix its own in); the lock dies with
    the run, even by SIGKILL, and a run killed before fracas.h5 got its name leaves only
    a fracas.h5.part, which does not count as results (issue 23, item 9)."""
    out = tmp_path / "out"
    deck = ROOT / "test_cases" / "hard" / "column_100"
    first = subprocess.Popen([fracas_bin(), "-q", "--output", str(out), "--set", "number_of_steps=1000000",
                              "--set", "output_hdf5_every=0", str(deck)],
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        start = time.monotonic()
        while not (out / "OUTBOX" / "fracas.h5").exists() and time.monotonic() - start < 20:
            time.sleep(0.05)
        p = run("-q", "--overwrite", "--output", out, "--set", "number_of_steps=5", deck)
        assert p.returncode == 1
        assert "another run is writing into" in p.stderr and "fracas.lock is locked" in p.stderr, p.stderr
        assert first.poll() is None                               # the first run goes on
    finally:
        first.send_signal(signal.SIGKILL)
        first.wait()
    with h5py.File(out / "OUTBOX" / "fracas.h5", "r") as f:
        assert f.attrs["complete"] == 0
    (out / "OUTBOX" / "fracas.h5").rename(out / "OUTBOX" / "fracas.h5.part")   # as if killed before the rename
    p = run("-q", "--output", out, "--set", "number_of_steps=5", deck)
    assert p.returncode == 0, p.stderr
    assert names(out / "OUTBOX") == ["DOF.OUT.1", "Vloc_Rloc.OUT.1", "fracas.h5"]
