"""``fetorsion run``: the main job, every analysis of a crank (or of both reference cranks) into a
report folder."""

from __future__ import annotations

import sys
from pathlib import Path

from .options import MM, integer, millimetres, real
from ..description.chain_model import Chain, Network
from ..errors import FetorsionError
from ..io import check_report_folder
from ..description.defaults import DEFAULT_INERTIA_RATIO, DEFAULT_MESH_SIZE, DEFAULT_MODES, DEFAULT_RUNUP_RATE, LUMPED17
from .common import SUPPORT_CHOICES, add_band_option, check_mesh_size, load_description
from ..design.methods import FATIGUE_METHODS
from .measured import add_measured_options


# The Peugeot GLX twice: alone (its measured 905.9 Hz) and in its engine (its fatigue assessment)
REFERENCE_CRANKS = ("renault21", "peugeot_glx", "peugeot_glx_engine")
RUN_SOURCES = ("condensed", LUMPED17)


def _geometry_folder():
    """``geometry/`` in the working folder, else beside the package (a source checkout)."""
    from pathlib import Path

    import os

    for folder in (Path("geometry"), Path(__file__).resolve().parents[1] / "geometry"):
        if (folder / f"{REFERENCE_CRANKS[0]}.toml").exists():
            rel = os.path.relpath(folder)
            return Path(rel) if not rel.startswith("..") else folder
    raise FetorsionError("no FILE given and no geometry/ folder with the reference cranks found; give FILE")


def run_jobs(args) -> list[tuple[Path, Path]]:
    """(description, report folder) of each crank ``run`` will do."""
    if args.all:
        if args.file:
            raise FetorsionError("--all runs both reference cranks; it takes no FILE")
        folder = _geometry_folder()
        return [(folder / f"{name}.toml", Path(args.out or "results") / name) for name in REFERENCE_CRANKS]
    file = Path(args.file) if args.file else _geometry_folder() / f"{REFERENCE_CRANKS[0]}.toml"
    return [(file, Path(args.out) if args.out else Path("out") / file.stem)]


def cmd_run(args) -> int:
    from ..app.run import FAST_STEPS, RunOptions, run

    jobs = run_jobs(args)
    if args.measured and args.all:
        raise FetorsionError("--measured belongs to one crank; give FILE instead of --all")
    if not args.measured and (args.band or args.station or args.teeth or args.calibration or args.twist
                              or args.channel_station or args.time_unit or args.frf_unit):
        raise FetorsionError("--band, --station, --teeth, --calibration, --twist, --channel-station, --time-unit and "
                             "--frf-unit go with --measured FILE ...")
    for file, out in jobs:  # every destination and description is checked before any work
        check_report_folder(out, "--out", force=args.force, inputs=[file], force_option="--force")
        crank = load_description(str(file))
        if not args.no_fe and not isinstance(crank, (Chain, Network)):  # a chain has no geometry: no FE step
            check_mesh_size(crank, args.mesh_size, "modal")
    options = {"mesh_size": args.mesh_size, "modes": args.modes, "support": args.support,
               "inertia_ratio": args.inertia_ratio, "source": args.source, "runup_rate": args.run_up_rate,
               "fatigue_method": args.fatigue_method, "workers": args.workers, "html": not args.no_html,
               "no_fe": args.no_fe, "fe_path": not args.no_fe_path}
    if args.measured:  # read and checked now, before any work
        from .measured import check_measured, check_station, measured_of

        engine = not args.no_fe and args.source == "condensed" and not isinstance(crank, (Chain, Network))
        check_station(crank, args.station, "condensed" if engine else LUMPED17)
        measured = measured_of(args, args.measured, crank=crank)
        for line in measured.notes:
            print(f"fetorsion: warning: {line}", file=sys.stderr)
        measured = check_measured(crank, measured, args.station, "condensed" if engine else LUMPED17)
        options.update(measured=measured, station=args.station)
    for file, out in jobs:
        outcome = run(file, out, options=RunOptions.of(options), force=args.force,
                      **({"steps": FAST_STEPS} if args.no_fe else {}))
        print(f"report: {Path(outcome.folder) / 'report.md'}")
    return 0


