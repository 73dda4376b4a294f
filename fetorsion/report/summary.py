"""The report's summary: the answers first, each naming the model it comes from, then the
verdict's table. Presents what the run's steps computed, computes nothing."""

from __future__ import annotations

from ..modes import F1_TORSION_SHARE, TORSION_SHARE_NOTED
from .fatigue import bending_lines, damper_spec, disagreement_lines
from .outcomes import RunOutcome, SensitivityOutcome, Skipped, VerdictOutcome


#: The modes below the headline f1 listed by name in the summary.
BELOW_F1_LISTED = 8


def _coupled_below(modal, f1: float) -> float | None:
    """The first free-free mode with :data:`TORSION_SHARE_NOTED` torsion when it lies below the first
    mostly torsional one ``f1`` (Hz), else None."""
    from ..errors import FetorsionError

    try:
        f = modal.first_carrying_torsion(TORSION_SHARE_NOTED)
    except FetorsionError:
        return None
    return f if f < f1 * (1 - 1e-9) else None


def summary_lines(run: RunOutcome) -> list[str]:
    """The answers first, each naming the model it comes from: free-free f1 against the
    measurement with the reconstruction's band, f1 in the engine, the worst location and its
    margin, the recommended damper, the barred ranges."""
    crank, out = run.crank, []
    measured = getattr(crank, "measured_f1_hz", None)  # a chain file has none
    if run.fe is not None:
        out += _fe_summary(run.fe, measured, run.sensitivity)
    if run.bearings is not None:
        out += _bearings_summary(run.bearings)
    if isinstance(run.verdict, VerdictOutcome):
        out += _verdict_summary(run.verdict)
    fat = run.fatigue
    if fat is not None and not isinstance(fat, Skipped):
        out += _fatigue_summary(fat)
    mea = run.measured
    if mea is not None and not isinstance(mea, Skipped):
        out += _measured_summary(mea)
    table = verdict_table(fat.verdict) if fat is not None and not isinstance(fat, Skipped) else []
    return ["## Summary", "", *out, "", *table] if out else []


def _fe_summary(fe, measured: float | None, sens) -> list[str]:
    """Free-free f1 of the 3D FE against the measurement, a coupled mode below it, the inputs' band."""
    f1 = fe.modal.first_torsional()
    line = f"- **Free-free f1: {f1:.1f} Hz** (3D FE, {fe.modal.dofs} DOF)"
    if measured:
        line += f"; measured {measured:g} Hz ({100 * (f1 / measured - 1):+.1f} %)"
    coupled = _coupled_below(fe.modal, f1)
    if coupled:
        line += (f"; below it a mode coupled with bending at {coupled:.1f} Hz carries at least "
                 f"{100 * TORSION_SHARE_NOTED:.0f} % of its kinetic energy in torsion: the engine's torque drives it "
                 "first")
    if isinstance(sens, SensitivityOutcome) and sens.studies:
        b = sens.studies["montecarlo"].bands["f1"]
        line += (f"; the reconstruction's inputs put f1 at {b['p5']:.0f}–{b['p95']:.0f} Hz (5–95 %, "
                 f"{sens.studies['montecarlo'].model} Monte Carlo)")
    return [line + "."]


def _bearings_summary(bearings) -> list[str]:
    """f1 in the engine (the condensed crank in its bearings) and every mode below it."""
    b = bearings.condensed.main_bearings
    support = ("rigid main bearings" if b.rigid else "oil-film main bearings" if b.oil_film is not None
               else "the [bearings] stiffness")
    held = bearings.bearings
    # the headline is the first mode the engine's torque drives with a real share of torsion;
    # every mode below it is named, so a coupled bending mode is never hidden behind it
    f1 = held.first_carrying_torsion(F1_TORSION_SHARE)
    below = [(f, k, t) for f, k, t in zip(held.frequencies_hz, held.kinds, held.fractions[:, 0]) if f < f1]
    line = (f"- **f1 in the engine: {f1:.1f} Hz** (condensed crank in {support}, "
            f"{bearings.condensed.reduced_dofs} DOF; {100 * (f1 / bearings.f1_free_hz - 1):+.1f} % on free-free; "
            f"the first mode with at least {100 * F1_TORSION_SHARE:.0f} % of its kinetic energy in torsion")
    if abs(f1 - bearings.f1_bearings_hz) > 1e-6 * f1:
        line += f"; the first mostly torsional one is at {bearings.f1_bearings_hz:.1f} Hz"
    line += ")"
    if below:
        shown = below[:BELOW_F1_LISTED]
        line += (f". Below it, {len(below)} mode(s) of the crank in its bearings: "
                 + ", ".join(f"{f:.1f} Hz ({k}, {100 * t:.0f} % torsion)" for f, k, t in shown)
                 + (f" and {len(below) - len(shown)} more" if len(below) > len(shown) else "")
                 + "; the forced response and the verdict carry every one of them")
    return [line + "."]


