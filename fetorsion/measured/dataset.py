"""Every measured record a comparison reads, as one typed set (read and checked before any model
is solved: :func:`fetorsion.cli.measured.read_measured`)."""
from __future__ import annotations

from dataclasses import dataclass, field

from .torsiograph import OrderTrack
from .uff import MeasuredFunction

#: Where a cut was measured: one station's name, or two for a twist.
Station = str | tuple[str, ...]


@dataclass(frozen=True)
class MeasuredData:
    """Measured records for a comparison.

    Attributes
    ----------
    frfs : tuple of MeasuredFunction
        Modal-test FRFs.
    cuts : tuple of MeasuredFunction
        Order cuts against speed, angles in rad.
    tracks : tuple of (str, OrderTrack)
        Torsiograph order maps by channel name.
    band : (float, float) or None
        The band the FRFs' modes are fitted in, Hz.
    stations : dict[str, (Station, bool)]
        Cut label → where it was measured and whether the user said so (cuts not named take the
        comparison's station); :meth:`settled` keeps the ones the model has.
    notes : tuple of str
        Warnings of the reading (edges repaired ...).
    """

    frfs: tuple[MeasuredFunction, ...] = ()
    cuts: tuple[MeasuredFunction, ...] = ()
    tracks: tuple[tuple[str, OrderTrack], ...] = ()
    band: tuple[float, float] | None = None
    stations: dict[str, tuple[Station, bool]] = field(default_factory=dict)
    notes: tuple[str, ...] = ()

    def station_of(self, label: str, default: str | None) -> Station | None:
        """Where cut ``label`` was measured (``default`` where no station is on record)."""
        return self.stations[label][0] if label in self.stations else default
