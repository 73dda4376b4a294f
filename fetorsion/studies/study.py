"""Uncertainty and sensitivity studies: sample the inputs, run the model on each sample (on a
Dask cluster, :mod:`fetorsion.studies.runner`), and summarise the outputs.

Every output gets its percentile band (5, 50, 95 %) over the runs that succeeded; a Sobol'
study gives first- and total-order indices, a Morris study μ* and σ, each with SALib's
bootstrap confidence interval (95 %). The statistics are SALib's, not re-derived here.
"""

from __future__ import annotations

import csv
import json
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Callable, Literal

import numpy as np

from ..description.defaults import DEFAULT_STUDY_SAMPLES, LUMPED17
from ..errors import FetorsionError
from ..results import from_fields
from ..io import atomic_folder, check_report_folder, save_figure_atomic, write_text_atomic
from .runner import RunSummary, SampleStore, open_store, run_samples
from .sampling import MORRIS_LEVELS, StudyInput, salib_problem, sample_matrix, samples_of

if TYPE_CHECKING:
    from distributed import Client

    from ..description.model import Crank
    from .runner import ClusterOnDemand, SampleRecord

PERCENTILES = (5.0, 50.0, 95.0)
CONF_LEVEL = 0.95
#: Bootstrap resamples behind each confidence interval (SALib's default is 100; 1000 makes
#: the interval's own sampling error a few per cent of its width).
RESAMPLES = 1000


