"""Model updating: the description's ``[uncertainty]`` inputs fitted to measured natural frequencies.

Two paths over the same inputs, prior and model:

- **Least squares** (``lsq``): the sensitivity method of model updating [Mottershead],
  regularised toward the nominal description. In each input's normalised coordinate
  u_i = (x_i − x0_i) / s_i, with s_i the standard deviation of its prior (a uniform range
  [a, b]: s = (b − a)/√12), it minimises

      Σ_j ((f_j(x) − f̃_j) / σ_j)² + Σ_i u_i²

  inside the ranges (``scipy.optimize.least_squares``, trust-region reflective, the prior as a
  second block of residuals: Tikhonov regularisation whose weight is the prior's own width).
  The Jacobian of the data block at the optimum is the sensitivity matrix; (JᵀJ + I)⁻¹ is the
  estimate's covariance in u (the Laplace approximation of the posterior).
- **Bayesian** (``bayes``): the posterior of the inputs, sampled with ``emcee``'s affine-invariant
  ensemble sampler [Emcee] [Goodman]: the prior is each input's ``[uncertainty]`` range, uniform,
  or its ``[distributions]`` entry (triangular or truncated normal); the likelihood is Gaussian,
  independent per mode, of standard deviation σ_j (measurement and model error together). The
  walkers move in the logit of each input's place in its range with differential-evolution moves
  [TerBraak], starting from the Laplace approximation around the least-squares estimate truncated
  to the ranges; a burn-in is discarded; the seed is fixed, so a run is reproducible.

**Identified** is decided by a deterministic rule, the same for every seed and method: the
local (Fisher) information of the data at the least-squares estimate, in prior standard
deviations, F = JᵀJ (J the Jacobian of the σ-weighted residuals with respect to u), gives the
Laplace posterior's covariance (F + I)⁻¹; an input is identified when its posterior standard
deviation √((F + I)⁻¹)ᵢᵢ is below :data:`IDENTIFIED_RATIO` of its prior's (the data have at
least halved it). The data determine as many quantities as F has eigenvalues above
1/r² − 1 (r = :data:`IDENTIFIED_RATIO`): each eigenvector is a combination Σ vᵢ uᵢ of the
inputs the data pin to below half its prior width, and with fewer measured frequencies than
inputs it is such a combination, not each input, that is determined — the result says which.
The MCMC posterior's own 5–95 % width against the prior's is reported beside the rule, with its
Monte Carlo standard error (batch means over the chain), as a check of the linearisation; a
sampled ratio is never the decision, because it moves with the seed by more than its margin.
A calibrated description changes the identified inputs; where the data identify none on its own,
every input the calibration moved, at its posterior median; every input the least squares moved
when all are asked for.

Measured modes are matched to the model's by order: the k frequencies given are the k lowest
elastic torsional modes of the free-free lumped chain, in ascending order. A modal test whose
lowest mode was not measured must leave the calibration out, or give every mode below it.

An input's coordinate x runs over its first member's range [a, b] (its nominal x0: the mean of a
``*`` field's entries in the file). Every entry it moves (each entry of a ``*`` field, each member
of a group) follows x by the map through (a, x0, b) -> (its low, its own value in the file, its
high), linear on each side of x0: at x0 the description is the file as written, even where a
``*`` field's entries differ (a nose of two steps) or a group's members sit at different places in
their ranges (E and density of a steel between the bounds of a cast iron and a steel); at the
bounds every entry is at its bound, as in :mod:`.sampling`; and no entry ever leaves its range.
"""

from __future__ import annotations

import datetime
import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..description.defaults import DEFAULT_WEB_METHOD, LUMPED17
from ..description.model import Chain, Crank, Network
from ..description.reader import resolve_field
from ..errors import FetorsionError, ParameterError
from ..lumped_model.lumped import PARTITIONS, lumped
from ..webs.methods import WEB_METHODS
from .sampling import study_inputs
from ..description.edit import edit_toml_values, field_values, with_values

METHODS = ("lsq", "bayes", "both")
#: Web-stiffness methods a calibration can run: not the static FE of each throw (``fe``,
#: ``fe-held``), which every new variant would mesh and solve again.
CALIBRATION_STIFFNESS = tuple(sorted(m for m in WEB_METHODS if not m.startswith("fe")))
#: Models a calibration can run: the lumped chains (the 3D FE is too slow for an MCMC).
CALIBRATION_MODELS = tuple(f"lumped{d}" for d in PARTITIONS)
#: Standard deviation of a measured frequency when none is stated, in % of it: the lumped
#: 17-DOF chain's f1 differs from the 3D FE's by 0.6 % (Renault 21) and 2.1 % (Peugeot GLX)
#: (docs/validation.md), a modal test's frequency error is ~0.1 %: the model's form dominates.
DEFAULT_SIGMA_PERCENT = 2.0
#: What a calibrated description changes, by :meth:`CalibrationResult.written_rule`.
WRITTEN_RULES = {"identified": "the inputs the data identify on their own, at their least-squares estimate",
                 "moved": "no input is identified on its own (the data fix a combination of them): every input "
                          "the calibration moved, at its posterior median (else its least-squares estimate)",
                 "all": "every input the least squares moved (write_all)"}
#: An input is identified when the data bring its (Laplace) posterior standard deviation below
#: this fraction of its prior's; a combination of inputs is determined likewise.
IDENTIFIED_RATIO = 0.5
#: Batches of the chain's steps for the Monte Carlo error of a sampled width ratio.
MC_BATCHES = 10
#: A determined combination lists the inputs whose coefficient is at least this share of its largest.
COMBINATION_SHARE = 0.1
#: Natural frequencies predicted (with their bands) beside the measured ones.
PREDICTED_MODES = 4
#: A chain file without ``[uncertainty]``: each inertia and stiffness within this share of its
#: value (a chain from a book, a supplier or an older calculation; stated with every result)
CHAIN_PRIOR_SHARE = 0.2


