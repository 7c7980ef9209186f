"""Run control from the settings an LMGC90 user knows.

An LMGC90 deck has no COMMAND.DAT: the time step, theta, the number of steps and the
NLGS settings live in the Python script that drives pylmgc90.chipy (``dt``, ``theta``,
``nb_steps``, ``norm``, ``tol``, ``relax``, ``gs_it1``, ``gs_it2``, ``freq_detect``,
``freq_write``, ``freq_display`` in LMGC90's examples). :func:`run_control` turns those
settings into a :class:`fracas_tools.pre.RunControl`; :func:`read_run_script` reads
them from such a script (top-level assignments of plain values only: the script is
parsed, never run); ``fracas-tools command`` writes the COMMAND.DAT.

LMGC90 name       COMMAND.DAT keyword        meaning
dt                time_step                  time step
theta             theta                      theta of the Moreau-Jean scheme
nb_steps          number_of_steps            steps to run
freq_detect       detection_frequency        rough detection every n steps
norm              nlgs_check                 'Quad ', 'Maxm ', 'QM/16' (blanks ignored)
tol               nlgs_tolerance             NLGS tolerance
relax             nlgs_relaxation            relaxation
gs_it1            nlgs_sweeps_per_check      Gauss-Seidel sweeps between two checks
gs_it2            nlgs_max_checks            checks before giving up
freq_write        output_dof_every           DOF.OUT.n / Vloc_Rloc.OUT.n every n steps
freq_display      output_vtk_every           DISPLAY files every n steps

LMGC90's solver type (``stype``: 'Stored_Delassus_Loops', 'Exchange_Local_Global')
is not a setting of Fracas: its one NLGS gives the same iterates.
"""
import ast
from pathlib import Path

from .pre import RunControl

#: LMGC90 script variable -> COMMAND.DAT keyword
LMGC90_NAMES = {
    "dt": "time_step",
    "theta": "theta",
    "nb_steps": "number_of_steps",
    "freq_detect": "detection_frequency",
    "norm": "nlgs_check",
    "tol": "nlgs_tolerance",
    "relax": "nlgs_relaxation",
    "gs_it1": "nlgs_sweeps_per_check",
    "gs_it2": "nlgs_max_checks",
    "freq_write": "output_dof_every",
    "freq_display": "output_vtk_every",
}


def run_control(**lmgc90):
    """RunControl from LMGC90 settings (names as in LMGC90_NAMES; None values are
    left out). dt and nb_steps are required."""
    rc = RunControl()
    for name, value in lmgc90.items():
        if value is None:
            continue
        if name not in LMGC90_NAMES:
            raise ValueError(f"unknown LMGC90 setting {name!r}; known: {', '.join(LMGC90_NAMES)}")
        if name == "norm":
            value = str(value).strip()
        rc.set(**{LMGC90_NAMES[name]: value})
    rc.check()
    return rc


def read_run_script(path):
    """The LMGC90 settings assigned at the top level of a pylmgc90 script, e.g.
    ``dt = 1.e-3`` or ``gs_it1, gs_it2 = 50, 400`` (plain numbers and strings only)."""
    tree = ast.parse(Path(path).read_text(), filename=str(path))
    found = {}
    for node in tree.body:
        if not isinstance(node, ast.Assign) or len(node.targets) != 1:
            continue
        target, value = node.targets[0], node.value
        pairs = []
        if isinstance(target, ast.Name):
            pairs = [(target, value)]
        elif isinstance(target, ast.Tuple) and isinstance(value, ast.Tuple) and \
                len(target.elts) == len(value.elts):
            pairs = list(zip(target.elts, value.elts))
        for t, v in pairs:
            if not isinstance(t, ast.Name) or t.id not in LMGC90_NAMES:
                continue
            try:
                found[t.id] = ast.literal_eval(v)
            except ValueError:
                pass        # an expression: left for the command line to give
    return found


def write_command(case_dir, rc, overwrite=False, path=None):
    """Write rc as CASE_DIR/DATBOX/COMMAND.DAT (or path); refuse to replace an
    existing file unless overwrite. Returns the path."""
    out = Path(path) if path else Path(case_dir) / "DATBOX" / "COMMAND.DAT"
    if out.exists() and not overwrite:
        raise ValueError(f"{out} exists (pass --overwrite to replace it)")
    if not out.parent.is_dir():
        raise FileNotFoundError(f"{out.parent} is not a folder (is {case_dir} a case directory?)")
    lines = rc.lines()
    lines.insert(1, "! written by fracas-tools command from LMGC90 settings")
    out.write_text("\n".join(lines) + "\n")
    return out
