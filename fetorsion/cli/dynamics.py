"""``fetorsion campbell``, ``response``, ``damper`` and ``transient``: the excited crank (or chain)
over its speed range. Here ``campbell`` and ``response`` and the four commands' parsers; ``damper``
in :mod:`.damper`, ``transient`` in :mod:`.transient`, what they share in :mod:`.excited`."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from .options import integer
from ..app.engine_answers import engine_campbell, engine_setup, stored_engine_model, worst_torque
from ..description.chain_model import Network
from ..errors import FetorsionError
from ..io import write_text_atomic
from ..lumped_model.lumped import lumped
from ..response.forced import COMPARE_UNITS
from ..description.defaults import DEFAULT_MODES, DEFAULT_PARTITION, DEFAULT_SPEED_STEPS
from . import damper as cli_damper
from . import transient as cli_transient
from .common import check_mesh_size, partition_of, report, stiffness_for
from .excited import add_excitation_options, engine_gap_line, engine_model, load_for, only_lumped_driveline


def cmd_campbell(args) -> int:
    from ..excitation.campbell import lumped_modes, run_campbell

    crank = load_for(args)
    only_lumped_driveline(crank, args, "campbell")
    if not args.source.startswith("lumped") and args.source != "condensed" and getattr(crank, "dampers", ()):
        print(f"fetorsion: warning: {args.file}: the FE modes are the crank's without its [[dampers]] "
              "(lumped sources and 'response --source condensed' include them)", file=sys.stderr)
    coupled = args.source == "condensed" or (args.source == "fe" and args.support == "bearings")
    gap = None
    if coupled:
        # the coupled crank: every mode an order meets in range, full pin forces, severity as stress
        cc, fillets = engine_model(crank, args)
        res = engine_campbell(cc, fillets, args.support, args.orders, args.speed_range, args.damping)
    elif args.source == "fe":
        from ..fe.crankfe import run_modal

        check_mesh_size(crank, args.mesh_size, "modal")

        modes = run_modal(crank, args.mesh_size, modes=DEFAULT_MODES).torsional_modes(args.modes)
    else:  # with [[dampers]], run_campbell builds the damped lumped modes itself
        modes = None if crank.dampers else lumped_modes(crank, partition_of(args.source), stiffness_for(args))
    if not coupled:
        res = run_campbell(crank, modes, orders=args.orders, speed_range=args.speed_range, n_modes=args.modes,
                           damping_ratio=args.damping,
                           partition=partition_of(args.source) if args.source.startswith("lumped") else DEFAULT_PARTITION,
                           web_method=stiffness_for(args))
        engine = stored_engine_model(crank, args.support, args.mesh_size) if args.source.startswith("lumped") else None
        if engine is not None and res.frequencies_hz.size:
            f1 = engine[0].modes(args.support).first_torsional()
            gap = engine_gap_line("f1", float(res.frequencies_hz[0]), f1, "Hz")
    head = (f"{res.name}: crossings inside {res.speed_range_rpm[0]:.0f}-{res.speed_range_rpm[1]:.0f} rpm, "
            f"most severe first ({res.source})")
    report(res, head + "\n" + res.table() + ("" if gap is None else "\n" + gap), args)
    if args.html:
        from ..report.html import campbell_figure, page

        text = f"# {res.name}: Campbell diagram\n\n![](campbell.png)\n\n```\n{head}\n{res.table()}\n```\n"
        write_text_atomic(args.html, page(res.name, text, {"campbell.png": campbell_figure(res, "campbell")},
                                          Path(args.html).parent))
    return 0


def _check_response(args, crank) -> None:
    """The options of ``response`` against each other and the description, before any work."""
    if args.misfire is not None and args.misfire > crank.engine.cylinders:
        raise FetorsionError(f"--misfire {args.misfire}: the engine has cylinders 1..{crank.engine.cylinders}")
    if args.misfire is not None and crank.excitation.pressure_curve is not None:
        raise FetorsionError(f"--misfire: {args.file} gives a measured pressure_csv; the motored cycle of a misfiring "
                             "cylinder needs the synthetic cycle (compression_ratio)")
    if args.bearing_forces and args.source != "condensed":
        raise FetorsionError("--bearing-forces: the bearings carry forces in the condensed crank only; "
                             "leave --source out (or give --source condensed)")
    if args.bearing_forces:
        for option in ("compare", "misfire"):
            if getattr(args, option) is not None:
                raise FetorsionError(f"--{option} is not taken with --bearing-forces")


def _misfired(setup, crank, misfire: int | None):
    """``setup`` with the 1-based cylinder ``misfire`` not firing (unchanged for None)."""
    from ..response.forced import misfire_harmonics

    return setup if misfire is None else setup.with_misfire(misfire - 1, misfire_harmonics(crank, setup))


def cmd_response(args) -> int:
    crank = load_for(args)
    if args.source == "fe":
        raise FetorsionError("--source fe: the forced response uses a lumped model or the condensed crank; "
                             "choose --source lumpedN or condensed")
    rpm = np.linspace(*(args.speed_range or crank.excitation.checked_range), args.steps)
    _check_response(args, crank)
    if args.bearing_forces:
        from ..response.coupled import run_coupled_response

        cc, _ = engine_model(crank, args)
        res = run_coupled_response(cc, args.support, rpm=rpm, orders=args.orders, damping_ratio=args.damping)
        return report(res, res.table(), args)
    if args.source == "condensed" and isinstance(crank, Network):
        res, gap = _driveline_response(args, crank, rpm), None
    elif args.source == "condensed":
        res, gap = _engine_response(args, crank, rpm), None
    else:
        res, gap = _lumped_response(args, crank, rpm)
    if args.compare is not None:
        from ..response.forced import compare_curve

        rpm_c, value, name, unit = args.compare_curve
        compare_curve(res, rpm_c, value, name, unit,
                      None if args.compare_section is None else args.compare_section - 1)
    return report(res, res.table() + ("" if gap is None else "\n" + gap), args)


def _driveline_response(args, crank, rpm):
    """The driveline with its crank as the condensed FE crank in its bearings."""
    from ..response.driveline import condensed_part, driveline_setup
    from ..response.forced import solve_response

    part = condensed_part(crank)
    if part is None:
        raise FetorsionError(f"--source condensed: {args.file} has no [[chain.cranks]] with dof = \"condensed\"")
    for option in ("misfire", "compare_section"):
        if getattr(args, option) is not None:
            raise FetorsionError(f"--{option.replace('_', '-')} is not taken for a network on a condensed crank yet")
    cc, fillets = engine_model(part.crank, args)
    return solve_response(driveline_setup(crank, cc, rpm, args.orders, args.damping, [f.label for f in fillets]),
                          crank.dampers)


def _engine_response(args, crank, rpm):
    """The condensed crank's response, its sections the fillets."""
    from ..response.forced import solve_response

    cc, fillets = engine_model(crank, args)
    setup = engine_setup(cc, fillets, args.support, rpm, args.orders, args.damping)
    if args.compare_section is not None and args.compare_section > len(setup.section_labels):
        raise FetorsionError(f"--compare-section {args.compare_section}: the model has "
                             f"{len(setup.section_labels)} sections (the fillets)")
    return solve_response(_misfired(setup, crank, args.misfire), crank.dampers)


