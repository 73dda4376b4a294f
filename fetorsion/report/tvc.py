"""The report's propulsion TVC section (:class:`~fetorsion.report.outcomes.TVCOutcome`), in the
order a class reviewer reads a torsional vibration calculation: the mass-elastic data, the natural
frequencies, the shaft stresses against UR M68 with the barred ranges, the couplings' heat at
their settled temperature, the gear meshes against hammering, and what is assumed (docs/propulsion-tvc.md)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from .outcomes import Skipped, TVCOutcome

if TYPE_CHECKING:
    from ..description.chain_model import Network


def mass_elastic_lines(net: Network) -> list[str]:
    """The mass-elastic table: each station's speed over station 1's, inertia (in water for a
    propeller) and absolute damping, each shaft's and coupling's stiffness and section, at their own
    stations' speed (not referred to the engine's)."""
    from ..lumped_model.network import speed_factors

    # each value at its own station's speed, as the file states it; the ratio says where it turns
    lines = ["| station | speed / station 1's | inertia [kg m²] | damping to ground [N m s/rad] |", "|---|---|---|---|"]
    damping = net.absolute_damping or (0.0,) * len(net.labels)
    lines += [f"| {s} | {f:.4g} | {j:.6g} | {c:.4g} |"
              for s, f, j, c in zip(net.labels, speed_factors(net), net.inertias, damping)]
    lines += ["", "| between | stiffness [N m/rad] | loss factor | section |", "|---|---|---|---|"]
    for sh in net.shafts:
        b = net.labels[sh.j] if sh.j >= 0 else "ground"
        sec = sh.section
        what = "" if sec is None else (f"d {sec.diameter * 1e3:.0f} mm, bore {sec.bore * 1e3:.0f} mm, σ_B "
                                       f"{sec.tensile_strength / 1e6:.0f} N/mm², {sec.feature} (C_K {sec.ck:g})")
        lines.append(f"| {net.labels[sh.i]} – {b} | {sh.stiffness:.6g} | {sh.loss_factor:.4g} | {what} |")
    lines += [f"| {net.labels[g.i]} – {net.labels[g.j]} | gear, ratio {g.ratio:g} | | |" for g in net.gears]
    if net.dampers:
        lines += ["", "| damper | kind | on | ring inertia [kg m²] | housing/hub [kg m²] | stiffness [N m/rad] | "
                  "damping [N m s/rad] | loss factor |", "|---|---|---|---|---|---|---|---|"]
        lines += [f"| {d.name} | {d.kind} | {d.at} | {d.ring_inertia:.6g} | {d.hub_inertia:.6g} | {d.stiffness:.6g} | "
                  f"{d.damping:.6g} | {d.loss_factor:.4g} |" for d in net.dampers]
    return lines


def installation_lines(net: Network) -> list[str]:
    """The installation's particulars as the file states them (engine, load, propellers, gears,
    couplings) and cylinder 1's tangential torque harmonics at the rated speed: what a reviewer
    checks the mass-elastic data and the excitation against."""
    lines = ["### Installation particulars", ""]
    ex, eng = net.excitation, net.engine
    if eng is not None and ex is not None:
        lo, hi = ex.speed_range
        load = {"propeller_imep": "on the propeller curve, p_mi ∝ n² below the rated speed",
                "imep": "as stated at each speed", "peak": "by its peak pressure"}.get(ex.load_kind, ex.load_kind)
        swept = eng.cylinders * math.pi / 4 * eng.bore ** 2 * eng.stroke
        p_mi = ex.running_imep(hi) if ex.load_kind != "peak" else math.nan
        power = p_mi * swept * hi / 60 / (eng.strokes_per_cycle / 2) if math.isfinite(p_mi) else math.nan
        lines += [f"- Engine: {eng.cylinders} cylinders {eng.layout}, {eng.strokes_per_cycle}-stroke, bore "
                  f"{eng.bore * 1e3:.1f} mm, stroke {eng.stroke * 1e3:.1f} mm, rod {eng.rod_length * 1e3:.1f} mm, "
                  f"firing order {'-'.join(str(c) for c in eng.firing_order)}; speed range {lo:g}-{hi:g} rpm (rated "
                  f"{hi:g}), computed to {ex.overspeed:g} × rated.",
                  f"- Load: p_mi {p_mi / 1e6:.3g} MPa at the rated speed, {load}" + (
                      f"; indicated power there {power / 1e3:.0f} kW (brake power is not in the file)"
                      if math.isfinite(power) else "") + "."]
    f = None
    for p in net.propellers:
        if f is None:
            from ..lumped_model.network import speed_factors

            f = speed_factors(net)
        lines.append(f"- Propeller '{p.name}' at {net.labels[p.station]}: {p.blades} blades, dry inertia "
                     f"{p.dry_inertia:.6g} kg m² + {100 * p.entrained_share:g} % entrained water = {p.inertia:.6g} kg m²; "
                     f"rated {p.rated_torque:.6g} N m at {p.rated_speed * 30 / math.pi:.1f} rpm (its shaft; "
                     f"{f[p.station]:.4g} × station 1's speed); blade orders at "
                     f"{', '.join(f'{100 * v:g} %' for v in p.order_shares) or 'none'} of the mean torque.")
    lines += [f"- Gear {net.labels[g.i]} – {net.labels[g.j]}: speed ratio {g.ratio:g}." for g in net.gears]
    for c in net.couplings:
        warm = "" if not math.isfinite(c.warm_temperature_c) else (
            f", {c.warm_stiffness:.4g} N m/rad and ψ {c.warm_relative_damping:g} at {c.warm_temperature_c:g} °C")
        lines.append(f"- Coupling '{c.name or 'coupling'}' ({net.labels[c.i]} – {net.labels[c.j]}): "
                     f"{c.stiffness:.4g} N m/rad and ψ {c.relative_damping:g} at {c.temperature_c:g} °C{warm}; "
                     f"permissible vibratory torque {f'{c.permissible_torque:.0f} N m' if c.permissible_torque else 'not stated'}, "
                     f"P_KV {f'{c.permissible_power:.0f} W' if c.permissible_power else 'not stated'}"
                     + (f" at {c.ambient_c:g} °C ambient" if math.isfinite(c.ambient_c) else "")
                     + (f"; source: {c.source}" if c.source else "") + ".")
    if eng is not None and ex is not None:
        lines += [""] + _excitation_lines(net)
    return lines + [""]


def _excitation_lines(net: Network) -> list[str]:
    """Cylinder 1's tangential torque harmonics at the rated speed, the largest eight by amplitude."""
    import numpy as np

    from ..excitation.loads import cylinder_loads

    rated = net.excitation.speed_range[1]
    orders = np.arange(0.5, 24.01, 0.5)
    try:
        h = cylinder_loads(net).torque_harmonics([rated], orders)[0, :, 0]
    except Exception:  # noqa: BLE001 - a table without every order: the section goes without the list
        return []
    top = sorted(np.argsort(-np.abs(h))[:8])
    return ([f"Cylinder 1's torque harmonics at {rated:g} rpm (gas and reciprocating inertia; the largest eight):", "",
             "| order | " + " | ".join(f"{orders[k]:g}" for k in top) + " |", "|---|" + "---|" * len(top),
             "| amplitude [N m] | " + " | ".join(f"{abs(h[k]):.4g}" for k in top) + " |"])


