"""What the design explorer measures of a candidate besides M53 (:mod:`fetorsion.design.search`):
the crank's steel mass (the objective ``mass``), and the first elastic frequency of its lumped
chain with that frequency's clearance of the running range (the resonance constraint).
"""

from __future__ import annotations

import math

import numpy as np

from ..description.model import Crank
from ..solid.outline import mass_properties


def crank_mass(crank: Crank) -> float:
    """The crank's steel mass, kg: its cylinders (journals, pins, front and rear sections, bores
    taken out) and its webs (their outlines with counterweights, uniform thickness); fillets and
    drillings left out (a fraction of a percent). A CAD crank's (``[solid]``): its solid's, by
    OpenCASCADE, fillets and drillings in."""
    if crank.solid_step:
        from ..solid.geometry import cad_mass_properties

        return float(cad_mass_properties(crank)[0].mass)
    rho = crank.material.density
    cylinders = (*crank.journals, *crank.pins, *crank.front, *crank.rear)
    shafts = sum(rho * math.pi / 4 * (c.diameter**2 - c.bore**2) * c.length for c in cylinders)
    radius = crank.engine.stroke / 2
    return float(shafts + sum(mass_properties(w, radius, rho)["mass"] for w in crank.webs))


def first_elastic_hz(setup) -> float:
    """The first elastic (torsional) mode of ``setup``'s undamped model, Hz: of a free chain its
    second eigenvalue (the first is the rigid rotation), else the first of its torsional modes."""
    import scipy.linalg

    w2 = np.sort(scipy.linalg.eigh(setup.K, setup.M, eigvals_only=True))
    k = 1 if setup.torsional_modes is None else int(setup.torsional_modes[0])
    return float(math.sqrt(max(w2[k], 0.0)) / (2 * math.pi))


def resonance_clearance(f1_hz: float, orders, speed_range_rpm) -> float:
    """How far the resonance speeds n_q = 60 f1 / q of ``orders`` lie outside the running range
    [low, high] rpm, as a share of the range's nearer end: min over q of
    max(1 − n_q / low, n_q / high − 1); negative when one lies inside (its depth in)."""
    low, high = speed_range_rpm
    n = 60.0 * f1_hz / np.asarray(orders, float)
    return float(np.min(np.maximum(1.0 - n / low, n / high - 1.0)))
