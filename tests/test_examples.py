"""The example scripts run as a user would run them (coarse meshes to keep the suite fast)."""

import subprocess
import sys

import pytest

from conftest import ROOT, assert_picture

pytestmark = [pytest.mark.slow, pytest.mark.fe]

CASES = [
    ["examples/lumped_vs_fe.py", "geometry/peugeot_glx.toml", "30"],
    ["examples/web_thickness_study.py", "40"],
    ["examples/campbell_renault.py"],
    ["examples/mendes2008_six_cylinder.py"],
]


@pytest.mark.parametrize("args", CASES, ids=lambda a: a[0])
def test_example_runs(args):
    p = subprocess.run([sys.executable, *args], capture_output=True, text=True, cwd=ROOT, timeout=600)
    assert p.returncode == 0, p.stderr[-2000:]
    assert "Hz" in p.stdout or "deg" in p.stdout


def test_render_example(tmp_path):
    p = subprocess.run([sys.executable, "examples/render_first_torsional.py", "geometry/renault21.toml", str(tmp_path),
                        "30"], capture_output=True, text=True, cwd=ROOT, timeout=600)
    assert p.returncode == 0, p.stderr[-2000:]
    assert_picture(tmp_path / "first_torsional.png", min_ink=0.05)
    assert_picture(tmp_path / "lumped_17dof_modes.png")
