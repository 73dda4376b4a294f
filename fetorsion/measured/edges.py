"""A torsiograph's tooth-edge times read and checked: a CSV file of one column of timestamps per
channel (its ``#`` lines saying the unit, the channel and where its wheel sits), and any record
of edges checked for pulses, their order and the revolutions it holds, before the record is
processed (:mod:`.torsiograph`)."""

from __future__ import annotations

import re

from pathlib import Path
from typing import NoReturn

import numpy as np

from ..errors import FetorsionError
from .units import unit as unit_of
from .ordercut import checked_text

MAX_EDGE_FILE_BYTES = 1 << 30  # a tooth-edge record is large (tens of MB), but not this large
#: A timestamp column's header: a time and its unit (``t_s``, ``time_ms``, ``t [us]``, ``time (s)``).
TIME_COLUMN = re.compile(r"(?i)(?:t|time)\s*(?:_|\[|\()\s*(s|ms|us|µs)\s*[\])]?")


def check_edges(times, teeth: int, where: str = "edges", revolutions: int = 1) -> np.ndarray:
    """``times`` as a float array, or one message naming ``where`` if they are unusable.

    Parameters
    ----------
    times : array_like
        Edge timestamps [s].
    teeth : int
        Teeth (edges) per revolution.
    where : str
        The file and channel, for the message.
    revolutions : int
        The whole revolutions the caller needs.
    """
    if isinstance(teeth, bool) or not isinstance(teeth, (int, np.integer)) or teeth < 1:
        raise FetorsionError(f"{where}: teeth = {teeth!r}: give the teeth per revolution, a whole number >= 1")
    t = np.asarray(times, dtype=float)
    if t.ndim != 1 or t.size == 0:
        raise FetorsionError(f"{where}: has no pulses")
    if not np.all(np.isfinite(t)):
        raise FetorsionError(f"{where}: edge {int(np.flatnonzero(~np.isfinite(t))[0]) + 1} is not a finite time")
    back = np.flatnonzero(np.diff(t) <= 0)
    if back.size:
        i = int(back[0]) + 1
        raise FetorsionError(f"{where}: timestamps are not increasing: edge {i + 1} ({t[i]:.9g} s) "
                             f"is not after edge {i} ({t[i - 1]:.9g} s)")
    needed = revolutions * teeth + 1
    if t.size < needed:
        raise FetorsionError(f"{where}: has {t.size} pulses, too few for {revolutions} revolution(s) "
                             f"of {teeth} teeth ({needed} edges)")
    return t


def read_edges_csv(path, unit: str | None = None, teeth: dict[str, int] | None = None) -> dict[str, np.ndarray]:
    """Tooth-edge timestamps per channel from a CSV file, in seconds.

    Parameters
    ----------
    path : str or Path
        Text: ``#`` comment lines (``# unit = s``, ``ms`` or ``us`` says the timestamps' unit),
        a header row naming the channels (``pulley, flywheel``), then one row per edge; a
        channel with fewer edges leaves its cells empty at the end.
    unit : str, optional
        The timestamps' unit, if the file has no ``# unit = ...`` line.
    teeth : dict[str, int], optional
        Channel -> teeth per revolution: each such channel must hold one revolution at least.

    Returns
    -------
    dict
        Channel name -> increasing timestamps [s], each checked for pulses and their order.
    """
    return read_edges_and_header(path, unit, teeth)[0]


def read_edges_and_header(path, unit: str | None = None,
                          teeth: dict[str, int] | None = None) -> tuple[dict[str, np.ndarray], dict[str, str]]:
    """:func:`read_edges_csv`'s timestamps and the file's ``# key = value`` lines, from one reading.

    ``path``, ``unit`` and ``teeth`` are :func:`read_edges_csv`'s. Returns ``(edges, header)``:
    channel name -> increasing timestamps [s], and the file's ``# key = value`` lines (``unit``,
    ``channel``, ``station``) as strings.
    """
    path = Path(path)
    lines = checked_text(path, MAX_EDGE_FILE_BYTES).splitlines()
    header = header_lines(lines)
    rows = [(n + 1, line) for n, line in enumerate(lines) if line.strip() and not line.startswith("#")]
    if not rows:
        _fail(path, "has no header row naming the channels")
    columns = _column_names(path, rows[0])
    # a column headed by a time and its unit (t_s, time [ms]) is a timestamp column, not a channel's
    # name: the unit is read from it, and the channel is the file's '# channel = NAME' line
    column_units = {TIME_COLUMN.fullmatch(n).group(1) for n in columns if TIME_COLUMN.fullmatch(n)}
    names = columns
    if "channel" in header:
        if len(columns) != 1:
            _fail(path, f"'# channel = {header['channel']}' names one channel, but the file has {len(columns)} "
                        f"columns ({', '.join(columns)}): name each in the header row instead")
        names = [header["channel"]]
    factor = _time_factor(path, column_units, header.get("unit"), unit)
    table = _edge_table(path, rows[1:], len(names))
    return _channel_times(path, table, rows[1:], names, factor, teeth), header


