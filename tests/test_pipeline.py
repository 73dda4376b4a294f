"""`fetorsion run`: a complete report folder, or nothing at all."""

from pathlib import Path
import json

import pytest

import fetorsion
from fetorsion.design.scfset import SCFSet
from fetorsion.errors import DescriptionError
from fetorsion.app.run import DEFAULT_STEPS, RunOptions, run

from conftest import GEOMETRY, ROOT, assert_picture


NO_FE = tuple(step for step in DEFAULT_STEPS if step[1] not in ("fe", "bearings"))
LUMPED = tuple(step for step in DEFAULT_STEPS if step[1] == "lumped")


@pytest.mark.slow
def test_run_writes_report_consistent_with_the_api(tmp_path, monkeypatch):
    from figure_checks import check_run_figures

    problems, drawn = check_run_figures(monkeypatch)  # issue 54: the studies' figures read at a glance too
    out = Path(run(GEOMETRY / "peugeot_glx.toml", tmp_path / "glx", steps=NO_FE).folder)
    assert {"sensitivity.png", "f1_montecarlo.png", "f1_sobol.png"} <= set(drawn) and not problems, problems
    report = (out / "report.md").read_text()
    assert "## Lumped models" in report and "905.9" in report
    data = json.loads((out / "results.json").read_text())
    f17 = data["lumped"]["carter"][2]["frequencies_hz"][0]
    assert f17 == pytest.approx(fetorsion.lumped(fetorsion.load(GEOMETRY / "peugeot_glx.toml"), 17).frequencies_hz[0],
                                rel=1e-12)
    for img in ("lumped_modes_17dof.png", "sensitivity.png", "f1_montecarlo.png", "f1_sobol.png"):
        assert_picture(out / img)
    assert [p.name for p in tmp_path.iterdir()] == ["glx"]  # no temporary folder left
    # Monte Carlo band against the corner band (f1 is monotone in each input, so the corners
    # bound every sample), and the Sobol' ranking against the one-at-a-time swings.
    mc, sob, sens = data["studies"]["montecarlo"], data["studies"]["sobol"], data["sensitivity"]
    assert mc["runs"] == 2000 and mc["failed"] == 0 and "### Monte Carlo distribution of f1" in report
    lo, hi = sens["band_hz"]
    assert lo < mc["bands"]["f1"]["p5"] < mc["bands"]["f1"]["p50"] < mc["bands"]["f1"]["p95"] < hi
    swing = {r["field"]: abs(r["f1_high_hz"] - r["f1_low_hz"]) for r in sens["rows"]}
    st = dict(zip([i["name"] for i in sob["inputs"]], sob["indices"]["f1"]["ST"]))
    assert max(st, key=st.get) == max(swing, key=swing.get) and "### Sobol' indices of f1" in report
    page = (out / "report.html").read_text()
    assert 'id="f1_montecarlo"' in page and 'id="f1_sobol"' in page  # interactive in the web page


