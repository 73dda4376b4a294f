"""The calibration itself: the ``[uncertainty]`` inputs of a description (a chain file's default
priors where it states none), the measured frequencies and the ensemble checked, the regularised
least-squares estimate and what it identifies, the posterior sampled, all in
:func:`run_calibration`. The method, its inputs, model and results: :mod:`.calibration`."""

from __future__ import annotations

import math
import time
from collections.abc import Sequence

import numpy as np

from ..description.defaults import DEFAULT_WEB_METHOD, LUMPED17
from ..description.edit import field_values
from ..description.model import Crank
from ..description.chain_model import Chain, Network
from ..errors import FetorsionError, ParameterError
from .calibration import (CALIBRATION_MODELS, CALIBRATION_STIFFNESS, CHAIN_PRIOR_SHARE, DE_SHARE, DEFAULT_BURN,
                          DEFAULT_SIGMA_PERCENT, DEFAULT_STEPS, DEFAULT_WALKERS, DIFF_STEP, IDENTIFIED_RATIO,
                          METHODS, MIN_STEPS, PREDICTED_MODES, CalibrationInput, CalibrationResult,
                          FrequencyModel, Identification, LeastSquaresFit, Posterior)
from .sampling import study_inputs


def default_chain_priors(chain: Chain) -> Chain:
    """``chain`` with an ``[uncertainty]`` entry for every inertia and stiffness, each within
    :data:`~fetorsion.studies.calibration.CHAIN_PRIOR_SHARE` of its value, where the file states
    none (a chain's inputs are its inertias and stiffnesses; a crank description's are its
    dimensions, which it must name)."""
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


def calibration_inputs(crank: Crank | Chain | Network, names: Sequence[str] | None = None) -> list[CalibrationInput]:
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


def identification(fit: LeastSquaresFit, inputs, sigma_hz) -> Identification:
    """The deterministic identification of a least-squares fit of ``inputs`` (see
    :class:`~fetorsion.studies.calibration.Identification`): each input's Laplace sd over its
    prior's is the fit's own ``sd`` over the prior sd; the combinations are the information's
    eigenvectors."""
    J = fit.sensitivity_hz / np.asarray(sigma_hz, float)[:, None]  # d(residual)/du at the estimate
    sd_ratio = fit.sd / np.array([i.prior_sd for i in inputs])
    lam, V = np.linalg.eigh(J.T @ J)
    order = np.argsort(lam)[::-1]
    lam, V = lam[order], V[:, order]
    keep = lam > 1.0 / IDENTIFIED_RATIO**2 - 1.0
    V = V[:, keep] * np.sign(V[np.argmax(np.abs(V[:, keep]), axis=0), np.arange(keep.sum())])
    return Identification(sd_ratio, sd_ratio < IDENTIFIED_RATIO, V.T, 1.0 / np.sqrt(1.0 + lam[keep]))


def _partition(model: str) -> int:
    """The DOF of a lumped ``model`` (``lumped17`` -> 17), or one message naming those it may be."""
    if model not in CALIBRATION_MODELS:
        raise ParameterError("model", f"{model}: choose from {', '.join(CALIBRATION_MODELS)} (the 3D FE is too slow "
                             "for the thousands of runs of a calibration)")
    return int(model.removeprefix("lumped"))


def check_measured_hz(measured_hz: Sequence[float], sigma_hz: float | Sequence[float] | None = None,
                      sigma_percent: float = DEFAULT_SIGMA_PERCENT):
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
    """The walkers (default: :data:`~fetorsion.studies.calibration.DEFAULT_WALKERS`, at least 2 per input plus 2) and chain
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
    """The regularised least-squares estimate of the inputs (see :mod:`fetorsion.studies.calibration`).

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


