"""The nonlinear time domain compiled: Dormand–Prince 5(4) with error control, the slider-crank's
variable inertia and exact Jenkins friction elements, in one numba kernel.

The equations are those of :mod:`fetorsion.response.nonlinear` (its docs derive them):

    (M + Wᵀ diag δJ(θ) W) q̈ = F(t) − C q̇ − K q − Wᵀ (½ δJ'(θ) θ̇² + δJ(θ) α) − Dᵀ T_e(D q, z).

What differs from the scipy path is how the friction state z is carried. There, z follows Bouc–Wen's
rate law with rounded corners, a stiff equation (its slip rate n ẋ/z_s reaches 10⁷ /s on a dual-mass
flywheel's arc springs) that drives LSODA to about a hundred evaluations per sample. Here each
friction element is the elastic-perfectly-plastic (Jenkins) element itself, written as its exact
return map: over a step from (x_n, z_n), z(x) = clip(z_n + x − x_n, −z_s, z_s), z_s = T_f/k_s [Jenkins].
That is exact while the twist x is monotone in the step (a reversal inside one step is met to the
step's error control, since the torque stays continuous in x), and it leaves no stiff state: the
error-controlled explicit steps are set by the structure's own modes, about one Dormand–Prince step
per sample at the 0.5° sample step.

The load F, the mean angle φ and speed Ω are given on the uniform sample grid and read linearly
between samples: the same first-order hold the exact linear propagator uses (F's error
(qΔθ)²/8 at order q; φ's α h²/8, below 10⁻⁸ rad at the shipped steps). The acceleration α is the
speed's slope in each sample interval (exact for the piecewise-linear schedules of
:func:`fetorsion.response.transient_load.speed_schedule` and its held start).

The kernel is compiled once per machine (numba's on-disk cache, ``cache=True``) and takes about 2 s to
compile the first time.
"""

from __future__ import annotations

import numpy as np
from numba import njit

# Dormand & Prince (1980) RK5(4)7M [DormandPrince]: nodes, the stage matrix, the 5th-order weights (the
# last stage is the first of the next step: FSAL) and the error weights (5th minus embedded 4th order).
_C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0])
_A = np.array([
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [1 / 5, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3 / 40, 9 / 40, 0.0, 0.0, 0.0, 0.0],
    [44 / 45, -56 / 15, 32 / 9, 0.0, 0.0, 0.0],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0.0, 0.0],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656, 0.0],
    [35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84],
])
_E = np.array([71 / 57600, 0.0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40])
#: Step-size control: safety factor, largest and smallest change of the step, the error exponent.
_SAFETY, _GROW, _SHRINK, _EXPONENT = 0.9, 5.0, 0.2, -1.0 / 5.0
#: Substeps within one sample interval before the kernel gives up (the error control has failed).
MAX_SUBSTEPS = 100_000


@njit(cache=True)
def _elastic(x, k, edges, n):
    """Piecewise-linear elastic torque at twist x: side 0 (drive, x ≥ 0) or 1 (coast) of the element's
    curve, stage s of stiffness k[side, s] from edges[side, s]."""
    side = 0 if x >= 0 else 1
    a = abs(x)
    t = 0.0
    for s in range(n[side]):
        hi = edges[side, s + 1] if s + 1 < n[side] else np.inf
        if a > edges[side, s]:
            t += k[side, s] * (min(a, hi) - edges[side, s])
    return t if x >= 0 else -t


@njit(cache=True)
def _element_torque(e, xs, xsn, zn, x0, preload, tf, ks, kst, edges, nst):
    """Element e's vibratory torque (preload off) with its spring twist ``xs`` on the path from ``xsn``,
    where its friction state was ``zn``: the damper's elastic curve and its Jenkins friction."""
    t = _elastic(x0[e] + xs, kst[e], edges[e], nst[e]) - preload[e]
    if tf[e] > 0:
        zs = tf[e] / ks[e]
        t += ks[e] * min(max(zn + xs - xsn, -zs), zs)
    return t


@njit(cache=True)
def _slip_point(e, xsn, xs, zn, target, x0, preload, tf, ks, kst, edges, nst):
    """The spring twist on [xsn, xs] where the damper's torque (preload on) reaches ``target``: the
    torque is monotone along the path, so bisection (to round-off) finds it."""
    lo, hi = xsn, xs
    up = xs > xsn
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid == lo or mid == hi:
            break
        over = preload[e] + _element_torque(e, mid, xsn, zn, x0, preload, tf, ks, kst, edges, nst) > target
        if over == up:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


