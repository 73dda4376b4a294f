"""Run a call in a forked child, so that a native library's abort becomes an ordinary error.

Gmsh is C++: on some inputs its optimiser throws past its C API and the runtime calls
``abort()``, which ends the whole Python process with no chance to clean up or to say what
happened. Run in a child process, the same failure ends only the child; the parent reads
the child's last words and raises a :class:`~fetorsion.errors.FetorsionError`.
"""

from __future__ import annotations

import faulthandler
import os
import pickle
import signal
import tempfile
import traceback

from ..errors import FetorsionError


def call_isolated(fn, *args, what: str = "the call", **kwargs):
    """``fn(*args, **kwargs)`` computed in a forked child process; its result is returned.

    An exception in the child is raised again here (a :class:`FetorsionError` with its
    message, anything else as a RuntimeError carrying the child's traceback). A child that
    dies without answering (abort, segmentation fault, killed) gives a FetorsionError naming
    ``what``, the signal and the last lines the child wrote to standard error.
    """
    if not hasattr(os, "fork"):
        return fn(*args, **kwargs)
    read_end, write_end = os.pipe()
    with tempfile.TemporaryFile() as err:
        parent = os.getpid()
        pid = os.fork()
        if pid == 0:  # the child: never returns into the caller's code
            status = 1
            try:
                _die_with(parent)
                faulthandler.disable()  # its dump would bypass the redirected standard error
                os.close(read_end)
                os.dup2(err.fileno(), 2)
                try:
                    payload = (True, fn(*args, **kwargs))
                except BaseException as exc:
                    payload = (False, (isinstance(exc, FetorsionError), str(exc), traceback.format_exc()))
                with os.fdopen(write_end, "wb") as fh:
                    pickle.dump(payload, fh, protocol=pickle.HIGHEST_PROTOCOL)
                status = 0
            finally:
                os._exit(status)
        os.close(write_end)
        try:
            with os.fdopen(read_end, "rb") as fh:
                data = fh.read()
        except BaseException:  # interrupted: the child must not outlive us
            os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
            raise
        _, status = os.waitpid(pid, 0)
        if not data:
            err.seek(0)
            tail = [line for line in err.read().decode("utf-8", "replace").splitlines() if line.strip()][-3:]
            how = (f"signal {signal.Signals(os.WTERMSIG(status)).name}" if os.WIFSIGNALED(status)
                   else f"exit status {os.WEXITSTATUS(status)}")
            raise FetorsionError(f"{what} ended abnormally ({how})" + (": " + " | ".join(tail) if tail else ""))
    ok, value = pickle.loads(data)
    if ok:
        return value
    is_user_error, message, trace = value
    if is_user_error:
        raise FetorsionError(message)
    raise RuntimeError(f"{what} failed in its child process:\n{trace}")


def _die_with(parent: int) -> None:
    """Linux: have the kernel kill this child when its parent dies (a SIGKILLed run must not
    leave Gmsh working on as an orphan)."""
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        return
    if os.getppid() != parent:  # the parent died before the request took effect
        os._exit(1)
