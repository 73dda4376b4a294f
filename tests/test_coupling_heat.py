"""A flexible coupling's heat from the forced response and the temperature its own heat holds it at
(:mod:`fetorsion.design.coupling_heat`): against the same line's matrices written out by hand, and
the fixed point of the heat balance found by bisection."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from fetorsion.description.network import parse_network
from fetorsion.design.coupling_heat import coupling_heat
from fetorsion.errors import DescriptionError
from fetorsion.response.propulsion import propeller_setup

# engine J1 —coupling (RATO-type sheet: 262.5 → 183.75 kN m/rad, ψ 1.13 → 0.79 from 20 to 80 °C)—
# flange JG —shaft KS— propeller J2 (z = 4, 5 % of Q = Q_r (n/n_r)², the law's damping at n_d)
J1, JG, KS, J2, Z, QR, NR, ND, S = 50.0, 10.0, 5e6, 200.0, 4, 60e3, 300.0, 200.0, 0.05
AMBIENT, T_MAX, P_KV = 40.0, 80.0, 50.0
RPM = np.linspace(100.0, 300.0, 21)
COUPLING = {"between": ["engine", "flange"], "stiffness_nm_per_rad": 262.5e3, "relative_damping": 1.13,
            "temperature_c": 20.0, "warm_stiffness_nm_per_rad": 183.75e3, "warm_relative_damping": 0.79,
            "warm_temperature_c": 80.0, "operating_temperature_c": 65.0}
LINE = {"chain": {"name": "line", "stations": [{"name": "engine", "inertia_kgm2": J1},
                                               {"name": "flange", "inertia_kgm2": JG},
                                               {"name": "propeller", "inertia_kgm2": J2}],
                  "couplings": [COUPLING], "shafts": [{"between": ["flange", "propeller"], "stiffness_nm_per_rad": KS}],
                  "propellers": [{"station": "propeller", "blades": Z, "entrained_water_share": 0.0,
                                  "rated_torque_nm": QR, "rated_speed_rpm": NR, "damping_speed_rpm": ND,
                                  "blade_order_shares": [S]}]}}


def sheet(t: float) -> tuple[float, float]:
    """(C, ψ) at t °C, linear between 20 and 80 °C, held outside."""
    s = min(max((t - 20.0) / 60.0, 0.0), 1.0)
    return 262.5e3 - s * 78.75e3, 1.13 - s * 0.34


def heat_by_hand(t: float, j1: float = J1, ring: tuple[float, float] | None = None) -> np.ndarray:
    """P (W) at each speed: θ = A⁻¹ (0, 0, F), A = K* − ω²M + iωC_p with the coupling C(1 + iψ/2π);
    the elastic torque T = C (θ1 − θ2), P = f ψ T²/(2C), f = z n/60. ``ring`` (J_d, c_d): a viscous
    damper's ring on the engine as a fourth coordinate, (k − J1 ω² + iωc_d) θ1 − iωc_d θ_d on the
    engine's row, −iωc_d θ1 + (iωc_d − J_d ω²) θ_d on the ring's."""
    C, psi = sheet(t)
    k = C * (1 + 1j * psi / (2 * math.pi))
    c = 2 * QR * (ND / NR) ** 2 / (ND * math.pi / 30)
    out = []
    for n in RPM:
        w = Z * n * math.pi / 30
        A = np.zeros((4, 4), complex)
        A[:3, :3] = [[k - j1 * w**2, -k, 0], [-k, k + KS - JG * w**2, -KS], [0, -KS, KS - J2 * w**2 + 1j * c * w]]
        if ring is None:
            A[3, 3] = 1.0  # no ring: its row decoupled, θ_d = 0
        else:
            d = 1j * w * ring[1]
            A[0, 0] += d
            A[0, 3] = A[3, 0] = -d
            A[3, 3] = d - ring[0] * w**2
        theta = np.linalg.solve(A, [0, 0, S * QR * (n / NR) ** 2, 0])
        out.append(Z * n / 60 * psi * abs(C * (theta[0] - theta[1])) ** 2 / (2 * C))
    return np.array(out)


def _run(data, tolerance_k=0.05):
    net = parse_network(data, "line")
    return coupling_heat(net, lambda n: propeller_setup(n, rpm=RPM, damping_ratio=0.0), tolerance_k=tolerance_k)


def test_the_heat_at_the_operating_temperature_equals_the_hand_calculation():
    r = _run(copy.deepcopy(LINE))  # no P_KV: the coupling stays at its operating 65 °C
    assert r.iterations == 0 and r.temperature_c[0] == 65.0
    assert r.heat_w[:, 0] == pytest.approx(heat_by_hand(65.0), rel=1e-9)  # the same arithmetic
    assert r.rows()[0]["heat_ok"] is None


def test_the_temperature_settles_at_the_heat_balance():
    data = copy.deepcopy(LINE)
    data["chain"]["couplings"][0].update(permissible_power_w=P_KV, ambient_c=AMBIENT, max_temperature_c=T_MAX)
    r = _run(data, tolerance_k=1e-6)
    # T = T_amb + (T_max − T_amb) max_n P(n; T)/P_KV, solved by bisection on the hand calculation
    fixed = brentq(lambda t: t - AMBIENT - (T_MAX - AMBIENT) * heat_by_hand(t).max() / P_KV, AMBIENT, 200.0,
                   xtol=1e-12)
    assert AMBIENT + 5 < fixed < T_MAX  # a case that moves the sheet's values
    # the iteration stops when a step moves T by < 1e-6 K; relaxed by 1/2 and g's slope small, it
    # lies within a few 1e-6 K of the fixed point
    assert r.temperature_c[0] == pytest.approx(fixed, abs=1e-4)
    assert r.heat_w[:, 0] == pytest.approx(heat_by_hand(r.temperature_c[0]), rel=1e-9)
    assert r.iterations == len(r.history_c) - 1 and 1 < r.iterations < 60
    assert r.history_c[0] == [AMBIENT]
    row = r.rows()[0]
    assert row["heat_ok"] is (row["heat_w"] <= P_KV) and "settled in" in r.table()


def test_a_maximum_below_the_ambient_is_refused_by_name():
    data = copy.deepcopy(LINE)
    data["chain"]["couplings"][0].update(permissible_power_w=P_KV, ambient_c=AMBIENT, max_temperature_c=30.0)
    with pytest.raises(DescriptionError, match="chain.couplings.1.max_temperature_c"):
        parse_network(data, "line")


# a viscous damper on the engine station: ring J_D on a dashpot C_D (N m s/rad) to it
J_D, C_D = 5.0, 4000.0


def test_the_tvc_response_carries_the_networks_dampers():
    """A TVC configuration (normal running) solves the line with its [[dampers]]: the coupling's heat
    with a viscous damper on the engine equals the hand calculation with the ring written out (1e-9),
    and the damper moves it (the TVC once left the network's dampers out)."""
    from fetorsion.design.tvc_cases import evaluate_case

    data = copy.deepcopy(LINE)
    data["dampers"] = [{"type": "viscous", "at": "front", "ring_inertia_kgm2": J_D, "damping_nms_per_rad": C_D}]
    net = parse_network(data, "line")
    case = evaluate_case(net, lambda n: propeller_setup(n, rpm=RPM, damping_ratio=0.0), "normal running")
    by_hand = heat_by_hand(65.0, ring=(J_D, C_D))
    assert case.couplings.heat_w[:, 0] == pytest.approx(by_hand, rel=1e-9)
    assert np.abs(by_hand / heat_by_hand(65.0) - 1).max() > 0.01
    assert case.response.damper_names == [net.dampers[0].name]


def test_a_failed_damper_is_the_line_written_without_it():
    """Each failed damper is a TVC configuration: its ring free is the line without the damper but
    with its housing on the engine station, seized the line with housing and ring on it (the
    coupling heat against the hand calculation of that three-inertia line, 1e-9); the states are
    named, the configurations read back with their damper, and an unknown state is refused by name."""
    from fetorsion.design.tvc_cases import TVCCase, damper_failure_cases, with_failed_damper
    from fetorsion.errors import FetorsionError

    housing = 2.0
    data = copy.deepcopy(LINE)
    data["dampers"] = [{"type": "viscous", "at": "front", "ring_inertia_kgm2": J_D, "damping_nms_per_rad": C_D,
                        "housing_inertia_kgm2": housing}]
    net = parse_network(data, "line")
    cases = damper_failure_cases(net, lambda n: propeller_setup(n, rpm=RPM, damping_ratio=0.0))
    assert [c.name for c in cases] == ["damper 'viscous' ring free", "damper 'viscous' seized"]
    for case, added in zip(cases, (housing, housing + J_D)):
        assert case.couplings.heat_w[:, 0] == pytest.approx(heat_by_hand(65.0, J1 + added), rel=1e-9)
        assert case.network.dampers == () and case.damper == 0
        back = TVCCase.from_dict(case.to_dict(), case.network)
        assert (back.damper, back.damper_state, back.name) == (0, case.damper_state, case.name)
    assert not np.allclose(cases[0].couplings.heat_w, cases[1].couplings.heat_w, rtol=1e-3)
    with pytest.raises(FetorsionError, match="jammed"):
        with_failed_damper(net, 0, "jammed")


def test_the_couplings_torque_is_what_its_element_carries():
    """The vibratory torque set against the sheet's permissible one is what the rubber carries,
    elastic and damping: |C (1 + iψ/2π)(θ1 − θ2)| at the one blade order (the same 3 × 3 solve as
    heat_by_hand, 1e-9), √(1 + (ψ/2π)²) = 1.6 % above the elastic part at ψ 1.13 (it was the
    elastic part alone); without a permissible torque on the sheet the table says it is not judged."""
    C, psi = sheet(65.0)
    k = C * (1 + 1j * psi / (2 * math.pi))
    c = 2 * QR * (ND / NR) ** 2 / (ND * math.pi / 30)
    want = []
    for n in RPM:
        w = Z * n * math.pi / 30
        A = np.array([[k - J1 * w**2, -k, 0], [-k, k + KS - JG * w**2, -KS], [0, -KS, KS - J2 * w**2 + 1j * c * w]])
        theta = np.linalg.solve(A, [0, 0, S * QR * (n / NR) ** 2])
        want.append(abs(k * (theta[0] - theta[1])))
    r = _run(copy.deepcopy(LINE))
    assert r.torque_nm[:, 0] == pytest.approx(want, rel=1e-9)
    assert "no permissible vibratory torque: not judged" in r.table()


def test_the_stiffness_tolerance_cases_are_the_sheet_written_at_its_ends():
    """A sheet with a stiffness tolerance t gives two configurations, the coupling at C (1 ∓ t) (nominal
    and warm): each equals the line parsed from a sheet whose stiffnesses are written multiplied
    (its settled temperature and heat, 1e-9); a tolerance of 1 or more is refused by name."""
    from fetorsion.design.tvc_cases import evaluate_case, tolerance_cases

    data = copy.deepcopy(LINE)
    data["chain"]["couplings"][0].update(permissible_power_w=P_KV, ambient_c=AMBIENT, max_temperature_c=T_MAX,
                                         stiffness_tolerance=0.15)
    setup_of = lambda n: propeller_setup(n, rpm=RPM, damping_ratio=0.0)  # noqa: E731
    cases = tolerance_cases(parse_network(data, "line"), setup_of)
    assert [c.stiffness_factor for c in cases] == [0.85, 1.15] and [c.coupling for c in cases] == [0, 0]
    for case, f in zip(cases, (0.85, 1.15)):
        written = copy.deepcopy(data)
        sheet = written["chain"]["couplings"][0]
        sheet.update(stiffness_nm_per_rad=sheet["stiffness_nm_per_rad"] * f,
                     warm_stiffness_nm_per_rad=sheet["warm_stiffness_nm_per_rad"] * f, stiffness_tolerance=0.0)
        by_file = evaluate_case(parse_network(written, "line"), setup_of, "written")
        assert case.couplings.temperature_c == pytest.approx(by_file.couplings.temperature_c, rel=1e-9)
        assert case.couplings.heat_w == pytest.approx(by_file.couplings.heat_w, rel=1e-9)
    bad = copy.deepcopy(LINE)
    bad["chain"]["couplings"][0]["stiffness_tolerance"] = 1.0
    with pytest.raises(DescriptionError, match="chain.couplings.1.stiffness_tolerance"):
        parse_network(bad, "line")
