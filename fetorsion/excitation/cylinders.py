"""Which cylinder loads which throw, and how: between an engine's cylinders and its crank's
throws (the consumers reach it through :meth:`fetorsion.excitation.loads.CylinderLoads.rods_of_throw`).

Each cylinder's torque and pin force, as functions of the crank angle from its own firing TDC,
are :class:`fetorsion.excitation.loads.CylinderLoads`' (today every cylinder is cylinder 1's
slider-crank, :mod:`fetorsion.excitation.torque`).
A vee cylinder differs from an in-line one only in when it fires (its throw's angle plus its
bank's, :meth:`fetorsion.description.model.Engine.tdc_lags`) and where its rod sits along the
pin. In the throw's own frame (radial along the crank arm, tangential ahead of it) its rod
force is the in-line one, a function of the crank angle from its own bank's axis: the bank's
direction enters through the phase alone. So the load maps keep one row per cylinder, built
from that cylinder's throw (:mod:`fetorsion.description.cylinders`; a misfire of one cylinder
is one row), and a throw's load is the sum of its rows with their phases (:func:`throw_rods`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..description.cylinders import cylinder_throws

if TYPE_CHECKING:
    from ..description.model import Crank


def throw_rods(crank: Crank, force: dict[str, np.ndarray], throw: int) -> dict[str, np.ndarray]:
    """The rods on 0-based ``throw`` over one working cycle, each at its own phase.

    Parameters
    ----------
    crank : Crank
    force : dict
        The rod forces over a cycle from each cylinder's own firing TDC: ``theta`` rad, ``radial``
        and ``tangential`` N, either every cylinder's (cylinders, samples):
        :meth:`fetorsion.excitation.loads.CylinderLoads.pin_forces`, which is how the consumers
        reach it (:meth:`~fetorsion.excitation.loads.CylinderLoads.rods_of_throw`), or one
        cylinder's (samples,) that every rod shares.
    throw : int

    Returns
    -------
    dict
        ``cylinders`` (rods,) 0-based; ``radial``, ``tangential`` (rods, samples), N, on the
        grid ``theta`` of the throw's first cylinder's cycle (each rod's force is its own cylinder's
        delayed by its firing angle less the first rod's, ``phase`` (rods,) rad); ``offset``
        (rods,), m: each big end's axial place from the pin's mid-length.
    """
    from .torque import cycle_angle, firing_angles

    engine = crank.engine
    rods = np.flatnonzero(cylinder_throws(engine) == throw)
    phi = firing_angles(engine)[rods]
    theta = np.asarray(force["theta"], float)
    period = cycle_angle(engine)
    own = {k: np.asarray(force[k], float) for k in ("radial", "tangential")}
    own = {k: v[rods] if v.ndim == 2 else np.broadcast_to(v, (len(rods), v.size)) for k, v in own.items()}
    shifted = {k: np.stack([np.interp(theta - (p - phi[0]), theta, f, period=period) for p, f in zip(phi, own[k])])
               for k in ("radial", "tangential")}
    return {"cylinders": rods, "theta": theta, **shifted, "phase": phi - phi[0],
            "offset": np.array([engine.rod_offset(int(c)) for c in rods])}
