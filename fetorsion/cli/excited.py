"""What the commands on an excited crank (``campbell``, ``response``, ``damper``, ``transient``)
share: the model that answers (``--source`` and its default), the engine model built or taken
from the store, the line that says how far a lumped answer is from it, and their options."""

from __future__ import annotations

import argparse
import math

from .options import MM, millimetres, real
from ..description.chain_model import Chain, Network
from ..errors import FetorsionError
from ..lumped_model.lumped import PARTITIONS
from ..description.defaults import DEFAULT_DAMPING_RATIO, DEFAULT_MESH_SIZE, DEFAULT_WEB_METHOD, LUMPED17
from ..webs.methods import WEB_METHODS
from .common import SUPPORT_CHOICES, add_json_option, check_mesh_size, load_excited
from .fe import condensed, engine_fillets


def source_of(args, model) -> str:
    """``--source``, or its default: a crank description's engine model (the condensed crank in
    its bearings, the run's), a chain's or network's own lumped model."""
    from ..response.driveline import condensed_part

    if args.source is not None:
        return args.source
    if isinstance(model, Network) and condensed_part(model) is not None:
        return "condensed"  # its [[chain.cranks]] names the condensed crank
    return LUMPED17 if isinstance(model, (Chain, Network)) else "condensed"


def load_for(args):
    """The command's description, with an [excitation] table; ``args.source`` set to its default
    (:func:`source_of`) when not given."""
    model = load_excited(args.file, args.source or LUMPED17)
    args.source = source_of(args, model)
    return model


def only_lumped_driveline(crank, args, command: str) -> None:
    """A network on the condensed crank (``dof = "condensed"``) is solved by ``response`` and
    ``run``; the other commands take its lumped stand-in only when asked by ``--source lumpedN``."""
    from ..response.driveline import condensed_part

    if isinstance(crank, Network) and condensed_part(crank) is not None and not str(args.source).startswith("lumped"):
        raise FetorsionError(f"{command}: {args.file} puts its crank in as the condensed crank, which `fetorsion "
                             f"response` and `fetorsion run` solve; give --source lumped17 for the driveline on the "
                             f"crank's lumped 17-DOF model")


def engine_model(crank, args):
    """(the run's condensed crank, with its oil films, and the crank's fillets): from the
    store, or built once and kept (:func:`fetorsion.cli.fe.condensed`)."""
    check_mesh_size(crank, args.mesh_size, "modal")
    return condensed(crank, args.mesh_size), engine_fillets(crank)


def engine_gap_line(what: str, lumped_value: float, engine_value: float, unit: str) -> str:
    """The line under a lumped answer: how far its ``what`` is from the stored engine model's."""
    return (f"(lumped answer; the condensed crank in its bearings, stored, gives {what} {engine_value:.4g} {unit}: "
            f"the lumped one is {100 * (lumped_value / engine_value - 1):+.1f} % from it)")


def _orders(text: str) -> list[float]:
    """``--orders``: comma-separated engine orders, each in (0, 100]."""
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"--orders {text!r}: give comma-separated numbers, e.g. 0.5,1,1.5") from None
    if any(not (math.isfinite(v) and 0 < v <= 100) for v in values):
        raise argparse.ArgumentTypeError(f"--orders {text!r}: orders must be > 0 and <= 100")
    return values


def add_excitation_options(p: argparse.ArgumentParser) -> None:
    """The options of ``campbell``, ``damper`` and ``response``: the file, the model, the speeds,
    the orders, the damping and the outputs."""
    p.add_argument("file", help="crank description or chain file with an [excitation] table (.toml)")
    p.add_argument("--source", choices=[f"lumped{d}" for d in PARTITIONS] + ["fe", "condensed"],
                   help="which model answers (default: for a crank description condensed, the engine model 'fetorsion "
                        "run' reports on: the 3D FE crank condensed to its journal and pin centres in its bearings, "
                        "torsion and bending coupled, taken from the store after its first build; for a chain or "
                        "network file its own lumped model). lumpedN: the fast N-DOF chain, with a line saying how "
                        "far it is from the stored condensed crank; fe: campbell only, free-free FE torsional modes")
    p.add_argument("--mesh-size", type=millimetres(), default=DEFAULT_MESH_SIZE, metavar="MM",
                   help=f"FE mesh size of the condensed crank (and of --source fe) (default {DEFAULT_MESH_SIZE / MM:g})")
    p.add_argument("--support", choices=SUPPORT_CHOICES, default="bearings",
                   help="the crank in its main bearings (default, as it runs) or free-free (as on a modal test "
                        "bench); lumped: the fe web method becomes fe-held")
    p.add_argument("--stiffness", choices=sorted(WEB_METHODS), default=DEFAULT_WEB_METHOD)
    p.add_argument("--speed-range", nargs=2, type=real(0.0, unit="rpm"), metavar=("LOW", "HIGH"),
                   help="rpm, 0 < LOW < HIGH")
    p.add_argument("--orders", type=_orders, help="comma-separated orders (default 0.5 ... 12 for a 4-stroke)")
    p.add_argument("--damping", type=real(0.0, 1.0), help=f"modal damping ratio, 0 < ζ < 1 (default from the file, else {DEFAULT_DAMPING_RATIO:g})")
    add_json_option(p)
    p.add_argument("--plot", metavar="PATH", help="save the plot (.png, .pdf, .svg)")