@pytest.mark.fe
@pytest.mark.slow
def test_full_run_with_fe_and_mode_images(tmp_path, monkeypatch):
    # Every step, FE included, on the Renault crank without fillets and drillings (cheap mesh), in a
    # store of its own: a run of the same crank earlier in the session would have left its FE step
    # there (fetorsion.app.run_store), and this test counts the FE work the run does.
    import re
    from PIL import Image

    from fetorsion.fe import condensed as condensed_module
    from fetorsion.fe import crankfe, cranksystem
    text = (GEOMETRY / "renault21.toml").read_text()
    text = re.sub(r"^\[uncertainty\].*", "", text, flags=re.M | re.S)
    text = re.sub(r"^(journal|pin|diameter) = (2\.5|5\.0)", r"\1 = 0.0", text, flags=re.M)
    src = tmp_path / "r21.toml"
    src.write_text(text)
    monkeypatch.setenv("FETORSION_STORE", str(tmp_path / "store"))
    condensations, systems = [], []
    original, build = condensed_module.run_condensed, cranksystem.build_system

    def counted(*args, **kwargs):
        condensations.append(kwargs.get("system"))
        return original(*args, **kwargs)

    def built(*args, **kwargs):
        systems.append(args[1:2])
        return build(*args, **kwargs)

    monkeypatch.setattr(condensed_module, "run_condensed", counted)
    for module in (crankfe, condensed_module, cranksystem):
        monkeypatch.setattr(module, "build_system", built)
    from figure_checks import check_run_figures

    problems, drawn = check_run_figures(monkeypatch)  # issue 54: every figure of the whole run
    out = Path(run(src, tmp_path / "r21", options=RunOptions(mesh_size=0.03)).folder)
    assert {"campbell.png", "response.png", "modes_free_and_bearings.png"} <= set(drawn), drawn  # no [uncertainty]: no studies
    assert not problems, problems
    # one mesh, one assembly and one factorisation serve the free-free modes, the condensed crank
    # (free and in bearings) and the lumped fe-held column (its throws' in-bearing stiffness)
    assert systems == [(0.03,)] and len(condensations) == 1 and condensations[0] is not None
    data = json.loads((out / "results.json").read_text())
    f1 = data["fe"]["first_torsional_hz"]
    assert 0.9 < f1 / data["lumped"]["carter"][2]["frequencies_hz"][0] < 1.1
    images = sorted(out.glob("mode_*_torsional.png"))
    assert images and Image.open(images[0]).size == (1400, 600)
    # the Campbell diagram used the FE crank's modes in its bearings (the condensed crank)
    assert "condensed FE crank, bearings" in data["campbell"]["source"]
    b = data["bearings"]
    assert b["reduced_dofs"] <= 400 and b["f1_free_hz"] == pytest.approx(f1, rel=1e-3)  # same mesh, same ties
    report = (out / "report.md").read_text()
    assert "## The crank in its bearings" in report and "## 3D FE modal analysis" in report
    # the summary opens the report, each line naming the model it comes from
    summary = report.split("## Summary", 1)[1].split("\n## ", 1)[0]
    lines = [x for x in summary.splitlines() if x.startswith("- ")]
    assert len(lines) >= 2  # free-free and in-engine f1 (no verdict: this crank has no fillet radii)
    for line in lines:
        assert any(m in line for m in ("3D FE", "condensed crank", "lumped")), line
    assert data["response"]["model"].startswith("condensed crank")  # the engine model answered
    # The web page beside it: the same sections, interactive figures, no still picture left
    # where one replaces it, nothing fetched from the network.
    page = (out / "report.html").read_text()
    assert "3D FE modal analysis" in page and "Campbell diagram" in page
    for div in ('id="modes"', 'id="campbell"', 'id="response"'):
        assert div in page, div
    assert 'src="campbell.png"' not in page and "<script src=" not in page
    assert (out / "report.html").stat().st_size < 25 * 2**20


