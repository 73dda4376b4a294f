"""Sparse Cholesky of a symmetric positive definite matrix by MKL PARDISO (ctypes, no build).

Why a second sparse Cholesky beside CHOLMOD: on the same node-graph METIS ordering, 2 cores,
PARDISO's numeric factorisation takes 4.1 s against CHOLMOD's 5.4–6.5 s at 342 k DOF (default
crank mesh) and 37.5 s against 45 s at 969 k DOF; its 8-right-hand-side solve 0.33 s against
0.40 s (docs/fe-speed.md).

The library is the ``mkl`` wheel's ``libmkl_rt`` (``pip install mkl``, see ``scripts/setup.sh``),
found next to the running Python (``sys.prefix/lib``) or on the loader path. PARDISO reads
the upper triangle of the matrix in CSR with 0-based 32-bit indices (``iparm[34] = 1``) and
takes the fill-reducing ordering from the caller (``iparm[4] = 1``): the node-graph METIS
ordering of :func:`fetorsion.fe.eigen.group_ordering`, so both backends factor the same
permuted matrix and runs are reproducible (PARDISO's own METIS pass took 3.3 s at 342 k DOF,
the node-graph ordering 1.3 s).
"""

from __future__ import annotations

import ctypes
import ctypes.util
import glob
import os
import sys
import weakref
from functools import cache

import numpy as np
import scipy.sparse as sp

from ..errors import FetorsionError

#: Matrix type "real symmetric positive definite".
_SPD = 2
#: PARDISO phases.
_ANALYSE, _FACTOR, _SOLVE, _RELEASE = 11, 22, 33, -1
#: PARDISO error codes worth naming (the rest are reported by number).
_ERRORS = {-2: "not enough memory", -3: "reordering problem", -4: "zero or negative pivot: the "
           "matrix is not positive definite", -12: "wrong PARDISO version"}

# Intel OpenMP threads otherwise spin 200 ms after each parallel region, on the core that the
# numpy work between two block solves needs (2 cores). A setting of the user's own is kept.
os.environ.setdefault("KMP_BLOCKTIME", "0")


@cache
def _library():
    """``libmkl_rt`` loaded, or None."""
    here = sorted(glob.glob(os.path.join(sys.prefix, "lib", "libmkl_rt.so*")), key=len)
    found = ctypes.util.find_library("mkl_rt")
    for path in here + ([found] if found else []):
        try:
            lib = ctypes.CDLL(path)
        except OSError:
            continue
        lib.pardiso.restype = None
        return lib
    return None


def available() -> bool:
    """True when MKL's PARDISO can be loaded."""
    return _library() is not None


def upper_csr(A) -> sp.csr_matrix:
    """The upper triangle (diagonal included) of a square sparse ``A`` as CSR, sorted indices.

    By masking A's CSR arrays: 0.11 s at 342 k DOF against 1.2 s for ``scipy.sparse.triu``
    (which goes through COO).
    """
    A = sp.csr_matrix(A)
    if not A.has_sorted_indices:
        A = A.sorted_indices()
    row = np.repeat(np.arange(A.shape[0], dtype=A.indices.dtype), np.diff(A.indptr))
    keep = A.indices >= row
    indptr = np.zeros(A.shape[0] + 1, dtype=np.int64)
    np.cumsum(np.bincount(row[keep], minlength=A.shape[0]), out=indptr[1:])
    return sp.csr_matrix((A.data[keep], A.indices[keep], indptr), shape=A.shape)


