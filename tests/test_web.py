"""The analytic web outline against closed-form section properties."""

import math

import pytest

from fetorsion.description.model import Web
from fetorsion.solid.outline import radial_function, section_properties


def stadium_polar(r, R):
    """Polar moment about the left centre of a stadium (two discs radius r, centres 0 and R)."""
    left_half_disc = math.pi * r**4 / 4
    rectangle = 2 * r * R**3 / 3 + 2 * R * r**3 / 3
    right_half_disc = math.pi * r**4 / 4 + 2 * R * (2 * r**3 / 3) + R**2 * math.pi * r**2 / 2
    return left_half_disc + rectangle + right_half_disc


def test_stadium_web():
    r, R = 0.035, 0.041
    s = section_properties(Web(0.02, 2 * r, 2 * r), R)
    assert s["area"] == pytest.approx(math.pi * r**2 + 2 * r * R, rel=1e-9)
    assert s["polar_moment"] == pytest.approx(stadium_polar(r, R), rel=1e-9)
    # Centroid of a stadium symmetric about R/2.
    assert s["centroid"] == pytest.approx(R / 2, rel=1e-9)


def test_counterweight_sector_adds_an_annular_sector():
    r, R, rc, alpha = 0.035, 0.041, 0.070, math.radians(100)
    plain = section_properties(Web(0.02, 2 * r, 2 * r), R)
    cw = section_properties(Web(0.02, 2 * r, 2 * r, rc, alpha), R)
    assert cw["area"] - plain["area"] == pytest.approx(alpha / 2 * (rc**2 - r**2), rel=1e-9)
    assert cw["polar_moment"] - plain["polar_moment"] == pytest.approx(alpha / 4 * (rc**4 - r**4), rel=1e-9)


def test_tapered_outline_touches_both_discs_and_tangent():
    web = Web(0.02, 0.090, 0.066)
    R = 0.041
    # Along the pin direction the outline is the far side of the pin disc; opposite, the journal disc.
    assert radial_function(web, R, 0.0) == pytest.approx(R + 0.033)
    assert radial_function(web, R, math.pi) == pytest.approx(0.045)
    # Distance from the common tangent line to both centres equals the disc radii.
    beta = math.acos((0.045 - 0.033) / R)
    phi = beta - 0.3
    rho = radial_function(web, R, phi)
    x, y = rho * math.cos(phi), rho * math.sin(phi)
    assert x * math.cos(beta) + y * math.sin(beta) == pytest.approx(0.045, rel=1e-9)
