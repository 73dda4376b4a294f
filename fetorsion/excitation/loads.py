"""The one load seam: every cylinder's load, built on a model's cylinders, for every consumer.

:class:`CylinderLoads` holds what each cylinder puts on the crank over its working cycle, from its
own firing TDC: its torque (gas and reciprocating inertia, from the pressure curve or the harmonic
table, :func:`fetorsion.excitation.torque.cylinder_torque`) and its rod's force on the pin in the
throw's frame (:func:`fetorsion.excitation.torque.cylinder_pin_forces`). A misfire is a variant of
one cylinder (its motored cycle). Its firing angle, its throw and its rod's place come from the
engine (:meth:`fetorsion.description.model.Engine.firing_angles`, ``throw_of_cylinder``,
``rod_offset``).

Every consumer reads the loads through it: the forced response's harmonics
(:meth:`~CylinderLoads.torque_harmonics`, :meth:`~CylinderLoads.pin_force_harmonics`), Campbell's
order torques, the time domain's torque tables (:meth:`~CylinderLoads.torque_table`), the condensed
crank's pin loads and load cycle (:meth:`~CylinderLoads.pin_forces`) and M53's throws
(:meth:`~CylinderLoads.rods_of_throw`). Each of these is built from the two one-cylinder methods
:meth:`~CylinderLoads.cylinder_torque` and :meth:`~CylinderLoads.cylinder_pin_forces`, cylinder by
cylinder, so a load that differs between cylinders (an articulated rod, a per-cylinder pressure)
is written there once and reaches all of them (docs/architecture.md, "An excitation").
"""

from __future__ import annotations

from collections import OrderedDict
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from .torque import (CycleTorque, Harmonics, articulated_cylinder_torque, articulated_pin_forces, cycle_angle,
                     cylinder_pin_forces, cylinder_torque, firing_angles, harmonics)

if TYPE_CHECKING:
    from collections.abc import Sequence

    from ..description.chain_model import Chain, Network
    from ..description.model import Crank, Engine

#: One-cylinder cycles kept per object (every cylinder at one speed, fired and motored).
_KEPT = 8
#: Whole harmonic tables (speeds, orders, cylinders) kept across objects, by the content of the
#: engine and excitation they are made of (all a cylinder's load reads): a design search's
#: candidates and a verdict's configurations move webs, pins and dampers, not the cylinders, and
#: each built its tables again (65 s of an 83 s search on the Renault, 98 candidates).
_TABLES: OrderedDict = OrderedDict()
#: Tables kept (each some 0.1-2 MB: 300 speeds, 48 orders, 6 cylinders are 1.4 MB).
_TABLES_KEPT = 16