@njit(cache=True)
def _solve_small(A, b):
    """A x = b for a small dense A (Gaussian elimination, partial pivoting); A and b are overwritten."""
    n = b.size
    for i in range(n):
        p = i
        for j in range(i + 1, n):
            if abs(A[j, i]) > abs(A[p, i]):
                p = j
        if p != i:
            for c in range(n):
                A[i, c], A[p, c] = A[p, c], A[i, c]
            b[i], b[p] = b[p], b[i]
        for j in range(i + 1, n):
            f = A[j, i] / A[i, i]
            for c in range(i, n):
                A[j, c] -= f * A[i, c]
            b[j] -= f * b[i]
    for i in range(n - 1, -1, -1):
        s = b[i]
        for c in range(i + 1, n):
            s -= A[i, c] * b[c]
        b[i] = s / A[i, i]
    return b


@njit(cache=True)
def _acceleration(out, s, q, v, F, phi, omega, alpha, Minv, K, C,
                  W, fire, crank_r, crank_l, crank_m, mean, B, P,
                  D, x0, preload, tf, ks, kst, edges, nst, cap, xn, zn, sn, f, wc, A):
    """q̈ into ``out`` at fraction s of a sample interval (F, phi, omega: the interval's two ends;
    xn, zn, sn: the elements' twists, friction states and slips at the step's start).
    Loops, not BLAS calls: at a few tens of coordinates a call's overhead is most of its cost; ``f``
    (r) and ``wc`` (5, cylinders), ``A`` (cylinders, cylinders) are scratch."""
    _linear_forces(f, s, q, v, F, K, C)
    _element_forces(f, q, D, x0, preload, tf, ks, kst, edges, nst, cap, xn, zn, sn)
    c = fire.size
    if c:
        _crank_forces(f, s, q, v, phi, omega, alpha, W, fire, crank_r, crank_l, crank_m, mean, wc)
    r = q.size
    for i in range(r):
        acc = 0.0
        for j in range(r):
            acc += Minv[i, j] * f[j]
        out[i] = acc
    if c:
        _variable_inertia_correction(out, W, B, P, wc, A)


@njit(cache=True, inline="always")
def _linear_forces(f, s, q, v, F, K, C):
    """f = F(s) − C q̇ − K q, the load read linearly at fraction s of the interval."""
    r = q.size
    for i in range(r):
        acc = (1.0 - s) * F[0, i] + s * F[1, i]
        for j in range(r):
            acc -= C[i, j] * v[j] + K[i, j] * q[j]
        f[i] = acc


@njit(cache=True, inline="always")
def _element_forces(f, q, D, x0, preload, tf, ks, kst, edges, nst, cap, xn, zn, sn):
    """f −= Dᵀ T_e: each nonlinear element's torque, its plates' capacity capping it."""
    r = q.size
    for e in range(x0.size):
        x = 0.0
        for j in range(r):
            x += D[e, j] * q[j]
        # the spring's twist: the element's less the plates' slip, held over the step (the return map)
        te = _element_torque(e, x - sn[e], xn[e] - sn[e], zn[e], x0, preload, tf, ks, kst, edges, nst)
        if cap[e] > 0:
            te = min(max(preload[e] + te, -cap[e]), cap[e]) - preload[e]
        for j in range(r):
            f[j] -= D[e, j] * te


@njit(cache=True, inline="always")
def _crank_forces(f, s, q, v, phi, omega, alpha, W, fire, crank_r, crank_l, crank_m, mean, wc):
    """f −= Wᵀ (½ δJ' θ̇² + δJ α) of the slider-cranks, with δJ of each cylinder into ``wc[0]``."""
    r = q.size
    c = fire.size
    th0 = (1.0 - s) * phi[0] + s * phi[1]
    w0 = (1.0 - s) * omega[0] + s * omega[1]
    lam = crank_r / crank_l
    for i in range(c):
        th = th0 - fire[i]
        thd = w0
        for j in range(r):
            th += W[i, j] * q[j]
            thd += W[i, j] * v[j]
        sn, cs = np.sin(th), np.cos(th)
        Dd = 1.0 - (lam * sn) ** 2
        rD = np.sqrt(Dd)
        s1 = -crank_r * (sn + lam * sn * cs / rD)
        s2 = -crank_r * (cs + lam * (cs * cs - sn * sn + lam * lam * sn ** 4) / (Dd * rD))
        wc[0, i] = crank_m * (s1 * s1 - mean)  # δJ
        wc[1, i] = crank_m * s1 * s2 * thd * thd + wc[0, i] * alpha  # ½ δJ' θ̇² + δJ α
    for j in range(r):
        acc = 0.0
        for i in range(c):
            acc += W[i, j] * wc[1, i]
        f[j] -= acc


