"""fetorsion design: the [design] table, the crank mass it minimises, the lumped explorer's search
against an optimum found independently, and the designed description written back."""

from pathlib import Path

import pytest
import scipy.optimize

import fetorsion
from fetorsion.description.model import Damper
from fetorsion.errors import DescriptionError

ROOT = Path(__file__).resolve().parent.parent
GEOMETRY = ROOT / "geometry"


def with_design(tmp_path, name: str, table: str) -> Path:
    path = tmp_path / f"{name}_design.toml"
    path.write_text((GEOMETRY / f"{name}.toml").read_text() + "\n[design]\n" + table)
    return path


@pytest.mark.parametrize("name", ["renault21", "inline6_diesel"])
def test_crank_mass_is_the_solids(name):
    """The explorer's mass (cylinders and web outlines by formula) against OpenCASCADE's volume of
    the built solid without fillets and drillings (a Boolean-fused CAD body, integrated by OCC):
    1e-4, OCC's integration tolerance on curved faces."""
    from fetorsion.design.search import crank_mass
    from fetorsion.solid.geometry import crank_mass_properties

    crank = fetorsion.load(GEOMETRY / f"{name}.toml")
    solid, _ = crank_mass_properties(fetorsion.with_values(crank, {}, details=False))
    assert crank_mass(crank) == pytest.approx(solid.mass, rel=1e-4)


def test_the_design_table_is_read_and_checked(tmp_path):
    ok = fetorsion.load(with_design(tmp_path, "inline6_diesel", 'damper = "rubber"\ndamper_inertia_ratio = [0.02, 0.3]\n'
                                    'damper_ring_radius = 85.0\n"webs.*.thickness" = [26.0, 34.0]\n'))
    d = ok.design
    assert d.inputs == (("webs.*.thickness", 26.0, 34.0),) and d.objective == "mass"
    assert d.damper == "rubber" and d.damper_inertia_ratio == (0.02, 0.3) and d.damper_ring_radius == pytest.approx(0.085)
    bad = with_design(tmp_path, "renault21", 'objective = "x"\ndamper = "rubber"\n"webs.*.thick" = [1, 2]\n'
                      '"pins.*.diameter" = [50.0, 60.0]\n"engine.cylinders" = [3, 6]\n')
    with pytest.raises(DescriptionError) as err:
        fetorsion.load(bad)
    text = str(err.value)
    assert "design.objective = 'x': must be one of mass, inertia, change" in text
    assert "design.damper_inertia_ratio" in text and "is required with damper = 'rubber'" in text
    assert "'webs.*.thick' does not name a numeric field" in text
    # issue 56: a count is refused here as in [uncertainty], not searched to "no candidate met the constraints"
    assert "design.engine.cylinders = [3, 6]: 'engine.cylinders' is a count (an integer field)" in text
    assert "pins" not in text  # a design range may leave the given value (48 mm) out


@pytest.mark.slow  # 38-45 s of lumped search; the default run keeps the clearance by hand and the explorer's f1
def test_the_search_finds_the_thickness_bisection_finds(tmp_path):
    """A made-up problem whose answer is found independently: the Renault's webs between 10 and
    14 mm, least mass, M53 safety >= 1.4 on the explorer. Safety rises with thickness there (the
    pin fillet governs thin webs) and mass rises with it, so the optimum is the thickness where the
    safety is 1.4: Brent's bisection on the same explorer finds it. The search's best feasible
    candidate is at it to 2 % of the 4 mm range (twenty generations of six resolve one variable to
    about that)."""
    from fetorsion.design.crank_verdict import verdict_scfs
    from fetorsion.design.search import ExplorerModel, run_design_search

    crank = fetorsion.load(with_design(tmp_path, "renault21", 'required_safety = 1.4\n"webs.*.thickness" = [10.0, 14.0]\n'))
    explorer = ExplorerModel(crank, verdict_scfs(crank))

    def gap(t):
        return explorer({"webs.*.thickness": t})["safety"] - 1.4

    assert gap(10.0) < 0 < gap(14.0)
    t_star = scipy.optimize.brentq(gap, 10.0, 14.0, xtol=1e-3)
    res = run_design_search(crank, seed=1, maxiter=20)
    t = res.best.values["webs.*.thickness"]
    assert res.best.safety >= 1.4 and res.required == 1.4
    assert t == pytest.approx(t_star, abs=0.02 * 4.0)
    # the front: no candidate below it on both counts, and the chosen one on it
    front = res.pareto
    assert any(c is res.best or c.objective == res.best.objective for c in front)
    assert all(not (c.objective < f.objective and c.safety > f.safety) for c in res.candidates for f in front)


