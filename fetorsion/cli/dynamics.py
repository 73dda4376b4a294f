"""``fetorsion campbell``, ``response`` and ``damper``: the excited crank (or chain) over its speed range."""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

from .options import MM, integer, millimetres, real
from ..description.model import Chain, Network
from ..errors import FetorsionError
from ..io import write_text_atomic
from ..lumped_model.lumped import PARTITIONS, lumped
from ..response.forced import COMPARE_UNITS
from ..description.defaults import (NONLINEAR_METHODS, DEFAULT_DAMPING_RATIO, DEFAULT_INERTIA_RATIO, DEFAULT_MESH_SIZE, DEFAULT_MODES,
                                    DEFAULT_PARTITION, DEFAULT_SPEED_STEPS, DEFAULT_STEP_DEG, DEFAULT_TEETH,
                                    DEFAULT_TRANSIENT_CYCLES, DEFAULT_WEB_METHOD, LUMPED17)
from ..webs.methods import WEB_METHODS
from ..description.model import DAMPER_STATIONS, DAMPER_TYPES
from ..design.dampers import OBJECTIVES
from .common import (SUPPORT_CHOICES, add_json_option, check_mesh_size, load_excited, partition_of, refuse_network,
                     report,
                     stiffness_for)
from .fe import condensed, engine_fillets


def source_of(args, model) -> str:
    """``--source``, or its default: a crank description's engine model (the condensed crank in
    its bearings, the run's), a chain's or network's own lumped model."""
    from ..response.driveline import condensed_part

    if args.source is not None:
        return args.source
    if isinstance(model, Network) and condensed_part(model) is not None:
        return "condensed"  # its [[chain.cranks]] names the condensed crank
    return LUMPED17 if isinstance(model, (Chain, Network)) else "condensed"


def load_for(args):
    """The command's description, with an [excitation] table; ``args.source`` set to its default
    (:func:`source_of`) when not given."""
    model = load_excited(args.file, args.source or LUMPED17)
    args.source = source_of(args, model)
    return model


def only_lumped_driveline(crank, args, command: str) -> None:
    """A network on the condensed crank (``dof = "condensed"``) is solved by ``response`` and
    ``run``; the other commands take its lumped stand-in only when asked by ``--source lumpedN``."""
    from ..response.driveline import condensed_part

    if isinstance(crank, Network) and condensed_part(crank) is not None and not str(args.source).startswith("lumped"):
        raise FetorsionError(f"{command}: {args.file} puts its crank in as the condensed crank, which `fetorsion "
                             f"response` and `fetorsion run` solve; give --source lumped17 for the driveline on the "
                             f"crank's lumped 17-DOF model")


def engine_model(crank, args):
    """(the run's condensed crank, with its oil films, and the crank's fillets): from the
    store, or built once and kept (:func:`fetorsion.cli.fe.condensed`)."""
    check_mesh_size(crank, args.mesh_size, "modal")
    return condensed(crank, args.mesh_size), engine_fillets(crank)


def stored_engine_model(crank, args):
    """(the condensed crank, fillets) when the store has this crank condensed already, else None:
    a lumped answer then says how far it is from the engine model's, at no rebuild."""
    from ..design.stress import fillet_cuts
    from ..fe.store import stored_condensed
    from ..response.coupled import with_film_bearings

    if isinstance(crank, (Chain, Network)) or getattr(args, "support", "bearings") != "bearings":
        return None
    fillets = engine_fillets(crank)
    cc = stored_condensed(crank, getattr(args, "mesh_size", DEFAULT_MESH_SIZE), fillet_cuts(crank, fillets))
    return None if cc is None else (with_film_bearings(cc), fillets)


def engine_campbell(cc, fillets, support: str, orders=None, speed_range=None, damping_ratio=None):
    """The condensed crank's Campbell diagram as the run draws it: severity the nominal stress at
    the worst fillet, named."""
    from ..response.coupled import run_coupled_campbell

    named = cc.cut_rows is not None and len(cc.cut_rows) == len(fillets)
    return run_coupled_campbell(cc, support, diameters=[(f.diameter, f.bore) for f in fillets], orders=orders,
                                speed_range=speed_range, damping_ratio=damping_ratio,
                                section_names=[f.label for f in fillets] if named else None)


