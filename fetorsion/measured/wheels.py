"""Toothed wheels with a once-per-revolution reference gap (``60-2``), and a record's repair:
lost edges put back by interpolation, spurious edges taken out, the gap's places filled, each
repair listed (:class:`EdgeRepair`) so the torsiograph can warn of it."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import FetorsionError


#: An interval this many local pitches long or more is a gap (edges lost, or a reference mark)
GAP_PITCHES = 1.5
#: An interval this short (in local pitches) or shorter holds a spurious edge
SHORT_PITCHES = 0.6
#: Intervals each side whose median is the local pitch
PITCH_WINDOW = 4


@dataclass(frozen=True)
class Wheel:
    """A toothed wheel: ``positions`` equal tooth places a revolution, of which the last
    ``gap`` are left out as a once-per-revolution reference mark (``60-2``: 58 teeth, a gap of
    three pitches; ``gap`` 0, a plain wheel)."""

    positions: int
    gap: int = 0

    def __str__(self) -> str:
        return f"{self.positions}-{self.gap}" if self.gap else f"{self.positions}"


def wheel_of(spec: Wheel | int | str, where: str = "teeth") -> Wheel:
    """A :class:`Wheel` from teeth per revolution (``60``) or a reference-gap wheel (``"60-2"``),
    or one message naming ``where``."""
    if isinstance(spec, Wheel):
        return spec
    if isinstance(spec, (int, np.integer)) and not isinstance(spec, bool):
        if spec < 1:
            raise FetorsionError(f"{where} = {spec}: give the teeth per revolution, a whole number >= 1")
        return Wheel(int(spec))
    text = str(spec).strip()
    positions, dash, gap = text.partition("-")
    try:
        z, g = int(positions), int(gap) if dash else 0
    except ValueError:
        raise FetorsionError(f"{where} = {text!r}: give the teeth per revolution (60) or a wheel with a reference "
                             "gap (60-2: 60 places, 2 teeth left out)") from None
    if z < 1 or g < 0 or (g and (g >= z // 2 or z < 8)):
        raise FetorsionError(f"{where} = {text!r}: a wheel of {z} places cannot leave out {g} teeth as a reference "
                             "mark (fewer than half of them, on a wheel of 8 or more)")
    return Wheel(z, g)


@dataclass(frozen=True)
class EdgeRepair:
    """What :func:`repaired_edges` did to one record: every edge it put in (interpolated where
    a tooth was lost, or the reference gap's places) or took out (spurious), with its time."""

    #: (original edge index, its time s, edges lost after it) of each gap where teeth were lost
    inserted: tuple = ()
    #: (original edge index, time s) of each spurious edge taken out
    removed: tuple = ()
    reference_edges: int = 0  # places of the reference gaps filled in
    start: int = 0  # original edges before the first revolution start (a reference wheel), left out

    def lines(self, where: str) -> list[str]:
        out = [f"{where}: {n} edge(s) missing after edge {i + 1} ({t:.6f} s; a gap of {n + 1} pitches): "
               "interpolated" for i, t, n in self.inserted]
        out += [f"{where}: edge {i + 1} at {t:.6f} s is spurious (less than {SHORT_PITCHES:g} of a pitch from "
                "its neighbour); left out" for i, t in self.removed]
        return out


def _local_pitch(dt: np.ndarray) -> np.ndarray:
    """Each interval's expected length: the median of its neighbours' (itself left out)."""
    from numpy.lib.stride_tricks import sliding_window_view

    w = PITCH_WINDOW
    padded = np.pad(dt, w, mode="reflect")
    windows = sliding_window_view(padded, 2 * w + 1)
    return np.median(np.delete(windows, w, axis=1), axis=1)


def repaired_edges(times, wheel, where: str = "edges") -> tuple[np.ndarray, EdgeRepair]:
    """A record with every tooth place present once: lost edges interpolated, spurious edges
    taken out, a reference wheel's gap filled and its first revolution start made edge 0.

    An interval of n ≥ :data:`GAP_PITCHES` local pitches (the median of its neighbours) is
    n − 1 lost edges (a reference wheel's own gap, once a revolution, is expected); an edge
    less than :data:`SHORT_PITCHES` of a pitch from its neighbours is spurious. The times of the
    edges put in are a cubic spline of time against tooth place through the edges around
    (angle is smooth in time, and so time in angle), so a vibration is not cut at a lost tooth.

    Parameters
    ----------
    times : array_like
        Edge timestamps [s].
    wheel : Wheel, int or str
        The wheel (:func:`wheel_of`).
    where : str
        The file and channel, for messages.

    Returns
    -------
    times : ndarray
        One edge per tooth place, ``wheel.positions`` a revolution; a reference wheel's starting
        at the first tooth after its first gap.
    repair : EdgeRepair
    """
    from scipy.interpolate import CubicSpline

    wheel = wheel_of(wheel)
    t = np.asarray(times, float)
    if t.size < 4 * PITCH_WINDOW:
        return t, EdgeRepair()
    removed, original = [], np.arange(t.size)
    while True:  # spurious edges first, one at a time: each changes its neighbours' pitch
        dt = np.diff(t)
        pitch = _local_pitch(dt)
        short = np.flatnonzero(dt < SHORT_PITCHES * pitch)
        if not short.size:
            break
        if len(removed) > max(10, t.size // 100):
            raise FetorsionError(f"{where}: more than {len(removed)} spurious edges (intervals shorter than "
                                 f"{SHORT_PITCHES:g} of a pitch): check the pickup's signal and trigger level")
        i = int(short[0])  # between edges i and i + 1: the one whose removal leaves the truer pitch goes
        after = abs((dt[i] + dt[i + 1]) / pitch[i] - 1) if i + 1 < dt.size else np.inf
        before = abs((dt[i - 1] + dt[i]) / pitch[i] - 1) if i >= 1 else np.inf
        drop = i + 1 if after <= before else i
        removed.append((int(original[drop]), float(t[drop])))
        t, original = np.delete(t, drop), np.delete(original, drop)
    dt = np.diff(t)
    pitch = _local_pitch(dt)
    places = np.where(dt < GAP_PITCHES * pitch, 1, np.rint(dt / pitch)).astype(int)
    reference = np.zeros(places.size, bool)
    if wheel.gap:
        reference = places == wheel.gap + 1
        ref = np.flatnonzero(reference)
        if ref.size == 0:
            raise FetorsionError(f"{where}: no reference gap of {wheel.gap + 1} pitches found; the wheel was given as "
                                 f"{wheel} ({wheel.positions - wheel.gap} teeth and a gap)")
        for a, b in zip(ref[:-1], ref[1:]):
            if places[a:b].sum() != wheel.positions:
                raise FetorsionError(f"{where}: the reference gaps at {t[a]:.6f} s and {t[b]:.6f} s are "
                                     f"{places[a:b].sum()} tooth places apart, not {wheel.positions}")
    filled = np.flatnonzero(places > 1)
    if filled.size and places.size - filled[-1] <= PITCH_WINDOW:
        # a gap among the record's last few edges is filled from one side only (a spline's end
        # is its least accurate part): the record ends at the last edge before it
        places, reference, t = places[: filled[-1]], reference[: filled[-1]], t[: filled[-1] + 1]
        if wheel.gap and not reference.any():
            raise FetorsionError(f"{where}: its only reference gap is among its last {PITCH_WINDOW} edges; record "
                                 "at least one more revolution")
    index = np.concatenate([[0], np.cumsum(places)])  # every edge's tooth place from the first
    out = CubicSpline(index, t)(np.arange(index[-1] + 1))
    out[index] = t
    lost = np.flatnonzero((places > 1) & ~reference)
    inserted = [(int(original[k]), float(t[k]), int(places[k] - 1)) for k in lost]
    reference_edges = int((places[reference] - 1).sum())
    start = 0
    if wheel.gap:
        first = int(np.flatnonzero(reference)[0])
        start = int(index[first + 1])  # the first tooth after the gap: tooth 0
        out = out[start:]
        inserted = [x for x, k in zip(inserted, lost) if k > first]
        start = int(original[first + 1])
    return out, EdgeRepair(tuple(inserted), tuple(removed), int(reference_edges), start)


# ---------------------------------------------------------------------------
# Angle, speed, tooth errors
