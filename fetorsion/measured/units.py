"""The units that test systems write beside measured data, and their SI factors.

A unit is looked up by its text, as a test system writes it (``"m/s^2"``, ``"N m"``, ``"deg"``);
the result is the factor that takes a value to SI, the SI unit's name and the physical quantity,
so that a file's unit can be checked against what the file says the data is (a UFF record's
specific data type, an order cut's column). Abscissae keep the units the rest of fetorsion uses:
frequencies in Hz, speeds in rpm, orders as plain numbers.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import FetorsionError


@dataclass(frozen=True)
class Unit:
    """A unit: ``value_si = value * factor``, in the SI unit ``si`` of ``quantity``."""

    factor: float
    si: str
    quantity: str


def _table() -> dict[str, Unit]:
    entries = {
        # abscissae
        "frequency": ("Hz", {"Hz": 1.0, "kHz": 1e3, "1/s": 1.0}),
        "speed": ("rpm", {"rpm": 1.0, "1/min": 1.0, "r/min": 1.0, "rev/min": 1.0}),
        "order": ("-", {"order": 1.0, "-": 1.0, "1": 1.0}),
        "time": ("s", {"s": 1.0, "ms": 1e-3, "us": 1e-6, "µs": 1e-6, "ns": 1e-9}),
        # ordinates: torsional quantities first, then the translational ones of accelerometers
        "angle": ("rad", {"rad": 1.0, "mrad": 1e-3, "urad": 1e-6, "µrad": 1e-6, "deg": math.pi / 180.0,
                          "°": math.pi / 180.0}),
        "angular velocity": ("rad/s", {"rad/s": 1.0, "deg/s": math.pi / 180.0}),
        "angular acceleration": ("rad/s^2", {"rad/s^2": 1.0, "deg/s^2": math.pi / 180.0, "krad/s^2": 1e3}),
        "torque": ("N m", {"N m": 1.0, "Nm": 1.0, "kN m": 1e3, "kNm": 1e3}),
        "force": ("N", {"N": 1.0, "kN": 1e3}),
        "length": ("m", {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6}),
        "velocity": ("m/s", {"m/s": 1.0, "mm/s": 1e-3}),
        "acceleration": ("m/s^2", {"m/s^2": 1.0, "mm/s^2": 1e-3, "g": 9.80665}),
        "pressure": ("Pa", {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "bar": 1e5}),
    }
    table = {}
    for quantity, (si, units) in entries.items():
        for name, factor in units.items():
            table[name] = Unit(factor, si, quantity)
    return table


UNITS = _table()
#: each quantity's SI unit (in the table's spelling)
SI_UNITS = {u.quantity: u.si for u in UNITS.values()}
#: what a measured amplitude may be (the rest are the abscissae's quantities)
RESPONSE_QUANTITIES = tuple(sorted({u.quantity for u in UNITS.values()} - {"frequency", "speed", "order", "time"}))


def normalise(text: str) -> str:
    """A unit's text in the table's spelling: ``N·m``/``N*m``/``N-m``/``(N m)`` -> ``N m``,
    ``s²`` -> ``s^2``, ``Nm`` kept (it is in the table)."""
    text = str(text).strip()
    if text.startswith("(") and text.endswith(")"):
        text = text[1:-1]
    text = " ".join(text.replace("·", " ").replace("*", " ").replace("²", "^2").split())
    text = text.replace("N-m", "N m").replace("N.m", "N m")
    return text.replace("s2", "s^2") if text.endswith("/s2") else text


def unit(text: str, where: str, quantities: tuple[str, ...] | None = None) -> Unit:
    """The :class:`Unit` that ``text`` names, or one message naming ``where`` it was found.

    Parameters
    ----------
    text : str
        A unit as written in a file or by a caller (``"m/s^2"``, ``"deg"``).
    where : str
        What the message names: the file and field the unit came from.
    quantities : tuple of str, optional
        The physical quantities allowed there (``("frequency",)``); any quantity if None.
    """
    found = UNITS.get(normalise(text))
    if found is None:
        known = ", ".join(sorted(UNITS))
        raise FetorsionError(f"{where}: unit {text!r} is not known; use one of {known}")
    if quantities is not None and found.quantity not in quantities:
        raise FetorsionError(f"{where}: unit {text!r} is a unit of {found.quantity}, "
                             f"not of {' or '.join(quantities)}")
    return found
