"""Lowest modes of the free-free pencil K x = ω² M x by shift-invert over a sparse Cholesky.

K is only positive semi-definite (six rigid-body modes), M positive definite, so for a
negative shift σ the matrix K - σ M is symmetric positive definite: a Cholesky
factorisation exists, and the rigid-body modes (ω² = 0) are the eigenvalues nearest σ,
found together with the lowest elastic ones.

Factorisations ("backends"):

``pardiso``
    MKL PARDISO's supernodal Cholesky (:mod:`fetorsion.fe.pardiso`; needs the ``mkl`` wheel,
    ``scripts/setup.sh``), on the same node-graph METIS ordering as CHOLMOD: at 342 k DOF on 2
    cores the numeric factorisation takes 4.1 s against 5.4–6.5 s, a block solve 0.33 s against
    0.40 s. The default where installed.
``cholmod``
    CHOLMOD supernodal Cholesky from scikit-sparse (needs ``libsuitesparse-dev`` and an
    optimised BLAS such as Debian's ``libopenblas0-pthread``; see ``scripts/setup.sh``).
    The fast choice: 39 s measured where SuperLU ran out of memory, at 330 k DOF (docs/fe-speed.md).
``superlu``
    scipy's SuperLU (LU of a symmetric matrix, so twice the work and more fill); the
    fallback that needs nothing beyond scipy, fine up to ~100 k DOF.

Eigen-methods:

``block`` (default)
    Block shift-invert Lanczos (:func:`block_lanczos`): the operator S⁻¹M, S = K - σM, is
    applied to a block of vectors at once, so each application is one multi-right-hand-side
    supernodal solve (dense matrix-matrix work over the supernodes, BLAS-3) instead of one
    memory-bound triangular sweep per vector; full M-reorthogonalisation, Rayleigh-Ritz on
    the whole block Krylov space, thick restart if it ever grows past its cap.
``lanczos``
    ARPACK ``eigsh`` in shift-invert mode, one vector at a time: the reference the block
    solver is tested against.
``lobpcg``
    scipy's LOBPCG preconditioned by the same factorisation (one multi-right-hand-side
    solve per iteration); kept for comparison.
"""

from __future__ import annotations

import contextlib
import os
import time
import warnings
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..errors import FetorsionError

#: Relative residual at which an eigenpair is converged (block Lanczos, ARPACK).
EIGEN_TOL = 1e-10
#: Directions whose M-norm falls below this share of the block's largest are dropped as
#: linearly dependent when a block is M-orthonormalised.
ORTHO_DROP = 1e-10

# CHOLMOD's OpenMP threads otherwise spin after each parallel region and take the core that
# the BLAS thread of the factorisation needs: on 2 cores, 342 k DOF, passive waiting cut the
# numeric factorisation from 6.5 to 5.4 s. Read when libgomp loads (with CHOLMOD, lazily);
# a setting of the user's own is kept.
os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

#: CPU features of OpenBLAS's AVX-512 ("SkylakeX") kernels.
AVX512_FLAGS = frozenset({"avx512f", "avx512cd", "avx512bw", "avx512dq", "avx512vl"})


def avx512_coretype(cpuinfo: str) -> str | None:
    """``"SkylakeX"`` when the CPU flags in ``cpuinfo`` (/proc/cpuinfo text) cover OpenBLAS's
    AVX-512 kernels, else None.

    Debian 12's OpenBLAS 0.3.21 predates AMD Zen 4/5 and runs them on its AVX2 ("Haswell")
    kernels; named explicitly, the AVX-512 ones cut CHOLMOD's numeric factorisation at 969 k DOF
    from 45.2 to 37.5 s (user time 46 → 32 s) on a Zen 5 (family 26), 2 cores.
    """
    for line in cpuinfo.splitlines():
        if line.startswith("flags"):
            return "SkylakeX" if AVX512_FLAGS <= set(line.split(":", 1)[1].split()) else None
    return None


def _choose_blas_kernels() -> None:
    """Name the AVX-512 kernels for the system OpenBLAS under CHOLMOD where the CPU has them
    (read when that library loads, lazily with CHOLMOD; a setting of the user's own is kept)."""
    if "OPENBLAS_CORETYPE" in os.environ:
        return
    try:
        with open("/proc/cpuinfo") as f:
            core = avx512_coretype(f.read(200_000))
    except OSError:
        return
    if core:
        os.environ["OPENBLAS_CORETYPE"] = core


