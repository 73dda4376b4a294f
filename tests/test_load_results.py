"""Issue 56: a run's results.json read back into its typed outcome, and ``fetorsion report DIR``
drawing the report folder again from it, with no FE."""

import json
import math
import shutil
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

import fetorsion
from conftest import ROOT

from fetorsion.cli.commands import main
from fetorsion.errors import FetorsionError
from fetorsion.report import markdown
from fetorsion.report.load import load_run
from fetorsion.report.outcomes import (CampbellOutcome, ChainOutcome, FEOutcome, LumpedOutcome, MeasuredOutcome,
                                      RunOutcome, SensitivityOutcome, TransientOutcome, VerdictOutcome)
from fetorsion.results import Result, from_fields, jsonable

#: Committed run folders (fetorsion run on the reference cranks; results/ is written by scripts/results.sh)
FOLDERS = ("renault21", "peugeot_glx")
#: The report's sections read back today, with the function that renders each.
READ_BACK = (("lumped", markdown.lumped_section), ("fe", markdown.fe_section),
             ("campbell", markdown.campbell_section), ("sensitivity", markdown.sensitivity_section))


def same_json(a, b, rel: float = 0.0) -> bool:
    """JSON equality with NaN equal to NaN (numbers within ``rel``: an order track's amplitudes go
    through degrees and back)."""
    if isinstance(a, dict):
        return isinstance(b, dict) and a.keys() == b.keys() and all(same_json(a[k], b[k], rel) for k in a)
    if isinstance(a, list):
        return isinstance(b, list) and len(a) == len(b) and all(same_json(x, y, rel) for x, y in zip(a, b))
    if isinstance(a, float) and isinstance(b, float):
        return a == b or math.isnan(a) and math.isnan(b) or math.isclose(a, b, rel_tol=rel, abs_tol=1e-300 if rel else 0)
    return a == b


def section_results(outcome):
    """Each section's results objects as (name, result)."""
    if isinstance(outcome, LumpedOutcome):
        return [(f"{m}[{k}]", r) for m, rs in outcome.table.items() for k, r in enumerate(rs)]
    if isinstance(outcome, FEOutcome):
        return [("modal", outcome.modal)]
    if isinstance(outcome, CampbellOutcome):
        return [("campbell", outcome.campbell), ("response", outcome.response)]
    if isinstance(outcome, SensitivityOutcome):
        return [("sensitivity", outcome.sensitivity)] + list(outcome.studies.items())
    return []


def twice(result):
    """``result`` through its own to_dict and from_dict, via JSON text."""
    return type(result).from_dict(json.loads(json.dumps(jsonable(result.to_dict()))))


@pytest.fixture(scope="module", params=FOLDERS)
def loaded(request):
    return load_run(ROOT / "results" / request.param)


def test_every_section_read_back_renders_the_same_after_a_second_round_trip(loaded):
    """load -> render is byte-identical to load -> to_dict -> from_dict -> render, section by section."""
    run = loaded.outcome
    for key, render in READ_BACK:
        outcome = getattr(run, key)
        if outcome is None:
            continue
        first = render(run.crank, outcome)
        again = outcome
        for name, result in section_results(outcome):
            assert isinstance(result, Result), name
            copy = twice(result)
            assert same_json(jsonable(copy.to_dict()), jsonable(result.to_dict())), name
            again = _replaced(again, result, copy)
        assert render(run.crank, again) == first, key


def _replaced(outcome, old, new):
    """``outcome`` with the result ``old`` swapped for ``new`` wherever it holds it."""
    import dataclasses

    changes = {}
    for f in dataclasses.fields(outcome):
        value = getattr(outcome, f.name)
        if value is old:
            changes[f.name] = new
        elif isinstance(value, dict):
            changes[f.name] = {k: (new if v is old else [new if x is old else x for x in v] if isinstance(v, list)
                                   else v) for k, v in value.items()}
    return dataclasses.replace(outcome, **changes)


