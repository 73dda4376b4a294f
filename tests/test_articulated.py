"""Master and articulated rods (fetorsion.excitation.articulated): the articulated piston's path
against a slider-crank where the knuckle is the pin's centre, against the loop closure solved
numerically, its derivatives against finite differences, and the statics of its pin force against
virtual work (two derivations of the same torque)."""

import math
import re
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

import fetorsion
from fetorsion.excitation.articulated import ArticulatedLink
from fetorsion.excitation.kinematics import pin_forces, piston_position

# A V12 rail-diesel proportion, invented: stroke 0.2 m, master rod 0.4 m, knuckle 0.075 m at the
# bank angle, articulated rod 0.325 m (the master's less the knuckle radius, the usual choice)
R, L, BANK = 0.1, 0.4, math.radians(60.0)
LINK = ArticulatedLink(R, L, 0.075, BANK, 0.325, BANK)
THETA = np.linspace(0.0, 4 * np.pi, 721)
ROOT = Path(__file__).resolve().parents[1]


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


def _v12(tmp_path, rods: str) -> Path:
    """The shipped V12 with its rods as ``rods`` (TOML lines replacing its side-by-side rods)."""
    text = (ROOT / "geometry" / "v12_diesel.toml").read_text()
    text = re.sub(r"(?m)^rod_spacing.*\n", "", text).replace('rods = "side-by-side"', rods)
    path = tmp_path / f"v12_{abs(hash(rods))}.toml"
    path.write_text(text)
    return path


def test_through_the_load_seam_a_vanishing_knuckle_is_a_fork_and_blade_pair(tmp_path):
    """Every cylinder's torque and pin-force harmonics of the V12 with articulated rods whose knuckle
    sits 1e-10 m off the pin, the articulated rod as long as the master, equal the same V12's with
    fork-and-blade rods (to 1e-8: the knuckle's offset over the crank radius is 1e-9)."""
    from fetorsion.excitation.loads import cylinder_loads

    fork = fetorsion.load(_v12(tmp_path, 'rods = "fork-and-blade"'))
    art = fetorsion.load(_v12(tmp_path, f'rods = "articulated"\nknuckle_radius = 1e-7\n'
                                        f'articulated_rod_length = {fork.engine.rod_length * 1e3!r}'))
    assert art.engine.articulated(6) and not art.engine.articulated(0)
    orders = np.arange(0.5, 12.5, 0.5)
    a, f = cylinder_loads(art), cylinder_loads(fork)
    for rpm in (800.0, 1900.0):
        for get in ("torque_harmonics", "pin_force_harmonics"):
            x, y = getattr(a, get)([rpm], orders), getattr(f, get)([rpm], orders)
            assert np.abs(x - y).max() <= 1e-8 * np.abs(y).max(), (rpm, get)


def test_an_articulated_v12s_loads_are_its_own(tmp_path):
    """With a real knuckle (60 mm, rod 208 mm: invented) the second bank's cylinders load the crank
    differently from the first's (their torque over the cycle differs by more than the knuckle's
    geometric share, 1 %), while the first bank's (master) cylinders are unchanged."""
    from fetorsion.excitation.loads import cylinder_loads

    fork = cylinder_loads(fetorsion.load(_v12(tmp_path, 'rods = "fork-and-blade"')))
    art = cylinder_loads(fetorsion.load(_v12(tmp_path, 'rods = "articulated"\nknuckle_radius = 60.0\n'
                                                     'articulated_rod_length = 208.0')))
    master, second = art.cylinder_torque(0, 1500.0).total, art.cylinder_torque(6, 1500.0).total
    assert np.array_equal(master, fork.cylinder_torque(0, 1500.0).total)
    assert np.abs(second - fork.cylinder_torque(6, 1500.0).total).max() > 0.01 * np.abs(master).max()


@pytest.mark.parametrize("rods, field, words", [
    ('rods = "articulated"\narticulated_rod_length = 208.0', "engine.knuckle_radius", "required"),
    ('rods = "articulated"\nknuckle_radius = 60.0\narticulated_rod_length = 100.0', "engine.articulated_rod_length",
     "knuckle_radius together"),
    ('rods = "fork-and-blade"\nknuckle_radius = 60.0', "engine.knuckle_radius", 'belongs to rods = "articulated"'),
])
def test_bad_articulated_rods_are_refused_by_name(tmp_path, rods, field, words):
    from fetorsion.errors import DescriptionError

    with pytest.raises(DescriptionError) as err:
        fetorsion.load(_v12(tmp_path, rods))
    assert field in str(err.value) and words in str(err.value), str(err.value)
