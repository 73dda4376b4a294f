"""Crank fatigue strength, equivalent stresses and safety factors, as pure functions.

Input: per location (pin fillet, journal fillet, oil-bore exit) the bending normal stress σ and
the torsional shear stress τ at the surface, as mean and alternating parts or as histories over
a cycle (arrays over crank angle), either local (already times the stress concentration factors:
leave ``kt_bending = kt_torsion = 1``) or nominal with their K_t. SI at the API (Pa, m); each
rule's own units (N/mm², mm; kpsi, in) only inside. Every formula, its source and what could not
be confirmed is in ``docs/fatigue.md``.

Two paths, and two multiaxial criteria as a cross-check:

* ``"iacs-m53"``: the classification rule [IACSM53] §5–§7. Fatigue strength σ_DW (§6) from the
  tensile strength, the diameter, the fillet radius (oil bore: half its diameter) and the
  manufacturing factor K, read from Indian Register of Shipping, *Classification Notes:
  Calculation of Crankshafts for Internal Combustion Engines* (2012), Section 6, which states
  M53's text (its fatigue-strength page as extracted by yumpu.com: the constants 0.42, 39.3,
  0.264, 1.073, 785, 4900, 196, R_X, and K = 1.05 / 1.0 / 0.93 with "values greater than 1 only
  in the fillet area"). The exponent −0.2 of D is garbled in that extraction ("0.2" survives,
  the sign does not) and is taken as −0.2. The equivalent alternating stresses (§5) and the
  required acceptability factor Q ≥ 1.15 (§7) could **not** be confirmed from a readable copy:
  they are implemented as the issue states them, and reduce correctly in the limiting cases
  (pure bending: σ_V = σ; pure torsion at the bore: σ_V = τ; at a fillet: √3 τ).
* ``"textbook"``: [Budynas] ch. 6 (Shigley's, 9th ed.): S'_e = 0.5 S_ut (700 MPa above
  1400 MPa, eq. 6-8), Marin factors k_a (Table 6-2, eq. 6-19), k_b (eq. 6-20), k_c (eq. 6-26),
  k_e (Table 6-5), Neuber notch sensitivity (eqs. 6-33 to 6-35a/b), the von Mises alternating and
  midrange stresses of combined loading (eqs. 6-55, 6-56: k_c = 1, K_f and K_fs on the stresses),
  modified Goodman and Gerber (eqs. 6-46, 6-47) and first-cycle yield.
* :func:`crossland` and :func:`findley` on a stress history ([Crossland], [Findley]): both reduce
  to σ_a ≤ f₋₁ in fully reversed bending and to τ_a ≤ t₋₁ in fully reversed torsion.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace

import numpy as np

from ..description.model import PROCESSES, SURFACES, Material
from ..errors import FetorsionError

MPA = 1e6  # Pa per N/mm²
KPSI = 6.894757293168361e6  # Pa per kpsi (1000 lbf/in², lbf = 4.4482216152605 N, in = 0.0254 m)
INCH = 0.0254  # m

#: Acceptability factor Q = σ_DW / σ_V required by [IACSM53] §7 (not confirmed from a readable copy).
M53_REQUIRED_Q = 1.15
#: [IACSM53] §6 factor K by manufacturing route (IRS Classification Notes 2012, Section 6).
M53_PROCESS_FACTOR = {"continuous-grain-flow": 1.05, "drop-forged": 1.05, "free-form-forged": 1.0,
                      "cast-cold-rolled": 0.93}
#: Marin surface factor k_a = a S_ut^b, S_ut in MPa: (a, b) from [Budynas] Table 6-2.
MARIN_SURFACE = {"ground": (1.58, -0.085), "machined": (4.51, -0.265), "cold-drawn": (4.51, -0.265),
                 "hot-rolled": (57.7, -0.718), "as-forged": (272.0, -0.995)}
#: Reliability factor k_e by reliability, [Budynas] Table 6-5 (8 % standard deviation of S_e).
RELIABILITY_FACTOR = {0.5: 1.000, 0.9: 0.897, 0.95: 0.868, 0.99: 0.814, 0.999: 0.753, 0.9999: 0.702}
#: Marin load factor k_c, [Budynas] eq. 6-26 (combined loading by von Mises uses "bending": 1).
LOAD_FACTOR = {"bending": 1.0, "axial": 0.85, "torsion": 0.59}
#: Reliability of the endurance limit unless stated: the mean (k_e = 1).
DEFAULT_RELIABILITY = 0.5
#: The kinds of location; an oil bore's notch is its bore (radius half its diameter).
KINDS = ("pin-fillet", "journal-fillet", "oil-bore")
METHODS = ("iacs-m53", "textbook")

assert set(M53_PROCESS_FACTOR) == set(PROCESSES) and set(MARIN_SURFACE) == set(SURFACES)


#: The least safe places a fatigue figure names in colour (the Haigh diagram's points; the rest grey)
HAIGH_LOCATIONS = 3


@dataclass(frozen=True)
class FatigueMaterial:
    """Static strengths (Pa), surface and manufacturing route of a crank's steel."""

    tensile_strength: float
    yield_strength: float
    surface: str
    process: str
    name: str = ""
    source: str = ""
    #: The user's alternating bending fatigue strength against local stresses, Pa (``[limits]
    #: fatigue_strength_bending_pa``): replaces M53's σ_DW and the textbook's S_e when set.
    fatigue_strength: float | None = None
    fatigue_strength_source: str = ""
    #: The fillets' surface treatment (``none``: untreated), its factor on the local fatigue
    #: strength and the factor's source, as the description states them.
    surface_treatment: str = "none"
    treatment_factor: float = 1.0
    treatment_source: str = ""


