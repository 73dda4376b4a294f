"""``fetorsion run``: every analysis of one crank into one report folder, written atomically.

The folder is built under a temporary name beside the target and renamed into place only
when every step has succeeded, so a failed run leaves nothing behind and a reader never
sees a half-written report. An existing target is replaced only when it is an earlier
report (:func:`fetorsion.io.check_report_folder`). Each step is a small function
``step(ctx) -> outcome`` (:mod:`fetorsion.app.steps`) that computes, saves its pictures and
returns its typed outcome (:mod:`fetorsion.report.outcomes`; its numbers also go to
``ctx.results``, the JSON beside the report); :mod:`fetorsion.report.markdown` and
:mod:`fetorsion.report.html` present the outcomes.
"""

from __future__ import annotations

import functools
import json
import time
from dataclasses import dataclass, field
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Callable


from ..description.files import load
from ..design.scfset import SCFSet
from ..measured.dataset import MeasuredData
from ..description.model import Crank
from ..description.chain_model import Chain, Network
from ..errors import FetorsionError, ParameterError
from ..io import atomic_folder, check_report_folder, jsonable, save_figure_atomic, write_text_atomic
from ..studies.runner import machine_workers
from ..description.defaults import DEFAULT_INERTIA_RATIO, DEFAULT_MESH_SIZE, DEFAULT_MODES
from ..report.markdown import report_markdown
from ..report.outcomes import RunOutcome, Skipped
from .tvc import is_propulsion_line, step_tvc
from .background import background_executor, needs_throw_fe, sensitivity_studies, throw_fe_results
from .steps import (fe_path_runs, progress, step_bearings, step_campbell, step_fatigue, step_fe, step_lumped, step_measured,
                    step_sensitivity, step_transient, step_verdict)

if TYPE_CHECKING:
    from ..report.outcomes import (BearingsOutcome, CampbellOutcome, ChainOutcome, FatigueOutcome, FEOutcome,
                                   LumpedOutcome, MeasuredOutcome, SensitivityOutcome, TransientOutcome,
                                   TVCOutcome, VerdictOutcome)

    #: What a step returns: the outcome of the RunOutcome field it fills
    StepOutcome = (LumpedOutcome | ChainOutcome | FEOutcome | BearingsOutcome | CampbellOutcome | SensitivityOutcome
                   | VerdictOutcome | FatigueOutcome | MeasuredOutcome | TransientOutcome | TVCOutcome | Skipped
                   | None)
    #: A step of the run: (what the progress line says, the RunOutcome field its outcome fills, the step)
    RunStep = tuple[str, str, Callable[["RunContext"], StepOutcome]]


#: Figures a run keeps open, drawn later (:meth:`RunContext.save`), before it draws them at once.
FIGURES_HELD = 16


@dataclass(frozen=True)
class RunOptions:
    """Every option a run's steps read, each set by an option of ``fetorsion run``.

    Attributes
    ----------
    mesh_size : float
        FE mesh size, m (``--mesh-size``).
    modes : int
        Free-free FE modes computed (``--modes``).
    support : {"bearings", "free"}
        The crank's support for the in-bearing sections (``--support``).
    source : {"condensed", "lumped17"}
        The model the response, stress, dampers and verdict run on (``--source``).
    inertia_ratio : float
        The recommended damper's ring inertia ratio (``--inertia-ratio``).
    fatigue_method : {"iacs-m53", "fe"} or None
        The method that decides the verdict (``--fatigue-method``; None: the description's).
    runup_rate : float or None
        A chain's or network's run-up rate, rpm/s (``--run-up-rate``; None: a propulsion line's
        stated passage rate, else the default, :func:`fetorsion.app.steps.stated_runup_rate`).
    workers : int or None
        Workers of the background studies' local cluster (``--workers``; None: the machine's
        cores less one).
    html : bool
        Write report.html too (``--no-html`` clears it).
    measured : dict or None
        Measured files read and checked (``--measured``; ``fetorsion.cli.measured.read_measured``).
    station : str or None
        Where the measured order cuts were taken (``--station``).
    no_fe : bool
        The run leaves out the FE steps (``--no-fe``, or a chain file).
    fe_path : bool
        The crank's verdict computes the ``fe`` fatigue path beside the deciding method
        (``--no-fe-path`` clears it, as the design loop's confirming runs do: they read the
        deciding method alone); kept whenever ``fe`` decides.
    """

    mesh_size: float = DEFAULT_MESH_SIZE
    modes: int = DEFAULT_MODES
    support: str = "bearings"
    source: str = "condensed"
    inertia_ratio: float = DEFAULT_INERTIA_RATIO
    fatigue_method: str | None = None
    runup_rate: float | None = None
    workers: int | None = None
    html: bool = True
    measured: MeasuredData | None = None
    station: str | None = None
    no_fe: bool = False
    fe_path: bool = True

    @classmethod
    def of(cls, options) -> "RunOptions":
        """``options`` as RunOptions: already one, a dict of its fields (an unknown key refused
        by name), or None (the defaults)."""
        import dataclasses

        if isinstance(options, cls):
            return options
        options = dict(options or {})
        unknown = set(options) - {f.name for f in dataclasses.fields(cls)}
        if unknown:
            raise FetorsionError(f"run: unknown option(s) {', '.join(sorted(unknown))}")
        return cls(**{k: v for k, v in options.items() if v is not None})  # None: the field's default


