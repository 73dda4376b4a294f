"""The report as Markdown: presents what the run's steps computed, computes nothing.

Each section function takes a step's typed outcome (:mod:`fetorsion.report.outcomes`: results
objects and picture file names) and returns its lines; :func:`report_markdown` puts the
sections of a run together. A second format (the web page, :mod:`.html`) takes the same
outcomes.
"""

from __future__ import annotations

import math
from pathlib import Path

from ..description.model import Crank
from ..excitation.campbell import zeta_text
from ..design.bridge import DISAGREEMENT as BRIDGE_DISAGREEMENT
from ..design.bridge import FACTORS as BRIDGE_FACTORS
from ..design.recovered import BENDING_FLAG
from ..lumped_model.lumped import PARTITIONS
from ..modes import F1_TORSION_SHARE, TORSION_SHARE_NOTED
from .outcomes import (BearingsOutcome, CampbellOutcome, ChainOutcome, FEOutcome, LumpedOutcome, RunOutcome,
                       SensitivityOutcome, Skipped, TransientOutcome, VerdictOutcome)



def _with_error(f: float, measured) -> str:
    return f"{f:.1f}" + (f" ({100 * (f / measured - 1):+.1f} %)" if measured else "")


def lumped_section(crank: Crank, outcome: LumpedOutcome | ChainOutcome) -> list[str]:
    """f1 of every partition and web method against the measurement; the 17-DOF shapes (a chain: its modes)."""
    if isinstance(outcome, ChainOutcome):
        res = outcome.chain
        if res.network is not None:
            net = res.network
            parts = [f"`{c.name}`: {c.crank.name} ({c.partition}-DOF lumped model, {c.web_method} webs, from "
                     f"`{c.crank.source}`)" for c in getattr(crank, "cranks", ())]
            return (["## Torsional network (stations, shafts and gears from the file)", "",
                     f"{len(net.labels)} stations, {res.dof} coordinates after the gears, "
                     f"{'grounded' if net.grounded else 'free-free'}."]
                    + ([f"Crank part: {p}." for p in parts]) + ["", "```", res.table(), "```", "",
                    f"Mode shapes in the coordinates (one per gear group), unit at the first: ![]({outcome.image})", ""])
        return ["## Torsional chain (inertias and stiffnesses from the file)", "",
                f"{res.dof} inertias, free-free.", "", "```", res.table(), "```", "",
                f"Mode shapes, unit twist at the first station: ![]({outcome.image})", ""]
    table, skipped = outcome.table, outcome.skipped
    measured = crank.measured_f1_hz
    paper = crank.paper_lumped_f1_hz
    lines = ["## Lumped models (BICERA-style equivalent lengths)", "",
             "First torsional frequency f1 (Hz), free-free; error against the measurement where there is one.", ""]
    lines += ["| model | " + " | ".join(table) + (" | paper |" if paper else " |"),
              "|" + "---|" * (len(table) + 1 + bool(paper))]
    for i, d in enumerate(PARTITIONS):
        cells = [_with_error(table[m][i].frequencies_hz[0], measured) for m in table]
        lines.append(f"| {d} DOF | " + " | ".join(cells) + (f" | {paper.get(str(d), '')} |" if paper else " |"))
    if measured:
        lines += ["", f"Measured (free-free modal test): **{measured:g} Hz**."]
    lines += [f"Web method `{m}` not used: {why}" for m, why in skipped.items()]
    lines += ["", f"17-DOF mode shapes (Carter webs), unit twist at the pulley end: ![]({outcome.image})", ""]
    return lines


