"""What the engine model answers for one command (``fetorsion campbell``, ``response``,
``damper``, ``transient``, ``compare``) as the run answers it: the condensed crank's Campbell
diagram and response setup with the fillets as its sections, and the stored engine model that a
lumped answer is measured against, when the store holds it (no rebuild)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from ..description.defaults import DEFAULT_MESH_SIZE
from ..description.chain_model import Chain, Network

if TYPE_CHECKING:
    from ..description.model import Crank
    from ..design.stress import Fillet
    from ..fe.condensed import CondensedCrank
    from ..response.forced import ResponseResult


def stored_engine_model(crank: Crank | Chain | Network, support: str = "bearings",
                        mesh_size: float = DEFAULT_MESH_SIZE):
    """(the condensed crank with its oil films, the crank's fillets) when the store has this crank
    condensed already, else None: a lumped answer then says how far it is from the engine
    model's, at no rebuild.

    Parameters
    ----------
    crank : Crank, Chain or Network
        The description; a chain or a network has no stored engine model.
    support : str
        ``bearings`` (the engine model: the crank as it runs) or ``free`` (none).
    mesh_size : float
        The FE mesh size the condensed crank was built at, m.
    """
    from ..design.stress import fillet_cuts
    from ..fe.store import stored_condensed
    from ..response.coupled import with_film_bearings
    from .engine import engine_fillets

    if isinstance(crank, (Chain, Network)) or support != "bearings":
        return None
    fillets = engine_fillets(crank)
    cc = stored_condensed(crank, mesh_size, fillet_cuts(crank, fillets))
    return None if cc is None else (with_film_bearings(cc), fillets)


def engine_campbell(cc: CondensedCrank, fillets: Sequence[Fillet], support: str,
                    orders: Sequence[float] | np.ndarray | None = None, speed_range: Sequence[float] | None = None,
                    damping_ratio: float | None = None):
    """The condensed crank's Campbell diagram as the run draws it: severity the nominal stress at
    the worst fillet, named.

    Parameters
    ----------
    cc : CondensedCrank
        The condensed crank, with its bearings.
    fillets : list of Fillet
        The crank's fillets (:func:`~fetorsion.app.engine.engine_fillets`), its section cuts in order.
    support : str
        ``bearings`` or ``free``.
    orders : sequence of float, optional
        Engine orders (default the engine's).
    speed_range : (float, float), optional
        Speeds, rpm (default the description's).
    damping_ratio : float, optional
        Modal damping ratio (default the description's).
    """
    from ..response.coupled import run_coupled_campbell

    named = cc.cut_rows is not None and len(cc.cut_rows) == len(fillets)
    return run_coupled_campbell(cc, support, diameters=[(f.diameter, f.bore) for f in fillets], orders=orders,
                                speed_range=speed_range, damping_ratio=damping_ratio,
                                section_names=[f.label for f in fillets] if named else None)


def engine_setup(cc: CondensedCrank, fillets: Sequence[Fillet], support: str, rpm: Sequence[float] | np.ndarray,
                 orders: Sequence[float] | np.ndarray | None = None, damping_ratio: float | None = None):
    """The condensed crank as a response setup, its sections the fillets: the run's.

    Parameters
    ----------
    cc : CondensedCrank
        The condensed crank, with its bearings.
    fillets : list of Fillet
        The crank's fillets, its section cuts in order (their labels name the sections).
    support : str
        ``bearings`` or ``free``.
    rpm : array_like
        Speeds, rpm.
    orders : sequence of float, optional
        Engine orders (default the engine's).
    damping_ratio : float, optional
        Modal damping ratio (default the description's).
    """
    from ..response.coupled import condensed_setup

    return condensed_setup(cc, support, rpm=rpm, orders=orders, damping_ratio=damping_ratio,
                           section_labels=[f.label for f in fillets])


def worst_torque(res: ResponseResult) -> float:
    """The largest section torque of a forced response (a
    :class:`~fetorsion.response.forced.ResponseResult`) over its speeds and sections, N m."""
    return float(np.max(res.section_torque_nm))
