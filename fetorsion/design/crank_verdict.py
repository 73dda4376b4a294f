"""The verdict on a crank: its fatigue, one criterion deciding, in every configuration.

Configurations: without a damper; with the description's ``[[dampers]]`` (when it has any); with
the recommended damper, designed here for this verdict (Den Hartog's start, then its stiffness
and loss optimised on the whole crank to make the deciding method's governing safety as large as
it can be, ring inertia held); and the misfire of the cylinder that makes it worst, without and
with that damper. Each is assessed by both methods:

* ``iacs-m53``: :mod:`fetorsion.design.m53`, the rule as written (the statically determinate
  throw's bending, the vibration calculation's largest alternating torque, the rule's SCFs);
* ``fe``: fetorsion's own path, :func:`fetorsion.design.recovered.run_recovered_assessment` on
  the condensed crank's load cycle (the local stress recovered at every fillet and oil bore from
  six unit end loads, Findley's critical plane with the sign of the mean, the local strength).

One of them decides (``method``); the other is printed beside it with its difference. The
damping is the description's modal damping ratio; the verdict also says at which damping ratio
it would flip, and what the description's (or the default) damping band gives.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np

from ..description.defaults import DEFAULT_INERTIA_RATIO
from ..description.model import Crank
from ..errors import FetorsionError
from .scfset import SCFSet
from .dampers import DamperResult
from .m53 import M53Result, m53_utilisation, run_m53_crank

from .methods import (DEFAULT_FATIGUE_METHOD, FATIGUE_METHODS, ConfigLoads, MethodAnswer, answer_dict,  # noqa: F401
                      fatigue_method, fillet_torque_amplitude)

if TYPE_CHECKING:
    from collections.abc import Callable

    from ..fe.condensed import CondensedCrank
    from ..response.forced import ResponseSetup
    from .stress import Fillet

#: The places within this factor of the governing safety are the ones the damping searches of the
#: ``fe`` path read.
NEAR_GOVERNING = 1.5
#: The damping ratios the flip search brackets.
FLIP_BRACKET = (1e-4, 0.3)
#: The bending damping ratios the ``fe`` path is also given at where the bending's is assumed:
#: the torsional default and five times it, a bracket (not a source) for an undamped-looking
#: crank in rigid bearings against one whose film and block damp its bending well.
BENDING_SENSITIVITY = (0.02, 0.10)


#: The most speeds the damper optimiser evaluates its objective on (every ``k``-th of the setup's).
DAMPER_DESIGN_SPEEDS = 100


def verdict_scfs(crank: Crank, fillet: SCFSet | None = None) -> SCFSet:
    """The SCFs the verdict reads: the fillets' (``fillet``, else
    :func:`fetorsion.design.scf.fillet_scfs`: the shipped table or one throw FE) and the oil
    bores' (:func:`fetorsion.design.oilbore.oil_bore_scfs`)."""
    from .oilbore import oil_bore_scfs
    from .scf import fillet_scfs

    out = fillet or fillet_scfs(crank)
    bores = oil_bore_scfs(crank)
    if not bores:
        return out
    return out.with_oil_bores({k: v for k, v in bores.items() if k != "source"}, bores["source"])