def fe_section(crank: Crank, outcome: FEOutcome) -> list[str]:
    """Mesh, solver and timings, f1 against the measurement, every mode with its label."""
    res, size = outcome.modal, outcome.mesh_size_m
    quality = res.mesh.quality if res.mesh is not None else None
    # two significant digits: a valid but poor element (SICN 1e-4) must not read as 0.000
    sicn = f"{quality.min_sicn:.2g}" if quality else "n/a"
    if quality and quality.straightened:
        sicn += f" ({quality.straightened} folded elements straightened)"
    measured = crank.measured_f1_hz
    paper_fe = crank.paper_fe_f1_hz
    t = res.timings_s
    step = getattr(crank, "solid_step", None)
    solid = (f"Solid: the CAD solid `{Path(step).name}` ([solid] step; its header's unit, crank axis x, cut into "
             "parts at the description's journal, web and pin planes; fillets and drillings found on it by their "
             "faces). " if step else "")
    lines = ["## 3D FE modal analysis (Gmsh + scikit-fem, curved P2 tetrahedra)", "",
             solid + f"Mesh: {res.elements} ten-node tetrahedra, {res.nodes} nodes, {res.dofs} DOF, global size "
             f"{size * 1e3:g} mm (finer at fillets and drillings), minimum SICN {sicn}. Solver "
             f"{res.backend}/{res.method}; assembly {t.get('assembly', 0):.1f} s, factorisation "
             f"{t.get('factorize', 0):.1f} s, eigen-solve {t.get('eigensolve', 0):.1f} s.", "",
             f"**First torsional mode: {_with_error(res.first_torsional(), measured)} Hz**"
             + (f" (paper's ANSYS: {paper_fe:g} Hz)" if paper_fe else "")
             + (f"; measured {measured:g} Hz." if measured else "."), "",
             "| mode | f (Hz) | kind | torsion | bending | axial |", "|---|---|---|---|---|---|"]
    lines += [f"| {j + 1} | {f:.1f} | {k} | {fr[0]:.2f} | {fr[1]:.2f} | {fr[2]:.2f} |"
              for j, (f, k, fr) in enumerate(zip(res.frequencies_hz, res.kinds, res.fractions))]
    lines += ["", "Rigid-body roots (Hz): " + ", ".join(f"{f:.1e}" for f in res.rigid_body_hz), ""]
    if outcome.solid_image:
        lines += ["What was found on the CAD solid (check it): journals blue, pins orange, fillets red, drillings "
                  "green.", "", f"![]({outcome.solid_image})", ""]
    if outcome.solid_features is not None:
        lines += solid_features_lines(outcome.solid_features)
    return lines + [f"![]({img.file})" for img in outcome.images] + [""]


def solid_features_lines(found) -> list[str]:
    """The journals, pins, fillets and drillings found on a CAD crank's solid
    (:class:`~fetorsion.solid.recognise.SolidFeatures`), and where its fillets differ from the
    description's radius, which radius decides what."""
    from ..solid.recognise import DIAMETER_TOL, FILLET_TOL

    def cyl(c):
        where = f" at {round(math.degrees(c.angle)) % 360:d}°" if c.part.startswith("pin") else ""
        return f"{c.part} {c.diameter * 1e3:.2f} mm{where}"

    holes = sorted({f"{d.diameter * 1e3:.2f}" for d in found.drillings})
    lines = [f"Found on `{found.step}` (each agrees with the description within {DIAMETER_TOL:.0%}): journals "
             + ", ".join(cyl(c) for c in found.journals) + "; pins " + ", ".join(cyl(c) for c in found.pins)
             + f"; {len(found.drillings)} drilling faces" + (f" ({', '.join(holes)} mm)" if holes else "")
             + (f"; {found.other_tori} toroidal faces that round no journal or pin end" if found.other_tori else "")
             + ". Fillets (the concave toroidal faces at each journal and pin end, one fillet per end however "
             "many faces it has; its smallest minor radius):", "",
             "| end | x (mm) | smallest radius (mm) | faces | description (mm) |", "|---|---|---|---|---|"]
    lines += [f"| {f.end} | {f.x * 1e3:.2f} | {f.radius * 1e3:.2f} | {f.faces} | {f.described * 1e3:.2f}"
              + (" (differs)" if f.differs else "") + " |" for f in found.fillets]
    off = [f for f in found.fillets if f.differs]
    if off:
        radii = ", ".join(sorted({f"{f.radius * 1e3:.2f} mm" for f in off}))
        lines += ["", f"**{len(off)} of the solid's {len(found.fillets)} fillets differ from the description's radius by "
                  f"more than {FILLET_TOL:.0%}** (smallest on the solid: {radii}). The M53 and textbook fillet SCFs "
                  "(the verdict's default method) take the description's radius (`[fillets]`); the FE meshes the "
                  "solid's own fillets, refined on every toroidal face. To have the formulas take the solid's "
                  "radius, state it in `[fillets]`."]
    return lines + [""]


