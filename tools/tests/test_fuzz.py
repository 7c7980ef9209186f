"""The deck fuzzer must report what it stands for: with a stand-in for fracas that
accepts every deck and then dies of SIGSEGV, or exits 0 leaving NaN in a complete
fracas.h5, or hangs, or crashes on a corrupted restart point fed back through --restart,
the batch reports crashes, lies and hangs and exits 1; with one that rejects every deck at
FILE:LINE:COL it reports located rejections and exits 0."""

import os
import stat
import subprocess
import sys
from pathlib import Path

import pytest

TOOLS = Path(__file__).resolve().parents[1]
FUZZ = TOOLS / "fuzz" / "fuzz_decks.py"

ACCEPT = 'case "$*" in *--check*) echo "check: OK (1 bodies, 1 contactors, 1 contact laws, 10 steps)"; exit 0;; esac\n'
OUTDIR = 'out=; prev=; for a in "$@"; do [ "$prev" = "--output" ] && out=$a; prev=$a; done\n'
FAKES = {
    "crash": ACCEPT + "kill -SEGV $$\n",
    "hang": ACCEPT + "sleep 30\n",
    "lie": ACCEPT + OUTDIR + (
        f'PYTHONPATH={str(TOOLS)!r} /usr/bin/python3 - "$out" <<PY\n'
        "import sys, h5py\n"
        "from fracas_tools import synthetic\n"
        "p = sys.argv[1] + '/OUTBOX/fracas.h5'\n"
        "import os; os.makedirs(sys.argv[1] + '/OUTBOX', exist_ok=True)\n"
        "synthetic.make_h5(p, nx=3, ny=2, n_steps=10, snapshot_every=5, help_style='writer')\n"
        "with h5py.File(p, 'r+') as f: f['series/kinetic_energy'][3] = float('nan')\n"
        "PY\n"),
    "reject": 'echo "$1:3:5: a planted rejection" >&2; exit 1\n',
    # a sound run with a restart point, then SIGSEGV when it is fed back through --restart
    "restart_crash": 'case "$*" in *--restart*) kill -SEGV $$;; esac\n' + ACCEPT + OUTDIR + (
        f'PYTHONPATH={str(TOOLS)!r} /usr/bin/python3 - "$out" <<PY\n'
        "import sys, h5py, numpy as np\n"
        "from fracas_tools import synthetic\n"
        "p = sys.argv[1] + '/OUTBOX/fracas.h5'\n"
        "import os; os.makedirs(sys.argv[1] + '/OUTBOX', exist_ok=True)\n"
        "synthetic.make_h5(p, nx=3, ny=2, n_steps=10, snapshot_every=5, help_style='writer')\n"
        "with h5py.File(p, 'r+') as f:\n"
        "    g = f.create_group('restart'); g.attrs['last'] = 10; g.create_group('10')['X'] = np.zeros((6, 3))\n"
        "PY\n"),
}


def run_fuzz(tmp_path, kind):
    fake = tmp_path / f"fake_{kind}"
    fake.write_text("#!/bin/sh\n" + FAKES[kind])
    fake.chmod(fake.stat().st_mode | stat.S_IEXEC)
    r = subprocess.run([sys.executable, str(FUZZ), "--fracas", str(fake), "--decks", "2", "--seed", "t",
                        "--sources", "small", "--steps", "10", "--jobs", "1",
                        "--run-timeout", "3" if kind == "hang" else "120", "--restarts", "1"],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    counts = {}
    for line in r.stdout.splitlines():
        w = line.split()
        if len(w) == 2 and w[1].isdigit():
            counts[w[0]] = int(w[1])
    return r.returncode, counts, r.stdout


@pytest.mark.parametrize("kind,key", [("crash", "run_crash"), ("hang", "run_hang"), ("lie", "run_lie"),
                                      ("restart_crash", "restart_crash")])
def test_fuzzer_reports(tmp_path, kind, key):
    rc, counts, out = run_fuzz(tmp_path, kind)
    assert rc == 1 and counts.get(key) == 2, out


def test_fuzzer_clean(tmp_path):
    rc, counts, out = run_fuzz(tmp_path, "reject")
    assert rc == 0 and counts.get("check_rejected_located") == 2, out
