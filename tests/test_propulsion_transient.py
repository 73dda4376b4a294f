"""A propulsion line in the time domain (:mod:`fetorsion.response.transient_sources`,
:mod:`fetorsion.design.barred_passage`): the propeller's blade orders in a steady run against the
frequency domain's, a misfire's run against the frequency domain's misfire, and the passage of a
barred range, run slowly, against the steady-state peak stress."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from fetorsion.design.barred_passage import passage_span, passage_through
from fetorsion.design.shaft_verdict import shaft_verdict
from fetorsion.response.forced import solve_response
from fetorsion.response.propulsion import propeller_setup
from fetorsion.response.transient import run_transient
from test_tvc_misfire import geared_line

RPM = 1500.0
BLADE_ORDER = 1.2  # three blades on the wheel turning 0.4 times as fast as the crank


@pytest.fixture(scope="module")
def line():
    """The geared four-cylinder line with a three-blade propeller, every damping viscous (no loss
    factor: the time domain takes a loss factor as an equivalent viscous damper, exact only at the
    resonances), so both domains solve the very same equations."""
    net = geared_line()
    return replace(net, shafts=tuple(replace(s, loss_factor=0.0) for s in net.shafts),
                   excitation=replace(net.excitation, modal_damping_ratio=0.02))


def test_blade_order_in_a_steady_run_equals_the_frequency_domain(line):
    # A steady run with the propellers less one without them is the propellers' own response (the
    # equations are linear): every section's signal against Re(T e^{i q φ(t)}) of the frequency
    # domain's blade order, amplitude and phase. The load is linear between samples 0.5° of crank
    # apart: its error (qΔθ)²/8 = 1.4e-5 at q = 1.2; tolerance 1e-4 of the section's amplitude.
    fr = solve_response(propeller_setup(line, rpm=[RPM]))
    k = int(np.flatnonzero(np.isclose(fr.orders, BLADE_ORDER))[0])
    phasor = fr.section_rows @ fr.theta[0, k, :]
    with_blades = run_transient(line, rpm=RPM, cycles=10)
    without = run_transient(line, rpm=RPM, cycles=10, propellers=False)
    keep = with_blades.time_s >= with_blades.settle_s
    own = (with_blades.section_torque_nm - without.section_torque_nm)[:, keep]
    expected = np.real(phasor[:, None] * np.exp(1j * BLADE_ORDER * with_blades.crank_angle_rad[keep])[None, :])
    assert np.all(np.abs(own - expected).max(axis=1) < 1e-4 * np.abs(phasor))
    assert "the propellers' blade orders load the run" in with_blades.notes


def test_misfire_in_a_steady_run_equals_the_frequency_domain(line):
    # Cylinder 2 misfiring: the half orders its firing cancelled are in both domains; the run's
    # largest |torque| after settling against the frequency domain's synthesised peak over its
    # common period (orders 0.5 … 24 of the engine and the blade order), within 1 % (the response's
    # orders stop at 24, the time domain has every harmonic of the torque table).
    setup = propeller_setup(line, rpm=[RPM])
    from fetorsion.response.forced import misfire_harmonics

    fr = solve_response(setup.with_misfire(1, misfire_harmonics(line, setup)))
    run = run_transient(line, rpm=RPM, cycles=12, misfire=1)
    assert np.allclose(run.steady_peak_nm(), fr.section_torque_peak_nm[0], rtol=0.01)
    assert "misfire of cylinder 2 (its motored cycle)" in run.notes


def test_slow_passage_of_a_barred_range_approaches_the_steady_state_peak(line):
    # The shaft's 12 mm section is barred about the first mode (24.2 Hz); passed at 1 rpm/s, 0.5 rpm
    # within each synthesis window (20π rad: 10 revolutions, the common period of the engine's
    # orders 0.5k and the blade order 1.2), the passage is slow against the mode's decay: its peak
    # half-range stress within 1 % of the steady state's (as the engines' slow run-up, test_transient),
    # at the steady peak's speed within 2 rpm (one window 0.5 rpm, the grid 0.25 rpm, the passage's delay).
    rpm = np.arange(1100.0, 1330.0, 0.25)
    fr = solve_response(propeller_setup(line, rpm=rpm))
    verdict = shaft_verdict(line, fr)
    s = verdict.sections[0]
    j = int(np.argmax(s.stress_pa))
    passage = passage_through(line, (1150.0, 1280.0), (1160.0, 1250.0), 1.0, "test", fr.cycle_rad)
    (sp,) = passage.sections
    assert fr.cycle_rad == pytest.approx(20 * np.pi)
    assert sp.peak_pa == pytest.approx(s.stress_pa[j], rel=0.01)
    assert abs(sp.peak_rpm - rpm[j]) < 2.0
    # τ_T at the peak's speed from the rule (the section's τ_C there × 1.7/√C_K, C_K 1 here)
    assert sp.tau_t_pa == pytest.approx(1.7 * sp.tau_c_pa, rel=1e-12)
    assert passage.verdict == ("within the limits" if sp.peak_pa <= sp.tau_t_pa else "above a limit")
    d = passage.to_dict()
    assert d["rate_rpm_per_s"] == 1.0 and d["rate_source"] == "test"


def test_passage_span_starts_and_ends_outside_the_range():
    # widened by its width either side, at least 20 rpm
    assert passage_span({"from_rpm": 400.0, "to_rpm": 430.0}) == (370.0, 460.0)
    assert passage_span({"from_rpm": 400.0, "to_rpm": 405.0}) == (380.0, 425.0)
    # never below the speed range's lowest speed: a range barred from there is passed from there
    assert passage_span({"from_rpm": 400.0, "to_rpm": 430.0}, 390.0) == (390.0, 460.0)


def test_damping_at_a_speed_is_the_law_there(line):
    """A propeller without a stated damping speed: the time domain's one damping at station 1's n
    is the law's c = 2 Q_r (n_p/n_r)² / ω_p at the propeller's own speed n_p = 0.4 n (its wheel),
    in place of the rated speed's the network holds; a stated damping speed is kept."""
    import math

    from fetorsion.response.propulsion import damping_at
    from test_tvc_misfire import N_R, Q_R

    s = line.propellers[0].station
    c = lambda n_p: 2 * Q_R * (n_p / N_R) ** 2 / (n_p * math.pi / 30)  # noqa: E731
    at = damping_at(line, RPM)
    assert at.absolute_damping[s] == pytest.approx(line.absolute_damping[s] - c(N_R) + c(0.4 * RPM), rel=1e-12)
    fixed = replace(line, propellers=tuple(replace(p, damping_each_speed=False) for p in line.propellers))
    assert damping_at(fixed, RPM) is fixed