def _log_posterior(model, priors, lo, width, measured_hz, sigma_hz):
    """The sampler's log posterior of every walker's z at once: [(log p, the model's frequencies)]."""
    from scipy.special import expit

    m = measured_hz.size

    def log_prob(z):
        # The walkers move in z = logit of each input's place in its range: unbounded, so that no
        # proposal falls outside a range; the prior density carries the Jacobian dx/dz. One call
        # per step for every walker (emcee's ``vectorize``): each prior's density is evaluated
        # once for all of them (scipy's per-call overhead was 61 of 200 s on the Renault's 15
        # inputs), the model still once per walker.
        t = expit(z)
        x = lo + width * t
        inside = np.all((t > 0) & (t < 1), axis=1)
        with np.errstate(divide="ignore", invalid="ignore"):
            lp = (np.sum([p.logpdf(x[:, i]) for i, p in enumerate(priors)], axis=0)
                  + np.sum(np.log(width * t * (1 - t)), axis=1))
        out = []
        for k in range(len(z)):
            if not (inside[k] and np.isfinite(lp[k])):
                out.append((-np.inf, np.full(model.modes, np.nan)))
                continue
            try:
                f = model(x[k])
            except FetorsionError:  # a variant that breaks a rule of the description: outside the prior
                out.append((-np.inf, np.full(model.modes, np.nan)))
                continue
            out.append((float(lp[k]) - 0.5 * float(np.sum(((f[:m] - measured_hz) / sigma_hz) ** 2)), f))
        return out

    return log_prob


def sample_posterior(model: FrequencyModel, inputs, measured_hz, sigma_hz, start: LeastSquaresFit, walkers: int,
                     steps: int, burn: int, seed: int) -> Posterior:
    """Sample the posterior of the inputs with ``emcee`` (see :mod:`fetorsion.studies.calibration`).

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

    d = len(inputs)
    lo = np.array([i.low for i in inputs])
    hi = np.array([i.high for i in inputs])
    width = hi - lo
    log_prob = _log_posterior(model, [i.prior() for i in inputs], lo, width, measured_hz, sigma_hz)

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
    sampler = emcee.EnsembleSampler(walkers, d, log_prob, moves=moves, blobs_dtype=[("f", float, (model.modes,))],
                                    vectorize=True)
    sampler.random_state = np.random.RandomState(seed).get_state()
    t0 = (p0 - lo) / width
    sampler.run_mcmc(np.log(t0 / (1 - t0)), burn + steps, progress=False)
    chain = lo + width * expit(sampler.get_chain(discard=burn, flat=True))
    blobs = sampler.get_blobs(discard=burn, flat=True)["f"]
    tau = sampler.get_autocorr_time(discard=burn, quiet=True, tol=0)
    return Posterior(chain, np.asarray(blobs, float), float(np.mean(sampler.acceptance_fraction)),
                     float(np.nanmax(tau)), walkers, steps, burn, seed)


def run_calibration(crank: Crank, measured_hz: Sequence[float], sigma_hz: float | Sequence[float] | None = None,
                    sigma_percent: float = DEFAULT_SIGMA_PERCENT, inputs: Sequence[str] | None = None,
                    model: str = LUMPED17, method: str = "lsq", stiffness: str = DEFAULT_WEB_METHOD,
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
        (default :data:`~fetorsion.studies.calibration.DEFAULT_SIGMA_PERCENT`).
    inputs : sequence of str, optional
        ``[uncertainty]`` entries to calibrate (default all); the others stay as in the file.
    model : str
        The lumped chain, ``lumped5`` ... ``lumped21`` (default the 17-DOF chain).
    method : {"lsq", "bayes", "both"}
        Regularised least squares, the MCMC posterior (it starts from the least-squares
        estimate), or both reported.
    stiffness : str
        Web-stiffness method of the lumped model, one of
        :data:`~fetorsion.studies.calibration.CALIBRATION_STIFFNESS` (not the FE ones).
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
    >>> from fetorsion.studies.calibration_fit import run_calibration
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