def bearings_section(crank: Crank, outcome: BearingsOutcome) -> list[str]:
    """The condensed crank free and in its bearings; the lumped chain against both; the coupled response."""
    cc, free, held = outcome.condensed, outcome.free, outcome.bearings
    b = cc.crank.main_bearings  # with an oil film's loads found from the crank's forces
    support = ("rigid main bearings (no `[bearings]` table: the default)" if not b.given else
               "main bearings of the `[bearings]` table: " + ", ".join("rigid" if k == float("inf") else f"{k:.3g} N/m"
                                                                        for k in b.radial_stiffness))
    film = getattr(b, "oil_film", None)
    if film is not None:
        support += (f" — oil films (short-bearing linearised coefficients [Friswell], mean of the two direct terms) "
                    f"at {film.speed * 30 / math.pi:.0f} rpm, viscosity {film.viscosity:g} Pa s, "
                    "eccentricity ratios " + ", ".join(f"{e:.2f}" for e in film.eccentricity)
                    + ", damping " + ", ".join(f"{c:.3g}" for c in b.radial_damping) + " N s/m")
    measured = crank.measured_f1_hz
    lines = ["## The crank in its bearings (condensed 3D FE, torsion and bending coupled)", "",
             f"The FE crank of the previous section condensed (Craig–Bampton, distributing couplings) to "
             f"{len(cc.labels)} masters ({', '.join(cc.labels)}): {cc.reduced.size} DOF from {cc.full_dofs} "
             f"({sum(v for k, v in cc.timings_s.items() if k not in ('total', 'meshing')):.1f} s). "
             f"In the engine: {support}. Free-free is what a modal test measures"
             + (f" (measured {measured:g} Hz)" if measured else "") + "; the Campbell diagram below uses the "
             "modes in bearings.", "",
             f"**First torsional mode: free-free {outcome.f1_free_hz:.1f} Hz, in bearings "
             f"{outcome.f1_bearings_hz:.1f} Hz ({100 * (outcome.f1_bearings_hz / outcome.f1_free_hz - 1):+.1f} %).**",
             "", "| mode | free (Hz) | kind (torsion/bending) | in bearings (Hz) | kind (torsion/bending) |",
             "|---|---|---|---|---|"]
    for j in range(min(8, len(free.frequencies_hz), len(held.frequencies_hz))):
        lines.append(f"| {j + 1} | {free.frequencies_hz[j]:.1f} | {free.kinds[j]} ({free.fractions[j, 0]:.2f}/"
                     f"{free.fractions[j, 1]:.2f}) | {held.frequencies_hz[j]:.1f} | {held.kinds[j]} "
                     f"({held.fractions[j, 0]:.2f}/{held.fractions[j, 1]:.2f}) |")
    lines += ["", "The 17-DOF torsional chain against the condensed crank (f1): `fe-held` takes each throw's "
              "stiffness inside the whole crank in rigid bearings (statically indeterminate), `fe` a single "
              "throw loaded by a couple (statically determinate: holding it sideways changes nothing).", "",
              "| web method | 17-DOF f1 (Hz) | vs free-free FE | vs FE in bearings |", "|---|---|---|---|"]
    lines += [f"| {m} | {c['f1_hz']:.1f} | {100 * c['vs_free']:+.1f} % | {100 * c['vs_bearings']:+.1f} % |"
              for m, c in outcome.chain.items()]
    lines += ["", "A torsion-only chain cannot carry the inertia of the throws bending between the bearings: the "
              "in-bearing torsional mode still has a bending share (table above).", ""]
    if outcome.coupled is not None:
        lines += ["Forced response of the condensed crank in its bearings (all orders synthesised; vibratory "
                  "amplitudes; bearing forces and bending moments: the largest vibratory magnitude over the cycle):",
                  "", "```", outcome.coupled.table(), "```", ""]
    return lines + [f"![]({img})" for img in outcome.images] + [""]


