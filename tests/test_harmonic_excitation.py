"""The engine's excitation by tangential-pressure harmonic coefficients (``[[excitation.
tangential_harmonics]]``): a pressure curve's coefficients, computed here by the test's own DFT,
fed back as a table give the same forced response as the curve; the table is read between its
mean-indicated-pressure columns linearly, its amplitude/phase form equals its sine/cosine form,
and the propeller law's p_mi is p_rated (n/n_rated)²."""

from __future__ import annotations

import copy
import math
import tomllib

import numpy as np
import pytest

from conftest import ROOT
from fetorsion.description.network import parse_network
from fetorsion.errors import FetorsionError
from fetorsion.excitation.torque import cylinder_torque
from fetorsion.response.forced import response_setup, solve_response

PATH = ROOT / "examples/networks/geared_engine.toml"
ORDERS = np.arange(1, 49) * 0.5  # 0.5 … 24
RPM = np.array([1000.0, 2500.0, 4000.0])


def curve_form():
    return parse_network(tomllib.loads(PATH.read_text()), str(PATH))


def coefficients(misfire: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """(a_q, b_q) Pa of the curve form's tangential gas pressure p_t = T_gas/(A r): its gas torque on
    its 4π grid from firing TDC, a_q = (2/N) Σ p_t sin qθ, b_q = (2/N) Σ p_t cos qθ. The synthetic
    cycle at a constant IMEP is the same at every speed, so one speed gives the table's column."""
    net = curve_form()
    e = net.engine
    torque = cylinder_torque(net, 1500.0, misfire=misfire)
    pt = torque.gas / (math.pi / 4 * e.bore**2 * e.crank_radius)
    th = torque.theta
    a = 2.0 / len(th) * (pt[None, :] * np.sin(ORDERS[:, None] * th[None, :])).sum(axis=1)
    b = 2.0 / len(th) * (pt[None, :] * np.cos(ORDERS[:, None] * th[None, :])).sum(axis=1)
    return a, b


def harmonic_form(imep, polar: bool = False, load_key: str = "imep_pa"):
    """The same network, its [excitation] the table: the curve's coefficients at 1.2 MPa (the curve's
    IMEP), twice them at 2.4 MPa, in bar."""
    data = copy.deepcopy(tomllib.loads(PATH.read_text()))
    a, b = coefficients()
    rows = []
    for q, aq, bq in zip(ORDERS, a / 1e5, b / 1e5):
        if polar:
            rows.append({"order": float(q), "amplitude": [math.hypot(aq, bq), 2 * math.hypot(aq, bq)],
                         "phase_deg": [math.degrees(math.atan2(bq, aq))] * 2})
        else:
            rows.append({"order": float(q), "sine": [aq, 2 * aq], "cosine": [bq, 2 * bq]})
    ex = data["excitation"]
    data["excitation"] = {"reciprocating_mass_kg": ex["reciprocating_mass_kg"], "speed_range_rpm": ex["speed_range_rpm"],
                          "tangential_pressure_unit": "bar", "harmonic_imep_pa": [1.2e6, 2.4e6], load_key: imep,
                          "tangential_harmonics": rows}
    return parse_network(data, str(PATH))


def test_a_curves_coefficients_as_a_table_give_the_curves_response():
    a = solve_response(response_setup(curve_form(), rpm=RPM, orders=ORDERS))
    b = solve_response(response_setup(harmonic_form(1.2e6), rpm=RPM, orders=ORDERS))
    # the table holds the curve's orders 0.5-24 exactly (the DFT of the same samples); the response
    # has no other order: equal to round-off, checked to 1e-6 of the largest torque
    scale = a.section_torque_nm.max()
    assert np.abs(a.section_torque_nm - b.section_torque_nm).max() < 1e-6 * scale
    assert np.abs(a.theta - b.theta).max() < 1e-6 * np.abs(a.theta).max()


def test_the_table_is_read_linearly_between_its_columns_and_in_polar_form():
    mid = response_setup(harmonic_form(1.8e6), rpm=RPM, orders=ORDERS).forces
    low = response_setup(harmonic_form(1.2e6), rpm=RPM, orders=ORDERS).forces
    high = response_setup(harmonic_form(2.4e6), rpm=RPM, orders=ORDERS).forces
    # forces are linear in the coefficients and the inertia torque is the same in all three
    assert np.allclose(mid, 0.5 * (low + high), rtol=0, atol=1e-12 * np.abs(high).max())
    polar = response_setup(harmonic_form(1.8e6, polar=True), rpm=RPM, orders=ORDERS).forces
    assert np.allclose(polar, mid, rtol=0, atol=1e-12 * np.abs(mid).max())


def test_the_propeller_laws_mean_indicated_pressure():
    net = harmonic_form(2.0e6, load_key="propeller_law_imep_pa")
    top = net.excitation.speed_range[1]
    for n in (800.0, 2000.0, top):
        assert net.excitation.running_imep(n) == pytest.approx(2.0e6 * (n / top) ** 2, rel=1e-15)
    # the mean of the gas torque is the indicated work over the cycle: p_mi V_s / 4π per cylinder
    e = net.engine
    t = cylinder_torque(net, 2000.0)
    assert t.gas.mean() == pytest.approx(2.0e6 * (2000.0 / top) ** 2 * math.pi / 4 * e.bore**2 * e.stroke
                                         / (4 * math.pi), rel=1e-12)
    with pytest.raises(FetorsionError, match="tangential-pressure harmonics"):
        cylinder_torque(net, 2000.0, misfire=True)


def test_a_misfire_reads_the_tables_motored_column():
    # The table with a column at p_mi 0 holding the synthetic cycle's motored coefficients (the test's own
    # DFT of its compression-and-expansion gas torque) and the firing column at 1.2 MPa: the misfire of
    # each cylinder by the table equals the synthetic cycle's misfire (the same orders exactly: to 1e-6 of
    # the largest torque, as the firing response above).
    from fetorsion.response.forced import misfire_harmonics

    data = copy.deepcopy(tomllib.loads(PATH.read_text()))
    (a0, b0), (a1, b1) = coefficients(misfire=True), coefficients()
    ex = data["excitation"]
    data["excitation"] = {"reciprocating_mass_kg": ex["reciprocating_mass_kg"], "speed_range_rpm": ex["speed_range_rpm"],
                          "harmonic_imep_pa": [0.0, 1.2e6], "imep_pa": 1.2e6,
                          "tangential_harmonics": [{"order": float(q), "sine": [x0, x1], "cosine": [y0, y1]}
                                                   for q, x0, x1, y0, y1 in zip(ORDERS, a0, a1, b0, b1)]}
    table, curve = parse_network(data, str(PATH)), curve_form()
    for c in range(curve.engine.cylinders):
        got = []
        for net in (curve, table):
            setup = response_setup(net, rpm=RPM, orders=ORDERS)
            got.append(solve_response(setup.with_misfire(c, misfire_harmonics(net, setup))).section_torque_nm)
        assert np.abs(got[0] - got[1]).max() < 1e-6 * got[0].max()
    # a table without its p_mi 0 column still says why no misfire is computed
    with pytest.raises(FetorsionError, match="harmonic"):
        cylinder_torque(harmonic_form(1.2e6), 2000.0, misfire=True)


def test_a_misfire_reads_the_makers_misfire_harmonics_first():
    # The firing columns at 1.2 and 2.4 MPa, and the synthetic cycle's motored coefficients given as the
    # maker's misfire harmonics (misfire_sine/misfire_cosine): each cylinder's misfire equals the cycle's
    # to 1e-6 of the largest torque; with a p_mi 0 column of zeros beside them, they still decide.
    from fetorsion.response.forced import misfire_harmonics

    (a0, b0), (a1, b1) = coefficients(misfire=True), coefficients()
    curve = curve_form()
    want = []
    for c in range(curve.engine.cylinders):
        setup = response_setup(curve, rpm=RPM, orders=ORDERS)
        want.append(solve_response(setup.with_misfire(c, misfire_harmonics(curve, setup))).section_torque_nm)
    for columns, firing in (([1.2e6, 2.4e6], lambda x: [x, 2 * x]), ([0.0, 1.2e6], lambda x: [0.0, x])):
        data = copy.deepcopy(tomllib.loads(PATH.read_text()))
        ex = data["excitation"]
        data["excitation"] = {"reciprocating_mass_kg": ex["reciprocating_mass_kg"],
                              "speed_range_rpm": ex["speed_range_rpm"], "harmonic_imep_pa": columns, "imep_pa": 1.2e6,
                              "tangential_harmonics": [{"order": float(q), "sine": firing(x1), "cosine": firing(y1),
                                                        "misfire_sine": x0, "misfire_cosine": y0}
                                                       for q, x0, x1, y0, y1 in zip(ORDERS, a0, a1, b0, b1)]}
        table = parse_network(data, str(PATH))
        for c in range(curve.engine.cylinders):
            setup = response_setup(table, rpm=RPM, orders=ORDERS)
            got = solve_response(setup.with_misfire(c, misfire_harmonics(table, setup))).section_torque_nm
            assert np.abs(got - want[c]).max() < 1e-6 * want[c].max()
    # for some orders only: refused by name
    rows = data["excitation"]["tangential_harmonics"]
    del rows[0]["misfire_sine"], rows[0]["misfire_cosine"]
    with pytest.raises(Exception, match="misfire_sine"):
        parse_network(data, str(PATH))
