"""``fetorsion run``: every analysis of one crank into one report folder, written atomically.

The folder is built under a temporary name beside the target and renamed into place only
when every step has succeeded, so a failed run leaves nothing behind and a reader never
sees a half-written report. An existing target is replaced only when it is an earlier
report (:func:`fetorsion.io.check_report_folder`). Each step is a small function
``step(ctx) -> outcome`` that computes, saves its pictures and returns its typed outcome
(:mod:`fetorsion.report.outcomes`; its numbers also go to ``ctx.results``, the JSON beside the
report); :mod:`fetorsion.report.markdown` and :mod:`fetorsion.report.html` present the outcomes.
"""

from __future__ import annotations

import contextlib
import functools
import json
import os
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np

from ..description.files import load
from ..design.scfset import SCFSet
from ..measured.dataset import MeasuredData
from ..description.model import Chain, Crank, Network
from ..errors import FetorsionError, ParameterError
from ..io import atomic_folder, check_report_folder, save_figure_atomic, write_text_atomic
from ..studies.runner import machine_workers
from ..lumped_model.lumped import PARTITIONS, lumped
from ..description.defaults import (DEFAULT_INERTIA_RATIO, DEFAULT_MESH_SIZE, DEFAULT_MODES, DEFAULT_PARTITION,
                                    DEFAULT_RUNUP_RATE, DEFAULT_STUDY_SAMPLES, DEFAULT_WEB_METHOD, LUMPED17)
from ..webs.methods import WEB_METHODS
from ..report.markdown import report_markdown
from ..report.outcomes import (BearingsOutcome, CampbellOutcome, ChainOutcome, FatigueOutcome, FEOutcome, LumpedOutcome, MeasuredOutcome,
                               ModeImage,
                               RunOutcome, SensitivityOutcome, Skipped, TransientOutcome, VerdictOutcome)


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
    runup_rate : float
        A chain's or network's run-up rate, rpm/s (``--run-up-rate``).
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
    """

    mesh_size: float = DEFAULT_MESH_SIZE
    modes: int = DEFAULT_MODES
    support: str = "bearings"
    source: str = "condensed"
    inertia_ratio: float = DEFAULT_INERTIA_RATIO
    fatigue_method: str | None = None
    runup_rate: float = DEFAULT_RUNUP_RATE
    workers: int | None = None
    html: bool = True
    measured: MeasuredData | None = None
    station: str | None = None
    no_fe: bool = False

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

    def parts(self, method: str = DEFAULT_WEB_METHOD):
        """The crank cut into its parts with ``method``'s web stiffness (built once). With the
        run's condensed crank built, ``fe-held`` takes its throws' stiffness from it, at the
        run's mesh size, instead of condensing the crank once more."""
        import functools

        from ..lumped_model.parts import build_parts
        from ..webs.throwfe import held_throw_stiffnesses, web_equivalent_length_held

        def build():
            if method == "fe":
                self.throw_fe()
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

            _progress("  fillet and oil-bore SCFs (static 3D FE, or the stored studies) ...")
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


#: A mode image's named places: the mesh's end faces
MODE_IMAGE_PLACES = (("front_face", "pulley end"), ("rear_face", "flywheel end"))


def mode_image_places(mesh) -> tuple:
    """(point, name) of the crank's pulley and flywheel ends on a mode image: each end face's
    centre (the faces the condensed crank's front and rear masters tie)."""
    found = []
    for key, name in MODE_IMAGE_PLACES:
        nodes = mesh.node_sets.get(key)
        if nodes is not None and len(nodes):
            found.append((mesh.nodes[np.asarray(nodes)].mean(axis=0), name))
    return tuple(found)


def _progress(message: str) -> None:
    print(f"[fetorsion] {message}", file=sys.stderr, flush=True)


