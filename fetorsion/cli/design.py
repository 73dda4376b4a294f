"""``fetorsion design``: from a failing crank to a passing one over its ``[design]`` space; the
chosen design written as a new description, and ``fetorsion run`` of it (the condensed FE crank's
verdict) confirming it."""

from __future__ import annotations

from pathlib import Path

from .options import integer


def add_parser(sub) -> None:
    from ..description.defaults import DEFAULT_MESH_SIZE
    from ..design.search import DESIGN_GENERATIONS
    from .options import MM, millimetres

    p = sub.add_parser("design", help="search the description's [design] space for the least mass (or inertia, or "
                       "change) that passes the fatigue verdict; write it and confirm it with fetorsion run")
    p.add_argument("file", help="crank description (.toml) with a [design] table")
    p.add_argument("--out", required=True, help="folder for the designed description, the search's table, "
                   "Pareto figure and JSON, and the confirming run's report (new, or an earlier design folder)")
    p.add_argument("--seed", type=integer(0), default=0, help="the search's seed (default %(default)s): the same "
                   "seed gives the same search")
    p.add_argument("--generations", type=integer(1), default=DESIGN_GENERATIONS,
                   help="differential evolution's generations (default %(default)s)")
    p.add_argument("--no-verify", action="store_true",
                   help="write the design without the confirming fetorsion run (the explorer's answer only)")
    p.add_argument("--mesh-size", type=millimetres(), default=DEFAULT_MESH_SIZE, metavar="MM",
                   help=f"FE mesh size of the confirming run (default {DEFAULT_MESH_SIZE / MM:g})")
    p.add_argument("--workers", type=integer(1, 4096), metavar="N",
                   help="run each generation's candidates on a local Dask cluster of N workers (default: here, one "
                        "after the other; the same search either way)")
    p.add_argument("--scheduler", metavar="ADDRESS", help="run them on an existing Dask scheduler (tcp://host:8786)")
    p.add_argument("--force", action="store_true", help="replace --out even when it is not an earlier report")
    p.set_defaults(func=cmd_design)


def cmd_design(args) -> int:
    from ..app.design import run_design
    from ..app.run import RunOptions
    from ..io import check_report_folder

    from ..errors import FetorsionError
    from ..studies.runner import check_scheduler, scheduler_address

    if args.scheduler and args.workers:
        raise FetorsionError("--workers sizes the local cluster; an existing cluster (--scheduler) has its own workers")
    if args.scheduler:
        address, where = scheduler_address(args.scheduler)
        check_scheduler(address, where)
    check_report_folder(args.out, "--out", force=args.force, inputs=[args.file], force_option="--force")
    if not args.no_verify:  # the confirming run's mesh, refused now rather than after the search
        from .common import check_mesh_size, load_description

        check_mesh_size(load_description(args.file), args.mesh_size, "modal")
    outcome = run_design(args.file, args.out, seed=args.seed, generations=args.generations, verify=not args.no_verify,
                         options=RunOptions(mesh_size=args.mesh_size, html=False), force=args.force,
                         workers=args.workers, scheduler=args.scheduler)
    print(outcome.search.table())
    for i, c in enumerate(outcome.confirmations):
        print(f"confirmation {i + 1} (fetorsion run, the condensed FE crank as designed): {c.line()}")
    out = Path(args.out)
    print(f"designed description: {out / (Path(args.file).stem + '_designed.toml')}")
    if args.no_verify:
        return 0
    if outcome.chosen is None:
        print(f"design: the FE verdict passed none of {len(outcome.confirmations)} designs; the last is in {out}")
        return 1
    print(f"the designed crank: PASS (the FE verdict {outcome.chosen.fe_safety:.3f} against "
          f"{outcome.chosen.required:.2f}); report: {out / 'run' / 'report.md'}")
    return 0