@njit(cache=True, inline="always")
def _variable_inertia_correction(out, W, B, P, wc, A):
    """``out`` = M⁻¹ f turned into (M + Wᵀ diag(δJ) W)⁻¹ f, δJ in ``wc[0]``."""
    # by Woodbury, B = M⁻¹Wᵀ, P = W M⁻¹ Wᵀ: a = u − B (I + diag(δJ) P)⁻¹ diag(δJ) W u, u = M⁻¹ f
    r = out.size
    c = wc.shape[1]
    for i in range(c):
        acc = 0.0
        for j in range(r):
            acc += W[i, j] * out[j]
        wc[2, i] = wc[0, i] * acc
        for k in range(c):
            A[i, k] = wc[0, i] * P[i, k]
        A[i, i] += 1.0
    y = _solve_small(A, wc[2])
    for j in range(r):
        acc = 0.0
        for i in range(c):
            acc += B[j, i] * y[i]
        out[j] -= acc


@njit(cache=True)
def run_kernel(y, zstate, slip, h, F, phi, omega, Minv, K, Cs, fidx, W, fire, crank_r, crank_l, crank_m, mean, B, P,
               D, x0, preload, tf, ks, kst, edges, nst, cap, rtol, atol_q, atol_v, q_out, z_out, s_out, h_try):
    """Integrate samples 0 … N−1 (N = F.shape[0]) from state ``y`` = (q, q̇), friction ``zstate`` and
    slip ``slip`` at sample 0; writes q, z and the slips at every sample into ``q_out`` (r, N),
    ``z_out`` and ``s_out`` (elements, N). The damping of each step is ``Cs[m]``, m the bits of the
    friction elements ``fidx`` that stick at its start (bit b: element fidx[b]).
    Returns (evaluations, the next step to try, status: 0 done, 1 the step control failed)."""
    r = y.size // 2
    q = y[:r].copy()
    v = y[r:].copy()
    z = zstate.copy()
    sl = slip.copy()
    kq, kv, qi, vi, a_first, f, xn, wc, A = _scratch(r, x0.size, fire.size)
    nfev = 0
    _record(0, q, z, sl, q_out, z_out, s_out)
    have_first = False
    state = -1
    for k in range(F.shape[0] - 1):
        Fk, ph, om = F[k:k + 2], phi[k:k + 2], omega[k:k + 2]
        alpha = (omega[k + 1] - omega[k]) / h
        s = 0.0  # the fraction of the interval done
        substeps = 0
        while s < 1.0:
            ds = _fraction_to_try(h_try / h, s)
            dt = ds * h
            _twists(xn, D, q)
            mask = _stick_mask(fidx, z, tf, ks)
            if mask != state:  # the damping of another stick state: the FSAL acceleration is not it
                state = mask
                have_first = False
            C = Cs[state]
            if not have_first:
                _acceleration(a_first, s, q, v, Fk, ph, om, alpha, Minv, K, C, W, fire, crank_r, crank_l,
                              crank_m, mean, B, P, D, x0, preload, tf, ks, kst, edges, nst, cap, xn, z, sl, f, wc, A)
                nfev += 1
                have_first = True
            kq[0] = v
            kv[0] = a_first
            for i in range(1, 7):
                _stage_state(qi, vi, q, v, kq, kv, i, dt)
                kq[i] = vi
                _acceleration(kv[i], s + _C[i] * ds, qi, vi, Fk, ph, om, alpha, Minv, K, C, W, fire, crank_r,
                              crank_l, crank_m, mean, B, P, D, x0, preload, tf, ks, kst, edges, nst, cap, xn, z, sl, f, wc, A)
                nfev += 1
            # stage 7 sits at the step's end with the 5th-order solution (FSAL): qi, vi are it
            err = _error_norm(kq, kv, q, v, qi, vi, dt, rtol, atol_q, atol_v)
            substeps += 1
            if substeps > MAX_SUBSTEPS:
                return nfev, h_try, 1
            if err <= 1.0:
                _advance_elements(z, sl, xn, qi, D, x0, preload, tf, ks, kst, edges, nst, cap)
                q[:] = qi
                v[:] = vi
                a_first[:] = kv[6]
                s += ds
            h_try = _next_step(err, ds, dt, h, h_try)
        _record(k + 1, q, z, sl, q_out, z_out, s_out)
    y[:r] = q
    y[r:] = v
    zstate[:] = z
    slip[:] = sl
    return nfev, h_try, 0


