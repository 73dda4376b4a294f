"""Synthesis against speed, fillet stress and the verdict (issue 14): hand-checkable cases."""

import math

import numpy as np
import pytest

import fetorsion
from conftest import GEOMETRY
from fetorsion.description.model import Limits
from fetorsion.response.forced import run_response
from fetorsion.design.scfset import SCFSet
from fetorsion.design.stress import fillet_stress, fillets_of
from fetorsion.design.verdict import VerdictCase, VerdictResult, barred_ranges

RENAULT = fetorsion.load(GEOMETRY / "renault21.toml")
SPEEDS = np.linspace(1000.0, 6500.0, 12)


def test_single_order_response_is_that_orders_amplitude_at_every_speed():
    r = run_response(RENAULT, rpm=SPEEDS, orders=[2.0])
    k = r.stiffnesses_nm_per_rad
    per_order = np.abs(k * (r.theta[:, 0, :-1] - r.theta[:, 0, 1:]))  # |k Δθ_q| of each section
    # One order: half the peak-to-peak and the peak of the synthesis are its amplitude (round-off).
    np.testing.assert_allclose(r.section_torque_nm, per_order, rtol=1e-10)
    np.testing.assert_allclose(r.section_torque_peak_nm, per_order, rtol=1e-10)
    np.testing.assert_allclose(r.pulley_angle_deg, np.degrees(np.abs(r.theta[:, 0, 0])), rtol=1e-10)


def test_synthesised_extremes_match_a_dense_waveform_at_every_speed():
    r = run_response(RENAULT, rpm=SPEEDS)
    for s in range(len(SPEEDS)):
        w = r.waveform(s, samples=14400)["section_torque_nm"]  # (springs, angles)
        half = 0.5 * (w.max(axis=1) - w.min(axis=1))
        # Sampling misses an extreme by at most ½ x'' Δθ² ≤ ½ (q_max Δθ)² of the amplitude
        # (q_max = 12, Δθ = 4π/14400): 5.5e-5; the exact extremes are never below the samples.
        assert np.all(r.section_torque_nm[s] >= half * (1 - 1e-12))
        np.testing.assert_allclose(r.section_torque_nm[s], half, rtol=1e-4)
        np.testing.assert_allclose(r.section_torque_peak_nm[s], np.abs(w).max(axis=1), rtol=1e-4)
    # Orders add with their phases: the synthesis never exceeds the sum of the order amplitudes.
    k = r.stiffnesses_nm_per_rad
    bound = np.abs(k * (r.theta[:, :, :-1] - r.theta[:, :, 1:])).sum(axis=1)
    assert np.all(r.section_torque_peak_nm <= bound * (1 + 1e-12))


def test_fillet_stress_is_the_nominal_formula_of_its_springs_torque():
    r = run_response(RENAULT, rpm=SPEEDS)
    st = fillet_stress(RENAULT, r, SCFSet.of(2.0, 3.0, "test"))
    fillets = fillets_of(RENAULT)
    assert [f.kind for f in fillets[:4]] == ["journal", "pin", "pin", "journal"] and len(fillets) == 16
    # By hand for the last fillet (pin 4, web 8 side, d = 48 mm, solid): 16 T / (π d³) x 2.
    T = r.section_torque_nm[:, st.springs[-2]]
    np.testing.assert_allclose(st.stress_pa[:, -2], 2.0 * 16 * T / (math.pi * 0.048**3), rtol=1e-12)
    # Each fillet lies between the anchors of the spring it reads.
    a = r.positions_m
    assert all(a[s] < f.x < a[s + 1] for f, s in zip(fillets, st.springs))


def test_barred_ranges_by_hand():
    rpm = np.array([1000.0, 2000.0, 3000.0, 4000.0, 5000.0, 6000.0])
    value = np.array([1.0, 2.0, 4.0, 2.0, 1.0, 5.0])
    bars = barred_ranges(rpm, value, 3.0)
    # 2→4 crosses 3 half-way (2500), 4→2 at 3500; 1→5 at 5500 and it runs to the end.
    assert bars == [{"from_rpm": 2500.0, "to_rpm": 3500.0, "peak": 4.0, "peak_rpm": 3000.0},
                    {"from_rpm": 5500.0, "to_rpm": 6000.0, "peak": 5.0, "peak_rpm": 6000.0}]
    assert barred_ranges(rpm, value, 10.0) == []


