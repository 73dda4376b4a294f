"""The ``fetorsion`` program's process: what it sets before the command runs — the allocator
(:func:`keep_freed_memory`) and OpenBLAS's idle threads (:func:`release_idle_blas_threads`).

glibc's ``malloc`` serves every block over 32 MB with a fresh ``mmap`` and gives it back on
``free``. fetorsion's FE work allocates and frees many such blocks (a 322 k × 66 block of
doubles is 170 MB), and each fresh one is paid again in page faults: on this project's 2-core
machine a first touch of 170 MB took 0.35 s beside the factor, a reused one 0.02 s. With
``mmap`` off for the heap and its top kept, freed blocks are reused instead (Renault 21,
``fetorsion run``: 19.1 → 12.2 s of system time, 52.7 → 48.2 s of wall, peak memory 5.3 →
6.0 GB; docs/performance.md). Set for the program only — a library caller's process is its
own — and passed to the processes it starts (the studies' workers) by glibc's environment
variables. Elsewhere than glibc nothing is changed.
"""

from __future__ import annotations

import ctypes
import os
import sys

#: glibc's mallopt parameters (malloc.h).
_M_TRIM_THRESHOLD, _M_MMAP_MAX = -1, -4
#: Heap top kept free before it is given back to the system, bytes (the largest int mallopt takes).
TRIM_THRESHOLD = 2**31 - 1


def keep_freed_memory() -> bool:
    """Make glibc reuse freed large blocks in this process and its children; True when set."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(None)
        mallopt = libc.mallopt
        if not libc.gnu_get_libc_version:  # glibc only: musl's mallopt takes no such parameters
            return False
    except (OSError, AttributeError):
        return False
    # a user's own setting of either wins, here and in the children
    mmap_max = os.environ.setdefault("MALLOC_MMAP_MAX_", "0")
    trim = os.environ.setdefault("MALLOC_TRIM_THRESHOLD_", str(TRIM_THRESHOLD))
    try:
        ok = mallopt(_M_MMAP_MAX, int(mmap_max)) == 1 and mallopt(_M_TRIM_THRESHOLD, int(trim)) == 1
    except (ValueError, ctypes.ArgumentError):
        return False
    return ok


#: OpenBLAS's idle-thread spin, log2 of CPU cycles: its least (its default, 28, spins ~0.1 s).
BLAS_THREAD_TIMEOUT = 4


def release_idle_blas_threads() -> bool:
    """Make OpenBLAS's worker threads sleep as soon as their work is done, in this process and its
    children; True when an OpenBLAS in this process was reset.

    By default an idle OpenBLAS thread spins for 2^28 cycles after each call, and ``fetorsion
    run``'s FE step makes thousands of calls: on 2 cores the spinning took the core its
    background studies run on (six-cylinder benchmark: 115 → 106 CPU-s of user time, 71–73 →
    66 s of wall; docs/performance.md). OpenBLAS reads ``OPENBLAS_THREAD_TIMEOUT`` when it loads,
    which numpy has done by now: the variable is set (for the children, and any OpenBLAS loaded
    later; a user's own setting wins), then read again by OpenBLAS's own ``openblas_read_env``, and
    the thread pool shut down, to start again with it on the next call.
    """
    os.environ.setdefault("OPENBLAS_THREAD_TIMEOUT", str(BLAS_THREAD_TIMEOUT))
    try:
        from threadpoolctl import threadpool_info

        libraries = [i["filepath"] for i in threadpool_info() if i.get("internal_api") == "openblas"]
    except Exception:  # noqa: BLE001 - a probe of the BLAS in use; nothing to change without it
        return False
    done = False
    for path in libraries:
        try:
            lib = ctypes.CDLL(path)
            read_env, shutdown = lib.openblas_read_env, lib.blas_thread_shutdown_
        except (OSError, AttributeError):
            continue
        read_env()  # a user's value OpenBLAS cannot read, it ignores, as at its own start
        shutdown()
        done = True
    return done


def console() -> int:
    """The ``fetorsion`` program: :func:`fetorsion.cli.commands.main` with :func:`keep_freed_memory`
    and :func:`release_idle_blas_threads`."""
    from .commands import main

    keep_freed_memory()
    release_idle_blas_threads()
    return main()