def default_chain_priors(chain: Chain) -> Chain:
    """``chain`` with an ``[uncertainty]`` entry for every inertia and stiffness, each within
    :data:`CHAIN_PRIOR_SHARE` of its value, where the file states none (a chain's inputs are its
    inertias and stiffnesses; a crank description's are its dimensions, which it must name)."""
    from dataclasses import replace

    if chain.uncertainty:
        return chain
    entries = []
    for key, values in (("inertias_kgm2", chain.inertias), ("stiffnesses_nm_per_rad", chain.stiffnesses)):
        for k, v in enumerate(values):
            path = f"chain.{key}.{k + 1}"
            entries.append((path, ((path, (1 - CHAIN_PRIOR_SHARE) * v, (1 + CHAIN_PRIOR_SHARE) * v),)))
    return replace(chain, uncertainty=tuple(entries))


def model_label(crank, model: str, stiffness: str) -> str:
    """What the calibrated model is, in words: a chain file's own chain, or the crank's lumped
    partition with its web-stiffness method."""
    if isinstance(crank, Chain):
        return f"the chain file's own {len(crank.inertias)}-inertia chain"
    return f"{model}, {stiffness} web stiffness"


def elastic_modes(crank, dof: int) -> int:
    """The model's elastic modes: a chain file's stations less the rigid rotation, else the
    partition's."""
    return len(crank.inertias) - 1 if isinstance(crank, Chain) else dof - 1
#: Posterior and prior interval reported: 5-95 %.
CREDIBLE_PERCENT = (5.0, 95.0)
#: The ensemble's default size and length: 32 walkers (at least 2 per input plus 2), 500 steps
#: kept after 150 of burn-in: on the Renault 21's 15 inputs the autocorrelation time was 35-45
#: steps, so 11-14 per walker, ~400 independent samples for the 5-95 % intervals, in ~21 000
#: model runs (35-50 s on this project's 2 shared cores).
DEFAULT_WALKERS = 32
DEFAULT_STEPS = 500
DEFAULT_BURN = 150
#: Share of differential-evolution moves; the rest are its snooker variant (emcee's example mix).
DE_SHARE = 0.8
#: Fewest steps kept: an autocorrelation time cannot be estimated from fewer.
MIN_STEPS = 50
#: Significant digits of a calibrated value written to the description.
WRITTEN_DIGITS = 6
#: Relative finite-difference step of the least-squares Jacobian, in prior standard deviations:
#: the eigenvalues are smooth, and 1e-6 sd keeps the round-off (~1e-12 of f) far below the change.
DIFF_STEP = 1e-6


@dataclass(frozen=True)
class CalibrationInput:
    """One calibrated input: an ``[uncertainty]`` entry (a field or a group).

    Attributes
    ----------
    name : str
        The ``[uncertainty]`` entry.
    nominal, low, high : float
        The first member's value in the file (mean of a ``*`` field's entries) and range, file units.
    entries : tuple of (str, float, float, float)
        Every concrete field (``webs.3.thickness``) it moves: its value in the file and its
        member's range (low, high).
    distribution : str
        ``uniform``, ``triangular`` (peak at the nominal) or ``normal`` (truncated to the range).
    sd : float or None
        A normal distribution's standard deviation, file units.
    """

    name: str
    nominal: float
    low: float
    high: float
    entries: tuple
    distribution: str = "uniform"
    sd: float | None = None

    def values(self, x: float) -> dict[str, float]:
        """Every concrete field's value with the input at ``x`` (file units): the map through
        (low, nominal, high) -> (its low, its value in the file, its high), linear on each side."""
        out = {}
        for path, v0, low, high in self.entries:
            if x >= self.nominal:
                t = (x - self.nominal) / (self.high - self.nominal) if self.high > self.nominal else 0.0
                out[path] = v0 + t * (high - v0)
            else:
                t = (self.nominal - x) / (self.nominal - self.low)
                out[path] = v0 - t * (v0 - low)
        return out

    def prior(self):
        """The prior as a frozen ``scipy.stats`` distribution over [low, high]."""
        from scipy import stats

        lo, width = self.low, self.high - self.low
        if self.distribution == "triangular":
            return stats.triang((self.nominal - lo) / width, loc=lo, scale=width)
        if self.distribution == "normal":
            a, b = (self.low - self.nominal) / self.sd, (self.high - self.nominal) / self.sd
            return stats.truncnorm(a, b, loc=self.nominal, scale=self.sd)
        return stats.uniform(loc=lo, scale=width)

    @property
    def prior_sd(self) -> float:
        """Standard deviation of the prior (file units): the least-squares regularisation's width."""
        return float(self.prior().std())


def calibration_inputs(crank: Crank | Chain | Network, names=None) -> list[CalibrationInput]:
    """The ``[uncertainty]`` entries of ``crank`` as calibration inputs: all, or those in ``names``
    (a chain file without the table: :func:`default_chain_priors`).

    Parameters
    ----------
    crank : Crank
        A description with an ``[uncertainty]`` table.
    names : sequence of str, optional
        ``[uncertainty]`` entry names (``"webs.*.thickness"``, ``"material"``); each once.

    Returns
    -------
    list of CalibrationInput
    """
    if isinstance(crank, Chain):
        crank = default_chain_priors(crank)
    if not getattr(crank, "uncertainty", None):
        raise FetorsionError(f"{crank.source or crank.name}: the description has no [uncertainty] table: "
                             "nothing to calibrate")
    if names is not None:
        names = list(names)
        if not names:
            raise ParameterError("inputs", "(none): name at least one [uncertainty] entry")
        if len(names) > len(crank.uncertainty):
            raise ParameterError("inputs", f"{len(names)} names: {crank.source} has only {len(crank.uncertainty)} "
                                 "[uncertainty] entries")
        twice = sorted({n for n in names if names.count(n) > 1})
        if twice:
            raise ParameterError("inputs", f"{twice[0]}: named twice")
    study, _ = study_inputs(crank, names)
    out = []
    for s in study:
        (path0, lo, hi) = s.members[0]
        entries = []
        for path, low, high in s.members:
            entries += [(where, float(v), float(low), float(high)) for where, v in field_values(crank, path)]
        out.append(CalibrationInput(s.name, float(s.nominal), float(lo), float(hi), tuple(entries),
                                    s.distribution, s.sd))
    return out