def test_verdict_rows_by_hand():
    rpm = np.array([1000.0, 2000.0, 3000.0, 4000.0])
    where = ["a", "b", "c", "d"]
    limits = Limits(continuous_shear=100.0, transient_shear=150.0, source="hand")
    cases = [VerdictCase("low", rpm, np.array([10.0, 50.0, 80.0, 20.0]), where),
             VerdictCase("passable", rpm, np.array([10.0, 120.0, 60.0, 20.0]), where),
             VerdictCase("too high", rpm, np.array([10.0, 160.0, 60.0, 20.0]), where),
             VerdictCase("at the top", rpm, np.array([10.0, 20.0, 60.0, 120.0]), where)]
    rows = VerdictResult("hand", limits, cases).rows()
    assert [r["verdict"] for r in rows] == ["pass", "pass with barred ranges", "fail", "fail"]
    assert rows[0]["margin"] == pytest.approx(1 - 80 / 100) and rows[0]["worst_section"] == "c"
    assert rows[1]["barred_ranges"][0]["from_rpm"] == pytest.approx(1000 + 1000 * 90 / 110)
    assert rows[2]["margin"] == pytest.approx(1 - 160 / 100)
    assert [b["passable"] for r in rows[1:] for b in r["barred_ranges"]] == [True, False, False]


def test_a_chain_files_dampers_and_limits_reach_campbell_response_and_verdict(tmp_path):
    from fetorsion.excitation.campbell import run_campbell
    from fetorsion.design.verdict import run_verdict

    text = (GEOMETRY.parent / "examples" / "mendes2008" / "mwm6_chain.toml").read_text()
    text += ('\n[[dampers]]\ntype = "viscous"\nhousing_inertia_kgm2 = 0.05\nring_inertia_kgm2 = 0.3\n'
             'damping_nms_per_rad = 60.0\n\n[limits]\ncontinuous_torque_nm = 4000.0\nsource = "test"\n')
    path = tmp_path / "chain.toml"
    path.write_text(text)
    chain = fetorsion.load(path)
    rpm = np.linspace(1000.0, 2600.0, 40)
    with_d, without = run_response(chain, rpm=rpm), run_response(chain, rpm=rpm, dampers=())
    assert with_d.damper_names == ["viscous"] and with_d.damper_power_w.shape == (40, 1, len(with_d.orders))
    # Measured, not a theorem (the ring also moves the modes): here the damper lowers the worst torque.
    assert with_d.section_torque_nm.max() < without.section_torque_nm.max()
    camp = run_campbell(chain)
    assert "damper" in camp.source and isinstance(camp.damping_ratio, tuple)
    v = run_verdict(chain, optimise=False, rpm=rpm)
    row = v.rows()[1]  # the description's damper
    # The torque verdict reads the worst section torque of the same response.
    assert row["value"] == pytest.approx(with_d.section_torque_nm.max(), rel=1e-12)
    assert row["limit"] == 4000.0 and v.limits.kind == "torque"
    assert row["damper_heat"] == "not rated" and row["damper_power_w"] > 0
    # rated below and above the heat its worst speed dissipates: the row fails and passes on heat alone
    heat = row["damper_power_w"]
    for rating, expected in ((0.5 * heat, "over the rating"), (2.0 * heat, "within the rating")):
        path.write_text(text.replace("damping_nms_per_rad = 60.0\n", f"damping_nms_per_rad = 60.0\nallowed_power_w = {rating}\n"))
        r = run_verdict(fetorsion.load(path), optimise=False, rpm=rpm).rows()[1]
        assert r["damper_heat"] == expected and r["damper_power_w"] == pytest.approx(heat, rel=1e-12)
        assert (r["verdict"] == "fail (damper heat)") == (expected == "over the rating")


@pytest.mark.parametrize("damper", [
    dict(kind="rubber", stiffness=3.5e4, loss_factor=0.1),
    dict(kind="tuned", stiffness=3.5e4, damping=2.0),
    dict(kind="viscous", damping=3.0)], ids=lambda d: d["kind"])
