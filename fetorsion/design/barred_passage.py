"""The transient passage through a barred speed range against UR M68's τ_T, in the time domain
(docs/propulsion-tvc.md).

A barred range (:mod:`.shaft_verdict`: where the steady-state stress exceeds τ_C) must be passed
quickly; in the passage the stress may reach τ_T = 1.7 τ_C/√C_K. The frequency domain's check
(``within_transient``) takes the steady state, the slow-passage limit. Here the line is run through
the range in the time domain (:func:`fetorsion.response.transient.run_transient`: the engine's
cylinders, the misfiring one on its motored cycle where the range is a misfire's, and the
propellers' blade orders), from the periodic steady state at the run's start speed, at a stated
rate: ``passage_rate_rpm_per_s`` of the network's first propeller, or :data:`DEFAULT_PASSAGE_RATE`
(ASSUMED, said in the result). The run spans the range widened by :data:`PASSAGE_MARGIN` of its
width either side (at least :data:`MIN_MARGIN_RPM`), so it starts and ends outside it.

**The stress in the passage.** The record of each section's torque is cut into windows of one
synthesis period of the response (the common period of the engine's and the blade orders, or the
engine's cycle where they share none); in each window the half-range (max − min)/2 of the torque,
as the rule's synthesised half-range amplitude, gives the nominal stress 16 T d/(π (d⁴ − d_i⁴)).
The largest over the windows is set against τ_T at its window's mean speed (λ = n/n_rated; the
rule gives no τ_T above λ 0.8: not judged there). For a passage slow against the mode's decay, the
peak approaches the steady state's (tests/test_propulsion_transient.py); where the sources share
no period, a window sees only some of their relative phases, and the peak stays at or under the
frequency domain's bound (the sum of each source's extremes).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace

import numpy as np

from ..description.chain_model import Network
from ..lumped_model.network import resolved
from ..response.propulsion import damping_at
from ..response.transient import TransientResult, run_transient
from ..results import from_fields
from .shaft_verdict import json_nulls, judged_sections, rated_speed, section_limits
from .tvc_cases import TVCCase

#: The passage rate when the network states none, rpm/s of station 1: ASSUMED (no rule text giving a
#: rate was read here); a slow governor-limited acceleration of a medium-speed engine.
DEFAULT_PASSAGE_RATE = 10.0
#: The run spans the barred range widened by this share of its width either side.
PASSAGE_MARGIN = 1.0
#: ... and by at least this many rpm either side.
MIN_MARGIN_RPM = 20.0
#: The kind of a start's run and of a stop's (:attr:`BarredPassage.kind`).
START_UP = "start-up"
SHUT_DOWN = "shut-down"


@dataclass(frozen=True)
class SectionPassage:
    """One shaft section's most utilised half-range stress in a passage (Pa, at ``peak_rpm`` of station 1)
    against its limit there, :attr:`limit_pa`: τ_T to λ 0.8, above it τ_C (UR M68 gives τ_T to λ 0.8 only;
    above, the continuous limit holds: no barred range is allowed there in a propeller line, and a
    start runs through it as a set runs); and its record: the windows' mean speeds (rpm), stresses and
    limits (Pa)."""

    label: str
    peak_pa: float
    peak_rpm: float
    tau_t_pa: float
    tau_c_pa: float
    window_rpm: np.ndarray
    window_stress_pa: np.ndarray
    #: The limit at each window's speed (Pa): τ_T to λ 0.8, τ_C above to λ 1.05, NaN beyond; empty in
    #: a passage stored before it was kept.
    window_limit_pa: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @property
    def limit_pa(self) -> float:
        """The limit at the peak, Pa: τ_T (λ ≤ 0.8), else τ_C (λ ≤ 1.05), else NaN (the rule gives none)."""
        return self.tau_t_pa if np.isfinite(self.tau_t_pa) else self.tau_c_pa

    @property
    def limit_name(self) -> str:
        """"τ_T" or "τ_C": which limit :attr:`limit_pa` is."""
        return "τ_T" if np.isfinite(self.tau_t_pa) else "τ_C"

    @property
    def utilisation(self) -> float:
        """τ over its limit at the peak (NaN where the rule gives none)."""
        return self.peak_pa / self.limit_pa

    @property
    def within(self) -> bool:
        """τ at or under its limit at the peak (True where the rule gives none: not judged)."""
        return not self.peak_pa > self.limit_pa


@dataclass(frozen=True)
class CouplingPassage:
    """A flexible coupling's largest torque in a passage (N·m, at ``peak_rpm`` of station 1): the
    run's vibratory torque through it (the mean its acceleration passes is not in the run's
    coordinates), against the sheet's T_Kmax (``maximum_nm``; 0: the sheet gives none, not judged)."""

    label: str
    peak_nm: float
    peak_rpm: float
    maximum_nm: float = 0.0

    @property
    def within(self) -> bool:
        """At or under T_Kmax (True where the sheet gives none: not judged)."""
        return not (self.maximum_nm > 0 and self.peak_nm > self.maximum_nm)

    def line(self) -> str:
        """The coupling's largest torque against T_Kmax, in words."""
        judged = (f"T_Kmax {self.maximum_nm:.0f} N m ({self.peak_nm / self.maximum_nm:.3f} T_Kmax)" if self.maximum_nm
                  else "not judged (the sheet gives no T_Kmax)")
        return f"coupling '{self.label}': largest torque {self.peak_nm:.0f} N m at {self.peak_rpm:.1f} rpm; {judged}"


