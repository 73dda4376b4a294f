"""The shaft sections of a propulsion line against IACS UR M68 over the speed range: each
section's synthesised vibratory stress against τ_C(λ) and τ_T(λ) (:mod:`.shaft_limits`), and the
barred speed ranges where τ_C is exceeded (docs/propulsion-tvc.md).

A shaft of a network file with a section (``[[chain.shafts]]`` with ``diameter_m`` …) carries the
elastic torque the forced response synthesises over all orders; its half-range amplitude T gives
the nominal stress τ = 16 T d / (π (d⁴ − d_i⁴)) on the plain section (the stress raisers are in
C_K). The speed ratio λ = n / n_rated is the same on every shaft of a geared line (the gears keep
their ratios), so it is read from station 1's speed against the rated speed referred to it.

A speed is barred where some section's τ exceeds its τ_C; the ranges of all sections are merged
into one list of intervals, each with its worst section and peak, whether every section stays at
or under its τ_T across the interval (the limit for passing through), and, for a propeller line,
whether it reaches above λ = 0.8, where the rule allows no barred range. Above λ = 1.05 the rule
gives no limit: those speeds are shown but not judged.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from ..description.chain_model import Network
from ..description.marine import ShaftSection
from ..errors import ParameterError
from ..lumped_model.network import resolved, speed_factors
from ..response.forced import ResponseResult
from ..results import from_fields
from .shaft_limits import LAMBDA_MAX, LAMBDA_TRANSIENT_MAX, capped_strength, continuous_limit, size_factor
from .shaft_limits import transient_limit
from .verdict import barred_ranges


@dataclass
class SectionStress:
    """One shaft section over the speed range: its half-range stress and the rule's limits, Pa
    (``tau_c_pa`` NaN above λ = 1.05, ``tau_t_pa`` NaN above λ = 0.8), and its own barred ranges
    ({from_rpm, to_rpm, peak_pa, peak_rpm})."""

    label: str
    section: ShaftSection
    stress_pa: np.ndarray
    tau_c_pa: np.ndarray
    tau_t_pa: np.ndarray
    barred: list[dict[str, float | str | bool]] = field(default_factory=list)

    @property
    def utilisation(self) -> np.ndarray:
        """τ / τ_C at each speed (NaN where the rule gives no τ_C)."""
        return self.stress_pa / self.tau_c_pa

    def to_dict(self) -> dict:
        """JSON-ready: the section (m, Pa), its stress and limits over the speeds (Pa, None where no limit)."""
        return {"label": self.label, "feature": self.section.feature, "ck": self.section.ck,
                "diameter_m": self.section.diameter, "bore_m": self.section.bore,
                "tensile_strength_pa": self.section.tensile_strength, "material": self.section.material,
                "stress_pa": self.stress_pa.tolist(), "tau_c_pa": json_nulls(self.tau_c_pa),
                "tau_t_pa": json_nulls(self.tau_t_pa), "barred_ranges": self.barred}

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "SectionStress":
        """The section back from its :meth:`to_dict` (one written before the material was kept: carbon steel,
        which only the limits already stored depended on)."""
        section = from_fields(ShaftSection, d, {"diameter": "diameter_m", "bore": "bore_m",
                                                "tensile_strength": "tensile_strength_pa"})
        return from_fields(cls, d, {"barred": "barred_ranges"}, section=section)


@dataclass
class ShaftVerdict:
    """Every judged shaft section of a network over the speed range, and the merged barred ranges.

    ``rpm`` are station 1's speeds, ``rated_rpm`` the rated (maximum continuous) speed referred to
    station 1, ``speed_ratio`` λ at each speed; ``barred`` the merged ranges: ``from_rpm``,
    ``to_rpm``, ``section`` (the worst), ``peak_pa``, ``peak_rpm``, ``peak_utilisation`` (τ/τ_C),
    ``within_transient`` (τ ≤ τ_T of every section across it), ``above_0_8`` (λ > 0.8 somewhere in
    it: not allowed for a propeller line).
    """

    name: str
    rpm: np.ndarray
    rated_rpm: float
    sections: list[SectionStress]
    barred: list[dict[str, float | str | bool]]
    propeller_line: bool = True
    notes: list[str] = field(default_factory=list)
    #: A constant-speed set (``[chain] constant_speed``): it runs continuously across its whole range, so
    #: any barred range fails.
    constant_speed: bool = False

    @property
    def speed_ratio(self) -> np.ndarray:
        return self.rpm / self.rated_rpm

    @property
    def verdict(self) -> str:
        """pass; pass with barred ranges (each passable); or fail (one is not, or a constant-speed set has one
        in its band, at or below its rated speed: above it lies only the overspeed a governor passes through)."""
        if not self.barred:
            return "pass"
        in_band = self.constant_speed and any(b["from_rpm"] <= self.rated_rpm for b in self.barred)
        ok = not in_band and all(b["within_transient"] and not (self.propeller_line and b["above_0_8"])
                                 for b in self.barred)
        return "pass with barred ranges" if ok else "fail"

    def to_dict(self) -> dict:
        """JSON-ready: speeds (rpm), λ, each section's stress and limits (Pa), the barred ranges."""
        return {"name": self.name, "rpm": self.rpm.tolist(), "rated_rpm": self.rated_rpm,
                "speed_ratio": self.speed_ratio.tolist(), "verdict": self.verdict, "barred_ranges": self.barred,
                "propeller_line": self.propeller_line, "constant_speed": self.constant_speed, "notes": self.notes,
                "sections": [s.to_dict() for s in self.sections]}

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "ShaftVerdict":
        """The verdict back from its :meth:`to_dict`."""
        return from_fields(cls, d, {"barred": "barred_ranges"})

    def table(self) -> str:
        """Each section's worst stress against τ_C there, the barred ranges, the verdict (N/mm²)."""
        lines = [f"{self.name}: shaft sections against IACS UR M68 (rated {self.rated_rpm:.1f} rpm of station 1)"]
        for s in self.sections:
            u = np.where(np.isfinite(s.utilisation), s.utilisation, -np.inf)
            k = int(np.argmax(u))
            lines.append(f"  {s.label} ({s.section.feature}, d {s.section.diameter * 1e3:.0f} mm): largest τ/τ_C "
                         f"{u[k]:.3f} at {self.rpm[k]:.1f} rpm (λ {self.speed_ratio[k]:.3f}): τ "
                         f"{s.stress_pa[k] / 1e6:.2f} N/mm², τ_C {s.tau_c_pa[k] / 1e6:.2f} N/mm²")
        for b in self.barred:
            lines.append(f"  barred {b['from_rpm']:.1f}-{b['to_rpm']:.1f} rpm: peak {b['peak_pa'] / 1e6:.2f} N/mm² "
                         f"({b['peak_utilisation']:.2f} τ_C) at {b['peak_rpm']:.1f} rpm in {b['section']}; "
                         + ("within τ_T" if b["within_transient"] else "ABOVE τ_T")
                         + ("; reaches above λ 0.8" if b["above_0_8"] else ""))
        return "\n".join(lines + [f"  verdict: {self.verdict}"] + [f"  note: {n}" for n in self.notes])

    def plot(self, ax=None):
        """Each section's τ/τ_C over speed (solid; log scale, so that a section far below its limit
        still shows its resonances), the limit 1 and τ_T/τ_C (dotted, to λ 0.8), past λ 1.05 the
        stress over τ_C at λ 1.05 (dashed: the rule gives none there), the barred ranges shaded and
        λ on the top axis with 0.8 and 1.05 marked. Returns the Axes."""
        import matplotlib.pyplot as plt

        ax = ax if ax is not None else plt.figure(figsize=(9, 5)).add_subplot()
        lam = self.speed_ratio
        low = []
        for k, s in enumerate(self.sections):
            color = f"C{k % 10}"
            u = s.utilisation
            ax.plot(self.rpm, u, color=color, label=f"τ/τ_C {s.label}")
            if np.isfinite(s.tau_t_pa).any():  # the rule gives τ_T to λ 0.8 only
                ax.plot(self.rpm, s.tau_t_pa / s.tau_c_pa, color=color, ls=":", lw=0.9, label=f"τ_T/τ_C {s.label}")
            beyond = lam > LAMBDA_MAX
            if beyond.any():
                ax.plot(self.rpm[beyond], s.stress_pa[beyond] / limit_at_edge(s.section), color=color, ls="--", lw=1.0,
                        label=f"τ/τ_C(λ {LAMBDA_MAX}) {s.label}, not judged")
            low.append(np.nanmin(np.where(u > 0, u, np.nan)) if np.any(u > 0) else 1.0)
        ax.axhline(1.0, color="crimson", lw=1.2, label="τ = τ_C")
        for b in self.barred:
            ax.axvspan(b["from_rpm"], b["to_rpm"], color="crimson", alpha=0.15, lw=0)
        ax.set_yscale("log")
        ax.set_ylim(max(min(low) / 3, 1e-4), 3.0)
        from matplotlib.ticker import FuncFormatter, NullFormatter

        ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
        ax.yaxis.set_minor_formatter(NullFormatter())
        ax.set(xlabel="engine speed, station 1 (rpm)", ylabel="τ / τ_C (log)",
               title=f"{self.name}: shaft stresses, UR M68 ({self.verdict})")
        top = ax.secondary_xaxis("top", functions=(lambda n: n / self.rated_rpm, lambda x: x * self.rated_rpm))
        top.set_xlabel("λ = n / rated", fontsize=8)
        for mark in (LAMBDA_TRANSIENT_MAX, LAMBDA_MAX):
            if lam[0] <= mark <= lam[-1]:
                ax.axvline(mark * self.rated_rpm, color="0.5", lw=0.8, ls="-.")
        ax.legend(fontsize=7, loc="best")
        return ax