def _major_orders_line(crank) -> str:
    """The engine's major orders: where every cylinder's torque adds in phase on a rigid crank."""
    from ..excitation.campbell import CAMPBELL_HIGHEST_ORDER, major_orders

    orders = major_orders(crank.engine)
    listed = ", ".join(f"{q:g}" for q in orders) if len(orders) else "none (the firing is uneven)"
    return (f"Major orders of this {crank.engine.cylinders}-cylinder {crank.engine.layout} engine, where every "
            f"cylinder's torque adds in phase on a rigid crank (to order {CAMPBELL_HIGHEST_ORDER:g}): "
            f"{listed}.")


def campbell_section(crank: Crank, outcome: CampbellOutcome | Skipped) -> list[str]:
    """Crossings by severity, the diagram, and the forced response."""
    if isinstance(outcome, Skipped):
        return ["## Campbell diagram", "", f"Not run: {outcome.reason}.", ""]
    camp, resp = outcome.campbell, outcome.response
    a, b = outcome.campbell_image, outcome.response_image
    return ["## Campbell diagram and forced response", "",
            f"Crossings inside the checked range {camp.speed_range_rpm[0]:.0f}-{camp.speed_range_rpm[1]:.0f} rpm (to "
            f"overspeed), most severe first ({camp.source}; severity in {camp.severity_unit.split(': ')[1]} for "
            f"ζ = {zeta_text(camp.damping_ratio)}, {camp.severity_unit.split(':')[0]}):", "", "```", camp.table(), "```",
            "", _major_orders_line(crank),
            "", f"![]({a})", "", f"Forced response on the {resp.model}, every order summed with its phase:", "",
            "```", resp.table(), "```", "", f"![]({b})", ""]


def sensitivity_section(crank: Crank, outcome: SensitivityOutcome | Skipped) -> list[str]:
    """One-at-a-time sensitivities, the band, where the measurement falls, the FE check."""
    if isinstance(outcome, Skipped):
        return ["## Sensitivity", "", f"Not run: {outcome.reason}.", ""]
    sens, checks = outcome.sensitivity, outcome.fe_check
    verdict = ""
    if sens.measured_hz is not None:
        verdict = (f"The measured {sens.measured_hz:g} Hz is **{'inside' if sens.measured_inside else 'outside'}** "
                   f"the band {sens.band_hz[0]:.0f}–{sens.band_hz[1]:.0f} Hz.")
    lines = ["## Sensitivity of f1 to the reconstructed geometry", "",
             "Each input of the description's `[uncertainty]` table at its bounds, one at a time, then all "
             "at the bounds that lower (raise) f1 together: the band's ends are model results.", "",
             "```", sens.table(), "```", "", verdict, ""]
    if checks:
        lines += ["FE check of the three most influential inputs (change of f1 from the low to the high bound; "
                  "FE on the crank without fillets and drillings, 25 mm mesh):", "",
                  "| input | lumped | FE |", "|---|---|---|"]
        lines += [f"| {c['field']} | {c['lumped_change_percent']:+.1f} % | {c['fe_change_percent']:+.1f} % |"
                  for c in checks] + [""]
    lines += [f"![]({outcome.image})", ""]
    return lines + studies_lines(sens, outcome.studies, outcome.study_images)


def studies_lines(sens, studies: dict | None, images: dict) -> list[str]:
    """The Monte Carlo band of f1 beside the one-at-a-time band, and the Sobol' indices."""
    if not studies:
        return []
    mc, sob = studies["montecarlo"], studies["sobol"]
    b = mc.bands["f1"]
    lines = ["### Monte Carlo distribution of f1", "",
             f"{len(mc.X)} runs of the {mc.model} model, every `[uncertainty]` input drawn uniformly over its range, "
             f"independently (groups move together), seed {mc.seed}: f1 5–95 % **{b['p5']:.0f}–{b['p95']:.0f} Hz**, "
             f"median {b['p50']:.0f} Hz (the one-at-a-time band above, every input at its worst bound at once, is "
             f"{sens.band_hz[0]:.0f}–{sens.band_hz[1]:.0f} Hz: a bound, not a probability)."]
    pct = mc.measured_percentile()
    if pct is not None:
        inside = b["p5"] <= mc.measured_hz <= b["p95"]
        lines[-1] += (f" The measured {mc.measured_hz:g} Hz has **{pct:.1f} % of the runs below it**: "
                      f"{'inside' if inside else 'outside'} the 5–95 % band.")
    if mc.errors:
        lines[-1] += f" {len(mc.errors)} runs failed (first: {mc.errors[0]['error']})."
    lines += ["", f"![]({images['montecarlo']})", "", "### Sobol' indices of f1", ""]
    idx = sob.indices["f1"]
    if "not_computed" in idx:
        return lines + [f"Not computed: {idx['not_computed']}", ""]
    lines += [f"{len(sob.X)} runs ({sob.samples} base samples, Saltelli's scheme, SALib); ± the 95 % bootstrap "
              "confidence half-width. S1: the share of f1's variance an input explains alone; ST: with its "
              "interactions.", "", "| input | S1 | ST |", "|---|---|---|"]
    order = sorted(range(len(sob.inputs)), key=lambda j: -idx["ST"][j])
    lines += [f"| {sob.input_names[j]} | {idx['S1'][j]:.3f} ± {idx['S1_conf'][j]:.3f} | "
              f"{idx['ST'][j]:.3f} ± {idx['ST_conf'][j]:.3f} |" for j in order]
    return lines + ["", f"![]({images['sobol']})", ""]




