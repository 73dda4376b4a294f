"""Run a call in a fresh child process, so that a native library's abort becomes an ordinary error.

Gmsh is C++: on some inputs its optimiser throws past its C API and the runtime calls
``abort()``, which ends the whole Python process with no chance to clean up or to say what
happened. Run in a child process, the same failure ends only the child; the parent reads
the child's last words and raises a :class:`~fetorsion.errors.FetorsionError`.

The child is a new interpreter (running :func:`serve`), not a fork: a fork
inherits the parent's thread pools without their threads, and Gmsh then waits forever on
workers that do not exist (seen when the parent had run Gmsh itself). The call and its
result travel pickled through the child's standard input and output, so ``fn`` must be a
module-level function and its arguments picklable.
"""

from __future__ import annotations

import os
import pickle
import signal
import subprocess
import sys
import tempfile
from typing import TYPE_CHECKING

from ..errors import FetorsionError

if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import TypeVar

    _T = TypeVar("_T")

_PARENT_ENV = "FETORSION_ISOLATE_PARENT"


def call_isolated(fn: Callable[..., _T], *args, what: str = "the call", **kwargs) -> _T:
    """``fn(*args, **kwargs)`` computed in a child process; its result is returned.

    An exception in the child is raised again here (a :class:`FetorsionError` with its
    message, anything else as a RuntimeError carrying the child's traceback). A child that
    dies without answering (abort, segmentation fault, killed) gives a FetorsionError naming
    ``what``, the signal and the last lines the child wrote to standard error.
    """
    request = pickle.dumps((fn, args, kwargs), protocol=pickle.HIGHEST_PROTOCOL)
    env = {**os.environ, _PARENT_ENV: str(os.getpid())}
    with tempfile.TemporaryFile() as err:
        proc = subprocess.Popen([sys.executable, "-c", _CHILD], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                stderr=err, env=env)
        try:
            data, _ = proc.communicate(request)
        except BaseException:  # interrupted: the child must not outlive us
            proc.kill()
            proc.wait()
            raise
        if proc.returncode != 0 or not data:
            err.seek(0)
            tail = [line for line in err.read().decode("utf-8", "replace").splitlines() if line.strip()][-3:]
            code = proc.returncode
            how = f"signal {signal.Signals(-code).name}" if code < 0 else f"exit status {code}"
            raise FetorsionError(f"{what} ended abnormally ({how})" + (": " + " | ".join(tail) if tail else ""))
    ok, value = pickle.loads(data)
    if ok:
        return value
    is_user_error, message, trace = value
    if is_user_error:
        raise FetorsionError(message)
    raise RuntimeError(f"{what} failed in its child process:\n{trace}")


def die_with_parent(parent: int) -> None:
    """A child process's first act: on Linux, have the kernel kill it when its parent dies (a
    SIGKILLed run must not leave Gmsh or its studies working on as orphans), and leave at once
    if the parent (pid ``parent``) is already gone."""
    try:
        import ctypes

        ctypes.CDLL(None).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass
    if os.getppid() != parent:
        os._exit(1)


# Only this module (numpy-free) is imported before the child ties itself to its parent.
_CHILD = f"""
import os
from fetorsion.solid.isolate import die_with_parent, serve
die_with_parent(int(os.environ["{_PARENT_ENV}"]))
serve()
"""


def serve() -> None:
    """The child: read one pickled call from standard input, write the pickled outcome."""
    import traceback

    out = sys.stdout.buffer
    sys.stdout = sys.stderr  # anything the call prints must not corrupt the answer
    fn, args, kwargs = pickle.loads(sys.stdin.buffer.read())
    try:
        payload = (True, fn(*args, **kwargs))
    except BaseException as exc:
        payload = (False, (isinstance(exc, FetorsionError), str(exc), traceback.format_exc()))
    out.write(pickle.dumps(payload, protocol=pickle.HIGHEST_PROTOCOL))
    out.flush()

