"""Many model runs on a Dask cluster, each result stored as it arrives.

A study is a list of samples (a dict of input values each) and a model, a picklable callable
``model(values) -> dict of outputs`` with a ``key`` string that says what it computes. Each
sample is keyed by a hash of the model's key, the sample's values and fetorsion's own source
(:func:`code_hash`), and its result is written to a :class:`SampleStore` (one SQLite file,
bounded in size, least recently used records dropped first) the moment its task comes back.
So an interrupted study resumes where it stopped, a re-run computes nothing twice, and a
change of fetorsion's code never serves stale numbers.

The engine is ``dask.distributed``: by default an embedded ``LocalCluster`` of worker
processes sized to the machine, each with one thread and one BLAS thread (workers do not
fight over cores); with ``scheduler="tcp://host:8786"`` (or ``DASK_SCHEDULER_ADDRESS``) the same
study runs on an existing cluster. The client writes the store, so remote workers need no
shared file system, only fetorsion installed. Cheap samples travel in batches (one task of
many samples keeps the scheduler's per-task cost off the samples); a sample that raises is
recorded with its error and the study goes on; a worker lost mid-task is replaced by the
nanny and its tasks rescheduled, and the samples of a task given up after its workers died
run again one at a time, so that only the culprit is recorded as failed.
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
from typing import TYPE_CHECKING, Callable, Iterable

from ..errors import FetorsionError, ParameterError
# the store's folder, bound and code hash live in io (the condensed cranks' cache shares them)
from ..io import (STORE_ENV, STORE_MAX_BYTES, STORE_MAX_ENV, code_hash, default_store,  # noqa: F401
                  store_max_bytes)

if TYPE_CHECKING:
    from distributed import Client

#: Environment of each local worker process: one BLAS/OpenMP thread, the worker's one core.
WORKER_ENV = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
#: Retries of a task whose function raised past the per-sample guard (a lost connection, a
#: worker's memory error); a sample's own exception is recorded, not retried.
TASK_RETRIES = 2
SCHEDULER_ENV = "DASK_SCHEDULER_ADDRESS"
#: How long a named scheduler may take to answer before it is refused, s.
SCHEDULER_TIMEOUT_S = 20.0
def sample_key(model_key: str, values: dict) -> str:
    """Hash of one sample: the model's key, the values (exact floats) and the code."""
    text = json.dumps({"model": model_key, "values": {k: _exact(v) for k, v in values.items()},
                       "code": code_hash()}, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()


def _exact(v):
    return float(v).hex() if isinstance(v, float) else v


STORE_FILE = "samples.sqlite"
#: Keys per SQL statement (SQLite's default limit on host parameters is 32 766).
_SQL_CHUNK = 900


class SampleStore:
    """Every sample's record in one SQLite database, ``FOLDER/samples.sqlite``, bounded in size.

    One file however many samples (SQLite's transactions make each write atomic, and a killed
    writer's journal is rolled back by the next reader). When the records pass ``max_bytes``
    the least recently used go first, down to 90 % of it, and the freed pages are returned to
    the file system: a cache, not an archive. Records of other fetorsion versions are never
    read again (their keys hold another :func:`code_hash`), so they are the first to age out.

    Parameters
    ----------
    folder : str or Path
        The store's folder (created on first write).
    max_bytes : int, optional
        Bound on the records' total size, bytes (default :func:`store_max_bytes`).
    """

    def __init__(self, folder, max_bytes: int | None = None):
        self.folder = Path(folder)
        self.file = self.folder / STORE_FILE
        self.max_bytes = store_max_bytes() if max_bytes is None else int(max_bytes)

    @contextmanager
    def _db(self, write: bool):
        import sqlite3

        if not write and not self.file.exists():
            yield None
            return
        self.folder.mkdir(parents=True, exist_ok=True)
        con = sqlite3.connect(self.file, timeout=60.0, isolation_level=None)
        try:
            # auto_vacuum must precede the first table: pages freed by a trim can then be given back.
            con.execute("PRAGMA auto_vacuum = INCREMENTAL")
            con.execute("PRAGMA synchronous = NORMAL")
            con.execute("CREATE TABLE IF NOT EXISTS samples (key TEXT PRIMARY KEY, record TEXT NOT NULL, "
                        "bytes INTEGER NOT NULL, used REAL NOT NULL) WITHOUT ROWID")
            con.execute("CREATE INDEX IF NOT EXISTS samples_used ON samples (used)")
            yield con
        finally:
            con.close()

    def get_many(self, keys) -> dict[str, dict]:
        """The stored records of ``keys`` (those present and readable), marked as used now."""
        keys = list(dict.fromkeys(keys))
        found: dict[str, dict] = {}
        with self._db(write=False) as con:
            if con is None:
                return found
            for i in range(0, len(keys), _SQL_CHUNK):
                chunk = keys[i:i + _SQL_CHUNK]
                marks = ",".join("?" * len(chunk))
                for key, text in con.execute(f"SELECT key, record FROM samples WHERE key IN ({marks})", chunk):
                    try:
                        found[key] = json.loads(text)
                    except ValueError:  # unreadable: computed again
                        pass
            now = time.time()
            con.execute("BEGIN IMMEDIATE")
            con.executemany("UPDATE samples SET used = ? WHERE key = ?", ((now, k) for k in found))
            con.execute("COMMIT")
        return found

    def get(self, key: str) -> dict | None:
        return self.get_many([key]).get(key)

    def put_many(self, items) -> None:
        """Store (key, record) pairs in one transaction, then keep the store within its bound."""
        rows = [(k, text, len(text), time.time()) for k, text in ((k, json.dumps(r)) for k, r in items)]
        if not rows:
            return
        with self._db(write=True) as con:
            con.execute("BEGIN IMMEDIATE")
            con.executemany("INSERT OR REPLACE INTO samples VALUES (?, ?, ?, ?)", rows)
            con.execute("COMMIT")
            self._trim(con)

    def put(self, key: str, record: dict) -> None:
        self.put_many([(key, record)])

    def _trim(self, con) -> None:
        # The records' text lies in the database's pages, so their sum is at most its size: the
        # sum (a scan of every row) is needed only once the pages alone pass the bound.
        pages = con.execute("PRAGMA page_count").fetchone()[0] * con.execute("PRAGMA page_size").fetchone()[0]
        if pages <= self.max_bytes:
            return
        total = con.execute("SELECT COALESCE(SUM(bytes), 0) FROM samples").fetchone()[0]
        if total <= self.max_bytes:
            return
        excess = total - int(0.9 * self.max_bytes)
        con.execute("BEGIN IMMEDIATE")
        cut = 0
        doomed = []
        for key, size in con.execute("SELECT key, bytes FROM samples ORDER BY used"):
            if cut >= excess:
                break
            doomed.append((key,))
            cut += size
        con.executemany("DELETE FROM samples WHERE key = ?", doomed)
        con.execute("COMMIT")
        con.execute("PRAGMA incremental_vacuum")

    def __contains__(self, key: str) -> bool:
        with self._db(write=False) as con:
            return con is not None and con.execute("SELECT 1 FROM samples WHERE key = ?", (key,)).fetchone() is not None

    def keys(self) -> set[str]:
        with self._db(write=False) as con:
            return set() if con is None else {k for (k,) in con.execute("SELECT key FROM samples")}

    def info(self) -> dict:
        """``file``, ``samples`` (count), ``bytes`` (the file's size on disk) and ``max_bytes``."""
        with self._db(write=False) as con:
            count = 0 if con is None else con.execute("SELECT COUNT(*) FROM samples").fetchone()[0]
        size = self.file.stat().st_size if self.file.exists() else 0
        return {"file": str(self.file), "samples": int(count), "bytes": int(size), "max_bytes": self.max_bytes}

    def describe(self) -> str:
        """One line: where the store is and how full."""
        i = self.info()
        return (f"sample store {i['file']}: {i['samples']} samples, {i['bytes'] / 2**20:.1f} MiB of at most "
                f"{i['max_bytes'] / 2**20:.0f} MiB")

    def clear(self) -> int:
        """Remove the store's database (and a journal beside it); returns the samples it held."""
        n = self.info()["samples"]
        for path in (self.file, self.file.with_name(STORE_FILE + "-journal")):
            path.unlink(missing_ok=True)
        return n


def remove_legacy_store(folder) -> int:
    """Remove the one-JSON-file-per-sample store of earlier fetorsion versions from ``folder``:
    only files named by a sample key (64 hex digits ``.json``) in two-hex-digit shard folders
    (fetorsion's own naming), and those folders once empty. Returns the files removed."""
    folder = Path(folder)
    if not folder.is_dir():
        return 0
    removed = 0
    for shard in folder.iterdir():
        if not (shard.is_dir() and not shard.is_symlink() and len(shard.name) == 2
                and all(c in "0123456789abcdef" for c in shard.name)):
            continue
        for entry in shard.iterdir():
            stem = entry.name.split(".fetorsion-tmp-")[0].lstrip(".").removesuffix(".json")
            if (entry.is_file() and len(stem) == 64 and stem.startswith(shard.name)
                    and all(c in "0123456789abcdef" for c in stem)):
                entry.unlink(missing_ok=True)
                removed += 1
        try:
            shard.rmdir()
        except OSError:  # something else is in it: kept
            pass
    return removed


def open_store(folder: str | Path | None = None, max_bytes: int | None = None) -> SampleStore:
    """The sample store in ``folder`` (default :func:`default_store`), after removing the
    per-file store an earlier fetorsion left there (said on stderr)."""
    folder = Path(folder) if folder is not None else default_store()
    removed = remove_legacy_store(folder)
    if removed:
        print(f"[fetorsion] removed the {removed} one-file-per-sample records of an earlier fetorsion from {folder}",
              file=sys.stderr, flush=True)
    return SampleStore(folder, max_bytes)


def check_store(folder: str | Path, option: str = "store") -> None:
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
        return scheduler, "scheduler"
    env = os.environ.get(SCHEDULER_ENV)
    return (env, SCHEDULER_ENV) if env else (None, "")


def _address_error(where: str, message: str) -> FetorsionError:
    """The error of an address given as the ``scheduler`` argument (a :class:`ParameterError`,
    which the command line names by its option) or read from the environment."""
    return ParameterError("scheduler", message) if where == "scheduler" else FetorsionError(f"{where} {message}")


def check_scheduler(address: str, option: str) -> None:
    """A scheduler address must read ``[tcp://|tls://|inproc://]host:port``."""
    from distributed.comm import parse_address
    from distributed.comm.addressing import parse_host_port

    try:
        proto, loc = parse_address(address if "://" in address else f"tcp://{address}")
        if proto in ("tcp", "tls"):
            parse_host_port(loc)
    except (ValueError, TypeError) as exc:
        raise _address_error(option, f"{address!r}: not a scheduler address such as tcp://host:8786 ({exc})") from None


def machine_workers() -> int:
    """Worker processes of a local cluster: one per core this process may use."""
    return max(1, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1)


@contextmanager
def open_client(scheduler: str | None = None, workers: int | None = None, timeout_s: float | None = None):
    """A ``distributed.Client``: on the scheduler at ``scheduler`` (or ``$DASK_SCHEDULER_ADDRESS``),
    else on an embedded ``LocalCluster`` of ``workers`` processes (default: one per core),
    one thread and one BLAS thread each. Closed (the local cluster shut down) on exit."""
    import logging

    from distributed import Client, LocalCluster

    address, where = scheduler_address(scheduler)
    if address is not None:
        check_scheduler(address, where)
        timeout_s = SCHEDULER_TIMEOUT_S if timeout_s is None else timeout_s
        try:
            client = Client(address, timeout=timeout_s)
        except (OSError, TimeoutError) as exc:
            raise _address_error(where, f"{address}: no scheduler answered within {timeout_s:g} s ({exc})") from None
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
    """A client whose local cluster is started only when some sample must be computed: a
    study whose every sample is stored costs no cluster start. A named scheduler (argument or
    ``$DASK_SCHEDULER_ADDRESS``) is contacted on entering, so a wrong address is refused even
    then. Use as a context manager and pass it where a client goes; arguments as
    :func:`open_client`."""

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
        if scheduler_address(self.scheduler)[0] is not None:  # a named cluster is reached (or refused) now,
            self.get()  # even if every sample turns out to be stored
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


#: Without a cluster, the samples computed within this many seconds, at most this many, are stored
#: in one transaction (the store's bound is kept at each transaction: a batch is what it can overshoot).
SERIAL_FLUSH_S = 1.0
SERIAL_BATCH = 32


#: One stored sample: its ``outputs`` (or ``error``), ``values``, ``model``, ``seconds``, ``worker``.
SampleRecord = dict[str, float | str | dict[str, float | str]]


def run_samples(model: Callable[[dict[str, float]], dict[str, float | str]], samples: list[dict[str, float]],
                store: SampleStore, client: Client | ClusterOnDemand | None = None, batch_size: int | None = None,
                retry_failed: bool = False, label: str = "study",
                on_record: Callable[[str, SampleRecord], None] | None = None,
                progress: bool = True) -> tuple[list[SampleRecord], RunSummary]:
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
    records: dict[str, dict] = {k: r for k, r in store.get_many(keys).items()
                                if "outputs" in r or not retry_failed}
    todo = [(k, s) for k, s in dict(zip(keys, samples)).items() if k not in records]
    stored_before = len(set(keys)) - len(todo)
    bar = Progress(len(set(keys)), stored_before, label) if progress else None
    failed = 0

    def keep(results: list[tuple[str, dict]], persist: bool = True) -> None:
        nonlocal failed
        if persist:  # one transaction per task's results
            store.put_many(results)
        for key, record in results:
            records[key] = record
            failed += "error" in record
            if bar:
                bar.update("error" in record)
            if on_record:
                on_record(key, record)

    if todo and client is None:
        pending, since = [], time.perf_counter()
        try:
            for item in run_each(model, todo):
                pending.append(item)
                # one transaction per batch, not per sample: a store write (and its bound's check)
                # costs more than a lumped sample; a kill loses at most one batch
                if (len(pending) >= SERIAL_BATCH or time.perf_counter() - since >= SERIAL_FLUSH_S
                        or getattr(model, "expensive", False)):
                    batch, pending, since = pending, [], time.perf_counter()
                    keep(batch)
        finally:  # an interrupt keeps what was finished
            if pending:
                keep(pending)
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
    """Run ``todo`` in tasks of ``batch_size`` samples; then each sample of a task whose worker
    died under it, alone.

    Dask gives a task up (KilledWorker) once the workers it was *assigned to* died under it
    ``allowed-failures + 1`` times, and a worker holds more tasks than it runs (one running,
    others queued): an innocent task queued behind the culprit shares its fate by chance. So
    a task lost that way is not judged in the first pass; its samples run afterwards one at a
    time, the only task on the cluster, where a worker that dies can have died of nothing else.
    """
    check_worker_code(client)
    suspects: list[tuple[str, dict]] = []
    _run_tasks(client, model, list(batches(todo, batch_size)), keep, on_killed=suspects.extend)
    for item in suspects:
        _run_tasks(client, model, [[item]], keep, on_killed=None)


def _run_tasks(client, model, tasks, keep, on_killed) -> None:
    """Submit ``tasks`` (lists of (key, values)), hand each finished one's records to ``keep``.

    A task given up after its workers died (KilledWorker) goes to ``on_killed``; with None,
    its one sample is recorded as the culprit.
    """
    from distributed import as_completed
    from distributed.scheduler import KilledWorker

    # The model travels inside each task (a few kB), not scattered once: scattered data lost
    # with a worker cannot be recomputed, and every task needing it would be cancelled.
    pending = {client.submit(run_batch, model, batch, retries=TASK_RETRIES, pure=False): batch for batch in tasks}
    try:
        for fut in as_completed(list(pending)):
            batch = pending.pop(fut)
            try:
                results = fut.result()
            except KilledWorker as exc:
                if on_killed is not None:
                    on_killed(batch)
                    continue
                (key, values), = batch
                results = [(key, {"error": f"the worker running this sample alone died repeatedly ({exc})",
                                  "values": values, "model": model.key})]
            except Exception as exc:  # the task itself failed after its retries: the cluster's
                # fault, not the samples' (a worker without fetorsion, a lost connection), so they
                # are reported but not stored: the next run computes them
                keep([(k, {"error": f"{type(exc).__name__}: {exc} (not stored: computed again next run)",
                           "values": v, "model": model.key}) for k, v in batch], persist=False)
                continue
            keep(results)
    finally:
        if pending:  # interrupted: no task keeps a worker busy for nobody
            client.cancel(list(pending))