@dataclass(frozen=True)
class BarredPassage:
    """The time-domain passage through one barred range (module docs): the ``configuration`` it is
    of, the range (``from_rpm``, ``to_rpm``), the run's span and rate (rpm, rpm/s) with where the
    rate comes from, the window (rad of station 1), the run's steps and each judged section."""

    configuration: str
    from_rpm: float
    to_rpm: float
    run_from_rpm: float
    run_to_rpm: float
    rate_rpm_per_s: float
    rate_source: str
    window_rad: float
    steps: int
    sections: tuple[SectionPassage, ...]
    #: "barred range"; "start-up": the engine's start from its firing speed to the range's lowest speed
    #: (``[start]``); or "shut-down": its coast-down after the fuel cut (``[stop]``).
    kind: str = "barred range"
    #: Each flexible coupling's largest torque in the run against its sheet's T_Kmax.
    couplings: tuple[CouplingPassage, ...] = ()

    @property
    def is_start(self) -> bool:
        """The engine's start (``[start]``), not a barred range's passage."""
        return self.kind == START_UP

    @property
    def is_stop(self) -> bool:
        """The engine's coast-down after its fuel is cut (``[stop]``)."""
        return self.kind == SHUT_DOWN

    @property
    def verdict(self) -> str:
        """"within the limits", or "above a limit" (some section's peak exceeds its τ_T, or its τ_C above λ 0.8)."""
        return "within the limits" if all(s.within for s in (*self.sections, *self.couplings)) else "above a limit"

    def to_dict(self) -> dict:
        """JSON-ready: the range, the run, the rate and its source, each section's peak and τ_T (Pa) and
        its windows' mean speeds (rpm) and stresses (Pa)."""
        return {"configuration": self.configuration, "from_rpm": self.from_rpm, "to_rpm": self.to_rpm,
                "run_rpm": [self.run_from_rpm, self.run_to_rpm], "rate_rpm_per_s": self.rate_rpm_per_s,
                "rate_source": self.rate_source, "window_rad": self.window_rad, "steps": self.steps,
                "verdict": self.verdict, "kind": self.kind,
                "sections": [{"label": s.label, "peak_pa": s.peak_pa, "peak_rpm": s.peak_rpm,
                              "tau_t_pa": None if not np.isfinite(s.tau_t_pa) else s.tau_t_pa,
                              "tau_c_pa": None if not np.isfinite(s.tau_c_pa) else s.tau_c_pa,
                              "within": s.within, "window_rpm": s.window_rpm.tolist(),
                              "window_stress_pa": s.window_stress_pa.tolist(),
                              "window_limit_pa": json_nulls(s.window_limit_pa)} for s in self.sections],
                "couplings": [{"label": c.label, "peak_nm": c.peak_nm, "peak_rpm": c.peak_rpm,
                               "maximum_nm": c.maximum_nm, "within": c.within} for c in self.couplings]}

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "BarredPassage":
        """The passage back from its :meth:`to_dict` (KeyError: one written before the windows were kept)."""
        sections = tuple(from_fields(SectionPassage, s, window_rpm=np.array(s["window_rpm"], dtype=float),
                                     window_stress_pa=np.array(s["window_stress_pa"], dtype=float))
                         for s in d["sections"])
        return from_fields(cls, d, run_from_rpm=float(d["run_rpm"][0]), run_to_rpm=float(d["run_rpm"][1]),
                           sections=sections,
                           couplings=tuple(from_fields(CouplingPassage, c) for c in d.get("couplings", [])))

    def table(self) -> str:
        """The passage as plain text, stresses in N/mm²."""
        what = (f"from {self.from_rpm:.1f} rpm up to the range's lowest speed {self.to_rpm:.1f} rpm"
                if self.is_start else f"fuel cut at {self.from_rpm:.1f} rpm, coasting down to {self.to_rpm:.1f} rpm"
                if self.is_stop else f"passage of the barred range {self.from_rpm:.1f}-{self.to_rpm:.1f} rpm")
        lines = [f"{self.configuration}: {what}, run {self.run_from_rpm:.1f} -> {self.run_to_rpm:.1f} rpm at "
                 f"{self.rate_rpm_per_s:g} rpm/s ({self.rate_source})"]
        for s in self.sections:
            limit = "no limit (λ > 1.05)" if not np.isfinite(s.limit_pa) else (
                f"{s.limit_name} {s.limit_pa / 1e6:.2f} N/mm² ({s.utilisation:.3f} {s.limit_name}"
                + ("; λ > 0.8: the continuous limit)" if s.limit_name == "τ_C" else ")"))
            lines.append(f"  {s.label}: peak τ {s.peak_pa / 1e6:.2f} N/mm² at {s.peak_rpm:.1f} rpm; {limit}")
        lines += [f"  {c.line()}" for c in self.couplings]
        return "\n".join(lines + [f"  verdict: {self.verdict}"])

    def plot(self, ax=None):
        """Each section's half-range stress per window over the run's speed with its τ_T at the peak and
        the barred range shaded (N/mm²). Returns the Axes."""
        import matplotlib.pyplot as plt

        ax = ax if ax is not None else plt.figure(figsize=(9, 4.5)).add_subplot()
        for k, s in enumerate(self.sections):
            ax.plot(s.window_rpm, s.window_stress_pa / 1e6, color=f"C{k % 10}", label=f"τ {s.label}")
            if s.window_limit_pa.size:  # τ_T to λ 0.8, τ_C above
                ax.plot(s.window_rpm, s.window_limit_pa / 1e6, color=f"C{k % 10}", ls=":", lw=0.9,
                        label=f"limit {s.label}: τ_T to λ 0.8, τ_C above")
            elif np.isfinite(s.tau_t_pa):
                ax.axhline(s.tau_t_pa / 1e6, color=f"C{k % 10}", ls=":", lw=0.9, label=f"τ_T {s.label}")
        if not (self.is_start or self.is_stop):  # a start's or stop's run is no barred range: nothing to shade
            ax.axvspan(self.from_rpm, self.to_rpm, color="crimson", alpha=0.15, lw=0, label="barred range")
        what = (f"{self.configuration} from {self.from_rpm:.0f} rpm" if self.is_start or self.is_stop else
                f"{self.configuration}: passage")
        ax.set(xlabel="engine speed (rpm)", ylabel="vibratory torsional stress, half-range (N/mm²)",
               title=f"{what} at {self.rate_rpm_per_s:g} rpm/s ({self.verdict})")
        ax.legend(fontsize=7)
        return ax


