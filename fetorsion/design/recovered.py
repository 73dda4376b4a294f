"""The ``fe`` path's assessment: Findley on the stress recovered at every fillet and oil bore.

For each location (:func:`fetorsion.design.recovery.crank_locations`) and speed, the local
plane-stress history at the zone's surface nodes is the unit-load fields times the rear-face load
of the cut(s) it reads (the static part from the cycle's order-0 loads, the vibratory part the
rest), and Findley's safety (:func:`fetorsion.design.criterion.findley_surface`) at the least safe
node is the location's. The strength is local:

    f₋₁ = S_e · n,     t₋₁ = f₋₁ / √3,

S_e the material's endurance limit with its Marin surface, size and reliability factors
([Budynas] eq. 6-18; the size factor at the section's diameter), n = K_t / K_f the notch's
support (K_f = 1 + q (K_t − 1), Neuber's q for the notch radius, [Budynas] eqs. 6-32 to 6-35a;
K_t the zone's own peak over nominal under the pure couple that bends it: the recovered stress
is the elastic peak, so the notch's support is the part of K_t the material does not feel).
A fatigue strength given in ``[limits]`` (against local stresses) replaces f₋₁ with n = 1.

Nodes: a zone has thousands of surface nodes and a run hundreds of speeds, so the nodes that can
govern are screened first (:func:`candidate_nodes`: the extreme loads over every speed and angle
along 256 directions in load space, and the nodes with the largest von Mises chord or stress
under them); Findley sweeps every speed on those (:func:`assess_location`), and at each
location's worst speed checks the rest: a node the screen missed joins the candidates.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import FetorsionError
from ..lumped_model.damped import threaded_map
from .assessment import HAIGH_LOCATIONS, CrankAssessment
from .criterion import findley_constants, findley_surface, signed_von_mises, von_mises_amplitude, von_mises_plane
from .fatigue import (DEFAULT_RELIABILITY, FatigueAssessment, FatigueMaterial, FatigueResult, endurance_limit,
                      fatigue_material, fatigue_notch_factor, marin_reliability, marin_size, marin_surface,
                      notch_sensitivity, with_limits)

#: The method's name in results.
METHOD = "findley-recovered"


def support_factor(kt: float, tensile_strength: float, notch_radius: float) -> tuple[float, float]:
    """(n = K_t / K_f, q) of a notch with elastic factor ``kt`` and radius ``notch_radius`` (m):
    Neuber's q in bending ([Budynas] eqs. 6-32, 6-34, 6-35a)."""
    q = notch_sensitivity(tensile_strength, notch_radius)
    return kt / fatigue_notch_factor(kt, q), q


def zone_kt(location) -> float:
    """The zone's elastic K_t under the pure couple that bends it in the throw's plane (a fillet:
    about the throw frame's z; a drilling: about the bar's z, the drilling in the moment's
    plane): the largest principal stress of either sign over the section's 32 M D/(π(D⁴ − d⁴))."""
    from .scf import nominal_bending

    s = location.zone.influence[:, :, 5]  # unit Mz
    centre = 0.5 * (s[:, 0] + s[:, 1])
    radius = np.sqrt(0.25 * (s[:, 0] - s[:, 1]) ** 2 + s[:, 2] ** 2)
    peak = float(np.max(np.abs(centre) + radius))
    return peak / float(nominal_bending(1.0, location.diameter))


@dataclass(frozen=True)
class LocalStrength:
    """f₋₁ (Pa) of one location and how it was found (``factors``)."""

    bending: float
    factors: dict

    @property
    def torsion(self) -> float:
        return self.bending / math.sqrt(3.0)


#: The treatments that reach a drilling's edge as well as the fillets (a fillet roller does not).
TREATED_BORES = ("nitrided", "induction-hardened", "shot-peened")


def treatment_factor(mat: FatigueMaterial, kind: str) -> float:
    """The description's surface-treatment factor at a place of ``kind`` (1 where it does not reach)."""
    if mat.surface_treatment == "none" or (kind == "oil-bore" and mat.surface_treatment not in TREATED_BORES):
        return 1.0
    return mat.treatment_factor