@dataclass
class StudyResult:
    """A finished study.

    ``X``: one row per run, the inputs' sampled values (file units, a group's first member);
    ``Y``: each output's value per run (NaN where the run failed); ``errors``: each failed run's
    ``index``, ``values`` and ``error``; ``bands``: per output ``p5``, ``p50``, ``p95``,
    ``mean``, ``std``, ``n``; ``indices``: per output, SALib's indices with their confidence
    half-widths (``S1``, ``S1_conf``, ``ST``, ``ST_conf``, or ``mu_star``, ``mu_star_conf``,
    ``sigma``), or ``{"not_computed": why}``.
    """

    name: str
    method: str
    model: str
    samples: int
    seed: int
    inputs: list[StudyInput]
    held: list[str]
    X: np.ndarray
    Y: dict[str, np.ndarray]
    errors: list[dict[str, int | str | dict[str, float]]]
    bands: dict[str, dict[str, float]]
    indices: dict[str, dict[str, list[float] | str]]
    measured_hz: float | None
    summary: RunSummary
    values: list[dict[str, float]] = field(default_factory=list, repr=False)
    #: The measured value's percentile as a results.json written before it kept the runs' outputs
    #: said it (:meth:`from_dict`); None when ``Y`` has them.
    percentile_read: float | None = field(default=None, repr=False)

    @property
    def input_names(self) -> list[str]:
        return [i.name for i in self.inputs]

    def measured_percentile(self, output: str = "f1") -> float | None:
        """Where the measured first torsional frequency falls: the share (%) of runs below it."""
        y = self.Y.get(output)
        if y is None and output == "f1" and self.percentile_read is not None:  # read back without the runs
            return self.percentile_read
        if self.measured_hz is None or y is None or not np.isfinite(y).any():
            return None
        y = y[np.isfinite(y)]
        return float(100.0 * np.mean(y < self.measured_hz))

    def to_dict(self) -> dict:
        """Every figure of the result as plain JSON-ready numbers, lists and strings (SI, or the unit in its key)."""
        return {"name": self.name, "method": self.method, "model": self.model, "samples": self.samples,
                "seed": self.seed, "runs": len(self.X), "failed": len(self.errors),
                "inputs": [{"name": i.name, "members": [list(m) for m in i.members], "distribution": i.distribution,
                            "nominal": i.nominal, "sd": i.sd} for i in self.inputs],
                "held_at_nominal": self.held, "bands": self.bands, "indices": self.indices,
                "confidence_level": CONF_LEVEL, "measured_hz": self.measured_hz,
                "measured_percentile": self.measured_percentile(), "errors": self.errors[:100],
                "computed": self.summary.computed, "stored_before": self.summary.stored_before,
                "wall_s": self.summary.wall_s, "frequency_unit": "Hz", "severity_unit": "deg",
                # the runs' outputs (the histogram's, the percentile's); none for a study read back without
                # them. Not their inputs: nothing the report draws reads them, and a Sobol' design's were 6 MB
                # of a run's results.json (the sample store keeps every run)
                **({} if not self.Y else {"Y": {
                    k: [None if math.isnan(v) else v for v in y.tolist()] for k, y in self.Y.items()}})}

    @classmethod
    def from_dict(cls, d: Mapping[str, object]) -> "StudyResult":
        """The study back from its :meth:`to_dict`: its runs' count with NaN inputs (``X`` is not
        kept) and their outputs. One written before the outputs were kept (no ``Y``) comes back
        without them (its histogram cannot be drawn again) and with the measured percentile it stated."""
        inputs = [from_fields(StudyInput, i) for i in d["inputs"]]
        X = np.array(d["X"], dtype=float) if "X" in d else np.full((d["runs"], len(inputs)), np.nan)
        Y = {k: np.array(y, dtype=float) for k, y in d.get("Y", {}).items()}
        summary = RunSummary(total=d["runs"], stored_before=d["stored_before"], computed=d["computed"],
                             failed=d["failed"], wall_s=d["wall_s"])
        return from_fields(cls, d, {"held": "held_at_nominal"}, inputs=inputs, X=X, Y=Y, summary=summary,
                           percentile_read=None if "Y" in d else d.get("measured_percentile"))

    def table(self) -> str:
        """The result as plain text: the table the command line prints."""
        lines = [f"{self.name}: {self.method} study, {len(self.X)} runs of {self.model} "
                 f"({self.summary.computed} computed, {self.summary.stored_before} stored before, "
                 f"{len(self.errors)} failed, {self.summary.wall_s:.1f} s)"]
        if self.held:
            lines.append(f"held at nominal (not in this model): {', '.join(self.held)}")
        shaped = [f"{i.name} {i.distribution}" + (f" (sd {i.sd:g})" if i.sd else "") for i in self.inputs
                  if i.distribution != "uniform"]
        lines.append("inputs uniform over their ranges" + (f", except {', '.join(shaped)}" if shaped else "")
                     + (" (the design spans the ranges)" if shaped and self.method in ("grid", "morris") else ""))
        head = f"{'output':<10} {'p5':>10} {'p50':>10} {'p95':>10} {'mean':>10} {'std':>10} {'runs':>6}"
        lines += ["", head, "-" * len(head)]
        for out, b in self.bands.items():
            if b["n"]:
                lines.append(f"{out:<10} {b['p5']:10.2f} {b['p50']:10.2f} {b['p95']:10.2f} {b['mean']:10.2f} "
                             f"{b['std']:10.2f} {b['n']:6d}")
        pct = self.measured_percentile()
        if pct is not None:
            b = self.bands["f1"]
            where = "inside" if b["p5"] <= self.measured_hz <= b["p95"] else "OUTSIDE"
            lines.append(f"measured f1 {self.measured_hz:g} Hz: {pct:.1f} % of the runs lie below it "
                         f"({where} the 5-95 % band)")
        for out, idx in self.indices.items():
            lines.append("")
            if "not_computed" in idx:
                lines.append(f"{out}: indices not computed: {idx['not_computed']}")
                continue
            if self.method == "sobol":
                lines.append(f"{out}: Sobol' indices (± {100 * CONF_LEVEL:g} % confidence half-width)")
                lines.append(f"{'input':<32} {'first order S1':>18} {'total ST':>18}")
                order = np.argsort(idx["ST"])[::-1]
                lines += [f"{self.input_names[j]:<32} {idx['S1'][j]:9.3f} ± {idx['S1_conf'][j]:6.3f} "
                          f"{idx['ST'][j]:9.3f} ± {idx['ST_conf'][j]:6.3f}" for j in order]
            else:
                lines.append(f"{out}: Morris elementary effects (μ* ± {100 * CONF_LEVEL:g} % half-width, σ)")
                order = np.argsort(idx["mu_star"])[::-1]
                lines += [f"{self.input_names[j]:<32} {idx['mu_star'][j]:10.3g} ± {idx['mu_star_conf'][j]:8.3g} "
                          f"{idx['sigma'][j]:10.3g}" for j in order]
        if self.errors:
            lines += ["", f"{len(self.errors)} failed runs; first: run {self.errors[0]['index']}: {self.errors[0]['error']}"]
        return "\n".join(lines)

    def plot(self, ax=None, kind: str | None = None, output: str | None = None):
        """``kind="histogram"`` (default for Monte Carlo and grid): the output's distribution with
        its 5-95 % band and the measured value; ``"indices"`` (default for Sobol' and Morris):
        the index bar chart with confidence intervals."""
        import matplotlib.pyplot as plt

        output = output or next(iter(self.Y or self.bands))
        idx = self.indices.get(output, {})
        if kind is None:
            kind = "indices" if idx and "not_computed" not in idx else "histogram"
        if kind == "histogram" and output not in self.Y:
            raise FetorsionError(f"{self.name}: the runs' {output} are not kept (a study read back from a "
                                 "results.json written before they were): no histogram")
        if ax is None:
            _, ax = plt.subplots(figsize=(8, 4.5 if kind == "histogram" else 0.3 * len(self.inputs) + 1.8))
        if kind == "indices":
            _index_bars(ax, self, output, idx)
        else:
            _histogram(ax, self, output)
        ax.figure.tight_layout()
        return ax