@dataclass
class RunContext:
    """What the steps share: the crank, options, the working folder, and the run's outcome so
    far (``outcome``: each step's typed result, which later steps build on); ``results`` is the
    JSON written beside the report.
    """

    crank: Crank
    folder: Path
    options: RunOptions
    outcome: RunOutcome
    results: dict = field(default_factory=dict)
    #: The network whose condensed crank part ``crank`` is (``[[chain.cranks]] dof = "condensed"``):
    #: the engine model's response, fatigue and verdict are then the crank's in that driveline.
    network: Network | None = None
    #: What several steps derive from the crank, built once by the first that needs it: the
    #: crank's parts by web method, the forced response's setup, the fillets.
    built: dict = field(default_factory=dict)
    #: Work whose outcome no later step reads (the mode images and the figures), kept for the
    #: moment the run waits on its background studies: it then takes the core the waiting
    #: leaves idle.
    deferred: list = field(default_factory=list)

    def run_deferred(self) -> None:
        """Do the deferred work now, in the order it was deferred."""
        while self.deferred:
            self.deferred.pop(0)()

    def once(self, key, build):
        """``built[key]``, made by ``build()`` the first time it is asked for."""
        if key not in self.built:
            self.built[key] = build()
        return self.built[key]

    def throw_fe(self):
        """The background throw FE's results, once: the throws' torsion entries go to the web
        stiffness cache (:func:`fetorsion.webs.throwfe.throw_torsion`), the fillet SCFs are kept."""
        pending = self.built.pop("throw_fe", None)
        if pending is not None:
            from ..webs.throwfe import remember_throw_torsion

            torsion, scf = pending.result()
            remember_throw_torsion(torsion)
            self.built["fillet_scf"] = scf
        return self.built.get("fillet_scf")

    def throws_stored(self) -> bool:
        """True when every throw's web stiffness is stored (the lumped ``fe`` column needs no wait
        on the background's throw FE)."""
        from ..webs.throwfe import stored_throw_torsion, throw_of

        return all(stored_throw_torsion(throw_of(self.crank, i)) is not None for i in range(self.crank.throws))

    def parts(self, method: str | None = None):
        """The crank cut into its parts with ``method``'s web stiffness (built once; None: the
        crank's own, :func:`~fetorsion.webs.methods.crank_web_method`). With the
        run's condensed crank built, ``fe-held`` takes its throws' stiffness from it, at the
        run's mesh size, instead of condensing the crank once more."""
        import functools

        from ..lumped_model.parts import build_parts
        from ..webs.methods import crank_web_method
        from ..webs.throwfe import held_throw_stiffnesses, web_equivalent_length_held

        method = method or crank_web_method(self.crank)

        def build():
            if method == "fe" and not self.throws_stored():
                self.throw_fe()  # else the background's stress recovery is left to the verdict's wait
            if method == "fe-held" and "condensed" not in self.built and self.options.no_fe:
                from ..webs.throwfe import held_stiffnesses_stored

                if not held_stiffnesses_stored(self.crank, self.options.mesh_size):
                    # a quick report does not condense the whole crank for one column of a table
                    raise FetorsionError("fe-held: the throws' stiffness inside the whole crank in its bearings "
                                         "needs the crank's FE, which a run without the FE steps does not build")
            web_length = None
            if method == "fe-held" and "condensed" in self.built:
                size = self.options.mesh_size
                k = held_throw_stiffnesses(self.crank, size, condensed=self.built["condensed"])
                web_length = functools.partial(web_equivalent_length_held, stiffnesses=k)
            return build_parts(self.crank, method, web_length=web_length)

        return self.once(("parts", method), build)

    def setup(self):
        """The forced response's setup (built once): the model, its damping, the cylinders' forces
        at every speed and order. The engine model — the condensed crank in its bearings — when
        the run has built it and ``source`` is ``condensed`` (the default), else the lumped
        17-DOF chain; the response, fillet stress, dampers, misfire and verdict derive from it."""
        if self.options.source == "condensed" and "condensed" in self.built:
            return self.engine_setup()
        return self.lumped_setup()

    def engine_setup(self):
        """The condensed crank in its bearings as a response setup (built once); None without it."""
        if "condensed" not in self.built:
            return None
        from ..response.coupled import condensed_setup
        from ..response.driveline import driveline_setup

        labels = [f.label for f in self.fillets()]
        if self.network is not None:
            return self.once("engine_setup", lambda: driveline_setup(self.network, self.built["condensed"],
                                                                     section_labels=labels))
        return self.once("engine_setup", lambda: condensed_setup(self.built["condensed"], "bearings",
                                                                 section_labels=labels))

    def lumped_setup(self):
        """The lumped 17-DOF chain's setup (built once): the fast model, and the engine model's yardstick."""
        from ..response.forced import response_setup

        return self.once("lumped_setup", lambda: response_setup(
            self.crank, parts=None if isinstance(self.crank, (Chain, Network)) else self.parts()))

    def scf(self) -> SCFSet:
        """The fillet SCFs of the crank (shipped, or one static FE of a throw) and its oil bores'
        (shipped, or one static FE of a drilled bar per drilled kind of section), found once."""
        def build():
            from ..design.crank_verdict import verdict_scfs

            progress("  fillet and oil-bore SCFs (static 3D FE, or the stored studies) ...")
            return verdict_scfs(self.crank, self.throw_fe())

        return self.once("scf", build)

    def fillets(self):
        """Every fillet of the crank (built once)."""
        from ..design.stress import fillets_of

        return self.once("fillets", lambda: fillets_of(self.crank, self.parts()))

    def save(self, fig, name: str) -> str:
        """``name``: the figure ``fig``, written into the report folder as deferred work
        (:attr:`deferred`): nothing in the run reads an image back before the report."""
        import matplotlib.pyplot as plt

        if len(plt.get_fignums()) >= FIGURES_HELD:  # pyplot warns past 20 open figures
            self.run_deferred()
        self.deferred.append(functools.partial(save_figure_atomic, fig, self.folder / name, close=True, dpi=120))
        return name


