"""The linear time domain: a chain, network or lumped crank at a fixed speed or in a run-up or
run-down at a stated rate, excited by crank-angle-resolved gas and inertia torques.

The shaft turns with a prescribed mean motion φ(t) (the speed schedule); the vibration q
(rad, the model's coordinates) is superposed on it:

    M q̈ + C q̇ + K q = F(t),   F = W_rᵀ T_c(φ(t) − φ_c, n(t))

with M, K, C the very matrices of the steady-state response (:func:`fetorsion.response.forced.response_setup`:
modal ζ on the undamped modes plus the file's stated viscous dampers), W_r where each cylinder
acts and T_c one cylinder's torque (gas + reciprocating inertia, :func:`fetorsion.excitation.torque.cylinder_torque`)
read at its own crank angle, less its mean over the cycle: like the frequency-domain response,
only the alternating torque (the orders) drives the vibration; the mean drive torque and the
static wind-up against its load are left out. The torque is tabulated over a cycle on a grid of
speeds and read bilinearly (in angle and speed); in a run-up the piston's tangential inertia
term m S'(θ) dω/dt is left out (at 1000 rpm/s and 1000 rpm it is 1 % of m S''(θ) ω², and it
falls as ω²).

**Scheme.** The matrices are constant, so the exact propagator of a step is a matrix exponential:
in the basis of the undamped modes Φ (ΦᵀMΦ = I) the equations become η̈ + ΦᵀCΦ η̇ + Λ η = ΦᵀF,
and the first-order state x = (η, η̇) is diagonalised once, x = V z, ż = λ z + V⁻¹B g. With the
force linear between samples (first-order hold) each z advances exactly:

    z_{k+1} = e^{λh} z_k + g_k (I₀ − I₁/h) + g_{k+1} I₁/h,   I₀ = (e^{λh} − 1)/λ,   I₁ = (e^{λh} − 1 − λh)/λ²

a first-order recursion (derived here: the convolution integral over one step with the load
linear in it) that :func:`scipy.signal.lfilter` runs in compiled code over the whole record. There is no period
elongation or numerical damping at any step (Newmark's average acceleration elongates periods
by (ωh)²/12 and would need a loop in Python over 10⁵–10⁶ steps); the only error is the
force's linear interpolation between samples (0.5° of crank angle by default at the top speed). The
free-free rigid-body mode, undamped and decoupled (Cφ₀ = 0 for relative and modal dampers), is
integrated apart as a double integral of its force (exact for the same hold); with absolute
dampers it is damped and coupled, and the full basis is diagonalised (λ = 0 is then simple).

Hysteretic loss factors (k(1 + iη)) have no causal time-domain form: each enters as the viscous
damping that dissipates as much at the resonance of every mode, C_η = MΦ diag(φ_jᵀHφ_j/ω_j)ΦᵀM
(exact at each mode's resonance, not between them).

**Dampers** (:func:`with_dampers`): each ring is a coordinate, a viscous or tuned damper's dashpot
and spring join C and K; a rubber damper's dynamic table is a generalised Maxwell model
[ParkSchapery] (:func:`fetorsion.lumped_model.damped.maxwell_fit`), each branch one first-order
state in the same exact propagator; a heat-following rubber at the frequency domain's temperature.

**Order tracking.** A station's simulated angle (mean motion plus vibration) is turned into the
tooth-edge times a toothed wheel of ``teeth`` teeth would give, and these go through the same
:func:`fetorsion.measured.torsiograph.order_track` as a measured record.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg
import scipy.signal

from ..errors import FetorsionError, ParameterError
from ..excitation.torque import cycle_angle, cylinder_torque, firing_angles
from ..measured.torsiograph import OrderTrack, order_track
from .nonlinear import (METHODS, RTOL, Elements, SliderCranks, element_work, integrate_compiled, integrate_nonlinear,
                        stick_damping_changes)
from ..excitation.campbell import RESPONSE_HIGHEST_ORDER
from ..description.defaults import (DEFAULT_PARTITION, DEFAULT_STEP_DEG, DEFAULT_TEETH, DEFAULT_TRANSIENT_CYCLES,
                                    DEFAULT_WEB_METHOD)

#: Crank angle per time step at the top speed, rad: 0.5° (orders to 360 sampled; the force's
#: linear interpolation errs by (qΔθ)²/8 at order q: 1.4e-3 at order 12).
DEFAULT_STEP_RAD = math.radians(DEFAULT_STEP_DEG)
#: The coarsest step: two samples a period of the highest order a response sums (Nyquist).
MAX_STEP_RAD = math.pi / RESPONSE_HIGHEST_ORDER
#: Speed grid of the torque tables, rpm (the gas torque's load and the inertia torque's ω² are
#: read linearly between; the inertia torque is exactly ∝ ω², so its error is ≤ (Δn/n)²/4).
TABLE_RPM_STEP = 25.0
#: Samples of a torque table over one cycle.
TABLE_SAMPLES = 1440
#: A steady run settles until the slowest elastic transient is this fraction of its start.
SETTLED = 1e-6
#: Samples computed per lfilter call: bounds the memory of a long record.
CHUNK = 1 << 16


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


#: A held start (:func:`run_transient` ``settled_start``) lasts until the slowest elastic transient is
#: this fraction of its start: the residue is 0.1 % of the start's ringing, below the order track's own
#: resampling error (docs/networks-and-transients.md), at half the cost of :data:`SETTLED`.
START_SETTLED = 1e-3


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


def periodic_state(M, K, C, W, fire, grid, step, table, rpm: float, phi0: float, period: float):
    """(q, q̇) at mean angle ``phi0`` of the periodic steady state at constant ``rpm``: the one-cycle
    load Wᵀ T_c(θ − φ_c) read from the torque table (its every harmonic, to the table's
    resolution) and, harmonic k of the cycle at ω_k = k (2π/period) Ω, Z_k = (K − ω_k² M + i ω_k C)⁻¹ F_k;
    q(θ) = Re Σ_k 2 Z_k e^{i k 2π θ/period} (its mean, the static wind-up, left out as the load's is).
    The start a run takes from it does not ring: every state is already the periodic one."""
    S = table.shape[1]
    theta = np.arange(S) * step
    T = np.stack([read_table(grid, step, table, theta - f, np.full(S, rpm)) for f in fire])  # (cylinders, S)
    F = np.fft.rfft(W.T @ T, axis=1) / S  # (r, S/2 + 1): F(θ_j) = Σ_k F_k e^{2πi jk/S}, one-sided doubled
    k = np.arange(1, F.shape[1])
    w = k * (2 * np.pi / period) * rpm * np.pi / 30
    A = K[None] - w[:, None, None] ** 2 * M[None] + 1j * w[:, None, None] * C[None]
    Z = np.linalg.solve(A, F[:, 1:].T[:, :, None])[:, :, 0]  # (harmonics, r)
    Z[-1] *= 0.5 if S % 2 == 0 else 1.0  # the Nyquist term is not doubled
    e = np.exp(1j * k * 2 * np.pi * phi0 / period)
    return np.real(2 * e @ Z), np.real(2 * (1j * w * e) @ Z)


def torque_table(crank, rpm_lo: float, rpm_hi: float, samples: int = TABLE_SAMPLES, part: str = "total"):
    """One cylinder's alternating torque (its cycle mean taken off) on a grid of speeds and angles.

    ``part``: ``"total"`` (gas and reciprocating inertia) or ``"gas"`` (the variable-inertia model
    makes the inertia torque itself). Returns (rpm grid, angle step rad, table (speeds, samples) N·m).
    """
    lo, hi = min(rpm_lo, rpm_hi), max(rpm_lo, rpm_hi)
    n = max(2, int(math.ceil((hi - lo) / TABLE_RPM_STEP)) + 1)
    grid = np.linspace(lo, hi, n) if hi > lo else np.array([lo, lo + 1.0])
    period = cycle_angle(crank.engine)
    theta = np.arange(samples) * (period / samples)
    table = np.array([getattr(cylinder_torque(crank, r, theta), part) for r in grid])
    return grid, period / samples, table - table.mean(axis=1, keepdims=True)


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


def table_load(W, fire, grid, step, table, phi, rpm):
    """``load(a, b)`` → (coordinates, b − a): the cylinders' torques read from :func:`torque_table`
    at samples a … b − 1 of the mean angle ``phi`` (rad) and speed ``rpm``, each at its firing angle,
    put on the coordinates by the weights ``W`` (cylinders × coordinates)."""
    def load(a, b):
        return W.T @ np.stack([read_table(grid, step, table, phi[a:b] - f, rpm[a:b]) for f in fire])

    return load


def hysteretic_equivalent(M, K, H) -> np.ndarray:
    """Viscous C_η = MΦ diag(φ_jᵀHφ_j/ω_j)ΦᵀM: the loss factors' dissipation at each elastic
    mode's resonance (module docs); the rigid-body mode gets none."""
    lam, Phi = scipy.linalg.eigh(K, M)
    elastic = lam > 1e-8 * np.abs(lam).max()
    c = np.zeros_like(lam)
    c[elastic] = np.einsum("ij,ik,kj->j", Phi[:, elastic], H, Phi[:, elastic]) / np.sqrt(lam[elastic])
    return M @ Phi @ np.diag(c) @ Phi.T @ M


@dataclass(frozen=True)
class Propagator:
    """The exact first-order-hold propagator of M q̈ + C q̇ + K q = F at step ``h`` (module docs).

    ``Phi`` (r × m) the modes integrated by the filters, ``lam`` (2m) their state eigenvalues,
    ``Vq``/``Vv`` (m × 2m) the modal states' share of η and η̇, ``Vinv_B`` (2m × m) the load's
    input to each, ``E, a, b`` the recursion's coefficients; ``rigid`` (r,) the mass-normalised
    rigid-body mode integrated apart, or None.
    """

    h: float
    Phi: np.ndarray
    lam: np.ndarray
    Vq: np.ndarray
    Vv: np.ndarray
    Vinv_B: np.ndarray
    E: np.ndarray
    a: np.ndarray
    b: np.ndarray
    rigid: np.ndarray | None
    #: The modal states' share of η (2m × m, Vinv's first block) and the modal coordinates per
    #: unit q (ΦᵀM, m × r; the rigid mode's φ₀ᵀM, r): an initial state's modal start.
    Vinv_q: np.ndarray | None = None
    PhiT_M: np.ndarray | None = None
    rigid_M: np.ndarray | None = None

    @property
    def settling_s(self) -> float:
        """Time for the slowest decaying modal state to fall to :data:`SETTLED` of its start, s."""
        # a λ = 0 state is the angle of a damped rigid-body mode: an offset, nothing to settle
        decay = -self.lam.real[np.abs(self.lam) > 1e-9 * np.abs(self.lam).max()]
        if np.any(decay <= 0):
            return math.inf
        return math.log(1 / SETTLED) / decay.min()


def propagator(M, K, C, h: float, grounded: bool = False, branches=None) -> Propagator:
    """Build the :class:`Propagator` (one eigen-decomposition per model and step).

    ``branches`` (D (b × r), k (b,), c (b,)), optional: Maxwell branches, each a spring k in
    series with a dashpot c across the twist D q, with one first-order state u (the dashpot's
    stroke): c u̇ = k (D q − u), its torque k (D q − u) on the coordinates through Dᵀ. The state
    (η, η̇, u) is diagonalised as a whole, so the propagator stays exact.
    """
    lam_u, Phi = scipy.linalg.eigh(K, M)  # ΦᵀMΦ = I
    D, kb, cb = (np.zeros((0, len(M))), np.zeros(0), np.zeros(0)) if branches is None else branches
    Kb = D.T @ (kb[:, None] * D)
    rigid = None
    if not grounded:
        # A rigid-body mode: zero stiffness, and neither damping nor a Maxwell branch on it. Zero
        # stiffness may have several shapes (a viscous damper's ring turns freely on its fluid):
        # within them, the one that nothing damps.
        zero = np.abs(lam_u) <= 1e-8 * abs(lam_u[-1])
        if zero.any():
            Z = Phi[:, zero]
            s_, R = np.linalg.eigh(Z.T @ (C + Kb) @ Z)
            Z = Z @ R
            phi0 = Z[:, 0]
            if s_[0] <= 1e-12 * max(np.abs(C).max(initial=0.0), np.abs(Kb).max(initial=0.0)) * (phi0 @ phi0):
                rigid, Phi, lam_u = phi0, np.hstack([Z[:, 1:], Phi[:, ~zero]]), np.concatenate(
                    [np.zeros(zero.sum() - 1), lam_u[~zero]])
    m, nb = Phi.shape[1], len(kb)
    Cm = Phi.T @ C @ Phi
    P = D @ Phi  # each branch's twist per modal coordinate
    A = np.block([[np.zeros((m, m)), np.eye(m), np.zeros((m, nb))],
                  [-np.diag(lam_u) - P.T @ (kb[:, None] * P), -Cm, P.T * kb],
                  [(kb / cb)[:, None] * P, np.zeros((nb, m)), -np.diag(kb / cb)]])
    lam, V = scipy.linalg.eig(A)
    Vinv = np.linalg.inv(V)
    lh = lam * h
    E = np.exp(lh)
    small = np.abs(lh) < 1e-5  # series: the closed forms lose digits as λh → 0
    with np.errstate(divide="ignore", invalid="ignore"):
        I0 = np.where(small, h * (1 + lh / 2 + lh**2 / 6), (E - 1) / lam)
        I1 = np.where(small, h * h * (0.5 + lh / 6 + lh**2 / 24), (E - 1 - lh) / lam**2)
    return Propagator(h, Phi, lam, V[:m], V[m:2 * m], Vinv[:, m:2 * m], E, I0 - I1 / h, I1 / h, rigid,
                      Vinv[:, :m], Phi.T @ M, None if rigid is None else rigid @ M)


def integrate(prop: Propagator, load, N: int, rigid_speed: float = 0.0, start=None) -> np.ndarray:
    """q(t_k) (r × N), starting at rest (the rigid-body mode at ``rigid_speed``, rad/s of η₀) or at
    ``start`` = (q₀, q̇₀) (the coordinates' angles and speeds; the rigid mode's share of them
    instead of ``rigid_speed``; not with Maxwell branches), under the load ``load(start, stop)`` → F (r × (stop − start))
    sampled every ``prop.h``. Runs in chunks of :data:`CHUNK` samples (the filters' states, the
    last load and the rigid mode's angle and speed carried on), so the memory is the output's.
    Conjugate modal states are one: only those with Im λ ≥ 0 are run, the others' share is the
    conjugate of theirs (the system is real)."""
    r = prop.Phi.shape[0]
    q = np.empty((r, N))
    up = prop.lam.imag > 1e-12 * np.abs(prop.lam).max()
    keep = up | (np.abs(prop.lam.imag) <= 1e-12 * np.abs(prop.lam).max())
    weight = np.where(up, 2.0, 1.0)[keep]
    E, a, b = prop.E[keep], prop.a[keep], prop.b[keep]
    Vq = prop.Phi @ (prop.Vq[:, keep] * weight)  # coordinates from the kept states
    B = prop.Vinv_B[keep] @ prop.Phi.T  # (kept states × r): the load's input to each
    state = np.zeros(keep.sum(), complex)
    u_last = None
    v, eta = rigid_speed, 0.0
    z0 = np.zeros(keep.sum(), complex)
    if start is not None:
        q0, v0 = (np.asarray(x, float) for x in start)
        if prop.Vinv_B.shape[0] != 2 * prop.Phi.shape[1]:
            raise FetorsionError("a start state with Maxwell branches (a rubber table's states) is not supported")
        z0 = (prop.Vinv_q @ (prop.PhiT_M @ q0) + prop.Vinv_B @ (prop.PhiT_M @ v0))[keep]
        if prop.rigid is not None:
            eta, v = float(prop.rigid_M @ q0), float(prop.rigid_M @ v0)
    g_last = None
    h = prop.h
    for start in range(0, N, CHUNK):
        stop = min(N, start + CHUNK)
        F = load(start, stop)
        u = B @ F
        w = np.empty_like(u)
        w[:, 1:] = a[:, None] * u[:, :-1] + b[:, None] * u[:, 1:]
        if u_last is None:
            w[:, 0] = 0.0  # z_0: rest, or the start state
            zi = z0
        else:
            w[:, 0] = a * u_last + b * u[:, 0]
            zi = E * state
        z = np.empty_like(u)
        for s_ in range(len(state)):
            z[s_], _ = scipy.signal.lfilter([1.0], [1.0, -E[s_]], w[s_], zi=[zi[s_]])
        state, u_last = z[:, -1], u[:, -1]
        q[:, start:stop] = np.real(Vq @ z)
        if prop.rigid is not None:
            # η₀'' = φ₀ᵀF, exact for the linear hold: the speed by trapezoids, the angle by its integral
            g0 = prop.rigid @ F
            g = g0 if g_last is None else np.concatenate([[g_last], g0])
            dv = 0.5 * h * (g[:-1] + g[1:])
            vs = v + np.concatenate([[0.0], np.cumsum(dv)])
            deta = h * vs[:-1] + h * h * (g[:-1] / 3 + g[1:] / 6)
            etas = eta + np.concatenate([[0.0], np.cumsum(deta)])
            if g_last is not None:
                vs, etas = vs[1:], etas[1:]
            q[:, start:stop] += np.outer(prop.rigid, etas)
            v, eta, g_last = vs[-1], etas[-1], g0[-1]
    return q


#: Decades of amplitude below its largest value that a waterfall's colour scale shows.
WATERFALL_SPAN = 3.0


@dataclass
class TransientResult:
    """A simulated run: time signals, their per-block envelope and the order track of a station.

    Attributes
    ----------
    time_s, rpm : ndarray (N,)
        Sample times (s) and the mean speed at each (rpm).
    crank_angle_rad : ndarray (N,)
        The mean motion φ(t) of station 1, rad.
    section_torque_nm : ndarray (sections, N)
        The elastic torque of every shaft section, N·m (vibratory: the mean drive torque left out).
    angle_rad : ndarray (coordinates, N)
        The vibration angle of every coordinate of the model, rad.
    block_rpm, block_peak_nm : ndarray
        Mean speed of each working cycle and the largest ``|torque|`` of each section in it (cycles ×
        sections): the run-up's envelope (a steady run: its settled cycles only).
    track : OrderTrack
        The order track of station ``track_station`` from its simulated tooth edges
        (:func:`fetorsion.measured.torsiograph.order_track`).
    elements : list of ElementWork
        Each nonlinear element's slip and friction heat over the run
        (:class:`fetorsion.response.nonlinear.ElementWork`; empty for a linear run).
    """

    name: str
    mode: str
    labels: list
    section_labels: list
    time_s: np.ndarray
    rpm: np.ndarray
    crank_angle_rad: np.ndarray
    section_torque_nm: np.ndarray
    angle_rad: np.ndarray
    block_rpm: np.ndarray
    block_peak_nm: np.ndarray
    track: OrderTrack
    step_s: float
    settle_s: float = 0.0
    scheme: str = ""
    notes: list = field(default_factory=list)
    track_station: str = ""
    elements: list = field(default_factory=list)

    def steady_peak_nm(self) -> np.ndarray:
        """Largest ``|torque|`` of each section after the settling time (a steady run), N·m."""
        keep = self.time_s >= self.settle_s
        return np.abs(self.section_torque_nm[:, keep]).max(axis=1)

    def to_dict(self, every: int | None = None) -> dict:
        """JSON-ready: the envelope, the order track, and the signals thinned to at most ~20 000
        samples: one per block of ``every`` (default so many that 20 000 remain), the block's
        sample where the largest absolute section torque peaks (so the record's peak is in it, not
        up to 1 % lower between kept samples), and each section's least and largest torque in each block
        (``section_torque_min_nm``, ``section_torque_max_nm``: every section's peak, exactly)."""
        every = every or max(1, self.time_s.size // 20000)
        T = self.section_torque_nm
        n = T.shape[1]
        starts = np.arange(0, n, every)
        worst = np.abs(T).max(axis=0) if T.size else np.zeros(n)
        keep = np.array([a + int(np.argmax(worst[a:a + every])) for a in starts], dtype=int) if n else starts
        lo = np.minimum.reduceat(T, starts, axis=1) if T.size else T
        hi = np.maximum.reduceat(T, starts, axis=1) if T.size else T
        return {"name": self.name, "mode": self.mode, "scheme": self.scheme, "step_s": self.step_s,
                "settle_s": self.settle_s, "labels": self.labels, "sections": self.section_labels,
                "notes": self.notes,
                "block_rpm": self.block_rpm.tolist(), "block_peak_torque_nm": self.block_peak_nm.tolist(),
                "order_track": {"station": self.track_station, **self.track.to_dict()},
                "elements": [w.to_dict() for w in self.elements],
                "signals": {"every": every, "time_s": self.time_s[keep].tolist(), "rpm": self.rpm[keep].tolist(),
                            "section_torque_nm": T[:, keep].tolist(), "section_torque_min_nm": lo.tolist(),
                            "section_torque_max_nm": hi.tolist()}}

    def table(self) -> str:
        """The result as plain text: the table the command line prints."""
        k = int(np.argmax(self.block_peak_nm.max(axis=0)))
        b = int(np.argmax(self.block_peak_nm[:, k]))
        lines = [f"{self.name}: {self.mode}, {self.time_s[-1]:.2f} s in steps of {self.step_s * 1e6:.1f} us "
                 f"({self.scheme})",
                 f"  largest section torque {self.block_peak_nm[b, k]:.1f} N m in {self.section_labels[k]} "
                 f"at {self.block_rpm[b]:.0f} rpm"]
        for w in self.elements:
            slip = (f"slipped {np.degrees(w.slip_rad):.2f} deg in {w.slip_events} slip(s), {w.slip_time_s:.3f} s, "
                    f"{w.slip_energy_j:.1f} J" if w.slip_rad > 0 else "did not slip")
            lines.append(f"  {w.name or 'element'}: {slip}; its friction {w.friction_energy_j:.1f} J")
        if self.mode.startswith("steady"):
            peaks = self.steady_peak_nm()
            lines.append("  steady peak |torque| per section [N m]: "
                         + ", ".join(f"{s} {p:.1f}" for s, p in zip(self.section_labels, peaks)))
        strongest = np.argsort(np.abs(self.track.amplitudes).max(axis=0))[::-1][:4]
        lines.append(f"  order track of {self.track_station}: strongest orders "
                     + ", ".join(f"{self.track.orders[j]:g} ({np.degrees(np.abs(self.track.amplitudes[:, j])).max():.4f} deg)"
                                 for j in sorted(strongest)))
        return "\n".join(lines + [f"  note: {n}" for n in self.notes])

    def plot(self, ax=None, orders=(1.0, 2.0)):
        """The most loaded section's torque against time (and its block envelope), and the order
        cuts of the tracked station against speed. Returns the first Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            fig = plt.figure(figsize=(9, 7))
            a1, a2 = fig.subplots(2, 1)
        else:
            fig, a1, a2 = ax.figure, ax, None
        k = int(np.argmax(self.block_peak_nm.max(axis=0)))
        every = max(1, self.time_s.size // 50000)
        a1.plot(self.time_s[::every], self.section_torque_nm[k, ::every], lw=0.5, color="C0",
                label=f"section {self.section_labels[k]}")
        a1.set_xlabel("time [s]")
        a1.set_ylabel("vibratory torque [N m]")
        a1.set_title(f"{self.name}: {self.mode}", fontsize=10, wrap=True)
        a1.legend(fontsize=8)
        if a2 is not None:
            for q in orders:
                if np.any(np.isclose(self.track.orders, q)):
                    a2.plot(self.track.rpm, np.degrees(np.abs(self.track.at(q))), label=f"order {q:g}")
            a2.set_xlabel("mean speed [rpm]")
            a2.set_ylabel(f"{self.track_station}: vibration [deg]")
            a2.legend(fontsize=8)
            fig.tight_layout()
        return a1

    def waterfall(self, ax=None, max_order: float | None = None, span: float = WATERFALL_SPAN):
        """The order track as a map: the tracked station's vibration (deg, colour on a log scale
        over ``span`` decades below its largest value) against mean speed (rpm) and order, orders
        up to ``max_order`` (default all tracked). Returns the Axes."""
        import matplotlib.pyplot as plt
        from matplotlib.colors import LogNorm

        if ax is None:
            _, ax = plt.subplots(figsize=(9, 5))
        keep = self.track.orders <= (max_order if max_order is not None else np.inf)
        amp = np.degrees(np.abs(self.track.amplitudes[:, keep])).T  # (orders, blocks)
        top = float(amp.max()) if amp.size and amp.max() > 0 else 1.0
        mesh = ax.pcolormesh(self.track.rpm, self.track.orders[keep], np.maximum(amp, top * 10.0**-span),
                             shading="nearest", norm=LogNorm(top * 10.0**-span, top), cmap="viridis")
        ax.figure.colorbar(mesh, ax=ax, label=f"{self.track_station}: vibration [deg]")
        ax.set_xlabel("mean speed [rpm]")
        ax.set_ylabel("order")
        ax.set_title(f"{self.name}: {self.mode}, order track of {self.track_station}", fontsize=10, wrap=True)
        ax.figure.tight_layout()
        return ax


#: The speeds about a crossing, as a fraction of its speed either side, in which a run-up's order cut
#: and the steady-state response are searched for their peaks.
CROSSING_WINDOW = 0.1


@dataclass(frozen=True)
class OrderCut:
    """One order of a run-up against the steady state about one crossing of the Campbell diagram.

    ``passage`` is α/Γ² = q |dΩ/dt| / (ζ ω)² (the sweep rate of the order's frequency over the square of
    the mode's half-power bandwidth, [Cowan]): ≪ 1 a slow passage, whose peak approaches the steady
    state; ≳ 0.1 the peak is lower and later. Amplitudes in deg, speeds in rpm, at the tracked station.
    """

    order: float
    mode: int
    mode_hz: float
    crossing_rpm: float
    passage: float
    steady_deg: float
    steady_rpm: float
    runup_deg: float
    runup_rpm: float

    @property
    def difference(self) -> float:
        """The run-up's peak over the steady state's, − 1."""
        return self.runup_deg / self.steady_deg - 1.0

    def to_dict(self) -> dict:
        return {"order": self.order, "mode": self.mode, "mode_hz": self.mode_hz, "crossing_rpm": self.crossing_rpm,
                "passage_alpha_over_gamma2": self.passage, "steady_peak_deg": self.steady_deg,
                "steady_peak_rpm": self.steady_rpm, "runup_peak_deg": self.runup_deg,
                "runup_peak_rpm": self.runup_rpm, "difference": self.difference}


def order_cuts(result: TransientResult, response, crossings, damping_ratio, rate_rpm_per_s: float,
               window: float = CROSSING_WINDOW) -> tuple[OrderCut, ...]:
    """The run-up's order cuts against the steady-state response at each crossing.

    Parameters
    ----------
    result : TransientResult
        A run-up (or run-down) tracked at the response's first coordinate (its "pulley").
    response : ResponseResult
        The steady-state forced response of the same model: its ``order_pulley_deg`` (each
        order's own amplitude, deg) is what the order track measures.
    crossings : sequence of Crossing
        Campbell crossings (:class:`fetorsion.excitation.campbell.Crossing`), each inside
        both the run's and the response's speeds and on both their orders (others are left out).
    damping_ratio : float or sequence of float
        ζ of every mode, or of each mode (the Campbell diagram's), for the passage parameter.
    rate_rpm_per_s : float
        |dn/dt| of the run, rpm/s.
    window : float
        The peaks are searched within ``rpm (1 ± window)`` of each crossing.

    Returns
    -------
    tuple of OrderCut
    """
    out = []
    lo, hi = max(result.track.rpm.min(), response.rpm.min()), min(result.track.rpm.max(), response.rpm.max())
    for c in crossings:
        q, n = c.order, c.rpm
        k = np.flatnonzero(np.isclose(response.orders, q))
        if not (lo <= n <= hi and k.size and np.any(np.isclose(result.track.orders, q))):
            continue
        zeta = damping_ratio[c.mode - 1] if np.ndim(damping_ratio) else damping_ratio
        omega = 2 * np.pi * c.frequency_hz
        a, b = n * (1 - window), n * (1 + window)
        s = (response.rpm >= a) & (response.rpm <= b)
        r = (result.track.rpm >= a) & (result.track.rpm <= b)
        steady, cut = response.order_pulley_deg[s, int(k[0])], np.degrees(np.abs(result.track.at(q)[r]))
        i, j = int(np.argmax(steady)), int(np.argmax(cut))
        out.append(OrderCut(q, c.mode, c.frequency_hz, n,
                            float(q * rate_rpm_per_s * np.pi / 30 / (zeta * omega) ** 2) if zeta > 0 else math.inf,
                            float(steady[i]), float(response.rpm[s][i]), float(cut[j]), float(result.track.rpm[r][j])))
    return tuple(out)


def plot_order_cuts(result: TransientResult, response, cuts, ax=None):
    """Each compared order's cut of the run-up (solid) over the steady-state response's (dashed),
    the tracked station's vibration in deg against speed. Returns the Axes."""
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(9, 5))
    for i, q in enumerate(dict.fromkeys(c.order for c in cuts)):
        k = int(np.flatnonzero(np.isclose(response.orders, q))[0])
        ax.plot(result.track.rpm, np.degrees(np.abs(result.track.at(q))), color=f"C{i}", lw=1.2,
                label=f"order {q:g}, run-up")
        ax.plot(response.rpm, response.order_pulley_deg[:, k], color=f"C{i}", lw=1.0, ls="--",
                label=f"order {q:g}, steady state")
    ax.set_yscale("log")  # a low order's rigid-body swing at idle would flatten the resonances
    ax.set_xlabel("mean speed [rpm]")
    ax.set_ylabel(f"{result.track_station}: vibration [deg]")
    ax.set_title(f"{result.name}: order cuts, {result.mode} (solid) and steady state (dashed)", fontsize=9, wrap=True)
    ax.legend(fontsize=8, ncol=2)
    ax.figure.tight_layout()
    return ax


def edge_times(t, angle, teeth: int) -> np.ndarray:
    """The times a wheel of ``teeth`` teeth turning through ``angle`` (rad, increasing, sampled
    at ``t``) passes each tooth edge, the first at the record's first angle: linear between
    samples (the angle is smooth on the scale of a step)."""
    pitch = 2 * np.pi / teeth
    edges = angle[0] + pitch * np.arange(int((angle[-1] - angle[0]) / pitch) + 1)
    return np.interp(edges, angle, t)


#: Speeds at which a heat-following rubber damper's temperature is found for a run (its
#: dissipation's largest value over them sets it, as in the frequency domain).
HEAT_SPEEDS = 60


def with_dampers(model, setup, dampers, speeds, partition, damping_ratio, web_method, notes):
    """The model's matrices with its ``[[dampers]]`` (module docs): (M, K complex, C, branches,
    ring labels). A ring is a coordinate; a viscous or tuned damper's dashpot joins C, its spring
    (with any loss factor, on ``K``'s imaginary part) K; a rubber damper with a dynamic table is
    its :func:`fetorsion.lumped_model.damped.maxwell_fit`: k∞ joins K, each branch is one of
    ``branches`` = (D, k, c, k at the band's middle) for :func:`propagator`, or None without any.
    A heat-following rubber is read at the temperature the frequency domain finds for ``speeds``
    (lowest, highest rpm: one speed when equal), with the default orders. Appends what it did to
    ``notes``."""
    from ..lumped_model.damped import DampedSystem, maxwell_fit
    from .forced import response_setup, solve_theta

    if not dampers:
        return setup.M, setup.K, np.real(setup.C), None, []
    if any(d.follows_heat for d in dampers):
        lo, hi = speeds
        grid = [lo] if hi == lo else np.linspace(lo, hi, HEAT_SPEEDS)
        hot = response_setup(model, partition, rpm=grid, damping_ratio=damping_ratio, web_method=web_method)
        dampers = solve_theta(hot, dampers)[2].dampers
        notes.extend(f"damper '{d.name}': rubber at {d.temperature_c:.1f} °C, the temperature its heat holds "
                     f"over {lo:g}-{hi:g} rpm in the frequency domain" for d in dampers if d.follows_heat)
    n = len(setup.labels)
    system = DampedSystem(setup.M, setup.K, np.real(setup.C), dampers, stations=n, at=setup.damper_station,
                          scale=setup.damper_factor)
    M, K, C = system.M, system.K.astype(complex), system.C
    rows, kb, cb, kmid = [], [], [], []
    for d, (s, r) in zip(system.dampers, system.joints):
        u = np.zeros(len(M))
        u[s], u[r] = 1.0, -1.0
        if d.kind == "rubber" and d.table:
            fit = maxwell_fit(d)
            K = K + fit.k_inf * np.outer(u, u)
            mid = 2 * np.pi * np.sqrt(fit.band_hz[0] * fit.band_hz[1])
            for k, c in zip(fit.stiffness, fit.damping):
                rows.append(u)
                kb.append(k)
                cb.append(c)
                kmid.append(np.real(k * 1j * mid * c / k / (1 + 1j * mid * c / k)))
            notes.append(f"damper '{d.name}': its dynamic table as k_inf = {fit.k_inf:.4g} N m/rad and "
                         f"{fit.stiffness.size} Maxwell branches fitted over {fit.band_hz[0]:g}-{fit.band_hz[1]:g} Hz; "
                         f"at the table's rows |k*| within {100 * fit.stiffness_error:.2f} %, the loss factor "
                         f"within {fit.loss_error:.4f} (held at the end rows outside in the frequency domain, "
                         "the model's own relaxation here)")
        else:
            K = K + d.stiffness * (1 + 1j * d.loss_factor) * np.outer(u, u)
    labels = [f"damper '{d.name}' ring" for d in dampers]
    if not kb:
        return M, K, C, None, labels
    return M, K, C, (np.array(rows), np.array(kb), np.array(cb), np.array(kmid)), labels


def run_transient(model, rpm: float | None = None, run: tuple[float, float] | None = None,
                  rate_rpm_per_s: float | None = None, cycles: int = DEFAULT_TRANSIENT_CYCLES,
                  damping_ratio: float | None = None,
                  partition: int = DEFAULT_PARTITION, web_method: str = DEFAULT_WEB_METHOD,
                  step_rad: float = DEFAULT_STEP_RAD, teeth: int = DEFAULT_TEETH,
                  track_station: int = 0, variable_inertia: bool = False, method: str = METHODS[0],
                  settled_start: bool = False) -> TransientResult:
    """Simulate a model with an engine in the time domain (module docs): linear by the exact
    propagator; with ``variable_inertia`` or a network's nonlinear elements by the nonlinear
    integrator of :mod:`fetorsion.response.nonlinear`.

    Parameters
    ----------
    model : Crank, Chain or Network
        With ``[engine]`` and ``[excitation]`` (a chain or network: ``cylinder_stations``).
    rpm : float, optional
        Steady running at this speed, rpm: the run lasts until every elastic transient has
        decayed to :data:`SETTLED` of its start, then ``cycles`` more working cycles.
    run : (float, float), optional
        Run-up (A < B) or run-down (A > B) from A to B rpm, instead of ``rpm``.
    rate_rpm_per_s : float, optional
        The magnitude of dn/dt of the run, rpm/s (required with ``run``).
    cycles : int
        Working cycles analysed after settling in a steady run.
    damping_ratio : float, optional
        Modal damping ratio ζ; default the description's (as :func:`run_response`).
    partition, web_method
        The lumped model of a crank (ignored for a chain or network).
    step_rad : float
        Crank angle per step at the run's top speed, rad (the step is constant in time); at most
        :data:`MAX_STEP_RAD`.
    teeth : int
        Teeth of the simulated wheel whose edges the order tracking reads.
    track_station : int
        0-based station (a coordinate of the model) whose angle is order-tracked.
    variable_inertia : bool
        Each cylinder's reciprocating mass as the crank-angle-dependent inertia m S'(θ)² on its
        station (:mod:`fetorsion.response.nonlinear`), instead of its mean in the station's inertia
        and its inertia torque as a load.
    method : str
        The nonlinear integrator: one of :data:`fetorsion.response.nonlinear.METHODS`: ``"compiled"``
        (the default: :mod:`fetorsion.response.compiled`, friction as exact Jenkins elements) or a
        scipy ``solve_ivp`` method (friction by Bouc–Wen's rate law; the cross-check); the linear
        case ignores it.
    settled_start : bool
        A run starts as an engine does that has run steadily at speed A before a test cell's
        run-up: a linear model in the periodic steady state at A (:func:`periodic_state`, from the
        frequency domain); a model with nonlinear elements or a rubber table's Maxwell states first
        holds A until the slowest elastic transient of starting from rest has fallen to
        :data:`START_SETTLED` of its size (the envelope and the order track begin after the hold,
        ``settle_s``). Without it the run starts from rest at speed A and its first cycles ring with
        the lightly damped modes (a driveline's, for seconds). Not with ``variable_inertia`` (its
        tangential term takes one rate).

    Returns
    -------
    TransientResult
    """
    from .forced import response_setup

    if (rpm is None) == (run is None):
        raise ParameterError("rpm", "give either a steady speed (rpm) or a run (run=(A, B) with rate_rpm_per_s)")
    if not (isinstance(teeth, int) and teeth >= 1):
        raise ParameterError("teeth", f"must be a whole number of teeth >= 1, got {teeth!r}")
    if not (math.isfinite(step_rad) and 0 < step_rad <= MAX_STEP_RAD):
        raise ParameterError("step_rad", f"must be > 0 and at most {MAX_STEP_RAD:.4g} rad "
                                         f"({math.degrees(MAX_STEP_RAD):.4g}°: two steps a period of order "
                                         f"{RESPONSE_HIGHEST_ORDER:g}), got {step_rad!r}")
    if method not in METHODS:
        raise ParameterError("method", f"must be one of {', '.join(METHODS)}")
    if method != "compiled" and any(e.slip_torque > 0 for e in getattr(model, "nonlinear", ())):
        raise ParameterError("method", f"a clutch's slip_torque is integrated by the compiled integrator only, "
                                       f"not {method}")
    if model.excitation is None or model.engine is None:
        raise FetorsionError(f"{model.source or model.name}: the description has no [engine] and [excitation]")
    top = rpm if run is None else max(run)
    lo = rpm if run is None else min(run)
    setup = response_setup(model, partition, rpm=[top], orders=[1.0], damping_ratio=damping_ratio,
                           web_method=web_method)
    dampers = tuple(getattr(model, "dampers", ()))
    notes = []
    M, Kc, C, branches, ring_labels = with_dampers(model, setup, dampers, (lo, top), partition, damping_ratio,
                                                   web_method, notes)
    K, H = np.real(Kc), np.imag(Kc)
    if np.any(H):
        # the Maxwell branches' stiffness at the middle of their band joins K for the modes C_η is set on
        Kmid = K if branches is None else K + branches[0].T @ (branches[3][:, None] * branches[0])
        C = C + hysteretic_equivalent(M, Kmid, H)
        notes.append("loss factors enter as the viscous damping that dissipates as much at each mode's "
                     "resonance (exact there, not between)")
    if branches is not None:
        branches = branches[:3]
    h = step_rad / (top * math.pi / 30)
    from ..lumped_model.lumped import lumped
    from ..lumped_model.network import speed_factors

    res = lumped(model, partition, web_method)
    grounded = res.network is not None and res.network.grounded
    prop = propagator(M, K, C, h, grounded, branches)
    period = cycle_angle(model.engine)
    if run is None:
        if not math.isfinite(prop.settling_s):
            raise FetorsionError(f"{model.name}: an elastic mode has no damping, a steady run never settles; "
                                 "give a modal damping ratio")
        settle = prop.settling_s
        w = rpm * math.pi / 30
        duration = settle + cycles * period / w
        duration, n_of_t, phi_of_t = speed_schedule(rpm, duration_s=duration)
        mode = f"steady running at {rpm:g} rpm"
    else:
        if not (rate_rpm_per_s and rate_rpm_per_s > 0):
            raise ParameterError("rate_rpm_per_s", "a run needs a rate > 0 rpm/s")
        settle = 0.0
        duration, n_of_t, phi_of_t = speed_schedule(run[0], run[1], rate_rpm_per_s)
        mode = f"{'run-up' if run[1] > run[0] else 'run-down'} {run[0]:g}-{run[1]:g} rpm at {rate_rpm_per_s:g} rpm/s"
        if settled_start:
            if variable_inertia:
                raise ParameterError("settled_start", "not with variable inertia (its tangential term takes one rate)")
            if not math.isfinite(prop.settling_s):
                raise FetorsionError(f"{model.name}: an elastic mode has no damping, a held start never settles")
            if getattr(model, "nonlinear", ()) or branches is not None:
                # no periodic state to start from in closed form: hold the start speed until it rings out
                settle = prop.settling_s * math.log(1 / START_SETTLED) / math.log(1 / SETTLED)
                duration, n_of_t, phi_of_t = held_schedule(settle, duration, n_of_t, phi_of_t)
    N = int(duration / h) + 1
    t = np.arange(N) * h
    n_t, phi = n_of_t(t), phi_of_t(t)
    grid, step, table = torque_table(model, lo, top)
    rings = len(M) - len(setup.labels)  # the dampers' rings: coordinates that no cylinder drives
    W = np.pad(setup.load_map[:, 0, :].real, ((0, 0), (0, rings)))  # (cylinders, coordinates)
    elements = tuple(getattr(model, "nonlinear", ()))
    fire = firing_angles(model.engine)

    load = table_load(W, fire, grid, step, table, phi, n_t)

    rigid_speed, start = 0.0, None
    if run is not None and settled_start and settle == 0.0:
        # linear: the run starts in the frequency domain's periodic state at its start speed
        start = periodic_state(M, K, C, W, fire, grid, step, table, run[0], float(phi[0]), period)
        notes.append(f"settled start: the periodic steady state at {run[0]:g} rpm (every harmonic of the torque "
                     "table) as the initial state")
    elif prop.rigid is not None:
        # The mean motion is the schedule's: the rigid-body mode starts at the speed that leaves
        # its first cycle's mean speed zero (from rest it would drift at the mean of ∫φ₀ᵀF dt, and the
        # torque would no longer be in step with the angle that carries it).
        n1 = min(N, int(np.searchsorted(phi, period)) + 1)
        g0 = prop.rigid @ load(0, n1)
        v = np.concatenate([[0.0], np.cumsum(0.5 * h * (g0[:-1] + g0[1:]))])
        rigid_speed = -float(np.trapezoid(v, dx=h) / (h * (n1 - 1)))
    rows = np.pad(np.real(setup.section_rows), ((0, 0), (0, rings)))
    if variable_inertia or elements:
        if branches is not None:
            raise FetorsionError(f"{model.source or model.name}: a rubber damper's dynamic table (its Maxwell "
                                 "states) is not in the nonlinear integrator yet: run without variable inertia")
        q, torque, scheme, work = _nonlinear_run(model, M, K, C, rows, W, fire, prop, rigid_speed, t, n_of_t,
                                                 phi_of_t, run, rate_rpm_per_s, lo, top, elements, variable_inertia,
                                                 method, setup)
    else:
        q = integrate(prop, load, N, rigid_speed, start)
        work = []
        torque = rows @ q
        scheme = "exact modal propagator, first-order hold, lfilter"
    # the tracked station turns at its speed factor times the crank: its angle for the wheel
    factor = 1.0 if res.network is None else float(speed_factors(model)[res.network.masters[track_station]])
    angle = factor * phi + q[track_station]
    revs = int(round(period / (2 * np.pi)))
    k0 = int(np.searchsorted(t, settle)) if run is not None else 0  # a held start is not tracked
    # the schedule's acceleration is known: the bow of the mean rotation comes off exactly, a
    # one-block record included
    alpha = None if run is None else factor * math.copysign(rate_rpm_per_s, run[1] - run[0]) * math.pi / 30
    track = order_track(edge_times(t[k0:], angle[k0:], teeth), teeth, revs, name=setup.labels[track_station],
                        accelerating=run is not None, alpha=alpha)
    # the envelope per block of whole cycles, from the crank's mean motion
    block = np.floor(phi / period).astype(int)
    # the last, unfinished cycle left out, and in a steady run the cycles before it settled
    full = (block < max(block[-1], 1)) & (t >= settle)
    nb = int(block[full].max()) + 1 if full.any() else 0
    peak = np.zeros((nb, torque.shape[0]))
    for s in range(torque.shape[0]):
        np.maximum.at(peak[:, s], block[full], np.abs(torque[s, full]))
    count = np.bincount(block[full], None, nb)
    block_rpm = np.bincount(block[full], n_t[full], nb) / np.maximum(count, 1)
    block_rpm, peak = block_rpm[count > 0], peak[count > 0]
    return TransientResult(model.name, mode, list(setup.labels) + ring_labels, list(setup.section_labels), t, n_t,
                           phi, torque, q, block_rpm, peak, track, h, settle, scheme, notes,
                           setup.labels[track_station], work)


def _nonlinear_run(model, M, K, C, rows, W, fire, prop, rigid_speed, t, n_of_t, phi_of_t, run, rate, lo, top,
                   elements, variable_inertia, method, setup):
    """q (coordinates × N), the section torques, the scheme's description and each element's
    :class:`~fetorsion.response.nonlinear.ElementWork` of a nonlinear run."""
    ne = len(elements)
    tangent = np.array([e.tangent for e in elements])
    D = rows[rows.shape[0] - ne:] / tangent[:, None] if ne else np.zeros((0, M.shape[0]))
    K_lin = K - D.T @ (tangent[:, None] * D)  # the elements' operating stiffness out: they act as they are
    cranks = None
    if variable_inertia:
        if np.any(np.abs(W.sum(axis=1) - 1) > 1e-9):
            raise FetorsionError(f"{model.name}: variable inertia needs every cylinder on a station that turns at "
                                 "the engine's speed (its weights summing to 1)")
        e, ex = model.engine, model.excitation
        cranks = SliderCranks(W, fire, e.crank_radius, e.rod_length, ex.reciprocating_mass)
    grid, step, table = torque_table(model, lo, top, part="gas" if variable_inertia else "total")
    alpha = 0.0 if run is None else math.copysign(rate, run[1] - run[0]) * math.pi / 30
    # the modal damping on the modes of each stick state of the friction elements
    rubbing = [i for i, e in enumerate(elements) if e.friction > 0]
    stuck = None
    if rubbing and setup.zeta > 0:
        stuck = C[None] + stick_damping_changes(np.real(setup.M), np.real(setup.K), setup.zeta, D[rubbing],
                                                Elements(D, elements).stick[rubbing], M.shape[0])

    v0 = None if prop.rigid is None else rigid_speed * prop.rigid
    parts = Elements(D, elements) if ne else None
    slip = np.zeros((ne, t.size))
    if method == "compiled":
        phi, n_t = phi_of_t(t), n_of_t(t)

        load = table_load(W, fire, grid, step, table, phi, n_t)
        q, z, slip, nfev = integrate_compiled(M, K_lin, C, t, phi, n_t * (math.pi / 30), load, cranks, parts, v0,
                                              stuck_damping=stuck)
    else:
        def force(tt):
            return W.T @ read_table(grid, step, table, phi_of_t(tt) - fire, n_of_t(tt))

        q, z, nfev = integrate_nonlinear(M, K_lin, C, t, phi_of_t, lambda tt: n_of_t(tt) * math.pi / 30, alpha,
                                         force, cranks, parts, v0, method, stuck_damping=stuck)
    torque = rows @ q
    work = []
    if ne:
        x = D @ q
        torque[rows.shape[0] - ne:] = parts.torque(x - slip, z)
        work = element_work(elements, x, z, slip, float(t[1] - t[0]))
    what = " and ".join(w for w, on in (("variable inertia", variable_inertia),
                                        (f"{ne} nonlinear element{'s' * (ne > 1)}", ne)) if on)
    how = ("compiled Dormand-Prince 5(4), friction as exact Jenkins elements" if method == "compiled"
           else f"{method} (scipy solve_ivp)")
    if stuck is not None:
        what += ", modal damping on each stick state's modes"
    return q, torque, f"{how}, rtol {RTOL:g}, {nfev} evaluations: {what}", work
