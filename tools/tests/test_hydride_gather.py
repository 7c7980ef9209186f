"""tools/hydride/gather.py: a campaign's summaries (synthetic summary.json files with
known shares) gathered into the table and the claim: mean and sample standard deviation
over seeds per bonding x element size, strong - weak differences paired by seed."""
import json
import sys
from pathlib import Path

import numpy as np
import pytest

from fracas_tools.scripts import load

gather = load(Path(__file__).resolve().parents[1] / "hydride" / "gather.py")

# (bonding, seed): shares HY_HY, HY_MA, MA_MA
SHARES = {("weak", 1): (0.00, 0.70, 0.30), ("weak", 2): (0.10, 0.50, 0.40), ("weak", 3): (0.05, 0.60, 0.35),
          ("strong", 1): (0.30, 0.20, 0.50), ("strong", 2): (0.20, 0.30, 0.50), ("strong", 3): (0.40, 0.10, 0.50)}


def summary(bonding, seed, shares):
    fam = dict(zip(("HY_HY", "HY_MA", "MA_MA"), shares))
    zero = {f: 0.0 for f in fam}
    return dict(seed=seed, bonding=bonding, h=1e-6, h_mean=0.95e-6, elements=2600 + seed, steps=800,
                crack=dict(separated=True, reach=1.0, path_length=40e-6, shares=fam, microcracks=seed,
                           microcrack_edges=2 * seed, broken_edges=50),
                peak_stress=800e6, strain_at_peak=0.01,
                energies=dict(work_supports=1.0, plastic=0.8, damage=0.1, damage_per_family=zero,
                              friction_and_numerical=0.05, kinetic=0.03, elastic=0.02,
                              relative_balance_error=1e-4),
                cpu_seconds=70.0, cpu_seconds_process=80.0 + seed, wall_seconds=300.0, load_average=4.0)


@pytest.fixture
def root(tmp_path):
    for (bonding, seed), shares in SHARES.items():
        d = tmp_path / f"{bonding}_h1000_s{seed}"
        d.mkdir()
        (d / "summary.json").write_text(json.dumps(summary(bonding, seed, shares)))
    return tmp_path


def test_table_and_claim(root):
    rows = [gather.flat(s) | {"dir": s["dir"]} for s in gather.load(root)]
    assert len(rows) == 6
    text = gather.markdown(rows)
    # weak HY_MA shares 70, 50, 60 %: mean 60, sample standard deviation 10
    weak = next(line for line in text.splitlines() if line.startswith("| weak | 1 |"))
    assert "60 % ± 10 %" in weak and "| 3/3 |" in weak
    strong = next(line for line in text.splitlines() if line.startswith("| strong | 1 |"))
    assert "30 % ± 10 %" in strong                # HY_HY 30, 20, 40
    c = gather.claim(rows)[1.0]
    dh = [0.30 - 0.00, 0.20 - 0.10, 0.40 - 0.05]   # strong - weak through hydrides, by seed
    di = [0.70 - 0.20, 0.50 - 0.30, 0.60 - 0.10]   # weak - strong along interfaces
    assert c["seeds"] == 3
    assert c["through_hydrides"] == pytest.approx((np.mean(dh), np.std(dh, ddof=1), min(dh)))
    assert c["along_interfaces"] == pytest.approx((np.mean(di), np.std(di, ddof=1), min(di)))
    assert "| 1 | 2 | +10 | +20 |" in text       # seed 2 row of the claim table
    # runtime: weak processor times 81, 82, 83 s over 2601..2603 elements x 800 steps
    run = next(line for line in text.splitlines() if line.startswith("| weak | 1 | 2602 | 800 |"))
    assert "| 82 ± 1 | " in run and f"| {82 / (2602 * 800):.2e} |" in run
