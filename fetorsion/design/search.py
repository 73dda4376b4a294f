"""From a failing crank to a passing one: a design search over the description's ``[design]`` space.

The explorer is the lumped chain (:func:`fetorsion.response.forced.response_setup`, the
description's partition) with IACS UR M53 on its fillet torques
(:func:`fetorsion.design.m53.run_m53_crank`, the rule's SCFs where the geometry is in their range,
else the given crank's FE factors), at every k-th speed of the verdict's range
(:func:`fetorsion.design.crank_verdict.design_speeds`). Each candidate moves the ``[design]``
inputs inside their bounds and, when the space allows one, adds a damper at the pulley tuned by
Den Hartog's rule to the first mode seen from there ([DenHartog]) with an inertia ratio inside its
bounds. The search minimises the objective (mass, rotating inertia or change) subject to M53's
governing safety reaching the required one, with SciPy's differential evolution ([Storn]) on the
unit cube of the bounds, the constraint as a penalty, then COBYQA ([Ragonneau]) from its best
feasible candidate with the constraint as such (the optimum lies on it); every candidate either
evaluates is kept, and the Pareto front (objective against safety) is read from them.

The explorer decides nothing: the chosen design is written as a new description and confirmed by
``fetorsion run`` on it, whose verdict is the condensed FE crank's (``fetorsion design`` does both).
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import asdict, dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np
import scipy.optimize

from ..description.model import Crank, Damper
from ..errors import FetorsionError
from ..description.edit import edit_toml_values, field_values, with_values
from .measures import crank_mass, first_elastic_hz, resonance_clearance
from .scfset import SCFSet

if TYPE_CHECKING:
    from collections.abc import Callable
    from distributed import Client
    from ..studies.runner import ClusterOnDemand, SampleStore

#: Differential evolution's generations by default.
DESIGN_GENERATIONS = 12
#: The objective's unit, per objective.
OBJECTIVE_UNITS = {"mass": "kg", "inertia": "kg m^2", "change": "-"}
#: The penalty per unit shortfall of safety (relative): large against the objective's own
#: relative changes (order 0.1), so any feasible candidate beats an infeasible one.
PENALTY = 10.0


@dataclass(frozen=True)
class Candidate:
    """One design the explorer evaluated: the inputs' values (file units), the added damper
    (None: none) and its inertia ratio, the objective, mass (kg, crank and ring), the explorer's
    governing M53 safety and where it governs, the lumped chain's first elastic frequency (Hz,
    the crank without the added damper) and the added damper's heat (W, its largest mean
    dissipation over the speeds; 0 without one)."""

    values: dict[str, float]
    inertia_ratio: float | None
    damper: Damper | None
    objective: float
    mass_kg: float
    safety: float
    governing: str
    governing_rpm: float
    f1_hz: float = math.nan
    damper_power_w: float = 0.0

    def to_dict(self) -> dict:
        return {"values": dict(self.values), "inertia_ratio": self.inertia_ratio,
                "damper": None if self.damper is None else {
                    "kind": self.damper.kind, "ring_inertia_kgm2": self.damper.ring_inertia,
                    "stiffness_nm_per_rad": self.damper.stiffness, "damping_nms_per_rad": self.damper.damping,
                    "loss_factor": self.damper.loss_factor},
                "objective": self.objective, "mass_kg": self.mass_kg, "safety": self.safety,
                "governing": self.governing, "governing_rpm": self.governing_rpm, "f1_hz": self.f1_hz,
                "damper_power_w": self.damper_power_w}


def pareto_front(candidates) -> list[Candidate]:
    """The candidates no other beats on both counts (lower objective, higher safety), by objective."""
    ordered = sorted(candidates, key=lambda c: (c.objective, -c.safety))
    front, best = [], -math.inf
    for c in ordered:
        if c.safety > best:
            front.append(c)
            best = c.safety
    return front


@dataclass(frozen=True)
class DesignTargets:
    """What the explorer's candidates must reach: the M53 safety (the required one, or re-aimed by
    the confirming FE verdict), the added damper's heat limit (W; 0: none), and the resonance
    constraint — ``orders`` kept out of ``speed_range_rpm`` by ``margin`` — on the lumped chain's
    f1 times ``frequency_factor`` (the FE crank's in-bearing f1 over the lumped chain's, 1 until a
    confirming run measures it)."""

    safety: float
    heat_limit_w: float = 0.0
    orders: tuple[float, ...] = ()
    margin: float = 0.0
    speed_range_rpm: tuple[float, float] = (0.0, 0.0)
    frequency_factor: float = 1.0

    def clearance(self, c: Candidate) -> float:
        """``c``'s resonance clearance (:func:`resonance_clearance`) with f1 corrected."""
        return resonance_clearance(c.f1_hz * self.frequency_factor, self.orders, self.speed_range_rpm)

    def shortfall(self, c: Candidate, safety: bool = True) -> float:
        """The sum of ``c``'s relative shortfalls (0: it meets every constraint): safety, heat,
        resonance clearance."""
        out = max(0.0, self.safety / c.safety - 1.0) if safety else 0.0
        if self.heat_limit_w and c.damper is not None:
            out += max(0.0, c.damper_power_w / self.heat_limit_w - 1.0)
        if self.orders:
            out += max(0.0, self.margin - self.clearance(c))
        return out