def _lumped_response(args, crank, rpm):
    """The lumped model's response, and the line saying how far its largest section torque is
    from the stored engine model's (None where the store has no engine model)."""
    from ..response.forced import run_response, solve_response

    if args.compare_section is not None:  # checked on the model's springs before the response is computed
        springs = len(lumped(crank, partition_of(args.source), args.stiffness).stiffnesses_nm_per_rad)
        if args.compare_section > springs:
            raise FetorsionError(f"--compare-section {args.compare_section}: the model has {springs} shaft sections")
    res = run_response(crank, partition_of(args.source), rpm=rpm, orders=args.orders, damping_ratio=args.damping,
                       web_method=stiffness_for(args), misfire=None if args.misfire is None else args.misfire - 1)
    engine = stored_engine_model(crank, args.support, args.mesh_size)
    if engine is None:
        return res, None
    setup = _misfired(engine_setup(*engine, args.support, rpm, args.orders, args.damping), crank, args.misfire)
    return res, engine_gap_line("the largest section torque", worst_torque(res),
                                worst_torque(solve_response(setup, crank.dampers)), "N m")


def _add_campbell_parser(sub) -> None:
    """The ``campbell`` command."""
    cp = sub.add_parser("campbell", help="Campbell diagram: crossings of modes and orders, with severity")
    add_excitation_options(cp)
    cp.add_argument("--modes", type=integer(1, 50), default=3,
                    help="number of lowest torsional modes (default %(default)s); the condensed crank in its bearings "
                         "shows every mode an order meets in range, with the fillet stress it drives")
    cp.add_argument("--html", metavar="PATH", help="write the interactive Campbell diagram as a web page (.html)")
    cp.set_defaults(func=cmd_campbell)


def _add_response_parser(sub) -> None:
    """The ``response`` command."""
    rp = sub.add_parser("response", help="forced response versus speed: the condensed crank in its bearings (a crank), "
                        "or the lumped model")
    add_excitation_options(rp)
    rp.add_argument("--steps", type=integer(2, 100_000), default=DEFAULT_SPEED_STEPS, help="speeds in the range (default %(default)s)")
    rp.add_argument("--bearing-forces", action="store_true",
                    help="the condensed crank's main-bearing forces and fillet-cut loads, torsion and bending coupled "
                         "(the run's 'crank in its bearings' response), instead of the section torques")
    rp.add_argument("--misfire", type=integer(1), metavar="CYL",
                    help="cylinder CYL (1-based) does not fire: compression and expansion only")
    rp.add_argument("--compare", metavar="CSV", help="a published or measured curve, rows 'rpm, value' ('#' lines: "
                    "comments, '# name = ...' and '# unit = ...' read), drawn over the response; the table gives "
                    "the difference at its peak")
    rp.add_argument("--compare-name", metavar="TEXT", help="what the --compare curve is (default the CSV's '# name')")
    rp.add_argument("--compare-unit", choices=sorted(COMPARE_UNITS),
                    help="its unit: a torque is compared with a section's torque, an angle with the pulley angle "
                         "(default the CSV's '# unit')")
    rp.add_argument("--compare-section", type=integer(1), metavar="N",
                    help="1-based shaft section (spring) whose torque is compared (default the most loaded)")
    rp.set_defaults(func=cmd_response)


def add_parsers(sub) -> None:
    """The ``campbell``, ``damper``, ``response`` and ``transient`` commands, in that order."""
    _add_campbell_parser(sub)
    cli_damper.add_parser(sub)
    _add_response_parser(sub)
    cli_transient.add_parser(sub)