def _verdict_summary(ver) -> list[str]:
    """A chain's or network's verdict: the worst place undamped, the recommended damper, the barred ranges."""
    out = []
    unit, scale = ver.verdict.unit
    rows = ver.verdict.rows()
    r = rows[0]
    out.append(f"- **Worst {'location' if ver.verdict.limits.kind == 'stress' else 'section'} without a damper: {r['worst_section']} at {r['worst_rpm']:.0f} rpm, "
               f"{r['value'] / scale:.4g} {unit} against {r['limit'] / scale:.4g} {unit}: margin "
               f"{100 * r['margin']:+.1f} %, {r['verdict']}** ({ver.model or 'lumped chain'}).")
    designed = [row for row in rows if row["case"] in ver.verdict.designs]
    if designed:
        best = min(designed, key=lambda row: row["value"])
        d = ver.verdict.designs[best["case"]]
        spec = damper_spec(d)
        out.append(f"- **Recommended damper: {best['case']}** ({spec}): worst {best['value'] / scale:.4g} {unit}, "
                   f"margin {100 * best['margin']:+.1f} %, {best['verdict']} ({ver.model or 'lumped chain'}).")
    bars = [f"{b['from_rpm']:.0f}-{b['to_rpm']:.0f} rpm" for b in r["barred_ranges"]]
    out.append(f"- **Barred speed ranges without a damper:** {', '.join(bars) or 'none'} "
               f"(checked {r['speed_range_rpm'][0]:.0f}-{r['speed_range_rpm'][1]:.0f} rpm, to overspeed; "
               f"{ver.model or 'lumped chain'}).")
    return out


def _fatigue_summary(fat) -> list[str]:
    """A crank's fatigue verdict: what decides, damping, bending, the methods' disagreement, damper, material."""
    out = []
    v = fat.verdict
    decide = [c.name for c in v.configs if c.as_described]
    out.append(f"- **The crank as described: {'PASS' if v.passes else 'FAIL'}** by {v.method}, ζ = "
               f"{v.damping_ratio:.4g} ({v.damping_source}) (decided by: "
               f"{'; '.join(decide)}; the other rows inform: no damper where it has one, the recommended damper).")
    out.append(f"- **Verdict per configuration:** the table below ({fat.model}).")
    out.append(f"- **Damping:** the verdict rests on ζ = {v.damping_ratio:.4g}, "
               + ("**assumed** (no source stated)" if v.damping_assumed else f"from {v.damping_source}")
               + "; " + (f"it {v.flip.kind}" if v.flip.zeta is None or v.flip.zeta <= v.damping_ratio
                         else f"as described it would pass from ζ = {v.flip.zeta:.4g} up") + ".")
    out += bending_lines(v) + disagreement_lines(v)
    if v.damper is not None and v.damper.optimised is not None:
        out.append(f"- **Recommended damper:** {damper_spec(v.damper.optimised)}, designed for the iacs-m53 "
                   "verdict's governing safety" + ("" if v.method == "iacs-m53" else
                                                   f" and checked by the deciding {v.method} method")
                   + " (its line above).")
    mat = None if fat.assessment is None else fat.assessment.worst.material
    if mat is not None and fat.assessment.worst.defaulted:
        out.append(f"- **Material assumed:** the description gives no strength; {mat.name}, R_m "
                   f"{mat.tensile_strength / 1e6:.0f} MPa, R_e {mat.yield_strength / 1e6:.0f} MPa ({mat.source}).")
    return out


def _measured_summary(mea) -> list[str]:
    """The model against the measured frequencies and order cuts."""
    out = []
    for f in mea.comparison.frequencies:
        d = f.difference_percent
        out.append(f"- **Measured frequencies: {len(d)} modes, model ({f.source}) {d.min():+.1f} to {d.max():+.1f} %** "
                   f"against the modal test.")
    for c in mea.comparison.order_cuts:
        p = c.peaks()
        out.append(f"- **Order {c.order:g} at {c.station} ({c.name}): model peak {p['peak_difference_percent']:+.1f} %, "
                   f"{p['peak_rpm_difference']:+.0f} rpm** against the measurement "
                   f"({mea.comparison.model or 'lumped chain'}).")
    return out


def verdict_table(v) -> list[str]:
    """The verdict as one row per configuration: whether it decides, the deciding method's
    governing place and speed, its safety against the required and the result, the other
    method's safety beside it."""
    rows = [f"| configuration | decides | {v.method}: governing place | rpm | safety | required | result "
            f"| {v.other} |", "|---|---|---|---:|---:|---:|---|---:|"]
    for c in v.configs:
        a, b = c.answer(v.method), c.answer(v.other)
        result = "pass" if a.passes else "**FAIL**"
        if not c.heat_ok:
            result = f"**FAIL** (damper heat {c.damper_power_w:.0f} W over {c.allowed_power_w:.0f} W)"
        elif a.yielding:
            result += f" (YIELDING at {', '.join(a.yielding)})"
        other = f"{b.safety:.2f}" if b else "—"
        rows.append(f"| {c.name} | {'yes' if c.as_described else 'informs'} | {a.location} ({a.where}) "
                    f"| {a.rpm:.0f} | {a.safety:.2f} | {a.required:.2f} | {result} | {other} |")
    return [f"Verdict by {v.method}, ζ = {v.damping_ratio:.4g} ({v.damping_source}); the rows marked 'yes' "
            f"decide, the others inform; {v.other} is shown beside, against its own required "
            f"{getattr(v.configs[0].answer(v.other), 'required', float('nan')):.2f}:", "", *rows, ""]
