"""Slider-crank kinematics: exact forms against geometry and numerical derivatives, series
against exact with the size of the first neglected term as the tolerance."""

import numpy as np
import pytest

from fetorsion.excitation import kinematics as kin
THETA = np.linspace(0.0, 2 * np.pi, 4001)
# EF7 of seed 004 (r 42.5 mm, l from its TDC/BDC positions) and the extremes of seed 002's range.
CASES = [(0.0425, 0.1345), (0.05, 0.05 / 0.24), (0.05, 0.05 / 0.31), (0.0355, 0.1175)]


@pytest.mark.parametrize("r,l", CASES)
def test_exact_position_closes_the_rod(r, l):
    # Independent of the formula: big end on the crank circle, pin on the axis, |pin − big end| = l.
    s = kin.piston_position(THETA, r, l)
    bx, by = r * np.cos(THETA), r * np.sin(THETA)
    np.testing.assert_allclose(np.hypot(s - bx, by), l, rtol=1e-12)
    np.testing.assert_allclose(np.sin(kin.rod_angle(THETA, r, l)) * l, by, atol=1e-15)


def test_ef7_positions_of_seed_004():
    # Seed 004 quotes TDC 177 mm and BDC 92 mm from the crank axis; l = 134.5 mm follows from them.
    s = kin.piston_position(np.array([0.0, np.pi]), 0.0425, 0.1345)
    np.testing.assert_allclose(s, [0.177, 0.092], atol=1e-12)


@pytest.mark.parametrize("r,l", CASES)
def test_exact_derivatives_match_numerical_derivatives(r, l):
    omega = 300.0
    h = THETA[1] - THETA[0]
    # Central differences are O(h²): with h = 1.6e-3 rad the error is ~h²/6 of the third derivative.
    grad = lambda y: np.gradient(y, h, edge_order=2)  # noqa: E731
    s = kin.piston_position(THETA, r, l)
    v = kin.piston_velocity(THETA, r, l, omega)
    a = kin.piston_acceleration(THETA, r, l, omega)
    np.testing.assert_allclose(v, omega * grad(s), atol=1e-5 * r * omega)
    np.testing.assert_allclose(a, omega * grad(v), atol=1e-5 * r * omega**2)
    beta = kin.rod_angle(THETA, r, l)
    bd = kin.rod_angular_velocity(THETA, r, l, omega)
    np.testing.assert_allclose(bd, omega * grad(beta), atol=1e-5 * omega)
    np.testing.assert_allclose(kin.rod_angular_acceleration(THETA, r, l, omega), omega * grad(bd), atol=1e-5 * omega**2)


@pytest.mark.parametrize("r,l", CASES)
def test_series_error_is_the_neglected_terms(r, l):
    lam = r / l
    omega = 300.0
    # Position: the neglected tail l(λ⁴s⁴/8 + λ⁶s⁶/16 + ...) has ratio < 1, so it is below
    # (λ⁴/8) l / (1 − λ²), and at θ = 90° at least the first term (λ⁴/8) l.
    err = kin.piston_position(THETA, r, l) - kin.piston_position_series(THETA, r, l)
    assert np.abs(err).max() <= lam**4 / 8 * l / (1 - lam**2)
    assert np.abs(err).max() >= lam**4 / 8 * l
    np.testing.assert_allclose(kin.piston_displacement(THETA, r, l) - kin.piston_displacement_series(THETA, r, l),
                               -err, atol=1e-15)
    # Velocity: rωλ sinθ cosθ (1/√D − 1), and 1/√(1−x) − 1 ≤ x/(2(1−x)^{3/2}); max |s³c| = 3√3/16.
    err_v = kin.piston_velocity(THETA, r, l, omega) - kin.piston_velocity_series(THETA, r, l, omega)
    assert np.abs(err_v).max() <= r * omega * lam**3 / 2 * (3 * np.sqrt(3) / 16) / (1 - lam**2) ** 1.5
    # Acceleration: |cos2θ|(D^{-3/2} − 1) + λ² s⁴ D^{-3/2} bounded at D = 1 − λ².
    err_a = kin.piston_acceleration(THETA, r, l, omega) - kin.piston_acceleration_series(THETA, r, l, omega)
    bound_a = r * omega**2 * lam * ((1 - lam**2) ** -1.5 - 1 + lam**2 * (1 - lam**2) ** -1.5)
    assert np.abs(err_a).max() <= bound_a
    assert np.abs(err_a).max() >= r * omega**2 * lam**3 / 4   # the 4th-harmonic term is really there
    # Rod angular velocity: series to λ³, tail from λ⁵ on: ≤ (3/8) λ⁵ ω / (1 − λ²)^{5/2}.
    err_b = kin.rod_angular_velocity(THETA, r, l, omega) - kin.rod_angular_velocity_series(THETA, r, l, omega)
    assert np.abs(err_b).max() <= 3 / 8 * lam**5 * omega / (1 - lam**2) ** 2.5


