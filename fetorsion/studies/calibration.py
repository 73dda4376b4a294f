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

Here: the inputs, the model and the results; the fit is :mod:`.calibration_fit`
(:func:`~fetorsion.studies.calibration_fit.run_calibration`), the file written :mod:`.calibrated`.
"""

from __future__ import annotations

import datetime
import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..description.model import Crank
from ..lumped_model.lumped import PARTITIONS, lumped
from ..webs.methods import WEB_METHODS
from ..description.edit import with_values

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