#: Used where the description gives no strength: 42CrMo4 (1.7225, ~SAE 4140) quenched and
#: tempered, the minimum strengths of EN 10083-3:2006 Table 7 for the ruling section
#: 40 < d ≤ 100 mm (car and light-truck crank journals): R_m 900–1100 MPa (minimum taken),
#: R_e ≥ 650 MPa; machined fillets, drop forged.
DEFAULT_FORGING_STEEL = FatigueMaterial(
    900e6, 650e6, "machined", "drop-forged", "42CrMo4 +QT",
    "EN 10083-3:2006, 42CrMo4 +QT, 40 < d <= 100 mm: Rm min 900 MPa, Re min 650 MPa")


def fatigue_material(material: Material | None) -> tuple[FatigueMaterial, list[str]]:
    """The description's strength fields, each missing one from :data:`DEFAULT_FORGING_STEEL`.

    Returns the material and the names of the fields that were defaulted (for the report).
    """
    d = DEFAULT_FORGING_STEEL
    given = {f: getattr(material, f, None) for f in ("tensile_strength", "yield_strength", "surface", "process")}
    defaulted = [f for f, v in given.items() if v is None]
    values = {f: getattr(d, f) if v is None else v for f, v in given.items()}
    name = (material.name if material is not None and material.name else "") or d.name
    source = d.source if defaulted else "description"
    if defaulted and len(defaulted) < 4:
        source = f"description; {', '.join(defaulted)} from {d.source}"
    treatment = getattr(material, "surface_treatment", None) or "none"
    factor = getattr(material, "surface_treatment_factor", None) if treatment != "none" else None
    return FatigueMaterial(**values, name=name, source=source, surface_treatment=treatment,
                           treatment_factor=factor or 1.0,
                           treatment_source=getattr(material, "surface_treatment_source", "") if factor else ""), defaulted


# ---------------------------------------------------------------------------
# Classification rule: IACS UR M53

