"""Command line: python3 -m fracas_tools <command> ... (or tools/fracas-tools)."""

import argparse
import sys
import warnings
from pathlib import Path


def _cmd_report(a):
    from .post import report
    p = report(a.case_dir, h5=a.h5, out_dir=a.out, snapshot=a.snapshot, x_is=a.x_is)
    print(p)
    return 0


def _cmd_deposit(a):
    from .generators import deposit_case
    case = deposit_case(n=a.n, seed=a.seed, rmin=a.rmin, rmax=a.rmax, width=a.width,
                        fric_grains=a.fric, fric_walls=a.fric_walls, time_step=a.dt,
                        duration=a.duration, method=a.method,
                        output_vtk_every=a.vtk_every, output_hdf5_every=a.hdf5_every)
    with warnings.catch_warnings():
        warnings.simplefilter("error" if a.strict else "default")
        d = case.write(a.case_dir)
    print(f"{d}: {case.summary()}")
    return 0


def _cmd_demo(a):
    from . import generators as g
    fn = {"deposit": g.demo_deposit, "masonry": g.demo_masonry, "arch": g.demo_arch}[a.which]
    case = fn(a.case_dir) if a.which != "deposit" else fn(a.case_dir, n=a.n, seed=a.seed)
    print(f"{Path(a.case_dir) / 'DATBOX'}: {case.summary()}")
    return 0


def _cmd_check_h5(a):
    from .post import check_h5
    errors, warns, info = check_h5(a.file)
    for s in info:
        print(f"info: {s}")
    for s in warns:
        print(f"warning: {s}")
    for s in errors:
        print(f"error: {s}")
    print(f"{a.file}: {'OK' if not errors else f'{len(errors)} error(s)'}"
          f"{f', {len(warns)} warning(s)' if warns else ''}")
    return 1 if errors or (a.strict and warns) else 0


def _cmd_info(a):
    from .datbox import read_case
    case = read_case(a.case_dir)
    print(case.summary())
    for w in case.check():
        print(f"warning: {w}")
    return 0


def _cmd_rewrite(a):
    from .datbox import read_case
    case = read_case(a.case_dir)
    d = case.write(a.out_dir)
    print(d)
    return 0


def _cmd_summary(a):
    from .post import Run, summary, summary_table
    rows = []
    for f in a.files:
        with Run(f) as run:
            rows.append(summary(run))
    print(summary_table(rows))
    return 0


def _cmd_synthetic(a):
    from .synthetic import make_case
    print(make_case(a.case_dir, nx=a.nx, ny=a.ny, seed=a.seed))
    return 0


def _cmd_render_vtk(a):
    from .vtu import render
    t = render(a.display_dir, a.frame, a.out)
    print(f"{a.out} (t = {t:.6g} s)")
    return 0


def _cmd_command(a):
    from .lmgc90 import read_run_script, run_control, write_command
    settings_notes = read_run_script(a.from_script) if a.from_script else None
    settings = dict(settings_notes or {})
    given = {"dt": a.dt, "theta": a.theta, "nb_steps": a.steps, "freq_detect": a.freq_detect,
             "norm": a.norm, "tol": a.tol, "relax": a.relax, "gs_it1": a.it1, "gs_it2": a.it2,
             "freq_write": a.freq_write, "freq_display": a.freq_display}
    settings.update({k: v for k, v in given.items() if v is not None})
    missing = [k for k in ("dt", "nb_steps") if k not in settings]
    if missing:
        raise ValueError("the time step and the number of steps are needed: give "
                         + " and ".join({"dt": "--dt", "nb_steps": "--steps"}[k] for k in missing)
                         + (f" (not found in {a.from_script})" if a.from_script else ""))
    scramble = settings.pop("quickscramble", False)
    rc = run_control(**settings)
    extra = {"output_hdf5_every": a.freq_hdf5, "nlgs_unconverged": a.unconverged}
    if scramble:
        extra["nlgs_order"] = "shuffled"       # LMGC90's nlgs_SetWithQuickScramble
    rc.set(**{k: v for k, v in extra.items() if v is not None})
    # Never guess silently: say what the script does that was not read, and the
    # physics it sets up that Fracas does not have (written in the file too).
    notes = []
    if a.from_script:
        notes = [f"not understood: {n}" for n in settings_notes.not_understood] + \
                [f"not in Fracas (the mechanics alone is run): {n}" for n in settings_notes.physics]
    out = write_command(a.case_dir, rc, overwrite=a.overwrite, path=a.output, notes=notes)
    for n in notes:
        print(f"fracas-tools command: {n}", file=sys.stderr)
    print(out)
    for line in rc.lines()[1:]:
        print("  " + line)
    return 0


