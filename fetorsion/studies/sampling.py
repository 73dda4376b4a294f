"""The inputs of a study and their samples: Sobol', Morris (SALib), Monte Carlo, grid.

Each entry of a description's ``[uncertainty]`` table is one input, uniform over its range
unless the description's ``[distributions]`` table gives it a triangular or truncated normal
distribution (SALib's inverse-CDF scaling, the same for every sampling method but the grid).
A group (inputs that move together, low with low) is one input too: its first member's value
is sampled and every other member sits at the same fraction of its own range. A sample is a
dict ``{field path: value}`` in file units, what :func:`~fetorsion.studies.sensitivity.with_values`
takes.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..errors import FetorsionError, ParameterError

if TYPE_CHECKING:
    from ..description.chain_model import Chain, Network
    from ..description.model import Crank

METHODS = ("sobol", "morris", "montecarlo", "grid")
#: Levels of the Morris grid (SALib's default; the trajectories' step is 2/3 of each range).
MORRIS_LEVELS = 4
#: A full-factorial grid larger than this is refused (it is a Monte Carlo's job).
MAX_GRID_RUNS = 1_000_000


@dataclass(frozen=True)
class StudyInput:
    """One sampled input: ``name`` (the ``[uncertainty]`` entry), ``members`` (path, low, high)
    in file units; the sampled value is the first member's. ``distribution``: ``uniform``
    over the range, ``triangular`` (peak at ``nominal``) or ``normal`` (mean ``nominal``,
    standard deviation ``sd``, truncated to the range)."""

    name: str
    members: tuple[tuple[str, float, float], ...]
    distribution: str = "uniform"
    nominal: float | None = None
    sd: float | None = None

    def salib(self) -> tuple[str, list[float]]:
        """SALib's name and parameters of the distribution."""
        lo, hi = self.bounds
        if self.distribution == "triangular":
            return "triang", [lo, hi, (self.nominal - lo) / (hi - lo)]
        if self.distribution == "normal":
            return "truncnorm", [lo, hi, self.nominal, self.sd]
        return "unif", [lo, hi]

    @property
    def bounds(self) -> tuple[float, float]:
        return self.members[0][1], self.members[0][2]

    def values(self, x: float) -> dict[str, float]:
        """Every member's value where the first is at ``x``."""
        lo, hi = self.bounds
        t = (x - lo) / (hi - lo)
        return {path: low + t * (high - low) for path, low, high in self.members}


def study_inputs(crank: Crank | Chain | Network, names: Sequence[str] | None = None,
                 exclude_prefixes: tuple[str, ...] = ()) -> tuple[list[StudyInput], list[str]]:
    """The ``[uncertainty]`` entries as inputs: all, or those in ``names``; entries whose
    paths start with one of ``exclude_prefixes`` (details a model leaves out) are returned
    apart, as the second list, held at their nominal values."""
    from ..description.edit import field_values

    dists = {name: (kind, sd) for name, kind, sd in getattr(crank, "distributions", ())}

    def entry(name, members):
        kind, sd = dists.get(name, ("uniform", None))
        values = [v for _, v in field_values(crank, members[0][0])]
        return StudyInput(name, tuple(members), kind, float(sum(values) / len(values)), sd)

    entries = [entry(n, m) for n, m in crank.uncertainty]
    if names is not None:
        known = {e.name for e in entries}
        unknown = [n for n in names if n not in known]
        if unknown:
            raise ParameterError("inputs", f"{unknown[0]}: not an [uncertainty] entry of {crank.source}; "
                                 f"choose from {', '.join(sorted(known))}")
        entries = [e for e in entries if e.name in names]
    kept = [e for e in entries if not any(p.startswith(exclude_prefixes) for p, _, _ in e.members)] \
        if exclude_prefixes else entries
    left = [e.name for e in entries if e not in kept]
    return kept, left


def salib_problem(inputs: list[StudyInput], distributions: bool = True) -> dict:
    """SALib's problem dict: names, and the bounds (uniform) or each input's distribution
    (``dists``, when any is not uniform and ``distributions``)."""
    problem = {"num_vars": len(inputs), "names": [i.name for i in inputs], "bounds": [list(i.bounds) for i in inputs]}
    if distributions and any(i.distribution != "uniform" for i in inputs):
        problem["dists"], problem["bounds"] = map(list, zip(*(i.salib() for i in inputs)))
    return problem


def runs_for(method: str, n: int, d: int) -> int:
    """Model runs a study of ``n`` samples needs with ``d`` inputs (see :func:`sample_matrix`)."""
    return {"sobol": n * (d + 2), "morris": n * (d + 1), "montecarlo": n, "grid": n**d}[method]


def check_samples(method: str, n: int, d: int) -> None:
    """Refuse a sample count the method cannot use (a :class:`ParameterError` of ``samples``)."""
    if d == 0:
        raise FetorsionError("the study has no input to sample")
    if method == "sobol" and (n < 2 or n & (n - 1)):
        raise ParameterError("samples", f"{n}: Sobol' sampling needs a power of 2 (base samples; "
                             f"the study runs N·(inputs + 2) = {runs_for(method, max(n, 1), d)} models)")
    if method in ("morris", "montecarlo", "grid") and n < 2:
        raise ParameterError("samples", f"{n}: the {method} method needs at least 2")
    if method == "grid" and n**d > MAX_GRID_RUNS:
        raise ParameterError("samples", f"{n}: a grid of {n} levels over {d} inputs is {n}^{d} runs "
                             f"(over {MAX_GRID_RUNS:,}); choose fewer inputs or the montecarlo method")


def sample_matrix(method: str, inputs: list[StudyInput], n: int, seed: int = 0) -> np.ndarray:
    """Sample points, one row per model run, one column per input (first member's value).

    ``sobol``: Saltelli's scheme over a scrambled Sobol' sequence, ``n`` base samples
    (power of 2), first and total order: ``n·(d + 2)`` rows. ``morris``: ``n`` trajectories of
    ``d + 1`` points on a 4-level grid. ``montecarlo``: ``n`` independent points. Each input
    follows its distribution (uniform unless ``[distributions]`` says otherwise) in ``sobol``
    and ``montecarlo``; Morris's levels and the grid span the ranges. ``grid``: ``n`` evenly spaced levels of each range (ends included), full factorial: ``n**d``.
    """
    # The grid and Morris's levels span each range: distributions are for the random designs.
    problem = salib_problem(inputs, distributions=method not in ("grid", "morris"))
    check_samples(method, n, len(inputs))
    if method == "sobol":
        from SALib.sample import sobol

        return sobol.sample(problem, n, calc_second_order=False, seed=seed)
    if method == "morris":
        from SALib.sample import morris

        return morris.sample(problem, n, num_levels=MORRIS_LEVELS, seed=seed)
    if method == "montecarlo":
        from SALib.util import scale_samples

        return scale_samples(np.random.default_rng(seed).random((n, len(inputs))), problem)
    if method == "grid":
        lo, hi = np.array(problem["bounds"]).T
        axes = np.linspace(lo, hi, n).T
        return np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, len(inputs))
    raise ParameterError("method", f"{method}: choose from {', '.join(METHODS)}")


def samples_of(inputs: list[StudyInput], X: np.ndarray) -> list[dict]:
    """Each row of ``X`` as the dict of field values a model run takes."""
    return [{path: float(v) for i, x in zip(inputs, row) for path, v in i.values(x).items()} for row in X]
