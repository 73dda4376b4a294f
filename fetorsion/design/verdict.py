"""The design verdict: the worst vibratory stress (or torque) over the speed range against
the description's ``[limits]``, without a damper, with Den Hartog's damper and with the optimised
one, the barred speed ranges and the misfire case.

A speed is barred where the worst fillet stress (a chain file: the worst section torque)
exceeds the continuous-running limit; a barred range may be passed through only if its peak
stays under the passing-through (transient) limit. Range edges are where the linearly
interpolated curve crosses the limit. The margin is 1 − value / limit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..description.defaults import DEFAULT_INERTIA_RATIO
from ..description.model import Crank, Damper, Limits
from ..description.chain_model import Chain
from ..errors import FetorsionError
from .scfset import SCFSet

if TYPE_CHECKING:
    from collections.abc import Sequence
    from ..response.forced import ResponseSetup
    from .stress import Fillet


def _number(x):
    """``x``, a NaN as None (JSON has no NaN; read back as a float field, None is NaN again)."""
    return None if isinstance(x, float) and math.isnan(x) else x


def barred_ranges(rpm, value, limit: float) -> list[dict]:
    """Speed ranges where ``value`` (sampled at ``rpm``) exceeds ``limit``: ``from_rpm``, ``to_rpm``
    (linear crossings of the limit, or the sampled ends), ``peak`` and ``peak_rpm``."""
    rpm, value = np.asarray(rpm, dtype=float), np.asarray(value, dtype=float)
    over = value > limit
    out = []
    edges = np.flatnonzero(np.diff(np.r_[False, over, False].astype(int)))
    for a, b in zip(edges[::2], edges[1::2]):  # samples a .. b-1 exceed
        def cross(i, j):  # where the line from sample i to j meets the limit
            return rpm[i] + (limit - value[i]) * (rpm[j] - rpm[i]) / (value[j] - value[i])
        lo = cross(a - 1, a) if a > 0 else rpm[0]
        hi = cross(b - 1, b) if b < len(rpm) else rpm[-1]
        k = a + int(np.argmax(value[a:b]))
        out.append({"from_rpm": float(lo), "to_rpm": float(hi), "peak": float(value[k]), "peak_rpm": float(rpm[k])})
    return out


@dataclass
class VerdictCase:
    """One configuration checked against the limits."""

    name: str
    rpm: np.ndarray
    value: np.ndarray  # worst over sections, against speed (Pa or N·m)
    where: list  # the worst section's label at each speed
    damper_power_w: float = 0.0
    damper_power_by_order_w: dict = field(default_factory=dict)
    #: The dampers' allowed continuous dissipation (their makers' ratings), W; 0: not given.
    allowed_power_w: float = 0.0
    #: Each damper's rubber temperature in this case, °C (NaN: none stated; a heat-following
    #: damper's as its own heat holds it).
    damper_temperatures_c: tuple = ()

    def worst(self) -> int:
        return int(np.argmax(self.value))


@dataclass
class VerdictResult:
    """Cases (no damper, Den Hartog, optimised, misfire ...) against one set of limits."""

    name: str
    limits: Limits
    cases: list
    notes: list = field(default_factory=list)
    #: The damper designed for each case that has one (case name → Damper).
    designs: dict[str, Damper] = field(default_factory=dict)

    @property
    def unit(self) -> tuple[str, float]:
        return ("MPa", 1e6) if self.limits.kind == "stress" else ("N m", 1.0)

    def rows(self) -> list[dict]:
        """One row per case: speed range, worst section, value, limit, margin, barred ranges, verdict."""
        out = []
        for c in self.cases:
            i = c.worst()
            bars = barred_ranges(c.rpm, c.value, self.limits.continuous)
            for b in bars:  # a range at an end of the speed range is where the engine runs, not one it passes
                b["passable"] = bool(self.limits.transient and b["peak"] <= self.limits.transient
                                     and b["from_rpm"] > c.rpm[0] and b["to_rpm"] < c.rpm[-1])
            verdict = "pass" if not bars else ("pass with barred ranges" if all(b["passable"] for b in bars) else "fail")
            heat = ("not rated" if not c.allowed_power_w else
                    "within the rating" if c.damper_power_w <= c.allowed_power_w else "over the rating")
            if heat == "over the rating":
                verdict = "fail (damper heat)"
            out.append({"case": c.name, "speed_range_rpm": [float(c.rpm[0]), float(c.rpm[-1])],
                        "worst_section": c.where[i], "worst_rpm": float(c.rpm[i]), "value": float(c.value[i]),
                        "limit": self.limits.continuous, "margin": 1.0 - float(c.value[i]) / self.limits.continuous,
                        "barred_ranges": bars, "transient_limit": self.limits.transient, "verdict": verdict,
                        "damper_power_w": c.damper_power_w, "damper_power_by_order_w": c.damper_power_by_order_w,
                        "damper_allowed_power_w": c.allowed_power_w, "damper_heat": heat if c.damper_power_w else "-",
                        "damper_temperatures_c": [float(t) for t in c.damper_temperatures_c if t == t]})
        return out

    def to_dict(self) -> dict:
        """Every figure of the result as plain JSON-ready numbers, lists and strings (SI, or the unit in its key)."""
        import dataclasses

        unit = "pa" if self.limits.kind == "stress" else "nm"
        return {"name": self.name, "limit_kind": self.limits.kind, "unit": unit,
                "continuous_limit": self.limits.continuous, "transient_limit": self.limits.transient,
                "limits_source": self.limits.source, "rows": self.rows(), "notes": self.notes,
                "curves": {c.name: {"rpm": c.rpm.tolist(), "value": c.value.tolist(), "where": list(c.where),
                                    "damper_power_w": c.damper_power_w,
                                    "damper_power_by_order_w": dict(c.damper_power_by_order_w),
                                    "allowed_power_w": c.allowed_power_w,
                                    "damper_temperatures_c": [_number(t) for t in c.damper_temperatures_c]}
                           for c in self.cases},
                "limits": dataclasses.asdict(self.limits),
                "designs": {k: {f: _number(v) for f, v in dataclasses.asdict(d).items()}
                            for k, d in self.designs.items()}}

    @classmethod
    def from_dict(cls, d) -> "VerdictResult":
        """The result back from its :meth:`to_dict` (its cases from ``curves``, in order)."""
        from ..results import from_fields

        cases = [from_fields(VerdictCase, c, name=name, damper_temperatures_c=tuple(
            math.nan if t is None else t for t in c["damper_temperatures_c"])) for name, c in d["curves"].items()]
        return from_fields(cls, d, cases=cases, limits=from_fields(Limits, d["limits"]),
                           designs={k: from_fields(Damper, v) for k, v in d["designs"].items()})

    def table(self) -> str:
        """The result as plain text: the table the command line prints."""
        u, s = self.unit
        what = "fillet shear stress" if self.limits.kind == "stress" else "section torque"
        lines = [f"{self.name}: verdict on the vibratory {what} (amplitude) against the continuous limit "
                 f"{self.limits.continuous / s:.4g} {u}"
                 + (f", passing-through limit {self.limits.transient / s:.4g} {u}" if self.limits.transient else "")
                 + f" (source: {self.limits.source})"]
        for r in self.rows():
            bars = ", ".join(f"{b['from_rpm']:.0f}-{b['to_rpm']:.0f} rpm (peak {b['peak'] / s:.4g})"
                             for b in r["barred_ranges"]) or "none"
            lines.append(f"  {r['case']}: worst {r['value'] / s:.4g} {u} at {r['worst_rpm']:.0f} rpm in "
                         f"{r['worst_section']}, margin {100 * r['margin']:+.1f} %, barred: {bars}; {r['verdict']}"
                         + (f"; damper heat up to {r['damper_power_w']:.1f} W" if r["damper_power_w"] else "")
                         + "".join(f", rubber at {t:.0f} °C" for t in r["damper_temperatures_c"]))
        return "\n".join(lines + [f"  note: {n}" for n in self.notes])

    def plot(self, ax=None):
        """Each case's worst value against speed with the limits. Returns the Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(9, 5))
        u, s = self.unit
        for c in self.cases:
            ax.plot(c.rpm, c.value / s, label=c.name)
        ax.axhline(self.limits.continuous / s, color="crimson", ls="--", label="continuous limit")
        if self.limits.transient:
            ax.axhline(self.limits.transient / s, color="crimson", ls=":", label="passing-through limit")
        ax.set_xlabel("engine speed [rpm]")
        ax.set_ylabel(("worst fillet shear stress" if self.limits.kind == "stress" else "worst section torque") + f" [{u}]")
        ax.set_title(f"{self.name}: verdict", fontsize=10, wrap=True)
        ax.legend(fontsize=7)
        return ax


