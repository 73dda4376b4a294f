"""Master and articulated rods (fetorsion.excitation.articulated): the articulated piston's path
against a slider-crank where the knuckle is the pin's centre, against the loop closure solved
numerically, its derivatives against finite differences, and the statics of its pin force against
virtual work (two derivations of the same torque)."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from fetorsion.excitation.articulated import ArticulatedLink
from fetorsion.excitation.kinematics import pin_forces, piston_position

# A V12 rail-diesel proportion, invented: stroke 0.2 m, master rod 0.4 m, knuckle 0.075 m at the
# bank angle, articulated rod 0.325 m (the master's less the knuckle radius, the usual choice)
R, L, BANK = 0.1, 0.4, math.radians(60.0)
LINK = ArticulatedLink(R, L, 0.075, BANK, 0.325, BANK)
THETA = np.linspace(0.0, 4 * np.pi, 721)


def test_with_the_knuckle_on_the_pins_centre_the_articulated_cylinder_is_a_slider_crank_a_bank_later():
    """r_k = 0: the path and the pin force equal a plain rod's of the articulated length at θ − δ
    (to round-off)."""
    plain = ArticulatedLink(R, L, 0.0, BANK, 0.35, BANK)
    s = plain.path(THETA)[0]
    assert np.allclose(s, piston_position(THETA - BANK, R, 0.35), rtol=0, atol=1e-13)
    force = 5e4 * np.cos(THETA) ** 2 + 1e3
    f = plain.pin_forces(THETA, force)
    ref = pin_forces(THETA - BANK, force, R, 0.35)
    for k in ("tangential", "radial"):
        assert np.allclose(f[k], ref[k], rtol=1e-12, atol=1e-7), k
    assert plain.tdc_shift() == pytest.approx(0.0, abs=1e-9)


def test_the_path_closes_the_linkage_solved_numerically():
    """s from the closed form against the loop |s e − K| = l_a solved by root finding, K itself
    from the master rod's angle solved from its own loop (sin β = r sin θ / l by root finding)."""
    e = np.array([math.cos(BANK), math.sin(BANK)])
    rot = np.array([[math.cos(LINK.gamma), -math.sin(LINK.gamma)], [math.sin(LINK.gamma), math.cos(LINK.gamma)]])
    for theta in np.linspace(0.0, 2 * np.pi, 37):
        beta = brentq(lambda b: L * math.sin(b) - R * math.sin(theta), -1.0, 1.0, xtol=1e-15)
        K = R * np.array([math.cos(theta), math.sin(theta)]) + LINK.rk * rot @ np.array([math.cos(beta), -math.sin(beta)])
        s = brentq(lambda x: np.linalg.norm(x * e - K) - LINK.la, K @ e, K @ e + LINK.la + 1.0, xtol=1e-15)
        assert float(LINK.path(theta)[0]) == pytest.approx(s, abs=1e-12)


def test_the_path_derivatives_are_its_slopes():
    """s′, s″ against central differences (h = 1e-4 rad: error h² s⁗ ≈ 1e-9 m)."""
    h = 1e-4
    s, s1, s2 = LINK.path(THETA)
    sp, sm = LINK.path(THETA + h)[0], LINK.path(THETA - h)[0]
    assert np.allclose(s1, (sp - sm) / (2 * h), rtol=0, atol=1e-8)
    assert np.allclose(s2, (sp - 2 * s + sm) / h**2, rtol=0, atol=1e-5)


def test_the_pin_forces_torque_is_the_piston_forces_virtual_work():
    """r × tangential from the rods' statics = F (−s′) from the path alone, to round-off."""
    force = 8e4 * np.exp(-((THETA - BANK - 0.3) / 0.4) ** 2) - 2e3 * np.cos(2 * THETA)
    torque = R * LINK.pin_forces(THETA, force)["tangential"]
    assert np.allclose(torque, force * -LINK.path(THETA)[1], rtol=1e-10, atol=1e-7)


def test_the_articulated_tdc_is_off_the_bank_angle():
    """The knuckle's own path moves the articulated piston's TDC off the bank angle (this linkage:
    1.15°; its stroke is 3e-4 longer than 2r): the reason it is not a fork-and-blade rod. The TDC is
    the path's top on a fine grid."""
    theta = np.linspace(0, 2 * np.pi, 200001)
    s = LINK.path(theta)[0]
    shift = LINK.tdc_shift()
    assert abs(shift) > math.radians(0.1)
    assert BANK + shift == pytest.approx(theta[np.argmax(s)], abs=2 * np.pi / 200000)
