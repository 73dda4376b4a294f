"""CLI: kinematics, balance, flywheel on the shipped files; user mistakes exit 2 with the rule."""

import json

import pytest

from fetorsion.cli import main
from conftest import GEOMETRY, assert_picture


def run(capsys, *argv):
    rc = main(list(argv))
    cap = capsys.readouterr()
    return rc, cap.out, cap.err


def test_balance_b112_json_and_plot(tmp_path, capsys):
    js, png = tmp_path / "b.json", tmp_path / "b.png"
    rc, out, _ = run(capsys, "balance", str(GEOMETRY / "b112_single.toml"), "--json", str(js), "--plot", str(png))
    assert rc == 0 and "counterweight B" in out
    rep = json.loads(js.read_text())
    assert rep["counterweight_kg"] == pytest.approx(2.109, abs=1.5e-3)   # seed 000, 3-digit intermediates
    assert rep["balance_shaft_kg"] == pytest.approx(0.693, abs=1.5e-3)
    assert_picture(png)


def test_flywheel_b112_json_stdout(capsys):
    rc, out, err = run(capsys, "flywheel", str(GEOMETRY / "b112_single.toml"), "--json", "-")
    assert rc == 0 and "ΔE" in err                                     # table to stderr when JSON goes to stdout
    rep = json.loads(out)
    assert rep["mass_at_rounded_inertia_kg"] == pytest.approx(6.15, abs=0.005)


def test_kinematics_slider_crank_and_planetary(tmp_path, capsys):
    rc, out, _ = run(capsys, "kinematics", str(GEOMETRY / "b112_single.toml"), "--step", "90")
    assert rc == 0 and len([l for l in out.splitlines() if l.strip().startswith(("0.0", "90.0", "180.0"))]) == 3
    png = tmp_path / "p.png"
    rc, out, _ = run(capsys, "kinematics", str(GEOMETRY / "planetary_ismailov.toml"), "--plot", str(png))
    assert rc == 0 and "epicycloid d_f = 60, d_p = 30 mm" in out and png.exists()


def test_crank_description_needs_rpm(capsys):
    rc, _, err = run(capsys, "kinematics", str(GEOMETRY / "renault21.toml"))
    assert rc == 2 and "--rpm" in err
    rc, out, _ = run(capsys, "kinematics", str(GEOMETRY / "renault21.toml"), "--rpm", "3000")
    assert rc == 0 and "λ = 0.28" in out


def test_bad_mechanics_file_lists_every_problem(tmp_path, capsys):
    f = tmp_path / "bad.toml"
    f.write_text('[units]\nlength = "mm"\n[slider_crank]\ncrank_radius = 50\nrod_length = 40\nspeed_rpm = -1\n'
                 'colour = "red"\n[flywheel]\npower_w = 1\nspeed_rpm = 100\nspeed_fluctuation = 0.02\nouter_diameter = 100\n')
    rc, _, err = run(capsys, "flywheel", str(f))
    assert rc == 2
    for text in ("slider_crank.speed_rpm", "slider_crank.colour", "slider_crank.rod_length", "flywheel.inner_diameter"):
        assert text in err
    rc, _, err = run(capsys, "balance", str(GEOMETRY / "planetary_ismailov.toml"))
    assert rc == 2 and "masses" in err and "this command needs the table" in err
