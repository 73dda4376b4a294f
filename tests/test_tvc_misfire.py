"""Misfire in a propulsion line's TVC (:mod:`fetorsion.design.tvc_cases`): each misfire case's
response against a direct solve assembled here, the misfiring cylinder's firing torque replaced by
its motored torque, and the worst misfire chosen by its shaft utilisation."""

from __future__ import annotations

import copy
import math
import tomllib

import numpy as np
import pytest

from conftest import ROOT
from fetorsion.description.network import parse_network
from fetorsion.design.tvc_cases import evaluate_case, misfire_cases, worst_case
from fetorsion.excitation.torque import cylinder_torque
from fetorsion.response.propulsion import propeller_setup

PATH = ROOT / "examples/networks/geared_engine.toml"
RPM = np.array([1500.0, 3000.0])
Z, SHARE, Q_R, N_R = 3, 0.1, 100.0, 1000.0


def geared_line():
    """The geared four-cylinder example with a three-blade propeller and a section on its shaft."""
    data = copy.deepcopy(tomllib.loads(PATH.read_text()))
    data["chain"]["propellers"] = [{"station": "propeller", "blades": Z, "entrained_water_share": 0.0,
                                    "rated_torque_nm": Q_R, "rated_speed_rpm": N_R, "blade_order_shares": [SHARE]}]
    shaft = next(s for s in data["chain"]["shafts"] if s["between"] == ["wheel", "propeller"])
    shaft.update(diameter_m=0.012, tensile_strength_pa=600e6, feature="integral_flange")
    return parse_network(data, str(PATH))


def own_harmonics(torque: np.ndarray, orders: np.ndarray) -> np.ndarray:
    """c_q with T(θ) = Re Σ c_q e^{iqθ} of a torque sampled uniformly over 4π from firing TDC."""
    theta = np.arange(len(torque)) * 4 * math.pi / len(torque)
    return 2.0 / len(torque) * (torque[None, :] * np.exp(-1j * orders[:, None] * theta[None, :])).sum(axis=1)


def direct_solve(net, orders: np.ndarray, misfire: int) -> np.ndarray:
    """(speeds, orders, stations) angles of every station, written out: M, K (1 + iη), C per station;
    the propeller's damping the law's at each speed; the gears' constraint by hand (wheel 0.4, pump gear 1.5 times the pinion; coordinates the other
    stations); the cylinders at the engine's orders (multiples of 1/2 on its 4π cycle), 1, 3, 4, 2 firing at 0, 180, 360, 540° (firing order 1-3-4-2 on 4 strokes)."""
    n = len(net.labels)
    K = np.zeros((n, n), complex)
    for s in net.shafts:
        e = np.zeros(n)
        e[s.i], e[s.j] = 1.0, -1.0
        K += s.stiffness * (1 + 1j * s.loss_factor) * np.outer(e, e)
    M, C = np.diag(net.inertias), np.diag(net.absolute_damping)
    lab = list(net.labels)
    coords = [s for s in range(n) if lab[s] not in ("wheel", "pump gear")]
    T = np.zeros((n, len(coords)))
    T[coords, range(len(coords))] = 1.0
    T[lab.index("wheel"), coords.index(lab.index("pinion"))] = 0.4
    T[lab.index("pump gear"), coords.index(lab.index("pinion"))] = 1.5
    fire = np.radians([0.0, 540.0, 180.0, 360.0])  # cylinders 1..4
    # the propeller law's damping c = 2 Q/ω at the propeller's own speed (0.4 × the engine's) at each
    # speed, in place of the one at its rated speed the network holds (the file names no damping speed)
    c_law = lambda n_p: 2 * Q_R * (n_p / N_R) ** 2 / (n_p * math.pi / 30)  # noqa: E731
    law = np.zeros((len(RPM), n, n))
    law[:, lab.index("propeller"), lab.index("propeller")] = [c_law(0.4 * r) - c_law(N_R) for r in RPM]
    out = np.zeros((len(RPM), len(orders), n), complex)
    for a, rpm in enumerate(RPM):
        firing = own_harmonics(cylinder_torque(net, rpm).total, orders)
        motored = own_harmonics(cylinder_torque(net, rpm, misfire=True).total, orders)
        for b, q in enumerate(orders):
            F = np.zeros(n, complex)
            for c in range(4 * math.isclose(2 * q, round(2 * q))):  # the engine's orders: multiples of 1/2
                F[lab.index(f"throw {c + 1}")] += (motored if c == misfire else firing)[b] * np.exp(-1j * q * fire[c])
            if math.isclose(q, Z * 0.4, rel_tol=1e-12):  # the blade order of the propeller at 0.4 × the engine
                F[lab.index("propeller")] += SHARE * Q_R * (0.4 * rpm / N_R) ** 2
            w = q * rpm * math.pi / 30
            A = T.T @ (K + 1j * w * (C + law[a]) - w**2 * M) @ T
            out[a, b] = T @ np.linalg.solve(A, T.T @ F)
    return out


def test_each_misfire_equals_a_direct_solve_with_that_cylinder_motored():
    net = geared_line()
    cases = misfire_cases(net, lambda n: propeller_setup(n, rpm=RPM, damping_ratio=0.0))
    assert [c.misfire for c in cases] == [0, 1, 2, 3]
    from fetorsion.lumped_model.network import network_matrices

    T = network_matrices(net).T
    for case in cases:
        theta = case.response.theta[:, :, :T.shape[1]] @ T.T
        expected = direct_solve(net, case.response.orders, case.misfire)
        # every order of every station to 1e-9 of that order's largest angle (round-off of the solves)
        scale = np.abs(expected).max(axis=2, keepdims=True)
        assert np.abs(theta - expected).max() <= 1e-9 * scale.max()
        assert np.all(np.abs(theta - expected) <= 1e-9 * scale + 1e-300)


def test_the_worst_misfire_is_the_most_utilised_and_differs_from_normal_running():
    net = geared_line()
    setup_of = lambda n: propeller_setup(n, rpm=np.linspace(800.0, 4500.0, 60), damping_ratio=0.02)  # noqa: E731
    normal = evaluate_case(net, setup_of, "normal running")
    cases = misfire_cases(net, setup_of)
    worst = worst_case(cases)
    u = [max(np.nanmax(s.utilisation) for s in c.shafts.sections) for c in cases]
    assert worst.misfire == int(np.argmax(u)) and worst.severity == pytest.approx(max(u), rel=1e-15)
    # a misfire adds the orders the balanced firing cancels (0.5, 1, ...): the response is not normal running's
    assert not np.allclose(worst.response.section_torque_nm, normal.response.section_torque_nm, rtol=1e-3)
    assert worst.summary()["misfire_cylinder"] == worst.misfire + 1 and worst.hammering is not None