def _gap_line(what: str, lumped_value: float, engine_value: float, unit: str) -> str:
    return (f"(lumped answer; the condensed crank in its bearings, stored, gives {what} {engine_value:.4g} {unit}: "
            f"the lumped one is {100 * (lumped_value / engine_value - 1):+.1f} % from it)")


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
        engine = stored_engine_model(crank, args) if args.source.startswith("lumped") else None
        if engine is not None and res.frequencies_hz.size:
            f1 = engine[0].modes(args.support).first_torsional()
            gap = _gap_line("f1", float(res.frequencies_hz[0]), f1, "Hz")
    head = (f"{res.name}: crossings inside {res.speed_range_rpm[0]:.0f}-{res.speed_range_rpm[1]:.0f} rpm, "
            f"most severe first ({res.source})")
    report(res, head + "\n" + res.table() + ("" if gap is None else "\n" + gap), args)
    if args.html:
        from ..report.html import campbell_figure, page

        text = f"# {res.name}: Campbell diagram\n\n![](campbell.png)\n\n```\n{head}\n{res.table()}\n```\n"
        write_text_atomic(args.html, page(res.name, text, {"campbell.png": campbell_figure(res, "campbell")},
                                          Path(args.html).parent))
    return 0


def engine_setup(cc, fillets, support: str, rpm, orders=None, damping_ratio=None):
    """The condensed crank as a response setup, its sections the fillets: the run's."""
    from ..response.coupled import condensed_setup

    return condensed_setup(cc, support, rpm=rpm, orders=orders, damping_ratio=damping_ratio,
                           section_labels=[f.label for f in fillets])


def _worst_torque(res) -> float:
    return float(np.max(res.section_torque_nm))


def cmd_response(args) -> int:
    from ..response.forced import misfire_harmonics, run_response, solve_response

    crank = load_for(args)
    if args.source == "fe":
        raise FetorsionError("--source fe: the forced response uses a lumped model or the condensed crank; "
                             "choose --source lumpedN or condensed")
    rpm = np.linspace(*(args.speed_range or crank.excitation.checked_range), args.steps)
    if args.misfire is not None and args.misfire > crank.engine.cylinders:
        raise FetorsionError(f"--misfire {args.misfire}: the engine has cylinders 1..{crank.engine.cylinders}")
    if args.misfire is not None and crank.excitation.pressure_curve is not None:
        raise FetorsionError(f"--misfire: {args.file} gives a measured pressure_csv; the motored cycle of a misfiring "
                             "cylinder needs the synthetic cycle (compression_ratio)")
    gap = None
    if args.bearing_forces and args.source != "condensed":
        raise FetorsionError("--bearing-forces: the bearings carry forces in the condensed crank only; "
                             "leave --source out (or give --source condensed)")
    if args.bearing_forces:
        from ..response.coupled import run_coupled_response

        for option in ("compare", "misfire"):
            if getattr(args, option) is not None:
                raise FetorsionError(f"--{option} is not taken with --bearing-forces")
        cc, _ = engine_model(crank, args)
        res = run_coupled_response(cc, args.support, rpm=rpm, orders=args.orders, damping_ratio=args.damping)
        return report(res, res.table(), args)
    if args.source == "condensed" and isinstance(crank, Network):
        # the driveline with its crank as the condensed FE crank in its bearings
        from ..response.driveline import condensed_part, driveline_setup

        part = condensed_part(crank)
        if part is None:
            raise FetorsionError(f"--source condensed: {args.file} has no [[chain.cranks]] with dof = \"condensed\"")
        for option in ("misfire", "compare_section"):
            if getattr(args, option) is not None:
                raise FetorsionError(f"--{option.replace('_', '-')} is not taken for a network on a condensed crank yet")
        cc, fillets = engine_model(part.crank, args)
        res = solve_response(driveline_setup(crank, cc, rpm, args.orders, args.damping, [f.label for f in fillets]),
                             crank.dampers)
    elif args.source == "condensed":
        cc, fillets = engine_model(crank, args)
        setup = engine_setup(cc, fillets, args.support, rpm, args.orders, args.damping)
        if args.compare_section is not None and args.compare_section > len(setup.section_labels):
            raise FetorsionError(f"--compare-section {args.compare_section}: the model has "
                                 f"{len(setup.section_labels)} sections (the fillets)")
        if args.misfire is not None:
            setup = setup.with_misfire(args.misfire - 1, misfire_harmonics(crank, setup))
        res = solve_response(setup, crank.dampers)
    else:
        if args.compare_section is not None:  # checked on the model's springs before the response is computed
            springs = len(lumped(crank, partition_of(args.source), args.stiffness).stiffnesses_nm_per_rad)
            if args.compare_section > springs:
                raise FetorsionError(f"--compare-section {args.compare_section}: the model has {springs} shaft sections")
        res = run_response(crank, partition_of(args.source), rpm=rpm, orders=args.orders, damping_ratio=args.damping,
                           web_method=stiffness_for(args), misfire=None if args.misfire is None else args.misfire - 1)
        engine = stored_engine_model(crank, args)
        if engine is not None:
            setup = engine_setup(*engine, args.support, rpm, args.orders, args.damping)
            if args.misfire is not None:
                setup = setup.with_misfire(args.misfire - 1, misfire_harmonics(crank, setup))
            gap = _gap_line("the largest section torque", _worst_torque(res),
                            _worst_torque(solve_response(setup, crank.dampers)), "N m")
    if args.compare is not None:
        from ..response.forced import compare_curve

        rpm_c, value, name, unit = args.compare_curve
        compare_curve(res, rpm_c, value, name, unit,
                      None if args.compare_section is None else args.compare_section - 1)
    return report(res, res.table() + ("" if gap is None else "\n" + gap), args)