def test_the_designed_description_reads_back(tmp_path):
    """The written file: each moved input edited and commented, a range of [uncertainty] the new
    value leaves commented out, the added damper as [[dampers]], and it loads with every rule."""
    from fetorsion.design.search import Candidate, designed_text

    src = with_design(tmp_path, "inline6_diesel", 'damper = "rubber"\ndamper_inertia_ratio = [0.02, 0.3]\n'
                      'damper_ring_radius = 85.0\n"webs.*.thickness" = [26.0, 34.0]\n')
    crank = fetorsion.load(src)
    damper = Damper("rubber", "front", 0.0, 0.0123456, 23456.7, 0.0, 0.31)
    best = Candidate({"webs.*.thickness": 26.2}, 0.05, damper, 90.0, 90.0, 1.3, "x", 2000.0)
    out = tmp_path / "designed.toml"
    out.write_text(designed_text(src.read_text(), crank, best))
    back = fetorsion.load(out)
    assert all(w.thickness == pytest.approx(0.0262) for w in back.webs)
    assert "# was 28.5: fetorsion design" in out.read_text()
    assert all(not any(p == "webs.*.thickness" for p, _, _ in members) for _, members in back.uncertainty)
    (d,) = back.dampers
    assert (d.kind, d.at) == ("rubber", "front")
    for got, want in ((d.ring_inertia, damper.ring_inertia), (d.stiffness, damper.stiffness),
                      (d.loss_factor, damper.loss_factor)):
        assert got == pytest.approx(want, rel=1e-5)  # written to six significant digits


def test_the_resonance_and_heat_constraints_are_read_and_checked(tmp_path):
    ok = fetorsion.load(with_design(tmp_path, "inline6_diesel", 'damper = "rubber"\ndamper_inertia_ratio = [0.02, 0.3]\n'
                                    'damper_ring_radius = 85.0\ndamper_heat_rating_w = 400.0\n'
                                    'resonance_orders = [3, 6]\nresonance_margin = 0.1\n'))
    d = ok.design
    assert (d.damper_heat_rating, d.resonance_orders, d.resonance_margin) == (400.0, (3.0, 6.0), 0.1)
    cases = [('resonance_orders = [6]\n"webs.*.thickness" = [26.0, 34.0]\n',
              "design.resonance_margin = None: is required with resonance_orders"),
             ('resonance_orders = []\nresonance_margin = 0.1\n"webs.*.thickness" = [26.0, 34.0]\n',
              "design.resonance_orders = []: must be a non-empty list of orders > 0"),
             ('resonance_orders = [6, -3]\nresonance_margin = 0.1\n"webs.*.thickness" = [26.0, 34.0]\n',
              "design.resonance_orders = [6, -3]: must be a non-empty list of orders > 0"),
             ('resonance_orders = [6]\nresonance_margin = 1.5\n"webs.*.thickness" = [26.0, 34.0]\n',
              "design.resonance_margin = 1.5"),
             ('damper_heat_rating_w = 300.0\n"webs.*.thickness" = [26.0, 34.0]\n',
              "design.damper_heat_rating_w = 300.0: goes with damper"),
             ('damper = "viscous"\ndamper_inertia_ratio = [0.02, 0.3]\ndamper_ring_radius = 85.0\n'
              'damper_heat_rating_w = -3\n', "design.damper_heat_rating_w = -3")]
    for table, message in cases:
        with pytest.raises(DescriptionError) as err:
            fetorsion.load(with_design(tmp_path, "inline6_diesel", table))
        assert message in str(err.value), table


def test_resonance_clearance_by_hand():
    """f1 = 500 Hz against 750-6500 rpm: order 4 resonates at 7500 rpm, 7500/6500 - 1 = 15.38 %
    above; order 2 at 15000 rpm; order 6 at 5000 rpm, inside, 1 - 5000/6500 = 23.08 % deep; order 48
    at 625 rpm, 1 - 625/750 = 16.67 % below."""
    from fetorsion.design.search import resonance_clearance

    assert resonance_clearance(500.0, (4.0,), (750.0, 6500.0)) == pytest.approx(7500 / 6500 - 1, rel=1e-12)
    assert resonance_clearance(500.0, (2.0, 4.0), (750.0, 6500.0)) == pytest.approx(7500 / 6500 - 1, rel=1e-12)
    assert resonance_clearance(500.0, (4.0, 6.0), (750.0, 6500.0)) == pytest.approx(5000 / 6500 - 1, rel=1e-12)
    assert resonance_clearance(500.0, (48.0,), (750.0, 6500.0)) == pytest.approx(1 - 625 / 750, rel=1e-12)


