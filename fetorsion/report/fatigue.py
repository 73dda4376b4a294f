"""The Markdown of a crank's fatigue verdict: the fatigue section (both methods in every
configuration, M53's steps, the ``fe`` path's detail) and the verdict's bullets the summary
shares with it (:mod:`fetorsion.report.summary`). Presents, computes nothing."""

from __future__ import annotations

from ..description.model import Crank
from ..design.bridge import DISAGREEMENT as BRIDGE_DISAGREEMENT
from ..design.bridge import FACTORS as BRIDGE_FACTORS
from ..design.recovered import BENDING_FLAG
from .outcomes import Skipped


def damper_spec(d) -> str:
    """A damper's design as one phrase: its ring inertia, and its stiffness, loss factor and
    damping where it has them.

    Parameters
    ----------
    d : damper design
        Its ``ring_inertia`` (kg m^2), ``stiffness`` (N m/rad), ``loss_factor`` and ``damping``
        (N m s/rad); a zero or None term is left out.
    """
    return (f"ring {d.ring_inertia:.4g} kg m^2" + (f", stiffness {d.stiffness:.4g} N m/rad" if d.stiffness else "")
            + (f", loss factor {d.loss_factor:.3g}" if d.loss_factor else "")
            + (f", damping {d.damping:.4g} N m s/rad" if d.damping else ""))


def bending_lines(v) -> list[str]:
    """The verdict's bending, as summary bullets: the bending damping and its source (with both
    methods at two bending damping ratios where it is assumed), and every fillet whose vibratory
    bending is beyond the statically determinate throw's (M53's)."""
    b = v.bending
    if not b:
        return []
    out = [f"- **Bending damping:** ζ_b = {b['ratio']:.4g} on the bending modes, "
           + (f"**{b['source']}**" if b["assumed"] else f"from {b['source']}")
           + ("" if not b.get("sensitivity") else
              "; the deciding safeties at " + ", ".join(
                  f"ζ_b = {x['bending_damping_ratio']:.2f}: "
                  + ", ".join(f"{k} {q:.2f}" for k, q in x.items() if k != "bending_damping_ratio")
                  for x in b["sensitivity"]) + " (torsional ζ held; the crank as described)") + "."]
    flags = v.bending_flags()
    if flags:
        worst = max(flags, key=lambda f: f[1]["ratio"])
        c, f = worst
        out.append(f"- **Bending beyond the rule:** {len({x['name'] for _, x in flags})} fillet(s) carry a vibratory "
                   "bending over "
                   f"{BENDING_FLAG:g}× the statically determinate throw's; the largest, {f['name']} ({c}): "
                   f"{f['vibratory_nm'] / 1e3:.2f} kN m at {f['rpm']:.0f} rpm against {f['determinate_nm'] / 1e3:.2f} kN m "
                   f"({f['ratio']:.2f}×). M53's bending is the determinate throw's: it does not cover this; the fe path "
                   "carries it.")
    return out