def damper_lines(outcome: TVCOutcome) -> list[str]:
    """Each damper's largest heat over the speed range, normal running and the worst misfire, against
    the heat its maker allows where the description states it."""
    dampers = outcome.network.dampers
    if not dampers:
        return []
    worst = outcome.worst_misfire
    lines = ["### Dampers: heat", "", "| damper | normal running [W] | " + (f"{worst.name} [W] | " if worst else "")
             + "permissible [W] | verdict |", "|---|---|" + "---|" * bool(worst) + "---|---|"]
    for k, d in enumerate(dampers):
        heats = [outcome.normal.damper_heat_w[k]] + ([worst.damper_heat_w[k]] if worst else [])
        verdict = "not judged (no permissible heat stated)" if not d.allowed_power else (
            "within" if max(heats) <= d.allowed_power else "EXCEEDED")
        lines.append(f"| {d.name} | " + " | ".join(f"{h:.1f}" for h in heats)
                     + f" | {_cell(d.allowed_power or None, '.0f')} | {verdict} |")
    return lines + [""]


def _cell(v, fmt: str) -> str:
    return "–" if v is None else format(v, fmt)


def misfire_lines(outcome: TVCOutcome) -> list[str]:
    """Normal running and each cylinder's misfire, one row each, and the worst misfire's shaft table."""
    if outcome.misfire_note:
        return ["### Misfire", "", f"Not computed: {outcome.misfire_note}.", ""]
    if not outcome.misfires:
        return []
    lines = ["### Normal running and misfire", ""] + configuration_rows((outcome.normal, *outcome.misfires))
    worst = outcome.worst_misfire
    lines += ["", f"Worst misfire: {worst.name} (each misfiring cylinder runs its motored cycle; the couplings "
              "at the temperature their heat holds in that configuration).", ""]
    if worst.shafts is not None:
        lines += ["```", worst.shafts.table(), "```", "", f"![]({outcome.misfire_shaft_image})", ""]
    return lines


