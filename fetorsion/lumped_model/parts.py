"""The crank as an axial sequence of parts, each with its torsional compliance and inertia.

Inertias follow [Seyedalian]: pins eq. (14), journals and end sections eq. (16) with the bore
removed, oil drillings eq. (15)/(17) removed, webs from the exact analytic outline
(:mod:`fetorsion.solid.outline`). Stiffnesses follow eq. (3)–(6) via :mod:`fetorsion.webs.sections`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..description.model import AttachPoint, Crank, Cylinder
from ..description.defaults import DEFAULT_WEB_METHOD
from ..webs.methods import web_equivalent_length
from ..webs.sections import cylinder_equivalent_length
from ..solid.outline import mass_properties


@dataclass(frozen=True)
class Part:
    """One axial piece of the crank; SI units, x measured from the front end."""

    kind: str  # "front", "journal", "web", "pin", "rear"
    index: int  # 0-based within its kind
    x0: float
    x1: float
    equivalent_length: float  # m, at the equivalent diameter
    compliance: float  # rad/(N·m)
    inertia: float  # kg·m², the metal of the part
    attached_inertia: float = 0.0  # kg·m², spread along the part (pistons + rods on a pin)

    @property
    def label(self) -> str:
        return {"front": "F", "journal": "J", "web": "W", "pin": "P", "rear": "R"}[self.kind] + str(self.index + 1)


@dataclass(frozen=True)
class PartChain:
    """The crank cut into parts, plus the point inertias at its two end faces."""

    parts: tuple[Part, ...]
    front_inertia: float  # kg·m² at x = 0 (pulley and what is fixed to it)
    rear_inertia: float  # kg·m² at x = length (flywheel and accessories)
    equivalent_diameter: float  # m
    shear_modulus: float  # Pa
    web_method: str

    @property
    def length(self) -> float:
        return self.parts[-1].x1

    def of_kind(self, kind: str) -> list[Part]:
        return [p for p in self.parts if p.kind == kind]


def cylinder_inertia(c: Cylinder, density: float, radius: float = 0.0) -> float:
    """Polar inertia (kg·m²) of a hollow cylinder whose axis is ``radius`` off the crank axis.

    Eq. (16) for radius 0; eq. (14) with the bore removed for a pin.
    """
    area = math.pi / 4 * (c.diameter**2 - c.bore**2)
    return density * c.length * (math.pi / 32 * (c.diameter**4 - c.bore**4) + area * radius**2)


def oil_hole_inertia(c: Cylinder, hole_diameter: float, density: float, radius: float = 0.0) -> float:
    """Polar inertia (kg·m²) of the metal removed by a diametral drilling of a part.

    The drilling crosses the wall twice, each piece of length (D − d)/2 centred at
    (D + d)/4 from the part's axis. For a solid part this is the exact second moment of
    a cylinder of length h = D, m (φ²/16 + h²/12), which eq. (17) gives; eq. (15) as
    printed has h²/16 where the exact value is h²/12, so we use the exact form for both.
    """
    piece = (c.diameter - c.bore) / 2
    mass = density * math.pi / 4 * hole_diameter**2 * 2 * piece
    centre = (c.diameter + c.bore) / 4
    return mass * (hole_diameter**2 / 16 + piece**2 / 12 + centre**2 + radius**2)


def build_parts(crank: Crank, web_method: str = DEFAULT_WEB_METHOD, web_length=None) -> PartChain:
    """Cut ``crank`` into its axial parts with compliances and inertias.

    Parameters
    ----------
    crank : Crank
        The description.
    web_method : str
        Name of the web stiffness method (see :data:`fetorsion.webs.sections.WEB_METHODS`).
    web_length : callable, optional
        ``web_length(crank, web_index, d_e) -> L_eb`` (m) in place of the registry's function of
        ``web_method``: the same method evaluated on a model the caller already has (the ``fe-held``
        throws of a run's own condensed crank).
    """
    rho = crank.material.density
    G = crank.material.shear_modulus
    R = crank.engine.crank_radius
    d_e = crank.journals[0].diameter
    j_e = math.pi * d_e**4 / 32
    oil = crank.oil_holes
    piston = sum(a.polar_inertia for a in crank.attachments_at(AttachPoint.PINS))

    pieces: list[tuple[str, int, float, float, float, float]] = []  # kind, index, length, L_e, I, attached
    for i, c in enumerate(crank.front):
        pieces.append(("front", i, c.length, cylinder_equivalent_length(c, d_e), cylinder_inertia(c, rho), 0.0))
    for t in range(crank.cylinders + 1):
        j = crank.journals[t]
        inertia = cylinder_inertia(j, rho)
        if oil.in_journals:
            inertia -= oil_hole_inertia(j, oil.diameter, rho)
        pieces.append(("journal", t, j.length, cylinder_equivalent_length(j, d_e), inertia, 0.0))
        if t == crank.cylinders:
            break
        for side in (0, 1):
            w = 2 * t + side
            web = crank.webs[w]
            if side == 1:
                p = crank.pins[t]
                inertia = cylinder_inertia(p, rho, R)
                if oil.in_pins:
                    inertia -= oil_hole_inertia(p, oil.diameter, rho, R)
                pieces.append(("pin", t, p.length, cylinder_equivalent_length(p, d_e), inertia, piston))
            length = web_equivalent_length(crank, w, d_e, web_method) if web_length is None else web_length(crank, w, d_e)
            pieces.append(("web", w, web.thickness, length,
                           mass_properties(web, R, rho)["polar_inertia"], 0.0))
    for i, c in enumerate(crank.rear):
        pieces.append(("rear", i, c.length, cylinder_equivalent_length(c, d_e), cylinder_inertia(c, rho), 0.0))

    ends = np.concatenate([[0.0], np.cumsum([p[2] for p in pieces])])
    parts = tuple(
        Part(kind, idx, float(ends[n]), float(ends[n + 1]), le, le / (G * j_e), inertia, attached)
        for n, (kind, idx, _, le, inertia, attached) in enumerate(pieces)
    )
    return PartChain(
        parts,
        front_inertia=sum(a.polar_inertia for a in crank.attachments_at(AttachPoint.FRONT)),
        rear_inertia=sum(a.polar_inertia for a in crank.attachments_at(AttachPoint.REAR)),
        equivalent_diameter=d_e,
        shear_modulus=G,
        web_method=web_method,
    )
