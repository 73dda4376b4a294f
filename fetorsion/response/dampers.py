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

from ..lumped_model.damped import DampedSystem, attach, damper_spring, damper_station  # noqa: F401 (re-exported)


def viscous_optimum(mu: float) -> tuple[float, float]:
    """Den Hartog's untuned viscous damper: (optimum ζ = c/(2 J_ring ω_n), peak amplification)."""
    return 1.0 / np.sqrt(2.0 * (1.0 + mu) * (2.0 + mu)), 1.0 + 2.0 / mu


def tuned_optimum(mu: float) -> tuple[float, float, float]:
    """Den Hartog's tuned absorber: (ring frequency / ω_n, optimum ζ = c/(2 J_ring ω_n),
    height of the fixed points = peak amplification at the optimum)."""
    return 1.0 / (1.0 + mu), np.sqrt(3.0 * mu / (8.0 * (1.0 + mu) ** 3)), np.sqrt(1.0 + 2.0 / mu)


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