def test_broken_description_fails_cleanly_and_writes_nothing(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text((GEOMETRY / "peugeot_glx.toml").read_text().replace("width_pin = 66.0", "width_pin = 40.0", 1))
    with pytest.raises(DescriptionError, match="webs.1.width_pin"):
        run(bad, tmp_path / "out")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml"]


def test_failing_step_keeps_the_previous_report(tmp_path):
    out = Path(run(GEOMETRY / "peugeot_glx.toml", tmp_path / "r", steps=LUMPED).folder)
    before = (out / "report.md").read_text()

    def broken(ctx):
        (ctx.folder / "partial.txt").write_text("half")
        raise RuntimeError("step failed")

    with pytest.raises(RuntimeError):
        run(GEOMETRY / "renault21.toml", tmp_path / "r", steps=LUMPED + (("broken", "verdict", broken),))
    assert (out / "report.md").read_text() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r"]
    assert not (out / "partial.txt").exists()


def test_report_files_are_readable_by_others(tmp_path):
    import os
    import stat
    out = Path(run(GEOMETRY / "peugeot_glx.toml", tmp_path / "glx", steps=NO_FE[:1]).folder)
    mask = os.umask(0)
    os.umask(mask)
    for p in [out, *out.iterdir()]:
        mode = stat.S_IMODE(p.stat().st_mode)
        expected = (0o777 if p.is_dir() else 0o666) & ~mask
        assert mode == expected, (p, oct(mode))


@pytest.mark.slow  # 28-33 s: a whole run without FE, its f1 studies included
def test_a_run_builds_what_its_steps_share_once(tmp_path, monkeypatch):
    # Every step that needs the crank's parts (per web method), the forced response's setup or
    # the fillet list gets the one the run built; studies' variants are other cranks and build
    # their own. Counted by wrapping each builder wherever a module holds it.
    import sys
    from collections import Counter

    from fetorsion.design import stress
    from fetorsion.lumped_model import parts
    from fetorsion.response import forced

    nominal = json.dumps(fetorsion.load(GEOMETRY / "renault21.toml").raw, sort_keys=True, default=str)
    calls = Counter()

    def counting(name, original):
        def wrapper(crank, *args, **kwargs):
            if json.dumps(crank.raw, sort_keys=True, default=str) == nominal:
                method = args[0] if name == "build_parts" and args else kwargs.get("web_method", "")
                calls[name, method if name == "build_parts" else ""] += 1
            return original(crank, *args, **kwargs)
        return wrapper

    for module, name in ((parts, "build_parts"), (forced, "response_setup"), (stress, "fillets_of")):
        original = getattr(module, name)
        wrapper = counting(name, original)
        for m in list(sys.modules.values()):
            if m is not None and m.__name__.startswith("fetorsion") and getattr(m, name, None) is original:
                monkeypatch.setattr(m, name, wrapper)
    run(GEOMETRY / "renault21.toml", tmp_path / "r", steps=NO_FE)
    from fetorsion.webs.methods import WEB_METHODS

    # without the FE steps a crank has no verdict step that needs its fillets (its verdict, the
    # fatigue, runs on the condensed crank): fillets_of is not called at all
    assert calls == Counter({**{("build_parts", m): 1 for m in WEB_METHODS}, ("response_setup", ""): 1})


def test_the_runs_background_throw_fe_is_what_the_fe_column_and_the_verdict_read(monkeypatch, tmp_path):
    """A crank without stored throw data: its throw FE runs in the background process (first in
    its queue) and the run's lumped ``fe`` column and fillet SCFs read that result, with no throw FE
    of their own (which would raise here). Web length checked against the method's formula."""
    import concurrent.futures
    import dataclasses
    import math

    from fetorsion.app.run import RunContext, needs_throw_fe
    from fetorsion.report.outcomes import RunOutcome
    from fetorsion.description.edit import with_values
    from fetorsion.webs import throwfe

    crank = with_values(fetorsion.load(GEOMETRY / "renault21.toml"), {"pins.*.diameter": 49.0})
    # the reference crank's web stiffnesses are shipped (its stress-recovery fields are the store's)
    assert needs_throw_fe(crank) and not needs_throw_fe(fetorsion.load(GEOMETRY / "renault21.toml"), scfs=False)
    throw = throwfe.throw_of(crank, 0)
    k = 7.5e5  # N·m/rad, any: what is checked is that this one is read
    entry = dataclasses.asdict(throwfe.TorsionResult(k, 0.1, 1, 1, 3, 0.01, 0.001, 1.0))
    keys = {throwfe.throw_key(throwfe.throw_of(crank, i), None) for i in range(len(crank.pins))}
    scf = SCFSet.of(2.0, 2.1, "background", pin_bending=3.0, journal_bending=1.5)
    done = concurrent.futures.Future()
    done.set_result(({key: entry for key in keys}, scf))

    def no_fe(*args, **kwargs):
        raise AssertionError("a throw FE in the run's own process")

    monkeypatch.setattr(throwfe, "torsional_stiffness_fe", no_fe)
    monkeypatch.setattr(throwfe, "_CACHE", {})
    ctx = RunContext(crank, tmp_path, RunOptions(), RunOutcome(crank, "x", timings_s={}), built={"throw_fe": done})
    ctx.parts("fe")  # built from the background's stiffness: no FE here
    assert ctx.scf().bending["pin"] == 3.0 and ctx.scf().source == "background"
    d_e = crank.journals[0].diameter
    l_throw = throw.material.shear_modulus * math.pi * d_e**4 / (32 * k)
    assert throwfe.web_equivalent_length_fe(crank, 0, d_e) == pytest.approx(throwfe.web_term(throw, l_throw, d_e),
                                                                            rel=1e-12)


def test_run_takes_typed_options_and_returns_its_outcome(tmp_path, monkeypatch):
    """Issue 41: every option a step reads is a field of RunOptions, each set by an option of
    `fetorsion run` (an unknown key is refused by name); run() returns the typed outcome of
    every section, with the report folder."""
    import dataclasses

    from fetorsion.cli.commands import build_parser
    from fetorsion.errors import FetorsionError
    from fetorsion.report.outcomes import LumpedOutcome, RunOutcome

    with pytest.raises(FetorsionError, match="unknown option.*mesh"):
        RunOptions.of({"mesh": 0.01})
    args = build_parser().parse_args(["run", "x.toml", "--modes", "12", "--workers", "3", "--fatigue-method", "fe"])
    assert (args.modes, args.workers, args.fatigue_method) == (12, 3, "fe")
    cli_dests = {a.dest for a in build_parser()._subparsers._group_actions[0].choices["run"]._actions}
    named = {"mesh_size": "mesh_size", "modes": "modes", "support": "support", "source": "source",
             "inertia_ratio": "inertia_ratio", "fatigue_method": "fatigue_method", "runup_rate": "run_up_rate",
             "workers": "workers", "html": "no_html", "measured": "measured", "station": "station", "no_fe": "no_fe",
             "fe_path": "no_fe_path"}
    assert set(named) == {f.name for f in dataclasses.fields(RunOptions)}
    assert set(named.values()) <= cli_dests
    outcome = run(GEOMETRY / "peugeot_glx.toml", tmp_path / "r", steps=LUMPED, options=RunOptions(html=False))
    assert isinstance(outcome, RunOutcome) and isinstance(outcome.lumped, LumpedOutcome)
    assert (Path(outcome.folder) / "report.md").is_file() and not (Path(outcome.folder) / "report.html").exists()


def test_a_propulsion_lines_run_up_takes_its_stated_passage_rate():
    """Without --run-up-rate, a network whose propellers state a passage rate runs up at the slowest
    stated (the medium-speed line's 10 rpm/s, not the 1000 rpm/s fast sweep its report once showed,
    which needed ~5 × the engine's rated torque to accelerate the line); a chain without one at the
    default; a given rate wins (RunOptions)."""
    import fetorsion
    from fetorsion.app.run import RunOptions
    from fetorsion.app.steps import stated_runup_rate
    from fetorsion.description.defaults import DEFAULT_RUNUP_RATE

    line = fetorsion.load(ROOT / "examples/networks/propulsion_line_medium_speed.toml")
    assert stated_runup_rate(line) == min(p.passage_rate for p in line.propellers) == 10.0
    assert stated_runup_rate(fetorsion.load(ROOT / "examples/networks/geared_engine.toml")) == DEFAULT_RUNUP_RATE
    assert RunOptions().runup_rate is None and RunOptions.of({"runup_rate": 50.0}).runup_rate == 50.0
