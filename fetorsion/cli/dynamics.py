"""``fetorsion campbell``, ``response`` and ``damper``: the excited crank (or chain) over its speed range."""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

from .options import MM, integer, millimetres, real
from ..description.model import Chain
from ..errors import FetorsionError
from ..io import write_text_atomic
from ..lumped_model.lumped import PARTITIONS, lumped
from ..response.forced import COMPARE_UNITS
from ..description.defaults import (NONLINEAR_METHODS, DEFAULT_DAMPING_RATIO, DEFAULT_INERTIA_RATIO, DEFAULT_MESH_SIZE, DEFAULT_MODES,
                                    DEFAULT_PARTITION, DEFAULT_SPEED_STEPS, DEFAULT_TEETH,
                                    DEFAULT_TRANSIENT_CYCLES, DEFAULT_WEB_METHOD)
from ..webs.methods import WEB_METHODS
from ..description.model import DAMPER_STATIONS, DAMPER_TYPES
from ..design.dampers import OBJECTIVES
from .common import (SUPPORT_CHOICES, add_json_option, check_mesh_size, load_excited, partition_of, refuse_network,
                     report,
                     stiffness_for)
from .fe import condensed


def cmd_campbell(args) -> int:
    from ..excitation.campbell import lumped_modes, run_campbell

    crank = load_excited(args.file, args.source)
    if not args.source.startswith("lumped") and getattr(crank, "dampers", ()):
        print(f"fetorsion: warning: {args.file}: the FE modes are the crank's without its [[dampers]] "
              "(lumped sources and 'response --source condensed' include them)", file=sys.stderr)
    coupled = args.source == "condensed" or (args.source == "fe" and args.support == "bearings")
    if coupled:
        # the coupled crank: every mode an order meets in range, full pin forces, severity as stress
        from ..response.coupled import run_coupled_campbell

        check_mesh_size(crank, args.mesh_size, "modal")
        res = run_coupled_campbell(condensed(crank, args.mesh_size), args.support, orders=args.orders,
                                   speed_range=args.speed_range, damping_ratio=args.damping)
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
    head = (f"{res.name}: crossings inside {res.speed_range_rpm[0]:.0f}-{res.speed_range_rpm[1]:.0f} rpm, "
            f"most severe first ({res.source})")
    report(res, head + "\n" + res.table(), args)
    if args.html:
        from ..report.html import campbell_figure, page

        text = f"# {res.name}: Campbell diagram\n\n![](campbell.png)\n\n```\n{head}\n{res.table()}\n```\n"
        write_text_atomic(args.html, page(res.name, text, {"campbell.png": campbell_figure(res, "campbell")},
                                          Path(args.html).parent))
    return 0


def cmd_response(args) -> int:
    from ..response.forced import run_response

    if args.source == "fe":
        raise FetorsionError("--source fe: the forced response uses a lumped model or the condensed crank; "
                             "choose --source lumpedN or condensed")
    crank = load_excited(args.file, args.source)
    rpm = np.linspace(*(args.speed_range or crank.excitation.checked_range), args.steps)
    if args.source == "condensed":
        from ..response.coupled import run_coupled_response

        if args.compare is not None:
            raise FetorsionError("--compare works with a lumped source (its section torques); "
                                 "leave --source condensed out")
        if args.misfire is not None:
            raise FetorsionError("--misfire works with a lumped source; leave --source condensed out")
        check_mesh_size(crank, args.mesh_size, "modal")
        res = run_coupled_response(condensed(crank, args.mesh_size), args.support, rpm=rpm, orders=args.orders,
                                   damping_ratio=args.damping)
        return report(res, res.table(), args)
    if args.compare_section is not None:  # checked on the model's springs before the response is computed
        springs = len(lumped(crank, partition_of(args.source), args.stiffness).stiffnesses_nm_per_rad)
        if args.compare_section > springs:
            raise FetorsionError(f"--compare-section {args.compare_section}: the model has {springs} shaft sections")
    if args.misfire is not None and args.misfire > crank.engine.cylinders:
        raise FetorsionError(f"--misfire {args.misfire}: the engine has cylinders 1..{crank.engine.cylinders}")
    if args.misfire is not None and crank.excitation.pressure_curve is not None:
        raise FetorsionError(f"--misfire: {args.file} gives a measured pressure_csv; the motored cycle of a misfiring "
                             "cylinder needs the synthetic cycle (compression_ratio)")
    res = run_response(crank, partition_of(args.source), rpm=rpm, orders=args.orders, damping_ratio=args.damping,
                       web_method=stiffness_for(args), misfire=None if args.misfire is None else args.misfire - 1)
    if args.compare is not None:
        from ..response.forced import compare_curve

        rpm_c, value, name, unit = args.compare_curve
        compare_curve(res, rpm_c, value, name, unit,
                      None if args.compare_section is None else args.compare_section - 1)
    return report(res, res.table(), args)