def step_lumped(ctx: RunContext) -> LumpedOutcome | ChainOutcome:
    """All five partitions with every web method; mode-shape plots of the 17-DOF model (a chain: its modes)."""
    import matplotlib

    matplotlib.use("Agg")
    if isinstance(ctx.crank, (Chain, Network)):
        res = lumped(ctx.crank)
        ctx.results["lumped"] = {"chain": res.to_dict()}
        return ChainOutcome(res, ctx.save(res.plot().figure, "chain_modes.png"))
    table, skipped = {}, {}
    for method in WEB_METHODS:
        try:
            parts = ctx.parts(method)
            table[method] = [lumped(ctx.crank, d, method, parts=parts) for d in PARTITIONS]
        except FetorsionError as exc:  # e.g. a web outside the computed chart's range
            skipped[method] = str(exc)
    ctx.results["lumped"] = {m: [r.to_dict() for r in rs] for m, rs in table.items()}
    ctx.results["lumped_skipped"] = skipped
    main = table[DEFAULT_WEB_METHOD][PARTITIONS.index(DEFAULT_PARTITION)]
    return LumpedOutcome(table, skipped, ctx.save(main.plot().figure, "lumped_modes_17dof.png"))


def step_fe(ctx: RunContext) -> FEOutcome:
    """The crank's FE system (mesh, assembly, one factorisation), condensed to its journals and
    pins, and its free-free modes with attachments; images of the torsional and first bending
    modes. The free-free modes are the condensed crank's, expanded and checked against the full
    model by one block solve (:func:`fetorsion.fe.crankfe.run_modal` ``ritz``): one model answers
    free-free and in bearings, and the block Lanczos runs only where that check fails."""
    from ..design.stress import fillet_cuts
    from ..fe.condensed import run_condensed
    from ..fe.cranksystem import build_system
    from ..fe.store import remember_condensed
    from ..fe.crankfe import run_modal
    from ..solid.mesh import mesh_crank
    from ..report.render import render_mode

    size = ctx.options.mesh_size
    modes = ctx.options.modes
    _progress(f"  meshing the Gmsh solid ({size * 1e3:g} mm, curved P2 tetrahedra) ...")
    mesh = mesh_crank(ctx.crank, size)
    _progress(f"  {len(mesh.tets)} tetrahedra, {len(np.unique(mesh.tets))} nodes in {mesh.quality.seconds:.1f} s; "
              "assembling, factorising, condensing ...")
    system = build_system(ctx.crank, size, mesh)
    cuts = fillet_cuts(ctx.crank, ctx.fillets())  # the verdict's sections: torque through every fillet
    cc = ctx.built["condensed"] = run_condensed(ctx.crank, system=system, cuts=cuts, start_modes=modes + 6 + 4)
    remember_condensed(cc, size, cuts)  # the next campbell, response, damper ... take it from the store
    fe = run_modal(ctx.crank, size, modes=modes, system=system, ritz=cc.free_ritz)
    cc.free_ritz = None
    fe.system = None  # the factor (the run's largest object) goes once the modes have it
    t = fe.timings_s = {**system.timings_s, "condensation": cc.timings_s["total"], "eigensolve": fe.timings_s["eigensolve"],
                        "identify": fe.timings_s["identify"]}
    t["total"] = sum(t.values())
    _progress(f"  assembly {t['assembly']:.1f} s, factorisation {t['factorize']:.1f} s, condensation "
              f"{t['condensation']:.1f} s, free-free modes ({fe.method}) {t['eigensolve']:.1f} s (mode images drawn at the end)")
    cm = fe.mesh
    ctx.results["fe"] = {**fe.to_dict(), "first_torsional_hz": fe.first_torsional(), "mesh_size_m": size,
                         "min_sicn": cm.quality.min_sicn if cm.quality else None}
    picks = [j for j, k in enumerate(fe.kinds) if k == "torsional"][:3]
    picks += [j for j, k in enumerate(fe.kinds) if k == "bending"][:2]
    images = tuple(ModeImage(j, f"mode_{j + 1:02d}_{fe.kinds[j]}.png") for j in sorted(picks))
    places = mode_image_places(cm)
    for im in images:  # drawn later (RunContext.deferred): nothing after reads them
        ctx.deferred.append(functools.partial(
            render_mode, cm.nodes, cm.tets, fe.shapes[im.mode], ctx.folder / im.file,
            title=f"mode {im.mode + 1}: {fe.frequencies_hz[im.mode]:.1f} Hz, {fe.kinds[im.mode]}", places=places))
    solid_image, features = "", None
    if ctx.crank.solid_step:  # a CAD solid: what was recognised on it, for the user to check
        from ..report.render import render_solid
        from ..solid.geometry import solid_features

        solid_image = "solid_recognised.png"
        ctx.deferred.append(functools.partial(render_solid, ctx.crank, ctx.folder / solid_image))
        features = solid_features(ctx.crank)  # read when the run began: kept
    return FEOutcome(fe, size, images, solid_image, features)


