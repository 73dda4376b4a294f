"""Many model runs on a Dask cluster, each result stored as it arrives.

A study is a list of samples (a dict of input values each) and a model, a picklable callable
``model(values) -> dict of outputs`` with a ``key`` string that says what it computes. Each
sample is keyed by a hash of the model's key, the sample's values and fetorsion's own source
(:func:`code_hash`), and its result is written to a :class:`SampleStore` as one small JSON
file, atomically, the moment it comes back. So an interrupted study resumes where it stopped,
a re-run computes nothing twice, and a change of fetorsion's code never serves stale numbers.

The engine is ``dask.distributed``: by default an embedded ``LocalCluster`` of worker
processes sized to the machine, each with one thread and one BLAS thread (workers do not
fight over cores); with ``scheduler="tcp://host:8786"`` (or ``DASK_SCHEDULER_ADDRESS``) the same
study runs on an existing cluster. The client writes the store, so remote workers need no
shared file system, only fetorsion installed. Cheap samples travel in batches (one task of
many samples keeps the scheduler's per-task cost off the samples); a sample that raises is
recorded with its error and the study goes on; a worker lost mid-task is replaced by the
nanny and its tasks rescheduled, and a task that kills its worker again is split into single
samples so that only the culprit is recorded as failed.
"""

from __future__ import annotations

import hashlib
import json
import numbers
import os
import sys
import time
import traceback
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Iterable

from ..errors import FetorsionError
from ..io import remove_stale_temporaries, write_small_atomic

#: Environment of each local worker process: one BLAS/OpenMP thread, the worker's one core.
WORKER_ENV = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
#: Retries of a task whose function raised past the per-sample guard (a lost connection, a
#: worker's memory error); a sample's own exception is recorded, not retried.
TASK_RETRIES = 2
SCHEDULER_ENV = "DASK_SCHEDULER_ADDRESS"
STORE_ENV = "FETORSION_STORE"


def default_store() -> Path:
    """The sample store: ``$FETORSION_STORE``, else ``~/.cache/fetorsion/samples``."""
    env = os.environ.get(STORE_ENV)
    if env:
        return Path(env)
    cache = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(cache) / "fetorsion" / "samples"


_CODE_HASH: str | None = None


def code_hash() -> str:
    """SHA-256 of fetorsion's Python source: part of every sample key, so that results stored
    by other code (an older checkout, an edited model) are never taken for this code's."""
    global _CODE_HASH
    if _CODE_HASH is None:
        root = Path(__file__).resolve().parents[1]
        h = hashlib.sha256()
        for path in sorted(root.rglob("*.py")):
            h.update(str(path.relative_to(root)).encode())
            h.update(path.read_bytes())
        _CODE_HASH = h.hexdigest()
    return _CODE_HASH


