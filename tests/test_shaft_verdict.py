"""A shaft section's synthesised stress against UR M68's τ_C(λ) and τ_T(λ) over the speed range, and
the barred range it gives (:mod:`fetorsion.design.shaft_verdict`): a propeller on a grounded shaft,
whose response and limits are written out here and whose crossings are solved by bisection."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from fetorsion.description.network import parse_network
from fetorsion.design.shaft_verdict import shaft_verdict
from fetorsion.response.forced import solve_response
from fetorsion.response.propulsion import propeller_setup

# a propeller J on a hollow shaft k to ground; z = 4 blades, 5 % of Q = Q_r (n/n_r)², the law's
# damping c = 2 Q(n_d)/ω_d to ground; the resonance √(k/J)/z near λ = 0.6
J, Z, N_R, Q_R, SHARE, N_D = 8000.0, 4, 120.0, 200e3, 0.015, 72.0
K = J * (Z * 0.6 * N_R * math.pi / 30) ** 2
D, BORE, SIGMA_B = 0.09, 0.05, 600e6
LINE = {"chain": {"name": "propeller on a grounded shaft",
                  "stations": [{"name": "propeller", "inertia_kgm2": J}],
                  "shafts": [{"between": ["propeller", "ground"], "stiffness_nm_per_rad": K, "diameter_m": D,
                              "bore_m": BORE, "tensile_strength_pa": SIGMA_B, "feature": "integral_flange"}],
                  "propellers": [{"station": "propeller", "blades": Z, "entrained_water_share": 0.0,
                                  "rated_torque_nm": Q_R, "rated_speed_rpm": N_R, "damping_speed_rpm": N_D,
                                  "blade_order_shares": [SHARE]}]}}


def stress_by_hand(n: float) -> float:
    """τ (Pa) at n rpm: T = k |F / (k − J w² + i c w)|, w = z n π/30, τ = 16 T d / (π (d⁴ − d_i⁴))."""
    w, c = Z * n * math.pi / 30, 2 * Q_R * (N_D / N_R) ** 2 / (N_D * math.pi / 30)
    torque = K * SHARE * Q_R * (n / N_R) ** 2 / abs(K - J * w**2 + 1j * c * w)
    return 16 * torque * D / (math.pi * (D**4 - BORE**4))


def tau_c_by_hand(n: float) -> float:
    """UR M68 for σ_B 600 N/mm², C_K 1, C_D = 0.35 + 0.93 · 90^-0.2: (3 − 2λ²) below λ 0.9, 1.38 above, Pa."""
    lam = n / N_R
    return (600 + 160) / 18 * 1.0 * (0.35 + 0.93 * 90**-0.2) * (3 - 2 * lam**2 if lam < 0.9 else 1.38) * 1e6


def test_the_barred_range_is_where_the_stress_crosses_tau_c():
    net = parse_network(LINE, "line")
    rpm = np.linspace(24.0, 126.0, 2041)  # λ 0.2 … 1.05, 0.05 rpm apart
    verdict = shaft_verdict(net, solve_response(propeller_setup(net, rpm=rpm, damping_ratio=0.0)))
    s = verdict.sections[0]
    # the stress and τ_C at every speed as written out by hand (1e-9: the same arithmetic)
    assert s.stress_pa == pytest.approx([stress_by_hand(n) for n in rpm], rel=1e-9)
    assert s.tau_c_pa == pytest.approx([tau_c_by_hand(n) for n in rpm], rel=1e-9)
    # the crossings by bisection on either side of the resonance (72 rpm)
    gap = lambda n: stress_by_hand(n) - tau_c_by_hand(n)  # noqa: E731
    lo, hi = brentq(gap, 60.0, 72.0, xtol=1e-10), brentq(gap, 72.0, 85.0, xtol=1e-10)
    assert len(verdict.barred) == 1
    b = verdict.barred[0]
    # the verdict interpolates linearly between samples 0.05 rpm apart: the curve's curvature over a
    # step leaves the crossing within 0.01 rpm
    assert b["from_rpm"] == pytest.approx(lo, abs=0.01) and b["to_rpm"] == pytest.approx(hi, abs=0.01)
    peak = max(np.linspace(lo, hi, 20001), key=stress_by_hand)
    assert b["peak_rpm"] == pytest.approx(peak, abs=0.05)  # the nearest sample
    assert b["peak_pa"] == pytest.approx(stress_by_hand(peak), rel=1e-4)
    # passing through: τ_T = 1.7 τ_C / √C_K stays above τ in the range, and it lies below λ 0.8
    assert all(stress_by_hand(n) <= 1.7 * tau_c_by_hand(n) for n in np.linspace(lo, hi, 101))
    assert b["within_transient"] and not b["above_0_8"]
    assert verdict.verdict == "pass with barred ranges"
    assert verdict.to_dict()["barred_ranges"][0]["section"] == "propeller-ground"
    assert "barred" in verdict.table()


def test_a_range_above_lambda_0_8_fails_a_propeller_line():
    # the same line stiffer: the resonance at λ 0.85, where the rule allows no barred range
    data = {"chain": dict(LINE["chain"], shafts=[dict(LINE["chain"]["shafts"][0], stiffness_nm_per_rad=K * (0.85 / 0.6)**2)])}
    net = parse_network(data, "line")
    rpm = np.linspace(24.0, 126.0, 1021)
    verdict = shaft_verdict(net, solve_response(propeller_setup(net, rpm=rpm, damping_ratio=0.0)))
    assert verdict.barred and verdict.barred[0]["above_0_8"]
    assert verdict.verdict == "fail"


def test_a_stress_over_tau_c_above_lambda_1_05_is_named_not_judged():
    """The same line stiffer (its resonance at λ 1.08) and excited at a ninth of the share, the
    speeds to λ 1.1 (a generator set's overspeed): below λ 1.05 the stress stays under τ_C, above
    it UR M68 gives no τ_C, so the verdict stays the rule's pass, but a line names the section,
    the speed from which its stress passes τ_C at λ 1.05 (bisection on the hand stress, to the
    0.02 rpm the linear interpolation between samples 0.05 rpm apart allows) and the peak's
    ratio to it."""
    k, share = K * (1.08 / 0.6) ** 2, SHARE / 9
    shaft = dict(LINE["chain"]["shafts"][0], stiffness_nm_per_rad=k)
    prop = dict(LINE["chain"]["propellers"][0], blade_order_shares=[share])
    net = parse_network({"chain": dict(LINE["chain"], shafts=[shaft], propellers=[prop])}, "line")
    rpm = np.linspace(96.0, 132.0, 721)  # λ 0.8 … 1.1, 0.05 rpm apart
    verdict = shaft_verdict(net, solve_response(propeller_setup(net, rpm=rpm, damping_ratio=0.0)))

    def stress(n):  # stress_by_hand's arithmetic with this stiffness and share
        w, c = Z * n * math.pi / 30, 2 * Q_R * (N_D / N_R) ** 2 / (N_D * math.pi / 30)
        torque = k * share * Q_R * (n / N_R) ** 2 / abs(k - J * w**2 + 1j * c * w)
        return 16 * torque * D / (math.pi * (D**4 - BORE**4))

    edge = tau_c_by_hand(1.05 * N_R)
    assert all(stress(n) < tau_c_by_hand(n) for n in rpm if n <= 1.05 * N_R)
    start = brentq(lambda n: stress(n) - edge, 1.05 * N_R, 1.08 * N_R, xtol=1e-10)
    line = next(n for n in verdict.notes if n.startswith("beyond the rule"))
    assert "propeller-ground" in line and f"{edge / 1e6:.2f} N/mm²" in line
    said = float(line.split(" from ")[1].split(" rpm")[0])
    assert said == pytest.approx(start, abs=0.02)
    top = max((n for n in rpm if n > 1.05 * N_R), key=stress)
    assert f"{stress(top) / edge:.2f} × it" in line
    assert not verdict.barred and verdict.verdict == "pass"
