"""Mesh-convergence extrapolation shared by the FE jobs (chart points, crank refinement)."""

from __future__ import annotations

from .errors import FetorsionError


def convergence_rate(values, shares) -> float:
    """Observed order p of L(h) = L∞ − C h^p from three meshes h₁ > h₂ > h₃ (bisection, 0.3 ≤ p ≤ 4)."""
    (l1, l2, l3), (h1, h2, h3) = values, shares
    ratio = (l2 - l1) / (l3 - l2)
    g = lambda p: (h1**p - h2**p) / (h2**p - h3**p) - ratio  # noqa: E731  increasing in p
    lo, hi = 0.3, 4.0
    if g(lo) * g(hi) > 0:
        raise FetorsionError(f"mesh sequence {values} is not in the asymptotic range")
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if g(lo) * g(mid) > 0 else (lo, mid)
    return 0.5 * (lo + hi)


def richardson(coarse: float, fine: float, h_coarse: float, h_fine: float, p: float) -> float:
    """L∞ ≈ L_fine + (L_fine − L_coarse) h_fineᵖ / (h_coarseᵖ − h_fineᵖ)."""
    return fine + (fine - coarse) * h_fine**p / (h_coarse**p - h_fine**p)