def step_bearings(ctx: RunContext) -> BearingsOutcome | None:
    """The crank condensed to its journal and pin centres (the FE step's system), free and in
    its bearings: modes with torsion/bending shares, the lumped chain against each, and the
    coupled forced response (gas, inertia, tangential and radial pin forces; bearing forces)."""
    from ..response.coupled import run_coupled_response, with_film_bearings

    if ctx.outcome.fe is None:
        return None
    # the FE step's condensed crank; oil films without stated loads take each journal's mean
    # load from the crank's own forces
    cc = ctx.built["condensed"] = with_film_bearings(ctx.built["condensed"])
    free, held = cc.modes("free"), cc.modes("bearings")
    f_free, f_held = free.first_torsional(), held.first_torsional()
    chain = {}
    for method in ("carter", "fe", "fe-held"):
        f17 = float(lumped(ctx.crank, DEFAULT_PARTITION, method, parts=ctx.parts(method)).frequencies_hz[0])
        chain[method] = {"f1_hz": f17, "vs_free": f17 / f_free - 1, "vs_bearings": f17 / f_held - 1}
    images = [ctx.save(cc.plot().figure, "modes_free_and_bearings.png")]
    coupled = None
    ctx.results["bearings"] = {**cc.to_dict(), "f1_free_hz": f_free, "f1_bearings_hz": f_held, "lumped_17dof": chain,
                               "support": {"radial_stiffness_n_per_m": list(cc.crank.main_bearings.radial_stiffness),
                                           "radial_damping_ns_per_m": list(cc.crank.main_bearings.radial_damping),
                                           "from_description": cc.crank.main_bearings.given,
                                           "oil_film_load_n": (None if cc.crank.main_bearings.oil_film is None
                                                               else cc.crank.main_bearings.oil_film.load)}}
    if ctx.crank.excitation is not None:
        coupled = run_coupled_response(cc, "bearings")
        images.append(ctx.save(coupled.plot().figure, "coupled_response.png"))
        ctx.results["bearings"]["coupled_response"] = coupled.to_dict()
    return BearingsOutcome(cc, free, held, chain, f_free, f_held, tuple(images), coupled)


def step_campbell(ctx: RunContext) -> CampbellOutcome | Skipped:
    """Campbell diagram (FE torsional modes when the FE step ran) and forced response."""
    from ..excitation.campbell import run_campbell
    from ..response.forced import solve_response

    if ctx.crank.excitation is None:
        return Skipped("the description has no `[excitation]` table")
    # In its bearings when the condensed crank exists (the engine as it runs: every mode, the
    # full pin forces, severity as fillet stress), else the free-free FE's torsional modes.
    bearings, fe = ctx.outcome.bearings, ctx.outcome.fe
    if bearings is not None and ctx.options.support == "bearings":
        from ..response.coupled import run_coupled_campbell

        fillets = ctx.fillets()
        camp = run_coupled_campbell(bearings.condensed, "bearings", diameters=[(f.diameter, f.bore) for f in fillets],
                                    section_names=[f.label for f in fillets])
    else:
        camp = run_campbell(ctx.crank, fe.modal.torsional_modes() if fe is not None else None,
                            parts=None if isinstance(ctx.crank, (Chain, Network)) else ctx.parts())
    resp = solve_response(ctx.setup(), ctx.crank.dampers)
    ctx.results["campbell"] = camp.to_dict()
    ctx.results["response"] = resp.to_dict()
    return CampbellOutcome(camp, resp, ctx.save(camp.plot().figure, "campbell.png"),
                           ctx.save(resp.plot().figure, "response.png"))