def passage_rate(net: Network) -> tuple[float, str]:
    """(rate rpm/s, where it comes from): the first propeller's ``passage_rate_rpm_per_s``, else
    :data:`DEFAULT_PASSAGE_RATE`."""
    stated = next((p.passage_rate for p in net.propellers if p.passage_rate), None)
    if stated:
        return stated, "stated in the network file"
    return DEFAULT_PASSAGE_RATE, "fetorsion's default, ASSUMED: no rate stated in the network file"


def window_stresses(result: TransientResult, torque_nm: np.ndarray, section, window_rad: float):
    """(mean rpm, half-range stress Pa) of each whole window of ``window_rad`` of station 1's mean
    angle in a run's record of one section's torque (N·m)."""
    phi = result.crank_angle_rad - result.crank_angle_rad[0]
    idx = np.floor(phi / window_rad).astype(int)
    starts = np.flatnonzero(np.diff(idx, prepend=-1))
    # the last window is cut short by the run's end: left out
    half = 0.5 * (np.maximum.reduceat(torque_nm, starts) - np.minimum.reduceat(torque_nm, starts))[:-1]
    rpm = (np.add.reduceat(result.rpm, starts) / np.diff(np.append(starts, result.rpm.size)))[:-1]
    return rpm, section.stress(half)


