"""The engine model of a run, as every command takes it: the crank condensed with a section cut at
every fillet, from the store when built before (:mod:`fetorsion.fe.store`), in its bearings with
their oil films at the journals' mean loads when the description states none."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..webs.methods import crank_web_method

if TYPE_CHECKING:
    from collections.abc import Callable

    from ..description.model import Crank


def engine_fillets(crank: Crank):
    """The crank's fillets (and oil bores) as the run finds them: their cuts are part of the
    condensed crank, and the verdict reads them in this order.

    Parameters
    ----------
    crank : Crank
        A crank description.
    """
    from ..design.stress import fillets_of
    from ..lumped_model.parts import build_parts

    return fillets_of(crank, build_parts(crank, crank_web_method(crank)))


def engine_condensed(crank: Crank, mesh_size: float, progress: Callable[[str], None] | None = None,
                     stage: Callable[[str], None] | None = None):
    """The run's condensed crank (:class:`~fetorsion.fe.condensed.CondensedCrank`): from the
    store, else built (said through ``progress``) and kept; with its oil films.

    Parameters
    ----------
    crank : Crank
        A crank description.
    mesh_size : float
        The FE mesh's element size, m.
    progress : callable, optional
        Called with a line of text when the crank has to be built.
    stage : callable, optional
        Called with each stage's name as the build starts it (a :class:`~fetorsion.io.Stages`).
    """
    from ..design.stress import fillet_cuts
    from ..fe.store import condensed_crank
    from ..response.coupled import with_film_bearings

    cc, _ = condensed_crank(crank, mesh_size, fillet_cuts(crank, engine_fillets(crank)), progress=progress,
                            stage=stage)
    return with_film_bearings(cc)
