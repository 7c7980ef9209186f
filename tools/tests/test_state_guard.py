"""The state guard of meshed bodies (issue 23, items 1 and 2): a run whose nodes leave
what double precision resolves at their body's size stops at that step with exit 1, a
message naming the step, the MAILx body, the node and the quantity, and fracas.h5 marked
complete = 0. The start-of-run side (gravity, DOF.INI and driven velocities of mesh
nodes) is in test_cases/broken/mesh_*_runaway."""
import re
import subprocess
import sys

import h5py

from fracas_run import ROOT, copy_deck, run


def test_diverged_nlgs_step_of_exploded_bars_stops(tmp_path):
    """The exploded bars of validation_fracture/compliance with nlgs_relaxation 1.99
    (allowed: (0, 2)): the first step hits the sweep limit with its nodes ~1e70 m away
    (the elements are 10 mm); before the guard covered meshes the run went on, later
    steps 'converged' and fracas.h5 said complete = 1."""
    case = tmp_path / "bars"
    subprocess.run([sys.executable, str(ROOT / "test_cases" / "validation_fracture" / "compliance" / "gen.py"),
                    str(case)], check=True, capture_output=True)
    # LMGC90's explicit update: its end-point springs (twice the midpoint's stiffness) are
    # what makes this over-relaxed NLGS diverge; with damage within the step it does not.
    p = run("-q", "--set", "nlgs_relaxation=1.99", "--set", "number_of_steps=20",
            "--set", "cohesive_damage=explicit", case, timeout=120)
    assert p.returncode == 1, p.stderr
    m = re.search(r"step (\d+) \(t=\S+\): MAILx body (\d+) ran away: node (\d+) is at (\S+) from the origin "
                  r"\(displacement .*\), beyond (\S+) \(what double precision resolves at the body's size, (\S+)\)",
                  p.stderr)
    assert m, p.stderr
    step, pos, lim, size = int(m.group(1)), float(m.group(4)), float(m.group(5)), float(m.group(6))
    assert step == 1
    assert pos > lim
    assert abs(size / (0.005 * 2 ** 0.5) - 1) < 1e-5             # half the diagonal of a 10 mm square (6 digits printed)
    assert abs(lim / (1e-3 * size / 2.0 ** -52) - 1) < 1e-5         # resolvable_length
    with h5py.File(case / "OUTBOX" / "fracas.h5") as f:
        assert f.attrs["complete"] == 0
        assert f["series/step"].shape == (step - 1,)               # the faulty step is not written
        assert f.attrs["end_reason"].startswith(m.group(0))          # the stop message (issue 23, item 10)
        assert "ran away" in f.attrs["end_reason"]


def test_non_finite_series_value_stops_the_run(tmp_path):
    """A sound state can still give non-finite step results: mesh_t3_pair_czm with the
    cohesive normal stiffness cn = 1e257 (found by the mesh23 fuzz batch, deck 9536)
    wrote residual_natural_map = Inf into the series of a run that said complete = 1.
    Now the step stops the run naming the series value; fracas.h5 says complete = 0."""
    deck = copy_deck("mesh_t3_pair_czm", tmp_path)
    tact = deck / "DATBOX" / "TACT_BEHAV.DAT"
    text = tact.read_text()
    assert "cn  = 1.0000000e+11" in text
    tact.write_text(text.replace("cn  = 1.0000000e+11", "cn  = 1.000000E+257", 1))
    out = tmp_path / "out"
    p = run("-q", "--command", ROOT / "test_cases" / "compat" / "mesh_t3_pair_czm" / "run.dat",
            "--set", "number_of_steps=5", "--output", out, deck, timeout=120)
    assert p.returncode == 1, p.stderr
    assert re.search(r"step 1 \(t=\S+\): the series value residual_natural_map of the step is Infinity", p.stderr), p.stderr
    with h5py.File(out / "OUTBOX" / "fracas.h5") as f:
        assert f.attrs["complete"] == 0 and "residual_natural_map" in f.attrs["end_reason"]