def cmd_damper(args) -> int:
    from ..design.crank_verdict import run_fatigue_damper, verdict_scfs
    from ..design.dampers import run_damper

    crank = load_for(args)
    refuse_network(crank, args.file, "damper")  # first: no --source makes a network a damper's model yet
    if args.source == "fe":
        raise FetorsionError("--source fe: the damper is designed on the condensed crank (default) or a lumped "
                             "model; choose --source condensed or lumpedN")
    objective = args.objective or ("twist" if isinstance(crank, Chain) else "fatigue")
    if objective in ("stress", "fatigue") and isinstance(crank, Chain):
        raise FetorsionError(f"--objective {objective}: {args.file} is a chain file, it has no shaft sections; "
                             "use --objective twist")
    if objective in ("stress", "fatigue") and not (crank.fillets.journal > 0 and crank.fillets.pin > 0):
        raise FetorsionError(f"--objective {objective}: {args.file} has no fillet radii (a sharp corner has no finite "
                             "SCF); give [fillets] or use --objective twist")
    rpm = np.linspace(*(args.speed_range or crank.excitation.checked_range), args.steps)
    if args.source == "condensed":
        cc, fillets = engine_model(crank, args)
        setup = engine_setup(cc, fillets, args.support, rpm, args.orders, args.damping)
    else:
        from ..response.forced import response_setup

        fillets = None if isinstance(crank, Chain) else engine_fillets(crank)
        setup = response_setup(crank, partition_of(args.source), rpm, args.orders, args.damping, stiffness_for(args))
    if objective == "fatigue":
        # the run's recommended damper: M53's governing safety over the speeds
        res = run_fatigue_damper(crank, setup, fillets, verdict_scfs(crank), args.type, args.inertia_ratio,
                                 args.optimise, args.at, args.hub_inertia)
    else:
        from ..design.crank_verdict import design_speeds

        res = run_damper(crank, args.type, args.inertia_ratio, args.optimise, objective, args.at, args.hub_inertia,
                         setup=design_speeds(setup), fillets=fillets)
    # checked on every speed of the range (the optimiser read at most 100 of them)
    from ..response.forced import solve_response

    chosen = res.optimised or res.den_hartog
    lines = [f"  checked at all {len(setup.rpm)} speeds ({setup.model}):"]
    for name, dampers in (("without a damper", ()), (f"with the {'optimised' if res.optimised else 'Den Hartog'} "
                                                     "damper", (chosen,))):
        lines.append(f"    {name}: {solve_response(setup, dampers).worst_torque_text()}")
    engine = stored_engine_model(crank, args) if args.source.startswith("lumped") else None
    if engine is not None:
        undamped = solve_response(setup, ())
        stored = solve_response(engine_setup(*engine, args.support, rpm, args.orders, args.damping), ())
        lines.append(_gap_line("the largest section torque without a damper", _worst_torque(undamped),
                               _worst_torque(stored), "N m"))
    return report(res, res.table() + "\n" + "\n".join(lines), args)


