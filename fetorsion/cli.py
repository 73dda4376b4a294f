"""Command line: ``fetorsion <command> ...``. User mistakes print one clear message, exit 2."""

from __future__ import annotations

import argparse
import json
import sys

from . import cli_mechanics
from .crank import Chain, load
from .errors import FetorsionError
from .io import write_text_atomic
from .lumped import PARTITIONS, lumped
from .stiffness import DEFAULT_WEB_METHOD, WEB_METHODS


def _dof_list(text: str) -> list[int]:
    if text == "all":
        return list(PARTITIONS)
    try:
        values = [int(v) for v in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"--dof {text!r}: give 'all' or some of {PARTITIONS}") from None
    bad = [v for v in values if v not in PARTITIONS]
    if bad:
        raise argparse.ArgumentTypeError(f"--dof {bad[0]} is not a partition; choose from {PARTITIONS} or 'all'")
    return values


def _emit_json(payload: dict, target: str | None) -> None:
    if target is None:
        return
    text = json.dumps(payload, indent=2) + "\n"
    if target == "-":
        sys.stdout.write(text)
    else:
        write_text_atomic(target, text)


def cmd_lumped(args) -> int:
    model = load(args.file)
    results = [lumped(model)] if isinstance(model, Chain) else [lumped(model, d, args.stiffness) for d in args.dof]
    out = sys.stderr if args.json == "-" else sys.stdout
    print(format_lumped_table(results), file=out)
    _emit_json({"file": args.file, "stiffness_method": None if isinstance(model, Chain) else args.stiffness,
                "models": [r.to_dict() for r in results]}, args.json)
    return 0


def format_lumped_table(results, modes: int = 4) -> str:
    """Plain-text table of the first ``modes`` elastic frequencies of each model."""
    name = results[0].name
    head = f"{'model':>8} " + " ".join(f"{'f' + str(j + 1) + ' [Hz]':>10}" for j in range(modes))
    lines = [f"{name}: free-free torsional natural frequencies", head, "-" * len(head)]
    for r in results:
        tag = f"{r.dof} DOF" if r.partition else "chain"
        freqs = " ".join(f"{f:10.1f}" for f in r.frequencies_hz[:modes])
        lines.append(f"{tag:>8} {freqs}")
    return "\n".join(lines)


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="fetorsion", description="Torsional vibration analysis of engine crankshafts.")
    sub = p.add_subparsers(dest="command", required=True)

    lp = sub.add_parser("lumped", help="BICERA-style equivalent-length lumped models (5/6/17/19/21 DOF)")
    lp.add_argument("file", help="crank description or chain file (.toml)")
    lp.add_argument("--dof", type=_dof_list, default=[17], help="partition(s): 5, 6, 17, 19, 21, a list, or 'all'")
    lp.add_argument("--stiffness", choices=sorted(WEB_METHODS), default=DEFAULT_WEB_METHOD,
                    help="web stiffness method (default %(default)s)")
    lp.add_argument("--json", metavar="PATH|-", help="write results as JSON to PATH, or '-' for stdout")
    lp.set_defaults(func=cmd_lumped)
    cli_mechanics.add_parsers(sub, _emit_json)
    return p


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except FetorsionError as exc:
        print(f"fetorsion: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