def _histogram(ax, res: StudyResult, output: str) -> None:
    y = res.Y[output][np.isfinite(res.Y[output])]
    unit = "deg" if output == "severity" else "Hz"
    ax.hist(y, bins=min(60, max(10, int(np.sqrt(len(y))))), color="C0", alpha=0.75)
    b = res.bands[output]
    if b["n"]:
        ax.axvspan(b["p5"], b["p95"], color="C0", alpha=0.12, label=f"5-95 %: {b['p5']:.0f}-{b['p95']:.0f} {unit}")
    if res.measured_hz is not None and output == "f1":
        pct = res.measured_percentile()
        ax.axvline(res.measured_hz, color="crimson", lw=1.5, ls="--",
                   label=f"measured {res.measured_hz:g} Hz ({pct:.0f} % below)")
    ax.set_xlabel(f"{output} [{unit}]")
    ax.set_ylabel("runs")
    ax.set_title(f"{res.name}\n{output}: {res.method}, {len(y)} runs of {res.model}", fontsize=10, wrap=True)
    ax.legend(fontsize=7)


def _index_bars(ax, res: StudyResult, output: str, idx: dict) -> None:
    names = res.input_names
    if res.method == "sobol":
        order = np.argsort(idx["ST"])
        pos = np.arange(len(order))
        ax.barh(pos + 0.2, np.array(idx["ST"])[order], 0.4, xerr=np.array(idx["ST_conf"])[order], label="total ST")
        ax.barh(pos - 0.2, np.array(idx["S1"])[order], 0.4, xerr=np.array(idx["S1_conf"])[order],
                label="first order S1")
        ax.set_xlabel(f"Sobol' index of {output} (bars: {100 * CONF_LEVEL:g} % confidence)")
    else:
        order = np.argsort(idx["mu_star"])
        pos = np.arange(len(order))
        ax.barh(pos, np.array(idx["mu_star"])[order], 0.6, xerr=np.array(idx["mu_star_conf"])[order], label="μ*")
        ax.set_xlabel(f"Morris μ* of {output} (bars: {100 * CONF_LEVEL:g} % confidence)")
    ax.set_yticks(pos, [names[j] for j in order], fontsize=7)
    ax.axvline(0, color="k", lw=0.5)
    ax.set_title(f"{res.name}\n{res.method} indices of {output} ({res.model}, {len(res.X)} runs)", fontsize=10, wrap=True)
    ax.legend(fontsize=7)


def percentile_bands(Y: dict[str, np.ndarray]) -> dict:
    """Per output: the 5, 50 and 95 % percentiles, mean, std and count of the finite runs."""
    out = {}
    for name, y in Y.items():
        y = y[np.isfinite(y)]
        if len(y) == 0:
            out[name] = {"n": 0}
            continue
        p5, p50, p95 = np.percentile(y, PERCENTILES)
        out[name] = {"p5": float(p5), "p50": float(p50), "p95": float(p95), "mean": float(y.mean()),
                     "std": float(y.std(ddof=1)) if len(y) > 1 else 0.0, "n": int(len(y))}
    return out


