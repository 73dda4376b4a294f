"""``fetorsion damper``: a torsional damper for the excited crank, Den Hartog's start optimised on
the whole crank (the run's recommended damper by default), checked at every speed."""

from __future__ import annotations

import numpy as np

from .options import integer, real
from ..app.engine_answers import engine_setup, stored_engine_model, worst_torque
from ..description.model import DAMPER_STATIONS, DAMPER_TYPES
from ..description.chain_model import Chain
from ..description.defaults import DEFAULT_INERTIA_RATIO, DEFAULT_SPEED_STEPS
from ..design.dampers import OBJECTIVES
from ..errors import FetorsionError
from .common import partition_of, refuse_network, report, stiffness_for
from .excited import add_excitation_options, engine_gap_line, engine_model, load_for
from .fe import engine_fillets


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
    return report(res, res.table() + "\n" + "\n".join(_checked_lines(args, crank, setup, res, rpm)), args)


def _checked_lines(args, crank, setup, res, rpm) -> list[str]:
    """The damper checked on every speed of the range (the optimiser read at most 100 of them),
    and a lumped answer's distance from the stored engine model."""
    from ..response.forced import solve_response

    chosen = res.optimised or res.den_hartog
    lines = [f"  checked at all {len(setup.rpm)} speeds ({setup.model}):"]
    for name, dampers in (("without a damper", ()), (f"with the {'optimised' if res.optimised else 'Den Hartog'} "
                                                     "damper", (chosen,))):
        lines.append(f"    {name}: {solve_response(setup, dampers).worst_torque_text()}")
    engine = stored_engine_model(crank, args.support, args.mesh_size) if args.source.startswith("lumped") else None
    if engine is not None:
        undamped = solve_response(setup, ())
        stored = solve_response(engine_setup(*engine, args.support, rpm, args.orders, args.damping), ())
        lines.append(engine_gap_line("the largest section torque without a damper", worst_torque(undamped),
                                     worst_torque(stored), "N m"))
    return lines


def add_parser(sub) -> None:
    """The ``damper`` command."""
    dp = sub.add_parser("damper", help="torsional damper: Den Hartog start, optimised on the whole crank")
    add_excitation_options(dp)
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