def cmd_transient(args) -> int:
    from ..response.transient import run_transient

    if args.source == "fe":
        raise FetorsionError("--source fe: the time domain uses the condensed crank (a crank's default for --rpm) "
                             "or a lumped model; choose --source condensed or lumpedN")
    if args.run_up is not None and args.rate is None:
        raise FetorsionError("--run-up A B needs --rate RPM_PER_S (how fast the speed changes)")
    if args.rate is not None and args.run_up is None:
        raise FetorsionError("--rate goes with --run-up A B (a steady --rpm has no rate)")
    from ..response.transient import MAX_STEP_RAD

    if args.step_deg > math.degrees(MAX_STEP_RAD):
        raise FetorsionError(f"--step-deg {args.step_deg:g}: at most {math.degrees(MAX_STEP_RAD):.4g}° (two steps a "
                             "period of the highest order a response sums)")
    if args.settled_start and args.run_up is None:
        raise FetorsionError("--settled-start goes with --run-up A B (a steady --rpm settles by itself)")
    if args.run_up is not None and args.run_up[0] == args.run_up[1]:
        raise FetorsionError(f"--run-up {args.run_up[0]:g} {args.run_up[1]:g}: A and B must differ "
                             "(A < B a run-up, A > B a run-down; for one speed use --rpm)")
    crank = load_excited(args.file, args.source or LUMPED17)
    only_lumped_driveline(crank, args, "transient")
    engine_can = args.run_up is None and not args.variable_inertia and not getattr(crank, "dampers", ())
    if args.source is None:
        # a crank's steady running: the engine model; what it cannot do yet, the lumped chain (said)
        args.source = LUMPED17 if isinstance(crank, (Chain, Network)) or not engine_can else "condensed"
    if args.source == "condensed":
        if not engine_can:
            what = ("--run-up" if args.run_up is not None else "--variable-inertia" if args.variable_inertia
                    else "[[dampers]]")
            raise FetorsionError(f"--source condensed: the condensed crank's time domain is steady running (--rpm) "
                                 f"without {what} yet; choose --source lumpedN")
        if args.station is not None:
            raise FetorsionError("--station: the condensed crank's steady run tracks the pulley's angle; leave "
                                 "--station out or choose --source lumpedN")
        from ..response.engine_transient import run_engine_steady

        cc, fillets = engine_model(crank, args)
        setup = engine_setup(cc, fillets, args.support, [args.rpm], damping_ratio=args.damping)
        res = run_engine_steady(setup, args.cycles, args.teeth)
        return report(res, res.table(), args)
    if args.station is not None:
        dof = lumped(crank, partition_of(args.source), args.stiffness).dof
        if args.station > dof:
            raise FetorsionError(f"--station {args.station}: the model has coordinates 1..{dof}")
    res = run_transient(crank, rpm=args.rpm, run=None if args.run_up is None else tuple(args.run_up),
                        rate_rpm_per_s=args.rate, cycles=args.cycles, damping_ratio=args.damping,
                        partition=partition_of(args.source), web_method=stiffness_for(args), teeth=args.teeth,
                        track_station=0 if args.station is None else args.station - 1,
                        variable_inertia=args.variable_inertia, method=args.integrator,
                        step_rad=math.radians(args.step_deg), settled_start=args.settled_start)
    model = "" if isinstance(crank, (Chain, Network)) else (
        f"\n(the crank's lumped {partition_of(args.source)}-DOF chain, not the condensed crank the run and 'response' "
        "answer for: the condensed crank's time domain is steady running, --rpm, without dampers)")
    return report(res, res.table() + model, args)


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
    p.add_argument("--source", choices=[f"lumped{d}" for d in PARTITIONS] + ["fe", "condensed"],
                   help="which model answers (default: for a crank description condensed, the engine model 'fetorsion "
                        "run' reports on: the 3D FE crank condensed to its journal and pin centres in its bearings, "
                        "torsion and bending coupled, taken from the store after its first build; for a chain or "
                        "network file its own lumped model). lumpedN: the fast N-DOF chain, with a line saying how "
                        "far it is from the stored condensed crank; fe: campbell only, free-free FE torsional modes")
    p.add_argument("--mesh-size", type=millimetres(), default=DEFAULT_MESH_SIZE, metavar="MM",
                   help=f"FE mesh size of the condensed crank (and of --source fe) (default {DEFAULT_MESH_SIZE / MM:g})")
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
    dp.add_argument("--objective", choices=OBJECTIVES,
                    help="what the optimiser minimises (default: fatigue for a crank, the run's recommended damper: "
                         "the largest IACS UR M53 utilisation over the speeds; twist for a chain): fatigue, the "
                         "largest fillet shear stress, or the pulley twist")
    dp.add_argument("--at", choices=DAMPER_STATIONS, default="front", help="pulley end (front) or flywheel side")
    dp.add_argument("--hub-inertia", type=real(0.0, 10.0, low_open=False, unit="kg m^2"), default=0.0,
                    metavar="KGM2", help="hub or housing inertia, kg m^2 (default 0)")
    dp.add_argument("--steps", type=integer(2, 2000), default=DEFAULT_SPEED_STEPS,
                    help="speeds in the range (default %(default)s, the run's; the optimiser reads at most 100 of them)")
    dp.set_defaults(func=cmd_damper)

    rp = sub.add_parser("response", help="forced response versus speed: the condensed crank in its bearings (a crank), "
                        "or the lumped model")
    _add_excitation_options(rp)
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
    tp.add_argument("--step-deg", type=real(0.0, 180.0, unit="degrees"), default=DEFAULT_STEP_DEG,
                    metavar="DEG", help="crank angle per time step at the run's top speed, degrees (default "
                    "%(default)g; at most 7.5)")
    tp.add_argument("--settled-start", action="store_true",
                    help="a run first holds its start speed until starting from rest has rung out (the envelope "
                         "and order track begin after the hold); without it the first revolutions ring")
    tp.add_argument("--station", type=integer(1), metavar="N",
                    help="1-based coordinate of the model whose angle is order-tracked (default 1, the pulley)")
    tp.add_argument("--source", choices=[f"lumped{d}" for d in PARTITIONS] + ["fe", "condensed"],
                    help="default: a crank's steady running (--rpm) on the condensed crank in its bearings (the run's "
                         "engine model, from the store), a run-up, variable inertia or [[dampers]] on its lumped "
                         "17-DOF chain (said in the output); chains and networks are their own model")
    tp.add_argument("--mesh-size", type=millimetres(), default=DEFAULT_MESH_SIZE, metavar="MM",
                    help=f"FE mesh size of the condensed crank (default {DEFAULT_MESH_SIZE / MM:g})")
    tp.add_argument("--support", choices=SUPPORT_CHOICES, default="bearings", help=argparse.SUPPRESS)
    tp.add_argument("--stiffness", choices=sorted(WEB_METHODS), default=DEFAULT_WEB_METHOD)
    tp.add_argument("--damping", type=real(0.0, 1.0), help="modal damping ratio, 0 < ζ < 1 (default from the file)")
    tp.add_argument("--variable-inertia", action="store_true",
                    help="each cylinder's reciprocating mass as the crank-angle-dependent inertia m S'(θ)² "
                         "(nonlinear integrator)")
    tp.add_argument("--integrator", choices=NONLINEAR_METHODS, default=NONLINEAR_METHODS[0],
                    help="the nonlinear integrator: compiled (Dormand-Prince in numba, friction as exact Jenkins "
                         "elements) or a scipy solve_ivp method, the cross-check (default %(default)s)")
    add_json_option(tp)
    tp.add_argument("--plot", metavar="PATH", help="save the plot (.png, .pdf, .svg)")
    tp.set_defaults(func=cmd_transient)
