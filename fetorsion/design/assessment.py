"""Fatigue assessment of every fillet over the speed range: bending and torsion, mean and
alternating, from the condensed crank's load cycle.

At each fillet the section's in-plane bending moment M(θ) and torque T(θ) over the cycle
(:func:`fetorsion.response.cycle.run_load_cycle`) give the nominal stresses

    σ(θ) = 32 M D / (π (D⁴ − d_i⁴)),    τ(θ) = 16 T D / (π (D⁴ − d_i⁴)),

which the fillet's bending and torsional SCFs (:func:`fetorsion.design.scf.fillet_scfs`) carry
to the fillet surface; their mean and alternating parts (half the range) go to the chosen
strength method (:func:`fetorsion.design.fatigue.run_fatigue`: the textbook path, the ``fe``
verdict's, or M53's criterion alone on these loads, a cross-check that is not the rule). Oil-bore exits take the bending about the throw's radius and the torque of their
section (:func:`oil_bore_stress_histories`) and the drilled bar's SCFs
(:func:`fetorsion.design.oilbore.oil_bore_scfs`). Every speed is assessed; each location's worst speed is then assessed again with its
whole history for the multiaxial cross-checks (Crossland, Findley).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import FetorsionError
from .scfset import SCFSet
from .fatigue import HAIGH_LOCATIONS, FatigueResult, LocationStress, run_fatigue


def section_modulus_factor(diameter: float, bore: float) -> float:
    """D / (π (D⁴ − d⁴)) in 1/m³: σ = 32 M × this, τ = 16 T × this."""
    return diameter / (math.pi * (diameter**4 - bore**4))


def fillet_stress_histories(crank, cycle, fillets) -> tuple[np.ndarray, np.ndarray]:
    """Nominal (σ, τ) at each fillet over the cycle: (speeds, fillets, angles) each, Pa. The
    cycle's cuts are the fillets in the same order."""
    if len(cycle.labels) != len(fillets):
        raise FetorsionError(f"the load cycle has {len(cycle.labels)} cuts for {len(fillets)} fillets")
    w = np.array([section_modulus_factor(f.diameter, f.bore) for f in fillets])[None, :, None]
    return 32 * w * cycle.bending_in_plane(), 16 * w * cycle.torque()


@dataclass(frozen=True)
class OilBoreSection:
    """A drilled pin or journal: ``label``, ``kind`` (``pin``/``journal``), the indices of its fillet
    cuts in the fillet list, diameter and bore (m), and ``angle`` (rad), the throw angle whose
    tangent the drilling runs along (the solid model's drillings: perpendicular to the crank radius
    of the nearest throw)."""

    label: str
    kind: str
    cuts: tuple
    diameter: float
    bore: float
    angle: float


def oil_bore_sections(crank, fillets) -> list[OilBoreSection]:
    """Every drilled pin and journal of ``crank``; none without ``[oil_holes]``."""
    holes = crank.oil_holes
    if holes is None or not holes.diameter > 0:
        return []
    angles = crank.engine.crank_angles
    out = []
    for kind, drilled, parts in (("pin", holes.in_pins, crank.pins), ("journal", holes.in_journals, crank.journals)):
        if not drilled:
            continue
        for i, part in enumerate(parts):
            cuts = tuple(j for j, f in enumerate(fillets) if f.kind == kind and f.index == i)
            if cuts:
                out.append(OilBoreSection(f"{'P' if kind == 'pin' else 'J'}{i + 1} oil bore", kind, cuts,
                                          part.diameter, part.bore, float(angles[min(i, len(angles) - 1)])))
    return out