def json_nulls(a: np.ndarray) -> list:
    """The array as a JSON list, NaN as null."""
    return [None if not np.isfinite(v) else float(v) for v in a]


def section_limits(section: ShaftSection, speed_ratio: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(τ_C, τ_T) of a section at each λ, Pa: NaN where the rule gives none (τ_C above λ 1.05,
    τ_T above λ 0.8)."""
    sigma, cd = capped_strength(section.tensile_strength, section.material), size_factor(section.diameter)
    tau_c = np.array([continuous_limit(sigma, section.ck, cd, x) if x <= LAMBDA_MAX else np.nan
                      for x in speed_ratio])
    tau_t = np.where(speed_ratio <= LAMBDA_TRANSIENT_MAX, transient_limit(tau_c, section.ck), np.nan)
    return tau_c, tau_t


def limit_at_edge(section: ShaftSection) -> float:
    """τ_C at λ 1.05, the last speed UR M68 gives one at, Pa: what a stress beyond it is set against."""
    return float(section_limits(section, np.array([LAMBDA_MAX]))[0][0])


def rated_speed(net: Network) -> float:
    """The rated speed referred to station 1, rpm: the first propeller's rated speed over its speed
    factor, else the top of the ``[excitation]`` speed range; NaN with neither."""
    if net.propellers:
        p = net.propellers[0]
        return float(p.rated_speed * 30.0 / np.pi / speed_factors(net)[p.station])
    return float(net.excitation.speed_range[1]) if net.excitation is not None else float("nan")


def judged_sections(net: Network, response: ResponseResult) -> list[tuple[int, str, ShaftSection]]:
    """(column of the response's section torques, label, section) of every shaft with a section;
    the response's sections are the resolved network's linear shafts, in order."""
    shafts = resolved(net).linear_shafts
    return [(k, response.section_labels[k], s.section) for k, s in enumerate(shafts) if s.section is not None]


def section_stress(label: str, section: ShaftSection, torque_nm: np.ndarray, rpm: np.ndarray,
                   speed_ratio: np.ndarray) -> SectionStress:
    """One section's stress from its half-range torque (N·m) at each speed, its limits and barred ranges."""
    stress = section.stress(np.asarray(torque_nm, dtype=float))
    tau_c, tau_t = section_limits(section, speed_ratio)
    judged = np.isfinite(tau_c)
    bars = barred_ranges(rpm[judged], (stress / tau_c)[judged], 1.0)
    for b in bars:
        inside = judged & (rpm >= b["from_rpm"]) & (rpm <= b["to_rpm"])
        # the peak stress in the range (a range narrower than the speed step: the sample at its peak)
        k = int(np.flatnonzero(inside)[np.argmax(stress[inside])]) if inside.any() else \
            int(np.argmin(abs(rpm - b["peak_rpm"])))
        b.update(peak_pa=float(stress[k]), peak_rpm=float(rpm[k]), peak_utilisation=b.pop("peak"))
    return SectionStress(label, section, stress, tau_c, tau_t, bars)


def merged_ranges(sections: list[SectionStress], rpm: np.ndarray, rated_rpm: float) -> list[dict]:
    """The sections' barred ranges merged where they overlap: each with its worst section (largest
    τ/τ_C), peak, whether every section stays within its τ_T at the speeds in it where the rule
    gives one (λ ≤ 0.8), and whether it reaches above λ 0.8 (``rated_rpm`` of station 1)."""
    spans = sorted((b["from_rpm"], b["to_rpm"]) for s in sections for b in s.barred)
    merged: list[list[float]] = []
    for lo, hi in spans:
        if merged and lo <= merged[-1][1]:
            merged[-1][1] = max(merged[-1][1], hi)
        else:
            merged.append([lo, hi])
    out = []
    for lo, hi in merged:
        own = [(b, s) for s in sections for b in s.barred if lo <= b["from_rpm"] and b["to_rpm"] <= hi]
        worst, where = max(own, key=lambda o: o[0]["peak_utilisation"])
        inside = (rpm >= lo) & (rpm <= hi)
        # a range narrower than the speed step: judged at its peak's sample
        inside = inside if inside.any() else rpm == worst["peak_rpm"]
        transient = all(np.all((s.stress_pa <= s.tau_t_pa)[inside & np.isfinite(s.tau_t_pa)]) for s in sections)
        out.append({"from_rpm": lo, "to_rpm": hi, "section": where.label, "peak_pa": worst["peak_pa"],
                    "peak_rpm": worst["peak_rpm"], "peak_utilisation": worst["peak_utilisation"],
                    "within_transient": bool(transient),
                    "above_0_8": bool(hi / rated_rpm > LAMBDA_TRANSIENT_MAX)})
    return out


def shaft_verdict(net: Network, response: ResponseResult, rated_rpm: float | None = None) -> ShaftVerdict:
    """Every shaft section of ``net`` against UR M68 over the response's speeds.

    Parameters
    ----------
    net : Network
        The network the response is of, with shaft sections (``[[chain.shafts]]`` ``diameter_m`` …).
    response : ResponseResult
        Its forced response (:func:`fetorsion.response.forced.solve_response`): the half-range
        section torques, N·m.
    rated_rpm : float, optional
        The rated speed referred to station 1, rpm; default :func:`rated_speed`.
    """
    rated = rated_speed(net) if rated_rpm is None else float(rated_rpm)
    if not np.isfinite(rated) or rated <= 0:
        raise ParameterError("rated_rpm", f"{rated_rpm}: the network states no rated speed (a propeller or an "
                             "[excitation] speed range); give it")
    rpm = np.asarray(response.rpm, dtype=float)
    lam = rpm / rated
    sections = [section_stress(label, sec, response.section_torque_nm[:, k], rpm, lam)
                for k, label, sec in judged_sections(net, response)]
    notes = ["stresses: half-range synthesised amplitudes, nominal on the plain section, 16 T d/(π(d⁴ − d_i⁴))"]
    if net.constant_speed:
        notes.append("a constant-speed set: it runs continuously anywhere in its band up to the rated speed, so a "
                     "barred speed there fails; above it lies only the overspeed it passes through")
    if lam[-1] > LAMBDA_MAX:
        notes.append(f"speeds above λ {LAMBDA_MAX} ({LAMBDA_MAX * rated:.1f} rpm) are not judged: the rule gives no τ_C")
        notes += beyond_the_rule(sections, rpm, lam)
    return ShaftVerdict(net.name, rpm, rated, sections, merged_ranges(sections, rpm, rated), bool(net.propellers), notes,
                        net.constant_speed)


def beyond_the_rule(sections: list[SectionStress], rpm: np.ndarray, lam: np.ndarray) -> list[str]:
    """A line for each section whose stress above λ 1.05 (speeds the file asks for, where UR M68 gives
    no τ_C) passes its τ_C at λ 1.05: from which speed (linear between samples), how far and where.
    Not a verdict — the rule does not reach there — but what a reviewer asks about first."""
    out = []
    above = lam > LAMBDA_MAX
    for s in sections:
        edge = limit_at_edge(s.section)
        over = above & (s.stress_pa > edge)
        if not over.any():
            continue
        k = int(np.flatnonzero(over)[0])
        start = float(rpm[k])
        if k > 0 and above[k - 1]:  # the crossing between this sample and the one before it
            a, b = s.stress_pa[k - 1] - edge, s.stress_pa[k] - edge
            start = float(rpm[k - 1] + (rpm[k] - rpm[k - 1]) * a / (a - b))
        j = int(np.flatnonzero(above)[np.argmax(s.stress_pa[above])])
        out.append(f"beyond the rule: {s.label} passes its τ_C at λ {LAMBDA_MAX} ({edge / 1e6:.2f} N/mm²) from "
                   f"{start:.1f} rpm, up to {s.stress_pa[j] / 1e6:.2f} N/mm² ({s.stress_pa[j] / edge:.2f} × it) at "
                   f"{rpm[j]:.1f} rpm (λ {lam[j]:.3f}): inside the speed range asked for, not judged by UR M68")
    return out