#: Start the sensitivity studies when the run begins, beside the FE steps (False: in their step).
BACKGROUND = True
#: The report's studies of f1 (lumped 17 DOF, default web method), each of the default size.
REPORT_STUDIES = ("montecarlo", "sobol")


def step_verdict(ctx: RunContext) -> VerdictOutcome | Skipped:
    """Fillet stresses, the damper designs and the verdict against the description's [limits]."""
    from ..design.verdict import run_verdict

    crank = ctx.crank
    if isinstance(crank, Crank):  # a crank's verdict is its fatigue (step_fatigue), not a shear limit
        return None
    if crank.excitation is None or crank.limits is None:
        return Skipped("the description has no [excitation] and [limits] tables" if crank.excitation is None
                       else "the description has no [limits] table")
    scf = None
    if crank.limits.kind == "stress":
        if not (crank.fillets.journal > 0 and crank.fillets.pin > 0):
            return Skipped("stress limits need fillet radii (a sharp corner has no finite SCF)")
        from ..design.scf import stored_fillet_scfs

        if stored_fillet_scfs(crank) is None and ctx.options.no_fe:
            scf = SCFSet.of(1.0, 1.0, "none (nominal stress: no FE step in this run and no stored FE SCF)")
        else:
            scf = ctx.scf()
    mu = ctx.options.inertia_ratio
    fillets = ctx.fillets() if scf is not None else None
    verdict = run_verdict(crank, mu=mu, scf=scf, setup=ctx.setup(), fillets=fillets)
    ctx.results["verdict"] = verdict.to_dict()
    stress = None
    if scf is not None:
        from ..design.stress import fillet_stress

        stress = fillet_stress(crank, ctx.outcome.campbell.response, scf, fillets)
        ctx.results["stress"] = stress.to_dict()
    setup = ctx.setup()  # a chain's or network's own model: the only one it has
    ctx.results["verdict"]["model"] = setup.model
    return VerdictOutcome(verdict, mu, scf, ctx.save(verdict.plot().figure, "verdict.png"), stress, setup.model)


def step_fatigue(ctx: RunContext) -> FatigueOutcome | Skipped:
    """A crank's verdict: its fatigue by both methods in every configuration (without a damper,
    with the description's, with the recommended damper designed for this verdict, misfire), on
    the condensed crank in its bearings at the description's damping; the method of
    ``options.fatigue_method`` (else the description's ``[limits] fatigue_method``, else
    ``iacs-m53``) decides (:func:`fetorsion.design.crank_verdict.run_crank_verdict`)."""
    from ..design.crank_verdict import run_crank_verdict
    from ..design.methods import described_method
    from ..design.stress import fillet_stress

    crank = ctx.crank
    if "condensed" not in ctx.built:
        return Skipped("the fatigue verdict runs on the condensed crank (the FE steps did not run)")
    if crank.excitation is None:
        return Skipped("the description has no [excitation] table")
    if not (crank.fillets.journal > 0 and crank.fillets.pin > 0):
        return Skipped("fillet fatigue needs fillet radii (a sharp corner has no finite SCF)")
    scf = ctx.scf()
    missing = scf.missing_bending()
    if missing:
        return Skipped(f"no {', '.join(missing)} SCF in {scf.source or 'the SCFs'}")
    method = described_method(crank, ctx.options.fatigue_method)
    cc, fillets, setup = ctx.built["condensed"], ctx.fillets(), ctx.engine_setup()
    verdict = run_crank_verdict(crank, cc, setup, fillets, scf, method,
                                mu=ctx.options.inertia_ratio, progress=_progress)
    described = verdict.configs[1 if crank.dampers else 0]
    a = described.fe
    stress = fillet_stress(crank, ctx.outcome.campbell.response, scf, fillets) \
        if isinstance(ctx.outcome.campbell, CampbellOutcome) else None
    images = (ctx.save(verdict.fatigue_figure(described), "fatigue_safety.png"),
              ctx.save(haigh_of(verdict, a).figure, "fatigue_haigh.png"),
              ctx.save(verdict.damper.plot().figure, "damper_design.png"))
    ctx.results["fatigue"] = {**verdict.to_dict(), "fe_detail": a.to_dict(), "scf": scf.to_dict()}
    if stress is not None:
        ctx.results["stress"] = stress.to_dict()
    return FatigueOutcome(verdict, a, stress, scf, images, setup.model)