class FrequencyModel:
    """The lowest elastic natural frequencies (Hz) of the free-free lumped chain of the crank
    with its inputs at ``x`` (file units); counts its evaluations.

    Parameters
    ----------
    crank : Crank
        The nominal description.
    inputs : list of CalibrationInput
        What ``x`` sets, in order.
    dof : int
        Lumped partition (5, 6, 17, 19, 21).
    stiffness : str
        Web-stiffness method.
    modes : int
        How many elastic frequencies to return.
    """

    def __init__(self, crank: Crank, inputs, dof: int, stiffness: str, modes: int):
        self.crank, self.inputs, self.dof, self.stiffness, self.modes = crank, list(inputs), dof, stiffness, modes
        self.evaluations = 0
        self.seconds = 0.0

    def __call__(self, x) -> np.ndarray:
        t0 = time.perf_counter()
        values = {}
        for inp, xi in zip(self.inputs, x):
            values.update(inp.values(float(xi)))
        f = np.asarray(lumped(with_values(self.crank, values), self.dof, self.stiffness).frequencies_hz, float)
        self.evaluations += 1
        self.seconds += time.perf_counter() - t0
        out = np.full(self.modes, np.nan)
        out[: min(self.modes, f.size)] = f[: self.modes]
        return out

    @property
    def rate(self) -> float:
        """Evaluations per second so far."""
        return self.evaluations / self.seconds if self.seconds else math.nan


@dataclass
class LeastSquaresFit:
    """The regularised least-squares estimate.

    Attributes
    ----------
    values : ndarray
        Each input's estimate, file units.
    sd : ndarray
        Its standard deviation from (JᵀJ + I)⁻¹ (Laplace approximation), file units.
    at_bound : list of bool
        Whether the estimate sits on its range's bound.
    frequencies_hz : ndarray
        The model's predicted frequencies at the estimate.
    sensitivity_hz : ndarray (modes, inputs)
        ∂f_j/∂x_i × s_i: Hz per prior standard deviation, at the estimate.
    chi2 : float
        Σ ((f_j − f̃_j)/σ_j)² at the estimate.
    evaluations : int
        Model runs the fit took.
    """

    values: np.ndarray
    sd: np.ndarray
    at_bound: list
    frequencies_hz: np.ndarray
    sensitivity_hz: np.ndarray
    chi2: float
    evaluations: int


@dataclass
class Identification:
    """What the measured frequencies determine, by the local information at the least-squares
    estimate (see the module docstring): deterministic, the same for every seed and method.

    Attributes
    ----------
    sd_ratio : ndarray (inputs,)
        Each input's Laplace posterior standard deviation over its prior's, √((F + I)⁻¹)ᵢᵢ.
    identified : ndarray of bool
        ``sd_ratio`` < :data:`IDENTIFIED_RATIO`.
    combinations : ndarray (determined, inputs)
        Unit vectors v (in prior standard deviations u) of the combinations Σ vᵢ uᵢ the data
        determine, most determined first.
    combination_sd : ndarray (determined,)
        The posterior standard deviation of each, in prior standard deviations.
    """

    sd_ratio: np.ndarray
    identified: np.ndarray
    combinations: np.ndarray
    combination_sd: np.ndarray

    def lines(self, names) -> list[str]:
        """Plain text: how many quantities the data determine, and which."""
        n, k = len(names), len(self.combination_sd)
        out = [f"identified (deterministic rule): Laplace posterior sd below {IDENTIFIED_RATIO:g} of the prior's, "
               f"from the data's information at the least-squares estimate"]
        if k == 0:
            return out + [f"the data determine none of the {n} inputs, nor any combination of them"]
        out.append(f"the data determine {k} quantit{'y' if k == 1 else 'ies'} of the {n} inputs:")
        for v, sd in zip(self.combinations, self.combination_sd):
            keep = np.flatnonzero(np.abs(v) >= COMBINATION_SHARE * np.abs(v).max())
            keep = keep[np.argsort(-np.abs(v[keep]))]
            terms = " ".join(f"{'+' if v[i] >= 0 else '-'} {abs(v[i]):.2f} u({names[i]})" for i in keep)
            out.append(f"  {terms.lstrip('+ ')}   (posterior sd {sd:.2f} of its prior's)")
        if k < n:
            out.append("  u(x) = (x - nominal) / prior sd; an input whose posterior sd stays above "
                       f"{IDENTIFIED_RATIO:g} of its prior's is determined only in such a combination, not on its own")
        return out

    def to_dict(self, names) -> dict:
        return {"rule": f"Laplace posterior sd < {IDENTIFIED_RATIO:g} x prior sd (information at the lsq estimate)",
                "sd_ratio": dict(zip(names, self.sd_ratio.tolist())),
                "identified": [n for n, i in zip(names, self.identified) if i],
                "combinations": [{"coefficients": dict(zip(names, v.tolist())), "posterior_sd": float(sd)}
                                 for v, sd in zip(self.combinations, self.combination_sd)]}


def identification(fit: LeastSquaresFit, inputs, sigma_hz) -> Identification:
    """The deterministic identification of a least-squares fit of ``inputs`` (see
    :class:`Identification`): each input's Laplace sd over its prior's is the fit's own ``sd``
    over the prior sd; the combinations are the information's eigenvectors."""
    J = fit.sensitivity_hz / np.asarray(sigma_hz, float)[:, None]  # d(residual)/du at the estimate
    sd_ratio = fit.sd / np.array([i.prior_sd for i in inputs])
    lam, V = np.linalg.eigh(J.T @ J)
    order = np.argsort(lam)[::-1]
    lam, V = lam[order], V[:, order]
    keep = lam > 1.0 / IDENTIFIED_RATIO**2 - 1.0
    V = V[:, keep] * np.sign(V[np.argmax(np.abs(V[:, keep]), axis=0), np.arange(keep.sum())])
    return Identification(sd_ratio, sd_ratio < IDENTIFIED_RATIO, V.T, 1.0 / np.sqrt(1.0 + lam[keep]))


def width_ratio_error(samples: np.ndarray, walkers: int, p5: float, p95: float) -> float:
    """Monte Carlo standard error of a sampled 5-95 % width over the prior's (p95 − p5): batch
    means over :data:`MC_BATCHES` consecutive stretches of the chain's steps (``samples`` flat,
    step-major as emcee gives them)."""
    steps = samples.size // walkers
    batches = np.array_split(samples[: steps * walkers].reshape(steps, walkers), MC_BATCHES)
    ratios = [np.subtract(*np.percentile(b.ravel(), CREDIBLE_PERCENT[::-1])) / (p95 - p5) for b in batches]
    return float(np.std(ratios, ddof=1) / np.sqrt(len(ratios)))