def test_the_explorers_f1_is_the_lumped_models(tmp_path):
    """The explorer's first elastic frequency (the response setup's matrices) against the lumped
    model's own modal solution (fetorsion.lumped): the same chain, two code paths, 1e-9."""
    from fetorsion.design.crank_verdict import verdict_scfs
    from fetorsion.design.search import ExplorerModel

    crank = fetorsion.load(with_design(tmp_path, "renault21", '"webs.*.thickness" = [10.0, 14.0]\n'))
    out = ExplorerModel(crank, verdict_scfs(crank))({})
    assert out["f1_hz"] == pytest.approx(fetorsion.lumped(crank).frequencies_hz[0], rel=1e-9)


@pytest.mark.slow  # 26 s; the default run keeps the clearance by hand and the explorer's f1
def test_the_search_keeps_a_resonance_out_where_bisection_puts_it(tmp_path):
    """A made-up problem: the Renault's webs between 10 and 14 mm, least mass, safety >= 1.0 (met
    over the whole range), order 4's resonance with the first mode kept 12 % above the 6500 rpm
    top speed. The lumped f1 rises with thickness there (477 Hz at 10 mm, 492 Hz at 14 mm), so the
    optimum is the thickness where the clearance is 12 %: Brent's method on the explorer's f1 finds
    it; the search must land on it to 2 % of the range, as for the safety constraint."""
    from fetorsion.design.crank_verdict import verdict_scfs
    from fetorsion.design.search import ExplorerModel, resonance_clearance, run_design_search

    crank = fetorsion.load(with_design(tmp_path, "renault21", 'required_safety = 1.0\nresonance_orders = [4.0]\n'
                                       'resonance_margin = 0.12\n"webs.*.thickness" = [10.0, 14.0]\n'))
    explorer = ExplorerModel(crank, verdict_scfs(crank))

    def gap(t):
        return resonance_clearance(explorer({"webs.*.thickness": t})["f1_hz"], (4.0,), (750.0, 6500.0)) - 0.12

    assert gap(10.0) < 0 < gap(14.0) and explorer({"webs.*.thickness": 10.0})["safety"] > 1.0
    t_star = scipy.optimize.brentq(gap, 10.0, 14.0, xtol=1e-3)
    res = run_design_search(crank, seed=1, maxiter=20)
    assert res.targets.clearance(res.best) >= 0.12
    assert res.best.values["webs.*.thickness"] == pytest.approx(t_star, abs=0.02 * 4.0)


@pytest.mark.slow
def test_the_search_keeps_the_added_dampers_heat_within_its_rating(tmp_path):
    """A made-up problem: the inline six with a rubber damper added (inertia ratio 0.02-0.3, least
    mass), rated 500 W. Its heat on the explorer falls from 540 W at 0.02 to 462 W at 0.05 while
    its safety stays above 1.5, so the lightest ring that passes is the one whose heat is 500 W:
    Brent's method on the explorer's heat finds it; the search lands on it to 2 % of the range."""
    from fetorsion.design.crank_verdict import verdict_scfs
    from fetorsion.design.search import INERTIA_RATIO, ExplorerModel, run_design_search

    src = with_design(tmp_path, "inline6_diesel", 'damper = "rubber"\ndamper_inertia_ratio = [0.02, 0.3]\n'
                      'damper_ring_radius = 85.0\ndamper_heat_rating_w = 500.0\n')
    crank = fetorsion.load(src)
    explorer = ExplorerModel(crank, verdict_scfs(crank))

    def gap(mu):
        return explorer({INERTIA_RATIO: mu})["damper_power_w"] - 500.0

    assert gap(0.02) > 0 > gap(0.05) and explorer({INERTIA_RATIO: 0.02})["safety"] > 1.15
    mu_star = scipy.optimize.brentq(gap, 0.02, 0.05, xtol=1e-5)
    res = run_design_search(crank, seed=1, maxiter=20)
    assert res.best.damper_power_w <= 500.0
    assert res.best.inertia_ratio == pytest.approx(mu_star, abs=0.02 * 0.28)
    from fetorsion.design.search import designed_text

    (tmp_path / "designed.toml").write_text(designed_text(src.read_text(), crank, res.best))
    assert fetorsion.load(tmp_path / "designed.toml").dampers[0].allowed_power == 500.0


def test_design_refuses_a_file_without_a_design_table(tmp_path, capsys):
    from fetorsion.cli.commands import main

    assert main(["design", str(GEOMETRY / "renault21.toml"), "--out", str(tmp_path / "d")]) == 2
    assert "has no [design] table" in capsys.readouterr().err
    assert not (tmp_path / "d").exists()


