"""LMGC90 decks as LMGC90 users run them (issue 9, items 3 and 4): no COMMAND.DAT,
run control from --set or from the settings of a pylmgc90 script, warnings for
missing initial files and see rules that never apply, POSTPRO.DAT commands, and
NLGS non-convergence made visible and, on request, fatal (exit status 3)."""
import re
import subprocess
import sys

import h5py
import numpy as np
import pytest

from fracas_run import ROOT, copy_deck, lmgc90_decks, run

from fracas_tools.lmgc90 import read_run_script  # noqa: E402


def test_missing_command_dat_says_what_to_do(tmp_path):
    p = run("--output", tmp_path / "out", lmgc90_decks() / "driven_evolution")
    assert p.returncode == 1
    for hint in ("--set time_step=", "number_of_steps=", "--command FILE", "fracas-tools command"):
        assert hint in p.stderr, p.stderr
    assert not (tmp_path / "out").exists()          # nothing written


def test_set_alone_runs_with_defaults(tmp_path):
    out = tmp_path / "out"
    p = run("-q", "--output", out, "--set", "time_step=1e-3", "--set", "number_of_steps=20",
            lmgc90_decks() / "driven_evolution")
    assert p.returncode == 0, p.stderr
    assert "no " in p.stderr and "COMMAND.DAT: run control from --set and the defaults" in p.stderr
    with h5py.File(out / "OUTBOX" / "fracas.h5") as f:
        r = f["run"].attrs
        assert r["time_step"] == 1e-3 and r["number_of_steps"] == 20
        # the documented defaults (doc/input_reference.md section 2)
        assert r["theta"] == 0.5 and r["nlgs_tolerance"] == 1e-4 and r["nlgs_check"] == "Quad"
        assert r["nlgs_sweeps_per_check"] == 50 and r["nlgs_max_checks"] == 400
        assert r["nlgs_unconverged"] == "warn" and r["command_file"] == ""
        assert list(f["run/settings"].asstr()[:]) == ["time_step=1e-3", "number_of_steps=20"]
        assert f["series/step"].shape == (20,)
        assert "deck" in f.attrs["units"]
        np.testing.assert_allclose(f.attrs["gravity"], [0.0, -9.81, 0.0])