def m53_fatigue_strength(tensile_strength: float, diameter: float, notch_radius: float,
                         process: str = "drop-forged", kind: str = "pin-fillet") -> float:
    """σ_DW of [IACSM53] §6, Pa.

    σ_DW = K (0.42 σ_B + 39.3) [0.264 + 1.073 D^−0.2 + (785 − σ_B)/4900 + (196/σ_B) √(1/R_X)]

    with σ_B in N/mm², D and R_X in mm. D: crankpin diameter for the pin fillet and the oil
    bore, journal diameter for the journal fillet; R_X: the fillet radius, or half the oil-bore
    diameter. K > 1 applies only in the fillets (the oil bore takes min(K, 1)).

    Parameters
    ----------
    tensile_strength : float
        Minimum tensile strength σ_B, Pa.
    diameter : float
        D (or D_G), m.
    notch_radius : float
        R_H / R_G (fillet radius) or D_O/2 (oil bore), m.
    process : str
        One of :data:`M53_PROCESS_FACTOR`.
    kind : str
        One of :data:`KINDS`.
    """
    if process not in M53_PROCESS_FACTOR:
        raise FetorsionError(f"process must be one of {', '.join(M53_PROCESS_FACTOR)}, got {process!r}")
    _check_kind(kind)
    if not (tensile_strength > 0 and diameter > 0 and notch_radius > 0):
        raise FetorsionError("tensile strength, diameter and notch radius must be > 0")
    k = M53_PROCESS_FACTOR[process]
    if kind == "oil-bore":
        k = min(k, 1.0)
    sb, d, r = tensile_strength / MPA, diameter * 1e3, notch_radius * 1e3
    return MPA * k * (0.42 * sb + 39.3) * (0.264 + 1.073 * d**-0.2 + (785.0 - sb) / 4900.0
                                           + 196.0 / sb * math.sqrt(1.0 / r))


def m53_equivalent_fillet(bending_alt, torsion_alt, additional_bending: float = 0.0):
    """σ_V = √((σ_BH + σ_add)² + 3 τ_H²) of [IACSM53] §5 at a fillet, Pa (amplitudes, local)."""
    return np.sqrt((np.abs(bending_alt) + additional_bending) ** 2 + 3.0 * np.square(torsion_alt))


def m53_equivalent_oil_bore(bending_alt, torsion_alt):
    """σ_V = (1/3) σ_BO [1 + 2 √(1 + (9/4)(τ_TO/σ_BO)²)] of [IACSM53] §5 at the oil-bore exit, Pa,
    written as |σ|/3 + (2/3) √(σ² + (9/4) τ²) so that σ_BO = 0 gives |τ|."""
    s, t = np.abs(bending_alt), np.abs(torsion_alt)
    return s / 3.0 + 2.0 / 3.0 * np.sqrt(s**2 + 2.25 * t**2)


# ---------------------------------------------------------------------------
# Textbook: Budynas–Nisbett (Shigley) ch. 6

def specimen_endurance_limit(tensile_strength: float) -> float:
    """S'_e = 0.5 S_ut for S_ut ≤ 1400 MPa, else 700 MPa ([Budynas] eq. 6-8), Pa."""
    return 0.5 * tensile_strength if tensile_strength <= 1400 * MPA else 700 * MPA


def marin_surface(tensile_strength: float, surface: str) -> float:
    """k_a = a S_ut^b, S_ut in MPa ([Budynas] eq. 6-19, Table 6-2)."""
    if surface not in MARIN_SURFACE:
        raise FetorsionError(f"surface must be one of {', '.join(MARIN_SURFACE)}, got {surface!r}")
    a, b = MARIN_SURFACE[surface]
    return a * (tensile_strength / MPA) ** b


def marin_size(diameter: float) -> float:
    """k_b of a rotating round in bending or torsion, d in mm ([Budynas] eq. 6-20):
    (d/7.62)^−0.107 (printed also as 1.24 d^−0.107; the book's examples use the first form) for
    2.79 ≤ d ≤ 51 mm, 1.51 d^−0.157 for 51 < d ≤ 254 mm."""
    d = diameter * 1e3
    if 2.79 <= d <= 51.0:
        return (d / 7.62) ** -0.107
    if 51.0 < d <= 254.0:
        return 1.51 * d**-0.157
    raise FetorsionError(f"the Marin size factor holds for 2.79 <= d <= 254 mm, got {d:.4g} mm")


def marin_reliability(reliability: float) -> float:
    """k_e of [Budynas] Table 6-5 for a reliability in :data:`RELIABILITY_FACTOR`."""
    for r, k in RELIABILITY_FACTOR.items():
        if math.isclose(r, reliability, abs_tol=1e-12):
            return k
    raise FetorsionError(f"reliability must be one of {', '.join(map(str, RELIABILITY_FACTOR))}, got {reliability}")


