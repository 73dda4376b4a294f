"""The analytic crank-web outline and its exact mass properties.

The web outline (see :class:`fetorsion.crank.Web`) is star-shaped about the crank axis,
so it is described by its radial function ρ(φ): the distance from the axis to the
boundary in direction φ, with φ = 0 pointing at the pin centre. Area integrals then
reduce to one-dimensional quadratures, e.g. the polar second moment
∫∫ r² dA = ∫ ρ(φ)⁴/4 dφ. The Gmsh solid (issue 3) builds the same outline, so the lumped
model and the FE model see the same web.
"""

from __future__ import annotations

import numpy as np

from .crank import Web

# 2¹⁴ midpoint samples put the quadrature error at the kinks of ρ(φ) below 1e-8 (relative).
_SAMPLES = 1 << 14


def radial_function(web: Web, crank_radius: float, phi: np.ndarray) -> np.ndarray:
    """Distance from the crank axis to the web boundary in direction ``phi`` (rad, 0 = pin).

    The outline is the convex hull of a disc of radius r1 = B_max/2 on the axis and a
    disc of radius r2 = B_min/2 at the pin centre (distance R), united with the
    counterweight sector. Both pieces are star-shaped about the axis, so the union's
    radial function is the larger of the two.
    """
    phi = np.angle(np.exp(1j * np.asarray(phi, dtype=float)))  # wrap to (-π, π]
    a = np.abs(phi)
    R = crank_radius
    r1, r2 = 0.5 * web.width_journal, 0.5 * web.width_pin
    # Common tangent of the two discs: unit normal at angle ±beta, n·x = r1.
    beta = np.arccos((r1 - r2) / R)
    # Polar angle of the tangent point on the pin disc.
    phi2 = np.arctan2(r2 * np.sin(beta), R + r2 * np.cos(beta))
    on_pin_disc = R * np.cos(a) + np.sqrt(np.maximum(r2**2 - (R * np.sin(a)) ** 2, 0.0))
    on_tangent = r1 / np.cos(np.minimum(np.abs(a - beta), 0.5 * np.pi - 1e-12))
    rho = np.where(a <= phi2, on_pin_disc, np.where(a <= beta, on_tangent, r1))
    if web.counterweight_radius > 0:
        in_sector = (np.pi - a) <= 0.5 * web.counterweight_angle
        rho = np.where(in_sector, np.maximum(rho, web.counterweight_radius), rho)
    return rho


def section_properties(web: Web, crank_radius: float) -> dict[str, float]:
    """Area (m²), centroid offset towards the pin (m), and polar second moment about the
    crank axis (m⁴) of the web outline."""
    phi = (np.arange(_SAMPLES) + 0.5) * (2 * np.pi / _SAMPLES) - np.pi
    dphi = 2 * np.pi / _SAMPLES
    rho = radial_function(web, crank_radius, phi)
    area = 0.5 * np.sum(rho**2) * dphi
    first_x = np.sum(rho**3 * np.cos(phi)) * dphi / 3.0
    polar = 0.25 * np.sum(rho**4) * dphi
    return {"area": area, "centroid": first_x / area, "polar_moment": polar}


def mass_properties(web: Web, crank_radius: float, density: float) -> dict[str, float]:
    """Mass (kg), polar inertia about the crank axis (kg·m²) and centroid offset (m)
    of a web of uniform thickness."""
    s = section_properties(web, crank_radius)
    return {
        "mass": density * web.thickness * s["area"],
        "polar_inertia": density * web.thickness * s["polar_moment"],
        "centroid": s["centroid"],
    }
