"""The work a run starts in a background process beside its FE steps: the throws' FE (web
stiffness, fillet SCFs, the ``fe`` path's stress recovery) and the sensitivity studies of f1.
Both depend on the crank alone, not on the run's other steps."""

from __future__ import annotations

import contextlib
import os
import sys

from ..description.model import Crank
from ..design.scfset import SCFSet
from ..errors import FetorsionError
from ..description.defaults import DEFAULT_STUDY_SAMPLES, LUMPED17


#: The report's studies of f1 (lumped 17 DOF, default web method), each of the default size.
REPORT_STUDIES = ("montecarlo", "sobol")


def sensitivity_studies(crank: Crank, workers: int | None, fe_checks: bool, parts=None):
    """(one-at-a-time sensitivity, {study: result}, FE checks) of f1: the lumped Monte Carlo and
    Sobol' studies and the FE checks of the most influential inputs, on an embedded Dask cluster,
    each sample stored as it finishes (``parts``: the nominal crank's, default web method, when
    the caller has them). Nothing here depends on the run's other steps, so :func:`fetorsion.app.run.run`
    starts it first, beside the FE work (:data:`fetorsion.app.run.BACKGROUND`)."""
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


def throw_fe_results(crank: Crank, scfs: bool = True, recovery: bool = True) -> tuple[dict, SCFSet | None]:
    """({throw key: the throw's torsion entry}, the fillet SCFs or None) of every distinct throw
    of ``crank``: its one throw FE each (:func:`fetorsion.webs.throwfe.end_loaded_fe`), found
    stored or computed. Run in the background process, first, when the crank has no stored throw
    data (:func:`needs_throw_fe`), so that the bearings step (the lumped ``fe`` column) and the
    verdict find them done. ``scfs=False`` (a run without the FE steps, whose verdict takes no FE
    SCF): the web stiffnesses only. With the SCFs, and an ``[excitation]`` for a verdict to read
    them, the ``fe`` path's stress-recovery fields (:func:`fetorsion.design.recovery.crank_zones`:
    every distinct throw and drilled section under six unit end loads) are stored too, unless
    ``recovery`` is False (a run whose verdict leaves the ``fe`` path out). SCFs that fail here
    are left to the verdict, which says why."""
    from ..design.recovery import crank_zones, stored_throw_zones
    from ..design.scf import fillet_scfs
    from ..webs.throwfe import forget_end_loaded, throw_key, throw_of, throw_torsion

    scf = None
    filleted = crank.fillets.journal > 0 and crank.fillets.pin > 0
    if scfs and filleted:
        try:
            # first: throw 1's FE is then the one kept in memory (the last one) when its web
            # stiffness is asked for below, and is not built a second time
            scf = fillet_scfs(crank)
        except FetorsionError:
            pass
    # the fe path's stress recovery, stored for the verdict: only where there is one (a crank
    # without [excitation] has no load cycle, and its zones would cost a minute for nothing)
    zones = recovery and scfs and filleted and crank.excitation is not None
    torsion = {}
    for i in range(len(crank.pins)):
        throw = throw_of(crank, i)
        key = throw_key(throw, None)  # the zones' key reads the same throw: one FE per distinct throw
        if key in torsion:
            continue
        torsion[key] = throw_torsion(throw)
        if zones:
            try:  # while the throw's FE (mesh, factorisation, end loads) is the one kept in memory
                stored_throw_zones(crank, i)
            except FetorsionError:
                pass  # left to the verdict, which says why
    forget_end_loaded()
    if zones:
        try:
            crank_zones(crank)  # the drilled sections' bars; the throws' are stored now
        except FetorsionError:
            pass
    return torsion, scf


def needs_throw_fe(crank: Crank, scfs: bool = True, recovery: bool = True) -> bool:
    """True when some throw of ``crank`` has its web stiffness, or (``scfs``) the crank its fillet
    SCFs (and, with ``recovery``, the ``fe`` path's stress-recovery fields), not stored."""
    from ..design.recovery import zones_stored
    from ..design.scf import stored_fillet_scfs
    from ..webs.throwfe import stored_throw_torsion, throw_of

    if any(stored_throw_torsion(throw_of(crank, i)) is None for i in range(len(crank.pins))):
        return True
    return scfs and crank.fillets.journal > 0 and crank.fillets.pin > 0 and (
        stored_fillet_scfs(crank) is None or (recovery and crank.excitation is not None and not zones_stored(crank)))


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