def configuration_rows(cases) -> list[str]:
    """The configurations' table: one row per TVC case (τ/τ_C, barred ranges, couplings, gears and,
    where the network has dampers, their heat)."""
    dampers = any(c.network.dampers for c in cases)  # normal running's, where a failed case has none
    crank = any(c.crank_torque_nm is not None for c in cases)
    lines = ["| configuration | largest τ/τ_C | barred ranges | shafts | coupling °C | coupling heat [W] | "
             "coupling torque [N m] | gears |" + " damper heat [W] |" * dampers
             + " crank torque [kN m] @ rpm (not judged) |" * crank,
             "|---|---|---|---|---|---|---|---|" + "---|" * dampers + "---|" * crank]
    for case in cases:
        r = case.summary()
        lines.append(f"| {r['case']} | {_cell(r['largest_tau_over_tau_c'], '.3f')} | {r['barred'] or '–'} | "
                     f"{r['shaft_verdict'] or '–'} | {_cell(r['coupling_temperature_c'], '.1f')} | "
                     f"{_cell(r['coupling_heat_w'], '.1f')} | {_cell(r['coupling_torque_nm'], '.0f')} | "
                     f"{r['hammering'] or '–'} |" + f" {_cell(r['largest_damper_heat_w'], '.1f')} |" * dampers
                     + f" {_crank_cell(case)} |" * crank)
    return lines


def _crank_cell(case) -> str:
    if case.crank_torque_nm is None:
        return "–"
    return f"{case.crank_torque_nm / 1e3:.1f} @ {case.crank_torque_rpm:.0f} ({case.crank_section})"


def conclusion_lines(outcome: TVCOutcome) -> list[str]:
    """Each criterion's result over every configuration computed (normal running, each misfire, each
    failed damper), what it restricts and what is not judged: what a reviewer reads first."""
    cases = [c for c in (outcome.normal, *outcome.misfires, *outcome.failed_dampers, *outcome.tolerances)
             if c is not None]
    if not cases:
        return []
    lines = ["### Conclusions", "", f"Over {len(cases)} configuration(s): normal running"
             + (f", the misfire of each of {len(outcome.misfires)} cylinders" if outcome.misfires else "")
             + (f", {len(outcome.failed_dampers)} failed-damper state(s)" if outcome.failed_dampers else "")
             + (f", {len(outcome.tolerances)} coupling stiffness(es) at the ends of their tolerance"
                if outcome.tolerances else "") + ".", ""]
    lines += (_shaft_conclusions(cases) + _passage_conclusions(outcome) + _coupling_conclusions(outcome, cases)
              + _hammering_conclusion(cases))
    if outcome.crank_m53 or outcome.crank_m53_note:
        lines += _crank_m53_conclusion(outcome)
    elif any(c.crank_torque_nm is not None for c in cases):
        w = max((c for c in cases if c.crank_torque_nm is not None), key=lambda c: c.crank_torque_nm)
        lines.append(f"- **Crankshaft: not judged here.** Its largest section torque {w.crank_torque_nm / 1e3:.1f} kN m "
                     f"({w.crank_section}, {w.crank_torque_rpm:.0f} rpm, {w.name}); the engine maker's permissible "
                     "values are not in a network file.")
    if outcome.normal is not None and outcome.normal.damper_heat_w:
        lines.append(f"- **Dampers' heat:** up to {max(c.summary()['largest_damper_heat_w'] or 0.0 for c in cases):.1f} W; "
                     "see the dampers' table for each against its permissible heat where the file states it.")
    return lines + [""]


