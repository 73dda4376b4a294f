"""Lowest modes of the free-free pencil K x = ω² M x by shift-invert over a sparse Cholesky.

K is only positive semi-definite (six rigid-body modes), M positive definite, so for a
negative shift σ the matrix K - σ M is symmetric positive definite: a Cholesky
factorisation exists, and the rigid-body modes (ω² = 0) are the eigenvalues nearest σ,
found together with the lowest elastic ones.

Factorisations ("backends"):

``cholmod``
    CHOLMOD supernodal Cholesky from scikit-sparse (needs ``libsuitesparse-dev`` and an
    optimised BLAS such as Debian's ``libopenblas0-pthread``; see ``scripts/setup.sh``).
    The fast choice: issue 4 measured 39 s vs SuperLU running out of memory at 330 k DOF.
``superlu``
    scipy's SuperLU (LU of a symmetric matrix, so twice the work and more fill); the
    fallback that needs nothing beyond scipy, fine up to ~100 k DOF.

Eigen-methods: ``lanczos`` (ARPACK ``eigsh`` in shift-invert mode, default) or ``lobpcg``
(a block method preconditioned by the same factorisation; one multi-right-hand-side solve
per iteration).
"""

from __future__ import annotations

import contextlib
import time
import warnings
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..errors import FetorsionError

BACKENDS = ("cholmod", "superlu")
METHODS = ("lanczos", "lobpcg")


def have_cholmod() -> bool:
    """True when scikit-sparse's CHOLMOD wrapper imports."""
    try:
        import sksparse.cholmod  # noqa: F401
    except ImportError:
        return False
    return True


def default_backend() -> str:
    return "cholmod" if have_cholmod() else "superlu"


def factorize(A: sp.spmatrix, backend: str = "auto"):
    """A callable x = A⁻¹ b (b of shape (n,) or (n, m)) for symmetric positive definite A.

    Parameters
    ----------
    A : sparse matrix
        Symmetric positive definite.
    backend : str
        ``"cholmod"``, ``"superlu"`` or ``"auto"`` (CHOLMOD when installed).
    """
    backend = default_backend() if backend == "auto" else backend
    if backend == "cholmod":
        from sksparse.cholmod import CholmodNotPositiveDefiniteError, cholesky

        try:
            f = cholesky(sp.csc_matrix(A), mode="supernodal")
        except CholmodNotPositiveDefiniteError as err:
            raise FetorsionError(f"K - σM is not positive definite ({err}); is the material valid?") from err
        return f
    if backend == "superlu":
        # Symmetric mode with a symmetric ordering: fill stays close to Cholesky's and no
        # pivoting is needed for a positive definite matrix.
        lu = spla.splu(sp.csc_matrix(A), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                       options={"SymmetricMode": True})
        return lu.solve
    raise FetorsionError(f"unknown solver backend {backend!r}; choose from {BACKENDS} or 'auto'")


@dataclass
class EigenResult:
    """Eigenpairs ascending: ``omega2`` (rad²/s²) and ``vectors`` (n, k), M-orthonormal."""

    omega2: np.ndarray
    vectors: np.ndarray
    timings_s: dict
    backend: str
    method: str


def blas_threads(n: int | None):
    """Context limiting every loaded BLAS (numpy's and CHOLMOD's) to ``n`` threads (None: as is).

    Without threadpoolctl this does nothing.
    """
    if n is None:
        return contextlib.nullcontext()
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:
        return contextlib.nullcontext()
    return threadpool_limits(n, user_api="blas")


def lowest_modes(K, M, k: int, sigma: float, backend: str = "auto", method: str = "lanczos",
                 tol: float = 1e-10, seed: int = 0, iteration_threads: int | None = 1) -> EigenResult:
    """The ``k`` eigenpairs of K x = ω² M x nearest the negative shift ``sigma``.

    Parameters
    ----------
    K, M : sparse matrix, shape (n, n)
        Stiffness (N/m) and mass (kg), symmetric; K - σM positive definite.
    k : int
        Number of modes (rigid-body ones included).
    sigma : float
        Shift, rad²/s², negative.
    backend : str
        ``"cholmod"``, ``"superlu"`` or ``"auto"``.
    method : str
        ``"lanczos"`` (ARPACK shift-invert) or ``"lobpcg"`` (block, factor as preconditioner).
    tol : float
        Relative eigenvalue tolerance.
    seed : int
        Start vector seed, for reproducible runs.
    iteration_threads : int or None
        BLAS threads during the iterations (None: leave as is). The iterations are
        memory-bound vector work and single-right-hand-side triangular solves; with two
        BLAS libraries loaded (numpy's and the system one under CHOLMOD) their spinning
        threads oversubscribe a small machine: on 2 shared cores, 80 k DOF, the Lanczos
        phase took 3.5 s with 1 thread and 12 s with 2. The factorisation keeps all threads.
    """
    if sigma >= 0:
        raise ValueError("the shift must be negative so that K - σM is positive definite")
    backend = default_backend() if backend == "auto" else backend
    t0 = time.perf_counter()
    solve = factorize((K - sigma * M).tocsc(), backend)
    t1 = time.perf_counter()
    rng = np.random.default_rng(seed)
    with blas_threads(iteration_threads):
        w, V = _iterate(K, M, k, sigma, solve, method, tol, rng)
    order = np.argsort(w)
    t2 = time.perf_counter()
    return EigenResult(w[order], V[:, order], {"factorize": t1 - t0, "eigensolve": t2 - t1}, backend, method)


def _iterate(K, M, k, sigma, solve, method, tol, rng):
    n = K.shape[0]
    if method == "lanczos":
        op = spla.LinearOperator((n, n), matvec=lambda b: solve(b), dtype=float)
        ncv = min(n, max(2 * k + 1, k + 32))
        w, V = spla.eigsh(K, k=k, M=M, sigma=sigma, which="LM", OPinv=op, tol=tol, ncv=ncv,
                          v0=rng.standard_normal(n))
    elif method == "lobpcg":
        # On S = K - σM (positive definite: no zero eigenvalues to upset the Rayleigh-Ritz
        # Gram matrices) with S⁻¹ as preconditioner, i.e. block shift-invert; a few guard
        # vectors speed up convergence of the last wanted ones.
        S = (K - sigma * M).tocsr()
        X = rng.standard_normal((n, k + max(8, k // 2)))
        prec = spla.LinearOperator((n, n), matvec=solve, matmat=solve, dtype=float)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            w, V = spla.lobpcg(S, X, B=M, M=prec, largest=False, tol=tol * abs(sigma), maxiter=100)
        w, V = w[:k] + sigma, V[:, :k]
    else:
        raise FetorsionError(f"unknown eigen-method {method!r}; choose from {METHODS}")
    return w, V
