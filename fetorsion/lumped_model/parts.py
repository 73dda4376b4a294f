"""The crank as an axial sequence of parts, each with its torsional compliance and inertia.

Inertias follow [Seyedalian]: pins eq. (14), journals and end sections eq. (16) with the bore
removed, oil drillings eq. (15)/(17) removed, webs from the exact analytic outline
(:mod:`fetorsion.solid.outline`). Stiffnesses follow eq. (3)–(6) via :mod:`fetorsion.webs.sections`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from ..description.cylinders import cylinders_per_throw
from ..description.model import PARTITIONS, AttachPoint, Crank, Cylinder, partition_labels
from ..errors import FetorsionError, ParameterError
from ..description.defaults import DEFAULT_WEB_METHOD
from ..webs.methods import web_equivalent_length
from ..webs.sections import cylinder_equivalent_length
from ..solid.outline import mass_properties

if TYPE_CHECKING:
    from collections.abc import Callable


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


def flying_web_inertia(pin: Cylinder, density: float, radius: float) -> float:
    """Polar inertia (kg·m²) about the crank axis of a split pin's flying web: a stadium, the convex
    hull of the two half pins' circles (radius r = D/2, centres c = 2R sin(|δ|/2) apart), ``flying_web``
    thick, its centre R cos(δ/2) off the axis. About its centre: the rectangle 2r × c,
    2rc (c² + 4r²)/12, and the two half discs, πr⁴/2 + πr²c²/4 + 4r³c/3 (each half disc by the
    parallel-axis theorem from its centroid, 4r/3π off its flat edge)."""
    r, d = 0.5 * pin.diameter, pin.split_angle
    c = 2.0 * radius * abs(math.sin(0.5 * d))
    own = 2 * r * c * (c**2 + 4 * r**2) / 12 + math.pi * r**4 / 2 + math.pi * r**2 * c**2 / 4 + 4 * r**3 * c / 3
    area = math.pi * r**2 + 2 * r * c
    return density * pin.flying_web * (own + area * (radius * math.cos(0.5 * d)) ** 2)


def pin_inertia(pin: Cylinder, density: float, radius: float, hole: float = 0.0) -> float:
    """Polar inertia (kg·m²) of a pin at ``radius`` from the crank axis less its drilling of diameter
    ``hole`` (0: none): eq. (14); a split pin is its two half pins (each drilled at its mid-length)
    and its flying web (:func:`flying_web_inertia`)."""
    if not pin.split:
        return cylinder_inertia(pin, density, radius) - (oil_hole_inertia(pin, hole, density, radius) if hole else 0.0)
    half = replace(pin, length=pin.half_length, split_angle=0.0, flying_web=0.0)
    return 2 * pin_inertia(half, density, radius, hole) + flying_web_inertia(pin, density, radius)


def build_parts(crank: Crank, web_method: str = DEFAULT_WEB_METHOD,
                web_length: Callable[[Crank, int, float], float] | None = None) -> PartChain:
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
    G = crank.material.shear_modulus
    d_e = crank.journals[0].diameter
    j_e = math.pi * d_e**4 / 32
    pieces = _pieces(crank, web_method, web_length, d_e)

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


def _pieces(crank: Crank, web_method: str, web_length, d_e: float) -> list[tuple[str, int, float, float, float, float]]:
    """The crank's axial pieces front to rear: (kind, index, length m, equivalent length m at the
    equivalent diameter ``d_e``, inertia kg·m², attached inertia kg·m²)."""
    rho = crank.material.density
    R = crank.engine.crank_radius
    oil = crank.oil_holes
    piston = sum(a.polar_inertia for a in crank.attachments_at(AttachPoint.PINS))  # per cylinder
    rods = cylinders_per_throw(crank.engine)
    if crank.solid_step:  # a CAD crank: its parts' inertias integrated on its own solid
        from ..solid.geometry import part_inertias

        solid = part_inertias(crank)
    else:
        solid = {}

    def own(kind: str, index: int, formula: float) -> float:
        return solid.get(f"{kind}_{index + 1}", formula)

    pieces: list[tuple[str, int, float, float, float, float]] = []  # kind, index, length, L_e, I, attached
    for i, c in enumerate(crank.front):
        pieces.append(("front", i, c.length, cylinder_equivalent_length(c, d_e), own("front", i, cylinder_inertia(c, rho)),
                       0.0))
    for t in range(crank.throws + 1):
        j = crank.journals[t]
        inertia = cylinder_inertia(j, rho)
        if oil.in_journals:
            inertia -= oil_hole_inertia(j, oil.diameter, rho)
        pieces.append(("journal", t, j.length, cylinder_equivalent_length(j, d_e), own("journal", t, inertia), 0.0))
        if t == crank.throws:
            break
        for side in (0, 1):
            w = 2 * t + side
            web = crank.webs[w]
            if side == 1:
                p = crank.pins[t]
                inertia = pin_inertia(p, rho, R, oil.diameter if oil.in_pins else 0.0)
                pieces.append(("pin", t, p.length, cylinder_equivalent_length(p, d_e), own("pin", t, inertia),
                               float(piston * rods[t])))
            length = web_equivalent_length(crank, w, d_e, web_method) if web_length is None else web_length(crank, w, d_e)
            pieces.append(("web", w, web.thickness, length, own("web", w, mass_properties(web, R, rho)["polar_inertia"]),
                           0.0))
    for i, c in enumerate(crank.rear):
        pieces.append(("rear", i, c.length, cylinder_equivalent_length(c, d_e), own("rear", i, cylinder_inertia(c, rho)),
                       0.0))
    return pieces


@dataclass(frozen=True)
class Station:
    label: str
    lo: float
    hi: float
    anchor: float


def stations(chain: PartChain, partition: int) -> list[Station]:
    """The stations of ``partition`` (one of :data:`~fetorsion.description.model.PARTITIONS`) on
    ``chain``, named by :func:`~fetorsion.description.model.partition_labels` (the names a network
    file uses for a crank's stations)."""
    if partition not in PARTITIONS:
        raise ParameterError("dof", f"{partition!r} is not a partition; choose from {PARTITIONS}")
    journals, webs, pins = chain.of_kind("journal"), chain.of_kind("web"), chain.of_kind("pin")
    labels = partition_labels(len(pins), partition)
    L = chain.length
    mid = lambda p: 0.5 * (p.x0 + p.x1)  # noqa: E731
    front_end, rear_end = journals[0].x0, journals[-1].x1
    if partition == 5:
        cuts = [0.0] + [mid(p) for p in pins] + [L]
        anchors = [0.0] + [mid(j) for j in journals[1:-1]] + [L]
    elif partition == 6:
        cuts = [0.0] + [mid(j) for j in journals] + [L]
        anchors = [0.0] + [mid(p) for p in pins] + [L]
    else:
        inner = sorted(journals + webs + pins, key=lambda p: p.x0)
        cuts = [p.x0 for p in inner] + [inner[-1].x1]
        anchors = [mid(p) for p in inner]
        if partition == 17:
            cuts[0], cuts[-1] = 0.0, L
        elif partition == 19:
            cuts, anchors = [0.0] + cuts + [L], [0.0] + anchors + [L]
        else:
            half_f, half_r = 0.5 * front_end, 0.5 * (L + rear_end)
            cuts = [0.0, half_f] + cuts + [half_r, L]
            anchors = [0.0, 0.5 * (half_f + front_end)] + anchors + [0.5 * (rear_end + half_r), L]
    return [Station(n, a, b, x) for n, a, b, x in zip(labels, cuts[:-1], cuts[1:], anchors, strict=True)]


def partition_matrices(chain: PartChain, partition: int):
    """Station inertias (kg·m²), springs (N·m/rad), labels and anchors of a partition."""
    st = stations(chain, partition)
    edges = np.array([chain.parts[0].x0] + [p.x1 for p in chain.parts])
    cum_compliance = np.concatenate([[0.0], np.cumsum([p.compliance for p in chain.parts])])
    cum_inertia = np.concatenate([[0.0], np.cumsum([p.inertia + p.attached_inertia for p in chain.parts])])
    lo = np.array([s.lo for s in st])
    hi = np.array([s.hi for s in st])
    anchors = np.array([s.anchor for s in st])
    # Both cumulative functions are piecewise linear in x, so interpolation is exact.
    inertias = np.interp(hi, edges, cum_inertia) - np.interp(lo, edges, cum_inertia)
    inertias[0] += chain.front_inertia
    inertias[-1] += chain.rear_inertia
    springs = 1.0 / np.diff(np.interp(anchors, edges, cum_compliance))
    empty = [s.label for s, i in zip(st, inertias) if not i > 0]
    if empty:
        raise FetorsionError(
            f"the {partition}-DOF partition has stations without inertia ({', '.join(empty)}): "
            "it needs front/rear sections or attachments at the crank ends")
    return inertias, springs, [s.label for s in st], anchors


def pin_weights(chain: PartChain, partition: int) -> np.ndarray:
    """(cylinders × stations) share of each pin in each station of a lumped partition.

    The cylinder torque acts where the pin is; a pin split between two stations (the 5-DOF
    model) passes its torque on in the same shares as its inertia.
    """
    st = stations(chain, partition)
    lo = np.array([s.lo for s in st])
    hi = np.array([s.hi for s in st])
    pins = chain.of_kind("pin")
    x0 = np.array([p.x0 for p in pins])[:, None]
    x1 = np.array([p.x1 for p in pins])[:, None]
    overlap = np.clip(np.minimum(x1, hi) - np.maximum(x0, lo), 0.0, None)
    return overlap / (x1 - x0)
