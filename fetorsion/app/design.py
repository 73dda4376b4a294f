"""The design loop: search on the explorer, write the design, confirm it with ``fetorsion run``.

The explorer (:func:`fetorsion.design.search.run_design_search`) and the FE verdict differ (the
lumped chain against the condensed crank in its bearings, firing against the worst misfire too),
so the loop maps one onto the other: after each confirming run the explorer's target safety
becomes the required one scaled by the explorer's safety over the FE verdict's at the design just
confirmed, its f1 is scaled by the FE crank's in-bearing f1 over its own (the resonance margin),
and its heat limit by its heat over the FE verdict's (the added damper's rating); the search runs
again — while the FE verdict fails, or passes with more than :data:`CLOSE_ENOUGH` to spare on a
constraint that held the explorer's design back. The lightest design the FE verdict passed is
the answer; its files and report are kept.
"""

from __future__ import annotations

import contextlib
import json
import math
import sys
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from ..design.search import (DESIGN_GENERATIONS, Candidate, DesignResult, DesignTargets, designed_text,
                             resonance_clearance, run_design_search)
from ..errors import FetorsionError
from ..io import atomic_folder, check_report_folder, save_figure_atomic, write_report_manifest, write_text_atomic
from .run import DEFAULT_STEPS, RunOptions, run

if TYPE_CHECKING:
    from .run import RunStep

#: Searches at most.
ROUNDS = 4
#: A confirmed design this close above the required safety (relative) is as light as the FE
#: verdict allows, to the explorer's resolution.
CLOSE_ENOUGH = 0.02


@dataclass(frozen=True)
class FEAnswer:
    """What ``fetorsion run`` of a designed description says: the FE verdict's least safety of the
    crank as designed (firing and misfire) and the required one, the first mode in its bearings
    that carries torsion (Hz, :meth:`~fetorsion.fe.condensed.CondensedModes.first_carrying_torsion`), the added damper's heat firing (W; 0 without one), and whether the verdict passes (the
    safety and the heat; the resonance margin is the loop's to judge)."""

    safety: float
    required: float
    f1_hz: float
    damper_power_w: float
    verdict_passes: bool


@dataclass(frozen=True)
class Confirmation:
    """One design confirmed by ``fetorsion run``: the explorer's candidate, the targets it was
    searched for, the FE answer, the resonance clearance on the FE f1 (NaN: no such constraint)
    and whether it passes every constraint."""

    candidate: Candidate
    targets: DesignTargets
    fe: FEAnswer
    clearance: float
    passes: bool

    @property
    def target(self) -> float:
        return self.targets.safety

    @property
    def fe_safety(self) -> float:
        return self.fe.safety

    @property
    def required(self) -> float:
        return self.fe.required

    def line(self) -> str:
        t = self.targets
        text = (f"explorer safety {self.candidate.safety:.3f} (target {t.safety:.3f}), FE verdict "
                f"{self.fe.safety:.3f} against {self.fe.required:.2f}")
        if t.orders:
            text += (f"; f1 in the bearings {self.fe.f1_hz:.1f} Hz (explorer {self.candidate.f1_hz:.1f} Hz), "
                     f"resonance clearance {100 * self.clearance:+.1f} % against {100 * t.margin:.0f} %")
        if t.heat_limit_w and self.candidate.damper is not None:
            text += f"; damper heat {self.fe.damper_power_w:.1f} W (explorer {self.candidate.damper_power_w:.1f} W)"
        return text + f": {'pass' if self.passes else 'FAIL'}, objective {self.candidate.objective:.4g}"

    def to_dict(self) -> dict:
        return {**self.candidate.to_dict(), "targets": asdict(self.targets), "fe": asdict(self.fe),
                "target": self.target, "fe_safety": self.fe.safety, "required": self.fe.required,
                "fe_resonance_clearance": None if self.clearance != self.clearance else self.clearance,
                "passes": self.passes}


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


