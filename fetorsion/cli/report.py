"""``fetorsion report DIR``: a run's report folder drawn again from its results.json, no FE."""

from __future__ import annotations


def add_parser(sub) -> None:
    p = sub.add_parser("report", help="draw a run's report folder again from its results.json (its figures, and "
                       "report.md and report.html when every section is read back); no FE, seconds")
    p.add_argument("folder", metavar="DIR", help="a folder written by fetorsion run")
    p.set_defaults(func=cmd_report)


def cmd_report(args) -> int:
    import time

    from ..app.rerender import rerender

    t0 = time.perf_counter()
    done = rerender(args.folder)
    print(f"{args.folder}: drawn again from results.json in {time.perf_counter() - t0:.1f} s: "
          + (", ".join(done.written) or "nothing"))
    for name, why in done.kept.items():
        print(f"  kept as it was: {name} ({why})")
    for section, why in done.unread.items():
        print(f"  not read back: {section}: {why}")
    return 0
