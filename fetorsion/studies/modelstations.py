"""Where a sensor sits on the model, and what the model says there: the stations of a chain or of
the condensed crank by name or 1-based number (as ``fetorsion compare`` and a universal file's
nodes give them), the running model's forced response, and its order cut at a station; the full
FE's twist at the condensed crank's stations, for the mode shapes a modal test is set beside."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from ..description.defaults import LUMPED17
from ..errors import FetorsionError

if TYPE_CHECKING:
    from ..description.chain_model import Chain, Network
    from ..description.model import Crank
    from ..fe.condensed import CondensedCrank


def response_stations(response) -> list[tuple[str, int]]:
    """(name, DOF) of every station of a response a sensor can sit on, in the model's order:
    a chain's stations; the condensed crank's masters (front, journals, pins, rear), their θx.
    A station's 1-based place in this list is its number (``--station``, a UFF node)."""
    labels = list(response.labels)
    twists = [(lb[:-3], j) for j, lb in enumerate(labels) if lb.endswith(" rx")]
    if twists:
        return twists
    rings = set(getattr(response, "damper_names", ()))
    return [(lb, j) for j, lb in enumerate(labels) if lb not in rings]


def model_stations(crank: Crank | Chain | Network, source: str = LUMPED17) -> list[str]:
    """The names of the stations a sensor can sit on in the ``source`` model of ``crank``, before
    it is built, in :func:`response_stations`'s order."""
    if source == LUMPED17 or not hasattr(crank, "journals"):
        from ..lumped_model.lumped import lumped

        return list(lumped(crank, 17).labels)
    from ..fe.cranksystem import master_labels

    return master_labels(crank)


def station_index(response, station: str | None) -> tuple[int, str]:
    """The response's DOF for a sensor: ``None`` or ``pulley`` the pulley end, ``flywheel`` the
    flywheel end, else a station's name (case-insensitive) or its 1-based number
    (:func:`response_stations`)."""
    stations = response_stations(response)
    names = {j: name for name, j in stations}
    p, f = response.pulley, response.flywheel % len(response.labels)
    if station is None or station.lower() == "pulley":
        return p, f"{names.get(p, response.labels[p])} (pulley end)"
    if station.lower() == "flywheel":
        return f, f"{names.get(f, response.labels[f])} (flywheel end)"
    name, j = stations[station_place([name for name, _ in stations], station)]
    return j, name


def station_place(names: Sequence[str], station: str) -> int:
    """The 0-based place among the model's station ``names`` of a station given by its name
    (case-insensitive) or its 1-based number; one message naming it otherwise."""
    if station.isdigit() and 1 <= int(station) <= len(names):
        return int(station) - 1
    low = [name.lower() for name in names]
    if station.lower() in low:
        return low.index(station.lower())
    raise FetorsionError(f"compare: station {station!r} is not in the model; give pulley, flywheel or one of "
                         f"{', '.join(names)}")


def order_index(response, order: float) -> int:
    """The place of engine order ``order`` among the response's orders, or one message naming it."""
    k = np.flatnonzero(np.isclose(response.orders, order, rtol=0, atol=1e-9))
    if not k.size:
        raise FetorsionError(f"compare: order {order:g} is not among the model's orders "
                             f"({response.orders.min():g}-{response.orders.max():g})")
    return int(k[0])


def model_order_cut(response, order: float, station: int) -> np.ndarray:
    """The model's order-``order`` angle amplitude (zero to peak, degrees) at ``station`` against
    the response's speeds."""
    return np.degrees(np.abs(response.theta[:, order_index(response, order), station]))


def model_response(crank: Crank | Chain | Network, source: str = LUMPED17, condensed: CondensedCrank | None = None):
    """The forced response of the running model: the lumped chain's, or the condensed crank's in
    its bearings with the description's dampers (:class:`~fetorsion.response.forced.ResponseResult`)."""
    from ..response.forced import run_response, solve_response

    if source == LUMPED17:
        return run_response(crank)
    from ..response.coupled import condensed_setup

    return solve_response(condensed_setup(need_condensed(condensed, source), "bearings"), getattr(crank, "dampers", ()))


def need_condensed(condensed, source: str):
    """``condensed``, the condensed crank the ``source`` model needs, or one message saying it is missing."""
    if condensed is None:
        raise FetorsionError(f"compare: source {source!r} needs the condensed crank")
    return condensed


def fe_station_twists(res) -> np.ndarray:
    """(modes, stations) the full FE modes' twist at the condensed crank's stations (front, J1,
    P1, …, rear): the mass-uniform rigid fit's θx of the front face's nodes, each journal's and
    pin's part, the rear face's (``res``: a :class:`~fetorsion.fe.crankfe.CrankModal`)."""
    from ..fe.cranksystem import master_labels
    from ..fe.crankfe import part_nodes
    from ..fe.modeshape import slab_fit

    mesh = res.mesh
    out = []
    for label in master_labels(res.crank):
        if label in ("front", "rear"):
            nodes = np.asarray(mesh.node_sets[f"{label}_face"])
        else:
            nodes = part_nodes(mesh, f"{'journal' if label[0] == 'J' else 'pin'}_{label[1:]}")
        out.append(slab_fit(res.shapes[:, nodes], mesh.nodes[nodes], np.ones(len(nodes)))[0][:, 3])
    return np.stack(out, axis=1)