def passage_through(net: Network, span_rpm: tuple[float, float], barred: tuple[float, float], rate: float,
                    rate_source: str, window_rad: float, configuration: str = "normal running",
                    misfire: int | None = None, kind: str = "barred range") -> BarredPassage:
    """Run ``net`` up through ``span_rpm`` at ``rate`` rpm/s from its settled state and judge the
    passage of the barred range ``barred`` (rpm) against τ_T (module docs).

    Parameters
    ----------
    net : Network
        The line, with its couplings at the configuration's settled temperature.
    span_rpm : (float, float)
        The run's start and end speed of station 1, rpm.
    barred : (float, float)
        The barred range's ends, rpm.
    rate : float
        |dn/dt| of the run, rpm/s; ``rate_source`` says where it comes from.
    window_rad : float
        The synthesis period the half-range is taken over, rad of station 1.
    configuration : str
        Normal running or a misfire, in words; ``misfire`` the 0-based misfiring cylinder.
    kind : str
        What is passed: "barred range", "start-up" or "shut-down" (:attr:`BarredPassage.kind`).

    Each section's peak is its window of the largest stress over its limit (τ_T to λ 0.8, τ_C above to
    λ 1.05; :class:`SectionPassage`), else of its largest stress where no window has a limit: a start's
    largest stress may lie where the limit is high and a smaller one exceed a lower limit.
    """
    # a propeller whose law damping follows the speed takes the one at the range's middle, where its peak is judged
    res = run_transient(damping_at(net, 0.5 * (barred[0] + barred[1])), run=span_rpm, rate_rpm_per_s=rate,
                        settled_start=True, misfire=misfire)
    rated = rated_speed(net)
    out = []
    for k, label, sec in judged_sections(net, res):
        rpm, stress = window_stresses(res, res.section_torque_nm[k], sec, window_rad)
        tau_c, tau_t = section_limits(sec, rpm / rated)
        limit = np.where(np.isfinite(tau_t), tau_t, tau_c)
        judged = np.isfinite(limit)
        j = int(np.argmax(np.where(judged, stress / np.where(judged, limit, 1.0), -np.inf))) if judged.any() \
            else int(np.argmax(stress))
        out.append(SectionPassage(label, float(stress[j]), float(rpm[j]), float(tau_t[j]), float(tau_c[j]), rpm,
                                  stress, limit))
    return BarredPassage(configuration, barred[0], barred[1], span_rpm[0], span_rpm[1], rate, rate_source,
                         window_rad, res.samples, tuple(out), kind, coupling_peaks(net, res))


