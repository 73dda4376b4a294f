"""The linear time domain: a chain, network or lumped crank at a fixed speed or in a run-up or
run-down at a stated rate, excited by crank-angle-resolved gas and inertia torques (one cylinder
misfiring where asked) and a network's propellers' blade orders (:mod:`.transient_sources`).

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

**Dampers** (:func:`fetorsion.response.transient_model.with_dampers`): each ring is a coordinate, a
viscous or tuned damper's dashpot and spring join C and K; a rubber damper's dynamic table is a
generalised Maxwell model [ParkSchapery] (:func:`fetorsion.lumped_model.damped.maxwell_fit`), each
branch one first-order state in the same exact propagator; a heat-following rubber at the frequency
domain's temperature.

**Order tracking.** A station's simulated angle (mean motion plus vibration) is turned into the
tooth-edge times a toothed wheel of ``teeth`` teeth would give, and these go through the same
:func:`fetorsion.measured.torsiograph.order_track` as a measured record.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg
import scipy.signal

from ..description.chain_model import Chain, Network
from ..description.model import Crank
from ..errors import FetorsionError, ParameterError
from ..excitation.torque import cycle_angle
from ..lumped_model.lumped import lumped
from ..lumped_model.network import speed_factors
from ..measured.torsiograph import OrderTrack, order_track
from .forced import ResponseResult
from .nonlinear import METHODS, nonlinear_run
from .transient_load import held_schedule, periodic_state, rigid_start_speed, speed_schedule
from .propulsion import run_damping
from .transient_sources import blade_state, run_sources
from ..results import from_fields
from .transient_record import (ORDER_CUT_KEYS, StoredRecord, block_envelope, station_order_track, thinned_signals,
                                transient_from_dict)
from .transient_model import hold_coefficients, rigid_and_elastic_modes, transient_matrices
from .time_budget import check_run_fits
# plot_order_cuts: the run's steps import it from here
from .transient_plots import plot_order_cuts, plot_transient, plot_waterfall  # noqa: F401
from ..excitation.campbell import RESPONSE_HIGHEST_ORDER, Crossing
from ..description.defaults import (DEFAULT_PARTITION, DEFAULT_STEP_DEG, DEFAULT_TEETH, DEFAULT_TRANSIENT_CYCLES,
                                    DEFAULT_WEB_METHOD)

#: Crank angle per time step at the top speed, rad: 0.5° (orders to 360 sampled; the force's
#: linear interpolation errs by (qΔθ)²/8 at order q: 1.4e-3 at order 12).
DEFAULT_STEP_RAD = math.radians(DEFAULT_STEP_DEG)
#: The coarsest step: two samples a period of the highest order a response sums (Nyquist).
MAX_STEP_RAD = math.pi / RESPONSE_HIGHEST_ORDER
#: A steady run settles until the slowest elastic transient is this fraction of its start.
SETTLED = 1e-6
#: Samples computed per lfilter call: bounds the memory of a long record.
CHUNK = 1 << 16


#: A held start (:func:`run_transient` ``settled_start``) lasts until the slowest elastic transient is
#: this fraction of its start: the residue is 0.1 % of the start's ringing, below the order track's own
#: resampling error (docs/networks-and-transients.md), at half the cost of :data:`SETTLED`.
START_SETTLED = 1e-3


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
    D, kb, cb = (np.zeros((0, len(M))), np.zeros(0), np.zeros(0)) if branches is None else branches
    rigid, Phi, lam_u = rigid_and_elastic_modes(M, K, C, D.T @ (kb[:, None] * D), grounded)
    m, nb = Phi.shape[1], len(kb)
    Cm = Phi.T @ C @ Phi
    P = D @ Phi  # each branch's twist per modal coordinate
    A = np.block([[np.zeros((m, m)), np.eye(m), np.zeros((m, nb))],
                  [-np.diag(lam_u) - P.T @ (kb[:, None] * P), -Cm, P.T * kb],
                  [(kb / cb)[:, None] * P, np.zeros((nb, m)), -np.diag(kb / cb)]])
    lam, V = scipy.linalg.eig(A)
    Vinv = np.linalg.inv(V)
    E, a, b = hold_coefficients(lam, h)
    return Propagator(h, Phi, lam, V[:m], V[m:2 * m], Vinv[:, m:2 * m], E, a, b, rigid,
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
    #: Read back (:meth:`from_dict`): the run's sample count ``samples``, its last time ``end_s``
    #: and its ``signals`` as stored; ``time_s``, ``rpm`` and the torques then hold the thinned record
    stored: StoredRecord | None = None

    @property
    def samples(self) -> int:
        """The run's time steps (counted when it ran, where a thinned record was read back)."""
        return self.time_s.size if self.stored is None else self.stored.samples

    @classmethod
    def from_dict(cls, d) -> "TransientResult":
        """The result back from its :meth:`to_dict` (:func:`~.transient_record.transient_from_dict`)."""
        return transient_from_dict(cls, d)

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
        kept = thinned_signals(self, every) if self.stored is None else {"end_s": self.stored.end_s,
                                                                         "signals": self.stored.signals}
        return {"name": self.name, "mode": self.mode, "scheme": self.scheme, "step_s": self.step_s,
                "settle_s": self.settle_s, "labels": self.labels, "sections": self.section_labels,
                "notes": self.notes,
                "block_rpm": self.block_rpm.tolist(), "block_peak_torque_nm": self.block_peak_nm.tolist(),
                "order_track": {"station": self.track_station, **self.track.to_dict()},
                "elements": [w.to_dict() for w in self.elements],
                "samples": self.samples, **kept}

    def table(self) -> str:
        """The result as plain text: the table the command line prints."""
        k = int(np.argmax(self.block_peak_nm.max(axis=0)))
        b = int(np.argmax(self.block_peak_nm[:, k]))
        lines = [f"{self.name}: {self.mode}, {self.time_s[-1] if self.stored is None else self.stored.end_s:.2f} s in steps of {self.step_s * 1e6:.1f} us "
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
        return plot_transient(self, ax, orders)

    def waterfall(self, ax=None, max_order: float | None = None, span: float = WATERFALL_SPAN):
        """The order track as a map: the tracked station's vibration (deg, colour on a log scale
        over ``span`` decades below its largest value) against mean speed (rpm) and order, orders
        up to ``max_order`` (default all tracked). Returns the Axes."""
        return plot_waterfall(self, ax, max_order, span)


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

    @classmethod
    def from_dict(cls, d) -> "OrderCut":
        """The cut back from its :meth:`to_dict` (:data:`~.transient_record.ORDER_CUT_KEYS`)."""
        return from_fields(cls, d, ORDER_CUT_KEYS)

    @property
    def difference(self) -> float:
        """The run-up's peak over the steady state's, − 1."""
        return self.runup_deg / self.steady_deg - 1.0

    def to_dict(self) -> dict:
        return {"order": self.order, "mode": self.mode, "mode_hz": self.mode_hz, "crossing_rpm": self.crossing_rpm,
                "passage_alpha_over_gamma2": self.passage, "steady_peak_deg": self.steady_deg,
                "steady_peak_rpm": self.steady_rpm, "runup_peak_deg": self.runup_deg,
                "runup_peak_rpm": self.runup_rpm, "difference": self.difference}


def order_cuts(result: TransientResult, response: ResponseResult, crossings: Sequence[Crossing],
               damping_ratio: float | Sequence[float], rate_rpm_per_s: float,
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
        if not (s.any() and r.any()):  # a fast run's order track has no sample this near the crossing
            continue
        steady, cut = response.order_pulley_deg[s, int(k[0])], np.degrees(np.abs(result.track.at(q)[r]))
        i, j = int(np.argmax(steady)), int(np.argmax(cut))
        out.append(OrderCut(q, c.mode, c.frequency_hz, n,
                            float(q * rate_rpm_per_s * np.pi / 30 / (zeta * omega) ** 2) if zeta > 0 else math.inf,
                            float(steady[i]), float(response.rpm[s][i]), float(cut[j]), float(result.track.rpm[r][j])))
    return tuple(out)



def run_transient(model: Crank | Chain | Network, rpm: float | None = None, run: tuple[float, float] | None = None,
                  rate_rpm_per_s: float | None = None, cycles: int = DEFAULT_TRANSIENT_CYCLES,
                  damping_ratio: float | None = None, partition: int = DEFAULT_PARTITION,
                  web_method: str = DEFAULT_WEB_METHOD, step_rad: float = DEFAULT_STEP_RAD, teeth: int = DEFAULT_TEETH,
                  track_station: int = 0, variable_inertia: bool = False, method: str = METHODS[0],
                  settled_start: bool = False, misfire: int | None = None, propellers: bool = True) -> TransientResult:
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
        run-up: a linear model in the periodic steady state at A
        (:func:`fetorsion.response.transient_load.periodic_state`, from the frequency domain); a
        model with nonlinear elements or a rubber table's Maxwell states first holds A until the
        slowest elastic transient of starting from rest has fallen to :data:`START_SETTLED` of its
        size (the envelope and the order track begin after the hold, ``settle_s``). Without it the
        run starts from rest at speed A and its first cycles ring with the lightly damped modes (a
        driveline's, for seconds). Not with ``variable_inertia`` (its tangential term takes one rate).
    misfire : int, optional
        This 0-based cylinder runs its motored cycle, the others fire (linear runs only).
    propellers : bool
        A network's propellers' blade orders load the run with the engine's
        (:mod:`fetorsion.response.transient_sources`; linear runs only).

    Returns
    -------
    TransientResult

    Examples
    --------
    >>> import fetorsion
    >>> line = fetorsion.load("examples/networks/conventional_flywheel.toml")
    >>> res = fetorsion.run_transient(line, rpm=2000.0, cycles=2)  # steady running, two engine cycles
    >>> res.mode, bool(res.time_s[-1] > 2 * 60 / 1000)  # a four-stroke cycle is two revolutions: 0.06 s each
    ('steady running at 2000 rpm', True)
    """
    _check_arguments(model, rpm, run, teeth, step_rad, method)
    model, law_notes = run_damping(model, rpm)
    lo, top = (rpm, rpm) if run is None else (min(run), max(run))
    setup, M, K, C, branches, ring_labels, notes = transient_matrices(model, (lo, top), partition, damping_ratio,
                                                                      web_method)
    h = step_rad / (top * math.pi / 30)
    res = lumped(model, partition, web_method)
    grounded = res.network is not None and res.network.grounded
    prop = propagator(M, K, C, h, grounded, branches)
    period = cycle_angle(model.engine)
    settle, duration, n_of_t, phi_of_t, mode = _schedule(model, prop, rpm, run, rate_rpm_per_s, cycles, period,
                                                         settled_start, variable_inertia, branches)
    N = check_run_fits(duration, step_rad, top, len(M), len(setup.section_labels), run)  # or refused, by name
    t = np.arange(N) * h
    n_t, phi = n_of_t(t), phi_of_t(t)
    rings = len(M) - len(setup.labels)  # the dampers' rings: coordinates that no cylinder drives
    src = run_sources(model, setup, rings, (lo, top), phi, n_t, misfire, propellers)
    W, fire, load, elements = src.W, src.fire, src.load, tuple(getattr(model, "nonlinear", ()))
    notes += src.notes + law_notes
    rigid_speed, start = 0.0, None
    if run is not None and settled_start and settle == 0.0:
        # linear: the run starts in the frequency domain's periodic state at its start speed
        start = periodic_state(M, K, C, W, fire, src.grid, src.step, src.table, run[0], float(phi[0]), period)
        start = tuple(a + b for a, b in zip(start, blade_state(M, K, C, src.blades, run[0], float(phi[0]))))
        notes.append(f"settled start: the periodic steady state at {run[0]:g} rpm (every harmonic of the torque "
                     "table) as the initial state")
    elif prop.rigid is not None:
        # the mean motion is the schedule's: the rigid-body mode starts at the speed that leaves its
        # first cycle's mean speed zero
        rigid_speed = rigid_start_speed(prop.rigid, load, phi, period, h)
    rows = np.pad(np.real(setup.section_rows), ((0, 0), (0, rings)))
    if variable_inertia or elements:
        if src.blades or misfire is not None:
            raise FetorsionError(f"{model.source or model.name}: the nonlinear integrator carries the engine's "
                                 "firing excitation only (no propeller blade orders, no misfire)")
        if branches is not None:
            raise FetorsionError(f"{model.source or model.name}: a rubber damper's dynamic table (its Maxwell "
                                 "states) is not in the nonlinear integrator yet: run without variable inertia")
        q, torque, scheme, work = nonlinear_run(model, M, K, C, rows, W, fire, prop, rigid_speed, t, n_of_t,
                                                phi_of_t, run, rate_rpm_per_s, lo, top, elements, variable_inertia,
                                                method, setup)
    else:
        q = integrate(prop, load, N, rigid_speed, start)
        work = []
        torque = rows @ q
        scheme = "exact modal propagator, first-order hold, lfilter"
    # the tracked station turns at its speed factor times the crank: its angle for the wheel
    factor = 1.0 if res.network is None else float(speed_factors(model)[res.network.masters[track_station]])
    track = station_order_track(t, factor * phi + q[track_station], settle, run, rate_rpm_per_s, factor, period, teeth,
                         setup.labels[track_station])
    block_rpm, peak = block_envelope(t, n_t, phi, torque, period, settle)
    return TransientResult(model.name, mode, list(setup.labels) + ring_labels, list(setup.section_labels), t, n_t,
                           phi, torque, q, block_rpm, peak, track, h, settle, scheme, notes,
                           setup.labels[track_station], work)


def _check_arguments(model, rpm, run, teeth, step_rad: float, method: str) -> None:
    """Refuse, by name, the arguments of :func:`run_transient` that cannot make a run."""
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


def _schedule(model, prop: Propagator, rpm, run, rate_rpm_per_s, cycles: int, period: float, settled_start: bool,
              variable_inertia: bool, branches):
    """The run's mean motion: (settling or held time s, duration s, n(t) rpm, φ(t) rad, the run in words)."""
    if run is None:
        if not math.isfinite(prop.settling_s):
            raise FetorsionError(f"{model.name}: an elastic mode has no damping, a steady run never settles; "
                                 "give a modal damping ratio")
        settle = prop.settling_s
        w = rpm * math.pi / 30
        duration = settle + cycles * period / w
        duration, n_of_t, phi_of_t = speed_schedule(rpm, duration_s=duration)
        return settle, duration, n_of_t, phi_of_t, f"steady running at {rpm:g} rpm"
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
    return settle, duration, n_of_t, phi_of_t, mode
