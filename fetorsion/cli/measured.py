"""``fetorsion compare``: the model against measured files (modal-test FRFs, order cuts,
torsiograph recordings), one table and one figure per quantity."""

from __future__ import annotations

import sys
from pathlib import Path

from .common import add_json_option, emit_json, load_description
from .options import integer, real
from ..errors import FetorsionError
from ..io import save_figure_atomic

#: Suffixes read as Universal File Format.
UFF_SUFFIXES = (".uff", ".unv", ".uf")


def _measured_kind(path: str, teeth) -> str:
    """What a measured file is, by its suffix (and --teeth for edge recordings), checked before any work."""
    p = Path(path)
    if not p.is_file():
        raise FetorsionError(f"compare: {path}: no such file")
    suffix = p.suffix.lower()
    if suffix in UFF_SUFFIXES:
        return "uff"
    if suffix == ".csv":
        return "edges" if teeth is not None else "order-cut"
    raise FetorsionError(f"compare: {path}: give a UFF file ({', '.join(UFF_SUFFIXES)}) or a CSV "
                         "(an order cut, or tooth-edge times with --teeth)")


def cmd_compare(args) -> int:
    from ..measured.modal import run_modal_fit
    from ..measured.ordercut import read_order_cut_csv
    from ..measured.torsiograph import read_edges_csv, run_torsiograph
    from ..measured.uff import read_uff58
    from ..studies.comparison import (ComparisonResult, compare_frequencies, compare_order_cut,
                                      track_order_cut)

    kinds = [_measured_kind(m, args.teeth) for m in args.measured]
    if args.band is not None and not 0 <= args.band[0] < args.band[1]:
        raise FetorsionError(f"--band {args.band[0]:g} {args.band[1]:g}: give 0 <= LOW < HIGH (Hz)")
    crank = load_description(args.file)
    if args.station is not None and args.station.lower() not in ("pulley", "flywheel"):
        from ..lumped_model.lumped import lumped
        from ..studies.comparison import station_index

        station_index(lumped(crank, 17), args.station)  # the chain's labels: a wrong station named now
    # every file read and checked before any model is solved
    frfs, cuts = [], []
    for path, kind in zip(args.measured, kinds):
        if kind == "uff":
            functions = read_uff58(path)
            frfs += [f for f in functions if f.kind == "frf"]
            cuts += [f for f in functions if f.kind == "order function" and f.abscissa_quantity == "speed"]
        elif kind == "order-cut":
            cuts.append(read_order_cut_csv(path, args.unit, args.order))
        else:
            edges = read_edges_csv(path)
            res = run_torsiograph(edges, {c: args.teeth for c in edges}, args.revolutions)
            for channel, track in res.tracks.items():
                for order in args.track_orders:
                    cuts.append(track_order_cut(track, order, f"{Path(path).name}: {channel}"))
    if frfs and args.band is None:
        raise FetorsionError("--band LOW HIGH: give the frequency band (Hz) to fit the measured FRFs' modes in")
    out = ComparisonResult(crank.name)
    if frfs:
        out.frequencies.append(compare_frequencies(run_modal_fit(frfs, tuple(args.band)), crank, args.source))
    if cuts:
        if getattr(crank, "excitation", None) is None:
            raise FetorsionError(f"compare: {args.file} has no [excitation] table: the model has no order cuts")
        from ..response.forced import run_response

        response = run_response(crank)
        out.order_cuts += [compare_order_cut(c, response, args.station) for c in cuts]
    if not (out.frequencies or out.order_cuts):
        raise FetorsionError("compare: the measured files hold no FRF and no order cut against speed")
    print(out.table())
    emit_json(out.to_dict(), args.json)
    if args.plot:
        save_figure_atomic(out.plot(), args.plot, close=True, dpi=120)
        print(f"figure: {args.plot}", file=sys.stderr)
    return 0


def add_parsers(sub) -> None:
    from ..studies.comparison import FREQUENCY_SOURCES

    cp = sub.add_parser("compare", help="the model against measurement: modal-test FRFs (UFF 58), order cuts "
                        "(UFF 58 or CSV), torsiograph tooth-edge recordings (CSV)")
    cp.add_argument("file", help="crank description (.toml)")
    cp.add_argument("measured", nargs="+", help="measured files: .uff/.unv (dataset 58: FRFs, order functions), "
                    ".csv order cuts (rpm, amplitude[, phase]; '# unit', '# order' lines), or .csv tooth-edge "
                    "times (with --teeth)")
    cp.add_argument("--source", choices=FREQUENCY_SOURCES, default="lumped17",
                    help="model of the natural frequencies: the lumped chain or the free-free 3D FE (default %(default)s)")
    cp.add_argument("--band", type=real(0.0, low_open=False), nargs=2, metavar=("LOW", "HIGH"),
                    help="frequency band (Hz) in which to fit the measured FRFs' modes")
    cp.add_argument("--station", help="where the order cuts were measured: pulley (default), flywheel, or a "
                    "station label of the lumped chain (J1 ... J5, P1 ...)")
    cp.add_argument("--unit", help="amplitude unit of CSV order cuts without a '# unit' line (deg, mrad, rad)")
    cp.add_argument("--order", type=real(0.0), help="engine order of CSV order cuts without a '# order' line")
    cp.add_argument("--teeth", type=integer(1), help="teeth per revolution of every wheel of a tooth-edge CSV")
    cp.add_argument("--revolutions", type=integer(1), default=2,
                    help="revolutions per block of a torsiograph's order tracking (default %(default)s: half orders "
                         "fall on its bins)")
    cp.add_argument("--track-orders", type=real(0.0), nargs="+", default=[2.0], metavar="K",
                    help="orders of a torsiograph's recording to compare (default 2)")
    cp.add_argument("--plot", metavar="PATH", help="figure of every comparison (.png, .pdf, .svg)")
    add_json_option(cp)
    cp.set_defaults(func=cmd_compare)