#: Start the sensitivity studies when the run begins, beside the FE steps (False: in their step).
BACKGROUND = True


#: (what the progress line says, the RunOutcome field its outcome fills, the step), in order. The
#: FE steps come first: the condensed crank they build also gives the in-bearing throw stiffness
#: that the lumped models' ``fe-held`` web method reads (one condensation per run, not two).
DEFAULT_STEPS: tuple[tuple[str, str, Callable[[RunContext], object]], ...] = (
    ("mesh, FE system, condensation and free-free modes", "fe", step_fe),
    ("condensed crank in its bearings", "bearings", step_bearings),
    ("lumped models", "lumped", step_lumped),
    ("Campbell diagram and forced response", "campbell", step_campbell),
    ("section torques, dampers and verdict (chain and network files)", "verdict", step_verdict),
    ("the verdict: fatigue by both methods, the recommended damper, misfire", "fatigue", step_fatigue),
    ("the model against measurement", "measured", step_measured),
    ("run-up in the time domain", "transient", step_transient),
    # last: the studies, started in the background when the run began, finish in the cores the
    # steps before leave idle (the verdict's many small solves keep one busy, not two)
    ("sensitivity of f1", "sensitivity", step_sensitivity),
)
# ``fetorsion run --no-fe``: the same report without the mesh and the FE modal analysis.
FAST_STEPS = tuple(s for s in DEFAULT_STEPS if s[2] not in (step_fe, step_bearings))