def test_campbell_severity_with_a_damper_matches_the_forced_responses_peak(damper):
    """Two methods: the Campbell crossing's pulley amplitude and the peak of the forced response of
    that order alone scanned across the crossing speed (±10 %)."""
    from dataclasses import replace

    from fetorsion.description.model import Damper
    from fetorsion.excitation.campbell import run_campbell

    crank = replace(RENAULT, dampers=(Damper(at="front", hub_inertia=1e-3, ring_inertia=6e-3, **damper),))
    camp = run_campbell(crank, n_modes=2)
    x = max((c for c in camp.crossings if c.in_range), key=lambda c: c.severity)
    r = run_response(crank, rpm=np.linspace(0.9 * x.rpm, 1.1 * x.rpm, 201), orders=[x.order])
    peak = r.pulley_angle_deg.max()
    # The crossing speed is the undamped mode's; the damped peak lies within 1 % of it in speed
    # (measured), where the response is flat: the two agree to 2 % and the scan's peak is the larger.
    assert x.severity == pytest.approx(peak, rel=0.02) and x.severity <= peak * (1 + 1e-9)


@pytest.fixture(scope="module")
def condensed_renault(condensed_plain_renault):
    """The Renault 21 (no fillets or drillings) condensed at 30 mm with a cut at every fillet."""
    return condensed_plain_renault


@pytest.mark.fe
def test_verdict_on_the_engine_model_is_the_section_torque_times_scf_over_modulus(condensed_renault):
    """Issue 26: the verdict's worst stress (the condensed crank in its bearings, projected solve)
    equals the torque through that fillet's cut at that speed — here from the other solver, the
    dense direct solve of the reduced model with its Coriolis term — times the SCF over the polar
    section modulus, within 1e-4 (the projected solve's static correction leaves ~1e-5)."""
    from fetorsion.design.verdict import run_verdict
    from fetorsion.fe.rotating import rotating_harmonic
    from fetorsion.response.coupled import condensed_setup, loads_on, master_loads, supported_damping
    from fetorsion.response.synthesis import half_peak_to_peak

    import dataclasses

    crank, fillets, cc = condensed_renault
    # crank descriptions no longer take shear limits (the fatigue verdict decides); the API still does
    crank = dataclasses.replace(crank, limits=Limits(continuous_shear=100e6, transient_shear=150e6, source="test"))
    scf = SCFSet.of(1.9, 2.2, "test")
    setup = condensed_setup(cc, rpm=np.linspace(1000.0, 7150.0, 40), section_labels=[f.label for f in fillets])
    v = run_verdict(crank, scf=scf, setup=setup, fillets=fillets, optimise=False, misfire=False)
    case = v.cases[0]
    s = case.worst()
    k = [f.label for f in fillets].index(case.where[s])
    f = fillets[k]
    rpm = setup.rpm[s:s + 1]
    spin = rpm * np.pi / 30
    Kk, Mk, Ck, keep = supported_damping(cc, "bearings", setup.zeta)
    F = loads_on(cc, master_loads(cc, rpm, setup.orders), keep)
    z = rotating_harmonic(Kk, Mk, Ck, cc.gyroscopic[np.ix_(keep, keep)], np.zeros_like(Kk), spin[:, None], F,
                          setup.orders[None, :] * spin[:, None])
    torque = half_peak_to_peak(z @ cc.cut_rows[k, 3][keep], setup.orders, setup.period)[0]
    modulus = math.pi * (f.diameter**4 - f.bore**4) / (16 * f.diameter)
    assert case.value[s] == pytest.approx(scf.torsion[f.kind] * torque / modulus, rel=1e-4)


@pytest.mark.fe
def test_engine_model_speeds_reach_overspeed(condensed_renault):
    # the default checked range ends at 1.1 × the rated speed; [excitation] overspeed_factor moves it
    import dataclasses

    from fetorsion.response.coupled import condensed_setup

    crank, _, cc = condensed_renault
    assert condensed_setup(cc).rpm[-1] == pytest.approx(1.1 * 6500.0)
    faster = dataclasses.replace(cc, crank=dataclasses.replace(
        crank, excitation=dataclasses.replace(crank.excitation, overspeed=1.25)))
    assert condensed_setup(faster).rpm[-1] == pytest.approx(1.25 * 6500.0)


def test_engine_model_at_another_damping_ratio_is_that_ratios_own_setup(condensed_renault):
    # the fatigue band's setups reuse the nominal one's forces; built from scratch they are the same
    from fetorsion.response.coupled import condensed_setup, with_damping_ratio
    from fetorsion.response.forced import solve_response

    _, _, cc = condensed_renault
    rpm = np.linspace(1000.0, 7150.0, 12)
    nominal = condensed_setup(cc, rpm=rpm)
    derived, direct = with_damping_ratio(nominal, cc, "bearings", 0.04), condensed_setup(cc, rpm=rpm, damping_ratio=0.04)
    assert derived.zeta == direct.zeta == 0.04
    assert np.array_equal(derived.C, direct.C) and np.array_equal(derived.forces, direct.forces)
    a, b = solve_response(derived).to_dict(), solve_response(direct).to_dict()
    assert a == b
    assert not np.array_equal(nominal.C, direct.C)