def design_speeds(setup: ResponseSetup) -> ResponseSetup:
    """``setup`` at every k-th speed, at most :data:`DAMPER_DESIGN_SPEEDS` of them: the speeds a
    damper optimiser reads (each of its ~80 trials solves them all)."""
    return setup.at_speeds(slice(None, None, -(-len(setup.rpm) // DAMPER_DESIGN_SPEEDS)))


def run_fatigue_damper(crank: Crank, setup: ResponseSetup, fillets: list[Fillet], scf: SCFSet, kind: str = "rubber",
                       mu: float = DEFAULT_INERTIA_RATIO, optimise: bool = True, at: str = "front",
                       hub_inertia: float = 0.0, undamped: M53Result | None = None):
    """The damper designed for the verdict: Den Hartog's start, then (``optimise``) its stiffness
    and loss optimised to make M53's governing safety over the speeds as large as it can be
    (:func:`fetorsion.design.dampers.run_damper` objective ``fatigue``), on at most
    :data:`DAMPER_DESIGN_SPEEDS` of ``setup``'s speeds. ``undamped``: M53 on the crank without a
    damper in ``setup``, when the caller has it. The run's recommended damper and ``fetorsion
    damper``'s default are this one."""
    from ..response.forced import solve_response
    from .dampers import run_damper

    if undamped is None:
        undamped = run_m53_crank(crank, fillets, fillet_torque_amplitude(setup, solve_response(setup, ()), fillets),
                                 setup.rpm, fe_scf=scf)
    coarse = design_speeds(setup)
    design = run_damper(crank, kind, mu, optimise, "fatigue", at, hub_inertia, setup=coarse, fillets=fillets,
                        utilisation=m53_utilisation(undamped, fillets, coarse))
    required = undamped.governing.required
    return replace(design, limit=1.0 / required,
                               limit_label=f"required: M53 Q {required:.2f}, utilisation 1/{required:.2f} = {1 / required:.3f}")


@dataclass
class VerdictConfig:
    """One configuration: its name, dampers, both methods' results, and the deciding one's answer."""

    name: str
    #: Its dampers (:class:`~fetorsion.description.model.Damper`; read back, :meth:`from_dict`: their names).
    dampers: tuple
    #: Each method's assessment by its name in :data:`FATIGUE_METHODS` (``iacs-m53`` always).
    results: dict[str, object]
    misfire: int | None = None  # 0-based cylinder
    damper_power_w: float = 0.0
    allowed_power_w: float = 0.0
    #: The crank as described (its own dampers, or none): the configurations the verdict is on.
    as_described: bool = False
    #: Per fillet, the vibratory bending against the determinate throw's
    #: (:func:`fetorsion.design.recovered.vibratory_bending`; as-described configurations).
    bending: list = field(default_factory=list)
    #: The two methods term by term (:func:`fetorsion.design.bridge.method_bridge`); {} without the fe path.
    bridge: dict = field(default_factory=dict)
    #: It carries the verdict's recommended damper (firing or in misfire).
    recommended: bool = False
    #: Each method's answer as it was stored (a configuration read back, :meth:`from_dict`, keeps
    #: M53's result and, as described, the ``fe`` path's; the other answers alone); {}: from ``results``.
    answers: dict[str, MethodAnswer] = field(default_factory=dict)

    @property
    def heat_ok(self) -> bool:
        """The dampers' heat within their ratings (True where they are not rated, or none)."""
        return not self.allowed_power_w or self.damper_power_w <= self.allowed_power_w

    def result(self, method: str):
        """The assessment of ``method`` (a name of :data:`FATIGUE_METHODS`), None where it did not run."""
        return self.results.get(method)

    @property
    def m53(self) -> M53Result:
        return self.results["iacs-m53"]

    @property
    def fe(self):
        """The ``fe`` path's :class:`~fetorsion.design.recovered.RecoveredAssessment`, None where it did not run."""
        return self.results.get("fe")

    def answer(self, method: str) -> MethodAnswer | None:
        """``method``'s answer (governing place and speed, safety against the required; None where it
        did not run)."""
        if method in self.answers:
            return self.answers[method]
        r = self.result(method)
        return None if r is None else fatigue_method(method).answer(r)

    def to_dict(self) -> dict:
        return {"name": self.name, "dampers": [getattr(d, "name", d) for d in self.dampers], "as_described": self.as_described,
                "misfire_cylinder": None if self.misfire is None else self.misfire + 1,
                "iacs-m53": {**self.answer("iacs-m53").to_dict(), "result": self.m53.to_dict()},
                "fe": answer_dict(self.answer("fe")), "damper_power_w": self.damper_power_w,
                "damper_allowed_power_w": self.allowed_power_w, "bending": list(self.bending),
                "recommended": self.recommended}

    @classmethod
    def from_dict(cls, d: Mapping[str, object], fe=None, bridge: dict | None = None) -> "VerdictConfig":
        """The configuration back from its :meth:`to_dict`: its dampers by name, M53's result, the
        ``fe`` path's assessment ``fe`` where it was kept (as described), every method's answer as
        stored; ``bridge`` its entry of the verdict's bridge."""
        m53 = d["iacs-m53"]
        answers = {"iacs-m53": MethodAnswer.from_dict(m53), **({"fe": MethodAnswer.from_dict(d["fe"])} if d["fe"] else {})}
        results = {"iacs-m53": M53Result.from_dict(m53["result"]), **({"fe": fe} if fe is not None else {})}
        misfire = None if d["misfire_cylinder"] is None else d["misfire_cylinder"] - 1
        return cls(d["name"], tuple(d["dampers"]), results, misfire, d["damper_power_w"], d["damper_allowed_power_w"],
                   d["as_described"], list(d["bending"]), dict(bridge or {}), d["recommended"], answers)


@dataclass
class CrankVerdict:
    """The crank's verdict: every configuration, the deciding method, the damping and its source,
    the flip damping ratio, the damping band (a sensitivity) and the recommended damper."""

    name: str
    method: str
    configs: list
    damping_ratio: float
    damping_source: str
    damping_assumed: bool
    flip: DampingFlip
    band: list
    damper: DamperResult | None = None  # the recommended damper's design
    scf_m53: dict[str, dict[str, float | bool | str | list | None]] = field(default_factory=dict)
    notes: list = field(default_factory=list)
    #: The ``fe`` path's σ_V on M53's own loads beside M53's, per place
    #: (:func:`fetorsion.design.recovered.same_load`): the recovery against the rule's SCFs.
    same_load: dict[str, dict[str, float]] = field(default_factory=dict)
    #: The bending damping (``ratio``, ``source``, ``assumed``) and, where it is assumed, the
    #: ``sensitivity``: both methods' governing safeties at :data:`BENDING_SENSITIVITY`.
    bending: dict[str, float | str | bool | list] = field(default_factory=dict)

    def bending_flags(self) -> list[tuple[str, dict]]:
        """(configuration, fillet) where the vibratory bending is over the flag's multiple of the
        determinate throw's."""
        return [(c.name, b) for c in self.configs for b in c.bending if b["flag"]]

    @property
    def other(self) -> str:
        """The method shown beside the deciding one (the registry's other)."""
        return [m for m in FATIGUE_METHODS if m != self.method][0]

    @property
    def passes(self) -> bool:
        """The crank as described passes, firing and in misfire: its own dampers (or none) decide,
        their heat within their ratings where they are rated; the other rows (no damper where it
        has one, the recommended damper) inform."""
        return all(getattr(c.answer(self.method), "passes", False) and c.heat_ok for c in self.configs if c.as_described)

    def lines(self) -> list[str]:
        """One verdict line per configuration: method, damping and its source, governing place and
        speed, safety against the required, and how far the other method is."""
        out = []
        for c in self.configs:
            a, b = c.answer(self.method), c.answer(self.other)
            text = (f"{c.name}: {self.method}, ζ = {self.damping_ratio:.4g} ({self.damping_source}), "
                    f"{a.location} ({a.where}, {a.rpm:.0f} rpm): safety {a.safety:.2f} against "
                    f"{a.required:.2f}: {'pass' if a.passes else 'FAIL'}"
                    + ("" if c.heat_ok else f"; the damper heat {c.damper_power_w:.0f} W is over its rating "
                       f"{c.allowed_power_w:.0f} W: FAIL")
                    + (f" (YIELDING at {', '.join(a.yielding)}: above R_e, beyond the linear assessment)"
                       if a.yielding else ""))
            if b:
                text += f"; {self.other} {b.safety:.2f} against {b.required:.2f} ({b.location})"
            out.append(text)
        return out

    def decides(self, method: str) -> str:
        """A phrase for a figure of ``method``'s: that it decides, or which method does and by how
        much this one differs from it (the as-described firing configuration's governing safety)."""
        described = next(c for c in self.configs if c.as_described)
        mine, theirs = described.answer(method), described.answer(self.method)
        if method == self.method:
            return f"{method} decides: safety {mine.safety:.2f} against {mine.required:.2f}"
        gap = 100 * (mine.safety / theirs.safety - 1) if mine and theirs else float("nan")
        return (f"shown beside; {self.method} decides ({theirs.safety:.2f}); this method's least "
                f"{mine.safety if mine else float('nan'):.2f} is {gap:+.0f} % from it")

    def fatigue_figure(self, config: VerdictConfig | None = None):
        """The deciding method's figure beside the other's, for one configuration (default the
        crank as described, firing): M53's Q of every place (:meth:`M53Result.plot`), the ``fe``
        path's safety over speed (:meth:`CrankAssessment.plot`), each titled with whether it
        decides. Returns the Figure."""
        import matplotlib.pyplot as plt

        config = config or next(c for c in self.configs if c.as_described)
        methods = [m for m in (self.method, self.other) if config.result(m) is not None]
        fig, axes = plt.subplots(1, len(methods), figsize=(6.5 * len(methods), 4.6), squeeze=False)
        for ax, m in zip(axes[0], methods):
            config.result(m).plot(ax=ax)
            title = ax.get_title().split("\n")[-1]
            ax.set_title(f"{title}\n{self.decides(m)}", fontsize=8.5, fontweight="bold" if m == self.method else None,
                         wrap=True)
        fig.suptitle(f"{self.name}: fatigue, {config.name}", fontsize=10, wrap=True)
        fig.tight_layout()
        return fig

    def to_dict(self) -> dict:
        """Every figure of the result as plain JSON-ready numbers, lists and strings (SI, or the unit in its key)."""
        return {"name": self.name, "method": self.method, "passes": self.passes,
                "damping_ratio": self.damping_ratio, "damping_source": self.damping_source,
                "damping_assumed": self.damping_assumed, "flip": asdict(self.flip), "band": list(self.band),
                "configurations": [c.to_dict() for c in self.configs], "lines": self.lines(),
                "damper": None if self.damper is None else self.damper.to_dict(), "scf_m53": self.scf_m53,
                "notes": list(self.notes), "same_load": self.same_load, "bending": self.bending,
                "bridge": [{"configuration": c.name, **c.bridge} for c in self.configs if c.bridge]}

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "CrankVerdict":
        """The verdict back from its :meth:`to_dict` and, where the run kept it (its ``fe_detail``),
        the ``fe`` path's assessment of the crank as described, firing (the first configuration as
        described). A configuration written before ``recommended`` was kept is refused by name."""
        from ..results import from_fields
        from .assessment import CrankAssessment
        from .recovered import RecoveredAssessment

        if any("recommended" not in c for c in d["configurations"]):
            raise FetorsionError("the verdict's configurations do not say which carries the recommended damper "
                                 "(written before results.json kept it)")
        fe = d.get("fe_detail") or None
        if fe is not None:
            fe = (RecoveredAssessment if fe.get("criterion") == "findley" else CrankAssessment).from_dict(fe)
        bridges = {b["configuration"]: {k: v for k, v in b.items() if k != "configuration"} for b in d["bridge"]}
        described = next(k for k, c in enumerate(d["configurations"]) if c["as_described"])
        configs = [VerdictConfig.from_dict(c, fe if k == described else None, bridges.get(c["name"]))
                   for k, c in enumerate(d["configurations"])]
        return from_fields(cls, d, configs=configs, flip=DampingFlip(d["flip"]["zeta"], d["flip"]["kind"]),
                           band=list(d["band"]), damper=None if d["damper"] is None else DamperResult.from_dict(d["damper"]),
                           scf_m53=dict(d["scf_m53"]), same_load=dict(d["same_load"]), bending=dict(d["bending"]),
                           notes=list(d["notes"]))


@dataclass(frozen=True)
class DampingFlip:
    """The damping ratio ``zeta`` at which the verdict flips (None when it does not inside
    :data:`FLIP_BRACKET`) and what that means (``kind``, a phrase)."""

    zeta: float | None
    kind: str


#: The flip search stops when its next step in ln ζ, or its bracket, is below this: ζ to 0.1 %.
FLIP_TOLERANCE = 1e-3


def _flip(safety_at, required: float, known: dict | None = None) -> DampingFlip:
    """The damping ratio at which ``safety_at(ζ)`` meets ``required`` (safety grows with damping).

    ``known``: {ζ: safety} already computed (the damping band's). In ln safety against ln ζ the
    curve is nearly straight (near a resonance the safety goes as ζ, away from it more slowly):
    the root is bracketed from the known points by steps along their secant, each a quarter
    longer than the secant says and at least a factor 2 in ζ, clamped to :data:`FLIP_BRACKET`;
    then regula falsi (Illinois) in that bracket until :data:`FLIP_TOLERANCE`. Two to five
    evaluations where a bisecting search from the bracket's ends took a dozen."""
    lo, hi = math.log(FLIP_BRACKET[0]), math.log(FLIP_BRACKET[1])
    seen = {math.log(z): s for z, s in (known or {}).items() if FLIP_BRACKET[0] <= z <= FLIP_BRACKET[1]}

    def g(u):  # ln(safety / required) at ζ = e^u; a safety of 0 (statically over) reads as far below
        if u not in seen:
            seen[u] = safety_at(math.exp(u))
        return math.log(max(seen[u], 1e-300) / required)

    if not seen:
        g(math.log(0.02))
    while True:
        us = sorted(seen)
        signs = [g(u) >= 0 for u in us]
        pair = next((k for k in range(len(us) - 1) if signs[k] != signs[k + 1]), None)
        if pair is not None:
            a, b = us[pair], us[pair + 1]
            break
        down = signs[0]  # passes everywhere seen: the root is below; fails everywhere: above
        end = us[0] if down else us[-1]
        if end == (lo if down else hi):
            return DampingFlip(None, f"passes down to ζ = {FLIP_BRACKET[0]:g} (the search's end)" if down
                               else f"fails up to ζ = {FLIP_BRACKET[1]:g} (the search's end)")
        step = -math.log(2.0) if down else math.log(2.0)
        if len(us) > 1:
            u0, u1 = (us[0], us[1]) if down else (us[-2], us[-1])
            slope = (g(u1) - g(u0)) / (u1 - u0)
            if slope > 0:
                guess = -1.25 * g(end) / slope
                step = min(guess, step) if down else max(guess, step)
        g(min(max(end + step, lo), hi))
    fa, fb = g(a), g(b)
    c = b
    while abs(b - a) > FLIP_TOLERANCE:
        slope = (fb - fa) / (b - a)
        c = b - fb / slope
        fc = g(c)
        if abs(fc / slope) < FLIP_TOLERANCE:  # the secant's next step would move ζ by under the tolerance
            break
        if (fc > 0) != (fb > 0):
            a, fa = b, fb
        else:
            fa *= 0.5  # Illinois: the end that stays is halved, so the bracket closes from both sides
        b, fb = c, fc
    z = math.exp(c)
    return DampingFlip(z, f"passes down to ζ = {z:.4g}")


def run_crank_verdict(crank: Crank, cc: CondensedCrank, setup: ResponseSetup, fillets: list[Fillet], scf: SCFSet,
                      method: str = DEFAULT_FATIGUE_METHOD, mu: float = DEFAULT_INERTIA_RATIO, kind: str = "rubber",
                      misfire: bool = True, fe_path: bool = True,
                      progress: Callable[[str], None] | None = None) -> CrankVerdict:
    """The crank's fatigue verdict in every configuration (module docstring).

    Parameters
    ----------
    crank : Crank
        With ``[excitation]`` and fillet radii.
    cc : CondensedCrank
        The condensed crank in its bearings, with fillet cuts (the ``fe`` path's load cycle).
    setup : ResponseSetup
        Its response setup in its bearings (:func:`fetorsion.response.coupled.condensed_setup`) at
        the description's damping ratio.
    fillets : list of Fillet
        The crank's fillets and oil bores, in the order of ``cc``'s cuts
        (:func:`fetorsion.design.stress.fillets_of`).
    scf : dict
        FE SCFs (:func:`fetorsion.design.scf.fillet_scfs`, with the oil bores').
    method : {"iacs-m53", "fe"}
        The one that decides.
    mu, kind : float, str
        Ring inertia ratio and type of the recommended damper.
    misfire : bool
        Add the misfire configurations.
    fe_path : bool
        Assess the ``fe`` path too (its load cycles cost about a second a configuration).
    progress : callable, optional
        Called with a line of text as each configuration starts (the run's progress lines).

    Examples
    --------
    The run's own verdict step builds every argument; ``fetorsion run`` (:func:`fetorsion.run`)
    is the way to it for a description, and a second run finds the FE parts stored:

    >>> import fetorsion
    >>> outcome = fetorsion.run("geometry/renault21.toml", "out/renault21")  # doctest: +SKIP
    >>> v = outcome.fatigue.verdict  # doctest: +SKIP
    >>> v.method, v.passes  # doctest: +SKIP
    """
    from ..response.coupled import bending_damping
    from .m53 import m53_geometry, split_pin_refusal
    from .m53_scfs import scf_comparison
    from .recovered import same_load

    if split_pin_refusal(crank):  # neither M53 nor the fe path's one-axis pin cuts model a split pin
        raise FetorsionError(split_pin_refusal(crank))

    fatigue_method(method, "the fatigue method")
    say = progress or (lambda m: None)
    ex = crank.excitation
    inputs = _verdict_inputs(crank, cc, setup, fillets, scf, fe_path, say)
    configs, design, notes = _configurations(inputs, setup, method, mu, kind, misfire, say)
    # the damping: the description's ratio decides; the flip ratio and the band are sensitivities
    required = configs[0].answer(method).required
    own = configs[1 if crank.dampers else 0]  # the crank as described, firing
    near = _near_governing(inputs, own)
    band, flip = _damping_band_and_flip(inputs, setup, method, required, near, say)
    bending = bending_damping(crank)
    if fe_path and bending["assumed"]:
        say("fatigue verdict: the fe path at two bending damping ratios ...")
        bending["sensitivity"] = [_at_bending_damping(inputs, setup, own, near, zb, bending["ratio"])
                                  for zb in BENDING_SENSITIVITY]
    given = ex.modal_damping_ratio_source if hasattr(ex, "modal_damping_ratio_source") else ""
    assumed = not given
    source = given or "assumed: the description states no source"
    comparison = scf_comparison(m53_geometry(crank), scf)
    return CrankVerdict(crank.name, method, configs, ex.modal_damping_ratio, source, assumed, flip, band, design,
                        comparison, notes,
                        same_load(crank, own.m53, inputs.zones, fe_factors={k: row["fe"] for k, row in comparison.items()})
                        if fe_path else {}, bending)


@dataclass(frozen=True)
class _VerdictInputs:
    """What every configuration of one verdict reads: the crank, its condensed model, fillets and SCFs,
    the methods that run, and the ``fe`` path's mean cut loads, zones and places (None without it)."""

    crank: Crank
    cc: object  # the CondensedCrank (fetorsion.fe.condensed), not imported for its name alone
    fillets: list
    scf: SCFSet
    methods: list
    fe_path: bool
    mean: np.ndarray | None = None
    zones: dict | None = None
    locations: list | None = None


def _verdict_inputs(crank, cc, setup, fillets, scf: SCFSet, fe_path: bool, say) -> _VerdictInputs:
    """The verdict's shared inputs; the ``fe`` path's places recovered where it runs."""
    from ..response.cycle import mean_cut_loads
    from .recovery import crank_locations, crank_zones

    mean = mean_cut_loads(cc, setup.rpm) if fe_path else None
    zones = crank_zones(crank, progress=say) if fe_path else None
    locations = crank_locations(crank, fillets, cc.cut_centres, zones=zones) if fe_path else None
    methods = [m for m in FATIGUE_METHODS.values() if fe_path or not m.needs_recovery]
    return _VerdictInputs(crank, cc, fillets, scf, methods, fe_path, mean, zones, locations)


def _loads(inputs: _VerdictInputs, s, dampers, places=None, check: bool = True) -> ConfigLoads:
    """The loads of setup ``s`` with ``dampers`` at ``places`` (default every place of the verdict)."""
    return ConfigLoads(inputs.crank, inputs.cc, s, tuple(dampers), inputs.fillets, inputs.scf,
                       inputs.locations if places is None else places, inputs.mean, check)


def _safety(inputs: _VerdictInputs, name: str, s, dampers, places=None) -> float:
    """The governing safety of method ``name`` alone (the damping searches)."""
    return FATIGUE_METHODS[name].governing_safety(_loads(inputs, s, dampers, places, check=False))


def _config(inputs: _VerdictInputs, name: str, s, dampers, cylinder: int | None = None) -> VerdictConfig:
    """One configuration assessed by every method, with its vibratory bending (as described), the
    methods' bridge and its dampers' heat."""
    from .bridge import method_bridge
    from .recovered import vibratory_bending
    from .verdict import allowed_power

    crank = inputs.crank
    loads = _loads(inputs, s, dampers)
    results = {m.name: m.assess(loads) for m in inputs.methods}
    described = tuple(dampers) == tuple(crank.dampers)
    c = VerdictConfig(name, tuple(dampers), results, cylinder, as_described=described)
    if inputs.fe_path and described:  # the rule's bending against the crank's own, where the verdict is
        c.bending = vibratory_bending(crank, loads.cycle, inputs.fillets, inputs.cc.cut_centres, c.m53.rated_rpm)
    loads.release()
    if inputs.fe_path:
        c.bridge = method_bridge(crank, c.fe, c.m53, inputs.locations, inputs.fillets, inputs.zones)
    if dampers:  # one solve: M53's torques and the dampers' heat
        p = loads.response.damper_power_w.sum(axis=(1, 2))
        c.damper_power_w, c.allowed_power_w = float(p.max()), allowed_power(dampers)
    return c


def _configurations(inputs: _VerdictInputs, setup, method: str, mu: float, kind: str, misfire: bool,
                    say) -> tuple[list[VerdictConfig], DamperResult, list[str]]:
    """(configurations, the recommended damper's design, notes): without a damper, with the
    description's, with the recommended one, and the worst misfire of each."""
    crank = inputs.crank
    rows = [("without a damper", ())] + ([("with the description's damper(s)", crank.dampers)] if crank.dampers else [])
    say("fatigue verdict: without a damper ...")
    configs = [_config(inputs, name, setup, dampers) for name, dampers in rows]
    # the recommended damper: designed for M53's governing safety (its bending does not move with
    # the damper, so the torques decide), on at most 100 speeds, then checked on all
    say("fatigue verdict: designing the recommended damper for it ...")
    design = run_fatigue_damper(crank, setup, inputs.fillets, inputs.scf, kind, mu, undamped=configs[0].m53)
    best = design.optimised
    rows.append((f"with the recommended {kind} damper", (best,)))
    configs.append(_config(inputs, rows[-1][0], setup, (best,)))
    notes = []
    if method != "iacs-m53":
        # the fe path's safety needs a load cycle per trial damper (about a second each): the
        # optimiser's objective stays M53's, whose torsional part is what a damper moves
        notes.append(f"the recommended damper is designed for M53's governing safety and the worst misfire "
                     f"cylinder chosen by M53; the deciding {method} method checks both")
    if misfire and crank.excitation.pressure_curve is None:
        say("fatigue verdict: misfire of each cylinder ...")
        configs += _misfire_configs(inputs, setup, rows)
        notes.append("misfire: the cylinder's pressure is the motored cycle; the worst cylinder by M53 is shown; "
                     "M53's bending keeps the firing rod forces (the larger)")
    elif misfire:
        notes.append("misfire not computed: the motored pressure of a measured pressure_csv is not known")
    for c in configs:
        c.recommended = best in c.dampers
    return configs, design, notes


def _misfire_configs(inputs: _VerdictInputs, setup, rows) -> list[VerdictConfig]:
    """For each (name, dampers) of ``rows``, the misfire of the cylinder that M53 finds worst."""
    from ..response.forced import misfire_harmonics

    motored = misfire_harmonics(inputs.crank, setup)
    # one setup per cylinder: its undamped response is solved once and serves every damper row
    # (a damper's response is that one and the shared unit responses, with_dampers)
    misfired = setup.with_misfires(motored)
    out = []
    for name, dampers in rows:
        # the worst cylinder by M53 (its governing safety alone), then its configuration in full
        worst_c = int(np.argmin([_safety(inputs, "iacs-m53", ms, dampers) for ms in misfired]))
        out.append(_config(inputs, f"misfire of cylinder {worst_c + 1}, {name}", misfired[worst_c], dampers, worst_c))
    return out


def _near_governing(inputs: _VerdictInputs, own: VerdictConfig) -> list | None:
    """The places whose ``fe`` safety comes within :data:`NEAR_GOVERNING` of the governing one in
    ``own`` (None without the ``fe`` path: every place)."""
    if not inputs.fe_path:
        return None
    # the damping searches read the places within 1.5x of the governing one (the others cannot
    # govern across the band): a load cycle each, not 25 places' Findley sweeps
    least = own.fe.safety.min(axis=0)
    return [loc for loc, q in zip(inputs.locations, least) if q <= NEAR_GOVERNING * least.min()]


def _damping_band_and_flip(inputs: _VerdictInputs, setup, method: str, required: float, near,
                           say) -> tuple[list[dict], DampingFlip]:
    """The deciding method's governing safety over the description's damping band, and the damping
    ratio at which the verdict flips (the crank as described, firing)."""
    from ..response.coupled import with_damping_ratio

    def safety_at(zeta):
        return _safety(inputs, method, with_damping_ratio(setup, inputs.cc, "bearings", zeta), inputs.crank.dampers, near)

    say("fatigue verdict: the damping band and the damping ratio at which it flips ...")
    band = [{"damping_ratio": z, "safety": safety_at(z)} for z in sorted(set(inputs.crank.excitation.damping_band))]
    flip = _flip(safety_at, required, {b["damping_ratio"]: b["safety"] for b in band})
    return band, flip


def _at_bending_damping(inputs: _VerdictInputs, setup, own: VerdictConfig, near, zb: float, own_ratio: float) -> dict:
    """Every method's governing safety at bending damping ratio ``zb`` (the crank as described,
    firing); at its own ratio ``own_ratio``, its configuration's."""
    from ..response.coupled import with_damping_ratio

    if zb == own_ratio:  # the crank as described: its configuration has them
        return {"bending_damping_ratio": zb, **{m.name: own.answer(m.name).safety for m in inputs.methods}}
    s = with_damping_ratio(setup, inputs.cc, "bearings", inputs.crank.excitation.modal_damping_ratio, zb)
    return {"bending_damping_ratio": zb, **{m.name: _safety(inputs, m.name, s, inputs.crank.dampers, near) for m in inputs.methods}}
