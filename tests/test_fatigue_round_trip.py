"""Issue 56: a crank's fatigue verdict read back from results.json renders as the live run's.

A live verdict needs the condensed crank (FE) for its ``fe`` path, so the outcome here is built
without FE from the run's own functions where they need none, on the lumped model of the shipped
inline six (M53 on its section torques, with and without the recommended damper designed by
:func:`run_fatigue_damper`, and in misfire; the SCFs against the rule's; the fillet stress) and by
hand where they do (each configuration's ``fe`` assessment, the methods' bridge, the bending, the
damping band and flip: made-up numbers of the right shapes). It is written as the fatigue step
writes its entry, read back by ``load_run`` and drawn again by ``fetorsion report``: the section,
the summary, the whole report.md and the three figures must be the live outcome's, byte for byte.
"""

import json
from pathlib import Path

import numpy as np
import pytest

import fetorsion
from conftest import ROOT

#: Every k-th speed of the lumped response: the damper optimiser solves them some 50 times.
STRIDE = 20


def _fe_assessment(crank, fillets, rpm, seed: int):
    """A made-up ``fe`` assessment of every fillet: safeties over the speeds, Findley's figures at
    each place's worst speed, the material the description gives."""
    from fetorsion.design.fatigue import FatigueAssessment, FatigueResult, fatigue_material
    from fetorsion.design.recovered import METHOD, RecoveredAssessment

    rng = np.random.default_rng(seed)
    labels = [f.label for f in fillets]
    safety = 1.2 + 3.0 * rng.random((len(rpm), len(labels)))
    worst = np.argmin(safety, axis=0)
    mat, defaulted = fatigue_material(crank.material)
    locs = tuple(FatigueAssessment(lb, f"{f.kind}-fillet", METHOD, 4e8 + 1e8 * rng.random(), 1e8 * rng.random(),
                                   5e7 * (rng.random() - 0.5), float(safety[worst[j], j]), 1.0,
                                   None if j % 2 else 1.5 + rng.random(), {"support": 1.1 + 0.1 * rng.random()},
                                   {"findley": {"value": 2e8 * rng.random(), "limit": 2.5e8}})
                 for j, (lb, f) in enumerate(zip(labels, fillets)))
    return RecoveredAssessment(crank.name, METHOD, np.asarray(rpm, dtype=float), labels, safety,
                               FatigueResult(METHOD, mat, tuple(defaulted), locs), np.asarray(rpm)[worst],
                               "stress recovery (six unit end loads)", ["a made-up note"],
                               np.array([f.diameter for f in fillets]), tuple(range(len(fillets))),
                               [[0.001 * j, 0.02, 0.0] for j in range(len(fillets))])


def _bridge(m53, fe, ratio: float) -> dict:
    """A made-up bridge between the methods at the fe path's governing place."""
    from fetorsion.design.bridge import DISAGREEMENT, FACTORS

    factors = {k: 1.0 + 0.1 * n for n, k in enumerate(FACTORS)}
    g = fe.labels[fe.governing]
    place = {"fe_place": g, "m53_place": m53.governing.name, "fe_safety": ratio * m53.governing.safety,
             "m53_safety": m53.governing.safety, "ratio": ratio, "factors": factors,
             "product": float(np.prod(list(factors.values()))), "largest": FACTORS[-1]}
    return {"fe_safety": place["fe_safety"], "m53_safety": place["m53_safety"], "ratio": ratio,
            "disagrees": abs(ratio - 1) > DISAGREEMENT, "carried_by": FACTORS[-1], "places": [place]}