@dataclass
class Posterior:
    """The sampled posterior.

    Attributes
    ----------
    samples : ndarray (n, inputs)
        Posterior samples (burn-in discarded), file units.
    frequencies_hz : ndarray (n, modes)
        The model's frequencies of each sample.
    acceptance : float
        Mean acceptance fraction of the walkers.
    autocorr_steps : float
        The largest integrated autocorrelation time over the inputs (of the walkers' logit
        coordinates), in steps (a lower estimate when the chain is short).
    walkers, steps, burn : int
        The ensemble's size, the steps kept and those discarded.
    seed : int
    """

    samples: np.ndarray
    frequencies_hz: np.ndarray
    acceptance: float
    autocorr_steps: float
    walkers: int
    steps: int
    burn: int
    seed: int


@dataclass
class CalibrationResult:
    """Inputs of a description fitted to measured natural frequencies.

    Attributes
    ----------
    name, source : str
        The crank and its file.
    model : str
        The lumped model (``lumped17``) and its web-stiffness method.
    method : str
        ``lsq``, ``bayes`` or ``both``.
    measured_hz, sigma_hz : ndarray
        The measured frequencies (the lowest elastic modes, ascending) and their standard deviations.
    inputs : list of CalibrationInput
    nominal_hz : ndarray
        The model's frequencies of the nominal description.
    lsq : LeastSquaresFit or None
    posterior : Posterior or None
    evaluations_per_s : float
        Model evaluations per second over the whole calibration.
    seconds : float
        Wall time of the calibration.
    """

    name: str
    source: str
    model: str
    method: str
    measured_hz: np.ndarray
    sigma_hz: np.ndarray
    inputs: list
    nominal_hz: np.ndarray
    lsq: LeastSquaresFit | None = None
    posterior: Posterior | None = None
    identification: Identification | None = None
    #: Write every input the least squares moved, not only the identified ones
    write_all: bool = False
    evaluations_per_s: float = math.nan
    seconds: float = math.nan
    date: str = field(default_factory=lambda: datetime.date.today().isoformat())
    #: Where the inputs' ranges came from when the file states none (a chain's default priors)
    priors: str = ""

    # -- the posterior's summaries

    def input_rows(self) -> list[dict]:
        """One dict per input: nominal, range, the estimate and the posterior's summary (file units)."""
        lo_q, hi_q = CREDIBLE_PERCENT
        rows = []
        for i, inp in enumerate(self.inputs):
            prior = inp.prior()
            p5, p95 = prior.ppf(lo_q / 100), prior.ppf(hi_q / 100)
            row = {"input": inp.name, "nominal": inp.nominal, "low": inp.low, "high": inp.high,
                   "distribution": inp.distribution, "prior_5": float(p5), "prior_95": float(p95)}
            if self.lsq is not None:
                row.update(lsq=float(self.lsq.values[i]), lsq_sd=float(self.lsq.sd[i]),
                           lsq_change_percent=float(100 * (self.lsq.values[i] - inp.nominal) / inp.nominal),
                           lsq_at_bound=bool(self.lsq.at_bound[i]))
            if self.identification is not None:
                row.update(sd_ratio=float(self.identification.sd_ratio[i]),
                           identified=bool(self.identification.identified[i]))
            if self.posterior is not None:
                s = self.posterior.samples[:, i]
                q5, q50, q95 = np.percentile(s, [lo_q, 50.0, hi_q])
                row.update(mean=float(s.mean()), median=float(q50), q5=float(q5), q95=float(q95),
                           width_ratio=float((q95 - q5) / (p95 - p5)),
                           width_ratio_mc_error=width_ratio_error(s, self.posterior.walkers, p5, p95))
            rows.append(row)
        return rows

    def prediction_rows(self) -> list[dict]:
        """One dict per predicted mode: measured (if any), nominal, least-squares and posterior (Hz)."""
        lo_q, hi_q = CREDIBLE_PERCENT
        rows = []
        for j in range(self.nominal_hz.size):
            row = {"mode": j + 1, "measured_hz": float(self.measured_hz[j]) if j < self.measured_hz.size else None,
                   "sigma_hz": float(self.sigma_hz[j]) if j < self.sigma_hz.size else None,
                   "nominal_hz": float(self.nominal_hz[j])}
            if self.lsq is not None:
                row["lsq_hz"] = float(self.lsq.frequencies_hz[j])
            if self.posterior is not None:
                f = self.posterior.frequencies_hz[:, j]
                q5, q50, q95 = np.percentile(f, [lo_q, 50.0, hi_q])
                row.update(median_hz=float(q50), q5_hz=float(q5), q95_hz=float(q95), mean_hz=float(f.mean()))
            rows.append(row)
        return rows

    def written_rule(self) -> str:
        """Which inputs a calibrated description changes: ``identified`` (the data identify some
        on their own: those), ``moved`` (none on its own, only a combination: every input the
        calibration moved, the posterior's median where there is one) or ``all`` (``write_all``:
        every input the least squares moved)."""
        if self.write_all:
            return "all"
        return "identified" if any(r.get("identified") for r in self.input_rows()) else "moved"

    def calibrated_values(self) -> dict[str, float]:
        """The inputs a calibrated description changes (:meth:`written_rule`), with their values
        (file units), each rounded to :data:`WRITTEN_DIGITS` significant digits and kept where
        that differs from the nominal: the least-squares estimate of the identified inputs (or of
        every input, ``write_all``), else the posterior median; with no input identified on its
        own, every input the posterior median (else the estimate) moves."""
        rule = self.written_rule()
        out = {}
        for i, (inp, row) in enumerate(zip(self.inputs, self.input_rows())):
            if rule == "identified" and not row.get("identified"):
                continue
            median = row.get("median")
            if rule == "moved" and median is not None or self.lsq is None:
                x = median
            else:
                x = float(self.lsq.values[i])
            x = float(f"{x:.{WRITTEN_DIGITS}g}")
            if x != float(f"{inp.nominal:.{WRITTEN_DIGITS}g}"):
                out[inp.name] = x
        return out

    def change_note(self, name: str) -> str:
        """What a written change of input ``name`` rests on: its posterior (median and 5-95 %
        interval) where there is one, and whether the data identify it on its own."""
        row = next(r for r in self.input_rows() if r["input"] == name)
        parts = []
        if "median" in row:
            parts.append(f"posterior median {row['median']:.4g} (5-95 %: {row['q5']:.4g} to {row['q95']:.4g})")
        if "lsq" in row:
            parts.append(f"least squares {row['lsq']:.4g}")
        if "identified" in row:
            parts.append("identified on its own" if row["identified"] else
                         "not identified on its own (the data fix a combination of the inputs)")
        return "; ".join(parts)

    def source_note(self) -> str:
        """Where the calibrated values come from, for the comments of the file written."""
        hz = ", ".join(f"{f:g}" for f in self.measured_hz)
        median = self.lsq is None or (self.written_rule() == "moved" and self.posterior is not None)
        how = "bayes (posterior median)" if median else "lsq"
        return f"calibrated to {hz} Hz measured, fetorsion calibrate {how}, {self.date}"

    # -- the results protocol

    def to_dict(self) -> dict:
        """JSON-ready: the inputs' and predictions' rows, the settings and the sampler's diagnostics
        (frequencies in Hz, inputs in file units)."""
        out = {"name": self.name, "source": self.source, "model": self.model, "method": self.method,
               "measured_hz": self.measured_hz.tolist(), "sigma_hz": self.sigma_hz.tolist(),
               "matching": "by order: the measured frequencies are the lowest elastic modes, ascending",
               "priors": self.priors or "the file's [uncertainty] table",
               "identified_rule": f"Laplace posterior sd < {IDENTIFIED_RATIO:g} x prior sd, from the information at "
                                  "the least-squares estimate (deterministic)",
               "written": WRITTEN_RULES[self.written_rule()],
               "inputs": self.input_rows(), "predictions": self.prediction_rows(),
               "calibrated_values": self.calibrated_values(), "evaluations_per_s": self.evaluations_per_s,
               "seconds": self.seconds, "date": self.date}
        if self.identification is not None:
            out["identification"] = self.identification.to_dict([i.name for i in self.inputs])
        if self.lsq is not None:
            out["lsq"] = {"chi2": self.lsq.chi2, "evaluations": self.lsq.evaluations,
                          "sensitivity_hz_per_prior_sd": self.lsq.sensitivity_hz.tolist()}
        if self.posterior is not None:
            p = self.posterior
            out["posterior"] = {"walkers": p.walkers, "steps": p.steps, "burn": p.burn, "seed": p.seed,
                                "acceptance": p.acceptance, "autocorr_steps": p.autocorr_steps,
                                "samples": int(p.samples.shape[0])}
        return out

    def table(self) -> str:
        """Plain text: each input (nominal, range, estimate, posterior interval, identified) and
        each natural frequency (measured, nominal, calibrated, band)."""
        lines = [f"{self.name}: calibrated to measured natural frequencies ({self.model}, {self.method})",
                 "measured modes matched by order to the model's lowest elastic modes"]
        if self.priors:
            lines.append(f"priors: {self.priors}")
        head = f"{'input':<30} {'nominal':>10} {'range':>19}"
        if self.lsq is not None:
            head += f" {'lsq':>10} {'± sd':>9}"
        if self.posterior is not None:
            head += f" {'median':>10} {'5-95 %':>21} {'width (MC)':>13}"
        head += f" {'sd ratio':>8} identified"
        lines += [head, "-" * len(head)]
        for r in self.input_rows():
            line = f"{r['input']:<30} {r['nominal']:10.5g} {r['low']:>9.4g}..{r['high']:<8.4g}"
            if self.lsq is not None:
                line += f" {r['lsq']:10.5g} {r['lsq_sd']:9.3g}" + (" (at bound)" if r["lsq_at_bound"] else "")
            if self.posterior is not None:
                band = f"{r['q5']:.4g}..{r['q95']:.4g}"
                width = f"{r['width_ratio']:.2f}±{r['width_ratio_mc_error']:.2f}"
                line += f" {r['median']:10.5g} {band:>21} {width:>13}"
            if "sd_ratio" in r:
                line += f" {r['sd_ratio']:8.2f} {'yes' if r['identified'] else 'no'}"
            lines.append(line)
        lines.append("")
        head = f"{'mode':>4} {'measured':>9} {'sigma':>6} {'nominal':>9}"
        head += f" {'lsq':>9}" if self.lsq is not None else ""
        head += f" {'posterior median':>16} {'5-95 %':>17}" if self.posterior is not None else ""
        lines += ["natural frequencies [Hz]", head]
        for r in self.prediction_rows():
            m = f"{r['measured_hz']:9.2f} {r['sigma_hz']:6.2f}" if r["measured_hz"] is not None else f"{'':9} {'':6}"
            line = f"{r['mode']:4d} {m} {r['nominal_hz']:9.2f}"
            if self.lsq is not None:
                line += f" {r['lsq_hz']:9.2f}"
            if self.posterior is not None:
                line += f" {r['median_hz']:16.2f} {r['q5_hz']:8.2f}..{r['q95_hz']:<8.2f}"
            lines.append(line)
        if self.lsq is not None:
            lines.append(f"least squares: chi2 {self.lsq.chi2:.3g} over {self.measured_hz.size} modes, "
                         f"{self.lsq.evaluations} model runs")
        if self.posterior is not None:
            p = self.posterior
            lines.append(f"posterior: {p.walkers} walkers x {p.steps} steps (+{p.burn} burn-in), seed {p.seed}; "
                         f"acceptance {p.acceptance:.2f}; autocorrelation time {p.autocorr_steps:.0f} steps "
                         f"({p.steps / p.autocorr_steps:.0f} per chain)")
            lines.append("width (MC): the sampled posterior's 5-95 % width over the prior's, ± its Monte Carlo "
                         "standard error (a check of the linearisation; not the rule)")
        if self.identification is not None:
            lines += self.identification.lines([i.name for i in self.inputs])
        written = self.calibrated_values()
        lines.append(f"a calibrated description would change {len(written)} input(s): {WRITTEN_RULES[self.written_rule()]}")
        lines.append(f"{self.evaluations_per_s:.0f} model evaluations/s; {self.seconds:.1f} s")
        return "\n".join(lines)

    def plot(self, ax=None):
        """Each input in its range (0 = low bound, 1 = high): the nominal, the least-squares
        estimate and the posterior's 5-95 % interval and median. Returns the Axes."""
        import matplotlib.pyplot as plt

        rows = self.input_rows()
        if ax is None:
            _, ax = plt.subplots(figsize=(8, 0.35 * len(rows) + 1.6))
        for k, r in enumerate(rows):
            span = r["high"] - r["low"]

            def t(v):
                return (v - r["low"]) / span

            ax.plot([t(r["prior_5"]), t(r["prior_95"])], [k, k], color="0.8", lw=6, solid_capstyle="butt",
                    label="prior 5-95 %" if k == 0 else None)
            if "q5" in r:
                ax.plot([t(r["q5"]), t(r["q95"])], [k, k], color="C0", lw=3,
                        label="posterior 5-95 %" if k == 0 else None)
                ax.plot(t(r["median"]), k, "o", color="C0", ms=4, label="posterior median" if k == 0 else None)
            if "lsq" in r:
                ax.plot(t(r["lsq"]), k, "D", color="C3", ms=4, label="least squares" if k == 0 else None)
            ax.plot(t(r["nominal"]), k, "|", color="k", ms=10, label="nominal" if k == 0 else None)
        ax.set_yticks(range(len(rows)), [r["input"] for r in rows], fontsize=7)
        ax.set_xlim(-0.02, 1.02)
        ax.set_xlabel("position in the [uncertainty] range (0 = low, 1 = high)")
        hz = ", ".join(f"{f:g}" for f in self.measured_hz)
        ax.set_title(f"{self.name}\ncalibrated to {hz} Hz ({self.model}, {self.method})", fontsize=9, wrap=True)
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0))
        ax.figure.tight_layout()
        return ax