def sensitivity_indices(method: str, inputs: list[StudyInput], X: np.ndarray, y: np.ndarray, seed: int) -> dict:
    """SALib's indices of one output, with confidence half-widths at :data:`CONF_LEVEL`."""
    if method not in ("sobol", "morris"):
        return {"not_computed": f"the {method} design gives bands, not indices (a sobol or morris study gives them)"}
    if not np.isfinite(y).all():
        return {"not_computed": f"{int((~np.isfinite(y)).sum())} runs failed; SALib's {method} estimators need "
                                "every run of the design"}
    problem = salib_problem(inputs, distributions=method == "sobol")
    # SALib seeds its bootstrap only for a truthy seed ("if seed:"): seed 0 gave other confidence
    # half-widths on every run (0.079 and 0.077 for the same index), so it is shifted by one.
    seed = seed + 1
    if method == "sobol":
        from SALib.analyze import sobol

        s = sobol.analyze(problem, y, calc_second_order=False, conf_level=CONF_LEVEL, num_resamples=RESAMPLES,
                          seed=seed)
        keys = ("S1", "S1_conf", "ST", "ST_conf")
    else:
        from SALib.analyze import morris

        s = morris.analyze(problem, X, y, conf_level=CONF_LEVEL, num_levels=MORRIS_LEVELS, num_resamples=RESAMPLES,
                           seed=seed)
        keys = ("mu", "mu_star", "mu_star_conf", "sigma")
    return {k: [float(v) for v in np.asarray(s[k])] for k in keys}


def run_study(model: Callable[[dict[str, float]], dict[str, float | str]], inputs: list[StudyInput], method: str,
              samples: int, *, seed: int = 0, client: Client | ClusterOnDemand | None = None,
              store: SampleStore | None = None, batch_size: int | None = None, name: str = "",
              measured_hz: float | None = None, held: Sequence[str] = (), retry_failed: bool = False,
              on_record: Callable[[str, SampleRecord], None] | None = None, progress: bool = True) -> StudyResult:
    """Sample ``inputs``, run ``model`` on every sample and summarise.

    Parameters
    ----------
    model : callable with ``key``
        One sample (``{path: value}``, file units) in, a dict of outputs out (see
        :mod:`fetorsion.studies.models`).
    inputs : list of StudyInput
        The sampled inputs, uniform over their ranges.
    method : str
        ``sobol`` (``samples`` base samples, a power of 2), ``morris`` (trajectories),
        ``montecarlo`` (runs) or ``grid`` (levels per input).
    samples : int
        See ``method``.
    seed : int
        Seed of the sampler and of the bootstrap.
    client : distributed.Client or ClusterOnDemand, optional
        Where the runs go (see :func:`fetorsion.studies.runner.open_client`); None: here, serially.
    store : SampleStore, optional
        Stored results (default :func:`fetorsion.studies.runner.default_store`).
    batch_size : int, optional
        Samples per task (default :func:`fetorsion.studies.runner.auto_batch`).
    measured_hz : float, optional
        The measured f1, Hz: its place in the f1 distribution is reported.
    held : sequence of str
        Inputs of the description held at nominal (said in the table).
    """
    X = sample_matrix(method, inputs, samples, seed)
    values = samples_of(inputs, X)
    store = store or open_store()
    records, summary = run_samples(model, values, store, client, batch_size, retry_failed=retry_failed,
                                   label=f"{name or 'study'} ({method})", on_record=on_record, progress=progress)
    outputs = list(getattr(model, "outputs", ())) or _output_names(records)
    Y = {o: np.array([r.get("outputs", {}).get(o, math.nan) for r in records], dtype=float) for o in outputs}
    errors = [{"index": i, "values": values[i], "error": r["error"]} for i, r in enumerate(records) if "error" in r]
    indices = {o: sensitivity_indices(method, inputs, X, Y[o], seed) for o in outputs} \
        if method in ("sobol", "morris") else {}
    return StudyResult(name, method, getattr(model, "label", model.key.split("/")[0]), samples, seed, list(inputs),
                       list(held), X, Y, errors, percentile_bands(Y), indices, measured_hz, summary, values)