def local_strength(mat: FatigueMaterial, location, reliability: float = DEFAULT_RELIABILITY) -> LocalStrength:
    """The location's local fatigue limit in reversed bending (module docstring), times the
    description's surface-treatment factor where the treatment reaches (:func:`treatment_factor`;
    not on a strength the description gives against local stresses, which is the treated part's)."""
    if mat.fatigue_strength:
        return LocalStrength(mat.fatigue_strength, {"given": mat.fatigue_strength_source, "support": 1.0})
    kt = zone_kt(location)
    n, q = support_factor(kt, mat.tensile_strength, location.notch_radius)
    se = endurance_limit(mat.tensile_strength, location.diameter, mat.surface, reliability)
    kv = treatment_factor(mat, location.kind)
    return LocalStrength(se * n * kv, {"S_e_pa": se, "ka": marin_surface(mat.tensile_strength, mat.surface),
                                       "kb": marin_size(location.diameter), "ke": marin_reliability(reliability),
                                       "surface": mat.surface, "Kt": kt, "q": q, "support": n,
                                       "treatment": mat.surface_treatment, "treatment_factor": kv})


@dataclass
class RecoveredAssessment(CrankAssessment):
    """:class:`~fetorsion.design.assessment.CrankAssessment` of the recovered path: per location
    its governing node (``nodes_m``, sub-model frame) and Findley's figures at its worst speed."""

    nodes_m: list = field(default_factory=list)

    def to_dict(self) -> dict:
        """:meth:`CrankAssessment.to_dict` with the criterion and each place's governing node (m,
        in its sub-model's frame: a throw's, journal centre at x = 0, pin on +y; a bar's)."""
        return {**super().to_dict(), "criterion": "findley", "nodes_m": list(self.nodes_m)}

    def table(self) -> str:
        lines = [f"{self.name}: Findley on the recovered local stress, each place at its worst speed",
                 f"{'location':<28} {'rpm':>6} {'σ_vM,a [MPa]':>12} {'σ_vM,m [MPa]':>12} {'Findley [MPa]':>13} "
                 f"{'limit [MPa]':>11} {'f₋₁ [MPa]':>9} {'safety':>7} {'required':>8}"]
        for j, a in enumerate(self.worst.locations):
            f = a.criteria.get("findley", {})
            lines.append(f"{self.labels[j]:<28} {self.worst_rpm[j]:6.0f} {a.equivalent_alternating / 1e6:12.1f} "
                         f"{a.equivalent_mean / 1e6:12.1f} {f.get('value', math.nan) / 1e6:13.1f} "
                         f"{f.get('limit', math.nan) / 1e6:11.1f} {a.strength / 1e6:9.1f} {a.safety:7.2f} {a.required:8.2f}")
        return "\n".join(lines)

    def haigh(self, count: int = HAIGH_LOCATIONS, ax=None):
        """The ``count`` least safe places at their worst speeds: von Mises mean (signed) and
        amplitude of the local stress, against each one's Findley limit for a uniaxial history
        (σ_a at the limit for each mean: the least over planes of (λ − k c² σ_m) / (s c + k c²)).
        Returns the Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(6, 4.5))
        rm = self.worst.material.tensile_strength
        sm = np.linspace(-0.5 * rm, rm, 200)
        th = np.linspace(1e-3, 0.5 * math.pi, 400)[:, None]
        c, s = np.cos(th), np.sin(th)
        for j in np.argsort(self.safety.min(axis=0))[:count]:
            a = self.worst.locations[j]
            k, lam = findley_constants(a.strength, a.strength / math.sqrt(3.0))
            sa = np.min((lam - k * c * c * sm[None]) / (s * c + k * c * c), axis=0)
            line, = ax.plot(sm / 1e6, np.maximum(sa, 0) / 1e6, lw=0.8, ls="--", label=f"Findley limit, {self.labels[j]}")
            ax.plot([a.equivalent_mean / 1e6], [a.equivalent_alternating / 1e6], "o", color=line.get_color(),
                    label=f"{self.labels[j]}, {self.worst_rpm[j]:.0f} rpm")
        ax.axvline(0, color="k", lw=0.5)
        ax.set_ylim(bottom=0)
        ax.set_xlabel("mean von Mises stress, signed by the trace [MPa]")
        ax.set_ylabel("von Mises amplitude [MPa]")
        ax.set_title(f"{self.name}\nHaigh diagram of the recovered local stress", fontsize=9, wrap=True)
        ax.legend(fontsize=6)
        return ax


#: Directions in load space whose extreme loads (over every speed and angle) screen the nodes.
SCREEN_DIRECTIONS = 96
#: Nodes kept by each screen: the largest chord and the largest stress under the extreme loads.
SCREEN_RANGE, SCREEN_PEAK = 12, 6
#: The sweep over every speed: the screen's leading nodes, every SWEEP_STRIDE-th angle, planes
#: every 180/SWEEP_PLANES degrees; the REFINED_SPEEDS least safe speeds are then taken again on
#: every candidate at every angle and the full plane grid.
SWEEP_NODES, SWEEP_STRIDE, SWEEP_PLANES, REFINED_SPEEDS = 3, 4, 18, 5
#: Nodes of the all-node check at a location's worst speed that go on to Findley (by their
#: components' half ranges at every SWEEP_STRIDE-th angle).
CHECK_NODES = 100


#: The screen reads every SCREEN_STRIDE-th crank angle (2°: order 24's peak is missed by at most
#: 1 − cos 12°, on loads that only order the nodes; the sweep and the check read every angle).
SCREEN_STRIDE = 2


def extreme_loads(loads: np.ndarray, directions: int = SCREEN_DIRECTIONS) -> tuple[np.ndarray, np.ndarray]:
    """The loads (speeds, 6, angles) that are largest and least along each of ``directions`` seeded
    directions in load space (each component scaled by its spread), every :data:`SCREEN_STRIDE`-th
    angle, in single precision (a screen: it orders nodes, it does not assess them): (directions, 6)
    each."""
    x = np.moveaxis(loads[..., ::SCREEN_STRIDE], 1, -1).reshape(-1, 6).astype(np.float32)
    scale = x.std(axis=0) + 1e-30
    w = np.random.default_rng(52).normal(size=(directions, 6))
    w /= np.linalg.norm(w, axis=1)[:, None]
    proj = (w / scale).astype(np.float32) @ x.T  # (directions, samples): each row's extremes are contiguous
    return x[np.argmax(proj, axis=1)].astype(float), x[np.argmin(proj, axis=1)].astype(float)


def candidate_nodes(location, loads: np.ndarray) -> np.ndarray:
    """Nodes of ``location``'s zone whose stress can govern under ``loads`` (speeds, 6, angles), the
    most likely first: the largest von Mises chord between the extreme loads of one direction, then
    the largest von Mises stress under any extreme load (single precision: the order, not a value)."""
    hi, lo = extreme_loads(loads)
    P = location.zone.influence.reshape(-1, 6).astype(np.float32)  # (nodes·3, 6)
    n = len(location.zone.xyz)
    at = lambda e: von_mises_plane(np.moveaxis((P @ e.T.astype(np.float32)).reshape(n, 3, -1), 1, -1)).max(axis=1)  # noqa: E731
    chord = at(hi - lo)
    peak = np.maximum(at(hi), at(lo))
    order = list(np.argsort(chord)[::-1][:SCREEN_RANGE]) + list(np.argsort(peak)[::-1][:SCREEN_PEAK])
    return np.array(list(dict.fromkeys(int(i) for i in order)))


def _findley(location, nodes, static_loads, vib, k, lam, planes=None):
    """Findley's safety (speeds, nodes) at ``nodes`` under static (speeds, 6) and vibratory
    (speeds, 6, angles) rear-face loads."""
    from .criterion import PLANES

    st = location.stresses(static_loads[..., None], nodes)[..., 0]
    return findley_surface(st, location.stresses(vib, nodes), k, lam, planes or PLANES)["safety"]


def assess_location(location, static_loads: np.ndarray, loads: np.ndarray, strength: LocalStrength,
                    check: bool = True) -> dict:
    """Findley at every speed on the location's least safe node.

    ``static_loads`` (speeds, 6) and ``loads`` (speeds, 6, angles): the rear-face loads of the
    order-0 part and of the whole history. The screen (:func:`candidate_nodes`) orders the nodes;
    the sweep over every speed takes its :data:`SWEEP_NODES` leading ones coarsely, the
    :data:`REFINED_SPEEDS` least safe speeds are taken again on every candidate, at every angle,
    on the full plane grid; ``check``: at the worst speed every node is checked (the
    :data:`CHECK_NODES` largest by their components' half ranges), and a node the screen missed
    joins the candidates. Returns ``safety`` (speeds,), ``node`` (speeds,), the ``candidates``
    and Findley's ``k`` and ``limit``."""
    k, lam = findley_constants(strength.bending, strength.torsion)
    vib = loads - static_loads[..., None]
    cand = candidate_nodes(location, loads)

    def sweep(nodes):
        lead = nodes[:SWEEP_NODES]
        safe = np.full((len(loads), len(nodes)), np.inf)
        safe[:, :len(lead)] = _findley(location, lead, static_loads, vib[..., ::SWEEP_STRIDE], k, lam, SWEEP_PLANES)
        refine = np.argsort(safe.min(axis=1))[:REFINED_SPEEDS]
        safe[refine] = _findley(location, nodes, static_loads[refine], vib[refine], k, lam)
        return safe

    safe = sweep(cand)
    if check:
        worst = int(np.argmin(safe.min(axis=1)))
        h = location.stresses(vib[worst][:, ::SWEEP_STRIDE])  # (all nodes, 3, angles)
        half = von_mises_plane(0.5 * (h.max(axis=-1) - h.min(axis=-1)))
        few = np.argsort(half)[-CHECK_NODES:]
        full = _findley(location, few, static_loads[worst], vib[worst], k, lam)
        if full.min() < safe[worst].min() * (1 - 1e-9) and int(few[np.argmin(full)]) not in cand:
            cand = np.r_[cand, int(few[np.argmin(full)])]
            safe = sweep(cand)
    best = np.argmin(safe, axis=1)
    return {"safety": safe[np.arange(len(safe)), best], "node": cand[best], "candidates": cand,
            "k": k, "limit": lam}


def run_recovered_assessment(crank, cycle, locations, required: float | None = None,
                             reliability: float = DEFAULT_RELIABILITY, check: bool = True) -> RecoveredAssessment:
    """Findley on the recovered local stress at every location of ``crank`` at every speed of ``cycle``.

    Parameters
    ----------
    crank : Crank
        Its ``[material]`` (missing strengths from the default forging steel, named) and ``[limits]``.
    cycle : LoadCycle
        The cuts' loads over the cycle (:func:`fetorsion.response.cycle.run_load_cycle`).
    locations : list of Location
        :func:`fetorsion.design.recovery.crank_locations` of the crank on the cycle's cuts.
    required : float, optional
        Required safety (default ``[limits] fatigue_required_safety``, else 1.0).
    reliability : float
        The endurance limit's reliability ([Budynas] Table 6-5).
    check : bool
        Check every node at each location's worst speed (:func:`assess_location`).
    """
    if not locations:
        raise FetorsionError("the recovered assessment needs at least one location")
    mat, defaulted = fatigue_material(crank.material)
    mat, required = with_limits(mat, crank.limits, required)
    required = 1.0 if required is None else required
    rpm = np.asarray(cycle.rpm)
    safety = np.empty((len(rpm), len(locations)))
    worst_locs, nodes_m = [], []

    def assessed(loc):
        strength = local_strength(mat, loc, reliability)
        loads = loc.rear_loads(cycle.history)  # (speeds, 6, angles)
        static = loc.rear_loads(cycle.mean[..., None])[..., 0]  # (speeds, 6)
        return strength, loads, static, assess_location(loc, static, loads, strength, check)

    for j, (loc, (strength, loads, static, res)) in enumerate(zip(locations, threaded_map(assessed, locations))):
        safety[:, j] = res["safety"]
        assessment, node = _at_worst_speed(loc, strength, loads, static, res, mat, required)
        worst_locs.append(assessment)
        nodes_m.append(loc.zone.xyz[node].tolist())
    worst_speed = np.argmin(safety, axis=0)
    result = FatigueResult(METHOD, mat, tuple(defaulted), tuple(worst_locs))
    return RecoveredAssessment(crank.name, METHOD, rpm, [loc.label for loc in locations], safety, result,
                               rpm[worst_speed], "stress recovery (six unit end loads)",
                               _recovered_notes(mat, defaulted, reliability),
                               np.array([loc.diameter for loc in locations]),
                               tuple(loc.cuts[0] for loc in locations), nodes_m)


def _at_worst_speed(loc, strength: LocalStrength, loads, static, res: dict, mat: FatigueMaterial,
                    required: float) -> tuple[FatigueAssessment, int]:
    """(the location's assessment at its worst speed, its least safe node there): Findley's terms, the
    peak von Mises stress and the safety without the mean at that node."""
    s = int(np.argmin(res["safety"]))
    node = int(res["node"][s])
    hist = loc.stresses(loads[s], [node])[0]  # (3, angles)
    st = loc.stresses(static[s][:, None], [node])[0, :, 0]
    f = findley_surface(st, hist - st[:, None], res["k"], res["limit"])
    peak = float(von_mises_plane(hist.T).max())
    # the same node and speed with the mean taken away: the bridge's mean factor
    free = findley_surface(np.zeros(3), hist - st[:, None], res["k"], res["limit"])
    crit = {"findley": {"value": float(f["value"]), "limit": res["limit"], "k": res["k"],
                        "plane_rad": float(f["plane"]), "tau_a_pa": float(f["tau_a"]),
                        "sigma_n_max_pa": float(f["sigma_n_max"]), "safety": float(res["safety"][s]),
                        "safety_without_mean": float(free["safety"])}}
    factors = {**strength.factors, "node_m": loc.zone.xyz[node].tolist(), "zone": loc.zone.name,
               "peak_von_mises_pa": peak, "surface_traction_residual": loc.zone.normal_residual}
    return FatigueAssessment(loc.label, loc.kind, METHOD, strength.bending, von_mises_amplitude(hist),
                             signed_von_mises(st), float(res["safety"][s]), required,
                             yield_safety=mat.yield_strength / peak if peak > 0 else math.inf,
                             factors=factors, criteria=crit), node


def _recovered_notes(mat: FatigueMaterial, defaulted, reliability: float) -> list[str]:
    """The recovered assessment's notes: the method, the local strength and its source."""
    notes = ["local stresses recovered from six unit end loads on each throw (fillets) and on a bar with the "
             "drilling (oil bores), superposed with the cut loads over the cycle; Findley's critical plane on "
             "planes through the surface, the static part with its sign, the safety a factor on the vibratory part"]
    if mat.fatigue_strength:
        notes.append(f"fatigue strength {mat.fatigue_strength / 1e6:.0f} MPa against local stresses: "
                     f"{mat.fatigue_strength_source}, no notch support")
    else:
        notes.append(f"local strength f₋₁ = S_e · K_t/K_f: S_e with the '{mat.surface}' surface factor "
                     f"([Budynas] Table 6-2; the material's surface field"
                     + (", not given: machined, the finish of a turned fillet, the most conservative of a "
                        "ground, rolled or machined one" if "surface" in defaulted else "")
                     + f"), size and reliability {reliability:g}; Neuber's q for each notch")
        if mat.surface_treatment != "none":
            notes.append(f"surface treatment '{mat.surface_treatment}': the local strength × {mat.treatment_factor:g} "
                         f"({mat.treatment_source}) at the fillets"
                         + (" and the oil bores" if mat.surface_treatment in TREATED_BORES else "")
                         + "; IACS M53 as written does not credit it")
        else:
            notes.append("no surface treatment stated: untreated fillets and bores (a rolled or nitrided fillet states "
                         "[material] surface_treatment with its factor and source)")
    if defaulted:
        notes.append(f"material strengths not in the description ({', '.join(defaulted)}): {mat.name} ({mat.source})")
    return notes

def determinate_cut(force: np.ndarray, at: np.ndarray, cut: np.ndarray, span: float) -> np.ndarray:
    """The resultant (F, M about ``cut``) that the right part exerts on the left at the plane
    x = cut[0] of a throw simply supported at its journal centres x = 0 and x = ``span`` (on its
    axis) under a force ``force`` (N, across the axis) at ``at`` (throw frame, m): [KR-M53] §2.1's
    statically determinate throw, the left part's external loads reversed. The force's torque
    about the axis is left out (M53 takes the torsion from the vibration calculation)."""
    force, at = np.asarray(force, float), np.asarray(at, float)
    r_rear = -force * at[0] / span  # the moment balance about the front support
    loads = [(np.zeros(3), -force - r_rear), (np.array([span, 0.0, 0.0]), r_rear), (at, force)]
    F, M = np.zeros(3), np.zeros(3)
    for x, f in loads:
        if x[0] < cut[0]:
            F -= f
            M -= np.cross(x - cut, f)
    M[0] = 0.0
    return np.r_[F, M]


#: A fillet's vibratory bending above this multiple of the statically determinate throw's is
#: flagged: the rule's bending (the determinate throw, [IACSM53]) does not cover it.
BENDING_FLAG = 1.5


def vibratory_bending(crank, cycle, fillets, cut_centres: np.ndarray, rated_rpm: float) -> list[dict]:
    """Per fillet cut of ``cycle``: the vibratory bending moment in its throw's plane (half peak
    to peak over the cycle, the largest over the speeds, N·m, and that speed) against the
    statically determinate throw's under the rod force's alternating radial part at
    ``rated_rpm`` ([KR-M53] §2.1: M53's bending): the larger of its moment at the cut and at the
    centre of the fillet's web (M_BRFN, the nominal the rule's α_B and β_B multiply; near a
    journal the cut's own is small, the shear carrying the fillet's stress), and their ratio;
    ``flag`` above :data:`BENDING_FLAG`. Where the crank's bending modes resonate, the first is
    the larger.

    ``fillets`` and ``cut_centres`` (cuts, 3; m) as :func:`fetorsion.design.recovery.crank_locations`.
    """
    from ..excitation.loads import cylinder_loads
    from .m53 import alternating, throw_spans
    from .recovery import throw_rotation, throw_index, throw_origin

    loads = cylinder_loads(crank)
    amp = alternating(cycle.bending_in_plane(), axis=-1)  # (speeds, cuts)
    angles = np.asarray(crank.engine.crank_angles, float)
    R = crank.engine.crank_radius
    origins, rods_of, out = {}, {}, []
    for k, f in enumerate(fillets):
        if f.kind not in ("pin", "journal"):
            continue
        i = throw_index(crank, fillets, f)
        if i not in origins:
            origins[i], rods_of[i] = throw_origin(crank, fillets, i), loads.rods_of_throw(rated_rpm, i)
        x = float((throw_rotation(-angles[i]) @ (cut_centres[k] - np.array([origins[i], 0.0, 0.0])))[0])
        spans = throw_spans(crank, i)
        web = spans.L1[0] if x < spans.L2 else spans.L3 - spans.L1[1]  # the fillet's web's centre
        rule = max(abs(float(half_range_cut(rods_of[i], "radial", spans, R, (at, 0.0, 0.0))[5])) for at in (x, web))
        s = int(np.argmax(amp[:, k]))
        run = float(amp[s, k])
        ratio = run / rule if rule > 0 else math.inf
        out.append({"name": f.label, "vibratory_nm": run, "rpm": float(cycle.rpm[s]), "determinate_nm": rule,
                    "ratio": ratio, "flag": bool(ratio > BENDING_FLAG)})
    return out


def half_range_cut(rods: dict, component: str, spans, R: float, at) -> np.ndarray:
    """The statically determinate throw's cut load (F, M; 6,) at the point ``at`` (m, throw frame)
    from the rod forces' ``component`` (``radial`` along y or ``tangential`` along z) over the
    cycle, as M53 takes it: half the change between the two crank angles where the throw's summed
    force of that component is largest and smallest. One rod: the alternating force's own cut;
    two rods of a vee, each at its own place along the pin and with its phase, superposed.

    ``rods``: :meth:`fetorsion.excitation.loads.CylinderLoads.rods_of_throw`; ``spans``: its
    :class:`~fetorsion.design.m53.ThrowSpans`."""
    f = np.asarray(rods[component], float)  # (rods, samples)
    total = f.sum(axis=0)
    hi, lo = int(np.argmax(total)), int(np.argmin(total))
    axis = 1 if component == "radial" else 2
    out = np.zeros(6)
    for r, offset in enumerate(rods["offset"]):
        unit = np.zeros(3)
        unit[axis] = 0.5 * (f[r, hi] - f[r, lo])
        out += determinate_cut(unit, np.array([spans.L2 + offset, R, 0.0]), np.asarray(at, float), spans.L3)
    return out


def m53_variant(m53, throw: int) -> str:
    """The name of ``m53``'s throw variant (a key of ``m53.nominal``) that holds 0-based ``throw``."""
    for name in m53.nominal:
        if throw + 1 in [int(x) for x in name.split(" ", 1)[1].split(", ")]:
            return name
    raise FetorsionError(f"M53 has no variant for throw {throw + 1} (variants: {', '.join(m53.nominal)})")


def m53_with_factors(loc, nominal: dict, factors: dict) -> float:
    """σ_V of M53's place ``loc`` (the rule's combination, no σ_add) with its SCFs replaced by
    ``factors`` where given ({name: value}, M53's convention: fetorsion's FE per [KR-M53]
    Appendix III, which the rule allows in place of its formulas), its nominal stresses kept."""
    from .fatigue import m53_equivalent_fillet, m53_equivalent_oil_bore

    f = {**loc.scfs, **{k: v for k, v in factors.items() if k in loc.scfs and v}}
    if loc.kind == "pin-fillet":
        return float(m53_equivalent_fillet(loc.bending * f["alpha_B"] / loc.scfs["alpha_B"],
                                           loc.torsion * f["alpha_T"] / loc.scfs["alpha_T"], 0.0))
    if loc.kind == "journal-fillet":
        bending = f["beta_B"] * nominal["sigma_BFN_pa"] + f["beta_Q"] * nominal["sigma_QFN_pa"]
        return float(m53_equivalent_fillet(bending, loc.torsion * f["beta_T"] / loc.scfs["beta_T"], 0.0))
    return float(m53_equivalent_oil_bore(loc.bending * f["gamma_B"] / loc.scfs["gamma_B"],
                                         loc.torsion * f["gamma_T"] / loc.scfs["gamma_T"]))


def same_load(crank, m53, zones: dict, throw: int = 0, fe_factors: dict | None = None) -> dict:
    """The ``fe`` path's σ_V on M53's own loads beside M53's, for the pin fillet, the journal
    fillet and the pin's oil bore of the throw variant that holds 0-based ``throw``: the rod force's alternating part
    at the rated speed on the statically determinate throw (radial force at the fillets; at the
    oil bore the tangential force's bending, ψ = 0, as the rule), the largest alternating torque
    M_TN of the vibration calculation, combined in phase as the rule does, the largest von Mises
    stress of the recovered local amplitude over the zone's nodes (either relative sign of torque
    and bending). No mean, no σ_add on either side (σ_V without it).

    Parameters
    ----------
    crank : Crank
        The description (its rod forces at ``m53.rated_rpm``).
    m53 : M53Result
        :func:`fetorsion.design.m53.run_m53_crank` of the configuration.
    zones : dict
        :func:`fetorsion.design.recovery.crank_zones` of the crank.

    fe_factors : dict, optional
        fetorsion's FE SCFs in M53's convention ({name: value}, :func:`fetorsion.design.m53_scfs.scf_comparison`'s
        ``fe``): M53's σ_V with them (:func:`m53_with_factors`) is given beside, ``m53_fe_scf_sigma_v_pa``
        and ``ratio_fe_scf`` (the recovery against the rule's combination on the same FE's factors).

    Returns ``{place: {"m53_sigma_v_pa", "fe_sigma_v_pa", "ratio"}}`` (ratio fe/M53).
    """
    from ..excitation.loads import cylinder_loads
    from .fatigue import m53_equivalent_fillet, m53_equivalent_oil_bore
    from .m53 import throw_spans
    from .recovery import load_map

    rods = cylinder_loads(crank).rods_of_throw(m53.rated_rpm, throw)
    i = throw
    spans = throw_spans(crank, i)
    R = crank.engine.crank_radius
    pin_at = np.array([spans.L2, R, 0.0])
    name = m53_variant(m53, i)
    nom = m53.nominal[name]
    throw = zones[("throw", i)]

    def peak(zone, cut_load, cut_torque, centre):
        A = load_map(np.eye(3), centre, zone.loaded)
        b = np.einsum("nck,k->nc", zone.influence, A @ cut_load)
        t = np.einsum("nck,k->nc", zone.influence, A @ np.r_[0, 0, 0, cut_torque, 0, 0])
        return float(max(von_mises_plane(b + t).max(), von_mises_plane(b - t).max()))

    out = {}
    places = {loc.kind: loc for loc in m53.locations if loc.name.startswith(name + ":")}
    cut_x = {"journal-fillet": (throw[0], throw[3]), "pin-fillet": (throw[1], throw[2])}
    j1, w1, pin = crank.journals[i], crank.webs[2 * i], crank.pins[i]
    faces = np.cumsum([0.5 * j1.length, w1.thickness, pin.length, crank.webs[2 * i + 1].thickness])
    centres = {"journal-fillet": (np.array([faces[0], 0, 0]), np.array([faces[3], 0, 0])),
               "pin-fillet": (np.array([faces[1], R, 0]), np.array([faces[2], R, 0]))}
    for kind in ("pin-fillet", "journal-fillet"):
        torque = nom["M_TN_pin_nm"] if kind == "pin-fillet" else nom["M_TN_journal_nm"]
        fe = max(peak(z, half_range_cut(rods, "radial", spans, R, c), torque, c)
                 for z, c in zip(cut_x[kind], centres[kind]))
        loc = places[kind]
        out[kind] = {"m53_sigma_v_pa": float(m53_equivalent_fillet(loc.bending, loc.torsion, 0.0)),
                     "fe_sigma_v_pa": fe}
    if "oil-bore" in places and ("bar", "pin") in zones:
        bar = zones[("bar", "pin")]
        # the pin's centre section: the mean of its two sides (the force acts there)
        eps = 1e-9
        cut = 0.5 * sum(half_range_cut(rods, "tangential", spans, R, pin_at + d)
                        for d in (np.array([-eps, 0, 0]), np.array([eps, 0, 0])))
        rows = np.array([[1.0, 0, 0], [0, 0, 1.0], [0, -1.0, 0]])  # crank angle 0: y = e_t, z = −e_r
        hole = np.array([0.5 * bar.loaded[0], 0.0, 0.0])
        A = load_map(rows, hole, bar.loaded)
        b = np.einsum("nck,k->nc", bar.influence, A @ cut)
        t = np.einsum("nck,k->nc", bar.influence, A @ np.r_[0, 0, 0, nom["M_TN_pin_nm"], 0, 0])
        loc = places["oil-bore"]
        out["oil-bore"] = {"m53_sigma_v_pa": float(m53_equivalent_oil_bore(loc.bending, loc.torsion)),
                           "fe_sigma_v_pa": float(max(_principal_plane(b + t).max(), _principal_plane(b - t).max()))}
    for kind, v in out.items():
        v["ratio"] = v["fe_sigma_v_pa"] / v["m53_sigma_v_pa"]
        if fe_factors:
            v["m53_fe_scf_sigma_v_pa"] = m53_with_factors(places[kind], nom, fe_factors)
            v["ratio_fe_scf"] = v["fe_sigma_v_pa"] / v["m53_fe_scf_sigma_v_pa"]
    return out


def _principal_plane(s: np.ndarray) -> np.ndarray:
    """The largest principal stress of either sign |σ|₁ of plane stresses (..., 3): at a drilling's
    wall the rule's σ_V is the peak principal stress (plate with a hole)."""
    c = 0.5 * (s[..., 0] + s[..., 1])
    r = np.sqrt(0.25 * (s[..., 0] - s[..., 1]) ** 2 + s[..., 2] ** 2)
    return np.abs(c) + r