@pytest.mark.parametrize("r,l", CASES)
def test_pin_forces_exact_against_vectors_and_work(r, l):
    force = 1.0e4 * (1 + 0.3 * np.cos(THETA))
    f = kin.pin_forces(THETA, force, r, l)
    # Vector construction: rod force along (pin → big end), split on the crank's radial/tangential axes.
    s = kin.piston_position(THETA, r, l)
    bx, by = r * np.cos(THETA), r * np.sin(THETA)
    u = np.stack([bx - s, by]) / l          # unit vector from piston pin to big end
    f_rod = force / np.abs(u[0])            # axial component of the rod force equals F
    radial = f_rod * (u[0] * np.cos(THETA) + u[1] * np.sin(THETA))
    tangential = f_rod * (-u[0] * np.sin(THETA) + u[1] * np.cos(THETA))
    np.testing.assert_allclose(f["radial"], radial, rtol=1e-9, atol=1e-9 * force.max())
    np.testing.assert_allclose(f["tangential"], tangential, rtol=1e-9, atol=1e-9 * force.max())
    np.testing.assert_allclose(f["rod"], f_rod, rtol=1e-12)
    np.testing.assert_allclose(f["side"], force * np.abs(u[1] / u[0]) * np.sign(np.sin(THETA)), atol=1e-9 * force.max())
    # Virtual work: T = −F dS/dθ.
    omega = 1.0
    np.testing.assert_allclose(kin.tangential_torque(THETA, force, r, l),
                               -force * kin.piston_velocity(THETA, r, l, omega) / omega, rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("r,l", CASES)
def test_pin_force_series_against_exact(r, l):
    lam = r / l
    f, s = kin.pin_forces(THETA, 1.0, r, l), kin.pin_forces_series(THETA, 1.0, r, l)
    # All four series stop at λ³ (rod: λ²); the first neglected terms are O(λ⁵) (rod: O(λ⁴)),
    # with coefficients ≤ 3/8 (rod: 3/8), so 3/8·λ⁵/(1−λ²)^{5/2} bounds the tail.
    tail5 = 3 / 8 * lam**5 / (1 - lam**2) ** 2.5
    for key in ("tangential", "radial", "side"):
        assert np.abs(f[key] - s[key]).max() <= tail5, key
    assert np.abs(f["rod"] - s["rod"]).max() <= 3 / 8 * lam**4 / (1 - lam**2) ** 2
    # The printed eq. 18 (λ terms with + sign) is off by 2λ sin²θ: it is not the radial force.
    printed_18 = -(lam / 2 + np.cos(THETA) - lam / 2 * np.cos(2 * THETA)
                   + lam**3 / 16 * (3 - 4 * np.cos(2 * THETA) + np.cos(4 * THETA)))
    assert np.abs(printed_18 - f["radial"]).max() > 1.9 * lam


def test_kinematics_result_round_trip():
    res = kin.kinematics(THETA[:10], 0.0425, 0.1345, 600.0, name="EF7")
    d = res.to_dict()
    assert d["name"] == "EF7" and len(d["position_m"]) == 10
    assert d["crank_ratio"] == pytest.approx(0.0425 / 0.1345)


def test_crank_ratio_rejects_impossible_mechanism():
    with pytest.raises(ValueError):
        kin.piston_position(0.0, 0.2, 0.1)