@pytest.mark.slow
@pytest.mark.fe
def test_the_design_loop_lands_where_the_fe_verdict_binds(tmp_path):
    """The made-up problem on the FE verdict: the Renault's webs between 10 and 14 mm, least mass,
    safety >= 1.9 by the condensed FE crank's verdict (30 mm mesh, firing and misfire; it gives 1.76
    at 10 mm and 2.00 at 14 mm, so the bound lies inside). The loop (explorer, written file,
    fetorsion run, explorer re-aimed) must end on a design the FE verdict passes with at most 2 %
    to spare (its stopping rule), and the FE verdict 1 mm thinner must fail, bracketing the
    thickness where it binds: 2 % of 1.9 is 0.038, 0.63 mm at the FE safety's slope there (0.06 per
    mm between the ends)."""
    from fetorsion.app.design import CLOSE_ENOUGH, _confirm, run_design
    from fetorsion.app.run import DEFAULT_STEPS, RunOptions
    from fetorsion.design.search import Candidate, designed_text

    src = with_design(tmp_path, "renault21", 'required_safety = 1.9\n"webs.*.thickness" = [10.0, 14.0]\n')
    steps = tuple(s for s in DEFAULT_STEPS if s[1] in ("fe", "bearings", "campbell", "fatigue"))
    options = RunOptions(mesh_size=0.03, html=False)
    outcome = run_design(src, tmp_path / "d", seed=1, options=options, steps=steps)
    chosen = outcome.chosen
    assert chosen is not None and chosen.passes and chosen.required == 1.9
    assert 1.9 <= chosen.fe_safety <= 1.9 * (1 + CLOSE_ENOUGH)
    t = chosen.candidate.values["webs.*.thickness"]
    thinner = Candidate({"webs.*.thickness": t - 1.0}, None, None, 0.0, 0.0, 0.0, "", 0.0)
    crank = fetorsion.load(src)
    (tmp_path / "thinner.toml").write_text(designed_text(src.read_text(), crank, thinner))
    fe = _confirm(tmp_path / "thinner.toml", tmp_path / "thinner", options, steps, 1.9)
    assert fe.safety < fe.required == 1.9  # the verdict's own 1.15 it passes; the design's 1.9 it fails
    report = (tmp_path / "d" / "run" / "report.md").read_text()
    assert "The crank as described: PASS" in report
    # a confirmation reads the deciding method alone: the fe path is left out, and said so
    assert "iacs-m53** decides; fe was left out" in report and "### fetorsion's own path (`fe`)" in report
    # and the lean folder reads back whole: `fetorsion report` writes the same report.md (issue 56)
    import shutil

    from fetorsion.app.rerender import rerender

    copy = shutil.copytree(tmp_path / "d" / "run", tmp_path / "copy")
    again = rerender(copy)
    assert not again.unread and (copy / "report.md").read_text() == report


@pytest.mark.parametrize("objective", ["inertia", "change"])
def test_the_other_objectives_are_what_they_say(tmp_path, objective):
    """``inertia``: the rotating inertia, the crank's (OpenCASCADE's polar inertia of the built solid
    without fillets and drillings) plus every attachment's (pistons and rods once per pin) plus
    the added ring's; ``change``: the moved inputs' relative changes summed, by hand."""
    from fetorsion.design.crank_verdict import verdict_scfs
    from fetorsion.design.search import INERTIA_RATIO, ExplorerModel

    src = with_design(tmp_path, "renault21", f'objective = "{objective}"\ndamper = "rubber"\n'
                      'damper_inertia_ratio = [0.05, 0.3]\n"webs.*.thickness" = [18.0, 26.0]\n'
                      '"pins.*.diameter" = [46.0, 50.0]\n')
    crank = fetorsion.load(src)
    out = ExplorerModel(crank, verdict_scfs(crank))({"webs.*.thickness": 20.0, "pins.*.diameter": 49.0,
                                                    INERTIA_RATIO: 0.1})
    if objective == "inertia":
        from fetorsion.solid.geometry import crank_mass_properties

        variant = fetorsion.with_values(crank, {"webs.*.thickness": 20.0, "pins.*.diameter": 49.0}, details=False)
        solid, _ = crank_mass_properties(variant)
        attached = sum(a.polar_inertia * (len(variant.pins) if a.at == "pins" else 1) for a in variant.attachments)
        want = solid.polar_inertia + attached + out["ring_inertia_kgm2"]
        assert out["objective"] == pytest.approx(want, rel=1e-4)  # OCC's integration tolerance, as for the mass
    else:
        assert out["objective"] == pytest.approx(abs(20.0 - 22.0) / 22.0 + abs(49.0 - 48.0) / 48.0, rel=1e-12)


