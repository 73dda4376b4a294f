"""A run-up's record: the envelope of its working cycles, its signals thinned for ``results.json``,
and a :class:`~.transient.TransientResult` read back from its ``to_dict()``."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..measured.torsiograph import OrderTrack, order_track
from ..results import from_fields
from .nonlinear import ElementWork

#: An :class:`~.transient.OrderCut`'s fields stored under another key by its ``to_dict()``.
ORDER_CUT_KEYS = {"passage": "passage_alpha_over_gamma2", "steady_deg": "steady_peak_deg",
                  "steady_rpm": "steady_peak_rpm", "runup_deg": "runup_peak_deg", "runup_rpm": "runup_peak_rpm"}


@dataclass(frozen=True)
class StoredRecord:
    """A run's time signals as ``results.json`` keeps them: the run's sample count, its last time
    (s) and the thinned ``signals`` (:func:`thinned_signals`)."""

    samples: int
    end_s: float
    signals: dict[str, list]


def thinned_signals(result, every: int | None = None) -> dict:
    """``result``'s (a :class:`~.transient.TransientResult`) last time ``end_s`` and its
    ``signals`` thinned to one sample per block of ``every`` (see its ``to_dict``)."""
    every = every or max(1, result.time_s.size // 20000)
    T = result.section_torque_nm
    n = T.shape[1]
    starts = np.arange(0, n, every)
    worst = np.abs(T).max(axis=0) if T.size else np.zeros(n)
    keep = np.array([a + int(np.argmax(worst[a:a + every])) for a in starts], dtype=int) if n else starts
    lo = np.minimum.reduceat(T, starts, axis=1) if T.size else T
    hi = np.maximum.reduceat(T, starts, axis=1) if T.size else T
    return {"end_s": float(result.time_s[-1]),
            "signals": {"every": every, "time_s": result.time_s[keep].tolist(), "rpm": result.rpm[keep].tolist(),
                        "section_torque_nm": T[:, keep].tolist(), "section_torque_min_nm": lo.tolist(),
                        "section_torque_max_nm": hi.tolist()}}


def transient_from_dict(cls: type, d: dict):
    """A :class:`~.transient.TransientResult` (``cls``) back from its ``to_dict()``: the envelope,
    the order track and the elements as they were; the time signals the thinned record stored
    (``stored``: the run's sample count and last time with them), the mean motion and the
    coordinates' angles not kept (empty)."""
    sig = d["signals"]
    stored = StoredRecord(d["samples"], d["end_s"], sig)
    torque = np.asarray(sig["section_torque_nm"], dtype=float).reshape(len(d["sections"]), -1)
    return from_fields(cls, d, {"section_labels": "sections", "block_peak_nm": "block_peak_torque_nm"},
                       time_s=np.asarray(sig["time_s"], dtype=float), rpm=np.asarray(sig["rpm"], dtype=float),
                       crank_angle_rad=np.empty(0), section_torque_nm=torque, angle_rad=np.empty((0, 0)),
                       track=OrderTrack.from_dict(d["order_track"]), track_station=d["order_track"]["station"],
                       elements=[from_fields(ElementWork, w) for w in d["elements"]], stored=stored)


def block_envelope(t, n_t, phi, torque, period: float, settle: float):
    """(mean speed rpm, largest |torque| of each section N·m) of each whole working cycle of the
    crank's mean motion ``phi``: the envelope of the run."""
    block = np.floor(phi / period).astype(int)
    # the last, unfinished cycle left out, and in a steady run the cycles before it settled
    full = (block < max(block[-1], 1)) & (t >= settle)
    nb = int(block[full].max()) + 1 if full.any() else 0
    peak = np.zeros((nb, torque.shape[0]))
    for s in range(torque.shape[0]):
        np.maximum.at(peak[:, s], block[full], np.abs(torque[s, full]))
    count = np.bincount(block[full], None, nb)
    block_rpm = np.bincount(block[full], n_t[full], nb) / np.maximum(count, 1)
    return block_rpm[count > 0], peak[count > 0]


def edge_times(t, angle, teeth: int) -> np.ndarray:
    """The times a wheel of ``teeth`` teeth turning through ``angle`` (rad, increasing, sampled
    at ``t``) passes each tooth edge, the first at the record's first angle: linear between
    samples (the angle is smooth on the scale of a step)."""
    pitch = 2 * np.pi / teeth
    edges = angle[0] + pitch * np.arange(int((angle[-1] - angle[0]) / pitch) + 1)
    return np.interp(edges, angle, t)


def station_order_track(t: np.ndarray, angle: np.ndarray, settle: float, run: tuple[float, float] | None,
                        rate_rpm_per_s: float | None, factor: float, period: float, teeth: int,
                        name: str) -> OrderTrack:
    """The order track of a station's simulated ``angle`` (rad at ``t``) from its wheel's tooth edges,
    a held start left out; ``factor``: the station's speed over the crank's."""
    revs = int(round(period / (2 * np.pi)))
    k0 = int(np.searchsorted(t, settle)) if run is not None else 0  # a held start is not tracked
    # the schedule's acceleration is known: the bow of the mean rotation comes off exactly, a
    # one-block record included
    alpha = None if run is None else factor * math.copysign(rate_rpm_per_s, run[1] - run[0]) * math.pi / 30
    return order_track(edge_times(t[k0:], angle[k0:], teeth), teeth, revs, name=name, accelerating=run is not None,
                       alpha=alpha)