def _partition(model: str) -> int:
    if model not in CALIBRATION_MODELS:
        raise ParameterError("model", f"{model}: choose from {', '.join(CALIBRATION_MODELS)} (the 3D FE is too slow "
                             "for the thousands of runs of a calibration)")
    return int(model.removeprefix("lumped"))


def check_measured_hz(measured_hz, sigma_hz=None, sigma_percent: float = DEFAULT_SIGMA_PERCENT):
    """The measured frequencies and their standard deviations (Hz), checked.

    Parameters
    ----------
    measured_hz : sequence of float
        Natural frequencies, Hz: the lowest elastic modes, ascending.
    sigma_hz : float or sequence of float, optional
        Standard deviation of each (measurement and model error), Hz; one for all or one each.
    sigma_percent : float
        When ``sigma_hz`` is not given: the standard deviation in % of each frequency.

    Returns
    -------
    (ndarray, ndarray)
        Frequencies and standard deviations, Hz.
    """
    f = np.atleast_1d(np.asarray(measured_hz, float))
    if f.size == 0:
        raise ParameterError("measured_hz", "(none): give at least one measured natural frequency (Hz)")
    bad = [v for v in f if not (math.isfinite(v) and v > 0)]
    if bad:
        raise ParameterError("measured_hz", f"{bad[0]:g}: a natural frequency must be a finite number > 0 (Hz)")
    if np.any(np.diff(f) <= 0):
        raise ParameterError("measured_hz", f"{' '.join(f'{v:g}' for v in f)}: give them in ascending order, each "
                             "once: they are matched by order to the model's lowest elastic modes")
    if sigma_hz is None:
        if not (math.isfinite(sigma_percent) and 0 < sigma_percent < 100):
            raise ParameterError("sigma_percent", f"{sigma_percent:g}: must be > 0 and < 100 (%)")
        return f, f * sigma_percent / 100
    s = np.atleast_1d(np.asarray(sigma_hz, float))
    if s.size not in (1, f.size):
        raise ParameterError("sigma_hz", f"{s.size} values for {f.size} measured frequencies: give one, or one each")
    bad = [v for v in s if not (math.isfinite(v) and v > 0)]
    if bad:
        raise ParameterError("sigma_hz", f"{bad[0]:g}: a standard deviation must be a finite number > 0 (Hz)")
    return f, np.broadcast_to(s, f.shape).astype(float)


