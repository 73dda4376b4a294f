"""What can be checked of a report figure by a program (issue 54): its titles inside the canvas,
few coloured lines per panel, a labelled required line where there is one, a size key where
sizes mean something. Each check returns the problems it finds, as text naming the panel."""

from __future__ import annotations

import matplotlib.colors as mcolors
import numpy as np

#: At most this many coloured (not grey or black) lines on one panel
MOST_COLOURED_LINES = 8


def coloured(colour) -> bool:
    """A colour that is not a grey (black and white included): its RGB channels differ."""
    r, g, b, _ = mcolors.to_rgba(colour)
    return max(r, g, b) - min(r, g, b) > 0.05


def titles_inside(fig) -> list[str]:
    """Every panel title and the figure's title lie inside the canvas (a title cut off is a
    title a reader cannot read)."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    box = fig.bbox
    texts = [ax.title for ax in fig.axes if ax.get_title()] + ([fig._suptitle] if fig._suptitle else [])
    out = []
    for t in texts:
        e = t.get_window_extent(renderer)
        if e.x0 < box.x0 - 1 or e.x1 > box.x1 + 1 or e.y0 < box.y0 - 1 or e.y1 > box.y1 + 1:
            out.append(f"title {t.get_text()!r} leaves the canvas")
    return out


def coloured_lines(fig) -> list[str]:
    """No panel draws more than :data:`MOST_COLOURED_LINES` coloured data lines."""
    out = []
    for ax in fig.axes:
        lines = [ln for ln in ax.get_lines() if len(ln.get_xdata()) > 2 and coloured(ln.get_color())
                 and ln.get_linestyle() not in ("None", "")]
        if len(lines) > MOST_COLOURED_LINES:
            out.append(f"panel {ax.get_title()!r}: {len(lines)} coloured lines")
    return out


def required_line(fig) -> list[str]:
    """A dashed line labelled 'required' on at least one panel, inside its axis limits."""
    for ax in fig.axes:
        for ln in ax.get_lines():
            if "required" in str(ln.get_label()):
                x, y = np.asarray(ln.get_xdata(), float), np.asarray(ln.get_ydata(), float)
                lo, hi = ax.get_ylim() if np.ptp(y) == 0 else ax.get_xlim()
                value = y[0] if np.ptp(y) == 0 else x[0]
                return [] if lo <= value <= hi else [f"the required line ({value:g}) is outside the axis"]
    return ["no line labelled 'required'"]


def size_key(fig, unit: str) -> list[str]:
    """A legend with three or more entries naming a size in ``unit``."""
    for ax in fig.axes:
        legend = ax.get_legend()
        if legend is not None and sum(unit in t.get_text() for t in legend.get_texts()) >= 3:
            return []
    return [f"no size key in {unit}"]


def figure_problems(fig, required: bool = False, key_unit: str | None = None) -> list[str]:
    """Every check above that applies to ``fig``."""
    out = titles_inside(fig) + coloured_lines(fig)
    if required:
        out += required_line(fig)
    if key_unit is not None:
        out += size_key(fig, key_unit)
    return out


#: The report figures that carry a required line, and the one with a size key (its unit)
REQUIRED_FIGURES = ("fatigue_safety.png", "damper_design.png")
KEYED_FIGURES = {"campbell.png": "MPa"}


def check_run_figures(monkeypatch):
    """Check every figure a ``fetorsion run`` writes as it writes it: returns (problems by figure
    name, the names drawn), filled as the run saves."""
    from pathlib import Path

    import fetorsion.app.run as app_run

    problems, drawn = {}, []
    saving = app_run.save_figure_atomic

    def checked(fig, path, **kwargs):
        name = Path(path).name
        drawn.append(name)
        found = figure_problems(fig, required=name in REQUIRED_FIGURES, key_unit=KEYED_FIGURES.get(name))
        if found:
            problems[name] = found
        return saving(fig, path, **kwargs)

    monkeypatch.setattr(app_run, "save_figure_atomic", checked)
    return problems, drawn
