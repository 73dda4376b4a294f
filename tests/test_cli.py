"""The command line as a user runs it: tables, JSON, clean errors."""

import json
import subprocess
import sys

from conftest import GEOMETRY, ROOT


def run(*args):
    return subprocess.run([sys.executable, "-m", "fetorsion.cli", *args], capture_output=True, text=True, cwd=ROOT)


def test_lumped_all_json_stdout():
    p = run("lumped", str(GEOMETRY / "peugeot_glx.toml"), "--dof", "all", "--json", "-")
    assert p.returncode == 0, p.stderr
    data = json.loads(p.stdout)
    assert [m["dof"] for m in data["models"]] == [5, 6, 17, 19, 21]
    for m in data["models"]:
        assert len(m["frequencies_hz"]) == m["dof"] - 1
        assert len(m["mode_shapes"]) == m["dof"] - 1 and len(m["mode_shapes"][0]) == m["dof"]
        assert len(m["inertias_kgm2"]) == m["dof"] and len(m["stiffnesses_nm_per_rad"]) == m["dof"] - 1
        assert m["frequencies_hz"] == sorted(m["frequencies_hz"])
    assert [q["part"] for q in data["parts"]][:4] == ["F1", "F2", "J1", "W1"]
    assert data["description"]["units"]["length"] == "mm"
    assert "17 DOF" in p.stderr  # the table goes to stderr when JSON takes stdout


def test_lumped_json_file_and_table(tmp_path):
    out = tmp_path / "r.json"
    p = run("lumped", str(GEOMETRY / "renault21.toml"), "--dof", "5,17", "--stiffness", "ker-wilson",
            "--json", str(out))
    assert p.returncode == 0, p.stderr
    assert "5 DOF" in p.stdout and "17 DOF" in p.stdout
    data = json.loads(out.read_text())
    assert data["stiffness_method"] == "ker-wilson" and len(data["models"]) == 2


def test_bad_description_is_a_clean_error(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text((GEOMETRY / "peugeot_glx.toml").read_text().replace('length = "mm"', 'length = "parsec"'))
    p = run("lumped", str(bad), "--json", str(tmp_path / "out.json"))
    assert p.returncode == 2
    assert "units.length" in p.stderr and "parsec" in p.stderr and "Traceback" not in p.stderr
    assert not (tmp_path / "out.json").exists()


def test_bad_dof_option():
    p = run("lumped", str(GEOMETRY / "peugeot_glx.toml"), "--dof", "7")
    assert p.returncode == 2 and "not a partition" in p.stderr


def test_run_on_broken_description_exits_2_and_writes_nothing(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text((GEOMETRY / "renault21.toml").read_text().replace("stroke = 83.5", "stroke = -83.5"))
    p = run("run", str(bad), "--out", str(tmp_path / "report"))
    assert p.returncode == 2 and "engine.stroke" in p.stderr and "Traceback" not in p.stderr
    assert sorted(x.name for x in tmp_path.iterdir()) == ["bad.toml"]


def test_version_is_printed(capsys):
    """Issue 41: `fetorsion --version` prints the package's version (not refused)."""
    import pytest

    import fetorsion
    from fetorsion.cli import main

    with pytest.raises(SystemExit) as exit_:
        main(["--version"])
    assert exit_.value.code == 0 and capsys.readouterr().out.strip() == f"fetorsion {fetorsion.__version__}"
