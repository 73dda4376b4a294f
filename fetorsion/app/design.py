"""The design loop: search on the explorer, write the design, confirm it with ``fetorsion run``.

The explorer (:func:`fetorsion.design.search.run_design_search`) and the FE verdict differ (the
lumped chain against the condensed crank in its bearings, firing against the worst misfire too),
so the loop maps one onto the other: after each confirming run the explorer's target safety
becomes the required one scaled by the explorer's safety over the FE verdict's at the design just
confirmed, and the search runs again — while the FE verdict fails, or passes with more than
:data:`CLOSE_ENOUGH` to spare where the explorer's constraint was the one holding the design
back. The lightest design the FE verdict passed is the answer; its files and report are kept.
"""

from __future__ import annotations

import contextlib
import json
import sys
from dataclasses import dataclass, field
from pathlib import Path

from ..design.search import DESIGN_GENERATIONS, Candidate, DesignResult, designed_text, run_design_search
from ..errors import FetorsionError
from ..io import atomic_folder, check_report_folder, save_figure_atomic, write_report_manifest, write_text_atomic
from .run import DEFAULT_STEPS, RunOptions, run

#: Searches at most.
ROUNDS = 4
#: A confirmed design this close above the required safety (relative) is as light as the FE
#: verdict allows, to the explorer's resolution.
CLOSE_ENOUGH = 0.02


@dataclass(frozen=True)
class Confirmation:
    """One design confirmed by ``fetorsion run``: the explorer's candidate, the FE verdict's least
    safety of the crank as designed (firing and misfire) against the required one, and whether it
    passes."""

    candidate: Candidate
    target: float
    fe_safety: float
    required: float
    passes: bool

    def line(self) -> str:
        return (f"explorer safety {self.candidate.safety:.3f} (target {self.target:.3f}), FE verdict "
                f"{self.fe_safety:.3f} against {self.required:.2f}: {'pass' if self.passes else 'FAIL'}, "
                f"objective {self.candidate.objective:.4g}")


@dataclass
class DesignOutcome:
    """The design loop's answer: the last search, every confirmation, the chosen design (the
    lightest the FE verdict passed; None without one, or without confirmation) and the folder."""

    search: DesignResult
    confirmations: list[Confirmation] = field(default_factory=list)
    chosen: Confirmation | None = None
    folder: Path | None = None


def _say(message: str) -> None:
    print(f"[fetorsion] {message}", file=sys.stderr, flush=True)


def run_design(path, out, seed: int = 0, generations: int = DESIGN_GENERATIONS, verify: bool = True,
               options: RunOptions | None = None, steps=DEFAULT_STEPS, force: bool = False,
               workers: int | None = None, scheduler: str | None = None) -> DesignOutcome:
    """Search ``path``'s ``[design]`` space, write the design into ``out`` and confirm it.

    Parameters
    ----------
    path : str or Path
        Crank description with a ``[design]`` table.
    out : str or Path
        Folder: the designed description ``<name>_designed.toml``, ``design.txt``,
        ``design.json``, ``design_pareto.png`` and the confirming run's report ``run/``.
    seed, generations : int
        The search's seed and differential evolution's generations.
    verify : bool
        Confirm with ``fetorsion run`` (else the explorer's answer is written as it is).
    options : RunOptions, optional
        The confirming run's options (mesh size ...).
    steps : sequence
        The confirming run's steps (default every step: the full report).
    force : bool
        Replace ``out`` even when it is not an earlier report.
    workers, scheduler : optional
        The explorer's candidates on a local Dask cluster of ``workers`` processes, or on the
        cluster at ``scheduler`` (default: here, one after the other).

    Returns
    -------
    DesignOutcome
    """
    from ..description.files import load

    path, out = Path(path), Path(out)
    crank = load(path)
    if getattr(crank, "design", None) is None:
        raise FetorsionError(f"design: {path} has no [design] table: say which inputs may move "
                             "(docs/design-search.md)")
    check_report_folder(out, "out", force=force, inputs=[path])
    name = f"{path.stem}_designed.toml"
    with contextlib.ExitStack() as stack:
        client = None
        if workers or scheduler:
            from ..studies.runner import open_client

            client = stack.enter_context(open_client(scheduler, workers))
        return _loop(crank, path, out, name, seed, generations, verify, options, steps, client)