def cmd_damper(args) -> int:
    from ..design.dampers import run_damper

    if args.source in ("fe", "condensed"):
        raise FetorsionError(f"--source {args.source}: the damper is tuned on a lumped model; choose --source lumpedN")
    crank = load_excited(args.file, args.source)
    refuse_network(crank, args.file, "damper")
    if args.objective == "stress" and isinstance(crank, Chain):
        raise FetorsionError(f"--objective stress: {args.file} is a chain file, it has no shaft sections; "
                             "use --objective twist")
    if args.objective == "stress" and not (crank.fillets.journal > 0 and crank.fillets.pin > 0):
        raise FetorsionError(f"--objective stress: {args.file} has no fillet radii (a sharp corner has no finite "
                             "SCF); give [fillets] or use --objective twist")
    rpm = np.linspace(*(args.speed_range or crank.excitation.checked_range), args.steps)
    res = run_damper(crank, args.type, args.inertia_ratio, args.optimise, args.objective, args.at, args.hub_inertia,
                     rpm=rpm, partition=partition_of(args.source), orders=args.orders, damping_ratio=args.damping,
                     web_method=stiffness_for(args))
    return report(res, res.table(), args)


def cmd_transient(args) -> int:
    from ..response.transient import run_transient

    if args.source in ("fe", "condensed"):
        raise FetorsionError(f"--source {args.source}: the time domain uses a lumped model; choose --source lumpedN")
    if args.run_up is not None and args.rate is None:
        raise FetorsionError("--run-up A B needs --rate RPM_PER_S (how fast the speed changes)")
    if args.rate is not None and args.run_up is None:
        raise FetorsionError("--rate goes with --run-up A B (a steady --rpm has no rate)")
    if args.run_up is not None and args.run_up[0] == args.run_up[1]:
        raise FetorsionError(f"--run-up {args.run_up[0]:g} {args.run_up[1]:g}: A and B must differ "
                             "(A < B a run-up, A > B a run-down; for one speed use --rpm)")
    crank = load_excited(args.file, args.source)
    if args.station is not None:
        dof = lumped(crank, partition_of(args.source), args.stiffness).dof
        if args.station > dof:
            raise FetorsionError(f"--station {args.station}: the model has coordinates 1..{dof}")
    res = run_transient(crank, rpm=args.rpm, run=None if args.run_up is None else tuple(args.run_up),
                        rate_rpm_per_s=args.rate, cycles=args.cycles, damping_ratio=args.damping,
                        partition=partition_of(args.source), web_method=stiffness_for(args), teeth=args.teeth,
                        track_station=0 if args.station is None else args.station - 1,
                        variable_inertia=args.variable_inertia, method=args.integrator)
    return report(res, res.table(), args)


def _orders(text: str) -> list[float]:
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"--orders {text!r}: give comma-separated numbers, e.g. 0.5,1,1.5") from None
    if any(not (math.isfinite(v) and 0 < v <= 100) for v in values):
        raise argparse.ArgumentTypeError(f"--orders {text!r}: orders must be > 0 and <= 100")
    return values


def _add_excitation_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("file", help="crank description or chain file with an [excitation] table (.toml)")
    p.add_argument("--source", default="lumped17", choices=[f"lumped{d}" for d in PARTITIONS] + ["fe", "condensed"],
                   help="which model gives the modes (default %(default)s; fe: campbell only; condensed: the 3D FE "
                        "crank condensed to its journal and pin centres, torsion and bending coupled)")
    p.add_argument("--support", choices=SUPPORT_CHOICES, default="bearings",
                   help="the crank in its main bearings (default, as it runs) or free-free (as on a modal test "
                        "bench); lumped: the fe web method becomes fe-held")
    p.add_argument("--stiffness", choices=sorted(WEB_METHODS), default=DEFAULT_WEB_METHOD)
    p.add_argument("--speed-range", nargs=2, type=real(0.0, unit="rpm"), metavar=("LOW", "HIGH"),
                   help="rpm, 0 < LOW < HIGH")
    p.add_argument("--orders", type=_orders, help="comma-separated orders (default 0.5 ... 12 for a 4-stroke)")
    p.add_argument("--damping", type=real(0.0, 1.0), help=f"modal damping ratio, 0 < ζ < 1 (default from the file, else {DEFAULT_DAMPING_RATIO:g})")
    add_json_option(p)
    p.add_argument("--plot", metavar="PATH", help="save the plot (.png, .pdf, .svg)")