def add_parser(sub) -> None:
    """The ``run`` commands."""
    up = sub.add_parser("run", help="the main job: every analysis of a crank into one report folder")
    up.add_argument("file", nargs="?", help="crank description, chain or network file (default "
                                            "geometry/renault21.toml; a chain or network gets the report without the "
                                            "FE sections, with a run-up in the time domain)")
    up.add_argument("--out", metavar="DIR", help="report folder (default out/<name>; with --all, the parent folder)")
    up.add_argument("--all", action="store_true", help="the reference cranks (Renault 21; Peugeot GLX alone and in its engine) into results/<name>/")
    up.add_argument("--mesh-size", type=millimetres(), default=DEFAULT_MESH_SIZE, metavar="MM",
                    help=f"FE mesh size in mm (default {DEFAULT_MESH_SIZE / MM:g})")
    up.add_argument("--no-fe", action="store_true", help="skip the mesh and FE modal steps (a quick report)")
    up.add_argument("--no-fe-path", action="store_true",
                    help="the crank's verdict by the deciding method alone: leave out the fe fatigue path (its stress "
                         "recovery and assessments) where it does not decide, as the design loop's confirmations do")
    up.add_argument("--support", choices=SUPPORT_CHOICES, default="bearings",
                    help="the modes the Campbell diagram uses: the condensed crank in its bearings (default) or the "
                         "free-free FE; the report shows both")
    up.add_argument("--source", choices=RUN_SOURCES, default=RUN_SOURCES[0],
                    help="the model the forced response, fillet stress, dampers and verdict run on: the condensed "
                         "crank in its bearings (default: the engine model) or the lumped 17-DOF chain (fast; "
                         "always with --no-fe); the report states the other's gap")
    up.add_argument("--modes", type=integer(1, 200), default=DEFAULT_MODES, metavar="N",
                    help="free-free FE modes computed for the report (default %(default)s)")
    up.add_argument("--workers", type=integer(1), metavar="N",
                    help="workers of the background studies' local Dask cluster (default: the machine's cores "
                         "less one, at least 1)")
    up.add_argument("--inertia-ratio", type=real(0.0, 2.0), default=DEFAULT_INERTIA_RATIO, metavar="MU",
                    help="the verdict's damper designs: ring inertia ratio, 0 < MU < 2 (default %(default)s)")
    up.add_argument("--fatigue-method", choices=tuple(FATIGUE_METHODS),
                    help="the method that decides a crank's fatigue verdict: IACS UR M53 as written (default, or "
                         "the description's [limits] fatigue_method) or fetorsion's own FE path; the report shows "
                         "both")
    up.add_argument("--measured", nargs="+", metavar="FILE",
                    help="measured files to set the model against in the report (as 'fetorsion compare': UFF 58 "
                         "FRFs and order functions, CSV order cuts, tooth-edge CSV with --teeth)")
    add_band_option(up)
    up.add_argument("--station", help="where the measured order cuts were taken: pulley (default), flywheel or a "
                    "station of the model by name or number (as 'fetorsion compare')")
    add_measured_options(up)
    up.add_argument("--run-up-rate", type=real(0.0, 1.0e5, unit="rpm/s"), default=None,
                    metavar="RPM_PER_S", help="a chain's or network's time-domain run-up over its checked range: "
                    f"|dn/dt| in rpm/s (default: a propulsion line's stated passage_rate_rpm_per_s, else "
                    f"{DEFAULT_RUNUP_RATE:g}; the cost grows as the rate falls)")
    up.add_argument("--no-html", action="store_true", help="no report.html (the interactive web page) beside report.md")
    up.add_argument("--force", action="store_true",
                    help="replace --out even if it is not an earlier fetorsion report (its contents are lost)")
    up.set_defaults(func=cmd_run)
