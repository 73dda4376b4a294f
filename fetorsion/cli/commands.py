"""Command line: ``fetorsion <command> ...``. User mistakes print one clear message, exit 2.

Each family of commands is a module of its own (:mod:`.lumped`, :mod:`.fe`, :mod:`.dynamics`,
:mod:`.study`, :mod:`.mechanics`, :mod:`.run`, :mod:`.measured`) that adds its parsers; what they share is in
:mod:`.common` and :mod:`.options`. Here: the parser, the checks made before any work, ``main``.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from .options import option_of, read_compare_csv
from ..errors import FetorsionError, ParameterError
from ..io import check_output_file
from . import design as cli_design
from . import dynamics as cli_dynamics
from . import fe as cli_fe
from . import lumped as cli_lumped
from . import measured as cli_measured
from . import mechanics as cli_mechanics
from . import report as cli_report
from . import run as cli_run
from . import study as cli_study
from .common import PLOT_FORMATS


def build_parser() -> argparse.ArgumentParser:
    from .. import __version__

    p = argparse.ArgumentParser(prog="fetorsion", description="Torsional vibration analysis of engine crankshafts.")
    p.add_argument("--version", action="version", version=f"fetorsion {__version__}")
    sub = p.add_subparsers(dest="command", required=True)
    cli_lumped.add_parsers(sub)
    cli_dynamics.add_parsers(sub)
    cli_mechanics.add_parsers(sub)
    cli_study.add_parser(sub)
    cli_run.add_parser(sub)
    cli_report.add_parser(sub)
    cli_fe.add_parsers(sub)
    cli_measured.add_parsers(sub)
    cli_design.add_parser(sub)
    return p


# Output options: (attribute, option name, accepted suffixes); "-" means standard output.
OUTPUT_OPTIONS = (("json", "--json", (".json",)), ("plot", "--plot", PLOT_FORMATS), ("html", "--html", (".html",)),
                  ("output", "-o", None), ("png", "--png", (".png",)), ("npz", "--npz", (".npz",)),
                  ("uff", "--uff", (".uff", ".unv")), ("step_file", "--step", (".step", ".stp")))


def check_options(args) -> None:
    """Every check on the command line that needs no file read: before any work."""
    from ..solid.mesh import MESH_FORMATS

    inputs = [getattr(args, "file", None), getattr(args, "mesh", None)]
    for attr, option, suffixes in OUTPUT_OPTIONS:
        targets = getattr(args, attr, None)
        for target in targets if isinstance(targets, list) else [targets]:
            if target is None or (attr == "json" and target == "-"):
                continue
            check_output_file(target, option, suffixes or MESH_FORMATS, inputs)
    speeds = getattr(args, "speed_range", None)
    if speeds is not None and not speeds[0] < speeds[1]:
        raise FetorsionError(f"--speed-range {speeds[0]:g} {speeds[1]:g}: LOW must be below HIGH (rpm)")
    if getattr(args, "compare", None) is not None:
        args.compare_curve = read_compare_csv(args.compare, args.compare_name, args.compare_unit)
    elif getattr(args, "compare_name", None) or getattr(args, "compare_unit", None) or getattr(
            args, "compare_section", None):
        raise FetorsionError("--compare-name, --compare-unit and --compare-section need --compare CSV")
    mesh = getattr(args, "mesh", None)
    if mesh is not None and not Path(mesh).is_file():
        raise FetorsionError(f"--mesh {mesh}: no such file")
    if args.command in ("run", "study") and not getattr(args, "scheduler", None):
        # Both run their studies on the cluster this names, if it is set.
        from ..studies.runner import SCHEDULER_ENV, check_scheduler, scheduler_address

        address, _ = scheduler_address(None)
        if address:
            check_scheduler(address, SCHEDULER_ENV)


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    try:
        check_options(args)
        return args.func(args)
    except ParameterError as exc:  # an argument of the API: named by the option that set it
        print(f"fetorsion: error: {exc.named(option_of(exc.parameter))}", file=sys.stderr)
        return 2
    except FetorsionError as exc:
        print(f"fetorsion: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("fetorsion: interrupted; nothing was written", file=sys.stderr)
        return 130
    except OSError as exc:  # the file system refused something after the checks (disk full, ...)
        where = f" {exc.filename}" if exc.filename else ""
        print(f"fetorsion: error:{where}: {exc.strerror or exc}", file=sys.stderr)
        return 1
