"""Every measured file of a comparison read, its channels matched by name and its orders
tracked, before any model is solved: one :class:`~fetorsion.measured.dataset.MeasuredData`, or
one message naming the file or the option.

What each file is comes from its suffix (a UFF, or a CSV: an order cut, or tooth-edge times when
wheels are given); what each channel is comes from the file: a UFF record's data types, a
tooth-edge column's name or its ``# channel`` and ``# station`` lines. Calibration runs are
matched to records by channel name only, never by position: a calibration whose channel no
record has, or that two records share, is refused naming the files.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..errors import FetorsionError, ParameterError
from .dataset import MeasuredData
from .uff import MeasuredFunction

if TYPE_CHECKING:
    from ..description.chain_model import Chain, Network
    from ..description.model import Crank

#: Suffixes read as Universal File Format.
UFF_SUFFIXES = (".uff", ".unv", ".uf")
#: The major orders a torsiograph's recording is compared in when none are asked for.
TRACKED_MAJOR_ORDERS = 3
#: The order a recording is compared in when the description has no engine.
FALLBACK_ORDER = 2.0
#: A recording compared in its default orders is compared too in its this many largest orders
#: (mean amplitude over its blocks) that are not among them: what the record says most of
LARGEST_FOUND = 3


@dataclass(frozen=True)
class MeasuredOptions:
    """How to read measured files (the command line's options of the same names).

    Attributes
    ----------
    band : (float, float), optional
        The band to fit the FRFs' modes in, Hz; default the FRFs' own span.
    unit, order : optional
        An order-cut CSV's amplitude unit and order, where its ``#`` lines do not say them.
    teeth : str or dict, optional
        Tooth-edge files' wheel: one for every channel (``60``, ``60-2``) or channel -> wheel.
    revolutions : int
        Revolutions per block of order tracking.
    track_orders : tuple of float
        Orders of a torsiograph's recording to compare.
    largest_orders : int
        How many of each recording's largest orders (mean amplitude over its blocks) to compare
        besides ``track_orders`` (the default orders; 0 where the orders were asked for).
    calibration : tuple of str
        Tooth-edge files of calibration runs, matched to records by channel name.
    twist_of : (str, str), optional
        Two channels whose twist is tracked too.
    stations : dict[str, str]
        Channel -> where its wheel sits (over a file's ``# station`` line).
    time_unit : str, optional
        The unit of tooth-edge times in files that do not say it.
    frf_units : dict[str, str]
        Units of unlabelled, untyped FRF records, as :func:`~fetorsion.measured.uff.read_uff58`'s
        ``units``.
    frf_type : {'receptance', 'mobility', 'accelerance'}, optional
        What the UFF FRFs' responses are, over their records' data types.
    definition : {'angle', 'time'}
        A torsiograph's orders against the shaft's angle or against time.
    """

    band: tuple[float, float] | None = None
    unit: str | None = None
    order: float | None = None
    teeth: str | dict[str, str] | None = None
    revolutions: int = 2
    track_orders: tuple[float, ...] = (FALLBACK_ORDER,)
    largest_orders: int = 0
    calibration: tuple[str, ...] = ()
    twist_of: tuple[str, str] | None = None
    stations: dict[str, str] = field(default_factory=dict)
    time_unit: str | None = None
    frf_units: dict[str, str] = field(default_factory=dict)
    frf_type: str | None = None
    definition: str = "angle"


def measured_kind(path: str, teeth: str | list[str] | dict[str, str] | None) -> str:
    """What a measured file is, by its suffix (and ``teeth`` for edge recordings): ``'uff'``,
    ``'edges'`` or ``'order-cut'``, checked before any work."""
    p = Path(path)
    if not p.is_file():
        raise FetorsionError(f"compare: {path}: no such file")
    suffix = p.suffix.lower()
    if suffix in UFF_SUFFIXES:
        return "uff"
    if suffix == ".csv":
        return "edges" if teeth is not None else "order-cut"
    raise FetorsionError(f"compare: {path}: give a UFF file ({', '.join(UFF_SUFFIXES)}) or a CSV "
                         "(an order cut; tooth-edge times when their wheels' teeth are given)")


def tracked_orders(crank: Crank | Chain | Network | None) -> tuple[float, ...]:
    """The orders a torsiograph's recording is compared in by default: the engine's lowest
    :data:`TRACKED_MAJOR_ORDERS` major orders (:func:`fetorsion.excitation.campbell.major_orders`:
    an in-line four's 2, 4, 6, an in-line six's 3, 6, 9, a V8's 4, 8, 12), where the torque of
    every cylinder adds and the engine's response is largest; order 2 where there is no engine."""
    engine = getattr(crank, "engine", None)
    if engine is None:
        return (FALLBACK_ORDER,)
    from ..excitation.campbell import major_orders

    try:
        found = major_orders(engine)
    except (FetorsionError, AttributeError, ValueError):
        return (FALLBACK_ORDER,)
    return tuple(float(k) for k in found[:TRACKED_MAJOR_ORDERS]) or (FALLBACK_ORDER,)


def channel_station(channel: str, stations: dict | None) -> tuple[str, bool]:
    """(the station a channel was measured at, whether the user or the file said so): as
    ``stations`` says, else the channel's own name, which the comparison keeps where it is one
    of the model's stations (a channel called ``pulley``, ``flywheel``, ``J3`` ...)."""
    if stations and channel in stations:
        return stations[channel], True
    return channel, False


def file_stations(path, channels, header: dict[str, str]) -> dict[str, str]:
    """A tooth-edge file's ``# station = NAME`` line (``header``: its ``# key = value`` lines, as
    read with its times): where its one channel's wheel sits (a file of several channels says
    each one's station by option instead, refused naming the line)."""
    if "station" not in header:
        return {}
    if len(channels) != 1:
        raise ParameterError("stations", f"CHANNEL=STATION: {path}'s '# station = {header['station']}' line names one "
                             f"station, but the file has channels {', '.join(channels)}: give each one's station")
    (channel,) = channels
    return {channel: header["station"]}


def check_calibration_channels(records: dict, calibrated_from: dict) -> None:
    """Each calibration run's channel is a channel of exactly one tooth-edge record (``records``:
    path -> channels): one that matches none, or that two records would share, is refused naming
    the files."""
    holders: dict[str, list] = {}
    for path, edges in records.items():
        for channel in edges:
            holders.setdefault(channel, []).append(path)
    for channel, cal in calibrated_from.items():
        found = holders.get(channel, [])
        if not found:
            raise ParameterError("calibration", f"{Path(cal).name}: its channel {channel!r} is in no measured record "
                                 f"(they have {', '.join(repr(h) for h in holders) or 'none'})")
        if len(found) > 1:
            raise ParameterError("calibration", f"{Path(cal).name}: channel {channel!r} is in both "
                                 f"{Path(found[0]).name} and {Path(found[1]).name}: which wheel is it? Name each "
                                 "file's wheel with a '# channel = NAME' line")


def frf_band(frfs) -> tuple[float, float]:
    """The band the FRFs span (the first record's frequencies; the fit checks the rest share
    them), from its first frequency above 0 Hz (a free body has no static receptance)."""
    f = np.asarray(frfs[0].abscissa, float)
    positive = f[f > 0]
    if positive.size < 3:
        raise ParameterError("band", "(none given): the measured FRFs have fewer than 3 frequencies above 0 Hz")
    return float(positive[0]), float(positive[-1])


def _calibrations(options: MeasuredOptions) -> tuple[dict, dict]:
    """Channel -> tooth-edge times of the calibration runs, and channel -> the file each came from."""
    from .edges import read_edges_csv

    calibrated, calibrated_from = {}, {}
    for c in options.calibration:
        for channel, times in read_edges_csv(c, options.time_unit).items():
            if channel in calibrated:
                raise ParameterError("calibration", f"{Path(calibrated_from[channel]).name} and {Path(c).name} both "
                                     f"calibrate channel {channel!r}; name each file's wheel with a "
                                     "'# channel = NAME' line (pulley, flywheel ...)")
            calibrated[channel], calibrated_from[channel] = times, c
    return calibrated, calibrated_from


def largest_orders(track, known, count: int) -> tuple[float, ...]:
    """The ``count`` orders of ``track`` (an :class:`~fetorsion.measured.torsiograph.OrderTrack`) with
    the largest mean amplitude over its blocks, ``known`` orders left out, largest first."""
    if count <= 0:
        return ()
    mean = np.abs(np.asarray(track.amplitudes)).mean(axis=0)
    fresh = [j for j in np.argsort(mean)[::-1]
             if track.orders[j] > 0 and not np.any(np.isclose(track.orders[j], known, rtol=0, atol=1e-9))]
    return tuple(float(track.orders[j]) for j in fresh[:count])


def _tracked(path, edges: dict, header: dict, calibrated: dict, options: MeasuredOptions):
    """A tooth-edge record's order cuts (each with where it was measured), its order maps and
    its reading's notes (``header``: the file's ``# key = value`` lines)."""
    from .torsiograph import TWIST, run_torsiograph, track_order_cut

    teeth = options.teeth
    wheels = teeth if isinstance(teeth, dict) else {c: teeth for c in set(edges) | set(calibrated)}
    lacking = [c for c in edges if c not in wheels]
    if lacking:
        raise ParameterError("teeth", f"of {Path(path).name}'s channel {lacking[0]!r}: not given "
                             f"(give {lacking[0]}=TEETH)")
    pair = None
    if options.twist_of is not None:
        absent = [c for c in options.twist_of if c not in edges]
        if absent:
            raise ParameterError("twist_of", f"{' '.join(options.twist_of)}: {Path(path).name} has no channel "
                                 f"{absent[0]!r} (it has {', '.join(edges)})")
        pair = tuple(options.twist_of)
    for c in options.stations:
        if c not in edges and c != TWIST:
            raise ParameterError("stations", f"{c}=...: {Path(path).name} has no channel {c!r} "
                                 f"(it has {', '.join(edges)})")
    stations = {**file_stations(path, list(edges), header), **options.stations}
    res = run_torsiograph(edges, wheels, options.revolutions, {c: t for c, t in calibrated.items() if c in edges},
                          pair, options.definition)
    cuts, where, tracks = [], {}, []
    for channel, track in res.tracks.items():
        name = f"{Path(path).name}: {channel}"
        if channel == TWIST:
            ends = (channel_station(pair[0], stations), channel_station(pair[1], stations))
            station = (tuple(x[0] for x in ends), any(x[1] for x in ends))
        else:
            station = channel_station(channel, stations)
        for k in options.track_orders + largest_orders(track, options.track_orders, options.largest_orders):
            cut = track_order_cut(track, k, name)
            cuts.append(cut)
            where[cut.label] = station
        tracks.append((name, track))
    return cuts, where, tracks, [f"{Path(path).name}: {line}" for line in res.warnings()]


def read_measured(paths: Sequence[str], options: MeasuredOptions = MeasuredOptions()) -> MeasuredData:
    """Every measured file read and checked, before any model is solved.

    Parameters
    ----------
    paths : sequence of str
        UFF files (FRFs, order functions), order-cut CSVs, or tooth-edge CSVs (with
        ``options.teeth``).
    options : MeasuredOptions
        How to read them.

    Returns
    -------
    MeasuredData
        With the notes of the reading (labels that contradict their data type, edges repaired).
    """
    from .edges import read_edges_and_header
    from .ordercut import read_order_cut_csv
    from .uff import read_uff58

    kinds = [measured_kind(m, options.teeth) for m in paths]
    for c in options.calibration:
        if measured_kind(c, options.teeth) != "edges":
            raise ParameterError("calibration", f"{c}: a calibration run is a tooth-edge CSV (its wheels' teeth given)")
    if (options.calibration or options.twist_of or options.stations) and "edges" not in kinds:
        raise FetorsionError("calibration runs, a twist and channel stations go with a tooth-edge CSV (and its "
                             "wheels' teeth)")
    band = options.band
    if band is not None and not 0 <= band[0] < band[1]:
        raise ParameterError("band", f"{band[0]:g} {band[1]:g}: give 0 <= LOW < HIGH (Hz)")
    calibrated, calibrated_from = _calibrations(options)
    # each tooth-edge file read once: its times, and its header lines for its station
    read = {path: read_edges_and_header(path, options.time_unit) for path, kind in zip(paths, kinds) if kind == "edges"}
    records = {path: edges for path, (edges, _) in read.items()}
    check_calibration_channels(records, calibrated_from)
    frfs, cuts, tracks, where, notes = [], [], [], {}, []
    for path, kind in zip(paths, kinds):
        if kind == "uff":
            functions = read_uff58(path, options.frf_units, options.frf_type)
            frfs += [f for f in functions if f.kind == "frf"]
            cuts += [f for f in functions if f.kind == "order function" and f.abscissa_quantity == "speed"]
            notes += [n for f in functions for n in f.notes]
        elif kind == "order-cut":
            cuts.append(read_order_cut_csv(path, options.unit, options.order))
        else:
            found, stations, maps, said = _tracked(path, *read[path], calibrated, options)
            cuts += found
            where.update(stations)
            tracks += maps
            notes += said
    if not (frfs or cuts):
        raise FetorsionError("compare: the measured files hold no FRF and no order cut against speed")
    if frfs and band is None:
        band = frf_band(frfs)
    return MeasuredData(tuple(frfs), tuple(cuts), tuple(tracks), None if band is None else tuple(band), where,
                        tuple(notes))
