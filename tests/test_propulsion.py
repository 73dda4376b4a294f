"""A propulsion line's components (description/marine.py): the propeller's linearised damping,
inertia in water and blade-order excitation, and a flexible coupling's data sheet and heat, each
against a hand calculation with its own numbers or a published case."""

from __future__ import annotations

import math

import numpy as np
import pytest

from fetorsion.description.marine import (PROPELLER_DAMPING, blade_excitation, blade_orders, coupling_heat,
                                          law_torque, loss_factor_of, propeller_law_damping, sheet_value,
                                          with_entrained_water)


def test_propeller_law_damping_by_hand_and_as_the_torque_curves_slope():
    # 500 kN m at 120 rpm; at 96 rpm Q = 500e3 · 0.8² = 320 kN m, ω = 96 · 2π/60 = 10.0531 rad/s
    w_r, w = 120 * 2 * math.pi / 60, 96 * 2 * math.pi / 60
    c = PROPELLER_DAMPING["propeller_law"](500e3, w_r, w, 2.0)
    assert c == pytest.approx(2 * 320e3 / (96 * 2 * math.pi / 60), rel=1e-12)
    assert c == pytest.approx(63662.0, abs=1.0)
    # the linearisation is the slope of Q(ω): a central difference of the law itself
    h = 1e-4
    slope = (500e3 * ((w + h) / w_r) ** 2 - 500e3 * ((w - h) / w_r) ** 2) / (2 * h)
    assert c == pytest.approx(slope, rel=1e-9)
    # and for another exponent (n = 2.5): c = n Q/ω
    q = law_torque(500e3, w_r, w, 2.5)
    assert propeller_law_damping(q, w, 2.5) == pytest.approx(2.5 * 500e3 * 0.8**2.5 / w, rel=1e-12)


def test_blade_order_excitation_as_gunter_and_chen_state_it():
    # [GunterChen2001] example 8.1 as [OpenTorsion] transcribes it: a five-blade propeller, its
    # excitation 10 % of the propeller torque Q = 22.24e6 lbf in (85 rpm)² law, at order 5
    lbf_in = 4.4482216152605 * 0.0254
    w0 = 85 * 2 * math.pi / 60
    q = law_torque(22.24e6 * lbf_in, w0, 60 * 2 * math.pi / 60)
    assert blade_orders(5, 2) == (5, 10)
    assert blade_excitation(q, (0.1,)) == pytest.approx((0.1 * 22.24e6 * lbf_in * (60 / 85) ** 2,), rel=1e-12)


def test_entrained_water():
    assert with_entrained_water(8000.0, 0.25) == pytest.approx(10000.0, rel=1e-15)


# A RATO-type sheet: C_Tdyn 262.5 → 183.75 kN m/rad and ψ 1.13 → 0.79 (the numbers), read
# here as nominal at 20 °C and warm at 80 °C (illustrative temperatures), P_KV 0.62 kW.
SHEET = dict(t_nominal_c=20.0, t_warm_c=80.0)


def test_sheet_values_between_and_beyond_the_two_temperatures():
    c50 = sheet_value(50.0, 20.0, 262.5e3, 80.0, 183.75e3)
    assert c50 == pytest.approx((262.5e3 + 183.75e3) / 2, rel=1e-15)  # 223.125 kN m/rad
    assert sheet_value(65.0, 20.0, 1.13, 80.0, 0.79) == pytest.approx(1.13 - 0.75 * 0.34, rel=1e-12)
    assert sheet_value(100.0, 20.0, 1.13, 80.0, 0.79) == 0.79 and sheet_value(0.0, 20.0, 1.13, 80.0, 0.79) == 1.13


def test_coupling_heat_at_one_temperature_by_hand_and_by_the_loop():
    # at 50 °C: C = 223 125 N m/rad, ψ = 0.96; two orders: 2.0 kN m at 30 Hz and 1.0 kN m at 60 Hz
    c, psi = 223125.0, 0.96
    p = coupling_heat((2000.0, 1000.0), (30.0, 60.0), c, psi)
    by_hand = 30 * 0.96 * 2000.0**2 / (2 * 223125.0) + 60 * 0.96 * 1000.0**2 / (2 * 223125.0)
    assert by_hand == pytest.approx(387.23, abs=0.01)  # 258.15 + 129.08 W
    assert p == pytest.approx(by_hand, rel=1e-12)
    assert p < 620.0  # within the sheet's permissible 0.62 kW
    # independently: the hysteretic spring k(1 + iη) is, at one frequency, a viscous c = ηk/ω;
    # its power averaged over a cycle of θ = (T/k) sin ωt, summed over the two orders
    eta = loss_factor_of(psi)
    total = 0.0
    for t_q, f in ((2000.0, 30.0), (1000.0, 60.0)):
        w = 2 * math.pi * f
        s = np.linspace(0.0, 1.0 / f, 20001)
        rate = (t_q / c) * w * np.cos(w * s)
        total += np.trapezoid((eta * c / w) * rate**2, s) * f
    assert total == pytest.approx(p, rel=1e-6)