def add_parsers(sub) -> None:
    """The ``campbell``, ``damper``, ``response`` commands."""
    cp = sub.add_parser("campbell", help="Campbell diagram: crossings of modes and orders, with severity")
    _add_excitation_options(cp)
    cp.add_argument("--modes", type=integer(1, 50), default=3,
                    help="number of lowest torsional modes (default %(default)s); the condensed crank in its bearings "
                         "shows every mode an order meets in range, with the fillet stress it drives")
    cp.add_argument("--mesh-size", type=millimetres(), default=DEFAULT_MESH_SIZE, metavar="MM",
                    help=f"FE mesh size for --source fe (default {DEFAULT_MESH_SIZE / MM:g})")
    cp.add_argument("--html", metavar="PATH", help="write the interactive Campbell diagram as a web page (.html)")
    cp.set_defaults(func=cmd_campbell)

    dp = sub.add_parser("damper", help="torsional damper: Den Hartog start, optimised on the whole crank")
    _add_excitation_options(dp)
    dp.add_argument("--type", choices=DAMPER_TYPES, default="rubber", help="damper type (default %(default)s)")
    dp.add_argument("--inertia-ratio", type=real(0.0, 2.0), default=DEFAULT_INERTIA_RATIO, metavar="MU",
                    help="ring inertia over the damped mode's equivalent inertia at the station, 0 < MU < 2 "
                         "(default %(default)s)")
    dp.add_argument("--optimise", action="store_true", help="optimise stiffness and damping on the whole crank "
                    "over the speed range after the Den Hartog start (ring inertia held)")
    dp.add_argument("--objective", choices=[o for o in OBJECTIVES if o != "fatigue"], default="stress",
                    help="what the optimiser minimises: the largest fillet shear stress or the pulley twist")
    dp.add_argument("--at", choices=DAMPER_STATIONS, default="front", help="pulley end (front) or flywheel side")
    dp.add_argument("--hub-inertia", type=real(0.0, 10.0, low_open=False, unit="kg m^2"), default=0.0,
                    metavar="KGM2", help="hub or housing inertia, kg m^2 (default 0)")
    dp.add_argument("--steps", type=integer(2, 2000), default=100, help="speeds in the range (default %(default)s)")
    dp.set_defaults(func=cmd_damper)

    rp = sub.add_parser("response", help="forced torsional response of a lumped model versus speed")
    _add_excitation_options(rp)
    rp.add_argument("--steps", type=integer(2, 100_000), default=DEFAULT_SPEED_STEPS, help="speeds in the range (default %(default)s)")
    rp.add_argument("--misfire", type=integer(1), metavar="CYL",
                    help="cylinder CYL (1-based) does not fire: compression and expansion only")
    rp.add_argument("--mesh-size", type=millimetres(), default=DEFAULT_MESH_SIZE, metavar="MM",
                    help=f"FE mesh size for --source condensed (default {DEFAULT_MESH_SIZE / MM:g})")
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

    tp = sub.add_parser("transient", help="time domain: steady running or a run-up/run-down, order-tracked (linear, "
                        "or nonlinear with --variable-inertia or [[chain.nonlinear]] elements)")
    tp.add_argument("file", help="chain, network or crank description with [engine] and [excitation] (.toml)")
    speed = tp.add_mutually_exclusive_group(required=True)
    speed.add_argument("--rpm", type=real(0.0, 100_000.0, unit="rpm"), help="steady running at this speed, rpm")
    speed.add_argument("--run-up", nargs=2, type=real(0.0, 100_000.0, unit="rpm"), metavar=("A", "B"),
                       help="run from A to B rpm (A > B: a run-down), at --rate")
    tp.add_argument("--rate", type=real(0.0, 1.0e6, unit="rpm/s"), metavar="RPM_PER_S",
                    help="|dn/dt| of the run, rpm/s")
    tp.add_argument("--cycles", type=integer(1, 10_000), default=DEFAULT_TRANSIENT_CYCLES,
                    help="working cycles kept after settling, steady running (default %(default)s)")
    tp.add_argument("--teeth", type=integer(8, 10_000), default=DEFAULT_TEETH,
                    help="teeth of the simulated wheel the order tracking reads (default %(default)s)")
    tp.add_argument("--station", type=integer(1), metavar="N",
                    help="1-based coordinate of the model whose angle is order-tracked (default 1, the pulley)")
    tp.add_argument("--source", default="lumped17", choices=[f"lumped{d}" for d in PARTITIONS] + ["fe", "condensed"],
                    help="a crank's lumped model (default %(default)s; chains and networks are their own model)")
    tp.add_argument("--support", choices=SUPPORT_CHOICES, default="bearings", help=argparse.SUPPRESS)
    tp.add_argument("--stiffness", choices=sorted(WEB_METHODS), default=DEFAULT_WEB_METHOD)
    tp.add_argument("--damping", type=real(0.0, 1.0), help="modal damping ratio, 0 < ζ < 1 (default from the file)")
    tp.add_argument("--variable-inertia", action="store_true",
                    help="each cylinder's reciprocating mass as the crank-angle-dependent inertia m S'(θ)² "
                         "(nonlinear integrator)")
    tp.add_argument("--integrator", choices=NONLINEAR_METHODS, default=NONLINEAR_METHODS[0],
                    help="scipy solve_ivp method of the nonlinear integrator (default %(default)s)")
    add_json_option(tp)
    tp.add_argument("--plot", metavar="PATH", help="save the plot (.png, .pdf, .svg)")
    tp.set_defaults(func=cmd_transient)