@dataclass
class DesignResult:
    """A design search: its space, the required safety, every evaluated candidate, the best
    feasible one (None: none reached the required safety) and the cost."""

    name: str
    objective: str
    required: float
    given: Candidate
    candidates: list[Candidate]
    best: Candidate | None
    seconds: float
    notes: list[str] = field(default_factory=list)
    targets: DesignTargets | None = None
    #: Why candidates could not be evaluated (their description broke a rule, say), each reason once
    failures: list[str] = field(default_factory=list)

    def meets_others(self, c: Candidate) -> bool:
        """``c`` meets the constraints other than the safety (the added damper's heat, the
        resonance margin) at the search's targets."""
        return self.targets is None or self.targets.shortfall(c, safety=False) == 0.0

    @property
    def pareto(self) -> list[Candidate]:
        """The Pareto front (objective against safety) of the candidates that meet the other
        constraints."""
        return pareto_front([c for c in self.candidates if self.meets_others(c)])

    def to_dict(self) -> dict:
        return {"name": self.name, "objective": self.objective, "objective_unit": OBJECTIVE_UNITS[self.objective],
                "required_safety": self.required, "targets": None if self.targets is None else asdict(self.targets),
                "given": self.given.to_dict(),
                "best": None if self.best is None else self.best.to_dict(), "evaluations": len(self.candidates),
                "seconds": self.seconds, "pareto": [c.to_dict() for c in self.pareto], "notes": list(self.notes)}

    def table(self) -> str:
        unit = OBJECTIVE_UNITS[self.objective]
        lines = [f"{self.name}: design search, minimise {self.objective} [{unit}] with M53 safety >= "
                 f"{self.required:.2f} (explorer: lumped chain; {len(self.candidates)} candidates, {self.seconds:.0f} s)",
                 f"given: {self.objective} {self.given.objective:.4g}, safety {self.given.safety:.3f} "
                 f"({self.given.governing}, {self.given.governing_rpm:.0f} rpm)"]
        t = self.targets
        if t is not None and (t.orders or t.heat_limit_w):
            lines.insert(1, "constraints besides the safety: " + "; ".join(
                ([f"the added damper's heat <= {t.heat_limit_w:.1f} W"] if t.heat_limit_w else [])
                + ([f"orders {', '.join(f'{q:g}' for q in t.orders)} resonant with the first mode in the bearings "
                    f"outside {t.speed_range_rpm[0]:.0f}-{t.speed_range_rpm[1]:.0f} rpm by {100 * t.margin:.0f} %; "
                    f"given: clearance {100 * t.clearance(self.given):+.1f} %"] if t.orders else [])))
        if self.best is None:
            lines.append("no candidate reached the required safety: widen the [design] bounds or allow a damper")
        else:
            b = self.best
            lines.append(f"best: {self.objective} {b.objective:.4g}, safety {b.safety:.3f} ({b.governing}, "
                         f"{b.governing_rpm:.0f} rpm)")
            lines += [f"  {p} = {v:.4g}" for p, v in b.values.items()]
            t = self.targets
            if t is not None and t.orders:
                lines.append(f"  first mode {b.f1_hz:.1f} Hz on the lumped chain ({b.f1_hz * t.frequency_factor:.1f} Hz "
                             f"as the bearings' f1), resonance clearance {100 * t.clearance(b):+.1f} % against "
                             f"{100 * t.margin:.0f} %")
            if t is not None and t.heat_limit_w and b.damper is not None:
                lines.append(f"  added damper's heat {b.damper_power_w:.1f} W against {t.heat_limit_w:.1f} W")
            if b.damper is not None:
                lines.append(f"  added {b.damper.kind} damper: ring {b.damper.ring_inertia:.4g} kg m^2 "
                             f"(inertia ratio {b.inertia_ratio:.3f}), stiffness {b.damper.stiffness:.4g} N m/rad"
                             + (f", loss factor {b.damper.loss_factor:.3g}" if b.damper.kind == "rubber" else "")
                             + (f", damping {b.damper.damping:.4g} N m s/rad" if b.damper.damping else ""))
        head = f"{self.objective + ' [' + unit + ']':>16} {'safety':>8}  governing"
        lines += ["Pareto front (objective against the explorer's safety):", head, "-" * len(head)]
        lines += [f"{c.objective:16.4g} {c.safety:8.3f}  {c.governing} at {c.governing_rpm:.0f} rpm" for c in self.pareto]
        return "\n".join(lines + [f"- {n}" for n in self.notes])

    def plot(self, ax=None):
        """Every candidate, the Pareto front, the given design and the required safety."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(8, 5))
        ax.scatter([c.objective for c in self.candidates], [c.safety for c in self.candidates], s=8, color="0.7",
                   label="candidates")
        front = self.pareto
        ax.plot([c.objective for c in front], [c.safety for c in front], "o-", color="C0", ms=4, label="Pareto front")
        ax.plot([self.given.objective], [self.given.safety], "ks", label="given design")
        if self.best is not None:
            ax.plot([self.best.objective], [self.best.safety], "*", color="crimson", ms=14, label="chosen")
        ax.axhline(self.required, color="crimson", lw=1, ls="--", label=f"required {self.required:.2f}")
        ax.set_xlabel(f"{self.objective} [{OBJECTIVE_UNITS[self.objective]}]")
        ax.set_ylabel("M53 governing safety (explorer: lumped chain)")
        ax.set_title(f"{self.name}: design search", fontsize=10, wrap=True)
        ax.legend(fontsize=7)
        ax.figure.tight_layout()
        return ax


#: The sample key of an added damper's inertia ratio (beside the field paths).
INERTIA_RATIO = "damper_inertia_ratio"


@dataclass(frozen=True)
class ExplorerModel:
    """The explorer as a study model (:func:`fetorsion.studies.runner.run_samples`): ``model(values)``
    with ``values`` the ``[design]`` inputs by field path (file units) and, with a damper allowed,
    :data:`INERTIA_RATIO`; returns the objective, mass, M53's governing safety, place and speed,
    and the added damper's constants. Its results go to the sample store (a search run again
    finds them there) and it runs on a Dask cluster as a study's samples do."""

    crank: Crank
    scf: SCFSet
    expensive = False

    @cached_property  # every stored sample names its model: one hash of the description and SCFs
    def key(self) -> str:
        from ..studies.models import description_hash

        import hashlib

        scf = hashlib.sha256(repr(self.scf).encode()).hexdigest()[:16]
        return f"design-explorer/2/{description_hash(self.crank)}/{scf}"  # 2: f1 and the damper's heat in

    def __call__(self, values: dict) -> dict:
        from ..response.forced import response_setup, solve_response
        from .crank_verdict import design_speeds, fillet_torque_amplitude
        from .dampers import den_hartog_damper, equivalent_sdof
        from .m53 import run_m53_crank
        from .stress import fillets_of

        space = self.crank.design
        moved = {p: float(v) for p, v in values.items() if p != INERTIA_RATIO}
        mu = values.get(INERTIA_RATIO)
        v = with_values(self.crank, moved) if moved else self.crank
        setup = design_speeds(response_setup(v))
        damper = None
        if mu is not None:
            station = setup.damper_station(Damper(space.damper, "front", 0.0, 1.0))
            j_eq, omega_n = equivalent_sdof(setup.M, setup.K, station, 0, setup.torsional_modes)
            damper = den_hartog_damper(space.damper, float(mu), j_eq, omega_n, "front", 0.0)
        fillets = fillets_of(v)
        response = solve_response(setup, () if damper is None else (damper,))
        m53 = run_m53_crank(v, fillets, fillet_torque_amplitude(setup, response, fillets), setup.rpm, fe_scf=self.scf)
        ring = 0.0 if damper is None else damper.ring_inertia
        mass = crank_mass(v) + (ring / space.damper_ring_radius**2 if ring and space.damper_ring_radius else 0.0)
        if space.objective == "mass":
            value = mass
        elif space.objective == "inertia":
            from ..lumped_model.lumped import lumped

            # as the mass: fillets and drillings left out (the lumped chain subtracts drillings by
            # formula, which OpenCASCADE's solid with them differs from by 3e-4); a CAD crank's is
            # its solid's, fillets and drillings in (dropping its details would drop its solid)
            bare = v if self.crank.solid_step else with_values(self.crank, moved, details=False)
            value = float(np.sum(lumped(bare).inertias_kgm2)) + ring
        else:
            value = float(sum(abs(_nominal(v, p) - _nominal(self.crank, p)) / abs(_nominal(self.crank, p))
                              for p, _, _ in space.inputs))
        g = m53.governing
        out = {"objective": value, "mass_kg": mass, "safety": float(g.safety), "governing": g.name,
               "governing_rpm": float(g.torque_rpm), "f1_hz": first_elastic_hz(setup),
               "damper_power_w": 0.0 if damper is None else float(response.damper_power_w.sum(axis=(1, 2)).max())}
        if damper is not None:
            out.update(ring_inertia_kgm2=damper.ring_inertia, stiffness_nm_per_rad=damper.stiffness,
                       damping_nms_per_rad=damper.damping, loss_factor=damper.loss_factor)
        return out