def sample_key(model_key: str, values: dict) -> str:
    """Hash of one sample: the model's key, the values (exact floats) and the code."""
    text = json.dumps({"model": model_key, "values": {k: _exact(v) for k, v in values.items()},
                       "code": code_hash()}, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()


def _exact(v):
    return float(v).hex() if isinstance(v, float) else v


class SampleStore:
    """One JSON file per sample, ``FOLDER/ab/abcdef….json`` (sharded by the key's first two
    hex digits so no folder grows large), each written atomically."""

    def __init__(self, folder):
        self.folder = Path(folder)
        remove_stale_temporaries(self.folder)  # what a killed study was writing

    def path(self, key: str) -> Path:
        return self.folder / key[:2] / f"{key}.json"

    def get(self, key: str) -> dict | None:
        try:
            return json.loads(self.path(key).read_text(encoding="utf-8"))
        except (OSError, ValueError):  # absent, or unreadable: computed again
            return None

    def put(self, key: str, record: dict) -> None:
        write_small_atomic(self.path(key), json.dumps(record).encode())


def check_store(folder, option: str = "--store") -> None:
    """Refuse, before any work, a store that is a file or cannot be written."""
    from ..io import check_writable_location

    folder = Path(folder)
    if os.path.lexists(folder) and not folder.is_dir():
        raise FetorsionError(f"{option} {folder}: exists and is not a folder")
    check_writable_location(folder / "x", option)


# ---------------------------------------------------------------------------
# The cluster


def scheduler_address(scheduler: str | None) -> tuple[str | None, str]:
    """The address to connect to (None: an embedded local cluster) and where it came from."""
    if scheduler:
        return scheduler, "--scheduler"
    env = os.environ.get(SCHEDULER_ENV)
    return (env, SCHEDULER_ENV) if env else (None, "")


def check_scheduler(address: str, option: str) -> None:
    """A scheduler address must read ``[tcp://|tls://|inproc://]host:port``."""
    from distributed.comm import parse_address
    from distributed.comm.addressing import parse_host_port

    try:
        proto, loc = parse_address(address if "://" in address else f"tcp://{address}")
        if proto in ("tcp", "tls"):
            parse_host_port(loc)
    except (ValueError, TypeError) as exc:
        raise FetorsionError(f"{option} {address!r}: not a scheduler address such as tcp://host:8786 ({exc})") from None


def machine_workers() -> int:
    """Worker processes of a local cluster: one per core this process may use."""
    return max(1, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1)


@contextmanager
def open_client(scheduler: str | None = None, workers: int | None = None, timeout_s: float = 20.0):
    """A ``distributed.Client``: on the scheduler at ``scheduler`` (or ``$DASK_SCHEDULER_ADDRESS``),
    else on an embedded ``LocalCluster`` of ``workers`` processes (default: one per core),
    one thread and one BLAS thread each. Closed (the local cluster shut down) on exit."""
    import logging

    from distributed import Client, LocalCluster

    address, where = scheduler_address(scheduler)
    if address is not None:
        check_scheduler(address, where)
        try:
            client = Client(address, timeout=timeout_s)
        except (OSError, TimeoutError) as exc:
            raise FetorsionError(f"{where} {address}: no scheduler answered within {timeout_s:g} s ({exc})") from None
        try:
            yield client
        finally:
            client.close()
        return
    import dask

    # Workers start as processes under a nanny (restarted when lost); the environment
    # reaches them before numpy loads its BLAS.
    with dask.config.set({"distributed.nanny.pre-spawn-environ": {**dask.config.get(
            "distributed.nanny.pre-spawn-environ", {}), **WORKER_ENV}}):
        cluster = LocalCluster(n_workers=workers or machine_workers(), threads_per_worker=1, processes=True,
                               dashboard_address=":0", silence_logs=logging.ERROR, env=dict(WORKER_ENV))
    try:
        client = Client(cluster)
        try:
            yield client
        finally:
            client.close()
    finally:
        cluster.close()


class ClusterOnDemand:
    """A client that is opened (cluster started) only when some sample must be computed: a
    study whose every sample is stored costs no cluster start. Use as a context manager and
    pass it where a client goes; arguments as :func:`open_client`."""

    def __init__(self, scheduler: str | None = None, workers: int | None = None):
        self.scheduler, self.workers = scheduler, workers
        self._stack = None
        self._client = None

    def get(self):
        if self._client is None:
            from contextlib import ExitStack

            self._stack = ExitStack()
            self._client = self._stack.enter_context(open_client(self.scheduler, self.workers))
            info = self._client.scheduler_info()
            print(f"[fetorsion] Dask cluster: scheduler {info.get('address', '?')}"
                  f"{'' if scheduler_address(self.scheduler)[0] else ' (local)'}, {len(info.get('workers', {}))} workers",
                  file=sys.stderr, flush=True)
        return self._client

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if self._stack is not None:
            self._stack.close()
        self._stack = self._client = None
        return False


def auto_batch(runs: int, client, expensive: bool) -> int:
    """Samples per task: one for an expensive model; else about eight tasks per worker, at
    most 500 samples each (a cheap sample is a millisecond; a task costs the scheduler ~1 ms)."""
    if expensive or client is None:
        return 1
    workers = max(1, sum(client.nthreads().values()))
    return int(min(500, max(1, -(-runs // (8 * workers)))))


# ---------------------------------------------------------------------------
# Running samples


def run_batch(model, batch: list[tuple[str, dict]]) -> list[tuple[str, dict]]:
    """Run ``model`` on each (key, values) of ``batch`` on a worker, with one BLAS thread."""
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=1):
        return list(run_each(model, batch))


def run_each(model, batch):
    """Yield (key, record) for each (key, values) of ``batch``: the model's ``outputs``, or the
    ``error`` its exception gave (the batch goes on), with the values, time and worker."""
    for key, values in batch:
        t0 = time.perf_counter()
        try:
            record = {"outputs": _jsonable_outputs(model(values))}
        except Exception as exc:  # the sample's failure is its result
            record = {"error": f"{type(exc).__name__}: {exc}",
                      "traceback": "".join(traceback.format_exception(exc)[-3:])}
        record.update(values=values, model=model.key, seconds=time.perf_counter() - t0,
                      worker=f"{os.uname().nodename}:{os.getpid()}")
        yield key, record


def _jsonable_outputs(outputs: dict) -> dict:
    """Numbers as floats (numpy scalars too), anything else as the model gave it (JSON-ready)."""
    return {k: float(v) if isinstance(v, numbers.Real) else v for k, v in outputs.items()}


@dataclass
class RunSummary:
    """What a run of samples did: computed now, found stored, failed (stored with the error)."""

    total: int
    stored_before: int
    computed: int
    failed: int
    wall_s: float


class Progress:
    """One line on stderr: samples done of the total, failures, rate; rewritten in place on
    a terminal, printed every few seconds otherwise."""

    def __init__(self, total: int, done: int, label: str, stream=None):
        self.total, self.done, self.failed, self.label = total, done, 0, label
        self.stream = stream or sys.stderr
        self.t0 = self.last = time.perf_counter()
        self.start_done = done
        self.tty = getattr(self.stream, "isatty", lambda: False)()

    def update(self, failed: bool) -> None:
        self.done += 1
        self.failed += failed
        now = time.perf_counter()
        if now - self.last >= (0.2 if self.tty else 5.0) or self.done == self.total:
            self.last = now
            self._write(final=self.done == self.total)

    def _write(self, final: bool) -> None:
        elapsed = time.perf_counter() - self.t0
        rate = (self.done - self.start_done) / max(elapsed, 1e-9)
        speed = f"{rate:.0f} samples/s" if rate >= 10 else f"{elapsed / max(self.done - self.start_done, 1):.1f} s/sample"
        eta = (self.total - self.done) / rate if rate > 0 else 0.0
        line = (f"[fetorsion] {self.label}: {self.done}/{self.total} samples"
                + (f" ({self.start_done} stored before)" if self.start_done else "")
                + (f", {self.failed} failed" if self.failed else "") + f", {speed}"
                + (f", about {eta:.0f} s left" if not final and eta >= 1 else ""))
        self.stream.write(("\r" + line + ("\n" if final else "")) if self.tty else line + "\n")
        self.stream.flush()


def batches(items: list, size: int) -> Iterable[list]:
    for i in range(0, len(items), size):
        yield items[i:i + size]


def run_samples(model, samples: list[dict], store: SampleStore, client=None, batch_size: int | None = None,
                retry_failed: bool = False, label: str = "study",
                on_record: Callable[[str, dict], None] | None = None, progress: bool = True) -> tuple[list[dict], RunSummary]:
    """Every sample's record (``outputs`` or ``error``), computing only those not stored.

    Parameters
    ----------
    model : callable
        ``model(values) -> dict`` of outputs (floats or JSON values), with a ``key`` attribute
        (str) naming what it computes; picklable (module-level class or function).
    samples : list of dict
        Input values of each sample (JSON-ready; floats are hashed exactly).
    store : SampleStore
        Where records are found and written.
    client : distributed.Client or ClusterOnDemand, optional
        Runs the tasks; None runs them here, one after the other (same store, same records).
    batch_size : int, optional
        Samples per task (default :func:`auto_batch`; the model's ``expensive`` attribute says).
    retry_failed : bool
        Compute again the samples stored with an error.
    on_record : callable, optional
        Called with (key, record) after each record is stored (a hook for tests and callers).

    Returns
    -------
    records : list of dict
        In the order of ``samples``.
    summary : RunSummary
    """
    t0 = time.perf_counter()
    keys = [sample_key(model.key, s) for s in samples]
    records: dict[str, dict] = {}
    for k in dict.fromkeys(keys):
        rec = store.get(k)
        if rec is not None and ("outputs" in rec or not retry_failed):
            records[k] = rec
    todo = [(k, s) for k, s in dict(zip(keys, samples)).items() if k not in records]
    stored_before = len(set(keys)) - len(todo)
    bar = Progress(len(set(keys)), stored_before, label) if progress else None
    failed = 0

    def keep(key: str, record: dict, persist: bool = True) -> None:
        nonlocal failed
        if persist:
            store.put(key, record)
        records[key] = record
        failed += "error" in record
        if bar:
            bar.update("error" in record)
        if on_record:
            on_record(key, record)

    if todo and client is None:
        for key, record in run_each(model, todo):
            keep(key, record)
    elif todo:
        client = client.get() if isinstance(client, ClusterOnDemand) else client
        batch_size = batch_size or auto_batch(len(todo), client, getattr(model, "expensive", False))
        _run_on_cluster(client, model, todo, batch_size, keep)
    summary = RunSummary(len(set(keys)), stored_before, len(todo), failed, time.perf_counter() - t0)
    return [records[k] for k in keys], summary


def check_worker_code(client) -> None:
    """Every worker must run the fetorsion the client runs: sample keys hash the client's
    source, so a worker with other code would store its numbers under this code's keys."""
    mine = code_hash()
    try:
        theirs = client.run(code_hash)
    except Exception as exc:  # e.g. a worker machine without fetorsion installed
        raise FetorsionError(f"the Dask workers could not run fetorsion ({type(exc).__name__}: {exc}); "
                             "install it on every worker machine") from None
    other = sorted(w for w, h in theirs.items() if h != mine)
    if other:
        raise FetorsionError(f"{len(other)} of {len(theirs)} Dask workers ({', '.join(other[:3])}) run a fetorsion "
                             "whose source differs from this one; install the same version on every worker")


def _run_on_cluster(client, model, todo, batch_size, keep) -> None:
    from distributed import as_completed
    from distributed.scheduler import KilledWorker

    check_worker_code(client)

    # The model travels inside each task (a few kB), not scattered once: scattered data lost
    # with a worker cannot be recomputed, and every task needing it would be cancelled.
    pending = {}

    def submit(batch):
        fut = client.submit(run_batch, model, batch, retries=TASK_RETRIES, pure=False)
        pending[fut] = batch
        return fut

    ac = as_completed([submit(b) for b in batches(todo, batch_size)])
    try:
        for fut in ac:
            batch = pending.pop(fut)
            try:
                results = fut.result()
            except KilledWorker as exc:
                if len(batch) > 1:  # find the one that kills its worker: the others still count
                    for single in batches(batch, 1):
                        ac.add(submit(single))
                    continue
                results = [(batch[0][0], {"error": f"the worker running this sample died repeatedly ({exc})",
                                          "values": batch[0][1], "model": model.key})]
            except Exception as exc:  # the task itself failed after its retries: the cluster's
                # fault, not the samples' (a worker without fetorsion, a lost connection), so they
                # are reported but not stored: the next run computes them
                for k, v in batch:
                    keep(k, {"error": f"{type(exc).__name__}: {exc} (not stored: computed again next run)",
                             "values": v, "model": model.key}, persist=False)
                continue
            for key, record in results:
                keep(key, record)
    finally:
        if pending:  # interrupted: no task keeps a worker busy for nobody
            client.cancel(list(pending))