_choose_blas_kernels()

BACKENDS = ("pardiso", "cholmod", "superlu")
METHODS = ("block", "lanczos", "lobpcg")


def have_cholmod() -> bool:
    """True when scikit-sparse's CHOLMOD wrapper imports."""
    try:
        import sksparse.cholmod  # noqa: F401
    except ImportError:
        return False
    return True


def default_backend() -> str:
    from . import pardiso

    return "pardiso" if pardiso.available() else "cholmod" if have_cholmod() else "superlu"


def factorize(A: sp.spmatrix, backend: str = "auto", groups: np.ndarray | None = None):
    """A callable x = A⁻¹ b (b of shape (n,) or (n, m)) for symmetric positive definite A.

    Parameters
    ----------
    A : sparse matrix
        Symmetric positive definite.
    backend : str
        ``"pardiso"``, ``"cholmod"``, ``"superlu"`` or ``"auto"`` (the first one installed).
    groups : ndarray of int, optional
        DOF groups that share one sparsity pattern (a mesh node's three displacements, a
        rigid body's six), as pointers: group j is DOFs ``groups[j]:groups[j + 1]``, covering
        all of A. With CHOLMOD's METIS available, the fill-reducing ordering is then computed
        on the graph of the groups (:func:`group_ordering`) instead of on A's.
    """
    backend = default_backend() if backend == "auto" else backend
    if backend == "pardiso":
        from . import pardiso

        order = group_ordering(A, groups) if groups is not None and have_cholmod() else None
        return pardiso.Factor(A, order)
    A = _as_csc_symmetric(A)
    if backend == "cholmod":
        from sksparse.cholmod import CholmodNotPositiveDefiniteError, cholesky

        perm = group_ordering(A, groups) if groups is not None else None
        if perm is not None:
            A = _as_csc_symmetric(A.tocsr()[perm][:, perm])
        try:
            # METIS: CHOLMOD's default tries AMD first and keeps METIS anyway on these 3D
            # meshes (10-20 % less fill), so the AMD pass is wasted (0.3 s at 120 k DOF).
            f = cholesky(A, mode="supernodal", ordering_method="natural" if perm is not None else _cholmod_ordering())
        except CholmodNotPositiveDefiniteError as err:
            raise FetorsionError(f"K - σM is not positive definite ({err}); is the material valid?") from err
        return f if perm is None else _permuted_solve(f, perm)
    if backend == "superlu":
        # Symmetric mode with a symmetric ordering: fill stays close to Cholesky's and no
        # pivoting is needed for a positive definite matrix.
        lu = spla.splu(A, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                       options={"SymmetricMode": True})
        return lu.solve
    raise FetorsionError(f"unknown solver backend {backend!r}; choose from {BACKENDS} or 'auto'")


def group_ordering(A, groups: np.ndarray) -> np.ndarray | None:
    """Fill-reducing permutation of A's DOFs from METIS on the graph of its DOF ``groups``.

    Every DOF of a group has the same neighbours, so ordering the group graph (a third of the
    rows, a ninth of the entries for 3D solids) and keeping each group's DOFs together loses
    little: at 342 k DOF the ordering took 1.3 s instead of CHOLMOD's 3.0 s on A itself, for
    2 % more fill (144 M against 141 M entries in L). None when CHOLMOD has no METIS or the groups do not cover A.
    """
    from sksparse.cholmod import analyze

    groups = np.asarray(groups, dtype=np.int64)
    sizes = np.diff(groups)
    if groups[0] != 0 or groups[-1] != A.shape[0] or (sizes <= 0).any() or _cholmod_ordering() != "metis":
        return None
    rep = groups[:-1]
    G = sp.csr_matrix(A.tocsr()[rep][:, rep], copy=True)
    G.data[:] = 1.0
    G.setdiag(len(rep))  # any positive definite values: analyze reads the pattern only
    p = analyze(sp.csc_matrix(G), mode="simplicial", ordering_method="metis").P()
    first = np.repeat(groups[p], sizes[p])
    within = np.arange(A.shape[0]) - np.repeat(np.cumsum(sizes[p]) - sizes[p], sizes[p])
    return first + within