def candidate_of(crank: Crank, values: dict, outputs: dict) -> Candidate:
    """The :class:`Candidate` of one explorer sample (its values and outputs)."""
    mu = values.get(INERTIA_RATIO)
    damper = None if mu is None else Damper(crank.design.damper, "front", 0.0, outputs["ring_inertia_kgm2"],
                                            outputs["stiffness_nm_per_rad"], outputs["damping_nms_per_rad"],
                                            outputs["loss_factor"])
    return Candidate({p: float(v) for p, v in values.items() if p != INERTIA_RATIO}, None if mu is None else float(mu),
                     damper, outputs["objective"], outputs["mass_kg"], outputs["safety"], outputs["governing"],
                     outputs["governing_rpm"], outputs["f1_hz"], outputs["damper_power_w"])


def _nominal(crank: Crank, path: str) -> float:
    """The value at ``path`` (its first entry where ``*`` names several), file units."""

    return float(field_values(crank, path)[0][1])


def run_design_search(crank: Crank, scf: SCFSet | None = None, seed: int = 0, popsize: int = 6,
                      maxiter: int = DESIGN_GENERATIONS, target: float | None = None, frequency_factor: float = 1.0,
                      heat_limit: float | None = None, client: Client | ClusterOnDemand | None = None,
                      store: SampleStore | None = None, progress: Callable[[str], None] | None = None) -> DesignResult:
    """Search the description's ``[design]`` space for the least objective that passes M53 on the
    lumped explorer (module docstring).

    Parameters
    ----------
    crank : Crank
        With ``[design]``, ``[excitation]`` and fillet radii.
    scf : SCFSet, optional
        The given crank's SCFs, M53's fallback outside its formulas' ranges (default
        :func:`fetorsion.design.crank_verdict.verdict_scfs`).
    seed : int
        Differential evolution's seed: the same seed gives the same search.
    popsize, maxiter : int
        Differential evolution's population (per variable) and generations.
    target : float, optional
        The safety the explorer must reach, where it differs from the required one: the required
        safety corrected by how far the confirming FE verdict fell short of the explorer's.
    frequency_factor : float
        The FE crank's first in-bearing frequency over the lumped chain's (the resonance
        constraint reads the lumped f1 times it); 1 until a confirming run measures it.
    heat_limit : float, optional
        The added damper's heat the explorer allows, W, where it differs from the rating (the
        rating corrected by the confirming FE verdict's heat over the explorer's).
    client : distributed.Client or ClusterOnDemand, optional
        Runs each generation's candidates on a Dask cluster (None: here, one after the other; the
        same search either way).
    store : SampleStore, optional
        Where the explorer's results are kept and found (default the sample store).
    progress : callable, optional
        Called with a line per generation.

    Returns
    -------
    DesignResult
    """
    from .crank_verdict import verdict_scfs
    from .m53 import m53_required

    _check_searchable(crank)
    from ..studies.runner import open_store

    space = crank.design
    start = time.perf_counter()
    model = ExplorerModel(crank, verdict_scfs(crank) if scf is None else scf)
    store = open_store() if store is None else store
    bounds = [(lo, hi) for _, lo, hi in space.inputs] + ([space.damper_inertia_ratio] if space.damper else [])
    pool = _Evaluations(crank, model, store, client, bounds)
    given = pool.evaluate([{}])[0]
    if given is None:
        raise FetorsionError(f"design: the explorer fails on the given design of {crank.name}")
    required = target or space.required_safety or m53_required(crank.limits)
    targets = DesignTargets(required, heat_limit or space.damper_heat_rating or 0.0, space.resonance_orders,
                            space.resonance_margin, tuple(crank.excitation.speed_range), frequency_factor)
    res = _global_search(pool, given, targets, seed, popsize, maxiter, progress, start)
    _walk_onto_constraints(pool, given, targets, progress)
    feasible = [c for c in pool.seen if targets.shortfall(c) == 0.0]
    best = min(feasible, key=lambda c: c.objective) if feasible else None
    notes = _search_notes(space, targets, len(bounds), seed, res.nit)
    return DesignResult(crank.name, space.objective, required, given, pool.seen, best, time.perf_counter() - start,
                        notes, targets, list(pool.failures))


