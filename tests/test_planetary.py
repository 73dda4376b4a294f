"""Planetary cranks: closed-form special cases, the conventional limit, derivatives, arms."""

import numpy as np
import pytest

from fetorsion.excitation import kinematics as kin
from fetorsion.mechanics import planetary as pl
def test_cardan_hypocycloid_is_a_straight_line_and_pure_harmonic():
    # Ring radius a = 2ρ: the big end runs on a diameter (Cardan / Tusi couple): x_p = l + a cos φ.
    a, l = 0.03, 0.2
    res = pl.planetary("hypocycloid", 2 * a, a, l)
    phi = res.phi_rad
    np.testing.assert_allclose(res.big_end_y_m, 0.0, atol=1e-15)
    np.testing.assert_allclose(res.piston_m, l + a * np.cos(phi), atol=1e-15)
    np.testing.assert_allclose(res.effective_arm_m, a * np.sin(phi), atol=1e-15)
    np.testing.assert_allclose(res.geometric_arm_m, 0.0, atol=1e-15)
    assert res.stroke_m == pytest.approx(2 * a, rel=1e-9)


@pytest.mark.parametrize("r,l", [(0.0425, 0.1345), (0.0355, 0.1175)])
def test_conventional_limit_matches_slider_crank(r, l):
    res = pl.planetary("conventional", 2 * r, 0.0, l, samples_per_turn=720)
    phi = res.phi_rad
    np.testing.assert_allclose(res.piston_m, kin.piston_position(phi, r, l), atol=1e-15)
    np.testing.assert_allclose(res.piston_dphi_m, kin.piston_velocity(phi, r, l, 1.0), atol=1e-14)
    np.testing.assert_allclose(res.piston_dphi2_m, kin.piston_acceleration(phi, r, l, 1.0), atol=1e-14)
    beta = kin.rod_angle(phi, r, l)
    np.testing.assert_allclose(res.geometric_arm_m, r * np.sin(phi + beta), atol=1e-15)
    np.testing.assert_allclose(res.effective_arm_m, kin.tangential_torque(phi, 1.0, r, l), atol=1e-15)


@pytest.mark.parametrize("kind", ["epicycloid", "hypocycloid"])
@pytest.mark.parametrize("dp", [0.020, 0.030, 0.040])
def test_trajectory_geometry(kind, dp):
    df = 0.060
    res = pl.planetary(kind, df, dp, 0.25)
    rad = np.hypot(res.big_end_x_m, res.big_end_y_m)
    a, rho = df / 2, dp / 2
    lo, hi = (a, a + 2 * rho) if kind == "epicycloid" else (abs(a - 2 * rho), a)
    # A point on the rolling circle touches the fixed circle (cusp) and swings out by 2ρ.
    assert rad.min() == pytest.approx(lo, abs=1e-9 + 1e-5 * a) and rad.max() == pytest.approx(hi, abs=1e-9)
    # Closes after q carrier turns with (a ± ρ)/ρ = p/q: 20/60 → 1, 30/60 → 1, 40/60 → 2.
    assert res.turns == {0.020: 1, 0.030: 1, 0.040: 2}[dp]
    # Rolling without slip: the contact point is the satellite's instant centre, |dB/dφ| = |spin|·|B − contact|.
    b, db, _ = pl.big_end(res.phi_rad, kind, df, dp)
    contact = a * np.exp(1j * res.phi_rad)
    spin = (a + rho) / rho if kind == "epicycloid" else -(a - rho) / rho
    np.testing.assert_allclose(np.abs(db), abs(spin) * np.abs(b - contact), atol=1e-12)


@pytest.mark.parametrize("kind,dp,phase", [("epicycloid", 0.02, 0.5), ("epicycloid", 0.04, 0.0),
                                           ("hypocycloid", 0.02, 0.3), ("hypocycloid", 0.04, 0.5)])
def test_piston_derivatives_and_arms(kind, dp, phase):
    res = pl.planetary(kind, 0.06, dp, 0.2, pin_phase=phase)
    h = res.phi_rad[1] - res.phi_rad[0]
    grad = lambda y: (np.roll(y, -1) - np.roll(y, 1)) / (2 * h)  # noqa: E731  periodic central difference
    scale = res.stroke_m
    np.testing.assert_allclose(res.piston_dphi_m, grad(res.piston_m), atol=1e-5 * scale)
    np.testing.assert_allclose(res.piston_dphi2_m, grad(res.piston_dphi_m), atol=1e-4 * scale)
    # At every dead centre the effective arm vanishes (to one grid step of x''), whatever the
    # geometric arm: the fixed gear's reaction cancels the rod moment about O.
    dead = np.concatenate([res.tdc_index, res.bdc_index])
    assert np.abs(res.effective_arm_m[dead]).max() <= np.abs(res.piston_dphi2_m).max() * h
    # Geometric arm: distance from O to the line through the big end and the piston pin.
    bx, by, xp = res.big_end_x_m, res.big_end_y_m, res.piston_m
    np.testing.assert_allclose(np.abs(res.geometric_arm_m), np.abs(bx * 0 - by * xp) / np.hypot(xp - bx, by), atol=1e-15)


def test_some_planetary_dead_centre_has_a_geometric_arm():
    # Seed 002 fig. 3: the rod line can miss the crank axis at a dead centre.
    res = pl.planetary("epicycloid", 0.06, 0.03, 0.2)
    assert np.abs(res.geometric_arm_m[res.tdc_index]).max() > 0.02


def test_bad_inputs():
    with pytest.raises(ValueError):
        pl.planetary("hypocycloid", 0.06, 0.07, 0.2)
    with pytest.raises(ValueError):
        pl.planetary("epicycloid", 0.06, 0.04, 0.05)
