"""Restart points are validated on reading (issue 23, items 4 and 5): a corrupted point is
refused with a message naming its dataset, before anything is written, and POSTPRO's
running sums (DISSIPATED ENERGY's cumulative column) continue across a restart."""
import re
import shutil

import h5py
import numpy as np
import pytest

from fracas_run import ROOT, copy_deck, run

BEAM = ["--command", str(ROOT / "test_cases" / "compat" / "mesh_exploded_beam" / "run.dat")]


@pytest.fixture(scope="module")
def beam_run(tmp_path_factory):
    """The exploded beam (meshes, cohesive interfaces) for 10 steps, a restart point every 5."""
    tmp = tmp_path_factory.mktemp("beam")
    deck = copy_deck("mesh_exploded_beam", tmp)
    out = tmp / "first"
    p = run("-q", *BEAM, "--set", "number_of_steps=10", "--set", "output_hdf5_every=5", "--output", out, deck)
    assert p.returncode == 0, p.stderr
    return deck, out / "OUTBOX" / "fracas.h5"


def corrupt(src, dest, edit):
    shutil.copy(src, dest)
    with h5py.File(dest, "r+") as f:
        g = f["restart/5"]
        edit(g)
    return dest


def replace(g, name, data):
    del g[name]
    g[name] = data


CASES = {
    # a mesh velocity array with one row more (h5py shape (nnodes + 1, 2))
    "mesh_v_row_more": (lambda g: replace(g, "mesh/V", np.vstack([g["mesh/V"][:], [[0.0, 0.0]]])),
                        r"/restart/5/mesh/V: shape \(145, 2\) as h5py shows it, expected \(144, 2\)"),
    "energies_one_short": (lambda g: replace(g, "energies", g["energies"][:-1]),
                           r"/restart/5/energies: 6 values, expected 7"),
    "nan_family_damage": (lambda g: replace(g, "cracks/family_damage",
                                            np.full_like(g["cracks/family_damage"][:], np.nan)),
                          r"/restart/5/cracks/family_damage: value 1 is NaN"),
    "history_index_huge": (lambda g: replace(g, "history/an", np.full_like(g["history/an"][:], 2**31 - 1)),
                           r"/restart/5/history/an: value 0 \(from 0\) is 2147483647, outside 1 \.\. 174"),
    "mesh_energies_short": (lambda g: replace(g, "mesh/energies", g["mesh/energies"][:-1]),
                            r"/restart/5/mesh/energies: 4 values, expected 5"),
    # finite but absurd: the restored state must pass the state guard
    "mesh_v_huge": (lambda g: replace(g, "mesh/V", g["mesh/V"][:] + 1e300),
                    r"/restart/5: the state it holds is not sound: MAILx body 1 ran away: the velocity of node 1"),
    "gp_square_overflows": (lambda g: replace(g, "mesh/gp", np.full_like(g["mesh/gp"][:], -1e308)),
                            r"/restart/5/mesh/gp: a value beyond 1\.34078E\+154 \(its square overflows"),
    "beta_out_of_range": (lambda g: replace(g, "cracks/beta", g["cracks/beta"][:] + 2.0),
                          r"/restart/5/cracks/beta: a damage outside \[0, 1\]"),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_corrupted_restart_point_refused_at_its_dataset(beam_run, tmp_path, case):
    deck, h5 = beam_run
    edit, message = CASES[case]
    bad = corrupt(h5, tmp_path / "bad.h5", edit)
    out = tmp_path / "second"
    p = run("-q", *BEAM, "--set", "number_of_steps=10", "--restart", bad, "--restart-step", "5", "--output", out, deck)
    assert p.returncode == 1, p.stderr
    assert re.search(r"fracas: error: restart point .*bad\.h5:" + message, p.stderr), p.stderr
    assert not out.exists()                       # refused before anything is written


def test_untouched_restart_point_accepted(beam_run, tmp_path):
    deck, h5 = beam_run
    p = run("-q", *BEAM, "--set", "number_of_steps=10", "--restart", h5, "--restart-step", "5",
            "--output", tmp_path / "second", deck)
    assert p.returncode == 0, p.stderr


def test_dissipated_energy_continues_across_a_restart(tmp_path):
    """DISSIPATED ENERGY's cumulative column of a restarted run continues the uninterrupted
    run's: the rows after the restart step are the same text (bit-for-bit restart, same
    printed digits). Before, the sum started again from 0 at the restart."""
    deck = copy_deck("driven_evolution", tmp_path)
    (deck / "DATBOX" / "POSTPRO.DAT").write_text("DISSIPATED ENERGY\nSTEP 1\nEND\n")
    args = ["--set", "time_step=1e-3", "--set", "number_of_steps=60", "--set", "output_hdf5_every=20"]
    whole, first, second = tmp_path / "whole", tmp_path / "first", tmp_path / "second"
    for out, extra in ((whole, []), (first, ["--set", "number_of_steps=40"])):
        p = run("-q", *args, *extra, "--output", out, deck)
        assert p.returncode == 0, p.stderr
    p = run("-q", *args, "--restart", first / "OUTBOX" / "fracas.h5", "--restart-step", "40", "--output", second, deck)
    assert p.returncode == 0, p.stderr
    rows = (whole / "POSTPRO" / "DISSIPATED_ENERGY.DAT").read_text().splitlines()
    rest = (second / "POSTPRO" / "DISSIPATED_ENERGY.DAT").read_text().splitlines()
    assert len(rows) == 60 and len(rest) == 20
    assert float(rows[39].split()[1]) > 0                   # something was dissipated before the restart
    assert rest == rows[40:]


@pytest.mark.parametrize("every, points", [(None, [5, 10, 15, 20]), (0, [20]), (4, [4, 8, 12, 16, 20])])
def test_restart_points_where_output_restart_every_says(tmp_path, every, points):
    """Restart points come with every snapshot unless output_restart_every is given: then
    every n steps, and always at the last step (0: there only). The snapshots are not
    changed by it; a point written is one a run restarts from."""
    deck = copy_deck("driven_evolution", tmp_path)
    args = ["--set", "time_step=1e-3", "--set", "number_of_steps=20", "--set", "output_hdf5_every=5"]
    if every is not None:
        args += ["--set", f"output_restart_every={every}"]
    p = run("-q", *args, "--output", tmp_path / "run", deck)
    assert p.returncode == 0, p.stderr
    with h5py.File(tmp_path / "run" / "OUTBOX" / "fracas.h5") as f:
        assert sorted(int(k) for k in f["restart"]) == points
        assert f["restart"].attrs["last"] == 20
        assert list(f["snapshot_index/step"][:]) == [5, 10, 15, 20]
        assert f["run"].attrs["output_restart_every"] == (-1 if every is None else every)
    p = run("-q", *args, "--set", "number_of_steps=24", "--restart", tmp_path / "run" / "OUTBOX" / "fracas.h5",
            "--restart-step", str(points[0]), "--output", tmp_path / "again", deck)
    assert p.returncode == 0, p.stderr