def coupling_peaks(net: Network, res: TransientResult) -> tuple[CouplingPassage, ...]:
    """Each coupling's largest torque in a run: its elastic section's record, the couplings being the
    network's last shafts (after the cranks' inner ones and the file's shafts)."""
    first = len(resolved(net).shafts) - len(net.couplings)
    out = []
    for k, c in enumerate(net.couplings):
        torque = np.abs(res.section_torque_nm[first + k])
        j = int(np.argmax(torque))
        out.append(CouplingPassage(c.name, float(torque[j]), float(res.rpm[j]), c.maximum_torque))
    return tuple(out)


def passage_span(barred: dict, lowest_rpm: float = 1.0) -> tuple[float, float]:
    """The run's span about a barred range {from_rpm, to_rpm} (module docs), rpm, starting no lower
    than ``lowest_rpm``: the speed range's lowest speed, below which the engine does not run (a range
    barred from there is passed from there; the run from below is the start's, ``[start]``)."""
    lo, hi = barred["from_rpm"], barred["to_rpm"]
    margin = max(PASSAGE_MARGIN * (hi - lo), MIN_MARGIN_RPM)
    return max(lo - margin, lowest_rpm, 1.0), hi + margin


def barred_passages(case: TVCCase) -> list[BarredPassage]:
    """The passage of every barred range of a TVC configuration (:class:`.tvc_cases.TVCCase`) at
    the network's passage rate (:func:`passage_rate`); none without barred ranges or an engine."""
    net = case.network
    if case.shafts is None or not case.shafts.barred or net.engine is None or net.excitation is None:
        return []
    rate, source = passage_rate(net)
    lowest = float(net.excitation.speed_range[0])
    return [passage_through(net, passage_span(b, lowest), (b["from_rpm"], b["to_rpm"]), rate, source,
                            case.response.cycle_rad, case.name, case.misfire) for b in case.shafts.barred]


def start_passages(case: TVCCase) -> list[BarredPassage]:
    """The engine's start (``[start]`` of the network file) through every resonance below the speed
    range: a run from the start's firing speed up to the range's lowest speed at its rate, every
    cylinder at the start's mean indicated pressure, each section against its limit. None without ``[start]``."""
    start, net = case.network.start, case.network
    if start is None or net.engine is None or net.excitation is None:
        return []
    return [run_at_load(case, start.imep_pa, (start.from_rpm, float(net.excitation.speed_range[0])),
                        start.rate_rpm_per_s, "[start]", start.source,
                        f"start at p_mi {start.imep_pa / 1e6:g} MPa", START_UP)]


def stop_passages(case: TVCCase) -> list[BarredPassage]:
    """The engine's stop (``[stop]`` of the network file): the fuel cut at its speed, every cylinder
    motored (the synthetic cycle, or the harmonic table's column, at p_mi 0), the line coasting down at
    its rate, each section against its limit as a start is. None without ``[stop]``."""
    stop, net = case.network.stop, case.network
    if stop is None or net.engine is None or net.excitation is None:
        return []
    return [run_at_load(case, 0.0, (stop.from_rpm, stop.to_rpm), stop.rate_rpm_per_s, "[stop]", stop.source,
                        "stop, every cylinder motored", SHUT_DOWN)]


def run_at_load(case: TVCCase, imep_pa: float, span_rpm: tuple[float, float], rate: float, table: str,
                source: str, configuration: str, kind: str) -> BarredPassage:
    """A start's or stop's run over ``span_rpm`` at ``rate`` rpm/s, every cylinder at ``imep_pa`` (Pa; 0: motored),
    judged over its whole span; ``table`` and ``source`` say where the rate comes from."""
    net = case.network
    at_load = replace(net, excitation=replace(net.excitation, load_kind="imep", load=((1.0, imep_pa),)))
    stated = f"stated in {table}{': ' + source if source else ''}"
    return passage_through(at_load, span_rpm, span_rpm, rate, stated, case.response.cycle_rad, configuration,
                           kind=kind)
