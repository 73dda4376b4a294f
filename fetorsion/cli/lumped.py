"""``fetorsion lumped`` and ``fetorsion sensitivity``: the lumped chains of a crank, and f1 against each
uncertain input."""

from __future__ import annotations

import argparse
import sys

from ..description.edit import document
from ..description.chain_model import Chain, Network
from ..errors import FetorsionError
from ..lumped_model.lumped import MODES_SHOWN, PARTITIONS, lumped
from ..lumped_model.parts import build_parts
from ..description.defaults import DEFAULT_PARTITION, DEFAULT_WEB_METHOD
from ..webs.methods import WEB_METHODS
from .common import add_json_option, emit_json, load_crank, load_description, report


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


def cmd_lumped(args) -> int:
    model = load_description(args.file)
    results = [lumped(model)] if isinstance(model, (Chain, Network)) else [lumped(model, d, args.stiffness) for d in args.dof]
    out = sys.stderr if args.json == "-" else sys.stdout
    print(format_lumped_table(results), file=out)
    payload = {"file": args.file, "models": [r.to_dict() for r in results]}
    if not isinstance(model, (Chain, Network)):
        payload.update(stiffness_method=args.stiffness, parts=parts_table(build_parts(model, args.stiffness)),
                       web_inertia="analytic web outline (fetorsion.solid.outline), no fillets", description=document(model))
    emit_json(payload, args.json)
    return 0


def parts_table(chain) -> list[dict]:
    """The crank parts with their equivalent lengths, stiffnesses and inertias (SI)."""
    return [{"part": p.label, "x0_m": p.x0, "x1_m": p.x1, "equivalent_length_m": p.equivalent_length,
             "stiffness_nm_per_rad": 1.0 / p.compliance, "inertia_kgm2": p.inertia,
             "attached_inertia_kgm2": p.attached_inertia} for p in chain.parts]


def format_lumped_table(results, modes: int = MODES_SHOWN) -> str:
    """Plain-text table of the first ``modes`` elastic frequencies of each model."""
    name = results[0].name
    net = results[0].network
    support = "grounded" if net is not None and net.grounded else "free-free"
    head = f"{'model':>8} " + " ".join(f"{'f' + str(j + 1) + ' [Hz]':>10}" for j in range(modes))
    lines = [f"{name}: {support} torsional natural frequencies", head, "-" * len(head)]
    for r in results:
        tag = f"{r.dof} DOF" if r.partition else "chain"
        freqs = " ".join(f"{f:10.1f}" for f in r.frequencies_hz[:modes])
        lines.append(f"{tag:>8} {freqs}")
    return "\n".join(lines)


def cmd_sensitivity(args) -> int:
    from ..studies.sensitivity import run_sensitivity

    crank = load_crank(args.file, "[uncertainty]")
    if not crank.uncertainty:
        raise FetorsionError(f"{args.file}: the description has no [uncertainty] table")
    res = run_sensitivity(crank, args.dof, args.stiffness)
    return report(res, res.table(), args)


def add_parsers(sub) -> None:
    """The ``lumped``, ``sensitivity`` commands."""
    lp = sub.add_parser("lumped", help="BICERA-style equivalent-length lumped models (5/6/17/19/21 DOF)")
    lp.add_argument("file", help="crank description or chain file (.toml)")
    lp.add_argument("--dof", type=_dof_list, default=[DEFAULT_PARTITION], help="partition(s): 5, 6, 17, 19, 21, a list, or 'all'")
    lp.add_argument("--stiffness", choices=sorted(WEB_METHODS), default=DEFAULT_WEB_METHOD,
                    help="web stiffness method (default %(default)s)")
    add_json_option(lp)
    lp.set_defaults(func=cmd_lumped)

    sp = sub.add_parser("sensitivity", help="f1 against each reconstructed input, and the f1 band")
    sp.add_argument("file", help="crank description with an [uncertainty] table (.toml)")
    sp.add_argument("--dof", type=int, choices=PARTITIONS, default=DEFAULT_PARTITION)
    sp.add_argument("--stiffness", choices=sorted(WEB_METHODS), default=DEFAULT_WEB_METHOD)
    add_json_option(sp)
    sp.add_argument("--plot", metavar="PATH", help="save the tornado chart (.png, .pdf, .svg)")
    sp.set_defaults(func=cmd_sensitivity)