def run_design(path: str | Path, out: str | Path, seed: int = 0, generations: int = DESIGN_GENERATIONS,
               verify: bool = True, options: RunOptions | None = None, steps: Sequence[RunStep] = DEFAULT_STEPS,
               force: bool = False, workers: int | None = None, scheduler: str | None = None) -> DesignOutcome:
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
    space = crank.design
    outcome, aim = None, {}
    if verify and space.resonance_orders:  # the explorer's f1 mapped onto the FE crank's from the start
        aim["frequency_factor"] = _frequency_factor(crank, options)
    texts: dict[int, tuple[str, DesignResult]] = {}
    for k in range(ROUNDS if verify else 1):
        result = run_design_search(crank, seed=seed, maxiter=generations, client=client, progress=_say, **aim)
        t = result.targets
        pick = result.best
        if pick is None:
            if not result.candidates and result.failures:  # every candidate broke a rule of the description
                first = result.failures[0].removeprefix("DescriptionError: ")
                raise FetorsionError("design: no candidate of the [design] space is a valid crank; the first "
                                     f"refused: {first}\nnarrow the [design] bounds that break these rules")
            if not verify or not result.candidates:
                raise FetorsionError(f"design: no candidate met the constraints on the explorer (safety "
                                     f"{result.required:.3f}{_others(t)}); widen the [design] bounds or allow a damper")
            # the explorer is not the verdict: the FE verdict may pass the candidate nearest to passing
            pick = min(result.candidates, key=t.shortfall)
            _say(f"round {k + 1}: no candidate met the constraints on the explorer; the FE verdict checks the "
                 f"nearest (safety {pick.safety:.3f})")
        outcome = outcome or DesignOutcome(result, folder=out)
        outcome.search = result
        text = designed_text(path.read_text(), crank, pick)
        if not verify:
            _write(out, name, text, result, outcome)
            return outcome
        texts[k] = (text, result)
        _write(out, name, text, result, outcome, run_folder=f"run-{k + 1}")
        fe = _confirm(out / name, out / f"run-{k + 1}", options, steps, space.required_safety)
        clearance = (resonance_clearance(fe.f1_hz, t.orders, t.speed_range_rpm) if t.orders else math.nan)
        passes = fe.verdict_passes and fe.safety >= fe.required and not clearance < t.margin
        c = Confirmation(pick, t, fe, clearance, passes)
        outcome.confirmations.append(c)
        _say(f"round {k + 1}: {c.line()}")
        if passes and (outcome.chosen is None or c.candidate.objective < outcome.chosen.candidate.objective):
            outcome.chosen = c
        # each constraint: (held the explorer's design back, the FE answer's spare on it)
        active = [(pick.safety <= t.safety * (1 + CLOSE_ENOUGH), fe.safety / fe.required - 1.0)]
        if t.heat_limit_w and pick.damper is not None and fe.damper_power_w > 0:
            active.append((pick.damper_power_w >= t.heat_limit_w / (1 + CLOSE_ENOUGH),
                           1.0 - fe.damper_power_w / space.damper_heat_rating))
        if t.orders:
            active.append((t.clearance(pick) <= t.margin + CLOSE_ENOUGH, clearance - t.margin))
        if passes and all(spare <= CLOSE_ENOUGH for held, spare in active if held):
            break
        if not passes and result.best is None:
            break  # the nearest candidate fails the FE verdict: nothing in the space passes
        aim = {"target": fe.required * pick.safety / fe.safety,
               "frequency_factor": fe.f1_hz / pick.f1_hz if t.orders else 1.0}
        if t.heat_limit_w and pick.damper is not None and fe.damper_power_w > 0:
            aim["heat_limit"] = space.damper_heat_rating * pick.damper_power_w / fe.damper_power_w
    if outcome.chosen is not None:  # the chosen round's files, and its run as run/
        k = outcome.confirmations.index(outcome.chosen)
        outcome.search = texts[k][1]
        _write(out, name, texts[k][0], outcome.search, outcome, run_folder=f"run-{k + 1}", keep_as="run")
    return outcome


def _frequency_factor(crank, options: RunOptions | None) -> float:
    """The given crank's first mode in its bearings that carries torsion, by the condensed FE crank
    (the run's: its mesh size, a cut at every fillet; from the store when built before), over the
    lumped chain's first elastic mode: what the explorer's f1 is scaled by before any design is
    confirmed."""
    from ..design.search import first_elastic_hz
    from ..response.forced import response_setup
    from .engine import engine_condensed

    f_fe = engine_condensed(crank, (options or RunOptions()).mesh_size, _say).modes("bearings").first_carrying_torsion()
    f_lumped = first_elastic_hz(response_setup(crank))
    _say(f"the first mode in its bearings: {f_fe:.1f} Hz by the condensed FE crank, {f_lumped:.1f} Hz on the lumped "
         f"chain: the explorer's f1 is scaled by {f_fe / f_lumped:.4f} until a design is confirmed")
    return f_fe / f_lumped


def _others(t: DesignTargets) -> str:
    """The constraints besides the safety, as words."""
    return ((f", damper heat <= {t.heat_limit_w:.1f} W" if t.heat_limit_w else "")
            + (f", resonance clearance >= {100 * t.margin:.0f} %" if t.orders else ""))


def _write(out: Path, name: str, text: str, result: DesignResult, outcome: DesignOutcome,
           run_folder: str | None = None, keep_as: str | None = None) -> None:
    """The folder ``out`` as one atomic step: the design's files, the confirmations so far, and
    the run reports already there (``keep_as``: only ``run_folder``'s, renamed)."""
    import shutil

    earlier = {p.name: p for p in out.iterdir() if p.is_dir()} if out.is_dir() else {}
    with atomic_folder(out) as work:
        write_text_atomic(work / name, text)
        data = {**result.to_dict(), "confirmations": [c.to_dict() for c in outcome.confirmations]}
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
             required: float | None = None) -> FEAnswer:
    """``fetorsion run`` of the designed description: the least safety of the crank as designed
    (its own dampers, firing and in misfire) by the deciding method, the required one (the
    larger of the verdict's and ``required``, the ``[design]`` table's), the first mode in the
    bearings, the designed dampers' heat firing, and whether the verdict passes. The ``fe`` path
    is left out where it does not decide: the loop reads the deciding method alone, and the
    path's stress recovery and assessments were most of a confirmation's verdict."""
    import dataclasses

    from ..report.outcomes import FatigueOutcome

    lean = dataclasses.replace(options or RunOptions(html=False), fe_path=False)
    outcome = run(designed, folder, steps=steps, options=lean, force=True)
    write_report_manifest(folder.parent)
    fatigue = outcome.fatigue
    if not isinstance(fatigue, FatigueOutcome):
        raise FetorsionError(f"design: the confirming run gave no fatigue verdict ({getattr(fatigue, 'reason', '')})")
    if outcome.bearings is None:
        raise FetorsionError("design: the confirming run built no condensed crank in its bearings")
    v = fatigue.verdict
    described = [c for c in v.configs if c.as_described]
    answers = [c.answer(v.method) for c in described]
    worst = min(answers, key=lambda a: a.safety / max(a.required, required or 0.0))
    need = max(float(worst.required), required or 0.0)
    heat = max((c.damper_power_w for c in described if c.misfire is None), default=0.0)
    return FEAnswer(float(worst.safety), need, outcome.bearings.bearings.first_carrying_torsion(), float(heat),
                    bool(v.passes))
