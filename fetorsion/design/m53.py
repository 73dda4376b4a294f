"""IACS UR M53 as written: the statically determinate throw, nominal stresses on the web section,
the rule's empirical stress concentration factors (or fetorsion's FE ones as its Appendix III
defines them, where the geometry lies outside the formulas' ranges), σ_add, σ_V, σ_DW and Q.

The rule's text is read from [KR-M53] (Korean Register, *Rules for the Classification of Steel
Ships*, Pt 5, Annex 5-3 "Guidance for Calculation of Crankshaft Stress (2)", 2025), a
reproduction of UR M53 whose formulas are legible; §6 agrees with the Indian Register of
Shipping's restatement [IRS-CN]. Section numbers below are M53's (the same in [KR-M53]).

* **§2.1 bending.** One throw, simply supported at the midpoints of its two main journals
  (distance L3), loaded at the pin centre by the radial and tangential components of its
  cylinder's rod force (gas and inertia) over one working cycle. The bending moment M_BRF and
  the radial force Q_RF of the radial component act at the centre of each web (distance L1
  from its main journal's midpoint); the moments M_BRO, M_BTO of the two components act at the
  pin's oil bore (its centre). Alternating values X_N = ½ (X_max − X_min).
  σ_BFN = M_BRFN / W_eqw · K_e,  σ_QFN = Q_RFN / F · K_e,  W_eqw = B W²/6,  F = B W,
  K_e = 1.0 (4-stroke), 0.8 (2-stroke); σ_BON = M_BON / W_e, M_BO = M_BTO cos ψ + M_BRO sin ψ,
  W_e = π (D⁴ − D_BH⁴)/(32 D).
* **§2.2 torsion.** τ_N = M_TN / W_P, M_TN the largest alternating torque (half peak-to-peak of
  the harmonic synthesis) at the most loaded section over the speed range, W_P = π (D⁴ −
  D_BH⁴)/(16 D) (pin) or with D_G, D_BG (journal).
* **§3 SCFs** α_B, α_T (pin fillet), β_B, β_Q, β_T (journal fillet), γ_B, γ_T (pin oil bore):
  :func:`fetorsion.design.m53_scfs.empirical_scfs`, valid inside
  :data:`fetorsion.design.m53_scfs.VALIDITY`.
* **§4** σ_add = ±10 N/mm² for trunk-piston engines (±30 crosshead), at both fillets.
* **§5** σ_V = √((σ_BH + σ_add)² + 3 τ_H²) (pin fillet; journal: σ_BG, τ_G),
  σ_V = σ_BO/3 · [1 + 2 √(1 + 9/4 (σ_TO/σ_BO)²)] (oil bore).
* **§6** σ_DW (:func:`fetorsion.design.fatigue.m53_fatigue_strength`), radii not below 2 mm.
* **§7** Q = σ_DW / σ_V ≥ 1.15.

SI at the API (m, N, Pa); the rule's own units (mm, N/mm²) only where its formulas need them
(the SCF ratios are dimensionless).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from dataclasses import replace as dataclasses_replace

import numpy as np

from ..description.model import Crank
from ..errors import FetorsionError
from .scfset import SCFSet
from .fatigue import HAIGH_LOCATIONS, M53_REQUIRED_Q, MPA, m53_equivalent_fillet, m53_equivalent_oil_bore, m53_fatigue_strength
from .m53_scfs import empirical_scfs, fe_scfs_m53, out_of_range

#: [KR-M53] §4: σ_add of a trunk-piston engine (every engine fetorsion describes; a crosshead
#: engine's is ±30 N/mm²: ±20 axial vibration, ±10 misalignment), Pa.
SIGMA_ADD_TRUNK_PISTON = 10.0 * MPA
#: [KR-M53] §6: fillet radii (and half the oil-bore diameter) are taken as not less than 2 mm.
M53_MIN_RADIUS = 2e-3


@dataclass(frozen=True)
class M53Geometry:
    """One throw's dimensions as [KR-M53] §3 names them, m.

    D, D_G: pin and journal diameters; E: pin eccentricity (crank radius); W: web thickness;
    B: web width; R_H, R_G: pin and journal fillet radii; D_BH, D_BG: axial bores; D_O: the pin's
    oil bore (0: none); T_H, T_G: fillet recesses.
    """

    D: float
    D_G: float
    E: float
    W: float
    B: float
    R_H: float
    R_G: float
    D_BH: float = 0.0
    D_BG: float = 0.0
    D_O: float = 0.0
    T_H: float = 0.0
    T_G: float = 0.0

    @property
    def S(self) -> float:
        """Pin overlap S = (D + D_G)/2 − E, m."""
        return 0.5 * (self.D + self.D_G) - self.E

    def ratios(self) -> dict:
        """The related dimensions of [KR-M53] §3.(1)(G), each over the pin diameter D (r_GG: the
        journal fillet over the journal diameter, β_T's r when pin and journal differ)."""
        D = self.D
        return {"r_H": self.R_H / D, "r_G": self.R_G / D, "r_GG": self.R_G / self.D_G, "s": self.S / D,
                "w": self.W / D, "b": self.B / D, "d_O": self.D_O / D, "d_G": self.D_BG / D,
                "d_H": self.D_BH / D, "t_H": self.T_H / D, "t_G": self.T_G / D}


def web_width(web, crank_radius: float, radius: float) -> float:
    """Width of a web outline (the convex hull of a circle of diameter ``width_journal`` about
    the axis and one of ``width_pin`` about the pin centre, at distance ``crank_radius``) across
    the throw's plane at distance ``radius`` from the axis along the pin direction, m."""
    r1, r2, e = 0.5 * web.width_journal, 0.5 * web.width_pin, crank_radius
    sin_phi = (r1 - r2) / e  # the hull's straight sides: tangent to both circles
    if abs(sin_phi) >= 1.0:
        return 2.0 * max(r1, r2)
    cos_phi = math.sqrt(1.0 - sin_phi**2)
    half = (r1 + (r2 - r1) * radius / e) / cos_phi
    return 2.0 * half


def m53_geometry(crank, throw: int = 0) -> M53Geometry:
    """The dimensions of throw ``throw`` (0-based) of a crank description.

    B, which the rule reads as "the web width" of the reference section (its Fig 3), is taken
    here as the web outline's width at mid-overlap: halfway between the journal's surface
    (D_G/2 from the axis) and the pin's inner surface (E − D/2), the section through which the
    web carries the throw's bending from one fillet to the other (with no overlap: the middle
    of the gap). Of the throw's two webs, the narrower there is taken (the larger nominal stress).
    """
    j, pin = crank.journals[throw], crank.pins[throw]
    webs = crank.webs[2 * throw], crank.webs[2 * throw + 1]
    E = crank.engine.crank_radius
    mid = 0.5 * (0.5 * j.diameter + E - 0.5 * pin.diameter)
    B = min(web_width(w, E, mid) for w in webs)
    W = min(w.thickness for w in webs)
    holes = crank.oil_holes
    d_o = holes.diameter if holes is not None and holes.in_pins else 0.0
    return M53Geometry(pin.diameter, j.diameter, E, W, B, crank.fillets.pin, crank.fillets.journal, pin.bore,
                       j.bore, d_o)


# ---------------------------------------------------------------------------
# §2: the statically determinate throw

@dataclass(frozen=True)
class ThrowSpans:
    """Axial distances of one throw, m ([KR-M53] Fig 1): ``L1`` from each main journal's midpoint
    to its web's centre (front, rear), ``L2`` from the front journal's midpoint to the pin's
    centre, ``L3`` between the two journals' midpoints."""

    L1: tuple
    L2: float
    L3: float


def throw_spans(crank, throw: int = 0) -> ThrowSpans:
    """:class:`ThrowSpans` of throw ``throw`` from the description's lengths."""
    j1, j2 = crank.journals[throw], crank.journals[throw + 1]
    w1, w2 = crank.webs[2 * throw], crank.webs[2 * throw + 1]
    pin = crank.pins[throw]
    x = np.cumsum([0.5 * j1.length, w1.thickness, pin.length, w2.thickness, 0.5 * j2.length])
    L3 = float(x[-1])
    return ThrowSpans((float(x[0] + 0.5 * w1.thickness), float(L3 - (x[2] + 0.5 * w2.thickness))),
                      float(x[1] + 0.5 * pin.length), L3)


def throw_loads(spans: ThrowSpans, radial, tangential, offset=None) -> dict:
    """The simply supported throw's loads over a cycle from the pin force's radial and tangential
    components (arrays, N): ``M_BRF`` (2, angles), the bending moment of the radial component at
    each web's centre, N·m; ``Q_RF`` (2, angles), the radial force in each web, N; ``M_BRO``,
    ``M_BTO`` (angles,), the moments of the two components at the pin's centre (its oil bore), N·m.
    Triangular moment diagrams: a force at s from the front support is carried F (L3 − s)/L3 by
    it and F s/L3 by the rear one.

    Two rods on one throw (a vee): ``radial``, ``tangential`` (rods, angles), each rod at its phase,
    and ``offset`` (rods,), m, each big end's place from the pin's mid-length; their moments are
    superposed angle by angle ([IACSM53] §2.1: the rods of one throw with their phase)."""
    fr, ft = np.atleast_2d(np.asarray(radial, float)), np.atleast_2d(np.asarray(tangential, float))
    s = spans.L2 + (np.zeros(len(fr)) if offset is None else np.asarray(offset, float))  # each force's place
    a, b = ((spans.L3 - s) / spans.L3)[:, None], (s / spans.L3)[:, None]  # support shares, per rod
    # the moment at the pin centre L2 of a force at s: front share · L2 behind it, rear share · (L3 − L2) before
    at_pin = np.where((s >= spans.L2)[:, None], a * spans.L2, b * (spans.L3 - spans.L2))
    return {"M_BRF": np.stack([(a * fr).sum(0) * spans.L1[0], (b * fr).sum(0) * spans.L1[1]]),
            "Q_RF": np.stack([(a * fr).sum(0), (b * fr).sum(0)]),
            "M_BRO": (at_pin * fr).sum(0), "M_BTO": (at_pin * ft).sum(0)}


def alternating(x, axis: int = -1):
    """X_N = ½ (X_max − X_min) over a working cycle ([KR-M53] §2.(1)(B)(a)(v))."""
    return 0.5 * np.ptp(np.asarray(x, float), axis=axis)


def nominal_bending_stresses(g: M53Geometry, loads: dict, strokes: int, psi: float = 0.0) -> dict:
    """σ_BFN (per web), σ_QFN (per web), σ_BON of [KR-M53] §2.(1)(B), Pa: the alternating web
    moment over W_eqw = B W²/6 and radial force over F = B W, each times K_e (1.0 four-stroke,
    0.8 two-stroke); the oil bore's M_BO = M_BTO cos ψ + M_BRO sin ψ over W_e = π (D⁴ − D_BH⁴)/(32 D).
    ``psi``: the oil bore's angular position, rad (0: along the throw's tangent, where the
    tangential force's bending peaks; fetorsion's drillings run so)."""
    ke = 1.0 if strokes == 4 else 0.8
    w_eqw, area = g.B * g.W**2 / 6.0, g.B * g.W
    w_e = math.pi * (g.D**4 - g.D_BH**4) / (32.0 * g.D)
    m_bo = loads["M_BTO"] * math.cos(psi) + loads["M_BRO"] * math.sin(psi)
    return {"sigma_BFN": alternating(loads["M_BRF"]) / w_eqw * ke, "sigma_QFN": alternating(loads["Q_RF"]) / area * ke,
            "sigma_BON": float(alternating(m_bo)) / w_e}


def polar_modulus(diameter: float, bore: float) -> float:
    """W_P = π (D⁴ − D_B⁴)/(16 D), m³ ([KR-M53] §2.(2)(A)(e))."""
    return math.pi * (diameter**4 - bore**4) / (16.0 * diameter)


# ---------------------------------------------------------------------------
# §4–§7: the assessment

@dataclass(frozen=True)
class M53Location:
    """One of M53's three places of a throw variant: its stresses (Pa), SCFs, σ_V, σ_DW and Q."""

    name: str
    kind: str  # "pin-fillet", "journal-fillet", "oil-bore"
    bending: float  # σ_BH, σ_BG or σ_BO
    torsion: float  # τ_H, τ_G or σ_TO
    additional: float  # σ_add (0 at the oil bore)
    equivalent: float  # σ_V
    strength: float  # σ_DW
    scfs: dict
    torque_section: str = ""
    torque_rpm: float = math.nan
    required: float = M53_REQUIRED_Q
    #: R_e, Pa: an equivalent alternating stress above it yields, which the rule's linear-elastic
    #: assessment cannot judge (a FAIL whatever Q says).
    yield_strength: float = math.inf

    @property
    def safety(self) -> float:
        return self.strength / self.equivalent if self.equivalent > 0 else math.inf

    @property
    def yielding(self) -> bool:
        return self.equivalent > self.yield_strength

    @property
    def passes(self) -> bool:
        return self.safety >= self.required and not self.yielding

    def to_dict(self) -> dict:
        return {"name": self.name, "kind": self.kind, "bending_pa": self.bending, "torsion_pa": self.torsion,
                "additional_bending_pa": self.additional, "equivalent_pa": self.equivalent,
                "strength_pa": self.strength, "safety": self.safety, "required": self.required,
                "passes": self.passes, "yielding": self.yielding, "scfs": dict(self.scfs), "torque_section": self.torque_section,
                "torque_rpm": self.torque_rpm, "yield_strength_pa": self.yield_strength}

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "M53Location":
        """The place back from its :meth:`to_dict` (one written before R_e was kept: yielding as it
        was recorded, R_e 0 where it yielded, else infinite)."""
        from ..results import from_fields

        given = {} if "yield_strength_pa" in d else {"yield_strength": 0.0 if d["yielding"] else math.inf}
        return from_fields(cls, d, {"bending": "bending_pa", "torsion": "torsion_pa", "additional": "additional_bending_pa",
                                    "equivalent": "equivalent_pa", "strength": "strength_pa",
                                    "yield_strength": "yield_strength_pa"}, **given)


@dataclass(frozen=True)
class M53Result:
    """M53 on one crank in one configuration: every throw variant's three places.

    ``nominal`` holds the nominal stresses (Pa) and where τ_N came from; ``scf_source`` per
    factor says whether the rule's formula or the FE (Appendix III) gave it."""

    locations: tuple
    #: Per throw variant: its nominal stresses and torques (Pa, N·m), dimensions (m) and ratios, cylinders.
    nominal: dict[str, dict[str, float | list[list[int]] | dict[str, float]]]
    #: Per throw variant: each factor's source (the rule's formula or the FE), in words.
    scf_source: dict[str, dict[str, str]]
    rated_rpm: float
    notes: tuple = ()

    @property
    def governing(self) -> M53Location:
        return min(self.locations, key=lambda a: a.safety / a.required)

    @property
    def passes(self) -> bool:
        return all(a.passes for a in self.locations)

    def plot(self, ax=None, count: int = HAIGH_LOCATIONS):
        """Q of every place as a bar, the ``count`` least safe in colour and named by their Q, the
        others grey; the required Q dashed and labelled; the axis up to three times the least Q
        (a place far above cannot govern). Returns the Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(6, 4))
        order = sorted(range(len(self.locations)), key=lambda j: self.locations[j].safety)
        q = np.array([self.locations[j].safety for j in order])
        colours = [f"C{k}" if k < count else "0.75" for k in range(len(order))]
        y = np.arange(len(order))[::-1]
        ax.barh(y, q, color=colours, height=0.7)
        ax.set_yticks(y, [self.locations[j].name for j in order], fontsize=6 if len(order) > 12 else 8)
        for k in range(min(count, len(order))):
            ax.annotate(f"Q {q[k]:.2f}", (min(q[k], 3.0 * q[0]), y[k]), xytext=(3, 0), textcoords="offset points",
                        va="center", fontsize=7)
        required = self.locations[order[0]].required
        ax.axvline(required, color="k", ls="--", lw=0.8, label=f"required Q {required:.2f}")
        ax.set_xlim(0, max(3.0 * q[0], 1.5 * required))
        ax.set_xlabel("M53 acceptability factor Q = σ_DW / σ_V [-]")
        ax.set_title(f"UR M53 at the rated {self.rated_rpm:.0f} rpm: Q of every place", fontsize=9)
        ax.legend(fontsize=7, loc="lower right")
        return ax

    def to_dict(self) -> dict:
        """Every figure of the result as plain JSON-ready numbers, lists and strings (SI, or the unit in its key)."""
        g = self.governing
        return {"method": "iacs-m53", "passes": self.passes, "rated_rpm": self.rated_rpm,
                "governing": {"location": g.name, "safety": g.safety, "required": g.required,
                              "section": g.torque_section, "rpm": g.torque_rpm},
                "nominal": {k: dict(v) for k, v in self.nominal.items()}, "scf_source": dict(self.scf_source), "notes": list(self.notes),
                "locations": [a.to_dict() for a in self.locations]}

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "M53Result":
        """The result back from its :meth:`to_dict`."""
        return cls(tuple(M53Location.from_dict(a) for a in d["locations"]), {k: dict(v) for k, v in d["nominal"].items()},
                   dict(d["scf_source"]), d["rated_rpm"], tuple(d["notes"]))


def choose_scfs(g: M53Geometry, fe: SCFSet | None) -> tuple[dict, dict]:
    """(factors, source per factor): the rule's formula where the geometry lies in its range,
    else fetorsion's FE in M53's convention ([KR-M53] §3.(1)(F) and Appendix III). A factor with
    neither (β_Q outside its range: no 3-point-bending FE) raises."""
    emp, bad = empirical_scfs(g), out_of_range(g)
    fe = fe_scfs_m53(g, fe) if fe else {}
    out, source = {}, {}
    for k, v in emp.items():
        if k not in bad:
            out[k], source[k] = v, "M53 §3 formula"
        elif k in fe:
            out[k], source[k] = fe[k], f"FE per Appendix III ({'; '.join(bad[k])})"
        elif k == "beta_Q":
            out[k], source[k] = v, f"M53 §3 formula OUTSIDE its range ({'; '.join(bad[k])}); no FE 3-point case"
        else:
            raise FetorsionError(f"M53 {k}: the geometry is outside the formula's range ({'; '.join(bad[k])}) "
                                 "and no FE factor was given")
    return out, source


def run_m53(g: M53Geometry, spans: ThrowSpans, pin_force: dict, torque_pin: float, torque_journal: float,
            tensile_strength: float, process: str, strokes: int = 4, additional_bending: float = SIGMA_ADD_TRUNK_PISTON,
            scfs: dict | None = None, scf_source: dict | None = None, name: str = "throw", where: dict | None = None,
            fatigue_strength: float | None = None) -> tuple[tuple[M53Location, ...], dict]:
    """M53's three places of one throw: the pin fillet, the journal fillet, the pin's oil bore
    (when it has one), and the nominal stresses (Pa) they come from.

    Parameters
    ----------
    g, spans : M53Geometry, ThrowSpans
        The throw.
    pin_force : dict
        ``radial`` and ``tangential`` rod force on the pin over one working cycle, N (at the rated
        speed).
    torque_pin, torque_journal : float
        M_TN, the largest alternating torque (half peak-to-peak) of the vibration calculation
        through the pin and through the journal sections, N·m.
    tensile_strength : float
        σ_B, Pa. ``process``: the manufacturing route (:data:`~fetorsion.design.fatigue.M53_PROCESS_FACTOR`).
    additional_bending : float
        σ_add, Pa (§4; :data:`SIGMA_ADD_TRUNK_PISTON` unless the user states another).
    scfs : dict, optional
        The factors (default the §3 formulas, whatever their range).
    where : dict, optional
        ``pin`` and ``journal``: (section label, rpm) of each M_TN, for the report.
    fatigue_strength : float, optional
        The user's σ_DW against local stresses (``[limits] fatigue_strength_bending_pa``).
    """
    scfs = empirical_scfs(g) if scfs is None else scfs
    scf_source = scf_source or {k: "M53 §3 formula" for k in scfs}
    where = where or {}
    loads = throw_loads(spans, pin_force["radial"], pin_force["tangential"], pin_force.get("offset"))
    nom = nominal_bending_stresses(g, loads, strokes)
    s_bfn, s_qfn = float(np.max(nom["sigma_BFN"])), float(np.max(nom["sigma_QFN"]))
    tau_pin = torque_pin / polar_modulus(g.D, g.D_BH)
    tau_journal = torque_journal / polar_modulus(g.D_G, g.D_BG)
    rh, rg = max(g.R_H, M53_MIN_RADIUS), max(g.R_G, M53_MIN_RADIUS)

    def strength(d, r, kind):
        return fatigue_strength or m53_fatigue_strength(tensile_strength, d, r, process, kind)

    out = []
    s_bh, t_h = scfs["alpha_B"] * s_bfn, scfs["alpha_T"] * tau_pin
    out.append(M53Location(f"{name}: pin fillet", "pin-fillet", s_bh, t_h, additional_bending,
                           float(m53_equivalent_fillet(s_bh, t_h, additional_bending)),
                           strength(g.D, rh, "pin-fillet"), {k: scfs[k] for k in ("alpha_B", "alpha_T")},
                           *where.get("pin", ("", math.nan))))
    s_bg, t_g = scfs["beta_B"] * s_bfn + scfs["beta_Q"] * s_qfn, scfs["beta_T"] * tau_journal
    out.append(M53Location(f"{name}: journal fillet", "journal-fillet", s_bg, t_g, additional_bending,
                           float(m53_equivalent_fillet(s_bg, t_g, additional_bending)),
                           strength(g.D_G, rg, "journal-fillet"), {k: scfs[k] for k in ("beta_B", "beta_Q", "beta_T")},
                           *where.get("journal", ("", math.nan))))
    if g.D_O > 0:
        s_bo, s_to = scfs["gamma_B"] * nom["sigma_BON"], scfs["gamma_T"] * tau_pin
        out.append(M53Location(f"{name}: pin oil bore", "oil-bore", s_bo, s_to, 0.0,
                               float(m53_equivalent_oil_bore(s_bo, s_to)),
                               strength(g.D, max(0.5 * g.D_O, M53_MIN_RADIUS), "oil-bore"),
                               {k: scfs[k] for k in ("gamma_B", "gamma_T")}, *where.get("pin", ("", math.nan))))
    return tuple(out), {"sigma_BFN_pa": s_bfn, "sigma_QFN_pa": s_qfn, "sigma_BON_pa": nom["sigma_BON"],
                        "tau_N_pin_pa": tau_pin, "tau_N_journal_pa": tau_journal,
                        "M_TN_pin_nm": torque_pin, "M_TN_journal_nm": torque_journal}


def largest_torques(fillets, torque_amplitude, rpm) -> dict:
    """{"pin" | "journal": (M_TN in N·m, section label, rpm)}: the largest alternating torque
    through any pin (journal) fillet section over the speeds, [KR-M53] §2.(2)(A)(f)'s "highest
    value at the most torsionally loaded mass point". ``torque_amplitude``: (speeds, fillets),
    half peak-to-peak, N·m."""
    t = np.asarray(torque_amplitude, float)
    out = {}
    for kind in ("pin", "journal"):
        cols = [j for j, f in enumerate(fillets) if f.kind == kind]
        sub = t[:, cols]
        s, j = np.unravel_index(int(np.argmax(sub)), sub.shape)
        out[kind] = (float(sub[s, j]), fillets[cols[j]].label, float(np.asarray(rpm)[s]))
    return out


def m53_required(limits) -> float:
    """The safety M53 requires: the description's ``[limits] fatigue_required_safety``, else the rule's 1.15."""
    return getattr(limits, "fatigue_required_safety", 0.0) or M53_REQUIRED_Q


def split_pin_refusal(crank: Crank) -> str | None:
    """Why a crank with split pins is outside the rule (None: it is not split). [IACSM53] §1.2 applies to
    crankshafts with one crankthrow between main bearings, and its throw (§2, Fig 1) and stress
    concentration factors (§3) are those of one straight pin between two webs; a split pin's two
    half pins on their own axes and the flying web between them are neither, so no M53 figure of
    it is given rather than an in-line one."""
    split = [i + 1 for i, p in enumerate(crank.pins) if p.split]
    if not split:
        return None
    return (f"IACS UR M53 does not cover split pins (pins {', '.join(map(str, split))}): its throw (§2, Fig 1) and "
            "stress concentration factors (§3) are those of one straight pin between two webs, not two half pins "
            "with a flying web between them; fetorsion gives no M53 figure for this crank")


def rods_signature(rods: dict[str, np.ndarray]) -> tuple:
    """What makes two throws' rod loads one M53 variant: their rods' places, phases and forces over
    the cycle (to the mN), so a throw whose cylinders load it differently
    (:class:`fetorsion.excitation.loads.CylinderLoads`) is a variant of its own."""
    forces = np.concatenate([np.ravel(rods["radial"]), np.ravel(rods["tangential"])])
    return tuple(np.round(np.r_[rods["offset"], rods["phase"]], 9)) + tuple(np.round(forces, 3))


def run_m53_crank(crank, fillets, torque_amplitude, rpm, fe_scf: SCFSet | None = None, rated_rpm: float | None = None,
                  material=None, limits=None) -> M53Result:
    """UR M53 on a crank description in one configuration.

    Parameters
    ----------
    crank : Crank
        With ``[excitation]`` (the rod forces) and fillet radii.
    fillets : list of Fillet
        :func:`fetorsion.design.stress.fillets_of` the crank, the columns of ``torque_amplitude``.
    torque_amplitude : ndarray (speeds, fillets)
        The vibration calculation's alternating torque (half peak-to-peak, every order summed with
        its phase) through each fillet's section, N·m; the configuration (dampers, misfire,
        damping) is whatever produced it.
    rpm : array_like (speeds,)
    fe_scf : dict, optional
        fetorsion's FE SCFs (:func:`fetorsion.design.scf.fillet_scfs` and the oil bores'), used
        for a factor whose formula is out of its range (Appendix III).
    rated_rpm : float, optional
        The speed of the rod forces for the bending (default: the top of the description's
        running range, ``[excitation] speed_range``).
    material : FatigueMaterial, optional
        Default :func:`fetorsion.design.fatigue.fatigue_material` of the description.
    limits : Limits, optional
        ``additional_bending`` (σ_add, Pa) replaces §4's trunk-piston value when > 0;
        ``fatigue_strength_bending`` replaces σ_DW; ``fatigue_required_safety`` the 1.15.
    """
    from ..excitation.loads import cylinder_loads
    from .fatigue import fatigue_material

    if split_pin_refusal(crank):
        raise FetorsionError(split_pin_refusal(crank))
    mat = material or fatigue_material(crank.material)[0]
    limits = crank.limits if limits is None else limits
    rated = float(crank.excitation.speed_range[1] if rated_rpm is None else rated_rpm)
    sigma_add = getattr(limits, "additional_bending", 0.0) or SIGMA_ADD_TRUNK_PISTON
    required = m53_required(limits)
    user_strength = getattr(limits, "fatigue_strength_bending", 0.0) or mat.fatigue_strength or None
    loads = cylinder_loads(crank)
    torques = largest_torques(fillets, torque_amplitude, rpm)
    groups: dict = {}
    rods = [loads.rods_of_throw(rated, i) for i in range(crank.throws)]
    for i in range(crank.throws):  # throws of one geometry and load are one variant ([KR-M53] §2.(1)(B)(a)(iv))
        groups.setdefault((m53_geometry(crank, i), throw_spans(crank, i), rods_signature(rods[i])), []).append(i + 1)
    locations, nominal, sources = [], {}, {}
    for (g, spans, _), throws in groups.items():
        name = f"throw{'s' if len(throws) > 1 else ''} {', '.join(map(str, throws))}"
        scfs, source = choose_scfs(g, fe_scf)
        force = rods[throws[0] - 1]
        locs, nom = run_m53(g, spans, force, torques["pin"][0], torques["journal"][0], mat.tensile_strength,
                            mat.process, crank.engine.strokes_per_cycle, sigma_add, scfs, source, name,
                            {k: v[1:] for k, v in torques.items()}, user_strength)
        locations += [dataclasses_replace(a, required=required, yield_strength=mat.yield_strength) for a in locs]
        nominal[name] = {**nom, "cylinders": [[int(c) + 1 for c in rods[t - 1]["cylinders"]] for t in throws], "B_m": g.B, "W_m": g.W, "D_m": g.D, "D_G_m": g.D_G, "D_BH_m": g.D_BH,
                         "D_BG_m": g.D_BG, "ratios": g.ratios()}
        sources[name] = source
    notes = [f"bending from the rod forces at the rated {rated:.0f} rpm (top of the running range) on the "
             "statically determinate throw; torsion from the vibration calculation over the whole checked range",
             f"σ_add {sigma_add / MPA:g} N/mm² "
             + ("([limits] additional_bending_pa)" if getattr(limits, "additional_bending", 0.0) else
                "(M53 §4, trunk-piston engine)")]
    holes = crank.oil_holes
    if holes is not None and holes.in_journals:
        bigger = all(j.diameter >= p.diameter for j, p in zip(crank.journals, crank.pins))
        notes.append("journal oil bores: " + ("M53 §1 covers them by the pin's (journals not smaller than the pins)"
                                             if bigger else "NOT covered by M53 (journals smaller than the pins): "
                                             "separate documentation required"))
    return M53Result(tuple(locations), nominal, sources, rated, tuple(notes))


def m53_utilisation(result: M53Result, fillets, setup):
    """A function (speeds, sections) alternating section torques → (speeds,) M53 utilisation
    σ_V/σ_DW of the worst place at each speed (1/Q): ``result``'s bending parts held (they do not
    depend on the torsional vibration), its torsion taken from the torques given, pin places from
    the largest pin-section torque at that speed, journal places from the journal's. The damper
    optimiser's objective: minimising its largest value maximises M53's governing Q."""
    from .stress import fillet_sections

    sections = fillet_sections(fillets, setup)
    cols = {k: sections[[j for j, f in enumerate(fillets) if f.kind == k]] for k in ("pin", "journal")}
    rows = []
    for a in result.locations:
        kind = "journal" if a.kind == "journal-fillet" else "pin"
        nominal = result.nominal[a.name.split(":")[0]]
        modulus = polar_modulus(nominal["D_G_m"], nominal["D_BG_m"]) if kind == "journal" else \
            polar_modulus(nominal["D_m"], nominal["D_BH_m"])
        t_scf = a.scfs.get("beta_T") or a.scfs.get("alpha_T") or a.scfs.get("gamma_T")
        rows.append((a.kind, kind, a.bending, a.additional, a.strength, t_scf / modulus))

    def utilisation(torque):
        t = np.asarray(torque, float)
        worst = np.zeros(t.shape[0])
        for loc_kind, kind, bending, add, strength, per_nm in rows:
            tau = per_nm * t[:, cols[kind]].max(axis=1)
            sv = m53_equivalent_oil_bore(bending, tau) if loc_kind == "oil-bore" else m53_equivalent_fillet(bending, tau, add)
            worst = np.maximum(worst, sv / strength)
        return worst

    # it reads the pin and the journal sections only through their largest torque at each speed,
    # and σ_V grows with τ: its largest value over the speeds follows from the two largest
    # torques (:func:`fetorsion.response.synthesis.group_maxima`)
    utilisation.groups = [cols["pin"], cols["journal"]]
    return utilisation
