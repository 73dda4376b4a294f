"""The linear and nonlinear time domain's load and start (:mod:`fetorsion.response.transient`): the
mean motion (a steady speed, a run-up or run-down, a held start), one cylinder's alternating torque
tabulated over a cycle on a grid of speeds and read bilinearly at the mean motion, and the two
starts a run takes from that load: the periodic steady state at constant speed and the rigid-body
mode's start speed.
"""

from __future__ import annotations

import math

import numpy as np

from ..excitation.loads import cylinder_loads


#: Speed grid of the torque tables, rpm (the gas torque's load and the inertia torque's ω² are
#: read linearly between; the inertia torque is exactly ∝ ω², so its error is ≤ (Δn/n)²/4).
TABLE_RPM_STEP = 25.0
#: Samples of a torque table over one cycle.
TABLE_SAMPLES = 1440


def speed_schedule(start_rpm: float, end_rpm: float | None = None, rate_rpm_per_s: float | None = None,
                   duration_s: float | None = None):
    """The mean motion: (duration s, n(t) rpm, φ(t) rad) as functions of t (numpy-vectorised).

    Parameters
    ----------
    start_rpm : float
        Speed at t = 0, rpm.
    end_rpm : float, optional
        Speed at the end of a run-up (above ``start_rpm``) or run-down (below), rpm; None: steady.
    rate_rpm_per_s : float, optional
        The magnitude of dn/dt of the run, rpm/s (required with ``end_rpm``).
    duration_s : float, optional
        Length of a steady run, s.
    """
    if end_rpm is None:
        w = start_rpm * math.pi / 30
        return duration_s, (lambda t: np.full_like(np.asarray(t, float), start_rpm)), (lambda t: w * np.asarray(t))
    a = math.copysign(rate_rpm_per_s, end_rpm - start_rpm)
    T = (end_rpm - start_rpm) / a
    return T, (lambda t: start_rpm + a * np.asarray(t)), \
        (lambda t: math.pi / 30 * (start_rpm * np.asarray(t) + 0.5 * a * np.asarray(t) ** 2))


def held_schedule(hold_s: float, duration_s: float, n_of_t, phi_of_t):
    """The schedule ``(duration_s, n_of_t, phi_of_t)`` of :func:`speed_schedule` after ``hold_s``
    seconds at its start speed: (duration s, n(t) rpm, φ(t) rad), φ continuous at the hold's end."""
    n0 = float(n_of_t(0.0))
    w0 = n0 * math.pi / 30

    def n(t):
        t = np.asarray(t, float)
        return np.where(t < hold_s, n0, n_of_t(np.maximum(t - hold_s, 0.0)))

    def phi(t):
        t = np.asarray(t, float)
        return np.where(t < hold_s, w0 * t, w0 * hold_s + phi_of_t(np.maximum(t - hold_s, 0.0)))

    return hold_s + duration_s, n, phi


def torque_table(crank, rpm_lo: float, rpm_hi: float, samples: int = TABLE_SAMPLES, part: str = "total",
                 misfire: int | None = None):
    """Each cylinder's alternating torque (its cycle mean taken off) on a grid of speeds and angles
    of its own cycle (:meth:`fetorsion.excitation.loads.CylinderLoads.torque_table`).

    ``part``: ``"total"`` (gas and reciprocating inertia) or ``"gas"`` (the variable-inertia model
    makes the inertia torque itself); ``misfire``: that 0-based cylinder's motored cycle (no
    combustion). Returns (rpm grid, angle step rad, table (cylinders, speeds, samples) N·m).
    """
    lo, hi = min(rpm_lo, rpm_hi), max(rpm_lo, rpm_hi)
    n = max(2, int(math.ceil((hi - lo) / TABLE_RPM_STEP)) + 1)
    grid = np.linspace(lo, hi, n) if hi > lo else np.array([lo, lo + 1.0])
    loads = cylinder_loads(crank)
    period = loads.period
    theta = np.arange(samples) * (period / samples)
    table = loads.torque_table(grid, theta, part, misfire)
    return grid, period / samples, table - table.mean(axis=2, keepdims=True)


