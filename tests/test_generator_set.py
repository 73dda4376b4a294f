"""The example diesel generator set (examples/networks/generator_set_mwm6.toml): the numbers its
comments derive, recomputed from the rules they state; and its run, whose report has the TVC
sections, whose results.json is consistent with itself (stresses from the stored torques, the
coupling's temperature from its stored heat, the rule's λ against the rated 1500 rpm) and in which
no speed of the constant-speed set's band is barred; its start is run against τ_T."""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from conftest import ROOT
import fetorsion

PATH = ROOT / "examples/networks/generator_set_mwm6.toml"
RATED_RPM = 120.0 * 50.0 / 4.0  # n = 120 f / p: 50 Hz, four poles


def test_the_generator_sets_numbers_follow_the_rules_its_comments_state():
    from fetorsion.lumped_model.lumped import lumped

    net = fetorsion.load(PATH)
    e, ex = net.engine, net.excitation
    assert RATED_RPM == 1500.0 and ex.speed_range == (0.9 * RATED_RPM, RATED_RPM) and ex.overspeed == 1.1
    vs = 6 * math.pi / 4 * e.bore**2 * e.stroke
    brake = 0.85 * ex.running_imep(RATED_RPM) * vs * RATED_RPM / 120.0  # p_mi V_s n/120, η_m 0.85
    assert brake == pytest.approx(90.75e3, rel=1e-4)  # the file's digits
    assert brake / (RATED_RPM * math.pi / 30.0) == pytest.approx(577.7, rel=1e-4)
    # the generator's shaft: the class rule's minimum diameter (F 100, k 1.0), rounded up to the next 5 mm
    rule = 100.0 * (brake / 1e3 / RATED_RPM * 560.0 / (600.0 + 160.0)) ** (1 / 3)
    (shaft,) = [s for s in net.shafts if s.section is not None]
    d = shaft.section.diameter
    assert rule == pytest.approx(35.5, abs=0.05) and 0 <= d * 1e3 - rule < 5
    assert shaft.stiffness == pytest.approx(80e9 * math.pi * d**4 / (32 * 0.3), rel=1e-6)  # G π d⁴/(32 L)
    inertia = dict(zip(net.labels, net.inertias))
    assert inertia["generator hub"] == pytest.approx(7850 * math.pi * 0.025 * 0.07**4 / 2, rel=1e-4)
    assert inertia["generator rotor"] == pytest.approx(135.5 * 0.25**2 / 8, rel=1e-4)  # m D²/8
    # Den Hartog's optimum at the set's first engine mode without the damper (the crank's: mode 2, mode 1
    # the generator against the engine on the coupling), μ = J_d / J_crank
    free = lumped(replace(net, dampers=()))
    w1 = 2 * math.pi * free.frequencies_hz[1]
    damper = net.dampers[0]
    mu = damper.ring_inertia / sum(net.inertias[:8])
    assert mu == pytest.approx(0.1, rel=1e-3)
    assert damper.damping == pytest.approx(w1 * damper.ring_inertia / math.sqrt(2 * (1 + mu) * (2 + mu)), rel=1e-3)
    # the start: SOLAS's 45 s from rest to the rated speed; p_mi the friction (η_m 0.85 at full load) and the
    # torque accelerating every station and the damper's ring, 4π J dω/dt / V_s
    start = net.start
    assert start.rate_rpm_per_s == pytest.approx(RATED_RPM / 45.0, rel=1e-4)
    accel = (sum(net.inertias) + damper.ring_inertia) * start.rate_rpm_per_s * math.pi / 30.0
    friction = (1 - 0.85) * ex.running_imep(RATED_RPM)
    assert start.imep_pa == pytest.approx(friction + 4 * math.pi * accel / vs, rel=1e-3)
    # the stop: the same friction torque p_f V_s/4π over the same inertia
    inertia = sum(net.inertias) + damper.ring_inertia
    assert net.stop.rate_rpm_per_s == pytest.approx(friction * vs / (4 * math.pi) / inertia * 30 / math.pi, rel=1e-3)


@pytest.fixture(scope="module")
def genset_run(tmp_path_factory) -> Path:
    from fetorsion.app.run import FAST_STEPS, RunOptions, run

    out = tmp_path_factory.mktemp("genset") / "r"
    return Path(run(PATH, out, steps=FAST_STEPS, options=RunOptions(html=False)).folder)


@pytest.mark.slow
def test_the_generator_sets_run_reports_its_tvc_and_its_numbers_agree(genset_run):
    text = (genset_run / "report.md").read_text()
    for heading in ("### Shaft stresses against IACS UR M68", "### Flexible couplings: vibratory torque and heat",
                    "### Normal running and misfire", "### What is assumed"):
        assert heading in text
    tvc = json.loads((genset_run / "results.json").read_text())["tvc"]
    rpm = np.array(tvc["shafts"]["rpm"])
    # the rule's λ against the full-load speed of the constant-speed set; the response spans 0.9-1.1 of it
    assert tvc["shafts"]["rated_rpm"] == RATED_RPM
    assert rpm[0] == pytest.approx(0.9 * RATED_RPM) and rpm[-1] == pytest.approx(1.1 * RATED_RPM)
    torque = np.array(tvc["response"]["section_torque_nm"])
    (s,) = tvc["shafts"]["sections"]
    k = tvc["response"]["sections"].index(s["label"])
    assert s["label"] == "generator hub-generator rotor"
    assert np.allclose(s["stress_pa"], 16 * torque[:, k] / (math.pi * s["diameter_m"] ** 3), rtol=1e-12)
    row = tvc["couplings"]["rows"][0]
    held = 40.0 + (80.0 - 40.0) * row["heat_w"] / 620.0  # the heat balance at the stored heat
    assert abs(held - row["temperature_c"]) <= tvc["couplings"]["tolerance_k"]
    # a constant-speed set: no barred range anywhere in its band, in normal running or any misfire
    assert tvc["shafts"]["barred_ranges"] == [] and all(m["barred"] == "" for m in tvc["misfires"])
    assert tvc["shafts"]["constant_speed"] and tvc["shafts"]["verdict"] == "pass"  # a barred range would fail it
    assert len(tvc["misfires"]) == 6
    # the time-domain runs are the start, from its firing speed to the band's lowest speed, and the stop, from
    # the rated speed down to it, each judged against τ_T (τ_C above λ 0.8)
    start, stop = tvc["barred_passages"]
    assert start["kind"] == "start-up" and start["run_rpm"] == [300.0, 0.9 * RATED_RPM]
    assert stop["kind"] == "shut-down" and stop["run_rpm"] == [RATED_RPM, 300.0]
    (sec,) = start["sections"]
    assert start["verdict"] == ("above a limit" if sec["peak_pa"] > sec["tau_t_pa"] else "within the limits")
    assert f"(τ_C above λ 0.8): {'fail' if start['verdict'] == 'above a limit' else 'pass'}" in text


@pytest.mark.slow
def test_the_generator_sets_report_reads_back_whole(genset_run, tmp_path, capsys):
    from test_tvc_round_trip import reports_the_same

    reports_the_same(genset_run, tmp_path / "copy")
    assert "not read back" not in capsys.readouterr().out