def haigh_of(verdict, assessment):
    """The ``fe`` path's Haigh diagram, titled with whether that path decides the verdict (M53
    reads no mean stress: it has no Haigh diagram of its own)."""
    ax = assessment.haigh()
    ax.set_title(f"{ax.get_title()} (fe path, Findley)\n{verdict.decides('fe')}", fontsize=8, wrap=True)
    return ax


def sensitivity_studies(crank: Crank, workers: int | None, fe_checks: bool, parts=None):
    """(one-at-a-time sensitivity, {study: result}, FE checks) of f1: the lumped Monte Carlo and
    Sobol' studies and the FE checks of the most influential inputs, on an embedded Dask cluster,
    each sample stored as it finishes (``parts``: the nominal crank's, default web method, when
    the caller has them). Nothing here depends on the run's other steps, so :func:`run` starts
    it first, beside the FE work (:data:`BACKGROUND`)."""
    from ..studies.runner import ClusterOnDemand, open_store
    from ..studies.models import make_model
    from ..studies.sampling import study_inputs
    from ..studies.sensitivity import fe_check, run_sensitivity
    from ..studies.study import run_study

    sens = run_sensitivity(crank, parts=parts)
    inputs, _ = study_inputs(crank)
    model = make_model(crank, LUMPED17)
    store = open_store()
    print(f"[fetorsion] {store.describe()}", file=sys.stderr, flush=True)
    # One worker: here, without a cluster. The background process isolates the studies already, and
    # a one-worker cluster only adds its start and its traffic (Renault 21 on 2 cores: 22.5 s and
    # 25 CPU-s here, 28.7 s and 31 CPU-s on a one-worker cluster).
    cluster = contextlib.nullcontext() if workers == 1 else ClusterOnDemand(workers=workers)
    with cluster as client:  # started only for samples not stored
        studies = {method: run_study(model, inputs, method, n, client=client, store=store, name=crank.name,
                                     measured_hz=sens.measured_hz)
                   for method, n in ((m, DEFAULT_STUDY_SAMPLES[m]) for m in REPORT_STUDIES)}
        checks = fe_check(crank, sens, client=client, store=store) if fe_checks else []
    return sens, studies, checks