def _permuted_solve(factor, perm: np.ndarray):
    """x = A⁻¹ b from the factor of A[perm][:, perm]."""
    def solve(b):
        b = np.asarray(b)
        x = np.empty_like(b, dtype=float)
        x[perm] = factor(b[perm])
        return x

    return solve


def shifted(K, M, sigma: float):
    """K − σM as CSR; when K and M share one CSR structure (:func:`fetorsion.fe.assembly.block_pattern`),
    by combining their values (no sparse addition: 1 s at 342 k DOF)."""
    if sp.issparse(K) and sp.issparse(M) and K.format == M.format == "csr" and K.shape == M.shape and (
            K.indices is M.indices and K.indptr is M.indptr):
        return sp.csr_matrix((K.data - sigma * M.data, K.indices, K.indptr), shape=K.shape)
    return sp.csr_matrix(K - sigma * M)


def _cholmod_ordering() -> str:
    """``"metis"`` when CHOLMOD was built with it (Debian's is), else its default."""
    from sksparse.cholmod import CholmodError, analyze

    try:
        analyze(sp.eye(3, format="csc"), ordering_method="metis")
    except CholmodError:
        return "default"
    return "metis"


def _as_csc_symmetric(A) -> sp.csc_matrix:
    """CSC of a symmetric A; a CSR one is reread as CSC (its transpose, i.e. itself) without
    the copy and sort that ``tocsc`` makes (0.5 s at 1 M DOF)."""
    if A.format == "csr":
        return sp.csc_matrix((A.data, A.indices, A.indptr), shape=A.shape)
    return sp.csc_matrix(A)


@dataclass
class EigenResult:
    """Eigenpairs ascending: ``omega2`` (rad²/s²) and ``vectors`` (n, k), M-orthonormal."""

    omega2: np.ndarray
    vectors: np.ndarray
    timings_s: dict[str, float]
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


def numpy_blas_threads(n: int | None):
    """Context limiting only numpy's (wheel-bundled) BLAS to ``n`` threads, leaving the
    system BLAS under CHOLMOD as is. Without threadpoolctl this does nothing.

    The block solver's dense products are numpy's and its block solves CHOLMOD's: two
    OpenBLAS thread pools whose idle threads spin. On 2 cores, 120 k DOF, the block
    eigen-solve took 29 s with both pools at 2 threads and 3.6 s with numpy's at 1.
    """
    if n is None:
        return contextlib.nullcontext()
    try:
        from threadpoolctl import ThreadpoolController
    except ImportError:
        return contextlib.nullcontext()
    import os

    ctl = ThreadpoolController()
    here = os.path.dirname(os.path.dirname(np.__file__))  # site-packages
    mine = [lib["filepath"] for lib in ctl.info() if lib["user_api"] == "blas" and lib["filepath"].startswith(here)]
    return ctl.select(filepath=mine).limit(limits=n) if mine else contextlib.nullcontext()


