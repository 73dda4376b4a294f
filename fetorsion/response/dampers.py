"""Torsional dampers on a lumped chain, and their classical optima (issue 14, first part).

A damper adds one degree of freedom, its ring (seismic mass), joined to the station that
carries it (the pulley or the flywheel) by a spring k (tuned absorber, rubber damper; none
for a viscous Houdaille damper), a viscous coefficient c and a hysteretic loss factor η on k.
The housing or hub simply adds its inertia to that station. :func:`attach` returns the
augmented matrices; the forced response then solves them like any chain.

Den Hartog's optima for a damper on an undamped single-degree-of-freedom system (inertia J,
stiffness k to ground, ω_n = √(k/J)), with μ = J_ring / J:

* untuned viscous (Lanchester, Houdaille) damper: ζ_opt = c_opt / (2 J_ring ω_n)
  = 1 / √(2 (1 + μ)(2 + μ)), peak amplification 1 + 2/μ;
* tuned absorber: ring frequency ratio f_opt = 1/(1 + μ), ζ_opt = √(3μ / (8 (1 + μ)³))
  (c = 2 ζ J_ring ω_n), and every damping's response curve passes through two fixed points of
  height √(1 + 2/μ), which f_opt makes equal.
"""

from __future__ import annotations

import numpy as np
import scipy.optimize

from ..errors import FetorsionError


def viscous_optimum(mu: float) -> tuple[float, float]:
    """Den Hartog's untuned viscous damper: (optimum ζ = c/(2 J_ring ω_n), peak amplification)."""
    return 1.0 / np.sqrt(2.0 * (1.0 + mu) * (2.0 + mu)), 1.0 + 2.0 / mu


def tuned_optimum(mu: float) -> tuple[float, float, float]:
    """Den Hartog's tuned absorber: (ring frequency / ω_n, optimum ζ = c/(2 J_ring ω_n),
    height of the fixed points = peak amplification at the optimum)."""
    return 1.0 / (1.0 + mu), np.sqrt(3.0 * mu / (8.0 * (1.0 + mu) ** 3)), np.sqrt(1.0 + 2.0 / mu)


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


def amplification(M, K, C, station: int, omegas) -> np.ndarray:
    """|θ_station| per unit static deflection under a unit harmonic torque on ``station``:
    |(K − ω²M + iωC)⁻¹|_ss · K_static, where the static deflection is that of the system
    without its dampers' dynamics, 1/(K⁻¹)_ss⁻¹ with the ring free to follow (ω = 0)."""
    omegas = np.atleast_1d(np.asarray(omegas, dtype=float))
    force = np.zeros(len(M))
    force[station] = 1.0
    A = K[None] - omegas[:, None, None] ** 2 * M[None] + 1j * omegas[:, None, None] * C[None]
    theta = np.linalg.solve(A, np.broadcast_to(force, (len(omegas), len(M)))[..., None])[..., station, 0]
    static = np.linalg.lstsq(np.real(K), force, rcond=None)[0][station]
    return np.abs(theta) / abs(static)


def peak_amplification(M, K, C, station: int, omega_range: tuple[float, float], samples: int = 2001) -> tuple[float, float]:
    """Largest :func:`amplification` in ``omega_range`` (rad/s): a dense sweep, then the best
    sample refined by a bounded scalar search between its neighbours. Returns (peak, ω)."""
    omegas = np.linspace(*omega_range, samples)
    amp = amplification(M, K, C, station, omegas)
    j = int(np.argmax(amp))
    lo, hi = omegas[max(j - 1, 0)], omegas[min(j + 1, samples - 1)]
    res = scipy.optimize.minimize_scalar(lambda w: -amplification(M, K, C, station, w)[0], bounds=(lo, hi),
                                         method="bounded", options={"xatol": 1e-10 * hi})
    return float(-res.fun), float(res.x)


def optimise_damping(build, start: float, omega_range: tuple[float, float], station: int = 0,
                     span: float = 1e3) -> tuple[float, float]:
    """The damping coefficient that minimises the peak amplification of ``build(c) -> (M, K, C)``.

    A bounded search in log c over ``start``/``span`` … ``start``·``span``, so a poor start
    (orders of magnitude off) still finds the optimum. Returns (c, peak).
    """
    def peak(log_c):
        return peak_amplification(*build(np.exp(log_c)), station, omega_range)[0]

    res = scipy.optimize.minimize_scalar(peak, bounds=(np.log(start / span), np.log(start * span)),
                                         method="bounded", options={"xatol": 1e-9})
    return float(np.exp(res.x)), float(res.fun)


def damper_station(damper, n: int) -> int:
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


class DampedSystem:
    """A chain's matrices with its dampers' rings appended as the last degrees of freedom.

    ``M``, ``C`` and ``K`` hold the chain, the hubs (added to their stations), the rings and
    the viscous dashpots; the damper springs, which may depend on frequency, are added per
    frequency by :meth:`matrix`. ``stations`` (the chain's size) and ``rings`` (index of each
    damper's ring) locate the DOF. Works for any reduced matrices (a lumped chain or a
    condensed FE crank): only (M, K, C, station) are used.
    """

    def __init__(self, M, K, C, dampers=(), stations: int | None = None, at=None):
        n = len(M) if stations is None else stations
        self.stations, self.dampers, self.rings, self.carriers, self.joints = n, tuple(dampers), [], [], []
        for d in self.dampers:
            s = damper_station(d, n) if at is None else at
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
