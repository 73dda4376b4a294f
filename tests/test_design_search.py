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
                      '"pins.*.diameter" = [50.0, 60.0]\n')
    with pytest.raises(DescriptionError) as err:
        fetorsion.load(bad)
    text = str(err.value)
    assert "design.objective = 'x': must be one of mass, inertia, change" in text
    assert "design.damper_inertia_ratio" in text and "is required with damper = 'rubber'" in text
    assert "'webs.*.thick' does not name a numeric field" in text
    assert "pins" not in text  # a design range may leave the given value (48 mm) out


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
    fe, required, passes = _confirm(tmp_path / "thinner.toml", tmp_path / "thinner", options, steps, 1.9)
    assert not passes and fe < required == 1.9
    assert "The crank as described: PASS" in (tmp_path / "d" / "run" / "report.md").read_text()


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
