"""Helpers for the tests that run the fracas program: where it is, where the
LMGC90 decks are, a copy of a deck to change, and one run."""
import os
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def fracas_bin():
    """FRACAS_BIN (set by ctest), else a build tree's bin/fracas; skip without one."""
    env = os.environ.get("FRACAS_BIN")
    if env and Path(env).exists():
        return env
    found = sorted(ROOT.glob("build/*/bin/fracas"), key=os.path.getmtime)
    if not found:
        pytest.skip("no fracas binary built (set FRACAS_BIN)")
    return str(found[-1])


def lmgc90_decks():
    """FRACAS_LMGC90_DECKS (set by ctest), else ../shared/lmgc90_decks; skip without them."""
    d = Path(os.environ.get("FRACAS_LMGC90_DECKS", ROOT.parent / "shared" / "lmgc90_decks"))
    if not (d / "driven_evolution").is_dir():
        pytest.skip(f"LMGC90 decks not found at {d} (set FRACAS_LMGC90_DECKS)")
    return d


def copy_deck(name, dest):
    """A writable copy of LMGC90 deck NAME's DATBOX (and run.py) under dest."""
    src = lmgc90_decks() / name
    dest = Path(dest) / name
    shutil.copytree(src / "DATBOX", dest / "DATBOX")
    if (src / "run.py").exists():
        shutil.copy(src / "run.py", dest / "run.py")
    for p in dest.rglob("*"):
        p.chmod(0o644 if p.is_file() else 0o755)
    return dest


def run(*args, timeout=600, **kw):
    """Run fracas with args; returns the CompletedProcess (text output)."""
    return subprocess.run([fracas_bin(), *map(str, args)], capture_output=True, text=True, timeout=timeout, **kw)


def run_example(tmp_path_factory, name, *settings):
    """Run the example deck test_cases/examples/NAME (quietly, with the --set SETTINGS
    KEY=VALUE) into a fresh temporary folder; returns that folder."""
    out = tmp_path_factory.mktemp(name)
    p = run("-q", "--output", out, *(a for s in settings for a in ("--set", s)), ROOT / "test_cases/examples" / name)
    assert p.returncode == 0, p.stderr
    return out
