"""``fetorsion run``: every analysis of one crank into one report folder, written atomically.

The folder is built under a temporary name beside the target and renamed into place only
when every step has succeeded, so a failed run leaves nothing behind and a reader never
sees a half-written report. Each step is a small function ``step(ctx) -> None`` that
writes its files and records its numbers in ``ctx.results``.
"""

from __future__ import annotations

import json
import shutil
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np

from .crank import Chain, Crank, load
from .errors import FetorsionError
from .io import save_figure_atomic, write_text_atomic
from .lumped import PARTITIONS, lumped
from .stiffness import DEFAULT_WEB_METHOD, WEB_METHODS


@dataclass
class RunContext:
    """What the steps share: the crank, options, the working folder and the results."""

    crank: Crank
    folder: Path
    options: dict
    results: dict = field(default_factory=dict)
    report: list[str] = field(default_factory=list)
    timings_s: dict = field(default_factory=dict)

    def save(self, fig, name: str) -> str:
        import matplotlib.pyplot as plt

        save_figure_atomic(fig, self.folder / name, dpi=120)
        plt.close(fig)
        return name


def _progress(message: str) -> None:
    print(f"[fetorsion] {message}", file=sys.stderr, flush=True)


def step_lumped(ctx: RunContext) -> None:
    """All five partitions with every web method; mode-shape plots of the 17-DOF model."""
    import matplotlib

    matplotlib.use("Agg")
    crank = ctx.crank
    table = {}
    for method in WEB_METHODS:
        table[method] = [lumped(crank, d, method) for d in PARTITIONS]
    ctx.results["lumped"] = {m: [r.to_dict() for r in rs] for m, rs in table.items()}
    main = table[DEFAULT_WEB_METHOD][PARTITIONS.index(17)]
    img = ctx.save(main.plot().figure, "lumped_modes_17dof.png")
    measured = crank.notes.get("measured_first_torsional_hz")
    paper = crank.notes.get("paper_lumped_first_torsional_hz", {})
    lines = ["## Lumped models (BICERA-style equivalent lengths)", "",
             "First torsional frequency f1 (Hz), free-free; error against the measurement where there is one.", ""]
    head = "| model | " + " | ".join(WEB_METHODS) + (" | paper |" if paper else " |")
    lines += [head, "|" + "---|" * (len(WEB_METHODS) + 1 + bool(paper))]
    for i, d in enumerate(PARTITIONS):
        cells = [_with_error(table[m][i].frequencies_hz[0], measured) for m in WEB_METHODS]
        row = f"| {d} DOF | " + " | ".join(cells)
        row += f" | {paper.get(str(d), '')} |" if paper else " |"
        lines.append(row)
    if measured:
        lines += ["", f"Measured (free-free modal test): **{measured:g} Hz**."]
    lines += ["", f"17-DOF mode shapes (Carter webs), unit twist at the pulley end: ![]({img})", ""]
    ctx.report += lines


def _with_error(f: float, measured) -> str:
    return f"{f:.1f}" + (f" ({100 * (f / measured - 1):+.1f} %)" if measured else "")


def step_campbell(ctx: RunContext) -> None:
    """Campbell diagram and forced response (needs an [excitation] table)."""
    from .campbell import run_campbell
    from .response import run_response

    if ctx.crank.excitation is None:
        ctx.report += ["## Campbell diagram", "", "Not run: the description has no `[excitation]` table.", ""]
        return
    camp = run_campbell(ctx.crank)
    resp = run_response(ctx.crank)
    ctx.results["campbell"] = camp.to_dict()
    ctx.results["response"] = resp.to_dict()
    a = ctx.save(camp.plot().figure, "campbell.png")
    b = ctx.save(resp.plot(), "response.png")
    ctx.report += ["## Campbell diagram and forced response", "",
                   f"Crossings inside the operating range, most severe first ({camp.source}; severity = resonant "
                   f"vibratory angle at the pulley for ζ = {camp.damping_ratio:g}):", "", "```", camp.table(), "```", "",
                   f"![]({a})", "", "```", resp.summary(), "```", "", f"![]({b})", ""]