def bridge_lines(v) -> list[str]:
    """The two methods term by term (:mod:`fetorsion.design.bridge`): per configuration and
    governing place, fe's safety over M53's and the five factors whose product it is."""
    rows = [(c.name, p) for c in v.configs if c.bridge for p in c.bridge["places"]]
    if not rows:
        return []
    out = ["**From M53 to the `fe` path, term by term** (each factor above 1 makes `fe` the safer; their product "
           "is the ratio of the safeties at the place): load (M53's loads and σ_add against the crank's cycle, both "
           "recovered), stress (the rule's SCFs against the recovery on M53's loads), combination (Findley against "
           "the von Mises amplitude), strength (f₋₁ against σ_DW), mean (Findley with the signed mean against "
           "without):", "",
           "| configuration | fe place | M53 place | fe | M53 | fe/M53 | load | stress | combination | strength | mean "
           "| product |", "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, p in rows:
        f = p["factors"]
        out.append(f"| {name} | {p['fe_place']} | {p['m53_place']} | {p['fe_safety']:.2f} | {p['m53_safety']:.2f} | "
                   f"**{p['ratio']:.3f}** | " + " | ".join(f"{f[k]:.3f}" for k in BRIDGE_FACTORS)
                   + f" | {p['product']:.3f} |")
    return out + [""]


def disagreement_lines(v) -> list[str]:
    """One summary bullet for the configurations where the two methods' governing safeties are
    further apart than :data:`fetorsion.design.bridge.DISAGREEMENT`, each with the factor that
    carries most of it at the ``fe`` path's governing place."""
    rows = []
    for c in v.configs:
        b = c.bridge
        if b and b["disagrees"] and b["places"]:
            p = b["places"][0]
            rows.append(f"{c.name}: fe {b['fe_safety']:.2f} against {b['m53_safety']:.2f} "
                        f"({100 * (b['ratio'] - 1):+.0f} %), at {p['fe_place']} **{b['carried_by']}** "
                        f"{p['factors'][b['carried_by']]:.2f}")
    if not rows:
        return []
    return [f"- **The methods disagree** (beyond ±{100 * BRIDGE_DISAGREEMENT:.0f} %) in {len(rows)} configuration(s), "
            "the factor that carries most of each named: " + "; ".join(rows)
            + " (the fatigue section's bridge table has all five factors)."]


def fatigue_section(crank: Crank, outcome) -> list[str]:
    """A crank's verdict: every configuration by the deciding method with the other beside it, the
    damping and where it comes from, the flip damping ratio and the band, the recommended damper,
    M53's steps, the SCFs against the rule's formulas, the fe path's detail and the torsional
    stress it started from."""
    if isinstance(outcome, Skipped):
        return ["## Verdict: fatigue of the fillets and oil bores", "", f"Not run: {outcome.reason}.", ""]
    v, a = outcome.verdict, outcome.assessment
    lines = _configurations_lines(v, a, outcome.model, crank)
    lines += ["", f"**Damping sensitivity** (the crank as described): {v.flip.kind}; across the band "
              + ", ".join(f"ζ = {b['damping_ratio']:.4g}: safety {b['safety']:.2f}" for b in v.band)
              + f" ({crank.excitation.damping_source}).", ""] + bending_lines(v) + [""]
    lines += _bending_table_lines(v)
    lines += _recommended_damper_lines(v)
    lines += _m53_lines(v)
    lines += _fe_path_lines(v, a)
    if outcome.stress is not None:
        lines += ["The vibratory torsional stress at the fillets that both methods start from (SCF × 16 T D / "
                  "(π (D⁴ − d⁴)) of the synthesised section torque; an input, not a verdict):", "", "```",
                  outcome.stress.table(), "```", ""]
    return lines + [f"![]({im})" for im in outcome.images] + [""]


def _configurations_lines(v, a, model: str, crank: Crank) -> list[str]:
    """The section's heading, the model, method, damping and material, and the table of every configuration."""
    if a is None:  # the fe path left out: its material (defaults filled in) was not assessed
        beside = f"{v.other} was left out (a design loop's confirming run reads the deciding method alone)"
        material = f"Material: {crank.material.name} (the description's)."
    else:
        mat = a.worst.material
        beside = f"{v.other} is shown beside it"
        material = (f"Material: {mat.name}, R_m {mat.tensile_strength / 1e6:.0f} MPa, R_e {mat.yield_strength / 1e6:.0f} "
                    f"MPa ({mat.source or 'the description'}).")
    lines = ["## Verdict: fatigue of the fillets and oil bores", "",
             f"Computed on the **{model}**. **{v.method}** decides; {beside}. Damping: modal damping ratio "
             f"**ζ = {v.damping_ratio:.4g}** ({v.damping_source}). {material}", "",
             f"| configuration | {v.method}: safety | required | governing | at rpm | verdict | {v.other}: safety "
             f"| required | its governing |", "|---|---|---|---|---|---|---|---|---|"]
    for c in v.configs:
        x, y = c.answer(v.method), c.answer(v.other)
        lines.append(f"| {c.name} | **{x.safety:.2f}** | {x.required:.2f} | {x.location} ({x.where}) | "
                     f"{x.rpm:.0f} | **{'pass' if x.passes and c.heat_ok else 'FAIL'}**"
                     + ("" if c.heat_ok else f" (damper heat {c.damper_power_w:.0f} W over {c.allowed_power_w:.0f} W)")
                     + " | "
                     + (f"{y.safety:.2f} | {y.required:.2f} | {y.location} |" if y else "- | - | - |"))
    return lines


def _bending_table_lines(v) -> list[str]:
    """The vibratory bending of each fillet against the determinate throw's (none: no lines)."""
    lines = []
    first = next((c for c in v.configs if c.bending), None)
    bent = first.bending if first is not None else []
    if bent:
        lines += [f"Vibratory bending in each fillet's throw plane ({first.name}, the crank as described; the largest "
                  "half peak-to-peak over the speeds) against the statically determinate throw's under the rod force's "
                  "alternating radial part at the rated speed (M53's bending; its misfire rows are in results.json):", "",
                  "| fillet | vibratory [kN m] | at rpm | determinate [kN m] | ratio |", "|---|---|---|---|---|"]
        lines += [f"| {b['name']} | {b['vibratory_nm'] / 1e3:.3f} | {b['rpm']:.0f} | {b['determinate_nm'] / 1e3:.3f} | "
                  f"{'**' if b['flag'] else ''}{b['ratio']:.2f}{'**' if b['flag'] else ''} |" for b in bent] + [""]
    return lines


def _recommended_damper_lines(v) -> list[str]:
    """The damper designed for this verdict, with its heat (none designed: no lines)."""
    lines = []
    if v.damper is not None and v.damper.optimised is not None:
        d = v.damper.optimised
        rec = [c for c in v.configs if c.recommended and c.misfire is None]
        heat = f"; its heat at the worst speed {rec[0].damper_power_w:.1f} W (no rating given)" if rec else ""
        lines += [f"**Recommended damper**, designed for this verdict (Den Hartog's start on mode 1, "
                  f"{v.damper.mode_hz:.1f} Hz, then its stiffness and loss optimised on the whole crank to make M53's "
                  f"governing safety as large as it can be, ring inertia held at μ = {v.damper.mu:g}): "
                  f"{damper_spec(d)}{heat}.", ""]
    return lines


def _m53_lines(v) -> list[str]:
    """IACS UR M53 as written on the crank as described (firing): each place's stresses and safety,
    the nominal stresses of each throw, and fetorsion's FE SCFs against the rule's formulas."""
    m = next(c for c in v.configs if c.as_described).m53
    lines = ["### IACS UR M53, as written ([KR-M53])", "",
             "| place | σ_B (bending) [MPa] | τ or σ_T (torsion) [MPa] | σ_add [MPa] | σ_V [MPa] | σ_DW [MPa] | Q | "
             "required | SCFs |", "|---|---|---|---|---|---|---|---|---|"]
    for loc in m.locations:
        lines.append(f"| {loc.name} | {loc.bending / 1e6:.1f} | {loc.torsion / 1e6:.1f} | {loc.additional / 1e6:.0f} | "
                     f"{loc.equivalent / 1e6:.1f} | {loc.strength / 1e6:.1f} | **{loc.safety:.2f}** | {loc.required:.2f} | "
                     + ", ".join(f"{k} {val:.3f}" for k, val in loc.scfs.items()) + " |")
    for name, nom in m.nominal.items():
        per_throw = nom.get("cylinders", [])
        rods = ("" if all(len(c) < 2 for c in per_throw) else " (each throw's rods superposed with their phases: "
                + ", ".join(f"cylinders {' and '.join(map(str, c))}" for c in per_throw) + ")")
        lines += ["", f"{name}{rods}: σ_BFN {nom['sigma_BFN_pa'] / 1e6:.2f} MPa, σ_QFN {nom['sigma_QFN_pa'] / 1e6:.2f} MPa "
                  f"(web section B {nom['B_m'] * 1e3:.1f} × W {nom['W_m'] * 1e3:.1f} mm), σ_BON {nom['sigma_BON_pa'] / 1e6:.2f} MPa; "
                  f"τ_N {nom['tau_N_pin_pa'] / 1e6:.2f} MPa (pin, M_TN {nom['M_TN_pin_nm']:.1f} N m), "
                  f"{nom['tau_N_journal_pa'] / 1e6:.2f} MPa (journal, M_TN {nom['M_TN_journal_nm']:.1f} N m); SCF sources: "
                  + "; ".join(f"{k}: {src}" for k, src in m.scf_source[name].items()) + "."]
    lines += [""] + [f"- {n}" for n in m.notes] + ["",
              "Fetorsion's FE SCFs in M53's convention (Appendix III: von Mises over the web section's M/(B W²/6) "
              "for bending, the largest shear over τ_N for torsion; oil bore: peak principal stress) against the "
              "rule's formulas:", "", "| factor | FE | M53 formula | FE / formula − 1 | formula's range |",
              "|---|---|---|---|---|"]
    for k, row in v.scf_m53.items():
        fe = "-" if row["fe"] is None else f"{row['fe']:.3f}"
        diff = "-" if row["difference"] is None else f"{100 * row['difference']:+.1f} %"
        lines.append(f"| {k} | {fe} | {row['empirical']:.3f} | {diff} | "
                     f"{'inside' if row['in_range'] else 'OUTSIDE: ' + '; '.join(row['outside'])} |")
    return lines


def _fe_path_lines(v, a) -> list[str]:
    """The ``fe`` path's detail: its table, its recovery on M53's loads, the bridge to M53, the notes."""
    if a is None:
        return ["", "### fetorsion's own path (`fe`)", "", "Left out of this run: `fetorsion run` on the same "
                "description gives it.", ""] + [f"- {n}" for n in v.notes] + [""]
    lines = ["", "### fetorsion's own path (`fe`)", "",
             "The condensed crank's fillet sections over the cycle (mean of the gas and inertia forces solved "
             "statically, every vibratory order, the resonant bending included) drive the local stress recovered "
             "at every surface node of each fillet (its throw under six unit end loads) and oil bore (a bar with "
             "the drilling under the same six); Findley's critical plane on planes through the surface, the mean "
             "with its sign ([Findley], [Socie]); the local strength f₋₁ = S_e · K_t/K_f ([Budynas]). The crank as "
             "described, each place at its worst speed (σ_vM: von Mises amplitude and signed mean at the governing "
             "node; Findley: the damage τ_a + k σ_n,max against its limit):", "", "```", a.table(), "```", ""]
    if v.same_load:
        lines += ["The recovery on M53's own loads (the statically determinate throw at the rated speed, M_TN in "
                  "phase, no mean, no σ_add): σ_V of the `fe` path against the rule's, "
                  + "; ".join(f"{k}: {x['fe_sigma_v_pa'] / 1e6:.1f} against {x['m53_sigma_v_pa'] / 1e6:.1f} MPa "
                              f"({100 * (x['ratio'] - 1):+.1f} %"
                              + (f"; {100 * (x['ratio_fe_scf'] - 1):+.1f} % against the rule's combination with "
                                 "fetorsion's FE SCFs in its convention, Appendix III" if "ratio_fe_scf" in x else "")
                              + ")" for k, x in v.same_load.items())
                  + ". What is left of the two methods' difference is load, strength and mean, not the stress at the notch.", ""]
    lines += bridge_lines(v)
    lines += [""] + [f"- {n}" for n in a.notes + v.notes] + [""]
    return lines