def build_parser():
    p = argparse.ArgumentParser(prog="fracas-tools",
                                description="Pre- and post-processing for Fracas cases.")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")

    s = sub.add_parser("report", help="write CASE_DIR/report/report.md with plots from OUTBOX/fracas.h5")
    s.add_argument("case_dir")
    s.add_argument("--h5", help="results file (default CASE_DIR/OUTBOX/fracas.h5)")
    s.add_argument("--out", help="output folder (default CASE_DIR/report)")
    s.add_argument("--snapshot", type=int, default=-1,
                   help="snapshot index for the force network and fabric (default -1: last)")
    s.add_argument("--x-is", choices=("auto", "displacement", "position"), default="auto",
                   help="meaning of snapshot X (default auto)")
    s.set_defaults(func=_cmd_report)

    s = sub.add_parser("deposit", help="write a ready-to-run deck of disks falling into a box")
    s.add_argument("case_dir")
    s.add_argument("--n", type=int, default=2000, help="number of disks (default 2000)")
    s.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    s.add_argument("--rmin", type=float, help="smallest radius [m] (default 0.004, or 0.008 for n < 1000)")
    s.add_argument("--rmax", type=float, help="largest radius [m] (default 0.006, or 0.012 for n < 1000)")
    s.add_argument("--width", type=float, help="box width [m] (default: from n)")
    s.add_argument("--fric", type=float, default=0.3, help="disk/disk friction (default 0.3)")
    s.add_argument("--fric-walls", type=float, default=0.5, help="disk/wall friction (default 0.5)")
    s.add_argument("--dt", type=float, default=1e-3, help="time step [s] (default 1e-3)")
    s.add_argument("--duration", type=float, default=1.0, help="simulated time [s] (default 1)")
    s.add_argument("--method", choices=("lattice", "ballistic"), default="lattice",
                   help="initial placement (default lattice: a loose cloud that falls)")
    s.add_argument("--vtk-every", type=int, help="VTK output every n steps (default: 100 outputs)")
    s.add_argument("--hdf5-every", type=int, help="HDF5 snapshot every n steps (default: 100 snapshots)")
    s.add_argument("--strict", action="store_true", help="turn deck warnings into errors")
    s.set_defaults(func=_cmd_deposit)

    s = sub.add_parser("demo", help="write a demo deck (deposit, masonry or arch)")
    s.add_argument("which", choices=("deposit", "masonry", "arch"))
    s.add_argument("case_dir")
    s.add_argument("--n", type=int, default=400, help="disks of the deposit demo (default 400)")
    s.add_argument("--seed", type=int, default=1)
    s.set_defaults(func=_cmd_demo)

    s = sub.add_parser("check-h5", help="check a fracas.h5 against the documented layout")
    s.add_argument("file")
    s.add_argument("--strict", action="store_true", help="exit 1 on warnings too")
    s.set_defaults(func=_cmd_check_h5)

    s = sub.add_parser("info", help="read a case's DATBOX and print a summary")
    s.add_argument("case_dir")
    s.set_defaults(func=_cmd_info)

    s = sub.add_parser("rewrite", help="read CASE_DIR/DATBOX and write it again to OUT_DIR/DATBOX")
    s.add_argument("case_dir")
    s.add_argument("out_dir")
    s.set_defaults(func=_cmd_rewrite)

    s = sub.add_parser("summary", help="print a Markdown table with one row per results file")
    s.add_argument("files", nargs="+")
    s.set_defaults(func=_cmd_summary)

    s = sub.add_parser("synthetic", help="write a synthetic case (DATBOX + OUTBOX/fracas.h5) for trying the tools")
    s.add_argument("case_dir")
    s.add_argument("--nx", type=int, default=10)
    s.add_argument("--ny", type=int, default=6)
    s.add_argument("--seed", type=int, default=0)
    s.set_defaults(func=_cmd_synthetic)

    s = sub.add_parser("command", help="write DATBOX/COMMAND.DAT from LMGC90 settings (dt, theta, nb_steps, "
                                       "norm, tol, gs_it1, gs_it2, ...)",
                       description="Write the run control of an LMGC90 deck (which has no COMMAND.DAT) from the "
                                   "settings of its pylmgc90 script: given here, or read from the script with "
                                   "--from-script (options given here win). Settings left out keep Fracas's "
                                   "defaults (doc/input_reference.md).")
    s.add_argument("case_dir", help="the case directory (holding DATBOX/)")
    s.add_argument("--from-script", metavar="RUN_PY",
                   help="read dt, theta, nb_steps, freq_detect, norm, tol, relax, gs_it1, gs_it2, freq_write, "
                        "freq_display from the top-level assignments of this pylmgc90 script")
    s.add_argument("--dt", type=float, help="time step (LMGC90 dt)")
    s.add_argument("--theta", type=float, help="theta (default 0.5)")
    s.add_argument("--steps", "--nb-steps", type=int, dest="steps", help="number of steps (LMGC90 nb_steps)")
    s.add_argument("--freq-detect", type=int, help="rough detection every n steps (default 1)")
    s.add_argument("--norm", choices=("Quad", "Maxm", "QM/16"), help="NLGS check type (default Quad)")
    s.add_argument("--tol", type=float, help="NLGS tolerance (default 1e-4)")
    s.add_argument("--relax", type=float, help="NLGS relaxation (default 1.0)")
    s.add_argument("--it1", "--gs-it1", type=int, dest="it1",
                   help="Gauss-Seidel sweeps between two convergence checks (default 50)")
    s.add_argument("--it2", "--gs-it2", type=int, dest="it2", help="convergence checks at most (default 400)")
    s.add_argument("--freq-write", type=int, help="DOF.OUT.n / Vloc_Rloc.OUT.n every n steps (default: last step)")
    s.add_argument("--freq-display", type=int, help="DISPLAY (VTK) files every n steps (default: none)")
    s.add_argument("--freq-hdf5", type=int, help="HDF5 snapshots every n steps (default: about 100 a run)")
    s.add_argument("--unconverged", choices=("warn", "fail", "stop"),
                   help="what a step at the NLGS sweep limit does (default warn)")
    s.add_argument("--output", help="file to write (default CASE_DIR/DATBOX/COMMAND.DAT)")
    s.add_argument("--overwrite", action="store_true", help="replace an existing COMMAND.DAT")
    s.set_defaults(func=_cmd_command)

    s = sub.add_parser("render-vtk", help="draw one frame of DISPLAY/*.vtu (outlines, contact forces) as PNG")
    s.add_argument("display_dir", help="a DISPLAY folder holding fracas.pvd")
    s.add_argument("out", help="PNG file to write")
    s.add_argument("--frame", type=int, default=-1, help="index of the output time (default: the last)")
    s.set_defaults(func=_cmd_render_vtk)
    return p


def main(argv=None):
    args = build_parser().parse_args(argv)
    return run_main(lambda: args.func(args), f"fracas-tools {args.command}")


def run_main(main, prog):
    """Run a command-line entry point; bad input (a deck, a file, a value) is reported as
    'PROG: error: message' on stderr with status 2, not as a traceback."""
    from .fortran_io import DatboxError
    try:
        return main()
    except (DatboxError, FileNotFoundError, ValueError, OSError, KeyError) as e:
        print(f"{prog}: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