def test_the_json_read_back_is_the_files(loaded):
    """Each result read back writes the entry it was read from (keys it adds aside: the file
    predates them)."""
    data, run = loaded.results, loaded.outcome
    pairs = [(data["fe"], run.fe.modal)] + [(data["lumped"][m][k], r) for m, rs in run.lumped.table.items()
                                           for k, r in enumerate(rs)]
    if isinstance(run.campbell, CampbellOutcome):
        pairs += [(data["campbell"], run.campbell.campbell), (data["response"], run.campbell.response)]
    pairs += [(data["sensitivity"], run.sensitivity.sensitivity)]
    pairs += [(data["studies"][m], s) for m, s in run.sensitivity.studies.items()]
    for stored, result in pairs:
        written = jsonable(result.to_dict())
        assert same_json({k: v for k, v in written.items() if k in stored},
                         {k: v for k, v in stored.items() if k in written})


def test_the_sections_read_back_render_as_the_committed_report():
    """The committed Renault 21 report's sections that are read back, rendered from its results.json."""
    run = load_run(ROOT / "results/renault21").outcome
    text = (ROOT / "results/renault21/report.md").read_text()
    for key, render in (("lumped", markdown.lumped_section), ("campbell", markdown.campbell_section),
                        ("sensitivity", markdown.sensitivity_section)):
        assert "\n".join(render(run.crank, getattr(run, key))) in text, key


@pytest.mark.parametrize("name", ["renault21", "peugeot_glx", "peugeot_glx_engine", "inline6_diesel", "v8_petrol"])
def test_the_bearings_section_read_back_is_the_committed_reports(name):
    """The condensed crank in its bearings from what results.json keeps (its facts and modes): its
    section (up to the coupled response, which these folders were written without the pins'
    torque and journals' bending of) and its summary line, as the committed report has them."""
    from fetorsion.fe.condensed import CondensedModes
    from fetorsion.report.outcomes import BearingsOutcome, CondensedFacts
    from fetorsion.report.summary import summary_lines

    folder = ROOT / "results" / name
    loaded, text = load_run(folder), (folder / "report.md").read_text()
    d = loaded.results["bearings"]
    outcome = BearingsOutcome(CondensedFacts.from_dict(d), CondensedModes.from_rows("free", d["free"]),
                              CondensedModes.from_rows("bearings", d["bearings"]), d["lumped_17dof"],
                              d["f1_free_hz"], d["f1_bearings_hz"], ("modes_free_and_bearings.png",))
    if "coupled_response" not in d:  # read back whole: the same outcome
        assert "bearings" not in loaded.unread
        assert markdown.bearings_section(loaded.outcome.crank, loaded.outcome.bearings) == markdown.bearings_section(
            loaded.outcome.crank, outcome)
    section = "\n".join(markdown.bearings_section(loaded.outcome.crank, outcome))
    head = section.split("\n\n![](modes_free_and_bearings.png)")[0]
    assert head in text
    run = RunOutcome(loaded.outcome.crank, "", bearings=outcome)
    assert summary_lines(run)[2] in text


def test_a_coupled_response_round_trips():
    from fetorsion.response.coupled import CoupledResponse

    d = dict(load_run(ROOT / "results/renault21").results["bearings"]["coupled_response"])
    d.pop("pin_torque_nm", None), d.pop("journal_bending_nm", None)  # as a folder written before they were kept
    with pytest.raises(FetorsionError, match="written before"):
        CoupledResponse.from_dict(d)
    rng = np.random.default_rng(2)
    d["pin_torque_nm"], d["journal_bending_nm"] = (rng.random(np.shape(d["journal_torque_nm"])) for _ in range(2))
    res = CoupledResponse.from_dict(json.loads(json.dumps(jsonable(d))))
    copy = twice(res)
    assert copy.table() == res.table() and same_json(jsonable(copy.to_dict()), jsonable(res.to_dict()))
    assert copy.plot().get_title() == res.plot().get_title()


