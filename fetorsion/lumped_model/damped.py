"""A chain's matrices with torsional dampers attached: one extra degree of freedom
per damper ring, the hub or housing added to its station. Here, before the excitation stage,
so that the Campbell analysis and the forced response see the same damped system; the
classical optima and the tuning live in :mod:`fetorsion.design.dampers`.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from ..errors import FetorsionError

if TYPE_CHECKING:
    from collections.abc import Callable, Iterable, Sequence
    from typing import TypeVar

    from ..description.model import Damper

    _T = TypeVar("_T")
    _R = TypeVar("_R")


def attach(M, K, C, station: int, ring_inertia: float, stiffness: float = 0.0, damping: float = 0.0,
           loss_factor: float = 0.0, housing_inertia: float = 0.0):
    """The chain's matrices with a damper on ``station``: its ring becomes a last degree of freedom.

    Parameters
    ----------
    M, K, C : ndarray (n, n)
        Inertia (kg·m²), stiffness (N·m/rad, may be complex: hysteretic springs) and damping
        (N·m·s/rad) of the chain.
    station : int
        0-based station that carries the damper.
    ring_inertia : float
        Seismic ring, kg·m².
    stiffness : float
        Spring between station and ring, N·m/rad (0: a viscous damper).
    damping : float
        Viscous coefficient between station and ring, N·m·s/rad.
    loss_factor : float
        Hysteretic loss factor of the spring (rubber), on ``stiffness``.
    housing_inertia : float
        Housing or hub, added to the station, kg·m².

    Returns
    -------
    M, K, C : ndarray (n + 1, n + 1)
    """
    if not ring_inertia > 0:
        raise FetorsionError(f"damper ring inertia {ring_inertia!r}: must be > 0 kg m^2")
    n = len(M)
    joint = np.zeros((n + 1, n + 1))
    joint[[station, n], [station, n]] = 1.0
    joint[[station, n], [n, station]] = -1.0

    def grow(A):
        out = np.zeros((n + 1, n + 1), dtype=np.result_type(A, float))
        out[:n, :n] = A
        return out

    M2 = grow(M)
    M2[station, station] += housing_inertia
    M2[n, n] = ring_inertia
    spring = stiffness * (1.0 + 1j * loss_factor) if loss_factor else stiffness
    return M2, grow(K) + spring * joint, grow(C) + damping * joint


def damper_station(damper: Damper, n: int) -> int:
    """0-based station carrying ``damper`` on a chain of ``n`` stations: the first (pulley end,
    ``at = "front"``) or the last (flywheel side, ``"rear"``)."""
    return 0 if damper.at == "front" else n - 1


def damper_spring(damper, omegas) -> np.ndarray:
    """Complex spring k(ω)(1 + iη(ω)) of ``damper`` (N·m/rad) at ``omegas`` (rad/s).

    A rubber damper's ``table`` (frequency Hz, dynamic stiffness, loss factor) is interpolated
    linearly in frequency and held at its end values outside it (no extrapolation of a
    measured property); without a table the stiffness and loss factor are constant.
    """
    omegas = np.asarray(omegas, dtype=float)
    if damper.table:
        f, k, eta = (np.asarray(c) for c in zip(*damper.table))
        hz = omegas / (2 * np.pi)
        return np.interp(hz, f, k) * (1 + 1j * np.interp(hz, f, eta))
    return np.full(omegas.shape, damper.stiffness * (1 + 1j * damper.loss_factor))


def referred_damper(damper, factor: float):
    """``damper`` referred to a coordinate that turns 1/f times as fast as its station
    (``factor`` = f²): inertias, springs (its table's too) and dashpot times f², so that its
    energies and heat in the coordinate's angle are those of the damper on the station."""
    if factor == 1.0:
        return damper
    from dataclasses import replace

    return replace(damper, hub_inertia=damper.hub_inertia * factor, ring_inertia=damper.ring_inertia * factor,
                   stiffness=damper.stiffness * factor, damping=damper.damping * factor,
                   table=tuple((f, k * factor, e) for f, k, e in damper.table),
                   temperature_table=tuple((T, f, k * factor, e) for T, f, k, e in damper.temperature_table))


class DampedSystem:
    """A chain's matrices with its dampers' rings appended as the last degrees of freedom.

    ``M``, ``C`` and ``K`` hold the chain, the hubs (added to their stations), the rings and
    the viscous dashpots; the damper springs, which may depend on frequency, are added per
    frequency by :meth:`matrix`. ``stations`` (the chain's size) and ``rings`` (index of each
    damper's ring) locate the DOF. Works for any reduced matrices (a lumped chain or a
    condensed FE crank): only (M, K, C, station) are used.
    """

    def __init__(self, M, K, C, dampers=(), stations: int | None = None, at=None, scale=None):
        n = len(M) if stations is None else stations
        # ``scale``: a function of the damper, f² for one on a station that turns f times its
        # coordinate's speed (a network's geared station): its ring is referred to the coordinate
        dampers = tuple(dampers) if scale is None else tuple(referred_damper(d, scale(d)) for d in dampers)
        self.stations, self.dampers, self.rings, self.carriers, self.joints = n, dampers, [], [], []
        for d in self.dampers:
            # ``at``: one station for every damper, or a function of the damper (a condensed crank's
            # front or rear master twist)
            s = damper_station(d, n) if at is None else (at(d) if callable(at) else at)
            M, K, C = attach(M, K, C, s, d.ring_inertia, 0.0, d.damping, 0.0, d.hub_inertia)
            ring = len(M) - 1
            self.rings.append(ring)
            self.carriers.append(s)
            self.joints.append((s, ring))
        self.M, self.K, self.C = M, K, C

    def _spring_terms(self, omegas):
        """Σ_d k_d(ω) J_d, shape omegas.shape + (N, N)."""
        omegas = np.asarray(omegas, dtype=float)
        N = len(self.M)
        out = np.zeros(omegas.shape + (N, N), dtype=complex)
        for d, (s, r) in zip(self.dampers, self.joints):
            k = damper_spring(d, omegas)
            out[..., s, s] += k
            out[..., r, r] += k
            out[..., s, r] -= k
            out[..., r, s] -= k
        return out

    def matrix(self, omegas) -> np.ndarray:
        """K − ω²M + iωC + Σ k_d(ω)(1 + iη_d(ω)) J_d for every ω (rad/s): shape omegas.shape + (N, N)."""
        w = np.asarray(omegas, dtype=float)[..., None, None]
        return self.K - w**2 * self.M + 1j * w * self.C + self._spring_terms(omegas)

    def nominal(self, omega: float = 0.0):
        """(M, real K, C, H): the springs' real stiffness and hysteretic part at ``omega`` (rad/s),
        for undamped modes and their equivalent damping."""
        S = self._spring_terms(np.asarray(omega))
        K = self.K + S
        return self.M, np.real(K), self.C, np.imag(K)

    def dissipated_power(self, theta, omegas) -> np.ndarray:
        """Mean power each damper turns into heat, W: ½ ω (ω c + Im k(ω)) |θ_station − θ_ring|².

        ``theta`` (..., N) complex amplitudes at ``omegas`` (...) rad/s; returns (..., dampers).
        """
        omegas = np.asarray(omegas, dtype=float)
        out = []
        for d, (s, r) in zip(self.dampers, self.joints):
            rel = np.abs(theta[..., s] - theta[..., r]) ** 2
            out.append(0.5 * omegas * (omegas * d.damping + np.imag(damper_spring(d, omegas))) * rel)
        return np.stack(out, axis=-1) if out else np.zeros(omegas.shape + (0,))


def viscous_impedance(damper, omega) -> complex:
    """Dynamic stiffness a viscous damper's ring adds to its station at ω (rad/s), N·m/rad:
    the ring J_r on the dashpot c gives D(ω) = iωc (−ω²J_r) / (iωc − ω²J_r); its imaginary part
    is the damping the station feels, its real part the ring inertia it drags along (the ring
    term of :func:`damper_impedance`, whose spring is zero here)."""
    return -(omega**2) * damper.ring_inertia * ring_transmission(damper, omega)


def damped_modes(inertias: Sequence[float] | np.ndarray, stiffnesses: Sequence[float] | np.ndarray,
                 pin_weights: np.ndarray, dampers: Sequence[Damper], source: str = "chain"):
    """Undamped modes of a chain with its dampers, and the damping ratio each mode gains from them.

    A rubber or tuned damper's ring is a degree of freedom on its spring (stiffness at 0 Hz,
    the first row of a dynamic table); a viscous damper's ring, held by fluid only, has no
    undamped mode of its own: its housing adds to the station and its ring acts through
    :func:`viscous_impedance`. The gained damping ratio of mode j (frequency ω_j, shape φ_j,
    modal inertia m_j) is the modal diagonal of the dampers' losses at ω_j:
    ζ_j = (ω_j φᵀCφ + φᵀ Im K(ω_j) φ + φ_s² Im D(ω_j)) / (2 ω_j² m_j).

    Returns
    -------
    (TorsionalModes, ndarray)
        The modes (pin amplitudes over the chain's stations, pulley at station 0) and the
        gained damping ratio per mode.
    """
    from .lumped import chain_matrices

    M, K = chain_matrices(inertias, stiffnesses)
    return damped_modes_of(M, K, pin_weights, dampers, source)


def damped_modes_of(M: np.ndarray, K: np.ndarray, pin_weights: np.ndarray, dampers: Sequence[Damper],
                    source: str = "chain", at: Callable[[Damper], int] | None = None,
                    scale: Callable[[Damper], float] | None = None):
    """:func:`damped_modes` of any model given by its matrices (a chain's, or a network's in its
    reduced coordinates with the gears' ratios in them): ``at`` and ``scale`` place and refer
    each damper as :class:`DampedSystem` does (None: a chain's front and rear stations, f = 1)."""
    import scipy.linalg

    from ..modes import TorsionalModes

    n = len(M)
    springy = [d for d in dampers if d.kind != "viscous"]
    system = DampedSystem(M, K, np.zeros_like(M), springy, stations=n, at=at, scale=scale)
    Mn, Kn, C, _ = system.nominal(0.0)
    Mn = Mn.copy()
    viscous = [(d if scale is None else referred_damper(d, scale(d)), damper_station(d, n) if at is None else at(d))
               for d in dampers if d.kind == "viscous"]
    for d, s in viscous:
        Mn[s, s] += d.hub_inertia
    lam, vec = scipy.linalg.eigh(Kn, Mn)
    shapes = vec[:, 1:].T  # the rigid-body mode first
    shapes = shapes / np.where(np.abs(shapes[:, 0]) > 1e-9, shapes[:, 0], 1.0)[:, None]
    omega = np.sqrt(np.clip(lam[1:], 0.0, None))
    m = np.einsum("js,st,jt->j", shapes, Mn, shapes)
    loss = np.einsum("js,st,jt->j", shapes, C, shapes) * omega
    for j, w in enumerate(omega):
        H = system.nominal(w)[3] if springy else np.zeros_like(Mn)
        loss[j] += shapes[j] @ H @ shapes[j]
        for d, s in viscous:
            loss[j] += shapes[j, s] ** 2 * np.imag(viscous_impedance(d, w))
    modes = TorsionalModes(source=source, frequencies_hz=omega / (2 * np.pi),
                           pin_amplitudes=shapes[:, :n] @ np.asarray(pin_weights).T,
                           pulley_amplitude=shapes[:, 0], modal_inertia=m)
    return modes, loss / (2 * omega**2 * m)


def ring_transmission(damper, omegas) -> np.ndarray:
    """θ_ring / θ_station of ``damper``'s ring at ``omegas`` (rad/s): the ring J_r on its spring and
    dashpot κ(ω) = k(ω) + iωc moves as κ / (κ − ω² J_r)."""
    w = np.asarray(omegas, dtype=float)
    kappa = damper_spring(damper, w) + 1j * w * damper.damping
    return kappa / (kappa - w**2 * damper.ring_inertia)


def damper_impedance(damper, omegas) -> np.ndarray:
    """Dynamic stiffness (N·m/rad) that ``damper`` adds to its station at ``omegas`` (rad/s), its
    ring condensed out exactly: −ω² J_hub + κ (θ_s − θ_r)/θ_s = −ω² J_hub − ω² J_r κ / (κ − ω² J_r)
    (:func:`viscous_impedance` is the case k = 0, without the hub)."""
    w = np.asarray(omegas, dtype=float)
    return -(w**2) * (damper.hub_inertia + damper.ring_inertia * ring_transmission(damper, w))


#: A projected solve keeps every undamped mode of the system (crank and rings) below this
#: multiple of the highest excitation frequency, at least MIN_MODES; the modes above it act
#: statically (their dynamic amplification there is at most 1/(1 − 1/3²) = 1.125, on a part
#: that is itself small).
DAMPED_CUTOFF = 3.0
MIN_MODES = 30
#: Complex entries of the kept-mode matrices a projected solve builds at once (a chunk of the
#: frequencies): 2**21 entries, 32 MiB.
PROJECTED_CHUNK_ENTRIES = 2**21
#: Threads over a projected solve's chunks (None: one per core this process may use).
PROJECTED_THREADS = None


def projected_solve(system: DampedSystem, forces: np.ndarray, omegas: np.ndarray, gyroscopic: np.ndarray | None = None,
                    spin: float | np.ndarray | None = None) -> np.ndarray:
    """Complex amplitudes x (..., N) of ``system`` under ``forces`` (..., stations) at ``omegas`` (...)
    rad/s, for a large reduced model (a condensed crank: ~200 DOF) at thousands of frequencies.

    The system is solved in the basis of its own undamped modes (springs at their stiffness at
    half the highest ω) below :data:`DAMPED_CUTOFF` × the highest ω, with the frequency-dependent
    damper springs and the full, non-proportional damping matrix projected on them (small dense
    solves; the imaginary part of K, loss factors of the model's own springs, likewise); the
    modes above act through their static flexibility (mode-acceleration correction), so static
    loads come out exactly. Zero-frequency modes (rigid rotation; axial
    motion without a thrust bearing) are kept dynamic; a static load on them has no solution.

    ``gyroscopic`` (stations × stations, skew, per unit spin speed) with ``spin`` (rad/s,
    broadcast against ``omegas``) adds the rotating frame's Coriolis term i ω Ω G: a velocity
    coupling like damping, projected on the same modes (it has no static part).

    ``forces`` of shape omegas.shape + (r, stations) are r right-hand sides at each frequency,
    solved on one factorisation of that frequency's matrix; the result is then (..., r, N).
    """
    om = np.asarray(omegas, float)
    block = forces.ndim == om.ndim + 2
    if not block:
        forces = forces[..., None, :]
    Mn, Kn, _, _ = system.nominal(float(om.max()) / 2)
    lam, Phi, count = _undamped_basis(Mn, Kn, om.max())
    low, high = Phi[:, :count], Phi[:, count:]
    F = np.zeros(forces.shape[:-1] + (len(Mn),), complex)
    F[..., :system.stations] = forces
    # In this basis M is I and K + Re Σ k_d(nominal) J_d is diag(λ): only iωC and each damper's
    # departure from its nominal spring fill the matrices (two passes over the big array).
    Cp = low.T @ system.C @ low
    Hs = np.imag(system.K)  # loss factors of the model's own springs (a network's shafts): i H on the kept modes
    Hp = low.T @ Hs @ low if np.any(Hs) else None
    U = [low[s] - low[r] for s, r in system.joints]
    nominal = system._spring_terms(np.asarray(float(om.max()) / 2))
    if gyroscopic is not None:
        Gll, Glh, Ghl, H = _coriolis_on_modes(gyroscopic, system.stations, low, high, lam[count:])
        spin_all = np.broadcast_to(np.asarray(spin, float), om.shape)
    # the frequencies in chunks: each chunk's kept-mode matrices (chunk × count² complex) stay a
    # few tens of MB, not the whole sweep's (a condensed crank's 300 speeds × 48 orders × 80² is
    # 1.5 GB) — the same arithmetic, memory bounded and cache-friendly
    flat_om = om.reshape(-1)
    flat_F = F.reshape((-1,) + F.shape[om.ndim:])
    flat_spin = spin_all.reshape(-1) if gyroscopic is not None else None
    x = np.empty(flat_F.shape, complex)
    step = max(1, PROJECTED_CHUNK_ENTRIES // max(count * count, 1))

    def chunk(a):
        b = min(a + step, len(flat_om))
        w, Fc = flat_om[a:b], flat_F[a:b]
        A = np.multiply(1j * w[:, None, None], Cp)
        if Hp is not None:
            A += 1j * Hp
        rhs = complex_times(Fc, low)  # (chunk, r, kept)
        Fh = complex_times(Fc, high) / lam[count:] if high.shape[1] else None
        if gyroscopic is not None:
            wO = w * flat_spin[a:b]
            A += (1j * wO)[:, None, None] * Gll
            if Fh is not None:
                A += (wO**2)[:, None, None] * H
                rhs = rhs - (1j * wO)[:, None, None] * complex_times(Fh, np.ascontiguousarray(Glh.T))
        diag = np.einsum("...ii->...i", A)
        diag += lam[:count] - w[:, None] ** 2
        _add_damper_departures(A, system, U, nominal, w)
        xi = np.swapaxes(np.linalg.solve(A, np.swapaxes(rhs, -1, -2)), -1, -2)
        xc = complex_times(xi, np.ascontiguousarray(low.T))
        if Fh is not None:
            if gyroscopic is not None:
                Fh = Fh - (1j * wO)[:, None, None] * complex_times(xi, np.ascontiguousarray(Ghl.T / lam[count:]))
            xc = xc + complex_times(Fh, np.ascontiguousarray(high.T))
        x[a:b] = xc

    # the chunks are independent, and numpy's stacked solves and products release the interpreter
    threaded_map(chunk, range(0, len(flat_om), step), PROJECTED_THREADS)
    x = x.reshape(F.shape)
    return x if block else x[..., 0, :]


def _undamped_basis(Mn, Kn, highest):
    """(λ, M-orthonormal undamped modes Φ, how many lowest are kept dynamic up to ``highest`` rad/s)."""
    L = np.linalg.cholesky(Mn)
    Linv = np.linalg.inv(L)
    lam, Y = np.linalg.eigh(Linv @ Kn @ Linv.T)
    Phi = Linv.T @ Y
    count = max(MIN_MODES, int((np.sqrt(np.clip(lam, 0, None)) < DAMPED_CUTOFF * highest).sum()))
    return lam, Phi, min(count, len(lam))


def _coriolis_on_modes(gyroscopic, stations: int, low, high, lam_high):
    """(G_ll, G_lh, G_hl, G_lh Λ_h⁻¹ G_hl or None) of the Coriolis matrix on the kept (l) and condensed (h) modes."""
    # Coriolis coupling i ω Ω G: among the kept modes in full; with the others condensed out
    # statically (η = Λ_h⁻¹ (F_h − i ω Ω G_hl ξ)), which adds (ω Ω)² G_lh Λ_h⁻¹ G_hl to the kept
    # modes' matrix and − i ω Ω G_lh Λ_h⁻¹ F_h to their load: the high modes carry a good part
    # of the pins' and journals' Coriolis forces (without them the truncation misses 20 % of
    # the Coriolis effect on the Renault's fillet torques)
    size = low.shape[0]
    Gn = np.zeros((size, size))
    Gn[:stations, :stations] = gyroscopic
    Gll, Glh, Ghl = low.T @ Gn @ low, low.T @ Gn @ high, high.T @ Gn @ low
    H = (Glh / lam_high) @ Ghl if lam_high.size else None
    return Gll, Glh, Ghl, H


def _add_damper_departures(A, system: DampedSystem, U, nominal, w) -> None:
    """Add to the kept modes' matrices ``A`` (in place) each damper's spring at ``w`` less its nominal one."""
    for d, u, (s, _) in zip(system.dampers, U, system.joints):
        k = damper_spring(d, w) - np.real(nominal[s, s])
        A += k[:, None, None] * np.outer(u, u)


def threaded_map(fn: Callable[[_T], _R], items: Iterable[_T], threads: int | None = None) -> list[_R]:
    """``[fn(x) for x in items]`` on ``threads`` threads (None: one per core this process may
    use), each thread's BLAS on one thread: for independent pieces of numpy work that release
    the interpreter (a projected solve's frequency chunks, the ``fe`` path's places)."""
    items = list(items)
    usable = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1
    workers = min(threads or usable, len(items))
    if workers <= 1:
        return [fn(x) for x in items]
    from concurrent.futures import ThreadPoolExecutor

    from threadpoolctl import threadpool_limits

    with threadpool_limits(1), ThreadPoolExecutor(workers) as pool:
        return list(pool.map(fn, items))


def unit_torques(shape: tuple, stations: int, places: Sequence[int]) -> np.ndarray:
    """A unit torque at each DOF of ``places``, as a block of right-hand sides of
    :func:`projected_solve`: shape ``shape + (len(places), stations)``, the unit responses
    :func:`with_dampers` reads."""
    out = np.zeros(tuple(shape) + (len(places), stations))
    out[..., np.arange(len(places)), list(places)] = 1.0
    return out


def with_dampers(x0: np.ndarray, unit: np.ndarray, places: list, system: DampedSystem,
                 omegas: np.ndarray) -> np.ndarray:
    """θ (..., N) of ``system`` — a model with its dampers' rings appended — from the model's own
    response without them: ``x0`` (..., stations) under the loads and ``unit`` (..., places,
    stations) under a unit torque at each DOF of ``places`` (those that carry a damper among them).

    Each damper acts on its station as the dynamic stiffness :func:`damper_impedance` z(ω), so
    with Z the stations' summed z and E their unit columns, (A + E Z Eᵀ) θ = F gives the stations'
    angles y from (I + Eᵀ A⁻¹ E Z) y = Eᵀ x0 and θ = x0 − A⁻¹ E Z y (Woodbury): exact for any
    number of dampers, a small solve per frequency instead of the damped model's own.
    The rings follow their stations by :func:`ring_transmission`.
    """
    omegas = np.asarray(omegas, dtype=float)
    at = sorted(set(system.carriers))
    U = unit[..., [places.index(s) for s in at], :]  # (..., m, stations): response to a unit torque at each
    Z = np.zeros(omegas.shape + (len(at),), complex)
    for d, s in zip(system.dampers, system.carriers):
        Z[..., at.index(s)] += damper_impedance(d, omegas)
    A = np.eye(len(at)) + np.swapaxes(U[..., at], -1, -2) * Z[..., None, :]
    y = np.linalg.solve(A, x0[..., at][..., None])[..., 0]
    x = x0 - np.einsum("...j,...jn->...n", Z * y, U)
    rings = [ring_transmission(d, omegas) * x[..., s] for d, s in zip(system.dampers, system.carriers)]
    return np.concatenate([x, np.stack(rings, axis=-1)], axis=-1)


def complex_times(Z: np.ndarray, B: np.ndarray) -> np.ndarray:
    """Z @ B for complex Z (..., n) and real B (n, k) as two real matrix products on 2-D views
    (numpy's stacked complex-by-real matmul does not reach BLAS and is up to 30× slower)."""
    z = Z.reshape(-1, Z.shape[-1])
    out = (np.ascontiguousarray(z.real) @ B) + 1j * (np.ascontiguousarray(z.imag) @ B)
    return out.reshape(Z.shape[:-1] + (B.shape[1],))


#: Maxwell branches per decade of the band a rubber damper's complex stiffness is fitted over
#: (:func:`maxwell_fit`): each branch's loss peaks over about a decade, so three a decade leave
#: little ripple on a flat loss factor.
MAXWELL_PER_DECADE = 3
#: The branches' relaxation frequencies reach this factor beyond the fitted band at each end (a
#: band edge then lies inside the branches' reach, not on the last one's flank).
MAXWELL_MARGIN = 2.0
#: Fit points per decade of the band (besides the table's own rows).
MAXWELL_SAMPLES = 40


@dataclass(frozen=True)
class MaxwellFit:
    """A rubber's complex stiffness as a generalised Maxwell (Prony) model [ParkSchapery]: a
    spring ``k_inf`` in parallel with branches of a spring ``stiffness[i]`` in series with a
    dashpot ``damping[i]`` (relaxation time τ_i = c_i/k_i),

        k*(ω) = k∞ + Σ k_i iωτ_i / (1 + iωτ_i),

    fitted over ``band_hz``; ``stiffness_error`` (largest |k*_fit/k*_table − 1|) and ``loss_error``
    (largest |η_fit − η_table|) at the table's own rows inside the band, and ``band_*`` the same
    over the whole band's fit points."""

    k_inf: float
    stiffness: np.ndarray
    damping: np.ndarray
    band_hz: tuple
    stiffness_error: float
    loss_error: float
    band_stiffness_error: float
    band_loss_error: float

    def spring(self, omegas) -> np.ndarray:
        """k*(ω) of the fitted model, N·m/rad, at ``omegas`` (rad/s)."""
        w = np.asarray(omegas, float)[..., None]
        iwt = 1j * w * self.damping / self.stiffness
        return self.k_inf + np.sum(self.stiffness * iwt / (1 + iwt), axis=-1)


def maxwell_fit(damper: Damper) -> MaxwellFit:
    """Fit a rubber damper's dynamic table (:func:`damper_spring`: linear between its rows) over
    the table's frequencies by a generalised Maxwell model with relaxation frequencies fixed
    log-uniformly and non-negative weights by least squares [ParkSchapery]: each point's real and
    imaginary parts relative to its |k*| (a relative fit at every frequency). Returns a
    :class:`MaxwellFit` with its error at the table's rows and over the band.
    """
    from scipy.optimize import nnls

    rows = np.array(damper.table, float).reshape(-1, 3)
    if len(rows) < 2:
        raise FetorsionError(f"damper '{damper.name}': a Maxwell fit needs its dynamic table (>= 2 rows)")
    f_lo, f_hi = rows[0, 0], rows[-1, 0]
    decades = max(np.log10(f_hi / f_lo), 0.0)
    band = np.logspace(np.log10(f_lo), np.log10(f_hi), max(2, int(np.ceil(decades * MAXWELL_SAMPLES)) + 1))
    f = np.union1d(band, rows[:, 0])
    reach = decades + 2 * np.log10(MAXWELL_MARGIN)
    poles = np.logspace(np.log10(f_lo / MAXWELL_MARGIN), np.log10(f_hi * MAXWELL_MARGIN),
                        max(2, int(np.ceil(reach * MAXWELL_PER_DECADE)) + 1))  # 1/(2πτ_i), Hz
    target = damper_spring(damper, 2 * np.pi * f)
    x = f[:, None] / poles[None, :]  # ωτ_i
    basis = np.concatenate([np.ones((f.size, 1)), 1j * x / (1 + 1j * x)], axis=1) / np.abs(target)[:, None]
    A = np.concatenate([basis.real, basis.imag])
    b = np.concatenate([(target / np.abs(target)).real, (target / np.abs(target)).imag])
    w, _ = nnls(A, b)
    keep = w[1:] > 0
    k = w[1:][keep]
    fit = MaxwellFit(float(w[0]), k, k / (2 * np.pi * poles[keep]), (float(f_lo), float(f_hi)), 0.0, 0.0, 0.0, 0.0)

    def errors(freqs):
        ref, got = damper_spring(damper, 2 * np.pi * freqs), fit.spring(2 * np.pi * freqs)
        return (float(np.max(np.abs(np.abs(got) / np.abs(ref) - 1))),
                float(np.max(np.abs(got.imag / got.real - ref.imag / ref.real))))

    return replace(fit, **dict(zip(("stiffness_error", "loss_error"), errors(rows[:, 0]))),
                   **dict(zip(("band_stiffness_error", "band_loss_error"), errors(f))))
