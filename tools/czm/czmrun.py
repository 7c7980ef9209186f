"""A fracas.h5 of a cohesive run as numpy arrays (test_cases/validation/czm_*), on the one
reader of fracas.h5 (fracas_tools.results.Results):

    run = Results("path/to/run_dir")      # or the .h5 file
    run.series["damage_dissipated"]      # one value per step
    run.step, run.time                   # (ns,) per snapshot
    run.X, run.V                         # (ns, nb, 3)
    run.contacts[i]                      # dict of arrays of snapshot i (incl. internals, broken)
    pair = run.pair(cd, an)              # contacts between bodies cd and an, per snapshot:
    pair.rn, pair.rt, pair.gap, pair.L, pair.ut, pair.un, pair.beta, pair.tpsini,
    pair.broken, pair.status             # (ns, npts) arrays (npts = points of the pair)

Snapshots are expected at every step (output_hdf5_every 1) and the pair is expected to
keep the same number of contact points in all snapshots (the glued faces here).
"""

import sys
from pathlib import Path

from fracas_tools.results import Pair, Results  # noqa: E402

__all__ = ["CzmRun", "Pair"]


class Results(Results):
    def __init__(self, run_dir, bodies=True, full=False):
        """bodies: read X and V of every snapshot. full is accepted for older scripts:
        the contacts' velocities, gaps and normals are always read (on demand)."""
        super().__init__(run_dir, bodies=bodies)