def endurance_limit(tensile_strength: float, diameter: float, surface: str, reliability: float = DEFAULT_RELIABILITY,
                    load: str = "bending", temperature_factor: float = 1.0) -> float:
    """S_e = k_a k_b k_c k_d k_e S'_e ([Budynas] eq. 6-18; k_f, miscellaneous, = 1), Pa."""
    if load not in LOAD_FACTOR:
        raise FetorsionError(f"load must be one of {', '.join(LOAD_FACTOR)}, got {load!r}")
    return (marin_surface(tensile_strength, surface) * marin_size(diameter) * LOAD_FACTOR[load]
            * temperature_factor * marin_reliability(reliability) * specimen_endurance_limit(tensile_strength))


def neuber_sqrt_a(tensile_strength: float, torsion: bool = False) -> float:
    """Neuber's √a of steel, √m ([Budynas] eq. 6-35a bending/axial, 6-35b torsion; fits in √in
    with S_ut in kpsi)."""
    s = tensile_strength / KPSI
    root_in = (0.190 - 2.51e-3 * s + 1.35e-5 * s**2 - 2.67e-8 * s**3 if torsion
               else 0.246 - 3.08e-3 * s + 1.51e-5 * s**2 - 2.67e-8 * s**3)
    return root_in * math.sqrt(INCH)


def notch_sensitivity(tensile_strength: float, notch_radius: float, torsion: bool = False) -> float:
    """q = 1 / (1 + √a / √r) ([Budynas] eq. 6-34)."""
    return 1.0 / (1.0 + neuber_sqrt_a(tensile_strength, torsion) / math.sqrt(notch_radius))


def fatigue_notch_factor(kt: float, q: float) -> float:
    """K_f = 1 + q (K_t − 1) ([Budynas] eq. 6-32)."""
    return 1.0 + q * (kt - 1.0)


def von_mises(sigma, tau):
    """√(σ² + 3 τ²): the von Mises stress of σ_xx = σ, τ_xy = τ (Pa)."""
    return np.sqrt(np.square(sigma) + 3.0 * np.square(tau))


def goodman_safety(alternating: float, mean: float, endurance: float, tensile_strength: float) -> float:
    """n = 1 / (σ_a/S_e + σ_m/S_ut): modified Goodman ([Budynas] eq. 6-46)."""
    return 1.0 / (alternating / endurance + mean / tensile_strength)


def gerber_safety(alternating: float, mean: float, endurance: float, tensile_strength: float) -> float:
    """n = ½ (S_ut/σ_m)² (σ_a/S_e) [−1 + √(1 + (2 σ_m S_e / (S_ut σ_a))²)] ([Budynas] eq. 6-47);
    S_e/σ_a without mean stress, S_ut/σ_m without alternating stress."""
    if mean <= 0.0:
        return endurance / alternating
    if alternating <= 0.0:
        return tensile_strength / mean
    x = 2.0 * mean * endurance / (tensile_strength * alternating)
    return 0.5 * (tensile_strength / mean) ** 2 * (alternating / endurance) * (-1.0 + math.sqrt(1.0 + x * x))


# ---------------------------------------------------------------------------
# Stress histories and the two multiaxial criteria

def mean_alternating(history) -> tuple[float, float]:
    """(mean, alternating) = ((max + min)/2, (max − min)/2) of one stress component's history."""
    x = np.asarray(history, dtype=float)
    return 0.5 * float(x.max() + x.min()), 0.5 * float(x.max() - x.min())


def _histories(sigma, tau) -> tuple[np.ndarray, np.ndarray]:
    s, t = np.atleast_1d(np.asarray(sigma, dtype=float)), np.atleast_1d(np.asarray(tau, dtype=float))
    if s.shape != t.shape or s.ndim != 1:
        raise FetorsionError(f"sigma and tau must be 1-D histories of one length, got {s.shape} and {t.shape}")
    return s, t


