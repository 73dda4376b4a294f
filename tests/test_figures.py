"""Issue 54: report figures a reader in a hurry reads in seconds, each checked for what a program
can check (tests/figure_checks.py): titles inside the canvas, few coloured lines, the required
line labelled, the Campbell diagram's size key and bold major orders."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from conftest import GEOMETRY  # noqa: E402
from figure_checks import coloured, figure_problems  # noqa: E402


def test_the_checks_find_what_they_look_for():
    """A figure made to break each rule: a title cut off, ten coloured lines, no required line,
    no size key; each is found."""
    fig, ax = plt.subplots(figsize=(4, 3))
    for k in range(10):
        ax.plot([0, 1, 2], [k, k + 1, k], color=plt.cm.viridis(k / 9))
    ax.set_title("a title far too long for a figure four inches wide, so it runs off the canvas on both sides")
    found = figure_problems(fig, required=True, key_unit="MPa")
    plt.close(fig)
    assert any("leaves the canvas" in p for p in found)
    assert any("10 coloured lines" in p for p in found)
    assert "no line labelled 'required'" in found and "no size key in MPa" in found
    assert coloured("C0") and not coloured("0.75") and not coloured("k")


@pytest.mark.parametrize("largest, key", [(3.7, [2.0, 1.0, 0.4]), (0.0537, [0.05, 0.025, 0.01]),
                                          (120.0, [100.0, 50.0, 20.0]), (5.0, [5.0, 2.5, 1.0])])
def test_the_size_key_is_three_round_values_below_the_largest(largest, key):
    from fetorsion.excitation.campbell import size_key

    assert size_key(largest) == key


def test_campbell_marks_the_major_orders_and_keys_the_circle_sizes():
    """The Renault's Campbell diagram (lumped modes): the in-line four's major orders 2, 4, 6, ...
    drawn bold and no other, a size key of three circles in the severity's unit (deg), every
    title inside the canvas."""
    import fetorsion
    from fetorsion.excitation.campbell import run_campbell

    res = run_campbell(fetorsion.load(GEOMETRY / "renault21.toml"))
    assert res.major == tuple(float(k) for k in range(2, 13, 2))
    fig = res.plot().figure
    ax = fig.axes[0]
    bold = sorted(round(ln.get_ydata()[1] * 60 / ln.get_xdata()[1], 6) for ln in ax.get_lines()
                  if ln.get_linewidth() > 1.5 and ln.get_xdata()[0] == 0 and ln.get_ydata()[0] == 0)
    assert bold == [2.0, 4.0, 6.0, 8.0, 10.0, 12.0]
    assert figure_problems(fig, key_unit="deg") == []
    plt.close(fig)


def test_m53_figure_names_the_least_safe_places_and_the_required_q():
    """M53's Q of every place: the three least safe coloured and named, the others grey; the
    required Q dashed, labelled, inside the axis."""
    from fetorsion.design.m53 import M53Location, M53Result

    q = [2.4, 1.98, 3.1, 2.05, 4.0, 2.2]
    places = tuple(M53Location(f"P{j + 1} pin fillet", "pin-fillet", 1.0, 1.0, 0.0, 100e6, v * 100e6, {})
                   for j, v in enumerate(q))
    ax = M53Result(places, {}, {}, 5500.0).plot()
    bars = ax.patches
    assert sorted(p.get_width() for p in bars if coloured(p.get_facecolor()))[:3] == [1.98, 2.05, 2.2]
    assert sum(coloured(p.get_facecolor()) for p in bars) == 3
    assert figure_problems(ax.figure, required=True) == []
    plt.close(ax.figure)


def test_the_damper_figure_draws_its_required_line():
    from fetorsion.design.dampers import DamperResult

    rpm = np.linspace(1000, 6000, 50)
    res = DamperResult("crank", "rubber", 0.25, "fatigue", 500.0, 0.01, None, None, rpm,
                       curves={"none": 0.3 + 0.2 * np.exp(-((rpm - 5000) / 300) ** 2)}, limit=1 / 1.15,
                       limit_label="required: M53 Q 1.15, utilisation 1/1.15 = 0.870")
    ax = res.plot()
    assert figure_problems(ax.figure, required=True) == []
    plt.close(ax.figure)


@pytest.mark.fe
@pytest.mark.slow
def test_every_figure_of_the_inline_six_run_reads_at_a_glance(tmp_path, monkeypatch):
    """Issue 54: the inline six's run (every step but the background studies, 30 mm mesh): each
    figure passes the checks (titles inside the canvas, at most 8 coloured lines, the fatigue and
    damper figures' labelled required line, the Campbell diagram's size key in MPa); the fatigue
    figure's first panel is the deciding method's."""
    from figure_checks import check_run_figures

    from fetorsion.app.run import DEFAULT_STEPS, RunOptions, run

    problems, drawn = check_run_figures(monkeypatch)
    steps = tuple(s for s in DEFAULT_STEPS if s[1] != "sensitivity")
    out = run(GEOMETRY / "inline6_diesel.toml", tmp_path / "i6", steps=steps, options=RunOptions(mesh_size=0.03))
    assert {"campbell.png", "response.png", "fatigue_safety.png", "fatigue_haigh.png",
            "damper_design.png"} <= set(drawn), drawn
    assert not problems, problems
    verdict = out.fatigue.verdict
    fig = verdict.fatigue_figure()
    assert fig.axes[0].get_title().splitlines()[-1].startswith(f"{verdict.method} decides: safety ")
    plt.close(fig)