def _check_searchable(crank: Crank) -> None:
    """Raise where ``crank``'s description gives the search nothing to move or to drive, or a
    damper twice."""
    space = crank.design
    if space is None:
        raise FetorsionError(f"design: {crank.source or crank.name} has no [design] table (what may change)")
    if crank.excitation is None:
        raise FetorsionError(f"design: {crank.source or crank.name} has no [excitation] table: nothing drives it")
    if crank.solid_step and space.inputs:
        raise FetorsionError(f"design: {crank.source or crank.name} takes its solid from {crank.solid_step}: its "
                             "dimensions cannot move ([design] may add a damper only)")
    if crank.dampers and space.damper:
        raise FetorsionError("design: the description has [[dampers]] already; [design] damper adds one: "
                             "remove one of them")


@dataclass
class _Evaluations:
    """The search's explorer calls: each point of the unit cube of ``bounds`` evaluated once
    (``cache``), every candidate in the order evaluated (``seen``), and why samples failed."""

    crank: Crank
    model: ExplorerModel
    store: object
    client: object
    bounds: list
    seen: list[Candidate] = field(default_factory=list)
    cache: dict[tuple, Candidate | None] = field(default_factory=dict)
    failures: dict[str, None] = field(default_factory=dict)  # the reasons, each once, in order

    def evaluate(self, samples: list[dict]) -> list[Candidate | None]:
        """The candidates of explorer ``samples`` (None where one failed, its reason kept)."""
        from ..studies.runner import run_samples

        records, _ = run_samples(self.model, samples, self.store, self.client, progress=False,
                                 label=f"{self.crank.name}: design")
        self.failures.update((r["error"], None) for r in records if "error" in r)
        return [candidate_of(self.crank, s, r["outputs"]) if "outputs" in r else None for s, r in zip(samples, records)]

    def sample_of(self, u) -> dict:
        """The explorer sample at point ``u`` of the unit cube."""
        space = self.crank.design
        x = [lo + ui * (hi - lo) for ui, (lo, hi) in zip(u, self.bounds)]
        values = {p: float(xi) for (p, _, _), xi in zip(space.inputs, x)}
        if space.damper:
            values[INERTIA_RATIO] = float(x[-1])
        return values

    def candidates(self, us) -> list[Candidate | None]:
        """The candidates at points ``us`` of the unit cube, those not evaluated yet at once."""
        keys = [tuple(np.round(np.clip(u, 0.0, 1.0), 12)) for u in us]
        todo = list(dict.fromkeys(k for k in keys if k not in self.cache))
        for k, c in zip(todo, self.evaluate([self.sample_of(k) for k in todo])):
            self.cache[k] = c
            if c is not None:  # None: a geometry that breaks a description rule (an overlap, a web too thin)
                self.seen.append(c)
        return [self.cache[k] for k in keys]