def throw_fe_results(crank: Crank, scfs: bool = True) -> tuple[dict, SCFSet | None]:
    """({throw key: the throw's torsion entry}, the fillet SCFs or None) of every distinct throw
    of ``crank``: its one throw FE each (:func:`fetorsion.webs.throwfe.end_loaded_fe`), found
    stored or computed. Run in the background process, first, when the crank has no stored throw
    data (:func:`needs_throw_fe`), so that the bearings step (the lumped ``fe`` column) and the
    verdict find them done. ``scfs=False`` (a run without the FE steps, whose verdict takes no FE
    SCF): the web stiffnesses only. With the SCFs, and an ``[excitation]`` for a verdict to read
    them, the ``fe`` path's stress-recovery fields (:func:`fetorsion.design.recovery.crank_zones`:
    every distinct throw and drilled section under six unit end loads) are stored too. SCFs that fail here are left to the verdict, which says why."""
    from ..design.recovery import crank_zones
    from ..design.scf import fillet_scfs
    from ..webs.throwfe import forget_end_loaded, throw_key, throw_of, throw_torsion

    scf = None
    if scfs and crank.fillets.journal > 0 and crank.fillets.pin > 0:
        try:
            # first: throw 1's FE is then the one kept in memory (the last one) when its web
            # stiffness is asked for below, and is not built a second time
            scf = fillet_scfs(crank)
        except FetorsionError:
            pass
    torsion = {}
    for i in range(len(crank.pins)):
        throw = throw_of(crank, i)
        torsion.setdefault(throw_key(throw, None), throw_torsion(throw))
    forget_end_loaded()
    # the fe path's stress recovery, stored for the verdict: only where there is one (a crank
    # without [excitation] has no load cycle, and its zones would cost a minute for nothing)
    if scfs and crank.fillets.journal > 0 and crank.fillets.pin > 0 and crank.excitation is not None:
        try:
            crank_zones(crank)
        except FetorsionError:
            pass  # left to the verdict, which says why
    return torsion, scf


def needs_throw_fe(crank: Crank, scfs: bool = True) -> bool:
    """True when some throw of ``crank`` has its web stiffness, or (``scfs``) the crank its fillet
    SCFs, not stored."""
    from ..design.recovery import zones_stored
    from ..design.scf import stored_fillet_scfs
    from ..webs.throwfe import stored_throw_torsion, throw_of

    if any(stored_throw_torsion(throw_of(crank, i)) is None for i in range(len(crank.pins))):
        return True
    return scfs and crank.fillets.journal > 0 and crank.fillets.pin > 0 and (
        stored_fillet_scfs(crank) is None or (crank.excitation is not None and not zones_stored(crank)))


#: Niceness of the background studies' process (and the Dask workers it starts): they take the
#: cores the FE work leaves idle (meshing, assembly, single-threaded stretches) instead of
#: slowing its factorisation and block solves.
BACKGROUND_NICENESS = 19


def _background_process(parent: int):
    """Initialiser of the studies' process: tied to the run (:func:`fetorsion.solid.isolate.die_with_parent`),
    then at a lower priority (where the platform allows)."""
    from ..solid.isolate import die_with_parent

    die_with_parent(parent)
    try:
        os.nice(BACKGROUND_NICENESS)
    except (AttributeError, OSError):
        pass


def background_executor():
    """One spawned process for :func:`sensitivity_studies` beside the FE work. A process, not a
    thread: in-process, its scheduler and store work held the interpreter and its threads the
    cores (Renault 21, 2 cores: the FE factorisation 11.2 s beside a study thread, 6.5 s beside
    the same studies in a process at niceness 19)."""
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    return ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn"), initializer=_background_process,
                               initargs=(os.getpid(),))


def step_measured(ctx: RunContext) -> MeasuredOutcome | Skipped | None:
    """The model against the measured files the run was given (none: no section)."""
    measured = ctx.options.measured
    if not measured:
        return None
    from ..studies.comparison import run_comparison

    # the model the verdict judged: the condensed crank in its bearings where the run built it;
    # its forced response with the description's dampers is the Campbell step's, solved once
    engine = ctx.setup() is ctx.engine_setup()
    camp = ctx.outcome.campbell
    response = camp.response if isinstance(camp, CampbellOutcome) else None
    res = run_comparison(ctx.crank, measured, "condensed" if engine else LUMPED17, ctx.options.station,
                         condensed=ctx.built.get("condensed"), response=response)
    ctx.results["measured"] = res.to_dict()
    return MeasuredOutcome(res, ctx.save(res.plot(), "measured.png"))


