"""[[dampers]] in the linear time domain (issue 29): a viscous, a tuned and a rubber damper with a
dynamic table on the MWM chain, the settled time record against the frequency domain's order
synthesis with the same damper (:func:`fetorsion.response.forced.solve_theta`), and the rubber's
generalised Maxwell fit against its table."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

import fetorsion
from conftest import ROOT
from fetorsion.description.model import Damper
from fetorsion.errors import FetorsionError
from fetorsion.lumped_model.damped import maxwell_fit
from fetorsion.response.forced import run_response
from fetorsion.response.transient import run_transient

ZETA = 0.02
ALL_ORDERS = np.arange(1, 49) * 0.5  # 0.5 … 24, as tests/test_transient.py
# An illustrative rubber, not a maker's data: loss factor 0.25 and the stiffness rise k ∝ f^α,
# α = 2 atan(η)/π, that a constant loss factor implies for a causal material (derived: (iω)^α
# has η = tan(απ/2)); 1.6e4 N m/rad at 200 Hz tunes a 0.01 kg m² ring near the chain's first mode.
ALPHA = 2 / math.pi * math.atan(0.25)
TABLE = tuple((f, 1.6e4 * (f / 200.0) ** ALPHA, 0.25) for f in (25.0, 50.0, 100.0, 200.0, 400.0, 800.0, 1600.0))
DAMPERS = {
    "viscous": Damper("viscous", hub_inertia=0.005, ring_inertia=0.01, damping=15.0, name="viscous"),
    "tuned": Damper("tuned", hub_inertia=0.003, ring_inertia=0.01, stiffness=1.6e4, damping=2.5, name="tuned"),
    "rubber": Damper("rubber", hub_inertia=0.003, ring_inertia=0.01, stiffness=TABLE[0][1], loss_factor=TABLE[0][2],
                     table=TABLE, name="rubber"),
}
# The fit's tolerance at the table's rows, set before the first fit: 2 % in |k*| moves the ring's
# tuning √(k/J) by 1 %, the steady-state criterion; 0.02 in η is under a tenth of a rubber's 0.25.
FIT_STIFFNESS, FIT_LOSS = 0.02, 0.02


@pytest.fixture(scope="module")
def chain():
    """The MWM chain with modal damping only (as tests/test_transient.py)."""
    c = fetorsion.load(ROOT / "examples" / "mendes2008" / "mwm6_chain.toml")
    return replace(c, absolute_damping=(), loss_factors=(), excitation=replace(c.excitation, modal_damping_ratio=ZETA))


@pytest.mark.parametrize("rpm", [1500.0, 2149.0])
@pytest.mark.parametrize("kind", list(DAMPERS))
def test_steady_state_with_a_damper_equals_order_synthesis(chain, kind, rpm):
    # Every section's peak |torque| of the settled record against run_response with the same damper
    # (orders 0.5 … 24), within 1 %, the criterion of the undamped chain. Viscous and tuned: the
    # same equations, so only orders above 24 and the force's interpolation differ. Rubber: the
    # frequency domain reads the table itself (linear between rows, held outside), the time domain
    # its Maxwell fit, so the difference also measures the fit.
    model = replace(chain, dampers=(DAMPERS[kind],))
    tr = run_transient(model, rpm=rpm)
    fr = run_response(model, rpm=[rpm], orders=ALL_ORDERS)
    bare = run_response(chain, rpm=[rpm], orders=ALL_ORDERS)
    # the damper does change the response (else the comparison would not test it)
    assert np.max(np.abs(fr.section_torque_peak_nm[0] / bare.section_torque_peak_nm[0] - 1)) > 0.05
    err = np.abs(tr.steady_peak_nm() / fr.section_torque_peak_nm[0] - 1)
    assert err.max() < 0.01, err
    assert tr.labels[-1] == f"damper '{kind}' ring"


def test_maxwell_fit_meets_the_table():
    fit = maxwell_fit(DAMPERS["rubber"])
    assert fit.stiffness_error < FIT_STIFFNESS and fit.loss_error < FIT_LOSS, (fit.stiffness_error, fit.loss_error)
    assert fit.k_inf >= 0 and np.all(fit.stiffness > 0) and np.all(fit.damping > 0)
    assert fit.band_hz == (25.0, 1600.0)


def test_maxwell_fit_recovers_a_maxwell_material():
    # A table sampled from a two-branch Maxwell model whose relaxation frequencies sit between the
    # fit's fixed ones: the fit is another Maxwell model, so it should meet every row closely (the
    # same tolerance as above).
    k_inf, k, p = 5e3, np.array([8e3, 4e3]), np.array([70.0, 450.0])  # N m/rad, N m/rad, Hz

    def spring(f):
        x = f / p
        return k_inf + np.sum(k * 1j * x / (1 + 1j * x))

    rows = tuple((f, float(spring(f).real), float(spring(f).imag / spring(f).real)) for f in np.geomspace(20, 2000, 11))
    fit = maxwell_fit(Damper("rubber", ring_inertia=0.01, table=rows))
    assert fit.stiffness_error < FIT_STIFFNESS and fit.loss_error < FIT_LOSS, (fit.stiffness_error, fit.loss_error)


def test_rubber_table_is_refused_by_the_nonlinear_integrator(chain):
    model = replace(chain, dampers=(DAMPERS["rubber"],))
    with pytest.raises(FetorsionError, match="Maxwell"):
        run_transient(model, rpm=1500.0, variable_inertia=True)


def test_heat_following_rubber_runs_at_the_frequency_domains_temperature(chain):
    # A rubber with tables at 20 and 100 °C (the hot one 40 % softer, illustrative) and a heat path
    # of 20 W/K: the time domain reads its table at the temperature the frequency domain's heat
    # balance finds at the run's speed, within that iteration's own tolerance.
    from fetorsion.response.forced import HEAT_TOLERANCE_K

    rows = tuple((T, f, s * 1.6e4 * (f / 200.0) ** ALPHA, 0.25)
                 for T, s in ((20.0, 1.0), (100.0, 0.6)) for f in (25.0, 100.0, 400.0, 1600.0))
    d = replace(Damper("rubber", hub_inertia=0.003, ring_inertia=0.01, name="hot", temperature_table=rows)
                .at_temperature(20.0), ambient_c=20.0, thermal_conductance=20.0)
    model = replace(chain, dampers=(d,))
    tr = run_transient(model, rpm=2149.0)
    fr = run_response(model, rpm=[2149.0], orders=ALL_ORDERS)
    said = [n for n in tr.notes if "the temperature its heat holds" in n]
    assert said and abs(float(said[0].split(" at ")[1].split(" °C")[0]) - fr.damper_temperatures_c[0]) < HEAT_TOLERANCE_K