def _cost(c: Candidate | None, given: Candidate, targets: DesignTargets) -> float:
    """The global search's cost: the objective over the given design's plus the penalty on the shortfalls."""
    if c is None:
        return 1e3
    return c.objective / given.objective + PENALTY * targets.shortfall(c)


def _global_search(pool: _Evaluations, given: Candidate, targets: DesignTargets, seed: int, popsize: int,
                   maxiter: int, progress, start: float) -> scipy.optimize.OptimizeResult:
    """Differential evolution on the unit cube from the given design, each generation's samples at once."""
    space, bounds = pool.crank.design, pool.bounds
    done = [0]

    def generation(intermediate_result):  # scipy passes the result by this parameter's name
        done[0] += 1
        if progress is not None:
            spent = time.perf_counter() - start
            progress(f"design: generation {done[0]} of at most {maxiter}, {len(pool.seen)} candidates, best cost "
                     f"{intermediate_result.fun:.4f} (its objective over the given design's, 1 = as given, plus "
                     f"{PENALTY:g} per unit of relative shortfall of a constraint); {spent:.0f} s, at most "
                     f"{spent / done[0] * (maxiter - done[0]):.0f} s left at this pace (the search may end sooner), "
                     "then the constraint walk")

    def cost(u):
        return _cost(pool.candidates([u])[0], given, targets)

    def population(func, us):  # a generation at once: its samples spread over the cluster's workers
        return [_cost(c, given, targets) for c in pool.candidates(list(us))]

    unit = [(0.0, 1.0)] * len(bounds)
    x0 = [min(max((_nominal(pool.crank, p) - lo) / (hi - lo), 0.0), 1.0) for p, lo, hi in space.inputs]
    x0 += [0.5] if space.damper else []
    return scipy.optimize.differential_evolution(cost, unit, seed=seed, popsize=popsize, maxiter=maxiter, polish=False,
                                                 init="sobol", x0=x0, callback=generation, tol=1e-3,
                                                 updating="deferred", workers=population)