def step_sensitivity(ctx: RunContext) -> SensitivityOutcome | Skipped:
    """f1 against each reconstructed input and the resulting band (needs [uncertainty]); the
    Monte Carlo distribution and Sobol' indices of f1; the FE check of the largest inputs
    (:func:`sensitivity_studies`, started in the background when the run began)."""
    if not getattr(ctx.crank, "uncertainty", ()):  # a chain file has none
        return Skipped("the description has no `[uncertainty]` table")
    pending = ctx.built.pop("studies", None)
    ctx.run_deferred()  # while the studies finish
    sens, studies, checks = (pending.result() if pending is not None else
                             sensitivity_studies(ctx.crank, ctx.options.workers, ctx.outcome.fe is not None,
                                                 ctx.parts()))
    ctx.results["sensitivity"] = sens.to_dict()
    if checks:
        ctx.results["sensitivity"]["fe_check"] = checks
    ctx.results["studies"] = {m: r.to_dict() for m, r in studies.items()}
    return SensitivityOutcome(
        sens, checks, ctx.save(sens.plot().figure, "sensitivity.png"), studies,
        {"montecarlo": ctx.save(studies["montecarlo"].plot(kind="histogram").figure, "f1_montecarlo.png"),
         "sobol": ctx.save(studies["sobol"].plot(kind="indices").figure, "f1_sobol.png")})


