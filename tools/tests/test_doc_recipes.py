"""The recipes of the docs run as printed (issue 22): doc/fracture.md §1's deck, executed
from the repository's root with its output redirected to a temporary folder, builds the
demo deck test_cases/examples/notched_plate_impact (same bodies, laws, materials, initial
state as its gen.py writes) and runs."""
import re
import subprocess
import sys

import pytest

from fracas_run import ROOT, run

pytest.importorskip("gmsh")


def python_block(doc, section):
    text = (ROOT / doc).read_text()
    m = re.search(rf"^## {section}\..*?```python\n(.*?)```", text, re.S | re.M)
    assert m, f"no python block in {doc} section {section}"
    return m.group(1)


def test_fracture_deck_recipe(tmp_path):
    code = python_block("doc/fracture.md", 1)
    assert '"build/my_plate"' in code
    code = code.replace('"build/my_plate"', repr(str(tmp_path / "my_plate")))
    p = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    made, demo = tmp_path / "my_plate" / "DATBOX", ROOT / "test_cases/examples/notched_plate_impact/DATBOX"
    for name in ("BODIES.DAT", "BULK_BEHAV.DAT", "TACT_BEHAV.DAT", "MODELS.DAT", "DOF.INI", "impact.txt"):
        assert (made / name).read_text() == (demo / name).read_text(), name
    cmd = (made / "COMMAND.DAT").read_text()
    assert re.search(r"^output_vtk_every 32$", cmd, re.M)        # the recipe writes DISPLAY
    p = run("-q", "--set", "number_of_steps=4", tmp_path / "my_plate")
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "my_plate/DISPLAY/fracas.pvd").exists()
