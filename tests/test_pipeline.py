"""`fetorsion run`: a complete report folder, or nothing at all."""

import json

import pytest

import fetorsion
from fetorsion.errors import DescriptionError
from fetorsion.pipeline import DEFAULT_STEPS, run

from conftest import GEOMETRY


def test_run_writes_report_consistent_with_the_api(tmp_path):
    out = run(GEOMETRY / "peugeot_glx.toml", tmp_path / "glx")
    report = (out / "report.md").read_text()
    assert "## Lumped models" in report and "905.9" in report
    data = json.loads((out / "results.json").read_text())
    f17 = data["lumped"]["carter"][2]["frequencies_hz"][0]
    assert f17 == pytest.approx(fetorsion.lumped(fetorsion.load(GEOMETRY / "peugeot_glx.toml"), 17).frequencies_hz[0],
                                rel=1e-12)
    for img in ("lumped_modes_17dof.png", "sensitivity.png"):
        assert (out / img).stat().st_size > 10_000
    assert [p.name for p in tmp_path.iterdir()] == ["glx"]  # no temporary folder left


def test_broken_description_fails_cleanly_and_writes_nothing(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text((GEOMETRY / "peugeot_glx.toml").read_text().replace("width_pin = 66.0", "width_pin = 40.0", 1))
    with pytest.raises(DescriptionError, match="webs.1.width_pin"):
        run(bad, tmp_path / "out")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml"]


def test_failing_step_keeps_the_previous_report(tmp_path):
    out = run(GEOMETRY / "peugeot_glx.toml", tmp_path / "r", steps=DEFAULT_STEPS[:1])
    before = (out / "report.md").read_text()

    def broken(ctx):
        (ctx.folder / "partial.txt").write_text("half")
        raise RuntimeError("step failed")

    with pytest.raises(RuntimeError):
        run(GEOMETRY / "renault21.toml", tmp_path / "r", steps=DEFAULT_STEPS[:1] + (("broken", broken),))
    assert (out / "report.md").read_text() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r"]
    assert not (out / "partial.txt").exists()