@njit(cache=True, inline="always")
def _scratch(r, ne, c):
    """The kernel's work arrays: the stages kq, kv (7, r); the stage state qi, vi, the step's first
    acceleration and the forces (r); the elements' twists (ne); the slider-cranks' wc (5, c) and A (c, c)."""
    return (np.empty((7, r)), np.empty((7, r)), np.empty(r), np.empty(r), np.empty(r), np.empty(r), np.zeros(ne),
            np.empty((5, c)), np.empty((c, c)))


@njit(cache=True, inline="always")
def _record(k, q, z, sl, q_out, z_out, s_out):
    """Sample k of the output: the angles, friction states and slips."""
    q_out[:, k] = q
    for e in range(z.size):
        z_out[e, k] = z[e]
        s_out[e, k] = sl[e]


@njit(cache=True, inline="always")
def _fraction_to_try(ds, s):
    """The fraction of the interval the next step covers: ``ds``, cut at the interval's end (a
    sliver of it taken along)."""
    ds = min(ds, 1.0 - s)
    if 1.0 - s - ds < 1e-9:
        ds = 1.0 - s
    return ds


@njit(cache=True, inline="always")
def _twists(xn, D, q):
    """Each element's twist D q into ``xn``."""
    for e in range(xn.size):
        acc = 0.0
        for j in range(q.size):
            acc += D[e, j] * q[j]
        xn[e] = acc


@njit(cache=True, inline="always")
def _stick_mask(fidx, z, tf, ks):
    """The bits of the friction elements ``fidx`` that stick (their state inside its limit)."""
    mask = 0
    for b in range(fidx.size):
        e = fidx[b]
        if abs(z[e]) < tf[e] / ks[e] * (1.0 - 1e-12):
            mask += 1 << b
    return mask


@njit(cache=True, inline="always")
def _stage_state(qi, vi, q, v, kq, kv, i, dt):
    """The state (qi, vi) at which Dormand–Prince stage i is evaluated, from the stages before it."""
    for m in range(q.size):
        accq = q[m]
        accv = v[m]
        for j in range(i):
            accq += dt * _A[i, j] * kq[j, m]
            accv += dt * _A[i, j] * kv[j, m]
        qi[m] = accq
        vi[m] = accv


@njit(cache=True, inline="always")
def _error_norm(kq, kv, q, v, qi, vi, dt, rtol, atol_q, atol_v):
    """The step's error (5th minus embedded 4th order) in the RMS norm of the tolerances: ≤ 1 passes."""
    r = q.size
    err = 0.0
    for i in range(r):
        eq = 0.0
        ev = 0.0
        for j in range(7):
            eq += _E[j] * kq[j, i]
            ev += _E[j] * kv[j, i]
        sq = atol_q + rtol * max(abs(q[i]), abs(qi[i]))
        sv = atol_v + rtol * max(abs(v[i]), abs(vi[i]))
        err += (dt * eq / sq) ** 2 + (dt * ev / sv) ** 2
    return np.sqrt(err / (2 * r))


@njit(cache=True, inline="always")
def _advance_elements(z, sl, xn, qi, D, x0, preload, tf, ks, kst, edges, nst, cap):
    """The elements' friction states and slips over an accepted step from twists ``xn`` to D ``qi``."""
    for e in range(x0.size):
        x1 = 0.0
        for j in range(qi.size):
            x1 += D[e, j] * qi[j]
        xs, xsn = x1 - sl[e], xn[e] - sl[e]
        if cap[e] > 0:
            total = preload[e] + _element_torque(e, xs, xsn, z[e], x0, preload, tf, ks, kst, edges, nst)
            if abs(total) > cap[e]:
                # the plates slipped: the spring stops where the torque met the capacity
                stop = _slip_point(e, xsn, xs, z[e], cap[e] if total > 0 else -cap[e], x0, preload,
                                   tf, ks, kst, edges, nst)
                sl[e] = x1 - stop
                xs = stop
        if tf[e] > 0:
            zs = tf[e] / ks[e]
            z[e] = min(max(z[e] + xs - xsn, -zs), zs)


@njit(cache=True, inline="always")
def _next_step(err, ds, dt, h, h_try):
    """The step to try after one of ``dt`` (``ds`` of the interval ``h``) with error ``err``."""
    if err <= 1.0:
        grow = _GROW if err == 0.0 else min(_GROW, _SAFETY * err ** _EXPONENT)
        if ds * h >= h_try * (1 - 1e-12):  # a full step (not one cut short by the interval's end)
            return dt * grow
        return h_try
    return dt * max(_SHRINK, _SAFETY * err ** _EXPONENT)
