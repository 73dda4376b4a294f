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