def read_table(grid, step, table, theta, rpm):
    """Bilinear read of :func:`torque_table` at crank angles ``theta`` (rad, any, periodic) and
    speeds ``rpm`` (clipped to the grid)."""
    G = table.shape[1]
    x = np.mod(theta / step, G)
    i0 = np.floor(x).astype(int) % G
    fx = x - np.floor(x)
    i1 = (i0 + 1) % G
    s = np.clip(np.interp(rpm, grid, np.arange(grid.size)), 0, grid.size - 1)
    j0 = np.minimum(np.floor(s).astype(int), grid.size - 2)
    fs = s - j0
    lo = table[j0, i0] * (1 - fx) + table[j0, i1] * fx
    hi = table[j0 + 1, i0] * (1 - fx) + table[j0 + 1, i1] * fx
    return lo * (1 - fs) + hi * fs


def own_table(table, c: int):
    """Cylinder ``c``'s torque table: its row of :func:`torque_table`'s (cylinders, speeds, samples), or
    ``table`` itself where every cylinder shares one (2-D)."""
    return table if table.ndim == 2 else table[c]


def table_load(W, fire, grid, step, table, phi, rpm):
    """``load(a, b)`` → (coordinates, b − a): the cylinders' torques read from :func:`torque_table`
    (one per cylinder: (cylinders, speeds, samples), or one shared) at samples a … b − 1 of the
    mean angle ``phi`` (rad) and speed ``rpm``, each at its firing angle, put on the coordinates by
    the weights ``W`` (cylinders × coordinates)."""
    def load(a, b):
        return W.T @ np.stack([read_table(grid, step, own_table(table, c), phi[a:b] - f, rpm[a:b])
                               for c, f in enumerate(fire)])

    return load


def periodic_state(M, K, C, W, fire, grid, step, table, rpm: float, phi0: float, period: float):
    """(q, q̇) at mean angle ``phi0`` of the periodic steady state at constant ``rpm``: the one-cycle
    load Wᵀ T_c(θ − φ_c) read from the torque table (its every harmonic, to the table's
    resolution) and, harmonic k of the cycle at ω_k = k (2π/period) Ω, Z_k = (K − ω_k² M + i ω_k C)⁻¹ F_k;
    q(θ) = Re Σ_k 2 Z_k e^{i k 2π θ/period} (its mean, the static wind-up, left out as the load's is).
    The start a run takes from it does not ring: every state is already the periodic one."""
    S = table.shape[-1]
    theta = np.arange(S) * step
    T = np.stack([read_table(grid, step, own_table(table, c), theta - f, np.full(S, rpm)) for c, f in enumerate(fire)])  # (cylinders, S)
    F = np.fft.rfft(W.T @ T, axis=1) / S  # (r, S/2 + 1): F(θ_j) = Σ_k F_k e^{2πi jk/S}, one-sided doubled
    k = np.arange(1, F.shape[1])
    w = k * (2 * np.pi / period) * rpm * np.pi / 30
    A = K[None] - w[:, None, None] ** 2 * M[None] + 1j * w[:, None, None] * C[None]
    Z = np.linalg.solve(A, F[:, 1:].T[:, :, None])[:, :, 0]  # (harmonics, r)
    Z[-1] *= 0.5 if S % 2 == 0 else 1.0  # the Nyquist term is not doubled
    e = np.exp(1j * k * 2 * np.pi * phi0 / period)
    return np.real(2 * e @ Z), np.real(2 * (1j * w * e) @ Z)


def rigid_start_speed(rigid, load, phi, period: float, h: float) -> float:
    """The speed η̇₀ (rad/s of η₀) at which the rigid-body mode starts so that its first working
    cycle's mean speed is zero: the mean motion stays the schedule's.

    Parameters
    ----------
    rigid : ndarray (r,)
        The mass-normalised rigid-body mode φ₀.
    load : callable
        ``load(a, b)`` → (r, b − a): the loads on the coordinates at samples a … b − 1, N·m
        (:func:`table_load`).
    phi : ndarray (N,)
        The mean angle at the samples, rad.
    period : float
        The working cycle, rad of crank angle.
    h : float
        The sample step, s.
    """
    # from rest it would drift at the mean of ∫φ₀ᵀF dt, and the torque would no longer be in step
    # with the angle that carries it
    n1 = min(phi.size, int(np.searchsorted(phi, period)) + 1)
    g0 = rigid @ load(0, n1)
    v = np.concatenate([[0.0], np.cumsum(0.5 * h * (g0[:-1] + g0[1:]))])
    return -float(np.trapezoid(v, dx=h) / (h * (n1 - 1)))
