"""Issue 56 for the propulsion TVC: ``fetorsion report DIR`` reads the TVC section back from
results.json (report/load.py: tvc_outcome) and draws it again: report.md byte-identical, every
TVC picture redrawn the same, and the entry read back writes the very JSON it was read from.

Two small lines run in seconds: the illustrative line of test_tvc_run (a data-sheet coupling and a
keyed shaft section, blade orders alone) and the geared four-cylinder with a propeller and a 12 mm
section (normal running and each misfire, gear hammering, barred ranges and their time-domain
passages, run fast at a stated rate). The medium-speed example line (about 110 s) is slow."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from conftest import ROOT
from fetorsion.app.run import FAST_STEPS, RunOptions, run
from fetorsion.cli.commands import main
from fetorsion.report.load import load_run
from fetorsion.report.outcomes import TVCOutcome
from fetorsion.report.tvc import tvc_section
from fetorsion.results import jsonable
from test_load_results import same_json, twice
from test_tvc_run import LINE

#: The geared four-cylinder with a three-blade propeller and a 12 mm section on its shaft (barred about
#: its first mode); the passages run at 200 rpm/s, stated, to keep the time domain to seconds.
ENGINE_LINE = (ROOT / "examples/networks/geared_engine.toml").read_text().replace(
    'between = ["wheel", "propeller"]     # propeller shaft',
    'between = ["wheel", "propeller"]\ndiameter_m = 0.012\ntensile_strength_pa = 600e6\nfeature = "integral_flange"'
) + ('\n[[chain.propellers]]\nstation = "propeller"\nblades = 3\nentrained_water_share = 0.0\n'
     'rated_torque_nm = 100.0\nrated_speed_rpm = 1000.0\nblade_order_shares = [0.1]\npassage_rate_rpm_per_s = 200.0\n')

#: The Renault 21 crank (lumped) in its driveline with a 25 mm section on the half-shafts: the network's
#: crank is judged by UR M53 in each configuration.
CRANK_LINE = (ROOT / "examples/networks/renault21_driveline.toml").read_text().replace(
    'file = "../../geometry/renault21.toml"', f'file = "{ROOT / "geometry/renault21.toml"}"').replace(
    'stiffness_nm_per_rad = 1.2e4\nloss_factor = 0.05',
    'stiffness_nm_per_rad = 1.2e4\nloss_factor = 0.05\ndiameter_m = 0.025\ntensile_strength_pa = 600e6\n'
    'feature = "integral_flange"')


def _run(tmp: Path, name: str, text: str | None = None, path: Path | None = None) -> Path:
    if path is None:
        path = tmp / f"{name}.toml"
        path.write_text(text)
    return Path(run(path, tmp / name, steps=FAST_STEPS, options=RunOptions(html=False)).folder)


@pytest.fixture(scope="module")
def tvc_runs(tmp_path_factory) -> dict[str, Path]:
    tmp = tmp_path_factory.mktemp("tvc")
    return {"coupling": _run(tmp, "coupling", LINE), "engine": _run(tmp, "engine", ENGINE_LINE),
            "crank": _run(tmp, "crank", CRANK_LINE)}


def reports_the_same(folder: Path, copy: Path) -> None:
    """``fetorsion report`` on a copy of ``folder`` without its pictures: report.md byte for byte, every
    picture drawn again, byte for byte."""
    shutil.copytree(folder, copy)
    for png in copy.glob("*.png"):
        png.unlink()
    assert main(["report", str(copy)]) == 0
    assert (copy / "report.md").read_bytes() == (folder / "report.md").read_bytes()
    pictures = sorted(p.name for p in folder.glob("*.png"))
    assert sorted(p.name for p in copy.glob("*.png")) == pictures
    for name in pictures:
        assert (copy / name).read_bytes() == (folder / name).read_bytes(), name


@pytest.mark.slow  # 25 s: its fixture runs the TVC lines
def test_fetorsion_report_of_a_tvc_writes_the_same_report(tvc_runs, tmp_path, capsys):
    for kind, folder in tvc_runs.items():
        reports_the_same(folder, tmp_path / kind)
        assert "not read back" not in capsys.readouterr().out


@pytest.mark.slow  # its fixture runs the TVC lines (17 s)
def test_the_tvc_read_back_writes_the_json_it_was_read_from(tvc_runs):
    seen = set()
    for folder in tvc_runs.values():
        loaded = load_run(folder)
        assert not loaded.unread
        tvc = loaded.outcome.tvc
        assert isinstance(tvc, TVCOutcome)
        assert same_json(jsonable(tvc.to_dict()), loaded.results["tvc"])
        seen |= {k for k in ("couplings", "shafts", "hammering") if getattr(tvc, k) is not None}
        seen |= {"misfires"} if tvc.misfires else set()
        seen |= {"passages"} if tvc.passages else set()
        seen |= {"crank_m53"} if tvc.crank_m53 else set()
        # each result through its own to_dict and from_dict renders the section the same
        first = tvc_section(loaded.outcome.crank, tvc)
        results = [r for r in (tvc.shafts, tvc.hammering, *tvc.passages, *tvc.mode_rows) if r is not None]
        for result in results:
            assert same_json(jsonable(twice(result).to_dict()), jsonable(result.to_dict()))
        if tvc.couplings is not None:
            again = type(tvc.couplings).from_dict(json.loads(json.dumps(jsonable(tvc.couplings.to_dict()))))
            assert again.table() == tvc.couplings.table()
        assert tvc_section(loaded.outcome.crank, tvc) == first
    assert seen == {"couplings", "shafts", "hammering", "misfires", "passages", "crank_m53"}


@pytest.mark.slow  # its fixture runs the TVC lines (17 s)
def test_a_tvc_entry_written_before_it_was_kept_whole_is_named_unread(tvc_runs, tmp_path, capsys):
    copy = tmp_path / "old"
    shutil.copytree(tvc_runs["coupling"], copy)
    data = json.loads((copy / "results.json").read_text())
    del data["tvc"]["assumptions"]
    (copy / "results.json").write_text(json.dumps(data))
    before = (copy / "report.md").read_bytes()
    assert "tvc" in load_run(copy).unread
    assert main(["report", str(copy)]) == 0
    assert "assumptions" in capsys.readouterr().out
    assert (copy / "report.md").read_bytes() == before  # kept as it was


@pytest.mark.slow
def test_fetorsion_report_of_the_medium_speed_line_writes_the_same_report(tmp_path):
    folder = _run(tmp_path, "medium", path=ROOT / "examples/networks/propulsion_line_medium_speed.toml")
    reports_the_same(folder, tmp_path / "copy")
    loaded = load_run(folder)
    assert same_json(jsonable(loaded.outcome.tvc.to_dict()), loaded.results["tvc"])


def test_the_conclusions_name_the_cranks_largest_torque_and_each_criterion(tvc_runs):
    """The TVC's conclusions: the crank's largest section torque is the largest half-range torque of
    the response's sections with a cylinder station at one end (read from results.json's own
    response), shown as not judged; each criterion the line has gets its line."""
    folder = tvc_runs["engine"]
    d = json.loads((folder / "results.json").read_text())["tvc"]
    response = d["response"]
    throws = {f"throw {k}" for k in range(1, 5)}
    torque = np.array(response["section_torque_nm"])
    cols = [k for k, label in enumerate(response["sections"]) if set(label.split("-")) & throws]
    assert cols and d["crank_torque_nm"] == pytest.approx(torque[:, cols].max(), rel=1e-12)
    text = (folder / "report.md").read_text()
    conclusions = text.split("### Conclusions")[1].split("###")[0]
    assert f"{d['crank_torque_nm'] / 1e3:.1f} kN m" in conclusions and "Crankshaft: not judged here" in conclusions
    assert "Shafts, IACS UR M68" in conclusions and "Gear hammering" in conclusions