def _shaft_conclusions(cases) -> list[str]:
    """The shafts against UR M68 over the configurations, and what lies beyond λ 1.05."""
    if not any(c.shafts is not None for c in cases):
        return []
    have = [c for c in cases if c.summary()["largest_tau_over_tau_c"] is not None]
    w = max(have, key=lambda c: c.summary()["largest_tau_over_tau_c"])
    barred = [(c.name, c.summary()["barred"], c.shafts.verdict) for c in cases if c.shafts and c.shafts.barred]
    verdict = "fail" if any(v == "fail" for _, _, v in barred) else "pass with barred ranges" if barred else "pass"
    lines = [f"- **Shafts, IACS UR M68: {verdict}.** Largest τ/τ_C {w.summary()['largest_tau_over_tau_c']:.3f} "
             f"({w.name})" + ("; barred speed ranges: " + "; ".join(f"{b} ({n})" for n, b, _ in barred)
                              if barred else "; no barred speed range") + "."]
    beyond = [(c, n) for c in cases if c.shafts for n in c.shafts.notes if n.startswith("beyond the rule")]
    if beyond:
        # the worst by its ratio "(r × it)", the others named
        ratio = lambda n: float(n.split(" × it")[0].rsplit("(", 1)[1])  # noqa: E731
        c, n = max(beyond, key=lambda b: ratio(b[1]))
        lines.append(f"- **Above λ 1.05, not judged by the rule,** in {len(beyond)} configuration(s) "
                     f"({', '.join(b[0].name for b in beyond)}); the worst, {c.name}: "
                     f"{n.removeprefix('beyond the rule: ')}.")
    return lines


def _crank_m53_conclusion(outcome: TVCOutcome) -> list[str]:
    """The network's crank against UR M53: normal running decides; the least Q of the other
    configurations beside it, a restriction where below the required."""
    crank = outcome.network.cranks[0].name if outcome.network.cranks else "the crank"
    if not outcome.crank_m53:
        return [f"- **Crankshaft '{crank}': not judged.** {outcome.crank_m53_note[:1].upper()}{outcome.crank_m53_note[1:]}."]
    (name, normal), others = outcome.crank_m53[0], outcome.crank_m53[1:]
    g = normal.governing
    line = (f"- **Crankshaft '{crank}', IACS UR M53 ({name} decides): {'pass' if normal.passes else 'fail'}.** Least Q "
            f"{g.safety:.3f} against the required {g.required:.2f} ({g.name}; torsion from the {g.torque_section} at "
            f"{g.torque_rpm:.0f} rpm).")
    if others:
        n, r = min(others, key=lambda o: o[1].governing.safety / o[1].governing.required)
        w = r.governing
        line += (f" The other configurations' least Q {w.safety:.3f} ({n})"
                 + (": below the required, a restriction for that operation." if w.safety < w.required else "."))
    return [line]


def crank_m53_lines(outcome: TVCOutcome) -> list[str]:
    """The network's crank against UR M53 in each configuration, and normal running's places."""
    if not outcome.crank_m53:
        return []
    lines = ["### Crankshaft against IACS UR M53", "",
             "The crank description's own rule, its torsion the network's synthesised torque through each fillet in "
             "each configuration, its bending the rod forces at the rated speed; normal running decides.", "",
             "| configuration | least Q | required | place | torsion from | at [rpm] |", "|---|---|---|---|---|---|"]
    for name, r in outcome.crank_m53:
        g = r.governing
        lines.append(f"| {name} | {g.safety:.3f} | {g.required:.2f} | {g.name} | {g.torque_section} | {g.torque_rpm:.0f} |")
    return lines + ["", f"![]({outcome.crank_m53_image})", ""]


def _passage_conclusions(outcome: TVCOutcome) -> list[str]:
    """The time-domain start, stop and barred-range passages against their limits: one line, the worst
    section of each named (a line without shaft sections has its couplings only)."""
    if not outcome.passages:
        return []

    def worst(p):
        return max(p.sections, key=lambda s: s.utilisation if math.isfinite(s.utilisation) else -1.0)

    parts = []
    for p in outcome.passages:
        w = worst(p) if p.sections else None
        what = (f"the start {p.from_rpm:.0f}-{p.to_rpm:.0f} rpm at {p.rate_rpm_per_s:g} rpm/s" if p.is_start
                else f"the stop {p.from_rpm:.0f}-{p.to_rpm:.0f} rpm at {p.rate_rpm_per_s:g} rpm/s" if p.is_stop
                else f"{p.configuration}, barred range {p.from_rpm:.0f}-{p.to_rpm:.0f} rpm")
        level = ("no shaft section" if w is None else f"{w.utilisation:.3f} {w.limit_name}"
                 if math.isfinite(w.utilisation) else "no limit above λ 1.05")
        couplings = "".join(f"; coupling '{c.label}' {c.peak_nm:.0f} N m "
                            + (f"({c.peak_nm / c.maximum_nm:.3f} T_Kmax)" if c.maximum_nm else "(no T_Kmax: not judged)")
                            for c in p.couplings)
        where = "" if w is None else f" ({w.label}, {w.peak_pa / 1e6:.1f} N/mm² at {w.peak_rpm:.0f} rpm)"
        parts.append(f"{what}: {p.verdict}, {level}{where}{couplings}")
    judged = any(p.sections or any(c.maximum_nm for c in p.couplings) for p in outcome.passages)
    verdict = ("fail" if any(p.verdict != "within the limits" for p in outcome.passages) else
               "pass" if judged else "not judged")
    text = "; ".join(parts)
    return [f"- **Transient passages in the time domain, UR M68's τ_T (τ_C above λ 0.8): {verdict}.** "
            f"{text[:1].upper()}{text[1:]}."]