def crossland(sigma, tau, bending_limit: float, torsion_limit: float) -> dict:
    """Crossland's criterion √J2,a + α p_max ≤ β on a plane-stress history σ_xx = σ(t), τ_xy = τ(t).

    α = 3 t₋₁/f₋₁ − √3, β = t₋₁ ([Crossland]; [Papadopoulos] for the constants). √J2,a is taken
    as half the longest chord of the deviatoric path in the √J2 norm (√J2 of the difference of
    two states: √((Δσ)²/3 + Δτ²)): exact for proportional histories, a lower bound on the
    minimum circumscribed circle's radius otherwise (by at most 1 − √3/2 ≈ 13 %, Jung's bound
    in 2-D). p_max = max σ/3.

    Returns ``sqrt_j2a``, ``p_max`` (Pa), ``value`` (left side, Pa), ``limit`` (β, Pa) and
    ``safety`` = β / value (the loads' common factor to the limit, all terms scaling linearly).
    """
    s, t = _histories(sigma, tau)
    chord = np.sqrt((s[:, None] - s[None, :]) ** 2 / 3.0 + (t[:, None] - t[None, :]) ** 2).max()
    sqrt_j2a, p_max = 0.5 * float(chord), float(s.max()) / 3.0
    alpha = 3.0 * torsion_limit / bending_limit - math.sqrt(3.0)
    value = sqrt_j2a + alpha * p_max
    return {"sqrt_j2a": sqrt_j2a, "p_max": p_max, "value": value, "limit": torsion_limit,
            "safety": torsion_limit / value if value > 0 else math.inf}


def findley_k(bending_limit: float, torsion_limit: float) -> float:
    """Findley's k from the two fatigue limits: for this plane search, reversed bending gives
    (f₋₁/2)(k + √(1+k²)) and reversed torsion t₋₁√(1+k²) at the limit, so with r = t₋₁/f₋₁,
    k = (2r − 1)/√(1 − (2r − 1)²) (0.5 < r < 1)."""
    r = torsion_limit / bending_limit
    if not 0.5 <= r < 1.0:
        raise FetorsionError(f"Findley's k needs 0.5 <= t/f < 1, got {r:.4g}")
    u = 2.0 * r - 1.0
    return u / math.sqrt(1.0 - u * u)


def findley(sigma, tau, bending_limit: float, torsion_limit: float, planes: int = 1800) -> dict:
    """Findley's critical plane: max over planes of τ_a + k σ_n,max ≤ λ ([Findley]).

    Planes are those perpendicular to the free surface, normal n = (cos θ, sin θ, 0), θ on a
    grid of ``planes`` angles over [0, π) (the search is vectorised over angles and time);
    on them σ_n = σ cos²θ + τ sin 2θ, τ_nt = −(σ/2) sin 2θ + τ cos 2θ, τ_a = half the range of
    τ_nt. k from :func:`findley_k`, λ = t₋₁ √(1 + k²). The grid misses the exact maximum by a
    relative 1 − cos(π/planes) at most.

    Returns ``value``, ``limit`` (Pa), ``angle_rad`` of the critical plane, ``k`` and ``safety``.
    """
    s, t = _histories(sigma, tau)
    k = findley_k(bending_limit, torsion_limit)
    theta = np.arange(planes) * (math.pi / planes)
    c2, s2 = np.cos(2 * theta)[:, None], np.sin(2 * theta)[:, None]
    normal = 0.5 * s * (1.0 + c2) + t * s2
    shear = -0.5 * s * s2 + t * c2
    damage = 0.5 * (shear.max(axis=1) - shear.min(axis=1)) + k * normal.max(axis=1)
    i = int(np.argmax(damage))
    limit = torsion_limit * math.sqrt(1.0 + k * k)
    value = float(damage[i])
    return {"value": value, "limit": limit, "angle_rad": float(theta[i]), "k": k,
            "safety": limit / value if value > 0 else math.inf}


# ---------------------------------------------------------------------------
# Locations, assessments, run