@pytest.mark.parametrize("name", ["renault21", "peugeot_glx", "peugeot_glx_engine", "inline6_diesel", "v8_petrol"])
def test_fetorsion_report_writes_the_committed_report_again(tmp_path, capsys, name):
    """Issue 56's done-when: `fetorsion report` on a copy of each committed crank folder (a
    `fetorsion run` with FE, written by this code) reads every section back and writes report.md
    byte-identical to the run's, every figure of matplotlib the same to the byte (the PyVista mode
    images are kept: they need the mesh); no FE, no solve."""
    folder = tmp_path / name
    shutil.copytree(ROOT / "results" / name, folder)
    before = {p.name: p.read_bytes() for p in folder.iterdir() if p.suffix in (".md", ".png")}
    t0 = time.perf_counter()
    assert main(["report", str(folder)]) == 0
    seconds = time.perf_counter() - t0
    out = capsys.readouterr().out
    assert "not read back" not in out and "report.md" in out.splitlines()[0], out
    after = {p.name: p.read_bytes() for p in folder.iterdir() if p.suffix in (".md", ".png")}
    assert after.keys() == before.keys()
    assert [n for n in before if after[n] != before[n]] == []
    # the issue asks under 10 s on a quiet machine (measured 5-9 s): the bound leaves a loaded CI
    # machine three times that
    assert seconds < 30, seconds


@pytest.mark.parametrize("make, message", [(lambda p: None, "no such report folder"),
                                           (lambda p: p.mkdir(), "no results.json"),
                                           (lambda p: (p.mkdir(), (p / "results.json").write_text("{")),
                                            "cannot be read")])
def test_a_bad_folder_is_named(tmp_path, capsys, make, message):
    folder = tmp_path / "out"
    make(folder)
    assert main(["report", str(folder)]) == 2
    err = capsys.readouterr().err
    assert str(folder) in err and message in err


def test_from_fields_reads_annotations():
    @dataclass
    class Inner:
        x: float

    @dataclass
    class Outer:
        a: np.ndarray
        b: tuple[float, ...]
        c: dict[str, Inner]
        d: Inner | None = None
        e: float = 0.0

    o = from_fields(Outer, {"a": [1, None], "b": [1.5, 2.5], "c": {"k": {"x": 1.5}}, "E": None}, {"e": "E"})
    assert np.isnan(o.a[1]) and o.b == (1.5, 2.5) and o.c["k"] == Inner(1.5) and o.d is None and np.isnan(o.e)


def test_a_network_result_reads_back_its_layout_not_its_matrices():
    from fetorsion.lumped_model.lumped import LumpedResult, lumped

    res = lumped(fetorsion.load(ROOT / "examples/networks/geared_engine.toml"))
    copy = twice(res)
    assert copy.table() == res.table() and same_json(jsonable(copy.to_dict()), jsonable(res.to_dict()))
    with pytest.raises(FetorsionError, match="not its matrices"):
        copy.matrices()


# ---------------------------------------------------------------------------
# Chain and network runs (no FE: seconds): run -> fetorsion report -> the same report.md and figures

def _chain_runs(tmp: Path) -> dict[str, Path]:
    """A chain set against a measured order cut (the measured comparison) and a network with torque
    limits (the verdict), both with their run-up: each run's report folder."""
    from fetorsion.response.forced import run_response

    chain = ROOT / "examples/mendes2008/mwm6_chain.toml"
    r = run_response(fetorsion.load(chain))
    k = int(np.flatnonzero(np.isclose(r.orders, 6.0))[0])
    rows = "\n".join(f"{s:.12g}, {0.9 * np.degrees(a):.12g}" for s, a in zip(r.rpm[::5], np.abs(r.theta[::5, k, 0])))
    (tmp / "cut.csv").write_text(f"# unit = deg\n# order = 6\n{rows}\n")
    (tmp / "net.toml").write_text((ROOT / "examples/networks/geared_engine.toml").read_text() + (
        '\n[limits]\ncontinuous_torque_nm = 2000.0\ntransient_torque_nm = 4000.0\nsource = "test"\n'))
    assert main(["run", str(chain), "--out", str(tmp / "chain"), "--measured", str(tmp / "cut.csv")]) == 0
    assert main(["run", str(tmp / "net.toml"), "--out", str(tmp / "network")]) == 0
    return {"chain": tmp / "chain", "network": tmp / "network"}