def _loop(crank, path: Path, out: Path, name: str, seed: int, generations: int, verify: bool, options, steps,
          client) -> DesignOutcome:
    """:func:`run_design`'s rounds."""
    outcome, target = None, None
    texts: dict[int, tuple[str, DesignResult]] = {}
    for k in range(ROUNDS if verify else 1):
        result = run_design_search(crank, seed=seed, maxiter=generations, target=target, client=client, progress=_say)
        pick = result.best
        if pick is None:
            if not verify or not result.candidates:
                raise FetorsionError(f"design: no candidate reached the safety {result.required:.3f} on the explorer; "
                                     "widen the [design] bounds or allow a damper")
            # the explorer is not the verdict: the FE verdict may pass its safest candidate
            pick = max(result.candidates, key=lambda c: c.safety)
            _say(f"round {k + 1}: no candidate reached {result.required:.3f} on the explorer; the FE verdict "
                 f"checks the safest ({pick.safety:.3f})")
        outcome = outcome or DesignOutcome(result, folder=out)
        outcome.search = result
        text = designed_text(path.read_text(), crank, pick)
        if not verify:
            _write(out, name, text, result, outcome)
            return outcome
        texts[k] = (text, result)
        _write(out, name, text, result, outcome, run_folder=f"run-{k + 1}")
        fe, required, passes = _confirm(out / name, out / f"run-{k + 1}", options, steps, crank.design.required_safety)
        c = Confirmation(pick, result.required, fe, required, passes)
        outcome.confirmations.append(c)
        _say(f"round {k + 1}: {c.line()}")
        if passes and (outcome.chosen is None or c.candidate.objective < outcome.chosen.candidate.objective):
            outcome.chosen = c
        held_back = pick.safety <= result.required * (1 + CLOSE_ENOUGH)  # the constraint is active
        if passes and (fe <= required * (1 + CLOSE_ENOUGH) or not held_back):
            break
        if not passes and result.best is None:
            break  # the safest candidate fails the FE verdict: nothing in the space passes
        target = required * pick.safety / fe
    if outcome.chosen is not None:  # the chosen round's files, and its run as run/
        k = outcome.confirmations.index(outcome.chosen)
        outcome.search = texts[k][1]
        _write(out, name, texts[k][0], outcome.search, outcome, run_folder=f"run-{k + 1}", keep_as="run")
    return outcome


def _write(out: Path, name: str, text: str, result: DesignResult, outcome: DesignOutcome,
           run_folder: str | None = None, keep_as: str | None = None) -> None:
    """The folder ``out`` as one atomic step: the design's files, the confirmations so far, and
    the run reports already there (``keep_as``: only ``run_folder``'s, renamed)."""
    import shutil

    earlier = {p.name: p for p in out.iterdir() if p.is_dir()} if out.is_dir() else {}
    with atomic_folder(out) as work:
        write_text_atomic(work / name, text)
        data = {**result.to_dict(), "confirmations": [
            {**c.candidate.to_dict(), "target": c.target, "fe_safety": c.fe_safety, "required": c.required,
             "passes": c.passes} for c in outcome.confirmations]}
        write_text_atomic(work / "design.json", json.dumps(data, indent=1) + "\n")
        lines = [result.table()] + [f"confirmation {i + 1}: {c.line()}" for i, c in enumerate(outcome.confirmations)]
        write_text_atomic(work / "design.txt", "\n".join(lines) + "\n")
        save_figure_atomic(result.plot().figure, work / "design_pareto.png", close=True, dpi=120)
        for folder_name, folder in earlier.items():
            if keep_as is None and folder_name.startswith("run-"):
                shutil.copytree(folder, work / folder_name)
            elif keep_as is not None and folder_name == run_folder:
                shutil.copytree(folder, work / keep_as)


def _confirm(designed: Path, folder: Path, options: RunOptions | None, steps,
             required: float | None = None) -> tuple[float, float, bool]:
    """``fetorsion run`` of the designed description: the least safety of the crank as designed
    (its own dampers, firing and in misfire) by the deciding method, the required one (the
    larger of the verdict's and ``required``, the ``[design]`` table's), and whether it passes."""
    from ..report.outcomes import FatigueOutcome

    outcome = run(designed, folder, steps=steps, options=options or RunOptions(html=False), force=True)
    write_report_manifest(folder.parent)
    fatigue = outcome.fatigue
    if not isinstance(fatigue, FatigueOutcome):
        raise FetorsionError(f"design: the confirming run gave no fatigue verdict ({getattr(fatigue, 'reason', '')})")
    v = fatigue.verdict
    answers = [c.answer(v.method) for c in v.configs if c.as_described]
    worst = min(answers, key=lambda a: a["safety"] / max(a["required"], required or 0.0))
    need = max(float(worst["required"]), required or 0.0)
    return float(worst["safety"]), need, bool(v.passes) and float(worst["safety"]) >= need
