"""Output policy: atomic writes, and nothing fetorsion did not write is ever replaced.

Every file or folder is written under a temporary sibling name and renamed into place only
on success. Temporary siblings carry :data:`TMP_TAG` and the writer's process id, so a run
killed outright (SIGKILL, a native library's abort) leaves something the next run can
recognise as its own and remove, while a run still in progress is left alone.

Report folders carry :data:`REPORT_MARKER`, a manifest of what fetorsion wrote there. An
existing folder is replaced only when it is empty or holds exactly such a report;
anything else is refused unless the user forces it (:func:`check_report_folder`).
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import shutil
import tempfile
from contextlib import contextmanager
from pathlib import Path

from .errors import FetorsionError

TMP_TAG = ".fetorsion-tmp-"
REPORT_MARKER = ".fetorsion-report"


def _tmp_prefix(path: Path) -> str:
    return f".{path.name}{TMP_TAG}{os.getpid()}-"


def _writer_gone(pid: int, entry: Path) -> bool:
    """Whether the fetorsion process ``pid`` that made ``entry`` has ended: no such process,
    or one that started after ``entry`` was last written (the number was given out again)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    except PermissionError:  # someone else's live process: judged by its start below
        pass
    try:
        import psutil

        return psutil.Process(pid).create_time() > entry.lstat().st_mtime + 1.0
    except Exception:  # psutil missing, or the process ended meanwhile: keep it this time
        return False


def remove_stale_temporaries(folder) -> list[Path]:
    """Remove, directly in ``folder``, the temporaries of fetorsion writers that no longer run.

    Only names made by :func:`atomic_output` / :func:`atomic_folder` (``.NAME`` + :data:`TMP_TAG`
    + a process id + ``-``) whose process is gone are removed, whatever NAME they were for;
    the removed paths are returned. Every fetorsion write calls it on its own folder, so a
    killed run's leftover goes with the next write there.
    """
    folder = Path(folder)
    if not folder.is_dir():
        return []
    removed = []
    for entry in folder.glob(f".*{TMP_TAG}*"):
        pid = entry.name.split(TMP_TAG, 1)[1].split("-", 1)[0]
        if not pid.isdigit() or not _writer_gone(int(pid), entry):
            continue
        if entry.is_dir() and not entry.is_symlink():
            shutil.rmtree(entry, ignore_errors=True)
        else:
            entry.unlink(missing_ok=True)
        removed.append(entry)
    return removed


@contextmanager
def atomic_output(path):
    """Yield a temporary path beside ``path`` (same suffix) to write to; on success it
    replaces ``path`` in one rename, on failure it is removed."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_temporaries(path.parent)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=_tmp_prefix(path), suffix=path.suffix)
    os.close(fd)
    tmp = Path(tmp)
    try:
        yield tmp
        # mkstemp makes the file private (0600); give it the mode a plain open() would.
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def write_text_atomic(path, text: str) -> None:
    """Write ``text`` to ``path`` atomically (UTF-8)."""
    with atomic_output(path) as tmp:
        tmp.write_text(text, encoding="utf-8")


def save_figure_atomic(fig, path, close: bool = False, **kwargs) -> None:
    """Save a matplotlib figure to ``path`` atomically (format from the suffix);
    ``close=True`` also releases the figure."""
    try:
        with atomic_output(path) as tmp:
            fig.savefig(tmp, **kwargs)
    finally:
        if close:
            import matplotlib.pyplot as plt

            plt.close(fig)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


# ---------------------------------------------------------------------------
# Checks made before any work


def _nearest_existing(path: Path) -> Path:
    for parent in (path, *path.parents):
        if os.path.lexists(parent):
            return parent
    return Path(".")


def check_writable_location(path, option: str) -> None:
    """Raise a :class:`FetorsionError` naming ``option`` unless ``path`` can be created:
    its nearest existing ancestor must be a writable folder."""
    path = Path(path)
    base = _nearest_existing(path.parent)
    if not base.is_dir():
        raise FetorsionError(f"{option} {path}: {base} is a file, not a folder")
    if not os.access(base, os.W_OK | os.X_OK):
        raise FetorsionError(f"{option} {path}: no permission to write in {base}")


def check_output_file(path, option: str, suffixes, inputs=()) -> None:
    """Check an output file option before any work.

    Parameters
    ----------
    path : str or Path
        The file the user named.
    option : str
        The option's name, for the message (``--json``).
    suffixes : iterable of str
        Accepted suffixes, lower case with the dot (``.json``).
    inputs : iterable of str or Path
        Files this command reads: writing onto one of them is refused.
    """
    path = Path(path)
    suffixes = tuple(suffixes)
    if path.is_dir():
        raise FetorsionError(f"{option} {path}: is a folder; give a file name")
    if path.suffix.lower() not in suffixes:
        raise FetorsionError(f"{option} {path}: unknown output format {path.suffix or '(no suffix)'!r}; "
                             f"use {', '.join(suffixes)}")
    for source in inputs:
        if source is not None and path.exists() and Path(source).exists() and os.path.samefile(path, source):
            raise FetorsionError(f"{option} {path}: is an input of this command; it would be overwritten")
    if path.exists() and not path.is_file():
        raise FetorsionError(f"{option} {path}: exists and is not a regular file")
    check_writable_location(path, option)


def report_manifest(folder) -> dict | None:
    """The marker of a report folder written by fetorsion, or None."""
    marker = Path(folder) / REPORT_MARKER
    try:
        data = json.loads(marker.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or data.get("written_by") != "fetorsion" or not isinstance(data.get("files"), list):
        return None
    return data


def write_report_manifest(folder) -> None:
    """Mark ``folder`` as a fetorsion report: the marker lists every entry fetorsion put there."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        written_by = version("fetorsion")
    except PackageNotFoundError:  # run from a source tree that was never installed
        written_by = "unknown"
    folder = Path(folder)
    files = sorted(p.name for p in folder.iterdir() if p.name != REPORT_MARKER)
    write_text_atomic(folder / REPORT_MARKER, json.dumps(
        {"written_by": "fetorsion", "version": written_by, "files": files}, indent=1) + "\n")


