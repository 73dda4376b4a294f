"""Synthesis over orders: the periodic vibratory signal over one engine cycle from the complex
amplitude of each order, and its extremes (what a torsiograph or a strain gauge reads).

x(θ) = Re Σ_q z_q e^{i q θ}, θ the crank angle (rad), q the orders (per revolution). Its
maximum and minimum over a cycle are found exactly, not to the sampling: a dense sample
(24 points in the shortest period) brackets each extreme, then Newton steps on x′(θ) = 0
polish it, so one order gives back |z_q| to round-off and two orders their analytic peak.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

SAMPLES_PER_PERIOD = 24
NEWTON_STEPS = 4


def waveform(z: np.ndarray, orders: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """x(θ) for amplitudes ``z`` (..., orders) at crank angles ``theta`` (rad): shape (..., angles)."""
    E = np.exp(1j * np.outer(orders, theta))
    flat = np.asarray(z).reshape(-1, len(orders))
    # Re(z E) as two real matrix products: one BLAS call each instead of a batched complex product
    # (30x faster on a response's (speeds, sections, orders) stack).
    out = flat.real @ E.real - flat.imag @ E.imag
    return out.reshape(np.shape(z)[:-1] + (len(theta),))


def extremes(z: np.ndarray, orders: np.ndarray, cycle: float) -> tuple[np.ndarray, np.ndarray]:
    """(max, min) over one cycle of x(θ) = Re Σ z_q e^{iqθ}.

    Parameters
    ----------
    z : ndarray (..., orders), complex
        Amplitude of each order (any unit; the extremes carry it).
    orders : ndarray (orders,)
        Orders, per revolution.
    cycle : float
        Cycle length, rad (4π for a four-stroke).
    """
    orders = np.asarray(orders, dtype=float)
    n = int(np.ceil(SAMPLES_PER_PERIOD * orders.max() * cycle / (2 * np.pi)))
    theta = np.linspace(0.0, cycle, n, endpoint=False)
    half = 0.5 * cycle / n  # the extreme lies within half a sample of the best sample
    x = waveform(z, orders, theta)
    z = np.asarray(z)
    q2 = orders**2
    out = []
    for pick in (np.argmax, np.argmin):
        t0 = theta[pick(x, axis=-1)]  # (...,): the best sample of each signal
        t = t0
        for _ in range(NEWTON_STEPS):  # x'(t) = 0 by Newton, kept within the bracket
            w = z * np.exp(1j * t[..., None] * orders)  # the terms z_q e^{iqt}
            # x' = Re Σ i q w = −Σ q Im w and x'' = −Σ q² Re w: products with the orders, not sums
            # of complex temporaries
            d1 = -(w.imag @ orders)
            d2 = -(w.real @ q2)
            t = np.clip(t - np.divide(d1, d2, out=np.zeros_like(d1), where=d2 != 0), t0 - half, t0 + half)
        out.append((z * np.exp(1j * t[..., None] * orders)).real.sum(axis=-1))
    return out[0], out[1]


def grouped_extremes(z: np.ndarray, orders: np.ndarray, cycle: float,
                     groups: Sequence[tuple[np.ndarray, float]] | None = None) -> tuple[np.ndarray, np.ndarray]:
    """(max, min) of x(θ) = Re Σ z_q e^{iqθ} whose orders fall in ``groups`` of incommensurate
    periods ([(indices into ``orders``, the group's period rad)]; None: one group of period
    ``cycle``, :func:`extremes`). The groups' relative phase takes every value in a long run
    (Kronecker's theorem for rationally independent frequencies), so the supremum of the sum is
    the sum of the groups' maxima and its infimum the sum of their minima."""
    if groups is None:
        return extremes(z, orders, cycle)
    z = np.asarray(z)
    top = bottom = np.zeros(z.shape[:-1])
    for index, period in groups:
        t, b = extremes(z[..., index], orders[index], period)
        top, bottom = top + t, bottom + b
    return top, bottom


def half_peak_to_peak(z: np.ndarray, orders: np.ndarray, cycle: float) -> np.ndarray:
    """Half the peak-to-peak of the synthesised signal: the vibratory amplitude."""
    top, bottom = extremes(z, orders, cycle)
    return 0.5 * (top - bottom)


#: Signals per batch of :func:`largest_half_peak_to_peak`'s exact syntheses.
BATCH = 256


def largest_half_peak_to_peak(z: np.ndarray, orders: np.ndarray, cycle: float,
                              scale: np.ndarray | float | None = None) -> float:
    """max over signals of ``scale`` · :func:`half_peak_to_peak` (z: (..., orders); ``scale``
    broadcast against z's leading axes, non-negative; default 1), synthesising only the signals
    that could reach it: half the peak-to-peak of Re Σ z_q e^{iqθ} is at most Σ |z_q| (each
    term's extremes are ±|z_q|), so the signals are taken in decreasing order of that bound, in
    batches, until the bound of the next falls to the largest found. The same value as the max
    of the whole array's :func:`half_peak_to_peak` times ``scale``, at a fraction of its cost
    when a few signals (a resonance) dominate: an optimiser's objective.
    """
    z = np.asarray(z)
    flat = z.reshape(-1, z.shape[-1])
    s = np.ones(len(flat)) if scale is None else np.broadcast_to(np.asarray(scale, float), z.shape[:-1]).ravel()
    bound = s * np.abs(flat).sum(axis=1)
    ranked = np.argsort(-bound, kind="stable")
    best = -np.inf
    for start in range(0, len(ranked), BATCH):
        pick = ranked[start:start + BATCH]
        if bound[pick[0]] <= best:
            break
        best = max(best, float((s[pick] * half_peak_to_peak(flat[pick], orders, cycle)).max()))
    return best


def group_maxima(z: np.ndarray, orders: np.ndarray, cycle: float, groups: Sequence[np.ndarray]) -> np.ndarray:
    """(1, columns): in each group of columns (index arrays) of ``z`` (speeds, columns, orders),
    the largest half peak-to-peak over the speeds and the group's columns
    (:func:`largest_half_peak_to_peak`), zero elsewhere. A function of the (speeds, columns)
    amplitudes that reads each group only through its largest column at each speed, and grows
    with it, takes its largest value over the speeds at this one row: the damper optimiser's
    and the damping searches' M53 utilisation without every signal synthesised."""
    out = np.zeros((1, z.shape[1]))
    for cols in groups:
        if len(cols):
            out[0, cols] = largest_half_peak_to_peak(z[:, cols], orders, cycle)
    return out