def worst_case(name: str, crank, response, scf, limits: Limits, fillets) -> VerdictCase:
    """The worst value over sections against speed for one response."""
    if limits.kind == "stress":
        from .stress import fillet_stress

        st = fillet_stress(crank, response, scf, fillets)
        j = np.argmax(st.stress_pa, axis=1)
        value, where = st.stress_pa.max(axis=1), [st.fillets[k].label for k in j]
    else:
        j = np.argmax(response.section_torque_nm, axis=1)
        value = response.section_torque_nm.max(axis=1)
        where = [f"section {response.section_labels[k]}" for k in j]
    power, by_order = 0.0, {}
    if response.damper_names:
        total = response.damper_power_w.sum(axis=(1, 2))  # (speeds,)
        s = int(np.argmax(total))
        power = float(total[s])
        by_order = {f"{q:g}": float(p) for q, p in zip(response.orders, response.damper_power_w[s].sum(axis=0))}
    return VerdictCase(name, response.rpm, value, where, power, by_order,
                       damper_temperatures_c=tuple(response.damper_temperatures_c))


def allowed_power(dampers) -> float:
    """The dampers' allowed dissipation together, W, when every one is rated; else 0 (unrated)."""
    allowed = [d.allowed_power for d in dampers]
    return float(sum(allowed)) if allowed and all(a > 0 for a in allowed) else 0.0