class Factor:
    """x = A⁻¹ b by PARDISO's Cholesky of a symmetric positive definite ``A``.

    Parameters
    ----------
    A : sparse matrix (n, n)
        Symmetric positive definite; only its upper triangle is read.
    order : ndarray of int (n,), optional
        Fill-reducing ordering: row ``order[j]`` of A is eliminated ``j``-th. None: PARDISO's
        own METIS.

    Calling the object with ``b`` of shape (n,) or (n, m) returns A⁻¹ b (float64). PARDISO's
    memory is released when the object is garbage-collected.
    """

    def __init__(self, A, order: np.ndarray | None = None):
        lib = _library()
        if lib is None:
            raise FetorsionError("MKL PARDISO is not installed (pip install mkl); use backend 'cholmod'")
        U = upper_csr(A)
        if U.nnz >= 2**31:
            raise FetorsionError(f"PARDISO (32-bit indices): {U.nnz} matrix entries are too many")
        self.n = A.shape[0]
        self._a = U.data.astype(np.float64, copy=False)
        self._ia = U.indptr.astype(np.int32, copy=False)
        self._ja = U.indices.astype(np.int32, copy=False)
        self._pt = np.zeros(64, np.int64)
        ip = self._iparm = np.zeros(64, np.int32)
        ip[0] = 1  # these settings, not the defaults
        ip[1] = 2  # METIS when no ordering is given
        ip[17] = -1  # report the factor's size
        ip[34] = 1  # 0-based indices
        self._perm = np.zeros(self.n, np.int32)
        if order is not None:
            order = np.asarray(order)
            if order.shape != (self.n,) or not np.array_equal(np.sort(order), np.arange(self.n)):
                # MKL does not check it, and reads out of bounds on a bad one
                raise FetorsionError(f"PARDISO: the ordering is not a permutation of the {self.n} rows")
            # MKL reads perm as the elimination order itself (measured: 145 M factor entries at
            # 342 k DOF; its inverse ran out of memory).
            self._perm[:] = order
            ip[4] = 1
        self._lib = lib
        # Before the first call: a phase that fails releases what PARDISO holds so far.
        self._finalizer = weakref.finalize(self, _release, lib, self._pt, self._iparm, self.n)
        self._call(_ANALYSE)
        self._call(_FACTOR)

    def _call(self, phase: int, b: np.ndarray | None = None) -> np.ndarray | None:
        nrhs = 1 if b is None else b.shape[1]
        x = None if b is None else np.empty_like(b)
        status = _pardiso(self._lib, self._pt, phase, self.n, self._a, self._ia, self._ja, self._perm, nrhs,
                          self._iparm, b, x)
        if status:
            self._finalizer()
            raise FetorsionError(f"PARDISO phase {phase}: {_ERRORS.get(status, f'error {status}')}")
        return x

    def __call__(self, b) -> np.ndarray:
        """A⁻¹ b, in b's shape and memory order (PARDISO works on columns: a C-ordered block
        is copied in and out, which costs less than the callers' row-wise work on a
        column-ordered result)."""
        b = np.asarray(b)
        B = np.asfortranarray(b.reshape(self.n, -1), dtype=np.float64)
        x = self._call(_SOLVE, B)
        del B  # before the copy out: two blocks of the caller's size at a time, not three
        order = "F" if b.ndim == 2 and b.flags.f_contiguous and not b.flags.c_contiguous else "C"
        return np.asarray(x, order=order).reshape(b.shape)


def _pardiso(lib, pt, phase, n, a, ia, ja, perm, nrhs, iparm, b, x) -> int:
    """One ``pardiso`` call; returns its error code."""
    i32 = ctypes.POINTER(ctypes.c_int32)
    one = ctypes.c_int32(1)
    err = ctypes.c_int32(0)
    null = ctypes.c_void_p()
    lib.pardiso(pt.ctypes.data_as(ctypes.c_void_p), ctypes.byref(one), ctypes.byref(one),
                ctypes.byref(ctypes.c_int32(_SPD)), ctypes.byref(ctypes.c_int32(phase)),
                ctypes.byref(ctypes.c_int32(n)),
                null if a is None else a.ctypes.data_as(ctypes.c_void_p),
                null if ia is None else ia.ctypes.data_as(i32), null if ja is None else ja.ctypes.data_as(i32),
                null if perm is None else perm.ctypes.data_as(i32), ctypes.byref(ctypes.c_int32(nrhs)),
                iparm.ctypes.data_as(i32), ctypes.byref(ctypes.c_int32(0)),
                null if b is None else b.ctypes.data_as(ctypes.c_void_p),
                null if x is None else x.ctypes.data_as(ctypes.c_void_p), ctypes.byref(err))
    return err.value


def _release(lib, pt, iparm, n) -> None:
    """Free PARDISO's internal memory of the handle ``pt`` (phase -1)."""
    if pt.any():
        _pardiso(lib, pt, _RELEASE, n, None, None, None, None, 1, iparm, None, None)
        pt[:] = 0