def check_report_folder(out, option: str = "out", force: bool = False, inputs=(),
                        force_option: str = "force=True") -> None:
    """Refuse, before any work, a report destination that would lose something of the user's.

    ``out`` may be new, an empty folder, or a folder that holds exactly a report fetorsion
    wrote (its marker lists every entry). A regular file, or a folder with anything else,
    is refused unless ``force``; a folder that holds one of ``inputs`` is refused always.
    """
    out = Path(out)
    if os.path.lexists(out) and (out.is_symlink() or not out.is_dir()):
        raise FetorsionError(f"{option} {out}: exists and is not a folder; give a folder name")
    for source in inputs:
        if source is not None and out.is_dir() and _inside(Path(source), out):
            raise FetorsionError(f"{option} {out}: holds the input {source}; the report would replace it")
    if out.is_dir():
        if not os.access(out, os.W_OK | os.X_OK):
            raise FetorsionError(f"{option} {out}: no permission to replace this folder")
        entries = sorted(p.name for p in out.iterdir())
        manifest = report_manifest(out)
        ours = set(manifest["files"]) | {REPORT_MARKER} if manifest else set()
        foreign = [e for e in entries if e not in ours]
        if foreign and not force:
            what = "is not a fetorsion report" if manifest is None else "holds files fetorsion did not write"
            shown = ", ".join(foreign[:5]) + (f" and {len(foreign) - 5} more" if len(foreign) > 5 else "")
            raise FetorsionError(f"{option} {out}: the folder exists and {what} ({shown}); "
                                 f"give a new folder, or {force_option} to replace it")
    check_writable_location(out, option)


def _inside(path: Path, folder: Path) -> bool:
    try:
        path.resolve().relative_to(folder.resolve())
    except ValueError:
        return False
    return True


@contextmanager
def atomic_folder(out):
    """Yield a fresh temporary folder beside ``out``; on success it becomes ``out`` (marked as
    a report, an earlier one replaced only after the rename), on failure it is removed.

    The caller checks ``out`` first with :func:`check_report_folder`.
    """
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_temporaries(out.parent)
    work = Path(tempfile.mkdtemp(prefix=_tmp_prefix(out), dir=out.parent))
    os.chmod(work, 0o777 & ~_umask())  # mkdtemp makes it private (0700)
    try:
        yield work
        write_report_manifest(work)
        _swap_into_place(work, out)
    except BaseException:
        shutil.rmtree(work, ignore_errors=True)
        raise


