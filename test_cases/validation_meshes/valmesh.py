"""Shared helpers of the meshed validation cases: command line, running fracas on a
generated case and opening its results with the one reader (fracas_tools.results:
every fracas.h5 snapshot holds the meshes' node and Gauss-point states at full
precision, Snapshot.mesh["X"], ["V"], ["gauss_points"], or Run.snapshot_arrays
("mesh_X") for all snapshots); checks are fracas_tools.checks.Checker rows (Checker
is imported from here).

Each case script is called as  case.py --fracas BIN --out DIR [--long]
and exits 1 if a check fails."""
import argparse
import subprocess
import sys
from pathlib import Path

TOOLS = Path(__file__).resolve().parents[2] / "tools"
if str(TOOLS) not in sys.path:
    sys.path.insert(0, str(TOOLS))
from fracas_tools.checks import Checker  # noqa: E402,F401
from fracas_tools.results import Run  # noqa: E402


def args(description):
    p = argparse.ArgumentParser(description=description)
    p.add_argument("--fracas", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--long", action="store_true", help="the long version (finer meshes)")
    return p.parse_args()


def run_fracas(fracas, case_dir, *settings):
    """Run fracas on case_dir (--set for each of settings) and return its results
    (a Run, to be closed; exits on failure or an unfinished run)."""
    # no restart points before the last step: the checks read snapshots and series only
    settings = ("output_restart_every=0",) + settings
    cmd = [fracas, "-q", "--overwrite"] + [x for s in settings for x in ("--set", s)] + [str(case_dir)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"fracas failed on {case_dir}:\n{r.stdout}\n{r.stderr}")
    run = Run(case_dir)
    if not run.complete:
        sys.exit(f"{case_dir}: unfinished run")
    return run