@dataclass(frozen=True)
class LocationStress:
    """Stresses at one location over a cycle, Pa, and its geometry, m.

    ``bending_*`` is the surface normal stress from bending, ``torsion_*`` the shear stress from
    torsion: local when ``kt_bending = kt_torsion = 1`` (the textbook path then takes K_f = K_t,
    full notch sensitivity), else nominal with these K_t. ``diameter`` is the rule's D (pin
    diameter for a pin fillet and the oil bore, journal diameter for a journal fillet);
    ``notch_radius`` the fillet radius or half the oil-bore diameter. ``additional_bending`` is
    [IACSM53] §4's σ_add (fillets only). Histories, when given, feed the criteria cross-check.
    """

    name: str
    kind: str
    diameter: float
    notch_radius: float
    bending_alt: float
    torsion_alt: float
    bending_mean: float = 0.0
    torsion_mean: float = 0.0
    kt_bending: float = 1.0
    kt_torsion: float = 1.0
    additional_bending: float = 0.0
    bending_history: tuple | None = field(default=None, repr=False)
    torsion_history: tuple | None = field(default=None, repr=False)

    @classmethod
    def from_history(cls, name: str, kind: str, diameter: float, notch_radius: float, bending, torsion,
                     **kwargs) -> "LocationStress":
        """Mean and alternating parts of each component from histories over crank angle."""
        s, t = _histories(bending, torsion)
        bm, ba = mean_alternating(s)
        tm, ta = mean_alternating(t)
        return cls(name, kind, diameter, notch_radius, ba, ta, bm, tm, bending_history=tuple(s),
                   torsion_history=tuple(t), **kwargs)


@dataclass(frozen=True)
class FatigueAssessment:
    """One location's verdict: strength and equivalent stresses (Pa), safety against the required.

    ``safety`` is Q = σ_DW/σ_V for ``iacs-m53`` and the Goodman (or Gerber) factor for
    ``textbook``; ``yield_safety`` the textbook first-cycle yield factor (None for M53);
    ``criteria`` the Crossland and Findley safety factors on the location's history, if any.
    """

    name: str
    kind: str
    method: str
    strength: float
    equivalent_alternating: float
    equivalent_mean: float
    safety: float
    required: float
    yield_safety: float | None = None
    factors: dict = field(default_factory=dict)
    criteria: dict = field(default_factory=dict)

    @property
    def passes(self) -> bool:
        return self.safety >= self.required and (self.yield_safety is None or self.yield_safety >= 1.0)

    def to_dict(self) -> dict:
        return {"name": self.name, "kind": self.kind, "method": self.method, "strength_pa": self.strength,
                "equivalent_alternating_pa": self.equivalent_alternating,
                "equivalent_mean_pa": self.equivalent_mean, "safety": self.safety, "required": self.required,
                "yield_safety": self.yield_safety, "passes": self.passes, "factors": dict(self.factors),
                "criteria": {k: dict(v) for k, v in self.criteria.items()}}

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "FatigueAssessment":
        """The assessment back from its :meth:`to_dict`."""
        from ..results import from_fields

        return from_fields(cls, d, {"strength": "strength_pa", "equivalent_alternating": "equivalent_alternating_pa",
                                    "equivalent_mean": "equivalent_mean_pa"})


@dataclass(frozen=True)
class FatigueResult:
    """Every location's assessment, the governing one (least safety over required) and the material."""

    method: str
    material: FatigueMaterial
    defaulted: tuple
    locations: tuple

    @property
    def governing(self) -> FatigueAssessment:
        return min(self.locations, key=lambda a: a.safety / a.required)

    @property
    def passes(self) -> bool:
        return all(a.passes for a in self.locations)

    def to_dict(self) -> dict:
        """Every figure of the result as plain JSON-ready numbers, lists and strings (SI, or the unit in its key)."""
        m = self.material
        return {"method": self.method, "governing": self.governing.name, "passes": self.passes,
                "material": {"name": m.name, "tensile_strength_pa": m.tensile_strength,
                             "yield_strength_pa": m.yield_strength, "surface": m.surface, "process": m.process,
                             "source": m.source, "defaulted": list(self.defaulted),
                             "fatigue_strength_pa": m.fatigue_strength, "fatigue_strength_source": m.fatigue_strength_source,
                             "surface_treatment": m.surface_treatment, "treatment_factor": m.treatment_factor,
                             "treatment_source": m.treatment_source},
                "locations": [a.to_dict() for a in self.locations]}

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "FatigueResult":
        """The result back from its :meth:`to_dict` (a material written before its fatigue strength
        and surface treatment were kept: without them)."""
        from ..results import from_fields

        m = d["material"]
        material = from_fields(FatigueMaterial, m, {"tensile_strength": "tensile_strength_pa",
                                                    "yield_strength": "yield_strength_pa",
                                                    "fatigue_strength": "fatigue_strength_pa"})
        return cls(d["method"], material, tuple(m["defaulted"]), tuple(FatigueAssessment.from_dict(a) for a in d["locations"]))