def rated(case: VerdictCase, dampers) -> VerdictCase:
    """``case`` with its dampers' allowed dissipation (:func:`allowed_power`)."""
    from dataclasses import replace

    return replace(case, allowed_power_w=allowed_power(dampers))


def run_verdict(crank: Crank | Chain, mu: float = DEFAULT_INERTIA_RATIO, kind: str = "rubber", optimise: bool = True,
                misfire: bool = True, scf: SCFSet | None = None, rpm: Sequence[float] | np.ndarray | None = None,
                setup: ResponseSetup | None = None, fillets: list[Fillet] | None = None) -> VerdictResult:
    """The verdict table of a crank (or chain file) with ``[limits]``.

    Cases: without damper; with the description's ``[[dampers]]`` if it has any; with Den
    Hartog's ``kind`` damper of inertia ratio ``mu`` on the first mode at the pulley; with that
    damper optimised on the whole crank (:func:`fetorsion.design.dampers.run_damper`,
    objective: the limited quantity); and the misfire of the cylinder that makes it worst, with
    the best of those dampers.

    ``setup`` and ``fillets`` are built here unless the caller has them; every case, the damper
    tuning and the misfires are derived from them.

    Parameters
    ----------
    crank : Crank or Chain
        With ``[excitation]`` and ``[limits]``.
    mu : float
        Ring inertia of the designed damper over the equivalent inertia of the first mode at the
        pulley (-).
    kind : str
        Type of the designed damper: ``viscous``, ``rubber`` or ``tuned``.
    optimise : bool
        Add the case of that damper optimised on the whole crank.
    misfire : bool
        Add the misfire case.
    scf : SCFSet, optional
        Fillet SCFs (``pin``, ``journal``, ``source``); default
        :func:`fetorsion.design.scf.fillet_scfs`.
    rpm : array_like, optional
        Speeds, rpm; default the response's (the speed range to overspeed).
    setup : ResponseSetup, optional
        The crank's :func:`~fetorsion.response.forced.response_setup` (then ``rpm`` is its own).
    fillets : list of Fillet, optional
        :func:`fetorsion.design.stress.fillets_of` the crank.

    Returns
    -------
    VerdictResult
        One row per case: worst stress (Pa) or section torque (N·m) against the limit, barred
        speed ranges (rpm), damper heat (W).

    Examples
    --------
    >>> from dataclasses import replace
    >>> import fetorsion
    >>> from fetorsion.description.model import Limits
    >>> chain = fetorsion.load("examples/mendes2008/mwm6_chain.toml")  # its file states no [limits]: give some
    >>> chain = replace(chain, limits=Limits(continuous_torque=3000.0, transient_torque=6000.0, source="example"))
    >>> v = fetorsion.run_verdict(chain, optimise=False)
    >>> [r["case"] for r in v.rows()][:2]
    ['without damper', 'Den Hartog rubber damper (mu = 0.25)']
    """
    from ..excitation.torque import MOTORED_COLUMN_MISSING, has_motored_column
    from ..response.forced import misfire_harmonics, response_setup, solve_response
    from .dampers import run_damper

    limits = crank.limits
    if limits is None:
        raise FetorsionError(f"{crank.source or crank.name}: the description has no [limits] table")
    if limits.kind == "stress" and scf is None:
        from .scf import fillet_scfs

        scf = fillet_scfs(crank)
    setup = response_setup(crank, rpm=rpm) if setup is None else setup
    if limits.kind == "stress" and fillets is None:
        from .stress import fillets_of

        fillets = fillets_of(crank)
    # The damper is tuned on every k-th speed, at most 100 (the optimiser's many responses),
    # then checked on all.
    coarse = setup.at_speeds(slice(None, None, -(-len(setup.rpm) // 100)))
    cases = [worst_case("without damper", crank, solve_response(setup, ()), scf, limits, fillets)]
    if crank.dampers:
        cases.append(rated(worst_case("with the description's damper(s)", crank, solve_response(setup, crank.dampers), scf,
                                      limits, fillets), crank.dampers))
    objective = "stress" if limits.kind == "stress" else "twist"
    tuned = run_damper(crank, kind, mu, optimise, objective, scf=scf, setup=coarse, fillets=fillets)
    options = [("Den Hartog " + kind + f" damper (mu = {mu:g})", tuned.den_hartog)]
    if tuned.optimised is not None:
        options.append((f"optimised {kind} damper (mu = {mu:g})", tuned.optimised))
    for name, d in options:
        cases.append(worst_case(name, crank, solve_response(setup, (d,)), scf, limits, fillets))
    notes = [f"Den Hartog start on mode 1 ({tuned.mode_hz:.1f} Hz) seen from the pulley: J_eq = "
             f"{tuned.equivalent_inertia_kgm2:.4g} kg m^2, ring {tuned.den_hartog.ring_inertia:.4g} kg m^2"]
    if misfire and crank.excitation.pressure_curve is not None:
        notes.append("misfire not computed: the motored pressure of a measured pressure_csv is not known")
    elif misfire and crank.excitation.tangential_harmonics and not has_motored_column(crank.excitation):
        notes.append(MOTORED_COLUMN_MISSING)
    elif misfire:
        best_name, best = min(options, key=lambda o: cases[[c.name for c in cases].index(o[0])].value.max())
        worst = {"without damper": None, best_name: None}
        motored = misfire_harmonics(crank, setup)
        for c in range(crank.engine.cylinders):
            ms = setup.with_misfire(c, motored)
            for name, dampers in (("without damper", ()), (best_name, (best,))):
                case = worst_case(f"misfire of cylinder {c + 1}, {name}", crank, solve_response(ms, dampers), scf, limits,
                             fillets)
                if worst[name] is None or case.value.max() > worst[name].value.max():
                    worst[name] = case
        cases += list(worst.values())
        notes.append("misfire: the cylinder's pressure is the motored cycle (compression and expansion only); "
                     "the worst cylinder is shown")
    return VerdictResult(crank.name, limits, cases, notes, dict(options))