def check_ensemble(ndim: int, walkers: int | None, steps: int, burn: int) -> int:
    """The walkers (default: :data:`DEFAULT_WALKERS`, at least 2 per input plus 2) and chain
    lengths, checked; returns the walkers."""
    need = 2 * ndim + 2
    if walkers is None:
        walkers = max(DEFAULT_WALKERS, need + need % 2)
    if walkers < need:
        raise ParameterError("walkers", f"{walkers}: the ensemble sampler needs at least 2 per input plus 2 "
                             f"({need} for {ndim} inputs)")
    if steps < MIN_STEPS:
        raise ParameterError("steps", f"{steps}: keep at least {MIN_STEPS} steps (an autocorrelation time needs them)")
    if burn < 0:
        raise ParameterError("burn", f"{burn}: must be >= 0")
    return walkers


def least_squares_fit(model: FrequencyModel, inputs, measured_hz, sigma_hz) -> LeastSquaresFit:
    """The regularised least-squares estimate of the inputs (see the module's docstring).

    Parameters
    ----------
    model : FrequencyModel
        Returns the model's frequencies (Hz) of a point (file units).
    inputs : list of CalibrationInput
    measured_hz, sigma_hz : ndarray
        Measured frequencies and their standard deviations, Hz.

    Returns
    -------
    LeastSquaresFit
    """
    from scipy.optimize import least_squares

    m = measured_hz.size
    x0 = np.array([i.nominal for i in inputs])
    s = np.array([i.prior_sd for i in inputs])
    lo = np.array([(i.low - i.nominal) for i in inputs]) / s
    hi = np.array([(i.high - i.nominal) for i in inputs]) / s
    start = model.evaluations

    def residuals(u):
        f = model(x0 + u * s)[:m]
        if not np.all(np.isfinite(f)):
            raise FetorsionError(f"calibrate: the model has fewer than {m} elastic modes at {x0 + u * s}")
        return np.concatenate([(f - measured_hz) / sigma_hz, u])

    res = least_squares(residuals, np.clip(np.zeros_like(x0), lo, hi), bounds=(lo, hi), method="trf",
                        diff_step=DIFF_STEP, x_scale=1.0)
    u = res.x
    J = res.jac[:m]  # d((f - f~)/sigma)/du
    cov = np.linalg.inv(J.T @ J + np.eye(len(u)))
    x = x0 + u * s
    f = model(x)
    span = np.array([i.high - i.low for i in inputs])
    at_bound = [bool(min(abs(xi - i.low), abs(xi - i.high)) < 1e-6 * w) for xi, i, w in zip(x, inputs, span)]
    return LeastSquaresFit(x, np.sqrt(np.diag(cov)) * s, at_bound, f, J * sigma_hz[:, None],
                           float(np.sum(((f[:m] - measured_hz) / sigma_hz) ** 2)), model.evaluations - start)