def _check_kind(kind: str) -> None:
    if kind not in KINDS:
        raise FetorsionError(f"location kind must be one of {', '.join(KINDS)}, got {kind!r}")


def assess_m53(loc: LocationStress, mat: FatigueMaterial, required: float = M53_REQUIRED_Q) -> FatigueAssessment:
    """[IACSM53]: local alternating stresses (K_t times nominal) against σ_DW; mean stresses are
    not part of the rule."""
    _check_kind(loc.kind)
    sb, tb = loc.kt_bending * abs(loc.bending_alt), loc.kt_torsion * abs(loc.torsion_alt)
    if loc.kind == "oil-bore":
        sv = float(m53_equivalent_oil_bore(sb, tb))
    else:
        sv = float(m53_equivalent_fillet(sb, tb, loc.additional_bending))
    dw = mat.fatigue_strength or m53_fatigue_strength(mat.tensile_strength, loc.diameter, loc.notch_radius,
                                                      mat.process, loc.kind)
    return FatigueAssessment(loc.name, loc.kind, "iacs-m53", dw, sv, 0.0, dw / sv if sv > 0 else math.inf,
                             required, factors={"K": M53_PROCESS_FACTOR[mat.process] if loc.kind != "oil-bore"
                                                else min(M53_PROCESS_FACTOR[mat.process], 1.0)})


def assess_textbook(loc: LocationStress, mat: FatigueMaterial, required: float = 1.0, mean_stress: str = "goodman",
                    reliability: float = DEFAULT_RELIABILITY, temperature_factor: float = 1.0) -> FatigueAssessment:
    """[Budynas] ch. 6: K_f, K_fs by Neuber on the nominal stresses, von Mises alternating and
    mean equivalents, S_e with k_c = 1, Goodman or Gerber, and first-cycle yield
    n_y = S_y / σ'_max with σ'_max = √((K_f(σ_m + σ_a))² + 3 (K_fs(τ_m + τ_a))²)."""
    _check_kind(loc.kind)
    if mean_stress not in ("goodman", "gerber"):
        raise FetorsionError(f"mean_stress must be goodman or gerber, got {mean_stress!r}")
    if mat.fatigue_strength:  # the user's strength is against local stresses: full K_t (q = 1)
        q = qs = 1.0
    else:
        q = notch_sensitivity(mat.tensile_strength, loc.notch_radius)
        qs = notch_sensitivity(mat.tensile_strength, loc.notch_radius, torsion=True)
    kf, kfs = fatigue_notch_factor(loc.kt_bending, q), fatigue_notch_factor(loc.kt_torsion, qs)
    sa = float(von_mises(kf * loc.bending_alt, kfs * loc.torsion_alt))
    sm = float(von_mises(kf * loc.bending_mean, kfs * loc.torsion_mean))
    se = mat.fatigue_strength or endurance_limit(mat.tensile_strength, loc.diameter, mat.surface, reliability,
                                                 "bending", temperature_factor)
    n = (goodman_safety if mean_stress == "goodman" else gerber_safety)(sa, sm, se, mat.tensile_strength)
    smax = float(von_mises(kf * (abs(loc.bending_mean) + abs(loc.bending_alt)),
                           kfs * (abs(loc.torsion_mean) + abs(loc.torsion_alt))))
    factors = {"q": q, "q_shear": qs, "Kf": kf, "Kfs": kfs,
               "ka": marin_surface(mat.tensile_strength, mat.surface), "kb": marin_size(loc.diameter),
               "ke": marin_reliability(reliability), "mean_stress": mean_stress}
    return FatigueAssessment(loc.name, loc.kind, "textbook", se, sa, sm, n, required,
                             yield_safety=mat.yield_strength / smax if smax > 0 else math.inf, factors=factors)


