"""``fetorsion report DIR``: a run's report folder drawn again from its ``results.json`` alone,
with no FE and nothing recomputed (:func:`fetorsion.report.load.load_run`).

Every matplotlib figure of a section read back is drawn again and written atomically in place;
report.md and report.html are written again when every section of the run was read back (a
report is never replaced by one that lacks a section). The FE mode images (drawn from the
mesh, which the folder does not keep) are kept as they are.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..description.defaults import DEFAULT_PARTITION, DEFAULT_WEB_METHOD
from ..webs.methods import SPLIT_PIN_METHODS
from ..errors import FetorsionError
from ..io import save_figure_atomic, write_text_atomic
from ..lumped_model.lumped import PARTITIONS
from ..report.load import LoadedRun, load_run
from .fatigue_figures import fatigue_figures
from ..report.outcomes import (BearingsOutcome, CampbellOutcome, ChainOutcome, FatigueOutcome, LumpedOutcome, MeasuredOutcome, RunOutcome,
                               SensitivityOutcome, TransientOutcome, TVCOutcome, VerdictOutcome)


@dataclass(frozen=True)
class Rerendered:
    """What ``fetorsion report`` wrote (file names), what it kept as it was and why (name -> why),
    and the sections of the run it could not read back (section -> why)."""

    written: tuple[str, ...]
    kept: dict[str, str]
    unread: dict[str, str]


def figures(run: RunOutcome) -> dict[str, Callable[[], object]]:
    """Each matplotlib figure of the sections read back: file name -> a function drawing it (an Axes)."""
    out = {}
    if isinstance(run.lumped, LumpedOutcome):
        main = run.lumped.table.get(DEFAULT_WEB_METHOD) or run.lumped.table[SPLIT_PIN_METHODS[0]]  # split pins: fe
        main = main[PARTITIONS.index(DEFAULT_PARTITION)]
        out[run.lumped.image] = main.plot
    if isinstance(run.lumped, ChainOutcome):
        out[run.lumped.image] = run.lumped.chain.plot
    if isinstance(run.campbell, CampbellOutcome):
        out[run.campbell.campbell_image] = run.campbell.campbell.plot
        out[run.campbell.response_image] = run.campbell.response.plot
    if isinstance(run.bearings, BearingsOutcome):
        out.update(_bearings_figures(run.bearings))
    out.update(_chain_figures(run))
    if isinstance(run.fatigue, FatigueOutcome):
        out.update(fatigue_figures(run.fatigue))
    if isinstance(run.tvc, TVCOutcome):
        from .tvc import tvc_figures

        out.update(tvc_figures(run.tvc))
    sens = run.sensitivity
    if isinstance(sens, SensitivityOutcome):
        out[sens.image] = sens.sensitivity.plot
        if sens.studies:
            out[sens.study_images["montecarlo"]] = lambda: sens.studies["montecarlo"].plot(kind="histogram")
            out[sens.study_images["sobol"]] = lambda: sens.studies["sobol"].plot(kind="indices")
    return out


def _bearings_figures(bearings: BearingsOutcome) -> dict[str, Callable[[], object]]:
    """The condensed crank's modes free and in bearings, and its coupled response."""
    from ..fe.condensed import CHECKED_MODES, plot_support_modes

    out = {bearings.images[0]: lambda: plot_support_modes(bearings.free.first(CHECKED_MODES),
                                                          bearings.bearings.first(CHECKED_MODES))}
    if bearings.coupled is not None:
        out[bearings.images[1]] = bearings.coupled.plot
    return out


def _chain_figures(run: RunOutcome) -> dict[str, Callable[[], object]]:
    """The verdict's, the measured comparison's and the run-up's figures (as the run's steps draw them)."""
    out = {}
    if isinstance(run.verdict, VerdictOutcome):
        out[run.verdict.image] = run.verdict.verdict.plot
    if isinstance(run.measured, MeasuredOutcome):
        out[run.measured.image] = lambda: run.measured.comparison.plot().axes[0]
    tra, camp = run.transient, run.campbell
    if isinstance(tra, TransientOutcome) and isinstance(camp, CampbellOutcome):
        from ..response.transient import plot_order_cuts  # the time domain's kernel: 2-3 s to import

        top = float(np.max(camp.response.orders))
        out[tra.waterfall_image] = lambda: tra.transient.waterfall(max_order=top)
        out[tra.cuts_image] = lambda: plot_order_cuts(tra.transient, camp.response, tra.cuts)
    return out


def rerender(folder: str | Path) -> Rerendered:
    """Draw the report folder ``folder`` (one ``fetorsion run`` wrote) again from its results.json
    (see the module docstring); the :class:`Rerendered` names the files written, those kept and
    why, and the sections not read back.
    """
    import matplotlib

    matplotlib.use("Agg")
    folder = Path(folder)
    loaded: LoadedRun = load_run(folder)
    written, kept = [], {}
    for name, draw in figures(loaded.outcome).items():
        try:
            ax = draw()
        except FetorsionError as exc:  # a result read back without what its figure needs
            kept[name] = str(exc)
            continue
        save_figure_atomic(ax.figure, folder / name, close=True, dpi=120)
        written.append(name)
    if loaded.unread:
        for name in ("report.md", "report.html"):
            kept[name] = "sections not read back: " + ", ".join(loaded.unread)
        return Rerendered(tuple(written), kept, dict(loaded.unread))
    from ..report.html import report_html
    from ..report.markdown import report_markdown

    write_text_atomic(folder / "report.md", report_markdown(loaded.outcome))
    written.append("report.md")
    if (folder / "report.html").exists():
        write_text_atomic(folder / "report.html", report_html(loaded.outcome, folder))
        written.append("report.html")
    return Rerendered(tuple(written), kept, {})
