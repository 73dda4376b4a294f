"""A crank's fatigue verdict's figures, as the run's fatigue step draws them and as ``fetorsion
report`` and a second run from the store draw them again (one definition: the same pictures)."""

from __future__ import annotations

from collections.abc import Callable

from ..report.outcomes import FatigueOutcome


def haigh_of(verdict, assessment):
    """The ``fe`` path's Haigh diagram, titled with whether that path decides the verdict (M53
    reads no mean stress: it has no Haigh diagram of its own)."""
    ax = assessment.haigh()
    ax.set_title(f"{ax.get_title()} (fe path, Findley)\n{verdict.decides('fe')}", fontsize=8, wrap=True)
    return ax


def fatigue_figures(fatigue: FatigueOutcome) -> dict[str, Callable[[], object]]:
    """A crank's fatigue verdict: both methods' safeties (the crank as described, firing), the ``fe``
    path's Haigh diagram and the recommended damper's design, as the fatigue step draws them."""
    v = fatigue.verdict
    draw = {"fatigue_safety.png": lambda: v.fatigue_figure().axes[0],
            "fatigue_haigh.png": lambda: haigh_of(v, fatigue.assessment), "damper_design.png": lambda: v.damper.plot()}
    return {image: draw[image] for image in fatigue.images}