def oil_bore_stress_histories(cycle, bore: OilBoreSection) -> tuple[np.ndarray, np.ndarray]:
    """Nominal (σ, τ) at a drilling's exits over the cycle: (speeds, angles) each, Pa.

    The drilling runs along the throw's tangent e_t, so its exits sit at ±e_t: the bending that
    loads them is the moment about the throw's radius e_r, M_r = M_y cos a + M_z sin a (the
    in-plane moment about e_t puts the drilling on the neutral axis). As [IACSM53] takes the
    bending at the oil bore, the moment resolved on the bore's direction. The exit is at
    mid-length: the mean of the section's own fillet cuts (the moment is linear along a pin or
    journal between its webs, the torque constant)."""
    c, s = math.cos(bore.angle), math.sin(bore.angle)
    h = cycle.history[:, list(bore.cuts)]
    w = section_modulus_factor(bore.diameter, bore.bore)
    moment = (c * h[:, :, 4] + s * h[:, :, 5]).mean(axis=1)
    return 32 * w * moment, 16 * w * h[:, :, 3].mean(axis=1)




@dataclass
class CrankAssessment:
    """Safety of every fillet against speed, the worst speed of each, and the governing one.

    Attributes
    ----------
    rpm : ndarray (speeds,)
    labels : list of str
        Fillets.
    safety : ndarray (speeds, fillets)
        The method's safety factor (M53: Q = σ_DW / σ_V; textbook: Goodman's n).
    worst : FatigueResult
        Each fillet assessed at its own worst speed, with its whole history (criteria included).
    worst_rpm : ndarray (fillets,)
    """

    name: str
    method: str
    rpm: np.ndarray
    labels: list
    safety: np.ndarray
    worst: FatigueResult
    worst_rpm: np.ndarray
    scf_source: str = ""
    notes: list = field(default_factory=list)
    worst_diameters: np.ndarray | None = None  # each location's section diameter, m
    #: The load cycle's cut each location reads (an oil bore: the first of its section's cuts).
    cuts: tuple = ()

    @property
    def governing(self) -> int:
        return int(np.argmin(self.safety.min(axis=0)))

    def to_dict(self) -> dict:
        g = self.governing
        return {"name": self.name, "method": self.method, "rpm": self.rpm.tolist(), "fillets": list(self.labels),
                "safety": self.safety.tolist(), "worst_rpm": self.worst_rpm.tolist(),
                "locations": [a.to_dict() for a in self.worst.locations], "material": self.worst.to_dict()["material"],
                "defaulted": list(self.worst.defaulted), "scf_source": self.scf_source, "notes": list(self.notes),
                "governing": {"fillet": self.labels[g], "rpm": float(self.worst_rpm[g]),
                              "safety": float(self.safety[:, g].min()),
                              "required": float(self.worst.locations[g].required)},
                "worst_diameters_m": None if self.worst_diameters is None else self.worst_diameters.tolist(),
                "cuts": list(self.cuts)}

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "CrankAssessment":
        """The assessment back from its :meth:`to_dict` (the worst speeds' method read from their
        places, or this assessment's criterion: ``textbook`` or M53's)."""
        from ..results import from_fields

        first = d["locations"][0]["method"] if d["locations"] else ASSESSMENT_METHODS.get(d["method"], d["method"])
        worst = FatigueResult.from_dict({"method": first, "material": d["material"], "locations": d["locations"]})
        return from_fields(cls, d, {"labels": "fillets", "worst_diameters": "worst_diameters_m"}, worst=worst,
                           cuts=tuple(d.get("cuts", ())))

    def table(self) -> str:
        lines = [f"{self.name}: fatigue of the fillets and oil bores ({self.method}), each at its worst speed",
                 f"{'location':<28} {'rpm':>6} {'σ_a [MPa]':>10} {'σ_m [MPa]':>10} {'τ_a [MPa]':>10} "
                 f"{'τ_m [MPa]':>10} {'safety':>7} {'required':>8}"]
        for j, a in enumerate(self.worst.locations):
            st = a.factors.get("stresses", {})
            lines.append(f"{self.labels[j]:<28} {self.worst_rpm[j]:6.0f} {st.get('bending_alt', 0) / 1e6:10.1f} "
                         f"{st.get('bending_mean', 0) / 1e6:10.1f} {st.get('torsion_alt', 0) / 1e6:10.1f} "
                         f"{st.get('torsion_mean', 0) / 1e6:10.1f} {a.safety:7.2f} {a.required:8.2f}")
        return "\n".join(lines)

    def haigh(self, count: int = HAIGH_LOCATIONS, ax=None):
        """Haigh diagram of the ``count`` least safe fillets at their worst speeds: von Mises mean
        and alternating local stresses (σ'_m, σ'_a) against each one's Goodman line (the
        textbook endurance limit S_e at that fillet to S_ut) and, for M53, its σ_DW (the rule
        reads the alternating stress only). Returns the Axes."""
        import matplotlib.pyplot as plt

        from .fatigue import endurance_limit, von_mises

        if ax is None:
            _, ax = plt.subplots(figsize=(6, 4.5))
        mat = self.worst.material
        order = np.argsort(self.safety.min(axis=0))[:count]
        for n, j in enumerate(order):
            a = self.worst.locations[j]
            st = a.factors.get("stresses", {})
            sm = float(von_mises(st.get("bending_mean", 0.0), st.get("torsion_mean", 0.0)))
            sa = float(von_mises(st.get("bending_alt", 0.0), st.get("torsion_alt", 0.0)))
            d = float(self.worst_diameters[j]) if self.worst_diameters is not None else 0.05
            se = mat.fatigue_strength or endurance_limit(mat.tensile_strength, d, mat.surface)
            line, = ax.plot([0, mat.tensile_strength / 1e6], [se / 1e6, 0], lw=0.8, ls="--",
                            label=f"Goodman, {self.labels[j]}")
            ax.plot([sm / 1e6], [sa / 1e6], "o", color=line.get_color(), label=f"{self.labels[j]}, {self.worst_rpm[j]:.0f} rpm")
            if self.method == "m53-criterion":
                ax.axhline(a.strength / 1e6, color=line.get_color(), lw=0.6, ls=":")
        ax.set_xlim(-0.05 * mat.tensile_strength / 1e6, mat.tensile_strength / 1e6)
        ax.set_ylim(bottom=0)
        ax.set_xlabel("mean equivalent stress [MPa]")
        ax.set_ylabel("alternating equivalent stress [MPa]")
        ax.set_title(f"{self.name}: Haigh diagram" + (" (dotted: M53 sigma_DW)" if self.method == "m53-criterion" else ""),
                     fontsize=9, wrap=True)
        ax.legend(fontsize=6)
        return ax

    def plot(self, ax=None):
        """Safety of every place against speed: the :data:`HAIGH_LOCATIONS` least safe in colour and
        named, the others thin grey; the required value dashed; the axis up to three times the
        least safety (a place far above cannot govern). Returns the Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(7, 4))
        least = self.safety.min(axis=0)
        worst = [int(j) for j in np.argsort(least)[:HAIGH_LOCATIONS]]
        others = [j for j in range(len(self.labels)) if j not in worst]
        for j in others:
            ax.plot(self.rpm, self.safety[:, j], lw=0.5, color="0.75", label="the other places" if j == others[0] else None)
        for j in worst:
            ax.plot(self.rpm, self.safety[:, j], lw=1.4 if j == self.governing else 1.0,
                    label=f"{self.labels[j]} (least {least[j]:.2f})")
        required = self.worst.locations[0].required
        ax.axhline(required, color="k", ls="--", lw=0.8, label=f"required {required:.2f}")
        ax.set_ylim(0, max(3.0 * least.min(), 1.5 * required))
        ax.set_xlabel("engine speed [rpm]")
        ax.set_ylabel("fatigue safety factor [-]")
        ax.set_title(f"{self.name}\nfatigue of fillets and oil bores ({self.method})", fontsize=9, wrap=True)
        ax.legend(fontsize=7)
        return ax

#: run_assessment's strength criteria, each applied to fetorsion's own loads and FE SCFs:
#: ``textbook`` (the ``fe`` path's) and ``m53-criterion`` (M53's σ_V, σ_DW and Q on those loads:
#: a cross-check, NOT the rule, whose loads and SCFs are :func:`fetorsion.design.m53.run_m53_crank`'s).
ASSESSMENT_METHODS = {"textbook": "textbook", "m53-criterion": "iacs-m53"}


def run_assessment(crank, cycle, fillets, scf: SCFSet, method: str = "textbook", required: float | None = None
                   ) -> CrankAssessment:
    """Assess every fillet of ``crank`` at every speed of ``cycle``.

    Parameters
    ----------
    crank : Crank
        Its ``[material]`` strengths (or the default forging steel, named in the result) and fillet radii.
    cycle : LoadCycle
        The fillet cuts' loads (:func:`fetorsion.response.cycle.run_load_cycle`), cuts = ``fillets``.
    fillets : list of Fillet
        :func:`fetorsion.design.stress.fillets_of` the crank, in the cuts' order.
    scf : dict
        ``pin``, ``journal`` (torsion) and ``pin_bending``, ``journal_bending`` SCFs; for the oil
        bores ``pin_oil_bore_bending``, ``pin_oil_bore_torsion`` and the journal's (a drilled kind
        without them is noted as not assessed).
    method : {"textbook", "m53-criterion"}
        The strength and criterion: the textbook path (Marin factors, Neuber's K_f, Goodman), or
        M53's criterion (alternating stresses, σ_V, σ_DW, Q ≥ 1.15) on these loads — not UR M53
        as written, whose statically determinate loads and empirical SCFs are
        :func:`fetorsion.design.m53.run_m53_crank`'s.
    required : float, optional
        Required safety (default the description's ``[limits] fatigue_required_safety``, else the
        method's: :func:`fetorsion.design.fatigue.run_fatigue`).
    """
    if method not in ASSESSMENT_METHODS:
        raise FetorsionError(f"assessment method must be one of {', '.join(ASSESSMENT_METHODS)}, got {method!r}"
                             + (" (UR M53 as written is fetorsion.design.m53.run_m53_crank)" if method == "iacs-m53" else ""))
    label, method = method, ASSESSMENT_METHODS[method]
    bores = oil_bore_sections(crank, fillets)
    missing = sorted({b.kind for b in bores if b.kind not in scf.oil_bore})
    sigma, tau, where, cuts_read = _local_histories(crank, cycle, fillets, scf,
                                                    [b for b in bores if b.kind not in missing])
    # M53's σ_add loads the fillets only; the rule's oil-bore equivalent has no such term
    add = [getattr(crank.limits, "additional_bending", 0.0) if kind != "oil-bore" else 0.0 for _, kind, *_ in where]
    safety = _safety_over_speeds(crank, sigma, tau, where, add, method, required)
    worst_speed = np.argmin(safety, axis=0)
    worst = _worst_speed_fatigue(crank, sigma, tau, where, add, worst_speed, method, required)
    notes = _assessment_notes(crank, method, where[0][4], scf, bores, missing, worst)
    return CrankAssessment(crank.name, label, np.asarray(cycle.rpm), [w[0] for w in where], safety, worst,
                           np.asarray(cycle.rpm)[worst_speed], scf.source, notes, np.array([w[2] for w in where]),
                           tuple(cuts_read))


def _local_histories(crank, cycle, fillets, scf: SCFSet, bores: list[OilBoreSection]):
    """(σ, τ) of every place over the cycle, (speeds, places, angles) Pa; each place's (label, kind,
    diameter, notch radius, (K_t bending, K_t torsion)); the cut each reads. The fillets' are
    nominal (their SCFs applied by run_fatigue), the oil bores' ``bores`` already local."""
    sigma, tau = fillet_stress_histories(crank, cycle, fillets)
    radius = {"pin": crank.fillets.pin, "journal": crank.fillets.journal}
    where = [(f.label, f"{f.kind}-fillet", f.diameter, radius[f.kind], scf.fillet(f.kind)) for f in fillets]
    cuts_read = list(range(len(fillets)))
    for b in bores:
        sb, tb = oil_bore_stress_histories(cycle, b)
        # At the bore's edge both loads give a normal stress along the edge (a free surface with no
        # shear): local σ = γ_B σ_b ± γ_T τ, the sign that makes the larger range, and no shear.
        gb, gt = scf.oil_bore[b.kind]
        plus, minus = gb * sb + gt * tb, gb * sb - gt * tb
        local = np.where((np.ptp(plus, axis=1) >= np.ptp(minus, axis=1))[:, None], plus, minus)
        sigma = np.concatenate([sigma, local[:, None]], axis=1)
        tau = np.concatenate([tau, np.zeros_like(tb)[:, None]], axis=1)
        where.append((b.label, "oil-bore", b.diameter, 0.5 * crank.oil_holes.diameter, (1.0, 1.0)))
        cuts_read.append(b.cuts[0])
    return sigma, tau, where, cuts_read


def _safety_over_speeds(crank, sigma, tau, where, add, method, required) -> np.ndarray:
    """Each place's safety at every speed, (speeds, places): the method on its histories' mean and alternating parts."""
    s_mean, s_alt = 0.5 * (sigma.max(axis=2) + sigma.min(axis=2)), 0.5 * np.ptp(sigma, axis=2)
    t_mean, t_alt = 0.5 * (tau.max(axis=2) + tau.min(axis=2)), 0.5 * np.ptp(tau, axis=2)
    safety = np.empty(sigma.shape[:2])
    for s in range(sigma.shape[0]):
        locs = [LocationStress(lb, kind, d, r, s_alt[s, j], t_alt[s, j], s_mean[s, j], t_mean[s, j],
                               kt_bending=kb, kt_torsion=kt, additional_bending=add[j])
                for j, (lb, kind, d, r, (kb, kt)) in enumerate(where)]
        safety[s] = [a.safety for a in run_fatigue(locs, crank.material, method, required, limits=crank.limits).locations]
    return safety


def _worst_speed_fatigue(crank, sigma, tau, where, add, worst_speed, method, required) -> FatigueResult:
    """The method at each place's worst speed on its whole history, its local stresses in its factors."""
    locs = [LocationStress.from_history(lb, kind, d, r, sigma[worst_speed[j], j], tau[worst_speed[j], j],
                                        kt_bending=kb, kt_torsion=kt, additional_bending=add[j])
            for j, (lb, kind, d, r, (kb, kt)) in enumerate(where)]
    worst = run_fatigue(locs, crank.material, method, required, limits=crank.limits)
    stresses = [{"bending_alt": kb * loc.bending_alt, "bending_mean": kb * loc.bending_mean,
                 "torsion_alt": kt * loc.torsion_alt, "torsion_mean": kt * loc.torsion_mean}
                for loc, (_, _, _, _, (kb, kt)) in zip(locs, where)]
    return replace(worst, locations=tuple(replace(a, factors={**a.factors, "stresses": st})
                                          for a, st in zip(worst.locations, stresses)))


def _assessment_notes(crank, method, kt_first, scf: SCFSet, bores, missing, worst: FatigueResult) -> list[str]:
    """The assessment's notes: its SCFs, σ_add, the oil bores assessed or not, the strengths' source."""
    notes = [f"local stresses: nominal section stresses × SCF (bending {kt_first[0]:.2f} …, torsion {kt_first[1]:.2f} …)"]
    if method == "iacs-m53":
        sigma_add = getattr(crank.limits, "additional_bending", 0.0)
        notes.append(f"M53's additional bending σ_add {sigma_add / 1e6:g} MPa at the fillets ([limits] additional_bending_pa)"
                     if sigma_add > 0 else "M53's additional bending σ_add not applied (0): give the class society's "
                     "value as [limits] additional_bending_pa")
    if missing:
        notes.append(f"oil-bore exits NOT assessed ({', '.join(b.label for b in bores if b.kind in missing)}): "
                     f"no {' or '.join(missing)} oil-bore SCF in {scf.source or 'the SCFs given'}")
    elif bores:
        notes.append(f"oil-bore exits: the bending about the throw's radius (the drillings run along its tangent), "
                     f"SCFs {scf.oil_bore_source}")
    if worst.material.fatigue_strength:
        notes.append(f"fatigue strength {worst.material.fatigue_strength / 1e6:.0f} MPa against local stresses: "
                     f"{worst.material.fatigue_strength_source}, in place of the method's own")
    if worst.defaulted:
        notes.append(f"material strengths not in the description ({', '.join(worst.defaulted)}): "
                     f"{worst.material.name} ({worst.material.source})")
    return notes