def verdict_section(crank: Crank, outcome: VerdictOutcome | Skipped) -> list[str]:
    """Fillet stresses and the verdict table: without a damper, with Den Hartog's and the optimised one."""
    if isinstance(outcome, Skipped):
        return ["## Verdict", "", f"Not run: {outcome.reason}.", ""]
    v = outcome.verdict
    unit, scale = v.unit
    lim = v.limits
    lines = [f"## {'Fillet stress' if lim.kind == 'stress' else 'Section torque'}, dampers and verdict", ""]
    if outcome.model:
        lines += [f"Computed on the **{outcome.model}**: it decides.", ""]
    if outcome.stress is not None:
        scf = outcome.scf
        lines += [f"Torsional stress concentration factors: pin fillet **{scf.torsion['pin']:.3f}**, journal fillet "
                  f"**{scf.torsion['journal']:.3f}** ({scf.source}). Vibratory shear stress = SCF x 16 T D / (pi (D^4 - d^4)) "
                  "of the synthesised section torque (all orders summed with their phases; amplitude = half "
                  "peak-to-peak), without a damper:", "", "```", outcome.stress.table(), "```", ""]
    limit_text = (f"continuous running **{lim.continuous / scale:.4g} {unit}**"
                  + (f", passing through **{lim.transient / scale:.4g} {unit}**" if lim.transient else "")
                  + (f" (fatigue strength {lim.fatigue_strength / scale:.4g} {unit} / safety factor "
                     f"{lim.safety_factor:g})" if lim.fatigue_strength else ""))
    lines += [f"Limits: {limit_text}. Source: {lim.source}.", "",
              f"Damper designs: Den Hartog's optimum for the first mode seen from the pulley, inertia ratio "
              f"**mu = {outcome.mu:g}** (the run's inertia ratio), then optimised "
              "on the whole crank over the speed range (its stiffness and damping; ring inertia held).", "",
              "| case | speed range (rpm) | worst section | at rpm | value | limit | margin | barred ranges | "
              "damper heat (W) | verdict |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in v.rows():
        bars = "; ".join(f"{b['from_rpm']:.0f}-{b['to_rpm']:.0f} (peak {b['peak'] / scale:.4g} {unit}"
                         + (", passable" if b["passable"] else ", at the end of the speed range" if
                            b["from_rpm"] <= r["speed_range_rpm"][0] or b["to_rpm"] >= r["speed_range_rpm"][1]
                            else ", above the passing-through limit")
                         + ")" for b in r["barred_ranges"]) or "none"
        heat = f"{r['damper_power_w']:.1f}" if r["damper_power_w"] else "-"
        if r.get("damper_allowed_power_w"):
            heat += f" of {r['damper_allowed_power_w']:.0f} allowed ({r['damper_heat']})"
        heat += "".join(f", rubber at {t:.0f} °C" for t in r.get("damper_temperatures_c", ()))
        lines.append(f"| {r['case']} | {r['speed_range_rpm'][0]:.0f}-{r['speed_range_rpm'][1]:.0f} | "
                     f"{r['worst_section']} | {r['worst_rpm']:.0f} | {r['value'] / scale:.4g} {unit} | "
                     f"{r['limit'] / scale:.4g} {unit} | {100 * r['margin']:+.1f} % | {bars} | {heat} | "
                     f"**{r['verdict']}** |")
    for r in v.rows():
        if r["damper_power_by_order_w"]:
            top = sorted(r["damper_power_by_order_w"].items(), key=lambda kv: -kv[1])[:4]
            lines += ["", f"Damper heat, {r['case']}: {r['damper_power_w']:.1f} W in total at its worst speed, of which "
                      + ", ".join(f"order {q}: {p:.1f} W" for q, p in top) + "."]
    lines += [""] + [f"- {n}" for n in v.notes] + [f"- every row's limit: {limit_text}; source: {lim.source}", ""]
    return lines + [f"![]({outcome.image})", ""]



def _damper_spec(d) -> str:
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
    mat = a.worst.material
    lines = ["## Verdict: fatigue of the fillets and oil bores", "",
             f"Computed on the **{outcome.model}**. **{v.method}** decides; {v.other} is "
             f"shown beside it. Damping: modal damping ratio **ζ = {v.damping_ratio:.4g}** ({v.damping_source}). "
             f"Material: {mat.name}, R_m {mat.tensile_strength / 1e6:.0f} MPa, R_e {mat.yield_strength / 1e6:.0f} MPa "
             f"({mat.source or 'the description'}).", "",
             f"| configuration | {v.method}: safety | required | governing | at rpm | verdict | {v.other}: safety "
             f"| required | its governing |", "|---|---|---|---|---|---|---|---|---|"]
    for c in v.configs:
        x, y = c.answer(v.method), c.answer(v.other)
        lines.append(f"| {c.name} | **{x.safety:.2f}** | {x.required:.2f} | {x.location} ({x.where}) | "
                     f"{x.rpm:.0f} | **{'pass' if x.passes and c.heat_ok else 'FAIL'}**"
                     + ("" if c.heat_ok else f" (damper heat {c.damper_power_w:.0f} W over {c.allowed_power_w:.0f} W)")
                     + " | "
                     + (f"{y.safety:.2f} | {y.required:.2f} | {y.location} |" if y else "- | - | - |"))
    lines += ["", f"**Damping sensitivity** (the crank as described): {v.flip.kind}; across the band "
              + ", ".join(f"ζ = {b['damping_ratio']:.4g}: safety {b['safety']:.2f}" for b in v.band)
              + f" ({crank.excitation.damping_source}).", ""] + bending_lines(v) + [""]
    first = next((c for c in v.configs if c.bending), None)
    bent = first.bending if first is not None else []
    if bent:
        lines += [f"Vibratory bending in each fillet's throw plane ({first.name}, the crank as described; the largest "
                  "half peak-to-peak over the speeds) against the statically determinate throw's under the rod force's "
                  "alternating radial part at the rated speed (M53's bending; its misfire rows are in results.json):", "",
                  "| fillet | vibratory [kN m] | at rpm | determinate [kN m] | ratio |", "|---|---|---|---|---|"]
        lines += [f"| {b['name']} | {b['vibratory_nm'] / 1e3:.3f} | {b['rpm']:.0f} | {b['determinate_nm'] / 1e3:.3f} | "
                  f"{'**' if b['flag'] else ''}{b['ratio']:.2f}{'**' if b['flag'] else ''} |" for b in bent] + [""]
    if v.damper is not None and v.damper.optimised is not None:
        d = v.damper.optimised
        rec = [c for c in v.configs if d in c.dampers and c.misfire is None]
        heat = f"; its heat at the worst speed {rec[0].damper_power_w:.1f} W (no rating given)" if rec else ""
        lines += [f"**Recommended damper**, designed for this verdict (Den Hartog's start on mode 1, "
                  f"{v.damper.mode_hz:.1f} Hz, then its stiffness and loss optimised on the whole crank to make M53's "
                  f"governing safety as large as it can be, ring inertia held at μ = {v.damper.mu:g}): "
                  f"{_damper_spec(d)}{heat}.", ""]
    m = next(c for c in v.configs if c.dampers == tuple(crank.dampers)).m53
    lines += ["### IACS UR M53, as written ([KR-M53])", "",
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
    lines += ["", "### fetorsion's own path (`fe`)", "",
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
    if outcome.stress is not None:
        lines += ["The vibratory torsional stress at the fillets that both methods start from (SCF × 16 T D / "
                  "(π (D⁴ − d⁴)) of the synthesised section torque; an input, not a verdict):", "", "```",
                  outcome.stress.table(), "```", ""]
    return lines + [f"![]({im})" for im in outcome.images] + [""]


def measured_section(crank: Crank, outcome) -> list[str]:
    """The model against the measured files the run was given: every table and the figure."""
    if isinstance(outcome, Skipped):
        return ["## Model against measurement", "", f"Not run: {outcome.reason}.", ""]
    c = outcome.comparison
    return ["## Model against measurement", "",
            "Natural frequencies: the modes fitted to the measured FRFs, each against the nearest free-free mode "
            "of the model named; order cuts: the measured amplitude against the model's own order at the sensor's "
            f"station, the model the {c.model or 'lumped chain'} (docs/measured-data.md).", "", "```", c.table(),
            "```", "",
            f"![]({outcome.image})", ""]


def transient_section(crank, outcome: TransientOutcome | Skipped) -> list[str]:
    """The run-up: which integrator ran and its time, the waterfall, the order cuts against the
    steady-state response at the most severe crossings, with each passage's α/Γ²."""
    if isinstance(outcome, Skipped):
        return ["## Time domain: run-up", "", f"Not run: {outcome.reason}.", ""]
    res = outcome.transient
    lines = ["## Time domain: run-up", "",
             f"A {res.mode} over the checked range, after {res.settle_s:.2f} s at its start speed (the start's "
             f"transient settled), {res.time_s.size:,} steps of {res.step_s * 1e6:.1f} µs "
             f"({res.scheme}): {outcome.seconds:.1f} s of computation. Only the alternating torque drives it, as in "
             f"the steady state; the order track reads the simulated tooth edges of `{res.track_station}` "
             "with the code that processes measured torsiograph records.",
             *[f"Note: {n}." for n in res.notes], "", "```", res.table(), "```", "",
             f"Waterfall, the vibration of `{res.track_station}` by order and speed: ![]({outcome.waterfall_image})", ""]
    if outcome.cuts:
        lines += ["The run-up's order cuts against the steady-state forced response at the most severe crossings "
                  "(peaks within ±10 % of the crossing's speed). α/Γ² = q (dΩ/dt)/(ζω)² is the passage's speed "
                  "[Cowan]: well below 0.1 the run-up's peak approaches the steady state's; above it the peak is "
                  "lower and later.", "",
                  "| order | mode (Hz) | crossing [rpm] | α/Γ² | steady peak [deg] at [rpm] | run-up peak [deg] at [rpm] "
                  "| run-up / steady − 1 |", "|---|---|---|---|---|---|---|"]
        lines += [f"| {c.order:g} | {c.mode} ({c.mode_hz:.1f}) | {c.crossing_rpm:.0f} | {c.passage:.3g} | "
                  f"{c.steady_deg:.4g} at {c.steady_rpm:.0f} | {c.runup_deg:.4g} at {c.runup_rpm:.0f} | "
                  f"{100 * c.difference:+.1f} % |" for c in outcome.cuts]
        lines += ["", f"![]({outcome.cuts_image})", ""]
    else:
        lines += ["No crossing of the Campbell diagram lies inside the run on an order both analyses carry.", ""]
    return lines


SECTIONS = (("lumped", lumped_section), ("fe", fe_section), ("bearings", bearings_section), ("campbell", campbell_section),
            ("sensitivity", sensitivity_section), ("verdict", verdict_section), ("fatigue", fatigue_section),
            ("measured", measured_section), ("transient", transient_section))


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
    fe, bearings, sens, ver = run.fe, run.bearings, run.sensitivity, run.verdict
    if fe is not None:
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
        out.append(line + ".")
    if bearings is not None:
        b = bearings.condensed.crank.main_bearings
        support = ("rigid main bearings" if b.rigid else "oil-film main bearings" if b.oil_film is not None
                   else "the [bearings] stiffness")
        held = bearings.bearings
        # the headline is the first mode the engine's torque drives with a real share of torsion;
        # every mode below it is named, so a coupled bending mode is never hidden behind it
        f1 = held.first_carrying_torsion(F1_TORSION_SHARE)
        below = [(f, k, t) for f, k, t in zip(held.frequencies_hz, held.kinds, held.fractions[:, 0]) if f < f1]
        line = (f"- **f1 in the engine: {f1:.1f} Hz** (condensed crank in {support}, "
                f"{bearings.condensed.reduced.size} DOF; {100 * (f1 / bearings.f1_free_hz - 1):+.1f} % on free-free; "
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
        out.append(line + ".")
    if isinstance(ver, VerdictOutcome):
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
            spec = (f"ring {d.ring_inertia:.4g} kg m^2"
                    + (f", stiffness {d.stiffness:.4g} N m/rad" if d.stiffness else "")
                    + (f", loss factor {d.loss_factor:.3g}" if d.loss_factor else "")
                    + (f", damping {d.damping:.4g} N m s/rad" if d.damping else ""))
            out.append(f"- **Recommended damper: {best['case']}** ({spec}): worst {best['value'] / scale:.4g} {unit}, "
                       f"margin {100 * best['margin']:+.1f} %, {best['verdict']} ({ver.model or 'lumped chain'}).")
        bars = [f"{b['from_rpm']:.0f}-{b['to_rpm']:.0f} rpm" for b in r["barred_ranges"]]
        out.append(f"- **Barred speed ranges without a damper:** {', '.join(bars) or 'none'} "
                   f"(checked {r['speed_range_rpm'][0]:.0f}-{r['speed_range_rpm'][1]:.0f} rpm, to overspeed; "
                   f"{ver.model or 'lumped chain'}).")
    fat = run.fatigue
    if fat is not None and not isinstance(fat, Skipped):
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
            out.append(f"- **Recommended damper:** {_damper_spec(v.damper.optimised)}, designed for the iacs-m53 "
                       "verdict's governing safety" + ("" if v.method == "iacs-m53" else
                                                       f" and checked by the deciding {v.method} method")
                       + " (its line above).")
        mat = fat.assessment.worst.material
        if fat.assessment.worst.defaulted:
            out.append(f"- **Material assumed:** the description gives no strength; {mat.name}, R_m "
                       f"{mat.tensile_strength / 1e6:.0f} MPa, R_e {mat.yield_strength / 1e6:.0f} MPa ({mat.source}).")
    mea = run.measured
    if mea is not None and not isinstance(mea, Skipped):
        for f in mea.comparison.frequencies:
            d = f.difference_percent
            out.append(f"- **Measured frequencies: {len(d)} modes, model ({f.source}) {d.min():+.1f} to {d.max():+.1f} %** "
                       f"against the modal test.")
        for c in mea.comparison.order_cuts:
            p = c.peaks()
            out.append(f"- **Order {c.order:g} at {c.station} ({c.name}): model peak {p['peak_difference_percent']:+.1f} %, "
                       f"{p['peak_rpm_difference']:+.0f} rpm** against the measurement "
                       f"({mea.comparison.model or 'lumped chain'}).")
    table = verdict_table(fat.verdict) if fat is not None and not isinstance(fat, Skipped) else []
    return ["## Summary", "", *out, "", *table] if out else []


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


def report_markdown(run: RunOutcome) -> str:
    """The whole report: a title, the summary, each section whose step ran, in pipeline order, the timings."""
    lines = [f"# {run.crank.name}", "", f"Description: `{run.path}`", ""]
    if run.driveline:
        lines += [f"In the driveline **{run.driveline}**: the forced response, the fatigue and the verdict are the "
                  "crank's in it (the condensed crank in its bearings joined to the network's stations at its pulley "
                  "and flywheel); the lumped models, the Campbell diagram and the bearings' coupled response are "
                  "the crank's alone.", ""]
    lines += summary_lines(run)
    for key, render in SECTIONS:
        outcome = getattr(run, key)
        if outcome is not None:
            lines += render(run.crank, outcome)
    lines += ["## Timings", "", *[f"- {k}: {v:.1f} s" for k, v in (run.timings_s or {}).items()], ""]
    return "\n".join(lines)
