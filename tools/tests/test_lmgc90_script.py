"""fracas-tools command --from-script reads what LMGC90's scripts really pass, and says
what it did not understand (issue 18, bug 6) and the physics the script sets up outside
the deck (bug 7). The script below is written the way LMGC90's example scripts are
(examples/*/command.py): the reference values are what LMGC90 would run with it."""
import subprocess
import sys
from pathlib import Path

from fracas_tools.lmgc90 import read_run_script  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]

SCRIPT = '''
from pylmgc90 import chipy
chipy.Initialize()
dt = 1.e-3
t_final = 0.25
nb_steps = int(t_final / dt)
theta = 0.5
tol, relax = 1.666e-4, 1.
norm = 'Quad '
chipy.TimeEvolution_SetTimeStep(dt)
chipy.Integrator_InitTheta(theta)
chipy.ReadDatbox(deformable=False)
chipy.SetPeriodicCondition(xperiod=1.1)
chipy.nlgs_SetWithQuickScramble()
for k in range(1, nb_steps + 1):
    chipy.IncrementStep()
    chipy.ExSolver('Stored_Delassus_Loops         ', norm, tol, relax, 33, 101)
    chipy.WriteOut(freq_write)
'''


def test_settings_from_the_calls_and_the_loop(tmp_path):
    p = tmp_path / "command.py"
    p.write_text(SCRIPT)
    r = read_run_script(p)
    # ExSolver's literal loop counts, the loop's length (int(0.25 / 1e-3) = 250 steps)
    assert (r["dt"], r["nb_steps"], r["theta"], r["gs_it1"], r["gs_it2"]) == (1e-3, 250, 0.5, 33, 101)
    assert (r["norm"], r["tol"], r["relax"]) == ("Quad ", 1.666e-4, 1.0)
    assert r["quickscramble"]
    # freq_write is never assigned: said, not guessed
    assert any("argument 1 (freq_write) not read" in n for n in r.not_understood), r.not_understood
    assert any(n.startswith("periodic boundaries (SetPeriodicCondition") for n in r.physics), r.physics


def test_while_loop_on_the_time(tmp_path):
    p = tmp_path / "command.py"
    # LMGC90 adds dt to the time each step: 0.01 ten times is below 0.1, an 11th step runs
    p.write_text("from pylmgc90 import chipy\nt_final = 0.1\ndt = 0.01\n"
                 "while chipy.TimeEvolution_GetTime() < t_final:\n    chipy.IncrementStep()\n")
    assert read_run_script(p)["nb_steps"] == 11


def test_command_says_what_it_did_not_read(tmp_path):
    case = tmp_path / "case"
    (case / "DATBOX").mkdir(parents=True)
    p = tmp_path / "command.py"
    p.write_text(SCRIPT)
    r = subprocess.run([str(ROOT / "tools" / "fracas-tools"), "command", str(case), "--from-script", str(p)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert "not in Fracas (the mechanics alone is run): periodic boundaries" in r.stderr
    assert "not understood:" in r.stderr
    text = (case / "DATBOX" / "COMMAND.DAT").read_text()
    for line in ("number_of_steps 250", "nlgs_sweeps_per_check 33", "nlgs_max_checks 101", "nlgs_order shuffled",
                 "! not in Fracas (the mechanics alone is run): periodic boundaries"):
        assert line in text, (line, text)


def test_modelling_hypothesis(tmp_path):
    # SetDimension(dim, mhyp): 1 plane strain, 2 plane stress, 3 axisymmetry (LMGC90's
    # taylor example runs axisymmetric: without it, its bar spreads 2.4 times too far)
    from fracas_tools.lmgc90 import run_control
    p = tmp_path / "command.py"
    p.write_text("from pylmgc90 import chipy\ndim = 2\nmhyp = 3\nchipy.SetDimension(dim, mhyp)\n"
                 "dt = 1e-7\nchipy.TimeEvolution_SetTimeStep(dt)\nfor k in range(10):\n    chipy.IncrementStep()\n")
    r = read_run_script(p)
    assert r["mhyp"] == 3
    assert "plane axisym" in "\n".join(run_control(**r).lines())
