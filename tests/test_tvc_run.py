"""``fetorsion run`` on a network with a propeller, a data-sheet coupling and a shaft section: the
report's TVC section (mass-elastic data, natural frequencies, shaft stresses against UR M68, the
coupling's heat at its settled temperature, what is assumed), and nothing of it for a network
without these fields."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from conftest import ROOT
from fetorsion.app.run import FAST_STEPS, RunOptions, run

# an illustrative line (the numbers of tests/test_coupling_heat.py, a 60 mm keyed shaft)
LINE = '''[chain]
name = "illustrative propulsion line"

[[chain.stations]]
name = "engine"
inertia_kgm2 = 50.0

[[chain.stations]]
name = "flange"
inertia_kgm2 = 10.0

[[chain.stations]]
name = "propeller"
inertia_kgm2 = 200.0

[[chain.couplings]]
between = ["engine", "flange"]
stiffness_nm_per_rad = 262.5e3
relative_damping = 1.13
temperature_c = 20.0
warm_stiffness_nm_per_rad = 183.75e3
warm_relative_damping = 0.79
warm_temperature_c = 80.0
permissible_power_w = 50.0
ambient_c = 40.0
permissible_vibratory_torque_nm = 1500.0

[[chain.shafts]]
between = ["flange", "propeller"]
stiffness_nm_per_rad = 5.0e6
diameter_m = 0.06
tensile_strength_pa = 600e6
feature = "keyway_tapered"

[[chain.propellers]]
station = "propeller"
blades = 4
entrained_water_share = 0.0
rated_torque_nm = 60e3
rated_speed_rpm = 300.0
damping_speed_rpm = 200.0
blade_order_shares = [0.05]
'''


def test_a_propulsion_line_gets_the_tvc_section(tmp_path):
    (tmp_path / "line.toml").write_text(LINE)
    out = Path(run(tmp_path / "line.toml", tmp_path / "r", steps=FAST_STEPS, options=RunOptions(html=False)).folder)
    text = (out / "report.md").read_text()
    for heading in ("## Propulsion line: torsional vibration calculation", "### Mass-elastic data",
                    "### Natural frequencies", "### Shaft stresses against IACS UR M68",
                    "### Flexible couplings: vibratory torque and heat", "### What is assumed"):
        assert heading in text
    for image in ("tvc_shafts.png", "tvc_coupling_heat.png"):
        assert f"![]({image})" in text and (out / image).stat().st_size > 10_000
    res = json.loads((out / "results.json").read_text())["tvc"]
    row = res["couplings"]["rows"][0]
    assert 40.0 < row["temperature_c"] < 80.0 and res["couplings"]["iterations"] >= 1
    assert res["shafts"]["sections"][0]["label"] == "flange-propeller" and res["shafts"]["verdict"] == "pass"


def test_a_network_without_propulsion_fields_has_no_tvc_section(tmp_path):
    out = Path(run(ROOT / "examples/networks/friswell_9_6_3.toml", tmp_path / "r", steps=FAST_STEPS,
                   options=RunOptions(html=False)).folder)
    text = (out / "report.md").read_text()
    assert "Propulsion line" not in text and "propulsion TVC" not in text
    assert "tvc" not in json.loads((out / "results.json").read_text())


GEARED = LINE.replace('''[[chain.shafts]]
between = ["flange", "propeller"]''', '''[[chain.stations]]
name = "wheel"
inertia_kgm2 = 30.0

[[chain.gears]]
between = ["flange", "wheel"]
ratio = 0.25

[[chain.shafts]]
between = ["wheel", "propeller"]''').replace('rated_speed_rpm = 300.0', 'rated_speed_rpm = 150.0').replace(
    'damping_speed_rpm = 200.0', 'damping_speed_rpm = 100.0')


def test_a_geared_line_gets_the_hammering_check(tmp_path):
    (tmp_path / "line.toml").write_text(GEARED)
    out = Path(run(tmp_path / "line.toml", tmp_path / "r", steps=FAST_STEPS, options=RunOptions(html=False)).folder)
    text = (out / "report.md").read_text()
    assert "### Gear hammering: vibratory against mean mesh torque" in text and "![](tvc_hammering.png)" in text
    ham = json.loads((out / "results.json").read_text())["tvc"]["hammering"]
    mesh = ham["meshes"][0]
    assert mesh["label"] == "flange-wheel" and mesh["station"] == "wheel"
    # the mean is the propeller law at the wheel (no other load on that side): Q_r (n f / n_r)²
    rpm = json.loads((out / "results.json").read_text())["tvc"]["hammering"]["rpm"]
    assert mesh["mean_nm"][-1] == pytest.approx(60e3 * (rpm[-1] * 0.25 / 150.0) ** 2, rel=1e-12)


@pytest.mark.slow  # 68 s: every misfire's passage in the time domain (each misfire's response: test_tvc_misfire)
def test_an_engine_line_gets_normal_running_and_each_misfire(tmp_path):
    text = (ROOT / "examples/networks/geared_engine.toml").read_text().replace(
        'between = ["wheel", "propeller"]     # propeller shaft',
        'between = ["wheel", "propeller"]\ndiameter_m = 0.012\ntensile_strength_pa = 600e6\nfeature = "integral_flange"')
    text += ('\n[[chain.propellers]]\nstation = "propeller"\nblades = 3\nentrained_water_share = 0.0\n'
             'rated_torque_nm = 100.0\nrated_speed_rpm = 1000.0\nblade_order_shares = [0.1]\n')
    (tmp_path / "line.toml").write_text(text)
    out = Path(run(tmp_path / "line.toml", tmp_path / "r", steps=FAST_STEPS, options=RunOptions(html=False)).folder)
    report = (out / "report.md").read_text()
    assert "### Normal running and misfire" in report and "Worst misfire: misfire of cylinder" in report
    res = json.loads((out / "results.json").read_text())["tvc"]
    assert [m["misfire_cylinder"] for m in res["misfires"]] == [1, 2, 3, 4]
    worst = res["worst_misfire_cylinder"]
    u = [m["largest_tau_over_tau_c"] for m in res["misfires"]]
    assert u[worst - 1] == max(u) and (out / "tvc_shafts_misfire.png").stat().st_size > 10_000


def test_the_installation_particulars_state_the_files_numbers():
    """The TVC's installation particulars: the indicated power at the rated speed is p_mi V_s n/120
    (4 strokes) from the file's bore, stroke and p_mi (the example's comment: 0.85 of it is its
    stated 1433 kW brake power, 1e-3), the coupling's sheet and the propeller's water as stated."""
    import math

    import fetorsion
    from conftest import ROOT
    from fetorsion.report.tvc import installation_lines

    net = fetorsion.load(ROOT / "examples/networks/propulsion_line_medium_speed.toml")
    text = "\n".join(installation_lines(net))
    v_s = 6 * math.pi / 4 * 0.32**2 * 0.41752
    kw = 1.2e6 * v_s * 836.7 / 120 / 1e3
    assert f"indicated power there {kw:.0f} kW" in text and 0.85 * kw == pytest.approx(1433, rel=1e-3)
    assert "on the propeller curve" in text and "25 % entrained water = 980 kg m²" in text
    assert "permissible vibratory torque not stated, P_KV 5759 W at 40 °C ambient" in text
    assert "| order | 0.5 |" in text
