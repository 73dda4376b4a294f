"""``[design]``: what a design search may move, within which bounds, and what it minimises."""

from __future__ import annotations

from dataclasses import dataclass


#: What a design search may minimise: the crank's mass (and an added damper ring's), its rotating
#: inertia, or the change from the given design (the sum of the moved inputs' relative changes).
DESIGN_OBJECTIVES = ("mass", "inertia", "change")


@dataclass(frozen=True)
class DesignSpace:
    """``[design]``: the inputs a design search may move and their bounds (field paths, file
    units), what it minimises, and the damper it may add.

    ``damper`` (``rubber``, ``viscous`` or ``tuned``; None: none added) with its ring inertia as a
    share of the first mode's equivalent inertia seen from the pulley (``damper_inertia_ratio``,
    the bounds) and the ring's radius of gyration (``damper_ring_radius``, m), which turns its
    inertia into mass. ``required_safety``: None for the fatigue method's own.
    ``damper_heat_rating``: the added damper's continuous heat rating, W (None: not rated).
    ``resonance_orders`` and ``resonance_margin``: each resonance speed 60 f1 / q of these orders
    with the first mode in the bearings lies outside the running range by this share of its nearer
    end (empty: no such constraint).
    """

    inputs: tuple[tuple[str, float, float], ...]
    objective: str = "mass"
    damper: str | None = None
    damper_inertia_ratio: tuple[float, float] | None = None
    damper_ring_radius: float | None = None
    required_safety: float | None = None
    damper_heat_rating: float | None = None
    resonance_orders: tuple[float, ...] = ()
    resonance_margin: float = 0.0