def _walk_onto_constraints(pool: _Evaluations, given: Candidate, targets: DesignTargets, progress) -> None:
    """COBYQA from the best feasible candidate so far, its candidates added to ``pool``; none without one."""
    # The global search ends near the optimum, which lies on the safety constraint; COBYQA (a
    # derivative-free trust-region method with the constraint as such, [Ragonneau]) walks onto it.
    feasible = [c for c in pool.seen if targets.shortfall(c) == 0.0]
    if not feasible:
        return
    space, bounds = pool.crank.design, pool.bounds
    start_at = min(feasible, key=lambda c: c.objective)
    u0 = [(start_at.values[p] - lo) / (hi - lo) for p, lo, hi in space.inputs]
    u0 += [(start_at.inertia_ratio - bounds[-1][0]) / (bounds[-1][1] - bounds[-1][0])] if space.damper else []

    def objective(u):
        c = pool.candidates([u])[0]
        return 1e3 if c is None else c.objective / given.objective

    def margins(u):  # each constraint as a relative margin, >= 0 where it holds
        c = pool.candidates([u])[0]
        if c is None:
            return -np.ones(3)
        heat = 1.0 - c.damper_power_w / targets.heat_limit_w if targets.heat_limit_w and c.damper else 0.0
        return np.array([c.safety / targets.safety - 1.0, heat,
                         targets.clearance(c) - targets.margin if targets.orders else 0.0])

    if progress is not None:
        progress(f"design: {len(pool.seen)} candidates; walking onto the constraints (COBYQA)")
    scipy.optimize.minimize(objective, u0, method="COBYQA", bounds=[(0.0, 1.0)] * len(bounds),
                            constraints=[scipy.optimize.NonlinearConstraint(margins, 0.0, np.inf)],
                            options={"maxfev": 40 * len(bounds), "initial_tr_radius": 0.05,
                                     "final_tr_radius": 1e-3})


