"""The steps of ``fetorsion run``: each ``step(ctx) -> outcome`` computes one analysis of the
crank, saves its pictures (:meth:`fetorsion.app.run.RunContext.save`) and returns its typed
outcome (:mod:`fetorsion.report.outcomes`), its numbers also going to ``ctx.results``.

``ctx`` is the run's :class:`fetorsion.app.run.RunContext`; the annotations name it without
importing it, since :mod:`fetorsion.app.run` imports this module to list its steps.
"""

from __future__ import annotations

import dataclasses
import functools
import sys
import time

import numpy as np

from ..design.scfset import SCFSet
from ..description.model import Crank
from ..description.chain_model import Chain, Network
from ..errors import FetorsionError
from ..lumped_model.lumped import PARTITIONS, lumped
from ..modes import F1_TORSION_SHARE
from ..description.defaults import DEFAULT_PARTITION, DEFAULT_RUNUP_RATE, LUMPED17
from ..webs.methods import SPLIT_PIN_METHODS, WEB_METHODS, crank_web_method
from ..report.outcomes import (BearingsOutcome, CampbellOutcome, ChainOutcome, CondensedFacts, FatigueOutcome, FEOutcome, LumpedOutcome,
                               MeasuredOutcome, ModeImage, SensitivityOutcome, Skipped, TransientOutcome,
                               VerdictOutcome)
from .background import sensitivity_studies
from .fatigue_figures import fatigue_figures, haigh_of
from .run_store import fatigue_key, fe_key, remember as remember_section, stored as stored_section


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



