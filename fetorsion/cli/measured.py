"""``fetorsion compare``: the model against measured files (modal-test FRFs, order cuts,
torsiograph recordings), one table and one figure per quantity."""

from __future__ import annotations

import sys
from pathlib import Path

from .common import add_json_option, emit_json, load_description, refuse_network
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


def read_measured(paths, band=None, unit=None, order=None, teeth=None, revolutions: int = 2,
                  track_orders=(2.0,)) -> dict:
    """Every measured file read and checked, before any model is solved: ``frfs`` (UFF FRFs),
    ``cuts`` (order cuts against speed, in SI) and the options the comparison takes. One message
    naming the file or option otherwise."""
    from ..measured.ordercut import read_order_cut_csv
    from ..measured.torsiograph import read_edges_csv, run_torsiograph
    from ..measured.uff import read_uff58
    from ..studies.comparison import track_order_cut

    kinds = [_measured_kind(m, teeth) for m in paths]
    if band is not None and not 0 <= band[0] < band[1]:
        raise FetorsionError(f"--band {band[0]:g} {band[1]:g}: give 0 <= LOW < HIGH (Hz)")
    frfs, cuts, tracks = [], [], []
    for path, kind in zip(paths, kinds):
        if kind == "uff":
            functions = read_uff58(path)
            frfs += [f for f in functions if f.kind == "frf"]
            cuts += [f for f in functions if f.kind == "order function" and f.abscissa_quantity == "speed"]
        elif kind == "order-cut":
            cuts.append(read_order_cut_csv(path, unit, order))
        else:
            edges = read_edges_csv(path)
            res = run_torsiograph(edges, {c: teeth for c in edges}, revolutions)
            for channel, track in res.tracks.items():
                for k in track_orders:
                    cuts.append(track_order_cut(track, k, f"{Path(path).name}: {channel}"))
                tracks.append((f"{Path(path).name}: {channel}", track))
    if frfs and band is None:
        raise FetorsionError("--band LOW HIGH: give the frequency band (Hz) to fit the measured FRFs' modes in")
    if not (frfs or cuts):
        raise FetorsionError("compare: the measured files hold no FRF and no order cut against speed")
    return {"frfs": frfs, "cuts": cuts, "tracks": tracks, "band": None if band is None else tuple(band)}


def check_measured(crank, measured: dict, station: str | None) -> None:
    """What the model needs of the measured data, checked before it is solved: order cuts need an
    ``[excitation]`` and must be angles; the station must exist."""
    if measured["cuts"] and getattr(crank, "excitation", None) is None:
        raise FetorsionError(f"compare: {crank.name} has no [excitation] table: the model has no order cuts")
    for c in measured["cuts"]:
        if c.unit != "rad":
            raise FetorsionError(f"compare: {c.label or 'an order cut'} is in {c.unit}; the model's order cuts are "
                                 "angles (deg, mrad or rad)")
    check_station(crank, station)


def check_station(crank, station: str | None) -> None:
    """A station that is not the pulley or flywheel end must be a label of the lumped chain."""
    if station is not None and station.lower() not in ("pulley", "flywheel"):
        from ..lumped_model.lumped import lumped
        from ..studies.comparison import station_index

        station_index(lumped(crank, 17), station)


def cmd_compare(args) -> int:
    from ..studies.comparison import run_comparison

    for m in args.measured:
        _measured_kind(m, args.teeth)
    if args.band is not None and not 0 <= args.band[0] < args.band[1]:
        raise FetorsionError(f"--band {args.band[0]:g} {args.band[1]:g}: give 0 <= LOW < HIGH (Hz)")
    crank = load_description(args.file)
    refuse_network(crank, args.file, "compare")
    check_station(crank, args.station)
    measured = read_measured(args.measured, args.band, args.unit, args.order, args.teeth, args.revolutions,
                             args.track_orders)
    check_measured(crank, measured, args.station)
    out = run_comparison(crank, measured, args.source, args.station)
    print(out.table())
    emit_json(out.to_dict(), args.json)
    if args.plot:
        save_figure_atomic(out.plot(), args.plot, close=True, dpi=120)
        print(f"figure: {args.plot}", file=sys.stderr)
    if args.uff:
        from ..measured.uff import write_uff58
        from ..studies.comparison import model_predictions

        write_uff58(args.uff, model_predictions(crank, out))
        print(f"the model's predictions (UFF 58): {args.uff}", file=sys.stderr)
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
    cp.add_argument("--uff", metavar="PATH", help="write the model's predictions as UFF 58 (its order cuts at the "
                    "sensor's station; its receptances at the pulley and flywheel ends over the measured band), to "
                    "overlay in a test system's own tools")
    add_json_option(cp)
    cp.set_defaults(func=cmd_compare)