def run(path: str | Path, out: str | Path, steps: Sequence[RunStep] = DEFAULT_STEPS, options: RunOptions | None = None,
        force: bool = False) -> RunOutcome:
    """Run every step on the crank in ``path`` and write the report folder ``out``.

    Parameters
    ----------
    path : str or Path
        Crank description or chain file (.toml); a chain gets the report without the FE steps.
    out : str or Path
        Report folder. It may be new, empty, or an earlier fetorsion report (replaced only
        once the whole run has succeeded); anything else is refused unless ``force``.
    steps : sequence of (name, field, function)
        The analyses, in order: ``function(ctx)`` returns the outcome of the
        :class:`~fetorsion.report.outcomes.RunOutcome` field ``field``.
    options : RunOptions, optional
        What the steps read (default: every option's default).
    force : bool
        Replace ``out`` even when it is not an earlier report.

    Returns
    -------
    RunOutcome
        Every section's typed outcome, each step's time, and the report folder (``folder``).

    Examples
    --------
    The main job (3D FE, the crank in its bearings, Campbell, the verdict; about a minute on two
    cores for the Renault 21); a chain or network file takes seconds:

    >>> import fetorsion
    >>> outcome = fetorsion.run("examples/networks/friswell_9_6_3.toml", "out/friswell")  # doctest: +SKIP
    >>> sorted(p.name for p in Path("out/friswell").iterdir())[:3]  # doctest: +SKIP
    >>> fetorsion.load_results("out/friswell").lumped.chain.frequencies_hz  # doctest: +SKIP
    """
    import dataclasses

    options = options or RunOptions()
    out = Path(out)
    check_report_folder(out, "out", force=force, inputs=[path])
    crank = load(path)  # every input rule is checked here, before any work or any file
    if isinstance(crank, Crank):
        from ..design.methods import described_method

        described_method(crank, options.fatigue_method)  # the fatigue method against the registry
    network, crank = _crank_in_driveline(crank, path, options, steps)
    features = None
    if getattr(crank, "solid_step", None):  # a CAD crank: its solid against its description, before any work
        from ..solid.geometry import solid_features

        features = solid_features(crank)
    if isinstance(crank, (Chain, Network)):  # no geometry: the report without the mesh and FE sections
        steps = tuple(s for s in steps if s[2] not in (step_fe, step_bearings))
    steps = _with_tvc(tuple(steps), crank if network is None else network)
    with atomic_folder(out) as work, background_executor() as background:
        outcome = RunOutcome(crank, str(path), timings_s={}, folder=str(out),
                             driveline="" if network is None else network.name)
        no_fe = options.no_fe or not any(s[2] is step_fe for s in steps)
        ctx = RunContext(crank, work, dataclasses.replace(options, no_fe=no_fe), outcome, network=network)
        # the description as read (load_results reads it again, wherever the file has gone since)
        ctx.results["description"] = {"path": str(path), "text": Path(path).read_text(encoding="utf-8")}
        if network is not None:
            ctx.results["driveline"] = _driveline_results(network, path)
        if features is not None:
            ctx.results["solid"] = features.to_dict()
        _start_background(ctx, background, steps)
        _run_steps(ctx, steps)
        _write_report(ctx)
    return outcome


#: The propulsion TVC step, added after the verdict for a network with a propeller or shaft sections
#: (other runs keep their steps and timings as they were).
TVC_STEP = ("propulsion TVC: shaft sections, barred ranges, coupling heat", "tvc", step_tvc)


def _with_tvc(steps: tuple, crank) -> tuple:
    """``steps`` with :data:`TVC_STEP` after the verdict's (or last) when ``crank`` is a propulsion line."""
    if not is_propulsion_line(crank) or any(s[2] is step_tvc for s in steps):
        return steps
    at = next((k + 1 for k, s in enumerate(steps) if s[2] is step_verdict), len(steps))
    return steps[:at] + (TVC_STEP,) + steps[at:]


