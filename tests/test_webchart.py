"""The computed web chart (issue 8): family geometry, shipped table, held-out FE point, range."""


import pytest

from fetorsion.extrapolation import convergence_rate

import fetorsion
from fetorsion.webs import chart as wc
from fetorsion.errors import FetorsionError
from fetorsion.webs.methods import WEB_METHODS, web_equivalent_length
from fetorsion.webs.sections import effective_web_width, overlap_ratio

from conftest import GEOMETRY


@pytest.mark.parametrize("c, q, split", [(0.0, 0.5, 0.5), (0.3, 1.0, 0.25), (0.5, 2.0, 0.75)])
def test_family_throw_sits_at_its_chart_point(c, q, split):
    t = wc.chart_throw(c, q, split=split)
    assert overlap_ratio(t, 0) == pytest.approx(c, abs=1e-12)
    assert wc.chart_coordinates(t, 1) == pytest.approx((c, q), rel=1e-12, abs=1e-12)
    assert effective_web_width(t.webs[0]) == pytest.approx(wc.web_dimensions(c, q, split, 0.06)[1], rel=1e-12)


def test_richardson_recovers_a_power_law():
    f = lambda h: 2.0 - 0.3 * h**1.4  # noqa: E731
    shares = (1 / 8, 1 / 12, 1 / 16)
    assert convergence_rate([f(h) for h in shares], shares) == pytest.approx(1.4, rel=1e-6)
    assert wc.richardson(f(1 / 8), f(1 / 12), 1 / 8, 1 / 12, 1.4) == pytest.approx(2.0, rel=1e-12)


@pytest.mark.slow  # 13 s: a throw FE
@pytest.mark.fe
def test_chart_reproduces_a_held_out_fe_point_within_its_stated_error():
    chart = wc.load_chart()
    v = chart["validity"]
    c, q = 0.25, 0.85  # not a grid node: the FE is run afresh here
    assert c not in chart["grid"]["c"] and q not in chart["grid"]["q"]
    fe = wc.chart_point(c, q, chart["mesh"]["richardson_order"])["le_dt"]
    # Stated error: the largest held-out miss of the sweep; plus 0.2 % for Gmsh's run-to-run
    # mesh differences (1e-4 D_t seen at one size), which enter through the extrapolation.
    assert wc.le0_dt(c, q) == pytest.approx(fe, rel=v["interpolation_rel_error"] + 2e-3)


def test_chart_refuses_points_outside_its_range():
    with pytest.raises(FetorsionError, match="outside the computed chart"):
        wc.le0_dt(0.6, 1.0)
    with pytest.raises(FetorsionError, match="outside the computed chart"):
        wc.le0_dt(0.3, 3.0)
    with pytest.raises(FetorsionError, match="outside the computed correction"):
        wc.correction_dt("fillet", 0.2)


@pytest.mark.parametrize("name", ["peugeot_glx", "renault21"])
def test_chart_method_on_the_reference_cranks(name):
    crank = fetorsion.load(GEOMETRY / f"{name}.toml")
    d_e = crank.journals[0].diameter
    le = web_equivalent_length(crank, 0, d_e, "chart")
    c, q = wc.chart_coordinates(crank, 0)
    base = d_e * wc.le0_dt(c, q)
    # Fillets stiffen the junction, oil holes soften the journal and pin: both small.
    assert le == pytest.approx(base, rel=0.15)
    # Same order as the elementary beam bound and the classical formulas.
    assert WEB_METHODS["beam"](crank, 0, d_e) < le < 2 * WEB_METHODS["carter"](crank, 0, d_e)
    # The chart interpolates FE throws of a family without counterweights: the 17-DOF f1 it gives
    # stays within 2 % of the one from the crank's own FE throws (README: 0.4 % and 0.9 %).
    assert fetorsion.lumped(crank, 17, "chart").frequencies_hz[0] == pytest.approx(
        fetorsion.lumped(crank, 17, "fe").frequencies_hz[0], rel=0.02)