def _swap_into_place(work: Path, out: Path) -> None:
    """Rename the finished folder onto ``out``; an older one is removed only afterwards."""
    old = None
    if os.path.lexists(out):
        old = Path(tempfile.mkdtemp(prefix=_tmp_prefix(out), dir=out.parent))
        try:
            os.replace(out, old)  # a rename onto the empty folder just made
        except OSError:
            old.rmdir()
            raise
    os.replace(work, out)
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)


# ---------------------------------------------------------------------------
# The store: where computed results are kept between runs

STORE_ENV = "FETORSION_STORE"


def default_store() -> Path:
    """The store's folder (the studies' samples, the condensed cranks): ``$FETORSION_STORE``, else
    ``~/.cache/fetorsion/samples``."""
    env = os.environ.get(STORE_ENV)
    if env:
        return Path(env)
    cache = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(cache) / "fetorsion" / "samples"


_CODE_HASH: str | None = None


def code_hash() -> str:
    """SHA-256 of fetorsion's Python source and shipped data (the ``data/*.json`` tables: the
    stored SCFs and throw stiffnesses answer as the code does): part of every stored key, so
    that results stored by other code (an older checkout, an edited model or table) are never
    taken for this code's."""
    global _CODE_HASH
    if _CODE_HASH is None:
        root = Path(__file__).resolve().parent
        h = hashlib.sha256()
        for path in sorted([*root.rglob("*.py"), *root.rglob("data/*.json")]):
            h.update(str(path.relative_to(root)).encode())
            h.update(path.read_bytes())
        _CODE_HASH = h.hexdigest()
    return _CODE_HASH



#: Default bound of the sample store, bytes (``$FETORSION_STORE_MAX_MB`` overrides): a full
#: ``fetorsion run`` of one description adds about 11 000 lumped samples, ~4 MB.
STORE_MAX_BYTES = 256 * 2**20
STORE_MAX_ENV = "FETORSION_STORE_MAX_MB"


def store_max_bytes() -> int:
    """The store's bound: ``$FETORSION_STORE_MAX_MB`` MiB, else :data:`STORE_MAX_BYTES`."""
    env = os.environ.get(STORE_MAX_ENV)
    if not env:
        return STORE_MAX_BYTES
    try:
        mb = float(env)
    except ValueError:
        mb = -1.0
    if not (mb > 0 and math.isfinite(mb)):
        raise FetorsionError(f"{STORE_MAX_ENV}={env!r}: must be a positive number of MiB")
    return int(mb * 2**20)


class Stages:
    """Progress through a long computation's stages, one line per stage: the stage, the share of
    the expected time done before it, the time so far and the time left at that pace.

    Parameters
    ----------
    what : str
        The computation (``modal``, ``condense``).
    seconds : dict[str, float]
        Each stage's expected time, in the order the stages run (a measured run's: only the
        shares matter).
    say : callable
        Takes each line (print to stderr, say).
    """

    def __init__(self, what: str, seconds: dict[str, float], say):
        import time

        self.what, self.seconds, self.say = what, dict(seconds), say
        self.clock = time.perf_counter
        self.start = self.clock()

    def __call__(self, stage: str) -> None:
        names = list(self.seconds)
        if stage not in self.seconds:
            raise ValueError(f"{self.what}: stage {stage!r} is not one of {names}")
        k = names.index(stage)
        done = sum(self.seconds[n] for n in names[:k]) / sum(self.seconds.values())
        elapsed = self.clock() - self.start
        left = f", about {elapsed * (1 - done) / done:.0f} s left" if done > 0 and elapsed > 0.5 else ""
        self.say(f"{self.what}: {stage} (stage {k + 1} of {len(names)}, {100 * done:.0f} % done, "
                 f"{elapsed:.0f} s{left})")


def available_memory() -> float:
    """Bytes of memory available to a new job (Linux MemAvailable; total RAM elsewhere)."""
    try:
        with open("/proc/meminfo") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return float(line.split()[1]) * 1024.0
    except OSError:
        pass
    return float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"))


def jsonable(x):
    """``x`` with numpy arrays and scalars as lists and Python numbers, dict keys as strings: what
    ``json.dumps`` writes and reads back as it was (a results.json entry)."""
    import numpy as np

    if isinstance(x, dict):
        return {str(k): jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [jsonable(v) for v in x]
    if isinstance(x, np.ndarray):
        return x.tolist()
    if isinstance(x, np.generic):
        return x.item()
    return x
