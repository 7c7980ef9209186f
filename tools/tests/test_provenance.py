"""Provenance and self-description of fracas.h5 (issue 22): `fracas --version` gives the
version, the git commit, the build type and flags, and fracas.h5 records the same with
rank and thread counts; every dataset carries `units` and a `description` (none left
'undocumented' by the table of modules/io/fracas_h5_describe.f90); counting series
are integers; /run/control lists every run-control setting as a replayable COMMAND.DAT."""
import subprocess
import sys

import h5py
import numpy as np
import pytest

from fracas_run import ROOT, fracas_bin, run, run_example


@pytest.fixture(scope="module")
def plate(tmp_path_factory):
    """The fracture demo for 40 steps (meshes, cohesive contacts, cracks, snapshots)."""
    return run_example(tmp_path_factory, "notched_plate_impact", "number_of_steps=40",
                       "output_hdf5_every=20") / "OUTBOX/fracas.h5"


def version_fields():
    p = subprocess.run([fracas_bin(), "--version"], capture_output=True, text=True)
    assert p.returncode == 0
    lines = p.stdout.splitlines()
    assert lines[0].startswith("fracas ")
    return lines[0].split()[1], dict(line.split(": ", 1) for line in lines[1:])


def test_version_names_commit_and_build():
    version, f = version_fields()
    assert set(f) == {"commit", "build", "compiler", "flags"}
    assert f["build"] in ("Release", "Debug", "RelWithDebInfo", "MinSizeRel")
    assert "-std=f2018" in f["flags"]
    head = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short=12", "HEAD"], capture_output=True, text=True)
    if head.returncode == 0:       # a build configured in this checkout (the commit is read at configure time)
        assert len(f["commit"].split("-")[0]) == 12 and all(c in "0123456789abcdef" for c in f["commit"][:12])


def test_fracas_h5_records_the_build(plate):
    version, v = version_fields()
    with h5py.File(plate) as f:
        a = f.attrs
        assert a["version"] == version and a["git_commit"] == v["commit"] and a["build_type"] == v["build"]
        assert a["compiler_flags"] == v["flags"] and a["compiler"] == v["compiler"]
        assert a["mpi_ranks"] == 1 and a["threads"] == 1


def test_every_dataset_has_units_and_description(plate):
    missing = []
    with h5py.File(plate) as f:
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                d, u = obj.attrs.get("description"), obj.attrs.get("units")
                if d in (None, "undocumented") or u in (None, "unknown"):
                    missing.append(name)
        f.visititems(visit)
        assert f["snapshots/000001/contacts/gap"].attrs["units"] == "length"
        assert "bodies/reference" in f["snapshots/000001/bodies/X"].attrs["description"]
    assert missing == []


def test_counting_series_are_integers(plate):
    with h5py.File(plate) as f:
        s = f["series"]
        for name in ("step", "contacts", "active_contacts", "sweeps", "converged", "newton_iterations",
                     "broken_interfaces", "damaged_interfaces"):
            assert s[name].dtype == np.int32, name
        assert s["time"].dtype == np.float64
        np.testing.assert_array_equal(s["step"][:], np.arange(1, 41))


def test_run_control_is_a_command_file(plate, tmp_path):
    """/run/control as COMMAND.DAT gives the same /run attributes."""
    with h5py.File(plate) as f:
        control = list(f["run/control"].asstr()[:])
        first = {k: f["run"].attrs[k] for k in f["run"].attrs if k not in ("command_file", "command_text")}
    keys = [c.split()[0] for c in control]
    assert "time_step" in keys and "number_of_steps" in keys and len(keys) == len(set(keys))
    cmd = tmp_path / "COMMAND.DAT"
    cmd.write_text("\n".join(control) + "\n")
    out = tmp_path / "again"
    p = run("-q", "--command", cmd, "--output", out, "--set", "number_of_steps=2",
            ROOT / "test_cases/examples/notched_plate_impact")
    assert p.returncode == 0, p.stderr
    with h5py.File(out / "OUTBOX/fracas.h5") as f:
        for k, v in first.items():
            if k != "number_of_steps":
                assert f["run"].attrs[k] == v, k


def test_report_on_a_fracture_run(plate, tmp_path):
    """fracas-tools report on a meshed run names its meshed bodies, reports its cracks and
    does not complain about a DATBOX it does not need (issue 22, item 10)."""
    p = subprocess.run([sys.executable, "-m", "fracas_tools", "report", str(plate.parent.parent), "--out",
                        str(tmp_path / "rep")], cwd=ROOT / "tools", capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    text = (tmp_path / "rep/report.md").read_text()
    assert "1474 meshed (1474 elements" in text and "DATBOX" not in text
    with h5py.File(plate) as f:
        length = f["series/crack_length"][-1]
    assert f"| crack length (broken interfaces) [length] | {length:.4g} |" in text
    assert (tmp_path / "rep/cracks.png").stat().st_size > 5000