def live_fatigue():
    """(crank, the fatigue outcome as the step returns it, its results.json entries as the step writes them)."""
    from fetorsion.io import jsonable as _jsonable
    from fetorsion.design.crank_verdict import (CrankVerdict, DampingFlip, VerdictConfig, fillet_torque_amplitude,
                                                run_fatigue_damper, verdict_scfs)
    from fetorsion.design.m53 import m53_geometry, run_m53_crank
    from fetorsion.design.m53_scfs import scf_comparison
    from fetorsion.design.stress import fillet_stress, fillets_of
    from fetorsion.report.load import FATIGUE_IMAGES
    from fetorsion.report.outcomes import FatigueOutcome
    from fetorsion.response.forced import misfire_harmonics, response_setup, solve_response

    crank = fetorsion.load(ROOT / "geometry/inline6_diesel.toml")
    setup = response_setup(crank).at_speeds(slice(None, None, STRIDE))
    fillets, scf = fillets_of(crank), verdict_scfs(crank)

    def m53_of(s, dampers):
        return run_m53_crank(crank, fillets, fillet_torque_amplitude(s, solve_response(s, dampers), fillets), s.rpm,
                             fe_scf=scf)

    undamped = m53_of(setup, ())
    design = run_fatigue_damper(crank, setup, fillets, scf, undamped=undamped)
    best = design.optimised
    misfired = setup.with_misfires(misfire_harmonics(crank, setup))[2]
    rows = [("without a damper", (), setup, None), ("with the recommended rubber damper", (best,), setup, None),
            ("misfire of cylinder 3, without a damper", (), misfired, 2)]
    configs = []
    for k, (name, dampers, s, cylinder) in enumerate(rows):
        m53, fe = m53_of(s, dampers), _fe_assessment(crank, fillets, s.rpm, k)
        c = VerdictConfig(name, dampers, {"iacs-m53": m53, "fe": fe}, cylinder, as_described=not dampers,
                          bridge=_bridge(m53, fe, 1.1 + 0.3 * k), recommended=best in dampers)
        if dampers:
            c.damper_power_w = float(solve_response(s, dampers).damper_power_w.sum(axis=(1, 2)).max())
        if k == 0:
            c.bending = [{"name": f.label, "vibratory_nm": 100.0 * (j + 1), "rpm": float(s.rpm[j]),
                          "determinate_nm": 80.0 * (j + 2), "ratio": (j + 1) / (0.8 * (j + 2)),
                          "flag": j == 3} for j, f in enumerate(fillets[:5])]
        configs.append(c)
    comparison = scf_comparison(m53_geometry(crank), scf)
    verdict = CrankVerdict(crank.name, "iacs-m53", configs, 0.02, "assumed: the description states no source", True,
                           DampingFlip(0.0123, "passes down to ζ = 0.0123"),
                           [{"damping_ratio": z, "safety": 1.0 + 20 * z} for z in (0.01, 0.02, 0.04)], design,
                           comparison, ["a made-up verdict note"],
                           {"pin fillet": {"fe_sigma_v_pa": 1.1e8, "m53_sigma_v_pa": 1.0e8, "ratio": 1.1,
                                           "ratio_fe_scf": 1.05}},
                           {"ratio": 0.02, "source": "assumed", "assumed": True,
                            "sensitivity": [{"bending_damping_ratio": zb, "iacs-m53": 1.4, "fe": 2.0 + zb}
                                            for zb in (0.02, 0.10)]})
    a = configs[0].fe
    stress = fillet_stress(crank, solve_response(setup, ()), scf, fillets)
    outcome = FatigueOutcome(verdict, a, stress, scf, FATIGUE_IMAGES, setup.model)
    entries = {"fatigue": {**verdict.to_dict(), "fe_detail": a.to_dict(), "scf": scf.to_dict(), "model": setup.model},
               "stress": stress.to_dict()}
    return crank, outcome, json.loads(json.dumps(_jsonable(entries)))


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    """The live outcome, and a report folder holding its results.json (no figures: the report draws them)."""
    from fetorsion.report.outcomes import RunOutcome

    crank, outcome, entries = live_fatigue()
    folder = tmp_path_factory.mktemp("fatigue") / "inline6"
    folder.mkdir()
    path = ROOT / "geometry/inline6_diesel.toml"
    data = {"description": {"path": str(path), "text": path.read_text(encoding="utf-8")}, "skipped": {},
            **entries, "timings_s": {"fatigue": 1.0}}
    (folder / "results.json").write_text(json.dumps(data, indent=1) + "\n")
    live = RunOutcome(crank, str(path), fatigue=outcome, timings_s={"fatigue": 1.0}, folder=str(folder))
    return live, folder


def test_the_fatigue_section_and_summary_read_back_are_the_live_runs(written):
    from fetorsion.report.fatigue import fatigue_section
    from fetorsion.report.load import load_run
    from fetorsion.report.summary import summary_lines

    live, folder = written
    loaded = load_run(folder)
    assert not loaded.unread
    back = loaded.outcome
    assert fatigue_section(back.crank, back.fatigue) == fatigue_section(live.crank, live.fatigue)
    assert summary_lines(back) == summary_lines(live)
    text = "\n".join(fatigue_section(live.crank, live.fatigue))
    # the made-up parts are all in it: the recommended damper and its heat, the bridge, the bending
    assert "**Recommended damper**" in text and "its heat at the worst speed" in text
    assert "term by term" in text and "Bending beyond the rule" in text


def test_the_verdict_writes_the_entry_it_was_read_from(written):
    """Read back, the verdict and the fe path's assessment write the JSON the run wrote."""
    from fetorsion.report.load import load_run
    from test_load_results import same_json

    live, folder = written
    loaded = load_run(folder)
    stored, fat = loaded.results["fatigue"], loaded.outcome.fatigue
    again = json.loads(json.dumps({**fat.verdict.to_dict(), "fe_detail": fat.assessment.to_dict(),
                                   "scf": fat.scf.to_dict(), "model": fat.model}))
    assert same_json(again, stored)
    assert [c.answer(m) for c in fat.verdict.configs for m in ("iacs-m53", "fe")] == [
        c.answer(m) for c in live.fatigue.verdict.configs for m in ("iacs-m53", "fe")]
    # a second round trip (load -> to_dict -> from_dict) renders the same
    from fetorsion.design.crank_verdict import CrankVerdict
    from fetorsion.report.fatigue import fatigue_section
    from fetorsion.report.load import _fatigue

    twice = _fatigue(loaded.outcome.crank, {**loaded.results, "fatigue": again})
    assert fatigue_section(loaded.outcome.crank, twice) == fatigue_section(loaded.outcome.crank, fat)
    assert isinstance(twice.verdict, CrankVerdict)


