"""Equivalent lengths of the crank parts (seed 003, eq. 4–7), with selectable web methods.

Every length is reduced to the equivalent diameter D_e (solid): a part of equivalent
length L_e has torsional stiffness k = G·J_e/L_e with J_e = π D_e⁴/32.

The web term of eq. (6) comes from BICERA charts that are not public, so the web is a
named method: a function ``method(crank, web_index, d_e) -> L_eb`` (metres, one web).
The classical throw formulas give the equivalent length of a whole throw (journal
centre to journal centre: one journal length, two webs, one pin); each is split here
into eq. (4) for the journal, eq. (5) for the pin, and the remainder shared by the two
webs, so that the sum over a throw is exactly the published throw formula.

Two methods are computed rather than quoted (docs/web-chart.md): ``fe``, the static 3D FE
of the web's own throw (:mod:`fetorsion.throwfe`), and ``chart``, fetorsion's computed
counterpart of the BICERA chart (:mod:`fetorsion.webchart`).

Carter's and Ker Wilson's coefficients are *as commonly quoted*: no source we could
read prints them (see docs/stiffness-formulas.md), so they are named constants here,
to be corrected against the books.
"""

from __future__ import annotations

import math

import numpy as np
from typing import Callable

from .crank import Crank, Cylinder, Web
from .errors import FetorsionError

# Carter, as commonly quoted, per throw: L_e = l_j + 0.8 h + 0.75 l_p (D_j/D_p)⁴ + 1.5 R D_j⁴/(h b³)
CARTER_WEB_THICKNESS = 0.8
CARTER_PIN_LENGTH = 0.75
CARTER_WEB_BENDING = 1.5
# Ker Wilson, as commonly quoted, per throw:
# L_e = (l_j + 0.4 D_j) + (l_p + 0.4 D_p)(D_j/D_p)⁴ + (R − 0.2 (D_j + D_p)) D_j⁴/(h b³)
WILSON_END_EFFECT = 0.4
WILSON_RADIUS_REDUCTION = 0.2


def cylinder_equivalent_length(c: Cylinder, d_e: float) -> float:
    """Eq. (4)/(5): L_e = L · D_e⁴ / (D⁴ − d⁴), m."""
    return c.length * d_e**4 / (c.diameter**4 - c.bore**4)


def effective_web_width(web: Web) -> float:
    """Eq. (7): 1/b_e³ = ½ (1/B_max³ + 1/B_min³), m."""
    return (0.5 * (web.width_journal**-3 + web.width_pin**-3)) ** (-1.0 / 3.0)


def overlap_ratio(crank: Crank, web_index: int) -> float:
    """BICERA overlap c = (R_m + R_t − R)/R of the journal and pin a web joins."""
    R = crank.engine.crank_radius
    pin = crank.pins[crank.throw_of_web(web_index)]
    journal = crank.journals[crank.journal_of_web(web_index)]
    return (0.5 * pin.diameter + 0.5 * journal.diameter - R) / R


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


WebMethod = Callable[[Crank, int, float], float]

WEB_METHODS: dict[str, WebMethod] = {"carter": carter, "ker-wilson": ker_wilson, "beam": beam}
DEFAULT_WEB_METHOD = "carter"


def web_equivalent_length(crank: Crank, web_index: int, d_e: float, method: str = DEFAULT_WEB_METHOD) -> float:
    """Equivalent length L_eb (m, at D_e) of web ``web_index`` (0-based) by ``method``."""
    try:
        fn = WEB_METHODS[method]
    except KeyError:
        raise FetorsionError(
            f"stiffness method {method!r} is not known; choose one of {', '.join(WEB_METHODS)}") from None
    value = fn(crank, web_index, d_e)
    if not value > 0:
        raise FetorsionError(
            f"webs.{web_index + 1}: the {method} formula gives a non-positive equivalent length "
            f"({value:.4g} m); this web is outside the range the formula was made for")
    return value


def fe(crank: Crank, web_index: int, d_e: float) -> float:
    """Web term of the throw's static 3D FE torsion (:mod:`fetorsion.throwfe`), per web, m."""
    from .throwfe import web_equivalent_length_fe  # Gmsh and scikit-fem load only when asked for

    return web_equivalent_length_fe(crank, web_index, d_e)


WEB_METHODS["fe"] = fe


# Nestorides (BICERA 1958) stepped-shaft fillet chart as fitted in the rotordin Fortran code
# (tsecdl.f, docs/stiffness-formulas.md §4): ΔL/d = Σ a_k(ρ) x^k, a_k quadratic in ρ.
_STEP_FIT = np.array([[-0.39806698, 0.905826203, -0.374011947],   # a0: ρ², ρ, 1
                      [0.70609558, -1.35354548, 0.534644181],     # a1
                      [-0.36438888, 0.518083459, -0.183161384],   # a2
                      [0.05618723, -0.065556259, 0.021020194]])   # a3


def step_fillet_length(d: float, D: float, r: float) -> float:
    """Extra length (m, at the smaller diameter d) of a shaft step d → D with fillet radius r.

    Nestorides' chart as fitted in ``tsecdlf`` (docs/stiffness-formulas.md §4), with
    x = min(D/d, 3), ρ = r/(d/2):  ΔL/d = max(0, a3 x³ + a2 x² + a1 x + a0), 0 for ρ > 0.52.

    Parameters
    ----------
    d, D : float
        Smaller and larger diameter, m.
    r : float
        Fillet radius, m.
    """
    rho = r / (0.5 * d)
    if rho > 0.52:
        return 0.0
    a = _STEP_FIT @ np.array([rho**2, rho, 1.0])
    x = min(D / d, 3.0)
    return d * max(0.0, float(np.polyval(a[::-1], x)))


def chart(crank: Crank, web_index: int, d_e: float) -> float:
    """Web term from fetorsion's computed BICERA-style chart (:mod:`fetorsion.webchart`), m."""
    from .webchart import web_equivalent_length_chart

    return web_equivalent_length_chart(crank, web_index, d_e)


WEB_METHODS["chart"] = chart