@pytest.mark.fe
def test_engine_model_with_dampers_is_the_exact_update_of_its_undamped_response(condensed_renault):
    """The condensed crank's response with dampers comes from its response without them by a
    low-rank (Woodbury) update. Given the undamped model's exact responses (dense direct solves
    of the reduced model with its Coriolis term: under the loads, and under a unit torque at each
    damper place), the update equals the dense direct solve with the rings as degrees of freedom
    to round-off (1e-9 of the largest angle): rubber with a table, viscous and tuned dampers, at
    either end and two on one station. The projected setup's own undamped responses are the
    projected solve's (its block of right-hand sides equals one solve per load to 1e-12), whose
    accuracy is tested above; the fillet torques the verdict reads come within 0.1 % of the dense
    solve's."""
    from fetorsion.description.model import Damper
    from fetorsion.lumped_model.damped import DampedSystem, projected_solve, with_dampers
    from fetorsion.response.coupled import condensed_setup
    from fetorsion.response.forced import section_torques, solve_theta

    crank, fillets, cc = condensed_renault
    # 7 speeds x every order (336 frequencies, the resonances among them): the update is exact frequency by
    # frequency, and the dense reference solves are what this test spends its time on (25 speeds: 24 s)
    setup = condensed_setup(cc, rpm=np.linspace(1000.0, 7150.0, 7), section_labels=[f.label for f in fillets])
    n = len(setup.labels)
    omegas = setup.orders[None, :] * setup.rpm[:, None] * np.pi / 30
    spin = setup.rpm[:, None] * np.pi / 30
    bare = DampedSystem(setup.M, setup.K, setup.C, (), stations=n)
    x0, (unit, places) = setup.free_response, setup.unit_response
    one = projected_solve(bare, setup.forces, omegas, setup.gyroscopic, spin)
    assert np.abs(x0 - one).max() <= 1e-12 * np.abs(one).max()
    e = projected_solve(bare, np.broadcast_to(np.eye(n)[places[-1]], setup.forces.shape), omegas, setup.gyroscopic, spin)
    assert np.abs(unit[:, :, -1] - e).max() <= 1e-12 * np.abs(e).max()
    G = (1j * omegas * spin)[..., None, None] * setup.gyroscopic
    rhs = np.zeros(omegas.shape + (n, 1 + len(places)), complex)
    rhs[..., 0] = setup.forces
    for j, s in enumerate(places):
        rhs[..., s, 1 + j] = 1.0
    exact = np.linalg.solve(bare.matrix(omegas) + G, rhs)
    rubber = Damper("rubber", "front", 2e-3, 8e-3, stiffness=5e4, damping=3.0, loss_factor=0.2,
                    table=((200.0, 4e4, 0.15), (900.0, 7e4, 0.25)))
    viscous = Damper("viscous", "front", 4e-3, 6e-3, damping=20.0)
    tuned = Damper("tuned", "rear", 1e-3, 5e-3, stiffness=4e4, damping=2.0)
    for dampers in ((rubber,), (viscous,), (tuned,), (rubber, viscous), (rubber, tuned)):
        theta, _, system = solve_theta(setup, dampers)
        assert theta.shape == omegas.shape + (len(system.M),)
        A = system.matrix(omegas)
        A[..., :n, :n] += G
        F = np.zeros(omegas.shape + (len(system.M),), complex)
        F[..., :n] = setup.forces
        direct = np.linalg.solve(A, F[..., None])[..., 0]
        updated = with_dampers(exact[..., 0], np.swapaxes(exact[..., 1:], -1, -2), places, system, omegas)
        assert np.abs(updated - direct).max() <= 1e-9 * np.abs(direct).max(), [d.kind for d in dampers]
        # and what the verdict reads, the fillet torques of the projected path, within 0.1 % of each
        # speed's largest (a margin printed to 0.1 %)
        mine, ref = section_torques(setup, theta), section_torques(setup, direct)
        assert np.all(np.abs(mine - ref) <= 1e-3 * np.abs(ref).max(axis=(1, 2), keepdims=True)), [d.kind for d in dampers]