def test_fetorsion_report_draws_the_live_report_and_figures(written, tmp_path):
    """``fetorsion report`` on the folder: report.md is the live outcome's, and each fatigue figure
    the live objects' PNG, byte for byte."""
    from fetorsion.app.rerender import rerender
    from fetorsion.app.fatigue_figures import haigh_of
    from fetorsion.io import save_figure_atomic
    from fetorsion.report.markdown import report_markdown

    live, folder = written
    done = rerender(folder)
    assert not done.unread and "report.md" in done.written
    assert set(live.fatigue.images) <= set(done.written)
    assert (folder / "report.md").read_text() == report_markdown(live)
    v, a = live.fatigue.verdict, live.fatigue.assessment
    # drawn as the fatigue step draws them (app/steps.py, step_fatigue)
    for name, fig in zip(live.fatigue.images, (v.fatigue_figure(v.configs[0]), haigh_of(v, a).figure,
                                               v.damper.plot().figure)):
        save_figure_atomic(fig, tmp_path / name, close=True, dpi=120)
        assert (tmp_path / name).read_bytes() == (folder / name).read_bytes(), name


def test_a_folder_written_before_the_entry_kept_its_model_is_named(written, tmp_path):
    from fetorsion.report.load import load_run

    _, folder = written
    data = json.loads((folder / "results.json").read_text())
    del data["fatigue"]["model"]
    (tmp_path / "results.json").write_text(json.dumps(data))
    loaded = load_run(tmp_path)
    assert "written before" in loaded.unread["fatigue"] and loaded.outcome.fatigue is None
    for c in data["fatigue"]["configurations"]:
        del c["recommended"]
    data["fatigue"]["model"] = "m"
    (tmp_path / "results.json").write_text(json.dumps(data))
    assert "recommended damper" in load_run(tmp_path).unread["fatigue"]


# ---------------------------------------------------------------------------
# The committed crank folders (written by a live run with FE, before the entry kept its model and
# which configuration carries the recommended damper): given those two from the folder itself,
# the fatigue section and summary read back are the ones the live run wrote

CRANK_FOLDERS = ("renault21", "peugeot_glx_engine", "inline6_diesel", "v8_petrol")


def completed_copy(name: str, tmp: Path) -> Path:
    """A copy of the committed folder ``name`` whose fatigue entry has the keys it predates: the
    model its report.md names and the configurations carrying the damper named as the
    recommended one is (:func:`fetorsion.design.dampers.run_damper`); a folder that has them is
    copied as it is."""
    import re
    import shutil

    folder = tmp / name
    shutil.copytree(ROOT / "results" / name, folder)
    data = json.loads((folder / "results.json").read_text())
    f = data["fatigue"]
    f.setdefault("model", re.search(r"Computed on the \*\*(.+?)\*\*", (folder / "report.md").read_text()).group(1))
    recommended = f"optimised {f['damper']['type']}, mu = {f['damper']['inertia_ratio']:g}"
    for c in f["configurations"]:
        c.setdefault("recommended", recommended in c["dampers"])
    (folder / "results.json").write_text(json.dumps(data, indent=1) + "\n")
    return folder


@pytest.mark.parametrize("name", CRANK_FOLDERS)
def test_the_committed_fatigue_sections_read_back_as_their_reports_have_them(name, tmp_path):
    from fetorsion.report.fatigue import fatigue_section
    from fetorsion.report.load import load_run
    from fetorsion.report.outcomes import RunOutcome
    from fetorsion.report.summary import summary_lines

    folder = completed_copy(name, tmp_path)
    loaded, text = load_run(folder), (folder / "report.md").read_text()
    assert "fatigue" not in loaded.unread
    run = loaded.outcome
    assert "\n".join(fatigue_section(run.crank, run.fatigue)) in text
    assert all(line in text for line in summary_lines(RunOutcome(run.crank, "", fatigue=run.fatigue)))


def test_the_committed_fatigue_figures_are_drawn_again_byte_for_byte(tmp_path):
    """The Renault 21's three fatigue figures drawn from its results.json are the live run's PNGs."""
    from fetorsion.app.rerender import figures
    from fetorsion.io import save_figure_atomic
    from fetorsion.report.load import load_run
    from fetorsion.report.outcomes import RunOutcome

    folder = completed_copy("renault21", tmp_path)
    fatigue = load_run(folder).outcome.fatigue
    for name, draw in figures(RunOutcome(fatigue=fatigue, crank=None, path="")).items():
        save_figure_atomic(draw().figure, tmp_path / name, close=True, dpi=120)
        assert (tmp_path / name).read_bytes() == (ROOT / "results/renault21" / name).read_bytes(), name
