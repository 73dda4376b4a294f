"""Section formulas of [Seyedalian]: eq. (4)-(5) for round parts, eq. (7) for a web's effective
width, the BICERA overlap ratio, and Nestorides' stepped-shaft fillet length.

Every length is reduced to the equivalent diameter D_e (solid): a part of equivalent
length L_e has torsional stiffness k = G·J_e/L_e with J_e = π D_e⁴/32. The web term of
eq. (6) is a named web method (:mod:`fetorsion.webs.methods`).
"""

from __future__ import annotations

import numpy as np

from ..description.model import Crank, Cylinder, Web


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