def with_limits(mat: FatigueMaterial, limits, required: float | None = None) -> tuple[FatigueMaterial, float | None]:
    """The description's ``[limits]`` applied: its ``fatigue_strength_bending`` (Pa, against local
    stresses) as the material's fatigue strength, and its ``fatigue_required_safety`` as the
    required safety unless ``required`` is given (None when neither says)."""
    if limits is not None and getattr(limits, "fatigue_strength_bending", 0.0) > 0:
        mat = replace(mat, fatigue_strength=float(limits.fatigue_strength_bending),
                      fatigue_strength_source=f"[limits] fatigue_strength_bending_pa ({limits.source})")
    if required is None and limits is not None and getattr(limits, "fatigue_required_safety", 0.0) > 0:
        required = float(limits.fatigue_required_safety)
    return mat, required


def run_fatigue(locations, material: Material | FatigueMaterial | None = None, method: str = "iacs-m53",
                required: float | None = None, mean_stress: str = "goodman",
                reliability: float = DEFAULT_RELIABILITY, limits=None) -> FatigueResult:
    """Assess every location by one method and name the governing one.

    Parameters
    ----------
    locations : iterable of LocationStress
        Each location's nominal stresses (Pa), SCFs, diameter and notch radius (m).
    material : Material, FatigueMaterial or None
        The description's material (missing strength fields from :data:`DEFAULT_FORGING_STEEL`),
        or strengths directly.
    method : {"iacs-m53", "textbook"}
        IACS UR M53 (alternating stresses against σ_DW) or the textbook path (Marin, Neuber,
        Goodman or Gerber).
    required : float, optional
        Required safety: default :data:`M53_REQUIRED_Q` for M53, 1.0 (the criterion itself) for
        the textbook path, where the caller states its design factor.
    mean_stress : {"goodman", "gerber"}
        Textbook path only.
    reliability : float
        Textbook path only, a key of :data:`RELIABILITY_FACTOR`.
    limits : Limits, optional
        The description's ``[limits]``: its ``fatigue_strength_bending`` (Pa, against local
        stresses) replaces the method's strength, its ``fatigue_required_safety`` the default
        required safety (an explicit ``required`` still wins).

    Where a location carries histories, its ``criteria`` hold the Crossland and Findley safety
    factors with f₋₁ = S_e (the location's fully corrected endurance limit) and t₋₁ = S_e/√3
    (von Mises), on the local stresses (K_t times the histories).

    Examples
    --------
    >>> import fetorsion
    >>> from fetorsion.design.fatigue import LocationStress
    >>> pin = LocationStress("P1 fillet", "pin-fillet", diameter=0.045, notch_radius=0.0025, bending_alt=30e6,
    ...                      torsion_alt=40e6, kt_bending=2.5, kt_torsion=1.8)  # nominal stresses, Pa
    >>> res = fetorsion.run_fatigue([pin])  # IACS UR M53: sigma_V = sqrt((2.5 x 30)^2 + 3 (1.8 x 40)^2) MPa
    >>> print(f"{res.governing.equivalent_alternating / 1e6:.2f} MPa")
    145.52 MPa
    """
    if method not in METHODS:
        raise FetorsionError(f"method must be one of {', '.join(METHODS)}, got {method!r}")
    if isinstance(material, FatigueMaterial):
        mat, defaulted = material, []
    else:
        mat, defaulted = fatigue_material(material)
    mat, required = with_limits(mat, limits, required)
    out = []
    for loc in locations:
        if method == "iacs-m53":
            a = assess_m53(loc, mat, M53_REQUIRED_Q if required is None else required)
        else:
            a = assess_textbook(loc, mat, 1.0 if required is None else required, mean_stress, reliability)
        if loc.bending_history is not None:
            f = mat.fatigue_strength or endurance_limit(mat.tensile_strength, loc.diameter, mat.surface, reliability)
            s = loc.kt_bending * np.asarray(loc.bending_history)
            t = loc.kt_torsion * np.asarray(loc.torsion_history)
            crit = {"crossland": crossland(s, t, f, f / math.sqrt(3.0)),
                    "findley": findley(s, t, f, f / math.sqrt(3.0))}
            a = replace(a, criteria=crit)
        out.append(a)
    if not out:
        raise FetorsionError("run_fatigue needs at least one location")
    return FatigueResult(method, mat, tuple(defaulted), tuple(out))
