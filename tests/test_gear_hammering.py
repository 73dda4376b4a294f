"""Gear hammering (:mod:`fetorsion.design.gear_hammering`): a geared two-inertia line whose mesh
torque and mean torque are written out by hand, and the speeds where the one crosses the other
found by bisection on that closed form."""

from __future__ import annotations

import math

import numpy as np
import pytest

from fetorsion.description.network import parse_network
from fetorsion.design.gear_hammering import gear_hammering
from fetorsion.response.forced import solve_response
from fetorsion.response.propulsion import propeller_setup

# motor J1 (station 1) → gear: the wheel (inertia Jw) turns f times as fast → shaft k → propeller J2,
# the law's damping c to ground; z blades excite order z f of the motor's speed with s Q_r (f Ω/Ω_r)²
J1, JW, J2, K, F, Z, S = 40.0, 5.0, 900.0, 2.0e6, 0.25, 4, 0.08
Q_R, N_R, N_D = 50e3, 150.0, 120.0


def line() -> dict:
    return {"chain": {"name": "geared line",
                      "stations": [{"name": "motor", "inertia_kgm2": J1}, {"name": "wheel", "inertia_kgm2": JW},
                                   {"name": "propeller", "inertia_kgm2": J2}],
                      "gears": [{"between": ["motor", "wheel"], "ratio": F}],
                      "shafts": [{"between": ["wheel", "propeller"], "stiffness_nm_per_rad": K}],
                      "propellers": [{"station": "propeller", "blades": Z, "entrained_water_share": 0.0,
                                      "rated_torque_nm": Q_R, "rated_speed_rpm": N_R, "damping_speed_rpm": N_D,
                                      "blade_order_shares": [S]}]}}


def by_hand(n: float) -> tuple[float, float]:
    """(vibratory, mean) mesh torque on the wheel at motor speed n rpm. In (θ1, θ2): M = diag(J1 + Jw f²,
    J2), K = [[k f², −k f], [−k f, k]], C = diag(0, c), force (0, F); Cramer's rule. The wheel's
    equilibrium: mesh torque = −ω² Jw f θ1 + k (f θ1 − θ2); the mean: the law's torque at the wheel."""
    c = 2 * Q_R * (N_D / N_R) ** 2 / (N_D * math.pi / 30)
    w = Z * F * n * math.pi / 30
    force = S * Q_R * (F * n / N_R) ** 2
    a, b, d = K * F**2 - (J1 + JW * F**2) * w**2, -K * F, K - J2 * w**2 + 1j * c * w
    det = a * d - b * b
    t1, t2 = -b * force / det, a * force / det
    return abs(-w**2 * JW * F * t1 + K * (F * t1 - t2)), Q_R * (F * n / N_R) ** 2


def test_mesh_torque_and_mean_against_the_closed_form():
    rpm = np.array([200.0, 300.0, 500.0, 640.0])
    setup = propeller_setup(parse_network(line(), "geared"), rpm=rpm, damping_ratio=0.0)
    h = gear_hammering(parse_network(line(), "geared"), setup, solve_response(setup).theta)
    m = h.meshes[0]
    assert m.label == "motor-wheel" and m.station == "wheel"
    for n, vib, mean in zip(rpm, m.vibratory_nm, m.mean_nm):
        v, q = by_hand(n)
        assert vib == pytest.approx(v, rel=1e-9) and mean == pytest.approx(q, rel=1e-12)  # one order: exact


def bisect(g, lo: float, hi: float) -> float:
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if (g(lo) > 0) == (g(mid) > 0) else (lo, mid)
    return 0.5 * (lo + hi)


def test_the_hammering_range_crosses_where_the_closed_form_does():
    rpm = np.linspace(100.0, 700.0, 3001)  # 0.2 rpm steps
    setup = propeller_setup(parse_network(line(), "geared"), rpm=rpm, damping_ratio=0.0)
    h = gear_hammering(parse_network(line(), "geared"), setup, solve_response(setup).theta)
    ratio = np.array([np.divide(*by_hand(n)) for n in rpm])
    peak = rpm[np.argmax(ratio)]
    g = lambda n: np.divide(*by_hand(n)) - 1.0  # noqa: E731
    lo, hi = bisect(g, rpm[0], peak), bisect(g, peak, rpm[-1])
    assert len(h.meshes[0].ranges) == 1 and h.verdict == "hammering possible"
    r = h.meshes[0].ranges[0]
    # linear interpolation of the ratio between 0.2 rpm steps: within a tenth of a step of the crossing
    assert r["from_rpm"] == pytest.approx(lo, abs=0.02) and r["to_rpm"] == pytest.approx(hi, abs=0.02)
    print(f"hammering {lo:.4f}-{hi:.4f} rpm by hand, {r['from_rpm']:.4f}-{r['to_rpm']:.4f} computed")