def run_crank_study(crank: Crank, method: str = "montecarlo", samples: int | None = None, model: str = LUMPED17,
                    outputs: Sequence[str] = ("f1",), inputs: Sequence[str] | None = None, *, seed: int = 0,
                    stiffness: str | None = None, mesh_size: float | None = None, scheduler: str | None = None,
                    workers: int | None = None, client: Client | Literal[False] | None = None,
                    store: SampleStore | None = None, **kwargs) -> StudyResult:
    """A study of a crank's ``[uncertainty]`` inputs: the composition ``fetorsion study`` runs.

    Parameters
    ----------
    crank : Crank
        A description with an ``[uncertainty]`` table.
    method, samples, seed
        See :func:`run_study`; ``samples`` defaults to the method's
        :data:`~fetorsion.description.defaults.DEFAULT_STUDY_SAMPLES`.
    model : str
        ``lumpedN`` (N = 5, 6, 17, 19, 21) or ``fe`` (3D FE without fillets and drillings at
        ``mesh_size``, m; their inputs are then held at nominal).
    stiffness : str, optional
        Web-stiffness method of a lumped model; default :data:`~fetorsion.description.defaults.DEFAULT_WEB_METHOD`.
    mesh_size : float, optional
        Global FE element size of the ``fe`` model, m.
    outputs : sequence of str
        ``f1``, ``f2``, ``f3``, ``severity`` (lumped) or ``f1``, ``f2`` (fe); Hz, degrees.
    inputs : sequence of str, optional
        Names of ``[uncertainty]`` entries to sample (default all).
    scheduler, workers
        An existing Dask scheduler's address, or the local cluster's worker count (started
        only if some sample is not stored). ``client`` overrides both (None of the three:
        a local cluster).
    client : distributed.Client or False, optional
        A Dask client to use; ``False`` runs the samples in this process.
    store : SampleStore, optional
        Where each sample's result is kept (default the user's sample store).
    **kwargs
        To :func:`run_study` (``batch_size``, ``retry_failed``, ``on_record``, ``progress``).

    Examples
    --------
    >>> import fetorsion
    >>> crank = fetorsion.load("geometry/peugeot_glx.toml")
    >>> res = fetorsion.run_crank_study(crank, "montecarlo", 20, client=False, progress=False)
    >>> res.bands["f1"]["p5"] < res.bands["f1"]["p95"]
    True
    """
    from .runner import ClusterOnDemand
    from .models import FE_LEFT_OUT, make_model
    from .sampling import study_inputs

    if not crank.uncertainty:
        raise FetorsionError(f"{crank.source or crank.name}: the description has no [uncertainty] table")
    options = {k: v for k, v in (("stiffness", stiffness), ("mesh_size", mesh_size)) if v is not None}
    m = make_model(crank, model, tuple(outputs), **options)
    chosen, held = study_inputs(crank, inputs, FE_LEFT_OUT if model == "fe" else ())
    samples = DEFAULT_STUDY_SAMPLES[method] if samples is None else samples
    measured = getattr(crank, "measured_f1_hz", None)
    common = dict(seed=seed, store=store, name=crank.name, measured_hz=float(measured) if measured else None,
                  held=held, **kwargs)
    if client is not None:  # False: here, serially
        return run_study(m, chosen, method, samples, client=client or None, **common)
    with ClusterOnDemand(scheduler, workers) as on_demand:
        return run_study(m, chosen, method, samples, client=on_demand, **common)


def _output_names(records: list[dict]) -> list[str]:
    for r in records:
        if "outputs" in r:
            return list(r["outputs"])
    return []


def write_study_folder(res: StudyResult, out: str | Path, force: bool = False,
                       inputs: Sequence[str | Path] = ()) -> Path:
    """The study's report folder, written atomically: ``samples.csv`` (every run's inputs,
    outputs and error), ``study.json``, ``study.txt``, the histogram of each output and the
    index chart of each output that has indices."""
    import matplotlib

    matplotlib.use("Agg")
    out = Path(out)
    check_report_folder(out, "out", force=force, inputs=inputs)
    with atomic_folder(out) as work:
        write_samples_csv(res, work / "samples.csv")
        write_text_atomic(work / "study.json", json.dumps(res.to_dict(), indent=1) + "\n")
        write_text_atomic(work / "study.txt", res.table() + "\n")
        for o in res.Y:
            if res.bands[o]["n"]:
                save_figure_atomic(res.plot(kind="histogram", output=o).figure, work / f"histogram_{o}.png",
                                   close=True, dpi=120)
            if o in res.indices and "not_computed" not in res.indices[o]:
                save_figure_atomic(res.plot(kind="indices", output=o).figure, work / f"indices_{o}.png",
                                   close=True, dpi=120)
    return out


def write_samples_csv(res: StudyResult, path) -> None:
    """One row per run: run number, every input field (file units), every output, the error."""
    paths = list(dict.fromkeys(p for v in res.values for p in v))
    errors = {e["index"]: e["error"] for e in res.errors}
    with open(path, "w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow(["run", *paths, *res.Y, "error"])
        for i, v in enumerate(res.values):
            w.writerow([i, *(repr(v.get(p, math.nan)) for p in paths),
                        *(repr(float(res.Y[o][i])) for o in res.Y), errors.get(i, "")])