@dataclass(frozen=True, eq=False)
class CylinderLoads:
    """Every cylinder's load of ``model`` (a Crank, or a Chain or Network with an engine): module docs.

    Speeds are given to each method (Campbell reads one per crossing, M53 one rated speed, the
    forced response a range): the one-cylinder cycle of a speed is computed once and shared by
    every cylinder whose load is cylinder 1's.
    """

    model: Crank | Chain | Network
    _kept: OrderedDict = field(default_factory=OrderedDict, repr=False, compare=False)
    _content: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def engine(self) -> Engine:
        return self.model.engine

    @property
    def cylinders(self) -> int:
        return self.engine.cylinders

    @property
    def period(self) -> float:
        """One working cycle, rad of crank angle."""
        return cycle_angle(self.engine)

    @property
    def firing(self) -> np.ndarray:
        """(cylinders,) each cylinder's firing angle after cylinder 1's, rad."""
        return firing_angles(self.engine)

    def phasors(self, orders: Sequence[float] | np.ndarray) -> np.ndarray:
        """(orders, cylinders) e^{−i q φ_c}: cylinder c's load lags its own cycle's by φ_c."""
        return np.exp(-1j * np.asarray(orders, float)[:, None] * self.firing[None, :])

    # -- the one place a cylinder's load is written -------------------------------------------------

    def cylinder_torque(self, cylinder: int, rpm: float, theta: np.ndarray | None = None,
                        misfire: bool = False) -> CycleTorque:
        """0-based ``cylinder``'s torque over its cycle from its own firing TDC at ``rpm`` (``theta``
        rad, default :func:`~fetorsion.excitation.torque.cycle_grid`); ``misfire``: its motored
        cycle. Every cylinder is cylinder 1's slider-crank on the engine's one pressure curve, but an
        articulated rod's (:func:`~fetorsion.excitation.torque.articulated_cylinder_torque`)."""
        art = self.engine.articulated(cylinder)  # a master and articulated rod pair's second cylinder
        key = ("torque", float(rpm), None if theta is None else np.asarray(theta, float).tobytes(), bool(misfire), art)
        if art:
            return self._kept_or(key, lambda: articulated_cylinder_torque(self.model, rpm, theta, misfire))
        return self._kept_or(key, lambda: cylinder_torque(self.model, rpm, theta, misfire))

    def cylinder_pin_forces(self, cylinder: int, rpm: float, misfire: bool = False) -> dict[str, np.ndarray]:
        """0-based ``cylinder``'s rod force on its pin over its cycle from its own firing TDC, in the
        throw's frame: ``theta`` rad, ``tangential`` and ``radial`` N
        (:func:`~fetorsion.excitation.torque.cylinder_pin_forces`); ``misfire``: its motored cycle."""
        if self.engine.articulated(cylinder):
            return self._kept_or(("pins", float(rpm), None, bool(misfire), True),
                                 lambda: articulated_pin_forces(self.model, rpm, misfire))
        return self._kept_or(("pins", float(rpm), None, bool(misfire)),
                             lambda: cylinder_pin_forces(self.model, rpm, misfire))

    def _kept_or(self, key: tuple, make):
        if key not in self._kept:
            if len(self._kept) >= _KEPT:
                self._kept.popitem(last=False)
            self._kept[key] = make()
        return self._kept[key]

    # -- what the consumers read ---------------------------------------------------------------------

    def torques(self, rpm: float, theta: np.ndarray | None = None, misfire: int | None = None) -> list[CycleTorque]:
        """Each cylinder's :meth:`cylinder_torque` (0-based ``misfire``: that one's motored cycle)."""
        return [self.cylinder_torque(c, rpm, theta, c == misfire) for c in range(self.cylinders)]

    def cylinder_harmonics(self, rpm: float, cylinder: int = 0, misfire: bool = False) -> Harmonics:
        """The orders of one cylinder's torque at ``rpm`` (its own cycle, no firing phase)."""
        return harmonics(self.cylinder_torque(cylinder, rpm, misfire=misfire).total, self.period)

    def torque_harmonics(self, rpm: Sequence[float] | np.ndarray, orders: Sequence[float] | np.ndarray,
                         misfire: int | None = None) -> np.ndarray:
        """(speeds, orders, cylinders) complex torque harmonics of each cylinder's own cycle, N·m
        (cylinder c's load on the crank is this times ``phasors`` [:, c]); 0-based ``misfire``: that
        cylinder's motored cycle."""
        return self._harmonics(rpm, orders, lambda c: c == misfire)

    def motored_torque_harmonics(self, rpm: Sequence[float] | np.ndarray,
                                 orders: Sequence[float] | np.ndarray) -> np.ndarray:
        """(speeds, orders, cylinders): each cylinder's harmonics when it is the one that misfires."""
        return self._harmonics(rpm, orders, lambda c: True)

    def _table(self, kind: tuple, rpm, orders, make) -> np.ndarray:
        """``make()``'s table, or a copy of the one kept for the same engine, excitation, ``kind``
        (which table, which cylinder misfires), speeds and orders."""
        import hashlib
        import pickle

        if "key" not in self._content:
            self._content["key"] = hashlib.sha256(pickle.dumps((self.engine, self.model.excitation))).hexdigest()
        key = (self._content["key"], kind, np.asarray(rpm, float).tobytes(), np.asarray(orders, float).tobytes())
        if key in _TABLES:
            _TABLES.move_to_end(key)
        else:
            if len(_TABLES) >= _TABLES_KEPT:
                _TABLES.popitem(last=False)
            _TABLES[key] = make()
        return _TABLES[key].copy()

    def _harmonics(self, rpm, orders, misfiring) -> np.ndarray:
        kind = ("torque", tuple(bool(misfiring(c)) for c in range(self.cylinders)))
        return self._table(kind, rpm, orders, lambda: self._harmonics_made(rpm, orders, misfiring))

    def _harmonics_made(self, rpm, orders, misfiring) -> np.ndarray:
        out = np.empty((len(rpm), len(orders), self.cylinders), complex)
        for s, n in enumerate(rpm):
            last = None
            for c in range(self.cylinders):
                t = self.cylinder_torque(c, n, misfire=misfiring(c))
                if last is None or t is not last[0]:  # a cylinder with cylinder 1's load: its harmonics
                    last = (t, harmonics(t.total, self.period).at(orders))
                out[s, :, c] = last[1]
        return out

    def pin_forces(self, rpm: float, misfire: int | None = None) -> dict[str, np.ndarray]:
        """Every cylinder's rod force over its own cycle from its firing TDC: ``theta`` (samples,)
        rad; ``tangential``, ``radial`` (cylinders, samples) N; 0-based ``misfire`` motored."""
        f = [self.cylinder_pin_forces(c, rpm, c == misfire) for c in range(self.cylinders)]
        return {"theta": f[0]["theta"], **{k: np.stack([x[k] for x in f]) for k in ("tangential", "radial")}}

    def pin_force_harmonics(self, rpm: Sequence[float] | np.ndarray, orders: Sequence[float] | np.ndarray,
                            misfire: int | None = None) -> np.ndarray:
        """(speeds, orders, cylinders, 2) complex harmonics of each cylinder's tangential and radial
        rod force over its own cycle, N; 0-based ``misfire``: that cylinder's motored cycle."""
        return self._pin_harmonics(rpm, orders, lambda c: c == misfire)

    def motored_pin_force_harmonics(self, rpm: Sequence[float] | np.ndarray,
                                    orders: Sequence[float] | np.ndarray) -> np.ndarray:
        """(speeds, orders, cylinders, 2): each cylinder's when it is the one that misfires."""
        return self._pin_harmonics(rpm, orders, lambda c: True)

    def _pin_harmonics(self, rpm, orders, misfiring) -> np.ndarray:
        kind = ("pins", tuple(bool(misfiring(c)) for c in range(self.cylinders)))
        return self._table(kind, rpm, orders, lambda: self._pin_harmonics_made(rpm, orders, misfiring))

    def _pin_harmonics_made(self, rpm, orders, misfiring) -> np.ndarray:
        out = np.empty((len(rpm), len(orders), self.cylinders, 2), complex)
        for s, n in enumerate(rpm):
            last = None
            for c in range(self.cylinders):
                f = self.cylinder_pin_forces(c, n, misfiring(c))
                if last is None or f is not last[0]:
                    last = (f, [harmonics(f[k], self.period).at(orders) for k in ("tangential", "radial")])
                out[s, :, c, 0], out[s, :, c, 1] = last[1]
        return out

    def torque_table(self, grid: Sequence[float] | np.ndarray, theta: np.ndarray, part: str = "total",
                     misfire: int | None = None) -> np.ndarray:
        """(cylinders, speeds, samples): each cylinder's torque ``part`` (``total``, ``gas`` or
        ``inertia``) at the speeds ``grid`` over its own cycle's angles ``theta``, N·m."""
        return np.stack([np.array([getattr(self.cylinder_torque(c, r, theta, c == misfire), part) for r in grid])
                         for c in range(self.cylinders)])

    def engine_torque(self, rpm: float) -> CycleTorque:
        """The sum of every cylinder's torque on a rigid crank over one cycle from cylinder 1's
        firing TDC, N·m: cylinder c's delayed by φ_c on the periodic sample grid (the firing angles
        must fall on it: they do for any even firing of up to 16 cylinders at 0.5°)."""
        from ..errors import FetorsionError

        each = self.torques(rpm)
        step = each[0].theta[1] - each[0].theta[0]
        shifts = self.firing / step
        if np.any(np.abs(shifts - np.rint(shifts)) > 1e-6):
            raise FetorsionError("firing angles do not fall on the 0.5° sample grid")
        return CycleTorque(each[0].theta, sum(np.roll(t.total, int(k)) for t, k in zip(each, np.rint(shifts))))

    def rods_of_throw(self, rpm: float, throw: int) -> dict[str, np.ndarray]:
        """The rods on 0-based ``throw`` at ``rpm``, each with its own force at its phase and place
        (:func:`fetorsion.excitation.cylinders.throw_rods`)."""
        from .cylinders import throw_rods

        return throw_rods(self.model, self.pin_forces(rpm), throw)


def cylinder_loads(model: Crank | Chain | Network) -> CylinderLoads:
    """The cylinder loads of ``model`` (with ``[engine]`` and ``[excitation]``): the one way every
    consumer reaches them."""
    from ..errors import FetorsionError

    if getattr(model, "excitation", None) is None:
        raise FetorsionError(f"{getattr(model, 'source', None) or model.name}: the description has no [excitation] table")
    return CylinderLoads(model)


def engine_torque(crank: Crank | Chain | Network, rpm: float) -> CycleTorque:
    """Sum of all cylinders' torques on a rigid crank over one cycle, N·m (:meth:`CylinderLoads.engine_torque`)."""
    return cylinder_loads(crank).engine_torque(rpm)
