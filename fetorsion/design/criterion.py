"""Findley's critical plane on a surface node's stress history, with the sign of the mean.

At a free surface the stress is plane: (σ₁₁, σ₂₂, σ₁₂) in the tangent frame (e₁, e₂). A fatigue
crack starts on a plane through the surface; on the plane whose normal is m = cos θ e₁ + sin θ e₂

    σ_n = σ₁₁ c² + σ₂₂ s² + 2 σ₁₂ s c,        τ = (σ₂₂ − σ₁₁) s c + σ₁₂ (c² − s²)

(c = cos θ, s = sin θ; the plane's other shear, along the surface normal, is zero at a free
surface), and Findley's damage ([Findley]; [Socie] ch. 5) is τ_a + k σ_n,max, the shear's half
range plus k times the largest normal stress on the plane, at its limit λ = t₋₁ √(1 + k²) on the
worst plane; k and λ from the bending and torsion fatigue limits f₋₁ and t₋₁
(:func:`fetorsion.design.fatigue.findley_k`: with this plane family reversed bending reaches
(f₋₁/2)(k + √(1 + k²)) and reversed torsion t₋₁ √(1 + k²)).

The mean has its sign: σ_n,max = σ_n,0 + max_t σ_n,v(t) carries the static part σ_n,0 as it is, so a
compressive mean lowers the damage on every plane, a tensile one raises it.

Safety: the factor s on the vibratory part with the static part held (the overload path of a
crank whose mean loads — gas pressure's mean, the centrifugal load — stay while the vibration
grows; [Rennert]'s overload case of a constant mean stress). On each plane the damage at s is
k σ_n,0 + s (τ_a + k max σ_n,v), which meets λ at

    s_p = (λ − k σ_n,0) / (τ_a + k max_t σ_n,v),

and the safety is the least s_p over the planes (a plane whose damage does not grow with s never
fails; one already over λ statically gives 0). A more compressive static stress raises every
s_p: the property tests/test_criterion.py checks on random histories.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import FetorsionError

#: Planes searched: every 5° over [0, π) (the grid misses the exact maximum of a damage that is
#: smooth in θ by at most 1 − cos(2.5°) = 0.1 %).
PLANES = 36


def plane_maps(planes: int = PLANES) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(θ (P,), normal-stress rows (P, 3), shear rows (P, 3)) acting on (σ₁₁, σ₂₂, σ₁₂)."""
    theta = np.arange(planes) * (math.pi / planes)
    c, s = np.cos(theta), np.sin(theta)
    normal = np.stack([c * c, s * s, 2 * s * c], axis=1)
    shear = np.stack([-s * c, s * c, c * c - s * s], axis=1)
    return theta, normal, shear


def findley_constants(bending_limit: float, torsion_limit: float) -> tuple[float, float]:
    """(k, λ) of Findley's criterion from f₋₁ and t₋₁ (Pa): :func:`fetorsion.design.fatigue.findley_k`
    and λ = t₋₁ √(1 + k²)."""
    from .fatigue import findley_k

    k = findley_k(bending_limit, torsion_limit)
    return k, torsion_limit * math.sqrt(1.0 + k * k)


def findley_surface(static, vibratory, k: float, limit: float, planes: int = PLANES) -> dict:
    """Findley's safety of surface nodes (module docstring).

    Parameters
    ----------
    static : array_like (..., 3)
        The static (order 0) (σ₁₁, σ₂₂, σ₁₂), Pa.
    vibratory : array_like (..., 3, angles)
        The rest of the history over one cycle, Pa.
    k, limit : float
        Findley's k and λ (Pa): :func:`findley_constants`.

    Returns
    -------
    dict of arrays (...)
        ``safety`` (the factor on the vibratory part), ``plane`` (the critical plane's θ, rad),
        ``value`` (the damage τ_a + k σ_n,max of the history as it is, on its own worst plane, Pa),
        ``tau_a`` and ``sigma_n_max`` on the critical plane, Pa.
    """
    static = np.asarray(static, float)
    vib = np.asarray(vibratory, float)
    if static.shape[-1] != 3 or vib.shape[:-1] != static.shape:
        raise FetorsionError(f"findley_surface: static (..., 3) and vibratory (..., 3, angles), "
                             f"got {static.shape} and {vib.shape}")
    theta, Cn, Ct = plane_maps(planes)
    sn0 = np.einsum("pc,...c->...p", Cn, static)
    snv = np.einsum("pc,...ct->...pt", Cn, vib, optimize=True)
    tv = np.einsum("pc,...ct->...pt", Ct, vib, optimize=True)
    tau_a = 0.5 * (tv.max(axis=-1) - tv.min(axis=-1))
    peak = snv.max(axis=-1)
    grow = tau_a + k * peak
    room = limit - k * sn0
    with np.errstate(divide="ignore", invalid="ignore"):
        s = np.where(grow > 0, room / grow, np.where(room > 0, np.inf, 0.0))
    s = np.where(room <= 0, 0.0, s)
    crit = np.argmin(s, axis=-1)
    damage = tau_a + k * (sn0 + peak)
    worst = np.argmax(damage, axis=-1)
    take = lambda a, i: np.take_along_axis(a, i[..., None], axis=-1)[..., 0]  # noqa: E731
    return {"safety": take(s, crit), "plane": theta[crit], "value": take(damage, worst),
            "tau_a": take(tau_a, crit), "sigma_n_max": take(sn0 + peak, crit)}


def von_mises_plane(s: np.ndarray) -> np.ndarray:
    """√(σ₁₁² + σ₂₂² − σ₁₁ σ₂₂ + 3 σ₁₂²) of plane stresses (..., 3), Pa."""
    return np.sqrt(np.maximum(s[..., 0] ** 2 + s[..., 1] ** 2 - s[..., 0] * s[..., 1] + 3 * s[..., 2] ** 2, 0.0))


def von_mises_amplitude(history: np.ndarray) -> float:
    """Half the longest chord of a plane-stress history (3, angles) in the von Mises norm, Pa: the
    von Mises amplitude (exact for a proportional history)."""
    h = np.asarray(history, float).T  # (angles, 3)
    d = h[:, None, :] - h[None, :, :]
    return 0.5 * float(von_mises_plane(d).max())


def signed_von_mises(s: np.ndarray) -> float:
    """The von Mises stress of a plane stress (3,) with the sign of its trace, Pa: a compressive
    mean reads negative."""
    s = np.asarray(s, float)
    return float(math.copysign(float(von_mises_plane(s)), s[0] + s[1]))
