"""Steady running of the engine model in the time domain: the condensed crank in its bearings.

The reduced crank in its rotating frame, M ẍ + (C + Ω G) ẋ + K x = f(t), driven by every
cylinder's tangential and radial pin force, f(t) = Σ_q Re(F_q e^{i q Ω t}) (the orders of
:func:`fetorsion.response.coupled.condensed_setup`, firing phases included). Each order's
cos(qΩt) and sin(qΩt) are the states of an undamped oscillator, ẇ_q = qΩ [[0, −1], [1, 0]] w_q, so
the crank and its forcing together are one autonomous linear system Ẋ = 𝒜 X, propagated exactly:
X(t + h) = e^{𝒜h} X(t) (one matrix exponential, no integration error). The crank starts at rest;
the run first jumps to the settling time in one step, e^{𝒜 t_s} X₀ (t_s: the slowest elastic
transient decayed to :data:`fetorsion.response.transient.SETTLED`), then samples ``cycles``
working cycles (and two teeth more, for the order track) at :data:`STEPS_PER_PERIOD` steps per
period of the highest order.

It is a second solver of the same question the forced response answers in the frequency domain
(:func:`fetorsion.response.forced.solve_response`: the projected modal solve with a static
correction): the two agree to within the sampling of the peaks (a test asks 0.5 %). Not here yet:
run-ups (the pin forces and the Coriolis term change with speed), dampers, the nonlinear terms.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
import scipy.linalg

from ..errors import FetorsionError
from ..measured.torsiograph import order_track
from .time_budget import check_cycles_fit
from .transient import SETTLED, TransientResult
from .transient_record import edge_times

if TYPE_CHECKING:
    from .forced import ResponseSetup

#: Samples per period of the highest order.
STEPS_PER_PERIOD = 200
#: Eigenvalues of the state matrix smaller than this in magnitude (rad/s; 0.16 Hz, far below any
#: crank mode) are the free rigid motions' (the rotation about the axis, and the axial slide where
#: no thrust bearing holds it): zero but for round-off.
RIGID_RATE = 1.0


def forcing_system(setup, spin: float):
    """(S, B, w0): the oscillators that make each order's cos and sin (S, 2n × 2n), their map
    onto the crank's forces (B, r × 2n, N per unit) and their start (w0: cos 1, sin 0)."""
    F = setup.forces[0]  # (orders, r): one speed
    n = len(setup.orders)
    S = np.zeros((2 * n, 2 * n))
    B = np.zeros((F.shape[1], 2 * n))
    for j, q in enumerate(setup.orders):
        w = q * spin
        S[2 * j:2 * j + 2, 2 * j:2 * j + 2] = [[0.0, -w], [w, 0.0]]
        B[:, 2 * j], B[:, 2 * j + 1] = F[j].real, -F[j].imag  # Re(F e^{iωt}) = Re F cos − Im F sin
    w0 = np.zeros(2 * n)
    w0[0::2] = 1.0
    return S, B, w0


def run_engine_steady(setup: ResponseSetup, cycles: int, teeth: int, track: int | None = None) -> TransientResult:
    """Steady running of ``setup`` (a :func:`~fetorsion.response.coupled.condensed_setup` at one
    speed) in the time domain (module docstring).

    Parameters
    ----------
    setup : ResponseSetup
        The condensed crank at one speed (``setup.rpm`` of length 1), its orders and damping.
    cycles : int
        Working cycles sampled after settling.
    teeth : int
        Teeth of the simulated wheel on the tracked coordinate.
    track : int, optional
        Coordinate order-tracked (default the pulley's θx).
    """
    if len(setup.rpm) != 1:
        raise FetorsionError("the engine model's steady running takes one speed")
    rpm = float(setup.rpm[0])
    spin = rpm * math.pi / 30
    M, K, C = np.asarray(setup.M), np.asarray(setup.K), np.real(np.asarray(setup.C))
    if setup.gyroscopic is not None:
        C = C + spin * np.asarray(setup.gyroscopic)
    r = len(M)
    S, B, w0 = forcing_system(setup, spin)
    Minv = np.linalg.inv(M)
    A = np.block([[np.zeros((r, r)), np.eye(r)], [-Minv @ K, -Minv @ C]])
    lam = np.linalg.eigvals(A)
    elastic = -lam[np.abs(lam) > RIGID_RATE].real
    if not elastic.size:
        raise FetorsionError(f"{setup.name}: no damped elastic mode, a steady run never settles")
    settle = math.log(1 / SETTLED) / float(elastic.min())
    m = len(w0)
    full = np.zeros((2 * r + m, 2 * r + m))
    full[:2 * r, :2 * r] = A
    full[r:2 * r, 2 * r:] = Minv @ B
    full[2 * r:, 2 * r:] = S
    X = np.concatenate([np.zeros(2 * r), w0])
    X = scipy.linalg.expm(full * settle) @ X
    h = 2 * math.pi / (float(setup.orders.max()) * spin) / STEPS_PER_PERIOD
    # two teeth beyond the last cycle: the order track reads one edge past its revolutions, which a
    # record of exactly one cycle would not hold
    N = int(round(cycles * setup.period / spin / h)) + 1 + math.ceil(2 * (2 * math.pi / teeth) / spin / h)
    check_cycles_fit(N, 2 * r + m + 8, cycles)  # the states, and the time, angle and torque rows beside them
    step = scipy.linalg.expm(full * h)
    states = np.empty((N, 2 * r + m))
    for k in range(N):
        states[k] = X
        X = step @ X
    q = states[:, :r].T
    t = settle + h * np.arange(N)
    phi = spin * t
    torque = np.real(setup.section_rows) @ q
    track = setup.pulley if track is None else track
    revs = int(round(setup.period / (2 * math.pi)))
    tracked = order_track(edge_times(t, phi + q[track], teeth), teeth, revs, name=setup.labels[track])
    # the samples past the last cycle's end (its closing sample, the two teeth) count with it
    block = np.minimum(np.floor((phi - phi[0]) / setup.period).astype(int), cycles - 1)
    peak = np.array([np.abs(torque[:, block == b]).max(axis=1) for b in range(cycles)])
    return TransientResult(setup.name, f"steady running at {rpm:g} rpm", list(setup.labels), list(setup.section_labels),
                           t, np.full(N, rpm), phi, torque, q, np.full(len(peak), rpm), peak, tracked, h, settle,
                           f"exact propagation of the crank and its order oscillators (matrix exponential), "
                           f"{setup.model}", [f"settled in one step to t = {settle:.3f} s (slowest elastic transient "
                                              f"at {SETTLED:g} of its start)"], setup.labels[track])