@pytest.fixture(scope="module")
def chain_runs(tmp_path_factory):
    return _chain_runs(tmp_path_factory.mktemp("runs"))


CHAIN_SECTIONS = (("lumped", ChainOutcome, markdown.lumped_section), ("verdict", VerdictOutcome, markdown.verdict_section),
                  ("measured", MeasuredOutcome, markdown.measured_section),
                  ("transient", TransientOutcome, markdown.transient_section),
                  ("campbell", CampbellOutcome, markdown.campbell_section))


def chain_results(outcome) -> list:
    """A chain's or network's section's results objects."""
    if isinstance(outcome, ChainOutcome):
        return [outcome.chain]
    if isinstance(outcome, VerdictOutcome):
        return [outcome.verdict]
    if isinstance(outcome, MeasuredOutcome):
        return [outcome.comparison]
    if isinstance(outcome, TransientOutcome):
        assert all(twice(c) == c for c in outcome.cuts)  # a part of the section, not a result of its own
        return [outcome.transient]
    return section_results(outcome) and [r for _, r in section_results(outcome)]


def test_fetorsion_report_of_a_chain_and_a_network_writes_the_same_report(chain_runs, tmp_path, capsys):
    """run -> fetorsion report: report.md byte-identical, every figure drawn again (the same PNG)."""
    for kind, folder in chain_runs.items():
        copy = tmp_path / kind
        shutil.copytree(folder, copy)
        for png in copy.glob("*.png"):
            png.unlink()
        t0 = time.perf_counter()
        assert main(["report", str(copy)]) == 0
        assert time.perf_counter() - t0 < 60  # about 4 s on a shared 2-core machine
        assert "not read back" not in capsys.readouterr().out
        assert (copy / "report.md").read_bytes() == (folder / "report.md").read_bytes(), kind
        pictures = sorted(p.name for p in folder.glob("*.png"))
        assert sorted(p.name for p in copy.glob("*.png")) == pictures, kind
        for name in pictures:
            assert (copy / name).read_bytes() == (folder / name).read_bytes(), (kind, name)


def test_a_chains_and_networks_sections_round_trip(chain_runs):
    """Each section read back renders the same after a second round trip; its JSON is the file's."""
    seen = set()
    for folder in chain_runs.values():
        loaded = load_run(folder)
        run, data = loaded.outcome, loaded.results
        assert not loaded.unread
        for key, kind, render in CHAIN_SECTIONS:
            outcome = getattr(run, key)
            if not isinstance(outcome, kind):
                continue
            seen.add(key)
            first = render(run.crank, outcome)
            again = outcome
            for result in chain_results(outcome):
                assert isinstance(result, Result), key
                copy = twice(result)
                assert same_json(jsonable(copy.to_dict()), jsonable(result.to_dict()), rel=1e-12), key
                again = _replaced(again, result, copy)
            assert render(run.crank, again) == first, key
        stored = {"lumped": data["lumped"]["chain"], "verdict": data.get("verdict"),
                  "measured": data.get("measured"), "transient": data.get("transient")}
        results = {"lumped": run.lumped.chain, "verdict": getattr(run.verdict, "verdict", None),
                   "measured": getattr(run.measured, "comparison", None),
                   "transient": getattr(run.transient, "transient", None)}
        for key, result in results.items():
            if result is not None:
                written = jsonable(result.to_dict())
                assert same_json({k: v for k, v in stored[key].items() if k in written}, written, rel=1e-12), key
    assert seen == {k for k, _, _ in CHAIN_SECTIONS}


def test_a_study_with_its_runs_round_trips_its_histogram_and_percentile():
    mc = load_run(ROOT / "results/peugeot_glx").outcome.sensitivity.studies["montecarlo"]
    rng = np.random.default_rng(1)
    mc.X, mc.Y, mc.percentile_read = rng.random((len(mc.X), len(mc.inputs))), {"f1": 850 + 100 * rng.random(len(mc.X))}, None
    copy = twice(mc)
    assert np.array_equal(copy.Y["f1"], mc.Y["f1"]) and copy.measured_percentile() == mc.measured_percentile()