def step_transient(ctx: RunContext) -> TransientOutcome | Skipped | None:
    """A chain's or network's run-up over its checked speed range at ``options.runup_rate``
    (default :data:`~fetorsion.description.defaults.DEFAULT_RUNUP_RATE`) in the time domain: the
    exact linear propagator, or the nonlinear integrator when the network has nonlinear elements;
    its waterfall, and its order cuts against the steady-state response at the Campbell crossings.
    A crank description's run leaves the section out (its response runs on the condensed crank;
    ``fetorsion transient`` takes its lumped model)."""
    from ..excitation.campbell import most_severe
    from ..response.transient import order_cuts, plot_order_cuts, run_transient

    if not isinstance(ctx.crank, (Chain, Network)):
        return None
    camp = ctx.outcome.campbell
    if not isinstance(camp, CampbellOutcome):
        return Skipped(camp.reason if isinstance(camp, Skipped) else "no Campbell diagram and forced response")
    rate = ctx.options.runup_rate
    lo, hi = ctx.crank.excitation.checked_range
    t0 = time.perf_counter()
    res = run_transient(ctx.crank, run=(lo, hi), rate_rpm_per_s=rate, settled_start=True)
    seconds = time.perf_counter() - t0
    cuts = order_cuts(res, camp.response, most_severe(camp.campbell.crossings, REPORT_CROSSINGS),
                      camp.campbell.damping_ratio, rate)
    top = float(np.max(camp.response.orders))
    ctx.results["transient"] = {**res.to_dict(every=max(1, res.time_s.size // REPORT_SIGNAL_SAMPLES)),
                                "rate_rpm_per_s": rate, "seconds": seconds, "order_cuts": [c.to_dict() for c in cuts]}
    waterfall = ctx.save(res.waterfall(max_order=top).figure, "runup_waterfall.png")
    image = ctx.save(plot_order_cuts(res, camp.response, cuts).figure, "runup_order_cuts.png")
    return TransientOutcome(res, rate, cuts, seconds, waterfall, image)


#: The most severe crossings whose orders the report's run-up compares with the steady state.
REPORT_CROSSINGS = 3
#: About so many samples of each time signal go to ``results.json`` (the figures use every sample).
REPORT_SIGNAL_SAMPLES = 2000


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


def run(path, out, steps=DEFAULT_STEPS, options: RunOptions | None = None, force: bool = False) -> RunOutcome:
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
    """
    import dataclasses

    options = options or RunOptions()
    out = Path(out)
    check_report_folder(out, "out", force=force, inputs=[path])
    crank = load(path)  # every input rule is checked here, before any work or any file
    if isinstance(crank, Crank):
        from ..design.methods import described_method

        described_method(crank, options.fatigue_method)  # the fatigue method against the registry
    network = None
    if isinstance(crank, Network) and any(c.condensed for c in crank.cranks):
        # a driveline on the condensed crank: the crank's own report, its engine model in that driveline
        network, crank = crank, next(c for c in crank.cranks if c.condensed).crank
        away = [d.name or d.at for d in network.dampers if d.at != "front"]
        if away:
            raise FetorsionError(f"{path}: damper(s) {', '.join(away)} away from the crank's pulley: the report of a "
                                 "network on the condensed crank takes a damper at \"front\" only yet (`fetorsion "
                                 "response` takes one on any station)")
        # the network's dampers at the pulley are the crank's in the report (its verdict's "as described")
        crank = dataclasses.replace(crank, dampers=tuple(network.dampers))
        if options.no_fe or not any(s[2] is step_fe for s in steps):
            raise ParameterError("no_fe", f"{path}: a network on the condensed crank needs the FE steps (its engine "
                                          "model); give the crank dof = 17 for the lumped driveline")
    features = None
    if getattr(crank, "solid_step", None):  # a CAD crank: its solid against its description, before any work
        from ..solid.geometry import solid_features

        features = solid_features(crank)
    if isinstance(crank, (Chain, Network)):  # no geometry: the report without the mesh and FE sections
        steps = tuple(s for s in steps if s[2] not in (step_fe, step_bearings))
    with atomic_folder(out) as work, background_executor() as background:
        outcome = RunOutcome(crank, str(path), timings_s={}, folder=str(out),
                             driveline="" if network is None else network.name)
        no_fe = options.no_fe or not any(s[2] is step_fe for s in steps)
        ctx = RunContext(crank, work, dataclasses.replace(options, no_fe=no_fe), outcome, network=network)
        if network is not None:
            ctx.results["driveline"] = {"network": network.name, "source": str(path),
                                        "stations": [s for s in network.labels
                                                     if not any(s in c.labels[1:-1] for c in network.cranks)],
                                        "note": "the response, fatigue and verdict are the crank's in this driveline "
                                                "(the condensed crank in its bearings joined to the network's stations); "
                                                "the lumped models, the Campbell diagram and the bearings' coupled "
                                                "response are the crank's alone"}
        if features is not None:
            ctx.results["solid"] = features.to_dict()
        scfs = not ctx.options.no_fe  # without the FE steps the verdict takes no FE SCF
        if BACKGROUND and not isinstance(crank, (Chain, Network)) and needs_throw_fe(crank, scfs):
            # first in the queue: the bearings step (the lumped `fe` column) and the verdict read it
            ctx.built["throw_fe"] = background.submit(throw_fe_results, crank, scfs)
        if BACKGROUND and any(s[2] is step_sensitivity for s in steps) and getattr(crank, "uncertainty", ()):
            # the studies run beside the FE steps on one core fewer than the machine has: the FE's
            # assembly and Lanczos iterations keep one core busy, not two (Renault 21 on 2 cores:
            # 97 s with the studies in their step, 93 s beside the FE on 2 workers, 88 s on 1)
            workers = ctx.options.workers or max(1, machine_workers() - 1)
            ctx.built["studies"] = background.submit(sensitivity_studies, crank, workers,
                                                     any(s[2] is step_fe for s in steps), ctx.parts())
        for name, key, fn in steps:
            _progress(f"{name} ...")
            t0 = time.perf_counter()
            setattr(outcome, key, fn(ctx))
            outcome.timings_s[name] = time.perf_counter() - t0
            _progress(f"{name}: done in {outcome.timings_s[name]:.1f} s")
        ctx.run_deferred()
        ctx.results["timings_s"] = outcome.timings_s
        write_text_atomic(work / "report.md", report_markdown(outcome))
        if ctx.options.html:
            from ..report.html import report_html

            write_text_atomic(work / "report.html", report_html(outcome, work))
        write_text_atomic(work / "results.json", json.dumps(_jsonable(ctx.results), indent=1) + "\n")
    return outcome


def _jsonable(x):
    if isinstance(x, dict):
        return {str(k): _jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_jsonable(v) for v in x]
    if isinstance(x, np.ndarray):
        return x.tolist()
    if isinstance(x, np.generic):
        return x.item()
    return x
