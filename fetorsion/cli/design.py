"""``fetorsion design``: from a failing crank to a passing one over its ``[design]`` space; the
chosen design written as a new description, and ``fetorsion run`` of it (the condensed FE crank's
verdict) confirming it."""

from __future__ import annotations

import json
import sys
from pathlib import Path

from ..errors import FetorsionError
from ..io import atomic_folder, check_report_folder, save_figure_atomic, write_text_atomic
from .common import load_description
from .options import integer


def add_parser(sub) -> None:
    from ..description.defaults import DEFAULT_MESH_SIZE
    from .options import MM, millimetres

    p = sub.add_parser("design", help="search the description's [design] space for the least mass (or inertia, or "
                       "change) that passes the fatigue verdict; write it and confirm it with fetorsion run")
    p.add_argument("file", help="crank description (.toml) with a [design] table")
    p.add_argument("--out", required=True, help="folder for the designed description, the search's table, "
                   "Pareto figure and JSON, and the confirming run's report (new, or an earlier design folder)")
    p.add_argument("--seed", type=integer(0), default=0, help="the search's seed (default %(default)s): the same "
                   "seed gives the same search")
    p.add_argument("--generations", type=integer(1), default=12,
                   help="differential evolution's generations (default %(default)s)")
    p.add_argument("--no-verify", action="store_true",
                   help="write the design without the confirming fetorsion run (the explorer's answer only)")
    p.add_argument("--mesh-size", type=millimetres(), default=DEFAULT_MESH_SIZE, metavar="MM",
                   help=f"FE mesh size of the confirming run (default {DEFAULT_MESH_SIZE / MM:g})")
    p.add_argument("--force", action="store_true", help="replace --out even when it is not an earlier report")
    p.set_defaults(func=cmd_design)


#: Searches at most: each after the first aims the explorer higher by the FE verdict's shortfall.
ROUNDS = 3
#: Margin added to each correction, so a round does not land exactly on the bound again.
CORRECTION_MARGIN = 0.02


def cmd_design(args) -> int:
    from ..design.search import designed_text, run_design_search
    from ..io import write_report_manifest

    crank = load_description(args.file)
    if getattr(crank, "design", None) is None:
        raise FetorsionError(f"design: {args.file} has no [design] table: say which inputs may move "
                             "(docs/design-search.md)")
    out = Path(args.out)
    check_report_folder(out, "--out", force=args.force, inputs=[args.file], force_option="--force")
    say = lambda m: print(f"[fetorsion] {m}", file=sys.stderr, flush=True)  # noqa: E731
    name = f"{Path(args.file).stem}_designed.toml"
    target, history = None, []
    for k in range(1 if args.no_verify else ROUNDS):
        result = run_design_search(crank, seed=args.seed, maxiter=args.generations, target=target, progress=say)
        result.notes += history
        print(result.table())
        if result.best is None:
            raise FetorsionError(f"design: no candidate reached the safety {result.required:.3f} on the explorer; "
                                 "widen the [design] bounds or allow a damper")
        text = designed_text(Path(args.file).read_text(), crank, result.best)
        with atomic_folder(out) as work:
            write_text_atomic(work / name, text)
            write_text_atomic(work / "design.json", json.dumps(result.to_dict(), indent=1) + "\n")
            write_text_atomic(work / "design.txt", result.table() + "\n")
            save_figure_atomic(result.plot().figure, work / "design_pareto.png", close=True, dpi=120)
        print(f"designed description: {out / name}")
        if args.no_verify:
            return 0
        passes, safety, required = confirm(out / name, out / "run", args.mesh_size)
        write_report_manifest(out)
        if passes:
            return 0
        target = result.required * required / safety * (1 + CORRECTION_MARGIN)
        history.append(f"round {k + 1}: explorer safety {result.best.safety:.3f}, the FE verdict's {safety:.3f} "
                       f"against {required:.2f}: the explorer aims at {target:.3f} next")
        say(history[-1])
    print(f"design: the FE verdict did not pass after {ROUNDS} searches; the last design is in {out}")
    return 1


def confirm(designed: Path, folder: Path, mesh_size: float) -> tuple[bool, float, float]:
    """``fetorsion run`` of the designed description: (passes, its least safety, the required one)
    of the crank as designed — its own dampers, firing and in misfire — by the deciding method."""
    from ..app.run import RunOptions, run
    from ..report.outcomes import FatigueOutcome

    outcome = run(designed, folder, options=RunOptions(mesh_size=mesh_size, html=False), force=True)
    fatigue = outcome.fatigue
    if not isinstance(fatigue, FatigueOutcome):
        raise FetorsionError(f"design: the confirming run gave no fatigue verdict ({getattr(fatigue, 'reason', '')})")
    v = fatigue.verdict
    answers = [(c, c.answer(v.method)) for c in v.configs if c.as_described]
    for c, a in answers:
        print(f"confirmed by fetorsion run ({fatigue.model}): {c.name}: {v.method} safety {a['safety']:.3f} against "
              f"{a['required']:.2f} at {a['location']} ({a['rpm']:.0f} rpm): {'pass' if a['passes'] else 'FAIL'}")
    print(f"the designed crank: {'PASS' if v.passes else 'FAIL'} ({v.method}, the condensed FE crank as described); "
          f"report: {folder / 'report.md'}")
    worst = min(answers, key=lambda ca: ca[1]["safety"] / ca[1]["required"])[1]
    return v.passes, float(worst["safety"]), float(worst["required"])