def sample_posterior(model: FrequencyModel, inputs, measured_hz, sigma_hz, start: LeastSquaresFit, walkers: int,
                     steps: int, burn: int, seed: int) -> Posterior:
    """Sample the posterior of the inputs with ``emcee`` (see the module's docstring).

    Parameters
    ----------
    model : FrequencyModel
    inputs : list of CalibrationInput
    measured_hz, sigma_hz : ndarray
        Hz.
    start : LeastSquaresFit
        The walkers start from its Laplace approximation, clipped into the ranges.
    walkers, steps, burn : int
        Ensemble size, steps kept, steps of burn-in discarded.
    seed : int
        Of the start and of the sampler's moves.

    Returns
    -------
    Posterior
    """
    import emcee
    from scipy.special import expit

    m, d = measured_hz.size, len(inputs)
    priors = [i.prior() for i in inputs]
    lo = np.array([i.low for i in inputs])
    hi = np.array([i.high for i in inputs])

    width = hi - lo

    def log_prob(z):
        # The walkers move in z = logit of each input's place in its range: unbounded, so that no
        # proposal falls outside a range; the prior density carries the Jacobian dx/dz.
        t = expit(z)
        x = lo + width * t
        if np.any(t <= 0) or np.any(t >= 1):
            return -np.inf, np.full(model.modes, np.nan)
        lp = sum(p.logpdf(xi) for p, xi in zip(priors, x)) + float(np.sum(np.log(width * t * (1 - t))))
        if not np.isfinite(lp):
            return -np.inf, np.full(model.modes, np.nan)
        try:
            f = model(x)
        except FetorsionError:  # a variant that breaks a rule of the description: outside the prior
            return -np.inf, np.full(model.modes, np.nan)
        return lp - 0.5 * float(np.sum(((f[:m] - measured_hz) / sigma_hz) ** 2)), f

    rng = np.random.default_rng(seed)
    # The Laplace approximation truncated to the ranges, less a sliver of each (a triangular prior
    # vanishes at its bounds): narrow where the data identify an input, the prior's width where not.
    eps = 1e-6 * (hi - lo)
    p0 = np.empty((walkers, d))
    for i in range(d):
        draws = np.empty(0)
        while draws.size < walkers:
            z = start.values[i] + rng.standard_normal(4 * walkers) * start.sd[i]
            draws = np.concatenate([draws, z[(z > lo[i] + eps[i]) & (z < hi[i] - eps[i])]])
        p0[:, i] = draws[:walkers]
    # Differential-evolution moves [TerBraak] in the logit coordinates: on the Renault's 15 inputs
    # and one frequency, acceptance 0.22 and autocorrelation time 45 steps, where emcee's default
    # stretch move [Goodman] in the bounded coordinates gave 0.11 and 113 (measured; DE moves in
    # the bounded coordinates 0.07 and 89: proposals fell outside the ranges).
    moves = [(emcee.moves.DEMove(), DE_SHARE), (emcee.moves.DESnookerMove(), 1.0 - DE_SHARE)]
    sampler = emcee.EnsembleSampler(walkers, d, log_prob, moves=moves, blobs_dtype=[("f", float, (model.modes,))])
    sampler.random_state = np.random.RandomState(seed).get_state()
    t0 = (p0 - lo) / width
    sampler.run_mcmc(np.log(t0 / (1 - t0)), burn + steps, progress=False)
    chain = lo + width * expit(sampler.get_chain(discard=burn, flat=True))
    blobs = sampler.get_blobs(discard=burn, flat=True)["f"]
    tau = sampler.get_autocorr_time(discard=burn, quiet=True, tol=0)
    return Posterior(chain, np.asarray(blobs, float), float(np.mean(sampler.acceptance_fraction)),
                     float(np.nanmax(tau)), walkers, steps, burn, seed)


