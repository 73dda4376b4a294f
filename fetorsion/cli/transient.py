"""``fetorsion transient``: the time domain, steady running or a run-up or run-down, order-tracked;
linear, or nonlinear with variable inertia or a chain's nonlinear elements."""

from __future__ import annotations

import argparse
import math

from .options import MM, integer, millimetres, real
from ..app.engine_answers import engine_setup
from ..description.chain_model import Chain, Network
from ..errors import FetorsionError
from ..lumped_model.lumped import PARTITIONS, lumped
from ..description.defaults import (NONLINEAR_METHODS, DEFAULT_MESH_SIZE, DEFAULT_STEP_DEG, DEFAULT_TEETH,
                                    DEFAULT_TRANSIENT_CYCLES, DEFAULT_WEB_METHOD, LUMPED17)
from ..webs.methods import WEB_METHODS
from .common import SUPPORT_CHOICES, add_json_option, load_excited, partition_of, report, stiffness_for
from .excited import engine_model, only_lumped_driveline


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


def add_parser(sub) -> None:
    """The ``transient`` command."""
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
