"""The analytic crank-web outline and its exact mass properties.

The web outline (see :class:`fetorsion.description.model.Web`) is star-shaped about the crank axis,
so it is described by its radial function ρ(φ): the distance from the axis to the
boundary in direction φ, with φ = 0 pointing at the pin centre. Area integrals then
reduce to one-dimensional quadratures, e.g. the polar second moment
∫∫ r² dA = ∫ ρ(φ)⁴/4 dφ. The Gmsh solid builds the same outline, so the lumped
model and the FE model see the same web.
"""

from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

import numpy as np

from ..description.model import Web

# Gauss–Legendre on each smooth piece of ρ(φ): 8 sub-intervals × 24 nodes integrate the
# arcs and tangent pieces to round-off.
_GAUSS = np.polynomial.legendre.leggauss(24)
_SPLIT = 8


def _geometry(web: Web, R: float):
    r1, r2 = 0.5 * web.width_journal, 0.5 * web.width_pin
    # Common tangent of the two discs: unit normal at angle ±beta, n·x = r1.
    beta = np.arccos((r1 - r2) / R)
    # Polar angle of the tangent point on the pin disc.
    phi2 = np.arctan2(r2 * np.sin(beta), R + r2 * np.cos(beta))
    return r1, r2, beta, phi2


def _kinks(web: Web, R: float) -> np.ndarray:
    """Angles in [-π, π] where ρ(φ) or its slope jumps: piece ends and sector edges."""
    r1, _, beta, phi2 = _geometry(web, R)
    pts = [-np.pi, np.pi, phi2, -phi2, beta, -beta]
    if web.counterweight_radius > 0:
        half = 0.5 * web.counterweight_angle
        pts += [np.pi - half, -np.pi + half]
        if web.counterweight_radius > r1:  # where the sector edge meets the tangent lines
            d = np.arccos(r1 / web.counterweight_radius)
            pts += [beta + d, -beta - d]
    pts = np.clip(np.array(pts, dtype=float), -np.pi, np.pi)
    return np.unique(pts)


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
    r1, r2, beta, phi2 = _geometry(web, R)
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
    # The outline does not depend on the thickness: webs alike but for it share one quadrature
    # (a study's lumped runs compute the same outline for every web of a crank).
    outline = replace(web, thickness=1.0)
    return dict(_section_properties(outline, float(crank_radius)))


@lru_cache(maxsize=4096)
def _section_properties(web: Web, crank_radius: float) -> tuple[tuple[str, float], ...]:
    kinks = _kinks(web, crank_radius)
    steps = np.arange(_SPLIT) / _SPLIT
    edges = np.append((kinks[:-1, None] + np.diff(kinks)[:, None] * steps).ravel(), np.pi)
    x, w = _GAUSS
    half = 0.5 * np.diff(edges)[:, None]
    phi = (0.5 * (edges[:-1] + edges[1:])[:, None] + half * x).ravel()
    weights = (half * w).ravel()
    rho = radial_function(web, crank_radius, phi)
    area = 0.5 * np.sum(weights * rho**2)
    first_x = np.sum(weights * rho**3 * np.cos(phi)) / 3.0
    polar = 0.25 * np.sum(weights * rho**4)
    return (("area", float(area)), ("centroid", float(first_x / area)), ("polar_moment", float(polar)))


def mass_properties(web: Web, crank_radius: float, density: float) -> dict[str, float]:
    """Mass (kg), polar inertia about the crank axis (kg·m²) and centroid offset (m)
    of a web of uniform thickness."""
    s = section_properties(web, crank_radius)
    return {
        "mass": density * web.thickness * s["area"],
        "polar_inertia": density * web.thickness * s["polar_moment"],
        "centroid": s["centroid"],
    }
