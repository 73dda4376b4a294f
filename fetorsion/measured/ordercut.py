"""Curves against engine speed from CSV: a measured order cut (amplitude, and phase if the test
system gave one, of one order against rpm) and the published or measured curve that the command
line sets beside a response.

The file is text: ``#`` lines are comments, and ``# key = value`` lines in them say what the
numbers are (``# unit = deg``, ``# order = 2.5``, ``# name = pulley``); the rows are numbers
separated by commas, rpm ascending first.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..errors import FetorsionError
from .units import RESPONSE_QUANTITIES, unit as unit_of
from .uff import MeasuredFunction

MIN_ROWS = 3  # a curve of fewer points has no shape to compare


def checked_text(path, limit: int) -> str:
    """The UTF-8 text of a measured file, or one message naming it: not a file, over ``limit``
    bytes, or not text."""
    path = Path(path)
    if not path.is_file():
        raise FetorsionError(f"{path}: is not a file")
    if path.stat().st_size > limit:
        raise FetorsionError(f"{path}: is larger than {limit >> 20} MiB")
    try:
        return path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise FetorsionError(f"{path}: could not be read as UTF-8 text ({exc})") from None


def read_curve_csv(path: str | Path, columns: tuple[str, ...] = ("rpm", "value"), optional: tuple[str, ...] = ()):
    """The rows and header of a curve against rpm, or one message naming the file.

    Parameters
    ----------
    path : str or Path
        The CSV file.
    columns : tuple of str
        The names of the columns every row has, rpm first; the second is an amplitude, >= 0.
    optional : tuple of str
        Names of further columns that all rows have or none has.

    Returns
    -------
    table : ndarray, shape (rows, columns)
        rpm > 0 ascending [rpm], then the values as written.
    header : dict
        ``key -> value`` of the ``# key = value`` lines.
    """
    from ..description.reader import MAX_DESCRIPTION_BYTES

    path = Path(path)
    rows = "rows of '" + ", ".join(columns) + "".join(f"[, {c}]" for c in optional) + "'"

    def fail(rule):
        raise FetorsionError(f"{path}: {rule}")

    text = checked_text(path, MAX_DESCRIPTION_BYTES)
    header = {}
    for line in text.splitlines():
        key, eq, value = line.lstrip("#").partition("=")
        if line.startswith("#") and eq:
            header[key.strip()] = value.strip()
    try:
        table = np.loadtxt(text.splitlines(), delimiter=",", comments="#", ndmin=2)
    except ValueError as exc:
        fail(f"could not be read as {rows} ({exc})")
    widths = [len(columns) + k for k in range(len(optional) + 1)]
    if table.ndim != 2 or table.shape[1] not in widths or len(table) < MIN_ROWS:
        fail(f"needs >= {MIN_ROWS} {rows}")
    if not np.all(np.isfinite(table)):
        fail(f"row {int(np.flatnonzero(~np.isfinite(table).all(axis=1))[0]) + 1} holds a non-finite number")
    if np.any(np.diff(table[:, 0]) <= 0) or np.any(table[:, 0] <= 0) or np.any(table[:, 1] < 0):
        fail(f"needs {rows} with rpm > 0 ascending and values >= 0")
    return table, header


def read_order_cut_csv(path, unit: str | None = None, order: float | None = None,
                       response: tuple[int, int] = (0, 0)) -> MeasuredFunction:
    """A measured order cut: rows ``rpm, amplitude[, phase]``, the amplitude's unit stated.

    Parameters
    ----------
    path : str or Path
        The CSV file: rpm [rpm] ascending, amplitude (zero to peak) >= 0, phase [deg] optional.
    unit : str, optional
        The amplitude's unit (``'deg'``, ``'mrad'``, ``'rad/s^2'``, ``'N m'``, ...), if the file
        has no ``# unit = ...`` line; a file with neither is refused, one with both must agree.
    order : float, optional
        The engine order, if the file has no ``# order = ...`` line.
    response : tuple of int
        (node, direction) the cut was measured at, for comparison with a model's station.

    Returns
    -------
    MeasuredFunction
        Kind ``'order function'`` against speed [rpm], in SI; complex ``A e^{i phase}`` when the
        file gives a phase, else real.
    """
    table, header = read_curve_csv(path, ("rpm", "amplitude"), ("phase_deg",))
    stated, written = unit, header.get("unit")
    if stated is None and written is None:
        raise FetorsionError(f"{path}: the amplitude has no unit: give one (unit=...) or a '# unit = ...' line")
    found = unit_of(written, f"{path}: '# unit'", RESPONSE_QUANTITIES) if written is not None else None
    given = unit_of(stated, f"{path}: stated unit", RESPONSE_QUANTITIES) if stated is not None else None
    if found and given and (found.quantity, found.factor) != (given.quantity, given.factor):
        raise FetorsionError(f"{path}: says '# unit = {written}', but {stated!r} was stated")
    u = found or given
    if order is None and "order" in header:
        try:
            order = float(header["order"])
        except ValueError:
            raise FetorsionError(f"{path}: '# order = {header['order']}' is not a number") from None
    amplitude = table[:, 1] * u.factor
    ordinate = amplitude * np.exp(1j * np.radians(table[:, 2])) if table.shape[1] == 3 else amplitude
    return MeasuredFunction(kind="order function", abscissa=table[:, 0], abscissa_quantity="speed",
                            ordinate=ordinate, unit=u.si, response=tuple(response),
                            label=header.get("name", Path(path).stem), order=order)
