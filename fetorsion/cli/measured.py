"""``fetorsion compare``: the model against measured files (modal-test FRFs, order cuts,
torsiograph recordings), one table and one figure per quantity; the options of measured files
(shared with ``run --measured``); and the parsers of ``compare`` and ``calibrate``
(:mod:`.calibrate`: the description's ``[uncertainty]`` inputs fitted to measured natural
frequencies)."""

from __future__ import annotations

import sys
from dataclasses import replace

from ..description.defaults import LUMPED17
from ..measured.dataset import MeasuredData
from ..measured.uff import UnstatedUnit
from ..measured.reading import (LARGEST_FOUND, TRACKED_MAJOR_ORDERS, MeasuredOptions, measured_kind, read_measured,
                                tracked_orders)
from .calibrate import add_calibrate_parser
from .common import add_band_option, add_json_option, check_mesh_size, emit_json, load_description, refuse_network
from .options import integer, real
from ..errors import FetorsionError
from ..io import save_figure_atomic

def teeth_of(values) -> dict | str | None:
    """``--teeth``: one wheel for every channel (``60``, ``60-2``), or ``CHANNEL=WHEEL`` each;
    every wheel checked now (:func:`fetorsion.measured.wheels.wheel_of`)."""
    from ..measured.wheels import wheel_of

    if not values:
        return None
    per, every = {}, None
    for v in values:
        name, eq, spec = str(v).rpartition("=")
        if eq:
            per[name.strip()] = wheel_of(spec, f"--teeth {v}")
        elif every is None and len(values) == 1:
            every = wheel_of(spec, f"--teeth {v}")
        else:
            raise FetorsionError(f"--teeth {' '.join(map(str, values))}: give one wheel for every channel (60, "
                                 "60-2) or CHANNEL=WHEEL for each")
    return every if every is not None else per


def frf_units(text: str | None) -> dict:
    """``--frf-unit``: the unit of FRF records without a label, ``rad/N m`` (response and
    excitation) or ``rad`` (the response only), as read_uff58's ``units``."""
    from ..measured.uff import split_ratio
    from ..measured.units import unit

    if text is None:
        return {}
    ratio = split_ratio(text)
    if ratio is not None:
        unit(ratio[0], "--frf-unit (response)")
        return {"ordinate": ratio[0], "reference": ratio[1]}
    unit(text, "--frf-unit")
    return {"ordinate": text}


def check_measured(crank, measured: MeasuredData, station: str | None, source: str = LUMPED17) -> MeasuredData:
    """What the model needs of the measured data, checked before it is solved: order cuts need an
    ``[excitation]`` and must be angles; the stations must exist. Returns the data with each
    torsiograph channel's station settled: the one the user gave, else the channel's name where
    the model has such a station, else (left out) ``station``."""
    from ..studies.modelstations import model_stations

    if measured.cuts and getattr(crank, "excitation", None) is None:
        raise FetorsionError(f"compare: {crank.name} has no [excitation] table: the model has no order cuts")
    for c in measured.cuts:
        if c.unit != "rad":
            raise FetorsionError(f"compare: {c.label or 'an order cut'} is in {c.unit}; the model's order cuts are "
                                 "angles (deg, mrad or rad)")
    check_station(crank, station, source)
    names = {n.lower() for n in model_stations(crank, source)} | {"pulley", "flywheel"}
    settled = {}
    for label, (where, said) in measured.stations.items():
        places = where if isinstance(where, tuple) else (where,)
        if said:
            for p in places:
                check_station(crank, p, source)
        elif not all(p.lower() in names for p in places):
            if isinstance(where, tuple):
                raise FetorsionError(f"--twist: the channels {' and '.join(where)} are not stations of the model; "
                                     "say where each was measured (--channel-station CHANNEL=STATION)")
            continue
        settled[label] = (where, said)
    return replace(measured, stations=settled)


def check_station(crank, station: str | None, source: str = LUMPED17) -> None:
    """A station that is not the pulley or flywheel end must be one of the model's
    (:func:`fetorsion.studies.modelstations.model_stations`), checked before any model is built."""
    if station is not None and station.lower() not in ("pulley", "flywheel"):
        from ..studies.modelstations import model_stations, station_place

        station_place(model_stations(crank, source), station)