def step_sensitivity(ctx: RunContext) -> None:
    """f1 against each reconstructed input and the resulting band (needs [uncertainty])."""
    from .sensitivity import run_sensitivity

    if not ctx.crank.uncertainty:
        ctx.report += ["## Sensitivity", "", "Not run: the description has no `[uncertainty]` table.", ""]
        return
    sens = run_sensitivity(ctx.crank)
    ctx.results["sensitivity"] = sens.to_dict()
    img = ctx.save(sens.plot().figure, "sensitivity.png")
    verdict = ""
    if sens.measured_hz is not None:
        verdict = (f"The measured {sens.measured_hz:g} Hz is **{'inside' if sens.measured_inside else 'outside'}** "
                   f"the band {sens.band_hz[0]:.0f}–{sens.band_hz[1]:.0f} Hz.")
    ctx.report += ["## Sensitivity of f1 to the reconstructed geometry", "",
                   "Each input of the description's `[uncertainty]` table at its bounds, one at a time, then all "
                   "at the bounds that lower (raise) f1 together: the band's ends are model results.", "",
                   "```", sens.table(), "```", "", verdict, "", f"![]({img})", ""]


DEFAULT_STEPS: tuple[tuple[str, Callable[[RunContext], None]], ...] = (
    ("lumped models", step_lumped),
    ("Campbell diagram and forced response", step_campbell),
    ("sensitivity of f1", step_sensitivity),
)


def run(path, out, steps=DEFAULT_STEPS, options: dict | None = None) -> Path:
    """Run every step on the crank in ``path`` and write the report folder ``out``.

    Parameters
    ----------
    path : str or Path
        Crank description (.toml).
    out : str or Path
        Report folder; replaced only once the whole run has succeeded.
    steps : sequence of (name, function)
        The analyses, in order.
    options : dict, optional
        Passed to the steps (mesh size and such).

    Returns
    -------
    Path
        The report folder.
    """
    crank = load(path)  # every input rule is checked here, before any work or any file
    if isinstance(crank, Chain):
        raise FetorsionError(f"{path}: 'run' needs a crank description, not a chain file")
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix=f".{out.name}.", dir=out.parent))
    try:
        ctx = RunContext(crank, work, dict(options or {}))
        ctx.report += [f"# {crank.name}", "", f"Description: `{path}`", ""]
        for name, fn in steps:
            _progress(f"{name} ...")
            t0 = time.perf_counter()
            fn(ctx)
            ctx.timings_s[name] = time.perf_counter() - t0
            _progress(f"{name}: done in {ctx.timings_s[name]:.1f} s")
        ctx.results["timings_s"] = ctx.timings_s
        ctx.report += ["## Timings", "", *[f"- {k}: {v:.1f} s" for k, v in ctx.timings_s.items()], ""]
        write_text_atomic(work / "report.md", "\n".join(ctx.report))
        write_text_atomic(work / "results.json", json.dumps(_jsonable(ctx.results), indent=1) + "\n")
        _swap_into_place(work, out)
    except BaseException:
        shutil.rmtree(work, ignore_errors=True)
        raise
    return out


def _swap_into_place(work: Path, out: Path) -> None:
    """Rename the finished folder onto ``out``; an older report is removed only afterwards."""
    old = None
    if out.exists():
        old = out.with_name(f".{out.name}.old-{time.time_ns()}")
        out.rename(old)
    work.rename(out)
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)


def _jsonable(x):
    if isinstance(x, dict):
        return {str(k): _jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_jsonable(v) for v in x]
    if isinstance(x, np.ndarray):
        return x.tolist()
    if isinstance(x, np.generic):
        return x.item()
    return x
