"""What the description's types work out from their fields (:mod:`.model` keeps the types, this
module their arithmetic): the crank angles at which an engine fires, a rubber damper's frequency
table at a temperature, the piecewise-linear curve of a network's nonlinear element, and the
reference values of ``[meta]``."""

from __future__ import annotations

import math


def firing_angles_from_lags(tdc_lags: tuple[float, ...], firing_order: tuple[int, ...],
                            strokes_per_cycle: int) -> tuple[float, ...]:
    """Crank angle at which each cylinder fires, cylinder 1 at 0 (rad): the firing order picks,
    cylinder by cylinder, the first TDC after the previous firing.

    Parameters
    ----------
    tdc_lags : tuple of float
        How far each cylinder's TDC lags cylinder 1's throw's first cylinder, rad (one per cylinder).
    firing_order : tuple of int
        The 1-based cylinder numbers in firing order.
    strokes_per_cycle : int
        2 or 4: each cylinder has ``strokes_per_cycle / 2`` TDCs per cycle.

    Raises
    ------
    ValueError
        If some cylinder has no TDC left in the cycle after the one before it fired.
    """
    period = math.pi * strokes_per_cycle
    turn = 2 * math.pi
    tdc = [(a - tdc_lags[0]) % turn for a in tdc_lags]
    out = [0.0] * len(tdc_lags)
    order = list(firing_order)
    start = order.index(1)
    previous = 0.0
    for c in order[start + 1:] + order[:start]:
        t = tdc[c - 1]
        if t <= previous + 1e-9:
            t += turn * math.ceil((previous + 1e-9 - t) / turn)
        if t >= period:
            raise ValueError(f"cylinder {c} has no TDC left in the {math.degrees(period):.0f}° cycle after "
                             f"the cylinder before it fired at {math.degrees(previous):.1f}°")
        out[c - 1] = previous = t
    return tuple(out)


def temperature_groups(rows: tuple[tuple[float, float, float, float], ...]) -> dict[float, list[tuple[float, float, float]]]:
    """A dynamic table's rows (°C, Hz, N·m/rad, loss factor) grouped by temperature: temperature ->
    rows (frequency Hz, stiffness N·m/rad, loss factor), in the rows' order."""
    groups: dict = {}
    for T, f, k, e in rows:
        groups.setdefault(T, []).append((f, k, e))
    return groups


def table_at_temperature(groups: dict, temperature: float) -> tuple[tuple[float, float, float], ...]:
    """A frequency table (f, k, η) at ``temperature`` from tables at several temperatures
    (``groups``: temperature -> rows [f, k, η], f ascending): linear in temperature between the two
    nearest, each read linearly in frequency on the union of their frequencies; the end
    temperature's table outside the range (no extrapolation of a measured property)."""
    import numpy as np

    temps = sorted(groups)
    lo = max([T for T in temps if T <= temperature], default=temps[0])
    hi = min([T for T in temps if T >= temperature], default=temps[-1])
    w = 0.0 if hi == lo else (temperature - lo) / (hi - lo)
    f = np.union1d([r[0] for r in groups[lo]], [r[0] for r in groups[hi]])

    def at(T, col):
        g = groups[T]
        return np.interp(f, [r[0] for r in g], [r[col] for r in g])

    k = (1 - w) * at(lo, 1) + w * at(hi, 1)
    eta = (1 - w) * at(lo, 2) + w * at(hi, 2)
    return tuple((float(a), float(b), float(c)) for a, b, c in zip(f, k, eta))


def piecewise_torque(x, drive: tuple[tuple[float, ...], tuple[float, ...]],
                     coast: tuple[tuple[float, ...], tuple[float, ...]]):
    """The elastic torque of a piecewise-linear spring at twist ``x`` (rad, array), N·m: continuous,
    of the twist's sign.

    Parameters
    ----------
    x : array_like
        Twist, rad.
    drive, coast : (tuple of float, tuple of float)
        (stiffnesses N·m/rad, angles rad at which each stage after the first begins) of the drive
        side (x ≥ 0) and of the coast side (x < 0, read on |x|).
    """
    import numpy as np

    x = np.asarray(x, dtype=float)
    a = np.abs(x)
    torque = np.zeros_like(a)
    for is_coast, (stiffnesses, angles) in ((False, drive), (True, coast)):
        edges = (0.0, *angles)
        side = np.zeros_like(a)
        for s, k in enumerate(stiffnesses):
            hi = edges[s + 1] if s + 1 < len(edges) else np.inf
            side += k * np.clip(a - edges[s], 0.0, hi - edges[s])
        torque = np.where((x < 0) == is_coast, side, torque)
    return np.sign(x) * torque


def twist_at_torque(stiffnesses: tuple[float, ...], angles: tuple[float, ...], torque: float) -> float:
    """The twist (rad, ≥ 0) at which a piecewise-linear spring carries ``torque`` (N·m, ≥ 0): unique,
    the curve being increasing.

    Parameters
    ----------
    stiffnesses : tuple of float
        The stages' stiffnesses, N·m/rad.
    angles : tuple of float
        Where each stage after the first begins, rad.
    torque : float
        The torque it carries, N·m.
    """
    edges = (0.0, *angles)
    x, carried = 0.0, 0.0
    for s, k in enumerate(stiffnesses):
        width = edges[s + 1] - edges[s] if s + 1 < len(edges) else math.inf
        if carried + k * width >= torque:
            x += (torque - carried) / k
            break
        x, carried = x + width, carried + k * width
    return x


def reference_value(notes: dict, key: str) -> float | None:
    """A reference frequency of ``[meta]`` as a float, None where absent."""
    value = notes.get(key)
    return None if value is None else float(value)


def piecewise_linear(x: float, rows: list[tuple[float, float]]) -> float:
    """y at ``x`` on the polyline of ``rows`` ((x, y), x ascending): linear between rows, held outside."""
    if x <= rows[0][0]:
        return float(rows[0][1])
    for (x0, y0), (x1, y1) in zip(rows, rows[1:]):
        if x <= x1:
            return float(y0 + (y1 - y0) * (x - x0) / (x1 - x0))
    return float(rows[-1][1])
