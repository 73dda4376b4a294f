"""Option types for the command line: each refuses a bad value by the option's name (argparse
prefixes the message with ``argument --OPTION:``) before any work starts."""

from __future__ import annotations

import argparse
import math


def real(low=None, high=None, *, low_open=True, high_open=True, unit=""):
    """An argparse type: a finite number inside the given bounds (open by default)."""
    unit = f" {unit}" if unit else ""

    def parse(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
        if not math.isfinite(value):
            raise argparse.ArgumentTypeError(f"{text!r}: must be a finite number")
        if low is not None and not (value > low if low_open else value >= low):
            raise argparse.ArgumentTypeError(f"{text}: must be {'>' if low_open else '>='} {low:g}{unit}")
        if high is not None and not (value < high if high_open else value <= high):
            raise argparse.ArgumentTypeError(f"{text}: must be {'<' if high_open else '<='} {high:g}{unit}")
        return value

    return parse


def integer(minimum: int, maximum: int | None = None):
    """An argparse type: a whole number in [minimum, maximum]."""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
        if value < minimum or (maximum is not None and value > maximum):
            raise argparse.ArgumentTypeError(f"{text}: must be from {minimum} to {maximum}" if maximum is not None
                                             else f"{text}: must be >= {minimum}")
        return value

    return parse


def millimetres(low=0.0):
    """An argparse type: a length given in mm on the command line, returned in m (the one
    place where the command line's millimetres become SI)."""
    check = real(low, unit="mm")

    def parse(text: str) -> float:
        return check(text) * MM

    return parse


MM = 1e-3  # m per mm


def read_compare_csv(path, name: str | None, unit: str | None):
    """The ``--compare`` curve: (rpm, value, name, unit), or one clear message naming the option.

    Rows ``rpm, value`` (rpm ascending, values finite and >= 0, read by
    :func:`~fetorsion.measured.ordercut.read_curve_csv`); ``# name = ...`` / ``# unit = ...``
    lines give the curve's name and unit unless the options do.
    """
    from pathlib import Path

    from ..errors import FetorsionError
    from ..measured.ordercut import read_curve_csv
    from ..response.forced import COMPARE_UNITS

    try:
        table, header = read_curve_csv(path, ("rpm", "value"))
    except FetorsionError as exc:
        raise FetorsionError(f"--compare {exc}") from None
    unit = unit or header.get("unit")
    if unit is None:
        raise FetorsionError(f"--compare-unit: give the unit of {path} ({', '.join(COMPARE_UNITS)}) "
                             "or a '# unit = ...' line in it")
    if unit not in COMPARE_UNITS:
        raise FetorsionError(f"--compare-unit: {path} says '# unit = {unit}'; use one of {', '.join(COMPARE_UNITS)}")
    return table[:, 0], table[:, 1], name or header.get("name") or Path(path).stem, unit


#: Parameters of the API whose command-line option is not ``--`` + the parameter's name.
OPTION_OF = {"step_rad": "--step-deg", "kind": "--type", "mu": "--inertia-ratio", "rate_rpm_per_s": "--rate", "damping_ratio": "--damping",
             "twist_of": "--twist", "stations": "--channel-station"}


def option_of(parameter: str) -> str:
    """The command-line option that sets the API's ``parameter`` (``mesh_size`` -> ``--mesh-size``)."""
    return OPTION_OF.get(parameter, "--" + parameter.replace("_", "-"))