def test_command_from_pylmgc90_script(tmp_path):
    deck = copy_deck("driven_evolution", tmp_path)
    tools = [str(ROOT / "tools" / "fracas-tools")]
    p = subprocess.run([*tools, "command", str(deck), "--from-script", str(deck / "run.py"),
                        "--freq-write", "100"], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    text = (deck / "DATBOX" / "COMMAND.DAT").read_text()
    # reference: the literal values assigned in the deck's run.py
    s = read_run_script(deck / "run.py")
    assert (s["dt"], s["nb_steps"], s["gs_it1"], s["gs_it2"], s["tol"]) == (1e-3, 2500, 50, 400, 1e-4)
    for line in ("time_step 0.001", "number_of_steps 2500", "theta 0.5", "nlgs_check Quad",
                 "nlgs_tolerance 0.0001", "nlgs_sweeps_per_check 50", "nlgs_max_checks 400",
                 "detection_frequency 1", "output_dof_every 100"):
        assert re.search(rf"^{line}$", text, re.M), (line, text)
    # refuses to replace it; fracas runs with it
    p = subprocess.run([*tools, "command", str(deck), "--dt", "1e-3", "--steps", "5"],
                       capture_output=True, text=True)
    assert p.returncode != 0 and "exists" in p.stderr
    p = run("-q", "--set", "number_of_steps=30", deck)
    assert p.returncode == 0, p.stderr
    with h5py.File(deck / "OUTBOX" / "fracas.h5") as f:
        assert "written by fracas-tools command" in f["run"].attrs["command_text"]
        assert f["run"].attrs["number_of_steps"] == 30            # --set wins over the file
        assert f["run"].attrs["command_file"].endswith("DATBOX/COMMAND.DAT")


def test_warnings_for_missing_initial_files_and_dead_see_rules(tmp_path):
    deck = copy_deck("disks_box", tmp_path)
    (deck / "DATBOX" / "DOF.INI").unlink()
    (deck / "DATBOX" / "Vloc_Rloc.INI").unlink()
    tact = deck / "DATBOX" / "TACT_BEHAV.DAT"
    lines = tact.read_text().splitlines(keepends=True)
    k = next(i for i, ln in enumerate(lines) if ln.startswith("$seety"))
    # the rule line is two lines below $seety (after its header line)
    rule = k + 2
    assert "WALLx" in lines[rule] or "BLEUx" in lines[rule]
    lines[rule] = lines[rule].replace("BLEUx", "BLUEx", 1)
    tact.write_text("".join(lines))
    p = run("--check", "--set", "time_step=1e-3", "--set", "number_of_steps=1", deck)
    assert p.returncode == 0, p.stderr
    assert "DOF.INI not found: every body starts at rest" in p.stderr
    assert "Vloc_Rloc.INI not found: the run starts without contact history" in p.stderr
    assert re.search(rf"TACT_BEHAV.DAT:{rule + 1}: see rule .*BLUEx.*: no DISKx contactor has colour BLUEx",
                     p.stderr), p.stderr


def write_postpro(deck, text):
    (deck / "DATBOX" / "POSTPRO.DAT").write_text(text)


def test_postpro_commands_checked(tmp_path):
    deck = copy_deck("driven_evolution", tmp_path)
    write_postpro(deck, "SOLVER INFORMATIONS\nSTEP 1\nBODY TRACKIN\nSTEP 10\n      1\n      1\nEND\n")
    p = run("--check", "--set", "time_step=1e-3", "--set", "number_of_steps=1", deck)
    assert p.returncode == 1
    assert "POSTPRO.DAT:3:1: unknown POSTPRO command 'BODY TRACKIN'; did you mean 'BODY TRACKING'?" in p.stderr
    write_postpro(deck, "BODY TRACKING\nSTEP 10\n      2\n      1\n      7\nEND\n")
    p = run("--check", "--set", "time_step=1e-3", "--set", "number_of_steps=1", deck)
    assert p.returncode == 1 and "POSTPRO.DAT:5:1: BODY TRACKING: body 7 does not exist" in p.stderr
    write_postpro(deck, "COORDINATION NUMBER\nSTEP 1\nDep EVOLUTION\nSTEP 1\nSOLVER INFORMATIONS\nSTEP 2\nEND\n")
    out = tmp_path / "out"
    p = run("-q", "--output", out, "--set", "time_step=1e-3", "--set", "number_of_steps=10", deck)
    assert p.returncode == 0, p.stderr
    assert "POSTPRO.DAT:1: POSTPRO command 'COORDINATION NUMBER' is not carried out by Fracas: skipped" in p.stderr
    assert "Dep EVOLUTION and Fint EVOLUTION without node sets ('NEW MECAx SETS'): nothing to write, skipped" in p.stderr
    assert sorted(x.name for x in (out / "POSTPRO").iterdir()) == ["SOLVER_INFORMATIONS.DAT"]
    t = np.loadtxt(out / "POSTPRO" / "SOLVER_INFORMATIONS.DAT")[:, 0]
    np.testing.assert_allclose(t, [0.002, 0.004, 0.006, 0.008, 0.010])      # STEP 2


def test_check_and_run_agree_on_node_sets(tmp_path):
    """NEW MECAx SETS announcing 3 sets where 2 follow (issue 23, item 6): --check used to
    say OK and the run refuse the deck after creating OUTBOX/fracas.h5 and
    DISPLAY/fracas.pvd (so the next run needed --overwrite). Both refuse it now, at the
    same line, and the run writes nothing."""
    deck = copy_deck("mesh_exploded_beam", tmp_path)
    text = (deck / "DATBOX" / "POSTPRO.DAT").read_text().splitlines()
    assert text[2].strip() == "2"
    text[2] = text[2].replace("2", "3")
    (deck / "DATBOX" / "POSTPRO.DAT").write_text("\n".join(text) + "\n")
    args = ["--set", "time_step=2e-5", "--set", "number_of_steps=5", "--set", "output_vtk_every=1"]
    check = run("--check", *args, deck)
    out = tmp_path / "out"
    p = run("-q", "--output", out, *args, deck)
    where = re.search(r"POSTPRO\.DAT:\d+:\d+: NEW MECAx SETS: .*", p.stderr)
    assert check.returncode == 1 and p.returncode == 1, (check.stdout, p.stderr)
    assert where and where.group(0) in check.stderr
    assert not out.exists()


def test_dissipated_energy_of_a_sliding_disk(tmp_path):
    """driven_evolution: the disk is pushed by Fx(t), slides from about t = 0.41 s to
    1.98 s against dynamic friction 0.4 W and sticks otherwise. Reference: the
    friction work mu_d W (x_stop - x_onset), with x from BODY_0000001.DAT
    (independent of the contact sums that DISSIPATED ENERGY adds up). The static
    phases add nothing; the two transition steps make the 0.5 % tolerance."""
    deck = copy_deck("driven_evolution", tmp_path)
    write_postpro(deck, "DISSIPATED ENERGY\nSTEP 1\nBODY TRACKING\nSTEP 1\n      1\n      1\nEND\n")
    out = tmp_path / "out"
    p = run("-q", "--output", out, "--set", "time_step=1e-3", "--set", "number_of_steps=2500", deck)
    assert p.returncode == 0, p.stderr
    e = np.loadtxt(out / "POSTPRO" / "DISSIPATED_ENERGY.DAT")
    body = np.loadtxt(out / "POSTPRO" / "BODY_0000001.DAT")
    assert e.shape == (2500, 3)
    np.testing.assert_allclose(np.cumsum(e[:, 2]), e[:, 1], rtol=1e-6, atol=1e-9)   # running sum
    x, v = body[:, 4], body[:, 7]
    moving = np.nonzero(np.abs(v) > 1e-9)[0]
    x_onset, x_stop = x[moving[0] - 1], x[moving[-1] + 1]
    weight = 1000.0 * np.pi * 0.1 ** 2 * 9.81
    reference = 0.4 * weight * (x_stop - x_onset)
    assert reference > 250.0
    assert e[-1, 1] == pytest.approx(reference, rel=5e-3)
    with h5py.File(out / "OUTBOX" / "fracas.h5") as f:                     # same sum as the HDF5 series
        assert e[-1, 1] == pytest.approx(f["series/dissipated"][-1], rel=1e-6)


def test_dissipated_energy_of_an_impact(tmp_path):
    """The same disk thrown down onto the ground at v0 = 1 m/s (DOF.INI): IQS stops it
    in the first step with the impulse r = m (v0 + g h) (theta = 0.5), and the
    energy dissipated in that step is -r (u_begin + u_end)/2 = m (v0 + g h) v0 / 2
    (= m v0^2 / 2 + the work of gravity over the step): the closed form of the
    scheme, to the printed precision."""
    deck = copy_deck("driven_evolution", tmp_path)
    dof = (deck / "DATBOX" / "DOF.INI").read_text().rstrip() + "\n" + (
        "$bdyty\n RBDY2      1\n$nodty\n"
        " NO3xx      1                X(1)= 0.0000000D+00  X(2)= 0.0000000D+00  X(3)= 0.0000000D+00\n"
        "                             V(1)= 0.0000000D+00  V(2)=-0.1000000D+01  V(3)= 0.0000000D+00\n"
        "$$$$$$\n")
    (deck / "DATBOX" / "DOF.INI").write_text(dof)
    write_postpro(deck, "DISSIPATED ENERGY\nSTEP 1\nEND\n")
    out = tmp_path / "out"
    p = run("-q", "--output", out, "--set", "time_step=1e-3", "--set", "number_of_steps=3", deck)
    assert p.returncode == 0, p.stderr
    e = np.loadtxt(out / "POSTPRO" / "DISSIPATED_ENERGY.DAT")
    m, g, h, v0 = 1000.0 * np.pi * 0.1 ** 2, 9.81, 1e-3, 1.0
    assert e[0, 2] == pytest.approx(m * (v0 + g * h) * v0 / 2, abs=1e-6)   # 1 unit of the 8th printed digit


# ---------------------------------------------------------------- NLGS non-convergence

def run_unconverged(tmp_path, mode, starve=True):
    """30 steps of a column of 100 disks (test_cases/hard/column_100), with two
    sweeps per step (starve): far too few for Maxm 1e-6 on 200 stacked contacts."""
    out = tmp_path / mode
    limits = ["--set", "nlgs_max_checks=1", "--set", "nlgs_sweeps_per_check=2"] if starve else []
    p = run("--overwrite", "--output", out, "--set", "number_of_steps=30", "--set", "progress_every=10", *limits,
            "--set", f"nlgs_unconverged={mode}", ROOT / "test_cases" / "hard" / "column_100")
    return p, out / "OUTBOX" / "fracas.h5"


def test_unconverged_steps_warned(tmp_path):
    p, h5 = run_unconverged(tmp_path, "warn")
    assert p.returncode == 0, p.stderr
    said = re.findall(r"step (\d+) \(t=.*\): NLGS did not converge in 2 sweeps", p.stdout)
    assert 1 <= len(said) <= 10
    with h5py.File(h5) as f:
        conv = f["series/converged"][:]
        assert f.attrs["complete"] == 1 and len(conv) == 30
        n = int(np.sum(conv == 0))
        assert n == 30                                       # the tolerance cannot be met in 2 sweeps
        assert int(said[0]) == int(f["series/step"][np.argmin(conv)])
    assert f"{n} of 30 steps reached the NLGS sweep limit" in p.stderr
    assert re.search(rf"unconverged steps {n}$", p.stdout, re.M)      # the last progress line counts them


def test_unconverged_steps_fail(tmp_path):
    p, h5 = run_unconverged(tmp_path, "fail")
    assert p.returncode == 3
    assert "nlgs_unconverged = fail" in p.stderr
    with h5py.File(h5) as f:
        assert f.attrs["complete"] == 1 and f["series/step"].shape == (30,)   # the run went to its end


def test_unconverged_steps_stop(tmp_path):
    p, h5 = run_unconverged(tmp_path, "stop")
    assert p.returncode == 3
    step = int(re.search(r"step (\d+) \(t=", p.stderr).group(1))
    with h5py.File(h5) as f:
        assert f.attrs["complete"] == 0 and "nlgs_unconverged = stop" in f.attrs["end_reason"]
        assert f["series/step"][-1] == step == 1 and f["series/converged"][-1] == 0


def test_converged_run_passes_in_fail_mode(tmp_path):
    p, h5 = run_unconverged(tmp_path, "fail", starve=False)
    assert p.returncode == 0, p.stderr
    assert "NLGS did not converge" not in p.stdout


def test_newton_iterations_share_the_step_sweep_budget(tmp_path):
    """A J2 body's Newton iterations share the step's NLGS sweep budget
    (nlgs_sweeps_per_check x nlgs_max_checks, the bound --check enforces) instead of each
    running it all (issue 23, item 11: one step took 354 s, 20 x the bound). The hydrided
    plate (J2 matrix, cohesive interfaces) with a budget of 2 x 3 sweeps and a tolerance
    it cannot meet: before, steps took up to 30 sweeps; now at most 6, marked unconverged.
    (Without the deck's crack_step_limit: the budget is a scene step's, and a step cut into
    sub-steps adds up theirs.)"""
    out = tmp_path / "out"
    p = run("-q", "--set", "number_of_steps=120", "--set", "nlgs_sweeps_per_check=2", "--set", "nlgs_max_checks=3",
            "--set", "nlgs_tolerance=1e-15", "--set", "crack_step_limit=0", "--output", out,
            ROOT / "test_cases" / "validation" / "hydrided_plate" / "weak")
    assert p.returncode == 0, p.stderr
    with h5py.File(out / "OUTBOX" / "fracas.h5") as f:
        sweeps = f["series/sweeps"][:]
        assert len(sweeps) == 120 and sweeps.max() <= 6
        assert f["series/newton_iterations"][:].max() >= 2          # the steps did iterate
        assert (f["series/converged"][:] == 0).all()
