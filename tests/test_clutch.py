"""A clutch as built (issue 43): the plates' capacity on the total torque (preload plus vibration),
drive and coast sides of the damper's curve, slip angle, time and heat reported, and the modal
damping of a friction element's stuck state."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

import fetorsion
from fetorsion.description.chain_model import NonlinearSpring, Shaft
from fetorsion.response.nonlinear import Elements, element_work, integrate_compiled
from fetorsion.response.transient import run_transient

from conftest import ROOT


def disc_on_clutch(spring, J, v0, t_end, n):
    """A disc of inertia J on ``spring`` to ground, released at rest twist with speed v0: the
    compiled integrator's (t, x, z, slip)."""
    t = np.linspace(0.0, t_end, n)
    el = Elements(np.ones((1, 1)), (spring,))
    q, z, slip, _ = integrate_compiled(np.array([[J]]), np.zeros((1, 1)), np.zeros((1, 1)), t, np.zeros(n),
                                       np.zeros(n), lambda a, b: np.zeros((1, b - a)), elements=el,
                                       v0=np.array([v0]))
    return t, q[0], z[0], slip[0]


def test_a_preloaded_clutch_slips_when_the_total_torque_exceeds_its_capacity():
    # By hand: a disc J on a clutch of spring k to ground carries a mean torque P and swings with
    # amplitude A = 1.5 x_c, x_c = (C − P)/k: its vibratory torque k A = 150 N m stays below the
    # capacity C = 200 N m, the total P + k x reaches it at x = x_c. From there the plates pass C:
    # the disc, at v_c = ω x_c √1.25, decelerates under the constant C − P for
    # τ = J v_c/(C − P) over the slip s = J v_c²/(2 (C − P)); the plates turn C s into heat; then
    # it sticks and swings about s with amplitude x_c, touching C at its turning points only.
    # Step 1 µs: the slip time within 2 samples (0.06 %); the slip angle to the step control's
    # rtol: within 1e-4.
    J, k, P, C = 0.1, 1.0e4, 100.0, 200.0
    w, xc = math.sqrt(k / J), (C - P) / k
    v0 = 1.5 * w * xc
    vc = w * xc * math.sqrt(1.25)
    tau, s = J * vc / (C - P), J * vc**2 / (2 * (C - P))
    clutch = NonlinearSpring(0, -1, (k,), preload=P, slip_torque=C)
    t, x, z, slip = disc_on_clutch(clutch, J, v0, 0.05, 50001)
    assert k * 1.5 * xc < C  # the vibratory torque alone never reaches the capacity
    work = element_work((clutch,), x[None], z[None], slip[None], t[1] - t[0])[0]
    assert work.slip_rad == pytest.approx(s, rel=1e-4)
    assert slip[-1] == pytest.approx(s, rel=1e-4)
    assert abs(work.slip_time_s - tau) <= 2 * (t[1] - t[0])
    assert work.slip_energy_j == pytest.approx(C * s, rel=1e-4)
    # after it: a swing of amplitude x_c about s
    after = t > tau + 0.01
    assert 0.5 * (x[after].max() - x[after].min()) == pytest.approx(xc, rel=1e-4)
    assert 0.5 * (x[after].max() + x[after].min()) == pytest.approx(s, rel=1e-4)
    # the same swing without the preload never slips: the capacity is on the total torque
    free = replace(clutch, preload=0.0)
    _, _, _, slip0 = disc_on_clutch(free, J, v0, 0.05, 50001)
    assert np.abs(slip0).max() == 0.0


def test_coast_side_of_the_damper_curve():
    # [Fmigo]'s truck clutch, both sides: drive 50 N m at 5.5°, 3500 at 10°; coast −30 N m at −3°,
    # −1000 at −5°: 10 and 485 N m/deg on the coast side (by hand from the breakpoints).
    d = math.radians
    k1, k2 = 50 / d(5.5), 3450 / d(4.5)
    c1, c2 = 30 / d(3.0), 970 / d(2.0)
    clutch = NonlinearSpring(0, 1, (k1, k2), (d(5.5),), coast_stiffnesses=(c1, c2), coast_stage_angles=(d(3.0),))
    assert clutch.elastic(np.array([d(5.5), d(10.0)])) == pytest.approx([50.0, 3500.0])
    assert clutch.elastic(np.array([-d(3.0), -d(5.0)])) == pytest.approx([-30.0, -1000.0])
    coasting = replace(clutch, preload=-500.0)
    assert coasting.tangent == pytest.approx(c2)
    assert clutch.elastic(coasting.operating_twist) == pytest.approx(-500.0)


def test_a_clutch_that_never_slips_equals_the_linear_shaft():
    # The conventional flywheel example's clutch damper with friction that never slides (1e5 N m)
    # and plates that never slip (1e5 N m): stuck, it is its stage stiffness plus the stick spring.
    # The same network with a linear shaft of that stiffness: same equations, the modal damping set
    # on the same (stuck) modes: block peaks within the 1 % (the compiled integrator's rtol
    # 1e-6 and the exact propagator's first-order hold at 0.5°: both far below).
    model = fetorsion.load(ROOT / "examples" / "networks" / "conventional_flywheel.toml")
    clutch = model.nonlinear[0]
    stuck = replace(clutch, friction=1.0e5, slip_torque=1.0e5)
    nl = replace(model, nonlinear=(stuck,))
    linear = replace(model, nonlinear=(), shafts=model.shafts + (Shaft(clutch.i, clutch.j, stuck.tangent
                                                                       + stuck.stick_stiffness),))
    a = run_transient(nl, run=(1000.0, 1400.0), rate_rpm_per_s=1000.0)
    b = run_transient(linear, run=(1000.0, 1400.0), rate_rpm_per_s=1000.0)
    assert "compiled" in a.scheme and "exact" in b.scheme
    assert a.elements[0].slip_rad == 0.0
    # sections: the linear shaft comes last as the element did
    assert np.abs(a.block_peak_nm / b.block_peak_nm - 1).max() < 0.01


def test_slip_is_reported_on_a_network():
    # The conventional flywheel example with plates of 1.2 × its 150 N m drive torque, run through
    # its driveline resonance (second order at about 1420 rpm): the plates slip there; the report
    # names the slip and its heat, which is the capacity times the slip angle.
    model = fetorsion.load(ROOT / "examples" / "networks" / "conventional_flywheel.toml")
    clutch = replace(model.nonlinear[0], slip_torque=180.0)
    res = run_transient(replace(model, nonlinear=(clutch,)), run=(1200.0, 1700.0), rate_rpm_per_s=500.0)
    w = res.elements[0]
    assert w.slip_rad > 0 and w.slip_time_s > 0 and w.slip_events >= 1
    assert w.slip_energy_j == pytest.approx(180.0 * w.slip_rad)
    assert "slipped" in res.table() and res.to_dict()["elements"][0]["slip_rad"] == w.slip_rad
    # the total torque through it never passes the capacity
    k = res.section_labels.index("clutch damper")
    assert (clutch.preload + res.section_torque_nm[k]).max() <= 180.0 * (1 + 1e-9)