def run_calibration(crank: Crank, measured_hz, sigma_hz=None, sigma_percent: float = DEFAULT_SIGMA_PERCENT,
                    inputs=None, model: str = LUMPED17, method: str = "lsq", stiffness: str = DEFAULT_WEB_METHOD,
                    walkers: int | None = None, steps: int = DEFAULT_STEPS, burn: int = DEFAULT_BURN,
                    seed: int = 0, write_all: bool = False) -> CalibrationResult:
    """Fit a description's ``[uncertainty]`` inputs to measured natural frequencies.

    Parameters
    ----------
    crank : Crank
        A description with an ``[uncertainty]`` table (ranges in file units).
    measured_hz : sequence of float
        Measured natural frequencies, Hz: the lowest elastic torsional modes of the free-free
        crank, ascending (matched by order to the model's).
    sigma_hz : float or sequence of float, optional
        Standard deviation of each measured frequency (measurement and model error), Hz.
    sigma_percent : float
        Without ``sigma_hz``: the standard deviation in % of each frequency
        (default :data:`DEFAULT_SIGMA_PERCENT`).
    inputs : sequence of str, optional
        ``[uncertainty]`` entries to calibrate (default all); the others stay as in the file.
    model : str
        The lumped chain, ``lumped5`` ... ``lumped21`` (default the 17-DOF chain).
    method : {"lsq", "bayes", "both"}
        Regularised least squares, the MCMC posterior (it starts from the least-squares
        estimate), or both reported.
    stiffness : str
        Web-stiffness method of the lumped model, one of :data:`CALIBRATION_STIFFNESS` (not the FE ones).
    walkers : int, optional
        Walkers of the ensemble (default 32, at least 2 per input plus 2).
    steps, burn : int
        Steps of each walker kept, and discarded first as burn-in.
    seed : int
        Seed of the walkers' start and moves: the same seed gives the same posterior (the
        identification does not depend on it).
    write_all : bool
        A calibrated description changes every input the least squares moved, not only the
        identified ones.

    Returns
    -------
    CalibrationResult

    Examples
    --------
    >>> import fetorsion
    >>> from fetorsion.studies.calibration import run_calibration
    >>> crank = fetorsion.load("geometry/renault21.toml")
    >>> res = run_calibration(crank, [530.0], inputs=["webs.*.counterweight_radius"])
    >>> bool(res.lsq.values[0] < 72.0)   # a lighter counterweight raises f1 towards 530 Hz
    True
    """
    if method not in METHODS:
        raise ParameterError("method", f"{method}: choose from {', '.join(METHODS)}")
    dof = _partition(model)
    if stiffness not in CALIBRATION_STIFFNESS:
        raise ParameterError("stiffness", f"{stiffness}: choose from {', '.join(CALIBRATION_STIFFNESS)} (an FE web "
                             "method would mesh every one of the calibration's thousands of variants)")
    f_meas, sig = check_measured_hz(measured_hz, sigma_hz, sigma_percent)
    elastic = elastic_modes(crank, dof)
    if f_meas.size > elastic:
        raise ParameterError("measured_hz", f"{f_meas.size} frequencies: {model_label(crank, model, stiffness)} has "
                             f"{elastic} elastic modes")
    priors = ""
    if isinstance(crank, Chain) and not crank.uncertainty:
        priors = (f"no [uncertainty] in the file: every inertia and stiffness within ±{100 * CHAIN_PRIOR_SHARE:g} % "
                  "of its value (the default prior of a chain)")
    chosen = calibration_inputs(crank, inputs)
    if method != "lsq":
        walkers = check_ensemble(len(chosen), walkers, steps, burn)
    t0 = time.perf_counter()
    fm = FrequencyModel(crank, chosen, dof, stiffness, min(elastic, max(PREDICTED_MODES, f_meas.size)))
    nominal = fm([i.nominal for i in chosen])
    out = CalibrationResult(crank.name, str(crank.source), model_label(crank, model, stiffness), method, f_meas, sig,
                            chosen, nominal)
    out.priors = priors
    out.lsq = least_squares_fit(fm, chosen, f_meas, sig)
    out.identification = identification(out.lsq, chosen, sig)
    out.write_all = write_all
    if method != "lsq":
        out.posterior = sample_posterior(fm, chosen, f_meas, sig, out.lsq, walkers, steps, burn, seed)
    if method == "bayes":
        out.lsq = None  # the chains' starting point only: the reported estimate is the posterior's
    out.seconds = time.perf_counter() - t0
    out.evaluations_per_s = fm.rate
    return out


# ---------------------------------------------------------------------------
# The calibrated description: a new file, every change commented


def calibrated_text(result: CalibrationResult, text: str) -> tuple[str, dict[str, float]]:
    """The calibrated description's text and the concrete fields it changes (file units).

    Parameters
    ----------
    result : CalibrationResult
        What to write (:meth:`CalibrationResult.calibrated_values`).
    text : str
        The original description's text.

    Returns
    -------
    (str, dict)
        A header comment listing every change and its source, then the original text with each
        changed line edited and commented; and every concrete field's new value.
    """
    values = result.calibrated_values()
    if not values:
        raise FetorsionError("calibrate: the calibration moves no input from its nominal value (to "
                             f"{WRITTEN_DIGITS} digits); no calibrated description to write")
    note = result.source_note()
    fields = {}
    header = [f"# Calibrated description: {note}.",
              f"# Model {result.model}; sigma {', '.join(f'{s:.3g}' for s in result.sigma_hz)} Hz; "
              "every changed value below is commented with its old value.",
              *([f"# Priors: {result.priors}."] if result.priors else []),
              "# Changed inputs (file units):"]
    by_name = {i.name: i for i in result.inputs}
    for name, x in values.items():
        inp = by_name[name]
        header.append(f"#   {name}: {inp.nominal:g} -> {x:g} ({result.change_note(name)})")
        for path, v in inp.values(x).items():
            fields[path] = float(f"{v:.{WRITTEN_DIGITS}g}")
    body = edit_toml_values(text, fields, note)
    return "\n".join(header) + "\n#\n" + body, fields


def write_calibrated(result: CalibrationResult, out, force: bool = False):
    """Write the calibrated description as a new file beside the original, never over it.

    Parameters
    ----------
    result : CalibrationResult
        The calibration; its ``source`` is the original file.
    out : str or Path
        The new ``.toml`` file: not the original, and not an existing file unless ``force``.
    force : bool
        Replace an existing ``out`` (never the original).

    Returns
    -------
    dict
        Every concrete field changed and its value (file units), as read back from ``out``.
    """
    import tomllib
    from pathlib import Path

    from ..description.files import parse_description
    from ..io import write_text_atomic

    src, out = Path(result.source), Path(out)
    check_calibrated_path(out, src, force)
    text, fields = calibrated_text(result, src.read_text(encoding="utf-8"))
    # Read back before writing: the new description must parse, by every rule, to the values written.
    raw = tomllib.loads(text)
    parse_description(raw, source=str(out))
    back = {p: float(v) for p in fields for _, v in resolve_field(raw, p)}
    if back != fields:
        raise FetorsionError(f"calibrate: the calibrated description would read back other values: {back}")
    write_text_atomic(out, text)
    return back


def check_calibrated_path(out, source, force: bool = False) -> None:
    """Refuse ``out`` as the calibrated description's file: the original (``source``), an
    existing file (unless ``force``), a folder, or a name without ``.toml``."""
    import os
    from pathlib import Path

    out, source = Path(out), Path(source)
    if out.suffix.lower() != ".toml":
        raise ParameterError("out", f"{out}: the calibrated description is a .toml file")
    if out.is_dir():
        raise ParameterError("out", f"{out}: is a folder; give a new file name")
    if out.exists() and source.exists() and os.path.samefile(out, source):
        raise ParameterError("out", f"{out}: is the original description; the calibrated one is written as a new file")
    if out.exists() and not force:
        raise ParameterError("out", f"{out}: exists; give a new file name (or force to replace it)")
