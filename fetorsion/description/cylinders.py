"""Which cylinder drives which throw: the engine's cylinders against its crank's throws (in-line:
one each; a vee: two cylinders per throw). The load maps of every model keep one row per cylinder,
built from its throw's entry by :func:`per_cylinder`; the phases are in
:meth:`~fetorsion.description.model.Engine.firing_angles`."""

from __future__ import annotations

import numpy as np

from .model import Engine


def cylinder_throws(engine: Engine) -> np.ndarray:
    """The 0-based throw of each cylinder, (cylinders,) int."""
    return np.array([engine.throw_of_cylinder(c) for c in range(engine.cylinders)], dtype=int)


def per_cylinder(engine: Engine, per_throw: np.ndarray, axis: int = 0) -> np.ndarray:
    """``per_throw`` (one entry per throw along ``axis``) with one entry per cylinder: its throw's."""
    return np.take(np.asarray(per_throw), cylinder_throws(engine), axis=axis)


def cylinders_per_throw(engine: Engine) -> np.ndarray:
    """How many cylinders (rods) each throw carries, (throws,) int."""
    return np.bincount(cylinder_throws(engine), minlength=engine.throws)


def rod_centre(engine: Engine, cylinder: int) -> np.ndarray:
    """(y, z), m: the axis of the pin, or half of a split pin, that 0-based ``cylinder``'s rod runs
    on, R (cos a_c, sin a_c) with a_c its throw's angle plus its half's split."""
    a = engine.pin_angle(cylinder)
    return engine.crank_radius * np.array([np.cos(a), np.sin(a)])


def pin_master_centre(engine: Engine, throw: int, split_angle: float = 0.0) -> np.ndarray:
    """(y, z), m: where the condensed crank's master of 0-based ``throw``'s pin sits across the crank
    axis: on the pin's axis; for a pin split by ``split_angle`` (rad), midway between its two half
    pins' axes, R cos(δ/2) from the crank axis at a_t + δ/2 (docs/vee-engines.md, *split pins*)."""
    a = engine.crank_angles[throw]
    ends = [a, a + split_angle]
    return 0.5 * engine.crank_radius * np.array([sum(np.cos(ends)), sum(np.sin(ends))])