def compare_source(args, crank) -> str:
    """``--source``, or its default: the condensed crank for a crank description, the chain's own
    lumped model for a chain file."""
    from ..description.chain_model import Chain

    if args.source is not None:
        if args.source != LUMPED17 and isinstance(crank, Chain):
            raise FetorsionError(f"--source {args.source}: {args.file} is a chain (no geometry); its model is "
                                 f"{LUMPED17}")
        return args.source
    return LUMPED17 if isinstance(crank, Chain) else "condensed"


def cmd_compare(args) -> int:
    from ..studies.comparison import run_comparison
    from ..studies.modelstations import model_response

    for m in args.measured:
        measured_kind(m, args.teeth)
    teeth_of(args.teeth)
    if args.band is not None and not 0 <= args.band[0] < args.band[1]:
        raise FetorsionError(f"--band {args.band[0]:g} {args.band[1]:g}: give 0 <= LOW < HIGH (Hz)")
    crank = load_description(args.file)
    refuse_network(crank, args.file, "compare")
    source = compare_source(args, crank)
    if source != LUMPED17:
        check_mesh_size(crank, args.mesh_size, "modal")
    check_station(crank, args.station, source)
    measured = measured_of(args, args.measured, args.unit, args.order, crank)
    for line in measured.notes:
        print(f"fetorsion: warning: {line}", file=sys.stderr)
    measured = check_measured(crank, measured, args.station, source)
    cc = None
    if source != LUMPED17 and (measured.cuts or measured.tracks or source == "condensed"):
        from .fe import condensed

        cc = condensed(crank, args.mesh_size)
    reference = None
    if source == LUMPED17 and measured.cuts:
        from ..app.engine_answers import stored_engine_model

        # compare's running measurements: the crank in its bearings
        engine = stored_engine_model(crank, mesh_size=args.mesh_size)
        if engine is not None:
            reference = model_response(crank, "condensed", engine[0])
    out = run_comparison(crank, measured, source, args.station, condensed=cc, mesh_size=args.mesh_size,
                         reference=reference)
    print(out.table())
    emit_json(out.to_dict(), args.json)
    if args.plot:
        save_figure_atomic(out.plot(), args.plot, close=True, dpi=120)
        print(f"figure: {args.plot}", file=sys.stderr)
    if args.uff:
        from ..measured.uff import write_uff58
        from ..studies.comparison import model_predictions

        write_uff58(args.uff, model_predictions(crank, out, source=source, condensed=cc, band=measured.band))
        print(f"the model's predictions (UFF 58): {args.uff}", file=sys.stderr)
    return 0


def add_measured_options(p) -> None:
    """The options of measured files, shared by ``compare`` and ``run --measured``."""
    p.add_argument("--teeth", nargs="+", metavar="WHEEL",
                   help="the wheels of a tooth-edge CSV: one for every channel (60; 60-2, a wheel of 60 places with "
                        "2 teeth left out as the reference mark) or CHANNEL=WHEEL for each")
    p.add_argument("--calibration", nargs="+", metavar="CSV", default=[],
                   help="tooth-edge CSV of a calibration run (motored or coasting, whole orders weak): each channel's "
                        "tooth spacing errors, by channel name")
    p.add_argument("--twist", nargs=2, metavar=("A", "B"),
                   help="track the twist A - B of two channels too, compared with the model's twist between their "
                        "stations")
    p.add_argument("--channel-station", nargs="+", metavar="CHANNEL=STATION", default=[],
                   help="where each channel's wheel sits (default: a channel named as a station, pulley, flywheel, "
                        "J3 ..., is there; any other at --station)")
    p.add_argument("--time-unit", help="unit of tooth-edge times without a '# unit' line (s, ms, us, ns)")
    p.add_argument("--frf-unit", help="unit of UFF FRF records without a unit label (rad/N m; the records' data types "
                   "give SI where they say the quantity)")
    p.add_argument("--frf-type", choices=("receptance", "mobility", "accelerance"),
                   help="what the UFF FRFs' responses are (displacement, velocity, acceleration per load, in SI or "
                        "the label's scale), over what their records' data types say")
    p.add_argument("--order-definition", choices=("angle", "time"), default="angle",
                   help="a torsiograph's orders against the shaft's own angle (default: computed order tracking) or "
                        "against time (resampled at equal times, as a time-domain analyser reads them)")
    p.add_argument("--revolutions", type=integer(1), default=2,
                   help="revolutions per block of a torsiograph's order tracking (default %(default)s: half orders "
                        "fall on its bins)")
    p.add_argument("--track-orders", type=real(0.0), nargs="+", metavar="K",
                   help=f"orders of a torsiograph's recording to compare (default: the engine's lowest "
                        f"{TRACKED_MAJOR_ORDERS} major orders, an in-line four's 2, 4, 6, order 2 without an engine, "
                        f"and the record's {LARGEST_FOUND} largest other orders)")


