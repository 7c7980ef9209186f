#!/usr/bin/python3
"""Energy audit of the czm_energy run (README.md): a glued block pushed until the glue
breaks, then sliding with friction. Every term is recomputed in Python from the
snapshots (positions, velocities, contact reactions and internals) and the damage is
taken from the closed form w L:

    W_F + W_g = KE + stored + w L (once broken) + friction      within 1 % of W_F

usage: check.py RUN_DIR
Prints one line per quantity and exits 1 if any check fails.
"""
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
import gen          # noqa: E402
from fracas_tools import valtools     # noqa: E402
from fracas_tools.results import Results  # noqa: E402

GROUND, BLOCK = 1, 2
AUDIT_TOL = 1e-2


def force(t):
    return gen.F0 * np.minimum(1.0, np.asarray(t) / gen.T_RAMP)


def audit(run, pr):
    """Cumulative terms per step (ns,), all J/m, recomputed from the snapshots."""
    h, law = run.h, gen.LAW
    t = run.time
    t0 = np.concatenate([[0.0], t[:-1]])
    X = run.X[:, BLOCK - 1]
    V = run.V[:, BLOCK - 1]
    dX = np.diff(np.vstack([np.zeros(3), X]), axis=0)
    m, inertia = run.mass[BLOCK - 1], run.inertia[BLOCK - 1]
    w_f = np.cumsum(0.5 * (force(t0) + force(t)) * dX[:, 0])       # theta = 0.5 average of F
    w_g = np.cumsum(-m * gen.G * dX[:, 1])
    ke = 0.5 * m * (V[:, 0] ** 2 + V[:, 1] ** 2) + 0.5 * inertia * V[:, 2] ** 2
    stored = np.sum(0.5 * pr.L * pr.beta * (law.cn * np.maximum(pr.un, 0.0) ** 2 + law.ct * pr.ut ** 2), axis=1)
    # contact part of the reaction = total - cohesive (frozen beta of the step): friction
    beta_prev = np.vstack([np.ones((1, pr.beta.shape[1])), pr.beta[:-1]])
    rct = pr.rt + pr.L * beta_prev * law.ct * pr.ut
    rcn = pr.rn + pr.L * beta_prev * law.cn * np.maximum(pr.un, 0.0)
    vt_prev = np.vstack([np.zeros((1, pr.vt.shape[1])), pr.vt[:-1]])
    vn_prev = np.vstack([np.zeros((1, pr.vn.shape[1])), pr.vn[:-1]])
    friction = np.cumsum(np.sum(-h * (rct * 0.5 * (pr.vt + vt_prev) + rcn * 0.5 * (pr.vn + vn_prev)), axis=1))
    return dict(w_f=w_f, w_g=w_g, ke=ke, stored=stored, friction=friction, rct=rct)


def main():
    run = Results(valtools.run_dir_from_argv(HERE))
    ck = valtools.Checker("czm_energy (MP3_CZM, pushed glued block)")
    law, s = gen.LAW, run.series
    pr = run.pair(BLOCK, GROUND)
    ck.true("run complete, a snapshot per step", run.complete == 1 and len(run.step) == gen.STEPS)
    ck.true("NLGS converged at every step", bool(np.all(s["converged"] == 1)))
    ck.true("two glued points of L = 0.5 m in every step", bool(np.all(pr.present) and np.all(pr.L == 0.5)))
    a = audit(run, pr)
    beta = pr.mean("beta")
    i_b = int(np.argmax(beta <= 0.0))                 # first step with the glue broken
    ck.true("the glue breaks", beta[-1] == 0.0 and i_b > 0 and np.all(pr.broken[i_b:] == 1),
            ours=f"t = {run.time[i_b]:.4f} s, F = {force(run.time[i_b]):.0f} N/m")
    ck.at_most("max normal jump (m): pure mode II (no tipping)", np.abs(pr.un).max(), 1e-12)
    GL = law.w * pr.L[0].sum()

    # the audit at the break, at the end of the ramp and at the end
    i_ramp = int(np.argmin(np.abs(run.time - gen.T_RAMP)))
    for label, i in (("break", i_b), ("end of ramp", i_ramp), ("end", len(run.time) - 1)):
        lhs = a["w_f"][i] + a["w_g"][i]
        rhs = a["ke"][i] + a["stored"][i] + GL + a["friction"][i]
        ck.rel(f"audit at {label} (t = {run.time[i]:.4f}): W_F + W_g = KE + stored + wL + friction", rhs, lhs,
               AUDIT_TOL, note=f"wL = {GL:.1f}, friction {a['friction'][i]:.2f}, KE {a['ke'][i]:.2f}")

    # each recomputed term against the solver's series
    ck.rel("W_F (J/m) = series work_forces", a["w_f"][-1], s["work_forces"][-1], 1e-9)
    ck.rel("KE (J/m) = series kinetic_energy", a["ke"][-1], s["kinetic_energy"][-1], 1e-9)
    ck.close("stored before the break (J/m) = series cohesive_energy", a["stored"][i_b - 1],
             s["cohesive_energy"][i_b - 1], 1e-9 * GL)
    ck.close("stored after the break (J/m) = 0", s["cohesive_energy"][-1], 0.0, 0.0)
    ck.rel("damage_dissipated (J/m) = w L", s["damage_dissipated"][-1], GL, AUDIT_TOL,
           note="dynamic snap-through: O(h) lag")
    # dissipated - damage_dissipated = friction + the O(h) dissipation of the
    # implicit cohesive springs (damage counts only the energy released when beta drops).
    ck.close("friction + spring O(h) term (J/m) = series dissipated - damage_dissipated", a["friction"][-1],
             s["dissipated"][-1] - s["damage_dissipated"][-1], 1e-2 * GL)
    ck.at_most("|balance_error| / W_F", np.abs(s["balance_error"]).max() / a["w_f"][-1], 1e-9)

    # after the break: plain Coulomb, sum rt = -mu sum rn, and a = (F - mu m g)/m
    after = slice(i_b + 1, None)
    ck.at_most("after the break: max |sum rt + mu sum rn| / (mu m g)",
               np.abs(pr.total("rt")[after] + gen.MU * pr.total("rn")[after]).max() / (gen.MU * run.mass[BLOCK - 1] * gen.G),
               1e-9)
    ck.rel("after the break: sum rn = m g", pr.total("rn")[-1], run.mass[BLOCK - 1] * gen.G, 1e-9)
    m = run.mass[BLOCK - 1]
    j = i_ramp + 1
    acc = (run.V[-1, BLOCK - 1, 0] - run.V[j, BLOCK - 1, 0]) / (run.time[-1] - run.time[j])
    ck.rel("acceleration after the ramp (m/s^2) = (F0 - mu m g)/m", acc, (gen.F0 - gen.MU * m * gen.G) / m, 1e-9)
    st = set(run.status_name(pr.status[after]).ravel())
    ck.true("statuses after the break: plain sliding", st <= {"slifw", "slibw"}, ours=",".join(sorted(st)))
    return ck.finish()


if __name__ == "__main__":
    sys.exit(main())