def progress(message: str) -> None:
    """Write one progress line of a run to standard error.

    Parameters
    ----------
    message : str
        The line, without the ``[fetorsion]`` prefix the run's lines carry.
    """
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
    main = table[crank_web_method(ctx.crank)][PARTITIONS.index(DEFAULT_PARTITION)]
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
    cuts = fillet_cuts(ctx.crank, ctx.fillets())  # the verdict's sections: torque through every fillet
    # kept in the store unless a CAD crank (its picture of the recognised solid is drawn from the
    # solid) or a Campbell diagram of the free-free modes (it reads their shapes, which are not kept)
    key = fe_key(ctx.crank, size, cuts, modes) if not ctx.crank.solid_step and ctx.options.support == "bearings" \
        else None
    kept = None if key is None else fe_from_store(ctx, key, cuts)
    if kept is not None:
        return kept
    progress(f"  meshing the Gmsh solid ({size * 1e3:g} mm, curved P2 tetrahedra) ...")
    mesh = mesh_crank(ctx.crank, size)
    progress(f"  {len(mesh.tets)} tetrahedra, {len(np.unique(mesh.tets))} nodes in {mesh.quality.seconds:.1f} s; "
              "assembling, factorising, condensing ...")
    system = build_system(ctx.crank, size, mesh)
    cc = ctx.built["condensed"] = run_condensed(ctx.crank, system=system, cuts=cuts, start_modes=modes + 6 + 4)
    remember_condensed(cc, size, cuts)  # the next campbell, response, damper ... take it from the store
    fe = run_modal(ctx.crank, size, modes=modes, system=system, ritz=cc.free_ritz)
    cc.free_ritz = None
    fe.system = None  # the factor (the run's largest object) goes once the modes have it
    t = fe.timings_s = {**system.timings_s, "condensation": cc.timings_s["total"], "eigensolve": fe.timings_s["eigensolve"],
                        "identify": fe.timings_s["identify"]}
    t["total"] = sum(t.values())
    progress(f"  assembly {t['assembly']:.1f} s, factorisation {t['factorize']:.1f} s, condensation "
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
    if key is not None:  # after the pictures: what the store keeps
        ctx.deferred.append(functools.partial(_remember_fe, ctx, key))
    return FEOutcome(fe, size, images, solid_image, features)


def fe_from_store(ctx: RunContext, key: str, cuts) -> FEOutcome | None:
    """The FE step's outcome kept under ``key`` by an earlier run of the same crank, mesh and code
    (:mod:`fetorsion.app.run_store`: its results.json entry, mode pictures and 3D view; the
    condensed crank from :mod:`fetorsion.fe.store`), or None."""
    from ..fe.crankfe import CrankModal
    from ..fe.store import stored_condensed
    from ..io import atomic_output
    from ..report.load import mode_images

    size = ctx.options.mesh_size
    hit = stored_section(key)
    if hit is None or (ctx.options.html and VIEW_FILE not in hit[1]):
        return None
    cc = stored_condensed(ctx.crank, size, cuts)
    if cc is None:  # the condensed crank went from the store first: the step is computed again
        return None
    entry, files = hit
    ctx.built["condensed"] = cc
    for name, data in files.items():
        if name != VIEW_FILE:
            with atomic_output(ctx.folder / name) as tmp:
                tmp.write_bytes(data)
    ctx.results["fe"] = entry
    ctx.results.setdefault("from_store", {})["fe"] = ctx.outcome.from_store["fe"] = key
    images = mode_images(files)
    progress(f"  the FE modes, their pictures and the condensed crank of an earlier run of this crank "
             f"(store key {key[:12]})")
    return FEOutcome(CrankModal.from_dict(entry), size, images,
                     view_html=files[VIEW_FILE].decode() if VIEW_FILE in files else "")


#: The store's name of the report page's 3D view of the FE step's modes.
VIEW_FILE = "modes_view.html"


def _remember_fe(ctx: RunContext, key: str) -> None:
    """Keep the FE step's results.json entry, mode pictures and (for a report page) its 3D view
    for the next run: deferred work, after the pictures are drawn."""
    from ..io import jsonable
    from ..report.html import fe_modes_view

    out = ctx.outcome.fe
    if ctx.options.html:  # the page's view, drawn here rather than by the page: the store keeps it
        out = ctx.outcome.fe = dataclasses.replace(out, view_html=fe_modes_view(out))
    files = {im.file: (ctx.folder / im.file).read_bytes() for im in out.images}
    if out.view_html:
        files[VIEW_FILE] = out.view_html.encode()
    remember_section(key, jsonable(ctx.results["fe"]), files)


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
    # the chains against f1 in the engine (the summary's headline): where torsion couples with
    # bending in the bearings, the first mostly torsional mode can lie far above the first the
    # engine's torque drives (a split-pin V6: 1001.9 against 315.8 Hz)
    f_engine = held.first_carrying_torsion(F1_TORSION_SHARE)
    free, held = reported_modes(free), reported_modes(held)  # what the report reads, kept in results.json
    chain = {}
    split = any(p.split for p in ctx.crank.pins)
    for method in (m for m in ("carter", "fe", "fe-held") if not split or m in SPLIT_PIN_METHODS):  # no formula splits
        f17 = float(lumped(ctx.crank, DEFAULT_PARTITION, method, parts=ctx.parts(method)).frequencies_hz[0])
        chain[method] = {"f1_hz": f17, "vs_free": f17 / f_free - 1, "vs_bearings": f17 / f_engine - 1}
    images = [ctx.save(cc.plot().figure, "modes_free_and_bearings.png")]
    coupled = None
    ctx.results["bearings"] = {**cc.to_dict(), "free": free.rows(), "bearings": held.rows(),
                               "f1_free_hz": f_free, "f1_bearings_hz": f_held, "lumped_17dof": chain,
                               "main_bearings": dataclasses.asdict(cc.crank.main_bearings),
                               "support": {"radial_stiffness_n_per_m": list(cc.crank.main_bearings.radial_stiffness),
                                           "radial_damping_ns_per_m": list(cc.crank.main_bearings.radial_damping),
                                           "from_description": cc.crank.main_bearings.given,
                                           "oil_film_load_n": (None if cc.crank.main_bearings.oil_film is None
                                                               else cc.crank.main_bearings.oil_film.load)}}
    if ctx.crank.excitation is not None:
        coupled = run_coupled_response(cc, "bearings")
        images.append(ctx.save(coupled.plot().figure, "coupled_response.png"))
        ctx.results["bearings"]["coupled_response"] = coupled.to_dict()
    return BearingsOutcome(CondensedFacts.of(cc), free, held, chain, f_free, f_held, tuple(images), coupled)


def reported_modes(md):
    """The lowest of the condensed modes ``md`` that the report and the design loop read: the
    first :data:`~fetorsion.fe.condensed.CHECKED_MODES`, and every one up to the first torsional
    and the first with :data:`~fetorsion.modes.TORSION_SHARE_NOTED` or
    :data:`~fetorsion.modes.F1_TORSION_SHARE` of its energy in torsion."""
    from ..fe.condensed import CHECKED_MODES
    from ..modes import F1_TORSION_SHARE, TORSION_SHARE_NOTED

    torsional = [j for j, k in enumerate(md.kinds) if k == "torsional"][:1]
    carrying = [int(np.argmax(md.fractions[:, 0] >= s)) for s in (TORSION_SHARE_NOTED, F1_TORSION_SHARE)
                if np.any(md.fractions[:, 0] >= s)]
    return md.first(max([CHECKED_MODES - 1, *torsional, *carrying]) + 1)


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
        camp = run_coupled_campbell(ctx.built["condensed"], "bearings", diameters=[(f.diameter, f.bore) for f in fillets],
                                    section_names=[f.label for f in fillets])
    else:
        camp = run_campbell(ctx.crank, fe.modal.torsional_modes() if fe is not None else None,
                            parts=None if isinstance(ctx.crank, (Chain, Network)) else ctx.parts())
    resp = solve_response(ctx.setup(), ctx.crank.dampers)
    ctx.results["campbell"] = camp.to_dict()
    ctx.results["response"] = resp.to_dict()
    return CampbellOutcome(camp, resp, ctx.save(camp.plot().figure, "campbell.png"),
                           ctx.save(resp.plot().figure, "response.png"))




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
    ctx.results["verdict"].update(model=setup.model, mu=mu, scf=None if scf is None else scf.to_dict())
    return VerdictOutcome(verdict, mu, scf, ctx.save(verdict.plot().figure, "verdict.png"), stress, setup.model)


def fe_path_runs(ctx: RunContext) -> bool:
    """Whether the run's crank verdict computes the ``fe`` path: unless the options leave it out
    (the design loop's confirmations), and always where it decides."""
    from ..design.methods import described_method

    if ctx.options.fe_path or isinstance(ctx.crank, (Chain, Network)):
        return True
    return described_method(ctx.crank, ctx.options.fatigue_method) == "fe"


def step_fatigue(ctx: RunContext) -> FatigueOutcome | Skipped:
    """A crank's verdict: its fatigue by both methods in every configuration (without a damper,
    with the description's, with the recommended damper designed for this verdict, misfire), on
    the condensed crank in its bearings at the description's damping; the method of
    ``options.fatigue_method`` (else the description's ``[limits] fatigue_method``, else
    ``iacs-m53``) decides (:func:`fetorsion.design.crank_verdict.run_crank_verdict`)."""
    from ..design.crank_verdict import run_crank_verdict
    from ..design.m53 import split_pin_refusal
    from ..design.methods import described_method
    from ..design.stress import fillet_stress
    from ..report.load import FATIGUE_IMAGES

    crank = ctx.crank
    if "condensed" not in ctx.built:
        return Skipped("the fatigue verdict runs on the condensed crank (the FE steps did not run)")
    if crank.excitation is None:
        return Skipped("the description has no [excitation] table")
    if not (crank.fillets.journal > 0 and crank.fillets.pin > 0):
        return Skipped("fillet fatigue needs fillet radii (a sharp corner has no finite SCF)")
    if split_pin_refusal(crank):  # and the fe path's pin cuts and SCFs sit on one pin axis per throw
        return Skipped(split_pin_refusal(crank) + "; the fe path's pin-fillet cuts and SCFs take one pin axis per "
                       "throw and do not model a split pin either")
    key = None if ctx.network is not None else fatigue_key(crank, ctx.options)  # a driveline's: not kept
    kept = None if key is None else stored_section(key)
    if kept is not None:  # kept only where the SCFs were complete
        return _fatigue_from_store(ctx, key, kept[0])
    scf = ctx.scf()
    missing = scf.missing_bending()
    if missing:
        return Skipped(f"no {', '.join(missing)} SCF in {scf.source or 'the SCFs'}")
    method = described_method(crank, ctx.options.fatigue_method)
    cc, fillets, setup = ctx.built["condensed"], ctx.fillets(), ctx.engine_setup()
    verdict = run_crank_verdict(crank, cc, setup, fillets, scf, method, mu=ctx.options.inertia_ratio,
                                fe_path=fe_path_runs(ctx), progress=progress)
    described = verdict.configs[1 if crank.dampers else 0]
    a = described.fe  # None where the fe path was left out
    stress = fillet_stress(crank, ctx.outcome.campbell.response, scf, fillets) \
        if isinstance(ctx.outcome.campbell, CampbellOutcome) else None
    figures = (verdict.fatigue_figure(described), None if a is None else haigh_of(verdict, a).figure,
               verdict.damper.plot().figure)
    images = tuple(ctx.save(fig, name) for fig, name in zip(figures, FATIGUE_IMAGES) if fig is not None)
    ctx.results["fatigue"] = {**verdict.to_dict(), "fe_detail": None if a is None else a.to_dict(),
                              "scf": scf.to_dict(), "model": setup.model}
    if stress is not None:
        ctx.results["stress"] = stress.to_dict()
    if key is not None:
        from ..io import jsonable

        remember_section(key, jsonable(ctx.results["fatigue"]))
    return FatigueOutcome(verdict, a, stress, scf, images, setup.model)


def _fatigue_from_store(ctx: RunContext, key: str, entry: dict) -> FatigueOutcome:
    """The fatigue step's outcome from its results.json entry as an earlier run of the same
    description, options and code kept it: read back as ``fetorsion report`` reads it, its
    figures drawn as that draws them; the fillet stress of this run's response."""
    from ..design.scfset import SCFSet
    from ..design.stress import fillet_stress
    from ..report.load import read_fatigue

    progress(f"  the fatigue verdict of an earlier run of this description (store key {key[:12]})")
    ctx.results["fatigue"] = entry
    ctx.results.setdefault("from_store", {})["fatigue"] = ctx.outcome.from_store["fatigue"] = key
    stress = None
    if isinstance(ctx.outcome.campbell, CampbellOutcome):
        stress = fillet_stress(ctx.crank, ctx.outcome.campbell.response, SCFSet.from_dict(entry["scf"]), ctx.fillets())
        ctx.results["stress"] = stress.to_dict()
    out = read_fatigue(entry, stress)
    for name, draw in fatigue_figures(out).items():
        ctx.save(draw().figure, name)
    return out


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
    rate = ctx.options.runup_rate or stated_runup_rate(ctx.crank)
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


def stated_runup_rate(net) -> float:
    """The run-up's rate where the run is not given one, rpm/s: a propulsion line's slowest stated
    passage rate (``passage_rate_rpm_per_s``: the rate its speed passes a range at, the barred
    ranges' time-domain check's), else :data:`~fetorsion.description.defaults.DEFAULT_RUNUP_RATE`
    (a fast sweep, the report stating its α/Γ²)."""
    rates = [p.passage_rate for p in getattr(net, "propellers", ()) if p.passage_rate > 0]
    return min(rates) if rates else DEFAULT_RUNUP_RATE


#: The most severe crossings whose orders the report's run-up compares with the steady state.
REPORT_CROSSINGS = 3
#: About so many samples of each time signal go to ``results.json`` (the figures use every sample).
REPORT_SIGNAL_SAMPLES = 2000
