"""The bridge between the two fatigue methods, term by term.

At one place, M53's safety is Q_M53 = σ_DW / σ_V (σ_V from the rule's SCFs on the statically
determinate throw's bending at the rated speed, the largest alternating torque, σ_add) and the
``fe`` path's is Findley's factor Q_fe on the recovered local stress history at its worst speed
(:mod:`fetorsion.design.recovered`). Their ratio is the product of five factors, each the step
from one method's figure to the other's with everything else held, each above 1 where it makes
the ``fe`` path the safer:

=============  ============================================================================
``stress``     σ_V,M53 (no σ_add) / σ_V,fe on M53's own loads (:func:`~.recovered.same_load`):
               the rule's SCFs × nominal against the recovered stress at the notch
``load``       (σ_V,M53 / σ_V,M53 without σ_add) · σ_V,fe on M53's loads / σ_vM,a on the run's:
               M53's loads (σ_add, the determinate throw at the rated speed, M_TN in phase)
               against the condensed crank's cycle at the place's worst speed, both recovered
``combination`` Q_F,0 · σ_vM,a / f₋₁: Findley at zero mean against the von Mises amplitude on
               the same strength (how the multiaxial history is combined)
``strength``   f₋₁ / σ_DW: the local strength against the rule's
``mean``       Q_fe / Q_F,0: Findley with the signed mean against without it
=============  ============================================================================

The product is Q_fe / Q_M53 exactly (each intermediate figure cancels); :func:`method_bridge`
checks it to round-off.
"""

from __future__ import annotations

import math

import numpy as np

#: The two methods' governing safeties further apart than this fraction are flagged.
DISAGREEMENT = 0.30
FACTORS = ("load", "stress", "combination", "strength", "mean")


def place_bridge(fe_loc, fe_safety: float, m53_loc, same: dict) -> dict:
    """The bridge at one place: ``fe_loc`` (:class:`~fetorsion.design.fatigue.FatigueAssessment`
    of the recovered path at its worst speed, safety ``fe_safety``), ``m53_loc``
    (:class:`~fetorsion.design.m53.M53Location` of the same kind and throw variant) and ``same``
    (:func:`~fetorsion.design.recovered.same_load`'s entry of that kind)."""
    s0 = m53_loc.equivalent
    s0n, s1 = same["m53_sigma_v_pa"], same["fe_sigma_v_pa"]
    s2 = fe_loc.equivalent_alternating
    f = fe_loc.strength
    q0 = fe_loc.criteria["findley"]["safety_without_mean"]
    factors = {"load": (s0 / s0n) * (s1 / s2), "stress": s0n / s1, "combination": q0 * s2 / f,
               "strength": f / m53_loc.strength, "mean": fe_safety / q0}
    product = float(np.prod(list(factors.values())))
    ratio = fe_safety / m53_loc.safety
    largest = max(factors, key=lambda k: abs(math.log(factors[k])))
    return {"fe_place": fe_loc.name, "m53_place": m53_loc.name, "fe_safety": fe_safety,
            "m53_safety": m53_loc.safety, "ratio": ratio, "factors": factors, "product": product,
            "largest": largest,
            "figures_pa": {"m53_sigma_v": s0, "m53_sigma_v_without_add": s0n, "fe_sigma_v_on_m53_loads": s1,
                           "fe_von_mises_amplitude": s2, "fe_strength": f, "m53_strength": m53_loc.strength},
            "fe_without_mean": q0}


def method_bridge(crank, fe, m53, locations, fillets, zones: dict) -> dict:
    """Per configuration: the bridge (:func:`place_bridge`) at the ``fe`` path's governing place
    and at the place of the same kind and throw variant as M53's governing one (one entry
    where they are the same), the governing safeties' ratio and whether it is beyond
    :data:`DISAGREEMENT`, and the factor that carries most of the fe-governing place's ratio.

    Parameters
    ----------
    crank : Crank
    fe : RecoveredAssessment
        The configuration's ``fe`` assessment on ``locations``.
    m53 : M53Result
        The configuration's M53.
    locations : list of Location
        :func:`fetorsion.design.recovery.crank_locations` (their cuts index ``fillets``).
    fillets : list of Fillet
    zones : dict
        :func:`fetorsion.design.recovery.crank_zones` of the crank.
    """
    from .recovered import m53_variant, same_load
    from .recovery import throw_index

    least = fe.safety.min(axis=0)
    throws = [throw_index(crank, fillets, fillets[loc.cuts[0]]) for loc in locations]
    same_of: dict = {}

    def at(j):
        variant = m53_variant(m53, throws[j])
        kind = locations[j].kind
        m = [a for a in m53.locations if a.name.startswith(variant + ":") and a.kind == kind]
        if variant not in same_of:
            same_of[variant] = same_load(crank, m53, zones, throws[j])
        if not m or kind not in same_of[variant]:
            return None
        return place_bridge(fe.worst.locations[j], float(least[j]), m[0], same_of[variant][kind])

    j_fe = int(np.argmin(least))
    g = m53.governing
    gv = g.name.split(":")[0]
    same_kind = [j for j, loc in enumerate(locations)
                 if loc.kind == g.kind and m53_variant(m53, throws[j]) == gv]
    j_m53 = min(same_kind, key=lambda j: least[j]) if same_kind else None
    places = [x for x in (at(j_fe), None if j_m53 in (None, j_fe) else at(j_m53)) if x is not None]
    ratio = float(least[j_fe]) / g.safety
    return {"fe_safety": float(least[j_fe]), "m53_safety": g.safety, "ratio": ratio,
            "disagrees": bool(abs(ratio - 1.0) > DISAGREEMENT),
            "carried_by": places[0]["largest"] if places else None, "places": places}
