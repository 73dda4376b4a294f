"""The ``fetorsion`` program's process settings (fetorsion/cli/process.py)."""

import os
import subprocess
import sys

import pytest

# mallinfo2 (glibc ≥ 2.33) reports the heap's free bytes: what a freed block left there for reuse.
PROBE = r"""
import ctypes, sys
import numpy as np
if {set}:
    from fetorsion.cli.process import keep_freed_memory
    assert keep_freed_memory()
class Info(ctypes.Structure):
    _fields_ = [(n, ctypes.c_size_t) for n in ("arena", "ordblks", "smblks", "hblks", "hblkhd", "usmblks",
                                                "fsmblks", "uordblks", "fordblks", "keepcost")]
libc = ctypes.CDLL(None)
libc.mallinfo2.restype = Info
a = np.ones(100 * 2**20 // 8)  # 100 MB, over glibc's largest mmap threshold (32 MB)
del a
print(libc.mallinfo2().fordblks)
"""


def _glibc_with_mallinfo2() -> bool:
    if not sys.platform.startswith("linux"):
        return False
    import ctypes

    try:
        return bool(ctypes.CDLL(None).mallinfo2)
    except (OSError, AttributeError):
        return False


@pytest.mark.skipif(not _glibc_with_mallinfo2(), reason="glibc ≥ 2.33 only")
def test_the_program_keeps_a_freed_large_block_for_reuse():
    """A freed 100 MB block: with the program's setting it stays in the heap (≥ 100 MB free there),
    without it glibc unmaps it (far less than that left). Fresh interpreters, a clean environment."""
    env = {k: v for k, v in os.environ.items() if not k.startswith("MALLOC_")}
    free = {}
    for on in (False, True):
        out = subprocess.run([sys.executable, "-c", PROBE.format(set=on)], env=env, capture_output=True, text=True,
                             check=True)
        free[on] = int(out.stdout.split()[-1])
    assert free[True] >= 100 * 2**20
    assert free[False] < 10 * 2**20


def test_the_program_passes_its_setting_to_its_children_and_keeps_the_users():
    """The studies' workers are new processes: they read glibc's environment variables, which the
    program sets unless the user has."""
    code = ("import os; from fetorsion.cli.process import keep_freed_memory; keep_freed_memory(); "
            "print(os.environ.get('MALLOC_MMAP_MAX_'), os.environ.get('MALLOC_TRIM_THRESHOLD_'))")
    env = {k: v for k, v in os.environ.items() if not k.startswith("MALLOC_")}
    mine = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    users = subprocess.run([sys.executable, "-c", code], env={**env, "MALLOC_MMAP_MAX_": "7"}, capture_output=True,
                           text=True, check=True)
    if not sys.platform.startswith("linux"):
        assert mine.stdout.split() == ["None", "None"]
        return
    assert mine.stdout.split() == ["0", str(2**31 - 1)]
    assert users.stdout.split()[0] == "7"


def test_the_program_lets_openblas_threads_sleep_here_and_in_its_children():
    """OpenBLAS's idle threads: after the program's setting the loaded OpenBLAS reports the short
    timeout (it re-read its environment), a product is still right on the restarted thread pool,
    and the children inherit the variable; a user's own value is kept."""
    code = ("import os, ctypes, numpy as np; from threadpoolctl import threadpool_info; "
            "from fetorsion.cli.process import release_idle_blas_threads; ok = release_idle_blas_threads(); "
            "libs = [i['filepath'] for i in threadpool_info() if i['internal_api'] == 'openblas']; "
            "a = np.arange(600.0).reshape(30, 20); "
            "right = np.allclose(a.T @ a, np.einsum('ki,kj->ij', a, a), rtol=1e-14, atol=0); "
            "print(ok, [ctypes.CDLL(p).openblas_thread_timeout() for p in libs], right, "
            "os.environ['OPENBLAS_THREAD_TIMEOUT'])")
    env = {k: v for k, v in os.environ.items() if k != "OPENBLAS_THREAD_TIMEOUT"}
    mine = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    words = mine.stdout.split()  # ok, [timeouts], right, the variable
    if words[0] == "False":
        pytest.skip("numpy's BLAS here is not an OpenBLAS with these entry points")
    assert words[-2] == "True" and words[-1] == "4"
    assert all(int(t.strip("[],")) == 4 for t in words[1:-2])
    users = subprocess.run([sys.executable, "-c", code], env={**env, "OPENBLAS_THREAD_TIMEOUT": "9"},
                           capture_output=True, text=True, check=True).stdout.split()
    assert users[-1] == "9" and all(int(t.strip("[],")) == 9 for t in users[1:-2])


def test_a_user_timeout_openblas_cannot_read_does_not_stop_the_program():
    """A value OpenBLAS ignores (not a number) is left to it: the program starts and says the
    pool was reset."""
    code = ("from fetorsion.cli.process import release_idle_blas_threads; import numpy; "
            "print(release_idle_blas_threads())")
    out = subprocess.run([sys.executable, "-c", code], env={**os.environ, "OPENBLAS_THREAD_TIMEOUT": "soon"},
                         capture_output=True, text=True, check=True)
    assert out.stdout.split()[-1] in ("True", "False")