def _coupling_conclusions(outcome: TVCOutcome, cases) -> list[str]:
    """Each coupling's largest heat and torque over the configurations against its sheet."""
    if outcome.couplings is None:
        return []
    lines = []
    for k in range(len(outcome.couplings.couplings)):
        rows = [(c, c.couplings.rows()[k]) for c in cases if c.couplings is not None]
        (hc, h), (tc, t) = max(rows, key=lambda x: x[1]["heat_w"]), max(rows, key=lambda x: x[1]["torque_nm"])
        heat = ("not judged (the sheet gives no P_KV)" if h["permissible_power_w"] is None else
                f"{'pass' if h['heat_w'] <= h['permissible_power_w'] else 'fail'} against P_KV "
                f"{h['permissible_power_w']:.0f} W")
        torque = ("not judged (the sheet gives no permissible vibratory torque)" if t["permissible_torque_nm"] is None
                  else f"{'pass' if t['torque_nm'] <= t['permissible_torque_nm'] else 'fail'} against "
                  f"{t['permissible_torque_nm']:.0f} N m")
        lines.append(f"- **Flexible coupling '{h['coupling']}':** heat up to {h['heat_w']:.1f} W ({hc.name}), {heat}; "
                     f"vibratory torque up to {t['torque_nm']:.0f} N m ({tc.name}), {torque}; settled at up to "
                     f"{max(r['temperature_c'] for _, r in rows):.1f} °C.")
    return lines


def _hammering_conclusion(cases) -> list[str]:
    """Gear hammering over the configurations: normal running, the misfires together, each failed damper."""
    if not any(c.hammering is not None for c in cases):
        return []
    groups = {}  # the span of each group's ranges and its worst peak
    for c in cases:
        key = "misfire (any cylinder)" if c.misfire is not None else c.name
        for m in (c.hammering.meshes if c.hammering else ()):
            for r in m.ranges:
                lo, hi, peak, who = groups.get(key, (math.inf, -math.inf, 0.0, ""))
                groups[key] = (min(lo, r["from_rpm"]), max(hi, r["to_rpm"]), *max((peak, who), (r["peak"], c.name)))
    if not groups:
        return ["- **Gear hammering: none.**"]
    return ["- **Gear hammering: possible.** " + "; ".join(
        f"{k} within {lo:.1f}-{hi:.1f} rpm, peak {p:.2f} × mean" + (f" ({w})" if w != k else "")
        for k, (lo, hi, p, w) in groups.items()) + ": a corrective measure, or an acceptance with its reason, is needed."]


def failed_damper_lines(outcome: TVCOutcome) -> list[str]:
    """Each damper failed in each of its states, one row each beside normal running ([LRNavalTV] Ch 1 §1.3)."""
    return _variant_lines(outcome, outcome.failed_dampers, "A failed damper", (
        "Each damper in turn with its ring free (the silicone lost, the rubber torn: the housing or hub left on its "
        "station) and, a viscous one, seized (its ring turning with its housing). A barred range here is the "
        "restriction the line runs under until the damper is mended."))


def tolerance_lines(outcome: TVCOutcome) -> list[str]:
    """Each coupling at both ends of its sheet's stiffness tolerance, one row each beside normal running."""
    return _variant_lines(outcome, outcome.tolerances, "Coupling stiffness at the ends of its tolerance", (
        "Each coupling whose sheet states a tolerance of its dynamic stiffness, at both ends of it (nominal and warm "
        "stiffness alike), one at a time: its modes, crossings and heat move with it."))


