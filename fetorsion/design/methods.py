"""The one registry of fatigue methods: name -> :class:`FatigueMethod`.

A method takes one configuration's loads (:class:`ConfigLoads`: the crank, its response setup
with the configuration's dampers, the synthesised section torques, the fillet cuts' load cycle)
and returns a typed assessment; :meth:`FatigueMethod.answer` reads from it the verdict's figures
(safety, required, governing place and speed, pass, yielding places). The verdict
(:mod:`fetorsion.design.crank_verdict`), the command line's ``--fatigue-method``, the check of a
description's ``[limits] fatigue_method`` and the report read the list from here.

Add a method by writing a module with its ``assess`` and ``answer`` and naming it in
:data:`FATIGUE_METHODS` (docs/architecture.md, "Add a fatigue method").
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Callable

import numpy as np

from ..errors import FetorsionError

if TYPE_CHECKING:
    from ..description.model import Crank


@dataclass
class ConfigLoads:
    """One configuration's loads, each computed once and only when a method asks.

    ``setup``: the response setup (:func:`fetorsion.response.coupled.condensed_setup`) at its
    damping, misfire included; ``dampers`` on it; ``fillets``, ``scf`` and (the ``fe`` path's)
    ``locations`` and ``mean`` (the cuts' order-0 loads) as the verdict has them; ``check``: the
    ``fe`` path's all-node check at the worst speed (off for the damping searches)."""

    crank: object
    cc: object
    setup: object
    dampers: tuple
    fillets: list
    scf: object
    locations: list | None = None
    mean: np.ndarray | None = None
    check: bool = True
    _response: object = None
    _cycle: object = None

    @property
    def response(self):
        """The forced response (:func:`fetorsion.response.forced.solve_response`), solved once."""
        if self._response is None:
            from ..response.forced import solve_response

            self._response = solve_response(self.setup, self.dampers)
        return self._response

    @property
    def cycle(self):
        """The fillet cuts' load cycle (:func:`fetorsion.response.cycle.run_load_cycle`), once."""
        if self._cycle is None:
            from ..response.cycle import run_load_cycle

            self._cycle = run_load_cycle(self.cc, self.setup, self.dampers, mean=self.mean)
        return self._cycle

    def release(self) -> None:
        """Drop the load cycle (hundreds of MB on a long speed range) once the methods have read it."""
        self._cycle = None


@dataclass(frozen=True)
class MethodAnswer:
    """A fatigue method's answer for one configuration: its governing place and speed, and the
    safety there against the required one.

    Attributes
    ----------
    safety, required : float
        The governing safety factor and the method's required one [-].
    location : str
        The governing place (``throws 1, 2: pin oil bore``, ``P4 fillet at x = 369.0 mm``).
    where : str
        The section it was read at (M53: the torque's section).
    rpm : float
        The governing speed [rpm].
    passes : bool
        Every place at or above the required safety, none yielding.
    yielding : tuple of str
        The places whose stress is above the yield strength (beyond a linear assessment).
    """

    safety: float
    required: float
    location: str
    where: str
    rpm: float
    passes: bool
    yielding: tuple[str, ...] = ()

    def to_dict(self) -> dict:
        """The answer as JSON-ready numbers and strings."""
        return {"safety": self.safety, "required": self.required, "location": self.location, "where": self.where,
                "rpm": self.rpm, "passes": self.passes, "yielding": list(self.yielding)}

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "MethodAnswer":
        """The answer back from its :meth:`to_dict` (other keys beside it are left)."""
        from ..results import from_fields

        return from_fields(cls, d)


def answer_dict(answer: MethodAnswer | None) -> dict:
    """An answer as JSON ({} where the method did not run)."""
    return {} if answer is None else answer.to_dict()


@dataclass(frozen=True)
class FatigueMethod:
    """A fatigue method: its ``name``, a one-line ``title``, whether it reads the recovered stress
    zones and the load cycle (``needs_recovery``), ``assess(loads) -> assessment`` and
    ``answer(assessment) -> MethodAnswer``."""

    name: str
    title: str
    needs_recovery: bool
    assess: Callable
    answer: Callable
    #: ``safety(loads) -> float``, the governing safety alone where a method has a shorter way to
    #: it than its whole assessment (the damping searches call it a dozen times); None: from
    #: :attr:`assess` and :attr:`answer`.
    safety: Callable | None = None

    def governing_safety(self, loads: "ConfigLoads") -> float:
        """The governing safety of ``loads`` by this method (:attr:`safety`, else the whole assessment's)."""
        return self.safety(loads) if self.safety is not None else self.answer(self.assess(loads)).safety


def fillet_torque_amplitude(setup, response, fillets) -> np.ndarray:
    """(speeds, fillets): the alternating torque (half peak-to-peak, N·m) each fillet's section
    carries in ``response`` (a :func:`~fetorsion.response.forced.solve_response` of ``setup``)."""
    from .stress import fillet_sections

    return np.asarray(response.section_torque_nm)[:, fillet_sections(fillets, setup)]


def assess_m53(loads: ConfigLoads):
    """[KR-M53] as written on the configuration's section torques (:func:`fetorsion.design.m53.run_m53_crank`)."""
    from .m53 import run_m53_crank

    return run_m53_crank(loads.crank, loads.fillets, fillet_torque_amplitude(loads.setup, loads.response, loads.fillets),
                         loads.setup.rpm, fe_scf=loads.scf)


def safety_m53(loads: ConfigLoads) -> float:
    """M53's governing safety alone: the rule reads from the vibration calculation only the largest
    alternating torque through a pin and through a journal fillet section over the speeds
    ([KR-M53] §2.(2)(A)(f)), so those two are synthesised by bound
    (:func:`fetorsion.response.synthesis.largest_half_peak_to_peak`, the same values as the whole
    response's) and put into the rule's places with their bending held
    (:func:`fetorsion.design.m53.m53_utilisation`), instead of every section at every speed."""
    from ..response.forced import section_torques, solve_theta
    from ..response.synthesis import group_maxima
    from .m53 import m53_utilisation, run_m53_crank

    setup = loads.setup
    held = run_m53_crank(loads.crank, loads.fillets, np.zeros((1, len(loads.fillets))), setup.rpm[:1], fe_scf=loads.scf)
    utilisation = m53_utilisation(held, loads.fillets, setup)
    theta, _, _ = solve_theta(setup, loads.dampers)
    torque = group_maxima(section_torques(setup, theta), setup.orders, setup.period, utilisation.groups)
    return 1.0 / float(utilisation(torque)[0])


def answer_m53(result) -> MethodAnswer:
    g = result.governing
    return MethodAnswer(g.safety, g.required, g.name, g.torque_section, g.torque_rpm, result.passes,
                        tuple(a.name for a in result.locations if a.yielding))


def assess_recovered(loads: ConfigLoads):
    """Findley on the recovered local stress (:func:`fetorsion.design.recovered.run_recovered_assessment`)."""
    from .recovered import run_recovered_assessment

    return run_recovered_assessment(loads.crank, loads.cycle, loads.locations, check=loads.check)


def answer_recovered(a) -> MethodAnswer:
    j = a.governing
    loc = a.worst.locations[j]
    yielding = tuple(a.labels[k] for k, x in enumerate(a.worst.locations) if x.yield_safety is not None
                     and x.yield_safety < 1.0)
    return MethodAnswer(float(a.safety[:, j].min()), loc.required, a.labels[j], a.labels[j], float(a.worst_rpm[j]),
                        bool(a.safety.min() >= loc.required and not yielding), yielding)


FATIGUE_METHODS: dict[str, FatigueMethod] = {
    "iacs-m53": FatigueMethod("iacs-m53", "IACS UR M53 as written", False, assess_m53, answer_m53, safety_m53),
    "fe": FatigueMethod("fe", "fetorsion's own path: Findley on the stress recovered at every fillet and oil bore",
                        True, assess_recovered, answer_recovered),
}
DEFAULT_FATIGUE_METHOD = "iacs-m53"


def fatigue_method(name: str, where: str = "the fatigue method") -> FatigueMethod:
    """The registered method ``name``; a name not registered is refused naming ``where`` it was given."""
    try:
        return FATIGUE_METHODS[name]
    except KeyError:
        raise FetorsionError(f"{where} = {name!r}: must be one of {', '.join(FATIGUE_METHODS)}") from None


def described_method(crank: Crank, option: str | None = None) -> str:
    """The method that decides: ``option`` (the run's), else the description's ``[limits]
    fatigue_method``, else :data:`DEFAULT_FATIGUE_METHOD`; each checked against the registry."""
    if option:
        return fatigue_method(option).name
    given = getattr(getattr(crank, "limits", None), "fatigue_method", "") or ""
    if given:
        return fatigue_method(given, f"{crank.source or crank.name}: limits.fatigue_method").name
    return DEFAULT_FATIGUE_METHOD
