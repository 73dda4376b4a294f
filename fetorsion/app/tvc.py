"""The run's propulsion TVC step (docs/propulsion-tvc.md): for a network with a propeller or shaft
sections, the forced response with the propellers' blade orders (and the engine's), the couplings
at the temperature their heat holds, every shaft section against UR M68 and the barred ranges.

``ctx`` is the run's :class:`fetorsion.app.run.RunContext` (named, not imported: :mod:`.run`
imports this module to list its steps).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from ..description.chain_model import Network
from ..design.barred_passage import barred_passages, start_passages, stop_passages
from ..design.tvc_cases import (TVCCase, damper_failure_cases, evaluate_case, misfire_cases, tolerance_cases,
                                 worst_case)
from ..design.tvc_crank import crank_m53
from ..design.tvc_modes import ModeRow, TVCCampbell, mode_table
from ..errors import FetorsionError
from ..excitation.torque import has_motored_column
from ..lumped_model.lumped import lumped
from ..report.outcomes import TVC_IMAGES, Skipped, TVCOutcome, passage_image
from ..excitation.campbell import major_orders
from ..lumped_model.network import speed_factors
from ..response.propulsion import DEFAULT_SPEED_RATIOS, propeller_orders, tvc_setup

#: The highest engine order the TVC's mode table lists resonances of and its Campbell diagram draws.
TABLE_HIGHEST_ORDER = 12.0


def is_propulsion_line(model) -> bool:
    """A network with a propeller or a shaft section: the run adds its TVC step."""
    return isinstance(model, Network) and bool(model.propellers or any(s.section for s in model.shafts))


def misfires_of(net: Network) -> tuple[list[TVCCase], str]:
    """(the misfire of each cylinder, a note: why none was computed, or "")."""
    if net.engine is None or net.excitation is None:
        return [], ""
    try:
        return misfire_cases(net, tvc_setup), ""
    except FetorsionError as e:
        return [], str(e)


def step_tvc(ctx: RunContext) -> TVCOutcome | Skipped | None:
    """The propulsion line's TVC: response, couplings' heat, shaft sections, barred ranges, gear
    hammering, in normal running, in the misfire of each cylinder and with each damper failed
    (results.json's ``tvc`` entry: :meth:`TVCOutcome.to_dict`)."""
    if ctx.network is not None and is_propulsion_line(ctx.network):
        return Skipped("the network's crank is its condensed FE crank: the report above judges that crank in this "
                       "driveline (M53 and fe); the TVC of the network's shafts, couplings and propellers runs on a lumped "
                       "crank part for now (dof = 17 in [[chain.cranks]])")
    net = ctx.crank
    if not is_propulsion_line(net):
        return None
    if not any(p.order_shares for p in net.propellers) and net.excitation is None:
        return Skipped("no excitation: the network has neither propeller blade_order_shares nor [engine] and "
                       "[excitation] tables")
    normal = evaluate_case(net, tvc_setup, "normal running")
    misfires, why = misfires_of(net)
    worst = worst_case(misfires)
    failed = damper_failure_cases(net, tvc_setup)
    tolerances = tolerance_cases(net, tvc_setup)
    response, shafts, heat, hammer = normal.response, normal.shafts, normal.couplings, normal.hammering
    # the time-domain passage of each barred range: normal running's, the worst misfire's and each
    # failed damper's (the restriction a ship runs under until the damper is mended); and the start's and stop's
    passages = tuple(start_passages(normal) + stop_passages(normal) + barred_passages(normal)
                     + (barred_passages(worst) if worst else [])
                     + [p for c in (*failed, *tolerances) for p in barred_passages(c)])
    rows, campbell = tvc_modes(normal, [normal, *misfires, *failed, *tolerances])
    m53, m53_note = crank_m53([normal, *misfires, *failed, *tolerances])
    outcome = TVCOutcome(normal.network, lumped(normal.network), response, shafts, heat,
                         TVC_IMAGES["shafts"] if shafts else "", TVC_IMAGES["heat"] if heat else "",
                         tuple(assumptions(net, response)), hammer, TVC_IMAGES["hammering"] if hammer else "",
                         normal, tuple(misfires), worst, why,
                         TVC_IMAGES["misfire_shafts"] if worst and worst.shafts else "",
                         passages, tuple(passage_image(k) for k in range(len(passages))),
                         tuple(rows), TVC_IMAGES["campbell"], campbell, tuple(failed), tuple(tolerances),
                         tuple(m53), m53_note, TVC_IMAGES["crank_m53"] if m53 else "")
    for name, draw in tvc_figures(outcome).items():
        ctx.save(draw().figure, name)
    ctx.results["tvc"] = outcome.to_dict()
    return outcome


def tvc_figures(outcome: TVCOutcome) -> dict[str, Callable[[], object]]:
    """Each picture of the TVC section: file name -> a function drawing it (an Axes)."""
    out = {}
    if outcome.shaft_image:
        out[outcome.shaft_image] = lambda: titled(outcome.shafts.plot(), outcome.normal.name)
    if outcome.heat_image:
        out[outcome.heat_image] = outcome.couplings.plot
    if outcome.hammering_image:
        out[outcome.hammering_image] = outcome.hammering.plot
    worst = outcome.worst_misfire
    if outcome.misfire_shaft_image:
        out[outcome.misfire_shaft_image] = lambda: titled(worst.shafts.plot(), worst.name)
    out.update({image: p.plot for p, image in zip(outcome.passages, outcome.passage_images)})
    if outcome.campbell_image:
        out[outcome.campbell_image] = lambda: outcome.campbell.plot(outcome.mode_rows)
    if outcome.crank_m53_image:
        name, result = outcome.crank_m53[0]
        out[outcome.crank_m53_image] = lambda: titled(result.plot(wide_axes()), name)
    return out


def wide_axes():
    """Axes of a figure that keeps long place names on its left inside it."""
    import matplotlib.pyplot as plt

    return plt.figure(figsize=(8, 4), layout="constrained").add_subplot()


def titled(ax, configuration: str):
    """``ax`` with the configuration it shows in its title (normal running and the worst misfire look alike)."""
    ax.set_title(f"{ax.get_title()}: {configuration}")
    return ax


def tvc_modes(normal: TVCCase, cases: list[TVCCase]) -> tuple[list[ModeRow], TVCCampbell]:
    """The mode table (modes up to the top speed's highest listed order) and the Campbell diagram's data
    with every configuration's barred ranges: (rows, diagram)."""
    net, response = normal.network, normal.response
    f = speed_factors(net)
    blades = sorted({float(q) for p in net.propellers if p.order_shares for q in propeller_orders(p, f[p.station])})
    engine = [float(q) for q in response.orders
              if q <= TABLE_HIGHEST_ORDER and not any(abs(q - b) < 1e-9 for b in blades)]
    span = (float(response.rpm.min()), float(response.rpm.max()))
    top = max([TABLE_HIGHEST_ORDER, *blades]) * span[1] / 60.0
    rows = [r for r in mode_table(net, np.array(engine + blades), span, max_modes=len(net.labels)) if r.frequency_hz <= top]
    rows = rows or mode_table(net, np.array(engine + blades), span, max_modes=1)
    major = major_orders(net.engine, TABLE_HIGHEST_ORDER) if net.engine is not None else ()
    barred = tuple((c.name, float(b["from_rpm"]), float(b["to_rpm"])) for c in cases if c.shafts for b in c.shafts.barred)
    return rows, TVCCampbell(tuple(engine), tuple(float(q) for q in major), tuple(blades), span, barred,
                             f"{net.name}: Campbell diagram, barred ranges")


def assumptions(net: Network, response) -> list[str]:
    """What the TVC assumes, one sentence each (the report's list)."""
    out = [f"Damping: {response.damping_text()} (the modal ratio on every elastic mode"
           + ("; no [excitation] table states it: fetorsion's default)" if net.excitation is None else ")")]
    for p in net.propellers:
        held = (f"c = n Q(ω)/ω at each speed of the sweep (the modes' damping at {p.damping_speed * 30 / math.pi:.1f} "
                "rpm, the time domain's at the speed it runs or judges)" if p.damping_each_speed else
                f"linearised at {p.damping_speed * 30 / math.pi:.1f} rpm, held at every speed")
        out.append(f"Propeller '{p.name}': damping by the {p.damping_model.replace('_', ' ')}, {held}; inertia with "
                   f"{100 * p.entrained_share:g} % entrained water; blade orders {p.blades} × k at "
                   f"{', '.join(f'{100 * s:g} %' for s in p.order_shares) or 'no'} of the law's mean torque")
    if net.propellers and net.excitation is not None:
        out.append("Blade orders in phase with the engine's reference (blade 1 at its reference angle at cylinder 1's "
                   "firing TDC): the propeller's keying is not known; incommensurate sources are summed at their "
                   "worst relative phase")
    if net.excitation is None:
        out.append(f"Speed range: {DEFAULT_SPEED_RATIOS[0]:g} to {DEFAULT_SPEED_RATIOS[1]:g} of the propeller's rated "
                   "speed (no [excitation] range stated)")
    out.append("Shaft stresses nominal on the plain section (stress raisers in C_K); UR M68's formula lines as "
               "commonly restated, not read in the rule's text (docs/propulsion-tvc.md)")
    if net.couplings:
        out.append("Coupling temperature: T = T_amb + (T_max − T_amb) P/P_KV with P the largest heat over the speeds; "
                   "the sheet's C and ψ linear between its two temperatures")
    if net.dampers:
        out.append("A failed damper: each damper in turn with its ring free (the housing or hub left on its station) "
                   "and, a viscous one, seized (its ring turning with its housing), no damping from it; the shafts' "
                   "limits and barred ranges as in normal running ([LRNavalTV] Ch 1 §1.3)")
    if net.gears and net.propellers:
        out.append("Gear hammering: mesh torque from the gear's own equilibrium (the modal damping left out), against "
                   "the propeller law's mean torque referred by power, no gear losses")
    ex = net.excitation
    if ex is not None and ex.tangential_harmonics and ex.misfire_harmonics:
        out.append("Misfire: the misfiring cylinder by the engine maker's misfire harmonics of the table")
    elif ex is not None and ex.tangential_harmonics and has_motored_column(ex):
        out.append("Misfire: the misfiring cylinder by the table's column at p_mi 0, the motored cylinder at no-load "
                   "boost; a turbocharged engine's misfire at load compresses at the running boost and is larger "
                   "(the maker's misfire harmonics, misfire_sine and misfire_cosine, take it)")
    return out