def _variant_lines(outcome: TVCOutcome, cases, title: str, text: str) -> list[str]:
    """A subsection of configurations that vary the line, their rows beside normal running's (none: nothing)."""
    if not cases:
        return []
    return [f"### {title}", "", text, ""] + configuration_rows((outcome.normal, *cases)) + [""]


def mode_lines(outcome: TVCOutcome) -> list[str]:
    """The modes with their resonances in the speed range, and each station's relative amplitude."""
    rows = outcome.mode_rows
    lines = ["| mode | frequency [Hz] | [cpm] | resonances in the speed range: order @ engine rpm |", "|---|---|---|---|"]
    lines += [f"| {r.number} | {r.frequency_hz:.3f} | {60 * r.frequency_hz:.0f} | "
              + (", ".join(f"{q:.4g} @ {n:.0f}" for q, n in r.resonances) or "none") + " |" for r in rows]
    blades = "; the blade orders are per engine revolution" if outcome.network.propellers else ""
    lines += ["", f"Relative amplitudes (each mode's physical station angles over its largest{blades}):", "",
              "| station | " + " | ".join(f"mode {r.number}" for r in rows) + " |", "|---|" + "---|" * len(rows)]
    lines += [f"| {name} | " + " | ".join(f"{r.amplitudes[k]:+.3f}".replace("-0.000", "+0.000") for r in rows) + " |"
              for k, name in enumerate(outcome.network.labels)]
    return lines + [""]


def passage_lines(outcome: TVCOutcome) -> list[str]:
    """The time-domain passage of each barred range against τ_T, with its rate and picture."""
    if not outcome.passages:
        return []
    start = any(p.is_start or p.is_stop for p in outcome.passages)
    lines = [f"### {'The start, the stop and the passages' if start else 'Passage'} through the barred ranges (time "
             "domain) against τ_T", "",
             ("The start runs from the speed the engine fires at up to the range's lowest speed at the start's rate "
              "and load ([start]); the stop from the fuel cut down, every cylinder motored, at the coast-down's rate "
              "([stop]); both through every resonance below the range, τ_C holding above λ 0.8. " if start else "")
             + "Run through each barred range from the steady state below it at the stated rate; the half-range "
             "stress over each synthesis period against τ_T at its speed.", ""]
    for p, image in zip(outcome.passages, outcome.passage_images):
        lines += ["```", p.table(), "```", "", f"![]({image})", ""]
    return lines


def tvc_section(crank, outcome: TVCOutcome | Skipped) -> list[str]:
    """The TVC section of the report (module docs)."""
    net = getattr(outcome, "network", crank)
    lines = [f"## {'Propulsion line' if getattr(net, 'propellers', ()) else 'Shaft line'}: torsional vibration "
             "calculation", ""]
    if isinstance(outcome, Skipped):
        return lines + [f"Not computed: {outcome.reason}.", ""]
    res = outcome.modes
    lines += conclusion_lines(outcome) + installation_lines(outcome.network)
    lines += ["### Mass-elastic data", "", "At the couplings' settled temperatures; every value at its own station's speed "
              "(not referred to the engine's), the speed ratio beside it.", ""]
    lines += mass_elastic_lines(outcome.network) + ["", "### Natural frequencies", ""]
    if outcome.mode_rows:
        lines += mode_lines(outcome) + ([f"![]({outcome.campbell_image})", ""] if outcome.campbell_image else [])
    else:
        lines += [", ".join(f"{f:.4g} Hz ({60 * f:.1f} cpm)" for f in res.frequencies_hz), ""]
    if outcome.shafts is not None:
        lines += ["### Shaft stresses against IACS UR M68, barred speed ranges", "", "```", outcome.shafts.table(),
                  "```", "", f"![]({outcome.shaft_image})", ""]
    if outcome.couplings is not None:
        lines += ["### Flexible couplings: vibratory torque and heat", "", "```", outcome.couplings.table(), "```",
                  "", f"![]({outcome.heat_image})", ""]
    if outcome.hammering is not None:
        lines += ["### Gear hammering: vibratory against mean mesh torque", "", "```", outcome.hammering.table(), "```",
                  "", f"![]({outcome.hammering_image})", ""]
    lines += (damper_lines(outcome) + misfire_lines(outcome) + failed_damper_lines(outcome) + tolerance_lines(outcome)
              + passage_lines(outcome) + crank_m53_lines(outcome))
    lines += ["### What is assumed", ""] + [f"- {a}." for a in outcome.assumptions] + [""]
    return lines