def measured_of(args, paths, unit=None, order=None, crank=None) -> MeasuredData:
    """:func:`~fetorsion.measured.reading.read_measured` with the options of
    :func:`add_measured_options` (``crank``: the description compared with, whose engine gives
    the default tracked orders)."""
    stations = {}
    for item in args.channel_station:
        channel, eq, station = item.partition("=")
        if not (eq and channel.strip() and station.strip()):
            raise FetorsionError(f"--channel-station {item}: give CHANNEL=STATION")
        stations[channel.strip()] = station.strip()
    kinds = [measured_kind(m, args.teeth) for m in paths]
    if (args.calibration or args.twist or stations) and "edges" not in kinds:
        raise FetorsionError("--calibration, --twist and --channel-station go with a tooth-edge CSV (and --teeth)")
    options = MeasuredOptions(
        band=None if args.band is None else tuple(args.band), unit=unit, order=order, teeth=teeth_of(args.teeth),
        revolutions=args.revolutions, track_orders=tuple(args.track_orders or tracked_orders(crank)),
        largest_orders=0 if args.track_orders else LARGEST_FOUND,
        calibration=tuple(args.calibration), twist_of=None if args.twist is None else tuple(args.twist),
        stations=stations, time_unit=args.time_unit, frf_units=frf_units(args.frf_unit), frf_type=args.frf_type,
        definition=args.order_definition)
    try:
        return read_measured(paths, options)
    except UnstatedUnit as exc:
        raise FetorsionError(exc.stating("--frf-unit, e.g. 'rad/N m'")) from None


def add_parsers(sub) -> None:
    from ..description.defaults import DEFAULT_MESH_SIZE
    from ..studies.comparison import SOURCES
    from .options import MM, millimetres

    cp = sub.add_parser("compare", help="the model against measurement: modal-test FRFs (UFF 58), order cuts "
                        "(UFF 58 or CSV), torsiograph tooth-edge recordings (CSV)")
    cp.add_argument("file", help="crank description (.toml)")
    cp.add_argument("measured", nargs="+", help="measured files: .uff/.unv (dataset 58: FRFs, order functions), "
                    ".csv order cuts (rpm, amplitude[, phase]; '# unit', '# order' lines), or .csv tooth-edge "
                    "times (with --teeth)")
    cp.add_argument("--source", choices=SOURCES,
                    help="the model: condensed (default for a crank description: the crank the run's verdict judged, "
                         "free-free against a modal test, in its bearings against running measurements), lumped17 "
                         "(the fast chain; a chain file's model), fe (frequencies from the full free-free 3D FE, "
                         "running measurements on the condensed crank)")
    cp.add_argument("--mesh-size", type=millimetres(), default=DEFAULT_MESH_SIZE, metavar="MM",
                    help=f"FE mesh size of the condensed crank (default {DEFAULT_MESH_SIZE / MM:g}; the run's, so its "
                         "stored condensed crank is used)")
    add_band_option(cp, ", from their first frequency above 0 Hz")
    cp.add_argument("--station", help="where the order cuts were measured: pulley (default), flywheel, or a "
                    "station of the model by name or number (the condensed crank's front, J1, P1, ..., rear; the "
                    "chain's labels)")
    cp.add_argument("--unit", help="amplitude unit of CSV order cuts without a '# unit' line (deg, mrad, rad)")
    cp.add_argument("--order", type=real(0.0), help="engine order of CSV order cuts without a '# order' line")
    add_measured_options(cp)
    cp.add_argument("--plot", metavar="PATH", help="figure of every comparison (.png, .pdf, .svg)")
    cp.add_argument("--uff", metavar="PATH", help="write the model's predictions as UFF 58 (its order cuts at the "
                    "sensor's station; its receptances at the pulley and flywheel ends over the measured band), to "
                    "overlay in a test system's own tools")
    add_json_option(cp)
    cp.set_defaults(func=cmd_compare)
    add_calibrate_parser(sub)
