"""The classical web formulas: Carter's and Ker Wilson's throw formulas and an elementary
beam bound, each as a web method ``method(crank, web_index, d_e) -> L_eb`` (m, one web).

The throw formulas give the equivalent length of a whole throw (journal centre to journal
centre: one journal length, two webs, one pin); each is split here into eq. (4) for the
journal, eq. (5) for the pin, and the remainder shared by the two webs, so that the sum
over a throw is exactly the published throw formula.

Carter's and Ker Wilson's coefficients are *as commonly quoted*: no source we could
read prints them (see docs/stiffness-formulas.md), so they are named constants here,
to be corrected against the books.
"""

from __future__ import annotations

import math

from ..description.model import Crank
from .sections import effective_web_width

# Carter, as commonly quoted, per throw: L_e = l_j + 0.8 h + 0.75 l_p (D_j/D_p)⁴ + 1.5 R D_j⁴/(h b³)
CARTER_WEB_THICKNESS = 0.8
CARTER_PIN_LENGTH = 0.75
CARTER_WEB_BENDING = 1.5
# Ker Wilson, as commonly quoted, per throw:
# L_e = (l_j + 0.4 D_j) + (l_p + 0.4 D_p)(D_j/D_p)⁴ + (R − 0.2 (D_j + D_p)) D_j⁴/(h b³)
WILSON_END_EFFECT = 0.4
WILSON_RADIUS_REDUCTION = 0.2


def _web_parts(crank: Crank, i: int):
    return (crank.webs[i], crank.journals[crank.journal_of_web(i)], crank.pins[crank.throw_of_web(i)],
            crank.engine.crank_radius)


def carter(crank: Crank, web_index: int, d_e: float) -> float:
    """Carter's throw formula (as commonly quoted) less eq. (4)–(5), per web, m."""
    web, _, pin, R = _web_parts(crank, web_index)
    b = effective_web_width(web)
    pin_ratio = d_e**4 / (pin.diameter**4 - pin.bore**4)
    return (0.5 * CARTER_WEB_THICKNESS * web.thickness * d_e**4 / _journal_d4(crank, web_index)
            + 0.5 * (CARTER_PIN_LENGTH - 1.0) * pin.length * pin_ratio
            + 0.5 * CARTER_WEB_BENDING * R * d_e**4 / (web.thickness * b**3))


def ker_wilson(crank: Crank, web_index: int, d_e: float) -> float:
    """Ker Wilson's throw formula (as commonly quoted) less eq. (4)–(5), per web, m."""
    web, journal, pin, R = _web_parts(crank, web_index)
    b = effective_web_width(web)
    pin_ratio = d_e**4 / (pin.diameter**4 - pin.bore**4)
    arm = R - WILSON_RADIUS_REDUCTION * (journal.diameter + pin.diameter)
    return (0.5 * WILSON_END_EFFECT * journal.diameter * d_e**4 / _journal_d4(crank, web_index)
            + 0.5 * WILSON_END_EFFECT * pin.diameter * pin_ratio
            + 0.5 * arm * d_e**4 / (web.thickness * b**3))


def beam(crank: Crank, web_index: int, d_e: float) -> float:
    """Web as an Euler–Bernoulli cantilever of length R bent by the throw torque, m.

    θ = 12 T R/(E h b³) equals the twist of a shaft of length (3π/8)(G/E) R D_e⁴/(h b³).
    Elementary mechanics, no fillet or overlap correction: a stiff bound, not a design
    formula.
    """
    web, _, _, R = _web_parts(crank, web_index)
    b = effective_web_width(web)
    m = crank.material
    return 3 * math.pi / 8 * m.shear_modulus / m.youngs_modulus * R * d_e**4 / (web.thickness * b**3)


def _journal_d4(crank: Crank, web_index: int) -> float:
    j = crank.journals[crank.journal_of_web(web_index)]
    return j.diameter**4 - j.bore**4
