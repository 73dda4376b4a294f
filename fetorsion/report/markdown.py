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
from ..lumped_model.lumped import PARTITIONS
from ..modes import F1_TORSION_SHARE
from .fatigue import fatigue_section
from .tvc import tvc_section
from .outcomes import (BearingsOutcome, CampbellOutcome, ChainOutcome, FEOutcome, LumpedOutcome, RunOutcome,
                       SensitivityOutcome, Skipped, TransientOutcome, VerdictOutcome)
from .summary import summary_lines



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
    lines += [""] * bool(skipped) + [f"Web method `{m}` not used: {why}" for m, why in skipped.items()]
    shown = "Carter" if "carter" in table else next(iter(table), "")  # a split-pin crank's plot is its fe chain's
    lines += ["", f"17-DOF mode shapes ({shown} webs), unit twist at the pulley end: ![]({outcome.image})", ""]
    return lines


def fe_section(crank: Crank, outcome: FEOutcome) -> list[str]:
    """Mesh, solver and timings, f1 against the measurement, every mode with its label."""
    res, size = outcome.modal, outcome.mesh_size_m
    quality = res.quality
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
    b = cc.main_bearings  # with an oil film's loads found from the crank's forces
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
    engine = outcome.bearings.first_carrying_torsion(F1_TORSION_SHARE)  # f1 in the engine, the summary's
    lines = ["## The crank in its bearings (condensed 3D FE, torsion and bending coupled)", "",
             f"The FE crank of the previous section condensed (Craig–Bampton, distributing couplings) to "
             f"{len(cc.labels)} masters ({', '.join(cc.labels)}): {cc.reduced_dofs} DOF from {cc.full_dofs} "
             f"({sum(v for k, v in cc.timings_s.items() if k not in ('total', 'meshing')):.1f} s). "
             f"In the engine: {support}. Free-free is what a modal test measures"
             + (f" (measured {measured:g} Hz)" if measured else "") + "; the Campbell diagram below uses the "
             "modes in bearings.", "",
             _first_modes_line(outcome, engine),
             "", "| mode | free (Hz) | kind (torsion/bending) | in bearings (Hz) | kind (torsion/bending) |",
             "|---|---|---|---|---|"]
    for j in range(min(8, len(free.frequencies_hz), len(held.frequencies_hz))):
        lines.append(f"| {j + 1} | {free.frequencies_hz[j]:.1f} | {free.kinds[j]} ({free.fractions[j, 0]:.2f}/"
                     f"{free.fractions[j, 1]:.2f}) | {held.frequencies_hz[j]:.1f} | {held.kinds[j]} "
                     f"({held.fractions[j, 0]:.2f}/{held.fractions[j, 1]:.2f}) |")
    which = "" if abs(engine - outcome.f1_bearings_hz) <= 1e-6 * engine else "; in bearings, f1 in the engine"
    lines += ["", f"The 17-DOF torsional chain against the condensed crank (f1{which}): `fe-held` takes each throw's "
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


def _first_modes_line(outcome: BearingsOutcome, engine: float) -> str:
    """f1 free-free and in the bearings; where the first mode the engine's torque drives
    (``engine``, Hz: :data:`~fetorsion.modes.F1_TORSION_SHARE` of torsion) lies below the first
    mostly torsional one, both."""
    free, held = outcome.f1_free_hz, outcome.f1_bearings_hz
    if abs(engine - held) <= 1e-6 * held:
        return f"**First torsional mode: free-free {free:.1f} Hz, in bearings {held:.1f} Hz ({100 * (held / free - 1):+.1f} %).**"
    return (f"**First torsional mode: free-free {free:.1f} Hz; in bearings the first mode with at least "
            f"{100 * F1_TORSION_SHARE:.0f} % torsion (f1 in the engine) is at {engine:.1f} Hz "
            f"({100 * (engine / free - 1):+.1f} %), the first mostly torsional one at {held:.1f} Hz.**")


def _major_orders_line(crank) -> str:
    """The engine's major orders: where every cylinder's torque adds in phase on a rigid crank."""
    from ..excitation.campbell import CAMPBELL_HIGHEST_ORDER, major_orders

    orders = major_orders(crank.engine)
    listed = ", ".join(f"{q:g}" for q in orders) if len(orders) else "none (the firing is uneven)"
    line = (f"Major orders of this {crank.engine.cylinders}-cylinder {crank.engine.layout} engine, where every "
            f"cylinder's torque adds in phase on a rigid crank (to order {CAMPBELL_HIGHEST_ORDER:g}): "
            f"{listed}.")
    if crank.engine.articulation is not None:
        import numpy as np

        from ..excitation.torque import articulated_link

        link = articulated_link(crank.engine)
        s = link.path(np.linspace(0.0, 2 * np.pi, 3601))[0]
        line += (f" Master and articulated rods: the articulated (second-bank) cylinders reach TDC "
                 f"{np.degrees(link.tdc_shift()):+.2f}° after their bank angle, with a stroke of "
                 f"{(s.max() - s.min()) * 1e3:.2f} mm (the master's {2e3 * link.r:.2f} mm); their loads reach the "
                 "pin through the master rod (the sums above take the bank angles alone; the response, "
                 "Campbell's order sums and the verdict take each cylinder's own).")
    return line


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
            "", f"![]({a})", "", f"Forced response on the {resp.model}, every order summed with its phase"
            f"{_coupling_basis(crank)}:", "", "```", resp.table(), "```", "", f"![]({b})", ""]