def _search_notes(space, targets: DesignTargets, variables: int, seed: int, generations: int) -> list[str]:
    """The search's notes: the explorer and its method, and the constraints besides the safety."""
    notes = [f"explorer: the lumped chain (default partition) with M53 at every k-th speed "
             f"(at most 100); differential evolution, {variables} variables, seed {seed}, {generations} generations, "
             "then COBYQA onto the constraints",
             "the explorer decides nothing: `fetorsion run` of the written description (the condensed FE crank) "
             "confirms the chosen design"]
    if targets.orders:
        notes.append(f"resonance: orders {', '.join(f'{q:g}' for q in targets.orders)} kept out of "
                     f"{targets.speed_range_rpm[0]:.0f}-{targets.speed_range_rpm[1]:.0f} rpm by {100 * targets.margin:.0f} % "
                     f"on the lumped chain's f1 times {targets.frequency_factor:.4f} (the FE crank's in-bearing f1 "
                     "over the lumped chain's" + (", measured by the condensed FE crank)" if targets.frequency_factor != 1.0
                                                  else "; 1: not measured)"))
    if targets.heat_limit_w:
        notes.append(f"the added damper's heat (its largest mean dissipation over the speeds) at most "
                     f"{targets.heat_limit_w:.1f} W on the explorer" + (
                         f" (its rating {space.damper_heat_rating:.1f} W re-aimed by the FE verdict)"
                         if targets.heat_limit_w != space.damper_heat_rating else ""))
    return notes

def _ranges_left_behind(text: str, crank: Crank, changes: dict[str, float]) -> str:
    """``text`` with each ``[uncertainty]`` entry whose range no longer holds a designed value
    (and its ``[distributions]`` line) commented out, saying why: the ranges were the given
    design's, and the description's rule that a range holds its nominal value would refuse the
    file. The other entries stay."""

    stale = set()
    for name, members in crank.uncertainty:
        for path, low, high in members:
            if any(where in changes and not low <= changes[where] <= high for where, _ in field_values(crank, path)):
                stale.add(name)
    if not stale:
        return text
    lines, table = text.splitlines(keepends=True), ""
    for k, line in enumerate(lines):
        stripped = line.strip()
        if stripped.startswith("["):
            table = stripped
            continue
        key = stripped.partition("=")[0].strip().strip('"')
        if table in ("[uncertainty]", "[distributions]") and "=" in stripped and not stripped.startswith("#") \
                and key in stale:
            lines[k] = f"# {line.rstrip()}  # fetorsion design: the given design's range, not the designed value's\n"
    return "".join(lines)


def _solid_path_absolute(text: str, step: str) -> str:
    """``text`` with its ``[solid] step`` path made absolute: the designed file is written elsewhere."""
    lines, table = text.splitlines(keepends=True), ""
    for k, line in enumerate(lines):
        stripped = line.strip()
        if stripped.startswith("["):
            table = stripped
        elif table == "[solid]" and stripped.partition("=")[0].strip() == "step":
            old = stripped.partition("=")[2].split("#")[0].strip()
            lines[k] = f"step = {json.dumps(step)}  # was {old}: the designed file lives elsewhere\n"
    return "".join(lines)


def designed_text(text: str, crank: Crank, best: Candidate) -> str:
    """The description ``text`` with the chosen design: each moved input set (every entry a ``*``
    path names) and commented, and the added damper as a ``[[dampers]]`` table."""

    changes = {}
    for path, value in best.values.items():
        for where, _ in field_values(crank, path):
            changes[where] = round(value, 3)
    out = edit_toml_values(text, changes, "fetorsion design") if changes else text
    out = _ranges_left_behind(out, crank, changes)
    if crank.solid_step:
        out = _solid_path_absolute(out, crank.solid_step)
    d = best.damper
    if d is not None:
        lines = ["", f"# Added by fetorsion design: a {d.kind} damper at the pulley tuned by Den Hartog's rule to the "
                 f"first mode, inertia ratio {best.inertia_ratio:.4f}.", "[[dampers]]", f'type = "{d.kind}"',
                 'at = "front"', f"ring_inertia_kgm2 = {d.ring_inertia:.6g}"]
        if d.kind in ("rubber", "tuned"):
            lines.append(f"stiffness_nm_per_rad = {d.stiffness:.6g}")
        if d.kind == "rubber":
            lines.append(f"loss_factor = {d.loss_factor:.6g}")
        if d.kind in ("viscous", "tuned") and d.damping:
            lines.append(f"damping_nms_per_rad = {d.damping:.6g}")
        if crank.design.damper_heat_rating:
            lines.append(f"allowed_power_w = {crank.design.damper_heat_rating:.6g}  # [design] damper_heat_rating_w")
        lines.append('source = "fetorsion design: Den Hartog tuning on the lumped chain"')
        out = out.rstrip("\n") + "\n" + "\n".join(lines) + "\n"
    return out