def test_the_verdict_fails_a_described_damper_over_its_heat_rating(tmp_path):
    """The crank as described with its rubber damper (the inline six, the ring the heat test finds):
    M53 passes it; its heat — the response's largest mean dissipation over the speeds, the energy
    balance tests/test_dampers.py checks — rated at half that fails the verdict, rated at twice
    passes it. Before, the crank verdict read the safety alone and passed an overheating damper."""
    from fetorsion.design.crank_verdict import CrankVerdict, DampingFlip, VerdictConfig, fillet_torque_amplitude, verdict_scfs
    from fetorsion.design.m53 import run_m53_crank
    from fetorsion.design.stress import fillets_of
    from fetorsion.response.forced import response_setup, solve_response

    crank = fetorsion.load(GEOMETRY / "inline6_diesel.toml")
    damper = Damper("rubber", "front", 0.0, 0.0097, 14300.0, 0.0, 0.215)
    setup = response_setup(crank)
    response = solve_response(setup, (damper,))
    fillets = fillets_of(crank)
    m53 = run_m53_crank(crank, fillets, fillet_torque_amplitude(setup, response, fillets), setup.rpm,
                        fe_scf=verdict_scfs(crank))
    heat = float(response.damper_power_w.sum(axis=(1, 2)).max())
    assert m53.passes and heat > 0
    for rating, passes in ((0.5 * heat, False), (2.0 * heat, True)):
        config = VerdictConfig("with the description's damper(s)", (damper,), {"iacs-m53": m53}, damper_power_w=heat,
                               allowed_power_w=rating, as_described=True)
        verdict = CrankVerdict(crank.name, "iacs-m53", [config], 0.02, "assumed", True, DampingFlip(None, "-"), [])
        assert verdict.passes is passes
        assert ("over its rating" in verdict.lines()[0]) is not passes


@pytest.mark.slow
@pytest.mark.fe
def test_the_design_loop_maps_the_resonance_onto_the_fe_crank(tmp_path):
    """The Renault's webs between 14 and 26 mm, least mass, order 4 kept 20 % above its 6500 rpm
    top speed. On the lumped chain alone no thickness does it (its f1 peaks near 493 Hz: 7400 rpm,
    14 % above), but the condensed FE crank in its bearings is stiffer (533 Hz given: 8000 rpm):
    the loop measures that ratio on the given crank first, so the search finds designs, and the
    written design's own FE run has its first mode (the report's, the first torsional one) with
    order 4 more than 20 % above 6500 rpm, by the hand formula 60 f1 / 4 / 6500 - 1."""
    import json

    from fetorsion.app.design import run_design
    from fetorsion.app.run import DEFAULT_STEPS, RunOptions
    from fetorsion.design.search import run_design_search

    src = with_design(tmp_path, "renault21", 'resonance_orders = [4.0]\nresonance_margin = 0.2\n'
                      '"webs.*.thickness" = [14.0, 26.0]\n')
    assert run_design_search(fetorsion.load(src), seed=1, maxiter=6).best is None  # the lumped chain alone
    steps = tuple(s for s in DEFAULT_STEPS if s[1] in ("fe", "bearings", "campbell", "fatigue"))
    outcome = run_design(src, tmp_path / "d", seed=1, options=RunOptions(mesh_size=0.03, html=False), steps=steps)
    assert outcome.chosen is not None and outcome.chosen.passes
    f1 = json.loads((tmp_path / "d" / "run" / "results.json").read_text())["bearings"]["f1_bearings_hz"]
    assert 60.0 * f1 / 4.0 / 6500.0 - 1.0 >= 0.2


def test_a_design_space_holding_no_valid_crank_names_the_rule_it_breaks(tmp_path, capsys):
    """Issue 56: webs of 1-2 mm cannot carry the Renault's 2.5 mm fillets: every candidate's
    description breaks that rule, and the search says so, naming the fields and the rule, not
    "no candidate met the constraints"."""
    from fetorsion.cli import main

    path = with_design(tmp_path, "renault21", 'objective = "mass"\n"webs.*.thickness" = [1.0, 2.0]\n')
    assert main(["design", str(path), "--out", str(tmp_path / "out"), "--generations", "1", "--no-verify"]) == 2
    err = capsys.readouterr().err
    assert "no candidate of the [design] space is a valid crank" in err
    assert "fillets.pin = 2.5: must be smaller than half the thickness of the thinnest web" in err
    assert "no candidate met the constraints" not in err and not (tmp_path / "out").exists()
