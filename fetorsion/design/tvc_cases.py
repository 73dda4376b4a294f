"""The configurations of a propulsion line's TVC: normal running and the misfire of each cylinder,
each with its couplings at the temperature their heat holds, its shaft sections against UR M68 with
the barred ranges, and its gear meshes against hammering (docs/propulsion-tvc.md).

A misfiring cylinder runs its motored cycle (compression and expansion, no combustion: the
engine's synthetic cycle, :func:`fetorsion.response.forced.misfire_harmonics`), the others fire as
before (:meth:`fetorsion.response.forced.ResponseSetup.with_misfire`); the propeller's blade orders
are unchanged. The worst misfire is the one with the largest τ/τ_C of any shaft section (without
sections, the largest coupling torque against its permissible, else the largest section torque).

A damper that fails is a configuration too ([LRNavalTV] Ch 1 §1.3.1: a design takes account of
component malfunction; §1.3.2: where a limit is exceeded, speed is restricted), one damper at a
time in each of :data:`DAMPER_STATES`: its ring free (the silicone lost, the rubber torn: the ring
no longer coupled, the housing or hub still on its station) and, for a viscous damper, seized (the
silicone thickened until the ring turns with its housing: both on the station, no damping).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace

import numpy as np

from ..description.chain_model import Network
from ..errors import FetorsionError
from ..excitation.torque import MOTORED_COLUMN_MISSING, has_motored_column
from ..lumped_model.network import network_matrices, rear_coordinate
from ..response.forced import ResponseResult, ResponseSetup, misfire_harmonics, solve_response
from ..results import from_fields
from .coupling_heat import CouplingHeat, at_temperatures, coupling_heat
from .gear_hammering import GearHammering, gear_hammering
from .shaft_verdict import ShaftVerdict, shaft_verdict


@dataclass
class TVCCase:
    """One configuration: ``name``, ``misfire`` (0-based cylinder, None: normal running), the
    ``network`` at its couplings' settled temperatures, its ``response`` and verdicts (None where the
    line has no shaft section, coupling, or gear and propeller), and ``damper_heat_w``: each of the
    network's ``[[dampers]]``' largest dissipated power over the speed range (W, in its order). Read
    back from results.json, a misfire's ``response`` is None (the file keeps normal running's alone)."""

    name: str
    misfire: int | None
    network: Network
    response: ResponseResult | None
    shafts: ShaftVerdict | None
    couplings: CouplingHeat | None
    hammering: GearHammering | None
    damper_heat_w: tuple[float, ...] = ()
    #: A failed damper's configuration: its index in the described network's dampers (0-based) and
    #: state (:data:`DAMPER_STATES`); None and "" otherwise.
    damper: int | None = None
    damper_state: str = ""
    #: The largest half-range torque over the crank's sections (a shaft with a cylinder station at
    #: one end), N·m, where and at which speed: shown, not judged — the engine maker's permissible
    #: values are not in a network file (None: no cylinder station).
    crank_torque_nm: float | None = None
    crank_torque_rpm: float | None = None
    crank_section: str = ""
    #: A coupling-tolerance configuration: the coupling's index (0-based) and the factor on its
    #: sheet's stiffness (:func:`tolerance_cases`); None and 1 otherwise.
    coupling: int | None = None
    stiffness_factor: float = 1.0

    @property
    def severity(self) -> float:
        """How close the case comes to a limit (module docs: the worst misfire's measure)."""
        if self.shafts is not None:
            return float(max(np.nanmax(np.where(np.isfinite(s.utilisation), s.utilisation, np.nan))
                             for s in self.shafts.sections))
        if self.couplings is not None and any(c.permissible_torque for c in self.couplings.couplings):
            return float(max(r["torque_nm"] / r["permissible_torque_nm"] for r in self.couplings.rows()
                             if r["permissible_torque_nm"]))
        return float(self.response.section_torque_nm.max())

    def summary(self) -> dict[str, str | float | int | None]:
        """One row of the configurations' table: τ/τ_C, barred ranges, coupling, hammering."""
        rows = self.couplings.rows() if self.couplings else []
        return {"case": self.name, "misfire_cylinder": None if self.misfire is None else self.misfire + 1,
                "largest_tau_over_tau_c": self.severity if self.shafts else None,
                "barred": "; ".join(f"{b['from_rpm']:.1f}-{b['to_rpm']:.1f} rpm" for b in self.shafts.barred)
                if self.shafts else None, "shaft_verdict": self.shafts.verdict if self.shafts else None,
                "coupling_temperature_c": max((r["temperature_c"] for r in rows), default=None),
                "coupling_heat_w": max((r["heat_w"] for r in rows), default=None),
                "coupling_torque_nm": max((r["torque_nm"] for r in rows), default=None),
                "hammering": self.hammering.verdict if self.hammering else None,
                "largest_damper_heat_w": max(self.damper_heat_w, default=None),
                "crank_torque_nm": self.crank_torque_nm, "crank_torque_rpm": self.crank_torque_rpm,
                "crank_section": self.crank_section}

    def to_dict(self) -> dict:
        """JSON-ready: the summary, each damper's heat, and the verdicts' own dicts."""
        return {**self.summary(), "damper_heat_w": list(self.damper_heat_w),
                "failed_damper": None if self.damper is None else self.damper + 1, "damper_state": self.damper_state,
                "coupling": None if self.coupling is None else self.coupling + 1, "stiffness_factor": self.stiffness_factor,
                "shafts": self.shafts.to_dict() if self.shafts else None,
                "couplings": self.couplings.to_dict() if self.couplings else None,
                "hammering": self.hammering.to_dict() if self.hammering else None}

    @classmethod
    def from_dict(cls, d: Mapping[str, object], network: Network | None = None,
                  response: ResponseResult | None = None) -> "TVCCase":
        """The case back from its :meth:`to_dict`; its ``network`` and ``response`` given (not kept in it)."""
        cylinder, failed, coupling = d["misfire_cylinder"], d.get("failed_damper"), d.get("coupling")
        heat = None if d["couplings"] is None else CouplingHeat.from_dict(d["couplings"], response)
        return from_fields(cls, d, {"name": "case"}, misfire=None if cylinder is None else cylinder - 1,
                           network=network, response=response, couplings=heat,
                           damper=None if failed is None else failed - 1,
                           coupling=None if coupling is None else coupling - 1)


def evaluate_case(net: Network, setup_of: Callable[[Network], ResponseSetup], name: str,
                  misfire: int | None = None, damper: int | None = None, damper_state: str = "",
                  coupling: int | None = None, stiffness_factor: float = 1.0) -> TVCCase:
    """One configuration of ``net`` (module docs), its response from ``setup_of`` (network → setup)."""
    heat = coupling_heat(net, setup_of) if net.couplings else None
    settled = at_temperatures(net, heat.temperature_c) if heat else net
    setup = setup_of(settled)
    response = heat.response if heat else solve_response(setup, net.dampers)
    shafts = shaft_verdict(settled, response) if any(s.section for s in net.shafts) else None
    hammer = gear_hammering(settled, setup, response.theta) if net.gears and net.propellers else None
    dampers = tuple(float(p) for p in response.damper_power_w.sum(axis=2).max(axis=0)) if net.dampers else ()
    return TVCCase(name, misfire, settled, response, shafts, heat, hammer, dampers, damper, damper_state,
                   *crank_torque(settled, response), coupling, stiffness_factor)


def crank_torque(net: Network, response: ResponseResult) -> tuple[float | None, float | None, str]:
    """(largest half-range torque N·m, its speed rpm, its section) over the crank's sections of ``net``
    (a shaft with a cylinder station at one end: the throws' and the crank's ends); (None, None, "")
    without cylinder stations."""
    cylinders = set(net.cylinder_stations)
    ks = [k for k, sh in enumerate(net.shafts) if sh.i in cylinders or sh.j in cylinders]
    if not ks:
        return None, None, ""
    T = response.section_torque_nm[:, ks]
    s, k = np.unravel_index(int(np.argmax(T)), T.shape)
    return float(T[s, k]), float(response.rpm[s]), str(response.section_labels[ks[k]])


def misfire_cases(net: Network, setup_of: Callable[[Network], ResponseSetup]) -> list[TVCCase]:
    """The misfire of each cylinder of ``net``'s engine, in order (module docs); none without an engine.

    Raises FetorsionError where the motored cycle is not known (a measured pressure curve)."""
    if net.engine is None or net.excitation is None:
        return []
    if net.excitation.pressure_curve is not None:
        raise FetorsionError("misfire not computed: the motored pressure of a measured pressure curve is not known")
    if net.excitation.tangential_harmonics and not has_motored_column(net.excitation):
        raise FetorsionError(MOTORED_COLUMN_MISSING)
    motored = misfire_harmonics(net, setup_of(net))
    return [evaluate_case(net, lambda n, c=c: setup_of(n).with_misfire(c, motored), f"misfire of cylinder {c + 1}", c)
            for c in range(net.engine.cylinders)]


def worst_case(cases: list[TVCCase]) -> TVCCase | None:
    """The case of the largest :attr:`TVCCase.severity` (None: no case)."""
    return max(cases, key=lambda c: c.severity, default=None)


#: A failed damper's states, each a configuration (module docs); "seized" for a viscous damper only.
DAMPER_STATES = ("ring free", "seized")


def damper_station(net: Network, at: str) -> int:
    """The station (index of ``net.labels``) a damper ``at`` acts on: ``front`` the first, ``rear``
    the last coordinate at the engine's speed, else the named station."""
    if at == "front":
        return 0
    if at == "rear":
        masters = network_matrices(net).masters
        return int(masters[rear_coordinate(net, masters)])
    return list(net.labels).index(at)


def with_failed_damper(net: Network, k: int, state: str) -> Network:
    """``net`` with its damper ``k`` failed in ``state`` (module docs): the damper taken out and its
    housing or hub (and, seized, its ring) added to its station's inertia."""
    if state not in DAMPER_STATES:
        raise FetorsionError(f"damper state {state!r}: choose from {', '.join(DAMPER_STATES)}")
    d = net.dampers[k]
    inertias = list(net.inertias)
    inertias[damper_station(net, d.at)] += d.hub_inertia + (d.ring_inertia if state == "seized" else 0.0)
    return replace(net, dampers=net.dampers[:k] + net.dampers[k + 1:], inertias=tuple(inertias))


def damper_failure_cases(net: Network, setup_of: Callable[[Network], ResponseSetup]) -> list[TVCCase]:
    """Each damper of ``net`` failed in each of its states, one at a time (module docs)."""
    return [evaluate_case(with_failed_damper(net, k, state), setup_of, f"damper '{d.name}' {state}",
                          damper=k, damper_state=state)
            for k, d in enumerate(net.dampers) for state in DAMPER_STATES if state != "seized" or d.kind == "viscous"]


def with_coupling_stiffness(net: Network, k: int, factor: float) -> Network:
    """``net`` with coupling ``k``'s sheet stiffness (nominal and warm) times ``factor``, and the spring
    the network holds for it at its operating temperature likewise (the couplings' springs are the last
    of ``net.shafts``, in the couplings' order)."""
    couplings = list(net.couplings)
    c = couplings[k]
    couplings[k] = replace(c, stiffness=c.stiffness * factor, warm_stiffness=c.warm_stiffness * factor)
    shafts = list(net.shafts)
    at = len(net.shafts) - len(net.couplings) + k
    shafts[at] = replace(shafts[at], stiffness=shafts[at].stiffness * factor)
    return replace(net, couplings=tuple(couplings), shafts=tuple(shafts))


def tolerance_cases(net: Network, setup_of: Callable[[Network], ResponseSetup]) -> list[TVCCase]:
    """Each coupling whose sheet states a stiffness tolerance at both ends of it, one at a time: its
    natural frequencies, and the crossings and heats that follow them, move with its stiffness (a
    rubber element's dynamic stiffness is made to a tolerance, typically ±15 %)."""
    return [evaluate_case(with_coupling_stiffness(net, k, 1 + s * c.stiffness_tolerance), setup_of,
                          f"coupling '{c.name}' C {100 * s * c.stiffness_tolerance:+g} %", coupling=k,
                          stiffness_factor=1 + s * c.stiffness_tolerance)
            for k, c in enumerate(net.couplings) if c.stiffness_tolerance > 0 for s in (-1, 1)]