def _coupling_basis(crank) -> str:
    """Where a network's flexible couplings stand in the Campbell diagram and the forced response:
    at the temperature the file states, not the one their heat settles to (the TVC's), so that a
    reader comparing the two sections knows why their numbers differ."""
    couplings = getattr(crank, "couplings", ())
    if not couplings:
        return ""
    at = ", ".join(f"{c.name or 'coupling'} at {c.operating_temperature_c:g} °C (C {c.stiffness_at(c.operating_temperature_c):.4g} "
                   "N m/rad)" for c in couplings)
    return (f" (the flexible couplings as the file states them, {at}; the propulsion TVC below runs them at the "
            "temperature their heat holds: its natural frequencies, stresses and heats are the ones judged)")


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
             f"transient settled), {res.samples:,} steps of {res.step_s * 1e6:.1f} µs "
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
            ("sensitivity", sensitivity_section), ("verdict", verdict_section), ("tvc", tvc_section),
            ("fatigue", fatigue_section),
            ("measured", measured_section), ("transient", transient_section))


#: What the report calls each section a run can take from the store (:mod:`fetorsion.app.run_store`).
STORED_SECTIONS = {"fe": "the 3D FE free-free modes and the condensed crank, with their pictures and timings",
                   "fatigue": "the fatigue verdict (both methods, the recommended damper, misfire)"}


#: The sections a TVC report leaves out where their step did not run (a network file has no
#: uncertainty table, no [limits] of its own beside the TVC's, no crank to judge for fatigue).
TVC_LEAVES_OUT = ("sensitivity", "verdict", "fatigue")


def report_markdown(run: RunOutcome) -> str:
    """The whole report: a title, the summary, each section whose step ran, in pipeline order, the timings."""
    lines = [f"# {run.crank.name}", "", f"Description: `{run.path}`", ""]
    if run.driveline:
        lines += [f"In the driveline **{run.driveline}**: the forced response, the fatigue and the verdict are the "
                  "crank's in it (the condensed crank in its bearings joined to the network's stations at its pulley "
                  "and flywheel); the lumped models, the Campbell diagram and the bearings' coupled response are "
                  "the crank's alone.", ""]
    lines += summary_lines(run)
    # a TVC report leaves out the crank's sections it cannot have (a reviewer read "Verdict: Not run"
    # beside the TVC's verdicts as a contradiction); their reasons stay in results.json's "skipped"
    tvc = getattr(run, "tvc", None) is not None and not isinstance(run.tvc, Skipped)
    for key, render in SECTIONS:
        outcome = getattr(run, key)
        if outcome is not None and not (tvc and key in TVC_LEAVES_OUT and isinstance(outcome, Skipped)):
            lines += render(run.crank, outcome)
    lines += ["## Timings", "", *[f"- {k}: {v:.1f} s" for k, v in (run.timings_s or {}).items()], ""]
    if run.from_store:
        lines += ["Taken from the store, computed by an earlier run of the same description, options and code: "
                  + ", ".join(STORED_SECTIONS.get(k, k) for k in run.from_store) + ".", ""]
    return "\n".join(lines)