def _crank_in_driveline(crank, path, options: RunOptions, steps) -> tuple[Network | None, Crank | Chain | Network]:
    """(network, its condensed crank with its dampers) of a network on the condensed crank, else (None, ``crank``)."""
    if not (isinstance(crank, Network) and any(c.condensed for c in crank.cranks)):
        return None, crank
    # a driveline on the condensed crank: the crank's own report, its engine model in that driveline
    network = crank
    away = [d.name or d.at for d in network.dampers if d.at != "front"]
    if away:
        raise FetorsionError(f"{path}: damper(s) {', '.join(away)} away from the crank's pulley: the report of a "
                             "network on the condensed crank takes a damper at \"front\" only yet (`fetorsion "
                             "response` takes one on any station)")
    # the network's dampers at the pulley are the crank's in the report (its verdict's "as described")
    crank = network.condensed_crank()
    if options.no_fe or not any(s[2] is step_fe for s in steps):
        raise ParameterError("no_fe", f"{path}: a network on the condensed crank needs the FE steps (its engine "
                                      "model); give the crank dof = 17 for the lumped driveline")
    return network, crank


def _driveline_results(network: Network, path) -> dict:
    """The driveline's entry of ``results.json``: the network, its file, its stations off the crank."""
    return {"network": network.name, "source": str(path),
            "stations": [s for s in network.labels if not any(s in c.labels[1:-1] for c in network.cranks)],
            "note": "the response, fatigue and verdict are the crank's in this driveline "
                    "(the condensed crank in its bearings joined to the network's stations); "
                    "the lumped models, the Campbell diagram and the bearings' coupled "
                    "response are the crank's alone"}


def _start_background(ctx: RunContext, background, steps) -> None:
    """Submit to ``background`` the throws' FE and the f1 studies that the run's steps will read."""
    crank = ctx.crank
    scfs = not ctx.options.no_fe  # without the FE steps the verdict takes no FE SCF
    recovery = fe_path_runs(ctx)
    if BACKGROUND and not isinstance(crank, (Chain, Network)) and needs_throw_fe(crank, scfs, recovery):
        # first in the queue: the bearings step (the lumped `fe` column) and the verdict read it
        ctx.built["throw_fe"] = background.submit(throw_fe_results, crank, scfs, recovery)
    if BACKGROUND and any(s[2] is step_sensitivity for s in steps) and getattr(crank, "uncertainty", ()):
        # the studies run beside the FE steps on one core fewer than the machine has: the FE's
        # assembly and Lanczos iterations keep one core busy, not two (Renault 21 on 2 cores:
        # 97 s with the studies in their step, 93 s beside the FE on 2 workers, 88 s on 1)
        workers = ctx.options.workers or max(1, machine_workers() - 1)
        ctx.built["studies"] = background.submit(sensitivity_studies, crank, workers,
                                                 any(s[2] is step_fe for s in steps), ctx.parts())


def _run_steps(ctx: RunContext, steps) -> None:
    """Run each step in order, its outcome into ``ctx.outcome`` and its time into the outcome's timings."""
    outcome = ctx.outcome
    for name, key, fn in steps:
        progress(f"{name} ...")
        t0 = time.perf_counter()
        setattr(outcome, key, fn(ctx))
        if isinstance(getattr(outcome, key), Skipped):  # the report says why; so does results.json
            ctx.results.setdefault("skipped", {})[key] = getattr(outcome, key).reason
        outcome.timings_s[name] = time.perf_counter() - t0
        progress(f"{name}: done in {outcome.timings_s[name]:.1f} s")


def _write_report(ctx: RunContext) -> None:
    """The deferred pictures, then report.md, report.html (where asked) and results.json in the folder."""
    work = ctx.folder
    ctx.run_deferred()
    ctx.results["timings_s"] = ctx.outcome.timings_s
    write_text_atomic(work / "report.md", report_markdown(ctx.outcome))
    if ctx.options.html:
        from ..report.html import report_html

        write_text_atomic(work / "report.html", report_html(ctx.outcome, work))
    write_text_atomic(work / "results.json", json.dumps(jsonable(ctx.results), indent=1) + "\n")

