"""The example propulsion line (examples/networks/propulsion_line_mwm6.toml): the numbers its comments
derive, recomputed from the rules they state; and (slow) its run, whose report has the TVC sections
and whose results.json is consistent with itself (stresses from the stored torques, the limits
against the stored stresses, the coupling's temperature from its stored heat)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from conftest import ROOT
import fetorsion

PATH = ROOT / "examples/networks/propulsion_line_mwm6.toml"


def test_the_examples_numbers_follow_the_rules_its_comments_state():
    net = fetorsion.load(PATH)
    e, ex = net.engine, net.excitation
    vs = 6 * math.pi / 4 * e.bore**2 * e.stroke
    brake = 0.85 * ex.running_imep(2550.0) * vs * 2550.0 / 120.0  # p_mi V_s n/120, η_m 0.85
    p = net.propellers[0]
    # the propeller absorbs the brake power at 2550/2.5 rpm (the file's four digits)
    assert p.rated_torque == pytest.approx(brake / (1020.0 * math.pi / 30.0), rel=1e-4)
    rule = 100.0 * (brake / 1e3 / 1020.0 * 560.0 / (600.0 + 160.0)) ** (1 / 3)  # mm, F = 100, k = 1
    sections = {net.labels[s.j]: s for s in net.shafts if s.section is not None}
    inter, prop = sections["flange"], sections["propeller"]
    assert inter.section.diameter * 1e3 >= rule and prop.section.diameter * 1e3 >= 1.26 * rule
    assert inter.section.diameter * 1e3 - rule < 5 and prop.section.diameter * 1e3 - 1.26 * rule < 5  # next 5 mm
    for s, length in ((inter, 2.5), (prop, 3.5)):  # G π d⁴ / (32 L), G 80 GPa, to the file's 7 digits
        assert s.stiffness == pytest.approx(80e9 * math.pi * s.section.diameter**4 / (32 * length), rel=1e-6)
    for name, r in (("pinion", 0.06), ("wheel", 0.15)):  # ρ π b r⁴/2, 4 digits
        assert net.inertias[net.labels.index(name)] == pytest.approx(7850 * math.pi * 0.05 * r**4 / 2, rel=5e-4)
    # the propeller in water: 60 kg (0.2 × 0.9 m)² × 1.25
    assert net.inertias[net.labels.index("propeller")] == pytest.approx(60 * 0.18**2 * 1.25, rel=1e-12)
    # Den Hartog's optimum at the first engine mode of the line without the damper (mode 2: mode 1 is the
    # propeller's), μ = J_d / J_crank
    from dataclasses import replace
    from fetorsion.lumped_model.lumped import lumped

    w1 = 2 * math.pi * lumped(replace(net, dampers=())).frequencies_hz[1]
    d = net.dampers[0]
    mu = d.ring_inertia / sum(net.inertias[:8])
    assert mu == pytest.approx(0.1, rel=1e-3)
    assert d.damping == pytest.approx(w1 * d.ring_inertia / math.sqrt(2 * (1 + mu) * (2 + mu)), rel=1e-3)


@pytest.mark.slow
def test_the_examples_run_reports_its_tvc_and_its_numbers_agree(tmp_path):
    from fetorsion.app.run import FAST_STEPS, RunOptions, run

    out = Path(run(PATH, tmp_path / "r", steps=FAST_STEPS, options=RunOptions(html=False)).folder)
    text = (out / "report.md").read_text()
    for heading in ("### Shaft stresses against IACS UR M68", "### Flexible couplings: vibratory torque and heat",
                    "### Gear hammering", "### Normal running and misfire", "### What is assumed"):
        assert heading in text
    tvc = json.loads((out / "results.json").read_text())["tvc"]
    torque = np.array(tvc["response"]["section_torque_nm"])
    for s in tvc["shafts"]["sections"]:
        k = tvc["response"]["sections"].index(s["label"])
        d = s["diameter_m"]
        # the stored stress is 16 T d / (π d⁴) of the stored torque (a solid shaft)
        assert np.allclose(s["stress_pa"], 16 * torque[:, k] / (math.pi * d**3), rtol=1e-12)
        tau, tau_c = np.array(s["stress_pa"]), np.array([np.nan if v is None else v for v in s["tau_c_pa"]])
        over = tau > tau_c
        # every speed over τ_C lies in a stored barred range, every barred range's ends where τ = τ_C
        ranges = s["barred_ranges"]
        rpm = np.array(tvc["shafts"]["rpm"])
        assert all(any(b["from_rpm"] <= n <= b["to_rpm"] for b in ranges) for n in rpm[over])
        for b in ranges:
            for end in (b["from_rpm"], b["to_rpm"]):
                if rpm[0] < end < rpm[-1]:
                    assert np.interp(end, rpm, tau - tau_c) == pytest.approx(0.0, abs=1e-6 * np.nanmax(tau_c))
    row = tvc["couplings"]["rows"][0]
    held = 40.0 + (80.0 - 40.0) * row["heat_w"] / 620.0  # the heat balance at the stored heat
    assert abs(held - row["temperature_c"]) <= tvc["couplings"]["tolerance_k"]
    worst = tvc["worst_misfire_cylinder"]
    u = [m["largest_tau_over_tau_c"] for m in tvc["misfires"]]
    assert u[worst - 1] == max(u) and len(u) == 6


MEDIUM = ROOT / "examples/networks/propulsion_line_medium_speed.toml"


def test_the_medium_speed_lines_numbers_follow_its_similarity_and_class_rules():
    # Every engine number is the MWM line's scaled by s = 320/105 (inertia s⁵, stiffness s³,
    # absolute damping s⁴, lengths and speed s and 1/s, reciprocating mass s³), to the file's four
    # digits (5e-4); the line's shafts by the class rule's minimum diameter and G π d⁴/(32 L).
    from dataclasses import replace
    from fetorsion.lumped_model.lumped import lumped

    s = 0.32 / 0.105
    small, net = fetorsion.load(PATH), fetorsion.load(MEDIUM)
    for name in ("pulley", "gear train", "cyl 1", "cyl 2", "cyl 6", "flywheel"):
        assert net.inertias[net.labels.index(name)] == pytest.approx(
            small.inertias[small.labels.index(name)] * s**5, rel=5e-4)
    for a, b in zip(small.shafts[:8], net.shafts[:8]):
        assert b.stiffness == pytest.approx(a.stiffness * s**3, rel=5e-4)
    assert net.absolute_damping[2] == pytest.approx(small.absolute_damping[2] * s**4, rel=5e-4)
    assert net.excitation.reciprocating_mass == pytest.approx(small.excitation.reciprocating_mass * s**3, rel=5e-4)
    assert net.engine.stroke == pytest.approx(small.engine.stroke * s, rel=1e-4)
    assert net.excitation.speed_range[1] == pytest.approx(2550.0 / s, rel=1e-4)
    e, ex = net.engine, net.excitation
    n = 2550.0 / s
    brake = 0.85 * ex.running_imep(n) * 6 * math.pi / 4 * e.bore**2 * e.stroke * n / 120.0
    p = net.propellers[0]
    assert p.rated_torque == pytest.approx(brake / (n / 3.5 * math.pi / 30.0), rel=1e-4)
    rule = 100.0 * (brake / 1e3 / (n / 3.5) * 560.0 / 760.0) ** (1 / 3)
    sections = {net.labels[sh.j]: sh for sh in net.shafts if sh.section is not None}
    inter, prop = sections["flange"], sections["propeller"]
    assert 0 <= inter.section.diameter * 1e3 - rule < 5 and 0 <= prop.section.diameter * 1e3 - 1.26 * rule < 5
    for sh, length in ((inter, 6.0), (prop, 8.0)):
        assert sh.stiffness == pytest.approx(80e9 * math.pi * sh.section.diameter**4 / (32 * length), rel=1e-6)
    assert net.inertias[net.labels.index("propeller")] == pytest.approx(2500 * 0.56**2 * 1.25, rel=1e-12)
    # Den Hartog at the crank mode of the line without the damper (mode 3: the pulley swings > 10 × the flywheel)
    res = lumped(replace(net, dampers=()))
    k = next(k for k in range(len(res.frequencies_hz))
             if abs(res.mode_shapes[k, 0]) > 10 * abs(res.mode_shapes[k, 8]))
    w1 = 2 * math.pi * res.frequencies_hz[k]
    d = net.dampers[0]
    mu = d.ring_inertia / sum(net.inertias[:8])
    assert mu == pytest.approx(0.1, rel=1e-3)
    assert d.damping == pytest.approx(w1 * d.ring_inertia / math.sqrt(2 * (1 + mu) * (2 + mu)), rel=1e-3)