def lowest_modes(K, M, k: int, sigma: float, backend: str = "auto", method: str = "block",
                 tol: float = EIGEN_TOL, seed: int = 0, iteration_threads: int | None = 1,
                 groups: np.ndarray | None = None, null_space: np.ndarray | None = None,
                 S=None) -> EigenResult:
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
        ``"pardiso"``, ``"cholmod"``, ``"superlu"`` or ``"auto"``.
    method : str
        ``"block"`` (block shift-invert Lanczos, default), ``"lanczos"`` (ARPACK
        shift-invert, one vector at a time) or ``"lobpcg"`` (factor as preconditioner).
    tol : float
        Relative eigenvalue tolerance.
    seed : int
        Start vector seed, for reproducible runs.
    iteration_threads : int or None
        BLAS threads during the ``lanczos`` and ``lobpcg`` iterations (None: leave as is).
        Those are memory-bound vector work and single-right-hand-side triangular solves;
        with two BLAS libraries loaded (numpy's and the system one under CHOLMOD) their
        spinning threads oversubscribe a small machine: on 2 shared cores, 80 k DOF, the
        Lanczos phase took 3.5 s with 1 thread and 12 s with 2. The factorisation and the
        ``block`` method (matrix-matrix work) keep all threads.
    groups : ndarray of int, optional
        DOF group pointers for the ordering (see :func:`factorize`).
    null_space : ndarray (n, r), optional
        A basis of K's null space known exactly (the rigid-body motions), counted among the
        ``k``. The ``block`` method starts its Krylov space from it and only iterates for the
        other k − r pairs (at 342 k DOF, 20 elastic modes: 14 block solves instead of 15);
        the other methods ignore it.
    S : sparse matrix, optional
        K − σM formed by the caller (in K's own memory: one matrix of that size less at the
        peak); K may then be None.
    """
    if sigma >= 0:
        raise ValueError("the shift must be negative so that K - σM is positive definite")
    backend = default_backend() if backend == "auto" else backend
    t0 = time.perf_counter()
    S = shifted(K, M, sigma) if S is None else S
    solve = factorize(S, backend, groups)
    t1 = time.perf_counter()
    rng = np.random.default_rng(seed)
    threads = numpy_blas_threads(1) if method == "block" else blas_threads(iteration_threads)
    with threads:
        w, V = _iterate(S, M, k, sigma, solve, method, tol, rng, null_space)
    order = np.argsort(w)
    t2 = time.perf_counter()
    return EigenResult(w[order], V[:, order], {"factorize": t1 - t0, "eigensolve": t2 - t1}, backend, method)


def _iterate(S, M, k, sigma, solve, method, tol, rng, null_space=None):
    n = S.shape[0]
    if method == "block":
        # K u = 0 for u in the null space, so S⁻¹M u = u / (0 − σ)
        known = None if null_space is None else (null_space, -1.0 / sigma)
        w, V = block_lanczos(solve, M, k, rng, tol=tol, known=known)
        w = sigma + 1.0 / w
    elif method == "lanczos":
        op = spla.LinearOperator((n, n), matvec=lambda b: solve(b), dtype=float)
        ncv = min(n, max(2 * k + 1, k + 32))
        w, V = spla.eigsh(S + sigma * M, k=k, M=M, sigma=sigma, which="LM", OPinv=op, tol=tol, ncv=ncv,
                          v0=rng.standard_normal(n))
    elif method == "lobpcg":
        # On S = K - σM (positive definite: no zero eigenvalues to upset the Rayleigh-Ritz
        # Gram matrices) with S⁻¹ as preconditioner, i.e. block shift-invert; a few guard
        # vectors speed up convergence of the last wanted ones.
        X = rng.standard_normal((n, k + max(8, k // 2)))
        prec = spla.LinearOperator((n, n), matvec=solve, matmat=solve, dtype=float)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            w, V = spla.lobpcg(S, X, B=M, M=prec, largest=False, tol=tol * abs(sigma), maxiter=100)
        w, V = w[:k] + sigma, V[:, :k]
    else:
        raise FetorsionError(f"unknown eigen-method {method!r}; choose from {METHODS}")
    return w, V


#: Block Lanczos: block width and the cap on the Krylov space (columns) before a thick restart.
#: On the 170 k-DOF Peugeot modal mesh, 26 pairs: width 16 converged in 4-5 block solves.
BLOCK_WIDTH = 8


def _svqb(W: np.ndarray, MW: np.ndarray, drop: float):
    """(U, s): the kept eigenvectors of the Gram matrix Wᵀ M W and the square roots of their
    eigenvalues, directions below ``drop`` of the largest dropped."""
    G = W.T @ MW
    G = 0.5 * (G + G.T)
    d, U = np.linalg.eigh(G)
    keep = d > drop * max(d.max(), 0.0)
    return U[:, keep], np.sqrt(d[keep])


def svqb_coefficients(W: np.ndarray, MW: np.ndarray, drop: float = ORTHO_DROP) -> np.ndarray:
    """C such that W C is an M-orthonormal basis of W's columns (given MW = M W), by SVQB; C may
    have fewer columns than W when W is (numerically) rank deficient."""
    U, s = _svqb(W, MW, drop)
    return U / s


def m_orthonormalize(W: np.ndarray, MW: np.ndarray, drop: float = ORTHO_DROP):
    """M-orthonormal basis of the columns of W (given MW = M W) by SVQB (eigen-decomposition
    of the Gram matrix), dropping directions below ``drop`` of the largest.

    Returns (V, MV, R) with W ≈ V R, Vᵀ M V = I; V may have fewer columns than W when W is
    (numerically) rank deficient.
    """
    U, s = _svqb(W, MW, drop)
    C = U / s
    return W @ C, MW @ C, (U * s).T


def block_lanczos(solve, M, k: int, rng, *, tol: float = EIGEN_TOL, width: int | None = None,
                  max_dim: int | None = None, max_restarts: int = 20, project=None, known=None, start=None):
    """The ``k`` largest eigenpairs θ of the M-self-adjoint operator A = S⁻¹M.

    Block Lanczos with full reorthogonalisation in the M inner product: each step applies A
    to a block of ``width`` vectors with one multi-right-hand-side ``solve`` (the BLAS-3
    path of a supernodal Cholesky), M-orthogonalises the result twice against the whole
    basis (classical Gram-Schmidt, blocked), and M-orthonormalises it (SVQB). Rayleigh-Ritz
    uses the full projected matrix T = Qᵀ M A Q (symmetrised). A Ritz pair (θ, Q s) has
    residual ‖A x − θ x‖_M = ‖R s_last‖, with R the coefficients of the next block and
    s_last the last block of s, the same criterion as ARPACK's (‖r‖ ≤ tol·θ). When the basis
    would outgrow ``max_dim`` columns, it restarts from its best Ritz vectors plus the next
    block (thick restart, exact: A Y = Y Θ + V_next R S_last).

    Parameters
    ----------
    solve : callable
        x = S⁻¹ b for b of shape (n, m).
    M : sparse matrix (n, n)
        Mass matrix, kg (positive definite).
    k : int
        Number of eigenpairs.
    rng : numpy.random.Generator
        For the random start block (reproducible runs).
    tol : float
        Relative residual tolerance.
    width : int, optional
        Block width (default :data:`BLOCK_WIDTH`, at least 6 for the six rigid-body modes).
    max_dim : int, optional
        Krylov space cap, columns (default max(5k, k + 8·width), at most n: at the default
        mesh, 26 pairs, the space converges at 120 columns, and a restart below that
        repeated two block solves; the cap costs 2 (n × cap) arrays, 0.7 GB at 342 k DOF).
    project : callable, optional
        Maps a block of random vectors into the space the operator works in (a constrained
        operator's range, e.g. ``lambda V: solve(M @ V)``); default: none needed.
    known : tuple (X, θ), optional
        An exact invariant subspace (columns of X, n × r, r < k) whose eigenvalues all equal
        θ: it opens the basis, so the Krylov space grows in its M-complement and the
        iteration converges the other k − r pairs only.
    start : ndarray (n, p), optional
        The first block instead of a random one (its width then that of every block): good
        approximations of the wanted vectors (Ritz vectors of a reduced model) make the
        iteration converge in one or two block solves. Same result, same tolerance.

    Returns
    -------
    theta : ndarray (k,)
        Eigenvalues of A, descending; for shift-invert, ω² = σ + 1/θ.
    X : ndarray (n, k)
        M-orthonormal eigenvectors.
    """
    n = M.shape[0]
    M = drop_zeros(M)
    b = min(width or BLOCK_WIDTH, n) if start is None else np.shape(start)[1]
    cap = min(n, max_dim or (max(5 * k, k + 8 * b) if start is None else max(5 * k, k + 3 * b)))
    if k >= cap:
        raise FetorsionError(f"block Lanczos: {k} eigenpairs need more than the {n} DOF")
    # The basis and its M-image: Gram-Schmidt coefficients Qᵀ M W = (MQ)ᵀ W then need no
    # sparse product, which on 120 k DOF took more time than the block solves.
    Q = np.empty((n, cap + b), order="F")
    MQ = np.empty((n, cap + b), order="F")
    T = np.zeros((cap + b, cap + b))
    m = 0  # basis columns whose image under A is in T
    if known is not None:
        X0, MX0, theta0 = _known_block(M, known, k)
        m = X0.shape[1]
        Q[:, :m], MQ[:, :m] = X0, MX0
        T[np.arange(m), np.arange(m)] = theta0
    if start is None:
        V, MV, _ = _random_block(M, rng, b, Q[:, :m], MQ[:, :m], project)
    else:
        V, MV = _start_block(M, start, Q[:, :m], MQ[:, :m], project)
    for _ in range(max_restarts + 1):
        while True:
            p = V.shape[1]
            Q[:, m:m + p], MQ[:, m:m + p] = V, MV
            W = np.asarray(solve(MV)).reshape(n, p)
            Qm, MQm = Q[:, :m + p], MQ[:, :m + p]
            C = MQm.T @ W
            W -= Qm @ C
            c = MQm.T @ W  # second pass: classical Gram-Schmidt twice is enough (Kahan-Parlett)
            W -= Qm @ c
            C += c
            V, MV, R = m_orthonormalize(W, M @ W)
            T[:m + p, m:m + p] = C
            m += p
            theta, S = np.linalg.eigh(0.5 * (T[:m, :m] + T[:m, :m].T))
            theta, S = theta[::-1], S[:, ::-1]  # descending: wanted first
            resid = np.linalg.norm(R @ S[m - p:m, :k], axis=0)
            if m >= k and np.all(resid <= tol * np.abs(theta[:k])):
                return theta[:k], Qm @ S[:, :k]
            if V.shape[1] == 0:  # an invariant subspace: go on from fresh directions
                V, MV, R = _random_block(M, rng, b, Q[:, :m], MQ[:, :m], project)
                R = np.zeros((V.shape[1], p))
            if m + V.shape[1] > cap:
                break
            T[m:m + V.shape[1], m - p:m] = R
        # thick restart from the best Ritz vectors (wanted plus guards): A Y = Y Θ + V R S_last
        keep = min(k + max(b, k // 2), m - 1)
        Q[:, :keep] = Qm @ S[:, :keep]
        MQ[:, :keep] = MQm @ S[:, :keep]
        T[:] = 0.0
        T[np.arange(keep), np.arange(keep)] = theta[:keep]
        T[keep:keep + V.shape[1], :keep] = R @ S[m - p:m, :keep]
        m = keep
    raise FetorsionError(f"block Lanczos did not converge to tol {tol:g} in {max_restarts} restarts")


def _known_block(M, known, k: int):
    """The known invariant subspace (X, θ) M-orthonormalised: (X, M X, θ); refused when it holds all ``k`` pairs."""
    X0, theta0 = known
    X0 = np.asarray(X0, dtype=float).reshape(M.shape[0], -1)
    X0, MX0, _ = m_orthonormalize(X0, M @ X0)
    if X0.shape[1] >= k:
        raise FetorsionError(f"block Lanczos: {k} eigenpairs asked, {X0.shape[1]} already known")
    return X0, MX0, theta0


def _start_block(M, start, Q: np.ndarray, MQ: np.ndarray, project):
    """The given first block, projected, M-orthogonalised twice against the basis Q and M-orthonormalised: (V, M V)."""
    V = np.array(start, dtype=float).reshape(M.shape[0], -1)
    if project is not None:
        V = np.asarray(project(V))
    for _ in range(2):
        V -= Q @ (MQ.T @ V)
    V, MV, _ = m_orthonormalize(V, M @ V)
    return V, MV


def drop_zeros(M):
    """A sparse M without its explicit zeros (a copy only when there are any); anything else
    (an operator with ``@``) as it is.

    The assembled mass keeps K's 3 × 3 block structure, two thirds of it zeros (ρ ∫ φ_a φ_b ⊗ I₃);
    the solver multiplies by M once per block, 16 times at the default mesh.
    """
    if not sp.issparse(M) or np.count_nonzero(M.data) == M.nnz:
        return M
    M = M.copy()
    M.eliminate_zeros()
    return M


def _random_block(M, rng, b, Q, MQ, project=None):
    """``b`` random directions, M-orthogonal to Q (MQ = M Q) and M-orthonormal: (V, MV, R)."""
    V = rng.standard_normal((M.shape[0], b))
    if project is not None:
        V = np.asarray(project(V))
    for _ in range(2):
        V -= Q @ (MQ.T @ V)
    return m_orthonormalize(V, M @ V)