def _fail(path: Path, rule: str) -> NoReturn:
    """Refuse the file ``path`` by the ``rule`` it breaks."""
    raise FetorsionError(f"{path}: {rule}")


def _column_names(path: Path, row: tuple[int, str]) -> list[str]:
    """The header row's column names: distinct, none a number."""
    number, line = row
    names = [c.strip() for c in line.split(",")]
    numeric = [n for n in names if _is_number(n)]
    if numeric:
        _fail(path, f"line {number}: the first row must name the channels (pulley, flywheel), not hold "
                    f"timestamps ({numeric[0]})")
    if not all(names) or len(set(names)) != len(names):
        _fail(path, f"line {number}: the header row needs distinct channel names, got {line!r}")
    return names


def _time_factor(path: Path, column_units: set[str], written: str | None, unit: str | None) -> float:
    """Seconds per unit of the timestamps: the columns' names, the ``# unit`` line or ``unit``,
    which must agree."""
    if len(column_units) > 1:
        _fail(path, f"its columns' names give different time units ({', '.join(sorted(column_units))})")
    if column_units:
        (named,) = column_units
        if written is not None and unit_of(written, f"{path}: '# unit'", ("time",)).factor != \
                unit_of(named, f"{path}: the column's unit", ("time",)).factor:
            _fail(path, f"says '# unit = {written}', but its column's name says {named}")
        written = named
    if written is None and unit is None:
        _fail(path, "the timestamps have no unit: give one (unit=...) or a '# unit = s' line")
    found = unit_of(written, f"{path}: '# unit'", ("time",)) if written is not None else None
    given = unit_of(unit, f"{path}: stated unit", ("time",)) if unit is not None else None
    if found and given and found.factor != given.factor:
        _fail(path, f"says '# unit = {written}', but {unit!r} was stated")
    return (found or given).factor


def _edge_table(path: Path, rows: list[tuple[int, str]], width: int) -> np.ndarray:
    """The data rows as numbers, (rows, width); an empty cell NaN."""
    table = np.full((len(rows), width), np.nan)
    for r, (number, line) in enumerate(rows):
        cells = [c.strip() for c in line.split(",")]
        if len(cells) > width:
            _fail(path, f"line {number}: {len(cells)} cells for {width} channels")
        for c, cell in enumerate(cells):
            if cell:
                try:
                    table[r, c] = float(cell)
                except ValueError:
                    _fail(path, f"line {number}: {cell!r} is not a number")
    return table


def _channel_times(path: Path, table: np.ndarray, rows: list[tuple[int, str]], names: list[str], factor: float,
                   teeth: dict[str, int] | None) -> dict[str, np.ndarray]:
    """Each channel's timestamps [s]: its cells up to its last edge, none empty, checked."""
    out = {}
    for c, name in enumerate(names):
        column = table[:, c]
        present = np.flatnonzero(~np.isnan(column))
        if present.size and present[-1] + 1 != present.size:
            gap = int(np.flatnonzero(np.isnan(column[: present[-1]]))[0])
            _fail(path, f"channel {name!r}: an empty cell before its last edge (line {rows[gap][0]})")
        z = (teeth or {}).get(name)
        out[name] = check_edges(column[: present.size] * factor, z or 1, f"{path}: channel {name!r}",
                                revolutions=1 if z else 0)
    return out


def header_lines(lines) -> dict[str, str]:
    """The ``# key = value`` lines of a tooth-edge file (``unit``, ``channel``, ``station``)."""
    header = {}
    for line in lines:
        key, eq, value = line.lstrip("#").partition("=")
        if line.startswith("#") and eq:
            header[key.strip()] = value.strip()
    return header


def _is_number(text: str) -> bool:
    """Whether ``text`` reads as a number."""
    try:
        float(text)
    except ValueError:
        return False
    return True
